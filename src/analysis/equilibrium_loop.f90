!> The equilibrium iteration of one increment, as the algorithm reads
!> (docs/architecture.md, "The equilibrium iteration"): a loop of named
!> steps over the iteration state (iteration_t), the same for every way
!> of solving a contact status's linear system (a linear_path_t: module
!> equilibrium's full path, condensed_equilibrium's condensed one). Each
!> iteration factors the matrix of the current status (unless the factor
!> in hand is for it), solves and updates the displacements, searches
!> the contact again (NLGEOM), makes one pivot of the contact status
!> search (contact_status), and judges the out-of-balance; a settled
!> status leaves the stabilised search, then augments the multipliers
!> (exact enforcement), then has converged. In a nonlinear step the same
!> loop is Newton's method: its decisions (predictor, CalculiX's tests,
!> the verdicts that give an increment up) are the routines of the last
!> section, its messages newton_control's.
module equilibrium_loop
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  use strings, only: itoa
  use model, only: elem_label, node_label, model_t
  use contact, only: contact_set_t
  use contact_status, only: contact_switch, begin_status_search, contact_energy, augment_multipliers, max_augmentations, &
                            status_search_t
  use dof_numbering, only: dofmap_t, expand_dependent, follow_rotations
  use equilibrium_common, only: report_iteration, contact_force_scale, take_back, next_stage
  use newton_control, only: newton_t, newton_begin, newton_test, newton_converged, newton_give_up, bad_element, &
                            tangent_overflow, singular_tangent, not_finite, status_cycle, not_settled
  use contact_repairing, only: search_in_iteration, coupling_length, numbering_fits
  use iteration_state, only: iteration_t, linear_path_t, go_on, again, give_up
  use analysis_events, only: tell_note
  use messages, only: fatal
  implicit none
  private
  public :: iterate

  !> The largest element tangent entry a nonlinear step accepts.
  real(dp), parameter :: tangent_limit = 1.0e250_dp

contains

  !> Purpose: the equilibrium of the increment whose problem st holds
  !> (solve_increment), by path. On return ok says whether it converged,
  !> iters the iterations used; where it failed in a nonlinear step,
  !> eq%newton%cut and reason say how much to cut the increment back and
  !> why. MAXIT (m%contact_max_iter) counts the iterations of each
  !> status search.
  subroutine iterate(path, st, ok, iters)
    class(linear_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    logical, intent(out) :: ok
    integer, intent(out) :: iters
    ok = .false.
    call begin_increment(path, st)
    do while (st%eq%search%iterations < st%m%contact_max_iter)
      st%it = st%it + 1
      st%verdict = go_on
      call tangent_and_factor(path, st)
      if (st%verdict == again) cycle
      if (st%verdict == give_up) exit
      call solve_and_update(path, st)
      if (st%verdict == give_up) exit
      if (.not. path%searches_itself) call search_again(st)
      call turn_rigid_bodies(st)
      call pivot_statuses(path, st)
      call residual_and_convergence(path, st)
      if (st%verdict == give_up) exit
      call report_iteration(st%eq, st%cs, st%obs, st%it, st%nchanged)
      call watch_for_cycles(st)
      if (st%verdict == give_up) exit
      if (leave_stabilised_search(path, st)) cycle
      if (augment(path, st)) cycle
      if (st%nchanged == 0 .and. st%converged) then
        call increment_converged(path, st)
        ok = .true.
        exit
      end if
    end do
    ! the increment control counts Newton iterations (each with its pivot
    ! on the full path), not the inner status pivots of the condensed one
    iters = st%it - st%ninner
    if (.not. ok) call give_up_unsettled(st)
  end subroutine iterate

  !> The start of the increment: no stabilisation yet, the dependent dofs
  !> from the independent ones, Newton's start, the path's, a new status
  !> search.
  subroutine begin_increment(path, st)
    class(linear_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    st%cs%stabilised = .false.
    st%eq%stabilisation_used = .false.
    st%fext_norm = norm2(st%fext)
    st%research = associated(st%presc) .and. associated(st%mpc)
    allocate(st%closed1(0), st%closed2(0))
    call expand_dependent(st%dm, st%u)
    call turn_rigid_bodies(st)
    if (st%body%nonlinear) call newton_start(st)
    call path%begin(st)
    ! the equations must be numbered for the couplings in hand (a cut-back
    ! restores both: the driver)
    if (st%research .and. .not. numbering_fits(st%eq, st%m, st%cs)) call fatal('internal error: the equations ' // &
      'are not numbered for the contact couplings of the increment')
    call begin_status_search(st%eq%search)
    st%it = 0
    st%naug = 0
  end subroutine begin_increment

  !> Step: the matrix of the current status factored (in a nonlinear
  !> step, Newton's tangent at u, every iteration). A status whose matrix
  !> is singular after a pivot of the search is taken back (again).
  subroutine tangent_and_factor(path, st)
    class(linear_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    if (st%body%nonlinear) call newton_before_factor(path, st)
    if (st%verdict == give_up) return
    call path%factor(st)
    if (st%body%nonlinear) call newton_after_factor(st)
    if (st%verdict == give_up) return
    if (.not. st%usable) then
      call take_back(st%eq, st%m, st%cs, st%dm, st%obs)
      call path%status_changed(st)
      st%verdict = again
      return
    end if
    if (st%restabilised) call path%status_changed(st)
  end subroutine tangent_and_factor

  !> Step: the status's system solved, u updated (a nonlinear step gives
  !> the increment up on a displacement that is not finite).
  subroutine solve_and_update(path, st)
    class(linear_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    call path%solve(st)
    if (st%body%nonlinear) then
      ! (the condensed Newton path's first solves move only the contact equations)
      if (st%it == 1 .and. st%predict .and. path%newton_refactors) call extrapolate_predictor(st)
      if (.not. all(ieee_is_finite(st%u))) call give_up_increment(st, not_finite)
    end if
  end subroutine solve_and_update

  !> Purpose: the first iteration's predictor step (u moved from the
  !> converged state by the tangent's response to the prescribed motion)
  !> extrapolated with the path's curvature: the predictor's error is the
  !> second-order term of the path, (1/2) u'' dt^2, and each converged
  !> increment measures it as what its later iterations added to its
  !> predictor step, c, over the step's squared length s^2. Where the last
  !> two increments measured the same curvature (c / s^2 of the one
  !> before within a cosine of 0.9 and a factor of 2 of the last one's:
  !> a smooth path, not the kink of a first yield or a contact change)
  !> and this predictor step points the way of the last one (cosine above
  !> 0.99: not at a reversal of the load), s^2 times the last curvature is
  !> added to the free equations. A better first iterate, nothing else:
  !> the residual and Newton's tests decide convergence as before (the
  !> O-ring: 48 Newton iterations instead of 64, most increments
  !> converging in two).
  subroutine extrapolate_predictor(st)
    type(iteration_t), intent(inout) :: st
    real(dp), allocatable :: step(:, :)
    real(dp) :: s2
    step = st%u - st%u_start
    st%u_pred = st%u
    associate(nt => st%eq%newton)
      s2 = sum(step**2)
      if (smooth_path(nt, step)) then
        where (st%dm%eq > 0) st%u = st%u + s2 * nt%curv
        call expand_dependent(st%dm, st%u)
        st%c_max = max(st%c_max, s2 * maxval(abs(nt%curv)))
      end if
      nt%pred = step
    end associate
  end subroutine extrapolate_predictor

  !> Purpose: may this increment's predictor step, step, be extrapolated
  !> with the curvature the last two increments measured
  !> (extrapolate_predictor says when)?
  pure logical function smooth_path(nt, step) result(ok)
    type(newton_t), intent(in) :: nt
    real(dp), intent(in) :: step(:, :)
    real(dp) :: c1, c2, p
    ok = .false.
    if (nt%ncurv < 2 .or. .not. allocated(nt%pred)) return
    if (any(shape(nt%pred) /= shape(step)) .or. any(shape(nt%curv) /= shape(step))) return
    c1 = norm2(nt%curv)
    c2 = norm2(nt%curv_before)
    p = norm2(nt%pred) * norm2(step)
    if (c1 <= 0.0_dp .or. c2 <= 0.0_dp .or. p <= 0.0_dp) return
    if (sum(step * nt%pred) <= 0.99_dp * p) return
    if (c1 > 2.0_dp * c2 .or. c2 > 2.0_dp * c1) return
    ok = sum(nt%curv * nt%curv_before) > 0.9_dp * c1 * c2
  end function smooth_path

  !> Step (NLGEOM with contact): the contact searched again on the updated
  !> configuration. The search follows an iterate whose correction is
  !> smaller than the couplings' mesh length; a larger one (an iterate far
  !> from equilibrium: a body falling through under a stabilised open
  !> penalty, a wild first iterate of a soft body) keeps the pairing,
  !> whose master normals would otherwise come from a wildly deformed
  !> master. An increment converges only in an iteration that searched.
  subroutine search_again(st)
    type(iteration_t), intent(inout) :: st
    st%nsearched = 0
    st%searched = .false.
    if (.not. st%research) return
    if (st%c_max >= coupling_length(st%cs)) return
    call search_in_iteration(st%eq, st%m, st%cs, st%u, st%presc, st%mpc, st%dm, st%sys, st%nsearched)
    st%searched = .true.
  end subroutine search_again

  !> Step (NLGEOM): rigid bodies and kinematic couplings turned exactly,
  !> T at the current rotation (dof_numbering's follow_rotations); after
  !> the search, whose renumbering would reset the constraints' T.
  subroutine turn_rigid_bodies(st)
    type(iteration_t), intent(inout) :: st
    if (st%body%nlgeom) call follow_rotations(st%dm, st%u)
  end subroutine turn_rigid_bodies

  !> Step: one pivot of the contact status search on the potential energy
  !> of this status's solution, eqs. (1) and (9); the statuses the search
  !> itself changed (couplings that came closed or were lost) count as
  !> changes too: the increment has not settled either.
  subroutine pivot_statuses(path, st)
    class(linear_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    call path%solution_energy(st)
    st%energy = st%energy + contact_energy(st%cs)
    call contact_switch(st%m, st%cs, st%eq%search, contact_force_scale(st%eq, st%cs, st%fext_norm), st%energy, &
                        st%nchanged, st%eq%changed)
    st%nchanged = st%nchanged + st%nsearched
  end subroutine pivot_statuses

  !> Step: the path made its settled solution better (condensed: the
  !> refinement of a status decided on an unrefined low-rank solution)
  !> and asks for its statuses to be judged again there (st%energy, the
  !> CFEs evaluated): one more pivot of the search, which is left as the
  !> first pivot left it where nothing changes; the path's rejudged makes
  !> the out-of-balance (of the change, or of the settled status).
  subroutine rejudge(path, st)
    class(linear_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    type(status_search_t) :: kept
    st%rejudge = .false.
    kept = st%eq%search
    call contact_switch(st%m, st%cs, st%eq%search, contact_force_scale(st%eq, st%cs, st%fext_norm), st%energy, &
                        st%nchanged, st%eq%changed)
    if (st%nchanged == 0) st%eq%search = kept
    call path%rejudged(st)
  end subroutine rejudge

  !> Step: the out-of-balance of the new status and whether it passes the
  !> test (a linear step: below the contact tolerance; a nonlinear one:
  !> CalculiX's tests, newton_judge).
  subroutine residual_and_convergence(path, st)
    class(linear_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    call path%residual(st)
    if (st%rejudge) call rejudge(path, st)
    st%eq%iterations = st%eq%iterations + 1
    if (st%body%nonlinear) then
      call newton_judge(st)
    else
      st%converged = st%eq%residual < st%m%contact_tolerance
    end if
  end subroutine residual_and_convergence

  !> Step: settled while stabilised: where the stabilisation, not the
  !> contact, still holds the body, another stage of it from where the
  !> body came to rest (equilibrium_common's next_stage; the same factor);
  !> otherwise a new search with the nominal open penalty (true if either).
  logical function leave_stabilised_search(path, st) result(left)
    class(linear_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    left = st%nchanged == 0 .and. st%cs%stabilised
    if (.not. left) return
    if (next_stage(st%eq, st%cs, contact_force_scale(st%eq, st%cs, st%fext_norm), st%obs)) then
      call path%restart(st)
      return
    end if
    st%cs%stabilised = .false.
    call begin_status_search(st%eq%search)
    call path%restart(st)
    call tell_note(st%obs, 'contact status settled with the stabilised open penalty; iterating on with the ' // &
                           'nominal one')
  end function leave_stabilised_search

  !> Step: settled and in balance: exact enforcement updates the
  !> multipliers and searches again (true if so).
  logical function augment(path, st) result(done)
    class(linear_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    done = .false.
    if (st%nchanged /= 0 .or. .not. st%converged .or. .not. path%augmented) return
    if (st%naug >= max_augmentations) return
    if (.not. augment_multipliers(st%cs, contact_force_scale(st%eq, st%cs, st%fext_norm))) return
    st%naug = st%naug + 1
    call path%restart(st)
    call begin_status_search(st%eq%search)
    done = .true.
  end function augment

  !> The increment has converged: what the path keeps, the force scale of
  !> the history, Newton's average force.
  subroutine increment_converged(path, st)
    class(linear_path_t), intent(inout) :: path
    type(iteration_t), intent(inout) :: st
    call path%converged(st)
    st%eq%force_history = max(st%eq%force_history, st%scale)
    if (st%body%nonlinear) call newton_converged(st%eq%newton)
    if (st%body%nonlinear) call measure_curvature(st)
  end subroutine increment_converged

  !> The path's curvature the converged increment measured (what its
  !> iterations added to its predictor step over the step's squared
  !> length: extrapolate_predictor); an increment that changed a contact
  !> status, or had no predictor step, measures none and starts the count
  !> again.
  subroutine measure_curvature(st)
    type(iteration_t), intent(inout) :: st
    real(dp) :: s2
    associate(nt => st%eq%newton)
      s2 = 0.0_dp
      if (allocated(st%u_pred) .and. allocated(nt%pred)) s2 = sum(nt%pred**2)
      if (nt%changes > 0 .or. s2 <= 0.0_dp) then
        nt%ncurv = 0
        return
      end if
      if (nt%ncurv > 0) nt%curv_before = nt%curv
      nt%curv = (st%u - st%u_pred) / s2
      nt%ncurv = min(nt%ncurv + 1, 2)
    end associate
  end subroutine measure_curvature

  ! ---- Newton's decisions (nonlinear steps) ----

  !> The start of a Newton increment: the counters of newton_t, the
  !> displacements of the increment's start and the predictor (u differs
  !> from the converged state u_from: the first iteration is linearised
  !> about u_from).
  subroutine newton_start(st)
    type(iteration_t), intent(inout) :: st
    call newton_begin(st%eq%newton)
    if (associated(st%u_from)) then
      st%u_start = st%u_from
      st%predict = any(st%u /= st%u_from)
    else
      st%u_start = st%u
    end if
  end subroutine newton_start

  !> Before the factorisation: an element that could not be evaluated
  !> gives the increment up; the tangent is that at the current u (the
  !> condensed Newton path says itself when it makes a new one).
  subroutine newton_before_factor(path, st)
    class(linear_path_t), intent(in) :: path
    type(iteration_t), intent(inout) :: st
    if (st%body%bad_elem > 0) then
      call give_up_increment(st, bad_element, elem_label(st%m, st%body%bad_elem))
      return
    end if
    if (path%newton_refactors) st%eq%factor_valid = .false.
  end subroutine newton_before_factor

  !> After it: a tangent whose entries would overflow, or a singular one
  !> (a limit load, a buckling state, a missing support), gives the
  !> increment up.
  subroutine newton_after_factor(st)
    type(iteration_t), intent(inout) :: st
    if (st%eq%kmax > tangent_limit) then
      call give_up_increment(st, tangent_overflow)
    else if (.not. st%usable .and. st%eq%newton%singular) then
      call give_up_increment(st, singular_tangent, singular_where(st%m, st%dm, st%eq%bad))
    end if
  end subroutine newton_after_factor

  !> Purpose: CalculiX's test of the iteration (newton_test: the force and
  !> correction criteria; its counts start again after a status change)
  !> and its verdict: a cut-back from it gives the increment up once the
  !> status has settled or the attempt has used its iterations. An inner
  !> iteration of the condensed Newton path (st%inner: a status pivot on
  !> the linearised problem) is no Newton iteration: nothing is judged.
  subroutine newton_judge(st)
    type(iteration_t), intent(inout) :: st
    st%converged = .false.
    if (st%inner) then
      st%ninner = st%ninner + 1
      return
    end if
    associate(nt => st%eq%newton)
      nt%it = nt%it + 1
      nt%attempt = nt%attempt + 1
      nt%total = nt%total + 1
      if (st%nchanged > 0) then
        nt%it = 0
        nt%changes = nt%changes + 1
      end if
      st%converged = .false.
      if (st%body%bad_elem /= 0) return
      call newton_test(nt, st%body%average_force, max_free(st%dm, st%rf), st%c_max, &
                       maxval(abs(st%u - st%u_start)), st%converged, st%eq%residual)
      if (st%research .and. .not. st%searched) st%converged = .false.
      if (nt%cut < 1.0_dp .and. (st%nchanged == 0 .or. nt%attempt >= nt%ctl%ic + nt%changes)) &
        st%verdict = give_up
    end associate
  end subroutine newton_judge

  !> Step of a nonlinear step that changed a status: the statuses and the
  !> out-of-balance of two iterations back again mean that the Newton
  !> iterates cycle (a coupling closing and opening in turn, as under a
  !> penalty far stiffer than a soft body) and would do so until MAXIT;
  !> the increment is given up now.
  subroutine watch_for_cycles(st)
    type(iteration_t), intent(inout) :: st
    if (.not. st%body%nonlinear .or. st%nchanged == 0) return
    if (status_cycles(st%cs, st%closed2, st%res2, st%eq%residual)) then
      call give_up_increment(st, status_cycle)
      return
    end if
    st%closed2 = st%closed1
    st%res2 = st%res1
    st%closed1 = st%cs%c(1:st%cs%n)%closed
    st%res1 = st%eq%residual
  end subroutine watch_for_cycles

  !> The loop ended without convergence: a nonlinear increment not given
  !> up already is given up for a status that did not settle in MAXIT.
  subroutine give_up_unsettled(st)
    type(iteration_t), intent(inout) :: st
    if (st%body%nonlinear .and. st%eq%newton%cut >= 1.0_dp) &
      call give_up_increment(st, not_settled, itoa(st%m%contact_max_iter))
  end subroutine give_up_unsettled

  !> The increment is given up (newton_give_up words why).
  subroutine give_up_increment(st, why, detail)
    type(iteration_t), intent(inout) :: st
    integer, intent(in) :: why
    character(len=*), intent(in), optional :: detail
    call newton_give_up(st%eq%newton, why, detail)
    st%verdict = give_up
  end subroutine give_up_increment

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
end module equilibrium_loop
