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
module condensed_contact
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  use model, only: model_t, carries_stiffness, elem_nodes
  use solver_codes, only: solver_cholmod, contact_solve_full, contact_solve_condensed
  use contact, only: cfe_t, contact_set_t, cfe_input, cfe_nodes, contact_forces
  use element_interface, only: elem_in_t, elem_out_t, max_en, max_edof, act_tangent
  use element_library, only: element_routine
  use assembly, only: body_t, element_counts_t, assemble_stiffness, free_residual
  use dof_numbering, only: dofmap_t, number_dofs
  use linear_solver, only: linear_system_t, sys_condensed_factor, sys_trailing_order, sys_forward, sys_backward, &
                           sys_factor_flops, sys_nlast, factor_ok, factor_singular, pivot_ratio_min
  use dense_cholesky, only: dense_factor, dense_solve, upper_times, lower_gram
  implicit none
  private
  public :: condensed_t, number_equations, condensed_factor_k0, condensed_status, condensed_begin, &
            condensed_solve, condensed_recover, condensed_correct, contact_part_forces, add_body_forces

  !> With CONTACT SOLVE=AUTO: the condensed solve is taken when one dense
  !> factorisation of S (m^3/3 operations) costs at most this share of a
  !> sparse factorisation of the whole system, and m is at most
  !> auto_max_m (two m x m matrices are kept).
  real(dp), parameter :: auto_flop_share = 0.5_dp
  integer, parameter :: auto_max_m = 6000

  type :: condensed_t
    logical :: active = .false.         ! this numbering is for the condensed solve
    integer :: n = 0, m = 0             ! equations, contact equations (the last m)
    integer, allocatable :: pos(:)      ! (n) trailing position of an equation, 0 for the others
    integer, allocatable :: eq_at(:)    ! (m) equation at a trailing position
    integer, allocatable :: cfe_pos(:, :)       ! (max_edof, ncfe) position of each CFE dof, 0 if none
    real(dp), allocatable :: ke0(:, :, :)       ! (max_edof, max_edof, ncfe) CFE tangents as in K0
    !> One m x m array for two matrices: the trailing block L22 of the
    !> factor of K0 as its transpose in the upper triangle and diagonal,
    !> the Schur complement S0 of K0 in the strict lower triangle (its
    !> diagonal in s0_diag), so that S's columns are copied contiguously.
    real(dp), allocatable :: l22(:, :), s0_diag(:)
    real(dp), allocatable :: s(:, :)    ! Cholesky factor of S of the current status (lower)
    real(dp), allocatable :: diag22(:)  ! K0's diagonal on the contact equations
    real(dp), allocatable :: kdiag(:)   ! the diagonal of the current status
    real(dp), allocatable :: z(:)       ! (n) forward-solved right-hand side of the increment
    real(dp), allocatable :: q0(:), x2(:)       ! (m) condensed right-hand side, solution
    real(dp), allocatable :: u0(:, :)   ! displacements at the start of the increment
    real(dp) :: umax_rest = 0.0_dp      ! largest |u0| off the contact equations
    real(dp), allocatable :: fw(:, :)   ! (2, nn) work: CFE forces, zero between uses
    real(dp) :: kmax = 0.0_dp           ! largest element diagonal of the current status
  end type condensed_t

contains

  !> Purpose: numbers the equations for the contact solve the model asks
  !> for (m%contact_solve) and sets up the solver's structure: with the
  !> condensed solve the contact equations last, cd%active and cd%m say so.
  !> The full solve where the model says FULL, without coupling elements,
  !> with a solver other than CHOLMOD, and (AUTO) where a dense
  !> factorisation of the condensed matrix would not be cheaper than a
  !> sparse one of the whole (m comparable to n).
  !> Arguments: t_analyse returns the wall time of the symbolic analysis
  !> done here to decide (0 when none was needed).
  subroutine number_equations(m, cs, prescribed, dm, sys, cd, t_analyse)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    logical, intent(in) :: prescribed(:, :)
    type(dofmap_t), intent(out) :: dm
    type(linear_system_t), intent(inout) :: sys
    type(condensed_t), intent(inout) :: cd
    real(dp), intent(out) :: t_analyse
    logical, allocatable :: mask(:, :)
    integer :: mc
    real(dp) :: flops
    integer(kind=8) :: c0, c1, rate
    t_analyse = 0.0_dp
    cd%active = .false.
    cd%m = 0
    if (m%contact_solve /= contact_solve_full .and. m%solver == solver_cholmod .and. cs%n > 0) then
      call contact_dof_mask(m, cs, prescribed, mask)
      mc = count(mask)
      if (mc > 0) then
        call number_dofs(m, cs, prescribed, m%solver, m%ordering, dm, sys, mask)
        cd%active = m%contact_solve == contact_solve_condensed
        if (.not. cd%active .and. mc <= auto_max_m) then
          call system_clock(c0, rate)
          flops = sys_factor_flops(sys)
          call system_clock(c1)
          t_analyse = real(c1 - c0, dp) / real(rate, dp)
          cd%active = real(mc, dp)**3 / 3.0_dp <= auto_flop_share * flops
        end if
        if (cd%active) then
          cd%n = dm%neq
          cd%m = mc
          return
        end if
      end if
    end if
    call number_dofs(m, cs, prescribed, m%solver, m%ordering, dm, sys)
  end subroutine number_equations

  !> The contact equations: free dofs on the diagonal of some CFE's closed
  !> tangent (those its B_e^T n reaches; where the normal has no x
  !> component, the x dofs are not among them).
  subroutine contact_dof_mask(m, cs, prescribed, mask)
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    logical, intent(in) :: prescribed(:, :)
    logical, allocatable, intent(out) :: mask(:, :)
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    type(cfe_t) :: c
    real(dp), allocatable :: u(:, :)
    integer :: j, k, d, nodes(max_en)
    allocate(mask(2, m%nn), u(2, m%nn))
    mask = .false.
    u = 0.0_dp
    do j = 1, cs%n
      c = cs%c(j)
      c%closed = .true.
      call cfe_input(m, c, u, .false., ein, nodes)
      call element_routine(act_tangent, ein, eout)
      do k = 1, ein%nen
        do d = 1, 2
          if (eout%ke(2 * k - 2 + d, 2 * k - 2 + d) /= 0.0_dp .and. .not. prescribed(d, nodes(k))) &
            mask(d, nodes(k)) = .true.
        end do
      end do
    end do
  end subroutine contact_dof_mask

  !> Purpose: assembles K0 (the bodies and every CFE open, nominal
  !> penalty), factors it with the contact block last and forms S0; maps
  !> the contact equations and the CFEs' dofs to trailing positions.
  !> Arguments: status, bad as sys_factor (factor_singular: the bodies are
  !> singular even with the contact equations held, which no contact
  !> status can mend); counts counts the CFE routine calls.
  subroutine condensed_factor_k0(cd, m, cs, body, dm, sys, counts, status, bad)
    type(condensed_t), intent(inout) :: cd
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    type(body_t), intent(in) :: body
    type(dofmap_t), intent(in) :: dm
    type(linear_system_t), intent(inout) :: sys
    type(element_counts_t), intent(inout) :: counts
    integer, intent(out) :: status, bad
    type(contact_set_t) :: open_set
    integer, allocatable :: tperm(:)
    real(dp) :: kmax
    integer :: p, mc
    mc = sys_nlast(sys)
    cd%n = dm%neq
    cd%m = mc
    if (.not. allocated(cd%u0)) allocate(cd%u0(2, m%nn))
    cd%u0 = 0.0_dp
    open_set = cs
    open_set%c(1:cs%n)%closed = .false.
    open_set%stabilised = .false.
    call assemble_stiffness(m, open_set, body, cd%u0, sys, kmax, counts)
    if (allocated(cd%l22)) deallocate(cd%l22, cd%s0_diag, cd%s, cd%diag22, cd%kdiag, cd%q0, cd%x2, cd%eq_at)
    allocate(cd%l22(mc, mc), cd%s0_diag(mc), cd%s(mc, mc), cd%diag22(mc), cd%kdiag(mc), cd%q0(mc), cd%x2(mc), &
             cd%eq_at(mc), tperm(mc))
    call sys_condensed_factor(sys, status, bad, cd%l22, cd%diag22)
    if (status /= factor_ok) return
    call sys_trailing_order(sys, tperm)
    cd%eq_at = cd%n - mc + tperm
    cd%pos = [(0, p = 1, cd%n)]
    cd%pos(cd%eq_at) = [(p, p = 1, mc)]
    ! the factor was of K0 with its trailing diagonal doubled
    call lower_gram(cd%l22, cd%s)
    do p = 1, mc
      cd%s0_diag(p) = cd%s(p, p) - cd%diag22(p)
      cd%l22(p, p + 1:mc) = cd%l22(p + 1:mc, p)
      cd%l22(p + 1:mc, p) = cd%s(p + 1:mc, p)
    end do
    call map_cfes(cd, m, cs, dm, open_set, counts)
  end subroutine condensed_factor_k0

  !> Trailing positions of every CFE's dofs, and its tangent as in K0.
  subroutine map_cfes(cd, m, cs, dm, open_set, counts)
    type(condensed_t), intent(inout) :: cd
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs, open_set
    type(dofmap_t), intent(in) :: dm
    type(element_counts_t), intent(inout) :: counts
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    integer :: j, k, d, e, nodes(max_en)
    if (allocated(cd%ke0)) deallocate(cd%ke0, cd%cfe_pos)
    allocate(cd%ke0(max_edof, max_edof, cs%n), cd%cfe_pos(max_edof, cs%n))
    cd%cfe_pos = 0
    cd%ke0 = 0.0_dp
    do j = 1, cs%n
      call cfe_input(m, open_set%c(j), cd%u0, .false., ein, nodes)
      call element_routine(act_tangent, ein, eout)
      counts%coupling = counts%coupling + 1
      cd%ke0(1:eout%ndof, 1:eout%ndof, j) = eout%ke(1:eout%ndof, 1:eout%ndof)
      do k = 1, ein%nen
        do d = 1, 2
          e = dm%eq(d, nodes(k))
          if (e > 0) cd%cfe_pos(2 * k - 2 + d, j) = cd%pos(e)
        end do
      end do
    end do
  end subroutine map_cfes

  !> Purpose: factors S of the current contact status (cs: statuses and
  !> stabilisation): S0 plus every CFE's tangent minus its tangent in K0
  !> (the lower triangles; LAPACK leaves the upper one alone).
  !> Arguments: kbody the bodies' largest element diagonal; status
  !> factor_ok or factor_singular (bad: the equation whose pivot vanished,
  !> judged as the sparse backends judge theirs: relative to the diagonal
  !> entry of the status's full matrix); counts counts CFE routine calls.
  subroutine condensed_status(cd, m, cs, kbody, counts, status, bad)
    type(condensed_t), intent(inout) :: cd
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(in) :: cs
    real(dp), intent(in) :: kbody
    type(element_counts_t), intent(inout) :: counts
    integer, intent(out) :: status, bad
    type(elem_in_t) :: ein
    type(elem_out_t) :: eout
    integer :: j, a, b, pa, pb, nd, info, nodes(max_en)
    real(dp) :: dk, ratio
    do b = 1, cd%m
      cd%s(b, b) = cd%s0_diag(b)
      cd%s(b + 1:cd%m, b) = cd%l22(b + 1:cd%m, b)
    end do
    cd%kdiag = cd%diag22
    cd%kmax = kbody
    do j = 1, cs%n
      call cfe_input(m, cs%c(j), cd%u0, cs%stabilised, ein, nodes)
      call element_routine(act_tangent, ein, eout)
      counts%coupling = counts%coupling + 1
      nd = eout%ndof
      do b = 1, nd
        cd%kmax = max(cd%kmax, abs(eout%ke(b, b)))
        pb = cd%cfe_pos(b, j)
        if (pb == 0) cycle
        do a = 1, nd
          pa = cd%cfe_pos(a, j)
          if (pa < pb) cycle               ! the lower triangle only
          dk = eout%ke(a, b) - cd%ke0(a, b, j)
          cd%s(pa, pb) = cd%s(pa, pb) + dk
          if (pa == pb) cd%kdiag(pa) = cd%kdiag(pa) + dk
        end do
      end do
    end do
    status = factor_ok
    bad = 0
    call dense_factor(cd%s, info)
    if (info > 0) then
      status = factor_singular
      bad = cd%eq_at(info)
      return
    end if
    do a = 1, cd%m
      ratio = 0.0_dp
      if (cd%kdiag(a) > 0.0_dp) ratio = cd%s(a, a)**2 / cd%kdiag(a)
      if (ratio < pivot_ratio_min) then
        status = factor_singular
        bad = cd%eq_at(a)
        return
      end if
    end do
  end subroutine condensed_status

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
    integer :: a, d, e
    cd%u0 = u
    if (.not. allocated(cd%fw)) then
      allocate(cd%fw(2, m%nn))
      cd%fw = 0.0_dp
    end if
    if (allocated(cd%z)) then
      if (size(cd%z) /= cd%n) deallocate(cd%z)
    end if
    if (.not. allocated(cd%z)) allocate(cd%z(cd%n))
    cd%umax_rest = 0.0_dp
    do a = 1, m%nn
      do d = 1, 2
        e = dm%eq(d, a)
        if (e > 0) then
          if (cd%pos(e) > 0) cycle
        end if
        cd%umax_rest = max(cd%umax_rest, abs(u(d, a)))
      end do
    end do
    call free_residual(dm, fext, fbody, cd%z)
    call sys_forward(sys, cd%z)
    cd%q0 = cd%z(cd%n - cd%m + 1:cd%n)
    call upper_times(cd%l22, cd%q0, .true.)
  end subroutine condensed_begin

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
    integer :: p, e, j, nen, nodes(max_en)
    call contact_forces(m, cs, u, cd%fw, ncalls)
    do p = 1, cd%m
      e = cd%eq_at(p)
      f(p) = cd%fw(dm%dof_of_eq(e), dm%node_of_eq(e))
    end do
    do j = 1, cs%n
      call cfe_nodes(m, cs%c(j), nodes, nen)
      cd%fw(:, nodes(1:nen)) = 0.0_dp
    end do
  end subroutine contact_part_forces

  !> Purpose: f += K_body du, element by element, skipping the elements
  !> where du is zero (between increments only prescribed values move).
  subroutine add_body_forces(m, body, du, f)
    type(model_t), intent(in) :: m
    type(body_t), intent(in) :: body
    real(dp), intent(in) :: du(:, :)
    real(dp), intent(inout) :: f(:, :)
    real(dp) :: ue(2 * max_en), fe(2 * max_en), a
    logical :: moved(size(du, 2)), any_moved
    integer :: e, i, j, k, nen, nd
    integer(kind=8) :: q
    moved = du(1, :) /= 0.0_dp .or. du(2, :) /= 0.0_dp
    if (.not. any(moved)) return
    do e = 1, m%ne
      if (.not. carries_stiffness(m, e)) cycle
      nen = elem_nodes(m, e)
      any_moved = .false.
      do k = 1, nen
        any_moved = any_moved .or. moved(m%conn(k, e))
      end do
      if (.not. any_moved) cycle
      nd = 2 * nen
      do k = 1, nen
        ue(2 * k - 1:2 * k) = du(:, m%conn(k, e))
      end do
      fe(1:nd) = 0.0_dp
      ! the stored upper triangle, column by column
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
    end do
  end subroutine add_body_forces

  !> Purpose: the contact equations for the current status (factored by
  !> condensed_status): S x2 = q0 - (CFE forces at the increment's start).
  !> u(contact equations) returns the start of the increment plus x2,
  !> enough for every gap; the caller keeps the other equations at the
  !> start until condensed_recover. finite says whether x2 is.
  subroutine condensed_solve(cd, m, cs, dm, u, finite, ncalls)
    type(condensed_t), intent(inout) :: cd
    type(model_t), intent(in) :: m
    type(contact_set_t), intent(inout) :: cs
    type(dofmap_t), intent(in) :: dm
    real(dp), intent(inout) :: u(:, :)
    logical, intent(out) :: finite
    integer(kind=8), intent(inout) :: ncalls
    real(dp) :: fc(cd%m)
    ! the CFE forces are affine in u: at the start, they are the constant part
    call contact_part_forces(cd, m, cs, dm, cd%u0, fc, ncalls)
    cd%x2 = cd%q0 - fc
    call dense_solve(cd%s, cd%x2)
    finite = all(ieee_is_finite(cd%x2))
    call add_contact_part(cd, dm, u)
  end subroutine condensed_solve

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
  !> them).
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
    call dense_solve(cd%s, t)
    call upper_times(cd%l22, t, .false.)
    r(cd%n - cd%m + 1:cd%n) = t
    call sys_backward(sys, r)
  end subroutine condensed_correct
end module condensed_contact
