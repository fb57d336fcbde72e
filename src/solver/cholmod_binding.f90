!> CHOLMOD (SuiteSparse) through the C shim cholmod_shim.c: the workspace
!> and the factor are one opaque handle, and no CHOLMOD struct is laid out
!> in Fortran, so any CHOLMOD from version 3 on will do. Matrices are the
!> 0-based compressed columns of the upper triangle; columns handed back
!> are 0-based in the caller's numbering.
module cholmod_binding
  use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr
  implicit none
  private
  public :: cfe_cholmod_start, cfe_cholmod_finish, cfe_cholmod_analyse, cfe_cholmod_factor, &
            cfe_cholmod_solve, cfe_cholmod_rcond, cfe_cholmod_version, cfe_cholmod_header_version, &
            cholmod_shim_ok, cholmod_shim_not_posdef

  !> Return codes of cfe_cholmod_factor (cholmod_shim.c); negative values
  !> are CHOLMOD's own error statuses.
  integer(c_int), parameter :: cholmod_shim_ok = 0, cholmod_shim_not_posdef = 1

  interface
    !> A new workspace (supernodal LL', silent, quick return if not
    !> positive definite), or a null pointer.
    type(c_ptr) function cfe_cholmod_start() bind(C, name='cfe_cholmod_start')
      import :: c_ptr
    end function cfe_cholmod_start

    subroutine cfe_cholmod_finish(h) bind(C, name='cfe_cholmod_finish')
      import :: c_ptr
      type(c_ptr), value :: h
    end subroutine cfe_cholmod_finish

    !> Ordering (AMD, or perm when it is not null) and symbolic analysis.
    integer(c_int) function cfe_cholmod_analyse(h, n, ap, ai, ax, perm, lnz) bind(C, name='cfe_cholmod_analyse')
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: h
      integer(c_int), value :: n
      integer(c_int), intent(in) :: ap(*), ai(*)
      real(c_double), intent(in) :: ax(*)
      type(c_ptr), value :: perm
      real(c_double), intent(out) :: lnz
    end function cfe_cholmod_analyse

    !> Numeric factorisation; ratio = smallest pivot over its diagonal
    !> entry, col = its column (or the column not positive definite).
    integer(c_int) function cfe_cholmod_factor(h, n, ap, ai, ax, ratio, col) bind(C, name='cfe_cholmod_factor')
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: h
      integer(c_int), value :: n
      integer(c_int), intent(in) :: ap(*), ai(*)
      real(c_double), intent(in) :: ax(*)
      real(c_double), intent(out) :: ratio
      integer(c_int), intent(out) :: col
    end function cfe_cholmod_factor

    !> b(n, nrhs) is overwritten by the solution of A x = b.
    integer(c_int) function cfe_cholmod_solve(h, n, nrhs, b) bind(C, name='cfe_cholmod_solve')
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: h
      integer(c_int), value :: n, nrhs
      real(c_double), intent(inout) :: b(*)
    end function cfe_cholmod_solve

    real(c_double) function cfe_cholmod_rcond(h) bind(C, name='cfe_cholmod_rcond')
      import :: c_double, c_ptr
      type(c_ptr), value :: h
    end function cfe_cholmod_rcond

    subroutine cfe_cholmod_version(v) bind(C, name='cfe_cholmod_version')
      import :: c_int
      integer(c_int), intent(out) :: v(3)
    end subroutine cfe_cholmod_version

    subroutine cfe_cholmod_header_version(v) bind(C, name='cfe_cholmod_header_version')
      import :: c_int
      integer(c_int), intent(out) :: v(3)
    end subroutine cfe_cholmod_header_version
  end interface
end module cholmod_binding
