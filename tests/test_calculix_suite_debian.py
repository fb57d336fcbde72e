"""Every deck with 2D elements in CalculiX's own test suite, as Debian ships
it (calculix-ccx-test: CalculiX 2.11's test/ folder, some files gzipped;
scripts/install-deps.sh installs it), through scripts/calculix_suite.py:
cfe2d runs each deck or rejects it at a line naming why, never crashes, and
every deck that runs and that the suite judges (plane strain,
axisymmetric) agrees with CalculiX's .dat.ref / .frd.ref within the
suite's 1e-3, but the two whose differences docs/calculix-suite.md
explains with measurements (axial: CalculiX integrates the centrifugal
load of CAX8R with the reduced rule; ax6: the linear CAX6 element, the same
difference without NLGEOM), each held to its measured difference.

The decks are CalculiX's and are not kept in this project; where the
package is absent the test is skipped, never passed."""
import gzip
import math
import os
import re
import shutil

from helpers import WORK, Skip, workdir

DEBIAN = "/usr/share/doc/calculix-ccx-test/examples/test"
# Decks that ran on 2.11's suite (measured 2026-11-25: 27 decks with 2D
# elements, 14 ran, 13 rejected, 0 crashed); a deck that stops running is a
# regression.
MUST_RUN = ("ax6", "axial", "axiplane", "oneel", "planestrain", "planestrain2", "planestress", "planestress2",
            "planestress3", "plate", "pret2", "ring1", "ring2", "thread", "spring4",
            # since issues 28, 30 and 31 (27 November 2026: 19 ran, 8
            # rejected: the fluid networks and cavity radiation)
            "scheibe", "bolt", "ax6ht", "dam")
# judged decks whose difference is explained in docs/calculix-suite.md, and
# the largest displacement difference measured (held with a small margin)
EXPLAINED = {"axial": 4.5e-3, "ax6": 1.7e-3}
# scheibe (runs since issue 28: its *NSET's undefined node 29 is dropped, as
# CalculiX drops it) turns a *RIGID BODY by 3.1415927 about z under NLGEOM.
# CalculiX 2.11's reference is no rigid motion (node 4, at (0, 1) from the
# reference node, moves by (3.173, -1.6e-4)); cfe2d's finite rotation puts
# it at (-sin t, cos t - 1) = (0, -2), checked below to 1e-7 (the 8 digits
# of the angle). The difference to the reference is held as measured: 1.00
# of the largest displacement.
EXPLAINED["scheibe"] = 1.01


def check_scheibe_rigid_rotation(outdir):
    """scheibe's node 4 at the exact rigid rotation by the deck's angle."""
    from cfe2d_listing import read_listing
    inc = read_listing(os.path.join(outdir, "scheibe", "scheibe.out")).increments[-1]
    block = inc.block("NODE U", set="N1")
    t = 3.1415927
    row = list(block["node"]).index(4)
    u1, u2 = float(block["U1"][row]), float(block["U2"][row])
    assert abs(u1 - (-math.sin(t))) < 1e-7 and abs(u2 - (math.cos(t) - 1.0)) < 1e-7, (u1, u2)


def unpacked_suite(folder):
    """CalculiX's test decks and references, decompressed into folder."""
    for name in os.listdir(DEBIAN):
        src = os.path.join(DEBIAN, name)
        if name.endswith(".gz"):
            with gzip.open(src, "rb") as f, open(os.path.join(folder, name[:-3]), "wb") as g:
                shutil.copyfileobj(f, g)
        else:
            shutil.copy(src, os.path.join(folder, name))


def test_calculix_suite_2d_decks_run_or_are_rejected_at_a_line_and_agree():
    if not os.path.isdir(DEBIAN):
        raise Skip("Debian's calculix-ccx-test is not installed (scripts/install-deps.sh installs it)")
    d = workdir("calculix_suite_debian")
    unpacked_suite(d)
    import calculix_suite
    rows = {r["deck"]: r for r in calculix_suite.main([d, "--quiet", "--out", os.path.join(WORK, "calculix_suite_out")])}
    assert len(rows) >= 27, sorted(rows)
    for name, r in rows.items():
        assert r["status"] in ("ran", "rejected"), (name, r["status"], r["detail"])
        if r["status"] == "rejected":
            # the reason at a line of the deck
            assert re.search(r"\.inp:\d+: error: ", r["detail"]), (name, r["detail"])
    for name in MUST_RUN:
        assert rows[name]["status"] == "ran", (name, rows[name]["detail"])
    for name, r in rows.items():
        if r["status"] != "ran" or "DIFFERS" not in r["detail"]:
            continue
        assert name in EXPLAINED, (name, r["detail"])
        got = float(re.search(r"displacements: largest difference ([0-9.e+-]+)", r["detail"]).group(1))
        assert got <= EXPLAINED[name], (name, got)
    assert rows["scheibe"]["status"] == "ran", rows["scheibe"]["detail"]
    check_scheibe_rigid_rotation(os.path.join(WORK, "calculix_suite_out"))
    judged = [n for n, r in rows.items() if r["status"] == "ran" and "(agrees)" in r["detail"]]
    assert len(judged) >= 6, judged
