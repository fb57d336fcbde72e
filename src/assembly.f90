!> Global equations: dof numbering with prescribed dofs eliminated (in a
!> profile-reducing node order), skyline structure, assembly of the
!> stiffness and of the internal force vector from the element routines.
module assembly
  use kinds, only: dp
  use model
  use contact, only: contact_set_t, cfe_input
  use element_types, only: elem_in_t, elem_out_t, max_en, kind_quad4, kind_tri3
  use element_library, only: element_routine
  use skyline, only: skyline_t, sky_setup, sky_add, sky_zero
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
    nen = et_nodes(m%etype(e))
    ein%nen = nen
    if (nen == 4) then
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
    ein%plane_strain = et_plane_strain(m%etype(e))
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
        call group_nodes(e, nodes, nen)
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
  contains
    subroutine group_nodes(g, nodes, nen)
      integer, intent(in) :: g
      integer, intent(out) :: nodes(:), nen
      if (g <= m%ne) then
        nen = 0
        if (.not. et_is_solid(m%etype(g))) return
        nen = et_nodes(m%etype(g))
        nodes(1:nen) = m%conn(1:nen, g)
      else
        associate(c => cs%c(g - m%ne))
          nen = et_nodes(m%etype(c%elem)) + 1
          nodes(1) = c%slave
          nodes(2:nen) = m%conn(1:nen - 1, c%elem)
        end associate
      end if
    end subroutine group_nodes
  end subroutine node_graph

  !> Numbers the free dofs node by node in RCM (or input) order and sets up
  !> the skyline with the column heights of that numbering.
  subroutine number_dofs(m, cs, prescribed, use_rcm, dm, k)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    logical, intent(in) :: prescribed(:, :)
    logical, intent(in) :: use_rcm
    type(dofmap_t), intent(out) :: dm
    type(skyline_t), intent(out) :: k
    integer, allocatable :: xadj(:), adj(:), perm(:), first(:)
    integer :: i, d, n, e, j, nen, nodes(max_en), lo, eqs(2 * max_en), ne
    type(elem_in_t) :: ein
    real(dp) :: dummy(2, m%nn)
    allocate(perm(m%nn), dm%eq(2, m%nn))
    if (use_rcm) then
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
    allocate(first(n))
    first = [(i, i = 1, n)]
    dummy = 0.0_dp
    do e = 1, m%ne + cs%n
      if (e <= m%ne) then
        if (.not. et_is_solid(m%etype(e))) cycle
        call solid_input(m, e, dummy, ein, nodes)
      else
        call cfe_input(m, cs%c(e - m%ne), dummy, ein, nodes)
      end if
      nen = ein%nen
      call element_eqs(dm, nodes(1:nen), eqs, ne)
      if (ne == 0) cycle
      lo = minval(eqs(1:ne))
      do j = 1, ne
        first(eqs(j)) = min(first(eqs(j)), lo)
      end do
    end do
    call sky_setup(k, first)
  end subroutine number_dofs

  pure subroutine element_eqs(dm, nodes, eqs, ne)
    type(dofmap_t), intent(in) :: dm
    integer, intent(in) :: nodes(:)
    integer, intent(out) :: eqs(:), ne
    integer :: i, d
    ne = 0
    do i = 1, size(nodes)
      do d = 1, 2
        if (dm%eq(d, nodes(i)) > 0) then
          ne = ne + 1
          eqs(ne) = dm%eq(d, nodes(i))
        end if
      end do
    end do
  end subroutine element_eqs

  !> Stiffness into k and the out-of-balance force f_ext - f_int(u) into
  !> rhs (free equations): k du = rhs corrects the free displacements.
  subroutine assemble(m, cs, u, fext, dm, k, rhs, with_k)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    real(dp), intent(in) :: u(:, :), fext(:, :)
    type(dofmap_t), intent(in) :: dm
    type(skyline_t), intent(inout) :: k
    real(dp), intent(out) :: rhs(:)
    logical, intent(in) :: with_k    ! .false.: only the right-hand side
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    integer :: e, i, j, nodes(max_en), gi, gj
    if (with_k) call sky_zero(k)
    rhs = 0.0_dp
    do i = 1, m%nn
      do j = 1, 2
        if (dm%eq(j, i) > 0) rhs(dm%eq(j, i)) = fext(j, i)
      end do
    end do
    do e = 1, m%ne + cs%n
      if (e <= m%ne) then
        if (.not. et_is_solid(m%etype(e))) cycle
        call solid_input(m, e, u, ein, nodes)
      else
        call cfe_input(m, cs%c(e - m%ne), u, ein, nodes)
      end if
      call element_routine(ein, eout)
      do i = 1, eout%ndof
        gi = dm%eq(2 - mod(i, 2), nodes((i + 1) / 2))
        if (gi == 0) cycle
        rhs(gi) = rhs(gi) - eout%fe(i)
        if (.not. with_k) cycle
        do j = i, eout%ndof
          gj = dm%eq(2 - mod(j, 2), nodes((j + 1) / 2))
          if (gj == 0) cycle
          call sky_add(k, gi, gj, eout%ke(i, j))
        end do
      end do
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
      if (e <= m%ne) then
        if (.not. et_is_solid(m%etype(e))) cycle
        call solid_input(m, e, u, ein, nodes)
      else
        call cfe_input(m, cs%c(e - m%ne), u, ein, nodes)
      end if
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
      if (.not. et_is_solid(m%etype(e))) cycle
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
