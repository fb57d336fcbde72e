!> CalculiX's print file <job>.dat: the blocks *NODE PRINT, *EL PRINT and
!> *CONTACT PRINT ask for, with CalculiX 2.20's captions and number format,
!> so that scripts and tools that parse CalculiX's .dat (FreeCAD, pycalculix,
!> the comparison of CalculiX's test suite with .dat.ref) read cfe2d's:
!>   displacements (vx,vy,vz), forces (fx,fy,fz) and total force of a node
!>   set (TOTALS=YES|ONLY; U and RF of a node with *TRANSFORM in its local
!>   axes unless GLOBAL=YES, as CalculiX); stresses, strains and the equivalent plastic
!>   strain at the integration points of an element set (cfe2d's points of
!>   the 2D element, where CalculiX prints those of the 3D element it
!>   expands a 2D element into); relative contact displacement and contact
!>   stress of the closed slave nodes.
!> Rows are sorted by node or element number, as CalculiX's sets are.
!> Written at the increments the step's FREQUENCY= or TIME POINTS= select.
module results_dat
  use kinds, only: dp
  use model, only: model_t, request_t, elem_nodes, node_axes
  use element_catalogue, only: catalogue, state_plane_stress, state_axisymmetric, shape_quad4, shape_quad8, &
                               shape_tri3, shape_tri6
  use messages, only: fatal
  use analysis_events, only: analysis_observer_t, run_timing_t
  use increment_results, only: increment_results_t
  use output_schedule, only: schedule_t
  implicit none
  private
  public :: dat_file_t, open_dat_file

  type, extends(analysis_observer_t) :: dat_file_t
    integer :: unit = 0
    logical :: open = .false.
    type(schedule_t) :: schedule
  contains
    procedure :: increment_done => write_dat_increment
    procedure :: run_finished => close_dat_file
  end type dat_file_t

contains

  !> Purpose: open <job>.dat (CalculiX writes one, empty if nothing is
  !> printed).
  subroutine open_dat_file(path, f)
    character(len=*), intent(in) :: path
    type(dat_file_t), intent(out) :: f
    integer :: ios
    open(newunit=f%unit, file=path, status='replace', action='write', iostat=ios)
    if (ios /= 0) call fatal('cannot write the CalculiX print file "' // path // '"')
    f%open = .true.
  end subroutine open_dat_file

  !> Purpose: close the file at the end of the run (the timing is not used).
  subroutine close_dat_file(self, timing)
    class(dat_file_t), intent(inout) :: self
    type(run_timing_t), intent(in) :: timing
    if (.not. self%open) return
    close(self%unit)
    self%open = .false.
  end subroutine close_dat_file

  !> Purpose: the print blocks of a converged increment: the node
  !> requests, then the element requests, then the contact blocks, each in
  !> the order of the cards (as CalculiX orders them).
  subroutine write_dat_increment(self, m, res)
    class(dat_file_t), intent(inout) :: self
    type(model_t), intent(in) :: m
    type(increment_results_t), intent(in) :: res
    integer :: q
    if (allocated(res%modes)) call eigenvalue_blocks(self%unit, res%modes, res%modal_total)
    if (.not. self%schedule%due(m, res)) return
    associate(st => m%steps(res%step))
      do q = 1, size(st%requests)
        if (.not. st%requests(q)%to_file .and. st%requests(q)%nodal) &
          call node_blocks(self%unit, m, st%requests(q), res)
      end do
      do q = 1, size(st%requests)
        if (.not. st%requests(q)%to_file .and. .not. st%requests(q)%nodal) &
          call element_blocks(self%unit, m, st%requests(q), res)
      end do
      if (st%contact_print_cdis) call contact_blocks(self%unit, m, res, .true.)
      if (st%contact_print_cstr) call contact_blocks(self%unit, m, res, .false.)
    end associate
    flush(self%unit)
  end subroutine write_dat_increment

  !> Purpose: a *FREQUENCY step's tables as CalculiX 2.20 prints them,
  !> before its first mode: eigenvalues (rad/time, cycles/time; no
  !> imaginary part), participation factors, effective modal masses
  !> with their totals, the total effective mass. The components out of
  !> the plane (z, rotations about x and y) are 0 in 2D.
  !> Arguments: modes(6, n) eigenvalue, omega, frequency, participation
  !> along x, y and about z; total r^T M r along x, y and about z.
  subroutine eigenvalue_blocks(u, modes, total)
    integer, intent(in) :: u
    real(dp), intent(in) :: modes(:, :), total(3)
    character(len=*), parameter :: head = 'MODE NO.   X-COMPONENT     Y-COMPONENT     Z-COMPONENT     ' // &
      'X-ROTATION      Y-ROTATION      Z-ROTATION'
    character(len=*), parameter :: row = '(i7, 6e16.7)'
    integer :: k
    write(u, '(a)') '', '     E I G E N V A L U E   O U T P U T', '', &
      ' MODE NO    EIGENVALUE                       FREQUENCY   ', &
      '                                     REAL PART            IMAGINARY PART', &
      '                           (RAD/TIME)      (CYCLES/TIME     (RAD/TIME)', ''
    do k = 1, size(modes, 2)
      write(u, '(i7, 4e16.7)') k, modes(1:3, k), 0.0_dp
    end do
    write(u, '(a)') '', '     P A R T I C I P A T I O N   F A C T O R S', '', head, ''
    do k = 1, size(modes, 2)
      write(u, row) k, modes(4:5, k), 0.0_dp, 0.0_dp, 0.0_dp, modes(6, k)
    end do
    write(u, '(a)') '', '     E F F E C T I V E   M O D A L   M A S S', '', head, ''
    do k = 1, size(modes, 2)
      write(u, row) k, modes(4:5, k)**2, 0.0_dp, 0.0_dp, 0.0_dp, modes(6, k)**2
    end do
    write(u, '(a, e18.7, 5e16.7)') 'TOTAL', sum(modes(4:5, :)**2, dim=2), 0.0_dp, 0.0_dp, 0.0_dp, sum(modes(6, :)**2)
    write(u, '(a)') '', '     T O T A L   E F F E C T I V E   M A S S', '', head, ''
    write(u, '(7x, 6e16.7)') total(1:2), 0.0_dp, 0.0_dp, 0.0_dp, total(3)
    write(u, '(a)') ''
  end subroutine eigenvalue_blocks

  !> CalculiX's caption: a blank line, the text, a blank line.
  subroutine caption(u, text, time)
    integer, intent(in) :: u
    character(len=*), intent(in) :: text
    real(dp), intent(in) :: time
    write(u, '(a)') ''
    write(u, '(a, e14.7)') ' ' // text // ' and time ', time
    write(u, '(a)') ''
  end subroutine caption

  !> Purpose: the items of a set (all when set = 0) sorted by user id.
  !> Arguments: items the set's items (internal numbers); ids the user
  !> numbers of every node or element.
  function sorted_items(items, ids) result(s)
    integer, intent(in) :: items(:), ids(:)
    integer :: s(size(items)), k, j, t
    s = items
    do k = 2, size(s)          ! insertion sort: sets are short or already sorted
      t = s(k)
      j = k - 1
      do while (j >= 1)
        if (ids(s(j)) <= ids(t)) exit
        s(j + 1) = s(j)
        j = j - 1
      end do
      s(j + 1) = t
    end do
  end function sorted_items

  !> Purpose: *NODE PRINT's blocks in the order of the card:
  !> displacements, forces (RF) and their total over the set (TOTALS=YES:
  !> after the rows; ONLY: the total alone). Values in global axes.
  subroutine node_blocks(u, m, r, res)
    integer, intent(in) :: u
    type(model_t), intent(in) :: m
    type(request_t), intent(in) :: r
    type(increment_results_t), intent(in) :: res
    integer, allocatable :: sel(:)
    character(len=:), allocatable :: sname
    integer :: k, q
    if (r%set > 0) then
      sel = sorted_items(m%nsets(r%set)%items, m%node_id)
      sname = trim(m%nsets(r%set)%name)
    else
      sel = [(k, k = 1, m%nn)]
      sname = 'NALL'
    end if
    ! heat transfer: CalculiX's temperature block (temperature_field)
    if (r%nt .and. res%heat) then
      call caption(u, 'temperatures for set ' // sname, res%total_time)
      do k = 1, size(sel)
        write(u, '(i10, 1p, 1x, e13.6)') m%node_id(sel(k)), tidy(res%nt(sel(k)))
      end do
    end if
    do q = 1, len_trim(r%order)
      if (r%order(q:q) == 'U' .and. .not. r%only_totals) then
        call caption(u, 'displacements (vx,vy,vz) for set ' // sname, res%total_time)
        do k = 1, size(sel)
          write(u, '(i10, 1p, 3(1x, e13.6))') m%node_id(sel(k)), shown(res%u(:, sel(k)), sel(k)), 0.0_dp
        end do
      else if (r%order(q:q) == 'R') then
        if (.not. r%only_totals) then
          call caption(u, 'forces (fx,fy,fz) for set ' // sname, res%total_time)
          do k = 1, size(sel)
            write(u, '(i10, 1p, 3(1x, e13.6))') m%node_id(sel(k)), shown(res%rf(:, sel(k)), sel(k)), 0.0_dp
          end do
        end if
        if (r%totals .or. r%only_totals) then
          ! (the total in global components, as CalculiX sums it)
          call caption(u, 'total force (fx,fy,fz) for set ' // sname, res%total_time)
          write(u, '(6x, 1p, 3(1x, e13.6))') tidy(sum(res%rf(1, sel))), tidy(sum(res%rf(2, sel))), 0.0_dp
        end if
      end if
    end do
  contains
    !> A nodal vector as printed: in the node's local axes (*TRANSFORM)
    !> unless GLOBAL=YES, as CalculiX's *NODE PRINT.
    function shown(v, a) result(w)
      real(dp), intent(in) :: v(2)
      integer, intent(in) :: a
      real(dp) :: w(2)
      w = v
      if (.not. r%global .and. size(m%transforms) > 0) w = matmul(transpose(node_axes(m, a)), v)
      w = tidy(w)
    end function shown
  end subroutine node_blocks

  !> Purpose: a value as printed: magnitudes below 1e-99 as zero, so that
  !> the exponent keeps CalculiX's two digits (round-off only).
  elemental real(dp) function tidy(x)
    real(dp), intent(in) :: x
    tidy = merge(0.0_dp, x, abs(x) < 1.0e-99_dp)
  end function tidy

  !> Purpose: *EL PRINT's blocks in the order of the card, at the
  !> integration points as CalculiX numbers those of the 3D element it
  !> expands a 2D element into (ccx_points): stresses (sxx, syy, szz, sxy,
  !> sxz, syz), strains (the tensor shear, half the engineering one; ezz as
  !> in strain_zz) and the equivalent plastic strain.
  subroutine element_blocks(u, m, r, res)
    integer, intent(in) :: u
    type(model_t), intent(in) :: m
    type(request_t), intent(in) :: r
    type(increment_results_t), intent(in) :: res
    integer, allocatable :: sel(:), pts(:)
    character(len=:), allocatable :: sname
    character(len=1) :: what
    integer :: k, e, j, ip, q
    if (r%hfl .and. res%heat) call heat_flux_block(u, m, r, res)
    if (.not. res%has_stresses) return
    if (r%set > 0) then
      sel = sorted_items(m%elsets(r%set)%items, m%elem_id)
      sname = trim(m%elsets(r%set)%name)
    else
      sel = [(k, k = 1, m%ne)]
      sname = 'EALL'
    end if
    do q = 1, len_trim(r%order)
      what = r%order(q:q)
      select case (what)
      case ('S')
        call caption(u, 'stresses (elem, integ.pnt.,sxx,syy,szz,sxy,sxz,syz) for set ' // sname, res%total_time)
      case ('E')
        call caption(u, 'strains (elem, integ.pnt.,exx,eyy,ezz,exy,exz,eyz) for set ' // sname, res%total_time)
      case ('P')
        if (size(res%peeq_ip, 2) /= m%ne) cycle
        write(u, '(a)') ''
        write(u, '(a, e14.7)') ' equivalent plastic strain (elem, integ.pnt.,pe)for set ' // sname // ' and time ', &
          res%total_time
        write(u, '(a)') ''
      case default
        cycle
      end select
      do k = 1, size(sel)
        e = sel(k)
        pts = ccx_points(m, e, res%nip(e))
        do j = 1, size(pts)
          ip = pts(j)
          select case (what)
          case ('S')
            write(u, '(i10, i4, 1p, 6(1x, e13.6))') m%elem_id(e), j, tidy(res%sig_ip(1:4, ip, e)), 0.0_dp, 0.0_dp
          case ('E')
            write(u, '(i10, i4, 1p, 6(1x, e13.6))') m%elem_id(e), j, tidy(res%eps_ip(1:2, ip, e)), &
              tidy(strain_zz(m, res, e, ip)), tidy(0.5_dp * res%eps_ip(3, ip, e)), 0.0_dp, 0.0_dp
          case ('P')
            write(u, '(i10, i4, 1p, 1x, e13.6)') m%elem_id(e), j, tidy(res%peeq_ip(ip, e))
          end select
        end do
      end do
    end do
  end subroutine element_blocks

  !> Purpose: *EL PRINT HFL of a heat transfer step: CalculiX's heat flux
  !> block (qx, qy, qz = 0) at its integration points (ccx_points).
  subroutine heat_flux_block(u, m, r, res)
    integer, intent(in) :: u
    type(model_t), intent(in) :: m
    type(request_t), intent(in) :: r
    type(increment_results_t), intent(in) :: res
    integer, allocatable :: sel(:), pts(:)
    integer :: k, e, j
    if (r%set > 0) then
      sel = sorted_items(m%elsets(r%set)%items, m%elem_id)
      call caption(u, 'heat flux (elem, integ.pnt.,qx,qy,qz) for set ' // trim(m%elsets(r%set)%name), &
                   res%total_time)
    else
      sel = [(k, k = 1, m%ne)]
      call caption(u, 'heat flux (elem, integ.pnt.,qx,qy,qz) for set EALL', res%total_time)
    end if
    do k = 1, size(sel)
      e = sel(k)
      pts = ccx_points(m, e, res%nip(e))
      do j = 1, size(pts)
        write(u, '(i10, i4, 1p, 3(1x, e13.6))') m%elem_id(e), j, tidy(res%hfl_ip(:, pts(j), e)), 0.0_dp
      end do
    end do
  end subroutine heat_flux_block

  !> Purpose: the integration points CalculiX lists for a 2D element, as
  !> cfe2d's points: CalculiX expands a plane or axisymmetric element into
  !> a 3D one (CPS4 C3D8, CPS4R C3D8R, CPS8R C3D20R, CPS8 C3D20, CPS3 C3D6,
  !> CPS6 C3D15) whose points are the 2D element's points (same order, xi
  !> fastest) in 2 or 3 layers through the thickness, where the values do
  !> not vary. An element whose rule has no such counterpart (CAX6's six
  !> points, trusses) lists its own points.
  function ccx_points(m, e, nip) result(pts)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e, nip
    integer, allocatable :: pts(:)
    integer :: layers, k
    layers = 1
    select case (catalogue(m%etype(e))%shape)
    case (shape_quad4, shape_quad8)
      if (nip == 4) layers = 2
      if (nip == 9) layers = 3
    case (shape_tri3, shape_tri6)
      if (nip == 1) layers = 2
      if (nip == 3) layers = 3
    end select
    pts = [(mod(k - 1, max(nip, 1)) + 1, k = 1, layers * nip)]
  end function ccx_points

  !> Purpose: the out-of-plane strain at an integration point, which
  !> cfe2d's results do not carry: zero in plane strain; in plane stress
  !> the elastic -nu (S11 + S22) / E (exact for an elastic material); in
  !> an axisymmetric element the hoop strain u_r / r averaged over its
  !> nodes off the axis.
  real(dp) function strain_zz(m, res, e, ip)
    type(model_t), intent(in) :: m
    type(increment_results_t), intent(in) :: res
    integer, intent(in) :: e, ip
    integer :: a, n, mat
    real(dp) :: r
    strain_zz = 0.0_dp
    select case (catalogue(m%etype(e))%state)
    case (state_plane_stress)
      if (.not. allocated(m%elem_section)) return
      if (m%elem_section(e) <= 0) return
      mat = m%sections(m%elem_section(e))%material
      if (mat <= 0) return
      if (m%materials(mat)%has_elastic .and. m%materials(mat)%e > 0.0_dp) strain_zz = &
        -m%materials(mat)%nu * (res%sig_ip(1, ip, e) + res%sig_ip(2, ip, e)) / m%materials(mat)%e
    case (state_axisymmetric)
      n = 0
      do a = 1, elem_nodes(m, e)
        r = m%x(1, m%conn(a, e))
        if (r > 0.0_dp) then
          strain_zz = strain_zz + res%u(1, m%conn(a, e)) / r
          n = n + 1
        end if
      end do
      if (n > 0) strain_zz = strain_zz / n
    end select
  end function strain_zz

  !> Purpose: *CONTACT PRINT's blocks at the closed slave nodes (CalculiX
  !> lists its active contact elements): CDIS, the relative contact
  !> displacement (normal: the gap, negative when penetrating; tang1: the
  !> accumulated slip), or CSTR, the contact stress (pressure, shear
  !> traction); no second tangent in 2D.
  subroutine contact_blocks(u, m, res, cdis)
    integer, intent(in) :: u
    type(model_t), intent(in) :: m
    type(increment_results_t), intent(in) :: res
    logical, intent(in) :: cdis
    integer :: k, j
    real(dp) :: t
    write(u, '(a)') ''
    if (cdis) then
      write(u, '(a, e13.7)') ' relative contact displacement (slave node,normal,tang1,tang2) for all contact ' // &
        'elements and time ', res%total_time
    else
      write(u, '(a, e13.7)') ' contact stress (slave node,press,tang1,tang2) for all contact elements and time ', &
        res%total_time
    end if
    write(u, '(a)') ''
    do k = 1, size(res%contact%pairs)
      associate(p => res%contact%pairs(k))
        do j = 1, size(p%slave_node)
          if (p%slave_node(j) <= 0 .or. .not. p%slave_closed(j)) cycle
          if (cdis) then
            t = 0.0_dp
            if (p%frictional) t = p%slave_slip(j)
            write(u, '(i10, 1p, 3(1x, e13.6))') m%node_id(p%slave_node(j)), tidy(p%slave_gap(j)), tidy(t), 0.0_dp
          else
            t = 0.0_dp
            if (p%frictional) t = p%slave_traction(j)
            write(u, '(i10, 1p, 3(1x, e13.6))') m%node_id(p%slave_node(j)), tidy(p%slave_pressure(j)), tidy(t), 0.0_dp
          end if
        end do
      end associate
    end do
  end subroutine contact_blocks
end module results_dat
