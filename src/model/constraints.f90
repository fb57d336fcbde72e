!> Linear multi-point constraints (*EQUATION) resolved for elimination.
!> Each equation sum_k c_k u_k = 0 makes its first term's dof dependent,
!> as CalculiX and Abaqus do: u_d = -sum_{k>1} c_k / c_1 u_k. A term on a
!> dof that is itself dependent in another equation is replaced by that
!> equation's terms (chains), so every dependent dof ends up in terms of
!> independent dofs only: the rows of the transformation u = T u_indep.
!> The checks that make elimination possible (a dof dependent once, a
!> non-zero coefficient of the dependent dof, no cycle, dofs 1..2) are
!> made here; the input layer names the equation's line, the analysis
!> builds its equations from the result.
module constraints
  use kinds, only: dp
  use strings, only: itoa
  use growable, only: grow
  use model, only: model_t, equation_t, node_label
  implicit none
  private
  public :: mpc_t, resolve_equations, constraint_label, rigid_chains

  !> The dependent dofs and, for each, its independent terms:
  !> u(dof(k), node(k)) = sum over j in xt(k):xt(k+1)-1 of
  !> tcoef(j) * u(tdof(j), tnode(j)), no dependent dof among the terms.
  type :: mpc_t
    integer :: ndep = 0
    !> (2, nn) index of a dependent dof, 0 if independent; the index of a
    !> dependent dof is that of the equation that makes it dependent.
    integer, allocatable :: dep(:, :)
    integer, allocatable :: node(:), dof(:)     ! (ndep) the dependent dofs
    integer, allocatable :: xt(:)               ! (ndep + 1)
    integer, allocatable :: tnode(:), tdof(:)
    real(dp), allocatable :: tcoef(:)
    !> (ndep) Rigid followers: a dependent dof made by a *RIGID BODY or
    !> *KINEMATIC coupling whose terms are the reference node's dof
    !> (rref) and the rotation (dof 1 of rrot), both independent, and that
    !> no other constraint names, so that it can follow the exact rotation
    !> u = u_ref + (R(theta) - I) roff of an NLGEOM step; rref 0 for the
    !> other dependent dofs (their constraint stays linear). roff(2, ndep)
    !> is the node's position relative to the reference node.
    integer, allocatable :: rref(:), rrot(:)
    real(dp), allocatable :: roff(:, :)
  end type mpc_t

  !> The equations' own terms (duplicates summed, the dependent dof's
  !> coefficient divided out), before chains are substituted.
  type :: raw_t
    integer, allocatable :: xr(:), rnode(:), rdof(:)
    real(dp), allocatable :: rcoef(:)
  end type raw_t

contains

  !> Purpose: resolves m%equations into mpc (see mpc_t).
  !> Arguments: bad returns 0, or the index of the equation at fault with
  !> msg saying what is wrong (a dof out of 1..2, an undefined node, a
  !> dependent dof whose coefficients sum to zero or that is dependent in
  !> two equations, a cycle of substitutions, coefficients that overflow
  !> when divided by the dependent dof's or multiplied along a chain).
  subroutine resolve_equations(m, mpc, bad, msg)
    type(model_t), intent(in) :: m
    type(mpc_t), intent(out) :: mpc
    integer, intent(out) :: bad
    character(len=:), allocatable, intent(out) :: msg
    type(raw_t) :: raw
    integer :: neqs
    neqs = 0
    if (allocated(m%equations)) neqs = size(m%equations)
    allocate(mpc%dep(2, m%nn), mpc%xt(1))
    mpc%dep = 0
    mpc%xt(1) = 1
    allocate(mpc%node(0), mpc%dof(0), mpc%tnode(0), mpc%tdof(0), mpc%tcoef(0), mpc%rref(0), mpc%rrot(0), &
             mpc%roff(2, 0))
    msg = ''
    bad = 0
    if (neqs == 0) return
    call raw_terms(m, mpc, raw, bad, msg)
    if (bad > 0) return
    call rigid_followers(m, mpc)
    call substitute(m, raw, mpc, bad, msg)
  end subroutine resolve_equations

  !> Marks the rigid followers (mpc_t: rref, rrot, roff): the equations
  !> made by a rigid card (equation_t%rigid_ref, with a rotation node)
  !> that no chain ties to other constraints (rigid_chains).
  subroutine rigid_followers(m, mpc)
    type(model_t), intent(in) :: m
    type(mpc_t), intent(inout) :: mpc
    logical, allocatable :: chained(:)
    integer :: k, a, r
    deallocate(mpc%rref, mpc%rrot, mpc%roff)
    allocate(mpc%rref(mpc%ndep), mpc%rrot(mpc%ndep), mpc%roff(2, mpc%ndep))
    chained = rigid_chains(m%equations, m%nn)
    mpc%rref = 0
    mpc%rrot = 0
    mpc%roff = 0.0_dp
    do k = 1, mpc%ndep
      a = m%equations(k)%rigid_ref
      r = m%equations(k)%rigid_rot
      if (a == 0 .or. r == 0 .or. chained(k)) cycle
      mpc%rref(k) = a
      mpc%rrot(k) = r
      mpc%roff(:, k) = m%x(:, mpc%node(k)) - m%x(:, a)
    end do
  end subroutine rigid_followers

  !> Purpose: the equations of a *RIGID BODY or *KINEMATIC coupling (with
  !> a rotation node) that a chain ties to other constraints, so that
  !> they keep the linear, small-rotation form under NLGEOM: the
  !> reference node's dof or the rotation is the dependent dof (first
  !> term) of another equation (the reference node constrained, or under
  !> a *TRANSFORM), or their own dependent dof is a term of another
  !> equation. Read from the equations as written, before they are
  !> resolved (the input layer warns with it).
  !> Arguments: eqs the equations, nn the number of nodes; chained(k) for
  !> eqs(k) (false for the others). Terms outside nodes 1..nn or dofs
  !> 1..2 are left to resolve_equations to report.
  pure function rigid_chains(eqs, nn) result(chained)
    type(equation_t), intent(in) :: eqs(:)
    integer, intent(in) :: nn
    logical, allocatable :: chained(:)
    integer, allocatable :: dep(:, :)
    integer :: k, j, i, a, r
    allocate(chained(size(eqs)), dep(2, nn))
    dep = 0
    do k = 1, size(eqs)
      if (valid(eqs(k)%node(1), eqs(k)%dof(1))) dep(eqs(k)%dof(1), eqs(k)%node(1)) = k
    end do
    chained = .false.
    do k = 1, size(eqs)
      do j = 2, size(eqs(k)%node)
        if (.not. valid(eqs(k)%node(j), eqs(k)%dof(j))) cycle
        i = dep(eqs(k)%dof(j), eqs(k)%node(j))
        if (i > 0 .and. i /= k) chained(i) = .true.
      end do
    end do
    do k = 1, size(eqs)
      a = eqs(k)%rigid_ref
      r = eqs(k)%rigid_rot
      if (a == 0 .or. r == 0) then
        chained(k) = .false.
      else if (valid(a, eqs(k)%dof(1)) .and. valid(r, 1)) then
        chained(k) = chained(k) .or. dep(eqs(k)%dof(1), a) > 0 .or. dep(1, r) > 0
      end if
    end do
  contains
    pure logical function valid(node, dof)
      integer, intent(in) :: node, dof
      valid = node >= 1 .and. node <= nn .and. dof >= 1 .and. dof <= 2
    end function valid
  end function rigid_chains

  !> Marks every equation's dependent dof and collects its other terms,
  !> duplicates summed, as coefficients of u_d = sum c u.
  subroutine raw_terms(m, mpc, raw, bad, msg)
    type(model_t), intent(in) :: m
    type(mpc_t), intent(inout) :: mpc
    type(raw_t), intent(out) :: raw
    integer, intent(out) :: bad
    character(len=:), allocatable, intent(inout) :: msg
    integer :: i, k, n, a, d, nt
    real(dp) :: c1
    n = size(m%equations)
    allocate(raw%xr(n + 1), raw%rnode(0), raw%rdof(0), raw%rcoef(0))
    mpc%ndep = n
    deallocate(mpc%node, mpc%dof)
    allocate(mpc%node(n), mpc%dof(n))
    raw%xr(1) = 1
    bad = 0
    do i = 1, n
      associate(eq => m%equations(i))
        do k = 1, size(eq%node)
          if (eq%node(k) < 1 .or. eq%node(k) > m%nn) then
            bad = i
            msg = 'undefined node in *EQUATION'
            return
          end if
          if (eq%dof(k) < 1 .or. eq%dof(k) > 2) then
            bad = i
            msg = 'dof ' // itoa(eq%dof(k)) // ' of node ' // node_label(m, eq%node(k)) // &
                  ': a 2D model has dofs 1 and 2 only'
            return
          end if
        end do
        a = eq%node(1)
        d = eq%dof(1)
        if (mpc%dep(d, a) > 0) then
          bad = i
          msg = 'dof ' // itoa(d) // ' of node ' // node_label(m, a) // ' is the dependent dof (the first ' // &
                'term) of two *EQUATIONs: each dof can be eliminated once; put another term first'
          return
        end if
        mpc%dep(d, a) = i
        mpc%node(i) = a
        mpc%dof(i) = d
        c1 = sum(eq%coef, mask=eq%node == a .and. eq%dof == d)
        if (c1 == 0.0_dp) then
          bad = i
          msg = 'the coefficients of the dependent dof (dof ' // itoa(d) // ' of node ' // &
                node_label(m, a) // ', the first term) sum to zero: it cannot be eliminated'
          return
        end if
        nt = raw%xr(i) - 1
        do k = 2, size(eq%node)
          if (eq%node(k) == a .and. eq%dof(k) == d) cycle
          if (.not. abs(eq%coef(k) / c1) <= huge(1.0_dp)) then
            bad = i
            msg = 'a coefficient divided by that of the dependent dof (the first term) overflows: ' // &
                  'give coefficients of comparable size'
            return
          end if
          call add_term(raw%rnode, raw%rdof, raw%rcoef, raw%xr(i), nt, eq%node(k), eq%dof(k), -eq%coef(k) / c1)
        end do
        raw%xr(i + 1) = nt + 1
      end associate
    end do
  end subroutine raw_terms

  !> Adds c to the term on (a, d) among terms first..n, or appends it.
  pure subroutine add_term(tnode, tdof, tcoef, first, n, a, d, c)
    integer, allocatable, intent(inout) :: tnode(:), tdof(:)
    real(dp), allocatable, intent(inout) :: tcoef(:)
    integer, intent(in) :: first, a, d
    integer, intent(inout) :: n
    real(dp), intent(in) :: c
    integer :: j
    do j = first, n
      if (tnode(j) == a .and. tdof(j) == d) then
        tcoef(j) = tcoef(j) + c
        return
      end if
    end do
    n = n + 1
    call grow(tnode, n)
    call grow(tdof, n)
    call grow(tcoef, n)
    tnode(n) = a
    tdof(n) = d
    tcoef(n) = c
  end subroutine add_term

  !> Substitutes chains in dependency order (a dependent dof is resolved
  !> once every dependent dof among its terms is), without recursion; what
  !> is left unresolved lies on a cycle.
  subroutine substitute(m, raw, mpc, bad, msg)
    type(model_t), intent(in) :: m
    type(raw_t), intent(in) :: raw
    type(mpc_t), intent(inout) :: mpc
    integer, intent(out) :: bad
    character(len=:), allocatable, intent(inout) :: msg
    integer, allocatable :: pending(:), xu(:), users(:), queue(:), first(:), last(:), tn(:), td(:)
    real(dp), allocatable :: tc(:)
    integer :: n, k, j, q, head, tail, nt
    n = mpc%ndep
    call dependency_graph(raw, mpc, pending, xu, users)
    allocate(queue(n), first(n), last(n), tn(0), td(0), tc(0))
    tail = 0
    do k = 1, n
      if (pending(k) > 0) cycle
      tail = tail + 1
      queue(tail) = k
    end do
    head = 0
    nt = 0
    do while (head < tail)
      head = head + 1
      k = queue(head)
      first(k) = nt + 1
      call resolve_one(raw, mpc, k, first, last, tn, td, tc, nt)
      last(k) = nt
      if (.not. all(abs(tc(first(k):nt)) <= huge(1.0_dp))) then
        bad = k
        msg = 'the coefficients overflow when the dependent dofs among its terms are replaced by their ' // &
              'own equations (a chain of equations): give coefficients of comparable size'
        return
      end if
      do q = xu(k), xu(k + 1) - 1
        j = users(q)
        pending(j) = pending(j) - 1
        if (pending(j) > 0) cycle
        tail = tail + 1
        queue(tail) = j
      end do
    end do
    bad = 0
    if (tail < n) then
      bad = on_cycle(raw, mpc, pending)
      msg = 'the *EQUATIONs form a cycle: dof ' // itoa(mpc%dof(bad)) // ' of node ' // &
            node_label(m, mpc%node(bad)) // ' depends on itself through the dependent dofs (first terms) ' // &
            'of other equations'
      return
    end if
    call compact(mpc, first, last, tn, td, tc)
  end subroutine substitute

  !> An unresolved dependent dof on a cycle: from the first unresolved one,
  !> follow unresolved dependent terms ndep times.
  pure integer function on_cycle(raw, mpc, pending) result(k)
    type(raw_t), intent(in) :: raw
    type(mpc_t), intent(in) :: mpc
    integer, intent(in) :: pending(:)
    integer :: step, j, i
    k = findloc(pending > 0, .true., dim=1)
    do step = 1, mpc%ndep
      do j = raw%xr(k), raw%xr(k + 1) - 1
        i = mpc%dep(raw%rdof(j), raw%rnode(j))
        if (i == 0) cycle
        if (pending(i) > 0) exit
      end do
      k = i
    end do
  end function on_cycle

  !> For each dependent dof, how many dependent dofs its terms name
  !> (pending), and the reverse lists: the dependents naming it (users).
  pure subroutine dependency_graph(raw, mpc, pending, xu, users)
    type(raw_t), intent(in) :: raw
    type(mpc_t), intent(in) :: mpc
    integer, allocatable, intent(out) :: pending(:), xu(:), users(:)
    integer, allocatable :: pos(:)
    integer :: k, j, i, n
    n = mpc%ndep
    allocate(pending(n), xu(n + 1), pos(n))
    pending = 0
    xu = 0
    do k = 1, n
      do j = raw%xr(k), raw%xr(k + 1) - 1
        i = mpc%dep(raw%rdof(j), raw%rnode(j))
        if (i == 0) cycle
        pending(k) = pending(k) + 1
        xu(i + 1) = xu(i + 1) + 1
      end do
    end do
    xu(1) = 1
    do k = 1, n
      xu(k + 1) = xu(k + 1) + xu(k)
    end do
    allocate(users(xu(n + 1) - 1))
    pos = xu(1:n)
    do k = 1, n
      do j = raw%xr(k), raw%xr(k + 1) - 1
        i = mpc%dep(raw%rdof(j), raw%rnode(j))
        if (i == 0) cycle
        users(pos(i)) = k
        pos(i) = pos(i) + 1
      end do
    end do
  end subroutine dependency_graph

  !> The independent terms of dependent k, appended to tn/td/tc from
  !> position first(k); the dependents among its own terms are resolved
  !> (first:last of each), duplicates summed, zero sums dropped.
  pure subroutine resolve_one(raw, mpc, k, first, last, tn, td, tc, nt)
    type(raw_t), intent(in) :: raw
    type(mpc_t), intent(in) :: mpc
    integer, intent(in) :: k, first(:), last(:)
    integer, allocatable, intent(inout) :: tn(:), td(:)
    real(dp), allocatable, intent(inout) :: tc(:)
    integer, intent(inout) :: nt
    integer :: j, i, q, f0, w, a, d
    real(dp) :: c
    f0 = nt + 1
    do j = raw%xr(k), raw%xr(k + 1) - 1
      i = mpc%dep(raw%rdof(j), raw%rnode(j))
      if (i == 0) then
        call add_term(tn, td, tc, f0, nt, raw%rnode(j), raw%rdof(j), raw%rcoef(j))
      else
        do q = first(i), last(i)
          ! copies: add_term may reallocate tn and td, which an actual
          ! argument tn(q) would still point into
          a = tn(q)
          d = td(q)
          c = raw%rcoef(j) * tc(q)
          call add_term(tn, td, tc, f0, nt, a, d, c)
        end do
      end if
    end do
    w = f0 - 1
    do q = f0, nt
      if (tc(q) == 0.0_dp) cycle
      w = w + 1
      tn(w) = tn(q)
      td(w) = td(q)
      tc(w) = tc(q)
    end do
    nt = w
  end subroutine resolve_one

  !> The resolved terms, stored in dependency order, into mpc in the
  !> order of the dependents.
  pure subroutine compact(mpc, first, last, tn, td, tc)
    type(mpc_t), intent(inout) :: mpc
    integer, intent(in) :: first(:), last(:), tn(:), td(:)
    real(dp), intent(in) :: tc(:)
    integer :: k, n, p
    n = mpc%ndep
    deallocate(mpc%xt, mpc%tnode, mpc%tdof, mpc%tcoef)
    allocate(mpc%xt(n + 1))
    mpc%xt(1) = 1
    do k = 1, n
      mpc%xt(k + 1) = mpc%xt(k) + (last(k) - first(k) + 1)
    end do
    p = mpc%xt(n + 1) - 1
    allocate(mpc%tnode(p), mpc%tdof(p), mpc%tcoef(p))
    do k = 1, n
      mpc%tnode(mpc%xt(k):mpc%xt(k + 1) - 1) = tn(first(k):last(k))
      mpc%tdof(mpc%xt(k):mpc%xt(k + 1) - 1) = td(first(k):last(k))
      mpc%tcoef(mpc%xt(k):mpc%xt(k + 1) - 1) = tc(first(k):last(k))
    end do
  end subroutine compact
  !> Purpose: constraint k named for a message once the deck's lines are
  !> gone: '*EQUATION k', or 'the constraint made by *TIE name' (or by a
  !> pre-tension section) for one a card generated.
  function constraint_label(m, k) result(txt)
    type(model_t), intent(in) :: m
    integer, intent(in) :: k
    character(len=:), allocatable :: txt
    if (len_trim(m%equations(k)%origin) > 0) then
      txt = 'the constraint made by ' // trim(m%equations(k)%origin)
    else
      txt = '*EQUATION ' // itoa(k)
    end if
  end function constraint_label
end module constraints
