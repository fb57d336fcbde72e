!> UMFPACK (SuiteSparse) through iso_c_binding: the int-index double
!> routines umfpack_di_*. Symbolic and Numeric objects are opaque handles.
module umfpack_binding
  use, intrinsic :: iso_c_binding
  implicit none
  private
  public :: umfpack_di_defaults, umfpack_di_symbolic, umfpack_di_numeric, umfpack_di_solve, &
            umfpack_di_free_symbolic, umfpack_di_free_numeric, umfpack_di_get_numeric, &
            umfpack_control, umfpack_info, &
            umfpack_ok, umfpack_warning_singular, umfpack_sys_a, umfpack_ordering, &
            umfpack_ordering_amd, umfpack_ordering_metis, umfpack_status, umfpack_lnz, umfpack_unz, &
            umfpack_peak_memory, umfpack_prl, umfpack_rcond

  integer, parameter :: umfpack_control = 20, umfpack_info = 90
  integer(c_int), parameter :: umfpack_ok = 0, umfpack_warning_singular = 1, umfpack_sys_a = 0
  ! indices into Control and Info, 1-based here (C index + 1)
  integer, parameter :: umfpack_prl = 1, umfpack_ordering = 11, umfpack_status = 1, &
                        umfpack_lnz = 44, umfpack_unz = 45, umfpack_peak_memory = 42, &
                        umfpack_rcond = 68
  real(c_double), parameter :: umfpack_ordering_amd = 1.0_c_double, umfpack_ordering_metis = 3.0_c_double

  interface
    subroutine umfpack_di_defaults(control) bind(C, name='umfpack_di_defaults')
      import :: c_double
      real(c_double), intent(out) :: control(*)
    end subroutine umfpack_di_defaults

    integer(c_int) function umfpack_di_symbolic(n_row, n_col, ap, ai, ax, symbolic, control, info) &
        bind(C, name='umfpack_di_symbolic')
      import :: c_int, c_double, c_ptr
      integer(c_int), value :: n_row, n_col
      integer(c_int), intent(in) :: ap(*), ai(*)
      real(c_double), intent(in) :: ax(*)
      type(c_ptr), intent(out) :: symbolic
      real(c_double), intent(in) :: control(*)
      real(c_double), intent(out) :: info(*)
    end function umfpack_di_symbolic

    integer(c_int) function umfpack_di_numeric(ap, ai, ax, symbolic, numeric, control, info) &
        bind(C, name='umfpack_di_numeric')
      import :: c_int, c_double, c_ptr
      integer(c_int), intent(in) :: ap(*), ai(*)
      real(c_double), intent(in) :: ax(*)
      type(c_ptr), value :: symbolic
      type(c_ptr), intent(out) :: numeric
      real(c_double), intent(in) :: control(*)
      real(c_double), intent(out) :: info(*)
    end function umfpack_di_numeric

    integer(c_int) function umfpack_di_solve(sys, ap, ai, ax, x, b, numeric, control, info) &
        bind(C, name='umfpack_di_solve')
      import :: c_int, c_double, c_ptr
      integer(c_int), value :: sys
      integer(c_int), intent(in) :: ap(*), ai(*)
      real(c_double), intent(in) :: ax(*)
      real(c_double), intent(out) :: x(*)
      real(c_double), intent(in) :: b(*)
      type(c_ptr), value :: numeric
      real(c_double), intent(in) :: control(*)
      real(c_double), intent(out) :: info(*)
    end function umfpack_di_solve

    !> Parts of the factorisation P R A Q = L U; a null pointer skips a
    !> part. Used for Q (column order), Dx (diag(U)), do_recip and Rs (the
    !> row scaling R: multiply by Rs when do_recip = 1, else divide).
    integer(c_int) function umfpack_di_get_numeric(lp, lj, lx, up, ui, ux, p, q, dx, do_recip, rs, numeric) &
        bind(C, name='umfpack_di_get_numeric')
      import :: c_int, c_ptr
      type(c_ptr), value :: lp, lj, lx, up, ui, ux, p, q, dx
      integer(c_int), intent(out) :: do_recip
      type(c_ptr), value :: rs, numeric
    end function umfpack_di_get_numeric

    subroutine umfpack_di_free_symbolic(symbolic) bind(C, name='umfpack_di_free_symbolic')
      import :: c_ptr
      type(c_ptr), intent(inout) :: symbolic
    end subroutine umfpack_di_free_symbolic

    subroutine umfpack_di_free_numeric(numeric) bind(C, name='umfpack_di_free_numeric')
      import :: c_ptr
      type(c_ptr), intent(inout) :: numeric
    end subroutine umfpack_di_free_numeric
  end interface
end module umfpack_binding
