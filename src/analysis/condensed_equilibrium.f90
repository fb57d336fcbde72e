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
!> In a nonlinear step whose tangent is symmetric (condensed_contact's
!> symmetric_tangent) the Newton path (newton_condensed_path_t) does the
!> same on Newton's linearised problem: the tangent at the Newton iterate
!> factored once, the contact status searched on it by the condensed
!> system until it settles (inner iterations, no element routine called),
!> then the whole correction recovered, the contact searched again under
!> NLGEOM, and the true out-of-balance judged by Newton's tests.
module condensed_equilibrium
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  use contact, only: contact_forces, frictional_set
  use model, only: model_t
  use assembly, only: body_t, body_forces, free_residual, nonlinear_body_forces, body_predictor_forces
  use dof_numbering, only: dofmap_t, expand_dependent, reduce_dependent
  use linear_solver, only: linear_system_t, sys_analyse, factor_singular
  use condensed_contact, only: condensed_factor_k0, condensed_status, condensed_begin, condensed_solve, &
                               condensed_recover, condensed_correct, contact_part_forces, add_body_forces, &
                               condensed_energy, direct_multipliers, condensed_multipliers, condense_change, &
                               condensed_begin_lazy, s0_times, moving_elements, forward_rhs, condensed_refine, &
                               load_change, copy_field, take_equations, subtract_field, zero_field
  use contact_status, only: contact_energy
  use equilibrium_common, only: equilibrium_t, relative_residual, check_finite, describe, singular, stabilise_open, &
                                set_aside_or_stop, factor_fits, factor_made
  use iteration_state, only: iteration_t, linear_path_t, give_up_verdict => give_up
  use analysis_events, only: tell_note, wall_time
  use newton_control, only: newton_give_up, converged_body_forces, converged_forces_at, not_finite, &
                            not_condensable
  use contact_repairing, only: search_in_iteration, coupling_length
  implicit none
  private
  public :: condensed_path_t, newton_condensed_path_t, condensed_complete

  !> The condensed path's state in an increment. Exact enforcement solves
  !> the multipliers directly per status (no augmentation: augmented
  !> false) unless friction needs the augmented Lagrangian, or the active
  !> rows are dependent.
  type, extends(linear_path_t) :: condensed_path_t
    real(dp), allocatable :: fold(:)    ! the CFE forces on the contact equations before the switch
    logical :: whole = .false.          ! u holds every equation's solution (recovered)
    integer :: nsolves = 0              ! direct multiplier solves of the increment
    real(dp), allocatable :: frefined(:) ! the CFE forces at the refined solution (settle_refined)
  contains
    procedure :: begin => condensed_begin_increment
    procedure :: factor => condensed_factor
    procedure :: solve => condensed_solve_status
    procedure :: solution_energy => condensed_solution_energy
    procedure :: residual => condensed_residual
    procedure :: status_changed => condensed_status_changed
    procedure :: restart => condensed_restart
    procedure :: converged => condensed_converged
    procedure :: rejudged => condensed_rejudged
  end type condensed_path_t

  !> The condensed path of a Newton increment: the bodies' tangent at the
  !> linearisation point ubase (with the open CFEs) condensed as K0 is for
  !> a linear step; fbase the bodies' forces there (linearised about the
  !> converged state in a first iteration with a predictor); rebase: a
  !> tangent is due at ubase (at_converged: ubase's tangent is that of the
  !> converged state, assemble_stiffness's converged, taken at tangent_at).
  type, extends(condensed_path_t) :: newton_condensed_path_t
    real(dp), allocatable :: ubase(:, :), fbase(:, :), tangent_at(:, :)
    logical :: rebase = .true., at_converged = .false.
    real(dp) :: kbody = 0.0_dp          ! the tangent's largest element entry
  contains
    procedure :: begin => newton_begin_increment
    procedure :: factor => newton_factor
    procedure :: solve => newton_solve
    procedure :: residual => newton_residual
    procedure :: restart => newton_restart
    procedure :: converged => newton_converged_increment
  end type newton_condensed_path_t

contains

  !> Purpose: the start of the increment: the bodies' factor (once per
  !> numbering), the free equations from the last converged solution, the
  !> condensed right-hand side; whether the multipliers are solved directly.
  subroutine condensed_begin_increment(path, st)
    class(condensed_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    call k0_if_needed(st)
    allocate(path%fold(st%eq%cd%m))
    call start_from_last(st)
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
    call condensed_factor_if_needed(st, st%body%kmax)
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
      call correct(st)
      call check_finite(st%m, st%is, st%inc, st%u)
      return
    end if
    ! (a status whose energy the search does not read is decided on the
    ! unrefined low-rank solution: the one that settles is refined,
    ! settle_refined)
    call condensed_solve(st%eq%cd, st%m, st%cs, st%dm, st%u, finite, st%eq%counts%coupling, defer=energy_free(st))
    if (.not. finite) call check_finite(st%m, st%is, st%inc, st%u)
    if (path%augmented) return
    call condensed_multipliers(st%eq%cd, st%m, st%cs, st%dm, st%u, nactive, solved)
    if (nactive > 0) path%nsolves = path%nsolves + 1
    ! dependent active rows: the augmented updates instead
    if (.not. solved) path%augmented = .true.
    if (.not. all(ieee_is_finite(st%eq%cd%x2))) call check_finite(st%m, st%is, st%inc, st%u)
  end subroutine condensed_solve_status

  !> Purpose: the CFE forces on the contact equations before the switch,
  !> and the bodies' part of the potential energy of the solution. Not
  !> the energy of a frictional set paired at every increment
  !> (keep_pairing): Coulomb friction has no potential, the status search
  !> reads no energy of a frictional set (contact_switch's block pivots),
  !> and such a set stays frictional through the increment (a linear
  !> step pairs only at its start); the energy, an m x m product with S0,
  !> was a twelfth of a fretting increment.
  subroutine condensed_solution_energy(path, st)
    class(condensed_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    call contact_part_forces(st%eq%cd, st%m, st%cs, st%dm, st%u, path%fold, st%eq%counts%coupling)
    if (energy_free(st)) then
      st%energy = 0.0_dp
      return
    end if
    st%energy = condensed_energy(st%eq%cd, st%dm, st%cs, st%u)
  end subroutine condensed_solution_energy

  !> Purpose: does the status search of this increment read no energy of
  !> the bodies' part (a frictional set paired at every increment of a
  !> linear step: condensed_solution_energy)? Its statuses may then be
  !> decided on unrefined low-rank solutions (settle_refined).
  logical function energy_free(st)
    type(iteration_t), intent(in) :: st
    energy_free = st%eq%cd%keep_pairing .and. .not. st%body%nonlinear .and. frictional_set(st%cs)
  end function energy_free

  !> Purpose: the out-of-balance after the switch: of the change of the
  !> CFE forces where a status changed (the next solve starts from the
  !> increment's start), of the recovered solution where none did.
  subroutine condensed_residual(path, st)
    class(condensed_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    if (st%nchanged == 0 .and. .not. path%whole .and. .not. st%eq%cd%refined) then
      call settle_refined(path, st)
      return
    end if
    if (st%nchanged > 0) then
      if (path%whole) st%u = st%eq%cd%u0
      path%whole = .false.
      st%eq%residual = change_residual(st, path%fold)
    else
      call settled_residual(st, path%whole)
    end if
  end subroutine condensed_residual

  !> Purpose: the status settled on an unrefined low-rank solution
  !> (condensed_solve's defer): the solution refined, the CFEs evaluated
  !> there and the statuses judged again (one more pivot of the search);
  !> a status the refinement changes (a coupling within 1e-12 of its
  !> limit) goes on as a change, with the out-of-balance of the change;
  !> otherwise the search is as the first pivot left it and the settled
  !> status's out-of-balance is made (settled_residual, from these CFE
  !> forces).
  subroutine settle_refined(path, st)
    class(condensed_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    real(dp) :: t0
    call condensed_refine(st%eq%cd, st%dm, st%u)
    t0 = wall_time()
    if (allocated(path%frefined)) then
      if (size(path%frefined) /= st%eq%cd%m) deallocate(path%frefined)
    end if
    if (.not. allocated(path%frefined)) allocate(path%frefined(st%eq%cd%m))
    call contact_at_u(st, path%frefined)
    st%eq%timing%recovery = st%eq%timing%recovery + (wall_time() - t0)
    st%energy = contact_energy(st%cs)
    ! (the statuses judged again by the loop: equilibrium_loop's rejudge)
    st%rejudge = .true.
  end subroutine settle_refined

  !> Purpose: the loop judged the statuses again on the refined solution
  !> (settle_refined): the out-of-balance of the change where one
  !> changed, else of the settled status, from the CFE forces there.
  subroutine condensed_rejudged(path, st)
    class(condensed_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    if (st%nchanged > 0) then
      st%eq%residual = change_residual(st, path%frefined)
      return
    end if
    call settled_residual(st, path%whole, path%frefined)
  end subroutine condensed_rejudged

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
    call keep_field(st%u, st%eq%u_last)
    associate(cd => st%eq%cd)
      if (cd%lazy) then
        ! the bodies' forces of u's other equations are not at hand
        if (allocated(st%eq%fbody_last)) deallocate(st%eq%fbody_last)
      else
        st%eq%fbody_last = st%eq%fbody
      end if
      if (cd%keep_pairing) then
        ! the next increment's condensed right-hand side (condensed_begin_lazy)
        if (.not. cd%qnext_fresh) then
          if (.not. allocated(cd%qnext)) allocate(cd%qnext(cd%m))
          call s0_times(cd, cd%x2, cd%qnext)
          cd%qnext = cd%q0 - cd%qnext
        end if
        call keep_field(st%fext, cd%fext_last)
        cd%qnext_valid = .true.
      end if
    end associate
  end subroutine condensed_converged

  !> dst = src, allocated to src's shape where it has another (copy_field).
  subroutine keep_field(src, dst)
    real(dp), intent(in) :: src(:, :)
    real(dp), allocatable, intent(inout) :: dst(:, :)
    if (allocated(dst)) then
      if (any(shape(dst) /= shape(src))) deallocate(dst)
    end if
    if (.not. allocated(dst)) allocate(dst(size(src, 1), size(src, 2)))
    call copy_field(size(src), src, dst)
  end subroutine keep_field

  !> The start of the increment: the free equations from the last
  !> converged solution, the bodies' internal forces there (updated where
  !> prescribed values moved), the condensed right-hand side.
  subroutine start_from_last(st)
    type(iteration_t), intent(inout) :: st
    real(dp), allocatable :: fbody(:, :)
    associate(eq => st%eq, m => st%m, dm => st%dm, u => st%u)
      if (allocated(eq%u_last)) call take_equations(size(u), dm%eq, eq%u_last, u)
      call expand_dependent(dm, u)
      if (lazy_start(st)) then
        call start_on_contact_equations(st)
        return
      end if
      if (allocated(eq%u_last) .and. allocated(eq%fbody_last)) then
        fbody = eq%fbody_last
        call add_body_forces(m, st%body, u - eq%u_last, fbody)
      else
        allocate(fbody(2, m%nn))
        call body_forces(m, st%body, u, fbody)
      end if
      call condensed_begin(eq%cd, m, dm, st%sys, st%fext, u, fbody)
    end associate
  end subroutine start_from_last

  !> May this increment be solved on the contact equations alone
  !> (docs/fretting.md, "Cost")? A linear step paired at every increment
  !> (keep_pairing) whose couplings are all penalty ones, not stabilised,
  !> without dependent dofs at their nodes: their forces are then affine
  !> in the contact equations (the status solve's), and only results
  !> need the other equations.
  logical function lazy_path(st)
    type(iteration_t), intent(in) :: st
    lazy_path = .false.
    if (.not. st%eq%cd%keep_pairing .or. st%body%nonlinear .or. st%cs%stabilised) return
    if (size(st%eq%cd%cdep) > 0) return
    lazy_path = .not. any(st%cs%c(1:st%cs%n)%exact)
  end function lazy_path

  !> Does the increment start on the contact equations alone: lazy_path,
  !> and the last converged increment left its condensed right-hand side
  !> for this numbering (qnext_valid) with its loads?
  logical function lazy_start(st)
    type(iteration_t), intent(in) :: st
    lazy_start = .false.
    if (.not. lazy_path(st) .or. .not. st%eq%cd%qnext_valid) return
    if (.not. allocated(st%eq%u_last) .or. .not. allocated(st%eq%cd%fext_last)) return
    lazy_start = size(st%eq%cd%qnext) == st%eq%cd%m
  end function lazy_start

  !> The start of an increment on the contact equations alone: the change
  !> of the right-hand side since the last converged increment,
  !> r = f_ext - f_ext,last - K_body (u - u_last) (only prescribed values
  !> moved; the elements they touch), condensed through the directions
  !> condensed before (condense_change), added to that increment's qnext.
  subroutine start_on_contact_equations(st)
    type(iteration_t), intent(inout) :: st
    real(dp) :: dq(st%eq%cd%m)
    associate(eq => st%eq, cd => st%eq%cd, m => st%m, dm => st%dm, u => st%u)
      ! (u is u_last on every equation: the elements of the other dofs)
      call moving_elements(cd, m, dm)
      if (allocated(eq%rhs)) then
        if (size(eq%rhs) /= cd%n) deallocate(eq%rhs)
      end if
      if (.not. allocated(eq%rhs)) allocate(eq%rhs(cd%n))
      call load_change(cd, m, st%body, dm, u, eq%u_last, st%fext, eq%rhs)
      call condense_change(cd, st%sys, eq%rhs, dq)
      call condensed_begin_lazy(cd, m, dm, u, dq)
    end associate
  end subroutine start_on_contact_equations

  !> The settled status's out-of-balance on the contact equations alone
  !> (lazy_path): q0 - S0 x2 - f_CFE(u), the rest of K u = f being
  !> in balance by construction once recovered (a linear step), relative
  !> to the scale of change_residual; S0 x2 kept for the next increment
  !> (qnext). The reactions' contact and load parts are put in rf (the
  !> bodies' part is added where the increment is recovered,
  !> condensed_complete). ok false where it is not below the tolerance:
  !> the caller recovers the whole solution as the full path does.
  !> Arguments: fc the CFE forces at u on the contact equations, rf
  !> holding them on every dof (contact_at_u).
  subroutine settled_on_contact_equations(st, fc, ok)
    type(iteration_t), intent(inout) :: st
    real(dp), intent(in) :: fc(:)
    logical, intent(out) :: ok
    real(dp) :: ref, umax, r
    integer :: p, e
    associate(eq => st%eq, cd => st%eq%cd, cs => st%cs, dm => st%dm, u => st%u, rf => st%rf)
      umax = cd%umax_rest
      do p = 1, cd%m
        e = cd%eq_at(p)
        umax = max(umax, abs(u(dm%dof_of_eq(e), dm%node_of_eq(e))))
      end do
      call subtract_field(size(rf), rf, st%fext)
      if (.not. allocated(cd%qnext)) allocate(cd%qnext(cd%m))
      ref = max(st%fext_norm, sum(abs(cs%c(1:cs%n)%force)), 1.0e-6_dp * eq%kmax * umax, tiny(1.0_dp))
      ok = .false.
      if (cd%s0x_valid) then
        ! S0 x2 from the refinement (condensed_refine), judged with the
        ! residual it measured of the solution before its last correction
        ! (at least the refined solution's, to round-off)
        cd%qnext = cd%q0 - cd%s0x
        r = max(norm2(cd%qnext - fc), cd%rres) / max(ref, eq%force_history)
        ok = r < st%m%contact_tolerance
      end if
      if (.not. ok) then
        call s0_times(cd, cd%x2, cd%qnext)
        cd%qnext = cd%q0 - cd%qnext
        r = norm2(cd%qnext - fc) / max(ref, eq%force_history)
        ok = r < st%m%contact_tolerance
      end if
      cd%qnext_fresh = .true.
      if (.not. ok) return
      eq%residual = r
      st%scale = ref
      cd%lazy = .true.
    end associate
  end subroutine settled_on_contact_equations

  !> Purpose: the whole solution of the last converged increment where it
  !> was solved on the contact equations alone (eq%cd%lazy; results need
  !> it: a written increment, reaction sums): the right-hand side of its
  !> start condensed (a forward solve, unless its start made it), the
  !> other equations recovered (condensed_recover), the bodies' forces at
  !> u added to rf (which holds the contact forces minus the loads:
  !> settled_on_contact_equations) and reduced to the independent dofs;
  !> u and the bodies' forces become the next increment's start.
  !> Arguments: eq the equilibrium state; m the model; body the bodies'
  !> stiffness; dm the numbering; sys the solver with K0's factor; u the
  !> displacements (the contact equations solved; returns whole); rf the
  !> residual forces (returns f_int - f_ext, T^T applied).
  subroutine condensed_complete(eq, m, body, dm, sys, u, rf)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    type(body_t), intent(in) :: body
    type(dofmap_t), intent(in) :: dm
    type(linear_system_t), intent(inout) :: sys
    real(dp), intent(inout) :: u(:, :), rf(:, :)
    real(dp) :: t0
    if (.not. eq%cd%lazy) return
    t0 = wall_time()
    call forward_start(eq, m, body, dm, sys, eq%cd%fext_last)
    call condensed_recover(eq%cd, dm, sys, u)
    if (.not. allocated(eq%fbody)) allocate(eq%fbody(2, m%nn))
    call body_forces(m, body, u, eq%fbody)
    rf = rf + eq%fbody
    call reduce_dependent(dm, rf)
    eq%u_last = u
    eq%fbody_last = eq%fbody
    eq%cd%lazy = .false.
    eq%timing%recovery = eq%timing%recovery + (wall_time() - t0)
  end subroutine condensed_complete

  !> The forward-solved right-hand side of the increment's start (cd%z),
  !> where the start did not make it (condensed_begin_lazy): the bodies'
  !> forces at u0 (every element: its other equations are an earlier
  !> increment's), r = f_ext - f_body on the free equations, z = L^-1 P r;
  !> fext the increment's loads.
  subroutine forward_start(eq, m, body, dm, sys, fext)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    type(body_t), intent(in) :: body
    type(dofmap_t), intent(in) :: dm
    type(linear_system_t), intent(inout) :: sys
    real(dp), intent(in) :: fext(:, :)
    real(dp), allocatable :: fb(:, :)
    associate(cd => eq%cd)
      if (cd%z_valid) return
      allocate(fb(2, m%nn))
      call body_forces(m, body, cd%u0, fb)
      call forward_rhs(cd, dm, sys, fext, fb)
    end associate
  end subroutine forward_start

  !> The status has settled: the other equations (unless u already holds
  !> them: whole), then forces, reactions and the out-of-balance as the
  !> full path has them; on the contact equations alone where the
  !> increment may be (lazy_path) and is in balance there. fc, if
  !> present, the CFE forces at u on the contact equations, rf holding
  !> them on every dof (contact_at_u; otherwise evaluated here).
  subroutine settled_residual(st, whole, fc)
    type(iteration_t), intent(inout) :: st
    logical, intent(inout) :: whole
    real(dp), intent(in), optional :: fc(:)
    real(dp) :: t0, fcu(st%eq%cd%m)
    logical :: ok
    t0 = wall_time()
    st%eq%cd%lazy = .false.
    if (.not. whole .and. lazy_path(st)) then
      if (present(fc)) then
        fcu = fc
      else
        call contact_at_u(st, fcu)
      end if
      call settled_on_contact_equations(st, fcu, ok)
      st%eq%timing%recovery = st%eq%timing%recovery + (wall_time() - t0)
      if (ok) return
      st%eq%cd%lazy = .false.
    end if
    associate(eq => st%eq, m => st%m, dm => st%dm, u => st%u, rf => st%rf)
      if (.not. whole) then
        call forward_start(eq, m, st%body, dm, st%sys, st%fext)
        call condensed_recover(eq%cd, dm, st%sys, u)
        call check_finite(m, st%is, st%inc, u)
      end if
      whole = .true.
      if (.not. allocated(eq%fbody)) allocate(eq%fbody(2, m%nn))
      call body_forces(m, st%body, u, eq%fbody)
      rf = eq%fbody
      call contact_forces(m, st%cs, u, rf, eq%counts%coupling)
      rf = rf - st%fext
      call reduce_dependent(dm, rf)
      eq%residual = relative_residual(dm, st%cs, st%fext, u, rf, eq%kmax, eq%force_history, st%scale)
      eq%timing%recovery = eq%timing%recovery + (wall_time() - t0)
    end associate
  end subroutine settled_residual

  !> The CFE forces at u: st%rf on every dof (zero elsewhere; the contact
  !> layer keeps each CFE's gap and force), fc on the contact equations.
  subroutine contact_at_u(st, fc)
    type(iteration_t), intent(inout) :: st
    real(dp), intent(out) :: fc(:)
    integer :: p, e
    associate(cd => st%eq%cd, dm => st%dm)
      call zero_field(size(st%rf), st%rf)
      call contact_forces(st%m, st%cs, st%u, st%rf, st%eq%counts%coupling)
      do p = 1, cd%m
        e = cd%eq_at(p)
        fc(p) = st%rf(dm%dof_of_eq(e), dm%node_of_eq(e))
      end do
    end associate
  end subroutine contact_at_u

  !> u += K^-1 (f_ext - f_int(u)) on the free equations, f_int - f_ext
  !> being st%rf of the u given.
  subroutine correct(st)
    type(iteration_t), intent(inout) :: st
    integer :: a, d
    real(dp) :: t0
    t0 = wall_time()
    associate(eq => st%eq, dm => st%dm, u => st%u)
      call free_residual(dm, st%fext, st%rf + st%fext, eq%rhs)
      call condensed_correct(eq%cd, st%sys, eq%rhs)
      do a = 1, st%m%nn
        do d = 1, 2
          if (dm%eq(d, a) > 0) u(d, a) = u(d, a) + eq%rhs(dm%eq(d, a))
        end do
      end do
      call expand_dependent(dm, u)
      eq%timing%recovery = eq%timing%recovery + (wall_time() - t0)
    end associate
  end subroutine correct

  !> The out-of-balance after status changes, before the other equations
  !> are recovered: the change of the CFE forces from fold (which lives on
  !> the contact equations; every other force is in balance by
  !> construction) relative to the loads, the contact forces, the
  !> stiffness times the displacements known so far, and the converged
  !> history. The full path's scale also has the reactions, which need the
  !> other equations: where they dominate, this value is the larger.
  real(dp) function change_residual(st, fold) result(r)
    type(iteration_t), intent(inout) :: st
    real(dp), intent(in) :: fold(:)
    real(dp) :: fnew(st%eq%cd%m), ref, umax
    integer :: p, e
    associate(eq => st%eq, cs => st%cs, dm => st%dm, u => st%u)
      call contact_part_forces(eq%cd, st%m, cs, dm, u, fnew, eq%counts%coupling)
      umax = eq%cd%umax_rest
      do p = 1, eq%cd%m
        e = eq%cd%eq_at(p)
        umax = max(umax, abs(u(dm%dof_of_eq(e), dm%node_of_eq(e))))
      end do
      ref = max(st%fext_norm, sum(abs(cs%c(1:cs%n)%force)), 1.0e-6_dp * eq%kmax * umax, tiny(1.0_dp))
      r = norm2(fnew - fold) / max(ref, eq%force_history)
    end associate
  end function change_residual

  !> The bodies' factor of the condensed solve, once per numbering: a
  !> singular one cannot be mended by any contact status.
  subroutine k0_if_needed(st)
    type(iteration_t), intent(inout) :: st
    integer :: status, bad
    real(dp) :: t0
    associate(eq => st%eq, sys => st%sys)
      if (eq%k0_valid) return
      t0 = wall_time()
      call sys_analyse(sys)
      eq%timing%analyse = eq%timing%analyse + (wall_time() - t0)
      t0 = wall_time()
      call condensed_factor_k0(eq%cd, st%m, st%cs, st%body, st%dm, sys, eq%counts, status, bad)
      eq%timing%factor = eq%timing%factor + (wall_time() - t0)
      eq%factorisations = eq%factorisations + 1
      eq%timing%numeric_factorisations = eq%timing%numeric_factorisations + 1
      if (status /= 0) call singular(st%m, st%cs, st%dm, bad)
      eq%k0_valid = .true.
      eq%factor_valid = .false.
      call describe(eq, st%is, st%cs, sys, st%obs)
    end associate
  end subroutine k0_if_needed

  !> Factors the condensed matrix unless the one in hand was made for the
  !> current contact status (factor_fits); stabilises open contact as the
  !> full path does when it is singular with open CFEs; st%usable false
  !> where it is singular after a pivot of the search with the
  !> stabilisation used, or (Newton) singular otherwise: the increment is
  !> given up (as the full path's factor_if_needed).
  subroutine condensed_factor_if_needed(st, kbody)
    type(iteration_t), intent(inout) :: st
    real(dp), intent(in) :: kbody          ! the bodies' largest element entry
    integer :: status, bad
    st%usable = .true.
    if (factor_fits(st%eq, st%cs)) return
    call dense_status(st, kbody, status, bad)
    if (status == factor_singular) then
      if (stabilise_open(st%eq, st%cs, st%obs)) call dense_status(st, kbody, status, bad)
    end if
    if (status == factor_singular .and. st%body%nonlinear .and. .not. st%eq%search%pivoted) then
      ! Newton's tangent singular: the increment is cut back (as the full path)
      st%usable = .false.
      st%eq%factor_valid = .false.
      st%eq%bad = bad
      st%eq%newton%singular = .true.
      return
    end if
    if (status == factor_singular) then
      call set_aside_or_stop(st%eq, st%m, st%cs, st%dm, bad, st%usable)
      return
    end if
    st%eq%kmax = st%eq%cd%kmax
    call factor_made(st%eq, st%cs)
  end subroutine condensed_factor_if_needed

  !> The condensed matrix of the status: one dense factorisation, or
  !> (UPDATE SEARCH in a linear step) the low-rank form against the
  !> reference's inverse, which factors nothing of size m; each counted
  !> on its own (condensed_factorisations, condensed_lowrank).
  subroutine dense_status(st, kbody, status, bad)
    type(iteration_t), intent(inout) :: st
    real(dp), intent(in) :: kbody
    integer, intent(out) :: status, bad
    call condensed_status(st%eq%cd, st%m, st%cs, st%dm, kbody, st%eq%counts, status, bad)
    if (st%eq%cd%lowrank) then
      st%eq%condensed_lowrank = st%eq%condensed_lowrank + 1
      st%eq%timing%condensed_lowrank = st%eq%timing%condensed_lowrank + 1
      return
    end if
    st%eq%condensed_factorisations = st%eq%condensed_factorisations + 1
    st%eq%timing%condensed_factorisations = st%eq%timing%condensed_factorisations + 1
  end subroutine dense_status

  ! ---- The Newton path ----

  !> Purpose: the start of a Newton increment: the linearisation point is
  !> u, its bodies' forces those at u (or, with a predictor, linearised
  !> about the converged u_from, whose tangent the first one is, as on the
  !> full path); the tangent is made by the first factor.
  subroutine newton_begin_increment(path, st)
    class(newton_condensed_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    path%newton_refactors = .false.
    path%searches_itself = st%research
    path%augmented = .not. direct_multipliers(st%cs)
    path%nsolves = 0
    path%whole = .false.
    path%ubase = st%u
    allocate(path%fbase(2, st%m%nn))
    if (st%predict) then
      if (converged_forces_at(st%eq%newton, st%u_from)) then
        ! the bodies' forces of the converged state kept: only the moved elements evaluated
        call body_predictor_forces(st%m, st%body, st%u_from, st%u - st%u_from, path%fbase, st%eq%counts, &
                                   f0=st%eq%newton%fconv)
      else
        call body_predictor_forces(st%m, st%body, st%u_from, st%u - st%u_from, path%fbase, st%eq%counts)
      end if
      path%tangent_at = st%u_from
      path%at_converged = .true.
    else
      call nonlinear_body_forces(st%m, st%body, st%u, path%fbase, st%eq%counts)
      path%tangent_at = st%u
      path%at_converged = associated(st%u_from)
    end if
    path%rebase = .true.
  end subroutine newton_begin_increment

  !> Purpose: a new Newton iteration once the last correction is whole
  !> (the linearisation point moves to u, the tangent there), or after the
  !> equations were numbered again (the same point): the tangent factored
  !> and condensed (newton_tangent); then the condensed matrix of the
  !> status, unless the one in hand is for it.
  subroutine newton_factor(path, st)
    class(newton_condensed_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    st%usable = .true.
    st%restabilised = .false.
    if (path%whole) then
      path%ubase = st%u
      path%fbase = st%eq%fbody
      path%tangent_at = st%u
      path%at_converged = .false.
      path%rebase = .true.
    end if
    if (.not. st%eq%k0_valid) path%rebase = .true.
    if (.not. st%eq%cd%active) then
      ! renumbered for couplings without a contact equation
      call newton_give_up(st%eq%newton, not_condensable)
      st%verdict = give_up_verdict
      return
    end if
    if (path%rebase) then
      call newton_tangent(path, st)
      if (.not. st%usable) return
    end if
    call condensed_factor_if_needed(st, path%kbody)
  end subroutine newton_factor

  !> The tangent at path%tangent_at with every CFE open, factored with the
  !> contact equations last and condensed (condensed_factor_k0, counted
  !> and timed), the right-hand side of the linearisation point condensed
  !> (condensed_begin); u back at that point. A singular tangent gives the
  !> increment up (st%usable false, eq%newton%singular: the loop's
  !> newton_after_factor).
  subroutine newton_tangent(path, st)
    class(newton_condensed_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    integer :: status, bad
    real(dp) :: t0, ta
    associate(eq => st%eq)
      t0 = wall_time()
      call sys_analyse(st%sys)
      eq%timing%analyse = eq%timing%analyse + (wall_time() - t0)
      t0 = wall_time()
      call condensed_factor_k0(eq%cd, st%m, st%cs, st%body, st%dm, st%sys, eq%counts, status, bad, &
                               u=path%tangent_at, converged=path%at_converged, kbody=path%kbody, t_assembly=ta)
      eq%timing%assembly = eq%timing%assembly + ta
      eq%timing%factor = eq%timing%factor + (wall_time() - t0 - ta)
      eq%factorisations = eq%factorisations + 1
      eq%timing%numeric_factorisations = eq%timing%numeric_factorisations + 1
      eq%factor_valid = .false.
      if (status /= 0) then
        eq%k0_valid = .false.
        eq%bad = bad
        eq%newton%singular = .true.
        st%usable = .false.
        return
      end if
      eq%k0_valid = .true.
      call describe(eq, st%is, st%cs, st%sys, st%obs)
      if (allocated(path%fold)) deallocate(path%fold)
      allocate(path%fold(eq%cd%m))
      st%u = path%ubase
      call condensed_begin(eq%cd, st%m, st%dm, st%sys, st%fext, st%u, path%fbase)
      path%rebase = .false.
      path%whole = .false.
    end associate
  end subroutine newton_tangent

  !> Purpose: the status of the linearised problem solved on the contact
  !> equations (with its multipliers where they are solved directly); the
  !> other equations stay at the linearisation point until it settles.
  !> A correction that is not finite is left in u (the loop gives up).
  subroutine newton_solve(path, st)
    class(newton_condensed_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    integer :: nactive
    logical :: finite, solved
    st%c_max = 0.0_dp
    st%nsearched = 0
    st%searched = .false.
    call condensed_solve(st%eq%cd, st%m, st%cs, st%dm, st%u, finite, st%eq%counts%coupling)
    if (.not. finite .or. path%augmented) return
    call condensed_multipliers(st%eq%cd, st%m, st%cs, st%dm, st%u, nactive, solved)
    if (nactive > 0) path%nsolves = path%nsolves + 1
    if (.not. solved) path%augmented = .true.
  end subroutine newton_solve

  !> Purpose: after the status switch: a status changed, the inner search
  !> goes on from the linearisation point (the change of the CFE forces
  !> its out-of-balance; st%inner: no Newton iteration); none did, the
  !> correction is recovered whole and its true out-of-balance made
  !> (newton_settled).
  subroutine newton_residual(path, st)
    class(newton_condensed_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    st%inner = st%nchanged > 0
    if (st%inner) then
      st%eq%residual = change_residual(st, path%fold)
    else
      call newton_settled(path, st)
    end if
  end subroutine newton_residual

  !> The settled status's correction recovered on every equation; c_max
  !> its largest entry; under NLGEOM the contact searched again on the
  !> new configuration (a search that changes statuses or couplings counts
  !> as a change: not converged; a renumbering makes the next factor
  !> start again); the bodies' forces at u (kept: the next linearisation
  !> point's), reactions and out-of-balance as on the full path.
  subroutine newton_settled(path, st)
    class(newton_condensed_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    real(dp) :: t0
    t0 = wall_time()
    associate(eq => st%eq, m => st%m, dm => st%dm, u => st%u, rf => st%rf)
      call condensed_recover(eq%cd, dm, st%sys, u)
      path%whole = .true.
      if (.not. all(ieee_is_finite(u))) then
        call newton_give_up(eq%newton, not_finite)
        st%verdict = give_up_verdict
        return
      end if
      st%c_max = maxval(abs(u - path%ubase), mask=dm%eq > 0)
      st%c_max = max(st%c_max, 0.0_dp)
      if (st%research .and. st%c_max < coupling_length(st%cs)) then
        call search_in_iteration(eq, m, st%cs, u, st%presc, st%mpc, dm, st%sys, st%nsearched)
        st%searched = .true.
        st%nchanged = st%nchanged + st%nsearched
      end if
      if (.not. allocated(eq%fbody)) allocate(eq%fbody(2, m%nn))
      call nonlinear_body_forces(m, st%body, u, eq%fbody, eq%counts)
      rf = eq%fbody
      call contact_forces(m, st%cs, u, rf, eq%counts%coupling)
      rf = rf - st%fext
      call reduce_dependent(dm, rf)
      eq%residual = relative_residual(dm, st%cs, st%fext, u, rf, eq%kmax, eq%force_history, st%scale)
      eq%timing%recovery = eq%timing%recovery + (wall_time() - t0)
    end associate
  end subroutine newton_settled

  !> Purpose: a new status search (augmented multipliers, the nominal open
  !> penalty) from the linearisation point; once the correction is whole,
  !> from the point it reached (the next factor moves there).
  subroutine newton_restart(path, st)
    class(newton_condensed_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    if (.not. path%whole) st%u = path%ubase
  end subroutine newton_restart

  !> Purpose: the increment converged: the direct solves said; a later
  !> linear step starts its condensed solve afresh (the bodies' forces
  !> kept here are not its stored stiffness times u).
  subroutine newton_converged_increment(path, st)
    class(newton_condensed_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    character(len=12) :: buf
    if (path%nsolves > 0) then
      write(buf, '(i0)') path%nsolves
      call tell_note(st%obs, 'exact contact: ' // trim(buf) // ' direct multiplier solves in the increment')
    end if
    if (allocated(st%eq%u_last)) deallocate(st%eq%u_last)
    if (allocated(st%eq%fbody_last)) deallocate(st%eq%fbody_last)
    ! the bodies' forces of the settled correction: the next predictor's
    if (allocated(st%eq%fbody)) call converged_body_forces(st%eq%newton, st%u, st%eq%fbody)
  end subroutine newton_converged_increment
end module condensed_equilibrium
