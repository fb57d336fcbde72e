!> Global equations: the free dofs numbered (prescribed ones eliminated),
!> node by node in a profile-reducing order for the skyline or in input
!> order for the sparse solvers (which order for themselves), optionally
!> with a chosen set of dofs numbered last; and the equation lists of the
!> assembly groups (continuum elements, then coupling elements) from which
!> the solver sets up its structure.
module dof_numbering
  use kinds, only: dp
  use model
  use contact, only: contact_set_t, cfe_nodes
  use element_interface, only: max_en
  use linear_solver, only: linear_system_t, sys_setup, solver_skyline, order_rcm
  use ordering, only: rcm_order
  implicit none
  private
  public :: dofmap_t, number_dofs

  type :: dofmap_t
    integer :: neq = 0
    integer, allocatable :: eq(:, :)     ! (2, nn): equation, 0 if prescribed
    integer, allocatable :: node_of_eq(:), dof_of_eq(:)
  end type dofmap_t

contains

  !> Purpose: nodes of assembly group g: body element g, or CFE g - ne
  !> (slave nodes first); no nodes for elements without stiffness (line
  !> elements that only describe boundaries).
  pure subroutine group_nodes(m, cs, g, nodes, nen)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    integer, intent(in) :: g
    integer, intent(out) :: nodes(:), nen
    if (g <= m%ne) then
      nen = 0
      if (.not. carries_stiffness(m, g)) return
      nen = elem_nodes(m, g)
      nodes(1:nen) = m%conn(1:nen, g)
    else
      call cfe_nodes(m, cs%c(g - m%ne), nodes, nen)
    end if
  end subroutine group_nodes

  !> Node graph of body elements and CFEs in compressed form.
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

  !> Purpose: numbers the free dofs and sets up the system's structure from
  !> the equation lists of the continuum elements and the CFEs, in
  !> assembly order.
  !> Arguments: prescribed(2, nn) dofs eliminated; kind, order the solver
  !> and its ordering; last(2, nn), if present, marks dofs numbered after
  !> all others (in node order), e.g. the contact equations of a condensed
  !> solve.
  subroutine number_dofs(m, cs, prescribed, kind, order, dm, sys, last)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    logical, intent(in) :: prescribed(:, :)
    integer, intent(in) :: kind, order
    type(dofmap_t), intent(out) :: dm
    type(linear_system_t), intent(inout) :: sys
    logical, intent(in), optional :: last(:, :)
    integer, allocatable :: xadj(:), adj(:), perm(:)
    integer :: i, d, n, pass, nlast
    logical :: take
    allocate(perm(m%nn), dm%eq(2, m%nn))
    if (kind == solver_skyline .and. order == order_rcm) then
      call node_graph(m, cs, xadj, adj)
      call rcm_order(m%nn, xadj, adj, perm)
    else
      perm = [(i, i = 1, m%nn)]
    end if
    dm%eq = 0
    n = 0
    do pass = 1, 2
      do i = 1, m%nn
        do d = 1, 2
          if (prescribed(d, perm(i))) cycle
          take = pass == 1
          if (present(last)) take = last(d, perm(i)) .eqv. (pass == 2)
          if (.not. take) cycle
          n = n + 1
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
    nlast = 0
    if (present(last)) nlast = count(last .and. .not. prescribed)
    call setup_structure(m, cs, dm, kind, order, nlast, sys)
  end subroutine number_dofs

  !> Equation lists (local dof order, 0 for prescribed dofs) of every
  !> assembly group, handed to the solver with the size of the trailing
  !> block (nlast).
  subroutine setup_structure(m, cs, dm, kind, order, nlast, sys)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    type(dofmap_t), intent(in) :: dm
    integer, intent(in) :: kind, order, nlast
    type(linear_system_t), intent(inout) :: sys
    integer, allocatable :: xeq(:), eqs(:)
    integer :: ng, e, i, k, nen, nodes(max_en)
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
    call sys_setup(sys, kind, order, dm%neq, xeq, eqs(1:xeq(ng + 1) - 1), nlast)
  end subroutine setup_structure
end module dof_numbering
