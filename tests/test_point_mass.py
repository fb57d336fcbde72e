"""Point masses (*ELEMENT, TYPE=MASS with *MASS) under gravity and
centrifugal loads in a static step, against closed forms: a bar pulled by
the weight of two masses at its end, the reactions of a centrifugal force
about an axis away from the origin, an axisymmetric mass as the ring load
it stands for; the errors, each at its line."""
from helpers import rel_err, run_deck

E, L, H, T = 2.0e5, 4.0, 1.0, 0.5
M, G, W2 = 3.0e-3, 9.81e3, 1.0e4


def bar(load, masses="2, 2\n3, 3\n", mass_card="*MASS, ELSET=MA\n{m}\n", supports="1, 1\n4, 1\n1, 2\n",
        section="*SOLID SECTION, ELSET=BAR, MATERIAL=STEEL\n{t}\n", element="CPS4"):
    """One plane element 0..L x 0..H (thickness T, nu = 0) with MASS
    elements at the right end, loaded by the *DLOAD line `load`."""
    return f"""*NODE, NSET=ALLN
1, 0., 0.
2, {L}, 0.
3, {L}, {H}
4, 0., {H}
*ELEMENT, TYPE={element}, ELSET=BAR
1, 1, 2, 3, 4
*ELEMENT, TYPE=MASS, ELSET=MA
{masses}*MATERIAL, NAME=STEEL
*ELASTIC
{E}, 0.
*DENSITY
7.8e-9
{section.format(t=T)}{mass_card.format(m=M)}*NSET, NSET=LEFT
1, 4
*BOUNDARY
{supports}*STEP
*STATIC
*DLOAD
{load}
*NODE PRINT, NSET=ALLN
U, RF
*END STEP
"""


def nodal(run, key):
    return run.listing.increments[-1].block("NODE " + key, set="ALLN")


def test_weight_of_end_masses_stretches_the_bar():
    """Two masses M at the right corners, gravity G along x: an end force
    2 M G shared equally, a uniform stress: u(L) = 2 M G L / (E H T) at
    both right nodes (exact for one bilinear element with nu = 0), and
    the left reactions sum to -2 M G."""
    run = run_deck("mass_grav_bar", bar(f"MA, GRAV, {G}, 1., 0., 0.")).ok()
    u, rf = nodal(run, "U"), nodal(run, "RF")
    exact = 2 * M * G * L / (E * H * T)
    assert max(rel_err(u["U1"][k], exact) for k in (1, 2)) < 1e-12, (u["U1"], exact)
    assert rel_err(sum(rf["RF1"]), -2 * M * G) < 1e-12, rf["RF1"]


def test_centrifugal_force_about_an_offset_axis():
    """One mass at (L, H), the axis through (x0, y0) normal to the plane:
    the force M omega^2 (x - x0, y - y0), which the supports (the left
    edge held in x and y) return in full. The mass's own density plays no
    part; the element's *DLOAD names only the mass set."""
    x0, y0 = -1.0, 3.0
    deck = bar(f"MA, CENTRIF, {W2}, {x0}, {y0}, 0., 0., 0., 1.", masses="2, 3\n",
               supports="1, 1, 2\n4, 1, 2\n")
    rf = nodal(run_deck("mass_centrif_plane", deck).ok(), "RF")
    fx, fy = M * W2 * (L - x0), M * W2 * (H - y0)
    assert rel_err(sum(rf["RF1"]), -fx) < 1e-12 and rel_err(sum(rf["RF2"]), -fy) < 1e-12, (rf, fx, fy)


def ring(load_lines):
    """A CAX4 ring r = 1..2, z = 0..0.5, held axially at z = 0."""
    return f"""*NODE, NSET=ALLN
1, 1., 0.
2, 2., 0.
3, 2., 0.5
4, 1., 0.5
*ELEMENT, TYPE=CAX4, ELSET=RING
1, 1, 2, 3, 4
*ELEMENT, TYPE=MASS, ELSET=MA
2, 3
*MATERIAL, NAME=STEEL
*ELASTIC
{E}, 0.3
*DENSITY
7.8e-9
*SOLID SECTION, ELSET=RING, MATERIAL=STEEL
*MASS, ELSET=MA
{M}
*BOUNDARY
1, 2
2, 2
*STEP
*STATIC
{load_lines}*NODE PRINT, NSET=ALLN
U, RF
*END STEP
"""


def test_axisymmetric_mass_is_the_ring_load_it_stands_for():
    """In an axisymmetric model a point mass is a ring's, as a point load
    is the whole ring's: CENTRIF on it equals a *CLOAD of M omega^2 r
    radially at its node, GRAV along the axis a *CLOAD of M G axially
    (same displacements to 1e-12)."""
    pairs = [(f"*DLOAD\nMA, CENTRIF, {W2}, 0., 0., 0., 0., 1., 0.\n", f"*CLOAD\n3, 1, {M * W2 * 2.0}\n"),
             (f"*DLOAD\nMA, GRAV, {G}, 0., -1., 0.\n", f"*CLOAD\n3, 2, {-M * G}\n")]
    for k, (dload, cload) in enumerate(pairs):
        a = nodal(run_deck(f"mass_axi_{k}", ring(dload)).ok(), "U")
        b = nodal(run_deck(f"mass_axi_cload_{k}", ring(cload)).ok(), "U")
        scale = max(abs(v) for v in b["U1"] + b["U2"])
        assert scale > 0
        assert max(abs(x - y) for key in ("U1", "U2") for x, y in zip(a[key], b[key])) < 1e-12 * scale, (a, b)


def test_mass_errors_name_the_line():
    good = bar(f"MA, GRAV, {G}, 1., 0., 0.")
    cases = [
        ("nomass", good.replace(f"*MASS, ELSET=MA\n{M}\n", ""), "2, 2", "has no *MASS"),
        ("negative", good.replace(f"*MASS, ELSET=MA\n{M}\n", f"*MASS, ELSET=MA\n-{M}\n"), f"-{M}",
         "must be positive"),
        ("twovalues", good.replace(f"*MASS, ELSET=MA\n{M}\n", f"*MASS, ELSET=MA\n{M}, 2.\n"), f"{M}, 2.",
         "one value"),
        ("notmass", good.replace("*MASS, ELSET=MA", "*MASS, ELSET=BAR"), "*MASS, ELSET=BAR", "not a point mass"),
        ("pressure", good.replace(f"MA, GRAV, {G}, 1., 0., 0.", "MA, P1, 5."), "MA, P1, 5.",
         "GRAV and CENTRIF loads only"),
        ("solid", good.replace("*SOLID SECTION, ELSET=BAR", "*SOLID SECTION, ELSET=MA"),
         "*SOLID SECTION, ELSET=MA, MATERIAL=STEEL", "its mass comes from *MASS"),
    ]
    for tag, deck, line_text, fragment in cases:
        run = run_deck("mass_err_" + tag, deck)
        line = next(k for k, t in enumerate(deck.splitlines(), 1) if t == line_text)
        assert run.rc == 1 and f"mass_err_{tag}.inp:{line}: error:" in run.stderr, (tag, line, run.stderr)
        assert fragment in run.stderr, (tag, run.stderr)


def test_mass_on_a_dof_nothing_carries_is_an_error():
    """A point mass on a node that belongs to no element with stiffness and
    whose other dof only an *EQUATION names: its weight along the free dof
    would be lost (and a false reaction printed); the run stops saying so."""
    deck = bar(f"MA, GRAV, {G}, 0., -1., 0.", masses="2, 5\n").replace(
        "4, 0., {H}\n".format(H=H), f"4, 0., {H}\n5, {2 * L}, 0.\n").replace(
        "*BOUNDARY\n", "*EQUATION\n2\n2, 1, 1., 5, 1, -1.\n*BOUNDARY\n", 1)
    assert "5, 8.0, 0." in deck
    run = run_deck("mass_unsupported_dof", deck)
    assert run.rc == 1 and "acts on dof 2 of node 5" in run.stderr and "nothing carries it" in run.stderr, run.stderr
