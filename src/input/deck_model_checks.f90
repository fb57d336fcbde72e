!> Checks that need the whole deck: sections and their materials (a
!> material may be defined after the section naming it), one section per
!> solid element, truss and spring, element geometry, a procedure in
!> every step, linear constraints that can be eliminated. The element
!> topology (edges and neighbours) is built last.
submodule (deck_parser) deck_model_checks
  use kinds, only: dp
  use strings, only: itoa, to_upper
  use deck_input, only: deck_warning
  use deck_cursor, only: err
  use model, only: is_continuum, carries_stiffness, is_truss, is_spring, is_mass, find_name, bc_t, kept_nodes, &
                   node_label, elem_label, law_elastic, step_dloads, law_neo_hooke, law_mooney_rivlin, &
                   law_deformation_plasticity, heat_load_t, heat_bf
  use constraints, only: mpc_t, resolve_equations
  use element_catalogue, only: catalogue, find_element_type, state_name, state_plane_stress, state_plane_strain, &
                               state_axisymmetric, shape_springa, max_edges
  use growable, only: grow
  use mesh_topology, only: build_topology
  implicit none

contains

  !> Purpose: checks after the last card; errors name the card at fault
  !> (the section, the element line, the step).
  module subroutine check_model(p, m)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    integer :: s
    call check_sections(p, m)
    call check_nonlinear_materials(p, m)
    call apply_section_states(p, m)
    call apply_nodal_thickness(p, m)
    ! (after the sections: an interaction's out-of-plane thickness is checked against theirs)
    call interaction_penalties(p, m)
    call warn_plane_stress(p, m)
    call check_elements(p, m)
    call check_equations(p, m)
    if (size(m%steps) == 0) then
      p%i = p%deck%n
      call err(p, 'the deck has no *STEP: nothing to analyse')
    end if
    do s = 1, size(m%steps)
      if (m%steps(s)%period < 0.0_dp) then
        p%i = m%steps(s)%src%line
        call err(p, 'step has no procedure (*STATIC)')
      end if
    end do
    if (count([(carries_stiffness(m, s), s = 1, m%ne)]) == 0) then
      p%i = m%steps(1)%src%line
      call err(p, 'the model has no element with stiffness (no continuum element, truss or spring; line ' // &
               'elements without a section only describe boundaries): nothing to analyse')
    end if
    call check_unused_nodes(p, m)
    call build_topology(m%nn, m%ne, m%etype, m%conn, m%topo)
    call drop_collapsed_faces(m)
  end subroutine check_model

  !> Purpose: a hyperelastic material makes every step geometrically
  !> nonlinear (CalculiX sets NLGEOM when it reads *HYPERELASTIC); a
  !> truss of a hyperelastic or plastic material stops at its section
  !> (the truss is linear elastic), so does the thermal strain of a
  !> hyperelastic material, and of a plastic one under NLGEOM, at the
  !> material (the element routines do not have it).
  subroutine check_nonlinear_materials(p, m)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    integer :: s, k, e, imat
    logical :: hyper
    hyper = .false.
    do s = 1, size(m%sections)
      if (m%sections(s)%spring .or. m%sections(s)%point_mass) cycle
      imat = m%sections(s)%material
      if (m%materials(imat)%law == law_elastic .and. m%materials(imat)%nyield == 0) cycle
      ! the initial stress is a load of the linear path (assembly)
      if (allocated(m%sig0)) then
        p%i = m%sections(s)%src%line
        call err(p, '*INITIAL CONDITIONS, TYPE=STRESS with the nonlinear material ' // &
                 trim(m%materials(imat)%name) // ' is not implemented (only with *ELASTIC)')
      end if
      ! (*DEFORMATION PLASTICITY set the parser's NLGEOM at its card: a step
      ! may still say NLGEOM=NO, where it is a law of small strain)
      hyper = hyper .or. m%materials(imat)%law == law_neo_hooke .or. m%materials(imat)%law == law_mooney_rivlin
      ! the element routines have no thermal strain for these laws
      if (m%materials(imat)%has_expansion .and. m%materials(imat)%alpha /= 0.0_dp) then
        p%i = m%materials(imat)%src%line
        if (m%materials(imat)%law == law_neo_hooke .or. m%materials(imat)%law == law_mooney_rivlin) call err(p, &
          'material ' // trim(m%materials(imat)%name) // &
          ': the thermal strain (*EXPANSION) of a hyperelastic material is not implemented')
        if (any(m%steps%nlgeom)) call err(p, 'material ' // trim(m%materials(imat)%name) // ': the thermal ' // &
          'strain (*EXPANSION) of a plastic material under NLGEOM is not implemented (it is without NLGEOM)')
      end if
      do k = 1, size(m%elsets(m%sections(s)%elset)%items)
        e = m%elsets(m%sections(s)%elset)%items(k)
        if (.not. is_truss(m, e)) cycle
        p%i = m%sections(s)%src%line
        call err(p, 'element ' // elem_label(m, e) // ' is a truss of material ' // trim(m%materials(imat)%name) // &
                 ', which is hyperelastic or plastic: the truss is linear elastic')
      end do
    end do
    if (hyper) m%steps(:)%nlgeom = .true.
    if (allocated(m%sig0) .and. any(m%steps%nlgeom)) then
      p%i = m%steps(findloc(m%steps%nlgeom, .true., 1))%src%line
      call err(p, '*INITIAL CONDITIONS, TYPE=STRESS under NLGEOM is not implemented (only in small-deformation steps)')
    end if
  end subroutine check_nonlinear_materials

  !> Purpose: nodes that no element, contact surface or constraint uses
  !> (model's kept_nodes: left over from meshing, a gmsh geometry point or
  !> the centre of an arc, as CalculiX ignores them) are dropped by the
  !> analysis: one warning counts them and names the first few, at the
  !> data line of the first. A *BOUNDARY on them is ignored, but a
  !> *CLOAD on one would be lost without a trace: an error at its line.
  subroutine check_unused_nodes(p, m)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(in) :: m
    integer, parameter :: named = 5
    logical :: kept(m%nn)
    integer, allocatable :: unused(:)
    character(len=:), allocatable :: ids
    integer :: k, s, j
    kept = kept_nodes(m)
    if (all(kept)) return
    unused = pack([(k, k = 1, m%nn)], .not. kept)
    ids = itoa(m%node_id(unused(1)))
    do k = 2, min(size(unused), named)
      ids = ids // ', ' // itoa(m%node_id(unused(k)))
    end do
    if (size(unused) > named) ids = ids // ' and ' // itoa(size(unused) - named) // ' more'
    if (size(unused) == 1) then
      ids = '1 node belongs to no element with stiffness or mass, contact surface or *EQUATION (left over ' // &
            'from meshing?): ' // ids // '; it is'
    else
      ids = itoa(size(unused)) // ' nodes belong to no element with stiffness or mass, contact surface or ' // &
            '*EQUATION (left over from meshing?): ' // ids // '; they are'
    end if
    call deck_warning(p%deck, p%node_line(unused(1)), ids // ' left out of the analysis, with zero ' // &
                      'displacement in the outputs (a *BOUNDARY there is ignored)')
    do s = 1, size(m%steps)
      do j = 1, size(m%steps(s)%loads)
        associate(ld => m%steps(s)%loads(j))
          if (kept(ld%node) .or. ld%value == 0.0_dp) cycle
          p%i = ld%src%line
          call err(p, 'node ' // itoa(m%node_id(ld%node)) // ' is left out of the analysis (it belongs to no ' // &
                   'element with stiffness or mass, contact surface or *EQUATION): this *CLOAD on it would be lost')
        end associate
      end do
    end do
  end subroutine check_unused_nodes

  !> *EQUATION: the constraints can be eliminated (module constraints
  !> says why not), and no dependent dof (a first term) is also
  !> prescribed by a *BOUNDARY of the model or of a step, which CalculiX
  !> refuses too. Errors name the equation's first term line.
  subroutine check_equations(p, m)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(in) :: m
    type(mpc_t) :: mpc
    character(len=:), allocatable :: msg
    integer :: bad, s
    if (size(m%equations) == 0) return
    call resolve_equations(m, mpc, bad, msg)
    if (bad == 0) then
      call bc_on_dependent(m, mpc, m%model_bcs, bad, msg)
      do s = 1, size(m%steps)
        if (bad == 0) call bc_on_dependent(m, mpc, m%steps(s)%bcs, bad, msg)
      end do
    end if
    if (bad == 0) return
    p%i = m%equations(bad)%src%line
    call err(p, msg)
  end subroutine check_equations

  !> The first equation whose dependent dof one of bcs prescribes (0 if
  !> none), and the message.
  subroutine bc_on_dependent(m, mpc, bcs, bad, msg)
    type(model_t), intent(in) :: m
    type(mpc_t), intent(in) :: mpc
    type(bc_t), intent(in) :: bcs(:)
    integer, intent(out) :: bad
    character(len=:), allocatable, intent(inout) :: msg
    integer :: j
    bad = 0
    do j = 1, size(bcs)
      bad = mpc%dep(bcs(j)%dof, bcs(j)%node)
      if (bad == 0) cycle
      if (len_trim(m%equations(bad)%origin) > 0) then
        ! a generated constraint: the card's node follows others
        msg = 'dof ' // itoa(bcs(j)%dof) // ' of node ' // node_label(m, bcs(j)%node) // ' follows other ' // &
              'dofs through the constraint made by ' // trim(m%equations(bad)%origin) // ' and also has a ' // &
              '*BOUNDARY; prescribe the dofs it follows (a reference node) instead'
      else
        msg = 'dof ' // itoa(bcs(j)%dof) // ' of node ' // node_label(m, bcs(j)%node) // ' is the dependent ' // &
              'dof of this *EQUATION (its first term, eliminated) and also has a *BOUNDARY; put an independent ' // &
              'dof first, or prescribe another one'
      end if
      return
    end do
  end subroutine bc_on_dependent

  !> Every solid section's material exists and is elastic; each element
  !> is in at most one section or *SPRING (m%elem_section filled here); a
  !> solid section's line elements are trusses, which need an area.
  subroutine check_sections(p, m)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    integer :: s, k, e, imat
    allocate(m%elem_section(m%ne))
    m%elem_section = 0
    do s = 1, size(m%sections)
      p%i = m%sections(s)%src%line
      if (.not. (m%sections(s)%spring .or. m%sections(s)%point_mass)) then
        imat = find_name(m%materials%name, m%sections(s)%material_name)
        if (imat == 0) call err(p, 'undefined material ' // trim(m%sections(s)%material_name))
        if (.not. m%materials(imat)%has_elastic .and. m%materials(imat)%law == law_elastic .and. .not. m%heat) then
          p%i = m%materials(imat)%src%line
          call err(p, 'material ' // trim(m%materials(imat)%name) // ' has no *ELASTIC (nor *HYPERELASTIC)')
        end if
        if (m%materials(imat)%has_elastic .and. m%materials(imat)%law == law_deformation_plasticity) then
          p%i = m%materials(imat)%src%line
          call err(p, 'material ' // trim(m%materials(imat)%name) // ' has *ELASTIC and *DEFORMATION PLASTICITY, ' // &
                   'which gives E and nu itself')
        end if
        if (m%materials(imat)%nyield > 0 .and. .not. m%materials(imat)%has_elastic) then
          p%i = m%materials(imat)%src%line
          call err(p, 'material ' // trim(m%materials(imat)%name) // ' has *PLASTIC but no *ELASTIC')
        end if
        m%sections(s)%material = imat
      end if
      do k = 1, size(m%elsets(m%sections(s)%elset)%items)
        e = m%elsets(m%sections(s)%elset)%items(k)
        if (is_spring(m, e) .and. .not. m%sections(s)%spring) call err(p, 'element ' // elem_label(m, e) // &
            ' is a spring (' // trim(catalogue(m%etype(e))%name) // '): its constant comes from *SPRING, not ' // &
            'from a *SOLID SECTION')
        if (is_mass(m, e) .and. .not. m%sections(s)%point_mass) call err(p, 'element ' // elem_label(m, e) // &
            ' is a point mass (MASS): its mass comes from *MASS, not from a *SOLID SECTION')
        if (m%elem_section(e) /= 0) call err(p, 'element ' // elem_label(m, e) // ' is in two sections')
        m%elem_section(e) = s
        if (.not. is_truss(m, e)) cycle
        if (m%sections(s)%nodal_thickness) call err(p, 'element ' // elem_label(m, e) // ' is a truss (' // &
            trim(catalogue(m%etype(e))%name) // ' with a section): its area comes from the data line of the ' // &
            'section, and NODAL THICKNESS is for plane elements')
        if (.not. m%sections(s)%thickness_given) call err(p, 'element ' // elem_label(m, e) // ' is a ' // &
            'truss (' // trim(catalogue(m%etype(e))%name) // ' with a section): its cross-sectional area ' // &
            'is needed on the data line of the section')
      end do
      call warn_mixed_section(p, m, s)
    end do
  end subroutine check_sections

  !> A section naming continuum elements and line elements alike (a gmsh
  !> set of everything, boundary lines included) makes the lines trusses
  !> whose area is the plane elements' thickness: as CalculiX does, but
  !> seldom what was meant, so it is said.
  subroutine warn_mixed_section(p, m, s)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    integer, intent(in) :: s
    integer :: k, e, nsolid, ntruss
    nsolid = 0
    ntruss = 0
    do k = 1, size(m%elsets(m%sections(s)%elset)%items)
      e = m%elsets(m%sections(s)%elset)%items(k)
      if (is_continuum(m, e)) nsolid = nsolid + 1
      if (is_truss(m, e)) ntruss = ntruss + 1
    end do
    if (nsolid > 0 .and. ntruss > 0) call deck_warning(p%deck, m%sections(s)%src%line, 'this section names ' // &
      itoa(nsolid) // ' continuum elements and ' // itoa(ntruss) // ' line elements: the line elements ' // &
      'become trusses whose cross-sectional area is the section''s thickness (to keep boundary lines out, ' // &
      'name the continuum elements'' set only)')
  end subroutine warn_mixed_section

  !> Purpose: STATE= of *SOLID SECTION: each element of the section takes
  !> the catalogue type of the asked stress state with the same shape
  !> (CPS4 -> CPE4 for PLANE STRAIN), so an unedited gmsh mesh (CPS*) can
  !> be plane strain. A type without such a counterpart is an error.
  subroutine apply_section_states(p, m)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    character(len=:), allocatable :: old, new
    integer :: e, s, it
    do e = 1, m%ne
      if (.not. is_continuum(m, e) .or. m%elem_section(e) == 0) cycle
      s = m%elem_section(e)
      if (m%sections(s)%state == 0) cycle
      if (catalogue(m%etype(e))%state == m%sections(s)%state) cycle
      old = trim(catalogue(m%etype(e))%name)
      new = state_prefix(m%sections(s)%state) // old(4:)
      it = 0
      if (any(old(1:3) == [state_prefix(state_plane_stress), state_prefix(state_plane_strain), &
                           state_prefix(state_axisymmetric)])) it = find_element_type(new)
      if (it == 0) then
        p%i = m%sections(s)%src%line
        call err(p, 'element type ' // old // ' (element ' // elem_label(m, e) // ') has no ' // &
                 state_name(m%sections(s)%state) // ' counterpart in cfe2d''s catalogue')
      end if
      m%etype(e) = it
    end do
  end subroutine apply_section_states

  !> The element name prefix of a stress state (Abaqus naming).
  pure function state_prefix(state) result(s)
    integer, intent(in) :: state
    character(len=3) :: s
    select case (state)
    case (state_plane_stress); s = 'CPS'
    case (state_plane_strain); s = 'CPE'
    case default; s = 'CAX'
    end select
  end function state_prefix

  !> Purpose: sections with NODAL THICKNESS take the thickness at each
  !> node of their plane elements from *NODAL THICKNESS (m%node_thickness;
  !> the elements interpolate it). Every such node needs one; the
  !> axisymmetric elements of such a section use none (their thickness is
  !> the whole circumference, as in CalculiX).
  subroutine apply_nodal_thickness(p, m)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    integer :: e, s, k, nen
    if (p%nodal_thickness_line > 0 .and. .not. any(m%sections%nodal_thickness)) then
      call deck_warning(p%deck, p%nodal_thickness_line, 'no *SOLID SECTION has NODAL THICKNESS: the ' // &
                        'section thickness applies and *NODAL THICKNESS is ignored (as in CalculiX)')
    end if
    if (.not. any(m%sections%nodal_thickness)) return
    call grow(p%node_thickness, m%nn, fill=-1.0_dp)
    do e = 1, m%ne
      s = m%elem_section(e)
      if (s == 0) cycle
      if (.not. m%sections(s)%nodal_thickness) cycle
      ! the section's thickness line (if any) is irrelevant, as in CalculiX
      m%sections(s)%thickness_given = .true.
      if (catalogue(m%etype(e))%state == state_axisymmetric) cycle
      nen = catalogue(m%etype(e))%nodes
      do k = 1, nen
        if (p%node_thickness(m%conn(k, e)) >= 0.0_dp) cycle
        p%i = m%sections(s)%src%line
        call err(p, 'NODAL THICKNESS: node ' // node_label(m, m%conn(k, e)) // ' of element ' // &
                 elem_label(m, e) // ' has no *NODAL THICKNESS')
      end do
    end do
    m%node_thickness = p%node_thickness(1:m%nn)
  end subroutine apply_nodal_thickness

  !> Purpose: warnings for a model that is probably meant to be plane
  !> strain but is plane stress: a plane-stress section without a
  !> thickness line, and plane-stress elements in a deck whose title says
  !> plane strain. Both name STATE=PLANE STRAIN as the way out.
  subroutine warn_plane_stress(p, m)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(in) :: m
    logical :: stress(size(m%sections))
    integer :: e
    stress = .false.
    ! (heat transfer: the stress state plays no part)
    if (m%heat) return
    do e = 1, m%ne
      if (m%elem_section(e) == 0) cycle
      if (catalogue(m%etype(e))%state == state_plane_stress) stress(m%elem_section(e)) = .true.
    end do
    do e = 1, size(m%sections)
      if (.not. stress(e) .or. m%sections(e)%thickness_given .or. m%sections(e)%state /= 0) cycle
      call deck_warning(p%deck, m%sections(e)%src%line, 'plane-stress elements (CPS) without a thickness ' // &
          'line: thickness 1 is used; for plane strain add STATE=PLANE STRAIN')
    end do
    if (any(stress) .and. p%heading_line > 0) then
      if (index(to_upper(m%heading), 'PLANE STRAIN') > 0) call deck_warning(p%deck, p%heading_line, &
          'the title says plane strain, but elements are plane stress (CPS); add STATE=PLANE STRAIN to their ' // &
          '*SOLID SECTION or use CPE elements')
    end if
  end subroutine warn_plane_stress

  !> Every solid element has a section and a positive Jacobian at each
  !> corner, or is a collapsed quadrilateral (check_corners; one warning
  !> counts them); every spring has its *SPRING; a truss or a SPRINGA has two
  !> distinct ends (its direction), a 3-node truss does not fold back;
  !> trusses and springs are not
  !> mixed with axisymmetric elements.
  subroutine check_elements(p, m)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    integer :: e, ncol, first_col
    logical :: axi
    axi = .false.
    ncol = 0
    first_col = 0
    do e = 1, m%ne
      p%i = m%elem_src(e)%line
      if (is_spring(m, e) .and. m%elem_section(e) == 0) call err(p, 'spring element ' // elem_label(m, e) // &
          ' has no *SPRING (its constant)')
      if (is_mass(m, e) .and. m%elem_section(e) == 0) call err(p, 'point mass element ' // elem_label(m, e) // &
          ' has no *MASS (its mass)')
      if (is_truss(m, e) .or. catalogue(m%etype(e))%shape == shape_springa) then
        if (end_distance(m, e) <= 0.0_dp) call err(p, 'element ' // elem_label(m, e) // ' (' // &
            trim(catalogue(m%etype(e))%name) // ') has both ends at the same point')
      end if
      if (is_truss(m, e) .and. catalogue(m%etype(e))%nodes == 3) then
        if (truss_folds(m, e)) call err(p, 'element ' // elem_label(m, e) // ' (' // &
            trim(catalogue(m%etype(e))%name) // ') folds back on itself: its middle node (the second) must lie ' // &
            'between the points a quarter of the way from each end, along the line of its ends')
      end if
      if (.not. is_continuum(m, e)) cycle
      axi = axi .or. catalogue(m%etype(e))%state == state_axisymmetric
      if (m%elem_section(e) == 0) call err(p, 'element ' // elem_label(m, e) // ' has no *SOLID SECTION')
      call check_corners(p, m, e, ncol, first_col)
    end do
    if (ncol > 0) call deck_warning(p%deck, m%elem_src(first_col)%line, itoa(ncol) // ' collapsed ' // &
        'quadrilateral(s) (two neighbouring corners at one point; the first: element ' // &
        elem_label(m, first_col) // '): where the two are one node the element is the triangle of its ' // &
        'corners; two nodes stay two (the degenerate element, as CalculiX integrates it)')
    if (ncol > 0) call collapse_to_triangles(m)
    if (.not. axi) return
    do e = 1, m%ne
      if (.not. (is_truss(m, e) .or. is_spring(m, e))) cycle
      p%i = m%elem_src(e)%line
      call err(p, 'element ' // elem_label(m, e) // ' (' // trim(catalogue(m%etype(e))%name) // ') in an ' // &
          'axisymmetric model: whether it stands for a ring or for bars around the axis is not defined ' // &
          'here; trusses and springs are implemented for plane models only')
    end do
  end subroutine check_elements

  !> Distance between the end nodes of a truss (a 3-node one lists end,
  !> middle, end) or a SPRINGA.
  real(dp) function end_distance(m, e)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    integer :: last
    last = catalogue(m%etype(e))%edge(2, 1)
    if (last == 0) last = 2
    end_distance = norm2(m%x(:, m%conn(last, e)) - m%x(:, m%conn(1, e)))
  end function end_distance

  !> A 3-node truss (end, middle, end) whose arc turns back: dx/ds =
  !> (x3 - x1) / 2 + s (x1 + x3 - 2 x2) is linear in s, so it keeps the
  !> direction of the chord x3 - x1 over s in [-1, 1] if and only if it
  !> does at both ends; otherwise a stretch of the bar is counted twice
  !> (the stiffness of a folded element, whose |dx/ds| stays positive).
  logical function truss_folds(m, e)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    real(dp) :: c(2), q(2)
    associate(x1 => m%x(:, m%conn(1, e)), x2 => m%x(:, m%conn(2, e)), x3 => m%x(:, m%conn(3, e)))
      c = x3 - x1
      q = x1 + x3 - 2.0_dp * x2
    end associate
    truss_folds = .not. 0.5_dp * dot_product(c, c) > abs(dot_product(q, c))
  end function truss_folds

  !> Purpose: the corner check of continuum element e: a positive
  !> Jacobian at every corner, or a collapsed quadrilateral (collapsed_face:
  !> two neighbouring corners at one point, and with 8 nodes the mid-side
  !> node between them there too) whose three other corners make a
  !> counter-clockwise triangle, counted in ncol (first_col the first).
  !> When the two corners are one node the element is that triangle
  !> (collapse_to_triangles makes it one): the shape functions of the
  !> merged corners add up to one function, and with the other two they
  !> span the triangle's linear fields (isoparametric). Two nodes at one
  !> point stay two nodes (the degenerate element as CalculiX integrates
  !> it). No node may appear twice otherwise. Errors say why an element is
  !> refused.
  !> Arguments: p the parser (errors at the element's line), m, e; ncol
  !> and first_col updated.
  subroutine check_corners(p, m, e, ncol, first_col)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    integer, intent(inout) :: ncol, first_col
    integer :: k, nc, nen, i, corner(3)
    character(len=:), allocatable :: what
    what = 'element ' // elem_label(m, e) // ' (' // trim(catalogue(m%etype(e))%name) // ')'
    nc = catalogue(m%etype(e))%corners
    nen = catalogue(m%etype(e))%nodes
    k = collapsed_face(m, e)
    if (k < 0) call err(p, what // ' has two corners at one point that are not neighbours, or two faces ' // &
                        'of no length (it collapses to a line or a point): it is no element')
    do i = 2, nen
      if (.not. any(m%conn(1:i - 1, e) == m%conn(i, e))) cycle
      if (k > 0) then
        if (any(catalogue(m%etype(e))%edge(:, k) == i)) cycle
      end if
      call err(p, what // ' uses node ' // node_label(m, m%conn(i, e)) // ' twice (only the two corners ' // &
               'of a collapsed face, and its mid-side node, may be one node)')
    end do
    if (k == 0) then
      if (min_corner_jacobian(m, e) <= 0.0_dp) call err(p, what // ' has a zero or negative Jacobian at a ' // &
          'corner: its corners are ' // corner_fault(m, m%conn(1:nc, e)))
      return
    end if
    associate(ed => catalogue(m%etype(e))%edge(:, k))
      if (ed(3) > 0) then
        if (.not. coincident(m, e, ed(3), ed(1))) call err(p, what // ' is a collapsed quadrilateral (face S' // &
            itoa(k) // ' has no length) whose mid-side node on that face is elsewhere: it must be at its corners')
      end if
      corner = [ed(2), mod(ed(2), nc) + 1, mod(ed(2) + 1, nc) + 1]
    end associate
    if (.not. triangle_area(m, m%conn(corner, e)) > 0.0_dp) call err(p, what // ' is a collapsed ' // &
        'quadrilateral (face S' // itoa(k) // ' has no length) whose other corners are ' // &
        corner_fault(m, m%conn(corner, e)))
    ncol = ncol + 1
    if (first_col == 0) first_col = e
  end subroutine check_corners

  !> Purpose: the face of quadrilateral e collapsed to a point: k where
  !> the two corners of face k coincide (one node, or two at one point)
  !> and no other two corners do; 0 when no two corners coincide (and for
  !> a triangle); -1 when two corners that are not neighbours coincide,
  !> or two faces do.
  integer function collapsed_face(m, e) result(k)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    integer :: i, j
    k = 0
    if (catalogue(m%etype(e))%corners /= 4) return
    do i = 1, 3
      do j = i + 1, 4
        if (.not. coincident(m, e, i, j)) cycle
        if (k /= 0 .or. j == i + 2) then
          k = -1
          return
        end if
        k = i
        if (j == 4 .and. i == 1) k = 4
      end do
    end do
  end function collapsed_face

  !> Are local nodes i and j of element e one node, or two at one point
  !> (round-off of the element's size)?
  logical function coincident(m, e, i, j)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e, i, j
    real(dp) :: size2
    integer :: k, nc
    coincident = m%conn(i, e) == m%conn(j, e)
    if (coincident) return
    nc = catalogue(m%etype(e))%corners
    size2 = 0.0_dp
    do k = 2, nc
      size2 = max(size2, sum((m%x(:, m%conn(k, e)) - m%x(:, m%conn(1, e)))**2))
    end do
    coincident = sum((m%x(:, m%conn(i, e)) - m%x(:, m%conn(j, e)))**2) <= 1.0e-24_dp * size2
  end function coincident

  !> Twice the signed area of the triangle of nodes t(1:3) (positive
  !> counter-clockwise), zero where it is round-off of its edges' size.
  real(dp) function triangle_area(m, t)
    type(model_t), intent(in) :: m
    integer, intent(in) :: t(3)
    real(dp) :: u(2), v(2)
    u = m%x(:, t(2)) - m%x(:, t(1))
    v = m%x(:, t(3)) - m%x(:, t(1))
    triangle_area = u(1) * v(2) - u(2) * v(1)
    if (abs(triangle_area) <= 1.0e-12_dp * max(sum(u**2), sum(v**2))) triangle_area = 0.0_dp
  end function triangle_area

  !> Purpose: why the corners (nodes) of a polygon give no valid element:
  !> two at one point, clockwise, on one line, or a corner of 180 degrees
  !> or more.
  function corner_fault(m, nodes) result(s)
    type(model_t), intent(in) :: m
    integer, intent(in) :: nodes(:)
    character(len=:), allocatable :: s
    integer :: i, j, n
    real(dp) :: area, scale
    n = size(nodes)
    area = 0.0_dp
    scale = 0.0_dp
    do i = 1, n
      j = mod(i, n) + 1
      if (norm2(m%x(:, nodes(j)) - m%x(:, nodes(i))) == 0.0_dp) then
        s = 'nodes ' // node_label(m, nodes(i)) // ' and ' // node_label(m, nodes(j)) // ', at one point'
        if (n == 4 .and. nodes(i) /= nodes(j)) s = s // ' (two nodes: a collapsed quadrilateral names one ' // &
            'node twice)'
        return
      end if
      area = area + m%x(1, nodes(i)) * m%x(2, nodes(j)) - m%x(1, nodes(j)) * m%x(2, nodes(i))
      scale = max(scale, sum((m%x(:, nodes(j)) - m%x(:, nodes(i)))**2))
    end do
    if (area < -1.0e-12_dp * scale) then
      s = 'clockwise (list them counter-clockwise)'
    else if (area <= 1.0e-12_dp * scale) then
      s = 'on one line'
    else
      s = 'not convex (an angle of 180 degrees or more)'
    end if
  end function corner_fault

  !> Purpose: a collapsed quadrilateral whose collapsed face is one node
  !> becomes the triangle it is: the catalogue's triangle of its stress
  !> state (CPS4, CPS4R -> CPS3; CPS8, CPS8R -> CPS6; CPE, CAX alike),
  !> its corners from the end of the collapsed face k on, k+1, k+2, k+3
  !> (and their faces' mid-side nodes); faces k+1, k+2, k+3 of the
  !> quadrilateral become the triangle's S1, S2, S3 in the element
  !> surfaces and the face loads, and face k (a point) leaves them. For
  !> the bilinear shape this changes nothing but the bookkeeping (its
  !> field and its stiffness are the triangle's, check_corners); the
  !> analysis then never sees an element that names a node twice.
  !> Arguments: m, whose etype, conn, surfaces and step loads change.
  subroutine collapse_to_triangles(m)
    type(model_t), intent(inout) :: m
    integer :: e, k, j, nc, it, map(max_edges), conn(8)
    character(len=:), allocatable :: name
    do e = 1, m%ne
      if (.not. is_continuum(m, e)) cycle
      k = collapsed_face(m, e)
      if (k <= 0) cycle
      if (m%conn(catalogue(m%etype(e))%edge(1, k), e) /= m%conn(catalogue(m%etype(e))%edge(2, k), e)) cycle
      name = trim(catalogue(m%etype(e))%name)
      nc = 3
      if (catalogue(m%etype(e))%nodes == 8) nc = 6
      ! the family's letters: CPS, CPE, CAX; DC2D, DCAX of heat transfer
      j = 3
      if (name(1:2) == 'DC') j = 4
      it = find_element_type(name(1:j) // merge('3', '6', nc == 3))
      if (it == 0) cycle
      map = 0
      conn = m%conn(1:8, e)
      do j = 1, 3
        map(mod(k + j - 1, 4) + 1) = j
        m%conn(j, e) = conn(mod(k + j - 1, 4) + 1)
        if (nc == 6) m%conn(3 + j, e) = conn(4 + mod(k + j - 1, 4) + 1)
      end do
      m%conn(nc + 1:, e) = 0
      m%etype(e) = it
      call renumber_faces(m, e, map)
    end do
  end subroutine collapse_to_triangles

  !> Purpose: face j of element e becomes face map(j) (0: it is gone, a
  !> point, and so are its surface entry and its pressure, whose resultant
  !> was zero) in the element surfaces and in the face loads of every step.
  subroutine renumber_faces(m, e, map)
    type(model_t), intent(inout) :: m
    integer, intent(in) :: e, map(max_edges)
    integer :: s, i
    logical, allocatable :: keep(:)
    do s = 1, size(m%surfaces)
      if (.not. allocated(m%surfaces(s)%elem)) cycle
      keep = .not. (m%surfaces(s)%elem == e .and. map(max(m%surfaces(s)%edge, 1)) == 0)
      where (m%surfaces(s)%elem == e) m%surfaces(s)%edge = map(max(m%surfaces(s)%edge, 1))
      m%surfaces(s)%elem = pack(m%surfaces(s)%elem, keep)
      m%surfaces(s)%edge = pack(m%surfaces(s)%edge, keep)
    end do
    do s = 1, size(m%steps)
      if (step_dloads(m%steps(s)) == 0) cycle
      keep = [(.true., i = 1, size(m%steps(s)%dloads))]
      do i = 1, size(m%steps(s)%dloads)
        associate(d => m%steps(s)%dloads(i))
          if (d%elem /= e .or. d%face == 0) cycle
          keep(i) = map(d%face) > 0
          if (keep(i)) d%face = map(d%face)
        end associate
      end do
      m%steps(s)%dloads = pack(m%steps(s)%dloads, keep)
    end do
    do s = 1, size(m%steps)
      if (allocated(m%steps(s)%dfluxes)) call renumber_heat_faces(m%steps(s)%dfluxes, e, map)
      if (allocated(m%steps(s)%films)) call renumber_heat_faces(m%steps(s)%films, e, map)
      if (allocated(m%steps(s)%radiates)) call renumber_heat_faces(m%steps(s)%radiates, e, map)
    end do
  end subroutine renumber_faces

  !> Purpose: the face fluxes, films and radiation of a heat step on element
  !> e follow its faces (renumber_faces): face j becomes map(j), a face that
  !> is a point leaves (nothing flows through it); a body flux (face 0)
  !> stays.
  subroutine renumber_heat_faces(loads, e, map)
    type(heat_load_t), allocatable, intent(inout) :: loads(:)
    integer, intent(in) :: e, map(max_edges)
    logical, allocatable :: keep(:)
    integer :: i
    allocate(keep(size(loads)))
    keep = .true.
    do i = 1, size(loads)
      if (loads(i)%elem /= e .or. loads(i)%face == heat_bf) cycle
      keep(i) = map(loads(i)%face) > 0
      if (keep(i)) loads(i)%face = map(loads(i)%face)
    end do
    loads = pack(loads, keep)
  end subroutine renumber_heat_faces

  !> Purpose: the collapsed face of a collapsed quadrilateral (a point) is
  !> no face: the topology gets no edge there (neighbour -1), so it is on
  !> no boundary a contact surface or a node set's faces would take.
  subroutine drop_collapsed_faces(m)
    type(model_t), intent(inout) :: m
    integer :: e, k
    do e = 1, m%ne
      if (.not. is_continuum(m, e)) cycle
      k = collapsed_face(m, e)
      if (k > 0) m%topo%neighbour(k, e) = -1
    end do
  end subroutine drop_collapsed_faces

  !> Smallest corner value of the Jacobian determinant: positive at every
  !> corner means a valid, convex, counter-clockwise element.
  real(dp) function min_corner_jacobian(m, e)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    integer :: nen, k
    real(dp) :: a(2), b(2), scale
    nen = catalogue(m%etype(e))%corners
    min_corner_jacobian = huge(1.0_dp)
    scale = 0.0_dp
    do k = 1, nen
      a = m%x(:, m%conn(mod(k, nen) + 1, e)) - m%x(:, m%conn(k, e))
      b = m%x(:, m%conn(mod(k + nen - 2, nen) + 1, e)) - m%x(:, m%conn(k, e))
      min_corner_jacobian = min(min_corner_jacobian, a(1) * b(2) - a(2) * b(1))
      scale = max(scale, sum(a**2))
    end do
    ! Collinear corners give round-off sized values of either sign.
    if (min_corner_jacobian <= 1.0e-12_dp * scale) min_corner_jacobian = 0.0_dp
  end function min_corner_jacobian
end submodule deck_model_checks
