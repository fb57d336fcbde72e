"""The condensed contact solve against the full one: every contact deck of
test_contact.py and the Hertz case on the coarse mesh, run with
*SOLVER, CONTACT SOLVE=FULL and =CONDENSED. Displacements (every node) and
contact forces (slave and master) agree to 1e-9 of their largest value;
statuses, iteration counts and the status changes of every contact
iteration are the same; runs that stop, stop the same way; the listing
says which path ran.

One allowance, for forces only: a penalty force is k times a gap that is
a difference of displacements, so two correct solutions that differ by a
few units in the last place of the displacements (as any two solvers do)
give forces that differ by k * eps * |u|. Where a deck barely closes (a
penetration of 1e-8 of the displacements) that is more than 1e-9 of the
force itself; the floor 16 * eps * k * max|u| is allowed on top, with k
read from the listing as force / gap of the closed nodes."""
import os
import re

import numpy as np

import test_contact as tc
from helpers import WORK, Skip, run_deck

RTOL = 1e-9
ITER = re.compile(r"^contact iteration (\d+): status changes (\d+), closed (\d+), out-of-balance +(\S+)(.*)$", re.M)


def with_path(deck, path):
    """The deck with CONTACT SOLVE=path and U printed at every node."""
    if "*SOLVER" in deck:
        deck = deck.replace("*SOLVER, TYPE=", f"*SOLVER, CONTACT SOLVE={path}, TYPE=")
    else:
        deck = deck.replace("*CONTACT PAIR", f"*SOLVER, CONTACT SOLVE={path}\n*CONTACT PAIR", 1)
    return re.sub(r"\*NODE PRINT, NSET=\w+\nU\n", "*NODE PRINT\nU\n", deck)


def contact_solve(run):
    """contact_solve of every step's SOLVER block."""
    return [b.as_dict().get("contact_solve") for b in run.listing.header if b.name == "SOLVER"]


def iterations(path):
    with open(path) as f:
        return [(int(a), int(b), int(c), nodes.strip(), float(r)) for a, b, c, r, nodes in ITER.findall(f.read())]


def column(run, block, col):
    """One column of a block over every increment and pair, concatenated."""
    vals = []
    for inc in run.listing.increments:
        vals += [b[col] for b in inc.blocks if b.name == block]
    return np.concatenate(vals) if vals else np.zeros(0)


def compare(full, cond):
    """Both runs of one deck: same increments, statuses and iterations;
    displacements and contact forces within RTOL of the largest."""
    assert len(full.listing.increments) == len(cond.listing.increments)
    for a, b in zip(full.listing.increments, cond.listing.increments):
        assert a.attrs == b.attrs, (a.attrs, b.attrs)
    fa, fb = iterations(full.listing_path), iterations(cond.listing_path)
    assert [i[:4] for i in fa] == [i[:4] for i in fb], "the status iterations differ"
    # displacements: both components against the largest; forces: slave and
    # master against the largest, with the round-off floor (module doc)
    umax = np.max(np.abs(np.concatenate([column(full, "NODE U", "U1"), column(full, "NODE U", "U2")])))
    closed = np.array(column(full, "CONTACT SLAVE", "state")) == "CLOSED"
    gap, force = column(full, "CONTACT SLAVE", "gap"), column(full, "CONTACT SLAVE", "force")
    k = np.max(np.abs(force[closed] / gap[closed]), initial=0.0, where=gap[closed] != 0)
    eps = np.finfo(float).eps
    for what, cols, floor in (("U", [("NODE U", "U1"), ("NODE U", "U2")], 0.0),
                              ("contact force", [("CONTACT SLAVE", "force"), ("CONTACT MASTER", "force")],
                               16 * eps * k * umax),
                              ("gap", [("CONTACT SLAVE", "gap")], 16 * eps * umax)):
        va = np.concatenate([column(full, block, col) for block, col in cols])
        vb = np.concatenate([column(cond, block, col) for block, col in cols])
        assert va.shape == vb.shape and va.size > 0, what
        scale = np.max(np.abs(va))
        err = np.max(np.abs(va - vb))
        assert err <= RTOL * scale + floor, \
            f"{what}: differ by {err:.3e}, {err / scale:.2e} of the largest {scale:.3e} (floor {floor:.2e})"
    assert list(column(full, "CONTACT SLAVE", "state")) == list(column(cond, "CONTACT SLAVE", "state"))


def both(name, deck, ok=True):
    runs = []
    for path in ("FULL", "CONDENSED"):
        run = run_deck(f"condensed_{name}_{path.lower()}", with_path(deck, path))
        if ok:
            run.ok()
            assert contact_solve(run) and set(contact_solve(run)) == {path.lower()}, contact_solve(run)
        runs.append(run)
    return runs


def blocks_cases():
    d = 3 * tc.G0
    back = tc.push_step(d, 2).replace(f"TOP, 2, 2, {-d}", "TOP, 2, 2, 0.0")
    auto = 1000 * tc.E / (tc.W / tc.NX2)
    yield "apart", tc.blocks_deck([tc.push_step(0.5 * tc.G0)])
    yield "pressed", tc.blocks_deck([tc.push_step(d, 2)])
    yield "unload", tc.blocks_deck([tc.push_step(d, 2), back])
    for factor in (0.999, 1.001):
        yield f"switch_{factor}", tc.blocks_deck([tc.push_step(factor * tc.G0)])
    for factor in (1, 10, 100):
        yield f"penalty_{factor}", tc.blocks_deck([tc.push_step(d)], f", PENALTY={factor * auto}")
    yield "force_driven", tc.force_driven_deck()[0]
    yield "force_driven_open", tc.force_driven_deck(", OPEN PENALTY=1e-6")[0]
    yield "update_search", tc.blocks_deck([tc.push_step(d, 2)], ", UPDATE SEARCH")


def seven_over_five_cases():
    d = 3 * tc.G0
    yield "general", tc.blocks_deck([tc.push_step(d)])
    deck = tc.blocks_deck([tc.push_step(d)], ", SYMMETRIC")
    bottom = ", ".join(str(1001 + i) for i in range(tc.NX2))
    yield "symmetric", deck.replace(
        "*SURFACE, NAME=MASTER", f"*ELSET, ELSET=UPPERBOTTOM\n{bottom}\n*SURFACE, NAME=UPPERFACE\n"
        "UPPERBOTTOM, S1\n*SURFACE, NAME=MASTER").replace("SLAVE, MASTER", "UPPERFACE, MASTER")


def test_contact_decks_same_answers_both_paths():
    for name, deck in blocks_cases():
        try:
            compare(*both(name, deck))
        except AssertionError as e:
            raise AssertionError(f"{name}: {e}") from e
    saved, tc.NX2 = tc.NX2, 7
    try:
        cases = list(seven_over_five_cases())
    finally:
        tc.NX2 = saved
    for name, deck in cases:
        try:
            compare(*both(name, deck))
        except AssertionError as e:
            raise AssertionError(f"{name}: {e}") from e


def test_stabilised_body_says_so_on_both_paths():
    """The body held only by contact is stabilised, then iterated with the
    nominal open penalty, on both paths alike."""
    full, cond = both("stabilised", tc.force_driven_deck()[0])
    for run in (full, cond):
        text = open(run.listing_path).read()
        assert "stabilising the open contact elements" in text and "iterating on with the nominal one" in text


def test_runs_that_stop_stop_alike():
    """A body pulled away from contact: singular on both paths, the same
    message; an unsettled status: the same bisections and the same
    increments kept."""
    deck, _ = tc.force_driven_deck()
    deck = deck.replace(f"TOP, 2, {-2.0 / (tc.NX2 + 1)}", f"TOP, 2, {2.0 / (tc.NX2 + 1)}")
    for run in both("pulled_away", deck, ok=False):
        assert run.rc != 0
        assert "singular stiffness at node" in run.stderr and "held only by open contact" in run.stderr, run.stderr
        assert "=== INCREMENT" not in open(run.listing_path).read()
    deck = tc.blocks_deck([tc.push_step(0.5 * tc.G0), tc.push_step(3 * tc.G0)]).replace(
        "*CONTACT PAIR", "*CONTACT CONTROLS, MAXIT=1, CUTBACKS=2\n*CONTACT PAIR")
    runs = both("unsettled", deck, ok=False)
    for run in runs:
        assert run.rc != 0 and "after 2 bisections" in run.stderr, run.stderr
        assert open(run.listing_path).read().count("increment bisected") == 2
    assert [i.attrs for i in runs[0].listing.increments] == [i.attrs for i in runs[1].listing.increments]


def test_default_is_condensed_with_cholmod_and_full_otherwise():
    """AUTO condenses with CHOLMOD where the dense matrix is small against
    the sparse factorisation, and factors the whole system otherwise (m
    comparable to n, UMFPACK, the skyline); CONDENSED needs CHOLMOD."""
    deck = tc.blocks_deck([tc.push_step(3 * tc.G0)])
    run = run_deck("condensed_default", deck).ok()
    assert contact_solve(run) == ["condensed"], contact_solve(run)
    text = open(run.listing_path).read()
    assert re.search(r"^contact_equations \d+$", text, re.M)
    assert re.search(r"^factor CHOLMOD, ordering AMD \(CAMD: the last \d+ equations kept last\)", text, re.M)
    assert re.search(r"^condensed_factorisations [1-9]", text, re.M)
    for solver in ("UMFPACK", "SKYLINE"):
        run = run_deck("condensed_" + solver.lower(), tc.force_driven_deck(solver=solver)[0]).ok()
        assert contact_solve(run) == ["full"], (solver, contact_solve(run))
    # two strips one element thick: a third of the equations are contact
    # equations, the dense matrix would cost most of a sparse factorisation
    saved = tc.NX1, tc.NY1, tc.NX2, tc.NY2
    tc.NX1, tc.NY1, tc.NX2, tc.NY2 = 20, 1, 40, 1
    try:
        strips = tc.blocks_deck([tc.push_step(3 * tc.G0)])
    finally:
        tc.NX1, tc.NY1, tc.NX2, tc.NY2 = saved
    run = run_deck("condensed_auto_strips", strips).ok()
    assert contact_solve(run) == ["full"], contact_solve(run)
    bad = deck.replace("*CONTACT PAIR", "*SOLVER, TYPE=UMFPACK, CONTACT SOLVE=CONDENSED\n*CONTACT PAIR")
    run = run_deck("condensed_bad_solver", bad)
    assert run.rc != 0 and "CONTACT SOLVE=CONDENSED needs TYPE=CHOLMOD" in run.stderr, run.stderr


def test_timing_block_ends_the_listing():
    run = run_deck("condensed_timing", tc.blocks_deck([tc.push_step(3 * tc.G0)])).ok()
    timing = [b for b in run.listing.header if b.name == "TIMING"]
    assert len(timing) == 1
    items = timing[0].as_dict()
    for key in ("read", "setup", "analyse", "factor", "condensed_iterations", "recovery", "output", "total"):
        assert float(items[key]) >= 0.0, key
    assert int(items["numeric_factorisations"]) == 1 and int(items["condensed_factorisations"]) >= 1
    assert open(run.listing_path).read().rstrip().splitlines()[-1].startswith("condensed_factorisations ")


def test_hertz_coarse_same_answers_both_paths():
    import shutil
    if shutil.which("gmsh") is None:
        raise Skip("gmsh is not installed")
    import run_hertz
    out = os.path.join(WORK, "condensed_hertz_coarse")
    job, _ = run_hertz.run_case(out, mesh="coarse")
    with open(job + ".inp") as f:
        deck = f.read()
    deck = re.sub(r"\*NODE FILE\n.*\n\*EL FILE\nS\n", "", deck)
    mesh = os.path.join(out, "hertz_mesh.inp")
    with open(mesh) as f:
        files = {"hertz_mesh.inp": f.read()}
    runs = []
    for path in ("FULL", "CONDENSED"):
        run = run_deck(f"condensed_hertz_{path.lower()}", with_path(deck, path), files=files).ok()
        assert contact_solve(run) == [path.lower()]
        runs.append(run)
    compare(*runs)
