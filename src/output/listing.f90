!> The text listing <job>.out and the machine-readable contact table
!> <job>_contact.csv. Every block of the listing starts with a line
!> "--- NAME key=value ...", then one header line of column names, then
!> rows; increments are framed by "=== INCREMENT ..." and "=== END". The
!> listing observes the analysis: it writes what the analysis tells it and
!> computes nothing.
module listing
  use kinds, only: dp, program_version
  use strings, only: rtoa, ftoa
  use model
  use materials, only: von_mises
  use messages, only: register_unit_to_close, fatal
  use solver_codes, only: solver_name, ordering_name
  use blas_info, only: blas_description
  use analysis_events, only: analysis_observer_t, step_info_t, iteration_info_t, step_summary_t, solver_info_t, &
                             run_timing_t
  use increment_results, only: increment_results_t
  use contact_results, only: pair_results_t, model_has_friction, model_has_wear, slave_state
  use contact_heat, only: has_contact_heat
  use output_schedule, only: schedule_t
  implicit none
  private
  public :: listing_t, open_listing, write_header

  type, extends(analysis_observer_t) :: listing_t
    integer :: unit = 0
    integer :: csv = 0
    logical :: has_csv = .false.
    integer :: digits = 7      ! significant digits of listed reals
    !> Row formats, made once for the digits asked for (not per row):
    !> set + 2 reals, node + 2, 4, 5 or 7 reals, element + point + 3 or 5
    !> reals, and a slave contact row without and with friction.
    character(len=:), allocatable :: f_set2, f_node2, f_node4, f_node5, f_node7, f_ip1, f_ip3, f_ip5, f_slave, &
                                     f_slave_fric, f_wear
    !> Which increments get the requested blocks (FREQUENCY=, TIME POINTS=)
    type(schedule_t) :: schedule
  contains
    procedure :: step_started => write_step_header
    procedure :: solver_ready => write_solver
    procedure :: iteration => write_iteration
    procedure :: note => write_note
    procedure :: increment_done => write_increment
    procedure :: step_finished => write_step_summary
    procedure :: run_finished => write_timing
  end type listing_t

contains

  subroutine open_listing(path, csv_path, digits, lst)
    character(len=*), intent(in) :: path, csv_path
    integer, intent(in) :: digits
    type(listing_t), intent(out) :: lst
    integer :: ios
    lst%digits = digits
    lst%f_set2 = rowfmt(lst, 'a', 2)
    lst%f_node2 = rowfmt(lst, 'i10', 2)
    lst%f_node4 = rowfmt(lst, 'i10', 4)
    lst%f_node5 = rowfmt(lst, 'i10', 5)
    lst%f_node7 = rowfmt(lst, 'i10', 7)
    lst%f_ip1 = rowfmt(lst, 'i10,i4', 1)
    lst%f_ip3 = rowfmt(lst, 'i10,i4', 3)
    lst%f_ip5 = rowfmt(lst, 'i10,i4', 5)
    lst%f_slave = '(i10,3' // efmt(lst) // ',1x,a6,3' // efmt(lst) // ')'
    lst%f_slave_fric = '(i10,3' // efmt(lst) // ',1x,a6,7' // efmt(lst) // ')'
    lst%f_wear = '(4' // efmt(lst) // ')'
    open(newunit=lst%unit, file=path, status='replace', action='write', iostat=ios)
    if (ios /= 0) call fatal('cannot write the listing "' // path // '"')
    call register_unit_to_close(lst%unit)
    if (len(csv_path) > 0) then
      open(newunit=lst%csv, file=csv_path, status='replace', action='write', iostat=ios)
      if (ios /= 0) call fatal('cannot write the contact table "' // csv_path // '"')
      call register_unit_to_close(lst%csv)
      lst%has_csv = .true.
    end if
  end subroutine open_listing

  subroutine write_text(lst, text)
    class(listing_t), intent(in) :: lst
    character(len=*), intent(in) :: text
    write(lst%unit, '(a)') text
    flush(lst%unit)
  end subroutine write_text

  !> Edit descriptor of one listed real: digits significant digits.
  function efmt(lst) result(f)
    class(listing_t), intent(in) :: lst
    character(len=:), allocatable :: f
    character(len=16) :: buf
    write(buf, '(a,i0,a,i0,a)') 'es', lst%digits + 9, '.', lst%digits - 1, 'e3'
    f = trim(buf)
  end function efmt

  !> Row format: leading descriptors, then n reals.
  function rowfmt(lst, lead, n) result(f)
    class(listing_t), intent(in) :: lst
    character(len=*), intent(in) :: lead
    integer, intent(in) :: n
    character(len=:), allocatable :: f
    character(len=8) :: buf
    write(buf, '(i0)') n
    f = '(' // lead // ',' // trim(buf) // efmt(lst) // ')'
  end function rowfmt

  !> Purpose: the listing's header and the contact table's column names
  !> (the table has the friction columns when some pair has friction,
  !> which only the model tells).
  subroutine write_header(lst, m)
    class(listing_t), intent(in) :: lst
    type(model_t), intent(in) :: m
    integer :: nsolid, u, e
    if (lst%has_csv) then
      if (model_has_friction(m)) then
        write(lst%csv, '(a)', advance='no') 'step,increment,time,pair,side,node,x,y,gap,state,force,pressure,' // &
                                            'shear_force,shear,slip,slip_increment'
      else
        write(lst%csv, '(a)', advance='no') 'step,increment,time,pair,side,node,x,y,gap,state,force,pressure'
      end if
      ! heat through the contact: the heat flux per point, the last column
      if (m%coupled .and. has_contact_heat(m)) write(lst%csv, '(a)', advance='no') ',heat_flux'
      ! wear (*WEAR): the worn depths and the worn surface point, last
      if (model_has_wear(m)) write(lst%csv, '(a)', advance='no') ',wear_slave,wear_master,worn_x,worn_y'
      write(lst%csv, '(a)') ''
      flush(lst%csv)
    end if
    u = lst%unit
    nsolid = count([(is_continuum(m, e), e = 1, m%ne)])
    write(u, '(a)') 'cfe2d ' // program_version // ' - 2D contact with coupling finite elements'
    write(u, '(a)') '--- MODEL'
    write(u, '(a)') 'item value'
    write(u, '(a)') 'deck ' // m%deck_name
    write(u, '(a)') 'heading ' // m%heading
    write(u, '(a,i0)') 'nodes ', m%nn
    write(u, '(a,i0)') 'elements ', m%ne
    write(u, '(a,i0)') 'solid_elements ', nsolid
    write(u, '(a,i0)') 'dofs ', 2 * m%nn
    write(u, '(a,i0)') 'materials ', size(m%materials)
    write(u, '(a,i0)') 'contact_pairs ', size(m%pairs)
    write(u, '(a,i0)') 'steps ', size(m%steps)
    write(u, '(a)') 'solver ' // solver_name(m%solver)
    write(u, '(a)') 'ordering ' // ordering_name(m%ordering)
    write(u, '(a)') 'blas ' // blas_description()
    call write_constraint_cards(u, m)
    call write_instances(u, m)
    flush(u)
  end subroutine write_header

  !> Purpose: the instances of an Abaqus/CAE deck: which part, how many
  !> nodes and elements, the offsets that make their ids in the result
  !> files and the `node`/`element` columns (offset + the part's number;
  !> the `label` column gives INSTANCE.NUMBER), and the placement.
  subroutine write_instances(u, m)
    integer, intent(in) :: u
    type(model_t), intent(in) :: m
    integer :: k
    if (.not. has_instances(m)) return
    write(u, '(a)') '--- INSTANCES (id in the result files = offset + the number in the part)'
    write(u, '(a)') 'instance part nodes node_offset elements element_offset dx dy angle'
    do k = 1, size(m%instances)
      associate(inst => m%instances(k))
        write(u, '(2(a,1x),4(i0,1x),a,1x,a,1x,a)') trim(inst%name), trim(inst%part), inst%nodes, inst%node_offset, &
          inst%elements, inst%elem_offset, rtoa(inst%shift(1), 8), rtoa(inst%shift(2), 8), rtoa(inst%angle, 8)
      end associate
    end do
  end subroutine write_instances

  !> ' label' after the column names of a block whose rows end with the
  !> node or element as the deck names it (a deck with instances).
  pure function label_column(m) result(s)
    type(model_t), intent(in) :: m
    character(len=:), allocatable :: s
    s = ''
    if (has_instances(m)) s = ' label'
  end function label_column

  !> The cards that generated linear constraints: each pre-tension
  !> section (its normal, the nodes it duplicated and their new ids) and
  !> each tie (slave nodes tied and not tied).
  subroutine write_constraint_cards(u, m)
    integer, intent(in) :: u
    type(model_t), intent(in) :: m
    integer :: k
    if (size(m%pretensions) > 0) then
      write(u, '(a)') '--- PRE-TENSION SECTIONS'
      write(u, '(a)') 'surface ref_node nx ny cut_nodes first_new_node last_new_node'
      do k = 1, size(m%pretensions)
        associate(pt => m%pretensions(k))
          write(u, '(a,1x,i0,2(1x,a),3(1x,i0))') trim(m%surfaces(pt%surface)%name), m%node_id(pt%ref_node), &
            rtoa(pt%normal(1), 8), rtoa(pt%normal(2), 8), size(pt%copy), m%node_id(pt%copy(1)), &
            m%node_id(pt%copy(size(pt%copy)))
        end associate
      end do
    end if
    if (size(m%ties) > 0) then
      write(u, '(a)') '--- TIES'
      write(u, '(a)') 'name slave master tied_nodes untied_nodes adjust largest_move'
      do k = 1, size(m%ties)
        associate(t => m%ties(k))
          write(u, '(3(a,1x),i0,1x,i0,1x,a,1x,a)') trim(t%name), trim(m%surfaces(t%slave_surface)%name), &
            trim(m%surfaces(t%master_surface)%name), t%tied, t%untied, trim(merge('yes', 'no ', t%adjust)), &
            rtoa(t%largest_move, 3)
        end associate
      end do
    end if
    call write_rigid_cards(u, m)
  end subroutine write_constraint_cards

  !> The rigid bodies and couplings (card, its set, surface or name, the
  !> reference node, the node whose dof 1 is the rotation, listed as its
  !> U1 and RF1: '-' when nothing turns, the nodes tied or averaged) and
  !> the *TRANSFORMs (set, type, the nodes made to carry the local
  !> displacements of the transformed nodes that cards name).
  subroutine write_rigid_cards(u, m)
    integer, intent(in) :: u
    type(model_t), intent(in) :: m
    integer :: k, nloc
    character(len=:), allocatable :: card, rot
    if (size(m%rigids) > 0) then
      write(u, '(a)') '--- RIGID BODIES'
      write(u, '(a)') 'card name ref_node rot_node nodes dofs'
      do k = 1, size(m%rigids)
        associate(r => m%rigids(k))
          select case (r%kind)
          case (rigid_body); card = 'RIGID_BODY'
          case (rigid_kinematic); card = 'KINEMATIC'
          case default; card = 'DISTRIBUTING'
          end select
          rot = '-'
          if (r%rot_node > 0) rot = node_label(m, r%rot_node)
          write(u, '(a,1x,a,1x,a,1x,a,1x,i0,1x,a)') card, trim(r%name), node_label(m, r%ref_node), rot, &
            size(r%nodes), trim(dof_list(r))
        end associate
      end do
    end if
    if (size(m%transforms) > 0) then
      write(u, '(a)') '--- TRANSFORMS'
      write(u, '(a)') 'set type nodes local_nodes'
      do k = 1, size(m%transforms)
        associate(t => m%transforms(k))
          nloc = 0
          if (allocated(m%local_node)) nloc = count(m%local_node > 0 .and. m%node_transform(1:size(m%local_node)) == k)
          write(u, '(a,1x,a,1x,i0,1x,i0)') trim(m%nsets(t%nset)%name), merge('R', 'C', t%kind == transform_rectangular), &
            count(m%node_transform == k), nloc
        end associate
      end do
    end if
  end subroutine write_rigid_cards

  !> The dofs a rigid body or coupling ties: 1,2 (and 6 where a moment
  !> is spread or the body turns).
  pure function dof_list(r) result(s)
    type(rigid_t), intent(in) :: r
    character(len=:), allocatable :: s
    s = ''
    if (r%follows(1)) s = '1'
    if (r%follows(2)) s = s // merge(',2', '2 ', len(s) > 0)
    s = trim(s)
    if (r%rot_node > 0 .and. (r%kind /= rigid_distributing .or. r%moment)) s = s // ',6'
    if (len(s) == 0) s = '-'
  end function dof_list

  subroutine write_step_header(self, m, info)
    class(listing_t), intent(inout) :: self
    type(model_t), intent(in) :: m
    type(step_info_t), intent(in) :: info
    integer :: u, k
    u = self%unit
    write(u, '(a)') ''
    write(u, '(a,i0,a)') '--- STEP step=', info%step, ' name=' // trim(m%steps(info%step)%name)
    write(u, '(a)') 'item value'
    write(u, '(a,i0)') 'equations ', info%equations
    write(u, '(a,i0)') 'prescribed_dofs ', info%prescribed
    write(u, '(a,es13.5e3)') 'time_period ', info%period
    write(u, '(a,i0)') 'increments ', info%increments
    write(u, '(a,i0)') 'coupling_elements ', info%coupling_elements
    if (size(info%uncoupled) > 0) then
      write(u, '(a)') '--- UNCOUPLED SLAVE NODES (no master segment under them)'
      write(u, '(a)') 'pair node' // label_column(m)
      do k = 1, size(info%uncoupled)
        if (has_instances(m)) then
          write(u, '(i0,1x,i0,1x,a)') info%uncoupled_pair(k), m%node_id(info%uncoupled(k)), &
            node_label(m, info%uncoupled(k))
        else
          write(u, '(i0,1x,i0)') info%uncoupled_pair(k), m%node_id(info%uncoupled(k))
        end if
      end do
    end if
    flush(u)
  end subroutine write_step_header

  subroutine write_solver(self, info)
    class(listing_t), intent(inout) :: self
    type(solver_info_t), intent(in) :: info
    write(self%unit, '(a,i0)') '--- SOLVER step=', info%step
    write(self%unit, '(a)') 'item value'
    write(self%unit, '(a)') 'factor ' // info%description
    if (len(info%contact_solve) > 0) write(self%unit, '(a)') 'contact_solve ' // info%contact_solve
    if (info%contact_equations > 0) write(self%unit, '(a,i0)') 'contact_equations ', info%contact_equations
    flush(self%unit)
  end subroutine write_solver

  subroutine write_iteration(self, info)
    class(listing_t), intent(inout) :: self
    type(iteration_info_t), intent(in) :: info
    character(len=:), allocatable :: nodes
    nodes = ''
    if (info%changes > 0) nodes = ' (nodes' // info%changed // ')'
    write(self%unit, '(a,i0,a,i0,a,i0,a,es11.3e3,a)') 'contact iteration ', info%iteration, ': status changes ', &
      info%changes, ', closed ', info%closed, ', out-of-balance ', info%residual, nodes
  end subroutine write_iteration

  subroutine write_note(self, text)
    class(listing_t), intent(inout) :: self
    character(len=*), intent(in) :: text
    call write_text(self, text)
  end subroutine write_note

  subroutine write_step_summary(self, summary)
    class(listing_t), intent(inout) :: self
    type(step_summary_t), intent(in) :: summary
    integer :: u
    u = self%unit
    write(u, '(a)') ''
    write(u, '(a,i0)') '--- STEP SUMMARY step=', summary%step
    write(u, '(a)') 'item value'
    write(u, '(a,i0)') 'increments ', summary%increments
    write(u, '(a,i0)') 'numeric_factorisations ', summary%factorisations
    write(u, '(a,i0)') 'condensed_factorisations ', summary%condensed_factorisations
    if (summary%temperature_factorisations >= 0) write(u, '(a,i0,a,i0)') &
      'numeric_factorisations_per_field temperature=', summary%temperature_factorisations, &
      ' displacement=', summary%factorisations - summary%temperature_factorisations
    write(u, '(a,i0)') 'contact_iterations ', summary%iterations
    write(u, '(a,i0)') 'contact_block_pivots ', summary%block_pivots
    write(u, '(a,i0)') 'contact_single_pivots ', summary%single_pivots
    write(u, '(a,i0)') 'element_calls_continuum_stiffness ', summary%continuum_tangent
    write(u, '(a,i0)') 'element_calls_continuum_stresses ', summary%continuum_stresses
    write(u, '(a,i0)') 'element_calls_coupling ', summary%coupling
    if (summary%nonlinear) then
      write(u, '(a,i0)') 'newton_iterations ', summary%newton_iterations
      write(u, '(a,i0)') 'cutbacks ', summary%cutbacks
    end if
    write(u, '(a)') 'wall_seconds ' // ftoa(summary%wall_seconds, 3)
    flush(u)
  end subroutine write_step_summary

  !> Purpose: the last block: where the wall time of the run went and how
  !> many matrices were factored.
  subroutine write_timing(self, timing)
    class(listing_t), intent(inout) :: self
    type(run_timing_t), intent(in) :: timing
    integer :: u
    u = self%unit
    write(u, '(a)') ''
    write(u, '(a)') '--- TIMING (wall seconds)'
    write(u, '(a)') 'item value'
    write(u, '(a,a)') 'read ', ftoa(timing%read, 3)
    write(u, '(a,a)') 'setup ', ftoa(timing%setup, 3)
    write(u, '(a,a)') 'assembly ', ftoa(timing%assembly, 3)
    write(u, '(a,a)') 'analyse ', ftoa(timing%analyse, 3)
    write(u, '(a,a)') 'factor ', ftoa(timing%factor, 3)
    write(u, '(a,a)') 'condensed_iterations ', ftoa(timing%condensed, 3)
    write(u, '(a,a)') 'full_iterations ', ftoa(timing%solve, 3)
    write(u, '(a,a)') 'recovery ', ftoa(timing%recovery, 3)
    write(u, '(a,a)') 'results ', ftoa(timing%results, 3)
    write(u, '(a,a)') 'output ', ftoa(timing%output, 3)
    write(u, '(a,a)') 'total ', ftoa(timing%total, 3)
    write(u, '(a,i0)') 'numeric_factorisations ', timing%numeric_factorisations
    write(u, '(a,i0)') 'condensed_factorisations ', timing%condensed_factorisations
    flush(u)
  end subroutine write_timing


  !> Purpose: one increment: reaction sums; the requested blocks and the
  !> contact results (and the contact table rows) at the increments the
  !> step's FREQUENCY= or TIME POINTS= select (output_schedule).
  subroutine write_increment(self, m, res)
    class(listing_t), intent(inout) :: self
    type(model_t), intent(in) :: m
    type(increment_results_t), intent(in) :: res
    integer :: ir, k, un
    logical :: due
    un = self%unit
    due = self%schedule%due(m, res)
    write(un, '(a)') ''
    write(un, '(a,i0,a,i0,a,i0,a)') '=== INCREMENT step=', res%step, ' increment=', res%increment, &
      ' time=' // rtoa(res%time, 9) // ' total_time=' // rtoa(res%total_time, 9) // ' iterations=', &
      res%iterations, ' ==='
    associate(reqs => m%steps(res%step)%requests)
      do ir = 1, size(reqs)
        if (reqs(ir)%to_file .or. .not. due) cycle
        if (reqs(ir)%nodal) then
          call write_node_request(self, m, reqs(ir), res)
        else
          call write_element_request(self, m, reqs(ir), res)
        end if
      end do
    end associate
    if (size(res%set_ids) > 0) then
      write(un, '(a)') '--- REACTIONS (sum over each prescribed node set)'
      write(un, '(a)') 'set RF1 RF2'
      do k = 1, size(res%set_ids)
        write(un, self%f_set2) trim(m%nsets(res%set_ids(k))%name), res%set_sums(:, k)
      end do
    end if
    ! the contact tables (and the contact table's rows) follow the step's
    ! FREQUENCY= or TIME POINTS= too: a long history (fretting: 1e5
    ! increments) writes only the increments asked for
    if (due) then
      do k = 1, size(res%contact%pairs)
        call write_contact(self, m, res, res%contact%pairs(k))
      end do
    end if
    write(un, '(a)') '=== END INCREMENT'
    flush(un)
    if (self%has_csv) flush(self%csv)
  end subroutine write_increment

  !> Header of a requested block: its name, set and columns.
  subroutine block_head(self, m, name, set, nodal, cols)
    class(listing_t), intent(in) :: self
    type(model_t), intent(in) :: m
    character(len=*), intent(in) :: name, cols
    integer, intent(in) :: set
    logical, intent(in) :: nodal
    character(len=:), allocatable :: sname
    sname = 'ALL'
    if (set > 0) then
      if (nodal) then
        sname = trim(m%nsets(set)%name)
      else
        sname = trim(m%elsets(set)%name)
      end if
    end if
    write(self%unit, '(a)') '--- ' // name // ' set=' // sname
    write(self%unit, '(a)') cols
  end subroutine block_head

  !> *NODE PRINT: U, RF, S at the nodes of a set (all nodes when set = 0).
  !> With instances each row ends with the node's label (INSTANCE.NUMBER).
  !> In a model with *TRANSFORM, U and RF of a transformed node are in its
  !> local axes unless GLOBAL=YES (CalculiX's *NODE PRINT, which marks
  !> such rows with L): a column `system` says L (local) or G (global).
  subroutine write_node_request(self, m, req, res)
    class(listing_t), intent(in) :: self
    type(model_t), intent(in) :: m
    type(request_t), intent(in) :: req
    type(increment_results_t), intent(in) :: res
    integer, allocatable :: sel(:)
    integer :: k, un
    logical :: lab, local
    un = self%unit
    lab = has_instances(m)
    local = .not. req%global .and. size(m%transforms) > 0
    if (req%set > 0) then
      sel = m%nsets(req%set)%items
    else
      sel = [(k, k = 1, m%nn)]
    end if
    if (req%totals) call write_rf_total(self, m, req, res, sel)
    if (req%only_totals) return
    if (req%u) then
      call block_head(self, m, 'NODE U', req%set, .true., 'node U1 U2' // system_column(local) // label_column(m))
      do k = 1, size(sel)
        call vector_row(res%u(:, sel(k)), sel(k))
      end do
    end if
    if (req%rf) then
      call block_head(self, m, 'NODE RF', req%set, .true., 'node RF1 RF2' // system_column(local) // &
                      label_column(m))
      do k = 1, size(sel)
        call vector_row(res%rf(:, sel(k)), sel(k))
      end do
    end if
    if (res%heat) call write_heat_rows(self, m, req, res, sel)
    if (req%s) then
      call block_head(self, m, 'NODE S', req%set, .true., 'node S11 S22 S33 S12 MISES' // label_column(m))
      do k = 1, size(sel)
        if (lab) then
          write(un, self%f_node5, advance='no') m%node_id(sel(k)), res%sig_node(:, sel(k)), &
            von_mises(res%sig_node(:, sel(k)))
          write(un, '(1x,a)') node_label(m, sel(k))
        else
          write(un, self%f_node5) m%node_id(sel(k)), res%sig_node(:, sel(k)), &
            von_mises(res%sig_node(:, sel(k)))
        end if
      end do
    end if
  contains
    !> A row of a nodal vector: global, or in node a's local axes.
    subroutine vector_row(v, a)
      real(dp), intent(in) :: v(2)
      integer, intent(in) :: a
      real(dp) :: w(2)
      character(len=2) :: sys
      w = v
      sys = ''
      if (local) then
        sys = ' G'
        if (has_transform(m, a)) then
          w = matmul(transpose(node_axes(m, a)), v)
          sys = ' L'
        end if
      end if
      if (lab .or. local) then
        write(un, self%f_node2, advance='no') m%node_id(a), w
        if (lab) then
          write(un, '(a,1x,a)') trim(sys), node_label(m, a)
        else
          write(un, '(a)') trim(sys)
        end if
      else
        write(un, self%f_node2) m%node_id(a), w
      end if
    end subroutine vector_row
  end subroutine write_node_request

  !> Purpose: *NODE PRINT of a heat transfer step: NT (temperatures) and
  !> RFL (reaction fluxes) at the nodes sel of the request's set.
  subroutine write_heat_rows(self, m, req, res, sel)
    class(listing_t), intent(in) :: self
    type(model_t), intent(in) :: m
    type(request_t), intent(in) :: req
    type(increment_results_t), intent(in) :: res
    integer, intent(in) :: sel(:)
    integer :: k
    if (req%nt) then
      call block_head(self, m, 'NODE NT', req%set, .true., 'node NT11')
      do k = 1, size(sel)
        write(self%unit, rowfmt(self, 'i10', 1)) m%node_id(sel(k)), res%nt(sel(k))
      end do
    end if
    if (req%rfl) then
      call block_head(self, m, 'NODE RFL', req%set, .true., 'node RFL11')
      do k = 1, size(sel)
        write(self%unit, rowfmt(self, 'i10', 1)) m%node_id(sel(k)), res%rfl(sel(k))
      end do
    end if
  end subroutine write_heat_rows

  !> Purpose: TOTALS=YES or ONLY of *NODE PRINT: the sum of RF over the
  !> nodes sel of the set, global components (CalculiX's "total force"),
  !> when RF is asked for.
  subroutine write_rf_total(self, m, req, res, sel)
    class(listing_t), intent(in) :: self
    type(model_t), intent(in) :: m
    type(request_t), intent(in) :: req
    type(increment_results_t), intent(in) :: res
    integer, intent(in) :: sel(:)
    integer :: k
    real(dp) :: total(2)
    if (.not. req%rf) return
    total = 0.0_dp
    do k = 1, size(sel)
      total = total + res%rf(:, sel(k))
    end do
    call block_head(self, m, 'NODE RF TOTAL', req%set, .true., 'RF1 RF2')
    write(self%unit, '(2' // efmt(self) // ')') total
  end subroutine write_rf_total

  !> ' system' after the column names of U and RF when rows may be in a
  !> node's local axes (L) or global (G).
  pure function system_column(local) result(s)
    logical, intent(in) :: local
    character(len=:), allocatable :: s
    s = ''
    if (local) s = ' system'
  end function system_column

  !> *EL PRINT: S, E and PEEQ at the integration points of an element set
  !> (under NLGEOM S is the Cauchy stress and E the strain the element
  !> routine reports).
  subroutine write_element_request(self, m, req, res)
    class(listing_t), intent(in) :: self
    type(model_t), intent(in) :: m
    type(request_t), intent(in) :: req
    type(increment_results_t), intent(in) :: res
    integer, allocatable :: sel(:)
    integer :: k, e, ip, un
    logical :: lab
    un = self%unit
    lab = has_instances(m)
    if (req%set > 0) then
      sel = m%elsets(req%set)%items
    else
      sel = [(k, k = 1, m%ne)]
    end if
    if (req%s) then
      call block_head(self, m, 'ELEMENT S', req%set, .false., 'element ip S11 S22 S33 S12 MISES' // &
                      label_column(m))
      do k = 1, size(sel)
        e = sel(k)
        do ip = 1, res%nip(e)
          if (lab) then
            write(un, self%f_ip5, advance='no') m%elem_id(e), ip, res%sig_ip(:, ip, e), &
              von_mises(res%sig_ip(:, ip, e))
            write(un, '(1x,a)') elem_label(m, e)
          else
            write(un, self%f_ip5) m%elem_id(e), ip, res%sig_ip(:, ip, e), &
              von_mises(res%sig_ip(:, ip, e))
          end if
        end do
      end do
    end if
    if (req%e) then
      call block_head(self, m, 'ELEMENT E', req%set, .false., 'element ip E11 E22 E12' // label_column(m))
      do k = 1, size(sel)
        e = sel(k)
        do ip = 1, res%nip(e)
          if (lab) then
            write(un, self%f_ip3, advance='no') m%elem_id(e), ip, res%eps_ip(:, ip, e)
            write(un, '(1x,a)') elem_label(m, e)
          else
            write(un, self%f_ip3) m%elem_id(e), ip, res%eps_ip(:, ip, e)
          end if
        end do
      end do
    end if
    if (req%hfl .and. res%heat) then
      ! heat transfer: the heat flux -k grad T at the integration points
      call block_head(self, m, 'ELEMENT HFL', req%set, .false., 'element ip HFL1 HFL2')
      do k = 1, size(sel)
        e = sel(k)
        do ip = 1, res%nip(e)
          write(un, rowfmt(self, 'i10,i4', 2)) m%elem_id(e), ip, res%hfl_ip(:, ip, e)
        end do
      end do
    end if
    if (req%peeq) then
      ! the equivalent plastic strain (zero for a material without *PLASTIC)
      call block_head(self, m, 'ELEMENT PEEQ', req%set, .false., 'element ip PEEQ' // label_column(m))
      do k = 1, size(sel)
        e = sel(k)
        do ip = 1, res%nip(e)
          if (lab) then
            write(un, self%f_ip1, advance='no') m%elem_id(e), ip, res%peeq_ip(ip, e)
            write(un, '(1x,a)') elem_label(m, e)
          else
            write(un, self%f_ip1) m%elem_id(e), ip, res%peeq_ip(ip, e)
          end if
        end do
      end do
    end if
  end subroutine write_element_request

  !> Slave rows, master rows and the summary of one contact pair, and the
  !> same rows in the contact table. A frictional pair's tables have the
  !> shear columns (and its slave rows say STICK or SLIP for CLOSED); the
  !> contact table has them on every row when some pair has friction
  !> (zeros for a frictionless pair, and for the slip of master rows), so
  !> that its columns are the same throughout the file.
  subroutine write_contact(self, m, res, r)
    class(listing_t), intent(in) :: self
    type(model_t), intent(in) :: m
    type(increment_results_t), intent(in) :: res
    type(pair_results_t), intent(in) :: r
    integer :: un
    un = self%unit
    call write_slave_rows(self, m, res, r)
    call write_master_rows(self, m, res, r)
    write(un, '(a,i0)') '--- CONTACT SUMMARY pair=', r%pair
    if (r%frictional) then
      write(un, '(a)') 'closed total_force resultant_x resultant_y max_penetration shear_total'
      write(un, self%f_node5) r%nclosed, r%total, r%resultant, r%max_pen, r%shear_total
    else
      write(un, '(a)') 'closed total_force resultant_x resultant_y max_penetration'
      write(un, self%f_node4) r%nclosed, r%total, r%resultant, r%max_pen
    end if
  end subroutine write_contact

  !> Purpose: the slave rows of one contact pair (write_contact): the
  !> listing's block and, with a contact table, its slave rows.
  subroutine write_slave_rows(self, m, res, r)
    class(listing_t), intent(in) :: self
    type(model_t), intent(in) :: m
    type(increment_results_t), intent(in) :: res
    type(pair_results_t), intent(in) :: r
    integer :: j, un, nid
    character(len=6) :: st
    character(len=*), parameter :: csv_slave = '(i0,",",i0,",",es16.8e3,",",i0,",slave,",i0,",",es16.8e3,",",' // &
      'es16.8e3,",",es16.8e3,",",a,",",es16.8e3,",",es16.8e3)'
    character(len=*), parameter :: csv_slave_fric = '(i0,",",i0,",",es16.8e3,",",i0,",slave,",i0,",",es16.8e3,' // &
      '",",es16.8e3,",",es16.8e3,",",a,6(",",es16.8e3))'
    character(len=*), parameter :: csv_wear = '(4(",",es16.8e3))'
    un = self%unit
    write(un, '(a,i0,a)') '--- CONTACT SLAVE pair=', r%pair, ' surface=' // &
      trim(m%surfaces(m%pairs(r%pair)%slave_surface)%name)
    if (r%frictional) then
      write(un, '(a)') 'node x y gap state force area pressure shear_force shear slip slip_inc' // &
                       wear_columns(r) // label_column(m)
    else
      write(un, '(a)') 'node x y gap state force area pressure' // wear_columns(r) // label_column(m)
    end if
    do j = 1, size(r%slave_node)
      nid = 0
      if (r%slave_node(j) > 0) nid = m%node_id(r%slave_node(j))
      st = slave_state(r, j)
      if (r%frictional) then
        write(un, self%f_slave_fric, advance='no') nid, r%slave_x(:, j), r%slave_gap(j), st, r%slave_force(j), &
          r%slave_area(j), r%slave_pressure(j), r%slave_shear(j), r%slave_traction(j), &
          r%slave_slip(j), r%slave_slip_inc(j)
      else
        write(un, self%f_slave, advance='no') nid, r%slave_x(:, j), &
          r%slave_gap(j), st, r%slave_force(j), r%slave_area(j), r%slave_pressure(j)
      end if
      if (allocated(r%slave_wear)) write(un, self%f_wear, advance='no') r%slave_wear(:, j), r%slave_worn(:, j)
      call end_row(un, m, r%slave_node(j))
      if (.not. self%has_csv) cycle
      if (res%contact%frictional) then
        write(self%csv, csv_slave_fric, advance='no') res%step, res%increment, res%total_time, r%pair, nid, &
          r%slave_x(:, j), r%slave_gap(j), trim(st), r%slave_force(j), r%slave_pressure(j), r%slave_shear(j), &
          r%slave_traction(j), r%slave_slip(j), r%slave_slip_inc(j)
      else
        write(self%csv, csv_slave, advance='no') res%step, res%increment, res%total_time, r%pair, nid, &
          r%slave_x(:, j), r%slave_gap(j), trim(st), r%slave_force(j), r%slave_pressure(j)
      end if
      ! heat through the contact: the point's heat flux, slave to master
      if (allocated(r%slave_heat_flux)) write(self%csv, '(",",es16.8e3)', advance='no') r%slave_heat_flux(j)
      if (allocated(r%slave_wear)) write(self%csv, csv_wear, advance='no') r%slave_wear(:, j), r%slave_worn(:, j)
      write(self%csv, '(a)') ''
    end do
  end subroutine write_slave_rows

  !> Purpose: the master rows of one contact pair (write_contact): the
  !> listing's block (deformed position, force, area, pressure = force /
  !> area) and, with a contact table, its master rows.
  subroutine write_master_rows(self, m, res, r)
    class(listing_t), intent(in) :: self
    type(model_t), intent(in) :: m
    type(increment_results_t), intent(in) :: res
    type(pair_results_t), intent(in) :: r
    integer :: j, nd, un
    real(dp) :: xs(2), p, tau
    character(len=*), parameter :: csv_master = '(i0,",",i0,",",es16.8e3,",",i0,",master,",i0,",",es16.8e3,",",' // &
      'es16.8e3,",0,-,",es16.8e3,",",es16.8e3)'
    character(len=*), parameter :: csv_master_fric = '(i0,",",i0,",",es16.8e3,",",i0,",master,",i0,",",es16.8e3,' // &
      '",",es16.8e3,",0,-,",es16.8e3,",",es16.8e3,",",es16.8e3,",",es16.8e3,",0,0")'
    character(len=*), parameter :: csv_wear = '(4(",",es16.8e3))'
    un = self%unit
    write(un, '(a,i0,a)') '--- CONTACT MASTER pair=', r%pair, ' surface=' // &
      trim(m%surfaces(m%pairs(r%pair)%master_surface)%name)
    if (r%frictional) then
      write(un, '(a)') 'node x y force area pressure shear_force shear' // wear_columns(r) // label_column(m)
    else
      write(un, '(a)') 'node x y force area pressure' // wear_columns(r) // label_column(m)
    end if
    do j = 1, size(r%master_node)
      nd = r%master_node(j)
      xs = m%x(:, nd) + res%u(:, nd)
      p = 0.0_dp
      tau = 0.0_dp
      if (r%master_area(j) > 0.0_dp) then
        p = r%master_force(j) / r%master_area(j)
        tau = r%master_shear(j) / r%master_area(j)
      end if
      if (r%frictional) then
        write(un, self%f_node7, advance='no') m%node_id(nd), xs, r%master_force(j), r%master_area(j), p, &
          r%master_shear(j), tau
      else
        write(un, self%f_node5, advance='no') m%node_id(nd), xs, r%master_force(j), r%master_area(j), p
      end if
      if (allocated(r%master_wear)) write(un, self%f_wear, advance='no') 0.0_dp, r%master_wear(j), &
                                                                       r%master_worn(:, j)
      call end_row(un, m, nd)
      if (.not. self%has_csv) cycle
      if (res%contact%frictional) then
        write(self%csv, csv_master_fric, advance='no') res%step, res%increment, res%total_time, r%pair, &
          m%node_id(nd), xs, r%master_force(j), p, r%master_shear(j), tau
      else
        write(self%csv, csv_master, advance='no') res%step, res%increment, res%total_time, r%pair, m%node_id(nd), &
          xs, r%master_force(j), p
      end if
      ! (heat through the contact: its flux is the slave points')
      if (allocated(r%slave_heat_flux)) write(self%csv, '(a)', advance='no') ',0'
      if (allocated(r%master_wear)) write(self%csv, csv_wear, advance='no') 0.0_dp, r%master_wear(j), &
                                                                            r%master_worn(:, j)
      write(self%csv, '(a)') ''
    end do
  end subroutine write_master_rows

  !> The wear columns of a contact block's header (a model with *WEAR:
  !> wear_rows of contact_results), else nothing.
  function wear_columns(r) result(s)
    type(pair_results_t), intent(in) :: r
    character(len=:), allocatable :: s
    s = ''
    if (allocated(r%slave_wear)) s = ' wear_slave wear_master worn_x worn_y'
  end function wear_columns

  !> Ends a row of the contact tables: with instances (Abaqus/CAE), the
  !> node's label in the deck's terms (a Gauss point of a slave face, node
  !> 0, has none: '-').
  subroutine end_row(un, m, nd)
    integer, intent(in) :: un, nd
    type(model_t), intent(in) :: m
    if (.not. has_instances(m)) then
      write(un, '(a)') ''
    else if (nd > 0) then
      write(un, '(1x,a)') node_label(m, nd)
    else
      write(un, '(1x,a)') '-'
    end if
  end subroutine end_row
end module listing
