!> CalculiX's status files: <job>.sta, one line per converged increment
!> (step, increment, attempts, iterations, total, step and increment
!> time), and <job>.cvg, one line per iteration (the contact elements
!> closed and the residual force in per cent), with CalculiX 2.20's
!> headers and number format, so that tools that follow a CalculiX run
!> (FreeCAD's solver progress, users' scripts) follow cfe2d's.
!> The attempt of an increment (ATT) is counted here from the iteration
!> events: an increment that is cut back or bisected is solved again from
!> its first iteration, so an iteration number that does not grow starts
!> the next attempt (an attempt that fails before its first iteration is
!> not seen). The events carry no displacement correction: the CORR. DISP
!> column is 0.
module results_sta
  use kinds, only: dp
  use model, only: model_t
  use messages, only: fatal
  use analysis_events, only: analysis_observer_t, run_timing_t, step_info_t, iteration_info_t
  use increment_results, only: increment_results_t
  implicit none
  private
  public :: status_files_t, open_status_files

  type, extends(analysis_observer_t) :: status_files_t
    integer :: sta = 0, cvg = 0
    logical :: open = .false.
    integer :: step = 0, increment = 0      ! of the iterations being reported
    integer :: attempt = 1, last_iteration = 0   ! the increment's attempt, its last iteration
    real(dp) :: last_time = 0.0_dp          ! step time of the previous increment
  contains
    procedure :: step_started => sta_step
    procedure :: iteration => cvg_iteration
    procedure :: increment_done => sta_increment
    procedure :: run_finished => close_status_files
  end type status_files_t

contains

  !> Purpose: open <job>.sta and <job>.cvg and write their headers.
  !> Arguments: job the path without extension; f the writer (out).
  subroutine open_status_files(job, f)
    character(len=*), intent(in) :: job
    type(status_files_t), intent(out) :: f
    integer :: ios
    open(newunit=f%sta, file=job // '.sta', status='replace', action='write', iostat=ios)
    if (ios /= 0) call fatal('cannot write the status file "' // job // '.sta"')
    open(newunit=f%cvg, file=job // '.cvg', status='replace', action='write', iostat=ios)
    if (ios /= 0) call fatal('cannot write the convergence file "' // job // '.cvg"')
    f%open = .true.
    write(f%sta, '(a)') 'SUMMARY OF JOB INFORMATION', &
      '  STEP      INC     ATT  ITRS     TOT TIME     STEP TIME      INC TIME'
    ! (CalculiX's header spells C0NVERGENCE with a zero; readers match it)
    write(f%cvg, '(a)') 'SUMMARY OF C0NVERGENCE INFORMATION', &
      '  STEP   INC  ATT   ITER     CONT.   RESID.        CORR.      RESID.      CORR.', &
      '                              EL.    FORCE         DISP       FLUX        TEMP.', &
      '                              (#)     (%)           (%)        (%)         (%)'
    flush(f%sta)
    flush(f%cvg)
  end subroutine open_status_files

  !> Purpose: a step starts: its iterations are reported from increment 1.
  subroutine sta_step(self, m, info)
    class(status_files_t), intent(inout) :: self
    type(model_t), intent(in) :: m
    type(step_info_t), intent(in) :: info
    self%step = info%step
    self%increment = 1
    self%last_time = 0.0_dp
    self%attempt = 1
    self%last_iteration = 0
  end subroutine sta_step

  !> Purpose: a .cvg line per iteration: step, increment, attempt,
  !> iteration, closed contact points, residual force (%).
  subroutine cvg_iteration(self, info)
    class(status_files_t), intent(inout) :: self
    type(iteration_info_t), intent(in) :: info
    if (info%iteration <= self%last_iteration) self%attempt = self%attempt + 1
    self%last_iteration = info%iteration
    write(self%cvg, '(i6, i6, i5, i6, i9, 4(2x, e10.4))') self%step, self%increment, self%attempt, info%iteration, &
      info%closed, 100.0_dp * info%residual, 0.0_dp, 0.0_dp, 0.0_dp
    flush(self%cvg)
  end subroutine cvg_iteration

  !> Purpose: a .sta line per converged increment.
  subroutine sta_increment(self, m, res)
    class(status_files_t), intent(inout) :: self
    type(model_t), intent(in) :: m
    type(increment_results_t), intent(in) :: res
    real(dp) :: dt
    dt = res%time - self%last_time
    if (res%nonlinear .and. res%dt > 0.0_dp) dt = res%dt
    write(self%sta, '(i6, i11, i6, i6, 3(2x, e12.6))') res%step, res%increment, self%attempt, &
      max(res%iterations, 1), res%total_time, res%time, dt
    flush(self%sta)
    self%last_time = res%time
    self%increment = res%increment + 1
    self%attempt = 1
    self%last_iteration = 0
  end subroutine sta_increment

  !> Purpose: close both files at the end of the run.
  subroutine close_status_files(self, timing)
    class(status_files_t), intent(inout) :: self
    type(run_timing_t), intent(in) :: timing
    if (.not. self%open) return
    close(self%sta)
    close(self%cvg)
    self%open = .false.
  end subroutine close_status_files
end module results_sta
