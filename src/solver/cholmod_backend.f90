!> CHOLMOD's supernodal LL' as a solver backend: the upper triangle in
!> compressed columns, ordered by AMD or METIS, analysed once per pattern.
!> A pivot that is not positive is reported as factor_not_posdef (the
!> caller may try an LU instead); a positive pivot that is only round-off
!> of its diagonal entry is a singular matrix.
!> With a trailing block (nlast > 0) the ordering keeps those equations
!> last (CAMD, or METIS on the others), and the backend also offers what a
!> condensed solve needs: the trailing block of L, and the forward and
!> backward halves of a solve in the factor's order.
module cholmod_backend
  use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr, c_null_ptr, c_associated, c_loc
  use kinds, only: dp
  use strings, only: itoa, rtoa
  use messages, only: fatal
  use blas_info, only: set_solver_threads
  use solver_codes, only: order_metis
  use sparse_matrix, only: csc_t, csc_build, csc_zero, csc_add_element, csc_matvec
  use ordering, only: metis_order
  use cholmod_binding, only: cfe_cholmod_start, cfe_cholmod_finish, cfe_cholmod_analyse, cfe_cholmod_factor, &
                             cfe_cholmod_solve, cholmod_shim_ok, cholmod_shim_not_posdef, cfe_cholmod_analyse_last, &
                             cfe_cholmod_trailing_order, cfe_cholmod_trailing_block, cfe_cholmod_forward, &
                             cfe_cholmod_backward
  use solver_backend, only: solver_backend_t, factor_ok, factor_singular, factor_not_posdef, pivot_ratio_min
  implicit none
  private
  public :: cholmod_backend_t

  type, extends(solver_backend_t) :: cholmod_backend_t
    type(csc_t) :: a                                 ! upper triangle
    type(c_ptr) :: handle = c_null_ptr               ! workspace and factor
    logical :: analysed = .false.
    real(dp) :: pivot_ratio = 1.0_dp                 ! smallest, last factorisation
  contains
    procedure :: setup, zero, add, analyse, factor, solve, matvec, describe, stored_entries, free
    procedure :: condensed_factor, forward, backward, trailing_order
    procedure, private :: factor_judging, c_indices
  end type cholmod_backend_t

contains

  subroutine setup(self, n, ordering, xeq, eqs)
    class(cholmod_backend_t), intent(inout) :: self
    integer, intent(in) :: n, ordering, xeq(:), eqs(:)
    call self%free()
    call self%keep_structure(n, ordering, xeq, eqs)
    ! with a trailing block the matrix is assembled once (condensed solve);
    ! without one, the value map is made once the matrix is assembled again
    call csc_build(self%a, n, xeq, eqs, upper=.true., with_map=self%nlast == 0, map_later=.true.)
  end subroutine setup

  !> Purpose: the pattern's indices in CHOLMOD's convention (0-based,
  !> by = -1) for the length of one call into the shim, and back
  !> (1-based, by = +1) right after it: CHOLMOD reads the backend's own
  !> arrays, so no 0-based copy is kept beside them (nnz + n + 1 integers:
  !> 2.2 MB on the flagship, 42 MB at 1e6 equations).
  subroutine c_indices(self, by)
    class(cholmod_backend_t), intent(inout) :: self
    integer, intent(in) :: by
    self%a%colptr = self%a%colptr + by
    self%a%rowind = self%a%rowind + by
  end subroutine c_indices

  subroutine zero(self)
    class(cholmod_backend_t), intent(inout) :: self
    call csc_zero(self%a, self%xeq, self%eqs)
  end subroutine zero

  subroutine add(self, e, ke)
    class(cholmod_backend_t), intent(inout) :: self
    integer, intent(in) :: e
    real(dp), intent(in) :: ke(:, :)
    call csc_add_element(self%a, e, self%eqs(self%xeq(e):self%xeq(e + 1) - 1), ke)
  end subroutine add

  !> Ordering and symbolic factorisation, once per pattern. CHOLMOD orders
  !> with AMD itself (CAMD with a trailing block); a METIS order is computed
  !> here (of the leading equations, with a trailing block) and given.
  subroutine analyse(self)
    class(cholmod_backend_t), intent(inout) :: self
    integer(c_int), allocatable, target :: perm(:)
    type(c_ptr) :: given
    real(c_double) :: lnz, flops
    integer(c_int) :: st
    integer :: nlead, k
    if (self%analysed) return
    self%analysed = .true.
    self%factor_entries = 0.0_dp
    if (self%n == 0) return
    call set_solver_threads()
    if (.not. c_associated(self%handle)) self%handle = cfe_cholmod_start()
    if (.not. c_associated(self%handle)) call fatal('CHOLMOD could not start (out of memory?)')
    given = c_null_ptr
    nlead = self%n - self%nlast
    if (self%ordering == order_metis .and. nlead > 0) then
      ! the leading block is the first nlead columns of the upper triangle
      call metis_order(nlead, self%a%colptr(1:nlead + 1), self%a%rowind(1:self%a%colptr(nlead + 1) - 1), perm)
      perm = [perm, [(int(k, c_int), k = nlead, self%n - 1)]]
      given = c_loc(perm)
    end if
    flops = 0.0_dp
    call self%c_indices(-1)
    if (self%nlast > 0) then
      st = cfe_cholmod_analyse_last(self%handle, int(self%n, c_int), self%a%colptr, self%a%rowind, self%a%val, &
                                    int(self%nlast, c_int), given, lnz, flops)
    else
      st = cfe_cholmod_analyse(self%handle, int(self%n, c_int), self%a%colptr, self%a%rowind, self%a%val, given, lnz)
    end if
    call self%c_indices(+1)
    if (st /= cholmod_shim_ok) call fatal('CHOLMOD analysis failed, status ' // itoa(int(st)))
    self%factor_entries = lnz
    self%factor_flops = flops
  end subroutine analyse

  subroutine factor(self, status, bad)
    class(cholmod_backend_t), intent(inout) :: self
    integer, intent(out) :: status, bad
    call self%factor_judging(0, status, bad)
  end subroutine factor

  !> Numeric factorisation, the last nskip pivots not judged singular.
  subroutine factor_judging(self, nskip, status, bad)
    class(cholmod_backend_t), intent(inout) :: self
    integer, intent(in) :: nskip
    integer, intent(out) :: status, bad
    integer(c_int) :: st, col
    real(c_double) :: ratio
    status = factor_ok
    bad = 0
    call self%analyse()
    self%pivot_ratio = 1.0_dp
    if (self%n == 0) return
    call self%c_indices(-1)
    st = cfe_cholmod_factor(self%handle, int(self%n, c_int), self%a%colptr, self%a%rowind, self%a%val, &
                            int(nskip, c_int), ratio, col)
    call self%c_indices(+1)
    if (st == cholmod_shim_not_posdef) then
      status = factor_not_posdef
      bad = int(col) + 1
    else if (st /= cholmod_shim_ok) then
      call fatal('CHOLMOD factorisation failed, status ' // itoa(int(st)))
    else
      self%pivot_ratio = ratio
      if (ratio < pivot_ratio_min) then
        status = factor_singular
        bad = int(col) + 1
      end if
    end if
  end subroutine factor_judging

  subroutine solve(self, b)
    class(cholmod_backend_t), intent(inout) :: self
    real(dp), intent(inout) :: b(:, :)
    integer(c_int) :: st
    if (self%n == 0 .or. size(b, 2) == 0) return
    st = cfe_cholmod_solve(self%handle, int(self%n, c_int), int(size(b, 2), c_int), b)
    if (st /= cholmod_shim_ok) call fatal('CHOLMOD solve failed, status ' // itoa(int(st)))
  end subroutine solve

  !> Purpose: numeric factorisation with a trailing block (nlast = m > 0)
  !> for a condensed solve. The trailing block's diagonal is doubled while
  !> factoring, so that its pivots stay positive even when the Schur
  !> complement of the leading block is singular (a body that only the
  !> trailing equations could hold); status and bad judge the leading
  !> pivots only, as factor does.
  !> Arguments: l22(m, m) returns the trailing block of L (lower triangle)
  !> and diag22(m) the matrix's trailing diagonal, both in the factor's
  !> trailing order (trailing_order), so that the Schur complement of the
  !> leading block is l22 l22^T - diag(diag22).
  subroutine condensed_factor(self, status, bad, l22, diag22)
    class(cholmod_backend_t), intent(inout) :: self
    integer, intent(out) :: status, bad
    real(dp), intent(out) :: l22(:, :), diag22(:)
    integer :: j, k, nlead
    integer :: tperm(self%nlast)
    real(dp) :: d(self%nlast)
    integer(c_int) :: st
    nlead = self%n - self%nlast
    do k = 1, self%nlast
      j = self%a%colptr(nlead + k + 1) - 1            ! sorted columns: the diagonal is last
      d(k) = self%a%val(j)
      self%a%val(j) = 2.0_dp * self%a%val(j)
    end do
    call self%factor_judging(self%nlast, status, bad)
    do k = 1, self%nlast
      self%a%val(self%a%colptr(nlead + k + 1) - 1) = d(k)
    end do
    if (status == factor_not_posdef .and. bad <= nlead) status = factor_singular
    if (status /= factor_ok) return
    st = cfe_cholmod_trailing_block(self%handle, int(self%nlast, c_int), l22)
    if (st /= cholmod_shim_ok) call fatal('CHOLMOD: the trailing block of the factor cannot be read')
    call self%trailing_order(tperm)
    diag22 = d(tperm)
  end subroutine condensed_factor

  !> Purpose: tperm(k) = the trailing equation (1..nlast) at trailing
  !> position k of the factor.
  subroutine trailing_order(self, tperm)
    class(cholmod_backend_t), intent(in) :: self
    integer, intent(out) :: tperm(:)
    integer(c_int) :: t(self%nlast)
    call cfe_cholmod_trailing_order(self%handle, t)
    tperm = int(t) + 1
  end subroutine trailing_order

  !> Purpose: b := L \ (P b): the forward half of a solve, in the factor's
  !> order.
  subroutine forward(self, b)
    class(cholmod_backend_t), intent(inout) :: self
    real(dp), intent(inout) :: b(:)
    if (self%n == 0) return
    if (cfe_cholmod_forward(self%handle, int(self%n, c_int), b) /= cholmod_shim_ok) &
      call fatal('CHOLMOD forward solve failed')
  end subroutine forward

  !> Purpose: b := P^T (L^T \ b): the backward half of a solve.
  subroutine backward(self, b)
    class(cholmod_backend_t), intent(inout) :: self
    real(dp), intent(inout) :: b(:)
    if (self%n == 0) return
    if (cfe_cholmod_backward(self%handle, int(self%n, c_int), b) /= cholmod_shim_ok) &
      call fatal('CHOLMOD backward solve failed')
  end subroutine backward

  pure subroutine matvec(self, x, y)
    class(cholmod_backend_t), intent(in) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: y(:)
    call csc_matvec(self%a, x, y)
  end subroutine matvec

  function describe(self) result(d)
    class(cholmod_backend_t), intent(in) :: self
    character(len=:), allocatable :: d
    d = 'factor entries ' // rtoa(self%factor_entries, 6)
  end function describe

  integer(8) function stored_entries(self)
    class(cholmod_backend_t), intent(in) :: self
    stored_entries = size(self%a%val, kind=8)
  end function stored_entries

  subroutine free(self)
    class(cholmod_backend_t), intent(inout) :: self
    type(csc_t) :: empty
    if (c_associated(self%handle)) call cfe_cholmod_finish(self%handle)
    self%handle = c_null_ptr
    self%analysed = .false.
    self%a = empty
    self%n = 0
    if (allocated(self%xeq)) deallocate(self%xeq, self%eqs)
  end subroutine free
end module cholmod_backend
