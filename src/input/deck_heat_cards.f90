!> The cards of heat transfer (docs/heat.md): *HEAT TRANSFER (the
!> procedure of a step of the temperature field), *CONDUCTIVITY and
!> *SPECIFIC HEAT (constants or tables), *BOUNDARY on dof 11 (prescribed
!> temperatures), *CFLUX, *DFLUX (faces S1..S4 and the body BF), *FILM
!> (faces F1..F4: film coefficient and sink temperature), *RADIATE
!> (faces R1..R4: radiation to the environment) with *PHYSICAL
!> CONSTANTS; the cards of heat transfer cfe2d does not have (cavity
!> radiation, fluid networks) stop with their reason. check_heat_model
!> checks, once the deck is read, that the steps of the deck are all of
!> heat transfer when one is (the coupled analysis is issue 30's item 2).
module deck_heat_cards
  use kinds, only: dp
  use strings, only: split_fields, to_upper, field_t, itoa
  use deck_input, only: keyword_t, param_value, has_param, is_keyword, parse_keyword, deck_warning
  use deck_cursor, only: parser_t, max_increments, read_time_line, line_text, err, next_data, require_data, no_data, &
                         allow_params, &
                         get_real, get_int, is_int, is_label, elem_ref, need_elset, warn_empty_set, &
                         target_nodes, amplitude_param
  use model, only: model_t, step_t, bc_t, cload_t, heat_load_t, heat_bf, src_t
  use element_catalogue, only: catalogue
  implicit none
  private
  public :: read_heat_transfer, read_thermal_procedure, check_fixed_increments, read_conductivity, &
            read_specific_heat, read_heat_boundary, read_cflux, &
            read_dflux, read_film, read_radiate, read_physical_constants, reject_heat_card, boundary_lines, &
            is_heat_line, &
            check_heat_model

  !> CalculiX's dof of the temperature.
  integer, parameter :: dof_temperature = 11

contains

  !> Purpose: *HEAT TRANSFER[, STEADY STATE][, DIRECT][, DELTMX=]
  !> (SOLVER= is read and ignored, as on *STATIC): the step's procedure;
  !> data line `initial increment, period[, min, max]` (CalculiX's
  !> defaults 1, 1). With DIRECT the increments are fixed (period /
  !> initial increment of them); without, automatic as CalculiX's, steady
  !> or transient: growing, and in a transient step cut back where a
  !> temperature changes by more than DELTMX= in an increment.
  subroutine read_heat_transfer(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    m%heat = .true.
    call read_thermal_procedure(p, kw, '*HEAT TRANSFER', m%steps(p%step))
    ! fixed increments are counted here (automatic ones as they are made)
    if (m%steps(p%step)%direct) call check_fixed_increments(p, m%steps(p%step))
  end subroutine read_heat_transfer

  !> Purpose: what *HEAT TRANSFER and *COUPLED TEMPERATURE-DISPLACEMENT
  !> share: STEADY STATE, DIRECT, DELTMX= (positive; none in a steady
  !> step) and the time line (read_time_line) into step s, which becomes a
  !> heat step; a second procedure in one step stops.
  !> Arguments: p the parser at the card, kw the card, card its name for
  !> the messages, s the step.
  subroutine read_thermal_procedure(p, kw, card, s)
    type(parser_t), intent(inout) :: p
    type(keyword_t), intent(in) :: kw
    character(len=*), intent(in) :: card
    type(step_t), intent(inout) :: s
    type(field_t), allocatable :: f(:)
    integer :: n
    call allow_params(p, kw, 'STEADY STATE,DIRECT,DELTMX,SOLVER')
    if (s%period > 0.0_dp) call err(p, 'second procedure in one step')
    s%heat = .true.
    s%steady = has_param(kw, 'STEADY STATE')
    s%direct = has_param(kw, 'DIRECT')
    s%deltmx = 0.0_dp
    if (has_param(kw, 'DELTMX')) then
      call split_fields(param_value(kw, 'DELTMX'), f, n)
      s%deltmx = get_real(p, f(1), 'DELTMX')
      if (s%deltmx <= 0.0_dp) call err(p, 'DELTMX must be positive')
    end if
    call read_time_line(p, card, s)
    if (s%steady) s%deltmx = 0.0_dp
  end subroutine read_thermal_procedure

  !> Purpose: a step of fixed increments takes period / initial increment
  !> of them: at most max_increments, and at most INC= of its *STEP.
  !> Arguments: p the parser at the card, s the step.
  subroutine check_fixed_increments(p, s)
    type(parser_t), intent(inout) :: p
    type(step_t), intent(in) :: s
    real(dp) :: ratio
    ratio = s%period / s%dt
    if (.not. (ratio <= real(max_increments, dp))) call err(p, 'the step would need ' // itoa(nint(min(ratio, &
        1.0e9_dp))) // ' or more increments (time period / initial increment); at most ' // &
        itoa(max_increments) // ' are allowed')
    if (nint(ratio) > s%max_inc) call err(p, 'the step needs ' // itoa(nint(ratio)) // &
        ' increments, more than INC=' // itoa(s%max_inc) // ' on *STEP allows')
  end subroutine check_fixed_increments

  !> Purpose: *CONDUCTIVITY[, TYPE=ISO]: `k[, temperature]`;
  !> TYPE=ORTHO: `k11, k22, k33[, temperature]` along the global axes
  !> (k33, out of the plane or the hoop direction, plays no part in 2D
  !> conduction). Several data lines, temperatures increasing: a table,
  !> linear between its points and constant beyond (the conduction then
  !> depends on the temperature: temperature_field iterates).
  subroutine read_conductivity(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    character(len=:), allocatable :: kind
    integer :: n, nv
    real(dp) :: k(2), t
    call allow_params(p, kw, 'TYPE')
    kind = 'ISO'
    if (has_param(kw, 'TYPE')) kind = to_upper(param_value(kw, 'TYPE'))
    if (kind /= 'ISO' .and. kind /= 'ORTHO') call err(p, 'TYPE=' // kind // ' of *CONDUCTIVITY is not ' // &
        'implemented (ISO and ORTHO are)')
    if (p%material == 0) call err(p, '*CONDUCTIVITY outside a *MATERIAL')
    nv = merge(1, 3, kind == 'ISO')
    call require_data(p, 'conductivity')
    associate(mat => m%materials(p%material))
      mat%nk = 0
      do
        call split_fields(line_text(p), f, n)
        if (n < nv .or. n > nv + 1) call err(p, '*CONDUCTIVITY data line needs: ' // &
            trim(merge('k[, temperature]            ', 'k11, k22, k33[, temperature]', kind == 'ISO')))
        k = get_real(p, f(1), 'conductivity')
        if (nv == 3) k = [k(1), get_real(p, f(2), 'k22')]
        if (any(k <= 0.0_dp)) call err(p, 'the conductivities must be positive')
        if (nv == 3) then
          if (get_real(p, f(3), 'k33') <= 0.0_dp) call err(p, 'the conductivities must be positive')
        end if
        t = table_temperature(p, f, n, nv + 1, mat%ktab, mat%nk, '*CONDUCTIVITY')
        mat%nk = mat%nk + 1
        mat%ktab(:, mat%nk) = [t, k]
        if (.not. next_data(p)) exit
      end do
      mat%conductivity = mat%ktab(2:3, 1)
      mat%has_conductivity = .true.
    end associate
  end subroutine read_conductivity

  !> Purpose: the temperature of a data line of a material table
  !> (*CONDUCTIVITY, *SPECIFIC HEAT): field pos when the line has it and
  !> it is not blank, else 0; it must exceed the table's last (rows 1:nrows
  !> of tab, temperatures in row 1), and the table must have room for one
  !> more row.
  !> Arguments: p the parser at the line, f(1:n) its fields, pos the
  !> temperature's field, tab and nrows the table so far, card its name.
  real(dp) function table_temperature(p, f, n, pos, tab, nrows, card) result(t)
    type(parser_t), intent(inout) :: p
    type(field_t), intent(in) :: f(:)
    integer, intent(in) :: n, pos, nrows
    real(dp), intent(in) :: tab(:, :)
    character(len=*), intent(in) :: card
    t = 0.0_dp
    if (n == pos) then
      if (len(f(pos)%s) > 0) t = get_real(p, f(pos), 'temperature')
    end if
    if (nrows > 0) then
      if (t <= tab(1, nrows)) call err(p, 'the temperatures of a ' // card // ' table must increase')
    end if
    if (nrows == size(tab, 2)) call err(p, 'a ' // card // ' table of more than ' // itoa(size(tab, 2)) // ' lines')
  end function table_temperature

  !> Purpose: *SPECIFIC HEAT: `c[, temperature]`; several data lines,
  !> temperatures increasing: a table, linear between its points and
  !> constant beyond (the capacity then depends on the temperature:
  !> temperature_field iterates).
  subroutine read_specific_heat(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    integer :: n
    real(dp) :: c, t
    call allow_params(p, kw, '')
    if (p%material == 0) call err(p, '*SPECIFIC HEAT outside a *MATERIAL')
    call require_data(p, 'specific heat')
    associate(mat => m%materials(p%material))
      mat%nc = 0
      do
        call split_fields(line_text(p), f, n)
        if (n > 2) call err(p, '*SPECIFIC HEAT data line needs: specific heat[, temperature]')
        c = get_real(p, f(1), 'specific heat')
        if (c <= 0.0_dp) call err(p, 'the specific heat must be positive')
        t = table_temperature(p, f, n, 2, mat%ctab, mat%nc, '*SPECIFIC HEAT')
        mat%nc = mat%nc + 1
        mat%ctab(:, mat%nc) = [t, c]
        if (.not. next_data(p)) exit
      end do
      mat%specific_heat = mat%ctab(2, 1)
      mat%has_specific_heat = .true.
    end associate
  end subroutine read_specific_heat

  !> Purpose: which kinds of lines the *BOUNDARY card at line p%i holds:
  !> temperature lines (is_heat_line: read_heat_boundary reads them) and
  !> displacement lines (the mechanical reader's). One card may hold both,
  !> as CalculiX's ring3 does; the cursor is not moved.
  !> Arguments: p the parser at the keyword line; has_heat, has_mech out.
  subroutine boundary_lines(p, has_heat, has_mech)
    type(parser_t), intent(in) :: p
    logical, intent(out) :: has_heat, has_mech
    integer :: i
    has_heat = .false.
    has_mech = .false.
    do i = p%i + 1, p%deck%n
      if (is_keyword(p%deck%lines(i)%text)) return
      if (is_heat_line(p%deck%lines(i)%text)) then
        has_heat = .true.
      else
        has_mech = .true.
      end if
    end do
  end subroutine boundary_lines

  !> Purpose: whether a *BOUNDARY data line prescribes the temperature: its
  !> dof range starts at 11 or at 0, which CalculiX also reads as the
  !> temperature (bounadd.f maps deck dofs 0 and 11 to its internal dof 0).
  !> A line the mechanical reader cannot read as dofs is not one (it says why).
  !> Arguments: text the data line.
  logical function is_heat_line(text)
    character(len=*), intent(in) :: text
    type(field_t), allocatable :: f(:)
    integer :: n, d1, ios
    is_heat_line = .false.
    call split_fields(text, f, n)
    if (n < 2) return
    if (.not. is_int(f(2)%s)) return
    read(f(2)%s, *, iostat=ios) d1
    if (ios /= 0) return
    is_heat_line = d1 == 0 .or. d1 == dof_temperature
  end function is_heat_line

  !> Purpose: *BOUNDARY on dof 11: prescribed temperatures, `node or nset,
  !> 11[, 11[, temperature]]` (model data: held from the start; in a step:
  !> from that step on); OP=NEW drops those of earlier steps; AMPLITUDE=.
  !> Dof 0 is the temperature too (CalculiX's internal number, which its
  !> decks use: ring3). Reads the card's temperature lines (is_heat_line)
  !> and passes over its displacement lines, the mechanical reader's.
  subroutine read_heat_boundary(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    type(bc_t), allocatable :: new(:)
    integer, allocatable :: nodes(:)
    integer :: n, d1, d2, amp, iset
    real(dp) :: v
    call allow_params(p, kw, 'OP,AMPLITUDE,TYPE')
    if (p%step > 0) then
      if (.not. m%steps(p%step)%heat) call err(p, 'dof 11 is the temperature (*BOUNDARY on it is a ' // &
          'prescribed temperature): it belongs to a *HEAT TRANSFER step (before it in the step; docs/heat.md); ' // &
          'heat transfer in a mechanical step (*COUPLED TEMPERATURE-DISPLACEMENT) is not implemented')
    end if
    amp = heat_options(p, m, kw, 'BOUNDARY')
    if (p%step == 0 .and. amp > 0) call err(p, 'AMPLITUDE= is only allowed inside *STEP')
    do while (next_data(p))
      if (.not. is_heat_line(line_text(p))) cycle
      if (p%step == 0 .and. .not. has_heat_step(p)) call err(p, 'dof 11 is the temperature ' // &
          '(*BOUNDARY on it is a prescribed temperature; on dof 0 too, as in CalculiX): it belongs to a *HEAT TRANSFER step ' // &
          'or a *COUPLED TEMPERATURE-DISPLACEMENT one, and this deck has neither (the temperatures of a ' // &
          'thermal strain are given by *TEMPERATURE)')
      call split_fields(line_text(p), f, n)
      if (n < 2 .or. n > 4) call err(p, '*BOUNDARY data line needs: node or node set, 11[, 11[, temperature]]')
      call target_nodes(p, m, f(1)%s, 'data line', nodes, iset)
      d1 = get_int(p, f(2), 'first dof')
      d2 = d1
      if (n >= 3) then
        if (len(f(3)%s) > 0) d2 = get_int(p, f(3), 'last dof')
      end if
      if (d1 == 0) d1 = dof_temperature
      if (d2 == 0) d2 = dof_temperature
      if (d1 /= dof_temperature .or. d2 /= dof_temperature) call err(p, 'a *BOUNDARY line on the ' // &
          'temperature prescribes dof 11 (or 0, as CalculiX) only: 11, 11, temperature; the displacements ' // &
          'go on lines of their own')
      v = 0.0_dp
      if (n == 4) v = get_real(p, f(4), 'temperature')
      allocate(new(size(nodes)))
      new%node = nodes
      new%dof = dof_temperature
      new%set = iset
      new%amp = amp
      new%value = v
      if (p%step == 0) then
        m%model_bcs = [m%model_bcs(1:p%nmbc), new]
        p%nmbc = p%nmbc + size(new)
      else
        if (.not. allocated(m%steps(p%step)%tbcs)) allocate(m%steps(p%step)%tbcs(0))
        m%steps(p%step)%tbcs = [m%steps(p%step)%tbcs, new]
      end if
      deallocate(new)
    end do
  end subroutine read_heat_boundary

  !> Purpose: whether the deck has a step with a temperature field (a
  !> *HEAT TRANSFER or *COUPLED TEMPERATURE-DISPLACEMENT card anywhere),
  !> for a prescribed temperature in the model data, read before the steps.
  !> Arguments: p the parser (its deck's lines are scanned, not moved).
  logical function has_heat_step(p)
    type(parser_t), intent(in) :: p
    character(len=:), allocatable :: t
    integer :: i
    has_heat_step = .false.
    do i = 1, p%deck%n
      if (.not. is_keyword(p%deck%lines(i)%text)) cycle
      t = to_upper(p%deck%lines(i)%text)
      t = t(1:min(len(t), 40))
      t = compact(t)
      has_heat_step = index(t, '*HEATTRANSFER') == 1 .or. index(t, '*COUPLEDTEMPERATURE') == 1
      if (has_heat_step) return
    end do
  end function has_heat_step

  !> Purpose: text without its blanks (CalculiX ignores them in keywords).
  !> Arguments: t the text.
  pure function compact(t) result(c)
    character(len=*), intent(in) :: t
    character(len=:), allocatable :: c
    integer :: k
    c = ''
    do k = 1, len(t)
      if (t(k:k) /= ' ') c = c // t(k:k)
    end do
  end function compact

  !> Purpose: *CFLUX: concentrated heat fluxes, `node or nset, 11, flux`
  !> (into the body; in axisymmetry over the whole circumference).
  subroutine read_cflux(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    integer, allocatable :: nodes(:)
    integer :: n, k, amp, iset
    real(dp) :: v
    call allow_params(p, kw, 'OP,AMPLITUDE')
    amp = heat_options(p, m, kw, 'CFLUX')
    if (.not. allocated(m%steps(p%step)%cfluxes)) allocate(m%steps(p%step)%cfluxes(0))
    do while (next_data(p))
      call split_fields(line_text(p), f, n)
      if (n /= 3) call err(p, '*CFLUX data line needs: node or node set, 11, flux')
      call target_nodes(p, m, f(1)%s, 'data line', nodes, iset)
      if (get_int(p, f(2), 'dof') /= dof_temperature) call err(p, '*CFLUX acts on dof 11 (the temperature)')
      v = get_real(p, f(3), 'heat flux')
      m%steps(p%step)%cfluxes = [m%steps(p%step)%cfluxes, &
        [(cload_t(node=nodes(k), dof=dof_temperature, amp=amp, value=v, src=src_t(p%i)), k = 1, size(nodes))]]
    end do
  end subroutine read_cflux

  !> Purpose: *DFLUX: distributed heat fluxes, `element or elset, label,
  !> flux`: label S1..S4 a flux per unit area into face k, BF a heat
  !> source per unit volume.
  subroutine read_dflux(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    integer, allocatable :: elems(:)
    integer :: n, k, amp, face
    character(len=:), allocatable :: label
    real(dp) :: v
    call allow_params(p, kw, 'OP,AMPLITUDE')
    amp = heat_options(p, m, kw, 'DFLUX')
    if (.not. allocated(m%steps(p%step)%dfluxes)) allocate(m%steps(p%step)%dfluxes(0))
    do while (next_data(p))
      call split_fields(line_text(p), f, n)
      if (n /= 3) call err(p, '*DFLUX data line needs: element or element set, S1..S4 or BF, flux')
      call target_elements(p, m, f(1)%s, elems)
      label = to_upper(f(2)%s)
      if (label == 'BF') then
        face = heat_bf
      else
        face = face_number(p, m, elems, label, 'S')
      end if
      v = get_real(p, f(3), 'heat flux')
      m%steps(p%step)%dfluxes = [m%steps(p%step)%dfluxes, &
        [(heat_load_t(elem=elems(k), face=face, amp=amp, value=v), k = 1, size(elems))]]
    end do
  end subroutine read_dflux

  !> Purpose: *FILM: film conditions, `element or elset, Fk, sink
  !> temperature, film coefficient h` (the flux h (T_sink - T) into face
  !> k); AMPLITUDE= scales the sink temperature.
  subroutine read_film(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    integer, allocatable :: elems(:)
    integer :: n, k, amp, face
    real(dp) :: sink, h
    call allow_params(p, kw, 'OP,AMPLITUDE')
    amp = heat_options(p, m, kw, 'FILM')
    if (.not. allocated(m%steps(p%step)%films)) allocate(m%steps(p%step)%films(0))
    do while (next_data(p))
      call split_fields(line_text(p), f, n)
      if (n /= 4) call err(p, '*FILM data line needs: element or element set, F1..F4, sink temperature, ' // &
                          'film coefficient')
      call target_elements(p, m, f(1)%s, elems)
      face = face_number(p, m, elems, to_upper(f(2)%s), 'F')
      sink = get_real(p, f(3), 'sink temperature')
      h = get_real(p, f(4), 'film coefficient')
      if (h < 0.0_dp) call err(p, 'the film coefficient must not be negative')
      m%steps(p%step)%films = [m%steps(p%step)%films, &
        [(heat_load_t(elem=elems(k), face=face, amp=amp, value=h, sink=sink), k = 1, size(elems))]]
    end do
  end subroutine read_film

  !> Purpose: *RADIATE: radiation to the environment, `element or elset,
  !> Rk, sink temperature, emissivity` (the flux eps sigma ((T_sink -
  !> T_0)^4 - (T - T_0)^4) into face k, sigma and T_0 of *PHYSICAL
  !> CONSTANTS); AMPLITUDE= scales the sink temperature. Cavity radiation
  !> (RkCR) and user radiation (RkNU) stop at their line.
  subroutine read_radiate(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    integer, allocatable :: elems(:)
    integer :: n, k, amp, face
    character(len=:), allocatable :: label
    real(dp) :: sink, emissivity
    if (has_param(kw, 'CAVITY') .or. has_param(kw, 'ENVNODE') .or. has_param(kw, 'RADIATION AMPLITUDE')) &
      call err(p, 'cavity radiation, an environment node and RADIATION AMPLITUDE= of *RADIATE are not ' // &
               'implemented: cfe2d radiates to a sink temperature (docs/heat.md)')
    call allow_params(p, kw, 'OP,AMPLITUDE')
    amp = heat_options(p, m, kw, 'RADIATE')
    if (.not. allocated(m%steps(p%step)%radiates)) allocate(m%steps(p%step)%radiates(0))
    do while (next_data(p))
      call split_fields(line_text(p), f, n)
      if (n /= 4) call err(p, '*RADIATE data line needs: element or element set, R1..R4, sink temperature, ' // &
                          'emissivity')
      call target_elements(p, m, f(1)%s, elems)
      label = to_upper(f(2)%s)
      if (len(label) > 2) then
        if (label(3:) == 'CR') call err(p, 'cavity radiation (' // label // ') is not implemented: cfe2d ' // &
          'radiates to the environment (R1..R4 with a sink temperature; docs/heat.md)')
        if (label(3:) == 'NU') call err(p, 'a user radiation subroutine (' // label // ') is not implemented')
      end if
      face = face_number(p, m, elems, label, 'R')
      sink = get_real(p, f(3), 'sink temperature')
      emissivity = get_real(p, f(4), 'emissivity')
      if (emissivity < 0.0_dp .or. emissivity > 1.0_dp) call err(p, 'the emissivity must lie in 0..1')
      m%steps(p%step)%radiates = [m%steps(p%step)%radiates, &
        [(heat_load_t(elem=elems(k), face=face, amp=amp, value=emissivity, sink=sink), k = 1, size(elems))]]
    end do
  end subroutine read_radiate

  !> Purpose: *PHYSICAL CONSTANTS, ABSOLUTE ZERO=, STEFAN BOLTZMANN= (the
  !> constants of *RADIATE; NEWTON GRAVITY= is read and not used). In a
  !> deck without *HEAT TRANSFER the card is not used and warns so.
  subroutine read_physical_constants(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(keyword_t) :: other
    type(field_t), allocatable :: f(:)
    integer :: i, n
    logical :: heat
    heat = .false.
    do i = 1, p%deck%n
      if (.not. is_keyword(p%deck%lines(i)%text)) cycle
      call parse_keyword(p%deck%lines(i)%text, other)
      heat = heat .or. other%name == 'HEAT TRANSFER' .or. other%name == 'HEATTRANSFER'
    end do
    if (.not. heat) then
      call deck_warning(p%deck, p%i, '*' // kw%name // ' is not implemented in cfe2d and is ignored')
      do while (next_data(p))
      end do
      return
    end if
    ! CalculiX drops the blanks of a keyword line: both spellings
    call allow_params(p, kw, 'ABSOLUTE ZERO,ABSOLUTEZERO,STEFAN BOLTZMANN,STEFANBOLTZMANN,NEWTON GRAVITY,' // &
                      'NEWTONGRAVITY')
    do i = 1, kw%np
      if (.not. allocated(kw%pvalue(i)%s)) cycle
      call split_fields(kw%pvalue(i)%s, f, n)
      if (n < 1) cycle
      select case (kw%pname(i)%s)
      case ('ABSOLUTE ZERO', 'ABSOLUTEZERO')
        m%absolute_zero = get_real(p, f(1), 'ABSOLUTE ZERO')
        m%has_absolute_zero = .true.
      case ('STEFAN BOLTZMANN', 'STEFANBOLTZMANN')
        m%stefan_boltzmann = get_real(p, f(1), 'STEFAN BOLTZMANN')
        if (m%stefan_boltzmann <= 0.0_dp) call err(p, 'STEFAN BOLTZMANN must be positive')
        m%has_stefan_boltzmann = .true.
      end select
    end do
    call no_data(p, kw)
  end subroutine read_physical_constants

  !> Purpose: the cards of heat transfer cfe2d does not have: stop with
  !> the reason at the card's line.
  subroutine reject_heat_card(p, kw)
    type(parser_t), intent(inout) :: p
    type(keyword_t), intent(in) :: kw
    select case (kw%name)
    case ('VIEWFACTOR', 'RADIATION VIEWFACTOR', 'CAVITY DEFINITION')
      call err(p, '*' // kw%name // ' is cavity radiation, which is not implemented: cfe2d''s heat transfer ' // &
               'radiates to the environment (*RADIATE Rk with a sink temperature; docs/heat.md)')
    case default
      call err(p, '*' // kw%name // ' is not implemented: cfe2d''s heat transfer is conduction with fluxes, ' // &
               'films and radiation to the environment (docs/heat.md), without fluid networks or cavity radiation')
    end select
  end subroutine reject_heat_card

  !> OP= (NEW: the card's loads of earlier steps dropped) and AMPLITUDE=
  !> of a heat card; a step's card must be in a *HEAT TRANSFER step.
  integer function heat_options(p, m, kw, card) result(amp)
    type(parser_t), intent(in) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    character(len=*), intent(in) :: card
    character(len=:), allocatable :: op
    op = 'MOD'
    if (has_param(kw, 'OP')) op = to_upper(param_value(kw, 'OP'))
    if (op /= 'MOD' .and. op /= 'NEW') call err(p, 'OP must be MOD or NEW')
    if (p%step > 0) then
      if (.not. m%steps(p%step)%heat) call err(p, '*' // card // ' needs a *HEAT TRANSFER step (before it in ' // &
          'the step); *COUPLED TEMPERATURE-DISPLACEMENT is not implemented')
      select case (card)
      case ('BOUNDARY'); m%steps(p%step)%new_tbcs = m%steps(p%step)%new_tbcs .or. op == 'NEW'
      case ('CFLUX'); m%steps(p%step)%new_cfluxes = m%steps(p%step)%new_cfluxes .or. op == 'NEW'
      case ('DFLUX'); m%steps(p%step)%new_dfluxes = m%steps(p%step)%new_dfluxes .or. op == 'NEW'
      case ('FILM'); m%steps(p%step)%new_films = m%steps(p%step)%new_films .or. op == 'NEW'
      case ('RADIATE'); m%steps(p%step)%new_radiates = m%steps(p%step)%new_radiates .or. op == 'NEW'
      end select
    else if (op == 'NEW') then
      call err(p, 'OP=NEW is only allowed inside *STEP')
    end if
    amp = amplitude_param(p, m, kw)
  end function heat_options

  !> The elements a data line's first field names (an element or a set).
  subroutine target_elements(p, m, s, elems)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    character(len=*), intent(in) :: s
    integer, allocatable, intent(out) :: elems(:)
    type(field_t) :: f
    integer :: es
    if (is_label(s)) then
      f%s = s
      elems = [elem_ref(p, m, f, 'element')]
    else
      if (len(s) == 0) call err(p, 'missing element or element set')
      es = need_elset(p, m, s)
      elems = m%elsets(es)%items
      call warn_empty_set(p, size(elems), 'element set', m%elsets(es)%name, 'data line')
    end if
  end subroutine target_elements

  !> Face k of label `letter`k (S1.. or F1..), which every element of
  !> elems must have.
  integer function face_number(p, m, elems, label, letter) result(k)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    integer, intent(in) :: elems(:)
    character(len=*), intent(in) :: label, letter
    integer :: j
    k = 0
    if (len(label) == 2) then
      if (label(1:1) == letter) k = index('1234', label(2:2))
    end if
    if (k == 0) call err(p, 'load label ' // label // ' is not one of ' // letter // '1..' // letter // '4' // &
                         trim(merge(' or BF', '      ', letter == 'S')))
    do j = 1, size(elems)
      if (k > catalogue(m%etype(elems(j)))%nedges .or. catalogue(m%etype(elems(j)))%nodes < 3) &
        call err(p, 'element ' // itoa(m%elem_id(elems(j))) // ' (' // trim(catalogue(m%etype(elems(j)))%name) // &
                 ') has no face ' // label)
    end do
  end function face_number

  !> Purpose: once the deck is read: a deck with a *HEAT TRANSFER step has
  !> only such steps, and every element with a section has a material
  !> with *CONDUCTIVITY (and *DENSITY and *SPECIFIC HEAT in a transient
  !> step); a deck without one names no DC2D*/DCAX* element.
  subroutine check_heat_model(p, m)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(in) :: m
    integer :: s, e
    logical :: transient
    if (m%heat) then
      do s = 1, size(m%steps)
        if (.not. allocated(m%steps(s)%radiates)) cycle
        if (size(m%steps(s)%radiates) == 0 .or. (m%has_absolute_zero .and. m%has_stefan_boltzmann)) cycle
        p%i = m%steps(s)%src%line
        call err(p, '*RADIATE in this step needs *PHYSICAL CONSTANTS with ABSOLUTE ZERO= and STEFAN BOLTZMANN= ' // &
                 '(model data)')
      end do
    end if
    if (.not. m%heat) then
      do e = 1, m%ne
        if (catalogue(m%etype(e))%name(1:2) /= 'DC') cycle
        p%i = m%elem_src(e)%line
        call err(p, 'element type ' // trim(catalogue(m%etype(e))%name) // ' is a heat transfer element: ' // &
                 'it needs *HEAT TRANSFER steps')
      end do
      return
    end if
    transient = .false.
    do s = 1, size(m%steps)
      p%i = m%steps(s)%src%line
      if (.not. m%steps(s)%heat) call err(p, 'a step without *HEAT TRANSFER in a heat transfer deck: ' // &
          'mechanical and heat transfer steps in one deck (*COUPLED TEMPERATURE-DISPLACEMENT) are not implemented')
      transient = transient .or. .not. m%steps(s)%steady
    end do
    do s = 1, size(m%sections)
      if (m%sections(s)%spring .or. m%sections(s)%point_mass .or. m%sections(s)%material == 0) cycle
      associate(mat => m%materials(m%sections(s)%material))
        p%i = mat%src%line
        if (.not. mat%has_conductivity) call err(p, 'material ' // trim(mat%name) // ' has no *CONDUCTIVITY ' // &
                                                 '(heat transfer)')
        if (transient .and. .not. (mat%has_specific_heat .and. mat%has_density)) call err(p, 'material ' // &
          trim(mat%name) // ' needs *DENSITY and *SPECIFIC HEAT for a transient *HEAT TRANSFER step')
      end associate
    end do
  end subroutine check_heat_model
end module deck_heat_cards