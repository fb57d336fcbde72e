!> CHOLMOD's supernodal LL' as a solver backend: the upper triangle in
!> compressed columns, ordered by AMD or METIS, analysed once per pattern.
!> A pivot that is not positive is reported as factor_not_posdef (the
!> caller may try an LU instead); a positive pivot that is only round-off
!> of its diagonal entry is a singular matrix.
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
                             cfe_cholmod_solve, cholmod_shim_ok, cholmod_shim_not_posdef
  use solver_backend, only: solver_backend_t, factor_ok, factor_singular, factor_not_posdef, pivot_ratio_min
  implicit none
  private
  public :: cholmod_backend_t

  type, extends(solver_backend_t) :: cholmod_backend_t
    type(csc_t) :: a                                 ! upper triangle
    integer(c_int), allocatable :: ap0(:), ai0(:)    ! 0-based copies for C
    type(c_ptr) :: handle = c_null_ptr               ! workspace and factor
    logical :: analysed = .false.
    real(dp) :: pivot_ratio = 1.0_dp                 ! smallest, last factorisation
  contains
    procedure :: setup, zero, add, analyse, factor, solve, matvec, describe, stored_entries, free
  end type cholmod_backend_t

contains

  subroutine setup(self, n, ordering, xeq, eqs)
    class(cholmod_backend_t), intent(inout) :: self
    integer, intent(in) :: n, ordering, xeq(:), eqs(:)
    call self%free()
    call self%keep_structure(n, ordering, xeq, eqs)
    call csc_build(self%a, n, xeq, eqs, upper=.true.)
    self%ap0 = int(self%a%colptr - 1, c_int)
    self%ai0 = int(self%a%rowind - 1, c_int)
  end subroutine setup

  subroutine zero(self)
    class(cholmod_backend_t), intent(inout) :: self
    call csc_zero(self%a)
  end subroutine zero

  subroutine add(self, e, ke)
    class(cholmod_backend_t), intent(inout) :: self
    integer, intent(in) :: e
    real(dp), intent(in) :: ke(:, :)
    call csc_add_element(self%a, e, self%eqs(self%xeq(e):self%xeq(e + 1) - 1), ke)
  end subroutine add

  !> Ordering and symbolic factorisation, once per pattern. CHOLMOD
  !> orders with AMD itself; a METIS order is computed here and given.
  subroutine analyse(self)
    class(cholmod_backend_t), intent(inout) :: self
    integer(c_int), allocatable, target :: perm(:)
    type(c_ptr) :: given
    real(c_double) :: lnz
    integer(c_int) :: st
    if (self%analysed) return
    self%analysed = .true.
    self%factor_entries = 0.0_dp
    if (self%n == 0) return
    call set_solver_threads()
    if (.not. c_associated(self%handle)) self%handle = cfe_cholmod_start()
    if (.not. c_associated(self%handle)) call fatal('CHOLMOD could not start (out of memory?)')
    given = c_null_ptr
    if (self%ordering == order_metis) then
      call metis_order(self%n, self%a%colptr, self%a%rowind, perm)
      given = c_loc(perm)
    end if
    st = cfe_cholmod_analyse(self%handle, int(self%n, c_int), self%ap0, self%ai0, self%a%val, given, lnz)
    if (st /= cholmod_shim_ok) call fatal('CHOLMOD analysis failed, status ' // itoa(int(st)))
    self%factor_entries = lnz
  end subroutine analyse

  subroutine factor(self, status, bad)
    class(cholmod_backend_t), intent(inout) :: self
    integer, intent(out) :: status, bad
    integer(c_int) :: st, col
    real(c_double) :: ratio
    status = factor_ok
    bad = 0
    call self%analyse()
    self%pivot_ratio = 1.0_dp
    if (self%n == 0) return
    st = cfe_cholmod_factor(self%handle, int(self%n, c_int), self%ap0, self%ai0, self%a%val, ratio, col)
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
  end subroutine factor

  subroutine solve(self, b)
    class(cholmod_backend_t), intent(inout) :: self
    real(dp), intent(inout) :: b(:, :)
    integer(c_int) :: st
    if (self%n == 0 .or. size(b, 2) == 0) return
    st = cfe_cholmod_solve(self%handle, int(self%n, c_int), int(size(b, 2), c_int), b)
    if (st /= cholmod_shim_ok) call fatal('CHOLMOD solve failed, status ' // itoa(int(st)))
  end subroutine solve

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
