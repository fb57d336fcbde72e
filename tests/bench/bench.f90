!> One benchmark case: a unit square in plane stress meshed with nx*nx Q4,
!> fixed on two sides, loaded on all nodes; assembled and solved by one
!> solver. Prints one line of key=value figures (times in seconds, wall
!> clock): pattern, assembly, ordering + symbolic analysis, the first
!> numeric factorisation, one solve, peak memory, residual.
!>   bench SOLVER ORDERING NX      (SOLVER: skyline|cholmod|umfpack)
program bench
  use kinds, only: dp
  use model
  use element_catalogue, only: find_element_type
  use contact, only: contact_set_t
  use dof_numbering, only: dofmap_t, number_dofs
  use assembly, only: body_t, element_counts_t, body_setup, assemble_stiffness, body_forces, free_residual
  use linear_solver
  implicit none
  character(len=32) :: a1, a2, a3
  integer :: nx, kind, order, i, j, e, n, st, bad
  type(model_t) :: m
  type(contact_set_t) :: cs
  type(dofmap_t) :: dm
  type(linear_system_t) :: sys
  logical, allocatable :: presc(:, :)
  real(dp), allocatable :: u(:, :), f(:, :), fint(:, :), rhs(:), b(:), r(:)
  type(body_t) :: body
  type(element_counts_t) :: counts
  real(dp) :: kmax, t_number, t_asm, t_analysis, t_fact, t_solve, res
  integer(8) :: c0, c1, rate

  call get_command_argument(1, a1)
  call get_command_argument(2, a2)
  call get_command_argument(3, a3)
  read(a3, *) nx
  select case (trim(a1))
  case ('skyline'); kind = solver_skyline
  case ('umfpack'); kind = solver_umfpack
  case default; kind = solver_cholmod
  end select
  select case (trim(a2))
  case ('rcm'); order = order_rcm
  case ('metis'); order = order_metis
  case ('none'); order = order_natural
  case default; order = order_amd
  end select

  ! mesh
  m%nn = (nx + 1)**2
  m%ne = nx * nx
  allocate(m%node_id(m%nn), m%x(2, m%nn), m%elem_id(m%ne), m%etype(m%ne), m%conn(4, m%ne), &
           m%elem_section(m%ne), m%materials(1), m%sections(1), m%pairs(0))
  do j = 0, nx
    do i = 0, nx
      n = j * (nx + 1) + i + 1
      m%node_id(n) = n
      m%x(:, n) = [real(i, dp), real(j, dp)] / nx
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
  allocate(cs%c(0), presc(2, m%nn), u(2, m%nn), f(2, m%nn), fint(2, m%nn))
  cs%n = 0
  presc = .false.
  do i = 1, nx + 1
    presc(2, i) = .true.                       ! bottom: rollers
    presc(1, (i - 1) * (nx + 1) + 1) = .true.  ! left: rollers
  end do
  u = 0.0_dp
  do n = 1, m%nn
    f(:, n) = [sin(0.37_dp * n), cos(0.11_dp * n)]
  end do

  call system_clock(c0, rate)
  call number_dofs(m, cs, presc, kind, order, dm, sys)
  t_number = elapsed()
  allocate(rhs(dm%neq))
  call body_setup(m, body, counts)
  call assemble_stiffness(m, cs, body, u, sys, kmax, counts, dm)
  call body_forces(m, body, u, fint)
  call free_residual(dm, f, fint, rhs)
  t_asm = elapsed()
  call sys_analyse(sys)
  t_analysis = elapsed()
  call sys_factor(sys, st, bad)
  t_fact = elapsed()
  if (st == factor_singular) stop 'singular'
  b = rhs
  call sys_solve(sys, b)
  t_solve = elapsed()
  ! residual with the assembled (for the skyline: re-assembled) matrix
  if (kind == solver_skyline) call assemble_stiffness(m, cs, body, u, sys, kmax, counts, dm)
  allocate(r(dm%neq))
  call sys_matvec(sys, b, r)
  res = norm2(r - rhs) / norm2(rhs)
  print '(a,a,a,a,a,i0,a,i0,a,es10.3,a,f8.3,a,f8.3,a,f8.3,a,f8.3,a,f8.3,a,i0,a,es9.2)', &
    'solver=', trim(a1), ' ordering=', trim(a2), ' dofs=', dm%neq, ' nnz=', nnz(), ' factor=', sys%factor_entries, &
    ' t_structure=', t_number, ' t_assembly=', t_asm, ' t_analysis=', t_analysis, &
    ' t_factor=', t_fact, ' t_solve=', t_solve, ' peak_MiB=', peak_mib(), ' residual=', res

contains

  real(dp) function elapsed()
    call system_clock(c1)
    elapsed = real(c1 - c0, dp) / rate
    call system_clock(c0)
  end function elapsed

  !> Stored entries of the assembled matrix (the skyline: its profile).
  integer(8) function nnz()
    nnz = sys_stored_entries(sys)
  end function nnz

  !> VmHWM of this process, from /proc/self/status.
  integer function peak_mib()
    character(len=256) :: line
    integer :: u_, ios, kb
    peak_mib = -1
    open(newunit=u_, file='/proc/self/status', action='read', iostat=ios)
    if (ios /= 0) return
    do
      read(u_, '(a)', iostat=ios) line
      if (ios /= 0) exit
      if (line(1:6) == 'VmHWM:') then
        read(line(7:), *) kb
        peak_mib = kb / 1024
      end if
    end do
    close(u_)
  end function peak_mib
end program bench
