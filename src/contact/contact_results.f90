!> Contact results of an increment, computed once and read by every
!> writer: per reported pair the slave rows (one per CFE: coupling point,
!> gap, status, normal force, area, pressure; node 0 for a Gauss point of
!> a slave face; with the multiplier on the master mesh one per slave
!> node, the multiplier field there: field_rows), the master rows (the CFE forces taken to the master edge
!> nodes with the weights N_i(X_C), their consistent areas, pressures) and
!> the pair's totals; and the nodal contact pressure field of the whole
!> model (slave nodes: their CFE's, or for Gauss points of slave faces the
!> nodal forces over consistent areas; master nodes).
!>
!> Friction adds the tangential side of the same quantities: per slave
!> row the shear force (the master's tangential force on the point along
!> the master edge's tangent t = (-n_y, n_x), that is -tforce of the CFE),
!> the accumulated and the increment's slip and the stick/slip state; per
!> master row the shear forces taken to the nodes with the same weights
!> N_i(X_C) (the same sign convention: along t, as the slave sees it, as a
!> pressure is compressive on both sides); the tangential total; and the
!> nodal shear traction field beside the pressure field, made the same
!> way. A frictionless CFE carries exactly zero tangential force, so its
!> shear columns are zeros and nothing else it reports changes.
!>
!> Wear (a model with *WEAR, contact_wear): per slave row the worn depth
!> of the slave surface at the point and of the master surface at its
!> projection, and the worn slave surface point (the point moved by its
!> depth along the master normal, into the slave body); per master row
!> the node's worn depth and worn position (moved into the master body).
module contact_results
  use kinds, only: dp
  use model
  use contact, only: contact_set_t, cfe_t, coupling_node
  use contact_geometry, only: edge_t, get_edge, edge_weights, surface_areas
  implicit none
  private
  public :: pair_results_t, contact_results_t, compute_contact_results, model_has_friction, slave_state, &
            model_has_wear, contact_total_force

  type :: pair_results_t
    integer :: pair = 0
    ! slave rows
    integer, allocatable :: slave_node(:)        ! coupling node (0 if not a node)
    real(dp), allocatable :: slave_x(:, :)       ! current coupling point (2, n)
    real(dp), allocatable :: slave_gap(:)
    logical, allocatable :: slave_closed(:)
    real(dp), allocatable :: slave_force(:)      ! compressive positive
    real(dp), allocatable :: slave_area(:)
    ! friction: shear force along t (the master's on the point), slip
    ! accumulated (sum of |slip| per increment) and of this increment
    ! (signed along t: the slave point's motion relative to the master)
    logical :: frictional = .false.              ! the pair has a friction coefficient
    logical, allocatable :: slave_sliding(:)
    real(dp), allocatable :: slave_shear(:), slave_slip(:), slave_slip_inc(:)
    ! the pressure and the shear traction at the row's point: force over
    ! area, or with the multiplier on the master mesh the field at the
    ! slave node (field_rows; the row's force is then the node's
    ! consistent force, which sums to the total)
    real(dp), allocatable :: slave_pressure(:), slave_traction(:)
    ! heat through the contact (a coupled run with *GAP CONDUCTANCE):
    ! the heat flux per unit area from the slave side to the master at
    ! each row's point (allocated only then; filled by the displacement
    ! field's report, contact_heat)
    real(dp), allocatable :: slave_heat_flux(:)
    ! master rows
    integer, allocatable :: master_node(:)
    real(dp), allocatable :: master_force(:), master_area(:)
    real(dp), allocatable :: master_shear(:)     ! N_i(X_C) times the slave points' shear forces
    ! wear (wear_rows; allocated in a model with *WEAR): slave rows' worn
    ! depths (slave surface, master surface at the projection) and worn
    ! slave surface points; master rows' worn depths and positions
    real(dp), allocatable :: slave_wear(:, :), slave_worn(:, :), master_wear(:), master_worn(:, :)
    ! totals: normal-force sum; resultant: the sum of the CFEs' internal
    ! forces at their slave points, force n + tforce t (the contact force
    ! on the master side, the reaction the slave body's supports give);
    ! shear_total: the sum of the slave points' shear forces
    real(dp) :: total = 0.0_dp, resultant(2) = 0.0_dp, max_pen = 0.0_dp, shear_total = 0.0_dp
    integer :: nclosed = 0
  end type pair_results_t

  type :: contact_results_t
    type(pair_results_t), allocatable :: pairs(:)   ! one per reported pair
    real(dp) :: total_force = 0.0_dp                ! sum over the reported pairs
    real(dp), allocatable :: pressure(:)            ! (nn) nodal contact pressure
    real(dp), allocatable :: shear(:)               ! (nn) nodal contact shear traction
    logical, allocatable :: has_pressure(:)         ! nodes that carry both
    logical :: frictional = .false.                 ! some pair of the model has friction
  end type contact_results_t

  !> Per-node sums of the master-mesh multipliers' field (sum_fields), by
  !> node number.
  type :: field_sums_t
    real(dp), allocatable :: p(:), tau(:), g(:), wsum(:), slip(:), slip_inc(:), fn(:), ft(:), gs(:), ws(:)
    logical, allocatable :: closed(:), sliding(:)
  end type field_sums_t

contains

  !> Purpose: does any contact pair of the model have friction? (Its
  !> results then carry the shear columns and fields.)
  pure logical function model_has_friction(m)
    type(model_t), intent(in) :: m
    model_has_friction = .false.
    if (allocated(m%pairs)) model_has_friction = any(m%pairs%mu > 0.0_dp)
  end function model_has_friction

  !> Purpose: does any contact pair of the model wear (*WEAR)? (Its
  !> results then carry the wear columns.)
  pure logical function model_has_wear(m)
    type(model_t), intent(in) :: m
    model_has_wear = .false.
    if (allocated(m%pairs)) model_has_wear = any(m%pairs%wear)
  end function model_has_wear

  !> Purpose: the state word of slave row j: OPEN, or for a closed point
  !> CLOSED (frictionless pair), STICK or SLIP (frictional pair).
  pure function slave_state(r, j) result(st)
    type(pair_results_t), intent(in) :: r
    integer, intent(in) :: j
    character(len=6) :: st
    if (.not. r%slave_closed(j)) then
      st = 'OPEN'
    else if (.not. r%frictional) then
      st = 'CLOSED'
    else if (r%slave_sliding(j)) then
      st = 'SLIP'
    else
      st = 'STICK'
    end if
  end function slave_state

  !> Purpose: the contact results at displacements u from the CFE gaps and
  !> forces of the last evaluation. The second pass of a SYMMETRIC pair is
  !> reported with its first one.
  subroutine compute_contact_results(m, cs, u, r)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    real(dp), intent(in) :: u(:, :)
    type(contact_results_t), intent(out) :: r
    integer :: ip, np, j
    real(dp), allocatable :: twin_force(:), twin_shear(:)
    np = 0
    do ip = 1, size(m%pairs)
      if (.not. (m%pairs(ip)%twin > 0 .and. m%pairs(ip)%twin < ip)) np = np + 1
    end do
    allocate(r%pairs(np), r%pressure(m%nn), r%shear(m%nn), r%has_pressure(m%nn))
    r%pressure = 0.0_dp
    r%shear = 0.0_dp
    r%has_pressure = .false.
    r%frictional = model_has_friction(m)
    np = 0
    do ip = 1, size(m%pairs)
      if (m%pairs(ip)%twin > 0 .and. m%pairs(ip)%twin < ip) cycle
      np = np + 1
      call pair_results(m, cs, u, ip, r%pairs(np), twin_force, twin_shear)
      associate(pr => r%pairs(np))
        r%total_force = r%total_force + pr%total
        do j = 1, size(pr%slave_node)
          if (pr%slave_node(j) == 0) cycle
          r%pressure(pr%slave_node(j)) = pr%slave_pressure(j)
          r%shear(pr%slave_node(j)) = pr%slave_traction(j)
          r%has_pressure(pr%slave_node(j)) = .true.
        end do
        do j = 1, size(pr%master_node)
          if (pr%master_area(j) > 0.0_dp) then
            r%pressure(pr%master_node(j)) = pr%master_force(j) / pr%master_area(j)
            r%shear(pr%master_node(j)) = pr%master_shear(j) / pr%master_area(j)
          end if
          r%has_pressure(pr%master_node(j)) = .true.
        end do
      end associate
      call face_point_pressures(m, cs, ip, twin_force, twin_shear, r%pressure, r%shear, r%has_pressure)
    end do
  end subroutine compute_contact_results

  !> Purpose: the total_force compute_contact_results gives, without its
  !> rows and nodal fields: the same sums in the same order (each
  !> reported pair's closed CFEs' forces, a twin pass's added to its
  !> pair's, the pairs summed in turn). For an increment whose contact
  !> results are not written (the progress line prints the total): a
  !> fretting history's rows at every increment were a twentieth of it.
  !> Arguments: m the model; cs the contact set.
  real(dp) function contact_total_force(m, cs) result(total)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    integer :: ip, it
    real(dp) :: pair_total
    total = 0.0_dp
    do ip = 1, size(m%pairs)
      if (m%pairs(ip)%twin > 0 .and. m%pairs(ip)%twin < ip) cycle
      pair_total = pass_total(cs, ip)
      it = m%pairs(ip)%twin
      if (it /= 0) pair_total = pair_total + pass_total(cs, it)
      total = total + pair_total
    end do
  end function contact_total_force

  !> Purpose: pass_results' total of pair ip: minus its closed CFEs'
  !> forces, summed in the set's order (compressive positive).
  pure real(dp) function pass_total(cs, ip) result(t)
    type(contact_set_t), intent(in) :: cs
    integer, intent(in) :: ip
    integer :: k
    t = 0.0_dp
    do k = 1, cs%n
      if (cs%c(k)%pair == ip .and. cs%c(k)%closed) t = t - cs%c(k)%force
    end do
  end function pass_total

  !> Nodal pressures and shear tractions of the slave nodes of pair ip
  !> whose CFEs are Gauss points of 3-node faces: the normal and the
  !> tangential force the points put on each node (weights N_j) over the
  !> node's consistent area. Unlike the point pressures this does not see
  !> the points' alternating mode (forces that cancel at the nodes, see
  !> contact). twin_force(nn), twin_shear(nn): the normal and shear forces
  !> the second pass of a SYMMETRIC pair puts on these nodes as its master.
  subroutine face_point_pressures(m, cs, ip, twin_force, twin_shear, pressure, shear, has_pressure)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    integer, intent(in) :: ip
    real(dp), intent(in) :: twin_force(:), twin_shear(:)
    real(dp), intent(inout) :: pressure(:), shear(:)
    logical, intent(inout) :: has_pressure(:)
    real(dp), allocatable :: f(:), fs(:), a(:)
    integer :: j, q
    if (.not. any(cs%c(1:cs%n)%pair == ip .and. cs%c(1:cs%n)%ns > 1)) return
    f = twin_force
    fs = twin_shear
    a = surface_areas(m, m%surfaces(m%pairs(ip)%slave_surface))
    do j = 1, cs%n
      associate(c => cs%c(j))
        ! open points carry no contact pressure (see pass_results)
        if (c%pair /= ip .or. c%ns == 1 .or. .not. c%closed) cycle
        do q = 1, c%ns
          f(c%snode(q)) = f(c%snode(q)) - c%sw(q) * c%force
          fs(c%snode(q)) = fs(c%snode(q)) - c%sw(q) * c%tforce
        end do
      end associate
    end do
    do j = 1, m%nn
      if (a(j) > 0.0_dp) then
        pressure(j) = f(j) / a(j)
        shear(j) = fs(j) / a(j)
        has_pressure(j) = .true.
      end if
    end do
  end subroutine face_point_pressures

  !> Purpose: results of pair ip. For a SYMMETRIC pair each point's force
  !> is what both passes put there: its own CFE force and what it takes
  !> as master of the other pass (at a slave node that pass's master
  !> force there; at a Gauss point of a 3-node face that pass's master
  !> pressure, interpolated with the face's weights, times the point's
  !> area); each master node gets the other pass's CFE forces with their
  !> slave weights. twin_force(nn) and twin_shear(nn) return the other
  !> pass's master forces and shear forces at the nodes (zero without
  !> one). The shear adds as the normal force does: the other pass's
  !> tangent is opposite to this one's (its master normal is this one's
  !> reversed), and a shear row is the force on the other body, so the two
  !> reversals cancel. Its resultant, a force on this pass's slave side, is
  !> subtracted.
  subroutine pair_results(m, cs, u, ip, r, twin_force, twin_shear)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    real(dp), intent(in) :: u(:, :)
    integer, intent(in) :: ip
    type(pair_results_t), intent(out) :: r
    real(dp), allocatable, intent(out) :: twin_force(:), twin_shear(:)
    type(pair_results_t) :: rt
    real(dp), allocatable :: twin_p(:), twin_tau(:)
    integer, allocatable :: pos(:), sel(:)
    integer :: j, k, q, it
    allocate(twin_force(m%nn), twin_shear(m%nn), twin_p(m%nn), twin_tau(m%nn), pos(m%nn))
    twin_force = 0.0_dp
    twin_shear = 0.0_dp
    twin_p = 0.0_dp
    twin_tau = 0.0_dp
    call pass_results(m, cs, u, ip, r)
    it = m%pairs(ip)%twin
    if (it == 0) then
      call row_tractions(r)
      return
    end if
    call pass_results(m, cs, u, it, rt)
    twin_force(rt%master_node) = rt%master_force
    twin_shear(rt%master_node) = rt%master_shear
    where (rt%master_area > 0.0_dp) twin_p(rt%master_node) = rt%master_force / rt%master_area
    where (rt%master_area > 0.0_dp) twin_tau(rt%master_node) = rt%master_shear / rt%master_area
    sel = pack([(k, k = 1, cs%n)], cs%c(1:cs%n)%pair == ip)
    do j = 1, size(sel)
      associate(c => cs%c(sel(j)))
        if (c%ns == 1) then
          r%slave_force(j) = r%slave_force(j) + twin_force(c%snode(1))
          if (r%frictional) r%slave_shear(j) = r%slave_shear(j) + twin_shear(c%snode(1))
        else
          r%slave_force(j) = r%slave_force(j) + c%area * sum(c%sw(1:c%ns) * twin_p(c%snode(1:c%ns)))
          if (r%frictional) r%slave_shear(j) = r%slave_shear(j) + &
                                               c%area * sum(c%sw(1:c%ns) * twin_tau(c%snode(1:c%ns)))
        end if
      end associate
    end do
    pos = 0
    pos(r%master_node) = [(k, k = 1, size(r%master_node))]
    sel = pack([(k, k = 1, cs%n)], cs%c(1:cs%n)%pair == it)
    do j = 1, size(sel)
      associate(c => cs%c(sel(j)))
        do q = 1, c%ns
          if (pos(c%snode(q)) > 0) r%master_force(pos(c%snode(q))) = r%master_force(pos(c%snode(q))) - &
                                                                    c%sw(q) * c%force
          ! (an open CFE's tangential force is zero: no closed-test needed)
          if (pos(c%snode(q)) > 0 .and. r%frictional) &
            r%master_shear(pos(c%snode(q))) = r%master_shear(pos(c%snode(q))) - c%sw(q) * c%tforce
        end do
      end associate
    end do
    r%total = r%total + rt%total
    r%shear_total = r%shear_total + rt%shear_total
    r%resultant = r%resultant - rt%resultant
    r%nclosed = r%nclosed + rt%nclosed
    r%max_pen = max(r%max_pen, rt%max_pen)
    call row_tractions(r)
  end subroutine pair_results

  !> Purpose: the slave rows' pressure and shear traction, force over
  !> area, where field_rows has not given them (the field's values).
  subroutine row_tractions(r)
    type(pair_results_t), intent(inout) :: r
    if (allocated(r%slave_pressure)) return
    r%slave_pressure = r%slave_force / r%slave_area
    r%slave_traction = r%slave_shear / r%slave_area
  end subroutine row_tractions

  !> Purpose: one pass: slave rows and the master-side forces its CFEs
  !> produce (each CFE force, normal and tangential, goes to the master
  !> edge nodes with the weights N_i(X_C)). Only closed CFEs report a
  !> force.
  subroutine pass_results(m, cs, u, ip, r)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    real(dp), intent(in) :: u(:, :)
    integer, intent(in) :: ip
    type(pair_results_t), intent(out) :: r
    integer :: k, j, ns, n, q, nw
    integer, allocatable :: pos(:), sel(:), wn(:)
    real(dp) :: shear
    real(dp), allocatable :: ww(:)
    sel = pack([(k, k = 1, cs%n)], cs%c(1:cs%n)%pair == ip)
    n = size(sel)
    call start_pass(m, ip, n, r, pos)
    do j = 1, n
      associate(c => cs%c(sel(j)))
        ns = c%ns
        r%slave_node(j) = coupling_node(c)
        r%slave_x(:, j) = matmul(m%x(:, c%snode(1:ns)) + u(:, c%snode(1:ns)), c%sw(1:ns))
        r%slave_gap(j) = c%gap
        r%slave_closed(j) = c%closed
        r%slave_area(j) = c%area
        ! the slip is history: an open point keeps what it slid before
        if (r%frictional) then
          r%slave_slip(j) = c%slip_total
          r%slave_slip_inc(j) = c%slip_inc
        end if
        ! An open CFE still carries its open penalty times the relative
        ! motion (1e-12 of the closed penalty, more while stabilised): a
        ! force that keeps the equations regular, not contact pressure. Its
        ! row, its master shares and the totals report none.
        if (.not. c%closed) then
          r%slave_force(j) = 0.0_dp
          cycle
        end if
        ! compressive force counted positive
        r%slave_force(j) = -c%force
        ! the master's tangential force on the point along t
        shear = -c%tforce
        call master_shares(m, c, wn, ww)
        nw = size(wn)
        do q = 1, nw
          r%master_force(pos(wn(q))) = r%master_force(pos(wn(q))) - ww(q) * c%force
        end do
        r%total = r%total - c%force
        r%resultant = r%resultant + c%force * c%normal
        ! Only for a frictional pair: adding a zero tangential force would
        ! still turn a resultant of -0 into +0 and change frictionless output.
        if (r%frictional) then
          r%slave_sliding(j) = c%sliding
          r%slave_shear(j) = shear
          do q = 1, nw
            r%master_shear(pos(wn(q))) = r%master_shear(pos(wn(q))) + ww(q) * shear
          end do
          r%shear_total = r%shear_total + shear
          r%resultant = r%resultant + c%tforce * [-c%normal(2), c%normal(1)]
        end if
        r%nclosed = r%nclosed + 1
        r%max_pen = max(r%max_pen, -c%gap)
      end associate
    end do
    if (any(cs%c(sel)%ns == 0)) call field_rows(m, cs, u, ip, sel, r)
    if (model_has_wear(m)) call wear_rows(m, cs, u, ip, sel, r)
  end subroutine pass_results

  !> Purpose: the wear columns of pair ip's rows (CFEs sel; zero for a
  !> pair without wear): a slave row of a CFE its worn depths (the
  !> slave's at the point, the master's at X_C) and the worn slave point
  !> x + h_slave n; a row of the master-mesh multiplier (a slave node) the
  !> node's depth and the master depths of the multipliers reaching it,
  !> interpolated with their hat functions as the pressure (field_rows),
  !> along their normals likewise; a master row its node's depth and
  !> worn position x - h_master n, n the CFEs' normals shared as their
  !> forces are (master_shares).
  subroutine wear_rows(m, cs, u, ip, sel, r)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    real(dp), intent(in) :: u(:, :)
    integer, intent(in) :: ip, sel(:)
    type(pair_results_t), intent(inout) :: r
    real(dp), allocatable :: nrm(:, :), nrs(:, :), hm(:), ws(:), ww(:)
    integer, allocatable :: wn(:)
    integer :: j, k, q, ns, nm
    ns = size(r%slave_node)
    nm = size(r%master_node)
    allocate(r%slave_wear(2, ns), r%master_wear(nm), nrm(2, m%nn), nrs(2, m%nn), hm(m%nn), ws(m%nn))
    r%slave_wear = 0.0_dp
    r%master_wear = 0.0_dp
    r%slave_worn = r%slave_x
    r%master_worn = m%x(:, r%master_node) + u(:, r%master_node)
    if (.not. m%pairs(ip)%wear) return
    nrm = 0.0_dp
    nrs = 0.0_dp
    hm = 0.0_dp
    ws = 0.0_dp
    associate(depth => cs%wear%pairs(ip)%depth)
      do k = 1, size(sel)
        associate(c => cs%c(sel(k)))
          if (c%ns > 0) then
            r%slave_wear(:, k) = c%wear
            r%slave_worn(:, k) = r%slave_x(:, k) + c%wear(1) * c%normal
          else
            ! a master node's multiplier: its depth and normal to the slave
            ! nodes under its hat
            do q = 1, c%nsl
              hm(c%mnode(q)) = hm(c%mnode(q)) + c%psi(q) * depth(2, c%lnode)
              ws(c%mnode(q)) = ws(c%mnode(q)) + c%psi(q)
              nrs(:, c%mnode(q)) = nrs(:, c%mnode(q)) + c%psi(q) * c%normal
            end do
          end if
          call master_shares(m, c, wn, ww)
          do q = 1, size(wn)
            nrm(:, wn(q)) = nrm(:, wn(q)) + ww(q) * c%normal
          end do
        end associate
      end do
      if (any(cs%c(sel)%ns == 0)) then
        do j = 1, ns
          r%slave_wear(1, j) = depth(1, r%slave_node(j))
          if (ws(r%slave_node(j)) > 0.0_dp) r%slave_wear(2, j) = hm(r%slave_node(j)) / ws(r%slave_node(j))
          if (norm2(nrs(:, r%slave_node(j))) > 0.0_dp) r%slave_worn(:, j) = r%slave_x(:, j) + &
            r%slave_wear(1, j) * nrs(:, r%slave_node(j)) / norm2(nrs(:, r%slave_node(j)))
        end do
      end if
      do j = 1, nm
        r%master_wear(j) = depth(2, r%master_node(j))
        if (norm2(nrm(:, r%master_node(j))) > 0.0_dp) r%master_worn(:, j) = r%master_worn(:, j) - &
          r%master_wear(j) * nrm(:, r%master_node(j)) / norm2(nrm(:, r%master_node(j)))
      end do
    end associate
  end subroutine wear_rows

  !> Purpose: the results of pair ip before its CFEs are summed: n slave
  !> rows and the master rows (the master surface's nodes, their
  !> consistent areas, the integral of N_i over the master faces), zero;
  !> pos(node) the master row of a node (0 for none).
  subroutine start_pass(m, ip, n, r, pos)
    type(model_t), intent(in) :: m
    integer, intent(in) :: ip, n
    type(pair_results_t), intent(out) :: r
    integer, allocatable, intent(out) :: pos(:)
    real(dp), allocatable :: area(:)
    integer :: k, nm
    r%pair = ip
    r%frictional = m%pairs(ip)%mu > 0.0_dp
    allocate(r%slave_node(n), r%slave_x(2, n), r%slave_gap(n), r%slave_closed(n), r%slave_force(n), &
             r%slave_area(n), r%slave_sliding(n), r%slave_shear(n), r%slave_slip(n), r%slave_slip_inc(n))
    r%slave_sliding = .false.
    r%slave_shear = 0.0_dp
    r%slave_slip = 0.0_dp
    r%slave_slip_inc = 0.0_dp
    associate(ms => m%surfaces(m%pairs(ip)%master_surface))
      r%master_node = ms%nodes
      nm = size(ms%nodes)
      allocate(r%master_force(nm), r%master_area(nm), r%master_shear(nm), pos(m%nn))
      pos = 0
      do k = 1, nm
        pos(ms%nodes(k)) = k
      end do
      r%master_force = 0.0_dp
      r%master_shear = 0.0_dp
      area = surface_areas(m, ms)
      r%master_area = area(ms%nodes)
    end associate
  end subroutine start_pass

  !> Purpose: the master nodes wn of CFE c and the shares ww of its force
  !> each receives: segment-to-segment, the master nodes' mortar weights
  !> (after the slave nodes, with the multiplier on the master mesh);
  !> node-to-segment, the master edge's shape functions at X_C (t).
  subroutine master_shares(m, c, wn, ww)
    type(model_t), intent(in) :: m
    type(cfe_t), intent(in) :: c
    integer, allocatable, intent(out) :: wn(:)
    real(dp), allocatable, intent(out) :: ww(:)
    type(edge_t) :: ed
    real(dp) :: w(3)
    if (c%nm > 0) then
      wn = c%mnode(c%nsl + 1:c%nm)
      ww = c%mw(c%nsl + 1:c%nm)
      return
    end if
    ed = get_edge(m, m%x, c%elem, c%edge)
    if (ed%nn == 2) then
      w(1:2) = [1.0_dp - c%t, c%t]
    else
      w = edge_weights(ed, c%t)
    end if
    wn = ed%node(1:ed%nn)
    ww = w(1:ed%nn)
  end subroutine master_shares

  !> Purpose: the slave rows of a pass whose multiplier lives on the
  !> master mesh (contact_master_multipliers: CFEs sel, one per master
  !> node): one row per slave node the field reaches, its pressure the
  !> field sum_m psi_m lambda_m at the node (lambda_m the CFE's pressure,
  !> closed CFEs only), its area the node's consistent area int N_j da,
  !> its force the force the couplings put on it, sum_m lambda_m S_mj =
  !> int lambda_h N_j da (so the rows sum to the pair's total), its gap
  !> the weighted gaps interpolated as the pressure; closed (and sliding)
  !> where a closed (sliding) CFE reaches it; the shear traction and the
  !> slips interpolated as the pressure, the shear force as the force.
  subroutine field_rows(m, cs, u, ip, sel, r)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    real(dp), intent(in) :: u(:, :)
    integer, intent(in) :: ip, sel(:)
    type(pair_results_t), intent(inout) :: r
    type(field_sums_t) :: f
    real(dp), allocatable :: area(:)
    integer, allocatable :: rows(:)
    call sum_fields(m, cs, sel, f)
    associate(sl => m%surfaces(m%pairs(ip)%slave_surface))
      area = surface_areas(m, sl)
      rows = pack(sl%nodes, f%wsum(sl%nodes) > 0.0_dp .or. f%fn(sl%nodes) /= 0.0_dp)
    end associate
    deallocate(r%slave_node, r%slave_x, r%slave_gap, r%slave_closed, r%slave_force, r%slave_area, r%slave_sliding, &
               r%slave_shear, r%slave_slip, r%slave_slip_inc)
    ! a row with no hat at its node: the S-weighted gap, no slip
    where (.not. f%wsum > 0.0_dp)
      f%g = f%gs
      f%wsum = f%ws
      f%slip = 0.0_dp
      f%slip_inc = 0.0_dp
      f%closed = f%fn /= 0.0_dp
    end where
    r%slave_node = rows
    r%slave_x = m%x(:, rows) + u(:, rows)
    r%slave_gap = f%g(rows) / f%wsum(rows)
    r%slave_closed = f%closed(rows)
    r%slave_area = area(rows)
    r%slave_force = f%fn(rows)
    r%slave_pressure = f%p(rows)
    r%slave_sliding = f%sliding(rows)
    r%slave_shear = 0.0_dp * area(rows)
    r%slave_traction = 0.0_dp * area(rows)
    r%slave_slip = 0.0_dp * area(rows)
    r%slave_slip_inc = 0.0_dp * area(rows)
    if (r%frictional) then
      r%slave_shear = f%ft(rows)
      r%slave_traction = f%tau(rows)
      r%slave_slip = f%slip(rows) / f%wsum(rows)
      r%slave_slip_inc = f%slip_inc(rows) / f%wsum(rows)
    end if
  end subroutine field_rows

  !> Purpose: the per-node sums field_rows makes its rows of, over the
  !> CFEs sel (one per master node) and the slave nodes j of each: the
  !> forces the couplings put on j (fn, ft) and the S-weighted gap (gs,
  !> ws); where psi_m > 0 at j, the field's pressure and traction (p,
  !> tau), the psi-weighted gap and slips (g, slip, slip_inc over wsum),
  !> and whether a closed (sliding) multiplier reaches it.
  subroutine sum_fields(m, cs, sel, f)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    integer, intent(in) :: sel(:)
    type(field_sums_t), intent(out) :: f
    real(dp) :: lam, ta, ps
    integer :: k, q, j
    allocate(f%p(m%nn), f%tau(m%nn), f%g(m%nn), f%wsum(m%nn), f%slip(m%nn), f%slip_inc(m%nn), f%closed(m%nn), &
             f%sliding(m%nn), f%fn(m%nn), f%ft(m%nn), f%gs(m%nn), f%ws(m%nn))
    f%fn = 0.0_dp
    f%ft = 0.0_dp
    f%gs = 0.0_dp
    f%ws = 0.0_dp
    f%p = 0.0_dp
    f%tau = 0.0_dp
    f%g = 0.0_dp
    f%wsum = 0.0_dp
    f%slip = 0.0_dp
    f%slip_inc = 0.0_dp
    f%closed = .false.
    f%sliding = .false.
    do k = 1, size(sel)
      associate(c => cs%c(sel(k)))
        lam = 0.0_dp
        ta = 0.0_dp
        if (c%closed) then
          lam = -c%force / c%area
          ta = -c%tforce / c%area
        end if
        do q = 1, c%nsl
          j = c%mnode(q)
          ! the slave weights S_mj / D_m are -mw (the CFE's slave side);
          ! an open CFE's force is not contact pressure (pass_results). A
          ! node may have S_mj > 0 and psi_m = 0 at its own projection
          ! (past the master's end): its row then has the force only.
          if (c%closed) then
            f%fn(j) = f%fn(j) + c%force * c%mw(q)
            f%ft(j) = f%ft(j) + c%tforce * c%mw(q)
          end if
          f%gs(j) = f%gs(j) - c%mw(q) * c%gap
          f%ws(j) = f%ws(j) - c%mw(q)
          ps = c%psi(q)
          if (ps <= 0.0_dp) cycle
          f%p(j) = f%p(j) + ps * lam
          f%tau(j) = f%tau(j) + ps * ta
          f%g(j) = f%g(j) + ps * c%gap
          f%wsum(j) = f%wsum(j) + ps
          f%slip(j) = f%slip(j) + ps * c%slip_total
          f%slip_inc(j) = f%slip_inc(j) + ps * c%slip_inc
          f%closed(j) = f%closed(j) .or. c%closed
          f%sliding(j) = f%sliding(j) .or. (c%closed .and. c%sliding)
        end do
      end associate
    end do
  end subroutine sum_fields
end module contact_results
