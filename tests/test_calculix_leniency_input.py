"""CalculiX's leniency in reading a deck (issue 28), each checked against
the plain deck's answer (to the bit: the same model read another way
must give the same numbers): node numbers in a *NSET that the deck never
defines are dropped with one warning that counts them; a node line
repeated keeps the later coordinates; text on the *HEADING line;
*ELASTIC, TYPE=ISO; *STEP, PERTURBATION as the first step; and a node,
element, set, surface, material or amplitude used before the card that
defines it, since CalculiX reads those cards first. What CalculiX 2.20
does with each was tried on these decks once (tests/calculix/README.md,
"leniency of reading")."""
from helpers import run_deck

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


def warnings(run):
    return [ln for ln in run.stderr.splitlines() if ": warning: " in ln]


def answer(run):
    inc = run.listing.increments[-1]
    u, rf = inc.block("NODE U", set="ALLN"), inc.block("NODE RF", set="ALLN")
    return {int(n): (a, b, c, d) for n, a, b, c, d in zip(u["node"], u["U1"], u["U2"], rf["RF1"], rf["RF2"])}


_PLAIN = {}


def plain():
    if "run" not in _PLAIN:
        _PLAIN["run"] = run_deck("lenient_input_plain", BAR).ok()
    return _PLAIN["run"]


def test_undefined_nodes_in_a_node_set_are_dropped_with_one_warning():
    """*NSET lists naming nodes the deck never defines (77, 78; 99; and 7,
    8, 9 of a GENERATE range): CalculiX 2.20 drops each ("value 77 in set
    LEFT > nk"); cfe2d drops them with one warning at the first such line
    that counts them (6) and names five, and the answer is the bar's to
    the bit. A set left empty by the dropping warns where a card uses it,
    as any empty set."""
    deck = replace("1, 4\n", "1, 4, 77, 78\n*NSET, NSET=MORE\n99\n*NSET, NSET=GEN, GENERATE\n5, 9\n")
    deck = replace("*END STEP", "*NODE PRINT, NSET=MORE\nU\n*END STEP", deck)
    run = run_deck("lenient_nset_undefined_nodes", deck).ok()
    assert sorted(warnings(run)) == sorted([
        f"{run.deck}:{line_of(deck, '1, 4, 77, 78')}: warning: 6 node numbers in *NSET lists name no node of the "
        "deck (77, 78, 99, 7, 8 and 1 more): dropped from their sets, as CalculiX does",
        f"{run.deck}:{line_of(deck, '*NODE PRINT, NSET=MORE')}: warning: node set MORE is empty: *NODE PRINT does "
        "nothing for it"]), run.stderr
    assert answer(run) == answer(plain())


def test_a_repeated_node_line_keeps_the_later_coordinates():
    """A node defined twice (a mesh file and a correction after it, or an
    include read twice): CalculiX 2.20 keeps the later line's coordinates
    (measured: its answer is that of the deck with the later line only);
    cfe2d does the same, with one warning at the first repeat that counts
    them. Node 5 first at (1, 1.5), then at (1, 1): the bar's answer to
    the bit; the other way round: the answer of the bar with node 5 at
    (1, 1.5), which differs."""
    first = replace("5, 1, 1\n6, 2, 1\n", "5, 1, 1.5\n6, 2, 1\n5, 1, 1\n")
    run = run_deck("lenient_repeated_node", first).ok()
    assert warnings(run) == [f"{run.deck}:{line_of(first, '5, 1, 1') + 2}: warning: 1 node line defines a node "
                             "again: the later coordinates win, as in CalculiX"], run.stderr
    assert answer(run) == answer(plain())
    moved = replace("5, 1, 1\n", "5, 1, 1.5\n")
    later = replace("6, 2, 1\n", "6, 2, 1\n5, 1, 1.5\n")
    a = answer(run_deck("lenient_repeated_node_later", later).ok())
    b = answer(run_deck("lenient_repeated_node_moved", moved).ok())
    assert a == b and a != answer(plain())


def test_heading_text_on_the_keyword_line():
    """`*HEADING my title` (CalculiX reads the rest of the line as a
    heading): the listing's heading is that text, commas and case kept;
    a title on the data line still works, and the answer is the bar's."""
    deck = replace("*HEADING\ntwo-element bar\n", "*Heading  Bar, two CPS4 elements\n")
    run = run_deck("lenient_heading_inline", deck).ok()
    assert warnings(run) == [], run.stderr
    assert "heading Bar, two CPS4 elements\n" in open(run.listing_path).read()
    assert answer(run) == answer(plain())
    assert "heading two-element bar\n" in open(plain().listing_path).read()


def test_elastic_type_iso_and_step_perturbation():
    """*ELASTIC, TYPE=ISO is TYPE=ISOTROPIC (CalculiX compares three
    letters); *STEP, PERTURBATION as the first step is a linear step
    about the unloaded model (CalculiX 2.20's answer on the bar is its
    answer without PERTURBATION, measured): both give the bar's answer to
    the bit without a warning. TYPE=ORTHO with E, nu is an error (it
    takes nine constants: tests/test_orthotropic.py); a PERTURBATION
    step after another step (a perturbation about a loaded state) is an
    error at its line."""
    deck = replace("*ELASTIC\n", "*ELASTIC, TYPE=ISO\n")
    deck = replace("*STEP\n", "*STEP, PERTURBATION\n", deck)
    run = run_deck("lenient_iso_perturbation", deck).ok()
    assert warnings(run) == [], run.stderr
    assert answer(run) == answer(plain())
    run = run_deck("lenient_ortho", replace("*ELASTIC\n", "*ELASTIC, TYPE=ORTHO\n"))
    assert run.rc == 1 and "9 elastic constants" in run.stderr, run.stderr
    second = BAR + "*STEP, PERTURBATION\n*STATIC\n*END STEP\n"
    run = run_deck("lenient_perturbation_second", second)
    assert run.rc == 1, run.stderr
    assert f"{run.deck}:{len(BAR.splitlines()) + 1}: error: PERTURBATION after another step" in run.stderr, run.stderr


# The bar with its cards in an order CalculiX 2.20 accepts (tried once: its
# answer is its answer on the bar): the support before its node set, the
# section before its elements and material, the elements before the
# nodes, an amplitude used before it is defined, the node set and the
# material after the step.
REORDERED = """*HEADING
two-element bar, reordered
*BOUNDARY
LEFT, 1, 2
*SOLID SECTION, ELSET=BAR, MATERIAL=STEEL
1.
*ELEMENT, TYPE=CPS4, ELSET=BAR
1, 1, 2, 5, 4
2, 2, 3, 6, 5
*NODE, NSET=ALLN
1, 0, 0
2, 1, 0
3, 2, 0
4, 0, 1
5, 1, 1
6, 2, 1
*STEP
*STATIC
*CLOAD, AMPLITUDE=DOUBLE
3, 1, 2.5
*NODE PRINT, NSET=ALLN
U, RF
*END STEP
*AMPLITUDE, NAME=DOUBLE
0., 0., 1., 2.
*NSET, NSET=LEFT
1, 4
*MATERIAL, NAME=STEEL
*ELASTIC
1000., 0.25
"""


def test_cards_may_use_what_later_cards_define():
    """CalculiX reads a deck's nodes, elements, sets, surfaces, materials
    and amplitudes before its other cards, so a card may name one that is
    defined further down: the reordered bar (REORDERED) runs without a
    warning and gives the bar's answer to the bit (a load of 2.5 at an
    amplitude reaching 2 is the bar's 5). The blocks example with its
    *SURFACE moved to the end of the deck (after the *CONTACT PAIR and the
    steps) gives the same contact table, to the character, and as many
    warnings. A name defined nowhere is still an error at the line that
    uses it."""
    run = run_deck("lenient_reordered", REORDERED).ok()
    assert warnings(run) == [], run.stderr
    assert answer(run) == answer(plain())
    import os
    from helpers import ROOT
    path = os.path.join(ROOT, "input", "examples", "blocks.inp")
    text = open(path).read()
    lines = text.splitlines(keepends=True)
    # move every *SURFACE card (with its data lines) to the end of the deck
    moved, rest, k = [], [], 0
    while k < len(lines):
        if lines[k].upper().startswith("*SURFACE,") or lines[k].upper().startswith("*SURFACE\n"):
            block = [lines[k]]
            k += 1
            while k < len(lines) and not lines[k].startswith("*"):
                block.append(lines[k])
                k += 1
            moved += block
            continue
        rest.append(lines[k])
        k += 1
    assert moved, "blocks.inp has no *SURFACE card"
    reordered = "".join(rest) + "".join(moved)
    a = run_deck("lenient_blocks_reordered", reordered).ok()
    b = run_deck("lenient_blocks_plain", path=path).ok()
    assert len(warnings(a)) == len(warnings(b)), (a.stderr, b.stderr)
    ca = open(a.listing_path.replace(".out", "_contact.csv")).read()
    cb = open(b.listing_path.replace(".out", "_contact.csv")).read()
    assert ca == cb
    bad = REORDERED.replace("*NSET, NSET=LEFT", "*NSET, NSET=LEFTSIDE")
    run = run_deck("lenient_reordered_undefined", bad)
    assert run.rc == 1 and f"{run.deck}:4: error: undefined node set LEFT" in run.stderr, run.stderr
