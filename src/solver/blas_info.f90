!> Which BLAS the program runs on, and on how many threads: cfe2d links
!> OpenBLAS, which reports its build and thread count. The thread policy
!> (thread_shim.c) is applied before either is reported or used: one
!> thread for the BLAS and for CHOLMOD's OpenMP loops unless the
!> environment (OPENBLAS_NUM_THREADS, OMP_NUM_THREADS, ...) asks otherwise.
module blas_info
  use, intrinsic :: iso_c_binding
  implicit none
  private
  public :: blas_description, set_solver_threads

  interface
    type(c_ptr) function openblas_get_config() bind(C, name='openblas_get_config')
      import :: c_ptr
    end function openblas_get_config

    integer(c_int) function cfe_solver_threads() bind(C, name='cfe_solver_threads')
      import :: c_int
    end function cfe_solver_threads
  end interface

contains

  !> Applies the thread policy (once per run; later calls do nothing).
  subroutine set_solver_threads()
    integer(c_int) :: nthreads
    nthreads = cfe_solver_threads()
  end subroutine set_solver_threads

  function blas_description() result(s)
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
  end function blas_description
end module blas_info
