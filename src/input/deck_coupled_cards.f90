!> The cards of coupled temperature-displacement analysis (docs/heat.md,
!> "Coupled temperature-displacement"): *COUPLED TEMPERATURE-DISPLACEMENT
!> (the procedure of a step of both fields), and the checks of a deck
!> whose run has both fields once it is read (settle_coupled_model,
!> check_coupled_model): a coupled step, or heat transfer and mechanical
!> steps in one deck.
module deck_coupled_cards
  use kinds, only: dp
  use strings, only: split_fields, field_t
  use deck_input, only: keyword_t, has_param, deck_warning, is_keyword, parse_keyword
  use deck_cursor, only: parser_t, err, allow_params, get_real, line_text, next_data, require_data
  use model, only: model_t, gap_heat_t
  use deck_heat_cards, only: read_thermal_procedure, check_fixed_increments
  implicit none
  private
  public :: read_coupled_step, settle_coupled_model, check_coupled_model, read_gap_conductance, &
            read_gap_heat_generation, gap_heat_pairs

contains

  !> Purpose: *COUPLED TEMPERATURE-DISPLACEMENT[, STEADY STATE][, DIRECT]
  !> [, DELTMX=] (SOLVER= read and ignored, as on *STATIC and *HEAT
  !> TRANSFER): the step's procedure, a step of the temperatures and the
  !> displacements; data line `initial increment, period[, min, max]`
  !> (default 1, 1), as CalculiX reads it. DIRECT: fixed increments of
  !> the initial size; without it the increments are automatic where a
  !> field needs them (NLGEOM or a nonlinear material, a transient with
  !> DELTMX), the driver's rules for either (docs/heat.md).
  !> Arguments: p the parser at the card, m the model, kw the card.
  subroutine read_coupled_step(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    m%coupled = .true.
    m%steps(p%step)%coupled = .true.
    call read_thermal_procedure(p, kw, '*COUPLED TEMPERATURE-DISPLACEMENT', m%steps(p%step))
    associate(s => m%steps(p%step))
      ! (automatic increments: counted as they are made)
      if (.not. s%direct .and. (s%deltmx > 0.0_dp .or. s%nlgeom)) return
      call check_fixed_increments(p, s)
    end associate
  end subroutine read_coupled_step

  !> Purpose: once the deck is read, before the model's checks: a deck of
  !> *HEAT TRANSFER and mechanical (*STATIC) steps is run with both
  !> fields, as a coupled deck is (the mechanical steps take the
  !> temperatures the heat steps left); its materials then need *ELASTIC
  !> (m%heat false: that is for decks of heat transfer steps alone).
  !> Arguments: m the model read.
  subroutine settle_coupled_model(m)
    type(model_t), intent(inout) :: m
    if (size(m%steps) == 0) return
    if (m%heat .and. .not. all(m%steps%heat)) m%coupled = .true.
    if (m%coupled) m%heat = .false.
  end subroutine settle_coupled_model

  !> Purpose: once the deck is read, in a run of both fields: every
  !> material with a section has *CONDUCTIVITY, and *DENSITY and *SPECIFIC
  !> HEAT when a step is transient; no *TEMPERATURE (the temperatures of
  !> the thermal strain are the temperature field's).
  !> Arguments: p the parser (its line moved to the card in error), m
  !> the model read.
  subroutine check_coupled_model(p, m)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(in) :: m
    integer :: s
    logical :: transient
    if (.not. m%coupled) return
    transient = .false.
    do s = 1, size(m%steps)
      p%i = m%steps(s)%src%line
      if (allocated(m%steps(s)%temps)) then
        if (size(m%steps(s)%temps) > 0) call err(p, '*TEMPERATURE in a deck with a *COUPLED TEMPERATURE-' // &
            'DISPLACEMENT or *HEAT TRANSFER step: the temperatures of the thermal strain are those the heat ' // &
            'transfer computes (*BOUNDARY on dof 11 prescribes them)')
      end if
      transient = transient .or. (m%steps(s)%heat .and. .not. m%steps(s)%steady)
    end do
    do s = 1, size(m%sections)
      if (m%sections(s)%spring .or. m%sections(s)%point_mass .or. m%sections(s)%material == 0) cycle
      associate(mat => m%materials(m%sections(s)%material))
        p%i = mat%src%line
        if (.not. mat%has_conductivity) call err(p, 'material ' // trim(mat%name) // ' has no *CONDUCTIVITY ' // &
                                                 '(a coupled temperature-displacement or heat transfer step)')
        if (transient .and. .not. (mat%has_specific_heat .and. mat%has_density)) call err(p, 'material ' // &
          trim(mat%name) // ' needs *DENSITY and *SPECIFIC HEAT for a transient heat transfer or coupled step')
      end associate
    end do
  end subroutine check_coupled_model

  !> Purpose: the gap heat entry of the current *SURFACE INTERACTION block
  !> (made on first use), its index in m%gap_heats.
  !> Arguments: p the parser (its current interaction), m the model,
  !> card the card's name for the message outside a block.
  integer function current_gap_heat(p, m, card) result(k)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    character(len=*), intent(in) :: card
    character(len=:), allocatable :: name
    if (p%interaction == 0) call err(p, '*' // card // ' outside a *SURFACE INTERACTION block')
    name = trim(p%inter(p%interaction)%name)
    if (.not. allocated(m%gap_heats)) allocate(m%gap_heats(0))
    do k = 1, size(m%gap_heats)
      if (m%gap_heats(k)%name == name) return
    end do
    m%gap_heats = [m%gap_heats, gap_heat_t(name=name)]
    k = size(m%gap_heats)
  end function current_gap_heat

  !> Purpose: *GAP CONDUCTANCE[, PRESSURE | CLEARANCE] in a *SURFACE
  !> INTERACTION block: data lines `conductance, x[, temperature]`, x
  !> increasing, linear between the lines. x is the contact pressure
  !> (CalculiX's reading, and Abaqus's with PRESSURE: h(p) of a closed
  !> point, constant beyond the table; one line without x: constant) or
  !> the clearance d (Abaqus's reading without PRESSURE; CLEARANCE, cfe2d's
  !> parameter, asks for it in any deck): h(d) of every coupled point,
  !> closed ones at d = 0, zero beyond the last clearance (the Abaqus
  !> keyword reference: "the value of the conductance drops to zero
  !> immediately after the last data point"). Without either parameter an
  !> Abaqus/CAE deck (*PART, *ASSEMBLY) reads clearances, any other deck
  !> pressures, with a warning where the two readings differ. A
  !> temperature dependence (different temperatures) and USER stop.
  !> Arguments: p the parser at the card, m the model, kw the card.
  subroutine read_gap_conductance(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    real(dp), allocatable :: hx(:, :)
    integer :: k, line0
    logical :: clearance
    call allow_params(p, kw, 'PRESSURE,CLEARANCE,USER')
    if (has_param(kw, 'USER')) call err(p, '*GAP CONDUCTANCE, USER: cfe2d has no user routines (CalculiX ' // &
      'calls gapcon, Abaqus GAPCON); give the conductance as data lines instead: `conductance, contact ' // &
      'pressure` with PRESSURE (or `conductance, clearance` with CLEARANCE), several lines for a table ' // &
      '(docs/heat.md)')
    if (has_param(kw, 'PRESSURE') .and. has_param(kw, 'CLEARANCE')) call err(p, '*GAP CONDUCTANCE: ' // &
      'PRESSURE or CLEARANCE, not both (the table''s second column is one of them)')
    k = current_gap_heat(p, m, 'GAP CONDUCTANCE')
    line0 = p%i
    clearance = has_param(kw, 'CLEARANCE') .or. (.not. has_param(kw, 'PRESSURE') .and. has_parts(p))
    call read_conductance_table(p, clearance, hx)
    ! the two readings differ unless the table is one line at x = 0
    if (.not. (has_param(kw, 'PRESSURE') .or. has_param(kw, 'CLEARANCE')) .and. &
        (size(hx, 2) > 1 .or. any(hx(2, :) /= 0.0_dp))) then
      if (clearance) then
        call deck_warning(p%deck, line0, '*GAP CONDUCTANCE without PRESSURE in an Abaqus/CAE deck (*PART, ' // &
          '*ASSEMBLY): its second column is read as the clearance, as Abaqus reads it (CalculiX would read ' // &
          'a contact pressure: add PRESSURE for that)')
      else
        call deck_warning(p%deck, line0, '*GAP CONDUCTANCE table without PRESSURE: its second column is ' // &
          'read as the contact pressure, as CalculiX reads it (Abaqus would read a clearance: add CLEARANCE ' // &
          'for that, or PRESSURE to say it is a pressure)')
      end if
    end if
    m%gap_heats(k)%gc_h = hx(1, :)
    m%gap_heats(k)%gc_p = hx(2, :)
    m%gap_heats(k)%clearance = clearance
  end subroutine read_gap_conductance

  !> Purpose: the data lines of *GAP CONDUCTANCE: hx(1, :) the
  !> conductances, hx(2, :) the pressures or (clearance) the clearances,
  !> increasing (an empty one 0), each line's temperature the first's.
  !> Arguments: p the parser at the card, clearance the second column is
  !> a clearance (for the messages), hx the table read.
  subroutine read_conductance_table(p, clearance, hx)
    type(parser_t), intent(inout) :: p
    logical, intent(in) :: clearance
    real(dp), allocatable, intent(out) :: hx(:, :)
    type(field_t), allocatable :: f(:)
    character(len=:), allocatable :: what
    real(dp) :: t1, t
    integer :: n
    what = merge('clearance       ', 'contact pressure', clearance)
    what = trim(what)
    call require_data(p, 'conductance')
    allocate(hx(2, 0))
    t1 = 0.0_dp
    do
      call split_fields(line_text(p), f, n)
      if (n < 1 .or. n > 3) call err(p, '*GAP CONDUCTANCE data line needs: conductance[, ' // what // &
                                     '[, temperature]]')
      hx = reshape([hx, get_real(p, f(1), 'conductance'), 0.0_dp], [2, size(hx, 2) + 1])
      if (n >= 2) then
        if (len(f(2)%s) > 0) hx(2, size(hx, 2)) = get_real(p, f(2), what)
      end if
      t = t1
      if (n == 3) then
        if (len(f(3)%s) > 0) t = get_real(p, f(3), 'temperature')
      end if
      if (size(hx, 2) == 1) t1 = t
      if (t /= t1) call err(p, 'a temperature-dependent *GAP CONDUCTANCE is not implemented (one temperature ' // &
                           'per table)')
      if (hx(1, size(hx, 2)) < 0.0_dp) call err(p, 'the gap conductance must not be negative')
      if (clearance .and. hx(2, size(hx, 2)) < 0.0_dp) call err(p, 'a clearance of *GAP CONDUCTANCE must ' // &
                                                                'not be negative')
      if (size(hx, 2) > 1) then
        if (hx(2, size(hx, 2)) <= hx(2, size(hx, 2) - 1)) call err(p, 'the ' // what // 's of a *GAP ' // &
                                                                  'CONDUCTANCE table must increase')
      end if
      if (.not. next_data(p)) exit
    end do
  end subroutine read_conductance_table

  !> Purpose: is the deck an Abaqus/CAE one (a *PART or an *ASSEMBLY
  !> anywhere in it, before or after the card asking), whose cards mean
  !> what Abaqus reads?
  !> Arguments: p the parser (its deck's lines).
  logical function has_parts(p)
    type(parser_t), intent(in) :: p
    type(keyword_t) :: kw
    integer :: i
    has_parts = .false.
    do i = 1, p%deck%n
      if (.not. is_keyword(p%deck%lines(i)%text)) cycle
      call parse_keyword(p%deck%lines(i)%text, kw)
      has_parts = kw%name == 'PART' .or. kw%name == 'ASSEMBLY'
      if (has_parts) return
    end do
  end function has_parts

  !> Purpose: *GAP HEAT GENERATION in a *SURFACE INTERACTION block: data
  !> line `eta, f[, velocity]` (defaults 1, 0.5): the fraction eta of the
  !> frictional power becomes heat, the fraction f of that goes to the
  !> slave surface; CalculiX's third value, the differential tangential
  !> velocity, is the slip rate used instead of the computed one (2D
  !> models sliding out of their plane). USER: the values CalculiX's default
  !> user routine fricheat returns (0.9, 0.3, 200), with a warning.
  !> Arguments: p the parser at the card, m the model, kw the card.
  subroutine read_gap_heat_generation(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    integer :: k, n
    call allow_params(p, kw, 'USER')
    k = current_gap_heat(p, m, 'GAP HEAT GENERATION')
    associate(g => m%gap_heats(k))
      g%generation = .true.
      if (has_param(kw, 'USER')) then
        ! CalculiX calls its user routine fricheat, whose default (the
        ! one compiled into ccx) returns eta 0.9, f 0.3 and the velocity
        ! 200 whatever the data lines say: the same here (CalculiX's ring4)
        g%eta = 0.9_dp
        g%f = 0.3_dp
        g%velocity = 200.0_dp
        call deck_warning(p%deck, p%i, '*GAP HEAT GENERATION, USER: cfe2d has no user routines; it takes what ' // &
            'CalculiX''s default fricheat returns: eta 0.9, f 0.3, velocity 200 (data lines ignored)')
        do while (next_data(p))
        end do
        return
      end if
      if (.not. next_data(p)) return
      call split_fields(line_text(p), f, n)
      if (n > 3) call err(p, '*GAP HEAT GENERATION data line needs: eta, f[, velocity]')
      if (len(f(1)%s) > 0) g%eta = get_real(p, f(1), 'eta')
      if (n >= 2) then
        if (len(f(2)%s) > 0) g%f = get_real(p, f(2), 'f')
      end if
      if (n >= 3) then
        if (len(f(3)%s) > 0) g%velocity = get_real(p, f(3), 'velocity')
      end if
      if (g%eta < 0.0_dp .or. g%eta > 1.0_dp .or. g%f < 0.0_dp .or. g%f > 1.0_dp) call err(p, 'eta and f of ' // &
          '*GAP HEAT GENERATION must lie in 0 .. 1')
      if (g%velocity < 0.0_dp) call err(p, 'the velocity of *GAP HEAT GENERATION must not be negative')
    end associate
  end subroutine read_gap_heat_generation

  !> Purpose: once the deck is read: each pair read with INTERACTION=
  !> takes its interaction's gap heat entry (contact_pair_t's gap_heat);
  !> in a deck of heat transfer steps alone that is an error (a deck of
  !> mechanical steps alone passes it over: it has no temperatures).
  !> Arguments: p the parser (its pairs' interaction names), m the model.
  subroutine gap_heat_pairs(p, m)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    integer :: j, k
    if (.not. allocated(m%gap_heats)) return
    do j = 1, p%npair_inter
      do k = 1, size(m%gap_heats)
        if (m%gap_heats(k)%name /= p%pair_inter(j)%name) cycle
        m%pairs(p%pair_inter(j)%pair)%gap_heat = k
        ! a deck of heat transfer steps alone has no contact pressures
        p%i = p%pair_inter(j)%line
        if (m%heat) call err(p, 'heat through the contact (*GAP CONDUCTANCE, *GAP HEAT GENERATION) needs ' // &
            'the contact''s pressures: a *COUPLED TEMPERATURE-DISPLACEMENT step, or a *STATIC step before the ' // &
            'heat transfer')
      end do
    end do
  end subroutine gap_heat_pairs
end module deck_coupled_cards
