#!/usr/bin/env python3
"""The rubber O-ring example: an axisymmetric neo-Hookean O-ring squeezed
by 25 % of its cord between two steel plates, with contact.

    python3 scripts/oring.py --write-deck      # (re)writes input/examples/oring.inp
    python3 scripts/oring.py [--out results/oring] [--ccx DIR]

The second form runs cfe2d on input/examples/oring.inp and writes, in the
output folder, the force-compression curve (oring_force.csv: compression
in mm and in % of the cord, the axial force on the upper plate in N, the
whole ring) and its plot (oring_force.png). With --ccx DIR, a folder where
CalculiX ran the same deck (its oring.dat), CalculiX's curve is read from
the .dat's *NODE PRINT totals and drawn beside cfe2d's.

The model (mm, N, MPa): the cord's section is a circle of diameter
d = 5 centred at r = 20, z = 0, meshed with CAX4 (an O-grid: a square core
and four blocks out to the circle); neo-Hooke C10 = 0.8, D1 = 0.001 (mu =
1.6, K = 2000: nearly incompressible; CAX4 takes F-bar). The plates are
steel (E = 210 000, nu = 0.3; St Venant-Kirchhoff under NLGEOM), 2 thick
and 10 wide in r, touching the ring at its top and bottom points. The
lower plate is held at its lower face; the upper plate is moved down by
1.25 (25 % of d) at its upper face and held radially there. Contact:
NODE TO SURFACE, the ring's nodes as slaves, frictionless, CalculiX's
linear pressure-overclosure law with 1e4 MPa/mm.
"""
import argparse
import math
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)

DECK = os.path.join(ROOT, "input", "examples", "oring.inp")
RC, D = 20.0, 5.0                 # centre radius of the cord, cord diameter
SQUEEZE = 0.25 * D
PLATE_T, PLATE_W = 2.0, 10.0


class Mesh:
    """Nodes merged by position within a body (the ring's top and the upper
    plate's face meet at one point and must stay two nodes), 4-node
    elements."""

    def __init__(self, first_node=1):
        self.nodes, self.key, self.elements, self.next = {}, {}, [], first_node
        self.body = 0

    def node(self, x, y):
        k = (self.body, round(x, 9), round(y, 9))
        if k not in self.key:
            self.key[k] = self.next
            self.nodes[self.next] = (x, y)
            self.next += 1
        return self.key[k]

    def quad(self, a, b, c, d):
        self.elements.append((a, b, c, d))


def ring_mesh(m, n_core=6, n_layer=5):
    """O-grid of the circle: a square core of half-width s = 0.45 R, and
    four blocks from its sides to the arcs (linear blend along the rays)."""
    r = 0.5 * D
    s = 0.45 * r

    def core(i, j):                       # i, j in 0..n_core
        return (RC - s + 2 * s * i / n_core, -s + 2 * s * j / n_core)

    ids = [[m.node(*core(i, j)) for j in range(n_core + 1)] for i in range(n_core + 1)]
    for i in range(n_core):
        for j in range(n_core):
            m.quad(ids[i][j], ids[i + 1][j], ids[i + 1][j + 1], ids[i][j + 1])
    # the four sides: core edge point -> arc point, counter-clockwise around the circle
    boundary = []
    for side in range(4):
        pts = []
        for k in range(n_core + 1):
            t = k / n_core
            if side == 0:      # right side, bottom to top
                cx, cy = RC + s, -s + 2 * s * t
            elif side == 1:    # top, right to left
                cx, cy = RC + s - 2 * s * t, s
            elif side == 2:    # left, top to bottom
                cx, cy = RC - s, s - 2 * s * t
            else:              # bottom, left to right
                cx, cy = RC - s + 2 * s * t, -s
            ang = math.atan2(cy, cx - RC)
            ax, ay = RC + r * math.cos(ang), r * math.sin(ang)
            row = [m.node(cx + (ax - cx) * q / n_layer, cy + (ay - cy) * q / n_layer) for q in range(n_layer + 1)]
            pts.append(row)
        for k in range(n_core):
            for q in range(n_layer):
                # (the orientation is made counter-clockwise afterwards: orient)
                m.quad(pts[k][q], pts[k + 1][q], pts[k + 1][q + 1], pts[k][q + 1])
        boundary += [(pts[k][n_layer], pts[k + 1][n_layer]) for k in range(n_core)]
    return boundary


def plate_mesh(m, z0, z1, nx=40, ny=3):
    m.body += 1
    ids = [[m.node(RC - PLATE_W / 2 + PLATE_W * i / nx, z0 + (z1 - z0) * j / ny) for j in range(ny + 1)]
           for i in range(nx + 1)]
    first = len(m.elements)
    for i in range(nx):
        for j in range(ny):
            m.quad(ids[i][j], ids[i + 1][j], ids[i + 1][j + 1], ids[i][j + 1])
    return ids, first


def orient(m, k):
    """Makes element k counter-clockwise (positive area)."""
    a = m.elements[k]
    x = [m.nodes[n] for n in a]
    area = 0.5 * sum(x[i][0] * x[(i + 1) % 4][1] - x[(i + 1) % 4][0] * x[i][1] for i in range(4))
    if area < 0:
        m.elements[k] = (a[0], a[3], a[2], a[1])


def face_of(elem, a, b):
    """Abaqus face number (S1..S4) of the edge a-b of a 4-node element."""
    for f in range(4):
        p, q = elem[f], elem[(f + 1) % 4]
        if {p, q} == {a, b}:
            return f + 1
    raise ValueError("edge not in element")


def write_deck(path=DECK):
    with open(path, "w") as f:
        f.write(deck_text())
    return path


def deck_text(n_core=6, n_layer=5, plate_nx=40, static="0.05, 1., 1e-5, 0.05"):
    """The deck as text: the example's mesh by default; coarser ones (the
    fuzzer's seed) with fewer elements."""
    m = Mesh()
    boundary = ring_mesh(m, n_core, n_layer)
    n_ring = len(m.elements)
    lower, first_lower = plate_mesh(m, -0.5 * D - PLATE_T, -0.5 * D, nx=plate_nx)
    upper, first_upper = plate_mesh(m, 0.5 * D, 0.5 * D + PLATE_T, nx=plate_nx)
    for k in range(len(m.elements)):
        orient(m, k)
    # the ring's boundary faces, upper and lower halves
    edge_elem = {}
    for e, el in enumerate(m.elements[:n_ring]):
        for f in range(4):
            edge_elem[frozenset((el[f], el[(f + 1) % 4]))] = e
    up_faces, low_faces = [], []
    for a, b in boundary:
        e = edge_elem[frozenset((a, b))]
        f = face_of(m.elements[e], a, b)
        zmid = 0.5 * (m.nodes[a][1] + m.nodes[b][1])
        (up_faces if zmid >= 0 else low_faces).append((e + 1, f))

    def plate_faces(ids, first, j_row, ny=3):
        out = []
        nx = len(ids) - 1
        for i in range(nx):
            e = first + i * ny + (0 if j_row == 0 else ny - 1)
            a, b = ids[i][j_row], ids[i + 1][j_row]
            out.append((e + 1, face_of(m.elements[e], a, b)))
        return out

    lower_top = plate_faces(lower, first_lower, 3)
    upper_bottom = plate_faces(upper, first_upper, 0)
    lower_bottom = [lower[i][0] for i in range(len(lower))]
    upper_top = [upper[i][3] for i in range(len(upper))]

    def chunks(items, k=8):
        items = list(items)
        return "".join(", ".join(map(str, items[i:i + k])) + "\n" for i in range(0, len(items), k))

    def surface(name, faces):
        return f"*SURFACE, NAME={name}, TYPE=ELEMENT\n" + "".join(f"{e}, S{f}\n" for e, f in faces)

    lines = [
        "*HEADING",
        "Rubber O-ring (neo-Hooke, CAX4) squeezed 25 % between steel plates, frictionless contact",
        "** Written by scripts/oring.py --write-deck (the model is described there). Units: mm, N, MPa.",
        "** Run: bin/cfe2d input/examples/oring.inp, or python3 scripts/oring.py (force-compression curve).",
        "*NODE, NSET=ALL",
    ]
    lines += [f"{n}, {x:.12g}, {y:.12g}" for n, (x, y) in m.nodes.items()]
    lines.append("*ELEMENT, TYPE=CAX4, ELSET=RING")
    lines += [f"{k + 1}, " + ", ".join(map(str, el)) for k, el in enumerate(m.elements[:n_ring])]
    lines.append("*ELEMENT, TYPE=CAX4, ELSET=PLATES")
    lines += [f"{k + 1}, " + ", ".join(map(str, el)) for k, el in enumerate(m.elements) if k >= n_ring]
    text = "\n".join(lines) + "\n"
    text += "*NSET, NSET=LOWER_BOTTOM\n" + chunks(lower_bottom)
    text += "*NSET, NSET=UPPER_TOP\n" + chunks(upper_top)
    text += surface("RING_UP", up_faces) + surface("RING_LOW", low_faces)
    text += surface("UPPER_PLATE", upper_bottom) + surface("LOWER_PLATE", lower_top)
    text += f"""*MATERIAL, NAME=RUBBER
*HYPERELASTIC, NEO HOOKE
0.8, 0.001
*MATERIAL, NAME=STEEL
*ELASTIC
210000., 0.3
*SOLID SECTION, ELSET=RING, MATERIAL=RUBBER
*SOLID SECTION, ELSET=PLATES, MATERIAL=STEEL
*SURFACE INTERACTION, NAME=RUBBER_STEEL
*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR
1e4
*CONTACT PAIR, INTERACTION=RUBBER_STEEL, TYPE=NODE TO SURFACE
RING_UP, UPPER_PLATE
*CONTACT PAIR, INTERACTION=RUBBER_STEEL, TYPE=NODE TO SURFACE
RING_LOW, LOWER_PLATE
*BOUNDARY
LOWER_BOTTOM, 1, 2
UPPER_TOP, 1, 1
*STEP, NLGEOM, INC=200
*STATIC
{static}
*BOUNDARY
UPPER_TOP, 2, 2, {-SQUEEZE}
*NODE PRINT, NSET=UPPER_TOP, TOTALS=ONLY
RF
*NODE FILE
U, S
*EL FILE
S
*END STEP
"""
    return text


def cfe2d_curve(listing):
    from cfe2d_listing import read_listing
    out = [(0.0, 0.0)]
    for inc in read_listing(listing).increments:
        b = inc.block("REACTIONS")
        fz = b["RF2"][list(b["set"]).index("UPPER_TOP")]
        out.append((SQUEEZE * inc.time, -fz))
    return out


# CalculiX solves an axisymmetric model as a 2 degree sector of 3D elements and its *NODE PRINT totals
# are the sector's (measured: 2/360 of cfe2d's whole-ring force where locking plays no part): the
# whole ring is 180 times that.
CCX_SECTOR = 180.0


def ccx_curve(dat):
    """CalculiX's *NODE PRINT, TOTALS=ONLY of UPPER_TOP from its .dat,
    for the whole ring: [(compression, force)]."""
    out = [(0.0, 0.0)]
    text = open(dat).read()
    pat = r"total force \(fx,fy,fz\) for set UPPER_TOP and time\s+(\S+)\s+(\S+)\s+(\S+)"
    for m in re.finditer(pat, text):
        out.append((SQUEEZE * float(m.group(1)), -CCX_SECTOR * float(m.group(3))))
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--write-deck", action="store_true")
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "oring"))
    ap.add_argument("--ccx", help="folder where CalculiX ran input/examples/oring.inp (its oring.dat)")
    args = ap.parse_args(argv)
    if args.write_deck:
        print(write_deck())
        return
    os.makedirs(args.out, exist_ok=True)
    subprocess.run([os.path.join(ROOT, "bin", "cfe2d"), "-o", args.out, DECK], check=True)
    curve = cfe2d_curve(os.path.join(args.out, "oring.out"))
    ccx = ccx_curve(os.path.join(args.ccx, "oring.dat")) if args.ccx else None
    with open(os.path.join(args.out, "oring_force.csv"), "w") as f:
        f.write("compression_mm,compression_percent,force_N\n")
        for c, fz in curve:
            f.write(f"{c:.6g},{100 * c / D:.4g},{fz:.8g}\n")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot([100 * c / D for c, _ in curve], [fz for _, fz in curve], "o-", label="cfe2d")
    if ccx:
        ax.plot([100 * c / D for c, _ in ccx], [fz for _, fz in ccx], "x--", label="CalculiX 2.20")
    ax.set_xlabel("compression (% of the cord)")
    ax.set_ylabel("axial force on the plate, whole ring (N)")
    ax.set_title("O-ring, neo-Hooke, d = 5 mm, r = 20 mm")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "oring_force.png"), dpi=120)
    print(f"force at {100 * curve[-1][0] / D:.0f} %: {curve[-1][1]:.2f} N; files in {args.out}")


if __name__ == "__main__":
    main()
