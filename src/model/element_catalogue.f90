!> The element catalogue: one entry per element type name a deck may use,
!> with everything the other layers need to know about that type (node
!> count, corner nodes, edges with their mid-side nodes, integration rule,
!> stress state, output type ids). Arrays everywhere are sized from here;
!> no other module tests node counts to find out what an element is.
!>
!> Adding an element type: one entry in `catalogue` (and, for a new shape,
!> the element routine in the elements layer with one line of dispatch).
module element_catalogue
  implicit none
  private
  public :: element_type_t, catalogue, max_nodes, max_edges, max_ip, &
            shape_line2, shape_tri3, shape_quad4, &
            state_none, state_plane_stress, state_plane_strain, state_axisymmetric, &
            find_element_type, state_name

  !> Geometric families; each has one element routine.
  integer, parameter :: shape_line2 = 1, shape_tri3 = 2, shape_quad4 = 3
  !> Stress states of the continuum elements (state_none: not a continuum).
  integer, parameter :: state_none = 0, state_plane_stress = 1, state_plane_strain = 2, &
                        state_axisymmetric = 3
  !> Largest node count, edge count and integration-point count of any type.
  integer, parameter :: max_nodes = 4, max_edges = 4, max_ip = 4

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
  integer, parameter :: line_edges(3, max_edges) = reshape([1, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0], [3, max_edges])

  !> T2D2/T3D2 are line elements: gmsh writes them for boundary curves; they
  !> carry no stiffness and serve to define surfaces.
  type(element_type_t), parameter :: catalogue(6) = [ &
    element_type_t('T3D2', shape_line2, 2, 2, 1, line_edges, 0, state_none, 1, 3), &
    element_type_t('T2D2', shape_line2, 2, 2, 1, line_edges, 0, state_none, 1, 3), &
    element_type_t('CPS3', shape_tri3, 3, 3, 3, tri_edges, 1, state_plane_stress, 2, 5), &
    element_type_t('CPE3', shape_tri3, 3, 3, 3, tri_edges, 1, state_plane_strain, 2, 5), &
    element_type_t('CPS4', shape_quad4, 4, 4, 4, quad_edges, 4, state_plane_stress, 3, 9), &
    element_type_t('CPE4', shape_quad4, 4, 4, 4, quad_edges, 4, state_plane_strain, 3, 9)]

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
end module element_catalogue
