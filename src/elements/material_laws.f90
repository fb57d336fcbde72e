!> Material laws with state for the nonlinear continuum elements: one
!> generic interface, material_response, with a small-strain form (strain
!> vector in, stress vector and tangent matrix out) and a finite-strain
!> form (deformation gradient in, first Piola-Kirchhoff stress and its
!> derivative dP/dF out). Both read the constants from the element data
!> (elem_in_t: e, nu, law, c10, c01, d1, nyield, yield) and take the
!> history committed by the last converged increment; they return the
!> trial history at the given strain without touching the committed one,
!> so that every Newton iteration of an increment starts from the same
!> state.
!>
!> Laws (docs/nonlinear.md, "Elements and materials"):
!> - *ELASTIC under NLGEOM: St Venant-Kirchhoff, S = D E with D the
!>   isotropic elastic_matrix (or an anisotropic material's matrix at the
!>   point, given as dmat) and E the Green-Lagrange strain (CalculiX's
!>   reading of *ELASTIC with NLGEOM).
!> - NEO HOOKE and MOONEY-RIVLIN with CalculiX's strain energy
!>   W = C10 (I1bar - 3) + C01 (I2bar - 3) + (J - 1)^2 / D1, I1bar, I2bar
!>   the invariants of bbar = J^(-2/3) b; D1 = 0 (|D1| < 1e-10) takes
!>   CalculiX's default 0.1 / mu0, mu0 = 2 (C10 + C01), the compressibility
!>   of an initial Poisson ratio of 0.475 (hyperelastics.f).
!> - *DEFORMATION PLASTICITY: Ramberg-Osgood by J2 deformation theory
!>   (module deformation_plasticity), a nonlinear elastic law without
!>   history: sig(eps) at small strain; under NLGEOM the Cauchy stress
!>   as the same function of the Euler-Almansi strain, CalculiX 2.20's
!>   reading (almansi_ramberg_osgood).
!> - *PLASTIC: von Mises with isotropic hardening on the piecewise-linear
!>   table yield(1, k) (yield stress) at yield(2, k) (equivalent plastic
!>   strain), perfectly plastic beyond its last point; radial return with
!>   the consistent (algorithmic) tangent (Simo and Taylor 1985; de Souza
!>   Neto, Peric and Owen 2008, Box 7.3-7.4). Finite strain: the
!>   multiplicative split F = Fe Fp with a Hencky (logarithmic) elastic
!>   law, tau = K tr(eps_e) I + 2 mu dev(eps_e), eps_e = ln(be) / 2, and
!>   the exponential-map return, which in the logarithmic strain is the
!>   small-strain radial return (Eterovic and Bathe 1990; Simo 1992; de
!>   Souza Neto et al. 2008, section 14.5).
!>
!> History per integration point (max_hist = 8 entries):
!>   small strain:  hist(1:4) = plastic strain eps_p (11, 22, 33, 12 as a
!>                  tensor component), hist(5) = PEEQ;
!>   finite strain: hist(1:4) = Cp^-1 - I (11, 22, 33, 12), Cp^-1 the
!>                  inverse plastic right Cauchy-Green tensor, so that a
!>                  zero history is the virgin state; hist(5) = PEEQ;
!>   hist(6:8) not the law's: it copies them through (nonlinear_continuum
!>   keeps the plastic hourglass curvatures of a one-point quadrilateral in
!>   hist(6:7); zero otherwise). Elastic laws keep the history unchanged
!>   (nonlinear_continuum gives them a zero one).
!>
!> Plane stress: the out-of-plane strain (small strain) or stretch F33
!> (finite strain) is found from s33 = 0, in closed form for the elastic
!> laws where it exists (St Venant-Kirchhoff, linear elasticity) and by a
!> local Newton iteration otherwise; the tangent is condensed (the
!> implicit function of s33 = 0), exact for the consistent tangent.
module material_laws
  use kinds, only: dp
  use small_matrices, only: det3, inv3
  use model, only: law_elastic, law_neo_hooke, law_mooney_rivlin, law_deformation_plasticity
  use element_catalogue, only: state_plane_stress, state_plane_strain
  use element_interface, only: elem_in_t, max_hist
  use materials, only: elastic_matrix
  use deformation_plasticity, only: ramberg_osgood
  implicit none
  private
  public :: material_response, hist_peeq, fc_i, fc_j, is_hyperelastic

  !> material_response(ein, state, eps, hist_in, sig, d, hist_out) small
  !> strain; material_response(ein, state, f, eth, hist_in, p, a, tau,
  !> hist_out, ok[, tangent]) finite strain.
  interface material_response
    module procedure small_strain_response, finite_strain_response
  end interface material_response

  !> Where PEEQ lives in the history.
  integer, parameter :: hist_peeq = 5
  !> The five components of F in a 2D continuum (the others are zero):
  !> (F11, F12, F21, F22, F33), component c = F(fc_i(c), fc_j(c)).
  integer, parameter :: fc_i(5) = [1, 1, 2, 2, 3], fc_j(5) = [1, 2, 1, 2, 3]
  real(dp), parameter :: eye(3, 3) = reshape([1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, &
                                              0.0_dp, 0.0_dp, 1.0_dp], [3, 3])
  !> Local Newton iterations on the plane-stress condition; it converges
  !> quadratically from the elastic estimate, this is a safeguard.
  integer, parameter :: max_local = 50

  !> The state of a radial return at one point: the trial stress, the
  !> plastic multiplier, the coefficients of the algorithmic tangent
  !> dsig = K tr(deps) I + c1 dev(deps) + c2 (nhat : deps) nhat.
  type :: return_t
    real(dp) :: sig(3, 3) = 0.0_dp
    real(dp) :: dgamma = 0.0_dp, peeq = 0.0_dp
    real(dp) :: flow(3, 3) = 0.0_dp     ! (3/2) dev sig_trial / q_trial
    real(dp) :: nhat(3, 3) = 0.0_dp     ! dev sig_trial / |dev sig_trial|
    real(dp) :: k = 0.0_dp, c1 = 0.0_dp, c2 = 0.0_dp
  end type return_t

contains

  !> Purpose: is the element's law hyperelastic (an energy of finite
  !> strain, so always on the finite-strain path, and its initial moduli
  !> not e and nu)?
  !> Arguments: ein the element data (its law).
  pure logical function is_hyperelastic(ein)
    type(elem_in_t), intent(in) :: ein
    is_hyperelastic = ein%law == law_neo_hooke .or. ein%law == law_mooney_rivlin
  end function is_hyperelastic

  ! ------------------------------------------------------------------
  ! Small strain
  ! ------------------------------------------------------------------

  !> Purpose: stress and tangent of the small-strain law at a point.
  !> Arguments: ein (constants, *PLASTIC table), state (element_catalogue
  !> stress state), eps(4) the mechanical strain (e11, e22, gamma12, e33)
  !> as the B matrix rows less the thermal strain (e33: the hoop strain in
  !> axisymmetry, minus the thermal strain in plane strain; in plane
  !> stress it is not used but solved from s33 = 0),
  !> hist_in the committed history; sig(4) = (s11, s22, s12, s33), d(4, 4)
  !> the consistent tangent dsig/deps (plane stress: condensed, its fourth
  !> row and column zero), hist_out the history at eps.
  pure subroutine small_strain_response(ein, state, eps, hist_in, sig, d, hist_out)
    type(elem_in_t), intent(in) :: ein
    integer, intent(in) :: state
    real(dp), intent(in) :: eps(4), hist_in(max_hist)
    real(dp), intent(out) :: sig(4), d(4, 4), hist_out(max_hist)
    real(dp) :: e(4), de33
    integer :: it
    e = eps
    if (state == state_plane_stress) then
      if (ein%nyield == 0 .and. ein%law == law_elastic) then
        d = elastic_matrix(ein%e, ein%nu, state_plane_stress)
        sig = matmul(d, [eps(1:3), 0.0_dp])
        hist_out = hist_in
        return
      end if
      ! e33 from s33 = 0 by Newton on the full law, started from the
      ! elastic estimate -nu / (1 - nu) (e11 + e22 - plastic part)
      e(4) = -ein%nu / (1.0_dp - ein%nu) * (eps(1) + eps(2) - hist_in(1) - hist_in(2)) + hist_in(3)
      do it = 1, max_local
        call small_strain_3d(ein, e, hist_in, sig, d, hist_out)
        de33 = -sig(4) / d(4, 4)
        e(4) = e(4) + de33
        if (abs(de33) <= 1e-14_dp * max(1.0_dp, maxval(abs(e)))) exit
      end do
      call small_strain_3d(ein, e, hist_in, sig, d, hist_out)
      call condense(d)
      sig(4) = 0.0_dp
    else
      call small_strain_3d(ein, e, hist_in, sig, d, hist_out)
    end if
  end subroutine small_strain_response

  !> Purpose: the three-dimensional small-strain law (elastic or von
  !> Mises with radial return) at strain eps(4) = (e11, e22, gamma12, e33).
  pure subroutine small_strain_3d(ein, eps, hist_in, sig, d, hist_out)
    type(elem_in_t), intent(in) :: ein
    real(dp), intent(in) :: eps(4), hist_in(max_hist)
    real(dp), intent(out) :: sig(4), d(4, 4), hist_out(max_hist)
    real(dp) :: et(3, 3), ep(3, 3), ds(3, 3)
    type(return_t) :: rm
    integer :: c
    hist_out = hist_in
    if (ein%law == law_deformation_plasticity) then
      call ramberg_osgood(ein%e, ein%nu, ein%ro_sigma0, ein%ro_n, ein%ro_alpha, voigt_to_tensor(eps), rm%sig, &
                          rm%k, rm%c1, rm%c2, rm%nhat)
    else if (ein%nyield == 0) then
      d = elastic_matrix(ein%e, ein%nu, state_plane_strain)
      sig = matmul(d, eps)
      return
    else
      ep = tensor_of(hist_in(1:4))
      et = voigt_to_tensor(eps) - ep
      call radial_return(ein, et, hist_in(hist_peeq), rm)
    end if
    sig = [rm%sig(1, 1), rm%sig(2, 2), rm%sig(1, 2), rm%sig(3, 3)]
    ! columns of the tangent: the return's derivative along each unit
    ! strain component (gamma12 = 2 e12)
    do c = 1, 4
      ds = return_tangent(rm, voigt_to_tensor(unit4(c)))
      d(:, c) = [ds(1, 1), ds(2, 2), ds(1, 2), ds(3, 3)]
    end do
    if (ein%law == law_deformation_plasticity) return
    ep = ep + rm%dgamma * rm%flow
    hist_out(1:4) = [ep(1, 1), ep(2, 2), ep(3, 3), ep(1, 2)]
    hist_out(hist_peeq) = rm%peeq
  end subroutine small_strain_3d

  ! ------------------------------------------------------------------
  ! Finite strain
  ! ------------------------------------------------------------------

  !> Purpose: first Piola-Kirchhoff stress and its derivative at a
  !> deformation gradient, for the five components of F a 2D continuum
  !> has (fc_i, fc_j).
  !> Arguments: ein (law and constants), state, f(3, 3) the deformation
  !> gradient (F13 = F23 = F31 = F32 = 0; F33 = 1 in plane strain, the
  !> hoop stretch r / R in axisymmetry; plane stress: F33 is solved from
  !> tau33 = 0 and returned), eth the thermal strain alpha dT (St
  !> Venant-Kirchhoff only, see saint_venant; the other laws ignore it),
  !> hist_in the
  !> committed history; p(5) the
  !> components of P, a(5, 5) = dP/dF (plane stress: condensed, fifth row
  !> and column zero), tau(3, 3) the Kirchhoff stress J sigma, hist_out the
  !> history at f, ok false where the plane-stress condition could not be
  !> met; tangent (optional, default true): false leaves a zero (the
  !> stress alone costs about half). A non-positive det F gives zero
  !> stress and tangent (the element reports the inverted point).
  !> df33df (optional, plane stress with the tangent): dF33/dF_c for the
  !> four in-plane components, -A(5, c) / A(5, 5) of the uncondensed
  !> tangent (the implicit function of P33 = 0; zero where A(5, 5) is).
  !> dmat (optional): St Venant-Kirchhoff's matrix on (E11, E22, 2 E12,
  !> E33) in place of the isotropic one, an anisotropic material's at the
  !> point in the global (reference) axes (continuum_element's
  !> material_matrix in plane strain).
  pure subroutine finite_strain_response(ein, state, f, eth, hist_in, p, a, tau, hist_out, ok, tangent, df33df, &
                                         dmat)
    type(elem_in_t), intent(in) :: ein
    integer, intent(in) :: state
    real(dp), intent(inout) :: f(3, 3)
    real(dp), intent(in) :: eth, hist_in(max_hist)
    real(dp), intent(out) :: p(5), a(5, 5), tau(3, 3), hist_out(max_hist)
    logical, intent(out) :: ok
    logical, intent(in), optional :: tangent
    real(dp), intent(out), optional :: df33df(4)
    real(dp), intent(in), optional :: dmat(4, 4)
    real(dp) :: e2(4), d(4, 4), e33, df33, j2
    integer :: it
    logical :: want
    want = .true.
    if (present(tangent)) want = tangent
    ok = .true.
    if (state == state_plane_stress) then
      j2 = f(1, 1) * f(2, 2) - f(1, 2) * f(2, 1)
      if (ein%law == law_elastic .and. ein%nyield == 0) then
        ! St Venant-Kirchhoff: S33 = 0 is linear in the mechanical E33
        ! (closed form); Em33 = ((F33 - eth)^2 - 1) / 2 (saint_venant)
        e2 = green_lagrange(f - eth * eye)
        if (present(dmat)) then
          d = dmat
        else
          d = elastic_matrix(ein%e, ein%nu, state_plane_strain)
        end if
        e33 = -(d(4, 1) * e2(1) + d(4, 2) * e2(2) + d(4, 3) * e2(3)) / d(4, 4)
        ! no real thickness stretch when 1 + 2 Em33 <= 0 (an in-plane
        ! stretch of about 1.5 each way for nu = 0.3): reported, not used
        ok = 1.0_dp + 2.0_dp * e33 > 0.0_dp
        f(3, 3) = eth + sqrt(max(1.0_dp + 2.0_dp * e33, tiny(1.0_dp)))
      else
        ! local Newton on tau33(F33) = 0 from an incompressible guess for
        ! rubber, and from 1 otherwise; halved steps keep F33 positive
        f(3, 3) = 1.0_dp
        if (is_hyperelastic(ein) .and. j2 > 0.0_dp) f(3, 3) = 1.0_dp / j2
        df33 = huge(1.0_dp)
        do it = 1, max_local
          call response_3d(ein, f, eth, hist_in, .true., p, a, tau, hist_out)
          if (.not. abs(a(5, 5)) > 0.0_dp) exit
          df33 = -p(5) / a(5, 5)
          do while (f(3, 3) + df33 <= 0.0_dp)
            df33 = 0.5_dp * df33
          end do
          f(3, 3) = f(3, 3) + df33
          if (abs(df33) <= 1e-14_dp * f(3, 3)) exit
        end do
        ! not converged (a tangent of zero, or no convergence in
        ! max_local steps): the point is reported, not used
        ok = abs(df33) <= 1e-10_dp * f(3, 3)
      end if
      call response_3d(ein, f, eth, hist_in, want, p, a, tau, hist_out, dmat)
      if (present(df33df)) then
        df33df = 0.0_dp
        if (abs(a(5, 5)) > 0.0_dp) df33df = -a(5, 1:4) / a(5, 5)
      end if
      call condense(a)
      p(5) = 0.0_dp
    else
      call response_3d(ein, f, eth, hist_in, want, p, a, tau, hist_out, dmat)
    end if
  end subroutine finite_strain_response

  !> Purpose: P(F) and dP/dF of the law for a given F (no plane-stress
  !> condition): tau and its directional derivatives along the five unit
  !> components of F, then P = tau F^-T and
  !> dP = dtau F^-T - tau F^-T dF^T F^-T; for the unit dF = e_i (x) e_j
  !> the last term is (P e_j) (x) (F^-1 e_i)^T, its (k, l) entry
  !> P_kj Finv_li, taken so instead of two 3x3 products. tangent false:
  !> P only (a = 0). dmat (optional) as finite_strain_response's.
  pure subroutine response_3d(ein, f, eth, hist_in, tangent, p, a, tau, hist_out, dmat)
    type(elem_in_t), intent(in) :: ein
    real(dp), intent(in) :: f(3, 3), eth, hist_in(max_hist)
    logical, intent(in) :: tangent
    real(dp), intent(in), optional :: dmat(4, 4)
    real(dp), intent(out) :: p(5), a(5, 5), tau(3, 3), hist_out(max_hist)
    real(dp) :: dtau(3, 3, 5), finv(3, 3), fit(3, 3), pm(3, 3), dpm(3, 3)
    integer :: c, r, i, j
    p = 0.0_dp
    a = 0.0_dp
    tau = 0.0_dp
    hist_out = hist_in
    if (.not. det3(f) > 0.0_dp) return
    if (ein%nyield > 0) then
      call hencky_plastic(ein, f, hist_in, tangent, tau, dtau, hist_out)
    else if (ein%law == law_deformation_plasticity) then
      call almansi_ramberg_osgood(ein, f, tangent, tau, dtau)
    else if (ein%law == law_elastic) then
      call saint_venant(ein, f, eth, tangent, tau, dtau, dmat)
    else
      call mooney_rivlin(ein, f, tangent, tau, dtau)
    end if
    finv = inv3(f)
    fit = transpose(finv)
    pm = matmul(tau, fit)
    p = [(pm(fc_i(c), fc_j(c)), c = 1, 5)]
    if (.not. tangent) return
    do c = 1, 5
      i = fc_i(c)
      j = fc_j(c)
      dpm = matmul(dtau(:, :, c), fit)
      do r = 1, 5
        a(r, c) = dpm(fc_i(r), fc_j(r)) - pm(fc_i(r), j) * finv(fc_j(r), i)
      end do
    end do
  end subroutine response_3d

  !> Purpose: St Venant-Kirchhoff: S = D Em (D the isotropic
  !> elastic_matrix on (E11, E22, 2 E12, E33)), Em the mechanical
  !> Lagrange strain of Fm = F - eth I: CalculiX 2.20's reading under
  !> NLGEOM (calcmechstrain.f of 2.20-2.22: the thermal strain is taken
  !> from the displacement gradient, Em = (Fm^T Fm - I) / 2; its later
  !> development sources divide F by 1 + eth instead, which moved ring1
  !> 4e-3 away from CalculiX 2.20 and its .dat.ref). Free expansion F =
  !> (1 + eth) I gives Em = 0; not objective when a heated body rotates
  !> (in-plane Em = eth (1 + eth) (1 - cos theta) I under F = (1 + eth) R),
  !> as CalculiX 2.20. With the total F, tau = F S F^T and along each
  !> unit component dF of F
  !>   dtau = dF S F^T + F S dF^T + F (D dEm) F^T,
  !>   dEm = sym(Fm^T dF)
  !> (dtau zero when tangent is false). dmat (optional): D of an
  !> anisotropic material at the point (finite_strain_response).
  pure subroutine saint_venant(ein, f, eth, tangent, tau, dtau, dmat)
    type(elem_in_t), intent(in) :: ein
    real(dp), intent(in) :: f(3, 3), eth
    logical, intent(in) :: tangent
    real(dp), intent(out) :: tau(3, 3), dtau(3, 3, 5)
    real(dp), intent(in), optional :: dmat(4, 4)
    real(dp) :: d(4, 4), s(3, 3), ds(3, 3), de(3, 3), fm(3, 3), sf(3, 3)
    integer :: c, i, j
    if (present(dmat)) then
      d = dmat
    else
      d = elastic_matrix(ein%e, ein%nu, state_plane_strain)
    end if
    fm = f - eth * eye
    s = voigt_stress(matmul(d, green_lagrange(fm)))
    sf = matmul(s, transpose(f))
    tau = matmul(f, sf)
    dtau = 0.0_dp
    if (.not. tangent) return
    ! dF = e_i (x) e_j: Fm^T dF has column j = row i of Fm; dF S F^T has
    ! row i = row j of S F^T, F S dF^T its transpose
    do c = 1, 5
      i = fc_i(c)
      j = fc_j(c)
      de = 0.0_dp
      de(:, j) = 0.5_dp * fm(i, :)
      de(j, :) = de(j, :) + 0.5_dp * fm(i, :)
      ds = voigt_stress(matmul(d, [de(1, 1), de(2, 2), 2.0_dp * de(1, 2), de(3, 3)]))
      dtau(:, :, c) = matmul(matmul(f, ds), transpose(f))
      dtau(i, :, c) = dtau(i, :, c) + sf(j, :)
      dtau(:, i, c) = dtau(:, i, c) + sf(j, :)
    end do
  end subroutine saint_venant

  !> Purpose: *DEFORMATION PLASTICITY under finite strain as CalculiX
  !> 2.20 computes it: the Cauchy stress sigma = RO(e), the Ramberg-Osgood
  !> law (deformation_plasticity) of the Euler-Almansi strain
  !> e = (I - b^-1) / 2, b = F F^T (measured: ccx on a plane-stress square
  !> in uniaxial tension to 2 sigma0 gives the Almansi strain of the
  !> Cauchy stress's curve to 1e-6, the .dat's digits; not the Lagrange
  !> strain of the second Piola-Kirchhoff stress). tau = J sigma; along a
  !> unit component dF = e_i (x) e_j of F,
  !>   dJ = J Finv_ji,  de = sym(b^-1 dF F^-1) = sym(b^-1(:, i) Finv(j, :)),
  !>   dtau = dJ sigma + J (k tr(de) I + c1 dev(de) + c2 (nhat : de) nhat)
  !> (the law's tangent; dtau zero when tangent is false). It is isotropic
  !> in the spatial e, hence objective. The thermal strain is not taken
  !> (deck_model_checks refuses *EXPANSION with it under NLGEOM).
  pure subroutine almansi_ramberg_osgood(ein, f, tangent, tau, dtau)
    type(elem_in_t), intent(in) :: ein
    real(dp), intent(in) :: f(3, 3)
    logical, intent(in) :: tangent
    real(dp), intent(out) :: tau(3, 3), dtau(3, 3, 5)
    real(dp) :: finv(3, 3), binv(3, 3), sig(3, 3), jac, x(3, 3)
    type(return_t) :: ro
    integer :: c, i, j
    jac = det3(f)
    finv = inv3(f)
    binv = matmul(transpose(finv), finv)
    call ramberg_osgood(ein%e, ein%nu, ein%ro_sigma0, ein%ro_n, ein%ro_alpha, 0.5_dp * (eye - binv), sig, &
                        ro%k, ro%c1, ro%c2, ro%nhat)
    tau = jac * sig
    dtau = 0.0_dp
    if (.not. tangent) return
    do c = 1, 5
      i = fc_i(c)
      j = fc_j(c)
      x = spread(binv(:, i), 2, 3) * spread(finv(j, :), 1, 3)
      dtau(:, :, c) = jac * finv(j, i) * sig + jac * return_tangent(ro, 0.5_dp * (x + transpose(x)))
    end do
  end subroutine almansi_ramberg_osgood

  !> Purpose: Mooney-Rivlin (neo-Hooke: C01 = 0) with CalculiX's energy
  !> W = C10 (I1bar - 3) + C01 (I2bar - 3) + (J - 1)^2 / D1. Kirchhoff
  !> stress (Holzapfel 2000, eq. 6.103 pushed forward):
  !>   tau = dev[2 (C10 + C01 I1bar) bbar - 2 C01 bbar^2] + J p I,
  !>   p = dW/dJ = 2 (J - 1) / D1, bbar = J^(-2/3) F F^T,
  !> and dtau along each unit component dF = e_i (x) e_j of F from
  !>   dJ = J tr(dF F^-1) = J Finv_ji, db = dF F^T + F dF^T (row and
  !>   column i of db: F's column j), dbbar = J^(-2/3) (db - 2/3 Finv_ji b);
  !> the C01 terms are skipped for neo-Hooke (dtau zero when tangent is
  !> false).
  pure subroutine mooney_rivlin(ein, f, tangent, tau, dtau)
    type(elem_in_t), intent(in) :: ein
    real(dp), intent(in) :: f(3, 3)
    logical, intent(in) :: tangent
    real(dp), intent(out) :: tau(3, 3), dtau(3, 3, 5)
    real(dp) :: c10, c01, d1, jac, jm23, b(3, 3), bb(3, 3), i1, w1, pr, finv(3, 3), trl, db(3, 3), &
                dbb(3, 3), di1, djac
    integer :: c, i, j
    c10 = ein%c10
    c01 = 0.0_dp
    if (ein%law == law_mooney_rivlin) c01 = ein%c01
    d1 = ein%d1
    ! CalculiX: a zero compressibility is replaced by 0.1 / mu0 (nu0 = 0.475)
    if (abs(d1) < 1e-10_dp) d1 = 0.1_dp / (2.0_dp * (c10 + c01))
    jac = det3(f)
    jm23 = jac**(-2.0_dp / 3.0_dp)
    b = matmul(f, transpose(f))
    bb = jm23 * b
    i1 = bb(1, 1) + bb(2, 2) + bb(3, 3)
    w1 = c10 + c01 * i1
    pr = 2.0_dp * (jac - 1.0_dp) / d1
    tau = deviator(2.0_dp * w1 * bb - 2.0_dp * c01 * matmul(bb, bb)) + jac * pr * eye
    dtau = 0.0_dp
    if (.not. tangent) return
    finv = inv3(f)
    do c = 1, 5
      i = fc_i(c)
      j = fc_j(c)
      trl = finv(j, i)                         ! tr(dF F^-1)
      db = 0.0_dp
      db(:, i) = f(:, j)
      db(i, :) = db(i, :) + f(:, j)
      dbb = jm23 * (db - (2.0_dp / 3.0_dp) * trl * b)
      djac = jac * trl
      if (c01 == 0.0_dp) then
        dtau(:, :, c) = deviator(2.0_dp * w1 * dbb)
      else
        di1 = dbb(1, 1) + dbb(2, 2) + dbb(3, 3)
        dtau(:, :, c) = deviator(2.0_dp * w1 * dbb + 2.0_dp * c01 * di1 * bb &
                                 - 2.0_dp * c01 * (matmul(dbb, bb) + matmul(bb, dbb)))
      end if
      dtau(:, :, c) = dtau(:, :, c) + (djac * pr + jac * 2.0_dp * djac / d1) * eye
    end do
  end subroutine mooney_rivlin

  !> Purpose: finite-strain von Mises plasticity (multiplicative split,
  !> Hencky elasticity, exponential-map return; Simo 1992, de Souza Neto
  !> et al. 2008 Box 14.3). The elastic trial left Cauchy-Green tensor
  !> be_tr = F Cp^-1 F^T (Cp^-1 committed), eps_tr = ln(be_tr) / 2, the
  !> small-strain radial return on eps_tr gives tau, and
  !>   dtau = Dalg : (1/2) dln(be_tr)[dF Cp^-1 F^T + F Cp^-1 dF^T]
  !> (the derivative of the tensor logarithm by the Daleckii-Krein
  !> formula, dlog_dir). The updated elastic strain eps_e = eps_tr -
  !> dgamma flow (coaxial with eps_tr) gives be = exp(2 eps_e) and the new
  !> Cp^-1 = F^-1 be F^-T (dtau zero when tangent is false).
  pure subroutine hencky_plastic(ein, f, hist_in, tangent, tau, dtau, hist_out)
    type(elem_in_t), intent(in) :: ein
    real(dp), intent(in) :: f(3, 3), hist_in(max_hist)
    logical, intent(in) :: tangent
    real(dp), intent(out) :: tau(3, 3), dtau(3, 3, 5), hist_out(max_hist)
    real(dp) :: cpi(3, 3), be(3, 3), et(3, 3), dbe(3, 3), finv(3, 3), cf(3, 3), lam(3), q(3, 3)
    type(return_t) :: rm
    integer :: c, i, j
    cpi = eye + tensor_of(hist_in(1:4))
    cf = matmul(cpi, transpose(f))
    be = matmul(f, cf)
    et = 0.5_dp * sym_fun(be, .true.)
    call radial_return(ein, et, hist_in(hist_peeq), rm)
    tau = rm%sig
    ! dbe along dF = e_i (x) e_j: row i and column i are row j of Cp^-1 F^T
    dtau = 0.0_dp
    if (tangent) call block_eig(be, lam, q)
    do c = 1, merge(5, 0, tangent)
      i = fc_i(c)
      j = fc_j(c)
      dbe = 0.0_dp
      dbe(i, :) = cf(j, :)
      dbe(:, i) = dbe(:, i) + cf(j, :)
      dtau(:, :, c) = return_tangent(rm, 0.5_dp * dlog_dir(lam, q, dbe))
    end do
    hist_out = hist_in
    if (rm%dgamma > 0.0_dp) then
      be = sym_fun(2.0_dp * (et - rm%dgamma * rm%flow), .false.)
      finv = inv3(f)
      cpi = matmul(matmul(finv, be), transpose(finv)) - eye
      hist_out(1:4) = [cpi(1, 1), cpi(2, 2), cpi(3, 3), 0.5_dp * (cpi(1, 2) + cpi(2, 1))]
      hist_out(hist_peeq) = rm%peeq
    end if
  end subroutine hencky_plastic

  ! ------------------------------------------------------------------
  ! Radial return (shared by both strain measures)
  ! ------------------------------------------------------------------

  !> Purpose: the von Mises radial return from the elastic trial strain
  !> et (small strain: eps - eps_p; finite strain: ln(be_tr) / 2) and the
  !> committed equivalent plastic strain peeq_n (de Souza Neto et al. 2008,
  !> Box 7.3). The hardening curve is piecewise linear, so the consistency
  !> condition q_tr - 3 mu dgamma - sy(peeq_n + dgamma) = 0 is solved
  !> exactly segment by segment (a segment softening faster than 3 mu has
  !> no root and is passed over: the first root of the piecewise-linear
  !> function lies beyond it).
  pure subroutine radial_return(ein, et, peeq_n, rm)
    type(elem_in_t), intent(in) :: ein
    real(dp), intent(in) :: et(3, 3), peeq_n
    type(return_t), intent(out) :: rm
    real(dp) :: mu, s(3, 3), snorm, q, sy0, h, lo, hi, dg
    integer :: k
    mu = ein%e / (2.0_dp * (1.0_dp + ein%nu))
    rm%k = ein%e / (3.0_dp * (1.0_dp - 2.0_dp * ein%nu))
    rm%sig = rm%k * (et(1, 1) + et(2, 2) + et(3, 3)) * eye + 2.0_dp * mu * deviator(et)
    rm%peeq = peeq_n
    rm%c1 = 2.0_dp * mu
    rm%c2 = 0.0_dp
    s = deviator(rm%sig)
    snorm = sqrt(sum(s * s))
    q = sqrt(1.5_dp) * snorm
    k = segment_of(ein, peeq_n)
    call segment(ein, k, lo, hi, sy0, h)
    if (.not. q > sy0 + h * (peeq_n - lo)) return          ! elastic (or unloading)
    ! f(dg) = q - 3 mu dg - sy(peeq_n + dg) is positive at dg = 0; on a
    ! segment with 3 mu + h > 0 it falls and its root is accepted if it lies
    ! on the segment; on a drop steeper than 3 mu (3 mu + h <= 0) f does
    ! not fall, so the root lies beyond it (the last segment is flat)
    do
      if (3.0_dp * mu + h > 0.0_dp) then
        dg = (q - sy0 - h * (peeq_n - lo)) / (3.0_dp * mu + h)
        if (peeq_n + dg <= hi .or. k >= ein%nyield) exit
      end if
      k = k + 1
      call segment(ein, k, lo, hi, sy0, h)
    end do
    rm%dgamma = dg
    rm%peeq = peeq_n + dg
    rm%flow = 1.5_dp * s / q
    rm%nhat = s / snorm
    rm%sig = rm%sig - 2.0_dp * mu * dg * rm%flow
    rm%c1 = 2.0_dp * mu * (1.0_dp - 3.0_dp * mu * dg / q)
    rm%c2 = 6.0_dp * mu**2 * (dg / q - 1.0_dp / (3.0_dp * mu + h))
  end subroutine radial_return

  !> Purpose: the algorithmic tangent of a radial return applied to a
  !> strain direction de (de Souza Neto et al. 2008, eq. 7.120):
  !> dsig = K tr(de) I + c1 dev(de) + c2 (nhat : de) nhat.
  pure function return_tangent(rm, de) result(ds)
    type(return_t), intent(in) :: rm
    real(dp), intent(in) :: de(3, 3)
    real(dp) :: ds(3, 3)
    ds = rm%k * (de(1, 1) + de(2, 2) + de(3, 3)) * eye + rm%c1 * deviator(de) + rm%c2 * sum(rm%nhat * de) * rm%nhat
  end function return_tangent

  !> Purpose: the segment of the hardening table that holds the
  !> equivalent plastic strain ep: 0 before the first point, k between
  !> points k and k + 1, nyield beyond the last (perfectly plastic).
  pure integer function segment_of(ein, ep) result(k)
    type(elem_in_t), intent(in) :: ein
    real(dp), intent(in) :: ep
    k = 0
    do while (k < ein%nyield)
      if (ep < ein%yield(2, k + 1)) exit
      k = k + 1
    end do
  end function segment_of

  !> Purpose: segment k of the hardening table: its range [lo, hi) of
  !> plastic strain, the yield stress sy0 at lo and the slope h (zero
  !> before the first point and beyond the last; a segment of zero length
  !> is a step, taken with a zero slope over no range).
  pure subroutine segment(ein, k, lo, hi, sy0, h)
    type(elem_in_t), intent(in) :: ein
    integer, intent(in) :: k
    real(dp), intent(out) :: lo, hi, sy0, h
    h = 0.0_dp
    if (k == 0) then
      lo = -huge(1.0_dp)
      hi = ein%yield(2, 1)
      sy0 = ein%yield(1, 1)
    else if (k >= ein%nyield) then
      lo = ein%yield(2, ein%nyield)
      hi = huge(1.0_dp)
      sy0 = ein%yield(1, ein%nyield)
    else
      lo = ein%yield(2, k)
      hi = ein%yield(2, k + 1)
      sy0 = ein%yield(1, k)
      if (hi > lo) h = (ein%yield(1, k + 1) - sy0) / (hi - lo)
    end if
  end subroutine segment

  ! ------------------------------------------------------------------
  ! Tensor helpers
  ! ------------------------------------------------------------------

  !> Purpose: the Green-Lagrange strain (E11, E22, 2 E12, E33) of F.
  pure function green_lagrange(f) result(e)
    real(dp), intent(in) :: f(3, 3)
    real(dp) :: e(4), c(3, 3)
    c = matmul(transpose(f), f)
    e = [0.5_dp * (c(1, 1) - 1.0_dp), 0.5_dp * (c(2, 2) - 1.0_dp), c(1, 2), 0.5_dp * (c(3, 3) - 1.0_dp)]
  end function green_lagrange

  !> Stress vector (s11, s22, s12, s33) as a symmetric tensor.
  pure function voigt_stress(v) result(t)
    real(dp), intent(in) :: v(4)
    real(dp) :: t(3, 3)
    t = 0.0_dp
    t(1, 1) = v(1)
    t(2, 2) = v(2)
    t(1, 2) = v(3)
    t(2, 1) = v(3)
    t(3, 3) = v(4)
  end function voigt_stress

  !> Strain vector (e11, e22, gamma12, e33) as a symmetric tensor.
  pure function voigt_to_tensor(v) result(t)
    real(dp), intent(in) :: v(4)
    real(dp) :: t(3, 3)
    t = voigt_stress([v(1), v(2), 0.5_dp * v(3), v(4)])
  end function voigt_to_tensor

  !> History components (11, 22, 33, 12) as a symmetric tensor.
  pure function tensor_of(h) result(t)
    real(dp), intent(in) :: h(4)
    real(dp) :: t(3, 3)
    t = voigt_stress([h(1), h(2), h(4), h(3)])
  end function tensor_of

  !> The unit strain vector (e11, e22, gamma12, e33) along component c.
  pure function unit4(c) result(v)
    integer, intent(in) :: c
    real(dp) :: v(4)
    v = 0.0_dp
    v(c) = 1.0_dp
  end function unit4

  !> The deviatoric part of a 3x3 tensor.
  pure function deviator(t) result(d)
    real(dp), intent(in) :: t(3, 3)
    real(dp) :: d(3, 3)
    d = t - (t(1, 1) + t(2, 2) + t(3, 3)) / 3.0_dp * eye
  end function deviator

  !> Purpose: eigenvalues lam and eigenvectors q (columns) of a symmetric
  !> tensor with the plane block structure (x13 = x23 = 0): the in-plane
  !> pair in closed form, the third x33.
  pure subroutine block_eig(x, lam, q)
    real(dp), intent(in) :: x(3, 3)
    real(dp), intent(out) :: lam(3), q(3, 3)
    real(dp) :: m, r, th, x12
    x12 = 0.5_dp * (x(1, 2) + x(2, 1))
    m = 0.5_dp * (x(1, 1) + x(2, 2))
    r = hypot(0.5_dp * (x(1, 1) - x(2, 2)), x12)
    th = 0.5_dp * atan2(2.0_dp * x12, x(1, 1) - x(2, 2))
    lam = [m + r, m - r, x(3, 3)]
    q = 0.0_dp
    q(:, 1) = [cos(th), sin(th), 0.0_dp]
    q(:, 2) = [-sin(th), cos(th), 0.0_dp]
    q(3, 3) = 1.0_dp
  end subroutine block_eig

  !> Purpose: ln(x) (logarithm = .true.) or exp(x) of a symmetric
  !> positive (for ln) tensor of the plane block structure, through its
  !> eigenvalues.
  pure function sym_fun(x, logarithm) result(y)
    real(dp), intent(in) :: x(3, 3)
    logical, intent(in) :: logarithm
    real(dp) :: y(3, 3), lam(3), q(3, 3), g(3)
    integer :: i
    call block_eig(x, lam, q)
    if (logarithm) then
      g = log(lam)
    else
      g = exp(lam)
    end if
    y = 0.0_dp
    do i = 1, 3
      y = y + g(i) * spread(q(:, i), 2, 3) * spread(q(:, i), 1, 3)
    end do
  end function sym_fun

  !> Purpose: the directional derivative of the tensor logarithm,
  !> dln(x)[dx], by the Daleckii-Krein formula: in the eigenbasis of x,
  !> component (i, j) of dx times the divided difference of ln at
  !> (lam_i, lam_j) (1 / lam_i when they coincide).
  !> Arguments: lam, q the eigenvalues and eigenvectors of x (block_eig,
  !> computed once for the five directions), dx the direction.
  pure function dlog_dir(lam, q, dx) result(dy)
    real(dp), intent(in) :: lam(3), q(3, 3), dx(3, 3)
    real(dp) :: dy(3, 3), h(3, 3)
    integer :: i, j
    h = matmul(matmul(transpose(q), dx), q)
    do j = 1, 3
      do i = 1, 3
        h(i, j) = h(i, j) * log_divided(lam(i), lam(j))
      end do
    end do
    dy = matmul(matmul(q, h), transpose(q))
  end function dlog_dir

  !> (ln a - ln b) / (a - b) without cancellation: with y = (a - b) /
  !> (a + b), ln(a / b) = 2 atanh(y), so the quotient is
  !> 2 atanh(y) / (y (a + b)); atanh(y) / y by its series for small y.
  pure real(dp) function log_divided(a, b)
    real(dp), intent(in) :: a, b
    real(dp) :: y, r
    y = (a - b) / (a + b)
    if (abs(y) < 1e-4_dp) then
      r = 1.0_dp + y**2 / 3.0_dp + y**4 / 5.0_dp
    else
      r = atanh(y) / y
    end if
    log_divided = 2.0_dp * r / (a + b)
  end function log_divided

  !> Purpose: static condensation of the last (out-of-plane) row of a
  !> tangent under a zero last stress (s33 = 0, d of order 4; P33 = 0, dP/dF
  !> of order 5 with F33 last): a_ij - a_in a_nj / a_nn, row and column n
  !> zero. A zero (or not finite) a_nn leaves a as it is.
  pure subroutine condense(a)
    real(dp), intent(inout) :: a(:, :)
    integer :: i, j, n
    n = size(a, 1)
    if (.not. abs(a(n, n)) > 0.0_dp) return
    do j = 1, n - 1
      do i = 1, n - 1
        a(i, j) = a(i, j) - a(i, n) * a(n, j) / a(n, n)
      end do
    end do
    a(n, :) = 0.0_dp
    a(:, n) = 0.0_dp
  end subroutine condense
end module material_laws
