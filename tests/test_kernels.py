"""Contact decisions must not depend on the CPU (issue 17, item 3).

cfe2d links OpenBLAS; Debian's DYNAMIC_ARCH build picks its kernels for
the CPU it runs on, and OPENBLAS_CORETYPE forces one (Prescott: SSE3,
runs on any x86-64; Sandybridge: AVX; Haswell and Zen: AVX2; SkylakeX: AVX-512).
Kernels sum in different orders, so one deck gives numbers that differ in
the last bits from one machine to the next. That is allowed; a contact
decision that follows those bits is not: a deck must open and close the
same contact elements, in the same iterations and increments, on every
machine.

This module runs the decks of DECKS (one test each, named
"kernels <deck>") with bin/cfe2d under every kernel this CPU can run and
compares each run with the reference, bin/cfe2d on Prescott:

* decisions, exactly: exit status and messages (folders masked); every
  listing line outside the increments' result blocks: step and solver
  headers (coupling elements, contact equations), each contact
  iteration's status changes, closed count and switching nodes, notes
  ("increment bisected", the stabilisation of open contact), the step
  summary's counts of increments, iterations and factorisations; only
  the out-of-balance values, wall times, the deck path, the BLAS line and
  UMFPACK's fill (it pivots on values) are masked; every increment header
  (step, increment, time, total time, iterations); the identity and state
  (OPEN/CLOSED, STICK/SLIP with friction) of every row of <job>_contact.csv;
* numbers, to round-off: every number of the increments' result blocks
  and of the contact table (x, y, gap, force, pressure, and with friction
  shear_force, shear, slip, slip_increment) within RTOL (below)
  of the largest magnitude of its quantity over the reference run (the
  table's 9 printed digits get one unit of their last digit more).

Kernels: Prescott always, Sandybridge if /proc/cpuinfo lists avx, Haswell
and Zen with avx2, SkylakeX with avx512f, and the one OpenBLAS detects by itself
if it is none of these; the listing's `blas` line must name each. The
runs' environment loses any inherited OPENBLAS_CORETYPE and
OPENBLAS_VERBOSE. On a machine that is not x86, or whose OpenBLAS ignores
OPENBLAS_CORETYPE, the kernel tests skip saying so.

The same comparison runs build-debug/cfe2d (-O0 -fcheck=all) on Prescott
against bin/cfe2d on Prescott ("debug build <deck>"); without the debug
build those tests skip (make check builds it first).

Threads (issue 32, item 2): the element loops run on OMP_NUM_THREADS
threads, and their results must not depend on the count at all. Each deck
also runs bin/cfe2d on the reference kernel with OMP_NUM_THREADS=1, 2 and 3
(those the reference run does not already have: it, the kernels and the
debug build inherit the environment's OMP_NUM_THREADS, so that
`OMP_NUM_THREADS=2 make kernels` compares them all on two threads), and
"threads <deck>" requires the same bits: exit status and messages, every
file written byte for byte, the listing with only its wall times and its
`blas` line (which names the team) masked.

By hand: python3 tests/run_tests.py -k test_kernels (one deck:
-k "kernels hertz_point_cax4"); the runs stay in tests/work/kernels_<deck>/
(one folder per variant, the deck in deck/).
"""
import csv
import decimal
import os
import platform
import re
import shutil
import subprocess
from concurrent.futures import ThreadPoolExecutor

from cfe2d_listing import parse_listing
from helpers import CFE2D, ROOT, Skip, workdir

# Round-off allowed, relative to the largest magnitude of the quantity over
# the reference run. Measured here across the kernels and the debug build:
# displacements and coordinates up to 8e-12, forces 3e-11, stresses 3e-10
# (at the contact of NAFEMS 1, where the displacements' round-off meets the
# smallest elements); a different decision moves them by far more.
RTOL = {"displacement": 1e-9, "coordinate": 1e-9, "area": 1e-9, "force": 1e-8, "stress": 1e-8, "strain": 1e-8}
DEBUG = os.path.join(ROOT, "build-debug", "cfe2d")
REFERENCE_CORE = "Prescott"
OOB = re.compile(r"out-of-balance +\S+")
UMF = re.compile(r"(factor entries )\S+")


# ----------------------------------------------------------------- variants

class Variant:
    """A run's program, OpenBLAS kernel (None: the one it detects) and
    element threads (None: the environment's OMP_NUM_THREADS)."""
    def __init__(self, label, exe, core, threads=None):
        self.label, self.exe, self.core, self.threads = label, exe, core, threads

    def env(self):
        env = {k: v for k, v in os.environ.items() if k not in ("OPENBLAS_CORETYPE", "OPENBLAS_VERBOSE")}
        if self.core:
            env["OPENBLAS_CORETYPE"] = self.core
        if self.threads:
            env["OMP_NUM_THREADS"] = str(self.threads)
        # threads that wait sleep: make check runs tests side by side, and a
        # spinning thread waiting for a descheduled one made a 2-thread run
        # 7 times slower (docs/benchmark.md, Threads)
        env.setdefault("OMP_WAIT_POLICY", "PASSIVE")
        return env


# element thread counts compared bit for bit
THREADS = (1, 2, 3)


def inherited_threads():
    """The element threads of a run that inherits the environment: the
    first value of OMP_NUM_THREADS, 1 if it is not set (thread_shim.c)."""
    m = re.match(r"\s*(\d+)", os.environ.get("OMP_NUM_THREADS", ""))
    return max(1, int(m.group(1))) if m else 1


def thread_variants():
    """bin/cfe2d on the reference's kernel with each count of THREADS the
    reference run does not already have."""
    ref, _ = reference_and_debug()
    return [Variant(threads_label(n), CFE2D, ref.core, n) for n in THREADS if n != inherited_threads()]


def threads_label(n):
    return f"{n} thread" + ("s" if n > 1 else "")


def cpu_flags():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("flags"):
                    return set(line.split(":", 1)[1].split())
    except OSError:
        pass
    return set()


def blas_line(listing_path):
    with open(listing_path) as f:
        for line in f:
            if line.startswith("blas "):
                return line.strip()
            if line.startswith("==="):
                break
    return ""


def core_name(line):
    """The kernel OpenBLAS names in its configuration string: the word
    before MAX_THREADS= / SINGLE_THREADED."""
    words = line.split()
    for k, w in enumerate(words):
        if w.startswith("MAX_THREADS=") or w == "SINGLE_THREADED":
            return words[k - 1]
    return ""


def names_core(line, core):
    return core.lower() in (w.lower() for w in line.split())


_PROBE = {}


def probe():
    """(kernel variants, reason they are unavailable or None), found once
    by running the blocks example with and without OPENBLAS_CORETYPE."""
    if _PROBE:
        return _PROBE["variants"], _PROBE["reason"]
    ref = Variant(REFERENCE_CORE, CFE2D, REFERENCE_CORE)
    variants, reason = [], None
    if platform.machine().lower() not in ("x86_64", "amd64", "i386", "i686"):
        reason = (f"not an x86 machine ({platform.machine()}): OPENBLAS_CORETYPE selects x86 kernels only; "
                  "contact decisions were not compared across BLAS kernels")
    else:
        d = workdir("kernels_probe")
        deck = os.path.join(ROOT, "input", "examples", "blocks.inp")
        lines = {}
        for v in (Variant("detected", CFE2D, None), ref):
            out = os.path.join(d, v.label)
            os.makedirs(out)
            r = subprocess.run([v.exe, "-q", "-o", out, deck], capture_output=True, text=True, env=v.env(),
                               timeout=120)
            assert r.returncode == 0, f"{v.exe} on {deck}: {r.stderr}"
            lines[v.label] = blas_line(os.path.join(out, "blocks.out"))
        if "DYNAMIC_ARCH" not in lines["detected"].split():
            reason = (f"the BLAS is not a DYNAMIC_ARCH OpenBLAS (listing: '{lines['detected']}'): "
                      "OPENBLAS_CORETYPE has no effect; contact decisions were not compared across BLAS kernels")
        elif not names_core(lines[REFERENCE_CORE], REFERENCE_CORE):
            reason = (f"OPENBLAS_CORETYPE={REFERENCE_CORE} did not change the kernel (listing: "
                      f"'{lines[REFERENCE_CORE]}'); contact decisions were not compared across BLAS kernels")
        else:
            flags = cpu_flags()
            variants = [ref]
            if "avx" in flags:
                variants.append(Variant("Sandybridge", CFE2D, "Sandybridge"))
            if "avx2" in flags:
                variants.append(Variant("Haswell", CFE2D, "Haswell"))
                variants.append(Variant("Zen", CFE2D, "Zen"))
            if "avx512f" in flags:
                variants.append(Variant("SkylakeX", CFE2D, "SkylakeX"))
            detected = core_name(lines["detected"])
            if detected and not any(v.core.lower() == detected.lower() for v in variants):
                variants.append(Variant(f"{detected} (detected)", CFE2D, None))
    _PROBE["variants"], _PROBE["reason"] = variants, reason
    return variants, reason


def reference_and_debug():
    variants, reason = probe()
    if reason:
        return Variant("default BLAS", CFE2D, None), Variant("debug build", DEBUG, None)
    return variants[0], Variant(f"debug build, {REFERENCE_CORE}", DEBUG, REFERENCE_CORE)


# -------------------------------------------------------------------- decks

def from_text(text, job):
    """A deck made by a test module's generator: text() written as job.inp."""
    def build(d):
        path = os.path.join(d, job + ".inp")
        with open(path, "w") as f:
            f.write(text())
        return path
    return build


def copy_of(relpath):
    def build(d):
        path = os.path.join(d, os.path.basename(relpath))
        shutil.copy(os.path.join(ROOT, relpath), path)
        return path
    return build


def needs_gmsh():
    if shutil.which("gmsh") is None:
        raise Skip("gmsh is not installed")


def meshed_example(base, order):
    """input/examples/<base>.inp with its mesh made by gmsh from <base>.geo
    (as tests/test_settle_decks.py meshes it)."""
    def build(d):
        needs_gmsh()
        import test_settle_decks
        test_settle_decks.mesh(os.path.join(ROOT, "input", "examples", base + ".geo"), d, order)
        path = os.path.join(d, base + ".inp")
        shutil.copy(os.path.join(ROOT, "input", "examples", base + ".inp"), path)
        return path
    return build


def hertz_point(order, h):
    def build(d):
        needs_gmsh()
        import run_hertz_point
        return run_hertz_point.write_case(d, order=order, h=h)
    return build


def hertz_coarse(d):
    needs_gmsh()
    import run_hertz
    return run_hertz.write_case(d, mesh="coarse")


def nafems(g0, edit=None):
    def build(d):
        needs_gmsh()
        import test_decks_nafems
        test_decks_nafems.mesh(d, g0)
        with open(os.path.join(ROOT, "input", "nafems", "nafems1.inp")) as f:
            deck = f.read()
        path = os.path.join(d, "nafems1.inp")
        with open(path, "w") as f:
            f.write(edit(deck) if edit else deck)
        return path
    return build


def contact_path(path):
    """CONTACT SOLVE=FULL or CONDENSED on a deck (test_condensed)."""
    def edit(deck):
        import test_condensed
        return test_condensed.with_path(deck, path)
    return edit


def blocks(kind):
    """The two blocks of tests/test_contact.py (10 slave over 5 master
    elements, gap 0.01, or 7 over 5 for the two-pass pair)."""
    def text():
        import test_condensed as tcd
        import test_contact as tc
        d = 3 * tc.G0
        if kind == "unload":
            back = tc.push_step(d, 2).replace(f"TOP, 2, 2, {-d}", "TOP, 2, 2, 0.0")
            return tc.blocks_deck([tc.push_step(d, 2), back])
        if kind == "unload_full":
            back = tc.push_step(d, 2).replace(f"TOP, 2, 2, {-d}", "TOP, 2, 2, 0.0")
            return tcd.with_path(tc.blocks_deck([tc.push_step(d, 2), back]), "FULL")
        if kind == "force_driven":
            return tc.force_driven_deck()[0]
        if kind == "force_driven_umfpack":
            return tc.force_driven_deck(solver="UMFPACK")[0]
        if kind == "update_search":
            return tc.blocks_deck([tc.push_step(d, 2)], ", UPDATE SEARCH")
        if kind == "unsettled":
            return tc.blocks_deck([tc.push_step(0.5 * tc.G0), tc.push_step(d)]).replace(
                "*CONTACT PAIR", "*CONTACT CONTROLS, MAXIT=1, CUTBACKS=2\n*CONTACT PAIR")
        if kind == "symmetric":
            saved, tc.NX2 = tc.NX2, 7
            try:
                return dict(tcd.seven_over_five_cases())["symmetric"]
            finally:
                tc.NX2 = saved
        raise ValueError(kind)
    return text


def quadratic(kind):
    def text():
        import test_contact_quadratic as tq
        if kind == "patch":
            return tq.two_blocks("Q8", "Q8", 5, 7)
        if kind == "symmetric":
            return tq.two_blocks("Q8", "Q8", 5, 5, pair=", SYMMETRIC")
        if kind == "shrink_pe":
            return tq.shrink_deck("Q8", "Q8", "E", n_inner=20, n_outer=14)[2]
        raise ValueError(kind)
    return text


def calculix_adjust():
    """The two blocks with CalculiX cards, ADJUST=0.02 closing the gap
    before the analysis (tests/test_decks_contact.py)."""
    import test_decks_contact as tdc
    return tdc.blocks(tdc.interaction("HARD", "") +
                      "*CONTACT PAIR, INTERACTION=SI1, SMALL SLIDING, ADJUST=0.02\nSLAVE, MASTER\n")


def equation_contact(path):
    def text():
        import test_condensed
        import test_equation
        return test_condensed.with_path(test_equation.contact_deck(), path)
    return text


def plastic_cylinder():
    """The plane-strain perfectly plastic cylinder of
    tests/test_nonlinear_closed_forms.py pressed to 0.9 of its collapse
    pressure: automatic increments whose sizes follow the Newton
    iteration counts."""
    import math
    import test_nonlinear_closed_forms as tn
    pc = 2.0 / math.sqrt(3.0) * 200.0 * math.log(2.0)
    m = tn.annulus(1.0, 2.0, 8, 4, shape="Q8")
    return tn.cylinder_deck(m, "CPE8R", "*ELASTIC\n200000., 0.3\n*PLASTIC\n200., 0.\n", 0.9 * pc,
                            "*STATIC\n0.1, 1.\n")


def plastic_nlgeom():
    """The perfectly plastic cylinder under NLGEOM on a mesh of 2160 CPE8R
    (more than one block of the element loops, assembly.f90's
    block_size): the nonlinear tangents, forces and stresses with
    plasticity and large deformation."""
    import math
    import test_nonlinear_closed_forms as tn
    pc = 2.0 / math.sqrt(3.0) * 200.0 * math.log(2.0)
    m = tn.annulus(1.0, 2.0, 24, 90, shape="Q8")
    return tn.cylinder_deck(m, "CPE8R", "*ELASTIC\n200000., 0.3\n*PLASTIC\n200., 0.\n", 0.9 * pc,
                            "*STATIC\n0.1, 1.\n", extra=", NLGEOM")


def hertz_friction(d):
    """The flagship's coarse mesh (8 933 elements) pressed, then pushed
    sideways until it slides with mu = 0.3 (make bench's friction
    history, scripts/bench.py)."""
    needs_gmsh()
    import bench
    import run_hertz
    with open(run_hertz.write_case(d, mesh="coarse")) as f:
        text = f.read()
    model = text[:text.index("*STEP")]
    model = re.sub(r"\*AMPLITUDE.*\n.*\n", "", model).replace("CYL_TOP, 1, 1\n", "")
    pair = "*CONTACT PAIR, SEARCH DISTANCE=1.0"
    assert pair + "\n" in model
    path = os.path.join(d, "push_friction.inp")
    with open(path, "w") as f:
        f.write(model.replace(pair, pair + ", FRICTION=0.3") + bench.FRICTION_STEPS)
    return path


# name, what it covers, builder(dir) -> deck path
DECKS = [
    ("hertz_point_cax4", "sphere on a flat, CAX4, h = 0.03 (tests/test_hertz_point.py): axisymmetric "
     "segment-to-segment (the default), initial gap, loading and unloading", hertz_point(1, 0.03)),
    ("hertz_point_cax8", "sphere on a flat, CAX8, h = 0.08: axisymmetric quadratic faces, segment-to-segment",
     hertz_point(2, 0.08)),
    ("hertz_coarse", "the flagship on its coarse mesh: plane stress line contact, gap, loading and unloading",
     hertz_coarse),
    ("nafems1", "NAFEMS benchmark 1: force-driven, CalculiX contact cards, plane strain", nafems(0.0)),
    ("nafems1_gap", "NAFEMS 1 starting 0.1 mm apart: held only by (stabilised) contact", nafems(0.1)),
    ("nafems1_full", "NAFEMS 1 with CONTACT SOLVE=FULL", nafems(0.0, contact_path("FULL"))),
    ("shrink_fit", "input/examples/shrink_fit.inp: thermal shrink fit, CAX8 quadratic faces",
     copy_of("input/examples/shrink_fit.inp")),
    ("shrink_pe_20_14", "plane-strain shrink fit, CPE8 curved faces 20 over 14 (tests/test_contact_quadratic.py)",
     from_text(quadratic("shrink_pe"), "shrink_pe_20_14")),
    ("blocks_example", "input/examples/blocks.inp: two blocks pressed and released, two steps",
     copy_of("input/examples/blocks.inp")),
    ("blocks_unload", "two blocks (tests/test_contact.py): gap, pressed and released, condensed solve",
     from_text(blocks("unload"), "blocks_unload")),
    ("blocks_unload_full", "the same with CONTACT SOLVE=FULL", from_text(blocks("unload_full"), "blocks_unload_full")),
    ("blocks_symmetric", "two-pass (SYMMETRIC) contact, 7 over 5", from_text(blocks("symmetric"), "blocks_symmetric")),
    ("blocks_force_driven", "force-driven block held only by contact (stabilisation)",
     from_text(blocks("force_driven"), "blocks_force_driven")),
    ("blocks_force_driven_umfpack", "the same with UMFPACK (full solve)",
     from_text(blocks("force_driven_umfpack"), "blocks_force_driven_umfpack")),
    ("blocks_update_search", "UPDATE SEARCH", from_text(blocks("update_search"), "blocks_update_search")),
    ("blocks_unsettled", "MAXIT=1, CUTBACKS=2: bisections, then the run stops",
     from_text(blocks("unsettled"), "blocks_unsettled")),
    ("blocks_adjust", "CalculiX cards, HARD, ADJUST=0.02 moving the slave nodes onto the master",
     from_text(calculix_adjust, "blocks_adjust")),
    ("quadratic_patch", "CPS8 on CPS8, 7 over 5 faces: Gauss points of quadratic slave faces",
     from_text(quadratic("patch"), "quadratic_patch")),
    ("quadratic_symmetric", "CPS8 two-pass, 5 over 5", from_text(quadratic("symmetric"), "quadratic_symmetric")),
    ("equation_contact", "*EQUATION on slave and master nodes (tests/test_equation.py), condensed",
     from_text(equation_contact("CONDENSED"), "equation_contact")),
    ("equation_contact_full", "the same with CONTACT SOLVE=FULL",
     from_text(equation_contact("FULL"), "equation_contact_full")),
    ("sphere_on_block", "input/examples/sphere_on_block.inp: a sphere pushed by a pressure, held only by "
     "contact and its axis, SURFACE TO SURFACE two-pass", meshed_example("sphere_on_block", 1)),
    ("hanging_plate", "input/examples/hanging_plate.inp: a CPS8 plate hanging on three pins with clearance "
     "(stabilised search, then the nominal one; full solve)", meshed_example("hanging_plate", 2)),
    ("oring", "input/examples/oring.inp: NLGEOM neo-Hooke O-ring squeezed between plates, contact searched "
     "again every increment, Newton with automatic increments", copy_of("input/examples/oring.inp")),
    ("plastic_cylinder", "a perfectly plastic cylinder to 0.9 of collapse (no contact): Newton iteration counts "
     "and the increment sizes they set", from_text(plastic_cylinder, "plastic_cylinder")),
    ("plastic_nlgeom", "the plastic cylinder under NLGEOM, 2160 CPE8R: more than one block of element loops",
     from_text(plastic_nlgeom, "plastic_nlgeom")),
    ("hertz_friction", "the flagship's coarse mesh pressed and pushed until it slides, mu = 0.3: stick and slip",
     hertz_friction),
]

# Families not compared as numbers: the unsettled deck completes only its
# increment without contact, where the upper block moves rigidly and its
# forces and stresses (5e-8 against 10 once pressed) are the open penalty's
# alone, at the level of round-off of the displacements; its point is the
# decisions (bisections, then the stop).
LOOSE = {"blocks_unsettled": ("force", "stress")}


# --------------------------------------------------------------------- runs

class Result:
    def __init__(self, variant, proc, outdir, deck, deckdir):
        self.variant = variant
        self.outdir = outdir
        self.rc = proc.returncode
        job = os.path.splitext(os.path.basename(deck))[0]
        self.listing_path = os.path.join(outdir, job + ".out")
        self.csv_path = os.path.join(outdir, job + "_contact.csv")
        # messages with the run's own folders named alike
        self.stderr = proc.stderr.replace(outdir, "<out>").replace(deckdir, "<deck>")
        self.text = ""
        if os.path.exists(self.listing_path):
            with open(self.listing_path) as f:
                self.text = f.read()

    def blas(self):
        return next((ln for ln in self.text.splitlines() if ln.startswith("blas ")), "")


def run_variant(variant, deck, deckdir, root):
    tag = re.sub(r"[^A-Za-z0-9]+", "_", variant.label).strip("_")
    outdir = os.path.join(root, tag)
    os.makedirs(outdir)
    proc = subprocess.run([variant.exe, "-q", "-d", "16", "-o", outdir, deck], capture_output=True, text=True,
                          env=variant.env(), timeout=600)
    return Result(variant, proc, outdir, deck, deckdir)


_RUNS = {}


def runs(name):
    """{variant label: Result} of one deck under every variant available
    (two at a time)."""
    if name not in _RUNS:
        build = {n: b for n, _, b in DECKS}[name]
        root = workdir("kernels_" + name)
        deckdir = os.path.join(root, "deck")
        os.makedirs(deckdir)
        deck = build(deckdir)
        kernels, _ = probe()
        ref, debug = reference_and_debug()
        todo = [ref] + [v for v in kernels if v.label != ref.label]
        if os.path.exists(DEBUG):
            todo.append(debug)
        todo += thread_variants()
        with ThreadPoolExecutor(max_workers=max(1, min(2, os.cpu_count() or 1))) as pool:
            results = list(pool.map(lambda v: run_variant(v, deck, deckdir, root), todo))
        _RUNS[name] = {r.variant.label: r for r in results}
    return _RUNS[name]


# -------------------------------------------------------------- comparison

def decision_trace(text):
    """The listing's decisions, one string per line: everything outside the
    increments' blocks and every increment header, with the out-of-balance
    values, wall times, the deck path and the BLAS line masked."""
    out, block, inside = [], "", False
    for line in text.splitlines():
        if line.startswith("=== INCREMENT"):
            out.append(line)
            inside = True
            continue
        if line.startswith("=== END INCREMENT"):
            inside = False
            continue
        if inside or not line.strip():
            continue
        if line.startswith("--- "):
            block = line[4:].split(" step=")[0].split(" (")[0]
        if block == "TIMING":
            continue
        word = line.split()[0]
        if (block == "MODEL" and word in ("deck", "blas")) or (block == "STEP SUMMARY" and word == "wall_seconds"):
            continue
        line = OOB.sub("out-of-balance *", line)
        # UMFPACK pivots on the values: its fill may follow round-off
        out.append(UMF.sub(r"\1*", line) if line.startswith("factor UMFPACK") else line)
    return out


def summary(trace):
    incs = sum(1 for ln in trace if ln.startswith("=== INCREMENT"))
    cuts = sum(1 for ln in trace if "bisected" in ln)
    its = sum(1 for ln in trace if ln.startswith("contact iteration "))
    return incs, cuts, its


def where(trace, k):
    """The increment a trace line belongs to (iteration lines and notes
    come before their increment's header)."""
    for ln in trace[k:]:
        if ln.startswith("=== INCREMENT"):
            return "before " + ln.strip("= ").replace("INCREMENT", "increment", 1)
    return "after the last increment"


def read_csv(path):
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return list(csv.DictReader(f))


CSV_KEYS = ("step", "increment", "time", "pair", "side", "node", "state")
CSV_NUMBERS = ("x", "y", "gap", "force", "pressure")
# and those of a model with friction
CSV_FRICTION = ("shear_force", "shear", "slip", "slip_increment")


def state_difference(a_rows, b_rows):
    """First contact row of the table whose identity or state differs."""
    for k, (ra, rb) in enumerate(zip(a_rows, b_rows)):
        ka, kb = tuple(ra[c] for c in CSV_KEYS), tuple(rb[c] for c in CSV_KEYS)
        if ka != kb:
            def row(r):
                return (f"step {r['step']} increment {r['increment']} time {r['time'].strip()} {r['side']} "
                        f"node {r['node']} {r['state']}")
            return f"contact table row {k + 2}: {row(rb)} against {row(ra)}"
    if len(a_rows) != len(b_rows):
        return f"contact table: {len(a_rows)} rows against {len(b_rows)}"
    return None


def decisions(ref, other):
    """Differences of decisions (empty if none)."""
    problems = []
    if ref.rc != other.rc:
        problems.append(f"exit status {other.rc} against {ref.rc}")
    if ref.stderr != other.stderr:
        problems.append(f"messages differ: {other.stderr.strip()[:300]!r} against {ref.stderr.strip()[:300]!r}")
    ta, tb = decision_trace(ref.text), decision_trace(other.text)
    if ta != tb:
        (ia, ca, na), (ib, cb, nb) = summary(ta), summary(tb)
        k = next((k for k, (a, b) in enumerate(zip(ta, tb)) if a != b), min(len(ta), len(tb)))
        la = ta[k] if k < len(ta) else "(end of listing)"
        lb = tb[k] if k < len(tb) else "(end of listing)"
        problems.append(f"{ib} increments against {ia}, {cb} bisections against {ca}, {nb} contact iterations "
                        f"against {na}; first difference {where(tb, k)}: '{lb}' against '{la}'")
    s = state_difference(read_csv(ref.csv_path), read_csv(other.csv_path))
    if s:
        problems.append(s)
    return problems


# Each number is compared against the largest magnitude of its quantity
# over the reference run, the columns of one quantity taken together (a
# component that is zero up to round-off, as RF1 under a vertical load,
# is judged against the whole vector). Ids and counts must be equal.
FAMILY = {"U1": "displacement", "U2": "displacement", "gap": "displacement", "max_penetration": "displacement",
          "RF1": "force", "RF2": "force", "force": "force", "total_force": "force", "resultant_x": "force",
          "resultant_y": "force",
          "S11": "stress", "S22": "stress", "S33": "stress", "S12": "stress", "MISES": "stress",
          "pressure": "stress", "shear_force": "force", "shear_total": "force", "shear": "stress",
          "slip": "displacement", "slip_inc": "displacement", "slip_increment": "displacement",
          "E11": "strain", "E22": "strain", "E33": "strain", "E12": "strain",
          "x": "coordinate", "y": "coordinate", "area": "area"}


def quantities(text, csv_path):
    """[(place, family, value, unit)] of every cell of the increments'
    result blocks and of the contact table's numeric columns (unit: one
    unit of the last printed digit of the table, which has 9 significant
    digits whatever --digits says; 0 for the listing's 16), and the
    structure (block names, attributes, columns, row counts) of the result
    blocks."""
    cells, shape = [], []
    for inc in parse_listing(text).increments:
        at = f"step {inc.attrs.get('step')} increment {inc.attrs.get('increment')}"
        for b in inc.blocks:
            shape.append((at, b.name, tuple(sorted(b.attrs.items())), tuple(b.columns), len(b.rows)))
            for row in b.rows:
                for c, v in zip(b.columns, row):
                    cells.append((f"{at} {b.name} {c} (row {row[0]})", FAMILY.get(c, c), v, 0.0))
    for r in read_csv(csv_path):
        at = f"contact table step {r['step']} increment {r['increment']} {r['side']} {r['node']}"
        for c in CSV_NUMBERS + tuple(c for c in CSV_FRICTION if c in r):
            unit = 10.0 ** decimal.Decimal(r[c].strip()).as_tuple().exponent
            cells.append((f"{at} {c}", FAMILY[c], float(r[c]), unit))
    return cells, shape


def numbers(ref, other, loose=()):
    """Differences beyond round-off of the numbers (called once the
    decisions agree); the families in `loose` are not compared."""
    ca, sa = quantities(ref.text, ref.csv_path)
    cb, sb = quantities(other.text, other.csv_path)
    if sa != sb:
        k = next((k for k, (a, b) in enumerate(zip(sa, sb)) if a != b), min(len(sa), len(sb)))
        return [f"result blocks differ at block {k + 1}: {sb[k] if k < len(sb) else None} against "
                f"{sa[k] if k < len(sa) else None}"]
    scale = {}
    for _, fam, v, _ in ca:
        if isinstance(v, float):
            scale[fam] = max(scale.get(fam, 0.0), abs(v))
    worst, problems = {}, []
    for (place, fam, va, unit), (_, _, vb, _) in zip(ca, cb):
        if not (isinstance(va, float) and isinstance(vb, float)) or fam not in FAMILY.values():
            if va != vb:
                problems.append(f"{place}: {vb} against {va}")
            continue
        if fam in loose:
            continue
        excess = max(0.0, abs(va - vb) - unit)
        rel = excess / scale[fam] if scale[fam] else excess
        if rel > worst.get(fam, (-1.0,))[0]:
            worst[fam] = (rel, place, va, vb)
    for fam, (rel, place, va, vb) in sorted(worst.items()):
        if rel > RTOL[fam]:
            problems.append(f"{fam} {place}: {vb!r} against {va!r}, {rel:.1e} of the largest {fam} "
                            f"{scale[fam]:.3e} (tolerance {RTOL[fam]:g})")
    return problems, {fam: w[0] for fam, w in worst.items()}


def compare_runs(name, ref, others):
    """Every run of `others` against `ref`; raises with one line per run
    that differs."""
    failures, worst = {}, {}     # what differs -> the runs it differs in
    for o in others:
        want = o.variant.core
        if want and not names_core(o.blas(), want):
            failures.setdefault(f"the listing does not name kernel {want}: '{o.blas()}'", []).append(o)
            continue
        problems = decisions(ref, o)
        if problems:
            failures.setdefault("contact decisions differ: " + "; ".join(problems[:3]), []).append(o)
            continue
        problems, w = numbers(ref, o, LOOSE.get(name, ()))
        for fam, rel in w.items():
            worst[fam] = max(worst.get(fam, 0.0), rel)
        if problems:
            failures.setdefault("numbers beyond round-off: " + "; ".join(problems[:3]), []).append(o)
    print(f"  {name}: {', '.join(o.variant.label for o in others)} against {ref.variant.label}" +
          ("; largest differences: " + ", ".join(f"{fam} {rel:.0e}" for fam, rel in sorted(worst.items()))
           if worst else ""))
    if failures:
        raise AssertionError(f"{name}: " + " | ".join(
            f"{', '.join(o.variant.label for o in runs_)} against {ref.variant.label}: {what}"
            for what, runs_ in failures.items()))


def check_kernels(name):
    kernels, reason = probe()
    if reason:
        raise Skip(reason)
    rs = runs(name)
    ref = rs[kernels[0].label]
    if ref.variant.core and not names_core(ref.blas(), ref.variant.core):
        raise AssertionError(f"{name}: the listing does not name kernel {ref.variant.core}: '{ref.blas()}'")
    if len(kernels) < 2:
        raise Skip(f"this CPU runs only the {REFERENCE_CORE} kernel (no avx2 in /proc/cpuinfo): nothing to compare")
    compare_runs(name, ref, [rs[v.label] for v in kernels[1:]])


def check_debug(name):
    if not os.path.exists(DEBUG):
        raise Skip("build-debug/cfe2d not built (make debug; make check builds it)")
    ref, debug = reference_and_debug()
    rs = runs(name)
    compare_runs(name, rs[ref.label], [rs[debug.label]])


def test_coretype_selects_the_kernel():
    """OPENBLAS_CORETYPE changes the kernel the listing names (each kernel
    of the comparison), or the kernel tests say why they cannot run."""
    kernels, reason = probe()
    if reason:
        raise Skip(reason)
    d = workdir("kernels_coretype")
    deck = os.path.join(ROOT, "input", "examples", "blocks.inp")
    seen = []
    for v in kernels:
        out = os.path.join(d, re.sub(r"[^A-Za-z0-9]+", "_", v.label))
        os.makedirs(out)
        r = subprocess.run([v.exe, "-q", "-o", out, deck], capture_output=True, text=True, env=v.env(), timeout=120)
        assert r.returncode == 0, r.stderr
        line = blas_line(os.path.join(out, "blocks.out"))
        if v.core:
            assert names_core(line, v.core), f"OPENBLAS_CORETYPE={v.core}: the listing says '{line}'"
        seen.append(core_name(line))
    assert len(set(seen)) == len(seen), f"kernels {seen}: OPENBLAS_CORETYPE did not give distinct kernels"
    print(f"  kernels compared: {', '.join(seen)} (reference {REFERENCE_CORE})")


def masked_listing(text):
    """The listing with what may differ between thread counts masked: the
    wall times (step summaries' wall_seconds, the TIMING block's seconds)
    and the blas line (which names the element team)."""
    out, timing = [], False
    for line in text.splitlines():
        word = line.split()[0] if line.split() else ""
        if line.startswith("--- "):
            timing = line.startswith("--- TIMING")
        if word == "blas" or word == "wall_seconds" or (timing and "." in line and word != "item"):
            line = word + " <masked>"
        out.append(line)
    return out


# a .frd's header records of the run's date and time (1UDATE, 1UTIME)
FRD_CLOCK = re.compile(rb"(?m)^    1U(?:DATE|TIME) .*$")


def bit_difference(ref, other):
    """The first difference between two runs that must give the same bits,
    or None: exit status, messages, the files written and each one byte
    for byte (the listing through masked_listing, a .frd without the
    date and time of its run)."""
    if ref.rc != other.rc:
        return f"exit status {other.rc} against {ref.rc}"
    if ref.stderr != other.stderr:
        return f"messages differ: {other.stderr.strip()[:300]!r} against {ref.stderr.strip()[:300]!r}"
    fa, fb = sorted(os.listdir(ref.outdir)), sorted(os.listdir(other.outdir))
    if fa != fb:
        return f"files {fb} against {fa}"
    for name in fa:
        with open(os.path.join(ref.outdir, name), "rb") as f:
            a = f.read()
        with open(os.path.join(other.outdir, name), "rb") as f:
            b = f.read()
        if name == os.path.basename(ref.listing_path):
            la, lb = masked_listing(a.decode()), masked_listing(b.decode())
            if la != lb:
                k = next((k for k, (x, y) in enumerate(zip(la, lb)) if x != y), min(len(la), len(lb)))
                return (f"{name} line {k + 1}: {lb[k] if k < len(lb) else '(end)'!r} against "
                        f"{la[k] if k < len(la) else '(end)'!r}")
        elif name.endswith(".frd") and FRD_CLOCK.sub(b"", a) == FRD_CLOCK.sub(b"", b):
            continue
        elif a != b:
            k = next((k for k, (x, y) in enumerate(zip(a, b)) if x != y), min(len(a), len(b)))
            line = a[:k].count(b"\n") + 1
            return f"{name} differs from byte {k} (line {line})"
    return None


def check_threads(name):
    """The deck on 1, 2 and 3 element threads: the same bits."""
    ref, _ = reference_and_debug()
    rs = runs(name)
    base = rs[ref.label]
    failures = []
    for v in thread_variants():
        run = rs[v.label]
        if v.threads > 1 and not re.search(rf"element loops on {v.threads} threads$", run.blas()):
            failures.append(f"{v.label}: the listing's blas line does not name the team: '{run.blas()}'")
            continue
        diff = bit_difference(base, run)
        if diff:
            failures.append(f"{v.label} against {ref.label} ({threads_label(inherited_threads())}): {diff}")
    print(f"  {name}: {', '.join(v.label for v in thread_variants())} against {ref.label} "
          f"({threads_label(inherited_threads())}): " + ("differ" if failures else "the same bits"))
    if failures:
        raise AssertionError(f"{name}: " + " | ".join(failures))


def cases():
    for name, _, _ in DECKS:
        yield f"kernels {name}", (lambda n=name: check_kernels(n))
        yield f"debug build {name}", (lambda n=name: check_debug(n))
        yield f"threads {name}", (lambda n=name: check_threads(n))
