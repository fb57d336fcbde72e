!> One interface over the direct solvers of the global equations, each a
!> backend (module solver_backend): the skyline LDL^T written here,
!> CHOLMOD (default; the penalty-contact stiffness is symmetric positive
!> definite), UMFPACK and MUMPS (over the MPI ranks of the run). Symbolic analysis is done once per pattern and
!> reused; only numeric factorisations repeat. If CHOLMOD finds the matrix
!> not positive definite the system falls back to UMFPACK and says so.
!> Adding a backend: a module extending solver_backend_t and one case in
!> new_backend.
!> A condensed solve (sys_condensed_factor, sys_forward, sys_backward,
!> sys_trailing_order) needs a backend that keeps a trailing block of
!> equations last and hands out that block of its factor: CHOLMOD, and
!> MUMPS through its Schur complement (sys_can_condense says whether the
!> system's backend can).
module linear_solver
  use kinds, only: dp
  use strings, only: itoa
  use messages, only: fatal
  use solver_codes, only: solver_skyline, solver_cholmod, solver_umfpack, solver_mumps, order_natural, order_rcm, order_amd, &
                          order_metis, solver_name, ordering_name
  use solver_backend, only: solver_backend_t, factor_ok, factor_singular, factor_fallback, factor_not_posdef, &
                            pivot_ratio_min
  use skyline_backend, only: skyline_backend_t
  use cholmod_backend, only: cholmod_backend_t
  use umfpack_backend, only: umfpack_backend_t
  use mumps_backend, only: mumps_backend_t
  implicit none
  private
  public :: linear_system_t, solver_skyline, solver_cholmod, solver_umfpack, solver_mumps, order_natural, &
            order_rcm, order_amd, order_metis, sys_setup, sys_zero, sys_add, sys_analyse, &
            sys_factor, sys_solve, sys_matvec, sys_free, sys_describe, sys_neq, sys_stored_entries, &
            solver_name, ordering_name, factor_ok, factor_singular, factor_fallback, &
            factor_not_posdef, sys_condensed_factor, sys_forward, sys_backward, sys_trailing_order, &
            sys_factor_flops, sys_nlast, pivot_ratio_min

  type :: linear_system_t
    integer :: kind = solver_cholmod                 ! the backend in use (solver_codes)
    integer :: ordering = order_amd
    integer :: n = 0
    real(dp) :: factor_entries = 0.0_dp              ! nnz(L) (+ nnz(U)) or profile
    character(len=:), allocatable :: note            ! fallback message, if any
    class(solver_backend_t), allocatable, private :: b   ! the solver in use
  end type linear_system_t

  !> Replaces b(n) or the columns of b(n, nrhs) by the solutions.
  interface sys_solve
    module procedure sys_solve_one, sys_solve_many
  end interface sys_solve

contains

  !> A backend of the given kind, not yet set up.
  subroutine new_backend(kind, b)
    integer, intent(in) :: kind
    class(solver_backend_t), allocatable, intent(out) :: b
    select case (kind)
    case (solver_skyline); allocate(skyline_backend_t :: b)
    case (solver_umfpack); allocate(umfpack_backend_t :: b)
    case (solver_mumps); allocate(mumps_backend_t :: b)
    case default; allocate(cholmod_backend_t :: b)
    end select
  end subroutine new_backend

  !> Structure of the system of n equations from the element equation
  !> lists eqs(xeq(e):xeq(e+1)-1) (entries <= 0: prescribed dofs).
  !> kind: solver_skyline|cholmod|umfpack; ordering: order_* (the
  !> skyline takes the equations in the order given); nlast (optional):
  !> the last nlast equations are to stay last in the factor (a condensed
  !> solve; CHOLMOD keeps them last, MUMPS makes them its Schur block).
  subroutine sys_setup(s, kind, ordering, n, xeq, eqs, nlast)
    type(linear_system_t), intent(inout) :: s
    integer, intent(in) :: kind, ordering, n, xeq(:), eqs(:)
    integer, intent(in), optional :: nlast
    call sys_free(s)
    s%kind = kind
    s%ordering = ordering
    s%n = n
    if (allocated(s%note)) deallocate(s%note)
    call new_backend(kind, s%b)
    s%b%nlast = 0
    if (present(nlast)) s%b%nlast = max(0, min(nlast, n))
    call s%b%setup(n, ordering, xeq, eqs)
    s%factor_entries = s%b%factor_entries
  end subroutine sys_setup

  !> Number of equations.
  pure integer function sys_neq(s)
    type(linear_system_t), intent(in) :: s
    sys_neq = s%n
  end function sys_neq

  !> Clears the matrix, keeping its structure.
  subroutine sys_zero(s)
    type(linear_system_t), intent(inout) :: s
    call s%b%zero()
  end subroutine sys_zero

  !> Adds the matrix ke of element e (equation list as given to sys_setup).
  subroutine sys_add(s, e, ke)
    type(linear_system_t), intent(inout) :: s
    integer, intent(in) :: e
    real(dp), intent(in) :: ke(:, :)
    call s%b%add(e, ke)
  end subroutine sys_add

  !> y = K x with the assembled matrix (for the skyline: not yet factored).
  pure subroutine sys_matvec(s, x, y)
    type(linear_system_t), intent(in) :: s
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: y(:)
    call s%b%matvec(x, y)
  end subroutine sys_matvec

  !> Ordering and symbolic analysis (done by sys_factor when needed;
  !> separate for timing).
  subroutine sys_analyse(s)
    type(linear_system_t), intent(inout) :: s
    call s%b%analyse()
    s%factor_entries = s%b%factor_entries
  end subroutine sys_analyse

  !> Numeric factorisation (symbolic analysis first if the pattern is new).
  !> status: factor_ok; factor_singular, bad = the equation (1-based, the
  !> caller's numbering) whose pivot vanished; or factor_fallback: CHOLMOD
  !> found the matrix not positive definite, UMFPACK factorised it and
  !> s%note says so.
  subroutine sys_factor(s, status, bad)
    type(linear_system_t), intent(inout) :: s
    integer, intent(out) :: status, bad
    call s%b%factor(status, bad)
    if (status == factor_not_posdef) then
      s%note = solver_name(s%kind) // ': the matrix is not positive definite (at equation ' // itoa(bad) // &
               '); falling back to UMFPACK'
      call fall_back_to_umfpack(s)
      call s%b%factor(status, bad)
      if (status == factor_ok) status = factor_fallback
    end if
    s%factor_entries = s%b%factor_entries
  end subroutine sys_factor

  !> An UMFPACK backend over the same equations takes the assembled
  !> matrix; the backend that gave up is freed.
  subroutine fall_back_to_umfpack(s)
    type(linear_system_t), intent(inout) :: s
    type(umfpack_backend_t), allocatable :: lu
    allocate(lu)
    call lu%setup(s%b%n, s%b%ordering, s%b%xeq, s%b%eqs)
    call lu%zero()
    select type (old => s%b)
    type is (cholmod_backend_t)
      call lu%add_upper(old%a)
    class default
      call fatal(solver_name(s%kind) // ' cannot hand its matrix to UMFPACK')
    end select
    call s%b%free()
    deallocate(s%b)
    call move_alloc(lu, s%b)
    s%kind = solver_umfpack
  end subroutine fall_back_to_umfpack

  subroutine sys_solve_one(s, b)
    type(linear_system_t), intent(inout) :: s
    real(dp), intent(inout) :: b(:)
    real(dp), allocatable :: b2(:, :)
    b2 = reshape(b, [size(b), 1])
    call s%b%solve(b2)
    b = b2(:, 1)
  end subroutine sys_solve_one

  subroutine sys_solve_many(s, b)
    type(linear_system_t), intent(inout) :: s
    real(dp), intent(inout) :: b(:, :)
    call s%b%solve(b)
  end subroutine sys_solve_many

  !> One line for the listing: solver, ordering and size of the factor.
  function sys_describe(s) result(d)
    type(linear_system_t), intent(in) :: s
    character(len=:), allocatable :: d
    d = solver_name(s%kind) // ', ordering ' // ordering_name(s%ordering)
    if (sys_nlast(s) > 0 .and. sys_can_condense(s)) then
      if (s%kind == solver_mumps) then
        d = d // ' (Schur complement on the last ' // itoa(sys_nlast(s)) // ' equations)'
      else if (s%ordering == order_metis) then
        d = d // ' (the last ' // itoa(sys_nlast(s)) // ' equations kept last)'
      else
        d = d // ' (CAMD: the last ' // itoa(sys_nlast(s)) // ' equations kept last)'
      end if
    end if
    if (allocated(s%b)) d = d // ', ' // s%b%describe()
  end function sys_describe

  !> Entries of the assembled matrix as stored (for the skyline: its profile).
  integer(8) function sys_stored_entries(s)
    type(linear_system_t), intent(in) :: s
    sys_stored_entries = s%b%stored_entries()
  end function sys_stored_entries

  !> Can the system's backend factor with a trailing block for a condensed
  !> solve?
  logical function sys_can_condense(s)
    type(linear_system_t), intent(in) :: s
    sys_can_condense = .false.
    if (.not. allocated(s%b)) return
    select type (b => s%b)
    type is (cholmod_backend_t)
      sys_can_condense = .true.
    type is (mumps_backend_t)
      sys_can_condense = .true.
    end select
  end function sys_can_condense

  !> Equations of the trailing block (0 without one).
  pure integer function sys_nlast(s)
    type(linear_system_t), intent(in) :: s
    sys_nlast = 0
    if (allocated(s%b)) sys_nlast = s%b%nlast
  end function sys_nlast

  !> Floating-point operations of one numeric factorisation (after the
  !> analysis; 0 where the backend does not say).
  real(dp) function sys_factor_flops(s)
    type(linear_system_t), intent(inout) :: s
    call sys_analyse(s)
    sys_factor_flops = s%b%factor_flops
  end function sys_factor_flops

  !> Purpose: factors the assembled matrix for a condensed solve: status
  !> and bad as sys_factor, judged on the leading equations; l22(m, m) the
  !> trailing block of the factor and diag22(m) the matrix's trailing
  !> diagonal, in the factor's trailing order (sys_trailing_order). The
  !> Schur complement of the leading equations is l22 l22^T - diag(diag22)
  !> (cholmod_backend says why). No fall-back to another solver.
  subroutine sys_condensed_factor(s, status, bad, l22, diag22)
    type(linear_system_t), intent(inout) :: s
    integer, intent(out) :: status, bad
    real(dp), intent(out) :: l22(:, :), diag22(:)
    select type (b => s%b)
    type is (cholmod_backend_t)
      call b%condensed_factor(status, bad, l22, diag22)
    type is (mumps_backend_t)
      call b%condensed_factor(status, bad, l22, diag22)
    class default
      call fatal(solver_name(s%kind) // ' cannot condense a block of equations')
    end select
    s%factor_entries = s%b%factor_entries
  end subroutine sys_condensed_factor

  !> Purpose: tperm(k) = the trailing equation (1..m, counted from the
  !> first trailing one) at trailing position k of the factor.
  subroutine sys_trailing_order(s, tperm)
    type(linear_system_t), intent(in) :: s
    integer, intent(out) :: tperm(:)
    select type (b => s%b)
    type is (cholmod_backend_t)
      call b%trailing_order(tperm)
    type is (mumps_backend_t)
      call b%trailing_order(tperm)
    class default
      call fatal(solver_name(s%kind) // ' has no trailing block')
    end select
  end subroutine sys_trailing_order

  !> Purpose: b(n) := L^-1 P b, the forward half of a solve with the
  !> condensed factor, in the factor's order (its last m entries in
  !> trailing order).
  subroutine sys_forward(s, b)
    type(linear_system_t), intent(inout) :: s
    real(dp), intent(inout) :: b(:)
    select type (bk => s%b)
    type is (cholmod_backend_t)
      call bk%forward(b)
    type is (mumps_backend_t)
      call bk%forward(b)
    class default
      call fatal(solver_name(s%kind) // ' has no forward solve')
    end select
  end subroutine sys_forward

  !> Purpose: b(n) := P^T L^-T b, the backward half, back in equation order.
  subroutine sys_backward(s, b)
    type(linear_system_t), intent(inout) :: s
    real(dp), intent(inout) :: b(:)
    select type (bk => s%b)
    type is (cholmod_backend_t)
      call bk%backward(b)
    type is (mumps_backend_t)
      call bk%backward(b)
    class default
      call fatal(solver_name(s%kind) // ' has no backward solve')
    end select
  end subroutine sys_backward

  !> Releases the factor and the matrix; the system can be set up again.
  subroutine sys_free(s)
    type(linear_system_t), intent(inout) :: s
    s%n = 0
    if (allocated(s%b)) then
      call s%b%free()
      deallocate(s%b)
    end if
  end subroutine sys_free
end module linear_solver
