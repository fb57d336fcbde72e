!> Mesh cards: *NODE, *ELEMENT, *NSET, *ELSET, *SURFACE.
submodule (deck_parser) deck_mesh_cards
  use kinds, only: dp
  use strings, only: split_fields, to_upper, field_t, itoa
  use deck_input, only: param_value, has_param, deck_warning
  use deck_cursor, only: max_id, line_text, err, next_data, no_data, allow_params, required_param, &
                         name_param, check_name_length, get_real, get_int, node_of, node_or_zero, elem_of, &
                         is_int, &
                         need_nset, need_elset, new_surface, warn_empty_set, &
                         is_label, node_ref, elem_ref, defined_name, new_node_id, new_elem_id, placed, &
                         instance_index, set_scope
  use model, only: surf_element, surf_node, elem_nodes, edge_nodes, find_name, elem_label
  use growable, only: append, grow
  use model_growth, only: grow
  use element_catalogue, only: catalogue, find_element_type, is_line, is_spring_shape, unsupported_reason
  use mesh_topology, only: build_topology, edge_owner
  implicit none

contains

  !> Purpose: *NODE: one node per data line, `id[, x[, y[, z]]]`, as
  !> lenient as CalculiX: a missing or empty coordinate is 0, z (gmsh
  !> writes it) is read and ignored, and so are fields after z (with a
  !> warning on the first such line). NSET= collects the nodes in a set.
  !> A card without data lines defines nothing and warns (cgx writes one
  !> for a set that has no nodes of its own; CalculiX accepts it); its
  !> NSET= still exists, empty.
  !> Inside an instance the number is the part's label and the node is
  !> placed as the instance says (new_node_id, placed).
  module subroutine read_nodes(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    integer :: n, id, gid, iset, nitems, k, card
    integer, allocatable :: items(:)
    real(dp) :: xyz(3)
    logical :: warned
    call allow_params(p, kw, 'NSET,SYSTEM')
    if (has_param(kw, 'SYSTEM')) then
      if (to_upper(param_value(kw, 'SYSTEM')) /= 'R') call err(p, 'only SYSTEM=R (rectangular) is implemented')
    end if
    card = p%i
    nitems = 0
    allocate(items(0))
    warned = .false.
    do while (next_data(p))
      call split_fields(line_text(p), f, n)
      id = get_int(p, f(1), 'node id')
      if (id < 1 .or. id > max_id) call err(p, 'node id out of range 1..' // itoa(max_id))
      xyz = 0.0_dp
      do k = 2, n
        if (len(f(k)%s) == 0) cycle
        if (k <= 4) then
          xyz(k - 1) = get_real(p, f(k), coordinate_name(k - 1))
        else if (.not. warned) then
          call deck_warning(p%deck, p%i, 'fields after the third coordinate are ignored (as CalculiX does)')
          warned = .true.
        end if
      end do
      gid = new_node_id(p, m, id)
      call grow(m%node_index, gid, fill=0)
      if (m%node_index(gid) /= 0) then
        call redefine_node(p, m, m%node_index(gid), xyz)
        call append(items, nitems, m%node_index(gid))
        cycle
      end if
      call grow(m%node_id, m%nn + 1)
      call grow(m%x, m%nn + 1)
      m%nn = m%nn + 1
      m%node_id(m%nn) = gid
      m%x(:, m%nn) = placed(p, m, xyz(1:2))
      m%node_index(gid) = m%nn
      call grow(p%node_line, m%nn)
      p%node_line(m%nn) = p%i
      call append(items, nitems, m%nn)
    end do
    if (nitems == 0 .and. has_param(kw, 'NSET')) then
      call deck_warning(p%deck, card, '*NODE without data lines defines no node (node set ' // &
                        to_upper(param_value(kw, 'NSET')) // ' gets none)')
    else if (nitems == 0) then
      call deck_warning(p%deck, card, '*NODE without data lines defines no node')
    end if
    if (has_param(kw, 'NSET')) then
      iset = add_nset(p, m, required_param(p, kw, 'NSET'))
      call extend_set(m%nsets(iset)%items, items(1:nitems))
    end if
  end subroutine read_nodes

  !> Purpose: a node line that defines node a again: the later
  !> coordinates win, as in CalculiX (which keeps the last line read); the
  !> repeats are counted for one warning once the deck is read
  !> (read_model). Inside an instance the count is per part read; an
  !> instance's nodes are new ids (new_node_id), so only a part's own
  !> repeats count.
  subroutine redefine_node(p, m, a, xyz)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    integer, intent(in) :: a
    real(dp), intent(in) :: xyz(3)
    m%x(:, a) = placed(p, m, xyz(1:2))
    p%node_line(a) = p%i
    p%repeated_nodes = p%repeated_nodes + 1
    if (p%repeated_line == 0) p%repeated_line = p%i
  end subroutine redefine_node

  pure function coordinate_name(k) result(s)
    integer, intent(in) :: k
    character(len=:), allocatable :: s
    character(len=1), parameter :: axis(3) = ['x', 'y', 'z']
    s = axis(k) // ' coordinate'
  end function coordinate_name

  !> Purpose: *ELEMENT, TYPE=: one element per data line, `id, n1, n2, ...`
  !> with the node count of the type; ELSET= collects them in a set.
  !> A node may be INSTANCE.LABEL (an assembly-level spring between
  !> instances).
  module subroutine read_elements(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    character(len=:), allocatable :: tname
    integer :: et, nen, n, id, gid, k, iset, nitems
    integer, allocatable :: items(:)
    call allow_params(p, kw, 'TYPE,ELSET')
    tname = to_upper(required_param(p, kw, 'TYPE'))
    et = find_element_type(tname)
    if (et == 0 .and. len(unsupported_reason(tname)) > 0) call err(p, 'element type ' // tname // ': ' // &
                                                                    unsupported_reason(tname))
    if (et == 0) call err(p, 'element type ' // tname // ' is not implemented (' // catalogue_names() // ')')
    nen = catalogue(et)%nodes
    nitems = 0
    do while (next_data(p))
      call split_fields(line_text(p), f, n)
      call continued_element_line(p, nen + 1, f, n)
      if (n /= nen + 1) call err(p, 'element ' // tname // ' needs an id and ' // itoa(nen) // ' nodes')
      id = get_int(p, f(1), 'element id')
      if (id < 1 .or. id > max_id) call err(p, 'element id out of range 1..' // itoa(max_id))
      gid = new_elem_id(p, m, id)
      call grow(m%elem_index, gid, fill=0)
      if (m%elem_index(gid) /= 0) call err(p, 'duplicate element id ' // f(1)%s)
      call grow(m%elem_id, m%ne + 1)
      call grow(m%etype, m%ne + 1)
      call grow(m%conn, m%ne + 1)
      call grow(m%elem_src, m%ne + 1)
      m%ne = m%ne + 1
      m%elem_id(m%ne) = gid
      m%etype(m%ne) = et
      m%conn(:, m%ne) = 0
      do k = 1, nen
        m%conn(k, m%ne) = node_ref(p, m, f(k + 1), 'node of element')
      end do
      ! a quadrilateral may name one node at two neighbouring corners (a
      ! collapsed one): check_model's corner check decides
      if (catalogue(et)%corners /= 4) then
        do k = 2, nen
          if (any(m%conn(1:k - 1, m%ne) == m%conn(k, m%ne))) call err(p, 'element uses the same node twice')
        end do
      end if
      m%elem_src(m%ne)%line = p%i
      m%elem_index(gid) = m%ne
      call append(items, nitems, m%ne)
    end do
    if (nitems == 0) call err(p, 'missing data line (*ELEMENT without elements)')
    if (has_param(kw, 'ELSET')) then
      iset = add_elset(p, m, param_value(kw, 'ELSET'))
      call extend_set(m%elsets(iset)%items, items(1:nitems))
    end if
  end subroutine read_elements

  !> An element data line that ends with a comma before all nodes are
  !> given continues on the next line (as CalculiX writes 8-node elements:
  !> eight fields, then the last node alone).
  subroutine continued_element_line(p, nwant, f, n)
    type(parser_t), intent(inout) :: p
    integer, intent(in) :: nwant
    type(field_t), allocatable, intent(inout) :: f(:)
    integer, intent(inout) :: n
    type(field_t), allocatable :: more(:)
    character(len=:), allocatable :: t
    integer :: nm
    do while (n < nwant)
      t = trim(line_text(p))
      if (len(t) == 0) exit
      if (t(len(t):len(t)) /= ',') exit
      if (.not. next_data(p)) exit
      call split_fields(line_text(p), more, nm)
      f = [f(1:n), more(1:nm)]
      n = n + nm
    end do
  end subroutine continued_element_line

  !> The element type names of the catalogue, for error messages.
  function catalogue_names() result(s)
    character(len=:), allocatable :: s
    integer :: it
    s = trim(catalogue(1)%name)
    do it = 2, size(catalogue)
      s = s // ', ' // trim(catalogue(it)%name)
    end do
  end function catalogue_names

  !> Purpose: *NSET, NSET=: node ids and set names, first-last-increment
  !> triples with GENERATE, or (ELSET=) all nodes of an element set. A
  !> repeated name extends the set. INSTANCE= (assembly level): the
  !> numbers and set names are those of that instance's part.
  module subroutine read_nset(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    integer :: iset, nitems, es, k
    integer, allocatable :: items(:)
    character(len=:), allocatable :: name
    call allow_params(p, kw, 'NSET,GENERATE,ELSET,UNSORTED,INTERNAL,INSTANCE')
    name = required_param(p, kw, 'NSET')
    call set_scope(p, m, instance_param(p, m, kw))
    nitems = 0
    allocate(items(0))
    if (has_param(kw, 'ELSET')) then
      ! The nodes of an element set, e.g. of gmsh's line elements.
      es = need_elset(p, m, param_value(kw, 'ELSET'))
      do k = 1, size(m%elsets(es)%items)
        associate(e => m%elsets(es)%items(k))
          call append(items, nitems, m%conn(1:elem_nodes(m, e), e))
        end associate
      end do
      call no_data(p, kw)
    else
      do while (next_data(p))
        call read_id_list(p, m, has_param(kw, 'GENERATE'), .true., items, nitems)
      end do
    end if
    call set_scope(p, m, p%owner)
    iset = add_nset(p, m, name)
    call extend_set(m%nsets(iset)%items, items(1:nitems))
  end subroutine read_nset

  !> Purpose: *ELSET, ELSET=: element ids and set names, or first-last-
  !> increment triples with GENERATE. A repeated name extends the set.
  !> INSTANCE= as on *NSET.
  module subroutine read_elset(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    integer :: iset, nitems
    integer, allocatable :: items(:)
    character(len=:), allocatable :: name
    call allow_params(p, kw, 'ELSET,GENERATE,UNSORTED,INTERNAL,INSTANCE')
    name = required_param(p, kw, 'ELSET')
    call set_scope(p, m, instance_param(p, m, kw))
    nitems = 0
    allocate(items(0))
    do while (next_data(p))
      call read_id_list(p, m, has_param(kw, 'GENERATE'), .false., items, nitems)
    end do
    call set_scope(p, m, p%owner)
    iset = add_elset(p, m, name)
    call extend_set(m%elsets(iset)%items, items(1:nitems))
  end subroutine read_elset

  !> INSTANCE= of an assembly-level *NSET or *ELSET: the instance whose
  !> numbers and set names the data lines give (0 without it).
  integer function instance_param(p, m, kw) result(k)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    type(keyword_t), intent(in) :: kw
    k = p%owner
    if (.not. has_param(kw, 'INSTANCE')) return
    if (p%owner > 0) call err(p, 'INSTANCE= is for sets of the assembly; inside a part or an instance the ' // &
                                 'numbers are already its own')
    k = instance_index(m, to_upper(param_value(kw, 'INSTANCE')))
    if (k == 0) call err(p, 'undefined instance ' // to_upper(param_value(kw, 'INSTANCE')) // &
                            ' (an *INSTANCE of the *ASSEMBLY before this line)')
  end function instance_param

  !> One data line of *NSET/*ELSET: ids and set names, or (GENERATE)
  !> first, last[, increment]; internal indices appended to items.
  subroutine read_id_list(p, m, generate, nodes, items, nitems)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(in) :: m
    logical, intent(in) :: generate, nodes
    integer, allocatable, intent(inout) :: items(:)
    integer, intent(inout) :: nitems
    type(field_t), allocatable :: f(:)
    integer :: n, k, a, b, c, id, last
    call split_fields(line_text(p), f, n)
    if (generate) then
      if (n < 2 .or. n > 3) call err(p, 'GENERATE data line needs: first, last[, increment]')
      a = get_int(p, f(1), 'first id')
      b = get_int(p, f(2), 'last id')
      c = 1
      if (n == 3) c = get_int(p, f(3), 'increment')
      if (c <= 0 .or. b < a) call err(p, 'GENERATE needs first <= last and a positive increment')
      if (nodes) then
        ! no node id lies beyond the lookup table: the numbers past it are
        ! dropped as a count, not one by one (a range to 2147483647 would
        ! take the parser minutes)
        last = b
        if (b > size(m%node_index)) last = max(a - 1, size(m%node_index))
        do id = a, last, c
          call add_node_or_drop(p, m, id, items, nitems)
        end do
        if (last < b) call drop_node_range(p, a + c * ((last - a + c) / c), b, c)
      else
        do id = a, b, c
          call append(items, nitems, entity_of(p, m, nodes, id))
        end do
      end if
      return
    end if
    do k = 1, n
      if (len(f(k)%s) == 0) call err(p, 'empty entry in list')
      if (nodes .and. is_int(f(k)%s)) then
        call add_node_or_drop(p, m, get_int(p, f(k), 'id'), items, nitems)
      else if (is_label(f(k)%s) .and. nodes) then
        call append(items, nitems, node_ref(p, m, f(k), 'id'))
      else if (is_label(f(k)%s)) then
        call append(items, nitems, elem_ref(p, m, f(k), 'id'))
      else if (nodes) then
        call append(items, nitems, m%nsets(need_nset(p, m, f(k)%s))%items)
      else
        call append(items, nitems, m%elsets(need_elset(p, m, f(k)%s))%items)
      end if
    end do
  end subroutine read_id_list

  !> Purpose: node number id of a *NSET list appended to items, or, when
  !> the deck defines no such node, dropped as CalculiX drops it ("value
  !> > nk"): counted, with the first line and numbers, for one warning
  !> once the deck is read (read_model).
  subroutine add_node_or_drop(p, m, id, items, nitems)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(in) :: m
    integer, intent(in) :: id
    integer, allocatable, intent(inout) :: items(:)
    integer, intent(inout) :: nitems
    integer :: a
    a = node_or_zero(p, m, id)
    if (a > 0) then
      call append(items, nitems, a)
      return
    end if
    p%dropped_nodes = p%dropped_nodes + 1
    if (p%dropped_line == 0) p%dropped_line = p%i
    if (p%dropped_nodes <= size(p%dropped_ids)) p%dropped_ids(p%dropped_nodes) = id
  end subroutine add_node_or_drop

  !> Purpose: the node numbers first, first + step, ... up to last (none of
  !> which any *NODE defines) dropped as add_node_or_drop drops one: counted,
  !> the first few kept for the warning.
  subroutine drop_node_range(p, first, last, step)
    type(parser_t), intent(inout) :: p
    integer, intent(in) :: first, last, step
    integer :: k, count
    if (first > last) return
    count = (last - first) / step + 1
    if (p%dropped_line == 0) p%dropped_line = p%i
    do k = p%dropped_nodes + 1, min(size(p%dropped_ids), p%dropped_nodes + count)
      p%dropped_ids(k) = first + (k - p%dropped_nodes - 1) * step
    end do
    if (p%dropped_nodes > huge(count) - count) then
      p%dropped_nodes = huge(count)
    else
      p%dropped_nodes = p%dropped_nodes + count
    end if
  end subroutine drop_node_range

  !> Internal index of node (nodes) or element id.
  integer function entity_of(p, m, nodes, id)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    logical, intent(in) :: nodes
    integer, intent(in) :: id
    if (nodes) then
      entity_of = node_of(p, m, id)
    else
      entity_of = elem_of(p, m, id)
    end if
  end function entity_of

  !> Existing set of that name (a repeated *NSET extends it) or a new one;
  !> inside an instance the name is INSTANCE.NAME.
  integer function add_nset(p, m, name) result(iset)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: dname
    dname = defined_name(p, m, name)
    iset = find_name(m%nsets(1:p%nsets)%name, dname)
    if (iset > 0) return
    call check_name_length(p, dname)
    call grow(m%nsets, p%nsets + 1)
    p%nsets = p%nsets + 1
    iset = p%nsets
    m%nsets(iset)%name = dname
    allocate(m%nsets(iset)%items(0))
  end function add_nset

  integer function add_elset(p, m, name) result(iset)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: dname
    dname = defined_name(p, m, name)
    iset = find_name(m%elsets(1:p%nelsets)%name, dname)
    if (iset > 0) return
    call check_name_length(p, dname)
    call grow(m%elsets, p%nelsets + 1)
    p%nelsets = p%nelsets + 1
    iset = p%nelsets
    m%elsets(iset)%name = dname
    allocate(m%elsets(iset)%items(0))
  end function add_elset

  !> Append items not yet in the set, keeping the order of first mention.
  !> Items are positive internal indices; set holds no repeats.
  subroutine extend_set(set, items)
    integer, allocatable, intent(inout) :: set(:)
    integer, intent(in) :: items(:)
    integer, allocatable :: all(:)
    logical, allocatable :: seen(:)
    integer :: k, n
    if (size(items) == 0) return
    allocate(seen(max(maxval(items), maxval(set))))
    seen = .false.
    seen(set) = .true.
    allocate(all(size(set) + size(items)))
    n = size(set)
    all(1:n) = set
    do k = 1, size(items)
      if (seen(items(k))) cycle
      seen(items(k)) = .true.
      n = n + 1
      all(n) = items(k)
    end do
    set = all(1:n)
  end subroutine extend_set

  !> Purpose: *SURFACE, NAME=: TYPE=ELEMENT (default) lists element faces
  !> (`element or elset, Sk`, or an elset of line elements lying on solid
  !> element boundaries); TYPE=NODE lists nodes and node sets.
  module subroutine read_surface(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    character(len=:), allocatable :: name, stype
    integer :: k, ne, nn, isurf, nlines
    integer, allocatable :: elems(:), edges(:), nodes(:), ends(:)
    call allow_params(p, kw, 'NAME,TYPE,INTERNAL')
    name = defined_name(p, m, name_param(p, kw, 'NAME'))
    stype = 'ELEMENT'
    if (has_param(kw, 'TYPE')) stype = to_upper(param_value(kw, 'TYPE'))
    if (stype /= 'ELEMENT' .and. stype /= 'NODE') call err(p, 'surface TYPE must be ELEMENT or NODE')
    if (find_name(m%surfaces(1:p%nsurf)%name, name) > 0) call err(p, 'duplicate surface ' // name)
    ne = 0
    nn = 0
    nlines = 0
    allocate(elems(0), edges(0), nodes(0))
    do while (next_data(p))
      if (stype == 'NODE') then
        call surface_nodes_line(p, m, nodes, nn)
      else
        call surface_faces_line(p, m, elems, edges, ne)
      end if
      nlines = nlines + 1
    end do
    ! Lines naming only empty sets leave the surface empty (warned there);
    ! a card without lines (cgx writes one for a set without faces) too. A
    ! card that names an empty surface warns where it does.
    if (nlines == 0) call deck_warning(p%deck, p%i, '*SURFACE without data lines: surface ' // name // &
                                       ' is empty')
    isurf = new_surface(p, m)
    associate(s => m%surfaces(isurf))
      s%name = name
      if (stype == 'NODE') then
        s%kind = surf_node
        allocate(s%elem(0), s%edge(0), s%nodes(0))
        call extend_set(s%nodes, nodes(1:nn))
      else
        s%kind = surf_element
        s%elem = elems(1:ne)
        s%edge = edges(1:ne)
        ! Node list of the surface: the nodes of its edges (ends and
        ! mid-side nodes), once each.
        allocate(s%nodes(0), ends(3 * ne))
        do k = 1, ne
          call edge_nodes(m, s%elem(k), s%edge(k), ends(3 * k - 2), ends(3 * k - 1), ends(3 * k))
        end do
        call extend_set(s%nodes, pack(ends, ends > 0))
      end if
    end associate
  end subroutine read_surface

  !> A data line of a node surface: `node or node set[, area]`.
  subroutine surface_nodes_line(p, m, nodes, nn)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(in) :: m
    integer, allocatable, intent(inout) :: nodes(:)
    integer, intent(inout) :: nn
    type(field_t), allocatable :: f(:)
    integer :: n, iset
    call split_fields(line_text(p), f, n)
    if (n > 2) call err(p, 'node surface data line needs: node or node set[, area]')
    if (is_label(f(1)%s)) then
      call append(nodes, nn, node_ref(p, m, f(1), 'node'))
    else
      iset = need_nset(p, m, f(1)%s)
      call warn_empty_set(p, size(m%nsets(iset)%items), 'node set', m%nsets(iset)%name, 'SURFACE')
      call append(nodes, nn, m%nsets(iset)%items)
    end if
  end subroutine surface_nodes_line

  !> A data line of an element surface: `element or elset, Sk` for solid
  !> elements, `element or elset` for line elements (each becomes the
  !> edge of the solid element it lies on).
  subroutine surface_faces_line(p, m, elems, edges, ne)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    integer, allocatable, intent(inout) :: elems(:), edges(:)
    integer, intent(inout) :: ne
    type(field_t), allocatable :: f(:)
    character(len=:), allocatable :: face
    integer, allocatable :: list(:)
    integer :: n, k, e, edge, owner, nedge, iset
    call split_fields(line_text(p), f, n)
    if (n > 2) call err(p, 'element surface data line needs: element or element set[, face S1..S4]')
    if (is_label(f(1)%s)) then
      list = [elem_ref(p, m, f(1), 'element')]
    else
      iset = need_elset(p, m, f(1)%s)
      list = m%elsets(iset)%items
      call warn_empty_set(p, size(list), 'element set', m%elsets(iset)%name, 'SURFACE')
    end if
    face = ''
    if (n == 2) face = to_upper(f(2)%s)
    nedge = ne
    do k = 1, size(list)
      e = list(k)
      if (is_spring_shape(catalogue(m%etype(e))%shape)) then
        call err(p, 'element ' // elem_label(m, e) // ' is a spring (' // trim(catalogue(m%etype(e))%name) // &
                 '): a surface is made of solid element faces or of line elements on them')
      else if (is_line(catalogue(m%etype(e))%shape)) then
        if (len(face) > 0) call err(p, 'a face id is not allowed for line elements')
        call owner_edge(p, m, m%conn(catalogue(m%etype(e))%edge(1, 1), e), m%conn(catalogue(m%etype(e))%edge(2, 1), e), &
                        owner, edge)
        call append(elems, ne, owner)
      else
        if (len(face) == 0) call err(p, 'solid elements need a face id S1..S4')
        edge = 0
        if (len(face) == 2 .and. face(1:1) == 'S') edge = index('123456789', face(2:2))
        if (edge == 0 .or. edge > catalogue(m%etype(e))%nedges) &
          call err(p, 'face ' // face // ' does not exist for ' // trim(catalogue(m%etype(e))%name))
        call append(elems, ne, e)
      end if
      call append(edges, nedge, edge)
    end do
  end subroutine surface_faces_line

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
end submodule deck_mesh_cards
