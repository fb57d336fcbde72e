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
            tell_note, tell_iteration, tell_solver_ready

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
    integer(kind=8) :: continuum_tangent = 0, continuum_stresses = 0, coupling = 0   ! element routine calls
    real(dp) :: wall_seconds = 0.0_dp
  end type step_summary_t

  type :: analysis_observer_t
  contains
    procedure :: step_started
    procedure :: solver_ready
    procedure :: iteration
    procedure :: note
    procedure :: increment_done
    procedure :: step_finished
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

  !> The first factorisation of a step is done: which solver, how large.
  subroutine solver_ready(self, step, description)
    class(analysis_observer_t), intent(inout) :: self
    integer, intent(in) :: step
    character(len=*), intent(in) :: description
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

  subroutine tell_solver_ready(obs, step, description)
    type(observer_ref_t), intent(in) :: obs(:)
    integer, intent(in) :: step
    character(len=*), intent(in) :: description
    integer :: k
    do k = 1, size(obs)
      call obs(k)%o%solver_ready(step, description)
    end do
  end subroutine tell_solver_ready
end module analysis_events
