#!/usr/bin/env python3
"""Accuracy of stick and slip on a mesh of the kind users make (issue 33,
item 4): a cylinder R = 10 mm pressed on a flat to a/R = 0.05, both plane-
strain steel, the two meshes not matching, each graded away from the
contact with 3:1 transition rows; then pushed sideways to Q* = mu P / 2 and
back to Q = 0 (Cattaneo-Mindlin, Mindlin-Deresiewicz).

    python3 scripts/stick_slip_accuracy.py [--cases nts,sts] [--hs 0.025 --hm 0.03] [--out DIR]
    # against the converged bodies, the cylinder's nodes moved by 0.4 spacings:
    python3 scripts/stick_slip_accuracy.py --cases sts --fixed-plate --shift 0.4 \
        --against tests/stick_slip_converged.json
    # the converged reference of tests/test_stick_slip_accuracy.py (about 10 minutes):
    python3 scripts/stick_slip_accuracy.py --cases sts --fixed-plate --incs 2,16,16 --hs 0.00625 --hm 0.0075 \
        --save fine.json --reference tests/stick_slip_converged.json --coarser h2.json
    # (h2.json: the same with --hs 0.0125 --hm 0.015 --save h2.json)
    # a/R = 0.025 on the mesh scaled with a:  --load 0.25 --hs 0.0125 --hm 0.015

Three figures per coupling, against the closed forms of two half-spaces of
one material (tests/test_friction.py states them):
  shear_press   the shear traction left by the pressing alone (zero by the
                closed form), rms over |x| < 0.9 a, in % of mu p0;
  shear_qstar   the shear traction at Q* against Cattaneo's, rms over
                |x| < 0.9 a, % of mu p0; shear_back the same back at Q = 0
                against Mindlin-Deresiewicz's locked-in traction q* - 2 q';
  stick_end     the stick zone's ends (the run of STICK slave rows about
                x = 0; its end the midpoint to the first SLIP row) against
                c = a sqrt(1 - Q / (mu P)) while loading and
                c' = a sqrt(1 - (Q* - Q) / (2 mu P)) while unloading, the
                largest distance in slave spacings.
a and p0 are the FE contact's (the Hertz ellipse fitted to the slave
pressures over |x| < 0.8 a_Hertz), x the slave nodes' reference positions.

The mesh (write_mesh): the cylinder is the cap |x| < 0.8 R of the disk,
its top flat at y = R (rigid: every top node tied to a reference node, as
tests/test_friction.py's Cattaneo case), meshed with columns of uniform
width hs along x at the contact, rows of square elements, and 3:1
transition rows (three elements into one) every few rows upwards; the
plate 2 W wide and W deep, likewise from hm at its top. The contact
surfaces are the top faces within |x| < 2.5 a (slave: the cylinder).
"""
import argparse
import math
import os
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)

R, E, NU, MU = 10.0, 210000.0, 0.3, 0.3
A_TARGET = 0.05 * R                          # a/R = 0.05
ESTAR = E / (2.0 * (1.0 - NU ** 2))          # plane strain, one material
P = math.pi * ESTAR * A_TARGET ** 2 / (4.0 * R)     # Hertz: a^2 = 4 P R / (pi E*)
QSTAR = 0.5 * MU * P
#: The deck's slave (cylinder) and master (plate) spacings at the contact.
HS, HM = 0.025, 0.03
#: The default mesh's plate (hm = 0.03, W = 20): 38.88 mm wide, 20.01 deep;
#: the refinement study keeps it (write_mesh's plate_size).
PLATE_SIZE = (19.44, 20.01)


class Body:
    """A structured quadrilateral mesh in parameter coordinates (s, d):
    s along the contact surface, d the depth into the body; columns of
    width w at d = 0, and after each level's rows a 3:1 transition row
    (three columns into one); rows[level] rows of square elements per
    level, the last level's as many as reach depth. mapxy(s, d) gives the
    node's (x, y)."""

    def __init__(self, ncols, w, levels, rows, depth, mapxy, first_node, first_elem):
        self.nodes, self.key, self.elems = {}, {}, []
        self.top_faces = []                 # (element, face) at d = 0
        self._next, self._first_elem = first_node, first_elem
        self.mapxy = mapxy
        s0 = -0.5 * ncols * w
        stride, d, row = 1, 0.0, 0
        for level in range(levels + 1):
            n = ncols // stride
            h = stride * w
            nrows = rows[level] if level < levels else max(1, math.ceil((depth - d) / h))
            for _ in range(nrows):
                for i in range(n):
                    ids = [self._node(i * stride, row, s0 + i * h, d),
                           self._node((i + 1) * stride, row, s0 + (i + 1) * h, d),
                           self._node((i + 1) * stride, row + 1, s0 + (i + 1) * h, d + h),
                           self._node(i * stride, row + 1, s0 + i * h, d + h)]
                    self._elem(ids, top=(row == 0))
                d += h
                row += 1
            if level == levels:
                break
            # transition: three columns of width h into one of 3 h, the
            # row 1.5 h high, two nodes at mid-height inside each group
            ht = 1.5 * h
            for i in range(0, n, 3):
                k = [i * stride + j * stride for j in range(4)]
                s = [s0 + (i + j) * h for j in range(4)]
                t = [self._node(k[j], row, s[j], d) for j in range(4)]
                b0 = self._node(k[0], row + 1, s[0], d + ht)
                b3 = self._node(k[3], row + 1, s[3], d + ht)
                m1 = self._node(k[1], row + 0.5, s[1], d + 0.5 * ht)
                m2 = self._node(k[2], row + 0.5, s[2], d + 0.5 * ht)
                for ids in ([t[0], t[1], m1, b0], [t[1], t[2], m2, m1], [t[2], t[3], b3, m2], [m1, m2, b3, b0]):
                    self._elem(ids, top=(row == 0))
            d += ht
            row += 1
            stride *= 3
        self.depth = d
        self.top_rows = sorted(n for (k, r), n in self.key.items() if r == row)

    def _node(self, k, row, s, d):
        if (k, row) not in self.key:
            self.key[k, row] = self._next
            self.nodes[self._next] = (s, d)
            self._next += 1
        return self.key[k, row]

    def _elem(self, ids, top):
        self.elems.append(ids)
        if top:
            self.top_faces.append(len(self.elems) - 1)

    def finish(self):
        """Map to (x, y), orient every element counter-clockwise, and find
        the faces at d = 0 (Abaqus face numbers)."""
        self.xy = {n: self.mapxy(s, d) for n, (s, d) in self.nodes.items()}
        out = []
        for ids in self.elems:
            p = np.array([self.xy[n] for n in ids])
            area = 0.5 * np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1])
            assert abs(area) > 0.0
            out.append(ids if area > 0 else ids[::-1])
        self.elems = out
        faces = []
        for e in self.top_faces:
            ids = self.elems[e]
            for f in range(4):
                a, b = ids[f], ids[(f + 1) % 4]
                if self.nodes[a][1] == 0.0 and self.nodes[b][1] == 0.0:
                    faces.append((self._first_elem + e, f + 1, 0.5 * (self.nodes[a][0] + self.nodes[b][0])))
        self.surface_faces = faces
        return self


def columns(width, w, levels):
    """The number of columns of width about w over width, a multiple of
    3^levels (so that every transition row has whole groups) and even (a
    node at s = 0)."""
    unit = 2 * 3 ** levels
    return max(1, round(width / w / unit)) * unit


def write_mesh(path, hs=HS, hm=HM, levels=4, rows=(4, 3, 3, 3), plate_half=2.0 * R, contact=2.5 * A_TARGET,
               swap=False, plate_size=None, shift=0.0):
    """Writes the *NODE/*ELEMENT/sets of the cylinder (slave, element ids
    from 1) and the plate (from 100001) to path; returns (xy of every
    node, the cylinder's slave nodes sorted by x, the top's node ids, the
    number of elements). swap: the plate's surface nodes instead (the
    plate the slave). plate_size: (half width, depth) the plate gets
    exactly, whatever hm (the rows stretched to the depth; the width a
    whole number of the coarsest columns), so that a mesh refinement
    study keeps the bodies (PLATE_SIZE: the default mesh's). shift: the
    cylinder's mesh moved along x by this much (its nodes then sit
    elsewhere against the stick zone's ends; the body the same but for its
    cap's ends, 8.1 mm away)."""
    cap = 0.8 * R
    nc = columns(2 * cap, hs, levels)
    cap = 0.5 * nc * hs

    def cyl(s, d):
        # the cap's bottom on the circle, its top at y = R; vertical lines
        yb = R - math.sqrt(R * R - s * s)
        return (s, yb + d / R * (R - yb) if d <= R else R)

    cylinder = Body(nc, hs, levels, rows, R, cyl, 1, 1)
    # stretch the depth so that the parameter's depth ends at R (the top)
    scale = R / cylinder.depth
    cylinder.mapxy = lambda s, d: cyl(s + shift, d * scale)
    cylinder.finish()
    npl = columns(2 * plate_half, hm, levels)
    if plate_size is not None:
        npl = round(2 * plate_size[0] / hm)
        assert npl % (2 * 3 ** levels) == 0 and abs(npl * hm - 2 * plate_size[0]) < 1e-9, (hm, plate_size)
    plate = Body(npl, hm, levels, rows, plate_half, lambda s, d: (s, -d), 1000001, 100001)
    if plate_size is not None:
        stretch = plate_size[1] / plate.depth
        plate.mapxy = lambda s, d: (s, -d * stretch)
    plate.finish()
    lines = ["*NODE"]
    for body in (cylinder, plate):
        lines += [f"{n}, {x:.15g}, {y:.15g}" for n, (x, y) in sorted(body.xy.items())]
    for name, body, first in (("CYLINDER", cylinder, 1), ("PLATE", plate, 100001)):
        lines.append(f"*ELEMENT, TYPE=CPE4, ELSET={name}")
        lines += [f"{first + k}, " + ", ".join(map(str, ids)) for k, ids in enumerate(body.elems)]
    lines.append("*SURFACE, NAME=CYL_ARC, TYPE=ELEMENT")
    lines += [f"{e}, S{f}" for e, f, s in cylinder.surface_faces if abs(s) < contact]
    lines.append("*SURFACE, NAME=PLATE_TOP, TYPE=ELEMENT")
    lines += [f"{e}, S{f}" for e, f, s in plate.surface_faces if abs(s) < contact + 2 * hm]
    top = cylinder.top_rows
    lines.append("*NSET, NSET=CYL_TOP")
    lines += [", ".join(map(str, top[i:i + 8])) for i in range(0, len(top), 8)]
    lines.append("*NSET, NSET=PLATE_BOTTOM")
    bottom = plate.top_rows
    lines += [", ".join(map(str, bottom[i:i + 8])) for i in range(0, len(bottom), 8)]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    xy = dict(cylinder.xy)
    xy.update(plate.xy)
    slave = sorted({n for e, fc, s in cylinder.surface_faces if abs(s) < contact
                    for n in (cylinder.elems[e - 1][fc - 1], cylinder.elems[e - 1][fc % 4])}, key=lambda n: xy[n][0])
    if swap:
        slave = sorted({n for e, fc, s in plate.surface_faces if abs(s) < contact + 2 * hm
                        for n in (plate.elems[e - 100001][fc - 1], plate.elems[e - 100001][fc % 4])},
                       key=lambda n: xy[n][0])
    return xy, slave, top, len(cylinder.elems) + len(plate.elems)


def write_deck(d, coupling, incs=(2, 4, 4), exact=True, extra="", swap=False, split=True, **mesh):
    """The deck in directory d (mesh.inp beside it): press P (n1
    increments, the top's x held), then Q to Q* (n2), then back to 0 (n3).
    coupling: NODE TO SURFACE or SURFACE TO SURFACE; swap: the plate the
    slave; split: the steps' *STATIC with SPLIT TOUCHING (increments
    split where frictional points close within them). Returns (deck path,
    xy, slave nodes, number of elements)."""
    static = "*STATIC, SPLIT TOUCHING" if split else "*STATIC"
    os.makedirs(d, exist_ok=True)
    xy, slave, top, nel = write_mesh(os.path.join(d, "mesh.inp"), swap=swap, **mesh)
    ref = top[0]
    eqs = "".join(f"2\n{n}, {k}, 1.0, {ref}, {k}, -1.0\n" for n in top[1:] for k in (1, 2))
    n1, n2, n3 = incs
    deck = f"""*HEADING
Stick and slip: cylinder R = {R} on a plate, a/R = 0.05, P = {P:.6f}, Q* = mu P / 2, mu = {MU}
*INCLUDE, INPUT=mesh.inp
*NSET, NSET=REF
{ref}
*MATERIAL, NAME=STEEL
*ELASTIC
{E}, {NU}
*SOLID SECTION, ELSET=PLATE, MATERIAL=STEEL
*SOLID SECTION, ELSET=CYLINDER, MATERIAL=STEEL
*CONTACT PAIR, FRICTION={MU}, TYPE={coupling}{', EXACT' if exact else ''}{extra}
{'PLATE_TOP, CYL_ARC' if swap else 'CYL_ARC, PLATE_TOP'}
*EQUATION
{eqs}*BOUNDARY
PLATE_BOTTOM, 1, 2
*STEP, NAME=PRESS
{static}
{1.0 / n1}, 1.0
*BOUNDARY
REF, 1, 1, 0.0
*CLOAD
REF, 2, {-P:.9f}
*END STEP
*STEP, NAME=LOAD Q
{static}
{1.0 / n2}, 1.0
*BOUNDARY, OP=NEW
PLATE_BOTTOM, 1, 2
*CLOAD
REF, 1, {QSTAR:.9f}
*END STEP
*STEP, NAME=UNLOAD Q
{static}
{1.0 / n3}, 1.0
*CLOAD
REF, 1, 0.0
*END STEP
"""
    path = os.path.join(d, "stick.inp")
    with open(path, "w") as f:
        f.write(deck)
    return path, xy, slave, nel


def run(path, cfe2d=os.path.join(ROOT, "bin", "cfe2d")):
    """Runs cfe2d on the deck (results beside it); returns the wall time."""
    t = time.time()
    p = subprocess.run([cfe2d, "-q", "-d", "16", "-o", os.path.dirname(path), path], capture_output=True, text=True)
    if p.returncode != 0:
        raise SystemExit(f"cfe2d failed on {path}:\n{p.stderr}")
    return time.time() - t


def slave_rows(path):
    """{(step, increment): {node: (pressure, shear, state, force, shear_force)}} of the
    contact table's slave rows."""
    import csv
    out = {}
    with open(path[:-4] + "_contact.csv") as f:
        for r in csv.DictReader(f):
            if r["side"] == "slave":
                out.setdefault((int(r["step"]), int(r["increment"])), {})[int(r["node"])] = (
                    float(r["pressure"]), float(r["shear"]), r["state"], float(r["force"]), float(r["shear_force"]))
    return out


def cattaneo(x, a, p0, c):
    """Cattaneo's shear traction for stick zone |x| < c of a Hertz contact
    a, p0 (tests/test_friction.py's cattaneo_traction)."""
    q = MU * p0 * np.sqrt(np.clip(1.0 - (x / a) ** 2, 0.0, None))
    inner = np.abs(x) < c
    q[inner] -= MU * p0 * (c / a) * np.sqrt(1.0 - (x[inner] / c) ** 2)
    return q


def fit_ellipse(x, p, window):
    """p0 and a of the Hertz ellipse fitted to the pressures with |x| < window
    (scripts/compare_hertz.py's)."""
    from compare_hertz import fit_ellipse as fit
    return fit(x, p, window)


def stick_ends(x, state):
    """The stick zone's ends (the run of STICK rows about x = 0, each end
    the midpoint to the next row) and the spacings there; None when the
    centre row does not stick."""
    k0 = int(np.argmin(np.abs(x)))
    if state[k0] != "STICK":
        return None
    hi, lo = k0, k0
    while hi + 1 < len(x) and state[hi + 1] == "STICK":
        hi += 1
    while lo > 0 and state[lo - 1] == "STICK":
        lo -= 1
    return (0.5 * (x[lo] + x[lo - 1]), x[lo] - x[lo - 1]), (0.5 * (x[hi] + x[hi + 1]), x[hi + 1] - x[hi])


def measure(path, xy, slave, incs=(2, 4, 4)):
    """The three figures of the run (module docstring) and per-increment
    detail: a dict."""
    rows = slave_rows(path)
    # each step's last increment (with automatic splits the steps may
    # take more increments than incs asks for)
    last = {}
    for step, inc in rows:
        last[step] = max(inc, last.get(step, 0))
    incs = (last[1], last[2], last[3])
    out_incs = incs
    hertz_a = math.sqrt(4 * P * R / (math.pi * ESTAR))
    out = {"stick": [], "incs": {}}
    qstar_fit = None
    for (step, inc) in sorted(rows):
        r = rows[step, inc]
        nodes = [n for n in slave if n in r]
        x = np.array([xy[n][0] for n in nodes])
        p = np.array([r[n][0] for n in nodes])
        q = np.array([r[n][1] for n in nodes])
        state = np.array([r[n][2] for n in nodes])
        big_p = sum(r[n][3] for n in nodes)
        big_q = sum(r[n][4] for n in nodes)
        p0, a = fit_ellipse(x, p, 0.8 * hertz_a * math.sqrt(big_p / P))
        inside = np.abs(x) < 0.9 * a
        rec = {"P": big_p, "Q": big_q, "a": a, "p0": p0}
        if step == 1 and inc == incs[0]:
            rec["expect"] = np.zeros_like(x)
            out["shear_press"] = float(np.sqrt(np.mean(q[inside] ** 2)) / (MU * p0))
            out["shear_press_max"] = float(np.max(np.abs(q[inside])) / (MU * p0))
        if step >= 2:
            if step == 2:
                c = a * math.sqrt(max(0.0, 1.0 - big_q / (MU * big_p)))
            else:
                c = a * math.sqrt(max(0.0, 1.0 - (QSTAR - big_q) / (2 * MU * big_p)))
            ends = stick_ends(x, state)
            if ends is None:
                err = float("inf")
            else:
                (lo, hl), (hi, hh) = ends
                err = max(abs(-lo - c) / hl, abs(hi - c) / hh)
            out["stick"].append((step, inc, c / a, None if ends is None else (ends[0][0] / a, ends[1][0] / a), err))
            if step == 2 and inc == incs[1]:
                qstar_fit = (a, p0, c)
                expect = cattaneo(x, a, p0, c)
                out["shear_qstar"] = float(np.sqrt(np.mean((q - expect)[inside] ** 2)) / (MU * p0))
                out["shear_qstar_max"] = float(np.max(np.abs(q - expect)[inside]) / (MU * p0))
            if step == 3 and inc == incs[2]:
                a1, p01, c1 = qstar_fit
                expect = cattaneo(x, a1, p01, c1) - 2 * cattaneo(x, a, p0, c)
                out["shear_back"] = float(np.sqrt(np.mean((q - expect)[inside] ** 2)) / (MU * p0))
                out["shear_back_max"] = float(np.max(np.abs(q - expect)[inside]) / (MU * p0))
        rec.update(x=x, p=p, q=q, state=state)
        out["incs"][step, inc] = rec
    out["last"] = out_incs
    out["stick_end"] = max(s[4] for s in out["stick"])
    out["stick_end_loading"] = max(s[4] for s in out["stick"] if s[0] == 2)
    return out


def save_states(path, f, incs, meta):
    """Writes the slave rows (x, p, q) at the end of the pressing, at Q*
    and back at Q = 0, with the fitted a, p0 and the figures, to a JSON
    file (the converged reference of tests/stick_slip_reference.json)."""
    import json
    out = dict(meta, shear_press=f["shear_press"], shear_qstar=f["shear_qstar"], shear_back=f["shear_back"],
               stick_end=f["stick_end"])
    for name, key in (("press", (1, incs[0])), ("qstar", (2, incs[1])), ("back", (3, incs[2]))):
        rec = f["incs"][key]
        out[name] = dict(a=rec["a"], p0=rec["p0"], P=rec["P"], Q=rec["Q"], x=[round(v, 12) for v in rec["x"].tolist()],
                         p=rec["p"].tolist(), q=rec["q"].tolist())
    with open(path, "w") as fh:
        json.dump(out, fh, indent=0)


def write_reference(path, full, every_h=0.025, against=None):
    """The converged reference of tests/test_stick_slip_accuracy.py from a
    fine run saved by --save (full: its JSON): at the three checked
    states the shear q and pressure p at the nodes of the default mesh's
    slave spacing every_h (x a multiple of it, |x| < a), with the fitted
    a and p0, the stick zone's ends where the traction has a kink (c at
    Q*; c and c' back at Q = 0), every node of the fine run within the
    contact (x_all, q_all: reference_shear), the figures against the
    closed forms, and, against: a coarser run's JSON (the fine mesh's own distance to
    it, rms over |x| < 0.9 a in mu p0, at the same nodes)."""
    import json
    src = json.load(open(full))
    out = {k: src[k] for k in ("hs", "hm", "incs", "elements", "shear_press", "shear_qstar", "shear_back")}
    out["hs_run"], out["hs"] = src["hs"], every_h
    out["about"] = ("converged reference of issue 33's stick/slip case (scripts/stick_slip_accuracy.py "
                    "--reference): the same bodies on a finer mesh, pressing split automatically; q, p in MPa")
    qs = src["qstar"]
    c = qs["a"] * math.sqrt(max(0.0, 1.0 - qs["Q"] / (MU * qs["P"])))
    bk = src["back"]
    cb = bk["a"] * math.sqrt(max(0.0, 1.0 - (qs["Q"] - bk["Q"]) / (2 * MU * bk["P"])))
    kinks = {"press": [], "qstar": [c], "back": [c, cb]}
    for name in ("press", "qstar", "back"):
        r = src[name]
        x = np.array(r["x"])
        keep = (np.abs(np.round(x / every_h) * every_h - x) < 1e-9) & (np.abs(x) < r["a"])
        out[name] = dict(a=r["a"], p0=r["p0"], P=r["P"], Q=r["Q"], kinks=kinks[name],
                         x=[round(v, 9) for v in x[keep].tolist()], q=[round(v, 6) for v in np.array(r["q"])[keep].tolist()],
                         p=[round(v, 6) for v in np.array(r["p"])[keep].tolist()])
        # every node of the fine run within the contact: the reference at
        # any node of a coarser or shifted mesh (reference_shear)
        whole = np.abs(x) < r["a"]
        out[name]["x_all"] = [round(v, 9) for v in x[whole].tolist()]
        out[name]["q_all"] = [round(v, 6) for v in np.array(r["q"])[whole].tolist()]
        if against:
            coarse = json.load(open(against))[name]
            at = {round(v, 9): k for k, v in enumerate(coarse["x"])}
            xs = np.array(out[name]["x"])
            ks = np.array([at[round(v, 9)] for v in xs])
            d = (np.array(coarse["q"])[ks] - np.array(out[name]["q"]))[np.abs(xs) < 0.9 * r["a"]]
            out[name]["coarser_rms"] = float(np.sqrt(np.mean(d ** 2)) / (MU * r["p0"]))
    with open(path, "w") as fh:
        json.dump(out, fh, indent=1)


def reference_shear(r, x, h=None):
    """The converged reference's shear (r: a state of write_reference's
    file, with x_all, q_all: every node of the fine run) at the points x of
    a run's slave nodes. h None: pointwise, the fine run's nodal values
    interpolated linearly (at the fine nodes themselves, their values).
    h a slave spacing: the reference averaged as a node of spacing h
    averages it, int q N da / int N da with N the hat of width 2 h about
    the point: a slave node's multiplier of the dual mortar is that mean of
    the traction over its support (Phi_j dual to N_j: lambda_j D_j =
    int q_h N_j da; docs/contact.md). The fine field q_h = sum_i q_i Phi_i
    gives it exactly as sum_i q_i d_i N(x_i) / sum_i d_i N(x_i), d_i the
    fine nodes' int N_i da on the cylinder's arc, since N is linear on the
    fine faces (nested meshes; 4 times finer)."""
    xf, qf = np.array(r["x_all"]), np.array(r["q_all"])
    x = np.asarray(x, dtype=float)
    if h is None:
        return np.interp(x, xf, qf)
    yf = R - np.sqrt(R * R - xf * xf)
    face = np.hypot(np.diff(xf), np.diff(yf))
    d = np.zeros_like(xf)
    d[:-1] += 0.5 * face
    d[1:] += 0.5 * face
    w = d[None, :] * np.clip(1.0 - np.abs(xf[None, :] - x[:, None]) / h, 0.0, None)
    return (w @ qf) / np.sum(w, axis=1)


def shear_against(rec, ref, name, h=None, kinks=True):
    """rms and largest difference over |x| < 0.9 a of a run's shear (rec: an
    increment of measure's "incs") against the reference state name (ref:
    write_reference's file) in mu p0 (the reference's a and p0): pointwise
    (h None) or averaged over a slave spacing h (reference_shear). kinks
    false: the nodes within one slave spacing of the stick zone's ends c (at
    Q*; c and c' back at Q = 0), where the traction's slope is infinite,
    left out (the spacing the reference's, ref["hs"])."""
    r = ref[name]
    x, q = rec["x"], rec["q"]
    inside = np.abs(x) < 0.9 * r["a"]
    if not kinks:
        for c in r.get("kinks", []):
            inside &= np.abs(np.abs(x) - c) > ref["hs"] * 1.000001
    d = q[inside] - reference_shear(r, x[inside], h)
    scale = MU * r["p0"]
    return float(np.sqrt(np.mean(d ** 2)) / scale), float(np.max(np.abs(d)) / scale)


#: The approach (the reference node's vertical displacement) at which the
#: deck's bodies carry P (cfe2d, small deformation, EXACT): the CalculiX
#: check is displacement-controlled (a cylinder held by contact alone is
#: singular there).
APPROACH = 0.05043057


def write_calculix_frictionless(d, nlgeom=False):
    """The frictionless check of tests/calculix/stick_slip_frictionless.csv
    in directory d (mesh.inp beside it): the default mesh (the plate
    PLATE_SIZE), CalculiX's own contact cards (SURFACE TO SURFACE, a
    linear pressure-overclosure of 4e8 N/mm^3), the top pressed down by
    APPROACH in 4 DIRECT increments; read unchanged by CalculiX and cfe2d.
    nlgeom: the step with NLGEOM (CalculiX poses its contact on the
    deformed configuration). Returns (deck path, xy, cylinder surface
    nodes, plate top nodes with |x| < 2, each sorted by x)."""
    os.makedirs(d, exist_ok=True)
    xy, slave, top, nel = write_mesh(os.path.join(d, "mesh.inp"), plate_size=PLATE_SIZE)
    ref = top[0]
    eqs = "".join(f"2\n{n}, {k}, 1.0, {ref}, {k}, -1.0\n" for n in top[1:] for k in (1, 2))
    deck = f"""*HEADING
Stick and slip, issue 33: cylinder R = {R} on a plate, a/R = 0.05, frictionless, pressed by the approach of P
*INCLUDE, INPUT=mesh.inp
*NSET, NSET=REF
{ref}
*MATERIAL, NAME=STEEL
*ELASTIC
{E}, {NU}
*SOLID SECTION, ELSET=PLATE, MATERIAL=STEEL
1.
*SOLID SECTION, ELSET=CYLINDER, MATERIAL=STEEL
1.
*SURFACE INTERACTION, NAME=SI
*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR
4.e8
*CONTACT PAIR, INTERACTION=SI, TYPE=SURFACE TO SURFACE
CYL_ARC, PLATE_TOP
*EQUATION
{eqs}*BOUNDARY
PLATE_BOTTOM, 1, 2
*STEP, NLGEOM{'' if nlgeom else '=NO'}, INC=1000
*STATIC, DIRECT
0.25, 1.0
*BOUNDARY
REF, 1, 1, 0.0
REF, 2, 2, {-APPROACH}
*NODE PRINT, NSET=CYL_TOP, TOTALS=ONLY
RF
*NODE FILE
U
*END STEP
"""
    path = os.path.join(d, "frictionless.inp")
    with open(path, "w") as f:
        f.write(deck)
    plate_top = sorted((n for n, (x, y) in xy.items() if n > 1000000 and y == 0.0 and abs(x) < 2.0),
                       key=lambda n: xy[n][0])
    return path, xy, slave, plate_top


def surface_mismatch(frd, xy, slave, plate_top, a=A_TARGET):
    """The relative tangential displacement of the two surfaces, delta(x) =
    u_x(cylinder) - u_x(plate) at the cylinder's surface nodes with
    |x| < a (the plate's u_x interpolated on its surface nodes), from the
    last displacement block of a .frd file (CalculiX's or cfe2d's): (x,
    delta, u_x of the cylinder). Two half-spaces of one material have
    delta = 0 under a normal load (Dundurs' beta = 0)."""
    disp, cur = None, None
    with open(frd) as f:
        for line in f:
            if line.startswith(" -4"):
                cur = {} if line.split()[1] == "DISP" else None
                if cur is not None:
                    disp = cur
            elif line.startswith(" -1") and cur is not None:
                cur[int(line[3:13])] = (float(line[13:25]), float(line[25:37]))
            elif line.startswith(" -3"):
                cur = None
    x = np.array([xy[n][0] for n in slave])
    ux = np.array([disp[n][0] for n in slave])
    xp = np.array([xy[n][0] for n in plate_top])
    delta = ux - np.interp(x, xp, np.array([disp[n][0] for n in plate_top]))
    keep = np.abs(x) < a
    return x[keep], delta[keep], ux[keep]


CASES = {"nts": "NODE TO SURFACE", "sts": "SURFACE TO SURFACE"}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", default="nts,sts")
    ap.add_argument("--hs", type=float, default=0.025, help="slave (cylinder) spacing at the contact")
    ap.add_argument("--hm", type=float, default=0.03, help="master (plate) spacing at the contact")
    ap.add_argument("--incs", default="2,4,4")
    ap.add_argument("--plate", type=float, default=2.0 * R, help="the plate's half width and depth")
    ap.add_argument("--penalty", action="store_true", help="the penalty, not EXACT")
    ap.add_argument("--no-split", action="store_true", help="the steps without SPLIT TOUCHING")
    ap.add_argument("--swap", action="store_true", help="the plate the slave, the cylinder the master")
    ap.add_argument("--load", type=float, default=1.0, help="P as a multiple of a/R = 0.05's (a grows as its root)")
    ap.add_argument("--fixed-plate", action="store_true",
                    help="the plate exactly the default mesh's, 38.88 x 20.01 mm, whatever --hm (refinement studies)")
    ap.add_argument("--shift", type=float, default=0.0,
                    help="the cylinder's mesh moved along x by this fraction of --hs (where its nodes sit against c, c')")
    ap.add_argument("--against", help="also the shear against this converged reference (write_reference's file), "
                    "pointwise and averaged over each node's support")
    ap.add_argument("--extra", default="", help="more *CONTACT PAIR parameters, e.g. ', STICK SLOPE=1e9'")
    ap.add_argument("--cfe2d", default=os.path.join(ROOT, "bin", "cfe2d"))
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "stick_slip"))
    ap.add_argument("--detail", action="store_true", help="print every slave row at the three checked states")
    ap.add_argument("--save", help="write the three checked states' slave rows (x, p, q) and figures to this JSON file")
    ap.add_argument("--reference", help="with --save: also write the converged reference the tests read "
                    "(write_reference) to this file")
    ap.add_argument("--coarser", help="with --reference: a coarser run's --save file, its distance stated")
    args = ap.parse_args()
    incs = tuple(int(k) for k in args.incs.split(","))
    global P, QSTAR
    P, QSTAR = P * args.load, QSTAR * args.load
    for case in args.cases.split(","):
        d = os.path.join(args.out, f"{case}_hs{args.hs:g}_hm{args.hm:g}")
        d += "_swap" if args.swap else ""
        d += f"_i{'-'.join(map(str, incs))}_l{args.load:g}"
        # the contact surfaces 2.5 a wide whatever the load (a grows as its root)
        path, xy, slave, nel = write_deck(d, CASES[case], incs=incs, exact=not args.penalty, extra=args.extra, swap=args.swap,
                                          split=not args.no_split,
                                          hs=args.hs, hm=args.hm, plate_half=args.plate,
                                          contact=2.5 * A_TARGET * math.sqrt(args.load),
                                          plate_size=PLATE_SIZE if args.fixed_plate else None,
                                          shift=args.shift * args.hs)
        wall = run(path, args.cfe2d)
        f = measure(path, xy, slave, incs)
        incs = f["last"]
        fin = f["incs"][1, incs[0]]
        print(f"{case} hs {args.hs:g} hm {args.hm:g} ({nel} elements, {wall:.1f} s): a {fin['a']:.4f} "
              f"p0 {fin['p0']:.1f} P {fin['P']:.2f}; press shear {f['shear_press']:.2%} (max "
              f"{f['shear_press_max']:.2%}), Q* {f['shear_qstar']:.2%} (max {f['shear_qstar_max']:.2%}), back "
              f"{f['shear_back']:.2%} (max {f['shear_back_max']:.2%}) of mu p0; stick end {f['stick_end_loading']:.2f} "
              f"slave spacings loading, {f['stick_end']:.2f} with unloading; increments {incs}")
        for s in f["stick"]:
            ends = "none" if s[3] is None else f"[{s[3][0]:.4f}, {s[3][1]:.4f}]"
            print(f"   {s[0]}.{s[1]}: c/a {s[2]:.4f}, stick zone {ends} a, {s[4]:.2f} spacings")
        if args.against:
            import json
            with open(args.against) as fh:
                ref = json.load(fh)
            for title, h in (("pointwise", None), ("averaged over each node's support", args.hs)):
                figs = []
                for name, key in (("press", (1, incs[0])), ("qstar", (2, incs[1])), ("back", (3, incs[2]))):
                    every = shear_against(f["incs"][key], ref, name, h=h)
                    away = shear_against(f["incs"][key], ref, name, h=h, kinks=False)
                    figs.append(f"{name} {every[0]:.2%} ({every[1]:.2%}; away from c, c' {away[0]:.2%})")
                print(f"   against the converged bodies, {title}: " + ", ".join(figs))
        if args.save:
            save_states(args.save, f, incs, dict(hs=args.hs, hm=args.hm, incs=incs, load=args.load, plate=args.plate,
                                                 case=case, elements=nel, wall=wall))
            if args.reference:
                write_reference(args.reference, args.save, against=args.coarser)
        if args.detail:
            for key in ((1, incs[0]), (2, incs[1]), (3, incs[2])):
                rec = f["incs"][key]
                print(f"  {key}: x, p, q, state")
                for x, p, q, st in zip(rec["x"], rec["p"], rec["q"], rec["state"]):
                    if abs(x) < 1.1 * rec["a"]:
                        print(f"    {x:+.4f} {p:10.3f} {q:+9.3f} {st}")


if __name__ == "__main__":
    main()
