!> Which BLAS the program runs on: cfe2d links OpenBLAS, which reports its
!> build and thread count.
module blas_info
  use, intrinsic :: iso_c_binding
  implicit none
  private
  public :: blas_description

  interface
    type(c_ptr) function openblas_get_config() bind(C, name='openblas_get_config')
      import :: c_ptr
    end function openblas_get_config
    integer(c_int) function openblas_get_num_threads() bind(C, name='openblas_get_num_threads')
      import :: c_int
    end function openblas_get_num_threads
  end interface

contains

  function blas_description() result(s)
    character(len=:), allocatable :: s
    character(kind=c_char), pointer :: cfg(:)
    type(c_ptr) :: p
    integer :: n
    character(len=16) :: buf
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
    write(buf, '(i0)') openblas_get_num_threads()
    s = s // ' (' // trim(buf) // ' threads)'
  end function blas_description
end module blas_info
