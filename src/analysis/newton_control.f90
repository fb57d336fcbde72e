!> Newton's method on the equilibrium of a nonlinear increment as
!> CalculiX decides it: the state of the iteration (newton_t), its
!> convergence and divergence tests with the step's *CONTROLS
!> (newton_test), and every reason for which an increment is given up
!> and cut back, with its message and cut factor (newton_give_up): the one
!> place where a failure of the iteration is worded.
module newton_control
  use kinds, only: dp
  use strings, only: itoa
  use model, only: controls_t
  implicit none
  private
  public :: newton_t, newton_begin, newton_test, newton_converged, newton_new_step, newton_give_up, &
            converged_body_forces, converged_forces_at

  !> Why an increment is given up (newton_give_up): CalculiX's tests
  !> (diverged, no_convergence, too_slow) and the iteration's own stops.
  integer, parameter, public :: diverged = 1, no_convergence = 2, too_slow = 3, bad_element = 4, &
                                tangent_overflow = 5, singular_tangent = 6, not_finite = 7, &
                                status_cycle = 8, not_settled = 9, not_condensable = 10

  !> The state of the Newton iteration of a nonlinear increment and its
  !> tests (CalculiX's manual, "Convergence criteria" and *CONTROLS, with
  !> its default constants): the reference force q-tilde is the average
  !> force q-bar (the mean |f| over the element dofs) averaged over the
  !> converged increments of the step and the current iteration (a new
  !> step starts from the average of the steps before); the largest
  !> residual force r_max of the last three iterations; why the increment
  !> failed: reason, and the factor to cut it by: cut.
  type :: newton_t
    real(dp) :: q_sum = 0.0_dp          ! sum of q-bar over the converged increments counted in q_count
    integer :: q_count = 0
    real(dp) :: q_last = 0.0_dp         ! q-bar of the last iteration
    real(dp) :: r(3) = 0.0_dp           ! r_max of iterations i, i-1, i-2
    integer :: it = 0                   ! Newton iterations since the last contact status change
    !> iterations of this attempt at the increment, and those of them that
    !> changed a contact status (each one adds an iteration to I_C, as
    !> CalculiX does for node-to-face contact)
    integer :: attempt = 0, changes = 0
    integer :: total = 0                ! Newton iterations of the step (all increments, cut ones too)
    real(dp) :: cut = 1.0_dp            ! when the increment failed: the factor to cut it by
    character(len=:), allocatable :: reason
    type(controls_t) :: ctl             ! the step's *CONTROLS
    logical :: singular = .false.       ! the last factorisation of the tangent was singular
    !> The predictor's correction (equilibrium_loop's
    !> extrapolate_predictor): the first iteration's step of the last
    !> increment (pred), and what the later iterations added to it over
    !> its squared length in the last two converged increments in turn
    !> without a status change (curv, curv_before; ncurv of them hold).
    real(dp), allocatable :: pred(:, :), curv(:, :), curv_before(:, :)
    integer :: ncurv = 0
    !> The bodies' internal forces fconv at the displacements uconv of the
    !> last converged increment, of its last iteration (the next
    !> predictor's f_int(u0) where u0 is uconv: assembly's
    !> body_predictor_forces), when have_fconv.
    real(dp), allocatable :: fconv(:, :), uconv(:, :)
    logical :: have_fconv = .false.
  end type newton_t


contains

  !> Purpose: the start of a nonlinear increment's Newton iteration.
  subroutine newton_begin(nt)
    type(newton_t), intent(inout) :: nt
    nt%singular = .false.
    nt%attempt = 0
    nt%changes = 0
    nt%r = 0.0_dp
    nt%it = 0
    nt%cut = 1.0_dp
    nt%reason = ''
  end subroutine newton_begin

  !> Purpose: CalculiX's convergence test of Newton iteration nt%it (its
  !> manual, "Convergence criteria"): q-bar the average force of this
  !> iteration, r_max the largest residual force on a free dof, c_max the
  !> largest correction of this iteration, du_max the largest change of
  !> the increment so far; the constants are the step's *CONTROLS
  !> (nt%ctl, model's controls_t, CalculiX's names). The reference force
  !> q-tilde is the mean of q-bar over the converged increments of the
  !> step and this iteration (newton_t), or q_u if given. Converged when r_max <= c1 q-tilde and one
  !> of: c_max <= c2 du_max; the estimate of the next correction
  !> r_max c_max / min(r_{i-1}, r_{i-2}) < c2 du_max; r_max <= R_l
  !> q-tilde (a linear increment); zero force; c_max < 1e-8 of the
  !> displacement scale. Otherwise nt%cut and nt%reason say whether to cut
  !> the increment back: divergence (from I_0 on, r_max grew twice: D_F)
  !> or too slow (from I_R on, the estimated iterations exceed I_C, or the
  !> attempt's iterations reach I_C plus one for each iteration that
  !> changed a contact status: D_C); the counts of I_0 and I_R start again
  !> after a status change (CalculiX's rule for node-to-face contact);
  !> nt%cut = 1 means iterate on. The returned ratio is
  !> r_max / q-tilde (the listing's residual).
  subroutine newton_test(nt, qbar, r_max, c_max, du_max, converged, ratio)
    type(newton_t), intent(inout) :: nt
    real(dp), intent(in) :: qbar, r_max, c_max, du_max
    logical, intent(out) :: converged
    real(dp), intent(out) :: ratio
    real(dp) :: q, c1, c2, est
    integer :: i
    nt%q_last = qbar
    q = max((nt%q_sum + qbar) / (nt%q_count + 1), tiny(1.0_dp))
    if (nt%ctl%qu > 0.0_dp) q = nt%ctl%qu
    nt%r = [r_max, nt%r(1), nt%r(2)]
    i = nt%it
    if (qbar > nt%ctl%eps * q) then
      c1 = nt%ctl%rn
      if (i > nt%ctl%ip) c1 = nt%ctl%rp
      c2 = nt%ctl%cn
    else
      c1 = nt%ctl%eps
      c2 = nt%ctl%ceps
    end if
    ratio = r_max / q
    converged = .false.
    nt%cut = 1.0_dp
    if (r_max <= c1 * q) then
      converged = c_max <= c2 * du_max .or. r_max <= nt%ctl%rl * q .or. qbar <= nt%ctl%eps * q .or. &
                  c_max <= 1.0e-8_dp * max(du_max, tiny(1.0_dp))
      if (.not. converged .and. i >= 3) then
        if (min(nt%r(2), nt%r(3)) > 0.0_dp) converged = r_max * c_max / min(nt%r(2), nt%r(3)) < c2 * du_max
      end if
      if (converged) return
    end if
    if (i >= nt%ctl%i0 .and. r_max > 1.0e-20_dp .and. c_max > 1.0e-20_dp .and. nt%r(2) > nt%r(3) .and. &
        r_max > nt%r(3) .and. r_max > c1 * q) then
      call newton_give_up(nt, diverged)
      return
    end if
    if (nt%attempt >= nt%ctl%ic + nt%changes) then
      call newton_give_up(nt, no_convergence)
      return
    end if
    if (i >= nt%ctl%ir .and. nt%r(2) > 0.0_dp .and. r_max < nt%r(2) .and. r_max > 0.0_dp) then
      est = i + log(nt%ctl%rn * q / r_max) / log(r_max / nt%r(2))
      if (est > nt%ctl%ic) then
        call newton_give_up(nt, too_slow)
      end if
    end if
  end subroutine newton_test

  !> Purpose: a converged increment: its average force joins the step's
  !> time average.
  subroutine newton_converged(nt)
    type(newton_t), intent(inout) :: nt
    nt%q_sum = nt%q_sum + nt%q_last
    nt%q_count = nt%q_count + 1
  end subroutine newton_converged

  !> Purpose: the bodies' forces fbody of the last iteration of the
  !> increment that converged at u, kept for the next increment's
  !> predictor (newton_t's fconv).
  subroutine converged_body_forces(nt, u, fbody)
    type(newton_t), intent(inout) :: nt
    real(dp), intent(in) :: u(:, :), fbody(:, :)
    nt%uconv = u
    nt%fconv = fbody
    nt%have_fconv = .true.
  end subroutine converged_body_forces

  !> Purpose: does nt hold the bodies' forces of the converged state u0
  !> (the last converged increment's, kept by converged_body_forces)?
  logical function converged_forces_at(nt, u0) result(yes)
    type(newton_t), intent(in) :: nt
    real(dp), intent(in) :: u0(:, :)
    yes = .false.
    if (.not. (nt%have_fconv .and. allocated(nt%uconv))) return
    if (any(shape(nt%uconv) /= shape(u0))) return
    yes = all(nt%uconv == u0)
  end function converged_forces_at

  !> Purpose: a new step starts from the time average of the steps
  !> before (one sample of it), CalculiX's q_0, with its *CONTROLS ctl.
  subroutine newton_new_step(nt, ctl)
    type(newton_t), intent(inout) :: nt
    type(controls_t), intent(in) :: ctl
    nt%ctl = ctl
    nt%ncurv = 0
    nt%have_fconv = .false.
    if (nt%q_count > 0) then
      nt%q_sum = nt%q_sum / nt%q_count
      nt%q_count = 1
    end if
    nt%total = 0
  end subroutine newton_new_step

  !> Purpose: the increment is given up: nt%reason says why and nt%cut
  !> by how much to cut it back (CalculiX's D_F for a diverging or broken
  !> iteration, D_C for a slow one or a contact status that does not
  !> settle).
  !> Arguments: why one of the codes above; detail what the message
  !> names: the element (bad_element), where the tangent is singular
  !> (singular_tangent: ' at node N, dof D' or empty), the iterations
  !> allowed (not_settled).
  subroutine newton_give_up(nt, why, detail)
    type(newton_t), intent(inout) :: nt
    integer, intent(in) :: why
    character(len=*), intent(in), optional :: detail
    character(len=:), allocatable :: d
    d = ''
    if (present(detail)) d = detail
    ! the correction of an increment given up is not the path's, and its
    ! iterations left the bodies' forces of another state
    nt%ncurv = 0
    nt%have_fconv = .false.
    nt%cut = nt%ctl%df
    select case (why)
    case (diverged)
      nt%reason = 'the residual force grew in two successive iterations (divergence)'
    case (no_convergence)
      nt%cut = nt%ctl%dc
      nt%reason = 'no convergence in ' // itoa(nt%attempt) // ' iterations'
    case (too_slow)
      nt%cut = nt%ctl%dc
      nt%reason = 'convergence too slow (' // itoa(nt%ctl%ic) // ' iterations would not do)'
    case (bad_element)
      nt%reason = 'element ' // d // ' is inverted or cannot be evaluated at the displacements of the iteration'
    case (tangent_overflow)
      ! entries this large sum to overflow in the assembled matrix
      nt%reason = 'the tangent stiffness overflows (an element entry beyond 1e250: a thickness, modulus or ' // &
                  'displacement out of range?)'
    case (singular_tangent)
      nt%reason = 'the tangent stiffness is singular' // d // ' (a limit load, or a missing support)'
    case (not_finite)
      nt%reason = 'the displacements are not finite numbers'
    case (not_condensable)
      nt%cut = nt%ctl%dc
      nt%reason = 'the contact couplings the search found leave no contact equation to condense'
    case (status_cycle)
      nt%cut = nt%ctl%dc
      nt%reason = 'the contact status cycles (the same statuses and out-of-balance every second iteration)'
    case default
      nt%cut = nt%ctl%dc
      nt%reason = 'the contact status did not settle in ' // d // ' iterations'
    end select
  end subroutine newton_give_up
end module newton_control
