!> The results of one converged increment, computed once and consumed by
!> every writer (listing, contact table, gmsh file, progress line):
!> displacements, reactions and their sums over prescribed node sets,
!> stresses at the integration points and the nodes, contact results.
module increment_results
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  use strings, only: itoa
  use messages, only: fatal
  use element_catalogue, only: max_ip, catalogue
  use model
  use contact, only: contact_set_t
  use contact_results, only: contact_results_t, compute_contact_results, contact_total_force, model_has_friction
  use assembly, only: stress_recovery, element_counts_t, body_t
  implicit none
  private
  public :: increment_results_t, compute_increment_results, output_due, written_here

  type :: increment_results_t
    integer :: step = 0, increment = 0, iterations = 0
    real(dp) :: time = 0.0_dp, total_time = 0.0_dp   ! step time and total time
    real(dp), allocatable :: u(:, :), rf(:, :)        ! (2, nn)
    integer, allocatable :: set_ids(:)                ! node sets summed
    real(dp), allocatable :: set_sums(:, :)           ! (2, size(set_ids))
    logical :: has_stresses = .false.
    integer, allocatable :: nip(:)                    ! (ne)
    real(dp), allocatable :: sig_ip(:, :, :)          ! (4, max_ip, ne); stress arrays are empty
                                                      ! when no request asks for S or E
    real(dp), allocatable :: eps_ip(:, :, :)          ! (3, max_ip, ne)
    real(dp), allocatable :: sig_node(:, :)           ! (4, nn)
    real(dp), allocatable :: sig_elem(:, :)           ! (4, ne) element averages
    type(contact_results_t) :: contact
    integer :: nclosed = 0
    !> A nonlinear step: its increment size (step time); the stresses are
    !> Cauchy stresses (NLGEOM); has_peeq: peeq_ip(max_ip, ne) holds the
    !> equivalent plastic strain at the integration points (asked for by
    !> PEEQ; empty otherwise).
    logical :: nonlinear = .false.
    real(dp) :: dt = 0.0_dp
    logical :: has_peeq = .false.
    real(dp), allocatable :: peeq_ip(:, :)
    real(dp), allocatable :: peeq_elem(:)             ! (ne) element averages when has_peeq
    !> A heat transfer step's increment (temperature_field): nt(nn) the
    !> temperatures, rfl(nn) the reaction fluxes, hfl_ip(2, max_ip, ne)
    !> the heat flux -k grad T at the nip(e) integration points (when
    !> HFL is asked for; empty otherwise); u and rf are zero.
    logical :: heat = .false.
    real(dp), allocatable :: nt(:), rfl(:), hfl_ip(:, :, :)
    !> A *FREQUENCY step's first mode carries the step's table
    !> (frequency_step): modes(6, number of modes) the eigenvalue, omega,
    !> frequency and participation factors along x, y and about z;
    !> modal_total the total effective masses r^T M r (x, y, about z).
    real(dp), allocatable :: modes(:, :)
    real(dp) :: modal_total(3) = 0.0_dp
  end type increment_results_t

contains

  !> Purpose: results of the increment that ended at step time t of step
  !> is, from the converged u, the residual rf = f_int - f_ext (reactions
  !> where prescribed) and the contact set.
  !> Arguments: set_ids node sets whose reactions are summed; counts
  !> counts the element routine calls of the stress recovery; dtemp(nn)
  !> the nodal temperature changes at t, given when there is thermal strain;
  !> dt the increment's length (the displacement field's increments:
  !> stresses and contact rows only where written); lean, an increment
  !> solved on the contact equations alone (condensed_equilibrium: its
  !> solve checked them finite, and the other equations are the last
  !> written increment's): where it is not written and no reaction sums
  !> are printed, u and rf are not copied (no writer reads them).
  subroutine compute_increment_results(m, is, inc, t, total_time, iters, u, rf, cs, set_ids, res, counts, dtemp, &
                                       body, dt, lean)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is, inc, iters
    real(dp), intent(in) :: t, total_time
    real(dp), intent(in) :: u(:, :), rf(:, :)
    type(contact_set_t), intent(in) :: cs
    integer, intent(in) :: set_ids(:)
    type(increment_results_t), intent(out) :: res
    type(element_counts_t), intent(inout) :: counts
    real(dp), intent(in), optional :: dtemp(:)
    type(body_t), intent(in), optional :: body
    real(dp), intent(in), optional :: dt
    logical, intent(in), optional :: lean
    logical :: written, copy
    res%step = is
    if (present(body)) res%nonlinear = body%nonlinear
    if (present(dt)) res%dt = dt
    res%increment = inc
    res%iterations = iters
    res%time = t
    res%total_time = total_time
    written = .true.
    if (present(dt)) written = written_here(m, is, inc, t, total_time, dt)
    copy = .true.
    if (present(lean)) copy = .not. lean .or. written .or. size(set_ids) > 0
    call nodal_results(m, u, rf, set_ids, copy, res)
    ! Stresses and strains only where a request asks for them and the
    ! increment's output is written (FREQUENCY=, TIME POINTS=: every
    ! writer that prints them follows output_due); the increments between
    ! carry empty stress arrays.
    res%has_stresses = any(m%steps(is)%requests%s) .or. any(m%steps(is)%requests%e) .or. &
                       any(m%steps(is)%requests%peeq)
    res%has_stresses = res%has_stresses .and. written
    res%has_peeq = res%has_stresses .and. any(m%steps(is)%requests%peeq)
    if (res%has_stresses) then
      call recover_stresses(m, u, res, counts, dtemp, body)
      ! the strains only where a card asks for E (every writer reads them
      ! only then): 3/7 of the integration-point arrays freed before the
      ! writers run
      if (.not. any(m%steps(is)%requests%e)) then
        deallocate(res%eps_ip)
        allocate(res%eps_ip(3, size(res%sig_ip, 2), 0))
      end if
    else
      ! nothing asks for stresses: no arrays of the model's size to fill
      ! (on a million elements they would be half a gigabyte of zeros)
      allocate(res%nip(m%ne), res%sig_ip(4, max_ip, 0), res%eps_ip(3, max_ip, 0), res%sig_node(4, 0), &
               res%sig_elem(4, 0), res%peeq_ip(max_ip, 0), res%peeq_elem(0))
      res%nip = 0
    end if
    ! The contact rows and nodal fields likewise only where written (every
    ! writer of them follows output_due); the increments between carry the
    ! total force alone, which the progress line prints.
    if (written) then
      call compute_contact_results(m, cs, u, res%contact)
    else
      res%contact%total_force = contact_total_force(m, cs)
      res%contact%frictional = model_has_friction(m)
      allocate(res%contact%pairs(0))
    end if
    res%nclosed = count(cs%c(1:cs%n)%closed)
    call check_finite(m, res)
  end subroutine compute_increment_results

  !> Purpose: the nodal results: u and rf (where copy; empty otherwise,
  !> an unwritten increment's that no writer reads), rf turned to global
  !> axes at *TRANSFORM nodes, the reaction sums of the node sets set_ids.
  subroutine nodal_results(m, u, rf, set_ids, copy, res)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: u(:, :), rf(:, :)
    integer, intent(in) :: set_ids(:)
    logical, intent(in) :: copy
    type(increment_results_t), intent(inout) :: res
    integer :: s, q, a
    if (copy) then
      res%u = u
      res%rf = rf
    else
      allocate(res%u(2, 0), res%rf(2, 0))
    end if
    ! A node with *TRANSFORM whose dofs cards named depends on the node
    ! carrying its local displacements, where its supports act: its own
    ! reaction is theirs, turned to global axes (the sums of the prescribed
    ! sets, which hold the node, are global, as CalculiX prints them).
    if (allocated(m%local_node) .and. size(res%rf, 2) > 0) then
      do a = 1, size(m%local_node)
        if (m%local_node(a) > 0) res%rf(:, a) = matmul(node_axes(m, a), rf(:, m%local_node(a)))
      end do
    end if
    res%set_ids = set_ids
    allocate(res%set_sums(2, size(set_ids)))
    do s = 1, size(set_ids)
      res%set_sums(:, s) = 0.0_dp
      do q = 1, size(m%nsets(set_ids(s))%items)
        res%set_sums(:, s) = res%set_sums(:, s) + res%rf(:, m%nsets(set_ids(s))%items(q))
      end do
    end do
  end subroutine nodal_results

  !> Purpose: the stresses (and strains, PEEQ) of the increment at the
  !> integration points, the nodes and as element averages.
  !> Arguments: m, u the model and displacements; res the results
  !> (has_stresses, has_peeq, nonlinear set; the arrays filled); counts
  !> the element call counts; dtemp, body as for compute_increment_results.
  !> The integration-point arrays hold as many points as the model's
  !> elements have (4 for a mesh of CPS4: 4/9 of max_ip's arrays).
  subroutine recover_stresses(m, u, res, counts, dtemp, body)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: u(:, :)
    type(increment_results_t), intent(inout) :: res
    type(element_counts_t), intent(inout) :: counts
    real(dp), intent(in), optional :: dtemp(:)
    type(body_t), intent(in), optional :: body
    integer :: e, nipm
    nipm = 1
    do e = 1, m%ne
      nipm = max(nipm, catalogue(m%etype(e))%nip)
    end do
    allocate(res%nip(m%ne), res%sig_ip(4, nipm, m%ne), res%eps_ip(3, nipm, m%ne), res%sig_node(4, m%nn), &
             res%sig_elem(4, m%ne), res%peeq_ip(max_ip, merge(m%ne, 0, res%has_peeq .or. res%nonlinear)))
    res%peeq_ip = 0.0_dp
    if (res%nonlinear) then
      call stress_recovery(m, u, res%nip, res%sig_ip, res%eps_ip, res%sig_node, counts, dtemp, body, res%peeq_ip)
    else
      call stress_recovery(m, u, res%nip, res%sig_ip, res%eps_ip, res%sig_node, counts, dtemp)
    end if
    do e = 1, m%ne
      res%sig_elem(:, e) = 0.0_dp
      if (res%nip(e) > 0) res%sig_elem(:, e) = sum(res%sig_ip(:, 1:res%nip(e), e), dim=2) / res%nip(e)
    end do
    allocate(res%peeq_elem(merge(m%ne, 0, res%has_peeq)))
    do e = 1, size(res%peeq_elem)
      res%peeq_elem(e) = 0.0_dp
      if (res%nip(e) > 0) res%peeq_elem(e) = sum(res%peeq_ip(1:res%nip(e), e)) / res%nip(e)
    end do
  end subroutine recover_stresses

  !> Purpose: is the output of the increment that ended at step time t
  !> (total time total_time, length dt) of step is written? output_due's
  !> rule with the previous increment's end at t - dt, moved back by 1e-12
  !> of the period (a thousandth of the rule's tolerance), so that the
  !> round-off of t - dt never leaves out stresses a writer prints, while
  !> a point on the previous increment's end still belongs to that one.
  !> Arguments: m the model; is, inc the step and increment; t, total_time
  !> its end in step and total time; dt its length.
  logical function written_here(m, is, inc, t, total_time, dt)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is, inc
    real(dp), intent(in) :: t, total_time, dt
    real(dp) :: tc
    tc = t
    if (m%steps(is)%out_total_time) tc = total_time
    written_here = output_due(m, is, inc, t, tc, tc - dt - 1.0e-12_dp * m%steps(is)%period)
  end function written_here

  !> Purpose: CalculiX's rule for the increments whose print and file
  !> output is written: always the last of a step (CalculiX writes the end
  !> of every step); otherwise every out_every-th increment (FREQUENCY=),
  !> or, with TIME POINTS=, an increment whose interval (last, tc] holds
  !> one (relative tolerance 1e-9 of the period, so that a point on an
  !> increment end is written there and not again at the next). Every
  !> writer's schedule (output_schedule) and the stresses computed here
  !> follow it.
  !> Arguments: m the model; is the step; inc the increment; t its end in
  !> step time; tc its end in the time the step's points are given in
  !> (step or total time); last the previous increment's end in that time.
  pure logical function output_due(m, is, inc, t, tc, last)
    type(model_t), intent(in) :: m
    integer, intent(in) :: is, inc
    real(dp), intent(in) :: t, tc, last
    real(dp) :: tol
    associate(s => m%steps(is))
      tol = 1.0e-9_dp * s%period
      output_due = t >= s%period - tol
      if (allocated(s%out_times)) then
        output_due = output_due .or. any(s%out_times > last + tol .and. s%out_times <= tc + tol)
      else
        output_due = output_due .or. mod(inc, max(s%out_every, 1)) == 0
      end if
    end associate
  end function output_due

  !> Purpose: stops the run, naming the increment, the quantity and where,
  !> if any result is not a finite number: nothing that is not a number is
  !> ever written. The increments before it are already on disk.
  subroutine check_finite(m, res)
    type(model_t), intent(in) :: m
    type(increment_results_t), intent(in) :: res
    character(len=:), allocatable :: where
    integer :: a, e, k
    where = 'step ' // itoa(res%step) // ', increment ' // itoa(res%increment) // ': '
    ! (a whole-array test first, a compare a value: every increment of a
    ! long history passes it; the loop names the node)
    if (.not. (all(abs(res%u) <= huge(1.0_dp)) .and. all(abs(res%rf) <= huge(1.0_dp)))) then
      do a = 1, size(res%u, 2)
        if (.not. all(ieee_is_finite(res%u(:, a)))) call stop_at('displacement', 'node', node_label(m, a))
        if (.not. all(ieee_is_finite(res%rf(:, a)))) call stop_at('reaction/internal force', 'node', node_label(m, a))
      end do
    end if
    do a = 1, size(res%sig_node, 2)
      if (.not. all(ieee_is_finite(res%sig_node(:, a)))) call stop_at('nodal stress', 'node', node_label(m, a))
    end do
    do e = 1, size(res%sig_ip, 3)
      if (.not. all(ieee_is_finite(res%sig_ip(:, :, e)))) call stop_at('stress or strain', 'element', elem_label(m, e))
    end do
    do e = 1, size(res%eps_ip, 3)
      if (.not. all(ieee_is_finite(res%eps_ip(:, :, e)))) call stop_at('stress or strain', 'element', elem_label(m, e))
    end do
    do k = 1, size(res%contact%pairs)
      associate(p => res%contact%pairs(k))
        if (.not. (all(ieee_is_finite(p%slave_force)) .and. all(ieee_is_finite(p%master_force)) .and. &
                   all(ieee_is_finite(p%slave_gap)) .and. ieee_is_finite(p%total) .and. &
                   all(ieee_is_finite(p%slave_shear)) .and. all(ieee_is_finite(p%master_shear)) .and. &
                   all(ieee_is_finite(p%slave_slip)) .and. all(ieee_is_finite(p%slave_slip_inc)))) &
          call stop_at('contact force', 'pair', itoa(p%pair))
        ! the pressures the writers print, force over area: a tiny area
        ! (a subnormal thickness) turns a finite force into Infinity
        do a = 1, size(p%master_area)
          if (p%master_area(a) > 0.0_dp) then
            if (.not. (ieee_is_finite(p%master_force(a) / p%master_area(a)) .and. &
                       ieee_is_finite(p%master_shear(a) / p%master_area(a)))) &
              call stop_at('contact pressure', 'pair', itoa(p%pair))
          end if
        end do
        if (allocated(p%slave_pressure)) then
          if (.not. all(ieee_is_finite(p%slave_pressure))) call stop_at('contact pressure', 'pair', itoa(p%pair))
        end if
        if (allocated(p%slave_traction)) then
          if (.not. all(ieee_is_finite(p%slave_traction))) call stop_at('contact pressure', 'pair', itoa(p%pair))
        end if
      end associate
    end do
    if (allocated(res%contact%pressure)) then
      if (.not. (all(ieee_is_finite(res%contact%pressure)) .and. all(ieee_is_finite(res%contact%shear)))) &
        call stop_at('contact pressure', 'model', 'nodes')
    end if
    ! (the progress line's; the pairs' totals above where they were made)
    if (.not. ieee_is_finite(res%contact%total_force)) call stop_at('contact force', 'model', 'pairs')
  contains
    subroutine stop_at(quantity, what, id)
      character(len=*), intent(in) :: quantity, what, id
      call fatal(where // 'the ' // quantity // ' at ' // what // ' ' // id // &
        ' is not a finite number (overflow: loads, stiffness or displacements out of range?); ' // &
        'results of this increment are not written')
    end subroutine stop_at
  end subroutine check_finite
end module increment_results
