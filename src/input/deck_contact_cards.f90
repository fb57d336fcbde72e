!> Contact and solver cards: *CONTACT PAIR, *CONTACT CONTROLS, *SOLVER.
!> (The *SURFACE INTERACTION block a pair may name: deck_interaction_cards.)
submodule (deck_parser) deck_contact_cards
  use kinds, only: dp
  use strings, only: split_fields, to_upper, field_t, parse_real, itoa, rtoa
  use deck_input, only: param_value, has_param, deck_warning
  use deck_cursor, only: max_cutbacks, max_contact_iterations, line_text, err, next_data, no_data, &
                         allow_params, param_real, param_int, need_nset, new_surface, get_real, &
                         behaviour_linear, behaviour_soft, add_pair_interaction, check_name_length, warn_empty_set, &
                         interaction_t
  use model, only: contact_pair_t, surface_t, surf_element, surf_node, coupling_nts, coupling_mortar, &
                   find_name, edge_nodes, elem_thickness, &
                   elem_nodes, axisymmetric_model, is_continuum
  use model_growth, only: grow
  use element_catalogue, only: max_nodes
  use solver_codes, only: solver_skyline, solver_cholmod, solver_mumps, solver_code, solver_in_build, &
                          order_natural, order_rcm, order_amd, order_metis, contact_solve_auto, &
                          contact_solve_condensed, contact_solve_full
  implicit none

contains

  !> Purpose: *CONTACT PAIR: `slave, master` per data line, the slave a
  !> surface or a node set, the master an element surface; the parameters
  !> (penalty, search) apply to every pair of the card. SYMMETRIC adds the
  !> pair with the roles swapped (two-pass contact); TYPE=SURFACE TO
  !> SURFACE is the segment-to-segment coupling, TYPE=NODE TO SURFACE the
  !> paper's node-to-segment one, and without TYPE= the first where the
  !> slave is an element surface (the second for INTERACTION=, as in
  !> CalculiX and Abaqus); EXACT exact enforcement.
  !> The CalculiX/Abaqus form names a *SURFACE INTERACTION (INTERACTION=)
  !> for the penalty (HARD: exact enforcement); SMALL SLIDING keeps the first
  !> pairing (without it, CalculiX's large sliding, the pairing is searched
  !> again every increment), ADJUST= moves slave nodes onto the master.
  module subroutine read_contact_pair(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(contact_pair_t) :: c
    integer :: card
    logical :: two_pass, sts, default_sts
    card = p%i
    associate(l => p%deck%lines(card))
      c%card_file = p%deck%files(l%file)%s
      c%card_line = l%line
      c%card_text = l%text
    end associate
    call allow_params(p, kw, 'PENALTY,OPEN PENALTY,NODAL,SEARCH DISTANCE,UPDATE SEARCH,TYPE,SYMMETRIC,' // &
                      'INTERACTION,SMALL SLIDING,ADJUST,FRICTION,STICK SLOPE,EXACT')
    sts = surface_to_surface(p, kw)
    two_pass = has_param(kw, 'SYMMETRIC')
    if (sts .and. two_pass) call err(p, 'SYMMETRIC (two-pass node-to-segment) and TYPE=SURFACE TO SURFACE ' // &
                                        '(segment-to-segment) exclude each other')
    ! Without TYPE=, cfe2d's own pair (no INTERACTION=) is segment-to-
    ! segment where it can be (an element slave surface, one pass): the
    ! smoother, consistent coupling (docs/contact.md, "Which coupling is
    ! the default"). A pair in CalculiX's and Abaqus's form (INTERACTION=)
    ! keeps their default, node to surface, so that their decks mean here
    ! what they mean there.
    default_sts = .not. (has_param(kw, 'TYPE') .or. has_param(kw, 'INTERACTION') .or. two_pass)
    call pair_penalty(p, kw, c)
    ! exact enforcement: cfe2d's EXACT, or (INTERACTION=) a HARD behaviour,
    ! set once the deck is read (interaction_penalties)
    c%exact = has_param(kw, 'EXACT')
    if (c%exact .and. has_param(kw, 'INTERACTION')) call err(p, 'give either INTERACTION= or EXACT (the ' // &
      'interaction''s PRESSURE-OVERCLOSURE=HARD is exact enforcement)')
    c%open_ratio = param_real(p, kw, 'OPEN PENALTY', 1.0e-12_dp)
    if (c%open_ratio < 0.0_dp .or. c%open_ratio >= 1.0_dp) call err(p, 'OPEN PENALTY (a ratio) must lie in [0, 1)')
    call pair_friction(p, kw, c)
    c%search_distance = param_real(p, kw, 'SEARCH DISTANCE', -1.0_dp)
    c%update_search = has_param(kw, 'UPDATE SEARCH') .or. &
        (has_param(kw, 'INTERACTION') .and. .not. (two_pass .or. sts) .and. .not. has_param(kw, 'SMALL SLIDING'))
    call pair_data_lines(p, m, kw, c, card, sts, default_sts, two_pass)
  end subroutine read_contact_pair

  !> Purpose: the data lines of a *CONTACT PAIR (`slave, master` each):
  !> one pair per line (and its twin for two-pass contact), taking the
  !> card's parameters already in c.
  !> Arguments:
  !>   p, m         parser state and model (the pairs are added to m)
  !>   kw           the *CONTACT PAIR keyword line
  !>   c            the pair as the card's parameters make it
  !>   card         the line of the *CONTACT PAIR card
  !>   sts          TYPE=SURFACE TO SURFACE was given
  !>   default_sts  no TYPE=, INTERACTION= nor SYMMETRIC: segment-to-segment where it can be
  !>   two_pass     SYMMETRIC: the pair again with the roles swapped
  subroutine pair_data_lines(p, m, kw, c, card, sts, default_sts, two_pass)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(contact_pair_t), intent(inout) :: c
    integer, intent(in) :: card
    logical, intent(in) :: sts, default_sts, two_pass
    type(field_t), allocatable :: f(:)
    integer :: n, npair
    npair = 0
    do while (next_data(p))
      call split_fields(line_text(p), f, n)
      if (n /= 2) call err(p, '*CONTACT PAIR data line needs: slave surface or node set, master surface')
      c%slave_surface = slave_surface(p, m, f(1)%s)
      c%master_surface = find_name(m%surfaces(1:p%nsurf)%name, to_upper(f(2)%s))
      if (c%master_surface == 0) call err(p, 'undefined surface ' // to_upper(f(2)%s))
      if (m%surfaces(c%master_surface)%kind /= surf_element) &
        call err(p, 'the master surface must be element-based')
      call warn_empty_set(p, size(m%surfaces(c%master_surface)%elem), 'surface', &
                          m%surfaces(c%master_surface)%name, kw%name)
      if (c%master_surface == c%slave_surface) call err(p, 'slave and master are the same surface')
      c%src%line = p%i
      c%twin = 0
      if (sts .and. m%surfaces(c%slave_surface)%kind /= surf_element) &
        call err(p, 'TYPE=SURFACE TO SURFACE (segment-to-segment) needs an element-based slave surface')
      c%coupling = coupling_nts
      if (sts .or. (default_sts .and. m%surfaces(c%slave_surface)%kind == surf_element)) &
        c%coupling = coupling_mortar
      if (has_param(kw, 'ADJUST')) call adjust_slave_nodes(p, m, param_value(kw, 'ADJUST'), c)
      call add_pair(p, m, c)
      if (has_param(kw, 'INTERACTION')) call add_pair_interaction(p, p%npairs, card, &
                                                                  to_upper(param_value(kw, 'INTERACTION')))
      npair = npair + 1
      if (two_pass) call add_second_pass(p, m, kw, c, card)
    end do
    if (npair == 0) call err(p, 'missing data line (slave, master)')
  end subroutine pair_data_lines

  !> Purpose: SYMMETRIC (two-pass node-to-segment): the pair just added
  !> (m%pairs(p%npairs), from c) again with slave and master swapped, its
  !> twin; refused where the two meshes differ in density.
  subroutine add_second_pass(p, m, kw, c, card)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(contact_pair_t), intent(inout) :: c
    integer, intent(in) :: card
    integer :: first
    real(dp) :: ratio
    if (.not. similar_density(m, c%slave_surface, c%master_surface, ratio)) then
      ! Two passes over meshes of different density fight: the finer
      ! side's nodes open in turn and its pressures alternate (measured
      ! -75 % / +72 % about the right value at 2:1), with a wrong total.
      if (has_param(kw, 'SYMMETRIC')) call err(p, 'SYMMETRIC two-pass contact needs slave and master meshes ' // &
        'of about the same density (mean edge lengths differ by a factor ' // rtoa(ratio, 3) // &
        '): drop SYMMETRIC and make the finer surface the slave')
      call deck_warning(p%deck, p%i, 'SURFACE TO SURFACE: the two meshes differ in density by a factor ' // &
        rtoa(ratio, 3) // '; contact is single-pass from the first (slave) surface, which should be the finer')
      return
    end if
    ! Two-pass contact: the same pair again with the roles swapped.
    if (m%surfaces(c%slave_surface)%kind /= surf_element) &
      call err(p, 'two-pass contact (SYMMETRIC, TYPE=SURFACE TO SURFACE) needs an element-based slave ' // &
               'surface (it is the master of the second pass)')
    first = p%npairs
    m%pairs(first)%twin = first + 1
    c%slave_surface = m%pairs(first)%master_surface
    c%master_surface = m%pairs(first)%slave_surface
    c%twin = first
    call add_pair(p, m, c)
    if (has_param(kw, 'INTERACTION')) call add_pair_interaction(p, p%npairs, card, &
                                                                to_upper(param_value(kw, 'INTERACTION')))
  end subroutine add_second_pass

  !> Purpose: do two element surfaces have about the same mesh density?
  !> ratio returns the larger mean edge length over the smaller; above
  !> 1.5 two-pass contact is not used (see read_contact_pair).
  logical function similar_density(m, s1, s2, ratio)
    type(model_t), intent(in) :: m
    integer, intent(in) :: s1, s2
    real(dp), intent(out) :: ratio
    real(dp) :: h1, h2
    ! an empty surface (warned about) has no density to compare
    ratio = 1.0_dp
    similar_density = .true.
    if (size(m%surfaces(s1)%elem) == 0 .or. size(m%surfaces(s2)%elem) == 0) return
    h1 = mean_edge_length(m, m%surfaces(s1))
    h2 = mean_edge_length(m, m%surfaces(s2))
    ratio = max(h1, h2) / max(min(h1, h2), tiny(1.0_dp))
    similar_density = ratio <= 1.5_dp
  end function similar_density

  real(dp) function mean_edge_length(m, s)
    type(model_t), intent(in) :: m
    type(surface_t), intent(in) :: s
    integer :: k, a, b
    mean_edge_length = 0.0_dp
    do k = 1, size(s%elem)
      call edge_nodes(m, s%elem(k), s%edge(k), a, b)
      mean_edge_length = mean_edge_length + norm2(m%x(:, b) - m%x(:, a))
    end do
    mean_edge_length = mean_edge_length / max(size(s%elem), 1)
  end function mean_edge_length

  !> TYPE= of *CONTACT PAIR: NODE TO SURFACE (the paper's node-to-segment
  !> coupling) or SURFACE TO SURFACE (true: segment-to-segment, see
  !> docs/contact.md); absent: false (the caller picks the default).
  logical function surface_to_surface(p, kw)
    type(parser_t), intent(in) :: p
    type(keyword_t), intent(in) :: kw
    character(len=:), allocatable :: t
    surface_to_surface = .false.
    if (.not. has_param(kw, 'TYPE')) return
    t = to_upper(param_value(kw, 'TYPE'))
    select case (t)
    case ('NODE TO SURFACE')
    case ('SURFACE TO SURFACE')
      surface_to_surface = .true.
    case ('MORTAR')
      call err(p, 'TYPE=MORTAR is not a CalculiX 2D pair type here; TYPE=SURFACE TO SURFACE is cfe2d''s ' // &
               'mortar (segment-to-segment) coupling, with exact enforcement under PRESSURE-OVERCLOSURE=HARD')
    case ('MASSLESS')
      call err(p, 'TYPE=MASSLESS belongs to explicit dynamics, which cfe2d does not do')
    case default
      call err(p, 'TYPE must be NODE TO SURFACE or SURFACE TO SURFACE')
    end select
  end function surface_to_surface

  !> The penalty of a pair given by cfe2d's PENALTY= (per area, or per
  !> node with NODAL); with INTERACTION= it comes from the *SURFACE
  !> INTERACTION, resolved once the deck is read (interaction_penalties).
  subroutine pair_penalty(p, kw, c)
    type(parser_t), intent(in) :: p
    type(keyword_t), intent(in) :: kw
    type(contact_pair_t), intent(inout) :: c
    if (has_param(kw, 'INTERACTION')) then
      if (has_param(kw, 'PENALTY') .or. has_param(kw, 'NODAL')) &
        call err(p, 'give either INTERACTION= or PENALTY= (the interaction''s *SURFACE BEHAVIOR is the penalty)')
      if (len(param_value(kw, 'INTERACTION')) == 0) call err(p, 'INTERACTION= needs the name of a *SURFACE INTERACTION')
      call check_name_length(p, param_value(kw, 'INTERACTION'))
      c%penalty = -1.0_dp
      c%nodal = .false.
      return
    end if
    c%penalty = param_real(p, kw, 'PENALTY', -1.0_dp)
    if (has_param(kw, 'PENALTY') .and. c%penalty <= 0.0_dp) call err(p, 'PENALTY must be positive')
    c%nodal = has_param(kw, 'NODAL')
    if (c%nodal .and. .not. has_param(kw, 'PENALTY')) call err(p, 'NODAL needs PENALTY=')
  end subroutine pair_penalty

  !> cfe2d's own friction parameters of a pair: FRICTION= (the Coulomb
  !> coefficient) and STICK SLOPE= (shear stress per unit slip); with
  !> INTERACTION= the interaction's *FRICTION gives them.
  subroutine pair_friction(p, kw, c)
    type(parser_t), intent(in) :: p
    type(keyword_t), intent(in) :: kw
    type(contact_pair_t), intent(inout) :: c
    if (has_param(kw, 'INTERACTION') .and. (has_param(kw, 'FRICTION') .or. has_param(kw, 'STICK SLOPE'))) &
      call err(p, 'give either INTERACTION= or FRICTION= (the interaction''s *FRICTION is the friction)')
    c%mu = param_real(p, kw, 'FRICTION', 0.0_dp)
    if (c%mu < 0.0_dp) call err(p, 'FRICTION (the friction coefficient) must not be negative')
    c%stick_slope = param_real(p, kw, 'STICK SLOPE', -1.0_dp)
    if (has_param(kw, 'STICK SLOPE') .and. c%stick_slope <= 0.0_dp) call err(p, 'STICK SLOPE must be positive')
    if (has_param(kw, 'STICK SLOPE') .and. c%mu == 0.0_dp) call err(p, 'STICK SLOPE needs FRICTION=')
  end subroutine pair_friction

  !> Purpose: the pairs read with INTERACTION= take the penalty of their
  !> *SURFACE INTERACTION (defined anywhere in the deck, as CalculiX allows):
  !> a LINEAR slope K is the penalty per area, split between the two passes
  !> of a two-pass pair so that the interface still yields K per unit
  !> overclosure; HARD (or no *SURFACE BEHAVIOR, as in Abaqus) is the
  !> automatic penalty. *FRICTION's coefficient and stick slope likewise
  !> (the slope split between the passes as K is).
  module subroutine interaction_penalties(p, m)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    integer :: j, k, it
    do j = 1, p%npair_inter
      associate(pi => p%pair_inter(j))
        it = 0
        do k = 1, p%ninter
          if (p%inter(k)%name == pi%name) it = k
        end do
        if (it == 0) then
          p%i = pi%line
          call err(p, 'undefined surface interaction ' // trim(pi%name))
        end if
        associate(c => m%pairs(pi%pair))
          c%penalty = -1.0_dp
          if (p%inter(it)%behaviour == behaviour_linear) c%penalty = p%inter(it)%slope
          ! HARD: exact enforcement (the automatic penalty only sets the pace)
          c%exact = p%inter(it)%behaviour /= behaviour_linear .and. p%inter(it)%behaviour /= behaviour_soft
          ! a soft law: its pressures, halved between the passes of a two-pass pair
          if (p%inter(it)%behaviour == behaviour_soft) then
            c%soft_h = p%inter(it)%soft_h
            c%soft_p = p%inter(it)%soft_p
            if (c%twin /= 0) c%soft_p = 0.5_dp * c%soft_p
          end if
          if (c%twin /= 0 .and. c%penalty > 0.0_dp) c%penalty = 0.5_dp * c%penalty
          c%mu = p%inter(it)%mu
          c%stick_slope = p%inter(it)%stick_slope
          if (p%inter(it)%thickness > 0.0_dp) call check_thickness(p, m, p%inter(it), c)
          if (c%twin /= 0 .and. c%stick_slope > 0.0_dp) c%stick_slope = 0.5_dp * c%stick_slope
          if (p%inter(it)%wear_line > 0) call pair_wear(p, p%inter(it), pi%line, c)
        end associate
      end associate
    end do
  end subroutine interaction_penalties

  !> Purpose: a pair takes its interaction's *WEAR (Archard wear,
  !> docs/contact.md "Wear"): its coefficients and cycle-jump factor. Wear
  !> integrates the friction's slip, so the interaction needs *FRICTION
  !> (an error at the *WEAR card); a two-pass (SYMMETRIC) pair is refused
  !> at its *CONTACT PAIR line (each surface would be worn by both passes).
  !> Arguments: p the parser; it the interaction; line the pair's line; c
  !> the pair.
  subroutine pair_wear(p, it, line, c)
    type(parser_t), intent(inout) :: p
    type(interaction_t), intent(in) :: it
    integer, intent(in) :: line
    type(contact_pair_t), intent(inout) :: c
    if (.not. c%mu > 0.0_dp) then
      p%i = it%wear_line
      call err(p, '*WEAR needs a friction coefficient (*FRICTION) in surface interaction ' // trim(it%name) // &
               ': the wear integrates the friction''s slip')
    end if
    if (c%twin /= 0) then
      p%i = line
      call err(p, '*WEAR (surface interaction ' // trim(it%name) // ') is not implemented for two-pass ' // &
               '(SYMMETRIC) contact; give one pass')
    end if
    c%wear = any(it%wear_k > 0.0_dp)
    c%wear_k = it%wear_k
    c%wear_jump = it%wear_jump
  end subroutine pair_wear

  !> The out-of-plane thickness on a *SURFACE INTERACTION's data line
  !> (Abaqus, 2D) must be the thickness of the sections of the pair's
  !> element surfaces, which cfe2d's contact areas take; axisymmetric
  !> models have none to compare.
  subroutine check_thickness(p, m, it, c)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(in) :: m
    type(interaction_t), intent(in) :: it
    type(contact_pair_t), intent(in) :: c
    integer :: s, k, e, surf(2)
    real(dp) :: t(max_nodes)
    if (axisymmetric_model(m)) return
    surf = [c%slave_surface, c%master_surface]
    do s = 1, 2
      if (m%surfaces(surf(s))%kind /= surf_element) cycle
      do k = 1, size(m%surfaces(surf(s))%elem)
        e = m%surfaces(surf(s))%elem(k)
        if (.not. is_continuum(m, e) .or. m%elem_section(e) == 0) cycle
        t = elem_thickness(m, e)
        if (any(abs(t(1:elem_nodes(m, e)) - it%thickness) > 1.0e-9_dp * it%thickness)) then
          p%i = it%line + 1
          call err(p, 'the out-of-plane thickness ' // rtoa(it%thickness, 6) // ' differs from the section ' // &
                   'thickness ' // rtoa(maxval(t(1:elem_nodes(m, e))), 6) // ' of surface ' // &
                   trim(m%surfaces(surf(s))%name) // ': cfe2d''s contact area takes the section''s')
        end if
      end do
    end do
  end subroutine check_thickness

  !> Purpose: ADJUST= of *CONTACT PAIR (CalculiX): before the analysis,
  !> slave nodes are moved onto the master surface along its normal. With
  !> a number, the slave nodes whose clearance is at most that number
  !> (penetrating ones always); with a node set, the nodes of the set.
  !> Only nodes whose projection falls on a master edge move; the count
  !> and the largest move are reported as a warning on the card.
  subroutine adjust_slave_nodes(p, m, value, c)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    character(len=*), intent(in) :: value
    type(contact_pair_t), intent(in) :: c
    type(field_t) :: f
    integer, allocatable :: nodes(:)
    real(dp) :: tol, d, nvec(2), largest
    logical :: by_set, ok
    integer :: k, moved
    by_set = .false.
    tol = 0.0_dp
    call parse_real(value, tol, ok)
    if (ok) then
      f%s = value
      tol = get_real(p, f, 'value of ADJUST')
      if (tol < 0.0_dp) call err(p, 'ADJUST= must be a non-negative distance or a node set')
      nodes = m%surfaces(c%slave_surface)%nodes
    else
      by_set = .true.
      k = need_nset(p, m, value)
      nodes = m%nsets(k)%items
      call warn_empty_set(p, size(nodes), 'node set', m%nsets(k)%name, 'CONTACT PAIR (ADJUST=)')
    end if
    moved = 0
    largest = 0.0_dp
    do k = 1, size(nodes)
      call master_projection(m, m%surfaces(c%master_surface), nodes(k), d, nvec, ok)
      if (.not. ok) cycle
      if (.not. by_set .and. d > tol) cycle
      if (d == 0.0_dp) cycle      ! on the master already
      m%x(:, nodes(k)) = m%x(:, nodes(k)) - d * nvec
      moved = moved + 1
      largest = max(largest, abs(d))
    end do
    call deck_warning(p%deck, p%i, 'ADJUST moved ' // itoa(moved) // ' slave node(s) onto the master surface ' // &
                      '(by at most ' // rtoa(largest, 3) // ')')
  end subroutine adjust_slave_nodes

  !> Signed distance d of node s from the nearest master edge on which its
  !> orthogonal projection falls (positive: clearance, on the outer side)
  !> and that edge's outward unit normal; ok false if there is none. The
  !> same rule as the contact search: a node more than half an edge length
  !> behind an edge is on the far side of the master body.
  subroutine master_projection(m, ms, s, d, nvec, ok)
    type(model_t), intent(in) :: m
    type(surface_t), intent(in) :: ms
    integer, intent(in) :: s
    real(dp), intent(out) :: d, nvec(2)
    logical, intent(out) :: ok
    real(dp), parameter :: edge_tol = 1.0e-6_dp
    real(dp) :: ab(2), t, len, dj, nj(2)
    integer :: j, a, b
    ok = .false.
    d = huge(1.0_dp)
    nvec = 0.0_dp
    do j = 1, size(ms%elem)
      call edge_nodes(m, ms%elem(j), ms%edge(j), a, b)
      if (a == s .or. b == s) cycle
      ab = m%x(:, b) - m%x(:, a)
      len = norm2(ab)
      t = dot_product(m%x(:, s) - m%x(:, a), ab) / len**2
      if (t < -edge_tol .or. t > 1.0_dp + edge_tol) cycle
      nj = [ab(2), -ab(1)] / len
      dj = dot_product(m%x(:, s) - m%x(:, a), nj)
      if (dj < -0.5_dp * len) cycle
      if (abs(dj) < abs(d)) then
        d = dj
        nvec = nj
        ok = .true.
      end if
    end do
  end subroutine master_projection

  subroutine add_pair(p, m, pair)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(contact_pair_t), intent(in) :: pair
    call grow(m%pairs, p%npairs + 1)
    p%npairs = p%npairs + 1
    m%pairs(p%npairs) = pair
  end subroutine add_pair

  !> The slave surface named on a *CONTACT PAIR line: a surface, or a node
  !> set, which becomes a node surface of the same name. Either one empty
  !> is warned about.
  integer function slave_surface(p, m, name) result(isurf)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    character(len=*), intent(in) :: name
    integer :: ns
    isurf = find_name(m%surfaces(1:p%nsurf)%name, to_upper(name))
    if (isurf > 0) then
      call warn_empty_set(p, size(m%surfaces(isurf)%nodes), 'surface', m%surfaces(isurf)%name, 'CONTACT PAIR')
      return
    end if
    ns = need_nset(p, m, name)
    call warn_empty_set(p, size(m%nsets(ns)%items), 'node set', m%nsets(ns)%name, 'CONTACT PAIR')
    isurf = new_surface(p, m)
    m%surfaces(isurf)%name = m%nsets(ns)%name
    m%surfaces(isurf)%kind = surf_node
    allocate(m%surfaces(isurf)%elem(0), m%surfaces(isurf)%edge(0))
    m%surfaces(isurf)%nodes = m%nsets(ns)%items
  end function slave_surface

  !> Purpose: *CONTACT CONTROLS: TOLERANCE= (positive), MAXIT= (contact
  !> status iterations per increment, 1..max_contact_iterations) and
  !> CUTBACKS= (increment bisections, 0..max_cutbacks: each one is a level
  !> of recursion in the analysis, so the count is bounded).
  module subroutine read_contact_controls(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    call allow_params(p, kw, 'TOLERANCE,MAXIT,CUTBACKS')
    m%contact_tolerance = param_real(p, kw, 'TOLERANCE', m%contact_tolerance)
    if (m%contact_tolerance <= 0.0_dp) call err(p, 'TOLERANCE must be positive')
    m%contact_max_iter = param_int(p, kw, 'MAXIT', m%contact_max_iter, 1, max_contact_iterations)
    m%max_cutbacks = param_int(p, kw, 'CUTBACKS', m%max_cutbacks, 0, max_cutbacks)
    call no_data(p, kw)
  end subroutine read_contact_controls

  !> Purpose: *SOLVER: TYPE= (CHOLMOD, UMFPACK, SKYLINE, MUMPS: the last
  !> only in a build with MPI and MUMPS), ORDERING= (AMD or METIS for the
  !> sparse solvers, RCM or NONE for the skyline) and CONTACT SOLVE=
  !> (AUTO, CONDENSED: CHOLMOD and MUMPS only, FULL).
  module subroutine read_solver(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    character(len=:), allocatable :: v
    call allow_params(p, kw, 'TYPE,ORDERING,CONTACT SOLVE')
    if (has_param(kw, 'TYPE')) then
      v = to_upper(param_value(kw, 'TYPE'))
      if (solver_code(v) == 0) call err(p, 'solver ' // v // ' is not available (SKYLINE, CHOLMOD, UMFPACK, MUMPS)')
      m%solver = solver_code(v)
      if (.not. solver_in_build(m%solver)) call err(p, 'TYPE=MUMPS: this cfe2d was built without MUMPS (no MPI ' // &
        'or libmumps-dev where it was built: install them, scripts/install-deps.sh, and make clean all)')
    end if
    ! default ordering of each solver
    if (m%solver == solver_skyline) then
      m%ordering = order_rcm
    else
      m%ordering = order_amd
    end if
    if (has_param(kw, 'ORDERING')) then
      v = to_upper(param_value(kw, 'ORDERING'))
      if (m%solver == solver_skyline) then
        select case (v)
        case ('RCM'); m%ordering = order_rcm
        case ('NONE'); m%ordering = order_natural
        case default; call err(p, 'ordering ' // v // ' is not available for the skyline solver (RCM, NONE)')
        end select
      else
        select case (v)
        case ('AMD'); m%ordering = order_amd
        case ('METIS'); m%ordering = order_metis
        case default; call err(p, 'ordering ' // v // ' is not available for CHOLMOD, UMFPACK and MUMPS (AMD, METIS)')
        end select
      end if
    end if
    if (has_param(kw, 'CONTACT SOLVE')) then
      v = to_upper(param_value(kw, 'CONTACT SOLVE'))
      select case (v)
      case ('AUTO'); m%contact_solve = contact_solve_auto
      case ('CONDENSED'); m%contact_solve = contact_solve_condensed
      case ('FULL'); m%contact_solve = contact_solve_full
      case default; call err(p, 'CONTACT SOLVE=' // v // ' is not available (AUTO, CONDENSED, FULL)')
      end select
    end if
    if (m%contact_solve == contact_solve_condensed .and. m%solver /= solver_cholmod .and. m%solver /= solver_mumps) &
      call err(p, 'CONTACT SOLVE=CONDENSED needs TYPE=CHOLMOD or MUMPS (the other solvers factor the full system)')
    call no_data(p, kw)
  end subroutine read_solver
end submodule deck_contact_cards
