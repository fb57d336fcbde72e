!> Geometry of element edges for contact: a 2-node (straight) or 3-node
!> (curved, quadratic) edge in a given configuration, points and tangents
!> along it, the orthogonal projection of a point onto it, the consistent
!> areas of its nodes (integral of N_i over the edge, times the thickness
!> interpolated along it, or 2 pi r in axisymmetry), and the natural coordinates in the element
!> of a point of the edge. Positions along an edge are t in [0, 1] from
!> its first corner to its second (counter-clockwise around the element).
module contact_geometry
  use kinds, only: dp
  use model, only: model_t, surface_t, edge_nodes, elem_thickness
  use element_catalogue, only: catalogue, max_nodes, is_triangle, state_axisymmetric, edge_node_count
  use shape_functions, only: line_shape, gauss_line
  implicit none
  private
  public :: edge_t, get_edge, edge_at, project_to_edge, project_to_chord, edge_areas, edge_natural, edge_weights, piece_point, &
            area_factor, edge_length, surface_areas

  real(dp), parameter :: two_pi = 6.283185307179586476925286766559_dp

  type :: edge_t
    integer :: elem = 0, k = 0
    integer :: nn = 2                 ! nodes: 2 straight, 3 with a mid-side node
    integer :: node(3) = 0            ! first corner, second corner, mid-side node
    real(dp) :: x(2, 3) = 0.0_dp      ! their coordinates in the configuration asked for
    logical :: axi = .false.
    real(dp) :: thickness(3) = 1.0_dp ! at its nodes (plane elements)
  end type edge_t

contains

  !> Purpose: edge k of element e with its nodes at x(:, node) (the
  !> reference coordinates, or deformed ones).
  pure function get_edge(m, x, e, k) result(ed)
    type(model_t), intent(in) :: m
    real(dp), intent(in) :: x(:, :)
    integer, intent(in) :: e, k
    type(edge_t) :: ed
    real(dp) :: te(max_nodes)
    integer :: j
    ed%elem = e
    ed%k = k
    ed%nn = edge_node_count(m%etype(e), k)
    call edge_nodes(m, e, k, ed%node(1), ed%node(2), ed%node(3))
    te = elem_thickness(m, e)
    do j = 1, ed%nn
      ed%x(:, j) = x(:, ed%node(j))
      ed%thickness(j) = te(catalogue(m%etype(e))%edge(j, k))
    end do
    ed%axi = catalogue(m%etype(e))%state == state_axisymmetric
  end function get_edge

  !> Purpose: shape-function weights w(1:nn) of the edge's nodes at t.
  pure function edge_weights(ed, t) result(w)
    type(edge_t), intent(in) :: ed
    real(dp), intent(in) :: t
    real(dp) :: w(3), ds(3)
    if (ed%nn == 2) then
      w = [1.0_dp - t, t, 0.0_dp]
    else
      call line_shape(3, 2.0_dp * t - 1.0_dp, w, ds)
    end if
  end function edge_weights

  !> Purpose: point p and tangent dp/dt of the edge at t.
  pure subroutine edge_at(ed, t, p, dpdt)
    type(edge_t), intent(in) :: ed
    real(dp), intent(in) :: t
    real(dp), intent(out) :: p(2), dpdt(2)
    real(dp) :: n(3), ds(3)
    call line_shape(ed%nn, 2.0_dp * t - 1.0_dp, n, ds)
    p = matmul(ed%x(:, 1:ed%nn), n(1:ed%nn))
    dpdt = 2.0_dp * matmul(ed%x(:, 1:ed%nn), ds(1:ed%nn))
  end subroutine edge_at

  !> Chord length between the corners.
  pure real(dp) function edge_length(ed)
    type(edge_t), intent(in) :: ed
    edge_length = norm2(ed%x(:, 2) - ed%x(:, 1))
  end function edge_length

  !> Purpose: orthogonal projection of xs onto the edge: its position t
  !> (not clamped: outside [0, 1] the foot lies beyond the edge's ends),
  !> the outward unit normal there and the signed distance d of xs along
  !> it. A straight edge in closed form; a curved one by Newton's method
  !> on (p(t) - xs) . p'(t) = 0 from the chord's projection.
  pure subroutine project_to_edge(ed, xs, t, nvec, d)
    type(edge_t), intent(in) :: ed
    real(dp), intent(in) :: xs(2)
    real(dp), intent(out) :: t, nvec(2), d
    real(dp) :: ab(2), tvec(2), len, p(2), dp1(2), dp2(2), f, df, dt
    integer :: it
    ab = ed%x(:, 2) - ed%x(:, 1)
    len = norm2(ab)
    tvec = ab / len
    if (ed%nn == 2) then
      call project_to_chord(ed%x(:, 1), tvec, len, xs, t, nvec, d)
      return
    end if
    t = dot_product(xs - ed%x(:, 1), tvec) / len
    ! p'' = 4 (x_a + x_b - 2 x_mid), constant along the quadratic edge
    dp2 = 4.0_dp * (ed%x(:, 1) + ed%x(:, 2) - 2.0_dp * ed%x(:, 3))
    do it = 1, 30
      call edge_at(ed, t, p, dp1)
      f = dot_product(p - xs, dp1)
      df = dot_product(dp1, dp1) + dot_product(p - xs, dp2)
      if (.not. df > 0.0_dp) exit
      dt = -f / df
      t = t + max(-0.5_dp, min(0.5_dp, dt))
      if (abs(dt) < 1.0e-13_dp) exit
    end do
    call edge_at(ed, t, p, dp1)
    nvec = [dp1(2), -dp1(1)] / norm2(dp1)
    d = dot_product(xs - p, nvec)
  end subroutine project_to_edge

  !> Purpose: the projection of xs onto the straight edge from x1 with unit
  !> tangent tvec and length len (project_to_edge's numbers, from the
  !> chord made once: the search's tree keeps it per edge).
  pure subroutine project_to_chord(x1, tvec, len, xs, t, nvec, d)
    real(dp), intent(in) :: x1(2), tvec(2), len, xs(2)
    real(dp), intent(out) :: t, nvec(2), d
    t = dot_product(xs - x1, tvec) / len
    nvec = [tvec(2), -tvec(1)]
    d = dot_product(xs - x1, nvec)
  end subroutine project_to_chord

  !> Purpose: Gauss point xg (weight wg, on [-1, 1]) of the piece [t0, t1]
  !> of edge ref (the reference configuration): its position t on the
  !> edge, the point pref there and the area da it stands for (the piece's
  !> length share times area_factor). The segment-to-segment integrals cut
  !> faces into such pieces.
  pure subroutine piece_point(ref, t0, t1, xg, wg, t, pref, da)
    type(edge_t), intent(in) :: ref
    real(dp), intent(in) :: t0, t1, xg, wg
    real(dp), intent(out) :: t, pref(2), da
    real(dp) :: dpdt(2)
    t = t0 + (t1 - t0) * 0.5_dp * (xg + 1.0_dp)
    call edge_at(ref, t, pref, dpdt)
    da = 0.5_dp * wg * (t1 - t0) * norm2(dpdt) * area_factor(ref, t, pref(1))
  end subroutine piece_point

  !> Purpose: area per unit length at position t of the edge, at radius
  !> r: the thickness there, or 2 pi r in axisymmetry (whole ring).
  pure real(dp) function area_factor(ed, t, r)
    type(edge_t), intent(in) :: ed
    real(dp), intent(in) :: t, r
    real(dp) :: w(3)
    if (ed%axi) then
      area_factor = two_pi * r
    else
      w = edge_weights(ed, t)
      area_factor = dot_product(w(1:ed%nn), ed%thickness(1:ed%nn))
    end if
  end function area_factor

  !> Purpose: consistent areas a(1:nn) of the edge's nodes, the integral of
  !> N_i over the edge's area (length times thickness, or the ring surface
  !> 2 pi r ds). A straight plane edge of one thickness gives half its
  !> area to each corner; three Gauss points are exact for a thickness
  !> quadratic along the edge.
  pure function edge_areas(ed) result(a)
    type(edge_t), intent(in) :: ed
    real(dp) :: a(3), s(3), w(3), n(3), ds(3), p(2), dpdt(2), t
    integer :: ig
    a = 0.0_dp
    if (ed%nn == 2 .and. .not. ed%axi .and. ed%thickness(1) == ed%thickness(2)) then
      a(1:2) = 0.5_dp * edge_length(ed) * ed%thickness(1)
      return
    end if
    call gauss_line(3, s, w)
    do ig = 1, 3
      t = 0.5_dp * (s(ig) + 1.0_dp)
      call edge_at(ed, t, p, dpdt)
      call line_shape(ed%nn, s(ig), n, ds)
      a = a + n * (0.5_dp * w(ig) * norm2(dpdt) * area_factor(ed, t, p(1)))
    end do
  end function edge_areas

  !> Purpose: the consistent areas of the nodes of element surface s on
  !> the reference configuration, sum over its faces of edge_areas
  !> (a(nn): zero at the nodes not on s).
  function surface_areas(m, s) result(a)
    type(model_t), intent(in) :: m
    type(surface_t), intent(in) :: s
    real(dp), allocatable :: a(:)
    real(dp) :: ae(3)
    type(edge_t) :: ed
    integer :: k
    allocate(a(m%nn))
    a = 0.0_dp
    do k = 1, size(s%elem)
      ed = get_edge(m, m%x, s%elem(k), s%edge(k))
      ae = edge_areas(ed)
      a(ed%node(1:ed%nn)) = a(ed%node(1:ed%nn)) + ae(1:ed%nn)
    end do
  end function surface_areas

  !> Purpose: natural coordinates of the point at position t along local
  !> edge k of an element of catalogue type et (the edge's parameter is
  !> linear in the element's natural coordinates, for 2- and 3-node edges).
  pure function edge_natural(et, k, t) result(xi)
    integer, intent(in) :: et, k
    real(dp), intent(in) :: t
    real(dp) :: xi(2)
    if (.not. is_triangle(catalogue(et)%shape)) then
      select case (k)
      case (1); xi = [-1.0_dp + 2.0_dp * t, -1.0_dp]
      case (2); xi = [1.0_dp, -1.0_dp + 2.0_dp * t]
      case (3); xi = [1.0_dp - 2.0_dp * t, 1.0_dp]
      case default; xi = [-1.0_dp, 1.0_dp - 2.0_dp * t]
      end select
    else
      select case (k)
      case (1); xi = [t, 0.0_dp]
      case (2); xi = [1.0_dp - t, t]
      case default; xi = [0.0_dp, 1.0_dp - t]
      end select
    end if
  end function edge_natural
end module contact_geometry
