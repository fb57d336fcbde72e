!> Consistent nodal loads of distributed loads on one continuum element:
!> a pressure on a face (straight or curved, two or three nodes) and a
!> body force per unit volume that may vary linearly in space (gravity, a
!> constant body force, a centrifugal load), the latter also on a truss
!> (over its length times its area). Forces are integrated over
!> the thickness (interpolated from the element's nodal thicknesses, along
!> the face for a pressure), or over the whole circumference (2 pi r) for
!> axisymmetric elements, as the element matrices.
!>
!> Under large deformation (NLGEOM) a pressure follows the deformed face:
!> follower_pressure_load gives its nodal forces on the current
!> configuration and their derivative, the load stiffness.
module distributed_loads
  use kinds, only: dp
  use element_catalogue, only: catalogue, max_nodes, max_ip, edge_node_count, is_line, state_axisymmetric
  use shape_functions, only: shape_at, line_shape, truss_shape, gauss_line, gauss_rule, load_rule
  use continuum_element, only: volume_factor
  implicit none
  private
  public :: face_pressure_load, body_force_load, follower_pressure_load

  real(dp), parameter :: two_pi = 6.283185307179586476925286766559_dp

contains

  !> Purpose: nodal forces f(2, nodes) of a unit pressure on face k of an
  !> element of catalogue type et with nodes at xy; a positive pressure
  !> pushes into the element (against the outward normal), as Abaqus Pk.
  !> thickness(nodes) holds the element's nodal thicknesses. Three Gauss
  !> points along the face: exact for a curved 3-node face in plane and
  !> axisymmetric elements, and for a thickness quadratic along it.
  pure subroutine face_pressure_load(et, xy, thickness, k, f)
    integer, intent(in) :: et, k
    real(dp), intent(in) :: xy(:, :), thickness(:)
    real(dp), intent(out) :: f(2, max_nodes)
    real(dp) :: s(3), w(3), n(3), ds(3), xe(2, 3), te(3), x(2), t(2), dw
    integer :: nn, ip, j, loc(3)
    f = 0.0_dp
    nn = edge_node_count(et, k)
    loc = catalogue(et)%edge(:, k)
    xe = 0.0_dp
    te = 0.0_dp
    do j = 1, nn
      xe(:, j) = xy(:, loc(j))
      te(j) = thickness(loc(j))
    end do
    call gauss_line(3, s, w)
    do ip = 1, 3
      call line_shape(nn, s(ip), n, ds)
      x = matmul(xe, n)
      t = matmul(xe, ds)          ! dx/ds; (t2, -t1) is the outward normal times |dx/ds|
      dw = w(ip) * volume_factor(catalogue(et)%state, 1.0_dp, x(1), dot_product(n(1:nn), te(1:nn)))
      do j = 1, nn
        f(:, loc(j)) = f(:, loc(j)) - n(j) * dw * [t(2), -t(1)]
      end do
    end do
  end subroutine face_pressure_load

  !> Purpose: a unit pressure on face k that follows the deformation: its
  !> nodal forces f(2, nodes) on the current face (nodes at xy + u) and
  !> the load stiffness kl = df/du (2 nodes x 2 nodes, dof 2 (a - 1) + i
  !> for direction i of local node a; unsymmetric in general). A pressure
  !> p adds p f to the external forces and -p kl to the tangent of the
  !> residual f_int - f_ext (Bonet and Wood 2008, section 8.5 in 2D).
  !> Arguments: et catalogue type, xy reference coordinates, u nodal
  !> displacements, thickness nodal thicknesses the face acts on (the
  !> reference ones, as the linear load; in plane stress the driver
  !> passes the current t0 lambda3, nonlinear_continuum's
  !> thickness_stretch, and adds the term of d lambda3 / du itself;
  !> axisymmetric: the whole ring, 2 pi r with the current radius r), k
  !> the face. At u = 0, f is face_pressure_load's.
  !> With t = dx/ds along the face and n~ = (t2, -t1) (the outward normal
  !> times |dx/ds|),
  !>   f_a = - sum_ip w N_a v(x) n~,  v = thickness or 2 pi x1,
  !>   df_a/du_b = - sum_ip w N_a (v dn~/du_b + n~ dv/du_b),
  !> dn~/du_b1 = (0, -dN_b/ds), dn~/du_b2 = (dN_b/ds, 0), dv/du_b1 =
  !> 2 pi N_b in axisymmetry.
  pure subroutine follower_pressure_load(et, xy, u, thickness, k, f, kl)
    integer, intent(in) :: et, k
    real(dp), intent(in) :: xy(:, :), u(:, :), thickness(:)
    real(dp), intent(out) :: f(2, max_nodes), kl(2 * max_nodes, 2 * max_nodes)
    real(dp) :: s(3), w(3), n(3), ds(3), xe(2, 3), te(3), x(2), t(2), v, dv1, nt(2), dnt(2, 2)
    integer :: nn, ip, a, b, loc(3), nen, ra, cb
    nen = catalogue(et)%nodes
    call face_pressure_load(et, xy(:, 1:nen) + u(:, 1:nen), thickness, k, f)
    kl = 0.0_dp
    nn = edge_node_count(et, k)
    loc = catalogue(et)%edge(:, k)
    xe = 0.0_dp
    te = 0.0_dp
    do a = 1, nn
      xe(:, a) = xy(:, loc(a)) + u(:, loc(a))
      te(a) = thickness(loc(a))
    end do
    call gauss_line(3, s, w)
    do ip = 1, 3
      call line_shape(nn, s(ip), n, ds)
      x = matmul(xe, n)
      t = matmul(xe, ds)
      nt = [t(2), -t(1)]
      v = volume_factor(catalogue(et)%state, 1.0_dp, x(1), dot_product(n(1:nn), te(1:nn)))
      ! dv/dx1: 2 pi in axisymmetry (v = 2 pi x1), 0 otherwise
      dv1 = 0.0_dp
      if (catalogue(et)%state == state_axisymmetric) dv1 = two_pi
      do b = 1, nn
        ! columns: d n~ / d u_b1 and d n~ / d u_b2
        dnt(:, 1) = [0.0_dp, -ds(b)]
        dnt(:, 2) = [ds(b), 0.0_dp]
        do a = 1, nn
          ra = 2 * (loc(a) - 1)
          cb = 2 * (loc(b) - 1)
          kl(ra + 1:ra + 2, cb + 1:cb + 2) = kl(ra + 1:ra + 2, cb + 1:cb + 2) - w(ip) * n(a) * v * dnt
          kl(ra + 1:ra + 2, cb + 1) = kl(ra + 1:ra + 2, cb + 1) - w(ip) * n(a) * dv1 * n(b) * nt
        end do
      end do
    end do
  end subroutine follower_pressure_load

  !> Purpose: nodal forces f(2, nodes) of the body force per unit volume
  !> b(x) = b0 + g (x - xc) over an element of catalogue type et with nodes
  !> at xy with nodal thicknesses thickness(nodes) (load_rule's points:
  !> exact for a linear b on undistorted elements, the radius of
  !> axisymmetric elements included).
  pure subroutine body_force_load(et, xy, thickness, b0, g, xc, f)
    integer, intent(in) :: et
    real(dp), intent(in) :: xy(:, :), thickness(:), b0(2), g(2, 2), xc(2)
    real(dp), intent(out) :: f(2, max_nodes)
    real(dp) :: xg(2, max_ip), wg(max_ip), n(max_nodes), dn(2, max_nodes), jac(2, 2), x(2), b(2), dv
    integer :: ip, k, nen, nip, shape
    f = 0.0_dp
    shape = catalogue(et)%shape
    nen = catalogue(et)%nodes
    if (is_line(shape)) then
      call truss_body_force_load(nen, xy, thickness(1), b0, g, xc, f)
      return
    end if
    nip = load_rule(shape)
    call gauss_rule(shape, nip, xg, wg)
    do ip = 1, nip
      call shape_at(shape, xg(:, ip), n, dn)
      jac = matmul(dn(:, 1:nen), transpose(xy(:, 1:nen)))
      x = matmul(xy(:, 1:nen), n(1:nen))
      b = b0 + matmul(g, x - xc)
      dv = wg(ip) * volume_factor(catalogue(et)%state, jac(1, 1) * jac(2, 2) - jac(1, 2) * jac(2, 1), &
                                  x(1), dot_product(n(1:nen), thickness(1:nen)))
      do k = 1, nen
        f(:, k) = f(:, k) + n(k) * dv * b
      end do
    end do
  end subroutine body_force_load

  !> Purpose: nodal forces f(2, nen) of the body force per unit volume
  !> b(x) = b0 + g (x - xc) over a truss of nen = 2 or 3 nodes at xy
  !> (Abaqus order: end, middle, end) and cross-sectional area `area`:
  !> the integral of N_k b A along its arc, three Gauss points (exact for
  !> a linear b on a straight truss).
  pure subroutine truss_body_force_load(nen, xy, area, b0, g, xc, f)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xy(:, :), area, b0(2), g(2, 2), xc(2)
    real(dp), intent(inout) :: f(2, max_nodes)
    real(dp) :: s(3), w(3), n(3), dn(3), x(2), dxds(2), b(2)
    integer :: ip, k
    call gauss_line(3, s, w)
    do ip = 1, 3
      call truss_shape(nen, s(ip), n, dn)
      x = matmul(xy(:, 1:nen), n(1:nen))
      dxds = matmul(xy(:, 1:nen), dn(1:nen))
      b = b0 + matmul(g, x - xc)
      do k = 1, nen
        f(:, k) = f(:, k) + n(k) * b * (area * norm2(dxds) * w(ip))
      end do
    end do
  end subroutine truss_body_force_load
end module distributed_loads
