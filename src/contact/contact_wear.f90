!> Archard wear at the coupling elements (docs/contact.md, "Wear"). On
!> each surface of a pair with *WEAR the worn depth grows as
!>   dh/dt = k p |ds/dt|           (Archard 1953; k = K / H per surface),
!> integrated over each converged increment from the increment's slip
!> (the friction history's, committed with it): a coupling element that
!> slides by ds under the normal force F (the converged end of the
!> increment) wears the volume (area per unit thickness in plane models)
!>   dV = N k F |ds|               (N the cycle-jump factor)
!> off each surface. The volumes are kept at the nodes of each surface:
!> a coupling element's slave share goes to its slave nodes with its
!> slave weights (one slave node, or the Gauss point's face weights, or
!> the master-mesh multiplier's S_mj / D_m), its master share to its
!> master nodes with the shape functions at X_C (N_i(X_C), or the mortar
!> weights M_jm / D_j) - the weights its forces are shared with - and a
!> node's worn depth is its volume over its consistent area int N_i da
!> on that surface (surface_areas). So the worn profile, interpolated
!> with the same shape functions, holds exactly the worn volume:
!> int h da = sum_i h_i int N_i da = sum dV (Archard's balance), and a
!> uniform pressure sliding uniformly wears k p s at every node it
!> covers. The coupling element reads both depths back at its point
!> (slave: its slave weights; master: the shape functions at X_C) as a
!> shift of its initial gap along its normal (contact's refresh_wear):
!> the bodies and their stiffness stay, only the gap changes.
!>
!> This module keeps the depths and the coupling elements' weights
!> (links); the contact module owns the coupling elements and calls it.
module contact_wear
  use kinds, only: dp
  use model, only: model_t, surf_element
  use contact_geometry, only: surface_areas
  implicit none
  private
  public :: wear_t, wear_link_t, wear_setup, wear_add, wear_at, wear_node_areas

  !> One coupling element as the wear sees it: its nodes, slave nodes
  !> first (nsl of them), with its weights (slave weights sum to one, and
  !> so do the master ones).
  type :: wear_link_t
    integer :: nsl = 0
    integer, allocatable :: node(:)
    real(dp), allocatable :: w(:)
  end type wear_link_t

  !> The wear of one pair: on (it has *WEAR), the coefficients of its
  !> slave (1) and master (2) surface, the cycle-jump factor, the worn
  !> depth at the nodes of each surface (2, nn) and the nodes' consistent
  !> areas there (2, nn; 0 off the surface).
  type :: wear_pair_t
    logical :: on = .false.
    real(dp) :: k(2) = 0.0_dp, jump = 1.0_dp
    real(dp), allocatable :: depth(:, :), area(:, :)
  end type wear_pair_t

  !> The wear of a contact set: on (some pair wears), per pair its wear,
  !> per coupling element its link (rebuilt with every search).
  type :: wear_t
    logical :: on = .false.
    type(wear_pair_t), allocatable :: pairs(:)
    type(wear_link_t), allocatable :: link(:)
  end type wear_t

contains

  !> Purpose: the wear state of model m before any wear: zero depths, and
  !> the consistent nodal areas of each wearing pair's surfaces (those of
  !> a slave node surface come later from its coupling elements,
  !> wear_node_areas).
  subroutine wear_setup(m, w)
    type(model_t), intent(in) :: m
    type(wear_t), intent(out) :: w
    integer :: ip
    allocate(w%pairs(size(m%pairs)))
    do ip = 1, size(m%pairs)
      if (.not. m%pairs(ip)%wear) cycle
      w%on = .true.
      associate(wp => w%pairs(ip), pr => m%pairs(ip))
        wp%on = .true.
        wp%k = pr%wear_k
        wp%jump = pr%wear_jump
        allocate(wp%depth(2, m%nn), wp%area(2, m%nn))
        wp%depth = 0.0_dp
        wp%area = 0.0_dp
        if (m%surfaces(pr%slave_surface)%kind == surf_element) wp%area(1, :) = surface_areas(m, &
                                                                                m%surfaces(pr%slave_surface))
        wp%area(2, :) = surface_areas(m, m%surfaces(pr%master_surface))
      end associate
    end do
  end subroutine wear_setup

  !> Purpose: the slave areas of a pair whose slave is a node surface (no
  !> faces to integrate over): the coupling elements' areas shared with
  !> their slave weights, once (the first search's).
  !> Arguments: w the wear; ip the pair; pair(j), area(j) of every
  !> coupling element j (its link w%link(j)).
  subroutine wear_node_areas(w, ip, pair, area)
    type(wear_t), intent(inout) :: w
    integer, intent(in) :: ip, pair(:)
    real(dp), intent(in) :: area(:)
    integer :: j, k
    associate(wp => w%pairs(ip))
      if (any(wp%area(1, :) > 0.0_dp)) return
      do j = 1, size(pair)
        if (pair(j) /= ip) cycle
        do k = 1, w%link(j)%nsl
          wp%area(1, w%link(j)%node(k)) = wp%area(1, w%link(j)%node(k)) + w%link(j)%w(k) * area(j)
        end do
      end do
    end associate
  end subroutine wear_node_areas

  !> Purpose: Archard's wear of coupling element j of pair ip in one
  !> converged increment: the volume N k F |ds| of each surface added to
  !> its nodes with the element's weights, as depth (volume over the
  !> node's consistent area).
  !> Arguments: w the wear; j the element (its link); ip its pair; force
  !> its compressive normal force F (>= 0); slip its slip in the increment.
  subroutine wear_add(w, j, ip, force, slip)
    type(wear_t), intent(inout) :: w
    integer, intent(in) :: j, ip
    real(dp), intent(in) :: force, slip
    real(dp) :: v(2)
    integer :: k, side, nd
    associate(wp => w%pairs(ip), ln => w%link(j))
      v = wp%jump * wp%k * force * abs(slip)
      if (all(v == 0.0_dp)) return
      do k = 1, size(ln%node)
        side = merge(1, 2, k <= ln%nsl)
        nd = ln%node(k)
        if (ln%w(k) == 0.0_dp .or. .not. wp%area(side, nd) > 0.0_dp) cycle
        wp%depth(side, nd) = wp%depth(side, nd) + ln%w(k) * v(side) / wp%area(side, nd)
      end do
    end associate
  end subroutine wear_add

  !> Purpose: the worn depths at coupling element j's point: its slave
  !> surface's (the slave weights) and its master surface's at X_C (the
  !> master weights); 0 where its pair does not wear.
  pure function wear_at(w, j, ip) result(h)
    type(wear_t), intent(in) :: w
    integer, intent(in) :: j, ip
    real(dp) :: h(2)
    integer :: k, side
    h = 0.0_dp
    if (.not. w%pairs(ip)%on) return
    associate(wp => w%pairs(ip), ln => w%link(j))
      do k = 1, size(ln%node)
        side = merge(1, 2, k <= ln%nsl)
        h(side) = h(side) + ln%w(k) * wp%depth(side, ln%node(k))
      end do
    end associate
  end function wear_at
end module contact_wear
