#!/usr/bin/env python3
"""Make the CalculiX reference of tests/test_friction_calculix.py from ccx's
own files (CalculiX is not needed by the tests; see tests/calculix/README.md).

    python3 scripts/calculix_friction_reference.py tests/calculix/friction_blocks.inp \\
        large=/scratch/large/friction_blocks small=/scratch/small/friction_blocks --out tests/calculix

Each VARIANT=JOB names a ccx job (JOB.dat, JOB.sta, JOB.frd) of the deck or
of a variant of it. Written:

  friction_blocks_reactions.csv  variant, step, increment, total_time and the
                                 summed reactions RF1, RF2 of the node sets
                                 TOP and BOTTOM at every increment (.sta gives
                                 the step and increment of each time)
  friction_blocks_contact.csv    variant, total_time, node, x, pressure, shear:
                                 *CONTACT PRINT CSTR of the slave nodes, the
                                 mean of each 2D node's expanded copies (mapped
                                 through the .frd of *NODE FILE, OUTPUT=3D)
"""
import argparse
import csv
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from calculix_results import (map_expanded_nodes, read_dat_set_forces, read_dat_slave_node_contact,  # noqa: E402
                              read_deck_mesh, read_frd_mesh)


def read_sta(path):
    """{total time: (step, increment)} of a ccx .sta file (the last attempt
    of each increment)."""
    out = {}
    with open(path) as f:
        for line in f:
            p = line.split()
            if len(p) >= 7 and p[0].isdigit() and p[1].isdigit():
                out[float(p[4])] = (int(p[0]), int(p[1]))
    return out


def nearest_time(times, t):
    k = min(times, key=lambda s: abs(s - t))
    if abs(k - t) > 1e-6 * max(1.0, abs(t)):
        raise SystemExit(f"no increment at time {t} in {sorted(times)}")
    return k


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("deck")
    ap.add_argument("jobs", nargs="+", metavar="VARIANT=JOB")
    ap.add_argument("--out", default=".")
    args = ap.parse_args()
    xy, elements = read_deck_mesh(args.deck)
    conn2d = {e: c for e, (_, c) in elements.items()}
    reactions, contact = [], []
    for job in args.jobs:
        variant, _, base = job.partition("=")
        steps = read_sta(base + ".sta")
        forces = read_dat_set_forces(base + ".dat")
        for t in sorted(forces["TOP"]):
            step, inc = steps[nearest_time(steps, t)]
            row = [variant, step, inc, f"{t:.7g}"]
            for name in ("TOP", "BOTTOM"):
                f = np.array(list(forces[name][t].values()))
                row += [f"{f[:, 0].sum():.7e}", f"{f[:, 1].sum():.7e}"]
            reactions.append(row)
        frd_xyz, frd_elements = read_frd_mesh(base + ".frd")
        groups, coincident, off = map_expanded_nodes(frd_xyz, frd_elements, xy, conn2d)
        back = {q: n for n, qs in groups.items() for q in qs}
        for t, rows in sorted(read_dat_slave_node_contact(base + ".dat").items()):
            per = {}
            for q, v in rows.items():
                per.setdefault(back[q], []).append(v)
            for n in sorted(per, key=lambda n: xy[n][0]):
                p, s = np.mean(np.array(per[n])[:, :2], axis=0)
                contact.append([variant, f"{t:.7g}", n, f"{xy[n][0]:.7g}", f"{p:.7e}", f"{s:.7e}"])
    with open(os.path.join(args.out, "friction_blocks_reactions.csv"), "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["variant", "step", "increment", "total_time", "top_rf1", "top_rf2", "bottom_rf1", "bottom_rf2"])
        w.writerows(reactions)
    with open(os.path.join(args.out, "friction_blocks_contact.csv"), "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["variant", "total_time", "node", "x", "pressure", "shear"])
        w.writerows(contact)


if __name__ == "__main__":
    main()
