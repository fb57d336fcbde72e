!> The load state of a step: which dofs are prescribed, the values they
!> and the concentrated loads start from and go to, their amplitudes, the
!> distributed loads as load patterns, and the node sets whose reactions
!> are summed; evaluated at any step time.
!>
!> A load pattern is one distributed load on one element (a face pressure,
!> a body force, gravity, a centrifugal load) as consistent nodal forces
!> per unit magnitude, with its magnitude at the start and at the end of
!> the step and its own amplitude. Its magnitude at step time t is
!> target * amplitude(t), or without an amplitude the linear ramp from
!> start to target, as for *CLOAD. From step to step a pattern keeps the
!> magnitude it ended with; a new definition of the same element, label
!> and face replaces it (ramping from the old nodal forces to the new ones
!> without an amplitude), OP=NEW removes them all.
!>
!> Temperatures (*TEMPERATURE) go from where the previous step left them
!> to the step's values like prescribed displacements (or follow their
!> amplitude); the thermal strain's nodal loads at time t join f_ext.
module load_state
  use kinds, only: dp
  use strings, only: itoa
  use messages, only: fatal
  use model
  use element_catalogue, only: catalogue, max_nodes, state_axisymmetric
  use distributed_loads, only: face_pressure_load, body_force_load
  use assembly, only: thermal_forces, initial_stress_forces
  implicit none
  private
  public :: load_state_t, load_pattern_t, begin_step, values_at, temperature_change_at, check_loads_reached, &
            follower_loads

  type :: load_pattern_t
    integer :: elem = 0, label = 0, face = 0     ! what it is (dload_t)
    integer :: n = 0                             ! nodes it loads
    integer :: node(max_nodes) = 0
    real(dp) :: f(2, max_nodes) = 0.0_dp         ! nodal forces per unit magnitude
    real(dp) :: start = 0.0_dp, target = 0.0_dp
    integer :: amp = 0
  end type load_pattern_t

  type :: load_state_t
    logical, allocatable :: presc(:, :)                  ! (2, nn)
    real(dp), allocatable :: bc_start(:, :), bc_target(:, :)
    integer, allocatable :: bc_amp(:, :), bc_set(:, :)
    real(dp), allocatable :: ld_start(:, :), ld_target(:, :)
    integer, allocatable :: ld_amp(:, :)
    type(load_pattern_t), allocatable :: pat(:)          ! distributed loads, npat of them
    integer :: npat = 0
    integer, allocatable :: set_ids(:)                   ! node sets with prescribed dofs
    real(dp) :: period = 1.0_dp
    real(dp) :: total_time = 0.0_dp                      ! total time at the step's start
    !> Nodal temperatures (nn): initial, at the step's start and end,
    !> amplitude; thermal: some material expands and some temperature
    !> differs from the initial one in some step.
    real(dp), allocatable :: temp_init(:), temp_start(:), temp_target(:)
    integer, allocatable :: temp_amp(:)
    logical :: thermal = .false.
    !> Nodes the model keeps (kept_nodes); a *BOUNDARY on a dropped node
    !> is ignored, so that it shows zero displacement and no reaction.
    logical, allocatable :: kept(:)
    !> NLGEOM of the step: the thermal strain is then in the elements'
    !> internal force, not a load (assembly's thermal_forces).
    logical :: nlgeom = .false.
    !> The dofs (2 (a - 1) + d) that values_at may set to other than
    !> zero: prescribed, loaded or with a load amplitude (active_dofs, at
    !> the end of begin_step); every other dof's u and fext are zero.
    integer, allocatable :: active(:)
  end type load_state_t

contains

  !> Purpose: the load state of step `is`, which starts from displacements
  !> u and loads fext (the end of the previous step) at total time
  !> total_time. Dofs held in earlier steps stay where they are unless the
  !> step says OP=NEW. Model-data conditions are prescribed in the first
  !> step as the step's own: a non-zero value ramps from the start over
  !> the step (CalculiX 2.20, measured: u = -0.225, -0.45, -0.675, -0.9 in
  !> four increments for a model-data -0.9), then is held like a step's
  !> (a step may change it; it stays where that step left it). Unlike
  !> CalculiX, OP=NEW does not remove them: a model-data dof it releases
  !> is held where it is.
  subroutine begin_step(m, is, u, fext, total_time, ls)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is
    real(dp), intent(in) :: u(:, :), fext(:, :), total_time
    type(load_state_t), intent(inout) :: ls
    real(dp), allocatable :: conc(:, :)
    integer :: j
    logical :: first
    type(bc_t) :: held
    conc = fext
    first = .not. allocated(ls%presc)
    if (first) then
      allocate(ls%presc(2, m%nn), ls%bc_start(2, m%nn), ls%bc_target(2, m%nn), ls%bc_amp(2, m%nn), &
               ls%bc_set(2, m%nn), ls%ld_start(2, m%nn), ls%ld_target(2, m%nn), ls%ld_amp(2, m%nn), ls%pat(16))
      ls%presc = .false.
      ls%bc_target = 0.0_dp
      ls%bc_set = 0
      ls%ld_target = 0.0_dp
      ls%kept = kept_nodes(m)
      call init_temperatures(m, ls)
    else
      ! distributed loads held where the previous step ended them, and
      ! taken out of fext to leave its concentrated part
      call hold_patterns(m, ls)
      call add_patterns(m, ls, 0.0_dp, -1.0_dp, conc)
      call hold_temperatures(m, ls, conc)
    end if
    associate(st => m%steps(is))
      ! (after hold_temperatures: the last step's loads were taken out as it made them)
      ls%nlgeom = st%nlgeom
      ls%period = st%period
      ls%total_time = total_time
      ls%bc_start = u
      where (ls%presc) ls%bc_target = u
      ls%bc_amp = 0
      if (st%new_bcs) then
        ls%presc = .false.
        ls%bc_set = 0
      end if
      do j = 1, size(m%model_bcs)
        ! a prescribed temperature (dof 11, model data of a coupled deck)
        ! is the temperature field's (temperature_field), not a displacement
        if (m%model_bcs(j)%dof > size(ls%presc, 1)) cycle
        if (first) then
          call prescribe(ls, m%model_bcs(j), .false.)
        else if (.not. ls%presc(m%model_bcs(j)%dof, m%model_bcs(j)%node)) then
          held = m%model_bcs(j)
          held%value = u(held%dof, held%node)
          call prescribe(ls, held, .true.)
        end if
      end do
      do j = 1, size(st%bcs)
        call prescribe(ls, st%bcs(j), .false.)
      end do
      ls%ld_start = conc
      ls%ld_amp = 0
      if (st%new_loads) then
        ls%ld_start = 0.0_dp
        ls%ld_target = 0.0_dp
      else
        ls%ld_target = conc
      end if
      do j = 1, size(st%loads)
        ls%ld_target(st%loads(j)%dof, st%loads(j)%node) = st%loads(j)%value
        ls%ld_amp(st%loads(j)%dof, st%loads(j)%node) = st%loads(j)%amp
      end do
      if (st%new_dloads) ls%npat = 0
      do j = 1, step_dloads(st)
        call define_pattern(m, st%dloads(j), ls)
      end do
      if (st%new_temps) ls%temp_target = ls%temp_init
      if (allocated(st%temps)) then
        do j = 1, size(st%temps)
          ls%temp_target(st%temps(j)%node) = st%temps(j)%value
          ls%temp_amp(st%temps(j)%node) = st%temps(j)%amp
        end do
      end if
    end associate
    call prescribed_sets(m, ls)
  end subroutine begin_step

  !> Purpose: ls%active, the dofs values_at computes (the others are zero
  !> there: no prescribed value, and a load ramping from 0 to 0). A
  !> fretting history prescribes one dof at each of its 720 000
  !> increments; the loop over every dof was 4 % of an increment.
  subroutine active_dofs(ls)
    type(load_state_t), intent(inout) :: ls
    integer :: a, d, n
    n = 0
    do a = 1, size(ls%presc, 2)
      do d = 1, 2
        if (dof_active(ls, d, a)) n = n + 1
      end do
    end do
    if (allocated(ls%active)) deallocate(ls%active)
    allocate(ls%active(n))
    n = 0
    do a = 1, size(ls%presc, 2)
      do d = 1, 2
        if (.not. dof_active(ls, d, a)) cycle
        n = n + 1
        ls%active(n) = 2 * (a - 1) + d
      end do
    end do
  end subroutine active_dofs

  !> Purpose: may values_at set dof d of node a to other than zero?
  pure logical function dof_active(ls, d, a)
    type(load_state_t), intent(in) :: ls
    integer, intent(in) :: d, a
    dof_active = ls%presc(d, a) .or. ls%ld_amp(d, a) > 0 .or. ls%ld_start(d, a) /= 0.0_dp .or. &
                 ls%ld_target(d, a) /= 0.0_dp
  end function dof_active

  !> The initial temperatures, held until a step changes them; whether
  !> the model has any thermal strain at all.
  subroutine init_temperatures(m, ls)
    type(model_t), intent(in) :: m
    type(load_state_t), intent(inout) :: ls
    integer :: j
    allocate(ls%temp_init(m%nn), ls%temp_amp(m%nn))
    ls%temp_init = 0.0_dp
    ls%temp_amp = 0
    if (allocated(m%initial_temps)) then
      do j = 1, size(m%initial_temps)
        ls%temp_init(m%initial_temps(j)%node) = m%initial_temps(j)%value
      end do
    end if
    ls%temp_start = ls%temp_init
    ls%temp_target = ls%temp_init
    ls%thermal = .false.
    if (.not. any(m%materials%alpha /= 0.0_dp)) return
    do j = 1, size(m%steps)
      if (allocated(m%steps(j)%temps)) ls%thermal = ls%thermal .or. size(m%steps(j)%temps) > 0
    end do
  end subroutine init_temperatures

  !> The temperatures at the end of the step just finished become the
  !> start and the held target of the next; their thermal loads are taken
  !> out of conc (fext at the end of that step).
  subroutine hold_temperatures(m, ls, conc)
    type(model_t), intent(in) :: m
    type(load_state_t), intent(inout) :: ls
    real(dp), intent(inout) :: conc(:, :)
    real(dp), allocatable :: dtemp(:), fth(:, :)
    allocate(dtemp(m%nn), fth(2, m%nn))
    call temperature_change_at(m, ls, ls%period, dtemp)
    ls%temp_start = ls%temp_init + dtemp
    ls%temp_target = ls%temp_start
    ls%temp_amp = 0
    if (.not. ls%thermal) return
    fth = 0.0_dp
    call thermal_forces(m, dtemp, fth, ls%nlgeom)
    conc = conc - fth
  end subroutine hold_temperatures

  !> Purpose: nodal temperatures at step time t less the initial ones.
  subroutine temperature_change_at(m, ls, t, dtemp)
    type(model_t), intent(in) :: m
    type(load_state_t), intent(in) :: ls
    real(dp), intent(in) :: t
    real(dp), intent(out) :: dtemp(:)
    integer :: a
    do a = 1, m%nn
      if (ls%temp_amp(a) > 0) then
        dtemp(a) = ls%temp_target(a) * amp_at(m, ls, ls%temp_amp(a), t) - ls%temp_init(a)
      else
        dtemp(a) = ls%temp_start(a) + (ls%temp_target(a) - ls%temp_start(a)) * (t / ls%period) - ls%temp_init(a)
      end if
    end do
  end subroutine temperature_change_at

  !> The patterns at the end of the step just finished (ls still holds its
  !> period and start time) become constant at that magnitude; those that
  !> ended at zero are dropped.
  subroutine hold_patterns(m, ls)
    type(model_t), intent(in) :: m
    type(load_state_t), intent(inout) :: ls
    integer :: j, keep
    real(dp) :: mag
    keep = 0
    do j = 1, ls%npat
      mag = pattern_magnitude(m, ls, ls%pat(j), ls%period)
      if (mag == 0.0_dp) cycle
      keep = keep + 1
      ls%pat(keep) = ls%pat(j)
      ls%pat(keep)%start = mag
      ls%pat(keep)%target = mag
      ls%pat(keep)%amp = 0
    end do
    ls%npat = keep
  end subroutine hold_patterns

  !> A distributed load of the step: it replaces the current pattern of
  !> the same element, label and face, which ramps down while the new one
  !> ramps up (the nodal forces go linearly from the old to the new), or
  !> is gone at once when the new one follows an amplitude.
  subroutine define_pattern(m, d, ls)
    type(model_t), intent(in) :: m
    type(dload_t), intent(in) :: d
    type(load_state_t), intent(inout) :: ls
    type(load_pattern_t), allocatable :: tmp(:)
    integer :: k
    do k = 1, ls%npat
      if (ls%pat(k)%elem /= d%elem .or. ls%pat(k)%label /= d%label .or. ls%pat(k)%face /= d%face) cycle
      ls%pat(k)%target = 0.0_dp
      if (d%amp > 0) ls%pat(k)%start = 0.0_dp
      ls%pat(k)%label = -ls%pat(k)%label      ! retired: no longer the current one of its key
    end do
    if (ls%npat == size(ls%pat)) then
      allocate(tmp(2 * size(ls%pat)))
      tmp(1:ls%npat) = ls%pat(1:ls%npat)
      call move_alloc(tmp, ls%pat)
    end if
    ls%npat = ls%npat + 1
    associate(pt => ls%pat(ls%npat))
      pt = load_pattern_t(elem=d%elem, label=d%label, face=d%face, amp=d%amp, start=0.0_dp, target=d%value)
      call unit_forces(m, d, pt)
    end associate
  end subroutine define_pattern

  !> Nodal forces of distributed load d per unit magnitude.
  subroutine unit_forces(m, d, pt)
    type(model_t), intent(in) :: m
    type(dload_t), intent(in) :: d
    type(load_pattern_t), intent(inout) :: pt
    real(dp) :: xy(2, max_nodes), rho, g(2, 2), zero(2)
    integer :: e, et, sec
    e = d%elem
    et = m%etype(e)
    pt%n = catalogue(et)%nodes
    pt%node(1:pt%n) = m%conn(1:pt%n, e)
    xy(:, 1:pt%n) = m%x(:, pt%node(1:pt%n))
    sec = m%elem_section(e)
    if (is_mass(m, e)) then
      call point_mass_forces(m, d, m%sections(sec)%mass, xy(:, 1), pt%f(:, 1))
      return
    end if
    zero = 0.0_dp
    g = 0.0_dp
    rho = m%materials(m%sections(sec)%material)%density
    if ((d%label == dload_grav .or. d%label == dload_centrif) .and. &
        .not. m%materials(m%sections(sec)%material)%has_density) &
      call fatal('gravity or centrifugal load on element ' // elem_label(m, e) // ' needs the density of ' // &
                 'material ' // trim(m%materials(m%sections(sec)%material)%name) // ' (*DENSITY)')
    associate(t => elem_thickness(m, e))
      select case (d%label)
      case (dload_p)
        call face_pressure_load(et, xy, t, d%face, pt%f)
      case (dload_bx)
        call body_force_load(et, xy, t, [1.0_dp, 0.0_dp], g, zero, pt%f)
      case (dload_by)
        call body_force_load(et, xy, t, [0.0_dp, 1.0_dp], g, zero, pt%f)
      case (dload_grav)
        call body_force_load(et, xy, t, rho * d%dir, g, zero, pt%f)
      case (dload_centrif)
        ! rho omega^2 times the distance from the axis: (r, 0) about the
        ! y axis in axisymmetry; (I - a a^T)(x - x0) about an axis a in the
        ! plane, (x - x0, y - y0) about a normal one (a = 0)
        if (catalogue(et)%state == state_axisymmetric) then
          g(1, 1) = rho
        else
          g = rho * off_axis(d%dir)
        end if
        call body_force_load(et, xy, t, zero, g, d%point, pt%f)
      end select
    end associate
  end subroutine unit_forces

  !> The force of unit GRAV or CENTRIF load d on a point mass at x: mass
  !> times the acceleration (the centrifugal one from the distance to the
  !> axis: the radius in an axisymmetric model, whose masses are whole
  !> rings; the in-plane distance to the axis otherwise).
  subroutine point_mass_forces(m, d, mass, x, f)
    type(model_t), intent(in) :: m
    type(dload_t), intent(in) :: d
    real(dp), intent(in) :: mass, x(2)
    real(dp), intent(out) :: f(2)
    if (d%label == dload_grav) then
      f = mass * d%dir
    else if (axisymmetric_model(m)) then
      f = mass * [x(1), 0.0_dp]
    else
      f = mass * matmul(off_axis(d%dir), x - d%point)
    end if
  end subroutine point_mass_forces

  !> Purpose: the projection I - a a^T onto the directions normal to the
  !> in-plane unit axis a of a centrifugal load (the identity for a = 0,
  !> an axis normal to the plane): it takes the distance from the axis'
  !> point to the distance from the axis.
  pure function off_axis(a) result(q)
    real(dp), intent(in) :: a(2)
    real(dp) :: q(2, 2)
    q = reshape([1.0_dp - a(1) * a(1), -a(2) * a(1), -a(1) * a(2), 1.0_dp - a(2) * a(2)], [2, 2])
  end function off_axis

  !> Magnitude of a pattern at step time t.
  real(dp) function pattern_magnitude(m, ls, pt, t)
    type(model_t), intent(in) :: m
    type(load_state_t), intent(in) :: ls
    type(load_pattern_t), intent(in) :: pt
    real(dp), intent(in) :: t
    if (pt%amp > 0) then
      pattern_magnitude = pt%target * amp_at(m, ls, pt%amp, t)
    else
      pattern_magnitude = pt%start + (pt%target - pt%start) * (t / ls%period)
    end if
  end function pattern_magnitude

  !> f = f + factor * (the nodal forces of every pattern at step time t);
  !> under NLGEOM (ls%nlgeom) the face pressures follow the deformed faces
  !> and are the body's (follower_loads), not part of f.
  subroutine add_patterns(m, ls, t, factor, f)
    type(model_t), intent(in) :: m
    type(load_state_t), intent(in) :: ls
    real(dp), intent(in) :: t, factor
    real(dp), intent(inout) :: f(:, :)
    integer :: j, k
    real(dp) :: mag
    do j = 1, ls%npat
      if (ls%nlgeom .and. is_follower(m, ls%pat(j))) cycle
      associate(pt => ls%pat(j))
        mag = factor * pattern_magnitude(m, ls, pt, t)
        if (mag == 0.0_dp) cycle
        do k = 1, pt%n
          f(:, pt%node(k)) = f(:, pt%node(k)) + mag * pt%f(:, k)
        end do
      end associate
    end do
  end subroutine add_patterns

  !> A face pressure of a continuum element: under NLGEOM a follower load.
  pure logical function is_follower(m, pt)
    type(model_t), intent(in) :: m
    type(load_pattern_t), intent(in) :: pt
    is_follower = abs(pt%label) == dload_p .and. pt%face > 0 .and. is_continuum(m, pt%elem)
  end function is_follower

  !> Purpose: the follower pressures of a NLGEOM step at step time t, by
  !> element (CSR): those on element e are k = ptr(e) .. ptr(e+1)-1, on
  !> face face(k) with magnitude mag(k) (assembly's body_t%fl_*). Empty
  !> (ptr all 1) outside NLGEOM.
  subroutine follower_loads(m, ls, t, ptr, face, mag)
    type(model_t), intent(in) :: m
    type(load_state_t), intent(in) :: ls
    real(dp), intent(in) :: t
    integer, allocatable, intent(out) :: ptr(:), face(:)
    real(dp), allocatable, intent(out) :: mag(:)
    integer :: j, e, n
    integer, allocatable :: next(:)
    allocate(ptr(m%ne + 1))
    ptr = 0
    n = 0
    do j = 1, ls%npat
      if (.not. (ls%nlgeom .and. is_follower(m, ls%pat(j)))) cycle
      ptr(ls%pat(j)%elem + 1) = ptr(ls%pat(j)%elem + 1) + 1
      n = n + 1
    end do
    ptr(1) = 1
    do e = 1, m%ne
      ptr(e + 1) = ptr(e + 1) + ptr(e)
    end do
    allocate(face(n), mag(n))
    next = ptr(1:m%ne)
    do j = 1, ls%npat
      if (.not. (ls%nlgeom .and. is_follower(m, ls%pat(j)))) cycle
      e = ls%pat(j)%elem
      face(next(e)) = ls%pat(j)%face
      mag(next(e)) = pattern_magnitude(m, ls, ls%pat(j), t)
      next(e) = next(e) + 1
    end do
  end subroutine follower_loads

  subroutine prescribe(ls, bc, immediate)
    type(load_state_t), intent(inout) :: ls
    type(bc_t), intent(in) :: bc
    logical, intent(in) :: immediate
    if (.not. ls%kept(bc%node)) return
    ls%presc(bc%dof, bc%node) = .true.
    ls%bc_target(bc%dof, bc%node) = bc%value
    ls%bc_amp(bc%dof, bc%node) = bc%amp
    if (bc%set > 0) ls%bc_set(bc%dof, bc%node) = bc%set
    if (immediate) ls%bc_start(bc%dof, bc%node) = bc%value
  end subroutine prescribe

  !> Purpose: the lists a step's conditions give: the node sets named by
  !> active boundary conditions (reaction sums) and, by active_dofs, the
  !> dofs values_at computes.
  subroutine prescribed_sets(m, ls)
    type(model_t), intent(in) :: m
    type(load_state_t), intent(inout) :: ls
    integer :: a, d, s
    logical, allocatable :: used(:)
    allocate(used(size(m%nsets)))
    used = .false.
    do a = 1, m%nn
      do d = 1, 2
        s = ls%bc_set(d, a)
        if (ls%presc(d, a) .and. s > 0) used(s) = .true.
      end do
    end do
    ls%set_ids = pack([(s, s = 1, size(m%nsets))], used)
    call active_dofs(ls)
  end subroutine prescribed_sets

  !> Purpose: prescribed displacements into u (free dofs set to zero, the
  !> start of the equilibrium iteration) and loads into fext at step time t:
  !> the concentrated loads, the distributed loads' patterns and the
  !> thermal strain's loads.
  subroutine values_at(m, ls, t, u, fext)
    type(model_t), intent(in) :: m
    type(load_state_t), intent(in) :: ls
    real(dp), intent(in) :: t
    real(dp), intent(out) :: u(:, :), fext(:, :)
    integer :: a, d, k
    real(dp) :: ramp
    ramp = t / ls%period
    ! (the other dofs: no prescribed value; a load of 0 + (0 - 0) ramp)
    u = 0.0_dp
    fext = 0.0_dp
    do k = 1, size(ls%active)
      a = (ls%active(k) + 1) / 2
      d = ls%active(k) - 2 * (a - 1)
      if (ls%presc(d, a)) then
        if (ls%bc_amp(d, a) > 0) then
          u(d, a) = ls%bc_target(d, a) * amp_at(m, ls, ls%bc_amp(d, a), t)
        else
          u(d, a) = ls%bc_start(d, a) + (ls%bc_target(d, a) - ls%bc_start(d, a)) * ramp
        end if
      end if
      if (ls%ld_amp(d, a) > 0) then
        fext(d, a) = ls%ld_target(d, a) * amp_at(m, ls, ls%ld_amp(d, a), t)
      else
        fext(d, a) = ls%ld_start(d, a) + (ls%ld_target(d, a) - ls%ld_start(d, a)) * ramp
      end if
    end do
    call add_patterns(m, ls, t, 1.0_dp, fext)
    if (ls%thermal) then
      block
        real(dp), allocatable :: dtemp(:)
        allocate(dtemp(m%nn))
        call temperature_change_at(m, ls, t, dtemp)
        call thermal_forces(m, dtemp, fext, ls%nlgeom)
      end block
    end if
    call initial_stress_forces(m, fext)
  end subroutine values_at

  !> Purpose: stops if a concentrated load of the step acts on a dof
  !> that nothing carries: inactive(2, nn) marks the unused dofs of nodes
  !> that belong to no element and that only constraints name.
  subroutine check_loads_reached(m, ls, inactive)
    type(model_t), intent(in) :: m
    type(load_state_t), intent(in) :: ls
    logical, intent(in) :: inactive(:, :)
    integer :: a, d, j, k
    do a = 1, m%nn
      do d = 1, 2
        if (.not. inactive(d, a)) cycle
        if (ls%ld_target(d, a) /= 0.0_dp .or. ls%ld_start(d, a) /= 0.0_dp) call fatal('a *CLOAD acts on dof ' // &
          itoa(d) // ' of node ' // node_label(m, a) // ', which belongs to no element and which no ' // &
          '*EQUATION names: nothing carries it')
      end do
    end do
    ! a point mass's weight or spin on such a dof would be lost just the same
    do j = 1, ls%npat
      do k = 1, ls%pat(j)%n
        a = ls%pat(j)%node(k)
        do d = 1, 2
          if (inactive(d, a) .and. ls%pat(j)%f(d, k) /= 0.0_dp) call fatal('a *DLOAD (a point mass''s ' // &
            'load) acts on dof ' // itoa(d) // ' of node ' // node_label(m, a) // ', which belongs to no ' // &
            'element with stiffness and which no *EQUATION names: nothing carries it')
        end do
      end do
    end do
  end subroutine check_loads_reached

  real(dp) function amp_at(m, ls, ia, t)
    type(model_t), intent(in) :: m
    type(load_state_t), intent(in) :: ls
    integer, intent(in) :: ia
    real(dp), intent(in) :: t
    if (m%amplitudes(ia)%time == amp_total_time) then
      amp_at = amplitude_at(m%amplitudes(ia), ls%total_time + t)
    else
      amp_at = amplitude_at(m%amplitudes(ia), t)
    end if
  end function amp_at
end module load_state
