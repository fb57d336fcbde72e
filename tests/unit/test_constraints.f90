!> The linear constraints that *PRE-TENSION SECTION and *TIE generate:
!> small decks are read (read_model cuts the pre-tension sections,
!> tie_surfaces ties), and the new nodes, the reconnected elements and
!> the equations (node, dof, coefficient) are checked term by term.
program test_constraints
  use kinds, only: dp
  use test_report, only: report, failures
  use model
  use deck_parser, only: read_model
  use tie_constraints, only: tie_surfaces
  implicit none
  character(len=:), allocatable :: dir
  character(len=80), parameter :: square2(*) = [character(len=80) :: &
    '*NODE', '1,0,0', '2,1,0', '3,2,0', '4,0,1', '5,1,1', '6,2,1', '7,0,0', &
    '*ELEMENT,TYPE=CPE4,ELSET=EALL', '1,1,2,5,4', '2,2,3,6,5', &
    '*MATERIAL,NAME=EL', '*ELASTIC', '210000.,.3', '*SOLID SECTION,ELSET=EALL,MATERIAL=EL', '.1']
  character(len=80), parameter :: step(*) = [character(len=80) :: '*STEP', '*STATIC', '*END STEP']

  call deck_directory(dir)
  call pretension_linear_given_normal()
  call pretension_quadratic_mean_normal()
  call pretension_oblique_face()
  call tie_linear_faces()
  call tie_tolerance_and_boundary()
  call tie_curved_master()
  if (failures() > 0) stop 1

contains

  !> Decks are written next to the test program (one tree per worktree).
  subroutine deck_directory(dir)
    character(len=:), allocatable, intent(out) :: dir
    character(len=4096) :: exe
    integer :: k
    call get_command_argument(0, exe)
    k = index(exe, '/', back=.true.)
    dir = exe(1:k)
  end subroutine deck_directory

  !> Writes the deck lines to a file and reads it into m.
  subroutine read_deck_lines(name, lines, m)
    character(len=*), intent(in) :: name
    character(len=80), intent(in) :: lines(:)
    type(model_t), intent(out) :: m
    integer :: u, k
    open(newunit=u, file=dir // name, status='replace', action='write')
    do k = 1, size(lines)
      write(u, '(a)') trim(lines(k))
    end do
    close(u)
    call read_model(dir // name, m)
  end subroutine read_deck_lines

  !> Does equation k read exactly: nodes (user ids), dofs, coefficients?
  logical function equation_is(m, k, ids, dofs, coefs)
    type(model_t), intent(in) :: m
    integer, intent(in) :: k, ids(:), dofs(:)
    real(dp), intent(in) :: coefs(:)
    equation_is = .false.
    if (k > size(m%equations)) return
    associate(e => m%equations(k))
      if (size(e%node) /= size(ids)) return
      equation_is = all(m%node_id(e%node) == ids) .and. all(e%dof == dofs) .and. &
                    all(abs(e%coef - coefs) <= 1.0e-14_dp)
    end associate
  end function equation_is

  character(len=200) function describe(m, k) result(s)
    type(model_t), intent(in) :: m
    integer, intent(in) :: k
    integer :: j
    s = 'no such equation'
    if (k > size(m%equations)) return
    s = ''
    associate(e => m%equations(k))
      do j = 1, size(e%node)
        write(s(len_trim(s) + 1:), '(1x,i0,":",i0,"*",g0.6)') m%node_id(e%node(j)), e%dof(j), e%coef(j)
      end do
    end associate
  end function describe

  !> CalculiX's pret5 shape: the face S2 of element 1 cut, normal given.
  subroutine pretension_linear_given_normal()
    type(model_t) :: m
    call read_deck_lines('pret_linear.inp', [character(len=80) :: square2, '*SURFACE,NAME=SURF1', '1,S2', &
                         '*PRE-TENSION SECTION,SURFACE=SURF1,NODE=7', '1.,0.,0.', step], m)
    call report('pre-tension: copies of nodes 2 and 5 numbered 8 and 9', m%nn == 9 .and. &
                all(m%node_id(8:9) == [8, 9]) .and. all(m%x(:, 8) == m%x(:, 2)) .and. all(m%x(:, 9) == m%x(:, 5)), &
                'nn and ids wrong')
    call report('pre-tension: the face owner takes the copies, its neighbour keeps the originals', &
                all(m%conn(1:4, 1) == [1, 8, 9, 4]) .and. all(m%conn(1:4, 2) == [2, 3, 6, 5]), 'connectivity wrong')
    call report('pre-tension: u(copy) - u(original) - n u1(ref) = 0 per dof (n = x)', size(m%equations) == 4 .and. &
                equation_is(m, 1, [8, 2, 7], [1, 1, 1], [1.0_dp, -1.0_dp, -1.0_dp]) .and. &
                equation_is(m, 2, [8, 2], [2, 2], [1.0_dp, -1.0_dp]) .and. &
                equation_is(m, 3, [9, 5, 7], [1, 1, 1], [1.0_dp, -1.0_dp, -1.0_dp]) .and. &
                equation_is(m, 4, [9, 5], [2, 2], [1.0_dp, -1.0_dp]), describe(m, 1))
    call report('pre-tension: the surface''s nodes are the copies', all(m%surfaces(1)%nodes == [8, 9]), &
                'surface nodes not renewed')
  end subroutine pretension_linear_given_normal

  !> CalculiX's pret6 shape (8-node), no normal: the mean outward normal;
  !> the mid-side node is copied too, temperatures follow the copies.
  subroutine pretension_quadratic_mean_normal()
    type(model_t) :: m
    integer :: k, ncopied
    call read_deck_lines('pret_quadratic.inp', [character(len=80) :: &
      '*NODE', '1,0,0', '2,1,0', '3,2,0', '4,0,1', '5,1,1', '6,2,1', '7,0,0', '8,.5,0', '9,1.5,0', '10,0,.5', &
      '11,1,.5', '12,2,.5', '13,.5,1', '14,1.5,1', &
      '*ELEMENT,TYPE=CPE8,ELSET=EALL', '1,1,2,5,4,8,11,13,10', '2,2,3,6,5,9,12,14,11', &
      '*MATERIAL,NAME=EL', '*ELASTIC', '210000.,.3', '*SOLID SECTION,ELSET=EALL,MATERIAL=EL', '.1', &
      '*SURFACE,NAME=SURF1', '1,S2', '*PRE-TENSION SECTION,SURFACE=SURF1,NODE=7', &
      '*INITIAL CONDITIONS,TYPE=TEMPERATURE', '11,20.', '*STEP', '*STATIC', '*TEMPERATURE', '5,80.', '*END STEP'], m)
    associate(pt => m%pretensions(1))
      call report('pre-tension: mean outward normal of the face', all(abs(pt%normal - [1.0_dp, 0.0_dp]) < 1e-15_dp), &
                  'normal wrong')
      call report('pre-tension: corners and mid-side node copied in face order', all(m%node_id(pt%copy) == &
                  [15, 16, 17]) .and. all(m%node_id(pt%original) == [2, 5, 11]), 'copies wrong')
      call report('pre-tension: 8-node owner reconnected', all(m%conn(1:8, 1) == [1, 15, 16, 4, 8, 17, 13, 10]) &
                  .and. all(m%conn(1:8, 2) == [2, 3, 6, 5, 9, 12, 14, 11]), 'connectivity wrong')
      call report('pre-tension: equation of the mid-side copy', size(m%equations) == 6 .and. &
                  equation_is(m, 5, [17, 11, 7], [1, 1, 1], [1.0_dp, -1.0_dp, -1.0_dp]), describe(m, 5))
    end associate
    ncopied = 0
    do k = 1, size(m%initial_temps)
      if (m%node_id(m%initial_temps(k)%node) == 17 .and. m%initial_temps(k)%value == 20.0_dp) ncopied = ncopied + 1
    end do
    do k = 1, size(m%steps(1)%temps)
      if (m%node_id(m%steps(1)%temps(k)%node) == 16 .and. m%steps(1)%temps(k)%value == 80.0_dp) ncopied = ncopied + 1
    end do
    call report('pre-tension: copies take their originals'' temperatures', ncopied == 2, 'temperatures not copied')
  end subroutine pretension_quadratic_mean_normal

  !> A face that is not along an axis: n = (2, 1)/sqrt(5) enters the
  !> equations of both dofs.
  subroutine pretension_oblique_face()
    type(model_t) :: m
    real(dp) :: n(2)
    call read_deck_lines('pret_oblique.inp', [character(len=80) :: &
      '*NODE', '1,0,0', '2,2,1', '3,1,3', '4,-1,2', '5,4,2', '6,3,4', '9,0,0', &
      '*ELEMENT,TYPE=CPS4,ELSET=EALL', '1,1,2,3,4', '2,2,5,6,3', &
      '*MATERIAL,NAME=EL', '*ELASTIC', '1.,.3', '*SOLID SECTION,ELSET=EALL,MATERIAL=EL', '1.', &
      '*NSET,NSET=REF', '9', '*SURFACE,NAME=CUT', '1,S2', '*PRE-TENSION SECTION,SURFACE=CUT,NODE=REF', step], m)
    n = [2.0_dp, 1.0_dp] / sqrt(5.0_dp)
    call report('pre-tension: oblique normal in both dofs', all(abs(m%pretensions(1)%normal - n) < 1e-15_dp) .and. &
                equation_is(m, 1, [10, 2, 9], [1, 1, 1], [1.0_dp, -1.0_dp, -n(1)]) .and. &
                equation_is(m, 2, [10, 2, 9], [2, 2, 1], [1.0_dp, -1.0_dp, -n(2)]) .and. &
                equation_is(m, 4, [11, 3, 9], [2, 2, 1], [1.0_dp, -1.0_dp, -n(2)]), describe(m, 2))
  end subroutine pretension_oblique_face

  !> Two blocks: 2 elements below, 3 above whose bottom lies 0.001 above
  !> the lower top; the upper bottom (slave) tied to the lower top.
  subroutine tie_linear_faces()
    type(model_t) :: m
    integer :: k, s
    real(dp) :: xm(2), err_pos, err_sum
    call read_deck_lines('tie_linear.inp', [character(len=80) :: two_blocks('1.001'), &
      '*TIE,NAME=T1', 'UP_BOTTOM,LOW_TOP', step], m)
    call tie_surfaces(m)
    call report('tie: every slave node tied, two equations each', m%ties(1)%tied == 4 .and. m%ties(1)%untied == 0 &
                .and. size(m%equations) == 8, 'tied count or equation count wrong')
    err_pos = 0.0_dp
    err_sum = 0.0_dp
    do k = 1, size(m%equations)
      associate(e => m%equations(k))
        s = e%node(1)
        xm = matmul(m%x(:, e%node(2:)), -e%coef(2:))
        err_pos = max(err_pos, norm2(xm - m%x(:, s)))
        err_sum = max(err_sum, abs(sum(e%coef)))
        if (e%coef(1) /= 1.0_dp .or. any(e%dof /= e%dof(1))) err_sum = huge(1.0_dp)
      end associate
    end do
    call report('tie: slave nodes moved onto the master (ADJUST default)', &
                all(abs(m%x(2, m%surfaces(2)%nodes) - 1.0_dp) < 1e-15_dp) .and. &
                abs(m%ties(1)%largest_move - 0.001_dp) < 1e-12_dp, 'slave nodes not at y = 1')
    call report('tie: weights sum to one and reproduce the slave position', err_pos < 1e-14_dp .and. &
                err_sum < 1e-14_dp, 'weights wrong')
    ! node 12 at x = 2/3 on the face S3 of element 1, from node 5 (1, 1) to 4 (0, 1)
    call report('tie: slave node 1/3 along a master face', equation_is(m, 3, [12, 5, 4], [1, 1, 1], &
                [1.0_dp, -2.0_dp / 3.0_dp, -1.0_dp / 3.0_dp]), describe(m, 3))
    call report('tie: slave node on a master corner: one master term', &
                equation_is(m, 1, [11, 4], [1, 1], [1.0_dp, -1.0_dp]), describe(m, 1))
  end subroutine tie_linear_faces

  !> Out of tolerance: nothing tied, nodes not moved; a prescribed dof of
  !> a slave node is left untied (ADJUST=NO keeps the node where it is).
  subroutine tie_tolerance_and_boundary()
    type(model_t) :: m
    integer :: k
    call read_deck_lines('tie_tolerance.inp', [character(len=80) :: two_blocks('1.001'), &
      '*TIE,NAME=T1,POSITION TOLERANCE=0.0005', 'UP_BOTTOM,LOW_TOP', step], m)
    call tie_surfaces(m)
    call report('tie: nodes beyond the position tolerance are not tied', m%ties(1)%tied == 0 .and. &
                m%ties(1)%untied == 4 .and. size(m%equations) == 0 .and. &
                all(abs(m%x(2, m%surfaces(2)%nodes) - 1.001_dp) < 1e-15_dp), 'something tied')
    call read_deck_lines('tie_boundary.inp', [character(len=80) :: two_blocks('1.001'), &
      '*BOUNDARY', '11,1', '*TIE,NAME=T1,ADJUST=NO', 'UP_BOTTOM,LOW_TOP', step], m)
    call tie_surfaces(m)
    call report('tie: a prescribed slave dof is not tied, ADJUST=NO moves nothing', m%ties(1)%tied == 4 .and. &
                size(m%equations) == 7 .and. count([(m%node_id(m%equations(k)%node(1)) == 11, k = 1, 7)]) == 1 &
                .and. all(abs(m%x(2, m%surfaces(2)%nodes) - 1.001_dp) < 1e-15_dp), 'wrong equations')
  end subroutine tie_tolerance_and_boundary

  !> A curved 3-node master face: a slave node ends on the curve and its
  !> weights are the quadratic shape functions there.
  subroutine tie_curved_master()
    type(model_t) :: m
    real(dp) :: xm(2), tpar, w(3)
    call read_deck_lines('tie_curved.inp', [character(len=80) :: &
      '*NODE', '1,0,0', '2,2,0', '3,2,1', '4,0,1', '5,1,0', '6,2,.5', '7,1,1.2', '8,0,.5', &
      '11,0.5,1.2', '12,1.5,1.2', '13,1,2', &
      '*ELEMENT,TYPE=CPE8,ELSET=LOW', '1,1,2,3,4,5,6,7,8', '*ELEMENT,TYPE=CPE3,ELSET=UP', '2,11,12,13', &
      '*MATERIAL,NAME=EL', '*ELASTIC', '1.,.3', '*SOLID SECTION,ELSET=LOW,MATERIAL=EL', '1.', &
      '*SOLID SECTION,ELSET=UP,MATERIAL=EL', '1.', &
      '*SURFACE,NAME=TOP', '1,S3', '*SURFACE,NAME=SL', '2,S1', '*TIE,NAME=T,POSITION TOLERANCE=0.2', 'SL,TOP', step], m)
    call tie_surfaces(m)
    ! y(s) on the face from node 3 (2,1) through 7 (1,1.2) to 4 (0,1), s in [-1, 1]
    xm = matmul(m%x(:, m%equations(1)%node(2:)), -m%equations(1)%coef(2:))
    call report('tie: curved master reproduces the slave position', size(m%equations) == 4 .and. &
                norm2(xm - m%x(:, m%equations(1)%node(1))) < 1e-13_dp, describe(m, 1))
    tpar = (2.0_dp - m%x(1, m%node_index(11))) / 2.0_dp
    w = [(2.0_dp * tpar - 1.0_dp) * (tpar - 1.0_dp), tpar * (2.0_dp * tpar - 1.0_dp), 4.0_dp * tpar * (1.0_dp - tpar)]
    call report('tie: slave node on the curve, y = 1 + 0.8 t (1 - t)', abs(m%x(2, m%node_index(11)) - &
                (1.0_dp + 0.8_dp * tpar * (1.0_dp - tpar))) < 1e-12_dp .and. &
                equation_is(m, 1, [11, 3, 4, 7], [1, 1, 1, 1], [1.0_dp, -w]), describe(m, 1))
  end subroutine tie_curved_master

  !> Lower block [0,2]x[0,1] (2 CPE4, nodes 1-6), upper block
  !> [0,2]x[y0,2] (3 CPE4, nodes 11-18, bottom 11-14); surfaces LOW_TOP
  !> and UP_BOTTOM.
  function two_blocks(y0) result(lines)
    character(len=*), intent(in) :: y0
    character(len=80), allocatable :: lines(:)
    lines = [character(len=80) :: '*NODE', '1,0,0', '2,1,0', '3,2,0', '4,0,1', '5,1,1', '6,2,1', &
      '11,0,' // y0, '12,0.6666666666666666,' // y0, '13,1.3333333333333333,' // y0, '14,2,' // y0, &
      '15,0,2', '16,0.6666666666666666,2', '17,1.3333333333333333,2', '18,2,2', &
      '*ELEMENT,TYPE=CPE4,ELSET=LOW', '1,1,2,5,4', '2,2,3,6,5', &
      '*ELEMENT,TYPE=CPE4,ELSET=UP', '11,11,12,16,15', '12,12,13,17,16', '13,13,14,18,17', &
      '*MATERIAL,NAME=EL', '*ELASTIC', '1.,.3', '*SOLID SECTION,ELSET=LOW,MATERIAL=EL', '1.', &
      '*SOLID SECTION,ELSET=UP,MATERIAL=EL', '1.', '*SURFACE,NAME=LOW_TOP', 'LOW,S3', &
      '*SURFACE,NAME=UP_BOTTOM', 'UP,S1']
  end function two_blocks
end program test_constraints
