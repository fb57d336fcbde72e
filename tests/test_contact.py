"""CFE contact against closed-form answers: two blocks with an initial gap
and non-matching meshes, pressed and released.

The upper (slave) block has 10 elements across, the lower (master) block 5:
the meshes do not match (every other slave node faces the middle of a
master edge). Single-pass node-to-segment contact transmits a uniform
pressure exactly on such nested meshes; on meshes with no common
refinement (7 over 5) it does not (the contact patch test), and
test_general_nonmatching_patch_error measures that error."""
from decks import grid, node_lines, quad_lines
from helpers import rel_err, run_deck

E, NU, W, H1, H2, G0 = 1000.0, 0.3, 1.0, 1.0, 1.0, 0.01
NX1, NY1, NX2, NY2 = 5, 5, 10, 4


def blocks_deck(steps, pair_params=""):
    """Lower block (master) on the ground, upper block (slave) G0 above it.
    steps: list of *STEP bodies."""
    n1, ids1, q1 = grid(NX1, NY1, 0.0, W, 0.0, H1)
    n2, ids2, q2 = grid(NX2, NY2, 0.0, W, H1 + G0, H1 + G0 + H2, first_node=1001)
    nodes = {**n1, **n2}
    top1 = [ids1[i, NY1] for i in range(NX1 + 1)]
    bottom1 = [ids1[i, 0] for i in range(NX1 + 1)]
    bottom2 = [ids2[i, 0] for i in range(NX2 + 1)]
    top2 = [ids2[i, NY2] for i in range(NX2 + 1)]
    # element faces S3 (node 3 -> 4) of the lower block's top row
    top_elems = [NX1 * (NY1 - 1) + i + 1 for i in range(NX1)]
    body = "".join(steps)
    return f"""*HEADING
two blocks, gap {G0}
*NODE, NSET=ALLN
{node_lines(nodes)}*ELEMENT, TYPE=CPS4, ELSET=LOWER
{quad_lines(q1, 1)}*ELEMENT, TYPE=CPS4, ELSET=UPPER
{quad_lines(q2, 1001)}*NSET, NSET=GROUND
{", ".join(map(str, bottom1))}
*NSET, NSET=ANCHOR
{bottom1[0]}
*NSET, NSET=SLAVE
{", ".join(map(str, bottom2))}
*NSET, NSET=TOP
{", ".join(map(str, top2))}
*NSET, NSET=TOPLEFT
{top2[0]}
*ELSET, ELSET=LOWERTOP
{", ".join(map(str, top_elems))}
*SURFACE, NAME=MASTER
LOWERTOP, S3
*MATERIAL, NAME=M
*ELASTIC
{E}, {NU}
*SOLID SECTION, ELSET=LOWER, MATERIAL=M
*SOLID SECTION, ELSET=UPPER, MATERIAL=M
*CONTACT PAIR{pair_params}
SLAVE, MASTER
*BOUNDARY
GROUND, 2, 2
ANCHOR, 1, 1
TOPLEFT, 1, 1
{body}"""


def push_step(d, incs=1):
    return f"""*STEP
*STATIC
{1.0 / incs}, 1.0
*BOUNDARY
TOP, 2, 2, {-d}
*NODE PRINT, NSET=TOP
U
*EL PRINT, ELSET=UPPER
S
*END STEP
"""


def series_pressure(d):
    return E * (d - G0) / (H1 + H2)


def contact_blocks(inc, pair=1):
    return inc.block("CONTACT SLAVE", pair=pair), inc.block("CONTACT MASTER", pair=pair), \
        inc.block("CONTACT SUMMARY", pair=pair)


def test_blocks_apart_no_force_no_stress():
    d = 0.5 * G0
    run = run_deck("contact_apart", blocks_deck([push_step(d)])).ok()
    inc = run.listing.increments[-1]
    slave, master, summ = contact_blocks(inc)
    assert all(s == "OPEN" for s in slave["state"]), slave["state"]
    scale = E * G0 / (H1 + H2)
    assert max(abs(slave["pressure"])) < 1e-6 * scale, max(abs(slave["pressure"]))
    assert max(abs(inc.block("ELEMENT S", set="UPPER")["S22"])) < 1e-6 * scale


def test_blocks_pressed_uniform_series_spring_pressure():
    d = 3 * G0
    run = run_deck("contact_pressed", blocks_deck([push_step(d, 2)])).ok()
    inc = run.listing.increments[-1]
    slave, master, summ = contact_blocks(inc)
    p = series_pressure(d)
    assert all(s == "CLOSED" for s in slave["state"]), slave["state"]
    err_s = max(abs(slave["pressure"] - p)) / p
    assert err_s < 0.005, f"slave pressure error {err_s:.4f}"
    err_m = max(abs(master["pressure"] - p)) / p
    assert err_m < 0.05, f"master pressure error {err_m:.4f}"
    s22 = inc.block("ELEMENT S", set="UPPER")["S22"]
    assert max(abs(s22 + p)) / p < 0.005
    assert rel_err(summ["total_force"][0], p * W) < 1e-3


def test_unloading_opens_every_cfe():
    d = 3 * G0
    back = push_step(d, 2).replace(f"TOP, 2, 2, {-d}", "TOP, 2, 2, 0.0")
    run = run_deck("contact_unload", blocks_deck([push_step(d, 2), back])).ok()
    last = run.listing.increments[-1]
    slave, master, summ = contact_blocks(last)
    assert all(s == "OPEN" for s in slave["state"])
    # the open penalty (1e-12 of the closed one) leaves a tensile force
    # many orders below the loaded value
    assert abs(summ["total_force"][0]) < 1e-6 * series_pressure(d) * W
    assert max(abs(last.block("NODE U", set="TOP")["U2"])) < 1e-12
    assert max(abs(last.block("ELEMENT S", set="UPPER")["S22"])) < 1e-6 * series_pressure(d)


def test_switch_at_sign_change_of_normal_force():
    for factor, closed in ((0.999, False), (1.001, True)):
        run = run_deck("contact_switch", blocks_deck([push_step(factor * G0)])).ok()
        slave, _, summ = contact_blocks(run.listing.increments[-1])
        states = set(slave["state"])
        assert states == {"CLOSED" if closed else "OPEN"}, (factor, states)
        if closed:
            assert rel_err(summ["total_force"][0], series_pressure(factor * G0) * W) < 0.01


def test_penalty_insensitivity_two_decades():
    d = 3 * G0
    # The automatic rule: 1000 E / h per unit area, h = smallest adjacent edge.
    auto = 1000 * E / (W / NX2)
    pressures = []
    for factor in (1, 10, 100):
        run = run_deck("contact_penalty", blocks_deck([push_step(d)], f", PENALTY={factor * auto}")).ok()
        slave, _, _ = contact_blocks(run.listing.increments[-1])
        pressures.append(slave["pressure"].mean())
    change = (max(pressures) - min(pressures)) / max(pressures)
    assert change < 0.005, f"pressures {pressures}"


def force_driven_deck(pair_params="", solver=""):
    load = 2.0
    step = f"""*STEP
*STATIC
*CLOAD
TOP, 2, {-load / (NX2 + 1)}
*NODE PRINT, NSET=TOP
U
*END STEP
"""
    deck = blocks_deck([step], pair_params)
    if solver:
        deck = deck.replace("*CONTACT PAIR", f"*SOLVER, TYPE={solver}\n*CONTACT PAIR")
    return deck, load


def test_body_held_away_from_contact_clear_error():
    """An upper block with an initial gap pulled away from the lower one:
    nothing holds it, whatever the stabilisation of the open contact; the
    run stops naming a node and saying why, and writes no increment."""
    deck, _ = force_driven_deck()
    deck = deck.replace(f"TOP, 2, {-2.0 / (NX2 + 1)}", f"TOP, 2, {2.0 / (NX2 + 1)}")
    run = run_deck("contact_pulled_away", deck)
    assert run.rc != 0
    assert "singular stiffness at node" in run.stderr and "held only by open contact" in run.stderr, run.stderr
    assert "NaN" not in open(run.listing_path).read()
    assert "=== INCREMENT" not in open(run.listing_path).read()


def test_body_held_only_by_contact_solved():
    """Force-driven upper block starting 1e-3 above the lower one, held by
    nothing but the contact: the stiffness with every CFE open is singular,
    the open CFEs are stabilised until the status settles, then the
    iteration goes on with the nominal open penalty. With every solver and
    the default open penalty (and with a larger one): all slave nodes close,
    the contact force equals the load and the pressure the uniform one."""
    for tag, params, solver in (("cholmod", "", ""), ("umfpack", "", "UMFPACK"), ("skyline", "", "SKYLINE"),
                                ("open", ", OPEN PENALTY=1e-6", "")):
        deck, load = force_driven_deck(params, solver)
        run = run_deck("contact_force_driven_" + tag, deck)
        assert "NaN" not in open(run.listing_path).read()
        run.ok()
        slave, _, summ = contact_blocks(run.listing.increments[-1])
        assert all(s == "CLOSED" for s in slave["state"]), tag
        assert rel_err(summ["total_force"][0], load) < 1e-6, (tag, summ["total_force"])
        assert max(abs(slave["pressure"] - load / W)) / (load / W) < 0.005, tag


def test_general_nonmatching_patch_error():
    """Meshes with no common refinement (7 slave over 5 master elements):
    single-pass node-to-segment does not pass the contact patch test. The
    measured errors (slave 9.5%, master 6.8% of p at the time of writing)
    are guarded here so that a change to the method shows up."""
    global NX2
    saved, NX2 = NX2, 7
    try:
        d = 3 * G0
        run = run_deck("contact_general", blocks_deck([push_step(d)])).ok()
    finally:
        NX2 = saved
    slave, master, summ = contact_blocks(run.listing.increments[-1])
    p = series_pressure(d)
    err_s = max(abs(slave["pressure"] - p)) / p
    err_m = max(abs(master["pressure"] - p)) / p
    assert rel_err(summ["total_force"][0], p * W) < 1e-3, "total force must still balance"
    assert err_s < 0.12 and err_m < 0.10, f"slave {err_s:.4f}, master {err_m:.4f}"


def test_update_search_on_deformed_configuration():
    """Searching again each increment on the deformed configuration gives
    the same answer here (the blocks do not slide) and keeps the listing's
    coupling count."""
    d = 3 * G0
    base = run_deck("contact_nosearch", blocks_deck([push_step(d, 2)])).ok()
    upd = run_deck("contact_update", blocks_deck([push_step(d, 2)], ", UPDATE SEARCH")).ok()
    s0, _, _ = contact_blocks(base.listing.increments[-1])
    s1, _, _ = contact_blocks(upd.listing.increments[-1])
    assert max(abs(s0["pressure"] - s1["pressure"])) < 1e-6 * series_pressure(d)


def test_symmetric_two_pass_passes_patch_test():
    """SYMMETRIC (two passes, each surface the slave of one) on the meshes
    with no common refinement: the uniform pressure is transmitted on both
    sides within 0.5%."""
    global NX2
    saved, NX2 = NX2, 7
    try:
        d = 3 * G0
        deck = blocks_deck([push_step(d)], ", SYMMETRIC")
        # the upper block's bottom faces (S1 of its first row) as a surface
        bottom = ", ".join(str(1001 + i) for i in range(NX2))
        deck = deck.replace("*SURFACE, NAME=MASTER", f"*ELSET, ELSET=UPPERBOTTOM\n{bottom}\n*SURFACE, NAME=UPPERFACE\n"
                            "UPPERBOTTOM, S1\n*SURFACE, NAME=MASTER").replace("SLAVE, MASTER", "UPPERFACE, MASTER")
        run = run_deck("contact_symmetric", deck).ok()
    finally:
        NX2 = saved
    inc = run.listing.increments[-1]
    assert not inc.has("CONTACT SLAVE", pair=2), "the second pass is reported with the first"
    slave, master, summ = contact_blocks(inc)
    p = series_pressure(d)
    err_s = max(abs(slave["pressure"] - p)) / p
    err_m = max(abs(master["pressure"] - p)) / p
    assert err_s < 0.005 and err_m < 0.005, f"slave {err_s:.4f}, master {err_m:.4f}"
    assert rel_err(summ["total_force"][0], p * W) < 1e-3


def test_unsettled_status_bisects_then_stops_keeping_completed_increments():
    """MAXIT=1 leaves no room for a status change: the increment that needs
    one is bisected CUTBACKS times, then the run stops naming the nodes; the
    increments completed before it stay in the listing."""
    approach = push_step(0.5 * G0)             # step 1: no contact, settles at once
    press = push_step(3 * G0)                  # step 2: contact, needs a change
    deck = blocks_deck([approach, press]).replace("*CONTACT PAIR", "*CONTACT CONTROLS, MAXIT=1, CUTBACKS=2\n*CONTACT PAIR")
    run = run_deck("contact_unsettled", deck)
    assert run.rc != 0
    assert "did not settle" in run.stderr and "after 2 bisections" in run.stderr, run.stderr
    text = open(run.listing_path).read()
    assert text.count("increment bisected") == 2, text.count("increment bisected")
    incs = run.listing.increments
    assert len(incs) == 1 and incs[0].step == 1, [(i.step, i.number) for i in incs]


def tilted_step(d_left):
    """The upper block's top pushed down by d_left at x = 0 falling
    linearly to 0 at x = W: its left part closes, its right part stays open
    but moves, so the open CFEs carry their open penalty force."""
    ids = [1001 + NY2 * (NX2 + 1) + i for i in range(NX2 + 1)]
    lines = "".join(f"{n}, 2, 2, {-d_left * (1.0 - i / NX2):.17g}\n" for i, n in enumerate(ids))
    return push_step(d_left).replace(f"TOP, 2, 2, {-d_left}\n", lines).replace(
        "*END STEP", "*NODE FILE\nCSTRESS\n*END STEP")


def test_open_points_report_zero_force_and_pressure():
    """Open coupling points (status OPEN) report exactly zero force and
    pressure in the listing, the contact table and the nodal pressure
    field, and the pair's totals are the sums over the closed rows; the
    open points moved, so their stabilising force is not zero."""
    import csv
    import numpy as np
    from test_decks_vtu import series
    run = run_deck("contact_open_rows", blocks_deck([tilted_step(3 * G0)]), args=("--vtu",)).ok()
    inc = run.listing.increments[-1]
    slave, master, summ = contact_blocks(inc)
    state = np.array(slave["state"])
    is_open = state == "OPEN"
    assert 2 <= is_open.sum() <= len(state) - 2, state
    # the open points moved towards the master but stayed apart
    assert np.all(slave["gap"][is_open] > 0.0) and np.all(slave["gap"][is_open] < 0.999 * G0), slave.rows
    assert np.all(slave["force"][is_open] == 0.0) and np.all(slave["pressure"][is_open] == 0.0), slave.rows
    assert np.all(slave["force"][~is_open] > 0.0)
    # master nodes beyond the closed points' segments carry nothing
    assert np.any(master["force"] == 0.0) and np.all(master["force"] >= 0.0), master.rows
    closed = slave["force"][~is_open]
    assert summ["closed"][0] == (~is_open).sum()
    assert abs(summ["total_force"][0] - closed.sum()) <= 1e-12 * closed.sum(), (summ.rows, closed.sum())
    assert abs(summ["resultant_y"][0] + closed.sum()) <= 1e-9 * closed.sum(), summ.rows
    # the contact table: every OPEN row exactly 0, the closed rows the listing's
    with open(run.listing_path[:-4] + "_contact.csv") as f:
        rows = [r for r in csv.DictReader(f) if r["side"] == "slave"]
    assert [r["state"] for r in rows] == list(state)
    for r in rows:
        if r["state"] == "OPEN":
            assert float(r["force"]) == 0.0 and float(r["pressure"]) == 0.0, r
            assert not r["force"].startswith("-"), r
    assert np.allclose([float(r["force"]) for r in rows], slave["force"], rtol=1e-7, atol=0.0)
    # the nodal pressure field: zero at the open slave nodes
    _, meshes = series(run, "contact_open_rows")
    at = {int(n): k for k, n in enumerate(meshes[-1].point_data["NodeId"])}
    cstress = meshes[-1].point_data["CSTRESS"]
    for n, p, st in zip(slave["node"], slave["pressure"], state):
        if st == "OPEN":
            assert cstress[at[int(n)]] == 0.0, (n, cstress[at[int(n)]])
        else:
            assert np.isclose(cstress[at[int(n)]], p, rtol=1e-14, atol=0.0), (n, p, cstress[at[int(n)]])
