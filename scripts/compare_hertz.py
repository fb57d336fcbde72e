#!/usr/bin/env python3
"""Compare the contact pressures of a cfe2d run with Hertz (line contact).

For every increment with closed contact elements, the load P is the FE
contact force (the sum of the slave nodal forces, times the symmetry factor
of a half model), and the FE pressures on the slave and on the master side
are compared with Hertz's solution for that P:

  a_FE, p0_FE   from a least-squares fit of the Hertz ellipse
                p^2 = p0^2 (1 - x^2/a^2) to the nodal pressures with
                |x - x0| < 0.8 a_Hertz (slave side)
  node p0 err   the largest nodal pressure against p0 (no fitting)
  L2            sqrt(sum (p - p_H)^2 / sum p_H^2) over |x - x0| < a_Hertz
  s-m           max |p_slave - p_master(x_slave)| / p0 over |x - x0| < 0.8 a

The run may be force- or displacement-driven: P always comes from the
contact force; u_top is the mean vertical displacement of a printed node
set (--load-set) when the listing has it.

E* and the stress state come from the deck (<result_dir>/<job>.inp, or
--deck): the materials of its sections (two materials: the two bodies;
one: both), and plane stress or strain from STATE= on *SOLID SECTION or
the element types (CPS*, CPE*). --E, --nu and --plane override them.

Usage: compare_hertz.py RESULT_DIR [--job hertz] [--deck DECK] [--radius 10]
       [--E E1 [E2]] [--nu NU1 [NU2]] [--plane stress|strain] [--symmetry 1]
       [--x0 0] [--load-set CYL_TOP] [--plots] [--quiet]
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
from cfe2d_listing import is_closed, read_listing  # noqa: E402
from hertz import HertzLine, HertzPoint, effective_modulus, point_modulus  # noqa: E402

__all__ = ["read_contact_table", "compare", "compare_point", "format_table", "read_deck_cards", "deck_materials",
           "deck_stress_state", "line_contact_modulus", "top_displacement"]


# the contact table's columns of a model with friction
FRICTION_COLUMNS = ("shear_force", "shear", "slip", "slip_increment")


def read_contact_table(path):
    """{(step, increment): {"time":..., "slave": arrays, "master": arrays}}.
    Arrays per side: node, x, y, gap, force, pressure, closed (CLOSED, STICK
    or SLIP), state; and, when the model has friction, shear_force, shear,
    slip, slip_increment (zeros on master rows' slip)."""
    incs = defaultdict(lambda: {"slave": defaultdict(list), "master": defaultdict(list)})
    with open(path) as f:
        rd = csv.DictReader(f)
        numeric = ["node", "x", "y", "gap", "force", "pressure"]
        numeric += [k for k in FRICTION_COLUMNS if k in (rd.fieldnames or [])]
        for r in rd:
            key = (int(r["step"]), int(r["increment"]))
            inc = incs[key]
            inc["time"] = float(r["time"])
            side = inc[r["side"]]
            for k in numeric:
                side[k].append(float(r[k]))
            side["closed"].append(is_closed(r["state"]))
            side["state"].append(r["state"])
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


def compare(table, radius, estar, x0=0.0, displacement=None, symmetry=1):
    """Rows of the comparison, one per increment in contact. symmetry: the
    whole contact force over the modelled one (2 for a half model cut at
    x0: its slave nodes lie on one side of x0)."""
    rows = []
    for key in sorted(table):
        inc = table[key]
        s, m = inc["slave"], inc["master"]
        P = symmetry * float(np.sum(s["force"]))
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


def read_deck_cards(path):
    """The cards of a keyword deck and the files it *INCLUDEs, in order:
    a list of (keyword, {PARAMETER: value}, [data lines as field lists])."""
    cards = []

    def read(p):
        with open(p) as f:
            for raw in f:
                line = raw.strip()
                if not line or line.startswith("**"):
                    continue
                if line.startswith("*"):
                    fields = [x.strip() for x in line[1:].split(",")]
                    name = " ".join(fields[0].upper().split())
                    params = {}
                    for fld in fields[1:]:
                        if fld:
                            k, _, v = fld.partition("=")
                            params[" ".join(k.upper().split())] = v.strip()
                    if name == "INCLUDE":
                        read(os.path.join(os.path.dirname(p), params["INPUT"]))
                        continue
                    cards.append((name, params, []))
                elif cards:
                    cards[-1][2].append([x.strip() for x in line.rstrip(",").split(",")])

    read(path)
    return cards


def deck_materials(cards):
    """{material name: (E, nu)} of the isotropic *ELASTIC materials."""
    out, current = {}, None
    for name, params, data in cards:
        if name == "MATERIAL":
            current = params["NAME"].upper()
        elif name == "ELASTIC" and current is not None and data:
            out[current] = (float(data[0][0]), float(data[0][1]))
    return out


_STATES = {"CPS": "stress", "CPE": "strain", "CAX": "axisymmetric",
           "PLANE STRESS": "stress", "PLANE STRAIN": "strain", "AXISYMMETRIC": "axisymmetric"}


def deck_stress_state(cards):
    """"stress", "strain" or "axisymmetric": STATE= of the sections, or
    the continuum element types where a section does not say."""
    sections = [p for n, p, _ in cards if n == "SOLID SECTION"]
    states = {_STATES[p["STATE"].upper()] for p in sections if "STATE" in p}
    if not sections or any("STATE" not in p for p in sections):
        for n, p, _ in cards:
            prefix = p.get("TYPE", "").upper()[:3]
            if n == "ELEMENT" and prefix in _STATES:
                states.add(_STATES[prefix])
    if len(states) != 1:
        raise ValueError(f"cannot tell the stress state from the deck ({sorted(states) or 'none'}); give --plane")
    return states.pop()


def line_contact_modulus(cards, plane=None, e=None, nu=None):
    """(E*, plane, [(E1, nu1), (E2, nu2)]) of the line contact the deck
    describes: the materials of its sections (one material: both bodies),
    plane stress or strain; plane, e and nu (lists of one or two values)
    override what the deck says."""
    plane = plane or deck_stress_state(cards)
    if plane not in ("stress", "strain"):
        raise ValueError(f"plane {plane}: Hertz line contact needs plane stress or plane strain")
    if e is None:
        mats = deck_materials(cards)
        used = []
        for n, p, _ in cards:
            if n == "SOLID SECTION" and p["MATERIAL"].upper() not in used:
                used.append(p["MATERIAL"].upper())
        if not 1 <= len(used) <= 2:
            raise ValueError(f"{len(used)} section materials: give --E and --nu of the two bodies")
        pairs = [mats[u] for u in used]
    else:
        nu = nu or [0.3]
        pairs = [(e[0], nu[0]), (e[-1], nu[-1])]
    if len(pairs) == 1:
        pairs = pairs * 2
    return effective_modulus(pairs[0][0], pairs[0][1], pairs[1][0], pairs[1][1], plane=plane), plane, pairs


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
    ap.add_argument("--deck", help="the deck run (default RESULT_DIR/JOB.inp)")
    ap.add_argument("--radius", type=float, default=10.0)
    ap.add_argument("--E", type=float, nargs="+", help="Young's moduli of the two bodies (one: both)")
    ap.add_argument("--nu", type=float, nargs="+", help="Poisson's ratios of the two bodies (one: both)")
    ap.add_argument("--plane", choices=["stress", "strain"], help="stress state (default: from the deck)")
    ap.add_argument("--symmetry", type=float, default=1.0,
                    help="whole contact force / modelled one (2 for a half model)")
    ap.add_argument("--x0", type=float, default=0.0, help="x of the cylinder's axis (the symmetry plane)")
    ap.add_argument("--load-set", default="CYL_TOP", help="node set whose mean U2 is reported as u_top")
    ap.add_argument("--plots", action="store_true", help="also draw the PNG plots")
    ap.add_argument("--quiet", action="store_true", help="write <job>_hertz.txt only")
    ap.add_argument("--point", action="store_true",
                    help="point contact of an axisymmetric model (sphere on flat): x is the radius, P the "
                         "ring total; the loaded edge is the node set SPHERE_TOP")
    args = ap.parse_args(argv)
    job = os.path.join(args.result_dir, args.job)
    deck = args.deck or job + ".inp"
    cards = read_deck_cards(deck) if os.path.exists(deck) else []
    if not cards and args.E is None:
        args.E, args.nu = [210000.0], args.nu or [0.3]     # the flagship's steel
    # (point contact needs only the materials: its E* has the plane-strain form)
    plane = "strain" if args.point else args.plane or (None if cards else "stress")
    estar, plane, mats = line_contact_modulus(cards, plane=plane,
                                              e=args.E, nu=args.nu)
    table = read_contact_table(job + "_contact.csv")
    if args.point:
        return point_main(job, table, args.radius, mats)
    disp = top_displacement(job + ".out", args.load_set)
    rows = compare(table, args.radius, estar, x0=args.x0, displacement=disp, symmetry=args.symmetry)
    text = format_table(rows)
    title = (f"# Hertz comparison of {job}: R = {args.radius}, plane {plane}, E1 = {mats[0][0]:g}, "
             f"nu1 = {mats[0][1]:g}, E2 = {mats[1][0]:g}, nu2 = {mats[1][1]:g}, E* = {estar:.6g}, "
             f"symmetry factor {args.symmetry:g}")
    if not args.quiet:
        print(title)
        print(text)
    with open(job + "_hertz.txt", "w") as f:
        f.write(title + "\n" + text + "\n")
    if args.plots:
        if args.symmetry != 1:
            print("(plots are drawn for whole models only)")
        else:
            import plots_hertz
            plots_hertz.draw_all(args.result_dir, args.job, table, rows, args.radius, estar)
    return rows


def point_main(job, table, radius, mats):
    """--point: the axisymmetric comparison, printed and written to
    <job>_hertz.txt; mats the (E, nu) of the two bodies (from the deck or
    --E/--nu)."""
    disp = top_displacement(job + ".out", "SPHERE_TOP")
    estar = point_modulus(mats[0][0], mats[0][1], mats[1][0], mats[1][1])
    rows = compare_point(table, radius, estar, displacement=disp)
    text = format_table(rows)
    print(text)
    with open(job + "_hertz.txt", "w") as f:
        f.write(f"# Hertz point contact of {job}: R = {radius}, E* = {estar:.6g} (axisymmetric)\n")
        f.write(text + "\n")
    return rows


if __name__ == "__main__":
    main()
