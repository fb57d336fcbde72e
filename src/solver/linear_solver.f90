!> One interface over the three direct solvers of the global equations:
!> the skyline LDL^T written here, CHOLMOD (default; the penalty-contact
!> stiffness is symmetric positive definite) and UMFPACK. Symbolic analysis
!> is done once per pattern and reused; only numeric factorisations repeat.
!> If CHOLMOD finds the matrix not positive definite the system falls back
!> to UMFPACK and says so.
module linear_solver
  use, intrinsic :: iso_c_binding
  use kinds, only: dp
  use strings, only: itoa
  use skyline, only: skyline_t, sky_setup, sky_add, sky_factor, sky_solve, sky_matvec, sky_zero
  use sparse_matrix, only: csc_t, csc_build, csc_zero, csc_add_element, csc_matvec, csc_position
  use cholmod_binding
  use umfpack_binding
  use metis_binding, only: metis_nodend, metis_setdefaultoptions, metis_noptions, metis_ok
  use messages, only: fatal
  use solver_codes
  implicit none
  private
  public :: linear_system_t, solver_skyline, solver_cholmod, solver_umfpack, &
            order_natural, order_rcm, order_amd, order_metis, &
            sys_setup, sys_zero, sys_add, sys_analyse, sys_factor, sys_solve, sys_matvec, sys_free, &
            sys_describe, solver_name, ordering_name, factor_ok, factor_singular, factor_fallback

  integer, parameter :: factor_ok = 0, factor_singular = 1, factor_fallback = 2
  !> Below these the factor is taken as singular: min/max of diag(L) for
  !> CHOLMOD's LL' (its square estimates 1/cond), UMFPACK's own estimate.
  real(dp), parameter :: rcond_l_min = 1.0e-7_dp, rcond_lu_min = 1.0e-14_dp

  !> The leading fields of cholmod_factor.
  type, bind(C) :: factor_head_t
    integer(c_size_t) :: n, minor
    type(c_ptr) :: perm, colcount, iperm
  end type factor_head_t

  type :: linear_system_t
    integer :: kind = solver_cholmod
    integer :: ordering = order_amd
    integer :: n = 0
    type(skyline_t) :: sky
    type(csc_t) :: a
    integer, allocatable :: xeq(:), eqs(:)           ! element equation lists
    ! CHOLMOD
    type(cholmod_common_t), pointer :: cc => null()
    type(cholmod_sparse_t) :: ca
    type(c_ptr) :: factor = c_null_ptr
    integer(c_int), allocatable :: ap0(:), ai0(:)    ! 0-based copies for C
    ! UMFPACK
    type(c_ptr) :: symbolic = c_null_ptr, numeric = c_null_ptr
    real(c_double) :: control(umfpack_control) = 0.0_c_double, info(umfpack_info) = 0.0_c_double
    logical :: analysed = .false.
    real(dp) :: factor_entries = 0.0_dp              ! nnz(L) (+ nnz(U)) or profile
    character(len=:), allocatable :: note            ! fallback message, if any
  end type linear_system_t

contains

  !> Structure of the system from the element equation lists (skyline
  !> heights, or the CSC pattern and its element map).
  subroutine sys_setup(s, kind, ordering, n, xeq, eqs)
    type(linear_system_t), intent(inout) :: s
    integer, intent(in) :: kind, ordering, n, xeq(:), eqs(:)
    integer, allocatable :: first(:)
    integer :: e, k, lo
    call sys_free(s)
    s%kind = kind
    s%ordering = ordering
    s%n = n
    s%xeq = xeq
    s%eqs = eqs
    s%analysed = .false.
    if (allocated(s%note)) deallocate(s%note)
    if (kind == solver_skyline) then
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
      call sky_setup(s%sky, first)
      s%factor_entries = real(s%sky%nnz, dp)
    else
      call csc_build(s%a, n, xeq, eqs, upper=(kind == solver_cholmod))
    end if
  end subroutine sys_setup

  subroutine sys_zero(s)
    type(linear_system_t), intent(inout) :: s
    if (s%kind == solver_skyline) then
      call sky_zero(s%sky)
    else
      call csc_zero(s%a)
    end if
  end subroutine sys_zero

  !> Adds the matrix of element e (its equation list as given to sys_setup).
  subroutine sys_add(s, e, ke)
    type(linear_system_t), intent(inout) :: s
    integer, intent(in) :: e
    real(dp), intent(in) :: ke(:, :)
    integer :: i, j, gi, gj, i0
    i0 = s%xeq(e) - 1
    if (s%kind == solver_skyline) then
      do i = 1, size(ke, 1)
        gi = s%eqs(i0 + i)
        if (gi <= 0) cycle
        do j = i, size(ke, 1)
          gj = s%eqs(i0 + j)
          if (gj > 0) call sky_add(s%sky, gi, gj, ke(i, j))
        end do
      end do
    else
      call csc_add_element(s%a, e, s%eqs(s%xeq(e):s%xeq(e + 1) - 1), ke)
    end if
  end subroutine sys_add

  pure subroutine sys_matvec(s, x, y)
    type(linear_system_t), intent(in) :: s
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: y(:)
    if (s%kind == solver_skyline) then
      call sky_matvec(s%sky, x, y)
    else
      call csc_matvec(s%a, x, y)
    end if
  end subroutine sys_matvec

  !> Ordering and symbolic analysis of the sparse solvers (done by
  !> sys_factor when needed; separate for timing).
  subroutine sys_analyse(s)
    type(linear_system_t), intent(inout) :: s
    if (s%analysed) return
    if (s%kind == solver_cholmod) call cholmod_analyse(s)
    if (s%kind == solver_umfpack) call umfpack_analyse(s)
  end subroutine sys_analyse

  !> Numeric factorisation (symbolic analysis first if the pattern is new).
  !> status: factor_ok, factor_singular (bad = equation where detected, 0
  !> if the solver does not say), or factor_fallback (CHOLMOD found the
  !> matrix not positive definite; UMFPACK factorised it).
  subroutine sys_factor(s, status, bad)
    type(linear_system_t), intent(inout) :: s
    integer, intent(out) :: status, bad
    status = factor_ok
    bad = 0
    select case (s%kind)
    case (solver_skyline)
      call sky_factor(s%sky, bad)
      if (bad > 0) status = factor_singular
    case (solver_cholmod)
      call cholmod_factor_numeric(s, status, bad)
      if (status == factor_fallback) then
        s%note = 'CHOLMOD: the matrix is not positive definite (at equation ' // itoa(bad) // &
                 '); falling back to UMFPACK'
        call switch_to_umfpack(s)
        call umfpack_factor_numeric(s, status, bad)
        if (status == factor_ok) status = factor_fallback
      end if
    case (solver_umfpack)
      call umfpack_factor_numeric(s, status, bad)
    end select
  end subroutine sys_factor

  subroutine sys_solve(s, b)
    type(linear_system_t), intent(inout) :: s
    real(dp), intent(inout) :: b(:)
    select case (s%kind)
    case (solver_skyline)
      call sky_solve(s%sky, b)
    case (solver_cholmod)
      call cholmod_solve_rhs(s, b)
    case (solver_umfpack)
      call umfpack_solve_rhs(s, b)
    end select
  end subroutine sys_solve

  function sys_describe(s) result(d)
    type(linear_system_t), intent(in) :: s
    character(len=:), allocatable :: d
    character(len=40) :: buf
    write(buf, '(es12.5)') s%factor_entries
    if (s%kind == solver_skyline) then
      d = solver_name(s%kind) // ', ordering ' // ordering_name(s%ordering) // ', profile ' // trim(adjustl(buf))
    else
      d = solver_name(s%kind) // ', ordering ' // ordering_name(s%ordering) // ', factor entries ' // &
          trim(adjustl(buf))
    end if
  end function sys_describe

  subroutine sys_free(s)
    type(linear_system_t), intent(inout) :: s
    integer(c_int) :: ok
    if (c_associated(s%factor)) ok = cholmod_free_factor(s%factor, s%cc)
    s%factor = c_null_ptr
    if (associated(s%cc)) then
      ok = cholmod_finish(s%cc)
      deallocate(s%cc)
    end if
    if (c_associated(s%numeric)) call umfpack_di_free_numeric(s%numeric)
    if (c_associated(s%symbolic)) call umfpack_di_free_symbolic(s%symbolic)
    s%numeric = c_null_ptr
    s%symbolic = c_null_ptr
    s%analysed = .false.
  end subroutine sys_free

  ! ------------------------------------------------------------- CHOLMOD

  subroutine cholmod_init(s)
    type(linear_system_t), intent(inout) :: s
    integer(c_int) :: v(3), ok
    ok = cholmod_version(v)
    if (v(1) /= 3) call fatal('CHOLMOD ' // itoa(int(v(1))) // '.' // itoa(int(v(2))) // &
      ' found; this binding mirrors the cholmod_common of CHOLMOD 3.x')
    allocate(s%cc)
    ok = cholmod_start(s%cc)
    ! Defaults documented for cholmod_start: a mismatch means the mirrored
    ! struct does not match the library's.
    if (ok /= 1 .or. abs(s%cc%grow0 - 1.2_c_double) > 1.0e-12_c_double .or. s%cc%maxrank /= 8 .or. &
        abs(s%cc%supernodal_switch - 40.0_c_double) > 1.0e-12_c_double .or. s%cc%status /= cholmod_ok) &
      call fatal('CHOLMOD common block layout does not match cholmod_start defaults')
    s%cc%print = 0
    s%cc%quick_return_if_not_posdef = 1
    ! Always the supernodal LL' factorisation: it reports a matrix that is
    ! not positive definite (the simplicial LDL' would factor it silently,
    ! without pivoting).
    s%cc%supernodal = 2
  end subroutine cholmod_init

  !> Ordering and symbolic factorisation, once per pattern.
  subroutine cholmod_analyse(s)
    type(linear_system_t), intent(inout), target :: s
    integer(c_int), allocatable :: perm(:)
    if (.not. associated(s%cc)) call cholmod_init(s)
    s%ap0 = int(s%a%colptr - 1, c_int)
    s%ai0 = int(s%a%rowind - 1, c_int)
    s%ca%nrow = int(s%n, c_size_t)
    s%ca%ncol = int(s%n, c_size_t)
    s%ca%nzmax = int(size(s%a%val), c_size_t)
    s%ca%p = c_loc(s%ap0)
    s%ca%i = c_loc(s%ai0)
    s%ca%nz = c_null_ptr
    s%ca%z = c_null_ptr
    s%ca%stype = 1          ! symmetric, upper triangle stored
    s%ca%itype = cholmod_int
    s%ca%xtype = cholmod_real
    s%ca%dtype = cholmod_double
    s%ca%sorted = 1
    s%ca%packed = 1
    s%ca%x = c_loc(s%a%val)
    if (s%ordering == order_metis) then
      call metis_order(s%n, s%a, perm)
      s%cc%nmethods = 1
      s%cc%method(1)%ordering = cholmod_given
      s%factor = cholmod_analyze_p(s%ca, perm, c_null_ptr, 0_c_size_t, s%cc)
    else
      s%cc%nmethods = 1
      s%cc%method(1)%ordering = cholmod_amd
      s%factor = cholmod_analyze(s%ca, s%cc)
    end if
    if (.not. c_associated(s%factor) .or. s%cc%status < cholmod_ok) &
      call fatal('CHOLMOD analysis failed, status ' // itoa(int(s%cc%status)))
    s%factor_entries = s%cc%lnz
    s%analysed = .true.
  end subroutine cholmod_analyse

  subroutine cholmod_factor_numeric(s, status, bad)
    type(linear_system_t), intent(inout), target :: s
    integer, intent(out) :: status, bad
    integer(c_int) :: ok
    status = factor_ok
    bad = 0
    if (.not. s%analysed) call cholmod_analyse(s)
    s%ca%x = c_loc(s%a%val)
    ok = cholmod_factorize(s%ca, s%factor, s%cc)
    if (s%cc%status == cholmod_not_posdef) then
      bad = factor_minor(s)
      status = factor_fallback
    else if (ok /= 1 .or. s%cc%status < cholmod_ok) then
      call fatal('CHOLMOD factorisation failed, status ' // itoa(int(s%cc%status)))
    else if (cholmod_rcond(s%factor, s%cc) < rcond_l_min) then
      ! min/max of diag(L): a left-over rigid mode shows as round-off sized
      ! pivots that CHOLMOD still accepts as positive.
      status = factor_singular
    end if
  end subroutine cholmod_factor_numeric

  !> Equation (1-based, original numbering) where the factorisation stopped:
  !> L->minor is a column of the permuted matrix, L->Perm maps it back.
  integer function factor_minor(s)
    type(linear_system_t), intent(in) :: s
    type(factor_head_t), pointer :: head
    integer(c_int), pointer :: perm(:)
    call c_f_pointer(s%factor, head)
    factor_minor = 0
    if (head%minor >= head%n .or. .not. c_associated(head%perm)) return
    call c_f_pointer(head%perm, perm, [int(head%n)])
    factor_minor = perm(int(head%minor) + 1) + 1
  end function factor_minor

  subroutine cholmod_solve_rhs(s, b)
    type(linear_system_t), intent(inout) :: s
    real(dp), intent(inout), target :: b(:)
    type(cholmod_dense_t) :: cb
    type(cholmod_dense_t), pointer :: cx
    type(c_ptr) :: px
    real(c_double), pointer :: x(:)
    integer(c_int) :: ok
    cb%nrow = int(s%n, c_size_t)
    cb%ncol = 1
    cb%nzmax = int(s%n, c_size_t)
    cb%d = int(s%n, c_size_t)
    cb%x = c_loc(b)
    cb%z = c_null_ptr
    cb%xtype = cholmod_real
    cb%dtype = cholmod_double
    px = cholmod_solve(cholmod_sys_a, s%factor, cb, s%cc)
    if (.not. c_associated(px)) call fatal('CHOLMOD solve failed, status ' // itoa(int(s%cc%status)))
    call c_f_pointer(px, cx)
    call c_f_pointer(cx%x, x, [s%n])
    b = x
    ok = cholmod_free_dense(px, s%cc)
  end subroutine cholmod_solve_rhs

  !> Nested-dissection order of the matrix graph (METIS_NodeND), 0-based
  !> as CHOLMOD wants it.
  subroutine metis_order(n, a, perm)
    integer, intent(in) :: n
    type(csc_t), intent(in) :: a
    integer(c_int), allocatable, intent(out) :: perm(:)
    integer(c_int), allocatable :: xadj(:), adj(:), iperm(:), cnt(:)
    integer(c_int) :: options(metis_noptions), nv, ok
    integer :: col, k, r
    ! symmetric graph without the diagonal from the upper pattern
    allocate(cnt(n), xadj(n + 1))
    cnt = 0
    do col = 1, n
      do k = a%colptr(col), a%colptr(col + 1) - 1
        r = a%rowind(k)
        if (r == col) cycle
        cnt(r) = cnt(r) + 1
        cnt(col) = cnt(col) + 1
      end do
    end do
    xadj(1) = 0
    do col = 1, n
      xadj(col + 1) = xadj(col) + cnt(col)
    end do
    allocate(adj(max(xadj(n + 1), 1)))
    cnt = xadj(1:n)
    do col = 1, n
      do k = a%colptr(col), a%colptr(col + 1) - 1
        r = a%rowind(k)
        if (r == col) cycle
        adj(cnt(r) + 1) = col - 1
        cnt(r) = cnt(r) + 1
        adj(cnt(col) + 1) = r - 1
        cnt(col) = cnt(col) + 1
      end do
    end do
    allocate(perm(n), iperm(n))
    ok = metis_setdefaultoptions(options)
    nv = int(n, c_int)
    ok = metis_nodend(nv, xadj, adj, c_null_ptr, options, perm, iperm)
    if (ok /= metis_ok) call fatal('METIS_NodeND failed with status ' // itoa(int(ok)))
  end subroutine metis_order

  ! ------------------------------------------------------------- UMFPACK

  !> CHOLMOD keeps the upper triangle; UMFPACK needs the full pattern.
  subroutine switch_to_umfpack(s)
    type(linear_system_t), intent(inout) :: s
    type(csc_t) :: full
    real(dp), allocatable :: v(:)
    integer :: col, k, r, kk
    integer(c_int) :: ok
    if (c_associated(s%factor)) ok = cholmod_free_factor(s%factor, s%cc)
    s%factor = c_null_ptr
    call csc_build(full, s%n, s%xeq, s%eqs, upper=.false.)
    ! copy the assembled values into both triangles
    allocate(v(size(full%val)))
    v = 0.0_dp
    do col = 1, s%n
      do k = s%a%colptr(col), s%a%colptr(col + 1) - 1
        r = s%a%rowind(k)
        kk = csc_position(full, r, col)
        v(kk) = v(kk) + s%a%val(k)
        if (r /= col) then
          kk = csc_position(full, col, r)
          v(kk) = v(kk) + s%a%val(k)
        end if
      end do
    end do
    full%val = v
    s%a = full
    s%kind = solver_umfpack
    s%analysed = .false.
  end subroutine switch_to_umfpack

  subroutine umfpack_analyse(s)
    type(linear_system_t), intent(inout) :: s
    integer(c_int) :: st
    call umfpack_di_defaults(s%control)
    s%control(umfpack_prl) = 0.0_c_double
    if (s%ordering == order_metis) then
      s%control(umfpack_ordering) = umfpack_ordering_metis
    else
      s%control(umfpack_ordering) = umfpack_ordering_amd
    end if
    s%ap0 = int(s%a%colptr - 1, c_int)
    s%ai0 = int(s%a%rowind - 1, c_int)
    if (c_associated(s%symbolic)) call umfpack_di_free_symbolic(s%symbolic)
    st = umfpack_di_symbolic(int(s%n, c_int), int(s%n, c_int), s%ap0, s%ai0, s%a%val, s%symbolic, &
                             s%control, s%info)
    if (st /= umfpack_ok) call fatal('UMFPACK symbolic analysis failed, status ' // itoa(int(st)))
    s%analysed = .true.
  end subroutine umfpack_analyse

  subroutine umfpack_factor_numeric(s, status, bad)
    type(linear_system_t), intent(inout) :: s
    integer, intent(out) :: status, bad
    integer(c_int) :: st
    status = factor_ok
    bad = 0
    if (.not. s%analysed) call umfpack_analyse(s)
    if (c_associated(s%numeric)) call umfpack_di_free_numeric(s%numeric)
    st = umfpack_di_numeric(s%ap0, s%ai0, s%a%val, s%symbolic, s%numeric, s%control, s%info)
    if (st == umfpack_warning_singular .or. (st == umfpack_ok .and. s%info(umfpack_rcond) < rcond_lu_min)) then
      status = factor_singular
      return
    end if
    if (st /= umfpack_ok) call fatal('UMFPACK numeric factorisation failed, status ' // itoa(int(st)))
    s%factor_entries = s%info(umfpack_lnz) + s%info(umfpack_unz)
  end subroutine umfpack_factor_numeric

  subroutine umfpack_solve_rhs(s, b)
    type(linear_system_t), intent(inout) :: s
    real(dp), intent(inout) :: b(:)
    real(c_double), allocatable :: x(:)
    integer(c_int) :: st
    allocate(x(s%n))
    st = umfpack_di_solve(umfpack_sys_a, s%ap0, s%ai0, s%a%val, x, b, s%numeric, s%control, s%info)
    if (st /= umfpack_ok) call fatal('UMFPACK solve failed, status ' // itoa(int(st)))
    b = x
  end subroutine umfpack_solve_rhs

end module linear_solver
