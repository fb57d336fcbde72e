!> Text helpers of module strings: the fixed-point seconds of the listing
!> and the progress line (ftoa) keep the zero before the point and drop
!> the sign of a value that rounds to zero.
program test_strings
  use kinds, only: dp
  use test_report, only: report, failures
  use strings, only: ftoa
  implicit none

  call check(0.041_dp, 3, '0.041')
  call check(0.004_dp, 2, '0.00')
  call check(0.0_dp, 2, '0.00')
  call check(0.0_dp, 3, '0.000')
  call check(-0.0_dp, 3, '0.000')
  call check(-0.0001_dp, 3, '0.000')
  call check(-0.25_dp, 2, '-0.25')
  call check(0.999_dp, 2, '1.00')
  call check(12.5_dp, 3, '12.500')
  call check(1234.5678_dp, 1, '1234.6')
  if (failures() > 0) stop 1

contains

  subroutine check(x, decimals, expected)
    real(dp), intent(in) :: x
    integer, intent(in) :: decimals
    character(len=*), intent(in) :: expected
    character(len=:), allocatable :: got
    character(len=16) :: buf
    got = ftoa(x, decimals)
    write(buf, '(es10.2e2)') x
    call report('ftoa(' // trim(adjustl(buf)) // ', ' // achar(iachar('0') + decimals) // ') = ' // expected, &
                got == expected, 'got "' // got // '"')
  end subroutine check
end program test_strings
