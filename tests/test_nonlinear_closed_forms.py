"""Nonlinear bodies against closed forms, through whole decks (the Newton
driver, the cards, the element routines, the output):

* a neo-Hookean block (CalculiX's energy, C10, D1) in plane-strain uniaxial
  stretch to 1.6 and compression to 0.6: nominal stress against stretch,
  the lateral stretch from s22 = 0 solved here, to 1e-6;
* uniaxial stress past yield and back with linear hardening (*PLASTIC two
  points, small strain): stress and PEEQ at every increment exactly (to
  1e-9 of the yield stress), elastic unloading and reversed yielding;
* a thick nearly incompressible neo-Hookean cylinder (plane strain,
  K/mu = 2000) under internal pressure, a follower load on the deformed
  inner face, against Rivlin's incompressible solution (the inner radius
  for the pressure, within 1 %);
* the plane-strain thick cylinder of a perfectly plastic von Mises
  material: the last pressure the automatic increments reach before they
  fall below the minimum is within 1 % of the collapse pressure
  (2 / sqrt 3) sigma_y ln(b / a), and the run stops with that reason.
Tighter *CONTROLS where the closed form is exact for the element (a
homogeneous state), so that the comparison sees the element, not the
Newton tolerance."""
import math

from helpers import run_deck
from quadmesh import Mesh

C10, D1 = 0.5, 0.02          # mu = 1, K = 2 / D1 = 100
TIGHT = "*CONTROLS, PARAMETERS=FIELD\n1e-10, 1e-10\n"


def neo_hooke_uniaxial(lam, c10=C10, d1=D1):
    """Plane-strain uniaxial stress: (nominal stress P11, lateral stretch)
    of W = C10 (I1bar - 3) + (J - 1)^2 / D1 at F = diag(lam, l2, 1) with
    tau22 = 0 (bisection on l2)."""
    def tau(l1, l2):
        j = l1 * l2
        i1 = l1 * l1 + l2 * l2 + 1.0
        p = 2.0 * (j - 1.0) / d1
        f = 2.0 * c10 * j ** (-2.0 / 3.0)
        return f * (l1 * l1 - i1 / 3.0) + j * p, f * (l2 * l2 - i1 / 3.0) + j * p
    lo, hi = 0.05, 5.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if tau(lam, mid)[1] > 0.0:
            hi = mid
        else:
            lo = mid
    l2 = 0.5 * (lo + hi)
    return tau(lam, l2)[0] / lam, l2


def block(lam, element="CPE4", material=f"*HYPERELASTIC, NEO HOOKE\n{C10}, {D1}\n", nlgeom=",NLGEOM",
          static="*STATIC\n0.1, 1.\n", steps=None):
    """A 2 x 1 block of 2 x 2 elements: x held at x = 0, y at node 1, the
    right side moved to x = 2 lam; reaction sum of the right side."""
    shape = {"3": "T3", "4": "Q4", "6": "T6", "8": "Q8"}[element.rstrip("R")[-1]]
    m = Mesh(shape, 2, 2, lambda s, t: (s, 0.5 * t), straight=True)
    left, right = m.side("left"), m.side("right")
    steps = steps or [(static, 2.0 * (lam - 1.0))]
    text = f"""*NODE, NSET=ALL
{m.node_lines()}{m.element_card(element, 'B')}*NSET, NSET=LEFT
{", ".join(map(str, left))}
*NSET, NSET=RIGHT
{", ".join(map(str, right))}
*MATERIAL, NAME=M
{material}*SOLID SECTION, ELSET=B, MATERIAL=M
1.
*BOUNDARY
LEFT, 1, 1
1, 2, 2
"""
    for k, (st, ux) in enumerate(steps):
        text += f"""*STEP{nlgeom if k == 0 else ''}, INC=500
{st}{TIGHT}*BOUNDARY
RIGHT, 1, 1, {ux!r}
*NODE PRINT, NSET=RIGHT, TOTALS=ONLY
RF
*EL PRINT
S, PEEQ
*END STEP
"""
    return text


def reaction(inc):
    return inc.block("NODE RF", set="RIGHT")


def right_force(inc):
    """The reaction sum of the right side (the listing's set sum)."""
    b = inc.block("REACTIONS")
    return b["RF1"][list(b["set"]).index("RIGHT")]


def test_neo_hooke_block_plane_strain_uniaxial_stretch_and_compression():
    for lam in (1.6, 0.6):
        for element in ("CPE4", "CPE8", "CPE3"):
            text = block(lam, element=element)
            run = run_deck(f"nl_nh_block_{element}_{lam}", text).ok()
            worst = 0.0
            for inc in run.listing.increments:
                l1 = 1.0 + (lam - 1.0) * inc.time
                p11, _ = neo_hooke_uniaxial(l1)
                got = right_force(inc) / 1.0        # reference area: height 1 x thickness 1
                worst = max(worst, abs(got - p11) / abs(p11))
                assert abs(got - p11) <= 1e-6 * abs(p11), (element, l1, got, p11)
            assert abs(run.listing.increments[-1].time - 1.0) < 1e-12
            print(f"  {element} stretch {lam}: {len(run.listing.increments)} increments, worst {worst:.1e}")


def uniaxial_plastic(strains, e, sy, h):
    """1D von Mises with linear isotropic hardening, exact return map along
    a path of total strains: [(stress, peeq)]."""
    eps_p, peeq, out = 0.0, 0.0, []
    for eps in strains:
        trial = e * (eps - eps_p)
        f = abs(trial) - (sy + h * peeq)
        if f > 0.0:
            dg = f / (e + h)
            eps_p += dg * math.copysign(1.0, trial)
            peeq += dg
        out.append((e * (eps - eps_p), peeq))
    return out


def test_uniaxial_tension_past_yield_and_back_with_linear_hardening():
    e, nu, sy, h = 200000.0, 0.3, 200.0, 20000.0
    ey = sy / e
    # plane stress: uniaxial stress; sy at PEEQ 0, sy + h at PEEQ 1
    material = f"*ELASTIC\n{e}, {nu}\n*PLASTIC\n{sy}, 0.\n{sy + h}, 1.\n"
    stretch = 3.0 * ey * 2.0                     # the 2-long block to 3 yield strains
    steps = [("*STATIC, DIRECT\n0.1, 1.\n", stretch), ("*STATIC, DIRECT\n0.1, 1.\n", -stretch)]
    text = block(1.0, element="CPS4", material=material, nlgeom="", steps=steps)
    run = run_deck("nl_plastic_uniaxial", text).ok()
    incs = run.listing.increments
    assert len(incs) == 20
    path = [3.0 * ey * (k + 1) / 10 for k in range(10)] + [3.0 * ey * (1 - 2 * (k + 1) / 10) for k in range(10)]
    expect = uniaxial_plastic(path, e, sy, h)
    reversed_yield = False
    for inc, (s, p) in zip(incs, expect):
        got = right_force(inc) / 1.0
        assert abs(got - s) <= 1e-9 * sy, (inc.time, got, s)
        peeq = inc.block("ELEMENT PEEQ")["PEEQ"]
        assert all(abs(q - p) <= 1e-12 + 1e-9 * p for q in peeq), (inc.time, peeq[0], p)
        s11 = inc.block("ELEMENT S")["S11"]
        assert all(abs(q - s) <= 1e-9 * sy for q in s11)
        reversed_yield = reversed_yield or (s < 0 and p > expect[9][1])
    assert expect[9][1] > 0 and reversed_yield


def annulus(a, b, nr, nt, shape="Q4"):
    return Mesh(shape, nr, nt, lambda s, t: ((a + (b - a) * s / nr) * math.cos(0.5 * math.pi * t / nt),
                                             (a + (b - a) * s / nr) * math.sin(0.5 * math.pi * t / nt)))


def cylinder_deck(m, element, material, pressure, static, extra=""):
    inner = m.faces("left")
    dload = "".join(f"{e}, P{f}, {pressure!r}\n" for e, f in inner)
    return f"""*NODE, NSET=ALL
{m.node_lines()}{m.element_card(element, 'B')}*NSET, NSET=XSYM
{", ".join(map(str, m.side('bottom')))}
*NSET, NSET=YSYM
{", ".join(map(str, m.side('top')))}
*NSET, NSET=INNER
{m.side('left')[0]}
*MATERIAL, NAME=M
{material}*SOLID SECTION, ELSET=B, MATERIAL=M
1.
*BOUNDARY
XSYM, 2, 2
YSYM, 1, 1
*STEP{extra}, INC=1000
{static}*DLOAD
{dload}*NODE PRINT, NSET=INNER
U
*END STEP
"""


def rivlin_pressure(a0, b0, a, mu):
    """Internal pressure of the incompressible neo-Hookean cylinder (plane
    strain) whose inner radius goes from a0 to a: r^2 = R^2 + a^2 - a0^2,
    p = mu integral_a^b (lt^2 - lt^-2) / r dr, lt = r / R (Simpson, 2000
    intervals)."""
    c = a * a - a0 * a0
    b = math.sqrt(b0 * b0 + c)
    n = 2000
    hgt = (b - a) / n

    def g(r):
        lt2 = r * r / (r * r - c)
        return (lt2 - 1.0 / lt2) / r
    s = g(a) + g(b) + sum((4 if k % 2 else 2) * g(a + k * hgt) for k in range(1, n))
    return mu * s * hgt / 3.0


def test_thick_nearly_incompressible_neo_hooke_cylinder_follower_pressure():
    a0, b0, mu = 1.0, 2.0, 1.0
    d1 = 2.0 / (2000.0 * mu)            # K / mu = 2000
    a = 1.5                              # inner radius +50 %
    p = rivlin_pressure(a0, b0, a, mu)
    m = annulus(a0, b0, 12, 12)
    text = cylinder_deck(m, "CPE4", f"*HYPERELASTIC, NEO HOOKE\n{mu / 2}, {d1!r}\n", p, "*STATIC\n0.1, 1.\n")
    run = run_deck("nl_nh_cylinder", text).ok()
    ur = run.listing.increments[-1].block("NODE U", set="INNER")["U1"][0]
    assert abs((a0 + ur) - a) <= 0.01 * (a - a0), (a0 + ur, a, p)
    # and on the way: the pressure of each increment gives its radius
    for inc in run.listing.increments:
        ur = inc.block("NODE U", set="INNER")["U1"][0]
        assert abs(rivlin_pressure(a0, b0, a0 + ur, mu) - p * inc.time) <= 0.01 * p * inc.time
    print(f"  p = {p:.5f} mu: inner radius {a0 + ur:.5f} (Rivlin {a})")


def test_thick_cylinder_plane_strain_collapse_pressure():
    a0, b0, e, nu, sy = 1.0, 2.0, 200000.0, 0.3, 200.0
    pc = 2.0 / math.sqrt(3.0) * sy * math.log(b0 / a0)
    m = annulus(a0, b0, 16, 8, shape="Q8")
    material = f"*ELASTIC\n{e}, {nu}\n*PLASTIC\n{sy}, 0.\n"
    text = cylinder_deck(m, "CPE8R", material, 1.2 * pc, "*STATIC\n0.1, 1., 1e-4\n")
    run = run_deck("nl_collapse", text)
    assert run.rc == 1 and "below the minimum" in run.stderr, run.stderr
    last = run.listing.increments[-1]
    reached = 1.2 * pc * last.time
    assert 0.99 * pc <= reached <= 1.01 * pc, (reached, pc)
    print(f"  last pressure reached {reached:.3f}, collapse {pc:.3f} ({reached / pc - 1:+.2%})")
