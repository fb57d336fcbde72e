!> Turns the lines of a keyword deck into a model. One handler per
!> keyword; every handler validates its parameters and data lines and stops
!> with file:line on the first problem.
module deck_parser
  use kinds, only: dp, name_len
  use strings, only: to_upper, split_fields, parse_real, parse_int, field_t, itoa
  use deck_input, only: deck_t, keyword_t, read_deck, parse_keyword, deck_error, &
                        deck_warning, param_value, has_param, is_keyword
  use model
  use element_catalogue, only: catalogue, max_nodes, find_element_type, shape_line2
  use mesh_topology, only: build_topology, edge_owner
  use solver_codes, only: solver_skyline, solver_cholmod, solver_umfpack, order_natural, order_rcm, &
                           order_amd, order_metis
  implicit none
  private
  public :: read_model

  integer, parameter :: max_id = 100000000

  !> Parser state that only lives while reading.
  type :: parser_t
    type(deck_t) :: deck
    integer :: i = 0             ! current line
    integer :: step = 0          ! current step, 0 outside *STEP
    integer :: step_line = 0
    integer :: material = 0      ! material that *ELASTIC applies to
    integer :: nsets = 0, nelsets = 0, nsurf = 0, nmat = 0, nsec = 0, namp = 0
    integer :: nsteps = 0, npairs = 0, nmbc = 0
  end type parser_t

contains

  subroutine read_model(path, m)
    character(len=*), intent(in) :: path
    type(model_t), intent(out) :: m
    type(parser_t) :: p
    type(keyword_t) :: kw

    call read_deck(path, p%deck)
    m%deck_name = path
    m%heading = ''
    allocate(m%node_id(1024), m%x(2, 1024), m%elem_id(1024), m%etype(1024), &
             m%conn(max_nodes, 1024), m%elem_src(1024), m%node_index(0), m%elem_index(0))
    allocate(m%nsets(16), m%elsets(16), m%surfaces(8), m%materials(4), m%sections(8), &
             m%amplitudes(4), m%steps(4), m%pairs(4), m%model_bcs(64))

    p%i = 1
    do while (p%i <= p%deck%n)
      if (.not. is_keyword(line_text(p))) call err(p, 'data line where a keyword line was expected')
      call parse_keyword(line_text(p), kw)
      call dispatch(p, m, kw)
      p%i = p%i + 1
    end do
    if (p%step /= 0) then
      p%i = p%step_line
      call err(p, '*STEP without *END STEP')
    end if

    m%nsets = m%nsets(1:p%nsets)
    m%elsets = m%elsets(1:p%nelsets)
    m%surfaces = m%surfaces(1:p%nsurf)
    m%materials = m%materials(1:p%nmat)
    m%sections = m%sections(1:p%nsec)
    m%amplitudes = m%amplitudes(1:p%namp)
    m%steps = m%steps(1:p%nsteps)
    m%pairs = m%pairs(1:p%npairs)
    m%model_bcs = m%model_bcs(1:p%nmbc)
    m%node_id = m%node_id(1:m%nn)
    m%x = m%x(:, 1:m%nn)
    m%elem_id = m%elem_id(1:m%ne)
    m%etype = m%etype(1:m%ne)
    m%conn = m%conn(:, 1:m%ne)
    m%elem_src = m%elem_src(1:m%ne)
    call check_model(p, m)
    call build_topology(m%nn, m%ne, m%etype, m%conn, m%topo)
  end subroutine read_model

  ! ------------------------------------------------------------------ helpers

  function line_text(p) result(t)
    type(parser_t), intent(in) :: p
    character(len=:), allocatable :: t
    t = p%deck%lines(p%i)%text
  end function line_text

  subroutine err(p, msg)
    type(parser_t), intent(in) :: p
    character(len=*), intent(in) :: msg
    associate(l => p%deck%lines(p%i))
      call deck_error(p%deck, l%file, l%line, msg, l%text)
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

  real(dp) function get_real(p, f, what)
    type(parser_t), intent(in) :: p
    type(field_t), intent(in) :: f
    character(len=*), intent(in) :: what
    logical :: ok
    call parse_real(f%s, get_real, ok)
    if (.not. ok) then
      if (len(f%s) == 0) call err(p, 'missing ' // what)
      call err(p, '"' // f%s // '" is not a number (' // what // ')')
    end if
  end function get_real

  integer function get_int(p, f, what)
    type(parser_t), intent(in) :: p
    type(field_t), intent(in) :: f
    character(len=*), intent(in) :: what
    logical :: ok
    call parse_int(f%s, get_int, ok)
    if (.not. ok) then
      if (len(f%s) == 0) call err(p, 'missing ' // what)
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

  integer function node_of(p, m, id)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    integer, intent(in) :: id
    character(len=16) :: s
    node_of = 0
    if (id >= 1 .and. id <= size(m%node_index)) node_of = m%node_index(id)
    if (node_of == 0) then
      write(s, '(i0)') id
      call err(p, 'undefined node ' // trim(s))
    end if
  end function node_of

  integer function elem_of(p, m, id)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    integer, intent(in) :: id
    character(len=16) :: s
    elem_of = 0
    if (id >= 1 .and. id <= size(m%elem_index)) elem_of = m%elem_index(id)
    if (elem_of == 0) then
      write(s, '(i0)') id
      call err(p, 'undefined element ' // trim(s))
    end if
  end function elem_of

  logical function is_int(s)
    character(len=*), intent(in) :: s
    integer :: k
    call parse_int(s, k, is_int)
  end function is_int

  integer function nset_index(p, m, name)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    character(len=*), intent(in) :: name
    nset_index = find_name(m%nsets(1:p%nsets)%name, to_upper(name))
  end function nset_index

  integer function elset_index(p, m, name)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    character(len=*), intent(in) :: name
    elset_index = find_name(m%elsets(1:p%nelsets)%name, to_upper(name))
  end function elset_index

  integer function need_nset(p, m, name)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    character(len=*), intent(in) :: name
    need_nset = nset_index(p, m, name)
    if (need_nset == 0) call err(p, 'undefined node set ' // to_upper(name))
  end function need_nset

  integer function need_elset(p, m, name)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    character(len=*), intent(in) :: name
    need_elset = elset_index(p, m, name)
    if (need_elset == 0) call err(p, 'undefined element set ' // to_upper(name))
  end function need_elset

  subroutine in_step(p, kw, inside)
    type(parser_t), intent(in) :: p
    type(keyword_t), intent(in) :: kw
    logical, intent(in) :: inside
    if (inside .and. p%step == 0) call err(p, '*' // kw%name // ' must be inside *STEP ... *END STEP')
    if (.not. inside .and. p%step /= 0) call err(p, '*' // kw%name // ' is model data and cannot be inside *STEP')
  end subroutine in_step

  ! ----------------------------------------------------------------- dispatch

  subroutine dispatch(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    select case (kw%name)
    case ('HEADING')
      call allow_params(p, kw, '')
      if (next_data(p)) m%heading = trim(adjustl(line_text(p)))
      do while (next_data(p))
      end do
    case ('NODE');          call in_step(p, kw, .false.); call read_nodes(p, m, kw)
    case ('ELEMENT');       call in_step(p, kw, .false.); call read_elements(p, m, kw)
    case ('NSET');          call in_step(p, kw, .false.); call read_nset(p, m, kw)
    case ('ELSET');         call in_step(p, kw, .false.); call read_elset(p, m, kw)
    case ('SURFACE');       call in_step(p, kw, .false.); call read_surface(p, m, kw)
    case ('MATERIAL');      call in_step(p, kw, .false.); call read_material(p, m, kw)
    case ('ELASTIC');       call in_step(p, kw, .false.); call read_elastic(p, m, kw)
    case ('SOLID SECTION'); call in_step(p, kw, .false.); call read_section(p, m, kw)
    case ('AMPLITUDE');     call read_amplitude(p, m, kw)
    case ('BOUNDARY');      call read_boundary(p, m, kw)
    case ('CLOAD');         call in_step(p, kw, .true.); call read_cload(p, m, kw)
    case ('STEP');          call read_step(p, m, kw)
    case ('STATIC');        call in_step(p, kw, .true.); call read_static(p, m, kw)
    case ('END STEP')
      call in_step(p, kw, .true.)
      call allow_params(p, kw, '')
      call no_data(p, kw)
      p%step = 0
    case ('NODE PRINT', 'EL PRINT', 'NODE FILE', 'EL FILE')
      call in_step(p, kw, .true.)
      call read_request(p, m, kw)
    case ('SOLVER');        call read_solver(p, m, kw)
    case ('CONTACT PAIR');  call in_step(p, kw, .false.); call read_contact_pair(p, m, kw)
    case ('CONTACT CONTROLS'); call read_contact_controls(p, m, kw)
    case ('OUTPUT', 'NODE OUTPUT', 'ELEMENT OUTPUT', 'CONTACT OUTPUT', 'CONTACT PRINT', &
          'CONTACT FILE', 'ENERGY PRINT', 'ENERGY FILE', 'SECTION PRINT', 'PREPRINT', &
          'RESTART', 'MONITOR', 'DENSITY')
      ! Pure output requests (and a density, which a static run without
      ! gravity never uses) cannot change the answer: warn and skip.
      call deck_warning(p%deck, p%i, '*' // kw%name // ' is not implemented in cfe2d and is ignored')
      do while (next_data(p))
      end do
    case default
      call err(p, 'keyword *' // kw%name // ' is not implemented in cfe2d')
    end select
  end subroutine dispatch

  ! ---------------------------------------------------------------- mesh data

  subroutine read_nodes(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    integer :: n, id, iset, nitems
    integer, allocatable :: items(:)
    real(dp) :: z
    call allow_params(p, kw, 'NSET,SYSTEM')
    if (has_param(kw, 'SYSTEM')) then
      if (to_upper(param_value(kw, 'SYSTEM')) /= 'R') call err(p, 'only SYSTEM=R (rectangular) is implemented')
    end if
    nitems = 0
    do while (next_data(p))
      call split_fields(line_text(p), f, n)
      if (n < 3) call err(p, '*NODE data line needs: node id, x, y')
      if (n > 4) call err(p, '*NODE data line has more than 3 coordinates')
      id = get_int(p, f(1), 'node id')
      if (id < 1 .or. id > max_id) call err(p, 'node id out of range 1..100000000')
      call grow_node_index(m, id)
      if (m%node_index(id) /= 0) call err(p, 'duplicate node id ' // f(1)%s)
      if (m%nn == size(m%node_id)) call grow_nodes(m)
      m%nn = m%nn + 1
      m%node_id(m%nn) = id
      m%x(1, m%nn) = get_real(p, f(2), 'x coordinate')
      m%x(2, m%nn) = get_real(p, f(3), 'y coordinate')
      ! gmsh writes z = 0 for planar meshes; it plays no part in 2D.
      if (n == 4) z = get_real(p, f(4), 'z coordinate')
      m%node_index(id) = m%nn
      call append_int(items, nitems, m%nn)
    end do
    if (nitems == 0) call err(p, 'missing data line (*NODE without nodes)')
    if (has_param(kw, 'NSET')) then
      iset = add_nset(p, m, required_param(p, kw, 'NSET'))
      call extend_set(m%nsets(iset)%items, items(1:nitems))
    end if
  end subroutine read_nodes

  subroutine grow_node_index(m, id)
    type(model_t), intent(inout) :: m
    integer, intent(in) :: id
    integer, allocatable :: tmp(:)
    if (id <= size(m%node_index)) return
    allocate(tmp(max(2 * size(m%node_index), id, 1024)))
    tmp = 0
    tmp(1:size(m%node_index)) = m%node_index
    call move_alloc(tmp, m%node_index)
  end subroutine grow_node_index

  subroutine grow_nodes(m)
    type(model_t), intent(inout) :: m
    integer, allocatable :: itmp(:)
    real(dp), allocatable :: xtmp(:, :)
    allocate(itmp(2 * m%nn), xtmp(2, 2 * m%nn))
    itmp(1:m%nn) = m%node_id(1:m%nn)
    xtmp(:, 1:m%nn) = m%x(:, 1:m%nn)
    call move_alloc(itmp, m%node_id)
    call move_alloc(xtmp, m%x)
  end subroutine grow_nodes

  subroutine grow_elements(m)
    type(model_t), intent(inout) :: m
    integer, allocatable :: itmp(:), ttmp(:), ctmp(:, :)
    type(src_t), allocatable :: stmp(:)
    integer :: n
    n = m%ne
    allocate(itmp(2 * n), ttmp(2 * n), ctmp(max_nodes, 2 * n), stmp(2 * n))
    itmp(1:n) = m%elem_id(1:n)
    ttmp(1:n) = m%etype(1:n)
    ctmp(:, 1:n) = m%conn(:, 1:n)
    stmp(1:n) = m%elem_src(1:n)
    call move_alloc(itmp, m%elem_id)
    call move_alloc(ttmp, m%etype)
    call move_alloc(ctmp, m%conn)
    call move_alloc(stmp, m%elem_src)
  end subroutine grow_elements

  subroutine read_elements(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    character(len=:), allocatable :: tname
    integer :: et, nen, n, id, k, iset, nitems
    integer, allocatable :: items(:), tmp(:)
    call allow_params(p, kw, 'TYPE,ELSET')
    tname = to_upper(required_param(p, kw, 'TYPE'))
    et = find_element_type(tname)
    if (et == 0) call err(p, 'element type ' // tname // ' is not implemented (' // catalogue_names() // ')')
    nen = catalogue(et)%nodes
    nitems = 0
    do while (next_data(p))
      call split_fields(line_text(p), f, n)
      if (n /= nen + 1) then
        call err(p, 'element ' // tname // ' needs an id and ' // achar(iachar('0') + nen) // ' nodes')
      end if
      id = get_int(p, f(1), 'element id')
      if (id < 1 .or. id > max_id) call err(p, 'element id out of range 1..100000000')
      if (id > size(m%elem_index)) then
        allocate(tmp(max(2 * size(m%elem_index), id, 1024)))
        tmp = 0
        tmp(1:size(m%elem_index)) = m%elem_index
        call move_alloc(tmp, m%elem_index)
      end if
      if (m%elem_index(id) /= 0) call err(p, 'duplicate element id ' // f(1)%s)
      if (m%ne == size(m%elem_id)) call grow_elements(m)
      m%ne = m%ne + 1
      m%elem_id(m%ne) = id
      m%etype(m%ne) = et
      m%conn(:, m%ne) = 0
      do k = 1, nen
        m%conn(k, m%ne) = node_of(p, m, get_int(p, f(k + 1), 'node of element'))
      end do
      do k = 2, nen
        if (any(m%conn(1:k - 1, m%ne) == m%conn(k, m%ne))) call err(p, 'element uses the same node twice')
      end do
      m%elem_src(m%ne)%line = p%i
      m%elem_index(id) = m%ne
      call append_int(items, nitems, m%ne)
    end do
    if (nitems == 0) call err(p, 'missing data line (*ELEMENT without elements)')
    if (has_param(kw, 'ELSET')) then
      iset = add_elset(p, m, param_value(kw, 'ELSET'))
      call extend_set(m%elsets(iset)%items, items(1:nitems))
    end if
  end subroutine read_elements

  ! --------------------------------------------------------------------- sets

  !> Existing set of that name (a repeated *NSET extends it) or a new one.
  integer function add_nset(p, m, name) result(iset)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    character(len=*), intent(in) :: name
    type(node_set_t), allocatable :: tmp(:)
    iset = nset_index(p, m, name)
    if (iset > 0) return
    if (len_trim(name) > name_len) call err(p, 'set name longer than 80 characters')
    if (p%nsets == size(m%nsets)) then
      allocate(tmp(2 * p%nsets))
      tmp(1:p%nsets) = m%nsets(1:p%nsets)
      call move_alloc(tmp, m%nsets)
    end if
    p%nsets = p%nsets + 1
    iset = p%nsets
    m%nsets(iset)%name = to_upper(name)
    allocate(m%nsets(iset)%items(0))
  end function add_nset

  integer function add_elset(p, m, name) result(iset)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    character(len=*), intent(in) :: name
    type(elem_set_t), allocatable :: tmp(:)
    iset = elset_index(p, m, name)
    if (iset > 0) return
    if (len_trim(name) > name_len) call err(p, 'set name longer than 80 characters')
    if (p%nelsets == size(m%elsets)) then
      allocate(tmp(2 * p%nelsets))
      tmp(1:p%nelsets) = m%elsets(1:p%nelsets)
      call move_alloc(tmp, m%elsets)
    end if
    p%nelsets = p%nelsets + 1
    iset = p%nelsets
    m%elsets(iset)%name = to_upper(name)
    allocate(m%elsets(iset)%items(0))
  end function add_elset

  !> Append items not yet in the set, keeping the order of first mention.
  subroutine extend_set(set, items)
    integer, allocatable, intent(inout) :: set(:)
    integer, intent(in) :: items(:)
    integer, allocatable :: all(:)
    logical, allocatable :: seen(:)
    integer :: k, n, top
    all = [set, items]
    if (size(all) == 0) return
    top = maxval(all)
    allocate(seen(top))
    seen = .false.
    n = 0
    do k = 1, size(all)
      if (seen(all(k))) cycle
      seen(all(k)) = .true.
      n = n + 1
      all(n) = all(k)
    end do
    set = all(1:n)
  end subroutine extend_set

  !> Data lines of *NSET/*ELSET/*BOUNDARY-like lists: ids, set names, or
  !> (GENERATE) first, last, increment.
  subroutine read_id_list(p, m, generate, nodes, items, nitems)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(in) :: m
    logical, intent(in) :: generate, nodes
    integer, allocatable, intent(inout) :: items(:)
    integer, intent(inout) :: nitems
    type(field_t), allocatable :: f(:)
    integer :: n, k, a, b, c, id, s
    call split_fields(line_text(p), f, n)
    if (generate) then
      if (n < 2 .or. n > 3) call err(p, 'GENERATE data line needs: first, last[, increment]')
      a = get_int(p, f(1), 'first id')
      b = get_int(p, f(2), 'last id')
      c = 1
      if (n == 3) c = get_int(p, f(3), 'increment')
      if (c <= 0 .or. b < a) call err(p, 'GENERATE needs first <= last and a positive increment')
      do id = a, b, c
        if (nodes) then
          call append_int(items, nitems, node_of(p, m, id))
        else
          call append_int(items, nitems, elem_of(p, m, id))
        end if
      end do
      return
    end if
    do k = 1, n
      if (len(f(k)%s) == 0) call err(p, 'empty entry in list')
      if (is_int(f(k)%s)) then
        id = get_int(p, f(k), 'id')
        if (nodes) then
          call append_int(items, nitems, node_of(p, m, id))
        else
          call append_int(items, nitems, elem_of(p, m, id))
        end if
      else if (nodes) then
        s = need_nset(p, m, f(k)%s)
        do id = 1, size(m%nsets(s)%items)
          call append_int(items, nitems, m%nsets(s)%items(id))
        end do
      else
        s = need_elset(p, m, f(k)%s)
        do id = 1, size(m%elsets(s)%items)
          call append_int(items, nitems, m%elsets(s)%items(id))
        end do
      end if
    end do
  end subroutine read_id_list

  subroutine read_nset(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    integer :: iset, nitems, es, k, j
    integer, allocatable :: items(:)
    character(len=:), allocatable :: name
    call allow_params(p, kw, 'NSET,GENERATE,ELSET,UNSORTED,INTERNAL')
    name = required_param(p, kw, 'NSET')
    nitems = 0
    allocate(items(64))
    if (has_param(kw, 'ELSET')) then
      ! The nodes of an element set, e.g. of gmsh's line elements.
      es = need_elset(p, m, param_value(kw, 'ELSET'))
      do k = 1, size(m%elsets(es)%items)
        associate(e => m%elsets(es)%items(k))
          do j = 1, elem_nodes(m, e)
            call append_int(items, nitems, m%conn(j, e))
          end do
        end associate
      end do
      call no_data(p, kw)
    else
      do while (next_data(p))
        call read_id_list(p, m, has_param(kw, 'GENERATE'), .true., items, nitems)
      end do
    end if
    iset = add_nset(p, m, name)
    call extend_set(m%nsets(iset)%items, items(1:nitems))
  end subroutine read_nset

  subroutine read_elset(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    integer :: iset, nitems
    integer, allocatable :: items(:)
    character(len=:), allocatable :: name
    call allow_params(p, kw, 'ELSET,GENERATE,UNSORTED,INTERNAL')
    name = required_param(p, kw, 'ELSET')
    nitems = 0
    allocate(items(64))
    do while (next_data(p))
      call read_id_list(p, m, has_param(kw, 'GENERATE'), .false., items, nitems)
    end do
    iset = add_elset(p, m, name)
    call extend_set(m%elsets(iset)%items, items(1:nitems))
  end subroutine read_elset

  !> Local edge of a continuum element that joins nodes a and b; used to
  !> turn gmsh line elements into faces. The edge table is rebuilt when
  !> elements were added since it was last built.
  subroutine owner_edge(p, m, a, b, e, k)
    type(parser_t), intent(in) :: p
    type(model_t), intent(inout) :: m
    integer, intent(in) :: a, b
    integer, intent(out) :: e, k
    if (m%topo%ne /= m%ne) call build_topology(m%nn, m%ne, m%etype, m%conn, m%topo)
    call edge_owner(m%topo, a, b, e, k)
    if (e == 0) call err(p, 'line element is not an edge of any solid element')
    if (m%topo%neighbour(k, e) > 0) call err(p, 'line element lies between two solid elements, not on a boundary')
  end subroutine owner_edge

  !> The element type names of the catalogue, for error messages.
  function catalogue_names() result(s)
    character(len=:), allocatable :: s
    integer :: it
    s = trim(catalogue(1)%name)
    do it = 2, size(catalogue)
      s = s // ', ' // trim(catalogue(it)%name)
    end do
  end function catalogue_names

  subroutine read_surface(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    character(len=:), allocatable :: name, stype, face
    integer :: n, k, e, edge, ne, nedge, nn, es, ns, a, b, ee
    integer, allocatable :: elems(:), edges(:), nodes(:), list(:)
    type(surface_t), allocatable :: tmp(:)
    call allow_params(p, kw, 'NAME,TYPE,INTERNAL')
    name = to_upper(required_param(p, kw, 'NAME'))
    stype = 'ELEMENT'
    if (has_param(kw, 'TYPE')) stype = to_upper(param_value(kw, 'TYPE'))
    if (stype /= 'ELEMENT' .and. stype /= 'NODE') call err(p, 'surface TYPE must be ELEMENT or NODE')
    if (find_name(m%surfaces(1:p%nsurf)%name, name) > 0) call err(p, 'duplicate surface ' // name)
    ne = 0
    nedge = 0
    nn = 0
    allocate(elems(16), edges(16), nodes(16))
    do while (next_data(p))
      call split_fields(line_text(p), f, n)
      if (stype == 'NODE') then
        if (n > 2) call err(p, 'node surface data line needs: node or node set[, area]')
        if (is_int(f(1)%s)) then
          call append_int(nodes, nn, node_of(p, m, get_int(p, f(1), 'node')))
        else
          ns = need_nset(p, m, f(1)%s)
          do k = 1, size(m%nsets(ns)%items)
            call append_int(nodes, nn, m%nsets(ns)%items(k))
          end do
        end if
        cycle
      end if
      if (n > 2) call err(p, 'element surface data line needs: element or element set[, face S1..S4]')
      if (is_int(f(1)%s)) then
        list = [elem_of(p, m, get_int(p, f(1), 'element'))]
      else
        es = need_elset(p, m, f(1)%s)
        list = m%elsets(es)%items
      end if
      face = ''
      if (n == 2) face = to_upper(f(2)%s)
      do k = 1, size(list)
        e = list(k)
        if (catalogue(m%etype(e))%shape == shape_line2) then
          if (len(face) > 0) call err(p, 'a face id is not allowed for line elements')
          call owner_edge(p, m, m%conn(1, e), m%conn(2, e), ee, edge)
          call append_int(elems, ne, ee)
          call append_int(edges, nedge, edge)
        else
          if (len(face) == 0) call err(p, 'solid elements need a face id S1..S4')
          edge = 0
          if (len(face) == 2 .and. face(1:1) == 'S') edge = index('123456789', face(2:2))
          if (edge == 0 .or. edge > catalogue(m%etype(e))%nedges) &
            call err(p, 'face ' // face // ' does not exist for ' // trim(catalogue(m%etype(e))%name))
          call append_int(elems, ne, e)
          call append_int(edges, nedge, edge)
        end if
      end do
    end do
    if (ne == 0 .and. nn == 0) call err(p, 'missing data line (empty surface)')
    if (p%nsurf == size(m%surfaces)) then
      allocate(tmp(2 * p%nsurf))
      tmp(1:p%nsurf) = m%surfaces(1:p%nsurf)
      call move_alloc(tmp, m%surfaces)
    end if
    p%nsurf = p%nsurf + 1
    associate(s => m%surfaces(p%nsurf))
      s%name = name
      if (stype == 'NODE') then
        s%kind = surf_node
        allocate(s%elem(0), s%edge(0))
        s%nodes = nodes(1:nn)
        call extend_set(s%nodes, [integer ::])
      else
        s%kind = surf_element
        s%elem = elems(1:ne)
        s%edge = edges(1:ne)
        ! Node list of the surface: the ends of its edges, once each.
        allocate(s%nodes(0))
        do k = 1, ne
          call edge_nodes(m, s%elem(k), s%edge(k), a, b)
          call extend_set(s%nodes, [a, b])
        end do
      end if
    end associate
  end subroutine read_surface

  ! ------------------------------------------------- materials and sections

  subroutine read_material(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    character(len=:), allocatable :: name
    type(material_t), allocatable :: tmp(:)
    call allow_params(p, kw, 'NAME')
    name = to_upper(required_param(p, kw, 'NAME'))
    if (find_name(m%materials(1:p%nmat)%name, name) > 0) call err(p, 'duplicate material ' // name)
    call no_data(p, kw)
    if (p%nmat == size(m%materials)) then
      allocate(tmp(2 * p%nmat))
      tmp(1:p%nmat) = m%materials(1:p%nmat)
      call move_alloc(tmp, m%materials)
    end if
    p%nmat = p%nmat + 1
    m%materials(p%nmat)%name = name
    m%materials(p%nmat)%src%line = p%i
    p%material = p%nmat
  end subroutine read_material

  subroutine read_elastic(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    integer :: n
    call allow_params(p, kw, 'TYPE')
    if (has_param(kw, 'TYPE')) then
      if (to_upper(param_value(kw, 'TYPE')) /= 'ISOTROPIC') call err(p, 'only TYPE=ISOTROPIC is implemented')
    end if
    if (p%material == 0) call err(p, '*ELASTIC outside a *MATERIAL')
    call require_data(p, 'E, nu')
    call split_fields(line_text(p), f, n)
    if (n < 2) call err(p, '*ELASTIC data line needs: E, nu')
    if (n > 3) call err(p, 'temperature-dependent *ELASTIC data is not implemented')
    associate(mat => m%materials(p%material))
      mat%e = get_real(p, f(1), 'Young''s modulus')
      mat%nu = get_real(p, f(2), 'Poisson''s ratio')
      if (mat%e <= 0.0_dp) call err(p, 'Young''s modulus must be positive')
      if (mat%nu <= -1.0_dp .or. mat%nu >= 0.5_dp) call err(p, 'Poisson''s ratio must lie in (-1, 0.5)')
      mat%has_elastic = .true.
    end associate
    if (next_data(p)) call err(p, 'temperature-dependent *ELASTIC data is not implemented')
  end subroutine read_elastic

  subroutine read_section(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    type(section_t), allocatable :: tmp(:)
    integer :: n
    call allow_params(p, kw, 'ELSET,MATERIAL')
    if (p%nsec == size(m%sections)) then
      allocate(tmp(2 * p%nsec))
      tmp(1:p%nsec) = m%sections(1:p%nsec)
      call move_alloc(tmp, m%sections)
    end if
    p%nsec = p%nsec + 1
    associate(s => m%sections(p%nsec))
      s%elset = need_elset(p, m, required_param(p, kw, 'ELSET'))
      s%material_name = to_upper(required_param(p, kw, 'MATERIAL'))
      s%src%line = p%i
      s%thickness = 1.0_dp
      if (next_data(p)) then
        call split_fields(line_text(p), f, n)
        if (len(f(1)%s) > 0) s%thickness = get_real(p, f(1), 'thickness')
        if (s%thickness <= 0.0_dp) call err(p, 'section thickness must be positive')
      end if
    end associate
  end subroutine read_section

  ! ------------------------------------------------------- loads and steps

  subroutine read_amplitude(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    type(amplitude_t), allocatable :: tmp(:)
    real(dp), allocatable :: t(:), a(:)
    character(len=:), allocatable :: name, tm
    integer :: n, k, np
    call allow_params(p, kw, 'NAME,TIME,DEFINITION,VALUE')
    name = to_upper(required_param(p, kw, 'NAME'))
    if (find_name(m%amplitudes(1:p%namp)%name, name) > 0) call err(p, 'duplicate amplitude ' // name)
    if (has_param(kw, 'DEFINITION')) then
      if (to_upper(param_value(kw, 'DEFINITION')) /= 'TABULAR') call err(p, 'only DEFINITION=TABULAR is implemented')
    end if
    if (has_param(kw, 'VALUE')) then
      if (to_upper(param_value(kw, 'VALUE')) /= 'ABSOLUTE') call err(p, 'only VALUE=ABSOLUTE is implemented')
    end if
    if (p%namp == size(m%amplitudes)) then
      allocate(tmp(2 * p%namp))
      tmp(1:p%namp) = m%amplitudes(1:p%namp)
      call move_alloc(tmp, m%amplitudes)
    end if
    p%namp = p%namp + 1
    m%amplitudes(p%namp)%name = name
    m%amplitudes(p%namp)%time = amp_step_time
    if (has_param(kw, 'TIME')) then
      tm = to_upper(param_value(kw, 'TIME'))
      if (tm == 'TOTAL TIME') then
        m%amplitudes(p%namp)%time = amp_total_time
      else if (tm /= 'STEP TIME') then
        call err(p, 'TIME must be STEP TIME or TOTAL TIME')
      end if
    end if
    allocate(t(0), a(0))
    np = 0
    do while (next_data(p))
      call split_fields(line_text(p), f, n)
      if (mod(n, 2) /= 0) call err(p, '*AMPLITUDE data come in pairs: time, value')
      do k = 1, n, 2
        t = [t, get_real(p, f(k), 'time')]
        a = [a, get_real(p, f(k + 1), 'amplitude value')]
        np = np + 1
        if (np > 1) then
          if (t(np) <= t(np - 1)) call err(p, 'amplitude times must increase')
        end if
      end do
    end do
    if (np == 0) call err(p, 'missing data line (time, value pairs)')
    m%amplitudes(p%namp)%t = t
    m%amplitudes(p%namp)%a = a
  end subroutine read_amplitude

  integer function amplitude_param(p, m, kw)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    type(keyword_t), intent(in) :: kw
    amplitude_param = 0
    if (.not. has_param(kw, 'AMPLITUDE')) return
    amplitude_param = find_name(m%amplitudes(1:p%namp)%name, to_upper(param_value(kw, 'AMPLITUDE')))
    if (amplitude_param == 0) call err(p, 'undefined amplitude ' // to_upper(param_value(kw, 'AMPLITUDE')))
  end function amplitude_param

  !> Nodes named by the first field of a *BOUNDARY or *CLOAD line.
  subroutine target_nodes(p, m, s, nodes, iset)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    character(len=*), intent(in) :: s
    integer, allocatable, intent(out) :: nodes(:)
    integer, intent(out) :: iset
    type(field_t) :: f
    iset = 0
    if (is_int(s)) then
      f%s = s
      nodes = [node_of(p, m, get_int(p, f, 'node'))]
    else
      if (len(s) == 0) call err(p, 'missing node or node set')
      iset = need_nset(p, m, s)
      nodes = m%nsets(iset)%items
    end if
  end subroutine target_nodes

  subroutine read_boundary(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    type(bc_t), allocatable :: new(:)
    integer, allocatable :: nodes(:)
    integer :: n, k, d, d1, d2, iset, amp, nnew
    real(dp) :: v
    character(len=:), allocatable :: op, word
    call allow_params(p, kw, 'OP,AMPLITUDE,TYPE')
    if (has_param(kw, 'TYPE')) then
      if (to_upper(param_value(kw, 'TYPE')) /= 'DISPLACEMENT') call err(p, 'only TYPE=DISPLACEMENT is implemented')
    end if
    op = 'MOD'
    if (has_param(kw, 'OP')) op = to_upper(param_value(kw, 'OP'))
    if (op /= 'MOD' .and. op /= 'NEW') call err(p, 'OP must be MOD or NEW')
    if (p%step == 0 .and. (op == 'NEW' .or. has_param(kw, 'AMPLITUDE'))) &
      call err(p, 'OP=NEW and AMPLITUDE= are only allowed inside *STEP')
    amp = amplitude_param(p, m, kw)
    if (p%step > 0 .and. op == 'NEW') m%steps(p%step)%new_bcs = .true.
    allocate(new(0))
    nnew = 0
    do while (next_data(p))
      call split_fields(line_text(p), f, n)
      if (n > 4) call err(p, '*BOUNDARY data line needs: node or set, first dof[, last dof[, value]]')
      call target_nodes(p, m, f(1)%s, nodes, iset)
      v = 0.0_dp
      if (n >= 2 .and. .not. is_int(f(min(n, 2))%s)) then
        ! Abaqus named conditions.
        word = to_upper(f(2)%s)
        if (n > 2) call err(p, 'a named boundary condition takes no further fields')
        select case (word)
        case ('ENCASTRE', 'PINNED'); d1 = 1; d2 = 2
        case ('XSYMM'); d1 = 1; d2 = 1
        case ('YSYMM'); d1 = 2; d2 = 2
        case default; call err(p, '"' // f(2)%s // '" is not a dof number or a known condition')
        end select
      else
        if (n < 2) call err(p, 'missing first dof')
        d1 = get_int(p, f(2), 'first dof')
        d2 = d1
        if (n >= 3) then
          if (len(f(3)%s) > 0) d2 = get_int(p, f(3), 'last dof')
        end if
        if (n == 4) v = get_real(p, f(4), 'prescribed value')
      end if
      if (d1 < 1 .or. d2 > 2 .or. d2 < d1) call err(p, 'dofs must satisfy 1 <= first <= last <= 2 in 2D')
      do k = 1, size(nodes)
        do d = d1, d2
          new = [new, bc_t(node=nodes(k), dof=d, set=iset, amp=amp, value=v)]
          nnew = nnew + 1
        end do
      end do
    end do
    if (nnew == 0) call err(p, 'missing data line (node or set, first dof[, last dof[, value]])')
    if (p%step == 0) then
      call append_bcs(m%model_bcs, p%nmbc, new)
    else
      m%steps(p%step)%bcs = [m%steps(p%step)%bcs, new]
    end if
  end subroutine read_boundary

  subroutine append_bcs(list, n, new)
    type(bc_t), allocatable, intent(inout) :: list(:)
    integer, intent(inout) :: n
    type(bc_t), intent(in) :: new(:)
    type(bc_t), allocatable :: tmp(:)
    if (n + size(new) > size(list)) then
      allocate(tmp(2 * (n + size(new))))
      tmp(1:n) = list(1:n)
      call move_alloc(tmp, list)
    end if
    list(n + 1:n + size(new)) = new
    n = n + size(new)
  end subroutine append_bcs

  subroutine read_cload(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    integer, allocatable :: nodes(:)
    integer :: n, k, d, iset, amp, nnew
    real(dp) :: v
    character(len=:), allocatable :: op
    call allow_params(p, kw, 'OP,AMPLITUDE')
    op = 'MOD'
    if (has_param(kw, 'OP')) op = to_upper(param_value(kw, 'OP'))
    if (op /= 'MOD' .and. op /= 'NEW') call err(p, 'OP must be MOD or NEW')
    if (op == 'NEW') m%steps(p%step)%new_loads = .true.
    amp = amplitude_param(p, m, kw)
    nnew = 0
    do while (next_data(p))
      call split_fields(line_text(p), f, n)
      if (n /= 3) call err(p, '*CLOAD data line needs: node or set, dof, value')
      call target_nodes(p, m, f(1)%s, nodes, iset)
      d = get_int(p, f(2), 'dof')
      if (d < 1 .or. d > 2) call err(p, 'dof must be 1 or 2 in 2D')
      v = get_real(p, f(3), 'load value')
      do k = 1, size(nodes)
        m%steps(p%step)%loads = [m%steps(p%step)%loads, cload_t(node=nodes(k), dof=d, amp=amp, value=v)]
        nnew = nnew + 1
      end do
    end do
    if (nnew == 0) call err(p, 'missing data line (node or set, dof, value)')
  end subroutine read_cload

  subroutine read_step(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(step_t), allocatable :: tmp(:)
    type(field_t) :: f
    if (p%step /= 0) call err(p, '*STEP inside a *STEP (missing *END STEP?)')
    call allow_params(p, kw, 'NAME,INC,NLGEOM,PERTURBATION,AMPLITUDE')
    if (has_param(kw, 'NLGEOM')) then
      if (to_upper(param_value(kw, 'NLGEOM')) /= 'NO') &
        call err(p, 'geometric nonlinearity (NLGEOM) is not implemented: cfe2d is small-deformation')
    end if
    if (has_param(kw, 'PERTURBATION')) call err(p, 'PERTURBATION steps are not implemented')
    if (has_param(kw, 'AMPLITUDE')) then
      if (to_upper(param_value(kw, 'AMPLITUDE')) /= 'RAMP') call err(p, 'only AMPLITUDE=RAMP is implemented on *STEP')
    end if
    call no_data(p, kw)
    if (p%nsteps == size(m%steps)) then
      allocate(tmp(2 * p%nsteps))
      tmp(1:p%nsteps) = m%steps(1:p%nsteps)
      call move_alloc(tmp, m%steps)
    end if
    p%nsteps = p%nsteps + 1
    p%step = p%nsteps
    p%step_line = p%i
    associate(s => m%steps(p%step))
      s%name = param_value(kw, 'NAME')
      s%src%line = p%i
      s%period = -1.0_dp
      allocate(s%bcs(0), s%loads(0), s%requests(0))
      if (has_param(kw, 'INC')) then
        f%s = param_value(kw, 'INC')
        s%max_inc = get_int(p, f, 'value of INC')
        if (s%max_inc < 1) call err(p, 'INC must be positive')
      end if
    end associate
  end subroutine read_step

  subroutine read_static(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    integer :: n
    call allow_params(p, kw, 'DIRECT,SOLVER')
    associate(s => m%steps(p%step))
      if (s%period > 0.0_dp) call err(p, 'second procedure in one step')
      s%dt = 1.0_dp
      s%period = 1.0_dp
      if (next_data(p)) then
        call split_fields(line_text(p), f, n)
        if (n > 4) call err(p, '*STATIC data line needs: initial increment, time period[, min, max]')
        if (len(f(1)%s) > 0) s%dt = get_real(p, f(1), 'initial time increment')
        if (n >= 2) then
          if (len(f(2)%s) > 0) s%period = get_real(p, f(2), 'time period')
        end if
        if (s%dt <= 0.0_dp .or. s%period <= 0.0_dp) call err(p, 'time increment and period must be positive')
        if (s%dt > s%period) s%dt = s%period
      end if
      if (nint(s%period / s%dt) > s%max_inc) &
        call err(p, 'the step needs more increments than INC= on *STEP allows')
    end associate
  end subroutine read_static

  subroutine read_request(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    type(request_t) :: r
    integer :: n, k
    character(len=:), allocatable :: q
    r%nodal = kw%name(1:4) == 'NODE'
    r%to_file = index(kw%name, 'FILE') > 0
    if (r%nodal) then
      call allow_params(p, kw, 'NSET,FREQUENCY,TOTALS,GLOBAL,SUMMARY,OUTPUT')
      if (has_param(kw, 'NSET')) r%set = need_nset(p, m, param_value(kw, 'NSET'))
    else
      call allow_params(p, kw, 'ELSET,FREQUENCY,POSITION,TOTALS,SUMMARY,OUTPUT,GLOBAL')
      if (has_param(kw, 'ELSET')) r%set = need_elset(p, m, param_value(kw, 'ELSET'))
    end if
    call require_data(p, 'output quantities')
    do
      call split_fields(line_text(p), f, n)
      do k = 1, n
        q = to_upper(f(k)%s)
        select case (q)
        case ('U'); r%u = .true.
        case ('RF'); r%rf = .true.
        case ('S'); r%s = .true.
        case ('E'); r%e = .true.
        case ('CSTRESS', 'CDISP', 'CONTACT'); r%cstress = .true.
        case ('')
        case default
          call deck_warning(p%deck, p%i, 'output quantity ' // q // ' is not available and is ignored')
        end select
      end do
      if (.not. next_data(p)) exit
    end do
    if (r%nodal .and. r%e) call err(p, 'E is an element quantity: ask for it in *EL PRINT or *EL FILE')
    associate(s => m%steps(p%step))
      s%requests = [s%requests, r]
    end associate
  end subroutine read_request

  subroutine read_solver(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    character(len=:), allocatable :: v
    call allow_params(p, kw, 'TYPE,ORDERING')
    if (p%step /= 0) call err(p, '*SOLVER is model data and cannot be inside *STEP')
    if (has_param(kw, 'TYPE')) then
      v = to_upper(param_value(kw, 'TYPE'))
      select case (v)
      case ('SKYLINE'); m%solver = solver_skyline
      case ('CHOLMOD'); m%solver = solver_cholmod
      case ('UMFPACK'); m%solver = solver_umfpack
      case default; call err(p, 'solver ' // v // ' is not available (SKYLINE, CHOLMOD, UMFPACK)')
      end select
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
        case default; call err(p, 'ordering ' // v // ' is not available for CHOLMOD and UMFPACK (AMD, METIS)')
        end select
      end if
    end if
    call no_data(p, kw)
  end subroutine read_solver

  subroutine read_contact_pair(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    type(contact_pair_t), allocatable :: tmp(:)
    type(contact_pair_t) :: c
    integer :: n, npair, ns, nsurf
    call allow_params(p, kw, 'PENALTY,OPEN PENALTY,NODAL,SEARCH DISTANCE,UPDATE SEARCH,TYPE,SYMMETRIC')
    if (has_param(kw, 'TYPE')) then
      if (to_upper(param_value(kw, 'TYPE')) /= 'NODE TO SURFACE') &
        call err(p, 'only TYPE=NODE TO SURFACE is implemented')
    end if
    c%penalty = param_real(p, kw, 'PENALTY', -1.0_dp)
    if (has_param(kw, 'PENALTY') .and. c%penalty <= 0.0_dp) call err(p, 'PENALTY must be positive')
    c%open_ratio = param_real(p, kw, 'OPEN PENALTY', 1.0e-12_dp)
    if (c%open_ratio < 0.0_dp .or. c%open_ratio >= 1.0_dp) call err(p, 'OPEN PENALTY (a ratio) must lie in [0, 1)')
    c%nodal = has_param(kw, 'NODAL')
    if (c%nodal .and. .not. has_param(kw, 'PENALTY')) call err(p, 'NODAL needs PENALTY=')
    c%search_distance = param_real(p, kw, 'SEARCH DISTANCE', -1.0_dp)
    c%update_search = has_param(kw, 'UPDATE SEARCH')
    npair = 0
    do while (next_data(p))
      call split_fields(line_text(p), f, n)
      if (n /= 2) call err(p, '*CONTACT PAIR data line needs: slave surface or node set, master surface')
      nsurf = find_name(m%surfaces(1:p%nsurf)%name, to_upper(f(1)%s))
      if (nsurf == 0) then
        ! A node set as slave becomes a node surface of the same name.
        ns = need_nset(p, m, f(1)%s)
        call node_surface_from_set(p, m, ns, nsurf)
      end if
      c%slave_surface = nsurf
      c%master_surface = find_name(m%surfaces(1:p%nsurf)%name, to_upper(f(2)%s))
      if (c%master_surface == 0) call err(p, 'undefined surface ' // to_upper(f(2)%s))
      if (m%surfaces(c%master_surface)%kind /= surf_element) &
        call err(p, 'the master surface must be element-based')
      if (c%master_surface == c%slave_surface) call err(p, 'slave and master are the same surface')
      c%src%line = p%i
      c%twin = 0
      call add_pair(c)
      npair = npair + 1
      if (has_param(kw, 'SYMMETRIC')) then
        ! Two-pass contact: the same pair again with the roles swapped.
        if (m%surfaces(c%slave_surface)%kind /= surf_element) &
          call err(p, 'SYMMETRIC needs an element-based slave surface (it is the master of the second pass)')
        m%pairs(p%npairs)%twin = p%npairs + 1
        c%slave_surface = m%pairs(p%npairs)%master_surface
        c%master_surface = m%pairs(p%npairs)%slave_surface
        c%twin = p%npairs
        call add_pair(c)
      end if
    end do
    if (npair == 0) call err(p, 'missing data line (slave, master)')
  contains
    subroutine add_pair(pair)
      type(contact_pair_t), intent(in) :: pair
      if (p%npairs == size(m%pairs)) then
        allocate(tmp(2 * p%npairs))
        tmp(1:p%npairs) = m%pairs(1:p%npairs)
        call move_alloc(tmp, m%pairs)
      end if
      p%npairs = p%npairs + 1
      m%pairs(p%npairs) = pair
    end subroutine add_pair
  end subroutine read_contact_pair

  subroutine node_surface_from_set(p, m, ns, isurf)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    integer, intent(in) :: ns
    integer, intent(out) :: isurf
    type(surface_t), allocatable :: tmp(:)
    if (p%nsurf == size(m%surfaces)) then
      allocate(tmp(2 * p%nsurf))
      tmp(1:p%nsurf) = m%surfaces(1:p%nsurf)
      call move_alloc(tmp, m%surfaces)
    end if
    p%nsurf = p%nsurf + 1
    isurf = p%nsurf
    m%surfaces(isurf)%name = m%nsets(ns)%name
    m%surfaces(isurf)%kind = surf_node
    allocate(m%surfaces(isurf)%elem(0), m%surfaces(isurf)%edge(0))
    m%surfaces(isurf)%nodes = m%nsets(ns)%items
  end subroutine node_surface_from_set

  subroutine read_contact_controls(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t) :: f
    call allow_params(p, kw, 'TOLERANCE,MAXIT,CUTBACKS')
    m%contact_tolerance = param_real(p, kw, 'TOLERANCE', m%contact_tolerance)
    if (m%contact_tolerance <= 0.0_dp) call err(p, 'TOLERANCE must be positive')
    if (has_param(kw, 'MAXIT')) then
      f%s = param_value(kw, 'MAXIT')
      m%contact_max_iter = get_int(p, f, 'value of MAXIT')
      if (m%contact_max_iter < 1) call err(p, 'MAXIT must be positive')
    end if
    if (has_param(kw, 'CUTBACKS')) then
      f%s = param_value(kw, 'CUTBACKS')
      m%max_cutbacks = get_int(p, f, 'value of CUTBACKS')
      if (m%max_cutbacks < 0) call err(p, 'CUTBACKS must not be negative')
    end if
    call no_data(p, kw)
  end subroutine read_contact_controls

  ! --------------------------------------------------------------- checks

  !> Checks that need the whole deck: materials referenced before they
  !> were defined, sections on every solid element, element geometry.
  subroutine check_model(p, m)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    integer :: s, k, e, imat
    real(dp) :: detj
    allocate(m%elem_section(m%ne))
    m%elem_section = 0
    do s = 1, size(m%sections)
      p%i = m%sections(s)%src%line
      imat = find_name(m%materials%name, m%sections(s)%material_name)
      if (imat == 0) call err(p, 'undefined material ' // trim(m%sections(s)%material_name))
      if (.not. m%materials(imat)%has_elastic) then
        p%i = m%materials(imat)%src%line
        call err(p, 'material ' // trim(m%materials(imat)%name) // ' has no *ELASTIC')
      end if
      m%sections(s)%material = imat
      do k = 1, size(m%elsets(m%sections(s)%elset)%items)
        e = m%elsets(m%sections(s)%elset)%items(k)
        if (.not. is_continuum(m, e)) cycle
        if (m%elem_section(e) /= 0) call err(p, 'element ' // itoa(m%elem_id(e)) // ' is in two sections')
        m%elem_section(e) = s
      end do
    end do
    do e = 1, m%ne
      if (.not. is_continuum(m, e)) cycle
      p%i = m%elem_src(e)%line
      if (m%elem_section(e) == 0) call err(p, 'element ' // itoa(m%elem_id(e)) // ' has no *SOLID SECTION')
      detj = min_corner_jacobian(m, e)
      if (detj <= 0.0_dp) call err(p, 'element ' // itoa(m%elem_id(e)) // &
          ' has a zero or negative Jacobian (nodes clockwise or element inverted)')
    end do
    if (size(m%steps) == 0) call fatal_no_step(p)
    do s = 1, size(m%steps)
      if (m%steps(s)%period < 0.0_dp) then
        p%i = m%steps(s)%src%line
        call err(p, 'step has no procedure (*STATIC)')
      end if
    end do
  end subroutine check_model

  subroutine fatal_no_step(p)
    type(parser_t), intent(inout) :: p
    p%i = p%deck%n
    call err(p, 'the deck has no *STEP: nothing to analyse')
  end subroutine fatal_no_step

  !> Smallest corner value of the Jacobian determinant: positive at every
  !> corner means a valid, convex, counter-clockwise element.
  real(dp) function min_corner_jacobian(m, e)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    integer :: nen, k
    real(dp) :: a(2), b(2), scale
    nen = catalogue(m%etype(e))%corners
    min_corner_jacobian = huge(1.0_dp)
    scale = 0.0_dp
    do k = 1, nen
      a = m%x(:, m%conn(mod(k, nen) + 1, e)) - m%x(:, m%conn(k, e))
      b = m%x(:, m%conn(mod(k + nen - 2, nen) + 1, e)) - m%x(:, m%conn(k, e))
      min_corner_jacobian = min(min_corner_jacobian, a(1) * b(2) - a(2) * b(1))
      scale = max(scale, sum(a**2))
    end do
    ! Collinear corners give round-off sized values of either sign.
    if (min_corner_jacobian <= 1.0e-12_dp * scale) min_corner_jacobian = 0.0_dp
  end function min_corner_jacobian

end module deck_parser
