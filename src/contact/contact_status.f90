!> The contact status of an increment, decided by a method that
!> terminates.
!>
!> For a fixed open/closed status the equilibrium of an increment is
!> linear (small strain, linear bodies, penalty CFEs). Which status is
!> the right one is a linear complementarity problem (LCP). Condensed on
!> the contact equations (docs/contact.md), with S0 the stiffness of the
!> bodies and every CFE open, b_c = B_e^T n of CFE c (eq. 4) and
!> d_c = k_closed - k_open, the closed CFEs' forces beyond their open
!> force, lambda_c = -d_c gh_c, satisfy
!>   lambda >= 0,  w = q + M lambda >= 0,  lambda_c w_c = 0,
!>   M = B^T S0^-1 B + diag(1/d_c),
!> where w_c = gh_c for an open CFE and gh_c is the CFE's shifted gap
!>   gh = g + k_open g0 / d          (g0 = n . [[U]]_0, eq. 8),
!> the gap at which the closed force (eq. 9, k_closed g) equals the open
!> one (k_open (g - g0): relative motion only): the status switches where
!> the force is continuous, which makes the problem an LCP. M is
!> symmetric positive definite (S0 is, and d_c > 0), so the LCP has one
!> solution (a P-matrix), whatever holds the bodies.
!>
!> An equilibrium iteration that solves the status's linear system and
!> then changes the status of every CFE whose complementarity is violated
!> (closed in tension: gh > 0; open and penetrating: gh < 0) is block
!> principal pivoting on that LCP (Kostreva 1978), the penalty switching
!> of the paper's section 5. It is fast but may cycle. Judice & Pires
!> (1994, "A block principal pivoting algorithm for large-scale strictly
!> monotone linear complementarity problems", Computers & Operations
!> Research 21, 587-596) make it terminate: block pivots while a merit of
!> the status keeps reaching a new best; after max_block_tries block
!> pivots without one, single pivots by Murty's least-index rule (Murty
!> 1974: change only the violated CFE of least index), which terminates
!> for any P-matrix, until the merit reaches a new best again. Any merit
!> that is a function of the status alone serves the argument (a new
!> best cannot repeat a status, and there are finitely many): Judice and
!> Pires count the violated CFEs; here it is the total potential energy
!> Pi of the status's solution (bodies, loads and CFEs; eqs. 1 and 9),
!> whose minimum over all displacements is the LCP's solution. The count
!> misleads where a contact zone shrinks from too many closed points (it
!> stays at one or two while the zone peels, and the least-index rule
!> then peels one point per iteration); the energy falls steadily there.
!> So the status search ends after finitely many iterations with the
!> LCP's solution, for any number of CFEs and however the bodies are held
!> (supports, contact alone, clearance).
!>
!> Round-off: a CFE whose shifted gap is zero to the round-off of the
!> problem is settled in either state: it is not counted as violated when
!> |gh| <= round_off * min(h, F / d), h the mesh length at the point and
!> F the force scale of the increment (loads, contact forces, forces
!> carried so far), or when |gh| is below the round-off of the gap itself
!> (64 epsilons of the coordinates: contact's gap_round; without any load
!> F is round-off too). Its force either way is then below round_off * F,
!> and its gap below round_off * h: either status gives the same answer to
!> the round-off of the problem, and a decision there no longer depends on
!> the BLAS kernel. The tolerance changes no answer beyond that.
!>
!> Soft laws (*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=EXPONENTIAL or
!> TABULAR; docs/contact.md, "Soft contact laws"): the law is piecewise
!> linear and a CFE's status is the segment its overclosure lies in
!> (contact's set_segment); a violated CFE pivots to the segment of its
!> overclosure (a block pivot raising the pressure at most max_rise
!> times), and its share of the merit is the law's own energy. A convex
!> law is a sum of hinges, each a complementarity pair of the LCP above,
!> on which a block pivot is block principal pivoting; the single pivot
!> moves one element whole, which Murty's proof does not cover (MAXIT and
!> bisection bound it, as with friction).
module contact_status
  use kinds, only: dp
  use model, only: model_t
  use contact, only: contact_set_t, cfe_t, cfe_label, open_penalty, open_shift, frictional_set, closed_offset, &
                     closed_stiffness, set_segment, soft_segment_at, soft_energy
  implicit none
  private
  public :: status_search_t, begin_status_search, contact_switch, reject_pivot, shifted_gap, contact_energy, &
            augment_multipliers, max_augmentations, touched_within, max_touched

  !> Relative round-off under which gap and force count as zero.
  real(dp), parameter :: round_off = 1.0e-10_dp
  !> Block pivots allowed without a new lowest potential energy before
  !> single pivots take over (Judice & Pires' p).
  integer, parameter :: max_block_tries = 3
  !> Status changes named in a message.
  integer, parameter :: max_named = 20
  !> Multiplier updates of exact enforcement per increment, at most (each
  !> shrinks the closed gaps by about the ratio of the bodies' stiffness
  !> under a point to the penalty: 1e-3 with the automatic one).
  integer, parameter :: max_augmentations = 30
  !> A soft law's block pivot raises the pressure at most this many times
  !> (pivot_soft).
  real(dp), parameter :: max_rise = 10.0_dp
  !> Frictional CFEs of one pair that may close from an open gap within
  !> one increment (touched_within): about one slave spacing at each end
  !> of a growing contact zone.
  integer, parameter :: max_touched = 2

  !> The state of one increment's status search, and the pivots made
  !> since it was made: block (every violated CFE changes) and single (the
  !> least-index rule).
  type :: status_search_t
    real(dp) :: best = huge(1.0_dp)     ! lowest potential energy so far
    integer :: tries = max_block_tries  ! block pivots left without a new best
    integer :: block_pivots = 0, single_pivots = 0
    integer :: iterations = 0           ! of the current search
    !> The last pivot: the status before it, the CFEs violated there, and
    !> the CFE a single pivot changed (0 for a block pivot), so that a
    !> pivot to a status that cannot be factored can be taken back.
    logical :: pivoted = .false.
    logical, allocatable :: before(:), before_sliding(:), violated(:)
    integer, allocatable :: before_seg(:)
    real(dp), allocatable :: before_sign(:)
    integer :: single = 0
  end type status_search_t

contains

  !> Purpose: a new status search (a new increment, or a new LCP: the
  !> open penalty changed); the pivot counts go on.
  pure subroutine begin_status_search(ss)
    type(status_search_t), intent(inout) :: ss
    ss%best = huge(1.0_dp)
    ss%tries = max_block_tries
    ss%pivoted = .false.
    ss%iterations = 0
  end subroutine begin_status_search

  !> Purpose: the shifted gap gh of CFE j at its last evaluation (see the
  !> module's comment): where the closed and the open force are equal.
  pure real(dp) function shifted_gap(cs, j) result(gh)
    type(contact_set_t), intent(in) :: cs
    integer, intent(in) :: j
    real(dp) :: ko, d
    associate(c => cs%c(j))
      ko = open_penalty(c, cs%stabilised)
      d = c%k_closed - ko
      gh = c%gap
      ! (lambda: exact enforcement's multiplier, see augment_multipliers)
      if (d > 0.0_dp) gh = c%gap + (ko * (dot_product(c%normal, c%gap0) + open_shift(c, cs%stabilised)) + &
                                    c%lambda) / d
    end associate
  end function shifted_gap

  !> Purpose: one pivot of the status search after the equilibrium of the
  !> current status has been solved and every CFE evaluated (its gap):
  !> block or single principal pivot (module comment).
  !> Arguments: force_scale the force scale F of the increment (> 0);
  !> energy the potential energy of the current status's solution (up to
  !> a constant of the increment: see contact_energy); nchanged the
  !> status changes (0: the status solves the LCP); changed the names of
  !> the first CFEs that changed, for messages.
  subroutine contact_switch(m, cs, ss, force_scale, energy, nchanged, changed)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(inout) :: cs
    type(status_search_t), intent(inout) :: ss
    real(dp), intent(in) :: force_scale, energy
    integer, intent(out) :: nchanged
    character(len=:), allocatable, intent(out) :: changed
    logical :: violated(cs%n), frictional
    integer :: j, nviol
    ss%iterations = ss%iterations + 1
    frictional = frictional_set(cs)
    do j = 1, cs%n
      violated(j) = is_violated(m, cs, j, force_scale)
    end do
    nviol = count(violated)
    nchanged = 0
    changed = ''
    ! the status before this pivot, to take it back (reject_pivot)
    ss%before = cs%c(1:cs%n)%closed
    ss%before_sliding = cs%c(1:cs%n)%sliding
    ss%before_sign = cs%c(1:cs%n)%slip_sign
    ss%before_seg = cs%c(1:cs%n)%seg
    ss%violated = violated
    ss%single = 0
    if (nviol > 0) then
      if (energy < ss%best .or. frictional) then
        ! (Coulomb friction has no potential: block pivots only)
        ss%best = energy
        ss%tries = max_block_tries
      else
        ss%tries = ss%tries - 1
      end if
      if (ss%tries >= 0) then
        ss%block_pivots = ss%block_pivots + 1
      else
        ! Murty's least-index rule: only the first violated CFE changes
        ss%single_pivots = ss%single_pivots + 1
        ss%single = findloc(violated, .true., dim=1)
        violated(ss%single + 1:) = .false.
        ss%tries = -1
      end if
      do j = 1, cs%n
        if (.not. violated(j)) cycle
        call note_change(m, cs, j, nchanged, changed)
        if (cs%c(j)%soft) then
          ! a soft law: to the segment of its overclosure
          call pivot_soft(m, cs%c(j), ss%single == 0, force_scale)
        else
          cs%c(j)%closed = .not. cs%c(j)%closed
        end if
      end do
    end if
    if (frictional) then
      call return_mapping(m, cs, force_scale, nchanged, changed)
      if (nviol == 0 .and. nchanged > 0) ss%block_pivots = ss%block_pivots + 1
    end if
    ss%pivoted = nchanged > 0
    if (nchanged > max_named) changed = changed // ' ...'
  end subroutine contact_switch

  !> One more changed CFE, named in changed while there are few.
  subroutine note_change(m, cs, j, nchanged, changed)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    integer, intent(in) :: j
    integer, intent(inout) :: nchanged
    character(len=:), allocatable, intent(inout) :: changed
    nchanged = nchanged + 1
    if (nchanged <= max_named) changed = changed // ' ' // cfe_label(m, cs%c(j))
  end subroutine note_change

  !> Coulomb's law on every closed frictional CFE (after the normal
  !> pivot): the return mapping of the increment. The trial tangential
  !> force k_t (t.[[U]] - anchor), from the anchor committed at the end of
  !> the last increment, sticks while it lies within mu times the normal
  !> force N = -k_closed g, and slides along its sign otherwise (the
  !> sliding force is then mu N). A sliding CFE keeps sliding while its
  !> trial force exceeds mu N in its direction, to round-off (N = -(lambda +
  !> k_closed g) under exact enforcement). Open CFEs
  !> neither stick nor slide. Round-off as in is_violated.
  subroutine return_mapping(m, cs, force_scale, nchanged, changed)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(inout) :: cs
    real(dp), intent(in) :: force_scale
    integer, intent(inout) :: nchanged
    character(len=:), allocatable, intent(inout) :: changed
    real(dp) :: trial, limit, tol, sgn
    logical :: slide
    integer :: j
    do j = 1, cs%n
      associate(c => cs%c(j))
        if (c%mu <= 0.0_dp) cycle
        ! forces to the round-off of the problem, and never below the force
        ! of a tangential offset at the gap's own round-off (without loads
        ! the force scale is round-off too)
        tol = max(round_off * force_scale, c%k_tan * c%gap_round)
        slide = .false.
        sgn = 0.0_dp
        if (c%closed) then
          trial = c%k_tan * (c%slide - c%anchor)
          ! (exact enforcement: the normal force is lambda + k_closed g)
          ! (a soft law: its segment's force k_soft g + f_soft)
          limit = c%mu * max(-(closed_stiffness(c) * c%gap + closed_offset(c)), 0.0_dp)
          if (c%sliding) then
            ! slides on while the trial force exceeds the limit its way;
            ! otherwise it sticks first (never reverses in one pivot,
            ! which makes neighbouring points swing together)
            slide = c%slip_sign * trial > limit - tol
            if (slide) sgn = c%slip_sign
          else if (abs(trial) > limit + tol) then
            slide = .true.
            sgn = sign(1.0_dp, trial)
          end if
        end if
        if ((slide .neqv. c%sliding) .or. sgn /= c%slip_sign) call note_change(m, cs, j, nchanged, changed)
        c%sliding = slide
        c%slip_sign = sgn
      end associate
    end do
  end subroutine return_mapping

  !> Purpose: the largest number, over the contact pairs, of frictional
  !> CFEs that closed within the increment from an open gap: open at its
  !> start (start, the CFEs as the increment began) with a gap above the
  !> round-off, closed at its end (cs, converged). Such a point takes its
  !> anchor from the increment's start (contact_commit), so the relative
  !> tangential motion before it touched counts as elastic stick (docs/
  !> contact.md, "Accuracy of stick and slip"): the driver splits an
  !> increment in which more than max_touched close in one pair (the
  !> points then touch within a slave spacing of the increment's start).
  !> A point that touched where the increment began (its gap zero, flat
  !> faces laid on each other) is not counted: its anchor is right.
  !> Arguments: start the CFEs at the increment's start (the same set as
  !> cs, else 0: a new search paired them anew); evaluated false where
  !> no increment has evaluated the CFEs yet (their gap then the initial
  !> one, n . [[U]]_0, eq. 8).
  pure integer function touched_within(start, cs, evaluated) result(most)
    type(cfe_t), intent(in) :: start(:)
    type(contact_set_t), intent(in) :: cs
    logical, intent(in) :: evaluated
    integer, allocatable :: per_pair(:)
    real(dp) :: g
    integer :: j
    most = 0
    if (size(start) /= cs%n .or. cs%n == 0) return
    if (.not. frictional_set(cs)) return
    allocate(per_pair(maxval(cs%c(1:cs%n)%pair)))
    per_pair = 0
    do j = 1, cs%n
      associate(c => cs%c(j), s => start(j))
        if (c%mu <= 0.0_dp .or. .not. c%closed .or. s%closed .or. c%pair /= s%pair) cycle
        g = s%gap
        if (.not. evaluated) g = dot_product(s%normal, s%gap0)
        if (g <= max(round_off * s%h, s%gap_round)) cycle
        per_pair(c%pair) = per_pair(c%pair) + 1
      end associate
    end do
    most = maxval(per_pair)
  end function touched_within

  !> Purpose: takes back the last pivot, whose status cannot be factored
  !> (its stiffness is singular: a body it leaves held by open contact
  !> only, which cannot be the solution where a load acts on that body),
  !> and makes a single pivot instead: the violated CFE of least index
  !> after the one a rejected single pivot changed.
  !> Arguments: found false when no pivot is left to try (the status
  !> stays as it was).
  subroutine reject_pivot(m, cs, ss, found, changed)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(inout) :: cs
    type(status_search_t), intent(inout) :: ss
    logical, intent(out) :: found
    character(len=:), allocatable, intent(out) :: changed
    integer :: j, k
    found = .false.
    changed = ''
    ss%iterations = ss%iterations + 1
    if (.not. ss%pivoted) return
    do j = ss%single + 1, cs%n
      if (ss%violated(j)) exit
    end do
    if (j > cs%n) return
    found = .true.
    cs%c(1:cs%n)%closed = ss%before
    cs%c(1:cs%n)%sliding = ss%before_sliding
    cs%c(1:cs%n)%slip_sign = ss%before_sign
    do k = 1, cs%n
      if (cs%c(k)%soft) call set_segment(m, cs%c(k), ss%before_seg(k))
    end do
    if (cs%c(j)%soft) then
      call pivot_soft(m, cs%c(j), .false., 0.0_dp)
    else
      cs%c(j)%closed = .not. cs%c(j)%closed
    end if
    ss%single = j
    ss%single_pivots = ss%single_pivots + 1
    ss%tries = -1
    changed = ' ' // cfe_label(m, cs%c(j))
  end subroutine reject_pivot

  !> Purpose: the CFEs' share of the potential energy at their last
  !> evaluation: per CFE, the open state's energy 1/2 k_open (n.B_e D_e)^2
  !> (relative motion only) plus 1/2 (k_closed - k_open) min(0, gh)^2.
  !> Its gradient is each CFE's force in the state its shifted gap
  !> gives (eq. 9 closed), so bodies' energy, loads' work and this sum make
  !> the potential whose minimum solves the LCP.
  pure real(dp) function contact_energy(cs) result(e)
    type(contact_set_t), intent(in) :: cs
    integer :: j
    real(dp) :: ko
    e = 0.0_dp
    do j = 1, cs%n
      associate(c => cs%c(j))
        ko = open_penalty(c, cs%stabilised)
        e = e + 0.5_dp * ko * (c%gap - dot_product(c%normal, c%gap0) - open_shift(c, cs%stabilised))**2
        if (c%soft) then
          ! a soft law: its energy at the last evaluation, the integral of
          ! the law's pressure over the overclosure times the area
          e = e + soft_energy(c)
        else
          e = e + 0.5_dp * max(c%k_closed - ko, 0.0_dp) * min(0.0_dp, shifted_gap(cs, j))**2
        end if
      end associate
    end do
  end function contact_energy

  !> Purpose: exact enforcement (pairs with cfe_t%exact) where its
  !> multipliers are not solved directly (the full path, and friction:
  !> the condensed path solves them per status, condensed_contact's
  !> condensed_multipliers), once the status search has settled: the
  !> augmented Lagrangian update (Powell 1969,
  !> Hestenes 1969; for contact Simo & Laursen 1992, "An augmented
  !> Lagrangian treatment of contact problems involving friction",
  !> Computers & Structures 42, 97-116). For a fixed multiplier lambda_c
  !> the status search solves the LCP of the penalty on the gap shifted by
  !> lambda_c / d_c (closed force lambda_c + k_closed g_c); the update
  !> lambda_c := that force (closed) or 0 (open) and a new search make the
  !> closed gaps shrink geometrically, by about the ratio of the bodies'
  !> stiffness under a point to its penalty per iteration, until they are
  !> zero to the round-off of the status search (round_off min(h, F/d), or
  !> the gap's own round-off): the multipliers are then the contact forces
  !> of exact non-penetration, independent of the penalty, which only sets
  !> the pace. Returns true when some multiplier changed (search again).
  !> Arguments: force_scale as contact_switch.
  logical function augment_multipliers(cs, force_scale) result(again)
    type(contact_set_t), intent(inout) :: cs
    real(dp), intent(in) :: force_scale
    integer :: j
    real(dp) :: tol
    again = .false.
    do j = 1, cs%n
      associate(c => cs%c(j))
        if (.not. c%exact .or. .not. c%closed) cycle
        tol = max(round_off * min(c%h, force_scale / max(c%k_closed, tiny(1.0_dp))), c%gap_round)
        if (abs(c%gap) > tol) again = .true.
      end associate
    end do
    if (.not. again) return
    do j = 1, cs%n
      associate(c => cs%c(j))
        if (.not. c%exact) cycle
        if (c%closed) then
          ! the closed force of the search (lambda + k_closed g, the open
          ! penalty's share left out: it resists relative motion only)
          c%lambda = min(c%lambda + c%k_closed * c%gap, 0.0_dp)
        else
          c%lambda = 0.0_dp
        end if
      end associate
    end do
  end function augment_multipliers

  !> Is CFE j's complementarity violated beyond round-off: closed and in
  !> tension, or open and penetrating? (A soft law: is its overclosure
  !> outside its segment, soft_violation.)
  logical function is_violated(m, cs, j, force_scale)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    integer, intent(in) :: j
    real(dp), intent(in) :: force_scale
    real(dp) :: gh, tol
    associate(c => cs%c(j))
      if (c%soft) then
        is_violated = soft_violation(m, c, force_scale) /= 0
        return
      end if
      gh = shifted_gap(cs, j)
      tol = round_off * min(c%h, force_scale / max(c%k_closed - open_penalty(c, cs%stabilised), tiny(1.0_dp)))
      ! never below the gap's own round-off (without loads F is round-off too)
      tol = max(tol, c%gap_round)
      if (c%closed) then
        is_violated = gh > tol
      else
        is_violated = gh < -tol
      end if
    end associate
  end function is_violated

  !> Purpose: where soft CFE c's overclosure h = -g lies relative to its
  !> segment (docs/contact.md, "Soft contact laws"): -1 before it, +1
  !> beyond it, 0 within it, to the round-off of the problem as for the
  !> penalty law (round_off min(h_mesh, F / k), never below the gap's own
  !> round-off), k the segment's stiffness (the closed penalty while open).
  integer function soft_violation(m, c, force_scale) result(v)
    type(model_t), intent(in) :: m
    type(cfe_t), intent(in) :: c
    real(dp), intent(in) :: force_scale
    real(dp) :: h, tol, k
    k = c%k_closed
    if (c%closed) k = c%k_soft
    tol = max(round_off * min(c%h, force_scale / max(k, tiny(1.0_dp))), c%gap_round)
    h = -c%gap
    v = 0
    if (c%closed) then
      if (h < c%seg_h - tol) v = -1
      if (c%seg_len < huge(1.0_dp)) then
        if (h > c%seg_h + c%seg_len + tol) v = 1
      end if
    else
      if (h > m%pairs(c%pair)%soft_h(1) + tol) v = 1
    end if
  end function soft_violation

  !> Purpose: a pivot of soft CFE c whose overclosure left its segment: to
  !> the segment it lies in, by a block pivot (every violated CFE) or a
  !> single one (the violated CFE of least index alone; docs/contact.md,
  !> "Soft contact laws"). A block pivot that raises the pressure goes at
  !> most to the segment where it reaches max_rise times the larger of
  !> the pressure at its segment's top and the increment's force scale
  !> over its area: the status's solution, linear in the old segment,
  !> overshoots a convex law from below (an exponential by many decades,
  !> from which its segments bring it back by about one beta per pivot).
  !> Arguments: m the model; c the CFE (its gap of the last evaluation);
  !> block true for a block pivot; force_scale the increment's force
  !> scale F (contact_switch).
  subroutine pivot_soft(m, c, block, force_scale)
    type(model_t), intent(in) :: m
    type(cfe_t), intent(inout) :: c
    logical, intent(in) :: block
    real(dp), intent(in) :: force_scale
    integer :: target
    real(dp) :: p_cap
    target = soft_segment_at(m%pairs(c%pair), -c%gap)
    if (block .and. target > c%seg + 1) then
      associate(kp => m%pairs(c%pair)%soft_p)
        p_cap = force_scale / max(c%area, tiny(1.0_dp))
        if (c%seg > 0) p_cap = max(p_cap, kp(c%seg + 1))
        p_cap = max_rise * p_cap
        ! the last knot below p_cap (at least the next segment)
        target = max(min(target, count(kp < p_cap)), c%seg + 1)
      end associate
    end if
    call set_segment(m, c, target)
  end subroutine pivot_soft
end module contact_status
