"""A mesh exported by gmsh (`gmsh -2 -format inp`, triangles and quads,
3 coordinates per node, T3D2 line elements for physical curves) is read
through *INCLUDE unchanged and solved: uniaxial tension must give the
exact uniform stress E*delta/L in every element."""
import os
import shutil
import subprocess

from helpers import HERE, Skip, run_deck, workdir

E, NU, L, DELTA = 2000.0, 0.3, 2.0, 0.01

DECK = """*HEADING
plate meshed by gmsh
*INCLUDE, INPUT=plate.inp
** node sets from gmsh's line elements, and a surface built on them
*NSET, NSET=LEFTN, ELSET=LEFT
*NSET, NSET=RIGHTN, ELSET=RIGHT
*SURFACE, NAME=RIGHTFACE
RIGHT
*MATERIAL, NAME=M
*ELASTIC
{E}, {NU}
*SOLID SECTION, ELSET=PLATE, MATERIAL=M
0.5
*BOUNDARY
LEFTN, 1, 1
BOTTOM, 2, 2
*STEP
*STATIC
0.5, 1.0
*BOUNDARY
RIGHTN, 1, 1, {DELTA}
*EL PRINT
S
*NODE PRINT, NSET=RIGHTN
U
*END STEP
"""


def mesh(workdir_path, args=()):
    if shutil.which("gmsh") is None:
        raise Skip("gmsh is not installed (scripts/install-deps.sh installs it)")
    out = os.path.join(workdir_path, "plate.inp")
    subprocess.run(["gmsh", "-2", "-format", "inp", "-setnumber", "Mesh.SaveGroupsOfNodes", "1", *args,
                    "-o", out, os.path.join(HERE, "gmsh", "plate.geo")], check=True, capture_output=True)
    return out


def test_gmsh_mesh_read_and_solved():
    d = workdir("gmsh_plate_mesh")
    with open(mesh(d)) as f:
        plate = f.read()
    assert "T3D2" in plate and "CPS3" in plate and "CPS4" in plate
    run = run_deck("gmsh_plate", DECK.format(E=E, NU=NU, DELTA=DELTA), files={"plate.inp": plate}).ok()
    inc = run.listing.increments[-1]
    s = inc.block("ELEMENT S")
    sxx = E * DELTA / L
    err = max(max(abs(s["S11"] - sxx)), max(abs(s["S22"])), max(abs(s["S12"]))) / sxx
    assert err < 1e-9, f"stress error {err:.2e}"
    assert len(set(s["element"])) > 20, "too few elements read"
    # half the load after the first of two increments
    first = run.listing.increments[0].block("ELEMENT S")
    assert max(abs(first["S11"] - sxx / 2)) / sxx < 1e-9
    rf = inc.block("REACTIONS").as_dict()
    assert abs(rf["RIGHTN"][0] - sxx * 1.0 * 0.5) < 1e-9 * sxx, rf


def test_binary_result_file_read_by_gmsh_and_by_the_reader():
    """The result file is binary MSH 2.2: gmsh reads it (the largest
    displacement and the stress range it computes equal the listing's),
    and scripts/gmsh_results.py reads the same values as the listing
    prints, node by node."""
    import sys
    import numpy as np
    sys.path.insert(0, os.path.join(os.path.dirname(HERE), "scripts"))
    from gmsh_results import read_msh
    d = workdir("gmsh_binary_mesh")
    with open(mesh(d)) as f:
        plate = f.read()
    deck = DECK.format(E=E, NU=NU, DELTA=DELTA).replace("*NODE PRINT, NSET=RIGHTN\nU\n",
                                                       "*NODE PRINT\nU\n*NODE FILE\nU, S\n")
    run = run_deck("gmsh_binary", deck, files={"plate.inp": plate}).ok()
    msh = os.path.splitext(run.listing_path)[0] + ".msh"
    with open(msh, "rb") as f:
        head = f.read(40)
    assert head.startswith(b"$MeshFormat\n2.2 1 8\n\x01\x00\x00\x00\n$EndMeshFormat\n"), head
    u = run.listing.increments[-1].block("NODE U")
    res = read_msh(msh)
    _, du = res.node_view("Displacement", 1)
    order = np.argsort(res.node_ids)
    ids = np.array(u["node"], dtype=int)
    disp = du[order[np.searchsorted(res.node_ids, ids, sorter=order)]]
    ref = np.column_stack([u["U1"], u["U2"]])
    assert np.max(np.abs(disp[:, :2] - ref)) <= 1e-14 * np.max(np.abs(ref)), "reader and listing differ"
    assert np.all(disp[:, 2] == 0.0)
    geo = os.path.join(d, "probe.geo")
    with open(geo, "w") as f:
        f.write(f'Merge "{msh}";\nView[0].TimeStep = 1;\nPrintf("umax %.15g", View[0].Max);\n'
                'View[2].TimeStep = 1;\nPrintf("s22 %.15g %.15g", View[2].Min, View[2].Max);\nExit;\n')
    out = subprocess.run(["gmsh", geo, "-0"], capture_output=True, text=True).stdout
    umax = float(out.split("umax ")[1].split()[0])
    assert abs(umax - np.max(np.hypot(ref[:, 0], ref[:, 1]))) <= 1e-12 * umax, (umax, out[-500:])
    _, s22 = res.node_view("S22", 1)
    lo, hi = (float(v) for v in out.split("s22 ")[1].split()[:2])
    assert np.isclose(lo, np.nanmin(s22), rtol=0, atol=1e-12 * E) and np.isclose(hi, np.nanmax(s22), rtol=0,
                                                                                  atol=1e-12 * E), out[-500:]
