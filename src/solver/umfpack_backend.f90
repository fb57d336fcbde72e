!> UMFPACK's LU as a solver backend: the full pattern in compressed
!> columns, ordered by AMD or METIS, analysed once per pattern. UMFPACK
!> factorises whatever it is given, so a singular matrix is recognised here
!> from the factor itself: a diagonal entry of U that is only round-off of
!> its (scaled) column.
module umfpack_backend
  use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr, c_null_ptr, c_associated, c_loc
  use kinds, only: dp
  use strings, only: itoa, rtoa
  use messages, only: fatal
  use blas_info, only: set_solver_threads
  use solver_codes, only: order_metis
  use sparse_matrix, only: csc_t, csc_build, csc_zero, csc_add_element, csc_matvec, csc_add_upper
  use umfpack_binding, only: umfpack_di_defaults, umfpack_di_symbolic, umfpack_di_numeric, umfpack_di_solve, &
                             umfpack_di_free_symbolic, umfpack_di_free_numeric, umfpack_di_get_numeric, &
                             umfpack_control, umfpack_info, umfpack_ok, umfpack_warning_singular, &
                             umfpack_sys_a, umfpack_ordering, umfpack_ordering_amd, umfpack_ordering_metis, &
                             umfpack_lnz, umfpack_unz, umfpack_prl
  use solver_backend, only: solver_backend_t, factor_ok, factor_singular, pivot_ratio_min
  implicit none
  private
  public :: umfpack_backend_t

  type, extends(solver_backend_t) :: umfpack_backend_t
    type(csc_t) :: a                                 ! both triangles
    integer(c_int), allocatable :: ap0(:), ai0(:)    ! 0-based copies for C
    type(c_ptr) :: symbolic = c_null_ptr, numeric = c_null_ptr
    real(c_double) :: control(umfpack_control) = 0.0_c_double, info(umfpack_info) = 0.0_c_double
    logical :: analysed = .false.
    real(dp) :: pivot_ratio = 1.0_dp                 ! smallest, last factorisation
  contains
    procedure :: setup, zero, add, analyse, factor, solve, matvec, describe, stored_entries, free
    procedure :: add_upper
  end type umfpack_backend_t

contains

  subroutine setup(self, n, ordering, xeq, eqs)
    class(umfpack_backend_t), intent(inout) :: self
    integer, intent(in) :: n, ordering, xeq(:), eqs(:)
    call self%free()
    call self%keep_structure(n, ordering, xeq, eqs)
    call csc_build(self%a, n, xeq, eqs, upper=.false.)
    self%ap0 = int(self%a%colptr - 1, c_int)
    self%ai0 = int(self%a%rowind - 1, c_int)
  end subroutine setup

  subroutine zero(self)
    class(umfpack_backend_t), intent(inout) :: self
    call csc_zero(self%a)
  end subroutine zero

  subroutine add(self, e, ke)
    class(umfpack_backend_t), intent(inout) :: self
    integer, intent(in) :: e
    real(dp), intent(in) :: ke(:, :)
    call csc_add_element(self%a, e, self%eqs(self%xeq(e):self%xeq(e + 1) - 1), ke)
  end subroutine add

  !> Adds a symmetric matrix assembled as its upper triangle on the same
  !> equations (what a symmetric backend hands over when it gives up).
  subroutine add_upper(self, upper)
    class(umfpack_backend_t), intent(inout) :: self
    type(csc_t), intent(in) :: upper
    call csc_add_upper(self%a, upper)
  end subroutine add_upper

  !> Ordering and symbolic factorisation, once per pattern.
  subroutine analyse(self)
    class(umfpack_backend_t), intent(inout) :: self
    integer(c_int) :: st
    if (self%analysed) return
    self%analysed = .true.
    self%factor_entries = 0.0_dp
    if (self%n == 0) return
    call set_solver_threads()
    call umfpack_di_defaults(self%control)
    self%control(umfpack_prl) = 0.0_c_double
    self%control(umfpack_ordering) = merge(umfpack_ordering_metis, umfpack_ordering_amd, &
                                           self%ordering == order_metis)
    if (c_associated(self%symbolic)) call umfpack_di_free_symbolic(self%symbolic)
    st = umfpack_di_symbolic(int(self%n, c_int), int(self%n, c_int), self%ap0, self%ai0, self%a%val, &
                             self%symbolic, self%control, self%info)
    if (st /= umfpack_ok) call fatal('UMFPACK symbolic analysis failed, status ' // itoa(int(st)))
  end subroutine analyse

  subroutine factor(self, status, bad)
    class(umfpack_backend_t), intent(inout) :: self
    integer, intent(out) :: status, bad
    integer(c_int) :: st
    status = factor_ok
    bad = 0
    call self%analyse()
    self%pivot_ratio = 1.0_dp
    if (self%n == 0) return
    if (c_associated(self%numeric)) call umfpack_di_free_numeric(self%numeric)
    st = umfpack_di_numeric(self%ap0, self%ai0, self%a%val, self%symbolic, self%numeric, self%control, self%info)
    if (st /= umfpack_ok .and. st /= umfpack_warning_singular) &
      call fatal('UMFPACK numeric factorisation failed, status ' // itoa(int(st)))
    self%factor_entries = self%info(umfpack_lnz) + self%info(umfpack_unz)
    call smallest_pivot(self, self%pivot_ratio, bad)
    if (self%pivot_ratio < pivot_ratio_min) then
      status = factor_singular
    else
      bad = 0
    end if
  end subroutine factor

  !> The smallest |U(k,k)| relative to the largest entry of column Q(k)
  !> of the row-scaled matrix, and that column (the equation, 1-based).
  subroutine smallest_pivot(self, ratio, col)
    class(umfpack_backend_t), intent(in) :: self
    real(dp), intent(out) :: ratio
    integer, intent(out) :: col
    integer(c_int), allocatable, target :: q(:)
    real(c_double), allocatable, target :: dx(:), rs(:)
    real(dp), allocatable :: scale(:)
    integer(c_int) :: st, do_recip
    integer :: k, j, p
    real(dp) :: colmax, r
    allocate(q(self%n), dx(self%n), rs(self%n))
    st = umfpack_di_get_numeric(c_null_ptr, c_null_ptr, c_null_ptr, c_null_ptr, c_null_ptr, c_null_ptr, &
                                c_null_ptr, c_loc(q), c_loc(dx), do_recip, c_loc(rs), self%numeric)
    if (st /= umfpack_ok) call fatal('UMFPACK could not return its factor, status ' // itoa(int(st)))
    if (do_recip == 1) then
      scale = rs
    else
      scale = 1.0_dp / rs
    end if
    ratio = huge(1.0_dp)
    col = 0
    do k = 1, self%n
      j = int(q(k)) + 1
      colmax = 0.0_dp
      do p = self%a%colptr(j), self%a%colptr(j + 1) - 1
        colmax = max(colmax, abs(self%a%val(p)) * scale(self%a%rowind(p)))
      end do
      r = 0.0_dp
      if (colmax > 0.0_dp) r = abs(dx(k)) / colmax
      if (r < ratio) then
        ratio = r
        col = j
      end if
    end do
  end subroutine smallest_pivot

  !> UMFPACK solves one right-hand side per call (with its iterative
  !> refinement); the columns are done in turn.
  subroutine solve(self, b)
    class(umfpack_backend_t), intent(inout) :: self
    real(dp), intent(inout) :: b(:, :)
    real(c_double), allocatable :: x(:)
    integer(c_int) :: st
    integer :: j
    if (self%n == 0) return
    allocate(x(self%n))
    do j = 1, size(b, 2)
      st = umfpack_di_solve(umfpack_sys_a, self%ap0, self%ai0, self%a%val, x, b(:, j), self%numeric, &
                            self%control, self%info)
      if (st /= umfpack_ok) call fatal('UMFPACK solve failed, status ' // itoa(int(st)))
      b(:, j) = x
    end do
  end subroutine solve

  pure subroutine matvec(self, x, y)
    class(umfpack_backend_t), intent(in) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: y(:)
    call csc_matvec(self%a, x, y)
  end subroutine matvec

  function describe(self) result(d)
    class(umfpack_backend_t), intent(in) :: self
    character(len=:), allocatable :: d
    d = 'factor entries ' // rtoa(self%factor_entries, 6)
  end function describe

  integer(8) function stored_entries(self)
    class(umfpack_backend_t), intent(in) :: self
    stored_entries = size(self%a%val, kind=8)
  end function stored_entries

  subroutine free(self)
    class(umfpack_backend_t), intent(inout) :: self
    type(csc_t) :: empty
    if (c_associated(self%numeric)) call umfpack_di_free_numeric(self%numeric)
    if (c_associated(self%symbolic)) call umfpack_di_free_symbolic(self%symbolic)
    self%numeric = c_null_ptr
    self%symbolic = c_null_ptr
    self%analysed = .false.
    self%a = empty
    self%n = 0
    if (allocated(self%xeq)) deallocate(self%xeq, self%eqs)
  end subroutine free
end module umfpack_backend
