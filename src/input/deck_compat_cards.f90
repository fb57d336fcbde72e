!> Cards of decks written for CalculiX or Abaqus that cfe2d reads for
!> what they mean to a static 2D analysis:
!> *NODAL THICKNESS, *EQUATION (linear constraints), and the cards
!> that would change the physics (other procedures, other material laws),
!> which stop the run with the reason.
submodule (deck_parser) deck_compat_cards
  use kinds, only: dp
  use strings, only: split_fields, field_t, itoa
  use deck_cursor, only: line_text, err, next_data, allow_params, get_real, get_int, is_label, node_ref, need_nset, &
                         warn_empty_set, deck_dof, dof_moves, note_named, rotation_hint
  use model, only: equation_t
  use model_growth, only: grow
  use growable, only: grow
  implicit none

contains

  !> Purpose: *NODAL THICKNESS: `node or node set, thickness[, second
  !> thickness]`. Used by the sections with NODAL THICKNESS (checked once
  !> the deck is read); the second thickness (beams) is ignored.
  module subroutine read_nodal_thickness(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    integer, allocatable :: nodes(:)
    real(dp) :: t
    integer :: n, nlines, iset
    call allow_params(p, kw, '')
    p%nodal_thickness_line = p%i
    call grow(p%node_thickness, m%nn, fill=-1.0_dp)
    nlines = 0
    do while (next_data(p))
      call split_fields(line_text(p), f, n)
      if (n < 2 .or. n > 3) call err(p, '*NODAL THICKNESS data line needs: node or node set, thickness')
      nodes = target_of(p, m, f(1), iset)
      if (iset > 0) call warn_empty_set(p, size(nodes), 'node set', m%nsets(iset)%name, kw%name)
      t = get_real(p, f(2), 'thickness')
      if (t <= 0.0_dp) call err(p, 'the thickness must be positive')
      if (n == 3) then
        if (get_real(p, f(3), 'second thickness') <= 0.0_dp) call err(p, 'the second thickness must be positive')
      end if
      p%node_thickness(nodes) = t
      nlines = nlines + 1
    end do
    if (nlines == 0) call err(p, 'missing data line (node or node set, thickness)')
  end subroutine read_nodal_thickness

  !> Nodes named by a node id or a node set name, and the set (0 for a
  !> node id).
  function target_of(p, m, f, iset) result(nodes)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    type(field_t), intent(in) :: f
    integer, intent(out) :: iset
    integer, allocatable :: nodes(:)
    iset = 0
    if (is_label(f%s)) then
      nodes = [node_ref(p, m, f, 'node')]
    else
      iset = need_nset(p, m, f%s)
      nodes = m%nsets(iset)%items
    end if
  end function target_of

  !> Purpose: *EQUATION: per constraint, a line with the number of terms,
  !> then `node, dof, coefficient` triples (four per line at most, as many
  !> lines as needed); a node set gives one constraint per node (sets of
  !> one node, and node ids, take part in each). The constraints are put
  !> into m%equations (checked once the deck is read: deck_model_checks;
  !> the analysis eliminates the first term's dof).
  module subroutine read_equation(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    integer :: n, nterms, card
    call allow_params(p, kw, '')
    card = p%i
    do while (next_data(p))
      call split_fields(line_text(p), f, n)
      if (n /= 1) call err(p, '*EQUATION: expected the number of terms of the next constraint')
      nterms = get_int(p, f(1), 'number of terms')
      if (nterms < 1 .or. nterms > 1000) call err(p, 'the number of terms must lie in 1..1000')
      call read_equation_terms(p, m, nterms)
    end do
    if (p%i == card) call err(p, 'missing data line (number of terms)')
  end subroutine read_equation

  !> The `node, dof, coefficient` triples of one *EQUATION constraint,
  !> appended to m%equations (one constraint per node of its node sets)
  !> with the line of its first term as its source. Each term's dof is
  !> what deck_dof makes of it at each node (dof 6 of a reference node of
  !> *RIGID BODY or *COUPLING, dof 3 of a ROT NODE: the rotation); a term
  !> on a dof a 2D model does not have is dropped if its coefficient is
  !> zero (CalculiX decks of plane models may name dof 3) and an error
  !> otherwise.
  subroutine read_equation_terms(p, m, nterms)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    integer, intent(in) :: nterms
    type(field_t), allocatable :: f(:)
    type(equation_t) :: eq
    integer, allocatable :: first(:), count(:), all_nodes(:), all_dofs(:), named(:)
    logical, allocatable :: all_kept(:)
    real(dp) :: coef(nterms)
    integer :: n, k, j, q, nread, nkept, ncopies, iset, nempty, d, kind, ra, rd, i0
    integer :: empty_named(nterms)
    allocate(first(nterms), count(nterms), all_nodes(0), all_dofs(0), all_kept(0))
    nread = 0
    do while (nread < nterms)
      if (.not. next_data(p)) call err(p, '*EQUATION: fewer terms than announced (' // itoa(nterms) // ')')
      if (nread == 0) eq%src%line = p%i
      nempty = 0
      call split_fields(line_text(p), f, n)
      if (mod(n, 3) /= 0 .or. nread + n / 3 > nterms) &
        call err(p, '*EQUATION data line needs node, dof, coefficient triples (' // itoa(nterms) // ' in all)')
      do k = 1, n, 3
        nread = nread + 1
        first(nread) = size(all_nodes) + 1
        named = target_of(p, m, f(k), iset)
        ! an empty set named by several terms of a line: one warning
        if (iset > 0 .and. .not. any(empty_named(1:nempty) == iset)) then
          call warn_empty_set(p, size(m%nsets(iset)%items), 'node set', m%nsets(iset)%name, 'EQUATION')
          if (size(m%nsets(iset)%items) == 0) then
            nempty = nempty + 1
            empty_named(nempty) = iset
          end if
        end if
        count(nread) = size(named)
        d = get_int(p, f(k + 1), 'dof')
        coef(nread) = get_real(p, f(k + 2), 'coefficient')
        if (nread == 1 .and. coef(1) == 0.0_dp) &
          call err(p, 'the first coefficient (of the dependent dof) must not be zero')
        i0 = size(all_nodes)
        all_nodes = [all_nodes, named]
        call grow(all_dofs, i0 + size(named))
        all_kept = [all_kept, spread(.true., 1, size(named))]
        do q = 1, size(named)
          call note_named(p, named(q))
          call deck_dof(p, named(q), d, kind, ra, rd)
          all_nodes(i0 + q) = ra
          all_dofs(i0 + q) = rd
          all_kept(i0 + q) = kind == dof_moves
          if (kind /= dof_moves .and. coef(nread) /= 0.0_dp) call err(p, 'dof ' // itoa(d) // &
            ' with a non-zero coefficient: a 2D model has dofs 1 and 2 only (CalculiX expands plane elements ' // &
            'to 3D; here a dof 3 term has no meaning)' // rotation_hint(d))
        end do
      end do
    end do
    ncopies = maxval(count)
    if (any(count /= 1 .and. count /= ncopies)) &
      call err(p, '*EQUATION: the node sets of one constraint must have the same number of nodes')
    allocate(eq%node(nterms), eq%dof(nterms), eq%coef(nterms))
    do j = 1, ncopies
      nkept = 0
      do k = 1, nterms
        q = first(k) + min(j, count(k)) - 1
        if (.not. all_kept(q)) cycle
        nkept = nkept + 1
        eq%node(nkept) = all_nodes(q)
        eq%dof(nkept) = all_dofs(q)
        eq%coef(nkept) = coef(k)
      end do
      call grow(m%equations, p%nequations + 1)
      p%nequations = p%nequations + 1
      m%equations(p%nequations) = equation_t(node=eq%node(1:nkept), dof=eq%dof(1:nkept), coef=eq%coef(1:nkept), &
                                              src=eq%src)
    end do
  end subroutine read_equation_terms

  !> Purpose: cards that would change the physics of a static analysis
  !> and that cfe2d does not implement: stop with the
  !> reason on the card's line.
  module subroutine reject_card(p, kw)
    type(parser_t), intent(inout) :: p
    type(keyword_t), intent(in) :: kw
    select case (kw%name)
    case ('DYNAMIC', 'MODAL DYNAMIC', 'STEADY STATE DYNAMICS', 'FREQUENCY', 'BUCKLE', 'COMPLEX FREQUENCY', &
          'VISCO', 'HEAT TRANSFER', 'COUPLED TEMPERATURE-DISPLACEMENT', 'UNCOUPLED TEMPERATURE-DISPLACEMENT', &
          'ELECTROMAGNETICS', 'GREEN', 'SENSITIVITY', 'CFD', 'SOIL')
      call err(p, 'the procedure *' // kw%name // ' is not implemented: cfe2d runs static (*STATIC) steps')
    case ('CYCLIC HARDENING', 'CREEP', 'HYPERFOAM', &
          'USER MATERIAL', 'DEPVAR', 'ANISOTROPIC HYPERELASTIC', 'VISCOELASTIC', 'MOHR COULOMB')
      call err(p, 'the material law *' // kw%name // ' is not implemented: cfe2d''s materials are *ELASTIC, ' // &
               '*HYPERELASTIC (NEO HOOKE, MOONEY-RIVLIN), *PLASTIC (von Mises, isotropic hardening) and ' // &
               '*DEFORMATION PLASTICITY')
    case ('CHANGE FRICTION', 'CHANGE SURFACE BEHAVIOR', 'CHANGE CONTACT TYPE', 'CONTACT DAMPING', &
          'GAP CONDUCTANCE', 'GAP HEAT GENERATION')
      call err(p, '*' // kw%name // ' is not implemented: cfe2d''s contact is static and keeps the law ' // &
               'and the friction of its *SURFACE INTERACTION')
    case default
      call err(p, 'keyword *' // kw%name // ' is not implemented in cfe2d')
    end select
  end subroutine reject_card
end submodule deck_compat_cards
