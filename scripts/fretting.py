#!/usr/bin/env python3
"""`make fretting`: McColl's fretting test, worn for 18 000 cycles.

McColl, Ding and Leen (Wear 256, 2004, 1114-1127): a steel cylinder of
radius 6 mm pressed on a steel flat and rubbed by a stroke of +-25 um,
Archard wear on both (k = 1.9e-8 cylinder, 2.9e-8 flat, mm^2/N, mu 0.9).
Set up as the public reproduction (illavori/LevelSetWear,
examples/05_fretting_mccoll) sets it up; why, and what differs from the
paper's numbers: docs/fretting.md. Plane strain, mm-N-MPa:

* the mesh input/fretting/mccoll.geo (gmsh): a flat 12 x 6 mm and the
  lower half disk of the cylinder, quadrilaterals of h = 0.01 mm over
  |x| < 0.5 mm, 0.2 mm deep, in both bodies;
* the cylinder's top is rigid (*RIGID BODY) on a reference node held
  sideways and in rotation and pressed by 18.5 N per mm of thickness
  (the reproduction's *CLOAD on its unit thickness); the flat's bottom is
  rigid on a reference node held vertically and in rotation and moved
  sideways by 0.025 mm times a triangular wave (0, 1, 0, -1, 0 over a
  cycle: the reproduction's amplitude), 40 increments per cycle (its 41
  less the rest increment);
* node-to-segment contact, the cylinder the slave, the search made again
  every increment (gross sliding: the stroke exceeds the contact's
  half-width), a penalty of 1e8 N/mm^3;
* *WEAR with the cycle jump J: C / J cycles computed, each counting J.

The run is written to results/fretting/ (deck, listing, contact table,
the plot fretting.png of the flat's and the cylinder's worn profiles
against the measured one and the reproduction's); the last line printed
is `fretting: depth D um (measured M), width W mm (measured V), C cycles,
jump J, wall T s`. The width is the extent over which the flat's depth
exceeds 1 % of its largest (linear between nodes), the reproduction's
rule; the measured numbers are those of the digitised profile (depth
below its unworn level, width between the points where it leaves that
level, see measured()).

  python3 scripts/fretting.py                   # 18 000 cycles, jump 100
  python3 scripts/fretting.py --cycles 2000 --jump 10 --out results/fretting_j10
"""
import argparse
import csv
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
INPUT = os.path.join(ROOT, "input", "fretting")
CFE2D = os.path.join(ROOT, "bin", "cfe2d")

LOAD = 18.5            # N per mm of thickness (the reproduction's *CLOAD, unit thickness)
STROKE = 0.025         # mm, amplitude of the flat's sideways motion
K_CYL, K_FLAT = 1.9e-8, 2.9e-8
MU = 0.9
MAX_INC = 100000       # the *STEP card's INC= limit: long histories take several steps


def mesh(out, h):
    """Meshes input/fretting/mccoll.geo with element size h in the contact
    zone into out/mccoll_mesh.inp (kept when it exists for this h)."""
    path = os.path.join(out, f"mccoll_mesh_h{h:g}.inp")
    if not os.path.exists(path):
        with open(os.path.join(out, "gmsh.log"), "w") as log:
            subprocess.run(["gmsh", "-2", "-format", "inp", "-setnumber", "Mesh.SaveGroupsOfNodes", "1",
                            "-setnumber", "h", str(h), "-o", path, os.path.join(INPUT, "mccoll.geo")],
                           check=True, stdout=log, stderr=subprocess.STDOUT)
    return os.path.basename(path)


def amplitude(first, last):
    """The triangular stroke 0, 1, 0, -1, 0 over each cycle of total time
    1, cycles first..last-1 starting at total time 1 + cycle."""
    pts = [(1.0 + first, 0.0)]
    for c in range(first, last):
        for f, a in ((0.25, 1.0), (0.5, 0.0), (0.75, -1.0), (1.0, 0.0)):
            pts.append((1.0 + c + f, a))
    lines = []
    for i in range(0, len(pts), 4):
        lines.append(", ".join(f"{t:.6f}, {a:g}" for t, a in pts[i:i + 4]))
    return "\n".join(lines)


def deck(mesh_name, computed, jump, inc_per_cycle, every):
    """The deck: a pressing step, then `computed` cycles in steps of at most
    MAX_INC increments; contact output every `every` increments (and at
    each step's end)."""
    per_step = max(1, MAX_INC // inc_per_cycle)
    out = [f"""*HEADING
McColl, Ding and Leen (2004) fretting test as illavori/LevelSetWear models it, plane strain, mm-N-MPa
*INCLUDE, INPUT={mesh_name}
*NODE
900001, 0., 7.
900002, 0., -7.
*MATERIAL, NAME=STEEL
*ELASTIC
200000., 0.3
*SOLID SECTION, ELSET=FLAT, MATERIAL=STEEL, STATE=PLANE STRAIN
1.
*SOLID SECTION, ELSET=CYLINDER, MATERIAL=STEEL, STATE=PLANE STRAIN
1.
*SURFACE, NAME=CYL
CYL_ARC
*SURFACE, NAME=FLATS
FLAT_TOP
*RIGID BODY, NSET=CYL_TOP, REF NODE=900001
*RIGID BODY, NSET=FLAT_BOTTOM, REF NODE=900002
*SURFACE INTERACTION, NAME=FRET
*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR
1e8
*FRICTION
{MU}
*WEAR
{K_CYL}, {K_FLAT}, {jump}
*CONTACT PAIR, INTERACTION=FRET, TYPE=NODE TO SURFACE, SEARCH DISTANCE=0.2
CYL, FLATS
*AMPLITUDE, NAME=STROKE, TIME=TOTAL TIME
{amplitude(0, computed)}
*BOUNDARY
900001, 1, 1
900001, 6, 6
900002, 1, 2
900002, 6, 6
*STEP
*STATIC
0.25, 1.
*CLOAD
900001, 2, -{LOAD}
*END STEP"""]
    done = 0
    while done < computed:
        n = min(per_step, computed - done)
        out.append(f"""*STEP, INC={n * inc_per_cycle}
*STATIC
{1.0 / inc_per_cycle:.12g}, {n}.
*BOUNDARY, AMPLITUDE=STROKE
900002, 1, 1, {STROKE}
*CONTACT PRINT, FREQUENCY={every}
CSTR
*END STEP""")
        done += n
    return "\n".join(out) + "\n"


def last_profiles(table):
    """(flat [(x, depth)], cylinder [(x, depth)]) of the last increment of
    the contact table, depths in mm; the flat is the master surface."""
    last, flat, cyl = None, [], []
    with open(table) as f:
        for r in csv.DictReader(f):
            key = (int(r["step"]), int(r["increment"]))
            if key != last:
                last, flat, cyl = key, [], []
            if r["side"] == "master":
                flat.append((float(r["x"]), float(r["wear_master"])))
            else:
                cyl.append((float(r["x"]), float(r["wear_slave"])))
    return sorted(flat), sorted(cyl)


def scar(profile, frac=0.01):
    """Largest depth and the extent over which the depth exceeds frac of
    it, interpolated linearly between nodes (the reproduction's rule)."""
    d = max(h for _, h in profile)
    t = frac * d
    on = [i for i, (_, h) in enumerate(profile) if h > t]
    i, j = on[0], on[-1]
    x = [p[0] for p in profile]
    w = [p[1] for p in profile]
    xl = x[i] if i == 0 else x[i - 1] + (t - w[i - 1]) * (x[i] - x[i - 1]) / (w[i] - w[i - 1])
    xr = x[j] if j == len(x) - 1 else x[j] + (t - w[j]) * (x[j + 1] - x[j]) / (w[j + 1] - w[j])
    return d, xr - xl


def read_xy(path):
    """(x, y) rows of a reference CSV of input/fretting (comments and the
    header skipped)."""
    rows = []
    with open(path) as f:
        for line in f:
            if line.startswith("#") or line.startswith("x_mm"):
                continue
            a, b = line.split(",")[:2]
            rows.append((float(a), float(b)))
    return rows


def measured():
    """Depth (um) and width (mm) of the measured scar: the unworn level is
    the mean height over |x| > 0.3 mm; the depth the largest drop below
    it; the width between the outermost points, walking out from the
    deepest one, where the profile is still below that level by more
    than 5 % of the depth (the digitised line's noise is about that)."""
    p = read_xy(os.path.join(INPUT, "measured_mccoll2004.csv"))
    base = sum(y for x, y in p if abs(x) > 0.3) / sum(1 for x, _ in p if abs(x) > 0.3)
    drop = [(x, base - y) for x, y in p]
    k = max(range(len(drop)), key=lambda i: drop[i][1])
    d = drop[k][1]
    i = k
    while i > 0 and drop[i - 1][1] > 0.05 * d:
        i -= 1
    j = k
    while j < len(drop) - 1 and drop[j + 1][1] > 0.05 * d:
        j += 1
    return d, drop[j][0] - drop[i][0]


def reference():
    """Depth (um) and width (mm) of the reproduction's profile after
    18 000 cycles (input/fretting/levelset_18000.csv)."""
    p = [(x, -y * 1e-3) for x, y in read_xy(os.path.join(INPUT, "levelset_18000.csv"))]
    d, w = scar(p)
    return d * 1e3, w


def plot(out, table, jump, computed):
    """scripts/plot_wear.py on the run, with the measured and the
    reproduction's profiles (written as x, depth in mm)."""
    refs = []
    for name, label, sign in (("measured_mccoll2004.csv", "measured (McColl 2004)", -1.0),
                              ("levelset_18000.csv", "LevelSetWear 18000 cycles", -1.0)):
        path = os.path.join(out, "ref_" + name)
        with open(path, "w") as f:
            for x, y in read_xy(os.path.join(INPUT, name)):
                f.write(f"{x},{sign * y * 1e-3},{label}\n")
        refs += ["--reference", path]
    every = max(1, computed // 6)
    # the rows within 0.5 mm of the axis, so that the plot shows the scar
    trimmed = os.path.join(out, "scar_rows.csv")
    with open(table) as f, open(trimmed, "w") as g:
        g.write(f.readline())
        for line in f:
            if abs(float(line.split(",")[6])) < 0.5:
                g.write(line)
    with open(os.path.join(out, "plot.log"), "w") as log:
        subprocess.run([sys.executable, os.path.join(HERE, "plot_wear.py"), trimmed, "-o",
                        os.path.join(out, "fretting.png"), "--period", "1", "--start", "1", "--jump", str(jump),
                        "--every", str(every), "--scale", "1e3", "--unit", "um"] + refs,
                       check=True, stdout=log, stderr=subprocess.STDOUT)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cycles", type=int, default=18000)
    ap.add_argument("--jump", type=int, default=100, help="cycle-jump factor (cycles must be a multiple)")
    ap.add_argument("--h", type=float, default=0.01, help="element size in the contact zone (mm)")
    ap.add_argument("--inc", type=int, default=40, help="increments per cycle (a multiple of 4)")
    ap.add_argument("--every", type=int, default=0,
                    help="contact output every n increments (default: once per computed cycle)")
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "fretting"))
    ap.add_argument("--no-plot", action="store_true")
    args = ap.parse_args()
    if args.cycles % args.jump or args.inc % 4:
        sys.exit("fretting: --cycles must be a multiple of --jump and --inc of 4")
    os.makedirs(args.out, exist_ok=True)
    computed = args.cycles // args.jump
    name = mesh(args.out, args.h)
    path = os.path.join(args.out, "mccoll.inp")
    with open(path, "w") as f:
        f.write(deck(name, computed, args.jump, args.inc, args.every or args.inc))
    t0 = time.perf_counter()
    with open(os.path.join(args.out, "run.log"), "w") as log:
        p = subprocess.run([CFE2D, path], stdout=log, stderr=subprocess.STDOUT, cwd=args.out)
    wall = time.perf_counter() - t0
    if p.returncode != 0:
        sys.exit(f"fretting: cfe2d failed (exit {p.returncode}), see {args.out}/run.log")
    table = os.path.join(args.out, "mccoll_contact.csv")
    flat, cyl = last_profiles(table)
    d, w = scar(flat)
    print(f"flat: depth {d * 1e3:.3f} um, width {w:.3f} mm; cylinder: depth "
          f"{max(h for _, h in cyl) * 1e3:.3f} um; worn area of the flat {area(flat) * 1e6:.2f} um*mm")
    rd, rw = reference()
    print(f"reproduction (LevelSetWear, 18000 cycles): depth {rd:.2f} um, width {rw:.2f} mm")
    if not args.no_plot:
        plot(args.out, table, args.jump, computed)
    md, mw = measured()
    print(f"fretting: depth {d * 1e3:.2f} um (measured {md:.2f}), width {w:.2f} mm (measured {mw:.2f}), "
          f"{args.cycles} cycles, jump {args.jump}, wall {wall:.1f} s")


def area(profile):
    """Worn area of a profile (trapezoidal), mm^2."""
    return sum(0.5 * (h0 + h1) * (x1 - x0) for (x0, h0), (x1, h1) in zip(profile, profile[1:]))


if __name__ == "__main__":
    main()
