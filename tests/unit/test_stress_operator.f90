!> The stress recovery's linear path (assembly's linear_stresses, taken
!> in a linear step by isotropic linear elastic continuum elements) against
!> the element routine (continuum, taken when a body is passed): on every
!> continuum shape and rule (3-, 4-, 6- and 8-node, full and reduced) in
!> plane stress, plane strain and axisymmetry, on distorted elements, at
!> arbitrary displacements, with and without a thermal strain and an
!> initial stress. The integration-point stresses and strains and the
!> nodal stresses must agree to 1e-12 of their largest magnitude (the
!> same arithmetic; only the compiler's order of it may differ).
program test_stress_operator
  use kinds, only: dp
  use test_report, only: report, failures
  use model
  use deck_parser, only: read_model
  use element_catalogue, only: max_ip
  use element_interface, only: max_hist
  use assembly, only: stress_recovery, element_counts_t, body_t
  implicit none
  character(len=:), allocatable :: dir
  character(len=3), parameter :: prefixes(3) = ['CPS', 'CPE', 'CAX']
  integer :: k

  call deck_directory(dir)
  do k = 1, size(prefixes)
    call compare_paths(prefixes(k), .false., .false.)
    call compare_paths(prefixes(k), .true., .false.)
    call compare_paths(prefixes(k), .false., .true.)
  end do
  if (failures() > 0) stop 1

contains

  !> Decks are written next to the test program (one tree per worktree).
  subroutine deck_directory(dir)
    character(len=:), allocatable, intent(out) :: dir
    character(len=4096) :: exe
    integer :: i
    call get_command_argument(0, exe)
    i = index(exe, '/', back=.true.)
    dir = exe(1:i)
  end subroutine deck_directory

  !> Purpose: writes a deck of one element of each continuum type of the
  !> stress state named by prefix (CPS, CPE, CAX), distorted, on its own
  !> nodes (x >= 1: positive radii), and reads it into m.
  subroutine shapes_model(prefix, m)
    character(len=3), intent(in) :: prefix
    type(model_t), intent(out) :: m
    character(len=*), parameter :: nodes(*) = [character(len=40) :: '*NODE', &
      '1, 1.0, 0.0', '2, 2.0, 0.1', '3, 1.2, 1.0', &
      '4, 3.0, 0.0', '5, 4.1, 0.2', '6, 4.0, 1.1', '7, 2.9, 0.9', &
      '8, 5.0, 0.0', '9, 6.0, 0.0', '10, 5.0, 1.0', '11, 5.5, 0.05', '12, 5.5, 0.5', '13, 5.02, 0.5', &
      '14, 7.0, 0.0', '15, 8.0, 0.1', '16, 8.1, 1.0', '17, 6.9, 1.1', &
      '18, 7.5, 0.03', '19, 8.05, 0.55', '20, 7.5, 1.07', '21, 6.95, 0.5']
    character(len=80), allocatable :: lines(:)
    integer :: u, i
    lines = [character(len=80) :: &
      '*ELEMENT, TYPE=' // prefix // '3, ELSET=EALL', '1, 1, 2, 3', &
      '*ELEMENT, TYPE=' // prefix // '4, ELSET=EALL', '2, 4, 5, 6, 7', &
      '*ELEMENT, TYPE=' // prefix // '4R, ELSET=EALL', '3, 4, 5, 6, 7', &
      '*ELEMENT, TYPE=' // prefix // '6, ELSET=EALL', '4, 8, 9, 10, 11, 12, 13', &
      '*ELEMENT, TYPE=' // prefix // '8, ELSET=EALL', '5, 14, 15, 16, 17, 18, 19, 20, 21', &
      '*ELEMENT, TYPE=' // prefix // '8R, ELSET=EALL', '6, 14, 15, 16, 17, 18, 19, 20, 21', &
      '*MATERIAL, NAME=EL', '*ELASTIC', '210000., 0.3', '*EXPANSION', '1.2e-5', &
      '*SOLID SECTION, ELSET=EALL, MATERIAL=EL', '0.7', '*STEP', '*STATIC', '*END STEP']
    open(newunit=u, file=dir // 'stress_operator_' // prefix // '.inp', status='replace', action='write')
    do i = 1, size(nodes)
      write(u, '(a)') trim(nodes(i))
    end do
    do i = 1, size(lines)
      write(u, '(a)') trim(lines(i))
    end do
    close(u)
    call read_model(dir // 'stress_operator_' // prefix // '.inp', m)
  end subroutine shapes_model

  !> Purpose: the stress recovery of the shapes_model of prefix by both
  !> paths at the same displacements (and, if thermal, nodal temperature
  !> changes; if initial, an initial stress at every point), compared.
  subroutine compare_paths(prefix, thermal, initial)
    character(len=3), intent(in) :: prefix
    logical, intent(in) :: thermal, initial
    type(model_t) :: m
    type(body_t) :: body
    type(element_counts_t) :: counts
    real(dp), allocatable :: u(:, :), dtemp(:), sa(:, :, :), sb(:, :, :), ea(:, :, :), eb(:, :, :), &
                             na(:, :), nb(:, :)
    integer, allocatable :: nipa(:), nipb(:)
    integer :: a, e, ip
    character(len=:), allocatable :: name
    call shapes_model(prefix, m)
    allocate(u(2, m%nn), dtemp(m%nn), sa(4, max_ip, m%ne), sb(4, max_ip, m%ne), ea(3, max_ip, m%ne), &
             eb(3, max_ip, m%ne), na(4, m%nn), nb(4, m%nn), nipa(m%ne), nipb(m%ne))
    do a = 1, m%nn
      u(:, a) = 1.0e-3_dp * [sin(1.7_dp * a + 0.3_dp), cos(2.3_dp * a - 0.1_dp)]
      dtemp(a) = 50.0_dp * sin(0.9_dp * a)
    end do
    if (initial) then
      allocate(m%sig0(4, max_ip, m%ne))
      do e = 1, m%ne
        do ip = 1, max_ip
          m%sig0(:, ip, e) = [120.0_dp, -40.0_dp, 25.0_dp, 7.0_dp] * (1.0_dp + 0.1_dp * ip + 0.03_dp * e)
        end do
      end do
    end if
    ! the element routine: a body (small deformation, no history) is passed
    body%nlgeom = .false.
    allocate(body%hist(max_hist, max_ip, m%ne))
    body%hist = 0.0_dp
    name = prefix
    if (thermal) name = name // ' thermal'
    if (initial) name = name // ' initial stress'
    if (thermal) then
      call stress_recovery(m, u, nipa, sa, ea, na, counts, dtemp)
      call stress_recovery(m, u, nipb, sb, eb, nb, counts, dtemp, body)
    else
      call stress_recovery(m, u, nipa, sa, ea, na, counts)
      call stress_recovery(m, u, nipb, sb, eb, nb, counts, body=body)
    end if
    call report(trim(name) // ': points per element', all(nipa == nipb) .and. all(nipa > 0), 'differ')
    call report(trim(name) // ': stresses at the points', close_to(sa, sb), 'differ by more than 1e-12')
    call report(trim(name) // ': strains at the points', close_to(ea, eb), 'differ by more than 1e-12')
    call report(trim(name) // ': stresses at the nodes', close_to(reshape(na, [4, m%nn, 1]), &
                reshape(nb, [4, m%nn, 1])), 'differ by more than 1e-12')
    ! the fixture must exercise something: nonzero stresses on every element
    call report(trim(name) // ': every element stressed', all(maxval(maxval(abs(sb), 1), 1) > 0.0_dp), 'zero')
  end subroutine compare_paths

  !> Purpose: do a and b agree to 1e-12 of b's largest magnitude?
  logical function close_to(a, b)
    real(dp), intent(in) :: a(:, :, :), b(:, :, :)
    close_to = maxval(abs(a - b)) <= 1.0e-12_dp * maxval(abs(b)) .and. maxval(abs(b)) > 0.0_dp
  end function close_to
end program test_stress_operator
