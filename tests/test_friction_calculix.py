"""cfe2d's Coulomb friction against CalculiX 2.20 on the same deck,
tests/calculix/friction_blocks.inp (tests/calculix/README.md: the case, the
ccx command, how the reference was made). CalculiX is not run here: its
numbers are in tests/calculix/friction_blocks_reactions.csv and
friction_blocks_contact.csv.

An upper block (2 x 1, CPE4) is pressed onto a lower one (4 x 1) by moving
its top edge down 0.01 (step 1, 5 increments), then pushed sideways 0.02
(step 2, 20 increments): it sticks, slips from its trailing corner, and
slides as a whole from t = 1.65. Both programs use the same penalties:
K = 1e4 per unit overclosure (LINEAR), mu = 0.3, stick slope 1e3 (shear
stress per unit slip), and the same increments (*STATIC, DIRECT).

Measured (cfe2d against CalculiX, every increment of both steps):

* the deck as it is (NODE TO SURFACE without SMALL SLIDING: CalculiX's
  large sliding, cfe2d searches again each increment): tangential reaction
  within 1.6e-4 of mu N, normal reaction within 2.3e-4 of N; the slave
  nodes' contact pressure within 0.6 % of the mean pressure (largest at
  the corners of the upper block, where the pressure peaks at 2.2 times
  the mean);
* with SMALL SLIDING (cfe2d pairs once on the initial configuration):
  3.7e-3 of mu N and 2.0e-3 of N.

The two discretisations differ: CalculiX expands the CPE4 blocks into a
layer of C3D8 bricks and couples each of the two copies of a slave node to
a master face with a spring element (penalty times the node's area, as
cfe2d's tributary area), cfe2d couples the 2D slave node to the master
edge (the CFE). Both are penalty methods with the same laws, so what is
left is geometry: CalculiX's contact springs work on the deformed
configuration (with SMALL SLIDING its reactions move by less than 5e-5),
cfe2d's coupling elements on the configuration of their search. Searched
on the initial configuration, cfe2d's sliding block carries exactly
T = mu N, CalculiX's 1.0006 mu N (the interface has rotated under the
push); searched every increment, cfe2d gives 1.0007 mu N too and the
differences drop 9 (N) to 23 (T) times, to the 2e-4 of the remaining
contact-element differences (halving the increments leaves them at
1.8e-4, so it is not cfe2d's search lagging one increment). Tolerances:
1e-3 (large sliding) and 1e-2 of mu N, 5e-3 of N (small sliding), 1 % of
the mean pressure: from 1.7 to 6 times the measured differences, and far
below what a wrong friction law gives against the same reference
(measured on the deck: stick slope doubled 5.8 % of mu N, halved 10.6 %,
left out (automatic) 9.5 %, mu = 0.29 3.4 %, K doubled 3.3 % of N)."""
import csv
import os
import time

import numpy as np

from helpers import HERE, run_deck

DECK = os.path.join(HERE, "calculix", "friction_blocks.inp")
MU = 0.3
PAIR = "*CONTACT PAIR, INTERACTION=ROUGH, TYPE=NODE TO SURFACE"


def _rows(name, variant):
    with open(os.path.join(HERE, "calculix", name)) as f:
        return [r for r in csv.DictReader(f) if r["variant"] == variant]


def run(variant):
    """cfe2d on the deck (large) or on it with SMALL SLIDING on the pair
    (small), as the reference's variants were run in CalculiX."""
    if variant == "large":
        r = run_deck("friction_calculix_large", path=DECK)
    else:
        text = open(DECK).read()
        assert text.count(PAIR + "\n") == 1
        r = run_deck("friction_calculix_small", text.replace(PAIR + "\n", PAIR + ", SMALL SLIDING\n"))
    r.ok()
    # runs unchanged: *CONTACT PRINT is the listing's contact tables; only
    # OUTPUT=3D of the *NODE FILE (CalculiX's expanded nodes) is warned about
    warnings = [ln for ln in r.stderr.splitlines() if "warning" in ln]
    assert len(warnings) == 1 and "OUTPUT=3D is ignored" in warnings[0], r.stderr
    return r


def reaction_differences(r, variant):
    """Largest |T - T_ccx| / (mu N_max) and |N - N_ccx| / N_max over the
    increments, T and N the tangential and normal reactions of the top
    edge (RF1, -RF2 summed over TOP), N_max CalculiX's largest N."""
    ref = _rows("friction_blocks_reactions.csv", variant)
    incs = r.listing.increments
    assert [(i.step, i.number) for i in incs] == [(int(x["step"]), int(x["increment"])) for x in ref], \
        [(i.step, i.number) for i in incs]
    n_max = max(-float(x["top_rf2"]) for x in ref)
    dt = dn = 0.0
    for inc, x in zip(incs, ref):
        assert abs(inc.time - float(x["total_time"])) < 1e-9, (inc.time, x["total_time"])
        t, n = inc.block("REACTIONS").as_dict()["TOP"]
        dt = max(dt, abs(t - float(x["top_rf1"])) / (MU * n_max))
        dn = max(dn, abs(-n + float(x["top_rf2"])) / n_max)
    return dt, dn


def test_friction_calculix_reactions():
    """The deck as it is: the tangential and normal reactions of every
    increment within 1e-3 of CalculiX's (measured 1.6e-4 and 2.3e-4)."""
    t0 = time.time()
    r = run("large")
    dt, dn = reaction_differences(r, "large")
    assert dt < 1e-3 and dn < 1e-3, (dt, dn)
    # the block slides as a whole at the end: T is mu N, up to the interface's rotation (CalculiX: 1.0007)
    t, n = r.listing.increments[-1].block("REACTIONS").as_dict()["TOP"]
    assert abs(t / (-n) / MU - 1.0) < 2e-3, t / (-n)
    assert time.time() - t0 < 30


def test_friction_calculix_contact_pressure():
    """The slave nodes' contact pressure at every increment within 1 % of
    the mean pressure of CalculiX's (measured 0.6 %, at the corners);
    CalculiX's value is the mean of the node's two expanded copies."""
    r = run("large")
    ref = {}
    for x in _rows("friction_blocks_contact.csv", "large"):
        ref.setdefault(round(float(x["total_time"]), 6), {})[int(x["node"])] = float(x["pressure"])
    worst = 0.0
    for inc in r.listing.increments:
        s = inc.block("CONTACT SLAVE", pair=1)
        cfe = dict(zip((int(n) for n in s["node"]), s["pressure"]))
        ccx = ref[round(inc.time, 6)]
        assert sorted(cfe) == sorted(ccx) and all(st in ("STICK", "SLIP") for st in s["state"]), (inc.time, s["state"])
        mean = np.mean(list(ccx.values()))
        worst = max(worst, max(abs(cfe[n] - ccx[n]) for n in ccx) / mean)
    assert worst < 0.01, worst


def test_friction_calculix_small_sliding():
    """With SMALL SLIDING cfe2d keeps the initial configuration's pairing
    and normals: within 1e-2 of mu N and 5e-3 of N of CalculiX (measured
    3.7e-3 and 2.0e-3), and the sliding block carries exactly mu N."""
    r = run("small")
    dt, dn = reaction_differences(r, "small")
    assert dt < 1e-2 and dn < 5e-3, (dt, dn)
    t, n = r.listing.increments[-1].block("REACTIONS").as_dict()["TOP"]
    assert abs(t / (-n) / MU - 1.0) < 1e-9, t / (-n)
