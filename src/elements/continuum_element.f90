!> The isoparametric continuum element of every catalogue shape (3- and
!> 6-node triangles, 4- and 8-node quadrilaterals) in the three stress
!> states: plane stress, plane strain and axisymmetry. The shape, the
!> integration rule (number of points) and the stress state come from the
!> element's catalogue entry.
!>
!> Axisymmetric elements: r = x, z = y; the strains are (e_rr, e_zz,
!> gamma_rz, e_hoop) with the hoop strain u_r / r, and S33 is the hoop
!> stress. Their matrices are integrated over the whole circumference,
!> dV = 2 pi r dA, as CalculiX and Abaqus count axisymmetric forces: a
!> concentrated load, a reaction and a contact force are totals over the
!> ring (the section thickness is not used).
!>
!> Plane elements: the thickness is interpolated from its nodal values
!> with the shape functions (*NODAL THICKNESS may vary inside an
!> element); a constant thickness is the same at every node.
!>
!> Thermal strain eps0 = alpha dT (1, 1, 0, 1), dT interpolated from the
!> nodal temperature changes, is an initial strain: stresses D (eps -
!> eps0), load integral B^T D eps0. The fourth component is the
!> out-of-plane strain: in plane stress D has no such row (S33 = 0); in
!> plane strain it gives S33 = nu (S11 + S22) - E alpha dT; in axisymmetry
!> it is the hoop strain.
!>
!> One-point quadrilaterals (CPS4R, CPE4R, CAX4R: the bilinear shape with
!> nip = 1) take one strain, the element's mean (uniform_strain; in plane
!> states the strain at the centre), and one stress, which leaves
!> the two hourglass modes (u = d xi eta, d a vector) without stiffness;
!> hourglass_stiffness gives them the stiffness they have in pure bending
!> (the stresses stay those of the one point, as in CalculiX and Abaqus,
!> and its value is every node's).
module continuum_element
  use kinds, only: dp
  use element_catalogue, only: max_nodes, max_ip, state_axisymmetric, state_plane_stress, shape_quad4
  use element_interface, only: elem_in_t, elem_out_t, act_tangent, act_residual, act_stresses, &
                               act_thermal, wants
  use shape_functions, only: shape_at, gauss_rule, extrapolation, quad4_shape, jacobian_det
  use materials, only: elastic_matrix, rotate_stiffness, state_matrix, orientation_axes
  implicit none
  private
  public :: material_matrix
  public :: continuum, volume_factor, strain_matrix, is_one_point_quad, uniform_strain, hourglass_modes, &
            hourglass_stiffness

  real(dp), parameter :: two_pi = 6.283185307179586476925286766559_dp

contains

  !> Purpose: the strain-displacement matrix at one point from the shape
  !> functions n and their natural derivatives dn; rows (e11, e22, gamma12,
  !> e33), the last the hoop strain u_r / r in axisymmetry and zero
  !> otherwise. Returns det J and the radius r = sum N_k x_k.
  pure subroutine strain_matrix(nen, xy, n, dn, state, b, detj, r)
    integer, intent(in) :: nen, state
    real(dp), intent(in) :: xy(2, nen), n(nen), dn(2, nen)
    real(dp), intent(out) :: b(4, 2 * nen), detj, r
    real(dp) :: jac(2, 2), jinv(2, 2), dx(2, nen)
    integer :: k
    jac = matmul(dn, transpose(xy))
    detj = jacobian_det(jac, dn, xy)
    jinv(1, 1) = jac(2, 2) / detj
    jinv(2, 2) = jac(1, 1) / detj
    jinv(1, 2) = -jac(1, 2) / detj
    jinv(2, 1) = -jac(2, 1) / detj
    dx = matmul(jinv, dn)
    r = dot_product(n, xy(1, :))
    b = 0.0_dp
    do k = 1, nen
      b(1, 2 * k - 1) = dx(1, k)
      b(2, 2 * k) = dx(2, k)
      b(3, 2 * k - 1) = dx(2, k)
      b(3, 2 * k) = dx(1, k)
      if (state == state_axisymmetric) b(4, 2 * k - 1) = n(k) / r
    end do
  end subroutine strain_matrix

  !> Purpose: volume per unit of natural area at a point: det J times the
  !> thickness, or 2 pi r det J in axisymmetry.
  pure real(dp) function volume_factor(state, detj, r, thickness)
    integer, intent(in) :: state
    real(dp), intent(in) :: detj, r, thickness
    if (state == state_axisymmetric) then
      volume_factor = two_pi * r * detj
    else
      volume_factor = detj * thickness
    end if
  end function volume_factor

  !> Purpose: element arrays of a continuum element.
  !> Arguments: action (act_* codes), ein (kind = catalogue shape, nip =
  !> catalogue rule, state), eout: ke and fe = ke ue for act_tangent /
  !> act_residual; for act_stresses the strains and stresses at the
  !> integration points and the stresses extrapolated to the nodes
  !> (shape_functions' extrapolation: exact for a stress field of the
  !> rule's own degree), less the thermal strain's share; for act_thermal
  !> fe = the equivalent nodal load of the thermal strain.
  pure subroutine continuum(action, ein, eout)
    integer, intent(in) :: action
    type(elem_in_t), intent(in) :: ein
    type(elem_out_t), intent(out) :: eout
    real(dp) :: d(4, 4), n(max_nodes), dn(2, max_nodes), b(4, 2 * max_nodes), db(4, 2 * max_nodes)
    real(dp) :: xg(2, max_ip), wg(max_ip), ex(max_nodes, max_ip), detj, r, eps(4), sig(4), eps0(4), dv, t_ip
    integer :: ip, i, j, nen, nd
    logical :: need_k
    nen = ein%nen
    nd = 2 * nen
    need_k = wants(action, act_tangent) .or. wants(action, act_residual)
    d = elastic_matrix(ein%e, ein%nu, ein%state)
    eout%ndof = nd
    eout%ke(1:nd, 1:nd) = 0.0_dp
    eout%nip = ein%nip
    call gauss_rule(ein%kind, ein%nip, xg, wg)
    eout%detj_min = huge(1.0_dp)
    do ip = 1, ein%nip
      call shape_at(ein%kind, xg(:, ip), n, dn)
      call strain_matrix(nen, ein%xy(:, 1:nen), n(1:nen), dn(:, 1:nen), ein%state, b(:, 1:nd), detj, r)
      if (ein%state == state_axisymmetric) then
        eout%detj_min = min(eout%detj_min, detj * r)
      else
        eout%detj_min = min(eout%detj_min, detj)
      end if
      eps0 = ein%alpha * dot_product(n(1:nen), ein%dtemp(1:nen)) * [1.0_dp, 1.0_dp, 0.0_dp, 1.0_dp]
      t_ip = dot_product(n(1:nen), ein%thickness(1:nen))
      ! a NODAL THICKNESS that a quadratic element interpolates below zero
      ! (its corner functions dip under zero) is flagged as a bad Jacobian
      if (ein%state /= state_axisymmetric .and. .not. t_ip > 0.0_dp) eout%detj_min = min(eout%detj_min, t_ip)
      dv = volume_factor(ein%state, detj, r, t_ip) * wg(ip)
      if (is_one_point_quad(ein)) call uniform_strain(ein, n, b(:, 1:nd), dv, eps0)
      if (ein%aniso) d = material_matrix(ein, matmul(ein%xy(:, 1:nen), n(1:nen)), ein%state)
      if (wants(action, act_thermal)) eout%fe(1:nd) = eout%fe(1:nd) + matmul(matmul(eps0, d), b(:, 1:nd)) * dv
      if (need_k) then
        ! upper triangle of B^T D B, mirrored below after the loop
        db(:, 1:nd) = matmul(d, b(:, 1:nd)) * dv
        do j = 1, nd
          do i = 1, j
            eout%ke(i, j) = eout%ke(i, j) + b(1, i) * db(1, j) + b(2, i) * db(2, j) + b(3, i) * db(3, j) &
                            + b(4, i) * db(4, j)
          end do
        end do
      end if
      if (wants(action, act_stresses)) then
        eps = matmul(b(:, 1:nd), ein%ue(1:nd))
        sig = matmul(d, eps - eps0)
        eout%eps_ip(:, ip) = eps(1:3)
        eout%sig_ip(:, ip) = [sig(1), sig(2), sig(4), sig(3)]
      end if
    end do
    if (need_k) then
      do j = 1, nd - 1
        eout%ke(j + 1:nd, j) = eout%ke(j, j + 1:nd)
      end do
      if (is_one_point_quad(ein)) eout%ke(1:8, 1:8) = eout%ke(1:8, 1:8) + &
          hourglass_stiffness(ein%xy(:, 1:4), ein%thickness(1:4), ein%e, ein%nu, ein%state)
    end if
    if (wants(action, act_residual)) eout%fe(1:nd) = matmul(eout%ke(1:nd, 1:nd), ein%ue(1:nd))
    if (.not. wants(action, act_tangent)) eout%ke(1:nd, 1:nd) = 0.0_dp
    if (wants(action, act_stresses)) then
      call extrapolation(ein%kind, nen, ein%nip, ex)
      eout%sig_node(:, 1:nen) = matmul(eout%sig_ip(:, 1:ein%nip), transpose(ex(1:nen, 1:ein%nip)))
    end if
  end subroutine continuum

  !> Purpose: the 4x4 stress-strain matrix of an anisotropic material
  !> (ein%aniso) at the point xp: its stiffness turned from the axes of its
  !> *ORIENTATION there to the global ones, in the element's stress state
  !> (materials: rotate_stiffness, state_matrix). Without orientation
  !> the material axes are the global ones.
  !> Arguments: ein (c6, orient_*), xp the point (global x, y; reference
  !> coordinates under NLGEOM), state the stress state (the element's;
  !> plane strain for St Venant-Kirchhoff, whose law meets s33 = 0 itself).
  pure function material_matrix(ein, xp, state) result(d)
    type(elem_in_t), intent(in) :: ein
    real(dp), intent(in) :: xp(2)
    integer, intent(in) :: state
    real(dp) :: d(4, 4), q(3, 3)
    if (ein%orient_system == 0) then
      d = state_matrix(ein%c6, state)
    else
      q = orientation_axes(ein%orient_system, ein%orient_a, ein%orient_b, ein%orient_axis, ein%orient_angle, &
                           [xp, 0.0_dp])
      d = state_matrix(rotate_stiffness(ein%c6, q), state)
    end if
  end function material_matrix

  !> Purpose: is the element a one-point bilinear quadrilateral (CPS4R,
  !> CPE4R, CAX4R), which needs hourglass_stiffness?
  pure logical function is_one_point_quad(ein)
    type(elem_in_t), intent(in) :: ein
    is_one_point_quad = ein%kind == shape_quad4 .and. ein%nip == 1
  end function is_one_point_quad

  !> Purpose: the one point of a one-point quadrilateral is the element's
  !> mean (the uniform strain element, Flanagan and Belytschko 1981,
  !> section 3): b = (1/V) int B dV, n = (1/V) int N dV, dv = V and the
  !> thermal strain eps0 of the mean temperature change, integrated by
  !> the 2x2 rule, exact for a bilinear shape. In plane states b is B at
  !> the centre; in axisymmetry (dV = 2 pi r dA) it is not, and the mean
  !> is what keeps the constant-strain patch test exact.
  !> Arguments: ein; n(max_nodes), b(4, 8), dv, eps0(4) out.
  pure subroutine uniform_strain(ein, n, b, dv, eps0)
    type(elem_in_t), intent(in) :: ein
    real(dp), intent(out) :: n(max_nodes), b(4, 8), dv, eps0(4)
    real(dp) :: xg(2, max_ip), wg(max_ip), np(max_nodes), dn(2, max_nodes), bp(4, 8), detj, r, w
    integer :: ip
    call gauss_rule(shape_quad4, 4, xg, wg)
    n = 0.0_dp
    b = 0.0_dp
    dv = 0.0_dp
    do ip = 1, 4
      call shape_at(shape_quad4, xg(:, ip), np, dn)
      call strain_matrix(4, ein%xy(:, 1:4), np(1:4), dn(:, 1:4), ein%state, bp, detj, r)
      w = volume_factor(ein%state, detj, r, dot_product(np(1:4), ein%thickness(1:4))) * wg(ip)
      n = n + np * w
      b = b + bp * w
      dv = dv + w
    end do
    n = n / dv
    b = b / dv
    eps0 = ein%alpha * dot_product(n(1:4), ein%dtemp(1:4)) * [1.0_dp, 1.0_dp, 0.0_dp, 1.0_dp]
  end subroutine uniform_strain

  !> Purpose: hourglass stabilization of the one-point bilinear
  !> quadrilateral, the stiffness of its two hourglass modes: the
  !> displacement fields d xi eta (d = (d1, d2)) that give no strain at the
  !> centre, as the element has them in pure bending when its other strains
  !> are relaxed (an assumed-strain stabilization in the spirit of
  !> Belytschko and Bindeman 1991, Comput. Methods Appl. Mech. Engrg. 88,
  !> 311-340, "ASQBI", and of Abaqus's HOURGLASS=ENHANCED, derived here).
  !> The amplitudes are d_k = gamma . u_k (u_k the nodal values of
  !> displacement component k) with
  !>   gamma = (h - (h.x) b_x - (h.y) b_y) / 4,  h = (1, -1, 1, -1),
  !> b = dN/dx at the centre (Flanagan and Belytschko 1981, Int. J. Numer.
  !> Meth. Engng 17, 679-706, eq. 55-56): gamma is orthogonal to every
  !> linear field, so the constant-strain patch test is untouched, and
  !> gamma . h = 1. The energy of the mode is that of its bending strains
  !> alone, the normal strain along grad xi of eta d . grad xi and along
  !> grad eta of xi d . grad eta, with the uniaxial modulus E' (E in plane
  !> stress, E / (1 - nu^2) in plane strain and axisymmetry) and int eta^2
  !> dV = V / 3:
  !>   W = (E' V / 6) ((d . g1)^2 + (d . g2)^2) = (1/2) d^T k2 d,
  !>   k2 = (E' V / 3) (g1 g1^T + g2 g2^T),
  !> g1 = grad xi, g2 = grad eta at the centre. For a rectangle 2a x 2b
  !> this is E' V / (3 a^2) on the mode along x: pure bending is exact, as
  !> with the incompatible-mode element QM6. V = A t (t at the centre),
  !> 2 pi r0 A in axisymmetry (r0 the centre's radius). Parameter-free: the
  !> material's elastic constants set it.
  !> Arguments: xy the corner coordinates, thickness at the corners, e and
  !> nu the (initial) elastic constants, state; out: gam (gamma), g (its
  !> columns g1 = grad xi and g2 = grad eta at the centre), vol (V) and
  !> emod (E'), so that k2 = (emod vol / 3) g g^T.
  pure subroutine hourglass_modes(xy, thickness, e, nu, state, gam, g, vol, emod)
    real(dp), intent(in) :: xy(2, 4), thickness(4), e, nu
    integer, intent(in) :: state
    real(dp), intent(out) :: gam(4), g(2, 2), vol, emod
    real(dp), parameter :: h(4) = [1.0_dp, -1.0_dp, 1.0_dp, -1.0_dp]
    real(dp) :: n(4), dn(2, 4), jac(2, 2), jinv(2, 2), detj, b(2, 4)
    call quad4_shape(0.0_dp, 0.0_dp, n, dn)
    jac = matmul(dn, transpose(xy))
    detj = jac(1, 1) * jac(2, 2) - jac(1, 2) * jac(2, 1)
    jinv = reshape([jac(2, 2), -jac(2, 1), -jac(1, 2), jac(1, 1)], [2, 2]) / detj
    ! b = dN/dx at the centre; grad xi, grad eta are the columns of jinv
    b = matmul(jinv, dn)
    gam = 0.25_dp * (h - dot_product(h, xy(1, :)) * b(1, :) - dot_product(h, xy(2, :)) * b(2, :))
    emod = e
    if (state /= state_plane_stress) emod = e / (1.0_dp - nu**2)
    vol = volume_factor(state, 4.0_dp * detj, dot_product(n, xy(1, :)), dot_product(n, thickness))
    g = jinv
  end subroutine hourglass_modes

  !> Purpose: the 8x8 stiffness of hourglass_modes on the element dofs
  !> (u1, v1, ..., u4, v4): k2 (x) gamma gamma^T.
  !> Arguments: as hourglass_modes.
  pure function hourglass_stiffness(xy, thickness, e, nu, state) result(k)
    real(dp), intent(in) :: xy(2, 4), thickness(4), e, nu
    integer, intent(in) :: state
    real(dp) :: k(8, 8), gam(4), g(2, 2), vol, emod, k2(2, 2)
    integer :: i, j
    call hourglass_modes(xy, thickness, e, nu, state, gam, g, vol, emod)
    k2 = emod * vol / 3.0_dp * matmul(g, transpose(g))
    do j = 1, 4
      do i = 1, 4
        k(2 * i - 1:2 * i, 2 * j - 1:2 * j) = k2 * gam(i) * gam(j)
      end do
    end do
  end function hourglass_stiffness
end module continuum_element
