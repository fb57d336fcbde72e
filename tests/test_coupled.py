"""Coupled temperature-displacement analysis (*COUPLED TEMPERATURE-
DISPLACEMENT; the driver's fields [temperatures, displacements], solved in
that order in each increment; docs/heat.md) against closed-form answers:

- free thermal expansion of a plate whose temperature the heat transfer
  of the same step computes (two faces held at T1, the rest insulated:
  T = T1 everywhere, exactly for every element): the strain alpha dT in
  plane stress and (1 + nu) alpha dT in plane strain at every integration
  point, to round-off (tolerance 1e-9 relative), on the coupled element
  names CPS4T, CPE4T, CPS8T, CPS3T, CPE8RT, CPS4RT, steady and transient;
- a ring heated onto a shaft and cooled: the ring's stress-free shape is
  the hot one (its initial temperature T0 + 100 K, its bore touching the
  shaft), the coupled step holds its outside at T0 and the shaft's bore
  at T0, so that each body conducts to a uniform T0 and the ring shrinks
  onto the shaft: the contact pressure and stresses against two Lame
  cylinders in plane strain (tests/test_shrink_fit.py's closed form,
  tolerance 1 %, as the mechanical fit there); the same fit as a *HEAT
  TRANSFER step followed by a *STATIC step (the mechanical step takes the
  temperatures the heat step left);
- mechanical results are unchanged where the temperatures are the same:
  the coupled fit equals the mechanical fit of *TEMPERATURE to 1e-9.
"""
import math

import numpy as np

from helpers import run_deck
from quadmesh import Mesh
from test_shrink_fit import shrink_deck, compare, fit_closed_form, T0

ALPHA, E, NU = 1.2e-5, 210000.0, 0.3


def plate_deck(shape, et, step, t1=120.0, t0=20.0, extra_material="", t_right=None):
    """A 2 x 1 plate of 2 x 2 elements, held at node (0, 0) and on y = 0
    in y, its left and right sides at t1 (the right at t_right if given)
    by *BOUNDARY on dof 11, starting from t0 everywhere."""
    m = Mesh(shape, 2, 2, lambda s, t: (s, 0.5 * t), straight=True)
    left = ", ".join(map(str, m.side("left")))
    right = ", ".join(map(str, m.side("right")))
    bottom = ", ".join(map(str, m.side("bottom")))
    origin = m.side("left")[0]
    return m, f"""*HEADING
free thermal expansion, {et}
*NODE, NSET=NALL
{m.node_lines()}{m.element_card(et, 'PLATE')}*NSET, NSET=LEFT
{left}
*NSET, NSET=RIGHT
{right}
*NSET, NSET=BOTTOM
{bottom}
*MATERIAL, NAME=STEEL
*ELASTIC
{E}, {NU}
*EXPANSION
{ALPHA}
*CONDUCTIVITY
50.
{extra_material}*SOLID SECTION, ELSET=PLATE, MATERIAL=STEEL
1.
*INITIAL CONDITIONS, TYPE=TEMPERATURE
NALL, {t0}
*STEP
{step}
*BOUNDARY
{origin}, 1, 1
BOTTOM, 2, 2
*BOUNDARY
LEFT, 11, 11, {t1}
RIGHT, 11, 11, {t1 if t_right is None else t_right}
*NODE PRINT, NSET=NALL
U, NT
*EL PRINT
E, S, HFL
*END STEP
"""


def test_free_expansion():
    """Every integration point's strain is the free thermal strain and its
    stress zero; every node's temperature T1 and displacement the strain
    times its coordinate."""
    dt = 100.0
    cases = [("Q4", "CPS4T", "*COUPLED TEMPERATURE-DISPLACEMENT, STEADY STATE", 1.0),
             ("Q4", "CPE4T", "*COUPLED TEMPERATURE-DISPLACEMENT, STEADY STATE", 1.0 + NU),
             ("Q8", "CPS8T", "*COUPLED TEMPERATURE-DISPLACEMENT, STEADY STATE\n0.25, 1.", 1.0),
             ("T3", "CPS3T", "*COUPLED TEMPERATURE-DISPLACEMENT, STEADY STATE", 1.0),
             ("Q8", "CPE8RT", "*COUPLED TEMPERATURE-DISPLACEMENT, STEADY STATE", 1.0 + NU),
             ("Q4", "CPS4RT", "*COUPLED TEMPERATURE-DISPLACEMENT, STEADY STATE", 1.0),
             # transient: the sides jump to T1 at once; the interior reaches it
             # only after a while, so the strain is checked at the end of a
             # long step (10 increments of 1e4 s; diffusion time L^2 rho c / k ~ 1e4 s)
             ("Q4", "CPS4T", "*COUPLED TEMPERATURE-DISPLACEMENT\n1e5, 1e6", 1.0)]
    for shape, et, step, factor in cases:
        extra = "*DENSITY\n7.8e-9\n*SPECIFIC HEAT\n4.6e8\n" if "STEADY" not in step else ""
        m, text = plate_deck(shape, et, step, extra_material=extra)
        run = run_deck("coupled_free_" + et.lower(), text).ok()
        inc = run.listing.increments[-1]
        eps = factor * ALPHA * dt
        nt = inc.block("NODE NT")
        assert np.max(np.abs(np.array(nt["NT11"]) - 120.0)) < 1e-9 * 120.0, (et, nt["NT11"])
        e = inc.block("ELEMENT E")
        for comp in ("E11", "E22"):
            assert np.max(np.abs(np.array(e[comp]) - eps)) < 1e-9 * eps, (et, comp, e[comp])
        assert np.max(np.abs(e["E12"])) < 1e-9 * eps, (et, e["E12"])
        s = inc.block("ELEMENT S")
        for comp in ("S11", "S22", "S12"):
            assert np.max(np.abs(s[comp])) < 1e-9 * E * ALPHA * dt, (et, comp, s[comp])
        u = inc.block("NODE U")
        for k, n in enumerate(u["node"]):
            x, y = m.nodes[int(n)]
            assert abs(u["U1"][k] - eps * x) < 1e-9 * eps and abs(u["U2"][k] - eps * y) < 1e-9 * eps, \
                (et, n, u["U1"][k], u["U2"][k])


def coupled_fit(text, ring, heat_then_static=False):
    """shrink_deck's mechanical fit (nothing heated) turned into the
    coupled one: coupled elements, conductivities, the ring's initial
    temperature T0 + 100, and a coupled step (or a heat transfer step and
    a static step) holding the ring's outside and the shaft's bore at T0."""
    text = text.replace("TYPE=CAX8,", "TYPE=CAX8T,")
    text = text.replace("*NODE PRINT, NSET=BORE\nU, S\n", "*NODE PRINT, NSET=BORE\nU, S, NT\n")
    text = text.replace("*EXPANSION\n", "*CONDUCTIVITY\n50.\n*EXPANSION\n")
    outside = "".join(", ".join(map(str, ring.side("right")[i:i + 10])) + "\n"
                      for i in range(0, len(ring.side("right")), 10))
    text = text.replace(f"*INITIAL CONDITIONS, TYPE=TEMPERATURE\nALLN, {T0}\n",
                        f"*NSET, NSET=OUTSIDE\n{outside}*INITIAL CONDITIONS, TYPE=TEMPERATURE\nALLN, {T0}\n"
                        f"RINGN, {T0 + 100.0}\n")
    held = f"*BOUNDARY\nOUTSIDE, 11, 11, {T0}\nBORE, 11, 11, {T0}\n"
    head, step = text.split("*STEP\n*STATIC\n*TEMPERATURE\n", 1)
    assert step.startswith("*NODE PRINT"), step[:40]
    if heat_then_static:
        return head + f"*STEP\n*HEAT TRANSFER, STEADY STATE\n{held}*END STEP\n*STEP\n*STATIC\n" + step
    return head + f"*STEP\n*COUPLED TEMPERATURE-DISPLACEMENT, STEADY STATE\n{held}" + step


def test_ring_heated_onto_shaft():
    """The ring cooled by 100 K onto the shaft (CAX8T, 6 + 8 elements through
    the walls): the contact pressure at every slave point and master node,
    the total force, the hoop and axial stresses and u_r at the bore within
    1 % of the closed form (fit_closed_form(0, -100)), as the mechanical
    fit of test_shrink_fit; the temperatures T0 everywhere (1e-9); the
    same with a *HEAT TRANSFER step and then a *STATIC step."""
    text, shaft, ring = shrink_deck("Q8", "AX", 0.0, 0.0)
    for name, two_steps in (("coupled_ring_fit", False), ("coupled_ring_fit_heat_static", True)):
        run = run_deck(name, coupled_fit(text, ring, two_steps)).ok()
        nt = np.array(run.listing.increments[-1].block("NODE NT", set="BORE")["NT11"])
        assert np.max(np.abs(nt - T0)) < 1e-9 * T0, nt
        compare(run, "AX", shaft, ring, 0.0, -100.0, {"default": 1e-2}, name)
    assert fit_closed_form(0.0, -100.0)["p"] > 0.0
    assert math.isfinite(fit_closed_form(0.0, -100.0)["p"])


def test_coupled_equals_mechanical_fit():
    """Where the temperatures are the same, the coupled step's mechanical
    results are those of *TEMPERATURE: the ring cooled by 100 K in a
    *STATIC step (test_shrink_fit's deck) and the coupled fit above give
    the same nodal stresses and displacements at the bore and the seat
    (to 1e-9 of the block's largest component) and the same total contact
    force (1e-9)."""
    text, shaft, ring = shrink_deck("Q8", "AX", 0.0, 0.0)
    coupled = run_deck("coupled_ring_fit_same", coupled_fit(text, ring)).ok().listing.increments[-1]
    static = run_deck("coupled_ring_fit_static", shrink_deck("Q8", "AX", 0.0, -100.0)[0]).ok().listing.increments[-1]
    for name, nset, comps in (("NODE U", "BORE", ("U1", "U2")), ("NODE S", "BORE", ("S11", "S22", "S33", "S12")),
                              ("NODE U", "SEAT", ("U1", "U2")), ("NODE S", "SEAT", ("S11", "S22", "S33", "S12"))):
        a, b = coupled.block(name, set=nset), static.block(name, set=nset)
        scale = max(np.max(np.abs(b[c])) for c in comps)
        for c in comps:
            x, y = np.array(a[c]), np.array(b[c])
            assert np.max(np.abs(x - y)) <= 1e-9 * scale, (name, nset, c, np.max(np.abs(x - y)), scale)
    fa = coupled.block("CONTACT SUMMARY")["total_force"][0]
    fb = static.block("CONTACT SUMMARY")["total_force"][0]
    assert abs(fa - fb) <= 1e-9 * abs(fb), (fa, fb)


def test_linear_temperature_no_stress():
    """The left side at 120, the right at 20 (x = 0 .. 2, k = 50): the
    conduction gives T linear in x, whose thermal strain alpha (T - T0) is
    compatible, so the free plate has no stress; the displacement is then
    quadratic (u_x = alpha (int T dx - T' y^2 / 2)), which the 8-node
    elements hold exactly: at every integration point of CPS8T the
    stresses within 1e-9 of E alpha dT, at every node T exact and u_y =
    alpha (T(x) - T0) y (1e-9 of alpha dT), and the
    heat flux HFL1 = -k dT/dx = 2500, HFL2 = 0 (1e-9)."""
    k, t_left, t_right, t0 = 50.0, 120.0, 20.0, 20.0
    m, text = plate_deck("Q8", "CPS8T", "*COUPLED TEMPERATURE-DISPLACEMENT, STEADY STATE", t1=t_left, t0=t0,
                         t_right=t_right)
    inc = run_deck("coupled_linear_t", text).ok().listing.increments[-1]
    s = inc.block("ELEMENT S")
    scale = E * ALPHA * (t_left - t0)
    for comp in ("S11", "S22", "S12"):
        assert np.max(np.abs(s[comp])) < 1e-9 * scale, (comp, np.max(np.abs(s[comp])))
    q = inc.block("ELEMENT HFL")
    flux = -k * (t_right - t_left) / 2.0
    assert len(q["HFL1"]) == 4 * 9, len(q["HFL1"])
    assert np.max(np.abs(np.array(q["HFL1"]) - flux)) < 1e-9 * flux, q["HFL1"]
    assert np.max(np.abs(q["HFL2"])) < 1e-9 * flux, q["HFL2"]
    u, nt = inc.block("NODE U"), inc.block("NODE NT")
    temp = dict(zip((int(n) for n in nt["node"]), nt["NT11"]))
    for kk, n in enumerate(u["node"]):
        x, y = m.nodes[int(n)]
        t_exact = t_left + (t_right - t_left) * x / 2.0
        assert abs(temp[int(n)] - t_exact) < 1e-9 * t_left, (n, temp[int(n)], t_exact)
        # u_y = alpha (T(x) - T0) y, the plate held on y = 0
        assert abs(u["U2"][kk] - ALPHA * (t_exact - t0) * y) < 1e-9 * ALPHA * (t_left - t0), (n, u["U2"][kk])


def ids_lines(ns):
    return "".join(", ".join(map(str, ns[i:i + 10])) + "\n" for i in range(0, len(ns), 10))


def blocks_deck(coupling, conductance, p0=10.0, k1=50.0, k2=50.0, alpha=0.0, top_held=False, nx=2, ny=2,
                shape="Q4", et="CPE4T", t_bottom=100.0, t_top=0.0, gap=0.0, gc_params=None):
    """Two blocks of 1 x 1 (plane strain, unit thickness), A on 0 < y < 1 and
    B on 1 + gap < y < 2 + gap, B's bottom the slave on A's top; A's bottom
    held at t_bottom and B's top at t_top (dof 11); both sides held in x (a
    1D state), A's bottom in y, B's top pressed by p0 (or held in y:
    top_held); conductance the *GAP CONDUCTANCE data lines, gc_params its
    parameters (default PRESSURE for a table of several lines)."""
    a = Mesh(shape, nx, ny, lambda s, t: (s / nx, t / ny), straight=True)
    b = Mesh(shape, nx, ny, lambda s, t: (s / nx, 1.0 + gap + t / ny), straight=True, first_node=1001,
             first_elem=1001)
    if gc_params is None:
        gc_params = ", PRESSURE" if conductance.count(chr(10)) > 1 else ""
    sides = sorted(a.side("left") + a.side("right") + b.side("left") + b.side("right"))
    top_faces = "".join(f"{e}, P{k}, {p0}\n" for e, k in b.faces("top"))
    load = f"*BOUNDARY\nTOP, 2, 2\n" if top_held else f"*DLOAD\n{top_faces}"
    return f"""*HEADING
two blocks through a gap conductance
*NODE, NSET=NALL
{a.node_lines()}{b.node_lines()}{a.element_card(et, 'A')}{b.element_card(et, 'B')}*NSET, NSET=BOTTOM
{ids_lines(a.side('bottom'))}*NSET, NSET=TOP
{ids_lines(b.side('top'))}*NSET, NSET=SIDES
{ids_lines(sides)}*NSET, NSET=ATOP
{ids_lines(a.side('top'))}*NSET, NSET=BBOTTOM
{ids_lines(b.side('bottom'))}{a.surface_card('ASURF', 'top')}{b.surface_card('BSURF', 'bottom')}*MATERIAL, NAME=M1
*ELASTIC
210000., 0.3
*EXPANSION
{alpha}
*CONDUCTIVITY
{k1}
*MATERIAL, NAME=M2
*ELASTIC
210000., 0.3
*EXPANSION
{alpha}
*CONDUCTIVITY
{k2}
*SOLID SECTION, ELSET=A, MATERIAL=M1
1.
*SOLID SECTION, ELSET=B, MATERIAL=M2
1.
*SURFACE INTERACTION, NAME=GAP
*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD
*GAP CONDUCTANCE{gc_params}
{conductance}*CONTACT PAIR, INTERACTION=GAP, TYPE={coupling}
BSURF, ASURF
*BOUNDARY
SIDES, 1, 1
BOTTOM, 2, 2
*STEP
*COUPLED TEMPERATURE-DISPLACEMENT, STEADY STATE
*BOUNDARY
BOTTOM, 11, 11, {t_bottom}
TOP, 11, 11, {t_top}
{load}*NODE PRINT, NSET=ATOP
NT
*NODE PRINT, NSET=BBOTTOM
NT
*NODE PRINT, NSET=BOTTOM
RFL
*NODE PRINT, NSET=TOP
RFL
*EL PRINT
HFL
*END STEP
"""


def test_gap_conductance_blocks():
    """The blocks pressed by p0 = 10 through a conductance h: the heat flows
    through them as through three resistances in series, q = (T_bottom -
    T_top) / (L/k + 1/h + L/k); the temperature jump across the contact is
    q/h, each block's temperature linear (exact for the elements: 1e-9 of
    100), the heat flux -k dT/dy = q at every integration point of both
    blocks and the reaction fluxes q and -q over the held faces (flux
    continuous; 1e-9), the contact table's heat flux -q at every slave
    point (from the slave, the colder side; 1e-7, its printed digits).
    Node-to-segment, segment-to-segment, and a two-pass (SYMMETRIC) pair,
    each of whose passes carries half (-q/2 in its rows). h = 25 constant, and h from a pressure table (10 at
    p = 0, 40 at p = 20: 25 at p0)."""
    k, h, tb, tt = 50.0, 25.0, 100.0, 0.0
    q = (tb - tt) / (1.0 / k + 1.0 / h + 1.0 / k)
    for coupling in ("SURFACE TO SURFACE", "NODE TO SURFACE", "NODE TO SURFACE, SYMMETRIC"):
        for name, table in (("const", "25.\n"), ("table", "10., 0.\n40., 20.\n")):
            tag = coupling[:4].lower() + ("_sym" if "SYMMETRIC" in coupling else "")
            run = run_deck(f"coupled_gap_{name}_{tag}", blocks_deck(coupling, table)).ok()
            inc = run.listing.increments[-1]
            ta = np.array(inc.block("NODE NT", set="ATOP")["NT11"])
            tb_ = np.array(inc.block("NODE NT", set="BBOTTOM")["NT11"])
            assert np.max(np.abs(ta - (tb - q / k))) < 1e-9 * tb, (coupling, name, ta, tb - q / k)
            assert np.max(np.abs(tb_ - (tt + q / k))) < 1e-9 * tb, (coupling, name, tb_, tt + q / k)
            assert abs(np.mean(ta) - np.mean(tb_) - q / h) < 1e-9 * tb
            hfl = np.array(inc.block("ELEMENT HFL")["HFL2"])
            assert np.max(np.abs(hfl - q)) < 1e-9 * q, (coupling, name, hfl)
            rb = sum(inc.block("NODE RFL", set="BOTTOM")["RFL11"])
            rt = sum(inc.block("NODE RFL", set="TOP")["RFL11"])
            assert abs(rb - q) < 1e-9 * q and abs(rt + q) < 1e-9 * q, (coupling, name, rb, rt, q)
            # the contact table's heat flux (slave to master: B is the colder side)
            # (a two-pass pair: each pass carries half)
            share = 0.5 if "SYMMETRIC" in coupling else 1.0
            flux = [float(r["heat_flux"]) for r in contact_rows(run) if r["side"] == "slave"]
            assert flux and max(abs(x + share * q) for x in flux) < 1e-7 * q, (coupling, name, flux)


def sliding_deck(coupling, generation, mu=0.3, p0=10.0, slide=0.1):
    """The blocks of blocks_deck as a base A (bottom held) and a block B
    pressed by p0 and pulled along x by `slide` at its top (its sides
    free), with friction mu and *GAP HEAT GENERATION `generation` (no
    conductance: each side's heat leaves through its own held face, A's
    bottom and B's top at 0)."""
    text = blocks_deck(coupling, "0.\n", p0=p0, t_bottom=0.0, t_top=0.0)
    text = text.replace("*GAP CONDUCTANCE\n0.\n", f"*FRICTION\n{mu}\n*GAP HEAT GENERATION\n{generation}")
    # B's sides free in x: only A's are held; B's top pulled along x
    a_sides = [n for n in map(int, text.split("*NSET, NSET=SIDES\n")[1].split("*")[0].replace(",", " ").split())
               if n < 1000]
    text = text.replace(text.split("*NSET, NSET=SIDES\n")[1].split("*")[0], ids_lines(a_sides))
    return text.replace("TOP, 11, 11, 0.0\n", f"TOP, 11, 11, 0.0\n*BOUNDARY\nTOP, 1, 1, {slide}\n")


def test_frictional_heating():
    """The block slides under p0 = 10 (N = 10 on unit width and thickness)
    with mu = 0.3 over one increment of length 1 (it tilts a little under
    the friction's moment: one corner opens): the heat is eta times the
    frictional power, the sum over the contact points of shear force times
    slip rate, the fraction f = 0.3 of it leaving through the block's held
    top and 1 - f through the base's held bottom (the reaction fluxes,
    summed: heat taken out is negative), within 1e-7 of that sum from the
    contact table (its 9 printed digits); the shear forces sum to mu N
    (1e-7) and the heat is eta mu N v with v the pulled 0.1 to 5e-3 (the
    blocks' elastic strain takes the rest of the 0.1: measured 1.9e-3). With CalculiX's given velocity (third value,
    200) the heat is eta mu N 200 whatever the slip (1e-9). Both
    couplings."""
    mu, p0, eta, frac = 0.3, 10.0, 0.9, 0.3
    cases = [(c, n, g, False) for c in ("SURFACE TO SURFACE", "NODE TO SURFACE")
             for n, g in (("slip", f"{eta}, {frac}\n"), ("velocity", f"{eta}, {frac}, 200.\n"))]
    cases += [(c, "slip", f"{eta}, {frac}\n", True) for c in ("SURFACE TO SURFACE", "NODE TO SURFACE")]
    # a two-pass pair: each pass half, f still the deck's slave's share
    cases += [("NODE TO SURFACE, SYMMETRIC", n, g, False) for n, g in (("slip", f"{eta}, {frac}\n"),
                                                                     ("velocity", f"{eta}, {frac}, 200.\n"))]
    for coupling, name, gen, nlgeom in cases:
        text = sliding_deck(coupling, gen, mu=mu, p0=p0)
        if nlgeom:
            text = text.replace("*STEP\n", "*STEP, NLGEOM\n")
        tag = coupling[:4].lower() + ("_nlgeom" if nlgeom else "") + ("_sym" if "SYMMETRIC" in coupling else "")
        run = run_deck(f"coupled_friction_heat_{name}_{tag}", text).ok()
        inc = run.listing.increments[-1]
        rb = sum(inc.block("NODE RFL", set="BOTTOM")["RFL11"])
        rt = sum(inc.block("NODE RFL", set="TOP")["RFL11"])
        rows = [r for r in contact_rows(run) if r["side"] == "slave" and r["state"] == "SLIP"]
        assert rows and all(r["state"] in ("SLIP", "OPEN") for r in contact_rows(run) if r["side"] == "slave")
        shear = np.array([float(r["shear_force"]) for r in rows])
        slip = np.abs([float(r["slip_increment"]) for r in rows])
        # (under NLGEOM the pressure follows the stretched face and the
        # normal turns: mu N within 2e-3, measured 6.3e-4)
        assert abs(shear.sum() - mu * p0) < (2e-3 if nlgeom else 1e-7) * mu * p0, (coupling, shear)
        if name == "velocity":
            q, tol = eta * mu * p0 * 200.0, 1e-9
        else:
            q, tol = eta * float(np.dot(shear, slip)), 1e-7
            assert abs(q - eta * mu * p0 * 0.1) < 5e-3 * q, (coupling, q)
        assert abs(rt + frac * q) < tol * q and abs(rb + (1 - frac) * q) < tol * q, \
            (coupling, name, rt, rb, q)


def contact_rows(run):
    """The contact table's rows of the last increment."""
    import csv
    with open(run.listing_path[:-4] + "_contact.csv") as f:
        rows = list(csv.DictReader(f))
    last = max((int(r["step"]), int(r["increment"])) for r in rows)
    return [r for r in rows if (int(r["step"]), int(r["increment"])) == last]


def two_way_pressure(k1, k2, h_of_p, e=210000.0, nu=0.3, alpha=1.2e-5, tb=100.0):
    """The blocks held at both ends (A's bottom, B's top) and on their
    sides (eps_xx = eps_zz = 0): heated from 0 with the bottom at tb and
    the top at 0, each expands by alpha (1 + nu)/(1 - nu) times its
    temperature's integral, which the uniform stress sigma_yy = -p takes
    back: p = E alpha I / (2 (1 - 2 nu)) over the stack of 2 x L = 2,
    I = tb + q/2 (1/k2 - 1/k1) the integral of T over y (T linear in each
    block), q = tb / (1/k1 + 1/h(p) + 1/k2) the heat through it. The root
    of this p(h(p)) by bisection."""
    def residual(p):
        q = tb / (1.0 / k1 + 1.0 / h_of_p(p) + 1.0 / k2)
        i = tb + 0.5 * q * (1.0 / k2 - 1.0 / k1)
        return e * alpha * i / (2.0 * (1.0 - 2.0 * nu)) - p, q
    lo, hi = 0.0, 1e4
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if residual(mid)[0] > 0.0:
            lo = mid
        else:
            hi = mid
    p = 0.5 * (lo + hi)
    return p, residual(p)[1]


def test_conductance_through_pressure_converges():
    """Two-way coupling: the blocks (CPE8T, k 50 below, 10 above) held at
    both ends, heated through the contact, expand against each other, so
    the contact pressure comes from the temperatures and the conductance
    h(p) = 10 + 0.18 p (a *GAP CONDUCTANCE table, 10 at 0, 100 at 500)
    from the pressure: the passes of the two fields converge (at most 10,
    the listing's note) to the root of the closed form (two_way_pressure):
    the total contact force (the pressure on the unit face) within 1e-7,
    the heat through the stack (the bottom's reaction flux) within 1e-7,
    both couplings; a constant h = 10 gives another pressure (more than
    1 % lower), so the table is what the answer follows."""
    table = "10., 0.\n100., 500.\n"
    p_ref, q_ref = two_way_pressure(50.0, 10.0, lambda p: 10.0 + 0.18 * min(max(p, 0.0), 500.0))
    p_const, _ = two_way_pressure(50.0, 10.0, lambda p: 10.0)
    assert (p_ref - p_const) / p_ref > 0.01, (p_ref, p_const)
    for coupling in ("SURFACE TO SURFACE", "NODE TO SURFACE"):
        text = blocks_deck(coupling, table, k1=50.0, k2=10.0, alpha=1.2e-5, top_held=True, shape="Q8",
                           et="CPE8T", nx=1, ny=2)
        run = run_deck(f"coupled_two_way_{coupling[:4].lower()}", text).ok()
        with open(run.listing_path) as f:
            notes = [line for line in f if "temperatures and contact settled in" in line]
        passes = [int(n.split("settled in ")[1].split()[0]) for n in notes]
        assert passes and max(passes) <= 10 and min(passes) >= 2, passes
        inc = run.listing.increments[-1]
        force = inc.block("CONTACT SUMMARY")["total_force"][0]
        rb = sum(inc.block("NODE RFL", set="BOTTOM")["RFL11"])
        assert abs(force - p_ref) < 1e-7 * p_ref, (coupling, force, p_ref)
        assert abs(rb - q_ref) < 1e-7 * q_ref, (coupling, rb, q_ref)


def test_result_files_carry_both_fields():
    """A coupled increment's one report holds both fields: *NODE FILE U, NT
    writes the displacements and the temperatures into the gmsh file
    (views Displacement and NT), the .frd (DISP and NDTEMP blocks, the temperature
    120 at every node) and the VTU file (arrays U and NT); the .dat has the
    temperatures (*NODE PRINT NT)."""
    import os
    m, text = plate_deck("Q4", "CPS4T", "*COUPLED TEMPERATURE-DISPLACEMENT, STEADY STATE")
    text = text.replace("*END STEP", "*NODE FILE\nU, NT\n*END STEP")
    run = run_deck("coupled_files", text, args=("--vtu",)).ok()
    d = os.path.dirname(run.listing_path)
    with open(os.path.join(d, "coupled_files.msh"), "rb") as f:
        msh = f.read()
    assert b'$NodeData\n1\n"NT"\n' in msh and b'$NodeData\n1\n"Displacement"\n' in msh
    with open(os.path.join(d, "coupled_files.frd")) as f:
        frd = f.read().splitlines()
    start = [i for i, ln in enumerate(frd) if ln.startswith(" -4  NDTEMP")]
    assert len(start) == 1 and any(ln.startswith(" -4  DISP") for ln in frd)
    rows = [ln for ln in frd[start[0]:] if ln.startswith(" -1")]
    rows = rows[:len(m.nodes)]
    assert len(rows) == len(m.nodes) and all(abs(float(r[13:25]) - 120.0) < 1e-9 for r in rows), rows
    with open(os.path.join(d, "coupled_files_0001.vtu"), "rb") as f:
        vtu = f.read()
    assert b'Name="NT"' in vtu and b'Name="U"' in vtu
    with open(os.path.join(d, "coupled_files.dat")) as f:
        dat = f.read()
    assert "temperatures for set NALL" in dat


def test_coupled_errors():
    """Bad coupled decks stop at their line with the reason (file:line:
    error, exit 1, no traceback)."""
    base = blocks_deck("SURFACE TO SURFACE", "25.\n")
    heat_only = base.replace("*COUPLED TEMPERATURE-DISPLACEMENT", "*HEAT TRANSFER").replace(
        "*DLOAD\n", "*DFLUX\n").replace(", P3, 10.0", ", S3, 10.0")
    cases = [
        (base.replace("*GAP CONDUCTANCE\n25.\n", "*GAP CONDUCTANCE, USER\n"),
         "*GAP CONDUCTANCE, USER: cfe2d has no user routines (CalculiX calls gapcon, Abaqus GAPCON); give the "
         "conductance as data lines instead"),
        (base.replace("*GAP CONDUCTANCE\n25.\n", "*GAP CONDUCTANCE, PRESSURE, CLEARANCE\n25.\n"), "not both"),
        (base.replace("*GAP CONDUCTANCE\n25.\n", "*GAP CONDUCTANCE, CLEARANCE\n25., -0.1\n"),
         "a clearance of *GAP CONDUCTANCE must not be negative"),
        (base.replace("*GAP CONDUCTANCE\n25.\n", "*GAP CONDUCTANCE, CLEARANCE\n25., 0.1\n20., 0.1\n"),
         "the clearances of a *GAP CONDUCTANCE table must increase"),
        (base.replace("*GAP CONDUCTANCE\n25.\n", "*GAP CONDUCTANCE\n25., 0., 20.\n30., 10., 100.\n"),
         "temperature-dependent *GAP CONDUCTANCE"),
        (base.replace("*GAP CONDUCTANCE\n25.\n", "*GAP CONDUCTANCE, PRESSURE\n25., 10.\n30., 5.\n"),
         "must increase"),
        (base.replace("*GAP CONDUCTANCE\n25.\n", "*GAP CONDUCTANCE\n-1.\n"), "must not be negative"),
        (base.replace("*GAP CONDUCTANCE\n25.\n", "*GAP HEAT GENERATION\n1.5, 0.5\n"), "must lie in 0 .. 1"),
        (base.replace("*SURFACE INTERACTION, NAME=GAP\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD\n"
                      "*GAP CONDUCTANCE\n25.\n", "*GAP CONDUCTANCE\n25.\n*SURFACE INTERACTION, NAME=GAP\n"),
         "outside a *SURFACE INTERACTION block"),
        (base.replace("*CONDUCTIVITY\n50.0\n", "", 1), "has no *CONDUCTIVITY"),
        (base.replace("*COUPLED TEMPERATURE-DISPLACEMENT, STEADY STATE", "*COUPLED TEMPERATURE-DISPLACEMENT"),
         "needs *DENSITY and *SPECIFIC HEAT"),
        (base.replace("*NODE PRINT, NSET=ATOP", "*TEMPERATURE\nTOP, 50.\n*NODE PRINT, NSET=ATOP"),
         "*TEMPERATURE in a deck with a *COUPLED"),
        (base.replace("*COUPLED TEMPERATURE-DISPLACEMENT, STEADY STATE",
                      "*COUPLED TEMPERATURE-DISPLACEMENT, STEADY STATE, DELTMX=0."), "DELTMX must be positive"),
        (heat_only, "needs the contact's pressures"),
    ]
    for i, (deck, msg) in enumerate(cases):
        run = run_deck("coupled_error_%d" % i, deck)
        assert run.rc == 1, (msg, run.rc, run.stderr)
        assert ": error: " in run.stderr and msg in run.stderr, (msg, run.stderr)
        assert "Traceback" not in run.stderr and "Fortran runtime" not in run.stderr


# CalculiX's ring3 (its test suite: two concentric CAX8 rings, NLGEOM,
# friction, *GAP HEAT GENERATION 0.9, 0.3, 200.), kept here as it is, and
# the temperatures of its ring3.dat.ref (CalculiX 2.20's numbers).
RING3 = """**
**    Structure: two concentric rings.
**    Test objective: *GAP HEAT GENERATION.
**
*NODE, NSET=Nall
       1,9.501000000000e-01,1.000000000000e-01,0.000000000000e+00
       2,9.501000000000e-01,0.000000000000e+00,0.000000000000e+00
       3,1.050100000000e+00,0.000000000000e+00,0.000000000000e+00
       4,1.050100000000e+00,1.000000000000e-01,0.000000000000e+00
       5,9.501000000000e-01,5.000000000000e-02,0.000000000000e+00
       6,1.000100000000e+00,0.000000000000e+00,0.000000000000e+00
       7,1.050100000000e+00,5.000000000000e-02,0.000000000000e+00
       8,1.000100000000e+00,1.000000000000e-01,0.000000000000e+00
       9,1.050000000000e+00,1.000000000000e-01,0.000000000000e+00
      10,1.050000000000e+00,0.000000000000e+00,0.000000000000e+00
      11,1.150000000000e+00,0.000000000000e+00,0.000000000000e+00
      12,1.150000000000e+00,1.000000000000e-01,0.000000000000e+00
      13,1.050000000000e+00,5.000000000000e-02,0.000000000000e+00
      14,1.100000000000e+00,0.000000000000e+00,0.000000000000e+00
      15,1.150000000000e+00,5.000000000000e-02,0.000000000000e+00
      16,1.100000000000e+00,1.000000000000e-01,0.000000000000e+00
*ELEMENT, TYPE=CAX8, ELSET=Eall
     1,1,2,3,4,5,6,7,8
     2,9,10,11,12,13,14,15,16
*MATERIAL,NAME=STEEL
*ELASTIC
210000.,.3
*DENSITY
7.8E-9
*EXPANSION
0.
*CONDUCTIVITY
5.E-3,0.
*SPECIFIC HEAT
446.E6
*SOLID SECTION,ELSET=Eall,MATERIAL=STEEL
*NSET,NSET=UP
9,10
*SURFACE,NAME=slave
2,S1
*SURFACE,NAME=master
1,S3
*CONTACT PAIR,INTERACTION=I1,TYPE=SURFACE TO SURFACE
slave,master
*SURFACE INTERACTION,NAME=I1
*SURFACE BEHAVIOR,PRESSURE-OVERCLOSURE=LINEAR
1.E7
*FRICTION
0.3,1.E5
*GAP HEAT GENERATION
0.9,0.3,200.
*NSET,NSET=N1
1,2,3,4,5,6,7,8
*NSET,NSET=N2
9,10,11,12,13,14,15,16
*NSET,NSET=FIXTEMP
2,5,1,11,15,12
*INITIAL CONDITIONS,TYPE=TEMPERATURE
Nall,293.
*STEP,NLGEOM
*COUPLED TEMPERATURE-DISPLACEMENT
*BOUNDARY
5,2,2
15,2,2
FIXTEMP,0,0,293.
*NODE PRINT,NSET=Nall
NT
*END STEP
"""
RING3_REF = {
    1: 2.930000E+02,
    2: 2.930000E+02,
    3: 4.124847E+02,
    4: 4.124847E+02,
    5: 2.930000E+02,
    6: 3.226767E+02,
    7: 4.124847E+02,
    8: 3.226767E+02,
    9: 3.422475E+02,
    10: 3.422475E+02,
    11: 2.930000E+02,
    12: 2.930000E+02,
    13: 3.422475E+02,
    14: 3.047798E+02,
    15: 2.930000E+02,
    16: 3.047798E+02}


def ring3_temperatures(run):
    """NT of the ring3 run's .dat (CalculiX's block: node, temperature)."""
    import os
    out = {}
    with open(os.path.join(os.path.dirname(run.listing_path), run.deck.rsplit("/", 1)[-1][:-4] + ".dat")) as f:
        for line in f:
            p = line.split()
            if len(p) == 2 and p[0].isdigit():
                out[int(p[0])] = float(p[1])
    return out


def test_calculix_ring3():
    """ring3 runs unchanged: its *BOUNDARY card holds displacement lines
    and a temperature line on dof 0 (CalculiX's number for the
    temperature), each read by its own reader; the card written the other
    way round gives the same .dat. CalculiX 2.20 puts 4/9 of the frictional
    heat eta mu p A v into 8-node faces (frictionheating.f sums the face's
    Jacobians at its 9 points without their weights: docs/heat.md), cfe2d
    all of it: so the temperature rises above 293 are 9/4 of the
    reference's (measured 2.2497..2.2514, tolerance 2e-3 relative), and
    with eta 0.9 x 4/9 = 0.4 they agree with the reference's (measured
    6.2e-4 of the rise, tolerance 1.5e-3); the 6 held nodes at 293 exactly."""
    run = run_deck("ring3", RING3).ok()
    got = ring3_temperatures(run)
    assert set(got) == set(RING3_REF), sorted(got)
    held = [2, 5, 1, 11, 15, 12]
    assert all(got[n] == 293.0 and RING3_REF[n] == 293.0 for n in held), got
    free = [n for n in RING3_REF if n not in held]
    ratios = [(got[n] - 293.0) / (RING3_REF[n] - 293.0) for n in free]
    assert all(abs(r / 2.25 - 1.0) < 2e-3 for r in ratios), ratios
    scaled = run_deck("ring3_eta04", RING3.replace("0.9,0.3,200.", "0.4,0.3,200.")).ok()
    got = ring3_temperatures(scaled)
    errs = [abs(got[n] - RING3_REF[n]) / (RING3_REF[n] - 293.0) for n in free]
    print(f"  ring3 (eta 0.4): largest relative error of the rise {max(errs):.2e}; unchanged: rises / reference's "
          f"{min(ratios):.4f}..{max(ratios):.4f}")
    assert max(errs) < 1.5e-3, errs
    swapped_card = "*BOUNDARY\nFIXTEMP,0,0,293.\n5,2,2\n15,2,2\n"
    swapped = RING3.replace("*BOUNDARY\n5,2,2\n15,2,2\nFIXTEMP,0,0,293.\n", swapped_card)
    assert swapped != RING3
    again = ring3_temperatures(run_deck("ring3_swapped", swapped).ok())
    assert again == ring3_temperatures(run), "the order of the lines of a *BOUNDARY card changed the answer"


def test_calculix_ring4():
    """ring4 is ring3 with `*GAP HEAT GENERATION,USER` and no data line:
    CalculiX calls its user routine fricheat, whose default (compiled
    into ccx) returns eta 0.9, f 0.3, velocity 200, ring3's values (its
    ring4.dat.ref equals ring3's within 1 in the 7th digit). cfe2d takes
    those values with a warning quoting the card: the temperatures equal
    ring3's run exactly."""
    ring4 = RING3.replace("*GAP HEAT GENERATION\n0.9,0.3,200.\n", "*GAP HEAT GENERATION,USER\n")
    assert ring4 != RING3
    run = run_deck("ring4", ring4).ok()
    assert "warning: *GAP HEAT GENERATION, USER" in run.stderr and "*GAP HEAT GENERATION,USER" in run.stderr, \
        run.stderr
    assert ring3_temperatures(run) == ring3_temperatures(run_deck("ring3", RING3).ok())


def test_model_data_temperatures_in_a_coupled_deck():
    """Prescribed temperatures in the model data of a coupled deck (a
    *BOUNDARY card before *STEP mixing a displacement line with
    temperature lines on dof 0 and 11) hold as the step's own do: the
    blocks through a conductance give the same temperatures, reaction
    fluxes and contact pressures, to the last printed digit (the fuzzer
    found the displacement field indexing a temperature there: a crash)."""
    text = blocks_deck("SURFACE TO SURFACE", "25.\n")
    step_bcs = "*BOUNDARY\nBOTTOM, 11, 11, 100.0\nTOP, 11, 11, 0.0\n"
    assert step_bcs in text
    model = text.replace(step_bcs, "").replace("*BOUNDARY\nSIDES, 1, 1\nBOTTOM, 2, 2\n",
                                                "*BOUNDARY\nSIDES, 1, 1\nBOTTOM, 0, 0, 100.0\nBOTTOM, 2, 2\n"
                                                "TOP, 11, 11, 0.0\n")
    assert model.count("*BOUNDARY") == text.count("*BOUNDARY") - 1
    a = run_deck("coupled_bcs_in_step", text).ok()
    b = run_deck("coupled_bcs_in_model", model).ok()
    inc_a, inc_b = a.listing.increments[-1], b.listing.increments[-1]
    for name, kw in (("NODE NT", {"set": "ATOP"}), ("NODE NT", {"set": "BBOTTOM"}), ("NODE RFL", {"set": "BOTTOM"}),
                     ("NODE RFL", {"set": "TOP"})):
        assert inc_a.block(name, **kw) == inc_b.block(name, **kw), (name, kw)
    assert inc_a.block("CONTACT SUMMARY") == inc_b.block("CONTACT SUMMARY")
    # q = 100 / (1/50 + 1/25 + 1/50) = 1250 through the blocks of k 50 and h 25: A's top at 100 - q/50
    nt = inc_b.block("NODE NT", set="ATOP")["NT11"]
    assert all(abs(t - 75.0) < 1e-9 * 75.0 for t in nt), nt


def transient(text, dt=0.1, period=1.0):
    """A blocks_deck made a transient coupled step of fixed increments
    (DIRECT, period / dt of them), rho c = 100 in both blocks."""
    text = text.replace("*COUPLED TEMPERATURE-DISPLACEMENT, STEADY STATE",
                        f"*COUPLED TEMPERATURE-DISPLACEMENT, DIRECT\n{dt}, {period}")
    return text.replace("*CONDUCTIVITY\n", "*DENSITY\n1.\n*SPECIFIC HEAT\n100.\n*CONDUCTIVITY\n")


def per_field(run):
    """The step summary's numeric factorisations per field: (temperature,
    displacement), and the condensed factorisations."""
    block = [b for b in run.listing.header if b.name == "STEP SUMMARY"][-1].as_dict()
    words = dict(w.split("=") for w in block["numeric_factorisations_per_field"].split())
    assert int(words["temperature"]) + int(words["displacement"]) == int(block["numeric_factorisations"]), block
    return int(words["temperature"]), int(words["displacement"]), int(block["condensed_factorisations"])


def test_coupled_step_factors_bodies_once():
    """A coupled step keeps the condensed contact solve for the
    displacements: the blocks through a gap conductance, a transient of 10
    fixed increments (each of 2 or more passes of the two fields), with
    CONTACT SOLVE=CONDENSED: the bodies are factored once for the whole
    step (the listing's per-field line: displacement=1, one condensed
    factorisation: the status holds), with segment-to-segment and with a
    SMALL SLIDING node-to-segment pair (searched once); the temperature
    matrix once too where the conductance is constant (h = 25: its
    couplings' h A w w^T do not change), again at the passes where it
    follows the pressure (h(p) = 10 + 0.18 p on blocks held at both ends:
    more than once per increment, the same count with either solve). Every increment's temperatures, reaction
    fluxes, displacements and contact force equal those of CONTACT
    SOLVE=FULL (1e-9 of each block's largest value)."""
    const = transient(blocks_deck("SURFACE TO SURFACE", "25.\n"))
    two_way = transient(blocks_deck("SURFACE TO SURFACE", "10., 0.\n100., 500.\n", k1=50.0, k2=10.0,
                                    alpha=1.2e-5, top_held=True, shape="Q8", et="CPE8T", nx=1, ny=2))
    small = const.replace("TYPE=SURFACE TO SURFACE", "TYPE=NODE TO SURFACE, SMALL SLIDING")
    for name, text, constant in (("const", const, True), ("two_way", two_way, False), ("small", small, True)):
        text = text.replace("*NODE PRINT, NSET=ATOP", "*NODE PRINT, NSET=NALL\nU\n*NODE PRINT, NSET=ATOP")
        runs = {}
        for solve in ("CONDENSED", "FULL"):
            deck = text.replace("*STEP\n", f"*SOLVER, CONTACT SOLVE={solve}\n*STEP\n", 1)
            runs[solve] = run_deck(f"coupled_factors_{name}_{solve.lower()}", deck).ok()
        cond, full = runs["CONDENSED"], runs["FULL"]
        t_cond, d_cond, c_cond = per_field(cond)
        t_full, d_full, _ = per_field(full)
        with open(cond.listing_path) as f:
            passes = [int(line.split("settled in ")[1].split()[0]) for line in f if "settled in" in line]
        assert len(cond.listing.increments) == 10 and len(passes) == 10 and min(passes) >= 2, (name, passes)
        assert d_cond == 1 and c_cond == 1, (name, d_cond, c_cond)
        assert d_full == 1, (name, d_full)
        if constant:
            assert t_cond == 1 and t_full == 1, (name, t_cond, t_full)
        else:
            assert t_cond > len(passes) and t_cond == t_full, (name, t_cond, t_full, passes)
        print(f"  {name}: factorisations temperature {t_cond}, displacement {d_cond} (condensed {c_cond}) "
              f"in 10 increments of {sum(passes)} passes")
        for a, b in zip(cond.listing.increments, full.listing.increments):
            for block, kw, comps in (("NODE NT", {"set": "ATOP"}, ("NT11",)), ("NODE NT", {"set": "BBOTTOM"},
                                     ("NT11",)), ("NODE RFL", {"set": "BOTTOM"}, ("RFL11",)),
                                     ("NODE U", {"set": "NALL"}, ("U1", "U2")),
                                     ("CONTACT SUMMARY", {}, ("total_force",))):
                x, y = a.block(block, **kw), b.block(block, **kw)
                scale = max(max(abs(v) for v in y[c]) for c in comps)
                assert scale > 0.0, (name, block)
                for c in comps:
                    err = max(abs(p - q) for p, q in zip(x[c], y[c]))
                    assert err <= 1e-9 * scale, (name, a.attrs, block, c, err, scale)



def test_gap_conductance_clearance():
    """Abaqus's clearance-dependent gap conductance (CLEARANCE, or an
    Abaqus/CAE deck without PRESSURE): k(d) = 40 - 300 d (a table, 40 at
    d = 0, 10 at d = 0.1, zero beyond). The blocks held apart at a
    clearance d0 = 0.05 (B's top held, alpha 0: nothing moves) conduct
    across the open gap: the jump is q/k(d0) = 50 with q = 100 / (2/50 +
    1/25) = 1250 through each block (temperatures exact to 1e-9 of 100,
    the reaction fluxes q and -q to 1e-9, the contact table's heat flux
    -q at every open slave point to 1e-7); node-to-segment,
    segment-to-segment and a two-pass pair (half each pass, at its own
    clearance). At d0 = 0.15, beyond the table's last clearance, nothing
    crosses (A at 100, B at 0, the reaction fluxes 1e-9 of q). B pushed
    down 0.06 (closed, d = 0): k(0) = 40, jump q/40 with q = 100 / (2/50 +
    1/40). The same table in an Abaqus/CAE deck (*PART, *ASSEMBLY) without
    PRESSURE gives the CLEARANCE answer with a warning; in a flat deck it
    is CalculiX's pressure table (the open gap conducts nothing), with a
    warning naming both readings."""
    k, table = 50.0, "40., 0.\n10., 0.1\n"

    def check(run, q, jump, tag):
        inc = run.listing.increments[-1]
        ta = np.array(inc.block("NODE NT", set=run.sets + "ATOP")["NT11"])
        tb = np.array(inc.block("NODE NT", set=run.sets + "BBOTTOM")["NT11"])
        assert np.max(np.abs(ta - (100.0 - q / k))) < 1e-9 * 100.0, (tag, ta)
        assert np.max(np.abs(tb - q / k)) < 1e-9 * 100.0, (tag, tb)
        assert abs(np.mean(ta) - np.mean(tb) - jump) < 1e-9 * 100.0, (tag, ta, tb, jump)
        rb = sum(inc.block("NODE RFL", set=run.sets + "BOTTOM")["RFL11"])
        rt = sum(inc.block("NODE RFL", set=run.sets + "TOP")["RFL11"])
        assert abs(rb - q) < 1e-9 * 1250.0 and abs(rt + q) < 1e-9 * 1250.0, (tag, rb, rt, q)

    q_open, q_closed = 100.0 / (2.0 / k + 1.0 / 25.0), 100.0 / (2.0 / k + 1.0 / 40.0)
    for coupling in ("SURFACE TO SURFACE", "NODE TO SURFACE", "NODE TO SURFACE, SYMMETRIC"):
        tag = coupling[:4].lower() + ("_sym" if "SYMMETRIC" in coupling else "")
        for name, gap, q, jump in (("open", 0.05, q_open, q_open / 25.0), ("far", 0.15, 0.0, 100.0)):
            run = run_deck(f"coupled_clearance_{name}_{tag}", blocks_deck(coupling, table, top_held=True, gap=gap,
                                                                        gc_params=", CLEARANCE")).ok()
            run.sets = ""
            assert "warning" not in run.stderr, run.stderr
            check(run, q, jump, (coupling, name))
            share = 0.5 if "SYMMETRIC" in coupling else 1.0
            rows = [r for r in contact_rows(run) if r["side"] == "slave"]
            assert rows and all(r["state"] == "OPEN" for r in rows), rows
            assert max(abs(float(r["heat_flux"]) + share * q) for r in rows) <= 1e-7 * q_open, (coupling, name)
        closing = blocks_deck(coupling, table, top_held=True, gap=0.05, gc_params=", CLEARANCE")
        assert "*BOUNDARY\nTOP, 2, 2\n" in closing
        run = run_deck(f"coupled_clearance_closed_{tag}", closing.replace("*BOUNDARY\nTOP, 2, 2\n",
                                                                          "*BOUNDARY\nTOP, 2, 2, -0.06\n")).ok()
        run.sets = ""
        assert any(r["state"] != "OPEN" for r in contact_rows(run) if r["side"] == "slave")
        check(run, q_closed, q_closed / 40.0, (coupling, "closed"))
    flat = blocks_deck("SURFACE TO SURFACE", table, top_held=True, gap=0.05, gc_params="")
    run = run_deck("coupled_clearance_cae", abaqus_cae(flat)).ok()
    run.sets = "I."
    assert "warning: *GAP CONDUCTANCE without PRESSURE in an Abaqus/CAE deck" in run.stderr, run.stderr
    check(run, q_open, q_open / 25.0, "Abaqus/CAE")
    run = run_deck("coupled_clearance_flat", flat).ok()
    run.sets = ""
    assert "read as the contact pressure, as CalculiX reads it" in run.stderr and "CLEARANCE" in run.stderr
    check(run, 0.0, 100.0, "flat")


def clearance_closed_form(d0, k1=50.0, k2=10.0, tb=100.0, e=210000.0, nu=0.3, alpha=1.2e-5):
    """The blocks of test_clearance_two_way (held at both ends and on their
    sides, heated from 0 with the bottom at tb and the top at 0, B's bottom
    d0 above A's top) through k(d) = 40 - 7500 d (0 beyond d = 0.004):
    each block lengthens by alpha (1 + nu)/(1 - nu) times the integral I of
    its temperature (T linear in each block: I = tb + q/2 (1/k2 - 1/k1) for
    the two), which closes the gap to d = d0 - alpha (1 + nu)/(1 - nu) I,
    and q = tb / (1/k1 + 1/k(d) + 1/k2): the root d by bisection, and q;
    where the expansion exceeds d0 the gap closes (k(0)) and the contact
    pressure is M (alpha (1 + nu)/(1 - nu) I - d0) / 2, M the constrained
    modulus, over the stack of 2. Returns d, q, p."""
    c = alpha * (1.0 + nu) / (1.0 - nu)

    def k_of(d):
        return 0.0 if d > 0.004 else 40.0 - 7500.0 * d

    def state(d):
        q = tb / (1.0 / k1 + 1.0 / k_of(d) + 1.0 / k2)
        return q, tb + 0.5 * q * (1.0 / k2 - 1.0 / k1)
    q, i = state(0.0)
    if c * i >= d0:
        return 0.0, q, e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu)) * (c * i - d0) / 2.0
    lo, hi = 0.0, d0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if d0 - c * state(mid)[1] > mid:
            lo = mid
        else:
            hi = mid
    d = 0.5 * (lo + hi)
    return d, state(d)[0], 0.0


def test_clearance_two_way():
    """The clearance closes as the blocks heat (CPE8T, k 50 below and 10
    above, alpha 1.2e-5, held at both ends) through k(d) = 40 - 7500 d:
    with d0 = 0.004 it stays open at d = 1.19e-3 (clearance_closed_form):
    the passes settle (2 .. 20, the listing's note), the heat through the
    stack (the bottom's reaction flux) within 1e-7 of the root's, the
    contact table's gap d within 1e-7 of d0; no contact force. With d0 =
    0.002 the expansion closes it: k(0) = 40, the heat within 1e-7 and the
    contact force (the pressure on the unit face) within 1e-7 of the
    closed form. Both couplings."""
    for d0 in (0.004, 0.002):
        d, q, p = clearance_closed_form(d0)
        assert (p == 0.0) == (d0 == 0.004) and (d > 1e-3 if p == 0.0 else d == 0.0), (d0, d, p)
        for coupling in ("SURFACE TO SURFACE", "NODE TO SURFACE"):
            text = blocks_deck(coupling, "40., 0.\n10., 0.004\n", k1=50.0, k2=10.0, alpha=1.2e-5, top_held=True,
                               shape="Q8", et="CPE8T", nx=1, ny=2, gap=d0, gc_params=", CLEARANCE")
            run = run_deck(f"coupled_clearance_two_way_{d0}_{coupling[:4].lower()}", text).ok()
            with open(run.listing_path) as f:
                passes = [int(line.split("settled in ")[1].split()[0]) for line in f if "settled in" in line]
            assert passes and 2 <= min(passes) and max(passes) <= 20, passes
            inc = run.listing.increments[-1]
            rb = sum(inc.block("NODE RFL", set="BOTTOM")["RFL11"])
            force = inc.block("CONTACT SUMMARY")["total_force"][0]
            assert abs(rb - q) < 1e-7 * q, (coupling, d0, rb, q)
            assert abs(force - p) < 1e-7 * max(p, 100.0), (coupling, d0, force, p)
            gaps = [float(r["gap"]) for r in contact_rows(run) if r["side"] == "slave"]
            assert gaps and max(abs(g - d) for g in gaps) < 1e-7 * d0, (coupling, d0, gaps, d)
            print(f"  {coupling}, d0 {d0}: {max(passes)} passes, heat {rb:.10g} (closed form {q:.10g}), "
                  f"force {force:.10g} ({p:.10g}), gap {max(gaps):.6e} ({d:.6e})")

def abaqus_cae(text):
    """A blocks_deck (held at its top: no element loads) written as
    Abaqus/CAE writes a deck: its mesh, sets, surfaces and sections in a
    *PART, one *INSTANCE I of it in the *ASSEMBLY, the rest at the model
    level naming the instance's sets I.NAME."""
    import re
    heading, rest = text.split("*NODE, NSET=NALL\n", 1)
    mesh, rest = rest.split("*MATERIAL, NAME=M1\n", 1)
    sections = "*SOLID SECTION, ELSET=A, MATERIAL=M1\n1.\n*SOLID SECTION, ELSET=B, MATERIAL=M2\n1.\n"
    assert sections in rest and "*DLOAD" not in rest
    rest = rest.replace(sections, "")
    rest = re.sub(r"\b(BSURF|ASURF|SIDES|BOTTOM|TOP|ATOP|BBOTTOM)\b", r"I.\1", rest)
    return (heading + "*PART, NAME=BLOCKS\n*NODE, NSET=NALL\n" + mesh + sections + "*END PART\n"
            "*ASSEMBLY, NAME=ASSEMBLY\n*INSTANCE, NAME=I, PART=BLOCKS\n*END INSTANCE\n*END ASSEMBLY\n"
            "*MATERIAL, NAME=M1\n" + rest)
