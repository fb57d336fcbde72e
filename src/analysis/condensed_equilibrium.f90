!> The condensed path of the equilibrium iteration (a linear_path_t of
!> equilibrium_loop): the contact equations condensed out of one
!> factorisation of the bodies (condensed_contact), each status solved
!> on the contact equations only, the other equations recovered once the
!> status has settled. Its observable behaviour is the full path's
!> (module equilibrium): the same switching rule, the same stabilisation
!> of a body held only by open contact, the same events, reactions and
!> contact results, and the convergence judged on the recovered solution
!> by the same test (a correction with the same matrix follows while the
!> out-of-balance is above the tolerance).
!> Work per status iteration is O(m + CFEs): nothing here touches all the
!> nodes between the increment's start and the recovery.
module condensed_equilibrium
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  use model, only: model_t
  use contact, only: contact_set_t, contact_forces, status_codes
  use assembly, only: body_t, body_forces, free_residual
  use dof_numbering, only: dofmap_t, expand_dependent, reduce_dependent
  use linear_solver, only: linear_system_t, sys_analyse, factor_singular
  use condensed_contact, only: condensed_factor_k0, condensed_status, condensed_begin, condensed_solve, &
                               condensed_recover, condensed_correct, contact_part_forces, add_body_forces, &
                               condensed_energy, direct_multipliers, condensed_multipliers
  use equilibrium_common, only: equilibrium_t, relative_residual, check_finite, describe, singular, &
                                stabilise_open, set_aside_or_stop
  use iteration_state, only: iteration_t, linear_path_t
  use analysis_events, only: observer_ref_t, tell_note, wall_time
  implicit none
  private
  public :: condensed_path_t

  !> The condensed path's state in an increment. Exact enforcement solves
  !> the multipliers directly per status (no augmentation: augmented
  !> false) unless friction needs the augmented Lagrangian, or the active
  !> rows are dependent.
  type, extends(linear_path_t) :: condensed_path_t
    real(dp), allocatable :: fold(:)    ! the CFE forces on the contact equations before the switch
    logical :: whole = .false.          ! u holds every equation's solution (recovered)
    integer :: nsolves = 0              ! direct multiplier solves of the increment
  contains
    procedure :: begin => condensed_begin_increment
    procedure :: factor => condensed_factor
    procedure :: solve => condensed_solve_status
    procedure :: solution_energy => condensed_solution_energy
    procedure :: residual => condensed_residual
    procedure :: status_changed => condensed_status_changed
    procedure :: restart => condensed_restart
    procedure :: converged => condensed_converged
  end type condensed_path_t

contains

  !> Purpose: the start of the increment: the bodies' factor (once per
  !> numbering), the free equations from the last converged solution, the
  !> condensed right-hand side; whether the multipliers are solved directly.
  subroutine condensed_begin_increment(path, st)
    class(condensed_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    call k0_if_needed(st%eq, st%m, st%is, st%body, st%cs, st%dm, st%sys, st%obs)
    allocate(path%fold(st%eq%cd%m))
    call start_from_last(st%eq, st%m, st%body, st%dm, st%sys, st%fext, st%u)
    path%whole = .false.
    path%augmented = .not. direct_multipliers(st%cs)
    path%nsolves = 0
  end subroutine condensed_begin_increment

  !> Purpose: the condensed matrix of the status factored unless the one
  !> in hand is for it; nothing to factor for a correction of the whole
  !> solution (the same matrix).
  subroutine condensed_factor(path, st)
    class(condensed_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    st%usable = .true.
    st%restabilised = .false.
    if (path%whole) return
    call condensed_factor_if_needed(st%eq, st%m, st%body, st%cs, st%dm, st%obs, st%usable)
  end subroutine condensed_factor

  !> Purpose: the status solved on the contact equations (with its
  !> multipliers where they are solved directly), or, once the whole
  !> solution is recovered but not yet in balance, a correction with the
  !> same matrix. A displacement that is not finite stops the run.
  subroutine condensed_solve_status(path, st)
    class(condensed_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    integer :: nactive
    logical :: finite, solved
    st%c_max = 0.0_dp
    if (path%whole) then
      call correct(st%eq, st%m, st%dm, st%sys, st%fext, st%rf, st%u)
      call check_finite(st%m, st%is, st%inc, st%u)
      return
    end if
    call condensed_solve(st%eq%cd, st%m, st%cs, st%dm, st%u, finite, st%eq%counts%coupling)
    if (.not. finite) call check_finite(st%m, st%is, st%inc, st%u)
    if (path%augmented) return
    call condensed_multipliers(st%eq%cd, st%m, st%cs, st%dm, st%u, nactive, solved)
    if (nactive > 0) path%nsolves = path%nsolves + 1
    ! dependent active rows: the augmented updates instead
    if (.not. solved) path%augmented = .true.
    if (.not. all(ieee_is_finite(st%eq%cd%x2))) call check_finite(st%m, st%is, st%inc, st%u)
  end subroutine condensed_solve_status

  !> Purpose: the CFE forces on the contact equations before the switch,
  !> and the bodies' part of the potential energy of the solution.
  subroutine condensed_solution_energy(path, st)
    class(condensed_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    call contact_part_forces(st%eq%cd, st%m, st%cs, st%dm, st%u, path%fold, st%eq%counts%coupling)
    st%energy = condensed_energy(st%eq%cd, st%dm, st%cs, st%u)
  end subroutine condensed_solution_energy

  !> Purpose: the out-of-balance after the switch: of the change of the
  !> CFE forces where a status changed (the next solve starts from the
  !> increment's start), of the recovered solution where none did.
  subroutine condensed_residual(path, st)
    class(condensed_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    if (st%nchanged > 0) then
      if (path%whole) st%u = st%eq%cd%u0
      path%whole = .false.
      st%eq%residual = change_residual(st%eq, st%m, st%cs, st%dm, st%u, path%fold, st%fext_norm)
    else
      call settled_residual(st%eq, st%m, st%is, st%inc, st%body, st%cs, st%dm, st%sys, st%fext, st%u, st%rf, &
                            path%whole, st%scale)
    end if
  end subroutine condensed_residual

  !> Purpose: a status changed outside the switch: nothing to do, the
  !> next solve makes its forces.
  subroutine condensed_status_changed(path, st)
    class(condensed_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
  end subroutine condensed_status_changed

  !> Purpose: a new status search starts from the increment's start.
  subroutine condensed_restart(path, st)
    class(condensed_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    st%u = st%eq%cd%u0
    path%whole = .false.
  end subroutine condensed_restart

  !> Purpose: the increment converged: the direct solves said, the
  !> solution and the bodies' forces kept for the next increment's start.
  subroutine condensed_converged(path, st)
    class(condensed_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    character(len=12) :: buf
    if (path%nsolves > 0) then
      write(buf, '(i0)') path%nsolves
      call tell_note(st%obs, 'exact contact: ' // trim(buf) // ' direct multiplier solves in the increment')
    end if
    st%eq%u_last = st%u
    st%eq%fbody_last = st%eq%fbody
  end subroutine condensed_converged

  !> The start of the increment: the free equations from the last
  !> converged solution, the bodies' internal forces there (updated where
  !> prescribed values moved), the condensed right-hand side.
  subroutine start_from_last(eq, m, body, dm, sys, fext, u)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    type(body_t), intent(in) :: body
    type(dofmap_t), intent(in) :: dm
    type(linear_system_t), intent(inout) :: sys
    real(dp), intent(in) :: fext(:, :)
    real(dp), intent(inout) :: u(:, :)
    real(dp), allocatable :: fbody(:, :)
    if (allocated(eq%u_last)) where (dm%eq > 0) u = eq%u_last
    call expand_dependent(dm, u)
    if (allocated(eq%u_last)) then
      fbody = eq%fbody_last
      call add_body_forces(m, body, u - eq%u_last, fbody)
    else
      allocate(fbody(2, m%nn))
      call body_forces(m, body, u, fbody)
    end if
    call condensed_begin(eq%cd, m, dm, sys, fext, u, fbody)
  end subroutine start_from_last

  !> The status has settled: the other equations (unless u already holds
  !> them), then forces, reactions and the out-of-balance as the full
  !> iteration has them.
  subroutine settled_residual(eq, m, is, inc, body, cs, dm, sys, fext, u, rf, whole, scale)
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
    logical, intent(inout) :: whole
    real(dp), intent(out) :: scale
    real(dp) :: t0
    t0 = wall_time()
    if (.not. whole) then
      call condensed_recover(eq%cd, dm, sys, u)
      call check_finite(m, is, inc, u)
    end if
    whole = .true.
    if (.not. allocated(eq%fbody)) allocate(eq%fbody(2, m%nn))
    call body_forces(m, body, u, eq%fbody)
    rf = eq%fbody
    call contact_forces(m, cs, u, rf, eq%counts%coupling)
    rf = rf - fext
    call reduce_dependent(dm, rf)
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
    call expand_dependent(dm, u)
    eq%timing%recovery = eq%timing%recovery + (wall_time() - t0)
  end subroutine correct

  !> The out-of-balance after status changes, before the other equations
  !> are recovered: the change of the CFE forces (which lives on the
  !> contact equations; every other force is in balance by construction)
  !> relative to the loads, the contact forces, the stiffness times the
  !> displacements known so far, and the converged history. The full
  !> iteration's scale also has the reactions, which need the other
  !> equations: where they dominate, this value is the larger.
  real(dp) function change_residual(eq, m, cs, dm, u, fold, fext_norm) result(r)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(inout) :: cs
    type(dofmap_t), intent(in) :: dm
    real(dp), intent(in) :: u(:, :), fold(:), fext_norm
    real(dp) :: fnew(eq%cd%m), ref, umax
    integer :: p, e
    call contact_part_forces(eq%cd, m, cs, dm, u, fnew, eq%counts%coupling)
    umax = eq%cd%umax_rest
    do p = 1, eq%cd%m
      e = eq%cd%eq_at(p)
      umax = max(umax, abs(u(dm%dof_of_eq(e), dm%node_of_eq(e))))
    end do
    ref = max(fext_norm, sum(abs(cs%c(1:cs%n)%force)), 1.0e-6_dp * eq%kmax * umax, tiny(1.0_dp))
    r = norm2(fnew - fold) / max(ref, eq%force_history)
  end function change_residual

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
  !> current contact status; stabilises open contact as the full
  !> iteration does when it is singular with open CFEs; usable false
  !> where it is singular after a pivot of the search with the
  !> stabilisation used (as the full iteration's factor_if_needed).
  subroutine condensed_factor_if_needed(eq, m, body, cs, dm, obs, usable)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    type(body_t), intent(in) :: body
    type(contact_set_t), intent(inout) :: cs
    type(dofmap_t), intent(in) :: dm
    type(observer_ref_t), intent(in) :: obs(:)
    logical, intent(out) :: usable
    integer :: status, bad
    usable = .true.
    if (eq%factor_valid .and. ((eq%factor_stabilised .eqv. cs%stabilised) .or. all(cs%c(1:cs%n)%closed))) then
      if (all(eq%factor_states == status_codes(cs))) return
    end if
    call dense_status(eq, m, cs, dm, body, status, bad)
    if (status == factor_singular) then
      if (stabilise_open(eq, cs, obs)) call dense_status(eq, m, cs, dm, body, status, bad)
    end if
    if (status == factor_singular) then
      call set_aside_or_stop(eq, m, cs, dm, bad, usable)
      return
    end if
    eq%kmax = eq%cd%kmax
    eq%factor_states = status_codes(cs)
    eq%factor_stabilised = cs%stabilised
    eq%factor_valid = .true.
  end subroutine condensed_factor_if_needed

  !> One dense factorisation of the condensed matrix (counted).
  subroutine dense_status(eq, m, cs, dm, body, status, bad)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    type(dofmap_t), intent(in) :: dm
    type(body_t), intent(in) :: body
    integer, intent(out) :: status, bad
    call condensed_status(eq%cd, m, cs, dm, body%kmax, eq%counts, status, bad)
    eq%condensed_factorisations = eq%condensed_factorisations + 1
    eq%timing%condensed_factorisations = eq%timing%condensed_factorisations + 1
  end subroutine dense_status
end module condensed_equilibrium
