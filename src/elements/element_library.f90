!> Dispatch from an element kind to its routine; the single entry point the
!> analysis layer calls for body elements (the coupling element has its
!> own types and routine, cfe_element). A new element routine is one
!> module and one line here.
module element_library
  use element_interface, only: elem_in_t, elem_out_t, kind_quad4, kind_tri3, kind_quad8, kind_tri6, &
                               kind_truss2, kind_truss3, kind_spring1, kind_spring2, kind_springa
  use continuum_element, only: continuum
  use nonlinear_continuum, only: nonlinear_continuum_element, is_nonlinear, thickness_stretch
  use truss_element, only: truss
  use spring_element, only: spring
  implicit none
  private
  public :: element_routine, thickness_stretch

contains

  !> Purpose: element arrays of one element.
  !> Arguments: action (act_* codes combined with ior), ein element data,
  !> eout the arrays asked for (the others are zero).
  pure subroutine element_routine(action, ein, eout)
    integer, intent(in) :: action
    type(elem_in_t), intent(in) :: ein
    type(elem_out_t), intent(out) :: eout
    select case (ein%kind)
    case (kind_tri3, kind_quad4, kind_tri6, kind_quad8)
      ! large deformation, a hyperelastic law or plasticity: the nonlinear
      ! routine; the linear elastic element otherwise (unchanged)
      if (is_nonlinear(ein)) then
        call nonlinear_continuum_element(action, ein, eout)
      else
        call continuum(action, ein, eout)
      end if
    case (kind_truss2, kind_truss3); call truss(action, ein, eout)
    case (kind_spring1, kind_spring2, kind_springa); call spring(action, ein, eout)
    end select
  end subroutine element_routine
end module element_library
