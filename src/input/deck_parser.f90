!> Turns the lines of a keyword deck into a model: read_model reads the
!> deck, dispatches every keyword line to the reader of its card, then
!> checks what needs the whole deck. The readers live in submodules, one
!> file per family of cards:
!>   deck_mesh_cards      *NODE, *ELEMENT, *NSET, *ELSET, *SURFACE
!>   deck_material_cards  *MATERIAL, *ELASTIC, *EXPANSION, *HYPERELASTIC,
!>                        *PLASTIC, *SOLID SECTION, *SPRING
!>   deck_step_cards      *AMPLITUDE, *BOUNDARY, *STEP, *STATIC, *CONTROLS, *CLOAD,
!>                        output requests, *END STEP, *INITIAL CONDITIONS,
!>                        *TEMPERATURE
!>   deck_contact_cards   *CONTACT PAIR, *CONTACT CONTROLS, *SOLVER
!>   deck_interaction_cards  *SURFACE INTERACTION, *SURFACE BEHAVIOR, *FRICTION
!>   deck_compat_cards    *NODAL THICKNESS, *EQUATION, and the cards of other
!>                        programs that would change the physics (rejected)
!>   deck_load_cards      *DLOAD, *DSLOAD, *DENSITY
!>   deck_constraint_cards  *PRE-TENSION SECTION (cut once the deck is read),
!>                        *TIE (its equations: the contact layer's tie_constraints)
!>   deck_rigid_cards     *RIGID BODY, *COUPLING with *KINEMATIC or *DISTRIBUTING,
!>                        *TRANSFORM (linear constraints; transforms applied
!>                        once the deck is read)
!>   deck_part_cards      *PART, *ASSEMBLY, *INSTANCE and their ends (Abaqus/CAE
!>                        decks: a part's cards are read for each instance)
!>   deck_model_checks    checks that need the whole deck
!>   deck_heat_cards      (a module) *HEAT TRANSFER, *CONDUCTIVITY, *SPECIFIC HEAT,
!>                        *BOUNDARY on dof 11, *CFLUX, *DFLUX, *FILM; check_heat_model
!>   deck_coupled_cards   (a module) *COUPLED TEMPERATURE-DISPLACEMENT; a deck run
!>                        with both fields settled and checked
!> The parser state and the helpers every reader uses are in deck_cursor.
module deck_parser
  use messages, only: fatal
  use strings, only: itoa, to_upper
  use deck_input, only: keyword_t, read_deck, parse_keyword, deck_warning, is_keyword, param_value
  use deck_cursor, only: parser_t, err, line_text, next_data, allow_params, in_step
  use model, only: model_t
  use element_catalogue, only: max_nodes
  use deck_heat_cards, only: read_heat_transfer, read_conductivity, read_specific_heat, read_heat_boundary, &
                             read_cflux, read_dflux, read_film, reject_heat_card, boundary_lines, is_heat_line, &
                             check_heat_model, &
                             read_radiate, read_physical_constants
  use deck_coupled_cards, only: read_coupled_step, settle_coupled_model, check_coupled_model, &
                                read_gap_conductance, read_gap_heat_generation, gap_heat_pairs
  implicit none
  private
  public :: read_model
  ! For the submodule deck_part_cards, which reads a part's cards for
  ! each of its instances (gfortran gives private module procedures local
  ! linkage, so a submodule could not call them: see deck_cursor).
  public :: dispatch, spaced_name

  ! The card readers, one per card, in the submodules named above. Each
  ! is entered on the keyword line (p%i) and leaves p%i on the last line
  ! of its card.
  interface
    module subroutine read_nodes(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_nodes
    module subroutine read_elements(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_elements
    module subroutine read_nset(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_nset
    module subroutine read_elset(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_elset
    module subroutine read_surface(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_surface
    module subroutine read_material(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_material
    module subroutine read_elastic(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_elastic
    module subroutine read_orientation(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_orientation
    module subroutine check_orientations(p, m)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
    end subroutine check_orientations
    module subroutine read_expansion(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_expansion
    module subroutine read_controls(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_controls
    module subroutine read_hyperelastic(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_hyperelastic
    module subroutine read_plastic(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_plastic
    module subroutine read_deformation_plasticity(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_deformation_plasticity
    module subroutine read_initial_stress(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_initial_stress
    module subroutine read_initial_conditions(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_initial_conditions
    module subroutine read_temperature(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_temperature
    module subroutine read_section(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_section
    module subroutine read_spring(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_spring
    module subroutine read_mass(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_mass
    module subroutine read_amplitude(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_amplitude
    module subroutine read_boundary(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_boundary
    module subroutine read_cload(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_cload
    module subroutine read_step(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_step
    module subroutine read_static(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_static
    module subroutine read_frequency(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_frequency
    module subroutine read_request(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_request
    module subroutine read_time_points(p, kw)
      type(parser_t), intent(inout) :: p
      type(keyword_t), intent(in) :: kw
    end subroutine read_time_points
    module subroutine read_end_step(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_end_step
    module subroutine read_contact_pair(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_contact_pair
    module subroutine read_contact_controls(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_contact_controls
    module subroutine read_solver(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_solver
    ! Decks written for CalculiX/Abaqus (deck_interaction_cards, deck_compat_cards):
    module subroutine read_surface_interaction(p, kw)
      type(parser_t), intent(inout) :: p
      type(keyword_t), intent(in) :: kw
    end subroutine read_surface_interaction
    module subroutine read_surface_behavior(p, kw)
      type(parser_t), intent(inout) :: p
      type(keyword_t), intent(in) :: kw
    end subroutine read_surface_behavior
    module subroutine read_friction(p, kw)
      type(parser_t), intent(inout) :: p
      type(keyword_t), intent(in) :: kw
    end subroutine read_friction
    module subroutine read_wear(p, kw)
      type(parser_t), intent(inout) :: p
      type(keyword_t), intent(in) :: kw
    end subroutine read_wear
    module subroutine read_nodal_thickness(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_nodal_thickness
    module subroutine read_equation(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_equation
    module subroutine interaction_penalties(p, m)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
    end subroutine interaction_penalties
    module subroutine reject_card(p, kw)
      type(parser_t), intent(inout) :: p
      type(keyword_t), intent(in) :: kw
    end subroutine reject_card
    module subroutine read_density(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_density
    module subroutine read_dload(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_dload
    module subroutine read_dsload(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_dsload
    module subroutine read_pretension_section(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_pretension_section
    module subroutine cut_pretension_sections(p, m)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
    end subroutine cut_pretension_sections
    module subroutine read_tie(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_tie
    ! Rigid bodies, couplings and local axes (deck_rigid_cards):
    module subroutine read_rigid_body(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_rigid_body
    module subroutine read_coupling(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_coupling
    module subroutine read_kinematic(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_kinematic
    module subroutine read_distributing(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_distributing
    module subroutine read_transform(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_transform
    module subroutine finish_kinematic_cards(p, m)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
    end subroutine finish_kinematic_cards
    module subroutine check_model(p, m)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
    end subroutine check_model
    ! Abaqus/CAE decks (deck_part_cards):
    module subroutine read_part(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_part
    module subroutine read_end_part(p, kw)
      type(parser_t), intent(inout) :: p
      type(keyword_t), intent(in) :: kw
    end subroutine read_end_part
    module subroutine read_assembly(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_assembly
    module subroutine read_instance(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_instance
    module subroutine read_end_instance(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine read_end_instance
    module subroutine read_end_assembly(p, kw)
      type(parser_t), intent(inout) :: p
      type(keyword_t), intent(in) :: kw
    end subroutine read_end_assembly
    module subroutine check_part_context(p, m, kw)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(in) :: m
      type(keyword_t), intent(in) :: kw
    end subroutine check_part_context
    module subroutine finish_parts(p)
      type(parser_t), intent(inout) :: p
    end subroutine finish_parts
  end interface

contains

  !> Purpose: read the deck at `path` (and its *INCLUDEs) into m; any
  !> problem stops the run with a message naming the file and line.
  subroutine read_model(path, m)
    character(len=*), intent(in) :: path
    type(model_t), intent(out) :: m
    type(parser_t) :: p
    type(keyword_t) :: kw

    call read_deck(path, p%deck)
    if (p%deck%n == 0) call fatal('deck "' // trim(path) // &
        '" has no keyword lines (it is empty or holds only comments and blank lines): nothing to analyse')
    m%deck_name = path
    m%heading = ''
    ! Empty but allocated: the readers grow them, and a deck may leave
    ! any of them empty.
    allocate(m%node_id(0), m%x(2, 0), m%elem_id(0), m%etype(0), m%conn(max_nodes, 0), &
             m%elem_src(0), m%node_index(0), m%elem_index(0))
    allocate(m%nsets(0), m%elsets(0), m%surfaces(0), m%materials(0), m%sections(0), &
             m%amplitudes(0), m%steps(0), m%pairs(0), m%model_bcs(0))
    allocate(m%equations(0), m%initial_temps(0), m%pretensions(0), m%ties(0))
    allocate(m%instances(0), m%rigids(0), m%transforms(0))

    call read_ahead(p, m)
    p%i = 1
    do while (p%i <= p%deck%n)
      if (.not. is_keyword(line_text(p))) call err(p, 'data line where a keyword line was expected')
      if (p%read_ahead(p%i)) then
        ! read by read_ahead: its data lines are passed over; as a card it
        ! still ends a *SURFACE INTERACTION block, stands where *COUPLING
        ! wants its *KINEMATIC, and a *MATERIAL is the one later material
        ! cards describe
        call pass_over(p)
      else
        call parse_keyword(line_text(p), kw)
        call dispatch(p, m, kw)
      end if
      p%i = p%i + 1
    end do
    if (p%step /= 0) then
      p%i = p%step_line
      call err(p, '*STEP without *END STEP')
    end if
    call finish_parts(p)
    if (p%coupling_line > 0) then
      p%i = p%coupling_line
      call err(p, '*COUPLING must be followed by *KINEMATIC or *DISTRIBUTING (the next card)')
    end if
    call lenient_warnings(p)
    call trim_model(p, m)
    call settle_coupled_model(m)
    call finish_kinematic_cards(p, m)
    call cut_pretension_sections(p, m)
    call check_model(p, m)
    call check_orientations(p, m)
    call check_heat_model(p, m)
    call check_coupled_model(p, m)
    call gap_heat_pairs(p, m)
  end subroutine read_model

  !> Purpose: CalculiX reads a deck in passes, its nodes first, then its
  !> elements, sets, surfaces, materials and amplitudes, and then the
  !> rest in order, so that a card may use a node, element, set,
  !> surface, material or amplitude that the deck defines further down.
  !> This reads those cards of a flat deck (outside *STEP) ahead in the
  !> same passes, each pass in deck order, and marks them in
  !> p%read_ahead so that read_model passes them over. A deck with
  !> *PART, *ASSEMBLY or *INSTANCE is read in order, as Abaqus reads it.
  !> A material's cards (*ELASTIC, *DENSITY, ...) are read with it.
  subroutine read_ahead(p, m)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    integer, allocatable :: pass(:)
    integer :: k, i, nmat
    allocate(p%read_ahead(p%deck%n), p%ahead_material(p%deck%n))
    p%read_ahead = .false.
    p%ahead_material = 0
    call ahead_passes(p, pass)
    if (size(pass) == 0) return
    do k = 1, maxval(pass)
      do i = 1, p%deck%n
        if (pass(i) /= k) cycle
        p%i = i
        nmat = p%nmat
        call read_card_at(p, m)
        p%read_ahead(i) = .true.
        if (p%nmat > nmat) p%ahead_material(i) = p%material
      end do
    end do
    ! the cards read in order find the state of their place (pass_over)
    p%interaction = 0
    p%material = 0
  end subroutine read_ahead

  !> Purpose: the card at p%i, read ahead (read_ahead), in its place in
  !> the deck: what its place means for the cards around it (see
  !> dispatch), and its data lines passed over.
  subroutine pass_over(p)
    type(parser_t), intent(inout) :: p
    call card_in_place(p, '')
    if (p%ahead_material(p%i) > 0) p%material = p%ahead_material(p%i)
    do while (next_data(p))
    end do
  end subroutine pass_over

  !> Purpose: what a card named `name` means for the cards around it: a
  !> *SURFACE INTERACTION block ends at the first card that does not
  !> describe it, and *COUPLING says what it is on the next card.
  subroutine card_in_place(p, name)
    type(parser_t), intent(inout) :: p
    character(len=*), intent(in) :: name
    if (name /= 'SURFACE BEHAVIOR' .and. name /= 'FRICTION' .and. name /= 'GAP CONDUCTANCE' .and. &
        name /= 'GAP HEAT GENERATION' .and. name /= 'WEAR') p%interaction = 0
    if (p%coupling_line > 0 .and. name /= 'KINEMATIC' .and. name /= 'DISTRIBUTING') then
      p%i = p%coupling_line
      call err(p, '*COUPLING must be followed by *KINEMATIC or *DISTRIBUTING (the next card)')
    end if
  end subroutine card_in_place

  !> The keyword at p%i handed to its reader.
  subroutine read_card_at(p, m)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t) :: kw
    call parse_keyword(line_text(p), kw)
    call dispatch(p, m, kw)
  end subroutine read_card_at

  !> Purpose: the pass of read_ahead each line is read in (0: in order,
  !> by read_model): 1 *NODE, 2 *ELEMENT, 3 *NSET and *ELSET, 4 *SURFACE,
  !> 5 a material with its cards, 6 *AMPLITUDE and *TIME POINTS; only
  !> model data outside *STEP. Empty when the deck has parts.
  subroutine ahead_passes(p, pass)
    type(parser_t), intent(in) :: p
    integer, allocatable, intent(out) :: pass(:)
    type(keyword_t) :: kw
    character(len=:), allocatable :: name
    logical :: in_step, in_material
    integer :: i
    allocate(pass(p%deck%n))
    pass = 0
    in_step = .false.
    in_material = .false.
    do i = 1, p%deck%n
      if (.not. is_keyword(p%deck%lines(i)%text)) cycle
      call parse_keyword(p%deck%lines(i)%text, kw)
      name = spaced_name(kw%name)
      select case (name)
      case ('PART', 'END PART', 'ASSEMBLY', 'INSTANCE')
        deallocate(pass)
        allocate(pass(0))
        return
      case ('STEP'); in_step = .true.
      case ('END STEP'); in_step = .false.
      end select
      in_material = name == 'MATERIAL' .or. (in_material .and. is_material_card(name))
      if (in_step) cycle
      select case (name)
      case ('NODE'); pass(i) = 1
      case ('ELEMENT'); pass(i) = 2
      case ('NSET', 'ELSET'); pass(i) = 3
      case ('SURFACE'); pass(i) = 4
      case ('AMPLITUDE', 'TIME POINTS'); pass(i) = 6
      case default
        if (in_material) pass(i) = 5
      end select
    end do
  end subroutine ahead_passes

  !> Cards that describe the material of the *MATERIAL before them.
  pure logical function is_material_card(name)
    character(len=*), intent(in) :: name
    select case (name)
    case ('ELASTIC', 'EXPANSION', 'HYPERELASTIC', 'PLASTIC', 'DENSITY', 'SPECIFIC HEAT', 'CONDUCTIVITY', &
          'DAMPING', 'DEFORMATION PLASTICITY')
      is_material_card = .true.
    case default
      is_material_card = .false.
    end select
  end function is_material_card

  !> Purpose: the warnings of CalculiX's leniency that count what they
  !> are about, once the deck is read: node numbers in *NSET lists that
  !> no *NODE defines (dropped from their sets) and node lines that
  !> define a node again (the later coordinates win), each at the first
  !> line concerned.
  subroutine lenient_warnings(p)
    type(parser_t), intent(in) :: p
    character(len=:), allocatable :: ids
    integer :: k
    if (p%dropped_nodes > 0) then
      ids = itoa(p%dropped_ids(1))
      do k = 2, min(p%dropped_nodes, size(p%dropped_ids))
        ids = ids // ', ' // itoa(p%dropped_ids(k))
      end do
      if (p%dropped_nodes > size(p%dropped_ids)) ids = ids // ' and ' // itoa(p%dropped_nodes - &
                                                                          size(p%dropped_ids)) // ' more'
      call deck_warning(p%deck, p%dropped_line, itoa(p%dropped_nodes) // ' node number' // &
        plural(p%dropped_nodes) // ' in *NSET lists ' // trim(merge('names', 'name ', p%dropped_nodes == 1)) // &
        ' no node of the deck (' // ids // &
        '): dropped from their sets, as CalculiX does')
    end if
    if (p%repeated_nodes > 0) call deck_warning(p%deck, p%repeated_line, itoa(p%repeated_nodes) // &
      ' node line' // plural(p%repeated_nodes) // trim(merge(' defines', ' define ', p%repeated_nodes == 1)) // &
      ' a node again: the later coordinates win, as in CalculiX')
  end subroutine lenient_warnings

  pure function plural(n) result(s)
    integer, intent(in) :: n
    character(len=:), allocatable :: s
    s = ''
    if (n /= 1) s = 's'
  end function plural

  !> The model's arrays cut to the number of entries read.
  subroutine trim_model(p, m)
    type(parser_t), intent(in) :: p
    type(model_t), intent(inout) :: m
    m%nsets = m%nsets(1:p%nsets)
    m%elsets = m%elsets(1:p%nelsets)
    m%surfaces = m%surfaces(1:p%nsurf)
    m%materials = m%materials(1:p%nmat)
    m%sections = m%sections(1:p%nsec)
    m%amplitudes = m%amplitudes(1:p%namp)
    m%steps = m%steps(1:p%nsteps)
    m%pairs = m%pairs(1:p%npairs)
    m%model_bcs = m%model_bcs(1:p%nmbc)
    m%equations = m%equations(1:p%nequations)
    m%node_id = m%node_id(1:m%nn)
    m%x = m%x(:, 1:m%nn)
    m%elem_id = m%elem_id(1:m%ne)
    m%etype = m%etype(1:m%ne)
    m%conn = m%conn(:, 1:m%ne)
    m%elem_src = m%elem_src(1:m%ne)
  end subroutine trim_model

  !> Purpose: *BOUNDARY, each data line to its reader: displacement lines
  !> to read_boundary, temperature lines (dof 11, or 0 as CalculiX reads
  !> it: is_heat_line) to read_heat_boundary. One card may hold both, as
  !> CalculiX's (ring3's); each reader passes over the other's lines, and
  !> both end at the card's last line. A card without temperature lines
  !> is read by the mechanical reader alone, as before.
  !> Arguments: p the parser at the keyword line; m the model; kw the card.
  subroutine read_boundary_card(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    logical :: has_heat, has_mech
    integer :: i0
    call boundary_lines(p, has_heat, has_mech)
    i0 = p%i
    if (has_mech .or. .not. has_heat) call read_boundary(p, m, kw)
    if (has_heat) then
      p%i = i0
      call read_heat_boundary(p, m, kw)
    end if
  end subroutine read_boundary_card

  ! ----------------------------------------------------------------- dispatch

  !> Purpose: hand the card starting at keyword kw to its reader, after
  !> checking that it stands in the right part of the deck. Recursive:
  !> *INSTANCE hands its part's cards here again (deck_part_cards).
  recursive subroutine dispatch(p, m, card)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: card
    type(keyword_t) :: kw
    kw = card
    kw%name = spaced_name(card%name)
    ! text on the *HEADING line itself (CalculiX reads it as a heading)
    if (kw%name(1:min(8, len(kw%name))) == 'HEADING ') kw%name = 'HEADING'
    call card_in_place(p, kw%name)
    call check_part_context(p, m, kw)
    select case (kw%name)
    case ('HEADING');       call read_heading(p, m)
    case ('NODE');          call in_step(p, kw, .false.); call read_nodes(p, m, kw)
    case ('ELEMENT');       call in_step(p, kw, .false.); call read_elements(p, m, kw)
    case ('NSET');          call in_step(p, kw, .false.); call read_nset(p, m, kw)
    case ('ELSET');         call in_step(p, kw, .false.); call read_elset(p, m, kw)
    case ('SURFACE');       call in_step(p, kw, .false.); call read_surface(p, m, kw)
    case ('MATERIAL');      call in_step(p, kw, .false.); call read_material(p, m, kw)
    case ('ELASTIC');       call in_step(p, kw, .false.); call read_elastic(p, m, kw)
    case ('EXPANSION');     call in_step(p, kw, .false.); call read_expansion(p, m, kw)
    case ('HYPERELASTIC');  call in_step(p, kw, .false.); call read_hyperelastic(p, m, kw)
    case ('PLASTIC');       call in_step(p, kw, .false.); call read_plastic(p, m, kw)
    case ('DEFORMATION PLASTICITY'); call in_step(p, kw, .false.); call read_deformation_plasticity(p, m, kw)
    case ('INITIAL CONDITIONS')
      call in_step(p, kw, .false.)
      if (to_upper(param_value(kw, 'TYPE')) == 'STRESS') then
        call read_initial_stress(p, m, kw)
      else
        call read_initial_conditions(p, m, kw)
      end if
    case ('TEMPERATURE');   call in_step(p, kw, .true.); call read_temperature(p, m, kw)
    case ('SOLID SECTION'); call in_step(p, kw, .false.); call read_section(p, m, kw)
    case ('ORIENTATION');   call in_step(p, kw, .false.); call read_orientation(p, m, kw)
    case ('SPRING');        call in_step(p, kw, .false.); call read_spring(p, m, kw)
    case ('MASS');          call in_step(p, kw, .false.); call read_mass(p, m, kw)
    case ('AMPLITUDE');     call read_amplitude(p, m, kw)
    case ('BOUNDARY');      call read_boundary_card(p, m, kw)
    case ('CLOAD');         call in_step(p, kw, .true.); call read_cload(p, m, kw)
    case ('DLOAD');         call in_step(p, kw, .true.); call read_dload(p, m, kw)
    case ('DSLOAD');        call in_step(p, kw, .true.); call read_dsload(p, m, kw)
    case ('DENSITY');       call in_step(p, kw, .false.); call read_density(p, m, kw)
    case ('STEP');          call read_step(p, m, kw)
    case ('STATIC');        call in_step(p, kw, .true.); call read_static(p, m, kw)
    case ('FREQUENCY');     call in_step(p, kw, .true.); call read_frequency(p, m, kw)
    case ('END STEP');      call in_step(p, kw, .true.); call read_end_step(p, m, kw)
    case ('NODE PRINT', 'EL PRINT', 'NODE FILE', 'EL FILE', 'CONTACT PRINT', 'CONTACT FILE')
      call in_step(p, kw, .true.)
      call read_request(p, m, kw)
    case ('TIME POINTS');   call read_time_points(p, kw)
    case default
      call dispatch_other(p, m, kw)
    end select
  end subroutine dispatch

  !> Purpose: dispatch's second half: the cards of contact and solver,
  !> constraints, parts and instances, controls, heat transfer, the cards
  !> passed over, and the reason a card is refused.
  recursive subroutine dispatch_other(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    select case (kw%name)
    case ('SOLVER');        call in_step(p, kw, .false.); call read_solver(p, m, kw)
    case ('CONTACT PAIR');  call in_step(p, kw, .false.); call read_contact_pair(p, m, kw)
    case ('CONTACT CONTROLS'); call read_contact_controls(p, m, kw)
    case ('SURFACE INTERACTION'); call in_step(p, kw, .false.); call read_surface_interaction(p, kw)
    case ('SURFACE BEHAVIOR'); call in_step(p, kw, .false.); call read_surface_behavior(p, kw)
    case ('FRICTION');      call in_step(p, kw, .false.); call read_friction(p, kw)
    case ('WEAR');          call in_step(p, kw, .false.); call read_wear(p, kw)
    case ('NODAL THICKNESS'); call in_step(p, kw, .false.); call read_nodal_thickness(p, m, kw)
    case ('EQUATION');      call in_step(p, kw, .false.); call read_equation(p, m, kw)
    case ('PRE-TENSION SECTION'); call in_step(p, kw, .false.); call read_pretension_section(p, m, kw)
    case ('TIE');           call in_step(p, kw, .false.); call read_tie(p, m, kw)
    case ('RIGID BODY');    call in_step(p, kw, .false.); call read_rigid_body(p, m, kw)
    case ('COUPLING');      call in_step(p, kw, .false.); call read_coupling(p, m, kw)
    case ('KINEMATIC');     call in_step(p, kw, .false.); call read_kinematic(p, m, kw)
    case ('DISTRIBUTING');  call in_step(p, kw, .false.); call read_distributing(p, m, kw)
    case ('TRANSFORM');     call in_step(p, kw, .false.); call read_transform(p, m, kw)
    case ('PART');          call in_step(p, kw, .false.); call read_part(p, m, kw)
    case ('END PART');      call read_end_part(p, kw)
    case ('ASSEMBLY');      call in_step(p, kw, .false.); call read_assembly(p, m, kw)
    case ('INSTANCE');      call in_step(p, kw, .false.); call read_instance(p, m, kw)
    case ('END INSTANCE');  call read_end_instance(p, m, kw)
    case ('END ASSEMBLY');  call read_end_assembly(p, kw)
    case ('CONTROLS');      call read_controls(p, m, kw)
    case ('SECTION CONTROLS', 'HOURGLASS STIFFNESS'); call in_step(p, kw, .false.); call read_hourglass_card(p, kw)
    case ('HEAT TRANSFER'); call in_step(p, kw, .true.); call read_heat_transfer(p, m, kw)
    case ('COUPLED TEMPERATURE-DISPLACEMENT'); call in_step(p, kw, .true.); call read_coupled_step(p, m, kw)
    case ('GAP CONDUCTANCE'); call in_step(p, kw, .false.); call read_gap_conductance(p, m, kw)
    case ('GAP HEAT GENERATION'); call in_step(p, kw, .false.); call read_gap_heat_generation(p, m, kw)
    case ('CONDUCTIVITY');  call in_step(p, kw, .false.); call read_conductivity(p, m, kw)
    case ('SPECIFIC HEAT'); call in_step(p, kw, .false.); call read_specific_heat(p, m, kw)
    case ('CFLUX');         call in_step(p, kw, .true.); call read_cflux(p, m, kw)
    case ('DFLUX');         call in_step(p, kw, .true.); call read_dflux(p, m, kw)
    case ('FILM');          call in_step(p, kw, .true.); call read_film(p, m, kw)
    case ('RADIATE');       call in_step(p, kw, .true.); call read_radiate(p, m, kw)
    case ('PHYSICAL CONSTANTS'); call read_physical_constants(p, m, kw)
    case ('CAVITY DEFINITION', 'FLUID SECTION', 'RADIATION VIEWFACTOR', 'VIEWFACTOR', 'FILM PROPERTY', &
          'FLUID CONSTANTS', 'GAS SPECIFIC HEAT')
      call reject_heat_card(p, kw)
    case ('DAMPING', 'FILE FORMAT')
      call skip_card(p, kw)
    case ('OUTPUT', 'NODE OUTPUT', 'ELEMENT OUTPUT', 'CONTACT OUTPUT', &
          'ENERGY PRINT', 'ENERGY FILE', 'SECTION PRINT', 'PREPRINT', &
          'RESTART', 'MONITOR')
      call skip_card(p, kw)
    case ('')
      call err(p, 'keyword line without a keyword after the *')
    case default
      ! not implemented: the reason when it is another procedure or material law
      call reject_card(p, kw)
    end select
  end subroutine dispatch_other

  !> Purpose: the name of a keyword of several words written without its
  !> blanks (`SOLIDSECTION`), as CalculiX reads it (it drops every blank of
  !> a keyword line), or the name unchanged.
  pure function spaced_name(name) result(s)
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: s
    character(len=20), parameter :: spaced(*) = [character(len=20) :: &
      'INITIAL CONDITIONS', 'SOLID SECTION', 'END STEP', 'NODE PRINT', 'EL PRINT', 'NODE FILE', 'EL FILE', &
      'CONTACT PAIR', 'CONTACT CONTROLS', 'SURFACE INTERACTION', 'SURFACE BEHAVIOR', 'NODAL THICKNESS', &
      'SPECIFIC HEAT', 'PHYSICAL CONSTANTS', 'TIME POINTS', 'FILE FORMAT', 'NODE OUTPUT', 'ELEMENT OUTPUT', &
      'CONTACT OUTPUT', 'CONTACT PRINT', 'CONTACT FILE', 'ENERGY PRINT', 'ENERGY FILE', 'SECTION PRINT', &
      'PRE-TENSION SECTION', 'END PART', 'END INSTANCE', 'END ASSEMBLY', 'RIGID BODY', 'SECTION CONTROLS', &
      'HOURGLASS STIFFNESS']
    integer :: i
    s = name
    if (index(name, ' ') > 0) return
    do i = 1, size(spaced)
      if (without_blanks(spaced(i)) == name) then
        s = trim(spaced(i))
        return
      end if
    end do
  end function spaced_name

  pure function without_blanks(t) result(r)
    character(len=*), intent(in) :: t
    character(len=:), allocatable :: r
    integer :: i
    r = ''
    do i = 1, len_trim(t)
      if (t(i:i) /= ' ') r = r // t(i:i)
    end do
  end function without_blanks

  !> Purpose: *HEADING: the first data line is the title; others are kept
  !> out of the model. Text on the *HEADING line itself (`*HEADING my
  !> model`, which CalculiX accepts) is the title, before any data line.
  !> The deck's own title wins over one from a file it includes (gmsh
  !> writes a *Heading into every mesh); otherwise the first title stays.
  subroutine read_heading(p, m)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    character(len=:), allocatable :: inline
    integer :: k
    ! what follows the keyword HEADING on its line, commas and case kept
    inline = adjustl(line_text(p))
    k = index(to_upper(inline), 'HEADING')
    inline = trim(adjustl(inline(k + 7:)))
    if (len(inline) > 0) then
      if (inline(1:1) == ',') inline = trim(adjustl(inline(2:)))
    end if
    if (len(inline) > 0) then
      call take_title(p, m, inline)
    else if (next_data(p)) then
      call take_title(p, m, trim(adjustl(line_text(p))))
    end if
    do while (next_data(p))
    end do
  contains
    subroutine take_title(p, m, title)
      type(parser_t), intent(inout) :: p
      type(model_t), intent(inout) :: m
      character(len=*), intent(in) :: title
      logical :: from_deck
      from_deck = p%deck%lines(p%i)%file == 1
      if (len(m%heading) == 0 .or. (from_deck .and. .not. p%heading_from_deck)) then
        m%heading = title
        p%heading_from_deck = from_deck
        p%heading_line = p%i
      end if
    end subroutine take_title
  end subroutine read_heading


  !> Purpose: cards that cannot change the answer (pure output requests):
  !> warn and skip them with their data lines.
  subroutine skip_card(p, kw)
    type(parser_t), intent(inout) :: p
    type(keyword_t), intent(in) :: kw
    call deck_warning(p%deck, p%i, '*' // kw%name // ' is not implemented in cfe2d and is ignored')
    do while (next_data(p))
    end do
  end subroutine skip_card

  !> Purpose: Abaqus's *SECTION CONTROLS and *HOURGLASS STIFFNESS, read
  !> for the one-point quadrilaterals (CPS4R, CPE4R, CAX4R), whose
  !> hourglass stabilization is cfe2d's own, the counterpart of
  !> HOURGLASS=ENHANCED without a parameter (docs/keywords.md, "Reduced
  !> integration"): *SECTION CONTROLS with HOURGLASS=ENHANCED, or without
  !> HOURGLASS=, and no data line is taken silently (a *SOLID SECTION's
  !> CONTROLS= may name it); another HOURGLASS=, another parameter, scale
  !> factors on its data line and *HOURGLASS STIFFNESS warn at their line
  !> that they are not used.
  subroutine read_hourglass_card(p, kw)
    type(parser_t), intent(inout) :: p
    type(keyword_t), intent(in) :: kw
    character(len=:), allocatable :: hg
    integer :: k
    if (kw%name == 'HOURGLASS STIFFNESS') then
      call deck_warning(p%deck, p%i, '*HOURGLASS STIFFNESS is not used: cfe2d''s hourglass stabilization of ' // &
                        'CPS4R, CPE4R, CAX4R follows from the elastic constants (as HOURGLASS=ENHANCED)')
    else
      hg = to_upper(param_value(kw, 'HOURGLASS'))
      if (len(hg) > 0 .and. hg /= 'ENHANCED') call deck_warning(p%deck, p%i, 'HOURGLASS=' // hg // &
          ' is not cfe2d''s: CPS4R, CPE4R, CAX4R keep their stabilization (as HOURGLASS=ENHANCED)')
      do k = 1, kw%np
        if (kw%pname(k)%s == 'NAME' .or. kw%pname(k)%s == 'HOURGLASS') cycle
        call deck_warning(p%deck, p%i, kw%pname(k)%s // ' of *SECTION CONTROLS is not used by cfe2d')
      end do
      if (next_data(p)) call deck_warning(p%deck, p%i, 'the scale factors of *SECTION CONTROLS are not ' // &
          'used: CPS4R, CPE4R, CAX4R keep their stabilization')
    end if
    do while (next_data(p))
    end do
  end subroutine read_hourglass_card

end module deck_parser
