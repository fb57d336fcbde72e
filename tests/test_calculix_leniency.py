"""What CalculiX accepts and cfe2d used to refuse (issue 20): an empty
*NODE block and an empty *SURFACE (cgx writes both for a set without
nodes or faces of its own), nodes that belong to no element (left over
from meshing), CENTRIF about an axis in the plane of plane elements; and
the message for CalculiX's temperature dof 11. Each is accepted with a
warning at its line, or refused with an error naming the line."""
import os

from helpers import rel_err, run_deck

BAR = """*HEADING
two-element bar
*NODE, NSET=ALLN
1, 0, 0
2, 1, 0
3, 2, 0
4, 0, 1
5, 1, 1
6, 2, 1
*ELEMENT, TYPE=CPS4, ELSET=BAR
1, 1, 2, 5, 4
2, 2, 3, 6, 5
*NSET, NSET=LEFT
1, 4
*MATERIAL, NAME=STEEL
*ELASTIC
1000., 0.25
*SOLID SECTION, ELSET=BAR, MATERIAL=STEEL
1.
*BOUNDARY
LEFT, 1, 2
*STEP
*STATIC
*CLOAD
3, 1, 5.
*NODE PRINT, NSET=ALLN
U, RF
*END STEP
"""


def replace(old, new, deck=BAR):
    assert old in deck, old
    return deck.replace(old, new, 1)


def line_of(text, fragment):
    for k, line in enumerate(text.splitlines(), 1):
        if fragment in line:
            return k
    raise AssertionError(fragment)


def displacements(run, nset="ALLN"):
    u = run.listing.increments[-1].block("NODE U", set=nset)
    return {int(n): (a, b) for n, a, b in zip(u["node"], u["U1"], u["U2"])}


def same_answer(run, plain):
    """run's displacements of the bar's nodes are plain's, to the bit."""
    got, want = displacements(run), displacements(plain)
    for node in range(1, 7):
        assert got[node] == want[node], (node, got[node], want[node])


def test_empty_node_block_warns():
    """*NODE without data lines (cgx writes `*NODE, NSET=N` for a set with
    no nodes of its own) defines nothing: a warning at its line, in the
    deck or in an included file; its node set exists, empty (a card naming
    it warns as for any empty set), and the answer is the bar's."""
    mesh = "** written by cgx\n*NODE, NSET=NONE\n"
    deck = replace("*ELEMENT", "*NODE\n*INCLUDE, INPUT=empty_nodes.inp\n*ELEMENT")
    deck = replace("*END STEP", "*NODE PRINT, NSET=NONE\nU\n*END STEP", deck)
    run = run_deck("empty_node_block", deck, files={"empty_nodes.inp": mesh}).ok()
    inc = os.path.join(os.path.dirname(run.deck), "empty_nodes.inp")
    assert f"{run.deck}:{deck.splitlines().index('*NODE') + 1}: warning: *NODE without data lines defines " \
           "no node\n" in run.stderr, run.stderr
    assert f"{inc}:2: warning: *NODE without data lines defines no node (node set NONE gets none)" in run.stderr, \
        run.stderr
    assert f"{run.deck}:{line_of(deck, '*NODE PRINT, NSET=NONE')}: warning: node set NONE is empty" in run.stderr
    assert "error" not in run.stderr, run.stderr
    same_answer(run, run_deck("empty_node_block_plain", BAR).ok())


def test_empty_surface_warns():
    """A *SURFACE without data lines (cgx's .sur file of a set without
    faces) is an empty surface: a warning at its line in the included
    file, element and node surfaces alike. Unused, it changes nothing;
    used by a *CONTACT PAIR (as slave or master) or a *DSLOAD, each use
    warns at its own line as for any empty surface, and the run goes on
    with the answer of the bar."""
    sur = "** written by cgx\n*SURFACE, NAME=SEMPTY, TYPE=ELEMENT\n*SURFACE, NAME=NEMPTY, TYPE=NODE\n" \
          "*SURFACE, NAME=UNUSED\n"
    deck = replace("*NSET, NSET=LEFT", "*INCLUDE, INPUT=empty.sur\n*SURFACE, NAME=RIGHT\nBAR, S2\n"
                   "*NSET, NSET=LEFT")
    plain = run_deck("empty_surface_plain", deck, files={"empty.sur": sur}).ok()
    inc = os.path.join(os.path.dirname(plain.deck), "empty.sur")
    for k, name in ((2, "SEMPTY"), (3, "NEMPTY"), (4, "UNUSED")):
        message = f"{inc}:{k}: warning: *SURFACE without data lines: surface {name} is empty"
        assert plain.stderr.count(message) == 1, plain.stderr
    assert "error" not in plain.stderr, plain.stderr
    same_answer(plain, run_deck("empty_surface_bar", BAR).ok())

    used = replace("*BOUNDARY", "*CONTACT PAIR\nSEMPTY, RIGHT\nNEMPTY, RIGHT\nRIGHT, SEMPTY\n*BOUNDARY", deck)
    used = replace("*NODE PRINT", "*DSLOAD\nSEMPTY, P, 3.\n*NODE PRINT", used)
    run = run_deck("empty_surface_used", used, files={"empty.sur": sur}).ok()
    for text, what, card in (("SEMPTY, RIGHT", "SEMPTY", "*CONTACT PAIR"), ("NEMPTY, RIGHT", "NEMPTY", "*CONTACT PAIR"),
                             ("RIGHT, SEMPTY", "SEMPTY", "*CONTACT PAIR"), ("SEMPTY, P, 3.", "SEMPTY", "*DSLOAD")):
        message = f"{run.deck}:{line_of(used, text)}: warning: surface {what} is empty: {card} does nothing for it"
        assert message in run.stderr, (message, run.stderr)
    same_answer(run, plain)


def test_temperature_dof_says_it_belongs_to_heat_transfer():
    """CalculiX's dof 11 is the temperature: a *BOUNDARY on it (a
    prescribed temperature) or a *CLOAD on it (a heat flux) in a static
    step belongs to a *HEAT TRANSFER step. The error names the line and
    says so, instead of the generic message about dofs 1 and 2."""
    cases = [("bc_dof11", replace("LEFT, 1, 2", "LEFT, 1, 2\nLEFT, 11, 11, 293."), "LEFT, 11, 11, 293.",
              "*BOUNDARY on it is a prescribed temperature"),
             ("bc_dof11_alone", replace("LEFT, 1, 2", "LEFT, 1, 2\n4, 11"), "4, 11",
              "*BOUNDARY on it is a prescribed temperature"),
             ("cload_dof11", replace("3, 1, 5.", "3, 11, 5."), "3, 11, 5.",
              "*CLOAD on it is a concentrated heat flux")]
    for name, deck, text, fragment in cases:
        run = run_deck(name, deck)
        assert run.rc == 1, (name, run.stderr)
        assert f"{run.deck}:{line_of(deck, text)}: error: dof 11 is the temperature" in run.stderr, run.stderr
        assert fragment in run.stderr and "it belongs to a *HEAT TRANSFER step" in run.stderr, run.stderr
        assert "dofs must satisfy" not in run.stderr and "dof must be 1 or 2" not in run.stderr, run.stderr
    # other dofs keep the generic message
    run = run_deck("bc_dof7", replace("LEFT, 1, 2", "LEFT, 7, 7"))
    assert run.rc == 1 and "dofs must satisfy" in run.stderr, run.stderr


# A slender bar 0 <= x <= L, 0 <= y <= H of thickness T (plane stress,
# nu = 0) spinning about an axis along y through (X0, Y0, 0): CENTRIF
# about an axis in the plane, as for a blade on a hub of radius -X0.
RL, RH, RT, RE, RHO, W2 = 10.0, 0.5, 2.0, 2.0e5, 7.8e-9, 1.0e6


def rotating_bar_exact(x, x0):
    """The body force rho omega^2 (x - x0) along x only (the distance from
    the axis, perpendicular to it, lies along x), the root x = 0 held
    axially, the tip free: with nu = 0 the plane-stress solution is the
    1D one, u_y = 0 and sigma_xx(x) = N / A with
        sigma(x) = c [(L^2 - x^2) / 2 - x0 (L - x)],   c = rho omega^2,
        u(x)     = c / E [(L^2 x - x^3 / 3) / 2 - x0 (L x - x^2 / 2)]
    (sigma(x) = rho omega^2 (L^2 - x^2) / 2 for an axis through the root)."""
    c = RHO * W2
    return c * ((RL ** 2 - x ** 2) / 2 - x0 * (RL - x)), c / RE * ((RL ** 2 * x - x ** 3 / 3) / 2 - x0 * (RL * x - x ** 2 / 2))


def rotating_bar_deck(shape, nx, ny, centrif, element=None):
    from quadmesh import Mesh, etype
    m = Mesh(shape, nx, ny, lambda s, t: (s * RL / nx, t * RH / ny))
    left = m.side("left")
    return m, f"""*NODE, NSET=ALLN
{m.node_lines()}{m.element_card(element or etype(shape, 'S'), 'BAR')}*NSET, NSET=ROOT
{", ".join(map(str, left))}
*MATERIAL, NAME=STEEL
*ELASTIC
{RE}, 0.
*DENSITY
{RHO}
*SOLID SECTION, ELSET=BAR, MATERIAL=STEEL
{RT}
*BOUNDARY
ROOT, 1, 1
{left[0]}, 2, 2
*STEP
*STATIC
*DLOAD
BAR, CENTRIF, {W2}, {centrif}
*NODE PRINT, NSET=ALLN
U, S
*NODE PRINT, NSET=ROOT
RF
*END STEP
"""


def test_centrif_about_an_axis_in_the_plane_spins_a_bar():
    """CENTRIF about an axis along y (in the plane of plane-stress
    elements) on a bar along x, against the closed form of
    rotating_bar_exact: an axis through the root and one through a hub
    point (x0 = -2, any y0, its direction given as (0, -2, 0): the length
    and sense of the direction do not matter). The consistent loads are
    exact (a linear body force) and with nu = 0 the 2D problem is the 1D
    one; its Galerkin solution is nodally exact for linear and quadratic
    elements (the cubic u differs from the quadratic interpolant by an odd
    bubble, which vanishes at the middle node): every nodal U1 to 1e-10 of
    the tip's, U2 = 0, the root reactions sum to -rho omega^2 A (L^2/2 -
    x0 L) and carry nothing along y (an axis along y pulls along x only).
    The CPS8 stress is linear in each element, off the exact quadratic by
    the odd bubble's slope, rho omega^2 h^2 / 24 (3 s^2 - 1) at the local
    coordinate s (+1/12 h^2 rho omega^2 at element ends, -1/24 at the
    middle nodes; exact at the 2-point Gauss points): the nodal S11
    (extrapolated, averaged) checked against that to 1e-9 of the root
    stress, S22 and S12 zero."""
    for x0, y0, axis in ((0.0, 0.0, "0., 1., 0."), (-2.0, 5.0, "0., -2., 0.")):
        for shape in ("Q4", "Q8"):
            m, deck = rotating_bar_deck(shape, 10, 2, f"{x0}, {y0}, 0., {axis}")
            run = run_deck(f"centrif_inplane_{shape}_{-x0:g}", deck).ok()
            inc = run.listing.increments[-1]
            u, rf = inc.block("NODE U", set="ALLN"), inc.block("NODE RF", set="ROOT")
            s_root, u_tip = rotating_bar_exact(0.0, x0)[0], rotating_bar_exact(RL, x0)[1]
            for n, u1, u2 in zip(u["node"], u["U1"], u["U2"]):
                want = rotating_bar_exact(m.nodes[int(n)][0], x0)[1]
                assert abs(u1 - want) < 1e-10 * u_tip and abs(u2) < 1e-10 * u_tip, (shape, x0, n, u1, u2, want)
            total = RHO * W2 * RH * RT * (RL ** 2 / 2 - x0 * RL)
            assert rel_err(-sum(rf["RF1"]), total) < 1e-10, (shape, x0, sum(rf["RF1"]), total)
            assert abs(sum(rf["RF2"])) < 1e-10 * total, (shape, x0, sum(rf["RF2"]))
            if shape != "Q8":
                continue
            s = inc.block("NODE S", set="ALLN")
            h = RL / 10
            for n, s11, s22, s12 in zip(s["node"], s["S11"], s["S22"], s["S12"]):
                x = m.nodes[int(n)][0]
                # the local coordinate: +-1 at an element's ends, 0 at its middle
                local = 1.0 if abs(x / h - round(x / h)) < 1e-9 else 0.0
                want = rotating_bar_exact(x, x0)[0] + RHO * W2 * h ** 2 / 24 * (3 * local ** 2 - 1)
                assert abs(s11 - want) < 1e-9 * s_root, (x0, n, s11, want)
                assert abs(s22) < 1e-9 * s_root and abs(s12) < 1e-9 * s_root, (x0, n, s22, s12)


def test_centrif_about_an_axis_in_the_plane_on_trusses_and_masses():
    """Trusses and point masses take CENTRIF about an in-plane axis too: a
    chain of T2D2 (and of T3D3) along x at height 1, spinning about the y
    axis through (x0, 0, 0), with a MASS at its tip: the distributed load
    rho A omega^2 (x - x0) along x plus the tip force M omega^2 (L - x0),
    so u(x) = rotating_bar_exact's u + M omega^2 (L - x0) x / (E A) at
    every node (1D Galerkin solutions are nodally exact); the transverse
    supports carry nothing (a normal axis would pull them along y)."""
    area, mass, x0, n = 3.0, 2.0e-4, -1.5, 8
    for etype_, per in (("T2D2", 1), ("T3D3", 2)):
        h = RL / (n * per)
        nodes = "".join(f"{k + 1}, {k * h!r}, 1.\n" for k in range(n * per + 1))
        if per == 1:
            elems = "".join(f"{k + 1}, {k + 1}, {k + 2}\n" for k in range(n))
        else:
            elems = "".join(f"{k + 1}, {2 * k + 1}, {2 * k + 2}, {2 * k + 3}\n" for k in range(n))
        tip = n * per + 1
        deck = f"""*NODE, NSET=ALLN
{nodes}*ELEMENT, TYPE={etype_}, ELSET=BAR
{elems}*ELEMENT, TYPE=MASS, ELSET=TIPMASS
{n + 1}, {tip}
*MATERIAL, NAME=STEEL
*ELASTIC
{RE}, 0.
*DENSITY
{RHO}
*SOLID SECTION, ELSET=BAR, MATERIAL=STEEL
{area}
*MASS, ELSET=TIPMASS
{mass}
*BOUNDARY
1, 1, 1
ALLN, 2, 2
*STEP
*STATIC
*DLOAD
BAR, CENTRIF, {W2}, {x0}, 0., 0., 0., 1., 0.
TIPMASS, CENTRIF, {W2}, {x0}, 0., 0., 0., 1., 0.
*NODE PRINT, NSET=ALLN
U, RF
*END STEP
"""
        run = run_deck(f"centrif_inplane_{etype_}", deck).ok()
        inc = run.listing.increments[-1]
        u, rf = inc.block("NODE U", set="ALLN"), inc.block("NODE RF", set="ALLN")
        tip_force = mass * W2 * (RL - x0)
        u_tip = rotating_bar_exact(RL, x0)[1] + tip_force * RL / (RE * area)
        for node, u1 in zip(u["node"], u["U1"]):
            x = (int(node) - 1) * h
            want = rotating_bar_exact(x, x0)[1] + tip_force * x / (RE * area)
            assert abs(u1 - want) < 1e-10 * u_tip, (etype_, node, u1, want)
        total = RHO * W2 * area * (RL ** 2 / 2 - x0 * RL) + tip_force
        assert rel_err(-sum(rf["RF1"]), total) < 1e-10, (etype_, sum(rf["RF1"]), total)
        assert max(abs(rf["RF2"])) < 1e-12 * total, (etype_, rf["RF2"])


def test_centrif_about_a_tilted_axis_is_an_error():
    """About an axis neither normal to the plane nor in it, or along the
    plane but off it (z0 not 0), the centrifugal load has an out-of-plane
    part, which a plane element cannot carry: an error at the *DLOAD
    line, saying why. Axisymmetric elements keep their own rule (the y
    axis only)."""
    cases = [("tilted", "0., 0., 0., 0., 1., 1.", "about a tilted axis the centrifugal load has an out-of-plane part"),
             ("off_plane", "0., 0., 0.5, 0., 1., 0.", "lies along the x-y plane but off it")]
    for name, centrif, fragment in cases:
        _, deck = rotating_bar_deck("Q4", 4, 1, centrif)
        run = run_deck(f"centrif_{name}", deck)
        line = line_of(deck, "BAR, CENTRIF")
        assert run.rc == 1 and f"{run.deck}:{line}: error:" in run.stderr, (name, run.stderr)
        assert fragment in run.stderr, (name, run.stderr)
    _, deck = rotating_bar_deck("Q4", 4, 1, "0., 0., 0., 1., 0., 0.", element="CAX4")
    run = run_deck("centrif_axi_x_axis", deck)
    assert run.rc == 1 and "must be its symmetry axis, the y axis" in run.stderr, run.stderr


def test_nodes_of_no_element_are_left_out():
    """Nodes no element uses (gmsh writes its geometry points, the centre
    of an arc, ...) are left out of the analysis, where they stopped it
    with 'singular stiffness' without a line: one warning at the data line
    of the first, counting them and naming five; they show zero
    displacement and no reaction, a *BOUNDARY on them is ignored (a node
    set of the mesher may hold them), and the bar's answer is unchanged.
    A zero *CLOAD on one loses nothing and passes."""
    extra = "".join(f"{n}, {n}., 7.\n" for n in range(14, 21))
    deck = replace("6, 2, 1\n", "6, 2, 1\n" + extra)
    deck = replace("LEFT, 1, 2\n", "LEFT, 1, 2\n*NSET, NSET=SOME\n4, 15, 16\n*BOUNDARY\nSOME, 1, 2, 0.25\n", deck)
    deck = replace("3, 1, 5.\n", "3, 1, 5.\nSOME, 2, 0.\n", deck)
    run = run_deck("unused_nodes", deck).ok()
    warnings = [line for line in run.stderr.splitlines() if "warning" in line]
    assert warnings == [f"{run.deck}:{line_of(deck, '14, 14., 7.')}: warning: 7 nodes belong to no element with "
                        "stiffness or mass, contact surface or *EQUATION (left over from meshing?): 14, 15, 16, 17, "
                        "18 and 2 more; they are left out of the analysis, with zero displacement in the outputs (a "
                        "*BOUNDARY there is ignored)"], run.stderr
    u = displacements(run)
    rf = run.listing.increments[-1].block("NODE RF", set="ALLN")
    for node in range(14, 21):
        assert u[node] == (0.0, 0.0), (node, u[node])
    for node, r1, r2 in zip(rf["node"], rf["RF1"], rf["RF2"]):
        if int(node) >= 14:
            assert r1 == 0.0 and r2 == 0.0, (node, r1, r2)
    plain = run_deck("unused_nodes_plain", replace("LEFT, 1, 2\n", "LEFT, 1, 2\n4, 1, 2, 0.25\n")).ok()
    same_answer(run, plain)


def test_load_on_a_node_of_no_element_is_an_error():
    """A *CLOAD on a node that is left out would be lost: an error at the
    *CLOAD line naming the node (also through a node set). A node of only a
    truss, a spring or a point mass is not left out: trusses and springs
    carry a load at their nodes, and a point mass's node without support
    has no stiffness (the run stops naming it, as before)."""
    deck = replace("6, 2, 1\n", "6, 2, 1\n7, 3., 3.\n")
    for name, cload in (("node", "7, 2, 1.5"), ("set", "ALLN, 1, 2.")):
        bad = replace("3, 1, 5.\n", f"3, 1, 5.\n{cload}\n", deck)
        run = run_deck(f"unused_node_cload_{name}", bad)
        assert run.rc == 1, run.stderr
        assert f"{run.deck}:{line_of(bad, cload)}: error: node 7 is left out of the analysis (it belongs to no " \
               "element with stiffness or mass, contact surface or *EQUATION): this *CLOAD on it would be lost" \
               in run.stderr, run.stderr
    # a truss from node 3 to node 21 and a spring between node 6 and node 22
    # (held along y) carry their nodes' loads: no warning, and the pull at
    # node 22 reaches the bar through the spring
    attached = replace("6, 2, 1\n", "6, 2, 1\n21, 3., 0.\n22, 3., 1.\n")
    attached = replace("*NSET, NSET=LEFT", "*ELEMENT, TYPE=T2D2, ELSET=TRUSS\n3, 3, 21\n"
                       "*ELEMENT, TYPE=SPRING2, ELSET=SPR\n4, 6, 22\n*NSET, NSET=LEFT", attached)
    attached = replace("*BOUNDARY", "*SOLID SECTION, ELSET=TRUSS, MATERIAL=STEEL\n0.5\n*SPRING, ELSET=SPR\n1, 1\n"
                       "400.\n*BOUNDARY\n21, 2\n22, 2\n", attached)
    attached = replace("3, 1, 5.\n", "3, 1, 5.\n21, 1, 1.\n22, 1, 2.\n", attached)
    run = run_deck("attached_nodes", attached).ok()
    assert "warning" not in run.stderr, run.stderr
    rf = run.listing.increments[-1].block("NODE RF", set="ALLN")
    assert abs(sum(rf["RF1"]) + 8.0) < 1e-9, sum(rf["RF1"])
    massed = replace("*NSET, NSET=LEFT", "*ELEMENT, TYPE=MASS, ELSET=MA\n5, 7\n*NSET, NSET=LEFT", deck)
    massed = replace("*BOUNDARY", "*MASS, ELSET=MA\n1.\n*BOUNDARY", massed)
    run = run_deck("mass_node_unsupported", massed)
    assert run.rc == 1 and "singular stiffness at node 7, dof 1" in run.stderr, run.stderr
    assert "left out" not in run.stderr, run.stderr
