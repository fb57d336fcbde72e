!> Result file <job>.msh that gmsh opens, in gmsh's binary MSH 2.2 format:
!> the mesh once, then per increment the views asked for by *NODE FILE and
!> *EL FILE, each view tagged with the increment's time so that gmsh steps
!> through them. Headers are text lines; node coordinates, connectivity
!> and view values are native 32-bit integers and 64-bit reals, one write
!> per block (about half the size of the text format, and no number
!> formatting: on the flagship the text file took most of the run).
!> It observes the analysis and writes at every converged increment.
module results_gmsh
  use, intrinsic :: iso_fortran_env, only: int32
  use kinds, only: dp
  use model
  use element_catalogue, only: catalogue, file_node_order, max_nodes
  use materials, only: von_mises
  use messages, only: register_unit_to_close, fatal
  use analysis_events, only: analysis_observer_t
  use increment_results, only: increment_results_t
  use output_schedule, only: schedule_t
  implicit none
  private
  public :: result_file_t, open_result_file

  character(len=1), parameter :: nl = new_line('a')

  type, extends(analysis_observer_t) :: result_file_t
    integer :: unit = 0
    logical :: open = .false.
    integer :: count = 0          ! increments written (gmsh time-step index)
    type(schedule_t) :: schedule  ! which increments are written (FREQUENCY=, TIME POINTS=)
  contains
    procedure :: increment_done => write_increment_views
  end type result_file_t

contains

  !> Purpose: the views of this increment that the step's *NODE FILE and
  !> *EL FILE requests ask for, merged into one nodal and one element set,
  !> at the increments the step's FREQUENCY= or TIME POINTS= select. U,
  !> RF and CSTRESS asked for on *EL FILE are nodal views (CalculiX
  !> writes U asked for there too); E is written as element averages.
  subroutine write_increment_views(self, m, res)
    class(result_file_t), intent(inout) :: self
    type(model_t), intent(in) :: m
    type(increment_results_t), intent(in) :: res
    type(request_t) :: fnode, felem
    integer :: q
    do q = 1, size(m%steps(res%step)%requests)
      associate(r => m%steps(res%step)%requests(q))
        if (.not. r%to_file) cycle
        fnode%u = fnode%u .or. r%u
        fnode%rf = fnode%rf .or. r%rf
        fnode%cstress = fnode%cstress .or. r%cstress
        fnode%nt = fnode%nt .or. r%nt
        if (r%nodal) then
          fnode%s = fnode%s .or. r%s
        else
          felem%s = felem%s .or. r%s
          felem%e = felem%e .or. r%e
          felem%peeq = felem%peeq .or. r%peeq
        end if
      end associate
    end do
    if (.not. self%open) return
    if (.not. self%schedule%due(m, res)) return
    if (.not. (fnode%u .or. fnode%rf .or. fnode%s .or. fnode%cstress .or. felem%s .or. felem%e .or. felem%peeq &
               .or. fnode%nt)) return
    call write_result_views(self, m, fnode, felem, res%total_time, res%u, res%rf, res%sig_node, res%sig_elem, &
                            res%contact%pressure, res%contact%has_pressure, res%contact%frictional, &
                            res%contact%shear, res%peeq_elem)
    if (felem%e .and. res%has_stresses) call write_strain_views(self, m, res)
    ! heat transfer: the temperatures (temperature_field)
    if (fnode%nt .and. res%heat) call write_view(self, 'NodeData', 'NT', res%total_time, m%node_id, &
                                                 [(.true., q = 1, m%nn)], reshape(res%nt, [1, m%nn]))
    flush(self%unit)
  end subroutine write_increment_views

  !> Purpose: E of *EL FILE: the element averages of the strain at the
  !> integration points (E11, E22, E12, as the listing's *EL PRINT),
  !> three element views of the increment just counted.
  subroutine write_strain_views(rf, m, res)
    type(result_file_t), intent(in) :: rf
    type(model_t), intent(in) :: m
    type(increment_results_t), intent(in) :: res
    real(dp) :: eps(3, m%ne)
    logical :: solid(m%ne)
    integer :: e, k
    character(len=3), parameter :: names(3) = ['E11', 'E22', 'E12']
    solid = [(is_drawn(m, e), e = 1, m%ne)]
    eps = 0.0_dp
    do e = 1, m%ne
      if (res%nip(e) > 0) eps(:, e) = sum(res%eps_ip(:, 1:res%nip(e), e), dim=2) / res%nip(e)
    end do
    do k = 1, 3
      call write_view(rf, 'ElementData', names(k) // ' (element)', res%total_time, m%elem_id, solid, eps(k:k, :))
    end do
  end subroutine write_strain_views

  !> One text line of the file.
  subroutine line(u, text)
    integer, intent(in) :: u
    character(len=*), intent(in) :: text
    write(u) text // nl
  end subroutine line

  function int_text(k) result(s)
    integer, intent(in) :: k
    character(len=:), allocatable :: s
    character(len=16) :: buf
    write(buf, '(i0)') k
    s = trim(buf)
  end function int_text

  !> Purpose: opens <job>.msh and writes the format header, the nodes and
  !> the continuum elements (tags: physical and elementary entity = the
  !> section number).
  subroutine open_result_file(path, m, rf)
    character(len=*), intent(in) :: path
    type(model_t), intent(in) :: m
    type(result_file_t), intent(out) :: rf
    integer :: ios, u, k
    integer(int32), allocatable :: buf(:, :)
    open(newunit=rf%unit, file=path, status='replace', action='write', access='stream', form='unformatted', &
         iostat=ios)
    if (ios /= 0) call fatal('cannot write the result file "' // path // '"')
    call register_unit_to_close(rf%unit)
    rf%open = .true.
    u = rf%unit
    call line(u, '$MeshFormat')
    call line(u, '2.2 1 8')
    write(u) 1_int32                  ! gmsh reads the byte order from it
    call line(u, '')
    call line(u, '$EndMeshFormat')
    call line(u, '$Nodes')
    call line(u, int_text(m%nn))
    allocate(buf(7, m%nn))
    do k = 1, m%nn
      buf(1, k) = int(m%node_id(k), int32)
      buf(2:7, k) = transfer([m%x(:, k), 0.0_dp], buf(1, k), 6)
    end do
    write(u) buf
    call line(u, '')
    call line(u, '$EndNodes')
    call write_elements(u, m)
    flush(u)
  end subroutine open_result_file

  !> $Elements in binary: runs of elements of one type, each run a header
  !> (type, count, tags) and then id, two tags and the nodes per element.
  subroutine write_elements(u, m)
    integer, intent(in) :: u
    type(model_t), intent(in) :: m
    integer(int32), allocatable :: buf(:)
    integer :: e, first, nsolid, k, nen, gtype, order(max_nodes)
    nsolid = count([(is_drawn(m, e), e = 1, m%ne)])
    call line(u, '$Elements')
    call line(u, int_text(nsolid))
    e = 1
    do while (e <= m%ne)
      if (.not. is_drawn(m, e)) then
        e = e + 1
        cycle
      end if
      first = e
      gtype = catalogue(m%etype(e))%gmsh_type
      nen = elem_nodes(m, e)
      order = file_node_order(m%etype(e))
      do while (e <= m%ne)
        if (.not. is_drawn(m, e)) exit
        if (catalogue(m%etype(e))%gmsh_type /= gtype) exit
        e = e + 1
      end do
      allocate(buf(3 + (e - first) * (3 + nen)))
      buf(1:3) = int([gtype, e - first, 2], int32)
      k = 3
      do first = first, e - 1
        buf(k + 1:k + 3 + nen) = int([m%elem_id(first), m%elem_section(first), m%elem_section(first), &
                                      m%node_id(m%conn(order(1:nen), first))], int32)
        k = k + 3 + nen
      end do
      write(u) buf
      deallocate(buf)
    end do
    call line(u, '')
    call line(u, '$EndElements')
  end subroutine write_elements

  !> The views of one increment. sig_node/sig_elem may be absent when no
  !> stress was requested, peeq_elem(ne) (element averages) when PEEQ was
  !> not; pressure(nn) holds contact pressures (slave and
  !> master nodes) and has_pressure marks the nodes that carry one;
  !> shear(nn) the contact shear tractions at the same nodes, a view of
  !> its own (CSHEAR) only when the model has friction (frictionless
  !> files stay as they were).
  subroutine write_result_views(rf, m, req_nodal, req_elem, time, u, reac, sig_node, sig_elem, &
                                pressure, has_pressure, frictional, shear, peeq_elem)
    type(result_file_t), intent(inout) :: rf
    type(model_t), intent(in) :: m
    type(request_t), intent(in) :: req_nodal, req_elem
    real(dp), intent(in) :: time
    real(dp), intent(in) :: u(:, :), reac(:, :), sig_node(:, :), sig_elem(:, :), pressure(:), shear(:)
    logical, intent(in) :: has_pressure(:), frictional
    real(dp), intent(in) :: peeq_elem(:)
    integer :: k
    logical :: all_nodes(m%nn), solid(m%ne)
    character(len=5), parameter :: names(4) = ['S11  ', 'S22  ', 'S33  ', 'S12  ']
    rf%count = rf%count + 1
    all_nodes = .true.
    solid = [(is_drawn(m, k), k = 1, m%ne)]
    if (req_nodal%u) call write_view(rf, 'NodeData', 'Displacement', time, m%node_id, all_nodes, &
                                     with_z(u))
    if (req_nodal%rf) call write_view(rf, 'NodeData', 'Reaction force', time, m%node_id, all_nodes, &
                                      with_z(reac))
    if (req_nodal%s) then
      do k = 1, 4
        call write_view(rf, 'NodeData', trim(names(k)), time, m%node_id, all_nodes, sig_node(k:k, :))
      end do
      call write_view(rf, 'NodeData', 'Mises', time, m%node_id, all_nodes, &
                      reshape([(von_mises(sig_node(:, k)), k = 1, m%nn)], [1, m%nn]))
    end if
    if (req_nodal%cstress) call write_view(rf, 'NodeData', 'Contact pressure', time, m%node_id, has_pressure, &
                                           reshape(pressure, [1, m%nn]))
    if (req_nodal%cstress .and. frictional) call write_view(rf, 'NodeData', 'CSHEAR', time, m%node_id, &
                                                            has_pressure, reshape(shear, [1, m%nn]))
    if (req_elem%s) then
      do k = 1, 4
        call write_view(rf, 'ElementData', trim(names(k)) // ' (element)', time, m%elem_id, solid, sig_elem(k:k, :))
      end do
      call write_view(rf, 'ElementData', 'Mises (element)', time, m%elem_id, solid, &
                      reshape([(von_mises(sig_elem(:, k)), k = 1, m%ne)], [1, m%ne]))
    end if
    ! PEEQ: the element average of the equivalent plastic strain
    if (req_elem%peeq .and. size(peeq_elem) == m%ne) call write_view(rf, 'ElementData', 'PEEQ (element)', time, &
                                                                     m%elem_id, solid, reshape(peeq_elem, [1, m%ne]))
    flush(rf%unit)
  end subroutine write_result_views

  !> A 2D vector field as gmsh's 3-component vectors (z = 0).
  pure function with_z(v) result(w)
    real(dp), intent(in) :: v(:, :)
    real(dp) :: w(3, size(v, 2))
    w(1:2, :) = v(1:2, :)
    w(3, :) = 0.0_dp
  end function with_z

  !> One $NodeData or $ElementData view: the text header, then for every
  !> selected entity its id and its ncomp = size(v, 1) values, in one write.
  subroutine write_view(rf, block, tag, time, ids, selected, v)
    type(result_file_t), intent(in) :: rf
    character(len=*), intent(in) :: block, tag
    real(dp), intent(in) :: time, v(:, :)
    integer, intent(in) :: ids(:)
    logical, intent(in) :: selected(:)
    integer(int32), allocatable :: buf(:, :), bits(:, :)
    character(len=32) :: tbuf
    integer :: i, k, nc
    nc = size(v, 1)
    allocate(buf(1 + 2 * nc, count(selected)))
    ! the values' bits in one transfer, then interleaved with the ids
    bits = reshape(transfer(v, 0_int32, 2 * nc * size(v, 2)), [2 * nc, size(v, 2)])
    k = 0
    do i = 1, size(ids)
      if (.not. selected(i)) cycle
      k = k + 1
      buf(1, k) = int(ids(i), int32)
      buf(2:, k) = bits(:, i)
    end do
    write(tbuf, '(es24.15e3)') time
    call line(rf%unit, '$' // block)
    call line(rf%unit, '1')
    call line(rf%unit, '"' // tag // '"')
    call line(rf%unit, '1')
    call line(rf%unit, trim(adjustl(tbuf)))
    call line(rf%unit, '3')
    call line(rf%unit, int_text(rf%count - 1))
    call line(rf%unit, int_text(nc))
    call line(rf%unit, int_text(k))
    write(rf%unit) buf
    call line(rf%unit, '')
    call line(rf%unit, '$End' // block)
  end subroutine write_view
end module results_gmsh
