!> Element-level checks of the continuum elements: symmetry, exactly three
!> zero-energy (rigid-body) modes and full rank otherwise, zero force for
!> rigid motions, and exact stresses for a linear displacement field.
program test_elements
  use kinds, only: dp
  use test_report, only: report, failures
  use element_interface, only: elem_in_t, elem_out_t, kind_quad4, kind_tri3, act_tangent, act_residual, act_stresses
  use element_catalogue, only: state_plane_stress, state_plane_strain
  use element_library, only: element_routine
  implicit none
  type(elem_in_t) :: ein

  ! A distorted quadrilateral and a general triangle.
  ein%e = 210000.0_dp
  ein%nu = 0.3_dp
  ein%thickness = 2.5_dp

  ein%kind = kind_quad4
  ein%nen = 4
  ein%xy(:, 1:4) = reshape([0.0_dp, 0.0_dp, 2.2_dp, 0.3_dp, 1.9_dp, 1.7_dp, -0.2_dp, 1.1_dp], [2, 4])
  ein%state = state_plane_stress
  call check_element('Q4 plane stress')
  ein%state = state_plane_strain
  call check_element('Q4 plane strain')

  ein%kind = kind_tri3
  ein%nen = 3
  ein%xy(:, 1:3) = reshape([0.1_dp, -0.2_dp, 1.7_dp, 0.4_dp, 0.6_dp, 1.3_dp], [2, 3])
  ein%state = state_plane_stress
  call check_element('T3 plane stress')
  ein%state = state_plane_strain
  call check_element('T3 plane strain')

  if (failures() > 0) stop 1

contains


  subroutine check_element(name)
    character(len=*), intent(in) :: name
    type(elem_out_t) :: eout
    type(elem_in_t) :: e2
    real(dp), allocatable :: k(:, :), w(:), work(:)
    real(dp) :: r(8, 3), s11, s22, s12, d(3, 3), c, asym, big, sig_exact(4)
    character(len=200) :: msg
    integer :: n, info, nzero, i, j
    call element_routine(ior(ior(act_tangent, act_residual), act_stresses), ein, eout)
    n = eout%ndof
    k = eout%ke(1:n, 1:n)
    big = maxval(abs(k))
    asym = maxval(abs(k - transpose(k))) / big
    write(msg, '(a,es9.2)') 'relative asymmetry ', asym
    call report(name // ' stiffness symmetric', asym < 1.0e-14_dp, msg)

    ! Eigenvalues (LAPACK dsyev): exactly 3 below 1e-10 of the largest.
    allocate(w(n), work(10 * n))
    call dsyev('N', 'U', n, k, n, w, work, size(work), info)
    nzero = count(abs(w) < 1.0e-10_dp * maxval(abs(w)))
    write(msg, '(a,i0,a,i0,a,es9.2)') 'zero eigenvalues ', nzero, ', info ', info, ', smallest ', minval(w)
    call report(name // ' three rigid-body modes', info == 0 .and. nzero == 3 .and. minval(w) > -1.0e-10_dp * maxval(w), msg)
    write(msg, '(a,i0,a,i0)') 'rank ', n - nzero, ' expected ', n - 3
    call report(name // ' rank 2n-3', n - nzero == n - 3, msg)

    ! Rigid motions (two translations and a small rotation) give no force.
    do i = 1, ein%nen
      r(2 * i - 1:2 * i, 1) = [1.0_dp, 0.0_dp]
      r(2 * i - 1:2 * i, 2) = [0.0_dp, 1.0_dp]
      r(2 * i - 1:2 * i, 3) = [-ein%xy(2, i), ein%xy(1, i)]
    end do
    c = 0.0_dp
    do j = 1, 3
      c = max(c, maxval(abs(matmul(eout%ke(1:n, 1:n), r(1:n, j)))) / (big * maxval(abs(r(1:n, j)))))
    end do
    write(msg, '(a,es9.2)') 'relative force ', c
    call report(name // ' rigid motion strain-free', c < 1.0e-13_dp, msg)

    ! Linear field u = (a x + b y, c x + d y): exact constant stress at every
    ! integration point and node.
    e2 = ein
    do i = 1, ein%nen
      e2%ue(2 * i - 1) = 1.0e-3_dp * ein%xy(1, i) + 2.0e-4_dp * ein%xy(2, i)
      e2%ue(2 * i) = -5.0e-4_dp * ein%xy(1, i) - 3.0e-4_dp * ein%xy(2, i)
    end do
    call element_routine(ior(ior(act_tangent, act_residual), act_stresses), e2, eout)
    if (ein%state == state_plane_strain) then
      c = ein%e / ((1 + ein%nu) * (1 - 2 * ein%nu))
      d = reshape([1 - ein%nu, ein%nu, 0.0_dp, ein%nu, 1 - ein%nu, 0.0_dp, 0.0_dp, 0.0_dp, &
                   (1 - 2 * ein%nu) / 2], [3, 3]) * c
    else
      c = ein%e / (1 - ein%nu**2)
      d = reshape([1.0_dp, ein%nu, 0.0_dp, ein%nu, 1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, (1 - ein%nu) / 2], [3, 3]) * c
    end if
    s11 = d(1, 1) * 1.0e-3_dp + d(1, 2) * (-3.0e-4_dp)
    s22 = d(2, 1) * 1.0e-3_dp + d(2, 2) * (-3.0e-4_dp)
    s12 = d(3, 3) * (2.0e-4_dp - 5.0e-4_dp)
    sig_exact = [s11, s22, 0.0_dp, s12]
    if (ein%state == state_plane_strain) sig_exact(3) = ein%nu * (s11 + s22)
    c = 0.0_dp
    do i = 1, eout%nip
      c = max(c, maxval(abs(eout%sig_ip(:, i) - sig_exact)))
    end do
    do i = 1, ein%nen
      c = max(c, maxval(abs(eout%sig_node(:, i) - sig_exact)))
    end do
    c = c / maxval(abs(sig_exact))
    write(msg, '(a,es9.2)') 'relative stress error ', c
    call report(name // ' constant stress exact', c < 1.0e-12_dp, msg)
  end subroutine check_element
end program test_elements
