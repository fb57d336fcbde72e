#!/usr/bin/env python3
"""`make bench`, the rows against CalculiX (issue 32): the nonlinear and
frictional histories run by cfe2d and by CalculiX's `ccx` in the same
`make bench`, one thread each, on the same deck.

    python3 scripts/bench_calculix.py [--cases nlgeom_hertz,cattaneo_mindlin,oring] [--repeats 3]

Cases (decks written into results/bench/calculix/, CalculiX's syntax, which
cfe2d reads unchanged):

  nlgeom_hertz      the flagship mesh (scripts/run_hertz.py, default mesh:
                    cylinder on plate, CPS4, plane stress) under NLGEOM,
                    pressed 0.4 mm and released (amplitude 0-1-0 over the
                    step time 2, automatic increments from 0.1), node-to-
                    surface contact, PRESSURE-OVERCLOSURE=LINEAR with
                    K = 50 E / h (h the mean master edge). Target: cfe2d
                    >= 20x faster than CalculiX.
  cattaneo_mindlin  the same mesh, small deformation, *FRICTION mu = 0.3,
                    K = 10 E / h, stick slope K / 100, SMALL SLIDING (paired once):
                    pressed 0.4 mm in 10 increments (cfe2d's linear
                    steps; CalculiX's automatic increments: with DIRECT
                    it stopped diverging in the fourth),
                    then pushed sideways 0.2 mm in 10 increments until it
                    slides (bench.py's friction history). Target >= 30x.
  oring             input/examples/oring.inp as it is (neo-Hooke O-ring
                    squeezed 25 %, NLGEOM). Target >= 5x.

Each deck runs in cfe2d `--repeats` times (the run of least CPU time
counts) and once in ccx (OMP_NUM_THREADS=1 and CalculiX's CCX_NPROC_* = 1;
the environment of both also keeps OpenBLAS to one thread). Printed per
case: wall and CPU (user + system) seconds of both, their ratios (the
target is judged on the CPU ratio: with one thread each it is the wall
ratio of an idle machine, and this machine is shared, its wall times
inflated by whatever else runs), cfe2d's one factorisation (the flagship
mesh: analysis, factorisation and solve of a one-increment run without
contact, bench.py's one_fs_s; the O-ring: the listing's factor time over its
numeric factorisations), cfe2d's wall over it, cfe2d's Newton iterations
and numeric + condensed factorisations, CalculiX's increments and
iterations (its .sta), and |RF2| of the moved set's printed totals in
both .dat files at one time `at_t` (the same parser, set, component and
time for both: the NLGEOM Hertz at its peak t = 1, a time point of its
deck that both programs' automatic increments end on; the O-ring at its
full squeeze; the friction history at its end). CalculiX's totals of an
axisymmetric deck are those of the 2 degree sector it expands it into:
multiplied by 180 for the whole ring, as cfe2d's. The O-ring's two
columns still differ by about 39 %: CalculiX's CAX4 is a full-integration
brick, which locks for the nearly incompressible rubber (K / mu = 1250);
with CAX4R in the ring (reduced-integration bricks) CalculiX gives
485.4 N against cfe2d's 467.5 N (CAX4R) and 469.2 N (CAX4, F-bar)
(docs/benchmark.md).

Without `ccx` on PATH the table says so and nothing runs.
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
sys.path.insert(0, HERE)

CFE2D = os.path.join(ROOT, "bin", "cfe2d")
WORK = os.path.join(ROOT, "results", "bench", "calculix")
ONE_THREAD = {"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "CCX_NPROC_EQUATION_SOLVER": "1",
              "CCX_NPROC_RESULTS": "1", "CCX_NPROC_STIFFNESS": "1"}
TARGETS = {"nlgeom_hertz": 20.0, "cattaneo_mindlin": 30.0, "oring": 5.0}
E_STEEL = 210000.0
# CPS4 faces in CalculiX's numbering: S1 = nodes 1-2, S2 = 2-3, S3 = 3-4, S4 = 4-1
FACES = ((0, 1), (1, 2), (2, 3), (3, 0))


def read_gmsh_inp(path):
    """Nodes, elements {id: (type, nodes)}, element and node sets of a gmsh .inp."""
    nodes, elements, elsets, nsets = {}, {}, {}, {}
    mode, cur, etype = None, None, None
    with open(path) as f:
        for line in f:
            s = line.strip()
            if not s or s.startswith("**"):
                continue
            if s.startswith("*"):
                key = s.upper().replace(" ", "")
                mode = None
                if key.startswith("*NODE"):
                    mode = "node"
                elif key.startswith("*ELEMENT"):
                    mode = "elem"
                    etype = re.search(r"TYPE=(\w+)", key).group(1)
                    cur = re.search(r"ELSET=(\w+)", key).group(1)
                elif key.startswith("*ELSET"):
                    mode, cur = "elset", re.search(r"ELSET=(\w+)", key).group(1)
                    elsets.setdefault(cur, [])
                elif key.startswith("*NSET"):
                    mode, cur = "nset", re.search(r"NSET=(\w+)", key).group(1)
                    nsets.setdefault(cur, [])
                continue
            vals = [v for v in s.replace(",", " ").split()]
            if mode == "node":
                nodes[int(vals[0])] = (float(vals[1]), float(vals[2]))
            elif mode == "elem":
                elements[int(vals[0])] = (etype, [int(v) for v in vals[1:]])
            elif mode == "elset":
                elsets[cur] += [int(v) for v in vals]
            elif mode == "nset":
                nsets[cur] += [int(v) for v in vals]
    return nodes, elements, elsets, nsets


def edge_faces(edges, elements):
    """(element, face) of the CPS4 element owning each line element's edge."""
    owner = {}
    for e, (t, conn) in elements.items():
        if t != "CPS4":
            continue
        for k, (a, b) in enumerate(FACES):
            owner[frozenset((conn[a], conn[b]))] = (e, k + 1)
    return [owner[frozenset(elements[le][1][:2])] for le in edges]


def lines(ids, per=8):
    return "".join(", ".join(str(i) for i in ids[k:k + per]) + "\n" for k in range(0, len(ids), per))


def hertz_model(mesh_inp, friction):
    """The flagship model in CalculiX's syntax (no step)."""
    nodes, elements, elsets, nsets = read_gmsh_inp(mesh_inp)
    quads = sorted(e for e, (t, _) in elements.items() if t == "CPS4")
    out = ["*HEADING\nflagship mesh (cylinder on plate, CPS4 plane stress), bench_calculix.py\n*NODE, NSET=NALL\n"]
    out += [f"{n}, {x:.12g}, {y:.12g}\n" for n, (x, y) in sorted(nodes.items())]
    out.append("*ELEMENT, TYPE=CPS4, ELSET=EALL\n")
    out += [f"{e}, " + ", ".join(map(str, elements[e][1])) + "\n" for e in quads]
    quadset = set(quads)
    for name in ("PLATE", "CYLINDER"):
        out.append(f"*ELSET, ELSET={name}\n" + lines([e for e in elsets[name] if e in quadset]))
    for name in ("PLATE_BOTTOM", "PLATE_ANCHOR", "CYL_TOP"):
        out.append(f"*NSET, NSET={name}\n" + lines(sorted(set(nsets[name]))))
    h = []
    for name, surf in (("PLATE_TOP", "PLATE_SURFACE"), ("CYL_ARC", "CYLINDER_SURFACE")):
        out.append(f"*SURFACE, NAME={surf}, TYPE=ELEMENT\n")
        out += [f"{e}, S{k}\n" for e, k in edge_faces(elsets[name], elements)]
        if name == "PLATE_TOP":
            for le in elsets[name]:
                a, b = elements[le][1][:2]
                h.append(((nodes[a][0] - nodes[b][0]) ** 2 + (nodes[a][1] - nodes[b][1]) ** 2) ** 0.5)
    # the penalty: 50 E / h (CalculiX's advice: 5 to 50 E / h); with friction 10 E / h and a stick
    # slope of K / 100 (with 50 E / h and K / 10 ccx 2.20 gave up the friction history at t = 0.35:
    # too many cutbacks)
    k = (10.0 if friction else 50.0) * E_STEEL / (sum(h) / len(h))
    out.append(f"*MATERIAL, NAME=STEEL\n*ELASTIC\n{E_STEEL:.1f}, 0.3\n"
               "*SOLID SECTION, ELSET=PLATE, MATERIAL=STEEL\n1.\n*SOLID SECTION, ELSET=CYLINDER, MATERIAL=STEEL\n1.\n")
    out.append(f"*SURFACE INTERACTION, NAME=STEEL_STEEL\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n{k:.6g}\n")
    if friction:
        out.append(f"*FRICTION\n0.3, {k / 100.0:.6g}\n")
    # the small-deformation friction history pairs once (SMALL SLIDING: CalculiX's contact elements and
    # cfe2d's couplings stay on their first master faces); under NLGEOM both follow the deformed surfaces
    small = ", SMALL SLIDING" if friction else ""
    out.append(f"*CONTACT PAIR, INTERACTION=STEEL_STEEL, TYPE=NODE TO SURFACE{small}\nCYLINDER_SURFACE, PLATE_SURFACE\n")
    out.append("*AMPLITUDE, NAME=DOWNUP\n0., 0., 1., 1., 2., 0.\n*BOUNDARY\nPLATE_BOTTOM, 2, 2\nPLATE_ANCHOR, 1, 1\n")
    return "".join(out)


# The peak (t = 1) is a time point of the printed totals: both programs shorten the increment that
# would pass it to end there, so both .dat files hold the reaction at the same load (without it the
# two reached different times near the peak: cfe2d 0.9125, 11 793 N, CalculiX another, 13 478 N).
NLGEOM_STEP = """*BOUNDARY
CYL_TOP, 1, 1
*TIME POINTS, NAME=PEAK
1.
*STEP, NLGEOM, INC=100
*STATIC
0.1, 2.0
*BOUNDARY, AMPLITUDE=DOWNUP
CYL_TOP, 2, 2, -0.4
*NODE PRINT, NSET=CYL_TOP, TOTALS=ONLY, TIME POINTS=PEAK
RF
*END STEP
"""

FRICTION_STEPS = """*STEP, INC=100
*STATIC
0.1, 1.0
*BOUNDARY
CYL_TOP, 1, 1
CYL_TOP, 2, 2, -0.4
*NODE PRINT, NSET=CYL_TOP, TOTALS=ONLY
RF
*END STEP
*STEP, INC=100
*STATIC
0.1, 1.0
*BOUNDARY
CYL_TOP, 1, 1, 0.2
CYL_TOP, 2, 2, -0.4
*NODE PRINT, NSET=CYL_TOP, TOTALS=ONLY
RF
*END STEP
"""


def decks(cases):
    """{case: deck path} (written when missing; the flagship mesh made by bench.py)."""
    import bench
    out = {}
    mesh_inp = None
    if {"nlgeom_hertz", "cattaneo_mindlin"} & set(cases):
        deck, _ = bench.hertz_decks("default")
        mesh_inp = os.path.join(os.path.dirname(deck), "hertz_mesh.inp")
    for case in cases:
        d = os.path.join(WORK, case)
        os.makedirs(d, exist_ok=True)
        path = os.path.join(d, case + ".inp")
        if case == "oring":
            shutil.copy(os.path.join(ROOT, "input", "examples", "oring.inp"), path)
        else:
            text = hertz_model(mesh_inp, case == "cattaneo_mindlin")
            text += NLGEOM_STEP if case == "nlgeom_hertz" else FRICTION_STEPS
            old = open(path).read() if os.path.exists(path) else None
            if text != old:
                with open(path, "w") as f:
                    f.write(text)
        out[case] = path
    return out


def timed(args, cwd):
    """(wall, CPU = user + system) seconds of a command run with one thread."""
    env = dict(os.environ, **ONE_THREAD)
    t0 = time.perf_counter()
    p = subprocess.run(["/usr/bin/time", "-f", "%U %S", *args], cwd=cwd, env=env, stdout=subprocess.DEVNULL,
                       stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - t0
    if p.returncode != 0:
        raise RuntimeError(f"{args[0]} failed on {cwd}: {p.stderr[-400:]}")
    user, syst = p.stderr.strip().splitlines()[-1].split()
    return wall, float(user) + float(syst)


def listing_items(path):
    with open(path) as f:
        text = f.read()
    items = {}
    for name in ("newton_iterations", "numeric_factorisations", "condensed_factorisations", "increments"):
        items[name] = sum(int(v) for v in re.findall(rf"^{name} (\d+)$", text.split("--- TIMING")[0], re.M))
    block = text.split("--- TIMING", 1)[1]
    for line in block.splitlines()[2:]:
        w = line.split()
        if len(w) == 2 and "." in w[1]:
            items[w[0]] = float(w[1])
    return items


def dat_totals(path):
    """{time: fy} of the `*NODE PRINT, TOTALS=ONLY` blocks of a .dat (CalculiX's layout, which
    cfe2d writes too): the same parser for both programs, so that the two columns are the same
    set, the same component and the same time."""
    with open(path) as f:
        text = f.read()
    out = {}
    for t, fy in re.findall(r"total force \(fx,fy,fz\) for set \S+ and time\s+(\S+)\s*\n\s*\n\s*\S+\s+(\S+)", text):
        out[float(t)] = float(fy)
    return out


def rf2_at(path, t, scale=1.0):
    """|RF2| of the printed totals at time t (nan where the .dat has no block there)."""
    for tt, fy in dat_totals(path).items():
        if abs(tt - t) <= 1e-6 * max(1.0, abs(t)):
            return abs(fy) * scale
    return float("nan")


# The time at which each case's reactions are compared: the NLGEOM Hertz's peak (a time point of
# its deck), the O-ring's full squeeze, the friction history's end (total time 2: its second step's end).
COMPARE_AT = {"nlgeom_hertz": 1.0, "cattaneo_mindlin": 2.0, "oring": 1.0}


def ccx_scale(deck):
    """CalculiX expands an axisymmetric model into a 2 degree sector of bricks and prints the
    sector's totals; cfe2d's are the whole ring's: 180 times (tests/calculix/README.md)."""
    with open(deck) as f:
        return 180.0 if re.search(r"^\*ELEMENT.*TYPE\s*=\s*CAX", f.read(), re.M | re.I) else 1.0


def ccx_items(job):
    """Increments and iterations of CalculiX's .sta."""
    incs = its = 0
    with open(job + ".sta") as f:
        for line in f:
            p = line.split()
            if len(p) >= 7 and p[0].isdigit() and p[1].isdigit():
                incs += 1
                its += int(p[3])
    return incs, its


def one_factorisation(case, items, repeats):
    """cfe2d's one factorisation for the case (see the module's text)."""
    if case == "oring":
        return items["factor"] / max(items["numeric_factorisations"], 1)
    import bench
    _, plain = bench.hertz_decks("default")
    return bench.one_factor_solve(bench.best_of(plain, repeats)[3])


def table(cases, repeats):
    print("\nagainst CalculiX (ccx, the same deck, one thread each): nonlinear and frictional histories")
    if shutil.which("ccx") is None:
        print("ccx is not on PATH (Debian: apt-get install calculix-ccx): no rows")
        return
    cols = ["case", "wall_s", "cpu_s", "ccx_wall_s", "ccx_cpu_s", "ratio_wall", "ratio_cpu", "one_f_s", "wall/one",
            "newton", "numeric+cond", "ccx_incs", "ccx_iters", "at_t", "RF2", "ccx_RF2", "target"]
    print(" ".join(f"{c:>12}" for c in cols), flush=True)
    for case, deck in decks(cases).items():
        d, name = os.path.dirname(deck), os.path.basename(deck)
        best = None
        for _ in range(repeats):
            w, u = timed([CFE2D, "-q", name], d)
            if best is None or u < best[1]:
                best = (w, u)
        items = listing_items(os.path.join(d, case + ".out"))
        # ccx in a folder of its own: both write .dat, .sta and .frd
        cd = os.path.join(d, "ccx")
        os.makedirs(cd, exist_ok=True)
        shutil.copy(deck, cd)
        cw, cu = timed(["ccx", "-i", case], cd)
        incs, its = ccx_items(os.path.join(cd, case))
        t = COMPARE_AT[case]
        rf2 = rf2_at(os.path.join(d, case + ".dat"), t)
        crf2 = rf2_at(os.path.join(cd, case + ".dat"), t, ccx_scale(deck))
        one = one_factorisation(case, items, repeats)
        ratio = cu / max(best[1], 1e-9)
        met = "met" if ratio >= TARGETS[case] else "not met"
        row = [case, f"{best[0]:.2f}", f"{best[1]:.2f}", f"{cw:.2f}", f"{cu:.2f}", f"{cw / best[0]:.1f}",
               f"{ratio:.1f}", f"{one:.3f}", f"{best[0] / one:.1f}", items["newton_iterations"],
               f"{items['numeric_factorisations']}+{items['condensed_factorisations']}", incs, its,
               f"{t:g}", f"{rf2:.5g}", f"{crf2:.5g}", f">={TARGETS[case]:g}x {met}"]
        print(" ".join(f"{c:>12}" for c in row), flush=True)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", default="nlgeom_hertz,cattaneo_mindlin,oring")
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args(argv)
    table([c for c in args.cases.split(",") if c], args.repeats)
    return 0


if __name__ == "__main__":
    sys.exit(main())
