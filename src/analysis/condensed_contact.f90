!> The condensed contact solve. Within a step the bodies are linear and
!> only the coupling elements change with the contact status; a CFE's
!> tangent reaches only the contact equations (the free dofs its B_e^T n
!> touches: slave nodes and the master edges' nodes). Those equations are
!> numbered last (m of the n), and the stiffness K0 of the bodies with
!> every CFE at its nominal open penalty is factored once, by CHOLMOD with
!> the contact block kept last: K0 = L L^T with L = [L11 0; L21 L22]. Its
!> Schur complement on the contact equations is S0 = L22 L22^T, read from
!> the factor's trailing block. For a contact status,
!>   S = S0 + sum over CFEs of (tangent now - tangent in K0)
!> on the contact equations, a dense m x m matrix factored by LAPACK. The
!> right-hand side of an increment is condensed once (the forward half of
!> a solve, z = L^-1 P r, then q0 = L22 z2); a status iteration solves
!> S x2 = q0 - (CFE forces at the increment's start), which gives the
!> contact equations, hence every gap; the other equations are recovered
!> once the status has settled, by the backward half of a solve with
!> z2 = L22^T x2. All positions and dense matrices here are in the
!> factor's trailing order (sys_trailing_order).
!> Measurements and the choice against the other ways in (a Schur
!> complement by many right-hand sides, Woodbury): docs/benchmark.md.
!> A linear step paired again at every increment (UPDATE SEARCH) numbers
!> the contact equations for the zone its pairings reach, keeps the
!> numbering and K0's factor across pairings (condensed_repair) and
!> solves a status near a reference one in low-rank form: the
!> reference's inverse, a capacitance matrix on the closed couplings'
!> equations, a refinement against S (docs/fretting.md, "Cost").
module condensed_contact
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  use model, only: model_t, carries_stiffness, elem_nodes, nonlinear_material, step_dloads, dload_p, edge_nodes
  use solver_codes, only: solver_cholmod, solver_umfpack, solver_mumps, contact_solve_full, contact_solve_condensed
  use contact, only: cfe_t, contact_set_t, cfe_input, cfe_nodes, contact_forces, frictional_set, closed_stiffness, &
                     open_penalty, closed_offset, open_shift, cfe_max_nodes
  use element_interface, only: cfe_in_t, cfe_out_t, max_en, act_tangent, act_residual
  use cfe_element, only: cfe, cfe_b_matrix
  use assembly, only: body_t, element_counts_t, assemble_stiffness, free_residual
  use dof_numbering, only: dofmap_t, number_dofs, has_dependent, group_transform, expand_dependent, reduce_dependent
  use constraints, only: mpc_t
  use linear_solver, only: linear_system_t, sys_condensed_factor, sys_trailing_order, sys_forward, sys_backward, &
                           sys_factor_flops, sys_nlast, factor_ok, factor_singular, pivot_ratio_min
  use dense_cholesky, only: dense_factor, dense_solve, upper_times, lower_gram, lower_solve, transposed_gram
  use dense_lu, only: lu_factor, lu_solve
  implicit none
  private
  public :: condensed_t, number_equations, symmetric_tangent, condensed_factor_k0, condensed_status, condensed_begin, &
            condensed_solve, condensed_recover, condensed_correct, contact_part_forces, add_body_forces, &
            condensed_energy, direct_multipliers, condensed_multipliers, condensed_repair, &
            condense_change, condensed_begin_lazy, s0_times, moving_elements, forward_rhs, condensed_refine, &
            load_change, copy_field, take_equations, subtract_field, zero_field

  !> With CONTACT SOLVE=AUTO: the condensed solve is taken when one dense
  !> factorisation of S (m^3/3 operations) costs at most this share of a
  !> sparse factorisation of the whole system, and m is at most
  !> auto_max_m (two m x m matrices are kept). MUMPS pays more per sparse
  !> factorisation and solve than its flop count says (the ranks' messages),
  !> so the condensed solve pays for a larger m: measured on contact
  !> surfaces of 250 to 2000 points over 2 ranks (docs/benchmark.md),
  !> condensed faster up to a share 0.72 (500 points), full from 0.85.
  real(dp), parameter :: auto_flop_share = 0.5_dp, auto_flop_share_mumps = 0.8_dp
  !> A nonlinear step takes the condensed solve (AUTO) only where a sparse
  !> factorisation of its tangent costs at least this many operations: on
  !> a small model the full solve's factor per Newton iteration is cheap
  !> and its iterates (a status pivot per Newton iteration) are kept.
  real(dp), parameter :: auto_min_flops_nonlinear = 1.0e8_dp
  integer, parameter :: auto_max_m = 6000

  type :: condensed_t
    logical :: active = .false.         ! this numbering is for the condensed solve
    integer :: n = 0, m = 0             ! equations, contact equations (the last m)
    integer, allocatable :: pos(:)      ! (n) trailing position of an equation, 0 for the others
    integer, allocatable :: eq_at(:)    ! (m) equation at a trailing position
    !> (maxng, ncfe): maxng the most dofs (equations, through constraints)
    !> of any CFE of the numbering (dependents_at_cfes)
    integer, allocatable :: cfe_pos(:, :)       ! position of each CFE dof, 0 if none
    real(dp), allocatable :: ke0(:, :, :)       ! (maxng, maxng, ncfe) CFE tangents as in K0
    !> One m x m array for two matrices: the trailing block L22 of the
    !> factor of K0 as its transpose in the upper triangle and diagonal,
    !> the Schur complement S0 of K0 in the strict lower triangle (its
    !> diagonal in s0_diag), so that S's columns are copied contiguously.
    real(dp), allocatable :: l22(:, :), s0_diag(:)
    real(dp), allocatable :: s(:, :)    ! Cholesky factor of S of the current status (lower)
    !> A sliding frictional CFE makes S unsymmetric: s then holds its LU
    !> factors (whole matrix), ipiv the row interchanges.
    logical :: lu = .false.
    integer, allocatable :: ipiv(:)
    real(dp), allocatable :: diag22(:)  ! K0's diagonal on the contact equations
    real(dp), allocatable :: kdiag(:)   ! the diagonal of the current status (LU: each column's scale)
    real(dp), allocatable :: z(:)       ! (n) forward-solved right-hand side of the increment
    real(dp), allocatable :: q0(:), x2(:)       ! (m) condensed right-hand side, solution
    !> A low-rank status solved without its refinement (condensed_solve's
    !> defer): refined false, rhs its right-hand side, for condensed_refine.
    logical :: refined = .true.
    real(dp), allocatable :: rhs(:)
    !> S0 x2 of the refined x2 from its refinement (condensed_refine;
    !> s0x_valid), and rres, the refinement's last measured residual
    !> |rhs - S x| (of x2 before its last correction): the settled
    !> balance's S0 x2 without a product of its own.
    logical :: s0x_valid = .false.
    real(dp), allocatable :: s0x(:)
    real(dp) :: rres = 0.0_dp
    !> Each CFE's forces at the increment's start u0 (start_forces):
    !> fe0(1:2 nen, j) for the state fe0_key(:, j) (force_key), valid
    !> (fe0_valid) for this start and the mapping fe0_gen: a later status
    !> of the increment evaluates only the CFEs whose state changed.
    real(dp), allocatable :: fe0(:, :), fe0_key(:, :)
    logical :: fe0_valid = .false.
    integer :: fe0_gen = -1
    real(dp), allocatable :: gap_start(:)       ! (ncfe) every CFE's gap at the increment's start
    real(dp), allocatable :: u0(:, :)   ! displacements at the start of the increment
    real(dp) :: umax_rest = 0.0_dp      ! largest |u0| off the contact equations
    real(dp), allocatable :: fw(:, :)   ! (2, nn) work: CFE forces, zero between uses
    real(dp) :: kmax = 0.0_dp           ! largest element diagonal of the current status
    !> Dependent dofs (indices into the constraints) at CFE nodes: their
    !> independent dofs are contact equations (or prescribed), so they
    !> follow the status iterations.
    integer, allocatable :: cdep(:)
    !> A pairing history (UPDATE SEARCH in a linear step: the couplings
    !> paired again at every increment): the contact equations are those
    !> of zone(2, nn), every dof some pairing of the step has reached so
    !> far (number_equations with grow), so that a new pairing whose dofs
    !> lie in the zone keeps the numbering and the bodies' factor
    !> (condensed_repair). S0 is then the bodies' Schur complement alone
    !> (K0's open CFEs taken out of it and of diag22, ke0 zero), and S of
    !> a status adds every CFE's whole tangent: the same matrix as
    !> S0 + (tangent now - tangent in K0) of the pairing K0 was made with.
    logical :: keep_pairing = .false.
    logical, allocatable :: zone(:, :)
    !> The low-rank status solve (keep_pairing; docs/fretting.md): finv
    !> (m, m) the inverse of S_ref, the condensed matrix of a reference
    !> status (ref_valid: the last one factored densely), and its closed
    !> CFEs' positions and tangents (ref_pos, ref_k). A status differs
    !> from it by dmat on the positions dset of its own and the
    !> reference's closed CFEs, S = S_ref + E dmat E^T (the open CFEs'
    !> share of the difference, 1e-12 of a closed one's, is left to the
    !> refinement), solved through the capacitance matrix
    !> cap = I + finv(D, D) dmat (LU, cap_piv) and refined against S
    !> itself: S0 and the status's tangents kt_all (kt_ng rows each).
    logical :: lowrank = .false., ref_valid = .false.
    !> The low-rank form keeps one more m x m matrix (finv) beside l22
    !> and s; the products with finv and S0 read their lower triangles.
    real(dp), allocatable :: finv(:, :), ref_k(:, :, :), kt_all(:, :, :), dmat(:, :), cap(:, :)
    !> The last product with finv (fb_y = finv fb_x; fb_valid, fb_chain:
    !> how many were made from it by the columns of the entries that
    !> changed, reference_product): the right-hand sides of an
    !> increment's statuses differ only at the couplings that changed.
    real(dp), allocatable :: fb_x(:), fb_y(:)
    logical :: fb_valid = .false.
    integer :: fb_chain = 0
    integer, allocatable :: ref_pos(:, :), kt_ng(:), dset(:), cap_piv(:)
    !> The reference's share of every capacitance matrix, made once per
    !> reference: ref_cols(:, c) = -(F E_ref K_ref)(:, c), the column of
    !> reference position ref_cpos(c) (reference_columns).
    real(dp), allocatable :: ref_cols(:, :)
    integer, allocatable :: ref_cpos(:)
    !> What each CFE's tangent in kt_all was made for (status_tangents):
    !> the CFE mapping (map_gen, counted up by map_cfes: the couplings'
    !> geometry and positions), and per CFE its status, slip sign and
    !> penalty (kt_key: closed, sliding as 0/1, slip_sign, the penalty in
    !> force), and kt_kraw its largest diagonal entry.
    integer :: map_gen = 0, kt_gen = -1
    real(dp), allocatable :: kt_key(:, :), kt_kraw(:)
    !> Increments solved on the contact equations alone (keep_pairing;
    !> docs/fretting.md, "Cost"). The condensed right-hand side of an
    !> increment that starts from u (free dofs those of the last converged
    !> increment) under loads fext is
    !>   q0 = qnext + C (fext - fext_last - K_body (u - u_last))
    !> with C the condensation r -> L22 z2 (z = L^-1 P r), qnext = q0 - S0 x2
    !> of the last converged increment (C of K_body is S0 on the contact
    !> equations: S0 u_C; the other equations cancel), fext_last its loads.
    !> The change of the loads and prescribed values lies in the span of a
    !> few directions (basis, orthonormal, n x nb; a load scaled by an
    !> amplitude is one), each condensed once (basis_q, m x nb), so that an
    !> increment needs no forward solve; the other equations are recovered
    !> only where results need them (condensed_equilibrium's
    !> condensed_complete). z_valid: z is the forward solve of this
    !> increment's start (condensed_begin); lazy: the last converged
    !> increment was not recovered (u's other equations are those of an
    !> earlier increment); qnext_fresh: qnext was made from the last x2.
    logical :: z_valid = .false., lazy = .false., qnext_valid = .false., qnext_fresh = .false.
    !> The elements with a node that has a dof off the equations
    !> (prescribed, dependent or inactive: dm%eq 0), in ascending order,
    !> made once per factor of K0 (its numbering): between two increments
    !> only those dofs move (moving_elements, add_body_forces).
    integer, allocatable :: moving_elems(:)
    !> (2, nn) the dofs that are not contact equations (start_from's
    !> umax_rest), made once per factor of K0 (the numbering's positions)
    logical, allocatable :: off_contact(:, :)
    real(dp), allocatable :: qnext(:), fext_last(:, :), basis(:, :), basis_q(:, :)
    integer :: nb = 0
    !> The equations where a change of the right-hand side or a direction
    !> of the basis is not zero (in_supp, and supp(1:nsupp) ascending):
    !> the elements moving the prescribed values and the loaded dofs, a
    !> few hundred of McColl's 13 547. condense_change's sums run over
    !> them alone (the other entries are zero: the same sums).
    logical, allocatable :: in_supp(:)
    integer, allocatable :: supp(:)
    integer :: nsupp = 0
    !> (2, nn) work of load_change: dfw the bodies' forces of the moved
    !> dofs, zero between uses; wk the change of the forces
    real(dp), allocatable :: dfw(:, :), wk(:, :)
  end type condensed_t

contains

  !> Purpose: numbers the equations for the contact solve the model asks
  !> for (m%contact_solve) and sets up the solver's structure: with the
  !> condensed solve the contact equations last, cd%active and cd%m say so.
  !> The full solve where the model says FULL, without coupling elements,
  !> with a solver other than CHOLMOD (and with UMFPACK where friction may
  !> make the matrix unsymmetric), and (AUTO) where a dense
  !> factorisation of the condensed matrix would not be cheaper than a
  !> sparse one of the whole (m comparable to n).
  !> Arguments: mpc the linear constraints (their dependent dofs
  !> eliminated); t_analyse returns the wall time of the symbolic analysis
  !> done here to decide (0 when none was needed); nonlinear, if true,
  !> says the step is nonlinear: where the bodies' tangent is symmetric
  !> (symmetric_tangent) the solve is chosen as for a linear step where the
  !> sparse factorisation costs auto_min_flops_nonlinear or more (Newton's
  !> tangent is then factored once per Newton iteration and the contact
  !> status searched on it by the condensed system); otherwise the full
  !> solve with UMFPACK (the tangent may be unsymmetric, F-bar and
  !> follower pressures, or indefinite). keep, if true (a renumbering
  !> inside an increment), keeps the solve cd had: the iteration's path
  !> stays (condensed: where any contact equation is left). grow, if true
  !> (a linear step that pairs again at every increment), makes the
  !> contact equations those of every dof the couplings reached since
  !> (cd%zone, still free) and of the couplings of cs, and sets
  !> cd%keep_pairing: a later pairing within the zone keeps this numbering.
  subroutine number_equations(m, cs, prescribed, mpc, dm, sys, cd, t_analyse, nonlinear, keep, grow)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    logical, intent(in) :: prescribed(:, :)
    type(mpc_t), intent(in) :: mpc
    type(dofmap_t), intent(out) :: dm
    type(linear_system_t), intent(inout) :: sys
    type(condensed_t), intent(inout) :: cd
    real(dp), intent(out) :: t_analyse
    logical, intent(in), optional :: nonlinear, keep, grow
    logical, allocatable :: mask(:, :)
    integer :: mc, solver
    real(dp) :: flops
    integer(kind=8) :: c0, c1, rate
    logical :: want_full, nl, stay, was_active, zone
    t_analyse = 0.0_dp
    stay = .false.
    if (present(keep)) stay = keep
    zone = .false.
    if (present(grow)) zone = grow
    cd%keep_pairing = .false.
    was_active = cd%active
    cd%active = .false.
    cd%m = 0
    nl = .false.
    if (present(nonlinear)) nl = nonlinear
    want_full = m%contact_solve == contact_solve_full .or. (nl .and. .not. symmetric_tangent(m))
    if (stay) want_full = .not. was_active
    if (.not. want_full .and. (m%solver == solver_cholmod .or. m%solver == solver_mumps) .and. cs%n > 0) then
      call contact_dof_mask(m, cs, prescribed, mpc, mask)
      if (zone) then
        if (allocated(cd%zone)) then
          if (all(shape(cd%zone) == shape(mask))) mask = mask .or. (cd%zone .and. .not. prescribed .and. mpc%dep == 0)
        end if
      end if
      mc = count(mask)
      if (mc > 0) then
        call number_dofs(m, cs, prescribed, m%solver, m%ordering, dm, sys, mask, mpc)
        cd%active = m%contact_solve == contact_solve_condensed .or. stay
        if (.not. cd%active .and. mc <= auto_max_m) then
          call system_clock(c0, rate)
          flops = sys_factor_flops(sys)
          call system_clock(c1)
          t_analyse = real(c1 - c0, dp) / real(rate, dp)
          cd%active = real(mc, dp)**3 / 3.0_dp <= &
                      merge(auto_flop_share_mumps, auto_flop_share, m%solver == solver_mumps) * flops
          if (nl) cd%active = cd%active .and. flops >= auto_min_flops_nonlinear
        end if
        if (cd%active) then
          cd%n = dm%neq
          cd%m = mc
          cd%keep_pairing = zone
          if (zone) cd%zone = mask
          return
        end if
      end if
    end if
    ! A sliding frictional CFE makes the full matrix unsymmetric: the
    ! symmetric backends (CHOLMOD, skyline) keep one triangle, so the full
    ! solve of a frictional model takes UMFPACK, which keeps both (MUMPS
    ! keeps both and turns to LU itself).
    solver = m%solver
    if ((frictional_set(cs) .or. nl) .and. solver /= solver_mumps) solver = solver_umfpack
    call number_dofs(m, cs, prescribed, solver, m%ordering, dm, sys, constraints=mpc)
  end subroutine number_equations

  !> Purpose: is the bodies' Newton tangent of model m symmetric, so that
  !> CHOLMOD can factor it for the condensed solve? Where the only
  !> nonlinearity is the geometry (NLGEOM with *ELASTIC: St Venant-Kirchhoff,
  !> whose A = dP/dF is symmetric; the plain element, no F-bar), no
  !> pressure follows the faces (its load stiffness is unsymmetric) and no
  !> rigid body or kinematic coupling turns (its followers are moved by the
  !> iteration after each update, which the condensed solve does not
  !> see). Hyperelastic laws and plasticity take the full solve (F-bar;
  !> plasticity's tangent at large strain).
  logical function symmetric_tangent(m)
    type(model_t), intent(in) :: m
    integer :: k
    symmetric_tangent = .not. nonlinear_material(m)
    if (allocated(m%equations)) symmetric_tangent = symmetric_tangent .and. .not. any(m%equations%rigid_ref > 0)
    if (.not. allocated(m%steps)) return
    do k = 1, size(m%steps)
      if (step_dloads(m%steps(k)) == 0) cycle
      symmetric_tangent = symmetric_tangent .and. .not. any(m%steps(k)%dloads%label == dload_p)
    end do
  end function symmetric_tangent

  !> The contact equations: free dofs on the diagonal of some CFE's closed
  !> tangent (those its B_e^T n reaches; where the normal has no x
  !> component, to round-off, the x dofs are not among them); for a
  !> dependent dof there, the free independent dofs it stands for.
  subroutine contact_dof_mask(m, cs, prescribed, mpc, mask)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    logical, intent(in) :: prescribed(:, :)
    type(mpc_t), intent(in) :: mpc
    logical, allocatable, intent(out) :: mask(:, :)
    integer, allocatable :: rdof(:), rnode(:)
    integer :: j, nr, r
    allocate(mask(2, m%nn))
    mask = .false.
    do j = 1, cs%n
      call cfe_reach(m, cs%c(j), prescribed, mpc, rdof, rnode, nr)
      do r = 1, nr
        mask(rdof(r), rnode(r)) = .true.
      end do
    end do
  end subroutine contact_dof_mask

  !> Purpose: the free dofs CFE c makes contact equations of
  !> (contact_dof_mask): those on the diagonal of its closed tangent, for
  !> a dependent dof there the free independent dofs it stands for.
  !> Arguments: prescribed, mpc as contact_dof_mask; rdof(1:nr),
  !> rnode(1:nr) return the dofs (a dof may repeat).
  subroutine cfe_reach(m, cin, prescribed, mpc, rdof, rnode, nr)
    type(model_t), intent(in) :: m
    type(cfe_t), intent(in) :: cin
    logical, intent(in) :: prescribed(:, :)
    type(mpc_t), intent(in) :: mpc
    integer, allocatable, intent(inout) :: rdof(:), rnode(:)
    integer, intent(out) :: nr
    type(cfe_in_t) :: ein
    type(cfe_out_t) :: eout
    type(cfe_t) :: c
    real(dp) :: kmax
    integer :: k, d, i, q, nmax
    integer, allocatable :: nodes(:)
    c = cin
    ! closed and (with friction) sticking: every dof its B_e^T n or
    ! B_e^T t reaches
    c%closed = .true.
    c%sliding = .false.
    ! (the tangent does not read the displacements: any array of the
    ! nodes' shape serves, here the coordinates, not a zero copy)
    call cfe_input(m, c, m%x, .false., ein, nodes)
    call cfe(act_tangent, ein, eout)
    kmax = 0.0_dp
    do k = 1, 2 * ein%nen
      kmax = max(kmax, abs(eout%ke(k, k)))
    end do
    nmax = 2 * ein%nen
    do k = 1, ein%nen
      do d = 1, 2
        i = mpc%dep(d, nodes(k))
        if (i > 0) nmax = nmax + mpc%xt(i + 1) - mpc%xt(i)
      end do
    end do
    if (allocated(rdof)) then
      if (size(rdof) < nmax) deallocate(rdof, rnode)
    end if
    if (.not. allocated(rdof)) allocate(rdof(nmax), rnode(nmax))
    nr = 0
    do k = 1, ein%nen
      do d = 1, 2
        ! A normal component below 1e-12 is round-off of an axis-aligned
        ! normal (a straight 3-node face gives (-1, +-3.6e-15) or (-1, 0)
        ! depending on the build): it makes no contact equation.
        if (abs(eout%ke(2 * k - 2 + d, 2 * k - 2 + d)) <= 1.0e-24_dp * kmax) cycle
        i = mpc%dep(d, nodes(k))
        if (i == 0) then
          if (.not. prescribed(d, nodes(k))) call add(d, nodes(k))
          cycle
        end if
        do q = mpc%xt(i), mpc%xt(i + 1) - 1
          if (.not. prescribed(mpc%tdof(q), mpc%tnode(q))) call add(mpc%tdof(q), mpc%tnode(q))
        end do
      end do
    end do
  contains
    !> One more dof reached.
    subroutine add(dof, node)
      integer, intent(in) :: dof, node
      nr = nr + 1
      rdof(nr) = dof
      rnode(nr) = node
    end subroutine add
  end subroutine cfe_reach

  !> Purpose: assembles K0 (the bodies and every CFE open, nominal
  !> penalty), factors it with the contact block last and forms S0; maps
  !> the contact equations and the CFEs' dofs to trailing positions.
  !> Arguments: status, bad as sys_factor (factor_singular: the bodies are
  !> singular even with the contact equations held, which no contact
  !> status can mend); counts counts the CFE routine calls. A nonlinear
  !> body (Newton's condensed path) gives u, the displacements its tangent
  !> is taken at (converged as assemble_stiffness's), and kbody returns
  !> the largest element entry, t_assembly the wall time of the assembly.
  subroutine condensed_factor_k0(cd, m, cs, body, dm, sys, counts, status, bad, u, converged, kbody, t_assembly)
    type(condensed_t), intent(inout) :: cd
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    type(body_t), intent(in) :: body
    type(dofmap_t), intent(in) :: dm
    type(linear_system_t), intent(inout) :: sys
    type(element_counts_t), intent(inout) :: counts
    integer, intent(out) :: status, bad
    real(dp), intent(in), optional :: u(:, :)
    logical, intent(in), optional :: converged
    real(dp), intent(out), optional :: kbody, t_assembly
    type(contact_set_t) :: open_set
    integer, allocatable :: tperm(:)
    real(dp) :: kmax
    integer :: p, mc
    integer(kind=8) :: c0, c1, rate
    mc = sys_nlast(sys)
    cd%n = dm%neq
    cd%m = mc
    if (.not. allocated(cd%u0)) allocate(cd%u0(2, m%nn))
    cd%u0 = 0.0_dp
    if (present(u)) cd%u0 = u
    cd%fe0_valid = .false.
    open_set = cs
    open_set%c(1:cs%n)%closed = .false.
    open_set%stabilised = .false.
    call system_clock(c0, rate)
    call assemble_stiffness(m, open_set, body, cd%u0, sys, kmax, counts, dm, converged)
    call system_clock(c1)
    if (present(t_assembly)) t_assembly = real(c1 - c0, dp) / real(rate, dp)
    if (present(kbody)) kbody = kmax
    if (allocated(cd%l22)) deallocate(cd%l22, cd%s0_diag, cd%s, cd%diag22, cd%kdiag, cd%q0, cd%x2, cd%eq_at)
    allocate(cd%l22(mc, mc), cd%s0_diag(mc), cd%s(mc, mc), cd%diag22(mc), cd%kdiag(mc), cd%q0(mc), cd%x2(mc), &
             cd%eq_at(mc), tperm(mc))
    call sys_condensed_factor(sys, status, bad, cd%l22, cd%diag22)
    if (status /= factor_ok) return
    call sys_trailing_order(sys, tperm)
    cd%eq_at = cd%n - mc + tperm
    cd%pos = [(0, p = 1, cd%n)]
    cd%pos(cd%eq_at) = [(p, p = 1, mc)]
    if (allocated(cd%off_contact)) deallocate(cd%off_contact)
    if (allocated(cd%moving_elems)) deallocate(cd%moving_elems)
    ! the factor was of K0 with its trailing diagonal doubled
    call lower_gram(cd%l22, cd%s)
    do p = 1, mc
      cd%s0_diag(p) = cd%s(p, p) - cd%diag22(p)
      cd%l22(p, p + 1:mc) = cd%l22(p + 1:mc, p)
      cd%l22(p + 1:mc, p) = cd%s(p + 1:mc, p)
    end do
    call map_cfes(cd, m, cs, dm, open_set, counts)
    cd%ref_valid = .false.
    ! a new factor: no condensed direction or right-hand side carries over
    cd%nb = 0
    if (allocated(cd%qnext)) deallocate(cd%qnext)
    cd%qnext_valid = .false.
    cd%qnext_fresh = .false.
    cd%z_valid = .false.
    if (cd%keep_pairing) call bodies_alone(cd, cs%n)
  end subroutine condensed_factor_k0

  !> S0 and diag22 of the bodies alone: K0's open CFE tangents (ke0) taken
  !> out of them, ke0 zero (keep_pairing: a later pairing's CFEs add
  !> their whole tangents to this S0, condensed_status).
  subroutine bodies_alone(cd, ncfe)
    type(condensed_t), intent(inout) :: cd
    integer, intent(in) :: ncfe
    integer :: j, a, b, pa, pb
    do j = 1, ncfe
      do b = 1, size(cd%cfe_pos, 1)
        pb = cd%cfe_pos(b, j)
        if (pb == 0) cycle
        do a = 1, size(cd%cfe_pos, 1)
          pa = cd%cfe_pos(a, j)
          if (pa == 0 .or. pa < pb) cycle
          if (pa == pb) then
            cd%s0_diag(pa) = cd%s0_diag(pa) - cd%ke0(a, b, j)
            cd%diag22(pa) = cd%diag22(pa) - cd%ke0(a, b, j)
          else
            cd%l22(pa, pb) = cd%l22(pa, pb) - cd%ke0(a, b, j)
          end if
        end do
      end do
    end do
    cd%ke0 = 0.0_dp
  end subroutine bodies_alone

  !> Purpose: the couplings of cs were paired again (a linear step's
  !> UPDATE SEARCH) and the equations were numbered for a zone
  !> (keep_pairing): if every dof the new couplings reach is a contact
  !> equation of the numbering, the numbering and the bodies' factor stay
  !> and the CFEs are mapped to their trailing positions (fits true; S of
  !> a status is then made from S0 of the bodies alone); otherwise fits
  !> is false and nothing changed (the caller numbers again, the zone
  !> grown by the new couplings' dofs).
  !> Arguments: prescribed, mpc as number_equations; counts counts the
  !> CFE routine calls.
  subroutine condensed_repair(cd, m, cs, prescribed, mpc, dm, counts, fits)
    type(condensed_t), intent(inout) :: cd
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    logical, intent(in) :: prescribed(:, :)
    type(mpc_t), intent(in) :: mpc
    type(dofmap_t), intent(in) :: dm
    type(element_counts_t), intent(inout) :: counts
    logical, intent(out) :: fits
    integer, allocatable :: rdof(:), rnode(:)
    integer :: j, nr, r
    fits = .false.
    if (.not. (cd%active .and. cd%keep_pairing) .or. .not. allocated(cd%ke0) .or. cs%n == 0) return
    ! per coupling: every free dof of its nodes in the zone, so are those
    ! its tangent reaches (no CFE call); otherwise the dofs it reaches
    ! (contact_dof_mask's) judged, its tangent evaluated (before, every
    ! coupling's where one had a node's dof outside: an open coupling at
    ! the surface's end, in McColl's case at every increment)
    do j = 1, cs%n
      if (nodes_in_zone(m, cs%c(j), prescribed, mpc, cd%zone)) cycle
      call cfe_reach(m, cs%c(j), prescribed, mpc, rdof, rnode, nr)
      do r = 1, nr
        if (.not. cd%zone(rdof(r), rnode(r))) return
      end do
    end do
    fits = .true.
    call map_cfes(cd, m, cs, dm, cs, counts, tangents=.false.)
  end subroutine condensed_repair

  !> Purpose: does zone hold every dof of CFE c's nodes that is not
  !> prescribed (a dependent dof: the independent dofs of its
  !> constraint)? Of a master element (node-to-segment) only the nodes
  !> of its edge count: the shape functions of the others vanish on it
  !> (to round-off, far below cfe_reach's 1e-24 of the largest diagonal),
  !> so B_e^T n and B_e^T t do not reach them (the module's header). A
  !> superset of the dofs cfe_reach gives, so true here means they lie
  !> in the zone too.
  logical function nodes_in_zone(m, c, prescribed, mpc, zone) result(inside)
    type(model_t), intent(in) :: m
    type(cfe_t), intent(in) :: c
    logical, intent(in) :: prescribed(:, :), zone(:, :)
    type(mpc_t), intent(in) :: mpc
    integer :: k, d, i, q, nen
    integer, allocatable :: nodes(:)
    inside = .false.
    call cfe_nodes(m, c, nodes, nen)
    if (c%nm == 0 .and. c%elem > 0 .and. c%edge > 0) then
      ! the slave nodes, then the master edge's corners and mid-side node
      call edge_nodes(m, c%elem, c%edge, nodes(c%ns + 1), nodes(c%ns + 2), nodes(c%ns + 3))
      nen = c%ns + 2
      if (nodes(nen + 1) > 0) nen = nen + 1
    end if
    do k = 1, nen
      do d = 1, 2
        i = mpc%dep(d, nodes(k))
        if (i == 0) then
          if (.not. (prescribed(d, nodes(k)) .or. zone(d, nodes(k)))) return
          cycle
        end if
        do q = mpc%xt(i), mpc%xt(i + 1) - 1
          if (.not. (prescribed(mpc%tdof(q), mpc%tnode(q)) .or. zone(mpc%tdof(q), mpc%tnode(q)))) return
        end do
      end do
    end do
    inside = .true.
  end function nodes_in_zone

  !> Trailing positions of every CFE's rows (its dofs, or with
  !> constraints the equations its transformed tangent reaches), its
  !> tangent as in K0 (of open_set's status; with tangents false none:
  !> ke0 zero, no CFE routine called), and the dependent dofs at CFE nodes.
  subroutine map_cfes(cd, m, cs, dm, open_set, counts, tangents)
    type(condensed_t), intent(inout) :: cd
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs, open_set
    type(dofmap_t), intent(in) :: dm
    type(element_counts_t), intent(inout) :: counts
    logical, intent(in), optional :: tangents
    real(dp), allocatable :: kt(:, :), t(:, :)
    integer, allocatable :: geq(:), nodes(:)
    integer :: j, p, ng, maxng, nen
    real(dp) :: kraw
    logical :: with_tangents
    with_tangents = .true.
    if (present(tangents)) with_tangents = tangents
    call dependents_at_cfes(cd, m, cs, dm, maxng)
    cd%map_gen = cd%map_gen + 1
    if (allocated(cd%ke0)) deallocate(cd%ke0, cd%cfe_pos)
    allocate(cd%ke0(maxng, maxng, cs%n), cd%cfe_pos(maxng, cs%n))
    cd%cfe_pos = 0
    cd%ke0 = 0.0_dp
    do j = 1, cs%n
      if (with_tangents) then
        call cfe_tangent(m, open_set%c(j), .false., dm, cd%u0, kt, geq, ng, kraw, counts%coupling)
        cd%ke0(1:ng, 1:ng, j) = kt
      else
        ! the positions alone, as cfe_tangent numbers them (a pairing
        ! repaired in the zone: ke0 stays zero, condensed_repair)
        call cfe_nodes(m, open_set%c(j), nodes, nen)
        if (has_dependent(dm, nodes(1:nen))) then
          call group_transform(dm, nodes(1:nen), geq, t)
          ng = size(geq)
        else
          ! (each node's two equations in place: no temporary per CFE)
          ng = 2 * nen
          if (allocated(geq)) then
            if (size(geq) < ng) deallocate(geq)
          end if
          if (.not. allocated(geq)) allocate(geq(ng))
          do p = 1, nen
            geq(2 * p - 1:2 * p) = dm%eq(:, nodes(p))
          end do
        end if
      end if
      do p = 1, ng
        if (geq(p) > 0) cd%cfe_pos(p, j) = cd%pos(geq(p))
      end do
    end do
  end subroutine map_cfes

  !> cd%cdep: the dependent dofs at CFE nodes (each once); maxng the
  !> largest number of rows of a CFE's tangent (transformed or not).
  subroutine dependents_at_cfes(cd, m, cs, dm, maxng)
    type(condensed_t), intent(inout) :: cd
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    type(dofmap_t), intent(in) :: dm
    integer, intent(out) :: maxng
    logical, allocatable :: seen(:)
    integer, allocatable :: geq(:)
    real(dp), allocatable :: t(:, :)
    integer :: j, k, d, i, nen
    integer, allocatable :: nodes(:)
    allocate(seen(dm%mpc%ndep))
    seen = .false.
    maxng = 0
    do j = 1, cs%n
      call cfe_nodes(m, cs%c(j), nodes, nen)
      maxng = max(maxng, 2 * nen)
      if (.not. has_dependent(dm, nodes(1:nen))) cycle
      call group_transform(dm, nodes(1:nen), geq, t)
      maxng = max(maxng, size(geq))
      do k = 1, nen
        do d = 1, 2
          i = dm%mpc%dep(d, nodes(k))
          if (i > 0) seen(i) = .true.
        end do
      end do
    end do
    cd%cdep = pack([(i, i = 1, dm%mpc%ndep)], seen)
  end subroutine dependents_at_cfes

  !> The tangent of CFE c at displacements u (stabilised: the open
  !> penalty's stabilisation), transformed by the constraints where a dof
  !> of it is dependent: kt(ng, ng) on the equations geq (0: none); kraw
  !> the largest diagonal entry of the element's own tangent.
  subroutine cfe_tangent(m, c, stabilised, dm, u, kt, geq, ng, kraw, ncalls)
    type(model_t), intent(in) :: m
    type(cfe_t), intent(in) :: c
    logical, intent(in) :: stabilised
    type(dofmap_t), intent(in) :: dm
    real(dp), intent(in) :: u(:, :)
    real(dp), allocatable, intent(out) :: kt(:, :)
    integer, allocatable, intent(out) :: geq(:)
    integer, intent(out) :: ng
    real(dp), intent(out) :: kraw
    integer(kind=8), intent(inout) :: ncalls
    type(cfe_in_t) :: ein
    type(cfe_out_t) :: eout
    real(dp), allocatable :: t(:, :)
    integer :: nd, b
    integer, allocatable :: nodes(:)
    call cfe_input(m, c, u, stabilised, ein, nodes)
    call cfe(act_tangent, ein, eout)
    ncalls = ncalls + 1
    nd = eout%ndof
    kraw = 0.0_dp
    do b = 1, nd
      kraw = max(kraw, abs(eout%ke(b, b)))
    end do
    if (has_dependent(dm, nodes(1:ein%nen))) then
      call group_transform(dm, nodes(1:ein%nen), geq, t)
      kt = matmul(transpose(t), matmul(eout%ke(1:nd, 1:nd), t))
    else
      geq = reshape(dm%eq(:, nodes(1:ein%nen)), [nd])
      kt = eout%ke(1:nd, 1:nd)
    end if
    ng = size(geq)
  end subroutine cfe_tangent

  !> Purpose: factors S of the current contact status (cs: statuses and
  !> stabilisation): S0 plus every CFE's tangent minus its tangent in K0
  !> (the lower triangles; LAPACK leaves the upper one alone). With
  !> keep_pairing, a status close to the reference one (lowrank_status)
  !> is not factored: its solves go through the reference's inverse
  !> (cd%lowrank); a symmetric status factored densely (no sliding CFE) becomes the reference.
  !> Arguments: kbody the bodies' largest element diagonal; status
  !> factor_ok or factor_singular (bad: the equation whose pivot vanished,
  !> judged as the sparse backends judge theirs: relative to the diagonal
  !> entry of the status's full matrix); counts counts CFE routine calls.
  subroutine condensed_status(cd, m, cs, dm, kbody, counts, status, bad)
    type(condensed_t), intent(inout) :: cd
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    type(dofmap_t), intent(in) :: dm
    real(dp), intent(in) :: kbody
    type(element_counts_t), intent(inout) :: counts
    integer, intent(out) :: status, bad
    ! S0: its diagonal and strict lower triangle; the whole matrix when a
    ! sliding CFE's tangent is unsymmetric (never symmetrised)
    cd%lu = any(cs%c(1:cs%n)%closed .and. cs%c(1:cs%n)%sliding)
    cd%lowrank = .false.
    status = factor_ok
    bad = 0
    if (cd%keep_pairing) then
      call status_tangents(cd, m, cs, dm, kbody, counts)
      cd%lowrank = lowrank_status(cd, cs)
      if (cd%lowrank) return
    end if
    call dense_status_matrix(cd, m, cs, dm, kbody, counts)
    call factor_dense_status(cd, status, bad)
    ! (a reference's inverse is symmetric, its products read one triangle
    ! (sym_times): a status with a sliding CFE, unsymmetric, is never one;
    ! the last symmetric reference stays)
    if (status == factor_ok .and. cd%keep_pairing .and. .not. cd%lu) call set_reference(cd, cs)
  end subroutine condensed_status

  !> S of the status in cd%s (lower triangle, or whole for LU) and the
  !> diagonal its pivots are judged against (kdiag); kmax the largest
  !> element diagonal. The tangents are kt_all's with keep_pairing
  !> (status_tangents), the element's otherwise.
  subroutine dense_status_matrix(cd, m, cs, dm, kbody, counts)
    type(condensed_t), intent(inout) :: cd
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    type(dofmap_t), intent(in) :: dm
    real(dp), intent(in) :: kbody
    type(element_counts_t), intent(inout) :: counts
    real(dp), allocatable :: kt(:, :)
    integer, allocatable :: geq(:)
    integer :: j, a, b, pa, pb, ng
    real(dp) :: dk, kraw
    do b = 1, cd%m
      cd%s(b, b) = cd%s0_diag(b)
      cd%s(b + 1:cd%m, b) = cd%l22(b + 1:cd%m, b)
      if (cd%lu) cd%s(b, b + 1:cd%m) = cd%l22(b + 1:cd%m, b)
    end do
    cd%kdiag = cd%diag22
    if (.not. cd%keep_pairing) cd%kmax = kbody
    do j = 1, cs%n
      if (cd%keep_pairing) then
        ng = cd%kt_ng(j)
        kt = cd%kt_all(1:ng, 1:ng, j)
      else
        call cfe_tangent(m, cs%c(j), cs%stabilised, dm, cd%u0, kt, geq, ng, kraw, counts%coupling)
        cd%kmax = max(cd%kmax, kraw)
      end if
      do b = 1, ng
        pb = cd%cfe_pos(b, j)
        if (pb == 0) cycle
        do a = 1, ng
          pa = cd%cfe_pos(a, j)
          if (pa == 0) cycle
          if (pa < pb .and. .not. cd%lu) cycle   ! the lower triangle only
          dk = kt(a, b) - cd%ke0(a, b, j)
          cd%s(pa, pb) = cd%s(pa, pb) + dk
          if (pa == pb) cd%kdiag(pa) = cd%kdiag(pa) + dk
        end do
      end do
    end do
  end subroutine dense_status_matrix

  !> Cholesky (LU where a CFE slides) of cd%s, its pivots judged against
  !> kdiag: status factor_singular and bad the equation where one vanished.
  subroutine factor_dense_status(cd, status, bad)
    type(condensed_t), intent(inout) :: cd
    integer, intent(out) :: status, bad
    integer :: a, info
    real(dp) :: ratio
    status = factor_ok
    bad = 0
    if (cd%lu) then
      if (.not. allocated(cd%ipiv)) allocate(cd%ipiv(cd%m))
      if (size(cd%ipiv) /= cd%m) then
        deallocate(cd%ipiv)
        allocate(cd%ipiv(cd%m))
      end if
      ! (a sliding CFE's diagonal entry may be negative: the pivots are
      ! judged against the larger of each column's largest entry and the
      ! magnitude of the full matrix's diagonal entry)
      do a = 1, cd%m
        cd%kdiag(a) = max(maxval(abs(cd%s(:, a))), abs(cd%kdiag(a)))
      end do
      call lu_factor(cd%s, cd%ipiv, info)
    else
      call dense_factor(cd%s, info)
    end if
    if (info > 0) then
      status = factor_singular
      bad = cd%eq_at(info)
      return
    end if
    do a = 1, cd%m
      ratio = 0.0_dp
      ! the pivot relative to the diagonal entry (Cholesky: its square);
      ! LU with partial pivoting: U(a, a), the pivot of column a, relative
      ! to that column's scale before the factorisation
      if (cd%kdiag(a) > 0.0_dp) then
        if (cd%lu) then
          ratio = abs(cd%s(a, a)) / cd%kdiag(a)
        else
          ratio = cd%s(a, a)**2 / cd%kdiag(a)
        end if
      end if
      if (ratio < pivot_ratio_min) then
        status = factor_singular
        bad = cd%eq_at(a)
        return
      end if
    end do
  end subroutine factor_dense_status

  !> Every CFE's tangent of the status (stabilised as cs says) in
  !> kt_all (kt_ng rows; on cfe_pos), kmax the largest element diagonal
  !> (kbody's or a CFE's). A CFE's tangent, B_e^T C B_e (eq. 10), depends on
  !> its geometry and positions (fixed between two mappings, map_cfes)
  !> and on its status, slip sign and penalty (cfe_key): one whose key is
  !> the one its tangent in kt_all was made for keeps it (the statuses of
  !> an increment differ at a few couplings; before, every CFE was
  !> evaluated at every status).
  subroutine status_tangents(cd, m, cs, dm, kbody, counts)
    type(condensed_t), intent(inout) :: cd
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    type(dofmap_t), intent(in) :: dm
    real(dp), intent(in) :: kbody
    type(element_counts_t), intent(inout) :: counts
    real(dp), allocatable :: kt(:, :)
    integer, allocatable :: geq(:)
    integer :: j, ng, maxng
    real(dp) :: kraw, key(4)
    logical :: fresh
    maxng = size(cd%cfe_pos, 1)
    if (allocated(cd%kt_all)) then
      if (size(cd%kt_all, 1) /= maxng .or. size(cd%kt_all, 3) /= cs%n) deallocate(cd%kt_all, cd%kt_ng)
    end if
    fresh = .not. allocated(cd%kt_all) .or. cd%kt_gen /= cd%map_gen
    if (.not. allocated(cd%kt_all)) allocate(cd%kt_all(maxng, maxng, cs%n), cd%kt_ng(cs%n))
    if (fresh) then
      if (allocated(cd%kt_key)) deallocate(cd%kt_key, cd%kt_kraw)
      allocate(cd%kt_key(4, cs%n), cd%kt_kraw(cs%n))
      cd%kt_gen = cd%map_gen
    end if
    cd%kmax = kbody
    do j = 1, cs%n
      key = cfe_key(cs%c(j), cs%stabilised)
      if (fresh .or. any(key /= cd%kt_key(:, j))) then
        call cfe_tangent(m, cs%c(j), cs%stabilised, dm, cd%u0, kt, geq, ng, kraw, counts%coupling)
        cd%kt_ng(j) = ng
        cd%kt_all(1:ng, 1:ng, j) = kt
        cd%kt_key(:, j) = key
        cd%kt_kraw(j) = kraw
      end if
      cd%kmax = max(cd%kmax, cd%kt_kraw(j))
    end do
  end subroutine status_tangents

  !> Purpose: what a CFE's tangent depends on beside its geometry (cfe's
  !> eq. 10): closed or open, sticking or sliding and the slip sign, and
  !> the penalty of its state (closed_stiffness, open_penalty).
  pure function cfe_key(c, stabilised) result(key)
    type(cfe_t), intent(in) :: c
    logical, intent(in) :: stabilised
    real(dp) :: key(4)
    key = [merge(1.0_dp, 0.0_dp, c%closed), merge(1.0_dp, 0.0_dp, c%sliding), c%slip_sign, 0.0_dp]
    if (c%closed) then
      key(4) = closed_stiffness(c)
    else
      key(4) = open_penalty(c, stabilised)
    end if
  end function cfe_key

  !> Purpose: may the status of cs be solved by the low-rank form about
  !> the reference (true: dset, dmat and the capacitance's LU made)? Not
  !> without a reference, with exact CFEs (their multipliers take the
  !> dense factor) or the stabilisation (its open penalty is no longer
  !> small), where the closed CFEs of the status and the reference touch
  !> more than half of the contact equations (the capacitance's LU, k^3
  !> 2/3, then costs at most a quarter of S's Cholesky), or where a pivot of
  !> the capacitance matrix is below pivot_ratio_min of its column's
  !> scale (S near singular: the dense factor judges it).
  logical function lowrank_status(cd, cs) result(ok)
    type(condensed_t), intent(inout) :: cd
    type(contact_set_t), intent(in) :: cs
    integer, allocatable :: at(:)
    real(dp), allocatable :: colscale(:)
    integer :: j, k, p, info
    ok = .false.
    if (.not. cd%ref_valid .or. cs%stabilised .or. any(cs%c(1:cs%n)%exact)) return
    allocate(at(cd%m))
    at = 0
    k = 0
    do j = 1, cs%n
      if (cs%c(j)%closed) call add_positions(cd%cfe_pos(:, j), at, k)
    end do
    do j = 1, size(cd%ref_pos, 2)
      call add_positions(cd%ref_pos(:, j), at, k)
    end do
    if (2 * k > cd%m) return
    if (allocated(cd%dset)) deallocate(cd%dset, cd%dmat)
    allocate(cd%dset(k), cd%dmat(k, k))
    do p = 1, cd%m
      if (at(p) > 0) cd%dset(at(p)) = p
    end do
    cd%dmat = 0.0_dp
    do j = 1, cs%n
      if (cs%c(j)%closed) call scatter_tangent(cd%kt_all(:, :, j), cd%cfe_pos(:, j), at, 1.0_dp, cd%dmat)
    end do
    do j = 1, size(cd%ref_pos, 2)
      call scatter_tangent(cd%ref_k(:, :, j), cd%ref_pos(:, j), at, -1.0_dp, cd%dmat)
    end do
    call capacitance(cd, cs, at)
    if (allocated(cd%cap_piv)) deallocate(cd%cap_piv)
    allocate(cd%cap_piv(k))
    ! (the scale of each column before the factorisation, as for S's LU)
    allocate(colscale(k))
    do j = 1, k
      colscale(j) = maxval(abs(cd%cap(:, j)))
    end do
    call lu_factor(cd%cap, cd%cap_piv, info)
    if (info > 0) return
    do j = 1, k
      if (.not. abs(cd%cap(j, j)) >= pivot_ratio_min * colscale(j)) return
    end do
    ok = .true.
  end function lowrank_status

  !> cap = I + finv(D, D) dmat, dmat taken block by block (each closed
  !> CFE's tangent, the reference's with sign -1: a few columns of
  !> finv(D, D) each, not a k^3 product), its sums in a fixed order
  !> (explicit loops, not matmul, whose inlining differs between the
  !> optimised and the debug build: both builds give the same digits).
  !> at(p) is the index in D of position p.
  subroutine capacitance(cd, cs, at)
    type(condensed_t), intent(inout) :: cd
    type(contact_set_t), intent(in) :: cs
    integer, intent(in) :: at(:)
    real(dp), allocatable :: fdd(:, :)
    integer :: j, k
    k = size(cd%dset)
    fdd = cd%finv(cd%dset, cd%dset)
    if (allocated(cd%cap)) deallocate(cd%cap)
    allocate(cd%cap(k, k))
    cd%cap = 0.0_dp
    do j = 1, k
      cd%cap(j, j) = 1.0_dp
    end do
    do j = 1, cs%n
      if (cs%c(j)%closed) call add_block(cd%kt_all(:, :, j), cd%cfe_pos(:, j), 1.0_dp)
    end do
    ! the reference's blocks: their columns of F K_ref, at this status's
    ! positions (rows dset)
    do j = 1, size(cd%ref_cpos)
      cd%cap(:, at(cd%ref_cpos(j))) = cd%cap(:, at(cd%ref_cpos(j))) + cd%ref_cols(cd%dset, j)
    end do
  contains
    !> cap(:, at(pb)) += sign kt(a, b) fdd(:, at(pa)) over the block,
    !> each update two entries at a time (SSE2; an entry's sum is the
    !> same sequence of operations in every build): a fifth of a
    !> fretting increment with a jump was these updates, one entry at a
    !> time.
    subroutine add_block(kt, pos, sign)
      real(dp), intent(in) :: kt(:, :), sign
      integer, intent(in) :: pos(:)
      real(dp) :: coef
      integer :: a, b, i, c, f
      do b = 1, size(pos)
        if (pos(b) == 0) cycle
        c = at(pos(b))
        do a = 1, size(pos)
          if (pos(a) == 0) cycle
          coef = sign * kt(a, b)
          f = at(pos(a))
          !$omp simd
          do i = 1, size(cd%cap, 1)
            cd%cap(i, c) = cd%cap(i, c) + coef * fdd(i, f)
          end do
        end do
      end do
    end subroutine add_block
  end subroutine capacitance

  !> The positions pos (0: none) not yet in the set at (at(p) its index
  !> there, k the set's size) added to it.
  pure subroutine add_positions(pos, at, k)
    integer, intent(in) :: pos(:)
    integer, intent(inout) :: at(:), k
    integer :: a
    do a = 1, size(pos)
      if (pos(a) == 0) cycle
      if (at(pos(a)) > 0) cycle
      k = k + 1
      at(pos(a)) = k
    end do
  end subroutine add_positions

  !> d(at(pa), at(pb)) += sign kt(a, b) for the positions pa, pb of pos.
  pure subroutine scatter_tangent(kt, pos, at, sign, d)
    real(dp), intent(in) :: kt(:, :), sign
    integer, intent(in) :: pos(:), at(:)
    real(dp), intent(inout) :: d(:, :)
    integer :: a, b
    do b = 1, size(pos)
      if (pos(b) == 0) cycle
      do a = 1, size(pos)
        if (pos(a) == 0) cycle
        d(at(pos(a)), at(pos(b))) = d(at(pos(a)), at(pos(b))) + sign * kt(a, b)
      end do
    end do
  end subroutine scatter_tangent

  !> The status just factored densely becomes the reference of the
  !> low-rank solves where it may be one (no exact CFE, not stabilised)
  !> and is likely to pay: its closed CFEs touch at most a quarter of the
  !> contact equations (a later status, with the reference's and its own
  !> closed CFEs, within lowrank_status's half). finv = S^-1 column by
  !> column (about two dense factorisations' work), its closed CFEs'
  !> positions and tangents.
  subroutine set_reference(cd, cs)
    type(condensed_t), intent(inout) :: cd
    type(contact_set_t), intent(in) :: cs
    integer, allocatable :: closed(:), at(:)
    integer :: j, k
    cd%ref_valid = .false.
    if (cs%stabilised .or. any(cs%c(1:cs%n)%exact)) return
    allocate(at(cd%m))
    at = 0
    k = 0
    do j = 1, cs%n
      if (cs%c(j)%closed) call add_positions(cd%cfe_pos(:, j), at, k)
    end do
    if (4 * k > cd%m) return
    if (allocated(cd%finv)) then
      if (size(cd%finv, 1) /= cd%m) deallocate(cd%finv)
    end if
    if (.not. allocated(cd%finv)) allocate(cd%finv(cd%m, cd%m))
    do j = 1, cd%m
      cd%finv(:, j) = 0.0_dp
      cd%finv(j, j) = 1.0_dp
      call solve_s(cd, cd%finv(:, j))
    end do
    ! symmetric to round-off; made exactly so from its lower triangle, the
    ! part the products read (sym_times)
    do j = 1, cd%m - 1
      cd%finv(j, j + 1:cd%m) = cd%finv(j + 1:cd%m, j)
    end do
    closed = pack([(j, j = 1, cs%n)], cs%c(1:cs%n)%closed)
    cd%ref_pos = cd%cfe_pos(:, closed)
    cd%ref_k = cd%kt_all(:, :, closed)
    call reference_columns(cd)
    cd%ref_valid = .true.
    cd%fb_valid = .false.
  end subroutine set_reference

  !> Purpose: the reference's share of the capacitance matrix (capacitance:
  !> cap = I + F_DD dmat, dmat holding minus each reference block): for
  !> each position p its reference blocks reach, ref_cols(:, c) = -sum
  !> over the blocks of kt(a, b) F(:, pa) with pb = p, over every contact
  !> equation; a status takes the rows of its positions. Made once per
  !> reference, not the reference's axpys at every status.
  subroutine reference_columns(cd)
    type(condensed_t), intent(inout) :: cd
    integer, allocatable :: col(:)
    integer :: j, a, b, nc
    allocate(col(cd%m))
    col = 0
    nc = 0
    call add_positions(reshape(cd%ref_pos, [size(cd%ref_pos)]), col, nc)
    if (allocated(cd%ref_cols)) deallocate(cd%ref_cols, cd%ref_cpos)
    allocate(cd%ref_cols(cd%m, nc), cd%ref_cpos(nc))
    do a = 1, cd%m
      if (col(a) > 0) cd%ref_cpos(col(a)) = a
    end do
    cd%ref_cols = 0.0_dp
    do j = 1, size(cd%ref_pos, 2)
      do b = 1, size(cd%ref_pos, 1)
        if (cd%ref_pos(b, j) == 0) cycle
        do a = 1, size(cd%ref_pos, 1)
          if (cd%ref_pos(a, j) == 0) cycle
          cd%ref_cols(:, col(cd%ref_pos(b, j))) = cd%ref_cols(:, col(cd%ref_pos(b, j))) - &
                                                  cd%ref_k(a, b, j) * cd%finv(:, cd%ref_pos(a, j))
        end do
      end do
    end do
  end subroutine reference_columns

  !> Purpose: condenses the right-hand side of an increment that starts
  !> from displacements u (prescribed values in place) under loads fext:
  !> r = fext - fbody on the free equations (fbody: the bodies' internal
  !> forces at u), z = L^-1 P r, q0 = L22 z2; u is kept as the start of the
  !> increment.
  subroutine condensed_begin(cd, m, dm, sys, fext, u, fbody)
    type(condensed_t), intent(inout) :: cd
    type(model_t), intent(in) :: m
    type(dofmap_t), intent(in) :: dm
    type(linear_system_t), intent(inout) :: sys
    real(dp), intent(in) :: fext(:, :), u(:, :), fbody(:, :)
    call start_from(cd, m, dm, u)
    call forward_rhs(cd, dm, sys, fext, fbody)
    cd%q0 = cd%z(cd%n - cd%m + 1:cd%n)
    call upper_times(cd%l22, cd%q0, .true.)
  end subroutine condensed_begin

  !> Purpose: the forward-solved right-hand side of the increment's start,
  !> cd%z = L^-1 P r with r = fext - fbody on the free equations (both
  !> starts: condensed_begin, and a lazy start's when its interior is
  !> wanted).
  !> Arguments: cd the condensed solve; dm the numbering; sys the bodies'
  !> factor; fext the loads, fbody the bodies' forces at the start.
  subroutine forward_rhs(cd, dm, sys, fext, fbody)
    type(condensed_t), intent(inout) :: cd
    type(dofmap_t), intent(in) :: dm
    type(linear_system_t), intent(inout) :: sys
    real(dp), intent(in) :: fext(:, :), fbody(:, :)
    if (allocated(cd%z)) then
      if (size(cd%z) /= cd%n) deallocate(cd%z)
    end if
    if (.not. allocated(cd%z)) allocate(cd%z(cd%n))
    call free_residual(dm, fext, fbody, cd%z)
    call sys_forward(sys, cd%z)
    cd%z_valid = .true.
  end subroutine forward_rhs

  !> Purpose: what both starts of an increment keep: u as the start (u0),
  !> the work forces allocated, and the largest displacement off the
  !> contact equations (umax_rest, the recovery's scale).
  !> Arguments: cd the condensed solve; m the model; dm the numbering; u
  !> the displacements the increment starts from.
  subroutine start_from(cd, m, dm, u)
    type(condensed_t), intent(inout) :: cd
    type(model_t), intent(in) :: m
    type(dofmap_t), intent(in) :: dm
    real(dp), intent(in) :: u(:, :)
    integer :: a, d, e
    if (.not. allocated(cd%fw)) then
      allocate(cd%fw(2, m%nn))
      cd%fw = 0.0_dp
    end if
    if (allocated(cd%off_contact)) then
      if (any(shape(cd%off_contact) /= shape(u))) deallocate(cd%off_contact)
    end if
    if (.not. allocated(cd%off_contact)) then
      allocate(cd%off_contact(2, m%nn))
      do a = 1, m%nn
        do d = 1, 2
          e = dm%eq(d, a)
          cd%off_contact(d, a) = .true.
          if (e > 0) cd%off_contact(d, a) = cd%pos(e) == 0
        end do
      end do
    end if
    call keep_start(size(u), u, cd%off_contact, cd%u0, cd%umax_rest)
    cd%fe0_valid = .false.
  end subroutine start_from

  !> u0 = u, and umax the largest |u| where off (0 if none), over the n
  !> entries of the nodal fields (copy_field's why). The largest in four
  !> running maxima, every fourth entry each (one running maximum waited
  !> on its last comparison at every entry: a thirtieth of an increment
  !> without a jump); a maximum is the same in any order.
  pure subroutine keep_start(n, u, off, u0, umax)
    integer, intent(in) :: n
    real(dp), intent(in) :: u(n)
    logical, intent(in) :: off(n)
    real(dp), intent(inout) :: u0(n)
    real(dp), intent(out) :: umax
    real(dp) :: big(4)
    integer :: i, k
    u0 = u
    big = 0.0_dp
    do i = 1, n - 3, 4
      do k = 0, 3
        if (off(i + k)) big(k + 1) = max(big(k + 1), abs(u(i + k)))
      end do
    end do
    do i = n - mod(n, 4) + 1, n
      if (off(i)) big(1) = max(big(1), abs(u(i)))
    end do
    umax = maxval(big)
  end subroutine keep_start

  !> Purpose: the start of an increment on the contact equations alone
  !> (keep_pairing, qnext_valid): u (prescribed values in place, free
  !> dofs the last converged increment's) kept as the start, the
  !> condensed right-hand side q0 = qnext + dq, dq the condensed change of
  !> the loads (condense_change); no forward solve (z_valid false).
  subroutine condensed_begin_lazy(cd, m, dm, u, dq)
    type(condensed_t), intent(inout) :: cd
    type(model_t), intent(in) :: m
    type(dofmap_t), intent(in) :: dm
    real(dp), intent(in) :: u(:, :), dq(:)
    call start_from(cd, m, dm, u)
    cd%q0 = cd%qnext + dq
    cd%z_valid = .false.
  end subroutine condensed_begin_lazy

  !> Purpose: the Euclidean norm of r as the square root of its dot product
  !> where that sum of squares is between 1e-200 and 1e200 (no square
  !> overflowed, and those that underflowed count for nothing against
  !> it), norm2's scaled sum otherwise (a third of an increment's start
  !> was norm2 over the equations).
  pure real(dp) function plain_norm(r) result(nrm)
    real(dp), intent(in) :: r(:)
    real(dp) :: ss
    ss = dot_product(r, r)
    if (ss > 1.0e-200_dp .and. ss < 1.0e200_dp) then
      nrm = sqrt(ss)
    else
      nrm = norm2(r)
    end if
  end function plain_norm

  !> Purpose: dq = C r, the condensed part of a change r(n) of the
  !> right-hand side: r projected on the basis of directions condensed
  !> before (twice, Gram-Schmidt with reorthogonalisation); a remainder
  !> above 1e-13 of |r| becomes a new direction, condensed by one forward
  !> solve (z = L^-1 P w, L22 z2); past max_basis directions the
  !> remainder is condensed without being kept. A remainder below 1e-13
  !> of |r| is left out (round-off of r itself). The projections run over
  !> the support of r and the basis (cd%supp, grown here by r's nonzero
  !> entries): every other entry is zero in both, so the sums are those
  !> over every equation (before, four passes over the 13 547 equations
  !> of McColl's case per direction).
  subroutine condense_change(cd, sys, r, dq)
    type(condensed_t), intent(inout) :: cd
    type(linear_system_t), intent(inout) :: sys
    real(dp), intent(in) :: r(:)
    real(dp), intent(out) :: dq(:)
    integer, parameter :: max_basis = 8
    real(dp) :: rnorm, rest, beta
    real(dp), allocatable :: w(:), q(:), rs(:), bs(:)
    integer :: k, pass
    logical :: kept
    dq = 0.0_dp
    if (allocated(cd%basis)) then
      if (size(cd%basis, 1) /= cd%n .or. size(cd%basis_q, 1) /= cd%m) deallocate(cd%basis, cd%basis_q)
    end if
    if (.not. allocated(cd%basis)) then
      allocate(cd%basis(cd%n, max_basis), cd%basis_q(cd%m, max_basis))
      cd%nb = 0
    end if
    call grow_support(cd, r)
    rs = r(cd%supp(1:cd%nsupp))
    rnorm = plain_norm(rs)
    if (rnorm == 0.0_dp) return
    do pass = 1, 2
      do k = 1, cd%nb
        bs = cd%basis(cd%supp(1:cd%nsupp), k)
        beta = dot_product(bs, rs)
        rs = rs - beta * bs
        dq = dq + beta * cd%basis_q(:, k)
      end do
    end do
    rest = plain_norm(rs)
    if (rest <= 1.0e-13_dp * rnorm) return
    allocate(w(cd%n))
    w = 0.0_dp
    w(cd%supp(1:cd%nsupp)) = rs / rest
    kept = cd%nb < max_basis
    if (kept) then
      cd%nb = cd%nb + 1
      cd%basis(:, cd%nb) = w
    end if
    call sys_forward(sys, w)
    q = w(cd%n - cd%m + 1:cd%n)
    call upper_times(cd%l22, q, .true.)
    if (kept) cd%basis_q(:, cd%nb) = q
    dq = dq + rest * q
  end subroutine condense_change

  !> Purpose: cd%supp, the equations where r or a kept direction of the
  !> basis may not be zero, grown by r's nonzero entries (listed again in
  !> ascending order where it grew, so that sums over it keep the order of
  !> sums over every equation); empty again while no direction is kept.
  !> Arguments: cd the condensed solve; r(n) a change of the right-hand side.
  subroutine grow_support(cd, r)
    type(condensed_t), intent(inout) :: cd
    real(dp), intent(in), contiguous :: r(:)
    integer :: i
    logical :: grew
    if (allocated(cd%in_supp)) then
      if (size(cd%in_supp) /= size(r)) deallocate(cd%in_supp, cd%supp)
    end if
    if (.not. allocated(cd%in_supp)) then
      allocate(cd%in_supp(size(r)), cd%supp(size(r)))
      cd%in_supp = .false.
      cd%nsupp = 0
    end if
    if (cd%nb == 0 .and. cd%nsupp > 0) then
      cd%in_supp = .false.
      cd%nsupp = 0
    end if
    grew = .false.
    do i = 1, size(r)
      if (r(i) /= 0.0_dp .and. .not. cd%in_supp(i)) then
        cd%in_supp(i) = .true.
        grew = .true.
      end if
    end do
    if (.not. grew) return
    cd%nsupp = 0
    do i = 1, size(r)
      if (.not. cd%in_supp(i)) cycle
      cd%nsupp = cd%nsupp + 1
      cd%supp(cd%nsupp) = i
    end do
  end subroutine grow_support

  !> Purpose: the change of the right-hand side between two increments
  !> of a lazy start (only the dofs off the equations moved: u is u_last
  !> on every equation), r = T^T (fext - fext_last - K_body (u - u_last))
  !> on the equations: free_residual's of add_body_forces's forces, the
  !> same sums, without temporaries of the whole model (the bodies'
  !> forces of the moving elements alone, in work kept between calls).
  !> Arguments: cd the condensed solve (fext_last, moving_elems made);
  !> m the model; body the bodies' stiffness; dm the numbering; u the
  !> displacements of the start, u_last those of the last converged
  !> increment; fext the loads; r(n) returns the change.
  subroutine load_change(cd, m, body, dm, u, u_last, fext, r)
    type(condensed_t), intent(inout) :: cd
    type(model_t), intent(in) :: m
    type(body_t), intent(in) :: body
    type(dofmap_t), intent(in) :: dm
    real(dp), intent(in) :: u(:, :), u_last(:, :), fext(:, :)
    real(dp), intent(out) :: r(:)
    integer :: ie, k
    if (allocated(cd%dfw)) then
      if (any(shape(cd%dfw) /= shape(u))) deallocate(cd%dfw, cd%wk)
    end if
    if (.not. allocated(cd%dfw)) then
      allocate(cd%dfw(2, m%nn), cd%wk(2, m%nn))
      cd%dfw = 0.0_dp
    end if
    call add_body_change(m, body, u, u_last, cd%dfw, cd%moving_elems)
    call force_change(size(fext), fext, cd%fext_last, cd%dfw, cd%wk)
    if (dm%mpc%ndep > 0) call reduce_dependent(dm, cd%wk)
    call scatter_equations(size(dm%eq), dm%eq, cd%wk, r)
    ! the work zero again (only the moving elements' nodes were written)
    do ie = 1, size(cd%moving_elems)
      do k = 1, elem_nodes(m, cd%moving_elems(ie))
        cd%dfw(:, m%conn(k, cd%moving_elems(ie))) = 0.0_dp
      end do
    end do
  end subroutine load_change

  !> w = (fext - fext_last) - df, entry by entry (free_residual's
  !> difference of the load change and the bodies' forces), over the n
  !> entries of nodal fields taken as one sequence (copy_field's why).
  pure subroutine force_change(n, fext, fext_last, df, w)
    integer, intent(in) :: n
    real(dp), intent(in) :: fext(n), fext_last(n), df(n)
    real(dp), intent(out) :: w(n)
    w = (fext - fext_last) - df
  end subroutine force_change

  !> r(eq(i)) = w(i) where eq(i) > 0, over the n entries of a nodal field
  !> and its equation numbers taken as one sequence.
  pure subroutine scatter_equations(n, eq, w, r)
    integer, intent(in) :: n, eq(n)
    real(dp), intent(in) :: w(n)
    real(dp), intent(inout) :: r(:)
    integer :: i
    do i = 1, n
      if (eq(i) > 0) r(eq(i)) = w(i)
    end do
  end subroutine scatter_equations

  !> Purpose: dst = src over the n entries of a nodal field (2 x nodes)
  !> taken as one sequence. The iteration's fields are pointers, and an
  !> assignment through them, or a loop over their (2, nodes) shape, went
  !> a pair of entries at a time; a sequence is copied at memory speed.
  pure subroutine copy_field(n, src, dst)
    integer, intent(in) :: n
    real(dp), intent(in) :: src(n)
    real(dp), intent(inout) :: dst(n)
    dst = src
  end subroutine copy_field

  !> Purpose: f = 0 over the n entries of a nodal field (copy_field's why).
  pure subroutine zero_field(n, f)
    integer, intent(in) :: n
    real(dp), intent(out) :: f(n)
    f = 0.0_dp
  end subroutine zero_field

  !> Purpose: dst = dst - src over the n entries of a nodal field
  !> (copy_field's why).
  pure subroutine subtract_field(n, dst, src)
    integer, intent(in) :: n
    real(dp), intent(inout) :: dst(n)
    real(dp), intent(in) :: src(n)
    dst = dst - src
  end subroutine subtract_field

  !> Purpose: u takes src on the dofs that are equations (eq > 0), the
  !> others kept (where (eq > 0) u = src), over the n entries of the
  !> nodal fields (copy_field's why).
  pure subroutine take_equations(n, eq, src, u)
    integer, intent(in) :: n, eq(n)
    real(dp), intent(in) :: src(n)
    real(dp), intent(inout) :: u(n)
    where (eq > 0) u = src
  end subroutine take_equations

  !> Purpose: the CFEs' forces at the increment's start u0 on the contact
  !> equations, f(m) in trailing order, as contact_part_forces gives them
  !> (the same element results summed in the same order: CFE by CFE, node
  !> by node), each CFE evaluated only where its state (force_key)
  !> differs from that of its kept forces (fe0: the statuses of an
  !> increment differ at a few CFEs; before, every CFE at every status).
  !> The contact layer's gaps and forces of the CFEs are not set (their
  !> next evaluation, at the status's solution, sets them). Not with
  !> dependent dofs at CFE nodes (contact_part_forces reduces them).
  !> Arguments: cd the condensed solve; m the model; cs the CFEs; dm the
  !> numbering; f the forces; ncalls counts CFE routine calls.
  subroutine start_forces(cd, m, cs, dm, f, ncalls)
    type(condensed_t), intent(inout) :: cd
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    type(dofmap_t), intent(in) :: dm
    real(dp), intent(out) :: f(:)
    integer(kind=8), intent(inout) :: ncalls
    type(cfe_in_t) :: ein
    type(cfe_out_t) :: eout
    real(dp) :: key(6)
    integer :: j, i, nen, nd
    integer, allocatable :: nodes(:)
    logical :: fresh
    nd = 2 * cfe_max_nodes(cs)
    fresh = .not. cd%fe0_valid .or. cd%fe0_gen /= cd%map_gen
    if (allocated(cd%fe0)) then
      if (size(cd%fe0, 1) < nd .or. size(cd%fe0, 2) /= cs%n) deallocate(cd%fe0, cd%fe0_key)
    end if
    if (.not. allocated(cd%fe0)) then
      allocate(cd%fe0(nd, cs%n), cd%fe0_key(6, cs%n))
      fresh = .true.
    end if
    do j = 1, cs%n
      key = force_key(cs%c(j), cs%stabilised)
      if (.not. fresh) then
        if (all(key == cd%fe0_key(:, j))) cycle
      end if
      call cfe_input(m, cs%c(j), cd%u0, cs%stabilised, ein, nodes)
      call cfe(act_residual, ein, eout)
      ncalls = ncalls + 1
      cd%fe0(1:2 * ein%nen, j) = eout%fe(1:2 * ein%nen)
      cd%fe0_key(:, j) = key
    end do
    cd%fe0_valid = .true.
    cd%fe0_gen = cd%map_gen
    do j = 1, cs%n
      call cfe_nodes(m, cs%c(j), nodes, nen)
      do i = 1, nen
        cd%fw(:, nodes(i)) = cd%fw(:, nodes(i)) + cd%fe0(2 * i - 1:2 * i, j)
      end do
    end do
    call take_contact_part(cd, m, cs, dm, f)
  end subroutine start_forces

  !> Purpose: f(m) = the work field cd%fw on the contact equations, in
  !> trailing order; fw zeroed again at the CFEs' nodes (the only ones
  !> written into it: it stays zero between calls).
  subroutine take_contact_part(cd, m, cs, dm, f)
    type(condensed_t), intent(inout) :: cd
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    type(dofmap_t), intent(in) :: dm
    real(dp), intent(out) :: f(:)
    integer :: p, e, j, nen
    integer, allocatable :: nodes(:)
    do p = 1, cd%m
      e = cd%eq_at(p)
      f(p) = cd%fw(dm%dof_of_eq(e), dm%node_of_eq(e))
    end do
    do j = 1, cs%n
      call cfe_nodes(m, cs%c(j), nodes, nen)
      cd%fw(:, nodes(1:nen)) = 0.0_dp
    end do
  end subroutine take_contact_part

  !> Purpose: what a CFE's forces at given displacements depend on beside
  !> its pairing (cfe_input): cfe_key's status, slip sign and penalty,
  !> the closed force's offset (a soft law's segment, exact enforcement's
  !> multiplier) or the open one's shift, and the friction anchor.
  pure function force_key(c, stabilised) result(key)
    type(cfe_t), intent(in) :: c
    logical, intent(in) :: stabilised
    real(dp) :: key(6)
    key(1:4) = cfe_key(c, stabilised)
    if (c%closed) then
      key(5) = closed_offset(c)
    else
      key(5) = open_shift(c, stabilised)
    end if
    key(6) = c%anchor
  end function force_key

  !> Purpose: the CFEs' internal forces at displacements u on the contact
  !> equations, f(m) in trailing order (the contact layer also keeps each
  !> CFE's gap and force); every CFE force lives there (B_e^T n reaches
  !> nothing else). ncalls counts CFE routine calls.
  subroutine contact_part_forces(cd, m, cs, dm, u, f, ncalls)
    type(condensed_t), intent(inout) :: cd
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(inout) :: cs
    type(dofmap_t), intent(in) :: dm
    real(dp), intent(in) :: u(:, :)
    real(dp), intent(out) :: f(:)
    integer(kind=8), intent(inout) :: ncalls
    integer :: j, k, q
    call contact_forces(m, cs, u, cd%fw, ncalls)
    ! forces on dependent dofs act on their independent dofs
    if (size(cd%cdep) > 0) call reduce_dependent(dm, cd%fw, cd%cdep)
    call take_contact_part(cd, m, cs, dm, f)
    do j = 1, size(cd%cdep)
      k = cd%cdep(j)
      do q = dm%mpc%xt(k), dm%mpc%xt(k + 1) - 1
        cd%fw(dm%mpc%tdof(q), dm%mpc%tnode(q)) = 0.0_dp
      end do
    end do
  end subroutine contact_part_forces

  !> Purpose: f += K_body du, element by element, skipping the elements
  !> where du is zero (between increments only prescribed values move).
  !> Arguments: elems, if present, the elements to look at, ascending
  !> (every element with a node where du is not zero among them:
  !> moving_elements); otherwise all.
  subroutine add_body_forces(m, body, du, f, elems)
    type(model_t), intent(in) :: m
    type(body_t), intent(in) :: body
    real(dp), intent(in) :: du(:, :)
    real(dp), intent(inout) :: f(:, :)
    integer, intent(in), optional :: elems(:)
    real(dp) :: ue(2 * max_en)
    logical :: moved(size(du, 2)), any_moved
    integer :: e, k, nen, ie, ne
    moved = du(1, :) /= 0.0_dp .or. du(2, :) /= 0.0_dp
    if (.not. any(moved)) return
    ne = m%ne
    if (present(elems)) ne = size(elems)
    do ie = 1, ne
      e = ie
      if (present(elems)) e = elems(ie)
      if (.not. carries_stiffness(m, e)) cycle
      nen = elem_nodes(m, e)
      any_moved = .false.
      do k = 1, nen
        any_moved = any_moved .or. moved(m%conn(k, e))
      end do
      if (.not. any_moved) cycle
      do k = 1, nen
        ue(2 * k - 1:2 * k) = du(:, m%conn(k, e))
      end do
      call add_element_force(m, body, e, ue, f)
    end do
  end subroutine add_body_forces

  !> Purpose: f += K_body (u - u_last) over the elements elems (ascending)
  !> whose nodes moved: add_body_forces of du = u - u_last, the same sums
  !> in the same order, without du over the whole model (a lazy start:
  !> elems the moving elements).
  subroutine add_body_change(m, body, u, u_last, f, elems)
    type(model_t), intent(in) :: m
    type(body_t), intent(in) :: body
    real(dp), intent(in) :: u(:, :), u_last(:, :)
    real(dp), intent(inout) :: f(:, :)
    integer, intent(in) :: elems(:)
    real(dp) :: ue(2 * max_en)
    integer :: e, k, nen, ie
    do ie = 1, size(elems)
      e = elems(ie)
      if (.not. carries_stiffness(m, e)) cycle
      nen = elem_nodes(m, e)
      do k = 1, nen
        ue(2 * k - 1:2 * k) = u(:, m%conn(k, e)) - u_last(:, m%conn(k, e))
      end do
      if (all(ue(1:2 * nen) == 0.0_dp)) cycle
      call add_element_force(m, body, e, ue, f)
    end do
  end subroutine add_body_change

  !> f += K_e ue on element e's nodes, K_e its stored upper triangle
  !> taken column by column.
  subroutine add_element_force(m, body, e, ue, f)
    type(model_t), intent(in) :: m
    type(body_t), intent(in) :: body
    integer, intent(in) :: e
    real(dp), intent(in) :: ue(:)
    real(dp), intent(inout) :: f(:, :)
    real(dp) :: fe(2 * max_en), a
    integer :: i, j, k, nen, nd
    integer(kind=8) :: q
    nen = elem_nodes(m, e)
    nd = 2 * nen
    fe(1:nd) = 0.0_dp
    q = body%kptr(e)
    do j = 1, nd
      do i = 1, j
        a = body%ke(q)
        q = q + 1
        fe(i) = fe(i) + a * ue(j)
        if (i /= j) fe(j) = fe(j) + a * ue(i)
      end do
    end do
    do k = 1, nen
      f(:, m%conn(k, e)) = f(:, m%conn(k, e)) + fe(2 * k - 1:2 * k)
    end do
  end subroutine add_element_force

  !> Purpose: the contact equations for the current status (factored by
  !> condensed_status): S x2 = q0 - (CFE forces at the increment's start).
  !> u(contact equations) returns the start of the increment plus x2,
  !> enough for every gap (with the dependent dofs at CFE nodes); the
  !> caller keeps the other equations at the start until
  !> condensed_recover. finite says whether x2 is. defer, if true, leaves
  !> a low-rank solution unrefined (cd%refined false; Woodbury's answer,
  !> about 3e-13 of x from the dense factor's in McColl's case): enough to
  !> decide the next status; the status that settles is refined
  !> (condensed_refine) before anything is kept of it.
  subroutine condensed_solve(cd, m, cs, dm, u, finite, ncalls, defer)
    type(condensed_t), intent(inout) :: cd
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(inout) :: cs
    type(dofmap_t), intent(in) :: dm
    real(dp), intent(inout) :: u(:, :)
    logical, intent(out) :: finite
    integer(kind=8), intent(inout) :: ncalls
    logical, intent(in), optional :: defer
    real(dp) :: fc(cd%m), fx(cd%m)
    logical :: later
    later = .false.
    if (present(defer)) later = defer
    ! the CFE forces are affine in u: at the start, they are the constant part
    ! (a deferred status, which reads no CFE's gap at the start: only the
    ! CFEs whose state changed since the last status evaluated there)
    if (later .and. size(cd%cdep) == 0 .and. .not. any(cs%c(1:cs%n)%exact)) then
      call start_forces(cd, m, cs, dm, fc, ncalls)
    else
      call contact_part_forces(cd, m, cs, dm, cd%u0, fc, ncalls)
      cd%gap_start = cs%c(1:cs%n)%gap
    end if
    cd%x2 = cd%q0 - fc
    cd%qnext_fresh = .false.
    cd%refined = .true.
    cd%s0x_valid = .false.
    if (cd%lowrank) then
      call reference_product(cd, cd%x2, fx)
      if (later) then
        cd%rhs = cd%x2
        call apply_reference(cd, cd%x2, fx)
        cd%refined = .false.
      else
        call lowrank_solve(cd, cd%x2, fx)
      end if
    else
      call solve_s(cd, cd%x2)
    end if
    finite = all(ieee_is_finite(cd%x2))
    call add_contact_part(cd, dm, u)
    if (size(cd%cdep) > 0) call expand_dependent(dm, u, cd%cdep)
  end subroutine condensed_solve

  !> Purpose: the refinement condensed_solve deferred (defer): x2
  !> refined against S as lowrank_solve refines (the same steps on the
  !> same numbers: the settled status's answer is the one an undeferred
  !> solve gives), u's contact equations (and the dependent dofs at CFE
  !> nodes) moved to it. Nothing where x2 is refined already.
  !> Arguments: cd the condensed solve; dm the numbering; u the
  !> displacements of the last condensed_solve.
  subroutine condensed_refine(cd, dm, u)
    type(condensed_t), intent(inout) :: cd
    type(dofmap_t), intent(in) :: dm
    real(dp), intent(inout) :: u(:, :)
    if (cd%refined) return
    if (allocated(cd%s0x)) then
      if (size(cd%s0x) /= cd%m) deallocate(cd%s0x)
    end if
    if (.not. allocated(cd%s0x)) allocate(cd%s0x(cd%m))
    call refine_lowrank(cd, cd%rhs, cd%x2, cd%s0x, cd%rres, cd%s0x_valid)
    cd%refined = .true.
    call add_contact_part(cd, dm, u)
    if (size(cd%cdep) > 0) call expand_dependent(dm, u, cd%cdep)
  end subroutine condensed_refine

  !> Purpose: does exact enforcement take its multipliers directly
  !> (condensed_multipliers) in this contact set: some CFE is exact and
  !> none is frictional (a sliding CFE's force, mu times the normal one,
  !> moves with its multiplier, which the normal constraint rows alone do
  !> not carry: friction keeps the augmented Lagrangian,
  !> contact_status's augment_multipliers).
  pure logical function direct_multipliers(cs)
    type(contact_set_t), intent(in) :: cs
    direct_multipliers = any(cs%c(1:cs%n)%exact) .and. .not. frictional_set(cs)
  end function direct_multipliers

  !> Purpose: exact enforcement for the current status, solved directly
  !> after condensed_solve: the multipliers of the closed exact CFEs (the
  !> active constraints) that make their normal gaps vanish. The gap of
  !> CFE c is affine in the contact equations' displacements x2,
  !> g_c = g_c(u0) + b_c . x2 with b_c = B_e^T n (eq. 4; through the
  !> constraints' transformation where a dof is dependent), and a change
  !> dlambda of the multipliers adds B^T dlambda to the internal forces,
  !> so x2 moves by -S^-1 B^T dlambda. The gaps vanish for
  !>   (B S^-1 B^T) dlambda = g(x2),
  !> the Schur complement of the bordered (KKT) system of S and the active
  !> rows B, symmetric positive definite where the rows are independent
  !> (S is): with S = L L^T it is Z^T Z, Z = L^-1 B^T (one triangular
  !> solve with the active columns at once, dtrsm, and dsyrk), factored by
  !> LAPACK (dpotrf): one solve, exact to round-off.
  !> The closed penalty already in S then carries no force (its gap is
  !> zero) and the multipliers are the closed forces; open exact CFEs get
  !> lambda = 0. The status search decides the active set as for the
  !> penalty (the LCP of contact_status with 1/d = 0): no augmentation.
  !> Arguments: u as condensed_solve (the contact equations returned
  !> moved by the multipliers' change); nactive the active constraints
  !> (0: nothing solved); ok false where B S^-1 B^T is singular to working
  !> precision (dependent active rows): nothing changed then.
  subroutine condensed_multipliers(cd, m, cs, dm, u, nactive, ok)
    type(condensed_t), intent(inout) :: cd
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(inout) :: cs
    type(dofmap_t), intent(in) :: dm
    real(dp), intent(inout) :: u(:, :)
    integer, intent(out) :: nactive
    logical, intent(out) :: ok
    integer, allocatable :: act(:), geq(:)
    real(dp), allocatable :: z(:, :), w(:, :), g(:), t(:, :), bn(:), wdiag(:), dx(:, :)
    type(cfe_in_t) :: ein
    real(dp), allocatable :: bm(:, :)
    integer :: j, k, p, nd, info
    integer, allocatable :: nodes(:)
    ok = .true.
    where (cs%c(1:cs%n)%exact .and. .not. cs%c(1:cs%n)%closed) cs%c(1:cs%n)%lambda = 0.0_dp
    act = pack([(j, j = 1, cs%n)], cs%c(1:cs%n)%exact .and. cs%c(1:cs%n)%closed)
    nactive = size(act)
    if (nactive == 0) return
    ! B^T on the trailing positions (b_c = B_e^T n of each active CFE, a
    ! column) and the gaps at x2
    allocate(z(cd%m, nactive), w(nactive, nactive), g(nactive), dx(cd%m, 1))
    z = 0.0_dp
    do k = 1, nactive
      j = act(k)
      call cfe_input(m, cs%c(j), cd%u0, cs%stabilised, ein, nodes)
      nd = 2 * ein%nen
      if (allocated(bm)) deallocate(bm)
      allocate(bm(2, nd))
      call cfe_b_matrix(ein, bm)
      bn = matmul(cs%c(j)%normal, bm(:, 1:nd))
      if (has_dependent(dm, nodes(1:ein%nen))) then
        call group_transform(dm, nodes(1:ein%nen), geq, t)
        bn = matmul(bn, t)
      end if
      do p = 1, size(bn)
        if (cd%cfe_pos(p, j) > 0) z(cd%cfe_pos(p, j), k) = z(cd%cfe_pos(p, j), k) + bn(p)
      end do
      g(k) = cd%gap_start(j) + dot_product(z(:, k), cd%x2)
    end do
    ! with S = L L^T: Z = L^-1 B^T, B S^-1 B^T = Z^T Z (dtrsm, dsyrk)
    call lower_solve(cd%s, z, .false.)
    call transposed_gram(z, w)
    wdiag = [(w(k, k), k = 1, nactive)]
    call dense_factor(w, info)
    if (info == 0) then
      do k = 1, nactive
        ! a pivot lost to cancellation: dependent active rows
        if (.not. (w(k, k)**2 > 1.0e-13_dp * wdiag(k))) info = k
      end do
    end if
    if (info /= 0) then
      ok = .false.
      return
    end if
    call dense_solve(w, g)
    ! x2 -= S^-1 B^T dlambda = L^-T (Z dlambda)
    dx(:, 1) = matmul(z, g)
    call lower_solve(cd%s, dx, .true.)
    cd%x2 = cd%x2 - dx(:, 1)
    do k = 1, nactive
      cs%c(act(k))%lambda = cs%c(act(k))%lambda + g(k)
    end do
    call add_contact_part(cd, dm, u)
    if (size(cd%cdep) > 0) call expand_dependent(dm, u, cd%cdep)
  end subroutine condensed_multipliers

  !> Purpose: the potential energy of the displacements u relative to
  !> the increment's start (u0), up to a constant of the increment, with
  !> the contact equations' displacements x = u - u0 and the other
  !> equations at their best for them: 1/2 x.S0 x - q0.x (the condensed
  !> bodies and open CFEs of K0, the condensed out-of-balance at u0)
  !> minus the open CFEs' share of S0, 1/2 k_open (gap change)^2, which
  !> the caller's contact_energy counts in full. cs holds the gaps at u
  !> (its last evaluation).
  real(dp) function condensed_energy(cd, dm, cs, u) result(e)
    type(condensed_t), intent(in) :: cd
    type(dofmap_t), intent(in) :: dm
    type(contact_set_t), intent(in) :: cs
    real(dp), intent(in) :: u(:, :)
    real(dp) :: x(cd%m), sx
    integer :: p, q, eqn, nd, nn
    do p = 1, cd%m
      eqn = cd%eq_at(p)
      nd = dm%dof_of_eq(eqn)
      nn = dm%node_of_eq(eqn)
      x(p) = u(nd, nn) - cd%u0(nd, nn)
    end do
    ! S0 is kept as its diagonal and strict lower triangle
    e = 0.0_dp
    do q = 1, cd%m
      sx = 0.5_dp * cd%s0_diag(q) * x(q) + dot_product(cd%l22(q + 1:cd%m, q), x(q + 1:cd%m))
      e = e + x(q) * sx - cd%q0(q) * x(q)
    end do
    ! (keep_pairing: S0 is the bodies' alone, no CFE's share in it)
    if (.not. cd%keep_pairing) e = e - 0.5_dp * sum(cs%c(1:cs%n)%k_open * (cs%c(1:cs%n)%gap - cd%gap_start)**2)
  end function condensed_energy

  !> x := S^-1 x with the factor of the current status (or its low-rank
  !> form about the reference, lowrank_solve).
  subroutine solve_s(cd, x)
    type(condensed_t), intent(in) :: cd
    real(dp), intent(inout) :: x(:)
    if (cd%lowrank) then
      call lowrank_solve(cd, x)
    else if (cd%lu) then
      call lu_solve(cd%s, cd%ipiv, x)
    else
      call dense_solve(cd%s, x)
    end if
  end subroutine solve_s

  !> x := S^-1 x for a status of the low-rank form: M = S_ref + E dmat E^T
  !> solved by the capacitance matrix (Woodbury's identity: with
  !> F = S_ref^-1 and y = F r, E^T x = cap^-1 E^T y and
  !> x = y - F E dmat E^T x), then refined against S itself: r - S x
  !> solved by M again and added. A correction c of x is about
  !> rho |x| with rho = |M^-1 (S - M)| (the open CFEs' share of S - M,
  !> 1e-12 of a closed one's, and Woodbury's round-off), and leaves an
  !> error of about rho |c| = |c|^2 / |x|: the refinement stops once a
  !> correction is below 1e-8 of x (the error left below 1e-16 of x, the
  !> round-off of S's own solution), or no longer half the last one (the
  !> round-off floor), at most max_refine times. Measured on McColl's
  !> case: the first correction 3e-13 of x, so one refinement.
  !> Arguments: fx, if present, S_ref^-1 x (reference_product).
  subroutine lowrank_solve(cd, x, fx)
    type(condensed_t), intent(in) :: cd
    real(dp), intent(inout) :: x(:)
    real(dp), intent(in), optional :: fx(:)
    real(dp) :: r(size(x))
    r = x
    call apply_reference(cd, x, fx)
    call refine_lowrank(cd, r, x)
  end subroutine lowrank_solve

  !> x, M^-1 r for a status of the low-rank form (apply_reference),
  !> refined against S itself (lowrank_solve says how far).
  !> s0x, rres, estimated: if present, S0 x of the refined x from the last
  !> correction's product and rres = |r - S x_k| (norm2), the residual of
  !> x_k, the solution before that correction dx = M^-1 (r - S x_k):
  !> S0 (x_k + dx) = S0 x_k + (r - S x_k) - T dx + (M - S) dx, T the
  !> status's tangents, and (M - S) dx (the open CFEs' share and
  !> Woodbury's round-off, times the last correction) is left out: about
  !> |dx|^2 / |x| of S x, round-off once the refinement has stopped on a
  !> small or no longer halving correction (estimated true; false where
  !> it ran out of corrections: the caller makes the product).
  subroutine refine_lowrank(cd, r, x, s0x, rres, estimated)
    type(condensed_t), intent(in) :: cd
    real(dp), intent(in) :: r(:)
    real(dp), intent(inout) :: x(:)
    real(dp), intent(out), optional :: s0x(:), rres
    logical, intent(out), optional :: estimated
    integer, parameter :: max_refine = 3
    real(dp) :: dx(size(x)), sx(size(x)), tdx(size(x)), last, now
    integer :: it
    logical :: stopped
    last = huge(1.0_dp)
    stopped = .false.
    do it = 1, max_refine
      call status_times(cd, x, dx, sx)
      dx = r - dx
      if (present(rres)) rres = norm2(dx)
      if (present(s0x)) s0x = sx + dx
      call apply_reference(cd, dx)
      x = x + dx
      now = maxval(abs(dx))
      stopped = .not. (now > 1.0e-8_dp * maxval(abs(x)) .and. now <= 0.5_dp * last)
      if (stopped) exit
      last = now
    end do
    if (present(estimated)) estimated = stopped
    if (.not. present(s0x)) return
    tdx = 0.0_dp
    call add_tangents_times(cd, dx, tdx)
    s0x = s0x - tdx
  end subroutine refine_lowrank

  !> x := M^-1 x, M = S_ref + E dmat E^T (lowrank_solve); fx, if present,
  !> is S_ref^-1 x.
  subroutine apply_reference(cd, x, fx)
    type(condensed_t), intent(in) :: cd
    real(dp), intent(inout) :: x(:)
    real(dp), intent(in), optional :: fx(:)
    real(dp) :: y(size(x)), w(size(cd%dset)), v(size(cd%dset))
    integer :: i, j
    ! (explicit loops in a fixed order, as capacitance)
    if (present(fx)) then
      y = fx
    else
      call sym_times(cd%finv, x, y)
    end if
    w = y(cd%dset)
    call lu_solve(cd%cap, cd%cap_piv, w)
    v = 0.0_dp
    do j = 1, size(w)
      v = v + w(j) * cd%dmat(:, j)
    end do
    ! four columns of finv at a time (one pass over y for four)
    i = 1
    do while (i + 3 <= size(v))
      y = y - ((v(i) * cd%finv(:, cd%dset(i)) + v(i + 1) * cd%finv(:, cd%dset(i + 1))) + &
               (v(i + 2) * cd%finv(:, cd%dset(i + 2)) + v(i + 3) * cd%finv(:, cd%dset(i + 3))))
      i = i + 4
    end do
    do j = i, size(v)
      y = y - v(j) * cd%finv(:, cd%dset(j))
    end do
    x = y
  end subroutine apply_reference

  !> Purpose: y = S_ref^-1 b (finv b). Where the last product's b differs
  !> from this one in at most an eighth of its entries (the statuses of
  !> an increment: the couplings that changed), from that product and
  !> the columns of the entries that changed, at most max_chain times in
  !> a row; otherwise whole (sym_times). Its round-off is the
  !> refinement's to take out (lowrank_solve).
  subroutine reference_product(cd, b, y)
    type(condensed_t), intent(inout) :: cd
    real(dp), intent(in) :: b(:)
    real(dp), intent(out) :: y(:)
    integer, parameter :: max_chain = 8
    integer :: j, nd
    integer, allocatable :: changed(:)
    nd = size(b) + 1
    if (cd%fb_valid .and. cd%fb_chain < max_chain) then
      if (size(cd%fb_x) == size(b)) then
        changed = pack([(j, j = 1, size(b))], b /= cd%fb_x)
        nd = size(changed)
      end if
    end if
    if (8 * nd <= size(b)) then
      y = cd%fb_y
      do j = 1, nd
        y = y + (b(changed(j)) - cd%fb_x(changed(j))) * cd%finv(:, changed(j))
      end do
      cd%fb_x = b
      cd%fb_y = y
      cd%fb_chain = cd%fb_chain + 1
      return
    end if
    call sym_times(cd%finv, b, y)
    cd%fb_x = b
    cd%fb_y = y
    cd%fb_valid = .true.
    cd%fb_chain = 0
  end subroutine reference_product

  !> y = S x for the status whose tangents are kt_all: S0 (s0_times)
  !> plus every CFE's tangent on its positions (keep_pairing: ke0 is
  !> zero); s0x, if present, returns S0 x.
  subroutine status_times(cd, x, y, s0x)
    type(condensed_t), intent(in) :: cd
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: y(:)
    real(dp), intent(out), optional :: s0x(:)
    call s0_times(cd, x, y)
    if (present(s0x)) s0x = y
    call add_tangents_times(cd, x, y)
  end subroutine status_times

  !> y += T x, T every CFE's tangent in kt_all on its positions.
  subroutine add_tangents_times(cd, x, y)
    type(condensed_t), intent(in) :: cd
    real(dp), intent(in) :: x(:)
    real(dp), intent(inout) :: y(:)
    integer :: j, a, b, pa, pb
    do j = 1, size(cd%kt_ng)
      do b = 1, cd%kt_ng(j)
        pb = cd%cfe_pos(b, j)
        if (pb == 0) cycle
        do a = 1, cd%kt_ng(j)
          pa = cd%cfe_pos(a, j)
          if (pa > 0) y(pa) = y(pa) + cd%kt_all(a, b, j) * x(pb)
        end do
      end do
    end do
  end subroutine add_tangents_times

  !> Purpose: y = S0 x, S0 from its diagonal and strict lower triangle
  !> (with keep_pairing the bodies' Schur complement alone; sym_times).
  subroutine s0_times(cd, x, y)
    type(condensed_t), intent(in) :: cd
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: y(:)
    call sym_times(cd%l22, x, y, cd%s0_diag)
  end subroutine s0_times

  !> Purpose: y = A x for a symmetric matrix A of which only the strict
  !> lower triangle is read, and the diagonal d (A's own where d is
  !> absent): half the memory of a whole product, which bounds these
  !> products. Four columns at a time: their four dot products with x
  !> and one update of y per row (0.043 ms against a whole product's
  !> 0.070 for m = 512 on this machine's EPYC, the optimised build); the
  !> sums in a fixed order, the same in every build.
  pure subroutine sym_times(a, x, y, d)
    real(dp), intent(in), contiguous :: a(:, :), x(:)
    real(dp), intent(out), contiguous :: y(:)
    real(dp), intent(in), optional, contiguous :: d(:)
    integer :: i, j, c, mc
    real(dp) :: s(4), xc(4)
    mc = size(x)
    do j = 1, mc
      if (present(d)) then
        y(j) = d(j) * x(j)
      else
        y(j) = a(j, j) * x(j)
      end if
    end do
    j = 1
    do while (j + 3 <= mc)
      ! the strict lower part of the 4 x 4 block on the diagonal
      do c = j, j + 2
        do i = c + 1, j + 3
          y(i) = y(i) + a(i, c) * x(c)
          y(c) = y(c) + a(i, c) * x(i)
        end do
      end do
      xc = x(j:j + 3)
      s = 0.0_dp
      do i = j + 4, mc
        y(i) = y(i) + ((a(i, j) * xc(1) + a(i, j + 1) * xc(2)) + (a(i, j + 2) * xc(3) + a(i, j + 3) * xc(4)))
        s(1) = s(1) + a(i, j) * x(i)
        s(2) = s(2) + a(i, j + 1) * x(i)
        s(3) = s(3) + a(i, j + 2) * x(i)
        s(4) = s(4) + a(i, j + 3) * x(i)
      end do
      y(j:j + 3) = y(j:j + 3) + s
      j = j + 4
    end do
    do c = j, mc - 1
      y(c + 1:mc) = y(c + 1:mc) + a(c + 1:mc, c) * x(c)
      y(c) = y(c) + dot_product(a(c + 1:mc, c), x(c + 1:mc))
    end do
  end subroutine sym_times

  !> Purpose: cd%moving_elems for the numbering dm (made once per factor
  !> of K0, which every numbering has before an increment starts): the elements with a node one
  !> of whose dofs is not an equation. Where an increment starts from the
  !> last one's solution on every equation, only their nodes move, and
  !> add_body_forces with this list gives its whole loop's sums in its
  !> order (a twelfth of a fretting increment was that loop over every
  !> element).
  subroutine moving_elements(cd, m, dm)
    type(condensed_t), intent(inout) :: cd
    type(model_t), intent(in) :: m
    type(dofmap_t), intent(in) :: dm
    logical :: fixed(size(dm%eq, 2))
    integer :: e, n
    if (allocated(cd%moving_elems)) return
    fixed = dm%eq(1, :) <= 0 .or. dm%eq(2, :) <= 0
    allocate(cd%moving_elems(m%ne))
    n = 0
    do e = 1, m%ne
      if (.not. any(fixed(m%conn(1:elem_nodes(m, e), e)))) cycle
      n = n + 1
      cd%moving_elems(n) = e
    end do
    cd%moving_elems = cd%moving_elems(1:n)
  end subroutine moving_elements

  !> u(contact equations) = u0 + x2.
  subroutine add_contact_part(cd, dm, u)
    type(condensed_t), intent(in) :: cd
    type(dofmap_t), intent(in) :: dm
    real(dp), intent(inout) :: u(:, :)
    integer :: p, e
    do p = 1, cd%m
      e = cd%eq_at(p)
      u(dm%dof_of_eq(e), dm%node_of_eq(e)) = cd%u0(dm%dof_of_eq(e), dm%node_of_eq(e)) + cd%x2(p)
    end do
  end subroutine add_contact_part

  !> Purpose: the other equations of the last condensed_solve: the
  !> backward half of a solve of [z1; L22^T x2]; u returns the whole
  !> solution (the contact equations exactly as the status iteration had
  !> them), dependent dofs included.
  subroutine condensed_recover(cd, dm, sys, u)
    type(condensed_t), intent(in) :: cd
    type(dofmap_t), intent(in) :: dm
    type(linear_system_t), intent(inout) :: sys
    real(dp), intent(inout) :: u(:, :)
    real(dp), allocatable :: w(:), t(:)
    integer :: e
    w = cd%z
    t = cd%x2
    call upper_times(cd%l22, t, .false.)
    w(cd%n - cd%m + 1:cd%n) = t
    call sys_backward(sys, w)
    do e = 1, cd%n
      u(dm%dof_of_eq(e), dm%node_of_eq(e)) = cd%u0(dm%dof_of_eq(e), dm%node_of_eq(e)) + w(e)
    end do
    call add_contact_part(cd, dm, u)
    call expand_dependent(dm, u)
  end subroutine condensed_recover

  !> Purpose: r(n) := K^-1 r with K the matrix of the current status
  !> (forward half, the condensed matrix, backward half): a correction
  !> when the recovered solution is not yet in balance.
  subroutine condensed_correct(cd, sys, r)
    type(condensed_t), intent(in) :: cd
    type(linear_system_t), intent(inout) :: sys
    real(dp), intent(inout) :: r(:)
    real(dp), allocatable :: t(:)
    call sys_forward(sys, r)
    t = r(cd%n - cd%m + 1:cd%n)
    call upper_times(cd%l22, t, .true.)
    call solve_s(cd, t)
    call upper_times(cd%l22, t, .false.)
    r(cd%n - cd%m + 1:cd%n) = t
    call sys_backward(sys, r)
  end subroutine condensed_correct
end module condensed_contact
