!> Contact interaction cards as CalculiX and Abaqus write them:
!> *SURFACE INTERACTION opens a block, *SURFACE BEHAVIOR and *FRICTION
!> describe it, and a *CONTACT PAIR, INTERACTION= takes its penalty and
!> friction, or a soft pressure-overclosure law (see docs/contact.md,
!> "Decks written for CalculiX or Abaqus" and "Soft contact laws"). What
!> cfe2d cannot do (tied contact, friction models other than Coulomb's)
!> stops at the card that asks for it. *WEAR (cfe2d's own card) adds
!> Archard wear to the interaction (docs/contact.md, "Wear").
submodule (deck_parser) deck_interaction_cards
  use kinds, only: dp
  use strings, only: split_fields, to_upper, field_t
  use deck_input, only: param_value, has_param, deck_warning
  use deck_cursor, only: line_text, err, next_data, require_data, allow_params, name_param, get_real, &
                         new_interaction, behaviour_linear, behaviour_hard, behaviour_soft, interaction_t
  implicit none

contains

  !> Purpose: *SURFACE INTERACTION, NAME=: opens a block that the cards
  !> after it (*SURFACE BEHAVIOR, *FRICTION) describe, up to the first
  !> card of another kind.
  module subroutine read_surface_interaction(p, kw)
    type(parser_t), intent(inout) :: p
    type(keyword_t), intent(in) :: kw
    character(len=:), allocatable :: name
    type(field_t), allocatable :: f(:)
    integer :: k, n
    call allow_params(p, kw, 'NAME')
    name = name_param(p, kw, 'NAME')
    do k = 1, p%ninter
      if (p%inter(k)%name == name) call err(p, 'duplicate surface interaction ' // name)
    end do
    k = new_interaction(p)
    p%inter(k)%name = name
    p%inter(k)%line = p%i
    ! Abaqus' optional data line is the out-of-plane thickness of a 2D
    ! contact (Abaqus/CAE writes 1. for every 2D model); cfe2d's contact
    ! areas take the section thickness, which it must equal (checked with
    ! the pairs, interaction_penalties).
    if (next_data(p)) then
      call split_fields(line_text(p), f, n)
      if (n /= 1) call err(p, '*SURFACE INTERACTION data line needs: out-of-plane thickness')
      p%inter(k)%thickness = get_real(p, f(1), 'out-of-plane thickness')
      if (p%inter(k)%thickness <= 0.0_dp) call err(p, 'the out-of-plane thickness must be positive')
    end if
  end subroutine read_surface_interaction

  !> Purpose: *SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=: the normal law of
  !> the current interaction. LINEAR takes `K[, sigma_inf[, c0]]`: K is
  !> cfe2d's penalty per unit area; sigma_inf and c0 (CalculiX's tension
  !> at large clearance and the clearance within which it makes contact
  !> springs) are checked as numbers and not used. HARD (Abaqus' default)
  !> is the automatic penalty; with a data line it is LINEAR, as in
  !> CalculiX. EXPONENTIAL and TABULAR are soft laws (read_exponential,
  !> read_tabular); TIED is an error.
  module subroutine read_surface_behavior(p, kw)
    type(parser_t), intent(inout) :: p
    type(keyword_t), intent(in) :: kw
    character(len=:), allocatable :: law
    call allow_params(p, kw, 'PRESSURE-OVERCLOSURE')
    if (p%interaction == 0) call err(p, '*SURFACE BEHAVIOR outside a *SURFACE INTERACTION block')
    law = 'HARD'
    if (has_param(kw, 'PRESSURE-OVERCLOSURE')) law = to_upper(param_value(kw, 'PRESSURE-OVERCLOSURE'))
    associate(it => p%inter(p%interaction))
      select case (law)
      case ('LINEAR', 'HARD')
        it%behaviour = behaviour_hard
        if (law == 'LINEAR') it%behaviour = behaviour_linear
        it%slope = -1.0_dp
        if (next_data(p)) then
          it%behaviour = behaviour_linear
          it%slope = linear_slope(p)
        else if (law == 'LINEAR') then
          call deck_warning(p%deck, p%i, 'PRESSURE-OVERCLOSURE=LINEAR without a data line (K, sigma_inf): ' // &
              'the automatic penalty (as HARD) is used')
        end if
      case ('EXPONENTIAL')
        call read_exponential(p, it)
      case ('TABULAR')
        call read_tabular(p, it)
      case ('TIED')
        call err(p, 'PRESSURE-OVERCLOSURE=TIED (contact that never separates) is not implemented; ' // &
                 'LINEAR and HARD are')
      case default
        call err(p, 'PRESSURE-OVERCLOSURE=' // law // ' is not known (LINEAR, HARD, EXPONENTIAL, TABULAR)')
      end select
    end associate
  end subroutine read_surface_behavior

  !> K of a LINEAR data line (the current line), the automatic penalty
  !> (-1) with a warning when it is empty or not positive, as CalculiX
  !> falls back on its default there.
  real(dp) function linear_slope(p) result(k)
    type(parser_t), intent(inout) :: p
    type(field_t), allocatable :: f(:)
    real(dp) :: x
    integer :: n, j
    call split_fields(line_text(p), f, n)
    if (n > 3) call err(p, 'PRESSURE-OVERCLOSURE=LINEAR data line needs: K[, sigma_inf[, c0]]')
    k = -1.0_dp
    if (len(f(1)%s) > 0) k = get_real(p, f(1), 'slope K of the pressure-overclosure curve')
    do j = 2, n
      if (len(f(j)%s) > 0) x = get_real(p, f(j), 'sigma_inf or c0')
    end do
    if (k <= 0.0_dp) then
      call deck_warning(p%deck, p%i, 'no positive slope K: the automatic penalty (as HARD) is used')
      k = -1.0_dp
    end if
  end function linear_slope

  !> Purpose: PRESSURE-OVERCLOSURE=EXPONENTIAL, data `c0, p0`: the soft
  !> law of the overclosure h (the negative clearance), beta = ln(100) / c0,
  !>   p(h) = p0 exp(beta h) - (p0 / 100) max(0, -h / c0),   h >= -c0,
  !> 0 for h < -c0: CalculiX's p0 exp(beta h) (measured with CalculiX
  !> 2.20, docs/contact.md, "Soft contact laws"), less a ramp that takes
  !> its 1 % of p0 at the clearance c0 (where CalculiX drops to 0) to zero:
  !> p0 at zero clearance, 0 at the clearance c0, continuous, increasing
  !> and convex. Kept as knots (exponential_knots); linear beyond the last.
  !> Arguments: p the parser (on the card); it the interaction.
  subroutine read_exponential(p, it)
    type(parser_t), intent(inout) :: p
    type(interaction_t), intent(inout) :: it
    type(field_t), allocatable :: f(:)
    real(dp) :: c0, p0
    integer :: n
    call require_data(p, 'c0, p0 of the exponential pressure-overclosure law')
    call split_fields(line_text(p), f, n)
    if (n /= 2) call err(p, 'PRESSURE-OVERCLOSURE=EXPONENTIAL data line needs: c0, p0 (the clearance ' // &
                         'where the pressure vanishes, the pressure at zero clearance)')
    c0 = get_real(p, f(1), 'c0 (clearance at which the pressure vanishes)')
    p0 = get_real(p, f(2), 'p0 (pressure at zero clearance)')
    if (.not. (c0 > 0.0_dp .and. c0 <= huge(1.0_dp))) call err(p, 'c0 must be a positive clearance')
    if (.not. (p0 > 0.0_dp .and. p0 <= 1.0e-3_dp * huge(1.0_dp))) call err(p, 'p0 must be a positive pressure')
    it%behaviour = behaviour_soft
    call exponential_knots(c0, p0, it%soft_h, it%soft_p)
  end subroutine read_exponential

  !> Purpose: knots of the exponential law (read_exponential) whose
  !> piecewise linear interpolant is within 1.3e-5 of it (relative): in
  !> x = beta (h + c0) steps of dx = 0.01 (an interpolant of exp errs by
  !> at most dx^2 / 8 of the value; the ramp is linear), from x = 0 to
  !> where p0 exp(beta h) reaches exp(23) (about where CalculiX 2.20 stops
  !> the exponential: measured, docs/contact.md), at least to 2 c0 of
  !> overclosure.
  !> Arguments: c0, p0 the law; h, p the knots.
  pure subroutine exponential_knots(c0, p0, h, p)
    real(dp), intent(in) :: c0, p0
    real(dp), allocatable, intent(out) :: h(:), p(:)
    real(dp), parameter :: dx = 0.01_dp
    real(dp) :: beta, xmax
    integer :: n, i
    beta = log(100.0_dp) / c0
    xmax = max(3.0_dp * log(100.0_dp), 23.0_dp - log(p0) + log(100.0_dp))
    xmax = min(xmax, 600.0_dp)
    n = ceiling(xmax / dx) + 1
    allocate(h(n), p(n))
    do i = 1, n
      h(i) = (i - 1) * dx / beta - c0
      p(i) = p0 * (exp((i - 1) * dx - log(100.0_dp)) - 0.01_dp * max(0.0_dp, 1.0_dp - (i - 1) * dx / log(100.0_dp)))
    end do
  end subroutine exponential_knots

  !> Purpose: PRESSURE-OVERCLOSURE=TABULAR, data lines `pressure,
  !> overclosure` (a clearance as a negative overclosure): the pressure is
  !> linear between the pairs, 0 before the first (whose pressure must be
  !> 0), the last segment's slope beyond the last. The overclosures must
  !> increase, and the pressures too (a monotone law: docs/contact.md).
  !> Arguments: p the parser (on the card); it the interaction.
  subroutine read_tabular(p, it)
    type(parser_t), intent(inout) :: p
    type(interaction_t), intent(inout) :: it
    type(field_t), allocatable :: f(:)
    real(dp), allocatable :: h(:), pr(:)
    integer :: n, k
    allocate(h(0), pr(0))
    k = 0
    do while (next_data(p))
      call split_fields(line_text(p), f, n)
      if (n /= 2) call err(p, 'PRESSURE-OVERCLOSURE=TABULAR data line needs: pressure, overclosure')
      k = k + 1
      pr = [pr, get_real(p, f(1), 'pressure')]
      h = [h, get_real(p, f(2), 'overclosure')]
      if (abs(pr(k)) > 1.0e-3_dp * huge(1.0_dp) .or. abs(h(k)) > 1.0e-3_dp * huge(1.0_dp)) &
        call err(p, 'pressure and overclosure must be finite numbers')
      if (k == 1 .and. pr(1) /= 0.0_dp) call err(p, 'the first pressure of a TABULAR law must be 0 ' // &
          '(its overclosure is where contact begins; a clearance is a negative overclosure)')
      if (k > 1) then
        if (.not. h(k) > h(k - 1)) call err(p, 'the overclosures of a TABULAR law must increase')
        if (.not. pr(k) > pr(k - 1)) call err(p, 'the pressures of a TABULAR law must increase with ' // &
            'the overclosure (a monotone law)')
      end if
    end do
    if (k < 2) call err(p, 'PRESSURE-OVERCLOSURE=TABULAR needs at least two data lines (pressure, overclosure)')
    it%behaviour = behaviour_soft
    it%soft_h = h
    it%soft_p = pr
  end subroutine read_tabular

  !> Purpose: *FRICTION: `mu[, stick slope]` of the current interaction
  !> (Coulomb friction, docs/contact.md): mu the friction coefficient,
  !> the stick slope CalculiX's lambda, the shear stress per unit slip
  !> while sticking (the tangential penalty per unit area; automatic, as
  !> the normal penalty, when not given). Abaqus' ROUGH, EXPONENTIAL
  !> DECAY, SLIP TOLERANCE= and the other friction models stop here.
  module subroutine read_friction(p, kw)
    type(parser_t), intent(inout) :: p
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    real(dp) :: mu, slope
    integer :: n
    if (has_param(kw, 'ROUGH')) call err(p, '*FRICTION, ROUGH (no slip at all) is not implemented; ' // &
        'give a friction coefficient (Coulomb friction)')
    if (has_param(kw, 'EXPONENTIAL DECAY')) call err(p, '*FRICTION, EXPONENTIAL DECAY (a coefficient ' // &
        'that falls with the slip rate) is not implemented; give one friction coefficient')
    if (has_param(kw, 'SLIP TOLERANCE')) call err(p, '*FRICTION, SLIP TOLERANCE= (Abaqus'' elastic slip ' // &
        'as a fraction of the element length) is not implemented; give the stick slope as the second ' // &
        'value of the data line, or leave it out for the automatic one')
    call allow_params(p, kw, '')
    if (p%interaction == 0) call err(p, '*FRICTION outside a *SURFACE INTERACTION block')
    call require_data(p, 'friction coefficient[, stick slope]')
    call split_fields(line_text(p), f, n)
    if (n > 2) call err(p, '*FRICTION data line needs: friction coefficient[, stick slope]')
    mu = get_real(p, f(1), 'friction coefficient')
    if (mu < 0.0_dp) call err(p, 'the friction coefficient must not be negative')
    slope = -1.0_dp
    if (n == 2) then
      if (len(f(2)%s) > 0) then
        slope = get_real(p, f(2), 'stick slope')
        if (slope <= 0.0_dp) call err(p, 'the stick slope (shear stress per unit slip) must be positive')
      end if
    end if
    p%inter(p%interaction)%mu = mu
    p%inter(p%interaction)%stick_slope = slope
  end subroutine read_friction

  !> Purpose: *WEAR (cfe2d's card, in a *SURFACE INTERACTION block):
  !> `k_slave, k_master[, N]`, Archard's wear coefficients of the pair's
  !> slave and master surfaces (worn depth per unit contact pressure and
  !> unit slip: the dimensional coefficient k = K / H, e.g. mm^2/N) and the
  !> cycle-jump factor N (default 1: each computed increment's wear counts
  !> N times). The pairs that take the interaction check that it has
  !> friction (interaction_penalties).
  module subroutine read_wear(p, kw)
    type(parser_t), intent(inout) :: p
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    real(dp) :: k(2), jump
    integer :: n, j, card
    card = p%i
    call allow_params(p, kw, '')
    if (p%interaction == 0) call err(p, '*WEAR outside a *SURFACE INTERACTION block')
    if (p%inter(p%interaction)%wear_line > 0) call err(p, 'a second *WEAR in surface interaction ' // &
                                                     trim(p%inter(p%interaction)%name))
    call require_data(p, 'k_slave, k_master[, cycle-jump factor N]')
    call split_fields(line_text(p), f, n)
    if (n < 2 .or. n > 3) call err(p, '*WEAR data line needs: k_slave, k_master[, cycle-jump factor N]')
    k(1) = get_real(p, f(1), 'wear coefficient of the slave surface')
    k(2) = get_real(p, f(2), 'wear coefficient of the master surface')
    do j = 1, 2
      if (k(j) < 0.0_dp) call err(p, 'a wear coefficient must not be negative')
    end do
    jump = 1.0_dp
    if (n == 3) then
      if (len(f(3)%s) > 0) jump = get_real(p, f(3), 'cycle-jump factor N')
      if (.not. jump > 0.0_dp) call err(p, 'the cycle-jump factor N must be positive')
    end if
    if (next_data(p)) call err(p, '*WEAR takes one data line: k_slave, k_master[, cycle-jump factor N]')
    p%inter(p%interaction)%wear_k = k
    p%inter(p%interaction)%wear_jump = jump
    p%inter(p%interaction)%wear_line = card
  end subroutine read_wear
end submodule deck_interaction_cards
