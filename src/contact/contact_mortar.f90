!> Segment-to-segment (mortar) integrals of a slave surface against a
!> master surface, with dual shape functions for the weighting.
!>
!> The gap is integrated over the slave faces: for slave node j,
!>   D_j = int Phi_j da,   M_jm = int Phi_j N_m(X_C(s)) da,
!> over the part of the slave surface that faces the master (da: length
!> times thickness, or 2 pi r ds in axisymmetry), N_m the master face's
!> shape functions at the projection X_C of the slave point, Phi_j the
!> dual shape functions of the slave face (Wohlmuth 2000, "A mortar finite
!> element method using dual spaces for the Lagrange multiplier", SIAM J.
!> Numer. Anal. 38, 989-1012; for contact: Hueber & Wohlmuth 2005, CMAME
!> 194, 3147-3166; Popp, Gee & Wall 2009, IJNME 79, 1354-1391): on each
!> face Phi_i = sum_k A_ik N_k with A = diag(d) Me^-1, Me_ik = int N_i N_k da,
!> d_i = int N_i da, so that int Phi_i N_k da = delta_ik d_i
!> (biorthogonality). The weighted gap of node j is then
!>   g_j = n_j . (D_j x_j - sum_m M_jm x_m),
!> in which the slave side is node j alone: each slave node is one
!> coupling element (the paper's CFE) whose master side is the master
!> nodes m with weights M_jm / D_j, whose area is D_j and whose normal
!> force is the nodal multiplier (the pressure) times D_j. Since the Phi
!> sum to one, a uniform pressure p puts p int N_j da on slave node j and
!> p int N_m da on master node m: the consistent forces, whatever the two
!> meshes (the contact patch test).
!>
!> Integration: each slave face is cut where the corners of the master
!> faces project onto it (between two cuts the slave face faces one
!> master face, whose shape functions are smooth there), and each piece
!> gets three Gauss points (exact for the straight faces' products of
!> shape functions and radius). A Gauss point on which no master face
!> lies (beyond the master surface's end, or farther than the search
!> distance) adds nothing: D and M are integrals over the covered part.
!> The normal n_j is the mean of the master faces' normals under node j's
!> support weighted with its standard shape function N_j (on a straight
!> master: its normal; on a curved one: the normal under the node).
module contact_mortar
  use kinds, only: dp
  use growable, only: append
  use small_matrices, only: inv3
  use model, only: model_t, surface_t
  use contact_geometry, only: edge_t, get_edge, edge_at, project_to_edge, edge_weights, area_factor, edge_length, piece_point
  use shape_functions, only: gauss_line
  use edge_tree, only: edge_tree_t, surface_tree, nearest_edge, slab_candidates, edge_tol
  implicit none
  private
  public :: nearest_edge, face_cuts, mortar_dual, mortar_t, mortar_integrals, edge_tol, grow_columns

  !> The initial width of the per-node lists of master nodes and of the
  !> cuts of a face; both grow as a mesh needs (no limit).
  integer, parameter :: initial_width = 16

  !> The integrals of every node of a slave surface (in the order of the
  !> surface's node list).
  type :: mortar_t
    integer :: n = 0
    real(dp), allocatable :: d(:)            ! D_j, over the covered part
    real(dp), allocatable :: full(:)         ! int N_j da over the whole slave surface
    real(dp), allocatable :: nsum(:, :)      ! int N_j n da (the normal, not normalised)
    real(dp), allocatable :: h(:)            ! shortest slave or master node spacing met
    integer, allocatable :: nm(:)            ! master nodes reached
    !> (width, n): node k's master nodes mnode(1:nm(k), k); the width grows
    !> with the longest list (add_master)
    integer, allocatable :: mnode(:, :)
    real(dp), allocatable :: mval(:, :)      ! M_jm
    integer, allocatable :: melem(:), medge(:)   ! a master face under the node (its last point)
    real(dp), allocatable :: mt(:)           ! and the position there
  end type mortar_t

contains

  !> Purpose: positions along a slave face (sorted, from 0 to 1) where the
  !> corners of the master edges project onto it: between two of them the
  !> slave face faces one master edge, whose shape functions are
  !> polynomials there.
  !> Arguments: cuts(1:ncut) returns them (allocated here, as long as the
  !> master mesh needs: a coarse face over a fine master has many); tree,
  !> if present, the tree of ms in x: a straight face looks only at the
  !> master edges in its strip (edge_tree's slab_candidates), in the same
  !> order, so the cuts are the same.
  subroutine face_cuts(m, x, ed, ms, dmax, cuts, ncut, tree)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :), dmax
    type(edge_t), intent(in) :: ed
    type(surface_t), intent(in) :: ms
    real(dp), allocatable, intent(out) :: cuts(:)
    integer, intent(out) :: ncut
    type(edge_tree_t), intent(in), optional :: tree
    real(dp), parameter :: tol = 1.0e-6_dp
    type(edge_t) :: mt
    integer, allocatable :: list(:)
    real(dp) :: t, nvec(2), d, u(2), len
    integer :: i, j, q, a, nlist
    allocate(cuts(initial_width))
    ncut = 2
    cuts(1:2) = [0.0_dp, 1.0_dp]
    len = edge_length(ed)
    nlist = -1
    if (present(tree) .and. ed%nn == 2 .and. len > 0.0_dp .and. len <= huge(1.0_dp)) then
      if (tree%finite .and. tree%n == size(ms%elem)) then
        ! an accepted corner: t = (x_a - x_1) . u / len in (tol, 1 - tol), |d| <= dmax
        u = (ed%x(:, 2) - ed%x(:, 1)) / len
        call slab_candidates(tree, ed%x(:, 1), u, 0.0_dp, len, [u(2), -u(1)], dmax, list, nlist)
      end if
    end if
    if (nlist < 0) then
      list = [(j, j = 1, size(ms%elem))]
      nlist = size(ms%elem)
    end if
    do i = 1, nlist
      j = list(i)
      mt = get_edge(m, x, ms%elem(j), ms%edge(j))
      do q = 1, 2
        a = mt%node(q)
        if (any(ed%node(1:ed%nn) == a)) cycle
        call project_to_edge(ed, x(:, a), t, nvec, d)
        if (t <= tol .or. t >= 1.0_dp - tol .or. abs(d) > dmax) cycle
        if (any(abs(cuts(1:ncut) - t) <= tol)) cycle
        call append(cuts, ncut, t)
      end do
    end do
    call sort_reals(cuts(1:ncut))
  end subroutine face_cuts

  pure subroutine sort_reals(a)
    real(dp), intent(inout) :: a(:)
    integer :: i, j
    real(dp) :: v
    do i = 2, size(a)
      v = a(i)
      j = i - 1
      do while (j >= 1)
        if (a(j) <= v) exit
        a(j + 1) = a(j)
        j = j - 1
      end do
      a(j + 1) = v
    end do
  end subroutine sort_reals

  !> Purpose: the dual shape functions of a slave face (reference
  !> configuration): Phi_i = sum_k a(i, k) N_k with a = diag(d) Me^-1,
  !> Me_ik = int N_i N_k da and d_i = int N_i da (Wohlmuth 2000). The
  !> integrals take the Gauss rule the mortar integrals take on each
  !> piece (three points), so that biorthogonality holds for them too.
  !> A node with d_i = 0 (the axis node of a 3-node axisymmetric face:
  !> int N r ds vanishes there) gets Phi_i = 0.
  pure function mortar_dual(ref) result(a)
    type(edge_t), intent(in) :: ref
    real(dp) :: a(3, 3)
    real(dp) :: me(3, 3), inv(3, 3), d(3), s(3), w(3), n(3), p(2), dpdt(2), t, da, det
    integer :: ig, i, nn
    nn = ref%nn
    call gauss_line(3, s, w)
    me = 0.0_dp
    do ig = 1, 3
      t = 0.5_dp * (s(ig) + 1.0_dp)
      call edge_at(ref, t, p, dpdt)
      n = edge_weights(ref, t)
      da = 0.5_dp * w(ig) * norm2(dpdt) * area_factor(ref, t, p(1))
      do i = 1, nn
        me(i, 1:nn) = me(i, 1:nn) + da * n(i) * n(1:nn)
      end do
    end do
    d = sum(me, dim=2)
    inv = 0.0_dp
    if (nn == 2) then
      det = me(1, 1) * me(2, 2) - me(1, 2) * me(2, 1)
      inv(1:2, 1:2) = reshape([me(2, 2), -me(2, 1), -me(1, 2), me(1, 1)], [2, 2]) / det
    else
      inv = inv3(me)
    end if
    a = 0.0_dp
    do i = 1, nn
      a(i, 1:nn) = d(i) * inv(i, 1:nn)
    end do
  end function mortar_dual

  !> Purpose: the mortar integrals (module comment) of every node of the
  !> slave surface sl against the master surface ms, the projection
  !> searched on configuration x (areas and dual functions on the
  !> reference one). Arguments: dmax the search distance; mo returns them.
  subroutine mortar_integrals(m, x, sl, ms, dmax, mo)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :), dmax
    type(surface_t), intent(in) :: sl, ms
    type(mortar_t), intent(out) :: mo
    type(edge_t) :: ed, ref, mt
    type(edge_tree_t) :: tree
    integer, allocatable :: pos(:)
    real(dp), allocatable :: cuts(:)
    real(dp) :: tg(3), wg(3), a(3, 3), t, nsl(3), phi(3), wmst(3), p(2), pref(2), dpdt(2), &
                mdp(2), nrm(2), tbest, da, hs, hmst
    integer :: f, ncut, iv, ig, best, q, r, k
    mo%n = size(sl%nodes)
    allocate(pos(m%nn), mo%d(mo%n), mo%full(mo%n), mo%nsum(2, mo%n), mo%h(mo%n), mo%nm(mo%n), &
             mo%mnode(initial_width, mo%n), mo%mval(initial_width, mo%n), mo%melem(mo%n), &
             mo%medge(mo%n), mo%mt(mo%n))
    pos = 0
    pos(sl%nodes) = [(k, k = 1, mo%n)]
    mo%d = 0.0_dp
    mo%full = 0.0_dp
    mo%nsum = 0.0_dp
    mo%h = huge(1.0_dp)
    mo%nm = 0
    mo%mnode = 0
    mo%mval = 0.0_dp
    mo%melem = 0
    mo%medge = 0
    mo%mt = 0.0_dp
    call gauss_line(3, tg, wg)
    call surface_tree(m, x, ms, tree)
    do f = 1, size(sl%elem)
      ed = get_edge(m, x, sl%elem(f), sl%edge(f))
      ref = get_edge(m, m%x, sl%elem(f), sl%edge(f))
      a = mortar_dual(ref)
      hs = edge_length(ref) / (ref%nn - 1)
      call face_cuts(m, x, ed, ms, dmax, cuts, ncut, tree)
      do iv = 1, ncut - 1
        do ig = 1, 3
          call piece_point(ref, cuts(iv), cuts(iv + 1), tg(ig), wg(ig), t, pref, da)
          nsl = edge_weights(ref, t)
          do q = 1, ed%nn
            k = pos(ed%node(q))
            mo%full(k) = mo%full(k) + da * nsl(q)
            mo%h(k) = min(mo%h(k), hs)
          end do
          call edge_at(ed, t, p, dpdt)
          call nearest_edge(m, x, ms, p, 0, sl%elem(f), dmax, best, tbest, tree)
          if (best == 0) cycle
          mt = get_edge(m, x, ms%elem(best), ms%edge(best))
          wmst = edge_weights(mt, tbest)
          call edge_at(mt, tbest, p, mdp)
          nrm = [mdp(2), -mdp(1)] / norm2(mdp)
          hmst = edge_length(mt) / (mt%nn - 1)
          phi = matmul(a, nsl)
          do q = 1, ed%nn
            k = pos(ed%node(q))
            mo%d(k) = mo%d(k) + da * phi(q)
            mo%nsum(:, k) = mo%nsum(:, k) + da * nsl(q) * nrm
            mo%h(k) = min(mo%h(k), hmst)
            mo%melem(k) = ms%elem(best)
            mo%medge(k) = ms%edge(best)
            mo%mt(k) = tbest
            do r = 1, mt%nn
              call add_master(mo, k, mt%node(r), da * phi(q) * wmst(r))
            end do
          end do
        end do
      end do
    end do
  end subroutine mortar_integrals

  !> M(k, node) += v in node k's list of master nodes (the lists widen as
  !> needed: grow_columns).
  subroutine add_master(mo, k, node, v)
    type(mortar_t), intent(inout) :: mo
    integer, intent(in) :: k, node
    real(dp), intent(in) :: v
    integer :: i
    do i = 1, mo%nm(k)
      if (mo%mnode(i, k) == node) then
        mo%mval(i, k) = mo%mval(i, k) + v
        return
      end if
    end do
    if (mo%nm(k) == size(mo%mnode, 1)) call grow_columns(mo%mnode, mo%mval)
    mo%nm(k) = mo%nm(k) + 1
    mo%mnode(mo%nm(k), k) = node
    mo%mval(mo%nm(k), k) = v
  end subroutine add_master

  !> Purpose: doubles the length of every column of a per-node list of
  !> (node, value) pairs, keeping the entries (the new ones 0).
  pure subroutine grow_columns(nodes, vals)
    integer, allocatable, intent(inout) :: nodes(:, :)
    real(dp), allocatable, intent(inout) :: vals(:, :)
    integer, allocatable :: wider(:, :)
    real(dp), allocatable :: wider_vals(:, :)
    integer :: w
    w = size(nodes, 1)
    allocate(wider(2 * w, size(nodes, 2)), wider_vals(2 * w, size(nodes, 2)))
    wider = 0
    wider_vals = 0.0_dp
    wider(1:w, :) = nodes
    wider_vals(1:w, :) = vals
    call move_alloc(wider, nodes)
    call move_alloc(wider_vals, vals)
  end subroutine grow_columns
end module contact_mortar
