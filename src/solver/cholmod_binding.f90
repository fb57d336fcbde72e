!> CHOLMOD (SuiteSparse) through iso_c_binding: the int-index double API,
!> cholmod_start/analyze(_p)/factorize/solve/free/finish. cholmod_common is
!> mirrored field by field up to the statistics cfe2d reads (status, fl,
!> lnz) and padded beyond; the layout is that of CHOLMOD 3.x, checked at
!> start against the version and the documented defaults.
module cholmod_binding
  use, intrinsic :: iso_c_binding
  implicit none
  private
  public :: cholmod_method_t, cholmod_common_t, cholmod_sparse_t, cholmod_dense_t, &
            cholmod_start, cholmod_finish, cholmod_analyze, cholmod_analyze_p, cholmod_factorize, &
            cholmod_solve, cholmod_free_factor, cholmod_free_dense, cholmod_version, cholmod_rcond, &
            cholmod_ok, cholmod_not_posdef, cholmod_natural, cholmod_given, cholmod_amd, cholmod_metis, &
            cholmod_int, cholmod_double, cholmod_real, cholmod_sys_a, cholmod_maxmethods

  integer(c_int), parameter :: cholmod_ok = 0, cholmod_not_posdef = 1
  integer(c_int), parameter :: cholmod_natural = 0, cholmod_given = 1, cholmod_amd = 2, cholmod_metis = 3
  integer(c_int), parameter :: cholmod_int = 0, cholmod_double = 0, cholmod_real = 1, cholmod_sys_a = 0
  integer, parameter :: cholmod_maxmethods = 9

  type, bind(C) :: cholmod_method_t
    real(c_double) :: lnz, fl, prune_dense, prune_dense2, nd_oksep, other_1(4)
    integer(c_size_t) :: nd_small, other_2(4)
    integer(c_int) :: aggressive, order_for_lu, nd_compress, nd_camd, nd_components, ordering
    integer(c_size_t) :: other_3(4)
  end type cholmod_method_t

  type, bind(C) :: cholmod_common_t
    real(c_double) :: dbound, grow0, grow1
    integer(c_size_t) :: grow2, maxrank
    real(c_double) :: supernodal_switch
    integer(c_int) :: supernodal, final_asis, final_super, final_ll, final_pack, final_monotonic, &
                      final_resymbol
    real(c_double) :: zrelax(3)
    integer(c_size_t) :: nrelax(3)
    integer(c_int) :: prefer_zomplex, prefer_upper, quick_return_if_not_posdef, prefer_binary, &
                      print, precise, try_catch
    type(c_funptr) :: error_handler
    integer(c_int) :: nmethods, current, selected
    type(cholmod_method_t) :: method(cholmod_maxmethods + 1)
    integer(c_int) :: postorder, default_nesdis
    real(c_double) :: metis_memory, metis_dswitch
    integer(c_size_t) :: metis_nswitch, nrow
    integer(c_int64_t) :: mark
    integer(c_size_t) :: iworksize, xworksize
    type(c_ptr) :: flag, head, xwork, iwork
    integer(c_int) :: itype, dtype, no_workspace_reallocate, status
    real(c_double) :: fl, lnz, anz, modfl
    ! the rest of cholmod_common (2664 bytes in all in CHOLMOD 3.0), with room
    integer(c_int8_t) :: rest(8192)
  end type cholmod_common_t

  type, bind(C) :: cholmod_sparse_t
    integer(c_size_t) :: nrow, ncol, nzmax
    type(c_ptr) :: p, i, nz, x, z
    integer(c_int) :: stype, itype, xtype, dtype, sorted, packed
  end type cholmod_sparse_t

  type, bind(C) :: cholmod_dense_t
    integer(c_size_t) :: nrow, ncol, nzmax, d
    type(c_ptr) :: x, z
    integer(c_int) :: xtype, dtype
  end type cholmod_dense_t

  interface
    integer(c_int) function cholmod_start(c) bind(C, name='cholmod_start')
      import :: c_int, cholmod_common_t
      type(cholmod_common_t), intent(inout) :: c
    end function cholmod_start

    integer(c_int) function cholmod_finish(c) bind(C, name='cholmod_finish')
      import :: c_int, cholmod_common_t
      type(cholmod_common_t), intent(inout) :: c
    end function cholmod_finish

    integer(c_int) function cholmod_version(version) bind(C, name='cholmod_version')
      import :: c_int
      integer(c_int), intent(out) :: version(3)
    end function cholmod_version

    type(c_ptr) function cholmod_analyze(a, c) bind(C, name='cholmod_analyze')
      import :: c_ptr, cholmod_sparse_t, cholmod_common_t
      type(cholmod_sparse_t), intent(inout) :: a
      type(cholmod_common_t), intent(inout) :: c
    end function cholmod_analyze

    type(c_ptr) function cholmod_analyze_p(a, perm, fset, fsize, c) bind(C, name='cholmod_analyze_p')
      import :: c_ptr, c_int, c_size_t, cholmod_sparse_t, cholmod_common_t
      type(cholmod_sparse_t), intent(inout) :: a
      integer(c_int), intent(in) :: perm(*)
      type(c_ptr), value :: fset
      integer(c_size_t), value :: fsize
      type(cholmod_common_t), intent(inout) :: c
    end function cholmod_analyze_p

    integer(c_int) function cholmod_factorize(a, l, c) bind(C, name='cholmod_factorize')
      import :: c_int, c_ptr, cholmod_sparse_t, cholmod_common_t
      type(cholmod_sparse_t), intent(inout) :: a
      type(c_ptr), value :: l
      type(cholmod_common_t), intent(inout) :: c
    end function cholmod_factorize

    type(c_ptr) function cholmod_solve(sys, l, b, c) bind(C, name='cholmod_solve')
      import :: c_int, c_ptr, cholmod_dense_t, cholmod_common_t
      integer(c_int), value :: sys
      type(c_ptr), value :: l
      type(cholmod_dense_t), intent(inout) :: b
      type(cholmod_common_t), intent(inout) :: c
    end function cholmod_solve

    integer(c_int) function cholmod_free_factor(l, c) bind(C, name='cholmod_free_factor')
      import :: c_int, c_ptr, cholmod_common_t
      type(c_ptr), intent(inout) :: l
      type(cholmod_common_t), intent(inout) :: c
    end function cholmod_free_factor

    real(c_double) function cholmod_rcond(l, c) bind(C, name='cholmod_rcond')
      import :: c_double, c_ptr, cholmod_common_t
      type(c_ptr), value :: l
      type(cholmod_common_t), intent(inout) :: c
    end function cholmod_rcond

    integer(c_int) function cholmod_free_dense(x, c) bind(C, name='cholmod_free_dense')
      import :: c_int, c_ptr, cholmod_common_t
      type(c_ptr), intent(inout) :: x
      type(cholmod_common_t), intent(inout) :: c
    end function cholmod_free_dense
  end interface
end module cholmod_binding
