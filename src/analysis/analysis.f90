!> The driver of a run: steps, increments and their bisection. Everything
!> else is data handed to the layers that own it: the load state of the
!> step (load_state), the equilibrium iteration (equilibrium), contact
!> (contact), the results of an increment (increment_results), and the
!> observers that write them (analysis_events).
module analysis
  use kinds, only: dp
  use strings, only: itoa, rtoa
  use model
  use contact, only: contact_set_t, cfe_t, contact_search, contact_research, contact_commit
  use assembly, only: body_t, element_counts_t, body_setup, commit_history
  use dof_numbering, only: dofmap_t
  use condensed_contact, only: number_equations
  use load_state, only: load_state_t, begin_step, values_at, temperature_change_at, check_loads_reached, &
                        follower_loads
  use constraints, only: mpc_t, resolve_equations, constraint_label
  use equilibrium, only: equilibrium_t, begin_equilibrium, solve_increment, renumber_couplings, note_numbering, &
                         numbering_fits
  use newton_control, only: newton_new_step
  use increment_results, only: increment_results_t, compute_increment_results
  use analysis_events, only: observer_ref_t, step_info_t, step_summary_t, run_timing_t, tell_note, wall_time
  use linear_solver, only: linear_system_t
  use messages, only: fatal
  implicit none
  private
  public :: run_analysis

  !> The state the driver carries from increment to increment.
  type :: run_state_t
    real(dp), allocatable :: u(:, :), fext(:, :), rf(:, :)   ! (2, nn)
    type(contact_set_t) :: cs
    type(dofmap_t) :: dm
    type(linear_system_t) :: sys
    type(load_state_t) :: ls
    type(equilibrium_t) :: eq
    type(body_t) :: body
    type(mpc_t) :: mpc                  ! the linear constraints, resolved once
    real(dp) :: total_time = 0.0_dp     ! at the start of the current step
    integer :: inc = 0                  ! increments done in the current step
    logical :: update_search = .false.
    !> The current step is nonlinear (NLGEOM or a nonlinear material):
    !> Newton with automatic increments (advance_nonlinear).
    logical :: nonlinear = .false.
    integer :: cutbacks = 0             ! increments cut back in the current step
    type(run_timing_t) :: timing        ! the driver's own parts (the iteration's are in eq)
  end type run_state_t

  !> An interval of step time still to be solved, and its bisection depth.
  type :: interval_t
    real(dp) :: t0 = 0.0_dp, t1 = 0.0_dp
    integer :: level = 0
  end type interval_t

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
    type(element_counts_t) :: counts
    integer :: is
    real(dp) :: t0
    if (present(timing)) rs%timing = timing
    if (rs%timing%started == 0.0_dp) rs%timing%started = wall_time()
    t0 = wall_time()
    allocate(rs%u(2, m%nn), rs%fext(2, m%nn), rs%rf(2, m%nn))
    rs%u = 0.0_dp
    rs%fext = 0.0_dp
    rs%rf = 0.0_dp
    call body_setup(m, rs%body, counts)
    call constraints_of(m, rs%mpc)
    ! Small deformation: one search on the initial configuration.
    call contact_search(m, m%x, rs%cs)
    if (size(m%pairs) > 0) rs%update_search = any(m%pairs%update_search)
    rs%timing%setup = rs%timing%setup + (wall_time() - t0)
    do is = 1, size(m%steps)
      call run_step(m, is, rs, obs, counts)
      counts = element_counts_t()
      rs%total_time = rs%total_time + m%steps(is)%period
    end do
    call finish(rs, obs)
    if (present(timing)) timing = rs%timing
  end subroutine run_analysis

  !> The linear constraints resolved for elimination (the deck's checks
  !> have reported what cannot be, naming its line).
  subroutine constraints_of(m, mpc)
    type(model_t), intent(in) :: m
    type(mpc_t), intent(out) :: mpc
    integer :: bad
    character(len=:), allocatable :: msg
    call resolve_equations(m, mpc, bad, msg)
    if (bad > 0) call fatal(constraint_label(m, bad) // ': ' // msg)
  end subroutine constraints_of

  !> The run's timing: the driver's parts and the iteration's, to every
  !> observer (the output of this last event is not in it).
  subroutine finish(rs, obs)
    type(run_state_t), intent(inout) :: rs
    type(observer_ref_t), intent(in) :: obs(:)
    integer :: k
    associate(t => rs%timing, e => rs%eq%timing)
      t%assembly = e%assembly
      t%analyse = t%analyse + e%analyse
      t%factor = e%factor
      t%condensed = e%condensed
      t%solve = e%solve
      t%recovery = e%recovery
      t%numeric_factorisations = e%numeric_factorisations
      t%condensed_factorisations = e%condensed_factorisations
      t%total = wall_time() - t%started
    end associate
    do k = 1, size(obs)
      call obs(k)%o%run_finished(rs%timing)
    end do
  end subroutine finish

  !> Purpose: one step: its load state and equations, its increments.
  !> Arguments: counts holds element routine calls made before the step
  !> (the body stiffness, for the first step).
  subroutine run_step(m, is, rs, obs, counts)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is
    type(run_state_t), intent(inout) :: rs
    type(observer_ref_t), intent(in) :: obs(:)
    type(element_counts_t), intent(in) :: counts
    type(step_info_t) :: info
    type(step_summary_t) :: summary
    integer :: i, ninc, k
    real(dp) :: t0, ta, started
    started = wall_time()
    t0 = started
    call begin_step(m, is, rs%u, rs%fext, rs%total_time, rs%ls)
    ! a nonlinear step: the bodies evaluated at u, the full solve
    rs%nonlinear = step_is_nonlinear(m, is)
    rs%body%nonlinear = rs%nonlinear
    rs%body%nlgeom = m%steps(is)%nlgeom
    call newton_new_step(rs%eq%newton, m%steps(is)%controls)
    rs%cutbacks = 0
    if (rs%nonlinear .and. m%steps(is)%nlgeom .and. size(m%pairs) > 0 .and. is > 1) call research(m, rs)
    call number_equations(m, rs%cs, rs%ls%presc, rs%mpc, rs%dm, rs%sys, rs%eq%cd, ta, rs%nonlinear)
    call check_loads_reached(m, rs%ls, rs%dm%inactive)
    call begin_equilibrium(rs%eq, rs%dm%neq, rs%cs%n, .true.)
    call note_numbering(rs%eq, m, rs%cs)
    rs%timing%setup = rs%timing%setup + (wall_time() - t0 - ta)
    rs%timing%analyse = rs%timing%analyse + ta
    rs%eq%counts = counts
    ninc = nint(m%steps(is)%period / m%steps(is)%dt)
    info%step = is
    info%equations = rs%dm%neq
    info%prescribed = count(rs%ls%presc)
    info%period = m%steps(is)%period
    info%increments = ninc
    info%coupling_elements = rs%cs%n
    info%uncoupled = rs%cs%uncoupled
    info%uncoupled_pair = rs%cs%uncoupled_pair
    t0 = wall_time()
    do k = 1, size(obs)
      call obs(k)%o%step_started(m, info)
    end do
    rs%timing%output = rs%timing%output + (wall_time() - t0)
    rs%inc = 0
    if (rs%nonlinear) then
      call advance_nonlinear(m, is, rs, obs)
      if (rs%eq%searches > 0) call tell_note(obs, 'contact searched again in ' // itoa(rs%eq%searches) // &
        ' Newton iterations; equations renumbered ' // itoa(rs%eq%renumberings) // ' times for changed couplings')
    else
      do i = 1, ninc
        call advance(m, is, rs, obs, m%steps(is)%period * (i - 1) / ninc, m%steps(is)%period * i / ninc)
      end do
    end if
    summary%step = is
    summary%increments = rs%inc
    summary%factorisations = rs%eq%factorisations
    summary%condensed_factorisations = rs%eq%condensed_factorisations
    summary%iterations = rs%eq%iterations
    summary%block_pivots = rs%eq%search%block_pivots
    summary%single_pivots = rs%eq%search%single_pivots
    summary%continuum_tangent = rs%eq%counts%continuum_tangent
    summary%continuum_stresses = rs%eq%counts%continuum_stresses
    summary%coupling = rs%eq%counts%coupling
    summary%wall_seconds = wall_time() - started
    summary%nonlinear = rs%nonlinear
    summary%newton_iterations = rs%eq%newton%total
    summary%cutbacks = rs%cutbacks
    t0 = wall_time()
    do k = 1, size(obs)
      call obs(k)%o%step_finished(summary)
    end do
    rs%timing%output = rs%timing%output + (wall_time() - t0)
  end subroutine run_step

  !> Purpose: takes the solution from step time t0 to t1, halving the
  !> interval when the contact status does not settle. The intervals still
  !> to do are kept on an explicit stack (at most max_cutbacks + 1 deep),
  !> so no depth of bisection can overflow the call stack.
  subroutine advance(m, is, rs, obs, t0, t1)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is
    type(run_state_t), intent(inout) :: rs
    type(observer_ref_t), intent(in) :: obs(:)
    real(dp), intent(in) :: t0, t1
    type(interval_t), allocatable :: stack(:)
    type(interval_t) :: iv
    type(cfe_t), allocatable :: saved(:)
    real(dp), allocatable :: u_saved(:, :)
    logical :: ok
    integer :: top, iters
    real(dp) :: mid
    allocate(stack(m%max_cutbacks + 2))
    top = 1
    stack(1) = interval_t(t0, t1, 0)
    do while (top > 0)
      iv = stack(top)
      top = top - 1
      if (rs%update_search .and. rs%inc + iv%level > 0) call research(m, rs)
      saved = rs%cs%c(1:rs%cs%n)
      u_saved = rs%u
      call values_at(m, rs%ls, iv%t1, rs%u, rs%fext)
      call solve_increment(rs%eq, m, is, rs%inc + 1, rs%body, rs%cs, rs%dm, rs%sys, rs%fext, rs%u, rs%rf, obs, ok, iters)
      if (ok) then
        call commit_increment(rs)
        rs%inc = rs%inc + 1
        call report(m, is, rs, obs, iv%t1, iters, iv%t1 - iv%t0)
        cycle
      end if
      ! the statuses and displacements the increment started with (the
      ! friction history is committed only by converged increments; a
      ! re-search of the halves pairs on the converged configuration)
      rs%cs%c(1:rs%cs%n) = saved
      rs%u = u_saved
      mid = 0.5_dp * (iv%t0 + iv%t1)
      if (iv%level >= m%max_cutbacks .or. mid <= iv%t0 .or. mid >= iv%t1) then
        call tell_note(obs, 'contact status did not settle; nodes still switching:' // rs%eq%changed)
        call fatal('contact status did not settle in step ' // itoa(is) // ' at time ' // rtoa(iv%t1, 6) // &
          ' after ' // itoa(iv%level) // ' bisections; nodes still switching:' // rs%eq%changed)
      end if
      call tell_note(obs, 'contact status did not settle: increment bisected')
      ! the second half below the first, so that the first is solved first
      stack(top + 1) = interval_t(mid, iv%t1, iv%level + 1)
      stack(top + 2) = interval_t(iv%t0, mid, iv%level + 1)
      top = top + 2
    end do
  end subroutine advance

  !> Purpose: a converged increment's history becomes the state the next
  !> increment starts from: the one place where state that depends on
  !> the loading path is committed (the contact layer's friction anchors
  !> and slips; the bodies' material history at their integration
  !> points, plastic strain and hardening). An increment that does not
  !> converge commits nothing: its bisected or cut-back parts start again
  !> from the last committed state.
  subroutine commit_increment(rs)
    type(run_state_t), intent(inout) :: rs
    call contact_commit(rs%cs)
    if (rs%nonlinear) call commit_history(rs%body)
  end subroutine commit_increment

  !> Purpose: whether step is of model m is solved as a nonlinear one:
  !> NLGEOM, or a hyperelastic or plastic material in a section.
  logical function step_is_nonlinear(m, is) result(nl)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is
    nl = m%steps(is)%nlgeom .or. nonlinear_material(m)
  end function step_is_nonlinear

  !> Purpose: a nonlinear step's increments (CalculiX's automatic
  !> incrementation, its manual "Convergence criteria"; the constants are
  !> the step's *CONTROLS, here with their defaults): the first is the
  !> initial increment of *STATIC; after two increments in a row that
  !> converged in at most I_G = 4 iterations the next is D_D = 1.5 times
  !> larger, after one that took more than I_L = 10 it is D_B = 0.75
  !> times smaller, never above the maximum (default the period) nor beyond the
  !> end of the step; an increment that fails (equilibrium's newton_t:
  !> divergence, too slow, an inverted element, a contact status that
  !> does not settle) is cut back by its factor (0.25 or 0.5) and solved
  !> again from the last committed state. Below the minimum increment
  !> (default min(initial, 1e-6 period)) the run stops with the reason;
  !> the increments done are written already. With DIRECT the increments
  !> are fixed, and a failure stops the run. Under NLGEOM a face pressure
  !> (*DLOAD P) follows the deformed face, its load stiffness in the
  !> tangent (load_state's follower_loads, the body's fl_*). Under NLGEOM
  !> with contact the pairs are searched again on the current
  !> configuration in every Newton iteration (equilibrium's
  !> search_in_iteration), so a converged increment ends with the
  !> couplings of its own configuration; the next starts with a search on
  !> that configuration that drops the couplings the iterations kept for
  !> points that found no master edge (contact_research); a cut-back
  !> restores the couplings the increment started with (the
  !> whole contact set: their number, geometry, statuses and friction
  !> state) and, where the failed attempt had renumbered the equations
  !> for other couplings, numbers them again for the restored ones.
  !> Without NLGEOM, UPDATE SEARCH searches at the start of every
  !> increment, as in a linear step.
  subroutine advance_nonlinear(m, is, rs, obs)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is
    type(run_state_t), intent(inout) :: rs
    type(observer_ref_t), intent(in) :: obs(:)
    type(cfe_t), allocatable :: saved(:)
    type(contact_set_t) :: saved_cs
    real(dp), allocatable :: u_saved(:, :)
    real(dp) :: t, dt, dt_try, dt_min, dt_max, period
    integer :: iters, fast
    logical :: ok, research_each
    period = m%steps(is)%period
    dt = m%steps(is)%dt
    dt_min = m%steps(is)%dt_min
    if (dt_min <= 0.0_dp) dt_min = min(dt, 1.0e-6_dp * period)
    dt_max = m%steps(is)%dt_max
    if (dt_max <= 0.0_dp) dt_max = period
    research_each = m%steps(is)%nlgeom .and. size(m%pairs) > 0
    t = 0.0_dp
    fast = 0
    do while (t < period)
      dt_try = min(dt, period - t)
      ! a last sliver of the step joins this increment
      if (period - (t + dt_try) < 1.0e-6_dp * dt_try) dt_try = period - t
      if (research_each) then
        ! the pairing of the converged configuration, without the closed
        ! couplings the last increment's iterations kept for points that
        ! found no master edge (contact_research)
        if (rs%inc > 0) then
          call contact_research(m, m%x + rs%u, rs%cs)
          if (.not. numbering_fits(rs%eq, m, rs%cs)) &
            call renumber_couplings(rs%eq, m, rs%cs, rs%ls%presc, rs%mpc, rs%dm, rs%sys)
        end if
        saved_cs = rs%cs
      else
        if (rs%update_search .and. rs%inc > 0) call research(m, rs)
        saved = rs%cs%c(1:rs%cs%n)
      end if
      u_saved = rs%u
      call values_at(m, rs%ls, t + dt_try, rs%u, rs%fext)
      ! the free dofs start where the last increment left them
      where (.not. rs%ls%presc) rs%u = u_saved
      ! the pressures on the deformed faces (NLGEOM)
      call follower_loads(m, rs%ls, t + dt_try, rs%body%fl_ptr, rs%body%fl_face, rs%body%fl_mag)
      if (rs%ls%thermal) then
        ! the temperatures at the end and at the start of the increment
        if (.not. allocated(rs%body%dtemp)) allocate(rs%body%dtemp(m%nn), rs%body%dtemp0(m%nn))
        call temperature_change_at(m, rs%ls, t + dt_try, rs%body%dtemp)
        call temperature_change_at(m, rs%ls, t, rs%body%dtemp0)
      end if
      if (research_each) then
        call solve_increment(rs%eq, m, is, rs%inc + 1, rs%body, rs%cs, rs%dm, rs%sys, rs%fext, rs%u, rs%rf, obs, &
                             ok, iters, u_saved, rs%ls%presc, rs%mpc)
      else
        call solve_increment(rs%eq, m, is, rs%inc + 1, rs%body, rs%cs, rs%dm, rs%sys, rs%fext, rs%u, rs%rf, obs, &
                             ok, iters, u_saved)
      end if
      if (ok) then
        call commit_increment(rs)
        rs%inc = rs%inc + 1
        t = t + dt_try
        if (period - t <= 1.0e-12_dp * period) t = period
        call report(m, is, rs, obs, t, iters, dt_try)
        if (t >= period) exit
        if (rs%inc >= m%steps(is)%max_inc) call fatal('step ' // itoa(is) // ': ' // itoa(rs%inc) // &
          ' increments done at step time ' // rtoa(t, 6) // ' of ' // rtoa(period, 6) // ', the most INC= ' // &
          'of *STEP allows (default 1000)')
        if (m%steps(is)%direct) cycle
        if (iters <= m%steps(is)%controls%ig) then
          fast = fast + 1
        else
          fast = 0
        end if
        if (iters > m%steps(is)%controls%il) then
          dt = m%steps(is)%controls%db * dt_try
        else if (fast >= 2) then
          dt = m%steps(is)%controls%dd * dt_try
        else
          dt = max(dt, dt_try)
        end if
        dt = min(max(dt, dt_min), dt_max)
        cycle
      end if
      ! nothing of the failed attempt is kept
      if (research_each) then
        rs%cs = saved_cs
        if (.not. numbering_fits(rs%eq, m, rs%cs)) &
          call renumber_couplings(rs%eq, m, rs%cs, rs%ls%presc, rs%mpc, rs%dm, rs%sys)
      else
        rs%cs%c(1:rs%cs%n) = saved
      end if
      rs%u = u_saved
      fast = 0
      rs%cutbacks = rs%cutbacks + 1
      if (m%steps(is)%direct) call fatal('step ' // itoa(is) // ', increment ' // itoa(rs%inc + 1) // ' (to step ' // &
        'time ' // rtoa(t + dt_try, 6) // '): ' // rs%eq%newton%reason // '; the increments are fixed (DIRECT on ' // &
        '*STATIC): a smaller initial increment, or automatic increments (no DIRECT), may converge')
      dt = dt_try * rs%eq%newton%cut
      if (dt < dt_min) call fatal('step ' // itoa(is) // ', increment ' // itoa(rs%inc + 1) // ': ' // &
        rs%eq%newton%reason // '; the increment cut back to ' // rtoa(dt, 4) // ' is below the minimum ' // &
        rtoa(dt_min, 4) // ' (*STATIC): no convergence at step time ' // rtoa(t, 6) // &
        '; the increments before are written')
      call tell_note(obs, rs%eq%newton%reason // ': increment cut back to ' // rtoa(dt, 4))
    end do
  end subroutine advance_nonlinear

  !> UPDATE SEARCH: the contact layer pairs again on the deformed
  !> configuration; the equations are renumbered for the new couplings.
  subroutine research(m, rs)
    type(model_t), intent(in) :: m
    type(run_state_t), intent(inout) :: rs
    real(dp) :: t0, ta
    t0 = wall_time()
    call contact_research(m, m%x + rs%u, rs%cs)
    call number_equations(m, rs%cs, rs%ls%presc, rs%mpc, rs%dm, rs%sys, rs%eq%cd, ta, rs%nonlinear)
    call begin_equilibrium(rs%eq, rs%dm%neq, rs%cs%n, .false.)
    call note_numbering(rs%eq, m, rs%cs)
    rs%timing%setup = rs%timing%setup + (wall_time() - t0 - ta)
    rs%timing%analyse = rs%timing%analyse + ta
  end subroutine research

  !> The results of a converged increment, computed once, to every observer.
  subroutine report(m, is, rs, obs, t, iters, dt)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is, iters
    type(run_state_t), intent(inout) :: rs
    type(observer_ref_t), intent(in) :: obs(:)
    real(dp), intent(in) :: t, dt
    type(increment_results_t) :: res
    integer :: k
    real(dp) :: t0, t1
    real(dp), allocatable :: dtemp(:)
    t0 = wall_time()
    if (rs%ls%thermal) then
      allocate(dtemp(m%nn))
      call temperature_change_at(m, rs%ls, t, dtemp)
      call compute_increment_results(m, is, rs%inc, t, rs%total_time + t, iters, rs%u, rs%rf, rs%cs, &
                                     rs%ls%set_ids, res, rs%eq%counts, dtemp, rs%body, dt)
    else
      call compute_increment_results(m, is, rs%inc, t, rs%total_time + t, iters, rs%u, rs%rf, rs%cs, &
                                     rs%ls%set_ids, res, rs%eq%counts, body=rs%body, dt=dt)
    end if
    t1 = wall_time()
    do k = 1, size(obs)
      call obs(k)%o%increment_done(m, res)
    end do
    rs%timing%results = rs%timing%results + (t1 - t0)
    rs%timing%output = rs%timing%output + (wall_time() - t1)
  end subroutine report
end module analysis
