#!/usr/bin/env python3
"""`make bench`: what a contact history costs against one factorisation.

1. The flagship (scripts/run_hertz.py, cylinder on plate, 20 increments
   down and up) on the coarse, default and fine meshes, and the 1e6-dof
   square (1 increment, no contact), each a whole cfe2d run from deck to
   listing, repeated (the best wall time counts; the machine is shared).
   Printed: wall, user and system time of the whole run, its peak memory,
   the factorisation counts, the solve part of the run (assembly, analysis,
   factorisations, status iterations, recovery: the listing's TIMING
   block), one factorisation plus solve of the same mesh without contact
   (analysis + factorisation + solve of a one-increment run without the
   contact pair), and their ratios.
2. Friction: the flagship mesh pressed (10 increments) then pushed
   sideways 0.2 mm (10 increments) until the cylinder slides (its
   tangential reaction reaches mu P, mu = 0.3), against the same two-step
   history without friction: wall times, their ratio (target <= 2), the
   sparse factorisations per step (target 1) and the contact iterations.
3. The couplings (scripts/contact_accuracy.py): node-to-segment against
   segment-to-segment with exact enforcement on the flagship history
   (default CPS4 mesh, CPS8, a coarse 5 300-node mesh): the pressures'
   oscillation about the fitted Hertz ellipse, the largest nodal pressure,
   the slave-master difference, the wall times and their ratio (target
   <= 1.5), and the exact answer with PENALTY= over three decades.
4. Nonlinear: the O-ring example (input/examples/oring.inp: axisymmetric
   neo-Hooke, NLGEOM, squeezed 25 % between steel plates with contact,
   automatic increments): wall time, increments, Newton iterations,
   increments cut back, numeric factorisations (one per Newton
   iteration: full Newton) and the force at full squeeze.
5. MUMPS (issue 22; where bin/cfe2d has it and mpirun starts): the 1e6-dof
   square with CHOLMOD, MUMPS on 1 rank and MUMPS on 2 ranks
   (mpirun -np 2) in the same run: wall time, solve part, peak memory of
   the largest process (a rank), the ratios to CHOLMOD.
6. With --surfaces N,N,...: contact surfaces of N contact points
   (scripts/contact_decks.py: two long strips, a rough surface on a flat;
   two steps of 4 increments) on the condensed and the full path, with
   CHOLMOD and with MUMPS over 2 ranks, and which path AUTO takes.
7. *FREQUENCY (scripts/bench_frequency.py): the 10 lowest modes of a
   CPS8 plate of about 1e5 dofs, and CalculiX on the same deck in the
   same run when ccx is on PATH.
8. Threads (issue 32, item 2): the flagship (default mesh) and the NLGEOM
   Hertz of scripts/bench_calculix.py on 1 and 2 element threads
   (OMP_NUM_THREADS): wall times, their ratio, and the listing's timed
   parts that hold the element loops (setup: stored stiffness; assembly:
   nonlinear tangents and the matrix sums; recovery: internal forces;
   results: stresses and contact results) with their share of the run.
   The answers are the same bits on any count (tests/test_kernels.py).
9. With --solvers: the solvers on a structured plane-stress square (Q4) at
   about 1e4, 1e5 and 1e6 dofs (tests/bench/bench.f90, one process per
   case): dofs, stored nonzeros, factor size, wall times of structure,
   assembly, ordering+symbolic analysis, numeric factorisation and solve,
   peak memory and the residual ||Ku-f||/||f||.

Meshes and decks are kept in results/bench/ (the fine mesh takes gmsh
about a minute) and made again only when missing.
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
WORK = os.path.join(ROOT, "results", "bench")
SIZES = [("1e4", 70), ("1e5", 223), ("1e6", 706)]
CASES = [("cholmod", "amd"), ("cholmod", "metis"), ("umfpack", "amd"), ("skyline", "rcm")]
SKYLINE_MAX = 223
SQUARE_NX = 706


def run_measured(args):
    """Runs a command; returns (wall, user, sys, peak MiB, returncode,
    minor page faults). The peak is read by /usr/bin/time where it exists:
    the rusage of a child forked from this Python process would count
    Python's own pages from before the exec. The minor faults (pages the
    kernel had to clear and map) are most of the system time of a large
    run."""
    gnu_time = shutil.which("time", path="/usr/bin")
    t0 = time.perf_counter()
    if gnu_time:
        p = subprocess.run([gnu_time, "-f", "%M %U %S %R", *args], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                           text=True)
        wall = time.perf_counter() - t0
        kib, user, syst, minflt = p.stderr.strip().splitlines()[-1].split()
        return wall, float(user), float(syst), float(kib) / 1024.0, p.returncode, int(minflt)
    p = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, ru = os.wait4(p.pid, 0)
    wall = time.perf_counter() - t0
    p.returncode = os.waitstatus_to_exitcode(status)
    return wall, ru.ru_utime, ru.ru_stime, ru.ru_maxrss / 1024.0, p.returncode, ru.ru_minflt


def timing_block(listing):
    """The listing's TIMING block and the SOLVER block's items."""
    items = {}
    with open(listing) as f:
        text = f.read()
    block = text.split("--- TIMING", 1)[1]
    for line in block.splitlines()[2:]:
        w = line.split()
        if len(w) == 2:
            items[w[0]] = float(w[1])
    m = re.search(r"^contact_equations (\d+)$", text, re.M)
    items["contact_equations"] = int(m.group(1)) if m else 0
    m = re.search(r"^equations (\d+)$", text, re.M)
    items["equations"] = int(m.group(1)) if m else 0
    return items


def solve_part(t):
    return t["assembly"] + t["analyse"] + t["factor"] + t["condensed_iterations"] + t["full_iterations"] + t["recovery"]


def one_factor_solve(t):
    return t["analyse"] + t["factor"] + t["full_iterations"]


def best_of(deck, repeats):
    """Best wall time of repeated runs of one deck, with its listing's
    timing (wall, user, sys, timing, peak, minor faults of that run); peak
    memory is the largest seen."""
    best = None
    peak = 0.0
    for _ in range(repeats):
        wall, user, syst, mib, rc, faults = run_measured([CFE2D, "-q", deck])
        if rc != 0:
            raise RuntimeError(f"cfe2d failed on {deck}")
        peak = max(peak, mib)
        t = timing_block(os.path.splitext(deck)[0] + ".out")
        if best is None or wall < best[0]:
            best = (wall, user, syst, t, faults)
    return best[:4] + (peak, best[4])


def hertz_decks(mesh):
    """The flagship deck on one mesh and the same mesh without contact."""
    import run_hertz
    out = os.path.join(WORK, "hertz_" + mesh)
    deck = os.path.join(out, "hertz.inp")
    if not os.path.exists(os.path.join(out, "hertz_mesh.inp")):
        print(f"  meshing {mesh} (gmsh) ...", flush=True)
        run_hertz.run_case(out, mesh)
    with open(deck) as f:
        text = f.read()
    nocontact = re.sub(r"\*CONTACT PAIR.*\n.*\n", "", text)
    nocontact = nocontact.replace("0.1, 2.0", "1.0, 1.0")
    nocontact = re.sub(r"\*NODE FILE\n.*\n\*EL FILE\nS\n", "", nocontact)
    assert "*CONTACT PAIR" not in nocontact and "*NODE FILE" not in nocontact
    plain = os.path.join(out, "nocontact.inp")
    with open(plain, "w") as f:
        f.write(nocontact)
    return deck, plain


FRICTION_STEPS = """*STEP, NAME=PRESS
*STATIC
0.1, 1.0
*BOUNDARY
CYL_TOP, 1, 1
CYL_TOP, 2, 2, -0.4
*END STEP
*STEP, NAME=PUSH
*STATIC
0.1, 1.0
*BOUNDARY
CYL_TOP, 1, 1, 0.2
CYL_TOP, 2, 2, -0.4
*NODE PRINT, NSET=CYL_TOP, TOTALS=ONLY
RF
*END STEP
"""


def friction_decks(mesh):
    """The flagship mesh pressed, then pushed sideways until it slides:
    with mu = 0.3 and without friction (same history)."""
    deck, _ = hertz_decks(mesh)
    with open(deck) as f:
        text = f.read()
    model = text[:text.index("*STEP")]
    model = re.sub(r"\*AMPLITUDE.*\n.*\n", "", model)
    model = model.replace("CYL_TOP, 1, 1\n", "")
    assert "*CONTACT PAIR, SEARCH DISTANCE=1.0\n" in model
    out = []
    for tag, extra in (("frictionless", ""), ("friction", ", FRICTION=0.3")):
        path = os.path.join(os.path.dirname(deck), f"push_{tag}.inp")
        with open(path, "w") as f:
            f.write(model.replace("*CONTACT PAIR, SEARCH DISTANCE=1.0", "*CONTACT PAIR, SEARCH DISTANCE=1.0" + extra)
                    + FRICTION_STEPS)
        out.append(path)
    return out


def step_counts(listing):
    """Per step: numeric factorisations and contact iterations (STEP SUMMARY)."""
    with open(listing) as f:
        blocks = [b.split("\n\n")[0] for b in f.read().split("--- STEP SUMMARY")[1:]]
    return ([int(re.search(r"^numeric_factorisations (\d+)$", b, re.M).group(1)) for b in blocks],
            [int(re.search(r"^contact_iterations (\d+)$", b, re.M).group(1)) for b in blocks])


def friction_table(meshes, repeats):
    print("\nfriction: flagship mesh pressed, then pushed sideways 0.2 mm until it slides (mu = 0.3),"
          " against the same history without friction")
    cols = ["mesh", "wall_s", "wall_mu0_s", "ratio", "numeric/step", "iters", "iters_mu0", "Q/P"]
    print(" ".join(f"{c:>12}" for c in cols), flush=True)
    for mesh in meshes:
        plain, fric = friction_decks(mesh)
        w0 = best_of(plain, repeats)[0]
        w1 = best_of(fric, repeats)[0]
        nf, it1 = step_counts(os.path.splitext(fric)[0] + ".out")
        _, it0 = step_counts(os.path.splitext(plain)[0] + ".out")
        with open(os.path.splitext(fric)[0] + ".out") as f:
            rf = re.findall(r"^CYL_TOP\s+(\S+)\s+(\S+)$", f.read(), re.M)
        q_over_p = -float(rf[-1][0]) / float(rf[-1][1]) if rf else float("nan")
        row = [mesh, f"{w1:.2f}", f"{w0:.2f}", f"{w1 / w0:.2f}", "/".join(map(str, nf)), sum(it1), sum(it0),
               f"{q_over_p:.4f}"]
        print(" ".join(f"{c:>12}" for c in row), flush=True)
    print("targets: ratio <= 2, one numeric factorisation per step, Q/P = mu = 0.3 at the end")


def nonlinear_table(repeats):
    """The O-ring example: a copy in results/bench/oring run repeatedly."""
    print("\nnonlinear: O-ring (input/examples/oring.inp), neo-Hooke CAX4 squeezed 25 % between steel plates")
    cols = ["deck", "wall_s", "increments", "newton", "cutbacks", "numeric", "force_N"]
    print(" ".join(f"{c:>12}" for c in cols), flush=True)
    d = os.path.join(WORK, "oring")
    os.makedirs(d, exist_ok=True)
    deck = os.path.join(d, "oring.inp")
    shutil.copy(os.path.join(ROOT, "input", "examples", "oring.inp"), deck)
    wall = best_of(deck, repeats)[0]
    with open(os.path.join(d, "oring.out")) as f:
        text = f.read()

    def item(name):
        m = re.search(rf"^{name} (\d+)$", text, re.M)
        return int(m.group(1)) if m else -1
    rf = re.findall(r"^UPPER_TOP\s+(\S+)\s+(\S+)$", text, re.M)
    force = -float(rf[-1][1]) if rf else float("nan")
    row = ["oring", f"{wall:.2f}", item("increments"), item("newton_iterations"), item("cutbacks"),
           item("numeric_factorisations"), f"{force:.2f}"]
    print(" ".join(f"{c:>12}" for c in row), flush=True)


def thread_table(repeats):
    """Wall time on 1 and 2 element threads (OMP_NUM_THREADS) of the
    flagship's default mesh and the NLGEOM Hertz on it; loops: the timed
    parts that hold the element loops (setup + assembly + recovery +
    results of the TIMING block, which also hold the matrix sums and the
    contact results), share: their part of the listing's total."""
    import bench_calculix
    print("\nthreads: element loops on 1 and 2 threads (OMP_NUM_THREADS; the same bits on either)")
    cols = ["deck", "wall_1t_s", "wall_2t_s", "ratio", "loops_1t_s", "loops_2t_s", "share_1t", "CPU_2t_s"]
    print(" ".join(f"{c:>12}" for c in cols), flush=True)
    cases = [("hertz_default", hertz_decks("default")[0]),
             ("nlgeom_hertz", bench_calculix.decks(["nlgeom_hertz"])["nlgeom_hertz"])]
    saved = os.environ.get("OMP_NUM_THREADS")
    try:
        for name, deck in cases:
            got = {}
            # the two counts alternate, so that both see the same load of a
            # shared machine; the best wall time of each counts
            for _ in range(repeats):
                for n in (1, 2):
                    os.environ["OMP_NUM_THREADS"] = str(n)
                    wall, user, syst, t = best_of(deck, 1)[:4]
                    if n not in got or wall < got[n][0]:
                        got[n] = (wall, t["setup"] + t["assembly"] + t["recovery"] + t["results"], t["total"],
                                  user + syst)
            (w1, l1, t1, _), (w2, l2, _, c2) = got[1], got[2]
            row = [name, f"{w1:.2f}", f"{w2:.2f}", f"{w1 / w2:.2f}", f"{l1:.2f}", f"{l2:.2f}", f"{l1 / t1:.2f}",
                   f"{c2:.2f}"]
            print(" ".join(f"{c:>12}" for c in row), flush=True)
    finally:
        if saved is None:
            os.environ.pop("OMP_NUM_THREADS", None)
        else:
            os.environ["OMP_NUM_THREADS"] = saved


def square_deck(nx=SQUARE_NX):
    """The unit square of nx * nx CPS4 with rollers on two sides and a load
    on every node, as a deck (about 43 MB at nx = 706, 1e6 dofs)."""
    path = os.path.join(WORK, "square", f"square{nx}.inp")
    if os.path.exists(path):
        return path
    os.makedirs(os.path.dirname(path), exist_ok=True)
    n = nx + 1
    with open(path, "w") as f:
        f.write(f"*HEADING\nunit square, {nx} x {nx} CPS4, plane stress\n*NODE, NSET=ALLN\n")
        f.write("".join(f"{j * n + i + 1}, {i / nx:.17g}, {j / nx:.17g}\n" for j in range(n) for i in range(n)))
        f.write("*ELEMENT, TYPE=CPS4, ELSET=ALL\n")
        f.write("".join(f"{j * nx + i + 1}, {j * n + i + 1}, {j * n + i + 2}, {j * n + i + n + 2}, {j * n + i + n + 1}\n"
                        for j in range(nx) for i in range(nx)))
        f.write(f"*NSET, NSET=BOTTOM, GENERATE\n1, {n}, 1\n*NSET, NSET=LEFT, GENERATE\n1, {n * (n - 1) + 1}, {n}\n"
                f"*NSET, NSET=CORNER\n{n * n}\n")
        f.write("*MATERIAL, NAME=STEEL\n*ELASTIC\n210000., 0.3\n*SOLID SECTION, ELSET=ALL, MATERIAL=STEEL\n1.\n"
                "*BOUNDARY\nBOTTOM, 2, 2\nLEFT, 1, 1\n*STEP\n*STATIC\n1., 1.\n*CLOAD\nALLN, 1, 1.0\nALLN, 2, 0.5\n"
                "*NODE PRINT, NSET=CORNER\nU\n*END STEP\n")
    return path


HEAD = ["case", "equations", "contact_eqs", "wall_s", "user_s", "sys_s", "sys/user", "minflt", "solve_s", "one_fs_s",
        "wall/one", "solve/one", "peak_MiB", "numeric", "condensed"]


def contact_table(meshes, repeats, square):
    print(f"cores: {os.cpu_count()}, load average before: {' '.join(f'{v:.2f}' for v in os.getloadavg())}")
    print("whole cfe2d runs, deck to listing, best wall time of", repeats, "runs")
    print(" ".join(f"{c:>11}" for c in HEAD), flush=True)
    cases = []
    for mesh in meshes:
        deck, plain = hertz_decks(mesh)
        cases.append(("hertz_" + mesh, deck, plain))
    if square:
        path = square_deck()
        cases.append(("square_1e6", path, None))
    for name, deck, plain in cases:
        wall, user, syst, t, peak, faults = best_of(deck, repeats)
        one = one_factor_solve(t) if plain is None else one_factor_solve(best_of(plain, repeats)[3])
        row = [name, t["equations"], t["contact_equations"], f"{wall:.2f}", f"{user:.2f}", f"{syst:.2f}",
               f"{syst / user:.2f}", faults, f"{solve_part(t):.2f}", f"{one:.3f}", f"{wall / one:.1f}",
               f"{solve_part(t) / one:.1f}", f"{peak:.0f}", int(t["numeric_factorisations"]),
               int(t["condensed_factorisations"])]
        print(" ".join(f"{c:>11}" for c in row), flush=True)
    print(f"load average after: {' '.join(f'{v:.2f}' for v in os.getloadavg())}")
    print("targets: wall/one <= 1.5 (default, fine; issue 32: hertz_default <= 4); hertz_default < 2 s, "
          "hertz_fine < 6 s; square_1e6 < 6 s with sys/user < 0.20; hertz_default peak <= 105 MiB "
          "(minflt: minor page faults of the best run)")


def mpirun(np_):
    """The launcher for np_ ranks (Open MPI: as root too, oversubscribed on
    a machine with fewer cores), or None where there is none."""
    exe = shutil.which("mpirun")
    if exe is None:
        return None
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    version = subprocess.run([exe, "--version"], capture_output=True, text=True).stdout
    return [exe] + (["--oversubscribe"] if "Open MPI" in version else []) + ["-np", str(np_)]


def mumps_runs():
    """(label, command prefix) of the MUMPS runs this machine can do."""
    probe = subprocess.run([CFE2D, "--solver", "MUMPS", "--version"], capture_output=True, text=True)
    if probe.returncode != 0:
        print(f"\nno MUMPS rows: {probe.stderr.strip()}")
        return []
    runs = [("mumps_1", [CFE2D, "--solver", "MUMPS"])]
    two = mpirun(2)
    if two:
        runs.append(("mumps_2", two + [CFE2D, "--solver", "MUMPS"]))
    return runs


def measured(cmd, deck, repeats, timeout=None):
    """Best wall time of repeated runs, the listing's timing, the largest peak."""
    best, peak = None, 0.0
    for _ in range(repeats):
        wall, user, syst, mib, rc, _ = run_measured(cmd + ["-q", deck])
        if rc != 0:
            raise RuntimeError(f"{' '.join(cmd)} failed on {deck}")
        peak = max(peak, mib)
        t = timing_block(os.path.splitext(deck)[0] + ".out")
        if best is None or wall < best[0]:
            best = (wall, t)
    return best[0], best[1], peak


def mumps_square_table(repeats):
    runs = mumps_runs()
    if not runs:
        return
    path = square_deck()
    print(f"\nthe 1e6-dof square: CHOLMOD and MUMPS in the same run, best of {repeats}; "
          f"load average before: {' '.join(f'{v:.2f}' for v in os.getloadavg())}")
    cols = ["solver", "equations", "wall_s", "solve_s", "factor_s", "peak_MiB", "wall/cholmod", "solve/cholmod"]
    print(" ".join(f"{c:>13}" for c in cols), flush=True)
    ref = None
    for label, cmd in [("cholmod", [CFE2D])] + runs:
        wall, t, peak = measured(cmd, path, repeats)
        solve = solve_part(t)
        if ref is None:
            ref = (wall, solve)
        row = [label, t["equations"], f"{wall:.2f}", f"{solve:.2f}", f"{t['factor']:.2f}", f"{peak:.0f}",
               f"{wall / ref[0]:.2f}", f"{solve / ref[1]:.2f}"]
        print(" ".join(f"{c:>13}" for c in row), flush=True)
    print(f"load average after: {' '.join(f'{v:.2f}' for v in os.getloadavg())}; peak: the largest process (a rank)")


def surface_table(points, repeats, condensed_max=4000):
    """Contact surfaces of many points: condensed and full, CHOLMOD and MUMPS (2 ranks).
    setup_s is the listing's setup, where the contact search's time goes (with the
    equation numbering): the 50 000-point rough surface's search is its target."""
    import contact_decks
    runs = [("cholmod", [CFE2D])] + [r for r in mumps_runs() if r[0] == "mumps_2"]
    print(f"\ncontact surfaces (scripts/contact_decks.py), best of {repeats}; load average before: "
          f"{' '.join(f'{v:.2f}' for v in os.getloadavg())}")
    cols = ["case", "points", "equations", "contact_eqs", "solver", "path", "wall_s", "setup_s", "peak_MiB",
            "auto_takes"]
    print(" ".join(f"{c:>11}" for c in cols), flush=True)
    d = os.path.join(WORK, "surfaces")
    os.makedirs(d, exist_ok=True)
    for kind in ("strips", "rough"):
        for n in points:
            for label, cmd in runs:
                solver = "MUMPS" if label.startswith("mumps") else "CHOLMOD"
                deck = os.path.join(d, f"{kind}{n}_{label}_auto.inp")
                with open(deck, "w") as f:
                    f.write(contact_decks.deck(kind, n, 4, 0.8, 0.02, 1, 3.0, 4, solver, "AUTO"))
                subprocess.run(cmd + ["-q", deck], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                with open(os.path.splitext(deck)[0] + ".out") as f:
                    m = re.search(r"^contact_solve (\w+)$", f.read(), re.M)
                auto = m.group(1) if m else "?"
                for path in ("condensed", "full"):
                    if path == "condensed" and n > condensed_max:
                        continue
                    deck = os.path.join(d, f"{kind}{n}_{label}_{path}.inp")
                    with open(deck, "w") as f:
                        f.write(contact_decks.deck(kind, n, 4, 0.8, 0.02, 1, 3.0, 4, solver, path.upper()))
                    wall, t, peak = measured(cmd, deck, repeats)
                    row = [kind, n, t["equations"], t["contact_equations"], label, path, f"{wall:.2f}",
                           f"{t['setup']:.2f}", f"{peak:.0f}", auto]
                    print(" ".join(f"{c:>11}" for c in row), flush=True)
    print(f"load average after: {' '.join(f'{v:.2f}' for v in os.getloadavg())}")


def solver_table(exe, sizes):
    print(f"\nsolvers on the structured square (tests/bench/bench.f90, {exe})")
    cols = ["size", "solver", "ordering", "dofs", "nnz", "factor", "t_structure", "t_assembly", "t_analysis",
            "t_factor", "t_solve", "peak_MiB", "residual"]
    print(" ".join(f"{c:>11}" for c in cols))
    failed = False
    for label, nx in SIZES:
        if label not in sizes:
            continue
        for solver, order in CASES:
            if solver == "skyline" and nx > SKYLINE_MAX:
                print(f"{label:>11} {solver:>11} {order:>11}   (skipped: profile too large for the skyline)")
                continue
            try:
                out = subprocess.run([exe, solver, order, str(nx)], capture_output=True, text=True, timeout=900)
            except subprocess.TimeoutExpired:
                print(f"{label:>11} {solver:>11} {order:>11}   (over 900 s)")
                continue
            if out.returncode != 0:
                print(f"{label:>11} {solver:>11} {order:>11}   failed: {out.stderr.strip()[:200]}")
                failed = True
                continue
            kv = dict(re.findall(r"(\w+)=\s*(\S+)", out.stdout))
            row = [label, solver, order] + [kv[c] for c in cols[3:]]
            print(" ".join(f"{c:>11}" for c in row), flush=True)
    return failed


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "bench"), help="the solver benchmark program")
    ap.add_argument("--meshes", default="coarse,default,fine")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--no-square", action="store_true", help="leave out the 1e6-dof square")
    ap.add_argument("--solvers", action="store_true", help="also the solver table on the structured square")
    ap.add_argument("--no-couplings", action="store_true", help="leave out the table of the two couplings")
    ap.add_argument("--sizes", default="1e4,1e5,1e6", help="sizes of the solver table")
    ap.add_argument("--no-mumps", action="store_true", help="leave out the MUMPS rows of the 1e6-dof square")
    ap.add_argument("--surfaces", default="", help="contact points of the surface table, e.g. 1000,2000,4000")
    ap.add_argument("--condensed-max", type=int, default=4000, help="largest surface run on the condensed path")
    ap.add_argument("--only-nonlinear", action="store_true", help="only the nonlinear table")
    ap.add_argument("--only-threads", action="store_true", help="only the thread table")
    args = ap.parse_args(argv)
    if args.only_nonlinear:
        nonlinear_table(args.repeats)
        return 0
    if args.only_threads:
        thread_table(args.repeats)
        return 0
    if shutil.which("gmsh") is None:
        print("gmsh is not installed: no flagship meshes (scripts/install-deps.sh installs it)")
        meshes = []
    else:
        meshes = [m for m in args.meshes.split(",") if m]
    contact_table(meshes, args.repeats, not args.no_square)
    friction_table([m for m in meshes if m != "fine"], args.repeats)
    if meshes and not args.no_couplings:
        import contact_accuracy
        print("\ncouplings: node-to-segment (nts) against segment-to-segment with exact enforcement (sts)")
        contact_accuracy.table(["default", "q8", "ccx"], os.path.join(WORK, "accuracy"), args.repeats, penalties=True)
    nonlinear_table(args.repeats)
    if meshes:
        thread_table(args.repeats)
    __import__("bench_calculix").table(["nlgeom_hertz", "cattaneo_mindlin", "oring"], args.repeats)
    __import__("bench_heat").table(repeats=args.repeats)   # heat: a linear transient against CalculiX (bench_heat.py)
    __import__("bench_coupled").table(repeats=args.repeats)   # coupled: two blocks through h(p) against CalculiX
    if not args.no_mumps and not args.no_square:
        mumps_square_table(args.repeats)
    __import__("bench_frequency").table(args.repeats)
    __import__("bench_fretting").table()
    if args.surfaces:
        surface_table([int(v) for v in args.surfaces.split(",")], 1, args.condensed_max)
    failed = solver_table(args.exe, args.sizes.split(",")) if args.solvers else False
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
