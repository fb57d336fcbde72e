!> Fatal errors and warnings. Every stop of the program for bad input goes
!> through here so that the message format and the exit status are uniform.
module messages
  use, intrinsic :: iso_c_binding, only: c_int
  use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
  implicit none
  private
  public :: fatal, fatal_at, warn_at, warn, register_unit_to_close, terminate

  interface
    ! libc exit: a plain non-zero status without the "STOP n" banner that
    ! gfortran prints, which would pollute the one-line error contract.
    subroutine c_exit(status) bind(C, name='exit')
      import :: c_int
      integer(c_int), value :: status
    end subroutine c_exit
  end interface

  ! newunit= numbers are negative, so a count marks the used slots.
  integer :: open_units(8) = 0
  integer :: n_open = 0

contains

  !> Units (the listing) that must reach the disk before a fatal exit, so
  !> that completed increments survive a later failure.
  subroutine register_unit_to_close(unit)
    integer, intent(in) :: unit
    if (n_open == size(open_units)) return
    n_open = n_open + 1
    open_units(n_open) = unit
  end subroutine register_unit_to_close

  subroutine terminate(status)
    integer, intent(in) :: status
    integer :: i
    logical :: opened
    do i = 1, n_open
      inquire(unit=open_units(i), opened=opened)
      if (opened) close(open_units(i))
    end do
    flush(output_unit)
    flush(error_unit)
    call c_exit(int(status, c_int))
  end subroutine terminate

  !> Error not tied to a deck line (command line, solver, convergence).
  subroutine fatal(msg)
    character(len=*), intent(in) :: msg
    write(error_unit, '(a)') 'cfe2d: error: ' // trim(msg)
    call terminate(1)
  end subroutine fatal

  !> Error in a deck: file:line: message, then the offending line quoted.
  subroutine fatal_at(file, line, text, msg)
    character(len=*), intent(in) :: file, text, msg
    integer, intent(in) :: line
    write(error_unit, '(a,":",i0,": error: ",a)') trim(file), line, trim(msg)
    if (len_trim(text) > 0) write(error_unit, '(4x,"| ",a)') trim(text)
    call terminate(1)
  end subroutine fatal_at

  subroutine warn_at(file, line, text, msg)
    character(len=*), intent(in) :: file, text, msg
    integer, intent(in) :: line
    write(error_unit, '(a,":",i0,": warning: ",a)') trim(file), line, trim(msg)
    if (len_trim(text) > 0) write(error_unit, '(4x,"| ",a)') trim(text)
  end subroutine warn_at

  subroutine warn(msg)
    character(len=*), intent(in) :: msg
    write(error_unit, '(a)') 'cfe2d: warning: ' // trim(msg)
  end subroutine warn
end module messages
