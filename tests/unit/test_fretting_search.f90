!> The re-search of UPDATE SEARCH (issue 33, fretting): a master edge tree
!> kept from one search to the next and refit to each new configuration
!> (edge_tree's refit_tree), and the last search's edge of a point tried
!> first (nearest_edge's hint), must answer as a search over every edge
!> does: the same edge and the same position along it, bit for bit, on
!> every configuration of a history. The histories move random master
!> surfaces rigidly, perturb their nodes, stretch them, close a channel
!> of two facing strips (a point's last edge, far along the surface from
!> the new nearest one, must not answer from its neighbour list), and
!> shuffle their edges (which loosens the refit tree's grouping until it
!> is built again). Hints are the point's edge of the configuration
!> before, a random edge, none, or out of range.
!> Run by tests/test_fretting_search.py (make build/tests/test_fretting_search).
program test_fretting_search
  use kinds, only: dp
  use test_report, only: report, failures
  use model, only: model_t, surface_t
  use element_catalogue, only: find_element_type, max_nodes
  use edge_tree, only: edge_tree_t, surface_tree, refit_tree, nearest_edge, tree_candidates
  implicit none
  real(dp), parameter :: pi = 3.14159265358979323846_dp
  call random_seed(put=seed_of(4711))
  call profile_history()
  call circle_history()
  call ties_history()
  call channel_history()
  call shuffled_history()
  if (failures() > 0) stop 1

contains

  !> A seed array of the size random_seed wants, from one number.
  function seed_of(k) result(s)
    integer, intent(in) :: k
    integer, allocatable :: s(:)
    integer :: n, i
    call random_seed(size=n)
    allocate(s(n))
    s = [(k + 53 * i, i = 1, n)]
  end function seed_of

  !> Purpose: a uniform random number in [0, 1).
  real(dp) function rnd()
    call random_number(rnd)
  end function rnd

  !> Purpose: a model of ne elements (CPS4, or CPS8 if curved), each with
  !> its own nodes, whose face S1 runs from a(:, e) to b(:, e) (through
  !> mid(:, e) if curved), and the surface of those faces.
  subroutine make_model(a, b, mid, curved, m, ms)
    real(dp), intent(in) :: a(:, :), b(:, :), mid(:, :)
    logical, intent(in) :: curved
    type(model_t), intent(out) :: m
    type(surface_t), intent(out) :: ms
    integer :: e, ne, nper, i
    real(dp) :: nrm(2)
    ne = size(a, 2)
    nper = merge(8, 4, curved)
    m%nn = ne * nper
    allocate(m%x(2, m%nn), m%etype(ne), m%conn(max_nodes, ne), m%elem_section(ne), m%sections(1))
    allocate(m%node_id(m%nn))
    m%node_id = [(e, e = 1, m%nn)]
    m%conn = 0
    m%elem_section = 1
    m%etype = find_element_type(merge('CPS8', 'CPS4', curved))
    do e = 1, ne
      m%conn(1:nper, e) = [((e - 1) * nper + i, i = 1, nper)]
      nrm = [-(b(2, e) - a(2, e)), b(1, e) - a(1, e)]
      associate(x => m%x(:, (e - 1) * nper + 1:e * nper))
        x(:, 1:4) = reshape([a(:, e), b(:, e), b(:, e) + nrm, a(:, e) + nrm], [2, 4])
        if (curved) x(:, 5:8) = reshape([mid(:, e), b(:, e) + 0.5_dp * nrm, 0.5_dp * (a(:, e) + b(:, e)) + nrm, &
                                         a(:, e) + 0.5_dp * nrm], [2, 4])
      end associate
    end do
    allocate(ms%elem(ne), ms%edge(ne))
    ms%elem = [(e, e = 1, ne)]
    ms%edge = 1
  end subroutine make_model

  !> Purpose: random points about the face corners of x (on the faces, on
  !> their corners, near them on either side, some far away).
  function points_about(m, x, n) result(p)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :)
    integer, intent(in) :: n
    real(dp) :: p(2, n), lo(2), hi(2), pa(2), pb(2)
    integer :: i, e
    lo = minval(x, dim=2)
    hi = maxval(x, dim=2)
    do i = 1, n
      e = 1 + int(rnd() * size(m%etype))
      pa = x(:, m%conn(1, e))
      pb = x(:, m%conn(2, e))
      select case (mod(i, 5))
      case (0)
        p(:, i) = pa
      case (1)
        p(:, i) = lo + [rnd(), rnd()] * (hi - lo) * 1.5_dp - 0.25_dp * (hi - lo)
      case default
        p(:, i) = pa + rnd() * (pb - pa) + (rnd() - 0.5_dp) * 0.2_dp * norm2(pb - pa) * [rnd() - 0.5_dp, rnd() - 0.5_dp]
      end select
    end do
  end function points_about

  !> Purpose: one configuration of a history: nearest_edge on the kept tree
  !> refit to x (hints: each point's answer on the configuration before,
  !> in last(:), or a random edge, none, or one out of range) against the
  !> search over every edge; the refit tree's root box and mean box size
  !> against a tree built on x. Returns ok false and a message at the first
  !> difference; last(:) takes this configuration's answers.
  subroutine compare_on(m, x, ms, tree, pts, dmax, last, ok, msg)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :), pts(:, :), dmax
    type(surface_t), intent(in) :: ms
    type(edge_tree_t), intent(inout) :: tree
    integer, intent(inout) :: last(:)
    logical, intent(inout) :: ok
    character(len=*), intent(inout) :: msg
    type(edge_tree_t) :: fresh
    integer, allocatable :: work(:)
    integer :: i, b1, b2, hint
    real(dp) :: t1, t2
    call refit_tree(m, x, ms, tree)
    call surface_tree(m, x, ms, fresh)
    if (.not. (all(tree%box(:, 1) == fresh%box(:, 1)) .and. tree%step == fresh%step)) then
      ok = .false.
      msg = 'the refit tree''s root box or mean box size differs from a new tree''s'
      return
    end if
    do i = 1, size(pts, 2)
      select case (mod(i, 7))
      case (0)
        hint = 1 + int(rnd() * size(ms%elem))
      case (1)
        hint = 0
      case (2)
        hint = size(ms%elem) + 3
      case default
        hint = last(i)
      end select
      call nearest_edge(m, x, ms, pts(:, i), 0, 0, dmax, b1, t1)
      call nearest_edge(m, x, ms, pts(:, i), 0, 0, dmax, b2, t2, tree, hint, work)
      last(i) = b2
      if (b1 /= b2 .or. .not. t1 == t2) then
        ok = .false.
        write(msg, '(a,i0,a,i0,a,i0,a,i0)') 'point ', i, ': all edges give ', b1, ', the kept tree ', b2, &
          ' (hint ', hint
        return
      end if
    end do
  end subroutine compare_on

  !> Purpose: a history of nstep configurations of the surface ms of m:
  !> x0 moved by step k of a rigid slide (of amplitude slide, back and
  !> forth as in a fretting cycle) and each node perturbed by up to jitter
  !> (stretch: x scaled by 1 + stretch k / nstep about the origin), the
  !> points moving with the slide; compare_on at every configuration.
  subroutine history(name, m, ms, nstep, slide, jitter, stretch, dmax)
    character(len=*), intent(in) :: name
    type(model_t), intent(in) :: m
    type(surface_t), intent(in) :: ms
    integer, intent(in) :: nstep
    real(dp), intent(in) :: slide(2), jitter, stretch, dmax
    type(edge_tree_t) :: tree
    real(dp), allocatable :: x(:, :), pts(:, :)
    integer, allocatable :: last(:)
    integer :: k, j
    logical :: ok
    character(len=200) :: msg, why
    pts = points_about(m, m%x, 1500)
    allocate(last(size(pts, 2)))
    last = 0
    ok = .true.
    msg = ''
    do k = 0, nstep
      x = m%x * (1.0_dp + stretch * k / nstep)
      do j = 1, m%nn
        x(:, j) = x(:, j) + sin(2.0_dp * pi * k / 20.0_dp) * slide + jitter * [rnd() - 0.5_dp, rnd() - 0.5_dp]
      end do
      call compare_on(m, x, ms, tree, pts + spread(sin(2.0_dp * pi * k / 20.0_dp) * slide, 2, size(pts, 2)), &
                      dmax, last, ok, msg)
      if (.not. ok) then
        why = msg
        write(msg, '(a,i0,a,a)') 'configuration ', k, ': ', trim(why)
        exit
      end if
    end do
    call report(name, ok, trim(msg))
  end subroutine history

  !> A rough profile of 400 straight edges along x, slid by 2.5 edges back
  !> and forth, perturbed, then stretched by half; with and without a
  !> search distance.
  subroutine profile_history()
    integer, parameter :: ne = 400
    real(dp) :: a(2, ne), b(2, ne), y(0:ne)
    type(model_t) :: m
    type(surface_t) :: ms
    integer :: i
    y(0) = 0.0_dp
    do i = 1, ne
      y(i) = y(i - 1) + 0.3_dp * (rnd() - 0.5_dp)
    end do
    do i = 1, ne
      ! right to left: the outward normal is +y
      a(:, i) = [real(ne - i + 1, dp), y(ne - i + 1)]
      b(:, i) = [real(ne - i, dp), y(ne - i)]
    end do
    call make_model(a, b, 0.5_dp * (a + b), .false., m, ms)
    call history('profile slid back and forth', m, ms, 40, [2.5_dp, 0.0_dp], 0.05_dp, 0.0_dp, huge(1.0_dp))
    call history('profile slid, search distance 0.2', m, ms, 40, [2.5_dp, 0.1_dp], 0.05_dp, 0.0_dp, 0.2_dp)
    call history('profile stretched by half', m, ms, 30, [0.5_dp, 0.0_dp], 0.01_dp, 0.5_dp, huge(1.0_dp))
  end subroutine profile_history

  !> A circle of 120 3-node edges slid and perturbed.
  subroutine circle_history()
    integer, parameter :: ne = 120
    real(dp) :: a(2, ne), b(2, ne), mid(2, ne), th0, th1
    type(model_t) :: m
    type(surface_t) :: ms
    integer :: i
    do i = 1, ne
      th0 = 2.0_dp * pi * (i - 1) / ne
      th1 = 2.0_dp * pi * i / ne
      a(:, i) = 5.0_dp * [cos(th0), sin(th0)]
      b(:, i) = 5.0_dp * [cos(th1), sin(th1)]
      mid(:, i) = 5.0_dp * [cos(0.5_dp * (th0 + th1)), sin(0.5_dp * (th0 + th1))]
    end do
    call make_model(a, b, mid, .true., m, ms)
    call history('circle of 3-node edges slid', m, ms, 40, [0.6_dp, 0.3_dp], 0.02_dp, 0.0_dp, huge(1.0_dp))
  end subroutine circle_history

  !> Every edge of a polyline given twice (the copies at the end), slid:
  !> hints at the copies must still give the first of two equal edges.
  subroutine ties_history()
    integer, parameter :: nh = 150
    real(dp) :: a(2, 2 * nh), b(2, 2 * nh)
    type(model_t) :: m
    type(surface_t) :: ms
    integer :: i
    do i = 1, nh
      a(:, i) = [real(nh - i + 1, dp), 0.5_dp * sin(0.1_dp * (nh - i + 1))]
      b(:, i) = [real(nh - i, dp), 0.5_dp * sin(0.1_dp * (nh - i))]
    end do
    a(:, nh + 1:) = a(:, 1:nh)
    b(:, nh + 1:) = b(:, 1:nh)
    call make_model(a, b, 0.5_dp * (a + b), .false., m, ms)
    ! (no jitter: the copies stay equal)
    call history('edges given twice, slid (ties)', m, ms, 40, [2.5_dp, 0.0_dp], 0.0_dp, 0.0_dp, huge(1.0_dp))
  end subroutine ties_history

  !> A channel: two straight strips of 200 edges facing each other, 6
  !> apart, the upper one closing in to 2 apart over 40 configurations,
  !> points between them: a point's edge of the configuration before (on
  !> the lower strip, taking it at |d| of a few edge lengths) is no longer
  !> the nearest once the upper strip passes it, and the upper edge is far
  !> from it along the surface (no neighbour of it).
  subroutine channel_history()
    integer, parameter :: nh = 200
    real(dp) :: a(2, 2 * nh), b(2, 2 * nh), pts(2, 1500)
    real(dp), allocatable :: x(:, :)
    type(model_t) :: m
    type(surface_t) :: ms
    type(edge_tree_t) :: tree
    integer :: i, k, last(1500)
    logical :: ok
    character(len=200) :: msg, why
    do i = 1, nh
      ! the lower strip right to left (normal +y), the upper left to right
      a(:, i) = [real(nh - i + 1, dp), 0.0_dp]
      b(:, i) = [real(nh - i, dp), 0.0_dp]
      a(:, nh + i) = [real(i - 1, dp), 6.0_dp]
      b(:, nh + i) = [real(i, dp), 6.0_dp]
    end do
    call make_model(a, b, 0.5_dp * (a + b), .false., m, ms)
    do i = 1, size(pts, 2)
      pts(:, i) = [real(nh, dp) * rnd(), 0.2_dp + 1.6_dp * rnd()]
    end do
    last = 0
    ok = .true.
    msg = ''
    do k = 0, 40
      x = m%x
      do i = nh + 1, 2 * nh
        x(2, m%conn(1:4, i)) = x(2, m%conn(1:4, i)) - 0.1_dp * k
      end do
      call compare_on(m, x, ms, tree, pts, huge(1.0_dp), last, ok, msg)
      if (.not. ok) then
        why = msg
        write(msg, '(a,i0,a,a)') 'configuration ', k, ': ', trim(why)
        exit
      end if
    end do
    call report('a channel closing', ok, trim(msg))
  end subroutine channel_history

  !> A flat surface of 2000 edges whose edges are then dealt out to random
  !> places along it (every element keeps its shape): the refit tree's
  !> grouping no longer fits, so it must be built again: the same answers,
  !> its nodes' boxes as tight as a new tree's (their sizes summed within
  !> 1.5 times), and at most 8 candidate edges within one mean box size of
  !> a point.
  subroutine shuffled_history()
    integer, parameter :: ne = 2000
    real(dp) :: a(2, ne), b(2, ne), shift
    real(dp), allocatable :: x(:, :), pts(:, :)
    type(model_t) :: m
    type(surface_t) :: ms
    type(edge_tree_t) :: tree, fresh
    integer, allocatable :: last(:), cand(:)
    integer :: i, j, most, ncand, place(ne)
    logical :: ok
    character(len=200) :: msg
    do i = 1, ne
      a(:, i) = [real(ne - i + 1, dp), 0.0_dp]
      b(:, i) = [real(ne - i, dp), 0.0_dp]
    end do
    call make_model(a, b, 0.5_dp * (a + b), .false., m, ms)
    call surface_tree(m, m%x, ms, tree)
    ! a random permutation of the places (Fisher-Yates)
    place = [(i, i = 1, ne)]
    do i = ne, 2, -1
      j = 1 + int(rnd() * i)
      place([i, j]) = place([j, i])
    end do
    x = m%x
    do i = 1, ne
      ! element i to place(i) along the line (its face from place(i) to place(i) - 1)
      shift = real(place(i), dp) - real(ne - i + 1, dp)
      x(1, m%conn(1:4, i)) = x(1, m%conn(1:4, i)) + shift
    end do
    pts = points_about(m, x, 2000)
    allocate(last(size(pts, 2)))
    last = 0
    ok = .true.
    msg = ''
    call compare_on(m, x, ms, tree, pts, huge(1.0_dp), last, ok, msg)
    most = 0
    do i = 1, size(pts, 2)
      call tree_candidates(tree, [pts(1, i), 0.0_dp], tree%step, cand, ncand)
      most = max(most, ncand)
    end do
    if (ok .and. most > 8) then
      ok = .false.
      write(msg, '(a,i0,a)') 'the refit tree offers ', most, ' edges within one box size'
    end if
    call surface_tree(m, x, ms, fresh)
    if (ok .and. .not. node_sizes(tree) <= 1.5_dp * node_sizes(fresh)) then
      ok = .false.
      write(msg, '(a,es10.3,a,es10.3,a)') 'the kept tree''s nodes span ', node_sizes(tree), ' against a new tree''s ', &
        node_sizes(fresh), ' (not built again?)'
    end if
    call report('edges shuffled: the tree built again', ok, trim(msg))
  end subroutine shuffled_history

  !> Purpose: the sum of the widths and heights of the tree's nodes' boxes.
  real(dp) function node_sizes(tree) result(s)
    type(edge_tree_t), intent(in) :: tree
    integer :: k
    s = 0.0_dp
    do k = 1, tree%nnode
      if (tree%last(k) < tree%first(k)) cycle
      s = s + (tree%box(3, k) - tree%box(1, k)) + (tree%box(4, k) - tree%box(2, k))
    end do
  end function node_sizes
end program test_fretting_search
