!> Linear springs (*SPRING, constant k): SPRING1 holds one dof of its
!> node against the ground, force k u_a; SPRING2 joins dof a of its first
!> node to dof b of its second, with the stretch d = u1_a - u2_b and the
!> forces k d on the first and -k d on the second (as CalculiX's SPRING2);
!> SPRINGA acts along the line n from its first node to its second, with
!> the stretch d = n . (u2 - u1) and the forces -k d n, k d n. Each is
!> ke = k g g^T with d = g . ue. Small displacements: n is the reference
!> direction. Its "stress" is its force, as Abaqus reports a spring's:
!> S11 = k d and E11 = d at one point (the other components zero).
module spring_element
  use kinds, only: dp
  use element_interface, only: elem_in_t, elem_out_t, kind_spring1, kind_spring2, kind_springa, act_tangent, &
                               act_residual, act_stresses, wants
  implicit none
  private
  public :: spring

contains

  !> Purpose: element arrays of a spring: ke = k g g^T, fe = ke ue for
  !> act_tangent / act_residual; for act_stresses its force and stretch
  !> as S11 and E11 of one point.
  !> Arguments: ein (kind_spring*, xy, ue, stiffness, dofs), eout.
  pure subroutine spring(action, ein, eout)
    integer, intent(in) :: action
    type(elem_in_t), intent(in) :: ein
    type(elem_out_t), intent(out) :: eout
    real(dp) :: g(4), dir(2)
    integer :: nd, i
    g = 0.0_dp
    eout%detj_min = 1.0_dp
    select case (ein%kind)
    case (kind_spring1)
      nd = 2
      g(ein%dofs(1)) = 1.0_dp
    case (kind_spring2)
      nd = 4
      g(ein%dofs(1)) = 1.0_dp
      g(2 + ein%dofs(2)) = -1.0_dp
    case default
      nd = 4
      dir = ein%xy(:, 2) - ein%xy(:, 1)
      eout%detj_min = norm2(dir)
      dir = dir / norm2(dir)
      g = [-dir, dir]
    end select
    eout%ndof = nd
    eout%ke(1:nd, 1:nd) = 0.0_dp
    if (wants(action, act_stresses)) then
      eout%nip = 1
      eout%eps_ip(:, 1) = [dot_product(g(1:nd), ein%ue(1:nd)), 0.0_dp, 0.0_dp]
      eout%sig_ip(:, 1) = [ein%stiffness * eout%eps_ip(1, 1), 0.0_dp, 0.0_dp, 0.0_dp]
    end if
    if (.not. (wants(action, act_tangent) .or. wants(action, act_residual))) return
    do i = 1, nd
      eout%ke(1:nd, i) = ein%stiffness * g(i) * g(1:nd)
    end do
    if (wants(action, act_residual)) eout%fe(1:nd) = matmul(eout%ke(1:nd, 1:nd), ein%ue(1:nd))
    if (.not. wants(action, act_tangent)) eout%ke(1:nd, 1:nd) = 0.0_dp
  end subroutine spring
end module spring_element
