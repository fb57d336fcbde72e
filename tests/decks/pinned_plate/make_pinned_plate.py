"""Writes the pinned plate decks with pycalculix, as a pycalculix user
would: a steel plate hanging with clearance on three pins, loaded by
gravity and a side load, held by nothing but the contact with the pins.

    pip install pycalculix     # 1.1.4; gmsh from Debian
    python3 make_pinned_plate.py quad    # pinned_plate_cps8.inp
    python3 make_pinned_plate.py tri     # pinned_plate_cps6.inp

pycalculix draws in (x, y) with gravity along -x (its only direction), so
x is up here: the plate (80 mm high, 150 mm wide) has three holes of
radius 5 mm at x = 65 mm; a pin of radius 4.95 mm sits in each (0.05 mm
clearance all around), held at its bore (radius 2 mm). Gravity (9810
mm/s^2, density 7.85e-9 t/mm^3) and a side load along +y on the bottom
edge: pycalculix's set_load('force', ...) puts the value given on every
node of the edge (not shared among them), 0.5 N each. The pins carry
both through frictionless contact (set_contact_linear: TYPE=SURFACE TO
SURFACE, PRESSURE-OVERCLOSURE=LINEAR, 1e7 MPa/mm).

pycalculix writes the deck, meshes with gmsh and would run ccx; here ccx
is not run (CalculiX's numbers: README.md). Two things are not
pycalculix's own: gmsh 4.8.4 (Debian 12) crashes in pycalculix's
Frontal-Delaunay-for-quads meshing of this geometry, so gmsh_algorithm6.sh
meshes with Frontal-Delaunay and the same recombination; and the deck
gets one *NODE PRINT, TOTALS=ONLY of RF per pin bore before its *END
STEP (output only), whose sums both programs print.
"""
import os
import sys
import types

import numpy

# pycalculix 1.1.4 imports numpy.lib.polynomial, which numpy 2 removed
_poly = types.ModuleType("numpy.lib.polynomial")
_poly.roots = numpy.roots
sys.modules.setdefault("numpy.lib.polynomial", _poly)
import pycalculix as pyc  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SIDE_PER_NODE = 0.5            # N on each node of the bottom edge, along +y
H, W = 80.0, 150.0             # x: height (gravity along -x), y: width
XC, YC = 65.0, (25.0, 75.0, 125.0)
RH, RP, RB = 5.0, 4.95, 2.0    # hole, pin and bore radius


def main(shape):
    name = "pinned_plate_" + ("cps8" if shape == "quad" else "cps6")
    model = pyc.FeaModel(name, gmsh=os.path.join(HERE, "gmsh_algorithm6.sh"))
    model.set_units("mm")
    plate = pyc.Part(model)
    plate.goto(0.0, 0.0)
    plate.draw_line_to(H, 0.0)
    plate.draw_line_to(H, W)
    plate.draw_line_to(0.0, W)
    plate.draw_line_to(0.0, 0.0)
    holes = [plate.draw_hole(XC, y, RH) for y in YC]
    pins, pin_arcs, bores = [], [], []
    for y in YC:
        pin = pyc.Part(model)
        pin_arcs.append(pin.draw_circle(XC, y, RP))
        bores.append(pin.draw_hole(XC, y, RB))
        pins.append(pin)
    for loop in holes + pin_arcs:
        model.set_ediv(list(loop), 16)
    steel = pyc.Material("steel")
    steel.set_mech_props(7.85e-9, 210000.0, 0.3)
    model.set_matl(steel, [plate] + pins)
    model.set_eshape(shape, 2)
    model.set_etype("plstress", [plate] + pins, 10.0)
    model.mesh(0.5, "gmsh")
    model.set_gravity(9810.0, plate)
    bottom = [l for l in plate.signlines if abs(l.pt(0).x) < 1e-9 and abs(l.pt(1).x) < 1e-9]
    model.set_load("force", bottom, SIDE_PER_NODE, "y")
    for loop in bores:
        model.set_constr("fix", list(loop), "x")
        model.set_constr("fix", list(loop), "y")
    for hole, pin in zip(holes, pin_arcs):
        model.set_contact_linear(list(pin), list(hole), 1e7)
    prob = pyc.Problem(model, "struct")
    pyc.environment.CCX = "true"     # write the deck only
    try:
        prob.solve()
    except Exception as exc:         # pycalculix reads results ccx did not write
        print("pycalculix after writing the deck:", repr(exc))
    add_reaction_prints(name + ".inp")


def add_reaction_prints(path):
    """One *NODE PRINT, TOTALS=ONLY of RF per held set, before *END STEP."""
    with open(path) as f:
        deck = f.read()
    held = []
    lines = deck.splitlines()
    for k, line in enumerate(lines):
        if line.upper().startswith("*BOUNDARY"):
            s = lines[k + 1].split(",")[0]
            if s not in held:
                held.append(s)
    prints = "".join(f"*NODE PRINT,NSET={s},TOTALS=ONLY\nRF\n" for s in held)
    with open(path, "w") as f:
        f.write(deck.replace("*END STEP", prints + "*END STEP"))


if __name__ == "__main__":
    main(sys.argv[1])
