"""The mutation fuzzer (scripts/fuzz.py) on both builds: a short fixed-seed
slice must find no crash, hang or silent bad result, and every minimised
deck of tests/fuzz/ (a past failure) must now be handled as its case.txt
expects: a clear error (ok-error) or a clean run (ok-run)."""
import os
import shutil
import tempfile

import fuzz
from helpers import Skip

HERE = os.path.dirname(os.path.abspath(__file__))
REGRESSIONS = os.path.join(HERE, "fuzz")

# About a minute on the 2-core machine for both builds (seeds included);
# a hang costs 2 x SLICE_TIME_LIMIT.
SLICE_SEED, SLICE_COUNT, SLICE_TIME_LIMIT = 1, 100, 5
# A fixed deck is handled at once; a longer limit only slows the failures.
REGRESSION_TIME_LIMIT = 5


def builds():
    exes = [os.path.join(fuzz.ROOT, b) for b in fuzz.DEFAULT_BUILDS]
    missing = [e for e in exes if not os.access(e, os.X_OK)]
    if missing:
        raise Skip(f"not built: {', '.join(missing)}")
    return exes


def test_fuzz_short_slice():
    exes = builds()
    out = tempfile.mkdtemp(prefix="cfe2d-fuzz-slice-")
    try:
        opts = fuzz.parse_args(["--seed", str(SLICE_SEED), "--count", str(SLICE_COUNT), "--time-limit",
                                str(SLICE_TIME_LIMIT), "--out", out, "--builds", ",".join(exes), "--keep", "0"])
        report = fuzz.fuzz(opts, log=lambda msg: None)
    finally:
        shutil.rmtree(out, ignore_errors=True)
    assert report.decks == SLICE_COUNT and report.runs >= 2 * SLICE_COUNT, report.summary()
    problems = [f"seed {n}: {c} {s}" for n, c, s in report.seed_failures]
    problems += [f"mutant {k} (python3 scripts/fuzz.py --seed {SLICE_SEED} --index {k} --time-limit "
                 f"{SLICE_TIME_LIMIT}): {c}: {s}" for k, c, s, _ in report.failures]
    # the builds must agree on contact statuses, increments, bisections, errors
    problems += [f"mutant {k} (python3 scripts/fuzz.py --seed {SLICE_SEED} --index {k}): the builds disagree "
                 f"on {kind}: {detail}" for (kind, _), items in report.disagree_distinct.items()
                 if kind in fuzz.AGREEMENT_DEFECTS for k, detail in items]
    assert not problems, report.summary() + "\n" + "\n".join(problems)


LISTING = """cfe2d 0.1.0 - 2D contact with coupling finite elements
--- MODEL
item value
deck {deck}
heading {heading}
nodes 6
elements {elements}
solid_elements {solid}

--- STEP step=1 name=
item value
time_period  1.00000E+00
increments 1

=== INCREMENT step=1 increment=1 time=1.00000000E+00 total_time=1.00000000E+00 iterations=1 ===
--- NODE U
         3   {value}   0.000000E+00
=== END INCREMENT
"""


def classify_listing(rc=0, stderr=b"", **fields):
    values = dict(deck="job.inp", heading="bar", value="1.500000E-02", elements="2", solid="2")
    values.update(fields)
    out = tempfile.mkdtemp(prefix="cfe2d-fuzz-classify-")
    try:
        with open(os.path.join(out, "job.out"), "w") as f:
            f.write(LISTING.format(**values))
        return fuzz.classify(rc, "", stderr, out, "job")
    finally:
        shutil.rmtree(out, ignore_errors=True)


def test_classifier_outputs():
    assert classify_listing() == ("ok-run", "")
    # the deck's own text is echoed as given: a "nan" in the heading is no result
    assert classify_listing(heading="gap nan inf 2.0+300", deck="x1e+999.inp") == ("ok-run", "")
    for bad in ("NaN", "-Infinity", "Infinity", "2.000000+160", "1.5-320", "**********"):
        cls, sig = classify_listing(value=bad)
        assert cls == "silent-bad" and ".out" in sig, (bad, cls, sig)
    # trusses or springs alone (no solid element) are a model; no element is none
    assert classify_listing(solid="0") == ("ok-run", "")
    assert classify_listing(elements="0", solid="0")[0] == "silent-bad"
    cls, sig = classify_listing(value="1.0E+00\n=== INCREMENT step=1 increment=2 time=5.0E-01 x")
    assert (cls, sig) == ("silent-bad", "a step stopped before the end of its time period"), sig


def test_classifier_exit_and_stderr():
    assert classify_listing(1, b"job.inp:3: error: undefined node 66\n    | 2, 66\n")[0] == "ok-error"
    assert classify_listing(1, b"cfe2d: error: cannot open deck file\n")[0] == "ok-error"
    assert classify_listing(1, b"something went wrong\n") == \
        ("crash", "exit 1 without a file:line: error: or cfe2d: error: message")
    assert classify_listing(-11, b"") == ("crash", "SIGSEGV")
    cls, sig = classify_listing(2, b"At line 86 of file src/input/deck_parser.f90\n"
                                   b"Fortran runtime error: Index '0' of dimension 1 below lower bound of 1\n")
    assert cls == "crash" and sig.startswith("runtime error at src/input/deck_parser.f90:86: Index '#'"), sig
    # an error message does not excuse a runtime error
    assert classify_listing(1, b"job.inp:3: error: x\nOperating system error: Cannot allocate memory\n")[0] == "crash"
    assert classify_listing(3, b"job.inp:3: error: x\n") == ("crash", "exit status 3")
    assert fuzz.classify(-9, "busy", b"", tempfile.gettempdir(), "no-such-job")[0] == "hang"


CONTACT_LISTING = """--- STEP step=1 name=
item value
time_period  1.00000E+000
increments 1
coupling_elements 2
--- SOLVER step=1
item value
contact_equations 4
contact iteration 1: status changes 2, closed 2, out-of-balance  5.244E-001 (nodes 11 12)
contact iteration 2: status changes 0, closed 2, out-of-balance  {residual}
{note}
=== INCREMENT step=1 increment=1 time=1.00000000E+00 total_time=1.00000000E+00 iterations=2 ===
--- CONTACT SUMMARY pair=1
closed total_force resultant_x resultant_y max_penetration
         {closed}   9.999500E+000   0.000000E+000  -9.999500E+000   9.999500E-007
=== END INCREMENT
"""
CONTACT_CSV = """step,increment,time,pair,side,node,x,y,gap,state,force,pressure
1,1, 1.00000000E+000,1,slave,11, 0.0E+000, 1.0E+000,-2.49987501E-007,CLOSED, 1.24993750E-001, 2.4E+000
1,1, 1.00000000E+000,1,slave,12, 1.0E-001, 1.0E+000,{gap},{state}, 1.24993750E-001, 2.4E+000
"""


def contact_result(build, cls="ok-run", stderr=b"", residual="3.573E-012", note="", closed="2", gap="-2.4E-007",
                   state="CLOSED"):
    out = tempfile.mkdtemp(prefix="cfe2d-fuzz-record-")
    try:
        with open(os.path.join(out, "job.out"), "w") as f:
            f.write(CONTACT_LISTING.format(residual=residual, note=note, closed=closed))
        with open(os.path.join(out, "job_contact.csv"), "w") as f:
            f.write(CONTACT_CSV.format(gap=gap, state=state))
        record = fuzz.contact_record(out, "job", stderr)
    finally:
        shutil.rmtree(out, ignore_errors=True)
    return fuzz.Result(build, cls, "", 0 if cls == "ok-run" else 1, 0.0, stderr, record)


def test_builds_compared_on_contact_statuses():
    """The fuzzer compares the builds' contact statuses, increments,
    bisections and errors, not only their classes; round-off in printed
    numbers, and which node an error names as an example, is no defect."""
    kinds = lambda *rs: [k for k, _ in fuzz.disagreement(list(rs))]
    a = contact_result("opt")
    assert kinds(a, contact_result("dbg", residual="4.340E-012", gap="-2.5E-007")) == []
    assert kinds(a, contact_result("dbg", state="OPEN")) == ["status"]
    assert kinds(a, contact_result("dbg", state="OPEN", closed="1")) == ["status"]
    assert kinds(a, contact_result("dbg", cls="ok-error")) == ["class"]
    bisected = "contact status did not settle: increment bisected"
    assert kinds(a, contact_result("dbg", note=bisected)) == ["increments", "detail"]
    err = b"cfe2d: error: singular stiffness at node %d, dof 1 (missing boundary condition?)\n"
    assert kinds(contact_result("opt", "ok-error", err % 58),
                 contact_result("dbg", "ok-error", err % 843)) == ["detail"]
    err2 = b"cfe2d: error: contact status did not settle in step 1 at time 1.00000E+00 after 5 bisections\n"
    assert kinds(contact_result("opt", "ok-error", err % 58), contact_result("dbg", "ok-error", err2)) == \
        ["error", "detail"]


def test_mutants_reproducible_and_varied():
    seeds = [fuzz.Deck("a", "a.inp", {"a.inp": b"*HEADING\nx\n*NODE\n1, 0, 0\n2, 1.5, 0\n*STEP\n*STATIC\n"
                                                  b"0.5, 1.0\n*END STEP\n"})]
    pool = fuzz.card_pool(seeds)
    first = [fuzz.mutant(seeds, pool, 7, k).files for k in range(30)]
    again = [fuzz.mutant(seeds, pool, 7, k).files for k in range(30)]
    assert first == again
    assert len({tuple(sorted(f.items())) for f in first}) > 20
    assert all(f != seeds[0].files for f in first[:5]), "a mutant must differ from its seed"


def test_ddmin_finds_the_two_lines():
    tried = []

    def fails(lines):
        tried.append(lines)
        return 3 in lines and 17 in lines

    assert fuzz._ddmin(list(range(100)), fails) == [3, 17]
    assert len(tried) < 100


def regression_folders():
    if not os.path.isdir(REGRESSIONS):
        return []
    return sorted(os.path.join(REGRESSIONS, d) for d in os.listdir(REGRESSIONS)
                  if os.path.exists(os.path.join(REGRESSIONS, d, "case.txt")))


def check_regression(folder):
    exes = builds()
    opts = fuzz.parse_args(["--builds", ",".join(exes), "--time-limit", str(REGRESSION_TIME_LIMIT)])
    results, meta = fuzz.replay(folder, opts, log=lambda msg: None)
    want = meta.get("expect", "").split(",")
    assert want and set(want) <= {"ok-error", "ok-run"}, \
        f"{folder}/case.txt: expect= must be ok-error, ok-run or ok-error,ok-run"
    wrong = [f"{r.build}: {r.cls} {r.sig} (exit {r.rc}); stderr: "
             f"{r.stderr[:200].decode(errors='replace').strip()!r}" for r in results if r.cls not in want]
    wrong += [f"the builds disagree on {kind}: {detail}" for kind, detail in fuzz.disagreement(results)
              if kind in fuzz.AGREEMENT_DEFECTS]
    assert not wrong, f"expected {' or '.join(want)} from both builds alike:\n" + "\n".join(wrong)


def test_fuzz_regressions_present():
    # the folder must not silently lose its decks (each is a past failure)
    assert len(regression_folders()) >= 5, regression_folders()


def cases():
    for folder in regression_folders():
        yield f"regression {os.path.basename(folder)}", (lambda f=folder: check_regression(f))


def test_seeds_carry_the_constraint_and_element_cards():
    """The tests' generators give seeds with each of today's cards (a maker
    that fails is skipped with a message: then a card would no longer be
    fuzzed, which this test reports), and the targeted operators change
    them."""
    skipped = []
    seeds = fuzz.test_seeds(skipped.append)
    assert not skipped, skipped
    text = b"\n".join(b"".join(s.files.values()) for s in seeds).upper()
    for card in (b"*EQUATION", b"*TIE", b"*PRE-TENSION SECTION", b"TYPE=T2D2", b"TYPE=T2D3", b"TYPE=SPRING1",
                 b"TYPE=SPRINGA", b"*SPRING", b"TYPE=MASS", b"*MASS", b"*NODAL THICKNESS",
                 b"TYPE=SURFACE TO SURFACE, EXACT", b"*TIE, NAME=GLUE, TYPE=SURFACE TO SURFACE",
                 b"PRESSURE-OVERCLOSURE=HARD"):
        assert card in text, card
    import random
    for op in (fuzz.m_card_field, fuzz.m_constraint, fuzz.m_coincide):
        changed = 0
        for k in range(20):
            rng = random.Random(k)
            seed = rng.choice(seeds)
            deck = seed.copy()
            if op(rng, deck, []) and deck.files != seed.files:
                changed += 1
        assert changed >= 15, (op.__name__, changed)
