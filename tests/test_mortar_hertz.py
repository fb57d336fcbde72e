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
