#!/usr/bin/env python3
"""Error study of the Hertz case at the peak load (increment 10).

1. Mesh convergence: coarse, default and fine meshes (h = 0.1, 0.05, 0.025 mm
   at the contact), the observed order of the FE peak pressure and
   half-width (self-convergence, ratio 2) and their distance from Hertz.
2. Model error: the default mesh with a plate three times larger
   (240 x 120 mm) and with half the approach (a/R about 0.09 instead of
   0.13): what changes there is Hertz's half-space idealisation, not the
   discretisation.

  python3 scripts/hertz_study.py [--out results/study] [--skip-fine]
"""
import argparse
import math
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import compare_hertz  # noqa: E402
import run_hertz  # noqa: E402
from hertz import effective_modulus  # noqa: E402

ESTAR = effective_modulus(210000.0, 0.3)


def peak_row(outdir, **kw):
    t0 = time.time()
    job, _ = run_hertz.run_case(outdir, **kw)
    table = compare_hertz.read_contact_table(job + "_contact.csv")
    rows = compare_hertz.compare(table, 10.0, ESTAR, displacement=compare_hertz.top_displacement(job + ".out"))
    row = max(rows, key=lambda r: r["P"])
    with open(job + ".out") as f:
        eqs = next(int(line.split()[1]) for line in f if line.startswith("equations "))
    row.update(seconds=time.time() - t0, equations=eqs)
    return row


def fmt(label, r):
    return (f"{label:<26} {r['equations']:>9d} {r['P']:>10.1f} {r['a_FE']:>8.4f} {r['err_a']:>7.2%} "
            f"{r['p0_FE']:>8.1f} {r['err_p0']:>7.2%} {r['err_p0_node']:>8.2%} {r['L2_slave']:>6.2%} "
            f"{r['slave_master']:>6.2%} {r['seconds']:>7.1f}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=os.path.join(os.path.dirname(HERE), "results", "study"))
    ap.add_argument("--skip-fine", action="store_true", help="leave out the fine mesh (minutes)")
    args = ap.parse_args(argv)
    head = (f"{'case (peak increment)':<26} {'equations':>9} {'P':>10} {'a_FE':>8} {'err_a':>7} {'p0_FE':>8} "
            f"{'err_p0':>7} {'node_p0':>8} {'L2_s':>6} {'s-m':>6} {'time_s':>7}")
    print(head)
    meshes = ["coarse", "default"] + ([] if args.skip_fine else ["fine"])
    conv = {}
    for mesh in meshes:
        conv[mesh] = peak_row(os.path.join(args.out, mesh), mesh=mesh)
        print(fmt(f"mesh {mesh}", conv[mesh]), flush=True)
    big = peak_row(os.path.join(args.out, "plate3"), plate=3.0)
    print(fmt("default mesh, plate x3", big), flush=True)
    half = peak_row(os.path.join(args.out, "approach_half"), approach=0.2)
    print(fmt("default mesh, approach/2", half), flush=True)
    if len(conv) == 3:
        print()
        for key, name in (("p0_FE", "p0"), ("a_FE", "a")):
            # the load differs slightly between meshes: compare p0/sqrt(P)
            # and a/sqrt(P), which Hertz makes load-independent
            v = [conv[m][key] / math.sqrt(conv[m]["P"]) for m in meshes]
            d1, d2 = v[0] - v[1], v[1] - v[2]
            order = math.log(abs(d1 / d2), 2) if d2 != 0 and d1 / d2 > 0 else float("nan")
            print(f"observed order of {name}/sqrt(P): {order:.2f} "
                  f"(coarse-default {d1 / v[2]:+.3%}, default-fine {d2 / v[2]:+.3%} of the fine value)")


if __name__ == "__main__":
    main()
