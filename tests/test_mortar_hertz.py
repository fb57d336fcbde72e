"""The figures of issue 21 on the flagship (scripts/contact_accuracy.py):
the segment-to-segment coupling with exact enforcement against node-to-
segment on the cylinder-on-plate history, at the peak load. Measured
(docs/contact.md, "Accuracy on the Hertz case"): on the 4-node meshes the
cylinder's slave faces are finer than the plate's, and segment-to-segment
takes the multiplier on the master mesh (contact_master_multipliers):
on the default CPS4 mesh the oscillation about the fitted ellipse is
0.06 % of p0 (node-to-segment 0.30 %), the largest nodal pressure +0.05 %
above the fitted p0 (+0.39 %), the slave-master difference 0.18 %
(0.95 %); on a coarse mesh of 5 300 nodes 0.20 % (1.59 %), +0.27 %
(+1.26 %), 0.10 % (2.63 %): the dual mortar (the multiplier on the slave
mesh) oscillated there by 1.82 % with the plate's period (the cylinder's
finer surface held to the plate's chords). On CPS8 (dual mortar) the
oscillation 0.84 % (2.10 %), the largest nodal pressure +0.08 % (+0.86 %),
the slave-master difference 4.3 % (12.8 %: the face points' force mode
is gone, the 1 % of the issue is not reached)."""
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
    assert sts["osc"] < nts["osc"] and sts["s-m"] < nts["s-m"], (sts, nts)
    # The master-mesh multipliers hold the finer slave in the mean over
    # each master node's hat, not at every slave node: the force is 1.9e-4
    # below node-to-segment's (13 919.27 against 13 921.87 N), towards the
    # finer mesh's (h = 0.025: node-to-segment 13 918.40, this coupling
    # 13 918.16; docs/contact.md).
    assert abs(sts["P"] - nts["P"]) < 3e-4 * nts["P"], (sts["P"], nts["P"])
    # every row's force is the force on its node: the slave rows sum to the
    # master rows' total at every increment (the field's value times the
    # area, reported before, summed to 13 919.14 against 13 919.23 N)
    import csv
    rows = list(csv.DictReader(open(os.path.splitext(sts["deck"])[0] + "_contact.csv")))
    for inc in sorted({int(r["increment"]) for r in rows}):
        side = {k: sum(float(r["force"]) for r in rows if int(r["increment"]) == inc and r["side"] == k)
                for k in ("slave", "master")}
        assert abs(side["slave"] - side["master"]) < 1e-8 * sts["P"], (inc, side)   # the table has 9 digits


def test_coarse_mesh_master_multipliers_meet_the_targets():
    """The coarse (5 300-node) flagship, the cylinder (slave) about twice
    as fine as the plate: with the multiplier on the master mesh the slave
    nodal pressures (the multiplier field at the slave nodes) oscillate
    about the fitted ellipse by less than 0.5 % of p0 (measured 0.20 %;
    node-to-segment 1.59 %, the dual mortar 1.82 %) and the largest is
    within 1 % of the fitted p0 (+0.27 %), the targets of issue 21; the
    slave-master difference below 0.5 % (0.10 %); the plate's period is
    gone: the mean deviations of the slave nodes over master corners and
    mid-face are below 0.15 % (+0.06 %, -0.06 %; dual mortar -1.75 %,
    +1.78 %)."""
    import contact_accuracy
    sts, nts = fig("ccx", "sts"), fig("ccx", "nts")
    ph = contact_accuracy.master_phases(os.path.splitext(sts["deck"])[0] + "_contact.csv")
    print(f"  coarse mesh: osc {sts['osc']:.2%} (nts {nts['osc']:.2%}), node_p0 {sts['node_p0']:+.2%} "
          f"(nts {nts['node_p0']:+.2%}), s-m {sts['s-m']:.2%} (nts {nts['s-m']:.2%}); by position on the master "
          f"face {ph['bin_mean'][0]:+.2%} / {ph['bin_mean'][1]:+.2%}, master rows {ph['master_osc']:.2%}")
    assert sts["osc"] < 0.005 and abs(sts["node_p0"]) < 0.01 and sts["s-m"] < 0.005, sts
    assert max(abs(v) for v in ph["bin_mean"]) < 0.0015, ph


def test_coarse_mesh_master_multipliers_with_friction():
    """The coarse flagship with FRICTION=0.3: segment-to-segment takes the
    multiplier on the master mesh with the consistent master side (int
    psi_m N_k da, whose tangential component is consistent): the
    oscillation below 1 % of p0 (measured 0.81 %; the dual mortar 1.97 %,
    node-to-segment 1.73 %) and the largest nodal pressure within 0.5 % of
    the fitted p0 (+0.03 %; dual +1.31 %)."""
    sts = fig("ccx", "sts", ", FRICTION=0.3, TYPE=SURFACE TO SURFACE, EXACT")
    nts = fig("ccx", "nts", ", FRICTION=0.3, TYPE=NODE TO SURFACE")
    print(f"  coarse mesh, friction 0.3: osc {sts['osc']:.2%} (nts {nts['osc']:.2%}), node_p0 {sts['node_p0']:+.2%} "
          f"(nts {nts['node_p0']:+.2%})")
    assert sts["osc"] < 0.01 and sts["osc"] < 0.6 * nts["osc"] and abs(sts["node_p0"]) < 0.005, (sts, nts)


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


def test_axisymmetric_sphere_master_multipliers():
    """Hertz's sphere on a flat in axisymmetry (input/hertz/hertz_point,
    CAX4, the sphere (slave) finer than the flat): segment-to-segment with
    EXACT takes the multiplier on the master mesh (the r weight in S_mj and
    D_m); at every loaded increment of the load-unload history the contact
    radius within 1.2 % of Hertz's and the peak pressure within 0.5 %
    (measured 0.80 % and 0.28 %; node-to-segment 1.96 % and 0.94 %, the
    dual mortar 1.81 % and 0.86 %), P the ring's contact force."""
    if shutil.which("gmsh") is None:
        raise Skip("gmsh is not installed")
    import subprocess
    import compare_hertz
    import run_hertz_point
    from hertz import point_modulus
    from helpers import CFE2D
    out = os.path.join(WORK, "hertz_point_cax4_sts")
    path = run_hertz_point.write_case(out, 1, 0.04)
    deck = open(path).read()
    pair = "*CONTACT PAIR, SEARCH DISTANCE=1.0\n"
    assert pair in deck
    with open(path, "w") as f:
        f.write(deck.replace(pair, pair[:-1] + ", TYPE=SURFACE TO SURFACE, EXACT\n"))
    subprocess.run([CFE2D, "-q", "--digits", "10", "-o", out, path], check=True, stdout=subprocess.DEVNULL)
    table = compare_hertz.read_contact_table(os.path.join(out, "hertz_point_contact.csv"))
    loaded = [r for r in compare_hertz.compare_point(table, 10.0, point_modulus(210000.0, 0.3)) if r["closed"] >= 3]
    worst_a = max(abs(r["err_a"]) for r in loaded)
    worst_p = max(abs(r["err_p0"]) for r in loaded)
    print(f"  CAX4 sphere, master-mesh multipliers: {len(loaded)} loaded increments, a within {worst_a:.2%}, "
          f"p0 within {worst_p:.2%}")
    assert len(loaded) == 15 and worst_a < 0.012 and worst_p < 0.005, (len(loaded), worst_a, worst_p)
