!> Cards that tie nodes to a reference node or turn the axes of their
!> dofs, all imposed as linear constraints (equation_t, the form of
!> *EQUATION) with small rotations: *RIGID BODY, *COUPLING with
!> *KINEMATIC or *DISTRIBUTING, and *TRANSFORM. The equations of *RIGID
!> BODY and *KINEMATIC name their reference and rotation nodes
!> (equation_t%rigid_ref, rigid_rot), by which an NLGEOM step turns
!> their nodes exactly (dof_numbering: follow_rotations).
!>
!> A reference node's in-plane rotation theta is dof 1 of a rotation
!> node: the user's ROT NODE (CalculiX; in the deck its dof 3, the
!> rotation about z) or a node made for it at the reference node, which
!> the deck reaches as dof 6 of the reference node (Abaqus). The readers
!> of *BOUNDARY, *CLOAD and *EQUATION map those dofs (deck_cursor's
!> deck_dof), so the cards must come before the lines that name the
!> rotation. Nodes made here get ids after the largest once the deck is
!> read (finish_kinematic_cards), as the copies of a pre-tension cut do.
!>
!> *TRANSFORM is applied once the deck is read: every node of a
!> transformed set whose dofs a *BOUNDARY, *CLOAD or *EQUATION names gets
!> a node carrying its local displacements, to which those cards are
!> redirected, and its own (global) dofs are made dependent on them.
submodule (deck_parser) deck_rigid_cards
  use kinds, only: dp
  use strings, only: split_fields, to_upper, field_t, itoa, rtoa
  use deck_input, only: param_value, has_param, deck_warning
  use deck_cursor, only: line_text, err, next_data, allow_params, get_real, get_int, is_label, node_ref, &
                         need_nset, need_elset, warn_empty_set, check_name_length, max_id
  use model, only: rigid_t, transform_t, equation_t, surf_element, find_name, edge_nodes, elem_nodes, node_label, &
                   elem_label, axisymmetric_model, rigid_body, rigid_kinematic, rigid_distributing, &
                   transform_rectangular, transform_cylindrical, node_axes
  use model_growth, only: grow
  use growable, only: grow
  use constraints, only: rigid_chains
  implicit none

  !> Relative size below which a coordinate counts as zero (a direction
  !> out of the plane, a node on a cylinder's axis).
  real(dp), parameter :: small = 1.0e-12_dp

contains

  ! ------------------------------------------------------------ *RIGID BODY

  !> Purpose: *RIGID BODY, NSET= or ELSET= (the nodes of its elements;
  !> Abaqus' PIN NSET= and TIE NSET= add nodes: in 2D, with no rotations
  !> at the nodes, they are the same), REF NODE= (default: a node made at
  !> the origin, as CalculiX does), ROT NODE= (default: a node made for
  !> the rotation, dof 6 of the reference node). Every node of the body but
  !> the reference and rotation nodes follows u = u_ref + theta x (x -
  !> x_ref): two equations per node.
  module subroutine read_rigid_body(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(rigid_t) :: r
    integer, allocatable :: nodes(:)
    integer :: iset, k, e
    call allow_params(p, kw, 'NSET,ELSET,REF NODE,REFNODE,ROT NODE,ROTNODE,PIN NSET,PINNSET,TIE NSET,TIENSET')
    r%kind = rigid_body
    r%src%line = p%i
    allocate(nodes(0))
    if (.not. (has_param(kw, 'NSET') .or. has_param(kw, 'ELSET') .or. param2(kw, 'PIN NSET') /= '' .or. &
               param2(kw, 'TIE NSET') /= '')) call err(p, '*RIGID BODY needs NSET= or ELSET= (the body)')
    if (has_param(kw, 'NSET') .and. has_param(kw, 'ELSET')) &
      call err(p, 'NSET= and ELSET= are mutually exclusive (as in CalculiX)')
    if (has_param(kw, 'NSET')) call add_nset_nodes(param_value(kw, 'NSET'))
    if (param2(kw, 'PIN NSET') /= '') call add_nset_nodes(param2(kw, 'PIN NSET'))
    if (param2(kw, 'TIE NSET') /= '') call add_nset_nodes(param2(kw, 'TIE NSET'))
    if (has_param(kw, 'ELSET')) then
      iset = need_elset(p, m, param_value(kw, 'ELSET'))
      r%name = m%elsets(iset)%name
      call warn_empty_set(p, size(m%elsets(iset)%items), 'element set', m%elsets(iset)%name, kw%name)
      do k = 1, size(m%elsets(iset)%items)
        e = m%elsets(iset)%items(k)
        nodes = [nodes, m%conn(1:elem_nodes(m, e), e)]
      end do
    end if
    r%nodes = unique(nodes)
    if (param2(kw, 'REF NODE') /= '') then
      r%ref_node = node_param(p, m, param2(kw, 'REF NODE'), 'REF NODE')
    else
      r%ref_node = made_node(p, m, [0.0_dp, 0.0_dp])
      r%ref_made = .true.
    end if
    if (param2(kw, 'ROT NODE') /= '') then
      r%rot_node = node_param(p, m, param2(kw, 'ROT NODE'), 'ROT NODE')
      r%rot_given = .true.
    end if
    call attach(p, m, r)
  contains
    subroutine add_nset_nodes(name)
      character(len=*), intent(in) :: name
      iset = need_nset(p, m, name)
      if (len_trim(r%name) == 0) r%name = m%nsets(iset)%name
      call warn_empty_set(p, size(m%nsets(iset)%items), 'node set', m%nsets(iset)%name, kw%name)
      nodes = [nodes, m%nsets(iset)%items]
    end subroutine add_nset_nodes
  end subroutine read_rigid_body

  ! ------------------------------------------------- *COUPLING and its kinds

  !> Purpose: *COUPLING, REF NODE= (a node or a node set of one node),
  !> SURFACE= (element faces, or for *KINEMATIC also nodes), CONSTRAINT
  !> NAME= (a name for the listing), INFLUENCE RADIUS= (Abaqus: only the
  !> surface's nodes within this distance of the reference node). No data
  !> lines; the next card must be *KINEMATIC or *DISTRIBUTING, which makes
  !> the constraints. ORIENTATION= is an error: cfe2d has no *ORIENTATION.
  module subroutine read_coupling(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    character(len=:), allocatable :: v
    type(field_t) :: fr
    call allow_params(p, kw, 'REF NODE,REFNODE,SURFACE,CONSTRAINT NAME,CONSTRAINTNAME,ORIENTATION,' // &
                      'INFLUENCE RADIUS,INFLUENCERADIUS')
    if (has_param(kw, 'ORIENTATION')) call err(p, 'ORIENTATION= (the coupling''s dofs in local axes) is not ' // &
      'implemented: cfe2d has no *ORIENTATION; give the coupling in global axes')
    p%coupling = rigid_t()
    p%coupling%src%line = p%i
    if (param2(kw, 'REF NODE') == '') call err(p, 'missing parameter REF NODE')
    p%coupling%ref_node = node_param(p, m, param2(kw, 'REF NODE'), 'REF NODE')
    v = to_upper(param_value(kw, 'SURFACE'))
    if (.not. has_param(kw, 'SURFACE')) call err(p, 'missing parameter SURFACE')
    p%coupling_surface = find_name(m%surfaces(1:p%nsurf)%name, v)
    if (p%coupling_surface == 0) call err(p, 'undefined surface ' // v)
    call warn_empty_set(p, size(m%surfaces(p%coupling_surface)%nodes), 'surface', v, kw%name)
    v = param2(kw, 'CONSTRAINT NAME')
    call check_name_length(p, v)
    p%coupling%name = to_upper(v)
    if (len_trim(p%coupling%name) == 0) p%coupling%name = m%surfaces(p%coupling_surface)%name
    p%coupling_radius = -1.0_dp
    if (param2(kw, 'INFLUENCE RADIUS') /= '') then
      fr%s = param2(kw, 'INFLUENCE RADIUS')
      p%coupling_radius = get_real(p, fr, 'INFLUENCE RADIUS')
      if (p%coupling_radius <= 0.0_dp) call err(p, 'INFLUENCE RADIUS must be positive')
    end if
    p%coupling_line = p%i
  end subroutine read_coupling

  !> Purpose: *KINEMATIC (after its *COUPLING): data lines `first dof[,
  !> last dof]`; none: every dof. Dofs 1 and 2 of each surface node follow
  !> the reference node rigidly, u = u_ref + theta x (x - x_ref) (theta:
  !> dof 6 of the reference node), the others stay free. Dof 3 (out of the
  !> plane) and the nodes' rotations 4..6 are accepted and constrain
  !> nothing: the nodes of 2D solid elements have neither (Abaqus CAE
  !> writes 6 for a 2D coupling; CalculiX allows 1..3 only).
  module subroutine read_kinematic(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(rigid_t) :: r
    logical :: named(6)
    call allow_params(p, kw, '')
    call coupling_dofs(p, kw, named)
    r = coupling_nodes(p, m, kw)
    r%kind = rigid_kinematic
    r%follows = named(1:2)
    if (.not. any(r%follows)) call deck_warning(p%deck, p%i, '*KINEMATIC names neither dof 1 nor dof 2: ' // &
      'no node follows the reference node')
    call attach(p, m, r)
  end subroutine read_kinematic

  !> Purpose: *DISTRIBUTING (after its *COUPLING), WEIGHTING METHOD=UNIFORM
  !> (the default; the distance-based methods are errors): data lines
  !> `first dof[, last dof]` (none: every dof). Not a rigid constraint: the
  !> reference node follows the weighted average of the surface's nodes
  !> (weights: the length, times the radius in an axisymmetric model,
  !> each node stands for on the faces), so a load on it is spread over
  !> them (statically equivalent, no stiffness added). Forces are always
  !> spread, with the moment of a reference node off the weighted
  !> centroid; a moment on it (dof 6) is spread only if dof 6 is named.
  module subroutine read_distributing(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(rigid_t) :: r
    logical :: named(6)
    call allow_params(p, kw, 'WEIGHTING METHOD,WEIGHTINGMETHOD,CYCLIC SYMMETRY,CYCLICSYMMETRY')
    if (has_param(kw, 'CYCLIC SYMMETRY') .or. has_param(kw, 'CYCLICSYMMETRY')) &
      call err(p, 'CYCLIC SYMMETRY (a sector of a 3D model) is not implemented')
    if (param2(kw, 'WEIGHTING METHOD') /= '') then
      if (to_upper(param2(kw, 'WEIGHTING METHOD')) /= 'UNIFORM') call err(p, 'only WEIGHTING METHOD=UNIFORM ' // &
        '(weights by the area each node stands for) is implemented')
    end if
    call coupling_dofs(p, kw, named)
    if (m%surfaces(p%coupling_surface)%kind /= surf_element) then
      p%i = p%coupling_line
      call err(p, 'the surface of a *DISTRIBUTING coupling must be made of element faces (the weights are ' // &
               'the areas the nodes stand for)')
    end if
    r = coupling_nodes(p, m, kw)
    r%kind = rigid_distributing
    r%moment = named(6)
    call attach_distributing(p, m, r)
  end subroutine read_distributing

  !> The dofs named on the data lines of *KINEMATIC or *DISTRIBUTING
  !> (`first[, last]`, 1..6; none: all), checked against its *COUPLING.
  subroutine coupling_dofs(p, kw, named)
    type(parser_t), intent(inout) :: p
    type(keyword_t), intent(in) :: kw
    logical, intent(out) :: named(6)
    type(field_t), allocatable :: f(:)
    integer :: n, d1, d2, nlines
    if (p%coupling_line == 0) call err(p, '*' // kw%name // ' must follow a *COUPLING card')
    named = .false.
    nlines = 0
    do while (next_data(p))
      call split_fields(line_text(p), f, n)
      if (n < 1 .or. n > 2) call err(p, '*' // kw%name // ' data line needs: first dof[, last dof]')
      d1 = get_int(p, f(1), 'first dof')
      d2 = d1
      if (n == 2) then
        if (len(f(2)%s) > 0) d2 = get_int(p, f(2), 'last dof')
      end if
      if (d1 < 1 .or. d2 > 6 .or. d2 < d1) call err(p, 'dofs must satisfy 1 <= first <= last <= 6 (1, 2: ' // &
        'the translations in the plane; 6: the rotation about z)')
      named(d1:d2) = .true.
      nlines = nlines + 1
    end do
    if (nlines == 0) named = .true.
  end subroutine coupling_dofs

  !> The pending *COUPLING with its surface's nodes (within INFLUENCE
  !> RADIUS), the reference node left out; the coupling is consumed.
  function coupling_nodes(p, m, kw) result(r)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(in) :: m
    type(keyword_t), intent(in) :: kw
    type(rigid_t) :: r
    integer, allocatable :: nodes(:)
    integer :: k, n
    r = p%coupling
    nodes = m%surfaces(p%coupling_surface)%nodes
    n = 0
    do k = 1, size(nodes)
      if (nodes(k) == r%ref_node) cycle
      if (p%coupling_radius > 0.0_dp) then
        if (norm2(m%x(:, nodes(k)) - m%x(:, r%ref_node)) > p%coupling_radius) cycle
      end if
      n = n + 1
      nodes(n) = nodes(k)
    end do
    r%nodes = nodes(1:n)
    if (n == 0 .and. size(nodes) > 0) call deck_warning(p%deck, p%i, '*' // kw%name // ': no node of surface ' // &
      trim(m%surfaces(p%coupling_surface)%name) // ' lies within the INFLUENCE RADIUS')
    p%coupling_line = 0
  end function coupling_nodes

  ! ------------------------------------------------ the rigid constraints

  !> The rotation node of r (its ROT NODE, the one its reference node
  !> already has, or one made now) and the equations of every node that
  !> follows: u_j,d - u_ref,d + c theta = 0 with c = y_j - y_ref (d = 1) or
  !> -(x_j - x_ref) (d = 2), the node's dof dependent. No rotation node
  !> when every coefficient c is zero (the nodes at the reference point).
  subroutine attach(p, m, r)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(rigid_t), intent(inout) :: r
    integer, allocatable :: dep_eq(:, :)
    type(equation_t), allocatable :: eqs(:)
    integer :: k, j, d, ne
    real(dp) :: c
    logical :: turns
    turns = .false.
    do k = 1, size(r%nodes)
      j = r%nodes(k)
      if (j == r%ref_node .or. j == r%rot_node) cycle
      turns = turns .or. (r%follows(1) .and. m%x(2, j) /= m%x(2, r%ref_node)) .or. &
                         (r%follows(2) .and. m%x(1, j) /= m%x(1, r%ref_node))
    end do
    call rotation_node(p, m, r, turns .or. r%rot_given)
    call dependent_dofs(p, m, dep_eq)
    allocate(eqs(2 * size(r%nodes)))
    ne = 0
    do k = 1, size(r%nodes)
      j = r%nodes(k)
      if (j == r%ref_node .or. j == r%rot_node) cycle
      if (is_rotation_node(p, j)) call err(p, 'node ' // node_label(m, j) // ' is the ROT NODE of a rigid ' // &
        'body (its dofs are rotations): it cannot follow a reference node')
      do d = 1, 2
        if (.not. r%follows(d)) cycle
        if (dep_eq(d, j) > 0) call err(p, 'dof ' // itoa(d) // ' of node ' // node_label(m, j) // &
          ' already depends on other dofs (it is the first term of the constraint of line ' // &
          itoa(p%deck%lines(m%equations(dep_eq(d, j))%src%line)%line) // '): a node can follow one ' // &
          'reference node, by one constraint')
        if (d == 1) then
          c = m%x(2, j) - m%x(2, r%ref_node)
        else
          c = -(m%x(1, j) - m%x(1, r%ref_node))
        end if
        ne = ne + 1
        if (c /= 0.0_dp .and. r%rot_node > 0) then
          eqs(ne)%node = [j, r%ref_node, r%rot_node]
          eqs(ne)%dof = [d, d, 1]
          eqs(ne)%coef = [1.0_dp, -1.0_dp, c]
        else
          eqs(ne)%node = [j, r%ref_node]
          eqs(ne)%dof = [d, d]
          eqs(ne)%coef = [1.0_dp, -1.0_dp]
        end if
        eqs(ne)%rigid_ref = r%ref_node
        eqs(ne)%rigid_rot = r%rot_node
      end do
    end do
    call append_equations(p, m, r, eqs(1:ne))
  end subroutine attach

  !> The weighted-average equations of a distributing coupling: with
  !> weights w_j, W = sum w_j, centroid c = sum w_j x_j / W, I = sum w_j
  !> |x_j - c|^2,
  !>   theta   = sum w_j ((x_j - c_x) u_j,2 - (y_j - c_y) u_j,1) / I
  !>   u_ref,1 = sum w_j u_j,1 / W - (y_ref - c_y) theta
  !>   u_ref,2 = sum w_j u_j,2 / W + (x_ref - c_x) theta
  !> (the reference node and theta dependent), whose transpose puts a
  !> force F and a moment M at the reference node on the nodes as w_j F / W
  !> plus w_j (M + (x_ref - c) x F) z x (x_j - c) / I: the same resultant
  !> and moment. No theta when I = 0 (a single point).
  subroutine attach_distributing(p, m, r)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(rigid_t), intent(inout) :: r
    type(equation_t) :: eqs(3)
    integer, allocatable :: dep_eq(:, :)
    real(dp), allocatable :: w(:)
    real(dp) :: wsum, c(2), inertia, dx(2)
    integer :: k, n, d, a, had
    a = r%ref_node
    if (any(r%nodes == a)) call err(p, 'the reference node is a node of the surface: it cannot be their average')
    if (is_rotation_node(p, a)) call err(p, 'the reference node is a ROT NODE')
    w = node_weights(m, p%coupling_surface, r%nodes)
    n = size(r%nodes)
    wsum = sum(w)
    if (n == 0) return
    if (.not. wsum > 0.0_dp) call err(p, 'the faces of the surface have no length: no weights')
    c = [sum(w * m%x(1, r%nodes)), sum(w * m%x(2, r%nodes))] / wsum
    inertia = 0.0_dp
    do k = 1, n
      inertia = inertia + w(k) * sum((m%x(:, r%nodes(k)) - c)**2)
    end do
    if (inertia > 0.0_dp) then
      call grow(p%ref_rotation, m%nn, fill=0)
      had = p%ref_rotation(a)
      call rotation_node(p, m, r, .true.)
      ! a moment on dof 6 is spread only if dof 6 is named
      if (.not. r%moment .and. had == 0) p%ref_rotation(a) = 0
    else if (r%moment) then
      call err(p, 'dof 6: the nodes of the surface lie at one point, they cannot carry a moment')
    end if
    call dependent_dofs(p, m, dep_eq)
    do d = 1, 2
      if (dep_eq(d, a) > 0) call err(p, 'dof ' // itoa(d) // ' of the reference node ' // node_label(m, a) // &
        ' already depends on other dofs (the constraint of line ' // &
        itoa(p%deck%lines(m%equations(dep_eq(d, a))%src%line)%line) // ')')
    end do
    if (r%rot_node > 0) then
      if (dep_eq(1, r%rot_node) > 0) call err(p, 'the rotation of the reference node ' // node_label(m, a) // &
        ' already depends on other dofs: a reference node can average one surface')
    end if
    dx = m%x(:, a) - c
    eqs(1)%node = [a, r%nodes]
    eqs(1)%dof = [1, (1, k = 1, n)]
    eqs(1)%coef = [1.0_dp, -w / wsum]
    eqs(2)%node = [a, r%nodes]
    eqs(2)%dof = [2, (2, k = 1, n)]
    eqs(2)%coef = [1.0_dp, -w / wsum]
    if (r%rot_node == 0) then
      call append_equations(p, m, r, eqs(1:2))
      return
    end if
    eqs(1)%node = [eqs(1)%node, r%rot_node]
    eqs(1)%dof = [eqs(1)%dof, 1]
    eqs(1)%coef = [eqs(1)%coef, dx(2)]
    eqs(2)%node = [eqs(2)%node, r%rot_node]
    eqs(2)%dof = [eqs(2)%dof, 1]
    eqs(2)%coef = [eqs(2)%coef, -dx(1)]
    eqs(3)%node = [r%rot_node, r%nodes, r%nodes]
    eqs(3)%dof = [1, (1, k = 1, n), (2, k = 1, n)]
    eqs(3)%coef = [1.0_dp, w * (m%x(2, r%nodes) - c(2)) / inertia, -w * (m%x(1, r%nodes) - c(1)) / inertia]
    do k = 1, 3
      eqs(k) = without_zero_terms(eqs(k))
    end do
    call append_equations(p, m, r, eqs)
  end subroutine attach_distributing

  !> The weight of each of `nodes` on the faces of surface isurf: the
  !> integral of its shape function along the faces (3 Gauss points,
  !> exact on straight faces), times the radius x in an axisymmetric model
  !> (the area of the ring it stands for, over 2 pi).
  function node_weights(m, isurf, nodes) result(w)
    type(model_t), intent(in) :: m
    integer, intent(in) :: isurf, nodes(:)
    real(dp) :: w(size(nodes))
    real(dp), parameter :: sg(3) = [-sqrt(0.6_dp), 0.0_dp, sqrt(0.6_dp)], &
                           wg(3) = [5.0_dp, 8.0_dp, 5.0_dp] / 9.0_dp
    real(dp) :: xs(2), dxs(2), nf(3), dn(3), xn(2, 3), f
    integer :: j, g, i, ends(3), nfn, k
    logical :: axi
    axi = axisymmetric_model(m)
    w = 0.0_dp
    associate(s => m%surfaces(isurf))
      do j = 1, size(s%elem)
        call edge_nodes(m, s%elem(j), s%edge(j), ends(1), ends(2), ends(3))
        nfn = merge(3, 2, ends(3) > 0)
        do i = 1, nfn
          xn(:, i) = m%x(:, ends(i))
        end do
        do g = 1, 3
          if (nfn == 2) then
            nf(1:2) = [1.0_dp - sg(g), 1.0_dp + sg(g)] / 2.0_dp
            dn(1:2) = [-0.5_dp, 0.5_dp]
          else
            nf = [sg(g) * (sg(g) - 1.0_dp) / 2.0_dp, sg(g) * (sg(g) + 1.0_dp) / 2.0_dp, 1.0_dp - sg(g)**2]
            dn = [sg(g) - 0.5_dp, sg(g) + 0.5_dp, -2.0_dp * sg(g)]
          end if
          xs = matmul(xn(:, 1:nfn), nf(1:nfn))
          dxs = matmul(xn(:, 1:nfn), dn(1:nfn))
          f = wg(g) * norm2(dxs)
          if (axi) f = f * xs(1)
          do i = 1, nfn
            k = findloc(nodes, ends(i), dim=1)
            if (k > 0) w(k) = w(k) + f * nf(i)
          end do
        end do
      end do
    end associate
  end function node_weights

  !> An equation without its zero terms but the first.
  pure function without_zero_terms(eq) result(r)
    type(equation_t), intent(in) :: eq
    type(equation_t) :: r
    logical :: keep(size(eq%node))
    keep = eq%coef /= 0.0_dp
    keep(1) = .true.
    r = eq
    r%node = pack(eq%node, keep)
    r%dof = pack(eq%dof, keep)
    r%coef = pack(eq%coef, keep)
  end function without_zero_terms

  !> The rotation node of r: its ROT NODE (checked: no reference node,
  !> not named as a plain node before this card), or the one its
  !> reference node already has, or (if needed) a node made at the
  !> reference node. The reference node's dof 6 then means it.
  subroutine rotation_node(p, m, r, needed)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(rigid_t), intent(inout) :: r
    logical, intent(in) :: needed
    integer :: have, a, rot
    real(dp) :: xref(2)
    a = r%ref_node
    call grow(p%ref_rotation, m%nn, fill=0)
    have = p%ref_rotation(a)
    if (r%rot_given) then
      rot = r%rot_node
      if (have > 0 .and. have /= rot) call err(p, 'the reference node ' // node_label(m, a) // ' already has ' // &
        'its rotation in ROT NODE ' // node_label(m, have) // ' (or in a node made for it): one reference node, ' // &
        'one rotation')
      if (rot == a) call err(p, 'ROT NODE and REF NODE must be two nodes')
      if (p%ref_rotation(rot) > 0) call err(p, 'the ROT NODE ' // node_label(m, rot) // ' is itself a reference node')
      if (have == 0) then
        if (allocated(p%named_line)) then
          if (rot <= size(p%named_line)) then
            if (p%named_line(rot) > 0) call err(p, 'node ' // node_label(m, rot) // ' is named by the ' // &
              '*BOUNDARY, *CLOAD or *EQUATION of line ' // itoa(p%deck%lines(p%named_line(rot))%line) // &
              ' before this card makes its dofs rotations (dof 3: about z): put the *RIGID BODY first')
          end if
        end if
      end if
      call mark_rotation_node(p, m, rot)
      p%ref_rotation(a) = rot
    else if (have > 0) then
      r%rot_node = have
    else if (needed) then
      xref = m%x(:, a)
      r%rot_node = made_node(p, m, xref)
      call grow(p%ref_rotation, m%nn, fill=0)
      p%ref_rotation(a) = r%rot_node
    end if
  end subroutine rotation_node

  !> Node a is a user's ROT NODE: its deck dofs 1..3 are rotations.
  subroutine mark_rotation_node(p, m, a)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(in) :: m
    integer, intent(in) :: a
    logical, allocatable :: tmp(:)
    if (.not. allocated(p%is_rot_node)) allocate(p%is_rot_node(0))
    if (size(p%is_rot_node) < m%nn) then
      allocate(tmp(m%nn))
      tmp = .false.
      tmp(1:size(p%is_rot_node)) = p%is_rot_node
      call move_alloc(tmp, p%is_rot_node)
    end if
    p%is_rot_node(a) = .true.
  end subroutine mark_rotation_node

  !> Is node a a user's ROT NODE?
  logical function is_rotation_node(p, a)
    type(parser_t), intent(in) :: p
    integer, intent(in) :: a
    is_rotation_node = .false.
    if (.not. allocated(p%is_rot_node)) return
    if (a <= size(p%is_rot_node)) is_rotation_node = p%is_rot_node(a)
  end function is_rotation_node

  !> dep_eq(d, a): the equation whose first term is dof d of node a (0 none).
  subroutine dependent_dofs(p, m, dep_eq)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    integer, allocatable, intent(out) :: dep_eq(:, :)
    integer :: k
    allocate(dep_eq(2, m%nn))
    dep_eq = 0
    do k = 1, p%nequations
      associate(eq => m%equations(k))
        if (eq%dof(1) >= 1 .and. eq%dof(1) <= 2 .and. eq%node(1) >= 1 .and. eq%node(1) <= m%nn) &
          dep_eq(eq%dof(1), eq%node(1)) = k
      end associate
    end do
  end subroutine dependent_dofs

  !> Appends eqs (made by r, from its card) to the model's equations and
  !> r to its rigid bodies.
  subroutine append_equations(p, m, r, eqs)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(rigid_t), intent(in) :: r
    type(equation_t), intent(in) :: eqs(:)
    integer :: k
    character(len=:), allocatable :: origin
    select case (r%kind)
    case (rigid_body); origin = '*RIGID BODY ' // trim(r%name)
    case (rigid_kinematic); origin = '*COUPLING ' // trim(r%name) // ' (*KINEMATIC)'
    case default; origin = '*COUPLING ' // trim(r%name) // ' (*DISTRIBUTING)'
    end select
    call grow(m%equations, p%nequations + size(eqs))
    do k = 1, size(eqs)
      p%nequations = p%nequations + 1
      m%equations(p%nequations) = eqs(k)
      m%equations(p%nequations)%src = r%src
      m%equations(p%nequations)%origin = origin
    end do
    m%rigids = [m%rigids, r]
  end subroutine append_equations

  ! ------------------------------------------------------------- *TRANSFORM

  !> Purpose: *TRANSFORM, NSET=, TYPE=R (default) or C; one data line
  !> `a1, a2, a3, b1, b2, b3`. R: x' along a, y' in the plane of a and b
  !> (towards b), in the x-y plane (the local z axis of a plane model is
  !> the global one): a point out of the plane is taken by its in-plane
  !> part, with a warning (rectangular_axes). C: a and b on the
  !> cylinder's axis, which must be parallel to z (a and b differ only in
  !> z): x' radial from the axis through the node, y' tangential (z' x x',
  !> z' from a to b); a node on the axis has no radial direction. The
  !> node's *BOUNDARY, *CLOAD and *EQUATION dofs are then local; the last
  !> *TRANSFORM naming a node holds.
  module subroutine read_transform(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(transform_t) :: t
    type(field_t), allocatable :: f(:)
    character(len=:), allocatable :: kind
    real(dp) :: scale, d(2)
    integer :: n, k, a
    call allow_params(p, kw, 'NSET,TYPE')
    if (.not. has_param(kw, 'NSET')) call err(p, 'missing parameter NSET')
    t%nset = need_nset(p, m, param_value(kw, 'NSET'))
    call warn_empty_set(p, size(m%nsets(t%nset)%items), 'node set', m%nsets(t%nset)%name, kw%name)
    kind = 'R'
    if (has_param(kw, 'TYPE')) kind = to_upper(param_value(kw, 'TYPE'))
    select case (kind)
    case ('R'); t%kind = transform_rectangular
    case ('C'); t%kind = transform_cylindrical
    case default; call err(p, 'TYPE must be R (rectangular) or C (cylindrical)')
    end select
    t%src%line = p%i
    if (.not. next_data(p)) call err(p, 'missing data line (a1, a2, a3, b1, b2, b3)')
    call split_fields(line_text(p), f, n)
    if (n /= 6) call err(p, '*TRANSFORM data line needs: a1, a2, a3, b1, b2, b3')
    do k = 1, 3
      t%a(k) = get_real(p, f(k), 'coordinate of point a')
      t%b(k) = get_real(p, f(k + 3), 'coordinate of point b')
    end do
    if (t%kind == transform_rectangular) then
      call rectangular_axes(p, t)
    else
      scale = max(norm2(t%a), norm2(t%b), 1.0_dp)
      if (norm2(t%a(1:2) - t%b(1:2)) > small * scale .or. t%a(3) == t%b(3)) call err(p, 'TYPE=C in a 2D ' // &
        'model needs the cylinder''s axis parallel to z (a and b differing in z only): its radial and ' // &
        'tangential directions then lie in the plane; any other axis turns them out of it')
      do k = 1, size(m%nsets(t%nset)%items)
        a = m%nsets(t%nset)%items(k)
        d = m%x(:, a) - t%a(1:2)
        if (norm2(d) <= small * max(scale, norm2(m%x(:, a)))) call err(p, 'node ' // node_label(m, a) // &
          ' lies on the axis of the cylindrical system: it has no radial direction')
      end do
    end if
    if (next_data(p)) call err(p, '*TRANSFORM takes one data line')
    m%transforms = [m%transforms, t]
    call grow(m%node_transform, m%nn, fill=0)
    m%node_transform(m%nsets(t%nset)%items) = size(m%transforms)
  end subroutine read_transform

  !> The axes of a rectangular *TRANSFORM (its data line current): x'
  !> along a, y' perpendicular to it in the x-y plane, on the side of b.
  !> A 2D model's local z axis is the global one, so a point out of the
  !> plane (a3 or b3 not 0) is taken by its in-plane part, (a1, a2) and
  !> (b1, b2): the in-plane projection of the 3D system (x' along a, y' in
  !> the plane of a and b), with a warning at the line. (CalculiX 2.20
  !> keeps the tilted 3D system and holds the node's displacement along
  !> its tilted local z axis: in a plane model that moves the node out of
  !> the plane and shifts it in the plane; measured.) An error where the
  !> in-plane parts give no axes: a on the z axis, or b's in-plane part
  !> on the line of a (then y' would be the global z axis).
  subroutine rectangular_axes(p, t)
    type(parser_t), intent(inout) :: p
    type(transform_t), intent(inout) :: t
    real(dp) :: e1(2), e2(2), scale
    scale = max(norm2(t%a), norm2(t%b))
    if (norm2(t%a) == 0.0_dp) call err(p, 'point a is the origin: it gives no direction for the local x axis')
    if (norm2(t%a(1:2)) <= small * norm2(t%a)) call err(p, 'point a lies on the z axis: its in-plane part ' // &
      'gives no direction for the local x axis of a 2D model')
    e1 = t%a(1:2) / norm2(t%a(1:2))
    e2 = t%b(1:2) - dot_product(t%b(1:2), e1) * e1
    if (norm2(e2) <= small * scale) call err(p, 'point b lies on the local x axis (the line through the ' // &
      'origin and a), or its in-plane part does: it does not fix a local y axis in the x-y plane')
    if (abs(t%a(3)) > small * scale .or. abs(t%b(3)) > small * scale) call deck_warning(p%deck, p%i, &
      '*TRANSFORM: a 2D model''s local z axis is the global one; point a or b lies out of the x-y plane ' // &
      '(a3 = ' // rtoa(t%a(3), 6) // ', b3 = ' // rtoa(t%b(3), 6) // '): the in-plane parts (a1, a2) and ' // &
      '(b1, b2) are used')
    t%axes(:, 1) = e1
    t%axes(:, 2) = e2 / norm2(e2)
  end subroutine rectangular_axes

  ! ------------------------------------------------ once the deck is read

  !> Purpose: what these cards leave for the end of the deck: ids for the
  !> nodes made (after the largest id, in the order made), a ROT NODE in
  !> no element, and the *TRANSFORMs: each transformed node whose dofs a
  !> *BOUNDARY, *CLOAD or *EQUATION (not a generated constraint) names gets
  !> a node carrying its local displacements (made here, at its place),
  !> those cards name that node instead (same dof numbers: local dofs),
  !> and u_d(node) - sum_k axes(d, k) u_k(local node) = 0, d = 1, 2.
  module subroutine finish_kinematic_cards(p, m)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    integer :: a, k, e, next_id
    next_id = 1
    if (m%nn > 0) next_id = maxval(m%node_id(1:m%nn)) + 1
    do a = 1, m%nn
      if (m%node_id(a) /= 0) cycle
      call give_id(p, m, a, next_id)
    end do
    do k = 1, size(m%rigids)
      if (.not. m%rigids(k)%rot_given) cycle
      do e = 1, m%ne
        if (any(m%conn(1:elem_nodes(m, e), e) == m%rigids(k)%rot_node)) then
          p%i = m%rigids(k)%src%line
          call err(p, 'the ROT NODE ' // node_label(m, m%rigids(k)%rot_node) // ' belongs to element ' // &
                   elem_label(m, e) // ': its dofs are the rotations of the body, it must be in no element')
        end if
      end do
    end do
    if (size(m%transforms) > 0) call apply_transforms(p, m, next_id)
    call warn_chained_rigids(p, m)
  end subroutine finish_kinematic_cards

  !> In a model with an NLGEOM step, a rigid card whose nodes a chain of
  !> constraints keeps at the small rotation (constraints: rigid_chains;
  !> its reference node constrained or transformed, its nodes named by an
  !> *EQUATION) is told so at its line, with the count: never a small
  !> rotation in silence where the others turn exactly.
  subroutine warn_chained_rigids(p, m)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(in) :: m
    logical, allocatable :: chained(:)
    integer :: j, n
    if (size(m%rigids) == 0 .or. p%nequations == 0 .or. .not. allocated(m%steps)) return
    if (.not. any(m%steps%nlgeom)) return
    chained = rigid_chains(m%equations(1:p%nequations), m%nn)
    do j = 1, size(m%rigids)
      n = count(chained .and. m%equations(1:p%nequations)%src%line == m%rigids(j)%src%line)
      if (n == 0) cycle
      call deck_warning(p%deck, m%rigids(j)%src%line, itoa(n) // ' constraint(s) of this card keep the small ' // &
        'rotation in NLGEOM steps: its reference node or rotation is itself constrained (another card, an ' // &
        '*EQUATION, a *TRANSFORM on the reference node), or an *EQUATION names its nodes; the other nodes ' // &
        'follow the exact rotation')
    end do
  end subroutine warn_chained_rigids

  !> Gives node a (made while reading, id 0) the id next_id.
  subroutine give_id(p, m, a, next_id)
    type(parser_t), intent(in) :: p
    type(model_t), intent(inout) :: m
    integer, intent(in) :: a
    integer, intent(inout) :: next_id
    if (next_id > max_id) call err(p, 'the nodes made for rigid bodies and couplings would need ids ' // &
      'beyond ' // itoa(max_id))
    m%node_id(a) = next_id
    call grow(m%node_index, next_id, fill=0)
    m%node_index(next_id) = a
    next_id = next_id + 1
  end subroutine give_id

  !> The local-displacement nodes of the transformed nodes that cards
  !> name, the cards redirected to them, and their equations.
  subroutine apply_transforms(p, m, next_id)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    integer, intent(inout) :: next_id
    logical, allocatable :: named(:), rotation(:)
    type(equation_t), allocatable :: eqs(:)
    integer :: k, s, j, a, nn0, d, loc
    real(dp) :: r(2, 2), xa(2)
    nn0 = m%nn
    call grow(m%node_transform, nn0, fill=0)
    allocate(named(nn0), rotation(nn0))
    named = .false.
    ! a rotation (dof 1 of a rotation node) has no axes to turn
    rotation = .false.
    do k = 1, size(m%rigids)
      if (m%rigids(k)%rot_node > 0) rotation(m%rigids(k)%rot_node) = .true.
    end do
    call mark(m%model_bcs%node)
    do s = 1, size(m%steps)
      call mark(m%steps(s)%bcs%node)
      call mark(m%steps(s)%loads%node)
    end do
    do k = 1, p%nequations
      if (len_trim(m%equations(k)%origin) == 0) call mark(m%equations(k)%node)
    end do
    allocate(m%local_node(nn0), eqs(2 * count(named)))
    m%local_node = 0
    k = 0
    do a = 1, nn0
      if (.not. named(a)) cycle
      xa = m%x(:, a)
      loc = made_node(p, m, xa)
      call give_id(p, m, loc, next_id)
      m%local_node(a) = loc
      r = node_axes(m, a)
      do d = 1, 2
        k = k + 1
        eqs(k) = without_zero_terms(equation_t(node=[a, loc, loc], dof=[d, 1, 2], coef=[1.0_dp, -r(d, :)], &
                                               src=m%transforms(m%node_transform(a))%src, &
                                               origin='*TRANSFORM on ' // &
                                               trim(m%nsets(m%transforms(m%node_transform(a))%nset)%name)))
      end do
    end do
    call redirect(m%model_bcs%node)
    do s = 1, size(m%steps)
      call redirect(m%steps(s)%bcs%node)
      call redirect(m%steps(s)%loads%node)
    end do
    do k = 1, p%nequations
      if (len_trim(m%equations(k)%origin) == 0) call redirect(m%equations(k)%node)
    end do
    m%equations = [m%equations(1:p%nequations), eqs]
    p%nequations = size(m%equations)
    m%node_id = m%node_id(1:m%nn)
    m%x = m%x(:, 1:m%nn)
  contains
    subroutine mark(nodes)
      integer, intent(in) :: nodes(:)
      do j = 1, size(nodes)
        if (nodes(j) > nn0) cycle
        if (rotation(nodes(j))) cycle
        if (m%node_transform(nodes(j)) > 0) named(nodes(j)) = .true.
      end do
    end subroutine mark
    subroutine redirect(nodes)
      integer, intent(inout) :: nodes(:)
      do j = 1, size(nodes)
        if (nodes(j) > nn0) cycle
        if (m%local_node(nodes(j)) > 0) nodes(j) = m%local_node(nodes(j))
      end do
    end subroutine redirect
  end subroutine apply_transforms

  ! ----------------------------------------------------------------- helpers

  !> A parameter written with or without its blanks (REF NODE, REFNODE),
  !> '' if absent.
  function param2(kw, name) result(v)
    type(keyword_t), intent(in) :: kw
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: v
    integer :: i
    character(len=:), allocatable :: tight
    tight = ''
    do i = 1, len(name)
      if (name(i:i) /= ' ') tight = tight // name(i:i)
    end do
    v = param_value(kw, name)
    if (len(v) == 0) v = param_value(kw, tight)
  end function param2

  !> A node given by a parameter: its id (INSTANCE.NUMBER in a deck with
  !> parts) or a node set of exactly one node.
  integer function node_param(p, m, v, what) result(a)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    character(len=*), intent(in) :: v, what
    type(field_t) :: f
    if (is_label(v)) then
      f%s = v
      a = node_ref(p, m, f, what)
    else
      associate(items => m%nsets(need_nset(p, m, v))%items)
        if (size(items) /= 1) call err(p, 'the node set of ' // what // '= must hold exactly one node (it holds ' // &
                                       itoa(size(items)) // ')')
        a = items(1)
      end associate
    end if
  end function node_param

  !> A node made at x while reading (id 0 until finish_kinematic_cards);
  !> its internal index.
  integer function made_node(p, m, x) result(a)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    real(dp), intent(in) :: x(2)
    call grow(m%node_id, m%nn + 1)
    call grow(m%x, m%nn + 1)
    m%nn = m%nn + 1
    a = m%nn
    m%node_id(a) = 0
    m%x(:, a) = x
    call grow(p%node_line, m%nn)
    p%node_line(a) = p%i
  end function made_node

  !> The distinct values of v (positive), in their first order.
  pure function unique(v) result(u)
    integer, intent(in) :: v(:)
    integer, allocatable :: u(:)
    logical, allocatable :: seen(:)
    integer :: k, n
    allocate(u(size(v)), seen(max(1, maxval(v))))
    seen = .false.
    n = 0
    do k = 1, size(v)
      if (seen(v(k))) cycle
      seen(v(k)) = .true.
      n = n + 1
      u(n) = v(k)
    end do
    u = u(1:n)
  end function unique
end submodule deck_rigid_cards
