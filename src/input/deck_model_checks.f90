!> Checks that need the whole deck: sections and their materials (a
!> material may be defined after the section naming it), one section per
!> solid element, element geometry, a procedure in every step. The
!> element topology (edges and neighbours) is built last.
submodule (deck_parser) deck_model_checks
  use kinds, only: dp
  use strings, only: itoa
  use deck_cursor, only: err
  use model, only: is_continuum, find_name
  use element_catalogue, only: catalogue
  use mesh_topology, only: build_topology
  implicit none

contains

  !> Purpose: checks after the last card; errors name the card at fault
  !> (the section, the element line, the step).
  module subroutine check_model(p, m)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    integer :: s
    call check_sections(p, m)
    call check_elements(p, m)
    if (size(m%steps) == 0) then
      p%i = p%deck%n
      call err(p, 'the deck has no *STEP: nothing to analyse')
    end if
    do s = 1, size(m%steps)
      if (m%steps(s)%period < 0.0_dp) then
        p%i = m%steps(s)%src%line
        call err(p, 'step has no procedure (*STATIC)')
      end if
    end do
    call build_topology(m%nn, m%ne, m%etype, m%conn, m%topo)
  end subroutine check_model

  !> Every section's material exists and is elastic; each solid element
  !> is in at most one section (m%elem_section filled here).
  subroutine check_sections(p, m)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    integer :: s, k, e, imat
    allocate(m%elem_section(m%ne))
    m%elem_section = 0
    do s = 1, size(m%sections)
      p%i = m%sections(s)%src%line
      imat = find_name(m%materials%name, m%sections(s)%material_name)
      if (imat == 0) call err(p, 'undefined material ' // trim(m%sections(s)%material_name))
      if (.not. m%materials(imat)%has_elastic) then
        p%i = m%materials(imat)%src%line
        call err(p, 'material ' // trim(m%materials(imat)%name) // ' has no *ELASTIC')
      end if
      m%sections(s)%material = imat
      do k = 1, size(m%elsets(m%sections(s)%elset)%items)
        e = m%elsets(m%sections(s)%elset)%items(k)
        if (.not. is_continuum(m, e)) cycle
        if (m%elem_section(e) /= 0) call err(p, 'element ' // itoa(m%elem_id(e)) // ' is in two sections')
        m%elem_section(e) = s
      end do
    end do
  end subroutine check_sections

  !> Every solid element has a section and a positive Jacobian at each
  !> corner.
  subroutine check_elements(p, m)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(in) :: m
    integer :: e
    do e = 1, m%ne
      if (.not. is_continuum(m, e)) cycle
      p%i = m%elem_src(e)%line
      if (m%elem_section(e) == 0) call err(p, 'element ' // itoa(m%elem_id(e)) // ' has no *SOLID SECTION')
      if (min_corner_jacobian(m, e) <= 0.0_dp) call err(p, 'element ' // itoa(m%elem_id(e)) // &
          ' has a zero or negative Jacobian (nodes clockwise or element inverted)')
    end do
  end subroutine check_elements

  !> Smallest corner value of the Jacobian determinant: positive at every
  !> corner means a valid, convex, counter-clockwise element.
  real(dp) function min_corner_jacobian(m, e)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    integer :: nen, k
    real(dp) :: a(2), b(2), scale
    nen = catalogue(m%etype(e))%corners
    min_corner_jacobian = huge(1.0_dp)
    scale = 0.0_dp
    do k = 1, nen
      a = m%x(:, m%conn(mod(k, nen) + 1, e)) - m%x(:, m%conn(k, e))
      b = m%x(:, m%conn(mod(k + nen - 2, nen) + 1, e)) - m%x(:, m%conn(k, e))
      min_corner_jacobian = min(min_corner_jacobian, a(1) * b(2) - a(2) * b(1))
      scale = max(scale, sum(a**2))
    end do
    ! Collinear corners give round-off sized values of either sign.
    if (min_corner_jacobian <= 1.0e-12_dp * scale) min_corner_jacobian = 0.0_dp
  end function min_corner_jacobian
end submodule deck_model_checks
