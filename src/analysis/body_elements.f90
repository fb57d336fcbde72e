!> The element data of a body element, one that carries stiffness (a
!> continuum element, a truss, a spring), taken from the model: its
!> nodes, coordinates and displacements, and what its routine needs of
!> its section (material, nodal thicknesses, truss area, spring constant
!> and dofs). The assembly, the stress recovery and the thermal load all
!> build their element input here.
module body_elements
  use kinds, only: dp
  use model, only: model_t, elem_nodes, elem_thickness, is_truss, elastic_iso
  use element_catalogue, only: catalogue
  use element_interface, only: elem_in_t, max_hist
  use element_catalogue, only: max_ip
  implicit none
  private
  public :: body_input, body_alpha

contains

  !> Purpose: element data of body element e at displacements u and, if
  !> given, nodal temperature changes dtemp(nn) from the initial state.
  !> The material's law, hyperelastic constants and hardening curve are
  !> always passed (a linear elastic material has law_elastic and no
  !> curve, and its element routine takes the linear path).
  !> Arguments: nodes returns the element's nodes (ein%nen of them);
  !> nlgeom, if given, the step's large-deformation switch and hist the
  !> element's committed history at its integration points.
  pure subroutine body_input(m, e, u, ein, nodes, dtemp, nlgeom, hist)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    real(dp), intent(in) :: u(:, :)
    real(dp), intent(in), optional :: dtemp(:)
    logical, intent(in), optional :: nlgeom
    real(dp), intent(in), optional :: hist(max_hist, max_ip)
    type(elem_in_t), intent(out) :: ein
    integer, intent(out) :: nodes(:)
    integer :: k, nen
    nen = elem_nodes(m, e)
    ein%nen = nen
    ein%kind = catalogue(m%etype(e))%shape
    ein%state = catalogue(m%etype(e))%state
    ein%nip = catalogue(m%etype(e))%nip
    nodes(1:nen) = m%conn(1:nen, e)
    do k = 1, nen
      ein%xy(:, k) = m%x(:, nodes(k))
      ein%ue(2 * k - 1:2 * k) = u(:, nodes(k))
    end do
    associate(sec => m%sections(m%elem_section(e)))
      if (sec%spring) then
        ein%stiffness = sec%stiffness
        ein%dofs = sec%dof
        return
      end if
      ein%e = m%materials(sec%material)%e
      ein%nu = m%materials(sec%material)%nu
      associate(mat => m%materials(sec%material))
        ein%law = mat%law
        ein%c10 = mat%c10
        ein%c01 = mat%c01
        ein%d1 = mat%d1
        ein%ro_sigma0 = mat%ro_sigma0
        ein%ro_n = mat%ro_n
        ein%ro_alpha = mat%ro_alpha
        ein%nyield = mat%nyield
        if (mat%nyield > 0) ein%yield(:, 1:mat%nyield) = mat%yield(:, 1:mat%nyield)
        if (mat%elastic_type /= elastic_iso) call anisotropic_input(m, sec%orientation, mat%c6, ein)
      end associate
      if (present(nlgeom)) ein%nlgeom = nlgeom
      ! (elem_in_t's history has no default: a plastic law reads it)
      if (present(hist)) then
        ein%hist = hist
      else if (m%materials(sec%material)%nyield > 0) then
        ein%hist = 0.0_dp
      end if
      if (is_truss(m, e)) then
        ein%area = sec%thickness
      else
        ein%thickness = elem_thickness(m, e)
      end if
      if (present(dtemp)) then
        ein%alpha = m%materials(sec%material)%alpha
        ein%dtemp(1:nen) = dtemp(nodes(1:nen))
      end if
    end associate
  end subroutine body_input

  !> Purpose: the anisotropic stiffness c6 (material axes) and the
  !> section's *ORIENTATION (index orient into m%orientations, 0 the
  !> global axes) into the element data.
  pure subroutine anisotropic_input(m, orient, c6, ein)
    type(model_t), intent(in) :: m
    integer, intent(in) :: orient
    real(dp), intent(in) :: c6(6, 6)
    type(elem_in_t), intent(inout) :: ein
    ein%aniso = .true.
    ein%c6 = c6
    ein%orient_system = 0
    if (orient == 0) return
    associate(o => m%orientations(orient))
      ein%orient_system = o%system
      ein%orient_a = o%a
      ein%orient_b = o%b
      ein%orient_axis = o%axis
      ein%orient_angle = o%angle
    end associate
  end subroutine anisotropic_input

  !> Purpose: the expansion coefficient of body element e's material (0
  !> for a spring, which has none).
  pure real(dp) function body_alpha(m, e)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    body_alpha = 0.0_dp
    associate(sec => m%sections(m%elem_section(e)))
      if (.not. sec%spring) body_alpha = m%materials(sec%material)%alpha
    end associate
  end function body_alpha
end module body_elements
