"""NLGEOM with contact: the contact is searched and evaluated in the
current configuration in every Newton iteration (equilibrium's
search_in_iteration; docs/nonlinear.md, "Contact under NLGEOM").

The model: a plane-strain elastic block (2 x 2 CPE4, width B, height H)
pressed into a fixed bowl, whose surface is a polygon of straight edges
inscribed in a circle of radius R (vertices every DELTA, the lowest edge
horizontal at y = 0), and slid along it by K edges in ONE increment
(*STATIC, DIRECT): its top is moved rigidly so that its bottom would lie
on the middle of edge K (rotated by theta = K DELTA) and pressed by D
along the edge's normal. The contact is EXACT (Lagrange multipliers), and
frictionless. Closed forms:

(a) every closed slave node lies on the current master polygon: its
    distance to the polygon edge under it is below 1e-8 of the edge length
    (EXACT enforcement leaves the gap at the status search's round-off,
    1e-10 of the mesh length);
(b) the contact forces are normal to edge K, whose normal is the circle's
    normal at the edge's middle, at angle theta: the block's reaction at
    its top is the contact resultant, so atan(RF1 / -RF2) = theta to the
    Newton tolerance (the out-of-balance of the converged increment,
    measured below 1e-9 of the force; tolerance 1e-7 rad). Against the
    circle the direction is exact here because the block sits on the
    middle of one edge; the mesh's own error (the chord's normal against
    the circle's under a point anywhere on the edge) would be up to
    DELTA / 2;
(c) the same answer with 1 and with 10 increments (elastic and
    frictionless: the end state does not depend on the path; nodal
    displacements to 1e-7 of the slide).

With the contact searched once per increment (at its start) the block is
measured against the extension of the lowest edge, the horizontal line
y = 0, which lies below the bowl's surface there (by R (1 - cos theta),
0.15): the coupling elements open, the block sinks by D through the
polygon (gap 1.1e-2 of an edge) and carries no contact force: (a) and
(b) fail. With friction (the last test) the frozen pairing is off by 0.4
to 1 degree even in ten increments of one edge each.

Both couplings are checked: node-to-segment (the default) and the
segment-to-segment mortar (TYPE=SURFACE TO SURFACE). A last case cuts an
increment back (automatic increments, *CONTROLS I_C small): the restore
of the couplings the increment started with (their number and the
equation numbering; a numbering that does not fit the couplings stops
the run with an internal error) must give the same answer."""
import math
import os

from helpers import run_deck

R, DELTA_DEG, K = 10.0, 1.0, 10
B, H, D = 0.1, 0.1, 0.002
E, NU = 1000.0, 0.3
T_FOUND = 0.5
DELTA = math.radians(DELTA_DEG)
THETA = K * DELTA
# the circle's centre: the lowest edge (from -DELTA/2 to DELTA/2) at y = 0
CY = R * math.cos(DELTA / 2)
EDGE = 2 * R * math.sin(DELTA / 2)
FIRST_EDGE, LAST_EDGE = -3, K + 4          # edges j span ((j - 1/2) DELTA, (j + 1/2) DELTA)


def bowl_point(r, a):
    """A point at radius r and angle a (from the downward vertical, positive to +x) of the bowl."""
    return (r * math.sin(a), CY - r * math.cos(a))


def vertices():
    return [bowl_point(R, (j - 0.5) * DELTA) for j in range(FIRST_EDGE, LAST_EDGE + 2)]


BLOCK_NODE_OFFSET, BLOCK_ELEM_OFFSET = 20, 10     # block b: nodes 20 b + 1.., elements 10 b + 1..


def block_nodes(b=0):
    """Node ids and reference coordinates of block b (2 x 2 CPE4: 3 x 3 nodes, row by row from the bottom)."""
    nodes = {}
    for j in range(3):
        for i in range(3):
            nodes[BLOCK_NODE_OFFSET * b + 1 + i + 3 * j] = (-B / 2 + i * B / 2, j * H / 2)
    return nodes


def target(x, y):
    """Where a block point (x, y) goes: rotated by theta, its bottom on the middle of edge K,
    pressed by D along the edge normal (the block shortened, its top moved)."""
    mx = R * math.cos(DELTA / 2) * math.sin(THETA)
    my = CY - R * math.cos(DELTA / 2) * math.cos(THETA)
    c, s = math.cos(THETA), math.sin(THETA)
    return (mx + c * x - s * (y - D), my + s * x + c * (y - D))


def deck(couplings=(", TYPE=NODE TO SURFACE",), static="*STATIC, DIRECT\n1., 1.\n", controls=""):
    """One block per entry of couplings (the *CONTACT PAIR options of its pair: ", TYPE=NODE TO SURFACE"
    node-to-segment,
    ", TYPE=SURFACE TO SURFACE" mortar), all in the same place: blocks do not touch each other
    (no pair between them), so each is a model of its own in the same deck."""
    lines, elems, sets, pairs, bc = [], [], [], [], []
    for b, coupling in enumerate(couplings):
        bn = block_nodes(b)
        lines += [f"{n}, {x!r}, {y!r}" for n, (x, y) in bn.items()]
        o, eo = BLOCK_NODE_OFFSET * b, BLOCK_ELEM_OFFSET * b
        for j in range(2):
            for i in range(2):
                a = o + 1 + i + 3 * j
                elems.append(f"{eo + 1 + i + 2 * j}, {a}, {a + 1}, {a + 4}, {a + 3}")
        sets.append(f"*NSET, NSET=TOP{b}\n{o + 7}, {o + 8}, {o + 9}\n*NSET, NSET=BOTTOM{b}\n{o + 1}, {o + 2}, {o + 3}\n"
                    f"*SURFACE, NAME=SLAVE{b}, TYPE=ELEMENT\n{eo + 1}, S1\n{eo + 2}, S1\n")
        pairs.append(f"*CONTACT PAIR, EXACT{coupling}\nSLAVE{b}, MASTER\n")
        for n in (o + 7, o + 8, o + 9):
            x, y = bn[n]
            tx, ty = target(x, y)
            bc.append(f"{n}, 1, 1, {tx - x!r}\n{n}, 2, 2, {ty - y!r}")
    # the bowl: one layer of CPE4 between radius R + T_FOUND (t = 0) and R (t = 1), counter-clockwise
    fn = {}
    nid = 100
    for j in range(FIRST_EDGE, LAST_EDGE + 2):
        for r in (R + T_FOUND, R):
            nid += 1
            fn[(j, r)] = nid
            x, y = bowl_point(r, (j - 0.5) * DELTA)
            lines.append(f"{nid}, {x!r}, {y!r}")
    felems, faces = [], []
    eid = 100
    for j in range(FIRST_EDGE, LAST_EDGE + 1):
        eid += 1
        felems.append(f"{eid}, {fn[(j, R + T_FOUND)]}, {fn[(j + 1, R + T_FOUND)]}, {fn[(j + 1, R)]}, {fn[(j, R)]}")
        faces.append(f"{eid}, S3")
    prints = "".join(f"*NODE PRINT, NSET=BOTTOM{b}\nU\n*NODE PRINT, NSET=TOP{b}\nRF\n" for b in range(len(couplings)))
    nl = chr(10)
    return f"""*NODE, NSET=ALL
{nl.join(lines)}
*ELEMENT, TYPE=CPE4, ELSET=BLOCK
{nl.join(elems)}
*ELEMENT, TYPE=CPE4, ELSET=BOWL
{nl.join(felems)}
{"".join(sets)}*NSET, NSET=FOUND
{", ".join(str(v) for v in fn.values())}
*SURFACE, NAME=MASTER, TYPE=ELEMENT
{nl.join(faces)}
*MATERIAL, NAME=M
*ELASTIC
{E}, {NU}
*SOLID SECTION, ELSET=BLOCK, MATERIAL=M
1.
*SOLID SECTION, ELSET=BOWL, MATERIAL=M
1.
{"".join(pairs)}*BOUNDARY
FOUND, 1, 2
*STEP, NLGEOM
{static}{controls}*BOUNDARY
{nl.join(bc)}
{prints}*END STEP
"""


def polygon_distance(p):
    """The signed distance of point p from the bowl polygon (positive inside the bowl, above it)
    and the edge under it: the edge on which its orthogonal projection falls, nearest first."""
    v = vertices()
    best = None
    for k in range(len(v) - 1):
        (ax, ay), (bx, by) = v[k], v[k + 1]
        tx, ty = bx - ax, by - ay
        length = math.hypot(tx, ty)
        t = ((p[0] - ax) * tx + (p[1] - ay) * ty) / length**2
        if t < -1e-9 or t > 1 + 1e-9:
            continue
        # inward normal (towards the centre, up)
        g = ((p[0] - ax) * -ty + (p[1] - ay) * tx) / length
        if best is None or abs(g) < abs(best[0]):
            best = (g, k + FIRST_EDGE)
    return best


NTS, MORTAR = ", TYPE=NODE TO SURFACE", ", TYPE=SURFACE TO SURFACE"
BOTH = (NTS, MORTAR)
NAMES = {NTS: "node-to-segment", MORTAR: "mortar"}
# (a)'s tolerance per coupling, relative to the edge. Node-to-segment puts
# every closed slave node on its master edge (measured 1e-15). The mortar
# pair here has the slave faces finer than the bowl's edges (0.05 against
# 0.17), so it takes the master-mesh multipliers (contact_master_multipliers):
# one constraint per master node, on the hat-weighted mean of the slave
# surface, so a slave node may sit off the edge by the bending of the block's
# face between those constraints (measured 6.2e-5 of the edge); the search
# once per increment leaves them 1.1e-2 of an edge off. A frictional pair
# searched again keeps the dual mortar (contact.f90's couple_mortar), whose
# slave nodes sit on the polygon (measured 1e-15 before the master-mesh
# multipliers came).
GAP_TOL = {"node-to-segment": 1e-8, "mortar": 1e-4}


def end_state(run, b=0):
    """Deformed bottom nodes of block b, its top's reaction and the last increment of a run."""
    inc = run.listing.increments[-1]
    u = inc.block("NODE U", set=f"BOTTOM{b}")
    bn = block_nodes(b)
    pos = {n: (bn[n][0] + u1, bn[n][1] + u2) for n, u1, u2 in zip(u["node"], u["U1"], u["U2"])}
    rf = inc.block("NODE RF", set=f"TOP{b}")
    return pos, (sum(rf["RF1"]), sum(rf["RF2"])), inc


def check_on_polygon_and_normal(run, label, b=0, expected=THETA):
    """(a) and (b) on block b of a run (expected: the angle of the top's reaction); returns its
    bottom nodes' positions."""
    pos, (f1, f2), inc = end_state(run, b)
    assert abs(inc.time - 1.0) < 1e-12
    worst = 0.0
    for n, p in pos.items():
        g, k = polygon_distance(p)
        # every bottom node is closed (pressed by D) and on edge K
        assert k == K, (label, n, k)
        worst = max(worst, abs(g))
    angle = math.atan2(f1, -f2)
    print(f"  {label}: |gap| max {worst / EDGE:.1e} of the edge, force angle {math.degrees(angle):.9f} deg "
          f"(off by {abs(angle - expected):.1e} rad), {inc.attrs['iterations']} iterations in the last increment")
    assert worst < GAP_TOL[label.split(",")[0]] * EDGE, (label, worst)
    assert f2 < 0 and abs(angle - expected) < 1e-7, (label, math.degrees(angle))
    return pos


def run_case(name, couplings=(NTS,), static="*STATIC, DIRECT\n1., 1.\n", controls=""):
    return run_deck(name, deck(couplings, static, controls)).ok()


def same_state(a, b, label):
    """(c): the bottom nodes of two runs within 1e-7 of the slide."""
    worst = max(math.hypot(a[n][0] - b[n][0], a[n][1] - b[n][1]) for n in a)
    slide = R * math.sin(THETA)
    print(f"  {label}: largest difference {worst / slide:.1e} of the slide")
    assert worst < 1e-7 * slide, (label, worst)


def test_slide_ten_edges_in_one_increment_node_to_segment():
    check_on_polygon_and_normal(run_case("nl_search_nts_1"), "node-to-segment, 1 increment")


def test_slide_ten_edges_in_one_increment_mortar():
    check_on_polygon_and_normal(run_case("nl_search_mortar_1", (MORTAR,)), "mortar, 1 increment")


def test_one_and_ten_increments_give_the_same_answer_both_couplings():
    """Both couplings in one deck (a block each), 1 and 10 increments."""
    one = run_case("nl_search_both_1", BOTH)
    ten = run_case("nl_search_both_10", BOTH, "*STATIC, DIRECT\n0.1, 1.\n")
    assert len(ten.listing.increments) == 10
    for b, coupling in enumerate(BOTH):
        p1 = check_on_polygon_and_normal(one, NAMES[coupling] + ", 1 increment", b)
        p10 = check_on_polygon_and_normal(ten, NAMES[coupling] + ", 10 increments", b)
        same_state(p1, p10, NAMES[coupling] + ": 1 against 10 increments")


def test_cut_back_restores_the_couplings():
    """Automatic increments starting with the whole step: I_C = 2 iterations (plus one per status
    change, the search's own included) are too few for the slide of ten edges at once (13 needed), so the first attempt
    fails and is cut back (D_C = 0.5) from couplings and a numbering it changed; the halves must
    converge to the one-increment answer, for both couplings in one deck."""
    ref = run_case("nl_search_cut_ref", BOTH)
    run = run_case("nl_search_cut", BOTH, static="*STATIC\n1., 1.\n",
                   controls="*CONTROLS, PARAMETERS=TIME INCREMENTATION\n4, 8, 9, 2, 10, 4\n")
    assert "increment cut back" in open(run.listing_path).read()
    assert len(run.listing.increments) > 1
    for b, coupling in enumerate(BOTH):
        p_ref = check_on_polygon_and_normal(ref, NAMES[coupling] + ", 1 increment", b)
        p_cut = check_on_polygon_and_normal(run, NAMES[coupling] + ", after a cut-back", b)
        same_state(p_ref, p_cut, NAMES[coupling] + ": cut back against 1 increment")


def test_coulomb_friction_carried_through_the_searches():
    """FRICTION=0.2, both couplings in one deck: the bottom slides all the way (its slide of ten
    edges dwarfs the Poisson spreading), so each closed point carries mu times its normal force
    against the slip (+t = (cos theta, sin theta)): the reaction at the top is at theta + atan(mu)
    (to 1e-7 rad). Automatic increments from the whole step (the first attempts stick and
    invert an element: cut back) and ten DIRECT increments; with the search once per increment
    the nodes end off the polygon and the angle is off by 0.4 to 1 degree."""
    mu = 0.2
    couplings = (NTS + f", FRICTION={mu}", MORTAR + f", FRICTION={mu}")
    auto = run_case("nl_search_fric_auto", couplings, "*STATIC\n1., 1.\n")
    ten = run_case("nl_search_fric_10", couplings, "*STATIC, DIRECT\n0.1, 1.\n")
    expected = THETA + math.atan(mu)
    for b, coupling in enumerate(BOTH):
        pa = check_on_polygon_and_normal(auto, NAMES[coupling] + ", friction, automatic", b, expected)
        p10 = check_on_polygon_and_normal(ten, NAMES[coupling] + ", friction, 10 increments", b, expected)
        same_state(pa, p10, NAMES[coupling] + ", friction: automatic against 10 increments")


def test_force_driven_body_under_nlgeom_settles():
    """test_contact's force-driven upper block (1e-3 above the lower one, held by nothing but the
    contact; its end slave node sits at the end of the master surface, which the block's Poisson
    spreading pushes a little past) under NLGEOM, with OPEN PENALTY=1e-6 and the default: every
    slave node closes, the contact force equals the load to the Newton iteration's force test
    (CalculiX's R_n = 0.005 of the average force: 1e-3 here; measured 1.2e-4 in one increment)
    and the pressure is the uniform one within 1 % (measured 0.50 % at the end node, the same
    Newton tolerance), as the small-strain test has it to 0.5 %. Without the search's hysteresis (a closed coupling
    kept while its point is within half an edge of its master edge) and without counting the
    search's own status changes, that end node lost and regained its coupling from iteration to
    iteration (closed 10, 11, 10, ...) and the run stopped on divergence after cutting the
    increment to 1e-6."""
    import test_contact as tc
    for tag, params in (("open", ", OPEN PENALTY=1e-6"), ("default", "")):
        deck, load = tc.force_driven_deck(params)
        assert deck.count("*STEP\n") == 1
        run = run_deck("nl_search_force_driven_" + tag, deck.replace("*STEP\n", "*STEP, NLGEOM\n")).ok()
        slave, _, summ = tc.contact_blocks(run.listing.increments[-1])
        print(f"  {tag}: {len(run.listing.increments)} increments, total force {summ['total_force'][0]:.9f}")
        assert all(s == "CLOSED" for s in slave["state"]), tag
        assert abs(summ["total_force"][0] - load) < 1e-3 * load, (tag, summ["total_force"])
        assert max(abs(slave["pressure"] - load / tc.W)) / (load / tc.W) < 0.01, tag


def test_status_cycle_cut_back_at_once():
    """A coupling that closes and opens in turn with the same out-of-
    balance every second Newton iteration (tests/decks/soft_first_touch:
    the fuzzer's Hertz seed with a neo-Hooke body a hundred thousand times
    softer than the automatic penalty assumes; the plate node first
    touched alternates between 1.26e7 closed and 2.8e-2 open) cuts the
    increment back at once instead of after MAXIT = 100 iterations: the
    run stops with the cycle named, at increment 4 as before, after 224
    listed contact iterations (406 without the test; measured)."""
    from helpers import HERE
    run = run_deck("nl_status_cycle", path=os.path.join(HERE, "decks", "soft_first_touch", "hertz.inp"))
    assert run.rc == 1, (run.rc, run.stderr[-500:])
    assert "the contact status cycles" in run.stderr and "increment 4" in run.stderr, run.stderr[-500:]
    iterations = open(run.listing_path).read().count("contact iteration")
    assert iterations < 300, iterations
    # CalculiX's status files count the attempts (results_sta): an
    # increment's ATT in the .sta is one more than the cut-backs the listing
    # notes since the increment before it (2 before increment 3 here), and
    # the .cvg's attempt column rises within an increment, one per cut-back
    want, cuts = [], 0
    for line in open(run.listing_path).read().splitlines():
        if "increment cut back to" in line:
            cuts += 1
        elif line.startswith("=== INCREMENT"):
            want.append(cuts + 1)
            cuts = 0
    out = os.path.dirname(run.listing_path)
    sta = [ln.split() for ln in open(os.path.join(out, "hertz.sta")).read().split("\n")[2:] if ln]
    assert [int(r[2]) for r in sta] == want and max(want) == 3, (sta, want)
    cvg = [ln.split() for ln in open(os.path.join(out, "hertz.cvg")).read().split("\n")[4:] if ln]
    for inc, att in zip([int(r[1]) for r in sta], want):
        seen = [int(r[2]) for r in cvg if int(r[1]) == inc]
        assert seen == sorted(seen) and seen[0] == 1 and seen[-1] == att, (inc, seen, att)
