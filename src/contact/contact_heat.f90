!> Heat through the contact (docs/heat.md, "Heat through the contact"):
!> for each coupling element (CFE) of a pair with *GAP CONDUCTANCE or *GAP
!> HEAT GENERATION, the heat flow between its slave point and the master
!> segment, in the same weights the CFE couples the displacements with
!> (the slave side's weights, the master element's shape functions at the
!> coupling point or the mortar weights): the temperature jump at the
!> point is
!>   [[T]] = sum_j w_j T_j    (w_j > 0 on the slave side, < 0 on the master),
!> the heat per unit time from the slave to the master side is
!> h(p) A [[T]] (h the conductance per unit area at the point's contact
!> pressure p, A its area; an open point conducts nothing), which is the
!> symmetric matrix h A w w^T in the temperature equations; frictional
!> heat, eta times the frictional power (mu p A v, v the slip rate), goes
!> in by the fraction f to the slave nodes and 1 - f to the master nodes,
!> each side's share spread in proportion to its weights (normalised by
!> the side's sum, as the CFE spreads its force). The couplings
!> of a pair take part whatever their status, so that the matrix keeps its
!> structure while statuses change. Everything here is of the last
!> evaluation of the contact set (contact_forces): its pressures and the
!> slip of its sliding points since their anchors.
module contact_heat
  use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
  use kinds, only: dp
  use model, only: model_t, gap_heat_t, elem_nodes
  use element_catalogue, only: catalogue, max_nodes
  use shape_functions, only: shape_at
  use contact, only: contact_set_t, cfe_t, cfe_nodes
  implicit none
  private
  public :: contact_heat_t, contact_heat_build, contact_heat_matrix, contact_heat_residual, same_couplings, &
            same_matrices, contact_heat_flux, has_contact_heat

  !> The heat couplings of a contact set: n of them, coupling k of CFE
  !> cfe(k) joining nodes node(xnode(k):xnode(k+1)-1) with the jump
  !> weights w(...); ha(k) its conductance times area (its area in
  !> area(k)); qs(k), qm(k) the frictional heat per unit time into its
  !> slave and master side; its first nslave(k) nodes are the slave side's.
  type :: contact_heat_t
    integer :: n = 0
    integer, allocatable :: cfe(:), xnode(:), node(:), nslave(:)
    real(dp), allocatable :: w(:), ha(:), qs(:), qm(:), area(:)
  end type contact_heat_t

  !> Couplings whose h A and weights differ by at most this fraction of
  !> the largest are the same matrix (same_matrices): far below what the
  !> passes settle to (1e-9), far above round-off.
  real(dp), parameter :: same_tolerance = 1.0e-12_dp

contains

  !> Purpose: does some pair of model m carry heat through its contact?
  pure logical function has_contact_heat(m)
    type(model_t), intent(in) :: m
    has_contact_heat = .false.
    if (size(m%pairs) > 0) has_contact_heat = any(m%pairs%gap_heat > 0)
  end function has_contact_heat

  !> Purpose: the heat couplings of contact set cs at its last evaluation.
  !> Arguments: m the model, cs the contact set, dt the increment's length
  !> (the slip over it is the slip rate times dt), ch the couplings made.
  subroutine contact_heat_build(m, cs, dt, ch)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    real(dp), intent(in) :: dt
    type(contact_heat_t), intent(out) :: ch
    integer, allocatable :: nodes(:)
    real(dp), allocatable :: w(:)
    integer :: j, k, nen, pos
    ch%n = 0
    do j = 1, cs%n
      if (m%pairs(cs%c(j)%pair)%gap_heat > 0) ch%n = ch%n + 1
    end do
    allocate(ch%cfe(ch%n), ch%xnode(ch%n + 1), ch%ha(ch%n), ch%qs(ch%n), ch%qm(ch%n), ch%area(ch%n), &
             ch%nslave(ch%n))
    ch%cfe = pack([(j, j = 1, cs%n)], [(m%pairs(cs%c(j)%pair)%gap_heat > 0, j = 1, cs%n)])
    ! the node lists' lengths first, then the lists
    ch%xnode(1) = 1
    do k = 1, ch%n
      call cfe_nodes(m, cs%c(ch%cfe(k)), nodes, nen)
      ch%xnode(k + 1) = ch%xnode(k) + nen
    end do
    allocate(ch%node(ch%xnode(ch%n + 1) - 1), ch%w(ch%xnode(ch%n + 1) - 1))
    do k = 1, ch%n
      associate(c => cs%c(ch%cfe(k)))
        call jump_weights(m, c, nodes, w, nen)
        pos = ch%xnode(k)
        ch%node(pos:pos + nen - 1) = nodes(1:nen)
        ch%w(pos:pos + nen - 1) = w(1:nen)
        call point_heat(m, c, dt, ch%ha(k), ch%qs(k), ch%qm(k))
        ch%area(k) = c%area
        ! the slave side: its nodes, or with the multiplier on the master
        ! mesh the slave nodes listed first among the master side's
        ch%nslave(k) = c%ns
        if (c%ns == 0) ch%nslave(k) = c%nsl
      end associate
    end do
  end subroutine contact_heat_build

  !> Purpose: the nodes of CFE c (cfe_nodes: slave side first) and the
  !> weights w of the temperature jump [[T]] = sum w_j T_j at its point:
  !> the slave weights, minus the master side's (the mortar weights, or
  !> the master element's shape functions at the coupling point), as the
  !> coupling element forms the relative displacement (cfe_element).
  subroutine jump_weights(m, c, nodes, w, nen)
    type(model_t), intent(in) :: m
    type(cfe_t), intent(in) :: c
    integer, allocatable, intent(inout) :: nodes(:)
    real(dp), allocatable, intent(out) :: w(:)
    integer, intent(out) :: nen
    real(dp) :: n(max_nodes), dn(2, max_nodes)
    call cfe_nodes(m, c, nodes, nen)
    allocate(w(nen))
    w(1:c%ns) = c%sw(1:c%ns)
    if (c%nm > 0) then
      w(c%ns + 1:nen) = -c%mw(1:c%nm)
    else
      call shape_at(catalogue(m%etype(c%elem))%shape, c%xi, n, dn)
      w(c%ns + 1:nen) = -n(1:elem_nodes(m, c%elem))
    end if
  end subroutine jump_weights

  !> Purpose: CFE c's conductance times area ha and frictional heat per
  !> unit time into its slave (qs) and master (qm) side, from its pair's
  !> gap heat entry: a closed point at pressure p = -force / area conducts
  !> h(p) A, an open one nothing; with Abaqus's clearance table every
  !> point conducts h(d) A (clearance_of: d = 0 closed). Sliding, a point
  !> makes eta mu p A v of heat (v the given velocity or the slip since
  !> its anchor over dt), the fraction f to the slave. A pass of a
  !> two-pass pair takes half of each, at the interface's pressure (twice
  !> the pass's own); f is the deck's slave surface's share in both passes.
  subroutine point_heat(m, c, dt, ha, qs, qm)
    type(model_t), intent(in) :: m
    type(cfe_t), intent(in) :: c
    real(dp), intent(in) :: dt
    real(dp), intent(out) :: ha, qs, qm
    real(dp) :: p, power, share, f
    ha = 0.0_dp
    qs = 0.0_dp
    qm = 0.0_dp
    if (c%area <= 0.0_dp) return
    share = merge(0.5_dp, 1.0_dp, m%pairs(c%pair)%twin /= 0)
    associate(g => m%gap_heats(m%pairs(c%pair)%gap_heat))
      if (allocated(g%gc_h) .and. g%clearance) ha = share * clearance_conductance(g, clearance_of(c)) * c%area
      if (.not. c%closed) return
      ! (a pass of a two-pass pair carries half of the interface's pressure)
      p = max(0.0_dp, -c%force / c%area) / share
      if (allocated(g%gc_h) .and. .not. g%clearance) ha = share * conductance_at(g, p) * c%area
      if (.not. g%generation .or. c%mu <= 0.0_dp) return
      power = 0.0_dp
      if (g%velocity > 0.0_dp) then
        power = share * c%mu * p * c%area * g%velocity
      else if (c%sliding .and. c%k_tan > 0.0_dp .and. dt > 0.0_dp) then
        ! the slip of this increment so far: where the anchor would go
        ! (contact_commit's return mapping) less where it is; the pass's
        ! own shear force (its share already)
        power = abs(c%tforce) * abs(c%slide - c%tforce / c%k_tan - c%anchor) / dt
      end if
      ! (the second pass of a two-pass pair has the deck's slave as its
      ! master: the deck's slave still takes f)
      f = g%f
      if (m%pairs(c%pair)%twin /= 0 .and. m%pairs(c%pair)%twin < c%pair) f = 1.0_dp - g%f
      qs = g%eta * f * power
      qm = g%eta * (1.0_dp - f) * power
    end associate
  end subroutine point_heat

  !> Purpose: the clearance of CFE c across the gap: 0 where it is
  !> closed, else its gap along the master normal at the last evaluation
  !> of the contact set (contact_forces). A coupling never evaluated (its
  !> gap and force still 0: a heat transfer step before any mechanical
  !> step of the run, or the first pass of a run's first increment) has
  !> the gap of the initial search, the normal part of its initial
  !> relative position gap0 (the gap at zero displacement, where it is
  !> evaluated as well).
  pure real(dp) function clearance_of(c) result(d)
    type(cfe_t), intent(in) :: c
    d = 0.0_dp
    if (c%closed) return
    d = c%gap
    if (c%gap == 0.0_dp .and. c%force == 0.0_dp) d = dot_product(c%normal, c%gap0)
    d = max(0.0_dp, d)
  end function clearance_of

  !> Purpose: Abaqus's conductance per unit area of gap heat entry g at
  !> clearance d (its table's second column the clearances, increasing):
  !> linear between the table's points, the first value below the first
  !> clearance, zero beyond the last (Abaqus's keyword reference of *GAP
  !> CONDUCTANCE: the conductance "drops to zero immediately after the
  !> last data point").
  pure real(dp) function clearance_conductance(g, d) result(h)
    type(gap_heat_t), intent(in) :: g
    real(dp), intent(in) :: d
    integer :: n
    n = size(g%gc_h)
    h = 0.0_dp
    if (d > g%gc_p(n)) return
    h = conductance_at(g, d)
  end function clearance_conductance

  !> Purpose: the conductance per unit area of gap heat entry g at contact
  !> pressure p (or clearance): linear in p between the table's points,
  !> constant beyond.
  pure real(dp) function conductance_at(g, p) result(h)
    type(gap_heat_t), intent(in) :: g
    real(dp), intent(in) :: p
    integer :: k, n
    n = size(g%gc_h)
    if (ieee_is_nan(p)) then
      ! (a pressure or clearance that is not a number, magnitudes of the
      ! deck that overflow: so is the conductance, and the temperatures
      ! stop the run naming a node, temperature_field)
      h = p
    else if (n == 1 .or. p <= g%gc_p(1)) then
      h = g%gc_h(1)
    else if (p >= g%gc_p(n)) then
      h = g%gc_h(n)
    else
      do k = 2, n
        if (p <= g%gc_p(k)) exit
      end do
      h = g%gc_h(k - 1) + (g%gc_h(k) - g%gc_h(k - 1)) * (p - g%gc_p(k - 1)) / (g%gc_p(k) - g%gc_p(k - 1))
    end if
  end function conductance_at

  !> Purpose: the matrix ae(n, n) = ha w w^T of heat coupling k (its
  !> nodes ch%node(ch%xnode(k):...), n of them).
  pure subroutine contact_heat_matrix(ch, k, ae, n)
    type(contact_heat_t), intent(in) :: ch
    integer, intent(in) :: k
    real(dp), allocatable, intent(out) :: ae(:, :)
    integer, intent(out) :: n
    integer :: i
    n = ch%xnode(k + 1) - ch%xnode(k)
    allocate(ae(n, n))
    associate(w => ch%w(ch%xnode(k):ch%xnode(k + 1) - 1))
      do i = 1, n
        ae(:, i) = ch%ha(k) * w * w(i)
      end do
    end associate
  end subroutine contact_heat_matrix

  !> Purpose: r = r + the couplings' heat into each node at temperatures
  !> temp(nn): the frictional heat, less ha w [[T]]; with only(nn) given
  !> the temperatures of the nodes it marks only (the prescribed ones,
  !> for the right-hand side of the free temperatures). Each side's
  !> frictional heat goes to its nodes in proportion to their weights (as
  !> the CFE's force does; a mortar weight may be negative), normalised
  !> by the side's sum.
  pure subroutine contact_heat_residual(ch, temp, r, only)
    type(contact_heat_t), intent(in) :: ch
    real(dp), intent(in) :: temp(:)
    real(dp), intent(inout) :: r(:)
    logical, intent(in), optional :: only(:)
    integer :: k, i, a, i0, is
    real(dp) :: jump, ws, wm
    do k = 1, ch%n
      i0 = ch%xnode(k)
      is = i0 + ch%nslave(k) - 1           ! the slave side: i0 .. is
      jump = 0.0_dp
      do i = i0, ch%xnode(k + 1) - 1
        a = ch%node(i)
        if (present(only)) then
          if (only(a)) jump = jump + ch%w(i) * temp(a)
        else
          jump = jump + ch%w(i) * temp(a)
        end if
      end do
      ws = sum(ch%w(i0:is))
      wm = -sum(ch%w(is + 1:ch%xnode(k + 1) - 1))
      do i = i0, ch%xnode(k + 1) - 1
        a = ch%node(i)
        r(a) = r(a) - ch%ha(k) * ch%w(i) * jump
        if (i <= is .and. ws /= 0.0_dp) r(a) = r(a) + ch%qs(k) * ch%w(i) / ws
        if (i > is .and. wm /= 0.0_dp) r(a) = r(a) - ch%qm(k) * ch%w(i) / wm
      end do
    end do
  end subroutine contact_heat_residual

  !> Purpose: do a and b couple the same nodes (the same structure of the
  !> temperature equations)?
  pure logical function same_couplings(a, b)
    type(contact_heat_t), intent(in) :: a, b
    same_couplings = .false.
    if (a%n /= b%n) return
    if (.not. (allocated(a%node) .and. allocated(b%node))) return
    if (size(a%node) /= size(b%node)) return
    same_couplings = all(a%xnode == b%xnode) .and. all(a%node == b%node)
  end function same_couplings

  !> Purpose: do a and b, which couple the same nodes (same_couplings),
  !> add the same matrices h A w w^T to the temperature equations, to
  !> round-off (same_tolerance of the largest h A, and of the largest
  !> weight)? A coupling that conducts nothing in both adds nothing
  !> whatever its weights (they move by round-off where the contact is
  !> searched again). Round-off must not decide: the two builds, and the
  !> BLAS kernels, then keep or renew the factor alike.
  pure logical function same_matrices(a, b)
    type(contact_heat_t), intent(in) :: a, b
    real(dp) :: hmax, wmax
    integer :: k
    same_matrices = .true.
    if (a%n == 0) return
    hmax = max(maxval(abs(a%ha)), maxval(abs(b%ha)))
    wmax = max(maxval(abs(a%w)), maxval(abs(b%w)))
    same_matrices = all(abs(a%ha - b%ha) <= same_tolerance * hmax)
    if (.not. same_matrices) return
    do k = 1, a%n
      if (a%ha(k) == 0.0_dp .and. b%ha(k) == 0.0_dp) cycle
      same_matrices = all(abs(a%w(a%xnode(k):a%xnode(k + 1) - 1) - b%w(b%xnode(k):b%xnode(k + 1) - 1)) <= &
                          same_tolerance * wmax)
      if (.not. same_matrices) return
    end do
  end function same_matrices

  !> Purpose: the heat flux across each CFE of the contact set (ncfe of
  !> them) at temperatures temp: per unit area, from the slave side to the
  !> master, h [[T]] (0 for CFEs of pairs without conductance and open
  !> ones).
  pure function contact_heat_flux(ch, temp, ncfe) result(q)
    type(contact_heat_t), intent(in) :: ch
    real(dp), intent(in) :: temp(:)
    integer, intent(in) :: ncfe
    real(dp) :: q(ncfe)
    integer :: k
    q = 0.0_dp
    do k = 1, ch%n
      if (ch%area(k) <= 0.0_dp) cycle
      associate(i0 => ch%xnode(k), i1 => ch%xnode(k + 1) - 1)
        q(ch%cfe(k)) = ch%ha(k) / ch%area(k) * dot_product(ch%w(i0:i1), temp(ch%node(i0:i1)))
      end associate
    end do
  end function contact_heat_flux
end module contact_heat
