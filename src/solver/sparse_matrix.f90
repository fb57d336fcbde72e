!> Compressed-column (CSC) matrices assembled straight from element arrays:
!> the pattern is computed once from the element equation lists, together
!> with the position in the value array of every element entry, so that
!> re-assembly only adds into place. Symmetric matrices keep the upper
!> triangle (CHOLMOD), unsymmetric solvers the full pattern (UMFPACK).
module sparse_matrix
  use kinds, only: dp
  implicit none
  private
  public :: csc_t, csc_build, csc_zero, csc_add_element, csc_matvec, csc_add_upper

  type :: csc_t
    integer :: n = 0
    logical :: upper = .true.
    integer, allocatable :: colptr(:)     ! 1-based, n+1
    integer, allocatable :: rowind(:)     ! 1-based, sorted in each column
    real(dp), allocatable :: val(:)
    ! position in val of entry (a, b) of element e: emap(eptr(e) + k), k
    ! running over the pairs in the order csc_add_element visits them;
    ! without the map (a matrix assembled once) positions are searched
    integer(8), allocatable :: eptr(:)
    integer, allocatable :: emap(:)
    ! map_later: the map is made by csc_zero once values have been added
    ! (added), that is for a matrix assembled a second time; until then
    ! positions are searched in the map's order (the same sums)
    logical :: map_later = .false., added = .false.
  end type csc_t

contains

  !> Pattern of the matrix of elements whose equation lists are
  !> eqs(xeq(e):xeq(e+1)-1) (0 entries = prescribed, skipped).
  !> with_map (default true): also the value position of every element
  !> entry, which makes repeated assembly a plain scatter; a matrix
  !> assembled once does without it (one integer per entry less).
  !> map_later (default false): the map is made only when the matrix is
  !> assembled a second time (csc_zero given the element lists), so that a
  !> matrix assembled once, which cannot know it beforehand, neither makes
  !> nor keeps it (at 1e6 equations: 72 MB and a pass of searches).
  subroutine csc_build(a, n, xeq, eqs, upper, with_map, map_later)
    type(csc_t), intent(out) :: a
    integer, intent(in) :: n, xeq(:), eqs(:)
    logical, intent(in) :: upper
    logical, intent(in), optional :: with_map, map_later
    integer, allocatable :: xel(:), el(:)
    a%n = n
    a%upper = upper
    call equation_elements(n, xeq, eqs, xel, el)
    call column_rows(a, n, xeq, eqs, upper, xel, el)
    allocate(a%val(a%colptr(n + 1) - 1))
    a%val = 0.0_dp
    if (present(with_map)) then
      if (.not. with_map) return
    end if
    if (present(map_later)) a%map_later = map_later
    if (a%map_later) return
    call element_entry_map(a, xeq, eqs, upper)
  end subroutine csc_build

  !> Purpose: the elements of each equation, the transpose of the element
  !> lists (csc_build).
  !> Arguments: n equations; xeq, eqs the element lists (eqs <= 0: no
  !> equation); el(xel(i):xel(i+1)-1) the elements holding equation i.
  subroutine equation_elements(n, xeq, eqs, xel, el)
    integer, intent(in) :: n, xeq(:), eqs(:)
    integer, allocatable, intent(out) :: xel(:), el(:)
    integer :: ne, e, i, k
    integer, allocatable :: fill(:)
    ne = size(xeq) - 1
    allocate(xel(n + 1), fill(n))
    xel = 0
    do k = 1, xeq(ne + 1) - 1
      if (eqs(k) > 0) xel(eqs(k) + 1) = xel(eqs(k) + 1) + 1
    end do
    xel(1) = 1
    do i = 1, n
      xel(i + 1) = xel(i + 1) + xel(i)
    end do
    allocate(el(xel(n + 1) - 1))
    fill = xel(1:n)
    do e = 1, ne
      do k = xeq(e), xeq(e + 1) - 1
        if (eqs(k) > 0) then
          el(fill(eqs(k))) = e
          fill(eqs(k)) = fill(eqs(k)) + 1
        end if
      end do
    end do
  end subroutine equation_elements

  !> Purpose: the rows of each column of a (colptr, rowind, sorted): the
  !> equations of the elements that hold it, the upper triangle only if
  !> upper; counted in a first pass, stored in a second (csc_build).
  !> Arguments: xel, el from equation_elements.
  subroutine column_rows(a, n, xeq, eqs, upper, xel, el)
    type(csc_t), intent(inout) :: a
    integer, intent(in) :: n, xeq(:), eqs(:), xel(:), el(:)
    logical, intent(in) :: upper
    integer :: e, j, k, gi, col, cnt, pass
    integer, allocatable :: mark(:)
    allocate(mark(n))
    mark = 0
    allocate(a%colptr(n + 1))
    a%colptr(1) = 1
    do pass = 1, 2
      do col = 1, n
        cnt = 0
        do k = xel(col), xel(col + 1) - 1
          e = el(k)
          do j = xeq(e), xeq(e + 1) - 1
            gi = eqs(j)
            if (gi <= 0) cycle
            if (upper .and. gi > col) cycle
            if (mark(gi) == col + (pass - 1) * n) cycle
            mark(gi) = col + (pass - 1) * n
            cnt = cnt + 1
            if (pass == 2) a%rowind(a%colptr(col) + cnt - 1) = gi
          end do
        end do
        if (pass == 1) then
          a%colptr(col + 1) = a%colptr(col) + cnt
        else
          call sort_int(a%rowind(a%colptr(col):a%colptr(col + 1) - 1))
        end if
      end do
      if (pass == 1) allocate(a%rowind(a%colptr(n + 1) - 1))
    end do
  end subroutine column_rows

  !> Purpose: the value position of every element entry (a%eptr, a%emap:
  !> element e's entries, row by row of its equation list, the upper
  !> triangle's (min, max) if upper), for assembly without searching.
  subroutine element_entry_map(a, xeq, eqs, upper)
    type(csc_t), intent(inout) :: a
    integer, intent(in) :: xeq(:), eqs(:)
    logical, intent(in) :: upper
    integer :: ne, e, i, j, k, gi, gj, col, cnt
    integer(8) :: npairs
    ne = size(xeq) - 1
    allocate(a%eptr(ne + 1))
    a%eptr(1) = 1
    do e = 1, ne
      cnt = count(eqs(xeq(e):xeq(e + 1) - 1) > 0)
      if (upper) then
        npairs = int(cnt, 8) * (cnt + 1) / 2
      else
        npairs = int(cnt, 8) * cnt
      end if
      a%eptr(e + 1) = a%eptr(e) + npairs
    end do
    allocate(a%emap(a%eptr(ne + 1) - 1))
    do e = 1, ne
      k = int(a%eptr(e))
      do i = xeq(e), xeq(e + 1) - 1
        gi = eqs(i)
        if (gi <= 0) cycle
        do j = xeq(e), xeq(e + 1) - 1
          gj = eqs(j)
          if (gj <= 0) cycle
          if (upper .and. j < i) cycle
          ! entry (row, col); the upper triangle takes (min, max)
          if (upper) then
            col = max(gi, gj)
            gj = min(gi, gj)
          else
            col = gj
            gj = gi
          end if
          a%emap(k) = csc_position(a, gj, col)
          k = k + 1
        end do
      end do
    end do
  end subroutine element_entry_map

  !> Index in rowind/val of entry (row, col), which must be in the pattern.
  pure integer function csc_position(a, row, col) result(lo)
    type(csc_t), intent(in) :: a
    integer, intent(in) :: row, col
    integer :: hi, mid
    lo = a%colptr(col)
    hi = a%colptr(col + 1) - 1
    do while (lo < hi)
      mid = (lo + hi) / 2
      if (a%rowind(mid) < row) then
        lo = mid + 1
      else
        hi = mid
      end if
    end do
  end function csc_position

  pure subroutine sort_int(v)
    integer, intent(inout) :: v(:)
    integer :: i, j, x
    do i = 2, size(v)
      x = v(i)
      j = i - 1
      do while (j >= 1)
        if (v(j) <= x) exit
        v(j + 1) = v(j)
        j = j - 1
      end do
      v(j + 1) = x
    end do
  end subroutine sort_int

  !> Purpose: clears the values, keeping the pattern; a matrix built with
  !> map_later makes its value map here once values were added before (the
  !> matrix is being assembled again).
  !> Arguments: xeq, eqs the element lists the matrix was built from
  !> (without them no map is made: positions stay searched).
  subroutine csc_zero(a, xeq, eqs)
    type(csc_t), intent(inout) :: a
    integer, intent(in), optional :: xeq(:), eqs(:)
    if (a%map_later .and. a%added .and. .not. allocated(a%emap) .and. present(xeq) .and. present(eqs)) &
      call element_entry_map(a, xeq, eqs, a%upper)
    a%val = 0.0_dp
  end subroutine csc_zero

  !> Adds element matrix ke (local dofs in the order of the element's
  !> equation list, prescribed ones included and skipped via eqs = 0).
  pure subroutine csc_add_element(a, e, eqs, ke)
    type(csc_t), intent(inout) :: a
    integer, intent(in) :: e, eqs(:)
    real(dp), intent(in) :: ke(:, :)
    integer :: i, j
    integer(8) :: k
    if (.not. allocated(a%emap)) then
      if (a%map_later) then
        call add_in_map_order(a, eqs, ke)
        a%added = .true.
      else
        call add_searching(a, eqs, ke)
      end if
      return
    end if
    k = a%eptr(e)
    do i = 1, size(eqs)
      if (eqs(i) <= 0) cycle
      do j = 1, size(eqs)
        if (eqs(j) <= 0) cycle
        if (a%upper .and. j < i) cycle
        a%val(a%emap(k)) = a%val(a%emap(k)) + ke(i, j)
        k = k + 1
      end do
    end do
  end subroutine csc_add_element

  !> Purpose: csc_add_element before its map is made (map_later): each
  !> position searched, the entries visited and taken from ke as the map's
  !> scatter does (row by row of the equation list, ke(i, j) with j >= i
  !> for the upper triangle), so that the sums are the same to the bit.
  pure subroutine add_in_map_order(a, eqs, ke)
    type(csc_t), intent(inout) :: a
    integer, intent(in) :: eqs(:)
    real(dp), intent(in) :: ke(:, :)
    integer :: i, j, k
    do i = 1, size(eqs)
      if (eqs(i) <= 0) cycle
      do j = 1, size(eqs)
        if (eqs(j) <= 0) cycle
        if (a%upper) then
          if (j < i) cycle
          k = csc_position(a, min(eqs(i), eqs(j)), max(eqs(i), eqs(j)))
        else
          k = csc_position(a, eqs(i), eqs(j))
        end if
        a%val(k) = a%val(k) + ke(i, j)
      end do
    end do
  end subroutine add_in_map_order

  !> csc_add_element without the value map: each position searched.
  pure subroutine add_searching(a, eqs, ke)
    type(csc_t), intent(inout) :: a
    integer, intent(in) :: eqs(:)
    real(dp), intent(in) :: ke(:, :)
    integer :: i, j, k
    do j = 1, size(eqs)
      if (eqs(j) <= 0) cycle
      do i = 1, size(eqs)
        if (eqs(i) <= 0) cycle
        if (a%upper) then
          if (eqs(i) > eqs(j)) cycle
          if (eqs(i) == eqs(j) .and. i > j) cycle
        end if
        k = csc_position(a, eqs(i), eqs(j))
        a%val(k) = a%val(k) + ke(i, j)
      end do
    end do
  end subroutine add_searching

  !> y = A x (the full symmetric matrix when only the upper part is kept).
  pure subroutine csc_matvec(a, x, y)
    type(csc_t), intent(in) :: a
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: y(:)
    integer :: col, k, r
    y = 0.0_dp
    do col = 1, a%n
      do k = a%colptr(col), a%colptr(col + 1) - 1
        r = a%rowind(k)
        y(r) = y(r) + a%val(k) * x(col)
        if (a%upper .and. r /= col) y(col) = y(col) + a%val(k) * x(r)
      end do
    end do
  end subroutine csc_matvec

  !> Adds the symmetric matrix kept as its upper triangle in upper to full,
  !> which keeps both triangles of a pattern holding upper's.
  subroutine csc_add_upper(full, upper)
    type(csc_t), intent(inout) :: full
    type(csc_t), intent(in) :: upper
    integer :: col, k, r, kk
    do col = 1, upper%n
      do k = upper%colptr(col), upper%colptr(col + 1) - 1
        r = upper%rowind(k)
        kk = csc_position(full, r, col)
        full%val(kk) = full%val(kk) + upper%val(k)
        if (r /= col) then
          kk = csc_position(full, col, r)
          full%val(kk) = full%val(kk) + upper%val(k)
        end if
      end do
    end do
  end subroutine csc_add_upper
end module sparse_matrix
