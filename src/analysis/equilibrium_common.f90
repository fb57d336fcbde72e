!> What the two linear paths of the equilibrium iteration share (module
!> equilibrium: the whole stiffness factored for every contact status;
!> condensed_equilibrium: the contact equations condensed out of one
!> factorisation of the bodies): the state of the iteration carried from
!> increment to increment, internal forces, the out-of-balance test, the
!> reuse of a factor while the status is the one it was made for
!> (factor_fits, factor_made), the stabilisation of open contact and the
!> taking back of a pivot, the events told to the observers, and the stop
!> on a singular stiffness.
module equilibrium_common
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  use strings, only: itoa
  use model, only: model_t, node_label
  use contact, only: contact_set_t, contact_forces, status_codes, reset_stabilisation, restabilise
  use contact_status, only: status_search_t, reject_pivot, begin_status_search
  use assembly, only: element_counts_t, body_t, body_forces, nonlinear_body_forces
  use dof_numbering, only: dofmap_t
  use linear_solver, only: linear_system_t, sys_describe
  use condensed_contact, only: condensed_t
  use analysis_events, only: observer_ref_t, iteration_info_t, solver_info_t, run_timing_t, tell_iteration, &
                             tell_solver_ready, tell_note
  use newton_control, only: newton_t
  use messages, only: fatal
  implicit none
  private
  public :: equilibrium_t, begin_equilibrium, internal_forces, relative_residual, check_finite, report_iteration, &
            describe, singular, contact_force_scale, take_back, stabilise_open, next_stage, set_aside_or_stop, &
            factor_fits, factor_made

  type :: equilibrium_t
    ! factor reuse policy: the factor is valid for the statuses it was made for
    logical :: factor_valid = .false.
    integer, allocatable :: factor_states(:)   ! contact's status_codes
    logical :: factor_stabilised = .false.
    !> The stabilisation of open contact was used in this increment (once
    !> at most: singular again with the nominal open penalty means a body
    !> that contact cannot hold).
    logical :: stabilisation_used = .false.
    logical :: described = .false.
    !> The condensed contact solve (active when the equations were
    !> numbered for it) and whether its factor of the bodies is current.
    type(condensed_t) :: cd
    logical :: k0_valid = .false.
    ! counters of the step
    integer :: factorisations = 0, iterations = 0, condensed_factorisations = 0
    !> statuses of the condensed solve solved in low-rank form (not factored)
    integer :: condensed_lowrank = 0
    type(element_counts_t) :: counts
    !> Wall time by part and factorisation counts of the whole run.
    type(run_timing_t) :: timing
    ! the last iteration
    real(dp) :: kmax = 0.0_dp           ! stiffness scale of the residual test
    real(dp) :: residual = 0.0_dp       ! relative out-of-balance force
    !> The largest force scale of the converged increments so far: an
    !> increment that unloads everything (all forces round-off) is judged
    !> against the forces the model has carried, as CalculiX judges against
    !> the average force of the history.
    real(dp) :: force_history = 0.0_dp
    character(len=:), allocatable :: changed   ! slave nodes that switched last
    !> The contact status search of the increment (contact_status), with
    !> the pivots of the step.
    type(status_search_t) :: search
    integer :: bad = 0                  ! the equation of the last singular factorisation
    real(dp), allocatable :: rhs(:)
    !> The last converged displacements and the bodies' internal forces
    !> there: the condensed solve starts an increment from them (the free
    !> equations), so that its solves are of the increment's change and
    !> their round-off relative to it, and updates the forces only where
    !> prescribed values moved.
    real(dp), allocatable :: u_last(:, :), fbody_last(:, :), fbody(:, :)
    !> Nonlinear steps (newton_t): the Newton iteration's convergence
    !> and divergence tests, as CalculiX makes them.
    type(newton_t) :: newton
    !> Under NLGEOM with contact: the searches made in Newton iterations
    !> (equilibrium's search_in_iteration) and the renumberings of the
    !> equations they (or a cut-back's restore) needed, over the step.
    integer :: searches = 0, renumberings = 0
    !> The couplings the equations were numbered for (equilibrium's
    !> note_numbering: every CFE's node list).
    integer, allocatable :: numbered_for(:)
  end type equilibrium_t

contains

  !> Purpose: a new equation numbering or contact pairing: no factor is
  !> valid; with new_step the step's counters restart.
  subroutine begin_equilibrium(eq, neq, ncfe, new_step)
    type(equilibrium_t), intent(inout) :: eq
    integer, intent(in) :: neq, ncfe
    logical, intent(in) :: new_step
    eq%factor_valid = .false.
    eq%k0_valid = .false.
    if (allocated(eq%factor_states)) deallocate(eq%factor_states)
    allocate(eq%factor_states(ncfe))
    if (allocated(eq%rhs)) deallocate(eq%rhs)
    allocate(eq%rhs(neq))
    if (new_step) then
      eq%described = .false.
      eq%factorisations = 0
      eq%condensed_factorisations = 0
      eq%condensed_lowrank = 0
      eq%iterations = 0
      eq%search = status_search_t()
      eq%searches = 0
      eq%renumberings = 0
    end if
  end subroutine begin_equilibrium

  !> f_int of the bodies (stored stiffness; in a nonlinear step the
  !> element routines at u, which also leave their trial history in body)
  !> and of the CFEs (which also updates their gaps and forces); energy, if
  !> present, the bodies' strain energy 1/2 u . f_body (in a nonlinear
  !> step the same expression: the merit of the contact status search,
  !> exact for the linear bodies it was made for).
  subroutine internal_forces(m, body, cs, u, fint, counts, energy)
    type(model_t), intent(in) :: m
    type(body_t), intent(inout) :: body
    type(contact_set_t), intent(inout) :: cs
    real(dp), intent(in) :: u(:, :)
    real(dp), intent(out) :: fint(:, :)
    type(element_counts_t), intent(inout) :: counts
    real(dp), intent(out), optional :: energy
    if (body%nonlinear) then
      call nonlinear_body_forces(m, body, u, fint, counts)
    else
      call body_forces(m, body, u, fint)
    end if
    if (present(energy)) energy = 0.5_dp * sum(u * fint)
    call contact_forces(m, cs, u, fint, counts%coupling)
  end subroutine internal_forces

  !> Out-of-balance force on the free equations relative to the force
  !> scale: loads, reactions, contact forces, and (for a body that only
  !> moves rigidly) the stiffness times the displacement scaled to a strain
  !> of 1e-6, so that round-off is not mistaken for an out-of-balance force;
  !> never below the force scale of the converged history. ref returns the
  !> force scale of this state.
  real(dp) function relative_residual(dm, cs, fext, u, rf, kmax, history, ref) result(r)
    type(dofmap_t), intent(in) :: dm
    type(contact_set_t), intent(in) :: cs
    real(dp), intent(in) :: fext(:, :), u(:, :), rf(:, :), kmax, history
    real(dp), intent(out) :: ref
    ! norm2 scales internally: no overflow for large but finite forces
    ref = max(norm2(pack(rf, dm%eq == 0)), norm2(fext), sum(abs(cs%c(1:cs%n)%force)), &
              1.0e-6_dp * kmax * maxval(abs(u)), tiny(1.0_dp))
    r = norm2(pack(rf, dm%eq > 0)) / max(ref, history)
  end function relative_residual

  !> Purpose: is the factor in hand (eq%factor_*) the one of the current
  !> contact status of cs? (With every CFE closed, stabilising changes no
  !> penalty.)
  logical function factor_fits(eq, cs)
    type(equilibrium_t), intent(in) :: eq
    type(contact_set_t), intent(in) :: cs
    factor_fits = .false.
    if (eq%factor_valid .and. ((eq%factor_stabilised .eqv. cs%stabilised) .or. all(cs%c(1:cs%n)%closed))) then
      factor_fits = all(eq%factor_states == status_codes(cs))
    end if
  end function factor_fits

  !> Purpose: the factor just made is that of the current status of cs.
  subroutine factor_made(eq, cs)
    type(equilibrium_t), intent(inout) :: eq
    type(contact_set_t), intent(in) :: cs
    eq%factor_states = status_codes(cs)
    eq%factor_stabilised = cs%stabilised
    eq%factor_valid = .true.
  end subroutine factor_made

  !> The force scale that the contact status search judges round-off
  !> against: loads, contact forces and the forces of the history.
  real(dp) function contact_force_scale(eq, cs, fext_norm) result(f)
    type(equilibrium_t), intent(in) :: eq
    type(contact_set_t), intent(in) :: cs
    real(dp), intent(in) :: fext_norm
    f = max(fext_norm, sum(abs(cs%c(1:cs%n)%force)), eq%force_history, tiny(1.0_dp))
  end function contact_force_scale

  !> Stops if a displacement is not a finite number.
  subroutine check_finite(m, is, inc, u)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is, inc
    real(dp), intent(in) :: u(:, :)
    integer :: a
    do a = 1, m%nn
      if (.not. all(ieee_is_finite(u(:, a)))) call fatal('step ' // itoa(is) // ', increment ' // &
        itoa(inc) // ': the displacement at node ' // node_label(m, a) // ' is not a finite number ' // &
        '(overflow: loads, stiffness or displacements out of range?); results of this increment are not written')
    end do
  end subroutine check_finite

  !> The iteration event (with contact only).
  subroutine report_iteration(eq, cs, obs, it, nchanged)
    type(equilibrium_t), intent(in) :: eq
    type(contact_set_t), intent(in) :: cs
    type(observer_ref_t), intent(in) :: obs(:)
    integer, intent(in) :: it, nchanged
    type(iteration_info_t) :: info
    if (cs%n == 0) return
    info%iteration = it
    info%changes = nchanged
    info%closed = count(cs%c(1:cs%n)%closed)
    info%residual = eq%residual
    info%changed = eq%changed
    call tell_iteration(obs, info)
  end subroutine report_iteration

  !> The solver event, once per step.
  subroutine describe(eq, is, cs, sys, obs)
    type(equilibrium_t), intent(inout) :: eq
    integer, intent(in) :: is
    type(contact_set_t), intent(in) :: cs
    type(linear_system_t), intent(in) :: sys
    type(observer_ref_t), intent(in) :: obs(:)
    type(solver_info_t) :: info
    if (eq%described) return
    info%step = is
    info%description = sys_describe(sys)
    info%contact_solve = ''
    if (cs%n > 0) info%contact_solve = merge('condensed', 'full     ', eq%cd%active)
    info%contact_solve = trim(info%contact_solve)
    if (eq%cd%active) info%contact_equations = eq%cd%m
    call tell_solver_ready(obs, info)
    eq%described = .true.
  end subroutine describe

  !> The last pivot led to a status whose stiffness is singular: it is
  !> taken back for a single pivot (contact_status's reject_pivot); none
  !> left stops the run naming the node and dof of the last singular
  !> factorisation.
  subroutine take_back(eq, m, cs, dm, obs)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(inout) :: cs
    type(dofmap_t), intent(in) :: dm
    type(observer_ref_t), intent(in) :: obs(:)
    logical :: found
    call reject_pivot(m, cs, eq%search, found, eq%changed)
    if (.not. found) call singular(m, cs, dm, eq%bad)
    call tell_note(obs, 'the contact status of the last pivot has a singular stiffness: pivot taken back, ' // &
                        'single pivot on' // eq%changed)
  end subroutine take_back

  !> Purpose: a singular stiffness with open CFEs (a body held only by
  !> open contact) and the stabilisation not yet used in this increment:
  !> the open CFEs are stabilised (contact_set_t), a new search begins
  !> (the open penalty changed), which may still take back the pivot that
  !> led here; true if so.
  logical function stabilise_open(eq, cs, obs) result(done)
    type(equilibrium_t), intent(inout) :: eq
    type(contact_set_t), intent(inout) :: cs
    type(observer_ref_t), intent(in) :: obs(:)
    logical :: pivoted
    done = .not. eq%stabilisation_used .and. any(.not. cs%c(1:cs%n)%closed)
    if (.not. done) return
    call reset_stabilisation(cs)
    cs%stabilised = .true.
    eq%stabilisation_used = .true.
    pivoted = eq%search%pivoted
    call begin_status_search(eq%search)
    eq%search%pivoted = pivoted
    call tell_note(obs, 'singular stiffness with open contact: stabilising the open contact elements ' // &
                        'until the status settles')
  end function stabilise_open

  !> Purpose: the stabilised search has settled: where the stabilisation,
  !> not the contact, still holds the body, a new stage of it, anchored
  !> where the body came to rest (contact's restabilise), and a new
  !> search; true if so (the caller searches again from the increment's
  !> start), false to go on with the nominal open penalty.
  !> Arguments: force_scale as contact_switch.
  logical function next_stage(eq, cs, force_scale, obs) result(again)
    type(equilibrium_t), intent(inout) :: eq
    type(contact_set_t), intent(inout) :: cs
    real(dp), intent(in) :: force_scale
    type(observer_ref_t), intent(in) :: obs(:)
    again = restabilise(cs, force_scale)
    if (.not. again) return
    call begin_status_search(eq%search)
    call tell_note(obs, 'the settled status holds the body only through the stabilisation: stabilising ' // &
                        'again from where it came to rest')
  end function next_stage

  !> Purpose: a singular stiffness that stabilising cannot mend: where the
  !> status comes from a pivot of the search, the factor is set aside
  !> (usable false: the pivot is to be taken back, take_back); otherwise
  !> the run stops naming node and dof (bad).
  subroutine set_aside_or_stop(eq, m, cs, dm, bad, usable)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    type(dofmap_t), intent(in) :: dm
    integer, intent(in) :: bad
    logical, intent(out) :: usable
    if (.not. eq%search%pivoted) call singular(m, cs, dm, bad)
    usable = .false.
    eq%factor_valid = .false.
    eq%bad = bad
  end subroutine set_aside_or_stop

  !> Stops on a singular stiffness, naming the node and dof where the
  !> factorisation found it.
  subroutine singular(m, cs, dm, bad)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    type(dofmap_t), intent(in) :: dm
    integer, intent(in) :: bad
    character(len=:), allocatable :: hint
    hint = ''
    if (cs%n > 0) hint = '; a body held only by open contact has no stiffness: give it a support, ' // &
      'or a load or displacement that brings it into contact'
    if (any(cs%c(1:cs%n)%closed .and. cs%c(1:cs%n)%sliding)) hint = '; points in contact slide: a body ' // &
      'held sideways only by sliding friction cannot take more than mu times its normal force (a load ' // &
      'beyond it has no equilibrium), or it is held by open contact only'
    if (bad > 0 .and. bad <= dm%neq) call fatal('singular stiffness at node ' // &
      node_label(m, dm%node_of_eq(bad)) // ', dof ' // itoa(dm%dof_of_eq(bad)) // &
      ' (missing boundary condition?)' // hint)
    call fatal('singular stiffness (missing boundary condition?)' // hint)
  end subroutine singular
end module equilibrium_common
