!> The displacement field of the driver (an analysis_field's field_t):
!> the bodies, the contact set, the equations and the load state of the
!> mechanical problem, solved per increment by the equilibrium iteration
!> (equilibrium's solve_increment). It commits the friction and material
!> history of a converged increment, restores the contact set (and its
!> equation numbering) and the displacements of a failed one, and hands
!> the results of a converged one to the observers.
module displacement_field
  use kinds, only: dp
  use model
  use contact, only: contact_set_t, cfe_t, contact_search, contact_research, contact_commit
  use contact_status, only: touched_within, max_touched
  use assembly, only: body_t, element_counts_t, body_setup, commit_history, thermal_forces
  use dof_numbering, only: dofmap_t
  use condensed_contact, only: number_equations, condensed_repair
  use load_state, only: load_state_t, begin_step, values_at, temperature_change_at, check_loads_reached, &
                        follower_loads
  use constraints, only: mpc_t, resolve_equations, constraint_label
  use equilibrium, only: equilibrium_t, begin_equilibrium, solve_increment, renumber_couplings, note_numbering, &
                         numbering_fits
  use newton_control, only: newton_new_step
  use increment_results, only: increment_results_t, compute_increment_results, written_here
  use condensed_equilibrium, only: condensed_complete
  use analysis_events, only: observer_ref_t, step_info_t, step_summary_t, run_timing_t, tell_note, wall_time
  use analysis_field, only: field_t
  use element_catalogue, only: catalogue, max_nodes, max_ip
  use shape_functions, only: gauss_rule
  use heat_element, only: heat_gradient, conductivity_at, temperature_at
  use contact_heat, only: contact_heat_t, contact_heat_build, contact_heat_flux, has_contact_heat
  use linear_solver, only: linear_system_t
  use strings, only: itoa
  use messages, only: fatal
  implicit none
  private
  public :: displacement_field_t

  type, extends(field_t) :: displacement_field_t
    real(dp), allocatable :: u(:, :), fext(:, :), rf(:, :)   ! (2, nn)
    type(contact_set_t) :: cs
    type(dofmap_t) :: dm
    type(linear_system_t) :: sys
    type(load_state_t) :: ls
    type(equilibrium_t) :: eq
    type(body_t) :: body
    type(mpc_t) :: mpc                  ! the linear constraints, resolved once
    logical :: update_search = .false.  ! UPDATE SEARCH on a contact pair
    !> The current step is nonlinear (NLGEOM or a nonlinear material):
    !> Newton with automatic increments; research_each: NLGEOM with
    !> contact, the contact searched in every Newton iteration.
    logical :: step_nonlinear = .false., research_each = .false.
    !> Element routine calls made before the step (the body stiffness,
    !> for the first step).
    type(element_counts_t) :: counts_before
    !> The state the increment started from (restore): the couplings'
    !> statuses, or under NLGEOM with contact the whole contact set, and u.
    type(cfe_t), allocatable :: saved(:)
    type(contact_set_t) :: saved_cs
    real(dp), allocatable :: u_saved(:, :)
    !> A run of both fields (model's coupled): the temperatures of the
    !> increment's start and end (nn), handed over by the driver once the
    !> temperature field has solved the increment (take_temperatures),
    !> whose thermal strain loads the bodies in place of *TEMPERATURE's,
    !> and the reaction fluxes reported with the displacements.
    logical :: coupled = .false.
    real(dp), allocatable :: temp0(:), temp1(:), rfl(:)
    !> An increment has been committed (the couplings' gaps are then the
    !> last converged ones; before, the initial gaps: split_wanted).
    logical :: evaluated = .false.
    !> The couplings' slips (slip_inc) of the increments committed since
    !> the last report: a split increment's sub-increments (the driver's
    !> advance) report the slip of the whole increment (since the last
    !> contact search: a search pairs the couplings anew).
    real(dp), allocatable :: slip_since(:)
    !> The configuration m%x + u that UPDATE SEARCH pairs on (research;
    !> kept, so that no temporary of every node is made per increment).
    real(dp), allocatable :: x_search(:, :)
  contains
    procedure :: setup
    procedure :: begin_step => begin_mechanical_step
    procedure :: nonlinear
    procedure :: step_notes
    procedure :: begin_increment
    procedure :: solve
    procedure :: commit
    procedure :: restore
    procedure :: failure
    procedure :: split_wanted => split_touching
    procedure :: report
    procedure :: end_step
    procedure :: finish
    procedure :: take_temperatures
  end type displacement_field_t

contains

  !> Purpose: the bodies' stored stiffness, the linear constraints
  !> resolved for elimination (the deck's checks have reported what
  !> cannot be, naming its line) and, small deformation, one contact
  !> search on the initial configuration.
  subroutine setup(f, m, timing)
    class(displacement_field_t), intent(inout) :: f
    type(model_t), intent(in) :: m
    type(run_timing_t), intent(inout) :: timing
    integer :: bad
    character(len=:), allocatable :: msg
    real(dp) :: t0
    t0 = wall_time()
    allocate(f%u(2, m%nn), f%fext(2, m%nn), f%rf(2, m%nn))
    f%u = 0.0_dp
    f%fext = 0.0_dp
    f%rf = 0.0_dp
    call body_setup(m, f%body, f%counts_before)
    call resolve_equations(m, f%mpc, bad, msg)
    if (bad > 0) call fatal(constraint_label(m, bad) // ': ' // msg)
    call contact_search(m, m%x, f%cs)
    if (size(m%pairs) > 0) f%update_search = any(m%pairs%update_search)
    timing%setup = timing%setup + (wall_time() - t0)
  end subroutine setup

  !> Purpose: the contact search's notes for the listing (a pair whose
  !> coarse slave resolves the pressure less well than the pair swapped
  !> would), told after the step's header.
  subroutine step_notes(f, obs)
    class(displacement_field_t), intent(in) :: f
    type(observer_ref_t), intent(in) :: obs(:)
    integer :: k
    if (.not. allocated(f%cs%notes)) return
    do k = 1, size(f%cs%notes)
      call tell_note(obs, trim(f%cs%notes(k)))
    end do
  end subroutine step_notes

  !> Purpose: a step of the displacements: its load state, whether it is
  !> nonlinear (NLGEOM, or a hyperelastic or plastic material), its
  !> equations (after a search on the deformed configuration where NLGEOM
  !> with contact, or UPDATE SEARCH, follows another step), the Newton controls; the
  !> equations and couplings in info.
  subroutine begin_mechanical_step(f, m, is, total_time, info, timing)
    class(displacement_field_t), intent(inout) :: f
    type(model_t), intent(in) :: m
    integer, intent(in) :: is
    real(dp), intent(in) :: total_time
    type(step_info_t), intent(inout) :: info
    type(run_timing_t), intent(inout) :: timing
    real(dp) :: t0, ta
    t0 = wall_time()
    call begin_step(m, is, f%u, f%fext, total_time, f%ls)
    f%step_nonlinear = m%steps(is)%nlgeom .or. nonlinear_material(m)
    f%body%nonlinear = f%step_nonlinear
    f%body%nlgeom = m%steps(is)%nlgeom
    f%research_each = f%step_nonlinear .and. m%steps(is)%nlgeom .and. size(m%pairs) > 0
    call newton_new_step(f%eq%newton, m%steps(is)%controls)
    ! (a step's first increment searches no more: the pairing of the last
    ! increment's start would miss that increment's slide, with UPDATE
    ! SEARCH as under NLGEOM)
    if ((f%research_each .or. f%update_search) .and. is > 1) call research(f, m, timing)
    call number_equations(m, f%cs, f%ls%presc, f%mpc, f%dm, f%sys, f%eq%cd, ta, f%step_nonlinear, &
                          grow=keep_zone(f))
    call check_loads_reached(m, f%ls, f%dm%inactive)
    call begin_equilibrium(f%eq, f%dm%neq, f%cs%n, .true.)
    call note_numbering(f%eq, m, f%cs)
    timing%setup = timing%setup + (wall_time() - t0 - ta)
    timing%analyse = timing%analyse + ta
    f%eq%counts = f%counts_before
    f%counts_before = element_counts_t()
    info%equations = f%dm%neq
    info%prescribed = count(f%ls%presc)
    info%coupling_elements = f%cs%n
    info%uncoupled = f%cs%uncoupled
    info%uncoupled_pair = f%cs%uncoupled_pair
  end subroutine begin_mechanical_step

  !> Purpose: is the step nonlinear (Newton with automatic increments)?
  logical function nonlinear(f)
    class(displacement_field_t), intent(in) :: f
    nonlinear = f%step_nonlinear
  end function nonlinear

  !> Purpose: an increment to step time t1 begins. The contact is paired
  !> again where a search is due: under NLGEOM with contact on the
  !> converged configuration, without the closed couplings the last
  !> increment's iterations kept for points that found no master edge
  !> (contact_research), the equations renumbered only if the couplings'
  !> node lists changed; with UPDATE SEARCH otherwise (research). The
  !> state to restore is saved, the prescribed values and loads of t1
  !> set; in a nonlinear step the free dofs start where the last
  !> increment left them, face pressures follow the deformed faces
  !> (NLGEOM) and the temperatures of t0 and t1 are those of the load
  !> state.
  subroutine begin_increment(f, m, t0, t1, search_due, timing)
    class(displacement_field_t), intent(inout) :: f
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: t0, t1
    logical, intent(in) :: search_due
    type(run_timing_t), intent(inout) :: timing
    ! (a new pairing: the slips carried since the last report are dropped)
    if ((f%research_each .or. f%update_search) .and. search_due .and. allocated(f%slip_since)) &
      deallocate(f%slip_since)
    if (f%research_each) then
      if (search_due) then
        call contact_research(m, m%x + f%u, f%cs)
        if (.not. numbering_fits(f%eq, m, f%cs)) &
          call renumber_couplings(f%eq, m, f%cs, f%ls%presc, f%mpc, f%dm, f%sys)
      end if
      f%saved_cs = f%cs
    else
      if (f%update_search .and. search_due) call research(f, m, timing)
      f%saved = f%cs%c(1:f%cs%n)
    end if
    f%u_saved = f%u
    call values_at(m, f%ls, t1, f%u, f%fext)
    if (.not. f%step_nonlinear) return
    where (.not. f%ls%presc) f%u = f%u_saved
    call follower_loads(m, f%ls, t1, f%body%fl_ptr, f%body%fl_face, f%body%fl_mag)
    if (f%ls%thermal) then
      if (.not. allocated(f%body%dtemp)) allocate(f%body%dtemp(m%nn), f%body%dtemp0(m%nn))
      call temperature_change_at(m, f%ls, t1, f%body%dtemp)
      call temperature_change_at(m, f%ls, t0, f%body%dtemp0)
    end if
  end subroutine begin_increment

  !> Purpose: the equilibrium of the increment (solve_increment): in a
  !> nonlinear step linearised about the saved converged state, under
  !> NLGEOM with contact searching the contact in every iteration. In a
  !> run of both fields the thermal strain of the temperature field's
  !> temperatures joins the loads (coupled_loads; f%fext keeps the
  !> load state's, which the next step's begin_step takes apart).
  subroutine solve(f, m, is, inc, obs, ok, iters)
    class(displacement_field_t), intent(inout) :: f
    type(model_t), intent(in) :: m
    integer, intent(in) :: is, inc
    type(observer_ref_t), intent(in) :: obs(:)
    logical, intent(out) :: ok
    integer, intent(out) :: iters
    real(dp), allocatable :: fext(:, :)
    fext = f%fext
    if (f%coupled) call coupled_loads(f, m, fext)
    if (f%research_each) then
      call solve_increment(f%eq, m, is, inc, f%body, f%cs, f%dm, f%sys, fext, f%u, f%rf, obs, ok, iters, &
                           f%u_saved, f%ls%presc, f%mpc)
    else if (f%step_nonlinear) then
      call solve_increment(f%eq, m, is, inc, f%body, f%cs, f%dm, f%sys, fext, f%u, f%rf, obs, ok, iters, &
                           f%u_saved)
    else
      call solve_increment(f%eq, m, is, inc, f%body, f%cs, f%dm, f%sys, fext, f%u, f%rf, obs, ok, iters)
    end if
  end subroutine solve

  !> Purpose: the temperature field's temperatures of the increment, from
  !> the driver in a run of both fields: temp0 at its start, temp1 at its
  !> end (nn each), rfl the reaction fluxes at temp1 (for the report).
  subroutine take_temperatures(f, temp0, temp1, rfl)
    class(displacement_field_t), intent(inout) :: f
    real(dp), intent(in) :: temp0(:), temp1(:), rfl(:)
    f%coupled = .true.
    f%temp0 = temp0
    f%temp1 = temp1
    f%rfl = rfl
  end subroutine take_temperatures

  !> Purpose: the thermal strain of the temperature field's temperatures
  !> as the load state makes *TEMPERATURE's (load_state's values_at and
  !> the field's begin_increment): the change from the initial
  !> temperatures at the increment's end, its nodal loads added to
  !> fext(2, nn) (none under NLGEOM or with a plastic material, whose
  !> element routines take the strain into their internal force from the
  !> body's dtemp, and dtemp0 the change at the increment's start).
  subroutine coupled_loads(f, m, fext)
    class(displacement_field_t), intent(inout) :: f
    type(model_t), intent(in) :: m
    real(dp), intent(inout) :: fext(:, :)
    if (.not. any(m%materials%alpha /= 0.0_dp)) return
    call thermal_forces(m, f%temp1 - f%ls%temp_init, fext, f%ls%nlgeom)
    if (.not. f%step_nonlinear) return
    f%body%dtemp = f%temp1 - f%ls%temp_init
    f%body%dtemp0 = f%temp0 - f%ls%temp_init
  end subroutine coupled_loads

  !> Purpose: a converged increment's history becomes the state the next
  !> increment starts from: the one place where state that depends on
  !> the loading path is committed (the contact layer's friction anchors
  !> and slips; the bodies' material history at their integration
  !> points, plastic strain and hardening). An increment that does not
  !> converge commits nothing: its bisected or cut-back parts start again
  !> from the last committed state.
  subroutine commit(f)
    class(displacement_field_t), intent(inout) :: f
    call contact_commit(f%cs)
    if (f%step_nonlinear) call commit_history(f%body)
    f%evaluated = .true.
    if (allocated(f%slip_since)) then
      if (size(f%slip_since) == f%cs%n) then
        f%slip_since = f%slip_since + f%cs%c(1:f%cs%n)%slip_inc
        return
      end if
    end if
    f%slip_since = f%cs%c(1:f%cs%n)%slip_inc
  end subroutine commit

  !> Purpose: should the converged increment be split in two? Where more
  !> than max_touched frictional couplings of a pair closed within it
  !> from an open gap (contact_status's touched_within): such points
  !> stick from their anchor of the increment's start, so the relative
  !> tangential motion before they touched counts as stick; splitting
  !> brings each touching instant within a slave spacing's growth of an
  !> increment's start (docs/contact.md, "Accuracy of stick and slip").
  !> Only where the step asks for it (*STATIC, SPLIT TOUCHING): the
  !> sub-increments cost status solves (the Cattaneo-Mindlin bench row
  !> 1.46 -> 4.8 s), and CalculiX and Abaqus keep their increments.
  !> Arguments: m the model; is the step; wanted, reason (for the note).
  subroutine split_touching(f, m, is, wanted, reason)
    class(displacement_field_t), intent(in) :: f
    type(model_t), intent(in) :: m
    integer, intent(in) :: is
    logical, intent(out) :: wanted
    character(len=:), allocatable, intent(out) :: reason
    integer :: n
    wanted = .false.
    reason = ''
    if (.not. m%steps(is)%split_touching) return
    if (f%research_each) then
      n = touched_within(f%saved_cs%c(1:f%saved_cs%n), f%cs, f%evaluated)
    else
      n = touched_within(f%saved, f%cs, f%evaluated)
    end if
    wanted = n > max_touched
    if (wanted) reason = 'frictional contact zone grew by ' // itoa(n) // ' points in the increment'
  end subroutine split_touching

  !> Purpose: nothing of the failed attempt is kept: the statuses and
  !> displacements the increment started with (the friction history is
  !> committed only by converged increments); under NLGEOM with contact
  !> the whole contact set (the number of couplings, geometry, statuses,
  !> friction state) and, where the failed attempt renumbered the
  !> equations for other couplings, the numbering for the restored ones.
  subroutine restore(f, m)
    class(displacement_field_t), intent(inout) :: f
    type(model_t), intent(in) :: m
    if (f%research_each) then
      f%cs = f%saved_cs
      if (.not. numbering_fits(f%eq, m, f%cs)) &
        call renumber_couplings(f%eq, m, f%cs, f%ls%presc, f%mpc, f%dm, f%sys)
    else
      f%cs%c(1:f%cs%n) = f%saved
    end if
    f%u = f%u_saved
  end subroutine restore

  !> Purpose: why the last solve failed (newton_control's reason) and by
  !> how much to cut the increment; the contact nodes still switching.
  subroutine failure(f, reason, cut, changing)
    class(displacement_field_t), intent(in) :: f
    character(len=:), allocatable, intent(out) :: reason, changing
    real(dp), intent(out) :: cut
    reason = f%eq%newton%reason
    cut = f%eq%newton%cut
    changing = f%eq%changed
  end subroutine failure

  !> Purpose: UPDATE SEARCH: the contact layer pairs again on the deformed
  !> configuration. In a linear step with the condensed solve the
  !> equations were numbered for a zone of the surfaces (keep_zone): where
  !> the new couplings stay in it, the numbering and the bodies' factor
  !> stay (condensed_repair: only the condensed matrix of the next status
  !> is made again); otherwise the equations are renumbered for the new
  !> couplings (the zone grown by them).
  subroutine research(f, m, timing)
    class(displacement_field_t), intent(inout) :: f
    type(model_t), intent(in) :: m
    type(run_timing_t), intent(inout) :: timing
    real(dp) :: t0, ta
    logical :: fits
    t0 = wall_time()
    ta = 0.0_dp
    if (.not. allocated(f%x_search)) allocate(f%x_search(2, m%nn))
    call add_configuration(m%nn, m%x, f%u, f%x_search)
    call contact_research(m, f%x_search, f%cs)
    ! (the bodies' factor must be in hand: a K0 assembled now would need
    ! the sparse structure of the new couplings)
    fits = .false.
    if (f%eq%k0_valid) call condensed_repair(f%eq%cd, m, f%cs, f%ls%presc, f%mpc, f%dm, f%eq%counts, fits)
    if (.not. fits) call number_equations(m, f%cs, f%ls%presc, f%mpc, f%dm, f%sys, f%eq%cd, ta, &
                                          f%step_nonlinear, grow=keep_zone(f))
    call begin_equilibrium(f%eq, f%dm%neq, f%cs%n, .false.)
    ! the bodies' factor of the kept numbering stays valid
    if (fits) f%eq%k0_valid = .true.
    call note_numbering(f%eq, m, f%cs)
    timing%setup = timing%setup + (wall_time() - t0 - ta)
    timing%analyse = timing%analyse + ta
  end subroutine research

  !> Purpose: x = x0 + u over nn nodes (the same sums as the array
  !> expression, in a loop the compiler vectorises: the array expression
  !> on the components cost 13 instructions a node, every increment).
  subroutine add_configuration(nn, x0, u, x)
    integer, intent(in) :: nn
    real(dp), intent(in) :: x0(2, nn), u(2, nn)
    real(dp), intent(out) :: x(2, nn)
    integer :: j
    do j = 1, nn
      x(1, j) = x0(1, j) + u(1, j)
      x(2, j) = x0(2, j) + u(2, j)
    end do
  end subroutine add_configuration

  !> Purpose: are the contact equations numbered for a zone of the
  !> surfaces that later pairings keep (number_equations' grow)? In a
  !> linear step that pairs again at every increment (UPDATE SEARCH).
  logical function keep_zone(f)
    class(displacement_field_t), intent(in) :: f
    keep_zone = f%update_search .and. .not. f%step_nonlinear
  end function keep_zone

  !> Purpose: the results of a converged increment at step time t,
  !> computed once, to every observer; the couplings' increment slips
  !> those of the whole increment (slip_since).
  subroutine report(f, m, is, inc, t, total_time, iters, dt, obs, timing)
    class(displacement_field_t), intent(inout) :: f
    type(model_t), intent(in) :: m
    integer, intent(in) :: is, inc, iters
    real(dp), intent(in) :: t, total_time, dt
    type(observer_ref_t), intent(in) :: obs(:)
    type(run_timing_t), intent(inout) :: timing
    type(increment_results_t) :: res
    integer :: k
    real(dp) :: t0, t1
    real(dp), allocatable :: dtemp(:)
    t0 = wall_time()
    ! an increment solved on the contact equations alone: the others where
    ! results need them (written, reaction sums printed every increment,
    ! the temperatures' field); wear and the contact results need only
    ! the contact equations
    if (f%eq%cd%lazy) then
      if (written_here(m, is, inc, t, total_time, dt) .or. size(f%ls%set_ids) > 0 .or. f%coupled) &
        call condensed_complete(f%eq, m, f%body, f%dm, f%sys, f%u, f%rf)
    end if
    ! the slip of the whole increment (its sub-increments' too)
    if (allocated(f%slip_since)) then
      if (size(f%slip_since) == f%cs%n) f%cs%c(1:f%cs%n)%slip_inc = f%slip_since
      deallocate(f%slip_since)
    end if
    if (f%coupled) then
      dtemp = f%temp1 - f%ls%temp_init
      call compute_increment_results(m, is, inc, t, total_time, iters, f%u, f%rf, f%cs, f%ls%set_ids, res, &
                                     f%eq%counts, dtemp, f%body, dt)
      res%heat = .true.
      res%nt = f%temp1
      res%rfl = f%rfl
      call coupled_heat_flux(f, m, any(m%steps(is)%requests%hfl), res%nip, res%hfl_ip)
      if (has_contact_heat(m)) call contact_heat_rows(f, m, dt, res)
    else if (f%ls%thermal) then
      allocate(dtemp(m%nn))
      call temperature_change_at(m, f%ls, t, dtemp)
      call compute_increment_results(m, is, inc, t, total_time, iters, f%u, f%rf, f%cs, f%ls%set_ids, res, &
                                     f%eq%counts, dtemp, f%body, dt)
    else
      call compute_increment_results(m, is, inc, t, total_time, iters, f%u, f%rf, f%cs, f%ls%set_ids, res, &
                                     f%eq%counts, body=f%body, dt=dt, lean=f%eq%cd%lazy)
    end if
    t1 = wall_time()
    do k = 1, size(obs)
      call obs(k)%o%increment_done(m, res)
    end do
    timing%results = timing%results + (t1 - t0)
    timing%output = timing%output + (wall_time() - t1)
  end subroutine report

  !> Purpose: a coupled increment's heat flux -k grad T (HFL) at the
  !> integration points of the stress results (nip(e) of each element:
  !> those the listing and the .dat print HFL at; set to the element's
  !> rule where no stresses were computed), from the temperature
  !> field's temperatures, when some output asks for it (wanted); the
  !> conductivity of a table at each point's temperature, as the
  !> temperature field's own (docs/heat.md).
  subroutine coupled_heat_flux(f, m, wanted, nip, hfl)
    class(displacement_field_t), intent(in) :: f
    type(model_t), intent(in) :: m
    logical, intent(in) :: wanted
    integer, intent(inout) :: nip(:)
    real(dp), allocatable, intent(out) :: hfl(:, :, :)
    real(dp) :: xi(2, max_ip), w(max_ip), cond(2), te(max_nodes)
    integer :: e, n, ip
    allocate(hfl(2, max_ip, merge(m%ne, 0, wanted)))
    if (.not. wanted) return
    hfl = 0.0_dp
    do e = 1, m%ne
      if (.not. is_continuum(m, e) .or. m%elem_section(e) == 0) cycle
      ! (no stresses asked for: the element's rule)
      if (nip(e) == 0) nip(e) = catalogue(m%etype(e))%nip
      n = elem_nodes(m, e)
      te(1:n) = f%temp1(m%conn(1:n, e))
      call gauss_rule(catalogue(m%etype(e))%shape, nip(e), xi, w)
      associate(mat => m%materials(m%sections(m%elem_section(e))%material))
        do ip = 1, nip(e)
          cond = mat%conductivity
          if (mat%nk > 1) cond = conductivity_at(mat%ktab(:, 1:mat%nk), temperature_at(m%etype(e), te(1:n), &
                                                                                        xi(:, ip)))
          hfl(:, ip, e) = -cond * heat_gradient(m%etype(e), m%x(:, m%conn(1:n, e)), te(1:n), xi(:, ip))
        end do
      end associate
    end do
  end subroutine coupled_heat_flux

  !> Purpose: the heat flux across the contact (contact_heat_flux: per
  !> unit area, slave to master, at the increment's temperatures) in each
  !> slave row of the contact results (the contact table's last column).
  !> A pair whose rows are the multiplier field's at the slave nodes (the
  !> multiplier on the master mesh) has one CFE per master node, not per
  !> row: its rows show 0 (docs/heat.md).
  subroutine contact_heat_rows(f, m, dt, res)
    class(displacement_field_t), intent(in) :: f
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: dt
    type(increment_results_t), intent(inout) :: res
    type(contact_heat_t) :: ch
    real(dp), allocatable :: q(:)
    integer, allocatable :: sel(:)
    integer :: k, j
    call contact_heat_build(m, f%cs, dt, ch)
    q = contact_heat_flux(ch, f%temp1, f%cs%n)
    do k = 1, size(res%contact%pairs)
      associate(r => res%contact%pairs(k))
        allocate(r%slave_heat_flux(size(r%slave_node)))
        r%slave_heat_flux = 0.0_dp
        sel = pack([(j, j = 1, f%cs%n)], f%cs%c(1:f%cs%n)%pair == r%pair)
        if (size(sel) /= size(r%slave_node)) cycle
        if (any(f%cs%c(sel)%ns == 0)) cycle
        r%slave_heat_flux = q(sel)
      end associate
    end do
  end subroutine contact_heat_rows

  !> Purpose: the step's counts of factorisations, iterations, pivots and
  !> element calls; under NLGEOM with contact a note of the searches and
  !> renumberings of the Newton iterations.
  subroutine end_step(f, obs, summary)
    class(displacement_field_t), intent(inout) :: f
    type(observer_ref_t), intent(in) :: obs(:)
    type(step_summary_t), intent(inout) :: summary
    if (f%step_nonlinear .and. f%eq%searches > 0) call tell_note(obs, 'contact searched again in ' // &
      itoa(f%eq%searches) // ' Newton iterations; equations renumbered ' // itoa(f%eq%renumberings) // &
      ' times for changed couplings')
    summary%factorisations = summary%factorisations + f%eq%factorisations
    summary%condensed_factorisations = f%eq%condensed_factorisations
    summary%condensed_lowrank = f%eq%condensed_lowrank
    summary%iterations = f%eq%iterations
    summary%block_pivots = f%eq%search%block_pivots
    summary%single_pivots = f%eq%search%single_pivots
    summary%continuum_tangent = f%eq%counts%continuum_tangent
    summary%continuum_stresses = f%eq%counts%continuum_stresses
    summary%coupling = f%eq%counts%coupling
    summary%newton_iterations = f%eq%newton%total
  end subroutine end_step

  !> Purpose: the iteration's parts of the run's timing.
  subroutine finish(f, timing)
    class(displacement_field_t), intent(in) :: f
    type(run_timing_t), intent(inout) :: timing
    associate(t => timing, e => f%eq%timing)
      ! (added: a coupled run's temperature field has put its own in)
      t%assembly = t%assembly + e%assembly
      t%analyse = t%analyse + e%analyse
      t%factor = t%factor + e%factor
      t%condensed = t%condensed + e%condensed
      t%solve = t%solve + e%solve
      t%recovery = t%recovery + e%recovery
      t%numeric_factorisations = t%numeric_factorisations + e%numeric_factorisations
      t%condensed_factorisations = t%condensed_factorisations + e%condensed_factorisations
      t%condensed_lowrank = t%condensed_lowrank + e%condensed_lowrank
    end associate
  end subroutine finish
end module displacement_field
