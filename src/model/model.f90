!> The analysis model as read from the deck: mesh, sets, surfaces,
!> materials, sections, amplitudes, steps and contact pairs. Everything is
!> stored with internal (1..n) indices; user ids are kept for output.
module model
  use kinds, only: dp, name_len
  use strings, only: itoa
  use solver_codes, only: solver_cholmod, order_amd
  use element_catalogue, only: catalogue, max_nodes, state_none, is_line, is_spring_shape, shape_mass, state_axisymmetric
  use mesh_topology, only: topology_t
  implicit none
  private
  public :: model_t, node_set_t, elem_set_t, surface_t, material_t, section_t, &
            bc_t, cload_t, dload_t, amplitude_t, request_t, step_t, contact_pair_t, src_t, &
            equation_t, temp_t, pretension_t, tie_t, instance_t, rigid_t, transform_t, &
            rigid_body, rigid_kinematic, rigid_distributing, transform_rectangular, transform_cylindrical, &
            node_axes, has_transform, local_node_of, &
            node_label, elem_label, has_instances, &
            is_continuum, carries_stiffness, is_truss, is_spring, is_mass, is_drawn, axisymmetric_model, &
            elem_nodes, elem_thickness, &
            surf_element, surf_node, coupling_nts, coupling_mortar, &
            amp_step_time, amp_total_time, amplitude_at, find_name, edge_nodes, step_dloads, &
            dload_p, dload_bx, dload_by, dload_grav, dload_centrif, &
            law_elastic, law_neo_hooke, law_mooney_rivlin, law_deformation_plasticity, max_yield, controls_t, &
            nonlinear_material
  public :: orientation_t, orient_rectangular, orient_cylindrical, elastic_iso, elastic_ortho, elastic_aniso
  public :: kept_nodes
  public :: heat_load_t, heat_bf, gap_heat_t

  integer, parameter :: surf_element = 1, surf_node = 2
  !> contact_pair_t%coupling
  integer, parameter :: coupling_nts = 1, coupling_mortar = 2
  integer, parameter :: amp_step_time = 1, amp_total_time = 2
  !> What made a rigid_t: *RIGID BODY, *COUPLING with *KINEMATIC or with
  !> *DISTRIBUTING.
  integer, parameter :: rigid_body = 1, rigid_kinematic = 2, rigid_distributing = 3
  !> TYPE= of *TRANSFORM: rectangular (R) or cylindrical (C).
  integer, parameter :: transform_rectangular = 1, transform_cylindrical = 2
  !> Labels of distributed loads (dload_t).
  integer, parameter :: dload_p = 1, dload_bx = 2, dload_by = 3, dload_grav = 4, dload_centrif = 5
  !> Elastic laws of a material (material_t%law): *ELASTIC (linear; St
  !> Venant-Kirchhoff under NLGEOM, as CalculiX), *HYPERELASTIC NEO HOOKE
  !> and MOONEY-RIVLIN (CalculiX's strain energy and constants).
  integer, parameter :: law_elastic = 0, law_neo_hooke = 1, law_mooney_rivlin = 2
  !> TYPE= of *ELASTIC (material_t%elastic_type): isotropic (E, nu),
  !> orthotropic (ORTHO or ENGINEERING CONSTANTS) or fully anisotropic
  !> (ANISO); the last two keep the stiffness in material_t%c6.
  integer, parameter :: elastic_iso = 0, elastic_ortho = 1, elastic_aniso = 2
  !> SYSTEM= of *ORIENTATION (orientation_t%system).
  integer, parameter :: orient_rectangular = 1, orient_cylindrical = 2
  !> *DEFORMATION PLASTICITY: Ramberg-Osgood, J2 deformation theory (a
  !> nonlinear elastic law of the total strain; E and nu are its linear part).
  integer, parameter :: law_deformation_plasticity = 3
  !> Points of a *PLASTIC hardening table.
  integer, parameter :: max_yield = 64

  !> Where something was defined in the deck: for errors found after reading.
  type :: src_t
    integer :: line = 0   ! index into deck%lines
  end type src_t

  type :: node_set_t
    character(len=name_len) :: name = ''
    integer, allocatable :: items(:)
  end type node_set_t

  type :: elem_set_t
    character(len=name_len) :: name = ''
    integer, allocatable :: items(:)
  end type elem_set_t

  !> An element-based surface is a list of solid-element edges (element,
  !> local edge number); a node-based surface is a list of nodes.
  type :: surface_t
    character(len=name_len) :: name = ''
    integer :: kind = surf_element
    integer, allocatable :: elem(:), edge(:)
    integer, allocatable :: nodes(:)
  end type surface_t

  type :: material_t
    character(len=name_len) :: name = ''
    logical :: has_elastic = .false.
    real(dp) :: e = 0.0_dp, nu = 0.0_dp
    type(src_t) :: src
    logical :: has_density = .false.
    real(dp) :: density = 0.0_dp          ! mass per unit volume (*DENSITY)
    !> *EXPANSION: isotropic expansion coefficient; ZERO= is kept for the
    !> listing only: with a constant alpha the thermal strain alpha (T -
    !> T_initial) does not depend on it.
    logical :: has_expansion = .false.
    real(dp) :: alpha = 0.0_dp, alpha_zero = 0.0_dp
    !> The elastic law and the *HYPERELASTIC constants (C10, C01, D1 as
    !> CalculiX and Abaqus define them).
    integer :: law = law_elastic
    real(dp) :: c10 = 0.0_dp, c01 = 0.0_dp, d1 = 0.0_dp
    !> *PLASTIC: von Mises with isotropic hardening, the yield stress
    !> yield(1, k) at the equivalent plastic strain yield(2, k); nyield = 0:
    !> no plasticity.
    integer :: nyield = 0
    real(dp) :: yield(2, max_yield) = 0.0_dp
    !> *ELASTIC, TYPE=ORTHO, ENGINEERING CONSTANTS or ANISO: the 6x6
    !> stiffness in the material's axes, Voigt order (11, 22, 33, 12, 13,
    !> 23) with engineering shear strains, so that c6(i, j) is CalculiX's
    !> Dijkl; e and nu then hold the isotropic values of its mean
    !> compliance (3 / (S11 + S22 + S33) and -(S12 + S13 + S23) / (S11 +
    !> S22 + S33)), which contact penalties and hourglass control take.
    integer :: elastic_type = elastic_iso
    real(dp) :: c6(6, 6) = 0.0_dp
    !> *DEFORMATION PLASTICITY (law_deformation_plasticity): the yield
    !> offset sigma0, the exponent n and the yield offset factor alpha of
    !> eps = sig / E + alpha (sigma0 / E) (sig / sigma0)^n.
    real(dp) :: ro_sigma0 = 0.0_dp, ro_n = 1.0_dp, ro_alpha = 0.0_dp
    !> Heat transfer (docs/heat.md): *CONDUCTIVITY, constant, along the
    !> global axes x and y (r and z in axisymmetry): k11 = k22 = k when
    !> isotropic, k11 and k22 of TYPE=ORTHO; *SPECIFIC HEAT c, constant;
    !> the capacity is density * c.
    logical :: has_conductivity = .false., has_specific_heat = .false.
    real(dp) :: conductivity(2) = 0.0_dp, specific_heat = 0.0_dp
    !> A *CONDUCTIVITY of several data lines: k11, k22 at temperatures
    !> ktab(1, 1:nk) (increasing; linear between, constant beyond), in
    !> ktab(2:3, :); nk <= 1: the constant conductivity above.
    integer :: nk = 0
    real(dp) :: ktab(3, max_yield) = 0.0_dp
    !> A *SPECIFIC HEAT of several data lines: c at temperatures
    !> ctab(1, 1:nc) (increasing; linear between, constant beyond) in
    !> ctab(2, :); nc <= 1: the constant specific heat above.
    integer :: nc = 0
    real(dp) :: ctab(2, max_yield) = 0.0_dp
  end type material_t

  !> *ORIENTATION: local material axes, rectangular (point a on local
  !> 1, point b in the local 1-2 plane) or cylindrical (a and b on the
  !> axis, local 1 radial, 2 tangential, 3 along b - a), as CalculiX and
  !> Abaqus define them; then a rotation by angle (degrees) about local
  !> axis `axis` (0: none) from the optional second data line.
  type :: orientation_t
    character(len=name_len) :: name = ''
    integer :: system = orient_rectangular
    real(dp) :: a(3) = [1.0_dp, 0.0_dp, 0.0_dp], b(3) = [0.0_dp, 1.0_dp, 0.0_dp]
    integer :: axis = 0
    real(dp) :: angle = 0.0_dp
    type(src_t) :: src
  end type orientation_t

  !> A *SOLID SECTION (continuum elements and trusses) or a *SPRING
  !> (spring elements): what gives the elements of a set their stiffness.
  type :: section_t
    integer :: elset = 0
    character(len=name_len) :: material_name = ''
    integer :: material = 0
    real(dp) :: thickness = 1.0_dp
    type(src_t) :: src
    ! Decks written for CalculiX/Abaqus and meshes from gmsh:
    !> STATE= on *SOLID SECTION: the stress state (element_catalogue
    !> state_*) its elements take whatever their type name says; 0 keeps
    !> each element type's own.
    integer :: state = 0
    logical :: thickness_given = .false.   ! a data line gave the thickness
    !> NODAL THICKNESS: the thickness at each node comes from *NODAL
    !> THICKNESS (model_t%node_thickness), interpolated inside the element.
    logical :: nodal_thickness = .false.
    !> *SPRING (no material): a linear spring of constant `stiffness`
    !> acting on dof(1) of its first node and (SPRING2) dof(2) of its
    !> second; a SPRINGA acts along the line between its nodes. A truss
    !> takes `thickness` as its cross-sectional area.
    logical :: spring = .false.
    real(dp) :: stiffness = 0.0_dp
    integer :: dof(2) = 0
    !> *MASS (no material): the point mass of each MASS element of the
    !> set (the whole ring's in an axisymmetric model, as a point load).
    logical :: point_mass = .false.
    real(dp) :: mass = 0.0_dp
    !> ORIENTATION= of *SOLID SECTION: the *ORIENTATION (index into
    !> model_t%orientations, 0 the global axes) of its material's axes.
    character(len=name_len) :: orientation_name = ''
    integer :: orientation = 0
  end type section_t

  !> One prescribed dof. set is the node set it came from (0 for a single
  !> node), used to sum reactions per prescribed set.
  type :: bc_t
    integer :: node = 0, dof = 0, set = 0, amp = 0
    real(dp) :: value = 0.0_dp
  end type bc_t

  !> A nodal temperature: the initial one (*INITIAL CONDITIONS,
  !> TYPE=TEMPERATURE) or the one at the end of a step (*TEMPERATURE).
  type :: temp_t
    integer :: node = 0, amp = 0
    real(dp) :: value = 0.0_dp
  end type temp_t

  type :: cload_t
    integer :: node = 0, dof = 0, amp = 0
    real(dp) :: value = 0.0_dp
    type(src_t) :: src       ! its data line
  end type cload_t

  !> One distributed load on one element (*DLOAD, *DSLOAD), by its Abaqus
  !> label: a pressure Pk on face k (dload_p), a body force per unit volume
  !> along x or y (dload_bx, dload_by), gravity g along dir times the
  !> density (dload_grav), or a centrifugal load density * omega^2 times
  !> the distance from the axis through `point` (dload_centrif; its dir is
  !> the axis when it lies in the plane, 0 when normal to it). value is
  !> the magnitude at the end of the step (pressure, force per volume, g,
  !> omega^2). Element, label and face identify a load from step to step.
  type :: dload_t
    integer :: elem = 0
    integer :: label = 0
    integer :: face = 0
    integer :: amp = 0
    real(dp) :: value = 0.0_dp
    real(dp) :: dir(2) = 0.0_dp
    real(dp) :: point(2) = 0.0_dp
  end type dload_t

  !> *AMPLITUDE: tabular (points t, a: linear between them, constant
  !> beyond), or DEFINITION=PERIODIC (Abaqus' Fourier series, periodic =
  !> .true.): a0 + sum_n (ca(n) cos(n omega (t - t0)) + cb(n) sin(n omega
  !> (t - t0))) from t0 on, a0 before (amplitude_at).
  type :: amplitude_t
    character(len=name_len) :: name = ''
    integer :: time = amp_step_time
    real(dp), allocatable :: t(:), a(:)
    logical :: periodic = .false.
    real(dp) :: omega = 0.0_dp, t0 = 0.0_dp, a0 = 0.0_dp
    real(dp), allocatable :: ca(:), cb(:)
  end type amplitude_t

  !> *NODE PRINT / *EL PRINT / *NODE FILE / *EL FILE: a set (0 = all) and
  !> the quantities asked for.
  type :: request_t
    logical :: nodal = .true.
    logical :: to_file = .false.
    integer :: set = 0
    logical :: u = .false., rf = .false., s = .false., e = .false., cstress = .false.
    !> PEEQ: the equivalent plastic strain (element quantity)
    logical :: peeq = .false.
    !> GLOBAL= of *NODE PRINT: U and RF of a node with *TRANSFORM in global
    !> axes (YES) or in its local ones (NO, CalculiX's default).
    logical :: global = .false.
    !> TOTALS= of *NODE PRINT: YES lists the sum of RF over the set after
    !> the rows, ONLY the sum alone (and no row of U or RF), as CalculiX.
    logical :: totals = .false., only_totals = .false.
    !> The quantities in the order the card lists them (U, R for RF, S, E,
    !> P for PEEQ), the order of CalculiX's blocks in <job>.dat.
    character(len=8) :: order = ''
    !> Heat transfer: NT (temperatures) and RFL (reaction fluxes) of
    !> *NODE PRINT / *NODE FILE; HFL (the heat flux at the integration
    !> points) of *EL PRINT.
    logical :: nt = .false., rfl = .false., hfl = .false.
  end type request_t

  !> face of a heat_load_t that is a body flux (*DFLUX label BF)
  integer, parameter :: heat_bf = 0

  !> A distributed heat load on one element: *DFLUX (value the flux per
  !> unit area into face `face`, or per unit volume with face heat_bf) or
  !> *FILM (value the film coefficient h of face `face`, sink the sink
  !> temperature). Amplitudes scale value (DFLUX) or the sink (FILM).
  type :: heat_load_t
    integer :: elem = 0, face = 0, amp = 0
    real(dp) :: value = 0.0_dp, sink = 0.0_dp
  end type heat_load_t

  !> *CONTROLS of a nonlinear step (CalculiX's names and defaults, its
  !> manual "Convergence criteria" and *CONTROLS): PARAMETERS=FIELD gives
  !> R_n, C_n, (q_0), q_u, R_p, epsilon, C_epsilon, R_l; PARAMETERS=TIME
  !> INCREMENTATION gives I_0, I_R, I_P, I_C, I_L, I_G and D_f, D_C, D_B,
  !> (D_A, D_S, D_H), D_D. q_u > 0 replaces the average force.
  type :: controls_t
    real(dp) :: rn = 0.005_dp, cn = 0.02_dp, qu = 0.0_dp, rp = 0.02_dp, eps = 1.0e-5_dp, ceps = 1.0e-3_dp, &
                rl = 1.0e-8_dp
    integer :: i0 = 4, ir = 8, ip = 9, ic = 16, il = 10, ig = 4
    real(dp) :: df = 0.25_dp, dc = 0.5_dp, db = 0.75_dp, dd = 1.5_dp
  end type controls_t

  type :: step_t
    character(len=name_len) :: name = ''
    real(dp) :: dt = 1.0_dp, period = 1.0_dp
    integer :: max_inc = 1000
    logical :: new_bcs = .false., new_loads = .false.
    type(bc_t), allocatable :: bcs(:)
    type(cload_t), allocatable :: loads(:)
    type(request_t), allocatable :: requests(:)
    type(src_t) :: src
    !> Distributed loads (*DLOAD, *DSLOAD) of the step, and OP=NEW on them.
    type(dload_t), allocatable :: dloads(:)
    logical :: new_dloads = .false.
    !> *TEMPERATURE of the step (ramped over it, held afterwards), and
    !> OP=NEW on it (temperatures not given go back to the initial ones).
    type(temp_t), allocatable :: temps(:)
    logical :: new_temps = .false.
    !> NLGEOM (large deformation; once on, on in the later steps, as
    !> CalculiX), *STATIC's DIRECT (fixed increments) and its minimum and
    !> maximum increments (0: CalculiX's defaults).
    logical :: nlgeom = .false., direct = .false.
    !> *STATIC's SPLIT TOUCHING (cfe2d's own): a converged increment in
    !> which frictional points closed from an open gap is split
    !> (displacement_field's split_wanted; docs/contact.md, "Accuracy of
    !> stick and slip"). Off by default: it costs sub-increments.
    logical :: split_touching = .false.
    real(dp) :: dt_min = 0.0_dp, dt_max = 0.0_dp
    !> *CONTROLS in force in the step (kept by the later steps until
    !> *CONTROLS, RESET, as CalculiX)
    type(controls_t) :: controls
    !> When the step's print and file output is written (CalculiX: the
    !> last FREQUENCY= or TIME POINTS= of the step's output cards applies
    !> to all of them): every out_every-th increment, or, when out_times
    !> is allocated, at the first increment ending at or after each of
    !> those times (step time, or total time if out_total_time); always at
    !> the step's last increment.
    integer :: out_every = 1
    real(dp), allocatable :: out_times(:)
    logical :: out_total_time = .false.
    !> *CONTACT PRINT of the step: CDIS and CSTR of the closed slave nodes
    !> in <job>.dat (the listing's contact tables are written anyway).
    logical :: contact_print_cdis = .false., contact_print_cstr = .false.
    !> *HEAT TRANSFER (docs/heat.md): a step of the temperature field;
    !> steady (STEADY STATE) or transient (backward Euler); deltmx > 0: the
    !> largest temperature change of an automatic increment (DELTMX).
    logical :: heat = .false., steady = .false.
    real(dp) :: deltmx = 0.0_dp
    !> *COUPLED TEMPERATURE-DISPLACEMENT: a step of both fields (heat
    !> is then true too), the temperatures solved first in each increment
    !> and their thermal strain loading the displacements (docs/heat.md).
    logical :: coupled = .false.
    !> Prescribed temperatures (*BOUNDARY on dof 11; bc_t%dof 11),
    !> concentrated fluxes (*CFLUX; cload_t%dof 11), *DFLUX and *FILM;
    !> new_*: OP=NEW (the lists of earlier steps dropped); otherwise a
    !> step's lists add to the previous step's.
    type(bc_t), allocatable :: tbcs(:)
    type(cload_t), allocatable :: cfluxes(:)
    type(heat_load_t), allocatable :: dfluxes(:), films(:)
    logical :: new_tbcs = .false., new_cfluxes = .false., new_dfluxes = .false., new_films = .false.
    !> *RADIATE to the environment (heat_load_t: value the emissivity,
    !> sink the sink temperature of face `face`), OP=NEW on it.
    type(heat_load_t), allocatable :: radiates(:)
    logical :: new_radiates = .false.
    !> *FREQUENCY (docs/keywords.md): the natural frequencies of the
    !> tangent at the state the steps before leave; nev eigenvalues
    !> nearest the shift (2 pi freq_lower)^2, those outside [freq_lower,
    !> freq_upper] (cycles/time; < 0: not given) dropped; STORAGE= and
    !> SOLVER= as written (read and reported).
    logical :: frequency = .false.
    integer :: nev = 10
    real(dp) :: freq_lower = -1.0_dp, freq_upper = -1.0_dp
    character(len=16) :: freq_storage = '', freq_solver = ''
  end type step_t

  !> A slave (node set or surface) coupled to a master element surface.
  type :: contact_pair_t
    integer :: slave_surface = 0, master_surface = 0
    real(dp) :: penalty = -1.0_dp         ! < 0: automatic
    real(dp) :: open_ratio = 1.0e-12_dp   ! open penalty / closed penalty
    logical :: nodal = .false.            ! penalty given per node, not per area
    real(dp) :: search_distance = -1.0_dp ! < 0: automatic
    logical :: update_search = .false.
    !> Coulomb friction: the coefficient (0: frictionless) and the stick
    !> slope, the tangential penalty per unit area (shear stress per unit
    !> slip; < 0: automatic, as the normal penalty).
    real(dp) :: mu = 0.0_dp
    real(dp) :: stick_slope = -1.0_dp
    !> SYMMETRIC: the pair made for the second pass (master and slave
    !> swapped) and the other way round; 0 for a single pass.
    integer :: twin = 0
    !> Archard wear (*WEAR in its *SURFACE INTERACTION; docs/contact.md,
    !> "Wear"): wear (any wear), the coefficients of the slave and the
    !> master surface (worn depth per unit pressure and unit slip) and the
    !> cycle-jump factor (each computed increment's wear counts wear_jump
    !> times).
    logical :: wear = .false.
    real(dp) :: wear_k(2) = 0.0_dp
    real(dp) :: wear_jump = 1.0_dp
    !> The coupling: node-to-segment (the paper's CFE at each slave node,
    !> or Gauss points of 3-node slave faces) or segment-to-segment (a
    !> dual mortar CFE per slave node, the gap integrated over the slave
    !> faces: contact_mortar).
    integer :: coupling = coupling_nts
    !> Exact enforcement: non-penetration held by Lagrange multipliers (the
    !> contact pressures), solved directly for each contact status on the
    !> condensed path without friction, otherwise found by augmenting the
    !> penalty until the closed gaps vanish; false: the penalty alone.
    logical :: exact = .false.
    !> A soft pressure-overclosure law (*SURFACE BEHAVIOR, PRESSURE-
    !> OVERCLOSURE=EXPONENTIAL or TABULAR; docs/contact.md, "Soft contact
    !> laws"): the pressure is piecewise linear in the overclosure h (the
    !> negative gap) through the knots (soft_h(i), soft_p(i)), h increasing,
    !> soft_p(1) = 0 and the pressure increasing; zero for h < soft_h(1)
    !> (a clearance beyond -soft_h(1)), the last segment's slope beyond the
    !> last knot. Not allocated: the penalty law (penalty, exact).
    real(dp), allocatable :: soft_h(:), soft_p(:)
    type(src_t) :: src
    !> The *CONTACT PAIR card (file, line number, text), for messages once
    !> the deck's lines are gone (the contact search refuses a pairing
    !> there); card_line 0 where the pair was not read from a deck.
    character(len=:), allocatable :: card_file, card_text
    integer :: card_line = 0
    !> Heat through the contact (coupled and heat transfer runs): the
    !> pair's *GAP CONDUCTANCE and *GAP HEAT GENERATION, m%gap_heats(gap_heat)
    !> (0: none); halved (conductance) for each pass of a two-pass pair.
    integer :: gap_heat = 0
  end type contact_pair_t

  !> *GAP CONDUCTANCE and *GAP HEAT GENERATION of a *SURFACE INTERACTION
  !> (docs/heat.md, "Heat through the contact"): the conductance per unit
  !> area h(p) of a closed contact point, linear in the contact pressure
  !> between the table's points (pressure gc_p(i), conductance gc_h(i),
  !> pressures increasing) and constant beyond (one point: constant); an
  !> open point conducts nothing. clearance: Abaqus's h(d) instead, gc_p
  !> the clearances d (closed points at d = 0, open ones at their gap;
  !> zero beyond the last). Frictional heat: the fraction eta of the
  !> frictional power mu p |slip rate| (per unit area) is heat, the
  !> fraction f of it goes to the slave surface and 1 - f to the master;
  !> velocity > 0 is CalculiX's given slip rate (2D and axisymmetric models
  !> whose sliding is out of the plane), else the rate of the slip.
  type :: gap_heat_t
    character(len=name_len) :: name = ''
    real(dp), allocatable :: gc_p(:), gc_h(:)
    logical :: clearance = .false.
    logical :: generation = .false.
    real(dp) :: eta = 1.0_dp, f = 0.5_dp, velocity = 0.0_dp
  end type gap_heat_t

  !> *EQUATION: sum_k coef(k) * u(dof(k)) of node(k) = 0, one linear
  !> multi-point constraint, imposed by eliminating its first term's dof
  !> (module constraints, the analysis' numbering). The
  !> cards that generate constraints (*PRE-TENSION SECTION, *TIE) append
  !> theirs in the same form; src is then their card.
  type :: equation_t
    integer, allocatable :: node(:), dof(:)
    real(dp), allocatable :: coef(:)
    type(src_t) :: src
    !> The card that made it when not an *EQUATION (*TIE name, *PRE-TENSION
    !> SECTION surface), for messages once the deck's lines are gone.
    character(len=name_len + 24) :: origin = ''
    !> Made by a *RIGID BODY or *KINEMATIC coupling: the reference node and
    !> the rotation node (0: none) the dependent node follows rigidly, so
    !> that an NLGEOM step can impose the exact rotation (dof_numbering).
    integer :: rigid_ref = 0, rigid_rot = 0
  end type equation_t

  !> *PRE-TENSION SECTION: the element faces of `surface` are cut. Their
  !> nodes (original) are duplicated (copy, new nodes numbered after the
  !> largest node id), the elements owning the faces take the copies, and
  !> equations make each copy's displacement its original's plus
  !> u1(ref_node) * normal: dof 1 of the reference node is the opening of
  !> the cut along the normal (a load on it is the pre-tension force).
  !> original and copy are filled once the deck is read.
  type :: pretension_t
    integer :: surface = 0, ref_node = 0
    logical :: normal_given = .false.
    real(dp) :: normal(2) = 0.0_dp        ! unit; away from the elements owning the faces
    integer, allocatable :: original(:), copy(:)
    type(src_t) :: src
  end type pretension_t

  !> *TIE: each node of the slave surface within `tolerance` of a face of
  !> the master surface follows that face (one equation per dof, made by
  !> the contact layer, which owns the projection onto faces).
  type :: tie_t
    character(len=name_len) :: name = ''
    integer :: slave_surface = 0, master_surface = 0
    real(dp) :: tolerance = -1.0_dp       ! <= 0: 2.5 % of the master's mean face length
    logical :: adjust = .true.            ! move tied slave nodes onto the master
    !> TYPE=SURFACE TO SURFACE: a mortar tie (dual mortar weights,
    !> tie_constraints), not node to face
    logical :: mortar = .false.
    type(src_t) :: src
    !> Once generated: slave nodes tied, and not tied (no master face
    !> within the tolerance, or a node of the master surface itself);
    !> the largest distance ADJUST moved a tied node.
    integer :: tied = 0, untied = 0
    real(dp) :: largest_move = 0.0_dp
  end type tie_t

  !> *RIGID BODY, or *COUPLING with *KINEMATIC or *DISTRIBUTING: nodes
  !> tied to a reference node by linear constraints (small rotations),
  !> generated when the card is read (equation_t with this card as src).
  !> The in-plane rotation theta is dof 1 of rot_node: the user's ROT NODE
  !> (CalculiX: its dof 3 in the deck) or a node made for it, which the
  !> deck reaches as dof 6 of the reference node (Abaqus). Rigid body and
  !> kinematic coupling: each node j follows u_j = u_ref + theta x (x_j -
  !> x_ref) in the dofs that follow. Distributing coupling: the reverse,
  !> the reference node and theta are the nodes' weighted average (weight
  !> = the area each node stands for), no stiffness added: a load on the
  !> reference node is spread over the nodes.
  type :: rigid_t
    integer :: kind = rigid_body
    character(len=name_len) :: name = ''   ! the node set, element set or surface; the constraint name
    integer :: ref_node = 0, rot_node = 0  ! rot_node 0: no rotation (every node at the reference point)
    logical :: rot_given = .false.         ! rot_node is the user's ROT NODE
    logical :: ref_made = .false.          ! the reference node was made (no REF NODE: the origin)
    integer, allocatable :: nodes(:)       ! the nodes that follow (or are averaged)
    logical :: follows(2) = .true.         ! the translations that follow (*KINEMATIC's dofs)
    logical :: moment = .false.            ! *DISTRIBUTING: dof 6 named, a moment on it is spread
    type(src_t) :: src
  end type rigid_t

  !> *TRANSFORM: the local axes of the nodes of a set, in which their
  !> *BOUNDARY, *CLOAD and *EQUATION dofs are given. Rectangular: x' along
  !> a, y' in the plane of a and b (towards b); cylindrical (the axis along
  !> z through a, from a to b): x' radial, y' tangential, z' x x' = y'.
  type :: transform_t
    integer :: nset = 0
    integer :: kind = transform_rectangular
    real(dp) :: a(3) = 0.0_dp, b(3) = 0.0_dp
    real(dp) :: axes(2, 2) = 0.0_dp        ! rectangular: the columns x', y' in global components
    type(src_t) :: src
  end type transform_t

  !> An *INSTANCE of a *PART (Abaqus/CAE decks): its own copy of the
  !> part's nodes and elements, placed by `shift` and then turned by
  !> `angle` (degrees, counter-clockwise) about the z axis through
  !> `centre`. Node and element numbers are the part's labels, which the
  !> instances of a part share; internally each copy gets the id offset +
  !> label (the id of the result files), the offsets keeping instances
  !> apart. Its sets and surfaces are named INSTANCE.NAME.
  type :: instance_t
    character(len=name_len) :: name = ''
    character(len=name_len) :: part = ''
    integer :: node_offset = 0, node_last = 0   ! ids node_offset + 1 .. node_last
    integer :: elem_offset = 0, elem_last = 0
    integer :: nodes = 0, elements = 0
    real(dp) :: shift(2) = 0.0_dp, centre(2) = 0.0_dp, angle = 0.0_dp
    type(src_t) :: src
  end type instance_t

  type :: model_t
    character(len=:), allocatable :: heading, deck_name
    integer :: nn = 0, ne = 0
    integer, allocatable :: node_id(:), elem_id(:)
    real(dp), allocatable :: x(:, :)                  ! (2, nn)
    integer, allocatable :: etype(:)                  ! element_catalogue index
    integer, allocatable :: conn(:, :)                ! (max_nodes, ne)
    integer, allocatable :: elem_section(:)
    type(src_t), allocatable :: elem_src(:)
    integer, allocatable :: node_index(:), elem_index(:)  ! user id -> internal, 0 if none
    type(node_set_t), allocatable :: nsets(:)
    type(elem_set_t), allocatable :: elsets(:)
    type(surface_t), allocatable :: surfaces(:)
    type(material_t), allocatable :: materials(:)
    type(section_t), allocatable :: sections(:)
    type(amplitude_t), allocatable :: amplitudes(:)
    type(bc_t), allocatable :: model_bcs(:)
    type(step_t), allocatable :: steps(:)
    type(contact_pair_t), allocatable :: pairs(:)
    type(topology_t) :: topo                          ! edges, found once per mesh
    integer :: solver = solver_cholmod   ! solver_codes
    integer :: ordering = order_amd      ! solver_codes
    real(dp) :: contact_tolerance = 1.0e-6_dp
    integer :: contact_max_iter = 100
    integer :: max_cutbacks = 5
    ! Decks written for CalculiX/Abaqus, ParaView output:
    logical :: vtu = .false.                          ! FORMAT=VTU on *NODE FILE / *EL FILE
    type(equation_t), allocatable :: equations(:)     ! *EQUATION, and those generated
    type(pretension_t), allocatable :: pretensions(:) ! *PRE-TENSION SECTION
    type(tie_t), allocatable :: ties(:)               ! *TIE
    !> *SOLVER, CONTACT SOLVE=: solver_codes contact_solve_* (auto: the
    !> condensed contact solve where it pays, else the full one).
    integer :: contact_solve = 0
    !> *INITIAL CONDITIONS, TYPE=TEMPERATURE (nodes not named start at 0).
    type(temp_t), allocatable :: initial_temps(:)
    !> *INITIAL CONDITIONS, TYPE=STRESS: the initial stress of element e at
    !> its integration point ip, sig0(:, ip, e) = (s11, s22, s12, s33) in the
    !> order of the strain vector (element_catalogue's max_ip points, ne
    !> elements as the card found them); not allocated without the card.
    real(dp), allocatable :: sig0(:, :, :)
    !> *NODAL THICKNESS by node (nn), for the sections with NODAL
    !> THICKNESS; allocated only when a section asks for it.
    real(dp), allocatable :: node_thickness(:)
    !> *INSTANCE of a *PART (Abaqus/CAE decks); empty for a flat deck,
    !> whose node and element ids are the deck's numbers.
    type(instance_t), allocatable :: instances(:)
    !> *RIGID BODY and *COUPLING (their equations are in `equations`).
    type(rigid_t), allocatable :: rigids(:)
    !> *TRANSFORM; per node the transform that applies (the last naming
    !> it, 0 none) and the node made to carry its local displacements
    !> (0 none: made only for a node whose dofs a card names), of which
    !> its own are dependent: u = axes u(local node).
    type(transform_t), allocatable :: transforms(:)
    !> *ORIENTATION cards (the sections name them).
    type(orientation_t), allocatable :: orientations(:)
    integer, allocatable :: node_transform(:), local_node(:)
    !> A step is *HEAT TRANSFER: the run's field is the temperatures
    !> (temperature_field) and the materials need no *ELASTIC.
    logical :: heat = .false.
    !> *PHYSICAL CONSTANTS: ABSOLUTE ZERO (the temperature scale's zero,
    !> 0 in kelvin) and STEFAN BOLTZMANN (radiation: *RADIATE); has_*:
    !> given.
    real(dp) :: absolute_zero = 0.0_dp, stefan_boltzmann = 0.0_dp
    logical :: has_absolute_zero = .false., has_stefan_boltzmann = .false.
    !> The run has both fields, the temperatures before the displacements:
    !> a *COUPLED TEMPERATURE-DISPLACEMENT step, or heat transfer and
    !> mechanical steps in one deck (heat is then false: the materials
    !> need *ELASTIC).
    logical :: coupled = .false.
    !> *GAP CONDUCTANCE / *GAP HEAT GENERATION by surface interaction
    !> (contact_pair_t's gap_heat).
    type(gap_heat_t), allocatable :: gap_heats(:)
  end type model_t

contains

  !> Is element e a continuum element (one with stiffness), as opposed to
  !> a line element that only describes a boundary?
  pure logical function is_continuum(m, e)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    is_continuum = catalogue(m%etype(e))%state /= state_none
  end function is_continuum

  !> Purpose: whether a section of m has a nonlinear material (a
  !> hyperelastic law or *PLASTIC), which makes every step nonlinear.
  pure logical function nonlinear_material(m)
    type(model_t), intent(in) :: m
    integer :: s
    nonlinear_material = .false.
    if (.not. (allocated(m%sections) .and. allocated(m%materials))) return
    do s = 1, size(m%sections)
      if (m%sections(s)%spring .or. m%sections(s)%point_mass) cycle
      associate(mat => m%materials(m%sections(s)%material))
        nonlinear_material = nonlinear_material .or. mat%law /= law_elastic .or. mat%nyield > 0
      end associate
    end do
  end function nonlinear_material

  !> Does element e carry stiffness: a continuum element, a line element
  !> with a *SOLID SECTION (a truss), a spring with its *SPRING? The
  !> others (line elements without a section) only describe boundaries;
  !> a point mass only takes loads.
  pure logical function carries_stiffness(m, e)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    carries_stiffness = is_continuum(m, e)
    if (.not. carries_stiffness .and. allocated(m%elem_section) .and. .not. is_mass(m, e)) &
      carries_stiffness = m%elem_section(e) /= 0
  end function carries_stiffness

  !> Is element e one the result files show: a continuum element, a truss,
  !> a spring, a point mass (line elements without a section only
  !> describe boundaries)?
  pure logical function is_drawn(m, e)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    is_drawn = carries_stiffness(m, e) .or. is_mass(m, e)
  end function is_drawn

  !> Purpose: the nodes (nn) the analysis keeps: those of an element with
  !> stiffness or of a point mass, of the surfaces of a contact pair or a
  !> *TIE, or named by a linear constraint (*EQUATION and the equations
  !> that cards generate). Any other node, left over from meshing (a gmsh
  !> geometry point, the centre of an arc), is dropped: it gets no
  !> equation, has zero displacement, and nothing could carry a load on it.
  pure function kept_nodes(m) result(kept)
    type(model_t), intent(in) :: m
    logical :: kept(m%nn)
    integer :: e, k
    kept = .false.
    do e = 1, m%ne
      if (carries_stiffness(m, e) .or. is_mass(m, e)) kept(m%conn(1:elem_nodes(m, e), e)) = .true.
    end do
    if (allocated(m%pairs)) then
      do k = 1, size(m%pairs)
        kept(m%surfaces(m%pairs(k)%slave_surface)%nodes) = .true.
        kept(m%surfaces(m%pairs(k)%master_surface)%nodes) = .true.
      end do
    end if
    if (allocated(m%ties)) then
      do k = 1, size(m%ties)
        kept(m%surfaces(m%ties(k)%slave_surface)%nodes) = .true.
        kept(m%surfaces(m%ties(k)%master_surface)%nodes) = .true.
      end do
    end if
    if (allocated(m%equations)) then
      do k = 1, size(m%equations)
        kept(m%equations(k)%node) = .true.
      end do
    end if
  end function kept_nodes

  !> Purpose: does a *TRANSFORM apply to node a?
  pure logical function has_transform(m, a)
    type(model_t), intent(in) :: m
    integer, intent(in) :: a
    has_transform = .false.
    if (.not. allocated(m%node_transform)) return
    if (a > size(m%node_transform)) return
    has_transform = m%node_transform(a) > 0
  end function has_transform

  !> Purpose: the node carrying node a's local displacements (its
  !> *TRANSFORM's), 0 if none.
  pure integer function local_node_of(m, a)
    type(model_t), intent(in) :: m
    integer, intent(in) :: a
    local_node_of = 0
    if (.not. allocated(m%local_node)) return
    if (a > size(m%local_node)) return
    local_node_of = m%local_node(a)
  end function local_node_of

  !> Purpose: the local axes of node a (columns x', y' in global
  !> components: u_global = r u_local), the identity without *TRANSFORM.
  !> Cylindrical: x' from the axis to the node, y' = z' x x' (z' from a
  !> to b); the reader refused nodes on the axis.
  pure function node_axes(m, a) result(r)
    type(model_t), intent(in) :: m
    integer, intent(in) :: a
    real(dp) :: r(2, 2), d(2), s
    r = reshape([1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [2, 2])
    if (.not. has_transform(m, a)) return
    associate(t => m%transforms(m%node_transform(a)))
      if (t%kind == transform_rectangular) then
        r = t%axes
      else
        d = m%x(:, a) - t%a(1:2)
        d = d / norm2(d)
        s = sign(1.0_dp, t%b(3) - t%a(3))
        r(:, 1) = d
        r(:, 2) = s * [-d(2), d(1)]
      end if
    end associate
  end function node_axes

  !> Has the model axisymmetric elements (so its point loads and masses
  !> are whole rings about the y axis)?
  pure logical function axisymmetric_model(m)
    type(model_t), intent(in) :: m
    axisymmetric_model = any(catalogue(m%etype(1:m%ne))%state == state_axisymmetric)
  end function axisymmetric_model

  !> Is element e a point mass (MASS)?
  pure logical function is_mass(m, e)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    is_mass = catalogue(m%etype(e))%shape == shape_mass
  end function is_mass

  !> Is element e a truss (a line element with a *SOLID SECTION)?
  pure logical function is_truss(m, e)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    is_truss = is_line(catalogue(m%etype(e))%shape)
    if (is_truss) is_truss = carries_stiffness(m, e)
  end function is_truss

  !> Is element e a spring (SPRING1, SPRING2, SPRINGA)?
  pure logical function is_spring(m, e)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    is_spring = is_spring_shape(catalogue(m%etype(e))%shape)
  end function is_spring

  !> Purpose: the thickness of continuum element e at each of its nodes
  !> (entries beyond its nodes are 1): its section's, or with NODAL
  !> THICKNESS the nodes' own (the element interpolates them).
  pure function elem_thickness(m, e) result(t)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    real(dp) :: t(max_nodes)
    integer :: n
    t = 1.0_dp
    n = elem_nodes(m, e)
    associate(sec => m%sections(m%elem_section(e)))
      if (sec%nodal_thickness .and. allocated(m%node_thickness)) then
        t(1:n) = m%node_thickness(m%conn(1:n, e))
      else
        t(1:n) = sec%thickness
      end if
    end associate
  end function elem_thickness

  !> Number of nodes of element e.
  pure integer function elem_nodes(m, e)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    elem_nodes = catalogue(m%etype(e))%nodes
  end function elem_nodes

  !> Nodes of local edge k of a solid element, counter-clockwise (Abaqus
  !> face Sk runs from corner k to corner k+1): corners a and b, and the
  !> mid-side node (0 on a straight 2-node edge).
  pure subroutine edge_nodes(m, e, k, a, b, mid)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e, k
    integer, intent(out) :: a, b
    integer, intent(out), optional :: mid
    a = m%conn(catalogue(m%etype(e))%edge(1, k), e)
    b = m%conn(catalogue(m%etype(e))%edge(2, k), e)
    if (present(mid)) then
      mid = 0
      if (catalogue(m%etype(e))%edge(3, k) > 0) mid = m%conn(catalogue(m%etype(e))%edge(3, k), e)
    end if
  end subroutine edge_nodes

  !> Number of distributed loads of a step (none if the step never had
  !> a *DLOAD or *DSLOAD).
  pure integer function step_dloads(st)
    type(step_t), intent(in) :: st
    step_dloads = 0
    if (allocated(st%dloads)) step_dloads = size(st%dloads)
  end function step_dloads

  !> Has the model instances of parts (an Abaqus/CAE deck)?
  pure logical function has_instances(m)
    type(model_t), intent(in) :: m
    has_instances = .false.
    if (allocated(m%instances)) has_instances = size(m%instances) > 0
  end function has_instances

  !> Purpose: node a as the deck names it, for messages and the listing:
  !> INSTANCE.LABEL for a node of an instance (`PART-1-1.17`), else its
  !> number (a flat deck's, or an assembly-level node's).
  pure function node_label(m, a) result(s)
    type(model_t), intent(in) :: m
    integer, intent(in) :: a
    character(len=:), allocatable :: s
    integer :: k
    s = itoa(m%node_id(a))
    if (.not. has_instances(m)) return
    do k = 1, size(m%instances)
      associate(inst => m%instances(k))
        if (m%node_id(a) > inst%node_offset .and. m%node_id(a) <= inst%node_last) then
          s = trim(inst%name) // '.' // itoa(m%node_id(a) - inst%node_offset)
          return
        end if
      end associate
    end do
  end function node_label

  !> Purpose: element e as the deck names it (see node_label).
  pure function elem_label(m, e) result(s)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    character(len=:), allocatable :: s
    integer :: k
    s = itoa(m%elem_id(e))
    if (.not. has_instances(m)) return
    do k = 1, size(m%instances)
      associate(inst => m%instances(k))
        if (m%elem_id(e) > inst%elem_offset .and. m%elem_id(e) <= inst%elem_last) then
          s = trim(inst%name) // '.' // itoa(m%elem_id(e) - inst%elem_offset)
          return
        end if
      end associate
    end do
  end function elem_label

  !> Purpose: the value of amplitude a at time tt (the step time, or the
  !> total time for TIME=TOTAL TIME: the caller's choice). Tabular: linear
  !> between its points, constant beyond its ends. PERIODIC (Abaqus'
  !> definition): a0 before t0, from t0 on the Fourier series
  !>   a0 + sum_{n=1}^N [ca(n) cos(n omega (tt - t0)) + cb(n) sin(n omega (tt - t0))].
  pure real(dp) function amplitude_at(a, tt) result(v)
    type(amplitude_t), intent(in) :: a
    real(dp), intent(in) :: tt
    integer :: k, n
    real(dp) :: phase
    if (a%periodic) then
      v = a%a0
      if (tt < a%t0) return
      phase = a%omega * (tt - a%t0)
      do k = 1, size(a%ca)
        v = v + a%ca(k) * cos(k * phase) + a%cb(k) * sin(k * phase)
      end do
      return
    end if
    n = size(a%t)
    if (tt <= a%t(1)) then
      v = a%a(1)
    else if (tt >= a%t(n)) then
      v = a%a(n)
    else
      k = first_not_below(a%t, tt)
      v = a%a(k - 1) + (a%a(k) - a%a(k - 1)) * (tt - a%t(k - 1)) / (a%t(k) - a%t(k - 1))
    end if
  end function amplitude_at

  !> Purpose: the first k >= 2 with tt <= t(k), for strictly increasing
  !> times t (the *AMPLITUDE reader's rule) and t(1) < tt < t(n): by
  !> bisection, since a cyclic history's table grows with its cycles
  !> (fretting: four points a cycle, 72 000 for 18 000 cycles, read at
  !> every increment). The same k as a scan from the start.
  pure integer function first_not_below(t, tt) result(k)
    real(dp), intent(in) :: t(:), tt
    integer :: lo, mid
    ! invariant: t(lo) < tt <= t(k)
    lo = 1
    k = size(t)
    do while (k - lo > 1)
      mid = lo + (k - lo) / 2
      if (tt <= t(mid)) then
        k = mid
      else
        lo = mid
      end if
    end do
  end function first_not_below

  !> Index of a name in a list of names (case already folded), 0 if absent.
  pure integer function find_name(names, name)
    character(len=*), intent(in) :: names(:)
    character(len=*), intent(in) :: name
    integer :: i
    find_name = 0
    do i = 1, size(names)
      if (names(i) == name) then
        find_name = i
        return
      end if
    end do
  end function find_name
end module model
