!> The contact search's spatial index: a bounding-volume tree over the
!> edges of a master surface, so that the nearest master edge of a slave
!> point is found among the few edges near it rather than among all of
!> them (issue 32: the search was O(slave points x master edges), 115 s
!> of a 50 000-point rough surface's 207 s).
!>
!> Each edge gets a box that holds every point a projection onto it may
!> return: the corners and, for a 3-node edge, the control point of the
!> same curve written as a quadratic Bezier curve (the curve lies in the
!> triangle of its control points), grown by the edge_tol extension
!> beyond its ends and by a rounding margin. The tree splits the edges at
!> the median of their box centres along the longer side, down to leaves
!> of leaf_size edges.
!>
!> The answer does not change: nearest_edge still takes, among the edges
!> that accept the point, the first (lowest index) of the smallest |d|.
!> It looks at every edge whose box is within a radius r of the point, in
!> the order of their indices, and grows r until the best |d| found is at
!> most r: an edge that accepts the point at distance |d| has the foot of
!> the projection in its box, so every edge with |d| <= r was looked at.
!> (For a 3-node edge |d| is the distance to the foot when the projection's
!> Newton iteration converged, as it does for points near the edge.)
module edge_tree
  use kinds, only: dp
  use growable, only: append
  use model, only: model_t, surface_t
  use contact_geometry, only: edge_t, get_edge, edge_at, project_to_edge, project_to_chord, edge_length
  implicit none
  private
  public :: edge_tree_t, surface_tree, refit_tree, boxes_tree, nearest_edge, edge_tol, tree_candidates, slab_candidates, &
            sort_ints

  !> A projection this far outside [0, 1] along an edge still counts: it
  !> catches slave nodes exactly above a master vertex.
  real(dp), parameter :: edge_tol = 1.0e-6_dp
  !> Edges in a leaf of the tree.
  integer, parameter :: leaf_size = 4

  type :: edge_tree_t
    integer :: n = 0                       ! edges (of the surface, in its order)
    integer :: nnode = 0                   ! tree nodes; node 1 is the root
    real(dp), allocatable :: ebox(:, :)    ! (4, n): xmin, ymin, xmax, ymax of each edge
    real(dp), allocatable :: box(:, :)     ! (4, nnode): the same of each tree node
    integer, allocatable :: first(:), last(:)  ! node's edges: perm(first:last)
    integer, allocatable :: left(:)        ! its first child (the second is left + 1), 0 at a leaf
    integer, allocatable :: perm(:)        ! edge indices, grouped by node
    real(dp) :: step = 0.0_dp              ! mean box size: the first radius and its growth
    !> the edges themselves (surface_tree; not for boxes_tree's items), so
    !> that a search judges them without making each again (get_edge)
    type(edge_t), allocatable :: ed(:)
    !> each straight edge's unit tangent and length (chord(1:2, j) and
    !> chord(3, j), for its projections: project_to_chord)
    real(dp), allocatable :: chord(:, :)
    !> every edge straight (2 nodes), and the longest chord: an edge that
    !> takes a point at |d| then has the foot within |d| of it, and |d| is
    !> at most the larger of the search distance and half the chord (judge)
    logical :: straight = .false.
    real(dp) :: longest = 0.0_dp
    !> every coordinate finite: else the searches look at every edge (a
    !> projection onto an edge with a NaN is judged there as before)
    logical :: finite = .true.
    !> spread_ratio when the tree was built (refit_tree builds it again
    !> once its nodes' boxes have loosened by half)
    real(dp) :: spread0 = 0.0_dp
    !> the largest magnitude of a coordinate of the edges (edge_boxes)
    real(dp) :: scale = 0.0_dp
    !> The neighbours of each edge (refit_tree's, for the hints of a
    !> re-search): nbr(nbr_first(h):nbr_first(h + 1) - 1) are the other
    !> edges whose boxes were within gap of edge h's box when they were
    !> listed, with the boxes then (ebox_ref); eps bounds how far a box
    !> coordinate has moved since, apart from a common translation.
    integer, allocatable :: nbr_first(:), nbr(:)
    real(dp), allocatable :: ebox_ref(:, :)
    real(dp) :: gap = 0.0_dp, eps = huge(1.0_dp)
  end type edge_tree_t

contains

  !> Purpose: the tree of the edges of element surface ms in configuration x.
  !> Arguments: tree returns it (empty for a surface without edges).
  subroutine surface_tree(m, x, ms, tree)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :)
    type(surface_t), intent(in) :: ms
    type(edge_tree_t), intent(out) :: tree
    integer :: j
    tree%n = size(ms%elem)
    allocate(tree%ebox(4, tree%n), tree%ed(tree%n))
    do j = 1, tree%n
      tree%ed(j) = get_edge(m, x, ms%elem(j), ms%edge(j))
    end do
    call edge_boxes(tree)
    call build_tree(tree)
    tree%spread0 = spread_ratio(tree)
  end subroutine surface_tree

  !> Purpose: the tree of surface ms moved to configuration x: its edges
  !> take the nodes' coordinates in x, their boxes are made again and
  !> every tree node's box is the union of its children's (a refit: the
  !> grouping of the edges stays). The candidates of a radius are then
  !> those of a tree built on x (the edges whose box is within it, in
  !> index order: the grouping only prunes), so a search answers as on a
  !> new tree, to the bit (the root box and the mean box size are the
  !> same numbers too), without its sort: UPDATE SEARCH pairs again at
  !> every increment, and the sort was two thirds of a new tree. The
  !> tree is built again where the grouping has become loose (its nodes'
  !> boxes, against its edges', have grown by half since it was built:
  !> the surface deformed, not only moved) or where it is not that of ms
  !> (its edge count).
  !> Arguments: tree in: a tree of ms (surface_tree), or an empty one;
  !> out: the tree of ms in x.
  subroutine refit_tree(m, x, ms, tree)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :)
    type(surface_t), intent(in) :: ms
    type(edge_tree_t), intent(inout) :: tree
    integer :: j, k
    if (tree%n /= size(ms%elem) .or. tree%n == 0 .or. .not. allocated(tree%ed) .or. .not. allocated(tree%perm)) then
      call surface_tree(m, x, ms, tree)
      return
    end if
    do j = 1, tree%n
      do k = 1, tree%ed(j)%nn
        tree%ed(j)%x(:, k) = x(:, tree%ed(j)%node(k))
      end do
    end do
    call edge_boxes(tree)
    tree%step = sum(tree%ebox(3:4, :) - tree%ebox(1:2, :)) / (2 * tree%n)
    call refit_boxes(tree)
    if (.not. spread_ratio(tree) <= 1.5_dp * tree%spread0) then
      deallocate(tree%perm, tree%box, tree%first, tree%last, tree%left)
      call build_tree(tree)
      tree%spread0 = spread_ratio(tree)
    end if
    ! the neighbour lists, listed again once the boxes have moved (apart
    ! from a common translation) by a sixth of the gap they were listed with
    tree%eps = box_motion(tree)
    if (.not. tree%eps <= tree%gap / 6.0_dp) call list_neighbours(tree)
  end subroutine refit_tree

  !> Purpose: how far the edges' boxes have moved since their neighbours
  !> were listed (ebox_ref), apart from the translation of the first box's
  !> lower corner: the largest change of a box coordinate (huge without
  !> lists).
  pure real(dp) function box_motion(tree) result(eps)
    type(edge_tree_t), intent(in) :: tree
    real(dp) :: v(2)
    integer :: j
    eps = huge(1.0_dp)
    if (.not. allocated(tree%nbr_first) .or. tree%n == 0) return
    if (size(tree%ebox_ref, 2) /= tree%n) return
    v = tree%ebox(1:2, 1) - tree%ebox_ref(1:2, 1)
    eps = 0.0_dp
    do j = 1, tree%n
      eps = max(eps, abs(tree%ebox(1, j) - tree%ebox_ref(1, j) - v(1)), abs(tree%ebox(2, j) - tree%ebox_ref(2, j) - v(2)), &
                abs(tree%ebox(3, j) - tree%ebox_ref(3, j) - v(1)), abs(tree%ebox(4, j) - tree%ebox_ref(4, j) - v(2)))
    end do
    if (.not. eps <= huge(1.0_dp)) eps = huge(1.0_dp)
  end function box_motion

  !> Purpose: the neighbour lists of the tree's edges (edge_tree_t's nbr):
  !> for each edge the other edges whose boxes lie within the gap of its
  !> box, the gap four mean box sizes (a little more in the comparison,
  !> for its rounding: a few edges each way along a surface, and a sixth of
  !> it the motion the lists outlast), the boxes kept as ebox_ref.
  subroutine list_neighbours(tree)
    type(edge_tree_t), intent(inout) :: tree
    integer :: stack(128), ns, k, i, e, h, nn
    real(dp) :: g2
    tree%gap = 4.0_dp * tree%step
    g2 = (tree%gap * (1.0_dp + 1.0e-9_dp) + 1.0e-13_dp * tree%scale)**2
    tree%ebox_ref = tree%ebox
    if (allocated(tree%nbr_first)) deallocate(tree%nbr_first)
    allocate(tree%nbr_first(tree%n + 1))
    if (.not. allocated(tree%nbr)) allocate(tree%nbr(4 * tree%n))
    nn = 0
    do h = 1, tree%n
      tree%nbr_first(h) = nn + 1
      ns = 1
      stack(1) = 1
      do while (ns > 0)
        k = stack(ns)
        ns = ns - 1
        if (.not. box_gap2(tree%box(:, k), tree%ebox(:, h)) <= g2) cycle
        if (tree%left(k) > 0) then
          stack(ns + 1:ns + 2) = [tree%left(k), tree%left(k) + 1]
          ns = ns + 2
          cycle
        end if
        do i = tree%first(k), tree%last(k)
          e = tree%perm(i)
          if (e == h .or. .not. box_gap2(tree%ebox(:, e), tree%ebox(:, h)) <= g2) cycle
          call append(tree%nbr, nn, e)
        end do
      end do
    end do
    tree%nbr_first(tree%n + 1) = nn + 1
    tree%eps = 0.0_dp
  end subroutine list_neighbours

  !> Purpose: the squared distance between boxes a and b (xmin, ymin,
  !> xmax, ymax); 0 where they meet.
  pure real(dp) function box_gap2(a, b) result(g2)
    real(dp), intent(in) :: a(4), b(4)
    real(dp) :: dx, dy
    dx = max(a(1) - b(3), 0.0_dp, b(1) - a(3))
    dy = max(a(2) - b(4), 0.0_dp, b(2) - a(4))
    g2 = dx * dx + dy * dy
  end function box_gap2

  !> Purpose: the boxes of the tree's edges tree%ed (in their
  !> configuration), and whether all are straight, the longest chord and
  !> whether every box is finite. Each box holds the corners and, for a
  !> 3-node edge, the Bezier control point, grown by the edge_tol extension
  !> and a rounding margin.
  subroutine edge_boxes(tree)
    type(edge_tree_t), intent(inout) :: tree
    real(dp) :: p(2), d0(2), d1(2), pts(2, 3), lo(2), hi(2), grow, scale, len
    integer :: j, np, q
    logical :: fin
    if (.not. allocated(tree%chord)) allocate(tree%chord(3, tree%n))
    scale = 0.0_dp
    fin = .true.
    tree%straight = .true.
    tree%longest = 0.0_dp
    do j = 1, tree%n
      associate(ed => tree%ed(j))
        len = edge_length(ed)
        tree%straight = tree%straight .and. ed%nn == 2
        tree%longest = max(tree%longest, len)
        pts(:, 1:2) = ed%x(:, 1:2)
        np = 2
        if (ed%nn == 3) then
          ! the Bezier control point of the quadratic edge
          pts(:, 3) = 2.0_dp * ed%x(:, 3) - 0.5_dp * (ed%x(:, 1) + ed%x(:, 2))
          np = 3
          call edge_at(ed, 0.0_dp, p, d0)
          call edge_at(ed, 1.0_dp, p, d1)
          ! the feet at t in [-edge_tol, 1 + edge_tol]: |p'| bounds the extension
          grow = 2.0_dp * edge_tol * max(norm2(d0), norm2(d1))
        else
          ! (p' is the chord)
          grow = 2.0_dp * edge_tol * len
          tree%chord(1:2, j) = (ed%x(:, 2) - ed%x(:, 1)) / len
          tree%chord(3, j) = len
        end if
      end associate
      lo = pts(:, 1)
      hi = pts(:, 1)
      do q = 1, np
        lo = min(lo, pts(:, q))
        hi = max(hi, pts(:, q))
        scale = max(scale, abs(pts(1, q)), abs(pts(2, q)))
        fin = fin .and. abs(pts(1, q)) <= huge(1.0_dp) .and. abs(pts(2, q)) <= huge(1.0_dp)
      end do
      tree%ebox(1:2, j) = lo - grow
      tree%ebox(3:4, j) = hi + grow
    end do
    ! rounding of the projection: far below any edge of a sound mesh
    tree%ebox(1:2, :) = tree%ebox(1:2, :) - 1.0e-10_dp * scale
    tree%ebox(3:4, :) = tree%ebox(3:4, :) + 1.0e-10_dp * scale
    tree%finite = fin .and. abs(scale) <= huge(1.0_dp) .and. all(abs(tree%ebox) <= huge(1.0_dp))
    tree%scale = scale
  end subroutine edge_boxes

  !> Purpose: every tree node's box from its edges' boxes (a leaf) or its
  !> children's (the same numbers as build_tree's: min and max are exact).
  !> Children are numbered after their parent, so a pass from the last
  !> node to the first meets them first.
  subroutine refit_boxes(tree)
    type(edge_tree_t), intent(inout) :: tree
    integer :: k, a, b, l, i
    do k = tree%nnode, 1, -1
      a = tree%first(k)
      b = tree%last(k)
      l = tree%left(k)
      if (b < a) then
        tree%box(:, k) = [huge(1.0_dp), huge(1.0_dp), -huge(1.0_dp), -huge(1.0_dp)]
      else if (l == 0) then
        tree%box(:, k) = tree%ebox(:, tree%perm(a))
        do i = a + 1, b
          tree%box(1:2, k) = min(tree%box(1:2, k), tree%ebox(1:2, tree%perm(i)))
          tree%box(3:4, k) = max(tree%box(3:4, k), tree%ebox(3:4, tree%perm(i)))
        end do
      else
        tree%box(1:2, k) = min(tree%box(1:2, l), tree%box(1:2, l + 1))
        tree%box(3:4, k) = max(tree%box(3:4, l), tree%box(3:4, l + 1))
      end if
    end do
  end subroutine refit_boxes

  !> Purpose: how loosely the tree groups its edges: the sum of its nodes'
  !> box sizes (width plus height) over the sum of its edges'. Neither a
  !> rigid motion nor a uniform stretch of the surface changes it.
  pure real(dp) function spread_ratio(tree) result(q)
    type(edge_tree_t), intent(in) :: tree
    real(dp) :: se
    integer :: k
    q = 0.0_dp
    do k = 1, tree%nnode
      if (tree%last(k) < tree%first(k)) cycle
      q = q + (tree%box(3, k) - tree%box(1, k)) + (tree%box(4, k) - tree%box(2, k))
    end do
    se = sum(tree%ebox(3:4, :) - tree%ebox(1:2, :))
    q = q / se
  end function spread_ratio

  !> Purpose: a tree over boxes given by the caller (ebox(1:2, j) the lower
  !> and ebox(3:4, j) the upper corner of item j), for tree_candidates:
  !> the items whose box holds a point are those within radius 0.
  !> Arguments: tree returns it; finite says whether every box was finite
  !> (a caller then searches all items otherwise).
  subroutine boxes_tree(ebox, tree)
    real(dp), intent(in) :: ebox(:, :)
    type(edge_tree_t), intent(out) :: tree
    tree%n = size(ebox, 2)
    tree%ebox = ebox
    tree%finite = all(abs(ebox) <= huge(1.0_dp))
    call build_tree(tree)
  end subroutine boxes_tree

  !> Purpose: the tree's nodes from the edge boxes tree%ebox: each node's
  !> edges split at the median of their centres along the longer side of
  !> the node's box, until leaf_size edges remain.
  subroutine build_tree(tree)
    type(edge_tree_t), intent(inout) :: tree
    integer, allocatable :: todo(:)
    real(dp), allocatable :: key(:)
    integer :: j, k, ntodo, a, b, axis
    allocate(tree%perm(tree%n), key(tree%n), todo(2 * tree%n + 1))
    tree%perm = [(j, j = 1, tree%n)]
    allocate(tree%box(4, 2 * tree%n + 1), tree%first(2 * tree%n + 1), tree%last(2 * tree%n + 1), &
             tree%left(2 * tree%n + 1))
    tree%step = 0.0_dp
    if (tree%n > 0) tree%step = sum(tree%ebox(3:4, :) - tree%ebox(1:2, :)) / (2 * tree%n)
    tree%nnode = 1
    tree%first(1) = 1
    tree%last(1) = tree%n
    ntodo = 1
    todo(1) = 1
    do while (ntodo > 0)
      k = todo(ntodo)
      ntodo = ntodo - 1
      a = tree%first(k)
      b = tree%last(k)
      tree%left(k) = 0
      if (b < a) then
        tree%box(:, k) = [huge(1.0_dp), huge(1.0_dp), -huge(1.0_dp), -huge(1.0_dp)]
        cycle
      end if
      tree%box(1:2, k) = minval(tree%ebox(1:2, tree%perm(a:b)), dim=2)
      tree%box(3:4, k) = maxval(tree%ebox(3:4, tree%perm(a:b)), dim=2)
      if (b - a + 1 <= leaf_size) cycle
      axis = 1
      if (tree%box(4, k) - tree%box(2, k) > tree%box(3, k) - tree%box(1, k)) axis = 2
      key(a:b) = tree%ebox(axis, tree%perm(a:b)) + tree%ebox(axis + 2, tree%perm(a:b))
      call sort_by_key(key(a:b), tree%perm(a:b))
      tree%left(k) = tree%nnode + 1
      tree%first(tree%nnode + 1) = a
      tree%last(tree%nnode + 1) = (a + b) / 2
      tree%first(tree%nnode + 2) = (a + b) / 2 + 1
      tree%last(tree%nnode + 2) = b
      todo(ntodo + 1:ntodo + 2) = [tree%nnode + 1, tree%nnode + 2]
      ntodo = ntodo + 2
      tree%nnode = tree%nnode + 2
    end do
  end subroutine build_tree

  !> Purpose: heap sort of idx by key (ascending key; the order of equal
  !> keys does not matter: the tree only groups edges).
  pure subroutine sort_by_key(key, idx)
    real(dp), intent(inout) :: key(:)
    integer, intent(inout) :: idx(:)
    integer :: n, i
    n = size(key)
    do i = n / 2, 1, -1
      call sift(key, idx, i, n)
    end do
    do i = n, 2, -1
      call swap(key, idx, 1, i)
      call sift(key, idx, 1, i - 1)
    end do
  end subroutine sort_by_key

  !> Purpose: moves entry i down the heap key(1:n) (largest at the top).
  pure subroutine sift(key, idx, i, n)
    real(dp), intent(inout) :: key(:)
    integer, intent(inout) :: idx(:)
    integer, intent(in) :: i, n
    integer :: p, c
    p = i
    do
      c = 2 * p
      if (c > n) exit
      if (c < n) then
        if (key(c + 1) > key(c)) c = c + 1
      end if
      if (.not. key(c) > key(p)) exit
      call swap(key, idx, p, c)
      p = c
    end do
  end subroutine sift

  !> Purpose: exchanges entries i and j of key and idx.
  pure subroutine swap(key, idx, i, j)
    real(dp), intent(inout) :: key(:)
    integer, intent(inout) :: idx(:)
    integer, intent(in) :: i, j
    real(dp) :: tk
    integer :: ti
    tk = key(i)
    key(i) = key(j)
    key(j) = tk
    ti = idx(i)
    idx(i) = idx(j)
    idx(j) = ti
  end subroutine swap

  !> Purpose: distance from point p to the box b (xmin, ymin, xmax, ymax);
  !> 0 inside.
  pure real(dp) function box_distance(b, p)
    real(dp), intent(in) :: b(4), p(2)
    real(dp) :: dx, dy
    dx = max(b(1) - p(1), 0.0_dp, p(1) - b(3))
    dy = max(b(2) - p(2), 0.0_dp, p(2) - b(4))
    box_distance = sqrt(dx * dx + dy * dy)
  end function box_distance

  !> Purpose: is box b (xmin, ymin, xmax, ymax) within distance r of point
  !> p? The squared distances are compared (no root per box of a search).
  !> A box whose edge takes a point at |d| <= r holds the foot with the
  !> rounding margin around it (surface_tree), so the last bits of either
  !> comparison cannot leave out an edge the search needs.
  pure logical function box_within(b, p, r2)
    real(dp), intent(in) :: b(4), p(2), r2     ! r2 = r**2
    real(dp) :: dx, dy
    dx = max(b(1) - p(1), 0.0_dp, p(1) - b(3))
    dy = max(b(2) - p(2), 0.0_dp, p(2) - b(4))
    box_within = dx * dx + dy * dy <= r2
  end function box_within

  !> Purpose: the edges whose box is within distance r of point p, in
  !> ascending order of their index (the order of a search over all).
  !> Arguments: cand(1:ncand) returns them (grown as needed).
  subroutine tree_candidates(tree, p, r, cand, ncand)
    type(edge_tree_t), intent(in) :: tree
    real(dp), intent(in) :: p(2), r
    integer, allocatable, intent(inout) :: cand(:)
    integer, intent(out) :: ncand
    integer :: stack(128), ns, k, i, j
    real(dp) :: r2
    if (.not. allocated(cand)) allocate(cand(32))   ! (callers read cand(1:ncand))
    ncand = 0
    if (tree%n == 0 .or. .not. r >= 0.0_dp) return
    r2 = r * r
    ns = 1
    stack(1) = 1
    do while (ns > 0)
      k = stack(ns)
      ns = ns - 1
      if (.not. box_within(tree%box(:, k), p, r2)) cycle
      if (tree%left(k) > 0) then
        stack(ns + 1:ns + 2) = [tree%left(k), tree%left(k) + 1]
        ns = ns + 2
        cycle
      end if
      do i = tree%first(k), tree%last(k)
        j = tree%perm(i)
        if (.not. box_within(tree%ebox(:, j), p, r2)) cycle
        if (ncand < size(cand)) then
          ncand = ncand + 1
          cand(ncand) = j
        else
          call append(cand, ncand, j)
        end if
      end do
    end do
    call sort_ints(cand(1:ncand))
  end subroutine tree_candidates

  !> Purpose: the edges whose box meets the strip of the points y with
  !> lo <= (y - o) . u <= hi and |(y - o) . v| <= dv (u, v unit vectors;
  !> dv = huge: no limit), in ascending order of their index. The corners
  !> of master edges that project onto a straight slave face (face_cuts)
  !> lie in such a strip.
  !> Arguments: cand(1:ncand) returns them (grown as needed).
  subroutine slab_candidates(tree, o, u, lo, hi, v, dv, cand, ncand)
    type(edge_tree_t), intent(in) :: tree
    real(dp), intent(in) :: o(2), u(2), lo, hi, v(2), dv
    integer, allocatable, intent(inout) :: cand(:)
    integer, intent(out) :: ncand
    integer :: stack(128), ns, k, i, j
    if (.not. allocated(cand)) allocate(cand(32))   ! (callers read cand(1:ncand))
    ncand = 0
    if (tree%n == 0) return
    ns = 1
    stack(1) = 1
    do while (ns > 0)
      k = stack(ns)
      ns = ns - 1
      if (.not. box_meets(tree%box(:, k), o, u, lo, hi, v, dv)) cycle
      if (tree%left(k) > 0) then
        stack(ns + 1:ns + 2) = [tree%left(k), tree%left(k) + 1]
        ns = ns + 2
        cycle
      end if
      do i = tree%first(k), tree%last(k)
        j = tree%perm(i)
        if (.not. box_meets(tree%ebox(:, j), o, u, lo, hi, v, dv)) cycle
        call append(cand, ncand, j)
      end do
    end do
    call sort_ints(cand(1:ncand))
  end subroutine slab_candidates

  !> Purpose: does box b meet both strips of slab_candidates? (Each tested on its
  !> own: a box that meets both but not their crossing is kept, which
  !> only costs a projection.)
  pure logical function box_meets(b, o, u, lo, hi, v, dv)
    real(dp), intent(in) :: b(4), o(2), u(2), lo, hi, v(2), dv
    real(dp) :: c(2), hw(2), su, ru, sv, rv
    c = 0.5_dp * (b(1:2) + b(3:4)) - o
    hw = 0.5_dp * (b(3:4) - b(1:2))
    su = dot_product(c, u)
    ru = hw(1) * abs(u(1)) + hw(2) * abs(u(2))
    sv = dot_product(c, v)
    rv = hw(1) * abs(v(1)) + hw(2) * abs(v(2))
    box_meets = su + ru >= lo .and. su - ru <= hi .and. abs(sv) - rv <= dv
  end function box_meets

  !> Purpose: ascending sort of a few integers (insertion; the candidate
  !> lists are short), longer lists by the heap sort.
  pure subroutine sort_ints(a)
    integer, intent(inout) :: a(:)
    real(dp), allocatable :: key(:)
    integer :: i, j, v
    if (size(a) > 64) then
      key = real(a, dp)
      call sort_by_key(key, a)
      return
    end if
    do i = 2, size(a)
      v = a(i)
      j = i - 1
      do while (j >= 1)
        if (a(j) <= v) exit
        a(j + 1) = a(j)
        j = j - 1
      end do
      a(j + 1) = v
    end do
  end subroutine sort_ints

  !> Purpose: the master edge (index into the master surface) on which the
  !> orthogonal projection of point xs falls, nearest first (the lowest
  !> index among equally near ones); 0 if none.
  !> Arguments: x configuration searched, skip_node a slave node (edges
  !> through it are skipped) and skip_elem a slave element (its edges are
  !> skipped), 0 for none; dmax search distance, tbest the projection's
  !> position along the edge; tree, if present, the tree of ms in x
  !> (surface_tree): the same answer from the edges near xs only; hint,
  !> with the tree, an edge to try first (the point's edge of the last
  !> search; 0 for none): where it takes the point at |d|, the first
  !> radius is |d| (every edge nearer has its box within it), so that a
  !> point that stays on its edge is answered from the few edges whose
  !> boxes reach it. The answer is the same with any hint.
  subroutine nearest_edge(m, x, ms, xs, skip_node, skip_elem, dmax, best, tbest, tree, hint, work)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :), xs(2), dmax
    type(surface_t), intent(in) :: ms
    integer, intent(in) :: skip_node, skip_elem
    integer, intent(out) :: best
    real(dp), intent(out) :: tbest
    type(edge_tree_t), intent(in), optional :: tree
    integer, intent(in), optional :: hint
    integer, allocatable, intent(inout), optional :: work(:)
    integer, allocatable :: cand(:)
    integer :: j, hs
    real(dp) :: dbest, rall
    logical :: found
    best = 0
    tbest = 0.0_dp
    dbest = huge(1.0_dp)
    rall = -1.0_dp
    if (present(tree)) then
      if (tree%n == size(ms%elem) .and. tree%n > 0 .and. tree%finite) rall = reach_all(tree, xs)
    end if
    if (.not. (rall >= 0.0_dp .and. rall <= huge(1.0_dp))) then
      ! no tree, or a point or box that is not finite: every edge
      do j = 1, size(ms%elem)
        call judge(m, x, ms, j, xs, skip_node, skip_elem, dmax, best, tbest, dbest)
      end do
      return
    end if
    hs = 0
    if (present(hint)) hs = hint
    if (present(work)) call move_alloc(work, cand)
    call tree_search(m, x, ms, xs, skip_node, skip_elem, dmax, tree, hs, rall, cand, best, tbest, found)
    if (present(work)) call move_alloc(cand, work)
    if (found) return
    ! a radius that takes in every edge (or one that is not finite)
    do j = 1, size(ms%elem)
      call judge(m, x, ms, j, xs, skip_node, skip_elem, dmax, best, tbest, dbest, tree)
    end do
  end subroutine nearest_edge

  !> Purpose: nearest_edge's search on the tree: the edges whose boxes are
  !> within a radius r of xs are judged, r growing until the best |d| is
  !> at most r (then every nearer edge was judged) or r passes the
  !> farthest an edge takes a point from (none takes it).
  !> Arguments: hint an edge to try first (0: none); rall a radius that
  !> takes in every edge; cand a work list; best, tbest the answer where
  !> found, which is false where r reached rall first (best 0: the caller
  !> judges every edge).
  subroutine tree_search(m, x, ms, xs, skip_node, skip_elem, dmax, tree, hint, rall, cand, best, tbest, found)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :), xs(2), dmax, rall
    type(surface_t), intent(in) :: ms
    integer, intent(in) :: skip_node, skip_elem, hint
    type(edge_tree_t), intent(in) :: tree
    integer, allocatable, intent(inout) :: cand(:)
    integer, intent(out) :: best
    real(dp), intent(out) :: tbest
    logical, intent(out) :: found
    integer :: j, ncand, hbest
    real(dp) :: dbest, r, rlim, htbest, hdbest
    found = .true.
    ! no edge takes the point at |d| > rlim (judge): a point farther than
    ! that from every edge (a slave node beyond the search distance) is
    ! answered without judging all of them
    rlim = huge(1.0_dp)
    if (tree%straight) rlim = max(dmax, 0.5_dp * tree%longest)
    r = box_distance(tree%box(:, 1), xs) + tree%step
    ! the hint's verdict, judged once: the best so far of every pass below
    ! (judge keeps the lowest index of the least |d| whatever the order)
    hbest = 0
    htbest = 0.0_dp
    hdbest = huge(1.0_dp)
    if (hint > 0 .and. hint <= tree%n) then
      call judge(m, x, ms, hint, xs, skip_node, skip_elem, dmax, hbest, htbest, hdbest, tree)
      if (hbest > 0) r = min(r, hdbest)
    end if
    if (hbest > 0) then
      call hint_neighbours(m, x, ms, xs, skip_node, skip_elem, dmax, tree, hbest, htbest, hdbest, best, tbest)
      if (best > 0) return
    end if
    do while (r < rall)
      best = hbest
      tbest = htbest
      dbest = hdbest
      call tree_candidates(tree, xs, r, cand, ncand)
      do j = 1, ncand
        if (cand(j) == hbest) cycle
        call judge(m, x, ms, cand(j), xs, skip_node, skip_elem, dmax, best, tbest, dbest, tree)
      end do
      ! every edge with |d| <= r was judged
      if (best > 0 .and. dbest <= r) return
      best = 0
      tbest = 0.0_dp
      if (r >= rlim) return
      r = 2.0_dp * r + tree%step
    end do
    best = 0
    tbest = 0.0_dp
    found = .false.
  end subroutine tree_search

  !> Purpose: tree_search's answer from the neighbours of the hint's edge h
  !> (nbr), which takes xs at |d| = dh, where they hold every edge whose
  !> box is within dh of xs: such a box is within 2 dh of h's box (which
  !> holds the foot), and the boxes have moved by at most eps since they
  !> were listed (apart from a common translation, which moves no distance
  !> between them), so it was within 2 dh + 2 sqrt(2) eps of h's then: in
  !> the list where that is at most the gap it was listed with (2.1 dh +
  !> 3 eps and a rounding margin: not the last bits). Those whose box is
  !> within dh are judged (judge keeps the lowest index of the least |d| in
  !> any order). best 0: the lists do not answer (the caller's tree search).
  !> Arguments: h, th, dh the hint's verdict (judge); best, tbest returned.
  subroutine hint_neighbours(m, x, ms, xs, skip_node, skip_elem, dmax, tree, h, th, dh, best, tbest)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :), xs(2), dmax, th, dh
    type(surface_t), intent(in) :: ms
    integer, intent(in) :: skip_node, skip_elem, h
    type(edge_tree_t), intent(in) :: tree
    integer, intent(out) :: best
    real(dp), intent(out) :: tbest
    real(dp) :: dbest, r2
    integer :: q, e
    best = 0
    tbest = 0.0_dp
    if (.not. allocated(tree%nbr_first)) return
    ! (each term on its own first: no overflow of a huge one)
    if (.not. (dh <= tree%gap .and. tree%eps <= tree%gap .and. tree%scale <= huge(1.0_dp) / 2)) return
    if (.not. 2.1_dp * dh + 3.0_dp * tree%eps + 1.0e-12_dp * tree%scale <= tree%gap) return
    best = h
    tbest = th
    dbest = dh
    r2 = dh * dh
    do q = tree%nbr_first(h), tree%nbr_first(h + 1) - 1
      e = tree%nbr(q)
      if (box_within(tree%ebox(:, e), xs, r2)) &
        call judge(m, x, ms, e, xs, skip_node, skip_elem, dmax, best, tbest, dbest, tree)
    end do
  end subroutine hint_neighbours

  !> Purpose: the farthest distance from p to a point of the tree's root
  !> box: a radius that takes in every edge.
  pure real(dp) function reach_all(tree, p)
    type(edge_tree_t), intent(in) :: tree
    real(dp), intent(in) :: p(2)
    real(dp) :: dx, dy
    dx = max(abs(p(1) - tree%box(1, 1)), abs(p(1) - tree%box(3, 1)))
    dy = max(abs(p(2) - tree%box(2, 1)), abs(p(2) - tree%box(4, 1)))
    reach_all = sqrt(dx * dx + dy * dy)
  end function reach_all

  !> Purpose: whether edge j of ms takes point xs, and whether it is nearer
  !> than the best so far (best, tbest, dbest = |d|, updated; as near and
  !> of a lower index also counts, so that the lowest index of the least
  !> |d| wins in any order of judging): its
  !> projection falls on it (within edge_tol), xs is not behind it by more
  !> than half its length (the far side of the master body) nor farther
  !> than dmax in front. Edges of skip_elem and through skip_node are not.
  !> tree, if present, holds the edge made on x (surface_tree).
  subroutine judge(m, x, ms, j, xs, skip_node, skip_elem, dmax, best, tbest, dbest, tree)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :), xs(2), dmax
    type(surface_t), intent(in) :: ms
    integer, intent(in) :: j, skip_node, skip_elem
    integer, intent(inout) :: best
    real(dp), intent(inout) :: tbest, dbest
    type(edge_tree_t), intent(in), optional :: tree
    if (ms%elem(j) == skip_elem) return
    if (present(tree)) then
      if (allocated(tree%ed)) then
        ! the tree's edge, and a straight one's chord (edge_boxes)
        if (tree%ed(j)%nn == 2) then
          call judge_edge(tree%ed(j), j, xs, skip_node, dmax, best, tbest, dbest, tree%chord(:, j))
        else
          call judge_edge(tree%ed(j), j, xs, skip_node, dmax, best, tbest, dbest)
        end if
        return
      end if
    end if
    call judge_edge(get_edge(m, x, ms%elem(j), ms%edge(j)), j, xs, skip_node, dmax, best, tbest, dbest)
  end subroutine judge

  !> Purpose: judge's verdict on edge ed (index j): its projection of xs
  !> (project_to_edge; for a straight edge given chord = its unit tangent
  !> and length, the same numbers from them) must fall on it, xs not
  !> behind it by more than half its length nor farther than dmax in
  !> front, nor the edge through skip_node.
  subroutine judge_edge(ed, j, xs, skip_node, dmax, best, tbest, dbest, chord)
    type(edge_t), intent(in) :: ed
    integer, intent(in) :: j, skip_node
    real(dp), intent(in) :: xs(2), dmax
    integer, intent(inout) :: best
    real(dp), intent(inout) :: tbest, dbest
    real(dp), intent(in), optional :: chord(3)
    real(dp) :: nvec(2), t, d, len
    if (any(ed%node(1:ed%nn) == skip_node)) return
    if (present(chord)) then
      call project_to_chord(ed%x(:, 1), chord(1:2), chord(3), xs, t, nvec, d)
      len = chord(3)
    else
      call project_to_edge(ed, xs, t, nvec, d)
      len = -1.0_dp
    end if
    if (t < -edge_tol .or. t > 1.0_dp + edge_tol) return
    t = min(max(t, 0.0_dp), 1.0_dp)
    if (d < 0.0_dp) then
      ! (the chord's length where the point is behind the edge)
      if (len < 0.0_dp) len = edge_length(ed)
      if (d < -0.5_dp * len) return
    end if
    if (d > dmax) return
    if (abs(d) < dbest .or. (abs(d) == dbest .and. j < best)) then
      dbest = abs(d)
      best = j
      tbest = t
    end if
  end subroutine judge_edge
end module edge_tree
