!> Contact with coupling finite elements: the search that couples each
!> slave point with the master element edge under it (eq. 8's initial
!> gap), the slave points' areas, penalties, the open/closed status of
!> every CFE (decided by contact_status), the re-search on the deformed
!> configuration, and the CFE forces at given displacements.
!>
!> Slave points: the nodes of a node surface, and of an element surface
!> with straight (2-node) faces, each with its tributary area (node-to-
!> segment, the paper's method); on an element surface with 3-node faces,
!> Gauss points of the slave faces instead, each a weighted combination of
!> its face's three nodes (section 5 of the paper allows any point of a
!> slave edge). Each slave face is first cut where the master surface's
!> element boundaries project onto it, and every piece gets two Gauss
!> points: both sides' nodal forces are then exact integrals of the
!> contact pressure, and a uniform pressure passes through non-matching
!> meshes unchanged (the contact patch test). Master edges may be curved
!> (3 nodes): points are projected onto the quadratic edge.
module contact
  use kinds, only: dp
  use strings, only: itoa, ftoa
  use messages, only: fatal
  use model
  use growable, only: append
  use element_catalogue, only: catalogue, max_nodes, max_edges
  use mesh_topology, only: is_boundary_edge
  use contact_geometry, only: edge_t, get_edge, edge_at, project_to_edge, piece_point, edge_areas, edge_natural, &
                              edge_weights, area_factor, edge_length
  use shape_functions, only: gauss_line, shape_at
  use contact_mortar, only: face_cuts, edge_tol, mortar_t, mortar_integrals
  use edge_tree, only: edge_tree_t, refit_tree, nearest_edge, sort_ints
  use contact_master_multipliers, only: master_space_t, master_space_integrals, master_space_wanted, coarse_straight_slave
  use element_interface, only: cfe_in_t, cfe_out_t, max_slave, act_residual
  use cfe_element, only: cfe
  use contact_wear, only: wear_t, wear_link_t, wear_setup, wear_add, wear_at, wear_node_areas
  implicit none
  private
  public :: cfe_t, contact_set_t, contact_search, contact_research, cfe_input, contact_forces, &
            coupling_node, cfe_nodes, coupling_weights, cfe_max_nodes, cfe_label, open_penalty, contact_commit, &
            frictional_set, status_codes, reset_stabilisation, restabilise, open_shift, closed_offset, closed_stiffness, &
            set_segment, soft_segment_at, soft_energy

  !> Automatic penalty per unit area = factor * E / h (see docs/contact.md).
  real(dp), parameter :: auto_penalty_factor = 1.0e3_dp
  !> The same for the Gauss points of 3-node slave faces. Two points of one
  !> face carrying equal and opposite forces, alternating from face to
  !> face, give the slave nodes no force at all: a stiff penalty leaves that
  !> mode nearly free and the point pressures scatter. Measured at the peak
  !> of the 2D Hertz case with 8-node elements (h = 0.1): 1000 E / h puts
  !> points of the contact zone into tension, 10 E / h leaves the half-width
  !> 3.2 % off Hertz, 3 E / h 1.8 %; the axisymmetric Hertz case with CAX8
  !> is within 1 % at 3 E / h. The penetration is then a third of one
  !> element's compression under the same pressure.
  real(dp), parameter :: auto_face_penalty_factor = 3.0_dp
  !> The round-off of a gap relative to the size of the coordinates that
  !> enter it (64 machine epsilons): a point this close to its master edge
  !> touches it, whatever the build or BLAS kernel rounds (the initial
  !> status, and the status search's tolerance, contact_status).
  real(dp), parameter :: gap_round_off = 64.0_dp * epsilon(1.0_dp)
  !> Open penalty (fraction of the closed one) while a body that only open
  !> contact holds is being brought into contact; see contact_set_t.
  real(dp), parameter :: stabilised_open_ratio = 1.0e-6_dp
  !> A status that the stabilised search settled while the stabilisation
  !> still carries more than stage_tolerance of the force scale holds the
  !> body through the stabilisation, not the contact (its loads moved it
  !> less than its clearances): it is searched again with the stabilised
  !> penalty anchored where the body came to rest (restabilise), a
  !> proximal-point step under which the loads move it on by as much
  !> again, until contact holds it; while it drifts freely (a stage ends
  !> with the status of the one before and the stabilisation carrying
  !> what it did then, to a tenth), the anchor is put ahead, by 1, 3, 7,
  !> ... (at most max_stage_lead) times that stage's motion, so that a
  !> light load crosses a wide clearance in a few stages; at most
  !> max_stabilised_stages stages in an increment.
  real(dp), parameter :: stage_tolerance = 1.0e-4_dp
  integer, parameter :: max_stabilised_stages = 60
  real(dp), parameter :: max_stage_lead = 1.0e6_dp
  !> A segment-to-segment CFE whose covered dual weight D_j is below this
  !> share of its node's whole int N_j da is not made: its support hardly
  !> faces the master, and its weights M_jm / D_j would be large.
  real(dp), parameter :: min_mortar_cover = 0.1_dp

  type :: cfe_t
    integer :: pair = 0
    !> Slave side: the coupling point is sum_j sw(j) * x(snode(j)).
    integer :: ns = 1
    integer :: snode(max_slave) = 0
    real(dp) :: sw(max_slave) = [1.0_dp, 0.0_dp, 0.0_dp]
    !> A Gauss point of a slave face: its element, face and number on the
    !> face (0 for a slave node).
    integer :: selem = 0, sedge = 0, sip = 0
    integer :: elem = 0, edge = 0    ! master element and its edge
    !> Segment-to-segment (nm > 0): the master side is these nodes with
    !> these weights (M_jm / D_j, contact_mortar), not the shape functions
    !> of elem at xi; elem, edge and t then name a master face under the
    !> slave node's support. As many as the support reaches: no limit.
    integer :: nm = 0
    integer, allocatable :: mnode(:)
    real(dp), allocatable :: mw(:)
    !> Segment-to-segment with the multiplier on the master mesh
    !> (contact_master_multipliers; ns = 0): mnode(1:nsl) are the slave
    !> nodes, with the weights -S_mj / D_m in mw (the element subtracts
    !> the master side), psi(1:nsl) the multiplier's hat function at them
    !> (the pressure field there), and lnode the master node that carries
    !> the multiplier (also in sip, which the re-search matches).
    integer :: nsl = 0, lnode = 0
    real(dp), allocatable :: psi(:)
    real(dp) :: t = 0.0_dp           ! position of X_C along the edge, 0..1
    real(dp) :: xi(2) = 0.0_dp       ! natural coordinates of X_C in the master
    real(dp) :: normal(2) = 0.0_dp   ! outward unit normal of the master edge
    real(dp) :: gap0(2) = 0.0_dp     ! [[U]]_0 = X_slave - X_C
    real(dp) :: area = 0.0_dp        ! tributary area of the coupling point
    real(dp) :: h = 0.0_dp           ! mesh length at the coupling point (slave or master edge)
    !> The round-off of its gap: coordinates of the size of the point's
    !> (and an edge) enter the gap, so a gap this small is zero.
    real(dp) :: gap_round = 0.0_dp
    real(dp) :: k_closed = 0.0_dp    ! normal penalty of the CFE (force/length)
    real(dp) :: k_open = 0.0_dp
    !> The normal relative motion at which the stabilised open penalty
    !> carries nothing (reset_stabilisation, restabilise).
    real(dp) :: stab_anchor = 0.0_dp
    logical :: closed = .false.
    !> Exact enforcement: the Lagrange multiplier (normal force, <= 0) the
    !> penalty is augmented with, and whether the pair asks for it: a
    !> closed CFE's force is lambda + k_closed g (solved for g = 0 per
    !> status on the condensed path, condensed_contact's
    !> condensed_multipliers; otherwise contact_status's
    !> augment_multipliers updates lambda until g vanishes).
    logical :: exact = .false.
    real(dp) :: lambda = 0.0_dp
    !> A soft pressure-overclosure law (the pair's soft_h, soft_p): the
    !> status is the law's segment seg the overclosure h = -g lies in (0:
    !> no pressure, open; k: between knots k and k + 1, the last one
    !> unbounded), closed = seg > 0. While closed the normal force is
    !> k_soft g + f_soft, the segment's affine law times the area
    !> (set_segment): the segment runs from seg_h to seg_h + seg_len
    !> (huge beyond the last knot), where the pressure is seg_p, the
    !> energy per area seg_w, and its slope seg_s.
    logical :: soft = .false.
    integer :: seg = 0
    real(dp) :: k_soft = 0.0_dp, f_soft = 0.0_dp
    real(dp) :: seg_h = 0.0_dp, seg_len = 0.0_dp, seg_p = 0.0_dp, seg_s = 0.0_dp, seg_w = 0.0_dp
    !> The law's energy A W(h) at the last evaluation's overclosure, W the
    !> integral of the law's pressure (whatever the status: the merit of
    !> the status search, contact_status's contact_energy).
    real(dp) :: w_law = 0.0_dp
    !> The law's energy per area w_at at its knot w_knot, from which the
    !> energy at another knot is summed (knot_energy: a few segments away
    !> once the search nears its end, not the thousands of an exponential).
    integer :: w_knot = 1
    real(dp) :: w_at = 0.0_dp
    !> Coulomb friction (mu = 0: none): tangential penalty (force/length);
    !> a closed CFE sticks or slides (slip_sign: +-1 along the tangent
    !> t = (-n_y, n_x)); anchor: the tangential relative displacement t.[[U]]
    !> where a sticking CFE carries no tangential force, its slip so far
    !> (committed at the end of each converged increment, as slip_total,
    !> the accumulated slip, and slip_inc, the increment's slip).
    real(dp) :: mu = 0.0_dp, k_tan = 0.0_dp
    logical :: sliding = .false.
    real(dp) :: slip_sign = 0.0_dp
    real(dp) :: anchor = 0.0_dp, slip_total = 0.0_dp, slip_inc = 0.0_dp
    !> Archard wear (contact_wear): the worn depths of the slave surface at
    !> the point and of the master surface at X_C that gap0 holds (shifted
    !> by their sum along the normal: refresh_wear).
    real(dp) :: wear(2) = 0.0_dp
    ! results of the last evaluation
    real(dp) :: gap = 0.0_dp, force = 0.0_dp
    real(dp) :: slide = 0.0_dp, tforce = 0.0_dp    ! t.[[U]], tangential force
  end type cfe_t

  !> The stages of the stabilisation in an increment (restabilise): how
  !> many, the status the last one settled, the force its stabilisation
  !> carried, and how far ahead of the rest point its anchor was put (in
  !> that stage's motions).
  type :: stabilisation_stages_t
    integer :: n = 0
    logical, allocatable :: closed(:)
    real(dp) :: carried = 0.0_dp, lead = 0.0_dp
  end type stabilisation_stages_t

  !> What a search of one pair keeps for the next (contact_research, at
  !> every increment with UPDATE SEARCH): the slave nodes' tributary areas,
  !> spacings and moduli (of the reference configuration: the same at
  !> every search), the master face each slave node found (0: none; the
  !> next search's hint, edge_tree's nearest_edge) and the master
  !> surface's edge tree (refit to the next configuration, refit_tree).
  !> None of them changes an answer.
  type :: pair_memo_t
    logical :: lengths = .false.
    real(dp), allocatable :: area(:), h(:), emod(:)
    integer, allocatable :: face(:)
    type(edge_tree_t) :: tree
    integer, allocatable :: cand(:)        ! nearest_edge's work list
  end type pair_memo_t

  type :: contact_set_t
    !> The couplings are c(1:n) (c may be longer after a re-search).
    integer :: n = 0
    type(cfe_t), allocatable :: c(:)
    !> Slave nodes of each pair that found no master segment.
    integer, allocatable :: uncoupled(:), uncoupled_pair(:)
    !> Stabilised: open CFEs take at least stabilised_open_ratio of their
    !> closed penalty. The equilibrium iteration turns this on when the
    !> stiffness is singular with open CFEs (a body that only open contact
    !> holds, e.g. starting apart under a load) and off again once the
    !> status has settled with the contact holding the body (in stages:
    !> restabilise), so that converged answers always have the nominal
    !> open penalty; the open state resists relative motion only (from its
    !> anchor while stabilised), so it biases nothing at zero relative
    !> motion.
    logical :: stabilised = .false.
    !> Notes for the listing from the search (a pair whose coarse slave
    !> resolves the pressure less well than the pair swapped would).
    character(len=600), allocatable :: notes(:)
    type(stabilisation_stages_t) :: stages
    !> Archard wear of the pairs with *WEAR (contact_wear): the worn
    !> depths, committed with the friction history (contact_commit).
    type(wear_t) :: wear
    !> Per pair, what the next search reuses (pair_memo_t).
    type(pair_memo_t), allocatable :: memo(:)
  end type contact_set_t

contains

  real(dp) function section_e(m, e)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    section_e = m%materials(m%sections(m%elem_section(e))%material)%e
  end function section_e

  !> The slave node of a node-to-segment CFE (0 when the coupling point is
  !> not a node).
  pure integer function coupling_node(c)
    type(cfe_t), intent(in) :: c
    coupling_node = 0
    if (c%ns == 1) coupling_node = c%snode(1)
  end function coupling_node

  !> Purpose: a CFE's name in messages: its slave node as the deck names
  !> it, or for a Gauss point of a slave face `element:Sk:point`.
  function cfe_label(m, c) result(s)
    type(model_t), intent(in) :: m
    type(cfe_t), intent(in) :: c
    character(len=:), allocatable :: s
    if (c%ns == 1) then
      s = node_label(m, c%snode(1))
    else if (c%ns == 0) then
      s = 'master node ' // node_label(m, c%lnode)
    else
      s = elem_label(m, c%selem) // ':S' // itoa(c%sedge) // ':' // itoa(c%sip)
    end if
  end function cfe_label

  !> Purpose: boundary edges whose corner nodes are both in the list give
  !> each of their nodes in the list its consistent area (half the edge to
  !> each corner of a straight plane edge), and their node spacing h (the
  !> smallest adjacent) and the largest adjacent modulus.
  subroutine tributary_lengths(m, nodes, area, h, emod)
    type(model_t), intent(in) :: m
    integer, intent(in) :: nodes(:)
    real(dp), intent(out) :: area(:), h(:), emod(:)
    integer, allocatable :: pos(:), ek(:, :)
    integer :: e, k, j, q, i, nek
    real(dp) :: a(3), len
    type(edge_t) :: ed
    allocate(pos(m%nn))
    pos = 0
    do k = 1, size(nodes)
      pos(nodes(k)) = k
    end do
    call list_edges(m, nodes, pos, ek, nek)
    area = 0.0_dp
    h = huge(1.0_dp)
    emod = 0.0_dp
    do i = 1, nek
      e = ek(1, i)
      k = ek(2, i)
      ed = get_edge(m, m%x, e, k)
      if (pos(ed%node(1)) == 0 .or. pos(ed%node(2)) == 0) cycle
      if (.not. is_boundary_edge(m%topo, e, k)) cycle
      a = edge_areas(ed)
      len = edge_length(ed) / (ed%nn - 1)
      do j = 1, ed%nn
        q = pos(ed%node(j))
        if (q == 0) cycle
        area(q) = area(q) + a(j)
        h(q) = min(h(q), len)
        emod(q) = max(emod(q), section_e(m, e))
      end do
    end do
  end subroutine tributary_lengths

  !> Purpose: the continuum element edges (e, k) whose corners may both be
  !> list nodes, in ascending order of e and then k (the order of a loop
  !> over every element's edges, so that the areas summed over them round
  !> as that loop's did). From the topology's edges of each list node as
  !> lower corner (an edge with both corners in the list is in the bucket
  !> of one of them), or every element's edges where the topology is not
  !> of this mesh. The UPDATE SEARCH path searches every increment, and the
  !> loop over the whole mesh was a fifth of a fretting increment.
  !> Arguments: pos(node) the node's place in nodes (0 outside); ek(1:2,
  !> 1:nek) returns the edges (element, local edge).
  subroutine list_edges(m, nodes, pos, ek, nek)
    type(model_t), intent(in) :: m
    integer, intent(in) :: nodes(:), pos(:)
    integer, allocatable, intent(out) :: ek(:, :)
    integer, intent(out) :: nek
    integer, allocatable :: key(:)
    integer :: e, k, a, j
    nek = 0
    if (m%topo%ne /= m%ne .or. .not. allocated(m%topo%first)) then
      allocate(ek(2, m%ne * max_edges))
      do e = 1, m%ne
        if (.not. is_continuum(m, e)) cycle
        do k = 1, catalogue(m%etype(e))%nedges
          nek = nek + 1
          ek(:, nek) = [e, k]
        end do
      end do
      return
    end if
    allocate(key(16))
    do k = 1, size(nodes)
      a = nodes(k)
      if (pos(a) /= k .or. a + 1 > size(m%topo%first)) cycle   ! a repeated node: once
      do j = m%topo%first(a), m%topo%first(a + 1) - 1
        if (pos(m%topo%edge_upper(j)) == 0) cycle
        call append(key, nek, max_edges * (m%topo%edge_elem(j) - 1) + m%topo%edge_local(j) - 1)
      end do
    end do
    key = key(1:nek)
    call sort_ints(key)
    allocate(ek(2, nek))
    ek(1, :) = key / max_edges + 1
    ek(2, :) = mod(key, max_edges) + 1
  end subroutine list_edges

  !> Purpose: couples the slave points of every pair (slave nodes, or
  !> Gauss points of 3-node slave faces) to the nearest master edge on
  !> which their orthogonal projection falls, searching on the
  !> configuration x (the initial one, or the deformed one with UPDATE
  !> SEARCH); the status starts closed where the point is on or behind the
  !> master edge. wear_later, if present and true (contact_research, which
  !> brings the worn depths so far), leaves the wear links to the caller.
  !> prior, if present, is the last search's set (contact_research): its
  !> memo (pair_memo_t: the same answers, sooner) moves to cs.
  subroutine contact_search(m, x, cs, wear_later, prior)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :)
    type(contact_set_t), intent(out) :: cs
    logical, intent(in), optional :: wear_later
    type(contact_set_t), intent(inout), optional :: prior
    integer, allocatable :: unc(:), uncp(:)
    integer :: ip, nunc, nunc_p
    real(dp) :: dmax
    nunc = 0
    nunc_p = 0
    ! (about as many couplings as the last search's)
    if (present(prior)) then
      allocate(cs%c(max(16, prior%n + prior%n / 8)))
    else
      allocate(cs%c(16))
    end if
    allocate(unc(16), uncp(16))
    if (present(prior)) then
      if (allocated(prior%memo)) then
        if (size(prior%memo) == size(m%pairs)) call move_alloc(prior%memo, cs%memo)
      end if
    end if
    if (.not. allocated(cs%memo)) allocate(cs%memo(size(m%pairs)))
    do ip = 1, size(m%pairs)
      dmax = m%pairs(ip)%search_distance
      if (dmax < 0.0_dp) dmax = huge(1.0_dp)
      if (m%pairs(ip)%coupling == coupling_mortar) then
        call couple_mortar(m, x, ip, dmax, cs, unc, nunc, uncp, nunc_p)
      else if (quadratic_faces(m, m%surfaces(m%pairs(ip)%slave_surface))) then
        call couple_slave_faces(m, x, ip, dmax, cs, unc, nunc, uncp, nunc_p)
      else
        call couple_slave_nodes(m, x, ip, dmax, cs, unc, nunc, uncp, nunc_p)
      end if
    end do
    ! (a re-search keeps the array's slack: cs%c(1:cs%n) are read, never
    ! the whole array, and the trimmed copy was a tenth of a re-search)
    if (.not. present(prior)) cs%c = cs%c(1:cs%n)
    call start_soft(m, cs)
    if (.not. allocated(cs%notes)) allocate(cs%notes(0))
    cs%uncoupled = unc(1:nunc)
    cs%uncoupled_pair = uncp(1:nunc_p)
    if (present(wear_later)) then
      if (wear_later) return
    end if
    call attach_wear(m, cs)
  end subroutine contact_search

  !> Is s an element surface of 3-node faces? (Mixed straight and 3-node
  !> faces stop the run: the two kinds of slave points are not mixed.)
  logical function quadratic_faces(m, s)
    type(model_t), intent(in) :: m
    type(surface_t), intent(in) :: s
    integer :: k, nq
    quadratic_faces = .false.
    if (s%kind /= surf_element .or. size(s%elem) == 0) return
    nq = 0
    do k = 1, size(s%elem)
      if (catalogue(m%etype(s%elem(k)))%edge(3, s%edge(k)) > 0) nq = nq + 1
    end do
    if (nq > 0 .and. nq < size(s%elem)) call fatal('slave surface ' // trim(s%name) // &
      ' mixes straight and 3-node faces: give the linear and the quadratic part a contact pair each')
    quadratic_faces = nq > 0
  end function quadratic_faces

  !> Node-to-segment: one CFE per slave node, with its tributary area.
  !> The pair's memo cs%memo(ip) keeps the tributary lengths, each node's
  !> master face and the master tree from one search to the next.
  subroutine couple_slave_nodes(m, x, ip, dmax, cs, unc, nunc, uncp, nunc_p)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :), dmax
    integer, intent(in) :: ip
    type(contact_set_t), intent(inout) :: cs
    integer, allocatable, intent(inout) :: unc(:), uncp(:)
    integer, intent(inout) :: nunc, nunc_p
    integer :: k, s, best
    real(dp) :: tbest
    type(cfe_t) :: c
    associate(sl => m%surfaces(m%pairs(ip)%slave_surface), ms => m%surfaces(m%pairs(ip)%master_surface), &
              mo => cs%memo(ip))
      if (.not. mo%lengths) then
        allocate(mo%area(size(sl%nodes)), mo%h(size(sl%nodes)), mo%emod(size(sl%nodes)))
        call tributary_lengths(m, sl%nodes, mo%area, mo%h, mo%emod)
        allocate(mo%face(size(sl%nodes)))
        mo%face = 0
        mo%lengths = .true.
      end if
      call refit_tree(m, x, ms, mo%tree)
      do k = 1, size(sl%nodes)
        s = sl%nodes(k)
        call nearest_edge(m, x, ms, x(:, s), s, 0, dmax, best, tbest, mo%tree, mo%face(k), mo%cand)
        mo%face(k) = best
        if (best == 0) then
          call append(unc, nunc, s)
          call append(uncp, nunc_p, ip)
          cycle
        end if
        c = cfe_t()
        c%ns = 1
        c%snode(1) = s
        call make_cfe(m, x, ip, m%x(:, s), x(:, s), mo%tree%ed(best), tbest, mo%area(k), mo%h(k), mo%emod(k), c)
        call add_cfe(cs, c)
      end do
    end associate
  end subroutine couple_slave_nodes

  !> Segment-to-segment: one CFE per slave node, its master side the
  !> master nodes with the mortar weights M_jm / D_j, its area the dual
  !> weight D_j, its normal the mean master normal under its support, its
  !> initial gap the weighted one (contact_mortar). A node whose support
  !> faces no master face (or less than min_mortar_cover of it) is
  !> uncoupled.
  subroutine couple_mortar(m, x, ip, dmax, cs, unc, nunc, uncp, nunc_p)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :), dmax
    integer, intent(in) :: ip
    type(contact_set_t), intent(inout) :: cs
    integer, allocatable, intent(inout) :: unc(:), uncp(:)
    integer, intent(inout) :: nunc, nunc_p
    type(mortar_t) :: mo
    type(cfe_t) :: c
    real(dp) :: em, xm(2), xm_ref(2)
    integer :: k, s
    associate(sl => m%surfaces(m%pairs(ip)%slave_surface), ms => m%surfaces(m%pairs(ip)%master_surface))
      if (sl%kind /= surf_element) call fatal('segment-to-segment contact (TYPE=SURFACE TO SURFACE) needs ' // &
        'an element-based slave surface: ' // trim(sl%name) // ' is a node set')
      ! the master-mesh multipliers where the slave is the finer side of
      ! straight faces, or of a straight master surface of 3-node faces
      ! (contact_master_multipliers). Not for a frictional
      ! pair that is searched again (UPDATE SEARCH, or any NLGEOM step):
      ! its couplings belong to master nodes, so a slave surface sliding
      ! past them meets new couplings without its friction history (a
      ! block slid ten master edges in one NLGEOM increment kept 10.8 of
      ! the 21.3 degrees of mu = 0.2); the dual mortar's belong to the
      ! slave nodes and carry it along.
      if (master_space_wanted(m, sl, ms, dmax) .and. .not. (m%pairs(ip)%mu > 0.0_dp .and. &
          (m%pairs(ip)%update_search .or. any(m%steps%nlgeom)))) then
        call couple_master_space(m, x, ip, dmax, cs, unc, nunc, uncp, nunc_p)
        return
      end if
      ! the note is about the meshes: made by the search on the reference
      ! configuration (not again in every Newton iteration under NLGEOM)
      if (all(x == m%x)) call note_coarse_slave(m, ip, dmax, cs)
      call mortar_integrals(m, x, sl, ms, dmax, mo)
      do k = 1, mo%n
        s = sl%nodes(k)
        if (mo%nm(k) == 0 .or. mo%d(k) <= min_mortar_cover * mo%full(k) .or. norm2(mo%nsum(:, k)) <= 0.0_dp) then
          call append(unc, nunc, s)
          call append(uncp, nunc_p, ip)
          cycle
        end if
        c = cfe_t()
        c%pair = ip
        c%ns = 1
        c%snode(1) = s
        c%nm = mo%nm(k)
        c%mnode = mo%mnode(1:c%nm, k)
        c%mw = mo%mval(1:c%nm, k) / mo%d(k)
        call place_on_master(m, mo%melem(k), mo%medge(k), mo%mt(k), mo%nsum(:, k), mo%d(k), mo%h(k), c)
        em = max(largest_modulus(m, sl, [s]), largest_modulus(m, ms, c%mnode))
        xm = matmul(x(:, c%mnode), c%mw)
        xm_ref = matmul(m%x(:, c%mnode), c%mw)
        c%gap0 = m%x(:, s) - xm_ref
        c%gap_round = gap_round_off * (norm2(x(:, s)) + c%h)
        c%k_closed = cfe_penalty(m%pairs(ip), c%area, em, c%h, .false.)
        c%exact = m%pairs(ip)%exact
        c%k_open = open_stiffness(m%pairs(ip), c%area, em, c%h, .false., c%k_closed)
        c%mu = m%pairs(ip)%mu
        if (c%mu > 0.0_dp) c%k_tan = stick_penalty(m%pairs(ip), c%area, c%k_closed)
        c%closed = dot_product(c%normal, x(:, s) - xm) <= c%gap_round
        call add_cfe(cs, c)
      end do
    end associate
  end subroutine couple_mortar

  !> Purpose: a note for the listing where the dual mortar couples a slave
  !> surface coarser than its master that would do better as the master
  !> (contact_master_multipliers' coarse_straight_slave, with the spacing
  !> ratio): the pair runs as given, the note says what swapping gives.
  subroutine note_coarse_slave(m, ip, dmax, cs)
    type(model_t), intent(in) :: m
    integer, intent(in) :: ip
    real(dp), intent(in) :: dmax
    type(contact_set_t), intent(inout) :: cs
    character(len=600), allocatable :: more(:)
    real(dp) :: ratio
    associate(sl => m%surfaces(m%pairs(ip)%slave_surface), ms => m%surfaces(m%pairs(ip)%master_surface))
      if (.not. coarse_straight_slave(m, sl, ms, dmax, ratio)) return
      if (.not. allocated(cs%notes)) allocate(cs%notes(0))
      allocate(more(size(cs%notes) + 1))
      more(1:size(cs%notes)) = cs%notes
      more(size(more)) = 'contact pair ' // itoa(ip) // ' (' // trim(sl%name) // ', ' // trim(ms%name) // &
        '): the slave faces are ' // ftoa(ratio, 2) // ' times the master faces under them: the contact ' // &
        'pressure is resolved at the slave spacing (dual mortar); swapped (the finer surface the slave, ' // &
        'the multiplier on this straight surface as the master mesh) it is more accurate ' // &
        '(docs/contact.md, "Any pair of meshes")'
      call move_alloc(more, cs%notes)
    end associate
  end subroutine note_coarse_slave

  !> Purpose: segment-to-segment with the multiplier on the master mesh
  !> (contact_master_multipliers; taken where the slave is the finer side
  !> of straight faces): one CFE per master node m whose hat function
  !> faces the slave surface over more than min_mortar_cover of its int
  !> N_m da (master_space_cfe). Slave nodes that no multiplier's field
  !> reaches are reported uncoupled. A CFE holds every slave node its hat
  !> reaches, however much finer the slave is.
  subroutine couple_master_space(m, x, ip, dmax, cs, unc, nunc, uncp, nunc_p)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :), dmax
    integer, intent(in) :: ip
    type(contact_set_t), intent(inout) :: cs
    integer, allocatable, intent(inout) :: unc(:), uncp(:)
    integer, intent(inout) :: nunc, nunc_p
    type(master_space_t) :: sp
    type(cfe_t) :: c
    logical, allocatable :: taken(:), reached(:)
    logical :: lumped
    integer :: k
    associate(sl => m%surfaces(m%pairs(ip)%slave_surface), ms => m%surfaces(m%pairs(ip)%master_surface))
      call master_space_integrals(m, x, sl, ms, dmax, sp)
      taken = sp%ns > 0 .and. sp%d > min_mortar_cover * sp%full .and. norm2(sp%nsum, dim=1) > 0.0_dp
      lumped = m%pairs(ip)%mu <= 0.0_dp .and. .not. sp%quadratic
      allocate(reached(m%nn))
      reached = .false.
      do k = 1, sp%n
        if (.not. taken(k)) cycle
        call master_space_cfe(m, x, ip, sp, k, lumped, c)
        reached(c%mnode(1:c%nsl)) = reached(c%mnode(1:c%nsl)) .or. c%psi(1:c%nsl) > 0.0_dp
        call add_cfe(cs, c)
      end do
      do k = 1, size(sl%nodes)
        if (reached(sl%nodes(k))) cycle
        call append(unc, nunc, sl%nodes(k))
        call append(uncp, nunc_p, ip)
      end do
    end associate
  end subroutine couple_master_space

  !> Purpose: the CFE of master node k (of the master surface's node list)
  !> with the multiplier on the master mesh: its slave side the slave
  !> nodes with the weights S_mj / D_m, its master side node m (weight
  !> one: the lumped master side), or for a frictional pair or 3-node
  !> master faces the master nodes k with M_mk / D_m (the consistent one,
  !> whose tangential component is consistent too; 3-node faces: their
  !> mid-side nodes carry no multiplier to lump onto), its area D_m, its
  !> normal the mean master normal under psi_m, its initial gap the
  !> weighted one.
  !> Arguments: sp the integrals (master_space_integrals), lumped the
  !> master side; c returns the CFE.
  subroutine master_space_cfe(m, x, ip, sp, k, lumped, c)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :)
    integer, intent(in) :: ip, k
    type(master_space_t), intent(in) :: sp
    logical, intent(in) :: lumped
    type(cfe_t), intent(out) :: c
    real(dp) :: em, rel(2)
    integer :: nn
    associate(sl => m%surfaces(m%pairs(ip)%slave_surface), ms => m%surfaces(m%pairs(ip)%master_surface))
      c%pair = ip
      c%ns = 0
      c%nsl = sp%ns(k)
      if (lumped) then
        nn = sp%ns(k) + 1
        c%mnode = [sp%snode(1:sp%ns(k), k), ms%nodes(k)]
        c%mw = [-sp%sval(1:sp%ns(k), k) / sp%d(k), 1.0_dp]
      else
        nn = sp%ns(k) + sp%nm(k)
        c%mnode = [sp%snode(1:sp%ns(k), k), sp%mnode(1:sp%nm(k), k)]
        c%mw = [-sp%sval(1:sp%ns(k), k), sp%mval(1:sp%nm(k), k)] / sp%d(k)
      end if
      c%nm = nn
      c%psi = sp%psi(1:sp%ns(k), k)
      c%lnode = ms%nodes(k)
      c%sip = c%lnode
      call place_on_master(m, sp%melem(k), sp%medge(k), sp%mt(k), sp%nsum(:, k), sp%d(k), sp%h(k), c)
      em = max(largest_modulus(m, sl, c%mnode), largest_modulus(m, ms, c%mnode))
      ! the weighted gap vector sum_j S_mj / D_m x_j - x_m (the element
      ! subtracts the weights mw)
      rel = -matmul(x(:, c%mnode), c%mw)
      c%gap0 = -matmul(m%x(:, c%mnode), c%mw)
      c%gap_round = gap_round_off * (maxval(norm2(x(:, c%mnode), dim=1)) + c%h)
      c%k_closed = cfe_penalty(m%pairs(ip), c%area, em, c%h, .false.)
      c%exact = m%pairs(ip)%exact
      c%k_open = open_stiffness(m%pairs(ip), c%area, em, c%h, .false., c%k_closed)
      c%mu = m%pairs(ip)%mu
      if (c%mu > 0.0_dp) c%k_tan = stick_penalty(m%pairs(ip), c%area, c%k_closed)
      c%closed = dot_product(c%normal, rel) <= c%gap_round
    end associate
  end subroutine master_space_cfe

  !> Purpose: the largest Young's modulus of the elements of surface s
  !> that hold any of the nodes (0 if none).
  real(dp) function largest_modulus(m, s, nodes) result(em)
    type(model_t), intent(in) :: m
    type(surface_t), intent(in) :: s
    integer, intent(in) :: nodes(:)
    integer :: q, e
    em = 0.0_dp
    do q = 1, size(nodes)
      do e = 1, size(s%elem)
        if (any(m%conn(1:elem_nodes(m, s%elem(e)), s%elem(e)) == nodes(q))) em = max(em, section_e(m, s%elem(e)))
      end do
    end do
  end function largest_modulus

  !> Purpose: the master face, normal and size of a segment-to-segment
  !> CFE (dual mortar or master-mesh multipliers): face edge of element
  !> elem with the point at t on it (named for messages and the contact
  !> table), the normal the normalised weighted sum nsum of the master
  !> normals under the multiplier's support, the area and mesh length.
  subroutine place_on_master(m, elem, edge, t, nsum, area, h, c)
    type(model_t), intent(in) :: m
    integer, intent(in) :: elem, edge
    real(dp), intent(in) :: t, nsum(2), area, h
    type(cfe_t), intent(inout) :: c
    c%elem = elem
    c%edge = edge
    c%t = t
    c%xi = edge_natural(m%etype(elem), edge, t)
    c%normal = nsum / norm2(nsum)
    c%area = area
    c%h = h
  end subroutine place_on_master

  !> Gauss points of 3-node slave faces: each face is cut where the ends
  !> of the master edges project onto it, each piece gets two points, each
  !> point is coupled to the master edge under it. A face none of whose
  !> points is coupled is reported by its mid-side node.
  subroutine couple_slave_faces(m, x, ip, dmax, cs, unc, nunc, uncp, nunc_p)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :), dmax
    integer, intent(in) :: ip
    type(contact_set_t), intent(inout) :: cs
    integer, allocatable, intent(inout) :: unc(:), uncp(:)
    integer, intent(inout) :: nunc, nunc_p
    type(edge_t) :: ed, ref
    type(cfe_t) :: c
    real(dp), allocatable :: cuts(:)
    real(dp) :: tg(3), wg(3), t, w(3), p(2), pref(2), dpdt(2), tbest, area, h, em
    integer :: f, ncut, iv, ig, best, npts, ncoupled
    call gauss_line(2, tg, wg)
    associate(sl => m%surfaces(m%pairs(ip)%slave_surface), ms => m%surfaces(m%pairs(ip)%master_surface), &
              tree => cs%memo(ip)%tree)
      call refit_tree(m, x, ms, tree)
      do f = 1, size(sl%elem)
        ed = get_edge(m, x, sl%elem(f), sl%edge(f))
        ref = get_edge(m, m%x, sl%elem(f), sl%edge(f))
        call face_cuts(m, x, ed, ms, dmax, cuts, ncut)
        h = 0.5_dp * edge_length(ed)
        em = section_e(m, sl%elem(f))
        npts = 0
        ncoupled = 0
        do iv = 1, ncut - 1
          do ig = 1, 2
            npts = npts + 1
            call piece_point(ref, cuts(iv), cuts(iv + 1), tg(ig), wg(ig), t, pref, area)
            call edge_at(ed, t, p, dpdt)
            call nearest_edge(m, x, ms, p, 0, sl%elem(f), dmax, best, tbest, tree)
            if (best == 0) cycle
            ncoupled = ncoupled + 1
            w = edge_weights(ed, t)
            c = cfe_t(ns=3, snode=ed%node, sw=w, selem=sl%elem(f), sedge=sl%edge(f), sip=npts)
            call make_cfe(m, x, ip, pref, p, tree%ed(best), tbest, area, h, em, c)
            call add_cfe(cs, c)
          end do
        end do
        if (ncoupled == 0) then
          call append(unc, nunc, ed%node(3))
          call append(uncp, nunc_p, ip)
        end if
      end do
    end associate
  end subroutine couple_slave_faces

  subroutine add_cfe(cs, c)
    type(contact_set_t), intent(inout) :: cs
    type(cfe_t), intent(in) :: c
    type(cfe_t), allocatable :: tmp(:)
    if (cs%n == size(cs%c)) then
      allocate(tmp(max(2 * size(cs%c), 16)))
      tmp(1:cs%n) = cs%c(1:cs%n)
      call move_alloc(tmp, cs%c)
    end if
    cs%n = cs%n + 1
    cs%c(cs%n) = c
  end subroutine add_cfe

  !> Purpose: completes CFE c, whose slave side (nodes, weights) is set:
  !> its coupling point at xs_ref (reference) and xs (configuration x) on
  !> master edge ed (get_edge in x: the search tree's) at position t,
  !> with its area, node spacing h and modulus emod (0 area: a lone node).
  subroutine make_cfe(m, x, ip, xs_ref, xs, ed, t, area, h, emod, c)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :), xs_ref(2), xs(2), t, area, h, emod
    integer, intent(in) :: ip
    type(edge_t), intent(in) :: ed
    type(cfe_t), intent(inout) :: c
    type(edge_t) :: ref
    real(dp) :: ab(2), tvec(2), hm, em, len, p(2), dpdt(2), w(3)
    integer :: e, edge, j
    e = ed%elem
    edge = ed%k
    ! the same edge on the reference coordinates
    ref = ed
    do j = 1, ed%nn
      ref%x(:, j) = m%x(:, ed%node(j))
    end do
    c%pair = ip
    c%elem = e
    c%edge = edge
    c%t = t
    c%xi = edge_natural(m%etype(e), edge, t)
    len = edge_length(ed)
    c%area = area
    hm = min(h, len / (ed%nn - 1))
    em = max(emod, section_e(m, e))
    if (area <= 0.0_dp) then
      ! A lone node with no slave edge: the master edge stands in.
      c%area = sum(edge_areas(ref))
      hm = len / (ed%nn - 1)
    end if
    c%h = hm
    c%gap_round = gap_round_off * (norm2(xs) + hm)
    c%k_closed = cfe_penalty(m%pairs(ip), c%area, em, hm, c%ns > 1)
    c%exact = m%pairs(ip)%exact
    c%k_open = open_stiffness(m%pairs(ip), c%area, em, hm, c%ns > 1, c%k_closed)
    c%mu = m%pairs(ip)%mu
    if (c%mu > 0.0_dp) c%k_tan = stick_penalty(m%pairs(ip), c%area, c%k_closed)
    ! [[U]]_0 between the reference positions of the slave point and of
    ! X_C: with a search on the deformed configuration, [[U]] of eq. (8)
    ! is then the current slave-to-X_C vector.
    if (ed%nn == 2) then
      ab = x(:, ed%node(2)) - x(:, ed%node(1))
      tvec = ab / norm2(ab)
      c%normal = [tvec(2), -tvec(1)]
      c%gap0 = xs_ref - (m%x(:, ed%node(1)) + t * (m%x(:, ed%node(2)) - m%x(:, ed%node(1))))
      c%closed = dot_product(c%normal, xs - (x(:, ed%node(1)) + t * ab)) <= c%gap_round
    else
      call edge_at(ed, t, p, dpdt)
      c%normal = [dpdt(2), -dpdt(1)] / norm2(dpdt)
      w = edge_weights(ref, t)
      c%gap0 = xs_ref - matmul(ref%x, w)
      c%closed = dot_product(c%normal, xs - p) <= c%gap_round
    end if
    ! At a corner of the master surface the normal of whichever edge the
    ! search met first would lean by half the corner's angle: a polygonal
    ! curve meshed node on node then drifts in pressure along the arc.
    if (t <= edge_tol) call blend_vertex_normal(m, x, ip, e, edge, ed%node(1), c%normal)
    if (t >= 1.0_dp - edge_tol) call blend_vertex_normal(m, x, ip, e, edge, ed%node(2), c%normal)
  end subroutine make_cfe

  !> Purpose: the normal at master corner node v: the mean of the normals
  !> of the two master edges meeting there (edge k of element e and its
  !> neighbour in the master surface); unchanged at an end of the surface.
  !> Arguments: x current coordinates; ip pair; normal in: edge (e, k)'s
  !> unit normal at v, out: the blended unit normal.
  subroutine blend_vertex_normal(m, x, ip, e, k, v, normal)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :)
    integer, intent(in) :: ip, e, k, v
    real(dp), intent(inout) :: normal(2)
    type(edge_t) :: nb
    real(dp) :: p(2), dpdt(2), nsum(2)
    integer :: j
    associate(ms => m%surfaces(m%pairs(ip)%master_surface))
      do j = 1, size(ms%elem)
        if (ms%elem(j) == e .and. ms%edge(j) == k) cycle
        nb = get_edge(m, x, ms%elem(j), ms%edge(j))
        if (nb%node(1) /= v .and. nb%node(2) /= v) cycle
        call edge_at(nb, merge(0.0_dp, 1.0_dp, nb%node(1) == v), p, dpdt)
        nsum = normal + [dpdt(2), -dpdt(1)] / norm2(dpdt)
        ! A fold back (a surface turning by nearly 180 degrees) has no mean.
        if (norm2(nsum) > 0.5_dp) normal = nsum / norm2(nsum)
        return
      end do
    end associate
  end subroutine blend_vertex_normal

  !> Purpose: UPDATE SEARCH, and under NLGEOM the search of every Newton
  !> iteration: pair again on the deformed configuration x. A slave point
  !> keeps the status it had in the same pair (the same node, or the same
  !> Gauss point of the same slave face), its exact multiplier and its
  !> friction history. The old couplings are found per slave node (a
  !> chain of the old CFEs of each first slave node, in their order), so
  !> the matching costs O(n_old + n_new + nodes) instead of the
  !> O(n_old n_new) of comparing every pair, and finds the same (first)
  !> match.
  !> Arguments: x the configuration searched (m%x + u); moved, if present
  !> and true, says that u is not where the CFEs were last evaluated (a
  !> search after a displacement update of an iteration): the old
  !> couplings' t.[[U]] is then evaluated again at u for their elastic
  !> tangential offset (otherwise their last evaluation serves, as at the
  !> start of an increment); it also keeps, within an iteration, a
  !> coupling whose point the search lost (see the end of the routine). changed, if present, returns the statuses
  !> the search changed: new couplings that start closed, and closed ones
  !> lost. The stabilised open penalty (contact_set_t) stays as it was.
  subroutine contact_research(m, x, cs, moved, changed)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :)
    type(contact_set_t), intent(inout) :: cs
    logical, intent(in), optional :: moved
    integer, intent(out), optional :: changed
    type(contact_set_t) :: old
    integer, allocatable :: head(:), next(:)
    logical, allocatable :: matched(:)
    integer :: j, q, nchg, klo, khi
    logical :: stabilised, reevaluate
    reevaluate = .false.
    if (present(moved)) reevaluate = moved
    nchg = 0
    stabilised = cs%stabilised
    call move_alloc(cs%c, old%c)
    old%n = cs%n
    if (allocated(cs%memo)) call move_alloc(cs%memo, old%memo)
    old%stages = cs%stages
    if (allocated(cs%wear%pairs)) call move_alloc(cs%wear%pairs, old%wear%pairs)
    if (allocated(cs%wear%link)) call move_alloc(cs%wear%link, old%wear%link)
    ! (the wear links once, below, with the depths so far: not a fresh wear
    ! state to throw away, every surface's areas made again)
    call contact_search(m, x, cs, wear_later=allocated(old%wear%pairs), prior=old)
    cs%stabilised = stabilised
    cs%stages = old%stages
    ! (the chains' heads over the key nodes' range, not every node)
    call key_range(old, cs, klo, khi)
    allocate(head(klo:khi), next(old%n), matched(old%n))
    head = 0
    matched = .false.
    do q = old%n, 1, -1
      next(q) = head(key_node(old%c(q)))
      head(key_node(old%c(q))) = q
    end do
    do j = 1, cs%n
      q = head(key_node(cs%c(j)))
      do while (q > 0)
        if (old%c(q)%pair == cs%c(j)%pair .and. old%c(q)%selem == cs%c(j)%selem .and. &
            old%c(q)%sedge == cs%c(j)%sedge .and. old%c(q)%sip == cs%c(j)%sip) exit
        q = next(q)
      end do
      if (q == 0) then
        ! a new coupling, its status from the geometry (contact_search)
        if (cs%c(j)%closed) nchg = nchg + 1
        cycle
      end if
      matched(q) = .true.
      call carry_history(m, x, old%c(q), reevaluate, cs%c(j))
    end do
    call keep_lost_couplings(old, matched, reevaluate, cs, nchg)
    ! the worn depths so far, read by the new couplings
    if (allocated(old%wear%pairs)) then
      call move_alloc(old%wear%pairs, cs%wear%pairs)
      if (allocated(old%wear%link)) call move_alloc(old%wear%link, cs%wear%link)
      call attach_wear(m, cs)
    end if
    if (present(changed)) changed = nchg
  end subroutine contact_research

  !> Purpose: what coupling c of the new search takes from the old
  !> coupling of the same slave point (contact_research): its status,
  !> multiplier and friction history, or, within an increment's iterations
  !> (reevaluate), the old coupling whole where it is closed and stays.
  !> Arguments: x the configuration searched; oc the old
  !> coupling; c the new one, completed.
  subroutine carry_history(m, x, oc, reevaluate, c)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :)
    type(cfe_t), intent(in) :: oc
    logical, intent(in) :: reevaluate
    type(cfe_t), intent(inout) :: c
    real(dp) :: old_slide
    ! Within an increment's iterations a closed coupling that stays on
    ! the same master element (the same node list) keeps its geometry:
    ! its normal and projection are the linearisation the tangent has
    ! (no contact geometric stiffness), and re-evaluating them at every
    ! iterate under a penalty far stiffer than the bodies chattered
    ! (a soft rubber cylinder on the Hertz plate: out-of-balance 5e4 and
    ! 7e9 in alternate iterations). The search at the start of the next
    ! increment evaluates it on the converged configuration.
    ! And it moves on to another master element only once its point has
    ! left its old edge by switch_band of the edge's length (a point at a
    ! master vertex otherwise alternates between the two edges from
    ! iterate to iterate).
    if (reevaluate .and. oc%closed .and. oc%ns > 0) then
      if (same_nodes(m, oc, c) .or. near_old_edge(m, x, oc)) then
        c = oc
        return
      end if
    end if
    c%closed = oc%closed
    c%lambda = oc%lambda
    c%stab_anchor = oc%stab_anchor
    if (c%soft) call set_segment(m, c, oc%seg)
    ! friction: the elastic tangential offset carries over to the
    ! new coupling, whose t.[[U]] is evaluated where the point is now
    ! (zero on a straight edge; not at a blended corner normal)
    c%sliding = oc%sliding
    c%slip_sign = oc%slip_sign
    c%slip_total = oc%slip_total
    if (c%mu > 0.0_dp) then
      old_slide = oc%slide
      if (reevaluate) old_slide = current_slide(m, oc, x)
      c%anchor = current_slide(m, c, x) - (old_slide - oc%anchor)
    end if
  end subroutine carry_history

  !> Purpose: the old couplings that no new one matched (contact_research).
  !> A coupling of a slave point that the search finds no master edge for
  !> (a point pushed past the end of the master surface) is kept within
  !> the iterations of an increment (reevaluate), its geometry and status
  !> as they were, as the pairing of the increment's start would have
  !> them; the search at the start of the next increment (not reevaluate)
  !> decides on the converged configuration. Otherwise a point at the
  !> master's end, just past it in one iterate and not in the next, loses
  !> its coupling and comes back with a new one whose status the geometry
  !> decides, from iteration to iteration, and the status never settles.
  !> Couplings of the master-mesh multiplier (ns = 0) belong to master
  !> nodes and are not kept; a closed one lost is a status change.
  !> Arguments: matched(q) whether old%c(q) found a match; nchg counts the
  !> status changes.
  subroutine keep_lost_couplings(old, matched, reevaluate, cs, nchg)
    type(contact_set_t), intent(in) :: old
    logical, intent(in) :: matched(:), reevaluate
    type(contact_set_t), intent(inout) :: cs
    integer, intent(inout) :: nchg
    integer :: q
    do q = 1, old%n
      if (matched(q)) cycle
      if (reevaluate .and. old%c(q)%ns > 0) then
        call add_cfe(cs, old%c(q))
        call drop_uncoupled(cs, old%c(q)%snode(1), old%c(q)%pair)
      else if (old%c(q)%closed) then
        nchg = nchg + 1
      end if
    end do
  end subroutine keep_lost_couplings

  !> Does the coupling point of c (configuration x) project onto its
  !> master edge (project_to_edge, t not clamped) within switch_band edge
  !> lengths of the edge's ends?
  logical function near_old_edge(m, x, c)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :)
    type(cfe_t), intent(in) :: c
    real(dp), parameter :: switch_band = 0.05_dp
    real(dp) :: nvec(2), d, t
    near_old_edge = .false.
    if (c%nm > 0) return           ! a mortar coupling's support: re-paired
    call project_to_edge(get_edge(m, x, c%elem, c%edge), matmul(x(:, c%snode(1:c%ns)), c%sw(1:c%ns)), t, nvec, d)
    near_old_edge = t >= -switch_band .and. t <= 1.0_dp + switch_band
  end function near_old_edge

  !> Do CFEs a and b couple the same nodes (in the same order)?
  pure logical function same_nodes(m, a, b)
    type(model_t), intent(in) :: m
    type(cfe_t), intent(in) :: a, b
    integer, allocatable :: na(:), nb(:)
    integer :: ka, kb
    call cfe_nodes(m, a, na, ka)
    call cfe_nodes(m, b, nb, kb)
    same_nodes = ka == kb
    if (same_nodes) same_nodes = all(na(1:ka) == nb(1:kb))
  end function same_nodes

  !> Slave node s of pair ip off the list of uncoupled nodes (its coupling
  !> was kept).
  subroutine drop_uncoupled(cs, s, ip)
    type(contact_set_t), intent(inout) :: cs
    integer, intent(in) :: s, ip
    logical, allocatable :: keep(:)
    if (.not. allocated(cs%uncoupled)) return
    keep = .not. (cs%uncoupled == s .and. cs%uncoupled_pair == ip)
    cs%uncoupled = pack(cs%uncoupled, keep)
    cs%uncoupled_pair = pack(cs%uncoupled_pair, keep)
  end subroutine drop_uncoupled

  !> Purpose: the least and largest key node (key_node) of the couplings of
  !> sets a and b (1 and 0 where there are none).
  pure subroutine key_range(a, b, lo, hi)
    type(contact_set_t), intent(in) :: a, b
    integer, intent(out) :: lo, hi
    integer :: j
    lo = huge(1)
    hi = -huge(1)
    do j = 1, a%n
      lo = min(lo, key_node(a%c(j)))
      hi = max(hi, key_node(a%c(j)))
    end do
    do j = 1, b%n
      lo = min(lo, key_node(b%c(j)))
      hi = max(hi, key_node(b%c(j)))
    end do
    if (hi < lo) then
      lo = 1
      hi = 0
    end if
  end subroutine key_range

  !> The node a CFE is filed under when old and new couplings are matched:
  !> its first slave node, or for a coupling of the master-mesh multiplier
  !> (ns = 0) the master node that carries the multiplier.
  pure integer function key_node(c)
    type(cfe_t), intent(in) :: c
    if (c%ns > 0) then
      key_node = c%snode(1)
    else
      key_node = c%lnode
    end if
  end function key_node

  !> Purpose: t.[[U]] of CFE c in configuration x (its displacements
  !> x - m%x at its nodes). A node-to-segment or slave-face coupling sums
  !> eq. (8)'s B_e D_e in the element's order (cfe_b_matrix's weights, the
  !> products of each component in dof order) without its element arrays:
  !> the re-search evaluates every coupling at every increment; a
  !> segment-to-segment one calls the element routine.
  !> Arguments: m the model; c the coupling; x the configuration.
  real(dp) function current_slide(m, c, x) result(slide)
    type(model_t), intent(in) :: m
    type(cfe_t), intent(in) :: c
    real(dp), intent(in) :: x(:, :)
    type(cfe_in_t) :: ein
    type(cfe_out_t) :: eout
    integer, allocatable :: nodes(:)
    real(dp) :: n(max_nodes), dn(2, max_nodes), rel(2), jump(2), tvec(2)
    integer :: k, nen, a
    if (c%nm > 0 .or. c%ns < 1) then
      call cfe_input(m, c, x, .false., ein, nodes)
      nen = ein%nen
      do k = 1, nen
        ein%ue(2 * k - 1:2 * k) = x(:, nodes(k)) - m%x(:, nodes(k))
      end do
      call cfe(act_residual, ein, eout)
      slide = eout%slide
      return
    end if
    call shape_at(catalogue(m%etype(c%elem))%shape, c%xi, n, dn)
    rel = 0.0_dp
    do k = 1, c%ns
      a = c%snode(k)
      rel = rel + c%sw(k) * (x(:, a) - m%x(:, a))
    end do
    do k = 1, elem_nodes(m, c%elem)
      a = m%conn(k, c%elem)
      rel = rel + (-n(k)) * (x(:, a) - m%x(:, a))
    end do
    jump = rel + c%gap0
    tvec = [-c%normal(2), c%normal(1)]
    slide = dot_product(tvec, jump)
  end function current_slide

  !> Normal penalty of one CFE (force per unit normal relative displacement):
  !> per node as given (NODAL), per area times the tributary area, or the
  !> automatic value factor * E / h per unit area.
  pure real(dp) function cfe_penalty(pr, area, e, h, face_point)
    type(contact_pair_t), intent(in) :: pr
    real(dp), intent(in) :: area, e, h
    logical, intent(in) :: face_point      ! a Gauss point of a 3-node slave face
    if (pr%nodal) then
      cfe_penalty = pr%penalty
    else if (pr%penalty > 0.0_dp) then
      cfe_penalty = pr%penalty * area
    else if (face_point) then
      cfe_penalty = auto_face_penalty_factor * e / h * area
    else
      cfe_penalty = auto_penalty_factor * e / h * area
    end if
  end function cfe_penalty

  !> The open penalty of one CFE: OPEN PENALTY (a ratio) times the closed
  !> penalty; under exact enforcement times the automatic penalty instead,
  !> whatever PENALTY= says (the penalty then only sets the pace of the
  !> multiplier updates, and the open state's small force, which the open
  !> points' relative motion makes, would otherwise follow it: 6.5e-6 of
  !> P on the flagship between PENALTY=1e8 and 1e11). Never above half
  !> the closed penalty.
  pure real(dp) function open_stiffness(pr, area, e, h, face_point, k_closed) result(k)
    type(contact_pair_t), intent(in) :: pr
    real(dp), intent(in) :: area, e, h, k_closed
    logical, intent(in) :: face_point
    type(contact_pair_t) :: auto
    k = pr%open_ratio * k_closed
    if (.not. pr%exact) return
    auto = pr
    auto%penalty = -1.0_dp
    auto%nodal = .false.
    k = min(pr%open_ratio * cfe_penalty(auto, area, e, h, face_point), 0.5_dp * k_closed)
  end function open_stiffness

  !> Tangential (stick) penalty of one CFE: the pair's stick slope per
  !> unit area times the CFE's area, or (no slope given) the normal
  !> penalty, as CalculiX and Abaqus choose a stick stiffness of the order
  !> of the normal one.
  pure real(dp) function stick_penalty(pr, area, k_closed)
    type(contact_pair_t), intent(in) :: pr
    real(dp), intent(in) :: area, k_closed
    stick_penalty = k_closed
    if (pr%stick_slope > 0.0_dp) stick_penalty = pr%stick_slope * area
  end function stick_penalty

  !> Purpose: the nodes of a CFE: slave nodes, then the master element's
  !> (or the segment-to-segment master side's).
  !> Arguments: nodes(1:nen) returns them; nodes is (re)allocated when it
  !> is shorter than nen (a caller keeps one list for many CFEs), so a
  !> coupling of any size fits.
  pure subroutine cfe_nodes(m, c, nodes, nen)
    type(model_t), intent(in) :: m
    type(cfe_t), intent(in) :: c
    integer, allocatable, intent(inout) :: nodes(:)
    integer, intent(out) :: nen
    integer :: nm
    if (c%nm > 0) then
      nm = c%nm
    else
      nm = elem_nodes(m, c%elem)
    end if
    nen = c%ns + nm
    if (allocated(nodes)) then
      if (size(nodes) < nen) deallocate(nodes)
    end if
    if (.not. allocated(nodes)) allocate(nodes(max(nen, max_nodes + max_slave)))
    nodes(1:c%ns) = c%snode(1:c%ns)
    if (c%nm > 0) then
      nodes(c%ns + 1:nen) = c%mnode(1:c%nm)
    else
      nodes(c%ns + 1:nen) = m%conn(1:nm, c%elem)
    end if
  end subroutine cfe_nodes

  !> Purpose: the largest node count of the CFEs of cs (at least that of
  !> a node-to-segment CFE on the largest element), for callers that size
  !> per-coupling arrays once.
  pure integer function cfe_max_nodes(cs) result(n)
    type(contact_set_t), intent(in) :: cs
    integer :: j
    n = max_nodes + max_slave
    do j = 1, cs%n
      n = max(n, cs%c(j)%ns + cs%c(j)%nm)
    end do
  end function cfe_max_nodes

  !> Purpose: element data of CFE c for the coupling element routine
  !> (cfe_element's cfe), and its node list (slave nodes first, then the
  !> master side's nodes; reallocated when shorter, as cfe_nodes).
  subroutine cfe_input(m, c, u, stabilised, ein, nodes)
    type(model_t), intent(in) :: m
    type(cfe_t), intent(in) :: c
    real(dp), intent(in) :: u(:, :)
    logical, intent(in) :: stabilised     ! contact_set_t%stabilised
    type(cfe_in_t), intent(out) :: ein
    integer, allocatable, intent(inout) :: nodes(:)
    integer :: k, nen
    call cfe_nodes(m, c, nodes, nen)
    ein%nen = nen
    ein%ns = c%ns
    ein%ws = c%sw
    allocate(ein%ue(2 * nen))
    do k = 1, nen
      ein%ue(2 * k - 1:2 * k) = u(:, nodes(k))
    end do
    if (c%nm > 0) then
      ein%master_kind = 0
      ein%wm = c%mw(1:c%nm)
    else
      ein%master_kind = catalogue(m%etype(c%elem))%shape
      ein%xi = c%xi
    end if
    ein%normal = c%normal
    ein%gap0 = c%gap0
    ! exact enforcement: the closed force lambda + k_closed g is the
    ! penalty's on the gap shifted by lambda / k_closed along the normal
    ! (a soft law: its segment's force k_soft g + f_soft likewise)
    if (c%closed .and. closed_offset(c) /= 0.0_dp) ein%gap0 = c%gap0 + (closed_offset(c) / closed_stiffness(c)) * c%normal
    ein%closed = c%closed
    if (c%closed) then
      ein%penalty = closed_stiffness(c)
    else
      ein%penalty = open_penalty(c, stabilised)
      ein%open_shift = open_shift(c, stabilised)
    end if
    ein%mu = c%mu
    ein%k_tan = c%k_tan
    ein%sliding = c%sliding
    ein%slip_sign = c%slip_sign
    ein%anchor = c%anchor
  end subroutine cfe_input

  !> Purpose: the penalty of CFE c while open (stabilised: see
  !> contact_set_t).
  pure real(dp) function open_penalty(c, stabilised)
    type(cfe_t), intent(in) :: c
    logical, intent(in) :: stabilised
    open_penalty = c%k_open
    if (stabilised) open_penalty = max(c%k_open, stabilised_open_ratio * c%k_closed)
  end function open_penalty

  !> Purpose: the normal relative motion at which CFE c's open penalty
  !> carries nothing: the stabilised penalty's anchor, else 0.
  pure real(dp) function open_shift(c, stabilised)
    type(cfe_t), intent(in) :: c
    logical, intent(in) :: stabilised
    open_shift = 0.0_dp
    if (stabilised) open_shift = c%stab_anchor
  end function open_shift

  !> Purpose: the stabilisation of an increment's first singular status:
  !> anchored at no motion.
  !> Arguments: cs - the contact set.
  subroutine reset_stabilisation(cs)
    type(contact_set_t), intent(inout) :: cs
    type(stabilisation_stages_t) :: none
    if (cs%n > 0) cs%c(1:cs%n)%stab_anchor = 0.0_dp
    cs%stages = none
  end subroutine reset_stabilisation

  !> Purpose: the next stage of the stabilisation, once the stabilised
  !> search has settled: where the open CFEs' stabilised penalties still
  !> carry more than stage_tolerance of the force scale in all, the
  !> stabilisation, not the contact, holds the body; each CFE's penalty is
  !> then anchored at its normal relative motion of the last evaluation
  !> (where the body came to rest: a proximal-point step, so that the
  !> loads move it on by as much again; at rest in contact, the next
  !> stage carries almost nothing), or ahead of it while the body drifts
  !> freely (see stage_tolerance). False, and nothing changed, where
  !> the stabilisation carries less, where the first stage moved no open
  !> point towards its master, or after max_stabilised_stages stages.
  !> Arguments: cs - the contact set (gaps of the settled status);
  !> force_scale - the force scale of the increment (contact_status);
  !> again - whether a new stage begins.
  logical function restabilise(cs, force_scale) result(again)
    type(contact_set_t), intent(inout) :: cs
    real(dp), intent(in) :: force_scale
    real(dp) :: motion(cs%n), carried
    logical :: same
    integer :: j
    again = .false.
    if (cs%n == 0 .or. cs%stages%n >= max_stabilised_stages) return
    carried = 0.0_dp
    do j = 1, cs%n
      motion(j) = cs%c(j)%gap - dot_product(cs%c(j)%normal, cs%c(j)%gap0)
      if (.not. cs%c(j)%closed) carried = carried + open_penalty(cs%c(j), .true.) * &
                                                    abs(motion(j) - cs%c(j)%stab_anchor)
    end do
    if (.not. carried > stage_tolerance * force_scale) return
    ! the first stage moved no open point towards its master (the loads
    ! pull the body away from every contact): nor would the next ones
    if (cs%stages%n == 0 .and. .not. any(.not. cs%c(1:cs%n)%closed .and. motion < -cs%c(1:cs%n)%gap_round)) return
    ! drifting freely: the status of the last stage, and the stabilisation
    ! carrying what it did then (the loads' share that no contact takes)
    associate(st => cs%stages)
      same = .false.
      if (allocated(st%closed)) then
        if (size(st%closed) == cs%n) same = all(st%closed .eqv. cs%c(1:cs%n)%closed)
      end if
      same = same .and. abs(carried - st%carried) <= 0.1_dp * carried
      st%lead = merge(min(2.0_dp * st%lead + 1.0_dp, max_stage_lead), 0.0_dp, same)
      st%carried = carried
      cs%c(1:cs%n)%stab_anchor = motion + st%lead * (motion - cs%c(1:cs%n)%stab_anchor)
      st%closed = cs%c(1:cs%n)%closed
      st%n = st%n + 1
    end associate
    again = .true.
  end function restabilise

  !> Purpose: the CFEs of pairs with a soft law (contact_pair_t%soft_h)
  !> start in the segment of zero overclosure where the search found them
  !> closed (on or behind the master), open otherwise; the status search
  !> moves them to the segment of their overclosure.
  !> Arguments: m the model; cs the contact set just searched.
  subroutine start_soft(m, cs)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(inout) :: cs
    integer :: j
    do j = 1, cs%n
      associate(c => cs%c(j))
        if (.not. allocated(m%pairs(c%pair)%soft_h)) cycle
        c%soft = .true.
        c%exact = .false.
        c%lambda = 0.0_dp
        if (c%closed) then
          call set_segment(m, c, soft_segment_at(m%pairs(c%pair), 0.0_dp))
        else
          call set_segment(m, c, 0)
        end if
      end associate
    end do
  end subroutine start_soft

  !> Purpose: the segment of pair pr's soft law that overclosure h lies
  !> in: 0 before the first knot, k between knots k and k + 1, the last
  !> knot's index beyond it (binary search).
  pure integer function soft_segment_at(pr, h) result(k)
    type(contact_pair_t), intent(in) :: pr
    real(dp), intent(in) :: h
    integer :: lo, hi, mid
    associate(kh => pr%soft_h)
      if (h < kh(1)) then
        k = 0
        return
      end if
      lo = 1
      hi = size(kh)
      ! invariant: kh(lo) <= h, and h < kh(hi) unless hi is the last knot
      if (h >= kh(hi)) then
        k = hi - 1
        return
      end if
      do while (hi - lo > 1)
        mid = (lo + hi) / 2
        if (kh(mid) <= h) then
          lo = mid
        else
          hi = mid
        end if
      end do
      k = lo
    end associate
  end function soft_segment_at

  !> Purpose: puts soft CFE c in segment k of its pair's law: closed for
  !> k > 0, with the segment's affine force (eq. 9 with the law): the
  !> pressure p(h) = seg_p + seg_s (h - seg_h) times the area, so with
  !> h = -g the normal force -A p = k_soft g + f_soft, k_soft = A seg_s,
  !> f_soft = A (seg_s seg_h - seg_p) (compression negative).
  !> Arguments: m the model; c the CFE; k the segment (0: open).
  subroutine set_segment(m, c, k)
    type(model_t), intent(in) :: m
    type(cfe_t), intent(inout) :: c
    integer, intent(in) :: k
    integer :: n
    c%seg = k
    c%closed = k > 0
    c%k_soft = 0.0_dp
    c%f_soft = 0.0_dp
    if (k == 0) return
    associate(kh => m%pairs(c%pair)%soft_h, kp => m%pairs(c%pair)%soft_p)
      n = size(kh)
      c%seg_h = kh(k)
      c%seg_p = kp(k)
      c%seg_s = (kp(k + 1) - kp(k)) / (kh(k + 1) - kh(k))
      c%seg_len = kh(k + 1) - kh(k)
      if (k == n - 1) c%seg_len = huge(1.0_dp)
      ! the energy per area at the segment's start: the trapezoids before it
      c%seg_w = knot_energy(m%pairs(c%pair), c%w_knot, c%w_at, k)
      c%w_knot = k
      c%w_at = c%seg_w
    end associate
    c%k_soft = c%area * c%seg_s
    c%f_soft = c%area * (c%seg_s * c%seg_h - c%seg_p)
  end subroutine set_segment

  !> Purpose: the energy of soft CFE c's law at its last evaluation, A
  !> W(h) (law_energy), whatever its status: the true potential of the
  !> law at the status's solution, the status search's merit.
  pure real(dp) function soft_energy(c) result(e)
    type(cfe_t), intent(in) :: c
    e = c%w_law
  end function soft_energy

  !> Purpose: W(h), the integral of pair pr's soft law's pressure over the
  !> overclosure from its first knot to h (0 before it): the energy at the
  !> start of h's segment (knot_energy from w_at at knot w_knot) and the
  !> part of h's own segment.
  pure real(dp) function law_energy(pr, h, w_knot, w_at) result(w)
    type(contact_pair_t), intent(in) :: pr
    real(dp), intent(in) :: h, w_at
    integer, intent(in) :: w_knot
    integer :: k
    real(dp) :: dh, s
    w = 0.0_dp
    k = soft_segment_at(pr, h)
    if (k == 0) return
    associate(kh => pr%soft_h, kp => pr%soft_p)
      w = knot_energy(pr, w_knot, w_at, k)
      dh = h - kh(k)
      s = (kp(k + 1) - kp(k)) / (kh(k + 1) - kh(k))
      w = w + kp(k) * dh + 0.5_dp * s * dh**2
    end associate
  end function law_energy

  !> Purpose: W at knot k of pair pr's soft law, from its value w0 at knot
  !> k0: the trapezoids of the segments between them.
  pure real(dp) function knot_energy(pr, k0, w0, k) result(w)
    type(contact_pair_t), intent(in) :: pr
    integer, intent(in) :: k0, k
    real(dp), intent(in) :: w0
    integer :: i
    w = w0
    associate(kh => pr%soft_h, kp => pr%soft_p)
      do i = k0, k - 1
        w = w + 0.5_dp * (kp(i) + kp(i + 1)) * (kh(i + 1) - kh(i))
      end do
      do i = k0 - 1, k, -1
        w = w - 0.5_dp * (kp(i) + kp(i + 1)) * (kh(i + 1) - kh(i))
      end do
    end associate
  end function knot_energy

  !> Purpose: the force of closed CFE c at zero gap: the multiplier of
  !> exact enforcement, or a soft law's segment offset f_soft.
  pure real(dp) function closed_offset(c)
    type(cfe_t), intent(in) :: c
    if (c%soft) then
      closed_offset = c%f_soft
    else
      closed_offset = c%lambda
    end if
  end function closed_offset

  !> The normal stiffness of closed CFE c: its soft segment's, or the
  !> closed penalty.
  pure real(dp) function closed_stiffness(c)
    type(cfe_t), intent(in) :: c
    ! (a soft CFE taken as closed outside its law, seg = 0: the contact
    ! equations' mask, condensed_contact, asks which dofs a closed
    ! coupling reaches; the closed penalty answers)
    if (c%soft .and. c%seg > 0) then
      closed_stiffness = c%k_soft
    else
      closed_stiffness = c%k_closed
    end if
  end function closed_stiffness

  !> Purpose: evaluates every CFE at displacements u with its current
  !> status: stores its gap and normal force and adds its internal force
  !> to fint (2, nn). ncalls counts the element routine calls.
  subroutine contact_forces(m, cs, u, fint, ncalls)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(inout) :: cs
    real(dp), intent(in) :: u(:, :)
    real(dp), intent(inout) :: fint(:, :)
    integer(kind=8), intent(inout) :: ncalls
    type(cfe_in_t) :: ein
    type(cfe_out_t) :: eout
    integer, allocatable :: nodes(:)
    integer :: j, i
    do j = 1, cs%n
      call cfe_input(m, cs%c(j), u, cs%stabilised, ein, nodes)
      call cfe(act_residual, ein, eout)
      ncalls = ncalls + 1
      do i = 1, ein%nen
        fint(:, nodes(i)) = fint(:, nodes(i)) + eout%fe(2 * i - 1:2 * i)
      end do
      cs%c(j)%gap = eout%gap
      if (cs%c(j)%closed .and. closed_offset(cs%c(j)) /= 0.0_dp) &
        cs%c(j)%gap = eout%gap - closed_offset(cs%c(j)) / closed_stiffness(cs%c(j))
      if (cs%c(j)%soft) cs%c(j)%w_law = cs%c(j)%area * law_energy(m%pairs(cs%c(j)%pair), -cs%c(j)%gap, &
                                                                   cs%c(j)%w_knot, cs%c(j)%w_at)
      cs%c(j)%force = eout%normal_force
      cs%c(j)%slide = eout%slide
      cs%c(j)%tforce = eout%tangential_force
    end do
  end subroutine contact_forces

  !> Purpose: the status of every CFE as a code that says which tangent
  !> it has: 0 open, 1 closed (sticking), 2 sliding along +t, 3 along -t;
  !> plus 4 times the segment of a soft law.
  pure function status_codes(cs) result(k)
    type(contact_set_t), intent(in) :: cs
    integer :: k(cs%n)
    integer :: j
    do j = 1, cs%n
      k(j) = 0
      if (cs%c(j)%closed) k(j) = 1
      if (cs%c(j)%closed .and. cs%c(j)%sliding) k(j) = merge(2, 3, cs%c(j)%slip_sign > 0.0_dp)
      ! a soft law: each segment its own tangent
      if (cs%c(j)%soft .and. cs%c(j)%closed) k(j) = k(j) + 4 * cs%c(j)%seg
    end do
  end function status_codes

  !> Purpose: does any CFE carry friction?
  pure logical function frictional_set(cs)
    type(contact_set_t), intent(in) :: cs
    frictional_set = any(cs%c(1:cs%n)%mu > 0.0_dp)
  end function frictional_set

  !> Purpose: commits the friction history of a converged increment
  !> (after the last evaluation of every CFE): an open CFE's anchor
  !> follows it (it touches again where it is), a sticking one keeps its
  !> anchor, a sliding one moves its anchor by its slip, so that its
  !> elastic tangential offset is the tangential force over the stick
  !> penalty (the return mapping); slip_inc and slip_total take the slip.
  subroutine contact_commit(cs)
    type(contact_set_t), intent(inout) :: cs
    integer :: j
    real(dp) :: new_anchor
    do j = 1, cs%n
      associate(c => cs%c(j))
        c%slip_inc = 0.0_dp
        if (c%mu <= 0.0_dp) cycle
        if (.not. c%closed) then
          c%anchor = c%slide
        else if (c%sliding) then
          new_anchor = c%slide - c%tforce / c%k_tan
          c%slip_inc = new_anchor - c%anchor
          c%slip_total = c%slip_total + abs(c%slip_inc)
          c%anchor = new_anchor
        end if
      end associate
    end do
    if (cs%wear%on) call commit_wear(cs)
  end subroutine contact_commit

  !> Purpose: Archard's wear of the converged increment (contact_wear):
  !> every closed coupling element of a wearing pair that slid wears both
  !> surfaces by its normal force times its slip (contact_commit has
  !> just made slip_inc); the gaps then take the new depths.
  subroutine commit_wear(cs)
    type(contact_set_t), intent(inout) :: cs
    integer :: j
    do j = 1, cs%n
      associate(c => cs%c(j))
        if (.not. cs%wear%pairs(c%pair)%on .or. .not. c%closed .or. c%slip_inc == 0.0_dp) cycle
        call wear_add(cs%wear, j, c%pair, max(0.0_dp, -c%force), c%slip_inc)
      end associate
    end do
    call refresh_wear(cs)
  end subroutine commit_wear

  !> Purpose: the wear of contact set cs after a search (contact_search,
  !> contact_research): its state where it has none yet (zero depths),
  !> every coupling element's link (its nodes and weights as the wear
  !> shares its volumes and reads its depths: coupling_weights),
  !> a slave node surface's areas (the first search's), and the worn
  !> depths applied to the gaps (refresh_wear). Nothing without *WEAR.
  subroutine attach_wear(m, cs)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(inout) :: cs
    integer, allocatable :: nodes(:)
    real(dp), allocatable :: w(:)
    integer :: j, ip, nen
    if (size(m%pairs) == 0) return
    if (.not. any(m%pairs%wear)) return
    if (.not. allocated(cs%wear%pairs)) call wear_setup(m, cs%wear)
    cs%wear%on = .true.
    call size_links(cs%wear%link, cs%n)
    do j = 1, cs%n
      ! its nodes and weights (coupling_weights), slave nodes first
      call coupling_weights(m, cs%c(j), nodes, w, nen)
      cs%wear%link(j)%node = nodes(1:nen)
      cs%wear%link(j)%w = w(1:nen)
      cs%wear%link(j)%nsl = cs%c(j)%ns + cs%c(j)%nsl
    end do
    do ip = 1, size(m%pairs)
      if (m%pairs(ip)%wear .and. m%surfaces(m%pairs(ip)%slave_surface)%kind /= surf_element) &
        call wear_node_areas(cs%wear, ip, cs%c(1:cs%n)%pair, cs%c(1:cs%n)%area)
    end do
    call refresh_wear(cs)
  end subroutine attach_wear

  !> Purpose: link(1:n) for n coupling elements, the arrays of the links
  !> there were kept (a link's assignment then reallocates them only where
  !> its node count changed: a re-search at every increment made two
  !> arrays per coupling anew).
  !> Arguments: link the wear's links (any, or none, before); n.
  subroutine size_links(link, n)
    type(wear_link_t), allocatable, intent(inout) :: link(:)
    integer, intent(in) :: n
    type(wear_link_t), allocatable :: more(:)
    integer :: j
    if (allocated(link)) then
      if (size(link) == n) return
    end if
    allocate(more(n))
    if (allocated(link)) then
      do j = 1, min(n, size(link))
        call move_alloc(link(j)%node, more(j)%node)
        call move_alloc(link(j)%w, more(j)%w)
      end do
    end if
    call move_alloc(more, link)
  end subroutine size_links

  !> Purpose: coupling element c's nodes (cfe_nodes) and the weights of its
  !> B_e (eq. 4) without their signs: slave nodes first (the slave weights
  !> sw, or the master-mesh multiplier's S_mj / D_m), then the master
  !> side's (the shape functions at X_C, or the mortar weights). A node of
  !> weight zero (a master element's node off the face) is reached by no
  !> force or tangent of the element.
  !> Arguments: nodes(1:nen), w(1:nen) returned (both reallocated where
  !> shorter than nen, as cfe_nodes: a caller keeps them for many CFEs).
  subroutine coupling_weights(m, c, nodes, w, nen)
    type(model_t), intent(in) :: m
    type(cfe_t), intent(in) :: c
    integer, allocatable, intent(inout) :: nodes(:)
    real(dp), allocatable, intent(inout) :: w(:)
    integer, intent(out) :: nen
    real(dp) :: n(max_nodes), dn(2, max_nodes)
    call cfe_nodes(m, c, nodes, nen)
    if (allocated(w)) then
      if (size(w) < nen) deallocate(w)
    end if
    if (.not. allocated(w)) allocate(w(size(nodes)))
    w(1:c%ns) = c%sw(1:c%ns)
    if (c%nm > 0) then
      w(c%ns + 1:nen) = c%mw(1:c%nm)
      ! the master-mesh multiplier (ns = 0): its slave nodes' weights are
      ! stored negative (the element subtracts the master side)
      w(1:c%nsl) = -c%mw(1:c%nsl)
    else
      call shape_at(catalogue(m%etype(c%elem))%shape, c%xi, n, dn)
      w(c%ns + 1:nen) = n(1:nen - c%ns)
    end if
  end subroutine coupling_weights

  !> Purpose: every coupling element's gap takes the worn depths at its
  !> point (contact_wear's wear_at): its initial gap [[U]]_0 moves by
  !> their change along its normal, so that the gap n.[[U]] grows by the
  !> slave's depth plus the master's (both surfaces recede). The tangential
  !> component (the friction's slide) is unchanged.
  subroutine refresh_wear(cs)
    type(contact_set_t), intent(inout) :: cs
    real(dp) :: h(2)
    integer :: j
    do j = 1, cs%n
      associate(c => cs%c(j))
        h = wear_at(cs%wear, j, c%pair)
        c%gap0 = c%gap0 + (sum(h) - sum(c%wear)) * c%normal
        c%wear = h
      end associate
    end do
  end subroutine refresh_wear
end module contact
