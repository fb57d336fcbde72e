"""Decks and meshes written for CalculiX, Abaqus and gmsh, read as those
programs read them: lenient *NODE lines, *SOLID SECTION with OFFSET=,
NODAL THICKNESS and STATE= (plane strain from a mesh that says CPS4),
*NODAL THICKNESS, *BOUNDARY on dof 3 held at zero, the deck's own
*HEADING over an included one, a hint
when a node set exists only as an element set, cards that would change
the physics stopped at their line, cards that cannot change it warned
about, and *EQUATION read in full and imposed (tests/test_equation.py
has the rest)."""
from helpers import rel_err, run_deck

E, NU, P = 1000.0, 0.25, 6.0

# A 2 x 1 block of two quads (nodes 1-3 at y = 0, 4-6 at y = 1), pulled
# along x at its right edge: uniform stress P / (height * thickness).
NODES = """*NODE, NSET=ALLN
1
2, 1.0, , 0.
3, 2.0, 0.0
4, 0.0, 1.0
5, 1.0, 1.0, , 0.
6, 2.0, 1.0
"""
PLAIN_NODES = NODES.replace("5, 1.0, 1.0, , 0.", "5, 1.0, 1.0")
ELEMENTS = """*ELEMENT, TYPE=CPS4, ELSET=BLOCK
1, 1, 2, 5, 4
2, 2, 3, 6, 5
"""


def block(section="*SOLID SECTION, ELSET=BLOCK, MATERIAL=M\n2.\n", nodes=PLAIN_NODES, elements=ELEMENTS, extra="",
          heading="*HEADING\nblock\n"):
    return f"""{heading}{nodes}{elements}*NSET, NSET=LEFT
1, 4
*NSET, NSET=RIGHT
3, 6
*MATERIAL, NAME=M
*ELASTIC
{E}, {NU}
{section}{extra}*BOUNDARY
LEFT, 1, 1
1, 2, 2
*STEP
*STATIC
*CLOAD
RIGHT, 1, {P / 2}
*NODE PRINT, NSET=RIGHT
U
*END STEP
"""


def u_right(run):
    return run.listing.increments[-1].block("NODE U", set="RIGHT")


def test_node_lines_as_lenient_as_calculix():
    """`1` alone is node 1 at the origin, `2, 1.0, , 0.` has y = 0 and
    `5, 1.0, 1.0, , 0.` a field after z (ignored, with a warning): the block
    is the regular one, its stretch the closed-form P L / (E A)."""
    run = run_deck("decks_nodes", block(nodes=NODES)).ok()
    u = u_right(run)
    assert rel_err(u["U1"][0], P * 2.0 / (E * 1.0 * 2.0)) < 1e-12, u["U1"]
    assert "fields after the third coordinate are ignored" in run.stderr, run.stderr
    bad = block(nodes=NODES.replace("2, 1.0, , 0.", "2, 1.0, y, 0."))
    run = run_deck("decks_nodes_bad", bad)
    assert run.rc == 1 and "decks_nodes_bad.inp:5: error:" in run.stderr, run.stderr


def test_section_offset_zero_accepted_other_warned():
    run = run_deck("decks_offset0", block("*SOLID SECTION, ELSET=BLOCK, MATERIAL=M, OFFSET=0.\n2.\n")).ok()
    assert "warning" not in run.stderr, run.stderr
    deck = block("*SOLID SECTION, ELSET=BLOCK, MATERIAL=M, OFFSET=0.5\n2.\n")
    run = run_deck("decks_offset", deck).ok()
    line = deck.splitlines().index("*SOLID SECTION, ELSET=BLOCK, MATERIAL=M, OFFSET=0.5") + 1
    assert f"decks_offset.inp:{line}: warning: OFFSET=" in run.stderr, run.stderr
    assert rel_err(u_right(run)["U1"][0], P * 2.0 / (E * 2.0)) < 1e-12


def test_nodal_thickness():
    """NODAL THICKNESS with 0.5 at every node: the stretch of thickness 0.5
    (the section's own line ignored); a thickness that varies inside an
    element (thicker at one corner) runs and stretches less than the
    thinner block, more than the thicker one (closed forms for a varying
    thickness: tests/test_nodal_thickness.py); *NODAL THICKNESS without a
    section asking for it is a warning and changes nothing."""
    sec = "*SOLID SECTION, ELSET=BLOCK, MATERIAL=M, NODAL THICKNESS\n"
    run = run_deck("decks_nodal_t", block(sec, extra="*NODAL THICKNESS\nALLN, 0.5\n")).ok()
    assert rel_err(u_right(run)["U1"][0], P * 2.0 / (E * 1.0 * 0.5)) < 1e-12, u_right(run)["U1"]
    deck = block(sec, extra="*NODAL THICKNESS\nALLN, 0.5\n3, 0.6\n")
    u = u_right(run_deck("decks_nodal_t_varies", deck).ok())["U1"]
    assert P * 2.0 / (E * 0.6) < min(u) and max(u) < P * 2.0 / (E * 0.5), u
    deck = block(extra="*NODAL THICKNESS\nALLN, 0.5\n")
    run = run_deck("decks_nodal_t_unused", deck).ok()
    assert "*NODAL THICKNESS is ignored" in run.stderr, run.stderr
    assert rel_err(u_right(run)["U1"][0], P * 2.0 / (E * 2.0)) < 1e-12


def test_out_of_plane_dof_held_at_zero():
    """*BOUNDARY over dofs 1 to 3, or 3 alone, with a zero value (CalculiX
    decks hold their springs' and trusses' nodes so): a 2D model has no
    dof 3, so the answer is that of the deck without it; a non-zero value
    on dof 3 is an error at its line."""
    plain = u_right(run_deck("decks_dof12", block()).ok())["U1"]
    deck = block().replace("1, 2, 2\n", "1, 1, 3\n4, 3, 3\nALLN, 3\n", 1)
    assert "4, 3, 3" in deck
    held = u_right(run_deck("decks_dof3", deck).ok())["U1"]
    assert (held == plain).all(), (held, plain)
    bad = block().replace("1, 2, 2\n", "1, 2, 2\n4, 3, 3, 0.1\n", 1)
    run = run_deck("decks_dof3_moved", bad)
    line = bad.splitlines().index("4, 3, 3, 0.1") + 1
    assert run.rc == 1 and f"decks_dof3_moved.inp:{line}: error: dofs must satisfy" in run.stderr, run.stderr


def test_state_plane_strain_from_a_cps_mesh():
    """STATE=PLANE STRAIN on a section of CPS4 elements gives the answer of
    the same mesh written with CPE4: u = P L (1 - nu^2) / (E A)."""
    strain = run_deck("decks_cpe", block(elements=ELEMENTS.replace("CPS4", "CPE4"))).ok()
    state = run_deck("decks_state", block("*SOLID SECTION, ELSET=BLOCK, MATERIAL=M, STATE=PLANE STRAIN\n2.\n")).ok()
    u_cpe, u_state = u_right(strain)["U1"], u_right(state)["U1"]
    assert (u_cpe == u_state).all(), (u_cpe, u_state)
    assert rel_err(u_state[0], P * 2.0 * (1 - NU ** 2) / (E * 2.0)) < 1e-12


def test_plane_stress_warnings():
    """A plane-stress section without a thickness line, and plane-stress
    elements under a title that says plane strain: warnings naming the
    line and STATE=PLANE STRAIN."""
    deck = block("*SOLID SECTION, ELSET=BLOCK, MATERIAL=M\n", heading="*HEADING\nA plane strain block\n")
    run = run_deck("decks_ps_warn", deck).ok()
    sec = deck.splitlines().index("*SOLID SECTION, ELSET=BLOCK, MATERIAL=M") + 1
    assert f"decks_ps_warn.inp:{sec}: warning: plane-stress elements (CPS) without a thickness line" in run.stderr
    assert "decks_ps_warn.inp:2: warning: the title says plane strain" in run.stderr, run.stderr
    assert run.stderr.count("STATE=PLANE STRAIN") == 2
    run = run_deck("decks_ps_quiet", block()).ok()
    assert "warning" not in run.stderr, run.stderr


def test_deck_heading_wins_over_included_mesh():
    """gmsh writes a *Heading into every mesh: the deck's own title stays,
    whether it comes before or after the *INCLUDE."""
    mesh = "*Heading\n mesh.inp written by gmsh\n" + PLAIN_NODES + ELEMENTS
    for tag, heading, after in (("before", "*HEADING\nmy title\n", ""), ("after", "", "*HEADING\nmy title\n")):
        deck = block(heading=heading, nodes="*INCLUDE, INPUT=mesh.inp\n" + after, elements="")
        run = run_deck("decks_heading_" + tag, deck, files={"mesh.inp": mesh}).ok()
        assert "heading my title" in open(run.listing_path).read(), tag
    deck = block(heading="", nodes="*INCLUDE, INPUT=mesh.inp\n", elements="")
    run = run_deck("decks_heading_mesh", deck, files={"mesh.inp": mesh}).ok()
    assert "heading mesh.inp written by gmsh" in open(run.listing_path).read()


def test_node_set_that_is_only_an_element_set():
    deck = block(extra="*ELSET, ELSET=EDGE\n2\n").replace("RIGHT, 1, ", "EDGE, 1, ")
    run = run_deck("decks_nset_hint", deck)
    line = deck.splitlines().index(f"EDGE, 1, {P / 2}") + 1
    assert run.rc == 1 and f"decks_nset_hint.inp:{line}: error: undefined node set EDGE" in run.stderr
    assert "Mesh.SaveGroupsOfNodes 1" in run.stderr and "*NSET, NSET=EDGE, ELSET=EDGE" in run.stderr


def test_cards_that_change_the_physics_stop_others_warn():
    # (*FREQUENCY runs since issue 31: the block has no *DENSITY, which it names)
    for card, fragment in (("*DYNAMIC\n0.1, 1.", "the procedure *DYNAMIC is not implemented"),
                           ("*FREQUENCY\n10", "*FREQUENCY: the model has no mass")):
        deck = block().replace("*STATIC\n", card + "\n")
        run = run_deck("decks_reject", deck)
        line = deck.splitlines().index(card.split("\n")[0]) + 1
        assert run.rc == 1 and f"decks_reject.inp:{line}: error: {fragment}" in run.stderr, run.stderr
    # *HEAT TRANSFER is read since issue 30: the mechanical block's material
    # has no *CONDUCTIVITY, which its *MATERIAL line is named for
    deck = block().replace("*STATIC\n", "*HEAT TRANSFER\n0.1, 1.\n")
    run = run_deck("decks_reject_heat", deck)
    line = next(k for k, ln in enumerate(deck.splitlines(), 1) if ln.upper().startswith("*MATERIAL"))
    assert run.rc == 1 and f"decks_reject_heat.inp:{line}: error: material M has no *CONDUCTIVITY" in run.stderr, \
        run.stderr
    deck = block(extra="*MATERIAL, NAME=P\n*ELASTIC\n1., 0.\n*CREEP\n1e-10, 3., 0.\n")
    run = run_deck("decks_creep", deck)
    line = deck.splitlines().index("*CREEP") + 1
    assert run.rc == 1 and f"decks_creep.inp:{line}: error: the material law *CREEP" in run.stderr
    deck = block(extra="*MATERIAL, NAME=Q\n*ELASTIC\n1., 0.\n*SPECIFIC HEAT\n450.\n*CONDUCTIVITY\n50.\n")
    run = run_deck("decks_inert", deck).ok()
    # thermal material data (read for heat transfer since issue 30) change
    # nothing of a mechanical step and need no word, as in CalculiX
    assert "warning" not in run.stderr, run.stderr
    assert rel_err(u_right(run)["U1"][0], P * 2.0 / (E * 2.0)) < 1e-12


def test_equation_read_in_full_and_imposed():
    """*EQUATION is read in full (terms over several lines, a node set
    giving one constraint per node) and imposed: u_y(3) = u_y(6), and each
    RIGHT node's u_x is the mean of those of nodes 5 and 2 (the loaded
    RIGHT nodes are eliminated, their loads carried by nodes 2 and 5).
    Malformed constraints are errors at the offending line."""
    eq = "*EQUATION\n2\n3, 2, 1., 6, 2, -1.\n3\nRIGHT, 1, 1.,\n5, 1, -0.5, 2, 1, -0.5\n"
    deck = block(extra=eq).replace("*NODE PRINT, NSET=RIGHT", "*NODE PRINT, NSET=ALLN")
    run = run_deck("decks_equation", deck).ok()
    u = run.listing.increments[-1].block("NODE U", set="ALLN")
    ux, uy = dict(zip(u["node"], u["U1"])), dict(zip(u["node"], u["U2"]))
    assert uy[3] == uy[6] and ux[2] > 0.0 and ux[5] > 0.0
    for n in (3, 6):
        assert abs(ux[n] - 0.5 * (ux[2] + ux[5])) <= 1e-15 * ux[2], (n, ux)
    for tag, text, bad, fragment in (("dof", "2\n3, 3, 1., 6, 2, -1.\n", "3, 3, 1., 6, 2, -1.",
                                      "dof 3 with a non-zero coefficient"),
                                     ("short", "3\n3, 2, 1., 6, 2, -1.\n", "3, 2, 1., 6, 2, -1.", "fewer terms"),
                                     ("zero", "2\n3, 2, 0., 6, 2, -1.\n", "3, 2, 0., 6, 2, -1.", "must not be zero")):
        deck = block(extra="*EQUATION\n" + text)
        run = run_deck("decks_equation_" + tag, deck)
        line = deck.splitlines().index(bad) + 1
        assert run.rc == 1 and f"decks_equation_{tag}.inp:{line}: error:" in run.stderr, (tag, run.stderr)
        assert fragment in run.stderr, (tag, run.stderr)


def test_keywords_written_without_blanks_read_as_calculix_reads_them():
    """CalculiX drops every blank of a keyword line (its scheibe.inp writes
    *SOLIDSECTION): the cantilever with *SOLIDSECTION, *NODEPRINT, *ELPRINT
    and *ENDSTEP gives the listing of the deck as written."""
    import os
    from helpers import ROOT, run_deck
    deck = open(os.path.join(ROOT, "input", "examples", "cantilever.inp")).read()
    packed = (deck.replace("*SOLID SECTION", "*SOLIDSECTION").replace("*NODE PRINT", "*NODEPRINT")
              .replace("*EL PRINT", "*ELPRINT").replace("*END STEP", "*ENDSTEP"))
    assert packed.count("*SOLIDSECTION") == 1 and "*ENDSTEP" in packed
    a = run_deck("decks_blanks_as_written", deck).ok().listing.increments[-1]
    b = run_deck("decks_blanks_dropped", packed).ok().listing.increments[-1]
    assert a.block("NODE U", set="TIP")["U2"].tolist() == b.block("NODE U", set="TIP")["U2"].tolist()
    assert b.has("ELEMENT S", set="ALL")
