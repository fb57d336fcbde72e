!> Node-to-segment contact with coupling finite elements: the search that
!> pairs each slave node with the master element edge under it (eq. 8's
!> initial gap), tributary areas, penalties, and the open/closed state of
!> every CFE used for the penalty switching of section 5.
module contact
  use kinds, only: dp
  use model
  use element_catalogue, only: catalogue, shape_quad4
  use element_types, only: elem_in_t, kind_cfe, kind_quad4, kind_tri3
  implicit none
  private
  public :: cfe_t, contact_set_t, contact_search, cfe_input

  !> Automatic penalty per unit area = factor * E / h (see docs/contact.md).
  real(dp), parameter :: auto_penalty_factor = 1.0e3_dp
  !> A projection this far outside [0, 1] along an edge still counts: it
  !> catches slave nodes exactly above a master vertex.
  real(dp), parameter :: edge_tol = 1.0e-6_dp

  type :: cfe_t
    integer :: pair = 0
    integer :: slave = 0             ! coupling node
    integer :: elem = 0, edge = 0    ! master element and its edge
    real(dp) :: t = 0.0_dp           ! position of X_C along the edge, 0..1
    real(dp) :: xi(2) = 0.0_dp       ! natural coordinates of X_C in the master
    real(dp) :: normal(2) = 0.0_dp   ! outward unit normal of the master edge
    real(dp) :: gap0(2) = 0.0_dp     ! [[U]]_0 = X_slave - X_C
    real(dp) :: area = 0.0_dp        ! tributary area of the slave node
    real(dp) :: k_closed = 0.0_dp    ! normal penalty of the CFE (force/length)
    real(dp) :: k_open = 0.0_dp
    logical :: closed = .false.
    ! results of the last evaluation
    real(dp) :: gap = 0.0_dp, force = 0.0_dp
  end type cfe_t

  type :: contact_set_t
    integer :: n = 0
    type(cfe_t), allocatable :: c(:)
    !> Slave nodes of each pair that found no master segment.
    integer, allocatable :: uncoupled(:), uncoupled_pair(:)
  end type contact_set_t

contains

  real(dp) function section_e(m, e)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    section_e = m%materials(m%sections(m%elem_section(e))%material)%e
  end function section_e

  real(dp) function section_thickness(m, e)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    section_thickness = m%sections(m%elem_section(e))%thickness
  end function section_thickness

  !> Boundary edges whose two nodes are both in the list give each node
  !> half their length times the thickness (its tributary area) and their
  !> smallest adjacent length h. Edges shared by two elements are interior.
  subroutine tributary_lengths(m, nodes, area, h, emod)
    type(model_t), intent(in) :: m
    integer, intent(in) :: nodes(:)
    real(dp), intent(out) :: area(:), h(:), emod(:)
    integer, allocatable :: pos(:)
    integer :: e, k, a, b, e2, k2, a2, b2, count
    real(dp) :: len
    allocate(pos(m%nn))
    pos = 0
    do k = 1, size(nodes)
      pos(nodes(k)) = k
    end do
    area = 0.0_dp
    h = huge(1.0_dp)
    emod = 0.0_dp
    do e = 1, m%ne
      if (.not. is_continuum(m, e)) cycle
      do k = 1, catalogue(m%etype(e))%nedges
        call edge_nodes(m, e, k, a, b)
        if (pos(a) == 0 .or. pos(b) == 0) cycle
        ! Is the edge shared with another element?
        count = 0
        do e2 = 1, m%ne
          if (e2 == e .or. .not. is_continuum(m, e2)) cycle
          if (.not. any(m%conn(:, e2) == a)) cycle
          do k2 = 1, catalogue(m%etype(e2))%nedges
            call edge_nodes(m, e2, k2, a2, b2)
            if (a2 == b .and. b2 == a) count = count + 1
          end do
        end do
        if (count > 0) cycle
        len = norm2(m%x(:, b) - m%x(:, a))
        area(pos(a)) = area(pos(a)) + 0.5_dp * len * section_thickness(m, e)
        area(pos(b)) = area(pos(b)) + 0.5_dp * len * section_thickness(m, e)
        h(pos(a)) = min(h(pos(a)), len)
        h(pos(b)) = min(h(pos(b)), len)
        emod(pos(a)) = max(emod(pos(a)), section_e(m, e))
        emod(pos(b)) = max(emod(pos(b)), section_e(m, e))
      end do
    end do
  end subroutine tributary_lengths

  !> Couples every slave node of every pair to the nearest master edge on
  !> which its orthogonal projection falls, searching on the configuration
  !> x (the initial one, or the deformed one with UPDATE SEARCH).
  subroutine contact_search(m, x, cs)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :)
    type(contact_set_t), intent(out) :: cs
    type(cfe_t), allocatable :: list(:)
    integer, allocatable :: unc(:), uncp(:)
    real(dp), allocatable :: area(:), h(:), emod(:)
    integer :: ip, k, j, s, a, b, best, nunc, nunc_p
    real(dp) :: ab(2), tvec(2), nvec(2), t, d, dbest, tbest, len, hm, em, dmax
    type(cfe_t) :: c
    allocate(list(0), unc(16), uncp(16))
    nunc = 0
    nunc_p = 0
    do ip = 1, size(m%pairs)
      associate(pr => m%pairs(ip), sl => m%surfaces(m%pairs(ip)%slave_surface), &
                ms => m%surfaces(m%pairs(ip)%master_surface))
        allocate(area(size(sl%nodes)), h(size(sl%nodes)), emod(size(sl%nodes)))
        call tributary_lengths(m, sl%nodes, area, h, emod)
        dmax = pr%search_distance
        if (dmax < 0.0_dp) dmax = huge(1.0_dp)
        do k = 1, size(sl%nodes)
          s = sl%nodes(k)
          best = 0
          dbest = huge(1.0_dp)
          do j = 1, size(ms%elem)
            call edge_nodes(m, ms%elem(j), ms%edge(j), a, b)
            if (a == s .or. b == s) cycle
            ab = x(:, b) - x(:, a)
            len = norm2(ab)
            tvec = ab / len
            t = dot_product(x(:, s) - x(:, a), tvec) / len
            if (t < -edge_tol .or. t > 1.0_dp + edge_tol) cycle
            t = min(max(t, 0.0_dp), 1.0_dp)
            nvec = [tvec(2), -tvec(1)]
            d = dot_product(x(:, s) - x(:, a), nvec)
            ! A node behind the master edge by more than half its length is
            ! on the far side of the master body, not in contact with it.
            if (d < -0.5_dp * len .or. d > dmax) cycle
            if (abs(d) < dbest) then
              dbest = abs(d)
              best = j
              tbest = t
            end if
          end do
          if (best == 0) then
            call append_int(unc, nunc, s)
            call append_int(uncp, nunc_p, ip)
            cycle
          end if
          call edge_nodes(m, ms%elem(best), ms%edge(best), a, b)
          c%pair = ip
          c%slave = s
          c%elem = ms%elem(best)
          c%edge = ms%edge(best)
          c%t = tbest
          c%xi = edge_natural(m%etype(c%elem), c%edge, tbest)
          ab = x(:, b) - x(:, a)
          tvec = ab / norm2(ab)
          c%normal = [tvec(2), -tvec(1)]
          ! [[U]]_0 between the reference positions of the slave node and of
          ! X_C: with a search on the deformed configuration, [[U]] of eq. (8)
          ! is then the current slave-to-X_C vector.
          c%gap0 = m%x(:, s) - (m%x(:, a) + tbest * (m%x(:, b) - m%x(:, a)))
          c%area = area(k)
          hm = min(h(k), norm2(ab))
          em = max(emod(k), section_e(m, c%elem))
          if (area(k) <= 0.0_dp) then
            ! A lone node with no slave edge: the master edge stands in.
            c%area = norm2(ab) * section_thickness(m, c%elem)
            hm = norm2(ab)
            em = max(em, section_e(m, c%elem))
          end if
          c%k_closed = cfe_penalty(pr, c%area, em, hm)
          c%k_open = pr%open_ratio * c%k_closed
          c%closed = dot_product(c%normal, x(:, s) - (x(:, a) + tbest * ab)) <= 0.0_dp
          list = [list, c]
        end do
        deallocate(area, h, emod)
      end associate
    end do
    cs%n = size(list)
    call move_alloc(list, cs%c)
    cs%uncoupled = unc(1:nunc)
    cs%uncoupled_pair = uncp(1:nunc_p)
  end subroutine contact_search

  !> Normal penalty of one CFE (force per unit normal relative displacement):
  !> per node as given (NODAL), per area times the tributary area, or the
  !> automatic value factor * E / h per unit area.
  pure real(dp) function cfe_penalty(pr, area, e, h)
    type(contact_pair_t), intent(in) :: pr
    real(dp), intent(in) :: area, e, h
    if (pr%nodal) then
      cfe_penalty = pr%penalty
    else if (pr%penalty > 0.0_dp) then
      cfe_penalty = pr%penalty * area
    else
      cfe_penalty = auto_penalty_factor * e / h * area
    end if
  end function cfe_penalty

  !> Natural coordinates of the point at fraction t along local edge k
  !> (counter-clockwise from node k to node k+1).
  pure function edge_natural(et, k, t) result(xi)
    integer, intent(in) :: et, k
    real(dp), intent(in) :: t
    real(dp) :: xi(2)
    if (catalogue(et)%shape == shape_quad4) then
      select case (k)
      case (1); xi = [-1.0_dp + 2.0_dp * t, -1.0_dp]
      case (2); xi = [1.0_dp, -1.0_dp + 2.0_dp * t]
      case (3); xi = [1.0_dp - 2.0_dp * t, 1.0_dp]
      case default; xi = [-1.0_dp, 1.0_dp - 2.0_dp * t]
      end select
    else
      select case (k)
      case (1); xi = [t, 0.0_dp]
      case (2); xi = [1.0_dp - t, t]
      case default; xi = [0.0_dp, 1.0_dp - t]
      end select
    end if
  end function edge_natural

  !> Element data of CFE k for the element routine, and its node list
  !> (coupling node first, then the master element's nodes).
  subroutine cfe_input(m, c, u, ein, nodes)
    type(model_t), intent(in) :: m
    type(cfe_t), intent(in) :: c
    real(dp), intent(in) :: u(:, :)
    type(elem_in_t), intent(out) :: ein
    integer, intent(out) :: nodes(:)
    integer :: nm, k
    nm = elem_nodes(m, c%elem)
    ein%kind = kind_cfe
    ein%nen = nm + 1
    nodes(1) = c%slave
    nodes(2:nm + 1) = m%conn(1:nm, c%elem)
    do k = 1, nm + 1
      ein%xy(:, k) = m%x(:, nodes(k))
      ein%ue(2 * k - 1:2 * k) = u(:, nodes(k))
    end do
    if (catalogue(m%etype(c%elem))%shape == shape_quad4) then
      ein%master_kind = kind_quad4
    else
      ein%master_kind = kind_tri3
    end if
    ein%xi = c%xi
    ein%normal = c%normal
    ein%gap0 = c%gap0
    if (c%closed) then
      ein%penalty = c%k_closed
    else
      ein%penalty = c%k_open
    end if
  end subroutine cfe_input
end module contact
