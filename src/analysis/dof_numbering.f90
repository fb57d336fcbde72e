!> Global equations: the free dofs numbered (prescribed ones and the
!> dependent dofs of linear constraints eliminated), node by node in a
!> profile-reducing order for the skyline or in input order for the
!> sparse solvers (which order for themselves), optionally with a chosen
!> set of dofs numbered last; and the equation lists of the assembly
!> groups (continuum elements, then coupling elements) from which the
!> solver sets up its structure.
!>
!> Linear constraints (*EQUATION, resolved by module constraints) are
!> imposed by elimination: u = T u_r, with u_r the independent dofs. A
!> group that touches a dependent dof reaches the equations of its
!> independent dofs instead (group_transform): its matrix enters as
!> T_g^T k T_g, forces on dependent dofs go to their independent dofs
!> (reduce_dependent: f_r = T^T f), and displacements of dependent dofs
!> follow from the independent ones (expand_dependent). The system stays
!> symmetric positive definite. Under NLGEOM the nodes of rigid cards
!> turn exactly (follow_rotations: their motion and their rows of T at the
!> current rotation, updated in every Newton iteration).
module dof_numbering
  use kinds, only: dp
  use strings, only: itoa
  use messages, only: fatal
  use model
  use constraints, only: mpc_t, constraint_label
  use contact, only: contact_set_t, cfe_nodes
  use element_interface, only: max_en
  use linear_solver, only: linear_system_t, sys_setup, solver_skyline, order_rcm
  use ordering, only: rcm_order
  use growable, only: grow
  implicit none
  private
  public :: dofmap_t, number_dofs, group_transform, has_dependent, expand_dependent, reduce_dependent, &
            follow_rotations

  type :: dofmap_t
    integer :: neq = 0
    integer, allocatable :: eq(:, :)     ! (2, nn): equation, 0 if prescribed, dependent or inactive
    integer, allocatable :: node_of_eq(:), dof_of_eq(:)
    !> The linear constraints: dependent dofs in terms of independent ones.
    type(mpc_t) :: mpc
    !> (2, nn) dofs without an equation because nothing reaches them: the
    !> unused dof of a node that only a constraint names (a reference node).
    logical, allocatable :: inactive(:, :)
    !> Finite rotations (an NLGEOM step, once follow_rotations was called):
    !> the rigid followers of the constraints (mpc_t%rref) move exactly,
    !> u = u_ref + (R(theta) - I) roff, and their rows of T are the
    !> derivatives at the current theta. rot_term(k) is the index of the
    !> rotation's term of dependent dof k (0: not a rigid follower, or no
    !> NLGEOM step in the model); it exists, with coefficient zero where the
    !> linear constraint has none, in every numbering of a model with an
    !> NLGEOM step, so that the equation structure holds for any theta.
    logical :: finite = .false.
    integer, allocatable :: rot_term(:)
  end type dofmap_t

contains


  !> Purpose: nodes of assembly group g: body element g, or CFE g - ne
  !> (slave nodes first); no nodes for elements without stiffness (line
  !> elements that only describe boundaries). nodes is (re)allocated when
  !> shorter than the group (a CFE may hold any number of nodes).
  pure subroutine group_nodes(m, cs, g, nodes, nen)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    integer, intent(in) :: g
    integer, allocatable, intent(inout) :: nodes(:)
    integer, intent(out) :: nen
    if (allocated(nodes)) then
      if (size(nodes) < max_en) deallocate(nodes)
    end if
    if (.not. allocated(nodes)) allocate(nodes(max_en))
    if (g <= m%ne) then
      nen = 0
      if (.not. carries_stiffness(m, g)) return
      nen = elem_nodes(m, g)
      nodes(1:nen) = m%conn(1:nen, g)
    else
      call cfe_nodes(m, cs%c(g - m%ne), nodes, nen)
    end if
  end subroutine group_nodes

  !> Node graph of body elements and CFEs in compressed form; a
  !> group's nodes include those of the independent dofs its dependent
  !> dofs stand for (the couplings its transformed matrix makes).
  subroutine node_graph(m, cs, mpc, xadj, adj)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    type(mpc_t), intent(in) :: mpc
    integer, allocatable, intent(out) :: xadj(:), adj(:)
    integer, allocatable :: cnt(:), pos(:), nodes(:)
    integer :: pass, e, i, j, nen, k
    allocate(cnt(m%nn), xadj(m%nn + 1), pos(m%nn), nodes(max_en))
    ! Pass 1 counts, pass 2 fills; duplicates are harmless to RCM.
    do pass = 1, 2
      cnt = 0
      do e = 1, m%ne + cs%n
        call graph_nodes(m, cs, mpc, e, nodes, nen)
        do i = 1, nen
          do j = 1, nen
            if (nodes(i) == nodes(j)) cycle
            cnt(nodes(i)) = cnt(nodes(i)) + 1
            if (pass == 2) then
              adj(pos(nodes(i))) = nodes(j)
              pos(nodes(i)) = pos(nodes(i)) + 1
            end if
          end do
        end do
      end do
      if (pass == 1) then
        xadj(1) = 1
        do k = 1, m%nn
          xadj(k + 1) = xadj(k) + cnt(k)
        end do
        allocate(adj(xadj(m%nn + 1) - 1))
        pos = xadj(1:m%nn)
      end if
    end do
  end subroutine node_graph

  !> The nodes of group g and, where a dof of them is dependent, the nodes
  !> of its independent dofs (each once).
  subroutine graph_nodes(m, cs, mpc, g, nodes, nen)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    type(mpc_t), intent(in) :: mpc
    integer, intent(in) :: g
    integer, allocatable, intent(inout) :: nodes(:)
    integer, intent(out) :: nen
    integer :: i, d, k, j, n0
    call group_nodes(m, cs, g, nodes, nen)
    if (mpc%ndep == 0) return
    n0 = nen
    do i = 1, n0
      do d = 1, 2
        k = mpc%dep(d, nodes(i))
        if (k == 0) cycle
        do j = mpc%xt(k), mpc%xt(k + 1) - 1
          if (any(nodes(1:nen) == mpc%tnode(j))) cycle
          nen = nen + 1
          call grow(nodes, nen)
          nodes(nen) = mpc%tnode(j)
        end do
      end do
    end do
  end subroutine graph_nodes

  !> Purpose: numbers the free dofs and sets up the system's structure from
  !> the equation lists of the continuum elements and the CFEs, in
  !> assembly order.
  !> Arguments: prescribed(2, nn) dofs eliminated; kind, order the solver
  !> and its ordering; last(2, nn), if present, marks dofs numbered after
  !> all others (in node order), e.g. the contact equations of a condensed
  !> solve; constraints, if present, the linear constraints (their
  !> dependent dofs eliminated; none without it).
  subroutine number_dofs(m, cs, prescribed, kind, order, dm, sys, last, constraints)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    logical, intent(in) :: prescribed(:, :)
    integer, intent(in) :: kind, order
    type(dofmap_t), intent(out) :: dm
    type(linear_system_t), intent(inout) :: sys
    logical, intent(in), optional :: last(:, :)
    type(mpc_t), intent(in), optional :: constraints
    integer, allocatable :: xadj(:), adj(:), perm(:)
    logical, allocatable :: numbered(:, :)
    integer :: i, d, n, pass, nlast
    logical :: take
    if (present(constraints)) then
      dm%mpc = constraints
    else
      allocate(dm%mpc%dep(2, m%nn), dm%mpc%xt(1), dm%mpc%node(0), dm%mpc%dof(0), dm%mpc%tnode(0), &
               dm%mpc%tdof(0), dm%mpc%tcoef(0), dm%mpc%rref(0), dm%mpc%rrot(0), dm%mpc%roff(2, 0))
      dm%mpc%dep = 0
      dm%mpc%xt = 1
    end if
    allocate(dm%rot_term(dm%mpc%ndep))
    dm%rot_term = 0
    if (allocated(m%steps) .and. allocated(dm%mpc%rref)) then
      if (any(m%steps%nlgeom)) call rotation_terms(dm)
    end if
    call active_dofs(m, cs, prescribed, dm, numbered)
    allocate(perm(m%nn), dm%eq(2, m%nn))
    if (kind == solver_skyline .and. order == order_rcm) then
      call node_graph(m, cs, dm%mpc, xadj, adj)
      call rcm_order(m%nn, xadj, adj, perm)
    else
      perm = [(i, i = 1, m%nn)]
    end if
    dm%eq = 0
    n = 0
    nlast = 0
    do pass = 1, 2
      do i = 1, m%nn
        do d = 1, 2
          if (.not. numbered(d, perm(i))) cycle
          take = pass == 1
          if (present(last)) take = last(d, perm(i)) .eqv. (pass == 2)
          if (.not. take) cycle
          n = n + 1
          if (pass == 2) nlast = nlast + 1
          dm%eq(d, perm(i)) = n
        end do
      end do
      if (.not. present(last)) exit
    end do
    dm%neq = n
    allocate(dm%node_of_eq(n), dm%dof_of_eq(n))
    do i = 1, m%nn
      do d = 1, 2
        if (dm%eq(d, i) > 0) then
          dm%node_of_eq(dm%eq(d, i)) = i
          dm%dof_of_eq(dm%eq(d, i)) = d
        end if
      end do
    end do
    call setup_structure(m, cs, dm, kind, order, nlast, sys)
  end subroutine number_dofs

  !> The dofs that get an equation: those neither prescribed nor
  !> dependent, except (dm%inactive) the free dofs of a node the model
  !> drops (no element with stiffness or mass, contact surface or
  !> constraint: kept_nodes; the deck's checks warned) and the unused dof
  !> of a node that only constraints name (no element, no CFE: a
  !> reference node): nothing could move them, they stay at zero. Any
  !> other free dof that nothing reaches (a point mass's node without
  !> support, a slave node no CFE couples) has no stiffness: the run
  !> stops, naming it.
  subroutine active_dofs(m, cs, prescribed, dm, numbered)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    logical, intent(in) :: prescribed(:, :)
    type(dofmap_t), intent(inout) :: dm
    logical, allocatable, intent(out) :: numbered(:, :)
    logical, allocatable :: reached(:), named(:, :), kept(:)
    integer :: g, a, d, k, nen
    integer, allocatable :: nodes(:)
    allocate(reached(m%nn), named(2, m%nn), numbered(2, m%nn), dm%inactive(2, m%nn))
    reached = .false.
    do g = 1, m%ne + cs%n
      call group_nodes(m, cs, g, nodes, nen)
      reached(nodes(1:nen)) = .true.
    end do
    named = dm%mpc%dep > 0
    do k = 1, size(dm%mpc%tnode)
      named(dm%mpc%tdof(k), dm%mpc%tnode(k)) = .true.
    end do
    kept = kept_nodes(m)
    do a = 1, m%nn
      do d = 1, 2
        if (prescribed(d, a) .and. dm%mpc%dep(d, a) > 0) call fatal('dof ' // itoa(d) // ' of node ' // &
          node_label(m, a) // ' is both prescribed and the dependent dof of a linear constraint' // &
          ' (' // constraint_label(m, dm%mpc%dep(d, a)) // ')')
        numbered(d, a) = .not. prescribed(d, a) .and. dm%mpc%dep(d, a) == 0
        dm%inactive(d, a) = numbered(d, a) .and. (.not. kept(a) .or. &
                            (.not. reached(a) .and. .not. named(d, a) .and. any(named(:, a))))
        if (dm%inactive(d, a)) numbered(d, a) = .false.
        if (numbered(d, a) .and. .not. reached(a) .and. .not. named(d, a)) call fatal('singular stiffness at ' // &
          'node ' // node_label(m, a) // ', dof ' // itoa(d) // ': no element with stiffness, coupling ' // &
          'element or *EQUATION reaches this dof and it has no *BOUNDARY (missing boundary condition?)')
      end do
    end do
  end subroutine active_dofs

  !> Equation lists (local dof order, 0 for prescribed dofs; a group
  !> touching a dependent dof reaches the equations of group_transform)
  !> of every assembly group, handed to the solver with the size of the
  !> trailing block (nlast).
  subroutine setup_structure(m, cs, dm, kind, order, nlast, sys)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    type(dofmap_t), intent(in) :: dm
    integer, intent(in) :: kind, order, nlast
    type(linear_system_t), intent(inout) :: sys
    integer, allocatable :: xeq(:), eqs(:), geq(:)
    real(dp), allocatable :: t(:, :)
    integer :: ng, e, i, k, nen
    integer, allocatable :: nodes(:)
    ng = m%ne + cs%n
    allocate(xeq(ng + 1), eqs(2 * max_en * ng))
    xeq(1) = 1
    do e = 1, ng
      call group_nodes(m, cs, e, nodes, nen)
      k = xeq(e)
      if (has_dependent(dm, nodes(1:nen))) then
        call group_transform(dm, nodes(1:nen), geq, t)
        call grow(eqs, k + size(geq))
        eqs(k:k + size(geq) - 1) = geq
        k = k + size(geq)
      else
        call grow(eqs, k + 2 * nen)
        do i = 1, nen
          eqs(k:k + 1) = dm%eq(:, nodes(i))
          k = k + 2
        end do
      end if
      xeq(e + 1) = k
    end do
    call sys_setup(sys, kind, order, dm%neq, xeq, eqs(1:xeq(ng + 1) - 1), nlast)
  end subroutine setup_structure

  !> Purpose: does a dof of these nodes depend on others?
  pure logical function has_dependent(dm, nodes)
    type(dofmap_t), intent(in) :: dm
    integer, intent(in) :: nodes(:)
    has_dependent = .false.
    if (dm%mpc%ndep == 0) return
    has_dependent = any(dm%mpc%dep(:, nodes) > 0)
  end function has_dependent

  !> Purpose: the equations an assembly group on `nodes` reaches and its
  !> constraint transformation. geq(1:nd) (nd = 2 size(nodes)) are the
  !> equations of its own dofs in local order (0 where prescribed,
  !> dependent or inactive), the rest those of the free independent dofs
  !> its dependent dofs stand for, each once; local dof i = sum_j t(i, j)
  !> u(geq(j)) plus prescribed values. The group's matrix enters the
  !> system as t^T k t, its forces as t^T f.
  pure subroutine group_transform(dm, nodes, geq, t)
    type(dofmap_t), intent(in) :: dm
    integer, intent(in) :: nodes(:)
    integer, allocatable, intent(out) :: geq(:)
    real(dp), allocatable, intent(out) :: t(:, :)
    integer, allocatable :: buf(:)
    integer :: nd, ng, i, k, j, e, pass
    nd = 2 * size(nodes)
    ng = nd
    do i = 1, nd
      k = dm%mpc%dep(2 - mod(i, 2), nodes((i + 1) / 2))
      if (k > 0) ng = ng + dm%mpc%xt(k + 1) - dm%mpc%xt(k)
    end do
    allocate(buf(ng))
    buf(1:nd) = reshape(dm%eq(:, nodes), [nd])
    ng = nd
    do pass = 1, 2
      do i = 1, nd
        k = dm%mpc%dep(2 - mod(i, 2), nodes((i + 1) / 2))
        if (k == 0) cycle
        do j = dm%mpc%xt(k), dm%mpc%xt(k + 1) - 1
          e = dm%eq(dm%mpc%tdof(j), dm%mpc%tnode(j))
          if (e <= 0) cycle                ! a prescribed value: in the residual
          if (pass == 1) then
            if (any(buf(1:ng) == e)) cycle
            ng = ng + 1
            buf(ng) = e
          else
            e = findloc(geq, e, dim=1)
            t(i, e) = t(i, e) + dm%mpc%tcoef(j)
          end if
        end do
      end do
      if (pass == 2) exit
      geq = buf(1:ng)
      allocate(t(nd, ng))
      t = 0.0_dp
      do i = 1, nd
        if (geq(i) > 0) t(i, i) = 1.0_dp
      end do
    end do
  end subroutine group_transform

  !> Purpose: u at the dependent dofs from the independent ones: all of
  !> them, or the dependent dofs listed in only (indices into dm%mpc).
  !> With finite rotations (dm%finite) the rigid followers take their
  !> exact rigid motion (rigid_motion), the others their linear terms.
  pure subroutine expand_dependent(dm, u, only)
    type(dofmap_t), intent(in) :: dm
    real(dp), intent(inout) :: u(:, :)
    integer, intent(in), optional :: only(:)
    integer :: q, k, j, n
    real(dp) :: v, g, dg
    n = dm%mpc%ndep
    if (present(only)) n = size(only)
    do q = 1, n
      k = q
      if (present(only)) k = only(q)
      v = 0.0_dp
      do j = dm%mpc%xt(k), dm%mpc%xt(k + 1) - 1
        v = v + dm%mpc%tcoef(j) * u(dm%mpc%tdof(j), dm%mpc%tnode(j))
      end do
      if (dm%finite) then
        if (dm%rot_term(k) > 0) then
          call rigid_motion(dm%mpc, k, u(1, dm%mpc%rrot(k)), g, dg)
          v = u(dm%mpc%dof(k), dm%mpc%rref(k)) + g
        end if
      end if
      u(dm%mpc%dof(k), dm%mpc%node(k)) = v
    end do
  end subroutine expand_dependent

  !> Purpose: finite rotations for the Newton iteration of an NLGEOM step,
  !> called after every update of u (and after a renumbering): each rigid
  !> follower k (a node of a *RIGID BODY or *KINEMATIC coupling) is put at
  !> its exact rigid motion, component d of
  !>   u_j = u_ref + (R(theta) - I) (X_j - X_ref),
  !> and the coefficient of theta in its row of T becomes the derivative
  !> d/dtheta of that component at the current theta, so that the
  !> assembled T^T K T and the residual T^T (f_int - f_ext) are those of
  !> the current configuration. This is CalculiX's treatment of a rigid
  !> body under NLGEOM (nonlinear MPCs whose coefficients are updated in
  !> each iteration); the term (dT^T/dtheta) f of the constraint's
  !> curvature is left out of the tangent, which stays convergent
  !> (exact where theta is prescribed: the term acts on theta alone).
  !> Arguments: dm the numbering, finite rotations switched on (dm%finite);
  !> u the displacements, the rigid followers' dofs set.
  pure subroutine follow_rotations(dm, u)
    type(dofmap_t), intent(inout) :: dm
    real(dp), intent(inout) :: u(:, :)
    integer :: k
    real(dp) :: g, dg
    dm%finite = .true.
    do k = 1, dm%mpc%ndep
      if (dm%rot_term(k) == 0) cycle
      call rigid_motion(dm%mpc, k, u(1, dm%mpc%rrot(k)), g, dg)
      u(dm%mpc%dof(k), dm%mpc%node(k)) = u(dm%mpc%dof(k), dm%mpc%rref(k)) + g
      dm%mpc%tcoef(dm%rot_term(k)) = dg
    end do
  end subroutine follow_rotations

  !> Component d (= mpc%dof(k)) of the rigid motion of follower k turned
  !> by theta about its reference node, g = ((R(theta) - I) r)_d with r =
  !> mpc%roff(:, k), and its derivative dg/dtheta = (R'(theta) r)_d:
  !>   g_1 = (cos - 1) r_1 - sin r_2,   g_2 = sin r_1 + (cos - 1) r_2,
  !> cos - 1 written -2 sin^2(theta/2), exact to round-off for small theta.
  pure subroutine rigid_motion(mpc, k, theta, g, dg)
    type(mpc_t), intent(in) :: mpc
    integer, intent(in) :: k
    real(dp), intent(in) :: theta
    real(dp), intent(out) :: g, dg
    real(dp) :: c1, s, c, r(2)
    r = mpc%roff(:, k)
    s = sin(theta)
    c = cos(theta)
    c1 = -2.0_dp * sin(0.5_dp * theta)**2
    if (mpc%dof(k) == 1) then
      g = c1 * r(1) - s * r(2)
      dg = -s * r(1) - c * r(2)
    else
      g = s * r(1) + c1 * r(2)
      dg = c * r(1) - s * r(2)
    end if
  end subroutine rigid_motion

  !> The term of the rotation (dof 1 of mpc%rrot) in the row of every
  !> rigid follower, dm%rot_term; a follower whose linear row has none (a
  !> node level with its reference node: zero coefficient at theta = 0)
  !> gets one with coefficient zero, so that the numbering's structure
  !> reaches theta for any rotation. The linear rows are otherwise kept.
  pure subroutine rotation_terms(dm)
    type(dofmap_t), intent(inout) :: dm
    integer, allocatable :: xt(:), tn(:), td(:)
    real(dp), allocatable :: tc(:)
    integer :: k, j, n, nt
    logical :: has
    n = dm%mpc%ndep
    allocate(xt(n + 1), tn(size(dm%mpc%tnode) + n), td(size(dm%mpc%tnode) + n), tc(size(dm%mpc%tnode) + n))
    xt(1) = 1
    nt = 0
    do k = 1, n
      has = .false.
      do j = dm%mpc%xt(k), dm%mpc%xt(k + 1) - 1
        nt = nt + 1
        tn(nt) = dm%mpc%tnode(j)
        td(nt) = dm%mpc%tdof(j)
        tc(nt) = dm%mpc%tcoef(j)
        if (dm%mpc%rref(k) == 0) cycle
        if (tn(nt) /= dm%mpc%rrot(k) .or. td(nt) /= 1) cycle
        has = .true.
        dm%rot_term(k) = nt
      end do
      if (dm%mpc%rref(k) > 0 .and. .not. has) then
        nt = nt + 1
        tn(nt) = dm%mpc%rrot(k)
        td(nt) = 1
        tc(nt) = 0.0_dp
        dm%rot_term(k) = nt
      end if
      xt(k + 1) = nt + 1
    end do
    dm%mpc%xt = xt
    dm%mpc%tnode = tn(1:nt)
    dm%mpc%tdof = td(1:nt)
    dm%mpc%tcoef = tc(1:nt)
  end subroutine rotation_terms

  !> Purpose: f := T^T f in place: each force on a dependent dof moves to
  !> its independent dofs (times their coefficients) and is zeroed there;
  !> all dependent dofs, or those listed in only.
  pure subroutine reduce_dependent(dm, f, only)
    type(dofmap_t), intent(in) :: dm
    real(dp), intent(inout) :: f(:, :)
    integer, intent(in), optional :: only(:)
    integer :: q, k, j, n
    real(dp) :: v
    n = dm%mpc%ndep
    if (present(only)) n = size(only)
    do q = 1, n
      k = q
      if (present(only)) k = only(q)
      v = f(dm%mpc%dof(k), dm%mpc%node(k))
      f(dm%mpc%dof(k), dm%mpc%node(k)) = 0.0_dp
      if (v == 0.0_dp) cycle
      do j = dm%mpc%xt(k), dm%mpc%xt(k + 1) - 1
        f(dm%mpc%tdof(j), dm%mpc%tnode(j)) = f(dm%mpc%tdof(j), dm%mpc%tnode(j)) + dm%mpc%tcoef(j) * v
      end do
    end do
  end subroutine reduce_dependent
end module dof_numbering
