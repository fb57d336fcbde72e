"""Thermal strain (*EXPANSION, *INITIAL CONDITIONS, TYPE=TEMPERATURE,
*TEMPERATURE) on every element shape and stress state, against closed
forms: free expansion (u = alpha dT x, no stress; plane strain: the
out-of-plane constraint gives u = (1 + nu) alpha dT x and S33 =
-E alpha dT), a block held at both ends (S11 = -E alpha dT in plane
stress, -E alpha dT / (1 - nu) in plane strain), the ramp over a step,
the hold into the next step, OP=NEW and an amplitude; a plane-strain
shrink fit in contact against the Lame solution; bad cards."""
import math

import numpy as np

from helpers import run_deck
from quadmesh import Mesh, etype
from test_dload import wavy

E, NU, ALPHA, T0, T1 = 1000.0, 0.25, 1.0e-5, 20.0, 120.0
SHAPES = ("T3", "Q4", "T6", "Q8")


def deck(m, et, bcs, steps, material_extra=f"*EXPANSION, ZERO=20.\n{ALPHA}\n", initial=True):
    init = f"*INITIAL CONDITIONS, TYPE=TEMPERATURE\nALL, {T0}\n" if initial else ""
    return f"""*NODE, NSET=ALL
{m.node_lines()}{m.element_card(et, 'BLOCK')}*NSET, NSET=BOT
{", ".join(map(str, m.side('bottom')))}
*NSET, NSET=LEFT
{", ".join(map(str, m.side('left')))}
*NSET, NSET=RIGHT
{", ".join(map(str, m.side('right')))}
*NSET, NSET=PIN
{m.side('bottom')[0]}
*MATERIAL, NAME=M
*ELASTIC
{E}, {NU}
{material_extra}*SOLID SECTION, ELSET=BLOCK, MATERIAL=M
0.5
{init}*BOUNDARY
{bcs}{steps}"""


def step(temp, inc="1., 1.", card="*TEMPERATURE"):
    return f"""*STEP
*STATIC
{inc}
{card}
{temp}*NODE PRINT
U, S
*END STEP
"""


def check(inc, m, exact_u, s_exact, scale_u, what):
    ub, sb = inc.block("NODE U"), inc.block("NODE S")
    for n, u1, u2 in zip(ub["node"], ub["U1"], ub["U2"]):
        ue = exact_u(m.nodes[int(n)])
        assert abs(u1 - ue[0]) < 1e-9 * scale_u and abs(u2 - ue[1]) < 1e-9 * scale_u, (what, n, u1, u2, ue)
    for col, se in zip(("S11", "S22", "S33", "S12"), s_exact):
        err = max(abs(np.array(sb[col]) - se)) / (E * ALPHA * (T1 - T0))
        assert err < 1e-9, f"{what}: {col} error {err:.2e}"


def free_case(shape, state):
    x0 = 1.0 if state == "AX" else 0.0
    m = Mesh(shape, 3, 2, wavy(3, 2, 2.0, 1.0, x0=x0))
    bcs = "BOT, 2, 2\n" + ("" if state == "AX" else "PIN, 1, 1\n")
    return m, x0, bcs


def test_free_expansion():
    """Heated from T0 to T1 with only rigid-body supports: u = alpha dT
    (x - x0, y) (axisymmetric: alpha dT (r, z)), no stress; in plane
    strain u = (1 + nu) alpha dT (x - x0, y) and S33 = -E alpha dT; on
    curved meshes of every element."""
    a = ALPHA * (T1 - T0)
    for shape in SHAPES:
        for state in ("S", "E", "AX"):
            m, x0, bcs = free_case(shape, state)
            run = run_deck(f"thermal_free_{shape}_{state}",
                           deck(m, etype(shape, state), bcs, step(f"ALL, {T1}\n"))).ok()
            inc = run.listing.increments[-1]
            s33 = -E * a if state == "E" else 0.0
            g = a * (1 + NU) if state == "E" else a
            check(inc, m, lambda p: (g * (p[0] - x0 * (state != "AX")), g * p[1]), (0.0, 0.0, s33, 0.0), a * 3.0,
                  f"free {shape} {state}")


def test_held_block():
    """Both ends held in x, the bottom in y, heated by dT: S11 = -E alpha
    dT (plane stress) or -E alpha dT / (1 - nu) (plane strain, where S33
    is the same), S22 = 0, u_y = (1 + nu) alpha dT y (plane stress) or
    (1 + nu) / (1 - nu) alpha dT y (plane strain); the reaction of the
    right wall is S11 times its area."""
    a = ALPHA * (T1 - T0)
    for shape in SHAPES:
        for state in ("S", "E"):
            m = Mesh(shape, 3, 2, wavy(3, 2, 2.0, 1.0))
            run = run_deck(f"thermal_held_{shape}_{state}",
                           deck(m, etype(shape, state), "BOT, 2, 2\nLEFT, 1, 1\nRIGHT, 1, 1\n",
                                step(f"ALL, {T1}\n"))).ok()
            inc = run.listing.increments[-1]
            if state == "S":
                s = (-E * a, 0.0, 0.0, 0.0)
                uy = a * (1 + NU)
            else:
                s = (-E * a / (1 - NU), 0.0, -E * a / (1 - NU), 0.0)
                uy = a * (1 + NU) / (1 - NU)
            check(inc, m, lambda p: (0.0, uy * p[1]), s, a * 3.0, f"held {shape} {state}")
            # the wall's reaction carries the stress: S11 * height * thickness
            rf = inc.block("REACTIONS").as_dict()["RIGHT"]
            assert abs(rf[0] - s[0] * 1.0 * 0.5) < 1e-9 * E * a, (shape, state, rf)


def test_ramp_hold_and_new():
    """Step 1 ramps T0 -> T1 over two increments (half the strain at the
    first), step 2 holds it, step 3 (OP=NEW without data lines) goes back
    to the initial temperature, step 4 follows an amplitude to 0.5 T1 (absolute)."""
    m, x0, bcs = free_case("Q4", "S")
    steps = ("*AMPLITUDE, NAME=HALF\n0., 0., 1., 0.5\n" + step(f"ALL, {T1}\n", inc="0.5, 1.")
             + step("", card="*CLOAD\nPIN, 1, 0.")
             + step("", card="*TEMPERATURE, OP=NEW")
             + step(f"ALL, {T1}\n", card="*TEMPERATURE, AMPLITUDE=HALF"))
    run = run_deck("thermal_steps", deck(m, "CPS4", bcs, steps)).ok()
    a = ALPHA * (T1 - T0)
    expect = {(1, 1): 0.5 * a, (1, 2): a, (2, 1): a, (3, 1): 0.0, (4, 1): ALPHA * (0.5 * T1 - T0)}
    got = {}
    for inc in run.listing.increments:
        ub = inc.block("NODE U")
        top_right = max(m.nodes, key=lambda n: m.nodes[n][0] + m.nodes[n][1])
        k = [int(n) for n in ub["node"]].index(top_right)
        got[inc.step, inc.number] = ub["U1"][k] / (m.nodes[top_right][0] - x0)
    assert sorted(got) == sorted(expect), sorted(got)
    for key, strain in expect.items():
        assert abs(got[key] - strain) < 1e-9 * a, (key, got[key], strain)


def test_no_initial_conditions_starts_at_zero():
    """Without *INITIAL CONDITIONS the reference temperature is 0."""
    m, x0, bcs = free_case("Q8", "S")
    run = run_deck("thermal_zero_ref", deck(m, "CPS8", bcs, step(f"ALL, {T1}\n"), initial=False)).ok()
    a = ALPHA * T1
    check(run.listing.increments[-1], m, lambda p: (a * p[0], a * p[1]), (0.0, 0.0, 0.0, 0.0), a * 3.0, "zero ref")


BAD = [
    ("type", "*EXPANSION, TYPE=ORTHO\n1e-5\n", "only TYPE=ISO"),
    ("table", "*EXPANSION\n1e-5, 20.\n1.2e-5, 100.\n", "temperature-dependent *EXPANSION"),
    ("initial type", "*INITIAL CONDITIONS, TYPE=PLASTIC STRAIN\nALL, 1.\n", "TYPE=PLASTIC STRAIN is not implemented"),
    ("initial set", "*INITIAL CONDITIONS, TYPE=TEMPERATURE\nNOSUCH, 1.\n", "NOSUCH"),
    ("initial fields", "*INITIAL CONDITIONS, TYPE=TEMPERATURE\nALL\n", "node or set, temperature"),
    ("initial empty", "*INITIAL CONDITIONS, TYPE=TEMPERATURE\n", "missing data line"),
]


def test_bad_thermal_cards():
    """Each bad card stops the run with file:line naming it."""
    m, x0, bcs = free_case("Q4", "S")
    for name, card, msg in BAD:
        text = deck(m, "CPS4", bcs, step(f"ALL, {T1}\n"), material_extra=card, initial=False)
        run = run_deck("bad_thermal_" + name.replace(" ", "_"), text)
        assert run.rc != 0 and msg in run.stderr and ".inp:" in run.stderr, (name, run.stderr)
    for name, card, msg in [("outside", "*TEMPERATURE\nALL, 1.\n", "must be inside *STEP"),
                            ("amp", None, "undefined amplitude NONE")]:
        if card is None:
            text = deck(m, "CPS4", bcs, step(f"ALL, {T1}\n", card="*TEMPERATURE, AMPLITUDE=NONE"))
        else:
            text = deck(m, "CPS4", bcs, step(f"ALL, {T1}\n")).replace("*BOUNDARY", card + "*BOUNDARY")
        run = run_deck("bad_thermal_" + name, text)
        assert run.rc != 0 and msg in run.stderr and ".inp:" in run.stderr, (name, run.stderr)


def lame_u(r, ri, ro, pi, po, e, nu):
    """Plane-strain radial displacement of a ring ri..ro under inner and
    outer pressures pi, po (Lame)."""
    a = (pi * ri ** 2 - po * ro ** 2) / (ro ** 2 - ri ** 2)
    b = (pi - po) * ri ** 2 * ro ** 2 / (ro ** 2 - ri ** 2)
    return r * (1 + nu) / e * ((1 - 2 * nu) * a + b / r ** 2)


def test_shrink_fit_plane_strain():
    """A heated inner ring (a..b, dT) expands into an outer ring (b..c)
    in frictionless contact, plane strain, a quarter model with symmetry.
    Closed form: the interface pressure p makes the inner ring's free
    thermal growth (1 + nu) alpha dT b plus its Lame displacement under
    outer pressure p equal the outer ring's under inner pressure p. The
    radial displacements at r = a and r = c agree within 1 %."""
    ea, nu, alpha, dt = 200000.0, 0.3, 1.2e-5, 100.0
    ra, rb, rc = 10.0, 20.0, 30.0

    def ring(r0, r1, nr, nth):
        return lambda s, t: ((r0 + (r1 - r0) * s / nr) * math.cos(0.5 * math.pi * t / nth),
                             (r0 + (r1 - r0) * s / nr) * math.sin(0.5 * math.pi * t / nth))
    inner = Mesh("Q8", 4, 16, ring(ra, rb, 4, 16))
    outer = Mesh("Q8", 4, 16, ring(rb, rc, 4, 16), first_node=10001, first_elem=1001)

    def ids(ns):
        return ",\n".join(", ".join(map(str, ns[i:i + 12])) for i in range(0, len(ns), 12))
    text = f"""*NODE, NSET=ALL
{inner.node_lines()}{outer.node_lines()}{inner.element_card('CPE8', 'INNER')}{outer.element_card('CPE8', 'OUTER')}*NSET, NSET=HOT
{ids(sorted(inner.nodes))}
*NSET, NSET=XSYM
{ids(inner.side('top') + outer.side('top'))}
*NSET, NSET=YSYM
{ids(inner.side('bottom') + outer.side('bottom'))}
*NSET, NSET=RIM
{ids(inner.side('right'))}
*NSET, NSET=BORE
{ids(inner.side('left'))}
*NSET, NSET=OUTSIDE
{ids(outer.side('right'))}
*SURFACE, NAME=SEAT
{"".join(f"{e}, S{k}" + chr(10) for e, k in outer.faces('left'))}*MATERIAL, NAME=STEEL
*ELASTIC
{ea}, {nu}
*EXPANSION
{alpha}
*SOLID SECTION, ELSET=INNER, MATERIAL=STEEL
*SOLID SECTION, ELSET=OUTER, MATERIAL=STEEL
*CONTACT PAIR
RIM, SEAT
*INITIAL CONDITIONS, TYPE=TEMPERATURE
ALL, 20.
*BOUNDARY
XSYM, 1, 1
YSYM, 2, 2
*STEP
*STATIC
*TEMPERATURE
HOT, {20.0 + dt}
*NODE PRINT
U
*END STEP
"""
    run = run_deck("thermal_shrink_fit", text).ok()
    # interface pressure: free growth + inner(p outside) = outer(p inside) at r = b
    free = (1 + nu) * alpha * dt * rb
    k_in = lame_u(rb, ra, rb, 0.0, 1.0, ea, nu)
    k_out = lame_u(rb, rb, rc, 1.0, 0.0, ea, nu)
    p = free / (k_out - k_in)
    exact_a = (1 + nu) * alpha * dt * ra + lame_u(ra, ra, rb, 0.0, p, ea, nu)
    exact_c = lame_u(rc, rb, rc, p, 0.0, ea, nu)
    ub = run.listing.increments[-1].block("NODE U")
    u = {int(n): (u1, u2) for n, u1, u2 in zip(ub["node"], ub["U1"], ub["U2"])}
    worst = 0.0
    for mesh, side, exact in ((inner, "left", exact_a), (outer, "right", exact_c)):
        for n in mesh.side(side):
            x, y = mesh.nodes[n]
            ur = (u[n][0] * x + u[n][1] * y) / math.hypot(x, y)
            worst = max(worst, abs(ur - exact) / abs(exact))
            assert abs(ur - exact) < 0.01 * abs(exact), (side, n, ur, exact, p)
    print(f"  shrink fit CPE8: p = {p:.4f}, worst radial displacement error {worst:.2e}")
