!> Global equations: dof numbering with prescribed dofs eliminated (in a
!> profile-reducing node order), skyline structure, assembly of the
!> stiffness and of the internal force vector from the element routines.
module assembly
  use kinds, only: dp
  use model
  use element_catalogue, only: catalogue, shape_quad4, state_plane_strain
  use contact, only: contact_set_t, cfe_input
  use element_types, only: elem_in_t, elem_out_t, max_en, kind_quad4, kind_tri3
  use element_library, only: element_routine
  use linear_solver, only: linear_system_t, sys_setup, sys_zero, sys_add, solver_skyline, order_rcm
  use ordering, only: rcm_order
  implicit none
  private
  public :: dofmap_t, number_dofs, assemble, internal_forces, solid_input, stress_recovery

  type :: dofmap_t
    integer :: neq = 0
    integer, allocatable :: eq(:, :)     ! (2, nn): equation, 0 if prescribed
    integer, allocatable :: node_of_eq(:), dof_of_eq(:)
  end type dofmap_t

contains

  !> Element data of solid element e at displacements u.
  subroutine solid_input(m, e, u, ein, nodes)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    real(dp), intent(in) :: u(:, :)
    type(elem_in_t), intent(out) :: ein
    integer, intent(out) :: nodes(:)
    integer :: k, nen
    nen = elem_nodes(m, e)
    ein%nen = nen
    if (catalogue(m%etype(e))%shape == shape_quad4) then
      ein%kind = kind_quad4
    else
      ein%kind = kind_tri3
    end if
    nodes(1:nen) = m%conn(1:nen, e)
    do k = 1, nen
      ein%xy(:, k) = m%x(:, nodes(k))
      ein%ue(2 * k - 1:2 * k) = u(:, nodes(k))
    end do
    associate(sec => m%sections(m%elem_section(e)))
      ein%e = m%materials(sec%material)%e
      ein%nu = m%materials(sec%material)%nu
      ein%thickness = sec%thickness
    end associate
    ein%plane_strain = catalogue(m%etype(e))%state == state_plane_strain
  end subroutine solid_input

  !> Node graph of solid elements and CFEs in compressed form.
  subroutine node_graph(m, cs, xadj, adj)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    integer, allocatable, intent(out) :: xadj(:), adj(:)
    integer, allocatable :: cnt(:), pos(:)
    integer :: pass, e, i, j, nen, nodes(max_en), k
    allocate(cnt(m%nn), xadj(m%nn + 1), pos(m%nn))
    ! Pass 1 counts, pass 2 fills; duplicates are harmless to RCM.
    do pass = 1, 2
      cnt = 0
      do e = 1, m%ne + cs%n
        call group_nodes(m, cs, e, nodes, nen)
        do i = 1, nen
          do j = 1, nen
            if (i == j) cycle
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

  !> Numbers the free dofs node by node (in RCM order for the skyline with
  !> ORDERING=RCM, in input order otherwise: the sparse solvers order for
  !> themselves) and sets up the system's structure from the equation lists
  !> of the solid elements and the CFEs, in assembly order.
  subroutine number_dofs(m, cs, prescribed, kind, order, dm, sys)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    logical, intent(in) :: prescribed(:, :)
    integer, intent(in) :: kind, order
    type(dofmap_t), intent(out) :: dm
    type(linear_system_t), intent(inout) :: sys
    integer, allocatable :: xadj(:), adj(:), perm(:), xeq(:), eqs(:)
    integer :: i, d, n, e, nen, nodes(max_en), ng, k
    allocate(perm(m%nn), dm%eq(2, m%nn))
    if (kind == solver_skyline .and. order == order_rcm) then
      call node_graph(m, cs, xadj, adj)
      call rcm_order(m%nn, xadj, adj, perm)
    else
      perm = [(i, i = 1, m%nn)]
    end if
    dm%eq = 0
    n = 0
    do i = 1, m%nn
      do d = 1, 2
        if (prescribed(d, perm(i))) cycle
        n = n + 1
        dm%eq(d, perm(i)) = n
      end do
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
    ! equation lists, local dof order, 0 for prescribed dofs
    ng = m%ne + cs%n
    allocate(xeq(ng + 1), eqs(2 * max_en * ng))
    xeq(1) = 1
    do e = 1, ng
      call group_nodes(m, cs, e, nodes, nen)
      k = xeq(e)
      do i = 1, nen
        eqs(k:k + 1) = dm%eq(:, nodes(i))
        k = k + 2
      end do
      xeq(e + 1) = k
    end do
    call sys_setup(sys, kind, order, n, xeq, eqs(1:xeq(ng + 1) - 1))
  end subroutine number_dofs

  !> Element data of assembly group g (solid element g, or CFE g - ne);
  !> false for line elements, which carry no stiffness.
  logical function group_input(m, cs, g, u, ein, nodes)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    integer, intent(in) :: g
    real(dp), intent(in) :: u(:, :)
    type(elem_in_t), intent(out) :: ein
    integer, intent(out) :: nodes(:)
    group_input = .true.
    if (g > m%ne) then
      call cfe_input(m, cs%c(g - m%ne), u, ein, nodes)
    else if (is_continuum(m, g)) then
      call solid_input(m, g, u, ein, nodes)
    else
      group_input = .false.
    end if
  end function group_input

  !> Nodes of assembly group g: solid element g, or CFE g - ne (coupling
  !> node first); no nodes for line elements.
  pure subroutine group_nodes(m, cs, g, nodes, nen)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    integer, intent(in) :: g
    integer, intent(out) :: nodes(:), nen
    if (g <= m%ne) then
      nen = 0
      if (.not. is_continuum(m, g)) return
      nen = elem_nodes(m, g)
      nodes(1:nen) = m%conn(1:nen, g)
    else
      associate(c => cs%c(g - m%ne))
        nen = elem_nodes(m, c%elem) + 1
        nodes(1) = c%slave
        nodes(2:nen) = m%conn(1:nen - 1, c%elem)
      end associate
    end if
  end subroutine group_nodes

  !> Stiffness into k and the out-of-balance force f_ext - f_int(u) into
  !> rhs (free equations): k du = rhs corrects the free displacements.
  subroutine assemble(m, cs, u, fext, dm, sys, rhs, with_k, kmax)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    real(dp), intent(in) :: u(:, :), fext(:, :)
    type(dofmap_t), intent(in) :: dm
    type(linear_system_t), intent(inout) :: sys
    real(dp), intent(out) :: rhs(:)
    logical, intent(in) :: with_k    ! .false.: only the right-hand side
    real(dp), intent(out) :: kmax    ! largest diagonal entry of an element matrix
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    integer :: e, i, j, nodes(max_en), gi
    kmax = 0.0_dp
    if (with_k) call sys_zero(sys)
    rhs = 0.0_dp
    do i = 1, m%nn
      do j = 1, 2
        if (dm%eq(j, i) > 0) rhs(dm%eq(j, i)) = fext(j, i)
      end do
    end do
    do e = 1, m%ne + cs%n
      if (.not. group_input(m, cs, e, u, ein, nodes)) cycle
      call element_routine(ein, eout)
      do i = 1, eout%ndof
        gi = dm%eq(2 - mod(i, 2), nodes((i + 1) / 2))
        if (gi > 0) rhs(gi) = rhs(gi) - eout%fe(i)
      end do
      if (with_k) then
        call sys_add(sys, e, eout%ke(1:eout%ndof, 1:eout%ndof))
        do j = 1, eout%ndof
          kmax = max(kmax, abs(eout%ke(j, j)))
        end do
      end if
    end do
  end subroutine assemble

  !> Internal force at every node (reactions where prescribed) and the gap
  !> and normal force of every CFE at displacements u.
  subroutine internal_forces(m, cs, u, fint)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(inout) :: cs
    real(dp), intent(in) :: u(:, :)
    real(dp), intent(out) :: fint(:, :)
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    integer :: e, i, nodes(max_en)
    fint = 0.0_dp
    do e = 1, m%ne + cs%n
      if (.not. group_input(m, cs, e, u, ein, nodes)) cycle
      call element_routine(ein, eout)
      do i = 1, ein%nen
        fint(:, nodes(i)) = fint(:, nodes(i)) + eout%fe(2 * i - 1:2 * i)
      end do
      if (e > m%ne) then
        cs%c(e - m%ne)%gap = eout%gap
        cs%c(e - m%ne)%force = eout%normal_force
      end if
    end do
  end subroutine internal_forces

  !> Integration-point stresses and strains of every solid element, and
  !> nodal stresses extrapolated from them and averaged over the elements
  !> that share the node (nodes are never shared across bodies, so this is
  !> an average per body).
  subroutine stress_recovery(m, u, nip, sig_ip, eps_ip, sig_node)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: u(:, :)
    integer, intent(out) :: nip(:)
    real(dp), intent(out) :: sig_ip(:, :, :), eps_ip(:, :, :), sig_node(:, :)
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    integer :: e, i, nodes(max_en)
    integer, allocatable :: cnt(:)
    allocate(cnt(m%nn))
    cnt = 0
    nip = 0
    sig_ip = 0.0_dp
    eps_ip = 0.0_dp
    sig_node = 0.0_dp
    do e = 1, m%ne
      if (.not. is_continuum(m, e)) cycle
      call solid_input(m, e, u, ein, nodes)
      call element_routine(ein, eout)
      nip(e) = eout%nip
      sig_ip(:, 1:eout%nip, e) = eout%sig_ip(:, 1:eout%nip)
      eps_ip(:, 1:eout%nip, e) = eout%eps_ip(:, 1:eout%nip)
      do i = 1, ein%nen
        sig_node(:, nodes(i)) = sig_node(:, nodes(i)) + eout%sig_node(:, i)
        cnt(nodes(i)) = cnt(nodes(i)) + 1
      end do
    end do
    do i = 1, m%nn
      if (cnt(i) > 0) sig_node(:, i) = sig_node(:, i) / cnt(i)
    end do
  end subroutine stress_recovery
end module assembly
