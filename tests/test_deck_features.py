"""Keyword-deck features against answers known in closed form: nested
*INCLUDE with relative paths, GENERATE, set names inside lists, trailing
commas, comments and mixed case, faces S1..S4 of quads and triangles,
named boundary conditions, amplitudes in step and total time, OP=NEW,
loads carried over between steps, reactions per set."""
import os
import re

import numpy as np

from helpers import rel_err, run_deck

E, NU = 1000.0, 0.25

# A 2 x 1 block of two quads, nodes 1-3 at y = 0, 4-6 at y = 1.
MESH = """** nodes with tabs, a trailing comma and mixed case
*Node, nset=allN
1,\t0.0,\t0.0
2, 1.0, 0.0,
3, 2.0, 0.0
4, 0.0, 1.0
5, 1.0, 1.0
6, 2.0, 1.0
*INCLUDE, INPUT=sub/elements.inp
"""
ELEMENTS = """*element, type=cps4, elset=QUADS
1, 1, 2, 5, 4
2, 2, 3, 6, 5
*INCLUDE, INPUT=../sets.inp
"""
SETS = """*NSET, NSET=LEFT, GENERATE
1, 4, 3
*NSET, NSET=RIGHTBOT
3
*NSET, NSET=RIGHT
RIGHTBOT, 6,
*ELSET, ELSET=ALLE, GENERATE
1, 2
"""


def block_deck(step_text, extra=""):
    return f"""*HEADING
features
*INCLUDE, INPUT=mesh.inp
*MATERIAL, NAME=m1
*ELASTIC
{E}, {NU}
*SOLID SECTION, ELSET=alle, MATERIAL=M1
2.0
{extra}*BOUNDARY
LEFT, XSYMM
1, YSYMM
{step_text}"""


FILES = {"mesh.inp": MESH, "sub/elements.inp": ELEMENTS, "sets.inp": SETS}


def run_block(name, step_text, extra="", files=None, mesh_include="mesh.inp", newline="\n"):
    """The block deck with its nested include tree; files replaces or adds
    include files, mesh_include is the file the deck includes first, and
    newline the line end written."""
    from helpers import workdir
    d = workdir("feat_" + name)
    tree = dict(FILES, **(files or {}))
    for fn, text in tree.items():
        os.makedirs(os.path.dirname(os.path.join(d, fn)), exist_ok=True)
        with open(os.path.join(d, fn), "w", newline=newline) as f:
            f.write(text)
    path = os.path.join(d, name + ".inp")
    with open(path, "w", newline=newline) as f:
        f.write(block_deck(step_text, extra).replace("INPUT=mesh.inp", "INPUT=" + mesh_include))
    return run_deck("feat_" + name + "_out", path=path)


def tension_u(force_total):
    """Uniaxial tension of the 2 x 1 x 2 (thickness) block: end displacement."""
    return force_total / (2.0 * 1.0) / E * 2.0


def test_nested_include_generate_sets_and_named_bcs():
    step = """*STEP
*STATIC
*CLOAD
RIGHT, 1, 3.0
*NODE PRINT, NSET=RIGHT
U
*END STEP
"""
    run = run_block("tension", step).ok()
    inc = run.listing.increments[-1]
    u = inc.block("NODE U", set="RIGHT")["U1"]
    assert np.allclose(u, tension_u(6.0), rtol=1e-10), u
    rf = inc.block("REACTIONS").as_dict()
    assert abs(rf["LEFT"][0] + 6.0) < 1e-9, rf


def test_amplitudes_step_and_total_time_and_op_new():
    """Step 1: load with a step-time amplitude (0 -> 1 -> 0.5 over the step);
    step 2: the same load value with a total-time amplitude; step 3: OP=NEW
    removes the loads."""
    step = """*AMPLITUDE, NAME=UPDOWN
0., 0., 0.5, 1., 1., 0.5
*AMPLITUDE, NAME=TOT, TIME=TOTAL TIME
0., 0., 2., 2.
*STEP
*STATIC
0.5, 1.0
*CLOAD, AMPLITUDE=UPDOWN
RIGHT, 1, 3.0
*NODE PRINT, NSET=RIGHT
U
*END STEP
*STEP
*STATIC
1.0, 1.0
*CLOAD, AMPLITUDE=TOT
RIGHT, 1, 3.0
*NODE PRINT, NSET=RIGHT
U
*END STEP
*STEP
*STATIC
*CLOAD, OP=NEW
*NODE PRINT, NSET=RIGHT
U
*END STEP
"""
    step = step.replace("*CLOAD, OP=NEW\n", "*CLOAD, OP=NEW\nRIGHT, 2, 0.0\n")
    run = run_block("amplitudes", step).ok()
    u = [i.block("NODE U", set="RIGHT")["U1"][0] for i in run.listing.increments]
    expect = [tension_u(6.0), tension_u(3.0), tension_u(6.0 * 2.0), 0.0]
    assert len(u) == 4
    for got, want in zip(u, expect):
        assert abs(got - want) < 1e-10 * tension_u(6.0), (u, expect)


def test_amplitude_table_at_and_between_its_points():
    """A 9-point table with unequal intervals, read at 20 increments of a
    step: at its points, between them, before the first and after the
    last (constant there). Each value against the table's linear
    interpolation in Python; the lookup is a bisection (a cyclic
    history's table grows with its cycles), which must pick the same
    interval as a scan."""
    tab = [(0.1, 0.0), (0.15, 1.0), (0.3, -0.5), (0.35, 0.25), (0.5, 2.0),
           (0.55, 2.0), (0.6, -1.0), (0.8, 0.5), (0.9, 1.5)]
    text = ", ".join(f"{t}, {a}" for t, a in tab[:4]) + "\n" + \
        ", ".join(f"{t}, {a}" for t, a in tab[4:8]) + "\n" + f"{tab[8][0]}, {tab[8][1]}"
    step = f"""*AMPLITUDE, NAME=ZIG
{text}
*STEP
*STATIC
0.05, 1.0
*CLOAD, AMPLITUDE=ZIG
RIGHT, 1, 3.0
*NODE PRINT, NSET=RIGHT
U
*END STEP
"""
    run = run_block("amplitude_table", step).ok()
    u = [i.block("NODE U", set="RIGHT")["U1"][0] for i in run.listing.increments]
    ts, amps = [t for t, _ in tab], [a for _, a in tab]
    times = [0.05 * (k + 1) for k in range(20)]
    expect = [tension_u(6.0 * float(np.interp(t, ts, amps))) for t in times]
    assert len(u) == 20, len(u)
    for t, got, want in zip(times, u, expect):
        assert abs(got - want) < 1e-10 * tension_u(6.0), (t, got, want)


def test_faces_of_quads_and_triangles():
    """Each face Sk of a quad and of a triangle, used as a contact master
    surface, has the outward normal of its edge: a node 0.1 outside each
    face is coupled with gap 0.1."""
    deck = """*NODE
1, 0, 0
2, 1, 0
3, 1, 1
4, 0, 1
11, 3, 0
12, 4, 0
13, 3, 1
21, 0.5, -0.1
22, 1.1, 0.5
23, 0.5, 1.1
24, -0.1, 0.5
31, 3.5, -0.1
32, 3.6, 0.5
33, 2.9, 0.5
*ELEMENT, TYPE=CPS4, ELSET=Q
1, 1, 2, 3, 4
*ELEMENT, TYPE=CPS3, ELSET=T
2, 11, 12, 13
*NSET, NSET=PROBES
21, 22, 23, 24, 31, 32, 33
*SURFACE, NAME=FACES
1, S1
1, S2
1, S3
1, S4
2, S1
2, S2
2, S3
*MATERIAL, NAME=M
*ELASTIC
1000., 0.3
*SOLID SECTION, ELSET=Q, MATERIAL=M
*SOLID SECTION, ELSET=T, MATERIAL=M
*CONTACT PAIR, PENALTY=1.0, NODAL
PROBES, FACES
*BOUNDARY
1, 1, 2
2, 2, 2
11, 1, 2
12, 2, 2
PROBES, 1, 2
*STEP
*STATIC
*END STEP
"""
    run = run_deck("feat_faces", deck).ok()
    slave = run.listing.increments[-1].block("CONTACT SLAVE", pair=1)
    gaps = dict(zip(slave["node"], slave["gap"]))
    expect = {21: 0.1, 22: 0.1, 23: 0.1, 24: 0.1, 31: 0.1, 33: 0.1}
    # node 32 faces the hypotenuse (face S2, node 12 to node 13)
    a, b = np.array([4.0, 0.0]), np.array([3.0, 1.0])
    t = (b - a) / np.linalg.norm(b - a)
    n = np.array([t[1], -t[0]])
    expect[32] = float(np.dot(np.array([3.6, 0.5]) - a, n))
    for node, g in expect.items():
        assert abs(gaps[node] - g) < 1e-12, (node, gaps[node], g)


def test_reaction_sums_balance_loads():
    step = """*STEP
*STATIC
*CLOAD
6, 2, -1.5
3, 1, 2.0
*NODE PRINT, NSET=LEFT
RF
*END STEP
"""
    run = run_block("reactions", step, extra="*NSET, NSET=BOTTOMLEFT\n1\n").ok()
    inc = run.listing.increments[-1]
    rf = inc.block("NODE RF", set="LEFT")
    assert abs(sum(rf["RF1"]) + 2.0) < 1e-9
    assert rel_err(inc.block("REACTIONS").as_dict()["LEFT"][0], -2.0) < 1e-9


TENSION_STEP = """*STEP
*STATIC
*CLOAD
RIGHT, 1, 3.0
*NODE PRINT, NSET=RIGHT
U
*END STEP
"""


def tension_end_u(run):
    return run.listing.increments[-1].block("NODE U", set="RIGHT")["U1"]


def test_sixteen_include_levels():
    """The deepest nesting allowed: l1.inp ... l13.inp, then mesh.inp,
    sub/elements.inp and sets.inp at level 16 (17 levels fail:
    test_bad_decks)."""
    chain = {f"l{k}.inp": f"** level {k}\n*INCLUDE, INPUT=l{k + 1}.inp\n" for k in range(1, 13)}
    chain["l13.inp"] = "*INCLUDE, INPUT=mesh.inp\n"
    run = run_block("depth16", TENSION_STEP, files=chain, mesh_include="l1.inp").ok()
    assert np.allclose(tension_end_u(run), tension_u(6.0), rtol=1e-10)


def test_crlf_line_ends():
    """Every file written with CR-LF line ends (Windows) reads the same."""
    run = run_block("crlf", TENSION_STEP, newline="\r\n").ok()
    assert np.allclose(tension_end_u(run), tension_u(6.0), rtol=1e-10)


def test_longest_line():
    """A line of exactly 4096 characters is read whole: its last field,
    the y coordinate, ends at column 4096 (4097 fail: test_bad_decks)."""
    head, tail = "5, 1.0, ", "1.0"
    line = head + " " * (4096 - len(head) - len(tail)) + tail
    assert len(line) == 4096
    mesh = MESH.replace("5, 1.0, 1.0\n", line + "\n")
    assert line in mesh
    run = run_block("longline", TENSION_STEP, files={"mesh.inp": mesh}).ok()
    assert np.allclose(tension_end_u(run), tension_u(6.0), rtol=1e-10)


def test_limits_are_inclusive():
    """INC=100000, MAXIT=1000 and CUTBACKS=50 are the documented caps
    themselves: accepted."""
    step = TENSION_STEP.replace("*STEP\n", "*STEP, INC=100000\n")
    run = run_block("caps", step, extra="*CONTACT CONTROLS, MAXIT=1000, CUTBACKS=50\n").ok()
    assert np.allclose(tension_end_u(run), tension_u(6.0), rtol=1e-10)


def test_huge_finite_load_is_read():
    """1e160 is a finite real: the reader takes it (what the analysis makes
    of its overflow is not the reader's business). If the run completes,
    the answer is linear in the load."""
    run = run_block("hugeload", TENSION_STEP.replace("RIGHT, 1, 3.0", "RIGHT, 1, 1e160"))
    assert "not a finite number" not in run.stderr and ".inp:" not in run.stderr, run.stderr
    if run.rc == 0:
        # Fortran's ES edit descriptor drops the E of a three-digit
        # exponent (1.999999999999998+157), which the listing reader leaves
        # as text.
        u = [float(re.sub(r"(\d)([+-]\d{3})$", r"\1E\2", str(v))) for v in tension_end_u(run)]
        assert np.allclose(u, tension_u(2e160), rtol=1e-10), u
    else:
        assert run.stderr.startswith("cfe2d: error:"), run.stderr


def test_long_lists_are_read_in_linear_time():
    """60000 nodes in a set, a *BOUNDARY and two *CLOAD lines on that set
    (120000 entries each) and a 60000-point amplitude: read in about half
    a second. Appending one entry at a time by reallocation (quadratic)
    took 180 s for 80000 on the same machine; the bound leaves a wide
    margin for a loaded machine. The deck stops after reading (a step
    without *STATIC), so only the reader is timed."""
    import time
    n = 60000
    lines = ["*NODE, NSET=ALL"] + [f"{i}, {i * 0.1}, 0" for i in range(1, n + 1)]
    lines += ["*BOUNDARY", "ALL, 1, 2", "*AMPLITUDE, NAME=A"] + [f"{i}., {i * 0.5}" for i in range(n)]
    lines += ["*STEP", "*CLOAD", "ALL, 1, 1.", "ALL, 2, 1.", "*END STEP"]
    t0 = time.time()
    run = run_deck("feat_long_lists", "\n".join(lines) + "\n")
    elapsed = time.time() - t0
    assert run.rc == 1 and "step has no procedure" in run.stderr, run.stderr
    assert elapsed < 20.0, f"{elapsed:.1f} s to read {n} entries"
