!> Contact and solver cards: *CONTACT PAIR, *CONTACT CONTROLS, *SOLVER.
submodule (deck_parser) deck_contact_cards
  use kinds, only: dp
  use strings, only: split_fields, to_upper, field_t
  use deck_input, only: param_value, has_param
  use deck_cursor, only: max_cutbacks, max_contact_iterations, line_text, err, next_data, no_data, &
                         allow_params, param_real, param_int, need_nset, new_surface
  use model, only: contact_pair_t, surf_element, surf_node, find_name
  use model_growth, only: grow
  use solver_codes, only: solver_skyline, solver_cholmod, solver_umfpack, order_natural, order_rcm, &
                          order_amd, order_metis, contact_solve_auto, contact_solve_condensed, contact_solve_full
  implicit none

contains

  !> Purpose: *CONTACT PAIR: `slave, master` per data line, the slave a
  !> surface or a node set, the master an element surface; the parameters
  !> (penalty, search) apply to every pair of the card. SYMMETRIC adds the
  !> pair with the roles swapped (two-pass contact).
  module subroutine read_contact_pair(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    type(contact_pair_t) :: c
    integer :: n, npair, first
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
      c%slave_surface = slave_surface(p, m, f(1)%s)
      c%master_surface = find_name(m%surfaces(1:p%nsurf)%name, to_upper(f(2)%s))
      if (c%master_surface == 0) call err(p, 'undefined surface ' // to_upper(f(2)%s))
      if (m%surfaces(c%master_surface)%kind /= surf_element) &
        call err(p, 'the master surface must be element-based')
      if (c%master_surface == c%slave_surface) call err(p, 'slave and master are the same surface')
      c%src%line = p%i
      c%twin = 0
      call add_pair(p, m, c)
      npair = npair + 1
      if (has_param(kw, 'SYMMETRIC')) then
        ! Two-pass contact: the same pair again with the roles swapped.
        if (m%surfaces(c%slave_surface)%kind /= surf_element) &
          call err(p, 'SYMMETRIC needs an element-based slave surface (it is the master of the second pass)')
        first = p%npairs
        m%pairs(first)%twin = first + 1
        c%slave_surface = m%pairs(first)%master_surface
        c%master_surface = m%pairs(first)%slave_surface
        c%twin = first
        call add_pair(p, m, c)
      end if
    end do
    if (npair == 0) call err(p, 'missing data line (slave, master)')
  end subroutine read_contact_pair

  subroutine add_pair(p, m, pair)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(contact_pair_t), intent(in) :: pair
    call grow(m%pairs, p%npairs + 1)
    p%npairs = p%npairs + 1
    m%pairs(p%npairs) = pair
  end subroutine add_pair

  !> The slave surface named on a *CONTACT PAIR line: a surface, or a node
  !> set, which becomes a node surface of the same name.
  integer function slave_surface(p, m, name) result(isurf)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    character(len=*), intent(in) :: name
    integer :: ns
    isurf = find_name(m%surfaces(1:p%nsurf)%name, to_upper(name))
    if (isurf > 0) return
    ns = need_nset(p, m, name)
    isurf = new_surface(p, m)
    m%surfaces(isurf)%name = m%nsets(ns)%name
    m%surfaces(isurf)%kind = surf_node
    allocate(m%surfaces(isurf)%elem(0), m%surfaces(isurf)%edge(0))
    m%surfaces(isurf)%nodes = m%nsets(ns)%items
  end function slave_surface

  !> Purpose: *CONTACT CONTROLS: TOLERANCE= (positive), MAXIT= (contact
  !> status iterations per increment, 1..max_contact_iterations) and
  !> CUTBACKS= (increment bisections, 0..max_cutbacks: each one is a level
  !> of recursion in the analysis, so the count is bounded).
  module subroutine read_contact_controls(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    call allow_params(p, kw, 'TOLERANCE,MAXIT,CUTBACKS')
    m%contact_tolerance = param_real(p, kw, 'TOLERANCE', m%contact_tolerance)
    if (m%contact_tolerance <= 0.0_dp) call err(p, 'TOLERANCE must be positive')
    m%contact_max_iter = param_int(p, kw, 'MAXIT', m%contact_max_iter, 1, max_contact_iterations)
    m%max_cutbacks = param_int(p, kw, 'CUTBACKS', m%max_cutbacks, 0, max_cutbacks)
    call no_data(p, kw)
  end subroutine read_contact_controls

  !> Purpose: *SOLVER: TYPE= (CHOLMOD, UMFPACK, SKYLINE), ORDERING= (AMD
  !> or METIS for the sparse solvers, RCM or NONE for the skyline) and
  !> CONTACT SOLVE= (AUTO, CONDENSED: CHOLMOD only, FULL).
  module subroutine read_solver(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    character(len=:), allocatable :: v
    call allow_params(p, kw, 'TYPE,ORDERING,CONTACT SOLVE')
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
    if (has_param(kw, 'CONTACT SOLVE')) then
      v = to_upper(param_value(kw, 'CONTACT SOLVE'))
      select case (v)
      case ('AUTO'); m%contact_solve = contact_solve_auto
      case ('CONDENSED'); m%contact_solve = contact_solve_condensed
      case ('FULL'); m%contact_solve = contact_solve_full
      case default; call err(p, 'CONTACT SOLVE=' // v // ' is not available (AUTO, CONDENSED, FULL)')
      end select
    end if
    if (m%contact_solve == contact_solve_condensed .and. m%solver /= solver_cholmod) &
      call err(p, 'CONTACT SOLVE=CONDENSED needs TYPE=CHOLMOD (the other solvers factor the full system)')
    call no_data(p, kw)
  end subroutine read_solver
end submodule deck_contact_cards
