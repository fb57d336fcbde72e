!> The driver of a run: steps, increments, prescribed values and loads at
!> each increment, and the contact status iteration (penalty switching) of
!> section 5 of the paper with increment bisection when it does not settle.
module analysis
  use, intrinsic :: iso_fortran_env, only: output_unit
  use kinds, only: dp
  use strings, only: itoa, rtoa
  use model
  use contact, only: contact_set_t, contact_search
  use assembly, only: dofmap_t, number_dofs, assemble, internal_forces, stress_recovery
  use results_gmsh, only: result_file_t, write_result_views
  use linear_solver, only: linear_system_t, sys_factor, sys_solve, sys_describe, sys_setup, sys_free, &
                           factor_ok, factor_singular, factor_fallback, solver_skyline, order_natural
  use listing, only: listing_t, write_step_header, write_increment, write_iteration, write_text, &
                     contact_results_t, contact_results
  use messages, only: fatal, warn
  implicit none
  private
  public :: run_analysis

contains

  !> Piecewise-linear tabular amplitude, constant beyond its ends.
  pure real(dp) function amplitude_value(a, t)
    type(amplitude_t), intent(in) :: a
    real(dp), intent(in) :: t
    integer :: k, n
    n = size(a%t)
    if (t <= a%t(1)) then
      amplitude_value = a%a(1)
    else if (t >= a%t(n)) then
      amplitude_value = a%a(n)
    else
      do k = 2, n
        if (t <= a%t(k)) exit
      end do
      amplitude_value = a%a(k - 1) + (a%a(k) - a%a(k - 1)) * (t - a%t(k - 1)) / (a%t(k) - a%t(k - 1))
    end if
  end function amplitude_value

  subroutine run_analysis(m, lst, res, quiet)
    type(model_t), intent(in) :: m
    type(listing_t), intent(in) :: lst
    type(result_file_t), intent(inout) :: res    ! written when res%open
    logical, intent(in) :: quiet
    real(dp), allocatable :: u(:, :), fext(:, :), fint(:, :), rf(:, :)
    real(dp), allocatable :: bc_start(:, :), bc_target(:, :), ld_start(:, :), ld_target(:, :)
    integer, allocatable :: bc_amp(:, :), bc_set(:, :), ld_amp(:, :), set_ids(:)
    logical, allocatable :: presc(:, :)
    real(dp), allocatable :: rhs(:), set_sums(:, :)
    type(contact_set_t) :: cs
    type(dofmap_t) :: dm
    type(linear_system_t) :: sys
    logical :: described
    integer :: is, i, ninc, inc, j, nset
    real(dp) :: total_time, period
    character(len=:), allocatable :: last_changed
    logical :: factor_valid, update_search
    logical, allocatable :: factor_states(:)
    integer :: nfactor
    real(dp) :: kmax

    allocate(u(2, m%nn), fext(2, m%nn), fint(2, m%nn), rf(2, m%nn), presc(2, m%nn), &
             bc_start(2, m%nn), bc_target(2, m%nn), ld_start(2, m%nn), ld_target(2, m%nn), &
             bc_amp(2, m%nn), bc_set(2, m%nn), ld_amp(2, m%nn))
    u = 0.0_dp
    fext = 0.0_dp
    presc = .false.
    bc_target = 0.0_dp
    bc_set = 0
    ld_target = 0.0_dp
    ld_amp = 0
    ! Small deformation: one search on the initial configuration.
    call contact_search(m, m%x, cs)
    update_search = .false.
    if (size(m%pairs) > 0) update_search = any(m%pairs%update_search)
    allocate(factor_states(cs%n))
    factor_valid = .false.
    nfactor = 0
    kmax = 0.0_dp
    total_time = 0.0_dp

    do is = 1, size(m%steps)
      associate(st => m%steps(is))
        ! Dofs held from earlier steps stay where they are.
        bc_start = u
        where (presc) bc_target = u
        bc_amp = 0
        if (st%new_bcs) then
          presc = .false.
          bc_set = 0
        end if
        do j = 1, size(m%model_bcs)
          call prescribe(m%model_bcs(j), .true.)
        end do
        do j = 1, size(st%bcs)
          call prescribe(st%bcs(j), .false.)
        end do
        ld_start = fext
        ld_amp = 0
        if (st%new_loads) then
          ld_start = 0.0_dp
          ld_target = 0.0_dp
        else
          ld_target = fext
        end if
        do j = 1, size(st%loads)
          ld_target(st%loads(j)%dof, st%loads(j)%node) = st%loads(j)%value
          ld_amp(st%loads(j)%dof, st%loads(j)%node) = st%loads(j)%amp
        end do
        call prescribed_sets()

        call number_dofs(m, cs, presc, m%solver, m%ordering, dm, sys)
        factor_valid = .false.
        described = .false.
        if (allocated(rhs)) deallocate(rhs)
        allocate(rhs(dm%neq))
        call write_step_header(lst, is, m, dm%neq, count(presc), cs)
        period = st%period
        ninc = nint(period / st%dt)
        inc = 0
        nfactor = 0
        do i = 1, ninc
          call advance(is, period * (i - 1) / ninc, period * i / ninc, 0)
        end do
        call write_text(lst, '')
        call write_text(lst, '--- STEP SUMMARY step=' // itoa(is))
        call write_text(lst, 'item value')
        call write_text(lst, 'increments ' // itoa(inc))
        call write_text(lst, 'numeric_factorisations ' // itoa(nfactor))
        total_time = total_time + period
      end associate
    end do

  contains

    subroutine prescribe(bc, immediate)
      type(bc_t), intent(in) :: bc
      logical, intent(in) :: immediate
      presc(bc%dof, bc%node) = .true.
      bc_target(bc%dof, bc%node) = bc%value
      bc_amp(bc%dof, bc%node) = bc%amp
      if (bc%set > 0) bc_set(bc%dof, bc%node) = bc%set
      if (immediate) bc_start(bc%dof, bc%node) = bc%value
    end subroutine prescribe

    !> Node sets named by active boundary conditions, for reaction sums.
    subroutine prescribed_sets()
      integer :: a, d, s
      logical, allocatable :: used(:)
      allocate(used(size(m%nsets)))
      used = .false.
      do a = 1, m%nn
        do d = 1, 2
          s = bc_set(d, a)
          if (presc(d, a) .and. s > 0) used(s) = .true.
        end do
      end do
      set_ids = pack([(s, s = 1, size(m%nsets))], used)
      nset = size(set_ids)
      if (allocated(set_sums)) deallocate(set_sums)
      allocate(set_sums(2, nset))
    end subroutine prescribed_sets

    !> Prescribed displacements and loads at step time t.
    subroutine values_at(is, t)
      integer, intent(in) :: is
      real(dp), intent(in) :: t
      integer :: a, d
      real(dp) :: ramp
      ramp = t / m%steps(is)%period
      do a = 1, m%nn
        do d = 1, 2
          u(d, a) = 0.0_dp
          if (presc(d, a)) then
            if (bc_amp(d, a) > 0) then
              u(d, a) = bc_target(d, a) * amp_at(bc_amp(d, a), t)
            else
              u(d, a) = bc_start(d, a) + (bc_target(d, a) - bc_start(d, a)) * ramp
            end if
          end if
          if (ld_amp(d, a) > 0) then
            fext(d, a) = ld_target(d, a) * amp_at(ld_amp(d, a), t)
          else
            fext(d, a) = ld_start(d, a) + (ld_target(d, a) - ld_start(d, a)) * ramp
          end if
        end do
      end do
    end subroutine values_at

    real(dp) function amp_at(ia, t)
      integer, intent(in) :: ia
      real(dp), intent(in) :: t
      if (m%amplitudes(ia)%time == amp_total_time) then
        amp_at = amplitude_value(m%amplitudes(ia), total_time + t)
      else
        amp_at = amplitude_value(m%amplitudes(ia), t)
      end if
    end function amp_at

    !> Takes the solution from step time t0 to t1; bisects when the contact
    !> status does not settle.
    recursive subroutine advance(is, t0, t1, level)
      integer, intent(in) :: is, level
      real(dp), intent(in) :: t0, t1
      logical, allocatable :: saved(:)
      logical :: ok
      integer :: iters
      if (update_search .and. inc + level > 0) call research()
      allocate(saved(cs%n))
      saved = cs%c(1:cs%n)%closed
      call solve_at(is, t1, ok, iters)
      if (ok) then
        inc = inc + 1
        call report(is, t1, iters)
        return
      end if
      cs%c(1:cs%n)%closed = saved
      if (level >= m%max_cutbacks) then
        call write_text(lst, 'contact status did not settle; nodes still switching:' // last_changed)
        call fatal('contact status did not settle in step ' // itoa(is) // ' at time ' // rtoa(t1, 6) // &
          ' after ' // itoa(level) // ' bisections; nodes still switching:' // last_changed)
      end if
      call write_text(lst, 'contact status did not settle: increment bisected')
      call advance(is, t0, 0.5_dp * (t0 + t1), level + 1)
      call advance(is, 0.5_dp * (t0 + t1), t1, level + 1)
    end subroutine advance

    !> UPDATE SEARCH: pair again on the deformed configuration. A slave node
    !> keeps the status it had; the equations are renumbered for the new
    !> couplings.
    subroutine research()
      type(contact_set_t) :: old
      integer :: j, q
      old = cs
      call contact_search(m, m%x + u, cs)
      do j = 1, cs%n
        do q = 1, old%n
          if (old%c(q)%slave == cs%c(j)%slave .and. old%c(q)%pair == cs%c(j)%pair) then
            cs%c(j)%closed = old%c(q)%closed
            exit
          end if
        end do
      end do
      call number_dofs(m, cs, presc, m%solver, m%ordering, dm, sys)
      factor_valid = .false.
      if (allocated(factor_states)) deallocate(factor_states)
      allocate(factor_states(cs%n))
    end subroutine research

    subroutine solve_at(is, t, ok, it)
      integer, intent(in) :: is
      real(dp), intent(in) :: t
      logical, intent(out) :: ok
      integer, intent(out) :: it
      integer :: bad, a, d, c, nchanged
      real(dp) :: resid, ref, kelem
      integer :: status
      logical :: closed, refactor
      ok = .false.
      call values_at(is, t)
      ! Newton iterations on the piecewise-linear system: each solves
      ! K du = f_ext - f_int(u) with the current contact status. With an
      ! unchanged status the next pass only removes round-off.
      do it = 1, m%contact_max_iter
        ! The stiffness depends only on the contact status: its factor is
        ! kept while the status is the one it was made for.
        refactor = .not. factor_valid
        if (.not. refactor) refactor = any(factor_states .neqv. cs%c(1:cs%n)%closed)
        call assemble(m, cs, u, fext, dm, sys, rhs, refactor, kelem)
        if (refactor) then
          kmax = kelem
          call sys_factor(sys, status, bad)
          if (status == factor_singular) call singular(bad)
          if (status == factor_fallback) then
            call write_text(lst, sys%note)
            call warn(sys%note)
          end if
          if (.not. described) then
            call write_text(lst, '--- SOLVER step=' // itoa(is))
            call write_text(lst, 'item value')
            call write_text(lst, 'factor ' // sys_describe(sys))
            described = .true.
          end if
          factor_states = cs%c(1:cs%n)%closed
          factor_valid = .true.
          nfactor = nfactor + 1
        end if
        call sys_solve(sys, rhs)
        do a = 1, m%nn
          do d = 1, 2
            if (dm%eq(d, a) > 0) u(d, a) = u(d, a) + rhs(dm%eq(d, a))
          end do
        end do
        call internal_forces(m, cs, u, fint)
        ! Penalty switching: a compressive normal force (negative gap)
        ! closes the CFE, a tensile one opens it.
        nchanged = 0
        last_changed = ''
        do c = 1, cs%n
          closed = cs%c(c)%gap < 0.0_dp
          if (closed .neqv. cs%c(c)%closed) then
            nchanged = nchanged + 1
            if (nchanged <= 20) last_changed = last_changed // ' ' // itoa(m%node_id(cs%c(c)%slave))
            cs%c(c)%closed = closed
          end if
        end do
        if (nchanged > 0) call internal_forces(m, cs, u, fint)
        rf = fint - fext
        resid = 0.0_dp
        ref = 0.0_dp
        do a = 1, m%nn
          do d = 1, 2
            if (dm%eq(d, a) > 0) then
              resid = resid + rf(d, a)**2
            else
              ref = ref + rf(d, a)**2
            end if
          end do
        end do
        ! Force scale: loads, reactions, contact forces, and (for a body
        ! that only moves rigidly) the stiffness times the displacement
        ! scaled to a strain of 1e-6, so that round-off is not mistaken
        ! for an out-of-balance force.
        ref = max(sqrt(ref), norm2(fext), sum(abs(cs%c(1:cs%n)%force)), &
                  1.0e-6_dp * kmax * maxval(abs(u)), tiny(1.0_dp))
        resid = sqrt(resid) / ref
        if (cs%n > 0) call write_iteration(lst, it, nchanged, count(cs%c(1:cs%n)%closed), resid, &
                                           changed_text(nchanged))
        if (nchanged == 0 .and. resid < m%contact_tolerance) then
          ok = .true.
          return
        end if
      end do
      it = it - 1
    end subroutine solve_at

    !> Stops on a singular stiffness, naming the node and dof. The sparse
    !> solvers do not say where: a skyline factorisation of the same
    !> matrix finds it when the problem is small enough.
    subroutine singular(bad)
      integer, intent(in) :: bad
      integer :: where, st
      type(linear_system_t) :: probe
      real(dp) :: kdummy
      real(dp), allocatable :: r(:)
      where = bad
      if (where == 0 .and. dm%neq <= 200000) then
        call sys_setup(probe, solver_skyline, order_natural, dm%neq, sys%xeq, sys%eqs)
        allocate(r(dm%neq))
        call assemble(m, cs, u, fext, dm, probe, r, .true., kdummy)
        call sys_factor(probe, st, where)
        call sys_free(probe)
      end if
      if (where > 0) call fatal('singular stiffness at node ' // itoa(m%node_id(dm%node_of_eq(where))) // &
        ', dof ' // itoa(dm%dof_of_eq(where)) // ' (missing boundary condition?)' // contact_hint())
      call fatal('singular stiffness (missing boundary condition?)' // contact_hint())
    end subroutine singular

    function changed_text(n) result(s)
      integer, intent(in) :: n
      character(len=:), allocatable :: s
      s = ''
      if (n > 0) s = ' (nodes' // last_changed // merge(' ...', '    ', n > 20) // ')'
    end function changed_text

    function contact_hint() result(s)
      character(len=:), allocatable :: s
      s = ''
      if (cs%n > 0) s = '; a body held only by open contact has no stiffness: give it a support, ' // &
        'start it in contact, or raise OPEN PENALTY on *CONTACT PAIR'
    end function contact_hint

    subroutine report(is, t, iters)
      integer, intent(in) :: is, iters
      real(dp), intent(in) :: t
      integer :: s, q, ip, j, e
      real(dp) :: force
      type(contact_results_t) :: cr
      type(request_t) :: fnode, felem
      integer, allocatable :: nip(:)
      real(dp), allocatable :: sig_ip(:, :, :), eps_ip(:, :, :), sig_node(:, :), sig_elem(:, :), pres(:)
      logical, allocatable :: has_pres(:)
      allocate(nip(m%ne), sig_ip(4, 4, m%ne), eps_ip(3, 4, m%ne), sig_node(4, m%nn), sig_elem(4, m%ne))
      ! Requests to file of this step, merged into one nodal and one element set of views.
      do q = 1, size(m%steps(is)%requests)
        associate(r => m%steps(is)%requests(q))
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
      if (any(m%steps(is)%requests%s) .or. any(m%steps(is)%requests%e)) then
        call stress_recovery(m, u, nip, sig_ip, eps_ip, sig_node)
      else
        nip = 0
        sig_ip = 0.0_dp
        eps_ip = 0.0_dp
        sig_node = 0.0_dp
      end if
      do s = 1, nset
        set_sums(:, s) = 0.0_dp
        do q = 1, size(m%nsets(set_ids(s))%items)
          set_sums(:, s) = set_sums(:, s) + rf(:, m%nsets(set_ids(s))%items(q))
        end do
      end do
      call write_increment(lst, m, is, inc, t, total_time + t, iters, u, rf, cs, set_sums, set_ids, &
                           nip, sig_ip, eps_ip, sig_node)
      force = 0.0_dp
      allocate(pres(m%nn), has_pres(m%nn))
      pres = 0.0_dp
      has_pres = .false.
      do ip = 1, size(m%pairs)
        if (m%pairs(ip)%twin > 0 .and. m%pairs(ip)%twin < ip) cycle
        call contact_results(m, cs, ip, cr)
        force = force + cr%total
        do j = 1, size(cr%slave_cfe)
          associate(c => cs%c(cr%slave_cfe(j)))
            pres(c%slave) = cr%slave_force(j) / c%area
            has_pres(c%slave) = .true.
          end associate
        end do
        do j = 1, size(cr%master_node)
          if (cr%master_area(j) > 0.0_dp) pres(cr%master_node(j)) = cr%master_force(j) / cr%master_area(j)
          has_pres(cr%master_node(j)) = .true.
        end do
      end do
      if (res%open .and. (fnode%u .or. fnode%rf .or. fnode%s .or. fnode%cstress .or. felem%s)) then
        do e = 1, m%ne
          sig_elem(:, e) = 0.0_dp
          if (nip(e) > 0) sig_elem(:, e) = sum(sig_ip(:, 1:nip(e), e), dim=2) / nip(e)
        end do
        call write_result_views(res, m, fnode, felem, total_time + t, u, rf, sig_node, sig_elem, pres, has_pres)
      end if
      if (.not. quiet) then
        write(output_unit, '(a,i0,a,i0,a,es11.4,a,i0,a,i0,a,es12.5)') 'step ', is, '  increment ', inc, &
          '  time ', total_time + t, '  iterations ', iters, '  closed ', count(cs%c(1:cs%n)%closed), &
          '  contact force ', force
        flush(output_unit)
      end if
    end subroutine report
  end subroutine run_analysis

end module analysis
