"""*TIE, TYPE=SURFACE TO SURFACE: the mortar tie (dual mortar weights, the
same integration as segment-to-segment contact, src/contact/
tie_constraints.f90). The tied patch test of test_constraint_decks: a
uniform stress (S11 = 2, S22 = 3) across a non-matching interface, the
slave side finer or coarser, 4- and 8-node elements; node-to-face ties
fail it where a traction crosses the interface and the meshes do not
nest (measured there, guarded in test_constraint_decks)."""
from helpers import run_deck
from test_constraint_decks import cantilever, patch_error, tie_patch_deck, tip_deflection

MORTAR = "*TIE, NAME=GLUE, TYPE=SURFACE TO SURFACE"


def test_mortar_tied_patch_test_either_side_coarser():
    """Slave faces 3, 1 (slave coarser), 5 (1e-4 off the master, moved
    onto it) and 4 over 2 master faces, CPS4 and CPS8, pulled across the
    interface by 3 and along it by 2: every integration point S11 = 2,
    S22 = 3, S12 = 0 to 1e-8 (measured 1e-14); node-to-face on 3 over 2
    is off (test_constraint_decks measures it)."""
    both = "TOP, P, -3.\nRIGHT, P, -2.\n"
    for quadratic in (False, True):
        for nup, shift in ((3, 0.0), (1, 0.0), (5, 1e-4), (4, 0.0)):
            deck = tie_patch_deck(quadratic, nup, shift, both).replace("*TIE, NAME=GLUE", MORTAR)
            assert MORTAR in deck
            tag = f"{'q8' if quadratic else 'q4'}_{nup}"
            run, err = patch_error(f"mortar_tie_{tag}", deck, 2.0, 3.0)
            print(f"  mortar tie {tag} over 2: {err:.1e}")
            assert err < 1e-8, (tag, err)
            tie = run.listing.header[[b.name for b in run.listing.header].index("TIES")]
            assert tie["untied_nodes"][0] == 0, tie.rows


def test_mortar_tie_cantilever_coarser_slave():
    """The cantilever cut at mid-length and tied, the slave (right) half
    with 3 elements over the depth against 4 on the master half, and with
    2: the mortar tie's tip deflection is within 1e-3 of the uncut one, as
    close as node to face or closer."""
    ref = tip_deflection(run_deck("mtie_cantilever_uncut", cantilever(4, 4, False)).ok())
    for ny in (3, 2):
        ntf = tip_deflection(run_deck(f"mtie_cantilever_ntf_{ny}", cantilever(4, ny, True)).ok())
        deck = cantilever(4, ny, True).replace("*TIE, NAME=CUT", "*TIE, NAME=CUT, TYPE=SURFACE TO SURFACE")
        mortar = tip_deflection(run_deck(f"mtie_cantilever_mortar_{ny}", deck).ok())
        print(f"  cantilever 4 | {ny}: node to face {abs(ntf - ref) / abs(ref):.1e}, "
              f"mortar {abs(mortar - ref) / abs(ref):.1e}")
        assert abs(mortar - ref) < 1e-3 * abs(ref), (ny, mortar, ref)
        assert abs(mortar - ref) <= abs(ntf - ref) * 1.01, (ny, mortar, ntf, ref)


def test_mortar_tie_cards_refused_at_their_line():
    """An unknown TYPE= stops at the *TIE line, a node-surface slave of a
    mortar tie at its data line, saying why."""
    from test_decks_contact import error_at
    deck = tie_patch_deck(False, 3, 0.0, "TOP, P, -3.\n")
    error_at("mtie_type", deck.replace("*TIE, NAME=GLUE", "*TIE, NAME=GLUE, TYPE=MORTAR"),
             "*TIE, NAME=GLUE, TYPE=MORTAR", "TYPE must be NODE TO SURFACE or SURFACE TO SURFACE")
    nodes = deck.replace("*TIE, NAME=GLUE", "*NSET, NSET=UB\n1001, 1002\n*SURFACE, NAME=UBN, TYPE=NODE\nUB\n"
                         "*TIE, NAME=GLUE, TYPE=SURFACE TO SURFACE").replace("UPPER_BOTTOM, LOWER_TOP", "UBN, LOWER_TOP")
    error_at("mtie_nodes", nodes, "UBN, LOWER_TOP", "needs a slave surface of element faces")
