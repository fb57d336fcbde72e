#!/usr/bin/env python3
"""`make bench`'s fretting rows (issue 33): McColl's test as
scripts/fretting.py sets it up (docs/fretting.md), 18 000 cycles,

* with a cycle jump of 100 (180 computed cycles, 7 200 increments):
  a whole run, target under 10 s;
* without a jump (18 000 computed cycles, 720 000 increments, in steps
  of 2 500 cycles; target under 10 minutes on 2 cores): a whole run,
  writing the contact table every 100 cycles (the jump run's 180 tables;
  every cycle's would be 2.5 GB of listing and table). With `--cycles N`
  below 18 000, a run of the first N cycles (each written) and its wall
  time per increment times the 720 000 increments, printed as an
  extrapolation (a quick look while developing: the extrapolation of
  50 cycles hid that the history stopped at its fourth step, found by
  the whole run).

Printed per row: wall time, CPU time (user + system of cfe2d), the load
average of the machine before the run (it is shared), increments, wall
and CPU per increment and where the wall goes (the listing's TIMING block
per increment: setup, i.e. the contact search and the numbering, analyse,
factor, condensed iterations, recovery, output), the numeric
factorisations of the bodies, the flat's depth and width.

    python3 scripts/bench_fretting.py [--cycles 18000] [--skip-jump] [--cfe2d path]
"""
import argparse
import os
import re
import resource
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
WORK = os.path.join(ROOT, "results", "bench", "fretting")
sys.path.insert(0, HERE)
import fretting  # noqa: E402

CFE2D = fretting.CFE2D
PARTS = ("setup", "analyse", "factor", "condensed_iterations", "recovery", "output")


def timing(listing):
    """The TIMING block of a listing: {item: seconds} (and the counts)."""
    out, on = {}, False
    with open(listing) as f:
        for line in f:
            if line.startswith("--- TIMING"):
                on = True
                continue
            if on:
                w = line.split()
                if len(w) == 2 and re.match(r"^[0-9.eE+-]+$", w[1]):
                    out[w[0]] = float(w[1])
                elif out:
                    break
    return out


def run(cycles, jump, tag, every=40):
    """A run of `cycles` cycles with the jump in WORK/tag, the contact table
    written every `every` increments: (wall, increments, timing, depth um,
    width mm)."""
    out = os.path.join(WORK, tag)
    os.makedirs(out, exist_ok=True)
    computed = cycles // jump
    name = fretting.mesh(out, 0.01)
    deck = os.path.join(out, "mccoll.inp")
    with open(deck, "w") as f:
        f.write(fretting.deck(name, computed, jump, 40, every))
    load = os.getloadavg()[0]
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    with open(os.path.join(out, "run.log"), "w") as log:
        p = subprocess.run([CFE2D, deck], stdout=log, stderr=subprocess.STDOUT, cwd=out)
    wall = time.perf_counter() - t0
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    if p.returncode != 0:
        sys.exit(f"bench_fretting: cfe2d failed in {out}")
    t = timing(os.path.join(out, "mccoll.out"))
    t["cpu"] = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
    t["load"] = load
    flat, _ = fretting.last_profiles(os.path.join(out, "mccoll_contact.csv"))
    d, w = fretting.scar(flat)
    return wall, computed * 40, t, d * 1e3, w


def row(label, wall, n, t, d, w, note=""):
    """One printed row and its per-increment split."""
    per = 1e3 * wall / n
    split = ", ".join(f"{k} {1e3 * t.get(k, 0.0) / n:.2f}" for k in PARTS)
    print(f"{label:<34} {wall:9.1f} s {n:8d} inc {per:7.2f} ms/inc  depth {d:.3f} um, width {w:.3f} mm{note}")
    print(f"{'':<34} CPU {t['cpu']:.1f} s ({1e3 * t['cpu'] / n:.2f} ms/inc), load average before {t['load']:.1f}")
    print(f"{'':<34} per increment (wall ms): {split}; numeric factorisations "
          f"{int(t.get('numeric_factorisations', 0))}, condensed factorisations "
          f"{int(t.get('condensed_factorisations', 0))}, low-rank statuses "
          f"{int(t.get('condensed_lowrank_statuses', 0))}")


def table(cycles=18000, skip_jump=False):
    """The fretting rows of make bench."""
    print("\n=== Fretting: McColl's test, 18 000 cycles (scripts/bench_fretting.py, docs/fretting.md)")
    if not skip_jump:
        wall, n, t, d, w = run(18000, 100, "jump100")
        row("jump 100 (target < 10 s)", wall, n, t, d, w, "  MET" if wall < 10 else "  not met")
    if cycles >= 18000:
        wall, n, t, d, w = run(18000, 1, "jump1", every=4000)
        row("no jump, 18 000 cycles (< 600 s)", wall, n, t, d, w, "  MET" if wall < 600 else "  not met")
        return
    wall, n, t, d, w = run(cycles, 1, f"jump1_{cycles}")
    full = wall / n * 720000
    row(f"no jump, first {cycles} cycles", wall, n, t, d, w)
    print(f"{'no jump, 18 000 cycles (extrap.)':<34} {full:9.0f} s {720000:8d} inc  (target < 600 s: "
          f"{'met' if full < 600 else 'not met'}; CPU {t['cpu'] / n * 720000:.0f} s)")


def main():
    global CFE2D
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cycles", type=int, default=18000,
                    help="cycles of the run without a jump (below 18 000: extrapolated)")
    ap.add_argument("--skip-jump", action="store_true", help="leave out the jump-100 run")
    ap.add_argument("--cfe2d", default=CFE2D, help="the binary to measure (default bin/cfe2d)")
    args = ap.parse_args()
    CFE2D = os.path.abspath(args.cfe2d)
    table(args.cycles, args.skip_jump)


if __name__ == "__main__":
    main()
