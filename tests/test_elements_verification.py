"""Closed-form verification of the new elements: the Lame thick-walled
cylinder under internal pressure (axisymmetric and plane strain), the
rotating hollow disk (plane stress, CENTRIF) and the rotating long hollow
cylinder (axisymmetric, CENTRIF), and a cantilever against the exact
elasticity solution where the 8-node quadrilateral converges faster than
the 4-node one."""
import math

import numpy as np

from helpers import run_deck
from quadmesh import Mesh, etype

E, NU = 1000.0, 0.3
RA, RB = 1.0, 2.0


def graded(nx, a, b, grade):
    """Radius of parameter s: corners graded towards a by `grade`, a
    mid-side node half-way between its corners."""
    def r(s):
        if s != int(s):
            return 0.5 * (r(math.floor(s)) + r(math.ceil(s)))
        return a + (b - a) * (s / nx) ** grade
    return r


def polar(nx, ny, a, b, angle=math.pi / 2, grade=1.0):
    """Quarter annulus a <= r <= b, 0 <= theta <= angle, nodes on circles
    (the mid-side nodes too: curved element edges)."""
    rad = graded(nx, a, b, grade)

    def xy(s, t):
        th = angle * t / ny
        return rad(s) * math.cos(th), rad(s) * math.sin(th)
    return xy


def ring(nx, ny, a, b, h, grade=1.0):
    rad = graded(nx, a, b, grade)
    return lambda s, t: (rad(s), h * t / ny)


def model(m, et, loads, bcs, material_extra="", requests="*NODE PRINT\nU, S\n"):
    return f"""*NODE, NSET=ALL
{m.node_lines()}{m.element_card(et, 'BODY')}*NSET, NSET=LEFT
{", ".join(map(str, m.side('left')))}
*NSET, NSET=BOTTOM
{", ".join(map(str, m.side('bottom')))}
*NSET, NSET=TOP
{", ".join(map(str, m.side('top')))}
{m.surface_card('INNER', 'left')}*MATERIAL, NAME=M
*ELASTIC
{E}, {NU}
{material_extra}*SOLID SECTION, ELSET=BODY, MATERIAL=M
1.
*BOUNDARY
{bcs}*STEP
*STATIC
{loads}{requests}*END STEP
"""


def lame(p, r):
    """Plane-strain (long cylinder) Lame solution: u_r, sigma_r, sigma_theta."""
    a2, b2 = RA ** 2, RB ** 2
    A, B = p * a2 / (b2 - a2), p * a2 * b2 / (b2 - a2)
    return (1 + NU) / E * ((1 - 2 * NU) * A * r + B / r), A - B / r ** 2, A + B / r ** 2


def radial_results(run, m, cartesian):
    """u_r, sigma_theta at every node (from S33 in axisymmetry, from the
    rotated plane stresses otherwise) and the node radii."""
    inc = run.listing.increments[-1]
    ub, sb = inc.block("NODE U"), inc.block("NODE S")
    r, ur, st = [], [], []
    for k, n in enumerate(ub["node"]):
        x, y = m.nodes[int(n)]
        if cartesian:
            rr = math.hypot(x, y)
            c, s = x / rr, y / rr
            ur.append(ub["U1"][k] * c + ub["U2"][k] * s)
            st.append(sb["S11"][k] * s * s - 2 * sb["S12"][k] * s * c + sb["S22"][k] * c * c)
        else:
            rr = x
            ur.append(ub["U1"][k])
            st.append(sb["S33"][k])
        r.append(rr)
    return np.array(r), np.array(ur), np.array(st)


def check_radial(r, ur, st, exact, what, tol=1e-3, stol=None):
    ue = np.array([exact(x)[0] for x in r])
    se = np.array([exact(x)[2] for x in r])
    err_u = np.max(np.abs(ur - ue)) / np.max(np.abs(ue))
    inner = np.abs(r - RA) < 1e-9
    err_s = np.max(np.abs(st[inner] - se[inner])) / np.max(np.abs(se))
    print(f"  {what}: u_r error {err_u:.2e}, hoop stress at r = a error {err_s:.2e}")
    stol = tol if stol is None else stol
    assert err_u < tol and err_s < stol, f"{what}: u_r error {err_u:.2e}, hoop stress error {err_s:.2e}"


def test_lame_cylinder_axisymmetric():
    """CAX8 and CAX6, 8 elements through the wall (graded towards the
    bore), ends held axially (plane strain): u_r at every node and the
    hoop stress S33 at the bore (extrapolated to the nodes) within 0.1 %
    of Lame."""
    p = 100.0
    for shape in ("Q8", "T6"):
        m = Mesh(shape, 8, 1, ring(8, 1, RA, RB, 0.3, grade=2.0))
        run = run_deck(f"lame_ax_{shape}", model(m, etype(shape, "AX"), f"*DSLOAD\nINNER, P, {p}\n",
                                                 "BOTTOM, 2, 2\nTOP, 2, 2\n")).ok()
        check_radial(*radial_results(run, m, False), lambda x: lame(p, x), f"Lame {etype(shape, 'AX')}")


def test_lame_cylinder_plane_strain():
    """CPE8 on a quarter annulus with curved edges, 8 x 8 elements graded
    towards the bore, symmetry planes held, the pressure on the curved bore
    (*DSLOAD): u_r and the bore's hoop stress within 0.1 % of Lame. CPE6 on
    the same nodes: u_r within 0.1 %, the hoop stress within 2 % (its three
    points give a linear stress, extrapolated to the bore)."""
    p = 100.0
    for shape, stol in (("Q8", 1e-3), ("T6", 2e-2)):
        m = Mesh(shape, 8, 8, polar(8, 8, RA, RB, grade=2.0))
        run = run_deck(f"lame_pe_{shape}", model(m, etype(shape, "E"), f"*DSLOAD\nINNER, P, {p}\n",
                                                 "BOTTOM, 2, 2\nTOP, 1, 1\n")).ok()
        check_radial(*radial_results(run, m, True), lambda x: lame(p, x), f"Lame {etype(shape, 'E')}", stol=stol)


def rotating(r, rho, w2, plane_strain):
    """Rotating hollow disk (plane stress) or long cylinder (plane strain),
    free at r = a and r = b: u_r, sigma_r, sigma_theta."""
    nu, e = NU, E
    if plane_strain:
        nu, e = NU / (1 - NU), E / (1 - NU ** 2)
    k = (3 + nu) / 8 * rho * w2
    a2, b2 = RA ** 2, RB ** 2
    sr = k * (a2 + b2 - a2 * b2 / r ** 2 - r ** 2)
    st = k * (a2 + b2 + a2 * b2 / r ** 2 - (1 + 3 * nu) / (3 + nu) * r ** 2)
    return r / e * (st - nu * sr), sr, st


def test_rotating_disk_plane_stress():
    """CPS8 quarter of a hollow disk, 8 x 6 elements graded towards the
    bore, spinning about the z axis (CENTRIF about (0, 0, 1) through the
    origin, *DENSITY): u_r and the bore's hoop stress within 0.1 % of the
    closed form."""
    rho, w2 = 2.0, 50.0
    m = Mesh("Q8", 8, 6, polar(8, 6, RA, RB, grade=2.0))
    run = run_deck("rotating_disk", model(m, "CPS8", f"*DLOAD\nBODY, CENTRIF, {w2}, 0., 0., 0., 0., 0., 1.\n",
                                          "BOTTOM, 2, 2\nTOP, 1, 1\n", material_extra=f"*DENSITY\n{rho}\n")).ok()
    check_radial(*radial_results(run, m, True), lambda x: rotating(x, rho, w2, False), "rotating disk CPS8")


def test_rotating_cylinder_axisymmetric():
    """CAX8 spinning about its axis (CENTRIF about the y axis), 8 elements
    graded towards the bore, ends held axially: the plane-strain closed
    form within 0.1 %; CAX4 with the same nodes within 1 %."""
    rho, w2 = 2.0, 50.0
    for shape, tol in (("Q8", 1e-3), ("Q4", 1e-2)):
        nx = 8 if shape == "Q8" else 16
        m = Mesh(shape, nx, 1, ring(nx, 1, RA, RB, 0.2, grade=2.0))
        run = run_deck(f"rotating_ax_{shape}", model(
            m, etype(shape, "AX"), f"*DLOAD\nBODY, CENTRIF, {w2}, 0., 0., 0., 0., 1., 0.\n",
            "BOTTOM, 2, 2\nTOP, 2, 2\n", material_extra=f"*DENSITY\n{rho}\n")).ok()
        check_radial(*radial_results(run, m, False), lambda x: rotating(x, rho, w2, True),
                     f"rotating cylinder {etype(shape, 'AX')}", tol)


# cantilever: exact plane-stress solution (Timoshenko and Goodier), the end
# x = 0 loaded by a parabolic shear P, the end x = L held at the exact field
CL, CC, CP = 10.0, 0.5, 1.0


def cantilever_exact(x, y):
    i, g = 2 * CC ** 3 / 3, E / (2 * (1 + NU))
    u = (-CP * x * x * y / (2 * E * i) - NU * CP * y ** 3 / (6 * E * i) + CP * y ** 3 / (6 * g * i)
         + (CP * CL ** 2 / (2 * E * i) - CP * CC ** 2 / (2 * g * i)) * y)
    v = NU * CP * x * y * y / (2 * E * i) + CP * x ** 3 / (6 * E * i) - CP * CL ** 2 * x / (2 * E * i) \
        + CP * CL ** 3 / (3 * E * i)
    return u, v


def cantilever_tip(shape, nx, ny):
    m = Mesh(shape, nx, ny, lambda s, t: (CL * s / nx, -CC + 2 * CC * t / ny))
    i = 2 * CC ** 3 / 3
    # consistent nodal forces of the shear P/(2I) (c^2 - y^2) on x = 0 (3-point Gauss per edge)
    f = {}
    g = (-math.sqrt(0.6), 0.0, math.sqrt(0.6))
    w = (5 / 9, 8 / 9, 5 / 9)
    for e, k in m.faces("left"):
        conn = m.elements[e - 1]
        npf = 3 if len(conn) == 8 else 2
        a, b = conn[[0, 1, 2, 3][k - 1]], conn[[1, 2, 3, 0][k - 1]]
        ids = (a, b, conn[4 + k - 1]) if npf == 3 else (a, b)
        ya, yb = m.nodes[a][1], m.nodes[b][1]
        for s, ws in zip(g, w):
            y = 0.5 * (ya + yb) + 0.5 * (yb - ya) * s
            n = (0.5 * s * (s - 1), 0.5 * s * (s + 1), 1 - s * s) if npf == 3 else (0.5 * (1 - s), 0.5 * (1 + s))
            tau = CP / (2 * i) * (CC ** 2 - y * y)
            for node, nv in zip(ids, n):
                f[node] = f.get(node, 0.0) + nv * tau * ws * 0.5 * abs(yb - ya)
    bcs = ""
    for n in m.side("right"):
        u, v = cantilever_exact(*m.nodes[n])
        bcs += f"{n}, 1, 1, {u:.17g}\n{n}, 2, 2, {v:.17g}\n"
    tip = min(m.side("left"), key=lambda n: abs(m.nodes[n][1]))
    loads = "*CLOAD\n" + "".join(f"{n}, 2, {v:.17g}\n" for n, v in f.items())
    deck = model(m, etype(shape, "S"), loads, bcs, requests=f"*NODE PRINT, NSET=TIP\nU\n")
    deck = deck.replace("*MATERIAL", f"*NSET, NSET=TIP\n{tip}\n*MATERIAL", 1)
    run = run_deck(f"cantilever_exact_{shape}_{nx}", deck).ok()
    v = run.listing.increments[-1].block("NODE U", set="TIP")["U2"][0]
    return v, 2 * len(m.nodes)


def test_cantilever_q8_converges_faster_than_q4():
    """Tip deflection against the exact PL^3/(3EI) on meshes of 10x1 to
    80x8 elements: Q4's observed order is about 2, Q8's about 4, and Q8 is
    the more accurate on every mesh (also per degree of freedom)."""
    exact = cantilever_exact(0.0, 0.0)[1]
    errs = {}
    for shape in ("Q4", "Q8"):
        errs[shape] = []
        for k in (1, 2, 4, 8):
            v, ndof = cantilever_tip(shape, 10 * k, k)
            errs[shape].append((abs(v - exact) / exact, ndof))
    orders = {s: [math.log2(a[0] / b[0]) for a, b in zip(e, e[1:])] for s, e in errs.items()}
    for s in errs:
        print(f"  cantilever {s}: errors " + ", ".join(f"{e:.2e} ({n} dofs)" for e, n in errs[s]) +
              "; observed orders " + ", ".join(f"{o:.2f}" for o in orders[s]))
    assert orders["Q4"][-1] > 1.9, orders
    assert orders["Q8"][-1] > 3.5 and min(orders["Q8"]) > orders["Q4"][-1] + 1.0, orders
    for (e4, n4), (e8, n8) in zip(errs["Q4"], errs["Q8"]):
        assert e8 < e4, (e4, e8)
    # Q8 on the 10x1 mesh beats Q4 on the 80x8 mesh, with far fewer unknowns
    assert errs["Q8"][0][0] < errs["Q4"][-1][0] and errs["Q8"][0][1] < errs["Q4"][-1][1]
