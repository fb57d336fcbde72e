!> Element-level checks of the nonlinear continuum element and its
!> material laws (src/elements/nonlinear_continuum.f90, material_laws.f90):
!> - the tangent ke against central differences of the internal force fe,
!>   every shape in every stress state, for St Venant-Kirchhoff, neo-Hooke,
!>   Mooney-Rivlin (F-bar on the 4-node quadrilateral) and von Mises
!>   plasticity at a plastic state, small and finite strain (relative 1e-6);
!> - a rigid rotation (plane) or axial translation (axisymmetry) gives no
!>   force; at zero and at tiny displacements St Venant-Kirchhoff's ke is the
!>   linear element's (1e-8);
!> - neo-Hooke and Mooney-Rivlin at zero displacement: the linear element
!>   with mu = 2 (C10 + C01), K = 2 / D1 (D1 = 0: CalculiX's 0.1 / mu)
!>   (1e-12; not the F-bar elements, whose operator differs);
!> - plane-strain uniaxial stretch and compression of one neo-Hookean and
!>   one Mooney-Rivlin element against the nominal stress dW/dlambda of
!>   CalculiX's energy (1e-6);
!> - uniaxial tension past yield, elastic unloading and reversed yielding
!>   with linear hardening, small strain and (in logarithmic strain)
!>   finite strain: stresses, PEEQ and plastic strain exact at the points;
!> - the follower pressure load: its load stiffness against central
!>   differences (1e-6), the dead load at zero displacement (1e-12), and
!>   forces turning with a rigid rotation of the element (1e-12);
!> - objectivity: a rigid rotation superposed on a deformed (for
!>   plasticity: plastically deformed and committed) state rotates the
!>   Cauchy stress and leaves PEEQ and the history unchanged (1e-12);
!> - F-bar: a nearly incompressible 4-node quadrilateral (K / mu = 1e5) has
!>   one volumetric constraint (one singular value of ke of the bulk
!>   modulus's size), where the element without it has more;
!> - Newton on one element (a distorted CPE4 neo-Hooke with F-bar pressed
!>   by 30 %, CAX4 finite-strain plasticity stretched by 20 %, CPS8
!>   Mooney-Rivlin by 50 %, CAX6 St Venant-Kirchhoff pressed by 20 %): the
!>   residual falls below 1e-10 of the first in at most 8 iterations, in
!>   one step from the previous increment, with quadratic convergence at
!>   the end;
!> - St Venant-Kirchhoff under NLGEOM with a temperature change: free
!>   thermal expansion (F = (1 + alpha dT) I) gives no force (plane stress,
!>   axisymmetry); at a homogeneous stretch the Cauchy stress is CalculiX
!>   2.20's, S = D Em with Em the Lagrange strain of F - alpha dT I (1e-12);
!> - a hardening table dropping faster than 3 mu: the return lands beyond
!>   the drop (Mises and PEEQ exact, small and finite strain);
!> - plane-stress St Venant-Kirchhoff past the stretch where no thickness
!>   stretch satisfies S33 = 0: reported (detj_min <= 0);
!> - the elastic laws do not read ein%hist (NaN there changes nothing);
!> - NaN in ue, a volume ratio of 1e-27 and displacements of 1e11: no NaN
!>   or Infinity in any array, and NaN reported through detj_min <= 0.
program test_nonlinear
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_value, ieee_quiet_nan
  use kinds, only: dp
  use test_report, only: report, failures
  use element_interface, only: elem_in_t, elem_out_t, act_tangent, act_residual, act_stresses
  use element_catalogue, only: max_nodes, find_element_type, catalogue, state_axisymmetric, &
                               state_plane_stress, shape_quad4
  use element_library, only: element_routine, thickness_stretch
  use distributed_loads, only: face_pressure_load, follower_pressure_load
  use model, only: law_neo_hooke, law_mooney_rivlin
  implicit none
  real(dp), parameter :: q4(2, 4) = reshape([0.0_dp, 0.0_dp, 2.2_dp, 0.3_dp, 1.9_dp, 1.7_dp, -0.2_dp, 1.1_dp], [2, 4])
  real(dp), parameter :: t3(2, 3) = reshape([0.1_dp, -0.2_dp, 1.7_dp, 0.4_dp, 0.6_dp, 1.3_dp], [2, 3])
  character(len=3), parameter :: prefix(3) = ['CPS', 'CPE', 'CAX']
  character(len=2), parameter :: suffix(5) = ['3 ', '4 ', '6 ', '8 ', '8R']
  character(len=4), parameter :: law_name(5) = ['SVK ', 'NH  ', 'MR  ', 'PLF ', 'PLS ']
  integer :: is, ie, il

  do is = 1, 3
    do ie = 1, 5
      do il = 1, 5
        call check_tangent(trim(prefix(is) // suffix(ie)), il, trim(law_name(il)))
        call check_bad_deformation(trim(prefix(is) // suffix(ie)), il, trim(law_name(il)))
        if (il <= 3) call check_no_history_read(trim(prefix(is) // suffix(ie)), il, trim(law_name(il)))
      end do
      call check_rigid(trim(prefix(is) // suffix(ie)))
      call check_linear_limit(trim(prefix(is) // suffix(ie)))
      call check_rubber_moduli(trim(prefix(is) // suffix(ie)))
    end do
  end do
  call check_uniaxial_rubber()
  call check_uniaxial_plastic(.false.)
  call check_uniaxial_plastic(.true.)
  call check_steep_drop(.false.)
  call check_steep_drop(.true.)
  call check_no_thickness()
  call check_follower()
  call check_thickness_stretch()
  call check_objectivity('CPE4')
  call check_objectivity('CPS6')
  call check_objectivity('CPE8R')
  call check_no_locking('CPE4')
  call check_no_locking('CAX4')
  call check_newton('CPE4', 2, -0.3_dp)
  call check_newton('CAX4', 4, 0.2_dp)
  call check_newton('CPS8', 3, 0.5_dp)
  call check_newton('CAX6', 1, -0.2_dp)
  do ie = 1, 5
    call check_free_expansion('CPS' // trim(suffix(ie)))
    call check_free_expansion('CAX' // trim(suffix(ie)))
  end do
  call check_thermal_nlgeom('CPE4')
  call check_thermal_nlgeom('CPS4')
  call check_thermal_nlgeom('CAX4')
  call check_thermal_nlgeom('CAX8')
  if (failures() > 0) stop 1

contains

  !> Element data of catalogue type `name` on a distorted quadrilateral or
  !> triangle (curved mid-side nodes for the quadratic shapes), moved to
  !> r > 0 in axisymmetry; law il: 1 SVK, 2 neo-Hooke, 3 Mooney-Rivlin,
  !> 4 plasticity under NLGEOM, 5 small-strain plasticity.
  function element(name, il) result(ein)
    character(len=*), intent(in) :: name
    integer, intent(in) :: il
    type(elem_in_t) :: ein
    integer :: it, k, nc
    real(dp) :: c(2, 4), d(2)
    it = find_element_type(name)
    ein%kind = catalogue(it)%shape
    ein%nen = catalogue(it)%nodes
    ein%nip = catalogue(it)%nip
    ein%state = catalogue(it)%state
    nc = catalogue(it)%corners
    c = 0.0_dp
    if (nc == 4) then
      c = q4
    else
      c(:, 1:3) = t3
    end if
    ein%xy = 0.0_dp
    ein%xy(:, 1:nc) = c(:, 1:nc)
    do k = 1, ein%nen - nc
      d = c(:, mod(k, nc) + 1) - c(:, k)
      ein%xy(:, nc + k) = 0.5_dp * (c(:, k) + c(:, mod(k, nc) + 1)) + 0.07_dp * [d(2), -d(1)]
    end do
    if (ein%state == state_axisymmetric) ein%xy(1, 1:ein%nen) = ein%xy(1, 1:ein%nen) + 0.7_dp
    ein%thickness = 1.3_dp
    ! the table and the history have no default in elem_in_t
    ein%yield = 0.0_dp
    ein%hist = 0.0_dp
    ein%e = 1000.0_dp
    ein%nu = 0.3_dp
    ein%nlgeom = il /= 5
    select case (il)
    case (2)
      ein%law = law_neo_hooke
      ein%c10 = 150.0_dp
      ein%d1 = 0.002_dp
    case (3)
      ein%law = law_mooney_rivlin
      ein%c10 = 120.0_dp
      ein%c01 = 30.0_dp
      ein%d1 = 0.0_dp           ! CalculiX's default compressibility
    case (4, 5)
      ein%nyield = 3
      ein%yield(:, 1:3) = reshape([10.0_dp, 0.0_dp, 14.0_dp, 0.05_dp, 15.0_dp, 0.4_dp], [2, 3])
    end select
  end function element

  !> A smooth displacement field of size `amp` at the nodes (not affine).
  subroutine deform(ein, amp)
    type(elem_in_t), intent(inout) :: ein
    real(dp), intent(in) :: amp
    integer :: k
    real(dp) :: x, y
    do k = 1, ein%nen
      x = ein%xy(1, k)
      y = ein%xy(2, k)
      ein%ue(2 * k - 1) = amp * (0.8_dp * x - 0.3_dp * y + 0.2_dp * x * y + 0.1_dp * sin(3.0_dp * y))
      ein%ue(2 * k) = amp * (0.25_dp * x + 0.5_dp * y - 0.15_dp * x**2 + 0.1_dp * cos(2.0_dp * x))
    end do
  end subroutine deform

  !> ke against central differences of fe at a deformed (for plasticity:
  !> plastic at every point, from a virgin history) state.
  subroutine check_tangent(name, il, lname)
    character(len=*), intent(in) :: name, lname
    integer, intent(in) :: il
    type(elem_in_t) :: ein, ep
    type(elem_out_t) :: eout, eplus, eminus
    real(dp) :: kfd(2 * max_nodes, 2 * max_nodes), h, err, scale, amp
    integer :: j, nd
    ein = element(name, il)
    ! a varying temperature change where the law takes the thermal strain
    if (il == 1 .or. il == 5) then
      ein%alpha = 1e-3_dp
      ein%dtemp(1:ein%nen) = [(5.0_dp + 3.0_dp * j, j = 1, ein%nen)]
    end if
    amp = 0.15_dp
    if (il >= 4) amp = 0.06_dp
    call deform(ein, amp)
    nd = 2 * ein%nen
    call element_routine(ior(act_tangent, ior(act_residual, act_stresses)), ein, eout)
    h = 1e-6_dp
    do j = 1, nd
      ep = ein
      ep%ue(j) = ein%ue(j) + h
      call element_routine(act_residual, ep, eplus)
      ep%ue(j) = ein%ue(j) - h
      call element_routine(act_residual, ep, eminus)
      kfd(1:nd, j) = (eplus%fe(1:nd) - eminus%fe(1:nd)) / (2.0_dp * h)
    end do
    scale = maxval(abs(eout%ke(1:nd, 1:nd)))
    err = maxval(abs(kfd(1:nd, 1:nd) - eout%ke(1:nd, 1:nd))) / scale
    call report('tangent vs differences ' // name // ' ' // lname, err < 1e-6_dp .and. scale > 0.0_dp &
                .and. eout%detj_min > 0.0_dp, 'relative error ' // num(err) // ', detj_min ' // num(eout%detj_min))
    if (il >= 4) call report('plastic at every point ' // name // ' ' // lname, &
                             all(eout%peeq_ip(1:ein%nip) > 0.0_dp), 'an elastic point: ' // num(minval(eout%peeq_ip(1:ein%nip))))
    ! act_residual alone skips the laws' derivatives: the same fe and history
    call element_routine(act_residual, ein, eplus)
    call report('residual without the tangent identical ' // name // ' ' // lname, &
                all(eplus%fe(1:nd) == eout%fe(1:nd)) .and. all(eplus%hist == eout%hist) &
                .and. all(eplus%ke(1:nd, 1:nd) == 0.0_dp), 'differs by ' // num(maxval(abs(eplus%fe(1:nd) - eout%fe(1:nd)))))
  end subroutine check_tangent

  !> Rigid motion: a rotation by 40 degrees and a translation (plane), a
  !> translation along z (axisymmetry), for every finite-strain law: no force.
  subroutine check_rigid(name)
    character(len=*), intent(in) :: name
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    real(dp) :: rot(2, 2), th, x(2), fmax
    integer :: k, il
    th = 40.0_dp * acos(-1.0_dp) / 180.0_dp
    rot = reshape([cos(th), sin(th), -sin(th), cos(th)], [2, 2])
    fmax = 0.0_dp
    do il = 1, 4
      ein = element(name, il)
      do k = 1, ein%nen
        x = ein%xy(:, k)
        if (ein%state == state_axisymmetric) then
          ein%ue(2 * k - 1:2 * k) = [0.0_dp, 0.37_dp]
        else
          ein%ue(2 * k - 1:2 * k) = matmul(rot, x) - x + [0.3_dp, -0.2_dp]
        end if
      end do
      call element_routine(act_residual, ein, eout)
      fmax = max(fmax, maxval(abs(eout%fe(1:2 * ein%nen))) / ein%e)
    end do
    call report('rigid motion no force ' // name, fmax < 1e-12_dp, 'max |fe| / E ' // num(fmax))
  end subroutine check_rigid

  !> St Venant-Kirchhoff at zero and at tiny displacements: the linear
  !> element's ke (relative 1e-8); small-strain plasticity in its elastic
  !> range (not the 4-node quadrilateral, which has B-bar): the same.
  subroutine check_linear_limit(name)
    character(len=*), intent(in) :: name
    type(elem_in_t) :: ein, elin
    type(elem_out_t) :: eout, elo
    real(dp) :: err0, err1, err2, scale
    integer :: nd
    elin = element(name, 1)
    elin%nlgeom = .false.
    nd = 2 * elin%nen
    call element_routine(act_tangent, elin, elo)
    scale = maxval(abs(elo%ke(1:nd, 1:nd)))
    ein = element(name, 1)
    call element_routine(act_tangent, ein, eout)
    err0 = maxval(abs(eout%ke(1:nd, 1:nd) - elo%ke(1:nd, 1:nd))) / scale
    call deform(ein, 1e-10_dp)
    call element_routine(act_tangent, ein, eout)
    err1 = maxval(abs(eout%ke(1:nd, 1:nd) - elo%ke(1:nd, 1:nd))) / scale
    call report('SVK at zero and tiny displacement is linear ' // name, max(err0, err1) < 1e-8_dp, &
                'relative ' // num(err0) // ' ' // num(err1))
    if (elin%kind /= shape_quad4 .or. elin%state == state_plane_stress) then
      ein = element(name, 5)
      call deform(ein, 1e-5_dp)
      call element_routine(act_tangent, ein, eout)
      err2 = maxval(abs(eout%ke(1:nd, 1:nd) - elo%ke(1:nd, 1:nd))) / scale
      call report('small-strain plasticity elastic range is linear ' // name, err2 < 1e-12_dp, 'relative ' // num(err2))
    end if
  end subroutine check_linear_limit

  !> The initial stiffness of the rubber laws is the linear element's with
  !> E and nu from mu = 2 (C10 + C01) and K = 2 / D1.
  subroutine check_rubber_moduli(name)
    character(len=*), intent(in) :: name
    type(elem_in_t) :: ein, elin
    type(elem_out_t) :: eout, elo
    real(dp) :: mu, kb, d1, err
    integer :: il, nd
    err = 0.0_dp
    do il = 2, 3
      ein = element(name, il)
      if (ein%kind == shape_quad4 .and. ein%state /= state_plane_stress) return
      d1 = ein%d1
      mu = 2.0_dp * (ein%c10 + ein%c01)
      if (d1 == 0.0_dp) d1 = 0.1_dp / mu
      kb = 2.0_dp / d1
      elin = element(name, 1)
      elin%nlgeom = .false.
      elin%e = 9.0_dp * kb * mu / (3.0_dp * kb + mu)
      elin%nu = (3.0_dp * kb - 2.0_dp * mu) / (2.0_dp * (3.0_dp * kb + mu))
      call element_routine(act_tangent, elin, elo)
      call element_routine(act_tangent, ein, eout)
      nd = 2 * ein%nen
      err = max(err, maxval(abs(eout%ke(1:nd, 1:nd) - elo%ke(1:nd, 1:nd))) / maxval(abs(elo%ke(1:nd, 1:nd))))
    end do
    call report('rubber initial stiffness is linear with mu, K ' // name, err < 1e-12_dp, 'relative ' // num(err))
  end subroutine check_rubber_moduli

  !> Nominal stresses (P1, P2) = dW/dlambda of CalculiX's Mooney-Rivlin
  !> energy at principal stretches (l1, l2, 1), differentiated by hand:
  !> I1bar = J^(-2/3) sum l^2, I2bar = J^(-4/3) (l1^2 l2^2 + l2^2 + l1^2).
  function nominal(c10, c01, d1, l1, l2) result(p)
    real(dp), intent(in) :: c10, c01, d1, l1, l2
    real(dp) :: p(2), l(3), jac, s1, s2, di1, di2
    integer :: i
    l = [l1, l2, 1.0_dp]
    jac = l1 * l2
    s1 = sum(l**2)
    s2 = l(1)**2 * l(2)**2 + l(2)**2 * l(3)**2 + l(3)**2 * l(1)**2
    do i = 1, 2
      di1 = jac**(-2.0_dp / 3.0_dp) * (2.0_dp * l(i) - (2.0_dp / 3.0_dp) * s1 / l(i))
      di2 = jac**(-4.0_dp / 3.0_dp) * (2.0_dp * l(i) * (s1 - l(i)**2) - (4.0_dp / 3.0_dp) * s2 / l(i))
      p(i) = c10 * di1 + c01 * di2 + 2.0_dp * (jac - 1.0_dp) / d1 * jac / l(i)
    end do
  end function nominal

  !> One element (CPE3, CPE4 with F-bar, CPE8) stretched to lambda in x
  !> (1.5) and compressed (0.7), free in y: the lateral stretch solves
  !> P2 = 0 (bisection on the closed form); the element's nominal stress
  !> sigma11 lambda2 and its edge force against P1, sigma22 against 0.
  subroutine check_uniaxial_rubber()
    character(len=4), parameter :: names(3) = ['CPE3', 'CPE4', 'CPE8']
    real(dp), parameter :: sq(2, 4) = reshape([0.0_dp, 0.0_dp, 2.0_dp, 0.0_dp, 2.0_dp, 1.5_dp, 0.0_dp, 1.5_dp], [2, 4])
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    real(dp) :: lam(2), l1, l2, lo, hi, p(2), d1, fx, err, scale
    integer :: i, k, il, it, ib
    lam = [1.5_dp, 0.7_dp]
    do il = 2, 3
      do i = 1, 3
        do it = 1, 2
          ein = element(names(i), il)
          ein%xy = 0.0_dp
          ein%xy(:, 1:4) = sq
          if (ein%nen == 3) ein%xy(:, 1:3) = sq(:, [1, 2, 4])
          if (ein%nen == 8) then
            do k = 1, 4
              ein%xy(:, 4 + k) = 0.5_dp * (sq(:, k) + sq(:, mod(k, 4) + 1))
            end do
          end if
          d1 = ein%d1
          if (d1 == 0.0_dp) d1 = 0.1_dp / (2.0_dp * (ein%c10 + ein%c01))
          l1 = lam(it)
          lo = 0.2_dp
          hi = 3.0_dp
          do ib = 1, 200
            l2 = 0.5_dp * (lo + hi)
            p = nominal(ein%c10, ein%c01, d1, l1, l2)
            if (p(2) > 0.0_dp) then
              hi = l2
            else
              lo = l2
            end if
          end do
          p = nominal(ein%c10, ein%c01, d1, l1, l2)
          do k = 1, ein%nen
            ein%ue(2 * k - 1:2 * k) = [(l1 - 1.0_dp) * ein%xy(1, k), (l2 - 1.0_dp) * ein%xy(2, k)]
          end do
          call element_routine(ior(act_residual, act_stresses), ein, eout)
          ! the x force on the right edge (x = 2) is P1 times its reference
          ! area; the triangle (0,0), (2,0), (0,1.5) has one node there,
          ! whose force integral P grad N2 dV0 is half of that (the other
          ! half is added here)
          fx = 0.0_dp
          if (ein%nen == 3) fx = 0.5_dp * p(1) * 1.5_dp * 1.3_dp
          do k = 1, ein%nen
            if (abs(ein%xy(1, k) - 2.0_dp) < 1e-12_dp) fx = fx + eout%fe(2 * k - 1)
          end do
          scale = abs(p(1))
          err = max(maxval(abs(eout%sig_ip(1, 1:ein%nip) * l2 - p(1))), maxval(abs(eout%sig_ip(2, 1:ein%nip))), &
                    abs(fx - p(1) * 1.5_dp * 1.3_dp) / 1.95_dp) / scale
          call report('uniaxial plane strain ' // trim(law_name(il)) // ' ' // names(i) // ' lambda ' // num(l1), &
                      err < 1e-6_dp, 'relative error ' // num(err))
        end do
      end do
    end do
  end subroutine check_uniaxial_rubber

  !> A square CPS4 in homogeneous uniaxial stress along x with linear
  !> hardening sy = 10 + 200 ep: loaded past yield, unloaded elastically,
  !> reloaded in compression past the reversed yield stress. Small strain:
  !> strains eps; finite strain: the same values as logarithmic strains
  !> (stretches exp(eps)), whose Kirchhoff stress has the small-strain
  !> closed form. At each state the lateral strain is the closed form's,
  !> so the point must give s11 exactly, s22 = 0, PEEQ and the plastic
  !> strain exactly (1e-10); the history is committed between states.
  subroutine check_uniaxial_plastic(finite)
    logical, intent(in) :: finite
    real(dp), parameter :: e = 1000.0_dp, nu = 0.3_dp, s0 = 10.0_dp, hh = 200.0_dp
    real(dp), parameter :: sq(2, 4) = reshape([0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, 1.0_dp, 0.0_dp, 1.0_dp], [2, 4])
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    real(dp) :: ex(3), sig(3), epl(3), peeq(3), e22, l1, l2, s11, jac, err
    integer :: st, k, ip
    character(len=10) :: tag
    ! state 1: tension to 5 yield strains; state 2: back to half the
    ! stress in compression (elastic); state 3: reversed yielding, peeq
    ! grown by 0.02
    peeq(1) = (e * 0.05_dp - s0) / (e + hh)
    sig(1) = s0 + hh * peeq(1)
    epl(1) = peeq(1)
    ex(1) = 0.05_dp
    sig(2) = -0.5_dp * sig(1)
    epl(2) = epl(1)
    peeq(2) = peeq(1)
    ex(2) = epl(2) + sig(2) / e
    peeq(3) = peeq(1) + 0.02_dp
    sig(3) = -(s0 + hh * peeq(3))
    epl(3) = epl(1) - 0.02_dp
    ex(3) = epl(3) + sig(3) / e
    ein = element('CPS4', 5)
    ein%nlgeom = finite
    ein%xy = 0.0_dp
    ein%xy(:, 1:4) = sq
    ein%nyield = 2
    ein%yield(:, 1:2) = reshape([s0, 0.0_dp, s0 + hh * 1.0_dp, 1.0_dp], [2, 2])
    tag = 'small'
    if (finite) tag = 'finite'
    do st = 1, 3
      e22 = -nu * sig(st) / e - 0.5_dp * epl(st)
      l1 = ex(st)
      l2 = e22
      if (finite) then
        l1 = exp(ex(st)) - 1.0_dp
        l2 = exp(e22) - 1.0_dp
      end if
      do k = 1, 4
        ein%ue(2 * k - 1:2 * k) = [l1 * ein%xy(1, k), l2 * ein%xy(2, k)]
      end do
      call element_routine(ior(act_residual, act_stresses), ein, eout)
      err = 0.0_dp
      do ip = 1, ein%nip
        s11 = eout%sig_ip(1, ip)
        if (finite) then
          jac = exp(ex(st)) * exp(2.0_dp * e22)       ! thickness stretch = lateral
          s11 = s11 * jac                            ! Kirchhoff
        end if
        err = max(err, abs(s11 - sig(st)) / s0, abs(eout%sig_ip(2, ip)) / s0, abs(eout%peeq_ip(ip) - peeq(st)), &
                  abs(eout%hist(5, ip) - peeq(st)))
        if (.not. finite) err = max(err, abs(eout%hist(1, ip) - epl(st)), abs(eout%hist(2, ip) + 0.5_dp * epl(st)), &
                                    abs(eout%hist(3, ip) + 0.5_dp * epl(st)), abs(eout%hist(4, ip)))
        if (finite) err = max(err, abs(eout%hist(1, ip) - (exp(-2.0_dp * epl(st)) - 1.0_dp)), &
                              abs(eout%hist(2, ip) - (exp(epl(st)) - 1.0_dp)))
      end do
      write (tag(8:10), '(i1)') st
      call report('uniaxial plasticity ' // trim(tag), err < 1e-10_dp, 'error ' // num(err))
      ein%hist = eout%hist
    end do
  end subroutine check_uniaxial_plastic

  !> The follower pressure on every face of CPS3, CPE4, CAX4, CPS6, CAX6,
  !> CPE8 and CAX8 (curved faces) at a deformed state.
  subroutine check_follower()
    character(len=4), parameter :: names(7) = ['CPS3', 'CPE4', 'CAX4', 'CPS6', 'CAX6', 'CPE8', 'CAX8']
    type(elem_in_t) :: ein
    real(dp) :: u(2, max_nodes), up(2, max_nodes), f(2, max_nodes), f0(2, max_nodes), fp(2, max_nodes), &
                fm(2, max_nodes), kl(2 * max_nodes, 2 * max_nodes), kd(2 * max_nodes, 2 * max_nodes), &
                kdum(2 * max_nodes, 2 * max_nodes), h, err_k, err_0, err_r, rot(2, 2), th
    integer :: i, it, k, j, nd, nen
    th = 0.7_dp
    rot = reshape([cos(th), sin(th), -sin(th), cos(th)], [2, 2])
    do i = 1, 7
      ein = element(names(i), 1)
      it = find_element_type(names(i))
      nen = ein%nen
      nd = 2 * nen
      ein%thickness(1:nen) = [(1.0_dp + 0.1_dp * k, k = 1, nen)]
      call deform(ein, 0.2_dp)
      u(:, 1:nen) = reshape(ein%ue(1:nd), [2, nen])
      err_k = 0.0_dp
      err_0 = 0.0_dp
      err_r = 0.0_dp
      do k = 1, catalogue(it)%nedges
        call follower_pressure_load(it, ein%xy, u, ein%thickness, k, f, kl)
        h = 1e-6_dp
        do j = 1, nd
          up = u
          up(mod(j - 1, 2) + 1, (j + 1) / 2) = u(mod(j - 1, 2) + 1, (j + 1) / 2) + h
          call follower_pressure_load(it, ein%xy, up, ein%thickness, k, fp, kdum)
          up(mod(j - 1, 2) + 1, (j + 1) / 2) = u(mod(j - 1, 2) + 1, (j + 1) / 2) - h
          call follower_pressure_load(it, ein%xy, up, ein%thickness, k, fm, kdum)
          kd(1:nd, j) = reshape(fp(:, 1:nen) - fm(:, 1:nen), [nd]) / (2.0_dp * h)
        end do
        err_k = max(err_k, maxval(abs(kd(1:nd, 1:nd) - kl(1:nd, 1:nd))) / maxval(abs(kl(1:nd, 1:nd))))
        up = 0.0_dp
        call follower_pressure_load(it, ein%xy, up, ein%thickness, k, f, kdum)
        call face_pressure_load(it, ein%xy, ein%thickness, k, f0)
        err_0 = max(err_0, maxval(abs(f(:, 1:nen) - f0(:, 1:nen))) / maxval(abs(f0(:, 1:nen))))
        if (ein%state /= state_axisymmetric) then
          up(:, 1:nen) = matmul(rot, ein%xy(:, 1:nen)) - ein%xy(:, 1:nen) + spread([0.4_dp, -0.1_dp], 2, nen)
          call follower_pressure_load(it, ein%xy, up, ein%thickness, k, f, kdum)
          err_r = max(err_r, maxval(abs(f(:, 1:nen) - matmul(rot, f0(:, 1:nen)))) / maxval(abs(f0(:, 1:nen))))
        end if
      end do
      call report('follower pressure load stiffness ' // names(i), err_k < 1e-6_dp, 'relative ' // num(err_k))
      call report('follower pressure at zero displacement is the dead load ' // names(i), err_0 < 1e-12_dp, &
                  'relative ' // num(err_0))
      call report('follower pressure turns with the element ' // names(i), err_r < 1e-12_dp, 'relative ' // num(err_r))
    end do
  end subroutine check_follower

  !> thickness_stretch (the plane-stress thickness a follower pressure
  !> acts on): d lambda3 / du against central differences of lambda3 for
  !> CPS3, CPS4, CPS6, CPS8, CPS8R and the four finite-strain laws at a
  !> deformed state (tolerance 1e-6 of the largest entry; lambda3 there
  !> positive and away from 1), and lambda3 = 1, d lambda3 / du = 0 in
  !> plane strain and on the small-strain path. Its value is checked by
  !> tests/test_nonlinear_ps_follower.py (closed form).
  subroutine check_thickness_stretch()
    character(len=5), parameter :: names(5) = ['CPS3 ', 'CPS4 ', 'CPS6 ', 'CPS8 ', 'CPS8R']
    type(elem_in_t) :: ein, ep
    real(dp) :: lam, dlam(2 * max_nodes), lp, lm, dd(2 * max_nodes), err, h
    integer :: i, il, j, nd
    logical :: ok
    h = 1e-6_dp
    do i = 1, 5
      do il = 1, 4
        ein = element(trim(names(i)), il)
        call deform(ein, 0.2_dp)
        nd = 2 * ein%nen
        call thickness_stretch(ein, lam, dlam)
        do j = 1, nd
          ep = ein
          ep%ue(j) = ein%ue(j) + h
          call thickness_stretch(ep, lp, dd)
          ep%ue(j) = ein%ue(j) - h
          call thickness_stretch(ep, lm, dd)
          dd(j) = (lp - lm) / (2.0_dp * h)
          if (j == 1) err = 0.0_dp
          err = max(err, abs(dd(j) - dlam(j)))
        end do
        err = err / maxval(abs(dlam(1:nd)))
        ok = err < 1e-6_dp .and. abs(lam - 1.0_dp) > 1e-3_dp .and. lam > 0.0_dp
        call report('plane-stress thickness stretch derivative ' // trim(names(i)) // ' ' // trim(law_name(il)), &
                    ok, 'relative ' // num(err) // ' lambda3 ' // num(lam))
      end do
    end do
    ein = element('CPE4', 2)
    call deform(ein, 0.2_dp)
    call thickness_stretch(ein, lam, dlam)
    ok = lam == 1.0_dp .and. all(dlam == 0.0_dp)
    ein = element('CPS4', 5)
    call deform(ein, 0.2_dp)
    call thickness_stretch(ein, lam, dlam)
    ok = ok .and. lam == 1.0_dp .and. all(dlam == 0.0_dp)
    call report('thickness stretch 1 in plane strain and at small strain', ok, 'lambda3 ' // num(lam))
  end subroutine check_thickness_stretch

  !> A deformed state u (plastic for il = 4, its history committed), then
  !> the same state rotated by 50 degrees, x -> Q x: the Cauchy stress at
  !> each point must be Q sigma Q^T, PEEQ and the history (Cp^-1 is
  !> invariant) unchanged.
  subroutine check_objectivity(name)
    character(len=*), intent(in) :: name
    type(elem_in_t) :: ein, erot
    type(elem_out_t) :: e1, e2
    real(dp) :: q(2, 2), th, x(2), s1(2, 2), s2(2, 2), err, scale
    integer :: il, k, ip, nd
    th = 50.0_dp * acos(-1.0_dp) / 180.0_dp
    q = reshape([cos(th), sin(th), -sin(th), cos(th)], [2, 2])
    err = 0.0_dp
    do il = 1, 4
      ein = element(name, il)
      nd = 2 * ein%nen
      call deform(ein, 0.06_dp)
      call element_routine(ior(act_residual, act_stresses), ein, e1)
      ein%hist = e1%hist
      call element_routine(ior(act_residual, act_stresses), ein, e1)
      erot = ein
      do k = 1, ein%nen
        x = ein%xy(:, k) + ein%ue(2 * k - 1:2 * k)
        erot%ue(2 * k - 1:2 * k) = matmul(q, x) - ein%xy(:, k)
      end do
      call element_routine(ior(act_residual, act_stresses), erot, e2)
      scale = maxval(abs(e1%sig_ip(:, 1:ein%nip)))
      do ip = 1, ein%nip
        s1 = reshape([e1%sig_ip(1, ip), e1%sig_ip(4, ip), e1%sig_ip(4, ip), e1%sig_ip(2, ip)], [2, 2])
        s2 = reshape([e2%sig_ip(1, ip), e2%sig_ip(4, ip), e2%sig_ip(4, ip), e2%sig_ip(2, ip)], [2, 2])
        err = max(err, maxval(abs(s2 - matmul(matmul(q, s1), transpose(q)))) / scale, &
                  abs(e2%sig_ip(3, ip) - e1%sig_ip(3, ip)) / scale, abs(e2%peeq_ip(ip) - e1%peeq_ip(ip)), &
                  maxval(abs(e2%hist(:, ip) - e1%hist(:, ip))))
      end do
      ! the internal force turns with the element
      do k = 1, ein%nen
        err = max(err, norm2(e2%fe(2 * k - 1:2 * k) - matmul(q, e1%fe(2 * k - 1:2 * k))) &
                       / maxval(abs(e1%fe(1:nd))))
      end do
      if (il == 4 .and. .not. all(e1%peeq_ip(1:ein%nip) > 0.0_dp)) err = huge(1.0_dp)
    end do
    call report('objectivity ' // name, err < 1e-12_dp, 'relative ' // num(err))
  end subroutine check_objectivity

  !> Singular values of ke at zero displacement of a neo-Hookean element
  !> with K / mu = 1e5: those above 1e-3 of the largest are the volumetric
  !> constraints; F-bar leaves one (the element's mean dilatation), the
  !> plain element (St Venant-Kirchhoff with the same moduli) more.
  subroutine check_no_locking(name)
    character(len=*), intent(in) :: name
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    real(dp) :: mu, kb, sv(8), work(200), dum(1, 1), a(8, 8)
    integer :: info, nbig(2), il
    do il = 1, 2
      ein = element(name, 2)
      mu = 2.0_dp * ein%c10
      kb = 1e5_dp * mu
      ein%d1 = 2.0_dp / kb
      if (il == 2) then
        ! the same moduli in St Venant-Kirchhoff: no F-bar
        ein%law = 0
        ein%e = 9.0_dp * kb * mu / (3.0_dp * kb + mu)
        ein%nu = (3.0_dp * kb - 2.0_dp * mu) / (2.0_dp * (3.0_dp * kb + mu))
      end if
      call element_routine(act_tangent, ein, eout)
      a = eout%ke(1:8, 1:8)
      call dgesvd('N', 'N', 8, 8, a, 8, sv, dum, 1, dum, 1, work, 200, info)
      nbig(il) = count(sv > 1e-3_dp * sv(1))
    end do
    call report('F-bar one volumetric constraint ' // name, nbig(1) == 1 .and. nbig(2) > 1, &
                'large singular values with F-bar / without: ' // num(real(nbig(1), dp)) // ' ' // &
                num(real(nbig(2), dp)))
  end subroutine check_no_locking

  !> Newton on one element: the nodes at y = min fixed in y, the node(s)
  !> at the smallest x fixed in x, the nodes at y = max displaced by
  !> stretch times the height in y, the other dofs solved (LAPACK dgesv on
  !> the unsymmetric tangent), in 4 increments.
  subroutine check_newton(name, il, stretch)
    character(len=*), intent(in) :: name
    integer, intent(in) :: il
    real(dp), intent(in) :: stretch
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    logical :: fixed(2 * max_nodes), ok, quadratic
    integer :: free(2 * max_nodes), nf, nd, k, inc, it, info, piv(2 * max_nodes), worst
    real(dp) :: ymin, ymax, xmin, res(0:20), a(2 * max_nodes, 2 * max_nodes), b(2 * max_nodes)
    ein = element(name, il)
    nd = 2 * ein%nen
    ymin = minval(ein%xy(2, 1:ein%nen))
    ymax = maxval(ein%xy(2, 1:ein%nen))
    xmin = minval(ein%xy(1, 1:ein%nen))
    fixed = .false.
    do k = 1, ein%nen
      if (ein%xy(2, k) <= ymin + 1e-12_dp .or. ein%xy(2, k) >= ymax - 0.35_dp) fixed(2 * k) = .true.
      if (ein%xy(1, k) <= xmin + 1e-12_dp) fixed(2 * k - 1) = .true.
    end do
    nf = 0
    do k = 1, nd
      if (.not. fixed(k)) then
        nf = nf + 1
        free(nf) = k
      end if
    end do
    ok = .true.
    quadratic = .true.
    worst = 0
    info = 0
    ein%ue = 0.0_dp
    do inc = 1, 4
      do k = 1, ein%nen
        if (fixed(2 * k) .and. ein%xy(2, k) > ymin + 1e-12_dp) &
          ein%ue(2 * k) = inc / 4.0_dp * stretch * (ein%xy(2, k) - ymin)
      end do
      ! ein%hist stays the committed history through the iterations
      do it = 0, 20
        call element_routine(ior(act_tangent, act_residual), ein, eout)
        res(it) = norm2(eout%fe(free(1:nf)))
        if (res(it) <= 1e-10_dp * res(0)) exit
        a(1:nf, 1:nf) = eout%ke(free(1:nf), free(1:nf))
        b(1:nf) = -eout%fe(free(1:nf))
        call dgesv(nf, 1, a, 2 * max_nodes, piv, b, 2 * max_nodes, info)
        if (info /= 0) exit
        ein%ue(free(1:nf)) = ein%ue(free(1:nf)) + b(1:nf)
      end do
      worst = max(worst, it)
      ok = ok .and. it <= 8 .and. info == 0
      ! quadratic: the last reduction is at least the square of the one
      ! before it (relative to the first residual), with a factor 100
      if (it >= 2 .and. it <= 8) quadratic = quadratic .and. &
        res(it) / res(0) <= 100.0_dp * (res(it - 1) / res(0))**2 + 1e-14_dp
      ein%hist = eout%hist       ! converged: commit
    end do
    call report('Newton on one element ' // name // ' ' // trim(law_name(il)), ok .and. quadratic, &
                'iterations ' // num(real(worst, dp)) // merge(' quadratic    ', ' not quadratic', quadratic))
  end subroutine check_newton

  !> Free thermal expansion under NLGEOM: u = alpha dT X is the thermal
  !> stretch 1 + alpha dT in every direction (plane stress: the thickness
  !> stretch follows from s33 = 0; axisymmetry: the hoop stretch is the
  !> same), no force.
  subroutine check_free_expansion(name)
    character(len=*), intent(in) :: name
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    real(dp) :: c, fmax
    integer :: k
    ein = element(name, 1)
    ein%alpha = 1e-3_dp
    ein%dtemp = 40.0_dp
    c = ein%alpha * 40.0_dp
    do k = 1, ein%nen
      ein%ue(2 * k - 1:2 * k) = c * ein%xy(:, k)
    end do
    call element_routine(ior(act_residual, act_stresses), ein, eout)
    fmax = max(maxval(abs(eout%fe(1:2 * ein%nen))), maxval(abs(eout%sig_ip(:, 1:ein%nip)))) / (ein%e * ein%alpha * 40.0_dp)
    call report('free thermal expansion no force ' // name, fmax < 1e-12_dp, 'relative ' // num(fmax))
  end subroutine check_free_expansion

  !> St Venant-Kirchhoff with a temperature change under NLGEOM at a
  !> homogeneous F (F12 = 0, so that the axisymmetric hoop stretch is F11):
  !> the Cauchy stress at every point against CalculiX 2.20's reading
  !> computed here in 3D, S = lambda tr(Em) I + 2 mu Em with Em the
  !> Lagrange strain of Fm = F - alpha dT I (calcmechstrain.f of 2.20:
  !> the thermal strain taken from the displacement gradient), sigma =
  !> F S F^T / det F; plane stress: F33 from S33 = 0 (relative 1e-12).
  subroutine check_thermal_nlgeom(name)
    character(len=*), intent(in) :: name
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    real(dp) :: f(3, 3), fm(3, 3), em(3, 3), s(3, 3), sig(3, 3), eth, lam, mu, err
    integer :: k, ip
    ein = element(name, 1)
    ein%alpha = 2e-3_dp
    ein%dtemp = 40.0_dp
    eth = ein%alpha * 40.0_dp
    f = 0.0_dp
    f(1:2, 1:2) = reshape([1.2_dp, 0.07_dp, 0.0_dp, 0.9_dp], [2, 2])
    f(3, 3) = 1.0_dp
    if (ein%state == state_axisymmetric) f(3, 3) = f(1, 1)
    do k = 1, ein%nen
      ein%ue(2 * k - 1:2 * k) = matmul(f(1:2, 1:2), ein%xy(:, k)) - ein%xy(:, k)
    end do
    call element_routine(ior(act_residual, act_stresses), ein, eout)
    lam = ein%e * ein%nu / ((1.0_dp + ein%nu) * (1.0_dp - 2.0_dp * ein%nu))
    mu = ein%e / (2.0_dp * (1.0_dp + ein%nu))
    fm = f
    do k = 1, 3
      fm(k, k) = f(k, k) - eth
    end do
    em = 0.5_dp * matmul(transpose(fm), fm)
    do k = 1, 3
      em(k, k) = em(k, k) - 0.5_dp
    end do
    if (ein%state == state_plane_stress) then
      em(3, 3) = -lam * (em(1, 1) + em(2, 2)) / (lam + 2.0_dp * mu)
      f(3, 3) = eth + sqrt(1.0_dp + 2.0_dp * em(3, 3))
    end if
    s = 2.0_dp * mu * em
    do k = 1, 3
      s(k, k) = s(k, k) + lam * (em(1, 1) + em(2, 2) + em(3, 3))
    end do
    sig = matmul(matmul(f, s), transpose(f)) / (f(3, 3) * (f(1, 1) * f(2, 2) - f(1, 2) * f(2, 1)))
    err = 0.0_dp
    do ip = 1, ein%nip
      err = max(err, maxval(abs(eout%sig_ip(:, ip) - [sig(1, 1), sig(2, 2), sig(3, 3), sig(1, 2)])))
    end do
    err = err / maxval(abs(sig))
    call report('St Venant-Kirchhoff thermal strain under NLGEOM as CalculiX 2.20 ' // name, err < 1e-12_dp, &
                'relative ' // num(err))
  end subroutine check_thermal_nlgeom

  !> Deformations the laws cannot evaluate: NaN in ue must be reported
  !> (detj_min <= 0, the driver cuts back) and no array may hold NaN or
  !> Infinity, for NaN in ue, a volume ratio of 1e-27 (ue = -(1 - 1e-9) X)
  !> and displacements of 1e11 times the element's size.
  subroutine check_bad_deformation(name, il, lname)
    character(len=*), intent(in) :: name, lname
    integer, intent(in) :: il
    character(len=8), parameter :: what(3) = ['NaN     ', 'collapse', 'huge    ']
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    integer :: ic, nd
    logical :: ok
    do ic = 1, 3
      ein = element(name, il)
      nd = 2 * ein%nen
      call deform(ein, 0.06_dp)
      select case (ic)
      case (1)
        ein%ue(3) = ieee_value(1.0_dp, ieee_quiet_nan)
      case (2)
        ein%ue(1:nd) = -(1.0_dp - 1e-9_dp) * reshape(ein%xy(:, 1:ein%nen), [nd])
      case (3)
        ein%ue(1:nd) = 1e11_dp * ein%ue(1:nd)
      end select
      call element_routine(ior(act_tangent, ior(act_residual, act_stresses)), ein, eout)
      ok = all(ieee_is_finite(eout%ke(1:nd, 1:nd))) .and. all(ieee_is_finite(eout%fe(1:nd))) .and. &
           all(ieee_is_finite(eout%sig_ip(:, 1:ein%nip))) .and. all(ieee_is_finite(eout%sig_node(:, 1:ein%nen))) .and. &
           all(ieee_is_finite(eout%eps_ip(:, 1:ein%nip))) .and. all(ieee_is_finite(eout%hist(:, 1:ein%nip))) .and. &
           all(ieee_is_finite(eout%peeq_ip(1:ein%nip))) .and. ieee_is_finite(eout%detj_min)
      if (ic == 1) ok = ok .and. eout%detj_min <= 0.0_dp
      call report('bad deformation ' // trim(what(ic)) // ' ' // name // ' ' // lname, ok, &
                  'detj_min ' // num(eout%detj_min))
    end do
  end subroutine check_bad_deformation

  !> A hardening table with a drop steeper than 3 mu (300 at PEEQ 0, 100
  !> from 1e-6 on): the local problem has no root on the drop, the return
  !> must land on the flat part beyond it, Mises = 100 and PEEQ = (q_tr -
  !> 100) / (3 mu) with q_tr = 2 mu e (small strain, uniaxial strain e =
  !> 0.01) or 2 mu ln(1 + e) and the Kirchhoff stress (finite strain);
  !> relative 1e-12.
  subroutine check_steep_drop(finite)
    logical, intent(in) :: finite
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    real(dp) :: mu, qtr, jac, sg(4), mises, err
    integer :: k
    ein = element('CPE4', merge(4, 5, finite))
    ein%xy(:, 1:4) = reshape([0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, 1.0_dp, 0.0_dp, 1.0_dp], [2, 4])
    ein%e = 200000.0_dp
    ein%nyield = 3
    ein%yield(:, 1:3) = reshape([300.0_dp, 0.0_dp, 100.0_dp, 1e-6_dp, 100.0_dp, 1.0_dp], [2, 3])
    do k = 1, 4
      ein%ue(2 * k - 1:2 * k) = [0.01_dp * ein%xy(1, k), 0.0_dp]
    end do
    call element_routine(ior(act_residual, act_stresses), ein, eout)
    mu = ein%e / (2.0_dp * (1.0_dp + ein%nu))
    qtr = 2.0_dp * mu * 0.01_dp
    jac = 1.0_dp
    if (finite) then
      qtr = 2.0_dp * mu * log(1.01_dp)
      jac = 1.01_dp
    end if
    err = 0.0_dp
    do k = 1, ein%nip
      sg = eout%sig_ip(:, k) * jac
      mises = sqrt(0.5_dp * ((sg(1) - sg(2))**2 + (sg(2) - sg(3))**2 + (sg(3) - sg(1))**2) + 3.0_dp * sg(4)**2)
      err = max(err, abs(mises - 100.0_dp) / 100.0_dp, &
                abs(eout%peeq_ip(k) - (qtr - 100.0_dp) / (3.0_dp * mu)) / ((qtr - 100.0_dp) / (3.0_dp * mu)))
    end do
    call report('hardening table with a drop steeper than 3 mu ' // merge('finite', 'small ', finite), &
                err < 1e-12_dp, 'relative ' // num(err))
  end subroutine check_steep_drop

  !> The elastic laws have no history and must not read ein%hist, which
  !> callers leave undefined (element_interface gives it no default; the
  !> driver's setup stiffness is built without it): with NaN there, the
  !> same fe, a zero history and PEEQ, and a positive detj_min.
  subroutine check_no_history_read(name, il, lname)
    character(len=*), intent(in) :: name, lname
    integer, intent(in) :: il
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout, eref
    integer :: nd
    ein = element(name, il)
    nd = 2 * ein%nen
    call deform(ein, 0.1_dp)
    call element_routine(ior(act_tangent, ior(act_residual, act_stresses)), ein, eref)
    ein%hist = ieee_value(1.0_dp, ieee_quiet_nan)
    call element_routine(ior(act_tangent, ior(act_residual, act_stresses)), ein, eout)
    call report('elastic law ignores ein%hist ' // name // ' ' // lname, all(eout%fe(1:nd) == eref%fe(1:nd)) &
                .and. all(eout%hist == 0.0_dp) .and. all(eout%peeq_ip == 0.0_dp) .and. eout%detj_min > 0.0_dp, &
                'detj_min ' // num(eout%detj_min))
  end subroutine check_no_history_read

  !> Plane-stress St Venant-Kirchhoff stretched 1.5 each way (nu = 0.3):
  !> S33 = 0 asks 1 + 2 Em33 < 0, no real thickness stretch; the element
  !> must report it (detj_min <= 0), not return F33 = 1e-154 and stresses
  !> of 1e156 with a positive detj_min.
  subroutine check_no_thickness()
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    integer :: k
    ein = element('CPS4', 1)
    do k = 1, ein%nen
      ein%ue(2 * k - 1:2 * k) = 0.5_dp * ein%xy(:, k)
    end do
    call element_routine(ior(act_tangent, ior(act_residual, act_stresses)), ein, eout)
    call report('plane-stress St Venant-Kirchhoff without a thickness stretch reported', eout%detj_min <= 0.0_dp, &
                'detj_min ' // num(eout%detj_min))
  end subroutine check_no_thickness

  function num(x) result(s)
    real(dp), intent(in) :: x
    character(len=:), allocatable :: s
    character(len=24) :: buf
    write (buf, '(es12.4)') x
    s = trim(adjustl(buf))
  end function num
end program test_nonlinear
