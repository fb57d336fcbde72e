"""McColl's fretting test as `make fretting` sets it up (scripts/fretting.py,
docs/fretting.md), at a coarse mesh (h = 0.02 mm in the contact zone, 8
increments per cycle) and 12 cycles, computed without a cycle jump and
with jumps of 3 and 12.

What is checked, on the last increment of each run's contact table:

* the cycle jump converges: the jumped runs' worn depth and worn area of
  the flat against the run without a jump (the scar is young, the cycle
  nearly steady: measured, depth and area 0.03 % and 0.13 % below at a
  jump of 3, 0.06 % and 0.72 % at 12 (one computed cycle, whose start
  from rest is counted 12 times); tolerances 1 % and 2 %);
* Archard's balance between the surfaces: both wear from the same forces
  and slips, so the cylinder's worn area over the flat's is k_cyl / k_flat
  (the areas integrated by the trapezoidal rule along x: exact for the
  flat; for the cylinder's arc, measured 8e-5 off; tolerance 1e-3);
* the slip is gross, as in the reproduction: the flat's worn area lies
  below k P 4 delta C (every point sliding the whole relative travel of
  the two rigid ends, 4 delta per cycle) and above 0.85 of it (the
  elastic stick at each reversal: measured 0.966);
* the history pairs the contact again at every increment (the points
  slide over several master segments) and still factors the bodies once
  per step: the equations are numbered for the surfaces' zone and the
  condensed solve works in low-rank form about a reference status
  (docs/fretting.md, "Cost"); its worn depths are those of the full
  solve (every status factored whole, the equations numbered for every
  pairing) to round-off (measured 2e-14 of the deepest; tolerance 1e-10);
* the increments that are not written are solved on the contact
  equations alone, and a written one recovers the bodies exactly: the
  flat's element stresses at every 4th increment are the full solve's
  (measured 1.6e-12 of the largest; tolerance 1e-9);
* the condensed solve decides a status on its unrefined low-rank
  solution and refines only the one that settles (docs/fretting.md,
  "Status solve and lazy start"): with a jump of 3 (several statuses an
  increment) every coupling's state at every increment, and the step's
  contact iterations and block pivots, are those of the full solve;
* the debug build (`make debug`: -fcheck=all) runs the low-rank status
  solves and gives the optimised build's worn depths (measured 9.5e-14
  and 1.3e-13 of the deepest on the flat and the cylinder; tolerance
  1e-11).
"""
import os
import shutil
import subprocess
import sys

import numpy as np

from helpers import ROOT, Skip, run_deck, workdir
from cfe2d_listing import read_listing

sys.path.insert(0, os.path.join(ROOT, "scripts"))
import fretting  # noqa: E402

CYCLES, H, INC = 12, 0.02, 8


def _mesh():
    """The coarse mesh, made once (gmsh) in tests/work/fretting_mesh/."""
    if shutil.which("gmsh") is None:
        raise Skip("gmsh is not installed")
    d = os.path.join(ROOT, "tests", "work", "fretting_mesh")
    path = os.path.join(d, f"mccoll_mesh_h{H:g}.inp")
    if not os.path.exists(path):
        d = workdir("fretting_mesh")
        fretting.mesh(d, H)
    return path


def _run(jump):
    """(flat, cylinder) worn profiles after CYCLES cycles with the jump."""
    text = fretting.deck(_mesh(), CYCLES // jump, jump, INC, INC)
    name = f"fretting_j{jump}"
    run_deck(name, text).ok()
    return fretting.last_profiles(os.path.join(ROOT, "tests", "work", name, name + "_contact.csv"))


def test_fretting_cycle_jump_converges():
    """Depth and worn area of the flat with jumps 3 and 12 against no jump."""
    flat1, _ = _run(1)
    d1, a1 = max(h for _, h in flat1), fretting.area(flat1)
    for jump, tol in ((3, 0.01), (12, 0.02)):
        flat, _ = _run(jump)
        d, a = max(h for _, h in flat), fretting.area(flat)
        assert abs(d / d1 - 1) < tol, (jump, d, d1)
        assert abs(a / a1 - 1) < tol, (jump, a, a1)


def test_fretting_archard_balance_and_gross_slip():
    """Cylinder over flat worn area = k_cyl / k_flat; the flat's worn area
    between 0.85 and 1 of k P 4 delta C."""
    flat, cyl = _run(3)
    af, ac = fretting.area(flat), fretting.area(cyl)
    assert abs((ac / af) / (fretting.K_CYL / fretting.K_FLAT) - 1) < 1e-3, (ac, af)
    bound = fretting.K_FLAT * fretting.LOAD * 4 * fretting.STROKE * CYCLES
    assert 0.85 < af / bound <= 1.0 + 1e-9, af / bound


def _step_summary(path, step):
    """{item: value} of the listing's STEP SUMMARY block of the step."""
    out, on = {}, False
    with open(path) as f:
        for line in f:
            if line.startswith("--- "):
                on = line.split() == ["---", "STEP", "SUMMARY", f"step={step}"]
                continue
            w = line.split()
            if on and len(w) == 2 and w[0] != "item":
                out[w[0]] = float(w[1])
    return out


def _worn(path):
    """Worn depths of the last increment's listing: (slave, master)."""
    inc = read_listing(path).increments[-1]
    return (np.asarray(inc.block("CONTACT SLAVE")["wear_slave"], float),
            np.asarray(inc.block("CONTACT MASTER")["wear_master"], float))


def test_fretting_repairing_keeps_one_factorisation_and_the_worn_depths():
    """Six cycles without a jump (48 increments, each paired again): one
    numeric factorisation in the rubbing step; the worn depths of both
    surfaces those of CONTACT SOLVE=FULL to 1e-10 of the deepest."""
    cycles = 6
    text = fretting.deck(_mesh(), cycles, 1, INC, INC)
    step = text.index("*STEP")
    runs = {}
    for solve in ("CONDENSED", "FULL"):
        name = f"fretting_repair_{solve.lower()}"
        r = run_deck(name, text[:step] + f"*SOLVER, CONTACT SOLVE={solve}\n" + text[step:]).ok()
        runs[solve] = r.listing_path
    cond = _step_summary(runs["CONDENSED"], 2)
    assert cond["increments"] == cycles * INC, cond
    assert cond["numeric_factorisations"] == 1, cond
    # the couplings were paired again: every closed point slid past more
    # than two master segments (h) per cycle
    last = read_listing(runs["CONDENSED"]).increments[-1].block("CONTACT SLAVE")
    closed = np.array([s.strip() != "OPEN" for s in last["state"]])
    assert closed.any() and np.all(np.asarray(last["slip"], float)[closed] / cycles > 2 * H), last["slip"]
    # and the full solve factored the whole stiffness for every status
    assert _step_summary(runs["FULL"], 2)["numeric_factorisations"] >= cycles * INC
    for a, b in zip(_worn(runs["CONDENSED"]), _worn(runs["FULL"])):
        assert a.shape == b.shape and np.max(b) > 0
        assert np.max(np.abs(a - b)) <= 1e-10 * np.max(np.abs(b)), np.max(np.abs(a - b)) / np.max(np.abs(b))


def _states(path):
    """[(step, increment, node, state)] of every row of a contact table."""
    with open(path) as f:
        head = f.readline().strip().split(",")
        cols = [head.index(c) for c in ("step", "increment", "side", "node", "state")]
        return [tuple(w[c].strip() for c in cols) for w in (line.split(",") for line in f)]


def test_fretting_condensed_statuses_are_the_full_solves():
    """A jump of 3 (4 computed cycles, 32 increments, each paired again,
    2.6 statuses an increment): the condensed solve decides its statuses
    on unrefined low-rank solutions (about 3e-13 of x from the dense
    factor's) and refines only the one that settles, judging it again;
    every coupling's state (open, stick, slip) at every increment and the
    rubbing step's contact iterations and block pivots are those of
    CONTACT SOLVE=FULL (measured: equal, 84 iterations and 52 block
    pivots)."""
    text = fretting.deck(_mesh(), 4, 3, INC, 1)
    step = text.index("*STEP")
    tables, summaries = {}, {}
    for solve in ("CONDENSED", "FULL"):
        name = f"fretting_statuses_{solve.lower()}"
        r = run_deck(name, text[:step] + f"*SOLVER, CONTACT SOLVE={solve}\n" + text[step:]).ok()
        tables[solve] = _states(os.path.join(ROOT, "tests", "work", name, name + "_contact.csv"))
        summaries[solve] = _step_summary(r.listing_path, 2)
    cond, full = summaries["CONDENSED"], summaries["FULL"]
    # statuses after an increment's first were searched (low-rank, unrefined)
    assert cond["condensed_lowrank_statuses"] > 1.5 * cond["increments"], cond
    for item in ("increments", "contact_iterations", "contact_block_pivots", "contact_single_pivots"):
        assert cond.get(item) == full.get(item), (item, cond.get(item), full.get(item))
    assert len(tables["FULL"]) >= 32 * 2 and tables["CONDENSED"] == tables["FULL"]


def _stresses(path):
    """{element: (sxx, syy, sxy)} of every written increment's element
    stresses of the flat (the listing's ELEMENT S blocks), by increment."""
    out = {}
    for inc in read_listing(path).increments:
        if not inc.has("ELEMENT S", set="FLAT"):
            continue
        b = inc.block("ELEMENT S", set="FLAT")
        out[(inc.step, inc.number)] = np.column_stack([np.asarray(b[c], float) for c in ("S11", "S22", "S12")])
    return out


def test_fretting_unwritten_increments_recover_the_bodies_exactly():
    """Increments that are not written are solved on the contact
    equations alone (docs/fretting.md, "Cost"); the increments written
    (every 4th) recover the other equations. The flat's element stresses
    there, which need every equation of the bodies, are those of CONTACT
    SOLVE=FULL (every equation solved at every increment) to 1e-9 of the
    largest stress at each written increment (measured 1.6e-12; with the
    recovery left out, the increments' stresses those of the last
    recovered one, 7.7)."""
    cycles = 2
    text = fretting.deck(_mesh(), cycles, 1, INC, INC)
    end = text.rindex("*END STEP")
    text = text[:end] + "*EL PRINT, ELSET=FLAT, FREQUENCY=4\nS\n" + text[end:]
    step = text.index("*STEP")
    runs = {}
    for solve in ("CONDENSED", "FULL"):
        name = f"fretting_recover_{solve.lower()}"
        r = run_deck(name, text[:step] + f"*SOLVER, CONTACT SOLVE={solve}\n" + text[step:]).ok()
        runs[solve] = _stresses(r.listing_path)
    cond, full = runs["CONDENSED"], runs["FULL"]
    assert sorted(cond) == sorted(full) and len(cond) >= cycles * INC // 4, (sorted(cond), sorted(full))
    for k in full:
        scale = np.max(np.abs(full[k]))
        assert scale > 0 and cond[k].shape == full[k].shape
        assert np.max(np.abs(cond[k] - full[k])) <= 1e-9 * scale, (k, np.max(np.abs(cond[k] - full[k])) / scale)


def test_fretting_debug_build_gives_the_worn_depths():
    """Two cycles without a jump (16 increments, each paired again, its
    statuses solved in low-rank form): the debug build runs them (its
    run-time checks on every array and allocation) and its worn depths
    of both surfaces are the optimised build's to 1e-11 of the deepest."""
    debug = os.path.join(ROOT, "build-debug", "cfe2d")
    if not os.path.exists(debug):
        raise Skip("build-debug/cfe2d not built (make debug)")
    text = fretting.deck(_mesh(), 2, 1, INC, INC)
    opt = run_deck("fretting_builds_opt", text).ok()
    assert _step_summary(opt.listing_path, 2)["condensed_lowrank_statuses"] > 0
    d = workdir("fretting_builds_debug")
    path = os.path.join(d, "fretting_builds_debug.inp")
    with open(path, "w") as f:
        f.write(text)
    proc = subprocess.run([debug, "-q", "-d", "16", "-o", d, path], capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr[-2000:]
    for a, b in zip(_worn(os.path.join(d, "fretting_builds_debug.out")), _worn(opt.listing_path)):
        assert a.shape == b.shape and np.max(b) > 0
        assert np.max(np.abs(a - b)) <= 1e-11 * np.max(np.abs(b)), np.max(np.abs(a - b)) / np.max(np.abs(b))
