"""A battery of broken decks: each must stop cfe2d with a non-zero exit and
a message "file:line: error: ..." naming the offending line, and never with
a crash or a Fortran runtime error."""
import os

from helpers import run_deck

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
    ("unimplemented Abaqus keyword", replace("*CLOAD", "*DLOAD\n1, P, 3.\n*CLOAD"), "*DLOAD", "*DLOAD is not implemented"),
    ("unknown parameter", replace("*NODE, NSET=ALLN", "*NODE, NSET=ALLN, COLOUR=RED"), "COLOUR", "unknown parameter COLOUR"),
    ("malformed number", replace("5, 1, 1\n", "5, 1, 1.x\n"), "5, 1, 1.x", '"1.x" is not a number'),
    ("missing coordinate", replace("5, 1, 1\n", "5, 1\n"), "5, 1", "needs: node id, x, y"),
    ("missing data line", replace("*ELASTIC\n1000., 0.25\n", "*ELASTIC\n"), "*ELASTIC", "missing data line"),
    ("undefined node", replace("2, 2, 3, 6, 5", "2, 2, 3, 66, 5"), "2, 2, 3, 66, 5", "undefined node 66"),
    ("undefined node set", replace("LEFT, 1, 2", "LEFTSIDE, 1, 2"), "LEFTSIDE", "undefined node set LEFTSIDE"),
    ("undefined material", replace("MATERIAL=STEEL", "MATERIAL=IRON"), "MATERIAL=IRON", "undefined material IRON"),
    ("duplicate node", replace("6, 2, 1\n", "6, 2, 1\n5, 3, 3\n"), "5, 3, 3", "duplicate node id 5"),
    ("duplicate element", replace("2, 2, 3, 6, 5\n", "2, 2, 3, 6, 5\n1, 2, 3, 6, 5\n"), "1, 2, 3, 6, 5", "duplicate element id 1"),
    ("clockwise element", replace("2, 2, 3, 6, 5", "2, 2, 5, 6, 3"), "2, 2, 5, 6, 3", "negative Jacobian"),
    ("degenerate element", replace("2, 2, 3, 6, 5", "2, 2, 3, 3, 5"), "2, 2, 3, 3, 5", "same node twice"),
    ("unimplemented element type", replace("TYPE=CPS4", "TYPE=C3D8"), "TYPE=C3D8", "C3D8 is not implemented"),
    ("wrong node count", replace("1, 1, 2, 5, 4", "1, 1, 2, 5"), "1, 1, 2, 5", "needs an id and 4 nodes"),
    ("step without end", replace("*END STEP\n", ""), "*STEP", "without *END STEP"),
    ("load outside step", replace("*STEP", "*CLOAD\n3, 1, 1.\n*STEP"), "*CLOAD", "must be inside *STEP"),
    ("dof out of range", replace("LEFT, 1, 2", "LEFT, 1, 3"), "LEFT, 1, 3", "dofs must satisfy"),
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
]


def check(name, deck, text, fragment, files=None, where=None):
    tag = "bad_" + "".join(c if c.isalnum() else "_" for c in name)
    run = run_deck(tag, deck, files=files)
    assert run.rc != 0, f"exit status 0 for a bad deck ({name})"
    err = run.stderr
    for bad in ("Fortran runtime error", "Backtrace", "Segmentation", "SIGSEGV", "STOP"):
        assert bad not in err, f"crash-like output: {err!r}"
    fname = where or run.deck
    lineno = line_of(open(fname).read(), text)
    expect = f"{fname}:{lineno}: error:"
    assert expect in err, f"expected '{expect}' in stderr, got:\n{err}"
    assert fragment in err, f"expected '{fragment}' in stderr, got:\n{err}"
    assert text.strip() in err, f"offending line not quoted:\n{err}"


def cases():
    for name, deck, text, frag in CASES:
        yield f"bad deck: {name}", (lambda d=deck, t=text, f=frag, n=name: check(n, d, t, f))


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
