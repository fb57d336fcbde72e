"""Contact on quadratic (and axisymmetric) elements: slave faces with
mid-side nodes coupled at Gauss points of the slave faces (cut where the
master element boundaries project onto them), master edges with three
nodes (projection onto the curved edge), areas and forces of axisymmetric
contact over the whole ring. Closed-form checks: the uniform-pressure
contact patch test on non-matching meshes, and the shrink fit of two
thick cylinders (curved master and slave faces, plane strain and
axisymmetric)."""
import math

import numpy as np

from helpers import run_deck
from quadmesh import Mesh, etype

E, NU = 1000.0, 0.3
# the automatic penalty of the Gauss points of 3-node slave faces:
# FACE_FACTOR * E / h per area, h the node spacing (src/contact/contact.f90)
FACE_FACTOR = 3.0


def coupling(pair):
    """The pair's options: this file checks the paper's node-to-segment
    coupling (Gauss points of 3-node faces), which the pair names since
    segment-to-segment became the default; SYMMETRIC is node-to-segment."""
    return pair if "SYMMETRIC" in pair or "TYPE=" in pair else ", TYPE=NODE TO SURFACE" + pair


def two_blocks(lower, upper, nx1, nx2, state="S", d=0.03, g0=0.01, slave_kind="element", x0=0.0, pair=""):
    """Lower block [x0, x0+1] x [0, 1] (master, nx1 across), upper block
    g0 above it (slave, nx2 across), the upper top pushed down by d."""
    m1 = Mesh(lower, nx1, 4, lambda s, t: (x0 + s / nx1, t / 4), first_node=1, first_elem=1)
    m2 = Mesh(upper, nx2, 4, lambda s, t: (x0 + s / nx2, 1 + g0 + t / 4), first_node=10001, first_elem=10001)
    slave = m2.surface_card("SLAVE", "bottom") if slave_kind == "element" else \
        "*NSET, NSET=SLAVEN\n" + ", ".join(map(str, m2.side("bottom"))) + "\n*SURFACE, NAME=SLAVE, TYPE=NODE\nSLAVEN\n"
    deck = f"""*NODE, NSET=ALLN
{m1.node_lines()}{m2.node_lines()}{m1.element_card(etype(lower, state), 'LOWER')}{m2.element_card(etype(upper, state), 'UPPER')}*NSET, NSET=GROUND
{", ".join(map(str, m1.side('bottom')))}
*NSET, NSET=ANCHOR
{m1.side('bottom')[0]}
*NSET, NSET=TOP
{", ".join(map(str, m2.side('top')))}
*NSET, NSET=TOPLEFT
{m2.side('top')[0]}
{slave}{m1.surface_card('MASTER', 'top')}*MATERIAL, NAME=M
*ELASTIC
{E}, {NU}
*SOLID SECTION, ELSET=LOWER, MATERIAL=M
*SOLID SECTION, ELSET=UPPER, MATERIAL=M
*CONTACT PAIR{coupling(pair)}
SLAVE, MASTER
*BOUNDARY
GROUND, 2, 2
ANCHOR, 1, 1
TOPLEFT, 1, 1
*STEP
*STATIC
*BOUNDARY
TOP, 2, 2, {-d}
*NODE PRINT, NSET=GROUND
RF
*NODE FILE
CSTRESS
*END STEP
"""
    return deck


def contact_rows(run):
    """Slave and master rows of the last increment's contact blocks."""
    inc = run.listing.increments[-1]
    return inc.block("CONTACT SLAVE"), inc.block("CONTACT MASTER"), inc


def test_uniform_pressure_patch_nonmatching_quadratic():
    """CPS8 on CPS8, 7 slave faces over 5 master faces (no common
    refinement), pressed 0.03 across a gap of 0.01: every slave point's
    pressure and every master node's pressure uniform to 1e-4 and within
    0.5 % of the series value E (d - g0) / (h1 + h2 + h/3) (the last term
    the automatic face penalty's compliance, 3 E / h per area with h the
    node spacing); also CPS6 on CPS8, CPS8 on CPS4 and 3 over 7 faces."""
    for lower, upper, n1, n2 in (("Q8", "Q8", 5, 7), ("Q8", "T6", 5, 7), ("Q4", "Q8", 5, 7), ("Q8", "Q8", 7, 3)):
        h = min(0.5 / n2, 1.0 / n1 / (1 if lower == "Q4" else 2))
        p = E * (0.03 - 0.01) / (2.0 + h / FACE_FACTOR)
        run = run_deck(f"patch_quad_{lower}_{upper}_{n1}_{n2}", two_blocks(lower, upper, n1, n2)).ok()
        s, mst, inc = contact_rows(run)
        ps = np.array(s["pressure"])
        pm = np.array(mst["pressure"])
        assert all(n == 0 for n in s["node"]) and all(st == "CLOSED" for st in s["state"]), s["state"]
        es, em = np.max(np.abs(ps - p)) / p, np.max(np.abs(pm - p)) / p
        spread = (max(ps.max(), pm.max()) - min(ps.min(), pm.min())) / p
        print(f"  {upper} slave on {lower} master, {n2} over {n1}: slave {es:.2e}, master {em:.2e}, "
              f"spread {spread:.2e}")
        assert es < 5e-3 and em < 5e-3 and spread < 1e-4, (lower, upper, es, em, spread)
        total = inc.block("CONTACT SUMMARY")["total_force"][0]
        assert abs(total - p) < 5e-3 * p, total
        # the result file's nodal contact pressure: slave nodes (forces of
        # the Gauss points over consistent areas) and master nodes alike
        from gmsh_results import read_msh
        res = read_msh(run.listing_path[:-4] + ".msh")
        _, pv = res.node_view("Contact pressure", 0)
        ids = list(res.node_ids)
        slave_nodes = [n for n in ids if n > 10000 and abs(res.xy[ids.index(n)][1] - 1.01) < 1e-9]
        vals = np.array([pv[ids.index(n)][0] for n in slave_nodes])
        assert len(vals) == 2 * n2 + 1 and np.max(np.abs(vals - p)) < 1e-9 * p, (lower, upper, vals)


def test_symmetric_quadratic_reports_both_passes():
    """SYMMETRIC on CPS8 (7 slave faces over 5, and 5 over 5), both passes
    coupled at Gauss points: every listed slave point, every master node
    and every node of the result file's pressure carries what both passes
    put there, the pair's total force over the unit width within 0.5 %
    (the passes' shares are not reported as the whole: each row once
    showed one pass, half the pressure)."""
    for n1, n2 in ((5, 7), (5, 5)):
        run = run_deck(f"patch_quad_sym_{n1}_{n2}", two_blocks("Q8", "Q8", n1, n2, pair=", SYMMETRIC")).ok()
        s, mst, inc = contact_rows(run)
        p = inc.block("CONTACT SUMMARY")["total_force"][0]
        ps, pm = np.array(s["pressure"]), np.array(mst["pressure"])
        es, em = np.max(np.abs(ps - p)) / p, np.max(np.abs(pm - p)) / p
        assert abs(sum(s["force"]) - p) < 5e-3 * p, (sum(s["force"]), p)
        from gmsh_results import read_msh
        res = read_msh(run.listing_path[:-4] + ".msh")
        _, pv = res.node_view("Contact pressure", 0)
        ids = list(res.node_ids)
        on_faces = [n for n in ids if abs(res.xy[ids.index(n)][1] - 1.0) < 1e-9 or
                    (n > 10000 and abs(res.xy[ids.index(n)][1] - 1.01) < 1e-9)]
        vals = np.array([pv[ids.index(n)][0] for n in on_faces])
        en = np.max(np.abs(vals - p)) / p
        print(f"  SYMMETRIC {n2} over {n1}: slave {es:.2e}, master {em:.2e}, nodes {en:.2e}")
        assert es < 5e-3 and em < 5e-3 and en < 5e-3, (n1, n2, es, em, en)


def test_node_to_segment_on_quadratic_slave_shows_the_problem():
    """The same patch with the slave side given as a node surface (node-
    to-segment on a quadratic face): the pressure is not uniform: the
    corner and mid-side nodes of a quadratic face do not see the same
    share as their consistent areas say, where the Gauss points above are
    uniform. (A measurement, not a target: this is why 3-node slave faces
    are coupled at Gauss points.)"""
    p = E * (0.03 - 0.01) / 2.0
    run = run_deck("patch_quad_nodes", two_blocks("Q8", "Q8", 5, 7, slave_kind="node")).ok()
    s, mst, _ = contact_rows(run)
    err = np.max(np.abs(np.array(s["pressure"]) - p)) / p
    print(f"  node-to-segment on 8-node faces, 7 over 5: slave pressure off by up to {err:.1%}")
    assert err > 0.02, err


def lame_u(p_in, p_out, a, b, r):
    """Radial displacement at r of a cylinder a < r < b under internal
    p_in and external p_out (plane strain)."""
    A = (p_in * a * a - p_out * b * b) / (b * b - a * a)
    B = (p_in - p_out) * a * a * b * b / (b * b - a * a)
    return (1 + NU) / E * ((1 - 2 * NU) * A * r + B / r)


def shrink_fit_pressure(a, b, c, delta, h=0.0):
    """Slave (inner cylinder a < r < b + delta) and master (outer
    cylinder b < r < c) pressures of the fit, plane strain, same material,
    as the small-deformation model states it: the overlap delta is closed
    (u_outer(b) - u_inner(b + delta) = delta) and each coupling force acts
    on the slave area at b + delta and on the master area at b, so
    p_master = p_slave (b + delta) / b. h: the node spacing that sets the
    automatic face penalty 3 E / h per area, whose compliance takes up
    part of the overlap (0 for a rigid penalty)."""
    f = (b + delta) / b
    ps = delta / (lame_u(f, 0.0, b, c, b) - lame_u(0.0, 1.0, a, b + delta, b + delta) + h / (FACE_FACTOR * E))
    return ps, ps * f


def polar(nx, ny, r0, r1, angle=math.pi / 2):
    def xy(s, t):
        r = r0 + (r1 - r0) * s / nx if s == int(s) else \
            0.5 * (r0 + (r1 - r0) * math.floor(s) / nx + r0 + (r1 - r0) * math.ceil(s) / nx)
        th = angle * t / ny
        return r * math.cos(th), r * math.sin(th)
    return xy


def shrink_deck(inner, outer, state, n_inner=28, n_outer=14, pair=""):
    """The shrink fit: plane strain quarter model (state 'E', symmetry
    planes held; n_inner slave faces, n_outer master faces around the
    quarter) or an axisymmetric slice (state 'AX', both faces of the slice
    held axially)."""
    if state == "E":
        mi = Mesh(inner, 3, n_inner, polar(3, n_inner, RA, RB + DELTA), first_node=1)
        mo = Mesh(outer, 4, n_outer, polar(4, n_outer, RB, RC), first_node=10001, first_elem=10001)
        bcs = "SYMX, 2, 2\nSYMY, 1, 1\n"
        symx = mi.side("bottom") + mo.side("bottom")
        symy = mi.side("top") + mo.side("top")
    else:
        # non-matching for the 3-node faces, nested for the 2-node ones
        # (single-pass node-to-segment is exact only on nested meshes)
        ni = 5 if inner == "Q8" else 6
        mi = Mesh(inner, 3, ni, lambda s, t: (RA + (RB + DELTA - RA) * s / 3, 0.5 * t / ni), first_node=1)
        mo = Mesh(outer, 4, 3, lambda s, t: (RB + (RC - RB) * s / 4, 0.5 * t / 3), first_node=10001,
                  first_elem=10001)
        bcs = "SYMX, 2, 2\n"
        symx = mi.side("bottom") + mo.side("bottom") + mi.side("top") + mo.side("top")
        symy = [1]
    return mi, mo, f"""*NODE, NSET=ALLN
{mi.node_lines()}{mo.node_lines()}{mi.element_card(etype(inner, state), 'INNER')}{mo.element_card(etype(outer, state), 'OUTER')}*NSET, NSET=SYMX
{", ".join(map(str, symx))}
*NSET, NSET=SYMY
{", ".join(map(str, symy))}
{mi.surface_card('SLAVE', 'right')}{mo.surface_card('MASTER', 'left')}*MATERIAL, NAME=M
*ELASTIC
{E}, {NU}
*SOLID SECTION, ELSET=INNER, MATERIAL=M
*SOLID SECTION, ELSET=OUTER, MATERIAL=M
*CONTACT PAIR{coupling(pair)}
SLAVE, MASTER
*BOUNDARY
{bcs}*STEP
*STATIC
*NODE PRINT, NSET=SYMX
RF
*END STEP
"""


# The overlap is large enough that the quadratic faces' deviation from
# the circles (3e-7 for the master's 14 faces) is small beside it: with an
# overlap of 1e-3 the waviness of two differently divided curves alone
# moves the pressure by tens of percent, whatever the contact method.
RA, RB, RC, DELTA = 1.0, 1.5, 2.5, 0.02


def face_spacing(r, n):
    """Node spacing of n 3-node faces on a quarter circle of radius r."""
    return r * math.sin(math.pi / 4 / n)


def test_shrink_fit_plane_strain_curved_faces():
    """Quarter model, CPE8 (and CPE6) in CPE8 with curved faces, 28 slave
    faces over 14 master faces: the pressure at every slave point and
    every master node within 0.5 % of the closed form (two Lame
    cylinders), the total force p_slave (b + delta) pi / 2 within 0.5 %."""
    ps, pm = shrink_fit_pressure(RA, RB, RC, DELTA, h=face_spacing(RB + DELTA, 28))
    for inner in ("Q8", "T6"):
        mi, mo, deck = shrink_deck(inner, "Q8", "E")
        run = run_deck(f"shrink_pe_{inner}", deck).ok()
        s, mst, inc = contact_rows(run)
        es = np.max(np.abs(np.array(s["pressure"]) - ps)) / ps
        em = np.max(np.abs(np.array(mst["pressure"]) - pm)) / pm
        total = inc.block("CONTACT SUMMARY")["total_force"][0]
        et = abs(total / (ps * (RB + DELTA) * math.pi / 2) - 1)
        print(f"  shrink fit {inner} in Q8, plane strain, 28 over 14: p = {ps:.5g}, slave {es:.2e}, "
              f"master {em:.2e}, total {et:.2e}")
        assert es < 5e-3 and em < 5e-3 and et < 5e-3, (inner, es, em, et)


def test_shrink_fit_curved_non_nested_geometric_mismatch():
    """Curved faces divided without a common refinement (20 slave faces
    over 14 master faces): the two piecewise-quadratic circles differ by up
    to 6e-7 between them. With the automatic face penalty (3 E / h per
    area) every slave point and master node is within 1 %,
    the total force
    within 0.5 %; a penalty 40 times stiffer (1e7 per area) turns the
    mismatch into a scatter of tens of percent between neighbouring slave
    points (printed, a measurement of the method's limit: see
    docs/contact.md), while the master nodes stay within 2 %."""
    for pair, slave_tol in (("", 1e-2), (", PENALTY=1e7", None)):
        ps, pm = shrink_fit_pressure(RA, RB, RC, DELTA, h=0.0 if pair else face_spacing(RB + DELTA, 20))
        mi, mo, deck = shrink_deck("Q8", "Q8", "E", n_inner=20, n_outer=14, pair=pair)
        run = run_deck("shrink_pe_20_14" + ("_stiff" if pair else ""), deck).ok()
        s, mst, inc = contact_rows(run)
        es = np.max(np.abs(np.array(s["pressure"]) - ps)) / ps
        em = np.max(np.abs(np.array(mst["pressure"]) - pm)) / pm
        total = inc.block("CONTACT SUMMARY")["total_force"][0]
        et = abs(total / (ps * (RB + DELTA) * math.pi / 2) - 1)
        print(f"  shrink fit 20 over 14{pair or ', automatic penalty'}: slave {es:.2e}, master {em:.2e}, "
              f"total {et:.2e}")
        assert em < 2e-2 and et < 5e-3, (pair, em, et)
        if slave_tol:
            assert es < slave_tol, (pair, es)


def test_shrink_fit_axisymmetric_ring_totals():
    """The same fit as an axisymmetric slice of height 0.5 (CAX8 in CAX8,
    non-matching 5 over 3 faces; CAX4 in CAX4, 6 over 3): the pressure
    within 0.5 %, and the contact force is the whole ring's
    p 2 pi (b + delta) h."""
    for shape in ("Q8", "Q4"):
        # the face penalty's spacing: half the slave faces' 0.1 (CAX4: node-to-segment, 1000 E / h)
        ps, pm = shrink_fit_pressure(RA, RB, RC, DELTA, h=0.05 if shape == "Q8" else 0.0)
        mi, mo, deck = shrink_deck(shape, shape, "AX")
        run = run_deck(f"shrink_ax_{shape}", deck).ok()
        s, mst, inc = contact_rows(run)
        es = np.max(np.abs(np.array(s["pressure"]) - ps)) / ps
        em = np.max(np.abs(np.array(mst["pressure"]) - pm)) / pm
        total = inc.block("CONTACT SUMMARY")["total_force"][0]
        ring = ps * 2 * math.pi * (RB + DELTA) * 0.5
        print(f"  shrink fit {etype(shape, 'AX')}: slave {es:.2e}, master {em:.2e}, total {total:.6g} "
              f"vs {ring:.6g}")
        assert es < 5e-3 and em < 5e-3, (shape, es, em)
        assert abs(total - ring) < 5e-3 * ring, (total, ring)
