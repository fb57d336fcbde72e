!> The coupling finite element at element level (eqs. 3-10): symmetry and
!> rank of K_e, F_int = K_e D_e + B_e^T C [[U]]_0, K_e as the derivative of
!> F_int, and [[U]] equal to the current slave-to-X_C vector; a master
!> side of given weights (segment-to-segment) against the shape functions
!> at X_C, and the dual shape functions of the mortar integrals
!> (biorthogonality, partition of unity).
program test_cfe
  use kinds, only: dp
  use test_report, only: report, failures
  use element_interface, only: cfe_in_t, cfe_out_t, kind_quad4, kind_tri3, act_tangent, act_residual
  use cfe_element, only: cfe, cfe_b_matrix
  use shape_functions, only: quad4_shape, tri3_shape, gauss_line
  use contact_geometry, only: edge_t, edge_at, edge_weights, area_factor
  use contact_mortar, only: mortar_dual
  implicit none
  call check('CFE on Q4 master', kind_quad4, 4, [0.3_dp, 1.0_dp])
  call check('CFE on T3 master', kind_tri3, 3, [0.35_dp, 0.65_dp])
  call check_slave_point()
  call check_friction(.false., 0.0_dp, 'sticking')
  call check_friction(.true., 1.0_dp, 'sliding along +t')
  call check_friction(.true., -1.0_dp, 'sliding along -t')
  call check_given_master_weights()
  call check_dual(2, .false., 'straight 2-node plane face')
  call check_dual(2, .true., '2-node axisymmetric face')
  call check_dual(3, .false., 'curved 3-node plane face')
  call check_dual(3, .true., 'curved 3-node axisymmetric face')
  if (failures() > 0) stop 1

contains


  subroutine check(name, mkind, nm, xi)
    character(len=*), intent(in) :: name
    integer, intent(in) :: mkind, nm
    real(dp), intent(in) :: xi(2)
    type(cfe_in_t) :: ein, ep, em
    type(cfe_out_t) :: eout, op, om
    real(dp) :: b(2, 2 * (nm + 1)), c(2, 2), f_expect(10), kfd(10, 10), err, h, n(4), dn(2, 4)
    real(dp) :: xc(2), uc(2), jump_geo(2), theta, xy(2, 5)
    character(len=120) :: msg
    integer :: nd, j, i
    ein%master_kind = mkind
    ein%nen = nm + 1
    ein%xi = xi
    ! A tilted master edge: outward normal at 30 degrees from -y.
    theta = 0.5235987755982988_dp
    ein%normal = [sin(theta), -cos(theta)]
    ein%penalty = 3.7e9_dp
    ! Master nodes (nodes 2..nm+1) and their displacements.
    xy(:, 2:5) = reshape([0.0_dp, 0.0_dp, 1.1_dp, 0.1_dp, 1.0_dp, 0.9_dp, -0.1_dp, 1.0_dp], [2, 4])
    nd = 2 * (nm + 1)
    allocate(ein%ue(nd))
    do i = 1, nd
      ein%ue(i) = 1.0e-4_dp * sin(1.3_dp * i)
    end do
    if (mkind == kind_quad4) then
      call quad4_shape(xi(1), xi(2), n, dn)
    else
      call tri3_shape(xi(1), xi(2), n(1:3), dn(:, 1:3))
    end if
    xc = matmul(xy(:, 2:nm + 1), n(1:nm))
    ein%gap0 = 2.0e-4_dp * ein%normal + [1.0e-5_dp, 0.0_dp]
    xy(:, 1) = xc + ein%gap0
    call cfe(ior(act_tangent, act_residual), ein, eout)

    err = maxval(abs(eout%ke(1:nd, 1:nd) - transpose(eout%ke(1:nd, 1:nd)))) / maxval(abs(eout%ke(1:nd, 1:nd)))
    write(msg, '(a,es9.2)') 'relative asymmetry ', err
    call report(name // ': K_e symmetric (eq. 10)', err < 1.0e-15_dp, msg)

    ! eq. (9)
    call cfe_b_matrix(ein, b)
    do j = 1, 2
      do i = 1, 2
        c(i, j) = ein%penalty * ein%normal(i) * ein%normal(j)
      end do
    end do
    f_expect(1:nd) = matmul(eout%ke(1:nd, 1:nd), ein%ue(1:nd)) + matmul(transpose(b), matmul(c, ein%gap0))
    err = maxval(abs(eout%fe(1:nd) - f_expect(1:nd))) / maxval(abs(f_expect(1:nd)))
    write(msg, '(a,es9.2)') 'relative difference ', err
    call report(name // ': F_int = K_e D_e + B_e^T C [[U]]_0 (eq. 9)', err < 1.0e-13_dp, msg)

    ! K_e as the central-difference derivative of F_int.
    h = 1.0e-7_dp
    do j = 1, nd
      ep = ein
      em = ein
      ep%ue(j) = ep%ue(j) + h
      em%ue(j) = em%ue(j) - h
      call cfe(ior(act_tangent, act_residual), ep, op)
      call cfe(ior(act_tangent, act_residual), em, om)
      kfd(1:nd, j) = (op%fe(1:nd) - om%fe(1:nd)) / (2.0_dp * h)
    end do
    err = maxval(abs(kfd(1:nd, 1:nd) - eout%ke(1:nd, 1:nd))) / maxval(abs(eout%ke(1:nd, 1:nd)))
    write(msg, '(a,es9.2)') 'relative difference ', err
    call report(name // ': K_e equals dF_int/dD_e by finite differences', err < 1.0e-6_dp, msg)

    ! [[U]] of eq. (8) is the current vector from X_C (moved with the master)
    ! to the slave node; its normal part is the gap, and the force is c*gap.
    uc = matmul(reshape(ein%ue(3:nd), [2, nm]), n(1:nm))
    jump_geo = (xy(:, 1) + ein%ue(1:2)) - (xc + uc)
    err = maxval(abs(eout%jump - jump_geo)) / maxval(abs(jump_geo))
    write(msg, '(a,es9.2)') 'relative difference ', err
    call report(name // ': [[U]] = B_e D_e + [[U]]_0 is the slave-to-X_C vector (eq. 8)', err < 1.0e-12_dp, msg)
    err = abs(eout%normal_force - ein%penalty * dot_product(ein%normal, jump_geo)) / abs(eout%normal_force)
    write(msg, '(a,es9.2)') 'relative difference ', err
    call report(name // ': normal force = penalty * normal gap', err < 1.0e-12_dp, msg)

    ! Only the normal direction is stiff: K_e has rank one, and a tangential
    ! slide of the slave node costs no force.
    ep = ein
    ep%ue(1:2) = ep%ue(1:2) + 1.0e-3_dp * [cos(theta), sin(theta)]
    call cfe(ior(act_tangent, act_residual), ep, op)
    err = maxval(abs(op%fe(1:nd) - eout%fe(1:nd))) / maxval(abs(eout%fe(1:nd)))
    write(msg, '(a,es9.2)') 'relative force change ', err
    call report(name // ': frictionless (tangential slide changes no force)', err < 1.0e-9_dp, msg)
  end subroutine check

  !> Coulomb friction on a closed, penetrating CFE over a Q4 master edge
  !> tilted by 30 degrees: K_e is dF_int/dD_e by central differences
  !> (sticking: symmetric; sliding: unsymmetric, the tangential force
  !> following the normal gap); the tangential force is k_t (t.[[U]] -
  !> anchor) sticking and slip_sign mu times the normal force's magnitude
  !> sliding, along t = (-n_y, n_x).
  subroutine check_friction(sliding, sgn, what)
    logical, intent(in) :: sliding
    real(dp), intent(in) :: sgn
    character(len=*), intent(in) :: what
    type(cfe_in_t) :: ein, ep, em
    type(cfe_out_t) :: eout, op, om
    real(dp) :: kfd(10, 10), err, h, theta, t(2), expect, asym
    character(len=120) :: msg
    integer :: i, j, nd
    ein%master_kind = kind_quad4
    ein%nen = 5
    ein%xi = [0.3_dp, 1.0_dp]
    theta = 0.5235987755982988_dp
    ein%normal = [sin(theta), -cos(theta)]
    ein%penalty = 3.7e9_dp
    ein%closed = .true.
    ein%mu = 0.3_dp
    ein%k_tan = 1.9e9_dp
    ein%sliding = sliding
    ein%slip_sign = sgn
    ein%anchor = 2.0e-5_dp
    ein%gap0 = -3.0e-5_dp * ein%normal
    nd = 10
    allocate(ein%ue(nd))
    do i = 1, nd
      ein%ue(i) = 1.0e-5_dp * sin(1.7_dp * i)
    end do
    call cfe(ior(act_tangent, act_residual), ein, eout)
    call report('friction, ' // what // ': closed and penetrating', eout%gap < 0.0_dp, 'the test setup opened')
    h = 1.0e-8_dp
    do j = 1, nd
      ep = ein
      em = ein
      ep%ue(j) = ep%ue(j) + h
      em%ue(j) = em%ue(j) - h
      call cfe(act_residual, ep, op)
      call cfe(act_residual, em, om)
      kfd(1:nd, j) = (op%fe(1:nd) - om%fe(1:nd)) / (2.0_dp * h)
    end do
    err = maxval(abs(kfd(1:nd, 1:nd) - eout%ke(1:nd, 1:nd))) / maxval(abs(eout%ke(1:nd, 1:nd)))
    write(msg, '(a,es9.2)') 'relative difference ', err
    call report('friction, ' // what // ': K_e equals dF_int/dD_e by finite differences', err < 1.0e-6_dp, msg)
    asym = maxval(abs(eout%ke(1:nd, 1:nd) - transpose(eout%ke(1:nd, 1:nd)))) / maxval(abs(eout%ke(1:nd, 1:nd)))
    write(msg, '(a,es9.2)') 'relative asymmetry ', asym
    if (sliding) then
      call report('friction, ' // what // ': K_e unsymmetric', asym > 1.0e-3_dp, msg)
    else
      call report('friction, ' // what // ': K_e symmetric', asym < 1.0e-15_dp, msg)
    end if
    t = [-ein%normal(2), ein%normal(1)]
    if (sliding) then
      expect = sgn * ein%mu * abs(eout%normal_force)
    else
      expect = ein%k_tan * (dot_product(t, eout%jump) - ein%anchor)
    end if
    err = abs(eout%tangential_force - expect) / abs(expect)
    write(msg, '(a,es9.2)') 'relative difference ', err
    call report('friction, ' // what // ': tangential force (Coulomb, return mapping)', err < 1.0e-13_dp, msg)
    ! the internal force is B_e^T (normal force n + tangential force t)
    err = abs(dot_product(t, eout%fe(1:2)) - eout%tangential_force) / abs(eout%tangential_force)
    write(msg, '(a,es9.2)') 'relative difference ', err
    call report('friction, ' // what // ': the slave node carries the tangential force along t', err < 1.0e-12_dp, msg)
  end subroutine check_friction

  !> A coupling point between two slave nodes (weights 0.3, 0.7), as the
  !> paper's section 5 allows: the element behaves as a one-node CFE whose
  !> node moves as the weighted slave nodes, and the slave forces are the
  !> weights times that node's force.
  subroutine check_slave_point()
    type(cfe_in_t) :: e1, e2
    type(cfe_out_t) :: o1, o2
    real(dp), parameter :: w(2) = [0.3_dp, 0.7_dp]
    real(dp) :: err, f_expect(12), b1(2, 10), b2(2, 12)
    character(len=120) :: msg
    integer :: i
    ! the one-node reference: coupling node + Q4 master
    e1%master_kind = kind_quad4
    e1%nen = 5
    e1%xi = [0.2_dp, 1.0_dp]
    e1%normal = [0.0_dp, -1.0_dp]
    e1%penalty = 2.0e8_dp
    allocate(e1%ue(10))
    e1%ue = 0.0_dp
    do i = 3, 10
      e1%ue(i) = 1.0e-4_dp * cos(0.7_dp * i)
    end do
    ! two slave nodes whose weighted position and displacement give node 1 of e1
    e2 = e1
    e2%ns = 2
    e2%ws(1:2) = w
    e2%nen = 6
    deallocate(e2%ue)
    allocate(e2%ue(12))
    e2%ue(5:12) = e1%ue(3:10)
    e2%ue(1:4) = [1.0e-4_dp, -3.0e-4_dp, -2.0e-4_dp, -1.0e-4_dp]
    e1%ue(1:2) = w(1) * e2%ue(1:2) + w(2) * e2%ue(3:4)
    e1%gap0 = [0.0_dp, 1.0e-5_dp]
    e2%gap0 = e1%gap0
    call cfe(ior(act_tangent, act_residual), e1, o1)
    call cfe(ior(act_tangent, act_residual), e2, o2)
    err = abs(o2%gap - o1%gap) / abs(o1%gap)
    write(msg, '(a,es9.2)') 'relative gap difference ', err
    call report('CFE with a slave point between two nodes: same gap as the one-node CFE', err < 1.0e-13_dp, msg)
    f_expect(1:2) = w(1) * o1%fe(1:2)
    f_expect(3:4) = w(2) * o1%fe(1:2)
    f_expect(5:12) = o1%fe(3:10)
    err = maxval(abs(o2%fe(1:12) - f_expect)) / maxval(abs(f_expect))
    write(msg, '(a,es9.2)') 'relative difference ', err
    call report('CFE with a slave point: slave forces are the weights times the point force', err < 1.0e-13_dp, msg)
    call cfe_b_matrix(e1, b1)
    call cfe_b_matrix(e2, b2)
    err = maxval(abs(b2(:, 1:2) - w(1) * b1(:, 1:2))) + maxval(abs(b2(:, 3:4) - w(2) * b1(:, 1:2))) + &
          maxval(abs(b2(:, 5:12) - b1(:, 3:10)))
    write(msg, '(a,es9.2)') 'largest difference ', err
    call report('CFE with a slave point: B_e holds the weights on the slave side (eq. 4)', err < 1.0e-15_dp, msg)
    err = maxval(abs(o2%ke(1:12, 1:12) - transpose(o2%ke(1:12, 1:12)))) / maxval(abs(o2%ke))
    write(msg, '(a,es9.2)') 'relative asymmetry ', err
    call report('CFE with a slave point: K_e symmetric', err < 1.0e-15_dp, msg)
  end subroutine check_slave_point

  !> A master side of given weights (master_kind 0, ein%wm) equal to the
  !> Q4 shape functions at X_C: the same gap, forces and K_e as the CFE on
  !> the Q4 master element.
  subroutine check_given_master_weights()
    type(cfe_in_t) :: e1, e2
    type(cfe_out_t) :: o1, o2
    real(dp) :: n(4), dn(2, 4), err
    character(len=120) :: msg
    integer :: i
    e1%master_kind = kind_quad4
    e1%nen = 5
    e1%xi = [0.2_dp, 1.0_dp]
    e1%normal = [0.6_dp, -0.8_dp]
    e1%penalty = 2.0e8_dp
    e1%gap0 = [1.0e-6_dp, -2.0e-5_dp]
    allocate(e1%ue(10))
    do i = 1, 10
      e1%ue(i) = 1.0e-4_dp * cos(0.7_dp * i)
    end do
    e2 = e1
    e2%master_kind = 0
    call quad4_shape(e1%xi(1), e1%xi(2), n, dn)
    e2%wm = n
    call cfe(ior(act_tangent, act_residual), e1, o1)
    call cfe(ior(act_tangent, act_residual), e2, o2)
    err = abs(o2%gap - o1%gap) / abs(o1%gap) + maxval(abs(o2%fe(1:10) - o1%fe(1:10))) / maxval(abs(o1%fe(1:10))) + &
          maxval(abs(o2%ke(1:10, 1:10) - o1%ke(1:10, 1:10))) / maxval(abs(o1%ke(1:10, 1:10)))
    write(msg, '(a,es9.2)') 'relative difference ', err
    call report('CFE with given master weights: as the shape functions at X_C', err < 1.0e-14_dp, msg)
  end subroutine check_given_master_weights

  !> The dual shape functions Phi_i = sum_k a(i, k) N_k of a slave face:
  !> int Phi_i N_k da = delta_ik int N_i da with the three-point rule of
  !> the mortar integrals (da: length times thickness, or 2 pi r ds), and
  !> sum_i Phi_i = 1.
  subroutine check_dual(nn, axi, what)
    integer, intent(in) :: nn
    logical, intent(in) :: axi
    character(len=*), intent(in) :: what
    type(edge_t) :: ed
    real(dp) :: a(3, 3), s(3), w(3), t, p(2), dpdt(2), nv(3), phi(3), da, mix(3, 3), d(3), err
    character(len=120) :: msg
    integer :: ig, i
    ed%nn = nn
    ed%axi = axi
    ed%x(:, 1) = [0.4_dp, 1.0_dp]
    ed%x(:, 2) = [1.6_dp, 1.3_dp]
    ed%x(:, 3) = [1.0_dp, 1.25_dp]          ! mid-side node off the chord
    ed%thickness = [0.8_dp, 1.2_dp, 1.0_dp]
    a = mortar_dual(ed)
    call gauss_line(3, s, w)
    mix = 0.0_dp
    d = 0.0_dp
    do ig = 1, 3
      t = 0.5_dp * (s(ig) + 1.0_dp)
      call edge_at(ed, t, p, dpdt)
      nv = edge_weights(ed, t)
      phi = matmul(a, nv)
      da = 0.5_dp * w(ig) * norm2(dpdt) * area_factor(ed, t, p(1))
      do i = 1, nn
        mix(i, 1:nn) = mix(i, 1:nn) + da * phi(i) * nv(1:nn)
        d(i) = d(i) + da * nv(i)
      end do
    end do
    err = 0.0_dp
    do i = 1, nn
      mix(i, i) = mix(i, i) - d(i)
    end do
    err = maxval(abs(mix(1:nn, 1:nn))) / maxval(d(1:nn)) + maxval(abs(sum(a(1:nn, 1:nn), dim=1) - 1.0_dp))
    write(msg, '(a,es9.2)') 'largest deviation ', err
    call report('dual shape functions, ' // what // ': biorthogonal, sum to one', err < 1.0e-13_dp, msg)
  end subroutine check_dual
end program test_cfe
