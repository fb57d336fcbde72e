"""Accuracy of stick and slip on a mesh of the kind users make (issue 33,
item 4; scripts/stick_slip_accuracy.py builds the mesh and measures): a
cylinder R = 10 mm (a cap |x| < 8.1 mm of the disk, its top flat and
rigid) pressed on a plate (38.88 x 20.01 mm) to a/R = 0.05, both plane-
strain steel, CPE4, the two meshes not matching (slave, the cylinder:
0.025 mm, 40 spacings across the contact; master, the plate: 0.03 mm),
each graded away from the contact with 3:1 transition rows; EXACT,
mu = 0.3; pressed by P in 2 increments, pushed to Q* = mu P / 2 in 4
and back to 0 in 4 (tests/test_friction.py states Cattaneo's and
Mindlin-Deresiewicz's closed forms, for two half-spaces of one
material). Each run 1-2 s on an idle machine (the mesh 1 s in python).

What the issue's figures measure (docs/contact.md, "Accuracy of stick
and slip"): the shear against the half-spaces' closed forms is the sum
of the model's part (these finite bodies carry a shear under the normal
load that two half-spaces do not: 2.3 % rms of mu p0 at a/R = 0.05,
O(a/R)) and the discretisation's. The discretisation is measured here
against the converged answer of the same bodies
(tests/stick_slip_converged.json: the same geometry on a 4 times finer
mesh, 0.00625 / 0.0075 mm, 60 256 elements, its pressing split
(SPLIT TOUCHING) into 79 increments, 16 + 16 increments of Q; its own
distance to the 2 times finer mesh, coarser_rms, 0.26 %, 0.93 % and
2.26 % of mu p0 rms; the script's docstring says how it is made)."""
import json
import os

import numpy as np

from helpers import HERE, workdir
import stick_slip_accuracy as ssa

INCS = (2, 4, 4)
REFERENCE = os.path.join(HERE, "stick_slip_converged.json")
STATES = (("press", 1), ("qstar", 2), ("back", 3))


def run_case(tag, coupling, hm=0.03, incs=INCS, load=1.0, hs=0.025, direct=False, split=True, shift=0.0):
    """Writes, runs and measures one case (stick_slip_accuracy's
    write_deck, run, measure) on the default plate; returns its figures.
    load scales P (a as its root; the contact surfaces 2.5 a wide);
    direct: fixed increments (*STATIC, DIRECT); split: *STATIC, SPLIT
    TOUCHING (the script's default; not cfe2d's); shift: the cylinder's
    mesh moved along x by this much."""
    d = workdir("stick_slip_" + tag)
    saved = ssa.P, ssa.QSTAR
    ssa.P, ssa.QSTAR = saved[0] * load, saved[1] * load
    try:
        path, xy, slave, _ = ssa.write_deck(d, coupling, incs=incs, hm=hm, hs=hs, plate_size=ssa.PLATE_SIZE, split=split,
                                            contact=2.5 * ssa.A_TARGET * load ** 0.5, shift=shift)
        if direct:
            with open(path) as f:
                text = f.read()
            with open(path, "w") as f:
                f.write(text.replace("*STATIC, SPLIT TOUCHING\n", "*STATIC, DIRECT\n"))
        ssa.run(path)
        return ssa.measure(path, xy, slave, incs)
    finally:
        ssa.P, ssa.QSTAR = saved


def reference():
    with open(REFERENCE) as f:
        return json.load(f)


def against(f, ref, name, step, kinks=False, h=None):
    """rms and largest difference over |x| < 0.9 a of run f's shear at the
    end of step against the reference state name, in mu p0 (the
    reference's a and p0; stick_slip_accuracy's shear_against): pointwise
    (h None) or the reference averaged over a node's support of spacing h.
    kinks false: the nodes within one slave spacing of the stick zone's
    ends c (at Q*; c and c' back at Q = 0), where the traction's slope is
    infinite, left out."""
    return ssa.shear_against(f["incs"][step, f["last"][step - 1]], ref, name, h=h, kinks=kinks)


def test_stick_zone_on_a_graded_nonmatching_mesh():
    """The stick zone (the run of STICK slave rows about the centre, its
    end the midpoint to the first SLIP row) within one slave spacing of
    Cattaneo's c = a sqrt(1 - Q / (mu P)) at each of the 4 loading
    increments and of Mindlin-Deresiewicz's c' at each of the 4 unloading
    ones, with both couplings (measured: within 0.56 spacings node-to-
    segment, 0.51 segment-to-segment); the contact force P to 1e-6 and
    the fitted a within 1 % of Hertz's (measured -0.6 %, -0.9 %)."""
    report = []
    for case, coupling in ssa.CASES.items():
        f = run_case(case, coupling)
        press = f["incs"][1, INCS[0]]
        assert abs(press["P"] - ssa.P) < 1e-6 * ssa.P, (case, press["P"])
        assert abs(press["a"] / ssa.A_TARGET - 1.0) < 0.01, (case, press["a"])
        for step, inc, c, ends, err in f["stick"]:
            zone = "none" if ends is None else f"[{ends[0]:.4f}, {ends[1]:.4f}] a"
            report.append(f"{case} {step}.{inc}: c/a {c:.4f}, stick zone {zone}, {err:.2f} spacings")
        assert len(f["stick"]) == INCS[1] + INCS[2]
        print("  " + "\n  ".join(report[-len(f["stick"]):]))
        assert f["stick_end"] <= 1.0, "\n".join(report)


def test_shear_against_the_converged_finite_bodies():
    """The discretisation error: the shear of the default deck (segment-to-
    segment, 2 + 4 + 4 increments) against the converged answer of the
    same bodies (REFERENCE), rms over |x| < 0.9 a in mu p0. Measured
    pointwise (the issue's figure): pressing 0.28 %, at Q* 1.27 %, back at
    Q = 0 3.04 % (largest 0.48 %, 7.09 % and 12.05 %); away from the stick
    zone's ends (one slave spacing either side of c, and of c' back at 0,
    left out) 0.28 %, 0.44 % and 1.22 %. Against the reference averaged
    over each node's support (what a dual mortar multiplier is:
    stick_slip_accuracy's reference_shear) 0.24 %, 0.86 %, 2.75 % (largest
    0.45, 3.13, 9.68; away from the ends 0.24, 0.48, 1.47 %): the mean
    takes half the error at c at Q* (the node at -0.35 mm, 0.009 mm inside
    the reference's stick zone: 7.09 % pointwise, 3.13 % averaged) and
    none of it at c' (the nodes at +-0.425 mm, 0.17 spacings inside c': 12.05
    and 8.76 % pointwise, 9.12 and 9.68 % averaged). The issue's bounds,
    0.5 % under P and 1.5 % at Q*, hold for the discretisation
    everywhere; back at Q = 0 only away from the zone ends. Allowed: 0.5 %
    and 1.5 % (the issue's), back 3.5 % rms over every node and 1.5 %
    away from the ends; averaged 0.5 %, 1.5 %, 3.2 % (2 % away)."""
    ref = reference()
    f = run_case("sts", ssa.CASES["sts"])
    got = {name: (against(f, ref, name, step, kinks=True), against(f, ref, name, step))
           for name, step in STATES}
    mean = {name: (against(f, ref, name, step, kinks=True, h=ssa.HS), against(f, ref, name, step, h=ssa.HS))
            for name, step in STATES}
    for title, figures in (("pointwise", got), ("averaged over each node's support", mean)):
        print(f"  against the converged finite bodies, {title}, % of mu p0 rms (largest); without the zone ends:\n  " +
              "\n  ".join(f"{n}: {100 * a[0]:.2f} ({100 * a[1]:.2f}); {100 * b[0]:.2f} ({100 * b[1]:.2f})"
                          for n, (a, b) in figures.items()))
    assert got["press"][0][0] < 0.005, got
    assert got["qstar"][0][0] < 0.015, got
    assert got["back"][0][0] < 0.035 and got["back"][1][0] < 0.015, got
    assert mean["press"][0][0] < 0.005 and mean["qstar"][0][0] < 0.015, mean
    assert mean["back"][0][0] < 0.032 and mean["back"][1][0] < 0.02, mean


def test_unloading_does_not_depend_on_its_increments():
    """What the error back at Q = 0 is not: the increments. The deck pushed
    to Q* and back in 1 + 1, 4 + 4 (the deck's) and 4 + 16 increments ends
    in the same state: every slave row's status the same and its shear
    within 1e-6 of mu p0 at Q* and back at Q = 0 (measured: 1e-7 MPa, the
    contact table's last digit). With one unloading increment every
    sliding point reverses within it (the return mapping from the anchor
    of Q*, docs/contact.md "Friction"), with 16 the slip zone regrows
    gradually: the same answer, so neither the unloading's increments nor
    the return mapping on a reversal is where the 3 % back at Q = 0 comes
    from; it is the mesh (test_shear_back_where_the_nodes_sit)."""
    runs = {incs: run_case("sts_" + "_".join(map(str, incs)), ssa.CASES["sts"], incs=incs)
            for incs in ((2, 1, 1), INCS, (2, 4, 16))}
    base = runs[INCS]
    for incs, f in runs.items():
        for step in (2, 3):
            a, b = base["incs"][step, INCS[step - 1]], f["incs"][step, incs[step - 1]]
            assert np.array_equal(a["x"], b["x"]) and np.array_equal(a["state"], b["state"]), (incs, step)
            dq = float(np.max(np.abs(a["q"] - b["q"]))) / (ssa.MU * a["p0"])
            print(f"  {incs}: step {step} largest shear difference from {INCS}: {dq:.1e} of mu p0")
            assert dq < 1e-6, (incs, step, dq)


#: Where the slave nodes sit against the stick zone's ends: the cylinder's
#: mesh moved along x by these fractions of its spacing.
SHIFTS = (0.0, 0.2, 0.4, 0.6, 0.8)


def test_shear_back_where_the_nodes_sit():
    """What the error back at Q = 0 is: the resolution of the stick zone's
    ends by one stick/slip status per slave node. Mindlin-Deresiewicz's
    locked-in traction has infinite slopes at c (the end of Q*'s stick
    zone) and at c' (the unloading's, where the change of traction, twice
    Cattaneo's, -2 q'(c'), has its square-root kink); a node whose support
    straddles an end sticks or slides as a whole. So the figure depends on
    where the nodes sit against c and c' (on the deck, -0.35 mm 0.0005 mm
    from c and +-0.425 mm 0.17 spacings inside c': the worst of the
    offsets measured), as on a user's mesh. The deck with the cylinder's
    mesh moved by 0, 0.2, 0.4, 0.6, 0.8 slave spacings, back at Q = 0
    against the converged bodies, rms over |x| < 0.9 a in mu p0: pointwise
    3.04, 2.53, 1.33, 1.20, 2.10 % (mean 2.04 %; ten offsets 0.1 apart:
    1.20-3.04 %, mean 2.03 %); against the reference averaged over each
    node's support 2.75, 3.36, 1.90, 2.09, 3.19 % (mean 2.66 %): the nodal
    values at the ends are nearer the traction at the node than its mean
    over the support, so the pointwise figure (the issue's) is the one
    that measures them. The twice finer mesh (0.0125 / 0.015 mm) at offsets
    0 and 0.2: 1.77 and 1.35 % pointwise. Checked: every offset below 3.5 %
    pointwise, the mean below 2.4 %, the best below 1.5 %, the averaged
    comparison's mean not below the pointwise one's."""
    ref = reference()
    point, mean = [], []
    for k, shift in enumerate(SHIFTS):
        f = run_case(f"sts_shift{k}", ssa.CASES["sts"], shift=shift * ssa.HS)
        point.append(against(f, ref, "back", 3, kinks=True)[0])
        mean.append(against(f, ref, "back", 3, kinks=True, h=ssa.HS)[0])
        print(f"  mesh moved by {shift:.1f} spacings: back at Q = 0 {point[-1]:.2%} pointwise, {mean[-1]:.2%} averaged "
              f"(of mu p0 rms); stick zone within {f['stick_end']:.2f} spacings")
        assert f["stick_end"] <= 1.0, (shift, f["stick_end"])
    print(f"  mean over the offsets: {np.mean(point):.2%} pointwise, {np.mean(mean):.2%} averaged")
    assert max(point) < 0.035 and np.mean(point) < 0.024 and min(point) < 0.015, point
    assert np.mean(mean) >= np.mean(point), (point, mean)


def test_shear_against_the_closed_forms_with_the_model_part_separated():
    """The issue's figures: the shear against the half-spaces' closed forms,
    rms over |x| < 0.9 a in mu p0 (the fitted a and p0 of each increment).
    Segment-to-segment: pressing 2.35 %, Q* 2.64 %, back 3.85 % (node-to-
    segment 2.72 %, 3.30 %, 5.55 %); the converged bodies' own figures
    (REFERENCE, the model's part, no coupling removes it) 2.29 %, 2.78 %,
    2.83 %. The issue's 0.5 % and 1.5 % are not met against the closed
    forms, by the model's part alone. Checked: the run's figures within
    0.5 % (pressing; Q*) and 1.5 % (back) of the reference's (the
    discretisation above, which adds in quadrature to the model's part),
    and below 2.6 %, 3.0 %, 4.3 % (node-to-segment 3 %, 3.7 %, 6 %)."""
    ref = reference()
    sts = run_case("sts", ssa.CASES["sts"])
    nts = run_case("nts", ssa.CASES["nts"])
    line = lambda c, f: (f"{c}: pressing {f['shear_press']:.2%}, Q* {f['shear_qstar']:.2%}, "
                         f"back {f['shear_back']:.2%} of mu p0 rms")
    print("  " + line("sts", sts) + "\n  " + line("nts", nts) + "\n  " + line("converged bodies", ref))
    assert sts["shear_press"] < 0.026 and sts["shear_qstar"] < 0.03 and sts["shear_back"] < 0.043, line("sts", sts)
    assert nts["shear_press"] < 0.03 and nts["shear_qstar"] < 0.037 and nts["shear_back"] < 0.06, line("nts", nts)
    for key, tol in (("shear_press", 0.005), ("shear_qstar", 0.005), ("shear_back", 0.015)):
        assert abs(sts[key] - ref[key]) < tol, (key, sts[key], ref[key])


def test_split_increments_follow_the_touching_points():
    """The increments: a point that closes within an increment sticks from
    its anchor of the increment's start. With *STATIC, SPLIT TOUCHING
    (cfe2d's own parameter, which the script writes) the driver splits a
    frictional increment in which more than two points of a pair close
    from an open gap (docs/contact.md): the 2 pressing increments are
    solved in 20 sub-increments, the listing keeps 2. Without it (cfe2d's
    default) and with fixed increments (DIRECT), as CalculiX, the deck's
    2 are solved as they are: the two give the same shear. Measured
    at the end of the pressing, rms of the difference over |x| < 0.9 a in
    mu p0: split against 64 pressing increments 0.11 % (the 2
    increments unsplit: 1.59 %), DIRECT against the split 1.53 %; the
    figures against the closed form 2.35 % split, 2.38 % with 64
    increments, 3.07 % DIRECT. Checked: split
    within 0.3 % of 64 increments, DIRECT at least 1 % from the split,
    and the listing's increments as the deck's."""
    split = run_case("sts", ssa.CASES["sts"])
    many = run_case("sts_64", ssa.CASES["sts"], incs=(64, 1, 1))
    direct = run_case("sts_direct", ssa.CASES["sts"], direct=True, incs=(2, 1, 1))
    plain = run_case("sts_plain", ssa.CASES["sts"], split=False, incs=(2, 1, 1))
    d = plain["incs"][1, 2]
    assert np.array_equal(d["x"], direct["incs"][1, 2]["x"])
    assert np.max(np.abs(d["q"] - direct["incs"][1, 2]["q"])) <= 1e-9 * ssa.MU * d["p0"]
    assert split["last"] == INCS and direct["last"] == (2, 1, 1) and many["last"] == (64, 1, 1)
    a, b, c = split["incs"][1, 2], many["incs"][1, 64], direct["incs"][1, 2]
    assert np.array_equal(a["x"], b["x"]) and np.array_equal(a["x"], c["x"])
    inside = np.abs(a["x"]) < 0.9 * a["a"]
    rms = lambda u, v: float(np.sqrt(np.mean((u["q"] - v["q"])[inside] ** 2)) / (ssa.MU * u["p0"]))
    print(f"  pressing: split - 64 increments {rms(a, b):.2%}, DIRECT - split {rms(c, a):.2%}; against the closed "
          f"form split {split['shear_press']:.2%}, 64 increments {many['shear_press']:.2%}, DIRECT "
          f"{direct['shear_press']:.2%}")
    assert rms(a, b) < 0.003, rms(a, b)
    assert rms(c, a) > 0.01, rms(c, a)


def test_finite_body_shear_vanishes_as_a_over_r():
    """The model's part is O(a/R): pressed to a/R = 0.025 (P / 4) on the
    mesh scaled with a (0.0125 / 0.015 mm, 29 456 elements, the same
    bodies), the shear under P alone against the closed form's zero is
    1.09 % of mu p0 against 2.35 % at a/R = 0.05 (a ratio of 2.15, order
    1.11; at a/R = 0.0125, 0.59 %, not run here: docs/contact.md). Checked: the
    ratio within 1.7-2.6 (order 0.8-1.4 in a/R)."""
    big = run_case("sts", ssa.CASES["sts"], incs=(2, 1, 1))
    small = run_case("sts_ar025", ssa.CASES["sts"], incs=(2, 1, 1), load=0.25, hs=0.0125, hm=0.015)
    ratio = big["shear_press"] / small["shear_press"]
    print(f"  shear under P alone: a/R 0.05 {big['shear_press']:.2%}, 0.025 {small['shear_press']:.2%} of mu p0; "
          f"ratio {ratio:.2f}, order {np.log2(ratio):.2f}")
    assert 1.7 < ratio < 2.6, ratio


def test_frictionless_surface_mismatch_against_calculix():
    """Where the finite bodies' shear comes from, checked against another
    program: under the normal load alone, without friction, the two
    surfaces do not move together tangentially (delta(x) = u_x of the
    cylinder - u_x of the plate; zero for two half-spaces of one
    material). CalculiX 2.20 ran the same deck once (stick_slip_accuracy's
    write_calculix_frictionless: the deck's mesh, SURFACE TO SURFACE,
    linear pressure-overclosure 4e8 N/mm^3, pressed by the approach of P
    in 4 DIRECT increments; tests/calculix/stick_slip_frictionless.csv,
    README there). CalculiX poses its contact on the deformed
    configuration: cfe2d with NLGEOM gives its delta within 7.8e-6 mm rms
    over |x| < 0.9 a (CalculiX's delta 2.5e-5 mm rms, cfe2d's 2.1e-5, the
    same shape, changing sign at x = 0.3 mm); in small deformation (the
    closed forms' model, and the stick/slip deck's) delta is 1.17e-4 mm
    rms, one sign, 4.6 times larger: the normals' rotation takes most of
    it back. Checked: NLGEOM within 1.2e-5 mm rms of CalculiX, the small-
    deformation delta at least 3 times CalculiX's."""
    import csv
    rows = list(csv.DictReader(open(os.path.join(HERE, "calculix", "stick_slip_frictionless.csv"))))
    ccx_x = np.array([float(r["x"]) for r in rows])
    ccx_d = np.array([float(r["delta"]) for r in rows])
    got = {}
    for tag, nl in (("small", False), ("nlgeom", True)):
        d = workdir("stick_slip_frictionless_" + tag)
        path, xy, slave, plate_top = ssa.write_calculix_frictionless(d, nlgeom=nl)
        ssa.run(path)
        x, delta, _ = ssa.surface_mismatch(path[:-4] + ".frd", xy, slave, plate_top)
        assert np.allclose(x, ccx_x, atol=1e-9)
        got[tag] = delta
    inside = np.abs(ccx_x) < 0.9 * ssa.A_TARGET
    rms = lambda v: float(np.sqrt(np.mean(v[inside] ** 2)))
    print(f"  delta rms (mm): CalculiX {rms(ccx_d):.3e}, cfe2d NLGEOM {rms(got['nlgeom']):.3e} (difference "
          f"{rms(got['nlgeom'] - ccx_d):.2e}), small deformation {rms(got['small']):.3e}")
    assert rms(got["nlgeom"] - ccx_d) < 1.2e-5, rms(got["nlgeom"] - ccx_d)
    assert rms(got["small"]) > 3.0 * rms(ccx_d), (rms(got["small"]), rms(ccx_d))
