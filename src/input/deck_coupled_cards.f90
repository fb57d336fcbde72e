!> The cards of coupled temperature-displacement analysis (docs/heat.md,
!> "Coupled temperature-displacement"): *COUPLED TEMPERATURE-DISPLACEMENT
!> (the procedure of a step of both fields), and the checks of a deck
!> whose run has both fields once it is read (settle_coupled_model,
!> check_coupled_model): a coupled step, or heat transfer and mechanical
!> steps in one deck.
module deck_coupled_cards
  use kinds, only: dp
  use strings, only: split_fields, field_t, itoa
  use deck_input, only: keyword_t, param_value, has_param
  use deck_cursor, only: parser_t, max_increments, read_time_line, err, allow_params, get_real
  use model, only: model_t
  implicit none
  private
  public :: read_coupled_step, settle_coupled_model, check_coupled_model

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
    type(field_t), allocatable :: f(:)
    integer :: n
    real(dp) :: ratio
    call allow_params(p, kw, 'STEADY STATE,DIRECT,DELTMX,SOLVER')
    associate(s => m%steps(p%step))
      if (s%period > 0.0_dp) call err(p, 'second procedure in one step')
      m%coupled = .true.
      s%heat = .true.
      s%coupled = .true.
      s%steady = has_param(kw, 'STEADY STATE')
      s%direct = has_param(kw, 'DIRECT')
      s%deltmx = 0.0_dp
      if (has_param(kw, 'DELTMX')) then
        call split_fields(param_value(kw, 'DELTMX'), f, n)
        s%deltmx = get_real(p, f(1), 'DELTMX')
        if (s%deltmx <= 0.0_dp) call err(p, 'DELTMX must be positive')
      end if
      call read_time_line(p, '*COUPLED TEMPERATURE-DISPLACEMENT', s)
      if (s%steady) s%deltmx = 0.0_dp
      ! (automatic increments: counted as they are made)
      if (.not. s%direct .and. (s%deltmx > 0.0_dp .or. s%nlgeom)) return
      ratio = s%period / s%dt
      if (.not. (ratio <= real(max_increments, dp))) call err(p, 'the step would need ' // itoa(nint(min(ratio, &
          1.0e9_dp))) // ' or more increments (time period / initial increment); at most ' // &
          itoa(max_increments) // ' are allowed')
      if (nint(ratio) > s%max_inc) call err(p, 'the step needs ' // itoa(nint(ratio)) // &
          ' increments, more than INC=' // itoa(s%max_inc) // ' on *STEP allows')
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
end module deck_coupled_cards
