!> The driver of a run: steps, increments and their bisection or
!> cut-back, over a list of fields (analysis_field: the displacements,
!> displacement_field; the temperatures, temperature_field; or both,
!> the temperatures first, in a coupled run). Everything else is data handed to
!> the layers that own it: a field owns its unknowns, equations, solve,
!> history and results; the observers that write them
!> (analysis_events) are told what happens. Within an increment the
!> fields are solved in the order of the list (a field may read the
!> converged values of the ones before it: a staggered coupling), and an
!> increment is done when every field has converged. In a coupled run
!> (model's coupled) a step takes part with the fields its procedure
!> names (a *HEAT TRANSFER step the temperatures, a *STATIC step the
!> displacements, a *COUPLED TEMPERATURE-DISPLACEMENT step both); the
!> displacements take the temperatures once they are solved
!> (hand_temperatures: a staggered coupling per increment, docs/heat.md)
!> and report the increment's results of both.
module analysis
  use kinds, only: dp
  use strings, only: itoa, rtoa
  use model, only: model_t, step_t
  use analysis_field, only: field_ref_t
  use displacement_field, only: displacement_field_t
  use temperature_field, only: temperature_field_t
  use frequency_step, only: run_frequency_step
  use analysis_events, only: observer_ref_t, step_info_t, step_summary_t, run_timing_t, tell_note, wall_time
  use messages, only: fatal
  use contact_heat, only: contact_heat_t, contact_heat_build, has_contact_heat
  implicit none
  private
  public :: run_analysis

  !> The state the driver carries from increment to increment.
  type :: run_state_t
    type(field_ref_t), allocatable :: fields(:)   ! solved in this order in every increment
    !> The fields that take part in the current step (a coupled run's
    !> heat transfer or mechanical step has one of its two).
    logical, allocatable :: active(:)
    real(dp) :: total_time = 0.0_dp     ! at the start of the current step
    integer :: inc = 0                  ! increments done in the current step
    !> The current step has a nonlinear field: Newton with automatic
    !> increments (advance_automatic).
    logical :: nonlinear = .false.
    integer :: cutbacks = 0             ! increments cut back in the current step
    integer :: failed = 0               ! the field whose solve failed last (solve_fields; 0: the passes)
    !> Heat through the contact (a coupled run): the fields' solves are
    !> repeated in each increment until the temperatures settle (passes).
    logical :: contact_heat = .false.
    integer :: passes = 0
    type(run_timing_t) :: timing        ! where the run's time went
  end type run_state_t

  !> An interval of step time still to be solved, its bisection depth,
  !> how many times a converged increment was split to make it, whether
  !> it is a sub-increment (quiet: committed, not reported) and the step
  !> time its reported increment starts from (start: t0 but for the last
  !> part of a split increment).
  type :: interval_t
    real(dp) :: t0 = 0.0_dp, t1 = 0.0_dp
    integer :: level = 0, splits = 0
    logical :: quiet = .false.
    real(dp) :: start = 0.0_dp
  end type interval_t

  !> A converged increment a field wants split (field_t's split_wanted: a
  !> frictional contact zone that grew too far in it) is split at most
  !> this many times (to 1/1024 of it), and never below the minimum
  !> increment of a nonlinear step.
  integer, parameter :: max_splits = 10

  !> Passes of a coupled increment with heat through the contact: at most
  !> max_passes, done when no temperature changes by more than
  !> coupling_tolerance of the largest (at least 1) between two.
  integer, parameter :: max_passes = 50
  real(dp), parameter :: coupling_tolerance = 1.0e-9_dp

contains

  !> Purpose: runs every step of model m, telling the observers obs what
  !> happens.
  !> Arguments: timing, if present, holds what the program spent before
  !> the analysis (reading, opening the writers; its start time) and is
  !> completed and handed to the observers' run_finished at the end.
  subroutine run_analysis(m, obs, timing)
    type(model_t), intent(in) :: m
    type(observer_ref_t), intent(in) :: obs(:)
    type(run_timing_t), intent(inout), optional :: timing
    type(run_state_t) :: rs
    integer :: is, k
    if (present(timing)) rs%timing = timing
    if (rs%timing%started == 0.0_dp) rs%timing%started = wall_time()
    ! the fields of the run: the temperatures in a heat transfer deck,
    ! both in a coupled one, the temperatures first
    if (m%coupled) then
      allocate(rs%fields(2))
      allocate(temperature_field_t :: rs%fields(1)%f)
      allocate(displacement_field_t :: rs%fields(2)%f)
    else
      allocate(rs%fields(1))
      if (m%heat) then
        allocate(temperature_field_t :: rs%fields(1)%f)
      else
        allocate(displacement_field_t :: rs%fields(1)%f)
      end if
    end if
    allocate(rs%active(size(rs%fields)))
    rs%active = .true.
    rs%contact_heat = m%coupled .and. has_contact_heat(m)
    do k = 1, size(rs%fields)
      call rs%fields(k)%f%setup(m, rs%timing)
    end do
    do is = 1, size(m%steps)
      call run_step(m, is, rs, obs)
      rs%total_time = rs%total_time + m%steps(is)%period
    end do
    call finish(rs, obs)
    if (present(timing)) timing = rs%timing
  end subroutine run_analysis

  !> The run's timing: the driver's parts and the fields', to every
  !> observer (the output of this last event is not in it).
  subroutine finish(rs, obs)
    type(run_state_t), intent(inout) :: rs
    type(observer_ref_t), intent(in) :: obs(:)
    integer :: k
    do k = 1, size(rs%fields)
      call rs%fields(k)%f%finish(rs%timing)
    end do
    rs%timing%total = wall_time() - rs%timing%started
    do k = 1, size(obs)
      call obs(k)%o%run_finished(rs%timing)
    end do
  end subroutine finish

  !> Purpose: one step: every field's loads and equations, its
  !> increments, its summary.
  subroutine run_step(m, is, rs, obs)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is
    type(run_state_t), intent(inout) :: rs
    type(observer_ref_t), intent(in) :: obs(:)
    type(step_info_t) :: info
    type(step_summary_t) :: summary
    integer :: i, ninc, k
    real(dp) :: t0, started
    ! a *FREQUENCY step: the modes about the state the steps before leave
    if (m%steps(is)%frequency) then
      call run_frequency_step(m, is, rs%fields(1)%f, obs, rs%total_time, rs%timing)
      return
    end if
    started = wall_time()
    rs%nonlinear = .false.
    if (m%coupled) rs%active = [m%steps(is)%heat, m%steps(is)%coupled .or. .not. m%steps(is)%heat]
    do k = 1, size(rs%fields)
      if (.not. rs%active(k)) cycle
      call rs%fields(k)%f%begin_step(m, is, rs%total_time, info, rs%timing)
      rs%nonlinear = rs%nonlinear .or. rs%fields(k)%f%nonlinear()
    end do
    rs%cutbacks = 0
    ninc = nint(m%steps(is)%period / m%steps(is)%dt)
    info%step = is
    info%period = m%steps(is)%period
    info%increments = ninc
    t0 = wall_time()
    do k = 1, size(obs)
      call obs(k)%o%step_started(m, info)
    end do
    do k = 1, size(rs%fields)
      if (rs%active(k)) call rs%fields(k)%f%step_notes(obs)
    end do
    rs%timing%output = rs%timing%output + (wall_time() - t0)
    rs%inc = 0
    if (rs%nonlinear) then
      call advance_automatic(m, is, rs, obs)
    else
      do i = 1, ninc
        call advance(m, is, rs, obs, m%steps(is)%period * (i - 1) / ninc, m%steps(is)%period * i / ninc)
      end do
    end if
    do k = 1, size(rs%fields)
      if (rs%active(k)) call rs%fields(k)%f%end_step(obs, summary)
    end do
    summary%step = is
    summary%increments = rs%inc
    summary%wall_seconds = wall_time() - started
    summary%nonlinear = rs%nonlinear
    summary%cutbacks = rs%cutbacks
    t0 = wall_time()
    do k = 1, size(obs)
      call obs(k)%o%step_finished(summary)
    end do
    rs%timing%output = rs%timing%output + (wall_time() - t0)
  end subroutine run_step

  !> Purpose: one attempt at the increment from step time t0 to t1: every
  !> field begins it and is solved in turn; ok when all converged, iters
  !> the iterations of the last field solved. With heat through the
  !> contact (a coupled run) the solves are repeated, each temperature
  !> solve with the contact's heat couplings of the last displacement
  !> solve (hand_contact_heat), until no temperature changes by more than
  !> coupling_tolerance of the largest (at least 1) from one pass to the
  !> next, at most max_passes times (docs/heat.md).
  !> Arguments: search_due, a contact search on the current configuration
  !> is due (begin_increment).
  subroutine solve_fields(m, is, rs, obs, t0, t1, search_due, ok, iters)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is
    type(run_state_t), intent(inout) :: rs
    type(observer_ref_t), intent(in) :: obs(:)
    real(dp), intent(in) :: t0, t1
    logical, intent(in) :: search_due
    logical, intent(out) :: ok
    integer, intent(out) :: iters
    integer :: k, pass
    real(dp), allocatable :: before(:)
    do k = 1, size(rs%fields)
      if (rs%active(k)) call rs%fields(k)%f%begin_increment(m, t0, t1, search_due, rs%timing)
    end do
    ok = .true.
    iters = 0
    rs%passes = 0
    do pass = 1, max_passes
      rs%passes = pass
      if (rs%contact_heat .and. rs%active(1)) before = hand_contact_heat(m, rs, t1 - t0)
      do k = 1, size(rs%fields)
        if (.not. rs%active(k)) cycle
        if (m%coupled .and. k == 2) call hand_temperatures(rs)
        call rs%fields(k)%f%solve(m, is, rs%inc + 1, obs, ok, iters)
        if (.not. ok) then
          rs%failed = k
          return
        end if
      end do
      if (.not. (rs%contact_heat .and. all(rs%active))) return
      if (pass > 1 .and. temperatures_settled(rs, before)) then
        call tell_note(obs, 'temperatures and contact settled in ' // itoa(pass) // ' passes of the two fields')
        return
      end if
    end do
    ok = .false.
    rs%failed = 0
  end subroutine solve_fields

  !> Purpose: a coupled run with heat through the contact: the contact's
  !> heat couplings of the displacement field's contact set as it was
  !> last evaluated (contact_heat_build; dt the increment's length) to the
  !> temperature field; the temperatures before its solve returned.
  function hand_contact_heat(m, rs, dt) result(temp)
    type(model_t), intent(in) :: m
    type(run_state_t), intent(inout) :: rs
    real(dp), intent(in) :: dt
    real(dp), allocatable :: temp(:)
    type(contact_heat_t) :: ch
    select type (tf => rs%fields(1)%f)
    type is (temperature_field_t)
      select type (df => rs%fields(2)%f)
      type is (displacement_field_t)
        call contact_heat_build(m, df%cs, dt, ch)
        call tf%take_contact_heat(m, ch)
        temp = tf%temp
      end select
    end select
  end function hand_contact_heat

  !> Purpose: has no temperature changed by more than coupling_tolerance
  !> of the largest (at least 1) since before (the last pass's)?
  logical function temperatures_settled(rs, before) result(settled)
    type(run_state_t), intent(in) :: rs
    real(dp), intent(in) :: before(:)
    settled = .true.
    select type (tf => rs%fields(1)%f)
    type is (temperature_field_t)
      settled = maxval(abs(tf%temp - before)) <= coupling_tolerance * max(1.0_dp, maxval(abs(tf%temp)))
    end select
  end function temperatures_settled

  !> Purpose: the increment converged: every field commits its history,
  !> and its results at step time t (increment length dt) go to the
  !> observers.
  subroutine increment_done(m, is, rs, obs, t, iters, dt)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is, iters
    type(run_state_t), intent(inout) :: rs
    type(observer_ref_t), intent(in) :: obs(:)
    real(dp), intent(in) :: t, dt
    integer :: k
    do k = 1, size(rs%fields)
      if (rs%active(k)) call rs%fields(k)%f%commit()
    end do
    rs%inc = rs%inc + 1
    do k = 1, size(rs%fields)
      if (.not. rs%active(k)) cycle
      ! (a coupled run's displacements report the temperatures with theirs)
      if (m%coupled .and. k == 1) then
        if (rs%active(2)) cycle
      end if
      call rs%fields(k)%f%report(m, is, rs%inc, t, rs%total_time + t, iters, dt, obs, rs%timing)
    end do
  end subroutine increment_done

  !> Purpose: a coupled run (fields temperatures, displacements): the
  !> temperatures of the increment's start and end, as the temperature
  !> field has them once solved (in a mechanical step, where it takes no
  !> part, those it last had), and its reaction fluxes, to the
  !> displacement field, whose thermal strain they make.
  subroutine hand_temperatures(rs)
    type(run_state_t), intent(inout) :: rs
    select type (tf => rs%fields(1)%f)
    type is (temperature_field_t)
      select type (df => rs%fields(2)%f)
      type is (displacement_field_t)
        if (rs%active(1)) then
          call df%take_temperatures(tf%saved, tf%temp, tf%rfl)
        else
          call df%take_temperatures(tf%temp, tf%temp, 0.0_dp * tf%rfl)
        end if
      end select
    end select
  end subroutine hand_temperatures

  !> Purpose: the increment failed: every field back to the state it
  !> started from; reason, cut and changing those of the field that
  !> failed (field_t's failure).
  subroutine restore_fields(m, rs, reason, cut, changing)
    type(model_t), intent(in) :: m
    type(run_state_t), intent(inout) :: rs
    character(len=:), allocatable, intent(out) :: reason, changing
    real(dp), intent(out) :: cut
    integer :: k
    do k = 1, size(rs%fields)
      if (rs%active(k)) call rs%fields(k)%f%restore(m)
    end do
    if (rs%failed == 0) then
      reason = 'the temperatures and the contact (heat through it) did not settle in ' // itoa(max_passes) // &
               ' passes of the two fields'
      cut = 0.25_dp
      changing = ''
      return
    end if
    call rs%fields(rs%failed)%f%failure(reason, cut, changing)
  end subroutine restore_fields

  !> Purpose: takes the solution from step time t0 to t1, halving the
  !> interval when the contact status does not settle (each half an
  !> increment of the results), or when it converged but a field wants it
  !> split (split_increment, at most max_splits times): the halves of a
  !> split are sub-increments, committed but not reported, save the last,
  !> which reports the whole interval (the deck's increments are the
  !> ones written). The intervals still to do are kept on an explicit
  !> stack (at most max_cutbacks + max_splits + 1 deep), so no depth of
  !> bisection can overflow the call stack.
  subroutine advance(m, is, rs, obs, t0, t1)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is
    type(run_state_t), intent(inout) :: rs
    type(observer_ref_t), intent(in) :: obs(:)
    real(dp), intent(in) :: t0, t1
    type(interval_t), allocatable :: stack(:)
    type(interval_t) :: iv
    character(len=:), allocatable :: reason, changing
    logical :: ok
    integer :: top, iters, k
    real(dp) :: mid, cut
    allocate(stack(m%max_cutbacks + max_splits + 2))
    top = 1
    stack(1) = interval_t(t0, t1, 0, 0, .false., t0)
    do while (top > 0)
      iv = stack(top)
      top = top - 1
      ! a bisected or split half of the step's first increment searches too
      call solve_fields(m, is, rs, obs, iv%t0, iv%t1, rs%inc + iv%level + iv%splits > 0, ok, iters)
      mid = 0.5_dp * (iv%t0 + iv%t1)
      if (ok .and. iv%splits < max_splits .and. mid > iv%t0 .and. mid < iv%t1) then
        if (split_increment(m, is, rs, obs)) then
          ! the first half a sub-increment; the second ends as this did
          stack(top + 1) = interval_t(mid, iv%t1, iv%level, iv%splits + 1, iv%quiet, iv%start)
          stack(top + 2) = interval_t(iv%t0, mid, iv%level, iv%splits + 1, .true., iv%start)
          top = top + 2
          cycle
        end if
      end if
      if (ok .and. iv%quiet) then
        do k = 1, size(rs%fields)
          if (rs%active(k)) call rs%fields(k)%f%commit()
        end do
        cycle
      end if
      if (ok) then
        call increment_done(m, is, rs, obs, iv%t1, iters, iv%t1 - iv%start)
        cycle
      end if
      ! (a re-search of the halves pairs on the converged configuration)
      call restore_fields(m, rs, reason, cut, changing)
      if (iv%level >= m%max_cutbacks .or. mid <= iv%t0 .or. mid >= iv%t1) then
        call tell_note(obs, 'contact status did not settle; nodes still switching:' // changing)
        call fatal('contact status did not settle in step ' // itoa(is) // ' at time ' // rtoa(iv%t1, 6) // &
          ' after ' // itoa(iv%level) // ' bisections; nodes still switching:' // changing)
      end if
      call tell_note(obs, 'contact status did not settle: increment bisected')
      ! the second half below the first, so that the first is solved first;
      ! each an increment of the results unless within a split's first half
      stack(top + 1) = interval_t(mid, iv%t1, iv%level + 1, iv%splits, iv%quiet, mid)
      stack(top + 2) = interval_t(iv%t0, mid, iv%level + 1, iv%splits, iv%quiet, iv%start)
      top = top + 2
    end do
  end subroutine advance

  !> Purpose: the increment just converged; should it be split in two
  !> (a field's split_wanted)? If so every field is restored to the
  !> state it started from and the observers are told why; the caller
  !> solves the two halves.
  logical function split_increment(m, is, rs, obs) result(split)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is
    type(run_state_t), intent(inout) :: rs
    type(observer_ref_t), intent(in) :: obs(:)
    character(len=:), allocatable :: why
    integer :: k
    split = .false.
    do k = 1, size(rs%fields)
      if (.not. rs%active(k)) cycle
      call rs%fields(k)%f%split_wanted(m, is, split, why)
      if (split) exit
    end do
    if (.not. split) return
    do k = 1, size(rs%fields)
      if (rs%active(k)) call rs%fields(k)%f%restore(m)
    end do
    call tell_note(obs, why // ': increment split in two')
  end function split_increment

  !> Purpose: a nonlinear step's increments (CalculiX's automatic
  !> incrementation, its manual "Convergence criteria"; the constants are
  !> the step's *CONTROLS, here with their defaults): the first is the
  !> initial increment of *STATIC; the next sized by next_increment; an
  !> increment that fails (a field's failure: divergence, too slow, an
  !> inverted element, a contact status that does not settle) is cut back
  !> by its factor (0.25 or 0.5) and solved again from the last committed
  !> state (cut_back); one that converged but a field wants split
  !> (split_increment) is solved again as its first half, the next sized
  !> from that. With DIRECT the increments are fixed. A search of
  !> the contact on the current configuration is due from the second
  !> increment on (displacement_field's begin_increment).
  subroutine advance_automatic(m, is, rs, obs)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is
    type(run_state_t), intent(inout) :: rs
    type(observer_ref_t), intent(in) :: obs(:)
    real(dp) :: t, dt, dt_try, dt_full, period
    integer :: iters, fast, splits
    logical :: ok
    period = m%steps(is)%period
    dt = m%steps(is)%dt
    t = 0.0_dp
    fast = 0
    splits = 0
    do while (t < period)
      dt_try = min(dt, period - t)
      ! a last sliver of the step joins this increment
      if (period - (t + dt_try) < 1.0e-6_dp * dt_try) dt_try = period - t
      ! shortened to end on a time point of the output (the size it would
      ! have had is the one the next increment grows from, as CalculiX)
      dt_full = dt_try
      if (.not. m%steps(is)%direct) dt_try = to_time_point(m%steps(is), rs%total_time, t, dt_try)
      call solve_fields(m, is, rs, obs, t, t + dt_try, rs%inc > 0, ok, iters)
      if (.not. ok) then
        fast = 0
        call cut_back(m, is, rs, obs, t, dt_try, dt)
        cycle
      end if
      ! a converged increment a field wants split: its first half next
      if (splits < max_splits .and. 0.5_dp * dt_try >= minimum_increment(m, is)) then
        if (split_increment(m, is, rs, obs)) then
          splits = splits + 1
          dt = 0.5_dp * dt_try
          cycle
        end if
      end if
      splits = 0
      t = t + dt_try
      if (period - t <= 1.0e-12_dp * period) t = period
      call increment_done(m, is, rs, obs, t, iters, dt_try)
      if (t >= period) exit
      if (rs%inc >= m%steps(is)%max_inc) call fatal('step ' // itoa(is) // ': ' // itoa(rs%inc) // &
        ' increments done at step time ' // rtoa(t, 6) // ' of ' // rtoa(period, 6) // ', the most INC= ' // &
        'of *STEP allows (default 1000)')
      if (m%steps(is)%direct) cycle
      call next_increment(m, is, iters, dt_full, fast, dt)
    end do
  end subroutine advance_automatic

  !> Purpose: the automatic increment from step time t of size dt,
  !> shortened to end on the first of the step's output time points
  !> (TIME POINTS=, s%out_times: step time, or total time from start, the
  !> total time at the step's start) that lies inside it, as CalculiX
  !> shortens its increments; dt where none does.
  pure real(dp) function to_time_point(s, start, t, dt) result(dtp)
    type(step_t), intent(in) :: s
    real(dp), intent(in) :: start, t, dt
    real(dp) :: tp, tol
    integer :: k
    dtp = dt
    if (.not. allocated(s%out_times)) return
    tol = 1.0e-9_dp * s%period
    do k = 1, size(s%out_times)
      tp = s%out_times(k)
      if (s%out_total_time) tp = tp - start
      if (tp > t + tol .and. tp < t + dtp - tol) dtp = tp - t
    end do
  end function to_time_point

  !> Purpose: the size of the next increment after one of dt_try that
  !> converged in iters iterations: after two increments in a row that
  !> converged in at most I_G = 4 iterations (fast counts them) the next
  !> is D_D = 1.5 times larger, after one that took more than I_L = 10 it
  !> is D_B = 0.75 times smaller, never above the maximum (default the
  !> period) nor below the minimum increment.
  subroutine next_increment(m, is, iters, dt_try, fast, dt)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is, iters
    real(dp), intent(in) :: dt_try
    integer, intent(inout) :: fast
    real(dp), intent(inout) :: dt
    associate(ctl => m%steps(is)%controls)
      if (iters <= ctl%ig) then
        fast = fast + 1
      else
        fast = 0
      end if
      if (iters > ctl%il) then
        dt = ctl%db * dt_try
      else if (fast >= 2) then
        dt = ctl%dd * dt_try
      else
        dt = max(dt, dt_try)
      end if
    end associate
    dt = min(max(dt, minimum_increment(m, is)), maximum_increment(m, is))
  end subroutine next_increment

  !> Purpose: the increment from step time t of dt_try failed: every field
  !> is restored and the increment cut back by the failure's factor (dt
  !> the new size). With DIRECT (fixed increments), or below the minimum
  !> increment (default min(initial, 1e-6 period)), the run stops with the
  !> reason; the increments done are written already.
  subroutine cut_back(m, is, rs, obs, t, dt_try, dt)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is
    type(run_state_t), intent(inout) :: rs
    type(observer_ref_t), intent(in) :: obs(:)
    real(dp), intent(in) :: t, dt_try
    real(dp), intent(out) :: dt
    character(len=:), allocatable :: reason, changing
    real(dp) :: cut, dt_min
    call restore_fields(m, rs, reason, cut, changing)
    rs%cutbacks = rs%cutbacks + 1
    if (m%steps(is)%direct) call fatal('step ' // itoa(is) // ', increment ' // itoa(rs%inc + 1) // ' (to step ' // &
      'time ' // rtoa(t + dt_try, 6) // '): ' // reason // '; the increments are fixed (DIRECT on ' // &
      '*STATIC): a smaller initial increment, or automatic increments (no DIRECT), may converge')
    dt = dt_try * cut
    dt_min = minimum_increment(m, is)
    if (dt < dt_min) call fatal('step ' // itoa(is) // ', increment ' // itoa(rs%inc + 1) // ': ' // &
      reason // '; the increment cut back to ' // rtoa(dt, 4) // ' is below the minimum ' // &
      rtoa(dt_min, 4) // ' (*STATIC): no convergence at step time ' // rtoa(t, 6) // &
      '; the increments before are written')
    call tell_note(obs, reason // ': increment cut back to ' // rtoa(dt, 4))
  end subroutine cut_back

  !> The minimum increment of step is (*STATIC; default min(initial,
  !> 1e-6 period)).
  pure real(dp) function minimum_increment(m, is) result(dt_min)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is
    dt_min = m%steps(is)%dt_min
    if (dt_min <= 0.0_dp) dt_min = min(m%steps(is)%dt, 1.0e-6_dp * m%steps(is)%period)
  end function minimum_increment

  !> The maximum increment of step is (*STATIC; default the period).
  pure real(dp) function maximum_increment(m, is) result(dt_max)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is
    dt_max = m%steps(is)%dt_max
    if (dt_max <= 0.0_dp) dt_max = m%steps(is)%period
  end function maximum_increment
end module analysis
