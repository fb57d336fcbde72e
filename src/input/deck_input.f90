!> Reads a keyword deck and the files it *INCLUDEs into one list of
!> significant lines, each remembering its file and line number so that
!> every later error can point at the text that caused it.
module deck_input
  use strings, only: to_upper, split_fields, field_t
  use messages, only: fatal, fatal_at
  implicit none
  private
  public :: deck_t, deck_line_t, keyword_t, read_deck, parse_keyword, &
            deck_error, deck_warning, param_value, has_param, is_keyword

  integer, parameter :: max_line = 4096
  integer, parameter :: max_include_depth = 16

  type :: deck_line_t
    character(len=:), allocatable :: text
    integer :: file = 0
    integer :: line = 0
  end type deck_line_t

  type :: deck_t
    type(deck_line_t), allocatable :: lines(:)
    integer :: n = 0
    type(field_t), allocatable :: files(:)
    integer :: nfiles = 0
  end type deck_t

  !> A keyword line taken apart: *NAME, P1=V1, FLAG, ...
  type :: keyword_t
    character(len=:), allocatable :: name
    type(field_t), allocatable :: pname(:)
    type(field_t), allocatable :: pvalue(:)
    integer :: np = 0
  end type keyword_t

contains

  subroutine read_deck(path, deck)
    character(len=*), intent(in) :: path
    type(deck_t), intent(out) :: deck
    allocate(deck%lines(1024), deck%files(8))
    call read_file(path, deck, 0)
  end subroutine read_deck

  recursive subroutine read_file(path, deck, depth)
    character(len=*), intent(in) :: path
    type(deck_t), intent(inout) :: deck
    integer, intent(in) :: depth
    character(len=max_line) :: buf
    integer :: u, ios, lineno, ifile, k
    type(keyword_t) :: kw
    character(len=:), allocatable :: inc, dir
    logical :: found

    open(newunit=u, file=path, status='old', action='read', iostat=ios)
    if (ios /= 0) call fatal('cannot open deck file "' // trim(path) // '"')
    call add_file(deck, path, ifile)
    lineno = 0
    do
      read(u, '(a)', iostat=ios) buf
      if (ios /= 0) exit
      lineno = lineno + 1
      call clean(buf)
      if (len_trim(buf) == max_line) then
        call fatal_at(path, lineno, '', 'line longer than 4095 characters')
      end if
      if (len_trim(buf) == 0) cycle
      if (is_comment(buf)) cycle
      if (is_keyword(buf)) then
        call parse_keyword(buf, kw)
        if (kw%name == 'INCLUDE') then
          inc = param_value(kw, 'INPUT')
          if (len(inc) == 0) call fatal_at(path, lineno, buf, '*INCLUDE needs INPUT=<file>')
          if (depth >= max_include_depth) call fatal_at(path, lineno, buf, &
              '*INCLUDE nested too deeply (a file including itself?)')
          if (inc(1:1) /= '/') then
            k = index(path, '/', back=.true.)
            dir = path(1:k)
            inc = dir // inc
          end if
          inquire(file=inc, exist=found)
          if (.not. found) call fatal_at(path, lineno, buf, 'include file "' // inc // '" not found')
          call read_file(inc, deck, depth + 1)
          cycle
        end if
      end if
      call add_line(deck, buf, ifile, lineno)
    end do
    close(u)
  end subroutine read_file

  !> Tabs and carriage returns (decks written on Windows) become blanks.
  subroutine clean(buf)
    character(len=*), intent(inout) :: buf
    integer :: i
    do i = 1, len_trim(buf)
      if (buf(i:i) == achar(9) .or. buf(i:i) == achar(13)) buf(i:i) = ' '
    end do
  end subroutine clean

  logical function is_comment(s)
    character(len=*), intent(in) :: s
    character(len=len(s)) :: t
    t = adjustl(s)
    is_comment = t(1:min(2, len(t))) == '**'
  end function is_comment

  logical function is_keyword(s)
    character(len=*), intent(in) :: s
    character(len=len(s)) :: t
    t = adjustl(s)
    is_keyword = t(1:1) == '*' .and. .not. is_comment(s)
  end function is_keyword

  subroutine add_file(deck, path, ifile)
    type(deck_t), intent(inout) :: deck
    character(len=*), intent(in) :: path
    integer, intent(out) :: ifile
    type(field_t), allocatable :: tmp(:)
    if (deck%nfiles == size(deck%files)) then
      allocate(tmp(2 * deck%nfiles))
      tmp(1:deck%nfiles) = deck%files(1:deck%nfiles)
      call move_alloc(tmp, deck%files)
    end if
    deck%nfiles = deck%nfiles + 1
    deck%files(deck%nfiles)%s = trim(path)
    ifile = deck%nfiles
  end subroutine add_file

  subroutine add_line(deck, text, ifile, lineno)
    type(deck_t), intent(inout) :: deck
    character(len=*), intent(in) :: text
    integer, intent(in) :: ifile, lineno
    type(deck_line_t), allocatable :: tmp(:)
    if (deck%n == size(deck%lines)) then
      allocate(tmp(2 * deck%n))
      tmp(1:deck%n) = deck%lines(1:deck%n)
      call move_alloc(tmp, deck%lines)
    end if
    deck%n = deck%n + 1
    deck%lines(deck%n)%text = trim(text)
    deck%lines(deck%n)%file = ifile
    deck%lines(deck%n)%line = lineno
  end subroutine add_line

  !> Keyword names are upper-cased with runs of blanks collapsed
  !> ("*Solid  section" -> "SOLID SECTION"); parameter names are
  !> upper-cased; values keep their case (file names) and callers
  !> fold them where the value is a name.
  subroutine parse_keyword(text, kw)
    character(len=*), intent(in) :: text
    type(keyword_t), intent(out) :: kw
    type(field_t), allocatable :: f(:)
    integer :: n, i, k
    character(len=:), allocatable :: s
    call split_fields(adjustl(text), f, n)
    s = to_upper(f(1)%s(2:))
    kw%name = collapse(trim(adjustl(s)))
    allocate(kw%pname(max(n - 1, 1)), kw%pvalue(max(n - 1, 1)))
    kw%np = 0
    do i = 2, n
      if (len(f(i)%s) == 0) cycle
      kw%np = kw%np + 1
      k = index(f(i)%s, '=')
      if (k > 0) then
        kw%pname(kw%np)%s = collapse(to_upper(trim(adjustl(f(i)%s(1:k - 1)))))
        kw%pvalue(kw%np)%s = trim(adjustl(f(i)%s(k + 1:)))
      else
        kw%pname(kw%np)%s = collapse(to_upper(trim(f(i)%s)))
        kw%pvalue(kw%np)%s = ''
      end if
    end do
  end subroutine parse_keyword

  pure function collapse(s) result(r)
    character(len=*), intent(in) :: s
    character(len=:), allocatable :: r
    integer :: i
    r = ''
    do i = 1, len_trim(s)
      if (s(i:i) == ' ' .and. i > 1) then
        if (s(i - 1:i - 1) == ' ') cycle
      end if
      r = r // s(i:i)
    end do
  end function collapse

  function param_value(kw, name) result(v)
    type(keyword_t), intent(in) :: kw
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: v
    integer :: i
    v = ''
    do i = 1, kw%np
      if (kw%pname(i)%s == name) then
        v = kw%pvalue(i)%s
        return
      end if
    end do
  end function param_value

  logical function has_param(kw, name)
    type(keyword_t), intent(in) :: kw
    character(len=*), intent(in) :: name
    integer :: i
    has_param = .false.
    do i = 1, kw%np
      if (kw%pname(i)%s == name) has_param = .true.
    end do
  end function has_param

  subroutine deck_error(deck, ifile, lineno, msg, text)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: ifile, lineno
    character(len=*), intent(in) :: msg
    character(len=*), intent(in), optional :: text
    if (present(text)) then
      call fatal_at(deck%files(ifile)%s, lineno, text, msg)
    else
      call fatal_at(deck%files(ifile)%s, lineno, '', msg)
    end if
  end subroutine deck_error

  subroutine deck_warning(deck, iline, msg)
    use messages, only: warn_at
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: iline
    character(len=*), intent(in) :: msg
    associate(l => deck%lines(iline))
      call warn_at(deck%files(l%file)%s, l%line, l%text, msg)
    end associate
  end subroutine deck_warning
end module deck_input
