!> *TIE (tied contact) as linear constraints: each slave node within the
!> position tolerance of a master face follows that face,
!>   u_j(slave) - sum_i N_i(t) u_j(master node i) = 0,  j = 1, 2,
!> with t the position of the node's projection on the face and N_i the
!> face's shape functions (2- or 3-node edges). The equations join the
!> model's others (equation_t, the form of *EQUATION), which the analysis
!> imposes. Here because the projection onto a face (contact_geometry)
!> belongs to the contact layer.
!>
!> As CalculiX does: the default tolerance is 2.5 % of the typical face
!> size (here the master's mean chord length), and the projection must
!> fall on the face or beyond its ends by at most that default; a slave
!> node found on no face is not tied (a warning counts them); a tied node
!> is moved onto the face (ADJUST=NO keeps it); a dof of a slave node
!> that is prescribed (*BOUNDARY in the model data or in the first step)
!> or already the dependent dof of an equation is not tied (a warning).
!> A slave node that is itself a node of the master surface is not tied.
!>
!> TYPE=SURFACE TO SURFACE (tie_t%mortar): the weights are the mortar
!> integrals of contact_mortar instead, M_jm / D_j with dual shape
!> functions (a mortar tie): the same form of equation, one per dof of a
!> slave node, and a uniform stress passes through non-matching meshes.
module tie_constraints
  use kinds, only: dp
  use strings, only: itoa, rtoa
  use messages, only: warn
  use model, only: model_t, tie_t, equation_t, node_label
  use contact_geometry, only: edge_t, get_edge, project_to_edge, edge_at, edge_weights, edge_length
  use contact_mortar, only: mortar_t, mortar_integrals
  use edge_tree, only: edge_tree_t, boxes_tree, tree_candidates
  implicit none
  private
  public :: tie_surfaces

  !> The default tolerance as a fraction of the mean master chord length.
  real(dp), parameter :: default_fraction = 0.025_dp
  !> Node ids listed in a warning, at most.
  integer, parameter :: max_listed = 10
  !> TYPE=SURFACE TO SURFACE: a tied node whose covered dual weight is below
  !> this share of its whole int N_j da takes the node-to-face equation.
  real(dp), parameter :: min_mortar_cover = 0.1_dp

  !> Where a slave node lands on the master surface.
  type :: landing_t
    integer :: face = 0             ! index into the master's faces, 0: none
    real(dp) :: t = 0.0_dp          ! position on the face, in [0, 1]
    real(dp) :: x(2) = 0.0_dp       ! the point of the face
  end type landing_t

contains

  !> Purpose: the equations of every *TIE of m, appended to m%equations
  !> in the order of the ties; tied slave nodes moved onto the master
  !> unless ADJUST=NO; m%ties(k)%tied and %untied set. Call once, after
  !> the deck is read and before the analysis.
  subroutine tie_surfaces(m)
    type(model_t), intent(inout) :: m
    logical, allocatable :: blocked(:, :), dependent(:, :)
    integer :: k
    if (size(m%ties) == 0) return
    call blocked_dofs(m, blocked, dependent)
    do k = 1, size(m%ties)
      call tie_one(m, m%ties(k), blocked, dependent)
      call warn_if_in_contact(m, m%ties(k))
    end do
  end subroutine tie_surfaces

  !> A tie between the two surfaces of a contact pair glues what the pair
  !> would let open: its contact elements then carry nothing, and their
  !> status may flip on round-off; said, since it is rarely meant.
  subroutine warn_if_in_contact(m, t)
    type(model_t), intent(in) :: m
    type(tie_t), intent(in) :: t
    integer :: ip
    do ip = 1, size(m%pairs)
      associate(c => m%pairs(ip))
        if ((c%slave_surface == t%slave_surface .and. c%master_surface == t%master_surface) .or. &
            (c%slave_surface == t%master_surface .and. c%master_surface == t%slave_surface)) then
          call warn('*TIE ' // trim(t%name) // ' ties the two surfaces of a *CONTACT PAIR: the tie holds ' // &
                    'them together and the pair''s contact carries nothing')
          return
        end if
      end associate
    end do
  end subroutine warn_if_in_contact

  !> Dofs a tie may not make dependent: prescribed in the model data or
  !> in the first step (blocked), or dependent in an equation already.
  subroutine blocked_dofs(m, blocked, dependent)
    type(model_t), intent(in) :: m
    logical, allocatable, intent(out) :: blocked(:, :), dependent(:, :)
    integer :: j
    allocate(blocked(2, m%nn), dependent(2, m%nn))
    blocked = .false.
    dependent = .false.
    do j = 1, size(m%model_bcs)
      ! (a coupled deck's model-data temperatures, dof 11, tie nothing)
      if (m%model_bcs(j)%dof > size(blocked, 1)) cycle
      blocked(m%model_bcs(j)%dof, m%model_bcs(j)%node) = .true.
    end do
    if (size(m%steps) > 0) then
      do j = 1, size(m%steps(1)%bcs)
        blocked(m%steps(1)%bcs(j)%dof, m%steps(1)%bcs(j)%node) = .true.
      end do
    end if
    do j = 1, size(m%equations)
      dependent(m%equations(j)%dof(1), m%equations(j)%node(1)) = .true.
    end do
  end subroutine blocked_dofs

  !> One tie: its slave nodes projected, moved and tied; warnings for
  !> the nodes and dofs left untied.
  subroutine tie_one(m, t, blocked, dependent)
    type(model_t), intent(inout) :: m
    type(tie_t), intent(inout) :: t
    logical, intent(in) :: blocked(:, :)
    logical, intent(inout) :: dependent(:, :)
    type(edge_t), allocatable :: faces(:)
    type(equation_t), allocatable :: eqs(:)
    type(landing_t) :: l
    type(landing_t), allocatable :: lands(:)
    type(mortar_t) :: mo
    logical, allocatable :: on_master(:)
    integer, allocatable :: missed(:), skipped(:)
    real(dp) :: tol_face, tol
    integer :: k, s, j, neq, nmissed, nskipped, nshared
    type(edge_tree_t) :: tree
    call master_faces(m, t, faces, on_master, tol_face)
    tol = t%tolerance
    if (tol <= 0.0_dp) tol = tol_face
    call reach_tree(faces, tol, tol_face, tree)
    associate(slaves => m%surfaces(t%slave_surface)%nodes)
      allocate(eqs(2 * size(slaves)), missed(size(slaves)), skipped(size(slaves)), lands(size(slaves)))
      neq = 0
      nmissed = 0
      nskipped = 0
      nshared = 0
      do k = 1, size(slaves)
        s = slaves(k)
        if (on_master(s)) then
          nshared = nshared + 1
          cycle
        end if
        l = landing(faces, m%x(:, s), tol, tol_face, tree)
        if (l%face == 0) then
          nmissed = nmissed + 1
          missed(nmissed) = s
          cycle
        end if
        if (t%adjust) then
          t%largest_move = max(t%largest_move, norm2(l%x - m%x(:, s)))
          m%x(:, s) = l%x
        end if
        t%tied = t%tied + 1
        lands(k) = l
      end do
      ! the mortar integrals on the adjusted slave surface
      if (t%mortar) call mortar_integrals(m, m%x, m%surfaces(t%slave_surface), m%surfaces(t%master_surface), &
                                          tol, mo)
      do k = 1, size(slaves)
        s = slaves(k)
        if (lands(k)%face == 0) cycle
        do j = 1, 2
          if (blocked(j, s) .or. dependent(j, s)) then
            if (nskipped == 0) then
              nskipped = 1
              skipped(1) = s
            else if (skipped(nskipped) /= s) then
              nskipped = nskipped + 1
              skipped(nskipped) = s
            end if
            cycle
          end if
          neq = neq + 1
          eqs(neq) = tie_equation(faces(lands(k)%face), lands(k)%t, s, j, t)
          ! (two tests: Fortran does not skip the second, and mo is only
          ! made for a mortar tie)
          if (t%mortar) then
            if (mortar_covered(mo, k)) eqs(neq) = mortar_equation(mo, k, s, j, t)
          end if
          dependent(j, s) = .true.
        end do
      end do
    end associate
    t%untied = nmissed + nshared
    m%equations = [m%equations, eqs(1:neq)]
    call report(m, t, missed(1:nmissed), skipped(1:nskipped), nshared, tol)
  end subroutine tie_one

  !> The master surface's faces in the current coordinates, which nodes
  !> are on them, and the default tolerance (default_fraction of their
  !> mean chord length).
  subroutine master_faces(m, t, faces, on_master, tol_face)
    type(model_t), intent(in) :: m
    type(tie_t), intent(in) :: t
    type(edge_t), allocatable, intent(out) :: faces(:)
    logical, allocatable, intent(out) :: on_master(:)
    real(dp), intent(out) :: tol_face
    integer :: j
    associate(ms => m%surfaces(t%master_surface))
      allocate(faces(size(ms%elem)), on_master(m%nn))
      on_master = .false.
      tol_face = 0.0_dp
      do j = 1, size(ms%elem)
        faces(j) = get_edge(m, m%x, ms%elem(j), ms%edge(j))
        on_master(faces(j)%node(1:faces(j)%nn)) = .true.
        tol_face = tol_face + edge_length(faces(j))
      end do
      tol_face = default_fraction * tol_face / max(size(ms%elem), 1)
    end associate
  end subroutine master_faces

  !> The face a slave node at xs is tied to: among the faces whose
  !> orthogonal projection of xs lies within `tol` of xs (normal
  !> distance) and on the face or at most tol_face beyond its ends, the
  !> one whose nearest point (the projection clamped to the face) is
  !> closest. face = 0 if there is none.
  !> Only the faces whose reach (below) holds xs are looked at: with the
  !> tree of reach_tree, those whose box holds it, in the same order.
  function landing(faces, xs, tol, tol_face, tree) result(l)
    type(edge_t), intent(in) :: faces(:)
    real(dp), intent(in) :: xs(2), tol, tol_face
    type(edge_tree_t), intent(in) :: tree
    type(landing_t) :: l
    real(dp) :: t, nvec(2), d, len, tc, p(2), dpdt(2), best
    integer, allocatable :: cand(:)
    integer :: i, j, ncand
    best = huge(1.0_dp)
    if (tree%finite .and. tree%n == size(faces)) then
      call tree_candidates(tree, xs, 0.0_dp, cand, ncand)
    else
      cand = [(j, j = 1, size(faces))]
      ncand = size(faces)
    end if
    do i = 1, ncand
      j = cand(i)
      associate(f => faces(j))
        len = edge_length(f)
        ! far from every node of the face: skip the projection
        if (norm2(xs - f%x(:, 1)) > face_reach(f, tol, tol_face)) cycle
        call project_to_edge(f, xs, t, nvec, d)
        if (abs(d) > tol) cycle
        if (t * len < -tol_face .or. (t - 1.0_dp) * len > tol_face) cycle
        tc = min(1.0_dp, max(0.0_dp, t))
        call edge_at(f, tc, p, dpdt)
        if (norm2(xs - p) >= best) cycle
        best = norm2(xs - p)
        l = landing_t(face=j, t=tc, x=p)
      end associate
    end do
  end function landing

  !> Purpose: the distance from face f's first node within which landing
  !> projects a node onto f: to its farthest node, plus tol and tol_face.
  pure real(dp) function face_reach(f, tol, tol_face)
    type(edge_t), intent(in) :: f
    real(dp), intent(in) :: tol, tol_face
    face_reach = maxval(norm2(f%x(:, 1:f%nn) - spread(f%x(:, 1), 2, f%nn), dim=1)) + tol + tol_face
  end function face_reach

  !> Purpose: the tree of the faces' reaches (a square about each face's
  !> first node holding the disc of radius face_reach, widened for
  !> rounding), so that landing looks only at the faces near a node
  !> rather than at all (a tie of n nodes on n faces was O(n^2)).
  subroutine reach_tree(faces, tol, tol_face, tree)
    type(edge_t), intent(in) :: faces(:)
    real(dp), intent(in) :: tol, tol_face
    type(edge_tree_t), intent(out) :: tree
    real(dp), allocatable :: box(:, :)
    real(dp) :: r
    integer :: j
    allocate(box(4, size(faces)))
    do j = 1, size(faces)
      r = face_reach(faces(j), tol, tol_face)
      r = r + 1.0e-12_dp * (r + maxval(abs(faces(j)%x(:, 1))))
      box(:, j) = [faces(j)%x(:, 1) - r, faces(j)%x(:, 1) + r]
    end do
    call boxes_tree(box, tree)
  end subroutine reach_tree

  !> u_j(s) - sum_i N_i(t) u_j(node i of the face) = 0; master terms with
  !> a zero weight (the node exactly at a corner) are left out.
  function tie_equation(f, t, s, j, tie) result(eq)
    type(edge_t), intent(in) :: f
    real(dp), intent(in) :: t
    integer, intent(in) :: s, j
    type(tie_t), intent(in) :: tie
    type(equation_t) :: eq
    real(dp) :: w(3)
    integer :: i
    w = edge_weights(f, t)
    eq%node = [s]
    eq%dof = [j]
    eq%coef = [1.0_dp]
    do i = 1, f%nn
      if (w(i) == 0.0_dp) cycle
      eq%node = [eq%node, f%node(i)]
      eq%dof = [eq%dof, j]
      eq%coef = [eq%coef, -w(i)]
    end do
    eq%src = tie%src
    eq%origin = '*TIE ' // trim(tie%name)
  end function tie_equation

  !> Does the mortar integral of slave node k (in the surface's order)
  !> cover enough of its support (min_mortar_cover)?
  pure logical function mortar_covered(mo, k)
    type(mortar_t), intent(in) :: mo
    integer, intent(in) :: k
    mortar_covered = mo%nm(k) > 0 .and. mo%d(k) > min_mortar_cover * mo%full(k)
  end function mortar_covered

  !> TYPE=SURFACE TO SURFACE (mortar tie): D_j u_j(s) = sum_m M_jm u_j(m)
  !> with the dual weights of contact_mortar (the dual shape functions make
  !> the slave side one node), so u_j(s) - sum_m (M_jm / D_j) u_j(m) = 0:
  !> the tie of the weak continuity int Phi_s (u_slave - u_master) da = 0,
  !> whose forces on the master are the consistent ones of the slave
  !> tractions (a uniform stress passes through any two meshes). Master
  !> terms with a zero weight are left out.
  function mortar_equation(mo, k, s, j, tie) result(eq)
    type(mortar_t), intent(in) :: mo
    integer, intent(in) :: k, s, j
    type(tie_t), intent(in) :: tie
    type(equation_t) :: eq
    integer :: i
    eq%node = [s]
    eq%dof = [j]
    eq%coef = [1.0_dp]
    do i = 1, mo%nm(k)
      if (mo%mval(i, k) == 0.0_dp .or. mo%mnode(i, k) == s) cycle
      eq%node = [eq%node, mo%mnode(i, k)]
      eq%dof = [eq%dof, j]
      eq%coef = [eq%coef, -mo%mval(i, k) / mo%d(k)]
    end do
    eq%src = tie%src
    eq%origin = '*TIE ' // trim(tie%name)
  end function mortar_equation

  !> Warnings for the slave nodes not tied and the dofs left free.
  subroutine report(m, t, missed, skipped, nshared, tol)
    type(model_t), intent(in) :: m
    type(tie_t), intent(in) :: t
    integer, intent(in) :: missed(:), skipped(:), nshared
    real(dp), intent(in) :: tol
    if (size(missed) > 0) call warn('*TIE ' // trim(t%name) // ': ' // itoa(size(missed)) // &
      ' slave node(s) not tied: no master face within the position tolerance ' // rtoa(tol, 3) // &
      ' (nodes' // id_list(m, missed) // ')')
    if (size(skipped) > 0) call warn('*TIE ' // trim(t%name) // ': ' // itoa(size(skipped)) // &
      ' slave node(s) with a dof prescribed by *BOUNDARY or dependent in another equation: that dof ' // &
      'is not tied (nodes' // id_list(m, skipped) // ')')
    if (nshared > 0) call warn('*TIE ' // trim(t%name) // ': ' // itoa(nshared) // &
      ' slave node(s) belong to the master surface too and are not tied')
    if (t%tied == 0) call warn('*TIE ' // trim(t%name) // ': no slave node is tied')
  end subroutine report

  !> " id id ..." of the first max_listed nodes, and "..." if there are more.
  function id_list(m, nodes) result(s)
    type(model_t), intent(in) :: m
    integer, intent(in) :: nodes(:)
    character(len=:), allocatable :: s
    integer :: k
    s = ''
    do k = 1, min(size(nodes), max_listed)
      s = s // ' ' // node_label(m, nodes(k))
    end do
    if (size(nodes) > max_listed) s = s // ' ...'
  end function id_list
end module tie_constraints
