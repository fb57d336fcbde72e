!> Symmetric skyline (profile) storage and the LDL^T factorisation of the
!> textbooks: column j keeps rows first(j)..j contiguously, diagonal last,
!> so every inner product of the Crout update is one contiguous dot product.
module skyline
  use kinds, only: dp
  implicit none
  private
  public :: skyline_t, sky_setup, sky_add, sky_factor, sky_solve, sky_matvec, sky_zero

  !> A pivot below this fraction of its original diagonal means the matrix
  !> is singular to working precision (a rigid-body mode left free).
  real(dp), parameter :: pivot_tolerance = 1.0e-11_dp

  type :: skyline_t
    integer :: n = 0
    integer(8) :: nnz = 0                 ! profile size (stored entries)
    integer, allocatable :: first(:)      ! first stored row of each column
    integer(8), allocatable :: ptr(:)     ! start of column j; ptr(n+1) = nnz+1
    real(dp), allocatable :: a(:)
    logical :: factored = .false.
  end type skyline_t

contains

  !> first(j) = smallest row with a nonzero in column j (j itself if none).
  subroutine sky_setup(k, first)
    type(skyline_t), intent(out) :: k
    integer, intent(in) :: first(:)
    integer :: j
    k%n = size(first)
    k%first = first
    allocate(k%ptr(k%n + 1))
    k%ptr(1) = 1
    do j = 1, k%n
      k%ptr(j + 1) = k%ptr(j) + (j - first(j) + 1)
    end do
    k%nnz = k%ptr(k%n + 1) - 1
    allocate(k%a(k%nnz))
    k%a = 0.0_dp
  end subroutine sky_setup

  subroutine sky_zero(k)
    type(skyline_t), intent(inout) :: k
    k%a = 0.0_dp
    k%factored = .false.
  end subroutine sky_zero

  !> Adds v to entry (i, j) of the symmetric matrix; either triangle may be
  !> named, the upper one is stored.
  pure subroutine sky_add(k, i, j, v)
    type(skyline_t), intent(inout) :: k
    integer, intent(in) :: i, j
    real(dp), intent(in) :: v
    integer :: r, c
    r = min(i, j)
    c = max(i, j)
    k%a(k%ptr(c) + (r - k%first(c))) = k%a(k%ptr(c) + (r - k%first(c))) + v
  end subroutine sky_add

  !> In-place LDL^T. On a pivot that is not safely positive, bad is the
  !> equation where it appeared and the factor is incomplete.
  subroutine sky_factor(k, bad)
    type(skyline_t), intent(inout) :: k
    integer, intent(out) :: bad
    integer :: i, j, m
    integer(8) :: pj, pi
    real(dp) :: d, g, orig
    bad = 0
    do j = 1, k%n
      pj = k%ptr(j) - k%first(j)      ! a(pj + i) is entry (i, j)
      orig = k%a(pj + j)
      ! g_ij = a_ij - sum_k l_ki g_kj over the rows both columns hold.
      do i = k%first(j) + 1, j - 1
        pi = k%ptr(i) - k%first(i)
        m = max(k%first(i), k%first(j))
        if (m < i) k%a(pj + i) = k%a(pj + i) - dot_product(k%a(pi + m:pi + i - 1), k%a(pj + m:pj + i - 1))
      end do
      ! l_ij = g_ij / d_i and d_j = a_jj - sum l_ij g_ij.
      d = orig
      do i = k%first(j), j - 1
        g = k%a(pj + i)
        k%a(pj + i) = g / k%a(k%ptr(i + 1) - 1)
        d = d - k%a(pj + i) * g
      end do
      if (.not. (d > pivot_tolerance * abs(orig)) .or. orig <= 0.0_dp) then
        bad = j
        return
      end if
      k%a(pj + j) = d
    end do
    k%factored = .true.
  end subroutine sky_factor

  !> Solves with the factor in place of the right-hand side.
  pure subroutine sky_solve(k, b)
    type(skyline_t), intent(in) :: k
    real(dp), intent(inout) :: b(:)
    integer :: j, f
    integer(8) :: pj
    do j = 1, k%n
      f = k%first(j)
      pj = k%ptr(j) - f
      if (f < j) b(j) = b(j) - dot_product(k%a(pj + f:pj + j - 1), b(f:j - 1))
    end do
    do j = 1, k%n
      b(j) = b(j) / k%a(k%ptr(j + 1) - 1)
    end do
    do j = k%n, 1, -1
      f = k%first(j)
      pj = k%ptr(j) - f
      if (f < j) b(f:j - 1) = b(f:j - 1) - k%a(pj + f:pj + j - 1) * b(j)
    end do
  end subroutine sky_solve

  !> y = K x with the unfactored matrix (residual checks).
  pure subroutine sky_matvec(k, x, y)
    type(skyline_t), intent(in) :: k
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: y(:)
    integer :: j, f
    integer(8) :: pj
    y = 0.0_dp
    do j = 1, k%n
      f = k%first(j)
      pj = k%ptr(j) - f
      y(j) = y(j) + dot_product(k%a(pj + f:pj + j), x(f:j))
      if (f < j) y(f:j - 1) = y(f:j - 1) + k%a(pj + f:pj + j - 1) * x(j)
    end do
  end subroutine sky_matvec
end module skyline
