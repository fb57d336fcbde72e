"""CalculiX's leniency on the output cards (issue 28): a card naming an
undefined set warns at its line and is ignored; FREQUENCY=, TIME POINTS=
and TOTALS= are honoured where cfe2d writes that output, as CalculiX 2.20
does (its output times kept in tests/calculix/leniency_output_times.csv,
see tests/calculix/README.md); the other parameters are honoured or warned
about at the line; *EL FILE U and E, *CONTACT PRINT and *CONTACT FILE are
honoured: no requested output is dropped without a word."""
import csv
import os

import numpy as np

from gmsh_results import read_msh
from helpers import HERE, run_deck

# A two-element CPS4 bar, held at its left end, pulled at node 3.
MESH = """*NODE, NSET=ALLN
1, 0, 0
2, 1, 0
3, 2, 0
4, 0, 1
5, 1, 1
6, 2, 1
*ELEMENT, TYPE=CPS4, ELSET=BAR
1, 1, 2, 5, 4
2, 2, 3, 6, 5
*NSET, NSET=LEFT
1, 4
*MATERIAL, NAME=STEEL
*ELASTIC
1000., 0.25
*SOLID SECTION, ELSET=BAR, MATERIAL=STEEL
1.
*BOUNDARY
LEFT, 1, 2
"""
LOAD = 5.0


def bar(step, output, extra=""):
    """The bar with a step (`*STEP ... *STATIC` lines) and output cards."""
    return f"{MESH}{extra}{step}\n*CLOAD\n3, 1, {LOAD}\n{output}*END STEP\n"


# five fixed increments of 0.2 under NLGEOM, as CalculiX ran the deck
NLGEOM_DIRECT = "*STEP, NLGEOM\n*STATIC, DIRECT\n0.2, 1."
# the schedules measured with CalculiX 2.20 (leniency_output_times.csv)
SCHEDULES = {
    "print_frequency": "*NODE PRINT, NSET=ALLN, FREQUENCY=2\nU\n*EL PRINT, ELSET=BAR\nS\n",
    "file_frequency": "*NODE PRINT, NSET=ALLN, FREQUENCY=2\nU\n*EL PRINT, ELSET=BAR\nS\n*NODE FILE, FREQUENCY=3\nU\n",
    "frequency_zero": "*NODE PRINT, NSET=ALLN, FREQUENCY=0\nU\n*NODE PRINT, NSET=LEFT\nRF\n",
}


def line_of(text, fragment):
    for k, line in enumerate(text.splitlines(), 1):
        if fragment in line:
            return k
    raise AssertionError(fragment)


def warnings(run):
    return [ln for ln in run.stderr.splitlines() if ": warning: " in ln]


def block_times(run, name, **attrs):
    """The times of the increments whose listing has block `name`."""
    return [inc.time for inc in run.listing.increments if inc.has(name, **attrs)]


def calculix_times():
    """{(case, file): [times]} of tests/calculix/leniency_output_times.csv:
    the times of the blocks CalculiX 2.20 wrote to its .dat (file dat) and
    .frd (file frd) for each case of SCHEDULES."""
    out = {}
    with open(os.path.join(HERE, "calculix", "leniency_output_times.csv")) as f:
        for row in csv.DictReader(f):
            out.setdefault((row["case"], row["file"], row["block"]), []).append(float(row["time"]))
    return out


def test_output_card_naming_an_undefined_set_warns_and_is_ignored():
    """*NODE PRINT, NSET=NALL where the deck never defines NALL (two decks
    of the issue stopped there): a warning at its line, the card ignored
    (no block in the listing), the run goes on and its other output is
    the same to the bit. *EL PRINT with an undefined ELSET= likewise. A
    file card writes every node whatever its set: only its NSET= is
    ignored, with a warning, and the displacement view is written."""
    plain_out = "*NODE PRINT, NSET=ALLN\nU, RF\n"
    out = ("*NODE PRINT, NSET=NALL\nU\n*EL PRINT, ELSET=NOPE\nS\n" + plain_out +
           "*NODE FILE, NSET=NOWHERE\nU\n")
    deck = bar("*STEP\n*STATIC", out)
    run = run_deck("lenient_undefined_output_set", deck).ok()
    want = [f"{run.deck}:{line_of(deck, '*NODE PRINT, NSET=NALL')}: warning: node set NALL is undefined: "
            "*NODE PRINT is ignored, as CalculiX ignores it",
            f"{run.deck}:{line_of(deck, '*EL PRINT, ELSET=NOPE')}: warning: element set NOPE is undefined: "
            "*EL PRINT is ignored, as CalculiX ignores it",
            f"{run.deck}:{line_of(deck, '*NODE FILE, NSET=NOWHERE')}: warning: node set NOWHERE is undefined: "
            "NSET= on *NODE FILE is ignored (the result files hold every node)"]
    assert warnings(run) == want, run.stderr
    inc = run.listing.increments[-1]
    assert block_times(run, "ELEMENT S") == [], "an ignored *EL PRINT listed S"
    plain = run_deck("lenient_undefined_output_set_plain", bar("*STEP\n*STATIC", plain_out)).ok()
    for q, cols in (("NODE U", ("U1", "U2")), ("NODE RF", ("RF1", "RF2"))):
        got, ref = inc.block(q, set="ALLN"), plain.listing.increments[-1].block(q, set="ALLN")
        for c in cols:
            assert list(got[c]) == list(ref[c]), (q, c)
    # an element set of that name: the warning says how gmsh writes node sets
    deck = bar("*STEP\n*STATIC", "*NODE PRINT, NSET=BAR\nU\n" + plain_out)
    hinted = run_deck("lenient_undefined_output_set_hint", deck).ok()
    assert warnings(hinted) == [f"{hinted.deck}:{line_of(deck, '*NODE PRINT, NSET=BAR')}: warning: node set BAR is "
                                "undefined: *NODE PRINT is ignored, as CalculiX ignores it (there is an element set "
                                "of that name: gmsh writes node sets only with -setnumber Mesh.SaveGroupsOfNodes 1; "
                                "or define it with *NSET, NSET=BAR, ELSET=BAR)"], hinted.stderr
    msh = read_msh(os.path.join(os.path.dirname(run.deck), "lenient_undefined_output_set.msh"))
    _, u = msh.node_view("Displacement", 0)
    ref = plain.listing.increments[-1].block("NODE U", set="ALLN")
    assert np.allclose(u[:, 0], ref["U1"], rtol=0, atol=1e-15 * max(abs(ref["U1"]))), (u, ref["U1"])


def test_frequency_and_time_points_as_calculix_writes_them():
    """FREQUENCY=n: CalculiX 2.20 writes the print and file output of a
    step every n-th increment and at the step's end, the last FREQUENCY=
    of the step's output cards applying to all of them (a *NODE FILE,
    FREQUENCY=3 after a *NODE PRINT, FREQUENCY=2 makes both every third);
    FREQUENCY=0 turns that card off. On the same deck (NLGEOM, five fixed
    increments of 0.2) cfe2d's listing blocks and gmsh views are at the
    times CalculiX's .dat and .frd blocks are (the reference file)."""
    ref = calculix_times()
    for case, out in SCHEDULES.items():
        deck = bar(NLGEOM_DIRECT, out)
        run = run_deck(f"lenient_schedule_{case}", deck).ok()
        assert warnings(run) == [], run.stderr
        if case == "frequency_zero":
            assert block_times(run, "NODE U", set="ALLN") == [], case
            assert np.allclose(block_times(run, "NODE RF", set="LEFT"), ref[(case, "dat", "RF")], atol=1e-12)
            continue
        for block, q in (("NODE U", "U"), ("ELEMENT S", "S")):
            got = block_times(run, block)
            assert np.allclose(got, ref[(case, "dat", q)], atol=1e-12), (case, block, got, ref[(case, "dat", q)])
        if case == "file_frequency":
            msh = read_msh(os.path.join(os.path.dirname(run.deck), f"lenient_schedule_{case}.msh"))
            got = [t for t, _, _ in msh.views["Displacement"]]
            assert np.allclose(got, ref[(case, "frd", "U")], atol=1e-12), (got, ref[(case, "frd", "U")])


def test_time_points_write_the_increments_that_reach_them():
    """TIME POINTS=name with *TIME POINTS (the card may follow the step,
    as CalculiX reads its time points first): output at the first
    increment ending at or after each point and at the step's end (cfe2d
    keeps its increments; CalculiX shortens its increments to end on the
    points, so a point inside an increment warns at the card, saying how
    many). A linear step of ten increments of 0.1 with points 0.3, 0.55
    and 0.6: U at 0.3, 0.6 (once for both points) and 1.0, one point
    inside an increment. GENERATE makes the points 0.25, 0.5, 0.75: U at
    0.3, 0.5, 0.8, 1.0, two inside. Points 0.2, 0.5: no warning. Under
    NLGEOM (automatic increments) the increments are shortened to end on
    the points, as CalculiX's (0.2, 0.3, 0.55, 0.6, 1.0, its .sta kept),
    no warning, U at each point and the end. An undefined
    name warns at the line and the step's output stays every increment."""
    step = "*STEP\n*STATIC\n0.1, 1."
    cases = (("*TIME POINTS, NAME=TP\n0.3, 0.55\n0.6\n", [0.3, 0.6, 1.0], "1 time point lies"),
             ("*TIME POINTS, NAME=TP, GENERATE\n0.25, 0.75, 0.25\n", [0.3, 0.5, 0.8, 1.0], "2 time points lie"),
             ("*TIME POINTS, NAME=TP\n0.2, 0.5\n", [0.2, 0.5, 1.0], None))
    for k, (points, want, missed) in enumerate(cases):
        deck = bar(step, "*NODE PRINT, NSET=ALLN, TIME POINTS=TP\nU\n") + points
        run = run_deck(f"lenient_time_points_{k}", deck).ok()
        if missed is None:
            assert warnings(run) == [], run.stderr
        else:
            assert warnings(run) == [f"{run.deck}:{line_of(deck, 'TIME POINTS=TP')}: warning: {missed} inside an "
                                     "increment of 1.00000E-01: the output is that of the increment ending after it "
                                     "(CalculiX shortens an increment to end on it)"], run.stderr
        got = block_times(run, "NODE U")
        assert np.allclose(got, want, atol=1e-12), (k, got, want)
    # automatic increments (NLGEOM): one warning, and output at the
    # increments that reach the points
    deck = bar("*STEP, NLGEOM\n*STATIC\n0.2, 1.", "*NODE PRINT, NSET=ALLN, TIME POINTS=TP\nU\n") + cases[0][0]
    run = run_deck("lenient_time_points_automatic", deck).ok()
    assert warnings(run) == [], run.stderr
    # the increments end where CalculiX 2.20's do (its .sta on the same
    # deck, tests/calculix/time_points_automatic.csv): shortened to end on
    # each point, the next growing from the size it would have had
    ref = {"sta": [], "dat": []}
    with open(os.path.join(HERE, "calculix", "time_points_automatic.csv")) as f:
        for line in f:
            if line.startswith("#") or line.startswith("file"):
                continue
            kind, t = line.strip().split(",")
            ref[kind].append(float(t))
    times = [inc.time for inc in run.listing.increments]
    assert np.allclose(times, ref["sta"], rtol=0, atol=1e-12), (times, ref["sta"])
    assert np.allclose(block_times(run, "NODE U"), ref["dat"], rtol=0, atol=1e-12), block_times(run, "NODE U")
    deck = bar(step, "*NODE PRINT, NSET=ALLN, TIME POINTS=NONE\nU\n")
    run = run_deck("lenient_time_points_undefined", deck).ok()
    assert warnings(run) == [f"{run.deck}:{line_of(deck, 'TIME POINTS=NONE')}: warning: undefined *TIME POINTS "
                             "NONE: TIME POINTS= is ignored"], run.stderr
    assert len(block_times(run, "NODE U")) == 10


def test_totals_sum_the_reactions():
    """TOTALS=YES on *NODE PRINT adds the sum of RF over the set (CalculiX's
    "total force"): over the held end it balances the load, -5 along x and
    0 along y (to 1e-12 of the load), and equals the sum of the listed
    rows; over all nodes it is the same (cfe2d's RF is the reaction,
    zero at free nodes; CalculiX's also holds the applied load); TOTALS=ONLY lists the sum alone (no U or RF rows, as CalculiX).
    TOTALS= on *EL PRINT sums whole-element quantities cfe2d does not
    have: a warning, and S is listed as without it."""
    out = "*NODE PRINT, NSET=LEFT, TOTALS=YES\nRF\n*NODE PRINT, NSET=ALLN, TOTALS=ONLY\nU, RF\n" \
          "*EL PRINT, ELSET=BAR, TOTALS=YES\nS\n"
    deck = bar("*STEP\n*STATIC", out)
    run = run_deck("lenient_totals", deck).ok()
    assert warnings(run) == [f"{run.deck}:{line_of(deck, '*EL PRINT, ELSET=BAR, TOTALS=YES')}: warning: TOTALS=YES "
                             "on *EL PRINT is ignored: it sums whole-element quantities (ELSE, EVOL), which cfe2d "
                             "does not have"], run.stderr
    inc = run.listing.increments[-1]
    rows, total = inc.block("NODE RF", set="LEFT"), inc.block("NODE RF TOTAL", set="LEFT")
    assert abs(total["RF1"][0] + LOAD) < 1e-12 * LOAD and abs(total["RF2"][0]) < 1e-12 * LOAD, total
    assert abs(total["RF1"][0] - sum(rows["RF1"])) < 1e-14 * LOAD, (total, rows)
    # (cfe2d's RF is the reaction, zero at free nodes: over all nodes the
    # sum is the support's)
    whole = inc.block("NODE RF TOTAL", set="ALLN")
    assert abs(whole["RF1"][0] + LOAD) < 1e-12 * LOAD and abs(whole["RF2"][0]) < 1e-12 * LOAD, whole
    assert block_times(run, "NODE U", set="ALLN") == [] and block_times(run, "NODE RF", set="ALLN") == []
    assert len(inc.block("ELEMENT S", set="BAR")["S11"]) == 8


def test_other_output_parameters_are_honoured_or_warned_about():
    """The other parameters of the print and file cards: those cfe2d does
    anyway pass silently (OUTPUT=2D, POSITION=INTEGRATION POINTS,
    SUMMARY=NO, GLOBAL=YES); those it cannot honour warn at the card's
    line (OUTPUT=3D, POSITION=CENTROIDAL, SUMMARY=YES, FREQUENCYF=, LAST
    ITERATIONS, CONTACT ELEMENTS, SECTION FORCES); U or RF asked for on
    *EL PRINT warns (it lists element quantities), and the answer is the
    plain run's."""
    quiet = ("*NODE FILE, OUTPUT=2D, GLOBAL=YES\nU\n*EL PRINT, ELSET=BAR, POSITION=INTEGRATION POINTS, SUMMARY=NO\n"
             "S\n*NODE PRINT, NSET=ALLN, GLOBAL=YES\nU\n")
    run = run_deck("lenient_params_quiet", bar("*STEP\n*STATIC", quiet)).ok()
    assert warnings(run) == [], run.stderr
    loud = [("*NODE FILE, OUTPUT=3D\nU\n", "OUTPUT=3D is ignored: cfe2d's results are those of the 2D model"),
            ("*EL PRINT, ELSET=BAR, POSITION=CENTROIDAL\nS\n", "POSITION=CENTROIDAL is ignored: *EL PRINT gives "
             "values at the integration points"),
            ("*NODE PRINT, NSET=ALLN, SUMMARY=YES\nU\n", "SUMMARY=YES is ignored"),
            ("*NODE FILE, FREQUENCYF=2\nU\n", "FREQUENCYF on *NODE FILE is not implemented in cfe2d and is ignored"),
            ("*NODE FILE, LAST ITERATIONS\nU\n", "LAST ITERATIONS on *NODE FILE is not implemented"),
            ("*EL FILE, CONTACT ELEMENTS\nS\n", "CONTACT ELEMENTS on *EL FILE is not implemented"),
            ("*EL FILE, SECTION FORCES\nS\n", "SECTION FORCES on *EL FILE is not implemented"),
            ("*EL PRINT, ELSET=BAR\nU, S\n", "U is a nodal quantity, which *EL PRINT does not list")]
    for k, (card, fragment) in enumerate(loud):
        deck = bar("*STEP\n*STATIC", card + "*NODE PRINT, NSET=ALLN\nU\n")
        run = run_deck(f"lenient_params_loud_{k}", deck).ok()
        first = card.splitlines()[0]
        line = line_of(deck, first) + (1 if card.startswith("*EL PRINT, ELSET=BAR\nU") else 0)
        w = warnings(run)
        assert len(w) == 1 and w[0].startswith(f"{run.deck}:{line}: warning: ") and fragment in w[0], (card, w)
        u = run.listing.increments[-1].block("NODE U", set="ALLN")
        assert u["U1"][2] > 0, (card, u)


def test_el_file_u_and_e_are_written():
    """*EL FILE asking for U and E (the issue: dropped without a word): U
    is the displacement view of the result file, as CalculiX writes U
    asked for on *EL FILE; E the element averages of the strain (views
    E11, E22, E12 (element)), which equal the means over the integration
    points of *EL PRINT's E (to 1e-15 relative). The VTU files
    (FORMAT=VTU) get U and E (element) alike."""
    out = "*EL FILE, FORMAT=VTU\nU, E\n*EL PRINT, ELSET=BAR\nE\n*NODE PRINT, NSET=ALLN\nU\n"
    run = run_deck("lenient_el_file", bar("*STEP\n*STATIC", out)).ok()
    assert warnings(run) == [], run.stderr
    d = os.path.dirname(run.deck)
    msh = read_msh(os.path.join(d, "lenient_el_file.msh"))
    inc = run.listing.increments[-1]
    u = inc.block("NODE U", set="ALLN")
    _, view = msh.node_view("Displacement", 0)
    assert np.allclose(view[:, :2], np.c_[u["U1"], u["U2"]], rtol=0, atol=1e-15), view
    e = inc.block("ELEMENT E", set="BAR")
    for k, comp in enumerate(("E11", "E22", "E12")):
        _, ids, vals = msh.views[f"{comp} (element)"][0]
        for elem, v in zip(ids, vals[:, 0]):
            mean = np.mean([x for el, x in zip(e["element"], e[comp]) if int(el) == int(elem)])
            assert abs(v - mean) <= 1e-15 * max(abs(e[comp])), (comp, elem, v, mean)
    vtu = open(os.path.join(d, "lenient_el_file_0001.vtu"), "rb").read()
    assert b'Name="E (element)"' in vtu and b'Name="U"' in vtu


def test_contact_print_and_file_are_honoured():
    """*CONTACT PRINT (CSTR, CDIS, CFN, ...) asks for what the listing's
    contact tables give at every increment: read, no warning (it was
    skipped with one); *CONTACT FILE with CSTR writes the contact pressure
    view of the result file, at the nodes where the *NODE FILE CSTRESS
    view of the same run has it, with the same values; an unknown
    quantity (CELS) warns at its line."""
    deck = open(os.path.join(os.path.dirname(HERE), "input", "examples", "blocks.inp")).read()
    end = deck.rindex("*END STEP")
    runs = {}
    for name, cards in (("print", "*CONTACT PRINT\nCSTR, CDIS, CFN\n*CONTACT FILE\nCSTR\n"),
                        ("node_file", "*NODE FILE\nCSTRESS\n"),
                        ("cels", "*CONTACT PRINT, TOTALS=YES\nCSTR, CELS\n")):
        text = deck[:end] + cards + deck[end:]
        runs[name] = (text, run_deck(f"lenient_contact_{name}", text).ok())
    text, run = runs["print"]
    base = [w for w in warnings(run_deck("lenient_contact_plain", deck).ok())]
    assert warnings(run) == base, run.stderr
    views = []
    for name in ("print", "node_file"):
        r = runs[name][1]
        msh = read_msh(os.path.join(os.path.dirname(r.deck), f"lenient_contact_{name}.msh"))
        views.append(msh.views["Contact pressure"])
    assert len(views[0]) == len(views[1]) > 0
    for (t1, ids1, v1), (t2, ids2, v2) in zip(*views):
        assert t1 == t2 and list(ids1) == list(ids2) and np.array_equal(v1, v2), t1
    assert max(np.max(np.abs(v)) for _, _, v in views[0]) > 0
    text, run = runs["cels"]
    w = [x for x in warnings(run) if x not in base]
    assert w == [f"{run.deck}:{line_of(text, 'CSTR, CELS')}: warning: output quantity CELS is not available and "
                 "is ignored"], run.stderr


def test_frequency_applies_to_the_vtu_files_and_excludes_time_points():
    """FREQUENCY=2 on a *NODE FILE, FORMAT=VTU of the five-increment step:
    the VTU series holds the increments CalculiX's schedule writes (0.4,
    0.8 and the step's end 1.0: three files, the .pvd listing those
    times), as the gmsh file does. FREQUENCY= and TIME POINTS= on one card
    are an error at its line."""
    import re
    deck = bar(NLGEOM_DIRECT, "*NODE FILE, FORMAT=VTU, FREQUENCY=2\nU\n")
    run = run_deck("lenient_vtu_frequency", deck).ok()
    d = os.path.dirname(run.deck)
    files = sorted(f for f in os.listdir(d) if f.endswith(".vtu"))
    assert files == [f"lenient_vtu_frequency_{k:04d}.vtu" for k in (1, 2, 3)], files
    pvd = open(os.path.join(d, "lenient_vtu_frequency.pvd")).read()
    times = [float(t) for t in re.findall(r'timestep="([^"]+)"', pvd)]
    assert np.allclose(times, [0.4, 0.8, 1.0], atol=1e-12), times
    msh = read_msh(os.path.join(d, "lenient_vtu_frequency.msh"))
    assert np.allclose([t for t, _, _ in msh.views["Displacement"]], times, atol=1e-12)
    bad = bar(NLGEOM_DIRECT, "*NODE PRINT, NSET=ALLN, FREQUENCY=2, TIME POINTS=TP\nU\n") + \
        "*TIME POINTS, NAME=TP\n0.5\n"
    run = run_deck("lenient_frequency_and_time_points", bad)
    assert run.rc == 1 and f"{run.deck}:{line_of(bad, 'FREQUENCY=2, TIME POINTS=TP')}: error: FREQUENCY= and TIME " \
        "POINTS= exclude each other" in run.stderr, run.stderr


def test_time_points_in_total_time_shorten_a_later_steps_increments():
    """TIME=TOTAL TIME: the points are in total time, so in a second
    NLGEOM step (after a first of period 1) the point 1.3 ends the
    increment at step time 0.3 (0.2, then 0.1 to the point), and 1.0, the
    first step's end, shortens nothing there."""
    step2 = "*STEP, NLGEOM\n*STATIC\n0.2, 1.\n*CLOAD\n3, 1, 6.0\n*NODE PRINT, NSET=ALLN, TIME POINTS=TP\nU\n*END STEP\n"
    deck = bar("*STEP, NLGEOM\n*STATIC\n0.5, 1.", "") + step2 + "*TIME POINTS, NAME=TP, TIME=TOTAL TIME\n1.0, 1.3\n"
    run = run_deck("lenient_time_points_total_time", deck).ok()
    assert warnings(run) == [], run.stderr
    second = [inc for inc in run.listing.increments if inc.step == 2]
    # (a listing increment's time is its total time)
    assert [round(inc.time, 12) for inc in second[:2]] == [1.2, 1.3], [inc.time for inc in second]
    assert any(abs(t - 1.3) < 1e-12 for t in block_times(run, "NODE U")), block_times(run, "NODE U")
