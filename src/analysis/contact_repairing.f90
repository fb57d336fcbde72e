!> The contact paired again inside the equilibrium iteration (NLGEOM with
!> contact: docs/nonlinear.md), and the bookkeeping of which couplings
!> the equations were numbered for, so that they are numbered again only
!> where a coupling's node list changed (a point moved on to another
!> master element, or was coupled or uncoupled), never for a change of
!> geometry alone.
module contact_repairing
  use kinds, only: dp
  use model, only: model_t
  use contact, only: contact_set_t, contact_research, cfe_nodes, cfe_max_nodes
  use dof_numbering, only: dofmap_t
  use constraints, only: mpc_t
  use condensed_contact, only: number_equations
  use linear_solver, only: linear_system_t
  use equilibrium_common, only: equilibrium_t, begin_equilibrium
  implicit none
  private
  public :: search_in_iteration, coupling_length, numbering_fits, note_numbering, renumber_couplings

contains

  !> Purpose: the contact of the configuration m%x + u within a Newton
  !> iteration (NLGEOM): contact_research pairs every slave point again
  !> (master edge, projection, normal, initial gap; the status, the exact
  !> multiplier and the friction state carried over per slave point), and
  !> the equations are numbered again only where the couplings' node lists
  !> changed (renumber_couplings). Where only the geometry of the
  !> couplings moved, the numbering, the sparse structure and its symbolic
  !> analysis stay.
  !> Arguments: presc, mpc the step's prescribed dofs and constraints;
  !> dm, sys renumbered where needed; changed the statuses the search
  !> changed (contact_research), counted as status changes of the iteration.
  subroutine search_in_iteration(eq, m, cs, u, presc, mpc, dm, sys, changed)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(inout) :: cs
    real(dp), intent(in) :: u(:, :)
    logical, intent(in) :: presc(:, :)
    type(mpc_t), intent(in) :: mpc
    type(dofmap_t), intent(inout) :: dm
    type(linear_system_t), intent(inout) :: sys
    integer, intent(out) :: changed
    call contact_research(m, m%x + u, cs, moved=.true., changed=changed)
    eq%searches = eq%searches + 1
    if (.not. numbering_fits(eq, m, cs)) call renumber_couplings(eq, m, cs, presc, mpc, dm, sys)
  end subroutine search_in_iteration

  !> The shortest mesh length of the couplings of cs (huge without any).
  pure real(dp) function coupling_length(cs) result(h)
    type(contact_set_t), intent(in) :: cs
    h = huge(1.0_dp)
    if (cs%n > 0) h = minval(cs%c(1:cs%n)%h)
  end function coupling_length

  !> Purpose: were the equations (eq%numbered_for, note_numbering) numbered
  !> for the couplings of cs: the same CFEs with the same node lists,
  !> whatever their geometry?
  logical function numbering_fits(eq, m, cs)
    type(equilibrium_t), intent(in) :: eq
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    numbering_fits = .false.
    if (allocated(eq%numbered_for)) numbering_fits = same_lists(eq%numbered_for, coupling_lists(m, cs))
  end function numbering_fits

  !> Purpose: the equations have just been numbered for the couplings of
  !> cs (number_equations): remembered for numbering_fits.
  subroutine note_numbering(eq, m, cs)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    eq%numbered_for = coupling_lists(m, cs)
  end subroutine note_numbering

  !> Purpose: the equations numbered again for the couplings of cs
  !> (number_equations of a nonlinear step, keeping the solve the
  !> increment's iteration has: full or condensed) and the
  !> iteration's arrays sized for them; the analysis time is timed.
  subroutine renumber_couplings(eq, m, cs, presc, mpc, dm, sys)
    type(equilibrium_t), intent(inout) :: eq
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    logical, intent(in) :: presc(:, :)
    type(mpc_t), intent(in) :: mpc
    type(dofmap_t), intent(inout) :: dm
    type(linear_system_t), intent(inout) :: sys
    real(dp) :: ta
    call number_equations(m, cs, presc, mpc, dm, sys, eq%cd, ta, .true., keep=.true.)
    eq%timing%analyse = eq%timing%analyse + ta
    call begin_equilibrium(eq, dm%neq, cs%n, .false.)
    call note_numbering(eq, m, cs)
    eq%renumberings = eq%renumberings + 1
  end subroutine renumber_couplings

  !> The node lists of every CFE of cs in order, each preceded by its
  !> length: what the equation structure depends on.
  function coupling_lists(m, cs) result(l)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    integer, allocatable :: l(:)
    integer :: j, nen, k
    integer, allocatable :: nodes(:)
    allocate(l(cs%n * (cfe_max_nodes(cs) + 1)))
    k = 0
    do j = 1, cs%n
      call cfe_nodes(m, cs%c(j), nodes, nen)
      l(k + 1) = nen
      l(k + 2:k + 1 + nen) = nodes(1:nen)
      k = k + 1 + nen
    end do
    l = l(1:k)
  end function coupling_lists

  !> Are the integer lists a and b equal (length and entries)?
  pure logical function same_lists(a, b)
    integer, intent(in) :: a(:), b(:)
    same_lists = size(a) == size(b)
    if (same_lists) same_lists = all(a == b)
  end function same_lists
end module contact_repairing
