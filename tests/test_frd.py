"""CalculiX's result file <job>.frd: its records, column for column as
CalculiX 2.20 writes them (read here with a strict fixed-column reader), the
values of a uniform plane-stress tension field against the closed form, and
the real clients: ccx2paraview (its VTU equals cfe2d's own VTU to the
printed digits) and cgx (reads the file in batch mode). ccx is never run
here."""
import json
import os
import shutil
import subprocess
import sys

import numpy as np

from helpers import CFE2D, Skip, run_deck, workdir
from test_decks_contact import NX2, blocks

E, NU = 210000.0, 0.3
LX, LY, SIG = 4.0, 2.0, 50.0      # plate, tension on the right edge
FRD_TYPE = {"CPS3": 7, "CPS6": 8, "CPS4": 9, "CPS8": 10, "CPS4R": 9, "CPE8R": 10, "CAX4": 9}


def num(s):
    """A 12-column real of the file (E12.5)."""
    assert len(s) == 12 and s[-4] == "E", f"not an E12.5 field: {s!r}"
    return float(s)


def read_frd(path):
    """The .frd by its fixed columns: nodes, elements and the result sets
    [(step, increment, time, {block: {node: values}})]; asserts every record
    it reads has CalculiX's layout."""
    with open(path) as f:
        lines = f.read().split("\n")
    assert lines[0] == "    1C", lines[0]
    assert lines[-2] == " 9999" and lines[-1] == "", "no end record"
    nodes, elems, sets = {}, {}, []
    i = 1
    while lines[i].startswith("    1U"):
        assert len(lines[i]) <= 80, repr(lines[i])
        i += 1
    while i < len(lines) - 2:
        ln = lines[i]
        if ln.startswith("    2C"):
            n = int(ln[6:36])
            assert ln[36:] == " " * 37 + "1", repr(ln)
            for k in range(n):
                r = lines[i + 1 + k]
                assert r[:3] == " -1" and len(r) == 49, repr(r)
                nodes[int(r[3:13])] = [num(r[13 + 12 * j:25 + 12 * j]) for j in range(3)]
            i += n + 1
            assert lines[i] == " -3"
        elif ln.startswith("    3C"):
            n = int(ln[6:36])
            for k in range(n):
                a, b = lines[i + 1 + 2 * k], lines[i + 2 + 2 * k]
                assert a[:3] == " -1" and len(a) == 28 and b[:3] == " -2", (a, b)
                conn = [int(b[3 + 10 * j:13 + 10 * j]) for j in range((len(b) - 3) // 10)]
                elems[int(a[3:13])] = (int(a[13:18]), int(a[18:23]), int(a[23:28]), conn)
            i += 2 * n + 1
            assert lines[i] == " -3"
        elif ln.startswith("    1PSTEP"):
            assert len(ln) == 70, repr(ln)
            block, inc, step = int(ln[10:36]), int(ln[36:48]), int(ln[48:60])
            head = lines[i + 1]
            assert head[:7] == "  100CL" and len(head) == 75, repr(head)
            # the time: E12.5 (cfe2d, and ccx for most values) or F12.9 (ccx near 1)
            kode, time, n = int(head[7:12]), float(head[12:24]), int(head[24:36])
            assert int(head[58:63]) == kode - 100 and head[63:] == " " * 11 + "1", repr(head)
            if not sets or sets[-1][3] != kode:
                sets.append((step, inc, time, kode, {}))
            name, ncomp = lines[i + 2][5:13].strip(), int(lines[i + 2][13:18])
            assert lines[i + 2][:5] == " -4  ", lines[i + 2]
            j = i + 3
            while lines[j].startswith(" -5"):
                j += 1
            values = {}
            for k in range(n):
                r = lines[j + k]
                nv = (len(r) - 13) // 12
                assert r[:3] == " -1" and len(r) == 13 + 12 * nv, repr(r)
                values[int(r[3:13])] = np.array([num(r[13 + 12 * c:25 + 12 * c]) for c in range(nv)])
            assert lines[j + n] == " -3", lines[j + n]
            assert block == sum(len(s[4]) for s in sets) + 1
            sets[-1][4][name] = values
            i = j + n
        i += 1
    return nodes, elems, [(s[0], s[1], s[2], s[4]) for s in sets]


def plate(etype, file_cards="*NODE FILE\nU, RF\n*EL FILE\nS, E\n", step="0.25, 1.0"):
    """A plate LX x LY of 4 x 2 cells of etype (triangles: two per cell),
    held on its left edge, pulled by SIG on its right edge."""
    quad = etype.startswith("CPS4") or etype.startswith("CAX4")
    mid = etype[3] in "68"
    nx, ny = 4, 2
    sub = 2 if mid else 1
    ids = {}
    lines = []
    for j in range(ny * sub + 1):
        for i in range(nx * sub + 1):
            ids[i, j] = len(ids) + 1
            lines.append(f"{ids[i, j]}, {LX * i / (nx * sub)!r}, {LY * j / (ny * sub)!r}")
    elems = []
    for j in range(ny):
        for i in range(nx):
            c = [ids[sub * i, sub * j], ids[sub * (i + 1), sub * j], ids[sub * (i + 1), sub * (j + 1)],
                 ids[sub * i, sub * (j + 1)]]
            if quad or etype == "CPS8" or etype == "CPE8R":
                if mid:
                    c += [ids[2 * i + 1, 2 * j], ids[2 * i + 2, 2 * j + 1], ids[2 * i + 1, 2 * j + 2],
                          ids[2 * i, 2 * j + 1]]
                elems.append(c)
            else:
                t1, t2 = [c[0], c[1], c[2]], [c[0], c[2], c[3]]
                if mid:
                    t1 += [ids[2 * i + 1, 2 * j], ids[2 * i + 2, 2 * j + 1], ids[2 * i + 1, 2 * j + 1]]
                    t2 += [ids[2 * i + 1, 2 * j + 1], ids[2 * i + 1, 2 * j + 2], ids[2 * i, 2 * j + 1]]
                elems += [t1, t2]
    left = [ids[0, j] for j in range(ny * sub + 1)]
    elem_lines = "\n".join(f"{k + 1}, " + ", ".join(map(str, c)) for k, c in enumerate(elems))
    return f"""*NODE
{chr(10).join(lines)}
*ELEMENT, TYPE={etype}, ELSET=PLATE
{elem_lines}
*SURFACE, NAME=RIGHT
{right_faces(etype, elems, ids, nx, ny, sub)}
*NSET, NSET=LEFT
{", ".join(map(str, left))}
*MATERIAL, NAME=STEEL
*ELASTIC
{E}, {NU}
*SOLID SECTION, ELSET=PLATE, MATERIAL=STEEL
1.
*BOUNDARY
LEFT, 1, 1
{ids[0, 0]}, 2, 2
*STEP
*STATIC
{step}
*DSLOAD
RIGHT, P, {-SIG}
{file_cards}*END STEP
"""


def right_faces(etype, elems, ids, nx, ny, sub):
    """The faces on x = LX, as element, face label."""
    right = {ids[nx * sub, j] for j in range(ny * sub + 1)}
    out = []
    for k, c in enumerate(elems):
        nc = 3 if etype[3] in "36" else 4
        for f in range(nc):
            if c[f] in right and c[(f + 1) % nc] in right:
                out.append(f"{k + 1}, S{f + 1}")
    return "\n".join(out)


def check_uniform(nodes, blocks, frac):
    """Uniform tension SIG * frac in x: the closed form (plane stress)."""
    s = SIG * frac
    for nid, (x, y, _) in nodes.items():
        u = blocks["DISP"][nid]
        assert np.allclose(u, [s * x / E, -NU * s * y / E, 0.0], rtol=0, atol=1e-5 * SIG * LX / E), (nid, u)
        assert np.allclose(blocks["STRESS"][nid], [s, 0, 0, 0, 0, 0], rtol=0, atol=1e-5 * SIG), nid
        assert np.allclose(blocks["TOSTRAIN"][nid], [s / E, -NU * s / E, -NU * s / E, 0, 0, 0],
                           rtol=0, atol=1e-5 * SIG / E), (nid, blocks["TOSTRAIN"][nid])
    left = [nid for nid, (x, _, _) in nodes.items() if x == 0.0]
    total = sum(blocks["FORC"][nid][0] for nid in left)
    assert abs(total + s * LY) <= 1e-5 * SIG * LY, total


def test_frd_plane_stress_tension_every_element():
    """Each 2D element type: CalculiX's type code in the element block, the
    nodes in deck order, and DISP, STRESS, TOSTRAIN (with the out-of-plane
    strain -nu S/E of plane stress) and FORC (the support reactions sum to
    the load) at every node of every increment, to 1e-5."""
    for etype in ("CPS3", "CPS6", "CPS4", "CPS8", "CPS4R"):
        run = run_deck("frd_" + etype.lower(), plate(etype)).ok()
        d = os.path.dirname(run.listing_path)
        nodes, elems, sets = read_frd(os.path.join(d, f"frd_{etype.lower()}.frd"))
        assert {t for t, _, _, _ in elems.values()} == {FRD_TYPE[etype]}, (etype, elems)
        assert all(g == 0 and mat == 1 for _, g, mat, _ in elems.values())
        assert [s[1] for s in sets] == [1, 2, 3, 4] and [s[0] for s in sets] == [1] * 4
        for step, inc, time, blocks in sets:
            assert list(blocks) == ["DISP", "STRESS", "TOSTRAIN", "FORC"], list(blocks)
            assert abs(time - 0.25 * inc) < 1e-12
            check_uniform(nodes, blocks, time)


def test_frd_frequency_and_only_what_is_asked():
    """FREQUENCY=2 over four increments writes increments 2 and 4; a deck
    asking only for U gets only DISP blocks; no file card, no .frd."""
    run = run_deck("frd_freq", plate("CPS4", "*NODE FILE, FREQUENCY=2\nU\n")).ok()
    d = os.path.dirname(run.listing_path)
    nodes, _, sets = read_frd(os.path.join(d, "frd_freq.frd"))
    assert [(s[1], s[2]) for s in sets] == [(2, 0.5), (4, 1.0)], sets
    assert all(list(s[3]) == ["DISP"] for s in sets)
    assert len(sets[0][3]["DISP"]) == len(nodes)
    run = run_deck("frd_none", plate("CPS4", "*NODE PRINT, NSET=LEFT\nU\n")).ok()
    assert not os.path.exists(os.path.join(os.path.dirname(run.listing_path), "frd_none.frd"))


def test_frd_contact_block():
    """*CONTACT FILE CSTR: the CONTACT block at the slave nodes, CPRESS
    equal to the VTU's CSTRESS (both written by cfe2d from the same
    results) to the printed digits, COPEN the gap."""
    deck = blocks("*CONTACT PAIR\nSLAVE, MASTER\n")
    deck = deck.replace("*END STEP", "*NODE FILE, FORMAT=VTU\nU, CSTRESS\n*CONTACT FILE\nCSTR, CDIS\n*END STEP")
    run = run_deck("frd_contact", deck).ok()
    d = os.path.dirname(run.listing_path)
    nodes, _, sets = read_frd(os.path.join(d, "frd_contact.frd"))
    import meshio
    for k, (_, _, _, blk) in enumerate(sets):
        assert list(blk) == ["DISP", "CONTACT"], list(blk)
        vtu = meshio.read(os.path.join(d, f"frd_contact_{k + 1:04d}.vtu"))
        ids = list(vtu.point_data["NodeId"])
        cp = {nid: v for nid, v in blk["CONTACT"].items()}
        assert len(cp) == NX2 + 1, sorted(cp)
        for nid, v in cp.items():
            p = vtu.point_data["CSTRESS"][ids.index(nid)]
            assert abs(v[3] - p) <= 5e-6 * abs(p) + 1e-90, (nid, v, p)
            if v[3] > 0:
                assert v[0] <= 1e-12, (nid, v)
        assert max(v[3] for v in cp.values()) > 0


def test_cli_as_ccx():
    """cfe2d -i job and cfe2d job (CalculiX's command lines) read job.inp and
    write job.out and job.frd beside it."""
    for args in (["-i", "job"], ["job"]):
        d = workdir("frd_cli")
        with open(os.path.join(d, "job.inp"), "w") as f:
            f.write(plate("CPS4"))
        proc = subprocess.run([CFE2D, "-q", *args], cwd=d, capture_output=True, text=True, timeout=120)
        assert proc.returncode == 0, proc.stderr
        assert os.path.exists(os.path.join(d, "job.out")) and os.path.exists(os.path.join(d, "job.frd")), args
        read_frd(os.path.join(d, "job.frd"))
    # -i without a job, and a job without its deck: an error, no traceback
    proc = subprocess.run([CFE2D, "-i"], cwd=d, capture_output=True, text=True, timeout=60)
    assert proc.returncode == 1 and "cfe2d: error: -i needs a job name" in proc.stderr, proc.stderr
    proc = subprocess.run([CFE2D, "-q", "nojob"], cwd=d, capture_output=True, text=True, timeout=60)
    assert proc.returncode == 1 and "error" in proc.stderr and "nojob" in proc.stderr, proc.stderr
    # ccx's -version, read by pycalculix: the last number is the layout's version
    proc = subprocess.run([CFE2D, "-version"], capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0 and proc.stdout.split()[-1] == "2.20", proc.stdout


def test_frd_ccx2paraview_equals_vtu():
    """ccx2paraview (PyPI) converts cfe2d's .frd; its U, S and RF equal cfe2d's
    own VTU at every node to the digits the .frd prints (5e-6 relative).
    One increment: ccx2paraview 3.2.0 writes each increment's file from a
    thread while it already fills the same grid with the next increment's
    values (so its files of a series may hold later values, or the
    conversion crash), for ccx's own .frd as for cfe2d's."""
    exe = shutil.which("ccx2paraview")
    if exe is None:
        raise Skip("ccx2paraview is not installed (scripts/install-deps.sh installs it from PyPI)")
    try:
        import meshio
    except ImportError:
        raise Skip("meshio is not installed (scripts/install-deps.sh installs it)")
    deck = plate("CPS8", "*NODE FILE, FORMAT=VTU\nU, RF, S\n*EL FILE\nS, E\n", step="1.0, 1.0")
    run = run_deck("frd_c2p", deck).ok()
    d = os.path.dirname(run.listing_path)
    conv = os.path.join(d, "conv")
    os.makedirs(conv)
    shutil.copy(os.path.join(d, "frd_c2p.frd"), conv)
    proc = subprocess.run([exe, "frd_c2p.frd", "vtu"], cwd=conv, capture_output=True, text=True, timeout=120)
    if "Module vtk is not available" in proc.stderr + proc.stdout:
        raise Skip("ccx2paraview needs the vtk module (PyPI vtk; scripts/install-deps.sh installs it)")
    assert proc.returncode == 0, (proc.returncode, proc.stderr[-2000:])
    frd_ids = list(read_frd(os.path.join(d, "frd_c2p.frd"))[0])
    theirs = meshio.read(os.path.join(conv, "frd_c2p.vtu"))
    ours = meshio.read(os.path.join(d, "frd_c2p_0001.vtu"))
    # ccx2paraview's points are the .frd's nodes in its order; cfe2d's VTU
    # holds every node of the deck (the cell centres unused by CPS8 too)
    row = {nid: r for r, nid in enumerate(ours.point_data["NodeId"])}
    pick = [row[nid] for nid in frd_ids]
    assert len(theirs.points) == len(frd_ids) < len(ours.points)
    assert np.array_equal(theirs.points[:, :2], ours.points[pick, :2])
    for name, ncomp in (("U", 3), ("RF", 3), ("S", 4)):
        a, b = theirs.point_data[name][:, :ncomp], ours.point_data[name][pick, :ncomp]
        tol = 5.0001e-6 * np.abs(b) + 1e-99
        assert np.all(np.abs(a - b) <= tol), (name, np.max(np.abs(a - b) - tol))
    assert np.max(np.abs(theirs.point_data["S"][:, 0])) > 0.9 * SIG


def test_frd_cgx_reads_batch():
    """cgx (Debian calculix-cgx) reads cfe2d's .frd in batch mode: it reports
    the nodes, elements and every data set, and no error."""
    exe = shutil.which("cgx")
    if exe is None:
        raise Skip("cgx is not installed (Debian calculix-cgx; scripts/install-deps.sh installs it)")
    run = run_deck("frd_cgx", plate("CPS6")).ok()
    d = os.path.dirname(run.listing_path)
    with open(os.path.join(d, "read.fbd"), "w") as f:
        f.write("read frd_cgx.frd\nprnt info\nquit\n")
    proc = subprocess.run([exe, "-bg", "read.fbd"], cwd=d, capture_output=True, text=True, timeout=120)
    out = proc.stdout + proc.stderr
    assert proc.returncode == 0, out
    assert "ERROR" not in out.upper(), out
    assert "reading Dataset No:16" in out and "reading Dataset No:17" not in out, out[-2000:]
    assert "record: 9999" in out
    nodes, elems, _ = read_frd(os.path.join(d, "frd_cgx.frd"))
    assert f"n:{len(nodes)} e:{len(elems)}" in out, out[-800:]


PYCALCULIX_SCRIPT = r'''
"""A plate 100 x 20 mm drawn, meshed (CPS6) and written by pycalculix,
solved by the "ccx" it is given (cfe2d), read back by its result reader."""
import json, sys, types
import numpy
if not hasattr(numpy.lib, "polynomial"):
    # pycalculix 1.1.4 imports numpy.lib.polynomial.roots, gone in numpy 2
    shim = types.ModuleType("numpy.lib.polynomial")
    shim.roots = numpy.roots
    sys.modules["numpy.lib.polynomial"] = shim
import matplotlib
matplotlib.use("Agg")
import pycalculix as pyc
pyc.environment.CCX, pyc.environment.GMSH = sys.argv[1], sys.argv[2]
model = pyc.FeaModel("plate")
model.set_units("mm")
part = pyc.Part(model)
part.goto(0.0, 0.0)
part.draw_line_ax(20.0)
part.draw_line_rad(100.0)
part.draw_line_ax(-20.0)
part.draw_line_rad(-100.0)
model.set_etype("plstress", part, 10.0)
model.set_eshape("tri", 2)
model.mesh(1.0, "gmsh")
model.set_constr("fix", part.bottom, "x")
model.set_constr("fix", part.left, "y")
model.set_load("press", part.right, -10.0)
mat = pyc.Material("steel")
mat.set_mech_props(7.8e-9, 210000.0, 0.3)
model.set_matl(mat, part)
prob = pyc.Problem(model, "struct")
prob.solve()
r = prob.rfile
out = {k: [r.get_nmax(k), r.get_nmin(k)] for k in ("Sx", "Sy", "ux", "uy", "ez")}
out["Sy_elem"] = [r.get_emax("Sy", 1.0), r.get_emin("Sy", 1.0)]
print("RESULTS " + json.dumps(out))
'''


def test_frd_pycalculix_reads_what_cfe2d_solves():
    """pycalculix (PyPI) writes a plate deck (CPS6, plane stress, pulled
    by 10 MPa), runs cfe2d as its ccx (`cfe2d plate`, `cfe2d -version`)
    and reads cfe2d's .frd (nodal) and .dat (integration points) with its
    own reader: Sy = 10 at every node and point, uy = 10 * 20 / E,
    ux = -nu 10 * 100 / E and ez = -nu 10 / E, to the printed digits."""
    gmsh = shutil.which("gmsh")
    if gmsh is None:
        raise Skip("gmsh is not installed (scripts/install-deps.sh installs it); pycalculix meshes with it")
    probe = subprocess.run([sys.executable, "-c", "import dxfgrabber, requests, matplotlib"], capture_output=True)
    if probe.returncode != 0 or subprocess.run([sys.executable, "-c", "import importlib.util, sys; "
                                                "sys.exit(importlib.util.find_spec('pycalculix') is None)"]).returncode:
        raise Skip("pycalculix is not installed (scripts/install-deps.sh installs it from PyPI)")
    d = workdir("frd_pycalculix")
    # gmsh 4.8 crashes (segfault) meshing pycalculix's .geo with the
    # Mesh.Algorithm 8 it writes; the wrapper meshes it with algorithm 6
    wrapper = os.path.join(d, "gmsh_wrapper")
    with open(wrapper, "w") as f:
        f.write(f'#!/bin/sh\nsed -i "s/Mesh.Algorithm = 8;/Mesh.Algorithm = 6;/" "$1"\nexec {gmsh} "$@"\n')
    os.chmod(wrapper, 0o755)
    with open(os.path.join(d, "drive.py"), "w") as f:
        f.write(PYCALCULIX_SCRIPT)
    proc = subprocess.run([sys.executable, "drive.py", CFE2D, wrapper], cwd=d, capture_output=True, text=True,
                          timeout=300)
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    line = [ln for ln in proc.stdout.splitlines() if ln.startswith("RESULTS ")]
    assert line, proc.stdout[-2000:]
    r = json.loads(line[0][8:])
    close = lambda a, b: abs(a - b) <= 5e-6 * abs(b)      # noqa: E731
    assert close(r["Sy"][0], 10.0) and close(r["Sy"][1], 10.0), r
    assert close(r["Sy_elem"][0], 10.0) and close(r["Sy_elem"][1], 10.0), r
    assert close(r["uy"][0], 10.0 * 20.0 / 210000.0) and r["uy"][1] == 0.0, r
    assert close(r["ux"][1], -0.3 * 10.0 * 100.0 / 210000.0) and r["ux"][0] == 0.0, r
    assert close(r["ez"][0], -0.3 * 10.0 / 210000.0) and close(r["ez"][1], -0.3 * 10.0 / 210000.0), r
    assert max(abs(v) for v in r["Sx"]) < 1e-6, r


def test_frd_as_ccx_writes_it():
    """The same deck (tests/calculix/frd_plate_cps8.inp, CPS8) in ccx 2.20's
    .frd (tests/calculix/frd_plate_cps8.frd, made once) and in cfe2d's:
    the strict reader above takes both; the same nodes (ccx too leaves out
    the unused cell centres), element types and connectivity, the blocks in
    the same order (ccx adds its ERROR estimate, cfe2d has none), DISP,
    STRESS and TOSTRAIN equal to 1e-4 of each block's largest value (ccx's
    strains are extrapolated from the points of its expanded element), FORC
    at the supported nodes too (ccx's FORC also holds the applied load at
    the loaded nodes, cfe2d's is the reaction: zero there)."""
    ref = os.path.join(os.path.dirname(os.path.abspath(__file__)), "calculix")
    cnodes, celems, csets = read_frd(os.path.join(ref, "frd_plate_cps8.frd"))
    with open(os.path.join(ref, "frd_plate_cps8.inp")) as f:
        run = run_deck("frd_as_ccx", f.read()).ok()
    nodes, elems, sets = read_frd(os.path.join(os.path.dirname(run.listing_path), "frd_as_ccx.frd"))
    assert nodes == cnodes and elems == celems
    assert len(sets) == len(csets) == 1
    blocks, cblocks = sets[0][3], csets[0][3]
    assert list(cblocks) == list(blocks) + ["ERROR"], (list(cblocks), list(blocks))
    assert sets[0][:3] == csets[0][:3]
    for name in ("DISP", "STRESS", "TOSTRAIN", "FORC"):
        big = max(np.max(np.abs(v)) for v in cblocks[name].values())
        keys = [n for n in cblocks[name] if name != "FORC" or cnodes[n][0] == 0.0]
        assert sorted(blocks[name]) == sorted(cblocks[name])
        worst = max(np.max(np.abs(blocks[name][n] - cblocks[name][n])) for n in keys) / big
        assert worst <= 1e-4, (name, worst)
    loaded = [n for n in cnodes if cnodes[n][0] == LX]
    assert all(abs(blocks["FORC"][n][0]) < 1e-9 * SIG < abs(cblocks["FORC"][n][0]) for n in loaded)


def test_frd_contact_block_with_friction():
    """A block pressed, then slid on a base (Coulomb, mu = 0.3; the deck of
    tests/test_friction_output.py): the CONTACT block's CSHEAR1 is the
    VTU's CSHEAR and CPRESS its CSTRESS at every slave node of every
    increment (5e-6), the shear reaches mu times the pressure where the
    block slides, and CSLIP1, the accumulated slip, never decreases."""
    from test_friction_output import slide_deck
    try:
        import meshio
    except ImportError:
        raise Skip("meshio is not installed (scripts/install-deps.sh installs it)")
    run = run_deck("frd_friction", slide_deck(), args=("--vtu",)).ok()
    d = os.path.dirname(run.listing_path)
    _, _, sets = read_frd(os.path.join(d, "frd_friction.frd"))
    assert len(sets) == 12, len(sets)
    slipping = 0
    last_slip = {}
    for k, (step, _, _, blk) in enumerate(sets):
        vtu = meshio.read(os.path.join(d, f"frd_friction_{k + 1:04d}.vtu"))
        ids = list(vtu.point_data["NodeId"])
        assert len(blk["CONTACT"]) == 8, sorted(blk["CONTACT"])
        for nid, v in blk["CONTACT"].items():
            p, t = vtu.point_data["CSTRESS"][ids.index(nid)], vtu.point_data["CSHEAR"][ids.index(nid)]
            assert abs(v[3] - p) <= 5e-6 * abs(p) + 1e-90 and abs(v[4] - t) <= 5e-6 * abs(t) + 1e-90, (nid, v, p, t)
            assert v[1] >= last_slip.get(nid, 0.0) - 1e-12, (nid, v, last_slip)
            last_slip[nid] = v[1]
            if step == 2 and v[3] > 0 and abs(abs(v[4]) - 0.3 * v[3]) <= 1e-4 * v[3]:
                slipping += 1
    assert slipping > 0
