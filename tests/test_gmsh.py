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
