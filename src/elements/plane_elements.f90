!> Isoparametric plane stress / plane strain elements: the bilinear
!> quadrilateral (2x2 Gauss) and the constant-strain triangle.
module plane_elements
  use kinds, only: dp
  use element_interface, only: elem_in_t, elem_out_t, act_tangent, act_residual, act_stresses, wants
  use materials, only: elastic_matrix, out_of_plane_stress
  implicit none
  private
  public :: quad4, tri3, quad4_shape, tri3_shape

  real(dp), parameter :: xi_node(4) = [-1.0_dp, 1.0_dp, 1.0_dp, -1.0_dp]
  real(dp), parameter :: eta_node(4) = [-1.0_dp, -1.0_dp, 1.0_dp, 1.0_dp]

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

  !> Strain-displacement matrix from natural derivatives; returns det J.
  pure subroutine strain_matrix(nen, xy, dn, b, detj)
    integer, intent(in) :: nen
    real(dp), intent(in) :: xy(2, nen), dn(2, nen)
    real(dp), intent(out) :: b(3, 2 * nen), detj
    real(dp) :: jac(2, 2), jinv(2, 2), dx(2, nen)
    integer :: k
    jac = matmul(dn, transpose(xy))
    detj = jac(1, 1) * jac(2, 2) - jac(1, 2) * jac(2, 1)
    jinv(1, 1) = jac(2, 2) / detj
    jinv(2, 2) = jac(1, 1) / detj
    jinv(1, 2) = -jac(1, 2) / detj
    jinv(2, 1) = -jac(2, 1) / detj
    dx = matmul(jinv, dn)
    b = 0.0_dp
    do k = 1, nen
      b(1, 2 * k - 1) = dx(1, k)
      b(2, 2 * k) = dx(2, k)
      b(3, 2 * k - 1) = dx(2, k)
      b(3, 2 * k) = dx(1, k)
    end do
  end subroutine strain_matrix

  !> Purpose: the bilinear quadrilateral, 2x2 Gauss.
  !> Arguments: action (act_* codes), ein, eout: ke and fe = ke ue for
  !> act_tangent/act_residual, integration-point and nodal stresses for
  !> act_stresses.
  pure subroutine quad4(action, ein, eout)
    integer, intent(in) :: action
    type(elem_in_t), intent(in) :: ein
    type(elem_out_t), intent(out) :: eout
    real(dp), parameter :: g = 1.0_dp / sqrt(3.0_dp)
    real(dp) :: d(3, 3), n(4), dn(2, 4), b(3, 8), db(3, 8), detj, eps(3), sig(3), w(4)
    integer :: ip, k, i, j
    logical :: need_k
    need_k = wants(action, act_tangent) .or. wants(action, act_residual)
    d = elastic_matrix(ein%e, ein%nu, ein%state)
    eout%ndof = 8
    eout%nip = 4
    ! Gauss points in the order of the corners they are nearest to, so that
    ! extrapolation to node k uses the bilinear field through them.
    do ip = 1, 4
      call quad4_shape(g * xi_node(ip), g * eta_node(ip), n, dn)
      call strain_matrix(4, ein%xy(:, 1:4), dn, b, detj)
      if (need_k) then
        ! upper triangle of B^T D B, mirrored below after the loop
        db = matmul(d, b) * (detj * ein%thickness)
        do j = 1, 8
          do i = 1, j
            eout%ke(i, j) = eout%ke(i, j) + b(1, i) * db(1, j) + b(2, i) * db(2, j) + b(3, i) * db(3, j)
          end do
        end do
      end if
      if (wants(action, act_stresses)) then
        eps = matmul(b, ein%ue(1:8))
        sig = matmul(d, eps)
        eout%eps_ip(:, ip) = eps
        eout%sig_ip(:, ip) = [sig(1), sig(2), out_of_plane_stress(sig(1), sig(2), ein%nu, ein%state), sig(3)]
      end if
    end do
    if (need_k) then
      do j = 1, 7
        eout%ke(j + 1:8, j) = eout%ke(j, j + 1:8)
      end do
    end if
    if (wants(action, act_residual)) eout%fe(1:8) = matmul(eout%ke(1:8, 1:8), ein%ue(1:8))
    if (.not. wants(action, act_tangent)) eout%ke = 0.0_dp
    if (wants(action, act_stresses)) then
      ! Node k sits at natural coordinates sqrt(3)*(xi_k, eta_k) of the
      ! Gauss-point grid.
      do k = 1, 4
        call quad4_shape(sqrt(3.0_dp) * xi_node(k), sqrt(3.0_dp) * eta_node(k), w, dn)
        eout%sig_node(:, k) = matmul(eout%sig_ip(:, 1:4), w)
      end do
    end if
  end subroutine quad4

  !> Purpose: the constant-strain triangle (one point).
  !> Arguments: as quad4.
  pure subroutine tri3(action, ein, eout)
    integer, intent(in) :: action
    type(elem_in_t), intent(in) :: ein
    type(elem_out_t), intent(out) :: eout
    real(dp) :: d(3, 3), n(3), dn(2, 3), b(3, 6), detj, eps(3), sig(3)
    integer :: k
    d = elastic_matrix(ein%e, ein%nu, ein%state)
    eout%ndof = 6
    eout%nip = 1
    call tri3_shape(1.0_dp / 3.0_dp, 1.0_dp / 3.0_dp, n, dn)
    call strain_matrix(3, ein%xy(:, 1:3), dn, b, detj)
    if (wants(action, act_tangent) .or. wants(action, act_residual)) &
      eout%ke(1:6, 1:6) = matmul(transpose(b), matmul(d, b)) * 0.5_dp * detj * ein%thickness
    if (wants(action, act_residual)) eout%fe(1:6) = matmul(eout%ke(1:6, 1:6), ein%ue(1:6))
    if (.not. wants(action, act_tangent)) eout%ke = 0.0_dp
    if (wants(action, act_stresses)) then
      eps = matmul(b, ein%ue(1:6))
      sig = matmul(d, eps)
      eout%eps_ip(:, 1) = eps
      eout%sig_ip(:, 1) = [sig(1), sig(2), out_of_plane_stress(sig(1), sig(2), ein%nu, ein%state), sig(3)]
      do k = 1, 3
        eout%sig_node(:, k) = eout%sig_ip(:, 1)
      end do
    end if
  end subroutine tri3
end module plane_elements
