#!/usr/bin/env python3
"""`make bench`'s *FREQUENCY row: the 10 lowest natural frequencies of a
plane-stress CPS8 plate (250 x 60 elements, 45 621 nodes, about 91 000
free dofs; steel, clamped on one short side), a whole cfe2d run from deck
to listing (ARPACK in shift-invert mode on CHOLMOD's factor), and, when
`ccx` is on PATH, CalculiX on the same deck in the same run (it expands
the CPS8 to C3D20R bricks, three times the nodes). Printed: wall times
(best of the repeats), the eigensolver, the first and tenth frequency of
each and their relative differences (the 3D brick is another element: a
few tenths of a percent are expected, as on the test's cantilever).

    python3 scripts/bench_frequency.py [--repeats N] [--nx 250 --ny 60]
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
CFE2D = os.path.join(ROOT, "bin", "cfe2d")
WORK = os.path.join(ROOT, "results", "bench", "frequency")


def plate_deck(nx, ny, L=2500.0, H=600.0, nev=10):
    """The CPS8 plate [0, L] x [0, H] (mm, t = 5), clamped at x = 0."""
    lines = ["*HEADING", f"CPS8 plate {nx} x {ny}, clamped at x = 0: {nev} natural frequencies", "*NODE, NSET=ALLN"]
    ids, k = {}, 0
    for j in range(2 * ny + 1):
        for i in range(2 * nx + 1):
            if i % 2 and j % 2:
                continue
            k += 1
            ids[i, j] = k
            lines.append(f"{k}, {i * L / (2 * nx)!r}, {j * H / (2 * ny)!r}")
    lines.append("*ELEMENT, TYPE=CPS8, ELSET=PLATE")
    e = 0
    for j in range(0, 2 * ny, 2):
        for i in range(0, 2 * nx, 2):
            e += 1
            c = [ids[i, j], ids[i + 2, j], ids[i + 2, j + 2], ids[i, j + 2],
                 ids[i + 1, j], ids[i + 2, j + 1], ids[i + 1, j + 2], ids[i, j + 1]]
            lines.append(f"{e}, " + ", ".join(map(str, c)))
    lines.append("*NSET, NSET=CLAMP")
    lines += [str(ids[0, j]) for j in range(2 * ny + 1)]
    lines += ["*MATERIAL, NAME=STEEL", "*ELASTIC", "210000., 0.3", "*DENSITY", "7.85e-9",
              "*SOLID SECTION, ELSET=PLATE, MATERIAL=STEEL", "5.", "*BOUNDARY", "CLAMP, 1, 2",
              "*STEP", "*FREQUENCY", f"{nev}", "*END STEP"]
    return "\n".join(lines) + "\n", 2 * (k - (2 * ny + 1))


def best_of(cmd, cwd, repeats):
    best = None
    for _ in range(repeats):
        t0 = time.perf_counter()
        p = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)
        t = time.perf_counter() - t0
        if p.returncode != 0:
            raise RuntimeError(f"{' '.join(cmd)} failed: {p.stderr[-400:]}{p.stdout[-400:]}")
        best = t if best is None else min(best, t)
    return best


def cfe2d_frequencies(listing):
    text = open(listing).read()
    block = text.split("--- EIGENVALUES")[1].split("\n--- ")[0].splitlines()[2:]
    freqs = [float(r.split()[3]) for r in block if r.strip()]
    method = re.search(r"^method (.*)$", text, re.M).group(1)
    return freqs, method


def ccx_frequencies(dat):
    text = open(dat).read().split("P A R T I C I P A T I O N")[0]
    return [float(m) for m in re.findall(r"^\s+\d+\s+\S+\s+\S+\s+(\S+)\s+0\.0000000E\+00$", text, re.M)]


def table(repeats=1, nx=250, ny=60):
    os.makedirs(WORK, exist_ok=True)
    deck, dofs = plate_deck(nx, ny)
    path = os.path.join(WORK, "plate.inp")
    if not os.path.exists(path) or open(path).read() != deck:
        with open(path, "w") as f:
            f.write(deck)
    print(f"\n*FREQUENCY: CPS8 plate {nx} x {ny}, {dofs} free dofs, 10 modes (results/bench/frequency/plate.inp), "
          f"best of {repeats}")
    cols = ("program", "wall_s", "f1", "f10", "f1/cfe2d-1", "f10/cfe2d-1")
    print(" ".join(f"{c:>12}" for c in cols), flush=True)
    t = best_of([CFE2D, "-q", "-o", WORK, path], WORK, repeats)
    freqs, method = cfe2d_frequencies(os.path.join(WORK, "plate.out"))
    print(" ".join(f"{c:>12}" for c in ("cfe2d", f"{t:.2f}", f"{freqs[0]:.5g}", f"{freqs[-1]:.5g}", "", "")))
    print(f"  eigensolver: {method}")
    if shutil.which("ccx") is None:
        print("  ccx is not on PATH: no CalculiX row (apt-get install calculix-ccx)")
        return
    ccxdir = os.path.join(WORK, "ccx")
    os.makedirs(ccxdir, exist_ok=True)
    shutil.copy(path, os.path.join(ccxdir, "plate.inp"))
    env = dict(os.environ, OMP_NUM_THREADS="1")
    t0 = time.perf_counter()
    p = subprocess.run(["ccx", "-i", "plate"], cwd=ccxdir, capture_output=True, text=True, env=env)
    tc = time.perf_counter() - t0
    if p.returncode != 0 or not os.path.exists(os.path.join(ccxdir, "plate.dat")):
        print(f"  ccx failed: {p.stdout[-300:]}")
        return
    cf = ccx_frequencies(os.path.join(ccxdir, "plate.dat"))
    print(" ".join(f"{c:>12}" for c in ("ccx", f"{tc:.2f}", f"{cf[0]:.5g}", f"{cf[-1]:.5g}",
                                        f"{cf[0] / freqs[0] - 1:+.4f}", f"{cf[-1] / freqs[-1] - 1:+.4f}")))
    print(f"  ccx / cfe2d wall time: {tc / t:.1f} (ccx once, its 3D expansion of the same deck)")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeats", type=int, default=1)
    ap.add_argument("--nx", type=int, default=250)
    ap.add_argument("--ny", type=int, default=60)
    args = ap.parse_args(argv)
    table(args.repeats, args.nx, args.ny)
    return 0


if __name__ == "__main__":
    sys.exit(main())
