"""CalculiX's print and status files: <job>.dat (the blocks of *NODE PRINT,
*EL PRINT and *CONTACT PRINT with CalculiX's captions and number format),
<job>.sta and <job>.cvg. The .dat of CalculiX's own 2D test decks is
compared with their .dat.ref as CalculiX's test suite compares them (same
number of lines, no NaN, every number within 1e-3 of the largest of its
block); a plate in uniform tension is checked against the closed form."""
import gzip
import os
import re
import shutil

from helpers import Skip, run_deck, workdir
from test_decks_contact import blocks
from test_frd import E, LY, NU, SIG, plate, read_frd

DEBIAN = "/usr/share/doc/calculix-ccx-test/examples/test"
# CalculiX's 2D decks whose printed answers cfe2d shares (the others differ
# by CalculiX's 3D expansion: shear stresses of the axisymmetric wedge, the
# out-of-plane stress of its plane-stress brick, of 1e-3 to 2e-2)
AGREEING = ("planestress", "planestress2", "planestrain", "planestrain2", "axiplane", "pret2")
ROW = re.compile(r"^([ \d]{9}\d([ \d]{3}\d)?| {6})( [ -]\d\.\d{6}E[+-]\d\d)+$")


def unpack(names, folder):
    """The decks and their .dat.ref from Debian's calculix-ccx-test."""
    for name in names:
        for ext in (".inp", ".dat.ref"):
            src = os.path.join(DEBIAN, name + ext)
            if os.path.exists(src + ".gz"):
                with gzip.open(src + ".gz", "rb") as f, open(os.path.join(folder, name + ext), "wb") as g:
                    shutil.copyfileobj(f, g)
            else:
                shutil.copy(src, os.path.join(folder, name + ext))


def datcheck(dat, ref):
    """CalculiX's comparison of a .dat with its .dat.ref: the same number of
    lines, no NaN, and each number of a data line within 1e-3 of the largest
    magnitude of its block (blocks end at blank lines; reference values
    below 1e-10 and caption lines are not compared). Returns the largest
    such error."""
    a = open(dat).read().split("\n")
    b = open(ref).read().split("\n")
    assert len(a) == len(b), f"{dat}: {len(a)} lines, the reference {len(b)}"
    assert "NaN" not in "".join(a)
    largest, k = {}, 0
    for line in b:
        if not line.strip():
            k += 1
            continue
        if "time" in line:
            continue
        for t in line.split():
            if "." in t:
                largest[k] = max(largest.get(k, 0.0), abs(float(t)))
    worst, k = 0.0, 0
    for la, lb in zip(a, b):
        if not lb.strip():
            assert not la.strip(), (la, lb)
            k += 1
            continue
        if "time" in lb:
            # the caption: the same words (CalculiX 2.11's refs spell "forset")
            norm = [re.sub(r"forset", "for set", s).split()[:-1] for s in (la, lb)]
            assert norm[0] == norm[1], (la, lb)
            continue
        assert ROW.match(la), f"not CalculiX's row layout: {la!r}"
        fa, fb = la.split(), lb.split()
        assert len(fa) == len(fb), (la, lb)
        for x, y in zip(fa, fb):
            if "." not in y:
                assert x == y, (la, lb)        # node, element and point numbers
                continue
            if abs(float(y)) >= 1e-10 and largest[k] > 1e-10:
                worst = max(worst, abs(float(x) - float(y)) / largest[k])
    return worst


def test_dat_calculix_suite_decks_against_dat_ref():
    """planestress, planestress2 (CPS8R), planestrain, planestrain2,
    axiplane, pret2: cfe2d's .dat passes CalculiX's own comparison with
    the .dat.ref (1e-3 of the block's largest value; measured: 3.8e-4 at
    most), the element blocks at the points of the 3D elements CalculiX
    expands 2D elements into."""
    if not os.path.isdir(DEBIAN):
        raise Skip("Debian's calculix-ccx-test is not installed (scripts/install-deps.sh installs it)")
    d = workdir("dat_suite")
    unpack(AGREEING, d)
    for name in AGREEING:
        run = run_deck("dat_suite_" + name, path=os.path.join(d, name + ".inp")).ok()
        out = os.path.dirname(run.listing_path)
        worst = datcheck(os.path.join(out, name + ".dat"), os.path.join(d, name + ".dat.ref"))
        assert worst <= 1e-3, (name, worst)


def blocks_of(path):
    """The .dat's blocks: {caption up to ' and time': [rows as lists]} in
    order, with the time of each."""
    out = []
    lines = open(path).read().split("\n")
    for i, line in enumerate(lines):
        if " and time" in line:
            assert lines[i - 1] == "" and lines[i + 1] == "", line
            cap, t = line.split(" and time")
            rows = []
            j = i + 2
            while j < len(lines) and lines[j].strip():
                assert ROW.match(lines[j]), repr(lines[j])
                rows.append(lines[j].split())
                j += 1
            out.append((cap.strip(), float(t), rows))
    return out


def test_dat_plate_closed_form_order_totals_frequency():
    """A plate in uniform tension (CPS4): the blocks in the order of the
    cards and of their quantities (RF before U as the card lists them), the
    total force of TOTALS=YES equal to the load, TOTALS=ONLY alone, the
    stresses and strains at 8 points per element (CalculiX's C3D8) with
    EZZ = -nu S / E, at the increments FREQUENCY=2 selects."""
    cards = ("*NODE PRINT, NSET=LEFT, TOTALS=YES, FREQUENCY=2\nRF, U\n*NODE PRINT, NSET=LEFT, TOTALS=ONLY\nRF\n"
             "*EL PRINT, ELSET=PLATE\nS, E\n")
    run = run_deck("dat_plate", plate("CPS4", cards)).ok()
    d = os.path.dirname(run.listing_path)
    got = blocks_of(os.path.join(d, "dat_plate.dat"))
    caps = [c.split(" (")[0] for c, _, _ in got]
    assert caps == ["forces", "total force", "displacements", "total force", "stresses", "strains"] * 2, caps
    assert [t for _, t, _ in got] == [0.5] * 6 + [1.0] * 6
    for cap, t, rows in got:
        s = SIG * t
        if cap.startswith("total force"):
            assert len(rows) == 1 and abs(float(rows[0][0]) + s * LY) <= 1e-6 * s * LY, rows
        elif cap.startswith("forces"):
            assert [r[0] for r in rows] == ["1", "6", "11"], rows       # sorted node numbers
        elif cap.startswith("displacements"):
            assert all(float(r[1]) == 0.0 for r in rows)
        elif cap.startswith("stresses"):
            assert len(rows) == 8 * 8 and [r[1] for r in rows[:8]] == [str(k) for k in range(1, 9)]
            assert all(abs(float(r[2]) - s) <= 1e-6 * s for r in rows)
        elif cap.startswith("strains"):
            for r in rows:
                exx, eyy, ezz = (float(v) for v in r[2:5])
                assert abs(exx - s / E) <= 1e-6 * s / E and abs(eyy + NU * s / E) <= 1e-6 * s / E
                assert abs(ezz + NU * s / E) <= 1e-6 * s / E, r


def test_dat_contact_print_and_status_files():
    """*CONTACT PRINT CDIS, CSTR: rows for the closed slave nodes, their
    pressure the CPRESS of the .frd's CONTACT block (the same results) and
    their normal the gap; the .sta one line per increment (step, increment,
    times); the .cvg CalculiX's header and a line per contact iteration."""
    deck = blocks("*CONTACT PAIR\nSLAVE, MASTER\n")
    deck = deck.replace("*END STEP", "*CONTACT PRINT\nCDIS, CSTR\n*CONTACT FILE\nCSTR\n*END STEP")
    run = run_deck("dat_contact", deck).ok()
    d = os.path.dirname(run.listing_path)
    got = blocks_of(os.path.join(d, "dat_contact.dat"))
    _, _, sets = read_frd(os.path.join(d, "dat_contact.frd"))
    cont = [b for b in got if b[0].startswith("relative contact displacement") or b[0].startswith("contact stress")]
    assert len(cont) == 2 * len(sets) == 4, [c[0] for c in got]
    for k, (_, _, _, blk) in enumerate(sets):
        cdis, cstr = cont[2 * k][2], cont[2 * k + 1][2]
        closed = sorted(n for n, v in blk["CONTACT"].items() if v[3] > 0)
        assert [int(r[0]) for r in cstr] == closed == [int(r[0]) for r in cdis] and closed, (cstr, closed)
        for r in cstr:
            p = blk["CONTACT"][int(r[0])][3]
            assert abs(float(r[1]) - p) <= 5e-6 * p, (r, p)
        for r in cdis:
            assert abs(float(r[1]) - blk["CONTACT"][int(r[0])][0]) <= 1e-12 + 5e-6 * abs(float(r[1]))
    sta = open(os.path.join(d, "dat_contact.sta")).read().split("\n")
    assert sta[:2] == ["SUMMARY OF JOB INFORMATION",
                       "  STEP      INC     ATT  ITRS     TOT TIME     STEP TIME      INC TIME"]
    rows = [ln.split() for ln in sta[2:] if ln]
    assert [(r[0], r[1]) for r in rows] == [("1", "1"), ("1", "2")], rows
    assert [float(r[4]) for r in rows] == [0.5, 1.0] and [float(r[6]) for r in rows] == [0.5, 0.5]
    assert all(re.match(r"^ {5}\d {10}\d {5}\d +\d+( {2}0\.\d{6}E[+-]\d\d){3}$", ln) for ln in sta[2:] if ln), sta
    cvg = open(os.path.join(d, "dat_contact.cvg")).read().split("\n")
    assert cvg[0] == "SUMMARY OF C0NVERGENCE INFORMATION" and len(cvg[1:4]) == 3
    its = [ln.split() for ln in cvg[4:] if ln]
    assert its and {r[1] for r in its} == {"1", "2"}, its
    assert all(int(r[3]) >= 1 for r in its)


def test_dat_node_print_local_axes():
    """*NODE PRINT of nodes with *TRANSFORM: U in their local axes by
    default (GLOBAL=NO, CalculiX's), in global ones with GLOBAL=YES; the
    right edge of the plate in tension turned by 90 degrees (x' = y,
    y' = -x): (u1', u2') = (uy, -ux) = (-nu S y / E, -S LX / E)."""
    from test_frd import LX
    right = ", ".join(str(5 * j + 5) for j in range(3))
    transform = f"*NSET, NSET=RIGHTN\n{right}\n*TRANSFORM, NSET=RIGHTN\n0., 1., 0., -1., 0., 0.\n*MATERIAL"
    cards = "*NODE PRINT, NSET=RIGHTN\nU\n*NODE PRINT, NSET=RIGHTN, GLOBAL=YES\nU\n"
    deck = plate("CPS4", cards, step="1.0, 1.0").replace("*MATERIAL", transform, 1)
    run = run_deck("dat_local", deck).ok()
    got = blocks_of(os.path.join(os.path.dirname(run.listing_path), "dat_local.dat"))
    assert [c for c, _, _ in got] == ["displacements (vx,vy,vz) for set RIGHTN"] * 2, got
    tol = 1e-6 * SIG * LX / E
    for (_, _, local), (_, _, glob) in [(got[0], got[1])]:
        assert [r[0] for r in local] == ["5", "10", "15"]
        for j, (rl, rg) in enumerate(zip(local, glob)):
            y = LY * j / 2
            assert abs(float(rl[1]) + NU * SIG * y / E) <= tol and abs(float(rl[2]) + SIG * LX / E) <= tol, rl
            assert abs(float(rg[1]) - SIG * LX / E) <= tol and abs(float(rg[2]) + NU * SIG * y / E) <= tol, rg
