!> PASS/FAIL lines of the Fortran unit-test programs, read by
!> tests/run_tests.py, and the failure count for their exit status.
module test_report
  implicit none
  private
  public :: report, failures

  integer :: nfail = 0

contains

  subroutine report(name, ok, detail)
    character(len=*), intent(in) :: name, detail
    logical, intent(in) :: ok
    if (ok) then
      print '(a)', 'PASS ' // name
    else
      print '(a)', 'FAIL ' // name // ': ' // detail
      nfail = nfail + 1
    end if
  end subroutine report

  integer function failures()
    failures = nfail
  end function failures
end module test_report
