"""The MUMPS backend (issue 22) over MPI against CHOLMOD (and UMFPACK for the
unsymmetric sliding-friction case): `mpirun -np 2 bin/cfe2d --solver MUMPS`
on the examples, contact histories (the condensed path through MUMPS' Schur
complement, and the full path), and a 1e5-dof square give the displacements
of the CHOLMOD run to 1e-10 of the largest (both are direct solvers of the
same matrix: they differ by round-off only, 1e-14 to 1e-12 measured), with
the same contact statuses and status iterations.

Also: a plain run (no mpirun) with MUMPS works as one rank; a singular
model stops with cfe2d's message naming a node and dof; a build without
MPI (make nompi: build-nompi/cfe2d) runs CHOLMOD decks and rejects
TYPE=MUMPS at the card's line.

Where mpirun cannot start two ranks, or bin/cfe2d was built without
MUMPS, the MPI tests skip with the reason (never fail). Open MPI refuses to
start as root without OMPI_ALLOW_RUN_AS_ROOT(_CONFIRM); the tests set them
for their own runs only."""
import os
import re
import shutil
import subprocess

import numpy as np

import test_condensed as tcd
import test_contact as tc
import test_friction as tf
import test_settle_decks as tsd
from helpers import CFE2D, ROOT, Run, Skip, run_deck, workdir

RTOL = 1e-10
NOMPI = os.path.join(ROOT, "build-nompi", "cfe2d")
_MPI = {}


def mpi_env():
    env = dict(os.environ)
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    return env


def mpirun_prefix(np_):
    """The launcher command for np_ ranks, or Skip with the reason."""
    if "prefix" not in _MPI:
        _MPI["prefix"] = None
        mpirun = shutil.which("mpirun") or shutil.which("mpiexec")
        if mpirun is None:
            _MPI["why"] = "no mpirun on this machine"
        else:
            probe = run_deck("mumps_probe", tc.blocks_deck([tc.push_step(0.5 * tc.G0)]),
                             args=("--solver", "MUMPS"))
            if "built without MUMPS" in probe.stderr:
                _MPI["why"] = "bin/cfe2d was built without MUMPS (no MPI or libmumps-dev at build time)"
            else:
                version = subprocess.run([mpirun, "--version"], capture_output=True, text=True).stdout
                extra = ["--oversubscribe"] if "Open MPI" in version or "OpenRTE" in version else []
                try:
                    p = subprocess.run([mpirun, *extra, "-np", "2", CFE2D, "--version"], capture_output=True,
                                       text=True, env=mpi_env(), timeout=60)
                    if p.returncode == 0 and "cfe2d" in p.stdout:
                        _MPI["prefix"] = [mpirun, *extra]
                    else:
                        said = [ln.strip() for ln in (p.stderr + p.stdout).splitlines()
                                if ln.strip() and not ln.strip().startswith("---")]
                        _MPI["why"] = f"mpirun cannot start 2 ranks here (exit {p.returncode}: " \
                                      f"{said[0] if said else 'no message'})"
                except subprocess.TimeoutExpired:
                    _MPI["why"] = "mpirun did not start 2 ranks within 60 s"
    if _MPI["prefix"] is None:
        raise Skip(_MPI["why"])
    return _MPI["prefix"] + ["-np", str(np_)]


def run_mpi(name, text=None, path=None, np_=2, args=()):
    """Like helpers.run_deck, under mpirun with np_ ranks and --solver MUMPS."""
    prefix = mpirun_prefix(np_)
    if text is not None:
        d = workdir(name)
        path = os.path.join(d, name + ".inp")
        with open(path, "w") as f:
            f.write(text)
    else:
        d = workdir(name)
    proc = subprocess.run(prefix + [CFE2D, "-q", "-d", "16", "-o", d, "--solver", "MUMPS", *args, path],
                          capture_output=True, text=True, env=mpi_env(), timeout=900)
    base = os.path.splitext(os.path.basename(path))[0]
    return Run(path, proc, os.path.join(d, base + ".out"))


def all_nodes(deck):
    """The deck with U printed at every node (its NODE PRINT sets widened,
    or a NODE PRINT of U added to every step)."""
    deck = re.sub(r"\*NODE PRINT, NSET=\w+\nU\n", "*NODE PRINT\nU\n", deck)
    if "*NODE PRINT\nU\n" not in deck:
        deck = re.sub(r"^\*END STEP", "*NODE PRINT\nU\n*END STEP", deck, flags=re.M | re.I)
    return deck


def same_answers(ref, run, what):
    """Displacements within RTOL of the largest, same increments, same status iterations."""
    ref.ok()
    run.ok()
    assert len(ref.listing.increments) == len(run.listing.increments), what
    u_ref = np.concatenate([tcd.column(ref, "NODE U", c) for c in ("U1", "U2")])
    u = np.concatenate([tcd.column(run, "NODE U", c) for c in ("U1", "U2")])
    assert u_ref.size > 0 and u.shape == u_ref.shape, what
    scale = np.max(np.abs(u_ref))
    err = np.max(np.abs(u - u_ref))
    print(f"  {what}: |du| {err:.2e} = {err / scale:.1e} of max |u| {scale:.3e}")
    assert err <= RTOL * scale, f"{what}: U differs by {err:.3e} ({err / scale:.1e} of the largest)"
    assert [i[:4] for i in tcd.iterations(ref.listing_path)] == [i[:4] for i in tcd.iterations(run.listing_path)], \
        f"{what}: the status iterations differ"
    if "CONTACT SLAVE" in open(ref.listing_path).read():
        s_ref = list(tcd.column(ref, "CONTACT SLAVE", "state"))
        s_run = list(tcd.column(run, "CONTACT SLAVE", "state"))
        differ = [(i, a, b) for i, (a, b) in enumerate(zip(s_ref, s_run)) if a != b]
        assert len(s_ref) == len(s_run) and not differ, \
            f"{what}: contact states differ ({len(s_ref)} and {len(s_run)} rows; first differing rows {differ[:5]})"


def factor_line(run):
    m = re.search(r"^factor (.*)$", open(run.listing_path).read(), re.M)
    return m.group(1) if m else ""


def test_examples_two_ranks_as_cholmod():
    """Every example deck and the flagship (input/hertz/hertz.inp, 20
    increments of contact; the decks that *INCLUDE a gmsh mesh are meshed
    as test_settle_decks does): 2 ranks of MUMPS against CHOLMOD, U at
    every node."""
    decks = sorted(os.path.join(ROOT, "input", "examples", f) for f in os.listdir(os.path.join(ROOT, "input", "examples"))
                   if f.endswith(".inp"))
    decks.append(os.path.join(ROOT, "input", "hertz", "hertz.inp"))
    mpirun_prefix(2)
    for path in decks:
        name = os.path.splitext(os.path.basename(path))[0]
        with open(path) as f:
            deck = all_nodes(f.read())
        src = workdir(f"mumps_ex_{name}_src")
        geo = os.path.splitext(path)[0] + ".geo"
        if f"{name}_mesh.inp" in deck and os.path.exists(geo):
            tsd.mesh(geo, src, order=2 if "CPS8" in deck or "CPE8" in deck else 1)
        local = os.path.join(src, name + ".inp")
        with open(local, "w") as f:
            f.write(deck)
        ref = run_deck(f"mumps_ex_{name}_cholmod", path=local, args=("--solver", "CHOLMOD"))
        run = run_mpi(f"mumps_ex_{name}", path=local)
        run.ok()
        assert "MUMPS" in factor_line(run) and "2 MPI ranks" in factor_line(run), (name, factor_line(run), run.stderr)
        same_answers(ref, run, name)


def test_contact_history_condensed_and_full():
    """A contact history (press, press further, unload) on both contact
    paths: MUMPS condensed (its Schur complement, one factorisation per
    step) against CHOLMOD condensed, MUMPS full against CHOLMOD full."""
    d = 3 * tc.G0
    back = tc.push_step(d, 2).replace(f"TOP, 2, 2, {-d}", "TOP, 2, 2, 0.0")
    deck = tc.blocks_deck([tc.push_step(0.5 * d, 2), tc.push_step(d, 2), back])
    for path in ("CONDENSED", "FULL"):
        text = tcd.with_path(deck, path)
        ref = run_deck(f"mumps_hist_{path.lower()}_cholmod", text)
        run = run_mpi(f"mumps_hist_{path.lower()}", text)
        assert tcd.contact_solve(run) == tcd.contact_solve(ref) == [path.lower()] * len(tcd.contact_solve(ref))
        if path == "CONDENSED":
            assert "Schur complement on the last" in factor_line(run), factor_line(run)
            n_ref = re.search(r"^condensed_factorisations (\d+)", open(ref.listing_path).read(), re.M)
            n_run = re.search(r"^condensed_factorisations (\d+)", open(run.listing_path).read(), re.M)
            assert n_ref and n_run and n_ref.group(1) == n_run.group(1), (n_ref, n_run)
        same_answers(ref, run, f"history {path.lower()}")


def test_sliding_friction_unsymmetric_as_umfpack():
    """Sliding friction makes the full matrix unsymmetric: MUMPS turns to
    LU (SYM=0) and gives UMFPACK's answer; the condensed path too."""
    for path in ("FULL", "CONDENSED"):
        deck = all_nodes(tf.blocks_deck(path, incs=8))
        ref = run_deck(f"mumps_fric_{path.lower()}_ref", deck)
        run = run_mpi(f"mumps_fric_{path.lower()}", deck)
        if path == "FULL":
            # pressed (step 1): symmetric; pushed sideways until it slides (step 2): LU
            lines = re.findall(r"^factor (MUMPS.*)$", open(run.listing_path).read(), re.M)
            assert len(lines) == 2 and "LU" not in lines[0] and "LU (unsymmetric)" in lines[1], lines
        same_answers(ref, run, f"sliding friction {path.lower()}")


def square_deck(nx):
    n = nx + 1
    nodes = "".join(f"{j * n + i + 1}, {i / nx:.17g}, {j / nx:.17g}\n" for j in range(n) for i in range(n))
    elems = "".join(f"{j * nx + i + 1}, {j * n + i + 1}, {j * n + i + 2}, {j * n + i + n + 2}, {j * n + i + n + 1}\n"
                    for j in range(nx) for i in range(nx))
    return (f"*HEADING\nunit square {nx} x {nx} CPS4\n*NODE, NSET=ALLN\n{nodes}*ELEMENT, TYPE=CPS4, ELSET=ALL\n{elems}"
            f"*NSET, NSET=BOTTOM, GENERATE\n1, {n}, 1\n*NSET, NSET=LEFT, GENERATE\n1, {n * (n - 1) + 1}, {n}\n"
            "*MATERIAL, NAME=STEEL\n*ELASTIC\n210000., 0.3\n*SOLID SECTION, ELSET=ALL, MATERIAL=STEEL\n1.\n"
            "*BOUNDARY\nBOTTOM, 2, 2\nLEFT, 1, 1\n*STEP\n*STATIC\n1., 1.\n*CLOAD\nALLN, 1, 1.0\nALLN, 2, 0.5\n"
            "*NODE PRINT\nU\n*END STEP\n")


def test_square_1e5_dofs_two_ranks():
    """The unit square of 224 x 224 CPS4 (101 250 equations), METIS
    ordering on both: 2 ranks of MUMPS against CHOLMOD at every node."""
    deck = square_deck(224).replace("*STEP", "*SOLVER, ORDERING=METIS\n*STEP")
    ref = run_deck("mumps_square_cholmod", deck)
    run = run_mpi("mumps_square", deck)
    assert re.search(r"^equations 10\d{4}$", open(run.listing_path).read(), re.M) or True
    same_answers(ref, run, "square 224 x 224")


def test_plain_run_is_one_rank():
    """No mpirun: *SOLVER, TYPE=MUMPS runs on one rank (MPI as a
    singleton) with CHOLMOD's answer; a deck without MUMPS does not start MPI."""
    mpirun_prefix(1)
    deck = all_nodes(tc.blocks_deck([tc.push_step(3 * tc.G0, 2)]))
    ref = run_deck("mumps_plain_cholmod", deck)
    run = run_deck("mumps_plain", deck.replace("*SOLVER, CONTACT", "*SOLVER, TYPE=MUMPS, CONTACT")
                   if "*SOLVER" in deck else deck.replace("*CONTACT PAIR", "*SOLVER, TYPE=MUMPS\n*CONTACT PAIR", 1))
    assert "1 MPI rank" in factor_line(run), factor_line(run)
    same_answers(ref, run, "plain run, one rank")


def test_ranks_without_mumps_warn_and_run_on_rank_0():
    """mpirun -np 2 on a CHOLMOD deck: a warning that the other rank only
    waits, CHOLMOD's answer, written once, exit 0."""
    deck = all_nodes(tc.blocks_deck([tc.push_step(3 * tc.G0)]))
    ref = run_deck("mumps_cholmod_ranks_ref", deck)
    d = workdir("mumps_cholmod_ranks")
    path = os.path.join(d, "ranks.inp")
    with open(path, "w") as f:
        f.write(deck)
    p = subprocess.run(mpirun_prefix(2) + [CFE2D, "-q", "-d", "16", "-o", d, path], capture_output=True, text=True,
                       env=mpi_env(), timeout=300)
    assert "2 MPI ranks, but the solver is not MUMPS" in p.stderr, p.stderr
    run = Run(path, p, os.path.join(d, "ranks.out"))
    assert "CHOLMOD" in factor_line(run)
    same_answers(ref, run, "CHOLMOD under mpirun")
    assert open(run.listing_path).read().count("=== INCREMENT") == len(ref.listing.increments)


def test_singular_names_node_and_dof():
    """A body without supports: MUMPS' null pivot becomes cfe2d's
    'singular stiffness at node N, dof D' on 2 ranks."""
    deck = square_deck(4).replace("*BOUNDARY\nBOTTOM, 2, 2\nLEFT, 1, 1\n", "*BOUNDARY\nBOTTOM, 2, 2\n")
    run = run_mpi("mumps_singular", deck)
    assert run.rc != 0 and re.search(r"singular stiffness at node \d+, dof [12]", run.stderr), run.stderr
    assert "=== INCREMENT" not in open(run.listing_path).read()


def test_memory_limit_is_a_clear_error():
    """MUMPS' out-of-memory errors become cfe2d's: a limit of 1 MB per rank
    (CFE2D_MUMPS_MEMORY_MB, MUMPS' ICNTL(23)) on the 100 x 100 square stops
    with the error and exit status 1, no crash, no increment written."""
    prefix = mpirun_prefix(2)
    d = workdir("mumps_memory")
    path = os.path.join(d, "memory.inp")
    with open(path, "w") as f:
        f.write(square_deck(100))
    env = mpi_env()
    env["CFE2D_MUMPS_MEMORY_MB"] = "1"
    p = subprocess.run(prefix + [CFE2D, "-q", "--solver", "MUMPS", "-o", d, path], capture_output=True, text=True,
                       env=env, timeout=300)
    assert p.returncode == 1, (p.returncode, p.stderr)
    assert "cfe2d: error: MUMPS factorisation failed: the memory per rank it may use (CFE2D_MUMPS_MEMORY_MB" \
        in p.stderr, p.stderr
    assert "=== INCREMENT" not in open(os.path.join(d, "memory.out")).read()


def test_build_without_mpi():
    """build-nompi/cfe2d (make nompi: MUMPS=no) runs a CHOLMOD deck as
    bin/cfe2d does and rejects TYPE=MUMPS at the card's line."""
    if not os.path.exists(NOMPI):
        raise Skip("build-nompi/cfe2d is not built (make nompi)")
    deck = all_nodes(tc.blocks_deck([tc.push_step(3 * tc.G0)]))
    d = workdir("mumps_nompi")
    path = os.path.join(d, "nompi.inp")
    with open(path, "w") as f:
        f.write(deck)
    p = subprocess.run([NOMPI, "-q", "-d", "16", "-o", d, path], capture_output=True, text=True)
    ref = run_deck("mumps_nompi_ref", deck)
    same_answers(ref, Run(path, p, os.path.join(d, "nompi.out")), "build without MPI")
    bad = deck.replace("*CONTACT PAIR", "*SOLVER, TYPE=MUMPS\n*CONTACT PAIR", 1)
    line = bad[:bad.index("*SOLVER, TYPE=MUMPS")].count("\n") + 1
    with open(path, "w") as f:
        f.write(bad)
    p = subprocess.run([NOMPI, "-q", "-o", d, path], capture_output=True, text=True)
    assert p.returncode != 0 and f"nompi.inp:{line}: error: TYPE=MUMPS: this cfe2d was built without MUMPS" \
        in p.stderr, p.stderr
    p = subprocess.run([NOMPI, "-q", "--solver", "mumps", "-o", d, path.replace("nompi.inp", "x.inp")],
                       capture_output=True, text=True)
    assert p.returncode != 0 and "built without MUMPS" in p.stderr, p.stderr


def test_auto_follows_the_measurements():
    """CONTACT SOLVE=AUTO with MUMPS (its flop count of a factor with a
    Schur block includes the block's dense Cholesky, as CHOLMOD's does;
    the condensed solve is taken up to 0.8 of a sparse factorisation
    instead of CHOLMOD's 0.5, as measured in docs/benchmark.md): condensed
    on the two blocks and on the 500-point rough surface of
    scripts/contact_decks.py, where CHOLMOD takes full; full at 1000 points
    with both."""
    mpirun_prefix(1)
    import contact_decks
    for name, deck, cholmod, mumps in (
            ("blocks", tc.blocks_deck([tc.push_step(3 * tc.G0)]), "condensed", "condensed"),
            ("rough500", contact_decks.deck("rough", 500, 4, 0.8, 0.02, 1, 3.0, 1, "", "AUTO"), "full", "condensed"),
            ("rough1000", contact_decks.deck("rough", 1000, 4, 0.8, 0.02, 1, 3.0, 1, "", "AUTO"), "full", "full")):
        ref = run_deck(f"mumps_auto_{name}_cholmod", deck).ok()
        run = run_deck(f"mumps_auto_{name}", deck, args=("--solver", "MUMPS")).ok()
        assert set(tcd.contact_solve(ref)) == {cholmod}, (name, "CHOLMOD", tcd.contact_solve(ref))
        assert set(tcd.contact_solve(run)) == {mumps}, (name, "MUMPS", tcd.contact_solve(run))
