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


def loaded_block(name, state, shape, material, section_extra="", orientation=""):
    """A 4 x 2 block (quadmesh, curved map so that no element is a
    parallelogram) clamped on its left side and loaded by two forces on
    its right: a non-uniform stress field. Returns the listing's
    displacements and element stresses (arrays)."""
    x0 = 1.0 if state == "AX" else 0.0
    mesh = Mesh(shape[:2], 4, 2, lambda s, t: (x0 + s + 0.08 * math.sin(1.3 * t + s), 0.5 * t + 0.05 * s * t))
    left, right = mesh.side("left"), mesh.side("right")
    bcs = "".join(f"{n}, 1, 2\n" for n in left)
    et = etype(shape, state) if shape != "Q4R" else etype("Q4", state) + "R"
    deck = f"""*NODE, NSET=ALL
{mesh.node_lines()}{mesh.element_card(et, "B")}{orientation}*MATERIAL, NAME=M
{material}*SOLID SECTION, ELSET=B, MATERIAL=M{section_extra}
0.5
*STEP
*STATIC
*BOUNDARY
{bcs}*CLOAD
{right[-1]}, 2, -3.
{right[0]}, 1, 5.
*NODE PRINT
U
*EL PRINT
S
*END STEP
"""
    inc = run_deck(name, deck).ok().listing.increments[-1]
    u, s = inc.block("NODE U"), inc.block("ELEMENT S")
    return np.array([u["U1"], u["U2"]]), np.array([s["S11"], s["S22"], s["S33"], s["S12"]])


def iso_ortho(e, nu):
    lam, mu = e * nu / ((1 + nu) * (1 - 2 * nu)), e / (2 * (1 + nu))
    return [lam + 2 * mu, lam, lam + 2 * mu, lam, lam, lam + 2 * mu, mu, mu, mu]


def rel_diff(a, b):
    return float(np.max(np.abs(a - b)) / np.max(np.abs(b)))


def test_isotropic_as_ortho_equals_iso():
    """The isotropic law given as ORTHO (D1111 = lambda + 2 mu, D1122 =
    lambda, D1212 = mu), in axes turned by 30 degrees (an isotropic law
    does not see them), gives *ELASTIC ISO's displacements and stresses
    to 1e-12 (relative to the largest), in every stress state and element
    family, the one-point CPS4R (hourglass control from the mean
    compliance) included."""
    e, nu = 2.1e5, 0.3
    for state, shape in (("S", "Q4"), ("E", "Q8"), ("AX", "T6"), ("S", "Q4R"), ("AX", "Q4")):
        name = f"ortho_iso_{state}_{shape}".lower()
        u0, s0 = loaded_block(name + "_iso", state, shape, f"*ELASTIC\n{e}, {nu}\n")
        u1, s1 = loaded_block(name + "_ortho", state, shape, "*ELASTIC, TYPE=ORTHO\n" +
                              constants_lines(iso_ortho(e, nu)), ", ORIENTATION=OR",
                              orientation_card(math.radians(30.0)))
        assert rel_diff(u1, u0) < 1e-12, f"{state} {shape}: displacements differ by {rel_diff(u1, u0):.2e}"
        assert rel_diff(s1, s0) < 1e-12, f"{state} {shape}: stresses differ by {rel_diff(s1, s0):.2e}"


def test_engineering_constants_equal_ortho():
    """ENGINEERING CONSTANTS and the ORTHO constants of the same material
    (the inverse of its compliance, computed here) give the same answer
    (1e-12, the round-off of 17 printed digits), as does ANISO with the
    same 21 constants; and the orientation matters (the answer in other
    axes differs by far more)."""
    for state, shape in (("S", "Q8"), ("E", "T3"), ("AX", "Q4")):
        name = f"ortho_eng_{state}_{shape}".lower()
        ori, sec = orientation_card(math.radians(-35.0)), ", ORIENTATION=OR"
        u0, s0 = loaded_block(name + "_eng", state, shape, material_card("ENG"), sec, ori)
        u1, s1 = loaded_block(name + "_ortho", state, shape, material_card("ORTHO"), sec, ori)
        u2, s2 = loaded_block(name + "_aniso", state, shape, material_card("ANISO"), sec, ori)
        u3, _ = loaded_block(name + "_global", state, shape, material_card("ORTHO"))
        for u, s, kind in ((u1, s1, "ORTHO"), (u2, s2, "ANISO")):
            assert rel_diff(u, u0) < 1e-12, f"{state} {shape} {kind}: displacements differ by {rel_diff(u, u0):.2e}"
            assert rel_diff(s, s0) < 1e-12, f"{state} {shape} {kind}: stresses differ by {rel_diff(s, s0):.2e}"
        assert rel_diff(u3, u0) > 0.05, f"{state} {shape}: the orientation changed nothing"


# a cylindrically orthotropic tube: local 1 radial, 2 tangential, 3 axial
RING = (1.0e4, 4.0e4, 1.5e4, 0.075, 0.3, 0.35, 6000.0, 5000.0, 7000.0)


def ring_closed_form(p, a, b, r, plane_strain):
    """Lekhnitskii's cylindrically orthotropic ring (or tube in plane
    strain) of radii a < b under internal pressure p (Lekhnitskii,
    Anisotropic plates, 1968, section 30; Anisotropic elasticity, section
    29): sigma_r = A r^(k-1) + B r^(-k-1), sigma_t = k (A r^(k-1) - B
    r^(-k-1)), k^2 = S_rr / S_tt (compatibility), the S the compliance in
    plane stress, reduced by S_zz in plane strain; u_r = r eps_t.
    Returns sigma_r, sigma_t, u_r."""
    s = compliance(RING)
    if plane_strain:
        s = s - np.outer(s[:, 2], s[2, :]) / s[2, 2]
    srr, srt, stt = s[0, 0], s[0, 1], s[1, 1]
    k = math.sqrt(srr / stt)
    c = a / b
    f = p * c ** (k + 1) / (1 - c ** (2 * k))
    sr = f * ((r / b) ** (k - 1) - (b / r) ** (k + 1))
    st = f * k * ((r / b) ** (k - 1) + (b / r) ** (k + 1))
    return sr, st, r * (srt * sr + stt * st)


def test_cylindrical_orientation_ring():
    """SYSTEM=CYLINDRICAL: a quarter of a thick ring (plane stress, CPS8,
    axis z through the origin) and a tube (CAX8, axis y, ends held:
    plane strain along the axis, the hoop direction local 2) under
    internal pressure against Lekhnitskii's closed form. Tolerances from
    the mesh (16 x 12 and 16 x 2 quadratic elements, k = 2; measured:
    radial displacement 2.5e-6 and 9e-7 of its largest value, nodal
    stresses, averaged and turned to r, theta, 4.5e-3 and 4.8e-3 of the
    pressure, 1.6e-2 with 8 elements across): 2e-5 and 1e-2."""
    p, a, b = 10.0, 1.0, 2.0
    eng = "*ELASTIC, TYPE=ENGINEERING CONSTANTS\n" + constants_lines(RING)
    cases = (
        ("S", Mesh("Q8", 16, 12, lambda s, t: ((a + s / 16 * (b - a)) * math.cos(t / 12 * math.pi / 2),
                                               (a + s / 16 * (b - a)) * math.sin(t / 12 * math.pi / 2))),
         "0., 0., 0., 0., 0., 1.", "bottom", "top"),
        ("AX", Mesh("Q8", 16, 2, lambda s, t: (a + s / 16 * (b - a), 0.25 * t)), "0., 0., 0., 0., 1., 0.", None, None))
    for state, mesh, points, fix_v, fix_u in cases:
        bcs = "".join(f"{n}, 2, 2\n" for n in (mesh.side(fix_v) if fix_v else mesh.nodes))
        bcs += "".join(f"{n}, 1, 1\n" for n in (mesh.side(fix_u) if fix_u else []))
        deck = f"""*NODE, NSET=ALL
{mesh.node_lines()}{mesh.element_card(etype("Q8", state), "R")}{mesh.surface_card("INNER", "left")}*ORIENTATION, NAME=CYL, SYSTEM=CYLINDRICAL
{points}
*MATERIAL, NAME=M
{eng}*SOLID SECTION, ELSET=R, MATERIAL=M, ORIENTATION=CYL
1.
*STEP
*STATIC
*BOUNDARY
{bcs}*DSLOAD
INNER, P, {p}
*NODE PRINT
U, S
*END STEP
"""
        inc = run_deck(f"ortho_ring_{state.lower()}", deck).ok().listing.increments[-1]
        ub, sb = inc.block("NODE U"), inc.block("NODE S")
        umax = ring_closed_form(p, a, b, a, state == "AX")[2]
        eu = es = 0.0
        for k, n in enumerate(ub["node"]):
            x, y = mesh.nodes[int(n)]
            r, th = (math.hypot(x, y), math.atan2(y, x)) if state == "S" else (x, 0.0)
            sr, st, ur = ring_closed_form(p, a, b, r, state == "AX")
            c, s = math.cos(th), math.sin(th)
            eu = max(eu, abs(c * ub["U1"][k] + s * ub["U2"][k] - ur) / umax)
            s11, s22, s12 = sb["S11"][k], sb["S22"][k], sb["S12"][k]
            fr = c * c * s11 + s * s * s22 + 2 * c * s * s12
            ft = s * s * s11 + c * c * s22 - 2 * c * s * s12
            if state == "AX":
                fr, ft = s11, sb["S33"][k]
            es = max(es, abs(fr - sr) / p, abs(ft - st) / p)
        assert eu < 2e-5, f"{state}: radial displacement error {eu:.2e}"
        assert es < 1e-2, f"{state}: stress error {es:.2e}"


def plate_with_hole(nr, nt, half_width, load_along_y):
    """Quarter of a square plate (half width `half_width`) with a circular
    hole of radius 1, CPS8, radially graded; symmetry on x = 0 and y = 0,
    a unit tension on the far edge along x (or y). The material's axis 1
    is the load direction (ORIENTATION turned by 90 degrees for y).
    Returns the normal stress along the load at the hole's edge on the
    other axis (the node at (0, 1) or (1, 0))."""
    def xy(s, t):
        phi = t / nt * math.pi / 2
        if phi <= math.pi / 4:
            outer = (half_width, half_width * math.tan(phi))
        else:
            outer = (half_width / math.tan(phi), half_width)
        rho = (s / nr) ** 2.2
        hx, hy = math.cos(phi), math.sin(phi)
        return hx + rho * (outer[0] - hx), hy + rho * (outer[1] - hy)
    mesh = Mesh("Q8", nr, nt, xy)
    on_x0 = [n for n, (x, y) in mesh.nodes.items() if abs(x) < 1e-9]
    on_y0 = [n for n, (x, y) in mesh.nodes.items() if abs(y) < 1e-9]
    edge = 0 if not load_along_y else 1
    far = {n for n, p in mesh.nodes.items() if abs(p[edge] - half_width) < 1e-9}
    faces = [(e, k) for e, k in mesh.faces("right")
             if all(mesh.elements[e - mesh.first_elem][i] in far for i in mesh_face(k))]
    surface = "*SURFACE, NAME=FAR\n" + "".join(f"{e}, S{k}\n" for e, k in faces)
    ori = "0., 1., 0., -1., 0., 0." if load_along_y else "1., 0., 0., 0., 1., 0."
    deck = f"""*NODE, NSET=ALL
{mesh.node_lines()}{mesh.element_card("CPS8", "P")}{surface}*ORIENTATION, NAME=OR
{ori}
*MATERIAL, NAME=M
*ELASTIC, TYPE=ENGINEERING CONSTANTS
{", ".join(map(str, HOLE))}
*SOLID SECTION, ELSET=P, MATERIAL=M, ORIENTATION=OR
1.
*STEP
*STATIC
*BOUNDARY
{"".join(f"{n}, 1, 1" + chr(10) for n in on_x0)}{"".join(f"{n}, 2, 2" + chr(10) for n in on_y0)}*DSLOAD
FAR, P, -1.
*NODE PRINT
S
*END STEP
"""
    inc = run_deck(f"ortho_hole_{nr}_{'y' if load_along_y else 'x'}", deck).ok().listing.increments[-1]
    sb = inc.block("NODE S")
    target = (1.0, 0.0) if load_along_y else (0.0, 1.0)
    n = next(n for n, p in mesh.nodes.items() if abs(p[0] - target[0]) < 1e-9 and abs(p[1] - target[1]) < 1e-9)
    k = list(sb["node"]).index(n)
    return sb["S22" if load_along_y else "S11"][k]


def mesh_face(k):
    """Corner positions (in an 8-node element's connectivity) of face k."""
    return [(0, 1), (1, 2), (2, 3), (3, 0)][k - 1]


# E1, E2, E3, nu12, nu13, nu23, G12, G13, G23 of a plate with a hole
HOLE = (40000.0, 10000.0, 10000.0, 0.25, 0.25, 0.3, 4000.0, 4000.0, 3800.0)


def test_lekhnitskii_plate_with_hole():
    """An orthotropic plate with a circular hole under tension along its
    axis 1 has at the hole's edge the stress concentration (Lekhnitskii,
    Anisotropic plates, section 37; infinite plate)
        Kt = 1 + sqrt(2 (sqrt(E1 / E2) - nu12) + E1 / G12) = 4.674
    for E1 / E2 = 4, nu12 = 0.25, E1 / G12 = 10. A finite plate of half
    width 40 radii, 36 x 36 graded CPS8: measured +0.10 % (half width 20:
    +1.1 % on this and a finer mesh, the finite width; half width 40 on
    24 x 24 and 48 x 48: -0.16 % and +0.17 %, the mesh): tolerance 0.5 %.
    The plate turned by 90 degrees (material and load along y) gives the
    same to 1e-9."""
    e1, e2, _, nu12, _, _, g12, _, _ = HOLE
    kt = 1 + math.sqrt(2 * (math.sqrt(e1 / e2) - nu12) + e1 / g12)
    sx = plate_with_hole(36, 36, 40.0, False)
    sy = plate_with_hole(36, 36, 40.0, True)
    print(f"Kt: closed form {kt:.5f}, cfe2d {sx:.5f} (x), {sy:.5f} (y)")
    assert abs(sx / kt - 1) < 5e-3, f"Kt {sx:.4f} against {kt:.4f}"
    assert abs(sy / sx - 1) < 1e-9, f"turned plate: {sy:.10g} against {sx:.10g}"


def calculix_displacements(path):
    """Node -> (vx, vy) of the displacement block of a CalculiX .dat file."""
    u = {}
    with open(path) as f:
        for line in f:
            fields = line.split()
            if len(fields) == 4 and fields[0].isdigit():
                u[int(fields[0])] = (float(fields[1]), float(fields[2]))
    return u


def test_calculix_strips():
    """Three decks run unchanged by cfe2d and by CalculiX 2.20 (once; its
    .dat kept in tests/calculix/, see its README.md): a plane-strain CPE8
    strip in ENGINEERING CONSTANTS turned by 30 degrees, a plane-stress
    CPS8 strip (a thin section) of ORTHO constants in cylindrical axes,
    an axisymmetric CAX8 ring of ANISO constants turned on the
    orientation's second line, and the same ring of ENGINEERING
    CONSTANTS in cylindrical axes about its symmetry axis y (local 2 the
    hoop direction); and the CPE8 strip's material turned by 30 degrees
    written out as ANISO in the global axes (D1112, D2212, D3312 not
    zero: CalculiX's order of the 21 constants). Displacements relative
    to the largest: CPE8 1e-6 (CalculiX prints 7 digits; measured 1.0e-7
    both), CPS8 1e-3 (measured
    1.3e-4: CalculiX runs plane stress as a 3D layer of the section's
    thickness), CAX8 1e-4 (measured 2.7e-5 and 1.3e-5: CalculiX runs an
    axisymmetric element as a thin 3D wedge)."""
    for name, tol in (("ortho_strip_cpe8", 1e-6), ("ortho_strip_cpe8_aniso", 1e-6), ("ortho_strip_cps8", 1e-3),
                      ("ortho_strip_cax8", 1e-4), ("ortho_ring_cax8_cyl", 1e-4)):
        ref = calculix_displacements(os.path.join(HERE, "calculix", name + ".dat"))
        inc = run_deck(name, path=os.path.join(HERE, "calculix", name + ".inp")).ok().listing.increments[-1]
        u = inc.block("NODE U")
        assert len(u["node"]) == len(ref), f"{name}: {len(u['node'])} nodes against CalculiX's {len(ref)}"
        umax = max(max(abs(a), abs(b)) for a, b in ref.values())
        err = max(max(abs(u["U1"][k] - ref[int(n)][0]), abs(u["U2"][k] - ref[int(n)][1])) / umax
                  for k, n in enumerate(u["node"]))
        assert err < tol, f"{name}: displacements differ from CalculiX's by {err:.2e} of the largest"


def test_errors_name_the_line():
    """Bad anisotropic input stops at its line with file:line: error: and
    exit status 1 (no NaN, no crash)."""
    good = open(os.path.join(HERE, "calculix", "ortho_strip_cpe8.inp")).read()
    eng_line = "140000., 10000., 12000., 0.3, 0.28, 0.45, 5000., 4800.,"
    ori = "*ORIENTATION, NAME=OR"
    cases = [
        ("undefined", good.replace("ORIENTATION=OR", "ORIENTATION=NONE"),
         "*SOLID SECTION, ELSET=EALL, MATERIAL=LAMINA, ORIENTATION=NONE", "undefined orientation NONE"),
        ("nonpd", good.replace(eng_line, "140000., 10000., 12000., 4., 0.28, 0.45, 5000., 4800.,"),
         "3600.", "no positive definite compliance"),
        ("negative", good.replace(eng_line, "140000., -10000., 12000., 0.3, 0.28, 0.45, 5000., 4800.,"),
         "3600.", "must be positive"),
        ("short", good.replace("\n3600.\n", "\n"), eng_line, "missing data line"),
        ("long", good.replace("\n3600.\n", "\n3600., 20., 1.\n"), "3600., 20., 1.", "too many constants"),
        ("temperature", good.replace("\n3600.\n", "\n3600., 20.\n" + eng_line + "\n3600., 100.\n"), eng_line,
         "temperature-dependent"),
        ("ortho_nonpd", good.replace("*ELASTIC, TYPE=ENGINEERING CONSTANTS\n" + eng_line + "\n3600.\n",
                                     "*ELASTIC, TYPE=ORTHO\n1., 2., 1., 0., 0., 1., 1., 1.,\n1.\n"),
         "1.", "not positive definite"),
        ("type", good.replace("TYPE=ENGINEERING CONSTANTS", "TYPE=LAMINA"),
         "*ELASTIC, TYPE=LAMINA", "TYPE=LAMINA is not implemented"),
        ("system", good.replace(ori, ori + ", SYSTEM=SPHERICAL"), ori + ", SYSTEM=SPHERICAL", "SYSTEM=SPHERICAL"),
        ("points", good.replace("0.86602540378443865, 0.5, 0., -0.5, 0.86602540378443865, 0.",
                                "1., 0., 0., 2., 0., 0."), "1., 0., 0., 2., 0., 0.", "off the line of a"),
        ("axis", good.replace("0.86602540378443865, 0.5, 0., -0.5, 0.86602540378443865, 0.",
                              "1., 0., 0., 0., 1., 0.\n4, 30."), "4, 30.", "must be 1, 2 or 3"),
        ("duplicate", good.replace(ori, ori + "\n1., 0., 0., 0., 1., 0.\n" + ori), ori, "duplicate orientation"),
        ("plastic", good.replace("*SOLID SECTION", "*PLASTIC\n100., 0.\n*SOLID SECTION"), "*MATERIAL, NAME=LAMINA",
         "plasticity or hyperelasticity of an anisotropic material"),
    ]
    for tag, deck, line_text, fragment in cases:
        run = run_deck("ortho_err_" + tag, deck)
        lines = deck.splitlines()
        line = next(k for k, t in enumerate(lines, 1) if t == line_text)
        if tag in ("duplicate", "temperature"):   # the second occurrence
            line = max(k for k, t in enumerate(lines, 1) if t == line_text)
        assert run.rc == 1 and f"ortho_err_{tag}.inp:{line}: error:" in run.stderr, (tag, line, run.stderr)
        assert fragment in run.stderr, (tag, run.stderr)


def svk_cauchy(fmat, theta, state):
    """Cauchy stress (s11, s22, s33, s12) of St Venant-Kirchhoff in axes
    turned by theta about z at the in-plane deformation gradient fmat
    (3x3; F33 given in plane strain and axisymmetry, solved from S33 = 0
    in plane stress): E = (F^T F - I) / 2 turned to the material axes,
    S' = C' E' there (Voigt, engineering shear), S = Q^T S' Q, sigma =
    F S F^T / det F."""
    c6 = np.linalg.inv(compliance(ENG))
    c, s = math.cos(theta), math.sin(theta)
    q = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])

    def second_pk(f):
        e = 0.5 * (f.T @ f - np.eye(3))
        el = q @ e @ q.T
        v = c6 @ np.array([el[0, 0], el[1, 1], el[2, 2], 2 * el[0, 1], 2 * el[0, 2], 2 * el[1, 2]])
        sl = np.array([[v[0], v[3], v[4]], [v[3], v[1], v[5]], [v[4], v[5], v[2]]])
        return q.T @ sl @ q

    f = np.array(fmat, dtype=float)
    if state == "S":
        # S33 is linear in E33 = (F33^2 - 1) / 2: two points give its root
        def s33(e33):
            g = f.copy()
            g[2, 2] = math.sqrt(1 + 2 * e33)
            return second_pk(g)[2, 2]
        e0, e1 = 0.0, -0.01
        root = e0 - s33(e0) * (e1 - e0) / (s33(e1) - s33(e0))
        f[2, 2] = math.sqrt(1 + 2 * root)
    sig = f @ second_pk(f) @ f.T / np.linalg.det(f)
    return sig[0, 0], sig[1, 1], sig[2, 2], sig[0, 1]


def test_nlgeom_st_venant_kirchhoff():
    """Under NLGEOM an anisotropic *ELASTIC is St Venant-Kirchhoff, S = C
    E in the material axes (CalculiX's reading of *ELASTIC with NLGEOM):
    one element of each stress state, every node given a homogeneous
    deformation of 10-15 % strain and rotation (axisymmetry: u_r = a r,
    the hoop stretch 1 + a), axes turned by 30 degrees: the Cauchy stress
    at every point to 1e-10 of the closed form (plane stress: S33 = 0)."""
    theta = math.radians(30.0)
    for state in ("S", "E", "AX"):
        a1, a2, a4, a5 = (0.1, 0.15, -0.05, -0.08) if state != "AX" else (0.1, 0.0, -0.05, -0.08)
        x0 = 1.0 if state == "AX" else 0.0
        nodes = {1: (x0, 0.0), 2: (x0 + 1.2, 0.1), 3: (x0 + 1.0, 0.9), 4: (x0 - 0.1, 1.1)}
        bcs = "".join(f"{n}, 1, 1, {a1 * x + a2 * y:.17g}\n{n}, 2, 2, {a4 * x + a5 * y:.17g}\n"
                      for n, (x, y) in nodes.items())
        et = {"S": "CPS4", "E": "CPE4", "AX": "CAX4"}[state]
        deck = f"""*NODE, NSET=ALL
{node_lines(nodes)}*ELEMENT, TYPE={et}, ELSET=E
1, 1, 2, 3, 4
{orientation_card(theta)}*MATERIAL, NAME=M
{material_card("ORTHO")}*SOLID SECTION, ELSET=E, MATERIAL=M, ORIENTATION=OR
1.
*STEP, NLGEOM
*STATIC
0.5, 1.
*BOUNDARY
{bcs}*EL PRINT
S
*END STEP
"""
        b = run_deck(f"ortho_svk_{state.lower()}", deck).ok().listing.increments[-1].block("ELEMENT S")
        f = [[1 + a1, a2, 0.0], [a4, 1 + a5, 0.0], [0.0, 0.0, 1 + a1 if state == "AX" else 1.0]]
        exact = svk_cauchy(f, theta, state)
        smax = max(abs(v) for v in exact)
        for col, se in zip(("S11", "S22", "S33", "S12"), exact):
            e = max(abs(b[col] - se)) / smax
            assert e < 1e-10, f"{et} NLGEOM {col}: error {e:.2e} (exact {se:.6g})"
