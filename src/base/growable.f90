!> Arrays that grow while they are filled (a deck is read once, without
!> knowing its size in advance). The capacity at least doubles on every
!> reallocation, so filling n items costs O(n) copies in total instead of
!> the O(n^2) of `x = [x, y]` in a loop.
!>
!> grow(a, n)          capacity of a at least n (1-D), or at least n
!>                     columns (2-D, the leading extent is kept); contents
!>                     are kept; new slots are set to `fill` if given.
!> append(a, n, v)     a(n+1) = v (or a(n+1:n+size(v)) = v), n advanced.
!> new_capacity(c, n)  the size to reallocate to: for derived types, whose
!>                     growth routines cannot be generic (see below).
!>
!> Fortran 2008 has no generic programming over types: an allocatable
!> dummy must have the declared type of its actual argument (class(*)
!> does not accept a type(t) allocatable), so each type needs its own
!> specific procedure. This module holds those of the intrinsic types;
!> modules with derived types add theirs to the generic `grow` by
!> declaring an interface of the same name.
module growable
  use kinds, only: dp
  implicit none
  private
  public :: grow, append, new_capacity

  !> Smallest capacity allocated: avoids a string of tiny reallocations.
  integer, parameter :: min_capacity = 16

  interface grow
    module procedure grow_int1, grow_real1, grow_int2, grow_real2
  end interface grow

  interface append
    module procedure append_int, append_ints, append_real, append_reals
  end interface append

contains

  !> Size to reallocate an array of `current` slots to when `needed` slots
  !> are wanted: at least double, at least needed.
  pure integer function new_capacity(current, needed)
    integer, intent(in) :: current, needed
    new_capacity = max(needed, 2 * current, min_capacity)
  end function new_capacity

  pure subroutine grow_int1(a, n, fill)
    integer, allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n
    integer, intent(in), optional :: fill
    integer, allocatable :: tmp(:)
    integer :: old
    old = 0
    if (allocated(a)) old = size(a)
    if (allocated(a) .and. n <= old) return
    allocate(tmp(new_capacity(old, n)))
    if (present(fill)) tmp(old + 1:) = fill
    if (old > 0) tmp(1:old) = a
    call move_alloc(tmp, a)
  end subroutine grow_int1

  pure subroutine grow_real1(a, n, fill)
    real(dp), allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n
    real(dp), intent(in), optional :: fill
    real(dp), allocatable :: tmp(:)
    integer :: old
    old = 0
    if (allocated(a)) old = size(a)
    if (allocated(a) .and. n <= old) return
    allocate(tmp(new_capacity(old, n)))
    if (present(fill)) tmp(old + 1:) = fill
    if (old > 0) tmp(1:old) = a
    call move_alloc(tmp, a)
  end subroutine grow_real1

  !> Columns of a 2-D array (e.g. coordinates (2, nn), connectivity
  !> (max_nodes, ne)); a must be allocated so that its leading extent is known.
  pure subroutine grow_int2(a, n, fill)
    integer, allocatable, intent(inout) :: a(:, :)
    integer, intent(in) :: n
    integer, intent(in), optional :: fill
    integer, allocatable :: tmp(:, :)
    integer :: old
    old = size(a, 2)
    if (n <= old) return
    allocate(tmp(size(a, 1), new_capacity(old, n)))
    if (present(fill)) tmp(:, old + 1:) = fill
    tmp(:, 1:old) = a
    call move_alloc(tmp, a)
  end subroutine grow_int2

  pure subroutine grow_real2(a, n, fill)
    real(dp), allocatable, intent(inout) :: a(:, :)
    integer, intent(in) :: n
    real(dp), intent(in), optional :: fill
    real(dp), allocatable :: tmp(:, :)
    integer :: old
    old = size(a, 2)
    if (n <= old) return
    allocate(tmp(size(a, 1), new_capacity(old, n)))
    if (present(fill)) tmp(:, old + 1:) = fill
    tmp(:, 1:old) = a
    call move_alloc(tmp, a)
  end subroutine grow_real2

  pure subroutine append_int(a, n, v)
    integer, allocatable, intent(inout) :: a(:)
    integer, intent(inout) :: n
    integer, intent(in) :: v
    call grow_int1(a, n + 1)
    n = n + 1
    a(n) = v
  end subroutine append_int

  pure subroutine append_ints(a, n, v)
    integer, allocatable, intent(inout) :: a(:)
    integer, intent(inout) :: n
    integer, intent(in) :: v(:)
    call grow_int1(a, n + size(v))
    a(n + 1:n + size(v)) = v
    n = n + size(v)
  end subroutine append_ints

  pure subroutine append_real(a, n, v)
    real(dp), allocatable, intent(inout) :: a(:)
    integer, intent(inout) :: n
    real(dp), intent(in) :: v
    call grow_real1(a, n + 1)
    n = n + 1
    a(n) = v
  end subroutine append_real

  pure subroutine append_reals(a, n, v)
    real(dp), allocatable, intent(inout) :: a(:)
    integer, intent(inout) :: n
    real(dp), intent(in) :: v(:)
    call grow_real1(a, n + size(v))
    a(n + 1:n + size(v)) = v
    n = n + size(v)
  end subroutine append_reals
end module growable
