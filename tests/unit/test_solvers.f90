!> Every solver backend behind linear_system_t against LAPACK on the same
!> matrices, several right-hand sides at once: SPD (skyline, CHOLMOD and
!> UMFPACK with AMD and METIS), a refactorisation with new values,
!> indefinite (CHOLMOD must report it and fall back to UMFPACK), singular
!> (each must say so and name an equation of the free mode), and the
!> system of no equations. Prints the CHOLMOD version it runs on.
program test_solvers
  use, intrinsic :: iso_c_binding, only: c_int
  use kinds, only: dp
  use test_report, only: report, failures
  use linear_solver
  use cholmod_binding, only: cfe_cholmod_version, cfe_cholmod_header_version
  use sparse_matrix, only: csc_t, csc_build, csc_zero, csc_add_element
  implicit none
  integer, parameter :: nkinds = 5
  integer, parameter :: kinds_(nkinds) = [solver_skyline, solver_cholmod, solver_cholmod, solver_umfpack, &
                                          solver_umfpack]
  integer, parameter :: orders(nkinds) = [order_rcm, order_amd, order_metis, order_amd, order_metis]
  call version_check()
  call spd_case()
  call refactor_case()
  call map_later_case()
  call indefinite_case()
  call singular_exact_case()
  call singular_tiny_pivot_case()
  call empty_case()
  if (failures() > 0) stop 1

contains

  function label(k) result(s)
    integer, intent(in) :: k
    character(len=:), allocatable :: s
    s = solver_name(kinds_(k)) // ' (' // ordering_name(orders(k)) // ')'
  end function label

  !> The library cfe2d runs on, and the header the shim was built with.
  subroutine version_check()
    integer(c_int) :: lib(3), hdr(3)
    character(len=80) :: msg
    call cfe_cholmod_version(lib)
    call cfe_cholmod_header_version(hdr)
    write(msg, '(a,i0,a,i0,a,i0,a,i0,a,i0,a,i0)') 'CHOLMOD ', lib(1), '.', lib(2), '.', lib(3), &
      ', header ', hdr(1), '.', hdr(2), '.', hdr(3)
    print '(a)', trim(msg)
    call report('CHOLMOD library (3 or later) matches the header of the shim', &
                lib(1) >= 3 .and. lib(1) == hdr(1) .and. lib(2) == hdr(2), msg)
  end subroutine version_check

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

  !> Sets up s (unless again: the same system, new values) and assembles
  !> the elements scaled by factor; dense gets the same matrix.
  subroutine assemble(s, again, kind, order, n, xeq, eqs, shift, factor, dense)
    type(linear_system_t), intent(inout) :: s
    logical, intent(in) :: again
    integer, intent(in) :: kind, order, n, xeq(:), eqs(:)
    real(dp), intent(in) :: shift, factor
    real(dp), intent(out) :: dense(n, n)
    real(dp) :: ke(4, 4)
    integer :: e, i, j, gi, gj
    if (.not. again) call sys_setup(s, kind, order, n, xeq, eqs)
    call sys_zero(s)
    dense = 0.0_dp
    do e = 1, size(xeq) - 1
      call element_matrix(e, shift, ke)
      ke = factor * ke
      call sys_add(s, e, ke)
      do j = 1, 4
        do i = 1, 4
          gi = eqs(xeq(e) + i - 1)
          gj = eqs(xeq(e) + j - 1)
          if (gi > 0 .and. gj > 0) dense(gi, gj) = dense(gi, gj) + ke(i, j)
        end do
      end do
    end do
  end subroutine assemble

  subroutine right_hand_sides(b)
    real(dp), intent(out) :: b(:, :)
    integer :: i, j
    do j = 1, size(b, 2)
      do i = 1, size(b, 1)
        b(i, j) = sin(0.7_dp * i * j) + 0.1_dp * j
      end do
    end do
  end subroutine right_hand_sides

  !> Three right-hand sides in one call, against dposv; the single
  !> right-hand side form must give the first column; K x = b checked
  !> with sys_matvec where the matrix is kept apart from its factor.
  subroutine spd_case()
    integer, parameter :: n = 300, nrhs = 3
    integer, allocatable :: xeq(:), eqs(:)
    real(dp) :: x(n, nrhs), x1(n), b(n, nrhs), y(n), err, err1, res
    real(dp), allocatable :: a(:, :)
    integer :: st, bad, info, k
    type(linear_system_t) :: s
    character(len=160) :: msg
    call make_elements(n, xeq, eqs)
    allocate(a(n, n))
    do k = 1, nkinds
      call assemble(s, .false., kinds_(k), orders(k), n, xeq, eqs, 1.0_dp, 1.0_dp, a)
      call right_hand_sides(x)
      res = 0.0_dp
      if (kinds_(k) /= solver_skyline) then
        call sys_matvec(s, x(:, 2), y)
        res = maxval(abs(y - matmul(a, x(:, 2)))) / maxval(abs(y))
      end if
      call sys_factor(s, st, bad)
      x1 = x(:, 1)
      call sys_solve(s, x)
      call sys_solve(s, x1)
      call right_hand_sides(b)
      call dposv('U', n, nrhs, a, n, b, n, info)
      err = maxval(abs(x - b)) / maxval(abs(b))
      err1 = maxval(abs(x1 - b(:, 1))) / maxval(abs(b(:, 1)))
      write(msg, '(a,es9.2,a,es9.2,a,es9.2,a,i0,a,i0)') 'difference ', err, ', one rhs ', err1, ', matvec ', res, &
        ', status ', st, ', info ', info
      call report(label(k) // ' equals LAPACK dposv on 3 right-hand sides', st == factor_ok .and. info == 0 .and. &
                  err < 1.0e-10_dp .and. err1 < 1.0e-12_dp .and. res < 1.0e-14_dp, msg)
      call sys_free(s)
    end do
  end subroutine spd_case

  !> The pattern analysed once, factorised twice: the second matrix is
  !> twice the first, so the solutions halve.
  subroutine refactor_case()
    integer, parameter :: n = 120, nrhs = 2
    integer, allocatable :: xeq(:), eqs(:)
    real(dp) :: x(n, nrhs), x2(n, nrhs), err
    real(dp), allocatable :: a(:, :)
    integer :: st, st2, bad, k
    type(linear_system_t) :: s
    character(len=120) :: msg
    call make_elements(n, xeq, eqs)
    allocate(a(n, n))
    do k = 1, nkinds
      call assemble(s, .false., kinds_(k), orders(k), n, xeq, eqs, 1.0_dp, 1.0_dp, a)
      call sys_analyse(s)
      call sys_factor(s, st, bad)
      call right_hand_sides(x)
      call sys_solve(s, x)
      call assemble(s, .true., kinds_(k), orders(k), n, xeq, eqs, 1.0_dp, 2.0_dp, a)
      call sys_factor(s, st2, bad)
      call right_hand_sides(x2)
      call sys_solve(s, x2)
      err = maxval(abs(2.0_dp * x2 - x)) / maxval(abs(x))
      write(msg, '(a,es9.2,a,i0,a,i0)') 'difference ', err, ', status ', st, ' then ', st2
      call report(label(k) // ' refactorises new values on the same analysis', &
                  st == factor_ok .and. st2 == factor_ok .and. err < 1.0e-12_dp, msg)
      call sys_free(s)
    end do
  end subroutine refactor_case

  !> A matrix whose value map is made at its second assembly (map_later)
  !> against one built with the map: the same values to the bit at each of
  !> three assemblies, upper triangle and full pattern, with element
  !> matrices that are not symmetric (so that taking ke(j, i) for ke(i, j)
  !> would show); no map before the second assembly, one after it.
  subroutine map_later_case()
    integer, parameter :: n = 90
    integer, allocatable :: xeq(:), eqs(:)
    type(csc_t) :: now, later
    real(dp) :: ke(4, 4)
    integer :: pass, e, i, j, up
    logical :: same, map_first, map_second
    character(len=120) :: msg
    call make_elements(n, xeq, eqs)
    do up = 0, 1
      call csc_build(now, n, xeq, eqs, upper=up == 1)
      call csc_build(later, n, xeq, eqs, upper=up == 1, map_later=.true.)
      same = .true.
      map_first = .false.
      map_second = .false.
      do pass = 1, 3
        call csc_zero(now, xeq, eqs)
        call csc_zero(later, xeq, eqs)
        if (pass == 1) map_first = allocated(later%emap)
        if (pass == 2) map_second = allocated(later%emap)
        do e = 1, size(xeq) - 1
          do j = 1, 4
            do i = 1, 4
              ke(i, j) = sin(0.37_dp * (e + pass) + 1.3_dp * i + 0.11_dp * j * j) / 3.0_dp
            end do
          end do
          call csc_add_element(now, e, eqs(xeq(e):xeq(e + 1) - 1), ke)
          call csc_add_element(later, e, eqs(xeq(e):xeq(e + 1) - 1), ke)
        end do
        same = same .and. all(now%val == later%val)
      end do
      write(msg, '(a,l1,a,l1,a,l1)') 'same values ', same, ', map at first assembly ', map_first, &
        ', at second ', map_second
      call report('map_later (upper ' // merge('T', 'F', up == 1) // ') assembles as the map, makes it once reassembled', &
                  same .and. .not. map_first .and. map_second, msg)
    end do
  end subroutine map_later_case

  subroutine indefinite_case()
    integer, parameter :: n = 120, nrhs = 2
    integer, allocatable :: xeq(:), eqs(:), ipiv(:)
    real(dp) :: x(n, nrhs), b(n, nrhs), err
    real(dp), allocatable :: a(:, :)
    integer :: st, info, bad, k
    type(linear_system_t) :: s
    character(len=200) :: msg
    logical :: noted
    call make_elements(n, xeq, eqs)
    allocate(ipiv(n), a(n, n))
    do k = 2, 3
      ! a negative shift on every element makes the sum indefinite
      call assemble(s, .false., solver_cholmod, orders(k), n, xeq, eqs, -3.0_dp, 1.0_dp, a)
      call sys_factor(s, st, bad)
      call right_hand_sides(x)
      call sys_solve(s, x)
      call right_hand_sides(b)
      call dgesv(n, nrhs, a, n, ipiv, b, n, info)
      err = maxval(abs(x - b)) / maxval(abs(b))
      noted = .false.
      if (allocated(s%note)) noted = index(s%note, 'CHOLMOD: the matrix is not positive definite (at equation ') == 1 &
        .and. index(s%note, '); falling back to UMFPACK') > 0
      write(msg, '(a,i0,a,es9.2,a,l1,a,i0)') 'status ', st, ', difference from dgesv ', err, ', note ', noted, &
        ', kind now ', s%kind
      call report(label(k) // ' reports an indefinite matrix and falls back to UMFPACK', st == factor_fallback .and. &
                  info == 0 .and. err < 1.0e-9_dp .and. noted .and. s%kind == solver_umfpack, msg)
      call sys_free(s)
    end do
  end subroutine indefinite_case

  !> A grounded chain of n - 3 equations (SPD) around three free ones,
  !> p .. p + 2, held only by two springs between them: one rigid mode,
  !> on those three equations only; delta is added to the last diagonal
  !> (0: exactly singular).
  subroutine free_chain_system(s, kind, order, n, p, delta)
    type(linear_system_t), intent(inout) :: s
    integer, intent(in) :: kind, order, n, p
    real(dp), intent(in) :: delta
    integer, allocatable :: xeq(:), eqs(:), xeq0(:), eqs0(:)
    real(dp) :: ke(4, 4), k2(2, 2)
    integer :: e, ne0
    call make_elements(n - 3, xeq0, eqs0)
    ne0 = size(xeq0) - 1
    ! renumber the chain around p .. p + 2 and add the two springs
    where (eqs0 >= p) eqs0 = eqs0 + 3
    xeq = [xeq0, xeq0(ne0 + 1) + 2, xeq0(ne0 + 1) + 4]
    eqs = [eqs0, p, p + 1, p + 1, p + 2]
    call sys_setup(s, kind, order, n, xeq, eqs)
    call sys_zero(s)
    do e = 1, ne0
      call element_matrix(e, 1.0_dp, ke)
      call sys_add(s, e, ke)
    end do
    k2 = reshape([0.3_dp, -0.3_dp, -0.3_dp, 0.3_dp], [2, 2])
    call sys_add(s, ne0 + 1, k2)
    k2 = reshape([0.7_dp, -0.7_dp, -0.7_dp, 0.7_dp + delta], [2, 2])
    call sys_add(s, ne0 + 2, k2)
  end subroutine free_chain_system

  !> Exactly singular: every backend reports it, naming one of the three
  !> free equations (the caller's numbering, whatever the ordering).
  subroutine singular_exact_case()
    integer, parameter :: n = 60, p = 23
    integer :: k, st, bad
    type(linear_system_t) :: s
    character(len=80) :: msg
    do k = 1, nkinds
      call free_chain_system(s, kinds_(k), orders(k), n, p, 0.0_dp)
      call sys_factor(s, st, bad)
      write(msg, '(a,i0,a,i0)') 'status ', st, ', equation ', bad
      call report(label(k) // ' reports a singular matrix at a free equation', &
                  st == factor_singular .and. bad >= p .and. bad <= p + 2, msg)
      call sys_free(s)
    end do
  end subroutine singular_exact_case

  !> Singular to working precision: the last pivot of the free equations
  !> is 1e-10 of its diagonal, positive. CHOLMOD must report it from its
  !> own factor (no fallback) and UMFPACK from its U, at a free equation.
  subroutine singular_tiny_pivot_case()
    integer, parameter :: n = 60, p = 41
    integer :: k, st, bad
    type(linear_system_t) :: s
    character(len=80) :: msg
    do k = 2, nkinds
      call free_chain_system(s, kinds_(k), orders(k), n, p, 1.0e-10_dp)
      call sys_factor(s, st, bad)
      write(msg, '(a,i0,a,i0,a,l1)') 'status ', st, ', equation ', bad, ', note ', allocated(s%note)
      call report(label(k) // ' reports a tiny pivot as singular at a free equation', st == factor_singular .and. &
                  bad >= p .and. bad <= p + 2 .and. .not. allocated(s%note), msg)
      call sys_free(s)
    end do
  end subroutine singular_tiny_pivot_case

  !> Every dof prescribed: nothing to factor, nothing to solve.
  subroutine empty_case()
    integer :: k, st, bad, xeq(3), eqs(8)
    real(dp) :: ke(4, 4), b1(0), b2(0, 3), y(0)
    type(linear_system_t) :: s
    character(len=80) :: msg
    xeq = [1, 5, 9]
    eqs = 0
    ke = 1.0_dp
    do k = 1, nkinds
      call sys_setup(s, kinds_(k), orders(k), 0, xeq, eqs)
      call sys_zero(s)
      call sys_add(s, 1, ke)
      call sys_add(s, 2, ke)
      call sys_analyse(s)
      call sys_factor(s, st, bad)
      call sys_solve(s, b1)
      call sys_solve(s, b2)
      call sys_matvec(s, b1, y)
      write(msg, '(a,i0,a,i0,a,i0)') 'status ', st, ', equation ', bad, ', equations ', sys_neq(s)
      call report(label(k) // ' takes a system of no equations', st == factor_ok .and. bad == 0 .and. &
                  sys_neq(s) == 0 .and. len(sys_describe(s)) > 0, msg)
      call sys_free(s)
    end do
  end subroutine empty_case
end program test_solvers
