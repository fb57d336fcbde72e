!> The load state of a step: which dofs are prescribed, the values they
!> and the concentrated loads start from and go to, their amplitudes, and
!> the node sets whose reactions are summed; evaluated at any step time.
module load_state
  use kinds, only: dp
  use model
  implicit none
  private
  public :: load_state_t, begin_step, values_at, amplitude_value

  type :: load_state_t
    logical, allocatable :: presc(:, :)                  ! (2, nn)
    real(dp), allocatable :: bc_start(:, :), bc_target(:, :)
    integer, allocatable :: bc_amp(:, :), bc_set(:, :)
    real(dp), allocatable :: ld_start(:, :), ld_target(:, :)
    integer, allocatable :: ld_amp(:, :)
    integer, allocatable :: set_ids(:)                   ! node sets with prescribed dofs
    real(dp) :: period = 1.0_dp
    real(dp) :: total_time = 0.0_dp                      ! total time at the step's start
  end type load_state_t

contains

  !> Purpose: piecewise-linear tabular amplitude, constant beyond its ends.
  pure real(dp) function amplitude_value(a, t)
    type(amplitude_t), intent(in) :: a
    real(dp), intent(in) :: t
    integer :: k, n
    n = size(a%t)
    if (t <= a%t(1)) then
      amplitude_value = a%a(1)
    else if (t >= a%t(n)) then
      amplitude_value = a%a(n)
    else
      do k = 2, n
        if (t <= a%t(k)) exit
      end do
      amplitude_value = a%a(k - 1) + (a%a(k) - a%a(k - 1)) * (t - a%t(k - 1)) / (a%t(k) - a%t(k - 1))
    end if
  end function amplitude_value

  !> Purpose: the load state of step `is`, which starts from displacements
  !> u and loads fext (the end of the previous step) at total time
  !> total_time. Dofs held in earlier steps stay where they are unless the
  !> step says OP=NEW; model-level conditions apply from the start.
  subroutine begin_step(m, is, u, fext, total_time, ls)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is
    real(dp), intent(in) :: u(:, :), fext(:, :), total_time
    type(load_state_t), intent(inout) :: ls
    integer :: j
    if (.not. allocated(ls%presc)) then
      allocate(ls%presc(2, m%nn), ls%bc_start(2, m%nn), ls%bc_target(2, m%nn), ls%bc_amp(2, m%nn), &
               ls%bc_set(2, m%nn), ls%ld_start(2, m%nn), ls%ld_target(2, m%nn), ls%ld_amp(2, m%nn))
      ls%presc = .false.
      ls%bc_target = 0.0_dp
      ls%bc_set = 0
      ls%ld_target = 0.0_dp
    end if
    associate(st => m%steps(is))
      ls%period = st%period
      ls%total_time = total_time
      ls%bc_start = u
      where (ls%presc) ls%bc_target = u
      ls%bc_amp = 0
      if (st%new_bcs) then
        ls%presc = .false.
        ls%bc_set = 0
      end if
      do j = 1, size(m%model_bcs)
        call prescribe(ls, m%model_bcs(j), .true.)
      end do
      do j = 1, size(st%bcs)
        call prescribe(ls, st%bcs(j), .false.)
      end do
      ls%ld_start = fext
      ls%ld_amp = 0
      if (st%new_loads) then
        ls%ld_start = 0.0_dp
        ls%ld_target = 0.0_dp
      else
        ls%ld_target = fext
      end if
      do j = 1, size(st%loads)
        ls%ld_target(st%loads(j)%dof, st%loads(j)%node) = st%loads(j)%value
        ls%ld_amp(st%loads(j)%dof, st%loads(j)%node) = st%loads(j)%amp
      end do
    end associate
    call prescribed_sets(m, ls)
  end subroutine begin_step

  subroutine prescribe(ls, bc, immediate)
    type(load_state_t), intent(inout) :: ls
    type(bc_t), intent(in) :: bc
    logical, intent(in) :: immediate
    ls%presc(bc%dof, bc%node) = .true.
    ls%bc_target(bc%dof, bc%node) = bc%value
    ls%bc_amp(bc%dof, bc%node) = bc%amp
    if (bc%set > 0) ls%bc_set(bc%dof, bc%node) = bc%set
    if (immediate) ls%bc_start(bc%dof, bc%node) = bc%value
  end subroutine prescribe

  !> Node sets named by active boundary conditions, for reaction sums.
  subroutine prescribed_sets(m, ls)
    type(model_t), intent(in) :: m
    type(load_state_t), intent(inout) :: ls
    integer :: a, d, s
    logical, allocatable :: used(:)
    allocate(used(size(m%nsets)))
    used = .false.
    do a = 1, m%nn
      do d = 1, 2
        s = ls%bc_set(d, a)
        if (ls%presc(d, a) .and. s > 0) used(s) = .true.
      end do
    end do
    ls%set_ids = pack([(s, s = 1, size(m%nsets))], used)
  end subroutine prescribed_sets

  !> Purpose: prescribed displacements into u (free dofs set to zero, the
  !> start of the equilibrium iteration) and loads into fext at step time t.
  subroutine values_at(m, ls, t, u, fext)
    type(model_t), intent(in) :: m
    type(load_state_t), intent(in) :: ls
    real(dp), intent(in) :: t
    real(dp), intent(out) :: u(:, :), fext(:, :)
    integer :: a, d
    real(dp) :: ramp
    ramp = t / ls%period
    do a = 1, m%nn
      do d = 1, 2
        u(d, a) = 0.0_dp
        if (ls%presc(d, a)) then
          if (ls%bc_amp(d, a) > 0) then
            u(d, a) = ls%bc_target(d, a) * amp_at(m, ls, ls%bc_amp(d, a), t)
          else
            u(d, a) = ls%bc_start(d, a) + (ls%bc_target(d, a) - ls%bc_start(d, a)) * ramp
          end if
        end if
        if (ls%ld_amp(d, a) > 0) then
          fext(d, a) = ls%ld_target(d, a) * amp_at(m, ls, ls%ld_amp(d, a), t)
        else
          fext(d, a) = ls%ld_start(d, a) + (ls%ld_target(d, a) - ls%ld_start(d, a)) * ramp
        end if
      end do
    end do
  end subroutine values_at

  real(dp) function amp_at(m, ls, ia, t)
    type(model_t), intent(in) :: m
    type(load_state_t), intent(in) :: ls
    integer, intent(in) :: ia
    real(dp), intent(in) :: t
    if (m%amplitudes(ia)%time == amp_total_time) then
      amp_at = amplitude_value(m%amplitudes(ia), ls%total_time + t)
    else
      amp_at = amplitude_value(m%amplitudes(ia), t)
    end if
  end function amp_at
end module load_state
