!> The coupling finite element (CFE) of the contact method: a coupling
!> node (the slave node) tied to the material point X_C of a master
!> isoparametric element through a normal penalty. Node 1 is the coupling
!> node, nodes 2..nen are the master element's nodes in its own order.
module cfe_element
  use kinds, only: dp
  use element_types, only: elem_in_t, elem_out_t, kind_quad4, kind_tri3
  use plane_elements, only: quad4_shape, tri3_shape
  implicit none
  private
  public :: cfe, cfe_b_matrix

contains

  !> B_e of eq. (4), preceded by the identity of the coupling node, so that
  !> B_e D_e = u_C - sum_i N_i(X_C) u_i, the relative displacement of eq. (3).
  pure subroutine cfe_b_matrix(ein, b)
    type(elem_in_t), intent(in) :: ein
    real(dp), intent(out) :: b(2, 2 * ein%nen)
    real(dp) :: n(4), dn(2, 4)
    integer :: nm, k
    nm = ein%nen - 1
    if (ein%master_kind == kind_quad4) then
      call quad4_shape(ein%xi(1), ein%xi(2), n, dn)
    else
      call tri3_shape(ein%xi(1), ein%xi(2), n(1:3), dn(:, 1:3))
    end if
    b = 0.0_dp
    b(1, 1) = 1.0_dp
    b(2, 2) = 1.0_dp
    do k = 1, nm
      b(1, 2 * k + 1) = -n(k)
      b(2, 2 * k + 2) = -n(k)
    end do
  end subroutine cfe_b_matrix

  pure subroutine cfe(ein, eout)
    type(elem_in_t), intent(in) :: ein
    type(elem_out_t), intent(out) :: eout
    real(dp) :: b(2, 2 * ein%nen), c(2, 2), cb(2, 2 * ein%nen)
    integer :: nd, i, j
    nd = 2 * ein%nen
    eout%ndof = nd
    eout%nip = 0
    call cfe_b_matrix(ein, b)
    ! eq. (7): C = R^T c R with c = diag(c_n, 0): only the normal penalty.
    do j = 1, 2
      do i = 1, 2
        c(i, j) = ein%penalty * ein%normal(i) * ein%normal(j)
      end do
    end do
    ! eq. (8): [[U]] = B_e D_e + [[U]]_0
    eout%jump = matmul(b, ein%ue(1:nd)) + ein%gap0
    eout%gap = dot_product(ein%normal, eout%jump)
    eout%normal_force = ein%penalty * eout%gap
    cb = matmul(c, b)
    ! eq. (10): K_e = B_e^T C B_e
    eout%ke(1:nd, 1:nd) = matmul(transpose(b), cb)
    ! eq. (9): F_int = B_e^T C B_e D_e + B_e^T C [[U]]_0 = B_e^T C [[U]]
    eout%fe(1:nd) = matmul(transpose(b), matmul(c, eout%jump))
  end subroutine cfe
end module cfe_element
