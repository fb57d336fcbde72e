!> Dispatch from an element kind to its routine; the single entry point the
!> assembly calls.
module element_library
  use element_types, only: elem_in_t, elem_out_t, kind_quad4, kind_tri3, kind_cfe
  use plane_elements, only: quad4, tri3
  use cfe_element, only: cfe
  implicit none
  private
  public :: element_routine

contains

  pure subroutine element_routine(ein, eout)
    type(elem_in_t), intent(in) :: ein
    type(elem_out_t), intent(out) :: eout
    select case (ein%kind)
    case (kind_quad4); call quad4(ein, eout)
    case (kind_tri3);  call tri3(ein, eout)
    case (kind_cfe);   call cfe(ein, eout)
    end select
  end subroutine element_routine
end module element_library
