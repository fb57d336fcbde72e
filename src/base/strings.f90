!> Text helpers for the deck reader: case folding, comma splitting, and
!> number conversion that reports failure instead of raising a runtime error.
module strings
  use, intrinsic :: iso_c_binding, only: c_char, c_double, c_ptr, c_null_char, c_loc, c_intptr_t
  use kinds, only: dp
  implicit none
  private
  public :: to_upper, split_fields, parse_real, parse_int, field_t, itoa, rtoa, ftoa, e12_5, int_field

  !> 10**k for |k| <= 22: exact from 1 to 1e22, correctly rounded below 1
  !> (pow10, e12_5's scaling).
  real(dp), parameter :: powers_of_ten(-22:22) = [1.0e-22_dp, 1.0e-21_dp, 1.0e-20_dp, 1.0e-19_dp, 1.0e-18_dp, &
    1.0e-17_dp, 1.0e-16_dp, 1.0e-15_dp, 1.0e-14_dp, 1.0e-13_dp, 1.0e-12_dp, 1.0e-11_dp, 1.0e-10_dp, 1.0e-9_dp, &
    1.0e-8_dp, 1.0e-7_dp, 1.0e-6_dp, 1.0e-5_dp, 1.0e-4_dp, 1.0e-3_dp, 1.0e-2_dp, 1.0e-1_dp, 1.0_dp, 1.0e1_dp, &
    1.0e2_dp, 1.0e3_dp, 1.0e4_dp, 1.0e5_dp, 1.0e6_dp, 1.0e7_dp, 1.0e8_dp, 1.0e9_dp, 1.0e10_dp, 1.0e11_dp, &
    1.0e12_dp, 1.0e13_dp, 1.0e14_dp, 1.0e15_dp, 1.0e16_dp, 1.0e17_dp, 1.0e18_dp, 1.0e19_dp, 1.0e20_dp, &
    1.0e21_dp, 1.0e22_dp]

  interface
    !> The C library's strtod (C99 7.20.1.3): the double a decimal
    !> literal names, correctly rounded; *endptr past its last character.
    function c_strtod(str, endptr) bind(C, name='strtod') result(x)
      import :: c_char, c_double, c_ptr
      character(kind=c_char), intent(in) :: str(*)
      type(c_ptr), value :: endptr
      real(c_double) :: x
    end function c_strtod
  end interface

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

  !> Purpose: split a deck line at commas, each field with the blanks at
  !> both ends removed; a trailing comma does not make an empty last field
  !> (gmsh and Abaqus both end list lines with one).
  !> Arguments: line the text; fields(n) the fields (at least 16 allocated);
  !> n how many. Each field's ends are found in place, with no adjusted
  !> copy of the line (a million-line mesh is split in one pass per line).
  subroutine split_fields(line, fields, n)
    character(len=*), intent(in) :: line
    type(field_t), allocatable, intent(out) :: fields(:)
    integer, intent(out) :: n
    integer :: start, k, last, ncomma
    last = len_trim(line)
    ncomma = 0
    do k = 1, last
      if (line(k:k) == ',') ncomma = ncomma + 1
    end do
    allocate(fields(max(16, ncomma + 1)))
    n = 0
    start = 1
    do
      k = index(line(start:last), ',')
      n = n + 1
      if (k == 0) then
        call set_field(fields(n), line, start, last)
        exit
      end if
      call set_field(fields(n), line, start, start + k - 2)
      start = start + k
      if (start > last) exit
    end do
  end subroutine split_fields

  !> Purpose: f holds line(a:b) without its leading and trailing blanks.
  !> Arguments: f the field set; line the text; a, b the field's range.
  subroutine set_field(f, line, a, b)
    type(field_t), intent(inout) :: f
    character(len=*), intent(in) :: line
    integer, intent(in) :: a, b
    integer :: i, j
    i = a
    j = b
    do while (i <= j)
      if (line(i:i) /= ' ') exit
      i = i + 1
    end do
    do while (j >= i)
      if (line(j:j) /= ' ') exit
      j = j - 1
    end do
    f%s = line(i:j)
  end subroutine set_field

  !> Purpose: x from the text of a real number; ok false (x = 0) where
  !> the text is not one or is not finite.
  !> Arguments: s the text (blanks at its end allowed); x the value; ok.
  !> A plain literal (sign, digits, point, exponent with E or D) is
  !> converted by the C library's strtod, which is what gfortran's
  !> list-directed read calls for it, so the value is the same bit for
  !> bit; anything else goes to the list-directed read as before.
  subroutine parse_real(s, x, ok)
    character(len=*), intent(in) :: s
    real(dp), intent(out) :: x
    logical, intent(out) :: ok
    integer :: ios, i, n
    character(len=1) :: c
    x = 0.0_dp
    ok = .false.
    n = len_trim(s)
    if (n == 0) return
    ! List-directed reads accept things a number is not ('1 2', '/', 'T');
    ! only the characters of a real literal are let through.
    do i = 1, n
      c = s(i:i)
      select case (c)
      case ('0':'9', '+', '-', '.', 'e', 'E', 'd', 'D')
      case default
        return
      end select
    end do
    if (plain_literal(s(1:n))) then
      call c_library_real(s(1:n), x, ok)
    end if
    if (.not. ok) then
      x = 0.0_dp
      read(s, *, iostat=ios) x
      ok = (ios == 0)
    end if
    if (ok) ok = (x == x) .and. abs(x) <= huge(x)
  end subroutine parse_real

  !> Purpose: is s [sign] digits [. digits] [(E|D) [sign] digits], with
  !> at least one digit before the exponent? (The literals strtod and
  !> Fortran read alike.)
  !> Arguments: s the text, no blanks.
  pure logical function plain_literal(s)
    character(len=*), intent(in) :: s
    integer :: i, n, mant
    plain_literal = .false.
    n = len(s)
    i = 1
    if (s(1:1) == '+' .or. s(1:1) == '-') i = 2
    mant = 0
    do while (i <= n)
      if (.not. is_digit(s(i:i))) exit
      mant = mant + 1
      i = i + 1
    end do
    if (i <= n) then
      if (s(i:i) == '.') then
        i = i + 1
        do while (i <= n)
          if (.not. is_digit(s(i:i))) exit
          mant = mant + 1
          i = i + 1
        end do
      end if
    end if
    if (mant == 0) return
    if (i > n) then
      plain_literal = .true.
      return
    end if
    if (index('eEdD', s(i:i)) == 0) return
    i = i + 1
    if (i <= n) then
      if (s(i:i) == '+' .or. s(i:i) == '-') i = i + 1
    end if
    if (i > n) return
    do while (i <= n)
      if (.not. is_digit(s(i:i))) return
      i = i + 1
    end do
    plain_literal = .true.
  end function plain_literal

  !> Purpose: is c one of 0-9? Arguments: c the character.
  pure logical function is_digit(c)
    character(len=1), intent(in) :: c
    is_digit = c >= '0' .and. c <= '9'
  end function is_digit

  !> Purpose: strtod of a plain literal (plain_literal), its D exponent
  !> written E; ok only if strtod took every character (a locale whose
  !> decimal mark is not '.' would stop it early: the caller then reads
  !> the text as before).
  !> Arguments: s the literal; x its value; ok.
  subroutine c_library_real(s, x, ok)
    character(len=*), intent(in) :: s
    real(dp), intent(out) :: x
    logical, intent(out) :: ok
    character(kind=c_char), target :: buf(64)
    type(c_ptr), target :: endp
    integer(c_intptr_t) :: used
    integer :: i, n
    n = len(s)
    ok = .false.
    x = 0.0_dp
    if (n >= size(buf)) return
    do i = 1, n
      buf(i) = s(i:i)
      if (buf(i) == 'd' .or. buf(i) == 'D') buf(i) = 'e'
    end do
    buf(n + 1) = c_null_char
    x = real(c_strtod(buf, c_loc(endp)), dp)
    used = transfer(endp, used) - transfer(c_loc(buf), used)
    ok = used == int(n, c_intptr_t)
  end subroutine c_library_real

  !> Purpose: k from the text of an integer; ok false (k = 0) where the
  !> text is not one or is out of range.
  !> Arguments: s the text (blanks at its end allowed); k; ok.
  !> Up to nine digits after an optional sign are summed here (no
  !> overflow possible); longer or odder text goes to the list-directed
  !> read as before.
  subroutine parse_int(s, k, ok)
    character(len=*), intent(in) :: s
    integer, intent(out) :: k
    logical, intent(out) :: ok
    integer :: ios, i, n, i0
    character(len=1) :: c
    k = 0
    ok = .false.
    n = len_trim(s)
    if (n == 0) return
    i0 = 1
    if (s(1:1) == '+' .or. s(1:1) == '-') i0 = 2
    if (n >= i0 .and. n - i0 < 9) then
      ok = .true.
      do i = i0, n
        if (.not. is_digit(s(i:i))) then
          ok = .false.
          exit
        end if
        k = 10 * k + (iachar(s(i:i)) - iachar('0'))
      end do
      if (ok) then
        if (s(1:1) == '-') k = -k
        return
      end if
      k = 0
    end if
    do i = 1, n
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
    integer :: e, r, k
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
    e = decade(a)
    mant = nint(a * pow10(5 - e), 8)
    if (mant >= 1000000_8) then
      e = e + 1
      mant = nint(a * pow10(5 - e), 8)
    else if (mant < 100000_8) then
      e = e - 1
      mant = nint(a * pow10(5 - e), 8)
    end if
    if (mant >= 1000000_8 .or. mant < 100000_8 .or. abs(e) > 99) then
      write(s, '(es12.5e2)') x
      return
    end if
    ! the characters set one by one: a concatenation of merge and digit
    ! strings made temporaries that cost more than the arithmetic
    s(1:1) = ' '
    if (x < 0.0_dp) s(1:1) = '-'
    r = int(mant)
    do k = 8, 4, -1
      s(k:k) = achar(iachar('0') + mod(r, 10))
      r = r / 10
    end do
    s(2:2) = achar(iachar('0') + r)
    s(3:3) = '.'
    s(9:9) = 'E'
    s(10:10) = '+'
    if (e < 0) s(10:10) = '-'
    s(11:11) = achar(iachar('0') + abs(e) / 10)
    s(12:12) = achar(iachar('0') + mod(abs(e), 10))
  end function e12_5

  !> Purpose: 10**k as the library's real**integer gives it: from the
  !> table for |k| <= 22, where every power is exact (or, negative, the
  !> correctly rounded quotient 1 / 10**|k| that the library computes);
  !> computed beyond.
  !> Arguments: k the exponent.
  pure real(dp) function pow10(k)
    integer, intent(in) :: k
    if (abs(k) <= 22) then
      pow10 = powers_of_ten(k)
    else
      pow10 = 10.0_dp**k
    end if
  end function pow10

  !> Purpose: floor(log10(a)) of 0 < a < 1e99, or one of its neighbours
  !> next to a power of ten (where e12_5's carry makes them give the same
  !> digits): from a's binary exponent and one comparison with the table
  !> between 1e-15 and 1e15, the logarithm elsewhere.
  !> Arguments: a the magnitude.
  pure integer function decade(a)
    real(dp), intent(in) :: a
    ! log10(2) rounded down: (exponent - 1) log10(2) <= log10(a)
    real(dp), parameter :: log10_2 = 0.30102999566398114_dp
    if (a >= 1.0e-15_dp .and. a < 1.0e15_dp) then
      decade = floor((exponent(a) - 1) * log10_2)
      if (a >= powers_of_ten(decade + 1)) decade = decade + 1
    else
      decade = floor(log10(a))
    end if
  end function decade

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
