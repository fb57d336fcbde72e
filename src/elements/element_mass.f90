!> The consistent mass matrices of the body elements, for the natural
!> frequencies (*FREQUENCY): M_e = integral of rho N^T N dV, the same
!> shape functions as the stiffness (a lumped mass is not used: the
!> consistent one converges from above with the stiffness, and is what
!> CalculiX's frequency step assembles). dV is t dA in the plane states
!> and 2 pi r dA in axisymmetry (the whole ring, as the stiffness and
!> CalculiX's axisymmetric forces count it); a truss's is A ds; a point
!> mass (MASS element, *MASS) is its mass on both dofs of its node (in
!> axisymmetry the mass of the whole ring, as its gravity load counts
!> it); a spring has none.
module element_mass
  use kinds, only: dp
  use element_catalogue, only: catalogue, max_nodes, max_ip, is_line, shape_mass
  use shape_functions, only: shape_at, gauss_rule, load_rule, truss_shape, gauss_line
  use continuum_element, only: volume_factor
  implicit none
  private
  public :: mass_matrix

contains

  !> Purpose: the consistent mass matrix me(2 nen, 2 nen) (dofs x, y of
  !> each node in turn) of an element of catalogue type et.
  !> Arguments: xy(2, nen) nodal coordinates; thickness(nen) the plane
  !> elements' nodal thickness (a truss: thickness(1) is its area); rho
  !> the density (mass per volume); point the mass of a MASS element.
  !> The continuum rule is load_rule's (2x2, 3x3, 6 points): exact for
  !> N^T N (times r in axisymmetry) on undistorted quadrilaterals and for
  !> the plane triangles; the 6-node axisymmetric triangle's degree-5
  !> integrand is integrated to degree 4.
  pure subroutine mass_matrix(et, xy, thickness, rho, point, me)
    integer, intent(in) :: et
    real(dp), intent(in) :: xy(:, :), thickness(:), rho, point
    real(dp), intent(out) :: me(:, :)
    real(dp) :: xg(2, max_ip), wg(max_ip), n(max_nodes), dn(2, max_nodes), jac(2, 2), dv
    integer :: ip, a, b, nen, nip, shape
    me = 0.0_dp
    shape = catalogue(et)%shape
    nen = catalogue(et)%nodes
    if (shape == shape_mass) then
      me(1, 1) = point
      me(2, 2) = point
      return
    end if
    if (is_line(shape)) then
      call truss_mass(nen, xy, rho * thickness(1), me)
      return
    end if
    nip = load_rule(shape)
    call gauss_rule(shape, nip, xg, wg)
    do ip = 1, nip
      call shape_at(shape, xg(:, ip), n, dn)
      jac = matmul(dn(:, 1:nen), transpose(xy(:, 1:nen)))
      dv = wg(ip) * rho * volume_factor(catalogue(et)%state, jac(1, 1) * jac(2, 2) - jac(1, 2) * jac(2, 1), &
                                        dot_product(xy(1, 1:nen), n(1:nen)), dot_product(n(1:nen), thickness(1:nen)))
      do b = 1, nen
        do a = 1, nen
          me(2 * a - 1, 2 * b - 1) = me(2 * a - 1, 2 * b - 1) + n(a) * n(b) * dv
        end do
      end do
    end do
    do b = 1, nen
      do a = 1, nen
        me(2 * a, 2 * b) = me(2 * a - 1, 2 * b - 1)
      end do
    end do
  end subroutine mass_matrix

  !> Purpose: the consistent mass of a truss of nen = 2 or 3 nodes at xy
  !> (deck order: end, middle, end) with mass per length rho_a: rho_a times
  !> the integral of N_a N_b along its arc, three Gauss points (exact on a
  !> straight truss of either order), into me (zeroed by the caller).
  pure subroutine truss_mass(nen, xy, rho_a, me)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xy(:, :), rho_a
    real(dp), intent(inout) :: me(:, :)
    real(dp) :: s(3), w(3), n(3), dn(3), ds
    integer :: ip, a, b
    call gauss_line(3, s, w)
    do ip = 1, 3
      call truss_shape(nen, s(ip), n, dn)
      ds = norm2(matmul(xy(:, 1:nen), dn(1:nen))) * w(ip)
      do b = 1, nen
        do a = 1, nen
          me(2 * a - 1, 2 * b - 1) = me(2 * a - 1, 2 * b - 1) + rho_a * n(a) * n(b) * ds
          me(2 * a, 2 * b) = me(2 * a, 2 * b) + rho_a * n(a) * n(b) * ds
        end do
      end do
    end do
  end subroutine truss_mass
end module element_mass
