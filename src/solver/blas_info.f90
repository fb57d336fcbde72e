!> Which BLAS the program runs on, and on how many threads: cfe2d links
!> OpenBLAS, which reports its build and thread count. The thread policy
!> (thread_shim.c) is applied before either is reported or used: the
!> element loops on OMP_NUM_THREADS threads (one if it is not set), one
!> thread for the BLAS and for CHOLMOD's OpenMP loops unless the
!> environment (OPENBLAS_NUM_THREADS, OMP_MAX_ACTIVE_LEVELS, ...) asks
!> otherwise. An element loop runs its parallel region between team_open
!> and team_close, on element_threads() threads.
module blas_info
  use, intrinsic :: iso_c_binding
  implicit none
  private
  public :: blas_description, set_solver_threads, element_threads, team_open, team_close

  interface
    type(c_ptr) function openblas_get_config() bind(C, name='openblas_get_config')
      import :: c_ptr
    end function openblas_get_config

    integer(c_int) function cfe_solver_threads() bind(C, name='cfe_solver_threads')
      import :: c_int
    end function cfe_solver_threads

    integer(c_int) function cfe_element_threads() bind(C, name='cfe_element_threads')
      import :: c_int
    end function cfe_element_threads

    subroutine cfe_team_open() bind(C, name='cfe_team_open')
    end subroutine cfe_team_open

    subroutine cfe_team_close() bind(C, name='cfe_team_close')
    end subroutine cfe_team_close
  end interface

contains

  !> Applies the thread policy (once per run; later calls do nothing).
  subroutine set_solver_threads()
    integer(c_int) :: nthreads
    nthreads = cfe_solver_threads()
  end subroutine set_solver_threads

  !> Purpose: the number of threads of the element loops: OMP_NUM_THREADS
  !> if set, else 1; 1 in a build without OpenMP (-fopenmp), whose
  !> parallel regions are comments.
  integer function element_threads()
    element_threads = 1
    !$ element_threads = int(cfe_element_threads())
  end function element_threads

  !> Purpose: before an element loop's parallel region: one OpenMP level
  !> active for its team (outside the element loops none is: CHOLMOD's
  !> own loops stay on one thread, thread_shim.c).
  subroutine team_open()
    !$ call cfe_team_open()
  end subroutine team_open

  !> Purpose: after an element loop's parallel region: no active level.
  subroutine team_close()
    !$ call cfe_team_close()
  end subroutine team_close

  !> Purpose: the listing's `blas` line: the BLAS's build and threads, and,
  !> when the element loops run on more than one thread, their count (the
  !> line of a one-thread run is as it was before the element threads).
  function blas_description() result(s)
    character(len=:), allocatable :: s
    character(len=16) :: buf
    s = blas_build()
    if (element_threads() > 1) then
      write(buf, '(i0)') element_threads()
      s = s // '; element loops on ' // trim(buf) // ' threads'
    end if
  end function blas_description

  !> Purpose: OpenBLAS's configuration string and its thread count.
  function blas_build() result(s)
    character(len=:), allocatable :: s
    character(kind=c_char), pointer :: cfg(:)
    type(c_ptr) :: p
    integer :: n, nthreads
    character(len=16) :: buf
    nthreads = int(cfe_solver_threads())
    p = openblas_get_config()
    s = 'OpenBLAS'
    if (.not. c_associated(p)) return
    call c_f_pointer(p, cfg, [256])
    n = 0
    do while (n < 256)
      if (cfg(n + 1) == c_null_char) exit
      n = n + 1
    end do
    s = 'OpenBLAS ' // transfer(cfg(1:n), repeat(' ', n))
    if (nthreads < 0) return
    write(buf, '(i0)') nthreads
    s = s // ' (' // trim(buf) // merge(' thread) ', ' threads)', nthreads == 1)
    s = trim(s)
  end function blas_build
end module blas_info
