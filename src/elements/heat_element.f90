!> Element arrays of heat conduction on the plane and axisymmetric
!> continuum shapes (catalogue: CPS*/CPE*/CAX* in a *HEAT TRANSFER step,
!> DC2D*/DCAX*): the conduction matrix K_ij = int grad N_i . k grad N_j dV (k diagonal),
!> the capacity matrix C_ij = int rho c N_i N_j dV (consistent), the film
!> matrix H_ij = int h N_i N_j dS and the nodal fluxes int N_j q dS (a face)
!> and int N_j r dV (the body). dV is the thickness times dA in the plane
!> and 2 pi r dA in axisymmetry (the whole circumference, as the
!> mechanical element matrices: continuum_element's volume_factor).
!> The rules are richer than the stiffness's: 6 points (degree 4) on a
!> triangle, 3x3 on a quadrilateral, which integrate N_i N_j r exactly on
!> straight-sided elements; 3 points along a face.
module heat_element
  use kinds, only: dp
  use element_catalogue, only: catalogue, max_nodes, max_ip, is_triangle, edge_node_count
  use shape_functions, only: shape_at, line_shape, gauss_line, gauss_rule
  use continuum_element, only: volume_factor
  implicit none
  private
  public :: heat_volume_arrays, heat_face_arrays, heat_gradient, conductivity_at, temperature_at

contains

  !> Purpose: conduction ke, capacity ce and unit body flux fe (int N dV)
  !> of an element of catalogue type et.
  !> Arguments: xy(2, nodes) the node coordinates; thick(nodes) the nodal
  !> thicknesses (plane); cond the conductivities along x and y (r and z);
  !> cap rho c; ktab(3, nk) and temp(nodes), if present with nk > 1: the
  !> conductivities at each point from the table at the point's
  !> temperature (conductivity_at) in place of cond.
  pure subroutine heat_volume_arrays(et, xy, thick, cond, cap, ke, ce, fe, ktab, temp)
    integer, intent(in) :: et
    real(dp), intent(in) :: xy(:, :), thick(:), cond(2), cap
    real(dp), intent(in), optional :: ktab(:, :), temp(:)
    real(dp), intent(out) :: ke(max_nodes, max_nodes), ce(max_nodes, max_nodes), fe(max_nodes)
    real(dp) :: xi(2, max_ip), w(max_ip), n(max_nodes), dx(2, max_nodes), kdx(2, max_nodes), detj, dv, k(2)
    integer :: ip, nen, nip, i
    logical :: tabled
    nen = catalogue(et)%nodes
    tabled = present(ktab) .and. present(temp)
    if (tabled) tabled = size(ktab, 2) > 1
    k = cond
    ke = 0.0_dp
    ce = 0.0_dp
    fe = 0.0_dp
    nip = merge(6, 9, is_triangle(catalogue(et)%shape))
    call gauss_rule(catalogue(et)%shape, nip, xi, w)
    do ip = 1, nip
      call physical_gradients(et, xy, xi(:, ip), n, dx, detj)
      dv = w(ip) * volume_factor(catalogue(et)%state, detj, dot_product(n(1:nen), xy(1, 1:nen)), &
                                 dot_product(n(1:nen), thick(1:nen)))
      if (tabled) k = conductivity_at(ktab, dot_product(n(1:nen), temp(1:nen)))
      kdx(1, 1:nen) = k(1) * dx(1, 1:nen)
      kdx(2, 1:nen) = k(2) * dx(2, 1:nen)
      ke(1:nen, 1:nen) = ke(1:nen, 1:nen) + dv * matmul(transpose(dx(:, 1:nen)), kdx(:, 1:nen))
      do i = 1, nen
        ce(i, 1:nen) = ce(i, 1:nen) + cap * dv * n(i) * n(1:nen)
      end do
      fe(1:nen) = fe(1:nen) + dv * n(1:nen)
    end do
  end subroutine heat_volume_arrays

  !> Purpose: on face k of an element of type et: the matrix he = int
  !> N_i N_j dS (times h: the film matrix) and fe = int N_j dS (times q: a
  !> surface flux; times h T_sink: the film's load), 3 Gauss points along
  !> the face (exact for a 3-node face and a linear thickness or radius).
  pure subroutine heat_face_arrays(et, xy, thick, k, he, fe)
    integer, intent(in) :: et, k
    real(dp), intent(in) :: xy(:, :), thick(:)
    real(dp), intent(out) :: he(max_nodes, max_nodes), fe(max_nodes)
    real(dp) :: s(3), w(3), nl(3), ds(3), xe(2, 3), te(3), x(2), t(2), da
    integer :: nn, ip, i, j, loc(3)
    he = 0.0_dp
    fe = 0.0_dp
    nn = edge_node_count(et, k)
    loc = catalogue(et)%edge(:, k)
    xe = 0.0_dp
    te = 0.0_dp
    do j = 1, nn
      xe(:, j) = xy(:, loc(j))
      te(j) = thick(loc(j))
    end do
    call gauss_line(3, s, w)
    do ip = 1, 3
      call line_shape(nn, s(ip), nl, ds)
      x = matmul(xe(:, 1:nn), nl(1:nn))
      t = matmul(xe(:, 1:nn), ds(1:nn))
      ! |dx/ds| ds times the thickness, or times 2 pi r
      da = w(ip) * volume_factor(catalogue(et)%state, norm2(t), x(1), dot_product(nl(1:nn), te(1:nn)))
      do i = 1, nn
        fe(loc(i)) = fe(loc(i)) + nl(i) * da
        do j = 1, nn
          he(loc(i), loc(j)) = he(loc(i), loc(j)) + nl(i) * nl(j) * da
        end do
      end do
    end do
  end subroutine heat_face_arrays

  !> Purpose: the temperature gradient at natural point xi of an element
  !> of type et with nodes at xy and nodal temperatures temp.
  pure function heat_gradient(et, xy, temp, xi) result(g)
    integer, intent(in) :: et
    real(dp), intent(in) :: xy(:, :), temp(:), xi(2)
    real(dp) :: g(2), n(max_nodes), dx(2, max_nodes), detj
    integer :: nen
    nen = catalogue(et)%nodes
    call physical_gradients(et, xy, xi, n, dx, detj)
    g = matmul(dx(:, 1:nen), temp(1:nen))
  end function heat_gradient

  !> Purpose: the conductivities (k11, k22) of a table ktab(3, nk) (rows:
  !> temperature, k11, k22; temperatures increasing) at temperature t:
  !> linear between its points, constant beyond them.
  pure function conductivity_at(ktab, t) result(k)
    real(dp), intent(in) :: ktab(:, :), t
    real(dp) :: k(2), s
    integer :: j, nk
    nk = size(ktab, 2)
    if (t <= ktab(1, 1)) then
      k = ktab(2:3, 1)
    else if (t >= ktab(1, nk)) then
      k = ktab(2:3, nk)
    else
      do j = 2, nk
        if (t <= ktab(1, j)) exit
      end do
      s = (t - ktab(1, j - 1)) / (ktab(1, j) - ktab(1, j - 1))
      k = ktab(2:3, j - 1) + s * (ktab(2:3, j) - ktab(2:3, j - 1))
    end if
  end function conductivity_at

  !> Purpose: the temperature at natural point xi of an element of type
  !> et with nodal temperatures temp.
  pure real(dp) function temperature_at(et, temp, xi) result(t)
    integer, intent(in) :: et
    real(dp), intent(in) :: temp(:), xi(2)
    real(dp) :: n(max_nodes), dn(2, max_nodes)
    integer :: nen
    nen = catalogue(et)%nodes
    call shape_at(catalogue(et)%shape, xi, n, dn)
    t = dot_product(n(1:nen), temp(1:nen))
  end function temperature_at

  !> Purpose: shape functions n, their x-y derivatives dx and det J at
  !> natural point xi (det J <= 0: an inverted element, dx left zero; the
  !> deck checks refuse such elements before the analysis).
  pure subroutine physical_gradients(et, xy, xi, n, dx, detj)
    integer, intent(in) :: et
    real(dp), intent(in) :: xy(:, :), xi(2)
    real(dp), intent(out) :: n(max_nodes), dx(2, max_nodes), detj
    real(dp) :: dn(2, max_nodes), jac(2, 2), jinv(2, 2)
    integer :: nen
    nen = catalogue(et)%nodes
    call shape_at(catalogue(et)%shape, xi, n, dn)
    jac = matmul(dn(:, 1:nen), transpose(xy(:, 1:nen)))
    detj = jac(1, 1) * jac(2, 2) - jac(1, 2) * jac(2, 1)
    dx = 0.0_dp
    if (detj <= 0.0_dp) return
    jinv(1, 1) = jac(2, 2) / detj
    jinv(2, 2) = jac(1, 1) / detj
    jinv(1, 2) = -jac(1, 2) / detj
    jinv(2, 1) = -jac(2, 1) / detj
    dx(:, 1:nen) = matmul(jinv, dn(:, 1:nen))
  end subroutine physical_gradients
end module heat_element