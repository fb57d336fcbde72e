!> The equilibrium iteration of one increment: Newton passes on the
!> piecewise-linear system, each solving K du = f_ext - f_int(u) with the
!> current contact status, followed by the contact layer's switching rule,
!> until no status changes and the out-of-balance force is below the
!> tolerance. The stiffness depends only on the contact status, so its
!> factor is kept while the status is the one it was made for.
!> Two ways to solve the same iteration (condensed_contact says which
!> numbering is in use): the full one factors the whole stiffness for
!> every status; the condensed one factors the bodies once and iterates
!> on the contact equations only, recovering the others once the status
!> has settled. Both switch by the same rule, stabilise a body held only
!> by open contact the same way, and tell the observers the same events.
module equilibrium
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  use strings, only: itoa
  use model
  use contact, only: contact_set_t, contact_forces, contact_switch
  use assembly, only: body_t, element_counts_t, assemble_stiffness, body_forces, free_residual
  use dof_numbering, only: dofmap_t
  use linear_solver, only: linear_system_t, sys_factor, sys_solve, sys_describe, sys_analyse, factor_singular, &
                           factor_fallback
  use condensed_contact, only: condensed_t, condensed_factor_k0, condensed_status, condensed_begin, &
                               condensed_solve, condensed_recover, condensed_correct
  use analysis_events, only: observer_ref_t, iteration_info_t, solver_info_t, run_timing_t, tell_iteration, &
                             tell_note, tell_solver_ready, wall_time
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
    !> The condensed contact solve (active when the equations were
    !> numbered for it) and whether its factor of the bodies is current.
    type(condensed_t) :: cd
    logical :: k0_valid = .false.
    ! counters of the step
    integer :: factorisations = 0, iterations = 0, condensed_factorisations = 0
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
    real(dp), allocatable :: rhs(:)
    !> The last converged displacements: the condensed solve starts an
    !> increment from them (the free equations), so that its solves are
    !> of the increment's change and their round-off relative to it.
    real(dp), allocatable :: u_last(:, :)
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
    integer, intent(in) :: is, inc
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
    real(dp) :: t0, parts
    t0 = wall_time()
    parts = timed_parts(eq%timing)
    if (eq%cd%active) then
      call solve_condensed(eq, m, is, inc, body, cs, dm, sys, fext, u, rf, obs, ok, iters)
      eq%timing%condensed = eq%timing%condensed + (wall_time() - t0) - (timed_parts(eq%timing) - parts)
    else
      call solve_full(eq, m, is, inc, body, cs, dm, sys, fext, u, rf, obs, ok, iters)
      eq%timing%solve = eq%timing%solve + (wall_time() - t0) - (timed_parts(eq%timing) - parts)
    end if
  end subroutine solve_increment

  !> The parts timed inside an iteration (the rest is the iteration's own).
  pure real(dp) function timed_parts(t)
    type(run_timing_t), intent(in) :: t
    timed_parts = t%assembly + t%analyse + t%factor + t%recovery
  end function timed_parts

  !> solve_increment by factoring the whole stiffness of every status.
  subroutine solve_full(eq, m, is, inc, body, cs, dm, sys, fext, u, rf, obs, ok, iters)
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
      end do
      call check_finite(m, is, inc, u)
      call internal_forces(m, body, cs, u, fint, eq%counts)
      call contact_switch(m, cs, nchanged, eq%changed)
      ! the residual of the new status
      if (nchanged > 0) call internal_forces(m, body, cs, u, fint, eq%counts)
      rf = fint - fext
      eq%residual = relative_residual(dm, cs, fext, u, rf, eq%kmax, eq%force_history, scale)
      eq%iterations = eq%iterations + 1
      call report_iteration(eq, cs, obs, it, nchanged)
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
  end subroutine solve_full

  !> Purpose: solve_increment by the condensed contact solve: the status
  !> iterations solve the contact equations only (condensed_contact); once
  !> the status has settled the others are recovered, the forces and
  !> reactions computed as solve_full computes them, and the out-of-balance
  !> judged the same way (a correction follows if it is not yet below the
  !> tolerance).
  subroutine solve_condensed(eq, m, is, inc, body, cs, dm, sys, fext, u, rf, obs, ok, iters)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    integer, intent(in) :: is, inc
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
    real(dp), allocatable :: fold(:, :)
    integer :: it, nchanged
    logical :: whole                    ! u holds every equation's solution
    real(dp) :: scale
    allocate(fold(2, m%nn))
    ok = .false.
    cs%stabilised = .false.
    eq%stabilisation_used = .false.
    call k0_if_needed(eq, m, is, body, cs, dm, sys, obs)
    if (allocated(eq%u_last)) where (dm%eq > 0) u = eq%u_last
    call condensed_begin(eq%cd, m, body, dm, sys, fext, u)
    whole = .false.
    do it = 1, m%contact_max_iter
      if (whole) then
        ! settled but not yet in balance: a correction with the same matrix
        call correct(eq, m, dm, sys, fext, rf, u)
      else
        call condensed_factor_if_needed(eq, m, body, cs, dm, obs)
        call condensed_solve(eq%cd, m, cs, dm, u, eq%counts%coupling)
      end if
      call check_finite(m, is, inc, u)
      fold = 0.0_dp
      call contact_forces(m, cs, u, fold, eq%counts%coupling)
      call contact_switch(m, cs, nchanged, eq%changed)
      if (nchanged > 0) then
        whole = .false.
        eq%residual = change_residual(m, dm, cs, fext, u, fold, eq%kmax, eq%force_history, eq%counts)
      else
        call settled_residual(eq, m, body, cs, dm, sys, fext, u, rf, whole, scale)
      end if
      eq%iterations = eq%iterations + 1
      call report_iteration(eq, cs, obs, it, nchanged)
      if (nchanged == 0 .and. cs%stabilised) then
        ! settled while stabilised: on with the nominal open penalty
        cs%stabilised = .false.
        whole = .false.
        call tell_note(obs, 'contact status settled with the stabilised open penalty; ' // &
                            'iterating on with the nominal one')
        cycle
      end if
      if (nchanged == 0 .and. eq%residual < m%contact_tolerance) then
        ok = .true.
        iters = it
        eq%force_history = max(eq%force_history, scale)
        eq%u_last = u
        return
      end if
    end do
    iters = m%contact_max_iter
  end subroutine solve_condensed

  !> The status has settled: the other equations (unless u already holds
  !> them), then forces, reactions and the out-of-balance as solve_full
  !> has them.
  subroutine settled_residual(eq, m, body, cs, dm, sys, fext, u, rf, whole, scale)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    type(body_t), intent(in) :: body
    type(contact_set_t), intent(inout) :: cs
    type(dofmap_t), intent(in) :: dm
    type(linear_system_t), intent(inout) :: sys
    real(dp), intent(in) :: fext(:, :)
    real(dp), intent(inout) :: u(:, :)
    real(dp), intent(out) :: rf(:, :)
    logical, intent(inout) :: whole
    real(dp), intent(out) :: scale
    real(dp), allocatable :: fint(:, :)
    real(dp) :: t0
    t0 = wall_time()
    allocate(fint(2, m%nn))
    if (.not. whole) call condensed_recover(eq%cd, dm, sys, u)
    whole = .true.
    call internal_forces(m, body, cs, u, fint, eq%counts)
    rf = fint - fext
    eq%residual = relative_residual(dm, cs, fext, u, rf, eq%kmax, eq%force_history, scale)
    eq%timing%recovery = eq%timing%recovery + (wall_time() - t0)
  end subroutine settled_residual

  !> u += K^-1 (f_ext - f_int(u)) on the free equations, rf = f_int - f_ext
  !> of the u given.
  subroutine correct(eq, m, dm, sys, fext, rf, u)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    type(dofmap_t), intent(in) :: dm
    type(linear_system_t), intent(inout) :: sys
    real(dp), intent(in) :: fext(:, :), rf(:, :)
    real(dp), intent(inout) :: u(:, :)
    integer :: a, d
    real(dp) :: t0
    t0 = wall_time()
    call free_residual(dm, fext, rf + fext, eq%rhs)
    call condensed_correct(eq%cd, sys, eq%rhs)
    do a = 1, m%nn
      do d = 1, 2
        if (dm%eq(d, a) > 0) u(d, a) = u(d, a) + eq%rhs(dm%eq(d, a))
      end do
    end do
    eq%timing%recovery = eq%timing%recovery + (wall_time() - t0)
  end subroutine correct

  !> The out-of-balance after status changes, before the other equations
  !> are recovered: the change of the CFE forces on the free equations
  !> (every other force is in balance by construction), relative to the
  !> loads, the contact forces, the stiffness times the displacements known
  !> so far, and the converged history. solve_full's scale also has the
  !> reactions, which need the other equations: where they dominate, this
  !> value is the larger.
  real(dp) function change_residual(m, dm, cs, fext, u, fold, kmax, history, counts) result(r)
    type(model_t), intent(in) :: m
    type(dofmap_t), intent(in) :: dm
    type(contact_set_t), intent(inout) :: cs
    real(dp), intent(in) :: fext(:, :), u(:, :), fold(:, :), kmax, history
    type(element_counts_t), intent(inout) :: counts
    real(dp), allocatable :: fnew(:, :)
    real(dp) :: ref
    allocate(fnew(2, m%nn))
    fnew = 0.0_dp
    call contact_forces(m, cs, u, fnew, counts%coupling)
    ref = max(norm2(fext), sum(abs(cs%c(1:cs%n)%force)), 1.0e-6_dp * kmax * maxval(abs(u)), tiny(1.0_dp))
    r = norm2(pack(fnew - fold, dm%eq > 0)) / max(ref, history)
  end function change_residual

  !> Stops if a displacement is not a finite number.
  subroutine check_finite(m, is, inc, u)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is, inc
    real(dp), intent(in) :: u(:, :)
    integer :: a
    do a = 1, m%nn
      if (.not. all(ieee_is_finite(u(:, a)))) call fatal('step ' // itoa(is) // ', increment ' // &
        itoa(inc) // ': the displacement at node ' // itoa(m%node_id(a)) // ' is not a finite number ' // &
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
    call assemble_and_factor(eq, m, body, cs, u, sys, status, bad)
    if (status == factor_singular .and. .not. eq%stabilisation_used .and. any(.not. cs%c(1:cs%n)%closed)) then
      cs%stabilised = .true.
      eq%stabilisation_used = .true.
      restabilised = .true.
      call tell_note(obs, 'singular stiffness with open contact: stabilising the open contact elements ' // &
                          'until the status settles')
      call assemble_and_factor(eq, m, body, cs, u, sys, status, bad)
    end if
    if (status == factor_singular) call singular(m, cs, dm, bad)
    if (status == factor_fallback) then
      call tell_note(obs, sys%note)
      call warn(sys%note)
    end if
    call describe(eq, is, cs, sys, obs)
    eq%factor_states = cs%c(1:cs%n)%closed
    eq%factor_stabilised = cs%stabilised
    eq%factor_valid = .true.
  end subroutine factor_if_needed

  !> The stiffness of the current status, assembled and factored (timed,
  !> counted).
  subroutine assemble_and_factor(eq, m, body, cs, u, sys, status, bad)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    type(body_t), intent(in) :: body
    type(contact_set_t), intent(in) :: cs
    real(dp), intent(in) :: u(:, :)
    type(linear_system_t), intent(inout) :: sys
    integer, intent(out) :: status, bad
    real(dp) :: t0, t1
    t0 = wall_time()
    call assemble_stiffness(m, cs, body, u, sys, eq%kmax, eq%counts)
    t1 = wall_time()
    call sys_analyse(sys)
    eq%timing%assembly = eq%timing%assembly + (t1 - t0)
    eq%timing%analyse = eq%timing%analyse + (wall_time() - t1)
    t1 = wall_time()
    call sys_factor(sys, status, bad)
    eq%timing%factor = eq%timing%factor + (wall_time() - t1)
    eq%factorisations = eq%factorisations + 1
    eq%timing%numeric_factorisations = eq%timing%numeric_factorisations + 1
  end subroutine assemble_and_factor

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

  !> The bodies' factor of the condensed solve, once per numbering: a
  !> singular one cannot be mended by any contact status.
  subroutine k0_if_needed(eq, m, is, body, cs, dm, sys, obs)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    integer, intent(in) :: is
    type(body_t), intent(in) :: body
    type(contact_set_t), intent(in) :: cs
    type(dofmap_t), intent(in) :: dm
    type(linear_system_t), intent(inout) :: sys
    type(observer_ref_t), intent(in) :: obs(:)
    integer :: status, bad
    real(dp) :: t0
    if (eq%k0_valid) return
    t0 = wall_time()
    call sys_analyse(sys)
    eq%timing%analyse = eq%timing%analyse + (wall_time() - t0)
    t0 = wall_time()
    call condensed_factor_k0(eq%cd, m, cs, body, dm, sys, eq%counts, status, bad)
    eq%timing%factor = eq%timing%factor + (wall_time() - t0)
    eq%factorisations = eq%factorisations + 1
    eq%timing%numeric_factorisations = eq%timing%numeric_factorisations + 1
    if (status /= 0) call singular(m, cs, dm, bad)
    eq%k0_valid = .true.
    eq%factor_valid = .false.
    call describe(eq, is, cs, sys, obs)
  end subroutine k0_if_needed

  !> Factors the condensed matrix unless the one in hand was made for the
  !> current contact status; stabilises open contact as factor_if_needed
  !> does when it is singular with open CFEs.
  subroutine condensed_factor_if_needed(eq, m, body, cs, dm, obs)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    type(body_t), intent(in) :: body
    type(contact_set_t), intent(inout) :: cs
    type(dofmap_t), intent(in) :: dm
    type(observer_ref_t), intent(in) :: obs(:)
    integer :: status, bad
    if (eq%factor_valid .and. ((eq%factor_stabilised .eqv. cs%stabilised) .or. all(cs%c(1:cs%n)%closed))) then
      if (all(eq%factor_states .eqv. cs%c(1:cs%n)%closed)) return
    end if
    call dense_status(eq, m, cs, body, status, bad)
    if (status == factor_singular .and. .not. eq%stabilisation_used .and. any(.not. cs%c(1:cs%n)%closed)) then
      cs%stabilised = .true.
      eq%stabilisation_used = .true.
      call tell_note(obs, 'singular stiffness with open contact: stabilising the open contact elements ' // &
                          'until the status settles')
      call dense_status(eq, m, cs, body, status, bad)
    end if
    if (status == factor_singular) call singular(m, cs, dm, bad)
    eq%kmax = eq%cd%kmax
    eq%factor_states = cs%c(1:cs%n)%closed
    eq%factor_stabilised = cs%stabilised
    eq%factor_valid = .true.
  end subroutine condensed_factor_if_needed

  !> One dense factorisation of the condensed matrix (counted).
  subroutine dense_status(eq, m, cs, body, status, bad)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    type(body_t), intent(in) :: body
    integer, intent(out) :: status, bad
    call condensed_status(eq%cd, m, cs, body%kmax, eq%counts, status, bad)
    eq%condensed_factorisations = eq%condensed_factorisations + 1
    eq%timing%condensed_factorisations = eq%timing%condensed_factorisations + 1
  end subroutine dense_status

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
