"""*RIGID BODY, *COUPLING with *KINEMATIC or *DISTRIBUTING, and *TRANSFORM
(linear constraints, small rotations) against closed forms: a rigid block
turned by its reference node (every displacement exact, CalculiX's ROT
NODE and Abaqus' dof 6 alike), a moment on a rigid body held by a spring
(its rotation, the spring force and the reactions), a face pulled and
turned through a kinematic coupling against the same *EQUATIONs written
by hand (to 1e-12), a force and a moment spread by a distributing
coupling against the hand-made nodal forces, a block on a roller on a
30-degree incline under gravity (the normal reaction and the sliding
against its spring), a cylindrical system turning a plate rigidly; and
bad cards stopped at their line."""
import math

import numpy as np

from helpers import run_deck

E = 1000.0


def grid(nx, ny, x0, x1, y0, y1, first=1, rot=None):
    """A structured CPS4 grid: ({id: (x, y)}, [element node lists],
    {(i, j): id}); rot = (c, s) turns the coordinates about the origin."""
    nodes, ids = {}, {}
    nid = first
    for j in range(ny + 1):
        for i in range(nx + 1):
            x = x0 + (x1 - x0) * i / nx
            y = y0 + (y1 - y0) * j / ny
            if rot is not None:
                x, y = rot[0] * x - rot[1] * y, rot[1] * x + rot[0] * y
            nodes[nid] = (x, y)
            ids[i, j] = nid
            nid += 1
    elems = [[ids[i, j], ids[i + 1, j], ids[i + 1, j + 1], ids[i, j + 1]] for j in range(ny) for i in range(nx)]
    return nodes, elems, ids


def mesh_text(nodes, elems, elset="ALL"):
    n = "*NODE, NSET=NALL\n" + "".join(f"{i}, {x:.17g}, {y:.17g}\n" for i, (x, y) in nodes.items())
    e = f"*ELEMENT, TYPE=CPS4, ELSET={elset}\n" + "".join(f"{k + 1}, " + ", ".join(map(str, c)) + "\n"
                                                       for k, c in enumerate(elems))
    return n + e + f"""*MATERIAL, NAME=M
*ELASTIC
{E}, 0.3
*SOLID SECTION, ELSET={elset}, MATERIAL=M
1.
"""


def node_values(run, block="NODE U", set_="NALL", inc=-1):
    b = run.listing.increments[inc].block(block, set=set_)
    cols = b.columns[1:3]
    return {int(r[0]): np.array(r[1:3], dtype=float) for r in b.rows}, cols


def header_block(run, name):
    return run.listing.header[[b.name for b in run.listing.header].index(name)]


# ------------------------------------------------------------ *RIGID BODY

REF = (1.3, 0.7)


def rigid_block_deck(style):
    """A 3 x 2 CPS4 block [0,3]x[0,2], every node rigid to reference node
    100 at REF, which is moved by (0.004, -0.003) and turned by 0.002:
    CalculiX style (ROT NODE 101, its dof 3), Abaqus style (no ROT NODE,
    dof 6 of the reference node) or ENCASTRE-like (the range 1..6)."""
    nodes, elems, _ = grid(3, 2, 0.0, 3.0, 0.0, 2.0)
    text = mesh_text(nodes, elems) + f"*NODE\n100, {REF[0]}, {REF[1]}\n"
    if style == "calculix":
        text += "101, 9., 9.\n*RIGID BODY, ELSET=ALL, REF NODE=100, ROT NODE=101\n*BOUNDARY\n100, 1, 1, 0.004\n" \
                "100, 2, 2, -0.003\n101, 3, 3, 0.002\n"
    elif style == "abaqus":
        text += "*NSET, NSET=RP\n100\n*RIGID BODY, NSET=NALL, REF NODE=RP\n*BOUNDARY\nRP, 1, 1, 0.004\n" \
                "RP, 2, 2, -0.003\nRP, 6, 6, 0.002\n"
    return text + """*STEP
*STATIC
*NODE PRINT, NSET=NALL
U, RF
*EL PRINT, ELSET=ALL
S
*END STEP
"""


def test_rigid_body_turned_by_its_reference_node_is_exact():
    """Every node of a rigid block moves by u_ref + theta z x (x - x_ref)
    to round-off, the rotation given as CalculiX's ROT NODE dof 3 or as
    Abaqus' dof 6 of the reference node (a node made for it, id 101 after
    the largest); the block is not strained and nothing reacts."""
    for style in ("calculix", "abaqus"):
        run = run_deck("rigid_turn_" + style, rigid_block_deck(style)).ok()
        u, _ = node_values(run)
        theta = 0.002
        for nid, (x, y) in grid(3, 2, 0.0, 3.0, 0.0, 2.0)[0].items():
            exact = np.array([0.004 - theta * (y - REF[1]), -0.003 + theta * (x - REF[0])])
            assert np.abs(u[nid] - exact).max() < 1e-15, (style, nid, u[nid], exact)
        rb = header_block(run, "RIGID BODIES")
        assert rb["card"] == ["RIGID_BODY"] and rb["ref_node"][0] == 100 and rb["rot_node"][0] == 101, rb.rows
        assert rb["nodes"][0] == 12, rb.rows
        rf, _ = node_values(run, "NODE RF")
        assert max(np.abs(v).max() for v in rf.values()) < 1e-10
        s = run.listing.increments[-1].block("ELEMENT S", set="ALL")
        assert np.abs(s["S11"]).max() < 1e-10 and np.abs(s["S12"]).max() < 1e-10


def spring_deck(load):
    """Four nodes of no element made rigid to reference node 10 at (0.5,
    0.5), which is pinned; node 2 at (2, 0) on a grounded spring (dof 2,
    k = 500): `load` turns the body. Node 11 is the CalculiX deck's ROT
    NODE (the Abaqus deck leaves it unused; its rotation node is made,
    id 12)."""
    return f"""*NODE, NSET=NALL
1, 0., 0.
2, 2., 0.
3, 2., 1.
4, 0., 1.
10, 0.5, 0.5
11, 0., 0.
*NSET, NSET=BODY
1, 2, 3, 4
*NSET, NSET=REF
10
*ELEMENT, TYPE=SPRING1, ELSET=SPR
1, 2
*SPRING, ELSET=SPR
2
500.
{load[0]}*STEP
*STATIC
{load[1]}*NODE PRINT
U, RF
*EL PRINT, ELSET=SPR
S
*END STEP
"""


def test_moment_on_a_rigid_body_held_by_a_spring():
    """A moment M = 30 on the rotation (Abaqus: *CLOAD on dof 6 of the
    reference node; CalculiX: on dof 3 of the ROT NODE) turns the body by
    theta = M / (k L^2) (L = 1.5, the spring's lever about the pinned
    reference node): the spring stretches by theta L, carries M / L, and
    the pin reacts with M / L; prescribing that rotation instead gives
    the moment M back as the reaction of the rotation (RF1 of its node)."""
    k, lever, moment = 500.0, 1.5, 30.0
    theta = moment / (k * lever ** 2)
    abaqus = ("*RIGID BODY, NSET=BODY, REF NODE=REF\n*BOUNDARY\nREF, 1, 2\n", "*CLOAD\nREF, 6, 30.\n")
    calculix = ("*RIGID BODY, NSET=BODY, REF NODE=10, ROT NODE=11\n*BOUNDARY\n10, 1, 2\n", "*CLOAD\n11, 3, 30.\n")
    for tag, load in (("abaqus", abaqus), ("calculix", calculix)):
        run = run_deck("rigid_spring_" + tag, spring_deck(load)).ok()
        u, _ = node_values(run, set_="ALL")
        rf, _ = node_values(run, "NODE RF", set_="ALL")
        rot = int(header_block(run, "RIGID BODIES")["rot_node"][0])
        assert rot == (12 if tag == "abaqus" else 11), rot
        assert abs(u[rot][0] - theta) < 1e-14 * theta, (tag, u[rot], theta)
        assert abs(u[2][1] - theta * lever) < 1e-14 * theta * lever, (tag, u[2])
        assert abs(u[4][0] - (-theta * 0.5)) < 1e-15 and abs(u[4][1] - (-theta * 0.5)) < 1e-15, u[4]
        assert abs(rf[10][1] - moment / lever) < 1e-12 * moment and abs(rf[10][0]) < 1e-12 * moment, (tag, rf[10])
        force = run.listing.increments[-1].block("ELEMENT S", set="SPR")["S11"][0]
        assert abs(force - moment / lever) < 1e-12 * moment, force
    prescribed = ("*RIGID BODY, NSET=BODY, REF NODE=REF\n*BOUNDARY\nREF, 1, 2\n", f"*BOUNDARY\nREF, 6, 6, {theta!r}\n")
    run = run_deck("rigid_spring_prescribed", spring_deck(prescribed)).ok()
    rf, _ = node_values(run, "NODE RF", set_="ALL")
    assert abs(rf[12][0] - moment) < 1e-12 * moment, rf[12]
    assert abs(rf[10][1] - moment / lever) < 1e-12 * moment, rf[10]


# ------------------------------------------------- *COUPLING, *KINEMATIC

RP = (5.0, 1.3)


def coupling_decks(dofs, step_coupled, step_by_hand):
    """A 4 x 2 CPS4 block [0,4]x[0,2] clamped at x = 0, its face x = 4
    coupled to reference node 100 at RP: with *COUPLING/*KINEMATIC (the
    dofs lines `dofs`) and with the same constraints written as
    *EQUATIONs, the rotation in node 101 of no element (its dof 1)."""
    nodes, elems, ids = grid(4, 2, 0.0, 4.0, 0.0, 2.0)
    base = mesh_text(nodes, elems) + f"*NODE, NSET=RPS\n100, {RP[0]}, {RP[1]}\n" + \
        "*NSET, NSET=LEFT\n" + "".join(f"{ids[0, j]}\n" for j in range(3))
    face = [ids[4, j] for j in range(3)]
    coupled = base + "*SURFACE, NAME=RIGHT\n4, S2\n8, S2\n*COUPLING, REF NODE=100, SURFACE=RIGHT, " \
        "CONSTRAINT NAME=PULL\n*KINEMATIC\n" + "".join(f"{d}\n" for d in dofs)
    eqs = ""
    follows = {1, 2} if not dofs else {d for d in dofs if d in (1, 2)}
    for j in face:
        x, y = nodes[j]
        if 1 in follows:
            eqs += f"3\n{j}, 1, 1., 100, 1, -1., 101, 1, {y - RP[1]!r}\n"
        if 2 in follows:
            eqs += f"3\n{j}, 2, 1., 100, 2, -1., 101, 1, {-(x - RP[0])!r}\n"
    by_hand = base + f"*NODE, NSET=RPS\n101, {RP[0]}, {RP[1]}\n*EQUATION\n" + eqs
    tail = "*BOUNDARY\nLEFT, 1, 2\n*STEP\n*STATIC\n{step}*NODE PRINT, NSET=NALL\nU\n*NODE PRINT, NSET=RPS\nU, RF\n" \
           "*END STEP\n"
    return coupled + tail.format(step=step_coupled), by_hand + tail.format(step=step_by_hand)


def test_kinematic_coupling_equals_the_equations_by_hand():
    """A face pulled, sheared and turned through a kinematic coupling
    (forces and a moment on the reference node; or its displacements
    and rotation prescribed; or only dof 1 following) gives the
    displacements of the same constraints written as *EQUATIONs to 1e-12
    of the largest, and the same reactions at the reference node; dof 6
    on *KINEMATIC (Abaqus CAE writes it for 2D) changes nothing."""
    loads = "*CLOAD\n100, 1, 10.\n100, 2, -5.\n{}, 3.\n"
    cases = {
        "loads": ((1, 2), loads.format("100, 6"), loads.format("101, 1")),
        "loads_dof6": ((1, 2, 6), loads.format("100, 6"), loads.format("101, 1")),
        "alldofs": ((), loads.format("100, 6"), loads.format("101, 1")),
        "prescribed": ((1, 2), "*BOUNDARY\n100, 1, 1, 0.01\n100, 2, 2, -0.02\n100, 6, 6, 0.001\n",
                       "*BOUNDARY\n100, 1, 1, 0.01\n100, 2, 2, -0.02\n101, 1, 1, 0.001\n"),
        "dof1": ((1,), "*CLOAD\n100, 1, 10.\n100, 6, -4.\n", "*CLOAD\n100, 1, 10.\n101, 1, -4.\n"),
    }
    for tag, (dofs, step_a, step_b) in cases.items():
        a, b = coupling_decks(dofs, step_a, step_b)
        ra = run_deck("kin_" + tag, a).ok()
        rb = run_deck("kin_" + tag + "_eq", b).ok()
        ua, _ = node_values(ra)
        ub, _ = node_values(rb)
        scale = max(np.abs(v).max() for v in ub.values())
        assert scale > 1e-4
        assert max(np.abs(ua[n] - ub[n]).max() for n in ub) < 1e-12 * scale, tag
        pa, _ = node_values(ra, set_="RPS")
        pb, _ = node_values(rb, set_="RPS")
        assert np.abs(pa[100] - pb[100]).max() < 1e-12 * scale, (tag, pa, pb)
        rot = int(header_block(ra, "RIGID BODIES")["rot_node"][0])
        assert abs(ra.listing.increments[-1].block("NODE U", set="NALL")["U1"][0]) >= 0  # listing readable
        fa, _ = node_values(ra, "NODE RF", set_="RPS")
        fb, _ = node_values(rb, "NODE RF", set_="RPS")
        assert np.abs(fa[100] - fb[100]).max() < 1e-9 * max(1.0, np.abs(fb[100]).max()), (tag, fa, fb)
        assert rot == 101, rot


# --------------------------------------------------------- *DISTRIBUTING

TOPREF = (3.0, 3.0)


def distributing_decks(dofs, f1, f2, moment):
    """A 4 x 2 CPS4 block [0,4]x[0,2] clamped at y = 0; a force (f1, f2)
    and a moment at reference node 100 at TOPREF spread over the top face
    by *DISTRIBUTING, and the same as nodal *CLOADs made here: weights
    w = (0.5, 1, 1, 1, 0.5) (the length each node stands for), W = 4,
    centroid (2, 2), I = sum w (x - 2)^2 = 6; f_j = w_j F / W + w_j (M +
    (x_ref - c) x F) (-(y_j - 2), x_j - 2) / I."""
    nodes, elems, ids = grid(4, 2, 0.0, 4.0, 0.0, 2.0)
    base = mesh_text(nodes, elems) + "*NSET, NSET=BOTTOM\n" + "".join(f"{ids[i, 0]}\n" for i in range(5))
    top = [ids[i, 2] for i in range(5)]
    w = np.array([0.5, 1.0, 1.0, 1.0, 0.5])
    c = np.array([2.0, 2.0])
    inertia = sum(w[i] * ((nodes[n][0] - c[0]) ** 2 + (nodes[n][1] - c[1]) ** 2) for i, n in enumerate(top))
    dx = np.array(TOPREF) - c
    total_moment = moment + dx[0] * f2 - dx[1] * f1
    loads = ""
    for i, n in enumerate(top):
        r = np.array(nodes[n]) - c
        f = w[i] * np.array([f1, f2]) / w.sum() + w[i] * total_moment * np.array([-r[1], r[0]]) / inertia
        loads += f"{n}, 1, {float(f[0])!r}\n{n}, 2, {float(f[1])!r}\n"
    spread = base + f"*NODE, NSET=RPS\n100, {TOPREF[0]}, {TOPREF[1]}\n*SURFACE, NAME=TOP\n5, S3\n6, S3\n7, S3\n" \
        "8, S3\n*COUPLING, REF NODE=100, SURFACE=TOP, CONSTRAINT NAME=SPREAD\n*DISTRIBUTING\n" + \
        "".join(f"{d}\n" for d in dofs)
    ref_loads = f"100, 1, {f1}\n100, 2, {f2}\n" + (f"100, 6, {moment}\n" if moment else "")
    tail = "*BOUNDARY\nBOTTOM, 1, 2\n*STEP\n*STATIC\n*CLOAD\n{loads}*NODE PRINT, NSET=NALL\nU\n{ref}*END STEP\n"
    return (spread + tail.format(loads=ref_loads, ref="*NODE PRINT, NSET=RPS\nU\n"),
            base + tail.format(loads=loads, ref=""), top, w, c, inertia)


def test_distributing_coupling_spreads_force_and_moment():
    """A force and a moment on the reference node of a *DISTRIBUTING
    coupling load the model as the hand-made nodal forces do (the
    displacements to 1e-12 of the largest); without dof 6 named the force
    still acts at the reference node (its moment about the centroid is
    spread). The reference node moves as the weighted average of the
    face, u_ref = sum w u / W + theta z x (x_ref - c), theta = sum w (r x
    u) / I, and adds no stiffness."""
    for tag, dofs, moment in (("fm", (1, 2, 6), 7.0), ("f", (1, 2), 0.0), ("all", (), 7.0)):
        a, b, top, w, c, inertia = distributing_decks(dofs, 10.0, -20.0, moment)
        ra = run_deck("dist_" + tag, a).ok()
        rb = run_deck("dist_" + tag + "_loads", b).ok()
        ua, _ = node_values(ra)
        ub, _ = node_values(rb)
        scale = max(np.abs(v).max() for v in ub.values())
        assert max(np.abs(ua[n] - ub[n]).max() for n in ub) < 1e-12 * scale, (tag, scale)
        ubar = sum(w[i] * ua[n] for i, n in enumerate(top)) / w.sum()
        xs = {n: np.array(p) for n, p in zip(top, [(float(i), 2.0) for i in range(5)])}
        theta = sum(w[i] * ((xs[n] - c)[0] * ua[n][1] - (xs[n] - c)[1] * ua[n][0]) for i, n in enumerate(top)) / inertia
        d = np.array(TOPREF) - c
        uref = ubar + theta * np.array([-d[1], d[0]])
        pa, _ = node_values(ra, set_="RPS")
        assert np.abs(pa[100] - uref).max() < 1e-12 * scale, (tag, pa[100], uref)


# ------------------------------------------------------------- *TRANSFORM

C30, S30 = math.cos(math.radians(30.0)), math.sin(math.radians(30.0))


def incline_deck(extra_step="", print_global=False, load="*DLOAD\nALL, GRAV, 10., 0., -1.\n", spring=True):
    """A 2 x 1 block (2 by 1, density 2: weight W = 40) on a 30-degree
    incline: its base nodes on rollers normal to the incline (*TRANSFORM
    with x' up the slope, *BOUNDARY on local dof 2), its lower corner
    held along the slope by a SPRINGA (k = 1000) to an anchor one unit
    down the slope."""
    nodes, elems, ids = grid(2, 1, 0.0, 2.0, 0.0, 1.0, rot=(C30, S30))
    base = [ids[i, 0] for i in range(3)]
    text = mesh_text(nodes, elems).replace("*SOLID SECTION", "*DENSITY\n2.\n*SOLID SECTION")
    if spring:
        text += f"*NODE, NSET=ANCHOR\n50, {-C30!r}, {-S30!r}\n*ELEMENT, TYPE=SPRINGA, ELSET=SPR\n10, 50, {ids[0, 0]}\n" \
                f"*SPRING, ELSET=SPR\n\n1000.\n"
    text += "*NSET, NSET=BASE\n" + "".join(f"{n}\n" for n in base) + \
            f"*NSET, NSET=TOP\n{ids[2, 1]}\n" \
            f"*TRANSFORM, NSET=BASE, TYPE=R\n{C30!r}, {S30!r}, 0., {-S30!r}, {C30!r}, 0.\n" \
            f"*TRANSFORM, NSET=TOP\n{C30!r}, {S30!r}, 0., {-S30!r}, {C30!r}, 0.\n" \
            "*BOUNDARY\nBASE, 2, 2\n" + ("ANCHOR, 1, 2\n" if spring else f"{ids[0, 0]}, 1, 1\n")
    prints = "*NODE PRINT, NSET=NALL\nU, RF\n"
    if print_global:
        prints += "*NODE PRINT, NSET=NALL, GLOBAL=YES\nU, RF\n"
    springs = "*EL PRINT, ELSET=SPR\nS\n" if spring else ""
    return text + f"*STEP\n*STATIC\n{load}{extra_step}{prints}{springs}*END STEP\n", ids


def test_block_on_a_roller_on_an_incline():
    """Gravity on a block whose base rolls on a 30-degree incline: the
    normal reactions of the base (its nodes' local RF2, printed in local
    axes as CalculiX's *NODE PRINT does, rows marked L) sum to W cos 30,
    the tangential ones are zero, the spring holds W sin 30 and the lower
    corner slides down the slope by W sin 30 / k; GLOBAL=YES gives the same
    vectors in global axes, the REACTIONS sums are global (the normal
    force along (-sin 30, cos 30)), and the supports balance the weight."""
    weight, k = 40.0, 1000.0
    deck, ids = incline_deck(print_global=True)
    run = run_deck("incline", deck).ok()
    inc = run.listing.increments[-1]
    blocks = [b for b in inc.blocks if b.name == "NODE RF"]
    local, glob = blocks
    assert local.columns[-1] == "system" and glob.columns == ["node", "RF1", "RF2"]
    rows = {int(r[0]): r for r in local.rows}
    base = [ids[i, 0] for i in range(3)]
    assert all(rows[n][3] == "L" for n in base) and rows[ids[1, 1]][3] == "G"
    normal = sum(rows[n][2] for n in base)
    tangential = sum(rows[n][1] for n in base)
    assert abs(normal - weight * C30) < 1e-12 * weight, normal
    assert abs(tangential) < 1e-12 * weight, tangential
    ul = {int(r[0]): np.array(r[1:3], dtype=float) for r in [b for b in inc.blocks if b.name == "NODE U"][0].rows}
    ug = {int(r[0]): np.array(r[1:3], dtype=float) for r in [b for b in inc.blocks if b.name == "NODE U"][1].rows}
    slide = -weight * S30 / k
    assert abs(ul[ids[0, 0]][0] - slide) < 1e-12 * abs(slide), ul[ids[0, 0]]
    assert abs(ul[ids[0, 0]][1]) < 1e-15 and abs(ul[ids[2, 0]][1]) < 1e-15
    axes = np.array([[C30, -S30], [S30, C30]])
    for n in base:
        assert np.abs(axes @ ul[n] - ug[n]).max() < 1e-15, n
    force = inc.block("ELEMENT S", set="SPR")["S11"][0]
    assert abs(force - (-weight * S30)) < 1e-12 * weight, force      # compressed by the block sliding down
    sums = inc.block("REACTIONS").as_dict()
    assert np.abs(np.array(sums["BASE"]) - weight * C30 * np.array([-S30, C30])).max() < 1e-12 * weight, sums
    total = np.array(sums["BASE"]) + np.array(sums["ANCHOR"])
    assert np.abs(total - [0.0, weight]).max() < 1e-12 * weight, total
    tr = header_block(run, "TRANSFORMS")
    assert tr["set"] == ["BASE", "TOP"] and tr["local_nodes"][0] == 3 and tr["local_nodes"][1] == 0, tr.rows


def test_load_in_local_axes_equals_its_global_components():
    """A *CLOAD on the local dofs of a transformed node (the block's top
    corner: P up the slope, Q normal to it) gives the displacements of
    the same force in global components on a node without *TRANSFORM, to
    1e-12 (the block on its roller and spring, no gravity)."""
    p, q = 3.0, -2.0
    deck, ids = incline_deck(load=f"*CLOAD\nTOP, 1, {p}\nTOP, 2, {q}\n")
    run = run_deck("incline_local_load", deck).ok()
    fx, fy = p * C30 - q * S30, p * S30 + q * C30
    plain, _ = incline_deck(load=f"*CLOAD\n{ids[2, 1]}, 1, {fx!r}\n{ids[2, 1]}, 2, {fy!r}\n")
    plain = plain.replace(f"*TRANSFORM, NSET=TOP\n{C30!r}, {S30!r}, 0., {-S30!r}, {C30!r}, 0.\n", "")
    ref = run_deck("incline_global_load", plain).ok()
    ua, _ = node_values(run, set_="NALL")
    ub, _ = node_values(ref, set_="NALL")
    top = ids[2, 1]
    axes = np.array([[C30, -S30], [S30, C30]])
    ua[top] = axes @ ua[top]           # the local row of the top corner, to global
    scale = max(np.abs(v).max() for v in ub.values())
    assert max(np.abs(ua[n] - ub[n]).max() for n in ub) < 1e-12 * scale


def test_transform_with_a_point_out_of_the_plane_uses_its_in_plane_part():
    """A rectangular *TRANSFORM whose points lie out of the x-y plane (b
    lifted by 1.7 above the incline's system, a by 0.4, both scaled) is
    read as its in-plane projection, with a warning quoting the data line:
    the incline's results are those of the in-plane system (1e-14).
    (CalculiX 2.20 keeps the tilted system and holds the node along its
    tilted local z axis: in a plane-strain model the node then moves out
    of the plane, by 1.56e-3 for a local 0.01 along a = (1, 1, 0) with b =
    (-1, 1, 1); no reference.)"""
    plain, _ = incline_deck()
    flat = f"{C30!r}, {S30!r}, 0., {-S30!r}, {C30!r}, 0."
    lifted = f"{2 * C30!r}, {2 * S30!r}, 0.4, {-3 * S30!r}, {3 * C30!r}, 1.7"
    deck = plain.replace(f"*TRANSFORM, NSET=BASE, TYPE=R\n{flat}\n", f"*TRANSFORM, NSET=BASE, TYPE=R\n{lifted}\n")
    assert deck != plain
    run = run_deck("incline_lifted", deck).ok()
    line = deck.splitlines().index(lifted) + 1
    assert f"incline_lifted.inp:{line}: warning: *TRANSFORM: a 2D model's local z axis is the global one" in \
        run.stderr and "the in-plane parts (a1, a2) and (b1, b2) are used" in run.stderr, run.stderr
    ref = run_deck("incline_flat", plain).ok()
    assert "warning" not in ref.stderr, ref.stderr
    ua, _ = node_values(run)
    ub, _ = node_values(ref)
    scale = max(np.abs(v).max() for v in ub.values())
    assert max(np.abs(ua[n] - ub[n]).max() for n in ub) < 1e-14 * scale


def test_cylindrical_system_turns_a_plate_rigidly():
    """TYPE=C about the z axis through the origin: every node of a plate
    held radially (local dof 1 = 0) and moved tangentially by r theta
    (local dof 2) turns rigidly by theta: u = theta (-y, x) exactly; with
    the axis reversed (b below a) the tangential direction flips."""
    theta = 0.003
    nodes, elems, ids = grid(2, 2, 1.0, 3.0, 1.0, 3.0)
    edge = [n for n in nodes if n != ids[1, 1]]           # the middle node is free
    for tag, axis, sign in (("up", "0., 0., 0., 0., 0., 1.", 1.0), ("down", "0., 0., 1., 0., 0., -2.", -1.0)):
        bcs = "".join(f"{n}, 1, 1\n{n}, 2, 2, {sign * theta * math.hypot(*nodes[n])!r}\n" for n in edge)
        deck = mesh_text(nodes, elems) + f"*TRANSFORM, NSET=NALL, TYPE=C\n{axis}\n*BOUNDARY\n{bcs}" + \
            "*STEP\n*STATIC\n*NODE PRINT, NSET=NALL, GLOBAL=YES\nU\n*END STEP\n"
        run = run_deck("cyl_turn_" + tag, deck).ok()
        u, _ = node_values(run)
        for n, (x, y) in nodes.items():
            assert np.abs(u[n] - theta * np.array([-y, x])).max() < 1e-14 * theta * 4, (tag, n, u[n])


def test_equation_on_local_dofs():
    """An *EQUATION term on a transformed node names its local dof (as
    CalculiX's MPCs do): u'_2 = 0 written as a one-term *EQUATION on each
    base node of the incline is its roller, the same displacements as
    the *BOUNDARY to 1e-12."""
    deck, ids = incline_deck()
    base = [ids[i, 0] for i in range(3)]
    eqs = "*EQUATION\n" + "".join(f"1\n{n}, 2, 1.\n" for n in base)
    run = run_deck("incline_eq", deck.replace("*BOUNDARY\nBASE, 2, 2\n", eqs + "*BOUNDARY\n")).ok()
    ref = run_deck("incline_bc", deck).ok()
    ua, _ = node_values(run)
    ub, _ = node_values(ref)
    scale = max(np.abs(v).max() for v in ub.values())
    assert max(np.abs(ua[n] - ub[n]).max() for n in ub) < 1e-12 * scale


# CalculiX 2.20 (Debian's ccx) on the same plane-strain decks (CPE4), its
# .dat as printed: the incline held along the slope at its lower corner
# (its node print in local axes, rows marked L, as cfe2d's), and the
# kinematic coupling's constraints written as *EQUATIONs (loads case).
CCX_INCLINE = """
1  0.000000E+00  0.000000E+00 L
2 -2.975373E-02  1.734723E-18 L
3 -3.620691E-02  0.000000E+00 L
4 -3.551330E-02 -3.475614E-02 G
5 -3.148254E-02 -1.705460E-02 G
6 -3.481659E-02 -5.523376E-03 L
"""
CCX_KINEMATIC = """
1  0.000000E+00  0.000000E+00
2 -2.092551E-02 -2.024597E-02
3 -3.770207E-02 -6.126496E-02
4 -4.825006E-02 -1.212701E-01
5 -5.254700E-02 -1.940482E-01
6  0.000000E+00  0.000000E+00
7  3.943434E-03 -1.601460E-02
8  8.724257E-03 -5.968648E-02
9  1.350508E-02 -1.204673E-01
10  1.744851E-02 -1.940482E-01
11  0.000000E+00  0.000000E+00
12  2.962089E-02 -2.427122E-02
13  5.515059E-02 -6.530753E-02
14  7.445171E-02 -1.252953E-01
15  8.744403E-02 -1.940482E-01
"""


def test_against_calculix():
    """CalculiX 2.20 on the same plane-strain decks: the incline (held
    along the slope at one corner instead of the spring) agrees to its 7
    printed digits in the same local and global rows, and the kinematic
    coupling agrees with CalculiX solving its constraints as *EQUATIONs.
    (CalculiX's own *COUPLING on a 2D mesh is not the reference: ccx 2.20
    reads the face S2 of CPE4 element 4 as a face of the brick it expands
    the element into, and made all four nodes of elements 4 and 8 rigid.)"""
    deck, _ = incline_deck(spring=False)
    run = run_deck("incline_ccx", deck.replace("TYPE=CPS4", "TYPE=CPE4")).ok()
    rows = {int(r[0]): r for r in run.listing.increments[-1].block("NODE U", set="NALL").rows}
    for line in CCX_INCLINE.split("\n")[1:-1]:
        n, u1, u2, sys = line.split()
        assert rows[int(n)][3] == sys and abs(rows[int(n)][1] - float(u1)) < 5e-7 * 0.04, (n, rows[int(n)])
        assert abs(rows[int(n)][2] - float(u2)) < 5e-7 * 0.04, (n, rows[int(n)])
    loads = "*CLOAD\n100, 1, 10.\n100, 2, -5.\n{}, 3.\n"
    a, _ = coupling_decks((1, 2), loads.format("100, 6"), loads.format("101, 1"))
    u, _ = node_values(run_deck("kin_ccx", a.replace("TYPE=CPS4", "TYPE=CPE4")).ok())
    for line in CCX_KINEMATIC.split("\n")[1:-1]:
        n, u1, u2 = line.split()
        assert np.abs(u[int(n)] - [float(u1), float(u2)]).max() < 5e-7 * 0.2, (n, u[int(n)])


def decks():
    """Good decks of every card here, for the debug and sanitizer builds."""
    out = {"rigid_calculix": rigid_block_deck("calculix"), "rigid_abaqus": rigid_block_deck("abaqus"),
           "incline": incline_deck(print_global=True)[0]}
    a, b = coupling_decks((1, 2, 6), "*CLOAD\n100, 1, 10.\n100, 6, 3.\n", "*CLOAD\n100, 1, 10.\n101, 1, 3.\n")
    out["kinematic"], out["kinematic_eq"] = a, b
    out["distributing"] = distributing_decks((1, 2, 6), 10.0, -20.0, 7.0)[0]
    out["spring"] = spring_deck(("*RIGID BODY, NSET=BODY, REF NODE=REF\n*BOUNDARY\nREF, 1, 2\n",
                                 "*CLOAD\nREF, 6, 30.\n"))
    return out


# ------------------------------------------------------------- bad cards

BASE = """*NODE, NSET=NALL
1, 0., 0.
2, 1., 0.
3, 1., 1.
4, 0., 1.
10, 2., 0.5
11, 5., 5.
*ELEMENT, TYPE=CPS4, ELSET=ALL
1, 1, 2, 3, 4
*MATERIAL, NAME=M
*ELASTIC
1000., 0.3
*SOLID SECTION, ELSET=ALL, MATERIAL=M
1.
*SURFACE, NAME=RIGHT
1, S2
*SURFACE, NAME=RNODES, TYPE=NODE
2, 3
*NSET, NSET=LEFT
1, 4
*NSET, NSET=TWO
10, 11
*BOUNDARY
LEFT, 1, 2
{card}*STEP
*STATIC
*CLOAD
{load}*END STEP
"""


def stops_at(name, card, bad_line, fragment, load="2, 1, 1.\n"):
    deck = BASE.format(card=card, load=load)
    run = run_deck(name, deck)
    line = deck.splitlines().index(bad_line) + 1
    assert run.rc == 1 and f"{name}.inp:{line}: error:" in run.stderr, run.stderr
    assert fragment in run.stderr, run.stderr


def bad_decks():
    """The bad cards' decks, for the debug and sanitizer builds."""
    return {"rigid_" + tag: BASE.format(card=card, load="2, 1, 1.\n") for tag, card, _, _ in BAD}


def test_rigid_cards_stop_at_their_line():
    """Each bad card stops the run at its line with the reason."""
    for tag, card, bad, fragment in BAD:
        stops_at("rigid_" + tag, card, bad, fragment)
    # a node of a rigid body cannot be prescribed: its dofs follow the reference node
    deck = BASE.format(card="*RIGID BODY, ELSET=ALL, REF NODE=10\n", load="10, 1, 1.\n")
    run = run_deck("rigid_bc_on_body", deck)
    line = deck.splitlines().index("*RIGID BODY, ELSET=ALL, REF NODE=10") + 1
    assert run.rc == 1 and f"rigid_bc_on_body.inp:{line}: error:" in run.stderr, run.stderr
    assert "also has a *BOUNDARY" in run.stderr, run.stderr
    # a moment about an in-plane axis has nothing to act on
    stops_at("rigid_cload_dof4", "*RIGID BODY, NSET=TWO, REF NODE=2\n", "2, 4, 1.", "rotation about the x axis",
             load="2, 4, 1.\n")


BAD = (
        ("rb_noset", "*RIGID BODY, REF NODE=10\n", "*RIGID BODY, REF NODE=10", "needs NSET= or ELSET="),
        ("rb_both", "*RIGID BODY, NSET=LEFT, ELSET=ALL, REF NODE=10\n", "*RIGID BODY, NSET=LEFT, ELSET=ALL, "
         "REF NODE=10", "mutually exclusive"),
        ("rb_refset", "*RIGID BODY, NSET=LEFT, REF NODE=TWO\n", "*RIGID BODY, NSET=LEFT, REF NODE=TWO",
         "exactly one node"),
        ("rb_rotelem", "*RIGID BODY, NSET=LEFT, REF NODE=10, ROT NODE=3\n",
         "*RIGID BODY, NSET=LEFT, REF NODE=10, ROT NODE=3", "must be in no element"),
        ("rb_rotref", "*RIGID BODY, NSET=LEFT, REF NODE=10, ROT NODE=10\n",
         "*RIGID BODY, NSET=LEFT, REF NODE=10, ROT NODE=10", "two nodes"),
        ("rb_twice", "*NSET, NSET=B\n2, 3\n*RIGID BODY, NSET=B, REF NODE=10\n*RIGID BODY, NSET=B, REF NODE=11\n",
         "*RIGID BODY, NSET=B, REF NODE=11", "already depends on other dofs"),
        ("cp_alone", "*COUPLING, REF NODE=10, SURFACE=RIGHT\n*BOUNDARY\n10, 1, 2\n",
         "*COUPLING, REF NODE=10, SURFACE=RIGHT", "must be followed by *KINEMATIC or *DISTRIBUTING"),
        ("kin_alone", "*KINEMATIC\n1, 2\n", "*KINEMATIC", "must follow a *COUPLING"),
        ("cp_orient", "*COUPLING, REF NODE=10, SURFACE=RIGHT, ORIENTATION=OR1\n*KINEMATIC\n",
         "*COUPLING, REF NODE=10, SURFACE=RIGHT, ORIENTATION=OR1", "ORIENTATION="),
        ("cp_nosurf", "*COUPLING, REF NODE=10, SURFACE=NONE\n*KINEMATIC\n", "*COUPLING, REF NODE=10, SURFACE=NONE",
         "undefined surface NONE"),
        ("kin_dof7", "*COUPLING, REF NODE=10, SURFACE=RIGHT\n*KINEMATIC\n1, 7\n", "1, 7", "1 <= first <= last <= 6"),
        ("dist_nodes", "*COUPLING, REF NODE=10, SURFACE=RNODES\n*DISTRIBUTING\n1, 6\n",
         "*COUPLING, REF NODE=10, SURFACE=RNODES", "must be made of element faces"),
        ("dist_weight", "*COUPLING, REF NODE=10, SURFACE=RIGHT\n*DISTRIBUTING, WEIGHTING METHOD=CUBIC\n",
         "*DISTRIBUTING, WEIGHTING METHOD=CUBIC", "only WEIGHTING METHOD=UNIFORM"),
        ("dof6_plain", "*BOUNDARY\n11, 6, 6\n", "11, 6, 6", "exist only at the reference node"),
        ("dof6_before", "*BOUNDARY\n10, 6, 6\n*RIGID BODY, NSET=LEFT, REF NODE=10\n", "10, 6, 6",
         "exist only at the reference node"),
        ("rot_named_before", "*BOUNDARY\n11, 1, 1\n*RIGID BODY, NSET=TWO, REF NODE=2, ROT NODE=11\n",
         "*RIGID BODY, NSET=TWO, REF NODE=2, ROT NODE=11", "put the *RIGID BODY first"),
        ("rot_dof1", "*RIGID BODY, ELSET=ALL, REF NODE=10, ROT NODE=11\n*BOUNDARY\n11, 1, 1, 0.1\n",
         "11, 1, 1, 0.1", "rotation about the x axis"),
        ("ref_dof4", "*RIGID BODY, ELSET=ALL, REF NODE=10\n*BOUNDARY\n10, 4, 4, 0.1\n", "10, 4, 4, 0.1",
         "rotation about the x axis"),
        ("tr_axis_z", "*TRANSFORM, NSET=LEFT\n0., 0., 1., 0., 1., 0.\n", "0., 0., 1., 0., 1., 0.",
         "lies on the z axis"),
        ("tr_b_above_a", "*TRANSFORM, NSET=LEFT\n1., 0., 0., 2., 0., 1.\n", "1., 0., 0., 2., 0., 1.",
         "its in-plane part does"),
        ("tr_line", "*TRANSFORM, NSET=LEFT\n1., 1., 0., 2., 2., 0.\n", "1., 1., 0., 2., 2., 0.",
         "lies on the local x axis"),
        ("tr_cyl_axis", "*TRANSFORM, NSET=LEFT, TYPE=C\n0., 0., 0., 1., 0., 0.\n", "0., 0., 0., 1., 0., 0.",
         "axis parallel to z"),
        ("tr_on_axis", "*TRANSFORM, NSET=LEFT, TYPE=C\n0., 1., 0., 0., 1., 1.\n", "0., 1., 0., 0., 1., 1.",
         "lies on the axis"),
        ("tr_type", "*TRANSFORM, NSET=LEFT, TYPE=S\n1., 0., 0., 0., 1., 0.\n", "*TRANSFORM, NSET=LEFT, TYPE=S",
         "TYPE must be R"),
)


def test_rigid_cards_without_blanks():
    """CalculiX reads *RIGIDBODY, REFNODE=, ROTNODE= as *RIGID BODY."""
    deck = rigid_block_deck("calculix").replace("*RIGID BODY, ELSET=ALL, REF NODE=100, ROT NODE=101",
                                                "*RIGIDBODY, ELSET=ALL, REFNODE=100, ROTNODE=101")
    run = run_deck("rigid_noblanks", deck).ok()
    u, _ = node_values(run)
    assert abs(u[1][0] - (0.004 + 0.002 * REF[1])) < 1e-15


# ------------------------------------------------ *RIGID BODY inside *PART

CAE_PUNCH = """*Heading
rigid punch part (as Abaqus/CAE writes it), two instances
*Part, name=Base
*Node
1, 0., 0.
2, 1., 0.
3, 2., 0.
4, 0., 1.
5, 1., 1.
6, 2., 1.
*Element, type=CPE4
1, 1, 2, 5, 4
2, 2, 3, 6, 5
*Elset, elset=All
1, 2
*Nset, nset=Bottom
1, 2, 3
*Solid Section, elset=All, material=Steel
1.
*End Part
*Part, name=Punch
*Node
1, 0., 0.
2, 0.5, 0.
3, 0.5, 0.5
4, 0., 0.5
*Element, type=CPE4
1, 1, 2, 3, 4
*Node
9, 0.25, 0.8
*Nset, nset=_PickedSet4, internal
9,
*Elset, elset=_PickedSet5, internal
1,
*Solid Section, elset=_PickedSet5, material=Steel
1.
*Rigid Body, ref node=_PickedSet4, elset=_PickedSet5
*End Part
*Assembly, name=Assembly
*Instance, name=Base-1, part=Base
*End Instance
*Instance, name=Punch-1, part=Punch
0.2, 1.5, 0.
*End Instance
*Instance, name=Punch-2, part=Punch
1.2, 1.5, 0.
1.2, 1.5, 0., 1.2, 1.5, 1., 30.
*End Instance
*Nset, nset=RP1, instance=Punch-1
9,
*Nset, nset=RP2, instance=Punch-2
9,
*End Assembly
*Material, name=Steel
*Elastic
1000., 0.3
*Boundary
Base-1.Bottom, 1, 2
*Step
*Static
*Boundary
RP1, 1, 1, 0.01
RP1, 2, 2, -0.02
RP1, 6, 6, 0.003
RP2, 1, 2, 0.
RP2, 6, 6, -0.004
*Node print
U
*End Step
"""


def test_rigid_body_inside_a_part_is_instanced():
    """Abaqus/CAE writes a rigid part's *RIGID BODY inside *PART, naming the
    part's reference point and element set: each instance gets its own
    rigid body (the sets and the reference node of that instance), placed
    with it. Punch-1 (translated) and Punch-2 (translated and turned by 30
    degrees) follow their own reference nodes, moved and turned by their
    dof 6, by the small-rotation formula about the placed reference point
    (to 1e-15); the listing names both bodies."""
    run = run_deck("rigid_in_part", CAE_PUNCH).ok()
    rows = run.listing.increments[-1].block("NODE U", set="ALL").rows
    u = {r[3]: np.array(r[1:3], dtype=float) for r in rows}
    part = {1: (0.0, 0.0), 2: (0.5, 0.0), 3: (0.5, 0.5), 4: (0.0, 0.5), 9: (0.25, 0.8)}
    c, s = math.cos(math.radians(30.0)), math.sin(math.radians(30.0))
    for inst, place, uref, theta in (("PUNCH-1", lambda x, y: (x + 0.2, y + 1.5), (0.01, -0.02), 0.003),
                                     ("PUNCH-2", lambda x, y: (1.2 + c * x - s * y, 1.5 + s * x + c * y),
                                      (0.0, 0.0), -0.004)):
        xr = place(*part[9])
        for label, xy in part.items():
            x = place(*xy)
            exact = np.array([uref[0] - theta * (x[1] - xr[1]), uref[1] + theta * (x[0] - xr[0])])
            assert np.abs(u[f"{inst}.{label}"] - exact).max() < 1e-15, (inst, label, u[f"{inst}.{label}"], exact)
    rb = header_block(run, "RIGID BODIES")
    assert rb["name"] == ["PUNCH-1._PICKEDSET5", "PUNCH-2._PICKEDSET5"], rb.rows
    assert rb["ref_node"] == ["PUNCH-1.9", "PUNCH-2.9"], rb.rows
    assert all(abs(v) < 1e-15 for r in rows if str(r[3]).startswith("BASE") for v in r[1:3])


def test_rigid_body_inside_a_part_naming_an_unknown_set_stops_at_its_line():
    """A part's *RIGID BODY is read for each instance; a set the part does
    not define stops the run at the card's line in the part."""
    deck = CAE_PUNCH.replace("*Rigid Body, ref node=_PickedSet4, elset=_PickedSet5",
                             "*Rigid Body, ref node=_PickedSet4, elset=NOSUCH")
    run = run_deck("rigid_in_part_bad", deck)
    line = deck.split("\n").index("*Rigid Body, ref node=_PickedSet4, elset=NOSUCH") + 1
    assert run.rc != 0 and f"rigid_in_part_bad.inp:{line}: error: undefined element set" in run.stderr, run.stderr
