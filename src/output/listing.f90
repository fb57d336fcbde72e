!> The text listing <job>.out and the machine-readable contact table
!> <job>_contact.csv. Every block of the listing starts with a line
!> "--- NAME key=value ...", then one header line of column names, then
!> rows; increments are framed by "=== INCREMENT ..." and "=== END".
module listing
  use kinds, only: dp, program_version
  use strings, only: rtoa
  use model
  use materials, only: von_mises
  use contact, only: contact_set_t
  use messages, only: register_unit_to_close, fatal
  use solver_codes, only: solver_name, ordering_name
  use blas_info, only: blas_description
  implicit none
  private
  public :: listing_t, open_listing, write_header, write_step_header, write_increment, &
            write_iteration, write_text, contact_results_t, contact_results

  type :: listing_t
    integer :: unit = 0
    integer :: csv = 0
    logical :: has_csv = .false.
    integer :: digits = 7      ! significant digits of listed reals
  end type listing_t

  !> Contact results of one pair, slave and master side, for the listing
  !> and the table.
  type :: contact_results_t
    integer, allocatable :: slave_cfe(:)       ! CFE index of each slave row
    real(dp), allocatable :: slave_force(:)    ! normal force at the slave node
    integer, allocatable :: master_node(:)
    real(dp), allocatable :: master_force(:), master_area(:)
    real(dp) :: total = 0.0_dp, resultant(2) = 0.0_dp, max_pen = 0.0_dp
    integer :: nclosed = 0
  end type contact_results_t


contains

  subroutine open_listing(path, csv_path, digits, lst)
    character(len=*), intent(in) :: path, csv_path
    integer, intent(in) :: digits
    type(listing_t), intent(out) :: lst
    integer :: ios
    lst%digits = digits
    open(newunit=lst%unit, file=path, status='replace', action='write', iostat=ios)
    if (ios /= 0) call fatal('cannot write the listing "' // path // '"')
    call register_unit_to_close(lst%unit)
    if (len(csv_path) > 0) then
      open(newunit=lst%csv, file=csv_path, status='replace', action='write', iostat=ios)
      if (ios /= 0) call fatal('cannot write the contact table "' // csv_path // '"')
      call register_unit_to_close(lst%csv)
      lst%has_csv = .true.
      write(lst%csv, '(a)') 'step,increment,time,pair,side,node,x,y,gap,state,force,pressure'
    end if
  end subroutine open_listing

  subroutine write_text(lst, text)
    type(listing_t), intent(in) :: lst
    character(len=*), intent(in) :: text
    write(lst%unit, '(a)') text
    flush(lst%unit)
  end subroutine write_text

  !> Edit descriptor of one listed real: digits significant digits.
  function efmt(lst) result(f)
    type(listing_t), intent(in) :: lst
    character(len=:), allocatable :: f
    character(len=16) :: buf
    write(buf, '(a,i0,a,i0)') 'es', lst%digits + 8, '.', lst%digits - 1
    f = trim(buf)
  end function efmt

  !> Row format: leading descriptors, then n reals.
  function rowfmt(lst, lead, n) result(f)
    type(listing_t), intent(in) :: lst
    character(len=*), intent(in) :: lead
    integer, intent(in) :: n
    character(len=:), allocatable :: f
    character(len=8) :: buf
    write(buf, '(i0)') n
    f = '(' // lead // ',' // trim(buf) // efmt(lst) // ')'
  end function rowfmt

  subroutine write_header(lst, m)
    type(listing_t), intent(in) :: lst
    type(model_t), intent(in) :: m
    integer :: nsolid, u, e
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
    flush(u)
  end subroutine write_header

  subroutine write_step_header(lst, istep, m, neq, nprescribed, cs)
    type(listing_t), intent(in) :: lst
    integer, intent(in) :: istep, neq, nprescribed
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    integer :: u, k
    u = lst%unit
    write(u, '(a)') ''
    write(u, '(a,i0,a)') '--- STEP step=', istep, ' name=' // trim(m%steps(istep)%name)
    write(u, '(a)') 'item value'
    write(u, '(a,i0)') 'equations ', neq
    write(u, '(a,i0)') 'prescribed_dofs ', nprescribed
    write(u, '(a,es12.5)') 'time_period ', m%steps(istep)%period
    write(u, '(a,i0)') 'increments ', nint(m%steps(istep)%period / m%steps(istep)%dt)
    write(u, '(a,i0)') 'coupling_elements ', cs%n
    if (size(cs%uncoupled) > 0) then
      write(u, '(a)') '--- UNCOUPLED SLAVE NODES (no master segment under them)'
      write(u, '(a)') 'pair node'
      do k = 1, size(cs%uncoupled)
        write(u, '(i0,1x,i0)') cs%uncoupled_pair(k), m%node_id(cs%uncoupled(k))
      end do
    end if
    flush(u)
  end subroutine write_step_header

  subroutine write_iteration(lst, it, nchanged, nclosed, resid, changed_nodes)
    type(listing_t), intent(in) :: lst
    integer, intent(in) :: it, nchanged, nclosed
    real(dp), intent(in) :: resid
    character(len=*), intent(in) :: changed_nodes
    write(lst%unit, '(a,i0,a,i0,a,i0,a,es10.3,a)') 'contact iteration ', it, ': status changes ', &
      nchanged, ', closed ', nclosed, ', out-of-balance ', resid, trim(changed_nodes)
  end subroutine write_iteration

  !> Results of pair ip. For a SYMMETRIC pair (reported on its first pass)
  !> each node's force is what both passes put on it: its own CFE force and
  !> what it receives as a master node of the other pass.
  subroutine contact_results(m, cs, ip, r)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    integer, intent(in) :: ip
    type(contact_results_t), intent(out) :: r
    type(contact_results_t) :: rt
    integer :: j, k
    call pass_results(m, cs, ip, r)
    if (m%pairs(ip)%twin == 0) return
    call pass_results(m, cs, m%pairs(ip)%twin, rt)
    do j = 1, size(r%slave_cfe)
      do k = 1, size(rt%master_node)
        if (rt%master_node(k) == cs%c(r%slave_cfe(j))%slave) r%slave_force(j) = r%slave_force(j) + rt%master_force(k)
      end do
    end do
    do k = 1, size(r%master_node)
      do j = 1, size(rt%slave_cfe)
        if (cs%c(rt%slave_cfe(j))%slave == r%master_node(k)) r%master_force(k) = r%master_force(k) + rt%slave_force(j)
      end do
    end do
    r%total = r%total + rt%total
    r%resultant = r%resultant - rt%resultant
    r%nclosed = r%nclosed + rt%nclosed
    r%max_pen = max(r%max_pen, rt%max_pen)
  end subroutine contact_results

  !> One pass: slave rows and the master-side forces its CFEs produce (each
  !> CFE force goes to the master edge nodes with the weights N_i(X_C)).
  subroutine pass_results(m, cs, ip, r)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    integer, intent(in) :: ip
    type(contact_results_t), intent(out) :: r
    integer :: k, j, a, b, nm
    integer, allocatable :: pos(:)
    real(dp) :: len, f
    associate(ms => m%surfaces(m%pairs(ip)%master_surface))
      r%slave_cfe = pack([(k, k = 1, cs%n)], cs%c(1:cs%n)%pair == ip)
      r%slave_force = -cs%c(r%slave_cfe)%force
      r%master_node = ms%nodes
      nm = size(ms%nodes)
      allocate(r%master_force(nm), r%master_area(nm), pos(m%nn))
      pos = 0
      do k = 1, nm
        pos(ms%nodes(k)) = k
      end do
      r%master_force = 0.0_dp
      r%master_area = 0.0_dp
      do j = 1, size(ms%elem)
        call edge_nodes(m, ms%elem(j), ms%edge(j), a, b)
        len = norm2(m%x(:, b) - m%x(:, a))
        f = 0.5_dp * len * m%sections(m%elem_section(ms%elem(j)))%thickness
        r%master_area(pos(a)) = r%master_area(pos(a)) + f
        r%master_area(pos(b)) = r%master_area(pos(b)) + f
      end do
      do j = 1, size(r%slave_cfe)
        associate(c => cs%c(r%slave_cfe(j)))
          call edge_nodes(m, c%elem, c%edge, a, b)
          ! compressive force counted positive
          r%master_force(pos(a)) = r%master_force(pos(a)) - (1.0_dp - c%t) * c%force
          r%master_force(pos(b)) = r%master_force(pos(b)) - c%t * c%force
          r%total = r%total - c%force
          r%resultant = r%resultant + c%force * c%normal
          if (c%closed) then
            r%nclosed = r%nclosed + 1
            r%max_pen = max(r%max_pen, -c%gap)
          end if
        end associate
      end do
    end associate
  end subroutine pass_results

  subroutine write_increment(lst, m, istep, inc, t, ttot, iters, u, rf, cs, set_sums, set_ids, &
                             nip, sig_ip, eps_ip, sig_node)
    type(listing_t), intent(in) :: lst
    type(model_t), intent(in) :: m
    integer, intent(in) :: istep, inc, iters
    real(dp), intent(in) :: t, ttot
    real(dp), intent(in) :: u(:, :), rf(:, :)
    type(contact_set_t), intent(in) :: cs
    real(dp), intent(in) :: set_sums(:, :)
    integer, intent(in) :: set_ids(:)
    integer, intent(in) :: nip(:)                 ! stresses: see stress_recovery
    real(dp), intent(in) :: sig_ip(:, :, :), eps_ip(:, :, :), sig_node(:, :)
    integer :: ir, k, un, e, ip, nsel
    integer, allocatable :: sel(:)
    type(contact_results_t) :: cr
    un = lst%unit
    write(un, '(a)') ''
    write(un, '(a,i0,a,i0,a,i0,a)') '=== INCREMENT step=', istep, ' increment=', inc, &
      ' time=' // rtoa(t, 9) // ' total_time=' // rtoa(ttot, 9) // ' iterations=', iters, ' ==='
    associate(reqs => m%steps(istep)%requests)
      do ir = 1, size(reqs)
        if (reqs(ir)%to_file) cycle
        if (reqs(ir)%nodal) then
          if (reqs(ir)%set > 0) then
            sel = m%nsets(reqs(ir)%set)%items
          else
            sel = [(k, k = 1, m%nn)]
          end if
          nsel = size(sel)
          if (reqs(ir)%u) then
            call block_head('NODE U', reqs(ir)%set, .true., 'node U1 U2')
            do k = 1, nsel
              write(un, rowfmt(lst, 'i10', 2)) m%node_id(sel(k)), u(:, sel(k))
            end do
          end if
          if (reqs(ir)%rf) then
            call block_head('NODE RF', reqs(ir)%set, .true., 'node RF1 RF2')
            do k = 1, nsel
              write(un, rowfmt(lst, 'i10', 2)) m%node_id(sel(k)), rf(:, sel(k))
            end do
          end if
          if (reqs(ir)%s) then
            call block_head('NODE S', reqs(ir)%set, .true., 'node S11 S22 S33 S12 MISES')
            do k = 1, nsel
              write(un, rowfmt(lst, 'i10', 5)) m%node_id(sel(k)), sig_node(:, sel(k)), von_mises(sig_node(:, sel(k)))
            end do
          end if
        else
          if (reqs(ir)%set > 0) then
            sel = m%elsets(reqs(ir)%set)%items
          else
            sel = [(k, k = 1, m%ne)]
          end if
          if (reqs(ir)%s) then
            call block_head('ELEMENT S', reqs(ir)%set, .false., 'element ip S11 S22 S33 S12 MISES')
            do k = 1, size(sel)
              e = sel(k)
              do ip = 1, nip(e)
                write(un, rowfmt(lst, 'i10,i4', 5)) m%elem_id(e), ip, sig_ip(:, ip, e), von_mises(sig_ip(:, ip, e))
              end do
            end do
          end if
          if (reqs(ir)%e) then
            call block_head('ELEMENT E', reqs(ir)%set, .false., 'element ip E11 E22 E12')
            do k = 1, size(sel)
              e = sel(k)
              do ip = 1, nip(e)
                write(un, rowfmt(lst, 'i10,i4', 3)) m%elem_id(e), ip, eps_ip(:, ip, e)
              end do
            end do
          end if
        end if
      end do
    end associate
    if (size(set_ids) > 0) then
      write(un, '(a)') '--- REACTIONS (sum over each prescribed node set)'
      write(un, '(a)') 'set RF1 RF2'
      do k = 1, size(set_ids)
        write(un, rowfmt(lst, 'a', 2)) trim(m%nsets(set_ids(k))%name), set_sums(:, k)
      end do
    end if
    do ip = 1, size(m%pairs)
      ! the second pass of a SYMMETRIC pair is reported with the first
      if (m%pairs(ip)%twin > 0 .and. m%pairs(ip)%twin < ip) cycle
      call contact_results(m, cs, ip, cr)
      call write_contact(ip, cr)
    end do
    write(un, '(a)') '=== END INCREMENT'
    flush(un)
    if (lst%has_csv) flush(lst%csv)

  contains

    subroutine block_head(name, set, nodal, cols)
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
      write(un, '(a)') '--- ' // name // ' set=' // sname
      write(un, '(a)') cols
    end subroutine block_head

    subroutine write_contact(ipair, r)
      integer, intent(in) :: ipair
      type(contact_results_t), intent(in) :: r
      integer :: j, nd
      real(dp) :: xs(2), p
      character(len=6) :: st
      write(un, '(a,i0,a)') '--- CONTACT SLAVE pair=', ipair, ' surface=' // &
        trim(m%surfaces(m%pairs(ipair)%slave_surface)%name)
      write(un, '(a)') 'node x y gap state force area pressure'
      do j = 1, size(r%slave_cfe)
        associate(c => cs%c(r%slave_cfe(j)))
          xs = m%x(:, c%slave) + u(:, c%slave)
          st = 'OPEN'
          if (c%closed) st = 'CLOSED'
          write(un, '(i10,3' // efmt(lst) // ',1x,a6,3' // efmt(lst) // ')') m%node_id(c%slave), xs, c%gap, st, &
            r%slave_force(j), c%area, r%slave_force(j) / c%area
          if (lst%has_csv) write(lst%csv, '(i0,",",i0,",",es15.8,",",i0,",slave,",i0,",",es15.8,",",es15.8,",",&
            &es15.8,",",a,",",es15.8,",",es15.8)') istep, inc, ttot, ipair, m%node_id(c%slave), xs, c%gap, &
            trim(st), r%slave_force(j), r%slave_force(j) / c%area
        end associate
      end do
      write(un, '(a,i0,a)') '--- CONTACT MASTER pair=', ipair, ' surface=' // &
        trim(m%surfaces(m%pairs(ipair)%master_surface)%name)
      write(un, '(a)') 'node x y force area pressure'
      do j = 1, size(r%master_node)
        nd = r%master_node(j)
        xs = m%x(:, nd) + u(:, nd)
        p = 0.0_dp
        if (r%master_area(j) > 0.0_dp) p = r%master_force(j) / r%master_area(j)
        write(un, rowfmt(lst, 'i10', 5)) m%node_id(nd), xs, r%master_force(j), r%master_area(j), p
        if (lst%has_csv) write(lst%csv, '(i0,",",i0,",",es15.8,",",i0,",master,",i0,",",es15.8,",",es15.8,&
          &",0,-,",es15.8,",",es15.8)') istep, inc, ttot, ipair, m%node_id(nd), xs, r%master_force(j), p
      end do
      write(un, '(a,i0)') '--- CONTACT SUMMARY pair=', ipair
      write(un, '(a)') 'closed total_force resultant_x resultant_y max_penetration'
      write(un, rowfmt(lst, 'i10', 4)) r%nclosed, r%total, r%resultant, r%max_pen
    end subroutine write_contact
  end subroutine write_increment
end module listing
