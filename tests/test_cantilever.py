"""Plane-stress cantilever under a parabolic end shear: the tip deflection
converges to beam theory with shear, PL^3/(3EI) + PL/(kGA), k = 5/6."""
from decks import grid, node_lines, quad_lines
from helpers import run_deck

L, H, T, E, NU, P = 10.0, 1.0, 1.0, 1000.0, 0.3, 1.0


def beam_theory():
    i = T * H ** 3 / 12
    g = E / (2 * (1 + NU))
    return P * L ** 3 / (3 * E * i) + P * L / (5.0 / 6.0 * g * H * T)


def tip_deflection(nx, ny):
    nodes, ids, quads = grid(nx, ny, 0.0, L, -H / 2, H / 2)
    clamp = [ids[0, j] for j in range(ny + 1)]
    tip = [ids[nx, j] for j in range(ny + 1)]
    # Consistent nodal forces of tau(y) = 3P/(2HT) (1 - 4y^2/H^2) (Simpson is
    # exact for the cubic integrand on each edge).
    tau = lambda y: 3 * P / (2 * H * T) * (1 - 4 * y * y / H ** 2) * T  # noqa: E731
    f = {n: 0.0 for n in tip}
    for j in range(ny):
        a, b = tip[j], tip[j + 1]
        ya, yb = nodes[a][1], nodes[b][1]
        h = yb - ya
        tm = tau(0.5 * (ya + yb))
        f[a] += h / 6 * (tau(ya) + 2 * tm)
        f[b] += h / 6 * (2 * tm + tau(yb))
    loads = "".join(f"{n}, 2, {-v:.17g}\n" for n, v in f.items())
    mid = ids[nx, ny // 2]
    deck = f"""*NODE
{node_lines(nodes)}*ELEMENT, TYPE=CPS4, ELSET=BEAM
{quad_lines(quads)}*NSET, NSET=CLAMP
{", ".join(map(str, clamp))}
*NSET, NSET=TIPMID
{mid}
*MATERIAL, NAME=M
*ELASTIC
{E}, {NU}
*SOLID SECTION, ELSET=BEAM, MATERIAL=M
{T}
*BOUNDARY
CLAMP, 1, 2
*STEP
*STATIC
*CLOAD
{loads}*NODE PRINT, NSET=TIPMID
U
*NODE PRINT, NSET=CLAMP
RF
*END STEP
"""
    run = run_deck(f"cantilever_{nx}x{ny}", deck).ok()
    inc = run.listing.increments[-1]
    rsum = inc.block("REACTIONS").as_dict()["CLAMP"]
    assert abs(rsum[1] - P) < 1e-9 * P, f"reaction {rsum} does not balance P"
    return -inc.block("NODE U", set="TIPMID")["U2"][0]


def test_cantilever_converges_to_beam_theory():
    exact = beam_theory()
    errs = []
    for nx, ny in ((20, 2), (40, 4), (80, 8), (160, 16)):
        errs.append(abs(tip_deflection(nx, ny) - exact) / exact)
    print_table = ", ".join(f"{e:.4f}" for e in errs)
    assert all(b < a for a, b in zip(errs, errs[1:])), f"not converging: {print_table}"
    assert errs[-1] < 0.01, f"finest mesh error {errs[-1]:.4f} >= 1% ({print_table})"
