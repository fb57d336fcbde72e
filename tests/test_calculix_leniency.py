"""What CalculiX accepts and cfe2d used to refuse (issue 20): an empty
*NODE block and an empty *SURFACE (cgx writes both for a set without
nodes or faces of its own), nodes that belong to no element (left over
from meshing), CENTRIF about an axis in the plane of plane elements; and
the message for CalculiX's temperature dof 11. Each is accepted with a
warning at its line, or refused with an error naming the line."""
import os

from helpers import rel_err, run_deck

BAR = """*HEADING
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
*NODE PRINT, NSET=ALLN
U, RF
*END STEP
"""


def replace(old, new, deck=BAR):
    assert old in deck, old
    return deck.replace(old, new, 1)


def line_of(text, fragment):
    for k, line in enumerate(text.splitlines(), 1):
        if fragment in line:
            return k
    raise AssertionError(fragment)


def displacements(run, nset="ALLN"):
    u = run.listing.increments[-1].block("NODE U", set=nset)
    return {int(n): (a, b) for n, a, b in zip(u["node"], u["U1"], u["U2"])}


def same_answer(run, plain):
    """run's displacements of the bar's nodes are plain's, to the bit."""
    got, want = displacements(run), displacements(plain)
    for node in range(1, 7):
        assert got[node] == want[node], (node, got[node], want[node])


def test_empty_node_block_warns():
    """*NODE without data lines (cgx writes `*NODE, NSET=N` for a set with
    no nodes of its own) defines nothing: a warning at its line, in the
    deck or in an included file; its node set exists, empty (a card naming
    it warns as for any empty set), and the answer is the bar's."""
    mesh = "** written by cgx\n*NODE, NSET=NONE\n"
    deck = replace("*ELEMENT", "*NODE\n*INCLUDE, INPUT=empty_nodes.inp\n*ELEMENT")
    deck = replace("*END STEP", "*NODE PRINT, NSET=NONE\nU\n*END STEP", deck)
    run = run_deck("empty_node_block", deck, files={"empty_nodes.inp": mesh}).ok()
    inc = os.path.join(os.path.dirname(run.deck), "empty_nodes.inp")
    assert f"{run.deck}:{deck.splitlines().index('*NODE') + 1}: warning: *NODE without data lines defines " \
           "no node\n" in run.stderr, run.stderr
    assert f"{inc}:2: warning: *NODE without data lines defines no node (node set NONE gets none)" in run.stderr, \
        run.stderr
    assert f"{run.deck}:{line_of(deck, '*NODE PRINT, NSET=NONE')}: warning: node set NONE is empty" in run.stderr
    assert "error" not in run.stderr, run.stderr
    same_answer(run, run_deck("empty_node_block_plain", BAR).ok())


def test_empty_surface_warns():
    """A *SURFACE without data lines (cgx's .sur file of a set without
    faces) is an empty surface: a warning at its line in the included
    file, element and node surfaces alike. Unused, it changes nothing;
    used by a *CONTACT PAIR (as slave or master) or a *DSLOAD, each use
    warns at its own line as for any empty surface, and the run goes on
    with the answer of the bar."""
    sur = "** written by cgx\n*SURFACE, NAME=SEMPTY, TYPE=ELEMENT\n*SURFACE, NAME=NEMPTY, TYPE=NODE\n" \
          "*SURFACE, NAME=UNUSED\n"
    deck = replace("*NSET, NSET=LEFT", "*INCLUDE, INPUT=empty.sur\n*SURFACE, NAME=RIGHT\nBAR, S2\n"
                   "*NSET, NSET=LEFT")
    plain = run_deck("empty_surface_plain", deck, files={"empty.sur": sur}).ok()
    inc = os.path.join(os.path.dirname(plain.deck), "empty.sur")
    for k, name in ((2, "SEMPTY"), (3, "NEMPTY"), (4, "UNUSED")):
        message = f"{inc}:{k}: warning: *SURFACE without data lines: surface {name} is empty"
        assert plain.stderr.count(message) == 1, plain.stderr
    assert "error" not in plain.stderr, plain.stderr
    same_answer(plain, run_deck("empty_surface_bar", BAR).ok())

    used = replace("*BOUNDARY", "*CONTACT PAIR\nSEMPTY, RIGHT\nNEMPTY, RIGHT\nRIGHT, SEMPTY\n*BOUNDARY", deck)
    used = replace("*NODE PRINT", "*DSLOAD\nSEMPTY, P, 3.\n*NODE PRINT", used)
    run = run_deck("empty_surface_used", used, files={"empty.sur": sur}).ok()
    for text, what, card in (("SEMPTY, RIGHT", "SEMPTY", "*CONTACT PAIR"), ("NEMPTY, RIGHT", "NEMPTY", "*CONTACT PAIR"),
                             ("RIGHT, SEMPTY", "SEMPTY", "*CONTACT PAIR"), ("SEMPTY, P, 3.", "SEMPTY", "*DSLOAD")):
        message = f"{run.deck}:{line_of(used, text)}: warning: surface {what} is empty: {card} does nothing for it"
        assert message in run.stderr, (message, run.stderr)
    same_answer(run, plain)


def test_temperature_dof_says_heat_transfer_is_not_part_of_cfe2d():
    """CalculiX's dof 11 is the temperature: a *BOUNDARY on it (a
    prescribed temperature) or a *CLOAD on it (a heat flux) belongs to a
    heat transfer analysis. The error names the line and says so, instead
    of the generic message about dofs 1 and 2."""
    cases = [("bc_dof11", replace("LEFT, 1, 2", "LEFT, 1, 2\nLEFT, 11, 11, 293."), "LEFT, 11, 11, 293.",
              "*BOUNDARY on it is a prescribed temperature"),
             ("bc_dof11_alone", replace("LEFT, 1, 2", "LEFT, 1, 2\n4, 11"), "4, 11",
              "*BOUNDARY on it is a prescribed temperature"),
             ("cload_dof11", replace("3, 1, 5.", "3, 11, 5."), "3, 11, 5.",
              "*CLOAD on it is a concentrated heat flux")]
    for name, deck, text, fragment in cases:
        run = run_deck(name, deck)
        assert run.rc == 1, (name, run.stderr)
        assert f"{run.deck}:{line_of(deck, text)}: error: dof 11 is the temperature" in run.stderr, run.stderr
        assert fragment in run.stderr and "heat transfer is not part of cfe2d" in run.stderr, run.stderr
        assert "dofs must satisfy" not in run.stderr and "dof must be 1 or 2" not in run.stderr, run.stderr
    # other dofs keep the generic message
    run = run_deck("bc_dof7", replace("LEFT, 1, 2", "LEFT, 7, 7"))
    assert run.rc == 1 and "dofs must satisfy" in run.stderr, run.stderr
