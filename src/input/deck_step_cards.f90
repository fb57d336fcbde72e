!> Step and load cards: *AMPLITUDE, *BOUNDARY, *STEP, *STATIC, *CLOAD,
!> the output requests (*NODE PRINT, *EL PRINT, *NODE FILE, *EL FILE) and
!> *END STEP; the temperatures: *INITIAL CONDITIONS, TYPE=TEMPERATURE and
!> *TEMPERATURE.
submodule (deck_parser) deck_step_cards
  use kinds, only: dp
  use strings, only: split_fields, to_upper, field_t, itoa, rtoa
  use deck_input, only: param_value, has_param, deck_warning, is_keyword
  use deck_cursor, only: max_increments, read_time_line, line_text, err, next_data, require_data, no_data, allow_params, &
                         name_param, check_name_length, get_real, get_int, param_int, is_int, &
                         need_elset, required_param, warn_empty_set, deck_dof, dof_moves, dof_zero, &
                         note_named, rotation_hint, nset_index, elset_index, time_points_t, target_nodes, amplitude_param
  use model, only: amplitude_t, step_t, bc_t, cload_t, request_t, temp_t, src_t, amp_step_time, amp_total_time, &
                   find_name, node_label, controls_t, law_elastic
  use growable, only: append
  use model_growth, only: grow
  implicit none

  !> CalculiX's dof of the temperature (heat transfer and coupled analyses).
  integer, parameter :: dof_temperature = 11
  character(len=*), parameter :: dof_range_message = 'dofs must satisfy 1 <= first <= last <= 2 in 2D ' // &
    '(dof 3, out of the plane, may only be held at zero)'

contains

  !> Purpose: *AMPLITUDE, NAME=: a tabular amplitude, `t1, a1, t2, a2, ...`
  !> over any number of data lines, times strictly increasing; or
  !> DEFINITION=PERIODIC, Abaqus' Fourier series (read_periodic).
  module subroutine read_amplitude(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    real(dp), allocatable :: t(:), a(:)
    character(len=:), allocatable :: name, tm, def
    integer :: n, k, np, na
    call allow_params(p, kw, 'NAME,TIME,DEFINITION,VALUE')
    name = name_param(p, kw, 'NAME')
    if (find_name(m%amplitudes(1:p%namp)%name, name) > 0) call err(p, 'duplicate amplitude ' // name)
    def = 'TABULAR'
    if (has_param(kw, 'DEFINITION')) def = to_upper(param_value(kw, 'DEFINITION'))
    if (def /= 'TABULAR' .and. def /= 'PERIODIC') &
      call err(p, 'only DEFINITION=TABULAR and PERIODIC are implemented')
    if (has_param(kw, 'VALUE')) then
      if (to_upper(param_value(kw, 'VALUE')) /= 'ABSOLUTE') call err(p, 'only VALUE=ABSOLUTE is implemented')
    end if
    call grow(m%amplitudes, p%namp + 1)
    p%namp = p%namp + 1
    m%amplitudes(p%namp) = amplitude_t(name=name, time=amp_step_time)
    if (has_param(kw, 'TIME')) then
      tm = to_upper(param_value(kw, 'TIME'))
      if (tm == 'TOTAL TIME') then
        m%amplitudes(p%namp)%time = amp_total_time
      else if (tm /= 'STEP TIME') then
        call err(p, 'TIME must be STEP TIME or TOTAL TIME')
      end if
    end if
    if (def == 'PERIODIC') then
      call read_periodic(p, m%amplitudes(p%namp))
      return
    end if
    allocate(t(0), a(0))
    np = 0
    na = 0
    do while (next_data(p))
      call split_fields(line_text(p), f, n)
      if (mod(n, 2) /= 0) call err(p, '*AMPLITUDE data come in pairs: time, value')
      do k = 1, n, 2
        call append(t, np, get_real(p, f(k), 'time'))
        call append(a, na, get_real(p, f(k + 1), 'amplitude value'))
        if (np > 1) then
          if (t(np) <= t(np - 1)) call err(p, 'amplitude times must increase')
        end if
      end do
    end do
    if (np == 0) call err(p, 'missing data line (time, value pairs)')
    m%amplitudes(p%namp)%t = t(1:np)
    m%amplitudes(p%namp)%a = a(1:np)
  end subroutine read_amplitude

  !> Purpose: the data of *AMPLITUDE, DEFINITION=PERIODIC as Abaqus writes
  !> them: `N, omega, t0, A0` (terms, circular frequency, starting time,
  !> constant), then `A1, B1, A2, B2, ...` (N pairs over any number of
  !> lines); the amplitude is model's amplitude_at.
  !> Arguments: p the parser (on the card); a the amplitude, completed.
  subroutine read_periodic(p, a)
    type(parser_t), intent(inout) :: p
    type(amplitude_t), intent(inout) :: a
    type(field_t), allocatable :: f(:)
    real(dp), allocatable :: c(:)
    integer :: n, k, nt, nc
    call require_data(p, 'N, omega, t0, A0 of a periodic amplitude')
    call split_fields(line_text(p), f, n)
    if (n /= 4) call err(p, '*AMPLITUDE, DEFINITION=PERIODIC first data line needs: N (terms), ' // &
                         'omega (circular frequency), t0 (starting time), A0 (constant)')
    nt = get_int(p, f(1), 'number of terms N')
    if (nt < 1 .or. nt > 10000) call err(p, 'the number of terms N must be between 1 and 10000')
    a%periodic = .true.
    a%omega = get_real(p, f(2), 'circular frequency omega')
    if (.not. a%omega > 0.0_dp) call err(p, 'the circular frequency omega must be positive')
    a%t0 = get_real(p, f(3), 'starting time t0')
    a%a0 = get_real(p, f(4), 'constant A0')
    allocate(c(0))
    nc = 0
    do while (next_data(p))
      call split_fields(line_text(p), f, n)
      do k = 1, n
        call append(c, nc, get_real(p, f(k), 'Fourier coefficient'))
      end do
    end do
    if (nc /= 2 * nt) call err(p, 'a periodic amplitude of ' // itoa(nt) // ' terms needs ' // itoa(2 * nt) // &
                               ' coefficients A1, B1, A2, B2, ... after its first data line; found ' // itoa(nc))
    a%ca = c(1:nc:2)
    a%cb = c(2:nc:2)
  end subroutine read_periodic

  !> Purpose: *BOUNDARY: prescribed displacements, `node or nset, first
  !> dof[, last dof[, value]]` or a named condition (ENCASTRE, PINNED,
  !> XSYMM, YSYMM). Model data outside *STEP, history data inside. Each
  !> dof is what deck_dof makes of it at each node: dof 6 of a reference
  !> node of *RIGID BODY or *COUPLING (or dof 3 of a ROT NODE) is its
  !> rotation; a dof a 2D model does not have may only be held at zero.
  !> The card's temperature lines (is_heat_line: dof 11 or 0) are passed
  !> over: read_heat_boundary reads them (read_boundary_card).
  module subroutine read_boundary(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    integer, allocatable :: nodes(:), dofs(:)
    integer :: n, k, j, iset, amp, nnew, kind, ra, rd
    real(dp) :: v
    logical :: named
    character(len=:), allocatable :: op
    call allow_params(p, kw, 'OP,AMPLITUDE,TYPE')
    if (has_param(kw, 'TYPE')) then
      if (to_upper(param_value(kw, 'TYPE')) /= 'DISPLACEMENT') call err(p, 'only TYPE=DISPLACEMENT is implemented')
    end if
    op = op_param(p, kw)
    if (p%step == 0 .and. (op == 'NEW' .or. has_param(kw, 'AMPLITUDE'))) &
      call err(p, 'OP=NEW and AMPLITUDE= are only allowed inside *STEP')
    amp = amplitude_param(p, m, kw)
    if (p%step > 0 .and. op == 'NEW') m%steps(p%step)%new_bcs = .true.
    nnew = 0
    do while (next_data(p))
      if (is_heat_line(line_text(p))) cycle
      call split_fields(line_text(p), f, n)
      if (n > 4) call err(p, '*BOUNDARY data line needs: node or set, first dof[, last dof[, value]]')
      call target_nodes(p, m, f(1)%s, kw%name, nodes, iset)
      call boundary_dofs(p, f, n, dofs, named, v)
      do k = 1, size(nodes)
        call note_named(p, nodes(k))
        do j = 1, size(dofs)
          call deck_dof(p, nodes(k), dofs(j), kind, ra, rd)
          select case (kind)
          case (dof_moves)
            call add_bc(p, m, bc_t(node=ra, dof=rd, set=iset, amp=amp, value=v))
          case (dof_zero)
            ! a 2D model has no such displacement: holding it at zero (as
            ! CalculiX decks do for their 3D springs and expanded
            ! elements) changes nothing
            if (v /= 0.0_dp) call err(p, zero_dof_message(p, m, nodes(k), dofs(j), 'held at zero'))
          case default
            ! a named condition holds the dofs the node has
            if (.not. named) call err(p, dof_range_message // rotation_hint(dofs(j)))
          end select
        end do
      end do
      nnew = nnew + 1
    end do
    if (nnew == 0) call err(p, 'missing data line (node or set, first dof[, last dof[, value]])')
  end subroutine read_boundary

  !> The dofs and value of a *BOUNDARY data line (fields f(2:n)): a range
  !> of dofs 1..6, or the dofs of a named condition (named), which Abaqus
  !> gives with the rotations a node may have: ENCASTRE all, PINNED the
  !> translations, XSYMM u1 and the rotations about y and z, YSYMM u2 and
  !> those about x and z.
  subroutine boundary_dofs(p, f, n, dofs, named, v)
    type(parser_t), intent(in) :: p
    type(field_t), intent(in) :: f(:)
    integer, intent(in) :: n
    integer, allocatable, intent(out) :: dofs(:)
    logical, intent(out) :: named
    real(dp), intent(out) :: v
    integer :: d1, d2, d
    v = 0.0_dp
    named = n >= 2 .and. .not. is_int(f(min(n, 2))%s)
    if (named) then
      ! Abaqus named conditions.
      if (n > 2) call err(p, 'a named boundary condition takes no further fields')
      select case (to_upper(f(2)%s))
      case ('ENCASTRE'); dofs = [1, 2, 3, 4, 5, 6]
      case ('PINNED'); dofs = [1, 2, 3]
      case ('XSYMM'); dofs = [1, 5, 6]
      case ('YSYMM'); dofs = [2, 4, 6]
      case default; call err(p, '"' // f(2)%s // '" is not a dof number or a known condition')
      end select
      return
    end if
    if (n < 2) call err(p, 'missing first dof')
    d1 = get_int(p, f(2), 'first dof')
    d2 = d1
    if (n >= 3) then
      if (len(f(3)%s) > 0) d2 = get_int(p, f(3), 'last dof')
    end if
    if (n == 4) v = get_real(p, f(4), 'prescribed value')
    if (d1 <= dof_temperature .and. dof_temperature <= d2) call err(p, heat_transfer_dof('*BOUNDARY', &
        'a prescribed temperature'))
    if (d1 < 1 .or. d2 > 6 .or. d2 < d1) call err(p, dof_range_message // rotation_hint(d2))
    dofs = [(d, d = d1, d2)]
  end subroutine boundary_dofs

  !> Purpose: the message for a non-zero value (`what`: held at, loaded)
  !> on dof d of node a, which a 2D model does not have (dof_zero).
  function zero_dof_message(p, m, a, d, what) result(msg)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    integer, intent(in) :: a, d
    character(len=*), intent(in) :: what
    character(len=:), allocatable :: msg
    logical :: rot
    rot = .false.
    if (allocated(p%is_rot_node)) then
      if (a <= size(p%is_rot_node)) rot = p%is_rot_node(a)
    end if
    if (rot) then
      msg = 'dof ' // itoa(d) // ' of ROT NODE ' // node_label(m, a) // ' is its rotation about the ' // &
            merge('x', 'y', d == 1) // ' axis, out of the plane of a 2D model: it may only be ' // what // &
            ' (dof 3 is the rotation in the plane)'
    else if (d == 3) then
      msg = dof_range_message
    else
      msg = 'dof ' // itoa(d) // ' of node ' // node_label(m, a) // ' is a rotation about the ' // &
            merge('x', 'y', d == 4) // ' axis, out of the plane of a 2D model: it may only be ' // what // &
            ' (dof 6 is the rotation in the plane)'
    end if
  end function zero_dof_message

  !> Purpose: the message for dof 11 (CalculiX's temperature dof) on `card`,
  !> which would be `what` in a heat transfer analysis: that belongs to a
  !> *HEAT TRANSFER step (deck_heat_cards), not a displacement dof.
  pure function heat_transfer_dof(card, what) result(msg)
    character(len=*), intent(in) :: card, what
    character(len=:), allocatable :: msg
    msg = 'dof 11 is the temperature (' // card // ' on it is ' // what // '): it belongs to a *HEAT ' // &
          'TRANSFER step (docs/heat.md: *BOUNDARY on dof 11, *CFLUX); heat transfer in a mechanical step ' // &
          '(*COUPLED TEMPERATURE-DISPLACEMENT) is not implemented (the temperatures of a thermal strain are ' // &
          'given by *TEMPERATURE)'
  end function heat_transfer_dof

  !> One prescribed dof: to the model outside a step, to the step inside.
  subroutine add_bc(p, m, bc)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(bc_t), intent(in) :: bc
    if (p%step == 0) then
      call grow(m%model_bcs, p%nmbc + 1)
      p%nmbc = p%nmbc + 1
      m%model_bcs(p%nmbc) = bc
    else
      call grow(m%steps(p%step)%bcs, p%nbc + 1)
      p%nbc = p%nbc + 1
      m%steps(p%step)%bcs(p%nbc) = bc
    end if
  end subroutine add_bc

  !> OP=MOD (default) or OP=NEW.
  function op_param(p, kw) result(op)
    type(parser_t), intent(in) :: p
    type(keyword_t), intent(in) :: kw
    character(len=:), allocatable :: op
    op = 'MOD'
    if (has_param(kw, 'OP')) op = to_upper(param_value(kw, 'OP'))
    if (op /= 'MOD' .and. op /= 'NEW') call err(p, 'OP must be MOD or NEW')
  end function op_param

  !> Purpose: *CLOAD: concentrated forces, `node or nset, dof, value`.
  !> Any finite value is accepted (huge loads are the analysis' concern).
  !> Dof 6 of a reference node of *RIGID BODY or *COUPLING (dof 3 of a
  !> ROT NODE) is a moment about z (deck_dof).
  module subroutine read_cload(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    integer, allocatable :: nodes(:)
    integer :: n, k, d, iset, amp, nnew, kind, ra, rd
    real(dp) :: v
    call allow_params(p, kw, 'OP,AMPLITUDE')
    if (op_param(p, kw) == 'NEW') m%steps(p%step)%new_loads = .true.
    amp = amplitude_param(p, m, kw)
    nnew = 0
    do while (next_data(p))
      call split_fields(line_text(p), f, n)
      if (n /= 3) call err(p, '*CLOAD data line needs: node or set, dof, value')
      call target_nodes(p, m, f(1)%s, kw%name, nodes, iset)
      d = get_int(p, f(2), 'dof')
      if (d == dof_temperature) call err(p, heat_transfer_dof('*CLOAD', 'a concentrated heat flux'))
      if (d < 1 .or. d > 6) call err(p, 'dof must be 1 or 2 in 2D' // rotation_hint(d))
      v = get_real(p, f(3), 'load value')
      call grow(m%steps(p%step)%loads, p%nload + size(nodes))
      do k = 1, size(nodes)
        call note_named(p, nodes(k))
        call deck_dof(p, nodes(k), d, kind, ra, rd)
        if (kind == dof_zero .and. d /= 3) &
          call err(p, zero_dof_message(p, m, nodes(k), d, 'zero; nothing carries a load on it'))
        if (kind /= dof_moves) call err(p, 'dof must be 1 or 2 in 2D' // rotation_hint(d))
        m%steps(p%step)%loads(p%nload + k) = cload_t(node=ra, dof=rd, amp=amp, value=v, src=src_t(p%i))
      end do
      p%nload = p%nload + size(nodes)
      nnew = nnew + 1
    end do
    if (nnew == 0) call err(p, 'missing data line (node or set, dof, value)')
  end subroutine read_cload

  !> Purpose: *INITIAL CONDITIONS, TYPE=TEMPERATURE: the temperatures of
  !> the reference (strain-free) state, `node or nset, temperature`;
  !> nodes not named start at 0. Other types are not implemented.
  module subroutine read_initial_conditions(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    character(len=:), allocatable :: kind
    call allow_params(p, kw, 'TYPE')
    kind = to_upper(required_param(p, kw, 'TYPE'))
    if (kind /= 'TEMPERATURE') call err(p, '*INITIAL CONDITIONS, TYPE=' // kind // &
      ' is not implemented (only TYPE=TEMPERATURE and TYPE=STRESS)')
    if (.not. allocated(m%initial_temps)) allocate(m%initial_temps(0))
    call read_temperature_lines(p, m, kw%name, 0, .false., m%initial_temps)
  end subroutine read_initial_conditions

  !> Purpose: *TEMPERATURE (in a step): the nodal temperatures at the end
  !> of the step, `node or nset, temperature`, ramped over the step from
  !> where the previous step left them (or following AMPLITUDE=) and held
  !> afterwards; OP=NEW sends the nodes not named back to their initial
  !> temperature.
  module subroutine read_temperature(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    logical :: new
    call allow_params(p, kw, 'OP,AMPLITUDE')
    new = op_param(p, kw) == 'NEW'
    if (new) m%steps(p%step)%new_temps = .true.
    if (.not. allocated(m%steps(p%step)%temps)) allocate(m%steps(p%step)%temps(0))
    call read_temperature_lines(p, m, kw%name, amplitude_param(p, m, kw), new, m%steps(p%step)%temps)
  end subroutine read_temperature

  !> The `node or nset, temperature` lines of a temperature card (`card`),
  !> appended to temps; none is allowed if may_be_empty (OP=NEW alone).
  subroutine read_temperature_lines(p, m, card, amp, may_be_empty, temps)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(in) :: m
    character(len=*), intent(in) :: card
    integer, intent(in) :: amp
    logical, intent(in) :: may_be_empty
    type(temp_t), allocatable, intent(inout) :: temps(:)
    type(field_t), allocatable :: f(:)
    integer, allocatable :: nodes(:)
    integer :: n, k, iset, nnew
    real(dp) :: v
    nnew = 0
    do while (next_data(p))
      call split_fields(line_text(p), f, n)
      if (n /= 2) call err(p, 'temperature data line needs: node or set, temperature')
      call target_nodes(p, m, f(1)%s, card, nodes, iset)
      v = get_real(p, f(2), 'temperature')
      temps = [temps, (temp_t(node=nodes(k), amp=amp, value=v), k = 1, size(nodes))]
      nnew = nnew + 1
    end do
    if (nnew == 0 .and. .not. may_be_empty) call err(p, 'missing data line (node or set, temperature)')
  end subroutine read_temperature_lines

  !> Purpose: *STEP: opens a step (NAME=, INC= the largest number of
  !> increments, 1..max_increments); its cards follow up to *END STEP.
  !> NLGEOM (or NLGEOM=YES) makes the step geometrically nonlinear and
  !> NLGEOM=NO linear; without the parameter a step keeps the previous
  !> step's choice, as CalculiX does.
  module subroutine read_step(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    character(len=:), allocatable :: v
    if (p%step /= 0) call err(p, '*STEP inside a *STEP (missing *END STEP?)')
    call allow_params(p, kw, 'NAME,INC,NLGEOM,PERTURBATION,AMPLITUDE')
    if (has_param(kw, 'NLGEOM')) then
      v = to_upper(param_value(kw, 'NLGEOM'))
      if (v /= '' .and. v /= 'YES' .and. v /= 'NO') call err(p, 'NLGEOM must be YES or NO (or stand alone)')
      p%nlgeom = v /= 'NO'
    end if
    if (has_param(kw, 'PERTURBATION')) call perturbation_step(p, kw)
    if (has_param(kw, 'AMPLITUDE')) then
      if (to_upper(param_value(kw, 'AMPLITUDE')) /= 'RAMP') call err(p, 'only AMPLITUDE=RAMP is implemented on *STEP')
    end if
    call no_data(p, kw)
    call grow(m%steps, p%nsteps + 1)
    p%nsteps = p%nsteps + 1
    p%step = p%nsteps
    p%step_line = p%i
    p%nbc = 0
    p%nload = 0
    p%nreq = 0
    m%steps(p%step) = step_t()
    associate(s => m%steps(p%step))
      call check_name_length(p, param_value(kw, 'NAME'))
      s%name = param_value(kw, 'NAME')
      s%src%line = p%i
      s%period = -1.0_dp
      s%nlgeom = p%nlgeom
      s%controls = p%controls
      allocate(s%bcs(0), s%loads(0), s%requests(0))
      s%max_inc = param_int(p, kw, 'INC', s%max_inc, 1, max_increments)
    end associate
  end subroutine read_step

  !> Purpose: *STEP, PERTURBATION: a linear perturbation step about the
  !> state the steps before it leave. As the first step (CalculiX then
  !> perturbs the unloaded, undeformed model) it is a linear step: read as
  !> one, NLGEOM off for it (CalculiX's answer, measured). After other
  !> steps only a *FREQUENCY step has that base state (a frequency step
  !> always takes the tangent of the state before it, CalculiX's prestressed
  !> modes); a static one is an error.
  subroutine perturbation_step(p, kw)
    type(parser_t), intent(inout) :: p
    type(keyword_t), intent(in) :: kw
    if (p%nsteps > 0) then
      if (frequency_follows(p)) return
      call err(p, 'PERTURBATION after another step (a linear perturbation about the state ' // &
        'it leaves) is implemented for *FREQUENCY only; as the first step it is a linear step')
    end if
    if (has_param(kw, 'NLGEOM')) then
      if (to_upper(param_value(kw, 'NLGEOM')) /= 'NO') call err(p, 'PERTURBATION and NLGEOM exclude each ' // &
                                                                   'other (a perturbation step is linear)')
    end if
    p%nlgeom = .false.
  end subroutine perturbation_step

  !> Is the line after p%i a data line (not a keyword line, not the end)?
  logical function data_follows(p)
    type(parser_t), intent(in) :: p
    data_follows = .false.
    if (p%i + 1 > p%deck%n) return
    data_follows = .not. is_keyword(p%deck%lines(p%i + 1)%text)
  end function data_follows

  !> Is the procedure of the step opened at line p%i a *FREQUENCY (the
  !> first keyword line up to *END STEP that names one)?
  logical function frequency_follows(p)
    type(parser_t), intent(in) :: p
    character(len=:), allocatable :: t
    integer :: k
    frequency_follows = .false.
    do k = p%i + 1, p%deck%n
      if (.not. is_keyword(p%deck%lines(k)%text)) cycle
      t = to_upper(adjustl(p%deck%lines(k)%text))
      if (index(t, '*END STEP') == 1 .or. index(t, '*ENDSTEP') == 1 .or. index(t, '*STATIC') == 1) return
      if (index(t, '*FREQUENCY') == 1) then
        frequency_follows = .true.
        return
      end if
    end do
  end function frequency_follows

  !> Purpose: *STATIC: `initial increment, time period[, min, max]`
  !> (default 1, 1). A linear step runs period / increment equal
  !> increments: both must be positive (and finite, as every real), and the
  !> count, computed in real arithmetic so that it cannot wrap, must not
  !> exceed max_increments nor INC= of *STEP. A nonlinear step (NLGEOM, a
  !> nonlinear material) starts with the initial increment and adapts it
  !> between the minimum and the maximum (CalculiX's defaults when not
  !> given: min(initial, 1e-6 period) and the period), unless DIRECT fixes
  !> it.
  module subroutine read_static(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    real(dp) :: ratio
    call allow_params(p, kw, 'DIRECT,SOLVER,SPLIT TOUCHING')
    associate(s => m%steps(p%step))
      if (s%period > 0.0_dp .or. s%frequency) call err(p, 'second procedure in one step')
      s%direct = has_param(kw, 'DIRECT')
      s%split_touching = has_param(kw, 'SPLIT TOUCHING')
      if (s%direct .and. s%split_touching) call err(p, 'SPLIT TOUCHING splits increments, DIRECT fixes them: ' // &
                                                  'give one of the two')
      call read_time_line(p, '*STATIC', s)
      ! (automatic increments of an NLGEOM step grow from the initial
      ! one: their count is checked as they are made)
      if (s%nlgeom .and. .not. s%direct) return
      ratio = s%period / s%dt
      if (.not. (ratio <= real(max_increments, dp))) call err(p, 'the step would need ' // count_text(ratio) // &
          ' increments (time period / initial increment); at most ' // itoa(max_increments) // ' are allowed')
      if (nint(ratio) > s%max_inc) call err(p, 'the step needs ' // itoa(nint(ratio)) // &
          ' increments, more than INC=' // itoa(s%max_inc) // ' on *STEP allows')
    end associate
  end subroutine read_static

  !> Purpose: *FREQUENCY (CalculiX's card): `number of eigenvalues[,
  !> lower, upper]`, the bounds in cycles/time (empty: not given; lower
  !> is also the shift, CalculiX's (2 pi lower)^2). STORAGE= and SOLVER=
  !> are kept to be reported (cfe2d's eigensolver is its own choice,
  !> docs/keywords.md); GLOBAL= and CYCMPC= (cyclic symmetry) are read
  !> and ignored. A frequency step has no time: its period is zero.
  module subroutine read_frequency(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    integer :: n
    logical :: massive
    call allow_params(p, kw, 'STORAGE,SOLVER,GLOBAL,CYCMPC,MATRIXSTORAGE')
    associate(s => m%steps(p%step))
      if (s%period >= 0.0_dp .or. s%frequency) call err(p, 'second procedure in one step')
      s%frequency = .true.
      s%period = 0.0_dp
      s%dt = 1.0_dp
      s%freq_storage = to_upper(param_value(kw, 'STORAGE'))
      s%freq_solver = to_upper(param_value(kw, 'SOLVER'))
      if (s%freq_storage /= '' .and. s%freq_storage /= 'YES' .and. s%freq_storage /= 'NO') &
        call err(p, 'STORAGE must be YES or NO')
      call require_data(p, 'number of eigenvalues[, lower, upper frequency]')
      call split_fields(line_text(p), f, n)
      if (n > 3) call err(p, '*FREQUENCY data line needs: number of eigenvalues[, lower, upper frequency]')
      s%nev = get_int(p, f(1), 'number of eigenvalues')
      if (s%nev < 1) call err(p, 'the number of eigenvalues must be at least 1')
      if (n >= 2) then
        if (len(f(2)%s) > 0) s%freq_lower = get_real(p, f(2), 'lower frequency')
        if (len(f(2)%s) > 0 .and. s%freq_lower < 0.0_dp) call err(p, 'the lower frequency must not be negative')
      end if
      if (n >= 3) then
        if (len(f(3)%s) > 0) s%freq_upper = get_real(p, f(3), 'upper frequency')
        if (len(f(3)%s) > 0 .and. s%freq_upper <= max(s%freq_lower, 0.0_dp)) &
          call err(p, 'the upper frequency must be positive and above the lower one')
      end if
      if (next_data(p)) call err(p, '*FREQUENCY takes one data line')
      ! (materials are read ahead, sections precede the steps); named at
      ! the keyword line, the one before its data line
      massive = .false.
      if (allocated(m%materials) .and. p%nmat > 0) massive = any(m%materials(1:p%nmat)%has_density)
      if (allocated(m%sections) .and. p%nsec > 0) massive = massive .or. any(m%sections(1:p%nsec)%point_mass)
      if (.not. massive) then
        p%i = p%i - 1
        call err(p, '*FREQUENCY: the model has no mass (a *DENSITY in the materials of its elements, or ' // &
                 'point masses: *MASS on MASS elements)')
      end if
    end associate
  end subroutine read_frequency

  !> Purpose: *CONTROLS: the Newton iteration's constants of nonlinear
  !> steps (CalculiX's, model's controls_t), from this step on until
  !> RESET. PARAMETERS=FIELD: one line `R_n, C_n, q_0, q_u, R_p,
  !> epsilon, C_epsilon, R_l` (q_0 is not used); PARAMETERS=TIME
  !> INCREMENTATION: `I_0, I_R, I_P, I_C, I_L, I_G[, I_S, I_A, I_J, I_T]`
  !> and a second line `D_f, D_C, D_B[, D_A, D_S, D_H, D_D, W_G]` (the
  !> entries CalculiX does not use, or that concern what cfe2d has not,
  !> are read and ignored); empty fields keep their values. The other
  !> PARAMETERS (LINE SEARCH, CONTACT, NETWORK, CFD) are warned about and
  !> ignored.
  module subroutine read_controls(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    character(len=:), allocatable :: what
    call allow_params(p, kw, 'PARAMETERS,RESET')
    if (has_param(kw, 'RESET')) then
      if (has_param(kw, 'PARAMETERS')) call err(p, 'RESET and PARAMETERS= exclude each other')
      call no_data(p, kw)
      p%controls = controls_t()
    else
      what = to_upper(param_value(kw, 'PARAMETERS'))
      select case (what)
      case ('FIELD')
        call field_controls(p)
      case ('TIME INCREMENTATION', 'TIMEINCREMENTATION')
        call time_controls(p)
      case ('LINE SEARCH', 'LINESEARCH', 'CONTACT', 'NETWORK', 'CFD')
        call deck_warning(p%deck, p%i, '*CONTROLS, PARAMETERS=' // what // ' is not implemented and is ignored')
        do while (next_data(p))
        end do
      case ('')
        call err(p, '*CONTROLS needs PARAMETERS= or RESET')
      case default
        call err(p, 'unknown PARAMETERS=' // what // ' on *CONTROLS')
      end select
    end if
    if (p%step > 0) m%steps(p%step)%controls = p%controls
  end subroutine read_controls

  !> Purpose: the data line of *CONTROLS, PARAMETERS=FIELD into p%controls:
  !> `R_n, C_n, q_0, q_u, R_p, epsilon, C_epsilon, R_l` (q_0 not used).
  subroutine field_controls(p)
    type(parser_t), intent(inout) :: p
    type(field_t), allocatable :: f(:)
    integer :: n
    call require_data(p, 'R_n, C_n, q_0, q_u, R_p, epsilon, C_epsilon, R_l')
    call split_fields(line_text(p), f, n)
    if (n > 8) call err(p, '*CONTROLS, PARAMETERS=FIELD data line has at most 8 fields')
    associate(c => p%controls)
      call control_real(p, f, n, 1, c%rn, 'R_n')
      call control_real(p, f, n, 2, c%cn, 'C_n')
      call control_real(p, f, n, 4, c%qu, 'q_u')
      call control_real(p, f, n, 5, c%rp, 'R_p')
      call control_real(p, f, n, 6, c%eps, 'epsilon')
      call control_real(p, f, n, 7, c%ceps, 'C_epsilon')
      call control_real(p, f, n, 8, c%rl, 'R_l')
    end associate
    if (next_data(p)) call err(p, '*CONTROLS, PARAMETERS=FIELD has one data line')
  end subroutine field_controls

  !> Purpose: the data lines of *CONTROLS, PARAMETERS=TIME INCREMENTATION
  !> into p%controls: `I_0, I_R, I_P, I_C, I_L, I_G[, I_S, I_A, I_J, I_T]`
  !> and, optionally, `D_f, D_C, D_B[, D_A, D_S, D_H, D_D, W_G]`.
  subroutine time_controls(p)
    type(parser_t), intent(inout) :: p
    type(field_t), allocatable :: f(:)
    integer :: n
    call require_data(p, 'I_0, I_R, I_P, I_C, I_L, I_G')
    call split_fields(line_text(p), f, n)
    if (n > 10) call err(p, 'the first line of *CONTROLS, PARAMETERS=TIME INCREMENTATION has at most 10 fields')
    associate(c => p%controls)
      call control_int(p, f, n, 1, c%i0, 'I_0')
      call control_int(p, f, n, 2, c%ir, 'I_R')
      call control_int(p, f, n, 3, c%ip, 'I_P')
      call control_int(p, f, n, 4, c%ic, 'I_C')
      call control_int(p, f, n, 5, c%il, 'I_L')
      call control_int(p, f, n, 6, c%ig, 'I_G')
      if (next_data(p)) then
        call split_fields(line_text(p), f, n)
        if (n > 8) call err(p, 'the second line of *CONTROLS, PARAMETERS=TIME INCREMENTATION has at most 8 fields')
        call control_real(p, f, n, 1, c%df, 'D_f')
        call control_real(p, f, n, 2, c%dc, 'D_C')
        call control_real(p, f, n, 3, c%db, 'D_B')
        call control_real(p, f, n, 7, c%dd, 'D_D')
        if (c%df >= 1.0_dp .or. c%dc >= 1.0_dp .or. c%db > 1.0_dp) call err(p, 'the cut-back factors ' // &
          'D_f, D_C and D_B must be below 1')
        if (c%dd < 1.0_dp) call err(p, 'D_D, the growth factor, must be at least 1')
        if (next_data(p)) call err(p, '*CONTROLS, PARAMETERS=TIME INCREMENTATION has two data lines')
      end if
    end associate
  end subroutine time_controls

  !> Purpose: a positive real (q_u: not negative) in field k of the n
  !> fields f of a *CONTROLS line into v, if given (else v is kept).
  subroutine control_real(p, f, n, k, v, name)
    type(parser_t), intent(in) :: p
    type(field_t), intent(in) :: f(:)
    integer, intent(in) :: n, k
    real(dp), intent(inout) :: v
    character(len=*), intent(in) :: name
    if (k > n) return
    if (len(f(k)%s) == 0) return
    v = get_real(p, f(k), name)
    if (.not. v > 0.0_dp .and. name /= 'q_u') call err(p, name // ' must be positive')
    if (v < 0.0_dp) call err(p, name // ' must not be negative')
  end subroutine control_real

  !> Purpose: a positive integer in field k of the n fields f of a
  !> *CONTROLS line into v, if given (else v is kept).
  subroutine control_int(p, f, n, k, v, name)
    type(parser_t), intent(in) :: p
    type(field_t), intent(in) :: f(:)
    integer, intent(in) :: n, k
    integer, intent(inout) :: v
    character(len=*), intent(in) :: name
    if (k > n) return
    if (len(f(k)%s) == 0) return
    v = get_int(p, f(k), name)
    if (v < 1) call err(p, name // ' must be a positive integer')
  end subroutine control_int

  !> A number of increments too large for an integer, as text.
  function count_text(ratio) result(s)
    real(dp), intent(in) :: ratio
    character(len=:), allocatable :: s
    if (ratio > huge(1.0_dp)) then
      s = 'more than 1e308'
    else
      s = rtoa(ratio, 3)
    end if
  end function count_text

  !> Purpose: *NODE PRINT, *EL PRINT, *NODE FILE, *EL FILE (and *CONTACT
  !> PRINT, *CONTACT FILE: contact_request): output of the step, a set
  !> (NSET= or ELSET=, default all) and quantities on the data lines.
  !> As CalculiX: a print card naming an undefined set is ignored with a
  !> warning (a file card writes every node anyway: only its NSET= is
  !> ignored), FREQUENCY= and TIME POINTS= set when the step's output is
  !> written (output_schedule), FREQUENCY=0 turns the card off. Every
  !> parameter and quantity is honoured or warned about at the line.
  module subroutine read_request(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(request_t) :: r
    logical :: keep
    integer :: card, every
    if (kw%name(1:min(7, len(kw%name))) == 'CONTACT') then
      call contact_request(p, m, kw)
      return
    end if
    card = p%i
    r%nodal = kw%name(1:4) == 'NODE'
    r%to_file = index(kw%name, 'FILE') > 0
    if (r%to_file) call file_format(p, m, kw)
    if (r%nodal) then
      call allow_params(p, kw, 'NSET,FREQUENCY,FREQUENCYF,TOTALS,GLOBAL,SUMMARY,OUTPUT,FORMAT,TIME POINTS,' // &
                        'LAST ITERATIONS,CONTACT ELEMENTS')
      call global_param(p, kw, r)
    else
      ! (NSET= on *EL FILE: CalculiX's set of the nodes written)
      call allow_params(p, kw, 'ELSET,FREQUENCY,FREQUENCYF,POSITION,TOTALS,SUMMARY,OUTPUT,GLOBAL,FORMAT,' // &
                        'TIME POINTS,LAST ITERATIONS,CONTACT ELEMENTS,SECTION FORCES' // trim(merge(',NSET', &
                        '     ', r%to_file)))
      call yes_no(p, kw, 'GLOBAL')
    end if
    call ignored_params(p, kw, r)
    keep = request_set(p, m, kw, r)
    if (.not. r%to_file .and. .not. data_follows(p)) then
      ! a print card without quantities: CalculiX prints nothing for it
      ! (its test deck spring4), its FREQUENCY= still counts
      call deck_warning(p%deck, p%i, '*' // kw%name // ' has no output quantities (no data line): it prints ' // &
                        'nothing, as in CalculiX')
      call output_schedule(p, m, kw, card, every)
      return
    end if
    call request_quantities(p, kw, r)
    call output_schedule(p, m, kw, card, every)
    if (.not. keep .or. every == 0) return
    call grow(m%steps(p%step)%requests, p%nreq + 1)
    p%nreq = p%nreq + 1
    m%steps(p%step)%requests(p%nreq) = r
  end subroutine read_request

  !> Purpose: the set of an output card (NSET= or ELSET=; r%set, 0 all)
  !> and whether the card is kept: a print card naming an undefined set
  !> is ignored with a warning at its line (CalculiX: "node set ... does
  !> not exist"); a file card keeps its quantities, since the result
  !> files hold every node whatever the set. An empty set is warned about.
  logical function request_set(p, m, kw, r) result(keep)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(in) :: m
    type(keyword_t), intent(in) :: kw
    type(request_t), intent(inout) :: r
    character(len=:), allocatable :: pname, what, name
    integer :: iset, n
    keep = .true.
    pname = merge('NSET ', 'ELSET', r%nodal .or. (r%to_file .and. has_param(kw, 'NSET')))
    pname = trim(pname)
    if (.not. has_param(kw, pname)) return
    name = to_upper(param_value(kw, pname))
    what = merge('node set   ', 'element set', pname == 'NSET')
    what = trim(what)
    if (pname == 'NSET') then
      iset = nset_index(p, m, name)
      if (iset > 0) n = size(m%nsets(iset)%items)
    else
      iset = elset_index(p, m, name)
      if (iset > 0) n = size(m%elsets(iset)%items)
    end if
    if (iset == 0 .and. r%to_file) then
      call deck_warning(p%deck, p%i, what // ' ' // name // ' is undefined: ' // pname // '= on *' // kw%name // &
                        ' is ignored (the result files hold every node)')
    else if (iset == 0) then
      call deck_warning(p%deck, p%i, what // ' ' // name // ' is undefined: *' // kw%name // &
                        ' is ignored, as CalculiX ignores it' // set_hint(p, m, pname, name))
      keep = .false.
    else if (r%to_file) then
      ! (the result files hold every node whatever the set)
      if (.not. r%nodal .and. pname == 'ELSET') r%set = iset
    else
      r%set = iset
      call warn_empty_set(p, n, what, name, kw%name)
    end if
  end function request_set

  !> Purpose: the hint to a warning about an undefined node set (pname
  !> NSET) that is an element set: how gmsh writes node sets, or how to
  !> make one; '' otherwise.
  function set_hint(p, m, pname, name) result(s)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    character(len=*), intent(in) :: pname, name
    character(len=:), allocatable :: s
    s = ''
    if (pname /= 'NSET') return
    if (elset_index(p, m, name) == 0) return
    s = ' (there is an element set of that name: gmsh writes node sets only with -setnumber ' // &
        'Mesh.SaveGroupsOfNodes 1; or define it with *NSET, NSET=' // name // ', ELSET=' // name // ')'
  end function set_hint

  !> Purpose: the quantities on the data lines of an output card into r.
  !> Nodal cards: U, RF, S (extrapolated to the nodes and averaged),
  !> CSTRESS (contact pressure; CDISP and CONTACT name it too); element
  !> cards: S, E, PEEQ at the integration points, and in *EL FILE also U,
  !> RF and CSTRESS (nodal views of the result file, as CalculiX writes U
  !> asked for on *EL FILE). Anything else is warned about and skipped.
  subroutine request_quantities(p, kw, r)
    type(parser_t), intent(inout) :: p
    type(keyword_t), intent(in) :: kw
    type(request_t), intent(inout) :: r
    type(field_t), allocatable :: f(:)
    integer :: n, k
    character(len=:), allocatable :: q
    call require_data(p, 'output quantities')
    do
      call split_fields(line_text(p), f, n)
      do k = 1, n
        q = to_upper(f(k)%s)
        select case (q)
        case ('U', 'RF', 'S', 'E', 'PEEQ')
          r%u = r%u .or. q == 'U'
          r%rf = r%rf .or. q == 'RF'
          r%s = r%s .or. q == 'S'
          r%e = r%e .or. q == 'E'
          r%peeq = r%peeq .or. q == 'PEEQ'
          ! the order of the card (that of CalculiX's .dat blocks)
          if (index(r%order, q(1:1)) == 0 .and. len_trim(r%order) < len(r%order)) &
            r%order = trim(r%order) // merge('P', q(1:1), q == 'PEEQ')
        case ('CSTRESS', 'CDISP', 'CONTACT'); r%cstress = .true.
        ! heat transfer (temperature_field): temperatures, reaction fluxes
        case ('NT'); r%nt = .true.
        case ('RFL'); r%rfl = .true.
        case ('HFL'); r%hfl = .true.
        case ('')
        case default
          call deck_warning(p%deck, p%i, 'output quantity ' // q // ' is not available and is ignored')
          cycle
        end select
        if ((r%nodal .or. r%to_file) .and. q == 'HFL') call deck_warning(p%deck, p%i, 'HFL (heat flux) is ' // &
          'listed at the integration points by *EL PRINT only; ignored here')
        if (r%to_file .and. q == 'RFL') call deck_warning(p%deck, p%i, 'RFL is listed by *NODE PRINT only ' // &
          '(not in the result files); ignored here')
        if (.not. r%nodal .and. .not. r%to_file .and. (q == 'U' .or. q == 'RF')) &
          call deck_warning(p%deck, p%i, q // ' is a nodal quantity, which *EL PRINT does not list: ask for it ' // &
                            'in *NODE PRINT; ignored here')
        if (.not. r%nodal .and. .not. r%to_file .and. (q == 'CSTRESS' .or. q == 'CDISP' .or. q == 'CONTACT')) &
          call deck_warning(p%deck, p%i, q // ' is listed in the contact tables of every increment, not by ' // &
                            '*EL PRINT; ignored here')
      end do
      if (.not. next_data(p)) exit
    end do
    if (r%nodal .and. r%e) call err(p, 'E is an element quantity: ask for it in *EL PRINT or *EL FILE')
    if (r%nodal .and. r%peeq) call err(p, 'PEEQ is an element quantity: ask for it in *EL PRINT or *EL FILE')
    if (r%only_totals .and. .not. r%rf) call deck_warning(p%deck, p%i, 'TOTALS=ONLY on *' // kw%name // &
      ' lists only the sum of RF, which is not asked for: the card lists nothing')
  end subroutine request_quantities

  !> Purpose: the parameters of an output card that cfe2d honours by
  !> what it does anyway, or cannot honour (a warning at the line): TOTALS=
  !> (*NODE PRINT: the sum of RF over the set; *EL PRINT sums whole-element
  !> quantities cfe2d does not have), OUTPUT= (2D: the result files are
  !> 2D), POSITION= (INTEGRATION POINTS), SUMMARY=NO, FREQUENCYF= (fluid
  !> output), LAST ITERATIONS, CONTACT ELEMENTS, SECTION FORCES (CalculiX's
  !> debugging and shell output).
  subroutine ignored_params(p, kw, r)
    type(parser_t), intent(in) :: p
    type(keyword_t), intent(in) :: kw
    type(request_t), intent(inout) :: r
    character(len=:), allocatable :: v
    integer :: k
    character(len=16), parameter :: unused(*) = [character(len=16) :: 'FREQUENCYF', 'LAST ITERATIONS', &
                                                 'CONTACT ELEMENTS', 'SECTION FORCES']
    if (has_param(kw, 'TOTALS')) then
      v = to_upper(param_value(kw, 'TOTALS'))
      if (v /= 'YES' .and. v /= 'ONLY' .and. v /= 'NO') call err(p, 'TOTALS must be YES, ONLY or NO')
      if (r%nodal .and. .not. r%to_file) then
        r%totals = v /= 'NO'
        r%only_totals = v == 'ONLY'
      else if (v /= 'NO') then
        call deck_warning(p%deck, p%i, 'TOTALS=' // v // ' on *' // kw%name // ' is ignored: it sums ' // &
          merge('whole-element quantities (ELSE, EVOL), which cfe2d does not have', &
                'RF of *NODE PRINT only                                          ', .not. r%nodal))
      end if
    end if
    if (has_param(kw, 'OUTPUT')) then
      v = to_upper(param_value(kw, 'OUTPUT'))
      if (v == '3D') call deck_warning(p%deck, p%i, 'OUTPUT=3D is ignored: cfe2d''s results are those of the ' // &
                                       '2D model (as OUTPUT=2D)')
      if (v /= '2D' .and. v /= '3D') call err(p, 'OUTPUT must be 2D or 3D')
    end if
    if (has_param(kw, 'POSITION')) then
      v = to_upper(param_value(kw, 'POSITION'))
      if (v /= 'INTEGRATION POINTS' .and. v /= 'INTEGRATIONPOINTS') call deck_warning(p%deck, p%i, &
        'POSITION=' // v // ' is ignored: *' // kw%name // ' gives values at the integration points')
    end if
    if (has_param(kw, 'SUMMARY')) then
      if (to_upper(param_value(kw, 'SUMMARY')) /= 'NO') call deck_warning(p%deck, p%i, 'SUMMARY=' // &
        to_upper(param_value(kw, 'SUMMARY')) // ' is ignored: cfe2d lists no summary of extreme values')
    end if
    do k = 1, size(unused)
      if (has_param(kw, trim(unused(k)))) call deck_warning(p%deck, p%i, trim(unused(k)) // ' on *' // &
        kw%name // ' is not implemented in cfe2d and is ignored')
    end do
  end subroutine ignored_params

  !> A parameter that must be YES or NO, if given.
  subroutine yes_no(p, kw, name)
    type(parser_t), intent(in) :: p
    type(keyword_t), intent(in) :: kw
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: v
    if (.not. has_param(kw, name)) return
    v = to_upper(param_value(kw, name))
    if (v /= 'YES' .and. v /= 'NO') call err(p, name // ' must be YES or NO')
  end subroutine yes_no

  !> Purpose: FREQUENCY= and TIME POINTS= of an output card (at line
  !> card). As in CalculiX the last one given in a step applies to all of
  !> its print and file output: FREQUENCY=n (n >= 1) writes it every n-th
  !> increment, TIME POINTS= at the times of that *TIME POINTS card (the
  !> first increment ending at or after each), and the step's last
  !> increment always. FREQUENCY=0 turns only this card off (every = 0).
  subroutine output_schedule(p, m, kw, card, every)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    integer, intent(in) :: card
    integer, intent(out) :: every
    integer :: k, line
    character(len=:), allocatable :: name
    every = 1
    line = p%i
    p%i = card
    if (has_param(kw, 'FREQUENCY') .and. has_param(kw, 'TIME POINTS')) &
      call err(p, 'FREQUENCY= and TIME POINTS= exclude each other')
    if (has_param(kw, 'FREQUENCY')) then
      every = param_int(p, kw, 'FREQUENCY', 1, 0, huge(1))
      if (every > 0) then
        m%steps(p%step)%out_every = every
        if (allocated(m%steps(p%step)%out_times)) deallocate(m%steps(p%step)%out_times)
        p%time_points_line = 0
      end if
    else if (has_param(kw, 'TIME POINTS')) then
      name = to_upper(param_value(kw, 'TIME POINTS'))
      k = 0
      if (p%ntime_points > 0) k = find_name(p%time_points(1:p%ntime_points)%name, name)
      if (k == 0) then
        call deck_warning(p%deck, p%i, 'undefined *TIME POINTS ' // name // ': TIME POINTS= is ignored')
      else
        m%steps(p%step)%out_every = 1
        m%steps(p%step)%out_times = p%time_points(k)%t
        m%steps(p%step)%out_total_time = p%time_points(k)%total
        p%time_points_line = card
      end if
    end if
    p%i = line
  end subroutine output_schedule

  !> Purpose: *CONTACT PRINT and *CONTACT FILE. The listing gives the
  !> contact tables (gap, status, force, area, pressure, friction) of
  !> every pair at every increment; *CONTACT PRINT's CDIS and CSTR add the
  !> blocks of CalculiX's .dat (step_t's contact_print_cdis/_cstr; CFN,
  !> CFS, CNUM are read; its TOTALS= are the pair summaries); *CONTACT
  !> FILE with CSTR or CDIS writes the contact pressure (and shear) views
  !> of the result files (gmsh, VTU, the .frd's CONTACT block). Other quantities
  !> (CELS, PCON, ...) are warned about; FREQUENCY= and TIME POINTS= as
  !> on the other output cards.
  subroutine contact_request(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(request_t) :: r
    type(field_t), allocatable :: f(:)
    integer :: n, k, card, every
    character(len=:), allocatable :: q
    card = p%i
    r%to_file = kw%name == 'CONTACT FILE'
    ! (CalculiX warns about a parameter it does not know here and goes on;
    ! its own test decks write SET=)
    do k = 1, kw%np
      if (index(',FREQUENCY,TIME POINTS,TOTALS,LAST ITERATIONS,CONTACT ELEMENTS,', ',' // kw%pname(k)%s // ',') &
          == 0) call deck_warning(p%deck, p%i, 'parameter ' // kw%pname(k)%s // ' of *' // kw%name // &
                                  ' is not known and is ignored')
    end do
    call ignored_params(p, kw, r)
    call require_data(p, 'output quantities')
    do
      call split_fields(line_text(p), f, n)
      do k = 1, n
        q = to_upper(f(k)%s)
        select case (q)
        case ('CSTR', 'CDIS', 'CSTRESS', 'CDISP')
          r%cstress = .true.
          ! *CONTACT PRINT: the blocks of <job>.dat
          if (.not. r%to_file .and. p%step > 0 .and. q(1:4) == 'CSTR') m%steps(p%step)%contact_print_cstr = .true.
          if (.not. r%to_file .and. p%step > 0 .and. q(1:4) == 'CDIS') m%steps(p%step)%contact_print_cdis = .true.
        case ('CFN', 'CFS', 'CNUM')
          if (r%to_file) call deck_warning(p%deck, p%i, 'output quantity ' // q // ' is not written to the ' // &
            'result files and is ignored (the listing''s contact tables give the contact forces)')
        case ('')
        case default
          call deck_warning(p%deck, p%i, 'output quantity ' // q // ' is not available and is ignored')
        end select
      end do
      if (.not. next_data(p)) exit
    end do
    call output_schedule(p, m, kw, card, every)
    if (.not. r%to_file .and. every == 0 .and. p%step > 0) then
      m%steps(p%step)%contact_print_cstr = .false.
      m%steps(p%step)%contact_print_cdis = .false.
    end if
    if (.not. r%to_file .or. .not. r%cstress .or. every == 0) return
    call grow(m%steps(p%step)%requests, p%nreq + 1)
    p%nreq = p%nreq + 1
    m%steps(p%step)%requests(p%nreq) = r
  end subroutine contact_request

  !> Purpose: *TIME POINTS, NAME=: times named by TIME POINTS= of the
  !> output cards, any number per data line, increasing; GENERATE: lines
  !> `start, end, increment`; TIME=TOTAL TIME: total times (default: step
  !> times).
  module subroutine read_time_points(p, kw)
    type(parser_t), intent(inout) :: p
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    real(dp), allocatable :: t(:)
    real(dp) :: a, b, c
    integer :: n, k, nt
    character(len=:), allocatable :: name
    call allow_params(p, kw, 'NAME,TIME,GENERATE')
    name = name_param(p, kw, 'NAME')
    allocate(t(0))
    nt = 0
    do while (next_data(p))
      call split_fields(line_text(p), f, n)
      if (has_param(kw, 'GENERATE')) then
        if (n /= 3) call err(p, '*TIME POINTS, GENERATE data line needs: start, end, increment')
        a = get_real(p, f(1), 'start time')
        b = get_real(p, f(2), 'end time')
        c = get_real(p, f(3), 'time increment')
        if (.not. c > 0.0_dp .or. b < a) call err(p, 'GENERATE needs start <= end and a positive increment')
        if ((b - a) / c > real(max_increments, dp)) call err(p, 'GENERATE would make more than ' // &
                                                              itoa(max_increments) // ' time points')
        do k = 0, int((b - a) / c * (1.0_dp + 1.0e-12_dp))
          call append(t, nt, a + k * c)
        end do
      else
        do k = 1, n
          if (len(f(k)%s) > 0) call append(t, nt, get_real(p, f(k), 'time point'))
        end do
      end if
      if (nt > 1) then
        if (any(t(2:nt) <= t(1:nt - 1))) call err(p, 'time points must increase')
      end if
    end do
    if (nt == 0) call err(p, 'missing data line (time points)')
    call add_time_points(p, name, t(1:nt), has_param(kw, 'TIME') .and. &
                         to_upper(param_value(kw, 'TIME')) == 'TOTAL TIME')
  end subroutine read_time_points

  !> A *TIME POINTS card into p%time_points (a repeated name is an error).
  subroutine add_time_points(p, name, t, total)
    type(parser_t), intent(inout) :: p
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: t(:)
    logical, intent(in) :: total
    type(time_points_t), allocatable :: tmp(:)
    if (.not. allocated(p%time_points)) allocate(p%time_points(2))
    if (p%ntime_points > 0) then
      if (find_name(p%time_points(1:p%ntime_points)%name, name) > 0) call err(p, 'duplicate *TIME POINTS ' // name)
    end if
    if (p%ntime_points == size(p%time_points)) then
      allocate(tmp(2 * p%ntime_points))
      tmp(1:p%ntime_points) = p%time_points(1:p%ntime_points)
      call move_alloc(tmp, p%time_points)
    end if
    p%ntime_points = p%ntime_points + 1
    p%time_points(p%ntime_points) = time_points_t(name=name, total=total, t=t)
  end subroutine add_time_points

  !> GLOBAL= of *NODE PRINT and *NODE FILE: whether U and RF of a node
  !> with *TRANSFORM are given in global axes. CalculiX's defaults: NO for
  !> *NODE PRINT (the listing then gives them in the node's local axes),
  !> YES for *NODE FILE; the result files always hold global components,
  !> so GLOBAL=NO there is a warning.
  subroutine global_param(p, kw, r)
    type(parser_t), intent(in) :: p
    type(keyword_t), intent(in) :: kw
    type(request_t), intent(inout) :: r
    character(len=:), allocatable :: v
    r%global = r%to_file
    if (.not. has_param(kw, 'GLOBAL')) return
    v = to_upper(param_value(kw, 'GLOBAL'))
    if (v /= 'YES' .and. v /= 'NO') call err(p, 'GLOBAL must be YES or NO')
    r%global = v == 'YES'
    if (r%to_file .and. .not. r%global) then
      call deck_warning(p%deck, p%i, 'GLOBAL=NO on *' // kw%name // ' is ignored: the result files hold ' // &
                        'global components (the listing, *NODE PRINT, gives local ones)')
      r%global = .true.
    end if
  end subroutine global_param

  !> FORMAT= of *NODE FILE and *EL FILE: MSH (default: the gmsh file only)
  !> or VTU (the ParaView files too; the gmsh file is written anyway).
  subroutine file_format(p, m, kw)
    type(parser_t), intent(in) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    if (.not. has_param(kw, 'FORMAT')) return
    select case (to_upper(param_value(kw, 'FORMAT')))
    case ('MSH')
    case ('VTU'); m%vtu = .true.
    case default; call err(p, 'FORMAT must be MSH or VTU')
    end select
  end subroutine file_format

  !> Purpose: where the step's output follows TIME POINTS= (read at line
  !> p%time_points_line), say at that line what cfe2d writes where
  !> CalculiX would write elsewhere: CalculiX shortens its increments to
  !> end on the time points, and so does cfe2d with automatic increments
  !> (NLGEOM, a nonlinear material: the driver's to_time_point); a step of
  !> fixed increments (linear, or DIRECT) keeps them and writes the first
  !> increment ending at or after each point (output_schedule), and warns
  !> about the points that fall inside an increment.
  subroutine check_time_points(p, m)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(in) :: m
    real(dp) :: start, t, n
    integer :: k, line, missed
    logical :: fixed
    line = p%i
    associate(s => m%steps(p%step))
      start = 0.0_dp
      if (s%out_total_time) start = sum(merge(m%steps(1:p%step - 1)%period, 1.0_dp, &
                                              m%steps(1:p%step - 1)%period > 0.0_dp))
      fixed = s%direct .or. .not. (s%nlgeom .or. any(m%materials(1:p%nmat)%law /= law_elastic) .or. &
                                   any(m%materials(1:p%nmat)%nyield > 0))
      p%i = p%time_points_line
      if (s%period <= 0.0_dp) then
        ! (no *STATIC: the step is refused elsewhere)
      else if (.not. fixed) then
        ! (automatic increments end on the points)
      else
        missed = 0
        do k = 1, size(s%out_times)
          t = s%out_times(k) - start
          if (t <= 0.0_dp .or. t > s%period) cycle
          n = t / s%dt
          if (abs(n - nint(n)) > 1.0e-9_dp * max(n, 1.0_dp)) missed = missed + 1
        end do
        if (missed > 0) call deck_warning(p%deck, p%i, itoa(missed) // ' time point' // &
          merge('s lie', ' lies', missed > 1) // ' inside an increment of ' // rtoa(s%dt, 6) // &
          ': the output is that of the increment ending after it (CalculiX shortens an increment to end on it)')
      end if
    end associate
    p%i = line
    p%time_points_line = 0
  end subroutine check_time_points

  !> Purpose: *END STEP: closes the step; its lists are cut to length.
  module subroutine read_end_step(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    call allow_params(p, kw, '')
    call no_data(p, kw)
    if (p%time_points_line > 0) call check_time_points(p, m)
    associate(s => m%steps(p%step))
      s%bcs = s%bcs(1:p%nbc)
      s%loads = s%loads(1:p%nload)
      s%requests = s%requests(1:p%nreq)
    end associate
    p%step = 0
  end subroutine read_end_step
end submodule deck_step_cards
