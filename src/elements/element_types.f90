!> The one interface every element routine shares (FEAP style): element
!> data in, element arrays out. No element routine sees global state.
module element_types
  use kinds, only: dp
  implicit none
  private
  public :: elem_in_t, elem_out_t, max_en, max_edof, max_ip, &
            kind_quad4, kind_tri3, kind_cfe

  !> A coupling element has a master element (up to 4 nodes) plus the
  !> coupling node.
  integer, parameter :: max_en = 5, max_edof = 2 * max_en, max_ip = 4
  integer, parameter :: kind_quad4 = 1, kind_tri3 = 2, kind_cfe = 3

  type :: elem_in_t
    integer :: kind = 0
    integer :: nen = 0                      ! nodes (CFE: master nodes + 1)
    real(dp) :: xy(2, max_en) = 0.0_dp      ! nodal coordinates
    real(dp) :: ue(max_edof) = 0.0_dp       ! nodal displacements
    ! continuum elements
    real(dp) :: e = 0.0_dp, nu = 0.0_dp, thickness = 1.0_dp
    logical :: plane_strain = .false.
    ! coupling element: master kind, natural coordinates of X_C in the
    ! master, unit outward normal of the master edge, normal penalty and
    ! the initial gap vector [[U]]_0
    integer :: master_kind = 0
    real(dp) :: xi(2) = 0.0_dp
    real(dp) :: normal(2) = 0.0_dp
    real(dp) :: penalty = 0.0_dp
    real(dp) :: gap0(2) = 0.0_dp
  end type elem_in_t

  type :: elem_out_t
    integer :: ndof = 0
    real(dp) :: ke(max_edof, max_edof) = 0.0_dp
    real(dp) :: fe(max_edof) = 0.0_dp          ! internal force
    integer :: nip = 0
    real(dp) :: sig_ip(4, max_ip) = 0.0_dp     ! s11, s22, s33, s12
    real(dp) :: eps_ip(3, max_ip) = 0.0_dp     ! e11, e22, gamma12
    real(dp) :: sig_node(4, max_en) = 0.0_dp   ! extrapolated to the nodes
    ! coupling element: relative displacement [[U]] (eq. 8) and its
    ! normal component, the normal gap (negative = penetration)
    real(dp) :: jump(2) = 0.0_dp
    real(dp) :: gap = 0.0_dp
    real(dp) :: normal_force = 0.0_dp
  end type elem_out_t
end module element_types
