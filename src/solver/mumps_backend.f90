!> MUMPS (multifrontal, distributed over the MPI ranks of the run) as a
!> solver backend. Rank 0 assembles the matrix in compressed columns and
!> hands MUMPS their coordinates and values: the upper triangle as a
!> symmetric matrix (SYM=2: LDL^T with pivoting, so that a matrix that is
!> not positive definite is factored too), or, from the first element
!> matrix that is unsymmetric beyond round-off (a sliding frictional
!> contact; symmetric_element says where the line is), both triangles as
!> an unsymmetric one (SYM=0, LU), after which the backend stays
!> unsymmetric for this structure. The
!> other ranks join every analysis, factorisation and solve
!> (mumps_shim.c). Ordering: METIS or AMD, by MUMPS (ICNTL(7)).
!> A singular matrix is recognised by MUMPS' null-pivot detection
!> (ICNTL(24)=1, threshold CNTL(3) = pivot_ratio_min of the scaled matrix):
!> the first null pivot's equation is reported. Workspace too small
!> (INFOG(1) = -8, -9, -14, -15, ...) is retried with twice the
!> workspace margin ICNTL(14); an allocation that fails (-13), the
!> memory limit per rank of CFE2D_MUMPS_MEMORY_MB (ICNTL(23), -19) or a
!> problem past MUMPS' integer range is a clear fatal error.
!> With a trailing block (nlast > 0) MUMPS returns the Schur complement
!> S0 of the leading equations on it (ICNTL(19)=1, centralised on rank 0);
!> the backend offers the same as CHOLMOD's trailing block: L22 = chol(S0
!> + diag(K22)) (so that S0 = L22 L22^T - diag(K22), as in
!> cholmod_backend) and the forward and backward halves of a solve,
!> written with solves of the leading block only (ICNTL(26)=0):
!>   forward:  [b1; b2] -> [b1; L22^-1 (b2 - K21 K11^-1 b1)]
!>   backward: [b1; w2] -> [K11^-1 (b1 - K12 x2); x2], x2 = L22^-T w2,
!> which compose to K^-1 with K22 = S0's share as the condensed solve
!> uses them (analysis/condensed_contact).
module mumps_backend
  use, intrinsic :: iso_c_binding, only: c_int, c_double, c_long_long
  use kinds, only: dp
  use strings, only: itoa, rtoa
  use messages, only: fatal
  use blas_info, only: set_solver_threads
  use solver_codes, only: order_metis, solver_mumps, solver_in_build
  use sparse_matrix, only: csc_t, csc_build, csc_zero, csc_add_element, csc_matvec, csc_add_upper
  use dense_cholesky, only: dense_factor
  use mumps_binding, only: cfe_mpi_start, cfe_mumps_new, cfe_mumps_free, &
                           cfe_mumps_get_control, cfe_mumps_set_control, cfe_mumps_job, cfe_mumps_null_pivots, &
                           mumps_job_analyse, mumps_job_factor, mumps_job_solve
  use solver_backend, only: solver_backend_t, factor_ok, factor_singular, pivot_ratio_min
  implicit none
  private
  public :: mumps_backend_t

  !> MUMPS' SYM: symmetric (LDL^T with pivoting) and unsymmetric (LU).
  integer, parameter :: sym_symmetric = 2, sym_general = 0
  !> Workspace retries: ICNTL(14) (percent over the analysis' estimate)
  !> doubled up to this many times.
  integer, parameter :: max_retries = 4

  interface
    subroutine dtrsv(uplo, trans, diag, n, a, lda, x, incx)
      import :: dp
      character, intent(in) :: uplo, trans, diag
      integer, intent(in) :: n, lda, incx
      real(dp), intent(in) :: a(lda, *)
      real(dp), intent(inout) :: x(*)
    end subroutine dtrsv
  end interface

  type, extends(solver_backend_t) :: mumps_backend_t
    type(csc_t) :: a                          ! upper triangle, both once unsymmetric
    integer(c_int) :: h = -1                  ! MUMPS instance (mumps_shim), -1 none
    integer :: sym = sym_symmetric
    integer :: ranks = 1
    integer :: margin = 35                    ! ICNTL(14)
    logical :: analysed = .false.
    integer(c_int), allocatable :: irn(:), jcn(:), schur_list(:)   ! coordinates of a's entries
    real(dp), allocatable :: l22(:, :)        ! chol(S0 + diag(K22)), lower
    !> MUMPS' memory in MB, the largest rank and all ranks: estimated by
    !> the analysis (INFOG(16), INFOG(17)), then used by the last
    !> factorisation (INFOG(21), INFOG(22))
    real(dp) :: mem_rank_mb = 0.0_dp, mem_total_mb = 0.0_dp
    integer(c_int) :: infog(80) = 0, info(80) = 0
    real(c_double) :: rinfog(40) = 0.0_c_double
  contains
    procedure :: setup, zero, add, analyse, factor, solve, matvec, describe, stored_entries, free
    procedure :: condensed_factor, forward, backward, trailing_order
    procedure, private :: run, interior_solve, numeric, go_general
  end type mumps_backend_t

contains

  subroutine setup(self, n, ordering, xeq, eqs)
    class(mumps_backend_t), intent(inout) :: self
    integer, intent(in) :: n, ordering, xeq(:), eqs(:)
    call self%free()
    if (.not. solver_in_build(solver_mumps)) call fatal('MUMPS is not in this build of cfe2d (built without MPI or ' // &
                                           'libmumps-dev; see docs/running.md, "Several machines")')
    call self%keep_structure(n, ordering, xeq, eqs)
    call csc_build(self%a, n, xeq, eqs, upper=.true.)
    self%sym = sym_symmetric
  end subroutine setup

  subroutine zero(self)
    class(mumps_backend_t), intent(inout) :: self
    call csc_zero(self%a)
  end subroutine zero

  !> Purpose: adds the element matrix ke of element e; the first one that
  !> is not symmetric turns the store to both triangles (go_general).
  subroutine add(self, e, ke)
    class(mumps_backend_t), intent(inout) :: self
    integer, intent(in) :: e
    real(dp), intent(in) :: ke(:, :)
    if (self%a%upper) then
      if (.not. symmetric_element(ke)) call self%go_general()
    end if
    call csc_add_element(self%a, e, self%eqs(self%xeq(e):self%xeq(e + 1) - 1), ke)
  end subroutine add

  !> Purpose: is an element matrix symmetric to round-off? Entry pairs may
  !> differ by 1e-12 of its largest diagonal entry (the last bits of a
  !> coupling element's tangent); sliding friction differs by a share mu
  !> of the normal stiffness.
  pure logical function symmetric_element(ke)
    real(dp), intent(in) :: ke(:, :)
    real(dp), parameter :: sym_tol = 1.0e-12_dp
    real(dp) :: dmax
    integer :: i, j
    dmax = 0.0_dp
    do i = 1, size(ke, 1)
      dmax = max(dmax, abs(ke(i, i)))
    end do
    symmetric_element = .true.
    do j = 1, size(ke, 2)
      do i = 1, j - 1
        if (abs(ke(i, j) - ke(j, i)) > sym_tol * dmax) symmetric_element = .false.
      end do
    end do
  end function symmetric_element

  !> Purpose: the store from the upper triangle to both (what is assembled
  !> so far is symmetric), MUMPS to LU: a new instance and analysis.
  subroutine go_general(self)
    class(mumps_backend_t), intent(inout) :: self
    type(csc_t) :: full
    call csc_build(full, self%n, self%xeq, self%eqs, upper=.false.)
    call csc_add_upper(full, self%a)
    self%a = full
    if (self%h >= 0) call cfe_mumps_free(self%h)
    self%h = -1
    self%sym = sym_general
    self%analysed = .false.
  end subroutine go_general

  !> Purpose: a MUMPS instance for the current symmetry, its controls, the
  !> coordinates handed to it, and MUMPS' analysis (ordering, symbolic
  !> factorisation, mapping onto the ranks), once per pattern and symmetry.
  subroutine analyse(self)
    class(mumps_backend_t), intent(inout) :: self
    integer(c_int) :: icntl(60)
    real(c_double) :: cntl(15)
    integer :: col, k, cnt, nlead
    if (self%analysed) return
    self%analysed = .true.
    self%factor_entries = 0.0_dp
    if (self%n == 0) return
    call set_solver_threads()
    if (self%h < 0) then
      self%ranks = int(cfe_mpi_start(1_c_int))
      if (self%ranks < 1) call fatal('MUMPS: MPI could not be started (MPI_Init failed)')
      self%h = cfe_mumps_new(int(self%sym, c_int))
      if (self%h < 0) call fatal('MUMPS: no instance could be made (MPI_Init failed, or too many systems)')
    end if
    call cfe_mumps_get_control(self%h, icntl, cntl)
    icntl(1:3) = -1                       ! no messages: cfe2d reports
    icntl(4) = 0
    icntl(5) = 0                          ! assembled matrix
    icntl(18) = 0                         ! centralised on rank 0
    icntl(7) = merge(5, 0, self%ordering == order_metis)   ! METIS or AMD
    icntl(14) = self%margin
    icntl(24) = 1                         ! null pivots detected and listed
    icntl(28) = 1                         ! sequential analysis: the matrix is on rank 0
    ! an analysis of the structure only (it may run before the matrix is
    ! assembled: CONTACT SOLVE=AUTO asks for the flop count first): no
    ! weighted matching or 2x2 compression from the values, which an empty
    ! matrix made meaningless (the 1e6-dof square: factor 2.0e8 entries
    ! instead of 1.07e8, 10 s instead of 2.4 s); scaling from the values
    ! at each factorisation
    icntl(6) = 0
    icntl(12) = 1
    icntl(8) = 7
    icntl(23) = memory_limit_mb()         ! 0: no limit
    cntl(3) = pivot_ratio_min
    icntl(19) = merge(1, 0, self%nlast > 0)   ! Schur complement, centralised by rows
    icntl(26) = 0                         ! with a Schur block: solves of the leading block
    call cfe_mumps_set_control(self%h, icntl, cntl)
    ! MUMPS gets every stored entry: the upper triangle, or both
    cnt = size(self%a%val)
    if (allocated(self%irn)) deallocate(self%irn, self%jcn)
    allocate(self%irn(cnt), self%jcn(cnt))
    do col = 1, self%n
      do k = self%a%colptr(col), self%a%colptr(col + 1) - 1
        self%irn(k) = int(self%a%rowind(k), c_int)
        self%jcn(k) = int(col, c_int)
      end do
    end do
    nlead = self%n - self%nlast
    self%schur_list = [(int(k, c_int), k = nlead + 1, self%n)]
    call self%run(mumps_job_analyse, 'analysis')
    self%factor_entries = mumps_count(self%infog(20))
    self%mem_rank_mb = real(self%infog(16), dp)
    self%mem_total_mb = real(self%infog(17), dp)
    ! MUMPS counts the leading equations only; with a Schur block the
    ! whole factorisation adds the block's dense Cholesky (m^3/3), as
    ! CHOLMOD's count of a factor with the block last does (the AUTO
    ! choice of the contact solve compares this with m^3/3)
    self%factor_flops = self%rinfog(1) + real(self%nlast, dp)**3 / 3.0_dp
  end subroutine analyse

  !> Purpose: one MUMPS job with the current matrix; a workspace too small
  !> is retried with a larger margin (the factorisation), any other error
  !> of MUMPS stops the run with its meaning. Null pivots are no error.
  !> Arguments: job (mumps_job_*), what names it in messages; rhs(n,
  !> nrhs) for a solve.
  subroutine run(self, job, what, rhs)
    class(mumps_backend_t), intent(inout) :: self
    integer(c_int), intent(in) :: job
    character(len=*), intent(in) :: what
    real(dp), intent(inout), optional, target :: rhs(:, :)
    real(c_double) :: none(1), sdum(1)
    integer(c_int) :: st, nrhs, icntl(60)
    real(c_double) :: cntl(15)
    integer :: attempt
    none = 0.0_c_double
    sdum = 0.0_c_double
    nrhs = 0
    if (present(rhs)) nrhs = int(size(rhs, 2), c_int)
    do attempt = 0, max_retries
      if (present(rhs)) then
        if (self%nlast > 0 .and. job == mumps_job_factor) then
          st = cfe_mumps_job(self%h, job, int(self%n, c_int), int(size(self%irn), c_long_long), self%irn, self%jcn, &
                             self%a%val, int(self%nlast, c_int), self%schur_list, self%l22, nrhs, rhs, self%infog, &
                             self%info, self%rinfog)
        else
          st = cfe_mumps_job(self%h, job, int(self%n, c_int), int(size(self%irn), c_long_long), self%irn, self%jcn, &
                             self%a%val, int(self%nlast, c_int), self%schur_list, sdum, nrhs, rhs, self%infog, &
                             self%info, self%rinfog)
        end if
      else if (self%nlast > 0 .and. job == mumps_job_factor) then
        st = cfe_mumps_job(self%h, job, int(self%n, c_int), int(size(self%irn), c_long_long), self%irn, self%jcn, &
                           self%a%val, int(self%nlast, c_int), self%schur_list, self%l22, 0_c_int, none, self%infog, &
                           self%info, self%rinfog)
      else
        st = cfe_mumps_job(self%h, job, int(self%n, c_int), int(size(self%irn), c_long_long), self%irn, self%jcn, &
                           self%a%val, int(self%nlast, c_int), self%schur_list, sdum, 0_c_int, none, self%infog, &
                           self%info, self%rinfog)
      end if
      if (st >= 0) return
      select case (st)
      case (-8, -9, -11, -12, -14, -15, -17, -20)
        if (job /= mumps_job_factor .or. attempt == max_retries) exit
        ! the workspace estimated by the analysis was too small
        self%margin = 2 * self%margin
        call cfe_mumps_get_control(self%h, icntl, cntl)
        icntl(14) = self%margin
        call cfe_mumps_set_control(self%h, icntl, cntl)
      case default
        exit
      end select
    end do
    call fatal('MUMPS ' // what // ' failed: ' // mumps_error(st, self%infog(2)) // ' (INFOG(1) = ' // &
               itoa(int(st)) // ', INFOG(2) = ' // itoa(int(self%infog(2))) // ')')
  end subroutine run

  !> Purpose: what an INFOG(1) < 0 of MUMPS means, in words.
  function mumps_error(st, info2) result(s)
    integer(c_int), intent(in) :: st, info2
    character(len=:), allocatable :: s
    select case (st)
    case (-10)
      s = 'the matrix is numerically singular'
    case (-13)
      s = 'memory could not be allocated (' // itoa(int(info2)) // ' more words on some rank): run on more ' // &
          'ranks or machines with more memory'
    case (-8, -9, -11, -12, -14, -15, -17, -20)
      s = 'its workspace stayed too small after ' // itoa(max_retries) // ' enlargements (ICNTL(14))'
    case (-19)
      s = 'the memory per rank it may use (CFE2D_MUMPS_MEMORY_MB, ICNTL(23)) is too small: raise it, or run on ' // &
          'more ranks'
    case (-16)
      s = 'the matrix has no equations, or too many'
    case (-51, -52)
      s = 'the problem is too large for 32-bit integers'
    case (-999)
      s = 'MUMPS is not in this build'
    case default
      s = 'see the MUMPS users'' guide for this error'
    end select
  end function mumps_error

  !> Purpose: the most memory (MB) MUMPS may take on a rank (ICNTL(23)),
  !> from the environment's CFE2D_MUMPS_MEMORY_MB (as a batch system's
  !> memory per process; 0 or unset: MUMPS' own estimate, no limit).
  integer(c_int) function memory_limit_mb()
    character(len=32) :: v
    integer :: st, mb
    memory_limit_mb = 0
    call get_environment_variable('CFE2D_MUMPS_MEMORY_MB', v, status=st)
    if (st /= 0) return
    read(v, *, iostat=st) mb
    if (st == 0 .and. mb > 0) memory_limit_mb = int(mb, c_int)
  end function memory_limit_mb

  !> An INFOG count of MUMPS: negative means millions.
  pure real(dp) function mumps_count(v)
    integer(c_int), intent(in) :: v
    if (v < 0) then
      mumps_count = -1.0e6_dp * real(v, dp)
    else
      mumps_count = real(v, dp)
    end if
  end function mumps_count

  subroutine factor(self, status, bad)
    class(mumps_backend_t), intent(inout) :: self
    integer, intent(out) :: status, bad
    call self%numeric(status, bad)
  end subroutine factor

  !> Purpose: numeric factorisation (analysis first where needed).
  !> status factor_singular with bad the first null
  !> pivot's equation (0 if MUMPS does not name it).
  subroutine numeric(self, status, bad)
    class(mumps_backend_t), intent(inout) :: self
    integer, intent(out) :: status, bad
    integer(c_int) :: piv(1), cnt
    status = factor_ok
    bad = 0
    if (self%n == 0) return
    call self%analyse()
    if (self%nlast > 0) then
      if (allocated(self%l22)) then
        if (size(self%l22, 1) /= self%nlast) deallocate(self%l22)
      end if
      if (.not. allocated(self%l22)) allocate(self%l22(self%nlast, self%nlast))
      self%l22 = 0.0_dp
    end if
    call self%run(mumps_job_factor, 'factorisation')
    self%factor_entries = mumps_count(self%infog(29))
    self%mem_rank_mb = real(self%infog(21), dp)
    self%mem_total_mb = real(self%infog(22), dp)
    cnt = cfe_mumps_null_pivots(self%h, piv, 1_c_int)
    if (cnt > 0) then
      status = factor_singular
      bad = int(piv(1))
    end if
  end subroutine numeric

  !> Purpose: b(n, nrhs) := K^-1 b (without a trailing block).
  subroutine solve(self, b)
    class(mumps_backend_t), intent(inout) :: self
    real(dp), intent(inout) :: b(:, :)
    if (self%n == 0 .or. size(b, 2) == 0) return
    if (self%nlast > 0) call fatal('MUMPS: a whole solve was asked of a factor with a Schur block')
    call self%run(mumps_job_solve, 'solve', b)
  end subroutine solve

  !> Purpose: x(1:n-nlast) := K11^-1 x(1:n-nlast), the Schur block's
  !> entries 0 (MUMPS' solve of the leading block, ICNTL(26)=0).
  subroutine interior_solve(self, x)
    class(mumps_backend_t), intent(inout) :: self
    real(dp), intent(inout) :: x(:)
    real(dp), allocatable :: b2(:, :)
    b2 = reshape(x, [self%n, 1])
    b2(self%n - self%nlast + 1:, 1) = 0.0_dp
    call self%run(mumps_job_solve, 'solve', b2)
    x = b2(:, 1)
    x(self%n - self%nlast + 1:) = 0.0_dp
  end subroutine interior_solve

  !> Purpose: factorisation with a trailing block of m = nlast equations
  !> for a condensed solve: MUMPS eliminates the leading equations and
  !> returns S0 (Schur complement); L22 = chol(S0 + diag(K22)).
  !> Arguments: status, bad as factor (leading pivots only); l22(m, m)
  !> returns L22 (lower triangle), diag22(m) K's trailing diagonal, both in
  !> equation order (trailing_order is the identity), so that S0 = l22
  !> l22^T - diag(diag22) as with cholmod_backend.
  subroutine condensed_factor(self, status, bad, l22, diag22)
    class(mumps_backend_t), intent(inout) :: self
    integer, intent(out) :: status, bad
    real(dp), intent(out) :: l22(:, :), diag22(:)
    integer :: i, j, k, nlead, info
    nlead = self%n - self%nlast
    call self%numeric(status, bad)
    if (status /= factor_ok) return
    ! MUMPS returns the lower triangle by rows: the upper one here
    do j = 1, self%nlast
      do i = j + 1, self%nlast
        self%l22(i, j) = self%l22(j, i)
        self%l22(j, i) = 0.0_dp
      end do
    end do
    do k = 1, self%nlast
      diag22(k) = diagonal_entry(self%a, nlead + k)
      self%l22(k, k) = self%l22(k, k) + diag22(k)
    end do
    call dense_factor(self%l22, info)
    if (info /= 0) then
      status = factor_singular
      bad = nlead + info
      return
    end if
    l22 = self%l22
  end subroutine condensed_factor

  pure real(dp) function diagonal_entry(a, j)
    type(csc_t), intent(in) :: a
    integer, intent(in) :: j
    integer :: k
    diagonal_entry = 0.0_dp
    do k = a%colptr(j), a%colptr(j + 1) - 1
      if (a%rowind(k) == j) diagonal_entry = a%val(k)
    end do
  end function diagonal_entry

  !> Purpose: tperm(k) = k: MUMPS keeps the Schur block in the order given.
  subroutine trailing_order(self, tperm)
    class(mumps_backend_t), intent(in) :: self
    integer, intent(out) :: tperm(:)
    integer :: k
    tperm = [(k, k = 1, self%nlast)]
  end subroutine trailing_order

  !> Purpose: b := [b1; L22^-1 (b2 - K21 K11^-1 b1)], the forward half.
  subroutine forward(self, b)
    class(mumps_backend_t), intent(inout) :: self
    real(dp), intent(inout) :: b(:)
    real(dp), allocatable :: x(:)
    integer :: col, k, nlead, r
    if (self%n == 0) return
    nlead = self%n - self%nlast
    x = b
    call self%interior_solve(x)
    ! b2 -= K21 x1: with the upper triangle, K21 is K12 (columns nlead+1..n) transposed
    if (self%a%upper) then
      do col = nlead + 1, self%n
        do k = self%a%colptr(col), self%a%colptr(col + 1) - 1
          r = self%a%rowind(k)
          if (r <= nlead) b(col) = b(col) - self%a%val(k) * x(r)
        end do
      end do
    else
      do col = 1, nlead
        do k = self%a%colptr(col), self%a%colptr(col + 1) - 1
          r = self%a%rowind(k)
          if (r > nlead) b(r) = b(r) - self%a%val(k) * x(col)
        end do
      end do
    end if
    if (self%nlast > 0) call dtrsv('L', 'N', 'N', self%nlast, self%l22, self%nlast, b(nlead + 1:), 1)
  end subroutine forward

  !> Purpose: b := [K11^-1 (b1 - K12 x2); x2] with x2 = L22^-T b2, the
  !> backward half.
  subroutine backward(self, b)
    class(mumps_backend_t), intent(inout) :: self
    real(dp), intent(inout) :: b(:)
    real(dp), allocatable :: x2(:)
    integer :: col, k, nlead, r
    if (self%n == 0) return
    nlead = self%n - self%nlast
    x2 = b(nlead + 1:)
    if (self%nlast > 0) call dtrsv('L', 'T', 'N', self%nlast, self%l22, self%nlast, x2, 1)
    do col = nlead + 1, self%n
      do k = self%a%colptr(col), self%a%colptr(col + 1) - 1
        r = self%a%rowind(k)
        if (r <= nlead) b(r) = b(r) - self%a%val(k) * x2(col - nlead)
      end do
    end do
    call self%interior_solve(b)
    b(nlead + 1:) = x2
  end subroutine backward

  pure subroutine matvec(self, x, y)
    class(mumps_backend_t), intent(in) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: y(:)
    call csc_matvec(self%a, x, y)
  end subroutine matvec

  function describe(self) result(d)
    class(mumps_backend_t), intent(in) :: self
    character(len=:), allocatable :: d
    d = 'factor entries ' // rtoa(self%factor_entries, 6) // ', ' // itoa(self%ranks) // ' MPI rank'
    if (self%ranks /= 1) d = d // 's'
    if (self%mem_total_mb > 0.0_dp) d = d // ', MUMPS memory ' // itoa(nint(self%mem_rank_mb)) // &
      ' MB on the largest rank, ' // itoa(nint(self%mem_total_mb)) // ' MB in all'
    if (self%sym == sym_general) d = d // ', LU (unsymmetric)'
  end function describe

  integer(8) function stored_entries(self)
    class(mumps_backend_t), intent(in) :: self
    stored_entries = size(self%a%val, kind=8)
  end function stored_entries

  subroutine free(self)
    class(mumps_backend_t), intent(inout) :: self
    type(csc_t) :: empty
    if (self%h >= 0) call cfe_mumps_free(self%h)
    self%h = -1
    self%analysed = .false.
    self%a = empty
    self%n = 0
    if (allocated(self%irn)) deallocate(self%irn, self%jcn)
    if (allocated(self%l22)) deallocate(self%l22)
    if (allocated(self%xeq)) deallocate(self%xeq, self%eqs)
  end subroutine free
end module mumps_backend
