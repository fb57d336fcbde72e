!> What every direct solver of the global equations provides. A backend
!> owns the assembled matrix in its own storage and its factor; it is set
!> up from the element equation lists and filled one element at a time.
!> Equations are numbered 1..n; an equation list entry <= 0 is a
!> prescribed dof and is skipped.
module solver_backend
  use kinds, only: dp
  implicit none
  private
  public :: solver_backend_t, factor_ok, factor_singular, factor_fallback, factor_not_posdef, pivot_ratio_min

  !> Outcomes of a factorisation. factor_fallback is linear_solver's: the
  !> matrix was not positive definite and another backend factorised it.
  !> factor_not_posdef is a backend's: it cannot factorise this matrix
  !> (a pivot not positive) but another backend may.
  integer, parameter :: factor_ok = 0, factor_singular = 1, factor_fallback = 2, factor_not_posdef = 3

  !> Smallest pivot the sparse backends accept, relative to the diagonal
  !> entry it came from (for the LU, the largest entry of its column): the
  !> share of that equation's stiffness left once the others are
  !> eliminated. Measured (CHOLMOD and UMFPACK, AMD and METIS, CPS4): a
  !> free rotation (beam held at one node, 124 to 165000 equations) leaves
  !> 2e-15 to 1.4e-11, and 2.8e-8 on a 2000 x 2 mesh of 100:1 elements;
  !> penalty contact that must solve leaves 1.1e-5 (Hertz, the paper's
  !> 1e10 N/mm per node), 1.3e-5 to 1.3e-7 (blocks, penalty 100 to 1e4
  !> times the automatic one); a block held only by the default open
  !> penalty (1e-12) leaves 4.8e-9 and is reported singular, as the run
  !> then says to raise OPEN PENALTY.
  real(dp), parameter :: pivot_ratio_min = 1.0e-8_dp

  type, abstract :: solver_backend_t
    integer :: n = 0
    integer :: ordering = 0               ! solver_codes order_*
    real(dp) :: factor_entries = 0.0_dp   ! nnz(L) (+ nnz(U)), or the profile
    real(dp) :: factor_flops = 0.0_dp     ! of one numeric factorisation, where the backend says
    !> The last nlast equations are a block to be kept last by the ordering
    !> (a condensed solve); backends that cannot keep it last ignore it.
    integer :: nlast = 0
    integer, allocatable :: xeq(:), eqs(:)   ! element equation lists
  contains
    procedure, non_overridable :: keep_structure
    procedure(setup_i), deferred :: setup
    procedure(plain_i), deferred :: zero
    procedure(add_i), deferred :: add
    procedure(plain_i), deferred :: analyse
    procedure(factor_i), deferred :: factor
    procedure(solve_i), deferred :: solve
    procedure(matvec_i), deferred :: matvec
    procedure(describe_i), deferred :: describe
    procedure(stored_i), deferred :: stored_entries
    procedure(plain_i), deferred :: free
  end type solver_backend_t

  abstract interface
    !> Storage for n equations coupled as the element lists
    !> eqs(xeq(e):xeq(e+1)-1) say; ordering: the fill-reducing ordering
    !> asked for (sparse backends), or how the equations were numbered.
    subroutine setup_i(self, n, ordering, xeq, eqs)
      import :: solver_backend_t
      class(solver_backend_t), intent(inout) :: self
      integer, intent(in) :: n, ordering, xeq(:), eqs(:)
    end subroutine setup_i

    subroutine plain_i(self)
      import :: solver_backend_t
      class(solver_backend_t), intent(inout) :: self
    end subroutine plain_i

    !> Adds the matrix ke of element e (rows and columns in the order of
    !> its equation list).
    subroutine add_i(self, e, ke)
      import :: solver_backend_t, dp
      class(solver_backend_t), intent(inout) :: self
      integer, intent(in) :: e
      real(dp), intent(in) :: ke(:, :)
    end subroutine add_i

    !> status: factor_ok, factor_singular (bad: the equation whose pivot
    !> vanished) or factor_not_posdef (bad: the equation where it stopped).
    subroutine factor_i(self, status, bad)
      import :: solver_backend_t
      class(solver_backend_t), intent(inout) :: self
      integer, intent(out) :: status, bad
    end subroutine factor_i

    !> b(n, nrhs) is replaced by the solutions, all in one pass.
    subroutine solve_i(self, b)
      import :: solver_backend_t, dp
      class(solver_backend_t), intent(inout) :: self
      real(dp), intent(inout) :: b(:, :)
    end subroutine solve_i

    !> y = A x with the assembled (unfactored) matrix.
    pure subroutine matvec_i(self, x, y)
      import :: solver_backend_t, dp
      class(solver_backend_t), intent(in) :: self
      real(dp), intent(in) :: x(:)
      real(dp), intent(out) :: y(:)
    end subroutine matvec_i

    !> Size of the factor in words, e.g. "factor entries 1.2E+05".
    function describe_i(self) result(d)
      import :: solver_backend_t
      class(solver_backend_t), intent(in) :: self
      character(len=:), allocatable :: d
    end function describe_i

    !> Entries of the assembled matrix as stored.
    integer(8) function stored_i(self)
      import :: solver_backend_t
      class(solver_backend_t), intent(in) :: self
    end function stored_i
  end interface

contains

  !> What every backend's setup keeps: size, ordering, element lists.
  subroutine keep_structure(self, n, ordering, xeq, eqs)
    class(solver_backend_t), intent(inout) :: self
    integer, intent(in) :: n, ordering, xeq(:), eqs(:)
    self%n = n
    self%ordering = ordering
    self%xeq = xeq
    self%eqs = eqs
  end subroutine keep_structure
end module solver_backend
