!> The temperature field of the driver (an analysis_field's field_t):
!> heat conduction on the plane and axisymmetric continuum elements in
!> *HEAT TRANSFER steps (docs/heat.md). Steady state: (K + H) T = F; a
!> transient step by backward Euler over the increment t0 -> t1 of
!> length dt:
!>   (C/dt + K + H) T1 = C/dt T0 + F(t1),
!> K conduction, C capacity (consistent), H film matrix, F the fluxes
!> (*CFLUX, *DFLUX, the films' h T_sink). Prescribed temperatures
!> (*BOUNDARY on dof 11) are eliminated; their reaction fluxes (RFL) are
!> the residual A T - F there. The matrix is factorised once for as long
!> as dt and the films stay the same (a linear transient at fixed
!> increments is one factorisation). Transient steps with DELTMX take
!> automatic increments: an increment whose largest temperature change
!> exceeds DELTMX fails (failure: the cut factor) and is solved again
!> smaller, as CalculiX does.
module temperature_field
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  use strings, only: itoa, rtoa
  use model, only: model_t, bc_t, cload_t, heat_load_t, heat_bf, amp_total_time, amplitude_at, is_continuum, &
                   elem_nodes, elem_thickness, node_label, elem_label
  use element_catalogue, only: catalogue, max_nodes, max_ip, shape_tri6
  use heat_element, only: heat_volume_arrays, heat_face_arrays, heat_radiation_arrays, heat_gradient, table_at, &
                          temperature_at
  use shape_functions, only: gauss_rule
  use linear_solver, only: linear_system_t, sys_setup, sys_zero, sys_add, sys_factor, sys_solve, factor_ok, &
                           factor_fallback
  use increment_results, only: increment_results_t
  use analysis_events, only: observer_ref_t, step_info_t, step_summary_t, run_timing_t, wall_time
  use analysis_field, only: field_t
  use contact_heat, only: contact_heat_t, contact_heat_matrix, contact_heat_residual, same_couplings, &
                          same_matrices
  use messages, only: fatal
  implicit none
  private
  public :: temperature_field_t

  type, extends(field_t) :: temperature_field_t
    real(dp), allocatable :: temp(:), saved(:), rfl(:)   ! (nn) temperatures, reaction fluxes
    integer, allocatable :: elems(:)                     ! the elements that conduct
    real(dp), allocatable :: ke(:, :, :), ce(:, :, :), fb(:, :)   ! their arrays
    integer, allocatable :: eqn(:)                       ! (nn) equation, 0: prescribed or no element
    logical, allocatable :: presc(:)                     ! (nn)
    real(dp), allocatable :: t_start(:), t_end(:)        ! prescribed: at the step's start, its value
    integer, allocatable :: t_amp(:)                     ! prescribed: amplitude (0: none)
    type(bc_t), allocatable :: tbcs(:)                   ! in force (the step's and the earlier ones)
    type(cload_t), allocatable :: cfluxes(:)
    type(heat_load_t), allocatable :: dfluxes(:), films(:), radiates(:)
    !> By conducting element k: its films films(ifilm(xfilm(k):xfilm(k+1)-1)),
    !> its fluxes dfluxes(iflux(xflux(k):xflux(k+1)-1)) and its radiation
    !> radiates(irad(xrad(k):xrad(k+1)-1)).
    integer, allocatable :: xfilm(:), ifilm(:), xflux(:), iflux(:), xrad(:), irad(:)
    type(linear_system_t) :: sys
    integer :: neq = 0, is = 0
    logical :: steady = .true.
    logical :: automatic = .false.                       ! the step's increments are automatic
    real(dp) :: total_time = 0.0_dp, deltmx = 0.0_dp
    real(dp) :: dt = 0.0_dp, t1 = 0.0_dp                 ! the increment's length and end (step time)
    real(dp) :: factored_dt = -1.0_dp                    ! < 0: no valid factor
    real(dp) :: largest_change = 0.0_dp                  ! of the last solve
    character(len=:), allocatable :: why                 ! why the last solve failed
    logical :: tabled = .false.                          ! some conductivity or specific heat is a table
    logical :: radiating = .false.                       ! the step has *RADIATE (Newton iterations)
    integer :: factorisations = 0                        ! in the current step
    integer :: run_factorisations = 0                    ! in the run
    integer :: iterations = 0                            ! solves of the current step, tries included
    real(dp) :: t_factor = 0.0_dp, t_solve = 0.0_dp
    !> Heat through the contact (contact_heat; a coupled run's driver
    !> hands it over, take_contact_heat): couplings numbered after the
    !> elements in the system's structure.
    type(contact_heat_t) :: ch
  contains
    procedure :: setup
    procedure :: begin_step => begin_heat_step
    procedure :: nonlinear
    procedure :: step_notes
    procedure :: begin_increment
    procedure :: solve
    procedure :: commit
    procedure :: restore
    procedure :: failure
    procedure :: report
    procedure :: end_step
    procedure :: finish
    procedure :: take_contact_heat
  end type temperature_field_t

  !> CalculiX's dof of the temperature.
  integer, parameter :: dof_temperature = 11
  !> The amplitude of a load held from an earlier step (hold_loads).
  integer, parameter :: held = -1
  !> Iterations of a nonlinear increment (a material table: fixed point;
  !> radiation: Newton): at most max_iterations, done when no temperature
  !> changes by more than iteration_tolerance times the largest (at
  !> least 1).
  integer, parameter :: max_iterations = 100
  real(dp), parameter :: iteration_tolerance = 1.0e-10_dp

contains

  !> Purpose: the conducting elements and their conduction, capacity and
  !> unit body-flux arrays (heat_element), computed once; the initial
  !> temperatures (*INITIAL CONDITIONS, TYPE=TEMPERATURE; 0 elsewhere).
  subroutine setup(f, m, timing)
    class(temperature_field_t), intent(inout) :: f
    type(model_t), intent(in) :: m
    type(run_timing_t), intent(inout) :: timing
    integer :: e, k, n, nel
    real(dp) :: t0, cap, dv_min
    t0 = wall_time()
    allocate(f%temp(m%nn), f%rfl(m%nn), f%presc(m%nn), f%t_start(m%nn), f%t_end(m%nn), f%t_amp(m%nn))
    f%temp = 0.0_dp
    if (allocated(m%initial_temps)) f%temp(m%initial_temps%node) = m%initial_temps%value
    f%saved = f%temp
    f%rfl = 0.0_dp
    f%presc = .false.
    f%t_amp = 0
    nel = count([(conducts(m, e), e = 1, m%ne)])
    allocate(f%elems(nel), f%ke(max_nodes, max_nodes, nel), f%ce(max_nodes, max_nodes, nel), f%fb(max_nodes, nel))
    f%elems = pack([(e, e = 1, m%ne)], [(conducts(m, e), e = 1, m%ne)])
    do k = 1, nel
      e = f%elems(k)
      n = elem_nodes(m, e)
      associate(mat => m%materials(m%sections(m%elem_section(e))%material))
        cap = mat%density * mat%specific_heat
        call heat_volume_arrays(m%etype(e), m%x(:, m%conn(1:n, e)), elem_thickness(m, e), mat%conductivity, &
                                cap, f%ke(:, :, k), f%ce(:, :, k), f%fb(:, k), dv_min)
        if (.not. dv_min > 0.0_dp) call fatal('element ' // elem_label(m, e) // ' (' // &
          trim(catalogue(m%etype(e))%name) // ') has a zero or negative Jacobian at an integration point of ' // &
          'its conduction: a mid-side node far from the middle of its edge, an axisymmetric element reaching ' // &
          'x < 0, or a NODAL THICKNESS that the element interpolates to zero or less')
      end associate
    end do
    f%tabled = .false.
    do k = 1, nel
      e = f%elems(k)
      associate(mat => m%materials(m%sections(m%elem_section(e))%material))
        f%tabled = f%tabled .or. mat%nk > 1 .or. mat%nc > 1
      end associate
    end do
    allocate(f%tbcs(0), f%cfluxes(0), f%dfluxes(0), f%films(0), f%radiates(0))
    timing%setup = timing%setup + (wall_time() - t0)
  end subroutine setup

  !> A continuum element with a section (and so a material): it conducts.
  logical function conducts(m, e)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    conducts = is_continuum(m, e)
    if (conducts) conducts = m%elem_section(e) > 0
    if (conducts) conducts = .not. (m%sections(m%elem_section(e))%spring .or. &
                                    m%sections(m%elem_section(e))%point_mass)
  end function conducts

  !> Purpose: a heat transfer step: its loads in force (a step's card
  !> adds to the earlier steps' unless OP=NEW), the prescribed nodes and
  !> the equations of the others; its part of info.
  subroutine begin_heat_step(f, m, is, total_time, info, timing)
    class(temperature_field_t), intent(inout) :: f
    type(model_t), intent(in) :: m
    integer, intent(in) :: is
    real(dp), intent(in) :: total_time
    type(step_info_t), intent(inout) :: info
    type(run_timing_t), intent(inout) :: timing
    real(dp) :: t0
    integer :: k
    t0 = wall_time()
    if (f%is > 0) call hold_loads(f, m)
    f%is = is
    f%total_time = total_time
    f%steady = m%steps(is)%steady
    f%deltmx = m%steps(is)%deltmx
    ! CalculiX's *HEAT TRANSFER without DIRECT; a coupled step's only
    ! with DELTMX (deck_coupled_cards: the displacements' rules otherwise)
    associate(s => m%steps(is))
      f%automatic = .not. s%direct .and. (.not. s%coupled .or. (.not. s%steady .and. s%deltmx > 0.0_dp))
    end associate
    associate(s => m%steps(is))
      if (is == 1) f%tbcs = pack(m%model_bcs, m%model_bcs%dof == dof_temperature)
      if (s%new_tbcs) f%tbcs = f%tbcs(1:0)
      if (allocated(s%tbcs)) f%tbcs = [pack(f%tbcs, [(.not. any(s%tbcs%node == f%tbcs(k)%node), &
                                                      k = 1, size(f%tbcs))]), s%tbcs]
      if (s%new_cfluxes) f%cfluxes = f%cfluxes(1:0)
      if (allocated(s%cfluxes)) f%cfluxes = [pack(f%cfluxes, [(.not. any(s%cfluxes%node == f%cfluxes(k)%node), &
                                                              k = 1, size(f%cfluxes))]), s%cfluxes]
      if (s%new_dfluxes) f%dfluxes = f%dfluxes(1:0)
      if (allocated(s%dfluxes)) f%dfluxes = [pack(f%dfluxes, .not. replaced(f%dfluxes, s%dfluxes)), s%dfluxes]
      if (s%new_films) f%films = f%films(1:0)
      if (allocated(s%films)) f%films = [pack(f%films, .not. replaced(f%films, s%films)), s%films]
      if (s%new_radiates) f%radiates = f%radiates(1:0)
      if (allocated(s%radiates)) f%radiates = [pack(f%radiates, .not. replaced(f%radiates, s%radiates)), &
                                               s%radiates]
    end associate
    call prescribe(f, m)
    call loads_by_element(f, m, f%films%elem, f%xfilm, f%ifilm)
    call loads_by_element(f, m, f%dfluxes%elem, f%xflux, f%iflux)
    call loads_by_element(f, m, f%radiates%elem, f%xrad, f%irad)
    f%radiating = size(f%irad) > 0
    call number_temperatures(f, m)
    f%factored_dt = -1.0_dp
    info%equations = f%neq
    info%prescribed = count(f%presc)
    info%coupling_elements = 0
    allocate(info%uncoupled(0), info%uncoupled_pair(0))
    timing%setup = timing%setup + (wall_time() - t0)
  end subroutine begin_heat_step

  !> The loads on each conducting element: the loads with elements
  !> elems(:) sorted by conducting element k into iload(xload(k):xload(k+1)-1)
  !> (loads on an element that does not conduct act on nothing).
  subroutine loads_by_element(f, m, elems, xload, iload)
    class(temperature_field_t), intent(in) :: f
    type(model_t), intent(in) :: m
    integer, intent(in) :: elems(:)
    integer, allocatable, intent(out) :: xload(:), iload(:)
    integer, allocatable :: kof(:)
    integer :: j, k, nel
    nel = size(f%elems)
    allocate(kof(m%ne))
    kof = 0
    kof(f%elems) = [(k, k = 1, nel)]
    allocate(xload(nel + 1), iload(count(kof(elems) > 0)))
    xload = 0
    do j = 1, size(elems)
      k = kof(elems(j))
      if (k > 0) xload(k + 1) = xload(k + 1) + 1
    end do
    xload(1) = 1
    do k = 1, nel
      xload(k + 1) = xload(k + 1) + xload(k)
    end do
    do j = size(elems), 1, -1
      k = kof(elems(j))
      if (k == 0) cycle
      xload(k + 1) = xload(k + 1) - 1
      iload(xload(k + 1)) = j
    end do
    ! xload(k + 1) now starts element k's loads: shift back
    xload(1:nel) = xload(2:nel + 1)
    xload(nel + 1) = size(iload) + 1
  end subroutine loads_by_element

  !> The loads of the steps before, as the next step inherits them: held
  !> at the values they reached at the end of the previous step (their
  !> amplitudes, which run on that step's time, folded in); a prescribed
  !> temperature is held where it is.
  subroutine hold_loads(f, m)
    class(temperature_field_t), intent(inout) :: f
    type(model_t), intent(in) :: m
    integer :: k
    real(dp) :: t_end
    t_end = m%steps(f%is)%period
    f%t1 = t_end
    do k = 1, size(f%tbcs)
      f%tbcs(k)%value = f%temp(f%tbcs(k)%node)
      f%tbcs(k)%amp = 0
    end do
    do k = 1, size(f%cfluxes)
      f%cfluxes(k)%value = f%cfluxes(k)%value * load_factor(f, m, f%cfluxes(k)%amp, t_end)
      f%cfluxes(k)%amp = held
    end do
    do k = 1, size(f%dfluxes)
      f%dfluxes(k)%value = f%dfluxes(k)%value * load_factor(f, m, f%dfluxes(k)%amp, t_end)
      f%dfluxes(k)%amp = held
    end do
    do k = 1, size(f%films)
      f%films(k)%sink = sink_at(f, m, f%films(k))
      f%films(k)%amp = 0
    end do
    do k = 1, size(f%radiates)
      f%radiates(k)%sink = sink_at(f, m, f%radiates(k))
      f%radiates(k)%amp = 0
    end do
  end subroutine hold_loads

  !> The loads of old that a load of new replaces (the same element and
  !> face, as a *DLOAD replaces one on the same face).
  pure function replaced(old, new) result(r)
    type(heat_load_t), intent(in) :: old(:), new(:)
    logical :: r(size(old))
    integer :: k
    r = [(any(new%elem == old(k)%elem .and. new%face == old(k)%face), k = 1, size(old))]
  end function replaced

  !> The prescribed nodes of the step: each starts from its temperature
  !> at the step's start and reaches the value of its last *BOUNDARY.
  subroutine prescribe(f, m)
    class(temperature_field_t), intent(inout) :: f
    type(model_t), intent(in) :: m
    integer :: k, a
    f%presc = .false.
    f%t_amp = 0
    f%t_start = f%temp
    f%t_end = f%temp
    do k = 1, size(f%tbcs)
      a = f%tbcs(k)%node
      f%presc(a) = .true.
      f%t_end(a) = f%tbcs(k)%value
      f%t_amp(a) = f%tbcs(k)%amp
    end do
  end subroutine prescribe

  !> Equations of the free nodes of the conducting elements, and the
  !> structure of the system (one list of equations per element).
  subroutine number_temperatures(f, m)
    class(temperature_field_t), intent(inout) :: f
    type(model_t), intent(in) :: m
    logical, allocatable :: used(:)
    integer, allocatable :: xeq(:), eqs(:)
    integer :: k, e, n, a, pos
    allocate(used(m%nn))
    used = .false.
    do k = 1, size(f%elems)
      e = f%elems(k)
      used(m%conn(1:elem_nodes(m, e), e)) = .true.
    end do
    if (allocated(f%eqn)) deallocate(f%eqn)
    allocate(f%eqn(m%nn))
    f%eqn = 0
    f%neq = 0
    do a = 1, m%nn
      if (.not. used(a) .or. f%presc(a)) cycle
      f%neq = f%neq + 1
      f%eqn(a) = f%neq
    end do
    allocate(xeq(size(f%elems) + 1))
    xeq(1) = 1
    do k = 1, size(f%elems)
      xeq(k + 1) = xeq(k) + elem_nodes(m, f%elems(k))
    end do
    allocate(eqs(xeq(size(xeq)) - 1))
    do k = 1, size(f%elems)
      e = f%elems(k)
      n = elem_nodes(m, e)
      pos = xeq(k)
      eqs(pos:pos + n - 1) = f%eqn(m%conn(1:n, e))
    end do
    ! the contact's heat couplings after the elements
    if (f%ch%n > 0) then
      xeq = [xeq, xeq(size(xeq)) - 1 + f%ch%xnode(2:)]
      eqs = [eqs, f%eqn(f%ch%node)]
    end if
    if (f%neq > 0) call sys_setup(f%sys, m%solver, m%ordering, f%neq, xeq, eqs)
  end subroutine number_temperatures

  !> Purpose: the driver's nonlinear path: automatic increments in a step
  !> without DIRECT, steady or transient (CalculiX's *HEAT TRANSFER: they
  !> grow 1.5 times after two increments in a row; DELTMX cuts them
  !> back), and where a material table or radiation makes a step
  !> nonlinear (an increment whose iterations do not converge is cut
  !> back; with DIRECT the run stops).
  logical function nonlinear(f)
    class(temperature_field_t), intent(in) :: f
    nonlinear = f%automatic .or. f%tabled .or. f%radiating
  end function nonlinear

  !> Purpose: the temperature field has no notes on its step.
  subroutine step_notes(f, obs)
    class(temperature_field_t), intent(in) :: f
    type(observer_ref_t), intent(in) :: obs(:)
  end subroutine step_notes

  !> Purpose: an increment t0 -> t1 begins: the temperatures it starts
  !> from are saved, the prescribed ones of t1 set (search_due and
  !> timing: nothing of the temperature field).
  subroutine begin_increment(f, m, t0, t1, search_due, timing)
    class(temperature_field_t), intent(inout) :: f
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: t0, t1
    logical, intent(in) :: search_due
    type(run_timing_t), intent(inout) :: timing
    integer :: a
    f%saved = f%temp
    f%dt = t1 - t0
    f%t1 = t1
    do a = 1, m%nn
      if (f%presc(a)) f%temp(a) = prescribed_at(f, m, a, t1)
    end do
  end subroutine begin_increment

  !> The temperature prescribed at node a at step time t: with an
  !> amplitude its value times the amplitude; without, in a steady step
  !> ramped from the step's start, in a transient one the value at once
  !> (the default amplitudes of Abaqus's *HEAT TRANSFER, docs/heat.md).
  real(dp) function prescribed_at(f, m, a, t) result(v)
    class(temperature_field_t), intent(in) :: f
    type(model_t), intent(in) :: m
    integer, intent(in) :: a
    real(dp), intent(in) :: t
    if (f%t_amp(a) > 0) then
      v = f%t_end(a) * amp_at(f, m, f%t_amp(a), t)
    else if (f%steady) then
      v = f%t_start(a) + (f%t_end(a) - f%t_start(a)) * t / m%steps(f%is)%period
    else
      v = f%t_end(a)
    end if
  end function prescribed_at

  !> The factor of a load at step time t: its amplitude's value, or the
  !> default amplitude (a ramp over a steady step, a step in a transient);
  !> 1 for a load held from an earlier step.
  real(dp) function load_factor(f, m, amp, t) result(v)
    class(temperature_field_t), intent(in) :: f
    type(model_t), intent(in) :: m
    integer, intent(in) :: amp
    real(dp), intent(in) :: t
    if (amp == held) then
      v = 1.0_dp
    else if (amp > 0) then
      v = amp_at(f, m, amp, t)
    else if (f%steady) then
      v = t / m%steps(f%is)%period
    else
      v = 1.0_dp
    end if
  end function load_factor

  !> Amplitude ia at step time t (TIME=TOTAL TIME: at the total time):
  !> the model's amplitude_at (tabular or periodic).
  real(dp) function amp_at(f, m, ia, t) result(v)
    class(temperature_field_t), intent(in) :: f
    type(model_t), intent(in) :: m
    integer, intent(in) :: ia
    real(dp), intent(in) :: t
    real(dp) :: tt
    tt = t
    if (m%amplitudes(ia)%time == amp_total_time) tt = f%total_time + t
    v = amplitude_at(m%amplitudes(ia), tt)
  end function amp_at

  !> Purpose: the temperatures of t1: the system (C/dt + K + H) T1 =
  !> C/dt T0' + F(t1) (steady: without C; T0' docs/heat.md) solved for
  !> the correction of the current temperatures, once where it is linear
  !> (factorised again only when dt or the step changed), iterated where
  !> a material table (fixed point: the matrices at the temperatures of
  !> the iteration before) or radiation (Newton: its tangent in the
  !> matrix) makes it nonlinear; the reaction fluxes; ok false when
  !> DELTMX is exceeded (automatic increments), the iterations do not
  !> converge or the factorisation failed.
  subroutine solve(f, m, is, inc, obs, ok, iters)
    class(temperature_field_t), intent(inout) :: f
    type(model_t), intent(in) :: m
    integer, intent(in) :: is, inc
    type(observer_ref_t), intent(in) :: obs(:)
    logical, intent(out) :: ok
    integer, intent(out) :: iters
    real(dp), allocatable :: rhs(:), r(:)
    real(dp) :: t0, change
    integer :: a
    ok = .true.
    f%why = ''
    allocate(rhs(max(f%neq, 1)), r(m%nn))
    do iters = 1, max_iterations
      if (f%tabled) call refresh_conduction(f, m)
      if (f%neq > 0 .and. (f%factored_dt < 0.0_dp .or. f%radiating .or. &
          (.not. f%steady .and. abs(f%dt - f%factored_dt) > 1.0e-12_dp * f%dt))) then
        call factor(f, m, is, inc, ok)
        if (.not. ok) return
      end if
      t0 = wall_time()
      call residual(f, m, rhs, r)
      change = 0.0_dp
      if (f%neq > 0) then
        call sys_solve(f%sys, rhs(1:f%neq))
        do a = 1, m%nn
          if (f%eqn(a) == 0) cycle
          f%temp(a) = f%temp(a) + rhs(f%eqn(a))
          change = max(change, abs(rhs(f%eqn(a))))
        end do
      end if
      f%t_solve = f%t_solve + (wall_time() - t0)
      f%iterations = f%iterations + 1
      call stop_if_not_finite(m, is, inc, f%temp)
      if (.not. (f%tabled .or. f%radiating)) exit
      if (change <= iteration_tolerance * max(1.0_dp, maxval(abs(f%temp)))) exit
    end do
    if (iters > max_iterations) then
      iters = max_iterations
      ok = .false.
      f%why = 'the iterations of the temperatures (a temperature-dependent material, radiation) did not ' // &
              'converge in ' // itoa(iters) // ' iterations'
      return
    end if
    ! the reaction fluxes: the residual at the prescribed nodes
    call residual(f, m, rhs, r)
    f%rfl = 0.0_dp
    where (f%presc) f%rfl = -r
    f%largest_change = maxval(abs(f%temp - f%saved), mask=f%eqn > 0, dim=1)
    if (f%neq == 0) f%largest_change = 0.0_dp
    if (f%deltmx > 0.0_dp .and. .not. f%steady) ok = f%largest_change <= f%deltmx
    if (.not. ok) f%why = 'a temperature changed by ' // rtoa(f%largest_change, 4) // ', more than DELTMX=' // &
                          rtoa(f%deltmx, 4)
  end subroutine solve

  !> Stops the run, naming the node, where a temperature of an iteration
  !> is not a finite number (magnitudes in the deck that overflow; no
  !> smaller increment helps), as check_finite does for the results.
  subroutine stop_if_not_finite(m, is, inc, temp)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is, inc
    real(dp), intent(in) :: temp(:)
    integer :: a
    do a = 1, size(temp)
      if (.not. ieee_is_finite(temp(a))) call fatal('step ' // itoa(is) // ', increment ' // itoa(inc) // &
        ': the temperature at node ' // node_label(m, a) // ' is not a finite number (the magnitudes of the ' // &
        'deck overflow)')
    end do
  end subroutine stop_if_not_finite

  !> The conduction and capacity matrices of the elements whose
  !> conductivity or specific heat is a table, at the current
  !> temperatures; the factor is made again.
  subroutine refresh_conduction(f, m)
    class(temperature_field_t), intent(inout) :: f
    type(model_t), intent(in) :: m
    real(dp) :: fb(max_nodes), dv_min
    integer :: k, e, n
    do k = 1, size(f%elems)
      e = f%elems(k)
      n = elem_nodes(m, e)
      associate(mat => m%materials(m%sections(m%elem_section(e))%material))
        if (mat%nk <= 1 .and. mat%nc <= 1) cycle
        call heat_volume_arrays(m%etype(e), m%x(:, m%conn(1:n, e)), elem_thickness(m, e), mat%conductivity, &
                                mat%density * mat%specific_heat, f%ke(:, :, k), f%ce(:, :, k), fb, dv_min, &
                                f%temp(m%conn(1:n, e)), mat%ktab(:, 1:max(mat%nk, 1)), mat%ctab(:, 1:max(mat%nc, 1)))
      end associate
    end do
    f%factored_dt = -1.0_dp
  end subroutine refresh_conduction

  !> The element matrix A_e = K_e + H_e (+ C_e / dt in a transient step)
  !> of the k-th conducting element, with the films of the step on it;
  !> tangent: with the tangent of its radiation at the current
  !> temperatures too (the matrix of a Newton iteration).
  subroutine element_matrix(f, m, k, tangent, ae)
    class(temperature_field_t), intent(in) :: f
    type(model_t), intent(in) :: m
    integer, intent(in) :: k
    logical, intent(in) :: tangent
    real(dp), intent(out) :: ae(max_nodes, max_nodes)
    real(dp) :: he(max_nodes, max_nodes), fe(max_nodes)
    integer :: i, j, e, n
    e = f%elems(k)
    n = elem_nodes(m, e)
    ae = f%ke(:, :, k)
    if (.not. f%steady) ae = ae + f%ce(:, :, k) / f%dt
    do i = f%xfilm(k), f%xfilm(k + 1) - 1
      j = f%ifilm(i)
      call heat_face_arrays(m%etype(e), m%x(:, m%conn(1:n, e)), elem_thickness(m, e), f%films(j)%face, he, fe)
      ae = ae + f%films(j)%value * he
    end do
    if (.not. tangent) return
    do i = f%xrad(k), f%xrad(k + 1) - 1
      call radiation(f, m, k, f%irad(i), he, fe)
      ae = ae + he
    end do
  end subroutine element_matrix

  !> The radiation of f%radiates(j) on the k-th conducting element at the
  !> current temperatures: its tangent re and the heat fe into the
  !> element's nodes (heat_radiation_arrays).
  subroutine radiation(f, m, k, j, re, fe)
    class(temperature_field_t), intent(in) :: f
    type(model_t), intent(in) :: m
    integer, intent(in) :: k, j
    real(dp), intent(out) :: re(max_nodes, max_nodes), fe(max_nodes)
    integer :: e, n
    e = f%elems(k)
    n = elem_nodes(m, e)
    call heat_radiation_arrays(m%etype(e), m%x(:, m%conn(1:n, e)), elem_thickness(m, e), f%radiates(j)%face, &
                               f%temp(m%conn(1:n, e)), m%absolute_zero, sink_at(f, m, f%radiates(j)), &
                               f%radiates(j)%value * m%stefan_boltzmann, re, fe)
  end subroutine radiation

  !> Assembles and factorises the system of the free temperatures.
  subroutine factor(f, m, is, inc, ok)
    class(temperature_field_t), intent(inout) :: f
    type(model_t), intent(in) :: m
    integer, intent(in) :: is, inc
    logical, intent(out) :: ok
    real(dp) :: ae(max_nodes, max_nodes), t0
    real(dp), allocatable :: ac(:, :)
    character(len=:), allocatable :: at
    integer :: k, n, status, bad, a
    t0 = wall_time()
    call sys_zero(f%sys)
    do k = 1, size(f%elems)
      n = elem_nodes(m, f%elems(k))
      call element_matrix(f, m, k, .true., ae)
      call sys_add(f%sys, k, ae(1:n, 1:n))
    end do
    do k = 1, f%ch%n
      call contact_heat_matrix(f%ch, k, ac, n)
      call sys_add(f%sys, size(f%elems) + k, ac)
    end do
    call sys_factor(f%sys, status, bad)
    ok = status == factor_ok .or. status == factor_fallback
    if (.not. ok) then
      ! a region that nothing holds, named by its first node (the node of
      ! the zero pivot is round-off's pick); without one the matrix is
      ! singular to round-off only, which no node explains
      a = floating_node(f, m)
      at = ' to round-off: conductances (*CONDUCTIVITY, *FILM, *GAP CONDUCTANCE) of too different magnitudes'
      if (a > 0) at = ': node ' // node_label(m, a) // ' is in a region without a prescribed temperature ' // &
                      'or a film (or radiating at absolute zero)'
      call fatal('step ' // itoa(is) // ', increment ' // itoa(inc) // ': the heat conduction matrix is ' // &
        'singular' // at)
    end if
    f%factored_dt = merge(0.0_dp, f%dt, f%steady)
    f%factorisations = f%factorisations + 1
    f%t_factor = f%t_factor + (wall_time() - t0)
  end subroutine factor

  !> The first node (in the model's order) of a region of conducting
  !> elements, joined through their nodes and the contact's conducting
  !> heat couplings, that has no prescribed temperature, film or
  !> radiation, where a steady conduction matrix is singular; 0 if there
  !> is none. It names the region in the error whatever the pivot order
  !> (the node the factorisation stops at depends on round-off).
  integer function floating_node(f, m) result(first)
    class(temperature_field_t), intent(in) :: f
    type(model_t), intent(in) :: m
    integer, allocatable :: root(:)
    logical, allocatable :: held(:)
    integer :: k, e, n, j, a
    allocate(root(m%nn), held(m%nn))
    root = [(a, a = 1, m%nn)]
    held = f%presc
    do k = 1, size(f%elems)
      e = f%elems(k)
      n = elem_nodes(m, e)
      do j = 2, n
        call join(m%conn(1, e), m%conn(j, e))
      end do
      if (f%xfilm(k + 1) > f%xfilm(k) .or. f%xrad(k + 1) > f%xrad(k)) held(m%conn(1, e)) = .true.
    end do
    do k = 1, f%ch%n
      if (f%ch%ha(k) <= 0.0_dp) cycle
      do j = f%ch%xnode(k) + 1, f%ch%xnode(k + 1) - 1
        call join(f%ch%node(f%ch%xnode(k)), f%ch%node(j))
      end do
    end do
    do a = 1, m%nn
      if (held(a)) held(top(a)) = .true.
    end do
    first = 0
    do a = 1, m%nn
      if (f%eqn(a) > 0 .and. .not. held(top(a))) then
        first = a
        return
      end if
    end do
  contains
    !> The root of node i's region (its smallest node once joined).
    integer function top(i)
      integer, intent(in) :: i
      top = i
      do while (root(top) /= top)
        root(top) = root(root(top))      ! (path halving: short chains)
        top = root(top)
      end do
    end function top
    !> Nodes i and j2 in one region.
    subroutine join(i, j2)
      integer, intent(in) :: i, j2
      integer :: ri, rj
      ri = top(i)
      rj = top(j2)
      if (ri /= rj) root(max(ri, rj)) = min(ri, rj)
    end subroutine join
  end function floating_node

  !> The residual r(nn) = F - A T of every node at the current
  !> temperatures T (F with the radiation at T), and rhs(neq) its free
  !> rows: the right-hand side of the correction.
  subroutine residual(f, m, rhs, r)
    class(temperature_field_t), intent(in) :: f
    type(model_t), intent(in) :: m
    real(dp), intent(out) :: rhs(:), r(:)
    real(dp) :: ae(max_nodes, max_nodes), fe(max_nodes), te(max_nodes)
    integer :: k, e, n, j, a
    r = 0.0_dp
    do k = 1, size(f%elems)
      e = f%elems(k)
      n = elem_nodes(m, e)
      call element_matrix(f, m, k, .false., ae)
      call element_loads(f, m, k, fe)
      te(1:n) = f%temp(m%conn(1:n, e))
      r(m%conn(1:n, e)) = r(m%conn(1:n, e)) + fe(1:n) - matmul(ae(1:n, 1:n), te(1:n))
    end do
    do j = 1, size(f%cfluxes)
      a = f%cfluxes(j)%node
      r(a) = r(a) + f%cfluxes(j)%value * load_factor(f, m, f%cfluxes(j)%amp, f%t1)
    end do
    call contact_heat_residual(f%ch, f%temp, r)
    rhs = 0.0_dp
    do a = 1, m%nn
      if (f%eqn(a) > 0) rhs(f%eqn(a)) = r(a)
    end do
  end subroutine residual

  !> The loads of the k-th conducting element at t1: the capacity term
  !> C_e/dt T0'_e of a transient step, its body and surface fluxes, its
  !> films' h T_sink, its radiation at the current temperatures.
  subroutine element_loads(f, m, k, fe)
    class(temperature_field_t), intent(in) :: f
    type(model_t), intent(in) :: m
    integer, intent(in) :: k
    real(dp), intent(out) :: fe(max_nodes)
    real(dp) :: he(max_nodes, max_nodes), fs(max_nodes), te(max_nodes)
    integer :: i, j, e, n
    e = f%elems(k)
    n = elem_nodes(m, e)
    fe = 0.0_dp
    if (.not. f%steady) then
      ! the capacity acts on the change of the free temperatures only (a
      ! prescribed node's start value is its value at t1), as CalculiX
      te(1:n) = merge(f%temp(m%conn(1:n, e)), f%saved(m%conn(1:n, e)), f%presc(m%conn(1:n, e)))
      fe(1:n) = matmul(f%ce(1:n, 1:n, k), te(1:n)) / f%dt
    end if
    do i = f%xflux(k), f%xflux(k + 1) - 1
      j = f%iflux(i)
      if (f%dfluxes(j)%face == heat_bf) then
        fs = f%fb(:, k)
      else
        call heat_face_arrays(m%etype(e), m%x(:, m%conn(1:n, e)), elem_thickness(m, e), f%dfluxes(j)%face, he, fs)
      end if
      fe = fe + f%dfluxes(j)%value * load_factor(f, m, f%dfluxes(j)%amp, f%t1) * fs
    end do
    do i = f%xfilm(k), f%xfilm(k + 1) - 1
      j = f%ifilm(i)
      call heat_face_arrays(m%etype(e), m%x(:, m%conn(1:n, e)), elem_thickness(m, e), f%films(j)%face, he, fs)
      fe = fe + f%films(j)%value * sink_at(f, m, f%films(j)) * fs
    end do
    do i = f%xrad(k), f%xrad(k + 1) - 1
      call radiation(f, m, k, f%irad(i), he, fs)
      fe = fe + fs
    end do
  end subroutine element_loads

  !> The sink temperature of a film or radiation at t1 (its amplitude
  !> scales it; no amplitude: the value at once, as the film
  !> coefficient).
  real(dp) function sink_at(f, m, film) result(v)
    class(temperature_field_t), intent(in) :: f
    type(model_t), intent(in) :: m
    type(heat_load_t), intent(in) :: film
    v = film%sink
    if (film%amp > 0) v = film%sink * amp_at(f, m, film%amp, f%t1)
  end function sink_at

  !> Purpose: nothing path-dependent to commit (the temperatures are the
  !> state the next increment starts from).
  subroutine commit(f)
    class(temperature_field_t), intent(inout) :: f
    f%saved = f%temp
  end subroutine commit

  !> Purpose: back to the temperatures the increment started from.
  subroutine restore(f, m)
    class(temperature_field_t), intent(inout) :: f
    type(model_t), intent(in) :: m
    f%temp = f%saved
  end subroutine restore

  !> Purpose: the increment changed a temperature by more than DELTMX:
  !> cut by D_A DELTMX / the largest change (CalculiX's checkconvergence,
  !> D_A = 0.85 of its *CONTROLS; below 0.85 since the change exceeds
  !> DELTMX); the conduction iterations did not converge: cut to a
  !> quarter (D_F).
  subroutine failure(f, reason, cut, changing)
    class(temperature_field_t), intent(in) :: f
    character(len=:), allocatable, intent(out) :: reason, changing
    real(dp), intent(out) :: cut
    reason = f%why
    cut = 0.85_dp * f%deltmx / max(f%largest_change, tiny(1.0_dp))
    if (f%deltmx <= 0.0_dp .or. f%largest_change <= f%deltmx) cut = 0.25_dp
    ! a cut that would not shrink the increment (a change that is not a
    ! finite number) is D_F's quarter: every cut back makes progress
    if (.not. (cut > 0.0_dp .and. cut <= 0.85_dp)) cut = 0.25_dp
    changing = ''
  end subroutine failure

  !> Purpose: the temperatures (NT) and reaction fluxes (RFL) of a
  !> converged increment at step time t, to every observer (no
  !> displacements, stresses or contact in a heat transfer step).
  subroutine report(f, m, is, inc, t, total_time, iters, dt, obs, timing)
    class(temperature_field_t), intent(inout) :: f
    type(model_t), intent(in) :: m
    integer, intent(in) :: is, inc, iters
    real(dp), intent(in) :: t, total_time, dt
    type(observer_ref_t), intent(in) :: obs(:)
    type(run_timing_t), intent(inout) :: timing
    type(increment_results_t) :: res
    integer :: k
    real(dp) :: t0
    t0 = wall_time()
    res%step = is
    res%increment = inc
    res%iterations = iters
    res%time = t
    res%total_time = total_time
    res%dt = dt
    res%heat = .true.
    res%nt = f%temp
    res%rfl = f%rfl
    allocate(res%u(2, m%nn), res%rf(2, m%nn), res%set_ids(0), res%set_sums(2, 0))
    res%u = 0.0_dp
    res%rf = 0.0_dp
    allocate(res%nip(m%ne), res%sig_ip(4, 1, 0), res%eps_ip(3, 1, 0), res%sig_node(4, 0), res%sig_elem(4, 0), &
             res%peeq_ip(1, 0), res%peeq_elem(0))
    call heat_fluxes(f, m, any(m%steps(is)%requests%hfl), res%nip, res%hfl_ip)
    call check_finite(m, res)
    allocate(res%contact%pairs(0), res%contact%pressure(m%nn), res%contact%shear(m%nn), &
             res%contact%has_pressure(m%nn))
    res%contact%pressure = 0.0_dp
    res%contact%shear = 0.0_dp
    res%contact%has_pressure = .false.
    do k = 1, size(obs)
      call obs(k)%o%increment_done(m, res)
    end do
    timing%output = timing%output + (wall_time() - t0)
  end subroutine report

  !> Stops the run, naming the increment, the quantity and the node or
  !> element, where a result is not a finite number (magnitudes in the
  !> deck that overflow): nothing that is not a number is written.
  subroutine check_finite(m, res)
    type(model_t), intent(in) :: m
    type(increment_results_t), intent(in) :: res
    character(len=:), allocatable :: at
    integer :: a, e
    at = 'step ' // itoa(res%step) // ', increment ' // itoa(res%increment) // ': '
    do a = 1, m%nn
      if (.not. ieee_is_finite(res%nt(a))) call fatal(at // 'the temperature at node ' // node_label(m, a) // &
        ' is not a finite number (the magnitudes of the deck overflow)')
      if (.not. ieee_is_finite(res%rfl(a))) call fatal(at // 'the reaction flux at node ' // node_label(m, a) // &
        ' is not a finite number (the magnitudes of the deck overflow)')
    end do
    do e = 1, size(res%hfl_ip, 3)
      if (.not. all(ieee_is_finite(res%hfl_ip(:, 1:res%nip(e), e)))) call fatal(at // 'the heat flux in element ' // &
        elem_label(m, e) // ' is not a finite number (the magnitudes of the deck overflow)')
    end do
  end subroutine check_finite

  !> The heat flux -k grad T at the integration points of the
  !> conducting elements (the catalogue's rule of each, 3 points on the
  !> quadratic triangles: CalculiX's points of the plane and axisymmetric
  !> elements), when wanted (HFL); nip(e) their count (0 for other
  !> elements, and for all when not wanted).
  subroutine heat_fluxes(f, m, wanted, nip, hfl)
    class(temperature_field_t), intent(in) :: f
    type(model_t), intent(in) :: m
    logical, intent(in) :: wanted
    integer, intent(out) :: nip(:)
    real(dp), allocatable, intent(out) :: hfl(:, :, :)
    real(dp) :: xi(2, max_ip), w(max_ip), cond(2)
    integer :: k, e, n, ip
    nip = 0
    allocate(hfl(2, max_ip, merge(m%ne, 0, wanted)))
    if (.not. wanted) return
    hfl = 0.0_dp
    do k = 1, size(f%elems)
      e = f%elems(k)
      n = elem_nodes(m, e)
      nip(e) = catalogue(m%etype(e))%nip
      ! a quadratic triangle at the 3 points of CPS6 (CAX6's 6 points are
      ! its hoop terms' rule; CalculiX lists its flux at 3 points too)
      if (catalogue(m%etype(e))%shape == shape_tri6) nip(e) = 3
      call gauss_rule(catalogue(m%etype(e))%shape, nip(e), xi, w)
      associate(mat => m%materials(m%sections(m%elem_section(e))%material))
        do ip = 1, nip(e)
          cond = mat%conductivity
          if (mat%nk > 1) cond = table_at(mat%ktab(:, 1:mat%nk), &
                                          temperature_at(m%etype(e), f%temp(m%conn(1:n, e)), xi(:, ip)))
          hfl(:, ip, e) = -cond * heat_gradient(m%etype(e), m%x(:, m%conn(1:n, e)), f%temp(m%conn(1:n, e)), &
                                                xi(:, ip))
        end do
      end associate
    end do
  end subroutine heat_fluxes

  !> Purpose: the step's factorisations (also apart: the listing's per
  !> field line) and iterations (the solves of its increments and their
  !> tries: one each where the step is linear).
  subroutine end_step(f, obs, summary)
    class(temperature_field_t), intent(inout) :: f
    type(observer_ref_t), intent(in) :: obs(:)
    type(step_summary_t), intent(inout) :: summary
    summary%factorisations = summary%factorisations + f%factorisations
    summary%temperature_factorisations = f%factorisations
    summary%newton_iterations = summary%newton_iterations + f%iterations
    f%run_factorisations = f%run_factorisations + f%factorisations
    f%factorisations = 0
    f%iterations = 0
  end subroutine end_step

  !> Purpose: the heat couplings of the contact (contact_heat) for the
  !> next solve, from a coupled run's driver: the structure made again
  !> where the couplings join other nodes; the matrix factorised again
  !> only where a coupling's h A w w^T changed (a pressure-dependent
  !> conductance, a point that opened or closed, a re-search), so that a
  !> constant conductance keeps the factor across the passes and
  !> increments as the conduction alone does (the frictional heat is on
  !> the right-hand side only).
  subroutine take_contact_heat(f, m, ch)
    class(temperature_field_t), intent(inout) :: f
    type(model_t), intent(in) :: m
    type(contact_heat_t), intent(in) :: ch
    logical :: same, same_matrix
    same = same_couplings(f%ch, ch)
    same_matrix = .false.
    ! (the same structure: both were built, their arrays allocated)
    if (same) same_matrix = same_matrices(f%ch, ch)
    f%ch = ch
    if (.not. same .and. allocated(f%eqn)) call number_temperatures(f, m)
    if (.not. same_matrix) f%factored_dt = -1.0_dp
  end subroutine take_contact_heat

  !> Purpose: the temperature field's factorisations (their count too)
  !> and solves in the run's timing.
  subroutine finish(f, timing)
    class(temperature_field_t), intent(in) :: f
    type(run_timing_t), intent(inout) :: timing
    timing%factor = timing%factor + f%t_factor
    timing%solve = timing%solve + f%t_solve
    timing%numeric_factorisations = timing%numeric_factorisations + f%run_factorisations
  end subroutine finish
end module temperature_field
