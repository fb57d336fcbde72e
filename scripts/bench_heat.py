#!/usr/bin/env python3
"""`make bench`, the heat row: linear transient conduction at a fixed
increment (issue 30 item 4), cfe2d against CalculiX on the same deck.

A square plate of N x N CPS4 (plane, thickness 1, steel-like k = 50, rho c
= 3.6e6), at 20 from the start, its left edge held at 100 and a film (h =
25 to 20) on its right edge, `*HEAT TRANSFER, DIRECT` with M equal
increments: a linear transient at a fixed step, which cfe2d solves with
one factorisation for the whole history (temperature_field keeps the
factor of C/dt + K + H while dt stays). Both programs print the
temperatures of a few nodes at every increment (*NODE PRINT, the .dat);
their largest difference over the history is printed as a check that
the two solved the same problem (the same backward Euler: docs/heat.md).

Printed per program: the best wall time of --repeats runs (the machine is
shared) and its user time, the increments, the factorisations (cfe2d: the listing's step
summary; CalculiX: the "Factoring the system of equations" lines of its
output), and the ratio CalculiX / cfe2d of the wall times, measured in the
same run. Without `ccx` on PATH only cfe2d's row is printed.

    python3 scripts/bench_heat.py [--n 100] [--increments 50] [--repeats 3]
"""
import argparse
import os
import re
import resource
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
CFE2D = os.path.join(ROOT, "bin", "cfe2d")
WORK = os.path.join(ROOT, "results", "bench", "heat")


def plate_deck(n, increments, size=1.0, dt=None):
    """The deck text: n x n CPS4 on a square of side `size` (m), probes at
    five nodes along the middle row, `increments` increments of dt (default:
    a tenth of the diffusion time over the plate, size^2 / alpha, in all)."""
    k, rho_c = 50.0, 3.6e6
    alpha = k / rho_c
    if dt is None:
        dt = 0.1 * size * size / alpha / increments
    h = size / n

    def nid(i, j):
        return j * (n + 1) + i + 1
    lines = ["** A plate of %d x %d CPS4: left edge held at 100, a film on the right, from 20 (scripts/bench_heat.py)"
             % (n, n), "*NODE, NSET=NALL"]
    lines += ["%d, %.12g, %.12g" % (nid(i, j), i * h, j * h) for j in range(n + 1) for i in range(n + 1)]
    lines.append("*ELEMENT, TYPE=CPS4, ELSET=EALL")
    e = 0
    for j in range(n):
        for i in range(n):
            e += 1
            lines.append("%d, %d, %d, %d, %d" % (e, nid(i, j), nid(i + 1, j), nid(i + 1, j + 1), nid(i, j + 1)))
    left = [nid(0, j) for j in range(n + 1)]
    lines.append("*NSET, NSET=LEFT")
    lines += [", ".join(map(str, left[k:k + 10])) for k in range(0, len(left), 10)]
    probes = sorted({nid(i, n // 2) for i in (1, n // 8, n // 4, n // 2, n)})
    lines.append("*NSET, NSET=PROBE")
    lines.append(", ".join(map(str, probes)))
    lines.append("*ELSET, ELSET=RIGHT")
    right = [j * n + n for j in range(n)]
    lines += [", ".join(map(str, right[k:k + 10])) for k in range(0, len(right), 10)]
    lines += ["*MATERIAL, NAME=STEEL", "*CONDUCTIVITY", "%g" % k, "*DENSITY", "7800.", "*SPECIFIC HEAT",
              "%.12g" % (rho_c / 7800.0), "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL", "1.",
              "*INITIAL CONDITIONS, TYPE=TEMPERATURE", "NALL, 20.",
              "*STEP, INC=%d" % (increments + 10), "*HEAT TRANSFER, DIRECT", "%.12g, %.12g" % (dt, dt * increments),
              "*BOUNDARY", "LEFT, 11, 11, 100.", "*FILM", "RIGHT, F2, 20., 25.",
              "*NODE PRINT, NSET=PROBE", "NT", "*END STEP", ""]
    return "\n".join(lines)


def dat_temperatures(path):
    """[(time, {node: T})] of a .dat's "temperatures for set" blocks."""
    out = []
    with open(path) as f:
        for line in f:
            m = re.match(r"\s*temperatures for set \S+ and time\s+(\S+)", line)
            if m:
                out.append((float(m.group(1)), {}))
                continue
            p = line.split()
            if out and len(p) == 2 and p[0].isdigit():
                out[-1][1][int(p[0])] = float(p[1])
    return out


def best_run(cmd, cwd, repeats):
    """The best wall time of repeated runs of cmd in cwd, the user time of
    that run (its children's CPU time: CalculiX's threads included) and
    the stdout of the last run."""
    best, out = None, ""
    for _ in range(repeats):
        r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        p = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)
        wall = time.perf_counter() - t0
        user = resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime - r0.ru_utime
        if p.returncode != 0:
            raise RuntimeError("%s failed in %s: %s" % (cmd[0], cwd, (p.stdout + p.stderr)[-400:]))
        out = p.stdout
        if best is None or wall < best[0]:
            best = (wall, user)
    return best[0], best[1], out


def table(n=100, increments=50, repeats=3):
    """Runs the plate in both programs and prints the rows; returns the
    cfe2d row as a dict."""
    print("\nheat: linear transient conduction, %d x %d CPS4 plate, %d fixed increments (DIRECT)"
          % (n, n, increments))
    deck = plate_deck(n, increments)
    cols = ["program", "nodes", "wall_s", "user_s", "increments", "factorisations", "wall_ratio"]
    print(" ".join("%14s" % c for c in cols), flush=True)
    d_cfe, d_ccx = os.path.join(WORK, "cfe2d"), os.path.join(WORK, "ccx")
    for d in (d_cfe, d_ccx):
        os.makedirs(d, exist_ok=True)
        with open(os.path.join(d, "plate.inp"), "w") as f:
            f.write(deck)
    wall, user, _ = best_run([CFE2D, "-q", "plate.inp"], d_cfe, repeats)
    with open(os.path.join(d_cfe, "plate.out")) as f:
        summaries = [t.split("\n---", 1)[0] for t in f.read().split("--- STEP SUMMARY")[1:]]
    factors = sum(int(v) for t in summaries for v in re.findall(r"^numeric_factorisations (\d+)$", t, re.M))
    incs = sum(int(v) for t in summaries for v in re.findall(r"^increments (\d+)$", t, re.M))
    nodes = (n + 1) ** 2
    row = {"program": "cfe2d", "nodes": nodes, "wall_s": wall, "increments": incs, "factorisations": factors}
    print(" ".join("%14s" % v for v in ("cfe2d", nodes, "%.2f" % wall, "%.2f" % user, incs, factors, "1.00")),
          flush=True)
    if shutil.which("ccx") is None:
        print("(ccx is not on PATH: no CalculiX row)")
        return row
    ccx_wall, ccx_user, out = best_run(["ccx", "-i", "plate"], d_ccx, repeats)
    ccx_factors = len(re.findall(r"Factoring the system of equations", out))
    ref = dat_temperatures(os.path.join(d_ccx, "plate.dat"))
    got = dat_temperatures(os.path.join(d_cfe, "plate.dat"))
    print(" ".join("%14s" % v for v in ("CalculiX", nodes, "%.2f" % ccx_wall, "%.2f" % ccx_user, len(ref),
                                         ccx_factors, "%.2f" % (ccx_wall / wall))), flush=True)
    if len(ref) == len(got) and ref:
        diff = max(abs(b[1][k] - v) for a, b in zip(ref, got) for k, v in a[1].items())
        print("largest difference of the probes' temperatures over the %d increments: %.2e (of 80)"
              % (len(ref), diff))
    else:
        print("the two printed %d and %d increments" % (len(ref), len(got)))
    row["ccx_wall_s"] = ccx_wall
    return row


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=100, help="elements along a side")
    ap.add_argument("--increments", type=int, default=50)
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args(argv)
    table(args.n, args.increments, args.repeats)
    return 0


if __name__ == "__main__":
    sys.exit(main())
