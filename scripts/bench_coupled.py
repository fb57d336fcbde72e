#!/usr/bin/env python3
"""`make bench`, the coupled row (issue 30 item 4): a coupled
temperature-displacement contact deck, cfe2d against CalculiX on the same
deck.

Two blocks of 1 x 1 (plane strain CPE4, N x N each), A on 0 < y < 1 and B
on 1 < y < 2, B's bottom the slave face on A's top (`*CONTACT PAIR, TYPE=
SURFACE TO SURFACE`, `PRESSURE-OVERCLOSURE=LINEAR`): A's bottom held in y
and at 100, B's top held in y and at 0, both sides held in x; B starts
1e-5 into A (the penalty 1e7 makes that a pressure of about 100). The
heat crosses the contact through a pressure-dependent `*GAP CONDUCTANCE`
(10 at 0, 100 at 500, CalculiX's layout: conductance, pressure), and the
blocks expand (alpha 1.2e-5) against each other, so that the pressure
depends on the temperatures and the conductance on the pressure: one
`*COUPLED TEMPERATURE-DISPLACEMENT, STEADY STATE` step. cfe2d solves it by passes of the two fields (docs/heat.md),
CalculiX monolithically. Both print the temperatures of the contact's
nodes (*NODE PRINT NT, the .dat); the largest difference is printed as a
check that the two solved the same problem.

Printed per program: the best wall time of --repeats runs (the machine is
shared) and its user time, and the ratio CalculiX / cfe2d of the wall
times, measured in the same run. Without `ccx` on PATH only cfe2d's row
is printed.

    python3 scripts/bench_coupled.py [--n 60] [--repeats 3]
"""
import argparse
import os
import shutil
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from bench_heat import best_run, dat_temperatures  # noqa: E402

ROOT = os.path.dirname(HERE)
CFE2D = os.path.join(ROOT, "bin", "cfe2d")
WORK = os.path.join(ROOT, "results", "bench", "coupled")


def lines_of(ids):
    """Set data lines of at most 10 ids each."""
    return [", ".join(map(str, ids[k:k + 10])) for k in range(0, len(ids), 10)]


def block(n, y0, n0, e0):
    """Nodes and CPE4 elements of an n x n block of side 1 from height y0,
    node numbers from n0 + 1 and element numbers from e0 + 1: (node lines,
    element lines, node id function, element id function)."""
    h = 1.0 / n

    def nid(i, j):
        return n0 + j * (n + 1) + i + 1

    def eid(i, j):
        return e0 + j * n + i + 1
    nodes = ["%d, %.12g, %.12g" % (nid(i, j), i * h, y0 + j * h) for j in range(n + 1) for i in range(n + 1)]
    elems = ["%d, %d, %d, %d, %d" % (eid(i, j), nid(i, j), nid(i + 1, j), nid(i + 1, j + 1), nid(i, j + 1))
             for j in range(n) for i in range(n)]
    return nodes, elems, nid, eid


def blocks_deck(n, overclosure=1e-5):
    """The deck text (see the module's comment)."""
    na, ea, nida, eida = block(n, 0.0, 0, 0)
    nb, eb, nidb, eidb = block(n, 1.0 - overclosure, 10 * (n + 1) ** 2, 10 * n * n)
    sides = sorted([nida(0, j) for j in range(n + 1)] + [nida(n, j) for j in range(n + 1)] +
                   [nidb(0, j) for j in range(n + 1)] + [nidb(n, j) for j in range(n + 1)])
    lines = ["** Two CPE4 blocks of %d x %d through a pressure-dependent gap conductance (scripts/bench_coupled.py)"
             % (n, n), "*NODE, NSET=NALL"] + na + nb
    lines += ["*ELEMENT, TYPE=CPE4, ELSET=A"] + ea + ["*ELEMENT, TYPE=CPE4, ELSET=B"] + eb
    lines += ["*NSET, NSET=BOTTOM"] + lines_of([nida(i, 0) for i in range(n + 1)])
    lines += ["*NSET, NSET=TOP"] + lines_of([nidb(i, n) for i in range(n + 1)])
    lines += ["*NSET, NSET=SIDES"] + lines_of(sides)
    lines += ["*NSET, NSET=PROBE"] + lines_of(sorted({nida(i, n) for i in range(0, n + 1, max(1, n // 4))} |
                                                     {nidb(i, 0) for i in range(0, n + 1, max(1, n // 4))}))
    lines += ["*SURFACE, NAME=ASURF"] + ["%d, S3" % eida(i, n - 1) for i in range(n)]
    lines += ["*SURFACE, NAME=BSURF"] + ["%d, S1" % eidb(i, 0) for i in range(n)]
    for name, k in (("M1", 50.0), ("M2", 10.0)):
        lines += ["*MATERIAL, NAME=%s" % name, "*ELASTIC", "210000., 0.3", "*EXPANSION", "1.2e-5",
                  "*CONDUCTIVITY", "%g" % k]
    lines += ["*SOLID SECTION, ELSET=A, MATERIAL=M1", "1.", "*SOLID SECTION, ELSET=B, MATERIAL=M2", "1.",
              "*SURFACE INTERACTION, NAME=GAP", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", "1.e7",
              "*GAP CONDUCTANCE", "10., 0.", "100., 500.",
              "*CONTACT PAIR, INTERACTION=GAP, TYPE=SURFACE TO SURFACE", "BSURF, ASURF",
              "*INITIAL CONDITIONS, TYPE=TEMPERATURE", "NALL, 0.",
              "*BOUNDARY", "SIDES, 1, 1", "BOTTOM, 2, 2", "TOP, 2, 2",
              "*STEP", "*COUPLED TEMPERATURE-DISPLACEMENT, STEADY STATE", "1., 1.",
              "*BOUNDARY", "BOTTOM, 11, 11, 100.", "TOP, 11, 11, 0."]
    lines += ["*NODE PRINT, NSET=PROBE", "NT", "*END STEP", ""]
    return "\n".join(lines)


def table(n=60, repeats=3):
    """Runs the blocks in both programs and prints the rows; returns the
    cfe2d row as a dict."""
    print("\ncoupled: two %d x %d CPE4 blocks through a pressure-dependent gap conductance, steady coupled step"
          % (n, n))
    deck = blocks_deck(n)
    cols = ["program", "nodes", "wall_s", "user_s", "wall_ratio"]
    print(" ".join("%14s" % c for c in cols), flush=True)
    d_cfe, d_ccx = os.path.join(WORK, "cfe2d"), os.path.join(WORK, "ccx")
    for d in (d_cfe, d_ccx):
        os.makedirs(d, exist_ok=True)
        with open(os.path.join(d, "blocks.inp"), "w") as f:
            f.write(deck)
    wall, user, _ = best_run([CFE2D, "-q", "blocks.inp"], d_cfe, repeats)
    nodes = 2 * (n + 1) ** 2
    row = {"program": "cfe2d", "nodes": nodes, "wall_s": wall}
    print(" ".join("%14s" % v for v in ("cfe2d", nodes, "%.2f" % wall, "%.2f" % user, "1.00")), flush=True)
    if shutil.which("ccx") is None:
        print("(ccx is not on PATH: no CalculiX row)")
        return row
    ccx_wall, ccx_user, _ = best_run(["ccx", "-i", "blocks"], d_ccx, repeats)
    print(" ".join("%14s" % v for v in ("CalculiX", nodes, "%.2f" % ccx_wall, "%.2f" % ccx_user,
                                         "%.2f" % (ccx_wall / wall))), flush=True)
    ref = dat_temperatures(os.path.join(d_ccx, "blocks.dat"))
    got = dat_temperatures(os.path.join(d_cfe, "blocks.dat"))
    if ref and got and set(ref[-1][1]) == set(got[-1][1]):
        diff = max(abs(got[-1][1][k] - v) for k, v in ref[-1][1].items())
        print("largest difference of the contact nodes' temperatures at the end: %.2e (of 100)" % diff)
    else:
        print("the two printed different temperatures (%d and %d blocks)" % (len(ref), len(got)))
    row["ccx_wall_s"] = ccx_wall
    return row


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=60, help="elements along a side of each block")
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args(argv)
    table(args.n, args.repeats)
    return 0


if __name__ == "__main__":
    sys.exit(main())
