"""The figures of issue 21 on the flagship (scripts/contact_accuracy.py):
the segment-to-segment coupling with exact enforcement against node-to-
segment on the cylinder-on-plate history, at the peak load. Measured
(docs/contact.md, "Accuracy on the Hertz case"): on the default CPS4 mesh
the oscillation about the fitted ellipse is 0.36 % of p0 (node-to-
segment 0.30 %), the largest nodal pressure +0.43 % above the fitted p0
(+0.39 %), the slave-master difference 0.58 % (0.95 %); on CPS8 the
oscillation 0.84 % (2.10 %), the largest nodal pressure +0.08 % (+0.86 %),
the slave-master difference 4.3 % (12.8 %: the face points' force mode
is gone, the 1 % of the issue is not reached); on a coarse mesh of 5 300
nodes both couplings oscillate by 1.6-1.8 % (the cylinder's finer
surface follows the plate's coarser polygon: its chords' sagitta)."""
import os
import shutil

from helpers import WORK, Skip

_CACHE = {}


def fig(mesh, coupling, params=None):
    if shutil.which("gmsh") is None:
        raise Skip("gmsh is not installed")
    import contact_accuracy
    key = (mesh, coupling, params)
    if key not in _CACHE:
        _CACHE[key] = contact_accuracy.measure(os.path.join(WORK, "accuracy"), mesh, coupling, pair_params=params)
    return _CACHE[key]


def test_flagship_default_mesh_smooth_pressures():
    sts, nts = fig("default", "sts"), fig("default", "nts")
    print(f"  default mesh: osc {sts['osc']:.2%} (nts {nts['osc']:.2%}), node_p0 {sts['node_p0']:+.2%} "
          f"(nts {nts['node_p0']:+.2%}), s-m {sts['s-m']:.2%} (nts {nts['s-m']:.2%}), P {sts['P']:.2f} "
          f"(nts {nts['P']:.2f})")
    assert sts["osc"] < 0.005 and abs(sts["node_p0"]) < 0.01, sts
    assert sts["s-m"] < nts["s-m"], (sts, nts)
    # exact enforcement against the automatic penalty: the same force to 1e-5
    assert abs(sts["P"] - nts["P"]) < 1e-5 * nts["P"], (sts["P"], nts["P"])


def test_flagship_cps8_force_mode_gone():
    sts, nts = fig("q8", "sts"), fig("q8", "nts")
    print(f"  CPS8: osc {sts['osc']:.2%} (nts {nts['osc']:.2%}), node_p0 {sts['node_p0']:+.2%} "
          f"(nts {nts['node_p0']:+.2%}), s-m {sts['s-m']:.2%} (nts {nts['s-m']:.2%})")
    assert sts["osc"] < 0.01 and abs(sts["node_p0"]) < 0.01, sts
    assert sts["s-m"] < 0.05 and sts["s-m"] < 0.5 * nts["s-m"], (sts, nts)


def test_exact_flagship_independent_of_the_penalty():
    """The coarse (5 300-node) flagship with EXACT and PENALTY= 1e8 and 1e11
    per area (the automatic one is about 3e9 there): the same contact force
    and pressures to 1e-9."""
    a = fig("ccx", "sts", ", TYPE=SURFACE TO SURFACE, EXACT, PENALTY=1e8")
    b = fig("ccx", "sts", ", TYPE=SURFACE TO SURFACE, EXACT, PENALTY=1e11")
    print(f"  PENALTY 1e8 / 1e11: P {a['P']:.9f} / {b['P']:.9f}")
    assert abs(a["P"] - b["P"]) < 1e-9 * a["P"] and abs(a["osc"] - b["osc"]) < 1e-8, (a, b)


def test_exact_direct_multipliers_against_augmented():
    """Exact enforcement on the coarse (5 300-node) flagship: on the
    condensed path the multipliers are solved directly for each status
    (the Schur complement B S^-1 B^T on the active constraints), on the
    full path by the augmented Lagrangian. Both solve the same LCP with
    1/d = 0: every slave force of every increment the same to 1e-7 of the
    largest (measured 4.5e-9 on the default mesh), the peak P to 1e-8;
    the condensed path makes one multiplier solve per status, a finite
    number per increment (at most the status search's MAXIT, 100; measured
    1..7 on the default mesh, 1..5 here)."""
    import csv
    params = ", TYPE=SURFACE TO SURFACE, EXACT"
    direct = fig("ccx", "sts", params)
    import contact_accuracy
    full = contact_accuracy.measure(os.path.join(WORK, "accuracy"), "ccx", "sts", pair_params=params, solve="FULL")
    print(f"  P direct {direct['P']:.9f}, augmented {full['P']:.9f}; multiplier solves per increment "
          f"{direct['solves']}")
    assert abs(direct["P"] - full["P"]) < 1e-8 * full["P"], (direct["P"], full["P"])
    assert direct["solves"] and max(direct["solves"]) <= 100 and min(direct["solves"]) >= 1, direct["solves"]
    assert not full["solves"]

    def forces(deck):
        rows = csv.DictReader(open(os.path.splitext(deck)[0] + "_contact.csv"))
        return {(r["increment"], r["side"], r["node"]): float(r["force"]) for r in rows}
    a, b = forces(direct["deck"]), forces(full["deck"])
    assert a.keys() == b.keys()
    fmax = max(abs(v) for v in b.values())
    diff = max(abs(a[k] - b[k]) for k in b) / fmax
    print(f"  every contact force, direct against augmented: {diff:.1e} of the largest")
    assert diff < 1e-7, diff
