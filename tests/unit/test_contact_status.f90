!> The contact status search (contact_status) on a small contact problem
!> written out by hand: three coupling points on three contact equations,
!> x = (S0 + sum over closed c of d_c b_c b_c^T)^-1 (q - sum over closed c
!> of d_c h_c b_c), gaps g = B^T x + h. The numbers were drawn at random
!> and kept because plain block pivoting (every violated point changes,
!> the paper's penalty switching) cycles on them from the all-open
!> status: the test shows that it does, and that the search with its
!> safeguard ends at the one status that solves the complementarity
!> problem (found by trying all eight). Also: a point whose gap is zero
!> to round-off counts as settled in either state.
program test_contact_status
  use kinds, only: dp
  use test_report, only: report, failures
  use model, only: model_t
  use contact, only: contact_set_t
  use contact_status, only: status_search_t, begin_status_search, contact_switch, contact_energy
  implicit none
  integer, parameter :: n = 3
  real(dp), parameter :: s0(3, 3) = reshape([ &
    3.1587873496734433_dp, -1.2122671115426027_dp, 2.411473205317899_dp, &
    -1.2122671115426027_dp, 0.8044927015578731_dp, -1.4926110079630013_dp, &
    2.411473205317899_dp, -1.4926110079630013_dp, 2.9182811750107858_dp], [3, 3])
  real(dp), parameter :: b(3, 3) = reshape([ &
    -0.3138665069556694_dp, 0.04566360549238405_dp, -1.5091947041043123_dp, &
    -0.4873163344450868_dp, 1.5866140697077962_dp, -0.32300739779235654_dp, &
    -0.09832609782544541_dp, -0.6297181557101874_dp, -2.0427777003533527_dp], [3, 3])
  real(dp), parameter :: d(3) = [2.8302906860477_dp, 0.5781230429393311_dp, 4.380423692932393_dp]
  real(dp), parameter :: q(3) = [-0.38565171345579197_dp, -1.0310656293035765_dp, 1.2268682075948119_dp]
  real(dp), parameter :: h(3) = [-0.8621420889459335_dp, 1.4728955178335572_dp, 0.10215079715448529_dp]
  type(model_t) :: m
  type(contact_set_t) :: cs
  integer :: j
  m%nn = n
  m%node_id = [(j, j = 1, n)]
  cs%n = n
  allocate(cs%c(n))
  do j = 1, n
    cs%c(j)%ns = 1
    cs%c(j)%snode(1) = j
    cs%c(j)%normal = [0.0_dp, 1.0_dp]
    cs%c(j)%gap0 = 0.0_dp
    cs%c(j)%k_closed = d(j)
    cs%c(j)%k_open = 0.0_dp
    cs%c(j)%h = 1.0_dp
  end do
  call block_pivoting_cycles()
  call search_terminates()
  call round_off_settles()
  if (failures() > 0) stop 1

contains

  !> The gaps of status closed(:) (x solved by Gaussian elimination).
  subroutine status_gaps(closed, g, x)
    logical, intent(in) :: closed(n)
    real(dp), intent(out) :: g(n), x(3)
    real(dp) :: a(3, 3), r(3), f
    integer :: c, i, k
    a = s0
    r = q
    do c = 1, n
      if (.not. closed(c)) cycle
      do k = 1, 3
        a(:, k) = a(:, k) + d(c) * b(:, c) * b(k, c)
      end do
      r = r - d(c) * h(c) * b(:, c)
    end do
    do k = 1, 3
      do i = k + 1, 3
        f = a(i, k) / a(k, k)
        a(i, k:3) = a(i, k:3) - f * a(k, k:3)
        r(i) = r(i) - f * r(k)
      end do
    end do
    do k = 3, 1, -1
      x(k) = (r(k) - dot_product(a(k, k + 1:3), x(k + 1:3))) / a(k, k)
    end do
    g = matmul(transpose(b), x) + h
  end subroutine status_gaps

  logical function solves(closed)
    logical, intent(in) :: closed(n)
    real(dp) :: g(n), x(3)
    call status_gaps(closed, g, x)
    solves = all(merge(g <= 0.0_dp, g >= 0.0_dp, closed))
  end function solves

  !> Plain block pivoting from all open comes back to a status it had.
  subroutine block_pivoting_cycles()
    logical :: closed(n), seen(0:2**n - 1)
    real(dp) :: g(n), x(3)
    integer :: it, key, c
    logical :: cycled
    closed = .false.
    seen = .false.
    cycled = .false.
    do it = 1, 20
      if (solves(closed)) exit
      key = 0
      do c = 1, n
        if (closed(c)) key = key + 2**(c - 1)
      end do
      if (seen(key)) then
        cycled = .true.
        exit
      end if
      seen(key) = .true.
      call status_gaps(closed, g, x)
      closed = closed .neqv. merge(g > 0.0_dp, g < 0.0_dp, closed)
    end do
    call report('plain block pivoting cycles on this problem', cycled, 'it did not: the problem no longer shows it')
  end subroutine block_pivoting_cycles

  !> The search ends at the one status that solves the problem.
  subroutine search_terminates()
    type(status_search_t) :: ss
    logical :: closed(n), answer(n)
    real(dp) :: g(n), x(3), energy
    integer :: it, k, c, nsol, nchanged
    character(len=:), allocatable :: changed
    character(len=120) :: msg
    nsol = 0
    do k = 0, 2**n - 1
      closed = [(btest(k, c - 1), c = 1, n)]
      if (solves(closed)) then
        nsol = nsol + 1
        answer = closed
      end if
    end do
    write(msg, '(i0)') nsol
    call report('one status solves the complementarity problem', nsol == 1, trim(msg) // ' statuses solve it')
    cs%c(1:n)%closed = .false.
    call begin_status_search(ss)
    do it = 1, 50
      call status_gaps(cs%c(1:n)%closed, g, x)
      cs%c(1:n)%gap = g
      energy = 0.5_dp * dot_product(x, matmul(s0, x)) - dot_product(q, x) + contact_energy(cs)
      call contact_switch(m, cs, ss, 1.0_dp, energy, nchanged, changed)
      if (nchanged == 0) exit
    end do
    write(msg, '(a,i0,a,i0,a,i0)') 'iterations ', it, ', block pivots ', ss%block_pivots, ', single ', ss%single_pivots
    call report('the search terminates at the solution', &
                it < 50 .and. all(cs%c(1:n)%closed .eqv. answer) .and. ss%single_pivots > 0, trim(msg))
  end subroutine search_terminates

  !> A closed point with a gap of +1e-17 (zero to round-off) and an open
  !> one at -1e-17 are not switched; at +-1e-6 they are.
  subroutine round_off_settles()
    type(status_search_t) :: ss
    integer :: nchanged
    character(len=:), allocatable :: changed
    cs%c(1:n)%closed = [.true., .false., .false.]
    cs%c(1:n)%gap = [1.0e-17_dp, -1.0e-17_dp, 1.0_dp]
    call begin_status_search(ss)
    call contact_switch(m, cs, ss, 1.0_dp, 0.0_dp, nchanged, changed)
    call report('gaps zero to round-off settle in either state', nchanged == 0, changed)
    cs%c(1:n)%gap = [1.0e-6_dp, -1.0e-6_dp, 1.0_dp]
    call contact_switch(m, cs, ss, 1.0_dp, 0.0_dp, nchanged, changed)
    call report('gaps of 1e-6 switch', nchanged == 2 .and. .not. cs%c(1)%closed .and. cs%c(2)%closed, changed)
  end subroutine round_off_settles
end program test_contact_status
