!> The parser's state (the deck and the current line) and what every
!> card reader does with it: errors that quote the card (file:line:
!> error:), data-line iteration, parameter and number parsing, id and set
!> lookup; and the limits the readers enforce.
!> Used by deck_parser and its card-reader submodules only. (These would
!> be private entities of deck_parser, but gfortran 12 gives private
!> module procedures local linkage, so its submodules could not call
!> them: the link fails with "undefined reference to __deck_parser_MOD_err".)
module deck_cursor
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp, name_len
  use strings, only: to_upper, parse_real, parse_int, field_t, itoa, split_fields
  use deck_input, only: deck_t, keyword_t, deck_error, deck_warning, param_value, has_param, is_keyword
  use model, only: model_t, find_name, has_instances, rigid_t, controls_t, step_t
  use model_growth, only: grow
  use growable, only: grow
  implicit none
  private
  public :: parser_t, time_points_t, max_id, max_increments, max_cutbacks, max_contact_iterations
  public :: interaction_t, behaviour_none, behaviour_linear, behaviour_hard, behaviour_soft, new_interaction
  public :: pair_interaction_t, add_pair_interaction
  public :: line_text, err, next_data, require_data, no_data, allow_params, required_param, &
            name_param, check_name_length, get_real, get_int, param_real, param_int, &
            node_of, node_or_zero, elem_of, is_int, nset_index, elset_index, need_nset, need_elset, &
            new_surface, in_step, warn_empty_set, read_time_line, target_nodes, amplitude_param
  ! Abaqus/CAE decks: parts, instances and the names and numbers of their members.
  public :: part_t, is_label, node_ref, elem_ref, defined_name, new_node_id, new_elem_id, placed, &
            instance_index, set_scope
  ! Rotations of reference nodes (*RIGID BODY, *COUPLING): what a deck's dof is.
  public :: deck_dof, dof_moves, dof_zero, dof_none, note_named, rotation_hint

  !> What a dof of the deck is at a node (deck_dof): one of the two dofs
  !> of a node of the model, a dof that is always zero in 2D (out of the
  !> plane, or a rotation about an in-plane axis), or no dof of that node.
  integer, parameter :: dof_moves = 1, dof_zero = 2, dof_none = 3

  !> Node and element ids are 1..max_id (an id indexes a lookup table).
  integer, parameter :: max_id = 100000000
  !> Increments of one step (period / initial increment, also INC=):
  !> each increment is a solution, and the count is stored as an integer.
  integer, parameter :: max_increments = 100000
  !> CUTBACKS= of *CONTACT CONTROLS: each cutback halves the increment
  !> through one more level of recursion; 2^-50 of a step is far below
  !> anything meaningful.
  integer, parameter :: max_cutbacks = 50
  !> MAXIT= of *CONTACT CONTROLS: contact status iterations per increment.
  integer, parameter :: max_contact_iterations = 1000

  !> Pressure-overclosure behaviours of a surface interaction that cfe2d
  !> maps onto its penalty (the others stop at their *SURFACE BEHAVIOR).
  integer, parameter :: behaviour_none = 0, behaviour_linear = 1, behaviour_hard = 2, behaviour_soft = 3

  !> A *SURFACE INTERACTION block as read. Each *CONTACT PAIR naming it
  !> takes its penalty into its contact_pair_t, so the block itself only
  !> lives while reading.
  type :: interaction_t
    character(len=name_len) :: name = ''
    integer :: behaviour = behaviour_none
    real(dp) :: slope = -1.0_dp     ! K of LINEAR (pressure per overclosure); < 0: automatic penalty
    real(dp) :: thickness = -1.0_dp ! its data line: Abaqus' out-of-plane thickness of 2D contact
    real(dp) :: mu = 0.0_dp         ! *FRICTION: coefficient (0: frictionless)
    real(dp) :: stick_slope = -1.0_dp   ! *FRICTION: shear stress per unit slip; < 0: automatic
    !> *WEAR: Archard coefficients of the slave and master surfaces, the
    !> cycle-jump factor and the card's line (0: no *WEAR)
    real(dp) :: wear_k(2) = 0.0_dp, wear_jump = 1.0_dp
    integer :: wear_line = 0
    integer :: line = 0             ! the *SURFACE INTERACTION line
    !> EXPONENTIAL or TABULAR: the soft law's knots (contact_pair_t%soft_h, %soft_p)
    real(dp), allocatable :: soft_h(:), soft_p(:)
  end type interaction_t

  !> INTERACTION= of a *CONTACT PAIR: resolved once the deck is read, as
  !> CalculiX lets the *SURFACE INTERACTION come after the pair.
  type :: pair_interaction_t
    integer :: pair = 0            ! index into model%pairs
    integer :: line = 0            ! the *CONTACT PAIR line
    character(len=name_len) :: name = ''
  end type pair_interaction_t

  !> A *PART as defined: its name and the lines of its *PART and *END
  !> PART. Its cards are read once for every *INSTANCE of it.
  type :: part_t
    character(len=name_len) :: name = ''
    integer :: first = 0, last = 0
    integer :: instances = 0
  end type part_t

  !> A *TIME POINTS card: its name, its times and whether they are total
  !> times (TIME=TOTAL TIME) rather than step times.
  type :: time_points_t
    character(len=name_len) :: name = ''
    logical :: total = .false.
    real(dp), allocatable :: t(:)
  end type time_points_t

  !> Parser state that only lives while reading.
  type :: parser_t
    type(deck_t) :: deck
    integer :: i = 0             ! current line
    integer :: step = 0          ! current step, 0 outside *STEP
    integer :: step_line = 0
    integer :: material = 0      ! material that *ELASTIC applies to
    integer :: nsets = 0, nelsets = 0, nsurf = 0, nmat = 0, nsec = 0, namp = 0
    integer :: nsteps = 0, npairs = 0, nmbc = 0
    integer :: nbc = 0, nload = 0, nreq = 0   ! of the current step
    logical :: nlgeom = .false.  ! NLGEOM of the last *STEP (a step without the parameter keeps it)
    type(controls_t) :: controls ! *CONTROLS in force (kept from step to step until RESET)
    ! Cards of decks written for CalculiX/Abaqus:
    type(interaction_t), allocatable :: inter(:)
    integer :: ninter = 0
    integer :: interaction = 0   ! the block that *SURFACE BEHAVIOR and *FRICTION describe
    type(pair_interaction_t), allocatable :: pair_inter(:)
    integer :: npair_inter = 0
    logical :: heading_from_deck = .false.     ! the title came from the deck, not an include
    real(dp), allocatable :: node_thickness(:) ! *NODAL THICKNESS by internal node, < 0: none
    integer :: nodal_thickness_line = 0        ! the last *NODAL THICKNESS card
    integer :: heading_line = 0                ! the *HEADING whose title is kept
    integer :: nequations = 0
    integer, allocatable :: node_line(:)       ! the data line of each node (internal index)
    ! Abaqus/CAE decks (deck_part_cards). Inside an instance (while its
    ! part's cards are read again, and up to its *END INSTANCE) `owner`
    ! is the instance (index into model%instances): names defined take
    ! its prefix INSTANCE., numbers its id offsets, nodes its placement.
    ! `scope` is the instance whose node and element labels and set
    ! names a card looks up: the owner, or INSTANCE= of an assembly-level
    ! *NSET/*ELSET; 0 is the assembly (or a flat deck).
    type(part_t), allocatable :: parts(:)
    integer :: nparts = 0
    logical :: part_based = .false.            ! the deck has a *PART or an *ASSEMBLY
    integer :: assembly_line = 0               ! the *ASSEMBLY line, while inside it
    logical :: assembly_done = .false.         ! *END ASSEMBLY was read
    integer :: owner = 0, scope = 0
    integer :: replaying = 0                   ! the part whose cards are being read for `owner`
    integer :: asm_node_max = 0, asm_elem_max = 0  ! largest assembly-level labels: instance ids start above
    character(len=:), allocatable :: scope_note    ! appended to errors: the instance being read
    ! *RIGID BODY and *COUPLING (deck_rigid_cards), by internal node: the
    ! node whose dof 1 is a reference node's rotation (its dof 6; 0 none),
    ! the user's ROT NODEs (their dofs 1..3 are rotations, dof 3 in the
    ! plane), and the first *BOUNDARY, *CLOAD or *EQUATION line naming a
    ! node (a ROT NODE must not have been named as a plain node before).
    integer, allocatable :: ref_rotation(:)
    logical, allocatable :: is_rot_node(:)
    integer, allocatable :: named_line(:)
    ! The *COUPLING waiting for its *KINEMATIC or *DISTRIBUTING (its line,
    ! 0 none), its surface and INFLUENCE RADIUS (< 0: every node).
    type(rigid_t) :: coupling
    integer :: coupling_line = 0, coupling_surface = 0
    real(dp) :: coupling_radius = -1.0_dp
    ! *TIME POINTS cards (deck_step_cards), named by TIME POINTS= of the
    ! output cards.
    type(time_points_t), allocatable :: time_points(:)
    integer :: ntime_points = 0
    integer :: time_points_line = 0   ! the output card whose TIME POINTS= the current step follows (0 none)
    ! Leniency as CalculiX's, each told by one warning once the deck is
    ! read: node numbers in *NSET lists that no *NODE defines (dropped:
    ! how many, the first line, the first five numbers), and node lines
    ! that define a node again (the later coordinates win: how many, the
    ! first such line).
    integer :: dropped_nodes = 0, dropped_line = 0
    integer :: dropped_ids(5) = 0
    integer :: repeated_nodes = 0, repeated_line = 0
    ! The keyword lines read ahead of their place (read_model reads the
    ! mesh and set cards of a flat deck first, as CalculiX does).
    logical, allocatable :: read_ahead(:)
    ! the material of each *MATERIAL line read ahead (0 on other lines):
    ! a material card out of its block still describes the material
    ! above it
    integer, allocatable :: ahead_material(:)
  end type parser_t

contains

  function line_text(p) result(t)
    type(parser_t), intent(in) :: p
    character(len=:), allocatable :: t
    t = p%deck%lines(p%i)%text
  end function line_text

  !> Stop with file:line: error: msg, quoting the current line. Inside
  !> an instance the message says which (a part's line is read once per
  !> instance of it).
  subroutine err(p, msg)
    type(parser_t), intent(in) :: p
    character(len=*), intent(in) :: msg
    associate(l => p%deck%lines(p%i))
      if (allocated(p%scope_note)) then
        call deck_error(p%deck, l%file, l%line, msg // p%scope_note, l%text)
      else
        call deck_error(p%deck, l%file, l%line, msg, l%text)
      end if
    end associate
  end subroutine err

  !> True and advances if the next line is a data line.
  logical function next_data(p)
    type(parser_t), intent(inout) :: p
    next_data = .false.
    if (p%i + 1 > p%deck%n) return
    if (is_keyword(p%deck%lines(p%i + 1)%text)) return
    p%i = p%i + 1
    next_data = .true.
  end function next_data

  subroutine require_data(p, what)
    type(parser_t), intent(inout) :: p
    character(len=*), intent(in) :: what
    if (.not. next_data(p)) call err(p, 'missing data line (' // what // ')')
  end subroutine require_data

  subroutine no_data(p, kw)
    type(parser_t), intent(inout) :: p
    type(keyword_t), intent(in) :: kw
    if (next_data(p)) call err(p, 'unexpected data line after *' // kw%name)
  end subroutine no_data

  !> Stops on a parameter the keyword does not know.
  subroutine allow_params(p, kw, allowed)
    type(parser_t), intent(in) :: p
    type(keyword_t), intent(in) :: kw
    character(len=*), intent(in) :: allowed
    integer :: k
    do k = 1, kw%np
      if (index(',' // allowed // ',', ',' // kw%pname(k)%s // ',') == 0) &
        call err(p, 'unknown parameter ' // kw%pname(k)%s // ' on *' // kw%name)
    end do
  end subroutine allow_params

  function required_param(p, kw, name) result(v)
    type(parser_t), intent(in) :: p
    type(keyword_t), intent(in) :: kw
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: v
    v = param_value(kw, name)
    if (len(v) == 0) call err(p, '*' // kw%name // ' needs ' // name // '=')
  end function required_param

  !> A name given as NAME=value (required): upper-cased, at most name_len
  !> characters (longer names would be cut and could clash).
  function name_param(p, kw, name) result(v)
    type(parser_t), intent(in) :: p
    type(keyword_t), intent(in) :: kw
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: v
    v = to_upper(required_param(p, kw, name))
    call check_name_length(p, v)
  end function name_param

  subroutine check_name_length(p, name)
    type(parser_t), intent(in) :: p
    character(len=*), intent(in) :: name
    if (len_trim(name) > name_len) call err(p, 'name longer than ' // itoa(name_len) // ' characters')
  end subroutine check_name_length

  !> A real field, which must be a finite number: NaN, Infinity and
  !> values beyond the range of real(dp) (1e400) are errors naming `what`.
  real(dp) function get_real(p, f, what)
    type(parser_t), intent(in) :: p
    type(field_t), intent(in) :: f
    character(len=*), intent(in) :: what
    logical :: ok
    call parse_real(f%s, get_real, ok)
    if (ok) ok = ieee_is_finite(get_real)
    if (.not. ok) then
      if (len(f%s) == 0) call err(p, 'missing ' // what)
      if (reads_as_infinite(f%s)) call err(p, '"' // f%s // '" is not a finite number (' // what // ')')
      call err(p, '"' // f%s // '" is not a number (' // what // ')')
    end if
  end function get_real

  !> Text that Fortran reads as NaN or Infinity (also an overflowing
  !> literal): told apart from text that is no number at all only to
  !> word the message.
  logical function reads_as_infinite(s)
    character(len=*), intent(in) :: s
    real(dp) :: x
    integer :: ios
    x = 0.0_dp
    read(s, *, iostat=ios) x
    reads_as_infinite = ios == 0 .and. .not. ieee_is_finite(x)
  end function reads_as_infinite

  integer function get_int(p, f, what)
    type(parser_t), intent(in) :: p
    type(field_t), intent(in) :: f
    character(len=*), intent(in) :: what
    logical :: ok
    call parse_int(f%s, get_int, ok)
    if (.not. ok) then
      if (len(f%s) == 0) call err(p, 'missing ' // what)
      ! Digits after an optional sign: a number, but too large.
      if (verify(f%s(1:1), '+-0123456789') == 0 .and. verify(f%s(2:), '0123456789') == 0 .and. &
          scan(f%s, '0123456789') > 0) &
        call err(p, '"' // f%s // '" is out of the integer range (' // what // ')')
      call err(p, '"' // f%s // '" is not an integer (' // what // ')')
    end if
  end function get_int

  real(dp) function param_real(p, kw, name, default)
    type(parser_t), intent(in) :: p
    type(keyword_t), intent(in) :: kw
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: default
    type(field_t) :: f
    param_real = default
    if (.not. has_param(kw, name)) return
    f%s = param_value(kw, name)
    param_real = get_real(p, f, 'value of ' // name)
  end function param_real

  !> An integer parameter NAME=k with lo <= k <= hi, or default if absent.
  integer function param_int(p, kw, name, default, lo, hi)
    type(parser_t), intent(in) :: p
    type(keyword_t), intent(in) :: kw
    character(len=*), intent(in) :: name
    integer, intent(in) :: default, lo, hi
    type(field_t) :: f
    param_int = default
    if (.not. has_param(kw, name)) return
    f%s = param_value(kw, name)
    param_int = get_int(p, f, 'value of ' // name)
    if (param_int < lo .or. param_int > hi) &
      call err(p, name // ' must lie in ' // itoa(lo) // '..' // itoa(hi))
  end function param_int

  !> The node with number `id` where the card stands (p%scope: an
  !> instance's label, or the deck's number), 0 stops with 'undefined'.
  integer function node_of(p, m, id)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    integer, intent(in) :: id
    integer :: gid
    node_of = 0
    gid = scoped_id(m, p%scope, id, .true.)
    if (gid >= 1 .and. gid <= size(m%node_index)) node_of = m%node_index(gid)
    if (node_of == 0) call err(p, 'undefined node ' // itoa(id) // assembly_hint(p, m, id))
  end function node_of

  !> Purpose: the node with number `id` where the card stands (as
  !> node_of), or 0 when the deck defines none (no error).
  integer function node_or_zero(p, m, id)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    integer, intent(in) :: id
    integer :: gid
    node_or_zero = 0
    gid = scoped_id(m, p%scope, id, .true.)
    if (gid >= 1 .and. gid <= size(m%node_index)) node_or_zero = m%node_index(gid)
  end function node_or_zero

  integer function elem_of(p, m, id)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    integer, intent(in) :: id
    integer :: gid
    elem_of = 0
    gid = scoped_id(m, p%scope, id, .false.)
    if (gid >= 1 .and. gid <= size(m%elem_index)) elem_of = m%elem_index(gid)
    if (elem_of == 0) call err(p, 'undefined element ' // itoa(id) // assembly_hint(p, m, id))
  end function elem_of

  !> At the assembly level of a deck with instances a bare number is an
  !> assembly-level node or element: say how an instance's is named.
  function assembly_hint(p, m, id) result(s)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    integer, intent(in) :: id
    character(len=:), allocatable :: s
    s = ''
    if (p%scope == 0 .and. has_instances(m)) s = ' at the assembly level (a member of an instance is named ' // &
        'INSTANCE.NUMBER, e.g. ' // trim(m%instances(1)%name) // '.' // itoa(id) // ')'
  end function assembly_hint

  !> Purpose: the id (m%node_id, m%elem_id) of number `id` in scope k:
  !> offset + label in instance k (0 beyond its largest label), the
  !> number itself at the assembly level or in a flat deck (0 if an
  !> instance's ids take it).
  pure integer function scoped_id(m, k, id, nodes) result(gid)
    type(model_t), intent(in) :: m
    integer, intent(in) :: k, id
    logical, intent(in) :: nodes
    integer :: j, off, last
    gid = 0
    if (k > 0) then
      call id_range(m, k, nodes, off, last)
      if (id >= 1 .and. id <= last - off) gid = off + id
      return
    end if
    gid = id
    if (.not. has_instances(m)) return
    do j = 1, size(m%instances)
      call id_range(m, j, nodes, off, last)
      if (gid > off .and. gid <= last) gid = 0
    end do
  end function scoped_id

  pure subroutine id_range(m, k, nodes, off, last)
    type(model_t), intent(in) :: m
    integer, intent(in) :: k
    logical, intent(in) :: nodes
    integer, intent(out) :: off, last
    if (nodes) then
      off = m%instances(k)%node_offset
      last = m%instances(k)%node_last
    else
      off = m%instances(k)%elem_offset
      last = m%instances(k)%elem_last
    end if
  end subroutine id_range

  logical function is_int(s)
    character(len=*), intent(in) :: s
    integer :: k
    call parse_int(s, k, is_int)
  end function is_int

  !> Is s a node or element label: a number, or INSTANCE.NUMBER (an
  !> instance's member, `Part-1-1.17`)? A name begins with a letter, so
  !> `1.5` is not one.
  logical function is_label(s)
    character(len=*), intent(in) :: s
    integer :: j
    is_label = is_int(s)
    if (is_label) return
    j = index(s, '.', back=.true.)
    if (j <= 1 .or. j == len(s)) return
    if (.not. is_int(s(j + 1:))) return
    is_label = verify(s(1:1), '0123456789+-.') /= 0
  end function is_label

  !> Purpose: the node a label names (is_label): a number where the card
  !> stands, or INSTANCE.NUMBER; stops if there is none.
  integer function node_ref(p, m, f, what)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    type(field_t), intent(in) :: f
    character(len=*), intent(in) :: what
    if (is_int(f%s)) then
      node_ref = node_of(p, m, get_int(p, f, what))
    else
      node_ref = qualified_member(p, m, f, what, .true.)
    end if
  end function node_ref

  !> Purpose: the element a label names (see node_ref).
  integer function elem_ref(p, m, f, what)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    type(field_t), intent(in) :: f
    character(len=*), intent(in) :: what
    if (is_int(f%s)) then
      elem_ref = elem_of(p, m, get_int(p, f, what))
    else
      elem_ref = qualified_member(p, m, f, what, .false.)
    end if
  end function elem_ref

  !> The internal index of the node (is_node) or element INSTANCE.NUMBER
  !> names; stops if the instance has none.
  integer function qualified_member(p, m, f, what, is_node) result(idx)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    type(field_t), intent(in) :: f
    character(len=*), intent(in) :: what
    logical, intent(in) :: is_node
    character(len=:), allocatable :: kind
    integer :: k, id, gid
    call qualified_label(p, m, f, what, k, id)
    gid = scoped_id(m, k, id, is_node)
    idx = 0
    if (is_node) then
      kind = 'node'
      if (gid >= 1 .and. gid <= size(m%node_index)) idx = m%node_index(gid)
    else
      kind = 'element'
      if (gid >= 1 .and. gid <= size(m%elem_index)) idx = m%elem_index(gid)
    end if
    if (idx == 0) call err(p, 'undefined ' // kind // ' ' // to_upper(f%s) // ' (instance ' // &
                              trim(m%instances(k)%name) // ' has no ' // kind // ' ' // itoa(id) // ')')
  end function qualified_member

  !> INSTANCE.NUMBER taken apart: the instance (which must exist) and
  !> the number.
  subroutine qualified_label(p, m, f, what, k, id)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    type(field_t), intent(in) :: f
    character(len=*), intent(in) :: what
    integer, intent(out) :: k, id
    integer :: j
    j = index(f%s, '.', back=.true.)
    k = instance_index(m, to_upper(f%s(1:j - 1)))
    if (k == 0) call err(p, 'undefined instance ' // to_upper(f%s(1:j - 1)) // ' in ' // to_upper(f%s) // &
                            ' (' // what // ': a number, or INSTANCE.NUMBER)')
    id = get_int(p, field_t(f%s(j + 1:)), what)
  end subroutine qualified_label

  !> Index of the instance of that name (upper case) in m%instances, 0 if none.
  integer function instance_index(m, name)
    type(model_t), intent(in) :: m
    character(len=*), intent(in) :: name
    instance_index = 0
    if (has_instances(m)) instance_index = find_name(m%instances%name, name)
  end function instance_index

  !> Purpose: look labels and set names up in instance k from now on
  !> (0: the assembly, or a flat deck); errors then say which instance.
  subroutine set_scope(p, m, k)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(in) :: m
    integer, intent(in) :: k
    p%scope = k
    if (allocated(p%scope_note)) deallocate(p%scope_note)
    if (k == 0) return
    if (p%replaying > 0) then
      p%scope_note = ' (reading part ' // trim(m%instances(k)%part) // ' for its instance ' // &
                     trim(m%instances(k)%name) // ')'
    else
      p%scope_note = ' (in instance ' // trim(m%instances(k)%name) // ')'
    end if
  end subroutine set_scope

  !> A set name as looked up where the card stands: INSTANCE.NAME inside
  !> an instance (its part's sets), else the name (upper case).
  function scoped_name(p, m, k, name) result(s)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    integer, intent(in) :: k
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: s
    s = to_upper(name)
    if (k == 0) return
    s = trim(m%instances(k)%name) // '.' // s
    if (len(s) > name_len) call err(p, 'the name ' // s // ' is longer than ' // itoa(name_len) // ' characters')
  end function scoped_name

  !> Purpose: the name a set or surface defined here takes: INSTANCE.NAME
  !> inside an instance (or its part), else the name; upper case.
  function defined_name(p, m, name) result(s)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: s
    s = scoped_name(p, m, p%owner, name)
  end function defined_name

  !> Purpose: the id (m%node_id) of a node defined here with number id:
  !> offset + id in an instance (whose range it extends), else id.
  integer function new_node_id(p, m, id) result(gid)
    type(parser_t), intent(in) :: p
    type(model_t), intent(inout) :: m
    integer, intent(in) :: id
    gid = id
    if (p%owner == 0) then
      if (scoped_id(m, 0, id, .true.) == 0) call err(p, 'node ' // itoa(id) // ' of the assembly has the id ' // &
          'of a node of an instance; define the assembly''s nodes inside *ASSEMBLY ... *END ASSEMBLY')
      return
    end if
    associate(inst => m%instances(p%owner))
      if (id > max_id - inst%node_offset) call err(p, 'node ' // itoa(id) // ' of instance ' // trim(inst%name) // &
          ' would have the id ' // itoa(inst%node_offset) // ' + ' // itoa(id) // ', beyond ' // itoa(max_id) // &
          ' (the ids of instances follow one another)')
      gid = inst%node_offset + id
      inst%node_last = max(inst%node_last, gid)
      inst%nodes = inst%nodes + 1
    end associate
  end function new_node_id

  !> Purpose: the id (m%elem_id) of an element defined here (see new_node_id).
  integer function new_elem_id(p, m, id) result(gid)
    type(parser_t), intent(in) :: p
    type(model_t), intent(inout) :: m
    integer, intent(in) :: id
    gid = id
    if (p%owner == 0) then
      if (scoped_id(m, 0, id, .false.) == 0) call err(p, 'element ' // itoa(id) // ' of the assembly has the ' // &
          'id of an element of an instance; define the assembly''s elements inside *ASSEMBLY ... *END ASSEMBLY')
      return
    end if
    associate(inst => m%instances(p%owner))
      if (id > max_id - inst%elem_offset) call err(p, 'element ' // itoa(id) // ' of instance ' // &
          trim(inst%name) // ' would have the id ' // itoa(inst%elem_offset) // ' + ' // itoa(id) // &
          ', beyond ' // itoa(max_id) // ' (the ids of instances follow one another)')
      gid = inst%elem_offset + id
      inst%elem_last = max(inst%elem_last, gid)
      inst%elements = inst%elements + 1
    end associate
  end function new_elem_id

  !> Purpose: where a node defined here lies: inside an instance, its
  !> part's coordinates x translated by the instance's shift, then turned
  !> about the z axis through its centre; else x.
  pure function placed(p, m, x) result(y)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(2)
    real(dp) :: y(2), d(2), c, s
    y = x
    if (p%owner == 0) return
    associate(inst => m%instances(p%owner))
      y = x + inst%shift
      if (inst%angle == 0.0_dp) return
      call turn(inst%angle, c, s)
      d = y - inst%centre
      y = inst%centre + [c * d(1) - s * d(2), s * d(1) + c * d(2)]
    end associate
  end function placed

  !> Cosine and sine of an angle in degrees, exact at multiples of 90
  !> degrees (edges along the axes stay along them: no round-off in a
  !> contact normal or a face's orientation).
  pure subroutine turn(degrees, c, s)
    real(dp), intent(in) :: degrees
    real(dp), intent(out) :: c, s
    real(dp), parameter :: pi = acos(-1.0_dp)
    real(dp) :: q
    q = modulo(degrees, 360.0_dp)
    if (modulo(q, 90.0_dp) == 0.0_dp) then
      select case (nint(q / 90.0_dp))
      case (1); c = 0.0_dp; s = 1.0_dp
      case (2); c = -1.0_dp; s = 0.0_dp
      case (3); c = 0.0_dp; s = -1.0_dp
      case default; c = 1.0_dp; s = 0.0_dp
      end select
    else
      c = cos(q * pi / 180.0_dp)
      s = sin(q * pi / 180.0_dp)
    end if
  end subroutine turn

  !> A node set looked up where the card stands (p%scope: in an instance
  !> its part's set INSTANCE.NAME), 0 if there is none.
  integer function nset_index(p, m, name)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    character(len=*), intent(in) :: name
    nset_index = find_name(m%nsets(1:p%nsets)%name, scoped_name(p, m, p%scope, name))
  end function nset_index

  integer function elset_index(p, m, name)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    character(len=*), intent(in) :: name
    elset_index = find_name(m%elsets(1:p%nelsets)%name, scoped_name(p, m, p%scope, name))
  end function elset_index

  integer function need_nset(p, m, name)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    character(len=*), intent(in) :: name
    need_nset = nset_index(p, m, name)
    if (need_nset == 0 .and. elset_index(p, m, name) > 0) call err(p, 'undefined node set ' // &
        to_upper(name) // ': there is an element set of that name (gmsh writes node sets only with ' // &
        '-setnumber Mesh.SaveGroupsOfNodes 1; or define it with *NSET, NSET=' // to_upper(name) // &
        ', ELSET=' // to_upper(name) // ')')
    if (need_nset == 0) call err(p, 'undefined node set ' // to_upper(name))
  end function need_nset

  integer function need_elset(p, m, name)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    character(len=*), intent(in) :: name
    need_elset = elset_index(p, m, name)
    if (need_elset == 0 .and. nset_index(p, m, name) > 0) call err(p, 'undefined element set ' // &
        to_upper(name) // ' (there is a node set of that name)')
    if (need_elset == 0) call err(p, 'undefined element set ' // to_upper(name))
  end function need_elset

  !> Purpose: a card that names an empty set acts on nothing there; say so
  !> (file:line: warning: at the current line, the data line or the card
  !> naming the set) instead of doing nothing silently, since it is mostly
  !> a set left unfilled or the wrong set named. Set definitions (*NSET,
  !> *ELSET) do not call this: a union may well hold an empty set, and a
  !> set left empty is reported where a card uses it.
  !> Arguments:
  !>   p     parser state (its current line is the one named)
  !>   n     number of nodes, elements or faces in the set
  !>   what  'node set', 'element set' or 'surface'
  !>   name  the set's name
  !>   card  the keyword, without its '*'
  subroutine warn_empty_set(p, n, what, name, card)
    type(parser_t), intent(in) :: p
    integer, intent(in) :: n
    character(len=*), intent(in) :: what, name, card
    if (n > 0) return
    call deck_warning(p%deck, p%i, what // ' ' // trim(name) // ' is empty: *' // card // ' does nothing for it')
  end subroutine warn_empty_set

  !> A new, empty surface slot (element and node surfaces, and the node
  !> surface a *CONTACT PAIR makes of a node set).
  integer function new_surface(p, m) result(isurf)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    call grow(m%surfaces, p%nsurf + 1)
    p%nsurf = p%nsurf + 1
    isurf = p%nsurf
  end function new_surface

  !> A new, empty surface interaction slot; p%interaction points at it.
  integer function new_interaction(p) result(k)
    type(parser_t), intent(inout) :: p
    type(interaction_t), allocatable :: tmp(:)
    if (.not. allocated(p%inter)) allocate(p%inter(4))
    if (p%ninter == size(p%inter)) then
      allocate(tmp(2 * p%ninter))
      tmp(1:p%ninter) = p%inter(1:p%ninter)
      call move_alloc(tmp, p%inter)
    end if
    p%ninter = p%ninter + 1
    k = p%ninter
    p%inter(k) = interaction_t()
    p%interaction = k
  end function new_interaction

  !> Records that pair `pair` (read on line `line`) takes the penalty of
  !> the interaction `name`.
  subroutine add_pair_interaction(p, pair, line, name)
    type(parser_t), intent(inout) :: p
    integer, intent(in) :: pair, line
    character(len=*), intent(in) :: name
    type(pair_interaction_t), allocatable :: tmp(:)
    if (.not. allocated(p%pair_inter)) allocate(p%pair_inter(4))
    if (p%npair_inter == size(p%pair_inter)) then
      allocate(tmp(2 * p%npair_inter))
      tmp(1:p%npair_inter) = p%pair_inter(1:p%npair_inter)
      call move_alloc(tmp, p%pair_inter)
    end if
    p%npair_inter = p%npair_inter + 1
    p%pair_inter(p%npair_inter) = pair_interaction_t(pair=pair, line=line, name=name)
  end subroutine add_pair_interaction

  subroutine in_step(p, kw, inside)
    type(parser_t), intent(in) :: p
    type(keyword_t), intent(in) :: kw
    logical, intent(in) :: inside
    if (inside .and. p%step == 0) call err(p, '*' // kw%name // ' must be inside *STEP ... *END STEP')
    if (.not. inside .and. p%step /= 0) call err(p, '*' // kw%name // ' is model data and cannot be inside *STEP')
  end subroutine in_step

  !> Purpose: what dof d of node a, as a deck names it on *BOUNDARY,
  !> *CLOAD or *EQUATION, is in the model: kind dof_moves with the model's
  !> node ra and dof rd (1 or 2) holding it, dof_zero for a dof that a 2D
  !> model does not have and that is therefore zero (dof 3, out of the
  !> plane; at a reference node also the rotations 4 and 5 about in-plane
  !> axes; at a ROT NODE its dofs 1 and 2, the rotations about x and y),
  !> or dof_none. The in-plane rotation of a reference node of *RIGID BODY
  !> or *COUPLING (dof 6, Abaqus) and of a ROT NODE (dof 3, CalculiX) is
  !> dof 1 of its rotation node.
  pure subroutine deck_dof(p, a, d, kind, ra, rd)
    type(parser_t), intent(in) :: p
    integer, intent(in) :: a, d
    integer, intent(out) :: kind, ra, rd
    integer :: rot
    logical :: is_rot
    ra = a
    rd = d
    rot = 0
    if (allocated(p%ref_rotation)) then
      if (a <= size(p%ref_rotation)) rot = p%ref_rotation(a)
    end if
    is_rot = .false.
    if (allocated(p%is_rot_node)) then
      if (a <= size(p%is_rot_node)) is_rot = p%is_rot_node(a)
    end if
    if (is_rot) then
      select case (d)
      case (1, 2); kind = dof_zero
      case (3); kind = dof_moves; rd = 1
      case default; kind = dof_none
      end select
    else
      select case (d)
      case (1, 2); kind = dof_moves
      case (3); kind = dof_zero
      case (4, 5)
        kind = dof_none
        if (rot > 0) kind = dof_zero
      case (6)
        kind = dof_none
        if (rot > 0) then
          kind = dof_moves
          ra = rot
          rd = 1
        end if
      case default; kind = dof_none
      end select
    end if
  end subroutine deck_dof

  !> Purpose: remembers the current line as the first naming node a on a
  !> *BOUNDARY, *CLOAD or *EQUATION (a later *RIGID BODY may not make such
  !> a node its ROT NODE: its dofs would change meaning).
  subroutine note_named(p, a)
    type(parser_t), intent(inout) :: p
    integer, intent(in) :: a
    call grow(p%named_line, a, fill=0)
    if (p%named_line(a) == 0) p%named_line(a) = p%i
  end subroutine note_named

  !> Purpose: the hint added to a message about dof d (4..6) of a node
  !> that has no rotation: where rotations come from.
  pure function rotation_hint(d) result(s)
    integer, intent(in) :: d
    character(len=:), allocatable :: s
    s = ''
    if (d >= 4 .and. d <= 6) s = '; rotations (dof 6 in the plane) exist only at the reference node of a ' // &
      '*RIGID BODY or *COUPLING defined before this line (at a ROT NODE: dof 3)'
  end function rotation_hint

  !> Purpose: the data line of a procedure card (*STATIC, *HEAT TRANSFER):
  !> initial increment, time period, minimum and maximum increment
  !> (CalculiX's fifth field, the initial increment of CFD, is read and
  !> has no use here), into s; without a line 1, 1 and no bounds. The
  !> initial increment is cut to the period.
  !> Arguments: card the card's name for the messages; s the step.
  subroutine read_time_line(p, card, s)
    type(parser_t), intent(inout) :: p
    character(len=*), intent(in) :: card
    type(step_t), intent(inout) :: s
    type(field_t), allocatable :: f(:)
    integer :: n
    real(dp) :: cfd
    s%dt = 1.0_dp
    s%period = 1.0_dp
    s%dt_min = 0.0_dp
    s%dt_max = 0.0_dp
    if (.not. next_data(p)) return
    call split_fields(line_text(p), f, n)
    if (n > 5) call err(p, card // ' data line needs: initial increment, time period[, min, max]')
    if (len(f(1)%s) > 0) s%dt = get_real(p, f(1), 'initial time increment')
    if (n >= 2) then
      if (len(f(2)%s) > 0) s%period = get_real(p, f(2), 'time period')
    end if
    if (n >= 3) then
      if (len(f(3)%s) > 0) s%dt_min = get_real(p, f(3), 'minimum time increment')
    end if
    if (n >= 4) then
      if (len(f(4)%s) > 0) s%dt_max = get_real(p, f(4), 'maximum time increment')
    end if
    if (n == 5) then
      if (len(f(5)%s) > 0) cfd = get_real(p, f(5), 'initial CFD time increment')
    end if
    if (s%dt <= 0.0_dp .or. s%period <= 0.0_dp) call err(p, 'time increment and period must be positive')
    if (s%dt_min < 0.0_dp .or. s%dt_max < 0.0_dp) call err(p, 'the minimum and maximum time increments ' // &
                                                            'must not be negative')
    if (s%dt > s%period) s%dt = s%period
    if (s%dt_max > 0.0_dp .and. s%dt_min > s%dt_max) call err(p, 'the minimum time increment exceeds the maximum')
  end subroutine read_time_line

  !> Nodes named by the first field of a data line (*BOUNDARY, *CLOAD, a
  !> temperature, *CFLUX, ...), and the node set they came from (0 for a single node); an empty
  !> set is warned about on the line of `card`.
  subroutine target_nodes(p, m, s, card, nodes, iset)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    character(len=*), intent(in) :: s, card
    integer, allocatable, intent(out) :: nodes(:)
    integer, intent(out) :: iset
    type(field_t) :: f
    iset = 0
    if (is_label(s)) then
      f%s = s
      nodes = [node_ref(p, m, f, 'node')]
    else
      if (len(s) == 0) call err(p, 'missing node or node set')
      iset = need_nset(p, m, s)
      nodes = m%nsets(iset)%items
      call warn_empty_set(p, size(nodes), 'node set', m%nsets(iset)%name, card)
    end if
  end subroutine target_nodes

  !> The amplitude named by AMPLITUDE= (0 if none).
  integer function amplitude_param(p, m, kw)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    type(keyword_t), intent(in) :: kw
    amplitude_param = 0
    if (.not. has_param(kw, 'AMPLITUDE')) return
    amplitude_param = find_name(m%amplitudes(1:p%namp)%name, to_upper(param_value(kw, 'AMPLITUDE')))
    if (amplitude_param == 0) call err(p, 'undefined amplitude ' // to_upper(param_value(kw, 'AMPLITUDE')))
  end function amplitude_param
end module deck_cursor
