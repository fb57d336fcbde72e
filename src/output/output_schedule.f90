!> When a step's print and file output is written: CalculiX's FREQUENCY=
!> and TIME POINTS= of the output cards, as the model's step_t keeps them
!> (out_every, out_times; the input layer's read_request). Each writer
!> (listing, gmsh file, VTU series) holds one schedule_t, which
!> remembers the time of the last increment it saw, so that a time point
!> inside an increment is written at that increment's end.
module output_schedule
  use kinds, only: dp
  use model, only: model_t
  use increment_results, only: increment_results_t, output_due
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

  !> Purpose: is this increment's requested output to be written?
  !> increment_results' output_due (CalculiX's FREQUENCY= and TIME
  !> POINTS=; the stresses are computed by the same rule), with the
  !> previous increment this writer saw as the interval's start.
  !> Arguments:
  !>   self  the writer's schedule (remembers the last increment seen)
  !>   m     the model (the step's out_every, out_times, period)
  !>   res   the increment's results (step, increment, step and total time)
  logical function due(self, m, res)
    class(schedule_t), intent(inout) :: self
    type(model_t), intent(in) :: m
    type(increment_results_t), intent(in) :: res
    real(dp) :: t
    associate(s => m%steps(res%step))
      t = res%time
      if (s%out_total_time) t = res%total_time
      if (self%step /= res%step) then
        ! the step's start: step time 0, or the total time it starts at
        self%step = res%step
        self%last = t - res%time
      end if
      due = output_due(m, res%step, res%increment, res%time, t, self%last)
      self%last = t
    end associate
  end function due
end module output_schedule
