!> The truss: a 2- or 3-node line element (T2D2, T3D2, T2D3, T3D3 given a
!> *SOLID SECTION, as CalculiX makes them) that carries an axial force
!> only. Isoparametric along its arc s in [-1, 1]: at a point the unit
!> tangent is e = x' / |x'| (x' = dx/ds), the axial strain
!> eps = e . u' / |x'| and the axial stress E (eps - alpha dT), with the
!> area A of the section; K = integral of B^T E A B |x'| ds. One Gauss
!> point for 2 nodes, two for 3: exact for a straight truss. Small
!> displacements: the direction is the reference one. Its stresses are
!> S11 = axial stress, E11 = axial strain at each point (the other
!> components zero); it adds nothing to the nodal stresses of the
!> continuum.
module truss_element
  use kinds, only: dp
  use element_interface, only: elem_in_t, elem_out_t, act_tangent, act_residual, act_stresses, &
                               act_thermal, wants
  use shape_functions, only: truss_shape, gauss_line
  implicit none
  private
  public :: truss

contains

  !> Purpose: the axial strain row b (d eps / d ue) and |dx/ds| at s, and
  !> the shape functions n in the element's node order.
  pure subroutine axial_row(nen, xy, s, n, b, jac)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xy(2, nen), s
    real(dp), intent(out) :: n(nen), b(2 * nen), jac
    real(dp) :: nl(3), dl(3), ds(nen), tangent(2)
    integer :: k
    call truss_shape(nen, s, nl, dl)
    n = nl(1:nen)
    ds = dl(1:nen)
    tangent = matmul(xy, ds)
    jac = norm2(tangent)
    do k = 1, nen
      b(2 * k - 1:2 * k) = tangent * ds(k) / jac**2
    end do
  end subroutine axial_row

  !> Purpose: element arrays of a truss.
  !> Arguments: action (act_* codes), ein (kind_truss2/3, nen = 2 or 3, xy, ue, e,
  !> area, nip, alpha, dtemp), eout: ke and fe = ke ue; for act_stresses
  !> the axial stress and strain at the points (S11, E11); for
  !> act_thermal fe = the nodal load of the thermal strain.
  pure subroutine truss(action, ein, eout)
    integer, intent(in) :: action
    type(elem_in_t), intent(in) :: ein
    type(elem_out_t), intent(out) :: eout
    real(dp) :: s(3), w(3), n(3), b(6), jac, eps, eps0, ea
    integer :: ip, nen, nd, i
    nen = ein%nen
    nd = 2 * nen
    eout%ndof = nd
    eout%ke(1:nd, 1:nd) = 0.0_dp
    eout%nip = ein%nip
    eout%detj_min = huge(1.0_dp)
    ea = ein%e * ein%area
    call gauss_line(ein%nip, s, w)
    do ip = 1, ein%nip
      call axial_row(nen, ein%xy(:, 1:nen), s(ip), n(1:nen), b(1:nd), jac)
      eout%detj_min = min(eout%detj_min, jac)
      eps0 = ein%alpha * dot_product(n(1:nen), ein%dtemp(1:nen))
      if (wants(action, act_tangent) .or. wants(action, act_residual)) then
        do i = 1, nd
          eout%ke(1:nd, i) = eout%ke(1:nd, i) + b(1:nd) * (b(i) * ea * jac * w(ip))
        end do
      end if
      if (wants(action, act_thermal)) eout%fe(1:nd) = eout%fe(1:nd) + b(1:nd) * (ea * eps0 * jac * w(ip))
      if (wants(action, act_stresses)) then
        eps = dot_product(b(1:nd), ein%ue(1:nd))
        eout%eps_ip(:, ip) = [eps, 0.0_dp, 0.0_dp]
        eout%sig_ip(:, ip) = [ein%e * (eps - eps0), 0.0_dp, 0.0_dp, 0.0_dp]
      end if
    end do
    if (wants(action, act_residual)) eout%fe(1:nd) = matmul(eout%ke(1:nd, 1:nd), ein%ue(1:nd))
    if (.not. wants(action, act_tangent)) eout%ke(1:nd, 1:nd) = 0.0_dp
  end subroutine truss
end module truss_element
