!> ParaView result files: one VTK XML unstructured grid per converged
!> increment, <job>_NNNN.vtu (the arrays as raw binary in an appended
!> block), and the time series <job>.pvd that ParaView opens, rewritten
!> after every increment so that it is complete whenever the run stops.
!> The files hold what the step's *NODE FILE and *EL FILE ask for (as the
!> gmsh file does), plus what every view needs: the displacement U, the
!> user node and element ids and the section of each element.
!> It observes the analysis and writes at every converged increment.
module results_vtu
  use, intrinsic :: iso_fortran_env, only: int8, int32, int64, real64
  use kinds, only: dp
  use strings, only: itoa
  use model
  use element_catalogue, only: catalogue, file_node_order, max_nodes
  use materials, only: von_mises
  use messages, only: fatal
  use analysis_events, only: analysis_observer_t
  use increment_results, only: increment_results_t
  use output_schedule, only: schedule_t
  implicit none
  private
  public :: vtu_series_t, open_vtu_series

  ! Where an array goes in the file.
  integer, parameter :: in_points = 1, in_cells = 2, point_data = 3, cell_data = 4

  !> One data array: its XML attributes and its values (one of r, i, b).
  type :: vtu_array_t
    character(len=32) :: name = '', vtype = ''
    integer :: ncomp = 1, place = point_data
    real(real64), allocatable :: r(:)
    integer(int32), allocatable :: i(:)
    integer(int8), allocatable :: b(:)
  end type vtu_array_t

  type, extends(analysis_observer_t) :: vtu_series_t
    character(len=:), allocatable :: job     ! path of the results without extension
    integer :: count = 0                     ! increments written
    real(dp), allocatable :: times(:)        ! total time of each file
    type(schedule_t) :: schedule             ! which increments are written (FREQUENCY=, TIME POINTS=)
  contains
    procedure :: increment_done => write_vtu_increment
  end type vtu_series_t

contains

  !> Purpose: start the series <job>_NNNN.vtu / <job>.pvd (nothing is
  !> written before the first increment).
  subroutine open_vtu_series(job, vs)
    character(len=*), intent(in) :: job
    type(vtu_series_t), intent(out) :: vs
    vs%job = job
    allocate(vs%times(0))
  end subroutine open_vtu_series

  !> Purpose: the VTU file of this increment and the updated .pvd, at the
  !> increments the step's FREQUENCY= or TIME POINTS= select.
  subroutine write_vtu_increment(self, m, res)
    class(vtu_series_t), intent(inout) :: self
    type(model_t), intent(in) :: m
    type(increment_results_t), intent(in) :: res
    type(vtu_array_t), allocatable :: arrays(:)
    character(len=:), allocatable :: name
    if (.not. self%schedule%due(m, res)) return
    self%count = self%count + 1
    self%times = [self%times, res%total_time]
    call collect_arrays(m, res, arrays)
    name = self%job // '_' // file_number(self%count) // '.vtu'
    call write_vtu_file(name, m, arrays)
    call write_pvd(self)
  end subroutine write_vtu_increment

  pure function file_number(k) result(s)
    integer, intent(in) :: k
    character(len=:), allocatable :: s
    character(len=16) :: buf
    write(buf, '(i4.4)') k
    s = trim(buf)
  end function file_number

  !> Purpose: the arrays of one increment: the mesh (points, cells), the
  !> ids, U, and what the step's file requests ask for.
  subroutine collect_arrays(m, res, arrays)
    type(model_t), intent(in) :: m
    type(increment_results_t), intent(in) :: res
    type(vtu_array_t), allocatable, intent(out) :: arrays(:)
    logical :: rf, s_node, cstress, s_elem, peeq, e_elem
    integer :: q, k
    integer, allocatable :: cells(:)
    rf = .false.; s_node = .false.; cstress = .false.; s_elem = .false.; peeq = .false.; e_elem = .false.
    do q = 1, size(m%steps(res%step)%requests)
      associate(r => m%steps(res%step)%requests(q))
        if (.not. r%to_file) cycle
        ! (U is always written; RF and CSTRESS asked for on *EL FILE are nodal arrays too)
        rf = rf .or. r%rf
        s_node = s_node .or. (r%nodal .and. r%s)
        cstress = cstress .or. r%cstress
        s_elem = s_elem .or. (.not. r%nodal .and. r%s)
        e_elem = e_elem .or. (.not. r%nodal .and. r%e)
        peeq = peeq .or. (.not. r%nodal .and. r%peeq)
      end associate
    end do
    cells = pack([(k, k = 1, m%ne)], [(is_drawn(m, k), k = 1, m%ne)])
    allocate(arrays(0))
    call add_mesh(m, cells, arrays)
    arrays = [arrays, int_array('NodeId', point_data, m%node_id), &
              int_array('ElementId', cell_data, m%elem_id(cells)), &
              int_array('Section', cell_data, m%elem_section(cells)), &
              vector_array('U', res%u)]
    ! heat transfer: the temperatures (temperature_field)
    if (res%heat) arrays = [arrays, real_array('NT', point_data, res%nt)]
    if (rf) arrays = [arrays, vector_array('RF', res%rf)]
    if (s_node .and. res%has_stresses) arrays = [arrays, tensor_array('S', point_data, res%sig_node), &
        real_array('Mises', point_data, [(von_mises(res%sig_node(:, k)), k = 1, m%nn)])]
    if (cstress) arrays = [arrays, real_array('CSTRESS', point_data, res%contact%pressure)]
    ! the contact shear traction beside it, only with friction (frictionless files stay as they were)
    if (cstress .and. res%contact%frictional) arrays = [arrays, real_array('CSHEAR', point_data, res%contact%shear)]
    if (s_elem .and. res%has_stresses) arrays = [arrays, &
        tensor_array('S (element)', cell_data, res%sig_elem(:, cells)), &
        real_array('Mises (element)', cell_data, [(von_mises(res%sig_elem(:, cells(k))), k = 1, size(cells))])]
    if (e_elem .and. res%has_stresses) arrays = [arrays, strain_array(m, res, cells)]
    ! the element average of the equivalent plastic strain
    if (peeq .and. size(res%peeq_elem) == m%ne) arrays = [arrays, &
        real_array('PEEQ (element)', cell_data, res%peeq_elem(cells))]
  end subroutine collect_arrays

  !> Purpose: E of *EL FILE: the element averages of the strain at the
  !> integration points (E11, E22, E12) of the elements cells.
  function strain_array(m, res, cells) result(a)
    type(model_t), intent(in) :: m
    type(increment_results_t), intent(in) :: res
    integer, intent(in) :: cells(:)
    type(vtu_array_t) :: a
    real(dp) :: eps(3, size(cells))
    integer :: k, e
    eps = 0.0_dp
    do k = 1, size(cells)
      e = cells(k)
      if (res%nip(e) > 0) eps(:, k) = sum(res%eps_ip(:, 1:res%nip(e), e), dim=2) / res%nip(e)
    end do
    a = vtu_array_t(name='E (element)', vtype='Float64', ncomp=3, place=cell_data)
    a%r = real(reshape(eps, [3 * size(cells)]), real64)
  end function strain_array

  !> Points (z = 0) and the elements the model draws (continuum elements,
  !> trusses, springs, point masses) as cells, with the VTK type of their
  !> catalogue entry (line elements without a section are not written).
  subroutine add_mesh(m, cells, arrays)
    type(model_t), intent(in) :: m
    integer, intent(in) :: cells(:)
    type(vtu_array_t), allocatable, intent(inout) :: arrays(:)
    type(vtu_array_t) :: pts, conn, offs, types
    integer :: k, e, n, pos, order(max_nodes)
    pts = vtu_array_t(name='Points', vtype='Float64', ncomp=3, place=in_points)
    allocate(pts%r(3 * m%nn))
    pts%r = 0.0_real64
    pts%r(1::3) = real(m%x(1, :), real64)
    pts%r(2::3) = real(m%x(2, :), real64)
    conn = vtu_array_t(name='connectivity', vtype='Int32', place=in_cells)
    offs = vtu_array_t(name='offsets', vtype='Int32', place=in_cells)
    types = vtu_array_t(name='types', vtype='UInt8', place=in_cells)
    allocate(conn%i(sum([(elem_nodes(m, cells(k)), k = 1, size(cells))])), offs%i(size(cells)), &
             types%b(size(cells)))
    pos = 0
    do k = 1, size(cells)
      e = cells(k)
      n = elem_nodes(m, e)
      order = file_node_order(m%etype(e))
      conn%i(pos + 1:pos + n) = int(m%conn(order(1:n), e) - 1, int32)   ! VTK points count from 0
      pos = pos + n
      offs%i(k) = int(pos, int32)
      types%b(k) = int(catalogue(m%etype(e))%vtk_type, int8)
    end do
    arrays = [arrays, pts, conn, offs, types]
  end subroutine add_mesh

  function int_array(name, place, v) result(a)
    character(len=*), intent(in) :: name
    integer, intent(in) :: place, v(:)
    type(vtu_array_t) :: a
    a = vtu_array_t(name=name, vtype='Int32', place=place)
    a%i = int(v, int32)
  end function int_array

  function real_array(name, place, v) result(a)
    character(len=*), intent(in) :: name
    integer, intent(in) :: place
    real(dp), intent(in) :: v(:)
    type(vtu_array_t) :: a
    a = vtu_array_t(name=name, vtype='Float64', place=place)
    a%r = real(v, real64)
  end function real_array

  !> A nodal 2D vector (2, nn) as a VTK 3-vector (z = 0).
  function vector_array(name, v) result(a)
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: v(:, :)
    type(vtu_array_t) :: a
    a = vtu_array_t(name=name, vtype='Float64', ncomp=3, place=point_data)
    allocate(a%r(3 * size(v, 2)))
    a%r = 0.0_real64
    a%r(1::3) = real(v(1, :), real64)
    a%r(2::3) = real(v(2, :), real64)
  end function vector_array

  !> Stresses (S11, S22, S33, S12) per node or cell as VTK's symmetric
  !> tensor of six components (XX, YY, ZZ, XY, YZ, XZ).
  function tensor_array(name, place, s) result(a)
    character(len=*), intent(in) :: name
    integer, intent(in) :: place
    real(dp), intent(in) :: s(:, :)
    type(vtu_array_t) :: a
    a = vtu_array_t(name=name, vtype='Float64', ncomp=6, place=place)
    allocate(a%r(6 * size(s, 2)))
    a%r = 0.0_real64
    a%r(1::6) = real(s(1, :), real64)
    a%r(2::6) = real(s(2, :), real64)
    a%r(3::6) = real(s(3, :), real64)
    a%r(4::6) = real(s(4, :), real64)
  end function tensor_array

  !> Bytes of an array's values.
  integer(int64) function nbytes(a)
    type(vtu_array_t), intent(in) :: a
    nbytes = 0
    if (allocated(a%r)) nbytes = 8_int64 * size(a%r, kind=int64)
    if (allocated(a%i)) nbytes = 4_int64 * size(a%i, kind=int64)
    if (allocated(a%b)) nbytes = size(a%b, kind=int64)
  end function nbytes

  !> Purpose: one .vtu file: the XML header naming every array with its
  !> offset into the appended block, then the block (for each array an
  !> 8-byte length and the raw values, in the machine's byte order).
  subroutine write_vtu_file(path, m, arrays)
    character(len=*), intent(in) :: path
    type(model_t), intent(in) :: m
    type(vtu_array_t), intent(in) :: arrays(:)
    integer(int64) :: offset(size(arrays))
    integer :: u, ios, k, ncells
    character(len=1), parameter :: nl = new_line('a')
    offset(1) = 0
    do k = 2, size(arrays)
      offset(k) = offset(k - 1) + 8 + nbytes(arrays(k - 1))
    end do
    ncells = size(arrays(findloc(arrays%name, 'types', dim=1))%b)
    open(newunit=u, file=path, access='stream', form='unformatted', status='replace', action='write', iostat=ios)
    if (ios /= 0) call fatal('cannot write the VTU file "' // path // '"')
    write(u) '<?xml version="1.0"?>' // nl // '<VTKFile type="UnstructuredGrid" version="1.0" byte_order="' // &
      byte_order() // '" header_type="UInt64">' // nl // '  <UnstructuredGrid>' // nl // &
      '    <Piece NumberOfPoints="' // itoa(m%nn) // '" NumberOfCells="' // itoa(ncells) // '">' // nl
    call write_section(u, arrays, offset, point_data, 'PointData')
    call write_section(u, arrays, offset, cell_data, 'CellData')
    call write_section(u, arrays, offset, in_points, 'Points')
    call write_section(u, arrays, offset, in_cells, 'Cells')
    write(u) '    </Piece>' // nl // '  </UnstructuredGrid>' // nl // '  <AppendedData encoding="raw">' // nl // '_'
    do k = 1, size(arrays)
      write(u) nbytes(arrays(k))
      if (allocated(arrays(k)%r)) write(u) arrays(k)%r
      if (allocated(arrays(k)%i)) write(u) arrays(k)%i
      if (allocated(arrays(k)%b)) write(u) arrays(k)%b
    end do
    write(u) nl // '  </AppendedData>' // nl // '</VTKFile>' // nl
    close(u)
  end subroutine write_vtu_file

  !> The DataArray elements of the arrays that go into one XML section.
  subroutine write_section(u, arrays, offset, place, tag)
    integer, intent(in) :: u, place
    type(vtu_array_t), intent(in) :: arrays(:)
    integer(int64), intent(in) :: offset(:)
    character(len=*), intent(in) :: tag
    character(len=1), parameter :: nl = new_line('a')
    character(len=:), allocatable :: comps
    integer :: k
    write(u) '      <' // tag // '>' // nl
    do k = 1, size(arrays)
      if (arrays(k)%place /= place) cycle
      ! (NumberOfComponents only for vectors: a scalar is read as one)
      comps = ''
      if (arrays(k)%ncomp > 1) comps = ' NumberOfComponents="' // itoa(arrays(k)%ncomp) // '"'
      write(u) '        <DataArray type="' // trim(arrays(k)%vtype) // '" Name="' // trim(arrays(k)%name) // &
        '"' // comps // ' format="appended" offset="' // itoa64(offset(k)) // '"/>' // nl
    end do
    write(u) '      </' // tag // '>' // nl
  end subroutine write_section

  !> Purpose: <job>.pvd, the time series of the files written so far.
  subroutine write_pvd(vs)
    type(vtu_series_t), intent(in) :: vs
    integer :: u, ios, k, slash
    character(len=40) :: t
    open(newunit=u, file=vs%job // '.pvd', status='replace', action='write', iostat=ios)
    if (ios /= 0) call fatal('cannot write the ParaView series "' // vs%job // '.pvd"')
    slash = index(vs%job, '/', back=.true.)
    write(u, '(a)') '<?xml version="1.0"?>', &
      '<VTKFile type="Collection" version="0.1" byte_order="' // byte_order() // '">', '  <Collection>'
    do k = 1, vs%count
      write(t, '(es24.16e3)') vs%times(k)
      write(u, '(a)') '    <DataSet timestep="' // trim(adjustl(t)) // '" group="" part="0" file="' // &
        vs%job(slash + 1:) // '_' // file_number(k) // '.vtu"/>'
    end do
    write(u, '(a)') '  </Collection>', '</VTKFile>'
    close(u)
  end subroutine write_pvd

  !> The machine's byte order, as the appended block is written in it.
  function byte_order() result(s)
    character(len=:), allocatable :: s
    integer(int8) :: bytes(4)
    bytes = transfer(1_int32, bytes)
    if (bytes(1) == 1) then
      s = 'LittleEndian'
    else
      s = 'BigEndian'
    end if
  end function byte_order

  pure function itoa64(k) result(s)
    integer(int64), intent(in) :: k
    character(len=:), allocatable :: s
    character(len=24) :: buf
    write(buf, '(i0)') k
    s = trim(buf)
  end function itoa64
end module results_vtu
