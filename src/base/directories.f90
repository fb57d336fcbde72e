!> Directories on the file system: making an output directory with its
!> missing parents (mkdir -p), through the C shim make_dirs.c, since
!> Fortran 2008 cannot create a directory.
module directories
  use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char
  implicit none
  private
  public :: make_directories

  interface
    function c_make_dirs(path, msg, msglen) bind(C, name='cfe2d_make_dirs') result(err)
      import :: c_char, c_int
      character(kind=c_char), intent(in) :: path(*)
      character(kind=c_char), intent(out) :: msg(*)
      integer(c_int), value :: msglen
      integer(c_int) :: err
    end function c_make_dirs
  end interface

contains

  !> Purpose: make directory `path` and every missing parent; an existing
  !> directory is fine.
  !> Arguments:
  !>   path    the directory (relative or absolute; blanks at the end are
  !>           not part of it)
  !>   ok      true when path is a directory afterwards
  !>   reason  when not ok: the level that could not be made and why
  !>           ("out/a: Permission denied"); empty otherwise
  subroutine make_directories(path, ok, reason)
    character(len=*), intent(in) :: path
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: reason
    character(kind=c_char) :: msg(1024)
    integer :: n, i
    ok = c_make_dirs(trim(path) // c_null_char, msg, int(size(msg), c_int)) == 0
    n = 0
    do while (.not. ok .and. n < size(msg))
      if (msg(n + 1) == c_null_char) exit
      n = n + 1
    end do
    allocate(character(len=n) :: reason)
    do i = 1, n
      reason(i:i) = msg(i)
    end do
  end subroutine make_directories
end module directories
