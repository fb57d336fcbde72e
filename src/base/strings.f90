!> Text helpers for the deck reader: case folding, comma splitting, and
!> number conversion that reports failure instead of raising a runtime error.
module strings
  use kinds, only: dp
  implicit none
  private
  public :: to_upper, split_fields, parse_real, parse_int, field_t, itoa, rtoa, ftoa

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
end module strings
