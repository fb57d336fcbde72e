!> Explicit interfaces of ARPACK's symmetric reverse-communication driver
!> (Lehoucq, Sorensen and Yang, ARPACK Users' Guide, SIAM 1998, chapter
!> 2): dsaupd iterates the implicitly restarted Lanczos method, asking the
!> caller for products with OP and B through ido; dseupd extracts the
!> Ritz values and vectors. Debian's libarpack2 (-larpack) provides them.
module arpack_binding
  use kinds, only: dp
  implicit none
  private
  public :: dsaupd, dseupd

  interface
    subroutine dsaupd(ido, bmat, n, which, nev, tol, resid, ncv, v, ldv, iparam, ipntr, workd, workl, lworkl, info)
      import :: dp
      integer, intent(inout) :: ido
      character(len=1), intent(in) :: bmat
      integer, intent(in) :: n
      character(len=2), intent(in) :: which
      integer, intent(in) :: nev, ncv, ldv, lworkl
      !> (dsaupd sets a tol <= 0 to the machine precision: a variable)
      real(dp), intent(inout) :: tol
      real(dp), intent(inout) :: resid(n), v(ldv, ncv), workd(3 * n), workl(lworkl)
      integer, intent(inout) :: iparam(11), ipntr(11), info
    end subroutine dsaupd

    subroutine dseupd(rvec, howmny, select, d, z, ldz, sigma, bmat, n, which, nev, tol, resid, ncv, v, ldv, &
                      iparam, ipntr, workd, workl, lworkl, info)
      import :: dp
      logical, intent(in) :: rvec
      character(len=1), intent(in) :: howmny, bmat
      integer, intent(in) :: ldz, n, nev, ncv, ldv, lworkl
      logical, intent(inout) :: select(ncv)
      real(dp), intent(out) :: d(nev), z(ldz, nev)
      real(dp), intent(in) :: sigma, tol
      character(len=2), intent(in) :: which
      real(dp), intent(inout) :: resid(n), v(ldv, ncv), workd(2 * n), workl(lworkl)
      integer, intent(inout) :: iparam(7), ipntr(11), info
    end subroutine dseupd
  end interface
end module arpack_binding
