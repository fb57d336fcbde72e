!> The coupling finite element (CFE) of the contact method: a coupling
!> point on the slave side tied to the material point X_C of a master
!> isoparametric element through a normal penalty. The coupling point is
!> the weighted combination sum_j w_j x_j of the ns slave nodes (one node
!> with weight 1 for node-to-segment contact; any point of a slave edge
!> otherwise, as section 5 of the paper allows). Nodes 1..ns are the slave
!> nodes, nodes ns+1..nen the master element's nodes in its own order, or
!> (master_kind 0, segment-to-segment contact) master nodes whose weights
!> are given (ein%wm: the mortar integrals, contact_mortar). Its input and
!> output (cfe_in_t, cfe_out_t) are its own, sized by each coupling: a
!> segment-to-segment coupling holds as many master (or slave) nodes as
!> its support reaches.
module cfe_element
  use kinds, only: dp
  use element_catalogue, only: max_nodes
  use element_interface, only: cfe_in_t, cfe_out_t, act_tangent, act_residual, wants, max_slave
  use shape_functions, only: shape_at
  implicit none
  private
  public :: cfe, cfe_b_matrix

contains

  !> Purpose: B_e of eq. (4), preceded by the weights of the slave nodes,
  !> so that B_e D_e = sum_j w_j u_j - sum_i N_i(X_C) u_i, the relative
  !> displacement of eq. (3).
  pure subroutine cfe_b_matrix(ein, b)
    type(cfe_in_t), intent(in) :: ein
    real(dp), intent(out) :: b(2, 2 * ein%nen)
    real(dp) :: n(max(ein%nen, max_nodes)), dn(2, max_nodes)
    integer :: nm, k
    nm = ein%nen - ein%ns
    if (ein%master_kind == 0) then
      ! segment-to-segment: the mortar weights of the master nodes
      n = 0.0_dp
      n(1:nm) = ein%wm(1:nm)
    else
      call shape_at(ein%master_kind, ein%xi, n, dn)
    end if
    b = 0.0_dp
    do k = 1, ein%ns
      b(1, 2 * k - 1) = ein%ws(k)
      b(2, 2 * k) = ein%ws(k)
    end do
    do k = 1, nm
      b(1, 2 * (ein%ns + k) - 1) = -n(k)
      b(2, 2 * (ein%ns + k)) = -n(k)
    end do
  end subroutine cfe_b_matrix

  !> Purpose: the weights of B_e (eq. 4) per node, with their signs:
  !> w(1:ns) the slave weights, w(ns+1:nen) minus the master shape
  !> functions at X_C (or minus the segment-to-segment weights), so that
  !> B_e = [w_1 I, ..., w_nen I] (I the 2 x 2 identity): cfe_b_matrix's
  !> numbers, one per node.
  pure subroutine cfe_weights(ein, w)
    type(cfe_in_t), intent(in) :: ein
    real(dp), intent(out) :: w(:)
    real(dp) :: n(max_nodes), dn(2, max_nodes)
    integer :: nm
    nm = ein%nen - ein%ns
    w(1:ein%ns) = ein%ws(1:ein%ns)
    if (ein%master_kind == 0) then
      w(ein%ns + 1:ein%nen) = -ein%wm(1:nm)
    else
      call shape_at(ein%master_kind, ein%xi, n, dn)
      w(ein%ns + 1:ein%nen) = -n(1:nm)
    end if
  end subroutine cfe_weights

  !> Purpose: element arrays of a coupling element.
  !> Arguments: action (act_tangent: K_e, eout%ke allocated only then;
  !> act_residual: F_int, the relative displacement, gap, normal force,
  !> slide and tangential force), ein, eout.
  !> Friction (ein%mu > 0, closed only): eq. (7)'s c gets a tangential
  !> factor. Sticking, C = c_n n n^T + k_t t t^T and the tangential force
  !> is k_t (t.[[U]] - anchor); sliding, the tangential force is
  !> slip_sign mu times the normal pressure force -c_n g, whose
  !> derivative makes K_e unsymmetric: -slip_sign mu c_n B^T t n^T B.
  !> B_e = [w_1 I, ..., w_nen I] (cfe_weights) is not formed: the
  !> products with it are taken node by node, each sum in the order (and
  !> with the only non-zero terms) of the matrix products of eqs. (8) to
  !> (10) (the coupling element is evaluated at every status of every
  !> increment of a fretting history).
  pure subroutine cfe(action, ein, eout)
    integer, intent(in) :: action
    type(cfe_in_t), intent(in) :: ein
    type(cfe_out_t), intent(out) :: eout
    ! (the weights of a node-to-segment coupling on the stack: an array
    ! sized by nen would be allocated on the heap at every call)
    real(dp) :: wfix(max_nodes + max_slave)
    real(dp), allocatable :: wlong(:)
    if (ein%nen <= size(wfix)) then
      call cfe_weights(ein, wfix)
      call cfe_arrays(action, ein, wfix, eout)
    else
      allocate(wlong(ein%nen))
      call cfe_weights(ein, wlong)
      call cfe_arrays(action, ein, wlong, eout)
    end if
  end subroutine cfe

  !> Purpose: cfe's arrays, given the weights w(1:nen) of B_e
  !> (cfe_weights).
  pure subroutine cfe_arrays(action, ein, w, eout)
    integer, intent(in) :: action
    type(cfe_in_t), intent(in) :: ein
    real(dp), intent(in) :: w(:)
    type(cfe_out_t), intent(out) :: eout
    real(dp) :: c(2, 2), rel(2), t(2), ft, v(2)
    integer :: nd, i, j, a, b
    nd = 2 * ein%nen
    eout%ndof = nd
    ! the tangent only where asked for: a residual evaluation (every CFE
    ! at every status iteration) need not fill a matrix that grows with
    ! the square of the coupling's nodes
    allocate(eout%fe(nd))
    eout%fe = 0.0_dp
    t = [-ein%normal(2), ein%normal(1)]
    call constitutive(ein, t, c)
    ! eq. (10): K_e = B_e^T C B_e, block (a, b) = w_a (C w_b)
    if (wants(action, act_tangent)) then
      allocate(eout%ke(nd, nd))
      do b = 1, ein%nen
        do a = 1, ein%nen
          do j = 1, 2
            do i = 1, 2
              eout%ke(2 * a - 2 + i, 2 * b - 2 + j) = w(a) * (c(i, j) * w(b))
            end do
          end do
        end do
      end do
    end if
    if (.not. wants(action, act_residual)) return
    ! B_e D_e: the weighted sum of the nodes' displacements
    rel = 0.0_dp
    do a = 1, ein%nen
      rel = rel + w(a) * ein%ue(2 * a - 1:2 * a)
    end do
    ! eq. (8): [[U]] = B_e D_e + [[U]]_0
    eout%jump = rel + ein%gap0
    eout%gap = dot_product(ein%normal, eout%jump)
    eout%slide = dot_product(t, eout%jump)
    if (ein%closed) then
      ! eq. (9): F_int = B_e^T C B_e D_e + B_e^T C [[U]]_0 = B_e^T C [[U]]
      eout%normal_force = ein%penalty * eout%gap
      ft = 0.0_dp
      if (frictional(ein)) then
        if (ein%sliding) then
          ft = -ein%slip_sign * ein%mu * eout%normal_force
        else
          ft = ein%k_tan * (eout%slide - ein%anchor)
        end if
      end if
      eout%tangential_force = ft
      if (frictional(ein)) then
        v = eout%normal_force * ein%normal + ft * t
      else
        v = matmul(c, eout%jump)
      end if
    else
      ! The open state's small penalty (the paper's c -> 0) only resists
      ! relative motion: without the [[U]]_0 term an open element pulls
      ! nothing across an initial gap, so it stabilises a body held only
      ! by contact without biasing it.
      ! (from the relative motion open_shift on: a stabilised penalty's anchor)
      eout%normal_force = ein%penalty * (dot_product(ein%normal, rel) - ein%open_shift)
      v = matmul(c, rel) - (ein%penalty * ein%open_shift) * ein%normal
    end if
    ! B_e^T v
    do a = 1, ein%nen
      eout%fe(2 * a - 1:2 * a) = w(a) * v
    end do
  end subroutine cfe_arrays

  !> Purpose: eq. (7)'s C = R^T c R of the coupling element: c = diag(c_n,
  !> 0), only the normal penalty, with friction (closed) the tangential
  !> factor: sticking + k_t t t^T, sliding - slip_sign mu c_n t n^T.
  !> Arguments: ein the element; t its unit tangent (-n_y, n_x); c returned.
  pure subroutine constitutive(ein, t, c)
    type(cfe_in_t), intent(in) :: ein
    real(dp), intent(in) :: t(2)
    real(dp), intent(out) :: c(2, 2)
    integer :: i, j
    do j = 1, 2
      do i = 1, 2
        c(i, j) = ein%penalty * ein%normal(i) * ein%normal(j)
      end do
    end do
    if (.not. frictional(ein)) return
    do j = 1, 2
      do i = 1, 2
        if (ein%sliding) then
          c(i, j) = c(i, j) - ein%slip_sign * ein%mu * ein%penalty * t(i) * ein%normal(j)
        else
          c(i, j) = c(i, j) + ein%k_tan * t(i) * t(j)
        end if
      end do
    end do
  end subroutine constitutive

  !> Does the closed element carry friction?
  pure logical function frictional(ein)
    type(cfe_in_t), intent(in) :: ein
    frictional = ein%closed .and. ein%mu > 0.0_dp
  end function frictional
end module cfe_element
