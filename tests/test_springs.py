"""Linear springs (*ELEMENT, TYPE=SPRING1 / SPRING2 / SPRINGA with *SPRING)
against closed forms: a node held by grounded springs, a spring along an
inclined line at any angle, springs in series with a block and with a
truss, a spring between two different dofs; the errors, each at its
line."""
import math

from decks import grid, node_lines, quad_lines
from helpers import rel_err, run_deck

K1, K2 = 40.0, 250.0


def grounded(fx=3.0, fy=-2.0, dof_line_x="1", extra_spring=""):
    """Node 1 held by two SPRING1: K1 along x, K2 along y."""
    return f"""*NODE, NSET=ALLN
1, 0.5, 0.5
*ELEMENT, TYPE=SPRING1, ELSET=SX
1, 1
*ELEMENT, TYPE=SPRING1, ELSET=SY
2, 1
*SPRING, ELSET=SX
{dof_line_x}
{K1}
*SPRING, ELSET=SY
2
{K2}
{extra_spring}*STEP
*STATIC
*CLOAD
1, 1, {fx}
1, 2, {fy}
*NODE PRINT
U
*END STEP
"""


def test_grounded_node():
    """u = F / k in each direction: a model of springs only runs."""
    run = run_deck("spring_grounded", grounded()).ok()
    u = run.listing.increments[-1].block("NODE U", set="ALL")
    assert rel_err(u["U1"][0], 3.0 / K1) < 1e-12 and rel_err(u["U2"][0], -2.0 / K2) < 1e-12, (u["U1"], u["U2"])


def v_springs(theta, a=1.5, h=2.0, p=5.0):
    """Two SPRINGA from (-a, 0) and (a, 0) to the apex (0, h), a load p
    towards the supports; all turned by theta."""
    c, s = math.cos(theta), math.sin(theta)
    rot = lambda x, y: (c * x - s * y, s * x + c * y)  # noqa: E731
    pts = {1: rot(-a, 0.0), 2: rot(a, 0.0), 3: rot(0.0, h)}
    load = rot(0.0, -p)
    return f"""*NODE, NSET=ALLN
{node_lines(pts)}*ELEMENT, TYPE=SPRINGA, ELSET=SPRINGS
1, 1, 3
2, 2, 3
*NSET, NSET=APEX
3
*SPRING, ELSET=SPRINGS

{K1}
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
*END STEP
"""


def test_axial_springs_at_any_angle():
    """Each SPRINGA acts along the line between its nodes: the apex moves
    p / (2 k sin^2 alpha) towards the supports, turned with the model."""
    a, h, p = 1.5, 2.0, 5.0
    sin_a = h / math.hypot(a, h)
    delta = p / (2 * K1 * sin_a ** 2)
    for k, theta in enumerate((0.0, 1.1, -2.7)):
        run = run_deck(f"spring_v{k}", v_springs(theta, a, h, p)).ok()
        u = run.listing.increments[-1].block("NODE U", set="APEX")
        expect = (delta * math.sin(theta), -delta * math.cos(theta))
        err = max(abs(u["U1"][0] - expect[0]), abs(u["U2"][0] - expect[1])) / delta
        assert err < 1e-12, (theta, u["U1"], u["U2"], expect)


def test_springs_in_series_with_a_block_and_a_truss():
    """A CPS4 strip (length 3, height 1, thickness 0.5, nu = 0) pulled at
    its right edge through two SPRINGA (one per edge node, each carrying
    F / 2), and a truss hung after the upper spring's far node carrying
    its own end load: the loaded node moves F L / (E t h) + F / (2 k) and
    the truss's end further by Ft Lt / (E A)."""
    e, width, height, thick, force, area, lt, ft = 1000.0, 3.0, 1.0, 0.5, 6.0, 0.2, 2.0, 1.5
    nodes, ids, quads = grid(3, 1, 0.0, width, 0.0, height)
    nodes.update({101: (width + 1.0, 0.0), 102: (width + 1.0, height), 103: (width + 1.0 + lt, height)})
    deck = f"""*NODE, NSET=ALLN
{node_lines(nodes)}*ELEMENT, TYPE=CPS4, ELSET=STRIP
{quad_lines(quads)}*ELEMENT, TYPE=SPRINGA, ELSET=SPRINGS
11, {ids[3, 0]}, 101
12, {ids[3, 1]}, 102
*ELEMENT, TYPE=T2D2, ELSET=BAR
13, 102, 103
*NSET, NSET=LEFT
{ids[0, 0]}, {ids[0, 1]}
*NSET, NSET=FAR
101, 102, 103
*MATERIAL, NAME=M
*ELASTIC
{e}, 0.
*SOLID SECTION, ELSET=STRIP, MATERIAL=M
{thick}
*SOLID SECTION, ELSET=BAR, MATERIAL=M
{area}
*SPRING, ELSET=SPRINGS
{K1}
*BOUNDARY
LEFT, 1, 1
{ids[0, 0]}, 2, 2
FAR, 2, 2
*STEP
*STATIC
*CLOAD
101, 1, {force / 2}
102, 1, {force / 2 - ft}
103, 1, {ft}
*NODE PRINT, NSET=FAR
U
*END STEP
"""
    run = run_deck("spring_series", deck).ok()
    u = run.listing.increments[-1].block("NODE U", set="FAR")
    block = force * width / (e * thick * height)
    expect = [block + force / (2 * K1), block + force / (2 * K1), block + force / (2 * K1) + ft * lt / (e * area)]
    for k in range(3):
        assert rel_err(u["U1"][k], expect[k]) < 1e-12, (u["node"], u["U1"], expect)


def test_spring_between_two_dofs():
    """SPRING2 from dof 1 of node 1 to dof 2 of node 2, node 2 held along y
    by a SPRING1 of K2, a force F along x on node 1: the stretch u1x - u2y
    is F / K1 and node 2 moves F / K2 along +y (the spring pulls it)."""
    force = 4.0
    deck = f"""*NODE, NSET=ALLN
1, 0., 0.
2, 1., 1.
*ELEMENT, TYPE=SPRING2, ELSET=LINK
1, 1, 2
*ELEMENT, TYPE=SPRING1, ELSET=GROUND
2, 2
*SPRING, ELSET=LINK
1, 2
{K1}
*SPRING, ELSET=GROUND
2
{K2}
*BOUNDARY
1, 2, 2
2, 1, 1
*STEP
*STATIC
*CLOAD
1, 1, {force}
*NODE PRINT
U
*END STEP
"""
    run = run_deck("spring_dofs", deck).ok()
    u = run.listing.increments[-1].block("NODE U", set="ALL")
    assert rel_err(u["U2"][1], force / K2) < 1e-12, u["U2"]
    assert rel_err(u["U1"][0], force / K1 + force / K2) < 1e-12, u["U1"]


def test_spring_errors_name_the_line():
    good = grounded()
    nospring = good.replace("*SPRING, ELSET=SY\n2\n" + f"{K2}\n", "")
    cases = [
        ("nonlinear", good.replace("*SPRING, ELSET=SX", "*SPRING, ELSET=SX, NONLINEAR"), "*SPRING, ELSET=SX, NONLINEAR",
         "NONLINEAR springs"),
        ("orient", good.replace("*SPRING, ELSET=SX", "*SPRING, ELSET=SX, ORIENTATION=OR1"),
         "*SPRING, ELSET=SX, ORIENTATION=OR1",
         "ORIENTATION on *SPRING"),
        ("missing", nospring, "2, 1", "has no *SPRING"),
        ("dof3", grounded(dof_line_x="3"), "3", "dof 3 (out of the plane)"),
        ("dof6", grounded(dof_line_x="6"), "6", "rotations do not exist"),
        ("nodof", good.replace("*SPRING, ELSET=SX\n1\n", "*SPRING, ELSET=SX\n"), f"{K1}", "SPRING1 needs its dof"),
        ("twodofs", grounded(dof_line_x="1, 2"), "1, 2", "SPRING1 needs its dof"),
        ("negative", good.replace(f"\n{K1}\n", f"\n-{K1}\n"), f"-{K1}", "must be positive"),
        ("temperature", good.replace(f"\n{K1}\n", f"\n{K1}, , 20.\n{2 * K1}, , 100.\n"), f"{2 * K1}, , 100.",
         "temperature-dependent"),
        ("mixed", good.replace("*ELEMENT, TYPE=SPRING1, ELSET=SY\n2, 1", "*ELEMENT, TYPE=SPRINGA, ELSET=SX\n2, 1, 3")
         .replace("1, 0.5, 0.5", "1, 0.5, 0.5\n3, 1., 1."), "*SPRING, ELSET=SX", "mixes spring types"),
        ("solid", good.replace("*STEP", "*MATERIAL, NAME=M\n*ELASTIC\n1., 0.\n*SOLID SECTION, ELSET=SX, MATERIAL=M\n"
                                        "*STEP"), "*SOLID SECTION, ELSET=SX, MATERIAL=M", "its constant comes from *SPRING"),
        ("notspring", good.replace("*SPRING, ELSET=SY", "*ELEMENT, TYPE=T2D2, ELSET=BAR\n5, 1, 3\n*SPRING, ELSET=BAR")
         .replace("1, 0.5, 0.5", "1, 0.5, 0.5\n3, 1., 1."), "*SPRING, ELSET=BAR", "not a spring"),
        ("springadof", v_springs(0.0).replace("*SPRING, ELSET=SPRINGS\n\n", "*SPRING, ELSET=SPRINGS\n1\n"), "1",
         "takes no dof line"),
        ("springazero", v_springs(0.0).replace("2, 2, 3\n", "2, 2, 1\n").replace(
            node_lines({2: (1.5, 0.0)}), node_lines({2: (-1.5, 0.0)})), "2, 2, 1", "both ends at the same point"),
    ]
    for tag, deck, line_text, fragment in cases:
        run = run_deck("spring_err_" + tag, deck)
        line = next(k for k, t in enumerate(deck.splitlines(), 1) if t == line_text)
        assert run.rc == 1 and f"spring_err_{tag}.inp:{line}: error:" in run.stderr, (tag, line, run.stderr)
        assert fragment in run.stderr, (tag, run.stderr)


def test_spring_force_and_stretch_as_s11_and_e11():
    """*EL PRINT S, E on springs gives, as Abaqus reports springs, S11 =
    the spring force and E11 = its stretch: a grounded node's springs carry
    the load (3 and -2), the V of SPRINGA the statics of the apex."""
    deck = grounded().replace("*NODE PRINT\nU\n", "*NODE PRINT\nU\n*EL PRINT, ELSET=SX\nS, E\n*EL PRINT, ELSET=SY\nS, E\n")
    inc = run_deck("spring_force_print", deck).ok().listing.increments[-1]
    sx, ex = inc.block("ELEMENT S", set="SX"), inc.block("ELEMENT E", set="SX")
    sy = inc.block("ELEMENT S", set="SY")
    assert rel_err(sx["S11"][0], 3.0) < 1e-12 and rel_err(sy["S11"][0], -2.0) < 1e-12, (sx, sy)
    assert rel_err(ex["E11"][0], 3.0 / K1) < 1e-12, ex
    a, h, p = 1.5, 2.0, 5.0
    deck = v_springs(0.7, a, h, p) + ""
    deck = deck.replace("*END STEP", "*EL PRINT, ELSET=SPRINGS\nS\n*END STEP")
    s = run_deck("spring_force_v", deck).ok().listing.increments[-1].block("ELEMENT S", set="SPRINGS")
    # each leg is compressed by p / (2 cos(beta)), cos(beta) = h / leg
    leg = math.hypot(a, h)
    assert max(rel_err(f, -p * leg / (2 * h)) for f in s["S11"]) < 1e-10, s["S11"]
