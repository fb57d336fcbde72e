"""scripts/calculix_suite.py on a small folder laid out as CalculiX's test/
(decks and .dat.ref files): it picks the decks with 2D elements, sorts
them into ran / rejected / crashed and compares displacements with the
reference where the state makes that meaningful."""
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
