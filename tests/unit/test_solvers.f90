!> The three direct solvers behind linear_system_t against LAPACK on the
!> same matrices: SPD (skyline, CHOLMOD with AMD and METIS, UMFPACK),
!> indefinite (CHOLMOD must report it and fall back to UMFPACK), singular
!> (each must say so); and the CHOLMOD common block mirrored in Fortran
!> against the C layout.
program test_solvers
  use, intrinsic :: iso_c_binding
  use kinds, only: dp
  use test_report, only: report, failures
  use linear_solver
  use cholmod_binding, only: cholmod_common_t
  implicit none
  call layout_check()
  call spd_case()
  call indefinite_case()
  call singular_case()
  if (failures() > 0) stop 1

contains


  !> Offsets of cholmod_common fields as the C compiler lays them out for
  !> CHOLMOD 3.0 (offsetof on this platform: nmethods 168, method 184,
  !> postorder 1864, status 1972, fl 1976, lnz 1984).
  subroutine layout_check()
    type(cholmod_common_t), target :: c
    integer(c_intptr_t) :: base
    character(len=120) :: msg
    integer :: off(6)
    base = transfer(c_loc(c), base)
    off(1) = int(transfer(c_loc(c%nmethods), base) - base)
    off(2) = int(transfer(c_loc(c%method), base) - base)
    off(3) = int(transfer(c_loc(c%postorder), base) - base)
    off(4) = int(transfer(c_loc(c%status), base) - base)
    off(5) = int(transfer(c_loc(c%fl), base) - base)
    off(6) = int(transfer(c_loc(c%lnz), base) - base)
    write(msg, '(a,6i6)') 'offsets ', off
    call report('cholmod_common mirror matches the C layout', all(off == [168, 184, 1864, 1972, 1976, 1984]), msg)
  end subroutine layout_check

  !> Element-like structure: overlapping 4x4 blocks along a chain with
  !> extra couplings, n equations.
  subroutine make_elements(n, xeq, eqs)
    integer, intent(in) :: n
    integer, allocatable, intent(out) :: xeq(:), eqs(:)
    integer :: ne, e
    ne = n - 3 + n / 5
    allocate(xeq(ne + 1), eqs(4 * ne))
    xeq(1) = 1
    do e = 1, ne
      if (e <= n - 3) then
        eqs(4 * e - 3:4 * e) = [e, e + 1, e + 2, e + 3]
      else
        eqs(4 * e - 3:4 * e) = [mod(7 * e, n) + 1, mod(13 * e, n) + 1, 0, mod(29 * e + 3, n) + 1]
        if (eqs(4 * e - 3) == eqs(4 * e - 2)) eqs(4 * e - 2) = 0
        if (eqs(4 * e) == eqs(4 * e - 3) .or. eqs(4 * e) == eqs(4 * e - 2)) eqs(4 * e) = 0
      end if
      xeq(e + 1) = 4 * e + 1
    end do
  end subroutine make_elements

  !> Element matrices: SPD (shift > 0) or indefinite (shift < 0) sums.
  subroutine element_matrix(e, shift, ke)
    integer, intent(in) :: e
    real(dp), intent(in) :: shift
    real(dp), intent(out) :: ke(4, 4)
    integer :: i, j
    do j = 1, 4
      do i = 1, 4
        ke(i, j) = -0.5_dp * cos(0.3_dp * (i + j + e))
      end do
    end do
    ke = 0.5_dp * (ke + transpose(ke))
    do i = 1, 4
      ke(i, i) = sum(abs(ke(:, i))) + shift
    end do
  end subroutine element_matrix

  subroutine build_and_solve(kind, order, n, xeq, eqs, shift, x, dense, status)
    integer, intent(in) :: kind, order, n, xeq(:), eqs(:)
    real(dp), intent(in) :: shift
    real(dp), intent(out) :: x(n), dense(n, n)
    integer, intent(out) :: status
    type(linear_system_t) :: s
    real(dp) :: ke(4, 4)
    integer :: e, i, j, bad
    call sys_setup(s, kind, order, n, xeq, eqs)
    call sys_zero(s)
    dense = 0.0_dp
    do e = 1, size(xeq) - 1
      call element_matrix(e, shift, ke)
      call sys_add(s, e, ke)
      do j = 1, 4
        do i = 1, 4
          if (eqs(xeq(e) + i - 1) > 0 .and. eqs(xeq(e) + j - 1) > 0) &
            dense(eqs(xeq(e) + i - 1), eqs(xeq(e) + j - 1)) = dense(eqs(xeq(e) + i - 1), eqs(xeq(e) + j - 1)) &
            + ke(i, j)
        end do
      end do
    end do
    do i = 1, n
      x(i) = sin(0.7_dp * i) + 0.1_dp
    end do
    call sys_factor(s, status, bad)
    if (status /= factor_singular) call sys_solve(s, x)
    call sys_free(s)
  end subroutine build_and_solve

  subroutine spd_case()
    integer, parameter :: n = 300
    integer, allocatable :: xeq(:), eqs(:), ipiv(:)
    real(dp) :: x(n), a(n, n), b(n), err
    integer :: st, info, k, i
    integer, parameter :: kinds_(4) = [solver_skyline, solver_cholmod, solver_cholmod, solver_umfpack]
    integer, parameter :: orders(4) = [order_rcm, order_amd, order_metis, order_amd]
    character(len=160) :: msg
    call make_elements(n, xeq, eqs)
    do k = 1, 4
      call build_and_solve(kinds_(k), orders(k), n, xeq, eqs, 1.0_dp, x, a, st)
      do i = 1, n
        b(i) = sin(0.7_dp * i) + 0.1_dp
      end do
      allocate(ipiv(n))
      call dposv('U', n, 1, a, n, b, n, info)
      deallocate(ipiv)
      err = maxval(abs(x - b)) / maxval(abs(b))
      write(msg, '(a,es9.2,a,i0,a,i0)') 'relative difference ', err, ', status ', st, ', info ', info
      call report(solver_name(kinds_(k)) // ' (' // ordering_name(orders(k)) // ') equals LAPACK dposv', &
                  st == factor_ok .and. info == 0 .and. err < 1.0e-10_dp, msg)
    end do
  end subroutine spd_case

  subroutine indefinite_case()
    integer, parameter :: n = 120
    integer, allocatable :: xeq(:), eqs(:), ipiv(:)
    real(dp) :: x(n), a(n, n), b(n), err
    integer :: st, info, i
    character(len=160) :: msg
    call make_elements(n, xeq, eqs)
    ! a strongly negative shift on one element makes the sum indefinite
    call build_and_solve(solver_cholmod, order_amd, n, xeq, eqs, -3.0_dp, x, a, st)
    do i = 1, n
      b(i) = sin(0.7_dp * i) + 0.1_dp
    end do
    allocate(ipiv(n))
    call dgesv(n, 1, a, n, ipiv, b, n, info)
    err = maxval(abs(x - b)) / maxval(abs(b))
    write(msg, '(a,i0,a,es9.2)') 'status ', st, ', difference from dgesv ', err
    call report('CHOLMOD reports an indefinite matrix and falls back to UMFPACK', &
                st == factor_fallback .and. info == 0 .and. err < 1.0e-9_dp, msg)
  end subroutine indefinite_case

  !> A free chain: every row sums to zero, one rigid mode.
  subroutine singular_case()
    integer, parameter :: n = 50
    integer :: xeq(n), eqs(2 * (n - 1)), e, k, st, bad
    type(linear_system_t) :: s
    real(dp) :: ke(2, 2)
    character(len=80) :: msg
    integer, parameter :: kinds_(3) = [solver_skyline, solver_cholmod, solver_umfpack]
    do e = 1, n - 1
      eqs(2 * e - 1:2 * e) = [e, e + 1]
      xeq(e) = 2 * e - 1
    end do
    xeq(n) = 2 * n - 1
    ke = reshape([1.0_dp, -1.0_dp, -1.0_dp, 1.0_dp], [2, 2])
    do k = 1, 3
      call sys_setup(s, kinds_(k), order_amd, n, xeq, eqs)
      if (kinds_(k) == solver_skyline) call sys_setup(s, kinds_(k), order_rcm, n, xeq, eqs)
      call sys_zero(s)
      do e = 1, n - 1
        call sys_add(s, e, ke)
      end do
      call sys_factor(s, st, bad)
      write(msg, '(a,i0,a,i0)') 'status ', st, ', equation ', bad
      call report(solver_name(kinds_(k)) // ' reports a singular matrix', st == factor_singular, msg)
      call sys_free(s)
    end do
  end subroutine singular_case
end program test_solvers
