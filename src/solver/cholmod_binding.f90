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
            cfe_cholmod_analyse_last, cfe_cholmod_trailing_order, cfe_cholmod_trailing_block, &
            cfe_cholmod_forward, cfe_cholmod_backward, cholmod_shim_ok, cholmod_shim_not_posdef

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
    !> entry (the last nskip pivots not judged), col = its column (or the
    !> column not positive definite).
    integer(c_int) function cfe_cholmod_factor(h, n, ap, ai, ax, nskip, ratio, col) bind(C, name='cfe_cholmod_factor')
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: h
      integer(c_int), value :: n, nskip
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

    !> Ordering with the last nlast equations kept last (CAMD, or perm when
    !> it is not null) and symbolic analysis; flops of the factorisation.
    integer(c_int) function cfe_cholmod_analyse_last(h, n, ap, ai, ax, nlast, perm, lnz, flops) &
        bind(C, name='cfe_cholmod_analyse_last')
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: h
      integer(c_int), value :: n, nlast
      integer(c_int), intent(in) :: ap(*), ai(*)
      real(c_double), intent(in) :: ax(*)
      type(c_ptr), value :: perm
      real(c_double), intent(out) :: lnz, flops
    end function cfe_cholmod_analyse_last

    !> tperm(k) (0-based): the trailing equation at trailing position k.
    subroutine cfe_cholmod_trailing_order(h, tperm) bind(C, name='cfe_cholmod_trailing_order')
      import :: c_int, c_ptr
      type(c_ptr), value :: h
      integer(c_int), intent(out) :: tperm(*)
    end subroutine cfe_cholmod_trailing_order

    !> The trailing m x m block of L, dense, lower triangle.
    integer(c_int) function cfe_cholmod_trailing_block(h, m, l22) bind(C, name='cfe_cholmod_trailing_block')
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: h
      integer(c_int), value :: m
      real(c_double), intent(out) :: l22(*)
    end function cfe_cholmod_trailing_block

    !> b := L \ (P b), in the factor's order.
    integer(c_int) function cfe_cholmod_forward(h, n, b) bind(C, name='cfe_cholmod_forward')
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: h
      integer(c_int), value :: n
      real(c_double), intent(inout) :: b(*)
    end function cfe_cholmod_forward

    !> b := P' (L' \ b).
    integer(c_int) function cfe_cholmod_backward(h, n, b) bind(C, name='cfe_cholmod_backward')
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: h
      integer(c_int), value :: n
      real(c_double), intent(inout) :: b(*)
    end function cfe_cholmod_backward

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
