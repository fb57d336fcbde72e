"""Anisotropic elasticity: *ELASTIC, TYPE=ORTHO, ENGINEERING CONSTANTS and
ANISO in the axes of an *ORIENTATION (rectangular, cylindrical), in plane
stress, plane strain and axisymmetry.

The closed forms here are computed independently of cfe2d's route (which
turns the 3D stiffness tensor to the global axes and then takes the stress
state): in the material axes by the 2D strain and stress transformations
of a rotation about z (Jones, Mechanics of composite materials, 2.6), the
plane-stress law as the inverse of the in-plane compliance."""
import math
import os

import numpy as np

from decks import grid, node_lines, quad_lines, tri_lines
from helpers import HERE, run_deck
from quadmesh import Mesh, etype

# a carbon-epoxy-like lamina (MPa)
E1, E2, E3 = 140000.0, 10000.0, 12000.0
NU12, NU13, NU23 = 0.3, 0.28, 0.45
G12, G13, G23 = 5000.0, 4800.0, 3600.0
ENG = (E1, E2, E3, NU12, NU13, NU23, G12, G13, G23)
# u = a0 + a1 x + a2 y, v = a3 + a4 x + a5 y
A = (1e-3, 2e-3, -4e-4, 5e-4, 3e-3, -1e-3)


def compliance(eng):
    """6x6 compliance, Voigt (11, 22, 33, 12, 13, 23), engineering shear."""
    e1, e2, e3, n12, n13, n23, g12, g13, g23 = eng
    s = np.zeros((6, 6))
    s[0, 0], s[1, 1], s[2, 2] = 1 / e1, 1 / e2, 1 / e3
    s[0, 1] = s[1, 0] = -n12 / e1
    s[0, 2] = s[2, 0] = -n13 / e1
    s[1, 2] = s[2, 1] = -n23 / e2
    s[3, 3], s[4, 4], s[5, 5] = 1 / g12, 1 / g13, 1 / g23
    return s


def ortho_constants(eng):
    """CalculiX's ORTHO constants D1111, D1122, D2222, D1133, D2233, D3333,
    D1212, D1313, D2323 of the engineering constants."""
    c = np.linalg.inv(compliance(eng))
    return [c[0, 0], c[0, 1], c[1, 1], c[0, 2], c[1, 2], c[2, 2], c[3, 3], c[4, 4], c[5, 5]]


def constants_lines(values):
    """Eight to a line, as CalculiX reads *ELASTIC's constants."""
    text = ""
    for k in range(0, len(values), 8):
        text += ", ".join(f"{v:.17g}" for v in values[k:k + 8]) + "\n"
    return text


def to_local(eps, theta):
    """Strain (e11, e22, g12) in axes turned by theta about z."""
    c, s = math.cos(theta), math.sin(theta)
    ex, ey, g = eps
    return np.array([c * c * ex + s * s * ey + c * s * g, s * s * ex + c * c * ey - c * s * g,
                     -2 * c * s * ex + 2 * c * s * ey + (c * c - s * s) * g])


def to_global(sig, theta):
    """Stress (s11, s22, s12) of axes turned by theta back to the global ones."""
    c, s = math.cos(theta), math.sin(theta)
    s1, s2, t = sig
    return np.array([c * c * s1 + s * s * s2 - 2 * c * s * t, s * s * s1 + c * c * s2 + 2 * c * s * t,
                     c * s * s1 - c * s * s2 + (c * c - s * s) * t])


def exact_stress(eps, theta, state, eps33=0.0):
    """(s11, s22, s33, s12) of the in-plane strain eps (e11, e22, g12):
    plane stress the reduced stiffness inv(S[in-plane]), s33 = 0; plane
    strain and axisymmetry the stiffness with eps33 given (0 in plane
    strain, the hoop strain in axisymmetry)."""
    loc = to_local(eps, theta)
    s = compliance(ENG)
    ip = [0, 1, 3]
    if state == "S":
        sl = np.linalg.solve(s[np.ix_(ip, ip)], loc)
        s33 = 0.0
    else:
        c = np.linalg.inv(s)
        e6 = np.array([loc[0], loc[1], eps33, loc[2], 0.0, 0.0])
        s6 = c @ e6
        sl, s33 = s6[[0, 1, 3]], s6[2]
    g = to_global(sl, theta)
    return g[0], g[1], s33, g[2]


def orientation_card(theta, extra=False):
    """Axes turned by theta about z: by the points a and b, or (extra) as
    the global axes turned on the card's second line about local axis 3."""
    if extra:
        return f"*ORIENTATION, NAME=OR\n1., 0., 0., 0., 1., 0.\n3, {math.degrees(theta):.17g}\n"
    c, s = math.cos(theta), math.sin(theta)
    return f"*ORIENTATION, NAME=OR\n{c:.17g}, {s:.17g}, 0., {-s:.17g}, {c:.17g}, 0.\n"


def material_card(kind):
    if kind == "ENG":
        return "*ELASTIC, TYPE=ENGINEERING CONSTANTS\n" + constants_lines(ENG)
    if kind == "ORTHO":
        return "*ELASTIC, TYPE=ORTHO\n" + constants_lines(ortho_constants(ENG))
    c = np.linalg.inv(compliance(ENG))
    upper = [c[i, j] for j in range(6) for i in range(j + 1)]
    return "*ELASTIC, TYPE=ANISO\n" + constants_lines(upper)


def rotated_patch(state, elem, kind="ENG", theta=math.radians(30.0), extra=False):
    """Patch of distorted elements, the boundary (plane states) or every
    node (axisymmetry, where a uniform stress with s_rr /= s_tt is not in
    equilibrium without a body force) given a linear displacement field;
    every stress must be the closed form to 1e-10."""
    a = A if state != "AX" else (0.0, 2e-3, 0.0, 5e-4, 3e-3, -1e-3)  # u_r = a1 r: uniform hoop strain
    x0 = 0.0 if state != "AX" else 1.0
    nodes, ids, quads = grid(4, 3, x0, x0 + 2.0, 0.0, 1.5, distort=0.6)
    if state == "AX":
        fixed = list(nodes)
    else:
        fixed = [n for (i, j), n in ids.items() if i in (0, 4) or j in (0, 3)]
    elements = tri_lines(quads) if elem == "3" else quad_lines(quads)
    bcs = ""
    for n in fixed:
        x, y = nodes[n]
        bcs += f"{n}, 1, 1, {a[0] + a[1] * x + a[2] * y:.17g}\n{n}, 2, 2, {a[3] + a[4] * x + a[5] * y:.17g}\n"
    et = {"S": "CPS", "E": "CPE", "AX": "CAX"}[state] + elem
    deck = f"""*NODE, NSET=ALL
{node_lines(nodes)}*ELEMENT, TYPE={et}, ELSET=PATCH
{elements}{orientation_card(theta, extra)}*MATERIAL, NAME=M
{material_card(kind)}*SOLID SECTION, ELSET=PATCH, MATERIAL=M, ORIENTATION=OR
0.7
*STEP
*STATIC
*BOUNDARY
{bcs}*NODE PRINT
U
*EL PRINT
S
*END STEP
"""
    run = run_deck(f"ortho_patch_{et.lower()}_{kind.lower()}", deck).ok()
    inc = run.listing.increments[-1]
    ub = inc.block("NODE U")
    scale = max(abs(v) for v in a)
    for n, u1, u2 in zip(ub["node"], ub["U1"], ub["U2"]):
        x, y = nodes[int(n)]
        e = max(abs(u1 - (a[0] + a[1] * x + a[2] * y)), abs(u2 - (a[3] + a[4] * x + a[5] * y))) / scale
        assert e < 1e-10, f"{et}: displacement error {e:.2e} at node {int(n)}"
    s_exact = exact_stress((a[1], a[5], a[2] + a[4]), theta, state, eps33=a[1] if state == "AX" else 0.0)
    smax = max(abs(s) for s in s_exact)
    b = inc.block("ELEMENT S")
    for col, se in zip(("S11", "S22", "S33", "S12"), s_exact):
        e = max(abs(b[col] - se)) / smax
        assert e < 1e-10, f"{et} {col}: error {e:.2e} (exact {se:.6g})"


def test_rotated_patch_plane_stress():
    rotated_patch("S", "4")
    rotated_patch("S", "3")


def test_rotated_patch_plane_strain():
    rotated_patch("E", "4")
    rotated_patch("E", "3", kind="ORTHO")


def test_rotated_patch_axisymmetric():
    rotated_patch("AX", "4")
    rotated_patch("AX", "3", kind="ANISO")


def test_rotated_patch_aniso_and_extra_rotation():
    """ANISO (the 21 constants of the same material) in plane stress, and
    the rotation given as the second line of *ORIENTATION (about local
    axis 3) instead of by the points."""
    rotated_patch("S", "4", kind="ANISO", theta=math.radians(-50.0), extra=True)
    rotated_patch("E", "3", kind="ANISO", theta=math.radians(110.0), extra=True)
