"""scripts/calculix_suite.py on a small folder laid out as CalculiX's test/
(decks, .dat.ref and .frd.ref files written here): it picks the decks with
2D elements, sorts them into ran / rejected / crashed and compares
displacements, stresses and contact pressures with the references; its
readers of CalculiX's files (.dat displacements, stresses and contact
pressures; ASCII .frd displacements, nodes and elements; the deck's mesh)
and the mappings of CalculiX's expanded 3D output back to the 2D model
(expanded nodes to 2D nodes, 3D integration points to 2D ones, 3D faces
to 2D faces), all on synthetic files written here."""
import os
import stat

from helpers import WORK, workdir
from test_decks_calculix import E, NU, P, PLAIN_NODES, block

SIGMA = P / (1.0 * 2.0)          # load over height times thickness


def dat_ref(scale=1.0):
    """A CalculiX .dat with the closed-form plane-strain displacements of
    the block (nodes 1-6), printed as CalculiX prints them."""
    xs = {1: (0, 0), 2: (1, 0), 3: (2, 0), 4: (0, 1), 5: (1, 1), 6: (2, 1)}
    eps_x = SIGMA * (1 - NU ** 2) / E
    eps_y = -SIGMA * NU * (1 + NU) / E
    lines = ["", "                        S T E P       1", "", "",
             " displacements (vx,vy,vz) for set NALL and time  0.1000000E+01", ""]
    for n, (x, y) in xs.items():
        lines.append(f"{n:10d} {scale * eps_x * x:13.6E} {scale * eps_y * y:13.6E}  0.000000E+00")
    return "\n".join(lines) + "\n"


def write(folder, name, text):
    with open(os.path.join(folder, name), "w") as f:
        f.write(text)


def suite_rows(folder, cfe2d=None):
    import calculix_suite
    args = [folder, "--quiet", "--out", os.path.join(WORK, "suite_out"), "--markdown", os.path.join(folder, "table.md")]
    if cfe2d:
        args += ["--cfe2d", cfe2d]
    return {r["deck"]: r for r in calculix_suite.main(args)}


def test_suite_sorts_and_compares():
    d = workdir("suite_tests")
    strain = block(nodes=PLAIN_NODES, elements="*ELEMENT, TYPE=CPE4, ELSET=BLOCK\n1, 1, 2, 5, 4\n2, 2, 3, 6, 5\n")
    write(d, "agree.inp", strain)
    write(d, "agree.dat.ref", dat_ref())
    write(d, "differ.inp", strain)
    write(d, "differ.dat.ref", dat_ref(1.01))
    write(d, "stress.inp", block())
    write(d, "stress.dat.ref", dat_ref())
    write(d, "quadratic.inp", block().replace("*ELEMENT, TYPE=CPS4", "*ELEMENT, TYPE=CPS9"))
    # elements in an included file still make a 2D deck
    write(d, "mesh.msh", "*ELEMENT, TYPE=CPS4, ELSET=BLOCK\n1, 1, 2, 5, 4\n2, 2, 3, 6, 5\n")
    write(d, "included.inp", block(elements="*INCLUDE, INPUT=mesh.msh\n").replace("*HEADING", "*DYNAMIC\n*HEADING"))
    write(d, "solid.inp", "*NODE\n1, 0, 0, 0\n*ELEMENT, TYPE=C3D8\n1, 1, 1, 1, 1, 1, 1, 1, 1\n")
    rows = suite_rows(d)
    assert sorted(rows) == ["agree", "differ", "included", "quadratic", "stress"], sorted(rows)
    assert rows["agree"]["status"] == "ran" and "(agrees)" in rows["agree"]["detail"], rows["agree"]
    assert rows["differ"]["status"] == "ran" and "(DIFFERS)" in rows["differ"]["detail"], rows["differ"]
    assert "not judged" in rows["stress"]["detail"] and rows["stress"]["state"] == "plane stress"
    assert rows["quadratic"]["status"] == "rejected" and "quadratic.inp:" in rows["quadratic"]["detail"]
    assert "element type CPS9" in rows["quadratic"]["detail"]
    assert rows["included"]["status"] == "rejected" and "*DYNAMIC" in rows["included"]["detail"]
    table = open(os.path.join(d, "table.md")).read()
    assert table.startswith("5 decks with 2D elements") and "2 rejected, 0 crashed" in table, table[:200]


def test_suite_reports_a_crash():
    """A cfe2d that dies of a signal is 'crashed', not 'rejected'."""
    d = workdir("suite_crash")
    write(d, "one.inp", block())
    fake = os.path.join(d, "fake_cfe2d")
    write(d, "fake_cfe2d", "#!/bin/sh\necho 'x.inp:1: error: before dying' >&2\nkill -SEGV $$\n")
    os.chmod(fake, os.stat(fake).st_mode | stat.S_IXUSR)
    rows = suite_rows(d, cfe2d=fake)
    assert rows["one"]["status"] == "crashed", rows["one"]


# --- CalculiX result files (.frd.ref) -------------------------------------

def frd_text(datasets, width=10, coords=None):
    """An ASCII .frd laid out as CalculiX writes one: a node block (the
    coordinates, records that are not displacements), then for each
    (step, increment, time, {node: (d1, d2, d3)}) a 1PSTEP record, a 100CL
    header and a DISP block, followed by a STRESS block to be skipped.
    width: 10 (long format, flag 1) or 5 (short, flag 0)."""
    flag = 1 if width == 10 else 0
    coords = coords or {}
    lines = ["    1Csynthetic", f"    2C{len(coords):30d}{'':37}{flag}"]
    lines += [f" -1{n:{width}d}" + "".join(f"{c:12.5E}" for c in xyz) for n, xyz in coords.items()]
    lines.append(" -3")
    for k, (step, inc, time, u) in enumerate(datasets):
        for name, ncomp in (("DISP", 3), ("STRESS", 6)):
            count = 2 * k + (name == "STRESS") + 1
            lines.append(f"    1PSTEP{'':14}{count:12d}{inc:12d}{step:12d}")
            lines.append(f"  100CL{100 + count:5d}{time:12.5E}{len(u):12d}{'':20}{0:2d}{count:5d}{'':11}{flag}")
            lines.append(f" -4  {name:8s}{ncomp + 1:4d}    1")
            lines += [f" -5  C{j}          1    2{j:5d}    0" for j in range(1, ncomp + 1)]
            for n, v in u.items():
                vals = v if name == "DISP" else (9.0, -9.0, 9.0, -9.0, 9.0, -9.0)
                lines.append(f" -1{n:{width}d}" + "".join(f"{x:12.5E}" for x in vals))
            lines.append(" -3")
    return "\n".join(lines + [" 9999"]) + "\n"


def block_u(scale=1.0):
    """The closed-form plane-strain displacements of the block's nodes 1-6
    under the load P (scaled), with u_z = 0."""
    xs = {1: (0, 0), 2: (1, 0), 3: (2, 0), 4: (0, 1), 5: (1, 1), 6: (2, 1)}
    eps_x = SIGMA * (1 - NU ** 2) / E
    eps_y = -SIGMA * NU * (1 + NU) / E
    return {n: (scale * eps_x * x, scale * eps_y * y, 0.0) for n, (x, y) in xs.items()}


def test_frd_reader_records():
    """Steps, increments and total times from the 1PSTEP and 100CL records;
    values that touch (a minus sign for a separator) split at their
    columns; node coordinates and STRESS blocks are not displacements;
    the short format's 5-digit node numbers; blank step fields read as 0."""
    import calculix_suite
    d = workdir("frd_reader")
    u1 = {7: (1.5e-3, -2.25e-4, 0.0), 123456: (-4.0e-2, -1.0e-5, 3.0)}
    u2 = {7: (-3.0e-3, 4.5e-4, 0.0)}
    path = os.path.join(d, "a.frd")
    write(d, "a.frd", frd_text([(1, 1, 1.0, u1), (2, 3, 1.5, u2), (2, 6, 2.0, u1)],
                               coords={7: (1.0, 2.0, 3.0)}))
    text = open(path).read()
    assert "-2.25000E-04-" not in text and "-4.00000E-02-1.00000E-05" in text   # values touch
    got = calculix_suite.read_frd_displacements(path)
    assert [(g["step"], g["increment"], g["time"]) for g in got] == [(1, 1, 1.0), (2, 3, 1.5), (2, 6, 2.0)], got
    assert got[0]["u"] == u1 and got[1]["u"] == u2 and got[2]["u"] == u1, got
    by_time = calculix_suite.frd_by_time(got)
    assert by_time[1.5] == {7: (-3.0e-3, 4.5e-4)} and set(by_time) == {1.0, 1.5, 2.0}
    write(d, "short.frd", frd_text([(1, 1, 1.0, {12: (-1.0, -2.0, -3.0)})], width=5))
    assert calculix_suite.read_frd_displacements(os.path.join(d, "short.frd"))[0]["u"] == {12: (-1.0, -2.0, -3.0)}
    # a 1PSTEP record with only its counter (as fluid results have it)
    write(d, "blank.frd", frd_text([(1, 1, 1.0, u2)]).replace(f"{1:12d}{1:12d}\n", "\n", 1))
    got = calculix_suite.read_frd_displacements(os.path.join(d, "blank.frd"))
    assert (got[0]["step"], got[0]["increment"], got[0]["u"]) == (0, 0, u2), got


def test_frd_reader_refuses_what_it_cannot_read():
    """A binary file and a record with a broken number are ValueErrors
    naming the file (and the line)."""
    import calculix_suite
    d = workdir("frd_reader_bad")
    with open(os.path.join(d, "bin.frd"), "wb") as f:
        f.write(b"    1C\n -1\0\0\0\x07\n")
    good = frd_text([(1, 1, 1.0, {7: (1.0, 2.0, 3.0)})])
    write(d, "broken.frd", good.replace(" 1.00000E+00 2.00000E+00", " 1.00000E+00 2.0000xE+00"))
    for name, msg in (("bin.frd", "binary"), ("broken.frd", "broken.frd:")):
        try:
            calculix_suite.read_frd_displacements(os.path.join(d, name))
        except ValueError as e:
            assert msg in str(e), (name, e)
        else:
            raise AssertionError(f"{name} was read")
    line = [k for k, t in enumerate(good.splitlines(), 1) if t.startswith(" -1         7 1.0")][0]
    try:
        calculix_suite.read_frd_displacements(os.path.join(d, "broken.frd"))
    except ValueError as e:
        assert f"broken.frd:{line}:" in str(e), (line, e)


def two_step_block(kind="CPE4"):
    """The block with *NODE FILE output (all nodes to <job>.msh, none to the
    listing) and a second step doubling the load."""
    deck = block(nodes=PLAIN_NODES, elements=f"*ELEMENT, TYPE={kind}, ELSET=BLOCK\n1, 1, 2, 5, 4\n2, 2, 3, 6, 5\n")
    deck = deck.replace("*NODE PRINT, NSET=RIGHT\nU\n", "*NODE FILE\nU\n")
    return deck + f"*STEP\n*STATIC\n*CLOAD\nRIGHT, 1, {P}\n*NODE FILE\nU\n*END STEP\n"


def test_suite_compares_frd_references():
    """Decks with only a .frd.ref are compared against it at the times both
    hold, over the deck's own nodes: the two steps' ends agree (a time
    cfe2d does not have, with wrong values, is left out); a step-2 value
    off by 1 % DIFFERS; a file holding only expanded nodes (numbered after
    the deck's) is named and not compared; plane stress is not judged; a
    deck with both references reports both, each by its file."""
    d = workdir("suite_frd")
    good = [(1, 1, 1.0, block_u()), (2, 1, 1.5, block_u(7.0)), (2, 2, 2.0, block_u(2.0))]
    cases = {
        "agree": (two_step_block(), good),
        "differ": (two_step_block(), good[:2] + [(2, 2, 2.0, block_u(2.02))]),
        "expanded": (two_step_block(), [(1, 1, 1.0, {n + 6: v for n, v in block_u().items()})]),
        "stress": (two_step_block("CPS4"), good),
    }
    for name, (deck, sets) in cases.items():
        write(d, name + ".inp", deck)
        write(d, name + ".frd.ref", frd_text(sets))
    write(d, "both.inp", two_step_block())
    write(d, "both.frd.ref", frd_text(good))
    write(d, "both.dat.ref", dat_ref())
    rows = suite_rows(d)
    detail = {k: r["detail"] for k, r in rows.items()}
    assert all(r["status"] == "ran" for r in rows.values()), rows
    assert detail["agree"].startswith(".frd.ref: ") and "(agrees)" in detail["agree"], detail
    assert "over 12 node values" in detail["agree"], detail["agree"]      # 6 nodes at t = 1 and 2
    assert "(DIFFERS)" in detail["differ"] and "9.90e-03" in detail["differ"], detail     # 0.02 / 2.02
    assert "only the expanded 3D nodes" in detail["expanded"] and "largest" not in detail["expanded"], detail
    assert "not judged" in detail["stress"], detail
    parts = detail["both"].split("; ")
    assert len(parts) == 2 and parts[0].startswith(".dat.ref: ") and parts[1].startswith(".frd.ref: "), parts
    assert all("(agrees)" in p for p in parts), parts


# --- CalculiX's expanded 3D output mapped back ---------------------------

def write_frd_mesh(path, coords, elements, width=10):
    """Prepend a node block (2C) of coords {node: (x, y, z)} and an element
    block (3C) of elements {element: [nodes]} (ten numbers a -2 record, as
    CalculiX writes them) to the .frd at path."""
    flag = 1 if width == 10 else 0
    lines = [f"    2C{len(coords):30d}{'':37}{flag}"]
    lines += [f" -1{n:{width}d}" + "".join(f"{c:12.5E}" for c in xyz) for n, xyz in coords.items()]
    lines += [" -3", f"    3C{len(elements):30d}{'':37}{flag}"]
    for e, conn in elements.items():
        lines.append(f" -1{e:{width}d}{4 if len(conn) == 20 else 1:5d}    0    1")
        lines += [" -2" + "".join(f"{n:{width}d}" for n in conn[k:k + 10]) for k in range(0, len(conn), 10)]
    lines.append(" -3")
    with open(path) as f:
        rest = f.read()
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n" + rest)


def test_frd_mesh_reader():
    """The node block's coordinates and the element block's node lists
    (over several -2 records), long and short format; a file without
    them gives empty dicts; a broken record names its line."""
    import calculix_results
    d = workdir("frd_mesh")
    coords = {10: (0.0, 0.0, -0.05), 11: (1.0, -2.5, 0.0), 123456: (0.5, 1.5, 5.0e-2)}
    conn = list(range(101, 121))
    for width in (10, 5):
        path = os.path.join(d, f"m{width}.frd")
        write(d, f"m{width}.frd", frd_text([(1, 1, 1.0, {10: (1.0, 2.0, 3.0)})], width=width))
        short = {n: c for n, c in coords.items() if width == 10 or n < 99999}
        write_frd_mesh(path, short, {1: conn, 7: [10, 11, 10, 11, 10, 11, 10, 11]}, width)
        xyz, elements = calculix_results.read_frd_mesh(path)
        assert xyz == short, (width, xyz)
        assert elements == {1: conn, 7: [10, 11, 10, 11, 10, 11, 10, 11]}, (width, elements)
        # the displacements are still read past the mesh blocks
        assert calculix_results.read_frd_displacements(path)[0]["u"] == {10: (1.0, 2.0, 3.0)}
    write(d, "bare.frd", frd_text([(1, 1, 1.0, {10: (1.0, 2.0, 3.0)})]))
    assert calculix_results.read_frd_mesh(os.path.join(d, "bare.frd")) == ({}, {})
    path = os.path.join(d, "m10.frd")
    text = open(path).read().replace("       111       112", "       111       1x2")
    write(d, "bad.frd", text)
    line = [k for k, t in enumerate(text.splitlines(), 1) if "1x2" in t][0]
    try:
        calculix_results.read_frd_mesh(os.path.join(d, "bad.frd"))
    except ValueError as e:
        assert f"bad.frd:{line}:" in str(e), (line, e)
    else:
        raise AssertionError("a broken element record was read")


def test_deck_mesh_reader():
    """Nodes and elements of a deck and its includes: blank coordinates
    are 0, a Fortran 'd' exponent reads; an element's nodes go on over the
    next line up to its type's count (CPE8) or after a trailing comma (a
    type without a count); *NODE PRINT data are not nodes."""
    import calculix_results
    d = workdir("deck_mesh")
    write(d, "mesh.inp", "*NODE, NSET=MORE\n7, 1.5d0, -2.\n")
    write(d, "m.inp", "*NODE, NSET=ALL\n1\n2, 1.0, , 0.\n3, 2.5e-1, 4.\n*INCLUDE, INPUT=mesh.inp\n"
                      "*ELEMENT, TYPE=CPE8, ELSET=E\n1, 1, 2, 3, 7,\n 2, 3, 7, 1\n2, 3, 2, 1, 7, 2, 3, 7, 1\n"
                      "*ELEMENT, TYPE=SPRINGA, ELSET=S\n5, 1,\n2\n6, 3, 7\n"
                      "*STEP\n*NODE PRINT, NSET=ALL\nU\n99, 1, 1\n*END STEP\n")
    nodes, elements = calculix_results.read_deck_mesh(os.path.join(d, "m.inp"))
    assert nodes == {1: (0.0, 0.0), 2: (1.0, 0.0), 3: (0.25, 4.0), 7: (1.5, -2.0)}, nodes
    assert elements == {1: ("CPE8", [1, 2, 3, 7, 2, 3, 7, 1]), 2: ("CPE8", [3, 2, 1, 7, 2, 3, 7, 1]),
                        5: ("SPRINGA", [1, 2]), 6: ("SPRINGA", [3, 7])}, elements


def expanded_model(copy_elements=True):
    """A 2D model as cfe2d holds it, two quads 1 (nodes 1 2 5 4) and 2
    (2 3 6 5) cut between them by a pre-tension (copies 8, 9 of nodes 2, 5
    in element 1; reference node 7 on node 1, in no element), a truss 3
    from node 5 to node 10 above it; and CalculiX's expansion of it: three
    layers (z = -0.1, 0, 0.1) of nodes at each quad node, numbered 20 +
    3 k, with displacements u(n) + (0.3, -0.2) z (they average out), and
    at each truss end four corners of a square around the node (offset
    0.02 across the truss and in z). Returns (xy, elements2d, frd_xyz,
    frd_elements, u2d, u3d)."""
    xy = {1: (0.0, 0.0), 2: (1.0, 0.0), 3: (2.0, 0.0), 4: (0.0, 1.0), 5: (1.0, 1.0), 6: (2.0, 1.0), 7: (0.0, 0.0),
          8: (1.0, 0.0), 9: (1.0, 1.0), 10: (1.0, 2.0)}
    elements = {1: [1, 8, 9, 4], 2: [2, 3, 6, 5], 3: [5, 10]}
    u2d = {n: (1e-3 * n, -2e-3 * n + 1e-4 * x) for n, (x, _) in xy.items()}
    frd_xyz, frd_el, u3d, layer = {}, {}, {}, {}
    q = 20
    for n in (1, 2, 3, 4, 5, 6, 8, 9):
        layer[n] = []
        for z in (-0.1, 0.0, 0.1):
            frd_xyz[q] = (*xy[n], z)
            u3d[q] = (u2d[n][0] + 0.3 * z, u2d[n][1] - 0.2 * z, 0.0)
            layer[n].append(q)
            q += 1
    for e in (1, 2):
        conn = elements[e]
        frd_el[e] = [layer[n][0] for n in conn] + [layer[n][2] for n in conn]
    corners = {}
    for n in (5, 10):
        corners[n] = []
        for dx, dz in ((-0.02, -0.02), (0.02, -0.02), (0.02, 0.02), (-0.02, 0.02)):
            frd_xyz[q] = (xy[n][0] + dx, xy[n][1], dz)
            u3d[q] = (u2d[n][0] + 5 * dx, u2d[n][1] + 7 * dz, 0.0)
            corners[n].append(q)
            q += 1
    frd_el[3] = corners[5] + corners[10]
    if not copy_elements:
        frd_el = {}
    return xy, elements, frd_xyz, frd_el, u2d, u3d


def test_expanded_nodes_map_back():
    """Each 2D node gets the expanded nodes at its (x, y): three layers of
    a quad node, plus a truss end's four corners; their mean is the 2D
    displacement. The pre-tension copies (same place as the node they
    copy) are split by their elements; the reference node, in no
    element, takes none (node 1 at the same place keeps its own)."""
    import calculix_results
    xy, elements, frd_xyz, frd_el, u2d, u3d = expanded_model()
    groups, coincident, off = calculix_results.map_expanded_nodes(frd_xyz, frd_el, xy, elements)
    assert coincident == [] and off == [], (coincident, off)
    assert sorted(groups) == [1, 2, 3, 4, 5, 6, 8, 9, 10], sorted(groups)
    # the copies' middle layer (39 at node 8, 24 at node 2) is in no element: left out
    assert groups[1] == [20, 21, 22] and groups[8] == [38, 40] and groups[2] == [23, 25], groups
    assert len(groups[5]) == 6 and len(groups[10]) == 4, groups      # 2 layers + 4 corners; 4 corners
    got = calculix_results.expanded_displacements([{"time": 1.0, "u": u3d}], groups)[1.0]
    for n, (u1, u2) in got.items():
        assert abs(u1 - u2d[n][0]) < 1e-15 and abs(u2 - u2d[n][1]) < 1e-15, (n, got[n], u2d[n])
    # without the element block the copies cannot be told from their originals
    xy, elements, frd_xyz, frd_el, u2d, u3d = expanded_model(copy_elements=False)
    groups, coincident, off = calculix_results.map_expanded_nodes(frd_xyz, frd_el, xy, elements)
    assert coincident == [2, 5, 8, 9] and sorted(groups) == [1, 3, 4, 6, 10], (coincident, sorted(groups))
    # expanded nodes that do not centre on their node (one truss corner lost)
    xy, elements, frd_xyz, frd_el, u2d, u3d = expanded_model()
    del frd_xyz[max(frd_xyz)]
    groups, coincident, off = calculix_results.map_expanded_nodes(frd_xyz, frd_el, xy, elements)
    assert off == [10] and 10 not in groups and 5 in groups, (off, sorted(groups))


def expanded_block(scale=1.0, first=7):
    """The plane-strain block's closed-form displacements at CalculiX's
    expansion of it: three layers (z = -1, 0, 1; the thickness is 2) at
    each node, numbered first + 3 (n - 1) + layer, the outer layers off by
    +-1e-3 in x (their mean is the node's); and the expanded elements."""
    u = block_u(scale)
    xs = {1: (0, 0), 2: (1, 0), 3: (2, 0), 4: (0, 1), 5: (1, 1), 6: (2, 1)}
    coords, u3 = {}, {}
    for n, (x, y) in xs.items():
        for k, z in enumerate((-1.0, 0.0, 1.0)):
            q = first + 3 * (n - 1) + k
            coords[q] = (float(x), float(y), z)
            u3[q] = (u[n][0] + 1e-3 * z, u[n][1], 0.0)
    outer = {n: (first + 3 * (n - 1), first + 2 + 3 * (n - 1)) for n in xs}
    elements = {e: [outer[n][0] for n in conn] + [outer[n][1] for n in conn]
                for e, conn in ((1, (1, 2, 5, 4)), (2, (2, 3, 6, 5)))}
    return coords, elements, u3


def test_suite_compares_expanded_frd():
    """A .frd.ref of expanded nodes only (OUTPUT=3D) is mapped back to the
    deck's nodes by their coordinates and compared: the closed form
    agrees, also when the expanded nodes carry the deck's numbers (at
    other places); 1 % off DIFFERS; without a node block it is not
    compared; an axisymmetric model's (a wedge) is not mapped."""
    d = workdir("suite_expanded")
    coords, elements, _ = expanded_block()
    for name, scale in (("agree", 1.0), ("differ", 1.01)):
        write(d, name + ".inp", two_step_block())
        write(d, name + ".frd.ref", frd_text([(1, 1, 1.0, expanded_block(scale)[2])]))
        write_frd_mesh(os.path.join(d, name + ".frd.ref"), coords, elements)
    # numbered from 1: the numbers are cfe2d's too, the places are not
    write(d, "collide.inp", two_step_block())
    coords1, elements1, u1 = expanded_block(first=1)
    write(d, "collide.frd.ref", frd_text([(1, 1, 1.0, u1)]))
    write_frd_mesh(os.path.join(d, "collide.frd.ref"), coords1, elements1)
    write(d, "bare.inp", two_step_block())
    write(d, "bare.frd.ref", frd_text([(1, 1, 1.0, expanded_block()[2])]))
    write(d, "axi.inp", two_step_block("CAX4"))
    write(d, "axi.frd.ref", frd_text([(1, 1, 1.0, expanded_block()[2])]))
    write_frd_mesh(os.path.join(d, "axi.frd.ref"), coords, elements)
    detail = {k: r["detail"] for k, r in suite_rows(d).items()}
    assert "expanded 3D nodes" in detail["agree"] and "each of 6 of cfe2d's nodes" in detail["agree"], detail
    assert "(agrees)" in detail["agree"] and "over 6 node values" in detail["agree"], detail["agree"]
    assert "(DIFFERS)" in detail["differ"] and "9.90e-03" in detail["differ"], detail["differ"]
    assert "expanded 3D nodes" in detail["collide"] and "(agrees)" in detail["collide"], detail["collide"]
    assert "not compared" in detail["bare"] and "largest" not in detail["bare"], detail["bare"]
    assert "axisymmetric" in detail["axi"] and "not mapped back" in detail["axi"], detail["axi"]


# --- stresses at integration points -----------------------------------------

def dat_stress_text(points, time=1.0, extra=""):
    """A .dat with *EL PRINT stresses {element: {point: 6 values}} laid out
    as CalculiX prints them, after a strain block (to be skipped)."""
    lines = ["", "                        S T E P       1", "", "",
             f" strains (elem, integ.pnt.,exx,eyy,ezz,exy,exz,eyz) for set EALL and time  {time:.7E}", ""]
    lines += [f"{e:10d}{k:4d}" + "".join(f" {9.0:13.6E}" for _ in range(6)) for e in points for k in points[e]]
    lines += ["", f" stresses (elem, integ.pnt.,sxx,syy,szz,sxy,sxz,syz) for set EALL and time  {time:.7E}", ""]
    lines += [f"{e:10d}{k:4d}" + "".join(f" {v:13.6E}" for v in vals) for e in points for k, vals in points[e].items()]
    return "\n".join(lines) + "\n" + extra


def test_dat_stress_reader_and_layers():
    """Stresses per element and point (the strain block is not read); the
    layer mapping: 27 points are 3 layers of 9 (the middle one), 8 are 2
    of 4 (the mean of both), as many as the 2D element's map one to one,
    and counts that do not divide are refused."""
    import calculix_results
    d = workdir("dat_stress")
    pts = {3: {1: (1.0, -2.0, 3.0, -4.0, 5.0, -6.0), 2: (-1.5e2, 0.0, 0.0, 1e-9, 0.0, 0.0)}, 14: {1: (7.0,) * 6}}
    write(d, "s.dat", dat_stress_text(pts, 2.5))
    got = calculix_results.read_dat_stresses(os.path.join(d, "s.dat"))
    assert got == {2.5: pts}, got
    assert calculix_results.read_dat_displacements(os.path.join(d, "s.dat")) == {}
    layers = calculix_results.stress_layers
    assert layers(27, 9) == [[10 + k] for k in range(9)], layers(27, 9)
    assert layers(8, 4) == [[1, 5], [2, 6], [3, 7], [4, 8]] and layers(4, 4) == [[1], [2], [3], [4]]
    assert layers(18, 3) == [[7, 10], [8, 11], [9, 12]] and layers(9, 4) is None and layers(4, 0) is None


def layered(values, layers, out_of_plane=50.0):
    """CalculiX's points of an expanded element whose middle (odd layer
    count) or middle two layers' mean is `values` (2D points in order, 4
    values each: S11 S22 S33 S12): the outer layers are off by +-
    out_of_plane in every component, with shears of opposite sign."""
    n2 = len(values)
    out = {}
    for m in range(layers):
        z = m - (layers - 1) / 2
        for k, (s11, s22, s33, s12) in enumerate(values, 1):
            dev = out_of_plane * z
            out[m * n2 + k] = (s11 + dev, s22 - dev, s33 + dev, s12 + dev, dev, -dev)
    return out


def test_compare_stresses_maps_points():
    """cfe2d's 2D points against CalculiX's 3D ones: the middle layer of 3
    and the mean of 2 layers agree exactly; S33 counts but in plane stress;
    taking the wrong layer, or points out of order, shows; an element whose
    point counts do not divide is counted, not compared."""
    import calculix_suite
    four = [(10.0 + k, -5.0 * k, 2.0 - k, 0.5 * k) for k in range(4)]
    nine = [(100.0 - k, 3.0 * k, 1.0, -k) for k in range(9)]
    ours = {1.0: {1: {k: v for k, v in enumerate(four, 1)}, 2: {k: v for k, v in enumerate(nine, 1)}}}
    ref = {1.0: {1: layered(four, 2), 2: layered(nine, 3)}}
    rel, count, unmapped, kinds = calculix_suite.compare_stresses(ours, ref, "plane strain")
    assert rel < 1e-15 and count == 13 and unmapped == 0 and kinds == [(8, 4), (27, 9)], (rel, count, unmapped, kinds)
    # points out of order in the 2D element
    swapped = {1.0: {1: {1: four[1], 2: four[0], 3: four[2], 4: four[3]}, 2: ours[1.0][2]}}
    rel, *_ = calculix_suite.compare_stresses(swapped, ref, "plane strain")
    assert abs(rel - 0.05) < 1e-12, rel          # S22 of points 1, 2 (0 vs -5) over the largest, 100
    # S33 off by 10: counted in plane strain, not in plane stress
    off33 = {1.0: {1: {k: (a, b, c + 10.0, s) for k, (a, b, c, s) in enumerate(four, 1)}}}
    ref1 = {1.0: {1: layered(four, 2)}}
    assert abs(calculix_suite.compare_stresses(off33, ref1, "plane strain")[0] - 10.0 / 15.0) < 1e-12
    assert calculix_suite.compare_stresses(off33, ref1, "plane stress")[0] < 1e-15
    # 9 CalculiX points for a 4-point element do not map
    rel, count, unmapped, _ = calculix_suite.compare_stresses(
        {1.0: {1: ours[1.0][1]}}, {1.0: {1: layered(nine, 1)}}, "plane strain")
    assert rel is None and count == 0 and unmapped == 1


def test_suite_compares_stresses():
    """*EL PRINT stresses of a .dat.ref against cfe2d's listing: the
    plane-strain block's uniform closed-form stress at CalculiX's 8 points
    of each expanded CPE4 (2 layers of 4) agrees; 1 % more DIFFERS; the
    displacements the same file holds are compared as well."""
    d = workdir("suite_stress")
    strain = block(nodes=PLAIN_NODES, elements="*ELEMENT, TYPE=CPE4, ELSET=BLOCK\n1, 1, 2, 5, 4\n2, 2, 3, 6, 5\n")
    strain = strain.replace("*END STEP", "*EL PRINT, ELSET=BLOCK\nS\n*END STEP")
    for name, scale in (("agree", 1.0), ("differ", 1.01)):
        s = scale * SIGMA
        pts = {e: {k: (s, 0.0, NU * s, 0.0, 0.0, 0.0) for k in range(1, 9)} for e in (1, 2)}
        write(d, name + ".inp", strain)
        write(d, name + ".dat.ref", dat_ref() + dat_stress_text(pts))
    detail = {k: r["detail"] for k, r in suite_rows(d).items()}
    for name, verdict in (("agree", "(agrees)"), ("differ", "(DIFFERS)")):
        parts = detail[name].split("stresses S11, S22, S33, S12")
        assert len(parts) == 2 and "displacements: " in parts[0] and "(agrees)" in parts[0], detail[name]
        assert "8 -> 4" in parts[1] and "over 8 integration points" in parts[1] and verdict in parts[1], parts[1]
    assert "9.90e-03 of the largest stress" in detail["differ"], detail["differ"]


# --- contact pressures --------------------------------------------------------

def test_contact_reader_and_faces():
    """The *CONTACT PRINT stress block: element, face, pressure per point;
    faces of 2D elements as node chains (corners, with the midside node of
    quadratic ones); the face nearest a point, relative to its length."""
    import calculix_results
    d = workdir("dat_contact")
    lines = ["", " relative contact displacement (slave element+face,normal,tang1,tang2) for all contact elements and "
             "time  0.1000000E+01", "", "        10          4 -5.000000E-06  0.000000E+00  0.000000E+00", "",
             " contact stress (slave element+face,press,tang1,tang2) for all contact elements and time  "
             "0.1000000E+01", "",
             "        10          4  5.000000E+00  0.000000E+00  0.000000E+00",
             "      1964          5  1.250000E+02  0.000000E+00  0.000000E+00", ""]
    write(d, "c.dat", "\n".join(lines))
    got = calculix_results.read_dat_contact_stresses(os.path.join(d, "c.dat"))
    assert got == {1.0: [(10, 4, 5.0), (1964, 5, 125.0)]}, got
    chain = calculix_results.deck_face_polyline
    assert chain("CPE8", [1, 2, 3, 4, 5, 6, 7, 8], 2) == [2, 6, 3]
    assert chain("CAX4", [1, 2, 3, 4], 4) == [4, 1] and chain("CPS3", [1, 2, 3], 3) == [3, 1]
    assert chain("CPE6", [1, 2, 3, 4, 5, 6], 1) == [1, 4, 2] and chain("CPE4", [1, 2, 3, 4], 5) is None
    faces = {"a": [(0, 0), (1, 0)], "b": [(1, 0), (1, 0.5), (1, 2)]}
    key, rel = calculix_results.nearest_face((0.5, 0.01), faces)
    assert key == "a" and abs(rel - 0.01) < 1e-12, (key, rel)
    key, rel = calculix_results.nearest_face((1.1, 1.5), faces)
    assert key == "b" and abs(rel - 0.05) < 1e-12, (key, rel)


def contact_listing(points, total):
    """A cfe2d listing with one increment and one contact pair on slave
    surface TOP: slave points (x, y, pressure) at area 1 each, and the
    pair's total force."""
    rows = "".join(f"0 {x} {y} -1e-5 CLOSED {p} 1.0 {p}\n" for x, y, p in points)
    return ("cfe2d\n=== INCREMENT step=1 increment=1 time=1.0 total_time=1.0 iterations=1 ===\n"
            "--- CONTACT SLAVE pair=1 surface=TOP\nnode x y gap state force area pressure\n" + rows +
            "--- CONTACT MASTER pair=1 surface=BOTTOM\nnode x y force area pressure\n"
            "--- CONTACT SUMMARY pair=1\nclosed total_force resultant_x resultant_y max_penetration\n"
            f"{len(points)} {total} 0 {total} 1e-5\n=== END INCREMENT\n")


def test_contact_pressures_per_face():
    """cfe2d's slave points go to CalculiX's slave faces (the expanded
    element's face 3 is the 2D face S1) and the mean pressures per face are
    reported: 10 % off on one face, 2 % on the other; a face CalculiX lists
    no pressure for leaves its cfe2d points stray, a face not in the mesh
    is counted. When the listed points carry half the pair's force (the
    second pass of two-pass contact is not listed) the comparison is also
    given scaled to the pair's total."""
    import calculix_suite
    d = workdir("contact_faces")
    write(d, "two.inp", "*NODE\n1, 0, 0\n2, 1, 0\n3, 2, 0\n4, 0, 1\n5, 1, 1\n6, 2, 1\n7, 3, 0\n8, 3, 1\n"
                        "*ELEMENT, TYPE=CPE4, ELSET=E\n1, 1, 2, 5, 4\n2, 2, 3, 6, 5\n3, 3, 7, 8, 6\n")
    ref = {1.0: [(1, 3, 10.0), (1, 3, 10.0), (1, 3, 10.0), (2, 3, 19.0), (2, 3, 21.0), (9, 3, 1.0)]}
    points = [(0.25, 0.0, 11.0), (0.75, 0.0, 11.0), (1.5, 0.0, 20.4), (2.5, 0.0, 3.0)]
    for name, share in (("one", 1.0), ("half", 0.5)):
        write(d, name + ".out", contact_listing([(x, y, share * p) for x, y, p in points], 45.4))
        text = calculix_suite.contact_text(os.path.join(d, name + ".out"), ref, os.path.join(d, "two.inp"))
        assert "TOP: 2 faces (5 CalculiX points, 3 cfe2d points), difference " in text, text
        assert "1 cfe2d points on faces CalculiX prints no pressure for" in text, text
        assert "1 CalculiX faces not found in the deck's mesh" in text and "reported, not judged" in text, text
        rows = open(os.path.join(d, name + "_contact_vs_ccx.csv")).read().splitlines()
        assert len(rows) == 3 and rows[1].startswith(f"1.000000e+00,1,S1,TOP,3,1.000000e+01,2,{11 * share:.6e}"), rows
        assert rows[2].endswith(f",{share:.6f}"), rows
        same = "difference 2 % to 10 % (largest at element 1 face S1: cfe2d 11, CalculiX 10)"
        if share == 1.0:
            assert "difference 2 % to 10 % of CalculiX's mean (largest at element 1 face S1: cfe2d 11, " \
                   "CalculiX 10)" in text and "scaled" not in text, text
        else:
            assert "difference 45 % to 49 % of CalculiX's mean (largest at element 2 face S1: cfe2d 10.2, " \
                   "CalculiX 20)" in text, text
            assert "carry 0.500 of the pair's total force" in text and "scaled by 1/0.500, " + same in text, text


HEAT_DECK = """*HEADING
a slab 0 <= x <= 2 held at 100 on x = 0 and 20 on x = 2: T linear in x
*NODE, NSET=NALL
1, 0., 0.
2, 1., 0.
3, 2., 0.
4, 0., 1.
5, 1., 1.
6, 2., 1.
*ELEMENT, TYPE=DC2D4, ELSET=EALL
1, 1, 2, 5, 4
2, 2, 3, 6, 5
*MATERIAL, NAME=M
*CONDUCTIVITY
50.
*SOLID SECTION, ELSET=EALL, MATERIAL=M
1.
*STEP
*HEAT TRANSFER, STEADY STATE
*BOUNDARY
1, 11, 11, 100.
4, 11, 11, 100.
3, 11, 11, 20.
6, 11, 11, 20.
*NODE PRINT, NSET=NALL
NT
*END STEP
"""


def heat_dat_ref(offset=0.0):
    """CalculiX's temperature block of the slab: T = 100 - 40 x (+ offset)."""
    xs = {1: 0, 2: 1, 3: 2, 4: 0, 5: 1, 6: 2}
    lines = ["", "                        S T E P       1", "", "",
             " temperatures for set NALL and time  0.1000000E+01", ""]
    for n, x in xs.items():
        lines.append(f"{n:10d} {100.0 - 40.0 * x + offset:13.6E}")
    return "\n".join(lines) + "\n"


def test_suite_compares_temperatures_and_names_fluid_networks():
    """Temperatures (*NODE PRINT NT) against the .dat.ref's, over the
    reference's range (80 here): the exact one agrees, one 0.8 off at a
    node (1 % of the range) differs; a fluid network element (CalculiX's
    type D) is rejected at its *ELEMENT line naming the networks."""
    d = workdir("suite_heat")
    write(d, "slab.inp", HEAT_DECK)
    write(d, "slab.dat.ref", heat_dat_ref())
    write(d, "slabwrong.inp", HEAT_DECK)
    write(d, "slabwrong.dat.ref", heat_dat_ref().replace(f"{60.0:13.6E}", f"{60.8:13.6E}"))
    write(d, "network.inp", HEAT_DECK.replace("*ELEMENT, TYPE=DC2D4, ELSET=EALL",
                                              "*ELEMENT, TYPE=D, ELSET=EW\n7, 1, 2, 3\n*ELEMENT, TYPE=DC2D4, ELSET=EALL"))
    rows = suite_rows(d)
    assert rows["slab"]["status"] == "ran" and "temperatures: largest difference" in rows["slab"]["detail"]
    assert "(agrees)" in rows["slab"]["detail"], rows["slab"]
    assert "1.00e-02 of the largest temperature range over 6" in rows["slabwrong"]["detail"], rows["slabwrong"]
    assert "(DIFFERS)" in rows["slabwrong"]["detail"], rows["slabwrong"]
    assert rows["network"]["status"] == "rejected" and "network.inp:" in rows["network"]["detail"]
    assert "fluid network" in rows["network"]["detail"], rows["network"]
