"""Contact cards as CalculiX and Abaqus write them (*SURFACE INTERACTION,
*SURFACE BEHAVIOR, *FRICTION, *CONTACT PAIR with INTERACTION=, TYPE=,
SMALL SLIDING, ADJUST=) against cfe2d's own *CONTACT PAIR on the two
blocks of tests/test_contact.py: the same answer to the last digit where
the cards mean the same thing, the closed-form one where ADJUST changes
the geometry, and an error naming the line where cfe2d cannot follow."""
import numpy as np

from decks import grid, node_lines, quad_lines
from helpers import rel_err, run_deck

E, NU, W, H1, H2, G0 = 1000.0, 0.3, 1.0, 1.0, 1.0, 0.01
NX1, NY1, NX2, NY2 = 5, 5, 10, 4
K = 2.0e5          # a LINEAR slope: pressure per unit overclosure


def blocks(contact, push=3 * G0, extra=""):
    """Lower block (master surface MASTER) and upper block G0 above it
    (slave node set SLAVE, slave face surface UPPERFACE), pushed down by
    `push`; `contact` holds the contact cards."""
    n1, ids1, q1 = grid(NX1, NY1, 0.0, W, 0.0, H1)
    n2, ids2, q2 = grid(NX2, NY2, 0.0, W, H1 + G0, H1 + G0 + H2, first_node=1001)
    bottom1 = [ids1[i, 0] for i in range(NX1 + 1)]
    bottom2 = [ids2[i, 0] for i in range(NX2 + 1)]
    top2 = [ids2[i, NY2] for i in range(NX2 + 1)]
    top_elems = [NX1 * (NY1 - 1) + i + 1 for i in range(NX1)]
    bottom_elems = [1001 + i for i in range(NX2)]
    return f"""*HEADING
two blocks, CalculiX-style contact cards
*NODE, NSET=ALLN
{node_lines({**n1, **n2})}*ELEMENT, TYPE=CPS4, ELSET=LOWER
{quad_lines(q1, 1)}*ELEMENT, TYPE=CPS4, ELSET=UPPER
{quad_lines(q2, 1001)}*NSET, NSET=GROUND
{", ".join(map(str, bottom1))}
*NSET, NSET=ANCHOR
{bottom1[0]}
*NSET, NSET=SLAVE
{", ".join(map(str, bottom2))}
*NSET, NSET=TOP
{", ".join(map(str, top2))}
*NSET, NSET=TOPLEFT
{top2[0]}
*ELSET, ELSET=LOWERTOP
{", ".join(map(str, top_elems))}
*ELSET, ELSET=UPPERBOTTOM
{", ".join(map(str, bottom_elems))}
*SURFACE, NAME=MASTER
LOWERTOP, S3
*SURFACE, NAME=UPPERFACE
UPPERBOTTOM, S1
*MATERIAL, NAME=M
*ELASTIC
{E}, {NU}
*SOLID SECTION, ELSET=LOWER, MATERIAL=M
1.
*SOLID SECTION, ELSET=UPPER, MATERIAL=M
1.
{extra}{contact}*BOUNDARY
GROUND, 2, 2
ANCHOR, 1, 1
TOPLEFT, 1, 1
*STEP
*STATIC
0.5, 1.0
*BOUNDARY
TOP, 2, 2, {-push}
*NODE PRINT, NSET=TOP
U
*EL PRINT, ELSET=UPPER
S
*END STEP
"""


def interaction(law="LINEAR", data=f"{K}, 0.01, 1e-3", name="SI1", friction=""):
    text = f"*SURFACE INTERACTION, NAME={name}\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE={law}\n"
    if data:
        text += data + "\n"
    return text + friction


def last(run):
    inc = run.listing.increments[-1]
    return inc.block("CONTACT SLAVE", pair=1), inc.block("CONTACT SUMMARY", pair=1), inc


def same_answer(a, b):
    """Two runs agree to the last printed digit (16 significant)."""
    sa, ma, ia = last(a)
    sb, mb, ib = last(b)
    assert np.array_equal(sa["pressure"], sb["pressure"]), (sa["pressure"], sb["pressure"])
    assert np.array_equal(ia.block("ELEMENT S", set="UPPER")["S22"], ib.block("ELEMENT S", set="UPPER")["S22"])
    assert ma["total_force"][0] == mb["total_force"][0]


def test_linear_slope_is_the_penalty_per_area():
    """PRESSURE-OVERCLOSURE=LINEAR, K: the same answer as PENALTY=K, and
    the penetration is the pressure over K (the overclosure law)."""
    own = run_deck("decks_own_penalty", blocks(f"*CONTACT PAIR, PENALTY={K}\nSLAVE, MASTER\n")).ok()
    ccx = run_deck("decks_linear", blocks(
        interaction() + "*CONTACT PAIR, INTERACTION=SI1, TYPE=NODE TO SURFACE, SMALL SLIDING\nSLAVE, MASTER\n")).ok()
    same_answer(own, ccx)
    slave, summ, _ = last(ccx)
    p = float(np.mean(slave["pressure"]))
    assert rel_err(summ["max_penetration"][0], p / K) < 0.02, (summ["max_penetration"][0], p / K)


def test_hard_is_exact_enforcement_and_friction_zero_frictionless():
    """HARD (no data line) = cfe2d's exact enforcement (EXACT, the automatic
    penalty only setting the pace of the multiplier updates): the same
    answer, the pressure of the series blocks with no penetration; *FRICTION
    with a zero coefficient is frictionless; no warning."""
    own = run_deck("decks_own_auto", blocks("*CONTACT PAIR, EXACT\nSLAVE, MASTER\n")).ok()
    deck = blocks(interaction("HARD", "", friction="*FRICTION\n0., 1e4\n") +
                  "*CONTACT PAIR, INTERACTION=SI1, SMALL SLIDING\nSLAVE, MASTER\n")
    ccx = run_deck("decks_hard", deck).ok()
    same_answer(own, ccx)
    assert "warning" not in ccx.stderr, ccx.stderr
    slave, summ, _ = last(ccx)
    p = E * (3 * G0 - G0) / (H1 + H2)
    assert max(abs(slave["pressure"] - p)) < 1e-8 * p, slave["pressure"]
    assert abs(summ["max_penetration"][0]) < 1e-10 * G0, summ["max_penetration"][0]


def test_surface_to_surface_is_segment_to_segment_on_any_densities():
    """TYPE=SURFACE TO SURFACE is the segment-to-segment (mortar) coupling,
    one pass, on meshes of any density (here 2:1): the same answer as
    cfe2d's own pair with TYPE=SURFACE TO SURFACE and PENALTY=K, the
    pressure uniform (the contact patch test) and that of the series
    springs 2 / E and 1 / K. SYMMETRIC asked for on the same meshes is
    refused, saying why. The *SURFACE INTERACTION comes after the pair, as
    in CalculiX's ring1.inp."""
    own = run_deck("decks_own_s2s", blocks(f"*CONTACT PAIR, TYPE=SURFACE TO SURFACE, PENALTY={K}\n"
                                           "UPPERFACE, MASTER\n")).ok()
    ccx = run_deck("decks_s2s", blocks(
        "*CONTACT PAIR,INTERACTION=SI1,TYPE=SURFACE TO SURFACE\nUPPERFACE,MASTER\n" + interaction())).ok()
    assert "warning" not in ccx.stderr, ccx.stderr
    same_answer(own, ccx)
    slave, summ, _ = last(ccx)
    p = (3 * G0 - G0) / ((H1 + H2) / E + 1.0 / K)
    assert max(abs(slave["pressure"] - p)) < 1e-9 * p, (slave["pressure"], p)
    assert rel_err(summ["total_force"][0], p * W) < 1e-9, summ["total_force"][0]
    sym = run_deck("decks_own_symmetric", blocks(f"*CONTACT PAIR, SYMMETRIC, PENALTY={K / 2}\nUPPERFACE, MASTER\n"))
    assert sym.rc == 1 and "same density" in sym.stderr, sym.stderr


def test_adjust_moves_slave_nodes_onto_the_master():
    """ADJUST=0.02 closes the 0.01 gap before the analysis: the pressure is
    that of blocks in contact from the start, E d / (H1 + H2); ADJUST=0.005
    (less than the gap) moves nothing; ADJUST=<node set> moves the set."""
    pair = "*CONTACT PAIR, INTERACTION=SI1, SMALL SLIDING, ADJUST={}\nSLAVE, MASTER\n"
    d = 3 * G0
    for tag, value, p in (("far", "0.02", E * d / (H1 + H2)), ("set", "SLAVE", E * d / (H1 + H2)),
                          ("near", "0.005", E * (d - G0) / (H1 + H2))):
        run = run_deck("decks_adjust_" + tag, blocks(interaction("HARD", "") + pair.format(value), push=d)).ok()
        slave, summ, _ = last(run)
        assert max(abs(slave["pressure"] - p)) / p < 0.01, (tag, slave["pressure"], p)
        moved = 0 if tag == "near" else NX2 + 1
        assert f"ADJUST moved {moved} slave node(s)" in run.stderr, (tag, run.stderr)


def error_at(name, deck, line_text, fragment):
    run = run_deck(name, deck)
    assert run.rc == 1, (name, run.rc, run.stderr)
    line = deck.splitlines().index(line_text) + 1
    assert f"{name}.inp:{line}: error:" in run.stderr, (name, run.stderr)
    assert fragment in run.stderr, (name, run.stderr)


def test_what_cfe2d_cannot_do_stops_at_the_card():
    pair = "*CONTACT PAIR, INTERACTION=SI1\nSLAVE, MASTER\n"
    error_at("decks_friction", blocks(interaction(friction="*FRICTION, ROUGH\n0.2\n") + pair), "*FRICTION, ROUGH",
             "ROUGH (no slip at all) is not implemented")
    # soft laws (tests/test_soft_contact.py) stop on data they cannot hold
    error_at("decks_exponential", blocks(interaction("EXPONENTIAL", "-1e-3, 10.") + pair),
             "-1e-3, 10.", "c0 must be a positive clearance")
    error_at("decks_tabular", blocks(interaction("TABULAR", "0., 0.\n100., 0.01\n50., 0.02") + pair),
             "50., 0.02", "the pressures of a TABULAR law must increase")
    error_at("decks_tied", blocks(interaction("TIED", "1e5") + pair),
             "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TIED", "TIED")
    error_at("decks_mortar", blocks(interaction() + "*CONTACT PAIR, INTERACTION=SI1, TYPE=MORTAR\nUPPERFACE, MASTER\n"),
             "*CONTACT PAIR, INTERACTION=SI1, TYPE=MORTAR", "MORTAR")
    error_at("decks_no_interaction", blocks("*CONTACT PAIR, INTERACTION=SI9\nSLAVE, MASTER\n"),
             "*CONTACT PAIR, INTERACTION=SI9", "undefined surface interaction SI9")
    error_at("decks_both_penalties", blocks(interaction() + "*CONTACT PAIR, INTERACTION=SI1, PENALTY=1e5\n"
                                            "SLAVE, MASTER\n"),
             "*CONTACT PAIR, INTERACTION=SI1, PENALTY=1e5", "either INTERACTION= or PENALTY=")
    # the block ends at the first card that does not describe it
    error_at("decks_behavior_outside", blocks(
        "*SURFACE INTERACTION, NAME=SI1\n*NSET, NSET=X\n1\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD\n" + pair),
        "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD", "outside a *SURFACE INTERACTION block")
    error_at("decks_nlgeom", blocks("*CONTACT PAIR\nSLAVE, MASTER\n").replace("*STEP\n", "*STEP, NLGEOM=MAYBE\n"),
             "*STEP, NLGEOM=MAYBE", "NLGEOM must be YES or NO")
