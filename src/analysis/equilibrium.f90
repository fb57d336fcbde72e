!> The equilibrium iteration of one increment: Newton passes on the
!> piecewise-linear system, each solving K du = f_ext - f_int(u) with the
!> current contact status, followed by the contact layer's switching rule,
!> until no status changes and the out-of-balance force is below the
!> tolerance. The stiffness depends only on the contact status, so its
!> factor is kept while the status is the one it was made for.
module equilibrium
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  use strings, only: itoa
  use model
  use contact, only: contact_set_t, contact_forces, contact_switch
  use assembly, only: body_t, element_counts_t, assemble_stiffness, body_forces, free_residual
  use dof_numbering, only: dofmap_t
  use linear_solver, only: linear_system_t, sys_factor, sys_solve, sys_describe, factor_singular, factor_fallback
  use analysis_events, only: observer_ref_t, iteration_info_t, tell_iteration, tell_note, tell_solver_ready
  use messages, only: fatal, warn
  implicit none
  private
  public :: equilibrium_t, begin_equilibrium, solve_increment

  type :: equilibrium_t
    ! factor reuse policy: the factor is valid for the statuses it was made for
    logical :: factor_valid = .false.
    logical, allocatable :: factor_states(:)
    logical :: factor_stabilised = .false.
    !> The stabilisation of open contact was used in this increment (once
    !> at most: singular again with the nominal open penalty means a body
    !> that contact cannot hold).
    logical :: stabilisation_used = .false.
    logical :: described = .false.
    ! counters of the step
    integer :: factorisations = 0, iterations = 0
    type(element_counts_t) :: counts
    ! the last iteration
    real(dp) :: kmax = 0.0_dp           ! stiffness scale of the residual test
    real(dp) :: residual = 0.0_dp       ! relative out-of-balance force
    !> The largest force scale of the converged increments so far: an
    !> increment that unloads everything (all forces round-off) is judged
    !> against the forces the model has carried, as CalculiX judges against
    !> the average force of the history.
    real(dp) :: force_history = 0.0_dp
    character(len=:), allocatable :: changed   ! slave nodes that switched last
    real(dp), allocatable :: rhs(:)
  end type equilibrium_t

contains

  !> Purpose: a new equation numbering or contact pairing: no factor is
  !> valid; with new_step the step's counters restart.
  subroutine begin_equilibrium(eq, neq, ncfe, new_step)
    type(equilibrium_t), intent(inout) :: eq
    integer, intent(in) :: neq, ncfe
    logical, intent(in) :: new_step
    eq%factor_valid = .false.
    if (allocated(eq%factor_states)) deallocate(eq%factor_states)
    allocate(eq%factor_states(ncfe))
    if (allocated(eq%rhs)) deallocate(eq%rhs)
    allocate(eq%rhs(neq))
    if (new_step) then
      eq%described = .false.
      eq%factorisations = 0
      eq%iterations = 0
    end if
  end subroutine begin_equilibrium

  !> Purpose: equilibrium at the prescribed values and loads already in u
  !> and fext. On return u holds the solution, rf = f_int - f_ext (the
  !> reactions at prescribed dofs), ok whether it converged and iters the
  !> iterations used.
  subroutine solve_increment(eq, m, is, inc, body, cs, dm, sys, fext, u, rf, obs, ok, iters)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    integer, intent(in) :: is, inc       ! step, and the increment being solved
    type(body_t), intent(in) :: body
    type(contact_set_t), intent(inout) :: cs
    type(dofmap_t), intent(in) :: dm
    type(linear_system_t), intent(inout) :: sys
    real(dp), intent(in) :: fext(:, :)
    real(dp), intent(inout) :: u(:, :)
    real(dp), intent(out) :: rf(:, :)
    type(observer_ref_t), intent(in) :: obs(:)
    logical, intent(out) :: ok
    integer, intent(out) :: iters
    type(iteration_info_t) :: info
    real(dp), allocatable :: fint(:, :)
    integer :: it, a, d, nchanged
    logical :: restabilised
    real(dp) :: scale
    allocate(fint(2, m%nn))
    ok = .false.
    cs%stabilised = .false.
    eq%stabilisation_used = .false.
    call internal_forces(m, body, cs, u, fint, eq%counts)
    do it = 1, m%contact_max_iter
      call factor_if_needed(eq, m, is, body, cs, dm, u, sys, obs, restabilised)
      if (restabilised) call internal_forces(m, body, cs, u, fint, eq%counts)
      call free_residual(dm, fext, fint, eq%rhs)
      call sys_solve(sys, eq%rhs)
      do a = 1, m%nn
        do d = 1, 2
          if (dm%eq(d, a) > 0) u(d, a) = u(d, a) + eq%rhs(dm%eq(d, a))
        end do
        if (.not. all(ieee_is_finite(u(:, a)))) call fatal('step ' // itoa(is) // ', increment ' // &
          itoa(inc) // ': the displacement at node ' // itoa(m%node_id(a)) // ' is not a finite number ' // &
          '(overflow: loads, stiffness or displacements out of range?); results of this increment are not written')
      end do
      call internal_forces(m, body, cs, u, fint, eq%counts)
      call contact_switch(m, cs, nchanged, eq%changed)
      ! the residual of the new status
      if (nchanged > 0) call internal_forces(m, body, cs, u, fint, eq%counts)
      rf = fint - fext
      eq%residual = relative_residual(dm, cs, fext, u, rf, eq%kmax, eq%force_history, scale)
      eq%iterations = eq%iterations + 1
      if (cs%n > 0) then
        info%iteration = it
        info%changes = nchanged
        info%closed = count(cs%c(1:cs%n)%closed)
        info%residual = eq%residual
        info%changed = eq%changed
        call tell_iteration(obs, info)
      end if
      if (nchanged == 0 .and. cs%stabilised) then
        ! settled while stabilised: on with the nominal open penalty
        cs%stabilised = .false.
        call internal_forces(m, body, cs, u, fint, eq%counts)
        call tell_note(obs, 'contact status settled with the stabilised open penalty; ' // &
                            'iterating on with the nominal one')
        cycle
      end if
      if (nchanged == 0 .and. eq%residual < m%contact_tolerance) then
        ok = .true.
        iters = it
        eq%force_history = max(eq%force_history, scale)
        return
      end if
    end do
    iters = m%contact_max_iter
  end subroutine solve_increment

  !> f_int of the bodies (stored stiffness) and of the CFEs (which also
  !> updates their gaps and forces).
  subroutine internal_forces(m, body, cs, u, fint, counts)
    type(model_t), intent(in) :: m
    type(body_t), intent(in) :: body
    type(contact_set_t), intent(inout) :: cs
    real(dp), intent(in) :: u(:, :)
    real(dp), intent(out) :: fint(:, :)
    type(element_counts_t), intent(inout) :: counts
    call body_forces(m, body, u, fint)
    call contact_forces(m, cs, u, fint, counts%coupling)
  end subroutine internal_forces

  !> Assembles and factors the stiffness unless the factor in hand was made
  !> for the current contact status. A singular stiffness with open CFEs
  !> (a body held only by open contact) is factored again with the
  !> stabilised open penalty (contact_set_t); restabilised says so.
  subroutine factor_if_needed(eq, m, is, body, cs, dm, u, sys, obs, restabilised)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    integer, intent(in) :: is
    type(body_t), intent(in) :: body
    type(contact_set_t), intent(inout) :: cs
    type(dofmap_t), intent(in) :: dm
    real(dp), intent(in) :: u(:, :)
    type(linear_system_t), intent(inout) :: sys
    type(observer_ref_t), intent(in) :: obs(:)
    logical, intent(out) :: restabilised
    integer :: status, bad
    restabilised = .false.
    ! (with every CFE closed, stabilising changes no penalty)
    if (eq%factor_valid .and. ((eq%factor_stabilised .eqv. cs%stabilised) .or. all(cs%c(1:cs%n)%closed))) then
      if (all(eq%factor_states .eqv. cs%c(1:cs%n)%closed)) return
    end if
    call assemble_stiffness(m, cs, body, u, sys, eq%kmax, eq%counts)
    call sys_factor(sys, status, bad)
    if (status == factor_singular .and. .not. eq%stabilisation_used .and. any(.not. cs%c(1:cs%n)%closed)) then
      cs%stabilised = .true.
      eq%stabilisation_used = .true.
      restabilised = .true.
      call tell_note(obs, 'singular stiffness with open contact: stabilising the open contact elements ' // &
                          'until the status settles')
      call assemble_stiffness(m, cs, body, u, sys, eq%kmax, eq%counts)
      call sys_factor(sys, status, bad)
    end if
    if (status == factor_singular) call singular(m, cs, dm, bad)
    if (status == factor_fallback) then
      call tell_note(obs, sys%note)
      call warn(sys%note)
    end if
    if (.not. eq%described) then
      call tell_solver_ready(obs, is, sys_describe(sys))
      eq%described = .true.
    end if
    eq%factor_states = cs%c(1:cs%n)%closed
    eq%factor_stabilised = cs%stabilised
    eq%factor_valid = .true.
    eq%factorisations = eq%factorisations + 1
  end subroutine factor_if_needed

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
    if (bad > 0 .and. bad <= dm%neq) call fatal('singular stiffness at node ' // &
      itoa(m%node_id(dm%node_of_eq(bad))) // ', dof ' // itoa(dm%dof_of_eq(bad)) // &
      ' (missing boundary condition?)' // hint)
    call fatal('singular stiffness (missing boundary condition?)' // hint)
  end subroutine singular
end module equilibrium
