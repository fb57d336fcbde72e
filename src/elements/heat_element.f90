!> Element arrays of heat conduction on the plane and axisymmetric
!> continuum shapes (catalogue: CPS*/CPE*/CAX* in a *HEAT TRANSFER step,
!> DC2D*/DCAX*): the conduction matrix K_ij = int grad N_i . k grad N_j dV (k diagonal),
!> the capacity matrix C_ij = int rho c N_i N_j dV (consistent), the film
!> matrix H_ij = int h N_i N_j dS, the nodal fluxes int N_j q dS (a face)
!> and int N_j r dV (the body), and radiation to the environment from a
!> face with its tangent (heat_radiation_arrays). dV is the thickness times dA in the plane
!> and 2 pi r dA in axisymmetry (the whole circumference, as the
!> mechanical element matrices: continuum_element's volume_factor).
!> The rules (heat_points): 6 points (degree 4) on a 3-node triangle and
!> 3x3 on a quadrilateral, which integrate N_i N_j r exactly on
!> straight-sided elements; CalculiX's rules where its elements take
!> fewer (the in-plane points of the 3D element it expands a 2D one to):
!> 3 on a 6-node triangle (C3D15), 2x2 on CPS8R/CPE8R/CAX8R (C3D20R);
!> 3 points along a face.
module heat_element
  use kinds, only: dp
  use element_catalogue, only: catalogue, max_nodes, max_ip, is_triangle, edge_node_count, shape_tri6, shape_quad8
  use shape_functions, only: shape_at, line_shape, gauss_line, gauss_rule, jacobian_det
  use continuum_element, only: volume_factor
  implicit none
  private
  public :: heat_volume_arrays, heat_face_arrays, heat_radiation_arrays, heat_gradient, table_at, conductivity_at, &
            temperature_at

contains

  !> Purpose: conduction ke, capacity ce and unit body flux fe (int N dV)
  !> of an element of catalogue type et.
  !> Arguments: xy(2, nodes) the node coordinates; thick(nodes) the nodal
  !> thicknesses (plane); cond the conductivities along x and y (r and z);
  !> cap rho c; temp(nodes), if present, the nodal temperatures at which
  !> the tables are evaluated at each point (table_at): ktab(3, nk) with
  !> nk > 1 the conductivities in place of cond, ctab(2, nc) with nc > 1
  !> the specific heat c, the capacity rho c with rho = cap / ctab(2, 1).
  pure subroutine heat_volume_arrays(et, xy, thick, cond, cap, ke, ce, fe, dv_min, temp, ktab, ctab)
    integer, intent(in) :: et
    real(dp), intent(in) :: xy(:, :), thick(:), cond(2), cap
    real(dp), intent(in), optional :: temp(:), ktab(:, :), ctab(:, :)
    real(dp), intent(out) :: ke(max_nodes, max_nodes), ce(max_nodes, max_nodes), fe(max_nodes)
    ! the smallest volume of an integration point over its weight: not
    ! positive where the Jacobian (or r, or the thickness) is not, and the
    ! caller stops (the point's gradients are then not computed)
    real(dp), intent(out) :: dv_min
    real(dp) :: xi(2, max_ip), w(max_ip), n(max_nodes), dx(2, max_nodes), kdx(2, max_nodes), detj, dv, k(2), &
                c(1), t
    integer :: ip, nen, nip, i
    logical :: ktabled, ctabled
    nen = catalogue(et)%nodes
    ktabled = present(ktab) .and. present(temp)
    if (ktabled) ktabled = size(ktab, 2) > 1
    ctabled = present(ctab) .and. present(temp)
    if (ctabled) ctabled = size(ctab, 2) > 1
    k = cond
    c = cap
    ke = 0.0_dp
    ce = 0.0_dp
    fe = 0.0_dp
    nip = heat_points(et)
    call gauss_rule(catalogue(et)%shape, nip, xi, w)
    dv_min = huge(1.0_dp)
    do ip = 1, nip
      call physical_gradients(et, xy, xi(:, ip), n, dx, detj)
      dv = volume_factor(catalogue(et)%state, detj, dot_product(n(1:nen), xy(1, 1:nen)), &
                         dot_product(n(1:nen), thick(1:nen)))
      if (.not. (detj > 0.0_dp .and. dv > 0.0_dp)) then
        dv_min = min(dv_min, dv, detj)
        cycle
      end if
      dv = w(ip) * dv
      if (ktabled .or. ctabled) t = dot_product(n(1:nen), temp(1:nen))
      if (ktabled) k = table_at(ktab, t)
      if (ctabled) c = cap / ctab(2, 1) * table_at(ctab, t)
      kdx(1, 1:nen) = k(1) * dx(1, 1:nen)
      kdx(2, 1:nen) = k(2) * dx(2, 1:nen)
      ke(1:nen, 1:nen) = ke(1:nen, 1:nen) + dv * matmul(transpose(dx(:, 1:nen)), kdx(:, 1:nen))
      do i = 1, nen
        ce(i, 1:nen) = ce(i, 1:nen) + c(1) * dv * n(i) * n(1:nen)
      end do
      fe(1:nen) = fe(1:nen) + dv * n(1:nen)
    end do
  end subroutine heat_volume_arrays

  !> Purpose: the number of integration points of the volume integrals
  !> of an element of type et: CalculiX's in-plane rule of the 3D element
  !> it expands the 2D one to where that has fewer points than the exact
  !> one (a 6-node triangle: C3D15's 3 points, degree 2, which leave r
  !> grad N . grad N of CAX6 and the capacity inexact; an 8-node
  !> quadrilateral with reduced integration: C3D20R's 2x2), so that
  !> CalculiX's decks give CalculiX's temperatures (ax6ht: docs/heat.md);
  !> otherwise 6 on a triangle and 3x3 on a quadrilateral (exact for the
  !> capacity N_i N_j r on straight-sided elements).
  pure integer function heat_points(et) result(nip)
    integer, intent(in) :: et
    if (catalogue(et)%shape == shape_tri6) then
      nip = 3
    else if (catalogue(et)%shape == shape_quad8 .and. catalogue(et)%nip == 4) then
      nip = 4
    else
      nip = merge(6, 9, is_triangle(catalogue(et)%shape))
    end if
  end function heat_points

  !> Purpose: on face k of an element of type et: the matrix he = int
  !> N_i N_j dS (times h: the film matrix) and fe = int N_j dS (times q: a
  !> surface flux; times h T_sink: the film's load), 3 Gauss points along
  !> the face (exact for a 3-node face and a linear thickness or radius).
  pure subroutine heat_face_arrays(et, xy, thick, k, he, fe)
    integer, intent(in) :: et, k
    real(dp), intent(in) :: xy(:, :), thick(:)
    real(dp), intent(out) :: he(max_nodes, max_nodes), fe(max_nodes)
    real(dp) :: nl(3, 3), da(3)
    integer :: nn, ip, i, j, loc(3)
    he = 0.0_dp
    fe = 0.0_dp
    call face_points(et, xy, thick, k, nn, loc, nl, da)
    do ip = 1, 3
      do i = 1, nn
        fe(loc(i)) = fe(loc(i)) + nl(i, ip) * da(ip)
        do j = 1, nn
          he(loc(i), loc(j)) = he(loc(i), loc(j)) + nl(i, ip) * nl(j, ip) * da(ip)
        end do
      end do
    end do
  end subroutine heat_face_arrays

  !> Purpose: radiation to the environment from face k of an element of
  !> type et (*RADIATE): the heat into it fe_i = int N_i es (Ts^4 - T^4)
  !> dS and its tangent re_ij = -d fe_i / d T_j = int N_i N_j 4 es T^3 dS
  !> at the nodal temperatures temp (Newton), T and Ts absolute (minus
  !> t_zero, *PHYSICAL CONSTANTS' ABSOLUTE ZERO), es the emissivity times
  !> Stefan-Boltzmann's constant (Stefan-Boltzmann's law for a grey body
  !> facing surroundings at Ts); 3 Gauss points along the face.
  pure subroutine heat_radiation_arrays(et, xy, thick, k, temp, t_zero, sink, es, re, fe)
    integer, intent(in) :: et, k
    real(dp), intent(in) :: xy(:, :), thick(:), temp(:), t_zero, sink, es
    real(dp), intent(out) :: re(max_nodes, max_nodes), fe(max_nodes)
    real(dp) :: nl(3, 3), da(3), ta, tsa
    integer :: nn, ip, i, j, loc(3)
    re = 0.0_dp
    fe = 0.0_dp
    call face_points(et, xy, thick, k, nn, loc, nl, da)
    tsa = sink - t_zero
    do ip = 1, 3
      ta = dot_product(nl(1:nn, ip), temp(loc(1:nn))) - t_zero
      do i = 1, nn
        fe(loc(i)) = fe(loc(i)) + nl(i, ip) * es * (tsa**4 - ta**4) * da(ip)
        do j = 1, nn
          re(loc(i), loc(j)) = re(loc(i), loc(j)) + nl(i, ip) * nl(j, ip) * 4.0_dp * es * ta**3 * da(ip)
        end do
      end do
    end do
  end subroutine heat_radiation_arrays

  !> The 3 Gauss points of face k of an element of type et: its nn
  !> nodes are the element's loc(1:nn), nl(1:nn, ip) their shape
  !> functions at point ip and da(ip) its weight times |dx/ds| times the
  !> thickness, or times 2 pi r (exact for a 3-node face and a linear
  !> thickness or radius).
  pure subroutine face_points(et, xy, thick, k, nn, loc, nl, da)
    integer, intent(in) :: et, k
    real(dp), intent(in) :: xy(:, :), thick(:)
    integer, intent(out) :: nn, loc(3)
    real(dp), intent(out) :: nl(3, 3), da(3)
    real(dp) :: s(3), w(3), ds(3), xe(2, 3), te(3), x(2), t(2)
    integer :: ip, j
    nn = edge_node_count(et, k)
    loc = catalogue(et)%edge(:, k)
    xe = 0.0_dp
    te = 0.0_dp
    do j = 1, nn
      xe(:, j) = xy(:, loc(j))
      te(j) = thick(loc(j))
    end do
    nl = 0.0_dp
    call gauss_line(3, s, w)
    do ip = 1, 3
      call line_shape(nn, s(ip), nl(:, ip), ds)
      x = matmul(xe(:, 1:nn), nl(1:nn, ip))
      t = matmul(xe(:, 1:nn), ds(1:nn))
      da(ip) = w(ip) * volume_factor(catalogue(et)%state, norm2(t), x(1), dot_product(nl(1:nn, ip), te(1:nn)))
    end do
  end subroutine face_points

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

  !> Purpose: the values of a material table tab(1 + nv, nt) (row 1 the
  !> temperatures, increasing; rows 2.. the values: k11, k22 of
  !> *CONDUCTIVITY, c of *SPECIFIC HEAT) at temperature t: linear between
  !> its points, constant beyond them.
  pure function table_at(tab, t) result(v)
    real(dp), intent(in) :: tab(:, :), t
    real(dp) :: v(size(tab, 1) - 1), s
    integer :: j, nt
    nt = size(tab, 2)
    if (.not. (t > tab(1, 1))) then
      v = tab(2:, 1)
    else if (t >= tab(1, nt)) then
      v = tab(2:, nt)
    else
      do j = 2, nt
        if (t <= tab(1, j)) exit
      end do
      s = (t - tab(1, j - 1)) / (tab(1, j) - tab(1, j - 1))
      v = tab(2:, j - 1) + s * (tab(2:, j) - tab(2:, j - 1))
    end if
  end function table_at

  !> Purpose: the conductivities (k11, k22) of a *CONDUCTIVITY table
  !> ktab(3, nk) at temperature t (table_at).
  pure function conductivity_at(ktab, t) result(k)
    real(dp), intent(in) :: ktab(:, :), t
    real(dp) :: k(2)
    k = table_at(ktab, t)
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
    detj = jacobian_det(jac, dn(:, 1:nen), xy(:, 1:nen))
    dx = 0.0_dp
    if (detj <= 0.0_dp) return
    jinv(1, 1) = jac(2, 2) / detj
    jinv(2, 2) = jac(1, 1) / detj
    jinv(1, 2) = -jac(1, 2) / detj
    jinv(2, 1) = -jac(2, 1) / detj
    dx(:, 1:nen) = matmul(jinv, dn(:, 1:nen))
  end subroutine physical_gradients
end module heat_element