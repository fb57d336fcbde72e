!> Fill-reducing orderings: reverse Cuthill-McKee of a graph given in
!> compressed form, with a pseudo-peripheral starting node per connected
!> component (the skyline's numbering), and METIS nested dissection of a
!> symmetric matrix's pattern (for CHOLMOD).
module ordering
  use, intrinsic :: iso_c_binding, only: c_int, c_null_ptr
  use metis_binding, only: metis_nodend, metis_setdefaultoptions, metis_noptions, metis_ok
  use messages, only: fatal
  use strings, only: itoa
  implicit none
  private
  public :: rcm_order, metis_order

contains

  !> perm(new) = old. xadj/adj: neighbours of node i are adj(xadj(i):xadj(i+1)-1).
  !> Each connected component is numbered from a pseudo-peripheral node by
  !> Cuthill-McKee and reversed.
  subroutine rcm_order(n, xadj, adj, perm)
    integer, intent(in) :: n, xadj(:), adj(:)
    integer, intent(out) :: perm(n)
    logical, allocatable :: done(:)
    integer, allocatable :: deg(:)
    integer :: nordered, i, first_in_comp
    allocate(done(n), deg(n))
    do i = 1, n
      deg(i) = xadj(i + 1) - xadj(i)
    end do
    done = .false.
    nordered = 0
    do i = 1, n
      if (done(i)) cycle
      first_in_comp = nordered + 1
      call cuthill_mckee(xadj, adj, deg, peripheral_node(n, xadj, adj, deg, i), done, perm, nordered)
      perm(first_in_comp:nordered) = perm(nordered:first_in_comp:-1)
    end do
  end subroutine rcm_order

  !> Purpose: a pseudo-peripheral node of the component of node i
  !> (George-Liu: the breadth-first search restarted from a node of its
  !> last level until the eccentricity stops growing).
  integer function peripheral_node(n, xadj, adj, deg, i) result(start)
    integer, intent(in) :: n, xadj(:), adj(:), deg(:), i
    integer :: ecc, last_ecc, w
    start = i
    last_ecc = -1
    do
      call bfs_levels(n, xadj, adj, deg, start, ecc, w)
      if (ecc <= last_ecc) exit
      last_ecc = ecc
      start = w
    end do
  end function peripheral_node

  !> Purpose: the Cuthill-McKee numbering of the component of start,
  !> appended to perm(nordered+1:) (nordered updated): breadth first, the
  !> unvisited neighbours of each node by increasing degree; done marks
  !> the numbered nodes.
  subroutine cuthill_mckee(xadj, adj, deg, start, done, perm, nordered)
    integer, intent(in) :: xadj(:), adj(:), deg(:), start
    logical, intent(inout) :: done(:)
    integer, intent(inout) :: perm(:), nordered
    integer :: head, tail, v, k, w
    nordered = nordered + 1
    perm(nordered) = start
    done(start) = .true.
    head = nordered
    tail = nordered
    do while (head <= tail)
      v = perm(head)
      head = head + 1
      k = tail
      do w = xadj(v), xadj(v + 1) - 1
        if (done(adj(w))) cycle
        done(adj(w)) = .true.
        tail = tail + 1
        perm(tail) = adj(w)
      end do
      call sort_by_degree(perm(k + 1:tail), deg)
    end do
    nordered = tail
  end subroutine cuthill_mckee

  !> Purpose: the level structure from s; depth its depth (the
  !> eccentricity of s), far a node of least degree in the last level.
  subroutine bfs_levels(n, xadj, adj, deg, s, depth, far)
    integer, intent(in) :: n, xadj(:), adj(:), deg(:), s
    integer, intent(out) :: depth, far
    integer, allocatable :: q(:), level(:)
    integer :: h, t, u, j
    allocate(q(n), level(n))
    level = -1
    level(s) = 0
    q(1) = s
    h = 1
    t = 1
    do while (h <= t)
      u = q(h)
      h = h + 1
      do j = xadj(u), xadj(u + 1) - 1
        if (level(adj(j)) < 0) then
          level(adj(j)) = level(u) + 1
          t = t + 1
          q(t) = adj(j)
        end if
      end do
    end do
    depth = level(q(t))
    far = q(t)
    do j = 1, t
      if (level(q(j)) == depth .and. deg(q(j)) < deg(far)) far = q(j)
    end do
  end subroutine bfs_levels

  !> Purpose: a sorted by increasing deg (insertion sort: stable, so ties
  !> keep their order).
  pure subroutine sort_by_degree(a, deg)
    integer, intent(inout) :: a(:)
    integer, intent(in) :: deg(:)
    integer :: p, q, x
    do p = 2, size(a)
      x = a(p)
      q = p - 1
      do while (q >= 1)
        if (deg(a(q)) <= deg(x)) exit
        a(q + 1) = a(q)
        q = q - 1
      end do
      a(q + 1) = x
    end do
  end subroutine sort_by_degree

  !> Nested-dissection order (METIS_NodeND) of the symmetric matrix whose
  !> upper triangle has the 1-based compressed-column pattern colptr,
  !> rowind; perm(new) = old, 0-based as CHOLMOD wants it.
  subroutine metis_order(n, colptr, rowind, perm)
    integer, intent(in) :: n, colptr(:), rowind(:)
    integer(c_int), allocatable, intent(out) :: perm(:)
    integer(c_int), allocatable :: xadj(:), adj(:), iperm(:), cnt(:)
    integer(c_int) :: options(metis_noptions), nv, ok
    integer :: col, k, r
    allocate(perm(n), iperm(n))
    ! METIS divides by the vertex count: nothing to order is not its case
    if (n == 0) return
    ! the graph: both triangles of the pattern, without the diagonal
    allocate(cnt(n), xadj(n + 1))
    cnt = 0
    do col = 1, n
      do k = colptr(col), colptr(col + 1) - 1
        r = rowind(k)
        if (r == col) cycle
        cnt(r) = cnt(r) + 1
        cnt(col) = cnt(col) + 1
      end do
    end do
    xadj(1) = 0
    do col = 1, n
      xadj(col + 1) = xadj(col) + cnt(col)
    end do
    allocate(adj(max(xadj(n + 1), 1)))
    cnt = xadj(1:n)
    do col = 1, n
      do k = colptr(col), colptr(col + 1) - 1
        r = rowind(k)
        if (r == col) cycle
        adj(cnt(r) + 1) = col - 1
        cnt(r) = cnt(r) + 1
        adj(cnt(col) + 1) = r - 1
        cnt(col) = cnt(col) + 1
      end do
    end do
    ok = metis_setdefaultoptions(options)
    nv = int(n, c_int)
    ok = metis_nodend(nv, xadj, adj, c_null_ptr, options, perm, iperm)
    if (ok /= metis_ok) call fatal('METIS_NodeND failed with status ' // itoa(int(ok)))
  end subroutine metis_order
end module ordering
