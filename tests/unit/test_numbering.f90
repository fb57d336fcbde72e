!> Equation numbering and the stored-stiffness assembly: a chosen set of
!> dofs numbered last (what a condensed contact solve needs), and the same
!> displacements whatever the numbering, through every solver.
program test_numbering
  use kinds, only: dp
  use test_report, only: report, failures
  use model
  use element_catalogue, only: find_element_type
  use mesh_topology, only: build_topology
  use contact, only: contact_set_t
  use dof_numbering, only: dofmap_t, number_dofs
  use assembly, only: body_t, element_counts_t, body_setup, assemble_stiffness, body_forces, free_residual
  use linear_solver
  implicit none
  integer, parameter :: nx = 6
  type(model_t) :: m
  type(contact_set_t) :: cs
  logical, allocatable :: presc(:, :), last(:, :)
  real(dp), allocatable :: u_ref(:), u(:)
  integer :: n, i, j, kind
  character(len=120) :: msg
  integer, parameter :: kinds_tested(3) = [solver_skyline, solver_cholmod, solver_umfpack]

  call square_mesh(m)
  allocate(cs%c(0))
  cs%n = 0
  allocate(presc(2, m%nn), last(2, m%nn))
  presc = .false.
  do i = 1, nx + 1
    presc(2, i) = .true.                       ! bottom: rollers
    presc(1, (i - 1) * (nx + 1) + 1) = .true.  ! left: rollers
  end do
  ! a middle row of nodes last (in node order they are not), as the
  ! contact equations of a condensed solve would be
  last = .false.
  last(:, (nx / 2) * (nx + 1) + 1:(nx / 2 + 1) * (nx + 1)) = .true.
  call solve(solver_skyline, .false., u_ref, n)
  do j = 1, size(kinds_tested)
    kind = kinds_tested(j)
    call solve(kind, .true., u, n)
    write(msg, '(a,es9.2)') 'largest relative difference ', maxval(abs(u - u_ref)) / maxval(abs(u_ref))
    call report(solver_name(kind) // ': same displacements with a middle row numbered last', &
                maxval(abs(u - u_ref)) <= 1.0e-10_dp * maxval(abs(u_ref)), msg)
  end do
  if (failures() > 0) stop 1

contains

  !> Solves the loaded square; u(2*nn) in node order (0 where prescribed).
  !> With with_last, also checks that the marked dofs hold the highest
  !> equation numbers.
  subroutine solve(kind, with_last, u, neq)
    integer, intent(in) :: kind
    logical, intent(in) :: with_last
    real(dp), allocatable, intent(out) :: u(:)
    integer, intent(out) :: neq
    type(dofmap_t) :: dm
    type(linear_system_t) :: sys
    type(body_t) :: body
    type(element_counts_t) :: counts
    real(dp), allocatable :: uu(:, :), f(:, :), fint(:, :), rhs(:)
    real(dp) :: kmax
    integer :: st, bad, a, d, nlast, lowest_last, highest_other
    if (with_last) then
      call number_dofs(m, cs, presc, kind, order_amd, dm, sys, last)
      nlast = count(last .and. .not. presc)
      lowest_last = minval(dm%eq, mask=last .and. .not. presc)
      highest_other = maxval(dm%eq, mask=.not. last .and. .not. presc)
      call report(solver_name(kind) // ': the chosen dofs are numbered last', &
                  lowest_last == dm%neq - nlast + 1 .and. highest_other == dm%neq - nlast, '')
    else
      call number_dofs(m, cs, presc, kind, order_rcm, dm, sys)
    end if
    neq = dm%neq
    allocate(uu(2, m%nn), f(2, m%nn), fint(2, m%nn), rhs(dm%neq), u(2 * m%nn))
    uu = 0.0_dp
    do a = 1, m%nn
      f(:, a) = [sin(0.37_dp * a), cos(0.11_dp * a)]
    end do
    call body_setup(m, body, counts)
    call assemble_stiffness(m, cs, body, uu, sys, kmax, counts, dm)
    call body_forces(m, body, uu, fint)
    call free_residual(dm, f, fint, rhs)
    call sys_factor(sys, st, bad)
    call sys_solve(sys, rhs)
    u = 0.0_dp
    do a = 1, m%nn
      do d = 1, 2
        if (dm%eq(d, a) > 0) u(2 * (a - 1) + d) = rhs(dm%eq(d, a))
      end do
    end do
    call sys_free(sys)
  end subroutine solve

  subroutine square_mesh(m)
    type(model_t), intent(out) :: m
    integer :: i, j, e, n
    m%nn = (nx + 1)**2
    m%ne = nx * nx
    allocate(m%node_id(m%nn), m%x(2, m%nn), m%elem_id(m%ne), m%etype(m%ne), m%conn(4, m%ne), &
             m%elem_section(m%ne), m%materials(1), m%sections(1), m%pairs(0))
    do j = 0, nx
      do i = 0, nx
        n = j * (nx + 1) + i + 1
        m%node_id(n) = n
        m%x(:, n) = [real(i, dp), real(j, dp)] / nx + 0.01_dp * [sin(1.0_dp * n), cos(2.0_dp * n)]
      end do
    end do
    do j = 0, nx - 1
      do i = 0, nx - 1
        e = j * nx + i + 1
        n = j * (nx + 1) + i + 1
        m%elem_id(e) = e
        m%etype(e) = find_element_type('CPS4')
        m%conn(:, e) = [n, n + 1, n + nx + 2, n + nx + 1]
      end do
    end do
    m%elem_section = 1
    m%materials(1)%e = 210000.0_dp
    m%materials(1)%nu = 0.3_dp
    m%sections(1)%material = 1
    m%sections(1)%thickness = 1.0_dp
    call build_topology(m%nn, m%ne, m%etype, m%conn, m%topo)
  end subroutine square_mesh
end program test_numbering
