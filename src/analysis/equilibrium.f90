!> The equilibrium iteration of one increment: Newton passes on the
!> piecewise-linear system, each solving K du = f_ext - f_int(u) with the
!> current contact status, followed by the contact layer's switching rule,
!> until no status changes and the out-of-balance force is below the
!> tolerance (the loop: equilibrium_loop). This module is its entry
!> (solve_increment: the problem of the increment made the iteration's
!> state, the path chosen) and the full path: the whole stiffness
!> assembled and factored for every status (kept while the status is the
!> one it was made for), and in a nonlinear step Newton's tangent at u in
!> every iteration. Where the equations were numbered for the condensed
!> contact solve the path is condensed_equilibrium's (its Newton path in
!> a nonlinear step).
module equilibrium
  use kinds, only: dp
  use model, only: model_t
  use contact, only: contact_set_t, contact_forces
  use assembly, only: body_t, assemble_stiffness, free_residual, body_predictor_forces, nonlinear_body_forces
  use dof_numbering, only: dofmap_t, expand_dependent, reduce_dependent
  use constraints, only: mpc_t
  use linear_solver, only: linear_system_t, sys_factor, sys_solve, sys_analyse, factor_singular, factor_fallback
  use equilibrium_common, only: equilibrium_t, begin_equilibrium, internal_forces, relative_residual, check_finite, &
                                describe, stabilise_open, set_aside_or_stop, factor_fits, factor_made
  use iteration_state, only: iteration_t, linear_path_t
  use equilibrium_loop, only: iterate
  use condensed_equilibrium, only: condensed_path_t, newton_condensed_path_t
  use newton_control, only: converged_body_forces, converged_forces_at
  use contact_repairing, only: renumber_couplings, note_numbering, numbering_fits
  use analysis_events, only: observer_ref_t, run_timing_t, tell_note, wall_time
  use messages, only: warn
  implicit none
  private
  public :: equilibrium_t, begin_equilibrium, solve_increment, renumber_couplings, note_numbering, numbering_fits

  !> The full path: the bodies' and CFEs' internal forces f_int of the
  !> current displacements and status.
  type, extends(linear_path_t) :: full_path_t
    real(dp), allocatable :: fint(:, :)
    !> A nonlinear step: the bodies' part of fint, when fbody_at_u (it is
    !> that of the current u: the forces of a new status need only the
    !> couplings' again).
    real(dp), allocatable :: fbody(:, :)
    logical :: fbody_at_u = .false.
  contains
    procedure :: begin => full_begin
    procedure :: factor => full_factor
    procedure :: solve => full_solve
    procedure :: solution_energy => full_energy
    procedure :: residual => full_residual
    procedure :: status_changed => full_forces
    procedure :: restart => full_forces
    procedure :: converged => full_converged
  end type full_path_t

contains

  !> Purpose: equilibrium at the prescribed values and loads already in u
  !> and fext (the dependent dofs of constraints are set from them here).
  !> On return u holds the solution, rf = T^T (f_int - f_ext) (the
  !> reactions at prescribed dofs; zero at dependent dofs), ok whether it
  !> converged and iters the iterations used (equilibrium_loop's iterate).
  !> u_from, in a nonlinear step, is the converged state the increment
  !> starts from (u has its free dofs and the new prescribed values): the
  !> first iteration is linearised about it. presc and mpc, in a
  !> nonlinear step under NLGEOM with contact, ask for the contact to be
  !> searched again after every displacement update (equilibrium_loop's
  !> search_again); they are the step's prescribed dofs and the
  !> constraints that a renumbering of dm and sys needs.
  subroutine solve_increment(eq, m, is, inc, body, cs, dm, sys, fext, u, rf, obs, ok, iters, u_from, presc, mpc)
    type(equilibrium_t), intent(inout), target :: eq
    type(model_t), intent(in), target :: m
    integer, intent(in) :: is, inc
    type(body_t), intent(inout), target :: body
    type(contact_set_t), intent(inout), target :: cs
    type(dofmap_t), intent(inout), target :: dm
    type(linear_system_t), intent(inout), target :: sys
    real(dp), intent(in), target :: fext(:, :)
    real(dp), intent(inout), target :: u(:, :)
    real(dp), intent(out), target :: rf(:, :)
    type(observer_ref_t), intent(in), target :: obs(:)
    logical, intent(out) :: ok
    integer, intent(out) :: iters
    real(dp), intent(in), optional, target :: u_from(:, :)
    logical, intent(in), optional, target :: presc(:, :)
    type(mpc_t), intent(in), optional, target :: mpc
    type(iteration_t) :: st
    type(full_path_t) :: full
    type(condensed_path_t) :: condensed
    type(newton_condensed_path_t) :: newton_condensed
    real(dp) :: t0, parts
    t0 = wall_time()
    parts = timed_parts(eq%timing)
    st = iteration_t(eq=eq, m=m, is=is, inc=inc, body=body, cs=cs, dm=dm, sys=sys, fext=fext, u=u, rf=rf, obs=obs)
    if (present(u_from)) st%u_from => u_from
    if (present(presc)) st%presc => presc
    if (present(mpc)) st%mpc => mpc
    if (eq%cd%active) then
      if (body%nonlinear) then
        call iterate(newton_condensed, st, ok, iters)
      else
        call iterate(condensed, st, ok, iters)
      end if
      eq%timing%condensed = eq%timing%condensed + (wall_time() - t0) - (timed_parts(eq%timing) - parts)
    else
      call iterate(full, st, ok, iters)
      eq%timing%solve = eq%timing%solve + (wall_time() - t0) - (timed_parts(eq%timing) - parts)
    end if
  end subroutine solve_increment

  !> The parts timed inside an iteration (the rest is the iteration's own).
  pure real(dp) function timed_parts(t)
    type(run_timing_t), intent(in) :: t
    timed_parts = t%assembly + t%analyse + t%factor + t%recovery
  end function timed_parts

  !> Purpose: the start of the increment on the full path: f_int at u, or
  !> in a Newton increment with a predictor f_int linearised about the
  !> converged state (body_predictor_forces).
  subroutine full_begin(path, st)
    class(full_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    allocate(path%fint(2, st%m%nn), path%fbody(2, st%m%nn))
    path%fbody_at_u = .false.
    if (st%predict) then
      if (converged_forces_at(st%eq%newton, st%u_from)) then
        call body_predictor_forces(st%m, st%body, st%u_from, st%u - st%u_from, path%fint, st%eq%counts, &
                                   f0=st%eq%newton%fconv)
      else
        call body_predictor_forces(st%m, st%body, st%u_from, st%u - st%u_from, path%fint, st%eq%counts)
      end if
      call contact_forces(st%m, st%cs, st%u, path%fint, st%eq%counts%coupling)
      st%body%bad_elem = 0
    else
      call path_forces(path, st)
    end if
  end subroutine full_begin

  !> Purpose: f_int at u (internal_forces); in a nonlinear step its
  !> bodies' part kept (path%fbody), and where it is that of u already,
  !> only the couplings' forces made again. energy, if present, returns
  !> the bodies' strain energy measure of internal_forces.
  subroutine path_forces(path, st, energy)
    class(full_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    real(dp), intent(out), optional :: energy
    if (.not. st%body%nonlinear) then
      call internal_forces(st%m, st%body, st%cs, st%u, path%fint, st%eq%counts, energy)
      return
    end if
    if (.not. path%fbody_at_u) call nonlinear_body_forces(st%m, st%body, st%u, path%fbody, st%eq%counts)
    path%fbody_at_u = .true.
    if (present(energy)) energy = 0.5_dp * sum(st%u * path%fbody)
    path%fint = path%fbody
    call contact_forces(st%m, st%cs, st%u, path%fint, st%eq%counts%coupling)
  end subroutine path_forces

  !> Purpose: the stiffness of the status factored unless the factor in
  !> hand is for it; in a Newton increment's first iteration the tangent
  !> is that of the converged state (u_from with a predictor, else u:
  !> assemble_stiffness's converged).
  subroutine full_factor(path, st)
    class(full_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    if (st%predict .and. st%it == 1) then
      call factor_if_needed(st, st%u_from, .true.)
    else
      call factor_if_needed(st, st%u, st%body%nonlinear .and. st%it == 1 .and. associated(st%u_from))
    end if
  end subroutine full_factor

  !> Purpose: K du = T^T (f_ext - f_int), u += T du; c_max the largest
  !> correction. A linear step stops on a displacement that is not finite
  !> (a nonlinear one gives the increment up: equilibrium_loop).
  subroutine full_solve(path, st)
    class(full_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    integer :: a, d
    call free_residual(st%dm, st%fext, path%fint, st%eq%rhs)
    call sys_solve(st%sys, st%eq%rhs)
    st%c_max = 0.0_dp
    do a = 1, st%m%nn
      do d = 1, 2
        if (st%dm%eq(d, a) > 0) then
          st%u(d, a) = st%u(d, a) + st%eq%rhs(st%dm%eq(d, a))
          st%c_max = max(st%c_max, abs(st%eq%rhs(st%dm%eq(d, a))))
        end if
      end do
    end do
    call expand_dependent(st%dm, st%u)
    path%fbody_at_u = .false.
    if (.not. st%body%nonlinear) call check_finite(st%m, st%is, st%inc, st%u)
  end subroutine full_solve

  !> Purpose: f_int of the solution and the bodies' part of its potential
  !> energy: the strain energy less the work of the loads.
  subroutine full_energy(path, st)
    class(full_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    real(dp) :: energy
    ! (u moved since the solve: the search and the rigid bodies' turn follow it)
    path%fbody_at_u = .false.
    call path_forces(path, st, energy)
    st%energy = energy - sum(st%fext * st%u)
  end subroutine full_energy

  !> Purpose: the out-of-balance of the switched status: f_int again where
  !> a status changed, rf = T^T (f_int - f_ext) and its relative norm.
  subroutine full_residual(path, st)
    class(full_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    if (st%nchanged > 0) call path_forces(path, st)
    st%rf = path%fint - st%fext
    call reduce_dependent(st%dm, st%rf)
    st%eq%residual = relative_residual(st%dm, st%cs, st%fext, st%u, st%rf, st%eq%kmax, st%eq%force_history, st%scale)
  end subroutine full_residual

  !> Purpose: f_int of a new status at the same u (a pivot taken back, the
  !> open contact stabilised, a new status search).
  subroutine full_forces(path, st)
    class(full_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    call path_forces(path, st)
  end subroutine full_forces

  !> Purpose: the next increment starts from u; in a nonlinear step the
  !> bodies' forces of its last iteration are kept for its predictor.
  subroutine full_converged(path, st)
    class(full_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    if (st%body%nonlinear .and. path%fbody_at_u) call converged_body_forces(st%eq%newton, st%u, path%fbody)
  end subroutine full_converged

  !> Assembles and factors the stiffness unless the factor in hand was made
  !> for the current contact status. A singular stiffness with open CFEs
  !> (a body held only by open contact) is factored again with the
  !> stabilised open penalty (contact_set_t); st%restabilised says so.
  !> Where the stabilisation was used already and the status comes from a
  !> pivot of the search, st%usable is false (the pivot is to be taken
  !> back); a singular tangent of a nonlinear body gives the increment up
  !> (eq%newton%singular); otherwise a singular stiffness stops the run.
  !> Arguments: u the displacements to assemble at; at_converged whether
  !> they are the converged state (assemble_stiffness).
  subroutine factor_if_needed(st, u, at_converged)
    type(iteration_t), intent(inout) :: st
    real(dp), intent(in) :: u(:, :)
    logical, intent(in) :: at_converged
    integer :: status, bad
    st%restabilised = .false.
    st%usable = .true.
    associate(eq => st%eq, cs => st%cs)
      if (factor_fits(eq, cs)) return
      call assemble_and_factor(st, u, status, bad, at_converged)
      if (status == factor_singular) then
        st%restabilised = stabilise_open(eq, cs, st%obs)
        if (st%restabilised) call assemble_and_factor(st, u, status, bad, at_converged)
      end if
      if (status == factor_singular .and. st%body%nonlinear .and. .not. eq%search%pivoted) then
        ! a singular tangent of a nonlinear body (a limit load, a buckling
        ! state, or a missing support): the increment fails and is cut back
        st%usable = .false.
        eq%factor_valid = .false.
        eq%bad = bad
        eq%newton%singular = .true.
        return
      end if
      if (status == factor_singular) then
        call set_aside_or_stop(eq, st%m, cs, st%dm, bad, st%usable)
        return
      end if
      if (status == factor_fallback) then
        call tell_note(st%obs, st%sys%note)
        call warn(st%sys%note)
      end if
      call describe(eq, st%is, cs, st%sys, st%obs)
      call factor_made(eq, cs)
    end associate
  end subroutine factor_if_needed

  !> The stiffness of the current status, assembled and factored (timed,
  !> counted).
  subroutine assemble_and_factor(st, u, status, bad, converged)
    type(iteration_t), intent(inout) :: st
    real(dp), intent(in) :: u(:, :)
    integer, intent(out) :: status, bad
    logical, intent(in) :: converged          ! u is the converged state (assemble_stiffness)
    real(dp) :: t0, t1
    associate(eq => st%eq)
      t0 = wall_time()
      call assemble_stiffness(st%m, st%cs, st%body, u, st%sys, eq%kmax, eq%counts, st%dm, converged)
      t1 = wall_time()
      call sys_analyse(st%sys)
      eq%timing%assembly = eq%timing%assembly + (t1 - t0)
      eq%timing%analyse = eq%timing%analyse + (wall_time() - t1)
      t1 = wall_time()
      call sys_factor(st%sys, status, bad)
      eq%timing%factor = eq%timing%factor + (wall_time() - t1)
      eq%factorisations = eq%factorisations + 1
      eq%timing%numeric_factorisations = eq%timing%numeric_factorisations + 1
    end associate
  end subroutine assemble_and_factor
end module equilibrium
