!> The skyline LDL^T solver against LAPACK (dposv, dgesv) on the same
!> matrices, with and without a reverse Cuthill-McKee renumbering, and its
!> detection of singular and indefinite matrices.
program test_skyline
  use kinds, only: dp
  use test_report, only: report, failures
  use skyline, only: skyline_t, sky_setup, sky_add, sky_factor, sky_solve, sky_matvec
  use ordering, only: rcm_order
  implicit none
  call random_profile_case(7, 40)
  call random_profile_case(11, 200)
  call reordered_grid_case(13, 9)
  call singular_cases()
  if (failures() > 0) stop 1

contains


  !> Symmetric, diagonally dominant matrix with a random profile.
  subroutine random_profile_case(seed, n)
    integer, intent(in) :: seed, n
    real(dp), allocatable :: a(:, :), b(:), x_sky(:), x_po(:), x_ge(:), y(:), af(:, :)
    integer, allocatable :: first(:), ipiv(:)
    type(skyline_t) :: k
    integer :: i, j, bad, info
    real(dp) :: r, e1, e2, e3
    character(len=160) :: msg, name
    call seed_rng(seed)
    allocate(a(n, n), b(n), first(n), ipiv(n))
    a = 0.0_dp
    do j = 1, n
      call random_number(r)
      first(j) = max(1, j - int(r * 12))
      do i = first(j), j - 1
        call random_number(r)
        if (r < 0.5_dp .and. i > first(j)) cycle
        a(i, j) = 2.0_dp * r - 1.0_dp
        a(j, i) = a(i, j)
      end do
    end do
    do j = 1, n
      a(j, j) = sum(abs(a(:, j))) + 1.0_dp
    end do
    call sky_setup(k, first)
    do j = 1, n
      do i = first(j), j
        call sky_add(k, i, j, a(i, j))
      end do
    end do
    do i = 1, n
      b(i) = sin(real(i, dp))
    end do
    allocate(y(n))
    call sky_matvec(k, b, y)
    e1 = maxval(abs(y - matmul(a, b))) / maxval(abs(matmul(a, b)))
    write(name, '(a,i0)') 'skyline product equals dense, n=', n
    write(msg, '(a,es9.2)') 'relative difference ', e1
    call report(trim(name), e1 < 1.0e-14_dp, msg)
    x_sky = b
    call sky_factor(k, bad)
    call sky_solve(k, x_sky)
    af = a
    x_po = b
    call dposv('U', n, 1, af, n, x_po, n, info)
    af = a
    x_ge = b
    call dgesv(n, 1, af, n, ipiv, x_ge, n, info)
    e2 = maxval(abs(x_sky - x_po)) / maxval(abs(x_po))
    e3 = maxval(abs(x_sky - x_ge)) / maxval(abs(x_ge))
    write(name, '(a,i0)') 'skyline LDL^T equals LAPACK dposv and dgesv, n=', n
    write(msg, '(a,es9.2,a,es9.2,a,i0)') 'vs dposv ', e2, ', vs dgesv ', e3, ', bad pivot ', bad
    call report(trim(name), bad == 0 .and. e2 < 1.0e-10_dp .and. e3 < 1.0e-10_dp, msg)
  end subroutine random_profile_case

  !> A 5-point grid operator with a shift, numbered at random, solved in
  !> the RCM order and compared with the dense solution in the original one.
  subroutine reordered_grid_case(seed, m)
    integer, intent(in) :: seed, m
    integer :: n, i, j, p, q, bad, info, na, cnt
    integer, allocatable :: label(:), xadj(:), adj(:), perm(:), inv(:), first(:), ipiv(:)
    real(dp), allocatable :: a(:, :), b(:), x(:), xd(:), af(:, :)
    type(skyline_t) :: k
    real(dp) :: r, e
    integer(8) :: prof_rand, prof_rcm
    character(len=160) :: msg
    call seed_rng(seed)
    n = m * m
    ! Random labels for the grid points.
    label = [(i, i = 1, n)]
    do i = n, 2, -1
      call random_number(r)
      j = 1 + int(r * i)
      p = label(i); label(i) = label(j); label(j) = p
    end do
    allocate(a(n, n))
    a = 0.0_dp
    do i = 1, m
      do j = 1, m
        p = label((i - 1) * m + j)
        a(p, p) = 4.5_dp
        if (i < m) call link(a, p, label(i * m + j))
        if (j < m) call link(a, p, label((i - 1) * m + j + 1))
      end do
    end do
    ! Graph of the matrix and its RCM order.
    allocate(xadj(n + 1))
    xadj(1) = 1
    do p = 1, n
      xadj(p + 1) = xadj(p) + count(a(:, p) /= 0.0_dp) - 1
    end do
    allocate(adj(xadj(n + 1) - 1))
    na = 0
    do p = 1, n
      do q = 1, n
        if (q /= p .and. a(q, p) /= 0.0_dp) then
          na = na + 1
          adj(na) = q
        end if
      end do
    end do
    allocate(perm(n), inv(n))
    call rcm_order(n, xadj, adj, perm)
    do i = 1, n
      inv(perm(i)) = i
    end do
    prof_rand = profile_of(a, [(i, i = 1, n)])
    prof_rcm = profile_of(a, inv)
    write(msg, '(a,i0,a,i0)') 'profile random ', prof_rand, ', RCM ', prof_rcm
    call report('RCM reduces the profile of a scrambled grid', prof_rcm < prof_rand / 2, msg)
    cnt = 0
    do i = 1, n
      if (any(perm == i)) cnt = cnt + 1
    end do
    call report('RCM order is a permutation', cnt == n, 'not a permutation')
    ! Skyline in the new numbering.
    allocate(first(n))
    do i = 1, n
      first(i) = i
    end do
    do p = 1, n
      do q = 1, n
        if (a(q, p) /= 0.0_dp) first(max(inv(p), inv(q))) = min(first(max(inv(p), inv(q))), min(inv(p), inv(q)))
      end do
    end do
    call sky_setup(k, first)
    do p = 1, n
      do q = p, n
        if (a(q, p) /= 0.0_dp) call sky_add(k, inv(p), inv(q), a(q, p))
      end do
    end do
    allocate(b(n), x(n))
    do p = 1, n
      b(p) = cos(0.37_dp * p)
    end do
    do p = 1, n
      x(inv(p)) = b(p)
    end do
    call sky_factor(k, bad)
    call sky_solve(k, x)
    xd = b
    af = a
    allocate(ipiv(n))
    call dgesv(n, 1, af, n, ipiv, xd, n, info)
    e = maxval(abs(x(inv) - xd)) / maxval(abs(xd))
    write(msg, '(a,es9.2)') 'relative difference ', e
    call report('skyline in RCM order equals LAPACK dgesv in the original order', &
                bad == 0 .and. info == 0 .and. e < 1.0e-10_dp, msg)
  end subroutine reordered_grid_case

  subroutine link(a, s, t)
    real(dp), intent(inout) :: a(:, :)
    integer, intent(in) :: s, t
    a(s, t) = -1.0_dp
    a(t, s) = -1.0_dp
  end subroutine link

  !> Skyline size of matrix a under the numbering newnum(old) = new.
  integer(8) function profile_of(a, newnum)
    real(dp), intent(in) :: a(:, :)
    integer, intent(in) :: newnum(:)
    integer :: c, q, lo
    profile_of = 0
    do c = 1, size(a, 2)
      lo = newnum(c)
      do q = 1, size(a, 1)
        if (a(q, c) /= 0.0_dp) lo = min(lo, newnum(q))
      end do
      profile_of = profile_of + (newnum(c) - lo + 1)
    end do
  end function profile_of

  subroutine singular_cases()
    type(skyline_t) :: k
    integer :: bad, i
    character(len=80) :: msg
    ! A free chain of springs: one rigid translation.
    call sky_setup(k, [1, 1, 2, 3])
    do i = 1, 3
      call sky_add(k, i, i, 1.0_dp)
      call sky_add(k, i + 1, i + 1, 1.0_dp)
      call sky_add(k, i, i + 1, -1.0_dp)
    end do
    call sky_factor(k, bad)
    write(msg, '(a,i0)') 'bad equation ', bad
    call report('singular matrix detected at its last equation', bad == 4, msg)
    ! Indefinite.
    call sky_setup(k, [1, 1])
    call sky_add(k, 1, 1, 1.0_dp)
    call sky_add(k, 2, 2, 1.0_dp)
    call sky_add(k, 1, 2, 2.0_dp)
    call sky_factor(k, bad)
    write(msg, '(a,i0)') 'bad equation ', bad
    call report('negative pivot detected', bad == 2, msg)
    ! Zero diagonal.
    call sky_setup(k, [1, 2])
    call sky_add(k, 1, 1, 1.0_dp)
    call sky_factor(k, bad)
    write(msg, '(a,i0)') 'bad equation ', bad
    call report('zero pivot detected', bad == 2, msg)
  end subroutine singular_cases

  subroutine seed_rng(s)
    integer, intent(in) :: s
    integer :: n
    integer, allocatable :: seed(:)
    call random_seed(size=n)
    allocate(seed(n))
    seed = s + 37 * [(n, n = 1, size(seed))]
    call random_seed(put=seed)
  end subroutine seed_rng
end program test_skyline
