"""Heat transfer (*HEAT TRANSFER, temperature_field; docs/heat.md) against
closed-form answers:

- a plane slab held at T0 on one face and cooled by a film (h, T_sink) on
  the other: the temperature is linear, q = (T0 - T_sink) / (L/k + 1/h),
  which every element reproduces to round-off (tolerance 1e-10 relative);
  the same with the heat put in by *DFLUX or *CFLUX instead of T0;
- radial conduction in a thick cylinder (CAX8 and DCAX4, axisymmetric):
  T = Ta + (Tb - Ta) ln(r/a) / ln(b/a), and the heat through it, the
  reaction flux summed over the inner face, 2 pi k H (Ta - Tb) / ln(b/a)
  (the whole circumference); tolerances are the mesh's, stated per test;
- transient conduction into a finite slab (backward Euler) against the
  Fourier series, the error at a fixed time falling at first order in the
  time step (ratio 2 +- 0.15 per halving); automatic increments under
  DELTMX, which conserve the heat put in;
- a conductivity table (steady slab against the Kirchhoff solution);
- CalculiX's dam (orthotropic conductivity) against its .dat.ref;
- the cards cfe2d does not have (*RADIATE, a mechanical step in a heat
  deck, anisotropic conductivity, a specific heat table) stop with
  file:line: error.
"""
import math

from helpers import run_deck
from quadmesh import Mesh


def node_values(run, name, step=1, inc=-1):
    """{node: value} of the NODE <name> block of an increment (the last)."""
    incs = [i for i in run.listing.increments if i.step == step]
    b = incs[inc].block("NODE " + name)
    return dict(zip((int(n) for n in b["node"]), b[b.columns[1]]))


def slab_deck(shape, et, nx, length, height, left, right, material, step_cards, step="*HEAT TRANSFER, STEADY STATE",
              thickness=1.0, extra=""):
    m = Mesh(shape, nx, 2, lambda s, t: (length * s / nx, height * t / 2), straight=True)
    films = "".join(f"{e}, F{k}, {right[1]}, {right[0]}\n" for e, k in m.faces("right")) if right else ""
    left_nodes = ", ".join(map(str, m.side("left")))
    deck = f"""*NODE, NSET=NALL
{m.node_lines()}{m.element_card(et, 'EALL')}*NSET, NSET=LEFT
{left_nodes}
*MATERIAL, NAME=M
{material}*SOLID SECTION, ELSET=EALL, MATERIAL=M
{thickness}
{extra}*STEP
{step}
{step_cards}"""
    if left is not None:
        deck += f"*BOUNDARY\nLEFT, 11, 11, {left}\n"
    if films:
        deck += "*FILM\n" + films
    deck += "*NODE PRINT, NSET=NALL\nNT, RFL\n*EL PRINT, ELSET=EALL\nHFL\n*END STEP\n"
    return m, deck


def check_linear(m, nt, t_at, tol):
    worst = 0.0
    for n, (x, _) in m.nodes.items():
        worst = max(worst, abs(nt[n] - t_at(x)) / 100.0)
    assert worst < tol, f"largest error {worst:.3e} of the linear temperature (tolerance {tol})"


def test_slab_film_every_element():
    """T0 = 100 at x = 0, film h = 50 to 20 at x = L = 1, k = 10: q = 80 /
    0.12, T(x) = 100 - q x / k, on every plane element and a thickness of
    0.1; the reaction flux over the left face is q A; the heat flux HFL
    (*EL PRINT) is (q, 0) at every integration point (1e-10 of q)."""
    k, h, sink, t0, length, height, thick = 10.0, 50.0, 20.0, 100.0, 1.0, 0.4, 0.1
    q = (t0 - sink) / (length / k + 1.0 / h)
    for shape, et in (("T3", "DC2D3"), ("Q4", "DC2D4"), ("T6", "DC2D6"), ("Q8", "DC2D8"), ("Q4", "CPS4"),
                      ("Q8", "CPE8R"), ("T6", "CPS6")):
        m, deck = slab_deck(shape, et, 3, length, height, t0, (h, sink), "*CONDUCTIVITY\n10.\n", "",
                            thickness=thick)
        run = run_deck("heat_slab_" + et, deck).ok()
        nt = node_values(run, "NT")
        check_linear(m, nt, lambda x: t0 - q * x / k, 1e-10)
        rfl = node_values(run, "RFL")
        total = sum(rfl[n] for n in m.side("left"))
        assert abs(total - q * height * thick) < 1e-9 * q * height * thick, (et, total, q * height * thick)
        hfl = run.listing.increments[-1].block("ELEMENT HFL")
        assert len(hfl) > 0 and max(abs(hfl["HFL1"] - q)) < 1e-10 * q and max(abs(hfl["HFL2"])) < 1e-10 * q, et


def test_slab_fluxes():
    """The heat put in by *DFLUX on the left faces (S4 of the quadrilaterals)
    or by *CFLUX at the left nodes (the same total) leaves through the film:
    T(x) = sink + q/h + q (L - x) / k."""
    k, h, sink, q, length, height = 10.0, 50.0, 20.0, 300.0, 1.0, 0.4
    m = Mesh("Q4", 3, 2, lambda s, t: (length * s / 3, height * t / 2), straight=True)
    left_faces = "".join(f"{e}, S{f}, {q}\n" for e, f in m.faces("left"))
    left = m.side("left")
    # the consistent nodal share of a uniform flux on two linear faces: 1/4, 1/2, 1/4 of q H
    shares = {left[0]: 0.25, left[1]: 0.5, left[2]: 0.25}
    cflux = "".join(f"{n}, 11, {q * height * s}\n" for n, s in shares.items())
    for name, cards in (("dflux", "*DFLUX\n" + left_faces), ("cflux", "*CFLUX\n" + cflux)):
        m, deck = slab_deck("Q4", "DC2D4", 3, length, height, None, (h, sink), "*CONDUCTIVITY\n10.\n", cards)
        run = run_deck("heat_slab_" + name, deck).ok()
        check_linear(m, node_values(run, "NT"), lambda x: sink + q / h + q * (length - x) / k, 1e-10)


def cylinder_deck(shape, et, nr, a, b, height, ta, tb, k):
    m = Mesh(shape, nr, 1, lambda s, t: (a + (b - a) * s / nr, height * t), straight=False)
    return m, f"""*NODE, NSET=NALL
{m.node_lines()}{m.element_card(et, 'EALL')}*NSET, NSET=INNER
{", ".join(map(str, m.side("left")))}
*NSET, NSET=OUTER
{", ".join(map(str, m.side("right")))}
*MATERIAL, NAME=M
*CONDUCTIVITY
{k}
*SOLID SECTION, ELSET=EALL, MATERIAL=M
*STEP
*HEAT TRANSFER, STEADY STATE
*BOUNDARY
INNER, 11, 11, {ta}
OUTER, 11, 11, {tb}
*NODE PRINT, NSET=NALL
NT, RFL
*EL PRINT, ELSET=EALL
HFL
*END STEP
"""


def test_cylinder_radial_conduction():
    """Thick cylinder a = 1, b = 2, Ta = 100, Tb = 0, k = 5, height 0.1:
    T = Ta + (Tb - Ta) ln(r/a) / ln 2 and the heat through the inner face
    2 pi k H (Ta - Tb) / ln 2 = 453.236; 8 quadratic elements (CAX8) within
    1e-5 of Ta - Tb, 16 linear ones (DCAX4) within 1e-4 (the mesh's
    error, measured 1.5e-6 and 3.0e-5); the heat within 1e-5 and 5e-4
    (measured 4.5e-7 and 1.8e-4); CAX8's HFL at its 3x3 points against
    k (Ta - Tb) / (r ln 2) within 2e-3 (measured 1.16e-3; 3.1e-4 on 16
    elements: the gradient's second order)."""
    a, b, height, ta, tb, k = 1.0, 2.0, 0.1, 100.0, 0.0, 5.0
    q_exact = 2 * math.pi * k * height * (ta - tb) / math.log(b / a)
    for shape, et, nr, tol_t, tol_q in (("Q8", "CAX8", 8, 1e-5, 1e-5), ("Q4", "DCAX4", 16, 1e-4, 5e-4)):
        m, deck = cylinder_deck(shape, et, nr, a, b, height, ta, tb, k)
        run = run_deck("heat_cylinder_" + et, deck).ok()
        nt = node_values(run, "NT")
        worst = max(abs(nt[n] - (ta + (tb - ta) * math.log(x / a) / math.log(b / a))) / (ta - tb)
                    for n, (x, _) in m.nodes.items())
        assert worst < tol_t, f"{et}: largest error {worst:.3e} of ln r (tolerance {tol_t})"
        rfl = node_values(run, "RFL")
        q = sum(rfl[n] for n in m.side("left"))
        assert abs(q - q_exact) < tol_q * q_exact, f"{et}: heat {q} against {q_exact}"
        if et == "CAX8":
            # the radial heat flux k (Ta - Tb) / (r ln(b/a)) at the 3x3 points (xi fastest) of each element
            g = math.sqrt(0.6)
            hfl = run.listing.increments[-1].block("ELEMENT HFL")
            worst = 0.0
            for e, ip, q1, q2 in zip(hfl["element"], hfl["ip"], hfl["HFL1"], hfl["HFL2"]):
                xi = (-g, 0.0, g)[(int(ip) - 1) % 3]
                r = a + (b - a) * (int(e) - 1 + 0.5 * (1 + xi)) / nr
                exact = k * (ta - tb) / (r * math.log(b / a))
                worst = max(worst, abs(q1 - exact) / exact, abs(q2) / exact)
            assert worst < 2e-3, f"HFL: largest error {worst:.2e}"


def slab_series(x, t, length, alpha, terms=200):
    """T(x, t) of a slab at 0 for t < 0, held at 1 at x = 0 from t = 0 and
    insulated at x = L (Carslaw and Jaeger's series)."""
    s = 0.0
    for n in range(terms):
        lam = (2 * n + 1) * math.pi / (2 * length)
        s += 4.0 / ((2 * n + 1) * math.pi) * math.sin(lam * x) * math.exp(-alpha * lam * lam * t)
    return 1.0 - s


def transient_deck(dt, period, nx):
    material = "*CONDUCTIVITY\n2.\n*DENSITY\n4.\n*SPECIFIC HEAT\n0.5\n"   # alpha = 2 / (4 * 0.5) = 1
    return slab_deck("Q8", "DC2D8", nx, 1.0, 0.1, 1.0, None, material, "",
                     step=f"*HEAT TRANSFER, DIRECT\n{dt}, {period}",
                     extra="*INITIAL CONDITIONS, TYPE=TEMPERATURE\nNALL, 0.\n")


def test_transient_slab_first_order():
    """Finite slab (L = 1, alpha = 1) from 0, held at 1 at x = 0: T at the
    insulated end at t = 0.2 (exact 0.227688) by backward Euler with
    dt = 0.01, 0.005, 0.0025 on 20 DC2D8: the error (measured 2.00e-3,
    1.06e-3, 5.5e-4) within 3e-3, 1.5e-3, 8e-4 and halved with every
    halving of dt (ratio 2 +- 0.15, measured 1.88 and 1.94: first
    order; the spatial error is far below)."""
    t_end = 0.2
    exact = slab_series(1.0, t_end, 1.0, 1.0)
    errs = []
    for dt in (0.01, 0.005, 0.0025):
        m, deck = transient_deck(dt, t_end, 20)
        run = run_deck("heat_transient_%g" % dt, deck).ok()
        incs = run.listing.increments
        assert len(incs) == round(t_end / dt), len(incs)
        assert abs(incs[-1].time - t_end) < 1e-12
        nt = node_values(run, "NT")
        far = [n for n in m.side("right")]
        errs.append(max(abs(nt[n] - exact) for n in far))
    for e, bound in zip(errs, (3e-3, 1.5e-3, 8e-4)):
        assert e < bound, (errs, bound)
    for e1, e2 in zip(errs, errs[1:]):
        assert abs(e1 / e2 - 2.0) < 0.15, f"errors {errs}: not first order"


def test_transient_deltmx():
    """Automatic increments with DELTMX = 0.05: a flux of 1 into the left
    face of a slab from 0; from an initial 0.001 the increments grow (1.5
    times after two that pass) or are cut, and none changes a temperature
    by more than 0.05; the last ends at the period; the heat stored,
    rho c times the integral of T, is the heat put in, q H t (to 1e-9:
    backward Euler conserves energy exactly)."""
    material = "*CONDUCTIVITY\n2.\n*DENSITY\n4.\n*SPECIFIC HEAT\n0.5\n"
    m = Mesh("Q4", 10, 2, lambda s, t: (s / 10, 0.1 * t / 2), straight=True)   # slab_deck's mesh
    flux = "".join(f"{e}, S{f}, 1.\n" for e, f in m.faces("left"))
    m, deck = slab_deck("Q4", "DC2D4", 10, 1.0, 0.1, None, None, material, "*DFLUX\n" + flux,
                        step="*HEAT TRANSFER, DELTMX=0.05\n0.001, 1.",
                        extra="*INITIAL CONDITIONS, TYPE=TEMPERATURE\nNALL, 0.\n")
    run = run_deck("heat_deltmx", deck).ok()
    incs = run.listing.increments
    prev = {n: 0.0 for n in m.nodes}
    for inc in incs:
        b = inc.block("NODE NT")
        cur = dict(zip((int(n) for n in b["node"]), b["NT11"]))
        assert max(abs(cur[n] - prev[n]) for n in m.nodes) <= 0.05 + 1e-12
        prev = cur
    assert abs(incs[-1].time - 1.0) < 1e-12
    assert 5 < len(incs) < 200, len(incs)
    # energy: rho c int T dV over the strip (linear elements: the trapezoid rule is exact for T linear in
    # each element) against q H t
    xs = sorted({x for x, _ in m.nodes.values()})
    tx = {x: sum(prev[n] for n, (xx, _) in m.nodes.items() if xx == x) / 3 for x in xs}
    stored = 2.0 * 0.1 * sum((tx[a] + tx[b]) / 2 * (b - a) for a, b in zip(xs, xs[1:]))
    assert abs(stored - 1.0 * 0.1 * 1.0) < 1e-9, stored


def test_heat_errors():
    """Cards cfe2d does not have stop at their line with the reason."""
    base = slab_deck("Q4", "DC2D4", 2, 1.0, 0.2, 100.0, None, "*CONDUCTIVITY\n10.\n", "")[1]
    cases = [
        (base.replace("*END STEP", "*RADIATE\n1, R2, 20., 0.8\n*END STEP"), "*RADIATE is not implemented"),
        (base.replace("*CONDUCTIVITY\n", "*CONDUCTIVITY, TYPE=ANISO\n"), "TYPE=ANISO of *CONDUCTIVITY is not"),
        (base.replace("*CONDUCTIVITY\n10.\n", "*CONDUCTIVITY\n10.\n*SPECIFIC HEAT\n1., 20.\n2., 100.\n"),
         "temperature-dependent *SPECIFIC HEAT"),
        (base.replace("*CONDUCTIVITY\n10.\n", "*CONDUCTIVITY\n10., 100.\n10., 20.\n"), "must increase"),
        (base + "*STEP\n*STATIC\n*END STEP\n", "has no *ELASTIC"),
        (base.replace("*CONDUCTIVITY\n10.\n", "*ELASTIC\n1000., 0.3\n"), "has no *CONDUCTIVITY"),
        (base.replace("*HEAT TRANSFER, STEADY STATE", "*HEAT TRANSFER\n0.1, 1."), "needs *DENSITY and *SPECIFIC"),
        (base.replace("*HEAT TRANSFER, STEADY STATE", "*STATIC"), "it belongs to a *HEAT TRANSFER step"),
        # magnitudes that overflow: stopped, never a NaN in the listing
        (base.replace("*CONDUCTIVITY\n10.\n", "*CONDUCTIVITY\n1e300\n").replace("LEFT, 11, 11, 100.0",
                                                                              "LEFT, 11, 11, 1e300"),
         "is not a finite number"),
        (base.replace("*HEAT TRANSFER, STEADY STATE", "*HEAT TRANSFER, DIRECT\n1e-9, 1."), "increments"),
        (base.replace("*HEAT TRANSFER, STEADY STATE", "*HEAT TRANSFER, STEADY STATE, TIME RESET"), "TIME RESET"),
        # a heat transfer element in a mechanical deck
        (base.replace("*CONDUCTIVITY\n10.\n", "*ELASTIC\n1000., 0.3\n").replace(
            "*HEAT TRANSFER, STEADY STATE", "*STATIC").replace("*BOUNDARY\nLEFT, 11, 11, 100.0\n",
                                                              "*BOUNDARY\nLEFT, 1, 2\n"), "is a heat transfer element"),
        # a region with neither a held temperature nor a film: no steady state
        (base.replace("*BOUNDARY\nLEFT, 11, 11, 100.0\n", "*CFLUX\n1, 11, 1.\n"), "matrix is singular"),
    ]
    for i, (deck, msg) in enumerate(cases):
        run = run_deck("heat_error_%d" % i, deck)
        assert run.rc != 0, (msg, run.stdout)
        assert ": error: " in run.stderr and msg in run.stderr, (msg, run.stderr)
        assert "Traceback" not in run.stderr and "Fortran runtime" not in run.stderr


DEBIAN = "/usr/share/doc/calculix-ccx-test/examples/test"


def test_calculix_dam():
    """CalculiX's dam (its test suite, as Debian's calculix-ccx-test ships
    it): steady conduction in a CPS8 dam of two orthotropic materials
    between two held temperatures, run unchanged; the temperatures of the
    .dat (CalculiX's block) agree with its .dat.ref at all 1045 nodes
    within 1e-6 of the largest (the reference's 7 digits; measured: every
    printed digit equal)."""
    import gzip
    import os
    from helpers import Skip
    if not os.path.isfile(os.path.join(DEBIAN, "dam.inp.gz")):
        raise Skip("Debian's calculix-ccx-test is not installed (scripts/install-deps.sh installs it)")
    with gzip.open(os.path.join(DEBIAN, "dam.inp.gz"), "rt") as f:
        text = f.read()
    with gzip.open(os.path.join(DEBIAN, "dam.dat.ref.gz"), "rt") as f:
        ref_text = f.read()
    run = run_deck("dam", text).ok()

    def temperatures(t):
        out = {}
        for line in t.splitlines():
            p = line.split()
            if len(p) == 2 and p[0].isdigit():
                out[int(p[0])] = float(p[1])
        return out
    with open(os.path.join(os.path.dirname(run.listing_path), "dam.dat")) as f:
        got = temperatures(f.read())
    ref = temperatures(ref_text)
    assert len(ref) == 1045 and set(got) == set(ref), (len(ref), len(got))
    scale = max(abs(v) for v in ref.values())
    worst = max(abs(got[n] - ref[n]) for n in ref) / scale
    assert worst < 1e-6, worst


def test_result_files_carry_temperatures():
    """*NODE FILE NT: the temperatures in the gmsh file (view NT), the
    .frd (CalculiX's NDTEMP block, node 1 at 100) and the VTU (array NT)."""
    import os
    m, deck = slab_deck("Q4", "DC2D4", 2, 1.0, 0.2, 100.0, (50.0, 20.0), "*CONDUCTIVITY\n10.\n", "")
    deck = deck.replace("*END STEP", "*NODE FILE\nNT\n*END STEP")
    run = run_deck("heat_files", deck, args=("--vtu",)).ok()
    d = os.path.dirname(run.listing_path)
    with open(os.path.join(d, "heat_files.msh"), "rb") as f:
        assert b'$NodeData\n1\n"NT"\n' in f.read()
    with open(os.path.join(d, "heat_files.frd")) as f:
        frd = f.read()
    assert " -4  NDTEMP      1    1" in frd and " -5  T           1    1    0    0" in frd, frd[-600:]
    row = [ln for ln in frd.splitlines() if ln.startswith(" -1         1")][-1]
    assert abs(float(row[13:25]) - 100.0) < 1e-9, row
    with open(os.path.join(d, "heat_files_0001.vtu"), "rb") as f:
        assert b'Name="NT"' in f.read()


def test_steps_and_amplitudes():
    """Two steps. Step 1, steady, 4 increments: a *DFLUX of 300 times the
    amplitude A (0 at t = 0, 2 at t = 1) into the left face of a slab with
    a film (h = 50, sink 20) on the right: at every increment T(x) = 20 +
    q/h + q (L - x)/k with q = 600 t, exact (1e-10). Step 2, transient
    (backward Euler, 3 fixed increments), the same loads held at their end
    values (OP=MOD: a step's cards add to the earlier ones'; the flux's
    amplitude stays A, held at 2 beyond t = 1): the steady state of step 1
    is a fixed point, kept to 1e-10 at every increment."""
    k, h, sink, length, height = 10.0, 50.0, 20.0, 1.0, 0.4
    m = Mesh("Q4", 3, 2, lambda s, t: (length * s / 3, height * t / 2), straight=True)
    flux = "".join(f"{e}, S{f}, 300.\n" for e, f in m.faces("left"))
    material = "*CONDUCTIVITY\n10.\n*DENSITY\n3.\n*SPECIFIC HEAT\n7.\n"
    m, deck = slab_deck("Q4", "DC2D4", 3, length, height, None, (h, sink), material, "*DFLUX, AMPLITUDE=A\n" + flux,
                        step="*HEAT TRANSFER, STEADY STATE\n0.25, 1.",
                        extra="*AMPLITUDE, NAME=A\n0., 0., 1., 2.\n")
    deck += """*STEP
*HEAT TRANSFER, DIRECT
0.1, 0.3
*NODE PRINT, NSET=NALL
NT
*END STEP
"""
    run = run_deck("heat_steps", deck).ok()
    incs = run.listing.increments
    assert [i.step for i in incs] == [1] * 4 + [2] * 3, [i.step for i in incs]
    for inc in incs:
        q = 600.0 * (min(float(inc.attrs["time"]), 1.0) if inc.step == 1 else 1.0)
        b = inc.block("NODE NT")
        nt = dict(zip((int(n) for n in b["node"]), b["NT11"]))
        worst = max(abs(nt[n] - (sink + q / h + q * (length - x) / k)) for n, (x, _) in m.nodes.items())
        assert worst < 1e-10 * 100, (inc.attrs, worst)


def kirchhoff_slab(x):
    """T(x) of a slab held at 100 (x = 0) and 0 (x = 1) with k = 10 (1 +
    0.01 T): the Kirchhoff transform 10 (T + 0.005 T^2) is linear in x,
    1500 (1 - x)."""
    return (-10.0 + math.sqrt(100.0 + 0.2 * 1500.0 * (1.0 - x))) / 0.1


def test_conductivity_table():
    """*CONDUCTIVITY as a table (10 at 0, 30 at 200: k = 10 (1 + 0.01 T)),
    steady slab between 100 and 0 (fixed-point iterations): T against
    the Kirchhoff solution within 1e-6 of 100 on 10 DC2D8 (measured
    4.9e-7), the heat through it, 1500 per unit area, within 1e-9
    (measured 1.6e-12); the same table as ORTHO (k11 = k22) gives the
    same temperatures to 1e-12."""
    table = "*CONDUCTIVITY\n10., 0.\n30., 200.\n"
    results = []
    for name, material in (("iso", table), ("ortho", "*CONDUCTIVITY, TYPE=ORTHO\n10., 10., 10., 0.\n"
                                                       "30., 30., 30., 200.\n")):
        m, deck = slab_deck("Q8", "DC2D8", 10, 1.0, 0.1, 100.0, None, material, "")
        deck = deck.replace("*NODE PRINT", "*BOUNDARY\nRIGHT, 11, 11, 0.\n*NODE PRINT").replace(
            "*MATERIAL", "*NSET, NSET=RIGHT\n" + ", ".join(map(str, m.side("right"))) + "\n*MATERIAL")
        run = run_deck("heat_ktable_" + name, deck).ok()
        nt = node_values(run, "NT")
        worst = max(abs(nt[n] - kirchhoff_slab(x)) for n, (x, _) in m.nodes.items()) / 100.0
        rfl = node_values(run, "RFL")
        q = sum(rfl[n] for n in m.side("left")) / 0.1
        assert worst < 1e-6, f"{name}: largest error {worst:.2e} of the Kirchhoff solution"
        assert abs(q - 1500.0) < 1e-9 * 1500.0, (name, q)
        assert int(run.listing.increments[-1].attrs["iterations"]) > 3
        results.append(nt)
    assert max(abs(results[0][n] - results[1][n]) for n in results[0]) < 1e-12 * 100
