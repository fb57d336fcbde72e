"""NAFEMS contact benchmark 1 (input/nafems): a steel cylinder (R = 50 mm)
on an aluminium block, plane strain, 35 kN/mm, half model, meshed by gmsh
and read unedited, with CalculiX-style contact cards. Against Hertz and the
benchmark's reference a = 6.21 mm, p0 = 3585 MPa, within 2 %; also with the
cylinder starting 0.1 mm above the block, held only by the contact."""
import os
import shutil
import subprocess

from helpers import ROOT, Skip, rel_err, run_deck, workdir

A_REF, P0_REF, P_WHOLE = 6.21, 3585.0, 35000.0
HERE = os.path.join(ROOT, "input", "nafems")
_CACHE = {}


def mesh(outdir, g0=0.0):
    if shutil.which("gmsh") is None:
        raise Skip("gmsh is not installed")
    subprocess.run(["gmsh", "-2", "-format", "inp", "-setnumber", "Mesh.SaveGroupsOfNodes", "1",
                    "-setnumber", "g0", str(g0), "-o", os.path.join(outdir, "nafems1_mesh.inp"),
                    os.path.join(HERE, "nafems1.geo")], check=True, capture_output=True)


def run_case(name, g0=0.0, edit=None):
    """Mesh and run the shipped deck (edited by `edit` if given) in
    tests/work/<name>; returns the run and the Hertz comparison rows."""
    if name not in _CACHE:
        import compare_hertz
        d = workdir(name + "_src")
        mesh(d, g0)
        with open(os.path.join(HERE, "nafems1.inp")) as f:
            deck = f.read()
        if edit:
            deck = edit(deck)
        path = os.path.join(d, "nafems1.inp")
        with open(path, "w") as f:
            f.write(deck)
        run = run_deck(name, path=path).ok()
        out = os.path.dirname(run.listing_path)
        rows = compare_hertz.main([out, "--job", "nafems1", "--deck", path, "--radius", "50", "--symmetry", "2",
                                   "--quiet"])
        _CACHE[name] = (run, rows)
    return _CACHE[name]


def check_against_hertz(rows):
    last = rows[-1]
    assert rel_err(last["P"], P_WHOLE) < 1e-6, last["P"]
    for key, ref in (("a_FE", A_REF), ("a_H", A_REF), ("p0_FE", P0_REF), ("p0_H", P0_REF)):
        assert rel_err(last[key], ref) < 0.02, (key, last[key], ref)
    assert abs(last["err_a"]) < 0.02 and abs(last["err_p0"]) < 0.02, (last["err_a"], last["err_p0"])


def test_nafems1_within_2_percent_of_hertz():
    run, rows = run_case("nafems1")
    check_against_hertz(rows)
    assert "warning" not in run.stderr, run.stderr


def test_nafems1_cylinder_starting_apart_held_only_by_contact():
    """g0 = 0.1 mm, force-driven: the cylinder hangs on open contact
    elements until they close; the answer is the touching one, the top
    0.1 mm lower."""
    run, rows = run_case("nafems1_gap", g0=0.1)
    check_against_hertz(rows)
    _, touching = run_case("nafems1")
    assert abs(rows[-1]["u"] - touching[-1]["u"] + 0.1) < 2e-3, (rows[-1]["u"], touching[-1]["u"])


def test_nafems1_cfe2d_contact_pair_gives_the_same_answer():
    """cfe2d's own *CONTACT PAIR (EXACT: HARD's exact enforcement, one
    search) in place of the CalculiX cards: the same P, a and p0 to the
    last digit."""
    def own(deck):
        deck = deck.replace("*SURFACE INTERACTION, NAME=FRICTIONLESS\n", "")
        deck = deck.replace("*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD\n", "")
        return deck.replace("*CONTACT PAIR, INTERACTION=FRICTIONLESS, TYPE=NODE TO SURFACE, SMALL SLIDING",
                            "*CONTACT PAIR, EXACT, TYPE=NODE TO SURFACE")
    _, ccx = run_case("nafems1")
    _, rows = run_case("nafems1_own", edit=own)
    for key in ("P", "a_FE", "p0_FE"):
        assert rows[-1][key] == ccx[-1][key], (key, rows[-1][key], ccx[-1][key])


def test_nafems1_without_state_is_plane_stress_and_says_so():
    """The mesh says CPS4: without STATE=PLANE STRAIN the run is plane stress
    (a about 4 % larger than the plane-strain reference) and the title that
    says plane strain draws a warning naming STATE=PLANE STRAIN."""
    run, rows = run_case("nafems1_stress", edit=lambda d: d.replace(", STATE=PLANE STRAIN", ""))
    assert "the title says plane strain" in run.stderr and "STATE=PLANE STRAIN" in run.stderr, run.stderr
    assert rows[-1]["a_FE"] > 1.03 * A_REF, rows[-1]["a_FE"]


def test_compare_hertz_reads_materials_and_state_from_the_deck():
    import compare_hertz
    from hertz import effective_modulus
    d = workdir("nafems1_cards")
    mesh(d)
    shutil.copy(os.path.join(HERE, "nafems1.inp"), d)
    cards = compare_hertz.read_deck_cards(os.path.join(d, "nafems1.inp"))
    assert compare_hertz.deck_materials(cards) == {"STEEL": (210000.0, 0.3), "ALUMINIUM": (70000.0, 0.3)}
    assert compare_hertz.deck_stress_state(cards) == "strain"
    estar, plane, _ = compare_hertz.line_contact_modulus(cards)
    assert plane == "strain" and rel_err(estar, effective_modulus(210000.0, 0.3, 70000.0, 0.3, "strain")) < 1e-15
    # without STATE= the element types (gmsh's CPS4) decide
    cards = [(n, {k: v for k, v in p.items() if k != "STATE"}, data) for n, p, data in cards]
    assert compare_hertz.deck_stress_state(cards + [("ELEMENT", {"TYPE": "CPS4"}, [])]) == "stress"
