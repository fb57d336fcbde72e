!> The element catalogue: one entry per element type name a deck may use,
!> with everything the other layers need to know about that type (node
!> count, corner nodes, edges with their mid-side nodes, integration rule,
!> stress state, output type ids). Arrays everywhere are sized from here;
!> no other module tests node counts to find out what an element is.
!>
!> Node order and face numbering are Abaqus/CalculiX's: corners counter-
!> clockwise first, then the mid-side nodes in the order of the faces; face
!> Sk runs from corner k to corner k+1 (for a triangle S3 from 3 to 1).
!>
!> Adding an element type: one entry in `catalogue`; a new shape also needs
!> its shape functions (elements layer, shape_functions) and, for a new
!> integration rule, the rule and its extrapolation to the nodes there.
module element_catalogue
  implicit none
  private
  public :: element_type_t, catalogue, max_nodes, max_edges, max_ip, shape_line2, shape_line3, &
            shape_tri3, shape_quad4, shape_tri6, shape_quad8, shape_spring1, shape_spring2, shape_springa, &
            shape_mass, is_line, is_spring_shape, state_none, state_plane_stress, &
            state_plane_strain, state_axisymmetric, find_element_type, state_name, is_triangle, &
            edge_node_count, unsupported_reason, file_node_order

  !> Geometric families (shape functions and natural coordinates). The
  !> springs have no shape functions; their family says which dofs they
  !> join: one dof of one node to the ground (SPRING1), one dof of each of
  !> two nodes (SPRING2), the line between two nodes (SPRINGA). A point
  !> mass (MASS) has one node and no stiffness.
  integer, parameter :: shape_line2 = 1, shape_tri3 = 2, shape_quad4 = 3, shape_line3 = 4, &
                        shape_tri6 = 5, shape_quad8 = 6, shape_spring1 = 7, shape_spring2 = 8, &
                        shape_springa = 9, shape_mass = 10
  !> Stress states of the continuum elements (state_none: not a continuum).
  integer, parameter :: state_none = 0, state_plane_stress = 1, state_plane_strain = 2, &
                        state_axisymmetric = 3
  !> Largest node count, edge count, integration-point count of any type,
  !> and nodes on one edge (two corners and a mid-side node).
  integer, parameter :: max_nodes = 8, max_edges = 4, max_ip = 9, max_edge_nodes = 3

  type :: element_type_t
    character(len=8) :: name = ''
    integer :: shape = 0
    integer :: nodes = 0          ! nodes per element
    integer :: corners = 0        ! the first `corners` nodes are the vertices
    integer :: nedges = 0         ! edges (faces S1..Sn in Abaqus numbering)
    !> edge(:, k): first corner, second corner (counter-clockwise, Abaqus
    !> face Sk) and mid-side node (0 = straight edge without one).
    integer :: edge(3, max_edges) = 0
    integer :: nip = 0            ! integration points of the stiffness
    integer :: state = state_none
    integer :: gmsh_type = 0      ! MSH element type
    integer :: vtk_type = 0       ! VTK cell type
  end type element_type_t

  integer, parameter :: tri_edges(3, max_edges) = reshape([1, 2, 0, 2, 3, 0, 3, 1, 0, 0, 0, 0], [3, max_edges])
  integer, parameter :: quad_edges(3, max_edges) = reshape([1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 1, 0], [3, max_edges])
  integer, parameter :: no_edges(3, max_edges) = 0
  integer, parameter :: line_edges(3, max_edges) = reshape([1, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0], [3, max_edges])
  integer, parameter :: tri6_edges(3, max_edges) = reshape([1, 2, 4, 2, 3, 5, 3, 1, 6, 0, 0, 0], [3, max_edges])
  integer, parameter :: quad8_edges(3, max_edges) = reshape([1, 2, 5, 2, 3, 6, 3, 4, 7, 4, 1, 8], [3, max_edges])
  !> A 3-node line is end, middle, end (Abaqus T3D3, as gmsh writes it).
  integer, parameter :: line3_edges(3, max_edges) = reshape([1, 3, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0], [3, max_edges])

  !> T3D2/T3D3 (and T2D2/T2D3) are line elements: gmsh writes them for
  !> boundary curves, where they carry no stiffness and serve to define
  !> surfaces; given a *SOLID SECTION they are trusses (as in CalculiX),
  !> with one integration point (2 nodes) or two (3 nodes). The springs
  !> carry the stiffness of their *SPRING; they have no edges and no
  !> integration points. MASS carries the point mass of its *MASS, which
  !> only gravity and centrifugal loads see in a static step.
  !> CPS8R/CPE8R/CAX8R are the 8-node quadrilateral with 2x2 points; the
  !> 8-node element's spurious mode under 2x2 is not communicable through a
  !> mesh of more than one element, as in Abaqus. CAX6 takes 6 points
  !> (degree 4) where CPS6/CPE6 take 3: the hoop terms N_i u_r / r times
  !> r dA of the axisymmetric triangle are of degree 3 for a quadratic
  !> field (degree 4 with curved edges), and 3 points fail its patch tests.
  !> CPS4R/CPE4R/CAX4R are the bilinear quadrilateral with one point at its
  !> centre; a one-point bilinear quadrilateral (nip = 1) gets the hourglass
  !> stabilization of continuum_element (its two spurious modes do spread
  !> through a mesh, unlike the 8-node element's).
  !> DC2D3/4/6/8 and DCAX3/4/6/8 are Abaqus's heat-transfer elements: the
  !> shapes and rules of the plane (thickness of the section) and the
  !> axisymmetric continuum elements, for *HEAT TRANSFER steps only
  !> (temperature_field; a mechanical step refuses them, deck_heat_cards).
  !> CPS3T ... CAX8RT are Abaqus's coupled temperature-displacement
  !> elements: each the element without the T (the same shape, rule and
  !> state), whose nodes carry a temperature in a coupled or heat step
  !> as every continuum element's do in cfe2d (docs/heat.md).
  type(element_type_t), parameter :: catalogue(49) = [ &
    element_type_t('T3D2', shape_line2, 2, 2, 1, line_edges, 1, state_none, 1, 3), &
    element_type_t('T2D2', shape_line2, 2, 2, 1, line_edges, 1, state_none, 1, 3), &
    element_type_t('T3D3', shape_line3, 3, 2, 1, line3_edges, 2, state_none, 8, 21), &
    element_type_t('T2D3', shape_line3, 3, 2, 1, line3_edges, 2, state_none, 8, 21), &
    element_type_t('SPRING1', shape_spring1, 1, 1, 0, no_edges, 0, state_none, 15, 1), &
    element_type_t('SPRING2', shape_spring2, 2, 2, 0, no_edges, 0, state_none, 1, 3), &
    element_type_t('SPRINGA', shape_springa, 2, 2, 0, no_edges, 0, state_none, 1, 3), &
    element_type_t('MASS', shape_mass, 1, 1, 0, no_edges, 0, state_none, 15, 1), &
    element_type_t('CPS3', shape_tri3, 3, 3, 3, tri_edges, 1, state_plane_stress, 2, 5), &
    element_type_t('CPE3', shape_tri3, 3, 3, 3, tri_edges, 1, state_plane_strain, 2, 5), &
    element_type_t('CAX3', shape_tri3, 3, 3, 3, tri_edges, 1, state_axisymmetric, 2, 5), &
    element_type_t('CPS4', shape_quad4, 4, 4, 4, quad_edges, 4, state_plane_stress, 3, 9), &
    element_type_t('CPE4', shape_quad4, 4, 4, 4, quad_edges, 4, state_plane_strain, 3, 9), &
    element_type_t('CAX4', shape_quad4, 4, 4, 4, quad_edges, 4, state_axisymmetric, 3, 9), &
    element_type_t('CPS4R', shape_quad4, 4, 4, 4, quad_edges, 1, state_plane_stress, 3, 9), &
    element_type_t('CPE4R', shape_quad4, 4, 4, 4, quad_edges, 1, state_plane_strain, 3, 9), &
    element_type_t('CAX4R', shape_quad4, 4, 4, 4, quad_edges, 1, state_axisymmetric, 3, 9), &
    element_type_t('CPS6', shape_tri6, 6, 3, 3, tri6_edges, 3, state_plane_stress, 9, 22), &
    element_type_t('CPE6', shape_tri6, 6, 3, 3, tri6_edges, 3, state_plane_strain, 9, 22), &
    element_type_t('CAX6', shape_tri6, 6, 3, 3, tri6_edges, 6, state_axisymmetric, 9, 22), &
    element_type_t('CPS8', shape_quad8, 8, 4, 4, quad8_edges, 9, state_plane_stress, 16, 23), &
    element_type_t('CPE8', shape_quad8, 8, 4, 4, quad8_edges, 9, state_plane_strain, 16, 23), &
    element_type_t('CAX8', shape_quad8, 8, 4, 4, quad8_edges, 9, state_axisymmetric, 16, 23), &
    element_type_t('CPS8R', shape_quad8, 8, 4, 4, quad8_edges, 4, state_plane_stress, 16, 23), &
    element_type_t('CPE8R', shape_quad8, 8, 4, 4, quad8_edges, 4, state_plane_strain, 16, 23), &
    element_type_t('CAX8R', shape_quad8, 8, 4, 4, quad8_edges, 4, state_axisymmetric, 16, 23), &
    element_type_t('DC2D3', shape_tri3, 3, 3, 3, tri_edges, 1, state_plane_stress, 2, 5), &
    element_type_t('DC2D4', shape_quad4, 4, 4, 4, quad_edges, 4, state_plane_stress, 3, 9), &
    element_type_t('DC2D6', shape_tri6, 6, 3, 3, tri6_edges, 3, state_plane_stress, 9, 22), &
    element_type_t('DC2D8', shape_quad8, 8, 4, 4, quad8_edges, 9, state_plane_stress, 16, 23), &
    element_type_t('DCAX3', shape_tri3, 3, 3, 3, tri_edges, 1, state_axisymmetric, 2, 5), &
    element_type_t('DCAX4', shape_quad4, 4, 4, 4, quad_edges, 4, state_axisymmetric, 3, 9), &
    element_type_t('DCAX6', shape_tri6, 6, 3, 3, tri6_edges, 6, state_axisymmetric, 9, 22), &
    element_type_t('DCAX8', shape_quad8, 8, 4, 4, quad8_edges, 9, state_axisymmetric, 16, 23), &
    element_type_t('CPS3T', shape_tri3, 3, 3, 3, tri_edges, 1, state_plane_stress, 2, 5), &
    element_type_t('CPE3T', shape_tri3, 3, 3, 3, tri_edges, 1, state_plane_strain, 2, 5), &
    element_type_t('CAX3T', shape_tri3, 3, 3, 3, tri_edges, 1, state_axisymmetric, 2, 5), &
    element_type_t('CPS4T', shape_quad4, 4, 4, 4, quad_edges, 4, state_plane_stress, 3, 9), &
    element_type_t('CPE4T', shape_quad4, 4, 4, 4, quad_edges, 4, state_plane_strain, 3, 9), &
    element_type_t('CAX4T', shape_quad4, 4, 4, 4, quad_edges, 4, state_axisymmetric, 3, 9), &
    element_type_t('CPS4RT', shape_quad4, 4, 4, 4, quad_edges, 1, state_plane_stress, 3, 9), &
    element_type_t('CPE4RT', shape_quad4, 4, 4, 4, quad_edges, 1, state_plane_strain, 3, 9), &
    element_type_t('CAX4RT', shape_quad4, 4, 4, 4, quad_edges, 1, state_axisymmetric, 3, 9), &
    element_type_t('CPS8T', shape_quad8, 8, 4, 4, quad8_edges, 9, state_plane_stress, 16, 23), &
    element_type_t('CPE8T', shape_quad8, 8, 4, 4, quad8_edges, 9, state_plane_strain, 16, 23), &
    element_type_t('CAX8T', shape_quad8, 8, 4, 4, quad8_edges, 9, state_axisymmetric, 16, 23), &
    element_type_t('CPS8RT', shape_quad8, 8, 4, 4, quad8_edges, 4, state_plane_stress, 16, 23), &
    element_type_t('CPE8RT', shape_quad8, 8, 4, 4, quad8_edges, 4, state_plane_strain, 16, 23), &
    element_type_t('CAX8RT', shape_quad8, 8, 4, 4, quad8_edges, 4, state_axisymmetric, 16, 23)]

contains

  !> Purpose: catalogue index of an element type name (upper case), 0 if
  !> the name is not in the catalogue.
  pure integer function find_element_type(name) result(it)
    character(len=*), intent(in) :: name
    do it = 1, size(catalogue)
      if (catalogue(it)%name == name) return
    end do
    it = 0
  end function find_element_type

  !> Purpose: why a known Abaqus/CalculiX element name is not in the
  !> catalogue ('' when there is nothing particular to say).
  pure function unsupported_reason(name) result(s)
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: s
    select case (name)
    case ('M3D9', 'CPS9', 'CPE9')
      s = 'the 9-node quadrilateral is not implemented; gmsh writes 8-node quadrilaterals (CPS8) with ' // &
          '-setnumber Mesh.SecondOrderIncomplete 1'
    case ('D', 'DCOUP3D')
      ! CalculiX's network elements: its fluid networks (*FLUID SECTION)
      s = 'a fluid network element (CalculiX''s networks of *FLUID SECTION): fluid networks are not ' // &
          'implemented in cfe2d (docs/heat.md)'
    case default
      s = ''
    end select
  end function unsupported_reason

  pure function state_name(state) result(s)
    integer, intent(in) :: state
    character(len=:), allocatable :: s
    select case (state)
    case (state_plane_stress); s = 'plane stress'
    case (state_plane_strain); s = 'plane strain'
    case (state_axisymmetric); s = 'axisymmetric'
    case default; s = 'none'
    end select
  end function state_name

  !> Does the shape use triangle (area) coordinates?
  pure logical function is_triangle(shape)
    integer, intent(in) :: shape
    is_triangle = shape == shape_tri3 .or. shape == shape_tri6
  end function is_triangle

  !> Is the shape a line (2 or 3 nodes: a boundary line or a truss)?
  pure logical function is_line(shape)
    integer, intent(in) :: shape
    is_line = shape == shape_line2 .or. shape == shape_line3
  end function is_line

  !> Is the shape one of the springs?
  pure logical function is_spring_shape(shape)
    integer, intent(in) :: shape
    is_spring_shape = shape == shape_spring1 .or. shape == shape_spring2 .or. shape == shape_springa
  end function is_spring_shape

  !> Nodes on edge k of element type et: 2 (straight) or 3 (with a
  !> mid-side node).
  pure integer function edge_node_count(et, k)
    integer, intent(in) :: et, k
    edge_node_count = 2
    if (catalogue(et)%edge(3, k) > 0) edge_node_count = 3
  end function edge_node_count
  !> Purpose: the order in which gmsh and VTK list the nodes of an element
  !> of catalogue type et: node file_node_order(k) is their k-th. The same
  !> as the deck's but for the 3-node line, which Abaqus lists end,
  !> middle, end and gmsh and VTK end, end, middle.
  pure function file_node_order(et) result(order)
    integer, intent(in) :: et
    integer :: order(max_nodes), k
    order = [(k, k = 1, max_nodes)]
    if (catalogue(et)%shape == shape_line3) order(1:3) = [1, 3, 2]
  end function file_node_order

end module element_catalogue
