!> The symmetric generalised eigenproblem K x = lambda M x of the natural
!> frequencies (lambda = omega^2), by libraries made for it:
!> - small systems (at most dense_switch equations): LAPACK's dsygvd
!>   (divide and conquer) on the dense matrices, every eigenpair at once;
!> - large ones: ARPACK's implicitly restarted Lanczos in shift-invert
!>   mode (dsaupd/dseupd, mode 3: OP = (K - sigma M)^-1 M, B = M; ARPACK
!>   Users' Guide, section 3.2.3) on the sparse factor of K - sigma M of
!>   the solver backends (linear_solver) and the product with M.
!> Both return the nev eigenvalues nearest the shift sigma (with sigma
!> below the lowest eigenvalue: the lowest ones), ascending, with
!> eigenvectors of unit generalised mass (x^T M x = 1, as CalculiX
!> normalises its modes), each turned so that its largest component (the
!> first of equal ones) is positive: the sign, which the methods leave
!> open, then does not depend on the method, build or BLAS kernel.
module eigen_solver
  use kinds, only: dp
  use linear_solver, only: linear_system_t, sys_solve
  use sparse_matrix, only: csc_t, csc_matvec
  use arpack_binding, only: dsaupd, dseupd
  implicit none
  private
  public :: eigen_dense, eigen_shift_invert, dense_switch

  !> Systems of at most this many equations are solved dense: dsygvd's
  !> O(n^3) costs about 0.2 s at 1000 equations on one core (measured:
  !> 4.3 s of CPU at 2 800), comparable to the sparse path's analysis,
  !> factorisation and Lanczos restarts at such sizes; above, it grows
  !> with n^3 and its n^2 memory.
  integer, parameter :: dense_switch = 1000

  interface
    subroutine dsygvd(itype, jobz, uplo, n, a, lda, b, ldb, w, work, lwork, iwork, liwork, info)
      import :: dp
      integer, intent(in) :: itype, n, lda, ldb, lwork, liwork
      character, intent(in) :: jobz, uplo
      real(dp), intent(inout) :: a(lda, *), b(ldb, *)
      real(dp), intent(out) :: w(*), work(*)
      integer, intent(out) :: iwork(*), info
    end subroutine dsygvd
  end interface

contains

  !> Purpose: the nev eigenpairs of K x = lambda M x nearest sigma, dense.
  !> Arguments: k(n, n), mm(n, n) symmetric (both triangles filled); nev
  !> wanted; nfound returns how many there are (fewer where M has fewer
  !> massive directions); lam(nev) ascending and vec(n, nev) of unit
  !> mass; info 0, or 1 when neither K - sigma M nor M is positive
  !> definite (a shift above the lowest eigenvalue of a model with
  !> massless dofs: not solvable this way).
  !> The first way (K - sigma M positive definite) solves M x = mu A x,
  !> A = K - sigma M, mu = 1 / (lambda - sigma), as shift-invert does: the
  !> directions without mass have mu = 0 and drop out; otherwise
  !> K x = lambda M x directly (M positive definite).
  subroutine eigen_dense(k, mm, sigma, nev, nfound, lam, vec, info)
    real(dp), intent(in) :: k(:, :), mm(:, :), sigma
    integer, intent(in) :: nev
    integer, intent(out) :: nfound, info
    real(dp), intent(out) :: lam(:), vec(:, :)
    real(dp), allocatable :: a(:, :), b(:, :), w(:)
    integer, allocatable :: order(:)
    integer :: n, j, c
    real(dp) :: mu_max
    n = size(k, 1)
    a = mm
    b = k - sigma * mm
    allocate(w(n))
    call sygvd(a, b, w, info)
    nfound = 0
    if (info == 0) then
      ! mu descending: lambda ascending above sigma; mu = 0 (massless) dropped
      mu_max = maxval(abs(w))
      do j = n, 1, -1
        if (nfound == nev .or. .not. w(j) > 1.0e-12_dp * mu_max) exit
        nfound = nfound + 1
        lam(nfound) = sigma + 1.0_dp / w(j)
        vec(:, nfound) = a(:, j) / sqrt(w(j))
      end do
    else
      a = k
      b = mm
      call sygvd(a, b, w, info)
      if (info /= 0) then
        info = 1
        return
      end if
      call window(w, sigma, min(nev, n), order)
      nfound = size(order)
      do c = 1, nfound
        lam(c) = w(order(c))
        vec(:, c) = a(:, order(c))
      end do
    end if
    do c = 1, nfound
      call fix_sign(vec(:, c))
    end do
  end subroutine eigen_dense

  !> LAPACK's dsygvd (itype 1: a x = w b x, b positive definite) with
  !> its workspace query; a returns the eigenvectors (x^T b x = 1), w the
  !> eigenvalues ascending; info 0, or not 0 when b is not positive
  !> definite or the method failed.
  subroutine sygvd(a, b, w, info)
    real(dp), intent(inout) :: a(:, :), b(:, :)
    real(dp), intent(out) :: w(:)
    integer, intent(out) :: info
    real(dp) :: wq(1)
    integer :: iq(1), n
    real(dp), allocatable :: work(:)
    integer, allocatable :: iwork(:)
    n = size(a, 1)
    call dsygvd(1, 'V', 'U', n, a, n, b, n, w, wq, -1, iq, -1, info)
    allocate(work(max(1, int(wq(1)))), iwork(max(1, iq(1))))
    call dsygvd(1, 'V', 'U', n, a, n, b, n, w, work, size(work), iwork, size(iwork), info)
  end subroutine sygvd

  !> The nwant consecutive indices of w (ascending) whose values lie
  !> nearest sigma: the window grown one value at a time from sigma's place.
  subroutine window(w, sigma, nwant, order)
    real(dp), intent(in) :: w(:), sigma
    integer, intent(in) :: nwant
    integer, allocatable, intent(out) :: order(:)
    integer :: lo, hi, n
    n = size(w)
    hi = 0
    do while (hi < n)
      if (w(hi + 1) >= sigma) exit
      hi = hi + 1
    end do
    lo = hi + 1
    do while (hi - lo + 1 < nwant)
      if (lo == 1) then
        hi = hi + 1
      else if (hi == n) then
        lo = lo - 1
      else if (sigma - w(lo - 1) < w(hi + 1) - sigma) then
        lo = lo - 1
      else
        hi = hi + 1
      end if
    end do
    order = [(hi, hi = lo, lo + nwant - 1)]
  end subroutine window

  !> The vector turned so that its largest component (the first of equal
  !> magnitude, to round-off) is positive.
  pure subroutine fix_sign(x)
    real(dp), intent(inout) :: x(:)
    integer :: j, jmax
    real(dp) :: big
    big = maxval(abs(x))
    jmax = 1
    do j = 1, size(x)
      if (abs(x(j)) >= (1.0_dp - 1.0e-8_dp) * big) then
        jmax = j
        exit
      end if
    end do
    if (x(jmax) < 0.0_dp) x = -x
  end subroutine fix_sign

  !> Purpose: the nev eigenpairs nearest sigma by ARPACK in shift-invert
  !> mode.
  !> Arguments: a the factored K - sigma M (its solves give OP with the
  !> product with mm, M kept as its upper triangle); nfound returns the
  !> converged pairs (ARPACK's iparam(5)), lam(nev) ascending and vec(n,
  !> nev) of unit mass; iters the Lanczos restarts (iparam(3)) and nop
  !> the solves with the factor; info 0, or ARPACK's info of dsaupd or
  !> dseupd (negative: an input error, 1: not every pair converged in
  !> the restarts allowed).
  subroutine eigen_shift_invert(a, mm, sigma, nev, nfound, lam, vec, iters, nop, info)
    type(linear_system_t), intent(inout) :: a
    type(csc_t), intent(in) :: mm
    real(dp), intent(in) :: sigma
    integer, intent(in) :: nev
    integer, intent(out) :: nfound, iters, nop, info
    real(dp), intent(out) :: lam(:), vec(:, :)
    integer :: n, ncv, lworkl, ido, iparam(11), ipntr(11), c
    real(dp) :: tol
    real(dp), allocatable :: resid(:), v(:, :), workd(:), workl(:), d(:), z(:, :)
    logical, allocatable :: sel(:)
    integer, allocatable :: order(:)
    n = mm%n
    ! ARPACK's advice: ncv at least 2 nev; 20 more for few modes converges in few restarts
    ncv = min(n, max(2 * nev + 1, nev + 20))
    lworkl = ncv * (ncv + 8)
    allocate(resid(n), v(n, ncv), workd(3 * n), workl(lworkl), d(nev), z(n, nev), sel(ncv))
    call start_vector(resid)
    iparam = 0
    iparam(1) = 1        ! exact shifts
    iparam(3) = 500      ! restarts allowed
    iparam(7) = 3        ! shift-invert
    ipntr = 0
    ido = 0
    info = 1             ! resid is the starting vector
    nop = 0
    tol = 0.0_dp         ! machine precision
    do
      call dsaupd(ido, 'G', n, 'LM', nev, tol, resid, ncv, v, n, iparam, ipntr, workd, workl, lworkl, info)
      if (ido == -1 .or. ido == 1) then
        call apply_op(a, mm, ido, workd, ipntr, n)
        nop = nop + 1
      else if (ido == 2) then
        call csc_matvec(mm, workd(ipntr(1):ipntr(1) + n - 1), workd(ipntr(2):ipntr(2) + n - 1))
      else
        exit
      end if
    end do
    iters = iparam(3)
    nfound = 0
    if (info < 0) return
    if (info == 1) return
    call dseupd(.true., 'A', sel, d, z, n, sigma, 'G', n, 'LM', nev, tol, resid, ncv, v, n, iparam, ipntr, &
                workd, workl, lworkl, info)
    if (info /= 0) return
    nfound = iparam(5)
    call sort_index(d(1:nfound), order)
    do c = 1, nfound
      lam(c) = d(order(c))
      vec(:, c) = z(:, order(c))
      call fix_sign(vec(:, c))
    end do
  end subroutine eigen_shift_invert

  !> ARPACK's request for y = OP x, OP = (K - sigma M)^-1 M: ido -1 (M x
  !> to be formed) or 1 (M x given in workd at ipntr(3)).
  subroutine apply_op(a, mm, ido, workd, ipntr, n)
    type(linear_system_t), intent(inout) :: a
    type(csc_t), intent(in) :: mm
    integer, intent(in) :: ido, ipntr(11), n
    real(dp), intent(inout) :: workd(:)
    real(dp), allocatable :: y(:)
    allocate(y(n))
    if (ido == -1) then
      call csc_matvec(mm, workd(ipntr(1):ipntr(1) + n - 1), y)
    else
      y = workd(ipntr(3):ipntr(3) + n - 1)
    end if
    call sys_solve(a, y)
    workd(ipntr(2):ipntr(2) + n - 1) = y
  end subroutine apply_op

  !> A starting vector of its own (a fixed linear congruential sequence
  !> in (-1, 1)): not orthogonal to the modes of a symmetric structure as
  !> a constant one would be, and the same in every run and build.
  pure subroutine start_vector(r)
    real(dp), intent(out) :: r(:)
    integer(kind=8) :: s
    integer :: j
    s = 12345_8
    do j = 1, size(r)
      s = modulo(1103515245_8 * s + 12345_8, 2147483648_8)
      r(j) = 2.0_dp * real(s, dp) / 2147483648.0_dp - 1.0_dp
    end do
  end subroutine start_vector

  !> The permutation that sorts d ascending (insertion sort: d is short).
  pure subroutine sort_index(d, order)
    real(dp), intent(in) :: d(:)
    integer, allocatable, intent(out) :: order(:)
    integer :: i, j, t
    order = [(i, i = 1, size(d))]
    do i = 2, size(d)
      t = order(i)
      j = i - 1
      do while (j >= 1)
        if (d(order(j)) <= d(t)) exit
        order(j + 1) = order(j)
        j = j - 1
      end do
      order(j + 1) = t
    end do
  end subroutine sort_index
end module eigen_solver
