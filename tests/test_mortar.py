"""Segment-to-segment (dual mortar) contact and exact enforcement against
closed-form answers: the contact patch test on non-matching meshes in one
pass (linear and quadratic faces, either side coarser, plane and
axisymmetric), exact enforcement independent of the penalty, the penalty
converging to it, friction with the new coupling.

The two blocks of test_contact_quadratic.two_blocks: a lower (master) block
[0, 1] x [0, 1] on the ground, an upper (slave) block of height 1 a gap
g0 = 0.01 above it, its top pushed down by d = 0.03. Both are free to
expand sideways (one x support each), so the stress is uniaxial and the
interface pressure is exactly p = E (d - g0) / 2 with exact
non-penetration (plane stress, and the axisymmetric column alike)."""
import re

import numpy as np

from helpers import run_deck
from test_contact_quadratic import E, two_blocks, contact_rows

STS = ", TYPE=SURFACE TO SURFACE"
P_EXACT = E * (0.03 - 0.01) / 2.0


def patch_errors(run):
    """Largest slave and master pressure errors relative to P_EXACT, the
    total force's, and the rows."""
    s, mst, inc = contact_rows(run)
    ps, pm = np.array(s["pressure"]), np.array(mst["pressure"])
    assert all(st == "CLOSED" for st in s["state"]), s["state"]
    total = inc.block("CONTACT SUMMARY")["total_force"][0]
    return np.max(np.abs(ps - P_EXACT)) / P_EXACT, np.max(np.abs(pm - P_EXACT)) / P_EXACT, total, s, mst


def test_mortar_patch_test_exact_one_pass():
    """TYPE=SURFACE TO SURFACE with EXACT on meshes with no common
    refinement, either side coarser, 4- and 8-node elements, a triangle
    slave: every slave node's and master node's pressure is p to 1e-8,
    the total force p times the width (plane stress: unit thickness)."""
    cases = (("Q4", "Q4", 5, 7), ("Q4", "Q4", 5, 3), ("Q4", "Q4", 5, 13), ("Q4", "Q4", 7, 2),
             ("Q8", "Q8", 5, 7), ("Q8", "Q8", 4, 3), ("Q8", "T6", 5, 7), ("Q4", "Q8", 5, 7), ("Q8", "Q4", 3, 7))
    for lower, upper, n1, n2 in cases:
        run = run_deck(f"mortar_patch_{lower}_{upper}_{n1}_{n2}",
                       two_blocks(lower, upper, n1, n2, pair=STS + ", EXACT")).ok()
        es, em, total, s, _ = patch_errors(run)
        print(f"  {upper} slave on {lower} master, {n2} over {n1}: slave {es:.1e}, master {em:.1e}")
        assert es < 1e-8 and em < 1e-8, (lower, upper, n1, n2, es, em)
        assert abs(total - P_EXACT) < 1e-8 * P_EXACT, total
        # one coupling element per slave node, all of them
        assert len(s["node"]) == (n2 + 1 if upper == "Q4" else 2 * n2 + 1) and all(n > 0 for n in s["node"])


def test_exact_patch_test_direct_and_augmented():
    """The exact patch test (Q8 slave over Q4, 7 over 5, and Q4 13 over 5)
    on the condensed path, whose multipliers are solved directly (one solve
    per status, noted in the listing), and on the full path (the augmented
    Lagrangian): both give p at every node to 1e-8, and the same pressures
    to 1e-10 of p."""
    for lower, upper, n1, n2 in (("Q4", "Q8", 5, 7), ("Q4", "Q4", 5, 13)):
        deck = two_blocks(lower, upper, n1, n2, pair=STS + ", EXACT")
        pressures = {}
        for solve in ("CONDENSED", "FULL"):
            run = run_deck(f"mortar_patch_{solve.lower()}_{upper}_{n2}",
                           deck.replace("*STEP", f"*SOLVER, CONTACT SOLVE={solve}\n*STEP", 1)).ok()
            es, em, total, s, _ = patch_errors(run)
            assert es < 1e-8 and em < 1e-8, (solve, es, em)
            pressures[solve] = np.array(s["pressure"])
            notes = re.findall(r"exact contact: (\d+) direct multiplier solves", open(run.listing_path).read())
            if solve == "CONDENSED":
                # the first status (all closed from the gap's closure) is the answer
                assert notes and all(1 <= int(k) <= 3 for k in notes), notes
            else:
                assert not notes, notes
        diff = np.max(np.abs(pressures["CONDENSED"] - pressures["FULL"])) / P_EXACT
        print(f"  {upper} {n2} over {n1}: direct against augmented {diff:.1e}")
        assert diff < 1e-10, diff


def test_exact_direct_multipliers_through_constraints():
    """The exact patch test (Q4, 7 over 5) with *EQUATIONs making a master
    and a slave interface node's y displacement dependent on a neighbour's
    (consistent with the uniform answer): the direct multipliers take the
    constraint rows b_c through the constraints' transformation; condensed
    and full paths give p at every node to 1e-8 and agree to 1e-10."""
    deck = two_blocks("Q4", "Q4", 5, 7, pair=STS + ", EXACT")
    deck = deck.replace("*BOUNDARY\nGROUND", "*EQUATION\n2\n25, 2, 1.0, 27, 2, -1.0\n2\n10005, 2, 1.0, 10002, 2, -1.0\n"
                        "*BOUNDARY\nGROUND", 1)
    pressures = {}
    for solve in ("CONDENSED", "FULL"):
        run = run_deck(f"mortar_patch_equation_{solve.lower()}",
                       deck.replace("*STEP", f"*SOLVER, CONTACT SOLVE={solve}\n*STEP", 1)).ok()
        es, em, _, s, _ = patch_errors(run)
        assert es < 1e-8 and em < 1e-8, (solve, es, em)
        pressures[solve] = np.array(s["pressure"])
        notes = re.findall(r"exact contact: (\d+) direct multiplier solves", open(run.listing_path).read())
        assert bool(notes) == (solve == "CONDENSED"), notes
    diff = np.max(np.abs(pressures["CONDENSED"] - pressures["FULL"])) / P_EXACT
    print(f"  with *EQUATIONs at interface nodes: direct against augmented {diff:.1e}")
    assert diff < 1e-10, diff


def test_mortar_patch_test_axisymmetric():
    """CAX4 and CAX8 columns (r from 0.5 to 1.5) pressed the same way, free
    to expand radially (no radial support: in axisymmetry a radial shift is
    no rigid motion): the ring's pressure is p at every node to 1e-8 (the
    r weight in the dual functions and the mortar integrals)."""
    for shape, n1, n2 in (("Q4", 5, 7), ("Q8", 5, 7), ("Q4", 7, 3)):
        deck = two_blocks(shape, shape, n1, n2, state="AX", x0=0.5, pair=STS + ", EXACT")
        deck = deck.replace("ANCHOR, 1, 1\nTOPLEFT, 1, 1\n", "")
        run = run_deck(f"mortar_patch_ax_{shape}_{n1}_{n2}", deck).ok()
        es, em, total, _, _ = patch_errors(run)
        print(f"  CAX {shape} {n2} over {n1}: slave {es:.1e}, master {em:.1e}")
        assert es < 1e-8 and em < 1e-8, (shape, es, em)
        # the whole ring: p times the annulus' area pi (1.5^2 - 0.5^2)
        assert abs(total - P_EXACT * np.pi * 2.0) < 1e-8 * total, total


def test_mortar_penalty_uniform_and_converging_to_exact():
    """The mortar coupling with a penalty alone (no EXACT) still transmits
    a uniform pressure (its compliance is uniform: the spread of the
    pressures is round-off), lower than p by the penalty's compliance;
    the error falls in proportion to the penalty (three decades)."""
    errs = []
    for k in (1e5, 1e6, 1e7):
        run = run_deck(f"mortar_penalty_{k:g}", two_blocks("Q4", "Q4", 5, 7, pair=STS + f", PENALTY={k}")).ok()
        s, mst, _ = contact_rows(run)
        ps, pm = np.array(s["pressure"]), np.array(mst["pressure"])
        spread = (max(ps.max(), pm.max()) - min(ps.min(), pm.min())) / P_EXACT
        # series springs: the two blocks (2 / E per unit pressure) and 1 / k
        p_series = (0.03 - 0.01) / (2.0 / E + 1.0 / k)
        assert spread < 1e-9, (k, spread)
        assert abs(ps.mean() - p_series) < 1e-9 * p_series, (k, ps.mean(), p_series)
        errs.append(abs(ps.mean() - P_EXACT) / P_EXACT)
    print(f"  penalty 1e5, 1e6, 1e7: error {errs[0]:.1e}, {errs[1]:.1e}, {errs[2]:.1e}")
    assert errs[0] > errs[1] > errs[2] and errs[2] < 1e-4


def test_exact_independent_of_penalty():
    """EXACT with three penalties four decades apart (the penalty only sets
    the pace of the multiplier updates): the same pressures to 1e-9, and
    node-to-segment with EXACT is independent of its penalty too."""
    for pair, tag in ((STS, "sts"), (", TYPE=NODE TO SURFACE", "nts")):
        ref = None
        for k in (1e4, 1e6, 1e8):
            run = run_deck(f"exact_penalty_{tag}_{k:g}", two_blocks("Q4", "Q4", 5, 7,
                                                                    pair=pair + f", EXACT, PENALTY={k}")).ok()
            s, _, _ = contact_rows(run)
            ps = np.array(s["pressure"])
            if ref is None:
                ref = ps
            assert np.max(np.abs(ps - ref)) < 1e-9 * P_EXACT, (tag, k, np.max(np.abs(ps - ref)))


def test_mortar_exact_gap_opens_and_closes():
    """Pushed by less than the gap, nothing touches (every node OPEN, no
    force); pushed by 0.999 of it still open, by 1.001 of it every node
    closed with the exact pressure E (d - g0) / 2."""
    for d, closed in ((0.005, False), (0.00999, False), (0.01001, True)):
        run = run_deck("mortar_gap", two_blocks("Q4", "Q4", 5, 7, d=d, pair=STS + ", EXACT")).ok()
        s, _, inc = contact_rows(run)
        assert set(s["state"]) == {"CLOSED" if closed else "OPEN"}, (d, set(s["state"]))
        p = E * max(d - 0.01, 0.0) / 2.0
        assert np.max(np.abs(np.array(s["pressure"]) - p)) < 1e-8 * E * 0.01, (d, s["pressure"])


def test_mortar_frictional_patch_test_condensed_and_full():
    """The frictional patch test of test_friction (a uniform pressure p and
    shear s = mu p / 2 through two blocks, the upper one held by contact
    alone, starting open: the stabilised search) on 7 over 5 elements with
    the segment-to-segment coupling, penalty and EXACT, on the condensed
    and the full path: every point sticks, stresses, pressures, shear
    tractions and reactions uniform to 1e-8 of p (single-pass
    node-to-segment is 9.4 % off on these meshes), and the paths agree.
    The slave is the finer side: the multiplier on the master mesh, with
    the consistent master side (a frictional pair), one coupling element
    per master node."""
    from test_friction import MU, patch_deck, patch_errors
    pressures = {}
    for exact in ("", ", EXACT"):
        for solve in ("CONDENSED", "FULL"):
            deck = patch_deck(7, "single", solve).replace(
                f"*CONTACT PAIR, FRICTION={MU}\nSLV, MASTER\n",
                f"*CONTACT PAIR, FRICTION={MU}, TYPE=SURFACE TO SURFACE{exact}\nUPPERFACE, MASTER\n")
            run = run_deck(f"mortar_friction_patch_{solve.lower()}{'_exact' if exact else ''}", deck).ok()
            err, states, ratio = patch_errors(run)
            print(f"  7 over 5, mortar{exact}, {solve}: " + ", ".join(f"{k} {v:.1e}" for k, v in err.items()))
            assert states == {"STICK"}, states
            assert max(err.values()) < 1e-8 and ratio < MU, (exact, solve, err, ratio)
            assert re.search(r"coupling_elements 6\n", open(run.listing_path).read())
            pressures[exact, solve] = np.array(run.listing.increments[-1].block("CONTACT SLAVE", pair=1)["pressure"])
        assert np.max(np.abs(pressures[exact, "CONDENSED"] - pressures[exact, "FULL"])) < 1e-9 * pressures[exact, "FULL"].max()


def test_mortar_exact_unloading_and_update_search():
    """Pressed (EXACT, segment-to-segment), then released: at the release
    every node is OPEN with no force and the upper block is stress-free;
    with UPDATE SEARCH (the mortar integrals made again on the deformed
    configuration every increment) the pressed increment has the same
    pressures to 1e-9 (the blocks do not slide)."""
    release = """*STEP
*STATIC
*BOUNDARY
TOP, 2, 2, 0.0
*EL PRINT
S
*END STEP
"""
    for extra in ("", ", UPDATE SEARCH"):
        deck = two_blocks("Q4", "Q4", 5, 7, pair=STS + ", EXACT" + extra) + release
        run = run_deck("mortar_release" + extra.replace(", ", "_").replace(" ", "_").lower(), deck).ok()
        incs = run.listing.increments
        s_press = np.array(incs[0].block("CONTACT SLAVE")["pressure"])
        assert np.max(np.abs(s_press - P_EXACT)) < 1e-8 * P_EXACT, (extra, s_press)
        s_rel = incs[-1].block("CONTACT SLAVE")
        assert set(s_rel["state"]) == {"OPEN"} and np.max(np.abs(s_rel["pressure"])) == 0.0, (extra, s_rel["state"])
        st = incs[-1].block("ELEMENT S")
        assert max(np.max(np.abs(st["S22"])), np.max(np.abs(st["S11"]))) < 1e-9 * P_EXACT, extra


def test_mortar_curved_interface_shrink_fit():
    """A curved interface: the plane-strain shrink fit of
    test_contact_quadratic (CPE8 in CPE8, 20 and 28 slave faces over 14
    master faces around a quarter, no common refinement) with segment-to-
    segment contact and EXACT against Lame's closed form: the total force
    within 1e-4 (measured 2e-5; node-to-segment with its face penalty
    3e-3), the master pressures within 2e-3 (measured 7e-4, 3e-4), the
    slave pressures within 1e-2 (measured 1.8e-3, 7.1e-3). Not 1e-8 as on
    straight faces: the two piecewise-quadratic circles differ by about
    6e-7 of the radius between their nodes, and exact enforcement turns
    that into pressure (docs/contact.md)."""
    import math
    from test_contact_quadratic import DELTA, RA, RB, RC, shrink_deck, shrink_fit_pressure
    ps, pm = shrink_fit_pressure(RA, RB, RC, DELTA, h=0.0)
    for n_inner in (20, 28):
        _, _, deck = shrink_deck("Q8", "Q8", "E", n_inner=n_inner, n_outer=14, pair=STS + ", EXACT")
        run = run_deck(f"mortar_shrink_{n_inner}", deck).ok()
        s, mst, inc = contact_rows(run)
        es = np.max(np.abs(np.array(s["pressure"]) - ps)) / ps
        em = np.max(np.abs(np.array(mst["pressure"]) - pm)) / pm
        total = inc.block("CONTACT SUMMARY")["total_force"][0]
        et = abs(total / (ps * (RB + DELTA) * math.pi / 2) - 1)
        print(f"  shrink fit {n_inner} over 14, mortar EXACT: slave {es:.1e}, master {em:.1e}, total {et:.1e}")
        assert et < 1e-4 and em < 2e-3 and es < 1e-2, (n_inner, es, em, et)


def test_mortar_cards_refused_at_their_line():
    """SYMMETRIC with TYPE=SURFACE TO SURFACE, EXACT with INTERACTION= and a
    node-set slave for segment-to-segment contact stop at the card's line,
    saying why."""
    from test_decks_contact import blocks, error_at, interaction
    error_at("mortar_symmetric", blocks("*CONTACT PAIR, SYMMETRIC, TYPE=SURFACE TO SURFACE\nUPPERFACE, MASTER\n"),
             "*CONTACT PAIR, SYMMETRIC, TYPE=SURFACE TO SURFACE", "exclude each other")
    error_at("mortar_exact_interaction", blocks(interaction() + "*CONTACT PAIR, INTERACTION=SI1, EXACT\n"
                                                "SLAVE, MASTER\n"),
             "*CONTACT PAIR, INTERACTION=SI1, EXACT", "PRESSURE-OVERCLOSURE=HARD")
    error_at("mortar_node_slave", blocks("*CONTACT PAIR, TYPE=SURFACE TO SURFACE\nSLAVE, MASTER\n"),
             "SLAVE, MASTER", "element-based slave surface")


def graded(deck, warp_lower, warp_upper):
    """The two blocks' deck with every node's x moved by a warp of [0, 1]
    onto itself (columns stay vertical: the elements stay rectangles of
    graded widths), the lower block (nodes below 10001) and the upper one
    each by its own."""
    lines = deck.splitlines()
    start = lines.index("*NODE, NSET=ALLN") + 1
    for i in range(start, len(lines)):
        if lines[i].startswith("*"):
            break
        nid, x, y = lines[i].split(",")
        warp = warp_lower if int(nid) < 10001 else warp_upper
        lines[i] = f"{nid}, {float(warp(float(x)))!r}, {y.strip()}"
    return "\n".join(lines) + "\n"


def test_mortar_master_multipliers_patch_test_graded():
    """The multiplier on the master mesh (a slave finer than its master,
    straight faces, no friction: contact_master_multipliers) on graded
    meshes with no common refinement (master x + 0.12 sin(pi x), slave
    x - 0.1 sin(2 pi x)), 13 and 9 slave faces over 5 and 4 master faces,
    EXACT: every slave and master node's pressure is p to 1e-8 (the
    lumped master side is consistent for the normal gap of straight
    faces: the psi_m-weighted mean of the slave surface lies on the line,
    however far off node m along it), the total p times the width; one
    coupling element per master node, one slave row per slave node (the
    field at the node; its force the node's, the rows summing to the total
    to 1e-12). The selection: 3 over 5 (a coarser slave) keeps
    the dual mortar's one element per slave node (so does a frictional
    pair: test_mortar_frictional_patch_test_condensed_and_full)."""
    lower = lambda x: x + 0.12 * np.sin(np.pi * x)  # noqa: E731
    upper = lambda x: x - 0.1 * np.sin(2.0 * np.pi * x)  # noqa: E731
    for n1, n2 in ((5, 13), (4, 9)):
        deck = graded(two_blocks("Q4", "Q4", n1, n2, pair=STS + ", EXACT"), lower, upper)
        run = run_deck(f"mortar_master_graded_{n1}_{n2}", deck).ok()
        es, em, total, s, mst = patch_errors(run)
        ncfe = int(re.search(r"coupling_elements (\d+)", open(run.listing_path).read()).group(1))
        print(f"  graded Q4 {n2} over {n1}: slave {es:.1e}, master {em:.1e}, {ncfe} coupling elements")
        assert es < 1e-8 and em < 1e-8 and abs(total - P_EXACT) < 1e-8 * P_EXACT, (n1, n2, es, em, total)
        assert ncfe == n1 + 1 and len(s["node"]) == n2 + 1 and all(n > 0 for n in s["node"]), (ncfe, s["node"])
        # a row's force is the force on its node, int lambda_h N_j da: the
        # rows sum to the total, and under a uniform p it is p times the
        # node's consistent area
        fs, area, ps = (np.array(s[k]) for k in ("force", "area", "pressure"))
        assert abs(fs.sum() - total) < 1e-12 * total, (fs.sum(), total)
        assert np.max(np.abs(fs - ps * area)) < 1e-8 * total, np.max(np.abs(fs - ps * area))
    run = run_deck("mortar_master_coarser_slave", two_blocks("Q4", "Q4", 5, 3, pair=STS + ", EXACT")).ok()
    assert int(re.search(r"coupling_elements (\d+)", open(run.listing_path).read()).group(1)) == 4
