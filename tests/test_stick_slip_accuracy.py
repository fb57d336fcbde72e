"""Accuracy of stick and slip on a mesh of the kind users make (issue 33,
item 4; scripts/stick_slip_accuracy.py builds the mesh and measures): a
cylinder R = 10 mm (a cap |x| < 8 mm of the disk, its top flat and
rigid) pressed on a plate (40 x 20 mm) to a/R = 0.05, both plane-strain
steel, CPE4, the two meshes not matching (slave, the cylinder: 0.025 mm,
40 spacings across the contact; master, the plate: 0.03 mm), each graded
away from the contact with 3:1 transition rows; EXACT, mu = 0.3; pressed
by P in 2 increments, pushed to Q* = mu P / 2 in 4 and back to 0 in 4
(tests/test_friction.py states Cattaneo's and Mindlin-Deresiewicz's
closed forms, for two half-spaces of one material). Each run about 1-2 s
(the mesh 1 s in python).

What the issue asks and what holds (docs/contact.md, "Accuracy of stick
and slip"):
* the stick zone within one slave spacing of c and c' at every increment:
  met by both couplings (checked);
* the shear under the normal load alone below 0.5 % of mu p0 and the
  Cattaneo-Mindlin shear within 1.5 % rms: not met. The converged answer
  of these finite bodies is not the half-spaces' zero: with 16 or 32
  pressing increments the pressing leaves 2.4 % rms on this mesh, the
  matching mesh and the twice finer one alike, with either coupling; it
  goes to 1.2-1.5 % at a/R = 0.025 and to 3.0 % with the plate twice as
  large: the bodies' finite size (O(a/R)), not the discretisation. What
  the discretisation adds is checked here: the non-matching meshes against
  the matching one with segment-to-segment (the dual mortar) and the
  increments' share."""
import numpy as np

from helpers import workdir
import stick_slip_accuracy as ssa

INCS = (2, 4, 4)


def run_case(tag, coupling, hm=0.03, incs=INCS):
    """Writes, runs and measures one case (stick_slip_accuracy's
    write_deck, run, measure); returns its figures."""
    d = workdir("stick_slip_" + tag)
    path, xy, slave, _ = ssa.write_deck(d, coupling, incs=incs, hm=hm)
    ssa.run(path)
    return ssa.measure(path, xy, slave, incs)


def pointwise_rms(f, g, key):
    """rms over |x| < 0.9 a of the difference of two runs' shear at
    increment key (the same slave nodes), in mu p0."""
    a, b = f["incs"][key], g["incs"][key]
    assert np.array_equal(a["x"], b["x"])
    inside = np.abs(a["x"]) < 0.9 * a["a"]
    return float(np.sqrt(np.mean((a["q"] - b["q"])[inside] ** 2)) / (ssa.MU * a["p0"]))


def test_stick_zone_on_a_graded_nonmatching_mesh():
    """The stick zone (the run of STICK slave rows about the centre, its
    end the midpoint to the first SLIP row) within one slave spacing of
    Cattaneo's c = a sqrt(1 - Q / (mu P)) at each of the 4 loading
    increments and of Mindlin-Deresiewicz's c' at each of the 4 unloading
    ones, with both couplings (measured: within 0.73 spacings node-to-
    segment, 0.67 segment-to-segment); the contact force P to 1e-6 and
    the fitted a within 1 % of Hertz's (measured -0.5 %, -0.9 %)."""
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


def test_shear_tractions_and_where_their_error_comes_from():
    """The shear against the closed forms, rms over |x| < 0.9 a in mu p0
    (the fitted a and p0 of each increment), with the bounds of what is
    measured (the issue's 0.5 % and 1.5 % are not met: module docstring):
    pressing alone 3.07 % segment-to-segment (3.52 % node-to-segment),
    at Q* 3.84 % (4.32 %), back at Q = 0 4.75 % (6.23 %); allowed 3.5 %,
    4.5 % and 5.5 % (node-to-segment 4 %, 5 %, 7 %).

    Where it comes from, segment-to-segment:
    * the non-matching meshes: the same run on the matching mesh (the
      plate at 0.025 mm too) differs by 0.25 % rms pressing and 0.44 % at
      Q* (allowed 0.75 %; node-to-segment differs by 1.55 % and 2.1 %:
      the nodal coupling of non-matching meshes, not checked);
    * the increments: pressing in 16 increments instead of 2 moves the
      shear by 1.55 % rms (the points that close within an increment
      take its relative motion before they touch as stick), and leaves
      2.39 % rms against the closed form (checked: within 1.5-3.2 %, the
      bodies' part that no coupling removes)."""
    nts = run_case("nts", ssa.CASES["nts"])
    sts = run_case("sts", ssa.CASES["sts"])
    line = lambda c, f: (f"{c}: pressing {f['shear_press']:.2%}, Q* {f['shear_qstar']:.2%}, "
                         f"back {f['shear_back']:.2%} of mu p0 rms")
    print("  " + line("nts", nts) + "\n  " + line("sts", sts))
    assert sts["shear_press"] < 0.035 and sts["shear_qstar"] < 0.045 and sts["shear_back"] < 0.055, line("sts", sts)
    assert nts["shear_press"] < 0.04 and nts["shear_qstar"] < 0.05 and nts["shear_back"] < 0.07, line("nts", nts)
    matching = run_case("sts_matching", ssa.CASES["sts"], hm=0.025)
    press = pointwise_rms(sts, matching, (1, INCS[0]))
    qstar = pointwise_rms(sts, matching, (2, INCS[1]))
    many = run_case("sts_16", ssa.CASES["sts"], incs=(16,) + INCS[1:])
    a, b = sts["incs"][1, INCS[0]], many["incs"][1, 16]
    inside = np.abs(a["x"]) < 0.9 * a["a"]
    steps = float(np.sqrt(np.mean((a["q"] - b["q"])[inside] ** 2)) / (ssa.MU * a["p0"]))
    print(f"  sts non-matching - matching: pressing {press:.2%}, Q* {qstar:.2%}; 2 - 16 pressing increments "
          f"{steps:.2%}; 16 increments against the closed form {many['shear_press']:.2%}")
    assert press < 0.0075 and qstar < 0.0075, (press, qstar)
    assert 0.015 < many["shear_press"] < 0.032, many["shear_press"]
    assert steps < 0.025, steps
