#!/usr/bin/env python3
"""Compare the contact pressures of a cfe2d run with Hertz.

For every increment with closed contact elements, the load P is the FE
contact force (sum of the slave nodal forces), and the FE pressures on the
slave and on the master side are compared with Hertz's solution for that P:

  a_FE, p0_FE   from a least-squares fit of the Hertz ellipse
                p^2 = p0^2 (1 - x^2/a^2) to the nodal pressures with
                |x| < 0.8 a_Hertz (slave side)
  node p0 err   the largest nodal pressure against p0 (no fitting)
  L2            sqrt(sum (p - p_H)^2 / sum p_H^2) over |x| < a_Hertz
  s-m           max |p_slave - p_master(x_slave)| / p0 over |x| < 0.8 a

Usage: compare_hertz.py RESULT_DIR [--job hertz] [--radius 10] [--E 210000]
       [--nu 0.3] [--plane stress] [--plots]
       compare_hertz.py RESULT_DIR --point --job hertz_point [--radius 10] ...
       (point contact of a sphere, axisymmetric: a = (3PR/(4E*))^(1/3),
       p0 = 3P/(2 pi a^2), P the whole ring's contact force)
"""
import argparse
import csv
import os
import sys
from collections import defaultdict

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cfe2d_listing import read_listing  # noqa: E402
from hertz import HertzLine, HertzPoint, effective_modulus, point_modulus  # noqa: E402

__all__ = ["read_contact_table", "compare", "compare_point", "format_table"]


def read_contact_table(path):
    """{(step, increment): {"time":..., "slave": arrays, "master": arrays}}"""
    incs = defaultdict(lambda: {"slave": defaultdict(list), "master": defaultdict(list)})
    with open(path) as f:
        for r in csv.DictReader(f):
            key = (int(r["step"]), int(r["increment"]))
            inc = incs[key]
            inc["time"] = float(r["time"])
            side = inc[r["side"]]
            for k in ("node", "x", "y", "gap", "force", "pressure"):
                side[k].append(float(r[k]))
            side["closed"].append(r["state"] == "CLOSED")
    out = {}
    for key, inc in incs.items():
        out[key] = {"time": inc["time"]}
        for s in ("slave", "master"):
            d = {k: np.array(v) for k, v in inc[s].items()}
            order = np.argsort(d["x"]) if len(d.get("x", [])) else []
            out[key][s] = {k: v[order] for k, v in d.items()}
    return out


def fit_ellipse(x, p, window):
    """p0 and a of the ellipse through the points with |x| < window."""
    m = (np.abs(x) < window) & (p > 0)
    if m.sum() < 3:
        return float("nan"), float("nan")
    A = np.vstack([np.ones(m.sum()), x[m] ** 2]).T
    (c0, c1), *_ = np.linalg.lstsq(A, p[m] ** 2, rcond=None)
    if c0 <= 0 or c1 >= 0:
        return float("nan"), float("nan")
    return float(np.sqrt(c0)), float(np.sqrt(-c0 / c1))


def compare(table, radius, estar, x0=0.0, displacement=None):
    """Rows of the comparison, one per increment in contact."""
    rows = []
    for key in sorted(table):
        inc = table[key]
        s, m = inc["slave"], inc["master"]
        P = float(np.sum(s["force"]))
        closed = int(np.sum(s["closed"]))
        row = {"step": key[0], "increment": key[1], "time": inc["time"], "P": P, "closed": closed,
               "u": displacement.get(key, float("nan")) if displacement else float("nan"),
               "max_penetration": float(max(0.0, -np.min(s["gap"][s["closed"]]))) if closed else 0.0}
        if closed < 3 or P <= 0:
            rows.append(row)
            continue
        h = HertzLine(P, radius, estar)
        xs, xm = s["x"] - x0, m["x"] - x0
        p0_fe, a_fe = fit_ellipse(xs, s["pressure"], 0.8 * h.a)
        inside_s, inside_m = np.abs(xs) < h.a, np.abs(xm) < h.a
        l2 = lambda x, p, w: float(np.sqrt(np.sum((p[w] - h(x[w])) ** 2) / np.sum(h(x[w]) ** 2)))  # noqa: E731
        core = np.abs(xs) < 0.8 * h.a
        pm_at_s = np.interp(xs[core], xm, m["pressure"])
        row.update({
            "a_H": h.a, "a_FE": a_fe, "err_a": (a_fe - h.a) / h.a,
            "p0_H": h.p0, "p0_FE": p0_fe, "err_p0": (p0_fe - h.p0) / h.p0,
            "err_p0_node": (float(np.max(s["pressure"])) - h.p0) / h.p0,
            "L2_slave": l2(xs, s["pressure"], inside_s), "L2_master": l2(xm, m["pressure"], inside_m),
            "slave_master": float(np.max(np.abs(s["pressure"][core] - pm_at_s)) / h.p0),
        })
        rows.append(row)
    return rows


def compare_point(table, radius, estar, displacement=None, min_closed=3):
    """Rows of the point-contact (axisymmetric) comparison, one per
    increment: x of the contact table is the radius r, P the total contact
    force (whole ring), Hertz's a = (3PR/(4E*))^(1/3), p0 = 3P/(2 pi a^2);
    a_FE, p0_FE from the fit of the ellipse p^2 = p0^2 (1 - r^2/a^2) to the
    slave pressures with r < 0.8 a (a slave row is a node or a Gauss point
    of a slave face)."""
    rows = []
    for key in sorted(table):
        inc = table[key]
        s, m = inc["slave"], inc["master"]
        P = float(np.sum(s["force"]))
        closed = int(np.sum(s["closed"]))
        row = {"step": key[0], "increment": key[1], "time": inc["time"], "P": P, "closed": closed,
               "u": displacement.get(key, float("nan")) if displacement else float("nan"),
               "max_penetration": float(max(0.0, -np.min(s["gap"][s["closed"]]))) if closed else 0.0}
        if closed < min_closed or P <= 0:
            rows.append(row)
            continue
        h = HertzPoint(P, radius, estar)
        # The axis node of a 3-node master face has no area in
        # axisymmetry (the integral of N r vanishes): its pressure is
        # undefined (listed as 0) and left out.
        keep = ~((m["x"] <= 0.0) & (m["pressure"] == 0.0))
        m = {k: v[keep] for k, v in m.items()}
        xs, xm = s["x"], m["x"]
        p0_fe, a_fe = fit_ellipse(xs, s["pressure"], 0.8 * h.a)
        inside_s, inside_m = xs < h.a, xm < h.a
        l2 = lambda x, p, w: float(np.sqrt(np.sum((p[w] - h(x[w])) ** 2) / np.sum(h(x[w]) ** 2)))  # noqa: E731
        core = xs < 0.8 * h.a
        pm_at_s = np.interp(xs[core], xm, m["pressure"])
        row.update({
            "a_H": h.a, "a_FE": a_fe, "err_a": (a_fe - h.a) / h.a,
            "p0_H": h.p0, "p0_FE": p0_fe, "err_p0": (p0_fe - h.p0) / h.p0,
            "err_p0_node": (float(np.max(s["pressure"])) - h.p0) / h.p0,
            "L2_slave": l2(xs, s["pressure"], inside_s), "L2_master": l2(xm, m["pressure"], inside_m),
            "slave_master": float(np.max(np.abs(s["pressure"][core] - pm_at_s)) / h.p0),
        })
        rows.append(row)
    return rows


COLUMNS = [("increment", "inc", "{:>4d}"), ("u", "u_top", "{:>9.4f}"), ("P", "P", "{:>10.2f}"),
           ("a_FE", "a_FE", "{:>7.4f}"), ("a_H", "a_H", "{:>7.4f}"), ("err_a", "err_a", "{:>7.2%}"),
           ("p0_FE", "p0_FE", "{:>8.1f}"), ("p0_H", "p0_H", "{:>8.1f}"), ("err_p0", "err_p0", "{:>7.2%}"),
           ("err_p0_node", "node_p0", "{:>7.2%}"), ("L2_slave", "L2_s", "{:>6.2%}"),
           ("L2_master", "L2_m", "{:>6.2%}"), ("slave_master", "s-m", "{:>6.2%}"),
           ("max_penetration", "max_pen", "{:>9.2e}")]


def format_table(rows):
    lines = [" ".join(f"{h:>{len(fmt.format(0) if 'd' in fmt else fmt.format(0.0))}}"
                      for _, h, fmt in COLUMNS)]
    for r in rows:
        cells = []
        for key, _, fmt in COLUMNS:
            v = r.get(key)
            width = len(fmt.format(0) if "d" in fmt else fmt.format(0.0))
            cells.append(fmt.format(v) if v is not None and v == v else "-".rjust(width))
        lines.append(" ".join(cells))
    return "\n".join(lines)


def top_displacement(listing_path, nset="CYL_TOP"):
    """Prescribed displacement of the loaded edge per increment."""
    out = {}
    for inc in read_listing(listing_path).increments:
        if inc.has("NODE U", set=nset):
            out[(inc.step, inc.number)] = float(np.mean(inc.block("NODE U", set=nset)["U2"]))
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("result_dir")
    ap.add_argument("--job", default="hertz")
    ap.add_argument("--radius", type=float, default=10.0)
    ap.add_argument("--E", type=float, default=210000.0)
    ap.add_argument("--nu", type=float, default=0.3)
    ap.add_argument("--plane", choices=["stress", "strain"], default="stress")
    ap.add_argument("--plots", action="store_true", help="also draw the PNG plots")
    ap.add_argument("--point", action="store_true",
                    help="point contact of an axisymmetric model (sphere on flat): x is the radius, P the "
                         "ring total; the loaded edge is the node set SPHERE_TOP")
    args = ap.parse_args(argv)
    job = os.path.join(args.result_dir, args.job)
    table = read_contact_table(job + "_contact.csv")
    if args.point:
        return point_main(args, job, table)
    disp = top_displacement(job + ".out")
    estar = effective_modulus(args.E, args.nu, plane=args.plane)
    rows = compare(table, args.radius, estar, displacement=disp)
    text = format_table(rows)
    print(text)
    with open(job + "_hertz.txt", "w") as f:
        f.write(f"# Hertz comparison of {job}: R = {args.radius}, E* = {estar:.6g} (plane {args.plane})\n")
        f.write(text + "\n")
    if args.plots:
        import plots_hertz
        plots_hertz.draw_all(args.result_dir, args.job, table, rows, args.radius, estar)
    return rows


def point_main(args, job, table):
    """--point: the axisymmetric comparison, printed and written to
    <job>_hertz.txt."""
    disp = top_displacement(job + ".out", nset="SPHERE_TOP")
    estar = point_modulus(args.E, args.nu)
    rows = compare_point(table, args.radius, estar, displacement=disp)
    text = format_table(rows)
    print(text)
    with open(job + "_hertz.txt", "w") as f:
        f.write(f"# Hertz point contact of {job}: R = {args.radius}, E* = {estar:.6g} (axisymmetric)\n")
        f.write(text + "\n")
    return rows


if __name__ == "__main__":
    main()
