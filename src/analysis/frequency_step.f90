!> A *FREQUENCY step (docs/keywords.md, docs/architecture.md): the natural
!> frequencies and modes of the displacement field about the state the
!> steps before it leave, K x = omega^2 M x on the step's free equations.
!> K is the tangent of that converged state: the stored linear stiffness,
!> or after a nonlinear step the element tangents at its last iteration
!> (under NLGEOM with the stress stiffening of its stresses), plus the
!> coupling elements as their statuses stand (a closed one with its
!> penalty, an open one with its open penalty, which leaves the bodies
!> free); M the consistent mass of the bodies (element_mass) and the
!> point masses. The step's loads play no part; its *BOUNDARY (and those
!> it keeps from the steps before) hold dofs at zero, and the displacement
!> field is left as it was (a static step after it goes on from there).
!> The eigenproblem goes to eigen_solver: dense LAPACK up to dense_switch
!> equations, ARPACK in shift-invert mode on the solver backend's
!> factorisation of K - sigma M above. Each mode is handed to the
!> observers as an increment of the step (its step time the frequency in
!> cycles/time, as CalculiX's .frd), the eigenvalue table and the
!> participation factors as a note (the listing's EIGENVALUES block).
module frequency_step
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  use strings, only: itoa, rtoa
  use messages, only: fatal
  use growable, only: append, grow
  use model, only: model_t, step_t, carries_stiffness, is_mass, is_truss, elem_nodes, elem_thickness
  use element_interface, only: elem_in_t, elem_out_t, cfe_in_t, cfe_out_t, max_en, act_tangent
  use element_library, only: element_routine
  use element_mass, only: mass_matrix
  use cfe_element, only: cfe
  use contact, only: cfe_input
  use body_elements, only: body_input
  use assembly, only: element_counts_t
  use dof_numbering, only: dofmap_t, number_dofs, has_dependent, group_transform, expand_dependent
  use load_state, only: load_state_t, begin_step
  use linear_solver, only: linear_system_t, sys_setup, sys_zero, sys_add, sys_factor, sys_describe
  use sparse_matrix, only: csc_t, csc_build, csc_add_element
  use eigen_solver, only: eigen_dense, eigen_shift_invert, dense_switch
  use increment_results, only: increment_results_t, compute_increment_results
  use analysis_events, only: observer_ref_t, step_info_t, step_summary_t, run_timing_t, tell_note, wall_time
  use analysis_field, only: field_t
  use displacement_field, only: displacement_field_t
  implicit none
  private
  public :: run_frequency_step

  real(dp), parameter :: two_pi = 6.283185307179586476925286766559_dp

  !> The element matrices of the eigenproblem, one group per body element
  !> (point masses included) and coupling element: group g's equation
  !> list eqs(xeq(g):xeq(g+1)-1) (0: prescribed) and its stiffness and
  !> mass, nd x nd column by column from kv(kptr(g)) and mv(kptr(g)),
  !> already transformed (T^T k T) where the group touches a dependent dof.
  type :: groups_t
    integer, allocatable :: xeq(:), eqs(:)
    integer(kind=8), allocatable :: kptr(:)
    real(dp), allocatable :: kv(:), mv(:)
  end type groups_t

  !> The eigenpairs found and how.
  type :: modes_t
    integer :: n = 0                        ! found
    real(dp), allocatable :: lam(:), vec(:, :)
    character(len=:), allocatable :: method
  end type modes_t

contains

  !> Purpose: step is of model m, a *FREQUENCY step, on the displacement
  !> field f (the driver's first field); obs are told the step, one
  !> increment per mode and the step's summary.
  !> Arguments: total_time the total time at the step's start; timing
  !> gets the step's results and output times (the assembly and the
  !> eigensolver, factorisation included, go to the field's timing, which
  !> its finish reports as assembly and factor).
  subroutine run_frequency_step(m, is, f, obs, total_time, timing)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is
    class(field_t), intent(inout) :: f
    type(observer_ref_t), intent(in) :: obs(:)
    real(dp), intent(in) :: total_time
    type(run_timing_t), intent(inout) :: timing
    type(load_state_t) :: ls
    type(dofmap_t) :: dm
    type(linear_system_t) :: sys
    type(groups_t) :: gr
    type(modes_t) :: modes
    type(step_info_t) :: info
    type(step_summary_t) :: summary
    real(dp) :: started, t0, total(3)
    real(dp), allocatable :: tab(:, :)
    integer :: k
    started = wall_time()
    select type (f)
    type is (displacement_field_t)
      ! the step's prescribed dofs, on a copy of the field's load state
      ls = f%ls
      call begin_step(m, is, f%u, f%fext, total_time, ls)
      t0 = wall_time()
      call number_dofs(m, f%cs, ls%presc, m%solver, m%ordering, dm, sys, constraints=f%mpc)
      call gather_groups(m, f, dm, gr)
      f%eq%timing%assembly = f%eq%timing%assembly + (wall_time() - t0)
      info%step = is
      info%equations = dm%neq
      info%prescribed = count(ls%presc)
      info%coupling_elements = f%cs%n
      allocate(info%uncoupled(0), info%uncoupled_pair(0))
      do k = 1, size(obs)
        call obs(k)%o%step_started(m, info)
      end do
      t0 = wall_time()
      call solve_modes(m, is, gr, dm%neq, sys, modes)
      f%eq%timing%factor = f%eq%timing%factor + (wall_time() - t0)
      call tell_note(obs, eigenvalue_table(m, is, gr, dm, modes, tab, total))
      call report_modes(m, is, f, ls, dm, modes, tab, total, obs, timing, summary)
    class default
      call fatal('*FREQUENCY: the step needs the displacement field (not a heat transfer deck)')
    end select
    summary%step = is
    summary%increments = modes%n
    summary%wall_seconds = wall_time() - started
    do k = 1, size(obs)
      call obs(k)%o%step_finished(summary)
    end do
  end subroutine run_frequency_step

  !> Purpose: every group's equation list and its stiffness and mass
  !> matrices (element_pair, coupling_pair), transformed where a dof is
  !> dependent; stops when the model has no mass at all.
  subroutine gather_groups(m, f, dm, gr)
    type(model_t), intent(in) :: m
    type(displacement_field_t), intent(in) :: f
    type(dofmap_t), intent(in) :: dm
    type(groups_t), intent(out) :: gr
    integer :: g, ng, nen, i, nd, neqs, nk, nm
    integer, allocatable :: nodes(:), geq(:)
    real(dp), allocatable :: ke(:, :), me(:, :), t(:, :)
    real(dp) :: total_mass
    ng = m%ne + f%cs%n
    allocate(gr%xeq(ng + 1), gr%kptr(ng + 1))
    neqs = 0
    nk = 0
    nm = 0
    gr%xeq(1) = 1
    gr%kptr(1) = 1
    total_mass = 0.0_dp
    do g = 1, ng
      if (g <= m%ne) then
        call element_pair(m, f, g, nodes, nen, ke, me)
      else
        call coupling_pair(m, f, g - m%ne, nodes, nen, ke, me)
      end if
      total_mass = total_mass + sum(me)
      if (nen > 0 .and. has_dependent(dm, nodes(1:nen))) then
        call group_transform(dm, nodes(1:nen), geq, t)
        ke = matmul(transpose(t), matmul(ke, t))
        me = matmul(transpose(t), matmul(me, t))
      else
        allocate(geq(2 * nen))
        do i = 1, nen
          geq(2 * i - 1:2 * i) = dm%eq(:, nodes(i))
        end do
      end if
      nd = size(geq)
      call append(gr%eqs, neqs, geq)
      call append(gr%kv, nk, reshape(ke, [nd * nd]))
      call append(gr%mv, nm, reshape(me, [nd * nd]))
      gr%xeq(g + 1) = gr%xeq(g) + nd
      gr%kptr(g + 1) = gr%kptr(g) + int(nd, 8)**2
      deallocate(geq)
    end do
    call grow(gr%eqs, 1)
    call grow(gr%kv, 1)
    call grow(gr%mv, 1)
    gr%eqs = gr%eqs(1:neqs)
    gr%kv = gr%kv(1:nk)
    gr%mv = gr%mv(1:nm)
    if (.not. total_mass > 0.0_dp) call fatal('*FREQUENCY: the model has no mass (a *DENSITY in the ' // &
      'materials of its elements, or point masses: *MASS on MASS elements)')
  end subroutine gather_groups

  !> Purpose: body element e's nodes and its (symmetrised) tangent ke and
  !> mass me: in a model with a nonlinear step the tangent at the field's
  !> converged u (the history before the last commit, as the Newton
  !> iteration's last tangent; NLGEOM as the step before had it), the
  !> linear stiffness otherwise; none for a point mass, no mass without
  !> a *DENSITY.
  subroutine element_pair(m, f, e, nodes, nen, ke, me)
    type(model_t), intent(in) :: m
    type(displacement_field_t), intent(in) :: f
    integer, intent(in) :: e
    integer, allocatable, intent(out) :: nodes(:)
    integer, intent(out) :: nen
    real(dp), allocatable, intent(out) :: ke(:, :), me(:, :)
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    real(dp) :: rho, point
    integer :: nd
    nen = 0
    allocate(nodes(max_en), ke(0, 0), me(0, 0))
    if (.not. (carries_stiffness(m, e) .or. is_mass(m, e))) return
    nen = elem_nodes(m, e)
    nd = 2 * nen
    nodes(1:nen) = m%conn(1:nen, e)
    deallocate(ke, me)
    allocate(ke(nd, nd), me(nd, nd))
    ke = 0.0_dp
    rho = 0.0_dp
    point = 0.0_dp
    associate(sec => m%sections(m%elem_section(e)))
      if (is_mass(m, e)) then
        point = sec%mass
      else if (sec%material > 0) then
        if (m%materials(sec%material)%has_density) rho = m%materials(sec%material)%density
      end if
    end associate
    if (carries_stiffness(m, e)) then
      ! a model with a nonlinear step keeps a history: the tangent at u with
      ! it, under NLGEOM if the step before had it (stress stiffening)
      if (allocated(f%body%hist_old)) then
        call body_input(m, e, f%u, ein, nodes, f%body%dtemp, nlgeom=f%body%nlgeom, hist=f%body%hist_old(:, :, e))
      else
        call body_input(m, e, f%u, ein, nodes)
      end if
      call element_routine(act_tangent, ein, eout)
      ke = 0.5_dp * (eout%ke(1:nd, 1:nd) + transpose(eout%ke(1:nd, 1:nd)))
    end if
    if (is_truss(m, e)) then
      call mass_matrix(m%etype(e), m%x(:, nodes(1:nen)), [m%sections(m%elem_section(e))%thickness], rho, point, me)
    else if (is_mass(m, e)) then
      call mass_matrix(m%etype(e), m%x(:, nodes(1:nen)), [1.0_dp], rho, point, me)
    else
      call mass_matrix(m%etype(e), m%x(:, nodes(1:nen)), elem_thickness(m, e), rho, point, me)
    end if
  end subroutine element_pair

  !> Purpose: coupling element c's nodes and its tangent as its status
  !> stands (symmetrised: a sliding frictional one is not symmetric); no
  !> mass.
  subroutine coupling_pair(m, f, c, nodes, nen, ke, me)
    type(model_t), intent(in) :: m
    type(displacement_field_t), intent(in) :: f
    integer, intent(in) :: c
    integer, allocatable, intent(out) :: nodes(:)
    integer, intent(out) :: nen
    real(dp), allocatable, intent(out) :: ke(:, :), me(:, :)
    type(cfe_in_t) :: cin
    type(cfe_out_t) :: cout
    call cfe_input(m, f%cs%c(c), f%u, f%cs%stabilised, cin, nodes)
    call cfe(act_tangent, cin, cout)
    nen = cin%nen
    ke = 0.5_dp * (cout%ke + transpose(cout%ke))
    allocate(me(2 * nen, 2 * nen))
    me = 0.0_dp
  end subroutine coupling_pair

  !> Purpose: the eigenpairs of the step: dense up to dense_switch
  !> equations (or when the modes asked for are most of them), ARPACK in
  !> shift-invert mode above; the modes outside the step's frequency
  !> range dropped.
  subroutine solve_modes(m, is, gr, n, sys, modes)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is, n
    type(groups_t), intent(in) :: gr
    type(linear_system_t), intent(inout) :: sys
    type(modes_t), intent(out) :: modes
    real(dp) :: sigma
    integer :: nev, nask, info, k, keep
    logical :: dense
    if (n == 0) call fatal('*FREQUENCY in step ' // itoa(is) // ': no free dof (every dof is held)')
    ! an overflowing section or material value (a truss area of 1e308)
    ! makes K infinite: the solvers then return no mode without a code
    if (.not. (all(ieee_is_finite(gr%kv)) .and. all(ieee_is_finite(gr%mv)))) call fatal('*FREQUENCY in step ' // &
      itoa(is) // ': the stiffness or mass matrix is not finite (a section, material or mass value overflows)')
    associate(s => m%steps(is))
      nev = min(s%nev, n)
      sigma = shift(s, gr)
      if (.not. ieee_is_finite(sigma)) call fatal('*FREQUENCY in step ' // itoa(is) // ': the shift ' // &
        '(1e-6 of the ratio of K to M) is not finite: the stiffness and mass are of too different magnitudes')
      dense = n <= dense_switch .or. 2 * nev >= n
      ! with a lower frequency the shift lies inside the spectrum: the
      ! eigenvalues nearest it lie on both sides; the nev lowest at or
      ! above it are among all (dense) or the 2 nev + 10 nearest (ARPACK)
      nask = nev
      if (s%freq_lower > 0.0_dp) nask = merge(n, min(n - 1, 2 * nev + 10), dense)
      allocate(modes%lam(nask), modes%vec(n, nask))
      if (dense) then
        call dense_modes(gr, n, sigma, nask, modes, info)
      else
        call sparse_modes(m, gr, n, sigma, nask, sys, modes, info)
      end if
      if (info /= 0) call fatal('*FREQUENCY in step ' // itoa(is) // ': the eigensolver (' // modes%method // &
        ') failed with code ' // itoa(info) // merge(' (not every mode converged)', '                           ', &
        info == 1))
      if (.not. all(ieee_is_finite(modes%lam(1:modes%n)))) call fatal('*FREQUENCY in step ' // itoa(is) // &
        ': K - sigma M is singular (a part of the model that nothing holds and that has no mass, or the shift ' // &
        'of the lower frequency on an eigenvalue)')
      keep = 0
      do k = 1, modes%n
        if (keep == nev) exit
        if (s%freq_lower > 0.0_dp .and. frequency_of(modes%lam(k)) < s%freq_lower) cycle
        if (s%freq_upper > 0.0_dp .and. frequency_of(modes%lam(k)) > s%freq_upper) cycle
        keep = keep + 1
        modes%lam(keep) = modes%lam(k)
        modes%vec(:, keep) = modes%vec(:, k)
      end do
      modes%n = keep
    end associate
  end subroutine solve_modes

  !> The shift: CalculiX's (2 pi lower)^2 where a lower frequency is given;
  !> otherwise slightly below zero (1e-6 of the mean diagonal ratio of K
  !> to M, negative), which keeps K - sigma M positive definite for a body
  !> free to move (rigid modes, eigenvalue 0) and makes the nearest
  !> eigenvalues the lowest.
  real(dp) function shift(s, gr) result(sigma)
    type(step_t), intent(in) :: s
    type(groups_t), intent(in) :: gr
    real(dp) :: kd, md
    integer :: g, nd, i
    integer(kind=8) :: p
    if (s%freq_lower > 0.0_dp) then
      sigma = (two_pi * s%freq_lower)**2
      return
    end if
    kd = 0.0_dp
    md = 0.0_dp
    do g = 1, size(gr%xeq) - 1
      nd = gr%xeq(g + 1) - gr%xeq(g)
      do i = 1, nd
        if (gr%eqs(gr%xeq(g) + i - 1) <= 0) cycle
        p = gr%kptr(g) + int(i - 1, 8) * nd + i - 1
        kd = kd + abs(gr%kv(p))
        md = md + abs(gr%mv(p))
      end do
    end do
    sigma = -1.0e-6_dp * kd / max(md, tiny(1.0_dp))
  end function shift

  !> Purpose: the dense eigenproblem of the assembled K and M (LAPACK).
  subroutine dense_modes(gr, n, sigma, nev, modes, info)
    type(groups_t), intent(in) :: gr
    integer, intent(in) :: n, nev
    real(dp), intent(in) :: sigma
    type(modes_t), intent(inout) :: modes
    integer, intent(out) :: info
    real(dp), allocatable :: k(:, :), mm(:, :)
    integer :: g, i, j, nd, a, b
    integer(kind=8) :: p
    allocate(k(n, n), mm(n, n))
    k = 0.0_dp
    mm = 0.0_dp
    do g = 1, size(gr%xeq) - 1
      nd = gr%xeq(g + 1) - gr%xeq(g)
      do j = 1, nd
        b = gr%eqs(gr%xeq(g) + j - 1)
        if (b <= 0) cycle
        do i = 1, nd
          a = gr%eqs(gr%xeq(g) + i - 1)
          if (a <= 0) cycle
          p = gr%kptr(g) + int(j - 1, 8) * nd + i - 1
          k(a, b) = k(a, b) + gr%kv(p)
          mm(a, b) = mm(a, b) + gr%mv(p)
        end do
      end do
    end do
    modes%method = 'LAPACK dsygvd, dense, ' // itoa(n) // ' equations'
    call eigen_dense(k, mm, sigma, nev, modes%n, modes%lam, modes%vec, info)
  end subroutine dense_modes

  !> Purpose: ARPACK in shift-invert mode: K - sigma M assembled on the
  !> groups' structure and factored by the model's solver backend (a
  !> matrix that is not positive definite, a shift above the lowest
  !> eigenvalue, falls back to UMFPACK as every factorisation does), M
  !> in CSC (upper triangle) for the products.
  subroutine sparse_modes(m, gr, n, sigma, nev, sys, modes, info)
    type(model_t), intent(in) :: m
    type(groups_t), intent(in) :: gr
    integer, intent(in) :: n, nev
    real(dp), intent(in) :: sigma
    type(linear_system_t), intent(inout) :: sys
    type(modes_t), intent(inout) :: modes
    integer, intent(out) :: info
    type(csc_t) :: mm
    integer :: g, nd, status, bad, iters, nop, kind
    integer(kind=8) :: p
    kind = m%solver
    call sys_setup(sys, kind, m%ordering, n, gr%xeq, gr%eqs)
    call csc_build(mm, n, gr%xeq, gr%eqs, .true., with_map=.false.)
    call sys_zero(sys)
    do g = 1, size(gr%xeq) - 1
      nd = gr%xeq(g + 1) - gr%xeq(g)
      if (nd == 0) cycle
      p = gr%kptr(g)
      call sys_add(sys, g, reshape(gr%kv(p:p + nd * nd - 1) - sigma * gr%mv(p:p + nd * nd - 1), [nd, nd]))
      call csc_add_element(mm, g, gr%eqs(gr%xeq(g):gr%xeq(g + 1) - 1), &
                           reshape(gr%mv(p:p + nd * nd - 1), [nd, nd]))
    end do
    ! (a small pivot, which the backends call singular for a static solve,
    ! is no failure here: a shift near an eigenvalue makes one, and
    ! shift-invert thrives on it; a factor that is truly singular gives
    ! eigenvalues that are not finite, which solve_modes stops at)
    call sys_factor(sys, status, bad)
    call eigen_shift_invert(sys, mm, sigma, nev, modes%n, modes%lam, modes%vec, iters, nop, info)
    modes%method = 'ARPACK shift-invert (dsaupd mode 3), ' // itoa(n) // ' equations, ' // sys_describe(sys) // &
                   ', ' // itoa(nop) // ' solves'
  end subroutine sparse_modes

  !> The frequency (cycles/time) of eigenvalue lam = omega^2 (0 for a
  !> negative one, a rigid mode to round-off).
  pure real(dp) function frequency_of(lam)
    real(dp), intent(in) :: lam
    frequency_of = sqrt(max(lam, 0.0_dp)) / two_pi
  end function frequency_of

  !> Purpose: the listing's block of the step's modes: eigenvalue, omega
  !> (rad/time), frequency (cycles/time), and CalculiX's participation
  !> factors phi^T M r and effective modal masses (phi^T M r)^2 for the
  !> rigid motions r of the free dofs: x, y and the rotation about z
  !> through the origin, r = (-y, x); their totals r^T M r last.
  !> Arguments: tab(6, modes%n) returns the eigenvalue, omega, frequency
  !> and participation factors of each mode, total the total effective
  !> masses (the .dat's tables, increment_results_t's modes).
  function eigenvalue_table(m, is, gr, dm, modes, tab, total) result(text)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is
    type(groups_t), intent(in) :: gr
    type(dofmap_t), intent(in) :: dm
    type(modes_t), intent(in) :: modes
    real(dp), allocatable, intent(out) :: tab(:, :)
    real(dp), intent(out) :: total(3)
    character(len=:), allocatable :: text
    real(dp), allocatable :: r(:, :), mr(:, :)
    real(dp) :: gam(3)
    integer :: k, j
    character(len=*), parameter :: nl = new_line('a')
    call rigid_motions(m, dm, r)
    call mass_times(gr, r, mr)
    allocate(tab(6, modes%n))
    do j = 1, 3
      total(j) = dot_product(r(:, j), mr(:, j))
    end do
    text = '--- EIGENVALUES step=' // itoa(is) // nl // 'mode eigenvalue omega frequency ' // &
           'participation_x participation_y participation_rz mass_x mass_y mass_rz'
    do k = 1, modes%n
      do j = 1, 3
        gam(j) = dot_product(modes%vec(:, k), mr(:, j))
        ! round-off (a bending mode's share along the beam): 0, so that
        ! the tables do not print the build's noise
        if (abs(gam(j)) <= 1.0e-10_dp * sqrt(abs(total(j)))) gam(j) = 0.0_dp
      end do
      tab(:, k) = [modes%lam(k), sqrt(max(modes%lam(k), 0.0_dp)), frequency_of(modes%lam(k)), gam]
      text = text // nl // itoa(k) // ' ' // rtoa(modes%lam(k), 9) // ' ' // &
             rtoa(sqrt(max(modes%lam(k), 0.0_dp)), 9) // ' ' // rtoa(frequency_of(modes%lam(k)), 9) // ' ' // &
             rtoa(gam(1), 9) // ' ' // rtoa(gam(2), 9) // ' ' // rtoa(gam(3), 9) // ' ' // &
             rtoa(gam(1)**2, 9) // ' ' // rtoa(gam(2)**2, 9) // ' ' // rtoa(gam(3)**2, 9)
    end do
    text = text // nl // '--- TOTAL EFFECTIVE MASS step=' // itoa(is) // nl // 'mass_x mass_y mass_rz' // nl // &
           rtoa(total(1), 9) // ' ' // rtoa(total(2), 9) // ' ' // rtoa(total(3), 9) // nl // &
           '--- EIGENSOLVER step=' // itoa(is) // nl // &
           'item value' // nl // 'method ' // modes%method
    if (len_trim(m%steps(is)%freq_solver) > 0) text = text // nl // 'deck_solver ' // &
      trim(m%steps(is)%freq_solver) // ' (read; cfe2d''s eigensolver is the method above)'
    if (len_trim(m%steps(is)%freq_storage) > 0) text = text // nl // 'storage ' // &
      trim(m%steps(is)%freq_storage) // ' (read; no matrices are stored)'
  end function eigenvalue_table

  !> The rigid motions of the free equations, r(n, 3): unit x, unit y,
  !> unit rotation about z through the origin (-y, x) at each
  !> equation's node.
  subroutine rigid_motions(m, dm, r)
    type(model_t), intent(in) :: m
    type(dofmap_t), intent(in) :: dm
    real(dp), allocatable, intent(out) :: r(:, :)
    integer :: q, a, d
    allocate(r(dm%neq, 3))
    r = 0.0_dp
    do q = 1, dm%neq
      a = dm%node_of_eq(q)
      d = dm%dof_of_eq(q)
      r(q, d) = 1.0_dp
      r(q, 3) = merge(-m%x(2, a), m%x(1, a), d == 1)
    end do
  end subroutine rigid_motions

  !> mr = M r for the columns of r, from the groups' mass matrices.
  subroutine mass_times(gr, r, mr)
    type(groups_t), intent(in) :: gr
    real(dp), intent(in) :: r(:, :)
    real(dp), allocatable, intent(out) :: mr(:, :)
    integer :: g, i, j, nd, a, b
    integer(kind=8) :: p
    allocate(mr(size(r, 1), size(r, 2)))
    mr = 0.0_dp
    do g = 1, size(gr%xeq) - 1
      nd = gr%xeq(g + 1) - gr%xeq(g)
      do j = 1, nd
        b = gr%eqs(gr%xeq(g) + j - 1)
        if (b <= 0) cycle
        do i = 1, nd
          a = gr%eqs(gr%xeq(g) + i - 1)
          if (a <= 0) cycle
          p = gr%kptr(g) + int(j - 1, 8) * nd + i - 1
          mr(a, :) = mr(a, :) + gr%mv(p) * r(b, :)
        end do
      end do
    end do
  end subroutine mass_times

  !> Purpose: each mode as an increment of the step to the observers: u
  !> the mode of unit generalised mass (the dependent dofs from the
  !> independent ones), no reactions, its step time and total time the
  !> frequency in cycles/time (CalculiX's .frd value of a mode); the first carries the step's table tab(6, modes) and
  !> total effective masses (CalculiX's .dat); the summary's counts.
  subroutine report_modes(m, is, f, ls, dm, modes, tab, total, obs, timing, summary)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is
    type(displacement_field_t), intent(in) :: f
    type(load_state_t), intent(in) :: ls
    type(dofmap_t), intent(in) :: dm
    type(modes_t), intent(in) :: modes
    real(dp), intent(in) :: tab(:, :), total(3)
    type(observer_ref_t), intent(in) :: obs(:)
    type(run_timing_t), intent(inout) :: timing
    type(step_summary_t), intent(inout) :: summary
    type(increment_results_t) :: res
    type(element_counts_t) :: counts
    real(dp), allocatable :: u(:, :), rf(:, :)
    real(dp) :: t0, t1, freq
    integer :: k, a, d, j
    allocate(u(2, m%nn), rf(2, m%nn))
    rf = 0.0_dp
    do k = 1, modes%n
      t0 = wall_time()
      u = 0.0_dp
      do a = 1, m%nn
        do d = 1, 2
          if (dm%eq(d, a) > 0) u(d, a) = modes%vec(dm%eq(d, a), k)
        end do
      end do
      ! components at round-off of the mode's largest (eigenvector noise,
      ! different in every build) are 0
      where (abs(u) <= 1.0e-12_dp * maxval(abs(u))) u = 0.0_dp
      call expand_dependent(dm, u)
      ! step time and total time the frequency: the value CalculiX's .frd
      ! gives a mode (and the .pvd's time of its file)
      freq = frequency_of(modes%lam(k))
      call compute_increment_results(m, is, k, freq, freq, 0, u, rf, f%cs, ls%set_ids, res, counts)
      if (k == 1) then
        res%modes = tab
        res%modal_total = total
      end if
      t1 = wall_time()
      do j = 1, size(obs)
        call obs(j)%o%increment_done(m, res)
      end do
      timing%results = timing%results + (t1 - t0)
      timing%output = timing%output + (wall_time() - t1)
    end do
    summary%factorisations = merge(1, 0, modes%method(1:6) == 'ARPACK')
    summary%continuum_stresses = counts%continuum_stresses
  end subroutine report_modes
end module frequency_step
