!> The equilibrium iteration of one increment by the condensed contact
!> solve (condensed_contact): the bodies factored once per numbering, the
!> status iterations on the contact equations only, the other equations
!> recovered once the status has settled. Its observable behaviour is the
!> full iteration's (module equilibrium): the same switching rule, the
!> same stabilisation of a body held only by open contact, the same
!> events, reactions and contact results, and the convergence judged on
!> the recovered solution by the same test.
!> Work per status iteration is O(m + CFEs): nothing here touches all the
!> nodes between the increment's start and the recovery.
module condensed_equilibrium
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  use model, only: model_t
  use contact, only: contact_set_t, contact_forces, status_codes
  use contact_status, only: contact_switch, begin_status_search, contact_energy, augment_multipliers, max_augmentations
  use assembly, only: body_t, body_forces, free_residual
  use dof_numbering, only: dofmap_t, expand_dependent, reduce_dependent
  use linear_solver, only: linear_system_t, sys_analyse, factor_singular
  use condensed_contact, only: condensed_factor_k0, condensed_status, condensed_begin, condensed_solve, &
                               condensed_recover, condensed_correct, contact_part_forces, add_body_forces, &
                               condensed_energy, direct_multipliers, condensed_multipliers
  use equilibrium_common, only: equilibrium_t, relative_residual, check_finite, report_iteration, describe, singular, &
                                contact_force_scale, take_back, stabilise_open, set_aside_or_stop, next_stage
  use analysis_events, only: observer_ref_t, tell_note, wall_time
  implicit none
  private
  public :: solve_condensed

contains

  !> Purpose: equilibrium at the prescribed values and loads already in u
  !> and fext by the condensed contact solve (arguments as
  !> equilibrium's solve_increment). Each status iteration solves the
  !> contact equations for the current status and switches; once no
  !> status changes, the other equations are recovered, forces and
  !> reactions computed and the out-of-balance judged as the full
  !> iteration judges it (a correction with the same matrix follows if it
  !> is not yet below the tolerance).
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
    real(dp), allocatable :: fold(:)
    integer :: it, nchanged, naug, nactive, nsolves
    logical :: whole                    ! u holds every equation's solution
    logical :: finite, usable, direct, solved
    character(len=12) :: buf
    real(dp) :: scale, fext_norm, energy
    ok = .false.
    cs%stabilised = .false.
    eq%stabilisation_used = .false.
    call k0_if_needed(eq, m, is, body, cs, dm, sys, obs)
    allocate(fold(eq%cd%m))
    call begin(eq, m, body, dm, sys, fext, u)
    fext_norm = norm2(fext)
    call begin_status_search(eq%search)
    whole = .false.
    it = 0
    naug = 0
    ! exact enforcement by multipliers solved directly per status (no
    ! augmentation), unless friction needs the augmented Lagrangian
    direct = direct_multipliers(cs)
    nsolves = 0
    ! MAXIT counts the iterations of each status search
    do while (eq%search%iterations < m%contact_max_iter)
      it = it + 1
      if (whole) then
        ! settled but not yet in balance: a correction with the same matrix
        call correct(eq, m, dm, sys, fext, rf, u)
        call check_finite(m, is, inc, u)
      else
        call condensed_factor_if_needed(eq, m, body, cs, dm, obs, usable)
        if (.not. usable) then
          call take_back(eq, m, cs, dm, obs)
          cycle
        end if
        call condensed_solve(eq%cd, m, cs, dm, u, finite, eq%counts%coupling)
        if (.not. finite) call check_finite(m, is, inc, u)
        if (direct) then
          call condensed_multipliers(eq%cd, m, cs, dm, u, nactive, solved)
          if (nactive > 0) nsolves = nsolves + 1
          ! dependent active rows: the augmented updates instead
          if (.not. solved) direct = .false.
          if (.not. all(ieee_is_finite(eq%cd%x2))) call check_finite(m, is, inc, u)
        end if
      end if
      call contact_part_forces(eq%cd, m, cs, dm, u, fold, eq%counts%coupling)
      ! the potential energy of this status's solution, eqs. (1) and (9)
      energy = condensed_energy(eq%cd, dm, cs, u) + contact_energy(cs)
      call contact_switch(m, cs, eq%search, contact_force_scale(eq, cs, fext_norm), energy, nchanged, eq%changed)
      if (nchanged > 0) then
        if (whole) u = eq%cd%u0          ! the next solve starts from the increment's start
        whole = .false.
        eq%residual = change_residual(eq, m, cs, dm, u, fold, fext_norm)
      else
        call settled_residual(eq, m, is, inc, body, cs, dm, sys, fext, u, rf, whole, scale)
      end if
      eq%iterations = eq%iterations + 1
      call report_iteration(eq, cs, obs, it, nchanged)
      if (nchanged == 0 .and. cs%stabilised) then
        if (next_stage(eq, cs, contact_force_scale(eq, cs, fext_norm), obs)) then
          u = eq%cd%u0
          whole = .false.
          cycle
        end if
        ! settled while stabilised: a new search with the nominal open penalty
        cs%stabilised = .false.
        call begin_status_search(eq%search)
        u = eq%cd%u0
        whole = .false.
        call tell_note(obs, 'contact status settled with the stabilised open penalty; ' // &
                            'iterating on with the nominal one')
        cycle
      end if
      if (nchanged == 0 .and. eq%residual < m%contact_tolerance .and. naug < max_augmentations .and. &
          .not. direct) then
        ! exact enforcement: the multipliers updated, the search again
        if (augment_multipliers(cs, contact_force_scale(eq, cs, fext_norm))) then
          naug = naug + 1
          u = eq%cd%u0
          whole = .false.
          call begin_status_search(eq%search)
          cycle
        end if
      end if
      if (nchanged == 0 .and. eq%residual < m%contact_tolerance) then
        ok = .true.
        iters = it
        if (nsolves > 0) then
          write(buf, '(i0)') nsolves
          call tell_note(obs, 'exact contact: ' // trim(buf) // ' direct multiplier solves in the increment')
        end if
        eq%force_history = max(eq%force_history, scale)
        eq%u_last = u
        eq%fbody_last = eq%fbody
        return
      end if
    end do
    iters = it
  end subroutine solve_condensed

  !> The start of the increment: the free equations from the last
  !> converged solution, the bodies' internal forces there (updated where
  !> prescribed values moved), the condensed right-hand side.
  subroutine begin(eq, m, body, dm, sys, fext, u)
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
  end subroutine begin

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
