!> Material and property cards: *MATERIAL, *ELASTIC, *EXPANSION,
!> *HYPERELASTIC, *PLASTIC, *DEFORMATION PLASTICITY, *SOLID SECTION,
!> *SPRING, *MASS, and *INITIAL CONDITIONS, TYPE=STRESS (a property of the
!> elements).
submodule (deck_parser) deck_material_cards
  use kinds, only: dp
  use strings, only: split_fields, to_upper, field_t, itoa, rtoa
  use deck_input, only: param_value, has_param, deck_warning
  use deck_cursor, only: line_text, err, next_data, require_data, no_data, allow_params, required_param, &
                         name_param, get_real, get_int, is_int, need_elset, param_real, warn_empty_set, elem_ref, &
                         defined_name, placed, instance_index
  use element_catalogue, only: catalogue, max_ip, state_plane_stress, state_plane_strain, state_axisymmetric, &
                               shape_spring1, shape_spring2, is_spring_shape, shape_mass
  use model, only: material_t, section_t, find_name, elem_label, law_elastic, law_neo_hooke, law_mooney_rivlin, &
                   max_yield, orientation_t, orient_rectangular, orient_cylindrical, elastic_iso, elastic_ortho, &
                   elastic_aniso, is_truss, law_deformation_plasticity, is_continuum
  use small_matrices, only: inv3
  use model_growth, only: grow
  implicit none

contains

  !> Purpose: *MATERIAL, NAME=: opens a material; the cards that follow
  !> (*ELASTIC) describe it. The material may be named by a section before
  !> it is defined (checked once the whole deck is read).
  module subroutine read_material(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    character(len=:), allocatable :: name
    call allow_params(p, kw, 'NAME')
    name = name_param(p, kw, 'NAME')
    if (find_name(m%materials(1:p%nmat)%name, name) > 0) call err(p, 'duplicate material ' // name)
    call no_data(p, kw)
    call grow(m%materials, p%nmat + 1)
    p%nmat = p%nmat + 1
    m%materials(p%nmat) = material_t(name=name)
    m%materials(p%nmat)%src%line = p%i
    p%material = p%nmat
  end subroutine read_material

  !> TYPE= of *ELASTIC naming the isotropic law: ISOTROPIC or a shortening
  !> of it to at least ISO.
  pure logical function is_isotropic(v)
    character(len=*), intent(in) :: v
    is_isotropic = len(v) >= 3 .and. len(v) <= 9
    if (is_isotropic) is_isotropic = v == 'ISOTROPIC'(1:len(v))
  end function is_isotropic

  !> Purpose: *ELASTIC of the current material. TYPE=ISOTROPIC (the
  !> default; ISO as CalculiX reads it, comparing the first three
  !> letters): `E, nu`, one data line. TYPE=ORTHO (ORTHOTROPIC),
  !> ENGINEERING CONSTANTS and ANISO (ANISOTROPIC): read_anisotropic.
  !> Temperature dependence (a second set of lines) is not implemented.
  module subroutine read_elastic(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    character(len=:), allocatable :: t
    integer :: n
    call allow_params(p, kw, 'TYPE')
    if (p%material == 0) call err(p, '*ELASTIC outside a *MATERIAL')
    t = 'ISOTROPIC'
    if (has_param(kw, 'TYPE')) t = to_upper(param_value(kw, 'TYPE'))
    if (.not. is_isotropic(t)) then
      call read_anisotropic(p, m, t)
      return
    end if
    call require_data(p, 'E, nu')
    call split_fields(line_text(p), f, n)
    if (n < 2) call err(p, '*ELASTIC data line needs: E, nu')
    if (n > 3) call err(p, 'temperature-dependent *ELASTIC data is not implemented')
    associate(mat => m%materials(p%material))
      mat%e = get_real(p, f(1), 'Young''s modulus')
      mat%nu = get_real(p, f(2), 'Poisson''s ratio')
      if (mat%e <= 0.0_dp) call err(p, 'Young''s modulus must be positive')
      if (mat%nu <= -1.0_dp .or. mat%nu >= 0.5_dp) call err(p, 'Poisson''s ratio must lie in (-1, 0.5)')
      mat%has_elastic = .true.
      mat%elastic_type = elastic_iso
    end associate
    if (next_data(p)) call err(p, 'temperature-dependent *ELASTIC data is not implemented')
  end subroutine read_elastic

  !> Purpose: *ELASTIC, TYPE=t for t ORTHO (or ORTHOTROPIC: D1111, D1122,
  !> D2222, D1133, D2233, D3333, D1212, D1313, D2323), ENGINEERING
  !> CONSTANTS (E1, E2, E3, nu12, nu13, nu23, G12, G13, G23) or ANISO (or
  !> ANISOTROPIC: the 21 Dijkl, aniso_stiffness), each then an
  !> optional temperature, eight to a line as CalculiX reads them. The
  !> stiffness must be positive definite. The material keeps it (c6) and,
  !> for contact penalties and hourglass control, the isotropic E and nu
  !> of its mean compliance (model's material_t).
  subroutine read_anisotropic(p, m, t)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    character(len=*), intent(in) :: t
    real(dp) :: v(21), c(6, 6)
    logical :: ok
    associate(mat => m%materials(p%material))
      if (is_prefix(t, 'ORTHOTROPIC', 5)) then
        call read_constants(p, 9, v)
        c = ortho_stiffness(v(1:9))
        mat%elastic_type = elastic_ortho
      else if (t == 'ENGINEERING CONSTANTS' .or. t == 'ENGINEERINGCONSTANTS') then
        call read_constants(p, 9, v)
        if (.not. all(v([1, 2, 3, 7, 8, 9]) > 0.0_dp)) call err(p, 'the moduli E1, E2, E3, G12, G13, G23 ' // &
                                                                 'must be positive')
        call engineering_stiffness(v(1:9), c, ok)
        if (.not. ok) call err(p, 'the Poisson''s ratios give no positive definite compliance (|nu_ij| < ' // &
                               'sqrt(Ei / Ej) and 1 - nu12 nu21 - nu23 nu32 - nu13 nu31 - 2 nu21 nu32 nu13 > 0)')
        mat%elastic_type = elastic_ortho
      else if (is_prefix(t, 'ANISOTROPIC', 5)) then
        call read_constants(p, 21, v)
        c = aniso_stiffness(v)
        mat%elastic_type = elastic_aniso
      else
        call err(p, 'TYPE=' // t // ' is not implemented on *ELASTIC: ISOTROPIC, ORTHO, ENGINEERING ' // &
                 'CONSTANTS and ANISO are')
      end if
      if (.not. is_positive_definite(c)) call err(p, 'the *ELASTIC, TYPE=' // t // ' stiffness is not ' // &
                                                 'positive definite (no stable material)')
      mat%c6 = c
      call mean_isotropic(c, mat%e, mat%nu)
      mat%has_elastic = .true.
    end associate
  end subroutine read_anisotropic

  !> Purpose: 6x6 stiffness of *ELASTIC, TYPE=ORTHO from its nine
  !> constants in CalculiX's order D1111, D1122, D2222, D1133, D2233,
  !> D3333, D1212, D1313, D2323.
  pure function ortho_stiffness(dc) result(c)
    real(dp), intent(in) :: dc(9)
    real(dp) :: c(6, 6)
    c = 0.0_dp
    c(1, 1) = dc(1)
    c(1, 2) = dc(2)
    c(2, 2) = dc(3)
    c(1, 3) = dc(4)
    c(2, 3) = dc(5)
    c(3, 3) = dc(6)
    c(4, 4) = dc(7)
    c(5, 5) = dc(8)
    c(6, 6) = dc(9)
    call mirror(c)
  end function ortho_stiffness

  !> Purpose: 6x6 stiffness of *ELASTIC, TYPE=ENGINEERING CONSTANTS,
  !> ec = (E1, E2, E3, nu12, nu13, nu23, G12, G13, G23): the inverse of the
  !> compliance S11 = 1/E1, S12 = -nu12/E1, S13 = -nu13/E1, S22 = 1/E2,
  !> S23 = -nu23/E2, S33 = 1/E3, S44 = 1/G12, S55 = 1/G13, S66 = 1/G23
  !> (Jones 1999, eq. 2.61; nu_ij = -eps_j / eps_i under s_i). ok is false
  !> where the compliance is not positive definite (no stiffness).
  pure subroutine engineering_stiffness(ec, c, ok)
    real(dp), intent(in) :: ec(9)
    real(dp), intent(out) :: c(6, 6)
    logical, intent(out) :: ok
    real(dp) :: s(3, 3)
    c = 0.0_dp
    ok = all(ec([1, 2, 3, 7, 8, 9]) > 0.0_dp)
    if (.not. ok) return
    s = reshape([1.0_dp / ec(1), -ec(4) / ec(1), -ec(5) / ec(1), &
                 -ec(4) / ec(1), 1.0_dp / ec(2), -ec(6) / ec(2), &
                 -ec(5) / ec(1), -ec(6) / ec(2), 1.0_dp / ec(3)], [3, 3])
    ok = is_positive_definite(s)
    if (.not. ok) return
    c(1:3, 1:3) = inv3(s)
    c(1:3, 1:3) = 0.5_dp * (c(1:3, 1:3) + transpose(c(1:3, 1:3)))
    c(4, 4) = ec(7)
    c(5, 5) = ec(8)
    c(6, 6) = ec(9)
  end subroutine engineering_stiffness

  !> Purpose: 6x6 stiffness of *ELASTIC, TYPE=ANISO from its 21 constants
  !> in CalculiX's (and Abaqus's) order, the upper triangle by columns:
  !> D1111, D1122, D2222, D1133, D2233, D3333, D1112, D2212, D3312, D1212,
  !> D1113, D2213, D3313, D1213, D1313, D1123, D2223, D3323, D1223, D1323,
  !> D2323.
  pure function aniso_stiffness(dc) result(c)
    real(dp), intent(in) :: dc(21)
    real(dp) :: c(6, 6)
    integer :: i, j, k
    c = 0.0_dp
    k = 0
    do j = 1, 6
      do i = 1, j
        k = k + 1
        c(i, j) = dc(k)
      end do
    end do
    call mirror(c)
  end function aniso_stiffness

  !> Purpose: copy the upper triangle of c to its lower one.
  pure subroutine mirror(c)
    real(dp), intent(inout) :: c(6, 6)
    integer :: j
    do j = 1, 5
      c(j + 1:6, j) = c(j, j + 1:6)
    end do
  end subroutine mirror

  !> Purpose: is the symmetric 3x3 or 6x6 matrix a positive definite
  !> (Cholesky without breakdown; a relative pivot floor of 1e-12)?
  pure logical function is_positive_definite(a)
    real(dp), intent(in) :: a(:, :)
    real(dp) :: l(size(a, 1), size(a, 1)), piv, scale
    integer :: j, n
    n = size(a, 1)
    l = 0.0_dp
    scale = maxval(abs([(a(j, j), j = 1, n)]))
    is_positive_definite = scale > 0.0_dp .and. scale <= huge(1.0_dp)
    do j = 1, n
      if (.not. is_positive_definite) return
      piv = a(j, j) - dot_product(l(j, 1:j - 1), l(j, 1:j - 1))
      is_positive_definite = piv > 1e-12_dp * scale
      if (.not. is_positive_definite) return
      l(j, j) = sqrt(piv)
      l(j + 1:n, j) = (a(j + 1:n, j) - matmul(l(j + 1:n, 1:j - 1), l(j, 1:j - 1))) / l(j, j)
    end do
  end function is_positive_definite

  !> Is t a shortening of word to at least nmin letters?
  pure logical function is_prefix(t, word, nmin)
    character(len=*), intent(in) :: t, word
    integer, intent(in) :: nmin
    is_prefix = len(t) >= nmin .and. len(t) <= len(word)
    if (is_prefix) is_prefix = t == word(1:len(t))
  end function is_prefix

  !> Purpose: nreq constants v(1:nreq) of *ELASTIC from as many data lines
  !> as they fill (CalculiX: eight to a line), and after the last one an
  !> optional temperature (read, not used: one temperature only). A
  !> further data line is a temperature-dependent table: an error.
  subroutine read_constants(p, nreq, v)
    type(parser_t), intent(inout) :: p
    integer, intent(in) :: nreq
    real(dp), intent(out) :: v(:)
    type(field_t), allocatable :: f(:)
    integer :: n, got, k
    real(dp) :: temperature
    v = 0.0_dp
    got = 0
    do while (got < nreq)
      call require_data(p, itoa(nreq) // ' elastic constants, eight to a line')
      call split_fields(line_text(p), f, n)
      if (got + n > nreq + 1) call err(p, 'too many constants on *ELASTIC''s line: ' // itoa(nreq) // &
                                       ' and a temperature in all, eight to a line')
      do k = 1, min(n, nreq - got)
        v(got + k) = get_real(p, f(k), 'elastic constant ' // itoa(got + k))
      end do
      if (got + n == nreq + 1) temperature = get_real(p, f(n), 'temperature')
      got = got + n
    end do
    if (next_data(p)) call err(p, 'temperature-dependent *ELASTIC data is not implemented')
  end subroutine read_constants

  !> Purpose: the isotropic E and nu of the mean compliance of stiffness c
  !> (3 / (S11 + S22 + S33) and -(S12 + S13 + S23) / (S11 + S22 + S33), S
  !> = c^-1; exact for an isotropic c), nu kept in [-0.9, 0.49] for the
  !> isotropic formulas that take it (hourglass control).
  subroutine mean_isotropic(c, e, nu)
    real(dp), intent(in) :: c(6, 6)
    real(dp), intent(out) :: e, nu
    real(dp) :: s(6, 6), tr
    s = inverse6(c)
    tr = s(1, 1) + s(2, 2) + s(3, 3)
    e = 3.0_dp / tr
    nu = min(0.49_dp, max(-0.9_dp, -(s(1, 2) + s(1, 3) + s(2, 3)) / tr))
  end subroutine mean_isotropic

  !> Purpose: inverse of a positive definite 6x6 matrix (Gauss-Jordan,
  !> no pivoting needed for positive definite matrices).
  pure function inverse6(a) result(b)
    real(dp), intent(in) :: a(6, 6)
    real(dp) :: b(6, 6), w(6, 12)
    integer :: i, k
    w = 0.0_dp
    w(:, 1:6) = a
    do i = 1, 6
      w(i, 6 + i) = 1.0_dp
    end do
    do k = 1, 6
      w(k, :) = w(k, :) / w(k, k)
      do i = 1, 6
        if (i /= k) w(i, :) = w(i, :) - w(i, k) * w(k, :)
      end do
    end do
    b = w(:, 7:12)
  end function inverse6

  !> Purpose: *ORIENTATION, NAME=, SYSTEM= (RECTANGULAR, the default, or
  !> CYLINDRICAL; DEFINITION=COORDINATES only): the points a, b on its
  !> first data line (model's orientation_t) and, optionally, a second
  !> line `axis, angle`: an extra rotation by angle (degrees) about local
  !> axis 1, 2 or 3. The sections that name it (ORIENTATION=) are bound
  !> to it once the deck is read (check_orientations). Inside a *PART (read
  !> for each instance) it is the instance's: named INSTANCE.NAME as the
  !> part's sets, and turned with the instance (place_orientation).
  module subroutine read_orientation(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    type(orientation_t) :: o
    type(orientation_t), allocatable :: tmp(:)
    character(len=:), allocatable :: sys
    integer :: n, k
    call allow_params(p, kw, 'NAME,SYSTEM,DEFINITION')
    if (.not. allocated(m%orientations)) allocate(m%orientations(0))
    o%name = defined_name(p, m, name_param(p, kw, 'NAME'))
    if (find_name(m%orientations%name, o%name) > 0) call err(p, 'duplicate orientation ' // trim(o%name))
    o%src%line = p%i
    sys = 'RECTANGULAR'
    if (has_param(kw, 'SYSTEM')) sys = to_upper(param_value(kw, 'SYSTEM'))
    if (is_prefix(sys, 'RECTANGULAR', 1)) then
      o%system = orient_rectangular
    else if (is_prefix(sys, 'CYLINDRICAL', 1)) then
      o%system = orient_cylindrical
    else
      call err(p, 'SYSTEM=' // sys // ' is not implemented on *ORIENTATION: RECTANGULAR and CYLINDRICAL are')
    end if
    if (has_param(kw, 'DEFINITION')) then
      if (to_upper(param_value(kw, 'DEFINITION')) /= 'COORDINATES') call err(p, 'DEFINITION=' // &
          param_value(kw, 'DEFINITION') // ' is not implemented on *ORIENTATION: only COORDINATES is')
    end if
    call require_data(p, 'xa, ya, za, xb, yb, zb')
    call split_fields(line_text(p), f, n)
    if (n /= 6) call err(p, '*ORIENTATION''s first data line needs six coordinates: xa, ya, za, xb, yb, zb')
    do k = 1, 3
      o%a(k) = get_real(p, f(k), 'coordinate of point a')
      o%b(k) = get_real(p, f(k + 3), 'coordinate of point b')
    end do
    call check_points(p, o)
    if (next_data(p)) then
      call split_fields(line_text(p), f, n)
      if (n /= 2 .or. .not. is_int(f(1)%s)) call err(p, '*ORIENTATION''s second data line is: local axis ' // &
                                                      '(1, 2 or 3), rotation angle in degrees')
      o%axis = get_int(p, f(1), 'local axis')
      if (o%axis < 1 .or. o%axis > 3) call err(p, 'the local axis of the extra rotation must be 1, 2 or 3')
      o%angle = get_real(p, f(2), 'rotation angle')
      if (abs(o%angle) > 1e6_dp) call err(p, 'the rotation angle (degrees) is beyond 1e6')
    end if
    call place_orientation(p, m, o)
    allocate(tmp(size(m%orientations) + 1))
    tmp(1:size(m%orientations)) = m%orientations
    tmp(size(tmp)) = o
    call move_alloc(tmp, m%orientations)
  end subroutine read_orientation

  !> Purpose: an *ORIENTATION read for an instance of a part turns with
  !> it (Abaqus: a part's orientation is fixed in the part): a rectangular
  !> system's points are directions from the origin, turned by the
  !> instance's rotation (placed(a) - placed(0): the translation cancels);
  !> a cylindrical system's points lie on its axis, placed as the part's
  !> nodes. Outside an instance placed() leaves them as they are.
  subroutine place_orientation(p, m, o)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    type(orientation_t), intent(inout) :: o
    real(dp) :: zero(2)
    if (o%system == orient_cylindrical) then
      o%a(1:2) = placed(p, m, o%a(1:2))
      o%b(1:2) = placed(p, m, o%b(1:2))
    else
      zero = placed(p, m, [0.0_dp, 0.0_dp])
      o%a(1:2) = placed(p, m, o%a(1:2)) - zero
      o%b(1:2) = placed(p, m, o%b(1:2)) - zero
    end if
  end subroutine place_orientation

  !> Purpose: the points of an *ORIENTATION define axes: rectangular, a
  !> not zero and b not along a; cylindrical, b apart from a. Scales are
  !> the points' own, so that any unit of length is taken.
  subroutine check_points(p, o)
    type(parser_t), intent(in) :: p
    type(orientation_t), intent(in) :: o
    real(dp) :: axb(3), sc
    sc = max(norm2(o%a), norm2(o%b))
    if (o%system == orient_cylindrical) then
      if (.not. norm2(o%b - o%a) > 1e-12_dp * sc) call err(p, 'a cylindrical *ORIENTATION needs two ' // &
                                                           'distinct points a and b on its axis')
    else
      axb = [o%a(2) * o%b(3) - o%a(3) * o%b(2), o%a(3) * o%b(1) - o%a(1) * o%b(3), &
             o%a(1) * o%b(2) - o%a(2) * o%b(1)]
      if (.not. norm2(axb) > 1e-12_dp * sc**2) call err(p, 'a rectangular *ORIENTATION needs point a (on ' // &
          'local axis 1) apart from the origin and point b (in the local 1-2 plane) off the line of a')
    end if
  end subroutine check_points

  !> Purpose: once the deck is read (the sections' materials bound by
  !> check_model): each ORIENTATION= of a *SOLID SECTION names an
  !> *ORIENTATION, and an anisotropic material (*ELASTIC, TYPE=ORTHO,
  !> ENGINEERING CONSTANTS or ANISO) is elastic on continuum elements
  !> (St Venant-Kirchhoff under NLGEOM): plasticity, hyperelasticity and
  !> trusses are errors.
  module subroutine check_orientations(p, m)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    integer :: s, k, imat
    if (.not. allocated(m%orientations)) allocate(m%orientations(0))
    do s = 1, size(m%sections)
      if (m%sections(s)%spring .or. m%sections(s)%point_mass) cycle
      p%i = m%sections(s)%src%line
      if (len_trim(m%sections(s)%orientation_name) > 0) then
        m%sections(s)%orientation = find_name(m%orientations%name, m%sections(s)%orientation_name)
        ! a part's section may name an orientation of the model's own
        k = index(m%sections(s)%orientation_name, '.')
        if (m%sections(s)%orientation == 0 .and. k > 1) then
          if (instance_index(m, m%sections(s)%orientation_name(:k - 1)) > 0) m%sections(s)%orientation = &
            find_name(m%orientations%name, m%sections(s)%orientation_name(k + 1:))
        end if
        if (m%sections(s)%orientation == 0) call err(p, 'undefined orientation ' // &
                                                     trim(m%sections(s)%orientation_name))
      end if
      imat = m%sections(s)%material
      if (m%materials(imat)%elastic_type == elastic_iso) cycle
      do k = 1, size(m%elsets(m%sections(s)%elset)%items)
        if (is_truss(m, m%elsets(m%sections(s)%elset)%items(k))) call err(p, 'element ' // &
            elem_label(m, m%elsets(m%sections(s)%elset)%items(k)) // ' is a truss of anisotropic material ' // &
            trim(m%materials(imat)%name) // ': a truss takes an isotropic *ELASTIC')
      end do
      p%i = m%materials(imat)%src%line
      if (m%materials(imat)%nyield > 0 .or. m%materials(imat)%law /= law_elastic) call err(p, 'material ' // &
          trim(m%materials(imat)%name) // ': plasticity or hyperelasticity of an anisotropic material ' // &
          '(*ELASTIC, TYPE=' // 'ORTHO, ENGINEERING CONSTANTS or ANISO) is not implemented')
    end do
  end subroutine check_orientations

  !> Purpose: *HYPERELASTIC of the current material, with CalculiX's
  !> strain energy (its manual, *HYPERELASTIC) and constants:
  !>   NEO HOOKE                 U = C10 (I1bar - 3) + (J - 1)^2 / D1,
  !>                             data line `C10, D1[, temperature]`;
  !>   MOONEY-RIVLIN, POLYNOMIAL N=1 (the same energy)
  !>                             U = C10 (I1bar - 3) + C01 (I2bar - 3)
  !>                                 + (J - 1)^2 / D1,
  !>                             data line `C10, C01, D1[, temperature]`.
  !> CalculiX's default (no model named) is POLYNOMIAL N=1. Other models,
  !> N > 1 and temperature dependence (a second data line) stop at the
  !> line. D1 must not be negative; D1 = 0 (|D1| < 1e-10, incompressible:
  !> the element routines have no pressure unknown) is taken as CalculiX
  !> 2.20 does as 0.1 / (2 (C10 + C01)), with a warning at the line. The
  !> initial shear modulus 2 (C10 + C01) must be positive; the bulk
  !> modulus 2 / D1 at most 1e8 times the shear modulus, both at most
  !> 1e100. Like CalculiX, a hyperelastic material makes
  !> every step geometrically nonlinear (deck_model_checks).
  module subroutine read_hyperelastic(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    integer :: n, law, k, nmodels
    character(len=*), parameter :: others = 'ARRUDA-BOYCE,OGDEN,REDUCED POLYNOMIAL,REDUCEDPOLYNOMIAL,YEOH'
    call allow_params(p, kw, 'NEO HOOKE,NEOHOOKE,MOONEY-RIVLIN,POLYNOMIAL,N,' // others)
    if (p%material == 0) call err(p, '*HYPERELASTIC outside a *MATERIAL')
    do k = 1, kw%np
      if (index(',' // others // ',', ',' // kw%pname(k)%s // ',') > 0) call err(p, 'the hyperelastic model ' // &
        kw%pname(k)%s // ' is not implemented: NEO HOOKE, MOONEY-RIVLIN and POLYNOMIAL with N=1 are')
    end do
    nmodels = count([has_param(kw, 'NEO HOOKE') .or. has_param(kw, 'NEOHOOKE'), has_param(kw, 'MOONEY-RIVLIN'), &
                     has_param(kw, 'POLYNOMIAL')])
    if (nmodels > 1) call err(p, '*HYPERELASTIC names more than one model')
    if (has_param(kw, 'N')) then
      if (.not. is_int(param_value(kw, 'N'))) call err(p, 'N must be an integer')
      if (param_value(kw, 'N') /= '1') call err(p, 'only N=1 is implemented on *HYPERELASTIC (the strain ' // &
                                                   'energy of order 1: neo-Hooke and Mooney-Rivlin)')
      if (has_param(kw, 'NEO HOOKE') .or. has_param(kw, 'NEOHOOKE') .or. has_param(kw, 'MOONEY-RIVLIN')) &
        call err(p, 'N= is for the POLYNOMIAL model only')
    end if
    law = law_mooney_rivlin
    if (has_param(kw, 'NEO HOOKE') .or. has_param(kw, 'NEOHOOKE')) law = law_neo_hooke
    if (m%materials(p%material)%law /= law_elastic) call err(p, 'second *HYPERELASTIC in material ' // &
                                                             trim(m%materials(p%material)%name))
    if (m%materials(p%material)%nyield > 0) call err(p, 'plasticity of a hyperelastic material is not implemented')
    if (law == law_neo_hooke) then
      call require_data(p, 'C10, D1')
    else
      call require_data(p, 'C10, C01, D1')
    end if
    call split_fields(line_text(p), f, n)
    associate(mat => m%materials(p%material))
      if (law == law_neo_hooke) then
        if (n < 2) call err(p, '*HYPERELASTIC, NEO HOOKE data line needs: C10, D1')
        if (n > 3) call err(p, 'too many fields: *HYPERELASTIC, NEO HOOKE data line is C10, D1[, temperature]')
        mat%c10 = get_real(p, f(1), 'C10')
        mat%c01 = 0.0_dp
        mat%d1 = get_real(p, f(2), 'D1')
      else
        if (n < 3) call err(p, '*HYPERELASTIC, ' // trim(merge('POLYNOMIAL   ', 'MOONEY-RIVLIN', &
          has_param(kw, 'POLYNOMIAL'))) // ' data line needs: C10, C01, D1')
        if (n > 4) call err(p, 'too many fields: the data line is C10, C01, D1[, temperature]')
        mat%c10 = get_real(p, f(1), 'C10')
        mat%c01 = get_real(p, f(2), 'C01')
        mat%d1 = get_real(p, f(3), 'D1')
      end if
      if (.not. mat%c10 + mat%c01 > 0.0_dp) call err(p, 'the initial shear modulus 2 (C10 + C01) must be positive')
      ! CalculiX 2.20 (hyperelastics.f) replaces a zero compressibility
      ! (|D1| < 1e-10) by 0.1 / mu0, mu0 = 2 (C10 + C01): K = 2 / D1 = 20 mu0,
      ! Poisson's ratio 0.475 at the origin, with a warning; the elements
      ! have no pressure unknown for a truly incompressible material
      if (abs(mat%d1) < 1.0e-10_dp) then
        mat%d1 = 0.1_dp / (2.0_dp * (mat%c10 + mat%c01))
        call deck_warning(p%deck, p%i, 'D1 = 0 (incompressible) is replaced, as in CalculiX, by 0.1 / (2 (C10 ' // &
          '+ C01)) = ' // rtoa(mat%d1, 6) // ' (initial Poisson''s ratio 0.475): the elements have no pressure unknown')
      end if
      if (.not. mat%d1 > 0.0_dp) call err(p, 'D1 must not be negative (the volumetric energy (J - 1)^2 / D1 ' // &
        'would have no minimum)')
      if (mat%c10 < 0.0_dp .and. law == law_neo_hooke) call err(p, 'C10 must be positive')
      ! K / mu = 1 / (D1 (C10 + C01)): beyond 1e8 the volumetric stiffness
      ! drowns the shear stiffness in round-off; moduli beyond 1e100 overflow
      ! the energy's products
      if (abs(mat%c10) + abs(mat%c01) > 1.0e100_dp .or. 2.0_dp > 1.0e100_dp * mat%d1) call err(p, &
        'the hyperelastic moduli 2 (C10 + C01) and 2 / D1 must not exceed 1e100')
      if (1.0_dp > 1.0e8_dp * mat%d1 * (mat%c10 + mat%c01)) call err(p, 'the bulk modulus 2 / D1 is more ' // &
        'than 1e8 times the shear modulus 2 (C10 + C01): nearly incompressible beyond what double precision ' // &
        'resolves (rubber has 1e3 to 1e4)')
      mat%law = law
    end associate
    if (next_data(p)) call err(p, 'temperature-dependent *HYPERELASTIC data is not implemented')
  end subroutine read_hyperelastic

  !> Purpose: *PLASTIC (von Mises, HARDENING=ISOTROPIC, CalculiX's and
  !> Abaqus' default) of the current material: data lines `yield stress,
  !> equivalent plastic strain[, temperature]`, the hardening curve, the
  !> first at plastic strain 0 and the strains increasing (linear between
  !> the points, constant beyond the last, as CalculiX). Other hardening
  !> rules and temperature dependence (a temperature that changes from
  !> line to line) stop at the line.
  module subroutine read_plastic(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    integer :: n, k
    real(dp) :: temp0, temp
    call allow_params(p, kw, 'HARDENING')
    if (has_param(kw, 'HARDENING')) then
      if (to_upper(param_value(kw, 'HARDENING')) /= 'ISOTROPIC') call err(p, 'HARDENING=' // &
        to_upper(param_value(kw, 'HARDENING')) // ' is not implemented: only HARDENING=ISOTROPIC is')
    end if
    if (p%material == 0) call err(p, '*PLASTIC outside a *MATERIAL')
    associate(mat => m%materials(p%material))
      if (mat%nyield > 0) call err(p, 'second *PLASTIC in material ' // trim(mat%name))
      if (mat%law == law_deformation_plasticity) call err(p, '*PLASTIC in material ' // trim(mat%name) // &
                                                          ', which has *DEFORMATION PLASTICITY')
      if (mat%law /= law_elastic) call err(p, 'plasticity of a hyperelastic material is not implemented')
      call require_data(p, 'yield stress, equivalent plastic strain')
      k = 0
      temp0 = 0.0_dp
      do
        call split_fields(line_text(p), f, n)
        if (n < 1) call err(p, '*PLASTIC data line needs: yield stress, equivalent plastic strain')
        if (n > 3) call err(p, 'too many fields: *PLASTIC data line is yield stress, plastic strain[, temperature]')
        k = k + 1
        if (k > max_yield) call err(p, 'more than ' // itoa(max_yield) // ' points in the hardening curve')
        mat%yield(1, k) = get_real(p, f(1), 'yield stress')
        mat%yield(2, k) = 0.0_dp
        if (n >= 2) then
          if (len(f(2)%s) > 0) mat%yield(2, k) = get_real(p, f(2), 'equivalent plastic strain')
        end if
        temp = 0.0_dp
        if (n == 3) then
          if (len(f(3)%s) > 0) temp = get_real(p, f(3), 'temperature')
        end if
        if (k == 1) temp0 = temp
        if (temp /= temp0) call err(p, 'temperature-dependent *PLASTIC data is not implemented')
        if (.not. mat%yield(1, k) > 0.0_dp) call err(p, 'the yield stress must be positive')
        if (k == 1 .and. mat%yield(2, k) /= 0.0_dp) call err(p, 'the first point of the hardening curve must ' // &
                                                             'be at equivalent plastic strain 0')
        if (k > 1) then
          if (.not. mat%yield(2, k) > mat%yield(2, k - 1)) call err(p, 'the equivalent plastic strains of ' // &
            'the hardening curve must increase from line to line')
        end if
        if (.not. next_data(p)) exit
      end do
      mat%nyield = k
    end associate
  end subroutine read_plastic

  !> Purpose: *DEFORMATION PLASTICITY of the current material (Abaqus'
  !> and CalculiX's card): one data line `E, nu, sigma0, n, alpha[,
  !> temperature]`, the Ramberg-Osgood law eps = sig / E + alpha (sigma0 /
  !> E) (sig / sigma0)^n in uniaxial stress, J2 deformation theory in
  !> general (elements' deformation_plasticity). The card gives the
  !> elastic constants itself, so the material has no *ELASTIC, and no
  !> *HYPERELASTIC or *PLASTIC. E > 0, -1 < nu < 0.5, sigma0 > 0, n >= 1,
  !> alpha >= 0, E and sigma0 and E / sigma0 at most 1e100; temperature
  !> dependence (a second data line) stops there.
  !> The steps of a model with it are nonlinear (Newton) and, as in
  !> CalculiX (its reader of the card turns NLGEOM on), geometrically
  !> nonlinear from here on unless a step says NLGEOM=NO (then the
  !> small-strain law, as Abaqus without NLGEOM).
  module subroutine read_deformation_plasticity(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    integer :: n
    call allow_params(p, kw, '')
    if (p%material == 0) call err(p, '*DEFORMATION PLASTICITY outside a *MATERIAL')
    associate(mat => m%materials(p%material))
      if (mat%has_elastic) call err(p, 'material ' // trim(mat%name) // ' has *ELASTIC: *DEFORMATION ' // &
                                    'PLASTICITY gives E and nu itself')
      if (mat%law == law_deformation_plasticity) call err(p, 'second *DEFORMATION PLASTICITY in material ' // &
                                                          trim(mat%name))
      if (mat%law /= law_elastic .or. mat%nyield > 0) call err(p, '*DEFORMATION PLASTICITY of a material with ' // &
                                                               '*HYPERELASTIC or *PLASTIC')
      call require_data(p, 'E, nu, sigma0, n, alpha')
      call split_fields(line_text(p), f, n)
      if (n < 5) call err(p, '*DEFORMATION PLASTICITY data line needs: E, nu, sigma0, n, alpha')
      if (n > 6) call err(p, 'too many fields: *DEFORMATION PLASTICITY data line is E, nu, sigma0, n, ' // &
                          'alpha[, temperature]')
      mat%e = get_real(p, f(1), 'Young''s modulus')
      mat%nu = get_real(p, f(2), 'Poisson''s ratio')
      mat%ro_sigma0 = get_real(p, f(3), 'yield offset sigma0')
      mat%ro_n = get_real(p, f(4), 'exponent n')
      mat%ro_alpha = get_real(p, f(5), 'yield offset factor alpha')
      if (.not. mat%e > 0.0_dp) call err(p, 'Young''s modulus must be positive')
      if (mat%nu <= -1.0_dp .or. mat%nu >= 0.5_dp) call err(p, 'Poisson''s ratio must lie in (-1, 0.5)')
      if (.not. mat%ro_sigma0 > 0.0_dp) call err(p, 'the yield offset sigma0 must be positive')
      if (.not. mat%ro_n >= 1.0_dp) call err(p, 'the exponent n must be at least 1')
      if (.not. mat%ro_alpha >= 0.0_dp) call err(p, 'the yield offset factor alpha must not be negative')
      ! beyond these the law's powers overflow before any load is applied
      if (mat%e > 1.0e100_dp .or. mat%ro_sigma0 > 1.0e100_dp .or. mat%ro_sigma0 < 1.0e-100_dp * mat%e) &
        call err(p, 'E and sigma0 must not exceed 1e100, nor E / sigma0 1e100')
      mat%law = law_deformation_plasticity
    end associate
    p%nlgeom = .true.
    if (next_data(p)) call err(p, 'temperature-dependent *DEFORMATION PLASTICITY data is not implemented')
  end subroutine read_deformation_plasticity

  !> Purpose: *INITIAL CONDITIONS, TYPE=STRESS, CalculiX's data lines
  !> `element or elset, integration point, S11, S22, S33, S12[, S13, S23]`:
  !> the stress at that point of the element (cfe2d's rule: 1 to the
  !> element type's nip; a point beyond it is an error at the line), zero
  !> at the points not named. S13 and S23 must be zero (2D), the others at
  !> most 1e100 in magnitude (a load beyond overflows). Only
  !> continuum elements; a later line for the same point replaces it.
  module subroutine read_initial_stress(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    integer, allocatable :: elems(:)
    integer :: n, k, ip, e
    real(dp) :: s(6)
    call allow_params(p, kw, 'TYPE')
    if (.not. allocated(m%sig0)) then
      allocate(m%sig0(4, max_ip, m%ne))
      m%sig0 = 0.0_dp
    end if
    call require_data(p, 'element or elset, integration point, S11, S22, S33, S12')
    do
      call split_fields(line_text(p), f, n)
      if (n < 6) call err(p, '*INITIAL CONDITIONS, TYPE=STRESS data line needs: element or elset, ' // &
                          'integration point, S11, S22, S33, S12')
      if (n > 8) call err(p, 'too many fields: the data line is element or elset, integration point, S11, ' // &
                          'S22, S33, S12[, S13, S23]')
      ! an element number, INSTANCE.NUMBER (Abaqus/CAE decks), or an elset
      if (is_int(f(1)%s) .or. is_int(f(1)%s(index(f(1)%s, '.', back=.true.) + 1:))) then
        elems = [elem_ref(p, m, f(1), 'element')]
      else
        elems = m%elsets(need_elset(p, m, f(1)%s))%items
      end if
      ip = get_int(p, f(2), 'integration point')
      s = 0.0_dp
      do k = 3, n
        if (len(f(k)%s) > 0) s(k - 2) = get_real(p, f(k), 'stress component')
      end do
      if (s(5) /= 0.0_dp .or. s(6) /= 0.0_dp) call err(p, 'S13 and S23 must be zero in a 2D model')
      if (any(abs(s) > 1.0e100_dp)) call err(p, 'the stress components must not exceed 1e100 in magnitude')
      do k = 1, size(elems)
        e = elems(k)
        if (e > size(m%sig0, 3)) call err(p, 'element ' // elem_label(m, e) // ' is defined after the first ' // &
                                          '*INITIAL CONDITIONS, TYPE=STRESS')
        if (.not. is_continuum(m, e)) call err(p, 'element ' // elem_label(m, e) // ' is not a continuum ' // &
                                               'element: an initial stress is for continuum elements')
        if (ip < 1 .or. ip > catalogue(m%etype(e))%nip) call err(p, 'element ' // elem_label(m, e) // &
          ' has integration points 1 to ' // itoa(catalogue(m%etype(e))%nip) // ', not ' // itoa(ip))
        m%sig0(:, ip, e) = [s(1), s(2), s(4), s(3)]
      end do
      if (.not. next_data(p)) exit
    end do
  end subroutine read_initial_stress

  !> Purpose: *EXPANSION (isotropic): `alpha` of the current material,
  !> one data line; ZERO= (the temperature at which alpha was measured,
  !> default 0) is kept but cannot change a constant alpha's thermal strain
  !> alpha (T - T_initial). Temperature dependence is not implemented.
  module subroutine read_expansion(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    integer :: n
    call allow_params(p, kw, 'TYPE,ZERO')
    if (has_param(kw, 'TYPE')) then
      if (to_upper(param_value(kw, 'TYPE')) /= 'ISO') call err(p, 'only TYPE=ISO is implemented on *EXPANSION')
    end if
    if (p%material == 0) call err(p, '*EXPANSION outside a *MATERIAL')
    call require_data(p, 'alpha')
    call split_fields(line_text(p), f, n)
    if (n > 2) call err(p, 'temperature-dependent *EXPANSION data is not implemented')
    associate(mat => m%materials(p%material))
      mat%alpha = get_real(p, f(1), 'expansion coefficient')
      mat%alpha_zero = param_real(p, kw, 'ZERO', 0.0_dp)
      mat%has_expansion = .true.
    end associate
    if (next_data(p)) call err(p, 'temperature-dependent *EXPANSION data is not implemented')
  end subroutine read_expansion

  !> Purpose: *SOLID SECTION, ELSET=, MATERIAL=: the material and the
  !> thickness (data line, default 1) of the solid elements of a set.
  !> STATE= (cfe2d) gives their stress state whatever their type name says
  !> (plane strain from a gmsh mesh that writes CPS4); NODAL THICKNESS
  !> takes the thickness from *NODAL THICKNESS; OFFSET= (CalculiX: the
  !> mid-plane of its expanded plane-stress layer) cannot change a 2D
  !> answer, so a non-zero one is a warning.
  module subroutine read_section(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    integer :: n
    ! (CONTROLS= names an Abaqus *SECTION CONTROLS, read for CPS4R's
    ! hourglass control: deck_parser's read_hourglass_card)
    call allow_params(p, kw, 'ELSET,MATERIAL,STATE,OFFSET,NODAL THICKNESS,CONTROLS,ORIENTATION')
    call grow(m%sections, p%nsec + 1)
    p%nsec = p%nsec + 1
    m%sections(p%nsec) = section_t()
    associate(s => m%sections(p%nsec))
      s%elset = need_elset(p, m, required_param(p, kw, 'ELSET'))
      call warn_empty_set(p, size(m%elsets(s%elset)%items), 'element set', m%elsets(s%elset)%name, kw%name)
      s%material_name = name_param(p, kw, 'MATERIAL')
      s%src%line = p%i
      s%state = state_param(p, kw)
      s%nodal_thickness = has_param(kw, 'NODAL THICKNESS')
      if (has_param(kw, 'ORIENTATION')) s%orientation_name = defined_name(p, m, name_param(p, kw, 'ORIENTATION'))
      if (param_real(p, kw, 'OFFSET', 0.0_dp) /= 0.0_dp) call deck_warning(p%deck, p%i, 'OFFSET= moves the ' // &
          'mid-plane of a plane-stress layer out of the plane; it cannot change a 2D answer and is ignored')
      s%thickness = 1.0_dp
      if (next_data(p)) then
        call split_fields(line_text(p), f, n)
        if (len(f(1)%s) > 0) then
          s%thickness = get_real(p, f(1), 'thickness')
          s%thickness_given = .true.
        end if
        if (s%thickness <= 0.0_dp) call err(p, 'the section''s thickness must be positive (a truss'' cross-sectional area)')
        ! a subnormal thickness has lost its digits (and makes the contact
        ! areas subnormal, a pressure, force over area, infinite)
        if (s%thickness < tiny(1.0_dp)) call err(p, 'the section''s thickness (a truss'' cross-sectional ' // &
            'area) must be at least 2.2e-308 (a normal floating-point number)')
      end if
    end associate
  end subroutine read_section

  !> Purpose: *SPRING, ELSET=: the constant of the linear springs of a set
  !> (all of one type). SPRING1 and SPRING2 first take their dofs, one or
  !> two integers (CalculiX tells that line from the constant's by its
  !> integers); SPRINGA takes none (Abaqus writes a blank line there, which
  !> the deck reader drops). Then `constant[, , temperature]`, once.
  !> NONLINEAR, ORIENTATION and a constant per temperature are not
  !> implemented (errors at their line).
  module subroutine read_spring(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    integer :: n, es, shape, ndofs, k, line
    call allow_params(p, kw, 'ELSET,NONLINEAR,ORIENTATION')
    if (has_param(kw, 'NONLINEAR')) call err(p, 'NONLINEAR springs (a force-elongation curve) are not ' // &
        'implemented: cfe2d''s springs are linear (a constant on the line under *SPRING)')
    if (has_param(kw, 'ORIENTATION')) call err(p, 'ORIENTATION on *SPRING (dofs in a local system) is not ' // &
        'implemented: the dofs are the global x (1) and y (2)')
    es = need_elset(p, m, required_param(p, kw, 'ELSET'))
    shape = spring_set_shape(p, m, es)
    call grow(m%sections, p%nsec + 1)
    p%nsec = p%nsec + 1
    m%sections(p%nsec) = section_t(elset=es, spring=.true.)
    m%sections(p%nsec)%src%line = p%i
    ndofs = 0
    if (shape == shape_spring1) ndofs = 1
    if (shape == shape_spring2) ndofs = 2
    call require_data(p, 'spring constant')
    call split_fields(line_text(p), f, n)
    if (ndofs > 0) then
      if (n /= ndofs .or. .not. all([(is_int(f(k)%s), k = 1, n)])) then
        if (ndofs == 1) call err(p, 'SPRING1 needs its dof (an integer) on the line under *SPRING, then the ' // &
                                 'spring constant')
        call err(p, 'SPRING2 needs its two dofs (integers) on the line under *SPRING, then the spring constant')
      end if
      do k = 1, ndofs
        m%sections(p%nsec)%dof(k) = spring_dof(p, f(k))
      end do
      call require_data(p, 'spring constant')
      call split_fields(line_text(p), f, n)
    else if (all([(is_int(f(k)%s), k = 1, n)])) then
      ! integers only: a dof line, if a constant line follows it
      line = p%i
      if (next_data(p)) then
        p%i = line
        call err(p, 'a SPRINGA acts along the line between its nodes and takes no dof line')
      end if
    end if
    if (n > 3) call err(p, '*SPRING data line needs: spring constant[, , temperature]')
    m%sections(p%nsec)%stiffness = get_real(p, f(1), 'spring constant')
    if (m%sections(p%nsec)%stiffness <= 0.0_dp) call err(p, 'the spring constant must be positive')
    if (next_data(p)) call err(p, 'temperature-dependent spring constants (several data lines) are not implemented')
  end subroutine read_spring

  !> The spring type (catalogue shape) of the elements of set es, which
  !> must all be springs of one type.
  integer function spring_set_shape(p, m, es) result(shape)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    integer, intent(in) :: es
    integer :: k, sk
    shape = 0
    do k = 1, size(m%elsets(es)%items)
      associate(e => m%elsets(es)%items(k))
        sk = catalogue(m%etype(e))%shape
        if (.not. is_spring_shape(sk)) call err(p, 'element ' // elem_label(m, e) // ' of set ' // &
            trim(m%elsets(es)%name) // ' is a ' // trim(catalogue(m%etype(e))%name) // &
            ', not a spring: *SPRING applies to SPRING1, SPRING2 and SPRINGA elements')
        if (shape /= 0 .and. sk /= shape) call err(p, 'set ' // trim(m%elsets(es)%name) // &
            ' mixes spring types; give each type its own *SPRING')
        shape = sk
      end associate
    end do
    if (shape == 0) call err(p, 'element set ' // trim(m%elsets(es)%name) // ' is empty')
  end function spring_set_shape

  !> Purpose: *MASS, ELSET=: the point mass of the MASS elements of the
  !> set, one positive value on the line under the card. In a static step
  !> only gravity and centrifugal loads (*DLOAD GRAV, CENTRIF on the set)
  !> see it.
  module subroutine read_mass(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    integer :: n, es, k, e, line
    call allow_params(p, kw, 'ELSET')
    es = need_elset(p, m, required_param(p, kw, 'ELSET'))
    call warn_empty_set(p, size(m%elsets(es)%items), 'element set', m%elsets(es)%name, kw%name)
    do k = 1, size(m%elsets(es)%items)
      e = m%elsets(es)%items(k)
      if (catalogue(m%etype(e))%shape /= shape_mass) call err(p, 'element ' // elem_label(m, e) // &
          ' of set ' // trim(m%elsets(es)%name) // ' is a ' // trim(catalogue(m%etype(e))%name) // &
          ', not a point mass: *MASS applies to MASS elements')
    end do
    line = p%i
    call require_data(p, 'mass')
    call split_fields(line_text(p), f, n)
    if (n /= 1) call err(p, '*MASS data line needs: mass (one value)')
    call grow(m%sections, p%nsec + 1)
    p%nsec = p%nsec + 1
    m%sections(p%nsec) = section_t(elset=es, point_mass=.true., mass=get_real(p, f(1), 'mass'))
    m%sections(p%nsec)%src%line = line
    if (.not. m%sections(p%nsec)%mass > 0.0_dp) call err(p, 'the mass must be positive')
    if (next_data(p)) call err(p, '*MASS takes one data line (the mass)')
  end subroutine read_mass

  !> A spring dof: 1 (x) or 2 (y).
  integer function spring_dof(p, f) result(d)
    type(parser_t), intent(in) :: p
    type(field_t), intent(in) :: f
    d = get_int(p, f, 'spring dof')
    if (d == 3) call err(p, 'spring dof 3 (out of the plane) does not exist in a 2D model')
    if (d < 1 .or. d > 2) call err(p, 'spring dofs are 1 (x) or 2 (y) in 2D; rotations do not exist here')
  end function spring_dof

  !> STATE= of *SOLID SECTION: PLANE STRESS, PLANE STRAIN or
  !> AXISYMMETRIC (element_catalogue state_*), 0 when absent.
  integer function state_param(p, kw) result(state)
    type(parser_t), intent(in) :: p
    type(keyword_t), intent(in) :: kw
    character(len=:), allocatable :: v
    state = 0
    if (.not. has_param(kw, 'STATE')) return
    v = to_upper(param_value(kw, 'STATE'))
    select case (v)
    case ('PLANE STRESS'); state = state_plane_stress
    case ('PLANE STRAIN'); state = state_plane_strain
    case ('AXISYMMETRIC'); state = state_axisymmetric
    case default; call err(p, 'STATE must be PLANE STRESS, PLANE STRAIN or AXISYMMETRIC')
    end select
  end function state_param
end submodule deck_material_cards
