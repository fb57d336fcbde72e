!> Material cards: *MATERIAL, *ELASTIC, *EXPANSION, *SOLID SECTION.
submodule (deck_parser) deck_material_cards
  use kinds, only: dp
  use strings, only: split_fields, to_upper, field_t
  use deck_input, only: param_value, has_param, deck_warning
  use deck_cursor, only: line_text, err, next_data, require_data, no_data, allow_params, required_param, &
                         name_param, get_real, need_elset, param_real
  use element_catalogue, only: state_plane_stress, state_plane_strain, state_axisymmetric
  use model, only: material_t, section_t, find_name
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

  !> Purpose: *ELASTIC (isotropic): `E, nu` of the current material, one
  !> data line (temperature dependence is not implemented).
  module subroutine read_elastic(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    integer :: n
    call allow_params(p, kw, 'TYPE')
    if (has_param(kw, 'TYPE')) then
      if (to_upper(param_value(kw, 'TYPE')) /= 'ISOTROPIC') call err(p, 'only TYPE=ISOTROPIC is implemented')
    end if
    if (p%material == 0) call err(p, '*ELASTIC outside a *MATERIAL')
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
    end associate
    if (next_data(p)) call err(p, 'temperature-dependent *ELASTIC data is not implemented')
  end subroutine read_elastic

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
    call allow_params(p, kw, 'ELSET,MATERIAL,STATE,OFFSET,NODAL THICKNESS')
    call grow(m%sections, p%nsec + 1)
    p%nsec = p%nsec + 1
    m%sections(p%nsec) = section_t()
    associate(s => m%sections(p%nsec))
      s%elset = need_elset(p, m, required_param(p, kw, 'ELSET'))
      s%material_name = name_param(p, kw, 'MATERIAL')
      s%src%line = p%i
      s%state = state_param(p, kw)
      s%nodal_thickness = has_param(kw, 'NODAL THICKNESS')
      if (param_real(p, kw, 'OFFSET', 0.0_dp) /= 0.0_dp) call deck_warning(p%deck, p%i, 'OFFSET= moves the ' // &
          'mid-plane of a plane-stress layer out of the plane; it cannot change a 2D answer and is ignored')
      s%thickness = 1.0_dp
      if (next_data(p)) then
        call split_fields(line_text(p), f, n)
        if (len(f(1)%s) > 0) then
          s%thickness = get_real(p, f(1), 'thickness')
          s%thickness_given = .true.
        end if
        if (s%thickness <= 0.0_dp) call err(p, 'section thickness must be positive')
      end if
    end associate
  end subroutine read_section

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
