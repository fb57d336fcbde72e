!> Distributed-load cards: *DLOAD, *DSLOAD (history data) and *DENSITY
!> (material data, which gravity and centrifugal loads need).
submodule (deck_parser) deck_load_cards
  use kinds, only: dp
  use strings, only: split_fields, to_upper, field_t, itoa
  use deck_input, only: param_value, has_param
  use deck_cursor, only: line_text, err, next_data, require_data, allow_params, get_real, &
                         is_label, elem_ref, need_elset, warn_empty_set, amplitude_param
  use model, only: dload_t, surf_element, find_name, is_continuum, is_mass, axisymmetric_model, step_dloads, &
                   dload_p, dload_bx, dload_by, dload_grav, dload_centrif, elem_label
  use element_catalogue, only: catalogue, state_axisymmetric, is_line
  implicit none

  !> Direction components this small (relative to the vector) count as zero.
  real(dp), parameter :: axis_tol = 1.0e-9_dp

contains

  !> Purpose: *DENSITY: `density` of the current material (one data line;
  !> temperature dependence is not implemented).
  module subroutine read_density(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    integer :: n
    call allow_params(p, kw, '')
    if (p%material == 0) call err(p, '*DENSITY outside a *MATERIAL')
    call require_data(p, 'density')
    call split_fields(line_text(p), f, n)
    if (n > 2) call err(p, 'temperature-dependent *DENSITY data is not implemented')
    associate(mat => m%materials(p%material))
      mat%density = get_real(p, f(1), 'density')
      if (mat%density <= 0.0_dp) call err(p, 'density must be positive')
      mat%has_density = .true.
    end associate
    if (next_data(p)) call err(p, 'temperature-dependent *DENSITY data is not implemented')
  end subroutine read_density

  !> Purpose: *DLOAD: distributed loads on elements, `element or elset,
  !> label, magnitude[, ...]` with the labels P1..P4 (face pressure), BX,
  !> BY (BR, BZ in axisymmetry: body force per unit volume), GRAV (`g, nx,
  !> ny, nz`: gravity, needs *DENSITY) and CENTRIF (`omega^2, point, axis`,
  !> the axis normal to the plane or in it: needs *DENSITY); OP=,
  !> AMPLITUDE= as for *CLOAD. OP=NEW without data lines removes the
  !> distributed loads of earlier steps.
  module subroutine read_dload(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    type(dload_t), allocatable :: new(:)
    integer, allocatable :: elems(:)
    integer :: n, k, amp, nnew, es
    call allow_params(p, kw, 'OP,AMPLITUDE')
    call load_options(p, m, kw, amp)
    nnew = 0
    do while (next_data(p))
      call split_fields(line_text(p), f, n)
      if (n < 3) call err(p, '*DLOAD data line needs: element or element set, load label, magnitude')
      if (is_label(f(1)%s)) then
        elems = [elem_ref(p, m, f(1), 'element')]
      else
        es = need_elset(p, m, f(1)%s)
        elems = m%elsets(es)%items
        call warn_empty_set(p, size(elems), 'element set', m%elsets(es)%name, kw%name)
      end if
      allocate(new(size(elems)))
      do k = 1, size(elems)
        new(k) = element_dload(p, m, elems(k), f, n, amp)
      end do
      call add_dloads(m, p%step, new)
      nnew = nnew + 1
      deallocate(new)
    end do
    ! OP=NEW alone removes the earlier distributed loads
    if (nnew == 0 .and. .not. m%steps(p%step)%new_dloads) &
      call err(p, 'missing data line (element or element set, load label, magnitude)')
  end subroutine read_dload

  !> Purpose: *DSLOAD: a pressure on an element-based surface, `surface,
  !> P, magnitude`; OP=, AMPLITUDE= as for *CLOAD.
  module subroutine read_dsload(p, m, kw)
    type(parser_t), intent(inout) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    type(field_t), allocatable :: f(:)
    type(dload_t), allocatable :: new(:)
    integer :: n, k, amp, isurf, nnew
    real(dp) :: pressure
    call allow_params(p, kw, 'OP,AMPLITUDE')
    call load_options(p, m, kw, amp)
    nnew = 0
    do while (next_data(p))
      call split_fields(line_text(p), f, n)
      if (n /= 3) call err(p, '*DSLOAD data line needs: surface, P, magnitude')
      isurf = find_name(m%surfaces(1:p%nsurf)%name, to_upper(f(1)%s))
      if (isurf == 0) call err(p, 'undefined surface ' // to_upper(f(1)%s))
      if (m%surfaces(isurf)%kind /= surf_element) call err(p, 'surface ' // to_upper(f(1)%s) // &
          ' is a node surface: *DSLOAD needs an element-based surface')
      if (to_upper(f(2)%s) /= 'P') call err(p, 'load label ' // to_upper(f(2)%s) // &
          ' is not implemented on *DSLOAD (only P, a pressure)')
      pressure = get_real(p, f(3), 'pressure')
      associate(s => m%surfaces(isurf))
        call warn_empty_set(p, size(s%elem), 'surface', s%name, kw%name)
        allocate(new(size(s%elem)))
        do k = 1, size(s%elem)
          new(k) = dload_t(elem=s%elem(k), label=dload_p, face=s%edge(k), amp=amp, value=pressure)
        end do
      end associate
      call add_dloads(m, p%step, new)
      nnew = nnew + 1
      deallocate(new)
    end do
    if (nnew == 0 .and. .not. m%steps(p%step)%new_dloads) call err(p, 'missing data line (surface, P, magnitude)')
  end subroutine read_dsload

  !> OP= (NEW removes the distributed loads of earlier steps) and
  !> AMPLITUDE= of *DLOAD and *DSLOAD.
  subroutine load_options(p, m, kw, amp)
    type(parser_t), intent(in) :: p
    type(model_t), intent(inout) :: m
    type(keyword_t), intent(in) :: kw
    integer, intent(out) :: amp
    character(len=:), allocatable :: op
    op = 'MOD'
    if (has_param(kw, 'OP')) op = to_upper(param_value(kw, 'OP'))
    if (op /= 'MOD' .and. op /= 'NEW') call err(p, 'OP must be MOD or NEW')
    if (op == 'NEW') m%steps(p%step)%new_dloads = .true.
    amp = amplitude_param(p, m, kw)
  end subroutine load_options

  subroutine add_dloads(m, is, new)
    type(model_t), intent(inout) :: m
    integer, intent(in) :: is
    type(dload_t), intent(in) :: new(:)
    if (step_dloads(m%steps(is)) == 0) then
      m%steps(is)%dloads = new
    else
      m%steps(is)%dloads = [m%steps(is)%dloads, new]
    end if
  end subroutine add_dloads

  !> The load a *DLOAD data line (fields f(1:n)) puts on element e.
  type(dload_t) function element_dload(p, m, e, f, n, amp) result(d)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    integer, intent(in) :: e, n, amp
    type(field_t), intent(in) :: f(:)
    character(len=:), allocatable :: label
    logical :: axi
    label = to_upper(f(2)%s)
    if (is_mass(m, e)) then
      ! A point mass takes the loads of its mass only, about the model's axis.
      if (label /= 'GRAV' .and. label /= 'CENTRIF') call err(p, 'element ' // elem_label(m, e) // &
          ' is a point mass (MASS): it takes GRAV and CENTRIF loads only')
      axi = axisymmetric_model(m)
    else if (is_line(catalogue(m%etype(e))%shape)) then
      ! A line element with a section is a truss: body forces over its length.
      if (section_of(p, m, e) == 0) call err(p, 'element ' // elem_label(m, e) // ' (' // &
          trim(catalogue(m%etype(e))%name) // ') has no *SOLID SECTION (yet): a line element takes a ' // &
          'distributed load as a truss, whose section must come before the step')
      if (index(label, 'P') == 1) call err(p, 'element ' // elem_label(m, e) // ' is a truss: it takes body ' // &
          'forces (BX, BY, GRAV, CENTRIF), not pressures')
      axi = .false.
    else
      if (.not. is_continuum(m, e)) call err(p, 'element ' // elem_label(m, e) // ' (' // &
          trim(catalogue(m%etype(e))%name) // ') is not a solid element: distributed loads act on solid ' // &
          'elements, trusses and point masses only (load a spring with *CLOAD)')
      axi = catalogue(m%etype(e))%state == state_axisymmetric
    end if
    d = dload_t(elem=e, amp=amp, value=get_real(p, f(3), 'load magnitude'))
    if (len(label) == 2 .and. label(1:1) == 'P' .and. index('123456789', label(2:2)) > 0) label = 'PK'
    select case (label)
    case ('PK')
      label = to_upper(f(2)%s)
      d%label = dload_p
      d%face = index('123456789', label(2:2))
      if (d%face > catalogue(m%etype(e))%nedges) call err(p, 'face ' // label(2:2) // ' does not exist for ' // &
          trim(catalogue(m%etype(e))%name) // ' (faces 1..' // itoa(catalogue(m%etype(e))%nedges) // ')')
      call no_more(p, n, 3, label)
    case ('BX', 'BR')
      if (label == 'BR' .and. .not. axi) &
        call err(p, 'BR is the radial body force of axisymmetric elements (plane elements take BX)')
      d%label = dload_bx
      call no_more(p, n, 3, label)
    case ('BY', 'BZ')
      if (label == 'BZ' .and. .not. axi) call err(p, 'BZ acts out of the plane of a plane element (use BY; '// &
          'BZ is the axial body force of axisymmetric elements only)')
      d%label = dload_by
      call no_more(p, n, 3, label)
    case ('GRAV')
      d%label = dload_grav
      d%dir = gravity_direction(p, f, n, axi)
      call need_density(p, m, e, label)
    case ('CENTRIF')
      d%label = dload_centrif
      call centrifugal_axis(p, f, n, axi, d%point, d%dir)
      call need_density(p, m, e, label)
    case default
      call err(p, 'load label ' // label // ' is not implemented (P1..P4, BX, BY, BR, BZ, GRAV, CENTRIF)')
    end select
  end function element_dload

  subroutine no_more(p, n, nmax, label)
    type(parser_t), intent(in) :: p
    integer, intent(in) :: n, nmax
    character(len=*), intent(in) :: label
    if (n > nmax) call err(p, label // ' takes one magnitude: element or set, ' // label // ', magnitude')
  end subroutine no_more

  !> GRAV: `g, nx, ny[, nz]`, the unit direction in the plane (along the
  !> axis in axisymmetry).
  function gravity_direction(p, f, n, axi) result(dir)
    type(parser_t), intent(in) :: p
    type(field_t), intent(in) :: f(:)
    integer, intent(in) :: n
    logical, intent(in) :: axi
    real(dp) :: dir(2), v(3), len
    if (n < 5 .or. n > 6) call err(p, 'GRAV needs: element or set, GRAV, g, nx, ny[, nz]')
    v = 0.0_dp
    v(1) = get_real(p, f(4), 'gravity direction x')
    v(2) = get_real(p, f(5), 'gravity direction y')
    if (n == 6) v(3) = get_real(p, f(6), 'gravity direction z')
    len = norm2(v)
    if (.not. len > 0.0_dp) call err(p, 'the gravity direction is a zero vector')
    v = v / len
    if (abs(v(3)) > axis_tol) call err(p, 'gravity out of the x-y plane is not possible in 2D')
    if (axi .and. abs(v(1)) > axis_tol) call err(p, 'gravity across the axis of an axisymmetric element is ' // &
        'not axisymmetric: its direction must be the axis (0, 1, 0) or (0, -1, 0)')
    dir = v(1:2)
  end function gravity_direction

  !> Purpose: CENTRIF: `omega^2, x0, y0, z0, ax, ay, az`, a point of the
  !> axis and its direction. The load density is rho omega^2 r_perp, r_perp
  !> the distance vector from the axis, perpendicular to it. Axisymmetric
  !> elements: the axis must be the y axis (their symmetry axis). Plane
  !> elements (the mid-plane z = 0): an axis normal to the plane gives
  !> r_perp = x - x0 in the plane; an axis in the plane (az = 0, through a
  !> point with z0 = 0; a blade spinning about an axis along y) gives
  !> r_perp = (I - a a^T)(x - x0), in the plane too. Any other axis (tilted,
  !> or in-plane but off the plane) has an out-of-plane part in r_perp,
  !> which a 2D model cannot carry: an error.
  !> Arguments: pt the axis' point in the plane; dir the unit in-plane
  !> direction of an axis lying in the plane, 0 for an axis normal to it
  !> (and for axisymmetric elements).
  subroutine centrifugal_axis(p, f, n, axi, pt, dir)
    type(parser_t), intent(in) :: p
    type(field_t), intent(in) :: f(:)
    integer, intent(in) :: n
    logical, intent(in) :: axi
    real(dp), intent(out) :: pt(2), dir(2)
    real(dp) :: x(3), a(3), len, scale
    integer :: k
    if (n /= 9) call err(p, 'CENTRIF needs: element or set, CENTRIF, omega^2, x0, y0, z0, ax, ay, az')
    do k = 1, 3
      x(k) = get_real(p, f(3 + k), 'point of the rotation axis')
      a(k) = get_real(p, f(6 + k), 'direction of the rotation axis')
    end do
    len = norm2(a)
    if (.not. len > 0.0_dp) call err(p, 'the rotation axis direction is a zero vector')
    a = a / len
    scale = axis_tol * max(1.0_dp, norm2(x))
    dir = 0.0_dp
    if (axi) then
      if (abs(a(1)) > axis_tol .or. abs(a(3)) > axis_tol .or. abs(x(1)) > scale .or. abs(x(3)) > scale) &
        call err(p, 'the rotation axis of an axisymmetric element must be its symmetry axis, the y axis ' // &
                    '(point 0, y, 0; direction 0, 1, 0)')
    else if (abs(a(3)) <= axis_tol) then
      if (abs(x(3)) > scale) call err(p, 'the rotation axis lies along the x-y plane but off it (z0 is not ' // &
          '0): its centrifugal load has an out-of-plane part, which a plane element cannot carry')
      dir = a(1:2) / norm2(a(1:2))
    else if (abs(a(1)) > axis_tol .or. abs(a(2)) > axis_tol) then
      call err(p, 'the rotation axis of a plane element must be normal to the x-y plane (direction 0, 0, 1) ' // &
          'or lie in it (az = 0, z0 = 0): about a tilted axis the centrifugal load has an out-of-plane part, ' // &
          'which a plane element cannot carry')
    end if
    pt = x(1:2)
  end subroutine centrifugal_axis

  !> The section (read so far) whose element set holds element e, 0 if none.
  integer function section_of(p, m, e) result(s)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    do s = 1, p%nsec
      if (any(m%elsets(m%sections(s)%elset)%items == e)) return
    end do
    s = 0
  end function section_of

  !> GRAV and CENTRIF need the density of the element's material; checked
  !> here when the section and material are already known (model data
  !> normally are), and at the start of the analysis otherwise.
  subroutine need_density(p, m, e, label)
    type(parser_t), intent(in) :: p
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    character(len=*), intent(in) :: label
    integer :: s, imat
    s = section_of(p, m, e)
    if (s == 0) return
    imat = find_name(m%materials(1:p%nmat)%name, m%sections(s)%material_name)
    if (imat == 0) return
    if (.not. m%materials(imat)%has_density) call err(p, label // ' on element ' // elem_label(m, e) // &
        ' needs the density of material ' // trim(m%materials(imat)%name) // ' (*DENSITY)')
  end subroutine need_density
end submodule deck_load_cards
