!> The contact search's tree (edge_tree) against the search over every
!> master edge: on random surfaces (a rough profile of 2-node edges, a
!> polygonal circle of 3-node edges, scattered edges of very different
!> lengths, edges given twice so that two are equally near) and random
!> points (on and near the surface, on its vertices, far from it, beyond
!> its ends), with and without a search distance and skipped edges,
!> nearest_edge with the tree must return the same edge and the same
!> position as without it, bit for bit. Also: the tree looks at few edges
!> for a point near a long surface (its point).
!> Run by tests/test_search.py (which builds it: make build/tests/test_search).
program test_search
  use kinds, only: dp
  use test_report, only: report, failures
  use model, only: model_t, surface_t
  use element_catalogue, only: find_element_type, max_nodes
  use edge_tree, only: edge_tree_t, surface_tree, nearest_edge, tree_candidates
  use contact_geometry, only: edge_t, get_edge
  use contact_mortar, only: face_cuts
  implicit none
  real(dp), parameter :: pi = 3.14159265358979323846_dp
  call random_seed(put=seed_of(12345))
  call rough_profile()
  call curved_circle()
  call scattered_edges()
  call twice_given_edges()
  call few_candidates()
  if (failures() > 0) stop 1

contains

  !> A seed array of the size random_seed wants, from one number.
  function seed_of(k) result(s)
    integer, intent(in) :: k
    integer, allocatable :: s(:)
    integer :: n, i
    call random_seed(size=n)
    allocate(s(n))
    s = [(k + 37 * i, i = 1, n)]
  end function seed_of

  !> Purpose: a uniform random number in [0, 1).
  real(dp) function rnd()
    call random_number(rnd)
  end function rnd

  !> Purpose: a model of ne elements (CPS4, or CPS8 if curved) whose face
  !> S1 runs from a(:, e) to b(:, e) (through mid(:, e) if curved), and the
  !> surface of those faces. The other nodes sit away from the faces.
  subroutine make_model(a, b, mid, curved, m, ms)
    real(dp), intent(in) :: a(:, :), b(:, :), mid(:, :)
    logical, intent(in) :: curved
    type(model_t), intent(out) :: m
    type(surface_t), intent(out) :: ms
    integer :: e, ne, nper, base
    ne = size(a, 2)
    nper = 4
    if (curved) nper = 8
    m%nn = ne * nper
    allocate(m%x(2, m%nn), m%etype(ne), m%conn(max_nodes, ne), m%elem_section(ne), m%sections(1))
    allocate(m%node_id(m%nn))
    m%node_id = [(e, e = 1, m%nn)]
    m%conn = 0
    m%elem_section = 1
    if (curved) then
      m%etype = find_element_type('CPS8')
    else
      m%etype = find_element_type('CPS4')
    end if
    do e = 1, ne
      base = (e - 1) * nper
      call fill_element(m, e, base, nper, a(:, e), b(:, e), mid(:, e))
    end do
    allocate(ms%elem(ne), ms%edge(ne))
    ms%elem = [(e, e = 1, ne)]
    ms%edge = 1
  end subroutine make_model

  !> Purpose: the nodes of element e (numbers base+1..base+nper): its face
  !> S1 from pa to pb (mid-side node pm), the rest offset to one side.
  subroutine fill_element(m, e, base, nper, pa, pb, pm)
    type(model_t), intent(inout) :: m
    integer, intent(in) :: e, base, nper
    real(dp), intent(in) :: pa(2), pb(2), pm(2)
    real(dp) :: nrm(2)
    integer :: i
    m%conn(1:nper, e) = [(base + i, i = 1, nper)]
    nrm = [-(pb(2) - pa(2)), pb(1) - pa(1)]
    m%x(:, base + 1) = pa
    m%x(:, base + 2) = pb
    m%x(:, base + 3) = pb + nrm
    m%x(:, base + 4) = pa + nrm
    if (nper == 8) then
      m%x(:, base + 5) = pm
      m%x(:, base + 6) = pb + 0.5_dp * nrm
      m%x(:, base + 7) = 0.5_dp * (pa + pb) + nrm
      m%x(:, base + 8) = pa + 0.5_dp * nrm
    end if
  end subroutine fill_element

  !> Purpose: nearest_edge with and without the tree at every point of
  !> pts (also with a search distance, and skipping an element or a node);
  !> reports the first disagreement.
  subroutine compare(name, m, ms, pts)
    character(len=*), intent(in) :: name
    type(model_t), intent(in) :: m
    type(surface_t), intent(in) :: ms
    real(dp), intent(in) :: pts(:, :)
    type(edge_tree_t) :: tree
    integer :: i, b1, b2, nfound, skip_e, skip_n, pass
    real(dp) :: t1, t2, dmax
    character(len=200) :: msg
    call surface_tree(m, m%x, ms, tree)
    nfound = 0
    do i = 1, size(pts, 2)
      do pass = 1, 3
        dmax = huge(1.0_dp)
        skip_e = 0
        skip_n = 0
        if (pass == 2) dmax = 0.05_dp * rnd()
        if (pass == 3) then
          skip_e = 1 + int(rnd() * size(ms%elem))
          skip_n = m%conn(1, 1 + int(rnd() * size(ms%elem)))
        end if
        call nearest_edge(m, m%x, ms, pts(:, i), skip_n, skip_e, dmax, b1, t1)
        call nearest_edge(m, m%x, ms, pts(:, i), skip_n, skip_e, dmax, b2, t2, tree)
        if (b1 /= b2 .or. .not. (t1 == t2)) then
          write(msg, '(a,i0,a,2es24.16,a,i0,a,i0,a,i0)') 'point ', i, ' at ', pts(:, i), ' pass ', pass, &
            ': all edges give ', b1, ', the tree ', b2
          call report(name, .false., trim(msg))
          return
        end if
        if (b1 > 0) nfound = nfound + 1
      end do
    end do
    ! the comparison means something only if most points found an edge
    write(msg, '(i0,a,i0,a)') nfound, ' of ', 3 * size(pts, 2), ' searches found an edge'
    call report(name, nfound > size(pts, 2), trim(msg))
    call compare_cuts(name // ': face cuts', m, ms, tree, pts)
  end subroutine compare

  !> Purpose: face_cuts with and without the tree on straight slave faces
  !> between consecutive points of pts (and on the master's own edges,
  !> whose nodes are skipped), with and without a search distance: the
  !> same cuts, bit for bit.
  subroutine compare_cuts(name, m, ms, tree, pts)
    character(len=*), intent(in) :: name
    type(model_t), intent(in) :: m
    type(surface_t), intent(in) :: ms
    type(edge_tree_t), intent(in) :: tree
    real(dp), intent(in) :: pts(:, :)
    type(edge_t) :: ed
    real(dp), allocatable :: c1(:), c2(:)
    real(dp) :: dmax
    integer :: i, n1, n2, pass, inner
    character(len=200) :: msg
    inner = 0
    do i = 1, size(pts, 2) - 1
      if (mod(i, 3) == 0) then
        ed = get_edge(m, m%x, ms%elem(1 + mod(i, size(ms%elem))), ms%edge(1 + mod(i, size(ms%elem))))
      else
        ed = edge_t(nn=2, node=[-1, -2, 0])
        ed%x(:, 1) = pts(:, i)
        ed%x(:, 2) = pts(:, i) + (pts(:, i + 1) - pts(:, i)) * (0.05_dp + rnd())
      end if
      do pass = 1, 2
        dmax = huge(1.0_dp)
        if (pass == 2) dmax = 0.1_dp * rnd()
        call face_cuts(m, m%x, ed, ms, dmax, c1, n1)
        call face_cuts(m, m%x, ed, ms, dmax, c2, n2, tree)
        if (n1 /= n2) then
          write(msg, '(a,i0,a,i0,a,i0)') 'face ', i, ': all edges give ', n1, ' cuts, the tree ', n2
          call report(name, .false., trim(msg))
          return
        end if
        if (any(.not. (c1(1:n1) == c2(1:n2)))) then
          write(msg, '(a,i0,a)') 'face ', i, ': the cuts differ'
          call report(name, .false., trim(msg))
          return
        end if
        inner = inner + n1 - 2
      end do
    end do
    write(msg, '(i0,a)') inner, ' cuts inside the faces'
    call report(name, inner > size(pts, 2), trim(msg))
  end subroutine compare_cuts

  !> Purpose: random points about the edges (on them, on their vertices,
  !> near them on either side, and some far away) inside box lo..hi.
  function points_about(a, b, n, lo, hi) result(p)
    real(dp), intent(in) :: a(:, :), b(:, :), lo(2), hi(2)
    integer, intent(in) :: n
    real(dp) :: p(2, n), s, off(2)
    integer :: i, e
    do i = 1, n
      e = 1 + int(rnd() * size(a, 2))
      select case (mod(i, 5))
      case (0)
        p(:, i) = a(:, e)
      case (1)
        p(:, i) = lo + [rnd(), rnd()] * (hi - lo) * 1.5_dp - 0.25_dp * (hi - lo)
      case default
        s = rnd()
        off = (rnd() - 0.5_dp) * 0.2_dp * norm2(b(:, e) - a(:, e)) * [rnd() - 0.5_dp, rnd() - 0.5_dp]
        p(:, i) = a(:, e) + s * (b(:, e) - a(:, e)) + off
      end select
    end do
  end function points_about

  !> A rough profile of 2000 straight edges along x.
  subroutine rough_profile()
    integer, parameter :: ne = 2000
    real(dp) :: a(2, ne), b(2, ne), mid(2, ne), y(0:ne)
    type(model_t) :: m
    type(surface_t) :: ms
    integer :: i
    y(0) = 0.0_dp
    do i = 1, ne
      y(i) = y(i - 1) + 0.3_dp * (rnd() - 0.5_dp)
    end do
    do i = 1, ne
      ! the master runs right to left so that its outward normal is +y
      a(:, i) = [real(ne - i + 1, dp), y(ne - i + 1)]
      b(:, i) = [real(ne - i, dp), y(ne - i)]
    end do
    mid = 0.5_dp * (a + b)
    call make_model(a, b, mid, .false., m, ms)
    call compare('rough profile of 2-node edges', m, ms, &
                 points_about(a, b, 4000, [0.0_dp, minval(y)], [real(ne, dp), maxval(y)]))
  end subroutine rough_profile

  !> A circle of 200 3-node edges (the mid-side nodes on the arc).
  subroutine curved_circle()
    integer, parameter :: ne = 200
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
    call compare('circle of 3-node edges', m, ms, points_about(a, b, 3000, [-5.0_dp, -5.0_dp], [5.0_dp, 5.0_dp]))
  end subroutine curved_circle

  !> 1000 edges scattered in a square, lengths from 0.001 to 30.
  subroutine scattered_edges()
    integer, parameter :: ne = 1000
    real(dp) :: a(2, ne), b(2, ne), mid(2, ne), ang, len
    type(model_t) :: m
    type(surface_t) :: ms
    integer :: i
    do i = 1, ne
      a(:, i) = 100.0_dp * [rnd(), rnd()]
      ang = 2.0_dp * pi * rnd()
      len = 10.0_dp ** (4.5_dp * rnd() - 3.0_dp)
      b(:, i) = a(:, i) + len * [cos(ang), sin(ang)]
    end do
    mid = 0.5_dp * (a + b)
    call make_model(a, b, mid, .false., m, ms)
    call compare('scattered edges of many lengths', m, ms, &
                 points_about(a, b, 4000, [0.0_dp, 0.0_dp], [100.0_dp, 100.0_dp]))
  end subroutine scattered_edges

  !> Every edge of a polyline given twice (the copies at the end): the
  !> first of two equally near edges must win, as in the search over all.
  subroutine twice_given_edges()
    integer, parameter :: nh = 300
    real(dp) :: a(2, 2 * nh), b(2, 2 * nh), mid(2, 2 * nh)
    type(model_t) :: m
    type(surface_t) :: ms
    integer :: i
    do i = 1, nh
      a(:, i) = [real(nh - i + 1, dp), 0.5_dp * sin(0.1_dp * (nh - i + 1))]
      b(:, i) = [real(nh - i, dp), 0.5_dp * sin(0.1_dp * (nh - i))]
    end do
    a(:, nh + 1:) = a(:, 1:nh)
    b(:, nh + 1:) = b(:, 1:nh)
    mid = 0.5_dp * (a + b)
    call make_model(a, b, mid, .false., m, ms)
    call compare('edges given twice (ties)', m, ms, points_about(a, b, 3000, [0.0_dp, -0.5_dp], [real(nh, dp), 0.5_dp]))
  end subroutine twice_given_edges

  !> Near a flat surface of 20 000 edges the tree offers at most a few
  !> dozen edges per point (the search over all looks at 20 000).
  subroutine few_candidates()
    integer, parameter :: ne = 20000
    real(dp), allocatable :: a(:, :), b(:, :), mid(:, :)
    real(dp) :: p(2)
    type(model_t) :: m
    type(surface_t) :: ms
    type(edge_tree_t) :: tree
    integer, allocatable :: cand(:)
    integer :: i, ncand, most
    character(len=80) :: msg
    allocate(a(2, ne), b(2, ne), mid(2, ne))
    do i = 1, ne
      a(:, i) = [real(ne - i + 1, dp), 0.0_dp]
      b(:, i) = [real(ne - i, dp), 0.0_dp]
    end do
    mid = 0.5_dp * (a + b)
    call make_model(a, b, mid, .false., m, ms)
    call surface_tree(m, m%x, ms, tree)
    most = 0
    do i = 1, 1000
      p = [rnd() * ne, 0.1_dp * (rnd() - 0.5_dp)]
      call tree_candidates(tree, p, tree%step, cand, ncand)
      most = max(most, ncand)
    end do
    write(msg, '(a,i0)') 'most candidates within one edge length: ', most
    call report('the tree looks at few edges', most >= 1 .and. most <= 8, trim(msg))
  end subroutine few_candidates
end program test_search
