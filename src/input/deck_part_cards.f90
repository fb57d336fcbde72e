!> Abaqus/CAE input: *PART ... *END PART, *ASSEMBLY ... *END ASSEMBLY,
!> *INSTANCE ... *END INSTANCE. Read as Abaqus resolves them: a part's
!> cards (nodes, elements, sets, surfaces, sections) are only recorded
!> where the part stands, and read again for every instance of it, which
!> so gets its own copy of the part's nodes and elements:
!>   numbers   the part's labels; the model's ids are offset + label, one
!>             offset per instance above the assembly's own numbers
!>             (deck_cursor: new_node_id, scoped_id);
!>   names     the part's set and surface NAME becomes INSTANCE.NAME;
!>   position  the part's coordinates translated, then turned about the
!>             z axis (deck_cursor: placed);
!>   sections  each instance's *SOLID SECTION names its own elements.
!> At the assembly level and after it, a member of an instance is
!> INSTANCE.NUMBER, a part-level set INSTANCE.NAME, and *NSET/*ELSET with
!> INSTANCE= list an instance's labels (deck_mesh_cards).
submodule (deck_parser) deck_part_cards
  use kinds, only: dp
  use strings, only: split_fields, field_t, rtoa
  use deck_input, only: deck_warning
  use deck_cursor, only: part_t, line_text, err, next_data, allow_params, name_param, get_real, get_int, is_int, &
                         instance_index, set_scope, max_id
  use model, only: instance_t
  implicit none

  !> The cards a part (or an instance) may hold: its mesh, its sets and
  !> surfaces, what gives its elements stiffness, and its own constraints
  !> (*RIGID BODY: Abaqus/CAE writes a rigid part's, e.g. an indenter's,
  !> inside the part, naming the part's sets and reference point; each
  !> instance then has its own rigid body; *ORIENTATION: the material axes
  !> of the part's sections, turned with each instance).
  character(len=16), parameter :: part_cards(*) = [character(len=16) :: 'NODE', 'ELEMENT', 'NSET', 'ELSET', &
    'SURFACE', 'SOLID SECTION', 'SPRING', 'MASS', 'NODAL THICKNESS', 'EQUATION', 'RIGID BODY', 'ORIENTATION']

contains

  !> Purpose: *PART, NAME=: record the part's lines, up to its *END PART,
  !> and check its cards; they are read for each *INSTANCE of it.
  module subroutine read_part(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(part_t), allocatable :: tmp(:)
    type(keyword_t) :: card
    character(len=:), allocatable :: name
    integer :: j, k
    call allow_params(p, kw, 'NAME')
    name = name_param(p, kw, 'NAME')
    if (p%assembly_line > 0) call err(p, '*PART inside *ASSEMBLY ... *END ASSEMBLY: parts are defined before ' // &
        'the assembly, which places them with *INSTANCE')
    if (p%assembly_done) call err(p, '*PART after *END ASSEMBLY: parts are defined before the assembly that ' // &
        'places them')
    call check_flat_mesh(p, m, kw)
    do k = 1, p%nparts
      if (p%parts(k)%name == name) call err(p, 'duplicate part ' // name)
    end do
    p%part_based = .true.
    if (.not. allocated(p%parts)) allocate(p%parts(4))
    if (p%nparts == size(p%parts)) then
      allocate(tmp(2 * p%nparts))
      tmp(1:p%nparts) = p%parts(1:p%nparts)
      call move_alloc(tmp, p%parts)
    end if
    p%nparts = p%nparts + 1
    p%parts(p%nparts) = part_t(name=name, first=p%i)
    if (next_data(p)) call err(p, 'unexpected data line after *PART')
    ! Its cards, checked now (a part never instanced is still a part of
    ! the deck); only *END PART ends it.
    do j = p%i + 1, p%deck%n
      if (.not. is_keyword(p%deck%lines(j)%text)) cycle
      p%i = j
      call parse_keyword(line_text(p), card)
      card%name = spaced_name(card%name)
      select case (card%name)
      case ('END PART')
        call allow_params(p, card, '')
        p%parts(p%nparts)%last = j
        return
      case ('PART')
        call err(p, '*PART inside *PART ' // name // ': its *END PART is missing before this line')
      case ('ASSEMBLY', 'INSTANCE', 'END INSTANCE', 'END ASSEMBLY', 'STEP')
        call err(p, '*' // card%name // ' inside *PART ' // name // ': its *END PART is missing before this line')
      case default
        if (.not. is_part_card(card%name)) call err(p, '*' // card%name // ' cannot be inside *PART ... ' // &
            '*END PART: cfe2d reads a part''s ' // part_card_list())
      end select
    end do
    p%i = p%parts(p%nparts)%first
    call err(p, '*PART ' // name // ' without *END PART')
  end subroutine read_part

  !> Purpose: *END PART where no *PART is open (read_part reads up to its
  !> own *END PART).
  module subroutine read_end_part(p, kw)
    type(parser_t), intent(inout) :: p
    type(keyword_t), intent(in) :: kw
    call allow_params(p, kw, '')
    call err(p, '*END PART without *PART')
  end subroutine read_end_part

  !> Purpose: *ASSEMBLY[, NAME=]: opens the assembly (one per deck), where
  !> *INSTANCE places the parts. Its own nodes and elements (reference
  !> nodes, springs between instances) keep their numbers: the ids of the
  !> instances start above the largest, found here.
  module subroutine read_assembly(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(keyword_t) :: card
    type(field_t), allocatable :: f(:)
    integer :: j, n, id
    logical :: in_instance, nodes, elements
    call allow_params(p, kw, 'NAME')
    if (p%assembly_line > 0) call err(p, '*ASSEMBLY inside *ASSEMBLY: its *END ASSEMBLY is missing')
    if (p%assembly_done) call err(p, 'a second *ASSEMBLY: a model has one assembly')
    call check_flat_mesh(p, m, kw)
    p%part_based = .true.
    p%assembly_line = p%i
    if (.not. allocated(m%instances)) allocate(m%instances(0))
    in_instance = .false.
    nodes = .false.
    elements = .false.
    do j = p%i + 1, p%deck%n
      if (is_keyword(p%deck%lines(j)%text)) then
        call parse_keyword(p%deck%lines(j)%text, card)
        card%name = spaced_name(card%name)
        nodes = card%name == 'NODE' .and. .not. in_instance
        elements = card%name == 'ELEMENT' .and. .not. in_instance
        select case (card%name)
        case ('INSTANCE'); in_instance = .true.
        case ('END INSTANCE'); in_instance = .false.
        case ('END ASSEMBLY'); return
        case ('STEP'); exit
        end select
      else if (nodes .or. elements) then
        ! A bad number is left to *NODE or *ELEMENT to report.
        call split_fields(p%deck%lines(j)%text, f, n)
        if (.not. is_int(f(1)%s)) cycle
        id = get_int(p, f(1), 'id')
        if (nodes) p%asm_node_max = max(p%asm_node_max, min(id, max_id))
        if (elements) p%asm_elem_max = max(p%asm_elem_max, min(id, max_id))
      end if
    end do
    call err(p, '*ASSEMBLY without *END ASSEMBLY (before the first *STEP)')
  end subroutine read_assembly

  !> A deck with parts defines its mesh in them (and in the assembly), as
  !> Abaqus requires: nodes or elements already read outside are an error.
  subroutine check_flat_mesh(p, m, kw)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    type(keyword_t), intent(in) :: kw
    if (p%part_based .or. (m%nn == 0 .and. m%ne == 0)) return
    call err(p, '*' // kw%name // ' in a deck that defines nodes or elements outside *PART and *ASSEMBLY: a ' // &
             'deck with parts defines its mesh inside them')
  end subroutine check_flat_mesh

  !> Purpose: *INSTANCE, NAME=, PART=: a copy of the part, placed by the
  !> optional data lines `dx, dy[, dz]` (a translation) and `ax, ay, az,
  !> bx, by, bz, angle` (a rotation by angle degrees about the axis from
  !> a to b, right-handed, after the translation). The axis must be
  !> parallel to z: any other turns the part out of the x-y plane. The
  !> part's cards are read here for the instance; the cards up to *END
  !> INSTANCE belong to it too (CAE writes the mesh of an independent
  !> instance there).
  module subroutine read_instance(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(instance_t) :: inst
    type(keyword_t) :: card
    integer :: ip, k, saved
    call allow_params(p, kw, 'NAME,PART')
    if (p%assembly_line == 0) call err(p, '*INSTANCE outside *ASSEMBLY ... *END ASSEMBLY')
    inst%name = name_param(p, kw, 'NAME')
    inst%part = name_param(p, kw, 'PART')
    inst%src%line = p%i
    if (instance_index(m, inst%name) > 0) call err(p, 'duplicate instance ' // trim(inst%name))
    ip = 0
    do k = 1, p%nparts
      if (p%parts(k)%name == inst%part) ip = k
    end do
    if (ip == 0) call err(p, '*INSTANCE of part ' // trim(inst%part) // ', which no *PART before it defines' // &
                             defined_parts(p))
    call placement(p, inst)
    ! Ids above everything numbered so far: the assembly's own numbers
    ! and the instances before.
    inst%node_offset = p%asm_node_max
    inst%elem_offset = p%asm_elem_max
    do k = 1, size(m%instances)
      inst%node_offset = max(inst%node_offset, m%instances(k)%node_last)
      inst%elem_offset = max(inst%elem_offset, m%instances(k)%elem_last)
    end do
    inst%node_last = inst%node_offset
    inst%elem_last = inst%elem_offset
    m%instances = [m%instances, inst]
    k = size(m%instances)
    p%parts(ip)%instances = p%parts(ip)%instances + 1
    ! The part's cards, read for this instance.
    saved = p%i
    p%owner = k
    p%replaying = ip
    call set_scope(p, m, k)
    ! (each reader leaves p%i on the last line of its card)
    p%i = p%parts(ip)%first + 1
    do while (p%i < p%parts(ip)%last)
      if (is_keyword(line_text(p))) then
        call parse_keyword(line_text(p), card)
        call dispatch(p, m, card)
      end if
      p%i = p%i + 1
    end do
    p%replaying = 0
    p%i = saved
    call set_scope(p, m, k)
  end subroutine read_instance

  !> The data lines of *INSTANCE: translation, then rotation (both optional).
  subroutine placement(p, inst)
    type(parser_t), intent(inout) :: p
    type(instance_t), intent(inout) :: inst
    type(field_t), allocatable :: f(:)
    real(dp) :: a(3), b(3), axis(3), v
    integer :: n, k
    if (.not. next_data(p)) return
    call split_fields(line_text(p), f, n)
    if (n > 3) call err(p, 'the first data line of *INSTANCE is the translation: dx, dy, dz')
    do k = 1, n
      if (len(f(k)%s) == 0) cycle
      v = get_real(p, f(k), 'translation')
      ! (dz moves the part along z, which a 2D model does not see)
      if (k <= 2) inst%shift(k) = v
    end do
    if (.not. next_data(p)) return
    call split_fields(line_text(p), f, n)
    if (n /= 7) call err(p, 'the second data line of *INSTANCE is the rotation: ax, ay, az, bx, by, bz, angle ' // &
                            '(two points on the axis, the angle in degrees)')
    do k = 1, 3
      a(k) = get_real(p, f(k), 'point a of the rotation axis')
      b(k) = get_real(p, f(k + 3), 'point b of the rotation axis')
    end do
    inst%angle = get_real(p, f(7), 'rotation angle')
    axis = b - a
    if (all(axis == 0.0_dp)) call err(p, 'the rotation axis needs two different points a and b')
    if (norm2(axis(1:2)) > 1.0e-10_dp * norm2(axis) .and. inst%angle /= 0.0_dp) &
      call err(p, 'a rotation about an axis that is not parallel to z (from a to b: ' // rtoa(axis(1), 6) // ', ' // &
               rtoa(axis(2), 6) // ', ' // rtoa(axis(3), 6) // ') turns the part out of the x-y plane: a 2D ' // &
               'model can only turn about z')
    ! The right-hand rule about a -> b: counter-clockwise in x-y when b
    ! lies above a.
    inst%centre = a(1:2)
    if (axis(3) < 0.0_dp) inst%angle = -inst%angle
    if (next_data(p)) call err(p, '*INSTANCE has at most two data lines: the translation and the rotation')
  end subroutine placement

  !> ' (parts: A, B)' for the message of an undefined part.
  function defined_parts(p) result(s)
    type(parser_t), intent(in) :: p
    character(len=:), allocatable :: s
    integer :: k
    s = ' (no part is defined)'
    if (p%nparts == 0) return
    s = ' (parts: ' // trim(p%parts(1)%name)
    do k = 2, p%nparts
      s = s // ', ' // trim(p%parts(k)%name)
    end do
    s = s // ')'
  end function defined_parts

  !> Purpose: *END INSTANCE: the cards after it are the assembly's again.
  module subroutine read_end_instance(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    call allow_params(p, kw, '')
    if (p%owner == 0) call err(p, '*END INSTANCE without *INSTANCE')
    p%owner = 0
    call set_scope(p, m, 0)
  end subroutine read_end_instance

  !> Purpose: *END ASSEMBLY: model data follows (materials, interactions,
  !> contact pairs, steps), naming the assembly's sets and surfaces and
  !> the instances' members as INSTANCE.NAME, INSTANCE.NUMBER.
  module subroutine read_end_assembly(p, kw)
    type(parser_t), intent(inout) :: p
    type(keyword_t), intent(in) :: kw
    call allow_params(p, kw, '')
    if (p%assembly_line == 0) call err(p, '*END ASSEMBLY without *ASSEMBLY')
    p%assembly_line = 0
    p%assembly_done = .true.
  end subroutine read_end_assembly

  !> Purpose: before a card is read: inside an instance only the cards
  !> of a part; inside the assembly no *STEP; outside both, in a deck
  !> with parts, no nodes or elements (they belong to a part or to the
  !> assembly). (The cards of a part are checked by read_part.)
  module subroutine check_part_context(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(in) :: m
    type(keyword_t), intent(in) :: kw
    if (p%replaying > 0) return
    if (p%owner > 0) then
      select case (kw%name)
      case ('END INSTANCE')
      case ('INSTANCE', 'END ASSEMBLY', 'STEP', 'PART', 'ASSEMBLY')
        call err(p, '*' // kw%name // ' inside *INSTANCE ' // trim(m%instances(p%owner)%name) // &
                 ': its *END INSTANCE is missing before this line')
      case default
        if (.not. is_part_card(kw%name)) call err(p, '*' // kw%name // ' cannot be inside *INSTANCE ... ' // &
            '*END INSTANCE: cfe2d reads an instance''s ' // part_card_list())
      end select
    else if (p%assembly_line > 0) then
      if (kw%name == 'STEP') call err(p, '*STEP inside *ASSEMBLY: its *END ASSEMBLY is missing before this line')
    else if (p%part_based) then
      if (kw%name == 'NODE' .or. kw%name == 'ELEMENT') call err(p, '*' // kw%name // ' outside *PART and ' // &
          '*ASSEMBLY: in a deck with parts, nodes and elements are defined in a *PART (or in the *ASSEMBLY)')
    end if
  end subroutine check_part_context

  !> Purpose: once the deck is read: a deck with parts needs the assembly
  !> that places them; a part never instanced is not in the model (a
  !> warning).
  module subroutine finish_parts(p)
    type(parser_t), intent(inout) :: p
    integer :: k
    if (p%nparts == 0) return
    if (.not. p%assembly_done) then
      p%i = p%parts(1)%first
      call err(p, 'a part is in the model only through an *INSTANCE in the *ASSEMBLY, and this deck has no ' // &
               '*ASSEMBLY')
    end if
    do k = 1, p%nparts
      if (p%parts(k)%instances == 0) call deck_warning(p%deck, p%parts(k)%first, 'part ' // &
          trim(p%parts(k)%name) // ' has no *INSTANCE: its nodes and elements are not in the model')
    end do
  end subroutine finish_parts

  pure logical function is_part_card(name)
    character(len=*), intent(in) :: name
    is_part_card = any(part_cards == name)
  end function is_part_card

  function part_card_list() result(s)
    character(len=:), allocatable :: s
    integer :: k
    s = '*' // trim(part_cards(1))
    do k = 2, size(part_cards) - 1
      s = s // ', *' // trim(part_cards(k))
    end do
    s = s // ' and *' // trim(part_cards(size(part_cards)))
  end function part_card_list
end submodule deck_part_cards
