!> What the analysis tells the outside world as it runs, and the observer
!> type through which it tells it. The analysis layer knows no writer: the
!> output layer extends `analysis_observer_t` (listing, result files,
!> progress line) and the main program hands the observers to the driver.
!> A new output format is one new module with an extension of this type
!> and one line in the main program. Every event has a do-nothing default.
module analysis_events
  use kinds, only: dp
  use model, only: model_t
  use increment_results, only: increment_results_t
  implicit none
  private
  public :: analysis_observer_t, observer_ref_t, step_info_t, iteration_info_t, step_summary_t, &
            solver_info_t, run_timing_t, tell_note, tell_iteration, tell_solver_ready, wall_time

  type :: step_info_t
    integer :: step = 0, equations = 0, prescribed = 0, increments = 0, coupling_elements = 0
    real(dp) :: period = 0.0_dp
    integer, allocatable :: uncoupled(:), uncoupled_pair(:)   ! slave nodes without a master segment
  end type step_info_t

  type :: iteration_info_t
    integer :: iteration = 0, changes = 0, closed = 0
    real(dp) :: residual = 0.0_dp                            ! relative out-of-balance force
    character(len=:), allocatable :: changed                  ! user ids of switching nodes
  end type iteration_info_t

  type :: step_summary_t
    integer :: step = 0, increments = 0, factorisations = 0, iterations = 0
    integer :: condensed_factorisations = 0                  ! dense ones of the condensed contact solve
    integer :: temperature_factorisations = -1               ! the temperature field's of them (-1: not in the step)
    integer :: block_pivots = 0, single_pivots = 0           ! of the contact status search (contact_status)
    integer(kind=8) :: continuum_tangent = 0, continuum_stresses = 0, coupling = 0   ! element routine calls
    real(dp) :: wall_seconds = 0.0_dp
    !> A nonlinear step: its Newton iterations (of every attempt) and the
    !> increments cut back.
    logical :: nonlinear = .false.
    integer :: newton_iterations = 0, cutbacks = 0
  end type step_summary_t

  !> The solver of a step, once its first factorisation is done.
  type :: solver_info_t
    integer :: step = 0
    character(len=:), allocatable :: description      ! solver, ordering, size of the factor
    !> 'condensed' or 'full' (the contact status iterations on the contact
    !> equations only, or on the whole system); empty without contact.
    character(len=:), allocatable :: contact_solve
    integer :: contact_equations = 0                  ! condensed: order of the dense matrix
  end type solver_info_t

  !> Where the wall time of a run went (seconds), and how many matrices
  !> were factored; the last event of a run.
  type :: run_timing_t
    real(dp) :: read = 0.0_dp        ! the deck
    real(dp) :: setup = 0.0_dp       ! body stiffness, contact search, equations, load states
    real(dp) :: assembly = 0.0_dp    ! global matrices
    real(dp) :: analyse = 0.0_dp     ! ordering and symbolic analysis
    real(dp) :: factor = 0.0_dp      ! numeric sparse factorisations
    real(dp) :: condensed = 0.0_dp   ! condensed iterations: right-hand sides, dense factorisations, solves, gaps
    real(dp) :: solve = 0.0_dp       ! full iterations: solves, forces, switching
    real(dp) :: recovery = 0.0_dp    ! condensed: the other equations, forces and reactions once settled
    real(dp) :: results = 0.0_dp     ! stresses and contact results of converged increments
    real(dp) :: output = 0.0_dp      ! the writers (listing, result files, progress)
    real(dp) :: total = 0.0_dp       ! the whole run so far
    real(dp) :: started = 0.0_dp     ! wall_time() at the start of the program
    integer :: numeric_factorisations = 0, condensed_factorisations = 0
  end type run_timing_t

  type :: analysis_observer_t
  contains
    procedure :: step_started
    procedure :: solver_ready
    procedure :: iteration
    procedure :: note
    procedure :: increment_done
    procedure :: step_finished
    procedure :: run_finished
  end type analysis_observer_t

  !> An entry of the list of observers the driver notifies.
  type :: observer_ref_t
    class(analysis_observer_t), pointer :: o => null()
  end type observer_ref_t

contains

  !> A step starts: its size and the contact pairing.
  subroutine step_started(self, m, info)
    class(analysis_observer_t), intent(inout) :: self
    type(model_t), intent(in) :: m
    type(step_info_t), intent(in) :: info
  end subroutine step_started

  !> The first factorisation of a step is done: which solver, how large,
  !> and how the contact iterations are solved.
  subroutine solver_ready(self, info)
    class(analysis_observer_t), intent(inout) :: self
    type(solver_info_t), intent(in) :: info
  end subroutine solver_ready

  !> One contact status iteration.
  subroutine iteration(self, info)
    class(analysis_observer_t), intent(inout) :: self
    type(iteration_info_t), intent(in) :: info
  end subroutine iteration

  !> A remark worth recording (a bisection, a solver fall-back).
  subroutine note(self, text)
    class(analysis_observer_t), intent(inout) :: self
    character(len=*), intent(in) :: text
  end subroutine note

  !> A converged increment and its results.
  subroutine increment_done(self, m, res)
    class(analysis_observer_t), intent(inout) :: self
    type(model_t), intent(in) :: m
    type(increment_results_t), intent(in) :: res
  end subroutine increment_done

  !> A step is finished.
  subroutine step_finished(self, summary)
    class(analysis_observer_t), intent(inout) :: self
    type(step_summary_t), intent(in) :: summary
  end subroutine step_finished

  !> Every step is done: where the time went.
  subroutine run_finished(self, timing)
    class(analysis_observer_t), intent(inout) :: self
    type(run_timing_t), intent(in) :: timing
  end subroutine run_finished

  !> Purpose: wall-clock seconds since an arbitrary origin (differences
  !> only).
  real(dp) function wall_time()
    integer(kind=8) :: count, rate
    call system_clock(count, rate)
    wall_time = real(count, dp) / real(rate, dp)
  end function wall_time

  !> Purpose: the note event to every observer.
  subroutine tell_note(obs, text)
    type(observer_ref_t), intent(in) :: obs(:)
    character(len=*), intent(in) :: text
    integer :: k
    do k = 1, size(obs)
      call obs(k)%o%note(text)
    end do
  end subroutine tell_note

  subroutine tell_iteration(obs, info)
    type(observer_ref_t), intent(in) :: obs(:)
    type(iteration_info_t), intent(in) :: info
    integer :: k
    do k = 1, size(obs)
      call obs(k)%o%iteration(info)
    end do
  end subroutine tell_iteration

  subroutine tell_solver_ready(obs, info)
    type(observer_ref_t), intent(in) :: obs(:)
    type(solver_info_t), intent(in) :: info
    integer :: k
    do k = 1, size(obs)
      call obs(k)%o%solver_ready(info)
    end do
  end subroutine tell_solver_ready
end module analysis_events
