"""Friction in the results: the shear columns and STICK/SLIP states of the
listing's contact tables and of <job>_contact.csv, the tangential total of
the contact summary, and the nodal contact shear traction (CSHEAR) of the
gmsh and VTU files; a frictionless model's outputs keep their columns.

The model (slide_deck): a block pressed onto a wider block (step 1),
pushed sideways in ten increments until every point slides, so that the
top reaction's RF1 reaches mu RF2 (step 2), then lifted off (step 3, every
point OPEN)."""
import csv
import os
import subprocess

import numpy as np

from cfe2d_listing import is_closed
from decks import grid, node_lines, quad_lines
from gmsh_results import read_msh
from helpers import ROOT, WORK, Skip, run_deck
from quadmesh import Mesh, etype
from test_decks_vtu import series

MU = 0.3
BASE_COLUMNS = "step,increment,time,pair,side,node,x,y,gap,state,force,pressure"
FRICTION_COLUMNS = "shear_force,shear,slip,slip_increment"


def slide_deck(pair="*CONTACT PAIR, FRICTION=0.3\nSS, MS\n", slave_surface="*SURFACE, NAME=SS, TYPE=NODE\nSLV\n"):
    """Lower block 10 x 3 (10 x 3 CPE4, bottom held), upper block 6 x 3 on
    it (7 x 3 CPE4, non-matching), its top held sideways and pressed down
    by 1e-3 (step 1),
    moved 2e-3 sideways in 10 increments (step 2) and lifted by 1e-3 (step 3)."""
    n1, ids1, q1 = grid(10, 3, 0, 10, -3, 0)
    n2, ids2, q2 = grid(7, 3, 2, 8, 0, 3, first_node=len(n1) + 1)
    top = "".join(f"{ids2[i, 3]},\n" for i in range(8))
    bottom = "".join(f"{ids1[i, 0]},\n" for i in range(11))
    slave = "".join(f"{ids2[i, 0]},\n" for i in range(8))
    master_elements = "".join(f"{20 + k + 1},\n" for k in range(10))
    requests = "*NODE PRINT, NSET=TOP, TOTALS=YES\nRF\n*NODE FILE\nU, CSTRESS\n*END STEP\n"
    return (f"*NODE\n{node_lines({**n1, **n2})}*ELEMENT, TYPE=CPE4, ELSET=LOW\n{quad_lines(q1)}"
            f"*ELEMENT, TYPE=CPE4, ELSET=UP\n{quad_lines(q2, first=len(q1) + 1)}"
            f"*NSET, NSET=TOP\n{top}*NSET, NSET=BOT\n{bottom}*NSET, NSET=SLV\n{slave}"
            f"*ELSET, ELSET=MEL\n{master_elements}*ELSET, ELSET=SEL\n"
            + "".join(f"{len(q1) + k + 1},\n" for k in range(7)) +
            "*MATERIAL, NAME=ST\n*ELASTIC\n210000., 0.3\n*SOLID SECTION, ELSET=LOW, MATERIAL=ST\n"
            "*SOLID SECTION, ELSET=UP, MATERIAL=ST\n*SURFACE, NAME=MS\nMEL, S3\n" + slave_surface + pair +
            "*BOUNDARY\nBOT, 1, 2\n"
            "*STEP\n*STATIC\n1.0, 1.0\n*BOUNDARY\nTOP, 1, 1, 0.\nTOP, 2, 2, -1e-3\n" + requests +
            "*STEP\n*STATIC\n0.1, 1.0\n*BOUNDARY\nTOP, 1, 1, 2e-3\nTOP, 2, 2, -1e-3\n" + requests +
            "*STEP\n*STATIC\n1.0, 1.0\n*BOUNDARY\nTOP, 1, 1, 2e-3\nTOP, 2, 2, 1e-3\n" + requests)


def read_table(run):
    """(header, rows as dicts) of the run's contact table."""
    with open(run.listing_path[:-4] + "_contact.csv") as f:
        header = f.readline().strip()
        f.seek(0)
        return header, list(csv.DictReader(f))


def friction_run(name="friction_slide", deck=None):
    return run_deck(name, deck or slide_deck(), args=("--vtu",)).ok()


def top_reaction(inc):
    """RF1, RF2 of the top set."""
    r = inc.block("REACTIONS")
    k = r["set"].index("TOP")
    return r["RF1"][k], r["RF2"][k]


def test_columns_and_states_of_the_tables():
    """The listing's CONTACT SLAVE / MASTER / SUMMARY blocks and the contact
    table of a frictional pair have the shear and slip columns; the table's
    rows are the listing's rows (9 printed digits); the states are OPEN,
    STICK, SLIP (no CLOSED); master rows' slip columns are 0; an OPEN row
    has zero shear, and a shear traction is its shear force over its area."""
    run = friction_run()
    header, rows = read_table(run)
    assert header == BASE_COLUMNS + "," + FRICTION_COLUMNS, header
    incs = run.listing.increments
    assert len(incs) == 1 + 10 + 1, len(incs)
    k = 0
    states = set()
    for inc in incs:
        s, m = inc.block("CONTACT SLAVE", pair=1), inc.block("CONTACT MASTER", pair=1)
        summ = inc.block("CONTACT SUMMARY", pair=1)
        assert s.columns == "node x y gap state force area pressure shear_force shear slip slip_inc".split(), s.columns
        assert m.columns == "node x y force area pressure shear_force shear".split(), m.columns
        assert summ.columns[-1] == "shear_total", summ.columns
        for j in range(len(s)):
            r = rows[k]
            k += 1
            assert (r["side"], int(r["node"]), r["state"]) == ("slave", int(s["node"][j]), s["state"][j]), (r, j)
            for col, lst in (("force", "force"), ("pressure", "pressure"), ("shear_force", "shear_force"),
                             ("shear", "shear"), ("slip", "slip"), ("slip_increment", "slip_inc")):
                assert np.isclose(float(r[col]), s[lst][j], rtol=1e-8, atol=1e-300), (col, r, j)
            states.add(s["state"][j])
            if s["state"][j] == "OPEN":
                assert s["shear_force"][j] == 0.0 and s["shear"][j] == 0.0 and s["force"][j] == 0.0, (inc.attrs, j)
                assert float(r["shear_force"]) == 0.0 and float(r["shear"]) == 0.0, r
            assert np.isclose(s["shear"][j], s["shear_force"][j] / s["area"][j], rtol=1e-14, atol=0.0)
        for j in range(len(m)):
            r = rows[k]
            k += 1
            assert (r["side"], int(r["node"]), r["state"]) == ("master", int(m["node"][j]), "-"), r
            assert r["slip"] == "0" and r["slip_increment"] == "0", r
            assert np.isclose(float(r["shear_force"]), m["shear_force"][j], rtol=1e-8, atol=1e-300), r
            if m["area"][j] > 0:
                assert np.isclose(m["shear"][j], m["shear_force"][j] / m["area"][j], rtol=1e-14, atol=0.0)
    assert k == len(rows), (k, len(rows))
    assert states == {"OPEN", "STICK", "SLIP"}, states
    assert all(s == "OPEN" for s in incs[-1].block("CONTACT SLAVE")["state"])
    # the slip history stays with the lifted points
    assert all(v > 0 for v in incs[-1].block("CONTACT SLAVE")["slip"])


def test_coulomb_law_and_equilibrium_in_the_rows():
    """At every increment: a SLIP row's shear force is mu times its normal
    force (1e-9), a STICK row's is at most that; the summary's shear_total
    is the sum of the slave rows' shear forces and of the master rows',
    and the top reaction's RF1 (the contact resultant's x: the tangent is
    -x on the lower block's top), and resultant_y is RF2. Once the block
    slides every point slips, its slip increment is against its shear
    (friction opposes the slip), and RF1 = mu RF2 in magnitude."""
    run = friction_run("friction_law")
    sliding = 0
    # open points carry their open penalty's forces (1e-12 of the closed
    # one) in the reactions, not in the rows: compare with the run's forces
    scale = max(inc.block("CONTACT SUMMARY")["total_force"][0] for inc in run.listing.increments)
    for inc in run.listing.increments:
        s, m = inc.block("CONTACT SLAVE"), inc.block("CONTACT MASTER")
        summ = inc.block("CONTACT SUMMARY")
        shear, force, states = s["shear_force"], s["force"], s["state"]
        for j, st in enumerate(states):
            if st == "SLIP":
                assert abs(abs(shear[j]) - MU * force[j]) <= 1e-9 * MU * force[j], (inc.attrs, j, shear[j], force[j])
            elif st == "STICK":
                assert abs(shear[j]) <= MU * force[j] * (1 + 1e-9), (inc.attrs, j, shear[j], force[j])
        total = summ["shear_total"][0]
        assert abs(total - np.sum(shear)) <= 1e-12 * scale, (inc.attrs, total, np.sum(shear))
        assert abs(total - np.sum(m["shear_force"])) <= 1e-12 * scale, (inc.attrs, total, np.sum(m["shear_force"]))
        rf1, rf2 = top_reaction(inc)
        assert abs(total - summ["resultant_x"][0]) <= 1e-12 * scale, (inc.attrs, total, summ["resultant_x"][0])
        assert abs(rf1 - total) <= 1e-6 * scale, (inc.attrs, rf1, total)
        assert abs(rf2 - summ["resultant_y"][0]) <= 1e-6 * scale, (inc.attrs, rf2, summ["resultant_y"][0])
        if len(states) and all(st == "SLIP" for st in states) and inc.step == 2:
            sliding += 1
            assert abs(abs(rf1) - MU * abs(rf2)) <= 1e-6 * abs(rf2), (inc.attrs, rf1, rf2)
            assert np.all(s["slip_inc"] * shear < 0), (inc.attrs, s["slip_inc"], shear)
    assert sliding >= 3, sliding


def test_cshear_in_the_gmsh_and_vtu_files():
    """The gmsh file has a CSHEAR view beside "Contact pressure" at every
    increment, the VTU files a CSHEAR point array beside CSTRESS; both hold
    the slave rows' shear tractions at the slave nodes and the master
    rows' at the master nodes."""
    run = friction_run("friction_files")
    d = os.path.dirname(run.listing_path)
    msh = read_msh(os.path.join(d, "friction_files.msh"))
    incs = run.listing.increments
    assert len(msh.views["CSHEAR"]) == len(msh.views["Contact pressure"]) == len(incs)
    _, meshes = series(run, "friction_files")
    assert len(meshes) == len(incs)
    index = {int(n): k for k, n in enumerate(msh.node_ids)}
    for k, (inc, mesh) in enumerate(zip(incs, meshes)):
        _, tau = msh.node_view("CSHEAR", k)
        at = {int(n): q for q, n in enumerate(mesh.point_data["NodeId"])}
        for block in ("CONTACT SLAVE", "CONTACT MASTER"):
            b = inc.block(block)
            nodes = [int(n) for n in b["node"]]
            want = b["shear"]
            assert np.allclose(tau[[index[n] for n in nodes], 0], want, rtol=1e-14, atol=1e-300), (k, block)
            assert np.allclose(mesh.point_data["CSHEAR"][[at[n] for n in nodes]], want, rtol=1e-14,
                               atol=1e-300), (k, block)
        assert np.any(tau[:, 0][~np.isnan(tau[:, 0])] != 0.0) or k == len(incs) - 1


def test_frictionless_outputs_keep_their_columns():
    """The same model without friction: the contact table's header is the
    old one, the tables have no shear columns, a closed point is CLOSED,
    and the result files have no CSHEAR."""
    run = friction_run("friction_none", slide_deck(pair="*CONTACT PAIR\nSS, MS\n"))
    header, rows = read_table(run)
    assert header == BASE_COLUMNS, header
    assert all(len(r) == len(BASE_COLUMNS.split(",")) for r in rows)
    assert {r["state"] for r in rows} == {"CLOSED", "OPEN", "-"}, {r["state"] for r in rows}
    inc = run.listing.increments[0]
    assert inc.block("CONTACT SLAVE").columns == "node x y gap state force area pressure".split()
    assert inc.block("CONTACT MASTER").columns == "node x y force area pressure".split()
    assert inc.block("CONTACT SUMMARY").columns == "closed total_force resultant_x resultant_y max_penetration".split()
    d = os.path.dirname(run.listing_path)
    assert "CSHEAR" not in read_msh(os.path.join(d, "friction_none.msh")).views
    _, meshes = series(run, "friction_none")
    assert "CSHEAR" not in meshes[0].point_data and "CSTRESS" in meshes[0].point_data


def test_symmetric_pair_adds_the_second_pass_shear():
    """Two-pass friction (SYMMETRIC, slave an element surface): each row
    also holds the shear the other pass puts on its node, and the totals
    still balance: shear_total = the slave rows' sum = resultant_x = RF1
    of the top, the block still slides at RF1 = mu RF2."""
    deck = slide_deck(pair="*CONTACT PAIR, FRICTION=0.3, SYMMETRIC\nSS, MS\n",
                      slave_surface="*SURFACE, NAME=SS\nSEL, S1\n")
    run = run_deck("friction_symmetric", deck).ok()
    scale = max(inc.block("CONTACT SUMMARY")["total_force"][0] for inc in run.listing.increments)
    for inc in run.listing.increments:
        s, summ = inc.block("CONTACT SLAVE"), inc.block("CONTACT SUMMARY")
        total = summ["shear_total"][0]
        rf1, rf2 = top_reaction(inc)
        assert abs(total - np.sum(s["shear_force"])) <= 1e-9 * scale, (inc.attrs, total, np.sum(s["shear_force"]))
        assert abs(total - summ["resultant_x"][0]) <= 1e-12 * scale, (inc.attrs, total, summ["resultant_x"][0])
        assert abs(rf1 - total) <= 1e-6 * scale, (inc.attrs, rf1, total)
    rf1, rf2 = top_reaction(run.listing.increments[10])
    assert abs(abs(rf1) - MU * abs(rf2)) <= 1e-6 * abs(rf2), (rf1, rf2)


def test_face_points_nodal_shear():
    """8-node blocks (slave points at Gauss points of the slave faces):
    pressed and pushed until they slide; every point slides with |shear|
    = mu force, and the nodal shear traction of the slave nodes (the
    points' shear forces taken to the face nodes, over the nodes'
    consistent areas 1/6, 4/6, 1/6 of a face) integrates to shear_total."""
    nx1, nx2 = 5, 7
    m1 = Mesh("Q8", nx1, 2, lambda s, t: (s / nx1, t / 4), first_node=1, first_elem=1)
    m2 = Mesh("Q8", nx2, 2, lambda s, t: (0.1 + 0.8 * s / nx2, 0.5 + t / 4), first_node=10001, first_elem=10001)
    step = ("*STEP\n*STATIC\n{inc}, 1.0\n*BOUNDARY\nTOP, 1, 1, {ux}\nTOP, 2, 2, -2e-3\n*NODE FILE\nCSTRESS\n"
            "*END STEP\n")
    deck = (f"*NODE\n{m1.node_lines()}{m2.node_lines()}{m1.element_card(etype('Q8', 'E'), 'LOWER')}"
            f"{m2.element_card(etype('Q8', 'E'), 'UPPER')}"
            f"*NSET, NSET=GROUND\n{', '.join(map(str, m1.side('bottom')))}\n"
            f"*NSET, NSET=TOP\n{', '.join(map(str, m2.side('top')))}\n"
            f"{m2.surface_card('SLAVE', 'bottom')}{m1.surface_card('MASTER', 'top')}"
            "*MATERIAL, NAME=M\n*ELASTIC\n1000., 0.3\n*SOLID SECTION, ELSET=LOWER, MATERIAL=M\n"
            "*SOLID SECTION, ELSET=UPPER, MATERIAL=M\n*CONTACT PAIR, FRICTION=0.3, TYPE=NODE TO SURFACE\n"
            "SLAVE, MASTER\n"
            "*BOUNDARY\nGROUND, 1, 2\n" + step.format(inc=1.0, ux=0.0) + step.format(inc=0.25, ux=1e-2))
    run = run_deck("friction_face_points", deck).ok()
    inc = run.listing.increments[-1]
    s, summ = inc.block("CONTACT SLAVE"), inc.block("CONTACT SUMMARY")
    assert all(n == 0 for n in s["node"]) and set(s["state"]) == {"SLIP"}, set(s["state"])
    assert np.allclose(np.abs(s["shear_force"]), MU * s["force"], rtol=1e-9, atol=0.0)
    msh = read_msh(os.path.join(os.path.dirname(run.listing_path), "friction_face_points.msh"))
    _, tau = msh.node_view("CSHEAR", len(run.listing.increments) - 1)
    index = {int(n): k for k, n in enumerate(msh.node_ids)}
    bottom = m2.side("bottom")                  # corner, mid, corner, ... along x
    face = 0.8 / nx2
    area = np.array([face / 6 * (1 if k in (0, len(bottom) - 1) else 2) if k % 2 == 0 else 4 * face / 6
                     for k in range(len(bottom))])
    nodal = tau[[index[n] for n in bottom], 0] * area
    total = summ["shear_total"][0]
    assert abs(np.sum(nodal) - total) <= 1e-9 * abs(total), (np.sum(nodal), total)
    assert abs(total - np.sum(s["shear_force"])) <= 1e-12 * abs(total)
    assert all(is_closed(st) for st in s["state"])


def test_debug_build_writes_the_same_tables():
    """The debug build (-fcheck=all: bounds of the new arrays and formats)
    runs the frictional decks, single and two-pass, without a runtime error
    and with the optimised build's rows and states."""
    debug = os.path.join(ROOT, "build-debug", "cfe2d")
    if not os.path.exists(debug):
        raise Skip("build-debug/cfe2d not built (make debug)")
    for name, deck in (("friction_debug", slide_deck()),
                       ("friction_debug_symmetric", slide_deck(pair="*CONTACT PAIR, FRICTION=0.3, SYMMETRIC\nSS, MS\n",
                                                               slave_surface="*SURFACE, NAME=SS\nSEL, S1\n"))):
        opt = run_deck(name, deck).ok()
        d = os.path.join(WORK, name + "_dbg")
        os.makedirs(d, exist_ok=True)
        r = subprocess.run([debug, "-q", "-o", d, opt.deck], capture_output=True, text=True, timeout=600)
        assert r.returncode == 0 and "Fortran runtime" not in r.stderr, r.stderr
        _, a = read_table(opt)
        with open(os.path.join(d, name + "_contact.csv")) as f:
            b = list(csv.DictReader(f))
        assert [(r["side"], r["node"], r["state"]) for r in a] == [(r["side"], r["node"], r["state"]) for r in b]
        for ra, rb in zip(a, b):
            for col in ("force", "shear_force", "slip"):
                assert abs(float(ra[col]) - float(rb[col])) <= 1e-8 * max(1.0, abs(float(ra[col]))), (col, ra, rb)
