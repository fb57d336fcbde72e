!> The equilibrium iteration of one increment: Newton passes on the
!> piecewise-linear system, each solving K du = f_ext - f_int(u) with the
!> current contact status, followed by the contact layer's switching rule,
!> until no status changes and the out-of-balance force is below the
!> tolerance. The stiffness depends only on the contact status, so its
!> factor is kept while the status is the one it was made for.
!> This module solves it on the whole system (a factorisation for every
!> status) and hands it to condensed_equilibrium when the equations were
!> numbered for the condensed contact solve; both switch by the same rule,
!> stabilise a body held only by open contact the same way and tell the
!> observers the same events.
module equilibrium
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  use strings, only: itoa
  use model, only: model_t, elem_label, node_label
  use contact, only: contact_set_t, status_codes, contact_forces, contact_research, cfe_nodes, cfe_max_nodes
  use contact_status, only: contact_switch, begin_status_search, contact_energy, augment_multipliers, max_augmentations
  use assembly, only: body_t, assemble_stiffness, free_residual, body_predictor_forces
  use dof_numbering, only: dofmap_t, expand_dependent, reduce_dependent, follow_rotations
  use constraints, only: mpc_t
  use condensed_contact, only: number_equations
  use linear_solver, only: linear_system_t, sys_factor, sys_solve, sys_analyse, factor_singular, factor_fallback
  use equilibrium_common, only: equilibrium_t, begin_equilibrium, internal_forces, relative_residual, check_finite, &
                                report_iteration, describe, singular, contact_force_scale, take_back, &
                                stabilise_open, set_aside_or_stop, newton_begin, newton_test, newton_converged, &
                                newton_failed, next_stage
  use condensed_equilibrium, only: solve_condensed
  use analysis_events, only: observer_ref_t, run_timing_t, tell_note, wall_time
  use messages, only: warn, fatal
  implicit none
  private
  public :: equilibrium_t, begin_equilibrium, solve_increment, renumber_couplings, note_numbering, numbering_fits

  !> The largest element tangent entry a nonlinear step accepts.
  real(dp), parameter :: tangent_limit = 1.0e250_dp

contains

  !> Purpose: equilibrium at the prescribed values and loads already in u
  !> and fext (the dependent dofs of constraints are set from them here).
  !> On return u holds the solution, rf = T^T (f_int - f_ext) (the
  !> reactions at prescribed dofs; zero at dependent dofs), ok whether it converged and iters the
  !> iterations used. u_from, in a nonlinear step, is the converged state
  !> the increment starts from (u has its free dofs and the new prescribed
  !> values): the first iteration is linearised about it. presc and mpc,
  !> in a nonlinear step under NLGEOM with contact, ask for the contact
  !> to be searched again after every displacement update (solve_full:
  !> search_in_iteration); they are the step's prescribed dofs and the
  !> constraints that a renumbering of dm and sys needs.
  subroutine solve_increment(eq, m, is, inc, body, cs, dm, sys, fext, u, rf, obs, ok, iters, u_from, presc, mpc)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    integer, intent(in) :: is, inc
    type(body_t), intent(inout) :: body
    type(contact_set_t), intent(inout) :: cs
    type(dofmap_t), intent(inout) :: dm
    type(linear_system_t), intent(inout) :: sys
    real(dp), intent(in) :: fext(:, :)
    real(dp), intent(inout) :: u(:, :)
    real(dp), intent(out) :: rf(:, :)
    type(observer_ref_t), intent(in) :: obs(:)
    logical, intent(out) :: ok
    integer, intent(out) :: iters
    real(dp), intent(in), optional :: u_from(:, :)
    logical, intent(in), optional :: presc(:, :)
    type(mpc_t), intent(in), optional :: mpc
    real(dp) :: t0, parts
    t0 = wall_time()
    parts = timed_parts(eq%timing)
    if (eq%cd%active) then
      call solve_condensed(eq, m, is, inc, body, cs, dm, sys, fext, u, rf, obs, ok, iters)
      eq%timing%condensed = eq%timing%condensed + (wall_time() - t0) - (timed_parts(eq%timing) - parts)
    else
      call solve_full(eq, m, is, inc, body, cs, dm, sys, fext, u, rf, obs, ok, iters, u_from, presc, mpc)
      eq%timing%solve = eq%timing%solve + (wall_time() - t0) - (timed_parts(eq%timing) - parts)
    end if
  end subroutine solve_increment

  !> The parts timed inside an iteration (the rest is the iteration's own).
  pure real(dp) function timed_parts(t)
    type(run_timing_t), intent(in) :: t
    timed_parts = t%assembly + t%analyse + t%factor + t%recovery
  end function timed_parts

  !> solve_increment by factoring the whole stiffness of every status.
  !> In a nonlinear step (body%nonlinear) the same loop is Newton's method:
  !> the tangent of the bodies at u is assembled and factored in every
  !> iteration (full Newton: the consistent tangent converges
  !> quadratically, and a factorisation costs little next to the element
  !> evaluations in 2D), the contact status search goes on inside it, and
  !> the increment has converged when no status changes and CalculiX's
  !> force and displacement tests pass (newton_test). It fails (ok false,
  !> eq%newton%cut and reason say how and why) on divergence, on too slow
  !> a convergence, on an element that cannot be evaluated at u or on a
  !> displacement that is not finite; the driver then cuts the increment.
  !> With presc and mpc (NLGEOM with contact) the contact is searched and
  !> evaluated again on the current configuration after every
  !> displacement update, before that iteration's status switch and
  !> residual test (search_in_iteration): the master edge, projection,
  !> normal and initial gap of every CFE follow the bodies, so that a
  !> slave point sliding past its master edge within the increment meets
  !> the next edge, not the extension of the old one. The tangent holds
  !> the CFEs' geometry fixed (no variation of the normal or projection:
  !> docs/nonlinear.md).
  subroutine solve_full(eq, m, is, inc, body, cs, dm, sys, fext, u, rf, obs, ok, iters, u_from, presc, mpc)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    integer, intent(in) :: is, inc       ! step, and the increment being solved
    type(body_t), intent(inout) :: body
    type(contact_set_t), intent(inout) :: cs
    type(dofmap_t), intent(inout) :: dm
    type(linear_system_t), intent(inout) :: sys
    real(dp), intent(in) :: fext(:, :)
    real(dp), intent(inout) :: u(:, :)
    real(dp), intent(out) :: rf(:, :)
    type(observer_ref_t), intent(in) :: obs(:)
    logical, intent(out) :: ok
    integer, intent(out) :: iters
    real(dp), intent(in), optional :: u_from(:, :)
    logical, intent(in), optional :: presc(:, :)
    type(mpc_t), intent(in), optional :: mpc
    real(dp), allocatable :: fint(:, :), u_start(:, :)
    logical, allocatable :: closed1(:), closed2(:)
    integer :: it, a, d, nchanged, naug, nsearched
    logical :: restabilised, usable, converged, predict, searched
    real(dp) :: scale, energy, c_max, res1, res2
    allocate(fint(2, m%nn), closed1(0), closed2(0))
    res1 = -1.0_dp
    res2 = -1.0_dp
    ok = .false.
    cs%stabilised = .false.
    eq%stabilisation_used = .false.
    call expand_dependent(dm, u)
    if (body%nlgeom) call follow_rotations(dm, u)
    predict = .false.
    if (body%nonlinear) then
      call newton_begin(eq%newton)
      if (present(u_from)) then
        u_start = u_from
        predict = any(u /= u_from)
      else
        u_start = u
      end if
    end if
    if (predict) then
      ! f_int linearised about the converged state (body_predictor_forces)
      call body_predictor_forces(m, body, u_from, u - u_from, fint, eq%counts)
      call contact_forces(m, cs, u, fint, eq%counts%coupling)
      body%bad_elem = 0
    else
      call internal_forces(m, body, cs, u, fint, eq%counts)
    end if
    ! the equations must be numbered for the couplings in hand (a cut-back
    ! restores both: advance_nonlinear)
    if (present(presc) .and. .not. numbering_fits(eq, m, cs)) call fatal('internal error: the equations are ' // &
      'not numbered for the contact couplings of the increment')
    call begin_status_search(eq%search)
    it = 0
    naug = 0
    ! MAXIT counts the iterations of each status search
    do while (eq%search%iterations < m%contact_max_iter)
      it = it + 1
      if (body%nonlinear) then
        if (body%bad_elem > 0) then
          call newton_failed(eq%newton, eq%newton%ctl%df, 'element ' // elem_label(m, body%bad_elem) // &
                             ' is inverted or cannot be evaluated at the displacements of the iteration')
          exit
        end if
        ! the tangent at the current displacements
        eq%factor_valid = .false.
      end if
      if (predict .and. it == 1) then
        call factor_if_needed(eq, m, is, body, cs, dm, u_from, sys, obs, restabilised, usable, .true.)
      else
        ! (the first iteration of a load-controlled increment is at the converged state)
        call factor_if_needed(eq, m, is, body, cs, dm, u, sys, obs, restabilised, usable, &
                              body%nonlinear .and. it == 1 .and. present(u_from))
      end if
      if (body%nonlinear .and. eq%kmax > tangent_limit) then
        ! entries this large sum to overflow in the assembled matrix
        call newton_failed(eq%newton, eq%newton%ctl%df, 'the tangent stiffness overflows (an element entry ' // &
                           'beyond 1e250: a thickness, modulus or displacement out of range?)')
        exit
      end if
      if (.not. usable .and. eq%newton%singular) then
        call newton_failed(eq%newton, eq%newton%ctl%df, 'the tangent stiffness is singular' // &
                           singular_where(m, dm, eq%bad) // ' (a limit load, or a missing support)')
        exit
      end if
      if (.not. usable) then
        call take_back(eq, m, cs, dm, obs)
        call internal_forces(m, body, cs, u, fint, eq%counts)
        cycle
      end if
      if (restabilised) call internal_forces(m, body, cs, u, fint, eq%counts)
      call free_residual(dm, fext, fint, eq%rhs)
      call sys_solve(sys, eq%rhs)
      c_max = 0.0_dp
      do a = 1, m%nn
        do d = 1, 2
          if (dm%eq(d, a) > 0) then
            u(d, a) = u(d, a) + eq%rhs(dm%eq(d, a))
            c_max = max(c_max, abs(eq%rhs(dm%eq(d, a))))
          end if
        end do
      end do
      call expand_dependent(dm, u)
      if (body%nonlinear) then
        if (.not. all(ieee_is_finite(u))) then
          call newton_failed(eq%newton, eq%newton%ctl%df, 'the displacements are not finite numbers')
          exit
        end if
      else
        call check_finite(m, is, inc, u)
      end if
      ! The search follows an iterate whose correction is smaller than the
      ! couplings' mesh length; a larger one (an iterate far from
      ! equilibrium: a body falling through under a stabilised open
      ! penalty, a wild first iterate of a soft body) keeps the pairing,
      ! whose master normals would otherwise come from a wildly deformed
      ! master. An increment converges only in an iteration that searched.
      nsearched = 0
      searched = .false.
      if (present(presc) .and. present(mpc)) then
        if (c_max < coupling_length(cs)) then
          call search_in_iteration(eq, m, cs, u, presc, mpc, dm, sys, nsearched)
          searched = .true.
        end if
      end if
      ! rigid bodies and kinematic couplings turn exactly under NLGEOM, T at the current theta
      if (body%nlgeom) call follow_rotations(dm, u)
      call internal_forces(m, body, cs, u, fint, eq%counts, energy)
      ! the potential energy of this status's solution, eqs. (1) and (9)
      energy = energy - sum(fext * u) + contact_energy(cs)
      call contact_switch(m, cs, eq%search, contact_force_scale(eq, cs, norm2(fext)), energy, nchanged, eq%changed)
      ! statuses the search itself changed (couplings that came closed or
      ! were lost): the increment has not settled either
      nchanged = nchanged + nsearched
      ! the residual of the new status
      if (nchanged > 0) call internal_forces(m, body, cs, u, fint, eq%counts)
      rf = fint - fext
      call reduce_dependent(dm, rf)
      eq%residual = relative_residual(dm, cs, fext, u, rf, eq%kmax, eq%force_history, scale)
      eq%iterations = eq%iterations + 1
      if (body%nonlinear) then
        eq%newton%it = eq%newton%it + 1
        eq%newton%attempt = eq%newton%attempt + 1
        eq%newton%total = eq%newton%total + 1
        if (nchanged > 0) then
          eq%newton%it = 0
          eq%newton%changes = eq%newton%changes + 1
        end if
        if (body%bad_elem == 0) then
          call newton_test(eq%newton, body%average_force, max_free(dm, rf), c_max, maxval(abs(u - u_start)), &
                           converged, eq%residual)
          if (present(presc) .and. .not. searched) converged = .false.
          if (eq%newton%cut < 1.0_dp .and. (nchanged == 0 .or. &
              eq%newton%attempt >= eq%newton%ctl%ic + eq%newton%changes)) exit
        else
          converged = .false.
        end if
      end if
      call report_iteration(eq, cs, obs, it, nchanged)
      if (body%nonlinear .and. nchanged > 0) then
        ! The statuses and the out-of-balance of two iterations back again:
        ! the Newton iterates cycle (a coupling closing and opening in
        ! turn, as under a penalty far stiffer than a soft body) and would
        ! do so until MAXIT; the increment is cut back now.
        if (status_cycles(cs, closed2, res2, eq%residual)) then
          call newton_failed(eq%newton, eq%newton%ctl%dc, 'the contact status cycles (the same statuses and ' // &
                             'out-of-balance every second iteration)')
          exit
        end if
        closed2 = closed1
        res2 = res1
        closed1 = cs%c(1:cs%n)%closed
        res1 = eq%residual
      end if
      if (nchanged == 0 .and. cs%stabilised) then
        if (next_stage(eq, cs, contact_force_scale(eq, cs, norm2(fext)), obs)) then
          call internal_forces(m, body, cs, u, fint, eq%counts)
          cycle
        end if
        ! settled while stabilised: a new search with the nominal open penalty
        cs%stabilised = .false.
        call begin_status_search(eq%search)
        call internal_forces(m, body, cs, u, fint, eq%counts)
        call tell_note(obs, 'contact status settled with the stabilised open penalty; ' // &
                            'iterating on with the nominal one')
        cycle
      end if
      ! settled: no status changed and the out-of-balance passes the test
      ! (a nonlinear step: CalculiX's force and correction tests)
      if (.not. body%nonlinear) converged = eq%residual < m%contact_tolerance
      if (nchanged == 0 .and. converged .and. naug < max_augmentations) then
        ! exact enforcement: the multipliers updated, the search again
        if (augment_multipliers(cs, contact_force_scale(eq, cs, norm2(fext)))) then
          naug = naug + 1
          call internal_forces(m, body, cs, u, fint, eq%counts)
          call begin_status_search(eq%search)
          cycle
        end if
      end if
      if (nchanged == 0 .and. converged) then
        ok = .true.
        iters = it
        eq%force_history = max(eq%force_history, scale)
        if (body%nonlinear) call newton_converged(eq%newton)
        return
      end if
    end do
    iters = it
    if (body%nonlinear .and. eq%newton%cut >= 1.0_dp) call newton_failed(eq%newton, eq%newton%ctl%dc, &
      'the contact status did not settle in ' // itoa(m%contact_max_iter) // ' iterations')
  end subroutine solve_full

  !> Purpose: are the couplings' statuses those of `closed` (two
  !> iterations back) and the relative out-of-balance `res` that of then,
  !> `res_was`, to 1e-6? (A repeat of both is a cycle of the iterates;
  !> the coupling set must be the same one: a search that renumbered it
  !> is no repeat.)
  pure logical function status_cycles(cs, closed, res_was, res)
    type(contact_set_t), intent(in) :: cs
    logical, intent(in) :: closed(:)
    real(dp), intent(in) :: res_was, res
    status_cycles = .false.
    if (size(closed) /= cs%n .or. res_was < 0.0_dp) return
    if (any(cs%c(1:cs%n)%closed .neqv. closed)) return
    status_cycles = abs(res - res_was) <= 1.0e-6_dp * max(abs(res), abs(res_was))
  end function status_cycles

  !> Purpose: the contact of the configuration m%x + u within a Newton
  !> iteration (NLGEOM): contact_research pairs every slave point again
  !> (master edge, projection, normal, initial gap; the status, the exact
  !> multiplier and the friction state carried over per slave point), and
  !> the equations are numbered again only where the couplings' node lists
  !> changed (renumber_couplings): a point moved on to another master
  !> element, or was coupled or uncoupled. Where only the geometry of the
  !> couplings moved, the numbering, the sparse structure and its symbolic
  !> analysis stay.
  !> Arguments: presc, mpc the step's prescribed dofs and constraints;
  !> dm, sys renumbered where needed; changed the statuses the search
  !> changed (contact_research), counted as status changes of the iteration.
  subroutine search_in_iteration(eq, m, cs, u, presc, mpc, dm, sys, changed)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(inout) :: cs
    real(dp), intent(in) :: u(:, :)
    logical, intent(in) :: presc(:, :)
    type(mpc_t), intent(in) :: mpc
    type(dofmap_t), intent(inout) :: dm
    type(linear_system_t), intent(inout) :: sys
    integer, intent(out) :: changed
    call contact_research(m, m%x + u, cs, moved=.true., changed=changed)
    eq%searches = eq%searches + 1
    if (.not. numbering_fits(eq, m, cs)) call renumber_couplings(eq, m, cs, presc, mpc, dm, sys)
  end subroutine search_in_iteration

  !> The shortest mesh length of the couplings of cs (huge without any).
  pure real(dp) function coupling_length(cs) result(h)
    type(contact_set_t), intent(in) :: cs
    h = huge(1.0_dp)
    if (cs%n > 0) h = minval(cs%c(1:cs%n)%h)
  end function coupling_length

  !> Purpose: were the equations (eq%numbered_for, note_numbering) numbered
  !> for the couplings of cs: the same CFEs with the same node lists,
  !> whatever their geometry?
  logical function numbering_fits(eq, m, cs)
    type(equilibrium_t), intent(in) :: eq
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    numbering_fits = .false.
    if (allocated(eq%numbered_for)) numbering_fits = same_lists(eq%numbered_for, coupling_lists(m, cs))
  end function numbering_fits

  !> Purpose: the equations have just been numbered for the couplings of
  !> cs (number_equations): remembered for numbering_fits.
  subroutine note_numbering(eq, m, cs)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    eq%numbered_for = coupling_lists(m, cs)
  end subroutine note_numbering

  !> Purpose: the equations numbered again for the couplings of cs
  !> (number_equations of a nonlinear step: the full solve) and the
  !> iteration's arrays sized for them; the analysis time is timed.
  subroutine renumber_couplings(eq, m, cs, presc, mpc, dm, sys)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    logical, intent(in) :: presc(:, :)
    type(mpc_t), intent(in) :: mpc
    type(dofmap_t), intent(inout) :: dm
    type(linear_system_t), intent(inout) :: sys
    real(dp) :: ta
    call number_equations(m, cs, presc, mpc, dm, sys, eq%cd, ta, .true.)
    eq%timing%analyse = eq%timing%analyse + ta
    call begin_equilibrium(eq, dm%neq, cs%n, .false.)
    call note_numbering(eq, m, cs)
    eq%renumberings = eq%renumberings + 1
  end subroutine renumber_couplings

  !> The node lists of every CFE of cs in order, each preceded by its
  !> length: what the equation structure depends on.
  function coupling_lists(m, cs) result(l)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    integer, allocatable :: l(:)
    integer :: j, nen, k
    integer, allocatable :: nodes(:)
    allocate(l(cs%n * (cfe_max_nodes(cs) + 1)))
    k = 0
    do j = 1, cs%n
      call cfe_nodes(m, cs%c(j), nodes, nen)
      l(k + 1) = nen
      l(k + 2:k + 1 + nen) = nodes(1:nen)
      k = k + 1 + nen
    end do
    l = l(1:k)
  end function coupling_lists

  !> Are the integer lists a and b equal (length and entries)?
  pure logical function same_lists(a, b)
    integer, intent(in) :: a(:), b(:)
    same_lists = size(a) == size(b)
    if (same_lists) same_lists = all(a == b)
  end function same_lists

  !> ' at node N, dof D' for equation bad of the numbering (empty if none).
  function singular_where(m, dm, bad) result(s)
    type(model_t), intent(in) :: m
    type(dofmap_t), intent(in) :: dm
    integer, intent(in) :: bad
    character(len=:), allocatable :: s
    s = ''
    if (bad > 0 .and. bad <= dm%neq) s = ' at node ' // node_label(m, dm%node_of_eq(bad)) // ', dof ' // &
                                         itoa(dm%dof_of_eq(bad))
  end function singular_where

  !> The largest residual force on a free dof (r_max): rf holds f_int -
  !> f_ext reduced to the independent dofs.
  pure real(dp) function max_free(dm, rf) result(r)
    type(dofmap_t), intent(in) :: dm
    real(dp), intent(in) :: rf(:, :)
    r = maxval(abs(rf), mask=dm%eq > 0)
    r = max(r, 0.0_dp)
  end function max_free

  !> Assembles and factors the stiffness unless the factor in hand was made
  !> for the current contact status. A singular stiffness with open CFEs
  !> (a body held only by open contact) is factored again with the
  !> stabilised open penalty (contact_set_t); restabilised says so. Where
  !> the stabilisation was used already and the status comes from a pivot
  !> of the search, usable is false (the pivot is to be taken back);
  !> otherwise a singular stiffness stops the run.
  subroutine factor_if_needed(eq, m, is, body, cs, dm, u, sys, obs, restabilised, usable, converged)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    integer, intent(in) :: is
    type(body_t), intent(inout) :: body
    type(contact_set_t), intent(inout) :: cs
    type(dofmap_t), intent(in) :: dm
    real(dp), intent(in) :: u(:, :)
    type(linear_system_t), intent(inout) :: sys
    type(observer_ref_t), intent(in) :: obs(:)
    logical, intent(out) :: restabilised, usable
    logical, intent(in), optional :: converged
    integer :: status, bad
    logical :: at_converged
    at_converged = .false.
    if (present(converged)) at_converged = converged
    restabilised = .false.
    usable = .true.
    ! (with every CFE closed, stabilising changes no penalty)
    if (eq%factor_valid .and. ((eq%factor_stabilised .eqv. cs%stabilised) .or. all(cs%c(1:cs%n)%closed))) then
      if (all(eq%factor_states == status_codes(cs))) return
    end if
    call assemble_and_factor(eq, m, body, cs, dm, u, sys, status, bad, at_converged)
    if (status == factor_singular) then
      restabilised = stabilise_open(eq, cs, obs)
      if (restabilised) call assemble_and_factor(eq, m, body, cs, dm, u, sys, status, bad, at_converged)
    end if
    if (status == factor_singular .and. body%nonlinear .and. .not. eq%search%pivoted) then
      ! a singular tangent of a nonlinear body (a limit load, a buckling
      ! state, or a missing support): the increment fails and is cut back
      usable = .false.
      eq%factor_valid = .false.
      eq%bad = bad
      eq%newton%singular = .true.
      return
    end if
    if (status == factor_singular) then
      call set_aside_or_stop(eq, m, cs, dm, bad, usable)
      return
    end if
    if (status == factor_fallback) then
      call tell_note(obs, sys%note)
      call warn(sys%note)
    end if
    call describe(eq, is, cs, sys, obs)
    eq%factor_states = status_codes(cs)
    eq%factor_stabilised = cs%stabilised
    eq%factor_valid = .true.
  end subroutine factor_if_needed

  !> The stiffness of the current status, assembled and factored (timed,
  !> counted).
  subroutine assemble_and_factor(eq, m, body, cs, dm, u, sys, status, bad, converged)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    type(body_t), intent(inout) :: body
    type(contact_set_t), intent(in) :: cs
    type(dofmap_t), intent(in) :: dm
    real(dp), intent(in) :: u(:, :)
    type(linear_system_t), intent(inout) :: sys
    integer, intent(out) :: status, bad
    logical, intent(in) :: converged          ! u is the converged state (assemble_stiffness)
    real(dp) :: t0, t1
    t0 = wall_time()
    call assemble_stiffness(m, cs, body, u, sys, eq%kmax, eq%counts, dm, converged)
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
end module equilibrium
