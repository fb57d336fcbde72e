!> When a step's print and file output is written: CalculiX's FREQUENCY=
!> and TIME POINTS= of the output cards, as the model's step_t keeps them
!> (out_every, out_times; the input layer's read_request). Each writer
!> (listing, gmsh file, VTU series) holds one schedule_t, which
!> remembers the time of the last increment it saw, so that a time point
!> inside an increment is written at that increment's end.
module output_schedule
  use kinds, only: dp
  use model, only: model_t
  use increment_results, only: increment_results_t
  implicit none
  private
  public :: schedule_t

  type :: schedule_t
    integer :: step = 0            ! the step of the last increment seen
    real(dp) :: last = 0.0_dp      ! its time (step or total time, as out_total_time says)
  contains
    procedure :: due
  end type schedule_t

contains

  !> Purpose: is this increment's requested output to be written? Always
  !> at the last increment of a step (CalculiX writes the end of every
  !> step); otherwise every out_every-th increment, or, with time points,
  !> at an increment whose interval (previous end, this end] holds one
  !> (relative tolerance 1e-9 of the period, so that a point on an
  !> increment end is written there and not again at the next).
  !> Arguments:
  !>   self  the writer's schedule (remembers the last increment seen)
  !>   m     the model (the step's out_every, out_times, period)
  !>   res   the increment's results (step, increment, step and total time)
  logical function due(self, m, res)
    class(schedule_t), intent(inout) :: self
    type(model_t), intent(in) :: m
    type(increment_results_t), intent(in) :: res
    real(dp) :: t, tol
    associate(s => m%steps(res%step))
      tol = 1.0e-9_dp * s%period
      t = res%time
      if (s%out_total_time) t = res%total_time
      if (self%step /= res%step) then
        ! the step's start: step time 0, or the total time it starts at
        self%step = res%step
        self%last = t - res%time
      end if
      due = res%time >= s%period - tol
      if (allocated(s%out_times)) then
        due = due .or. any(s%out_times > self%last + tol .and. s%out_times <= t + tol)
      else
        due = due .or. mod(res%increment, max(s%out_every, 1)) == 0
      end if
      self%last = t
    end associate
  end function due
end module output_schedule
