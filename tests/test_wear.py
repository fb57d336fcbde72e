"""Archard wear at the coupling elements (*WEAR, docs/contact.md "Wear").

The model (punch_deck): a flat punch (10 x 2) pressed by a uniform
pressure p onto a base of the same width (10 x 2, bottom held), both
plane stress, the punch rubbed sideways by a prescribed displacement
d(t) = stroke sin(2 pi t) (*AMPLITUDE, DEFINITION=PERIODIC) for one or
more cycles. With every node of both bodies held in x (rigid=True) the
stress is homogeneous: the contact pressure is p at every point and
every point slides by the same slip, so Archard's law integrates in
closed form, h = N k p s on both surfaces (s the accumulated slip, N the
cycle jump). With only the punch's top held in x (rigid=False) the
punch shears, the pressure peaks at its edges and the points stick and
slip in turn: Archard's balance (the worn area of each surface is k N
times the sum over increments and points of F |ds|) has no closed form
but must hold to round-off.

Tolerances: the closed forms to 1e-11 relative (the listing's 16 digits;
the solve's round-off is 1e-14 of the pressure), the balance to 1e-10
relative (the requirement of issue 33), the punch's sinking to 1e-12 of
its displacement.
"""
import math

from decks import grid, node_lines, quad_lines
from helpers import run_deck

P = 100.0
MU = 0.3
K_SLAVE, K_MASTER = 1.0e-6, 2.0e-6
STROKE = 0.01
THICKNESS = 1.0


def punch_mesh(nx_base=10, nx_punch=7, base_span=(0.0, 10.0)):
    """The base (nx_base x 2 CPS4 over base_span, y -2..0) and the punch
    (nx_punch x 2 CPS4, x 0..10, y 0..2): grid()'s nodes, ids and quads of
    each, the punch's numbered after the base's."""
    n1, ids1, q1 = grid(nx_base, 2, base_span[0], base_span[1], -2, 0)
    n2, ids2, q2 = grid(nx_punch, 2, 0, 10, 0, 2, first_node=len(n1) + 1)
    return (n1, ids1, q1), (n2, ids2, q2)


def stroke_steps(steady, cycles, inc):
    """Step 2 (and 3) of the deck: the rubbing. Not steady: `cycles`
    cycles of d = stroke sin(2 pi t) from rest. Steady: the punch slid to
    -stroke (step 2), then `cycles` cycles of d = -stroke cos(2 pi t)
    (step 3), each of which starts sliding and reverses twice, as the next."""
    out = "*NODE PRINT, NSET=PUNCHX\nU\n*END STEP\n"
    if not steady:
        return (f"*STEP\n*STATIC\n{inc}, {cycles}.\n*BOUNDARY, AMPLITUDE=SLIDE\nPUNCHX, 1, 1, {STROKE}\n" + out)
    return (f"*STEP\n*STATIC\n0.5, 1.\n*BOUNDARY\nPUNCHX, 1, 1, {-STROKE}\n" + out +
            f"*STEP\n*STATIC\n{inc}, {cycles}.\n*BOUNDARY, AMPLITUDE=CYCLE\nPUNCHX, 1, 1, {STROKE}\n" + out)


def punch_deck(nx_base=10, nx_punch=7, kind="SURFACE TO SURFACE", jump=None, cycles=1, inc=0.05,
               rigid=True, wear=True, friction=True, symmetric=False, base_span=(0.0, 10.0), steady=False,
               maxit=None):
    """The punch on its base (module docstring): step 1 presses, the next
    rub (stroke_steps). A node-to-segment pair is SMALL SLIDING (paired
    once: a slave node slid past the master's end keeps its coupling)."""
    (n1, ids1, q1), (n2, ids2, q2) = punch_mesh(nx_base, nx_punch, base_span)
    e0 = len(q1)
    punch_held = n2 if rigid else [ids2[i, 2] for i in range(nx_punch + 1)]
    punch_set = "".join(f"{n},\n" for n in punch_held)
    base_held = n1 if rigid else [ids1[i, 0] for i in range(nx_base + 1)]
    base_set = "".join(f"{n},\n" for n in base_held)
    bottom = "".join(f"{ids1[i, 0]},\n" for i in range(nx_base + 1))
    ms = "".join(f"{nx_base + i + 1}, S3\n" for i in range(nx_base))
    ss = "".join(f"{e0 + i + 1}, S1\n" for i in range(nx_punch))
    tops = "".join(f"{e0 + nx_punch + i + 1}, S3\n" for i in range(nx_punch))
    cards = "*FRICTION\n0.3, 1e7\n" if friction else ""
    if wear:
        cards += f"*WEAR\n{K_SLAVE}, {K_MASTER}" + (f", {jump}" if jump else "") + "\n"
    pair = f"*CONTACT PAIR, INTERACTION=WI, TYPE={kind}" + (", SYMMETRIC" if symmetric else "")
    if kind == "NODE TO SURFACE" and not symmetric:
        pair += ", SMALL SLIDING"
    if maxit:
        pair = f"*CONTACT CONTROLS, MAXIT={maxit}\n" + pair
    return (f"*NODE\n{node_lines({**n1, **n2})}*ELEMENT, TYPE=CPS4, ELSET=BASE\n{quad_lines(q1)}"
            f"*ELEMENT, TYPE=CPS4, ELSET=PUNCH\n{quad_lines(q2, first=e0 + 1)}"
            f"*NSET, NSET=BASEX\n{base_set}*NSET, NSET=PUNCHX\n{punch_set}*NSET, NSET=BOTTOM\n{bottom}"
            f"*SURFACE, NAME=MS\n{ms}*SURFACE, NAME=SS\n{ss}*SURFACE, NAME=TOPS\n{tops}"
            "*MATERIAL, NAME=ST\n*ELASTIC\n200000., 0.3\n"
            f"*SOLID SECTION, ELSET=BASE, MATERIAL=ST\n{THICKNESS}\n"
            f"*SOLID SECTION, ELSET=PUNCH, MATERIAL=ST\n{THICKNESS}\n"
            "*SURFACE INTERACTION, NAME=WI\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n1e7\n"
            f"{cards}{pair}\nSS, MS\n"
            "*AMPLITUDE, NAME=SLIDE, DEFINITION=PERIODIC\n1, 6.283185307179586, 0., 0.\n0., 1.\n"
            "*AMPLITUDE, NAME=CYCLE, DEFINITION=PERIODIC\n1, 6.283185307179586, 0., 0.\n-1., 0.\n"
            "*BOUNDARY\nBOTTOM, 2, 2\nBASEX, 1, 1\n"
            f"*STEP\n*STATIC\n1., 1.\n*BOUNDARY\nPUNCHX, 1, 1, 0.\n*DSLOAD\nTOPS, P, {P}\n*END STEP\n"
            + stroke_steps(steady, cycles, inc))


def rubbing_increments(run, step=2):
    """The listing's increments of a rubbing step."""
    return [inc for inc in run.listing.increments if inc.step == step]


def check_depth_is_k_p_s(name, **kw):
    """Module docstring, rigid=True: at every increment and slave row the
    slave's depth is N k_slave p s and the master's at the point N k_master
    p s (s the row's accumulated slip), every master node's depth N
    k_master p s; the punch sinks by the depth worn before the increment."""
    jump = kw.get("jump") or 1.0
    run = run_deck(name, punch_deck(**kw)).ok()
    y0 = None
    s_before = 0.0
    for inc in rubbing_increments(run):
        sl, ms = inc.block("CONTACT SLAVE", pair=1), inc.block("CONTACT MASTER", pair=1)
        s = sl["slip"][0]
        assert s > 0.0, s
        for j in range(len(sl)):
            assert sl["state"][j] == "SLIP", (inc.attrs, j, sl["state"][j])
            assert abs(sl["pressure"][j] - P) <= 1e-12 * P, (sl["pressure"][j], j)
            assert abs(sl["slip"][j] - s) <= 1e-12 * s, (sl["slip"][j], s)
            assert abs(sl["wear_slave"][j] - jump * K_SLAVE * P * s) <= 1e-11 * jump * K_SLAVE * P * s, \
                (inc.attrs, j, sl["wear_slave"][j], jump * K_SLAVE * P * s)
            assert abs(sl["wear_master"][j] - jump * K_MASTER * P * s) <= 1e-11 * jump * K_MASTER * P * s, \
                (inc.attrs, j, sl["wear_master"][j])
            # the worn slave surface: the point lifted by its depth
            assert abs(sl["worn_y"][j] - sl["y"][j] - sl["wear_slave"][j]) <= 1e-15, (sl["worn_y"][j], j)
        for j in range(len(ms)):
            assert abs(ms["wear_master"][j] - jump * K_MASTER * P * s) <= 1e-11 * jump * K_MASTER * P * s, \
                (inc.attrs, j, ms["node"][j], ms["wear_master"][j])
            assert ms["wear_slave"][j] == 0.0
            assert abs(ms["worn_y"][j] - ms["y"][j] + ms["wear_master"][j]) <= 1e-15, (ms["worn_y"][j], j)
        # the punch sinks by both depths worn up to the increment before
        # (each converged increment's wear moves the next one's gap)
        if y0 is None:
            y0 = sl["y"][0]
        sink = jump * (K_SLAVE + K_MASTER) * P * s_before
        for j in range(len(sl)):
            assert abs(y0 - sl["y"][j] - sink) <= 1e-12 * abs(y0), (inc.attrs, j, y0 - sl["y"][j], sink)
        s_before = s
    return run


def test_flat_punch_depth_is_k_p_s_dual_mortar():
    """Non-matching meshes (7 punch faces on 10 base faces), the dual
    mortar (TYPE=SURFACE TO SURFACE): h = k p s on both surfaces to round-
    off at every increment of a cycle; the slip of a cycle is about four
    strokes less the elastic stick offset mu p / (stick slope)."""
    run = check_depth_is_k_p_s("wear_punch_mortar")
    s = rubbing_increments(run)[-1].block("CONTACT SLAVE", pair=1)["slip"][0]
    assert abs(s - (4 * STROKE - 5 * MU * P / 1e7)) < 1e-3 * s, s


def test_flat_punch_depth_is_k_p_s_node_to_surface():
    """The paper's node-to-segment coupling on matching meshes (10 on 10):
    h = k p s on both surfaces to round-off."""
    check_depth_is_k_p_s("wear_punch_nts", nx_punch=10, kind="NODE TO SURFACE")


def test_flat_punch_depth_is_k_p_s_master_multiplier():
    """The slave the finer side (20 punch faces on 10): the multiplier on
    the master mesh, whose couplings belong to the master nodes; its slave
    rows are the slave nodes with the field there: h = k p s on both
    surfaces to round-off."""
    check_depth_is_k_p_s("wear_punch_master_space", nx_punch=20)


def consistent_areas(xs):
    """Consistent nodal areas int N_i da of a straight surface through the
    x positions xs, thickness THICKNESS: {x: area}."""
    xs = sorted(xs)
    a = {x: 0.0 for x in xs}
    for x0, x1 in zip(xs, xs[1:]):
        a[x0] += 0.5 * (x1 - x0) * THICKNESS
        a[x1] += 0.5 * (x1 - x0) * THICKNESS
    return a


def check_balance(name, jump=None, nx_punch=7, **kw):
    """Module docstring, rigid=False, the base wider than the punch (the
    punch's edges on the base's faces): after each increment the worn area
    of each surface, sum_i h_i int N_i da over its nodes (reference
    positions), equals k N times the sum over the increments so far and
    the slave rows of F |ds| (the row's compressive force and increment
    slip), to 1e-10."""
    n = jump or 1.0
    span = (-2.0, 12.0)
    bisections = kw.pop("bisections", 0)
    run = run_deck(name, punch_deck(rigid=False, jump=jump, nx_punch=nx_punch, nx_base=14, base_span=span,
                                    **kw)).ok()
    (n1, ids1, _), (n2, ids2, _) = punch_mesh(14, nx_punch, span)
    a_slave = consistent_areas([n2[ids2[i, 0]][0] for i in range(nx_punch + 1)])
    a_master = consistent_areas([n1[ids1[i, 2]][0] for i in range(15)])
    work = 0.0
    nonuniform = False
    # (from the pressing step on: the punch's edges slide outwards as it
    # is pressed)
    for inc in run.listing.increments:
        sl, ms = inc.block("CONTACT SLAVE", pair=1), inc.block("CONTACT MASTER", pair=1)
        work += sum(f * abs(ds) for f, ds in zip(sl["force"], sl["slip_inc"]))
        p = [f / a for f, a in zip(sl["force"], sl["area"])]
        nonuniform = nonuniform or max(p) > 1.2 * min(p)
        worn_slave = sum(h * a_slave[n2[int(nd)][0]] for h, nd in zip(sl["wear_slave"], sl["node"]))
        worn_master = sum(h * a_master[n1[int(nd)][0]] for h, nd in zip(ms["wear_master"], ms["node"]))
        assert len(sl) == nx_punch + 1 and len(ms) == 15, (len(sl), len(ms))
        if work == 0.0:
            assert worn_slave == 0.0 and worn_master == 0.0
            continue
        assert abs(worn_slave - n * K_SLAVE * work) <= 1e-10 * n * K_SLAVE * work, (inc.attrs, worn_slave,
                                                                                    n * K_SLAVE * work)
        assert abs(worn_master - n * K_MASTER * work) <= 1e-10 * n * K_MASTER * work, (inc.attrs, worn_master,
                                                                                       n * K_MASTER * work)
    # the case is not the uniform one
    assert nonuniform
    states = {st for inc in rubbing_increments(run) for st in inc.block("CONTACT SLAVE", pair=1)["state"]}
    assert "STICK" in states and "SLIP" in states, states
    with open(run.listing_path) as f:
        assert f.read().count("increment bisected") == bisections


def test_archard_balance_dual_mortar():
    """Archard's balance on both surfaces, partial slip, the dual mortar
    on non-matching meshes (7 slave faces on 10 master ones)."""
    check_balance("wear_balance_mortar")


def test_archard_balance_node_to_surface():
    """Archard's balance on both surfaces, node-to-segment on non-matching
    meshes (13 slave faces on 10), with a cycle jump of 3."""
    check_balance("wear_balance_nts", kind="NODE TO SURFACE", nx_punch=13, jump=3)


def test_archard_balance_through_bisections():
    """Wear is committed with the friction history by converged increments
    only: with MAXIT=2 seven increments of the partial-slip cycle (0.1
    long) are bisected (measured), and Archard's balance over the converged
    increments still holds to 1e-10 on both surfaces (a failed attempt's
    wear kept would break it)."""
    check_balance("wear_balance_bisected", inc=0.1, maxit=2, bisections=7)


def test_cycle_jump_counts_a_steady_cycle_n_times():
    """A steady cycle (stroke_steps, steady: the rigid punch, whose
    pressure does not change as it wears, already sliding when each cycle
    begins): the wear of one cycle with a jump of 10 is ten times that of
    one cycle without, and that of ten cycles without, on both surfaces,
    to 1e-12 (the slide to the cycle's start is jumped too)."""
    def cycle_wear(run, jump):
        """Per slave row (slave, master) and per master row the depth worn
        in step 3 over that of step 2 times the jump (step 2 wears N times
        too)."""
        a, b = rubbing_increments(run, 2)[-1], rubbing_increments(run, 3)[-1]
        rows = []
        for blk, cols in (("CONTACT SLAVE", ("wear_slave", "wear_master")), ("CONTACT MASTER", ("wear_master",))):
            for col in cols:
                h2, h3 = a.block(blk, pair=1)[col], b.block(blk, pair=1)[col]
                rows += [(y - x, x / jump) for x, y in zip(h2, h3)]
        return rows
    one = cycle_wear(run_deck("wear_jump_1", punch_deck(inc=0.1, steady=True)).ok(), 1)
    jumped = cycle_wear(run_deck("wear_jump_10", punch_deck(inc=0.1, steady=True, jump=10)).ok(), 10)
    ten = cycle_wear(run_deck("wear_cycles_10", punch_deck(inc=0.1, steady=True, cycles=10)).ok(), 1)
    assert len(one) == len(jumped) == len(ten) == 2 * 8 + 11
    for (a, a2), (b, b2), (c, c2) in zip(one, jumped, ten):
        assert a > 0.0 and a2 > 0.0
        assert abs(b - 10 * a) <= 1e-12 * b, (a, b)
        assert abs(c - b) <= 1e-12 * b, (b, c)
        # the slide to the start: the same slip, worn N times
        assert abs(b2 - a2) <= 1e-12 * a2 and abs(c2 - a2) <= 1e-12 * a2, (a2, b2, c2)


def test_periodic_amplitude_drives_the_stroke():
    """*AMPLITUDE, DEFINITION=PERIODIC (Abaqus' Fourier form, one term
    B1 = 1, omega = 2 pi, t0 = 0, A0 = 0): the punch's prescribed U1 at
    each increment is stroke sin(2 pi t), t the step time, to 1e-15 of
    the stroke."""
    run = run_deck("wear_periodic", punch_deck(inc=0.125)).ok()
    incs = rubbing_increments(run)
    assert len(incs) == 8
    for inc in incs:
        u = inc.block("NODE U")
        want = STROKE * math.sin(2 * math.pi * inc.time)
        assert all(abs(v - want) <= 1e-15 * STROKE * 10 for v in u["U1"]), (inc.time, u["U1"][0], want)


def test_without_wear_card_nothing_wears():
    """The same deck without *WEAR: no wear columns, and the punch keeps
    its height (the slave points' y do not move while it rubs)."""
    run = run_deck("wear_none", punch_deck(wear=False)).ok()
    ys = set()
    for inc in rubbing_increments(run):
        sl = inc.block("CONTACT SLAVE", pair=1)
        assert "wear_slave" not in sl.columns
        ys.update(round(y, 15) for y in sl["y"])
    assert len(ys) == 1, ys
    with open(run.listing_path[:-4] + "_contact.csv") as f:
        assert "wear" not in f.readline()


def check_error(name, deck, card, words):
    """cfe2d stops with `file:line: error: ...` at the line of `card`
    (the first line starting with it), naming words; exit status 1."""
    run = run_deck(name, deck)
    assert run.rc == 1, (run.rc, run.stderr)
    line = next(k + 1 for k, t in enumerate(deck.splitlines()) if t.startswith(card))
    assert f"{name}.inp:{line}: error:" in run.stderr, (line, run.stderr)
    for w in words:
        assert w in run.stderr, (w, run.stderr)
    assert "Backtrace" not in run.stderr and "NaN" not in run.stderr


def test_bad_wear_and_periodic_cards():
    """The input errors of the wear and periodic amplitude cards, each at
    its card's line."""
    deck = punch_deck()
    check_error("wear_no_friction", punch_deck(friction=False), "*WEAR", ["*WEAR needs a friction coefficient"])
    check_error("wear_symmetric", punch_deck(kind="NODE TO SURFACE", nx_punch=10, symmetric=True),
                "*CONTACT PAIR", ["two-pass"])
    check_error("wear_negative", deck.replace(f"*WEAR\n{K_SLAVE}", "*WEAR\n-1e-6"), "-1e-6",
                ["must not be negative"])
    check_error("wear_jump_zero", deck.replace(f"{K_MASTER}\n*CONTACT", f"{K_MASTER}, 0\n*CONTACT"),
                f"{K_SLAVE}, {K_MASTER}, 0", ["cycle-jump factor N must be positive"])
    check_error("wear_one_value", deck.replace(f"{K_SLAVE}, {K_MASTER}\n", f"{K_SLAVE}\n"), f"{K_SLAVE}",
                ["k_slave, k_master"])
    check_error("wear_outside", deck.replace("*WEAR", "*NSET, NSET=EXTRA\n1,\n*WEAR"),
                "*WEAR", ["outside a *SURFACE INTERACTION"])
    check_error("periodic_terms", deck.replace("1, 6.283185307179586, 0., 0.\n0., 1.\n",
                                                "2, 6.283185307179586, 0., 0.\n0., 1.\n"),
                "0., 1.", ["needs 4 coefficients"])
    check_error("periodic_omega", deck.replace("1, 6.283185307179586, 0., 0.", "1, 0., 0., 0."),
                "1, 0., 0., 0.", ["omega must be positive"])
    check_error("periodic_first_line", deck.replace("1, 6.283185307179586, 0., 0.", "1, 6.28, 0."),
                "1, 6.28, 0.", ["N (terms)"])


def test_plot_wear_script():
    """scripts/plot_wear.py on a run of three cycles after the pressing
    step (--start 1): one line per cycle whose master and slave depths are
    the table's largest at the cycle's end (to its 6 printed digits), and
    a PNG."""
    import csv
    import os
    import subprocess
    import sys
    from helpers import ROOT
    run = run_deck("wear_plot", punch_deck(rigid=False, nx_base=14, base_span=(-2.0, 12.0), cycles=3)).ok()
    table = run.listing_path[:-4] + "_contact.csv"
    png = os.path.join(os.path.dirname(table), "wear.png")
    out = subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "plot_wear.py"), table, "--start", "1",
                          "-o", png], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    lines = [ln for ln in out.stdout.splitlines() if ln.startswith("cycle ")]
    assert [ln.split(":")[0] for ln in lines] == ["cycle 1", "cycle 2", "cycle 3"], out.stdout
    with open(table) as f:
        rows = list(csv.DictReader(f))
    for c, ln in zip((2.0, 3.0, 4.0), lines):
        at = [r for r in rows if abs(float(r["time"]) - c) < 1e-9 and int(r["step"]) == 2]
        hm = max(float(r["wear_master"]) for r in at if r["side"] == "master")
        hs = max(float(r["wear_slave"]) for r in at if r["side"] == "slave")
        printed = ln.replace(",", "").split()
        assert abs(float(printed[printed.index("master") + 2]) - hm) <= 1e-5 * hm, (ln, hm)
        assert abs(float(printed[printed.index("slave") + 2]) - hs) <= 1e-5 * hs, (ln, hs)
    assert os.path.getsize(png) > 1000
