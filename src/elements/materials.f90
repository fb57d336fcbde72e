!> Linear elasticity in the three stress states of the 2D continuum
!> elements: isotropic, and anisotropic (orthotropic or general, as
!> *ELASTIC TYPE=ORTHO, ENGINEERING CONSTANTS and ANISO give it) in the
!> material axes of an *ORIENTATION, rectangular or cylindrical (the
!> reader, deck_material_cards, makes the 6x6 stiffness of the constants).
!>
!> The 3D stiffness is kept as a 6x6 matrix in Voigt order (11, 22, 33,
!> 12, 13, 23) with engineering shear strains: its entries are the tensor
!> components Cijkl (sigma_12 = C1212 gamma_12 = 2 C1212 eps_12), so the
!> rotation to the global axes is the tensor rule Cijkl = Qpi Qqj Qrk Qsl
!> C'pqrs (Q(p, :) local axis p in global components). The 2D matrix of
!> a stress state then takes (Lekhnitskii 1981, Anisotropic plates,
!> sections 2-3; Jones 1999, Mechanics of composite materials, 2.5):
!> plane strain and axisymmetry (eps33 given, eps13 = eps23 = 0) the rows
!> and columns of (11, 22, 12, 33); plane stress (s33 = s13 = s23 = 0)
!> the Schur complement of the (33, 13, 23) block, the reduced stiffness.
module materials
  use kinds, only: dp
  use element_catalogue, only: state_plane_stress
  use small_matrices, only: inv3
  implicit none
  private
  public :: elastic_matrix, von_mises
  public :: rotate_stiffness, state_matrix, orientation_axes
  !> orientation_axes' systems (model's orient_rectangular, orient_cylindrical)
  integer, parameter :: sys_rectangular = 1, sys_cylindrical = 2
  !> The element's 4-vector (11, 22, 12, 33) in the Voigt 6-vector.
  integer, parameter :: v4(4) = [1, 2, 4, 3]
  !> Voigt index of the tensor pair (i, j).
  integer, parameter :: voigt(3, 3) = reshape([1, 4, 5, 4, 2, 6, 5, 6, 3], [3, 3])

contains

  !> Purpose: stress-strain matrix for the strain vector (eps11, eps22,
  !> gamma12, eps33) and the stress vector (s11, s22, s12, s33). Plane
  !> stress: eps33 is no independent strain and s33 = 0, so its row and
  !> column are zero. Plane strain (eps33 = 0) and axisymmetry (eps33 the
  !> hoop strain u_r / r): the full isotropic law.
  pure function elastic_matrix(e, nu, state) result(d)
    real(dp), intent(in) :: e, nu
    integer, intent(in) :: state     ! element_catalogue stress state
    real(dp) :: d(4, 4), c
    d = 0.0_dp
    if (state == state_plane_stress) then
      c = e / (1.0_dp - nu**2)
      d(1, 1) = c
      d(2, 2) = c
      d(1, 2) = c * nu
      d(3, 3) = c * (1.0_dp - nu) / 2.0_dp
    else
      c = e / ((1.0_dp + nu) * (1.0_dp - 2.0_dp * nu))
      d(1, 1) = c * (1.0_dp - nu)
      d(2, 2) = d(1, 1)
      d(4, 4) = d(1, 1)
      d(1, 2) = c * nu
      d(1, 4) = c * nu
      d(2, 4) = c * nu
      d(3, 3) = c * (1.0_dp - 2.0_dp * nu) / 2.0_dp
    end if
    d(2, 1) = d(1, 2)
    d(4, 1) = d(1, 4)
    d(4, 2) = d(2, 4)
  end function elastic_matrix

  !> von Mises stress of (s11, s22, s33, s12), scaled by the largest
  !> component so that the squares cannot overflow for any finite stress.
  pure real(dp) function von_mises(s)
    real(dp), intent(in) :: s(4)
    real(dp) :: smax, t(4)
    smax = maxval(abs(s))
    von_mises = 0.0_dp
    if (.not. smax > 0.0_dp .or. smax > huge(1.0_dp)) then
      von_mises = smax          ! zero, or not a number / infinite as given
      return
    end if
    t = s / smax
    von_mises = smax * sqrt(0.5_dp * ((t(1) - t(2))**2 + (t(2) - t(3))**2 + (t(3) - t(1))**2) &
                            + 3.0_dp * t(4)**2)
  end function von_mises

  !> Purpose: the stiffness c (6x6, material axes) in the global axes,
  !> Cijkl = Qpi Qqj Qrk Qsl C'pqrs, q(p, :) the unit local axis p in
  !> global components; one index at a time (4 x 81 x 3 products).
  pure function rotate_stiffness(c, q) result(cg)
    real(dp), intent(in) :: c(6, 6), q(3, 3)
    real(dp) :: cg(6, 6), t(3, 3, 3, 3), u(3, 3, 3, 3)
    integer :: i, j, k, l
    do l = 1, 3
      do k = 1, 3
        do j = 1, 3
          do i = 1, 3
            t(i, j, k, l) = c(voigt(i, j), voigt(k, l))
          end do
        end do
      end do
    end do
    do i = 1, 3
      u(i, :, :, :) = q(1, i) * t(1, :, :, :) + q(2, i) * t(2, :, :, :) + q(3, i) * t(3, :, :, :)
    end do
    do j = 1, 3
      t(:, j, :, :) = q(1, j) * u(:, 1, :, :) + q(2, j) * u(:, 2, :, :) + q(3, j) * u(:, 3, :, :)
    end do
    do k = 1, 3
      u(:, :, k, :) = q(1, k) * t(:, :, 1, :) + q(2, k) * t(:, :, 2, :) + q(3, k) * t(:, :, 3, :)
    end do
    do l = 1, 3
      t(:, :, :, l) = q(1, l) * u(:, :, :, 1) + q(2, l) * u(:, :, :, 2) + q(3, l) * u(:, :, :, 3)
    end do
    do j = 1, 3
      do i = 1, j
        do l = 1, 3
          do k = 1, l
            cg(voigt(i, j), voigt(k, l)) = t(i, j, k, l)
          end do
        end do
      end do
    end do
  end function rotate_stiffness

  !> Purpose: the element's 4x4 matrix (strain (e11, e22, gamma12, e33),
  !> stress (s11, s22, s12, s33)) of the global 6x6 stiffness cg in a
  !> stress state: plane stress the reduced stiffness (Schur complement of
  !> the (33, 13, 23) block: s33 = s13 = s23 = 0), its fourth row and
  !> column zero as elastic_matrix's; otherwise the (11, 22, 12, 33) rows
  !> and columns (eps13 = eps23 = 0).
  pure function state_matrix(cg, state) result(d)
    real(dp), intent(in) :: cg(6, 6)
    integer, intent(in) :: state
    real(dp) :: d(4, 4), cbb(3, 3), cab(3, 3)
    integer, parameter :: ia(3) = [1, 2, 4], ib(3) = [3, 5, 6]
    d = cg(v4, v4)
    if (state == state_plane_stress) then
      cbb = inv3(cg(ib, ib))
      cab = cg(ia, ib)
      d(1:3, 1:3) = cg(ia, ia) - matmul(cab, matmul(cbb, transpose(cab)))
      d(1:3, 1:3) = 0.5_dp * (d(1:3, 1:3) + transpose(d(1:3, 1:3)))
      d(4, :) = 0.0_dp
      d(:, 4) = 0.0_dp
    end if
  end function state_matrix

  !> Purpose: the material axes q (q(p, :) local axis p, unit, in global
  !> components) of an *ORIENTATION at the point x (global, z = 0; in
  !> axisymmetry x = (r, z_axial, 0), the hoop direction global 3).
  !> Rectangular: q1 along a, q3 along a x b, q2 = q3 x q1. Cylindrical: q3
  !> along b - a, q1 the radial direction from the axis to x, q2 = q3 x
  !> q1; on the axis itself (no radial direction) q1 is the global axis
  !> most nearly normal to q3. Then the rotation by angle (degrees) about
  !> local axis `axis` (1-3; 0 none), as the optional second data line of
  !> *ORIENTATION gives it. Arguments: system (sys_*), a, b the points,
  !> axis and angle, x.
  pure function orientation_axes(system, a, b, axis, angle, x) result(q)
    integer, intent(in) :: system, axis
    real(dp), intent(in) :: a(3), b(3), angle, x(3)
    real(dp) :: q(3, 3), r(3), c, s, p1(3), p2(3)
    integer :: i, j, k
    if (system == sys_cylindrical) then
      q(3, :) = unit(b - a)
      r = x - a
      r = r - dot_product(r, q(3, :)) * q(3, :)
      if (norm2(r) <= 1e-12_dp * max(norm2(x - a), norm2(b - a))) then
        r = 0.0_dp
        r(minloc(abs(q(3, :)), 1)) = 1.0_dp
        r = r - dot_product(r, q(3, :)) * q(3, :)
      end if
      q(1, :) = unit(r)
    else
      q(1, :) = unit(a)
      q(3, :) = unit(cross(a, b))
    end if
    q(2, :) = cross(q(3, :), q(1, :))
    if (axis >= 1 .and. axis <= 3 .and. angle /= 0.0_dp) then
      ! the two other axes turn in their plane (right-handed about `axis`)
      i = axis
      j = modulo(i, 3) + 1
      k = modulo(j, 3) + 1
      c = cos(angle * acos(-1.0_dp) / 180.0_dp)
      s = sin(angle * acos(-1.0_dp) / 180.0_dp)
      p1 = c * q(j, :) + s * q(k, :)
      p2 = -s * q(j, :) + c * q(k, :)
      q(j, :) = p1
      q(k, :) = p2
    end if
  end function orientation_axes

  !> Purpose: v / |v| (v itself if zero: the reader rejects such points).
  pure function unit(v) result(u)
    real(dp), intent(in) :: v(3)
    real(dp) :: u(3)
    u = v
    if (norm2(v) > 0.0_dp) u = v / norm2(v)
  end function unit

  !> Purpose: the cross product a x b.
  pure function cross(a, b) result(c)
    real(dp), intent(in) :: a(3), b(3)
    real(dp) :: c(3)
    c = [a(2) * b(3) - a(3) * b(2), a(3) * b(1) - a(1) * b(3), a(1) * b(2) - a(2) * b(1)]
  end function cross
end module materials
