!> CalculiX's result file <job>.frd (ASCII), so that cgx, ccx2paraview,
!> pycalculix and other readers of CalculiX's results read cfe2d's. The
!> layout is CalculiX 2.20's as it writes a 2D model with OUTPUT=2D: the
!> header records (1C, 1U), the node block (2C, z = 0), the element block
!> (3C) with CalculiX's 2D element type codes (7 tr3, 8 tr6, 9 qu4,
!> 10 qu8, 11 be2, 12 be3), and per written increment one result block
!> (1P, 100C, -4, -5, -1 records, -3) for each quantity the step's file
!> cards ask for: DISP (U), STRESS (S), TOSTRAIN (E), FORC (RF), PE (PEEQ),
!> CONTACT (CSTR/CDIS of *CONTACT FILE), all at the nodes, in that order
!> (CalculiX's). Each written increment is flushed to the file; the end
!> record 9999 is written when the run finishes.
!> Numbers are written as CalculiX writes them (1X,I2,I10,6E12.5 records).
module results_frd
  use kinds, only: dp, program_version
  use strings, only: itoa, e12_5, int_field
  use model, only: model_t, carries_stiffness, elem_nodes, kept_nodes
  use element_catalogue, only: catalogue, file_node_order, shape_tri3, shape_tri6, shape_quad4, shape_quad8, &
                               shape_line2, shape_line3, state_plane_stress, state_axisymmetric
  use messages, only: fatal
  use analysis_events, only: analysis_observer_t, run_timing_t
  use increment_results, only: increment_results_t
  use output_schedule, only: schedule_t
  implicit none
  private
  public :: frd_file_t, open_frd_file, frd_type

  type, extends(analysis_observer_t) :: frd_file_t
    character(len=:), allocatable :: path
    integer :: unit = 0
    logical :: open = .false.      ! (newunit numbers are negative)
    integer :: blocks = 0          ! result blocks written (the 1PSTEP counter)
    integer :: sets = 0            ! increments written (the 100CL counter)
    integer, allocatable :: ids(:) ! user node ids
    logical, allocatable :: kept(:) ! the nodes written: those the analysis keeps
    type(schedule_t) :: schedule   ! which increments are written (FREQUENCY=, TIME POINTS=)
  contains
    procedure :: increment_done => write_frd_increment
    procedure :: run_finished => close_frd_file
  end type frd_file_t

  !> What the step's file cards ask for.
  type :: frd_wants_t
    logical :: u = .false., s = .false., e = .false., rf = .false., pe = .false., contact = .false.
    logical :: nt = .false.   ! heat transfer: the temperatures (NDTEMP)
  end type frd_wants_t

  !> Characters of a batch of records written at once (nodes, elements).
  integer, parameter :: record_batch = 65536

contains

  !> Purpose: open <job>.frd and write the header, the nodes and the
  !> elements (the model's mesh, which does not change).
  !> Arguments: path the file; m the model; f the writer (out).
  subroutine open_frd_file(path, m, f)
    character(len=*), intent(in) :: path
    type(model_t), intent(in) :: m
    type(frd_file_t), intent(out) :: f
    integer :: ios, k
    character(len=8) :: date
    character(len=10) :: time
    f%path = path
    f%ids = m%node_id
    ! (as CalculiX, nodes of no element, left over from meshing, are not written)
    f%kept = kept_nodes(m)
    open(newunit=f%unit, file=path, status='replace', action='write', iostat=ios)
    if (ios /= 0) call fatal('cannot write the CalculiX result file "' // path // '"')
    f%open = .true.
    call date_and_time(date=date, time=time)
    write(f%unit, '(a)') '    1C'
    call user_record(f%unit, 'USER', '')
    call user_record(f%unit, 'DATE', date(7:8) // '.' // month_name(date(5:6)) // '.' // date(1:4))
    call user_record(f%unit, 'TIME', time(1:2) // ':' // time(3:4) // ':' // time(5:6))
    call user_record(f%unit, 'HOST', '')
    call user_record(f%unit, 'PGM', 'cfe2d')
    call user_record(f%unit, 'VERSION', 'Version ' // program_version)
    call user_record(f%unit, 'COMPILETIME', '')
    call user_record(f%unit, 'DIR', '')
    call user_record(f%unit, 'DBN', '')
    do k = 1, size(m%materials)
      write(f%unit, '(a, i5, a58)') '    1UMAT', k, m%materials(k)%name
    end do
    call write_nodes(f%unit, m, f%kept)
    call write_elements(f%unit, m)
  end subroutine open_frd_file

  !> A 1U record: key in 18 columns, the value after it (72 columns in
  !> all, as CalculiX pads them).
  subroutine user_record(u, key, value)
    integer, intent(in) :: u
    character(len=*), intent(in) :: key, value
    character(len=18) :: k
    character(len=48) :: v
    k = key
    v = value
    write(u, '(a)') '    1U' // k // v
  end subroutine user_record

  !> The month's name as CalculiX writes the date (27.november.2026).
  pure function month_name(mm) result(s)
    character(len=2), intent(in) :: mm
    character(len=:), allocatable :: s
    character(len=9), parameter :: names(12) = [character(len=9) :: 'january', 'february', 'march', 'april', &
      'may', 'june', 'july', 'august', 'september', 'october', 'november', 'december']
    integer :: k, ios
    read(mm, *, iostat=ios) k
    if (ios /= 0 .or. k < 1 .or. k > 12) k = 1
    s = trim(names(k))
  end function month_name

  !> The node block 2C: the nodes kept, z = 0.
  subroutine write_nodes(u, m, kept)
    integer, intent(in) :: u
    type(model_t), intent(in) :: m
    logical, intent(in) :: kept(:)
    integer :: a, pos
    character(len=record_batch) :: buf
    write(u, '(a, i30, i38)') '    2C', count(kept), 1
    pos = 0
    do a = 1, m%nn
      if (kept(a)) call put_record(u, buf, pos, ' -1' // int_field(m%node_id(a), 10) // e12_5(m%x(1, a)) // &
                                   e12_5(m%x(2, a)) // e12_5(0.0_dp))
    end do
    call put_record(u, buf, pos, ' -3')
    call flush_records(u, buf, pos)
  end subroutine write_nodes

  !> Purpose: appends one record to buf (records joined by newlines),
  !> writing buf out first when the record would not fit: a write
  !> statement per record cost more than composing it (the flagship's
  !> 29 000 nodes and elements: 31 ms of the run's 1.1 s CPU, perf).
  !> Arguments: u the file; buf the batch, pos its characters in use.
  subroutine put_record(u, buf, pos, text)
    integer, intent(in) :: u
    character(len=*), intent(inout) :: buf
    integer, intent(inout) :: pos
    character(len=*), intent(in) :: text
    if (pos + len(text) + 1 > len(buf)) call flush_records(u, buf, pos)
    buf(pos + 1:pos + len(text)) = text
    buf(pos + len(text) + 1:pos + len(text) + 1) = new_line('a')
    pos = pos + len(text) + 1
  end subroutine put_record

  !> Purpose: writes the records batched in buf(1:pos) (the last newline
  !> is the write's own) and empties the batch.
  subroutine flush_records(u, buf, pos)
    integer, intent(in) :: u
    character(len=*), intent(in) :: buf
    integer, intent(inout) :: pos
    if (pos > 0) write(u, '(a)') buf(1:pos - 1)
    pos = 0
  end subroutine flush_records

  !> Purpose: CalculiX's frd element type of catalogue entry et as it
  !> writes 2D elements with OUTPUT=2D (0: not written: springs, masses).
  pure integer function frd_type(et)
    integer, intent(in) :: et
    select case (catalogue(et)%shape)
    case (shape_tri3); frd_type = 7
    case (shape_tri6); frd_type = 8
    case (shape_quad4); frd_type = 9
    case (shape_quad8); frd_type = 10
    case (shape_line2); frd_type = 11
    case (shape_line3); frd_type = 12
    case default; frd_type = 0
    end select
  end function frd_type

  !> The element block 3C: the elements with stiffness that have an frd
  !> type, each with its material number (0 without one).
  !> (records as the formats (a, i10, 3i5) and (a, *(i10)) write them,
  !> composed with int_field and batched)
  subroutine write_elements(u, m)
    integer, intent(in) :: u
    type(model_t), intent(in) :: m
    integer :: e, n, mat, order(8), k, count, pos
    character(len=record_batch) :: buf
    character(len=3 + 10 * 8) :: nodes
    count = 0
    do e = 1, m%ne
      if (written(m, e)) count = count + 1
    end do
    write(u, '(a, i30, i38)') '    3C', count, 1
    pos = 0
    do e = 1, m%ne
      if (.not. written(m, e)) cycle
      mat = 0
      if (allocated(m%elem_section)) then
        if (m%elem_section(e) > 0) mat = m%sections(m%elem_section(e))%material
      end if
      call put_record(u, buf, pos, ' -1' // int_field(m%elem_id(e), 10) // int_field(frd_type(m%etype(e)), 5) // &
                      int_field(0, 5) // int_field(mat, 5))
      n = elem_nodes(m, e)
      order = file_node_order(m%etype(e))
      nodes(1:3) = ' -2'
      do k = 1, n
        nodes(4 + 10 * (k - 1):3 + 10 * k) = int_field(m%node_id(m%conn(order(k), e)), 10)
      end do
      call put_record(u, buf, pos, nodes(1:3 + 10 * n))
    end do
    call put_record(u, buf, pos, ' -3')
    call flush_records(u, buf, pos)
  end subroutine write_elements

  !> An element of the element block: one that carries stiffness and has
  !> an frd type.
  pure logical function written(m, e)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    written = carries_stiffness(m, e) .and. frd_type(m%etype(e)) > 0
  end function written


  !> Purpose: the result blocks of a converged increment, at the
  !> increments the step's FREQUENCY= or TIME POINTS= select.
  subroutine write_frd_increment(self, m, res)
    class(frd_file_t), intent(inout) :: self
    type(model_t), intent(in) :: m
    type(increment_results_t), intent(in) :: res
    type(frd_wants_t) :: w
    real(dp), allocatable :: v(:, :)
    logical, allocatable :: at(:)
    if (.not. self%schedule%due(m, res)) return
    w = wants(m, res%step)
    if (.not. (w%u .or. w%s .or. w%e .or. w%rf .or. w%pe .or. w%contact .or. w%nt)) return
    self%sets = self%sets + 1
    at = self%kept
    if (w%u) then
      allocate(v(3, m%nn))
      v = 0.0_dp
      v(1:2, :) = res%u
      call vector_block(self, res, 'DISP', 'D', v, at)
      deallocate(v)
    end if
    if (w%s .and. size(res%sig_node, 2) == m%nn) call tensor_block(self, res, 'STRESS', 'S', nodal_stress(res), at)
    if (w%e .and. res%has_stresses) call tensor_block(self, res, 'TOSTRAIN', 'E', nodal_strain(m, res), at)
    if (w%rf) then
      allocate(v(3, m%nn))
      v = 0.0_dp
      v(1:2, :) = res%rf
      call vector_block(self, res, 'FORC', 'F', v, at)
      deallocate(v)
    end if
    if (w%pe .and. size(res%peeq_elem) == m%ne) call scalar_block(self, res, 'PE', nodal_peeq(m, res), at)
    if (w%contact) call contact_block(self, m, res)
    ! heat transfer: CalculiX's NDTEMP block, its one component T
    if (w%nt .and. res%heat) then
      call block_head(self, res, 'NDTEMP', 1, count(at))
      call component(self%unit, 'T', 1, 0, 0)
      call values(self%unit, self%ids, reshape(res%nt, [1, m%nn]), at)
    end if
    flush(self%unit)
  end subroutine write_frd_increment

  !> What the file requests of step is ask for (U is CalculiX's default
  !> of *NODE FILE; RF asked for on *EL FILE is nodal too).
  function wants(m, is) result(w)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is
    type(frd_wants_t) :: w
    integer :: q
    do q = 1, size(m%steps(is)%requests)
      associate(r => m%steps(is)%requests(q))
        if (.not. r%to_file) cycle
        w%u = w%u .or. r%u
        w%rf = w%rf .or. r%rf
        w%s = w%s .or. r%s
        w%e = w%e .or. r%e
        w%pe = w%pe .or. r%peeq
        w%contact = w%contact .or. r%cstress
        w%nt = w%nt .or. r%nt
      end associate
    end do
  end function wants

  !> The 1P and 100C records that open a result block of nv values per
  !> node at n nodes, and its -4 record.
  subroutine block_head(self, res, name, ncomp, n)
    class(frd_file_t), intent(inout) :: self
    type(increment_results_t), intent(in) :: res
    character(len=*), intent(in) :: name
    integer, intent(in) :: ncomp, n
    character(len=8) :: nm
    self%blocks = self%blocks + 1
    write(self%unit, '(a, i26, i12, i12, a)') '    1PSTEP', self%blocks, res%increment, res%step, repeat(' ', 10)
    write(self%unit, '(a, i5, a12, i12, a20, i2, i5, i12)') '  100CL', 100 + self%sets, e12_5(res%total_time), n, &
      '', 0, self%sets, 1
    nm = name
    write(self%unit, '(a, a8, 2i5)') ' -4  ', nm, ncomp, 1
  end subroutine block_head

  !> A -5 record: component name, type (1 scalar, 2 vector, 4 tensor) and
  !> its place in the vector or tensor.
  subroutine component(u, name, kind, i, j)
    integer, intent(in) :: u, kind, i, j
    character(len=*), intent(in) :: name
    character(len=8) :: nm
    nm = name
    write(u, '(a, a8, 4i5)') ' -5  ', nm, 1, kind, i, j
  end subroutine component

  !> Purpose: a vector block (DISP, FORC): components p1..p3 and ALL.
  subroutine vector_block(self, res, name, p, v, at)
    class(frd_file_t), intent(inout) :: self
    type(increment_results_t), intent(in) :: res
    character(len=*), intent(in) :: name, p
    real(dp), intent(in) :: v(:, :)
    logical, intent(in) :: at(:)
    integer :: k
    call block_head(self, res, name, 4, count(at))
    do k = 1, 3
      call component(self%unit, p // itoa(k), 2, k, 0)
    end do
    write(self%unit, '(a)') ' -5  ALL         1    2    0    0    1ALL'
    call values(self%unit, self%ids, v, at)
  end subroutine vector_block

  !> Purpose: a tensor block (STRESS, TOSTRAIN) of the components
  !> xx, yy, zz, xy, yz, zx in v(6, nn).
  subroutine tensor_block(self, res, name, p, v, at)
    class(frd_file_t), intent(inout) :: self
    type(increment_results_t), intent(in) :: res
    character(len=*), intent(in) :: name, p
    real(dp), intent(in) :: v(:, :)
    logical, intent(in) :: at(:)
    call block_head(self, res, name, 6, count(at))
    call component(self%unit, p // 'XX', 4, 1, 1)
    call component(self%unit, p // 'YY', 4, 2, 2)
    call component(self%unit, p // 'ZZ', 4, 3, 3)
    call component(self%unit, p // 'XY', 4, 1, 2)
    call component(self%unit, p // 'YZ', 4, 2, 3)
    call component(self%unit, p // 'ZX', 4, 3, 1)
    call values(self%unit, self%ids, v, at)
  end subroutine tensor_block

  !> Purpose: a scalar block (PE): its one component and the values.
  subroutine scalar_block(self, res, name, v, at)
    class(frd_file_t), intent(inout) :: self
    type(increment_results_t), intent(in) :: res
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: v(:)
    logical, intent(in) :: at(:)
    call block_head(self, res, name, 1, count(at))
    call component(self%unit, name, 1, 0, 0)
    call values(self%unit, self%ids, reshape(v, [1, size(v)]), at)
  end subroutine scalar_block

  !> The -1 records of the nodes at(a) (user ids), and the closing -3.
  !> The records go out batch_lines at a time, joined by newlines in one
  !> write: a write statement per record cost more than the records.
  subroutine values(u, ids, v, at)
    integer, intent(in) :: u
    integer, intent(in) :: ids(:)
    real(dp), intent(in) :: v(:, :)
    logical, intent(in) :: at(:)
    integer, parameter :: batch_lines = 512
    integer :: a, k, width, pos, nlines
    character(len=:), allocatable :: buf
    width = 14 + 12 * size(v, 1)           ! a record and its newline
    allocate(character(len=width * batch_lines) :: buf)
    pos = 0
    nlines = 0
    do a = 1, size(at)
      if (.not. at(a)) cycle
      buf(pos + 1:pos + 13) = ' -1' // int_field(ids(a), 10)
      do k = 1, size(v, 1)
        buf(pos + 2 + 12 * k:pos + 13 + 12 * k) = e12_5(v(k, a))
      end do
      buf(pos + width:pos + width) = new_line('a')
      pos = pos + width
      nlines = nlines + 1
      if (nlines == batch_lines) then
        write(u, '(a)') buf(1:pos - 1)
        pos = 0
        nlines = 0
      end if
    end do
    if (pos > 0) write(u, '(a)') buf(1:pos - 1)
    write(u, '(a)') ' -3'
  end subroutine values

  !> Nodal stresses (S11, S22, S33, S12) as the six components.
  function nodal_stress(res) result(v)
    type(increment_results_t), intent(in) :: res
    real(dp) :: v(6, size(res%sig_node, 2))
    v = 0.0_dp
    v(1:3, :) = res%sig_node(1:3, :)
    v(4, :) = res%sig_node(4, :)
  end function nodal_stress

  !> Purpose: TOSTRAIN at the nodes: the element averages of the strain
  !> at the integration points (the shear as the tensor component, half
  !> the engineering one), averaged over the elements at each node. The
  !> out-of-plane strain: zero in plane strain; the hoop strain u_r / r
  !> (its element average over the nodes off the axis) axisymmetric; in
  !> plane stress the elastic -nu (S11 + S22) / E of the element average
  !> stress (cfe2d's results carry no other; exact for elastic material).
  function nodal_strain(m, res) result(v)
    type(model_t), intent(in) :: m
    type(increment_results_t), intent(in) :: res
    real(dp) :: v(6, m%nn), ee(6), r
    integer :: e, k, n, hits(m%nn), a
    v = 0.0_dp
    hits = 0
    do e = 1, m%ne
      if (res%nip(e) <= 0 .or. .not. written(m, e)) cycle
      n = elem_nodes(m, e)
      ee = 0.0_dp
      ee(1:2) = sum(res%eps_ip(1:2, 1:res%nip(e), e), dim=2) / res%nip(e)
      ee(4) = 0.5_dp * sum(res%eps_ip(3, 1:res%nip(e), e)) / res%nip(e)
      select case (catalogue(m%etype(e))%state)
      case (state_axisymmetric)
        k = 0
        do a = 1, n
          r = m%x(1, m%conn(a, e))
          if (r > 0.0_dp) then
            ee(3) = ee(3) + res%u(1, m%conn(a, e)) / r
            k = k + 1
          end if
        end do
        if (k > 0) ee(3) = ee(3) / k
      case (state_plane_stress)
        ee(3) = plane_stress_ezz(m, e, res)
      end select
      do k = 1, n
        a = m%conn(k, e)
        v(:, a) = v(:, a) + ee
        hits(a) = hits(a) + 1
      end do
    end do
    do a = 1, m%nn
      if (hits(a) > 0) v(:, a) = v(:, a) / hits(a)
    end do
  end function nodal_strain

  !> The elastic out-of-plane strain of a plane-stress element.
  real(dp) function plane_stress_ezz(m, e, res)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    type(increment_results_t), intent(in) :: res
    integer :: mat
    plane_stress_ezz = 0.0_dp
    if (.not. allocated(m%elem_section) .or. size(res%sig_elem, 2) /= m%ne) return
    if (m%elem_section(e) <= 0) return
    mat = m%sections(m%elem_section(e))%material
    if (mat <= 0) return
    associate(mt => m%materials(mat))
      if (mt%has_elastic .and. mt%e > 0.0_dp) &
        plane_stress_ezz = -mt%nu * (res%sig_elem(1, e) + res%sig_elem(2, e)) / mt%e
    end associate
  end function plane_stress_ezz

  !> PEEQ at the nodes: the element averages averaged over the elements at
  !> each node.
  function nodal_peeq(m, res) result(v)
    type(model_t), intent(in) :: m
    type(increment_results_t), intent(in) :: res
    real(dp) :: v(m%nn)
    integer :: e, k, hits(m%nn), a
    v = 0.0_dp
    hits = 0
    do e = 1, m%ne
      if (res%nip(e) <= 0 .or. .not. written(m, e)) cycle
      do k = 1, elem_nodes(m, e)
        a = m%conn(k, e)
        v(a) = v(a) + res%peeq_elem(e)
        hits(a) = hits(a) + 1
      end do
    end do
    where (hits > 0) v = v / hits
  end function nodal_peeq

  !> Purpose: the CONTACT block (CalculiX's COPEN, CSLIP1, CSLIP2,
  !> CPRESS, CSHEAR1, CSHEAR2) at the slave nodes of every pair: the gap
  !> (negative: penetration), the accumulated slip, the contact pressure
  !> and the shear traction (zero without friction); 2D: no second
  !> tangent.
  subroutine contact_block(self, m, res)
    class(frd_file_t), intent(inout) :: self
    type(model_t), intent(in) :: m
    type(increment_results_t), intent(in) :: res
    real(dp) :: v(6, m%nn)
    logical :: at(m%nn)
    integer :: k, j, a
    v = 0.0_dp
    at = .false.
    do k = 1, size(res%contact%pairs)
      associate(p => res%contact%pairs(k))
        do j = 1, size(p%slave_node)
          a = p%slave_node(j)
          if (a <= 0) cycle
          at(a) = .true.
          v(1, a) = p%slave_gap(j)
          if (p%frictional) v(2, a) = p%slave_slip(j)
          if (p%slave_closed(j)) v(4, a) = p%slave_pressure(j)
          if (p%frictional .and. p%slave_closed(j)) v(5, a) = p%slave_traction(j)
        end do
      end associate
    end do
    call block_head(self, res, 'CONTACT', 6, count(at))
    call component(self%unit, 'COPEN', 4, 1, 1)
    call component(self%unit, 'CSLIP1', 4, 2, 2)
    call component(self%unit, 'CSLIP2', 4, 3, 3)
    call component(self%unit, 'CPRESS', 4, 1, 2)
    call component(self%unit, 'CSHEAR1', 4, 2, 3)
    call component(self%unit, 'CSHEAR2', 4, 3, 1)
    call values(self%unit, self%ids, v, at)
  end subroutine contact_block

  !> Purpose: the end record; the file is complete.
  subroutine close_frd_file(self, timing)
    class(frd_file_t), intent(inout) :: self
    type(run_timing_t), intent(in) :: timing
    if (.not. self%open) return
    write(self%unit, '(a)') ' 9999'
    close(self%unit)
    self%open = .false.
  end subroutine close_frd_file
end module results_frd
