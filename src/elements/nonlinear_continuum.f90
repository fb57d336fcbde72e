!> The continuum element of every catalogue shape with a nonlinear body:
!> large deformation (NLGEOM), a hyperelastic law or plasticity. The
!> linear elastic small-strain element stays continuum_element's, which
!> element_library calls unless is_nonlinear says otherwise.
!>
!> Finite strain (NLGEOM, and always for the hyperelastic laws, whose
!> energy is one of finite strain): total Lagrangian. ue is the total
!> displacement from the initial configuration X; at each integration
!> point
!>   F = I + sum_a u_a (x) dN_a/dX        (in-plane 2x2 block),
!>   F33 = 1 (plane strain), 1 + u_r / R (axisymmetry: the hoop stretch
!>   r / R), or solved from s33 = 0 by the material (plane stress),
!> and with G the matrix giving the five components (F11, F12, F21, F22,
!> F33) of dF from the nodal dofs,
!>   fe = integral G^T P dV0,  ke = integral G^T (dP/dF) G dV0
!> over the reference volume (thickness t0 dA0, or 2 pi R dA0 for the
!> whole ring as the linear element), P the first Piola-Kirchhoff
!> stress. dP/dF holds the material and the geometric (initial stress)
!> stiffness at once (Bonet and Wood 2008, ch. 8; Wriggers 2008, ch. 4).
!>
!> F-bar (de Souza Neto, Peric, Dutko and Owen 1996, Int. J. Solids
!> Struct. 33, 3277-3296; de Souza Neto et al. 2008, section 15.2) for
!> the 4-node quadrilateral in plane strain and axisymmetry with a
!> hyperelastic law or plasticity, whose isochoric response would
!> otherwise lock: the material sees Fbar = s F, s = (J0 / J)^(1/n), J0 =
!> det F at the element's centre, n = 2 (plane strain: the in-plane
!> block is scaled) or 3 (axisymmetry: all of F), and the internal force
!> is integral sigma(Fbar) : grad_x(du) dv, i.e. P_eff = (J / Jbar) tau(Fbar)
!> F^-T = s^(1 - n) P(Fbar). Its exact (unsymmetric) tangent:
!>   dP_eff = c s A dF + (c / n) [(1 - n) Pbar + s A F] (F0^-T : dF0 - F^-T : dF),
!> c = s^(1 - n), A = dP/dF at Fbar, dF0 the centre's dF.
!>
!> Small strain with plasticity (NLGEOM off): fe = integral B^T sig dV,
!> ke = integral B^T D B dV with the law's consistent tangent D; the
!> 4-node quadrilateral in plane strain and axisymmetry uses B-bar (the
!> small-strain F-bar: eps_bar = eps + (1/n) (tr eps0 - tr eps) m, m the
!> identity over the scaled components; Hughes 1980) against plastic
!> locking. The thermal strain alpha dT is subtracted from the strain
!> the law sees (small strain: eps - alpha dT (1, 1, 0, 1); finite strain,
!> St Venant-Kirchhoff only: the Lagrange strain of F - alpha dT I,
!> CalculiX 2.20's mechanical strain under NLGEOM; the hyperelastic laws and
!> finite-strain plasticity ignore it), so fe is the whole internal force
!> and act_thermal gives zero on this path.
!>
!> One-point quadrilaterals (CPS4R, CPE4R, CAX4R): one F (or small
!> strain), the element's mean (uniform_gradient, continuum_element's
!> uniform_strain), no F-bar, and continuum_element's hourglass
!> stabilization, corotational under finite strain and with elastic-
!> perfectly plastic modes under *PLASTIC (add_hourglass).
!>
!> Stresses (act_stresses): sig_ip the Cauchy stress (s11, s22, s33, s12)
!> (sigma = tau / det Fbar with F-bar), extrapolated to the nodes;
!> eps_ip the Green-Lagrange strain (E11, E22, 2 E12) under finite
!> strain, what CalculiX prints as E under NLGEOM ("total Lagrangian
!> strain", its manual), the small strain otherwise; peeq_ip the
!> equivalent plastic strain. Every action returns eout%hist, the
!> history at ue computed from ein%hist (read for *PLASTIC only: the
!> elastic laws have no history, zero).
!>
!> detj_min: the smallest reference det J (times R in axisymmetry) and,
!> under finite strain, that times det F, the current one: an element
!> turned inside out reports a non-positive value, and its points give
!> no force; so does (zero) a plane-stress point whose thickness stretch
!> could not be found, or NaN in ue. Arrays that are not finite (the laws
!> overflow at absurd deformations) are returned as zero with detj_min 0.
module nonlinear_continuum
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  use model, only: law_elastic
  use element_catalogue, only: max_nodes, max_ip, state_axisymmetric, state_plane_stress, shape_quad4, &
                               state_plane_strain
  use element_interface, only: elem_in_t, elem_out_t, act_tangent, act_residual, act_stresses, wants, max_hist
  use shape_functions, only: shape_at, gauss_rule, extrapolation, jacobian_det
  use continuum_element, only: volume_factor, strain_matrix, is_one_point_quad, uniform_strain, hourglass_modes, &
                               material_matrix
  use material_laws, only: material_response, hist_peeq, fc_i, fc_j, is_hyperelastic
  use small_matrices, only: det3, inv3
  implicit none
  private
  public :: nonlinear_continuum_element, is_nonlinear, thickness_stretch

contains

  !> Purpose: does this continuum element need the nonlinear routine
  !> (large deformation, a hyperelastic law or plasticity)?
  pure logical function is_nonlinear(ein)
    type(elem_in_t), intent(in) :: ein
    is_nonlinear = ein%nlgeom .or. ein%law /= law_elastic .or. ein%nyield > 0
  end function is_nonlinear

  !> Purpose: element arrays of a nonlinear continuum element.
  !> Arguments: action (act_* codes), ein (ue the total displacement,
  !> hist the committed history), eout: ke the consistent tangent and fe
  !> the internal force at ue, the stresses, strains and PEEQ at the
  !> integration points, hist the history at ue.
  pure subroutine nonlinear_continuum_element(action, ein, eout)
    integer, intent(in) :: action
    type(elem_in_t), intent(in) :: ein
    type(elem_out_t), intent(out) :: eout
    real(dp) :: ex(max_nodes, max_ip)
    integer :: nen, ip
    nen = ein%nen
    eout%ndof = 2 * nen
    eout%ke(1:eout%ndof, 1:eout%ndof) = 0.0_dp
    eout%nip = ein%nip
    if (ein%nlgeom .or. is_hyperelastic(ein)) then
      call finite_strain(ein, wants(action, act_tangent), eout)
    else
      call small_strain(ein, eout)
    end if
    if (is_one_point_quad(ein)) call add_hourglass(ein, eout)
    ! a deformation the laws cannot evaluate (NaN in ue, an overflow at an
    ! absurd stretch or volume ratio): no arrays, the history unchanged,
    ! and the element reported bad so that the driver cuts back
    if (.not. (eout%detj_min <= 0.0_dp .or. eout%detj_min > 0.0_dp) &
        .or. .not. finite_arrays(eout, 2 * nen, ein%nip)) then
      eout%detj_min = min(eout%detj_min, 0.0_dp)
      if (.not. eout%detj_min <= 0.0_dp) eout%detj_min = 0.0_dp
      eout%ke(1:eout%ndof, 1:eout%ndof) = 0.0_dp
      eout%fe = 0.0_dp
      eout%sig_ip = 0.0_dp
      eout%eps_ip = 0.0_dp
      eout%peeq_ip = 0.0_dp
      do ip = 1, ein%nip
        eout%hist(:, ip) = committed(ein, ip)
      end do
    end if
    if (.not. wants(action, act_tangent)) eout%ke(1:eout%ndof, 1:eout%ndof) = 0.0_dp
    if (.not. wants(action, act_residual)) eout%fe = 0.0_dp
    if (wants(action, act_stresses)) then
      call extrapolation(ein%kind, nen, ein%nip, ex)
      eout%sig_node(:, 1:nen) = matmul(eout%sig_ip(:, 1:ein%nip), transpose(ex(1:nen, 1:ein%nip)))
    else
      eout%sig_ip = 0.0_dp
      eout%eps_ip = 0.0_dp
    end if
  end subroutine nonlinear_continuum_element

  !> Purpose: the thickness stretch lambda3 = F33 of a plane-stress
  !> element at ue (F33 from s33 = 0 at each integration point, as
  !> finite_strain finds it), averaged over the element's reference
  !> volume, lambda3 = sum dV0 F33 / sum dV0, and its derivative
  !> dlam = d lambda3 / d ue (dF33 = sum_c dF33/dF_c G_c du at each point,
  !> the implicit derivative of P33 = 0 from material_response). The
  !> current thickness of the element's faces is t0 lambda3, on which a
  !> follower pressure acts (CalculiX expands a plane-stress element into
  !> a layer of 3D elements, whose faces thin with the material).
  !> lambda3 = 1 and dlam = 0 for any other element, on the small-strain
  !> path, and where a point has no thickness stretch (turned inside
  !> out, the local iteration failed, NaN: detj_min of the element
  !> routine reports these, and the driver cuts back).
  !> Arguments: ein as for nonlinear_continuum_element (ue, hist, dtemp);
  !> lam, dlam(2 * max_nodes) out.
  pure subroutine thickness_stretch(ein, lam, dlam)
    type(elem_in_t), intent(in) :: ein
    real(dp), intent(out) :: lam, dlam(2 * max_nodes)
    real(dp) :: xg(2, max_ip), wg(max_ip), n(max_nodes), dndx(2, max_nodes), detj, r, dv, eth, sw, swl
    real(dp) :: f(3, 3), g(5, 2 * max_nodes), p(5), a(5, 5), tau(3, 3), h(max_hist), d33(4), sdl(2 * max_nodes)
    integer :: ip, nd
    logical :: ok
    lam = 1.0_dp
    dlam = 0.0_dp
    if (ein%state /= state_plane_stress .or. .not. (ein%nlgeom .or. is_hyperelastic(ein))) return
    nd = 2 * ein%nen
    call gauss_rule(ein%kind, ein%nip, xg, wg)
    sw = 0.0_dp
    swl = 0.0_dp
    sdl = 0.0_dp
    do ip = 1, ein%nip
      call reference_point(ein, xg(:, ip), n, dndx, detj, r)
      dv = volume_factor(ein%state, detj, r, dot_product(n(1:ein%nen), ein%thickness(1:ein%nen))) * wg(ip)
      call deformation(ein, n, dndx, r, f, g)
      if (.not. (f(1, 1) * f(2, 2) - f(1, 2) * f(2, 1)) > 0.0_dp) return
      eth = ein%alpha * dot_product(n(1:ein%nen), ein%dtemp(1:ein%nen))
      if (ein%aniso) then
        call material_response(ein, ein%state, f, eth, committed(ein, ip), p, a, tau, h, ok, .true., d33, &
                               material_matrix(ein, matmul(ein%xy(:, 1:ein%nen), n(1:ein%nen)), state_plane_strain))
      else
        call material_response(ein, ein%state, f, eth, committed(ein, ip), p, a, tau, h, ok, .true., d33)
      end if
      if (.not. (ok .and. ieee_is_finite(f(3, 3)) .and. f(3, 3) > 0.0_dp)) return
      sw = sw + dv
      swl = swl + dv * f(3, 3)
      sdl(1:nd) = sdl(1:nd) + dv * matmul(d33, g(1:4, 1:nd))
    end do
    if (.not. (sw > 0.0_dp .and. ieee_is_finite(swl / sw) .and. all(ieee_is_finite(sdl(1:nd) / sw)))) return
    lam = swl / sw
    dlam(1:nd) = sdl(1:nd) / sw
  end subroutine thickness_stretch

  !> Purpose: are the element's arrays (ke, fe, stresses, strains,
  !> history at the points) all finite?
  !> Arguments: eout, nd its dofs, nip its integration points.
  pure logical function finite_arrays(eout, nd, nip)
    type(elem_out_t), intent(in) :: eout
    integer, intent(in) :: nd, nip
    finite_arrays = all(ieee_is_finite(eout%ke(1:nd, 1:nd))) .and. all(ieee_is_finite(eout%fe(1:nd))) .and. &
                    all(ieee_is_finite(eout%sig_ip(:, 1:nip))) .and. all(ieee_is_finite(eout%eps_ip(:, 1:nip))) .and. &
                    all(ieee_is_finite(eout%hist(:, 1:nip)))
  end function finite_arrays

  !> Purpose: the committed history of integration point ip: ein%hist
  !> for a law with state (*PLASTIC), zero for the elastic laws, whose
  !> callers need not define ein%hist (element_interface gives it no
  !> default, and the stiffness at setup is built without it).
  pure function committed(ein, ip) result(h)
    type(elem_in_t), intent(in) :: ein
    integer, intent(in) :: ip
    real(dp) :: h(max_hist)
    h = 0.0_dp
    if (ein%nyield > 0) h = ein%hist(:, ip)
  end function committed

  !> Does the element use F-bar / B-bar (see the module header)? Not the
  !> one-point quadrilateral, whose one point is the centre F-bar would
  !> take J0 from.
  pure logical function uses_fbar(ein)
    type(elem_in_t), intent(in) :: ein
    uses_fbar = ein%kind == shape_quad4 .and. ein%state /= state_plane_stress .and. ein%nip > 1 &
                .and. (ein%law /= law_elastic .or. ein%nyield > 0)
  end function uses_fbar

  !> Purpose: the hourglass stabilization of a one-point quadrilateral
  !> (continuum_element's hourglass_modes) on the nonlinear path, with the
  !> law's initial elastic constants: the amplitudes d = Gam ue (d_k =
  !> gamma . u_k), in the element's frame dl = R^T d, their curvatures
  !> kappa_j = dl . g_j and the peak bending stresses m_j = E' kappa_j, the
  !> force Gam^T q, q = R (V / 3) sum_j m_j g_j. Small strain: R = I.
  !> Finite strain, corotational: R(theta) the rotation of the polar
  !> decomposition of F at the centre, theta = atan2(F21 - F12, F11 + F22);
  !> the exact tangent of q is kr + (W q - kr W d) dtheta/du^T, kr = R
  !> (V / 3) sum_j E'_j g_j g_j^T R^T, W = dR/dtheta R^T the quarter turn
  !> (unsymmetric, as F-bar's). A rigid motion of any size is linear in X
  !> and has d = 0: no force. With *PLASTIC the modes are elastic-perfectly
  !> plastic at the point's yield stress (hourglass_yield), so that a
  !> plastic mechanism is not held up by them.
  !> Arguments: ein; eout, whose ke, fe (and with *PLASTIC hist(6:7, 1))
  !> it sets.
  pure subroutine add_hourglass(ein, eout)
    type(elem_in_t), intent(in) :: ein
    type(elem_out_t), intent(inout) :: eout
    real(dp), parameter :: w(2, 2) = reshape([0.0_dp, 1.0_dp, -1.0_dp, 0.0_dp], [2, 2])
    real(dp) :: e0, nu0, gam(4), gk(2, 2), vol, emod, rot(2, 2), gm(2, 8), d(2), kappa(2), m(2), et(2), q(2)
    real(dp) :: kr(2, 2), kd(2), nth(8), c, s, rr, n(max_nodes), dndx(2, max_nodes), detj, r, f(3, 3), &
                g(5, 2 * max_nodes)
    integer :: k
    call initial_moduli(ein, e0, nu0)
    call hourglass_modes(ein%xy(:, 1:4), ein%thickness(1:4), e0, nu0, ein%state, gam, gk, vol, emod)
    gm = 0.0_dp
    gm(1, 1:7:2) = gam
    gm(2, 2:8:2) = gam
    d = matmul(gm, ein%ue(1:8))
    rot = reshape([1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [2, 2])
    nth = 0.0_dp
    if (ein%nlgeom .or. is_hyperelastic(ein)) then
      call reference_point(ein, [0.0_dp, 0.0_dp], n, dndx, detj, r)
      call deformation(ein, n, dndx, r, f, g)
      c = f(1, 1) + f(2, 2)
      s = f(2, 1) - f(1, 2)
      rr = c**2 + s**2
      ! (rr = 0 only where det F <= 0: an element turned inside out, which
      ! the element reports; no rotation then)
      if (rr > 0.0_dp) then
        rot = reshape([c, s, -s, c], [2, 2]) / sqrt(rr)
        nth = (c * (g(3, 1:8) - g(2, 1:8)) - s * (g(1, 1:8) + g(4, 1:8))) / rr
      end if
    end if
    kappa = matmul(matmul(transpose(rot), d), gk)
    m = emod * kappa
    et = emod
    if (ein%nyield > 0) call hourglass_yield(ein, emod, kappa, eout%hist(:, 1), m, et)
    q = matmul(rot, matmul(gk, m)) * vol / 3.0_dp
    kr = matmul(rot, matmul(matmul(gk, matmul(reshape([et(1), 0.0_dp, 0.0_dp, et(2)], [2, 2]), &
                                              transpose(gk))), transpose(rot))) * vol / 3.0_dp
    kd = matmul(w, q) - matmul(kr, matmul(w, d))
    eout%fe(1:8) = eout%fe(1:8) + matmul(q, gm)
    eout%ke(1:8, 1:8) = eout%ke(1:8, 1:8) + matmul(transpose(gm), matmul(kr, gm))
    do k = 1, 8
      eout%ke(1:8, k) = eout%ke(1:8, k) + matmul(kd, gm) * nth(k)
    end do
  end subroutine add_hourglass

  !> Purpose: the hourglass modes of a one-point quadrilateral with
  !> *PLASTIC, elastic-perfectly plastic: each mode's peak bending stress
  !> m_j = E' (kappa_j - kp_j) is held to the yield stress of the point's
  !> PEEQ (its hardening table), kp_j the mode's plastic curvature, kept as
  !> history(6:7) of the point (material_laws leaves those entries to the
  !> element); the tangent E'_j is E' or, yielding, 0. Without this an
  !> elastic stabilization would carry a plastic mechanism's load without
  !> bound.
  !> Arguments: ein (the committed kp in ein%hist(6:7, 1)), emod E', kappa
  !> the curvatures; hist the point's history at ue (PEEQ read, kp written);
  !> m, et out.
  pure subroutine hourglass_yield(ein, emod, kappa, hist, m, et)
    type(elem_in_t), intent(in) :: ein
    real(dp), intent(in) :: emod, kappa(2)
    real(dp), intent(inout) :: hist(max_hist)
    real(dp), intent(out) :: m(2), et(2)
    real(dp) :: kp(2), sy, p
    integer :: j, k
    kp = ein%hist(6:7, 1)
    p = hist(hist_peeq)
    ! the yield stress at PEEQ p: the piecewise-linear table, constant
    ! beyond its last point
    k = count(ein%yield(2, 1:ein%nyield) <= p)
    if (k == 0) then
      sy = ein%yield(1, 1)
    else if (k >= ein%nyield) then
      sy = ein%yield(1, ein%nyield)
    else
      sy = ein%yield(1, k) + (ein%yield(1, k + 1) - ein%yield(1, k)) * (p - ein%yield(2, k)) / &
           (ein%yield(2, k + 1) - ein%yield(2, k))
    end if
    do j = 1, 2
      m(j) = emod * (kappa(j) - kp(j))
      et(j) = emod
      if (abs(m(j)) > sy) then
        m(j) = sign(sy, m(j))
        kp(j) = kappa(j) - m(j) / emod
        et(j) = 0.0_dp
      end if
    end do
    hist(6:7) = kp
  end subroutine hourglass_yield

  !> Purpose: Young's modulus and Poisson's ratio of the law at zero
  !> strain: *ELASTIC's, or of a hyperelastic law mu0 = 2 (C10 + C01) and
  !> K0 = 2 / D1 (D1 = 0 taking material_laws' default 0.1 / mu0):
  !> E0 = 9 K0 mu0 / (3 K0 + mu0), nu0 = (3 K0 - 2 mu0) / (2 (3 K0 + mu0)).
  !> Arguments: ein; e0, nu0 out.
  pure subroutine initial_moduli(ein, e0, nu0)
    type(elem_in_t), intent(in) :: ein
    real(dp), intent(out) :: e0, nu0
    real(dp) :: mu0, k0, d1
    e0 = ein%e
    nu0 = ein%nu
    if (.not. is_hyperelastic(ein)) return
    mu0 = 2.0_dp * (ein%c10 + ein%c01)
    d1 = ein%d1
    if (abs(d1) < 1e-10_dp) d1 = 0.1_dp / mu0
    k0 = 2.0_dp / d1
    e0 = 9.0_dp * k0 * mu0 / (3.0_dp * k0 + mu0)
    nu0 = (3.0_dp * k0 - 2.0_dp * mu0) / (2.0_dp * (3.0_dp * k0 + mu0))
  end subroutine initial_moduli

  !> Purpose: reference geometry at natural point xi: shape functions n,
  !> their derivatives dndx = dN/dX, det J and the radius R.
  pure subroutine reference_point(ein, xi, n, dndx, detj, r)
    type(elem_in_t), intent(in) :: ein
    real(dp), intent(in) :: xi(2)
    real(dp), intent(out) :: n(max_nodes), dndx(2, max_nodes), detj, r
    real(dp) :: dn(2, max_nodes), jac(2, 2), jinv(2, 2)
    integer :: nen
    nen = ein%nen
    call shape_at(ein%kind, xi, n, dn)
    jac = matmul(dn(:, 1:nen), transpose(ein%xy(:, 1:nen)))
    detj = jacobian_det(jac, dn(:, 1:nen), ein%xy(:, 1:nen))
    jinv = reshape([jac(2, 2), -jac(2, 1), -jac(1, 2), jac(1, 1)], [2, 2]) / detj
    dndx = 0.0_dp
    dndx(:, 1:nen) = matmul(jinv, dn(:, 1:nen))
    r = dot_product(n(1:nen), ein%xy(1, 1:nen))
  end subroutine reference_point

  !> Purpose: F at a point (F33 = 1 but in axisymmetry, 1 + u_r / R) and
  !> G(5, nd), dF = G du in the component order (F11, F12, F21, F22, F33);
  !> hoop, if given, the row of F33 (N_a / R at a point; uniform_gradient's
  !> mean of it for a one-point quadrilateral).
  pure subroutine deformation(ein, n, dndx, r, f, g, hoop)
    type(elem_in_t), intent(in) :: ein
    real(dp), intent(in) :: n(max_nodes), dndx(2, max_nodes), r
    real(dp), intent(out) :: f(3, 3), g(5, 2 * max_nodes)
    real(dp), intent(in), optional :: hoop(max_nodes)
    integer :: a, c
    f = 0.0_dp
    f(3, 3) = 1.0_dp
    g = 0.0_dp
    do c = 1, 4
      do a = 1, ein%nen
        g(c, 2 * (a - 1) + fc_i(c)) = dndx(fc_j(c), a)
      end do
    end do
    if (ein%state == state_axisymmetric) then
      do a = 1, ein%nen
        if (present(hoop)) then
          g(5, 2 * a - 1) = hoop(a)
        else
          g(5, 2 * a - 1) = n(a) / r
        end if
      end do
    end if
    do c = 1, 5
      f(fc_i(c), fc_j(c)) = f(fc_i(c), fc_j(c)) + dot_product(g(c, 1:2 * ein%nen), ein%ue(1:2 * ein%nen))
    end do
    f(1, 1) = f(1, 1) + 1.0_dp
    f(2, 2) = f(2, 2) + 1.0_dp
  end subroutine deformation

  !> Purpose: the one point of a one-point quadrilateral under finite
  !> strain is the element's mean, as on the small-strain path
  !> (continuum_element's uniform_strain): dndx = (1/V0) int dN/dX dV0,
  !> n = (1/V0) int N dV0, hoop = (1/V0) int N / R dV0 (the F33 row in
  !> axisymmetry), dv = V0, so that F is the element's mean F (dF is linear
  !> in the dofs). In plane states dndx is its value at the centre.
  !> Arguments: ein; n, dndx, hoop, dv out.
  pure subroutine uniform_gradient(ein, n, dndx, hoop, dv)
    type(elem_in_t), intent(in) :: ein
    real(dp), intent(out) :: n(max_nodes), dndx(2, max_nodes), hoop(max_nodes), dv
    real(dp) :: xg(2, max_ip), wg(max_ip), np(max_nodes), dnx(2, max_nodes), detj, r, w
    integer :: ip
    call gauss_rule(shape_quad4, 4, xg, wg)
    n = 0.0_dp
    dndx = 0.0_dp
    hoop = 0.0_dp
    dv = 0.0_dp
    do ip = 1, 4
      call reference_point(ein, xg(:, ip), np, dnx, detj, r)
      w = volume_factor(ein%state, detj, r, dot_product(np(1:4), ein%thickness(1:4))) * wg(ip)
      n = n + np * w
      dndx = dndx + dnx * w
      if (ein%state == state_axisymmetric) hoop = hoop + np / r * w
      dv = dv + w
    end do
    n = n / dv
    dndx = dndx / dv
    hoop = hoop / dv
  end subroutine uniform_gradient

  !> The five components of a 3x3 tensor.
  pure function comps(t) result(v)
    real(dp), intent(in) :: t(3, 3)
    real(dp) :: v(5)
    integer :: c
    do c = 1, 5
      v(c) = t(fc_i(c), fc_j(c))
    end do
  end function comps

  !> Purpose: the total Lagrangian element (module header).
  !> Arguments: ein, tangent (false: fe, stresses and history only, ke
  !> left zero; the laws then skip their derivatives), eout.
  pure subroutine finite_strain(ein, tangent, eout)
    type(elem_in_t), intent(in) :: ein
    logical, intent(in) :: tangent
    type(elem_out_t), intent(inout) :: eout
    real(dp) :: xg(2, max_ip), wg(max_ip), n(max_nodes), dndx(2, max_nodes), detj, r, dv, t_ip, vol, vinv
    real(dp) :: f(3, 3), g(5, 2 * max_nodes), p(5), a(5, 5), tau(3, 3), jac, j0, cg(3, 3), eth, w0(2 * max_nodes)
    real(dp) :: hoop(max_nodes)
    integer :: ip, nd, nexp
    logical :: fbar, ok
    nd = 2 * ein%nen
    fbar = uses_fbar(ein)
    j0 = 1.0_dp
    nexp = 2
    if (ein%state == state_axisymmetric) nexp = 3
    if (fbar) call fbar_centre(ein, j0, w0)
    call gauss_rule(ein%kind, ein%nip, xg, wg)
    eout%detj_min = huge(1.0_dp)
    do ip = 1, ein%nip
      call reference_point(ein, xg(:, ip), n, dndx, detj, r)
      vol = detj
      if (ein%state == state_axisymmetric) vol = detj * r
      t_ip = dot_product(n(1:ein%nen), ein%thickness(1:ein%nen))
      if (ein%state /= state_axisymmetric .and. .not. t_ip > 0.0_dp) vol = min(vol, t_ip)
      eout%detj_min = min(eout%detj_min, vol)
      dv = volume_factor(ein%state, detj, r, t_ip) * wg(ip)
      if (is_one_point_quad(ein)) then
        call uniform_gradient(ein, n, dndx, hoop, dv)
        call deformation(ein, n, dndx, r, f, g, hoop)
      else
        call deformation(ein, n, dndx, r, f, g)
      end if
      eth = ein%alpha * dot_product(n(1:ein%nen), ein%dtemp(1:ein%nen))
      eout%hist(:, ip) = committed(ein, ip)
      jac = (f(1, 1) * f(2, 2) - f(1, 2) * f(2, 1)) * f(3, 3)
      if (.not. jac > 0.0_dp .or. (fbar .and. .not. j0 > 0.0_dp)) then
        ! turned inside out (or NaN in ue: reported as zero, which min
        ! would not do): no force, reported through detj_min
        vinv = vol * min(jac, merge(j0, jac, fbar))
        if (.not. vinv <= 0.0_dp) vinv = 0.0_dp
        eout%detj_min = min(eout%detj_min, vinv)
        cycle
      end if
      if (fbar) then
        call fbar_point(ein, ip, tangent, f, g, dv, eth, j0, w0, nexp, eout, tau, jac, ok)
      else
        if (ein%aniso) then
          ! St Venant-Kirchhoff in the material's axes at the reference point
          call material_response(ein, ein%state, f, eth, committed(ein, ip), p, a, tau, eout%hist(:, ip), ok, &
                                 tangent, dmat=material_matrix(ein, matmul(ein%xy(:, 1:ein%nen), n(1:ein%nen)), &
                                                               state_plane_strain))
        else
          call material_response(ein, ein%state, f, eth, committed(ein, ip), p, a, tau, eout%hist(:, ip), ok, tangent)
        end if
        eout%fe(1:nd) = eout%fe(1:nd) + matmul(p, g(:, 1:nd)) * dv
        if (tangent) eout%ke(1:nd, 1:nd) = eout%ke(1:nd, 1:nd) &
                                           + matmul(transpose(g(:, 1:nd)), matmul(a, g(:, 1:nd))) * dv
        jac = det3(f)
      end if
      ! the current volume element (det F of the point itself, F33 solved
      ! in plane stress); zero where the plane-stress condition failed
      eout%detj_min = min(eout%detj_min, vol * det3(f))
      if (.not. ok) eout%detj_min = min(eout%detj_min, 0.0_dp)
      eout%peeq_ip(ip) = eout%hist(hist_peeq, ip)
      eout%sig_ip(:, ip) = [tau(1, 1), tau(2, 2), tau(3, 3), tau(1, 2)] / jac
      cg = matmul(transpose(f), f)
      eout%eps_ip(:, ip) = [0.5_dp * (cg(1, 1) - 1.0_dp), 0.5_dp * (cg(2, 2) - 1.0_dp), cg(1, 2)]
    end do
  end subroutine finite_strain

  !> Purpose: what F-bar needs of the element's centre: J0 = det F0 and,
  !> where J0 > 0, the row w0 = F0^-T : dF0 over the dofs (the same at
  !> every point; w0 is left undefined otherwise, where every point gives
  !> no force).
  !> Arguments: ein; j0, w0(2 * max_nodes) out.
  pure subroutine fbar_centre(ein, j0, w0)
    type(elem_in_t), intent(in) :: ein
    real(dp), intent(out) :: j0, w0(2 * max_nodes)
    real(dp) :: n(max_nodes), dndx(2, max_nodes), detj, r, f0(3, 3), g0(5, 2 * max_nodes)
    integer :: nd
    nd = 2 * ein%nen
    call reference_point(ein, [0.0_dp, 0.0_dp], n, dndx, detj, r)
    call deformation(ein, n, dndx, r, f0, g0)
    j0 = det3(f0)
    if (j0 > 0.0_dp) w0(1:nd) = matmul(comps(transpose(inv3(f0))), g0(:, 1:nd))
  end subroutine fbar_centre

  !> Purpose: one integration point of the F-bar element (module header):
  !> the material at Fbar = s F, s = (J0 / J)^(1/n), its force c P(Fbar)
  !> (c = s^(1 - n)) and exact tangent added to eout%fe and eout%ke, the
  !> point's history in eout%hist(:, ip).
  !> Arguments: ein, ip the point, tangent (ke wanted), f and g the point's
  !> F and dF/du, dv its reference volume, eth its thermal strain, j0 and
  !> w0 from fbar_centre, nexp (2 plane strain, 3 axisymmetry); eout
  !> inout; tau the Kirchhoff stress of Fbar, jac = det Fbar and ok (the
  !> law's answer) out.
  pure subroutine fbar_point(ein, ip, tangent, f, g, dv, eth, j0, w0, nexp, eout, tau, jac, ok)
    type(elem_in_t), intent(in) :: ein
    integer, intent(in) :: ip, nexp
    logical, intent(in) :: tangent
    real(dp), intent(in) :: f(3, 3), g(5, 2 * max_nodes), dv, eth, j0, w0(2 * max_nodes)
    type(elem_out_t), intent(inout) :: eout
    real(dp), intent(out) :: tau(3, 3), jac
    logical, intent(out) :: ok
    real(dp) :: fb(3, 3), s, c, v(5), fm(5), p(5), a(5, 5), kmat(5, 2 * max_nodes), wd(2 * max_nodes)
    integer :: nd, k
    nd = 2 * ein%nen
    jac = (f(1, 1) * f(2, 2) - f(1, 2) * f(2, 1)) * f(3, 3)
    s = (j0 / jac)**(1.0_dp / nexp)
    fb = f
    fb(1:2, 1:2) = s * f(1:2, 1:2)
    if (nexp == 3) fb(3, 3) = s * f(3, 3)
    call material_response(ein, ein%state, fb, eth, committed(ein, ip), p, a, tau, eout%hist(:, ip), ok, tangent)
    c = s**(1 - nexp)
    eout%fe(1:nd) = eout%fe(1:nd) + matmul(c * p, g(:, 1:nd)) * dv
    if (tangent) then
      fm = comps(f)
      if (nexp == 2) fm(5) = 0.0_dp
      v = (c / nexp) * ((1 - nexp) * p + s * matmul(a, fm))
      wd(1:nd) = w0(1:nd) - matmul(comps(transpose(inv3(f))), g(:, 1:nd))
      kmat(:, 1:nd) = c * s * matmul(a, g(:, 1:nd))
      do k = 1, nd
        kmat(:, k) = kmat(:, k) + v * wd(k)
      end do
      eout%ke(1:nd, 1:nd) = eout%ke(1:nd, 1:nd) + matmul(transpose(g(:, 1:nd)), kmat(:, 1:nd)) * dv
    end if
    jac = det3(fb)
  end subroutine fbar_point

  !> Purpose: the small-strain element with a law with state (module
  !> header), B-bar for the 4-node quadrilateral in plane strain and
  !> axisymmetry.
  pure subroutine small_strain(ein, eout)
    type(elem_in_t), intent(in) :: ein
    type(elem_out_t), intent(inout) :: eout
    real(dp) :: xg(2, max_ip), wg(max_ip), n(max_nodes), dn(2, max_nodes), b(4, 2 * max_nodes), &
                b0(4, 2 * max_nodes), bv0(2 * max_nodes), m(4), detj, r, dv, t_ip, eps(4), eps0(4), sig(4), &
                d(4, 4), vol
    integer :: ip, nd, nen, nexp
    logical :: bbar
    nen = ein%nen
    nd = 2 * nen
    bbar = uses_fbar(ein)
    m = [1.0_dp, 1.0_dp, 0.0_dp, 0.0_dp]
    nexp = 2
    if (ein%state == state_axisymmetric) then
      m(4) = 1.0_dp
      nexp = 3
    end if
    if (bbar) then
      call shape_at(ein%kind, [0.0_dp, 0.0_dp], n, dn)
      call strain_matrix(nen, ein%xy(:, 1:nen), n(1:nen), dn(:, 1:nen), ein%state, b0(:, 1:nd), detj, r)
      bv0(1:nd) = matmul(m, b0(:, 1:nd))
    end if
    call gauss_rule(ein%kind, ein%nip, xg, wg)
    eout%detj_min = huge(1.0_dp)
    do ip = 1, ein%nip
      call shape_at(ein%kind, xg(:, ip), n, dn)
      call strain_matrix(nen, ein%xy(:, 1:nen), n(1:nen), dn(:, 1:nen), ein%state, b(:, 1:nd), detj, r)
      vol = detj
      if (ein%state == state_axisymmetric) vol = detj * r
      t_ip = dot_product(n(1:nen), ein%thickness(1:nen))
      if (ein%state /= state_axisymmetric .and. .not. t_ip > 0.0_dp) vol = min(vol, t_ip)
      eout%detj_min = min(eout%detj_min, vol)
      dv = volume_factor(ein%state, detj, r, t_ip) * wg(ip)
      eps0 = ein%alpha * dot_product(n(1:nen), ein%dtemp(1:nen)) * [1.0_dp, 1.0_dp, 0.0_dp, 1.0_dp]
      if (is_one_point_quad(ein)) call uniform_strain(ein, n, b(:, 1:nd), dv, eps0)
      if (bbar) b(:, 1:nd) = b(:, 1:nd) + spread(m, 2, nd) * spread(bv0(1:nd) - matmul(m, b(:, 1:nd)), 1, 4) / nexp
      eps = matmul(b(:, 1:nd), ein%ue(1:nd))
      call material_response(ein, ein%state, eps - eps0, committed(ein, ip), sig, d, eout%hist(:, ip))
      eout%fe(1:nd) = eout%fe(1:nd) + matmul(sig, b(:, 1:nd)) * dv
      eout%ke(1:nd, 1:nd) = eout%ke(1:nd, 1:nd) + matmul(transpose(b(:, 1:nd)), matmul(d, b(:, 1:nd))) * dv
      eout%peeq_ip(ip) = eout%hist(hist_peeq, ip)
      eout%sig_ip(:, ip) = [sig(1), sig(2), sig(4), sig(3)]
      eout%eps_ip(:, ip) = eps(1:3)
    end do
  end subroutine small_strain
end module nonlinear_continuum
