!> Reads a keyword deck and the files it *INCLUDEs into one list of
!> significant lines, each remembering its file and line number so that
!> every later error can point at the text that caused it.
module deck_input
  use, intrinsic :: iso_c_binding, only: c_char, c_int, c_long_long, c_null_char
  use, intrinsic :: iso_fortran_env, only: iostat_end, iostat_eor
  use strings, only: to_upper, split_fields, field_t, itoa
  use messages, only: fatal, fatal_at
  use growable, only: new_capacity
  implicit none
  private
  public :: deck_t, deck_line_t, keyword_t, read_deck, parse_keyword, &
            deck_error, deck_warning, param_value, has_param, is_keyword, &
            max_line, max_include_depth

  !> Longest line read (characters, blanks included); a longer one is an
  !> error rather than silently cut.
  integer, parameter :: max_line = 4096
  !> Deepest *INCLUDE nesting: the deck is level 0, a file it includes
  !> level 1, and so on up to this level.
  integer, parameter :: max_include_depth = 16

  ! Kinds of file system entries returned by cfe2d_file_kind (file_kind.c).
  integer, parameter :: kind_missing = 0, kind_regular = 1, kind_directory = 2

  interface
    function c_file_kind(path, device, inode) bind(C, name='cfe2d_file_kind') result(kind)
      import :: c_char, c_int, c_long_long
      character(kind=c_char), intent(in) :: path(*)
      integer(c_long_long), intent(out) :: device, inode
      integer(c_int) :: kind
    end function c_file_kind
  end interface

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

  !> The files being read, outermost first, identified by device and
  !> inode so that a file reached again under another path is recognised.
  type :: include_chain_t
    integer(c_long_long) :: device(0:max_include_depth) = 0
    integer(c_long_long) :: inode(0:max_include_depth) = 0
  end type include_chain_t

contains

  !> Purpose: read the deck at `path` and every file it includes into one
  !> list of significant lines (no comments, no blank lines).
  !> The deck must be a regular file; so must every included file.
  subroutine read_deck(path, deck)
    character(len=*), intent(in) :: path
    type(deck_t), intent(out) :: deck
    type(include_chain_t) :: chain
    allocate(deck%lines(1024), deck%files(8))
    select case (file_kind(path, chain%device(0), chain%inode(0)))
    case (kind_missing)
      call fatal('cannot open deck file "' // trim(path) // '"')
    case (kind_directory)
      call fatal('deck "' // trim(path) // '" is a directory, not a regular file')
    case (kind_regular)
    case default
      call fatal('deck "' // trim(path) // '" is not a regular file (a device, FIFO or socket)')
    end select
    call read_file(path, deck, 0, chain)
  end subroutine read_deck

  integer function file_kind(path, device, inode)
    character(len=*), intent(in) :: path
    integer(c_long_long), intent(out) :: device, inode
    file_kind = int(c_file_kind(trim(path) // c_null_char, device, inode))
  end function file_kind

  recursive subroutine read_file(path, deck, depth, chain)
    character(len=*), intent(in) :: path
    type(deck_t), intent(inout) :: deck
    integer, intent(in) :: depth
    type(include_chain_t), intent(inout) :: chain
    character(len=max_line + 1) :: buf
    integer :: u, ios, lineno, ifile, nc
    type(keyword_t) :: kw
    character(len=:), allocatable :: inc

    open(newunit=u, file=path, status='old', action='read', iostat=ios)
    if (ios /= 0) call fatal('cannot open deck file "' // trim(path) // '"')
    call add_file(deck, path, ifile)
    lineno = 0
    do
      read(u, '(a)', advance='no', iostat=ios, size=nc) buf
      if (ios == iostat_end) exit
      lineno = lineno + 1
      ! ios == 0: the buffer (one character more than allowed) filled up
      ! before the end of the line.
      if (ios == 0) call fatal_at(path, lineno, '', 'line longer than ' // itoa(max_line) // ' characters')
      if (ios /= iostat_eor) call fatal_at(path, lineno, '', 'cannot read this line (not a text file?)')
      ! only the nc characters read are looked at (the rest of the buffer
      ! is blank): a million-line mesh is not scanned 4 kB per line
      call clean(buf(1:nc))
      if (len_trim(buf(1:nc)) == 0) cycle
      if (is_comment(buf(1:nc))) cycle
      if (is_keyword(buf(1:nc))) then
        call parse_keyword(buf(1:nc), kw)
        if (kw%name == 'INCLUDE') then
          inc = include_path(path, lineno, buf(1:nc), kw, depth, chain)
          call read_file(inc, deck, depth + 1, chain)
          cycle
        end if
      end if
      call add_line(deck, buf(1:nc), ifile, lineno)
    end do
    close(u)
  end subroutine read_file

  !> Purpose: the file named by an *INCLUDE card (relative to the including
  !> file), checked before it is opened: it must exist, be a regular file,
  !> not be one of the files being read, and not nest too deeply.
  function include_path(path, lineno, text, kw, depth, chain) result(inc)
    character(len=*), intent(in) :: path, text
    integer, intent(in) :: lineno, depth
    type(keyword_t), intent(in) :: kw
    type(include_chain_t), intent(inout) :: chain
    character(len=:), allocatable :: inc
    integer(c_long_long) :: device, inode
    integer :: k
    inc = param_value(kw, 'INPUT')
    if (len(inc) == 0) call fatal_at(path, lineno, text, '*INCLUDE needs INPUT=<file>')
    if (inc(1:1) /= '/') then
      k = index(path, '/', back=.true.)
      inc = path(1:k) // inc
    end if
    select case (file_kind(inc, device, inode))
    case (kind_missing)
      call fatal_at(path, lineno, text, 'include file "' // inc // '" not found')
    case (kind_directory)
      call fatal_at(path, lineno, text, 'include file "' // inc // '" is a directory, not a regular file')
    case (kind_regular)
    case default
      call fatal_at(path, lineno, text, 'include file "' // inc // &
                    '" is not a regular file (a device, FIFO or socket)')
    end select
    do k = 0, depth
      if (chain%device(k) == device .and. chain%inode(k) == inode) call fatal_at(path, lineno, text, &
          'recursive *INCLUDE: "' // inc // '" is already being read (it includes itself)')
    end do
    if (depth >= max_include_depth) call fatal_at(path, lineno, text, &
        '*INCLUDE nested more than ' // itoa(max_include_depth) // ' levels deep')
    chain%device(depth + 1) = device
    chain%inode(depth + 1) = inode
  end function include_path

  !> Tabs and carriage returns (decks written on Windows) become blanks.
  subroutine clean(buf)
    character(len=*), intent(inout) :: buf
    integer :: i
    do i = 1, len_trim(buf)
      if (buf(i:i) == achar(9) .or. buf(i:i) == achar(13)) buf(i:i) = ' '
    end do
  end subroutine clean

  !> A comment line: "**" at its first non-blank character. (The first
  !> non-blank is found in place: an adjusted copy of every line, taken
  !> for each test in each of the parser's passes, cost more than the test.)
  logical function is_comment(s)
    character(len=*), intent(in) :: s
    integer :: k
    k = verify(s, ' ')
    is_comment = .false.
    if (k > 0 .and. k < len(s)) is_comment = s(k:k + 1) == '**'
  end function is_comment

  !> A keyword line: "*" at its first non-blank character, not a comment.
  logical function is_keyword(s)
    character(len=*), intent(in) :: s
    integer :: k
    k = verify(s, ' ')
    is_keyword = .false.
    if (k > 0) is_keyword = s(k:k) == '*'
    if (is_keyword .and. k < len(s)) is_keyword = s(k + 1:k + 1) /= '*'
  end function is_keyword

  subroutine add_file(deck, path, ifile)
    type(deck_t), intent(inout) :: deck
    character(len=*), intent(in) :: path
    integer, intent(out) :: ifile
    type(field_t), allocatable :: tmp(:)
    ! deck_t's own types: growable's generic grow cannot take them.
    if (deck%nfiles == size(deck%files)) then
      allocate(tmp(new_capacity(deck%nfiles, deck%nfiles + 1)))
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
    integer :: i
    if (deck%n == size(deck%lines)) then
      allocate(tmp(new_capacity(deck%n, deck%n + 1)))
      ! each line's text moved, not copied: an assignment of the array
      ! would allocate and copy every line again at every growth
      do i = 1, deck%n
        call move_alloc(deck%lines(i)%text, tmp(i)%text)
        tmp(i)%file = deck%lines(i)%file
        tmp(i)%line = deck%lines(i)%line
      end do
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

  !> Runs of blanks as one blank (blanks at the start are kept).
  pure function collapse(s) result(r)
    character(len=*), intent(in) :: s
    character(len=:), allocatable :: r
    character(len=len(s)) :: buf
    integer :: i, n
    n = 0
    do i = 1, len_trim(s)
      if (s(i:i) == ' ' .and. i > 1) then
        if (s(i - 1:i - 1) == ' ') cycle
      end if
      n = n + 1
      buf(n:n) = s(i:i)
    end do
    r = buf(1:n)
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
