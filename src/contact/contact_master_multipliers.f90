!> Segment-to-segment (mortar) contact with the Lagrange multiplier on
!> the master mesh, for a slave surface finer than its master (straight,
!> 2-node faces on both sides): the contact pressure is the continuous
!> piecewise-linear field lambda_h = sum_m lambda_m psi_m over the master
!> surface (psi_m the master nodes' hat functions, carried onto the slave
!> surface by the projection X_C(s)), and the non-penetration condition is
!> tested with the same psi_m, integrated over the slave segments:
!>   G_m = n_m . (sum_j S_mj x_j - D_m x_m) = 0,
!>   S_mj = int psi_m(X_C(s)) N_j(s) da,   D_m = int psi_m(X_C(s)) da,
!> over the part of the slave surface that faces the master (da: length
!> times thickness, or 2 pi r ds in axisymmetry; N_j the slave faces'
!> shape functions). The master-side matrix of the standard mortar method,
!> int psi_m N_k da, is taken with the nodal (trapezoidal) rule of the
!> master mesh, that is row-sum lumped to D_m delta_mk: the master node
!> itself stands against the psi_m-weighted mean of the slave surface.
!> One coupling element (the paper's CFE, eqs. (3)-(10)) per master node
!> m: its slave side the slave nodes j with the weights S_mj / D_m (they
!> sum to one), its master side node m with weight one, its area D_m, its
!> normal force lambda_m D_m. Slave node j then receives int lambda_h N_j
!> da, a continuous traction, and master node m lambda_m D_m; the pressure
!> at a slave node is the field lambda_h at its projection. Since the
!> psi_m sum to one on the covered part, a uniform pressure p puts p int
!> N_j da on slave node j and p int N_m da on master node m: the
!> consistent forces on both sides; and any configuration in which both
!> surfaces lie on one straight line has G_m = 0 (the weighted mean of
!> points of a line lies on it): the contact patch test is passed exactly.
!> On a curved interface the psi_m-weighted mean lies off the surface by
!> about kappa <s^2> / 2 (kappa its curvature, <s^2> about h_m^2 / 6): a
!> shift of the gap that varies smoothly along the surface, of the order
!> of the chord error any piecewise-linear master has. The tangential
!> component is not consistent: the psi_m-weighted mean of the slave
!> surface lies off node m along the surface by (h_r - h_l) / 3 (h_l,
!> h_r the master faces at m; h / 3 at an end of the master surface), so
!> a sticking CFE would be anchored off its node and a uniform shear not
!> passed. A frictional pair therefore takes the consistent master side
!> M_mk = int psi_m N_k da (the standard mortar method's; its CFE's master
!> side the master nodes k with M_mk / D_m): the psi_m-weighted means of
!> both surfaces then coincide wherever the surfaces do, in both
!> directions (contact's couple_master_space).
!>
!> Why (docs/contact.md, "Which multiplier space"): with the multiplier
!> on the slave mesh (contact_mortar's dual mortar) every slave node is
!> held on the master's polygon; where the slave is the finer side, its
!> nodes between two master corners are forced onto the master's chords,
!> and the slave body answers the chords' sagitta with a pressure wave of
!> the master's period (1.8 % of p0 on the coarse Hertz mesh). A
!> multiplier no richer than the coarser side is the mortar method's
!> choice of the multiplier ("non-mortar") side: McDevitt & Laursen 2000,
!> "A mortar-finite element formulation for frictional contact problems",
!> IJNME 48, 1525-1547 (multipliers on the non-mortar side's nodes, the
!> weighted gaps integrated over segments); Akula, Vignollet & Yastrebov
!> 2019, "MorteX method for contact along real and embedded surfaces:
!> coupling X-FEM with the mortar method", CMAME 354, 1113-1147 (the
!> mortar method's interface oscillations at a mesh-density contrast,
!> removed by interpolating the multipliers on a coarser set of nodes).
!> The lumped master-side matrix is what makes the multipliers local: with
!> the consistent one (int psi_m N_k da, tridiagonal) lambda is the L2
!> projection of the master's nodal forces, which rings near the edge of
!> contact (measured: 0.80 % instead of 0.20 % on the coarse Hertz mesh,
!> still below the dual mortar's 1.82 %; with friction 0.81 % against
!> 1.97 %);
!> lumped, lambda_m is master node m's force over D_m, as the dual basis
!> of Wohlmuth 2000 (SIAM J. Numer. Anal. 38, 989-1012) makes the slave
!> side's matrix diagonal. The dual basis itself is not taken on the
!> master side: its discontinuous functions would put a sawtooth traction
!> sum_m lambda_m Phi_m on the finer slave body.
!>
!> 3-node (quadratic) master faces, taken where the master surface is
!> straight and the slave the finer (master_space_wanted; CalculiX's
!> plate and ring1 decks, one slave face on one master face, were 5e-2
!> and 1.1e-3 off its references with them against 9e-5 and 2e-5 with
!> the dual mortar): psi_m the hat functions of the master
!> CORNERS (1 - t, t on each face, none at the mid-side nodes: N_q + N_3
!> / 2 of the face's shape functions), the master side consistent, M_mk
!> = int psi_m N_k da over the master's 3-node N_k (a lumped one would
!> leave the mid-side nodes unheld), and the integrals taken over the
!> MASTER faces: each cut where the slave corners project onto it, three
!> Gauss points per piece, each point's slave functions N_j at its
!> closest point on the slave surface, da the master's. G_m is then the
!> psi_m-weighted mean of the pointwise gap along the master surface.
!> Measured on the flagship's CPS8 mesh (docs/contact.md, "Quadratic
!> faces"): the master's quadratic N_m as psi_m, lumped, oscillate
!> between corner and mid-side rows (osc 1.03 %, s-m 2.6 %); the corner
!> hats integrated over the slave faces meet the oscillation target
!> (0.26 %) but not s-m (2.7 %: the master rows alternate by +-3 % with
!> the slave/master node offset, as the slave's reference measure per
!> master length varies within its quadratic faces); over the master
!> faces 0.19 %, +0.11 %, 0.47 %. On a curved master the single normal
!> of a coupling element over a hat two faces wide costs about
!> (h / R)^2 / 12 of the normal force (measured 1e-3 on the quarter
!> shrink fit of 14 faces, whose total force the dual mortar gets to
!> 2e-5): there the dual mortar stays.
module contact_master_multipliers
  use kinds, only: dp
  use model, only: model_t, surface_t
  use contact_geometry, only: edge_t, get_edge, edge_at, piece_point, project_to_edge, edge_weights, area_factor, edge_length, &
                              edge_areas
  use contact_mortar, only: nearest_edge, face_cuts, grow_columns
  use edge_tree, only: edge_tree_t, surface_tree
  use shape_functions, only: gauss_line
  implicit none
  private
  public :: master_space_t, master_space_integrals, master_space_wanted, coarse_straight_slave

  !> The initial width of the per-node lists of slave and master nodes;
  !> they grow as the meshes need (no limit).
  integer, parameter :: initial_width = 16
  !> The master-mesh multipliers are taken where the slave faces are
  !> less than this share of the master faces under them (the mean over
  !> the slave faces, master_space_wanted): the slave clearly the finer
  !> side (docs/contact.md, "Which multiplier space").
  real(dp), parameter :: finer_ratio = 0.75_dp
  !> The position t along a face of its nodes (first corner, second
  !> corner, mid-side node: contact_geometry's order).
  real(dp), parameter :: node_position(3) = [0.0_dp, 1.0_dp, 0.5_dp]
  !> 3-node master faces take the master-mesh multipliers only where the
  !> master surface is straight: its tangents within this angle (radians)
  !> of each other (master_space_wanted).
  real(dp), parameter :: max_turn = 1.0e-3_dp

  !> The integrals of every node of a master surface (in the order of the
  !> surface's node list).
  type :: master_space_t
    integer :: n = 0
    real(dp), allocatable :: d(:)               ! D_m, over the covered part
    real(dp), allocatable :: full(:)            ! int N_m da over the master surface
    real(dp), allocatable :: nsum(:, :)         ! int psi_m n da (the normal, not normalised)
    real(dp), allocatable :: h(:)               ! shortest master face length at the node
    integer, allocatable :: ns(:)               ! slave nodes reached
    !> (width, n): master node k's slave nodes snode(1:ns(k), k); the width
    !> grows with the longest list (add_entry)
    integer, allocatable :: snode(:, :)
    real(dp), allocatable :: sval(:, :)         ! S_mj
    !> The consistent master side M_mk = int psi_m N_k da (master nodes
    !> mnode(1:nm(m), m)), which a frictional pair takes (module comment).
    integer, allocatable :: nm(:), mnode(:, :)
    real(dp), allocatable :: mval(:, :)
    !> psi_m at the slave nodes snode(:, m) (at their projections on the
    !> master surface): the pressure field there is sum_m psi_m lambda_m.
    real(dp), allocatable :: psi(:, :)
    integer, allocatable :: melem(:), medge(:)  ! a master face at the node
    real(dp), allocatable :: mt(:)              ! and the node's position on it (0 or 1)
    !> 3-node master faces: the multiplier is linear between the master
    !> corners, integrated over the master faces (module comment).
    logical :: quadratic = .false.
  end type master_space_t

contains

  !> Purpose: does pair (sl, ms) take the master-mesh multipliers? Both
  !> surfaces of straight (2-node) faces, or a straight master surface of
  !> 3-node faces (straight_surface; module comment), and the slave the
  !> finer: the
  !> mean over the slave faces of (slave face length / length of the
  !> master face under its midpoint) below finer_ratio. Each face counts
  !> once, so that a finely meshed contact zone decides, not the long
  !> faces far from it where both sides are coarse (the Hertz meshes: 0.57
  !> per face, 0.79 weighted with the lengths). Reference configuration;
  !> slave faces whose midpoint faces no master face (within dmax) do not
  !> count.
  logical function master_space_wanted(m, sl, ms, dmax)
    type(model_t), intent(in) :: m
    type(surface_t), intent(in) :: sl, ms
    real(dp), intent(in) :: dmax
    real(dp) :: num, den
    integer :: f
    logical :: quadratic
    master_space_wanted = .false.
    quadratic = size(ms%elem) > 0 .and. all([(get_edge_nn(m, ms, f), f = 1, size(ms%elem))] == 3)
    if (quadratic) then
      if (.not. straight_surface(m, ms)) return
    else
      do f = 1, size(ms%elem)
        if (get_edge_nn(m, ms, f) /= 2) return
      end do
      do f = 1, size(sl%elem)
        if (get_edge_nn(m, sl, f) /= 2) return
      end do
    end if
    call face_ratio_sums(m, sl, ms, dmax, num, den)
    master_space_wanted = den > 0.0_dp .and. num < finer_ratio * den
  end function master_space_wanted

  !> Purpose: the sums of master_space_wanted's statistic: num the sum
  !> over the slave faces whose midpoint faces a master face (within dmax,
  !> reference configuration) of (slave face length / that master face's
  !> length), den their number.
  subroutine face_ratio_sums(m, sl, ms, dmax, num, den)
    type(model_t), intent(in) :: m
    type(surface_t), intent(in) :: sl, ms
    real(dp), intent(in) :: dmax
    real(dp), intent(out) :: num, den
    type(edge_t) :: ed, mt
    type(edge_tree_t) :: tree
    real(dp) :: p(2), dpdt(2), tbest
    integer :: f, best
    num = 0.0_dp
    den = 0.0_dp
    call surface_tree(m, m%x, ms, tree)
    do f = 1, size(sl%elem)
      ed = get_edge(m, m%x, sl%elem(f), sl%edge(f))
      call edge_at(ed, 0.5_dp, p, dpdt)
      call nearest_edge(m, m%x, ms, p, 0, sl%elem(f), dmax, best, tbest, tree)
      if (best == 0) cycle
      mt = get_edge(m, m%x, ms%elem(best), ms%edge(best))
      num = num + edge_length(ed) / edge_length(mt)
      den = den + 1.0_dp
    end do
  end subroutine face_ratio_sums

  !> Purpose: is the slave the coarser side of a pair that would be more
  !> accurate swapped? The slave faces coarser than the master faces under
  !> them (master_space_wanted's mean ratio above 1 / finer_ratio, the
  !> rule that takes the master-mesh multipliers for a finer slave, turned
  !> round) and the slave surface straight: swapped, the finer surface is
  !> the slave and the multiplier lies on this straight surface as the
  !> master mesh. Measured on the Hertz cylinder with a flat 5 times
  !> coarser than the cylinder (docs/contact.md, "Any pair of meshes"): at
  !> the peak the flat as the slave (dual mortar) gives p0 +1.86 % and the
  !> slave-master difference 11.8 % of p0, swapped +0.55 % and 0.42 %;
  !> a coarse curved slave on a fine flat master is not (swapped, the
  !> multiplier would lie on the curved master: p0 +2.84 % against
  !> +0.54 %). Arguments: ratio returns the mean ratio (0: no slave face
  !> faces the master).
  logical function coarse_straight_slave(m, sl, ms, dmax, ratio)
    type(model_t), intent(in) :: m
    type(surface_t), intent(in) :: sl, ms
    real(dp), intent(in) :: dmax
    real(dp), intent(out) :: ratio
    real(dp) :: num, den
    call face_ratio_sums(m, sl, ms, dmax, num, den)
    ratio = 0.0_dp
    if (den > 0.0_dp) ratio = num / den
    coarse_straight_slave = ratio * finer_ratio > 1.0_dp
    if (coarse_straight_slave) coarse_straight_slave = straight_surface(m, sl)
  end function coarse_straight_slave

  !> Purpose: the multipliers' functions psi of the nodes of master face
  !> mt at t: its shape functions on a 2-node face, the corners' hat
  !> functions (linear between the corners, zero at the mid-side node) on
  !> a 3-node face (module comment).
  pure function psi_weights(mt, t) result(w)
    type(edge_t), intent(in) :: mt
    real(dp), intent(in) :: t
    real(dp) :: w(3)
    if (mt%nn == 3) then
      w = [1.0_dp - t, t, 0.0_dp]
    else
      w = edge_weights(mt, t)
    end if
  end function psi_weights

  !> Purpose: is surface s straight? The tangents of its faces at their
  !> ends and middles (reference configuration) within max_turn of the
  !> first face's.
  logical function straight_surface(m, s)
    type(model_t), intent(in) :: m
    type(surface_t), intent(in) :: s
    type(edge_t) :: ed
    real(dp) :: p(2), dpdt(2), t0(2), tt(2)
    integer :: f, i
    straight_surface = .false.
    if (size(s%elem) == 0) return
    ed = get_edge(m, m%x, s%elem(1), s%edge(1))
    call edge_at(ed, 0.0_dp, p, dpdt)
    t0 = dpdt / norm2(dpdt)
    do f = 1, size(s%elem)
      ed = get_edge(m, m%x, s%elem(f), s%edge(f))
      do i = 0, 2
        call edge_at(ed, 0.5_dp * i, p, dpdt)
        tt = dpdt / norm2(dpdt)
        if (abs(t0(1) * tt(2) - t0(2) * tt(1)) > sin(max_turn) .or. dot_product(t0, tt) <= 0.0_dp) return
      end do
    end do
    straight_surface = .true.
  end function straight_surface

  !> Purpose: the node count of face f of surface s (2 or 3).
  integer function get_edge_nn(m, s, f)
    type(model_t), intent(in) :: m
    type(surface_t), intent(in) :: s
    integer, intent(in) :: f
    type(edge_t) :: ed
    ed = get_edge(m, m%x, s%elem(f), s%edge(f))
    get_edge_nn = ed%nn
  end function get_edge_nn

  !> Purpose: the integrals of the module comment for every node of the
  !> master surface ms against the slave surface sl (2-node faces; for
  !> 3-node master faces see below and the module comment), the
  !> projection searched on configuration x (areas on the reference one):
  !> each slave face is cut where the master corners project onto it (psi_m
  !> and N_j are then linear on each piece), three Gauss points per piece
  !> (exact for the product of two linear functions and the radius). A
  !> slave Gauss point on which no master face lies adds nothing. The
  !> field psi_m at a slave node is taken at the closest point of the
  !> master surface (closest_master_point). 3-node master faces: each
  !> master face is cut where the slave corners project onto it, three
  !> Gauss points per piece (the corner hats, the master's N_k and the
  !> slave's N_j at the point's closest slave point), da the master's; a
  !> master Gauss point that faces no slave face adds nothing. Every list
  !> grows as the meshes need: a master node's hat may reach any number of
  !> slave nodes.
  !> Arguments: dmax the search distance; sp returns them.
  subroutine master_space_integrals(m, x, sl, ms, dmax, sp)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :), dmax
    type(surface_t), intent(in) :: sl, ms
    type(master_space_t), intent(out) :: sp
    integer, allocatable :: pos(:)
    integer :: f, k
    sp%n = size(ms%nodes)
    allocate(pos(m%nn), sp%d(sp%n), sp%full(sp%n), sp%nsum(2, sp%n), sp%h(sp%n), sp%ns(sp%n), &
             sp%snode(initial_width, sp%n), sp%sval(initial_width, sp%n), &
             sp%nm(sp%n), sp%mnode(initial_width, sp%n), sp%mval(initial_width, sp%n), &
             sp%melem(sp%n), sp%medge(sp%n), sp%mt(sp%n))
    pos = 0
    pos(ms%nodes) = [(k, k = 1, sp%n)]
    sp%quadratic = size(ms%elem) > 0 .and. all([(get_edge_nn(m, ms, f), f = 1, size(ms%elem))] == 3)
    sp%d = 0.0_dp
    sp%nsum = 0.0_dp
    sp%ns = 0
    sp%snode = 0
    sp%sval = 0.0_dp
    sp%nm = 0
    sp%mnode = 0
    sp%mval = 0.0_dp
    call master_node_extents(m, ms, pos, sp)
    if (sp%quadratic) then
      call integrate_on_master_faces(m, x, sl, ms, dmax, pos, sp)
    else
      call integrate_on_slave_faces(m, x, sl, ms, dmax, pos, sp)
    end if
    call psi_at_slave_nodes(m, x, ms, dmax, sp)
  end subroutine master_space_integrals

  !> Purpose: each master node's whole int psi_m da (sp%full), its
  !> shortest face (sp%h), and a face at it with the node's position there
  !> (sp%melem, medge, mt). Arguments: pos the node's place in ms%nodes.
  subroutine master_node_extents(m, ms, pos, sp)
    type(model_t), intent(in) :: m
    type(surface_t), intent(in) :: ms
    integer, intent(in) :: pos(:)
    type(master_space_t), intent(inout) :: sp
    type(edge_t) :: ref
    real(dp) :: a(3)
    integer :: f, q, k
    sp%full = 0.0_dp
    sp%h = huge(1.0_dp)
    sp%melem = 0
    sp%medge = 0
    sp%mt = 0.0_dp
    do f = 1, size(ms%elem)
      ref = get_edge(m, m%x, ms%elem(f), ms%edge(f))
      a = edge_areas(ref)
      do q = 1, ref%nn
        k = pos(ref%node(q))
        ! int psi_m da: on a 3-node face the corner's hat 1 - t (or t) is
        ! N_q + N_3 / 2, the mid-side node carries no multiplier
        if (ref%nn == 3) then
          if (q < 3) sp%full(k) = sp%full(k) + a(q) + 0.5_dp * a(3)
        else
          sp%full(k) = sp%full(k) + a(q)
        end if
        sp%h(k) = min(sp%h(k), edge_length(ref))
        sp%melem(k) = ms%elem(f)
        sp%medge(k) = ms%edge(f)
        sp%mt(k) = node_position(q)
      end do
    end do
  end subroutine master_node_extents

  !> Purpose: the integrals on 3-node master faces, taken over the master
  !> faces, each cut where the slave corners project onto it (module
  !> comment). Arguments: pos the master node's place in ms%nodes.
  subroutine integrate_on_master_faces(m, x, sl, ms, dmax, pos, sp)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :), dmax
    type(surface_t), intent(in) :: sl, ms
    integer, intent(in) :: pos(:)
    type(master_space_t), intent(inout) :: sp
    type(edge_t) :: ed, ref, mt
    real(dp), allocatable :: cuts(:)
    real(dp) :: tg(3), wg(3), t, nsl(3), wmst(3), psiw(3), p(2), pref(2), mdp(2), nrm(2), tbest, da
    integer :: f, ncut, iv, ig, best
    type(edge_tree_t) :: tree
    call gauss_line(3, tg, wg)
    call surface_tree(m, x, sl, tree)
    do f = 1, size(ms%elem)
      mt = get_edge(m, x, ms%elem(f), ms%edge(f))
      ref = get_edge(m, m%x, ms%elem(f), ms%edge(f))
      call face_cuts(m, x, mt, sl, dmax, cuts, ncut, tree)
      do iv = 1, ncut - 1
        do ig = 1, 3
          call piece_point(ref, cuts(iv), cuts(iv + 1), tg(ig), wg(ig), t, pref, da)
          wmst = edge_weights(mt, t)
          psiw = psi_weights(mt, t)
          call edge_at(mt, t, p, mdp)
          nrm = [mdp(2), -mdp(1)] / norm2(mdp)
          call nearest_edge(m, x, sl, p, 0, ms%elem(f), dmax, best, tbest, tree)
          if (best == 0) cycle
          ed = get_edge(m, x, sl%elem(best), sl%edge(best))
          nsl = edge_weights(ed, tbest)
          call add_point(sp, pos, mt%node(1:mt%nn), psiw(1:mt%nn), nrm, da, ed%node(1:ed%nn), nsl(1:ed%nn), &
                         wmst(1:mt%nn))
        end do
      end do
    end do
  end subroutine integrate_on_master_faces

  !> Purpose: the integrals on 2-node faces, taken over the slave faces,
  !> each cut where the master corners project onto it (module comment).
  !> Arguments: pos the master node's place in ms%nodes.
  subroutine integrate_on_slave_faces(m, x, sl, ms, dmax, pos, sp)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :), dmax
    type(surface_t), intent(in) :: sl, ms
    integer, intent(in) :: pos(:)
    type(master_space_t), intent(inout) :: sp
    type(edge_t) :: ed, ref, mt
    real(dp), allocatable :: cuts(:)
    real(dp) :: tg(3), wg(3), t, nsl(3), wmst(3), p(2), pref(2), dpdt(2), mdp(2), nrm(2), tbest, da
    integer :: f, ncut, iv, ig, best
    type(edge_tree_t) :: tree
    call gauss_line(3, tg, wg)
    call surface_tree(m, x, ms, tree)
    do f = 1, size(sl%elem)
      ed = get_edge(m, x, sl%elem(f), sl%edge(f))
      ref = get_edge(m, m%x, sl%elem(f), sl%edge(f))
      call face_cuts(m, x, ed, ms, dmax, cuts, ncut, tree)
      do iv = 1, ncut - 1
        do ig = 1, 3
          call piece_point(ref, cuts(iv), cuts(iv + 1), tg(ig), wg(ig), t, pref, da)
          nsl = edge_weights(ref, t)
          call edge_at(ed, t, p, dpdt)
          call nearest_edge(m, x, ms, p, 0, sl%elem(f), dmax, best, tbest, tree)
          if (best == 0) cycle
          mt = get_edge(m, x, ms%elem(best), ms%edge(best))
          wmst = edge_weights(mt, tbest)
          call edge_at(mt, tbest, p, mdp)
          nrm = [mdp(2), -mdp(1)] / norm2(mdp)
          call add_point(sp, pos, mt%node(1:2), wmst(1:2), nrm, da, ed%node(1:2), nsl(1:2), wmst(1:2))
        end do
      end do
    end do
  end subroutine integrate_on_slave_faces

  !> Purpose: one integration point's share of the master-space integrals
  !> (both integration orders): for each master node k of the face with
  !> weight w(r) (its hat or psi function at the point), D_k, the summed
  !> normal, and the entries of S_kj (the slave nodes' shape functions nsl)
  !> and of M_kl (the master nodes' shape functions mw), times da.
  subroutine add_point(sp, pos, mnodes, w, nrm, da, snodes, nsl, mw)
    type(master_space_t), intent(inout) :: sp
    integer, intent(in) :: pos(:), mnodes(:), snodes(:)
    real(dp), intent(in) :: w(:), nrm(2), da, nsl(:), mw(:)
    integer :: r, q, k
    do r = 1, size(mnodes)
      k = pos(mnodes(r))
      sp%d(k) = sp%d(k) + da * w(r)
      sp%nsum(:, k) = sp%nsum(:, k) + da * w(r) * nrm
      do q = 1, size(snodes)
        call add_entry(sp%ns, sp%snode, sp%sval, k, snodes(q), da * w(r) * nsl(q))
      end do
      do q = 1, size(mnodes)
        call add_entry(sp%nm, sp%mnode, sp%mval, k, mnodes(q), da * w(r) * mw(q))
      end do
    end do
  end subroutine add_point

  !> Purpose: psi_m at the slave nodes of each master node's list (sp%psi,
  !> as wide as sp%snode): the master face under each slave node, at its
  !> closest point (closest_master_point).
  subroutine psi_at_slave_nodes(m, x, ms, dmax, sp)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :), dmax
    type(surface_t), intent(in) :: ms
    type(master_space_t), intent(inout) :: sp
    type(edge_t) :: mt
    real(dp) :: wmst(3), tbest
    integer :: k, j, r, best
    allocate(sp%psi(size(sp%snode, 1), sp%n))
    sp%psi = 0.0_dp
    do k = 1, sp%n
      do j = 1, sp%ns(k)
        call closest_master_point(m, x, ms, x(:, sp%snode(j, k)), sp%snode(j, k), dmax, best, tbest)
        if (best == 0) cycle
        mt = get_edge(m, x, ms%elem(best), ms%edge(best))
        wmst = psi_weights(mt, tbest)
        do r = 1, mt%nn
          if (mt%node(r) == ms%nodes(k)) sp%psi(j, k) = wmst(r)
        end do
      end do
    end do
  end subroutine psi_at_slave_nodes

  !> Purpose: the point of the master surface closest to point xs: the
  !> master edge (index into ms) and the position on it, the orthogonal
  !> projection clamped to the edge; 0 if none within the search distance
  !> dmax, or behind an edge by more than half its length (the far side
  !> of the master body), as nearest_edge. Unlike nearest_edge's
  !> projection this finds a point for every xs near the surface: behind
  !> a corner of a concave master polygon (a slave node pressed into it)
  !> no edge's projection falls inside [0, 1], and the closest point is
  !> the corner. Arguments: skip_node a slave node whose edges are not
  !> searched.
  subroutine closest_master_point(m, x, ms, xs, skip_node, dmax, best, tbest)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :), xs(2), dmax
    type(surface_t), intent(in) :: ms
    integer, intent(in) :: skip_node
    integer, intent(out) :: best
    real(dp), intent(out) :: tbest
    type(edge_t) :: ed
    real(dp) :: t, nvec(2), d, p(2), dpdt(2), dist, dbest
    integer :: j
    best = 0
    tbest = 0.0_dp
    dbest = huge(1.0_dp)
    do j = 1, size(ms%elem)
      ed = get_edge(m, x, ms%elem(j), ms%edge(j))
      if (any(ed%node(1:ed%nn) == skip_node)) cycle
      call project_to_edge(ed, xs, t, nvec, d)
      if (d < -0.5_dp * edge_length(ed) .or. d > dmax) cycle
      t = min(max(t, 0.0_dp), 1.0_dp)
      call edge_at(ed, t, p, dpdt)
      dist = norm2(xs - p)
      if (dist > dmax) cycle
      if (dist < dbest) then
        dbest = dist
        best = j
        tbest = t
      end if
    end do
  end subroutine closest_master_point

  !> Purpose: vals(node, k) += v in column k's list of n(k) (node, value)
  !> pairs; the columns widen when the list is full (grow_columns).
  subroutine add_entry(n, nodes, vals, k, node, v)
    integer, intent(inout) :: n(:)
    integer, allocatable, intent(inout) :: nodes(:, :)
    real(dp), allocatable, intent(inout) :: vals(:, :)
    integer, intent(in) :: k, node
    real(dp), intent(in) :: v
    integer :: i
    do i = 1, n(k)
      if (nodes(i, k) == node) then
        vals(i, k) = vals(i, k) + v
        return
      end if
    end do
    if (n(k) == size(nodes, 1)) call grow_columns(nodes, vals)
    n(k) = n(k) + 1
    nodes(n(k), k) = node
    vals(n(k), k) = v
  end subroutine add_entry
end module contact_master_multipliers
