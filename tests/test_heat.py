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
- CalculiX's dam (orthotropic conductivity) and ax6ht (CAX6) against
  their .dat.ref;
- radiation to the environment (*RADIATE, Newton): a steady slab against
  the root of its energy balance, a plate cooling to 0 K against
  backward Euler on its ODE and the ODE's closed form;
- the cards cfe2d does not have (cavity radiation, a mechanical step in
  a heat deck, anisotropic conductivity) stop with file:line: error.
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


def dat_temperatures(path):
    """[(time, {node: temperature})] of the "temperatures for set" blocks of
    a CalculiX or cfe2d .dat."""
    import re
    out = []
    with open(path) as f:
        for line in f:
            m = re.match(r"\s*temperatures for set \S+ and time\s+(\S+)", line)
            if m:
                out.append((float(m.group(1)), {}))
                continue
            p = line.split()
            if out and len(p) == 2 and p[0].isdigit():
                out[-1][1][int(p[0])] = float(p[1])
    return out


def test_deltmx_increments_as_calculix():
    """Automatic increments under DELTMX = 0.05 on a CPS8 strip from 0
    (tests/calculix/heat_deltmx_*.inp, run once with CalculiX 2.20, its
    .dat kept beside them; docs/heat.md): the left end held at 1 from t = 0
    (a step) or heated by a flux of 1. Every increment CalculiX accepts
    (51 and 23, with 20 and 5 cut back) is cfe2d's: the same step times
    (to 1e-6, the printed digits) and the same temperatures at five
    points (to 1e-6 + 1e-6 |T|; measured: every printed digit equal). It
    takes CalculiX's cut back (0.85 DELTMX / the largest change), its
    growth (1.5 times after two increments in a row) and its capacity
    term, which acts on the change of the free temperatures only (with
    the prescribed ones' change in it, a step of the held end moves its
    neighbours by a finite amount however small the increment)."""
    import os
    here = os.path.dirname(os.path.abspath(__file__))
    for name, count in (("heat_deltmx_step", 51), ("heat_deltmx_flux", 23)):
        ref = dat_temperatures(os.path.join(here, "calculix", name + ".dat"))
        run = run_deck(name, path=os.path.join(here, "calculix", name + ".inp")).ok()
        got = dat_temperatures(os.path.join(os.path.dirname(run.listing_path), name + ".dat"))
        assert len(ref) == count and len(got) == count, (name, len(ref), len(got))
        for (t_ref, nt_ref), (t, nt) in zip(ref, got):
            assert abs(t - t_ref) <= 1e-6 * t_ref, (name, t, t_ref)
            assert set(nt) == set(nt_ref), (name, t)
            worst = max(abs(nt[n] - v) - 1e-6 * abs(v) for n, v in nt_ref.items())
            assert worst <= 1e-6, (name, t, worst)


def test_automatic_increments():
    """Without DIRECT the increments are automatic, as CalculiX's, with or
    without DELTMX and in a steady step too: the first two of the initial
    size, each next one 1.5 times the one before (two increments in a row
    that converged at once), the last cut to the step's end, never above
    the maximum (the data line's fourth field); with DIRECT period /
    initial of them. Step times against that rule to 1e-8 (the listing's
    9 digits; CalculiX's .sta has the same sequences: 17, 29, 6
    increments); a step of 0.1, 1000. under INC=100 (CalculiX's axrad)
    takes 23."""
    material = "*CONDUCTIVITY\n2.\n*DENSITY\n4.\n*SPECIFIC HEAT\n0.5\n"
    m = Mesh("Q4", 10, 2, lambda s, t: (s / 10, 0.1 * t / 2), straight=True)   # slab_deck's mesh
    flux = "*DFLUX\n" + "".join(f"{e}, S{f}, 1.\n" for e, f in m.faces("left"))

    def rule(dt0, period, dt_max):
        times, t, dt, k = [], 0.0, dt0, 0
        while t < period - 1e-12:
            step = min(dt, period - t)
            t += step
            times.append(t)
            k += 1
            if k >= 2:
                dt = min(1.5 * dt, dt_max)
        return times
    cases = [("auto", "*HEAT TRANSFER\n0.001, 1.", rule(0.001, 1.0, 1.0)),
             ("auto_max", "*HEAT TRANSFER\n0.001, 1., 1e-5, 0.05", rule(0.001, 1.0, 0.05)),
             ("steady", "*HEAT TRANSFER, STEADY STATE\n0.1, 1.", rule(0.1, 1.0, 1.0)),
             ("direct", "*HEAT TRANSFER, DIRECT\n0.01, 0.1", [0.01 * (k + 1) for k in range(10)]),
             # CalculiX's axrad step (INC=100 on its *STEP): 23 increments where fixed ones would be 10 000
             ("axrad_step", "*HEAT TRANSFER\n0.1, 1000.", rule(0.1, 1000.0, 1000.0))]
    for name, step, times in cases:
        m, deck = slab_deck("Q4", "DC2D4", 10, 1.0, 0.1, None, (50.0, 20.0), material, flux, step=step,
                            extra="*INITIAL CONDITIONS, TYPE=TEMPERATURE\nNALL, 0.\n")
        run = run_deck("heat_increments_" + name, deck.replace("*STEP\n", "*STEP, INC=100\n")).ok()
        got = [float(i.attrs["time"]) for i in run.listing.increments]
        assert len(got) == len(times), (name, len(got), len(times))
        assert max(abs(a - b) / b for a, b in zip(got, times)) < 1e-8, (name, got, times)
    assert [len(c[2]) for c in cases] == [17, 29, 6, 10, 23]


def bisect(g, lo, hi):
    """The root of g, increasing on [lo, hi], to round-off."""
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if g(mid) > 0.0:
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


def test_radiation_steady_slab():
    """*RADIATE: a slab (L = 0.1, k = 10) held at 500 C on the left,
    radiating from its right face (emissivity 0.8) to surroundings at 20 C
    (*PHYSICAL CONSTANTS, ABSOLUTE ZERO=-273.15, STEFAN BOLTZMANN=5.669e-8).
    The conducted heat k (T0 - T1) / L leaves by radiation, eps sigma ((T1 +
    273.15)^4 - 293.15^4): T1 the root of that scalar equation (bisection),
    the temperature linear in x; every element reproduces it (Newton to
    1e-10 of the largest temperature; checked to 1e-9 of T0 - T1), and the
    reaction flux over the held face is the radiated heat times the area
    (1e-9); Newton converges in at most 8 iterations."""
    k, length, height, t0, sink, eps, sigma, zero = 10.0, 0.1, 0.04, 500.0, 20.0, 0.8, 5.669e-8, -273.15
    t1 = bisect(lambda t: eps * sigma * ((t - zero) ** 4 - (sink - zero) ** 4) - k * (t0 - t) / length, sink, t0)
    q = k * (t0 - t1) / length
    for shape, et in (("Q4", "DC2D4"), ("Q8", "DC2D8"), ("T6", "CPS6"), ("T3", "DC2D3")):
        m = Mesh(shape, 3, 2, lambda s, t: (length * s / 3, height * t / 2), straight=True)
        rad = "".join(f"{e}, R{f}, {sink}, {eps}\n" for e, f in m.faces("right"))
        m, deck = slab_deck(shape, et, 3, length, height, t0, None, "*CONDUCTIVITY\n10.\n", "*RADIATE\n" + rad,
                            extra=f"*PHYSICAL CONSTANTS, ABSOLUTE ZERO={zero}, STEFAN BOLTZMANN={sigma}\n")
        run = run_deck("heat_radiate_" + et, deck).ok()
        nt = node_values(run, "NT")
        worst = max(abs(nt[n] - (t0 - q * x / k)) for n, (x, _) in m.nodes.items()) / (t0 - t1)
        assert worst < 1e-9, (et, worst)
        rfl = node_values(run, "RFL")
        total = sum(rfl[n] for n in m.side("left"))
        assert abs(total - q * height) < 1e-9 * q * height, (et, total, q * height)
        assert 1 < int(run.listing.increments[-1].attrs["iterations"]) <= 8, run.listing.increments[-1].attrs


def test_radiation_cooling_plate():
    """A thin plate (0.01 x 1, rho c = 1e6, k = 1e5: nearly uniform) at
    1000 K radiating from its top face (eps 0.5, sigma 5.67e-8) to 0 K:
    rho c h dT/dt = -eps sigma T^4. Backward Euler on that ODE, T1 + dt a
    T1^4 = T0 with a = eps sigma / (rho c h), is what the elements do at
    every increment (1e-5 of T: the plate's own gradient, q h / 2k, is
    1.4e-6 of T); the exact T(t) = (T0^-3 + 3 a t)^(-1/3) at t = 100 is
    met within the scheme's first-order error (20 and 40 fixed increments,
    DIRECT: the errors, measured 3.08e-3 and 1.56e-3, within 5e-3 and
    2.5e-3, halved: ratio 2 +- 0.1); automatic increments (no DIRECT, from
    dt = 5, growing) within 2e-2 (measured 1.07e-2)."""
    thick, rho_c, eps, sigma, temp0, t_end = 0.01, 1e6, 0.5, 5.67e-8, 1000.0, 100.0
    a = eps * sigma / (rho_c * thick)
    exact = (temp0 ** -3 + 3 * a * t_end) ** (-1.0 / 3.0)
    material = "*CONDUCTIVITY\n1e5\n*DENSITY\n1.\n*SPECIFIC HEAT\n1e6\n"
    errs = []
    for n_inc, direct in ((20, True), (40, True), (20, False)):
        m = Mesh("Q4", 4, 1, lambda s, t: (s / 4, thick * t), straight=True)
        rad = "".join(f"{e}, R{f}, 0., {eps}\n" for e, f in m.faces("top"))
        deck = f"""*NODE, NSET=NALL
{m.node_lines()}{m.element_card('DC2D4', 'EALL')}*MATERIAL, NAME=M
{material}*SOLID SECTION, ELSET=EALL, MATERIAL=M
1.
*PHYSICAL CONSTANTS, ABSOLUTE ZERO=0., STEFAN BOLTZMANN={sigma}
*INITIAL CONDITIONS, TYPE=TEMPERATURE
NALL, {temp0}
*STEP
*HEAT TRANSFER{', DIRECT' if direct else ''}
{t_end / n_inc}, {t_end}
*RADIATE
{rad}*NODE PRINT, NSET=NALL
NT
*END STEP
"""
        run = run_deck(f"heat_radiate_plate_{n_inc}_{direct}", deck).ok()
        incs = run.listing.increments
        temp, t_prev = temp0, 0.0
        for inc in incs:
            dt = float(inc.attrs["time"]) - t_prev
            t_prev = float(inc.attrs["time"])
            temp = bisect(lambda t: t + dt * a * t ** 4 - temp, 0.0, temp)
            b = inc.block("NODE NT")
            assert max(abs(v - temp) for v in b["NT11"]) < 1e-5 * temp, (n_inc, inc.attrs, temp)
        if direct:
            assert len(incs) == n_inc
        errs.append(abs(temp - exact) / exact)
    print("plate: errors against the closed form", ["%.3e" % e for e in errs])
    assert errs[0] < 5e-3 and errs[1] < 2.5e-3 and abs(errs[0] / errs[1] - 2.0) < 0.1, errs
    assert errs[2] < 2e-2, errs


def test_specific_heat_table():
    """*SPECIFIC HEAT as a table (c = 1 at 0, 3 at 100, linear between,
    constant beyond), rho = 2: a block heated uniformly by a body flux r
    = 100 (*DFLUX BF) with no way out stays uniform, and each increment
    of backward Euler with the capacity at the end temperature (the
    fixed-point iterations) is rho c(T1) (T1 - T0) = r dt: T1 of that
    scalar equation at each of 10 increments (DIRECT, dt = 0.5) on DC2D4
    and DC2D8, to 1e-9 of T, past the table's end (T > 100); the
    iterations are more than one."""
    rho, r, dt = 2.0, 100.0, 0.5

    def c_of(t):
        return 1.0 + 2.0 * min(max(t, 0.0), 100.0) / 100.0
    for shape, et in (("Q4", "DC2D4"), ("Q8", "DC2D8")):
        m = Mesh(shape, 2, 2, lambda s, t: (0.5 * s, 0.5 * t), straight=True)
        deck = f"""*NODE, NSET=NALL
{m.node_lines()}{m.element_card(et, 'EALL')}*MATERIAL, NAME=M
*CONDUCTIVITY
3.
*DENSITY
{rho}
*SPECIFIC HEAT
1., 0.
3., 100.
*SOLID SECTION, ELSET=EALL, MATERIAL=M
1.
*INITIAL CONDITIONS, TYPE=TEMPERATURE
NALL, 0.
*STEP
*HEAT TRANSFER, DIRECT
{dt}, {10 * dt}
*DFLUX
EALL, BF, {r}
*NODE PRINT, NSET=NALL
NT
*END STEP
"""
        run = run_deck("heat_ctable_" + et, deck).ok()
        temp = 0.0
        for inc in run.listing.increments:
            t_old = temp
            temp = bisect(lambda t: rho * c_of(t) * (t - t_old) - r * dt, t_old, t_old + r * dt / rho)
            b = inc.block("NODE NT")
            assert max(abs(v - temp) for v in b["NT11"]) < 1e-9 * temp, (et, inc.attrs, temp, b["NT11"][:3])
            assert int(inc.attrs["iterations"]) > 1
        assert len(run.listing.increments) == 10 and temp > 100.0, temp


def test_heat_errors():
    """Cards cfe2d does not have stop at their line with the reason."""
    base = slab_deck("Q4", "DC2D4", 2, 1.0, 0.2, 100.0, None, "*CONDUCTIVITY\n10.\n", "")[1]
    cases = [
        (base.replace("*END STEP", "*RADIATE\n1, R2, 20., 0.8\n*END STEP"), "needs *PHYSICAL CONSTANTS"),
        (base.replace("*END STEP", "*RADIATE\n1, R2CR, 20., 0.8\n*END STEP"), "cavity radiation (R2CR)"),
        (base.replace("*END STEP", "*RADIATE\n1, R2, 20., 1.8\n*END STEP"), "emissivity must lie in 0..1"),
        (base.replace("*END STEP", "*RADIATE, CAVITY=A\n1, R2, 20., 0.8\n*END STEP"), "cavity radiation, an"),
        (base.replace("*END STEP", "*RADIATE\n1, R7, 20., 0.8\n*END STEP"), "is not one of R1..R4"),
        (base.replace("*END STEP", "*VIEWFACTOR, READ\n*END STEP"), "*VIEWFACTOR is cavity radiation"),
        (base.replace("*CONDUCTIVITY\n", "*CONDUCTIVITY, TYPE=ANISO\n"), "TYPE=ANISO of *CONDUCTIVITY is not"),
        (base.replace("*CONDUCTIVITY\n10.\n", "*CONDUCTIVITY\n10.\n*SPECIFIC HEAT\n1., 200.\n2., 100.\n"),
         "*SPECIFIC HEAT table must increase"),
        (base.replace("*STEP", "*PHYSICAL CONSTANTS, ABSOLUTE ZERO=0., STEFAN BOLTZMANN=-1.\n*STEP"),
         "STEFAN BOLTZMANN must be positive"),
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
        # a region with neither a held temperature nor a film: no steady state;
        # the error names its first node, whichever pivot the factorisation stops at
        (base.replace("*BOUNDARY\nLEFT, 11, 11, 100.0\n", "*CFLUX\n1, 11, 1.\n"),
         "matrix is singular: node 1 is in a region without a prescribed temperature"),
        (base.replace("*MATERIAL", "*NODE\n901, 5., 0.\n902, 6., 0.\n903, 6., 1.\n904, 5., 1.\n"
                      "*ELEMENT, TYPE=DC2D4, ELSET=EALL\n901, 901, 902, 903, 904\n*MATERIAL"),
         "matrix is singular: node 901 is in a region without a prescribed temperature"),
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


def test_calculix_ax6ht():
    """CalculiX's ax6ht (Debian's calculix-ccx-test): steady conduction in
    a CAX6 disk between two single nodes held at 0 and 100, run
    unchanged; its .dat.ref holds the heat flux at the 9 points of the
    C3D15 wedge CalculiX expands a CAX6 into (3 in the plane, xi fastest,
    in 3 layers through the 2 degree sector). The middle layer is the
    plane of the section: cfe2d's flux (printed at the same points) within
    1e-9 of the largest (measured 1.5e-11: the 6-node triangle's 3 points,
    as CalculiX's); the outer layers lie off the plane in the 3D sector
    (their qz is not 0): within 2e-4 (measured 8.9e-5)."""
    import gzip
    import os
    from helpers import Skip
    if not os.path.isfile(os.path.join(DEBIAN, "ax6ht.inp.gz")):
        raise Skip("Debian's calculix-ccx-test is not installed (scripts/install-deps.sh installs it)")
    with gzip.open(os.path.join(DEBIAN, "ax6ht.inp.gz"), "rt") as f:
        text = f.read()
    with gzip.open(os.path.join(DEBIAN, "ax6ht.dat.ref.gz"), "rt") as f:
        ref_text = f.read()
    run = run_deck("ax6ht", text).ok()

    def fluxes(t):
        out = {}
        for line in t.splitlines():
            p = line.split()
            if len(p) == 5 and p[0].isdigit() and p[1].isdigit():
                out[(int(p[0]), int(p[1]))] = (float(p[2]), float(p[3]))
        return out
    with open(os.path.join(os.path.dirname(run.listing_path), "ax6ht.dat")) as f:
        got = fluxes(f.read())
    ref = fluxes(ref_text)
    assert len(ref) == 32 * 9 and set(got) == set(ref), (len(ref), len(got))
    scale = max(max(abs(q1), abs(q2)) for q1, q2 in ref.values())
    worst = {True: 0.0, False: 0.0}
    for key, (q1, q2) in ref.items():
        middle = 4 <= key[1] <= 6
        worst[middle] = max(worst[middle], abs(got[key][0] - q1) / scale, abs(got[key][1] - q2) / scale)
    assert worst[True] < 1e-9 and worst[False] < 2e-4, worst


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
