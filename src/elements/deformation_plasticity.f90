!> *DEFORMATION PLASTICITY: the Ramberg-Osgood law generalised by J2
!> deformation theory, a nonlinear elastic (path-independent) law of the
!> total strain, as Abaqus and CalculiX define it (Abaqus Analysis User's
!> Guide, "Deformation plasticity"; CalculiX's manual, *DEFORMATION
!> PLASTICITY):
!>   E eps = (1 + nu) s - (1 - 2 nu) p I + (3/2) alpha (q / sigma0)^(n-1) s,
!> s = dev(sig), p = -tr(sig) / 3, q = sqrt(3/2 s : s). In uniaxial stress
!> sig this is eps = sig / E + alpha (sigma0 / E) (sig / sigma0)^n.
!>
!> Inversion (strain in, stress out). The volumetric part is linear:
!> tr(sig) = 3 K tr(eps), K = E / (3 (1 - 2 nu)). The deviatoric part is
!> e = dev(eps) = c(q) s, c(q) = ((1 + nu) + (3/2) alpha (q / sigma0)^(n-1)) / E,
!> so s is parallel to e and, with e_eq = sqrt(2/3 e : e) = (2/3) c q,
!> q solves the scalar equation
!>   g(q) = (1 + nu) q + (3/2) alpha sigma0 (q / sigma0)^n - (3/2) E e_eq = 0,
!> increasing and convex in q >= 0 for n >= 1: Newton started to the right
!> of the root (at the smaller of the two bounds the elastic and the
!> plastic term alone give) falls monotonically onto it.
!>
!> Consistent tangent: with nhat = e / |e|,
!>   dsig = K tr(deps) I + c1 dev(deps) + c2 (nhat : deps) nhat,
!>   c1 = 1 / c,  c2 = -(3/2) E e_eq c'(q) / (c^2 g'(q)),
!> from ds = de / c - e dc / c^2, dc = c'(q) dq, dq = (3/2) E de_eq / g'(q),
!> de_eq = (2/3) e : de / e_eq and e (e : de) = (3/2) e_eq^2 nhat (nhat : de);
!> c2 = 0 at zero deviatoric strain (the tangent there is the elastic one).
module deformation_plasticity
  use kinds, only: dp
  implicit none
  private
  public :: ramberg_osgood

  !> Newton steps on g(q) = 0: monotone and quadratic near the root, so a
  !> few dozen are a safeguard only.
  integer, parameter :: max_newton = 200

contains

  !> Purpose: stress and consistent tangent of the Ramberg-Osgood law
  !> (J2 deformation theory) at a total (mechanical) strain.
  !> Arguments: e, nu (the linear elastic part), sigma0 (the yield offset),
  !> rn (the hardening exponent n >= 1), alpha (the yield offset factor),
  !> eps(3, 3) the strain tensor; sig(3, 3) the stress, and the tangent
  !> coefficients k, c1, c2, nhat(3, 3) of
  !> dsig = k tr(deps) I + c1 dev(deps) + c2 (nhat : deps) nhat.
  pure subroutine ramberg_osgood(e, nu, sigma0, rn, alpha, eps, sig, k, c1, c2, nhat)
    real(dp), intent(in) :: e, nu, sigma0, rn, alpha, eps(3, 3)
    real(dp), intent(out) :: sig(3, 3), k, c1, c2, nhat(3, 3)
    real(dp) :: tr, dev(3, 3), enorm, eeq, q, c, dc, dg
    integer :: i
    k = e / (3.0_dp * (1.0_dp - 2.0_dp * nu))
    tr = eps(1, 1) + eps(2, 2) + eps(3, 3)
    dev = eps
    do i = 1, 3
      dev(i, i) = dev(i, i) - tr / 3.0_dp
    end do
    enorm = sqrt(sum(dev * dev))
    eeq = sqrt(2.0_dp / 3.0_dp) * enorm
    nhat = 0.0_dp
    c2 = 0.0_dp
    if (enorm > 0.0_dp) nhat = dev / enorm
    q = equivalent_stress(e, nu, sigma0, rn, alpha, eeq)
    c = compliance(e, nu, sigma0, rn, alpha, q)
    c1 = 1.0_dp / c
    sig = dev / c
    do i = 1, 3
      sig(i, i) = sig(i, i) + k * tr
    end do
    if (.not. q > 0.0_dp .or. alpha == 0.0_dp .or. rn == 1.0_dp) return
    ! c'(q) and g'(q); c' e_eq is finite as q -> 0 for every n >= 1
    dc = 1.5_dp * alpha * (rn - 1.0_dp) / (e * sigma0) * (q / sigma0)**(rn - 2.0_dp)
    dg = (1.0_dp + nu) + 1.5_dp * alpha * rn * (q / sigma0)**(rn - 1.0_dp)
    c2 = -1.5_dp * e * eeq * dc / (c**2 * dg)
  end subroutine ramberg_osgood

  !> Purpose: the deviatoric compliance c(q) = e / s of the law at the
  !> Mises stress q (module header).
  !> Arguments: the law's constants; q the Mises stress.
  pure real(dp) function compliance(e, nu, sigma0, rn, alpha, q)
    real(dp), intent(in) :: e, nu, sigma0, rn, alpha, q
    compliance = (1.0_dp + nu) / e
    if (q > 0.0_dp) compliance = compliance + 1.5_dp * alpha * (q / sigma0)**(rn - 1.0_dp) / e
  end function compliance

  !> Purpose: the Mises stress q at the equivalent strain e_eq: the root
  !> of g(q) (module header) by Newton from the right of the root.
  !> Arguments: the law's constants; eeq the equivalent deviatoric strain
  !> sqrt(2/3 e : e) (>= 0).
  pure real(dp) function equivalent_stress(e, nu, sigma0, rn, alpha, eeq) result(q)
    real(dp), intent(in) :: e, nu, sigma0, rn, alpha, eeq
    real(dp) :: g, dg, dq
    integer :: it
    q = 1.5_dp * e * eeq / (1.0_dp + nu)
    if (.not. q > 0.0_dp .or. alpha == 0.0_dp) return
    ! the plastic term alone also bounds the root from above
    q = min(q, sigma0 * (e * eeq / (alpha * sigma0))**(1.0_dp / rn))
    do it = 1, max_newton
      g = (1.0_dp + nu) * q + 1.5_dp * alpha * sigma0 * (q / sigma0)**rn - 1.5_dp * e * eeq
      dg = (1.0_dp + nu) + 1.5_dp * alpha * rn * (q / sigma0)**(rn - 1.0_dp)
      dq = g / dg
      q = q - dq
      if (abs(dq) <= 1e-13_dp * q) exit   ! quadratic: the next step is below round-off
    end do
  end function equivalent_stress
end module deformation_plasticity
