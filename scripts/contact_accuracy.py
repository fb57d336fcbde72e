#!/usr/bin/env python3
"""Accuracy of the contact pressures on the flagship (cylinder on plate,
Hertz line contact) for the two couplings: the figures of issue 21.

At the peak load (increment 10 of the flagship history), from the contact
table (<job>_contact.csv):

  osc       the oscillation of the slave nodal pressures about the best-
            fitting Hertz ellipse p^2 = p0^2 (1 - x^2/a^2) (least squares
            on p^2, compare_hertz.fit_ellipse), rms over |x| < 0.8 a_H,
            relative to the fitted p0
  node_p0   the largest nodal pressure against the fitted p0
  s-m       max |p_slave - p_master(x_slave)| / p0_H over |x| < 0.8 a_H
            (compare_hertz's s-m)
  P         the contact force (the master rows' sum: the pair's total
            for every coupling; with the master-mesh multipliers the slave
            rows hold the pressure field at the slave nodes times their
            consistent areas, whose sum differs from the total by the
            field's interpolation)

Cases (scripts/run_hertz.py meshes the geometry with gmsh):
  default   the flagship's default mesh (CPS4, h = 0.05; the cylinder meshed
            at half the plate's size)
  q8        the same geometry with CPS8 (h = 0.1, gmsh -order 2), as
            tests/test_hertz_q8.py
  ccx       a coarse mesh of about 5 300 nodes (h = 0.14), like CalculiX's
            2D Hertz mesh (the cylinder about twice as fine as the plate)
and couplings
  nts       the flagship deck as it is: node-to-segment, automatic penalty
            (Gauss points of the slave faces on CPS8)
  sts       TYPE=SURFACE TO SURFACE, EXACT: segment-to-segment, exact
            enforcement; on the 4-node meshes (the cylinder's slave faces
            finer than the plate's) the multiplier on the master mesh
            (contact_master_multipliers), on CPS8 the dual mortar

Usage: contact_accuracy.py [--cases default,q8,ccx] [--out results/accuracy]
       [--penalties]   (also: the sts figures with PENALTY= over three decades)
"""
import argparse
import csv
import os
import re
import shutil
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)

from compare_hertz import fit_ellipse  # noqa: E402
from hertz import HertzLine, effective_modulus  # noqa: E402

CFE2D = os.path.join(ROOT, "bin", "cfe2d")
MESHES = {"default": (0.05, 1), "q8": (0.1, 2), "ccx": (0.14, 1)}
PAIR = "*CONTACT PAIR, SEARCH DISTANCE=1.0"
COUPLINGS = {"nts": ", TYPE=NODE TO SURFACE", "sts": ", TYPE=SURFACE TO SURFACE, EXACT"}
RADIUS = 10.0
ESTAR = effective_modulus(210000.0, 0.3)


def write_case(outdir, mesh, pair_params, solve=None):
    """The flagship deck on one mesh with the pair's parameters appended
    (and a *SOLVER, CONTACT SOLVE=solve card where solve is given: FULL
    keeps exact enforcement's augmented Lagrangian, CONDENSED its direct
    multipliers); returns the deck's path. The mesh is made once per
    folder."""
    os.makedirs(outdir, exist_ok=True)
    h, order = MESHES[mesh]
    mesh_file = os.path.join(outdir, "hertz_mesh.inp")
    if not os.path.exists(mesh_file):
        cmd = ["gmsh", "-2", "-format", "inp", "-setnumber", "Mesh.SaveGroupsOfNodes", "1", "-setnumber", "h", str(h),
               "-o", mesh_file, os.path.join(ROOT, "input", "hertz", "hertz.geo")]
        if order == 2:
            cmd[1:1] = ["-order", "2", "-setnumber", "Mesh.SecondOrderIncomplete", "1"]
        subprocess.run(cmd, check=True, capture_output=True)
    with open(os.path.join(ROOT, "input", "hertz", "hertz.inp")) as f:
        deck = f.read()
    assert PAIR + "\n" in deck
    deck = deck.replace(PAIR + "\n", PAIR + pair_params + "\n")
    if solve is not None:
        assert "*SOLVER" not in deck
        deck = deck.replace("*STEP", f"*SOLVER, CONTACT SOLVE={solve}\n*STEP", 1)
    path = os.path.join(outdir, "hertz.inp")
    with open(path, "w") as f:
        f.write(deck)
    return path


def run(deck):
    """Runs cfe2d on the deck; returns the wall time."""
    t0 = time.perf_counter()
    subprocess.run([CFE2D, "-q", "--digits", "10", "-o", os.path.dirname(deck), deck], check=True,
                   stdout=subprocess.DEVNULL)
    return time.perf_counter() - t0


def figures(contact_csv, increment=10):
    """The figures of the module comment at one increment."""
    rows = [r for r in csv.DictReader(open(contact_csv)) if int(r["increment"]) == increment]
    side = {k: [r for r in rows if r["side"] == k] for k in ("slave", "master")}
    xs = np.array([float(r["x"]) for r in side["slave"]])
    ps = np.array([float(r["pressure"]) for r in side["slave"]])
    xm = np.array([float(r["x"]) for r in side["master"]])
    pm = np.array([float(r["pressure"]) for r in side["master"]])
    order = np.argsort(xm)
    xm, pm = xm[order], pm[order]
    force = float(sum(float(r["force"]) for r in side["master"]))
    h = HertzLine(force, RADIUS, ESTAR)
    p0, a = fit_ellipse(xs, ps, 0.8 * h.a)
    core = np.abs(xs) < 0.8 * h.a
    fit = p0 * np.sqrt(np.clip(1.0 - xs[core] ** 2 / a ** 2, 0.0, None))
    return {"P": force, "osc": float(np.sqrt(np.mean((ps[core] - fit) ** 2)) / p0),
            "node_p0": float((ps.max() - p0) / p0),
            "s-m": float(np.max(np.abs(ps[core] - np.interp(xs[core], xm, pm))) / h.p0),
            "points": int(core.sum())}


def master_phases(contact_csv, increment=10, quadratic=False, bins=2):
    """Where the slave pressures' oscillation sits (docs/contact.md,
    "Where the rest is"): each slave node's deviation from the fitted
    ellipse (relative to the fitted p0, |x| < 0.8 a_H), binned by its
    position on the master face under it (0: over a master corner, 0.5:
    mid-face); returns the bins' mean and rms deviations and node counts, the rms
    left after taking out the bins' means, and the master rows' rms
    deviation about the same ellipse. quadratic: 3-node master faces
    (every other master node a corner)."""
    rows = [r for r in csv.DictReader(open(contact_csv)) if int(r["increment"]) == increment]
    side = {k: sorted((r for r in rows if r["side"] == k), key=lambda r: float(r["x"])) for k in ("slave", "master")}
    xs = np.array([float(r["x"]) for r in side["slave"]])
    ps = np.array([float(r["pressure"]) for r in side["slave"]])
    xm = np.array([float(r["x"]) for r in side["master"]])
    pm = np.array([float(r["pressure"]) for r in side["master"]])
    h = HertzLine(float(sum(float(r["force"]) for r in side["master"])), RADIUS, ESTAR)
    p0, a = fit_ellipse(xs, ps, 0.8 * h.a)

    def dev(x, p):
        return (p - p0 * np.sqrt(np.clip(1.0 - x ** 2 / a ** 2, 0.0, None))) / p0
    core = np.abs(xs) < 0.8 * h.a
    d = dev(xs, ps)[core]
    corners = xm[::2] if quadratic else xm
    k = np.clip(np.searchsorted(corners, xs[core]) - 1, 0, len(corners) - 2)
    phase = (xs[core] - corners[k]) / (corners[k + 1] - corners[k])
    b = np.floor(phase * bins + 0.5).astype(int) % bins
    means = [float(d[b == i].mean()) if (b == i).any() else 0.0 for i in range(bins)]
    left = d - np.array(means)[b]
    mcore = np.abs(xm) < 0.8 * h.a
    rms = [float(np.sqrt(np.mean(d[b == i] ** 2))) if (b == i).any() else 0.0 for i in range(bins)]
    return {"bin_mean": means, "bin_rms": rms, "bin_n": [int((b == i).sum()) for i in range(bins)],
            "left": float(np.sqrt(np.mean(left ** 2))), "master_osc": float(np.sqrt(np.mean(dev(xm, pm)[mcore] ** 2)))}


def measure(out, mesh, coupling, pair_params=None, repeats=1, solve=None):
    """Runs one case (best wall time of `repeats`) and returns its figures,
    with `solves` the direct multiplier solves of each increment (exact
    enforcement on the condensed path: the listing's notes) and `deck`."""
    params = COUPLINGS[coupling] if pair_params is None else pair_params
    # a folder of its own per parameter set: a cached result's deck and
    # tables stay its own
    folder = coupling if pair_params is None else "custom_" + re.sub(r"[^a-z0-9]+", "_", params.lower()).strip("_")
    if solve is not None:
        folder += "_" + solve.lower()
    deck = write_case(os.path.join(out, mesh, folder), mesh, params, solve)
    wall = min(run(deck) for _ in range(repeats))
    f = figures(os.path.splitext(deck)[0] + "_contact.csv")
    f["wall"] = wall
    f["deck"] = deck
    f["solves"] = multiplier_solves(os.path.splitext(deck)[0] + ".out")
    return f


def multiplier_solves(listing):
    """The direct multiplier solves of each increment, from the listing's
    notes (empty where exact enforcement did not take them)."""
    pat = re.compile(r"exact contact: (\d+) direct multiplier solves")
    return [int(mo.group(1)) for mo in pat.finditer(open(listing).read())]


def table(cases, out, repeats=1, penalties=False):
    print(f"cores: {os.cpu_count()}, load average before: {' '.join(f'{v:.2f}' for v in os.getloadavg())}")
    print("flagship history (20 increments), figures at the peak; wall: best of", repeats)
    cols = ["mesh", "coupling", "P", "osc", "node_p0", "s-m", "wall_s", "wall/nts"]
    print(" ".join(f"{c:>10}" for c in cols), flush=True)
    results = {}
    for mesh in cases:
        for coupling in COUPLINGS:
            f = measure(out, mesh, coupling, repeats=repeats)
            results[mesh, coupling] = f
            ratio = f["wall"] / results[mesh, "nts"]["wall"]
            row = [mesh, coupling, f"{f['P']:.2f}", f"{f['osc']:.2%}", f"{f['node_p0']:+.2%}", f"{f['s-m']:.2%}",
                   f"{f['wall']:.2f}", f"{ratio:.2f}"]
            print(" ".join(f"{c:>10}" for c in row), flush=True)
            if f["solves"]:
                print(f"{'':>10} exact: direct multiplier solves per increment {min(f['solves'])}..{max(f['solves'])}, "
                      f"{sum(f['solves'])} in {len(f['solves'])} increments", flush=True)
    print("where sts's oscillation sits: slave deviations by position on the master face (0 corner, 0.5 mid-face)")
    for mesh in cases:
        quadratic = MESHES[mesh][1] == 2
        ph = master_phases(os.path.splitext(results[mesh, "sts"]["deck"])[0] + "_contact.csv", quadratic=quadratic,
                           bins=4 if quadratic else 2)
        bins = ", ".join(f"{i / len(ph['bin_mean']):.2f}: {v:+.2%} rms {r:.2%} ({n})"
                         for i, (v, r, n) in enumerate(zip(ph["bin_mean"], ph["bin_rms"], ph["bin_n"])))
        print(f"  {mesh}: by position {bins}; rms left after the means {ph['left']:.2%}; "
              f"master rows {ph['master_osc']:.2%}", flush=True)
    if penalties:
        print("sts (EXACT) on the default mesh with PENALTY= over three decades (automatic: about 8e9 per area)")
        for k in ("1e8", "1e9", "1e10", "1e11"):
            f = measure(out, "default", "sts", pair_params=f", TYPE=SURFACE TO SURFACE, EXACT, PENALTY={k}")
            print(f"  PENALTY={k:>5}: P {f['P']:.4f}, osc {f['osc']:.3%}, node_p0 {f['node_p0']:+.3%}, "
                  f"wall {f['wall']:.2f} s", flush=True)
    print(f"load average after: {' '.join(f'{v:.2f}' for v in os.getloadavg())}")
    print("targets (issue 21): osc < 0.5 %, |node_p0| < 1 %, s-m (q8) < 1 %, wall/nts <= 1.5")
    return results


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", default="default,q8,ccx")
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "accuracy"))
    ap.add_argument("--repeats", type=int, default=1)
    ap.add_argument("--penalties", action="store_true")
    args = ap.parse_args(argv)
    if shutil.which("gmsh") is None:
        print("gmsh is not installed (scripts/install-deps.sh installs it)")
        return 1
    table([c for c in args.cases.split(",") if c], args.out, args.repeats, args.penalties)
    return 0


if __name__ == "__main__":
    sys.exit(main())
