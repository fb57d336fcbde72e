!> The progress line on standard output: one line per converged increment
!> and one per finished step, so that a long run shows where it is.
module progress
  use, intrinsic :: iso_fortran_env, only: output_unit
  use kinds, only: dp
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
    write(output_unit, '(a,i0,a,i0,a,es12.4e3,a,i0,a,i0,a,es13.5e3)') 'step ', res%step, '  increment ', &
      res%increment, '  time ', res%total_time, '  iterations ', res%iterations, '  closed ', res%nclosed, &
      '  contact force ', res%contact%total_force
    flush(output_unit)
  end subroutine progress_increment

  subroutine progress_step(self, summary)
    class(progress_t), intent(inout) :: self
    type(step_summary_t), intent(in) :: summary
    write(output_unit, '(a,i0,a,i0,a,i0,a,i0,a,i0,a,f0.2,a)') 'step ', summary%step, ' done: ', &
      summary%increments, ' increments, ', summary%iterations, ' contact iterations, ', summary%factorisations, &
      ' factorisations, ', summary%condensed_factorisations, ' condensed factorisations, ', &
      summary%wall_seconds, ' s'
    flush(output_unit)
  end subroutine progress_step

  !> The listing's timing block, on two lines.
  subroutine progress_timing(self, timing)
    class(progress_t), intent(inout) :: self
    type(run_timing_t), intent(in) :: timing
    write(output_unit, '(a)') 'time (s): read ' // sec(timing%read) // ', setup ' // sec(timing%setup) // &
      ', assembly ' // sec(timing%assembly) // ', analyse ' // sec(timing%analyse) // ', factor ' // &
      sec(timing%factor) // ', condensed iterations ' // sec(timing%condensed) // ', full iterations ' // &
      sec(timing%solve) // ', recovery ' // sec(timing%recovery) // ', results ' // sec(timing%results) // &
      ', output ' // sec(timing%output) // ', total ' // sec(timing%total)
    write(output_unit, '(a,i0,a,i0)') 'factorisations: numeric ', timing%numeric_factorisations, &
      ', condensed ', timing%condensed_factorisations
    flush(output_unit)
  end subroutine progress_timing

  !> Seconds with three decimals and a leading zero.
  pure function sec(t) result(s)
    real(dp), intent(in) :: t
    character(len=:), allocatable :: s
    character(len=24) :: buf
    write(buf, '(f24.3)') t
    s = trim(adjustl(buf))
  end function sec
end module progress
