"""*INITIAL CONDITIONS, TYPE=STRESS (CalculiX's data lines: element or
elset, integration point, S11, S22, S33, S12) on linear elastic bodies,
against closed forms: sig = D eps + sig0, the initial stress a load
-integral B^T sig0 dV.

* Self-equilibrated: a 2 x 1 plane-strain block (4 x 2 CPE4, and CPE8)
  with sig11 = +100 in the lower row of elements and -60 in the upper one
  (and s33 = 30), both ends held along x: no node but the held ones gets
  a net force, so u = 0 to round-off, the stresses stay sig0 at every
  point, and each end's reaction is the stress's resultant (100 - 60) x
  0.5 (thickness 1), with the sign of an internal force.
* Unbalanced: a free plane-stress square (CPS4, CPS8, CPS4R, CPS3; only
  rigid motions held) with a uniform sig0 = (s11, s22, s12): it relaxes
  to zero stress with the strain -C sig0 (u_x = eps11 x + gamma y,
  u_y = eps22 y), to 1e-9.
* Errors: a point beyond the element's rule, a nonlinear material, NLGEOM."""
from helpers import run_deck
from quadmesh import Mesh

E, NU = 200000.0, 0.3
NIP = {"CPE4": 4, "CPE8": 9, "CPS4": 4, "CPS8": 9, "CPS4R": 1, "CPS3": 1}


def block(element, width, height, nx, ny, sig0_of_row, bcs, step_extra="", material=None):
    shape = {"3": "T3", "4": "Q4", "8": "Q8", "R": "Q4"}[element[-1]]
    m = Mesh(shape, nx, ny, lambda s, t: (width * s / nx, height * t / ny), straight=True)
    per_row = len(m.elements) // ny
    lines = ""
    for k in range(len(m.elements)):
        s11, s22, s33, s12 = sig0_of_row(k // per_row)
        for ip in range(1, NIP[element] + 1):
            lines += f"{k + 1}, {ip}, {s11!r}, {s22!r}, {s33!r}, {s12!r}, 0., 0.\n"
    material = material or f"*ELASTIC\n{E}, {NU}\n"
    text = f"""*NODE, NSET=ALL
{m.node_lines()}{m.element_card(element, 'B')}*NSET, NSET=LEFT
{", ".join(map(str, m.side("left")))}
*NSET, NSET=RIGHT
{", ".join(map(str, m.side("right")))}
*MATERIAL, NAME=M
{material}*SOLID SECTION, ELSET=B, MATERIAL=M
1.
*INITIAL CONDITIONS, TYPE=STRESS
{lines}*BOUNDARY
{bcs(m)}*STEP{step_extra}
*STATIC
*NODE PRINT, NSET=ALL
U
*NODE PRINT, NSET=RIGHT, TOTALS=ONLY
RF
*EL PRINT
S
*END STEP
"""
    return m, text


def test_self_equilibrated_residual_stress_stays():
    rows = {0: (100.0, 0.0, 30.0, 0.0), 1: (-60.0, 0.0, 30.0, 0.0)}
    for element in ("CPE4", "CPE8"):
        m, text = block(element, 2.0, 1.0, 4, 2, rows.get,
                        lambda m: f"LEFT, 1, 1\nRIGHT, 1, 1\n{m.side('left')[0]}, 2, 2\n")
        run = run_deck(f"sig0_stays_{element}", text).ok()
        inc = run.listing.increments[-1]
        u = inc.block("NODE U", set="ALL")
        assert max(abs(v) for v in list(u["U1"]) + list(u["U2"])) <= 1e-12, element
        s = inc.block("ELEMENT S")
        per_row = len(m.elements) // 2
        for k, (elem, s11, s22, s33, s12) in enumerate(zip(s["element"], s["S11"], s["S22"], s["S33"], s["S12"])):
            want = rows[(int(elem) - 1) // per_row]
            assert abs(s11 - want[0]) <= 1e-9 and abs(s22) <= 1e-9 and abs(s12) <= 1e-9, (element, elem, s11)
            assert abs(s33 - want[2]) <= 1e-9, (element, elem, s33)
        b = inc.block("REACTIONS")
        rf = b["RF1"][list(b["set"]).index("RIGHT")]
        assert abs(rf - (100.0 - 60.0) * 0.5) <= 1e-9, (element, rf)


def test_unbalanced_initial_stress_relaxes_to_the_free_strain():
    s11, s22, s12 = 120.0, -40.0, 25.0
    g = E / (2.0 * (1.0 + NU))
    e11 = -(s11 - NU * s22) / E
    e22 = -(s22 - NU * s11) / E
    gam = -s12 / g
    for element in ("CPS4", "CPS8", "CPS4R", "CPS3"):
        # only the rigid motions held: the corner (0, 0) and y at (1, 0)
        m, text = block(element, 1.0, 1.0, 2, 2, lambda r: (s11, s22, 0.0, s12),
                        lambda m: f"{m.index[(0, 0)]}, 1, 2\n{m.index[(4, 0)]}, 2, 2\n")
        run = run_deck(f"sig0_relaxes_{element}", text).ok()
        inc = run.listing.increments[-1]
        u = inc.block("NODE U", set="ALL")
        ids = list(u["node"])
        for node, (x, y) in m.nodes.items():
            k = ids.index(node)
            assert abs(u["U1"][k] - (e11 * x + gam * y)) <= 1e-9 * abs(gam), (element, node, u["U1"][k])
            assert abs(u["U2"][k] - e22 * y) <= 1e-9 * abs(gam), (element, node, u["U2"][k])
        s = inc.block("ELEMENT S")
        assert max(abs(v) for c in ("S11", "S22", "S12") for v in s[c]) <= 1e-7 * s11, element


def test_initial_stress_errors():
    rows = lambda r: (100.0, 0.0, 0.0, 0.0)
    bcs = lambda m: "LEFT, 1, 2\n"
    _, text = block("CPE4", 1.0, 1.0, 1, 1, rows, bcs)
    for bad, message in (
            (text.replace("1, 4, 100.0", "1, 5, 100.0"), "has integration points 1 to 4, not 5"),
            (text.replace("*STEP", "*STEP, NLGEOM"), "under NLGEOM is not implemented"),
            (text.replace(f"*ELASTIC\n{E}, {NU}\n", f"*ELASTIC\n{E}, {NU}\n*PLASTIC\n200., 0.\n"),
             "with the nonlinear material M is not implemented"),
            (text.replace("1, 1, 100.0, 0.0, 0.0, 0.0, 0., 0.", "1, 1, 100.0, 0.0, 0.0, 0.0, 5., 0."),
             "S13 and S23 must be zero")):
        assert bad != text, message
        run = run_deck("sig0_error", bad)
        assert run.rc == 1 and message in run.stderr and "sig0_error.inp:" in run.stderr, (message, run.stderr)
