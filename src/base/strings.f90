!> Text helpers for the deck reader: case folding, comma splitting, and
!> number conversion that reports failure instead of raising a runtime error.
module strings
  use kinds, only: dp
  implicit none
  private
  public :: to_upper, split_fields, parse_real, parse_int, field_t, itoa, rtoa, ftoa, e12_5, int_field

  !> One comma-separated field of a deck line, blanks removed at both ends.
  type :: field_t
    character(len=:), allocatable :: s
  end type field_t

contains

  pure function to_upper(s) result(u)
    character(len=*), intent(in) :: s
    character(len=len(s)) :: u
    integer :: i, c
    u = s
    do i = 1, len(s)
      c = iachar(s(i:i))
      if (c >= iachar('a') .and. c <= iachar('z')) u(i:i) = achar(c - 32)
    end do
  end function to_upper

  !> Split at commas; a trailing comma does not make an empty last field
  !> (gmsh and Abaqus both end list lines with one).
  subroutine split_fields(line, fields, n)
    character(len=*), intent(in) :: line
    type(field_t), allocatable, intent(out) :: fields(:)
    integer, intent(out) :: n
    integer :: start, k, last
    type(field_t), allocatable :: tmp(:)
    allocate(fields(16))
    n = 0
    start = 1
    last = len_trim(line)
    do
      k = index(line(start:last), ',')
      if (n == size(fields)) then
        allocate(tmp(2 * n))
        tmp(1:n) = fields(1:n)
        call move_alloc(tmp, fields)
      end if
      n = n + 1
      if (k == 0) then
        fields(n)%s = trim(adjustl(line(start:last)))
        exit
      end if
      fields(n)%s = trim(adjustl(line(start:start + k - 2)))
      start = start + k
      if (start > last) exit
    end do
  end subroutine split_fields

  subroutine parse_real(s, x, ok)
    character(len=*), intent(in) :: s
    real(dp), intent(out) :: x
    logical, intent(out) :: ok
    integer :: ios, i
    character(len=1) :: c
    x = 0.0_dp
    ok = .false.
    if (len_trim(s) == 0) return
    ! List-directed reads accept things a number is not ('1 2', '/', 'T');
    ! only the characters of a real literal are let through.
    do i = 1, len_trim(s)
      c = s(i:i)
      if (index('0123456789+-.eEdD', c) == 0) return
    end do
    read(s, *, iostat=ios) x
    ok = (ios == 0)
    if (ok) ok = (x == x) .and. abs(x) <= huge(x)
  end subroutine parse_real

  subroutine parse_int(s, k, ok)
    character(len=*), intent(in) :: s
    integer, intent(out) :: k
    logical, intent(out) :: ok
    integer :: ios, i
    character(len=1) :: c
    k = 0
    ok = .false.
    if (len_trim(s) == 0) return
    do i = 1, len_trim(s)
      c = s(i:i)
      if (index('0123456789+-', c) == 0) return
    end do
    read(s, *, iostat=ios) k
    ok = (ios == 0)
  end subroutine parse_int

  !> An integer as text without blanks.
  pure function itoa(k) result(s)
    integer, intent(in) :: k
    character(len=:), allocatable :: s
    character(len=16) :: buf
    write(buf, '(i0)') k
    s = trim(buf)
  end function itoa

  !> A real as text without blanks (key=value fields, messages) with
  !> `digits` significant digits.
  pure function rtoa(x, digits) result(s)
    real(dp), intent(in) :: x
    integer, intent(in) :: digits
    character(len=:), allocatable :: s
    character(len=40) :: buf, fmt
    ! A three-digit exponent needs its width given, or the E is dropped
    ! (1e160 would print as 1.0+160).
    if (abs(x) >= 1.0e99_dp .or. (x /= 0.0_dp .and. abs(x) < 1.0e-98_dp)) then
      write(fmt, '(a,i0,a,i0,a)') '(es', digits + 9, '.', digits - 1, 'e3)'
    else
      write(fmt, '(a,i0,a,i0,a)') '(es', digits + 8, '.', digits - 1, ')'
    end if
    write(buf, fmt) x
    s = trim(adjustl(buf))
  end function rtoa

  !> A real as fixed-point text without blanks, `decimals` after the point
  !> (times in seconds: 0.041). Values below 1 keep their leading zero,
  !> which the F edit descriptor may drop (f0.2 writes .04), and a value
  !> that rounds to zero has no sign (-0.0001 and -0.0 give 0.000).
  pure function ftoa(x, decimals) result(s)
    real(dp), intent(in) :: x
    integer, intent(in) :: decimals
    character(len=:), allocatable :: s
    character(len=40) :: buf, fmt
    write(fmt, '(a,i0,a)') '(f40.', decimals, ')'
    write(buf, fmt) x
    s = trim(adjustl(buf))
    if (s(1:1) == '-' .and. verify(s, '-0.') == 0) s = s(2:)
    if (s(1:1) == '.') then
      s = '0' // s
    else if (len(s) > 1) then
      if (s(1:2) == '-.') s = '-0' // s(2:)
    end if
  end function ftoa

  !> Purpose: a real as Fortran's ES12.5E2 writes it (' 1.23456E+02', the
  !> numbers of CalculiX's .frd);
  !> magnitudes below 1e-99 as zero, so that the exponent keeps two digits.
  !> Composed digit by digit: an internal write per number made the
  !> flagship's 83 MB .frd (results_frd) take 4.5 s of a 6.3 s run. The six significant
  !> digits are the nearest to x * 10**(5 - e) (within the last bit of x
  !> of the library's correctly rounded ones); what E12.5 cannot hold
  !> (1e100 and above, not finite) is left to the library.
  pure function e12_5(x) result(s)
    real(dp), intent(in) :: x
    character(len=12) :: s
    real(dp) :: a
    integer :: e
    integer(8) :: mant
    a = abs(x)
    if (a < 1.0e-99_dp) then
      s = ' 0.00000E+00'
      return
    end if
    if (.not. (a < 1.0e99_dp)) then
      write(s, '(es12.5e2)') x
      return
    end if
    e = floor(log10(a))
    mant = nint(a * 10.0_dp**(5 - e), 8)
    if (mant >= 1000000_8) then
      e = e + 1
      mant = nint(a * 10.0_dp**(5 - e), 8)
    else if (mant < 100000_8) then
      e = e - 1
      mant = nint(a * 10.0_dp**(5 - e), 8)
    end if
    if (mant >= 1000000_8 .or. mant < 100000_8 .or. abs(e) > 99) then
      write(s, '(es12.5e2)') x
      return
    end if
    s = merge('-', ' ', x < 0.0_dp) // digits(int(mant / 100000_8), 1) // '.' // &
        digits(int(mod(mant, 100000_8)), 5) // 'E' // merge('-', '+', e < 0) // digits(abs(e), 2)
  end function e12_5

  !> The n digits of 0 <= i < 10**n, with leading zeros.
  pure function digits(i, n) result(s)
    integer, intent(in) :: i, n
    character(len=n) :: s
    integer :: k, r
    r = i
    do k = n, 1, -1
      s(k:k) = achar(iachar('0') + mod(r, 10))
      r = r / 10
    end do
  end function digits

  !> An integer right-aligned in a field of width w, as Fortran's Iw
  !> (asterisks where it does not fit).
  pure function int_field(i, w) result(s)
    integer, intent(in) :: i, w
    character(len=w) :: s
    integer :: k, r
    s = repeat(' ', w)
    r = abs(i)
    k = w
    do
      s(k:k) = achar(iachar('0') + mod(r, 10))
      r = r / 10
      k = k - 1
      if (r == 0 .or. k == 0) exit
    end do
    if (r > 0 .or. (i < 0 .and. k == 0)) then
      s = repeat('*', w)
    else if (i < 0) then
      s(k:k) = '-'
    end if
  end function int_field
end module strings
