"""Constant-stress patch tests on distorted meshes: with the boundary
displacements of a linear field, interior displacements and every stress
must be exact (relative error below 1e-10)."""
from decks import grid, node_lines, quad_lines, tri_lines
from helpers import run_deck

E, NU = 1000.0, 0.25
A = (1e-3, 2e-3, -4e-4, 5e-4, 3e-3, -1e-3)  # u = a0 + a1 x + a2 y, v = a3 + a4 x + a5 y


def exact_u(x, y):
    return A[0] + A[1] * x + A[2] * y, A[3] + A[4] * x + A[5] * y


def exact_stress(plane_strain):
    ex, ey, gxy = A[1], A[5], A[2] + A[4]
    if plane_strain:
        c = E / ((1 + NU) * (1 - 2 * NU))
        s11, s22, s12 = c * ((1 - NU) * ex + NU * ey), c * (NU * ex + (1 - NU) * ey), c * (1 - 2 * NU) / 2 * gxy
        return s11, s22, NU * (s11 + s22), s12
    c = E / (1 - NU ** 2)
    return c * (ex + NU * ey), c * (NU * ex + ey), 0.0, c * (1 - NU) / 2 * gxy


def patch(etype):
    nodes, ids, quads = grid(4, 3, 0.0, 2.0, 0.0, 1.5, distort=0.6)
    boundary = [n for (i, j), n in ids.items() if i in (0, 4) or j in (0, 3)]
    elements = tri_lines(quads) if etype.endswith("3") else quad_lines(quads)
    bcs = ""
    for n in boundary:
        u, v = exact_u(*nodes[n])
        bcs += f"{n}, 1, 1, {u:.17g}\n{n}, 2, 2, {v:.17g}\n"
    deck = f"""*HEADING
patch test {etype}
*NODE, NSET=ALL
{node_lines(nodes)}*ELEMENT, TYPE={etype}, ELSET=PATCH
{elements}*MATERIAL, NAME=M
*ELASTIC
{E}, {NU}
*SOLID SECTION, ELSET=PATCH, MATERIAL=M
0.7
*STEP
*STATIC
*BOUNDARY
{bcs}*NODE PRINT
U, S
*EL PRINT
S
*END STEP
"""
    run = run_deck(f"patch_{etype.lower()}", deck).ok()
    inc = run.listing.increments[-1]
    ub = inc.block("NODE U")
    err = 0.0
    scale = max(abs(a) for a in A)
    for n, u1, u2 in zip(ub["node"], ub["U1"], ub["U2"]):
        ue, ve = exact_u(*nodes[int(n)])
        err = max(err, abs(u1 - ue) / scale, abs(u2 - ve) / scale)
    assert err < 1e-10, f"displacement error {err:.2e}"
    s_exact = exact_stress(etype.startswith("CPE"))
    smax = max(abs(s) for s in s_exact)
    for name in ("ELEMENT S", "NODE S"):
        b = inc.block(name)
        for col, se in zip(("S11", "S22", "S33", "S12"), s_exact):
            e = max(abs(b[col] - se)) / smax
            assert e < 1e-10, f"{name} {col} error {e:.2e}"


def test_patch_q4_plane_stress():
    patch("CPS4")


def test_patch_q4_plane_strain():
    patch("CPE4")


def test_patch_t3_plane_stress():
    patch("CPS3")


def test_patch_t3_plane_strain():
    patch("CPE3")
