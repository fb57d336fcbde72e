#!/usr/bin/env python3
"""Worn profiles of a cfe2d run with *WEAR, against the cycles.

Reads the contact table <job>_contact.csv (the columns wear_slave,
wear_master, worn_x, worn_y that a wearing pair adds, docs/contact.md
"Wear") and plots, for one pair, the worn depth of its master surface (the
master rows: node position, depth) and of its slave surface (the slave
rows: the point's position, the slave's depth) at the increments that end
a cycle, drawn below the surface (depth negative). A cycle is `--period`
of total time (default 1, as a periodic amplitude of omega = 2 pi); with a
cycle jump N (`--jump`, the *WEAR card's third value) each computed cycle
stands for N. Reference profiles (`--reference file.csv`, columns x,
depth in the run's units, optional third column a label; more than one
may be given) are drawn over them, e.g. a measured scar.

  python3 scripts/plot_wear.py job_contact.csv -o wear.png
  python3 scripts/plot_wear.py job_contact.csv --jump 100 --scale 1e3 --unit um \\
      --reference measured.csv -o scar.png

Prints one line per plotted cycle: the cycle, the largest depth of each
surface and the width over which the master's depth exceeds 1 % of its
largest.
"""
import argparse
import csv
import sys
from collections import defaultdict


def read_table(path):
    """Rows of the contact table as dicts; stops if it has no wear columns."""
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if not rows or "wear_master" not in rows[0]:
        sys.exit(f"{path}: no wear columns (a run without *WEAR?)")
    return rows


def profiles(rows, pair):
    """{(step, increment): (total time, master [(x, h)], slave [(x, h)])}
    for one pair, each profile sorted by x."""
    out = defaultdict(lambda: [0.0, [], []])
    for r in rows:
        if int(r["pair"]) != pair:
            continue
        key = (int(r["step"]), int(r["increment"]))
        out[key][0] = float(r["time"])
        if r["side"] == "master":
            out[key][1].append((float(r["x"]), float(r["wear_master"])))
        else:
            out[key][2].append((float(r["x"]), float(r["wear_slave"])))
    for v in out.values():
        v[1].sort()
        v[2].sort()
    return dict(sorted(out.items()))


def cycle_ends(prof, start, period, every):
    """The increments that end every `every`-th cycle (total time less
    start within 1e-9 of a multiple of period), and the last one."""
    keys = list(prof)
    chosen = []
    for k in keys:
        c = (prof[k][0] - start) / period
        if abs(c - round(c)) <= 1e-9 * max(1.0, c) and round(c) > 0 and round(c) % every == 0:
            chosen.append(k)
    if keys and keys[-1] not in chosen:
        chosen.append(keys[-1])
    return chosen


def width(profile, frac=0.01):
    """Extent in x of the points whose depth exceeds frac of the largest."""
    hmax = max((h for _, h in profile), default=0.0)
    xs = [x for x, h in profile if hmax > 0.0 and h > frac * hmax]
    return (max(xs) - min(xs)) if xs else 0.0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("table", help="<job>_contact.csv of a run with *WEAR")
    ap.add_argument("-o", "--output", default="wear_profiles.png")
    ap.add_argument("--pair", type=int, default=1)
    ap.add_argument("--period", type=float, default=1.0, help="total time of one cycle")
    ap.add_argument("--start", type=float, default=0.0, help="total time at which the cycles begin")
    ap.add_argument("--jump", type=float, default=1.0, help="cycle-jump factor N of the *WEAR card")
    ap.add_argument("--every", type=int, default=1, help="plot every n-th computed cycle")
    ap.add_argument("--scale", type=float, default=1.0, help="factor on the depths (e.g. 1e3: mm to um)")
    ap.add_argument("--unit", default="", help="the depths' unit after --scale, for the axis label")
    ap.add_argument("--reference", action="append", default=[], help="x,depth[,label] CSV; may repeat")
    args = ap.parse_args()

    prof = profiles(read_table(args.table), args.pair)
    if not prof:
        sys.exit(f"{args.table}: no rows of pair {args.pair}")
    chosen = cycle_ends(prof, args.start, args.period, args.every)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    cmap = plt.get_cmap("viridis")
    for i, k in enumerate(chosen):
        t, master, slave = prof[k]
        cycles = (t - args.start) / args.period * args.jump
        colour = cmap(i / max(1, len(chosen) - 1))
        for ax, p in ((axes[0], master), (axes[1], slave)):
            ax.plot([x for x, _ in p], [-args.scale * h for _, h in p], color=colour, label=f"{cycles:g} cycles")
        print(f"cycle {cycles:g}: master depth {args.scale * max(h for _, h in master):.6g} {args.unit}, "
              f"slave depth {args.scale * max((h for _, h in slave), default=0.0):.6g} {args.unit}, "
              f"master width {width(master):.6g}")
    for path in args.reference:
        with open(path) as f:
            pts = [r for r in csv.reader(f) if r and not r[0].lstrip().startswith("#")]
        data = []
        for r in pts:
            try:
                data.append((float(r[0]), float(r[1])))
            except ValueError:
                continue           # a header line
        label = pts[-1][2] if len(pts[-1]) > 2 else path
        axes[0].plot([x for x, _ in data], [-args.scale * abs(h) for _, h in data], "k--", label=label)
    unit = f" ({args.unit})" if args.unit else ""
    axes[0].set_ylabel("master worn depth" + unit)
    axes[1].set_ylabel("slave worn depth" + unit)
    axes[1].set_xlabel("x")
    for ax in axes:
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
