"""scripts/calculix_suite.py on a small folder laid out as CalculiX's test/
(decks, .dat.ref and .frd.ref files written here): it picks the decks with
2D elements, sorts them into ran / rejected / crashed and compares
displacements with the references where the state makes that meaningful;
its reader of CalculiX's ASCII result files (.frd) on synthetic files."""
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
