!> Dense symmetric positive definite matrices through LAPACK and BLAS
!> (OpenBLAS): Cholesky factorisation and solves (lower triangles only),
!> products with an upper triangle, and the Gram matrix L L^T. The condensed contact solve keeps its Schur complement
!> here.
module dense_cholesky
  use kinds, only: dp
  implicit none
  private
  public :: dense_factor, dense_solve, upper_times, lower_gram, lower_solve, transposed_gram

  interface
    subroutine dpotrf(uplo, n, a, lda, info)
      import :: dp
      character, intent(in) :: uplo
      integer, intent(in) :: n, lda
      real(dp), intent(inout) :: a(lda, *)
      integer, intent(out) :: info
    end subroutine dpotrf

    subroutine dpotrs(uplo, n, nrhs, a, lda, b, ldb, info)
      import :: dp
      character, intent(in) :: uplo
      integer, intent(in) :: n, nrhs, lda, ldb
      real(dp), intent(in) :: a(lda, *)
      real(dp), intent(inout) :: b(ldb, *)
      integer, intent(out) :: info
    end subroutine dpotrs

    subroutine dtrmv(uplo, trans, diag, n, a, lda, x, incx)
      import :: dp
      character, intent(in) :: uplo, trans, diag
      integer, intent(in) :: n, lda, incx
      real(dp), intent(in) :: a(lda, *)
      real(dp), intent(inout) :: x(*)
    end subroutine dtrmv

    subroutine dtrsm(side, uplo, transa, diag, m, n, alpha, a, lda, b, ldb)
      import :: dp
      character, intent(in) :: side, uplo, transa, diag
      integer, intent(in) :: m, n, lda, ldb
      real(dp), intent(in) :: alpha
      real(dp), intent(in) :: a(lda, *)
      real(dp), intent(inout) :: b(ldb, *)
    end subroutine dtrsm

    subroutine dsyrk(uplo, trans, n, k, alpha, a, lda, beta, c, ldc)
      import :: dp
      character, intent(in) :: uplo, trans
      integer, intent(in) :: n, k, lda, ldc
      real(dp), intent(in) :: alpha, beta
      real(dp), intent(in) :: a(lda, *)
      real(dp), intent(inout) :: c(ldc, *)
    end subroutine dsyrk
  end interface

contains

  !> Purpose: a(m, m) := its Cholesky factor L (lower triangle), a = L L^T.
  !> Arguments: info 0, or k > 0: the leading minor of order k is not
  !> positive definite (a holds the partial factor).
  subroutine dense_factor(a, info)
    real(dp), intent(inout) :: a(:, :)
    integer, intent(out) :: info
    info = 0
    if (size(a, 1) == 0) return
    call dpotrf('L', size(a, 1), a, size(a, 1), info)
  end subroutine dense_factor

  !> Purpose: b := A^-1 b with the factor from dense_factor.
  subroutine dense_solve(l, b)
    real(dp), intent(in) :: l(:, :)
    real(dp), intent(inout) :: b(:)
    integer :: info
    if (size(l, 1) == 0) return
    call dpotrs('L', size(l, 1), 1, l, size(l, 1), b, size(b), info)
  end subroutine dense_solve

  !> Purpose: x := U x (transposed: U^T x) with the upper triangle and
  !> diagonal of u.
  subroutine upper_times(u, x, transposed)
    real(dp), intent(in) :: u(:, :)
    real(dp), intent(inout) :: x(:)
    logical, intent(in) :: transposed
    if (size(u, 1) == 0) return
    call dtrmv('U', merge('T', 'N', transposed), 'N', size(u, 1), u, size(u, 1), x, 1)
  end subroutine upper_times

  !> Purpose: the lower triangle of s := L L^T, L the lower triangle of l
  !> (zero above the diagonal).
  subroutine lower_gram(l, s)
    real(dp), intent(in) :: l(:, :)
    real(dp), intent(inout) :: s(:, :)
    if (size(l, 1) == 0) return
    call dsyrk('L', 'N', size(l, 1), size(l, 1), 1.0_dp, l, size(l, 1), 0.0_dp, s, size(s, 1))
  end subroutine lower_gram

  !> Purpose: b := L^-1 b (transposed: L^-T b) for the columns of b, L the
  !> lower triangle of a factor from dense_factor (one half of a solve,
  !> many right-hand sides at once).
  subroutine lower_solve(l, b, transposed)
    real(dp), intent(in) :: l(:, :)
    real(dp), intent(inout) :: b(:, :)
    logical, intent(in) :: transposed
    if (size(l, 1) == 0 .or. size(b, 2) == 0) return
    call dtrsm('L', 'L', merge('T', 'N', transposed), 'N', size(l, 1), size(b, 2), 1.0_dp, l, size(l, 1), &
               b, size(b, 1))
  end subroutine lower_solve

  !> Purpose: the lower triangle of w := z^T z (z: m x k, w: k x k).
  subroutine transposed_gram(z, w)
    real(dp), intent(in) :: z(:, :)
    real(dp), intent(inout) :: w(:, :)
    if (size(z, 2) == 0) return
    call dsyrk('L', 'T', size(z, 2), size(z, 1), 1.0_dp, z, size(z, 1), 0.0_dp, w, size(w, 1))
  end subroutine transposed_gram
end module dense_cholesky
