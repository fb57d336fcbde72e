!> Element-level checks of the continuum elements, every shape in every
!> stress state: symmetry; the zero-energy modes (three rigid-body modes in
!> the plane, one axial translation in axisymmetry, and the one spurious
!> mode of the 8-node quadrilateral with 2x2 points; none more for the
!> one-point quadrilateral, whose hourglass modes are stabilized) and full rank
!> otherwise; zero force for rigid motions; exact stresses for a linear
!> displacement field (distorted and curved elements) and, for the
!> quadratic elements, for a quadratic field (straight-sided elements);
!> consistent nodal loads of pressure and body forces, also with a
!> thickness that varies inside the element. The truss and the springs:
!> their stiffness in closed form for an inclined member, and the truss's
!> axial stress and thermal load.
program test_elements
  use kinds, only: dp
  use test_report, only: report, failures
  use element_interface, only: elem_in_t, elem_out_t, kind_tri3, kind_quad8, kind_truss2, kind_truss3, &
                               kind_spring1, kind_spring2, kind_springa, act_tangent, act_residual, act_stresses, &
                               act_thermal
  use element_catalogue, only: state_plane_stress, state_axisymmetric, max_nodes, find_element_type, catalogue
  use element_library, only: element_routine
  use shape_functions, only: shape_at, gauss_rule
  use distributed_loads, only: face_pressure_load, body_force_load
  implicit none
  real(dp), parameter :: pi = 3.14159265358979323846_dp
  ! corners of a distorted quadrilateral and a general triangle
  real(dp), parameter :: q4(2, 4) = reshape([0.0_dp, 0.0_dp, 2.2_dp, 0.3_dp, 1.9_dp, 1.7_dp, -0.2_dp, 1.1_dp], [2, 4])
  real(dp), parameter :: t3(2, 3) = reshape([0.1_dp, -0.2_dp, 1.7_dp, 0.4_dp, 0.6_dp, 1.3_dp], [2, 3])
  ! a parallelogram (an affine image of the square)
  real(dp), parameter :: par(2, 4) = reshape([0.0_dp, 0.0_dp, 2.0_dp, 0.4_dp, 2.6_dp, 1.9_dp, 0.6_dp, 1.5_dp], [2, 4])
  character(len=3), parameter :: prefix(3) = ['CPS', 'CPE', 'CAX']
  real(dp) :: xy(2, max_nodes)
  integer :: is

  ! every continuum type of the catalogue: its shape, rule and state
  do is = 1, 3
    call check_element('Q4 ', prefix(is) // '4', shifted(q4, 4, is), .false.)
    ! one point with hourglass stabilization: no zero-energy mode but the
    ! rigid ones, linear fields exact
    call check_element('Q4R ', prefix(is) // '4R', shifted(q4, 4, is), .false.)
    call check_element('T3 ', prefix(is) // '3', shifted(t3, 3, is), .false.)
    xy = quad8_nodes(q4, 0.08_dp)
    call check_element('Q8 curved ', prefix(is) // '8', shifted(xy, 8, is), .false.)
    call check_element('Q8R curved ', prefix(is) // '8R', shifted(xy, 8, is), .false.)
    xy = tri6_nodes(t3, 0.06_dp)
    call check_element('T6 curved ', prefix(is) // '6', shifted(xy, 6, is), .false.)
    xy = quad8_nodes(par, 0.0_dp)
    call check_element('Q8 ', prefix(is) // '8', shifted(xy, 8, is), .true.)
    call check_element('Q8R ', prefix(is) // '8R', shifted(xy, 8, is), .true.)
    xy = tri6_nodes(t3, 0.0_dp)
    call check_element('T6 ', prefix(is) // '6', shifted(xy, 6, is), .true.)
  end do
  call check_loads()
  call check_varying_thickness()
  call check_truss()
  call check_springs()
  if (failures() > 0) stop 1

contains

  !> Nodes moved to x > 0.5 for axisymmetry (r > 0), as given otherwise.
  function shifted(x, n, is) result(y)
    real(dp), intent(in) :: x(:, :)
    integer, intent(in) :: n, is
    real(dp) :: y(2, max_nodes)
    y = 0.0_dp
    y(:, 1:n) = x(:, 1:n)
    if (is == 3) y(1, 1:n) = y(1, 1:n) + 0.7_dp
  end function shifted

  !> 8-node quadrilateral on corners c: mid-side nodes at the edge
  !> midpoints pushed out by bulge times the edge length (curved edges).
  function quad8_nodes(c, bulge) result(x)
    real(dp), intent(in) :: c(2, 4), bulge
    real(dp) :: x(2, max_nodes), d(2)
    integer :: k
    x = 0.0_dp
    x(:, 1:4) = c
    do k = 1, 4
      d = c(:, mod(k, 4) + 1) - c(:, k)
      x(:, 4 + k) = 0.5_dp * (c(:, k) + c(:, mod(k, 4) + 1)) + bulge * [d(2), -d(1)]
    end do
  end function quad8_nodes

  function tri6_nodes(c, bulge) result(x)
    real(dp), intent(in) :: c(2, 3), bulge
    real(dp) :: x(2, max_nodes), d(2)
    integer :: k
    x = 0.0_dp
    x(:, 1:3) = c
    do k = 1, 3
      d = c(:, mod(k, 3) + 1) - c(:, k)
      x(:, 3 + k) = 0.5_dp * (c(:, k) + c(:, mod(k, 3) + 1)) + bulge * [d(2), -d(1)]
    end do
  end function tri6_nodes

  !> Elasticity matrix for (e11, e22, g12, e33) -> (s11, s22, s12, s33),
  !> written out independently of the program's.
  function dmat(e, nu, state) result(d)
    real(dp), intent(in) :: e, nu
    integer, intent(in) :: state
    real(dp) :: d(4, 4), lam, mu
    mu = e / (2 * (1 + nu))
    lam = e * nu / ((1 + nu) * (1 - 2 * nu))
    if (state == state_plane_stress) lam = 2 * mu * lam / (lam + 2 * mu)
    d = 0.0_dp
    d(1:2, 1:2) = lam
    d(1, 1) = lam + 2 * mu
    d(2, 2) = lam + 2 * mu
    d(3, 3) = mu
    if (state /= state_plane_stress) then
      d(4, 1:2) = lam
      d(1:2, 4) = lam
      d(4, 4) = lam + 2 * mu
    end if
  end function dmat

  !> Exact displacement of the test fields at x: linear (quad = false) or
  !> with quadratic terms; and its strain (e11, e22, g12, e33).
  subroutine field(x, state, quad, u, eps)
    real(dp), intent(in) :: x(2)
    integer, intent(in) :: state
    logical, intent(in) :: quad
    real(dp), intent(out) :: u(2), eps(4)
    real(dp), parameter :: a = 1.0e-3_dp, b = 2.0e-4_dp, c = -5.0e-4_dp, d = -3.0e-4_dp
    real(dp), parameter :: qa = 4.0e-4_dp, qb = -2.5e-4_dp, qc = 3.0e-4_dp, qd = 1.5e-4_dp
    real(dp) :: bb
    ! in axisymmetry u_r must not depend on z alone (b = 0): u_r/r constant
    bb = b
    if (state == state_axisymmetric) bb = 0.0_dp
    u = [a * x(1) + bb * x(2), c * x(1) + d * x(2)]
    eps = [a, d, bb + c, 0.0_dp]
    if (quad) then
      u(1) = u(1) + qa * x(1)**2 + qb * x(1) * x(2)
      u(2) = u(2) + qc * x(2)**2 + qd * x(1) * x(2)
      eps(1) = eps(1) + 2 * qa * x(1) + qb * x(2)
      eps(2) = eps(2) + 2 * qc * x(2) + qd * x(1)
      eps(3) = eps(3) + qb * x(1) + qd * x(2)
    end if
    if (state == state_axisymmetric) eps(4) = u(1) / x(1)
  end subroutine field

  subroutine check_element(label, tname, x, quadratic)
    character(len=*), intent(in) :: label, tname
    real(dp), intent(in) :: x(2, max_nodes)
    logical, intent(in) :: quadratic
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    real(dp), allocatable :: k(:, :), w(:), work(:)
    real(dp) :: r(2 * max_nodes, 3), c, asym, big, u(2), eps(4), sig(4), d(4, 4), err, smax
    real(dp) :: xg(2, 9), wg(9), n(max_nodes), dn(2, max_nodes), xp(2)
    character(len=200) :: msg
    character(len=:), allocatable :: name
    integer :: nd, info, nzero, i, j, nrigid, expect, kind, nen, nip, state, et
    et = find_element_type(tname)
    kind = catalogue(et)%shape
    nen = catalogue(et)%nodes
    nip = catalogue(et)%nip
    state = catalogue(et)%state
    name = label // trim(tname)
    ein%e = 210000.0_dp
    ein%nu = 0.3_dp
    ein%thickness = 2.5_dp
    ein%kind = kind
    ein%nen = nen
    ein%nip = nip
    ein%state = state
    ein%xy(:, 1:nen) = x(:, 1:nen)
    call element_routine(ior(ior(act_tangent, act_residual), act_stresses), ein, eout)
    nd = eout%ndof
    k = eout%ke(1:nd, 1:nd)
    big = maxval(abs(k))
    asym = maxval(abs(k - transpose(k))) / big
    write(msg, '(a,es9.2)') 'relative asymmetry ', asym
    call report(name // ' stiffness symmetric', asym < 1.0e-14_dp, msg)

    ! zero-energy modes: eigenvalues below 1e-10 of the largest (LAPACK dsyev)
    allocate(w(nd), work(10 * nd))
    call dsyev('N', 'U', nd, k, nd, w, work, size(work), info)
    nzero = count(abs(w) < 1.0e-10_dp * maxval(abs(w)))
    nrigid = 3
    if (state == state_axisymmetric) nrigid = 1
    expect = nrigid
    ! The 8-node quadrilateral with 2x2 points has one spurious mode (not
    ! communicable through a mesh); in axisymmetry the hoop strain gives it
    ! a small stiffness (about 5e-5 of the largest) once an edge is curved.
    if (kind == kind_quad8 .and. nip == 4 .and. .not. (state == state_axisymmetric .and. index(label, 'curved') > 0)) &
      expect = nrigid + 1
    ! The one-point axisymmetric triangle (CAX3, as Abaqus's): a rotation
    ! about its centroid strains nothing at the centroid. In a mesh the
    ! neighbours' different centroids stop it.
    if (kind == kind_tri3 .and. state == state_axisymmetric) expect = nrigid + 1
    ! So has the one-point quadrilateral (CAX4R): its one hoop strain is
    ! the mean over 2 pi r dA, zero for a rotation about the centroid of
    ! its area; the hourglass stabilization leaves linear fields alone.
    if (nip == 1 .and. state == state_axisymmetric) expect = nrigid + 1
    write(msg, '(a,i0,a,i0,a,i0,a,es9.2)') 'zero eigenvalues ', nzero, ' expected ', expect, ', info ', info, &
      ', smallest ', minval(w)
    call report(name // ' zero-energy modes', info == 0 .and. nzero == expect .and. &
                minval(w) > -1.0e-10_dp * maxval(w), msg)

    ! rigid motions give no force: translations (only the axial one in
    ! axisymmetry) and a small rotation
    do i = 1, nen
      r(2 * i - 1:2 * i, 1) = [0.0_dp, 1.0_dp]
      r(2 * i - 1:2 * i, 2) = [1.0_dp, 0.0_dp]
      r(2 * i - 1:2 * i, 3) = [-x(2, i), x(1, i)]
    end do
    c = 0.0_dp
    do j = 1, nrigid
      c = max(c, maxval(abs(matmul(eout%ke(1:nd, 1:nd), r(1:nd, j)))) / (big * maxval(abs(r(1:nd, j)))))
    end do
    write(msg, '(a,es9.2)') 'relative force ', c
    call report(name // ' rigid motion strain-free', c < 1.0e-13_dp, msg)

    ! the linear field (and the quadratic one): exact stresses at every
    ! integration point and node
    d = dmat(ein%e, ein%nu, state)
    do j = 1, merge(2, 1, quadratic)
      do i = 1, nen
        call field(x(:, i), state, j == 2, u, eps)
        ein%ue(2 * i - 1:2 * i) = u
      end do
      call element_routine(act_stresses, ein, eout)
      call gauss_rule(kind, nip, xg, wg)
      err = 0.0_dp
      smax = 0.0_dp
      do i = 1, nip
        call shape_at(kind, xg(:, i), n, dn)
        xp = matmul(x(:, 1:nen), n(1:nen))
        call field(xp, state, j == 2, u, eps)
        sig = matmul(d, eps)
        smax = max(smax, maxval(abs(sig)))
        err = max(err, maxval(abs(eout%sig_ip(:, i) - [sig(1), sig(2), sig(4), sig(3)])))
      end do
      do i = 1, nen
        call field(x(:, i), state, j == 2, u, eps)
        sig = matmul(d, eps)
        err = max(err, maxval(abs(eout%sig_node(:, i) - [sig(1), sig(2), sig(4), sig(3)])))
      end do
      write(msg, '(a,es9.2)') 'relative stress error ', err / smax
      call report(name // merge(' quadratic field exact', ' linear field exact   ', j == 2), &
                  err / smax < 1.0e-11_dp, msg)
    end do
  end subroutine check_element

  !> Pressure and body-force loads: the 1/6, 4/6, 1/6 split on a straight
  !> quadratic face; the resultant of a pressure on a curved face (the
  !> chord turned by 90 degrees, whatever the curvature); in axisymmetry the
  !> axial resultant pi (r2^2 - r1^2) p of a flat annular face; body forces
  !> summing to b times the volume (2 pi r_c A in axisymmetry).
  subroutine check_loads()
    real(dp) :: f(2, max_nodes), x(2, max_nodes), err, tot(2), expect(2), area
    character(len=160) :: msg
    integer :: et
    x = quad8_nodes(par, 0.0_dp)
    et = find_element_type('CPS8')
    call face_pressure_load(et, x, uniform(2.0_dp), 1, f)
    ! face 1 runs from (0, 0) to (2, 0.4): the force is -p n_out times the length
    expect = -2.0_dp * [0.4_dp, -2.0_dp]
    err = maxval(abs(f(:, [1, 2, 5]) - reshape([expect / 6, expect / 6, 4 * expect / 6], [2, 3])))
    err = err + maxval(abs(f(:, [3, 4, 6, 7, 8])))
    write(msg, '(a,es9.2)') 'error ', err
    call report('pressure on a straight 3-node face: 1/6, 4/6, 1/6', err < 1.0e-14_dp, msg)

    x = quad8_nodes(q4, 0.1_dp)
    call face_pressure_load(et, x, uniform(2.0_dp), 2, f)
    tot = sum(f, dim=2)
    expect = -2.0_dp * [q4(2, 3) - q4(2, 2), -(q4(1, 3) - q4(1, 2))]
    err = maxval(abs(tot - expect)) / maxval(abs(expect))
    write(msg, '(a,es9.2)') 'relative error ', err
    call report('pressure on a curved face: resultant = chord x thickness', err < 1.0e-14_dp, msg)

    et = find_element_type('CAX8')
    x = quad8_nodes(reshape([1.0_dp, 0.0_dp, 3.0_dp, 0.0_dp, 3.0_dp, 1.0_dp, 1.0_dp, 1.0_dp], [2, 4]), 0.0_dp)
    call face_pressure_load(et, x, uniform(1.0_dp), 3, f)
    tot = sum(f, dim=2)
    expect = [0.0_dp, -pi * (3.0_dp**2 - 1.0_dp**2)]
    err = maxval(abs(tot - expect)) / maxval(abs(expect))
    write(msg, '(a,es9.2)') 'relative error ', err
    call report('axisymmetric pressure on an annulus: pi (r2^2 - r1^2) p', err < 1.0e-14_dp, msg)

    ! body force on the CAX8 ring of cross-section [1,3] x [0,1]: volume 2 pi * 2 * 2
    call body_force_load(et, x, uniform(1.0_dp), [0.0_dp, -3.0_dp], reshape([0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], [2, 2]), &
                         [0.0_dp, 0.0_dp], f)
    tot = sum(f, dim=2)
    expect = [0.0_dp, -3.0_dp * 2 * pi * 2.0_dp * 2.0_dp]
    err = maxval(abs(tot - expect)) / maxval(abs(expect))
    write(msg, '(a,es9.2)') 'relative error ', err
    call report('axisymmetric body force: b x 2 pi r_c A', err < 1.0e-14_dp, msg)

    ! centrifugal b = w2 r on the ring: total radial force w2 * 2 pi int r^2 dA = w2 2 pi (27 - 1)/3
    call body_force_load(et, x, uniform(1.0_dp), [0.0_dp, 0.0_dp], reshape([5.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], [2, 2]), &
                         [0.0_dp, 0.0_dp], f)
    tot = sum(f, dim=2)
    expect = [5.0_dp * 2 * pi * 26.0_dp / 3.0_dp, 0.0_dp]
    err = maxval(abs(tot - expect)) / maxval(abs(expect))
    write(msg, '(a,es9.2)') 'relative error ', err
    call report('axisymmetric centrifugal load: w2 2 pi int r^2 dA', err < 1.0e-14_dp, msg)

    ! plane body force on a distorted 6-node triangle: b x area x thickness
    et = find_element_type('CPS6')
    x = tri6_nodes(t3, 0.0_dp)
    area = 0.5_dp * ((t3(1, 2) - t3(1, 1)) * (t3(2, 3) - t3(2, 1)) - (t3(1, 3) - t3(1, 1)) * (t3(2, 2) - t3(2, 1)))
    call body_force_load(et, x, uniform(0.5_dp), [1.0_dp, 2.0_dp], reshape([0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], [2, 2]), &
                         [0.0_dp, 0.0_dp], f)
    tot = sum(f, dim=2)
    expect = [1.0_dp, 2.0_dp] * area * 0.5_dp
    err = maxval(abs(tot - expect)) / maxval(abs(expect))
    ! a 6-node triangle's constant body force goes to the mid-side nodes only
    err = err + maxval(abs(f(:, 1:3))) + maxval(abs(f(:, 4:6) - spread(expect / 3, 2, 3)))
    write(msg, '(a,es9.2)') 'error ', err
    call report('body force on T6: b x area x thickness, all on the mid-side nodes', err < 1.0e-14_dp, msg)
  end subroutine check_loads

  !> The same thickness at every node.
  pure function uniform(t) result(a)
    real(dp), intent(in) :: t
    real(dp) :: a(max_nodes)
    a = t
  end function uniform

  !> A thickness linear in x over a CPS4 rectangle [0, 2] x [0, 1], t =
  !> 1 + x: a pressure on the right face (t = 3) gives p h t; on the
  !> bottom face the consistent loads of a linear thickness, L (2 t1 + t2)
  !> / 6 and L (t1 + 2 t2) / 6; a unit body force the integral of N_i t;
  !> a uniform strain (u = 1e-3 x) the internal forces integral of
  !> B^T sigma t: at node 1 (-sxx, -syy int (1 - x/2)(1 + x) dx = -5/3
  !> syy), at node 2 (sxx, -syy int x/2 (1 + x) dx = -7/3 syy).
  subroutine check_varying_thickness()
    real(dp) :: f(2, max_nodes), x(2, max_nodes), t(max_nodes), err, expect(2, 2), fvol(4), sxx, syy
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    character(len=160) :: msg
    integer :: et, k
    et = find_element_type('CPS4')
    x = 0.0_dp
    x(:, 1:4) = reshape([0.0_dp, 0.0_dp, 2.0_dp, 0.0_dp, 2.0_dp, 1.0_dp, 0.0_dp, 1.0_dp], [2, 4])
    t = 1.0_dp
    t(1:4) = 1.0_dp + x(1, 1:4)
    call face_pressure_load(et, x, t, 2, f)
    err = maxval(abs(f(:, 2:3) - reshape([-1.5_dp, 0.0_dp, -1.5_dp, 0.0_dp], [2, 2])))
    call face_pressure_load(et, x, t, 1, f)
    expect = reshape([0.0_dp, 2.0_dp * (2 * 1 + 3) / 6, 0.0_dp, 2.0_dp * (1 + 2 * 3) / 6], [2, 2])
    err = err + maxval(abs(f(:, 1:2) - expect))
    call body_force_load(et, x, t, [1.0_dp, 0.0_dp], reshape([0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], [2, 2]), &
                         [0.0_dp, 0.0_dp], f)
    fvol = [5.0_dp, 7.0_dp, 7.0_dp, 5.0_dp] / 6.0_dp
    err = err + maxval(abs(f(1, 1:4) - fvol))
    write(msg, '(a,es9.2)') 'error ', err
    call report('loads with a thickness 1 + x: pressure, consistent edge loads, body force', err < 1.0e-14_dp, msg)
    ein%e = 100.0_dp
    ein%nu = 0.25_dp
    ein%kind = catalogue(et)%shape
    ein%nen = 4
    ein%nip = 4
    ein%state = catalogue(et)%state
    ein%xy(:, 1:4) = x(:, 1:4)
    do k = 1, 4
      ein%ue(2 * k - 1:2 * k) = [1.0e-3_dp * x(1, k), 0.0_dp]
    end do
    ein%thickness = t
    call element_routine(ior(act_tangent, act_residual), ein, eout)
    sxx = ein%e / (1.0_dp - ein%nu**2) * 1.0e-3_dp
    syy = ein%nu * sxx
    err = maxval(abs(eout%fe(1:4) - [-sxx, -5.0_dp / 3.0_dp * syy, sxx, -7.0_dp / 3.0_dp * syy])) / sxx
    write(msg, '(a,es9.2)') 'relative error ', err
    call report('uniform strain, thickness 1 + x: internal forces integral of B^T sigma t', err < 1.0e-14_dp, msg)
  end subroutine check_varying_thickness

  !> A bar from (1, 2) along (cos a, sin a), length L: ke = E A / L (g g^T)
  !> with g = (-c, -s, c, s); a 3-node bar (middle node at the middle) is
  !> as stiff for a linear field; stresses E eps; the thermal load E A
  !> alpha dT at the ends.
  subroutine check_truss()
    real(dp), parameter :: ang = 0.7_dp, len = 2.5_dp, e = 200.0_dp, area = 0.3_dp
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    real(dp) :: g(4), err, dir(2), x2(2), u(4)
    character(len=160) :: msg
    integer :: i
    dir = [cos(ang), sin(ang)]
    x2 = [1.0_dp, 2.0_dp] + len * dir
    g = [-dir, dir]
    ein%kind = kind_truss2
    ein%nen = 2
    ein%nip = 1
    ein%e = e
    ein%area = area
    ein%xy(:, 1:2) = reshape([1.0_dp, 2.0_dp, x2], [2, 2])
    u = [0.1_dp, -0.2_dp, 0.4_dp, 0.3_dp]
    ein%ue(1:4) = u
    ein%alpha = 1.0e-5_dp
    ein%dtemp(1:2) = 50.0_dp
    call element_routine(ior(ior(act_tangent, act_stresses), act_thermal), ein, eout)
    err = 0.0_dp
    do i = 1, 4
      err = max(err, maxval(abs(eout%ke(1:4, i) - e * area / len * g(i) * g)))
    end do
    err = err / (e * area / len)
    err = err + abs(eout%sig_ip(1, 1) - e * (dot_product(g, u) / len - 1.0e-5_dp * 50.0_dp)) / e
    err = err + maxval(abs(eout%fe(1:4) - e * area * 1.0e-5_dp * 50.0_dp * g)) / (e * area)
    write(msg, '(a,es9.2)') 'relative error ', err
    call report('inclined 2-node truss: E A / L g g^T, axial stress, thermal load', err < 1.0e-14_dp, msg)
    ! the 3-node truss lists end, middle, end
    ein%kind = kind_truss3
    ein%nen = 3
    ein%nip = 2
    ein%xy(:, 1:3) = reshape([1.0_dp, 2.0_dp, [1.0_dp, 2.0_dp] + 0.5_dp * len * dir, x2], [2, 3])
    ein%ue(1:6) = [u(1:2), 0.5_dp * (u(1:2) + u(3:4)), u(3:4)]
    ein%dtemp(1:3) = 50.0_dp
    call element_routine(ior(ior(act_tangent, act_stresses), act_residual), ein, eout)
    err = maxval(abs(eout%sig_ip(1, 1:2) - e * (dot_product(g, u) / len - 1.0e-5_dp * 50.0_dp))) / e
    ! fe = ke ue for the linear field: end forces E A eps (-dir, dir), none at the middle
    err = err + maxval(abs(eout%fe(1:6) - e * area * dot_product(g, u) / len * [g(1:2), 0.0_dp, 0.0_dp, g(3:4)])) &
          / (e * area)
    write(msg, '(a,es9.2)') 'relative error ', err
    call report('3-node truss: axial stress and end forces of a linear field', err < 1.0e-13_dp, msg)
  end subroutine check_truss

  !> SPRING1 on dof 2: k at (2, 2) only; SPRING2 from dof 1 to dof 2:
  !> k g g^T, g = (1, 0, 0, -1); SPRINGA along (3, 4) / 5: k g g^T.
  subroutine check_springs()
    real(dp), parameter :: k = 7.0_dp
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    real(dp) :: g(4), err
    character(len=160) :: msg
    integer :: i
    ein%stiffness = k
    ein%kind = kind_spring1
    ein%nen = 1
    ein%dofs = [2, 0]
    call element_routine(act_tangent, ein, eout)
    err = abs(eout%ke(2, 2) - k) + abs(eout%ke(1, 1)) + abs(eout%ke(1, 2)) + abs(eout%ndof - 2)
    ein%kind = kind_spring2
    ein%nen = 2
    ein%dofs = [1, 2]
    call element_routine(act_tangent, ein, eout)
    g = [1.0_dp, 0.0_dp, 0.0_dp, -1.0_dp]
    do i = 1, 4
      err = err + maxval(abs(eout%ke(1:4, i) - k * g(i) * g))
    end do
    ein%kind = kind_springa
    ein%xy(:, 1:2) = reshape([1.0_dp, 1.0_dp, 4.0_dp, 5.0_dp], [2, 2])
    call element_routine(act_tangent, ein, eout)
    g = [-0.6_dp, -0.8_dp, 0.6_dp, 0.8_dp]
    do i = 1, 4
      err = err + maxval(abs(eout%ke(1:4, i) - k * g(i) * g))
    end do
    write(msg, '(a,es9.2)') 'error ', err
    call report('springs: SPRING1, SPRING2 and SPRINGA stiffness', err < 1.0e-14_dp, msg)
  end subroutine check_springs
end program test_elements
