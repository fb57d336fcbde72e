!> The element arrays of the bodies and their assembly. In a linear step
!> (small deformation, linear elastic materials) the element stiffness
!> matrices are computed once and kept (`body_t`); internal forces are
!> then ke * ue, and only the coupling elements are evaluated again as the
!> contact status changes. In a nonlinear step (NLGEOM, a hyperelastic or
!> plastic material; body_t%nonlinear) every body element is evaluated by
!> its routine at the current displacements: its tangent for the
!> assembly, its internal force and its trial history for the residual;
!> the history committed by the last converged increment is kept per
!> element and integration point (body_t%hist) and replaced by the trial
!> one only by commit_history. Stresses are computed once per written
!> increment: by the element routines, or in a linear step, for the
!> isotropic linear elastic continuum elements, by linear_stresses from
!> the coordinates and per-type shape tables (the element call's records
!> cost more than its arithmetic; nothing is stored). A thermal strain enters as a
!> load (`thermal_forces`) and in the stresses; the stiffness does not
!> change. So does an initial stress (*INITIAL CONDITIONS, TYPE=STRESS,
!> linear steps only): sig = D eps + sig0, its load -integral B^T sig0 dV
!> (`initial_stress_forces`) and sig0 added to the recovered stresses.
!>
!> Threads (OpenMP, blas_info's element_threads: OMP_NUM_THREADS, else
!> one): the element loops of the stored stiffness, the internal forces
!> (linear and nonlinear), the nonlinear tangents and the stresses compute
!> each element's arrays on the team into storage of their own, a block
!> of block_size elements at a time; the sums into the global vector and
!> matrix, the counts and the largest entries are then made by one thread
!> in element order, as without threads: the results are the same bits
!> for any thread count. Nothing inside a parallel region writes anything
!> but its own element's storage (an element that cannot be evaluated is
!> flagged there and reported after the loop).
module assembly
  use kinds, only: dp
  use strings, only: itoa
  use messages, only: fatal
  use model
  use element_catalogue, only: catalogue
  use contact, only: contact_set_t, cfe_input
  use element_interface, only: elem_in_t, elem_out_t, cfe_in_t, cfe_out_t, max_en, act_tangent, act_stresses, act_thermal, &
                               act_residual, max_hist, max_edof
  use element_catalogue, only: max_ip, max_nodes, state_plane_stress, shape_quad4, state_axisymmetric
  use materials, only: elastic_matrix
  use distributed_loads, only: follower_pressure_load
  use element_library, only: element_routine, thickness_stretch
  use continuum_element, only: strain_matrix, volume_factor, is_one_point_quad, uniform_strain
  use shape_functions, only: shape_at, gauss_rule, extrapolation
  use cfe_element, only: cfe
  use body_elements, only: body_input, body_alpha
  use linear_solver, only: linear_system_t, sys_zero, sys_add
  use blas_info, only: element_threads, team_open, team_close
  use dof_numbering, only: dofmap_t, has_dependent, group_transform, reduce_dependent
  implicit none
  private
  public :: body_t, element_counts_t, body_setup, assemble_stiffness, body_forces, free_residual, &
            stress_recovery, thermal_forces, nonlinear_body_forces, commit_history, nonlinear_model, &
            body_predictor_forces, initial_stress_forces

  !> Stored element stiffness of every body element: the upper
  !> triangle of the symmetric nd x nd matrix of element e, column by
  !> column, in ke(kptr(e) : kptr(e+1)-1).
  type :: body_t
    integer(kind=8), allocatable :: kptr(:)
    real(dp), allocatable :: ke(:)
    real(dp) :: kmax = 0.0_dp     ! largest diagonal entry of an element matrix
    !> The current step is nonlinear: element routines at the current u
    !> (nlgeom: with large deformation).
    logical :: nonlinear = .false., nlgeom = .false.
    !> History at the integration points (max_hist, max_ip, ne): hist as
    !> committed by the last converged increment, hist_trial at the last
    !> evaluation of the internal forces; peeq and peeq_trial (max_ip, ne)
    !> the equivalent plastic strain likewise. Allocated once the model is
    !> known to have a nonlinear step.
    real(dp), allocatable :: hist(:, :, :), hist_trial(:, :, :), peeq(:, :), peeq_trial(:, :)
    !> the committed history before the last commit: the tangent at a
    !> converged state is the one of its last iteration (assemble_stiffness
    !> with converged, body_predictor_forces)
    real(dp), allocatable :: hist_old(:, :, :)
    !> The last evaluation at u met an element that cannot be evaluated
    !> there (an inverted element, det F <= 0, or a number that is not
    !> finite): bad_elem is it (0: none). The increment is cut back.
    integer :: bad_elem = 0
    !> Nodal temperature changes at the time of the increment being solved
    !> (nn; allocated only when the model has thermal strain): in a
    !> nonlinear step the element routines take them into their internal
    !> force.
    real(dp), allocatable :: dtemp(:)
    !> ... and at the converged state the increment starts from (the
    !> first iteration is linearised about it, body_predictor_forces).
    real(dp), allocatable :: dtemp0(:)
    !> Follower pressures of a NLGEOM step (*DLOAD P on the deformed
    !> faces), set by the driver for the increment being solved: load k
    !> acts on face fl_face(k) of element fl_elem(k) with magnitude
    !> fl_mag(k); those of element e are k = fl_ptr(e) .. fl_ptr(e+1)-1.
    !> Their forces enter the internal force with the opposite sign (f_int
    !> - f_p(u)) and their load stiffness the tangent (K_T - p dfp/du).
    integer, allocatable :: fl_ptr(:), fl_face(:)
    real(dp), allocatable :: fl_mag(:)
    !> CalculiX's average force q-bar of the last evaluation: the mean
    !> |f| over the element dofs of the body elements (its manual,
    !> "Convergence criteria").
    real(dp) :: average_force = 0.0_dp
  end type body_t

  !> The shape functions n, natural derivatives dn and extrapolation ex
  !> to the nodes at the integration points of one catalogue entry (the
  !> stress recovery's, built when an element of the type first needs it).
  type :: point_table_t
    logical :: ready = .false.
    real(dp) :: n(max_nodes, max_ip), dn(2, max_nodes, max_ip), ex(max_nodes, max_ip)
  end type point_table_t

  !> Elements whose arrays the team computes before one thread sums them
  !> (the storage of a block of tangents: 4 MB).
  integer, parameter :: block_size = 2048

  !> How often element routines ran, by purpose.
  type :: element_counts_t
    integer(kind=8) :: continuum_tangent = 0, continuum_stresses = 0, coupling = 0
  end type element_counts_t

contains

  !> Purpose: f = f + the equivalent nodal loads of the thermal strain of
  !> every body element at nodal temperature changes dtemp(nn). Under
  !> NLGEOM (nlgeom) and with a plastic material the element routines
  !> take the thermal strain into their internal force instead (their
  !> act_thermal gives zero): the body's dtemp carries it there.
  subroutine thermal_forces(m, dtemp, f, nlgeom)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: dtemp(:)
    real(dp), intent(inout) :: f(:, :)
    logical, intent(in) :: nlgeom
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    integer :: e, k, nodes(max_en)
    real(dp), allocatable :: u0(:, :)
    allocate(u0(2, m%nn))
    u0 = 0.0_dp
    do e = 1, m%ne
      if (.not. carries_stiffness(m, e)) cycle
      if (body_alpha(m, e) == 0.0_dp) cycle
      call body_input(m, e, u0, ein, nodes, dtemp, nlgeom=nlgeom)
      if (all(ein%dtemp(1:ein%nen) == 0.0_dp)) cycle
      call element_routine(act_thermal, ein, eout)
      do k = 1, ein%nen
        f(:, nodes(k)) = f(:, nodes(k)) + eout%fe(2 * k - 1:2 * k)
      end do
    end do
  end subroutine thermal_forces

  !> Purpose: f = f - integral B^T sig0 dV over every element with an
  !> initial stress (m%sig0): with sig = D eps + sig0 the internal force is
  !> K u + integral B^T sig0 dV, so the initial stress is a load, and a
  !> self-equilibrated one (no net nodal force) leaves u = 0. Each
  !> element's own rule and B matrix (the one-point quadrilateral's mean
  !> B, as its stiffness).
  !> Arguments: m the model; f(2, nn) the nodal loads, added to.
  subroutine initial_stress_forces(m, f)
    type(model_t), intent(in) :: m
    real(dp), intent(inout) :: f(:, :)
    type(elem_in_t) :: ein
    real(dp) :: xg(2, max_ip), wg(max_ip), n(max_nodes), dn(2, max_nodes), b(4, 2 * max_nodes), detj, r, dv, &
                eps0(4), fe(2 * max_nodes)
    integer :: e, k, ip, nen, nd, nodes(max_en)
    real(dp), allocatable :: u0(:, :)
    if (.not. allocated(m%sig0)) return
    allocate(u0(2, m%nn))
    u0 = 0.0_dp
    do e = 1, min(m%ne, size(m%sig0, 3))
      if (.not. any(m%sig0(:, :, e) /= 0.0_dp)) cycle
      call body_input(m, e, u0, ein, nodes)
      nen = ein%nen
      nd = 2 * nen
      call gauss_rule(ein%kind, ein%nip, xg, wg)
      fe = 0.0_dp
      do ip = 1, ein%nip
        call shape_at(ein%kind, xg(:, ip), n, dn)
        call strain_matrix(nen, ein%xy(:, 1:nen), n(1:nen), dn(:, 1:nen), ein%state, b(:, 1:nd), detj, r)
        dv = volume_factor(ein%state, detj, r, dot_product(n(1:nen), ein%thickness(1:nen))) * wg(ip)
        if (is_one_point_quad(ein)) call uniform_strain(ein, n, b(:, 1:nd), dv, eps0)
        fe(1:nd) = fe(1:nd) + matmul(m%sig0(:, ip, e), b(:, 1:nd)) * dv
      end do
      do k = 1, nen
        f(:, nodes(k)) = f(:, nodes(k)) - fe(2 * k - 1:2 * k)
      end do
    end do
  end subroutine initial_stress_forces

  !> Purpose: computes and keeps the stiffness of every body element
  !> (continuum elements, trusses, springs), on the element team: each
  !> element's matrix into its own slice of body%ke; the count, the
  !> largest diagonal entry and the first element with a bad Jacobian
  !> found after, in element order.
  subroutine body_setup(m, body, counts)
    type(model_t), intent(in) :: m
    type(body_t), intent(out) :: body
    type(element_counts_t), intent(inout) :: counts
    integer :: e, nd, j, nt, bad
    integer(kind=8) :: k
    real(dp), allocatable :: u0(:, :)
    allocate(body%kptr(m%ne + 1), u0(2, m%nn))
    u0 = 0.0_dp
    body%kptr(1) = 1
    do e = 1, m%ne
      nd = 0
      if (carries_stiffness(m, e)) nd = 2 * elem_nodes(m, e)
      body%kptr(e + 1) = body%kptr(e) + int(nd, 8) * (nd + 1) / 2
    end do
    allocate(body%ke(body%kptr(m%ne + 1) - 1))
    bad = huge(bad)
    nt = element_threads()
    call team_open()
    !$omp parallel do num_threads(nt) if (nt > 1) schedule(dynamic, 64) default(shared) private(e) &
    !$omp reduction(min: bad)
    do e = 1, m%ne
      if (.not. carries_stiffness(m, e)) cycle
      if (.not. stored_stiffness(m, e, u0, body%ke(body%kptr(e):body%kptr(e + 1) - 1))) bad = min(bad, e)
    end do
    !$omp end parallel do
    call team_close()
    if (bad < huge(bad)) call fatal('element ' // elem_label(m, bad) // ' (' // &
      trim(catalogue(m%etype(bad))%name) // ') has a zero or negative Jacobian at an integration point: ' // &
      'a mid-side node far from the middle of its edge, an axisymmetric element reaching x < 0, or a ' // &
      'NODAL THICKNESS that the element interpolates to zero or less')
    do e = 1, m%ne
      if (.not. carries_stiffness(m, e)) cycle
      counts%continuum_tangent = counts%continuum_tangent + 1
      nd = 2 * elem_nodes(m, e)
      ! the diagonal of the packed upper triangle: entry j(j+1)/2 of column j
      do j = 1, nd
        k = body%kptr(e) - 1 + int(j, 8) * (j + 1) / 2
        body%kmax = max(body%kmax, abs(body%ke(k)))
      end do
    end do
    if (nonlinear_model(m)) then
      allocate(body%hist(max_hist, max_ip, m%ne), body%peeq(max_ip, m%ne))
      body%hist = 0.0_dp
      body%peeq = 0.0_dp
      body%hist_trial = body%hist
      body%hist_old = body%hist
      body%peeq_trial = body%peeq
    end if
  end subroutine body_setup

  !> Purpose: the stiffness of body element e at u0 (zero), packed (upper
  !> triangle by columns) into kp; false if its Jacobian is not positive
  !> at some integration point (kp then undefined). One element's work of
  !> body_setup's team: it writes kp only.
  logical function stored_stiffness(m, e, u0, kp)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    real(dp), intent(in) :: u0(:, :)
    real(dp), intent(out) :: kp(:)
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    integer :: nodes(max_en), nd
    call body_input(m, e, u0, ein, nodes)
    call element_routine(act_tangent, ein, eout)
    stored_stiffness = eout%detj_min > 0.0_dp
    if (.not. stored_stiffness) return
    nd = eout%ndof
    call pack_upper(eout%ke(1:nd, 1:nd), kp)
  end function stored_stiffness

  !> Purpose: whether some step of model m is nonlinear: NLGEOM, or a
  !> hyperelastic or plastic material in a section.
  pure logical function nonlinear_model(m)
    type(model_t), intent(in) :: m
    nonlinear_model = nonlinear_material(m)
    if (allocated(m%steps)) nonlinear_model = nonlinear_model .or. any(m%steps%nlgeom)
  end function nonlinear_model

  !> Purpose: the trial history of the last evaluation (at the converged
  !> displacements) becomes the committed one: called once per converged
  !> increment, by the driver's commit_increment.
  subroutine commit_history(body)
    type(body_t), intent(inout) :: body
    if (.not. allocated(body%hist)) return
    body%hist_old = body%hist
    body%hist = body%hist_trial
    body%peeq = body%peeq_trial
  end subroutine commit_history

  !> Purpose: internal forces of the bodies at u in a nonlinear step: every
  !> body element's routine at u with its committed history (act_residual);
  !> their trial history and plastic strain are kept (body%hist_trial),
  !> the average force q-bar too. An element that cannot be evaluated at u
  !> (det F <= 0 or a force that is not finite) sets body%bad_elem (the
  !> first such in element order). The elements on the team a block at a
  !> time (element_force); their forces summed into fint, and q-bar's sums
  !> made, by one thread in element order.
  subroutine nonlinear_body_forces(m, body, u, fint, counts)
    type(model_t), intent(in) :: m
    type(body_t), intent(inout) :: body
    real(dp), intent(in) :: u(:, :)
    real(dp), intent(out) :: fint(:, :)
    type(element_counts_t), intent(inout) :: counts
    integer :: e, e0, k, nt, ndof_total
    integer, allocatable :: st(:), nd(:)
    real(dp), allocatable :: fe(:, :), fabs(:)
    real(dp) :: fsum
    allocate(fe(max_edof, block_size), fabs(block_size), st(block_size), nd(block_size))
    fint = 0.0_dp
    body%bad_elem = 0
    fsum = 0.0_dp
    ndof_total = 0
    nt = element_threads()
    call team_open()
    do e0 = 1, m%ne, block_size
      !$omp parallel do num_threads(nt) if (nt > 1) schedule(dynamic, 16) default(shared) private(e)
      do e = e0, min(m%ne, e0 + block_size - 1)
        call element_force(m, body, u, e, fe(:, e - e0 + 1), fabs(e - e0 + 1), st(e - e0 + 1), nd(e - e0 + 1))
      end do
      !$omp end parallel do
      do e = e0, min(m%ne, e0 + block_size - 1)
        if (st(e - e0 + 1) == 0) cycle
        counts%continuum_tangent = counts%continuum_tangent + 1
        if (st(e - e0 + 1) == 2) then
          if (body%bad_elem == 0) body%bad_elem = e
          cycle
        end if
        fsum = fsum + fabs(e - e0 + 1)
        ndof_total = ndof_total + nd(e - e0 + 1)
        do k = 1, elem_nodes(m, e)
          fint(:, m%conn(k, e)) = fint(:, m%conn(k, e)) + fe(2 * k - 1:2 * k, e - e0 + 1)
        end do
      end do
    end do
    call team_close()
    body%average_force = fsum / max(ndof_total, 1)
  end subroutine nonlinear_body_forces

  !> Purpose: one element's work of nonlinear_body_forces' team: the
  !> internal force fe of body element e at u (with its follower
  !> pressures), fabs the sum of |f| over its dofs before them (q-bar's
  !> share), its trial history into body%hist_trial(:, :, e) and
  !> peeq_trial(:, e) (the element's own slices: nothing else of body is
  !> written). st: 0 not a body element, 1 evaluated, 2 cannot be
  !> evaluated at u (fe, fabs and the trial history then untouched); nd
  !> the element's dofs.
  subroutine element_force(m, body, u, e, fe, fabs, st, nd)
    type(model_t), intent(in) :: m
    type(body_t), intent(inout) :: body
    real(dp), intent(in) :: u(:, :)
    integer, intent(in) :: e
    real(dp), intent(inout) :: fe(:), fabs
    integer, intent(out) :: st, nd
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    integer :: nodes(max_en)
    real(dp) :: ke_dummy(1, 1)
    st = 0
    nd = 0
    if (.not. carries_stiffness(m, e)) return
    ! (an unallocated body%dtemp is an absent argument: no thermal strain)
    call body_input(m, e, u, ein, nodes, body%dtemp, nlgeom=body%nlgeom, hist=body%hist(:, :, e))
    call element_routine(act_residual, ein, eout)
    nd = eout%ndof
    st = 2
    if (.not. (eout%detj_min > 0.0_dp .and. all(abs(eout%fe(1:nd)) <= huge(1.0_dp)))) return
    st = 1
    body%hist_trial(:, :, e) = eout%hist
    body%peeq_trial(:, e) = eout%peeq_ip
    fabs = sum(abs(eout%fe(1:nd)))
    if (allocated(body%fl_ptr)) call follower_part(m, body, e, u, ein, eout%fe, ke_dummy, .false.)
    fe(1:nd) = eout%fe(1:nd)
  end subroutine element_force

  !> The upper triangle of a symmetric matrix, column by column.
  pure subroutine pack_upper(a, p)
    real(dp), intent(in) :: a(:, :)
    real(dp), intent(out) :: p(:)
    integer :: i, j, k
    k = 0
    do j = 1, size(a, 2)
      do i = 1, j
        k = k + 1
        p(k) = a(i, j)
      end do
    end do
  end subroutine pack_upper

  pure subroutine unpack_upper(p, a)
    real(dp), intent(in) :: p(:)
    real(dp), intent(out) :: a(:, :)
    integer :: i, j, k
    k = 0
    do j = 1, size(a, 2)
      do i = 1, j
        k = k + 1
        a(i, j) = p(k)
        a(j, i) = p(k)
      end do
    end do
  end subroutine unpack_upper

  !> Purpose: the first iteration of a nonlinear increment whose
  !> prescribed displacements moved by du from the converged u0: the
  !> bodies' internal forces linearised about u0, f = f_int(u0) + K_T(u0)
  !> du (overwritten), so that the first solve spreads the prescribed
  !> motion through the body by the tangent instead of meeting it in the
  !> elements next to the prescribed nodes only (which a large step could
  !> invert). Both are those of the last iteration of the increment that
  !> converged at u0 (from the history before its commit, body%hist_old):
  !> evaluated from the committed history at u0 itself, a point on the
  !> yield surface would be elastic or plastic by round-off, and the
  !> builds would take different first iterations. f0, if given, is
  !> f_int(u0) of that last iteration (the caller's, without follower
  !> pressures or thermal strain, which move with the increment): then only
  !> the elements that du moves are evaluated, for K_T(u0) du.
  subroutine body_predictor_forces(m, body, u0, du, f, counts, f0)
    type(model_t), intent(in) :: m
    type(body_t), intent(in) :: body
    real(dp), intent(in) :: u0(:, :), du(:, :)
    real(dp), intent(out) :: f(:, :)
    type(element_counts_t), intent(inout) :: counts
    real(dp), intent(in), optional :: f0(:, :)
    integer :: e, e0, k, nt
    real(dp), allocatable :: fe(:, :)
    logical, allocatable :: moved(:)
    logical :: moved_only
    moved_only = present(f0) .and. .not. allocated(body%dtemp0)
    if (allocated(body%fl_ptr)) moved_only = moved_only .and. body%fl_ptr(size(body%fl_ptr)) == body%fl_ptr(1)
    allocate(fe(max_edof, block_size), moved(block_size))
    f = 0.0_dp
    if (moved_only) f = f0
    nt = element_threads()
    ! each element's f_int + K_T du (K_T du alone with f0) on the team, a
    ! block at a time; the sum into f in element order
    call team_open()
    do e0 = 1, m%ne, block_size
      !$omp parallel do num_threads(nt) if (nt > 1) schedule(dynamic, 16) default(shared) private(e)
      do e = e0, min(m%ne, e0 + block_size - 1)
        moved(e - e0 + 1) = carries_stiffness(m, e)
        if (moved_only .and. moved(e - e0 + 1)) moved(e - e0 + 1) = any(du(:, m%conn(1:elem_nodes(m, e), e)) /= 0.0_dp)
        if (moved(e - e0 + 1)) call predictor_force(m, body, u0, du, e, moved_only, fe(:, e - e0 + 1))
      end do
      !$omp end parallel do
      do e = e0, min(m%ne, e0 + block_size - 1)
        if (.not. moved(e - e0 + 1)) cycle
        counts%continuum_tangent = counts%continuum_tangent + 1
        do k = 1, elem_nodes(m, e)
          f(:, m%conn(k, e)) = f(:, m%conn(k, e)) + fe(2 * k - 1:2 * k, e - e0 + 1)
        end do
      end do
    end do
    call team_close()
  end subroutine body_predictor_forces

  !> Purpose: one element's work of body_predictor_forces' team: fe =
  !> f_int(u0) + K_T(u0) du of body element e (with its follower
  !> pressures), from the history before the last commit; with
  !> tangent_only, K_T(u0) du alone.
  subroutine predictor_force(m, body, u0, du, e, tangent_only, fe)
    type(model_t), intent(in) :: m
    type(body_t), intent(in) :: body
    real(dp), intent(in) :: u0(:, :), du(:, :)
    integer, intent(in) :: e
    logical, intent(in) :: tangent_only
    real(dp), intent(inout) :: fe(:)
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    integer :: k, nd, nodes(max_en)
    real(dp) :: due(2 * max_en)
    ! (an unallocated body%dtemp0 is an absent argument: no thermal strain)
    call body_input(m, e, u0, ein, nodes, body%dtemp0, nlgeom=body%nlgeom, hist=body%hist_old(:, :, e))
    call element_routine(ior(act_tangent, act_residual), ein, eout)
    nd = eout%ndof
    do k = 1, ein%nen
      due(2 * k - 1:2 * k) = du(:, nodes(k))
    end do
    if (allocated(body%fl_ptr)) then
      call follower_part(m, body, e, u0, ein, eout%fe, eout%ke, .true.)
      call follower_part(m, body, e, u0, ein, eout%fe, eout%ke, .false.)
    end if
    if (tangent_only) eout%fe(1:nd) = 0.0_dp
    fe(1:nd) = eout%fe(1:nd) + matmul(eout%ke(1:nd, 1:nd), due(1:nd))
  end subroutine predictor_force

  !> Purpose: the follower pressures on element e at u (body%fl_*): with
  !> tangent, ke = ke - sum p dfp/du (the load stiffness); otherwise fe =
  !> fe - sum p fp(u) (the pressure's forces on the deformed faces, taken
  !> into the internal force). fp and its stiffness come from
  !> distributed_loads' follower_pressure_load (per unit pressure). A
  !> plane-stress face acts on its current thickness t0 lambda3, lambda3
  !> the element's thickness stretch at u (element_library's
  !> thickness_stretch, the volume mean of F33 over its points, from
  !> s33 = 0). The forces are lambda3 times those of t0, so the load
  !> stiffness is that of t0 lambda3 (lambda3 held) plus
  !> (fp / lambda3) (x) d lambda3 / du over all the element's dofs.
  !> Plane strain and axisymmetry: the reference thickness (or 2 pi r)
  !> unchanged, bit for bit.
  !> Arguments: ein the element's input at u (body_input, with the
  !> history of the caller's element call), fe, ke updated.
  subroutine follower_part(m, body, e, u, ein, fe, ke, tangent)
    type(model_t), intent(in) :: m
    type(body_t), intent(in) :: body
    integer, intent(in) :: e
    real(dp), intent(in) :: u(:, :)
    type(elem_in_t), intent(in) :: ein
    real(dp), intent(inout) :: fe(:), ke(:, :)
    logical, intent(in) :: tangent
    real(dp) :: fp(2, max_nodes), kl(2 * max_nodes, 2 * max_nodes), xy(2, max_nodes), ue(2, max_nodes)
    real(dp) :: thick(max_nodes), lam, dlam(2 * max_nodes)
    integer :: k, nen, nd, a, b
    logical :: ps
    if (body%fl_ptr(e + 1) == body%fl_ptr(e)) return
    nen = elem_nodes(m, e)
    nd = 2 * nen
    xy(:, 1:nen) = m%x(:, m%conn(1:nen, e))
    ue(:, 1:nen) = u(:, m%conn(1:nen, e))
    thick = elem_thickness(m, e)
    ps = catalogue(m%etype(e))%state == state_plane_stress
    if (ps) then
      call thickness_stretch(ein, lam, dlam)
      thick = thick * lam
    end if
    do k = body%fl_ptr(e), body%fl_ptr(e + 1) - 1
      call follower_pressure_load(m%etype(e), xy(:, 1:nen), ue(:, 1:nen), thick, body%fl_face(k), &
                                  fp, kl)
      if (tangent) then
        ke(1:nd, 1:nd) = ke(1:nd, 1:nd) - body%fl_mag(k) * kl(1:nd, 1:nd)
        if (ps) then
          do b = 1, nd
            do a = 1, nen
              ke(2 * a - 1:2 * a, b) = ke(2 * a - 1:2 * a, b) - body%fl_mag(k) * fp(:, a) / lam * dlam(b)
            end do
          end do
        end if
      else
        do a = 1, nen
          fe(2 * a - 1:2 * a) = fe(2 * a - 1:2 * a) - body%fl_mag(k) * fp(:, a)
        end do
      end if
    end do
  end subroutine follower_part

  !> Purpose: the stiffness of the current contact status into sys: the
  !> stored body matrices (in a nonlinear step the element tangents at u;
  !> with converged, u is the converged state an increment starts from and
  !> the tangent that of its last iteration, from body%hist_old) plus the
  !> tangent of every CFE.
  !> Arguments: kmax returns the largest diagonal entry of any element
  !> matrix (a stiffness scale for the residual test; in a nonlinear step
  !> the largest entry of any, huge if one is not finite); dm the numbering
  !> the system was set up for (its constraints transform the groups that
  !> touch a dependent dof).
  subroutine assemble_stiffness(m, cs, body, u, sys, kmax, counts, dm, converged)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    type(body_t), intent(in) :: body
    real(dp), intent(in) :: u(:, :)
    type(linear_system_t), intent(inout) :: sys
    real(dp), intent(out) :: kmax
    type(element_counts_t), intent(inout) :: counts
    type(dofmap_t), intent(in) :: dm
    logical, intent(in), optional :: converged
    type(cfe_in_t) :: cin
    type(cfe_out_t) :: cout
    integer :: e, j, nd
    integer, allocatable :: cnodes(:)
    real(dp) :: ke(2 * max_en, 2 * max_en)
    logical :: at_converged
    at_converged = .false.
    if (present(converged)) at_converged = converged
    call sys_zero(sys)
    kmax = body%kmax
    if (body%nonlinear) then
      call nonlinear_tangents(m, body, u, sys, kmax, counts, dm, at_converged)
    else
      do e = 1, m%ne
        if (.not. carries_stiffness(m, e)) cycle
        nd = 2 * elem_nodes(m, e)
        call unpack_upper(body%ke(body%kptr(e):body%kptr(e + 1) - 1), ke(1:nd, 1:nd))
        call add_group(sys, dm, e, m%conn(1:nd / 2, e), ke(1:nd, 1:nd))
      end do
    end if
    do e = 1, cs%n
      call cfe_input(m, cs%c(e), u, cs%stabilised, cin, cnodes)
      call cfe(act_tangent, cin, cout)
      counts%coupling = counts%coupling + 1
      call add_group(sys, dm, m%ne + e, cnodes(1:cin%nen), cout%ke)
      do j = 1, cout%ndof
        kmax = max(kmax, abs(cout%ke(j, j)))
      end do
    end do
  end subroutine assemble_stiffness

  !> Purpose: assemble_stiffness's body elements in a nonlinear step: the
  !> consistent tangent of every body element at u with the committed
  !> history (at_converged: the history before the last commit, the
  !> tangent of the last iteration at the converged state), with its
  !> follower pressures' load stiffness; the tangents of a block of
  !> elements on the team (element_tangent), then added to sys, and
  !> kmax raised to their largest entry (huge if one is not finite), by
  !> one thread in element order.
  subroutine nonlinear_tangents(m, body, u, sys, kmax, counts, dm, at_converged)
    type(model_t), intent(in) :: m
    type(body_t), intent(in) :: body
    real(dp), intent(in) :: u(:, :)
    type(linear_system_t), intent(inout) :: sys
    real(dp), intent(inout) :: kmax
    type(element_counts_t), intent(inout) :: counts
    type(dofmap_t), intent(in) :: dm
    logical, intent(in) :: at_converged
    real(dp), allocatable :: ke(:, :, :)
    integer :: e, e0, nd, nt
    allocate(ke(max_edof, max_edof, block_size))
    nt = element_threads()
    call team_open()
    do e0 = 1, m%ne, block_size
      !$omp parallel do num_threads(nt) if (nt > 1) schedule(dynamic, 16) default(shared) private(e)
      do e = e0, min(m%ne, e0 + block_size - 1)
        if (carries_stiffness(m, e)) call element_tangent(m, body, u, e, at_converged, ke(:, :, e - e0 + 1))
      end do
      !$omp end parallel do
      do e = e0, min(m%ne, e0 + block_size - 1)
        if (.not. carries_stiffness(m, e)) cycle
        counts%continuum_tangent = counts%continuum_tangent + 1
        nd = 2 * elem_nodes(m, e)
        ! every entry (a tangent that overflows is caught by the iteration)
        kmax = max(kmax, maxval(abs(ke(1:nd, 1:nd, e - e0 + 1))))
        if (.not. kmax <= huge(1.0_dp)) kmax = huge(1.0_dp)
        call add_group(sys, dm, e, m%conn(1:nd / 2, e), ke(1:nd, 1:nd, e - e0 + 1))
      end do
    end do
    call team_close()
  end subroutine nonlinear_tangents

  !> Purpose: one element's work of nonlinear_tangents' team: the tangent
  !> ke of body element e at u with the committed history (at_converged:
  !> the history before the last commit) and its follower pressures.
  subroutine element_tangent(m, body, u, e, at_converged, ke)
    type(model_t), intent(in) :: m
    type(body_t), intent(in) :: body
    real(dp), intent(in) :: u(:, :)
    integer, intent(in) :: e
    logical, intent(in) :: at_converged
    real(dp), intent(inout) :: ke(:, :)
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    integer :: nd, nodes(max_en)
    real(dp) :: fe_dummy(2 * max_en)
    nd = 2 * elem_nodes(m, e)
    ! (an unallocated body%dtemp is an absent argument: no thermal strain)
    call body_input(m, e, u, ein, nodes, body%dtemp, nlgeom=body%nlgeom, hist=body%hist(:, :, e))
    ! at the converged state the increment starts from: its last iteration's tangent
    if (at_converged) ein%hist = body%hist_old(:, :, e)
    call element_routine(act_tangent, ein, eout)
    ke(1:nd, 1:nd) = eout%ke(1:nd, 1:nd)
    if (allocated(body%fl_ptr)) call follower_part(m, body, e, u, ein, fe_dummy, ke, .true.)
  end subroutine element_tangent

  !> The matrix k of assembly group g on nodes into sys: as it is, or
  !> transformed by the constraints (t^T k t) where a dof is dependent.
  subroutine add_group(sys, dm, g, nodes, k)
    type(linear_system_t), intent(inout) :: sys
    type(dofmap_t), intent(in) :: dm
    integer, intent(in) :: g, nodes(:)
    real(dp), intent(in) :: k(:, :)
    integer, allocatable :: geq(:)
    real(dp), allocatable :: t(:, :)
    if (.not. has_dependent(dm, nodes)) then
      call sys_add(sys, g, k)
      return
    end if
    call group_transform(dm, nodes, geq, t)
    call sys_add(sys, g, matmul(transpose(t), matmul(k, t)))
  end subroutine add_group

  !> Purpose: internal forces of the bodies, sum of ke * ue, into fint
  !> (2, nn), which is overwritten: each element's ke * ue on the team a
  !> block at a time, the sum in element order.
  subroutine body_forces(m, body, u, fint)
    type(model_t), intent(in) :: m
    type(body_t), intent(in) :: body
    real(dp), intent(in) :: u(:, :)
    real(dp), intent(out) :: fint(:, :)
    real(dp), allocatable :: fe(:, :)
    integer :: e, e0, k, nt
    allocate(fe(max_edof, block_size))
    fint = 0.0_dp
    nt = element_threads()
    call team_open()
    do e0 = 1, m%ne, block_size
      !$omp parallel do num_threads(nt) if (nt > 1) schedule(static) default(shared) private(e)
      do e = e0, min(m%ne, e0 + block_size - 1)
        if (carries_stiffness(m, e)) call stored_force(m, body, u, e, fe(:, e - e0 + 1))
      end do
      !$omp end parallel do
      do e = e0, min(m%ne, e0 + block_size - 1)
        if (.not. carries_stiffness(m, e)) cycle
        do k = 1, elem_nodes(m, e)
          fint(:, m%conn(k, e)) = fint(:, m%conn(k, e)) + fe(2 * k - 1:2 * k, e - e0 + 1)
        end do
      end do
    end do
    call team_close()
  end subroutine body_forces

  !> Purpose: fe = ke ue of body element e from its stored stiffness.
  subroutine stored_force(m, body, u, e, fe)
    type(model_t), intent(in) :: m
    type(body_t), intent(in) :: body
    real(dp), intent(in) :: u(:, :)
    integer, intent(in) :: e
    real(dp), intent(inout) :: fe(:)
    real(dp) :: ue(2 * max_en), ke(2 * max_en, 2 * max_en)
    integer :: k, nen, nd
    nen = elem_nodes(m, e)
    nd = 2 * nen
    do k = 1, nen
      ue(2 * k - 1:2 * k) = u(:, m%conn(k, e))
    end do
    call unpack_upper(body%ke(body%kptr(e):body%kptr(e + 1) - 1), ke(1:nd, 1:nd))
    fe(1:nd) = matmul(ke(1:nd, 1:nd), ue(1:nd))
  end subroutine stored_force

  !> Purpose: the out-of-balance force f_ext - f_int on the free
  !> equations, the right-hand side of K du = rhs (T^T (f_ext - f_int)
  !> with constraints: forces on dependent dofs act on their independent
  !> dofs).
  subroutine free_residual(dm, fext, fint, rhs)
    type(dofmap_t), intent(in) :: dm
    real(dp), intent(in) :: fext(:, :), fint(:, :)
    real(dp), intent(out) :: rhs(:)
    real(dp), allocatable :: r(:, :)
    integer :: a, d
    if (dm%mpc%ndep > 0) then
      r = fext - fint
      call reduce_dependent(dm, r)
      do a = 1, size(dm%eq, 2)
        do d = 1, 2
          if (dm%eq(d, a) > 0) rhs(dm%eq(d, a)) = r(d, a)
        end do
      end do
      return
    end if
    do a = 1, size(dm%eq, 2)
      do d = 1, 2
        if (dm%eq(d, a) > 0) rhs(dm%eq(d, a)) = fext(d, a) - fint(d, a)
      end do
    end do
  end subroutine free_residual

  !> Purpose: integration-point stresses and strains of every body element
  !> (a truss: its axial stress and strain), and nodal stresses of the
  !> continuum elements extrapolated from them and averaged over the
  !> elements that share the node (nodes are never shared across bodies,
  !> so this is an average per body). In a linear step an isotropic
  !> linear elastic continuum element with a full integration rule takes
  !> linear_stresses (no element call: its input and output records cost
  !> more than its arithmetic); every other element its element routine.
  !> Arguments: nip(ne), sig_ip(4, max_ip, ne), eps_ip(3, max_ip, ne),
  !> sig_node(4, nn); dtemp(nn) the nodal temperature changes if any;
  !> body, in a nonlinear step, gives NLGEOM and the committed history
  !> (the stresses are then Cauchy stresses); peeq_ip(max_ip, ne) returns
  !> the equivalent plastic strain. counts%continuum_stresses counts the
  !> stress evaluations of either kind. The elements on the team a block at
  !> a time (element_stresses, each writing its own columns), the nodal
  !> sums in element order.
  subroutine stress_recovery(m, u, nip, sig_ip, eps_ip, sig_node, counts, dtemp, body, peeq_ip)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: u(:, :)
    real(dp), intent(in), optional :: dtemp(:)
    type(body_t), intent(in), optional :: body
    real(dp), intent(out), optional :: peeq_ip(:, :)
    integer, intent(out) :: nip(:)
    real(dp), intent(out) :: sig_ip(:, :, :), eps_ip(:, :, :), sig_node(:, :)
    type(element_counts_t), intent(inout) :: counts
    type(point_table_t), allocatable :: tab(:)
    real(dp), allocatable :: sn(:, :, :)
    logical, allocatable :: nodal(:)
    integer :: e, e0, i, nt
    integer, allocatable :: cnt(:)
    allocate(cnt(m%nn), tab(size(catalogue)), sn(4, max_nodes, block_size), nodal(block_size))
    cnt = 0
    nip = 0
    sig_ip = 0.0_dp
    eps_ip = 0.0_dp
    sig_node = 0.0_dp
    ! the shape tables of the linear_path types, made before the team reads them
    do e = 1, m%ne
      if (present(body) .or. .not. carries_stiffness(m, e)) cycle
      if (tab(m%etype(e))%ready) cycle
      if (linear_path(m, e)) call point_table(m%etype(e), tab(m%etype(e)))
    end do
    nt = element_threads()
    call team_open()
    do e0 = 1, m%ne, block_size
      !$omp parallel do num_threads(nt) if (nt > 1) schedule(dynamic, 32) default(shared) private(e)
      do e = e0, min(m%ne, e0 + block_size - 1)
        if (carries_stiffness(m, e)) call element_stresses(m, e, u, tab, nip, sig_ip, eps_ip, sn(:, :, e - e0 + 1), &
                                                           nodal(e - e0 + 1), dtemp, body, peeq_ip)
      end do
      !$omp end parallel do
      do e = e0, min(m%ne, e0 + block_size - 1)
        if (.not. carries_stiffness(m, e)) cycle
        counts%continuum_stresses = counts%continuum_stresses + 1
        if (.not. nodal(e - e0 + 1)) cycle
        do i = 1, elem_nodes(m, e)
          sig_node(:, m%conn(i, e)) = sig_node(:, m%conn(i, e)) + sn(:, i, e - e0 + 1)
          cnt(m%conn(i, e)) = cnt(m%conn(i, e)) + 1
        end do
      end do
    end do
    call team_close()
    do i = 1, m%nn
      if (cnt(i) > 0) sig_node(:, i) = sig_node(:, i) / cnt(i)
    end do
  end subroutine stress_recovery

  !> Purpose: one element's work of stress_recovery's team: the stresses
  !> and strains of body element e at its integration points into nip(e),
  !> sig_ip(:, :, e), eps_ip(:, :, e) (and peeq_ip(:, e)), its nodal
  !> stresses into sn(4, nen); nodal says whether they join the nodal
  !> average (a continuum element). By linear_stresses where linear_path
  !> holds in a linear step (tab: the types' shape tables, made), by the
  !> element routine otherwise. Writes only element e's columns and sn.
  subroutine element_stresses(m, e, u, tab, nip, sig_ip, eps_ip, sn, nodal, dtemp, body, peeq_ip)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    real(dp), intent(in) :: u(:, :)
    type(point_table_t), intent(in) :: tab(:)
    integer, intent(inout) :: nip(:)
    real(dp), intent(inout) :: sig_ip(:, :, :), eps_ip(:, :, :), sn(:, :)
    logical, intent(out) :: nodal
    real(dp), intent(in), optional :: dtemp(:)
    type(body_t), intent(in), optional :: body
    real(dp), intent(inout), optional :: peeq_ip(:, :)
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    integer :: nen, nodes(max_en)
    nodal = .true.
    nen = elem_nodes(m, e)
    if (.not. present(body) .and. linear_path(m, e)) then
      nip(e) = catalogue(m%etype(e))%nip
      call linear_stresses(m, e, u, tab(m%etype(e)), sig_ip(:, 1:nip(e), e), eps_ip(:, 1:nip(e), e), &
                           sn(:, 1:nen), dtemp)
      call add_initial_stress(m, e, catalogue(m%etype(e))%shape, nen, nip(e), sig_ip(:, 1:nip(e), e), sn(:, 1:nen))
      return
    end if
    if (present(body)) then
      call body_input(m, e, u, ein, nodes, dtemp, nlgeom=body%nlgeom, hist=body%hist(:, :, e))
    else
      call body_input(m, e, u, ein, nodes, dtemp)
    end if
    call element_routine(act_stresses, ein, eout)
    call add_initial_stress(m, e, ein%kind, nen, eout%nip, eout%sig_ip(:, 1:eout%nip), eout%sig_node(:, 1:nen))
    if (present(peeq_ip)) peeq_ip(:, e) = eout%peeq_ip
    nip(e) = eout%nip
    sig_ip(:, 1:eout%nip, e) = eout%sig_ip(:, 1:eout%nip)
    eps_ip(:, 1:eout%nip, e) = eout%eps_ip(:, 1:eout%nip)
    nodal = is_continuum(m, e)
    if (nodal) sn(:, 1:nen) = eout%sig_node(:, 1:nen)
  end subroutine element_stresses

  !> Purpose: does body element e take linear_stresses in a linear step?
  !> A continuum element of an isotropic linear elastic material without
  !> hardening, not a one-point quadrilateral (whose mean strain is
  !> uniform_strain's): the elements for which continuum's stresses are
  !> D (B ue - eps0) at its own rule's points.
  pure logical function linear_path(m, e)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    linear_path = .false.
    if (.not. is_continuum(m, e)) return
    if (catalogue(m%etype(e))%shape == shape_quad4 .and. catalogue(m%etype(e))%nip == 1) return
    associate(sec => m%sections(m%elem_section(e)))
      if (sec%spring) return
      associate(mat => m%materials(sec%material))
        linear_path = mat%law == law_elastic .and. mat%nyield == 0 .and. mat%elastic_type == elastic_iso
      end associate
    end associate
  end function linear_path

  !> Purpose: the shape functions, their natural derivatives and the
  !> extrapolation to the nodes at the integration points of catalogue
  !> entry it, which every element of that type shares.
  pure subroutine point_table(it, tab)
    integer, intent(in) :: it
    type(point_table_t), intent(out) :: tab
    real(dp) :: xg(2, max_ip), wg(max_ip)
    integer :: ip
    call gauss_rule(catalogue(it)%shape, catalogue(it)%nip, xg, wg)
    do ip = 1, catalogue(it)%nip
      call shape_at(catalogue(it)%shape, xg(:, ip), tab%n(:, ip), tab%dn(:, :, ip))
    end do
    call extrapolation(catalogue(it)%shape, catalogue(it)%nodes, catalogue(it)%nip, tab%ex)
    tab%ready = .true.
  end subroutine point_table

  !> Purpose: the stresses of a linear_path element e as continuum
  !> computes them, without the element call: at each point of its rule
  !> eps = B ue, sig = D (eps - eps0) (eps0 = alpha dT (1, 1, 0, 1), dT
  !> interpolated from the nodes), then extrapolated to the nodes. B is
  !> continuum_element's strain_matrix written out on its nonzero entries
  !> (J = dN X^T, dN/dx = J^-1 dN, the hoop row N / r), summed in its
  !> order: only terms that are exact zeros are left out.
  !> Arguments: m, e, u; tab the element type's point_table; sip(4, nip)
  !> the stresses (s11, s22, s33, s12) and eip(3, nip) the strains at the
  !> points, snode(4, nen) at the nodes; dtemp(nn) as stress_recovery's.
  pure subroutine linear_stresses(m, e, u, tab, sip, eip, snode, dtemp)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e
    real(dp), intent(in) :: u(:, :)
    type(point_table_t), intent(in) :: tab
    real(dp), intent(out) :: sip(:, :), eip(:, :), snode(:, :)
    real(dp), intent(in), optional :: dtemp(:)
    real(dp) :: d(4, 4), xy(2, max_nodes), ue(2, max_nodes), dt(max_nodes), jac(2, 2), jinv(2, 2), dx(2, max_nodes), &
                eps(4), sig(4), detj, r, alpha
    integer :: k, ip, nen, state
    nen = elem_nodes(m, e)
    state = catalogue(m%etype(e))%state
    associate(mat => m%materials(m%sections(m%elem_section(e))%material))
      d = elastic_matrix(mat%e, mat%nu, state)
      alpha = 0.0_dp
      if (present(dtemp)) alpha = mat%alpha
    end associate
    do k = 1, nen
      xy(:, k) = m%x(:, m%conn(k, e))
      ue(:, k) = u(:, m%conn(k, e))
      if (alpha /= 0.0_dp) dt(k) = dtemp(m%conn(k, e))
    end do
    do ip = 1, size(sip, 2)
      associate(n => tab%n(:, ip), dn => tab%dn(:, :, ip))
        jac = 0.0_dp
        do k = 1, nen
          jac(:, 1) = jac(:, 1) + dn(:, k) * xy(1, k)
          jac(:, 2) = jac(:, 2) + dn(:, k) * xy(2, k)
        end do
        detj = jac(1, 1) * jac(2, 2) - jac(1, 2) * jac(2, 1)
        jinv(1, 1) = jac(2, 2) / detj
        jinv(2, 2) = jac(1, 1) / detj
        jinv(1, 2) = -jac(1, 2) / detj
        jinv(2, 1) = -jac(2, 1) / detj
        eps = 0.0_dp
        do k = 1, nen
          dx(:, k) = jinv(:, 1) * dn(1, k) + jinv(:, 2) * dn(2, k)
          eps(1) = eps(1) + dx(1, k) * ue(1, k)
          eps(2) = eps(2) + dx(2, k) * ue(2, k)
          eps(3) = eps(3) + dx(2, k) * ue(1, k)
          eps(3) = eps(3) + dx(1, k) * ue(2, k)
        end do
        if (state == state_axisymmetric) then
          r = dot_product(n(1:nen), xy(1, 1:nen))
          do k = 1, nen
            eps(4) = eps(4) + n(k) / r * ue(1, k)
          end do
        end if
        eip(:, ip) = eps(1:3)
        if (alpha /= 0.0_dp) eps = eps - alpha * dot_product(n(1:nen), dt(1:nen)) * [1.0_dp, 1.0_dp, 0.0_dp, 1.0_dp]
        sig = matmul(d, eps)
        sip(:, ip) = [sig(1), sig(2), sig(4), sig(3)]
      end associate
    end do
    do k = 1, nen
      snode(:, k) = 0.0_dp
      do ip = 1, size(sip, 2)
        snode(:, k) = snode(:, k) + sip(:, ip) * tab%ex(k, ip)
      end do
    end do
  end subroutine linear_stresses

  !> Purpose: the initial stress of element e (m%sig0, linear steps) added
  !> to its stresses: at the integration points, and extrapolated to the
  !> nodes as the element's own stresses are.
  !> Arguments: m, e; shape, nen, nip the element's catalogue shape, nodes
  !> and points; sip(4, nip), snode(4, nen) its stresses, updated.
  subroutine add_initial_stress(m, e, shape, nen, nip, sip, snode)
    type(model_t), intent(in) :: m
    integer, intent(in) :: e, shape, nen, nip
    real(dp), intent(inout) :: sip(:, :), snode(:, :)
    real(dp) :: ex(max_nodes, max_ip), s0(4, max_ip)
    if (.not. allocated(m%sig0)) return
    if (e > size(m%sig0, 3)) return
    if (.not. any(m%sig0(:, :, e) /= 0.0_dp)) return
    ! (s11, s22, s12, s33) -> the output order (s11, s22, s33, s12)
    s0(:, 1:nip) = m%sig0([1, 2, 4, 3], 1:nip, e)
    sip(:, 1:nip) = sip(:, 1:nip) + s0(:, 1:nip)
    call extrapolation(shape, nen, nip, ex)
    snode(:, 1:nen) = snode(:, 1:nen) + matmul(s0(:, 1:nip), transpose(ex(1:nen, 1:nip)))
  end subroutine add_initial_stress
end module assembly
