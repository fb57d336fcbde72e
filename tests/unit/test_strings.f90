!> Text helpers of module strings: the fixed-point seconds of the listing
!> and the progress line (ftoa) keep the zero before the point and drop
!> the sign of a value that rounds to zero; the .frd's numbers (e12_5,
!> composed without an internal write) are ES12.5E2's, and int_field is
!> Iw, over values spread across the whole range.
program test_strings
  use kinds, only: dp
  use test_report, only: report, failures
  use strings, only: ftoa, e12_5, int_field
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
  call check_e12_5()
  call check_int_field()
  if (failures() > 0) stop 1

contains

  !> e12_5 against the library's ES12.5E2 on 200 000 values of random
  !> sign, mantissa and exponent (1e-99 to 1e99) and on the edges: equal
  !> text, or, where the two round a value within 1e-12 of a half-way
  !> point of the sixth digit apart, one unit of it.
  subroutine check_e12_5()
    real(dp) :: r(3), x, a, b
    character(len=12) :: lib, own
    integer :: k, bad
    integer, allocatable :: seed(:)
    call random_seed(size=k)
    allocate(seed(k))
    seed = 12345
    call random_seed(put=seed)
    bad = 0
    do k = 1, 200000
      call random_number(r)
      x = sign(1.0_dp, r(1) - 0.5_dp) * (1.0_dp + 9.0_dp * r(2)) * 10.0_dp**(floor(198.0_dp * r(3)) - 99)
      if (abs(x) >= 1.0e99_dp) cycle
      write(lib, '(es12.5e2)') x
      own = e12_5(x)
      if (lib == own) cycle
      read(lib, *) a
      read(own, *) b
      if (abs(a - b) > 1.000001e-5_dp * 10.0_dp**floor(log10(abs(a)))) bad = bad + 1
    end do
    call report('e12_5 is ES12.5E2 on 200 000 random values', bad == 0, '')
    call report('e12_5 writes magnitudes below 1e-99 as zero', &
                e12_5(0.0_dp) == ' 0.00000E+00' .and. e12_5(-1.0e-120_dp) == ' 0.00000E+00', '')
    call report('e12_5 at a carry, a negative value and the ends of the exponent', &
                e12_5(9.999996_dp) == ' 1.00000E+01' .and. e12_5(-123.456_dp) == '-1.23456E+02' .and. &
                e12_5(1.0e-99_dp) == ' 1.00000E-99' .and. e12_5(2.5e98_dp) == ' 2.50000E+98', '')
  end subroutine check_e12_5

  subroutine check_int_field()
    character(len=10) :: lib
    integer :: k, bad, v(8)
    v = [0, 7, -7, 123456789, 1234567890, -123456789, -1234567890, 2147483647]
    bad = 0
    do k = 1, size(v)
      write(lib, '(i10)') v(k)
      if (lib /= int_field(v(k), 10)) bad = bad + 1
    end do
    call report('int_field is I10 and I5, asterisks where the number does not fit', &
                bad == 0 .and. int_field(123456, 5) == '*****' .and. int_field(-1234, 5) == '-1234', '')
  end subroutine check_int_field

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
