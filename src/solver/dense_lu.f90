!> Dense general (unsymmetric) matrices through LAPACK: LU factorisation
!> with partial pivoting and solves. The condensed contact solve factors
!> its Schur complement here when a sliding frictional contact makes it
!> unsymmetric (dense_cholesky otherwise).
module dense_lu
  use kinds, only: dp
  implicit none
  private
  public :: lu_factor, lu_solve

  interface
    subroutine dgetrf(m, n, a, lda, ipiv, info)
      import :: dp
      integer, intent(in) :: m, n, lda
      real(dp), intent(inout) :: a(lda, *)
      integer, intent(out) :: ipiv(*), info
    end subroutine dgetrf

    subroutine dgetrs(trans, n, nrhs, a, lda, ipiv, b, ldb, info)
      import :: dp
      character, intent(in) :: trans
      integer, intent(in) :: n, nrhs, lda, ldb, ipiv(*)
      real(dp), intent(in) :: a(lda, *)
      real(dp), intent(inout) :: b(ldb, *)
      integer, intent(out) :: info
    end subroutine dgetrs
  end interface

contains

  !> Purpose: a(m, m) := its LU factors (P a = L U, unit L below the
  !> diagonal, U on and above it), ipiv the row interchanges.
  !> Arguments: info 0, or k > 0: U(k, k) is exactly zero.
  subroutine lu_factor(a, ipiv, info)
    real(dp), intent(inout) :: a(:, :)
    integer, intent(out) :: ipiv(:), info
    info = 0
    if (size(a, 1) == 0) return
    call dgetrf(size(a, 1), size(a, 1), a, size(a, 1), ipiv, info)
  end subroutine lu_factor

  !> Purpose: b := A^-1 b with the factors from lu_factor.
  subroutine lu_solve(a, ipiv, b)
    real(dp), intent(in) :: a(:, :)
    integer, intent(in) :: ipiv(:)
    real(dp), intent(inout) :: b(:)
    integer :: info
    if (size(a, 1) == 0) return
    call dgetrs('N', size(a, 1), 1, a, size(a, 1), ipiv, b, size(b), info)
  end subroutine lu_solve
end module dense_lu
