!> Edges of the continuum elements, found once per mesh: which element
!> edges are shared (interior) and which lie on the boundary, and which
!> element edge joins two given corner nodes. Edges are bucketed by their
!> lower corner node, so every query looks at a handful of candidates
!> instead of the whole mesh.
module mesh_topology
  use element_catalogue, only: catalogue, max_edges, state_none
  implicit none
  private
  public :: topology_t, build_topology, edge_owner, is_boundary_edge

  type :: topology_t
    integer :: ne = 0                       ! elements the topology was built for
    !> neighbour(k, e): element sharing edge k of element e; 0 on the
    !> boundary, -1 where element e has no edge k or is not a continuum.
    integer, allocatable :: neighbour(:, :)
    ! edges bucketed by lower corner node: bucket(first(a):first(a+1)-1)
    integer, allocatable :: first(:), edge_elem(:), edge_local(:), edge_upper(:)
  end type topology_t

contains

  !> Purpose: corner nodes (a, b) of local edge k of an element, counter-
  !> clockwise as Abaqus face Sk.
  !> Arguments: etype catalogue index, conn the element's nodes.
  pure subroutine edge_corners(etype, conn, k, a, b)
    integer, intent(in) :: etype, conn(:), k
    integer, intent(out) :: a, b
    a = conn(catalogue(etype)%edge(1, k))
    b = conn(catalogue(etype)%edge(2, k))
  end subroutine edge_corners

  !> Purpose: the edge table of a mesh of nn nodes and ne elements.
  !> Arguments: etype(ne) catalogue indices, conn(:, ne) element nodes.
  subroutine build_topology(nn, ne, etype, conn, topo)
    integer, intent(in) :: nn, ne, etype(:), conn(:, :)
    type(topology_t), intent(out) :: topo
    integer, allocatable :: fill(:)
    integer :: e, k, a, b, j, n
    topo%ne = ne
    allocate(topo%first(nn + 1), fill(nn + 1), topo%neighbour(max_edges, ne))
    topo%first = 0
    topo%neighbour = -1
    do e = 1, ne
      if (catalogue(etype(e))%state == state_none) cycle
      do k = 1, catalogue(etype(e))%nedges
        call edge_corners(etype(e), conn(:, e), k, a, b)
        topo%first(min(a, b)) = topo%first(min(a, b)) + 1
      end do
    end do
    ! counts -> bucket starts
    n = 1
    do a = 1, nn + 1
      j = topo%first(a)
      topo%first(a) = n
      n = n + j
    end do
    allocate(topo%edge_elem(n - 1), topo%edge_local(n - 1), topo%edge_upper(n - 1))
    fill = topo%first
    do e = 1, ne
      if (catalogue(etype(e))%state == state_none) cycle
      do k = 1, catalogue(etype(e))%nedges
        call edge_corners(etype(e), conn(:, e), k, a, b)
        j = fill(min(a, b))
        topo%edge_elem(j) = e
        topo%edge_local(j) = k
        topo%edge_upper(j) = max(a, b)
        fill(min(a, b)) = j + 1
        topo%neighbour(k, e) = 0
      end do
    end do
    ! two edges with the same corners in one bucket are one interior edge
    do a = 1, nn
      do j = topo%first(a), topo%first(a + 1) - 1
        do k = j + 1, topo%first(a + 1) - 1
          if (topo%edge_upper(k) /= topo%edge_upper(j)) cycle
          topo%neighbour(topo%edge_local(j), topo%edge_elem(j)) = topo%edge_elem(k)
          topo%neighbour(topo%edge_local(k), topo%edge_elem(k)) = topo%edge_elem(j)
        end do
      end do
    end do
  end subroutine build_topology

  !> Purpose: a continuum element edge with corners a and b (either
  !> direction): e = element, k = local edge; e = 0 if there is none. With
  !> two (an interior edge) the first one is returned.
  pure subroutine edge_owner(topo, a, b, e, k)
    type(topology_t), intent(in) :: topo
    integer, intent(in) :: a, b
    integer, intent(out) :: e, k
    integer :: j, lo
    e = 0
    k = 0
    lo = min(a, b)
    if (lo < 1 .or. lo >= size(topo%first)) return
    do j = topo%first(lo), topo%first(lo + 1) - 1
      if (topo%edge_upper(j) == max(a, b)) then
        e = topo%edge_elem(j)
        k = topo%edge_local(j)
        return
      end if
    end do
  end subroutine edge_owner

  pure logical function is_boundary_edge(topo, e, k)
    type(topology_t), intent(in) :: topo
    integer, intent(in) :: e, k
    is_boundary_edge = topo%neighbour(k, e) == 0
  end function is_boundary_edge
end module mesh_topology
