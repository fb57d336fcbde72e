"""Distributed loads (*DLOAD, *DSLOAD, *DENSITY) on every element type:
uniform pressure patch tests (exact uniform stress on distorted, curved
meshes; the axisymmetric reaction is the ring total p pi (r2^2 - r1^2)),
quadratic patch tests (a quadratic displacement field with the constant
body force that balances it is reproduced exactly by the quadratic
elements), gravity, amplitudes and steps, and the errors of bad cards."""
import math

import numpy as np

from helpers import run_deck
from quadmesh import Mesh, etype

E, NU, P = 1000.0, 0.25, 10.0
SHAPES = ("T3", "Q4", "T6", "Q8")


def wavy(nx, ny, w, h, x0=0.0):
    """Rectangle [x0, x0 + w] x [0, h] with straight outer edges and wavy
    interior lines (curved element edges for the mid-side nodes)."""
    def xy(s, t):
        ss, tt = math.sin(math.pi * s / nx), math.sin(math.pi * t / ny)
        return (x0 + w * s / nx + 0.12 * w / nx * math.sin(2 * math.pi * s / nx) * tt,
                h * t / ny + 0.15 * h / ny * ss * math.sin(2 * math.pi * t / ny))
    return xy


def block_deck(m, et, loads, bcs, extra_model="", step_extra="", thickness=1.0, steps=None):
    deck = f"""*NODE, NSET=ALL
{m.node_lines()}{m.element_card(et, 'BLOCK')}*NSET, NSET=BOT
{", ".join(map(str, m.side('bottom')))}
*NSET, NSET=PIN
{m.side('bottom')[0]}
{m.surface_card('TOP', 'top')}*MATERIAL, NAME=M
*ELASTIC
{E}, {NU}
{extra_model}*SOLID SECTION, ELSET=BLOCK, MATERIAL=M
{thickness}
*BOUNDARY
{bcs}"""
    if steps is not None:
        return deck + steps
    return deck + f"""*STEP
*STATIC
{loads}*NODE PRINT
U, S
*NODE PRINT, NSET=BOT
RF
{step_extra}*END STEP
"""


def check_uniform(run, exact_u, s_exact, what):
    inc = run.listing.increments[-1]
    ub, sb = inc.block("NODE U"), inc.block("NODE S")
    uscale = max(abs(np.array(ub["U2"])).max(), 1e-30)
    for n, u1, u2 in zip(ub["node"], ub["U1"], ub["U2"]):
        ue = exact_u(int(n))
        assert abs(u1 - ue[0]) < 1e-10 * uscale and abs(u2 - ue[1]) < 1e-10 * uscale, (what, n, u1, u2, ue)
    for col, se in zip(("S11", "S22", "S33", "S12"), s_exact):
        err = max(abs(np.array(sb[col]) - se)) / P
        assert err < 1e-10, f"{what}: {col} error {err:.2e}"
    return inc


def test_pressure_patch_plane():
    """P on the top face (*DSLOAD and *DLOAD P3/P2): sigma_yy = -p
    exactly on wavy meshes of every element, the reaction p w t."""
    for shape in SHAPES:
        for state in ("S", "E"):
            m = Mesh(shape, 3, 2, wavy(3, 2, 2.0, 1.0))
            for card in ("dsload", "dload"):
                if card == "dsload":
                    loads = f"*DSLOAD\nTOP, P, {P}\n"
                else:
                    loads = "*DLOAD\n" + "".join(f"{e}, P{k}, {P}\n" for e, k in m.faces("top"))
                run = run_deck(f"dload_patch_{shape}_{state}_{card}",
                               block_deck(m, etype(shape, state), loads, "BOT, 2, 2\nPIN, 1, 1\n", thickness=0.5)).ok()
                nu = NU if state == "S" else NU / (1 - NU)
                e = E if state == "S" else E / (1 - NU ** 2)
                x0 = m.nodes[m.side("bottom")[0]]
                exact = lambda n: (nu * P / e * (m.nodes[n][0] - x0[0]), -P / e * m.nodes[n][1])  # noqa: E731
                s33 = 0.0 if state == "S" else -NU * P
                inc = check_uniform(run, exact, (0.0, -P, s33, 0.0), f"{shape} {state} {card}")
                rf = inc.block("REACTIONS").as_dict()["BOT"]
                assert abs(rf[1] - P * 2.0 * 0.5) < 1e-12 * P, (shape, state, card, rf)


def test_pressure_patch_axisymmetric():
    """A ring r in [1, 3], z in [0, 1] under axial pressure p: sigma_zz =
    -p, u_r = nu p r / E, u_z = -p z / E exactly; the reaction is the
    whole ring's p pi (r2^2 - r1^2) (CalculiX and Abaqus count axisymmetric
    forces over the full circumference), the section thickness unused."""
    for shape in SHAPES:
        m = Mesh(shape, 3, 2, wavy(3, 2, 2.0, 1.0, x0=1.0))
        run = run_deck(f"dload_patch_{shape}_ax", block_deck(m, etype(shape, "AX"), f"*DSLOAD\nTOP, P, {P}\n",
                                                             "BOT, 2, 2\n", thickness=7.0)).ok()
        exact = lambda n: (NU * P / E * m.nodes[n][0], -P / E * m.nodes[n][1])  # noqa: E731
        inc = check_uniform(run, exact, (0.0, -P, 0.0, 0.0), f"{shape} AX")
        rf = inc.block("REACTIONS").as_dict()["BOT"]
        assert abs(rf[1] - P * math.pi * (3.0 ** 2 - 1.0 ** 2)) < 1e-11 * P, (shape, rf)


def parallelograms(nx, ny, w, h, x0=0.0):
    """Corners x = X(s) + S(t), y = Y(t) + T(s): every element a different
    parallelogram (an affine image of the square)."""
    def xy(s, t):
        return (x0 + w * s / nx + 0.07 * w * math.sin(1.7 * s) + 0.09 * w * math.sin(2.3 * t),
                h * t / ny + 0.08 * h * math.sin(1.3 * t) + 0.06 * h * math.sin(2.9 * s))
    return xy


def distorted(nx, ny, w, h, x0=0.0):
    def xy(s, t):
        d = 0.0 if s in (0, nx) or t in (0, ny) else 1.0
        return (x0 + w * s / nx + d * 0.25 * w / nx * math.sin(3.1 * s + 1.7 * t),
                h * t / ny + d * 0.25 * h / ny * math.cos(2.3 * s - 1.1 * t))
    return xy


A = (1e-3, 2e-3, -4e-4, 3e-4, -2e-4, 5e-4)   # u quadratic coefficients (1, x, y, x^2, xy, y^2)
B = (5e-4, 3e-3, -1e-3, -2e-4, 4e-4, 1e-4)


def lame(state):
    mu = E / (2 * (1 + NU))
    lam = E * NU / ((1 + NU) * (1 - 2 * NU))
    if state == "S":
        lam = 2 * mu * lam / (lam + 2 * mu)
    return lam, mu


def quad_field(state, x, y):
    """Displacement, stresses (S11, S22, S33, S12) and the body force that
    balances them, for the quadratic test fields (plane: A, B; axi:
    u_r = a r + alpha r^2 + kappa r z, u_z = d0 + d z + beta z^2 + gamma r^2)."""
    lam, mu = lame(state)
    if state == "AX":
        a, al, ka, d0, d, be, ga = 1e-3, 4e-4, -3e-4, 2e-4, -1e-3, 5e-4, 3e-4
        u = (a * x + al * x * x + ka * x * y, d0 + d * y + be * y * y + ga * x * x)
        err_, ezz, ett, grz = a + 2 * al * x + ka * y, d + 2 * be * y, a + al * x + ka * y, ka * x + 2 * ga * x
        tr = err_ + ezz + ett
        s = (lam * tr + 2 * mu * err_, lam * tr + 2 * mu * ezz, lam * tr + 2 * mu * ett, mu * grz)
        b = (-3 * (lam + 2 * mu) * al, -(2 * mu * (ka + 2 * ga) + 2 * lam * (ka + be) + 4 * mu * be))
        return u, s, b
    u = (A[0] + A[1] * x + A[2] * y + A[3] * x * x + A[4] * x * y + A[5] * y * y,
         B[0] + B[1] * x + B[2] * y + B[3] * x * x + B[4] * x * y + B[5] * y * y)
    e11 = A[1] + 2 * A[3] * x + A[4] * y
    e22 = B[2] + B[4] * x + 2 * B[5] * y
    g12 = A[2] + B[1] + (A[4] + 2 * B[3]) * x + (2 * A[5] + B[4]) * y
    s11, s22, s12 = lam * (e11 + e22) + 2 * mu * e11, lam * (e11 + e22) + 2 * mu * e22, mu * g12
    s33 = 0.0 if state == "S" else NU * (s11 + s22)
    d11, d12 = lam + 2 * mu, lam
    b = (-(d11 * 2 * A[3] + d12 * B[4] + mu * (2 * A[5] + B[4])),
         -(mu * (A[4] + 2 * B[3]) + d12 * A[4] + d11 * 2 * B[5]))
    return u, (s11, s22, s33, s12), b


def quadratic_patch(shape, state, mapping):
    m = Mesh(shape, 4, 3, mapping, straight=True)
    u0, _, b = quad_field(state, 0.0, 0.0)
    bcs = ""
    for n in m.boundary():
        u, _, _ = quad_field(state, *m.nodes[n])
        bcs += f"{n}, 1, 1, {u[0]:.17g}\n{n}, 2, 2, {u[1]:.17g}\n"
    bx, by = ("BR", "BZ") if state == "AX" else ("BX", "BY")
    loads = f"*DLOAD\nBLOCK, {bx}, {b[0]:.17g}\nBLOCK, {by}, {b[1]:.17g}\n"
    run = run_deck(f"quadratic_patch_{shape}_{state}", block_deck(m, etype(shape, state), loads, bcs,
                                                                  thickness=0.3)).ok()
    inc = run.listing.increments[-1]
    ub, sb = inc.block("NODE U"), inc.block("NODE S")
    uerr = serr = 0.0
    smax = max(max(abs(v) for v in quad_field(state, *p)[1]) for p in m.nodes.values())
    for k, n in enumerate(ub["node"]):
        u, s, _ = quad_field(state, *m.nodes[int(n)])
        uerr = max(uerr, abs(ub["U1"][k] - u[0]) / 1e-3, abs(ub["U2"][k] - u[1]) / 1e-3)
        for col, se in zip(("S11", "S22", "S33", "S12"), s):
            serr = max(serr, abs(sb[col][k] - se) / smax)
    return uerr, serr


def test_quadratic_patch():
    """A complete quadratic displacement field, its body force applied with
    *DLOAD BX/BY (BR/BZ), the boundary held at the field: every
    displacement and nodal stress exact to 1e-10 for the 8-node
    quadrilateral on parallelograms (serendipity elements are quadratic-
    complete only on affine shapes) and the 6-node triangle on a distorted
    mesh, in plane stress, plane strain and axisymmetry."""
    for state in ("S", "E", "AX"):
        x0 = 0.5 if state == "AX" else 0.0
        for shape, mapping in (("Q8", parallelograms(4, 3, 2.0, 1.5, x0)), ("T6", distorted(4, 3, 2.0, 1.5, x0))):
            uerr, serr = quadratic_patch(shape, state, mapping)
            assert uerr < 1e-10 and serr < 1e-10, f"{shape} {state}: displacement {uerr:.2e}, stress {serr:.2e}"


def test_linear_elements_are_not_quadratic_exact():
    """The same quadratic patch on 4-node quadrilaterals is not exact: the
    quadratic test can fail."""
    uerr, serr = quadratic_patch("Q4", "S", parallelograms(4, 3, 2.0, 1.5))
    assert uerr > 1e-4 or serr > 1e-3, (uerr, serr)


def test_gravity_column():
    """A column of height 2 under its own weight (GRAV with *DENSITY): the
    base reaction is rho g A, sigma_yy = -rho g (H - y) is linear and the
    8-node and 6-node elements give it exactly at every node."""
    rho, g, w, h = 2.5, 9.0, 1.0, 2.0
    # rectangles of unequal sizes (affine) for Q8, distorted straight-sided
    # triangles for T6: elements on which quadratic fields are exact
    rects = lambda s, t: (w * (s / 2) ** 1.3, h * (t / 4) ** 1.2)  # noqa: E731
    for shape in ("Q8", "T6", "Q4"):
        m = Mesh(shape, 2, 4, distorted(2, 4, w, h) if shape == "T6" else rects, straight=True)
        # the base held at the exact field u = (nu rho g (h - y) x, nu rho g x^2 / 2) / E
        c = NU * rho * g / E
        # (BOT first, so that its reactions are summed; the node lines then set the values)
        bcs = "BOT, 1, 2\n" + "".join(f"{n}, 1, 1, {c * h * m.nodes[n][0]:.17g}\n{n}, 2, 2, "
                                      f"{c * m.nodes[n][0] ** 2 / 2:.17g}\n" for n in m.side("bottom"))
        run = run_deck(f"gravity_{shape}", block_deck(m, etype(shape, "S"), f"*DLOAD\nBLOCK, GRAV, {g}, 0., -1., 0.\n",
                                                      bcs, extra_model=f"*DENSITY\n{rho}\n", thickness=0.4)).ok()
        inc = run.listing.increments[-1]
        rf = inc.block("REACTIONS").as_dict()["BOT"]
        assert abs(rf[1] - rho * g * w * h * 0.4) < 1e-11 * rho * g * w * h, (shape, rf)
        if shape != "Q4":
            sb = inc.block("NODE S")
            err = max(abs(s22 + rho * g * (h - m.nodes[int(n)][1])) for n, s22 in zip(sb["node"], sb["S22"]))
            assert err < 1e-10 * rho * g * h, (shape, err)


def test_amplitudes_and_steps():
    """One face pressure through four steps: an amplitude (0 -> 1 -> 0.5
    over step 1), held in step 2, redefined without an amplitude in step 3
    (ramping from the held value to the new one), removed by OP=NEW in
    step 4 while a *CLOAD of step 3 stays. The base reaction follows
    p(t) * width at every increment."""
    m = Mesh("Q8", 2, 1, wavy(2, 1, 2.0, 1.0))
    top = m.side("top")
    steps = f"""*AMPLITUDE, NAME=A1
0., 0., 1., 1., 2., 0.5
*STEP
*STATIC
0.5, 2.
*DLOAD, AMPLITUDE=A1
{"".join(f"{e}, P{k}, {P}" + chr(10) for e, k in m.faces("top"))}*END STEP
*STEP
*STATIC
0.5, 1.
*END STEP
*STEP
*STATIC
0.25, 1.
*DSLOAD
TOP, P, 30.
*CLOAD
{top[0]}, 2, -3.
*END STEP
*STEP
*STATIC
0.5, 1.
*DLOAD, OP=NEW
*END STEP
"""
    run = run_deck("dload_steps", block_deck(m, "CPS8", "", "BOT, 2, 2\nPIN, 1, 1\n", steps=steps)).ok()
    expect = {(1, 1): 5.0, (1, 2): 10.0, (1, 3): 7.5, (1, 4): 5.0, (2, 1): 5.0, (2, 2): 5.0,
              (3, 1): 11.25, (3, 2): 17.5, (3, 3): 23.75, (3, 4): 30.0, (4, 1): 0.0, (4, 2): 0.0}
    got = {}
    for inc in run.listing.increments:
        got[inc.step, inc.number] = inc.block("REACTIONS").as_dict()["BOT"][1]
    assert sorted(got) == sorted(expect), sorted(got)
    for key, p in expect.items():
        # the *CLOAD of step 3 ramps to 3 over step 3 and stays
        cload = {3: 3.0 * key[1] / 4, 4: 3.0}.get(key[0], 0.0)
        assert abs(got[key] - (p * 2.0 + cload)) < 1e-10 * 60, (key, got[key], p * 2.0 + cload)


BAD = [
    ("face", "*DLOAD\nBLOCK, P5, 1.\n", "face 5 does not exist"),
    ("label", "*DLOAD\nBLOCK, TRSHR, 1.\n", "load label TRSHR is not implemented"),
    ("density", "*DLOAD\nBLOCK, GRAV, 9.81, 0., -1., 0.\n", "needs the density of material M"),
    ("bz", "*DLOAD\nBLOCK, BZ, 1.\n", "BZ acts out of the plane"),
    # (a tilted axis; one in the plane is accepted: tests/test_calculix_leniency.py)
    ("centrif axis", "*DLOAD\nBLOCK, CENTRIF, 100., 0., 0., 0., 0., 1., 1.\n", "must be normal to the x-y plane"),
    ("gravity z", "*DLOAD\nBLOCK, GRAV, 9.81, 0., 0., 1.\n", "gravity out of the x-y plane"),
    ("node surface", "*DSLOAD\nNS, P, 1.\n", "is a node surface"),
    ("surface", "*DSLOAD\nNOSUCH, P, 1.\n", "undefined surface NOSUCH"),
    ("amplitude", "*DLOAD, AMPLITUDE=NONE\nBLOCK, P1, 1.\n", "undefined amplitude NONE"),
    ("outside step", None, "must be inside *STEP"),
]


def test_bad_dload_cards():
    """Each bad card stops the run with file:line naming it."""
    m = Mesh("Q4", 2, 1, wavy(2, 1, 2.0, 1.0))
    for name, card, msg in BAD:
        base = block_deck(m, "CPS4", "", "BOT, 2, 2\nPIN, 1, 1\n",
                          extra_model="*SURFACE, NAME=NS, TYPE=NODE\nPIN\n")
        if card is None:
            deck = base.replace("*STEP", "*DLOAD\nBLOCK, P1, 1.\n*STEP", 1)
        else:
            deck = base.replace("*NODE PRINT\n", card + "*NODE PRINT\n", 1)
        run = run_deck("bad_dload_" + name.replace(" ", "_"), deck)
        assert run.rc != 0 and msg in run.stderr and ".inp:" in run.stderr, (name, run.stderr)


def test_invalid_quadratic_and_axisymmetric_elements():
    """A mid-side node pushed past the middle of the element (the corners
    are fine, the Jacobian is negative inside) and an axisymmetric element
    reaching x < 0 stop the run naming the element."""
    m = Mesh("Q8", 1, 1, lambda s, t: (s, t), straight=True)
    mid = m.elements[0][4]                     # node 5, on face 1
    m.nodes[mid] = (0.5, 1.6)
    run = run_deck("bad_midside", block_deck(m, "CPS8", "", "BOT, 2, 2\n"))
    assert run.rc != 0 and "element 1 (CPS8) has a zero or negative Jacobian" in run.stderr, run.stderr
    m = Mesh("Q4", 1, 1, lambda s, t: (s - 0.5, t))
    run = run_deck("bad_axi_x", block_deck(m, "CAX4", "", "BOT, 2, 2\n"))
    assert run.rc != 0 and "element 1 (CAX4) has a zero or negative Jacobian" in run.stderr, run.stderr
