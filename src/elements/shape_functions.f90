!> Shape functions of the catalogue's shapes in natural coordinates, their
!> Gauss rules, and the extrapolation of integration-point values to the
!> nodes. Natural coordinates: quadrilaterals (xi, eta) in [-1, 1]^2 with
!> corner 1 at (-1, -1) counter-clockwise; triangles (xi, eta) = area
!> coordinates of corners 2 and 3 (corner 1 at the origin). Lines: s in
!> [-1, 1] from the first corner to the second, nodes (corner, corner,
!> middle) as the catalogue lists an edge.
module shape_functions
  use kinds, only: dp
  use element_catalogue, only: max_nodes, max_ip, shape_tri3, shape_quad4, shape_tri6, shape_quad8, &
                               is_triangle
  implicit none
  private
  public :: shape_at, quad4_shape, tri3_shape, line_shape, truss_shape, gauss_rule, gauss_line, load_rule, &
            extrapolation, jacobian_det

  real(dp), parameter :: xi_node(8) = [-1.0_dp, 1.0_dp, 1.0_dp, -1.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, -1.0_dp]
  real(dp), parameter :: eta_node(8) = [-1.0_dp, -1.0_dp, 1.0_dp, 1.0_dp, -1.0_dp, 0.0_dp, 1.0_dp, 0.0_dp]
  real(dp), parameter :: tri_xi(6) = [0.0_dp, 1.0_dp, 0.0_dp, 0.5_dp, 0.5_dp, 0.0_dp]
  real(dp), parameter :: tri_eta(6) = [0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 0.5_dp, 0.5_dp]

contains

  pure subroutine quad4_shape(xi, eta, n, dn)
    real(dp), intent(in) :: xi, eta
    real(dp), intent(out) :: n(4), dn(2, 4)
    integer :: k
    do k = 1, 4
      n(k) = 0.25_dp * (1.0_dp + xi * xi_node(k)) * (1.0_dp + eta * eta_node(k))
      dn(1, k) = 0.25_dp * xi_node(k) * (1.0_dp + eta * eta_node(k))
      dn(2, k) = 0.25_dp * eta_node(k) * (1.0_dp + xi * xi_node(k))
    end do
  end subroutine quad4_shape

  !> Area coordinates: N1 = 1 - xi - eta, N2 = xi, N3 = eta.
  pure subroutine tri3_shape(xi, eta, n, dn)
    real(dp), intent(in) :: xi, eta
    real(dp), intent(out) :: n(3), dn(2, 3)
    n = [1.0_dp - xi - eta, xi, eta]
    dn(1, :) = [-1.0_dp, 1.0_dp, 0.0_dp]
    dn(2, :) = [-1.0_dp, 0.0_dp, 1.0_dp]
  end subroutine tri3_shape

  !> The 6-node triangle: corners L(2L-1), mid-sides 4 La Lb.
  pure subroutine tri6_shape(xi, eta, n, dn)
    real(dp), intent(in) :: xi, eta
    real(dp), intent(out) :: n(6), dn(2, 6)
    real(dp) :: l1, l2, l3
    l1 = 1.0_dp - xi - eta
    l2 = xi
    l3 = eta
    n = [l1 * (2 * l1 - 1), l2 * (2 * l2 - 1), l3 * (2 * l3 - 1), 4 * l1 * l2, 4 * l2 * l3, 4 * l3 * l1]
    ! d/dxi and d/deta with dL1 = (-1, -1), dL2 = (1, 0), dL3 = (0, 1)
    dn(1, :) = [1 - 4 * l1, 4 * l2 - 1, 0.0_dp, 4 * (l1 - l2), 4 * l3, -4 * l3]
    dn(2, :) = [1 - 4 * l1, 0.0_dp, 4 * l3 - 1, -4 * l2, 4 * l2, 4 * (l1 - l3)]
  end subroutine tri6_shape

  !> The 8-node serendipity quadrilateral.
  pure subroutine quad8_shape(xi, eta, n, dn)
    real(dp), intent(in) :: xi, eta
    real(dp), intent(out) :: n(8), dn(2, 8)
    real(dp) :: a, b
    integer :: k
    do k = 1, 4
      a = xi_node(k)
      b = eta_node(k)
      n(k) = 0.25_dp * (1 + a * xi) * (1 + b * eta) * (a * xi + b * eta - 1)
      dn(1, k) = 0.25_dp * a * (1 + b * eta) * (2 * a * xi + b * eta)
      dn(2, k) = 0.25_dp * b * (1 + a * xi) * (a * xi + 2 * b * eta)
    end do
    do k = 5, 7, 2          ! mid-sides on eta = -1, +1
      b = eta_node(k)
      n(k) = 0.5_dp * (1 - xi**2) * (1 + b * eta)
      dn(1, k) = -xi * (1 + b * eta)
      dn(2, k) = 0.5_dp * b * (1 - xi**2)
    end do
    do k = 6, 8, 2          ! mid-sides on xi = +1, -1
      a = xi_node(k)
      n(k) = 0.5_dp * (1 + a * xi) * (1 - eta**2)
      dn(1, k) = 0.5_dp * a * (1 - eta**2)
      dn(2, k) = -eta * (1 + a * xi)
    end do
  end subroutine quad8_shape

  !> Purpose: shape functions n and their natural derivatives dn (d/dxi,
  !> d/deta) of a shape at xi; entries beyond the shape's nodes are zero.
  pure subroutine shape_at(shape, xi, n, dn)
    integer, intent(in) :: shape
    real(dp), intent(in) :: xi(2)
    real(dp), intent(out) :: n(max_nodes), dn(2, max_nodes)
    n = 0.0_dp
    dn = 0.0_dp
    select case (shape)
    case (shape_tri3); call tri3_shape(xi(1), xi(2), n(1:3), dn(:, 1:3))
    case (shape_quad4); call quad4_shape(xi(1), xi(2), n(1:4), dn(:, 1:4))
    case (shape_tri6); call tri6_shape(xi(1), xi(2), n(1:6), dn(:, 1:6))
    case (shape_quad8); call quad8_shape(xi(1), xi(2), n(1:8), dn(:, 1:8))
    end select
  end subroutine shape_at

  !> Purpose: natural coordinates of local node k of a shape.
  pure function natural_of_node(shape, k) result(xi)
    integer, intent(in) :: shape, k
    real(dp) :: xi(2)
    if (is_triangle(shape)) then
      xi = [tri_xi(k), tri_eta(k)]
    else
      xi = [xi_node(k), eta_node(k)]
    end if
  end function natural_of_node

  !> Purpose: a 2- or 3-node line at s in [-1, 1]: nodes (first corner,
  !> second corner, middle); ds the derivatives d/ds.
  pure subroutine line_shape(nn, s, n, ds)
    integer, intent(in) :: nn
    real(dp), intent(in) :: s
    real(dp), intent(out) :: n(3), ds(3)
    if (nn == 3) then
      n = [0.5_dp * s * (s - 1), 0.5_dp * s * (s + 1), 1 - s**2]
      ds = [s - 0.5_dp, s + 0.5_dp, -2 * s]
    else
      n = [0.5_dp * (1 - s), 0.5_dp * (1 + s), 0.0_dp]
      ds = [-0.5_dp, 0.5_dp, 0.0_dp]
    end if
  end subroutine line_shape

  !> Purpose: line_shape in the node order of a line element of the deck
  !> (a 3-node one lists end, middle, end, as Abaqus does).
  pure subroutine truss_shape(nn, s, n, ds)
    integer, intent(in) :: nn
    real(dp), intent(in) :: s
    real(dp), intent(out) :: n(3), ds(3)
    call line_shape(nn, s, n, ds)
    if (nn == 3) then
      n = n([1, 3, 2])
      ds = ds([1, 3, 2])
    end if
  end subroutine truss_shape

  !> Purpose: Gauss-Legendre points s and weights w on [-1, 1], n = 1..3.
  pure subroutine gauss_line(n, s, w)
    integer, intent(in) :: n
    real(dp), intent(out) :: s(3), w(3)
    s = 0.0_dp
    w = 0.0_dp
    select case (n)
    case (1)
      w(1) = 2.0_dp
    case (2)
      s(1:2) = [-1.0_dp, 1.0_dp] / sqrt(3.0_dp)
      w(1:2) = 1.0_dp
    case default
      s = [-sqrt(0.6_dp), 0.0_dp, sqrt(0.6_dp)]
      w = [5.0_dp, 8.0_dp, 5.0_dp] / 9.0_dp
    end select
  end subroutine gauss_line

  !> Purpose: the integration rule of nip points of a shape: natural
  !> coordinates xi(2, nip), weights w(nip) (a triangle's weights sum to
  !> its natural area 1/2). Quadrilaterals: 1 point (the centre, weight
  !> 4: the reduced-integration CPS4R family), 2x2 with xi fastest, 3x3 row
  !> by row (xi fastest);
  !> triangles: 1 point (centroid), 3 points (degree 2, at the mid-points
  !> of the lines from the centroid to the corners), 6 points (degree 4).
  pure subroutine gauss_rule(shape, nip, xi, w)
    integer, intent(in) :: shape, nip
    real(dp), intent(out) :: xi(2, max_ip), w(max_ip)
    real(dp) :: s(3), ws(3), g
    integer :: i, j
    xi = 0.0_dp
    w = 0.0_dp
    if (is_triangle(shape)) then
      call triangle_rule(nip, xi, w)
    else if (nip == 1) then
      w(1) = 4.0_dp
    else if (nip == 4) then
      ! xi fastest, then eta, as the 3x3 rule and as Abaqus and CalculiX
      ! number the points (what *EL PRINT lists point by point)
      g = 1.0_dp / sqrt(3.0_dp)
      do j = 1, 2
        do i = 1, 2
          xi(:, 2 * (j - 1) + i) = g * [real(2 * i - 3, dp), real(2 * j - 3, dp)]
        end do
      end do
      w(1:4) = 1.0_dp
    else
      call gauss_line(3, s, ws)
      do j = 1, 3
        do i = 1, 3
          xi(:, 3 * (j - 1) + i) = [s(i), s(j)]
          w(3 * (j - 1) + i) = ws(i) * ws(j)
        end do
      end do
    end if
  end subroutine gauss_rule

  pure subroutine triangle_rule(nip, xi, w)
    integer, intent(in) :: nip
    real(dp), intent(out) :: xi(2, max_ip), w(max_ip)
    ! degree-4 rule (Strang and Fix): two orbits of three points
    real(dp), parameter :: a1 = 0.445948490915965_dp, w1 = 0.223381589678011_dp, &
                           a2 = 0.091576213509771_dp, w2 = 0.109951743655322_dp
    select case (nip)
    case (1)
      xi(:, 1) = [1.0_dp, 1.0_dp] / 3.0_dp
      w(1) = 0.5_dp
    case (3)
      xi(:, 1:3) = reshape([1.0_dp, 1.0_dp, 4.0_dp, 1.0_dp, 1.0_dp, 4.0_dp] / 6.0_dp, [2, 3])
      w(1:3) = 1.0_dp / 6.0_dp
    case default
      xi(:, 1:6) = reshape([a1, a1, 1 - 2 * a1, a1, a1, 1 - 2 * a1, &
                            a2, a2, 1 - 2 * a2, a2, a2, 1 - 2 * a2], [2, 6])
      w(1:3) = 0.5_dp * w1
      w(4:6) = 0.5_dp * w2
    end select
  end subroutine triangle_rule

  !> Purpose: the rule for load vectors (body forces, centrifugal loads):
  !> exact for the shape functions times a linear load times the radius of
  !> an axisymmetric element on an undistorted element (2x2 for the
  !> bilinear quadrilateral, 3x3 for the 8-node one, 6 points for triangles).
  pure integer function load_rule(shape)
    integer, intent(in) :: shape
    select case (shape)
    case (shape_quad4); load_rule = 4
    case (shape_quad8); load_rule = 9
    case default; load_rule = 6
    end select
  end function load_rule

  !> Weights w(1:6) such that sum w_i v_i is the value at xi of the
  !> complete quadratic through the values v_i at the six points of the
  !> degree-4 triangle rule.
  pure function quadratic_fit_weights(xi) result(w)
    real(dp), intent(in) :: xi(2)
    real(dp) :: w(6), a(6, 6), xg(2, max_ip), wg(max_ip), f, tmp(6)
    integer :: i, j, piv
    call triangle_rule(6, xg, wg)
    ! solve V^T w = q(xi) with V(i, :) the quadratic basis at point i
    do i = 1, 6
      a(:, i) = quadratic_basis(xg(:, i))
    end do
    w = quadratic_basis(xi)
    do j = 1, 6                       ! Gaussian elimination, partial pivoting
      piv = j - 1 + maxloc(abs(a(j:6, j)), 1)
      tmp = a(j, :)
      a(j, :) = a(piv, :)
      a(piv, :) = tmp
      f = w(j)
      w(j) = w(piv)
      w(piv) = f
      do i = j + 1, 6
        f = a(i, j) / a(j, j)
        a(i, j:6) = a(i, j:6) - f * a(j, j:6)
        w(i) = w(i) - f * w(j)
      end do
    end do
    do j = 6, 1, -1
      w(j) = (w(j) - dot_product(a(j, j + 1:6), w(j + 1:6))) / a(j, j)
    end do
  end function quadratic_fit_weights

  pure function quadratic_basis(xi) result(q)
    real(dp), intent(in) :: xi(2)
    real(dp) :: q(6)
    q = [1.0_dp, xi(1), xi(2), xi(1)**2, xi(1) * xi(2), xi(2)**2]
  end function quadratic_basis

  !> Purpose: extrapolation of integration-point values to the nodes,
  !> v_node(k) = sum_i e(k, i) v_ip(i), for the rule of nip points. The
  !> values at the points are interpolated by the polynomial of the rule's
  !> own grid and evaluated at the node: 1 point constant; 3 triangle
  !> points linear; 6 triangle points quadratic; 2x2 bilinear; 3x3
  !> biquadratic (Lagrange through the 3x3 Gauss points). A field of that
  !> degree is reproduced exactly.
  pure subroutine extrapolation(shape, nnode, nip, e)
    integer, intent(in) :: shape, nnode, nip
    real(dp), intent(out) :: e(max_nodes, max_ip)
    real(dp) :: xi(2), n(4), dn(2, 4), s, t, ls(3), lt(3)
    integer :: k, i, j
    e = 0.0_dp
    do k = 1, nnode
      xi = natural_of_node(shape, k)
      if (nip == 1) then
        e(k, 1) = 1.0_dp
      else if (is_triangle(shape) .and. nip == 3) then
        ! the three points (1/6, 1/6), (2/3, 1/6), (1/6, 2/3) as a triangle
        ! of their own: its area coordinates at the node
        s = 2.0_dp * xi(1) - 1.0_dp / 3.0_dp
        t = 2.0_dp * xi(2) - 1.0_dp / 3.0_dp
        e(k, 1:3) = [1.0_dp - s - t, s, t]
      else if (is_triangle(shape)) then
        e(k, 1:6) = quadratic_fit_weights(xi)
      else if (nip == 4) then
        ! the bilinear through the points, numbered as gauss_rule numbers them
        call quad4_shape(sqrt(3.0_dp) * xi(1), sqrt(3.0_dp) * xi(2), n, dn)
        e(k, 1:4) = [n(1), n(2), n(4), n(3)]
      else
        s = xi(1) / sqrt(0.6_dp)
        t = xi(2) / sqrt(0.6_dp)
        ls = [0.5_dp * s * (s - 1), 1 - s**2, 0.5_dp * s * (s + 1)]
        lt = [0.5_dp * t * (t - 1), 1 - t**2, 0.5_dp * t * (t + 1)]
        do j = 1, 3
          do i = 1, 3
            e(k, 3 * (j - 1) + i) = ls(i) * lt(j)
          end do
        end do
      end if
    end do
  end subroutine extrapolation
  !> Purpose: det J = det(dN X^T), and exactly zero where it is below
  !> 1e-10 of the size the element's nodes give it (the sums of |dN/dxi|
  !> and |dN/deta| times the nodes' distances from their centroid): there
  !> its sign is round-off (a degenerate element: a mid-side node moved
  !> onto a corner makes dx/dxi vanish at an integration point, computed
  !> as 1e-17 of either sign), which the optimised and the debug builds
  !> decided differently (fuzz seed 23 mutant 736: one build refused the
  !> element, the other ran on to a singular stiffness). Zero is what
  !> the element checks refuse.
  !> Arguments: jac the Jacobian dN X^T; dn(2, nen) the natural
  !> derivatives and xy(2, nen) the nodes it was made from.
  pure real(dp) function jacobian_det(jac, dn, xy) result(detj)
    real(dp), intent(in) :: jac(2, 2), dn(:, :), xy(:, :)
    real(dp) :: c(2), a, b, d
    integer :: k
    detj = jac(1, 1) * jac(2, 2) - jac(1, 2) * jac(2, 1)
    c = sum(xy, dim=2) / size(xy, 2)
    a = 0.0_dp
    b = 0.0_dp
    do k = 1, size(xy, 2)
      d = norm2(xy(:, k) - c)
      a = a + abs(dn(1, k)) * d
      b = b + abs(dn(2, k)) * d
    end do
    if (abs(detj) <= 1.0e-10_dp * a * b) detj = 0.0_dp
  end function jacobian_det
end module shape_functions
