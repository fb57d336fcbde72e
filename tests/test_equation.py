"""*EQUATION: linear multi-point constraints imposed exactly by
elimination of each equation's first dof, in every solver and contact
path.

- Two blocks meshed apart, their coincident interface nodes tied by
  equations, give the displacements and reactions of the merged mesh
  (each solver), loads on dependent dofs included.
- An inhomogeneous constraint through a reference node (a node of no
  element with a *BOUNDARY) gives what prescribing the edge directly gives,
  and the reference node's reaction is the edge's support reaction; the
  same through a chain of equations.
- A plane-strain block whose top edge is kept straight by equations and
  pulled through the reference node, and a block on a skew roller
  (c1 u_x + c2 u_y = 0), against the closed-form uniform states.
- Contact with dependent dofs on contact nodes: the full and the
  condensed contact solve agree, and the solvers agree.
- Constraints that cannot be eliminated are errors naming the equation's
  line."""
import math
import re

import numpy as np

from decks import grid, node_lines, quad_lines
from helpers import run_deck
from test_solvers import with_solver

E, NU = 1000.0, 0.3
SOLVERS = ["TYPE=SKYLINE", "TYPE=CHOLMOD", "TYPE=UMFPACK"]


def block_text(nodes, elements, sets, eqs, bcs, steps, etype="CPE4", extra=""):
    """A deck of quads: nodes {id: (x, y)}, elements [(id, nodes)], sets
    {name: [ids]}, model-level *EQUATION text and *BOUNDARY lines, step
    bodies."""
    out = ["*HEADING\nequation test\n*NODE, NSET=ALLN\n", node_lines(nodes), f"*ELEMENT, TYPE={etype}, ELSET=ALLE\n"]
    out += [f"{e}, " + ", ".join(map(str, c)) + "\n" for e, c in elements]
    for name, ids in sets.items():
        out.append(f"*NSET, NSET={name}\n")
        out += [", ".join(map(str, ids[k:k + 8])) + "\n" for k in range(0, len(ids), 8)]
    out.append(f"*MATERIAL, NAME=M\n*ELASTIC\n{E}, {NU}\n*SOLID SECTION, ELSET=ALLE, MATERIAL=M\n1.\n")
    out.append(extra)
    if eqs:
        out.append("*EQUATION\n" + eqs)
    if bcs:
        out.append("*BOUNDARY\n" + bcs)
    out += steps
    return "".join(out)


def step(body, incs=1, prints="*NODE PRINT, NSET=ALLN\nU, RF\n"):
    return f"*STEP\n*STATIC\n{1.0 / incs}, 1.0\n{body}{prints}*END STEP\n"


def node_u(run, inc=-1, set_name="ALLN"):
    """{node: (u1, u2)} of one increment."""
    b = run.listing.increments[inc].block("NODE U", set=set_name)
    return {int(n): (a, c) for n, a, c in zip(b["node"], b["U1"], b["U2"])}


def node_rf(run, inc=-1, set_name="ALLN"):
    b = run.listing.increments[inc].block("NODE RF", set=set_name)
    return {int(n): (a, c) for n, a, c in zip(b["node"], b["RF1"], b["RF2"])}


# ------------------------------------------------------------- tied blocks

NX, NY, L, H = 8, 4, 4.0, 1.0


def beam(split):
    """A 4 x 1 plane-strain beam, clamped at x = 0, with an end shear and
    axial load, a pressure on its top and a load at an interface node.
    split: the right half is a separate mesh (node ids from 1001) tied to
    the left one by equations, one per interface node and dof: dof 1 by
    node sets, the right block's node first (eliminated; it carries the
    interface load); dof 2 node by node, either node first."""
    nodes, ids, quads = grid(NX, NY, 0.0, L, 0.0, H, distort=0.3)
    elements = [(k + 1, q) for k, q in enumerate(quads)]
    half = NX // 2
    iface = [ids[half, j] for j in range(NY + 1)]
    eqs = ""
    sets = {"LEFT": [ids[0, j] for j in range(NY + 1)], "TIP": [ids[NX, j] for j in range(NY + 1)]}
    if split:
        twin = {n: 1001 + k for k, n in enumerate(iface)}
        for n, t in twin.items():
            nodes[t] = nodes[n]
        for k, (e, q) in enumerate(elements):
            if k % NX >= half:
                elements[k] = (e, tuple(twin.get(n, n) for n in q))
        sets["IFR"], sets["IFL"] = list(twin.values()), iface
        eqs = "2\nIFR, 1, 2.5, IFL, 1, -2.5\n" + "".join(
            f"2\n{t}, 2, 0.7, {n}, 2, -0.7\n" if k % 2 else f"2\n{n}, 2, -3., {t}, 2, 3.\n"
            for k, (n, t) in enumerate(twin.items()))
        loaded = twin[iface[2]]
    else:
        loaded = iface[2]
    top = [e for e, q in elements if (e - 1) // NX == NY - 1]
    body = (f"*CLOAD\nTIP, 2, -0.2\nTIP, 1, 0.5\n{loaded}, 1, 0.3\n{loaded}, 2, -0.7\n*DLOAD\n" +
            "".join(f"{e}, P3, 0.1\n" for e in top))
    return block_text(nodes, elements, sets, eqs, "LEFT, 1, 2\n", [step(body)])


def test_tied_blocks_equal_the_merged_mesh_each_solver():
    """Displacements of every node (interface twins included) within 1e-10
    of the merged mesh's largest, and the clamp's reactions the same, with
    the skyline (RCM), CHOLMOD and UMFPACK."""
    merged_deck, split_deck = beam(False), beam(True)
    for solver in SOLVERS:
        ref = run_deck("equation_merged", with_solver(merged_deck, solver)).ok()
        run = run_deck("equation_tied", with_solver(split_deck, solver)).ok()
        u0, u1 = node_u(ref), node_u(run)
        umax = max(max(abs(a), abs(b)) for a, b in u0.values())
        twin_of = {1001 + k: n for k, n in enumerate(sorted(u0)[NX // 2::NX + 1])}
        assert len(u1) == len(u0) + NY + 1
        err = max(max(abs(u1[n][d] - u0[twin_of.get(n, n)][d]) for d in (0, 1)) for n in u1)
        assert err <= 1e-10 * umax, f"{solver}: {err / umax:.2e}"
        r0, r1 = node_rf(ref), node_rf(run)
        rmax = max(max(abs(a), abs(b)) for a, b in r0.values())
        left = [n for n in u0 if n % (NX + 1) == 1]
        for n in left:
            assert max(abs(r1[n][d] - r0[n][d]) for d in (0, 1)) <= 1e-9 * rmax, (solver, n, r1[n], r0[n])
        # no out-of-balance force elsewhere: the dependent dofs' loads went
        # to their independent dofs, and the dependent dofs show none
        assert max(max(abs(r1[n][0]), abs(r1[n][1])) for n in r1 if n not in left) <= 1e-9 * rmax, solver
        assert all(r1[n] == (0.0, 0.0) for n in r1 if n > 1000 and (n - 1001) % 2 == 1), solver
        if solver == "TYPE=SKYLINE":
            # RCM orders the node graph with the equations' couplings: the
            # tied mesh's profile is the merged one's (1090 instead of 956
            # when they are left out)
            prof = [float(re.search(r"profile (\S+)", open(r.listing_path).read()).group(1)) for r in (ref, run)]
            assert prof[1] <= prof[0], prof


# ------------------------------------------------- reference node, chains

W, HB, NXB, NYB, REF = 2.0, 1.0, 6, 4, 999


def pressed_block(top, ref_eqs=None, extra_eqs="", extra_bcs="", body1="", body2=""):
    """A distorted plane-strain block on rollers (bottom), held at its
    bottom-left corner, sheared by a load at its top-right corner; two
    steps move its top edge (-0.01 over two increments, then 0.02 through
    an amplitude). top(value) gives the *BOUNDARY lines that do it;
    ref_eqs(top nodes) the equations tying the edge to the reference node
    REF (a node of no element at (1, 2)), if any."""
    nodes, ids, quads = grid(NXB, NYB, 0.0, W, 0.0, HB, distort=0.25)
    elements = [(k + 1, q) for k, q in enumerate(quads)]
    top_nodes = [ids[i, NYB] for i in range(NXB + 1)]
    sets = {"BOTTOM": [ids[i, 0] for i in range(NXB + 1)], "TOP": top_nodes, "CORNER": [ids[0, 0]],
            "TR": [ids[NXB, NYB]], "BLOCK": list(nodes)}
    eqs = extra_eqs
    if ref_eqs:
        nodes[REF] = (1.0, 2.0)
        sets["REF"] = [REF]
        eqs += ref_eqs(top_nodes)
    amp = "*AMPLITUDE, NAME=UP\n0., 0., 0.5, 0.8, 1., 1.\n"
    prints = "*NODE PRINT, NSET=ALLN\nU, RF\n"
    steps = [step(top(-0.01) + "*CLOAD\nTR, 1, 0.3\n" + body1, 2, prints),
             step(top(0.02).replace("*BOUNDARY", "*BOUNDARY, AMPLITUDE=UP") + body2, 2, prints)]
    return block_text(nodes, elements, sets, eqs, "BOTTOM, 2, 2\nCORNER, 1, 1\n" + extra_bcs, steps, extra=amp)


def direct(v):
    return f"*BOUNDARY\nTOP, 2, 2, {v}\n"


def through_ref(v):
    return f"*BOUNDARY\nREF, 2, 2, {v}\n"


def ref_by_sets(top_nodes):
    """One equation per top node (node sets), the top node eliminated; a
    third term on the held x dof of the corner (zero) names dof 1 of
    another node than REF, whose dof 1 stays unused."""
    return "3\nTOP, 2, 1., REF, 2, -1., CORNER, 1, 0.5\n"


def ref_by_chain(top_nodes):
    """A chain: each top node equal to the next, the last equal to REF,
    listed last link first with scaled coefficients, over two lines each."""
    links = [(a, b) for a, b in zip(top_nodes, top_nodes[1:] + [REF])]
    return "".join(f"2\n{a}, 2, -2.,\n{b}, 2, 2.\n" for a, b in reversed(links))


def compare_with_direct(name, ref_eqs):
    ref = run_deck(f"{name}_direct", pressed_block(direct)).ok()
    run = run_deck(name, pressed_block(through_ref, ref_eqs)).ok()
    assert len(ref.listing.increments) == len(run.listing.increments) == 4
    for inc in range(4):
        u0, u1 = node_u(ref, inc), node_u(run, inc)
        umax = max(max(abs(a), abs(b)) for a, b in u0.values())
        err = max(max(abs(u1[n][d] - u0[n][d]) for d in (0, 1)) for n in u0)
        assert err <= 1e-10 * umax, (name, inc, err / umax)
        # the reference node moves with the edge; its unused dof stays at 0
        assert abs(u1[REF][1] - u0[max(u0)][1]) <= 1e-12 * umax and u1[REF][0] == 0.0, (name, u1[REF])
        r0, r1 = node_rf(ref, inc), node_rf(run, inc)
        top_sum = sum(r0[n][1] for n in r0 if n > (NXB + 1) * NYB)
        assert abs(r1[REF][1] - top_sum) <= 1e-9 * abs(top_sum), (name, inc, r1[REF][1], top_sum)
        assert abs(top_sum) > 1.0, top_sum
        bottom = [n for n in r0 if n <= NXB + 1]
        rmax = max(abs(r0[n][1]) for n in bottom)
        assert max(abs(r1[n][1] - r0[n][1]) for n in bottom) <= 1e-9 * rmax, (name, inc)


def test_reference_node_boundary_equals_prescribing_the_edge():
    """Each top node tied to REF by a node-set equation; REF prescribed
    (ramped, then through an amplitude in a second step): displacements of
    every node within 1e-10 of prescribing the edge directly, in all four
    increments; REF's reaction equals the edge's summed reaction, the
    bottom reactions are the same."""
    compare_with_direct("equation_ref", ref_by_sets)


def test_chain_of_equations_resolved():
    """The same through a chain t1 = t2 = ... = t7 = REF (each link an
    equation whose independent dof is dependent in the next)."""
    compare_with_direct("equation_chain", ref_by_chain)


# ------------------------------------------------------------ closed form

def test_straight_top_edge_uniform_tension_exact():
    """Plane strain, a distorted mesh on rollers (bottom and left); the top
    edge kept straight by u_y(top node) - u_y(REF) = 0 and pulled by a
    *CLOAD F on REF. The uniform state is exact: u_y = (1 - nu^2) F / (E W)
    y, u_x = -nu (1 + nu) F / (E W) x at every node; REF moves with the
    edge and its reaction is zero; the bottom reactions sum to -F."""
    F = 3.0
    nodes, ids, quads = grid(NXB, NYB, 0.0, W, 0.0, HB, distort=0.3)
    elements = [(k + 1, q) for k, q in enumerate(quads)]
    nodes[REF] = (0.3, 1.7)
    sets = {"BOTTOM": [ids[i, 0] for i in range(NXB + 1)], "LEFT": [ids[0, j] for j in range(NYB + 1)],
            "TOP": [ids[i, NYB] for i in range(NXB + 1)], "REF": [REF]}
    eqs = "2\nTOP, 2, 1., REF, 2, -1.\n"
    deck = block_text(nodes, elements, sets, eqs, "BOTTOM, 2, 2\nLEFT, 1, 1\n", [step(f"*CLOAD\nREF, 2, {F}\n")])
    for solver in SOLVERS:
        run = run_deck("equation_straight_edge", with_solver(deck, solver)).ok()
        u, rf = node_u(run), node_rf(run)
        sig = F / W
        ey, ex = (1 - NU ** 2) * sig / E, -NU * (1 + NU) * sig / E
        scale = ey * HB
        for n, (x, y) in nodes.items():
            if n == REF:
                assert abs(u[n][1] - ey * HB) <= 1e-10 * scale and u[n][0] == 0.0, (solver, u[n])
                continue
            assert abs(u[n][0] - ex * x) <= 1e-10 * scale and abs(u[n][1] - ey * y) <= 1e-10 * scale, \
                (solver, n, u[n], (ex * x, ey * y))
        assert abs(sum(rf[n][1] for n in sets["BOTTOM"]) + F) <= 1e-10 * F, solver
        assert abs(rf[REF][1]) <= 1e-10 * F, solver


def test_dependent_dofs_in_every_output():
    """The straight-edge block: the stresses (computed from the expanded
    displacements) are the uniform F / W, and the gmsh result file and the
    ParaView file hold the dependent top nodes' displacements as the
    listing does."""
    import os
    import sys
    from helpers import ROOT
    sys.path.insert(0, os.path.join(ROOT, "scripts"))
    from gmsh_results import read_msh
    F = 3.0
    nodes, ids, quads = grid(NXB, NYB, 0.0, W, 0.0, HB, distort=0.3)
    elements = [(k + 1, q) for k, q in enumerate(quads)]
    nodes[REF] = (0.3, 1.7)
    sets = {"BOTTOM": [ids[i, 0] for i in range(NXB + 1)], "LEFT": [ids[0, j] for j in range(NYB + 1)],
            "TOP": [ids[i, NYB] for i in range(NXB + 1)], "REF": [REF]}
    prints = "*NODE PRINT, NSET=ALLN\nU\n*EL PRINT, ELSET=ALLE\nS\n*NODE FILE\nU\n"
    deck = block_text(nodes, elements, sets, "2\nTOP, 2, 1., REF, 2, -1.\n", "BOTTOM, 2, 2\nLEFT, 1, 1\n",
                      [step(f"*CLOAD\nREF, 2, {F}\n", prints=prints)])
    run = run_deck("equation_outputs", deck, args=("--vtu",)).ok()
    inc = run.listing.increments[-1]
    s = inc.block("ELEMENT S", set="ALLE")
    assert np.max(np.abs(s["S22"] - F / W)) <= 1e-9 * F / W and np.max(np.abs(s["S11"])) <= 1e-9 * F / W
    u = node_u(run)
    top = sets["TOP"]
    assert all(u[n][1] == u[REF][1] for n in top) and u[REF][1] > 0.0
    res = read_msh(os.path.splitext(run.listing_path)[0] + ".msh")
    _, disp = res.node_view("Displacement", 0)
    at = {int(n): k for k, n in enumerate(res.node_ids)}
    for n in top:
        assert abs(disp[at[n], 1] - u[n][1]) <= 1e-14 * u[n][1] and abs(disp[at[n], 0] - u[n][0]) <= 1e-14 * u[REF][1]
    try:
        import meshio
    except ImportError:
        return
    vtu = os.path.splitext(run.listing_path)[0] + "_0001.vtu"
    mesh = meshio.read(vtu)
    at = {int(n): k for k, n in enumerate(mesh.point_data["NodeId"])}
    for n in top:
        assert abs(mesh.point_data["U"][at[n], 1] - u[n][1]) <= 1e-14 * u[n][1]


def test_skew_roller_uniform_tension_exact():
    """A block rotated by 30 degrees on skew rollers: bottom nodes
    -sin(a) u_x + cos(a) u_y = 0, left nodes cos(a) u_x + sin(a) u_y = 0
    (CPE8, the equations' dependent dofs differ: u_x below, u_y on the
    left), its corner fixed, a uniform tension on its top face. Every
    node moves as the rotated uniaxial state: u' = (-nu (1 + nu) s x',
    (1 - nu^2) s y') / E."""
    from quadmesh import Mesh
    a, s = math.radians(30.0), 2.0
    c, sn = math.cos(a), math.sin(a)
    mesh = Mesh("Q8", 3, 2, lambda p, q: (p * 1.0 / 3 * W + 0.05 * math.sin(3 * p * q),
                                          q * HB / 2 + 0.04 * math.sin(2 * p + q)), straight=True)
    # the sides must stay straight lines for the rollers: only interior nodes move
    local = {}
    for n, (x, y) in mesh.nodes.items():
        i, j = [k for k, v in mesh.index.items() if v == n][0]
        px, py = i / 2 * W / 3, j / 2 * HB / 2
        if 0 < i < 6 and 0 < j < 4:
            px, py = x, y
        local[n] = (px, py)
    nodes = {n: (c * x - sn * y, sn * x + c * y) for n, (x, y) in local.items()}
    elements = [(k + 1, conn) for k, conn in enumerate(mesh.elements)]
    corner = mesh.index[0, 0]
    bottom = [n for n in mesh.side("bottom") if n != corner]
    left = [n for n in mesh.side("left") if n != corner]
    eqs = "".join(f"2\n{n}, 1, {-sn!r}, {n}, 2, {c!r}\n" for n in bottom)
    eqs += "".join(f"2\n{n}, 2, {sn!r}, {n}, 1, {c!r}\n" for n in left)
    top = "".join(f"{1 + e}, P3, {-s}\n" for e in range(len(elements)) if e // 3 == 1)
    deck = block_text(nodes, elements, {}, eqs, f"{corner}, 1, 2\n", [step("*DLOAD\n" + top)], etype="CPE8")
    for solver in SOLVERS:
        run = run_deck("equation_skew", with_solver(deck, solver)).ok()
        u = node_u(run)
        ex, ey = -NU * (1 + NU) * s / E, (1 - NU ** 2) * s / E
        scale = ey * HB
        for n, (x, y) in local.items():
            ux, uy = ex * x, ey * y
            want = (c * ux - sn * uy, sn * ux + c * uy)
            got = u[n]
            assert max(abs(got[0] - want[0]), abs(got[1] - want[1])) <= 1e-10 * scale, (solver, n, got, want)


# ---------------------------------------------------------------- contact

CONTACT_EQS = ("*EQUATION\n"
               "2\n1004, 2, 1., 1005, 2, -1.\n"            # slave node on a slave node
               "2\n1007, 1, 1., 1018, 1, -1.\n"            # slave node on an interior node
               "3\n1009, 2, 2., 1008, 2, -1., 1010, 2, -1.\n"  # slave node on two, one of them dependent next
               "2\n1010, 2, 1., 1050, 2, -0.5\n"           # ... on a prescribed top node (a chain)
               "2\n33, 2, 1., 27, 2, -1.\n")               # master node on the node below it


def contact_deck():
    import test_contact as tc
    d = 3 * tc.G0
    back = tc.push_step(d, 2).replace(f"TOP, 2, 2, {-d}", "TOP, 2, 2, 0.0")
    return tc.blocks_deck([CONTACT_EQS, tc.push_step(d, 2), back])


def test_contact_with_dependent_dofs_full_and_condensed_agree():
    """Dependent dofs on slave and master nodes (their independent dofs
    join the contact equations; one is an interior node, one a prescribed
    node through a chain): FULL and CONDENSED agree to 1e-9 in
    displacements, contact forces and gaps, with the same statuses and
    iterations; the condensed path really ran. The skyline and UMFPACK
    (full) give CHOLMOD's displacements."""
    import test_condensed as tcd
    deck = contact_deck()
    full = run_deck("equation_contact_full", tcd.with_path(deck, "FULL")).ok()
    cond = run_deck("equation_contact_condensed", tcd.with_path(deck, "CONDENSED")).ok()
    assert set(tcd.contact_solve(cond)) == {"condensed"} and set(tcd.contact_solve(full)) == {"full"}
    tcd.compare(full, cond)
    closed = np.array(tcd.column(full, "CONTACT SLAVE", "state")) == "CLOSED"
    assert closed.any() and not closed.all()
    u = node_u(full, 1, "ALL")
    assert u[1004][1] == u[1005][1] and abs(u[1010][1] - 0.5 * u[1050][1]) <= 1e-15 and u[33][1] == u[27][1]
    assert abs(u[1009][1] - 0.5 * (u[1008][1] + u[1010][1])) <= 1e-15 * abs(u[1010][1])
    ref = np.concatenate([tcd.column(full, "NODE U", c) for c in ("U1", "U2")])
    for solver in ("TYPE=SKYLINE", "TYPE=UMFPACK"):
        run = run_deck("equation_contact_" + solver[5:].lower(), tcd.with_path(with_solver(deck, solver), "FULL")).ok()
        got = np.concatenate([tcd.column(run, "NODE U", c) for c in ("U1", "U2")])
        assert np.max(np.abs(got - ref)) <= 1e-9 * np.max(np.abs(ref)), solver


# ----------------------------------------------------------------- errors

def small_deck(eqs, bcs="", body="", nodes_extra=""):
    """pressed_block's mesh with equations eqs (text after *EQUATION)."""
    deck = pressed_block(direct, extra_eqs=eqs, extra_bcs=bcs, body1=body)
    if nodes_extra:
        deck = deck.replace("*ELEMENT", nodes_extra + "*ELEMENT", 1)
    return deck


def line_of(deck, text):
    """The line number of the only line that reads text."""
    found = [k + 1 for k, line in enumerate(deck.splitlines()) if line == text]
    assert len(found) == 1, (text, found)
    return found[0]


def stops_at(name, deck, line, fragment):
    run = run_deck(name, deck)
    assert run.rc == 1, (name, run.rc, run.stderr)
    assert f"{name}.inp:{line}: error:" in run.stderr, (name, line, run.stderr)
    assert fragment in run.stderr, (name, run.stderr)
    assert "Traceback" not in run.stderr and "Backtrace" not in run.stderr and "Error termination" not in run.stderr
    return run


def test_equation_errors_name_the_equation_line():
    """Each constraint that cannot be eliminated stops the run naming the
    line of the equation at fault (its first term), exit status 1, no
    backtrace: a cycle, a dof dependent in two equations, coefficients of
    the dependent dof summing to zero, a dependent dof with a *BOUNDARY
    (model or step), a zero first coefficient, a dof 3 term with a
    non-zero coefficient, an undefined node, a coefficient whose ratio to
    the first overflows (1 / 1e-320; it ran into a singular stiffness at
    another node), ratios of 1e200 chained into 1e400."""
    # nodes: 8..14 the second row, 1..7 the bottom (held in y), 35 top right
    cases = [
        ("eq_cycle", "2\n9, 2, 1., 10, 2, -1.\n2\n11, 2, 1., 9, 2, -1.\n2\n10, 2, 1., 11, 2, -1.\n", "", "",
         "9, 2, 1., 10, 2, -1.", "form a cycle"),
        ("eq_twice", "2\n9, 2, 1., 10, 2, -1.\n2\n9, 2, 1., 11, 2, -1.\n", "", "",
         "9, 2, 1., 11, 2, -1.", "dependent dof (the first term) of two"),
        ("eq_sum_zero", "3\n9, 2, 1., 10, 2, -1., 9, 2, -1.\n", "", "",
         "9, 2, 1., 10, 2, -1., 9, 2, -1.", "sum to zero"),
        ("eq_bc_model", "2\n3, 2, 1., 10, 2, -1.\n", "", "", "3, 2, 1., 10, 2, -1.", "also has a *BOUNDARY"),
        ("eq_bc_step", "2\n9, 1, 1., 10, 1, -1.\n", "", "*BOUNDARY\n9, 1, 1, 0.001\n", "9, 1, 1., 10, 1, -1.",
         "also has a *BOUNDARY"),
        ("eq_zero_first", "2\n9, 2, 0., 10, 2, -1.\n", "", "", "9, 2, 0., 10, 2, -1.", "must not be zero"),
        ("eq_dof3", "2\n9, 2, 1., 10, 3, -1.\n", "", "", "9, 2, 1., 10, 3, -1.", "dof 3 with a non-zero coefficient"),
        ("eq_undefined", "2\n9, 2, 1., 777, 2, -1.\n", "", "", "9, 2, 1., 777, 2, -1.", "undefined node 777"),
        ("eq_ratio_overflow", "2\n9, 2, 1e-320, 10, 2, -1.\n", "", "", "9, 2, 1e-320, 10, 2, -1.",
         "divided by that of the dependent dof (the first term) overflows"),
        ("eq_chain_overflow", "2\n9, 2, 1e-100, 10, 2, -1e100\n2\n10, 2, 1e-100, 11, 2, -1e100\n", "", "",
         "9, 2, 1e-100, 10, 2, -1e100", "the coefficients overflow when the dependent dofs"),
    ]
    for name, eqs, bcs, body, bad, fragment in cases:
        deck = small_deck(eqs, bcs, body)
        if name == "eq_cycle":
            run = run_deck(name, deck)
            lines = [line_of(deck, t) for t in ("9, 2, 1., 10, 2, -1.", "11, 2, 1., 9, 2, -1.", "10, 2, 1., 11, 2, -1.")]
            assert run.rc == 1 and any(f"{name}.inp:{k}: error:" in run.stderr for k in lines), run.stderr
            assert fragment in run.stderr and "Backtrace" not in run.stderr, run.stderr
            continue
        stops_at(name, deck, line_of(deck, bad), fragment)


def test_dof3_with_zero_coefficient_is_dropped():
    """A dof 3 term with coefficient 0 (CalculiX decks of plane models may
    carry one) is dropped, and terms on the same dof are summed: the
    constraint u_y(9) = 0.25 u_y(10) + 0.75 u_y(10) holds."""
    run = run_deck("eq_dof3_zero", small_deck("4\n9, 2, 1., 10, 3, 0., 10, 2, -0.25, 10, 2, -0.75\n")).ok()
    for inc in range(4):
        u = node_u(run, inc)
        assert u[9][1] == u[10][1] and u[9][1] != 0.0


def test_nodes_no_element_reaches():
    """A node of no element and no equation is left out of the analysis
    with a warning at its line (tests/test_calculix_leniency.py has the
    rest). A load on the unused dof of a reference node (no element
    reaches it, no equation names that dof) stops the run: nothing
    carries it; the reference node's used dof is fine (tested above)."""
    deck = small_deck("", nodes_extra="*NODE\n555, 7., 7.\n")
    run = run_deck("eq_free_node", deck).ok()
    assert f"eq_free_node.inp:{line_of(deck, '555, 7., 7.')}: warning: 1 node belongs to no element" in run.stderr, \
        run.stderr
    deck = pressed_block(through_ref, ref_by_sets, body1="*CLOAD\nREF, 1, 1.\n")
    run = run_deck("eq_unused_dof_load", deck)
    assert run.rc == 1 and "*CLOAD acts on dof 1 of node 999" in run.stderr, run.stderr
    deck = pressed_block(through_ref, ref_by_sets, extra_bcs="REF, 1, 1\n", body1="*CLOAD\nREF, 1, 1.\n")
    run_deck("eq_unused_dof_held", deck).ok()
