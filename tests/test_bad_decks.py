"""A battery of broken decks: each must stop cfe2d with a non-zero exit and
a message "file:line: error: ..." naming the offending line (or
"cfe2d: error: ..." when no line is at fault), and never with a crash, a
Fortran runtime error or a hang."""
import os
import subprocess

from helpers import CFE2D, Run, run_deck, workdir

# Seconds a broken deck may take: every one is rejected while reading, so
# anything longer is a hang (a FIFO or /dev/zero being read).
TIMEOUT = 60

GOOD = """*HEADING
two-element bar
*NODE, NSET=ALLN
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
*STEP
*STATIC
*CLOAD
3, 1, 5.
*NODE PRINT
U
*END STEP
"""


def replace(old, new, deck=GOOD):
    assert old in deck, old
    return deck.replace(old, new, 1)


def line_of(deck, text):
    for k, line in enumerate(deck.splitlines(), 1):
        if text in line:
            return k
    raise AssertionError(text)


# (name, deck, text of the line that must be named, message fragment)
CASES = [
    ("unknown keyword", replace("*NSET, NSET=LEFT", "*FOO\n*NSET, NSET=LEFT"), "*FOO", "not implemented"),
    ("unimplemented Abaqus keyword", replace("*CLOAD", "*DYNAMIC\n0.1, 1.\n*CLOAD"), "*DYNAMIC", "*DYNAMIC is not implemented"),
    ("unknown parameter", replace("*NODE, NSET=ALLN", "*NODE, NSET=ALLN, COLOUR=RED"), "COLOUR", "unknown parameter COLOUR"),
    ("malformed number", replace("5, 1, 1\n", "5, 1, 1.x\n"), "5, 1, 1.x", '"1.x" is not a number'),
    # (a missing coordinate is 0, as in CalculiX: tests/test_decks_calculix.py)
    ("coordinate not a number", replace("5, 1, 1\n", "5, 1, y1\n"), "5, 1, y1", "not a number (y coordinate)"),
    ("missing data line", replace("*ELASTIC\n1000., 0.25\n", "*ELASTIC\n"), "*ELASTIC", "missing data line"),
    ("undefined node", replace("2, 2, 3, 6, 5", "2, 2, 3, 66, 5"), "2, 2, 3, 66, 5", "undefined node 66"),
    ("undefined node set", replace("LEFT, 1, 2", "LEFTSIDE, 1, 2"), "LEFTSIDE", "undefined node set LEFTSIDE"),
    ("undefined material", replace("MATERIAL=STEEL", "MATERIAL=IRON"), "MATERIAL=IRON", "undefined material IRON"),
    # (a node line repeated is no error: the later coordinates win, as in CalculiX,
    # tests/test_calculix_leniency_input.py)
    ("duplicate element", replace("2, 2, 3, 6, 5\n", "2, 2, 3, 6, 5\n1, 2, 3, 6, 5\n"), "1, 2, 3, 6, 5", "duplicate element id 1"),
    ("clockwise element", replace("2, 2, 3, 6, 5", "2, 2, 5, 6, 3"), "2, 2, 5, 6, 3", "negative Jacobian"),
    # (one node at two neighbouring corners is a collapsed quadrilateral: tests/test_reduced_quads.py)
    ("degenerate element", replace("2, 2, 3, 6, 5", "2, 2, 3, 2, 5"), "2, 2, 3, 2, 5", "two corners at one point"),
    ("unimplemented element type", replace("TYPE=CPS4", "TYPE=C3D8"), "TYPE=C3D8", "C3D8 is not implemented"),
    ("wrong node count", replace("1, 1, 2, 5, 4", "1, 1, 2, 5"), "1, 1, 2, 5", "needs an id and 4 nodes"),
    ("step without end", replace("*END STEP\n", ""), "*STEP", "without *END STEP"),
    ("load outside step", replace("*STEP", "*CLOAD\n3, 1, 1.\n*STEP"), "*CLOAD", "must be inside *STEP"),
    ("dof out of range", replace("LEFT, 1, 2", "LEFT, 1, 4"), "LEFT, 1, 4", "dofs must satisfy"),
    # dof 3 (out of the plane) may be held at zero only (tests/test_springs.py)
    ("dof 3 moved", replace("LEFT, 1, 2", "LEFT, 1, 3, 0.5"), "LEFT, 1, 3, 0.5", "dofs must satisfy"),
    ("Poisson ratio 0.5", replace("1000., 0.25", "1000., 0.5"), "1000., 0.5", "Poisson's ratio"),
    ("undefined amplitude", replace("*CLOAD", "*CLOAD, AMPLITUDE=RAMP2"), "AMPLITUDE=RAMP2", "undefined amplitude RAMP2"),
    ("no section", replace("*SOLID SECTION, ELSET=BAR, MATERIAL=STEEL\n1.\n", ""), "1, 1, 2, 5, 4", "no *SOLID SECTION"),
    ("data line before any keyword", "1, 2, 3\n" + GOOD, "1, 2, 3", "data line where a keyword"),
    ("undefined surface in contact pair",
     replace("*STEP", "*CONTACT PAIR\nLEFT, NOSUCH\n*STEP"), "LEFT, NOSUCH", "undefined surface NOSUCH"),
    ("face id beyond the element", replace("*STEP", "*SURFACE, NAME=S\n1, S5\n*STEP"), "1, S5", "face S5 does not exist"),
    ("no step", GOOD[:GOOD.index("*STEP")], "LEFT, 1, 2", "no *STEP"),
    ("missing include", replace("*NSET, NSET=LEFT", "*INCLUDE, INPUT=nosuch.inp\n*NSET, NSET=LEFT"),
     "*INCLUDE", 'include file'),
    ("negative thickness", replace("MATERIAL=STEEL\n1.", "MATERIAL=STEEL\n-1."), "-1.", "thickness must be positive"),
    # Includes that are not regular files: read, they would never end
    # (/dev/zero), block (a FIFO) or fail obscurely (a directory).
    ("include of a device", replace("*NSET, NSET=LEFT", "*INCLUDE, INPUT=/dev/zero\n*NSET, NSET=LEFT"),
     "*INCLUDE", '"/dev/zero" is not a regular file'),
    ("include of a FIFO", replace("*NSET, NSET=LEFT", "*INCLUDE, INPUT=pipe.inp\n*NSET, NSET=LEFT"),
     "*INCLUDE", "is not a regular file", lambda d: os.mkfifo(os.path.join(d, "pipe.inp"))),
    ("include of a directory", replace("*NSET, NSET=LEFT", "*INCLUDE, INPUT=sub\n*NSET, NSET=LEFT"),
     "*INCLUDE", "is a directory", lambda d: os.mkdir(os.path.join(d, "sub"))),
    # Step time: the increment count period / dt is checked in real
    # arithmetic (an integer conversion overflows or wraps).
    ("denormal time increment", replace("*STATIC\n", "*STATIC\n1e-320, 1\n"), "1e-320, 1", "at most 100000"),
    ("time increment below period * 1e-12", replace("*STATIC\n", "*STATIC\n1e-13, 1\n"), "1e-13, 1",
     "at most 100000"),
    ("huge time period", replace("*STATIC\n", "*STATIC\n1, 1e308\n"), "1, 1e308", "at most 100000"),
    ("SPLIT TOUCHING with DIRECT", replace("*STATIC\n", "*STATIC, DIRECT, SPLIT TOUCHING\n"),
     "*STATIC, DIRECT, SPLIT TOUCHING", "give one of the two"),
    ("increments beyond 2^32", replace("*STATIC\n", "*STATIC\n1, 4294967299\n"), "1, 4294967299",
     "4.29E+09 increments"),
    ("increments just above the cap", replace("*STATIC\n", "*STATIC\n1, 100000.6\n"), "1, 100000.6",
     "at most 100000"),
    ("zero time increment", replace("*STATIC\n", "*STATIC\n0.0, 1.0\n"), "0.0, 1.0", "must be positive"),
    ("NaN time period", replace("*STATIC\n", "*STATIC\n1, nan\n"), "1, nan",
     '"nan" is not a finite number (time period)'),
    ("INC beyond the cap", replace("*STEP", "*STEP, INC=100001"), "INC=100001", "INC must lie in 1..100000"),
    ("increments beyond INC", replace("*STEP\n*STATIC\n", "*STEP, INC=3\n*STATIC\n0.25, 1\n"), "0.25, 1",
     "the step needs 4 increments, more than INC=3"),
    # Reals must be finite: NaN, Infinity and overflowing literals are
    # errors naming the field.
    ("overflowing coordinate", replace("5, 1, 1\n", "5, 1, 1e400\n"), "5, 1, 1e400",
     '"1e400" is not a finite number (y coordinate)'),
    ("NaN Young's modulus", replace("1000., 0.25", "nan, 0.25"), "nan, 0.25",
     '"nan" is not a finite number (Young\'s modulus)'),
    ("infinite load", replace("3, 1, 5.", "3, 1, inf"), "3, 1, inf", '"inf" is not a finite number (load value)'),
    ("negative overflow in a prescribed value", replace("LEFT, 1, 2", "LEFT, 1, 1, -1e309\nLEFT, 2, 2"),
     "LEFT, 1, 1, -1e309", "is not a finite number (prescribed value)"),
    ("infinite parameter", replace("*STEP", "*CONTACT CONTROLS, TOLERANCE=Infinity\n*STEP"), "TOLERANCE=Infinity",
     "is not a finite number (value of TOLERANCE)"),
    ("node id beyond the integer range", replace("6, 2, 1\n", "6, 2, 1\n99999999999, 3, 3\n"),
     "99999999999, 3, 3", "out of the integer range (node id)"),
    ("node id beyond the id range", replace("6, 2, 1\n", "6, 2, 1\n100000001, 3, 3\n"),
     "100000001, 3, 3", "node id out of range 1..100000000"),
    # Contact controls: each cutback is a level of recursion.
    ("CUTBACKS beyond the cap", replace("*STEP", "*CONTACT CONTROLS, CUTBACKS=20000\n*STEP"), "CUTBACKS=20000",
     "CUTBACKS must lie in 0..50"),
    ("CUTBACKS just above the cap", replace("*STEP", "*CONTACT CONTROLS, CUTBACKS=51\n*STEP"), "CUTBACKS=51",
     "CUTBACKS must lie in 0..50"),
    ("MAXIT beyond the cap", replace("*STEP", "*CONTACT CONTROLS, MAXIT=1001\n*STEP"), "MAXIT=1001",
     "MAXIT must lie in 1..1000"),
    ("name longer than 80 characters", replace("NAME=STEEL", "NAME=" + "S" * 81), "S" * 81,
     "name longer than 80 characters"),
]


def run_bounded(tag, deck=None, path=None, files=None, setup=None):
    """run_deck with a time limit (a hang is a failure, not a stuck test
    run); setup(dir) may add files beside the deck (FIFOs, directories)."""
    if deck is not None:
        d = workdir(tag)
        path = os.path.join(d, tag + ".inp")
        with open(path, "w", newline="") as f:
            f.write(deck)
        if setup:
            setup(d)
        for fn, text in (files or {}).items():
            os.makedirs(os.path.dirname(os.path.join(d, fn)), exist_ok=True)
            with open(os.path.join(d, fn), "w") as f:
                f.write(text)
    outdir = workdir(tag + "_out")
    try:
        proc = subprocess.run([CFE2D, "-q", "-o", outdir, path], capture_output=True, text=True, timeout=TIMEOUT)
    except subprocess.TimeoutExpired:
        raise AssertionError(f"cfe2d still running after {TIMEOUT} s on {path}")
    return Run(path, proc, os.path.join(outdir, tag + ".out"))


def assert_clean_failure(run, name):
    assert run.rc == 1, f"exit status {run.rc} for a bad deck ({name}):\n{run.stderr}"
    for bad in ("Fortran runtime error", "Backtrace", "Segmentation", "SIGSEGV", "STOP"):
        assert bad not in run.stderr, f"crash-like output: {run.stderr!r}"


def check(name, deck, text, fragment, setup=None, files=None, where=None):
    tag = "bad_" + "".join(c if c.isalnum() else "_" for c in name)
    run = run_bounded(tag, deck, files=files, setup=setup)
    assert_clean_failure(run, name)
    err = run.stderr
    fname = where or run.deck
    lineno = line_of(open(fname).read(), text)
    expect = f"{fname}:{lineno}: error:"
    assert expect in err, f"expected '{expect}' in stderr, got:\n{err}"
    assert fragment in err, f"expected '{fragment}' in stderr, got:\n{err}"
    assert text.strip() in err, f"offending line not quoted:\n{err}"


def cases():
    for name, deck, text, frag, *setup in CASES:
        yield f"bad deck: {name}", (lambda d=deck, t=text, f=frag, n=name, s=setup: check(n, d, t, f, *s))


def test_error_inside_included_file():
    """The message names the included file and its own line number."""
    mesh = "*NODE\n1, 0, 0\n2, 1, 0\n3, 1, oops\n"
    deck = replace("*NODE, NSET=ALLN\n1, 0, 0\n2, 1, 0\n3, 2, 0\n", "*INCLUDE, INPUT=mesh.inp\n*NODE, NSET=ALLN\n")
    run = run_deck("bad_include_content", deck, files={"mesh.inp": mesh})
    inc = os.path.join(os.path.dirname(run.deck), "mesh.inp")
    assert run.rc != 0
    assert f"{inc}:4: error:" in run.stderr, run.stderr
    assert "oops" in run.stderr


def test_singular_stiffness_is_reported():
    """A missing support: a clear message naming a node and dof, no NaNs."""
    deck = replace("LEFT, 1, 2", "LEFT, 1, 1")
    run = run_deck("bad_singular", deck)
    assert run.rc != 0
    assert "singular stiffness at node" in run.stderr and "(missing boundary condition?)" in run.stderr, run.stderr
    assert "NaN" not in open(run.listing_path).read()


def test_missing_deck_file():
    run = run_deck("bad_missing_deck", path="/nonexistent/deck.inp")
    assert run.rc != 0 and "cannot open deck file" in run.stderr, run.stderr


def test_output_request_keyword_only_warns():
    """Pure output requests of Abaqus that cfe2d lacks cannot change the
    answer: a warning with file:line, and the run completes."""
    deck = replace("*NODE PRINT", "*NODE OUTPUT\nU\n*NODE PRINT")
    run = run_deck("warn_node_output", deck)
    assert run.rc == 0, run.stderr
    assert f"{run.deck}:{line_of(deck, '*NODE OUTPUT')}: warning:" in run.stderr, run.stderr


def test_card_on_empty_set_warns():
    """Cards that name an empty node set, element set or surface warn
    "file:line: warning: <set> is empty: *<card> does nothing for it" at
    the line naming the set (in an included file: that file and its own
    line), once each, and the run completes with the answer of the deck
    without them. Set definitions (*NSET, *ELSET) do not warn."""
    empty = ("*NSET, NSET=NOWHERE\n*ELSET, ELSET=NOBODY\n*NSET, NSET=STILLNONE\nNOWHERE\n"
             "*SURFACE, NAME=NOFACES\nNOBODY, S1\n*MATERIAL, NAME=STEEL")
    deck = replace("*MATERIAL, NAME=STEEL", empty)
    deck = replace("1.\n*BOUNDARY\n", "1.\n*SOLID SECTION, ELSET=NOBODY, MATERIAL=STEEL\n1.\n*BOUNDARY\n", deck)
    deck = replace("LEFT, 1, 2\n", "LEFT, 1, 2\n*INCLUDE, INPUT=more_bcs.inp\n", deck)
    deck = replace("*NODE PRINT\nU\n", "*CLOAD\nSTILLNONE, 2, 7.\n*DLOAD\nNOBODY, P2, 3.\n*DSLOAD\nNOFACES, P, 4.\n"
                   "*NODE PRINT, NSET=NOWHERE\nU\n*EL PRINT, ELSET=NOBODY\nS\n*NODE PRINT\nU\n", deck)
    more = "** boundary conditions kept apart\n*BOUNDARY\nNOWHERE, 1, 2\n"
    run = run_deck("warn_empty_sets", deck, files={"more_bcs.inp": more})
    assert run.rc == 0, run.stderr
    inc = os.path.join(os.path.dirname(run.deck), "more_bcs.inp")
    expected = [
        (run.deck, "NOBODY, S1", "element set NOBODY", "*SURFACE"),
        (run.deck, "*SOLID SECTION, ELSET=NOBODY", "element set NOBODY", "*SOLID SECTION"),
        (inc, "NOWHERE, 1, 2", "node set NOWHERE", "*BOUNDARY"),
        (run.deck, "STILLNONE, 2, 7.", "node set STILLNONE", "*CLOAD"),
        (run.deck, "NOBODY, P2, 3.", "element set NOBODY", "*DLOAD"),
        (run.deck, "NOFACES, P, 4.", "surface NOFACES", "*DSLOAD"),
        (run.deck, "*NODE PRINT, NSET=NOWHERE", "node set NOWHERE", "*NODE PRINT"),
        (run.deck, "*EL PRINT, ELSET=NOBODY", "element set NOBODY", "*EL PRINT"),
    ]
    warnings = [line for line in run.stderr.splitlines() if "is empty:" in line]
    for fname, text, what, card in expected:
        lineno = line_of(open(fname).read(), text)
        message = f"{fname}:{lineno}: warning: {what} is empty: {card} does nothing for it"
        assert warnings.count(message) == 1, f"expected once: {message}\ngot:\n{run.stderr}"
    assert len(warnings) == len(expected), run.stderr
    # the cards on empty sets changed nothing
    plain = run_deck("warn_empty_sets_plain", GOOD).ok()
    assert "is empty" not in plain.stderr, plain.stderr
    got, want = run.listing.increments[-1], plain.listing.increments[-1]
    assert len(got.block("NODE U", set="NOWHERE")) == 0
    for col in ("U1", "U2"):
        assert list(got.block("NODE U", set="ALL")[col]) == list(want.block("NODE U", set="ALL")[col]), col


def test_deck_without_keywords():
    """An empty deck, one of comments only, one of blank and CR-LF lines:
    no line is at fault, so the message is cfe2d: error: and says why."""
    decks = {"empty": "", "comments": "** a comment\n**\n** another\n", "blank": "\n   \n\t\n",
             "crlf": "\r\n\r\n  \r\n** comment\r\n"}
    for name, text in decks.items():
        run = run_bounded("bad_no_keyword_" + name, text)
        assert_clean_failure(run, name)
        assert "cfe2d: error:" in run.stderr and "has no keyword lines" in run.stderr, (name, run.stderr)


def test_deck_that_is_not_a_regular_file():
    """The deck itself: a device, a FIFO (opening it would block) or a
    directory."""
    d = workdir("notfile_deck")
    fifo = os.path.join(d, "pipe.inp")
    os.mkfifo(fifo)
    for path, fragment in (("/dev/zero", "is not a regular file"), (fifo, "is not a regular file"),
                           (d, "is a directory")):
        run = run_bounded("notfile_deck_run", path=path)
        assert_clean_failure(run, path)
        assert f'cfe2d: error: deck "{path}" {fragment}' in run.stderr, run.stderr


def test_recursive_include():
    """A file that includes itself, directly or through another file, is
    named at the *INCLUDE that closes the loop (not after 16 levels)."""
    deck = replace("*NSET, NSET=LEFT", "*INCLUDE, INPUT=bad_include_self.inp\n*NSET, NSET=LEFT")
    run = run_bounded("bad_include_self", deck)
    assert_clean_failure(run, "self include")
    assert f"{run.deck}:{line_of(deck, '*INCLUDE')}: error: recursive *INCLUDE" in run.stderr, run.stderr

    deck = replace("*NSET, NSET=LEFT", "*INCLUDE, INPUT=a.inp\n*NSET, NSET=LEFT")
    files = {"a.inp": "** a\n*INCLUDE, INPUT=sub/b.inp\n", "sub/b.inp": "*INCLUDE, INPUT=../a.inp\n"}
    run = run_bounded("bad_include_loop", deck, files=files)
    b = os.path.join(os.path.dirname(run.deck), "sub", "b.inp")
    assert_clean_failure(run, "include loop")
    assert f"{b}:1: error: recursive *INCLUDE" in run.stderr, run.stderr
    assert "is already being read" in run.stderr, run.stderr


def include_chain(levels, content):
    """Files l1.inp ... l<levels>.inp, each including the next; the last
    holds `content`."""
    files = {f"l{k}.inp": f"** level {k}\n*INCLUDE, INPUT=l{k + 1}.inp\n" for k in range(1, levels)}
    files[f"l{levels}.inp"] = content
    return files


def test_include_depth_limit():
    """17 nested levels are one too many (16 pass: test_deck_features)."""
    mesh = GOOD[GOOD.index("*NODE"):GOOD.index("*NSET, NSET=LEFT")]
    deck = GOOD.replace(mesh, "*INCLUDE, INPUT=l1.inp\n")
    run = run_bounded("bad_include_depth", deck, files=include_chain(17, mesh))
    last = os.path.join(os.path.dirname(run.deck), "l16.inp")
    assert_clean_failure(run, "depth")
    assert f"{last}:2: error: *INCLUDE nested more than 16 levels deep" in run.stderr, run.stderr


def test_line_too_long():
    """A line of 4097 characters is an error naming its line (4096 pass:
    test_deck_features); it is not quoted, being too long to help."""
    deck = replace("5, 1, 1\n", "5, 1, 1" + " " * (4097 - 7) + "\n")
    run = run_bounded("bad_line_too_long", deck)
    assert_clean_failure(run, "long line")
    assert f"{run.deck}:{line_of(deck, '5, 1, 1')}: error: line longer than 4096 characters" in run.stderr, \
        run.stderr
