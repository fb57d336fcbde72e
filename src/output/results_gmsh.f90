!> Result file <job>.msh that gmsh opens (MSH 2.2 ASCII): the mesh once,
!> then per increment the views asked for by *NODE FILE and *EL FILE, each
!> view tagged with the increment's time so that gmsh steps through them.
!> It observes the analysis and writes at every converged increment.
module results_gmsh
  use kinds, only: dp
  use model
  use element_catalogue, only: catalogue
  use materials, only: von_mises
  use messages, only: register_unit_to_close, fatal
  use analysis_events, only: analysis_observer_t
  use increment_results, only: increment_results_t
  implicit none
  private
  public :: result_file_t, open_result_file, write_result_views

  type, extends(analysis_observer_t) :: result_file_t
    integer :: unit = 0
    logical :: open = .false.
    integer :: count = 0          ! increments written (gmsh time-step index)
  contains
    procedure :: increment_done => write_increment_views
  end type result_file_t

contains

  !> Purpose: the views of this increment that the step's *NODE FILE and
  !> *EL FILE requests ask for, merged into one nodal and one element set.
  subroutine write_increment_views(self, m, res)
    class(result_file_t), intent(inout) :: self
    type(model_t), intent(in) :: m
    type(increment_results_t), intent(in) :: res
    type(request_t) :: fnode, felem
    integer :: q
    do q = 1, size(m%steps(res%step)%requests)
      associate(r => m%steps(res%step)%requests(q))
        if (.not. r%to_file) cycle
        if (r%nodal) then
          fnode%u = fnode%u .or. r%u
          fnode%rf = fnode%rf .or. r%rf
          fnode%s = fnode%s .or. r%s
          fnode%cstress = fnode%cstress .or. r%cstress
        else
          felem%s = felem%s .or. r%s
        end if
      end associate
    end do
    if (.not. self%open) return
    if (.not. (fnode%u .or. fnode%rf .or. fnode%s .or. fnode%cstress .or. felem%s)) return
    call write_result_views(self, m, fnode, felem, res%total_time, res%u, res%rf, res%sig_node, res%sig_elem, &
                            res%contact%pressure, res%contact%has_pressure)
  end subroutine write_increment_views

  subroutine open_result_file(path, m, rf)
    character(len=*), intent(in) :: path
    type(model_t), intent(in) :: m
    type(result_file_t), intent(out) :: rf
    integer :: ios, e, u, gtype, nsolid
    open(newunit=rf%unit, file=path, status='replace', action='write', iostat=ios)
    if (ios /= 0) call fatal('cannot write the result file "' // path // '"')
    call register_unit_to_close(rf%unit)
    rf%open = .true.
    u = rf%unit
    write(u, '(a)') '$MeshFormat', '2.2 0 8', '$EndMeshFormat'
    write(u, '(a)') '$Nodes'
    write(u, '(i0)') m%nn
    do e = 1, m%nn
      write(u, '(i0,3(1x,es24.15e3))') m%node_id(e), m%x(:, e), 0.0_dp
    end do
    write(u, '(a)') '$EndNodes'
    nsolid = count([(is_continuum(m, e), e = 1, m%ne)])
    write(u, '(a)') '$Elements'
    write(u, '(i0)') nsolid
    do e = 1, m%ne
      if (.not. is_continuum(m, e)) cycle
      gtype = catalogue(m%etype(e))%gmsh_type
      ! two tags: physical and elementary entity = section number
      write(u, '(i0,1x,i0,1x,i0,1x,i0,1x,i0,*(1x,i0))') m%elem_id(e), gtype, 2, m%elem_section(e), &
        m%elem_section(e), m%node_id(m%conn(1:elem_nodes(m, e), e))
    end do
    write(u, '(a)') '$EndElements'
    flush(u)
  end subroutine open_result_file

  !> The views of one increment. sig_node/sig_elem may be absent when no
  !> stress was requested; pressure(nn) holds contact pressures (slave and
  !> master nodes) and has_pressure marks the nodes that carry one.
  subroutine write_result_views(rf, m, req_nodal, req_elem, time, u, reac, sig_node, sig_elem, &
                                pressure, has_pressure)
    type(result_file_t), intent(inout) :: rf
    type(model_t), intent(in) :: m
    type(request_t), intent(in) :: req_nodal, req_elem
    real(dp), intent(in) :: time
    real(dp), intent(in) :: u(:, :), reac(:, :), sig_node(:, :), sig_elem(:, :), pressure(:)
    logical, intent(in) :: has_pressure(:)
    integer :: k
    character(len=5), parameter :: names(4) = ['S11  ', 'S22  ', 'S33  ', 'S12  ']
    rf%count = rf%count + 1
    if (req_nodal%u) call node_view('Displacement', 3, u)
    if (req_nodal%rf) call node_view('Reaction force', 3, reac)
    if (req_nodal%s) then
      do k = 1, 4
        call node_view(trim(names(k)), 1, sig_node(k:k, :))
      end do
      call node_view('Mises', 1, reshape([(von_mises(sig_node(:, k)), k = 1, m%nn)], [1, m%nn]))
    end if
    if (req_nodal%cstress) call pressure_view()
    if (req_elem%s) then
      do k = 1, 4
        call elem_view(trim(names(k)) // ' (element)', sig_elem(k:k, :))
      end do
      call elem_view('Mises (element)', reshape([(von_mises(sig_elem(:, k)), k = 1, m%ne)], [1, m%ne]))
    end if
    flush(rf%unit)

  contains

    subroutine header(tag, block, ncomp, n)
      character(len=*), intent(in) :: tag, block
      integer, intent(in) :: ncomp, n
      write(rf%unit, '(a)') '$' // block
      write(rf%unit, '(a)') '1', '"' // tag // '"', '1'
      write(rf%unit, '(es24.15e3)') time
      write(rf%unit, '(a)') '3'
      write(rf%unit, '(i0)') rf%count - 1, ncomp, n
    end subroutine header

    subroutine node_view(tag, ncomp, v)
      character(len=*), intent(in) :: tag
      integer, intent(in) :: ncomp
      real(dp), intent(in) :: v(:, :)
      integer :: i
      call header(tag, 'NodeData', ncomp, m%nn)
      do i = 1, m%nn
        if (ncomp == 3) then
          write(rf%unit, '(i0,3(1x,es17.8e3))') m%node_id(i), v(1:2, i), 0.0_dp
        else
          write(rf%unit, '(i0,1x,es17.8e3)') m%node_id(i), v(1, i)
        end if
      end do
      write(rf%unit, '(a)') '$EndNodeData'
    end subroutine node_view

    subroutine pressure_view()
      integer :: i
      call header('Contact pressure', 'NodeData', 1, count(has_pressure))
      do i = 1, m%nn
        if (has_pressure(i)) write(rf%unit, '(i0,1x,es17.8e3)') m%node_id(i), pressure(i)
      end do
      write(rf%unit, '(a)') '$EndNodeData'
    end subroutine pressure_view

    subroutine elem_view(tag, v)
      character(len=*), intent(in) :: tag
      real(dp), intent(in) :: v(:, :)
      integer :: e
      call header(tag, 'ElementData', 1, count([(is_continuum(m, e), e = 1, m%ne)]))
      do e = 1, m%ne
        if (is_continuum(m, e)) write(rf%unit, '(i0,1x,es17.8e3)') m%elem_id(e), v(1, e)
      end do
      write(rf%unit, '(a)') '$EndElementData'
    end subroutine elem_view
  end subroutine write_result_views
end module results_gmsh
