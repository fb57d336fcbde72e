"""Large rotations under NLGEOM: a slender cantilever (St Venant-Kirchhoff,
*ELASTIC under NLGEOM) under a dead transverse end load up to
P L^2 / EI = 10, against the elastica of an inextensible Euler-Bernoulli
beam computed here by shooting (theta'' = -alpha cos theta on [0, 1],
theta(0) = 0, theta'(1) = 0; RK4 with 400 steps and bisection on
theta'(0), converged to 1e-12). At alpha = 10 it gives the tip deflection
0.81061 L and the shortening 0.55500 L, Mattiasson's (1981) table values.

The beam: L = 10, h = 0.1 (L/h = 100: shear and stretching change the
tip by about (h/L)^2 and P/EA, 1e-4), plane stress with nu = 0 (the beam's
E I), 100 x 2 CPS8R elements; every increment the progress line reports
is written, so the curve is checked at each alpha the automatic
increments reach, and at the end. Tolerance: 0.2 % of L on both tip
displacements (the issue asks 1 %; measured 1.5e-4 L with the tighter
*CONTROLS below, 8.8e-3 L with CalculiX's default ones)."""
import math

from helpers import run_deck
from quadmesh import Mesh

L, H, E = 10.0, 0.1, 1.0e5
# CalculiX's default force criterion (R_n = 0.005 of the average element force) leaves a tip force
# error of a few per cent of P in a beam this slender (its element forces are bending couples, larger
# than P): measured up to 0.9 % of L in the tip deflection with the defaults. *CONTROLS tightens it,
# as a CalculiX user would.
R_N, C_N = 1.0e-5, 1.0e-3
EI = E * H ** 3 / 12.0
ALPHA_END = 10.0


def elastica(alpha, n=400):
    """(tip deflection, shortening) / L of the inextensible cantilever."""
    def shoot(k0):
        th, k = 0.0, k0
        x = y = 0.0
        ds = 1.0 / n

        def f(state):
            t, kk, _, _ = state
            return (kk, -alpha * math.cos(t), math.cos(t), math.sin(t))
        state = (th, k, x, y)
        for _ in range(n):
            k1 = f(state)
            k2 = f(tuple(s + 0.5 * ds * d for s, d in zip(state, k1)))
            k3 = f(tuple(s + 0.5 * ds * d for s, d in zip(state, k2)))
            k4 = f(tuple(s + ds * d for s, d in zip(state, k3)))
            state = tuple(s + ds / 6.0 * (a + 2 * b + 2 * c + d) for s, a, b, c, d in zip(state, k1, k2, k3, k4))
        return state
    lo, hi = 0.0, alpha            # theta'(0) in (0, alpha]: the moment at the root is below P L
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if shoot(mid)[1] > 0.0:     # curvature left at the tip: too much moment at the root
            hi = mid
        else:
            lo = mid
        if hi - lo < 1e-13:
            break
    _, _, x, y = shoot(0.5 * (lo + hi))
    return y, 1.0 - x


def test_elastica_shooting_matches_mattiasson():
    d, s = elastica(10.0)
    assert abs(d - 0.81061) < 2e-5 and abs(s - 0.55500) < 2e-5, (d, s)


def cantilever_deck():
    m = Mesh("Q8", 100, 2, lambda s, t: (s * L / 100, (t - 1.0) * H / 2), straight=True)
    tip = m.side("right")
    # consistent loads of a uniform traction on the 3-node edges of the tip face: 1/6, 2/3, 1/6 per edge
    share = {}
    for k in range(0, len(tip) - 1, 2):
        for node, w in zip(tip[k:k + 3], (1 / 6, 2 / 3, 1 / 6)):
            share[node] = share.get(node, 0.0) + w / 2
    p = ALPHA_END * EI / L ** 2
    loads = "".join(f"{n}, 2, {p * w!r}\n" for n, w in share.items())
    mid = tip[len(tip) // 2]
    return f"""*NODE, NSET=ALL
{m.node_lines()}{m.element_card('CPS8R', 'BEAM')}*NSET, NSET=ROOT
{", ".join(map(str, m.side('left')))}
*NSET, NSET=TIP
{mid}
*MATERIAL, NAME=M
*ELASTIC
{E}, 0.
*SOLID SECTION, ELSET=BEAM, MATERIAL=M
1.
*STEP, NLGEOM, INC=200
*STATIC
0.05, 1., 1e-5, 0.1
*CONTROLS, PARAMETERS=FIELD
{R_N}, {C_N}
*BOUNDARY
ROOT, 1, 2
*CLOAD
{loads}*NODE PRINT, NSET=TIP
U
*END STEP
""", mid


def test_cantilever_follows_the_elastica_to_alpha_10():
    text, mid = cantilever_deck()
    run = run_deck("nl_elastica", text).ok()
    worst = 0.0
    for inc in run.listing.increments:
        alpha = ALPHA_END * inc.time
        u = inc.block("NODE U", set="TIP")
        d, s = elastica(alpha)
        err = max(abs(u["U2"][0] / L - d), abs(-u["U1"][0] / L - s))
        worst = max(worst, err)
        assert err < 0.002, (alpha, u["U2"][0] / L, d, -u["U1"][0] / L, s)
    last = run.listing.increments[-1]
    assert abs(last.time - 1.0) < 1e-12
    assert len(run.listing.increments) >= 5
    print(f"  {len(run.listing.increments)} increments; largest difference from the elastica {worst:.2e} L")


def test_a_first_increment_too_large_is_cut_back_and_the_step_completes():
    """The whole load in one increment: the Newton iteration would need more
    than I_C = 16 iterations; the increment is cut back by D_C = 0.5 (the
    listing's notes say why) until it converges, nothing of the failed
    attempts is kept, and the step ends on the elastica."""
    text, mid = cantilever_deck()
    text = text.replace("*STATIC\n0.05, 1., 1e-5, 0.1\n", "*STATIC\n1., 1.\n")
    run = run_deck("nl_elastica_cut", text).ok()
    listing = open(run.listing_path).read()
    assert "increment cut back to 5.000E-01" in listing, listing[-2000:]
    cut = int(listing.split("\ncutbacks ")[1].split()[0])
    assert cut >= 1
    last = run.listing.increments[-1]
    u = last.block("NODE U", set="TIP")
    d, s = elastica(10.0)
    assert abs(last.time - 1.0) < 1e-12
    assert abs(u["U2"][0] / L - d) < 0.002 and abs(-u["U1"][0] / L - s) < 0.002, (u["U2"][0] / L, d)
    print(f"  {cut} increments cut back, {len(run.listing.increments)} written")
