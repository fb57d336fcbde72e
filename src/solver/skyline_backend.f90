!> The skyline LDL^T of module skyline as a solver backend. Its profile
!> follows the equation numbering it is given (the caller numbers the
!> equations with RCM for it), so it takes no ordering of its own.
module skyline_backend
  use kinds, only: dp
  use strings, only: rtoa
  use skyline, only: skyline_t, sky_setup, sky_add, sky_factor, sky_solve, sky_matvec, sky_zero
  use solver_backend, only: solver_backend_t, factor_ok, factor_singular
  implicit none
  private
  public :: skyline_backend_t

  type, extends(solver_backend_t) :: skyline_backend_t
    type(skyline_t) :: sky
  contains
    procedure :: setup, zero, add, analyse, factor, solve, matvec, describe, stored_entries, free
  end type skyline_backend_t

contains

  !> Column heights from the element lists: each column reaches up to the
  !> lowest equation of any element holding it.
  subroutine setup(self, n, ordering, xeq, eqs)
    class(skyline_backend_t), intent(inout) :: self
    integer, intent(in) :: n, ordering, xeq(:), eqs(:)
    integer, allocatable :: first(:)
    integer :: e, k, lo
    call self%keep_structure(n, ordering, xeq, eqs)
    allocate(first(n))
    first = [(k, k = 1, n)]
    do e = 1, size(xeq) - 1
      lo = huge(1)
      do k = xeq(e), xeq(e + 1) - 1
        if (eqs(k) > 0) lo = min(lo, eqs(k))
      end do
      do k = xeq(e), xeq(e + 1) - 1
        if (eqs(k) > 0) first(eqs(k)) = min(first(eqs(k)), lo)
      end do
    end do
    call sky_setup(self%sky, first)
    self%factor_entries = real(self%sky%nnz, dp)
  end subroutine setup

  subroutine zero(self)
    class(skyline_backend_t), intent(inout) :: self
    call sky_zero(self%sky)
  end subroutine zero

  subroutine add(self, e, ke)
    class(skyline_backend_t), intent(inout) :: self
    integer, intent(in) :: e
    real(dp), intent(in) :: ke(:, :)
    integer :: i, j, gi, gj, i0
    i0 = self%xeq(e) - 1
    do i = 1, self%xeq(e + 1) - self%xeq(e)
      gi = self%eqs(i0 + i)
      if (gi <= 0) cycle
      do j = i, self%xeq(e + 1) - self%xeq(e)
        gj = self%eqs(i0 + j)
        if (gj > 0) call sky_add(self%sky, gi, gj, ke(i, j))
      end do
    end do
  end subroutine add

  !> Nothing to order or analyse: the profile was fixed by setup and is
  !> the size of the factor.
  subroutine analyse(self)
    class(skyline_backend_t), intent(inout) :: self
    self%factor_entries = real(self%sky%nnz, dp)
  end subroutine analyse

  !> The skyline names the equation of the first pivot that is not safely
  !> positive (a free rigid-body mode, or an indefinite matrix).
  subroutine factor(self, status, bad)
    class(skyline_backend_t), intent(inout) :: self
    integer, intent(out) :: status, bad
    call sky_factor(self%sky, bad)
    status = merge(factor_singular, factor_ok, bad > 0)
  end subroutine factor

  subroutine solve(self, b)
    class(skyline_backend_t), intent(inout) :: self
    real(dp), intent(inout) :: b(:, :)
    integer :: j
    do j = 1, size(b, 2)
      call sky_solve(self%sky, b(:, j))
    end do
  end subroutine solve

  pure subroutine matvec(self, x, y)
    class(skyline_backend_t), intent(in) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: y(:)
    call sky_matvec(self%sky, x, y)
  end subroutine matvec

  function describe(self) result(d)
    class(skyline_backend_t), intent(in) :: self
    character(len=:), allocatable :: d
    d = 'profile ' // rtoa(self%factor_entries, 6)
  end function describe

  integer(8) function stored_entries(self)
    class(skyline_backend_t), intent(in) :: self
    stored_entries = self%sky%nnz
  end function stored_entries

  subroutine free(self)
    class(skyline_backend_t), intent(inout) :: self
    type(skyline_t) :: empty
    self%sky = empty
    self%n = 0
    if (allocated(self%xeq)) deallocate(self%xeq, self%eqs)
  end subroutine free
end module skyline_backend
