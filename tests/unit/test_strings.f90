!> Text helpers of module strings: the fixed-point seconds of the listing
!> and the progress line (ftoa) keep the zero before the point and drop
!> the sign of a value that rounds to zero; the .frd's numbers (e12_5,
!> composed without an internal write) are ES12.5E2's, and int_field is
!> Iw, over values spread across the whole range; the deck's numbers
!> (parse_real, parse_int: strtod and digit sums in place of the
!> list-directed read) are the read's, bit for bit, and split_fields
!> keeps its fields.
program test_strings
  use kinds, only: dp
  use test_report, only: report, failures
  use strings, only: ftoa, e12_5, int_field, parse_real, parse_int, split_fields, field_t
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
  call check_parse_real()
  call check_parse_int()
  call check_split_fields()
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

  !> parse_real against the list-directed read on 100 000 literals of
  !> random form (sign, digits before and after the point, E, e, D or no
  !> exponent, exponent sign and digits, values near the ends of the
  !> range) and on literals strtod would read otherwise ('1+5', '.', '1e',
  !> '1.e5', '-.5d-3'): the same value bit for bit and the same verdict.
  subroutine check_parse_real()
    character(len=40) :: t
    character(len=*), parameter :: odd(12) = [character(len=12) :: '1+5', '.', '1e', '1.e5', '-.5d-3', '+', &
      '1e400', '1e-400', '0.', '1.5E+0', '-0', '1-5']
    real(dp) :: r(8), x, y
    integer :: k, bad, ios
    logical :: ok
    bad = 0
    do k = 1, 100000
      call random_number(r)
      t = ''
      if (r(1) < 0.3_dp) t = '-'
      if (r(1) > 0.9_dp) t = '+'
      t = trim(t) // digit_run(int(7 * r(2)), r(3))
      if (r(4) < 0.7_dp) t = trim(t) // '.' // digit_run(int(9 * r(5)), r(6))
      if (len_trim(t) == 0 .or. verify(trim(t), '+-.') == 0) t = trim(t) // '7'
      if (r(7) < 0.6_dp) t = trim(t) // exponent_of(r(8))
      call parse_real(t, x, ok)
      read(t, *, iostat=ios) y
      ! the read gives Infinity past huge: parse_real says it is no number
      if (ios == 0) ios = merge(0, 1, abs(y) <= huge(y))
      if (ios /= 0) then
        if (ok) bad = bad + 1
      else if (.not. ok .or. transfer(x, 1_8) /= transfer(y, 1_8)) then
        bad = bad + 1
      end if
    end do
    call report('parse_real is the list-directed read on 100 000 random literals', bad == 0, itoa_(bad) // ' differ')
    bad = 0
    do k = 1, size(odd)
      t = odd(k)
      call parse_real(t, x, ok)
      y = 0.0_dp
      read(t, *, iostat=ios) y
      if (ios == 0) ios = merge(0, 1, y == y .and. abs(y) <= huge(y))
      if (ok .neqv. ios == 0) bad = bad + 1
      if (ok .and. ios == 0 .and. transfer(x, 1_8) /= transfer(y, 1_8)) bad = bad + 1
    end do
    call report('parse_real on literals outside the plain form', bad == 0, itoa_(bad) // ' differ')
  end subroutine check_parse_real

  !> n random digits from the seed r.
  function digit_run(n, r) result(s)
    integer, intent(in) :: n
    real(dp), intent(in) :: r
    character(len=n) :: s
    integer :: i
    real(dp) :: q
    do i = 1, n
      call random_number(q)
      s(i:i) = achar(iachar('0') + min(9, int(10 * q)))
    end do
    if (n > 0 .and. r < 0.2_dp) s(1:1) = '0'
  end function digit_run

  !> An exponent: E, e, D or d, a sign or none, one to three digits
  !> (up to the ends of the range).
  function exponent_of(r) result(s)
    real(dp), intent(in) :: r
    character(len=:), allocatable :: s
    character(len=1), parameter :: letters(4) = ['E', 'e', 'D', 'd']
    real(dp) :: q(3)
    character(len=8) :: buf
    call random_number(q)
    s = letters(1 + min(3, int(4 * r)))
    if (q(1) < 0.4_dp) s = s // '-'
    if (q(1) > 0.8_dp) s = s // '+'
    write(buf, '(i0)') int(330 * q(2)**3)
    s = s // trim(buf)
  end function exponent_of

  !> parse_int against the list-directed read: signs, leading zeros,
  !> nine and ten digits, the ends of the range and past them.
  subroutine check_parse_int()
    character(len=*), parameter :: t(16) = [character(len=14) :: '0', '7', '-7', '+7', '007', '123456789', &
      '-123456789', '1234567890', '2147483647', '-2147483648', '2147483648', '99999999999', '--5', '5-3', &
      '+', '-']
    character(len=14) :: w
    integer :: k, bad, ios, a, b
    logical :: ok
    bad = 0
    do k = 1, size(t)
      w = t(k)
      call parse_int(w, a, ok)
      b = 0
      read(w, *, iostat=ios) b
      if (ok .neqv. ios == 0) bad = bad + 1
      if (ok .and. ios == 0 .and. a /= b) bad = bad + 1
    end do
    call report('parse_int is the list-directed read', bad == 0, itoa_(bad) // ' differ')
  end subroutine check_parse_int

  !> split_fields: blanks at both ends of each field removed, empty
  !> fields kept, a trailing comma makes no last field, more than 16
  !> fields.
  subroutine check_split_fields()
    type(field_t), allocatable :: f(:)
    integer :: n, k
    logical :: ok
    call split_fields('  1 ,  2.5e3,, x y ,', f, n)
    ok = n == 4
    if (ok) ok = f(1)%s == '1' .and. f(2)%s == '2.5e3' .and. len(f(3)%s) == 0 .and. f(4)%s == 'x y'
    call split_fields('', f, n)
    ok = ok .and. n == 1
    if (ok) ok = len(f(1)%s) == 0
    call split_fields(',', f, n)
    ok = ok .and. n == 1
    call split_fields(repeat('ab,', 20) // 'c', f, n)
    ok = ok .and. n == 21
    if (ok) then
      do k = 1, 20
        ok = ok .and. f(k)%s == 'ab'
      end do
      ok = ok .and. f(21)%s == 'c'
    end if
    call report('split_fields: trimmed, empty and trailing fields, more than 16', ok, '')
  end subroutine check_split_fields

  function itoa_(k) result(s)
    integer, intent(in) :: k
    character(len=:), allocatable :: s
    character(len=12) :: buf
    write(buf, '(i0)') k
    s = trim(buf)
  end function itoa_

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
