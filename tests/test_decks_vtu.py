"""ParaView output: the .vtu files (one per increment) and the .pvd series
read back with meshio and compared with the listing, value by value."""
import os
import xml.etree.ElementTree as ET

import numpy as np

from helpers import Skip, run_deck
from test_decks_contact import blocks

REQUESTS = """*NODE PRINT
U, RF, S
*EL PRINT
S
*NODE FILE
U, RF, S, CSTRESS
*EL FILE
S
"""


def two_steps(file_params=""):
    """The contact blocks pressed in two increments and released in two,
    every quantity printed and filed."""
    deck = blocks("*CONTACT PAIR\nSLAVE, MASTER\n")
    deck = deck.replace("*NODE PRINT, NSET=TOP\nU\n*EL PRINT, ELSET=UPPER\nS\n",
                        REQUESTS.replace("*NODE FILE", "*NODE FILE" + file_params))
    first = deck[deck.index("*STEP"):]
    return deck + first.replace("TOP, 2, 2, -0.03", "TOP, 2, 2, 0.0")


def meshio_or_skip():
    try:
        import meshio
    except ImportError:
        raise Skip("meshio is not installed (scripts/install-deps.sh installs it)")
    return meshio


def series(run, job):
    """(times, [meshio meshes]) of the .pvd next to the listing."""
    meshio = meshio_or_skip()
    d = os.path.dirname(run.listing_path)
    root = ET.parse(os.path.join(d, job + ".pvd")).getroot()
    sets = root.find("Collection").findall("DataSet")
    return [float(s.get("timestep")) for s in sets], [meshio.read(os.path.join(d, s.get("file"))) for s in sets]


def test_vtu_series_equals_the_listing():
    run = run_deck("decks_vtu", two_steps(), args=("--vtu",)).ok()
    times, meshes = series(run, "decks_vtu")
    incs = run.listing.increments
    assert len(meshes) == len(incs) == 4
    assert times == [inc.time for inc in incs], times
    for inc, mesh in zip(incs, meshes):
        ids = mesh.point_data["NodeId"]
        at = {int(n): k for k, n in enumerate(ids)}
        for block, field, cols in (("NODE U", "U", ("U1", "U2")), ("NODE RF", "RF", ("RF1", "RF2")),
                                   ("NODE S", "S", ("S11", "S22", "S33", "S12"))):
            b = inc.block(block)
            rows = [at[int(n)] for n in b["node"]]
            for j, c in enumerate(cols):
                assert np.allclose(mesh.point_data[field][rows, j], b[c], rtol=1e-14, atol=1e-300), (block, c)
        assert np.allclose(mesh.point_data["Mises"][rows], inc.block("NODE S")["MISES"], rtol=1e-14)
        # element averages of the integration-point stresses
        es = inc.block("ELEMENT S")
        cells = {int(e): k for k, e in enumerate(mesh.cell_data["ElementId"][0])}
        for e in set(es["element"]):
            pick = es["element"] == e
            for j, c in enumerate(("S11", "S22", "S33", "S12")):
                assert np.isclose(mesh.cell_data["S (element)"][0][cells[int(e)], j], es[c][pick].mean(),
                                  rtol=1e-13, atol=1e-12), (e, c)
        # contact pressure of the slave nodes
        slave = inc.block("CONTACT SLAVE", pair=1)
        rows = [at[int(n)] for n in slave["node"]]
        assert np.allclose(mesh.point_data["CSTRESS"][rows], slave["pressure"], rtol=1e-14, atol=1e-300)


def test_vtu_mesh_is_the_deck_mesh():
    """Points at the deck's coordinates, quads with the deck's nodes
    counter-clockwise (VTK type 9), every solid element once."""
    deck = two_steps()
    run = run_deck("decks_vtu_mesh", deck, args=("--vtu",)).ok()
    _, meshes = series(run, "decks_vtu_mesh")
    mesh = meshes[0]
    coords = {}
    for line in deck[deck.index("*NODE"):deck.index("*ELEMENT")].splitlines()[1:]:
        n, x, y = line.split(",")
        coords[int(n)] = (float(x), float(y))
    ids = mesh.point_data["NodeId"]
    for k, n in enumerate(ids):
        assert tuple(mesh.points[k, :2]) == coords[int(n)] and mesh.points[k, 2] == 0.0
    assert [c.type for c in mesh.cells] == ["quad"]
    assert len(mesh.cells[0].data) == 25 + 40
    # element 1 is 1-2-8-7 in the deck
    first = list(mesh.cell_data["ElementId"][0]).index(1)
    assert [int(ids[k]) for k in mesh.cells[0].data[first]] == [1, 2, 8, 7]


def test_vtu_selected_in_the_deck_or_not_at_all():
    run = run_deck("decks_vtu_deck", two_steps(", FORMAT=VTU")).ok()
    _, meshes = series(run, "decks_vtu_deck")
    assert len(meshes) == 4
    run = run_deck("decks_vtu_none", two_steps()).ok()
    files = os.listdir(os.path.dirname(run.listing_path))
    assert not any(f.endswith(".vtu") or f.endswith(".pvd") for f in files), files
    run = run_deck("decks_vtu_bad", two_steps(", FORMAT=VTK"))
    assert run.rc == 1 and "FORMAT must be MSH or VTU" in run.stderr
