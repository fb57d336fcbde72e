!> Isotropic linear elasticity in the three stress states of the 2D
!> continuum elements.
module materials
  use kinds, only: dp
  use element_catalogue, only: state_plane_stress
  implicit none
  private
  public :: elastic_matrix, von_mises

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
end module materials
