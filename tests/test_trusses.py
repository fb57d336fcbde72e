"""Trusses: line elements (T2D2, T3D2, T2D3, T3D3) given a *SOLID SECTION
carry an axial force E A / L times their stretch, as CalculiX makes them;
against closed forms: a bar under an end load, a two-bar truss at any
angle, a truss in parallel with a continuum block, a heated bar held at
both ends; the writers with trusses in the model; the errors."""
import math
import os

from decks import grid, node_lines, quad_lines
from helpers import rel_err, run_deck

E, A, L, F = 210000.0, 0.01, 2.0, 7.0


def bar_deck(etype="T2D2", extra_model="", step_extra="", load=f"2, 1, {F}"):
    """A bar along x from node 1 (held) to node 2; the 3-node bar lists
    end, middle (node 3), end."""
    if etype in ("T2D3", "T3D3"):
        elements, nodes = "1, 1, 3, 2\n", f"1, 0., 0.\n2, {L}, 0.\n3, {L / 2}, 0.\n"
    else:
        elements, nodes = "1, 1, 2\n", f"1, 0., 0.\n2, {L}, 0.\n"
    return f"""*NODE, NSET=ALLN
{nodes}*ELEMENT, TYPE={etype}, ELSET=BAR
{elements}*NSET, NSET=TIP
2
*MATERIAL, NAME=M
*ELASTIC
{E}, 0.3
{extra_model}*SOLID SECTION, ELSET=BAR, MATERIAL=M
{A}
*BOUNDARY
1, 1, 2
ALLN, 2, 2
*STEP
*STATIC
*CLOAD
{load}
{step_extra}*NODE PRINT, NSET=TIP
U
*EL PRINT, ELSET=BAR
S, E
*END STEP
"""


def test_bar_under_end_load():
    """u = F L / (E A), S11 = F / A, E11 = F / (E A) at every point, for
    the 2-node and the 3-node truss, 2D and 3D names alike."""
    for etype in ("T2D2", "T3D2", "T2D3", "T3D3"):
        run = run_deck("truss_bar_" + etype, bar_deck(etype)).ok()
        inc = run.listing.increments[-1]
        u = inc.block("NODE U", set="TIP")
        assert rel_err(u["U1"][0], F * L / (E * A)) < 1e-12, (etype, u["U1"])
        s = inc.block("ELEMENT S", set="BAR")
        assert len(s) == (2 if etype.endswith("3") else 1), etype
        assert max(abs(x - F / A) for x in s["S11"]) < 1e-12 * F / A, (etype, s["S11"])
        assert max(abs(x) for x in list(s["S22"]) + list(s["S12"])) == 0.0
        e = inc.block("ELEMENT E", set="BAR")
        assert max(abs(x - F / (E * A)) for x in e["E11"]) < 1e-12 * F / (E * A), (etype, e["E11"])


def v_truss(theta, a=1.5, h=2.0, p=5.0):
    """Two bars from (-a, 0) and (a, 0) to the apex (0, h), a load p
    towards the supports, everything turned by theta about the origin."""
    c, s = math.cos(theta), math.sin(theta)
    rot = lambda x, y: (c * x - s * y, s * x + c * y)  # noqa: E731
    pts = {1: rot(-a, 0.0), 2: rot(a, 0.0), 3: rot(0.0, h)}
    load = rot(0.0, -p)
    return f"""*NODE, NSET=ALLN
{node_lines(pts)}*ELEMENT, TYPE=T2D2, ELSET=BARS
1, 1, 3
2, 2, 3
*NSET, NSET=APEX
3
*MATERIAL, NAME=M
*ELASTIC
{E}, 0.3
*SOLID SECTION, ELSET=BARS, MATERIAL=M
{A}
*BOUNDARY
1, 1, 2
2, 1, 2
*STEP
*STATIC
*CLOAD
3, 1, {load[0]!r}
3, 2, {load[1]!r}
*NODE PRINT, NSET=APEX
U
*EL PRINT, ELSET=BARS
S
*END STEP
"""


def test_two_bar_truss_at_any_angle():
    """Each bar carries N = p / (2 sin alpha) in compression; the apex moves
    p L / (2 E A sin^2 alpha) towards the supports. Turning the whole truss
    and its load by theta turns the displacement by theta (the bars'
    directions come from their nodes)."""
    a, h, p = 1.5, 2.0, 5.0
    bar = math.hypot(a, h)
    sin_a = h / bar
    delta = p * bar / (2 * E * A * sin_a ** 2)
    for k, theta in enumerate((0.0, 0.4, 2.3)):
        run = run_deck(f"truss_v{k}", v_truss(theta, a, h, p)).ok()
        inc = run.listing.increments[-1]
        u = inc.block("NODE U", set="APEX")
        expect = (delta * math.sin(theta), -delta * math.cos(theta))
        err = max(abs(u["U1"][0] - expect[0]), abs(u["U2"][0] - expect[1])) / delta
        assert err < 1e-12, (theta, u["U1"], u["U2"], expect)
        s11 = inc.block("ELEMENT S", set="BARS")["S11"]
        assert max(abs(x + p / (2 * sin_a * A)) for x in s11) < 1e-12 * p / A, (theta, s11)


def block_with_truss(nu, delta=1e-3, nx=4, width=3.0, height=1.0, thick=0.5):
    """A CPS4 strip [0, width] x [0, height] of thickness `thick`, trusses of
    area A along its bottom edge node to node; the left edge held along x
    (node 1 also along y), the right edge moved by delta."""
    nodes, ids, quads = grid(nx, 1, 0.0, width, 0.0, height)
    bottom = [ids[i, 0] for i in range(nx + 1)]
    trusses = "".join(f"{100 + i}, {bottom[i]}, {bottom[i + 1]}\n" for i in range(nx))
    left = [ids[0, j] for j in range(2)]
    right = [ids[nx, j] for j in range(2)]
    return f"""*NODE, NSET=ALLN
{node_lines(nodes)}*ELEMENT, TYPE=CPS4, ELSET=STRIP
{quad_lines(quads)}*ELEMENT, TYPE=T2D2, ELSET=TIES
{trusses}*NSET, NSET=LEFT
{", ".join(map(str, left))}
*NSET, NSET=RIGHT
{", ".join(map(str, right))}
*MATERIAL, NAME=M
*ELASTIC
{E}, {nu}
*SOLID SECTION, ELSET=STRIP, MATERIAL=M
{thick}
*SOLID SECTION, ELSET=TIES, MATERIAL=M
{A}
*BOUNDARY
LEFT, 1, 1
{left[0]}, 2, 2
*STEP
*STATIC
*BOUNDARY
RIGHT, 1, 1, {delta}
*NODE PRINT, NSET=ALLN
U
*EL PRINT, ELSET=TIES
S
*END STEP
"""


def test_truss_in_parallel_with_a_block():
    """The uniform stretch u = delta x / width (v = -nu delta y / width) is
    exact for the strip and leaves the bottom edge straight: the reaction
    on the moved edge is (E t h + E A) delta / width, the trusses' stress
    E delta / width."""
    delta, width, height, thick = 1e-3, 3.0, 1.0, 0.5
    run = run_deck("truss_parallel", block_with_truss(0.3, delta, 4, width, height, thick)).ok()
    inc = run.listing.increments[-1]
    rf = inc.block("REACTIONS").as_dict()["RIGHT"]
    expect = (E * thick * height + E * A) * delta / width
    assert rel_err(rf[0], expect) < 1e-12, (rf, expect)
    s11 = inc.block("ELEMENT S", set="TIES")["S11"]
    assert max(abs(x - E * delta / width) for x in s11) < 1e-12 * E * delta / width, s11
    u = inc.block("NODE U", set="ALLN")
    nodes = grid(4, 1, 0.0, width, 0.0, height)[0]
    for k, nid in enumerate(u["node"]):
        x, y = nodes[int(nid)]
        assert abs(u["U1"][k] - delta * x / width) < 1e-12 * delta, (nid, u["U1"][k])
        assert abs(u["U2"][k] + 0.3 * delta * y / width) < 1e-12 * delta, (nid, u["U2"][k])


def test_heated_bar_held_at_both_ends():
    """alpha dT in a bar held at both ends: S11 = -E alpha dT, and the
    support pushes the far end back with E A alpha dT (RF1 = -E A alpha
    dT); held at one end only, the bar grows by alpha dT L."""
    alpha, dt = 1.2e-5, 80.0
    temps = f"*INITIAL CONDITIONS, TYPE=TEMPERATURE\nALLN, 20.\n"
    heat = f"*TEMPERATURE\nALLN, {20.0 + dt}\n"
    free = bar_deck(extra_model=f"*EXPANSION\n{alpha}\n", load="2, 1, 0.", step_extra=heat)
    free = free.replace("*BOUNDARY\n", temps + "*BOUNDARY\n", 1)
    run = run_deck("truss_heat_free", free).ok()
    u = run.listing.increments[-1].block("NODE U", set="TIP")
    assert rel_err(u["U1"][0], alpha * dt * L) < 1e-12, u["U1"]
    held = free.replace("ALLN, 2, 2\n", "ALLN, 2, 2\n2, 1, 1\n").replace("*NODE PRINT, NSET=TIP\nU",
                                                                      "*NODE PRINT, NSET=TIP\nRF")
    run = run_deck("truss_heat_held", held).ok()
    inc = run.listing.increments[-1]
    assert rel_err(inc.block("ELEMENT S", set="BAR")["S11"][0], -E * alpha * dt) < 1e-12
    assert rel_err(inc.block("NODE RF", set="TIP")["RF1"][0], -E * A * alpha * dt) < 1e-12


def test_writers_with_trusses():
    """The gmsh file and the VTU files show the trusses (a line cell of
    their two nodes, its element stress S11 the listing's) beside the
    continuum elements, and leave out plain line elements (boundaries)."""
    deck = block_with_truss(0.3).replace("*NODE PRINT, NSET=ALLN\nU\n",
                                         "*NODE FILE, FORMAT=VTU\nU, RF, S\n*EL FILE\nS\n")
    deck = deck.replace("*NSET, NSET=LEFT", "*ELEMENT, TYPE=T2D2, ELSET=EDGE\n200, 6, 7\n*NSET, NSET=LEFT")
    run = run_deck("truss_writers", deck).ok()
    out = os.path.dirname(run.listing_path)
    files = os.listdir(out)
    assert any(f.endswith(".msh") for f in files) and any(f.endswith(".vtu") for f in files), files
    from gmsh_results import read_msh
    msh = read_msh(run.listing_path[:-4] + ".msh")
    lines = [(i, c) for i, c, t in zip(msh.element_ids, msh.elements, msh.element_types) if t == 1]
    assert 200 not in msh.element_ids, "a line element without a section is not drawn"
    truss_ids = [i for i, _ in lines]
    assert truss_ids, msh.element_types
    s11 = run.listing.increments[-1].block("ELEMENT S")
    listed = {int(e): s for e, s in zip(s11["element"], s11["S11"])}
    _, ids, vals = msh.views["S11 (element)"][-1]
    for i in truss_ids:
        assert abs(vals[list(ids).index(i)][0] - listed[i]) <= 1e-9 * abs(listed[i]), (i, listed[i])
    import meshio
    vtu = sorted(f for f in files if f.endswith(".vtu"))[-1]
    mesh = meshio.read(os.path.join(out, vtu))
    assert sum(len(b.data) for b in mesh.cells if b.type == "line") == len(truss_ids), mesh.cells


def test_truss_errors_name_the_line():
    """A truss section without its area line, NODAL THICKNESS on a truss, a
    truss of zero length, a 3-node truss whose middle node is not between
    the quarter points of its ends (on an end, beyond it, on the quarter
    point), a truss in an axisymmetric model; a curved 3-node truss (its
    middle node off the line of its ends) and one whose middle node is
    just inside the quarter point run."""
    good = bar_deck()
    cases = [
        ("noarea", good.replace(f"MATERIAL=M\n{A}\n", "MATERIAL=M\n"), "*SOLID SECTION", "cross-sectional area"),
        ("nodal", good.replace("MATERIAL=M\n", "MATERIAL=M, NODAL THICKNESS\n", 1).replace(
            "*BOUNDARY", "*NODAL THICKNESS\nALLN, 0.1\n*BOUNDARY", 1), "*SOLID SECTION", "NODAL THICKNESS is for"),
        ("zero", good.replace(f"2, {L}, 0.", "2, 0., 0."), "1, 1, 2", "both ends at the same point"),
    ]
    # the middle node of a 3-node truss onto an end, or beyond the quarter
    # point: the arc turns back (|dx/ds| stays positive, a stiffness was
    # computed as if the bar were longer)
    three = bar_deck("T2D3")
    for tag, mid in (("folded_end", f"3, {L}, 0."), ("folded_out", f"3, {3 * L}, 0."),
                     ("folded_quarter", f"3, {L / 4}, 0.")):
        cases.append((tag, three.replace(f"3, {L / 2}, 0.", mid), "1, 1, 3, 2", "folds back on itself"))
    axi = good.replace("*MATERIAL", "*ELEMENT, TYPE=CAX4, ELSET=RING\n5, 10, 11, 12, 13\n*MATERIAL").replace(
        "*NODE, NSET=ALLN\n", "*NODE, NSET=ALLN\n10, 1., 1.\n11, 2., 1.\n12, 2., 2.\n13, 1., 2.\n").replace(
        "*BOUNDARY", "*SOLID SECTION, ELSET=RING, MATERIAL=M\n*BOUNDARY", 1)
    cases.append(("axi", axi, "1, 1, 2", "axisymmetric model"))
    for tag, deck, line_text, fragment in cases:
        run = run_deck("truss_err_" + tag, deck)
        line = next(k for k, t in enumerate(deck.splitlines(), 1) if t.startswith(line_text))
        assert run.rc == 1 and f"truss_err_{tag}.inp:{line}: error:" in run.stderr, (tag, run.stderr)
        assert fragment in run.stderr, (tag, run.stderr)
    for tag, mid in (("curved", f"3, {L / 2}, {L}"), ("near_quarter", f"3, {0.26 * L}, 0.")):
        run_deck("truss_ok_" + tag, bar_deck("T2D3").replace(f"3, {L / 2}, 0.", mid)).ok()


def test_three_node_truss_in_the_files_ends_first():
    """A 3-node truss (listed end, middle, end in the deck) is written to
    gmsh (type 8) and VTK (quadratic edge) with its ends first and the
    middle node last, the order those formats expect."""
    deck = bar_deck("T3D3", step_extra="*NODE FILE, FORMAT=VTU\nU\n*NODE FILE\nU\n")
    run = run_deck("truss_bar_t3d3_files", deck).ok()
    from gmsh_results import read_msh
    msh = read_msh(run.listing_path[:-4] + ".msh")
    assert msh.element_types == [8] and msh.elements == [[1, 2, 3]], (msh.element_types, msh.elements)
    import meshio
    out = os.path.dirname(run.listing_path)
    vtu = sorted(f for f in os.listdir(out) if f.endswith(".vtu"))[-1]
    mesh = meshio.read(os.path.join(out, vtu))
    (block,) = mesh.cells
    # points count from 0 in node order 1, 2, 3
    assert block.type == "line3" and block.data.tolist() == [[0, 1, 2]], (block.type, block.data)


def test_truss_under_its_own_weight_and_spinning():
    """Body forces on trusses (over length times area): a bar along x held
    at node 1 under GRAV along +x has the tip displacement rho g L^2 / (2 E)
    and the reaction -rho g A L; spun about a z axis through node 1
    (CENTRIF omega^2) its tip moves rho omega^2 L^3 / (3 E). Linear
    elements in 1D are exact at the nodes for consistent loads, so both the
    2- and the 3-node truss give the closed form to round-off. A pressure
    on a truss is an error at its line."""
    rho, g, w2 = 7.8e-9, 9810.0, 1.0e6
    for etype in ("T2D2", "T3D3"):
        for label, load, tip in (("GRAV", f"BAR, GRAV, {g}, 1., 0., 0.", rho * g * L * L / (2 * E)),
                                 ("CENTRIF", f"BAR, CENTRIF, {w2}, 0., 0., 0., 0., 0., 1.", rho * w2 * L ** 3 / (3 * E))):
            deck = bar_deck(etype, extra_model=f"*DENSITY\n{rho}\n", load="2, 1, 0.").replace(
                "*CLOAD\n2, 1, 0.\n", f"*DLOAD\n{load}\n").replace("*NODE PRINT, NSET=TIP\nU",
                                                                  "*NODE PRINT, NSET=TIP\nU\n*NODE PRINT, NSET=ALLN\nRF")
            inc = run_deck(f"truss_{label.lower()}_{etype}", deck).ok().listing.increments[-1]
            u = inc.block("NODE U", set="TIP")["U1"][0]
            assert rel_err(u, tip) < 1e-12, (etype, label, u, tip)
            if label == "GRAV":
                rf = sum(inc.block("NODE RF", set="ALLN")["RF1"])
                assert rel_err(rf, -rho * g * A * L) < 1e-12, (etype, rf)
    deck = bar_deck().replace("*CLOAD\n2, 1, 7.0\n", "*DLOAD\nBAR, P1, 5.\n")
    run = run_deck("truss_pressure", deck)
    line = deck.splitlines().index("BAR, P1, 5.") + 1
    assert run.rc == 1 and f"truss_pressure.inp:{line}: error:" in run.stderr and "not pressures" in run.stderr, \
        run.stderr


def test_section_of_continuum_and_lines_warns():
    """A section naming a set of plane elements and line elements alike
    (gmsh's boundary lines in an everything set) makes the lines trusses of
    the thickness as area, as CalculiX does; cfe2d says so at the
    section's line and runs."""
    deck = f"""*NODE, NSET=ALLN
1, 0., 0.
2, 1., 0.
3, 1., 1.
4, 0., 1.
*ELEMENT, TYPE=CPS4, ELSET=ALL
1, 1, 2, 3, 4
*ELEMENT, TYPE=T2D2, ELSET=ALL
2, 2, 3
*MATERIAL, NAME=M
*ELASTIC
{E}, 0.
*SOLID SECTION, ELSET=ALL, MATERIAL=M
0.5
*BOUNDARY
1, 1, 2
4, 1
*STEP
*STATIC
*CLOAD
3, 2, 10.
*NODE PRINT, NSET=ALLN
U
*END STEP
"""
    run = run_deck("truss_mixed_section", deck).ok()
    line = deck.splitlines().index("*SOLID SECTION, ELSET=ALL, MATERIAL=M") + 1
    assert f"truss_mixed_section.inp:{line}: warning: this section names 1 continuum elements and 1 line" in \
        run.stderr, run.stderr
