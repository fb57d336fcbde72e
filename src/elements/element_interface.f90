!> The one interface every element routine shares (FEAP style): an action
!> code says what to compute, element data come in, element arrays go out.
!> No element routine sees global state. Sizes come from the element
!> catalogue.
module element_interface
  use kinds, only: dp
  use model, only: law_elastic, max_yield
  use element_catalogue, only: max_nodes, max_ip, shape_tri3, shape_quad4, shape_tri6, shape_quad8, state_none, &
                               shape_line2, shape_line3, shape_spring1, shape_spring2, shape_springa
  implicit none
  private
  public :: elem_in_t, elem_out_t, cfe_in_t, cfe_out_t, max_en, max_edof, max_ip, max_slave, &
            kind_quad4, kind_tri3, kind_quad8, kind_tri6, kind_truss2, kind_truss3, kind_spring1, &
            kind_spring2, kind_springa, act_tangent, act_residual, act_stresses, &
            act_thermal, wants, max_hist

  !> Routine selectors: a continuum element is its catalogue shape (one
  !> routine serves them all), so are a truss (a line) and a spring. The
  !> coupling element is not among them: it has its own types and routine
  !> (cfe_element), which the contact and analysis layers call.
  integer, parameter :: kind_tri3 = shape_tri3, kind_quad4 = shape_quad4, kind_tri6 = shape_tri6, &
                        kind_quad8 = shape_quad8, kind_truss2 = shape_line2, kind_truss3 = shape_line3, &
                        kind_spring1 = shape_spring1, kind_spring2 = shape_spring2, &
                        kind_springa = shape_springa
  !> Slave-side nodes of a coupling element whose coupling point lies on
  !> one slave face (its coupling point is a weighted combination of them,
  !> section 5 of the paper).
  integer, parameter :: max_slave = 3
  !> Nodes of the largest body element: the fixed arrays of elem_in_t and
  !> elem_out_t, on the hot path of every body element call, hold this
  !> many. Coupling elements have their own types (cfe_in_t, cfe_out_t)
  !> with arrays as large as each coupling needs: a segment-to-segment
  !> coupling holds every node its support reaches, however many.
  integer, parameter :: max_en = max_nodes, max_edof = 2 * max_en
  !> Actions, combined with ior: tangent stiffness ke, internal force fe
  !> (and, for a coupling element, its gap and normal force), stresses and
  !> strains at the integration points and extrapolated to the nodes; the
  !> equivalent nodal load of the thermal strain (continuum elements: fe =
  !> integral of B^T D eps0, eps0 = alpha * (T - T_initial)).
  integer, parameter :: act_tangent = 1, act_residual = 2, act_stresses = 4, act_thermal = 8
  !> History variables per integration point of a material with state
  !> (plasticity); their layout is the material law's.
  integer, parameter :: max_hist = 8

  type :: elem_in_t
    integer :: kind = 0
    integer :: nen = 0                      ! nodes
    real(dp) :: xy(2, max_en) = 0.0_dp      ! nodal coordinates
    real(dp) :: ue(max_edof) = 0.0_dp       ! nodal displacements
    ! continuum elements and trusses
    real(dp) :: e = 0.0_dp, nu = 0.0_dp
    !> Thickness at each node (continuum elements), interpolated with the
    !> shape functions; not used in axisymmetry.
    real(dp) :: thickness(max_nodes) = 1.0_dp
    integer :: state = state_none           ! element_catalogue stress state
    integer :: nip = 0                      ! integration points (catalogue rule)
    real(dp) :: area = 0.0_dp               ! truss: cross-sectional area
    ! springs: the constant, and the dof (1 or 2) at the first node and
    ! (SPRING2) at the second
    real(dp) :: stiffness = 0.0_dp
    integer :: dofs(2) = 0
    !> Thermal strain: expansion coefficient and the nodal temperature
    !> change from the initial state; the stresses are D (eps - eps0).
    real(dp) :: alpha = 0.0_dp
    real(dp) :: dtemp(max_nodes) = 0.0_dp
    !> Nonlinear bodies: large deformation (NLGEOM), the elastic law and
    !> its constants (model's law_*; law_elastic uses e and nu), the
    !> *PLASTIC table (nyield = 0: elastic), and the history at the
    !> integration points committed by the last converged increment.
    !> The table and the history have no default: they are defined (and
    !> read) only where nyield > 0 or the law has state, so that the
    !> linear elements' input is not made larger to initialise (the
    !> stress recovery builds it once per element and increment).
    logical :: nlgeom = .false.
    integer :: law = law_elastic
    real(dp) :: c10 = 0.0_dp, c01 = 0.0_dp, d1 = 0.0_dp
    !> *DEFORMATION PLASTICITY's sigma0, n and alpha (model's material_t)
    real(dp) :: ro_sigma0 = 0.0_dp, ro_n = 1.0_dp, ro_alpha = 0.0_dp
    integer :: nyield = 0
    real(dp) :: yield(2, max_yield)
    real(dp) :: hist(max_hist, max_ip)
    !> Anisotropic elasticity (*ELASTIC TYPE=ORTHO, ENGINEERING CONSTANTS,
    !> ANISO): c6 the 6x6 stiffness in the material axes (materials'
    !> Voigt order; no default, read only where aniso), and the
    !> *ORIENTATION that gives those axes at a point (materials'
    !> orientation_axes: system 0 the global axes, else model's
    !> orient_*; points a, b; the extra rotation by angle about axis).
    logical :: aniso = .false.
    real(dp) :: c6(6, 6)
    integer :: orient_system = 0, orient_axis = 0
    real(dp) :: orient_a(3) = 0.0_dp, orient_b(3) = 0.0_dp, orient_angle = 0.0_dp
  end type elem_in_t

  type :: elem_out_t
    integer :: ndof = 0
    !> No default: each element routine zeroes ke(1:ndof, 1:ndof), the part
    !> it defines and its callers read; a default would clear the whole
    !> max_edof square on every element call.
    real(dp) :: ke(max_edof, max_edof)
    real(dp) :: fe(max_edof) = 0.0_dp          ! internal force
    integer :: nip = 0
    real(dp) :: sig_ip(4, max_ip) = 0.0_dp     ! s11, s22, s33, s12
    real(dp) :: eps_ip(3, max_ip) = 0.0_dp     ! e11, e22, gamma12
    real(dp) :: sig_node(4, max_nodes) = 0.0_dp   ! extrapolated to the nodes
    !> continuum element: the smallest det J (times r in axisymmetry) at
    !> its integration points; not positive means an invalid element
    real(dp) :: detj_min = 0.0_dp
    !> Nonlinear bodies: the history at the integration points at ue (from
    !> ein%hist; the driver commits it when the increment converges) and
    !> the equivalent plastic strain (PEEQ) there.
    real(dp) :: hist(max_hist, max_ip) = 0.0_dp
    real(dp) :: peeq_ip(max_ip) = 0.0_dp
  end type elem_out_t

  !> Input of a coupling element (cfe_element): nen nodes, the ns slave
  !> nodes first (the coupling point sum_j ws(j) x_j), then the master
  !> side: the master element's nodes with its shape functions at xi
  !> (master_kind its catalogue shape), or (master_kind 0, segment-to-
  !> segment contact) master nodes with the given weights wm. The arrays
  !> that grow with the coupling are allocatable: ue(2 nen), wm(nen - ns).
  type :: cfe_in_t
    integer :: nen = 0
    real(dp), allocatable :: ue(:)          ! nodal displacements
    integer :: ns = 1
    real(dp) :: ws(max_slave) = [1.0_dp, 0.0_dp, 0.0_dp]
    integer :: master_kind = 0
    real(dp) :: xi(2) = 0.0_dp
    real(dp), allocatable :: wm(:)
    !> unit outward normal of the master edge, normal penalty and the
    !> initial gap [[U]]_0
    real(dp) :: normal(2) = 0.0_dp
    real(dp) :: penalty = 0.0_dp
    real(dp) :: gap0(2) = 0.0_dp
    !> Closed: the penalty acts on the gap [[U]] (eq. 9). Open: it acts on
    !> the relative motion B_e D_e only, so that an open CFE carries no
    !> force at zero relative motion whatever its initial gap.
    logical :: closed = .true.
    !> Open: the normal relative motion n . B_e D_e at which the penalty
    !> carries nothing (0; the anchor of a stabilised open penalty,
    !> contact's restabilise).
    real(dp) :: open_shift = 0.0_dp
    !> Coulomb friction of a closed coupling element (mu = 0: none): the
    !> tangential penalty, sliding or sticking, the direction of sliding
    !> (+-1 along t = (-n_y, n_x)) and the anchor, the tangential relative
    !> displacement t.[[U]] at which a sticking element carries no
    !> tangential force (its slip so far).
    real(dp) :: mu = 0.0_dp, k_tan = 0.0_dp
    logical :: sliding = .false.
    real(dp) :: slip_sign = 0.0_dp, anchor = 0.0_dp
  end type cfe_in_t

  !> Output of a coupling element: its tangent ke(ndof, ndof) (allocated
  !> with act_tangent only) and internal force fe(ndof) (ndof = 2 nen), the relative
  !> displacement [[U]] (eq. 8) and its normal component, the normal gap
  !> (negative = penetration), the normal force, and the tangential
  !> component t.[[U]] and tangential force.
  type :: cfe_out_t
    integer :: ndof = 0
    real(dp), allocatable :: ke(:, :), fe(:)
    real(dp) :: jump(2) = 0.0_dp
    real(dp) :: gap = 0.0_dp
    real(dp) :: normal_force = 0.0_dp
    real(dp) :: slide = 0.0_dp, tangential_force = 0.0_dp
  end type cfe_out_t

contains

  !> Does action code `action` include `what`?
  pure logical function wants(action, what)
    integer, intent(in) :: action, what
    wants = iand(action, what) /= 0
  end function wants
end module element_interface
