"""*TIE and *PRE-TENSION SECTION through whole runs: ties of meshes of
different density pass the patch test (uniform stress exact), a
cantilever cut and tied equals the uncut one, a pre-tension section in a
bar and in a tube gives the stress of its prescribed opening or force
exactly, and CalculiX's pret5 and pret2 answers are reproduced."""
import os

from gmsh_results import read_msh
from helpers import run_deck

E = 1000.0


def block_q(nx, ny, x0, x1, y0, y1, first, quadratic, bottom_shift=0.0):
    """A structured block of CPS4 or CPS8 elements with node ids from
    `first`: nodes {id: (x, y)}, element node lists, and the node ids by
    grid position (i, j) on the doubled grid of an 8-node mesh."""
    k = 2 if quadratic else 1
    nodes, ids = {}, {}
    nid = first
    for j in range(k * ny + 1):
        for i in range(k * nx + 1):
            if quadratic and i % 2 and j % 2:
                continue
            y = y0 + (y1 - y0) * j / (k * ny)
            if j == 0:
                y += bottom_shift
            nodes[nid] = (x0 + (x1 - x0) * i / (k * nx), y)
            ids[i, j] = nid
            nid += 1
    elems = []
    for j in range(ny):
        for i in range(nx):
            a, b = k * i, k * j
            conn = [ids[a, b], ids[a + k, b], ids[a + k, b + k], ids[a, b + k]]
            if quadratic:
                conn += [ids[a + 1, b], ids[a + 2, b + 1], ids[a + 1, b + 2], ids[a, b + 1]]
            elems.append(conn)
    return nodes, elems, ids


def lines(nodes, elems, first_elem):
    n = "".join(f"{i}, {x:.17g}, {y:.17g}\n" for i, (x, y) in nodes.items())
    e = "".join(f"{first_elem + k}, " + ", ".join(map(str, c)) + "\n" for k, c in enumerate(elems))
    return n, e


def stresses(run, elset="ALL"):
    b = run.listing.increments[-1].block("ELEMENT S", set=elset)
    return b["S11"], b["S22"], b["S12"]


def tie_patch_deck(quadratic, nup, shift, load):
    """Lower block [0,2]x[0,1] (2 x 2 elements, its top face the master),
    upper [0,2]x[1,2] (nup x 2, its bottom face the slave) with its bottom
    row `shift` above y = 1 (ADJUST moves it down), rollers on the bottom
    and the left edges (the slave node there keeps its held dof 1
    untied), `load`: *DSLOAD lines on TOP and RIGHT."""
    et = "CPS8" if quadratic else "CPS4"
    k = 2 if quadratic else 1
    lo, le, lids = block_q(2, 2, 0.0, 2.0, 0.0, 1.0, 1, quadratic)
    up, ue, uids = block_q(nup, 2, 0.0, 2.0, 1.0, 2.0, 1001, quadratic, bottom_shift=shift)
    ln, lel = lines(lo, le, 1)
    un, uel = lines(up, ue, 101)
    bottom = [lids[i, 0] for i in range(2 * k + 1)]
    left = [lids[0, j] for j in range(2 * k + 1)] + [uids[0, j] for j in range(2 * k + 1)]
    up_right = [100 + nup, 100 + 2 * nup]
    return f"""*NODE
{ln}{un}*ELEMENT, TYPE={et}, ELSET=LOWER
{lel}*ELEMENT, TYPE={et}, ELSET=UPPER
{uel}*ELSET, ELSET=ALL
LOWER, UPPER
*SURFACE, NAME=LOWER_TOP
3, S3
4, S3
*SURFACE, NAME=UPPER_BOTTOM
""" + "".join(f"{101 + i}, S1\n" for i in range(nup)) + "*SURFACE, NAME=TOP\n" + \
        "".join(f"{101 + nup + i}, S3\n" for i in range(nup)) + f"""*SURFACE, NAME=RIGHT
2, S2
4, S2
{up_right[0]}, S2
{up_right[1]}, S2
*MATERIAL, NAME=M
*ELASTIC
{E}, 0.3
*SOLID SECTION, ELSET=ALL, MATERIAL=M
0.5
*TIE, NAME=GLUE
UPPER_BOTTOM, LOWER_TOP
*BOUNDARY
""" + "".join(f"{n}, 2, 2\n" for n in bottom) + "".join(f"{n}, 1, 1\n" for n in left) + f"""*STEP
*STATIC
*DSLOAD
{load}*EL PRINT, ELSET=ALL
S
*END STEP
"""


def patch_error(name, deck, s11, s22):
    run = run_deck(name, deck).ok()
    a, b, c = stresses(run)
    return run, max(abs(a - s11).max(), abs(b - s22).max(), abs(c).max()) / max(s11, s22)


def test_tie_patch_test_uniform_stress_exact():
    """A finer slave face whose nodes include every master node (4 slave
    faces on 2 master faces, 4- and 8-node, 1e-4 off the master and moved
    onto it), pulled by 3 along y across the interface and 2 along x: every
    integration point has S11 = 2, S22 = 3, S12 = 0 within 1e-10. With 3
    slave faces on 2 (master nodes between slave nodes) the uniform state
    is exact while no traction crosses the interface (pulled along x only);
    a traction across it is not carried uniformly by node-to-face ties
    (the slave nodes' forces, spread by the shape functions, are not the
    master's consistent nodal forces): the error is measured, not hidden."""
    both = "TOP, P, -3.\nRIGHT, P, -2.\n"
    for quadratic in (False, True):
        tag = "q8" if quadratic else "q4"
        run, err = patch_error(f"tie_patch_{tag}_nested", tie_patch_deck(quadratic, 4, 1e-4, both), 2.0, 3.0)
        assert err < 1e-10, (tag, err)
        tie = run.listing.header[[b.name for b in run.listing.header].index("TIES")]
        assert tie["tied_nodes"][0] == (9 if quadratic else 5) and tie["untied_nodes"][0] == 0, tie.rows
        _, err = patch_error(f"tie_patch_{tag}_along", tie_patch_deck(quadratic, 3, 1e-4, "RIGHT, P, -2.\n"), 2.0, 0.0)
        assert err < 1e-10, (tag, err)
        _, err = patch_error(f"tie_patch_{tag}_across", tie_patch_deck(quadratic, 3, 0.0, both), 2.0, 3.0)
        assert 1e-3 < err < 0.5, (tag, err)


def cantilever(left_ny, right_ny, cut):
    """A cantilever [0,10]x[0,1] of CPS8, clamped at x = 0, a tip load of
    -1 spread over the right end; uncut (20 x 4), or cut at x = 5 into two
    blocks (10 x left_ny, 10 x right_ny) tied (the right block's face is
    the slave)."""
    if not cut:
        n, e, ids = block_q(20, 4, 0.0, 10.0, 0.0, 1.0, 1, True)
        nl, el = lines(n, e, 1)
        left = [ids[0, j] for j in range(9)]
        tip = [ids[40, j] for j in range(9)]
        elements, tie, surfaces = f"*ELEMENT, TYPE=CPS8, ELSET=ALL\n{el}", "", ""
        nodes = nl
    else:
        n1, e1, i1 = block_q(10, left_ny, 0.0, 5.0, 0.0, 1.0, 1, True)
        n2, e2, i2 = block_q(10, right_ny, 5.0, 10.0, 0.0, 1.0, 10001, True)
        a, b = lines(n1, e1, 1)
        c, d = lines(n2, e2, 1001)
        nodes = a + c
        elements = f"*ELEMENT, TYPE=CPS8, ELSET=LEFT\n{b}*ELEMENT, TYPE=CPS8, ELSET=RIGHT\n{d}" \
                   "*ELSET, ELSET=ALL\nLEFT, RIGHT\n"
        surfaces = "*SURFACE, NAME=CUT_L\n" + "".join(f"{10 * (j + 1)}, S2\n" for j in range(left_ny)) + \
                   "*SURFACE, NAME=CUT_R\n" + "".join(f"{1001 + 10 * j}, S4\n" for j in range(right_ny))
        tie = "*TIE, NAME=CUT\nCUT_R, CUT_L\n"
        left = [i1[0, j] for j in range(2 * left_ny + 1)]
        tip = [i2[20, j] for j in range(2 * right_ny + 1)]
    return f"""*NODE
{nodes}{elements}*NSET, NSET=TIP
{", ".join(map(str, tip))}
{surfaces}*MATERIAL, NAME=M
*ELASTIC
{E}, 0.3
*SOLID SECTION, ELSET=ALL, MATERIAL=M
1.
{tie}*BOUNDARY
""" + "".join(f"{i}, 1, 2\n" for i in left) + f"""*STEP
*STATIC
*CLOAD
TIP, 2, {-1.0 / len(tip):.17g}
*NODE PRINT, NSET=TIP
U
*END STEP
"""


def tip_deflection(run):
    return run.listing.increments[-1].block("NODE U", set="TIP")["U2"].mean()


def test_tie_cantilever_cut_and_tied_as_uncut():
    """Cut at mid-length with the same mesh on both sides and tied, the
    cantilever deflects as the uncut one (1e-10); with 3 elements over
    the depth on the tied right half instead of 4, within 1e-3."""
    ref = tip_deflection(run_deck("tie_cantilever_uncut", cantilever(4, 4, False)).ok())
    same = tip_deflection(run_deck("tie_cantilever_matching", cantilever(4, 4, True)).ok())
    assert abs(same - ref) < 1e-10 * abs(ref), (same, ref)
    coarse = tip_deflection(run_deck("tie_cantilever_nonmatching", cantilever(4, 3, True)).ok())
    assert abs(coarse - ref) < 1e-3 * abs(ref), (coarse, ref)
    assert abs(coarse - ref) > 1e-12 * abs(ref)   # a different mesh: not the same answer by accident


def bar(load, extra_model="", extra_step=""):
    """Plane stress bar [0,4]x[0,1], 4 CPS4, thickness 2, nu = 0, ends held
    along x, cut at x = 2 (face S2 of element 2), reference node 100."""
    return f"""*NODE, NSET=DECK
1, 0., 0.
2, 1., 0.
3, 2., 0.
4, 3., 0.
5, 4., 0.
6, 0., 1.
7, 1., 1.
8, 2., 1.
9, 3., 1.
10, 4., 1.
100, 0., 0.
*ELEMENT, TYPE=CPS4, ELSET=ALL
1, 1, 2, 7, 6
2, 2, 3, 8, 7
3, 3, 4, 9, 8
4, 4, 5, 10, 9
*NSET, NSET=REF
100
*MATERIAL, NAME=M
*ELASTIC
{E}, 0.
{extra_model}*SOLID SECTION, ELSET=ALL, MATERIAL=M
2.
*SURFACE, NAME=CUT
2, S2
*PRE-TENSION SECTION, SURFACE=CUT, NODE=REF
*BOUNDARY
1, 1, 2
6, 1, 1
5, 1, 1
10, 1, 1
*STEP
*STATIC
{load}{extra_step}*NODE PRINT, NSET=REF
U, RF
*EL PRINT, ELSET=ALL
S
*END STEP
"""


def test_pretension_bar_opening_and_force():
    """Prescribed opening d = 0.01 of the cut: each half stretches by d/2,
    S11 = E d / 4 = 2.5 in every element and the reference node's
    reaction is S11 times the area (2); a force 10 on the reference node
    instead: S11 = 10 / 2 and the opening 4 S11 / E."""
    run = run_deck("pret_bar_opening", bar("*BOUNDARY\nREF, 1, 1, 0.01\n")).ok()
    s11, s22, s12 = stresses(run)
    assert abs(s11 - 2.5).max() < 1e-10 * 2.5 and abs(s22).max() < 1e-10 and abs(s12).max() < 1e-10
    inc = run.listing.increments[-1]
    assert abs(inc.block("NODE RF", set="REF")["RF1"][0] - 5.0) < 1e-9
    run = run_deck("pret_bar_force", bar("*CLOAD\nREF, 1, 10.\n")).ok()
    s11, _, _ = stresses(run)
    assert abs(s11 - 5.0).max() < 1e-10 * 5.0
    u = run.listing.increments[-1].block("NODE U", set="REF")
    assert abs(u["U1"][0] - 4 * 5.0 / E) < 1e-12 and u["U2"][0] == 0.0
    nodes = run.listing.header[[b.name for b in run.listing.header].index("PRE-TENSION SECTIONS")]
    assert nodes["cut_nodes"][0] == 2 and nodes["first_new_node"][0] == 101 and nodes["last_new_node"][0] == 102


def test_pretension_copies_take_the_temperatures():
    """The cut closed (opening 0) in a bar held at both ends and heated by
    50: S11 = -E alpha dT in every element, the owner of the cut (on the
    copies) included."""
    deck = bar("*BOUNDARY\nREF, 1, 1, 0.\n", extra_model="*EXPANSION\n1e-4\n",
               extra_step="*TEMPERATURE\nDECK, 50.\n")
    run = run_deck("pret_bar_thermal", deck).ok()
    s11, _, _ = stresses(run)
    assert abs(s11 + E * 1e-4 * 50.0).max() < 1e-10 * 5.0, s11


def test_pretension_axisymmetric_tube_force():
    """A tube r in [1, 2], z in [0, 4] (2 x 4 CAX4, nu = 0, ends held
    along z), cut at z = 2 with the normal computed: a force 300 on the
    reference node (the whole ring) gives S22 = 300 / (pi (2^2 - 1^2))."""
    import math
    nodes, elems, ids = block_q(2, 4, 1.0, 2.0, 0.0, 4.0, 1, False)
    nl, el = lines(nodes, elems, 1)
    ends = [ids[i, j] for i in range(3) for j in (0, 4)]
    deck = f"""*NODE
{nl}500, 0., 0.
*ELEMENT, TYPE=CAX4, ELSET=ALL
{el}*MATERIAL, NAME=M
*ELASTIC
{E}, 0.
*SOLID SECTION, ELSET=ALL, MATERIAL=M
*SURFACE, NAME=CUT
3, S3
4, S3
*PRE-TENSION SECTION, SURFACE=CUT, NODE=500
*BOUNDARY
""" + "".join(f"{n}, 2, 2\n" for n in ends) + """*STEP
*STATIC
*CLOAD
500, 1, 300.
*EL PRINT, ELSET=ALL
S
*END STEP
"""
    run = run_deck("pret_tube", deck).ok()
    s11, s22, s12 = stresses(run)
    expected = 300.0 / (math.pi * 3.0)
    assert abs(s22 - expected).max() < 1e-10 * expected, s22
    assert abs(s11).max() < 1e-10 * expected and abs(s12).max() < 1e-10 * expected


def two_square_cut_deck():
    """The model of CalculiX's pret5 test, written out here: two unit
    squares (CPE4, E 210000, nu 0.3, thickness 0.1) side by side, the four
    outer corners clamped, the shared face x = 1 cut by a pre-tension
    section along +x whose reference node 7 takes a force of -10."""
    nodes = {1: (0, 0), 2: (1, 0), 3: (2, 0), 4: (0, 1), 5: (1, 1), 6: (2, 1), 7: (0, 0)}
    node_text = "".join(f"{n}, {x:.1f}, {y:.1f}\n" for n, (x, y) in nodes.items())
    clamp = "".join(f"{n}, 1, 2\n" for n in (1, 3, 4, 6))
    return ("*NODE\n" + node_text
            + "*ELEMENT, TYPE=CPE4, ELSET=SQUARES\n1, 1, 2, 5, 4\n2, 2, 3, 6, 5\n"
            + "*BOUNDARY\n" + clamp
            + "*MATERIAL, NAME=STEEL\n*ELASTIC\n210000., 0.3\n"
            + "*SOLID SECTION, ELSET=SQUARES, MATERIAL=STEEL\n0.1\n"
            + "*SURFACE, NAME=CUT\n1, S2\n"
            + "*PRE-TENSION SECTION, SURFACE=CUT, NODE=7\n1., 0., 0.\n"
            + "*STEP\n*STATIC\n*CLOAD\n7, 1, -10.\n"
            + "*NODE PRINT\nU\n*NODE FILE, FORMAT=VTU\nU\n*NODE FILE\nU\n*END STEP\n")


PRET5 = two_square_cut_deck()


def test_pretension_calculix_pret5():
    """CalculiX's pret5 (two CPE4, a pre-tension force of -10): its
    displacements (pret5.frd.ref, six digits) at the originals 2, 5 and
    the copies 8, 9 it numbers after the largest id; the VTU and gmsh files
    have the nine nodes, element 1 on the copies."""
    run = run_deck("pret_calculix_pret5", PRET5).ok()
    u = run.listing.increments[-1].block("NODE U")
    got = {int(n): (a, b) for n, a, b in zip(u["node"], u["U1"], u["U2"])}
    ref = {2: (4.05933e-4, -1.21780e-4), 5: (4.05933e-4, 1.21780e-4),
           8: (-4.05933e-4, -1.21780e-4), 9: (-4.05933e-4, 1.21780e-4)}
    for n, (a, b) in ref.items():
        assert abs(got[n][0] - a) < 2e-6 * 4.06e-4 and abs(got[n][1] - b) < 2e-6 * 4.06e-4, (n, got[n])
    vtu = [f for f in os.listdir(os.path.dirname(run.listing_path)) if f.endswith(".vtu")]
    text = open(os.path.join(os.path.dirname(run.listing_path), vtu[0]), "rb").read()
    assert b'NumberOfPoints="9"' in text, text[:500]
    msh = read_msh(run.listing_path[:-4] + ".msh")
    assert sorted(msh.node_ids) == list(range(1, 10)) and [1, 8, 9, 4] in [list(c) for c in msh.elements]
    _, um = msh.node_view("Displacement", 0)
    assert abs(um[list(msh.node_ids).index(8), 0] + 4.05933e-4) < 2e-6 * 4.06e-4


def test_later_step_boundary_on_a_tied_dof_names_the_tie():
    """A *BOUNDARY in a second step on a dof the *TIE made dependent (the
    tie is made after reading, so the deck's lines are gone): the run stops
    after step 1 with a message naming the *TIE, not an anonymous
    constraint number, and step 1's results are on disk."""
    deck = tie_patch_deck(False, 4, 0.0, "TOP, P, -3.\n")
    deck += "*STEP\n*STATIC\n*BOUNDARY\n1002, 2, 2, 0.\n*END STEP\n"
    run = run_deck("tie_later_boundary", deck)
    assert run.rc == 1, run.stderr
    assert "dof 2 of node 1002 is both prescribed and the dependent dof" in run.stderr, run.stderr
    assert "(the constraint made by *TIE GLUE)" in run.stderr, run.stderr
    assert len(run.listing.increments) >= 1


def test_pretension_cut_through_triangles_fanning_from_a_node():
    """A cut along y = 1 through a strip of CPS3 (nu = 0) held at both ends,
    opened by 0.01 through the reference node: element 1 touches the cut
    only at node 4, below it; it takes node 4's copy like the face's owner,
    so every element carries S22 = E * 0.01 / 2 = 5 (before, element 1 kept
    the original node and bridged the cut: S22 from -1.07 to 6.07)."""
    deck = """*NODE
1, 0., 0.
2, 1., 0.
3, 0., 1.
4, 1., 1.
5, 0., 2.
6, 1., 2.
100, 0., 0.
*ELEMENT, TYPE=CPS3, ELSET=STRIP
1, 1, 2, 4
2, 1, 4, 3
3, 3, 4, 6
4, 3, 6, 5
*MATERIAL, NAME=M
*ELASTIC
1000., 0.
*SOLID SECTION, ELSET=STRIP, MATERIAL=M
1.
*SURFACE, NAME=CUT
2, S2
*PRE-TENSION SECTION, SURFACE=CUT, NODE=100
*BOUNDARY
1, 1, 2
2, 2
5, 1, 2
6, 2
*STEP
*STATIC
*BOUNDARY
100, 1, 1, 0.01
*EL PRINT, ELSET=STRIP
S
*END STEP
"""
    s = run_deck("pret_triangle_fan", deck).ok().listing.increments[-1].block("ELEMENT S", set="STRIP")
    assert max(abs(v - 5.0) for v in s["S22"]) < 1e-10, s["S22"]


def test_tie_onto_a_pretension_cut_patch_test():
    """The nested tie patch whose master face (the lower block's top) is
    also cut by a pre-tension section, its reference node held (opening
    0): each slave dof depends on master copies that depend on the
    originals, a chain of constraints longer than the first capacity of
    the term lists (it once read the dofs of the chain from freed memory:
    SIGSEGV). Uniform stress S11 = 2, S22 = 3, S12 = 0 within 1e-10."""
    deck = tie_patch_deck(False, 4, 1e-4, "TOP, P, -3.\nRIGHT, P, -2.\n")
    deck = deck.replace("*NODE\n", "*NODE\n5000, 0., 0.\n", 1).replace(
        "*BOUNDARY\n", "*PRE-TENSION SECTION, SURFACE=LOWER_TOP, NODE=5000\n*BOUNDARY\n5000, 1, 2\n", 1)
    run, err = patch_error("tie_on_pretension_cut", deck, 2.0, 3.0)
    assert err < 1e-10, err
    pret = run.listing.header[[b.name for b in run.listing.header].index("PRE-TENSION SECTIONS")]
    assert pret["cut_nodes"][0] == 3, pret.rows


def test_tie_across_a_contact_pair_warns():
    """A *TIE between the two surfaces of a *CONTACT PAIR glues them: the
    run goes on (the uniform stress of the tie patch is still exact) and
    says that the pair's contact carries nothing."""
    deck = tie_patch_deck(False, 4, 0.0, "TOP, P, -3.\nRIGHT, P, -2.\n").replace(
        "*TIE, NAME=GLUE", "*CONTACT PAIR\nUPPER_BOTTOM, LOWER_TOP\n*TIE, NAME=GLUE")
    run, err = patch_error("tie_across_contact", deck, 2.0, 3.0)
    assert err < 1e-10, err
    assert "*TIE GLUE ties the two surfaces of a *CONTACT PAIR" in run.stderr, run.stderr
