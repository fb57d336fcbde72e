!> Node-to-segment contact with coupling finite elements: the search that
!> pairs each slave node with the master element edge under it (eq. 8's
!> initial gap), tributary areas, penalties, the open/closed status of
!> every CFE and its switching rule (section 5), the re-search on the
!> deformed configuration, and the CFE forces at given displacements.
module contact
  use kinds, only: dp
  use strings, only: itoa
  use model
  use element_catalogue, only: catalogue, is_triangle
  use mesh_topology, only: is_boundary_edge
  use element_interface, only: elem_in_t, elem_out_t, kind_cfe, max_slave, max_en, act_residual
  use element_library, only: element_routine
  implicit none
  private
  public :: cfe_t, contact_set_t, contact_search, contact_research, cfe_input, contact_forces, &
            contact_switch, coupling_node, cfe_nodes

  !> Automatic penalty per unit area = factor * E / h (see docs/contact.md).
  real(dp), parameter :: auto_penalty_factor = 1.0e3_dp
  !> A projection this far outside [0, 1] along an edge still counts: it
  !> catches slave nodes exactly above a master vertex.
  real(dp), parameter :: edge_tol = 1.0e-6_dp
  !> Status changes named in a message.
  integer, parameter :: max_named = 20
  !> Open penalty (fraction of the closed one) while a body that only open
  !> contact holds is being brought into contact; see contact_set_t.
  real(dp), parameter :: stabilised_open_ratio = 1.0e-6_dp

  type :: cfe_t
    integer :: pair = 0
    !> Slave side: the coupling point is sum_j sw(j) * x(snode(j)).
    integer :: ns = 1
    integer :: snode(max_slave) = 0
    real(dp) :: sw(max_slave) = [1.0_dp, 0.0_dp, 0.0_dp]
    integer :: elem = 0, edge = 0    ! master element and its edge
    real(dp) :: t = 0.0_dp           ! position of X_C along the edge, 0..1
    real(dp) :: xi(2) = 0.0_dp       ! natural coordinates of X_C in the master
    real(dp) :: normal(2) = 0.0_dp   ! outward unit normal of the master edge
    real(dp) :: gap0(2) = 0.0_dp     ! [[U]]_0 = X_slave - X_C
    real(dp) :: area = 0.0_dp        ! tributary area of the coupling point
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
    !> Stabilised: open CFEs take at least stabilised_open_ratio of their
    !> closed penalty. The equilibrium iteration turns this on when the
    !> stiffness is singular with open CFEs (a body that only open contact
    !> holds, e.g. starting apart under a load) and off again once the
    !> status has settled, so that converged answers always have the
    !> nominal open penalty; the open state resists relative motion only,
    !> so it biases nothing at zero relative motion.
    logical :: stabilised = .false.
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

  !> The slave node of a node-to-segment CFE (0 when the coupling point is
  !> not a node).
  pure integer function coupling_node(c)
    type(cfe_t), intent(in) :: c
    coupling_node = 0
    if (c%ns == 1) coupling_node = c%snode(1)
  end function coupling_node

  !> Purpose: boundary edges whose two nodes are both in the list give
  !> each node half their length times the thickness (its tributary area),
  !> their smallest adjacent length h and the largest adjacent modulus.
  subroutine tributary_lengths(m, nodes, area, h, emod)
    type(model_t), intent(in) :: m
    integer, intent(in) :: nodes(:)
    real(dp), intent(out) :: area(:), h(:), emod(:)
    integer, allocatable :: pos(:)
    integer :: e, k, a, b
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
        if (.not. is_boundary_edge(m%topo, e, k)) cycle
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

  !> Purpose: the master edge (index into the master surface) on which the
  !> orthogonal projection of point xs falls, nearest first; 0 if none.
  !> Arguments: x configuration searched, s the slave node (edges through
  !> it are skipped), dmax search distance, t the projection's position.
  subroutine nearest_edge(m, x, ms, s, dmax, best, tbest)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :), dmax
    type(surface_t), intent(in) :: ms
    integer, intent(in) :: s
    integer, intent(out) :: best
    real(dp), intent(out) :: tbest
    integer :: j, a, b
    real(dp) :: ab(2), tvec(2), nvec(2), t, d, dbest, len
    best = 0
    tbest = 0.0_dp
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
      ! A node behind the master edge by more than half its length is on
      ! the far side of the master body, not in contact with it.
      if (d < -0.5_dp * len .or. d > dmax) cycle
      if (abs(d) < dbest) then
        dbest = abs(d)
        best = j
        tbest = t
      end if
    end do
  end subroutine nearest_edge

  !> Purpose: couples every slave node of every pair to the nearest master
  !> edge on which its orthogonal projection falls, searching on the
  !> configuration x (the initial one, or the deformed one with UPDATE
  !> SEARCH); the status starts closed where the node is on or behind the
  !> master edge.
  subroutine contact_search(m, x, cs)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :)
    type(contact_set_t), intent(out) :: cs
    integer, allocatable :: unc(:), uncp(:)
    real(dp), allocatable :: area(:), h(:), emod(:)
    integer :: ip, k, s, best, nunc, nunc_p
    real(dp) :: tbest, dmax
    allocate(cs%c(16), unc(16), uncp(16))
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
          call nearest_edge(m, x, ms, s, dmax, best, tbest)
          if (best == 0) then
            call append_int(unc, nunc, s)
            call append_int(uncp, nunc_p, ip)
            cycle
          end if
          if (cs%n == size(cs%c)) call grow_cfes(cs)
          cs%n = cs%n + 1
          call make_cfe(m, x, ip, s, ms%elem(best), ms%edge(best), tbest, area(k), h(k), emod(k), cs%c(cs%n))
        end do
        deallocate(area, h, emod)
      end associate
    end do
    cs%c = cs%c(1:cs%n)
    cs%uncoupled = unc(1:nunc)
    cs%uncoupled_pair = uncp(1:nunc_p)
  end subroutine contact_search

  subroutine grow_cfes(cs)
    type(contact_set_t), intent(inout) :: cs
    type(cfe_t), allocatable :: tmp(:)
    allocate(tmp(2 * size(cs%c)))
    tmp(1:cs%n) = cs%c(1:cs%n)
    call move_alloc(tmp, cs%c)
  end subroutine grow_cfes

  !> Purpose: one node-to-segment CFE: slave node s on edge `edge` of
  !> master element e at fraction t, with the slave node's tributary area,
  !> adjacent length h and modulus emod (0 area: a lone node).
  subroutine make_cfe(m, x, ip, s, e, edge, t, area, h, emod, c)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :), t, area, h, emod
    integer, intent(in) :: ip, s, e, edge
    type(cfe_t), intent(out) :: c
    integer :: a, b
    real(dp) :: ab(2), tvec(2), hm, em
    call edge_nodes(m, e, edge, a, b)
    c%pair = ip
    c%ns = 1
    c%snode(1) = s
    c%elem = e
    c%edge = edge
    c%t = t
    c%xi = edge_natural(m%etype(e), edge, t)
    ab = x(:, b) - x(:, a)
    tvec = ab / norm2(ab)
    c%normal = [tvec(2), -tvec(1)]
    ! [[U]]_0 between the reference positions of the slave node and of X_C:
    ! with a search on the deformed configuration, [[U]] of eq. (8) is
    ! then the current slave-to-X_C vector.
    c%gap0 = m%x(:, s) - (m%x(:, a) + t * (m%x(:, b) - m%x(:, a)))
    c%area = area
    hm = min(h, norm2(ab))
    em = max(emod, section_e(m, e))
    if (area <= 0.0_dp) then
      ! A lone node with no slave edge: the master edge stands in.
      c%area = norm2(ab) * section_thickness(m, e)
      hm = norm2(ab)
    end if
    c%k_closed = cfe_penalty(m%pairs(ip), c%area, em, hm)
    c%k_open = m%pairs(ip)%open_ratio * c%k_closed
    c%closed = dot_product(c%normal, x(:, s) - (x(:, a) + t * ab)) <= 0.0_dp
  end subroutine make_cfe

  !> Purpose: UPDATE SEARCH: pair again on the deformed configuration x. A
  !> slave node keeps the status it had in the same pair.
  subroutine contact_research(m, x, cs)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :)
    type(contact_set_t), intent(inout) :: cs
    type(contact_set_t) :: old
    integer :: j, q
    call move_alloc(cs%c, old%c)
    old%n = cs%n
    call contact_search(m, x, cs)
    do j = 1, cs%n
      do q = 1, old%n
        if (old%c(q)%snode(1) == cs%c(j)%snode(1) .and. old%c(q)%pair == cs%c(j)%pair) then
          cs%c(j)%closed = old%c(q)%closed
          exit
        end if
      end do
    end do
  end subroutine contact_research

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
    if (.not. is_triangle(catalogue(et)%shape)) then
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

  !> Purpose: the nodes of a CFE: slave nodes, then the master element's.
  pure subroutine cfe_nodes(m, c, nodes, nen)
    type(model_t), intent(in) :: m
    type(cfe_t), intent(in) :: c
    integer, intent(out) :: nodes(:), nen
    integer :: nm
    nm = elem_nodes(m, c%elem)
    nen = c%ns + nm
    nodes(1:c%ns) = c%snode(1:c%ns)
    nodes(c%ns + 1:nen) = m%conn(1:nm, c%elem)
  end subroutine cfe_nodes

  !> Purpose: element data of CFE c for the element routine, and its node
  !> list (slave nodes first, then the master element's nodes).
  subroutine cfe_input(m, c, u, stabilised, ein, nodes)
    type(model_t), intent(in) :: m
    type(cfe_t), intent(in) :: c
    real(dp), intent(in) :: u(:, :)
    logical, intent(in) :: stabilised     ! contact_set_t%stabilised
    type(elem_in_t), intent(out) :: ein
    integer, intent(out) :: nodes(:)
    integer :: k, nen
    call cfe_nodes(m, c, nodes, nen)
    ein%kind = kind_cfe
    ein%nen = nen
    ein%ns = c%ns
    ein%ws = c%sw
    do k = 1, nen
      ein%xy(:, k) = m%x(:, nodes(k))
      ein%ue(2 * k - 1:2 * k) = u(:, nodes(k))
    end do
    ein%master_kind = catalogue(m%etype(c%elem))%shape
    ein%xi = c%xi
    ein%normal = c%normal
    ein%gap0 = c%gap0
    ein%closed = c%closed
    if (c%closed) then
      ein%penalty = c%k_closed
    else if (stabilised) then
      ein%penalty = max(c%k_open, stabilised_open_ratio * c%k_closed)
    else
      ein%penalty = c%k_open
    end if
  end subroutine cfe_input

  !> Purpose: evaluates every CFE at displacements u with its current
  !> status: stores its gap and normal force and adds its internal force
  !> to fint (2, nn). ncalls counts the element routine calls.
  subroutine contact_forces(m, cs, u, fint, ncalls)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(inout) :: cs
    real(dp), intent(in) :: u(:, :)
    real(dp), intent(inout) :: fint(:, :)
    integer(kind=8), intent(inout) :: ncalls
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    integer :: j, i, nodes(max_en)
    do j = 1, cs%n
      call cfe_input(m, cs%c(j), u, cs%stabilised, ein, nodes)
      call element_routine(act_residual, ein, eout)
      ncalls = ncalls + 1
      do i = 1, ein%nen
        fint(:, nodes(i)) = fint(:, nodes(i)) + eout%fe(2 * i - 1:2 * i)
      end do
      cs%c(j)%gap = eout%gap
      cs%c(j)%force = eout%normal_force
    end do
  end subroutine contact_forces

  !> Purpose: penalty switching (section 5): a compressive normal force
  !> (negative gap) closes a CFE, a tensile one opens it.
  !> Arguments: nchanged status changes; changed the user ids of the first
  !> slave nodes that switched, for messages.
  subroutine contact_switch(m, cs, nchanged, changed)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(inout) :: cs
    integer, intent(out) :: nchanged
    character(len=:), allocatable, intent(out) :: changed
    logical :: closed
    integer :: j
    nchanged = 0
    changed = ''
    do j = 1, cs%n
      closed = cs%c(j)%gap < 0.0_dp
      if (closed .neqv. cs%c(j)%closed) then
        nchanged = nchanged + 1
        if (nchanged <= max_named) changed = changed // ' ' // itoa(m%node_id(cs%c(j)%snode(1)))
        cs%c(j)%closed = closed
      end if
    end do
    if (nchanged > max_named) changed = changed // ' ...'
  end subroutine contact_switch
end module contact
