"""The three solvers (skyline, CHOLMOD with AMD and METIS, UMFPACK) give the
same displacements to 1e-10 (relative to the largest) on the foundation's
problems and on a contact problem of Hertz size; each reports a singular
stiffness clearly, naming a node and dof, and takes a model with no free
dof."""
import os
import re

import numpy as np

from decks import grid, node_lines, quad_lines
from helpers import ROOT, WORK, run_deck
from test_bad_decks import GOOD, replace

SOLVERS = ["TYPE=SKYLINE", "TYPE=CHOLMOD, ORDERING=AMD", "TYPE=CHOLMOD, ORDERING=METIS", "TYPE=UMFPACK"]
ALL_SOLVERS = SOLVERS + ["TYPE=UMFPACK, ORDERING=METIS"]


def with_solver(deck, solver):
    """The deck with a *SOLVER line before its first *STEP."""
    return re.sub(r"^\*STEP", f"*SOLVER, {solver}\n*STEP", deck, count=1, flags=re.M)


def displacements(run):
    out = []
    for inc in run.listing.increments:
        for b in inc.blocks:
            if b.name == "NODE U":
                out += [b["U1"], b["U2"]]
    return np.concatenate(out)


def agree(name, deck, files=None):
    ref = None
    for solver in SOLVERS:
        run = run_deck(f"solvers_{name}", with_solver(deck, solver), files=files).ok()
        u = displacements(run)
        assert len(u) > 0
        if ref is None:
            ref = u
            continue
        err = np.max(np.abs(u - ref)) / np.max(np.abs(ref))
        assert err < 1e-10, f"{solver}: {err:.2e} from the skyline"


def test_solvers_agree_cantilever():
    with open(os.path.join(ROOT, "input", "examples", "cantilever.inp")) as f:
        agree("cantilever", f.read().replace("*NODE PRINT, NSET=TIP", "*NODE PRINT"))


def test_solvers_agree_contact_blocks():
    with open(os.path.join(ROOT, "input", "examples", "blocks.inp")) as f:
        agree("blocks", f.read().replace("*NODE PRINT, NSET=TOP", "*NODE PRINT"))


def test_solvers_agree_hertz_contact():
    """The Hertz deck on a coarse mesh (h = 0.2 mm, about 6500 equations),
    all 20 increments, displacements of every node."""
    import subprocess
    d = os.path.join(WORK, "solvers_hertz_mesh")
    os.makedirs(d, exist_ok=True)
    mesh = os.path.join(d, "hertz_mesh.inp")
    subprocess.run(["gmsh", "-2", "-format", "inp", "-setnumber", "Mesh.SaveGroupsOfNodes", "1", "-setnumber",
                    "h", "0.2", "-o", mesh, os.path.join(ROOT, "input", "hertz", "hertz.geo")], check=True,
                   capture_output=True)
    with open(os.path.join(ROOT, "input", "hertz", "hertz.inp")) as f:
        deck = f.read().replace("*NODE PRINT, NSET=CYL_TOP", "*NODE PRINT").replace("*NODE FILE\nU, S, CSTRESS\n*EL FILE\nS\n", "")
    with open(mesh) as f:
        agree("hertz", deck, files={"hertz_mesh.inp": f.read()})


def test_singular_reported_by_each_solver():
    deck = replace("LEFT, 1, 2", "LEFT, 1, 1", GOOD)
    for solver in SOLVERS:
        run = run_deck("solvers_singular", with_solver(deck, solver))
        assert run.rc != 0, solver
        assert "singular stiffness at node" in run.stderr and "missing boundary condition" in run.stderr, \
            (solver, run.stderr)
        assert "NaN" not in open(run.listing_path).read()


def test_solver_named_in_listing():
    run = run_deck("solvers_listing", with_solver(GOOD, "TYPE=CHOLMOD, ORDERING=METIS")).ok()
    text = open(run.listing_path).read()
    assert "solver CHOLMOD" in text and "ordering METIS" in text and "blas OpenBLAS" in text
    assert re.search(r"factor CHOLMOD, ordering METIS, factor entries \d", text)


def cantilever_held_at_one_node(nx, ny):
    """A 10 x 1 CPS4 cantilever, end load, both dofs of one corner node
    fixed and nothing else: the rotation about that node is free."""
    nodes, ids, quads = grid(nx, ny, 0.0, 10.0, -0.5, 0.5)
    tip = ", ".join(str(ids[nx, j]) for j in range(ny + 1))
    return f"""*HEADING
cantilever {nx} x {ny} held at one node
*NODE, NSET=ALL
{node_lines(nodes)}*ELEMENT, TYPE=CPS4, ELSET=BEAM
{quad_lines(quads)}*NSET, NSET=PIN
{ids[0, 0]}
*NSET, NSET=TIP
{tip}
*MATERIAL, NAME=M
*ELASTIC
1000., 0.3
*SOLID SECTION, ELSET=BEAM, MATERIAL=M
1.
*BOUNDARY
PIN, 1, 2
*STEP
*STATIC
*CLOAD
TIP, 2, -0.2
*NODE PRINT, NSET=TIP
U
*END STEP
""", ids[0, 0], len(nodes)


def test_free_rotation_reported_by_each_solver():
    """Held at one node, the rotation is free: every solver must stop with
    a non-zero exit naming a node and dof of the free mode (any node but
    the pinned one), never print a displacement. UMFPACK used to accept the
    20 x 2 case (tip displacement -1.5e12); CHOLMOD with AMD the 160 x 32
    one (its smallest pivot 1.4e-11 of its diagonal)."""
    for nx, ny in ((20, 2), (160, 32)):
        deck, pinned, nnodes = cantilever_held_at_one_node(nx, ny)
        for solver in ALL_SOLVERS:
            run = run_deck("solvers_free_rotation", with_solver(deck, solver))
            assert run.rc != 0, (nx, ny, solver, "accepted")
            m = re.search(r"singular stiffness at node (\d+), dof (\d+)", run.stderr)
            assert m, (nx, ny, solver, run.stderr)
            node, dof = int(m.group(1)), int(m.group(2))
            assert 1 <= node <= nnodes and node != pinned and dof in (1, 2), (nx, ny, solver, run.stderr)
            text = open(run.listing_path).read()
            assert "NaN" not in text and "--- NODE U" not in text, (nx, ny, solver)


def test_no_free_dof_each_solver():
    """Every dof prescribed: a system of no equations. CHOLMOD with METIS
    used to die of SIGFPE inside METIS_NodeND; every solver must run and
    give the prescribed (zero) displacements."""
    deck = replace("LEFT, 1, 2", "ALLN, 1, 2", GOOD)
    for solver in ALL_SOLVERS:
        run = run_deck("solvers_no_free_dof", with_solver(deck, solver)).ok()
        u = displacements(run)
        assert len(u) == 12 and np.all(u == 0.0), (solver, u)


def test_thread_policy_one_blas_thread_unless_asked():
    """The solvers run the BLAS on one thread (two teams of threads spun
    against each other on small machines) unless the environment asks for
    more, and the listing says which."""
    names = ("OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "OMP_NUM_THREADS", "OMP_THREAD_LIMIT", "OMP_MAX_ACTIVE_LEVELS")
    saved = {k: os.environ.pop(k) for k in names if k in os.environ}
    try:
        run = run_deck("solvers_threads_default", with_solver(GOOD, "TYPE=CHOLMOD")).ok()
        assert re.search(r"^blas OpenBLAS .*\(1 thread\)$", open(run.listing_path).read(), re.M)
        if (os.cpu_count() or 1) >= 2:   # OpenBLAS caps its threads at the cores
            os.environ["OPENBLAS_NUM_THREADS"] = "2"
            run = run_deck("solvers_threads_asked", with_solver(GOOD, "TYPE=CHOLMOD")).ok()
            assert re.search(r"^blas OpenBLAS .*\(2 threads\)$", open(run.listing_path).read(), re.M)
    finally:
        os.environ.pop("OPENBLAS_NUM_THREADS", None)
        os.environ.update(saved)
