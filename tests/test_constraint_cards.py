"""*PRE-TENSION SECTION and *TIE, the CalculiX cards that generate linear
constraints: bad cards stop the run at their line with the reason; the
generated equations themselves are checked term by term in
tests/unit/test_constraints.f90."""
from helpers import run_deck

# Two plane-strain quads side by side (CalculiX's pret5 shape), node 7 a
# free reference node; element 1's face S2 (x = 1) is the cut.
PRET = """*NODE
1, 0., 0.
2, 1., 0.
3, 2., 0.
4, 0., 1.
5, 1., 1.
6, 2., 1.
7, 0., 0.
*ELEMENT, TYPE=CPE4, ELSET=EALL
1, 1, 2, 5, 4
2, 2, 3, 6, 5
*BOUNDARY
1, 1, 2
3, 1, 2
4, 1, 2
6, 1, 2
*MATERIAL, NAME=EL
*ELASTIC
210000., .3
*SOLID SECTION, ELSET=EALL, MATERIAL=EL
.1
*SURFACE, NAME=SURF1
1, S2
*SURFACE, NAME=NODES, TYPE=NODE
2, 5
*NSET, NSET=TWO
2, 7
{card}*STEP
*STATIC
*CLOAD
7, 1, -10.
*END STEP
"""


def stops_at(name, card, bad_line, fragment):
    """The deck with `card` stops with file:line: error naming bad_line."""
    deck = PRET.format(card=card)
    run = run_deck(name, deck)
    line = deck.splitlines().index(bad_line) + 1
    assert run.rc == 1 and f"{name}.inp:{line}: error:" in run.stderr, run.stderr
    assert fragment in run.stderr, run.stderr
    return run


def test_pretension_bad_cards_stop_at_their_line():
    """ELEMENT= (a B31 beam), a node surface, an undefined surface, a node
    set of two nodes, a normal out of the plane or of zero length, and a
    reference node that belongs to an element are errors at the card."""
    cases = (
        ("elem", "*PRE-TENSION SECTION, ELEMENT=1, NODE=7\n", "B31 beam"),
        ("both", "*PRE-TENSION SECTION, ELEMENT=1, SURFACE=SURF1, NODE=7\n", "mutually exclusive"),
        ("nodes", "*PRE-TENSION SECTION, SURFACE=NODES, NODE=7\n", "element faces, not of nodes"),
        ("undef", "*PRE-TENSION SECTION, SURFACE=NONE, NODE=7\n", "undefined surface NONE"),
        ("noref", "*PRE-TENSION SECTION, SURFACE=SURF1\n", "needs NODE="),
        ("set2", "*PRE-TENSION SECTION, SURFACE=SURF1, NODE=TWO\n", "exactly one node"),
        ("inelem", "*PRE-TENSION SECTION, SURFACE=SURF1, NODE=5\n", "belongs to element"),
    )
    for tag, card, fragment in cases:
        stops_at("pret_" + tag, card, card.strip(), fragment)
    for tag, normal, fragment in (("nz", "0., 0., 1.", "no component in the x-y plane"),
                                  ("tilt", "1., 0., 1.", "must lie in the x-y plane"),
                                  ("two", "1.", "needs the normal")):
        stops_at("pret_" + tag, f"*PRE-TENSION SECTION, SURFACE=SURF1, NODE=7\n{normal}\n", normal, fragment)


def test_pretension_twice_on_one_node_or_surface():
    """A reference node serves one section, a surface is cut once: the
    second card is the error, naming the first card's line."""
    first = "*PRE-TENSION SECTION, SURFACE=SURF1, NODE=7\n"
    card = first + "*NODE\n8, 0., 0.\n*PRE-TENSION SECTION, SURFACE=SURF1, NODE=8\n"
    line = PRET.format(card=card).splitlines().index(first.strip()) + 1
    stops_at("pret_twice", card, "*PRE-TENSION SECTION, SURFACE=SURF1, NODE=8", f"of line {line}")
    card = first + "*SURFACE, NAME=OTHER\n2, S4\n*PRE-TENSION SECTION, SURFACE=OTHER, NODE=7\n"
    stops_at("pret_ref_twice", card, "*PRE-TENSION SECTION, SURFACE=OTHER, NODE=7", "already serves")


def test_pretension_normals_that_cancel_need_a_data_line():
    """Faces facing opposite ways have no mean normal: the card says to
    give one."""
    card = "*SURFACE, NAME=BOTH\n1, S2\n2, S4\n*PRE-TENSION SECTION, SURFACE=BOTH, NODE=7\n"
    stops_at("pret_cancel", card, "*PRE-TENSION SECTION, SURFACE=BOTH, NODE=7", "give the normal on a data line")


def test_pretension_on_an_empty_surface_is_an_error():
    """A surface made only of an empty element set (a warning at its line)
    has no faces to cut: the *PRE-TENSION SECTION naming it stops the run,
    as a reference node in no element could not be what was meant."""
    card = "*ELSET, ELSET=NOTHING\n*SURFACE, NAME=HOLLOW\nNOTHING, S2\n*PRE-TENSION SECTION, SURFACE=HOLLOW, NODE=7\n1., 0.\n"
    run = stops_at("pret_empty", card, "*PRE-TENSION SECTION, SURFACE=HOLLOW, NODE=7",
                   "surface HOLLOW is empty: *PRE-TENSION SECTION has no faces to cut")
    assert "warning: element set NOTHING is empty: *SURFACE does nothing for it" in run.stderr, run.stderr


def test_pretension_keyword_without_blanks():
    """CalculiX drops the blanks of a keyword line: *PRE-TENSIONSECTION is
    the same card (it reaches the same check)."""
    stops_at("pret_packed", "*PRE-TENSIONSECTION, ELEMENT=1, NODE=7\n", "*PRE-TENSIONSECTION, ELEMENT=1, NODE=7",
             "B31 beam")


def test_tie_bad_cards_stop_at_their_line():
    """NAME= is required and unique; CYCLIC SYMMETRY and MULTISTAGE are
    not implemented; ADJUST is YES or NO; the tolerance is not negative;
    the master is an element surface; one data line of two surfaces."""
    cases = (
        ("noname", "*TIE\nNODES, SURF1\n", "*TIE", "needs NAME="),
        ("cyclic", "*TIE, NAME=T, CYCLIC SYMMETRY\nNODES, SURF1\n", "*TIE, NAME=T, CYCLIC SYMMETRY",
         "not implemented"),
        ("adjust", "*TIE, NAME=T, ADJUST=MAYBE\nNODES, SURF1\n", "*TIE, NAME=T, ADJUST=MAYBE", "YES or NO"),
        ("tol", "*TIE, NAME=T, POSITION TOLERANCE=-1.\nNODES, SURF1\n", "*TIE, NAME=T, POSITION TOLERANCE=-1.",
         "must not be negative"),
        ("master", "*TIE, NAME=T\nSURF1, NODES\n", "SURF1, NODES", "element faces"),
        ("same", "*TIE, NAME=T\nSURF1, SURF1\n", "SURF1, SURF1", "same surface"),
        ("undef", "*TIE, NAME=T\nNONE, SURF1\n", "NONE, SURF1", "undefined surface NONE"),
        ("fields", "*TIE, NAME=T\nNODES\n", "NODES", "slave surface, master surface"),
        ("lines", "*TIE, NAME=T\nNODES, SURF1\nNODES, SURF1\n", "NODES, SURF1", "one data line"),
        ("nodata", "*TIE, NAME=T\n", "*TIE, NAME=T", "missing data line"),
        ("twice", "*TIE, NAME=T\nNODES, SURF1\n*TIE, NAME=t\nNODES, SURF1\n", "*TIE, NAME=t", "duplicate tie"),
    )
    for tag, card, bad, fragment in cases:
        deck = PRET.format(card=card)
        name = "tie_" + tag
        run = run_deck(name, deck)
        lines = deck.splitlines()
        line = len(lines) - lines[::-1].index(bad) if tag == "lines" else lines.index(bad) + 1
        assert run.rc == 1 and f"{name}.inp:{line}: error:" in run.stderr, (tag, run.stderr)
        assert fragment in run.stderr, (tag, run.stderr)
