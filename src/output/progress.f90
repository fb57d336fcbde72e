!> The progress line on standard output: one line per converged increment
!> (in a nonlinear step with its size and Newton iterations) and one per
!> finished step, so that a long run shows where it is.
module progress
  use, intrinsic :: iso_fortran_env, only: output_unit
  use kinds, only: dp
  use strings, only: ftoa
  use model, only: model_t
  use analysis_events, only: analysis_observer_t, step_summary_t, run_timing_t
  use increment_results, only: increment_results_t
  implicit none
  private
  public :: progress_t

  type, extends(analysis_observer_t) :: progress_t
  contains
    procedure :: increment_done => progress_increment
    procedure :: step_finished => progress_step
    procedure :: run_finished => progress_timing
  end type progress_t

contains

  subroutine progress_increment(self, m, res)
    class(progress_t), intent(inout) :: self
    type(model_t), intent(in) :: m
    type(increment_results_t), intent(in) :: res
    if (res%nonlinear) then
      ! a nonlinear step: the increment size and its Newton iterations
      write(output_unit, '(a,i0,a,i0,a,es12.4e3,a,es11.3e3,a,i0,a,i0,a,es13.5e3)') 'step ', res%step, &
        '  increment ', res%increment, '  time ', res%total_time, '  size ', res%dt, '  newton iterations ', &
        res%iterations, '  closed ', res%nclosed, '  contact force ', res%contact%total_force
    else
      write(output_unit, '(a,i0,a,i0,a,es12.4e3,a,i0,a,i0,a,es13.5e3)') 'step ', res%step, '  increment ', &
        res%increment, '  time ', res%total_time, '  iterations ', res%iterations, '  closed ', res%nclosed, &
        '  contact force ', res%contact%total_force
    end if
    flush(output_unit)
  end subroutine progress_increment

  subroutine progress_step(self, summary)
    class(progress_t), intent(inout) :: self
    type(step_summary_t), intent(in) :: summary
    write(output_unit, '(a,i0,a,i0,a,i0,a,i0,a,i0,a)') 'step ', summary%step, ' done: ', &
      summary%increments, ' increments, ', summary%iterations, ' contact iterations, ', summary%factorisations, &
      ' factorisations, ', summary%condensed_factorisations, ' condensed factorisations, ' // &
      ftoa(summary%wall_seconds, 2) // ' s'
    if (summary%nonlinear) write(output_unit, '(a,i0,a,i0,a,i0,a)') 'step ', summary%step, ' nonlinear: ', &
      summary%newton_iterations, ' Newton iterations, ', summary%cutbacks, ' increments cut back'
    flush(output_unit)
  end subroutine progress_step

  !> The listing's timing block, on two lines.
  subroutine progress_timing(self, timing)
    class(progress_t), intent(inout) :: self
    type(run_timing_t), intent(in) :: timing
    write(output_unit, '(a)') 'time (s): read ' // ftoa(timing%read, 3) // ', setup ' // ftoa(timing%setup, 3) // &
      ', assembly ' // ftoa(timing%assembly, 3) // ', analyse ' // ftoa(timing%analyse, 3) // ', factor ' // &
      ftoa(timing%factor, 3) // ', condensed iterations ' // ftoa(timing%condensed, 3) // ', full iterations ' // &
      ftoa(timing%solve, 3) // ', recovery ' // ftoa(timing%recovery, 3) // ', results ' // ftoa(timing%results, 3) // &
      ', output ' // ftoa(timing%output, 3) // ', total ' // ftoa(timing%total, 3)
    if (timing%condensed_lowrank > 0) then
      write(output_unit, '(a,i0,a,i0,a,i0,a)') 'factorisations: numeric ', timing%numeric_factorisations, &
        ', condensed ', timing%condensed_factorisations, ' (low-rank statuses ', timing%condensed_lowrank, ')'
    else
      write(output_unit, '(a,i0,a,i0)') 'factorisations: numeric ', timing%numeric_factorisations, &
        ', condensed ', timing%condensed_factorisations
    end if
    flush(output_unit)
  end subroutine progress_timing

end module progress
