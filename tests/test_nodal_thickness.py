"""*NODAL THICKNESS that varies inside an element: the elements
interpolate the nodal thicknesses with their shape functions (stiffness,
thermal load, body forces), an edge pressure the thickness along its
edge, a contact area the thickness along the slave face. Closed forms: a
patch in uniform stress under a thickness linear across the load (exact
on distorted meshes), a tapered bar (converging as the mesh is refined),
uniform contact pressure between blocks of varying thickness."""
import math

from decks import grid, node_lines, quad_lines
from helpers import rel_err, run_deck
from test_contact import blocks_deck, push_step, contact_blocks, series_pressure, G0, W, NX1, NX2

E, NU, SIG = 1000.0, 0.25, 3.0


def thickness_lines(nodes, t):
    return "".join(f"{n}, {t(x, y)!r}\n" for n, (x, y) in nodes.items())


def patch_deck(etype, nodes, elements, right_elems, right_face, thickness):
    """A plate [0, 2] x [0, 1] pulled by a traction SIG on its right edge
    (a *DLOAD pressure -SIG on the right elements' face), held along x on
    the left edge and at the origin along y."""
    left = [n for n, (x, y) in nodes.items() if abs(x) < 1e-12]
    origin = [n for n, (x, y) in nodes.items() if abs(x) < 1e-12 and abs(y) < 1e-12]
    dload = "".join(f"{e}, P{right_face}, {-SIG}\n" for e in right_elems)
    return f"""*NODE, NSET=ALLN
{node_lines(nodes)}*ELEMENT, TYPE={etype}, ELSET=PLATE
{elements}*NSET, NSET=LEFT
{", ".join(map(str, left))}
*MATERIAL, NAME=M
*ELASTIC
{E}, {NU}
*SOLID SECTION, ELSET=PLATE, MATERIAL=M, NODAL THICKNESS
*NODAL THICKNESS
{thickness_lines(nodes, thickness)}*BOUNDARY
LEFT, 1, 1
{origin[0]}, 2, 2
*STEP
*STATIC
*DLOAD
{dload}*NODE PRINT, NSET=ALLN
U
*EL PRINT, ELSET=PLATE
S
*END STEP
"""


def quad8_mesh(nx, ny, x1, y1):
    """8-node quadrilaterals on a regular grid [0, x1] x [0, y1]: nodes and
    element lines (corners counter-clockwise, then mid-sides)."""
    nodes, ids = {}, {}
    nid = 1
    for j in range(2 * ny + 1):
        for i in range(2 * nx + 1):
            if i % 2 and j % 2:
                continue
            nodes[nid] = (x1 * i / (2 * nx), y1 * j / (2 * ny))
            ids[i, j] = nid
            nid += 1
    lines = []
    for j in range(ny):
        for i in range(nx):
            a, b = 2 * i, 2 * j
            conn = [ids[a, b], ids[a + 2, b], ids[a + 2, b + 2], ids[a, b + 2],
                    ids[a + 1, b], ids[a + 2, b + 1], ids[a + 1, b + 2], ids[a, b + 1]]
            lines.append(f"{j * nx + i + 1}, " + ", ".join(map(str, conn)) + "\n")
    return nodes, "".join(lines), [j * nx + nx for j in range(ny)]


def test_patch_uniform_stress_thickness_across_the_load():
    """Thickness t = 0.5 + 0.8 y, linear across the pulled edge: S11 = SIG,
    S22 = S12 = 0 is in equilibrium (the force per length SIG t(y) does not
    change along x) and u = SIG x / E', v = -nu' SIG y / E' (plane stress
    E' = E, nu' = nu; plane strain E' = E / (1 - nu^2), nu' = nu / (1 -
    nu)) is exact: every element reproduces it to round-off, on a distorted
    mesh of 4-node quadrilaterals and on 8-node ones."""
    t = lambda x, y: 0.5 + 0.8 * y  # noqa: E731
    n4, ids, quads = grid(4, 3, 0.0, 2.0, 0.0, 1.0, distort=0.35)
    right4 = [j * 4 + 4 for j in range(3)]
    cases = [("CPS4", n4, quad_lines(quads), right4, E, NU),
             ("CPE4", n4, quad_lines(quads), right4, E / (1 - NU ** 2), NU / (1 - NU))]
    n8, lines8, right8 = quad8_mesh(3, 2, 2.0, 1.0)
    cases.append(("CPS8", n8, lines8, right8, E, NU))
    for etype, nodes, lines, right, e_eff, nu_eff in cases:
        run = run_deck("thick_patch_" + etype, patch_deck(etype, nodes, lines, right, 2, t)).ok()
        inc = run.listing.increments[-1]
        u = inc.block("NODE U", set="ALLN")
        umax = SIG * 2.0 / e_eff
        for k, nid in enumerate(u["node"]):
            x, y = nodes[int(nid)]
            assert abs(u["U1"][k] - SIG * x / e_eff) < 1e-12 * umax, (etype, nid, u["U1"][k])
            assert abs(u["U2"][k] + nu_eff * SIG * y / e_eff) < 1e-12 * umax, (etype, nid, u["U2"][k])
        s = inc.block("ELEMENT S", set="PLATE")
        assert max(abs(s["S11"] - SIG)) < 1e-11 * SIG, (etype, s["S11"])
        assert max(abs(s["S22"])) < 1e-11 * SIG and max(abs(s["S12"])) < 1e-11 * SIG, etype


def tapered_bar(nx, etype="CPS8", length=10.0, width=1.0, t0=1.0, t1=3.0, p=2.0):
    """A bar of width `width` whose thickness grows linearly from t0 at x = 0
    to t1 at x = length, nu = 0, pulled by a traction p on its right end."""
    t = lambda x, y: t0 + (t1 - t0) * x / length  # noqa: E731
    if etype == "CPS8":
        nodes, lines, right = quad8_mesh(nx, 1, length, width)
    else:
        nodes, ids, quads = grid(nx, 1, 0.0, length, 0.0, width)
        lines, right = quad_lines(quads), [nx]
    deck = patch_deck(etype, nodes, lines, right, 2, t).replace(f"{E}, {NU}", f"{E}, 0.").replace(
        f"P2, {-SIG}", f"P2, {-p}")
    tip = [n for n, (x, y) in nodes.items() if abs(x - length) < 1e-12]
    return deck, tip


def test_tapered_bar_converges_to_the_closed_form():
    """nu = 0 makes the 2D answer the 1D one: N = F / width constant, so
    u(L) = F / (E width) * integral dx / t(x) = F L ln(t1/t0) / (E width
    (t1 - t0)), with F = p width t1. The stress F / (width t(x)) is not a
    polynomial, and the elements are stiffer than the bar: CPS8 elements
    converge to it as h^4 (measured relative errors, thickness ratio 3:
    8.2e-4 with 2 elements along the bar, 6.8e-5 with 4, 4.7e-6 with 8,
    3.0e-7 with 16), CPS4 ones as h^2 (8.1e-3 with 4, 2.1e-3 with 8).
    Every node of the loaded end moves alike (N does not vary across)."""
    length, width, t0, t1, p = 10.0, 1.0, 1.0, 3.0, 2.0
    force = p * width * t1
    exact = force * length * math.log(t1 / t0) / (E * width * (t1 - t0))
    errors = {}
    for etype, nx in (("CPS8", 2), ("CPS8", 4), ("CPS8", 8), ("CPS4", 4), ("CPS4", 8)):
        deck, tip = tapered_bar(nx, etype, length, width, t0, t1, p)
        run = run_deck(f"thick_taper_{etype}_{nx}", deck).ok()
        u = run.listing.increments[-1].block("NODE U", set="ALLN")
        u_tip = [u["U1"][k] for k, nid in enumerate(u["node"]) if int(nid) in tip]
        assert max(u_tip) - min(u_tip) < 1e-12 * exact, (etype, nx, u_tip)
        errors[etype, nx] = rel_err(u_tip[0], exact)
    assert errors["CPS8", 4] < 1e-4, errors
    assert errors["CPS8", 8] < 1e-5, errors
    assert errors["CPS8", 4] / errors["CPS8", 8] > 12.0, errors
    assert 3.0 < errors["CPS4", 4] / errors["CPS4", 8] < 5.0, errors


def test_contact_area_follows_the_thickness():
    """Two blocks pressed together, both of thickness 1 + x along the contact
    line: the stress stays uniform, each slave node's area is the integral
    of N_i (1 + x) over the slave face (h t_i inside, h (2 t_end + t_next)
    / 6 at the ends), and the pressure, force over area, is the same at
    every node (the series pressure of the blocks within the penalty's
    share) and equals the total force over the area W (1 + W / 2)."""
    d = 3 * G0
    deck = blocks_deck([push_step(d, 2)])
    sections = "*SOLID SECTION, ELSET=LOWER, MATERIAL=M\n*SOLID SECTION, ELSET=UPPER, MATERIAL=M\n"
    assert sections in deck
    nodes = {}
    node_part = deck[deck.index("*NODE, NSET=ALLN\n") + 17:deck.index("*ELEMENT")]
    for line in node_part.splitlines():
        n, x, y = line.split(",")
        nodes[int(n)] = (float(x), float(y))
    deck = deck.replace(sections, sections.replace("MATERIAL=M\n", "MATERIAL=M, NODAL THICKNESS\n") +
                        "*NODAL THICKNESS\n" + thickness_lines(nodes, lambda x, y: 1.0 + x))
    run = run_deck("thick_contact", deck).ok()
    slave, master, summ = contact_blocks(run.listing.increments[-1])
    h = W / NX2
    for k, nid in enumerate(slave["node"]):
        x = nodes[int(nid)][0]
        if abs(x) < 1e-9 or abs(x - W) < 1e-9:
            nxt = x + h if abs(x) < 1e-9 else x - h
            area = h * (2 * (1 + x) + (1 + nxt)) / 6
        else:
            area = h * (1 + x)
        assert rel_err(slave["area"][k], area) < 1e-12, (x, slave["area"][k], area)
    p = slave["pressure"]
    assert (max(p) - min(p)) / max(p) < 1e-9, p
    assert rel_err(p[0], series_pressure(d)) < 0.005, (p[0], series_pressure(d))
    assert rel_err(summ["total_force"][0], p[0] * W * (1 + W / 2)) < 1e-9


def test_nodal_thickness_checks():
    """A node of a plane element without a thickness is an error naming the
    section; axisymmetric elements in a NODAL THICKNESS section need none
    (their thickness is the circumference)."""
    nodes, ids, quads = grid(2, 1, 0.0, 2.0, 0.0, 1.0)
    deck = patch_deck("CPS4", nodes, quad_lines(quads), [2], 2, lambda x, y: 1.0)
    missing = deck.replace("*NODAL THICKNESS\n1, 1.0\n", "*NODAL THICKNESS\n")
    run = run_deck("thick_missing", missing)
    line = missing.splitlines().index("*SOLID SECTION, ELSET=PLATE, MATERIAL=M, NODAL THICKNESS") + 1
    assert run.rc == 1 and f"thick_missing.inp:{line}: error: NODAL THICKNESS: node 1 of element 1" in run.stderr, \
        run.stderr
    axi = deck.replace("CPS4", "CAX4").replace("*NODAL THICKNESS\n" + thickness_lines(nodes, lambda x, y: 1.0),
                                               "*NODAL THICKNESS\n3, 2.\n")
    run = run_deck("thick_axi", axi).ok()
    assert "warning" not in run.stderr, run.stderr


def test_thickness_interpolated_below_zero_is_an_error():
    """Quadratic shape functions dip below zero at the corners' far side: a
    CPS8 with thickness 1 at its corners and 0.01 at its mid-side nodes has
    a negative thickness inside. The run stops naming the element instead
    of integrating a negative volume."""
    deck, _ = tapered_bar(1)
    nodes, _, _ = quad8_mesh(1, 1, 10.0, 1.0)
    mids = [n for n, (x, y) in nodes.items() if abs(x - 5.0) < 1e-12 or abs(y - 0.5) < 1e-12]
    lines = "".join(f"{n}, {0.01 if n in mids else 1.0}\n" for n in nodes)
    head, rest = deck.split("*NODAL THICKNESS\n", 1)
    rest = rest[rest.index("*"):]
    run = run_deck("thick_negative", head + "*NODAL THICKNESS\n" + lines + rest)
    assert run.rc == 1 and "element 1 (CPS8)" in run.stderr and "NODAL THICKNESS that the element interpolates" \
        in run.stderr, run.stderr
