"""Abaqus/CAE input: *PART, *ASSEMBLY, *INSTANCE (docs/keywords.md, "Abaqus/CAE
input"). The example input/examples/block_on_base.inp gives the results of the
same model written flat; two instances of one part are two bodies; node labels
INSTANCE.NUMBER in *BOUNDARY and *CLOAD; cards out of place stop at their line."""
import glob
import math
import os
import subprocess

from helpers import ROOT, WORK, Skip, run_deck

EXAMPLE = os.path.join(ROOT, "input", "examples", "block_on_base.inp")
DEBUG = os.path.join(ROOT, "build-debug", "cfe2d")
ASAN = os.path.join(ROOT, "build-asan", "cfe2d")


# ----------------------------------------------------------------- helpers

def keyword(line):
    """(NAME, {PARAM: value}) of a keyword line, upper case."""
    fields = [f.strip() for f in line[1:].split(",")]
    params = {}
    for f in fields[1:]:
        if f:
            k, _, v = f.partition("=")
            params[k.strip().upper()] = v.strip()
    return " ".join(fields[0].upper().split()), params


def read_cae(path):
    """The parts (nodes, elements) and instances (part, placement) of a CAE
    deck: what a user flattening it by hand takes from it."""
    parts, instances = {}, []
    part = inst = card = None
    for raw in open(path):
        line = raw.strip()
        if not line or line.startswith("**"):
            continue
        if line.startswith("*"):
            card, params = keyword(line)
            if card == "PART":
                part = parts.setdefault(params["NAME"].upper(), {"nodes": {}, "elements": []})
            elif card == "END PART":
                part = None
            elif card == "INSTANCE":
                inst = {"name": params["NAME"].upper(), "part": params["PART"].upper(), "data": []}
                instances.append(inst)
            elif card == "END INSTANCE":
                inst = None
            elif card == "ELEMENT" and part is not None:
                etype = params["TYPE"].upper()
            continue
        values = [v.strip() for v in line.split(",") if v.strip()]
        if card == "NODE" and part is not None:
            part["nodes"][int(values[0])] = (float(values[1]), float(values[2]))
        elif card == "ELEMENT" and part is not None:
            part["elements"].append((etype, int(values[0]), [int(v) for v in values[1:]]))
        elif card == "INSTANCE" and inst is not None:
            inst["data"].append([float(v) for v in values])
    return parts, instances


def place(xy, data):
    """A part's point placed as Abaqus places an instance: translated, then
    turned about the axis a -> b (right-handed) by the angle in degrees."""
    x, y = xy
    if data:
        x, y = x + data[0][0], y + data[0][1]
    if len(data) > 1:
        ax, ay, az, bx, by, bz, angle = data[1]
        t = math.radians(angle) * (1 if bz > az else -1)
        c, s = math.cos(t), math.sin(t)
        if angle % 90.0 == 0.0:
            # as a hand-written flat deck has it (cos 90 degrees is 0, not 6e-17)
            c, s = round(c), round(s)
        dx, dy = x - ax, y - ay
        x, y = ax + c * dx - s * dy, ay + s * dx + c * dy
    return x, y


def by_label(block, key):
    """{label: row} of a listing block of a deck with instances (the label
    column ends each row)."""
    return {row[-1]: row for row in block.rows} if key == "label" else \
        {int(row[0]): row for row in block.rows}


def compare_rows(cae, flat, ids, columns, what, rtol=1e-9):
    """Rows of the CAE run (by label) against the flat run's (by id), for
    the columns; relative to the largest value of each column."""
    rc, rf = by_label(cae, "label"), by_label(flat, "id")
    assert len(rc) == len(rf) == len(ids), (what, len(rc), len(rf), len(ids))
    worst = 0.0
    for col in columns:
        j = cae.columns.index(col)
        scale = max(abs(r[j]) for r in rf.values()) or 1.0
        for label, fid in ids.items():
            a, b = rc[label][j], rf[fid][j]
            worst = max(worst, abs(a - b) / scale)
    assert worst <= rtol, f"{what}: CAE and flat differ by {worst:.2e} of the largest value"
    return worst


def stops_at(name, deck, bad_line, fragment):
    """The deck stops with file:line: error at the (unique) bad_line, saying fragment."""
    run = run_deck(name, deck)
    lines = deck.splitlines()
    assert lines.count(bad_line) == 1, bad_line
    line = lines.index(bad_line) + 1
    assert run.rc == 1 and f"{name}.inp:{line}: error:" in run.stderr, run.stderr
    assert fragment in run.stderr, run.stderr
    return run


# ------------------------------------------------- the example against flat

def flat_example():
    """input/examples/block_on_base.inp written flat: the instances' nodes
    and elements renumbered (1000 k + label for the k-th instance), placed
    here, and the sets and surfaces named directly. Returns the deck and
    {CAE label: flat id} of nodes and elements."""
    parts, instances = read_cae(EXAMPLE)
    nodes, elements, node_ids, elem_ids = [], [], {}, {}
    for k, inst in enumerate(instances, 1):
        part = parts[inst["part"]]
        elements.append(f"*ELEMENT, TYPE=CPE4, ELSET={inst['part']}")
        for label, xy in part["nodes"].items():
            x, y = place(xy, inst["data"])
            nodes.append(f"{1000 * k + label}, {x!r}, {y!r}")
            node_ids[f"{inst['name']}.{label}"] = 1000 * k + label
        for etype, label, conn in part["elements"]:
            assert etype == "CPE4"
            elements.append(", ".join(str(1000 * k + v) for v in [label] + conn))
            elem_ids[f"{inst['name']}.{label}"] = 1000 * k + label
    assert [i["name"] for i in instances] == ["BASE-1", "BLOCK-1"]
    deck = "\n".join(["*HEADING", "block on base, written flat", "*NODE"] + nodes + elements + [
        "*NSET, NSET=BASE_BOTTOM, GENERATE", "1001, 1009",
        "*NSET, NSET=ANCHOR", "1005",
        "*NSET, NSET=TOP", "2005, 2010, 2015",
        "*ELSET, ELSET=BASE_TOP_FACES, GENERATE", "1009, 1016",
        "*SURFACE, NAME=BASE_TOP", "BASE_TOP_FACES, S3",
        "*ELSET, ELSET=BLOCK_BOTTOM_FACES", "2001, 2005",
        "*SURFACE, NAME=BLOCK_BOTTOM", "BLOCK_BOTTOM_FACES, S4",
        "*MATERIAL, NAME=ALUMINIUM", "*ELASTIC", "70000., 0.33",
        "*MATERIAL, NAME=STEEL", "*ELASTIC", "210000., 0.3",
        "*SOLID SECTION, ELSET=BASE, MATERIAL=STEEL", "1.",
        "*SOLID SECTION, ELSET=BLOCK, MATERIAL=ALUMINIUM", "1.",
        "*SURFACE INTERACTION, NAME=HARD", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD",
        "*CONTACT PAIR, INTERACTION=HARD, SMALL SLIDING", "BLOCK_BOTTOM, BASE_TOP",
        "*BOUNDARY", "BASE_BOTTOM, 2, 2", "ANCHOR, 1, 1",
        "*STEP", "*STATIC", "0.5, 1.",
        "*BOUNDARY", "TOP, 1, 1", "TOP, 2, 2, -0.01",
        "*NODE PRINT", "U, RF", "*NODE PRINT", "S", "*EL PRINT", "S",
        "*END STEP"]) + "\n"
    return deck, node_ids, elem_ids


def test_cae_example_same_results_as_flat_deck():
    """input/examples/block_on_base.inp (two parts, a translated base, a block
    translated and turned by 90 degrees about z, assembly sets and a surface
    through INSTANCE=, a part-level surface as Base-1.Top, a contact pair, a
    step) gives the displacements, reactions, stresses and contact forces of
    the same model written flat, to round-off."""
    cae = run_deck("parts_example", path=EXAMPLE).ok()
    deck, node_ids, elem_ids = flat_example()
    flat = run_deck("parts_example_flat", deck).ok()
    # The instances' ids: the base's labels, the block's above them.
    inst = {r[0]: r for r in cae.listing.header[[b.name for b in cae.listing.header].index("INSTANCES")].rows}
    assert inst["BASE-1"][1:6] == ["BASE", 27.0, 0.0, 16.0, 0.0], inst
    assert inst["BLOCK-1"][1:6] == ["BLOCK", 15.0, 27.0, 8.0, 16.0], inst
    assert len(cae.listing.increments) == len(flat.listing.increments) == 2
    worst = 0.0
    for ic, iflat in zip(cae.listing.increments, flat.listing.increments):
        assert ic.attrs == iflat.attrs
        worst = max(worst, compare_rows(ic.block("NODE U"), iflat.block("NODE U"), node_ids, ["U1", "U2"], "U"))
        worst = max(worst, compare_rows(ic.block("NODE RF"), iflat.block("NODE RF"), node_ids, ["RF1", "RF2"], "RF"))
        worst = max(worst, compare_rows(ic.block("NODE S"), iflat.block("NODE S"), node_ids,
                                        ["S11", "S22", "S33", "S12"], "nodal S"))
        sc, sf = ic.block("ELEMENT S"), iflat.block("ELEMENT S")
        assert len(sc) == len(sf) == 4 * len(elem_ids)
        rows_f = {(int(r[0]), int(r[1])): r for r in sf.rows}
        scale = max(abs(v) for r in sf.rows for v in r[2:6])
        for r in sc.rows:
            f = rows_f[(elem_ids[r[-1]], int(r[1]))]
            worst = max(worst, max(abs(a - b) for a, b in zip(r[2:6], f[2:6])) / scale)
        # contact: the slave rows, node by node, and the totals
        cs, fs = ic.block("CONTACT SLAVE"), iflat.block("CONTACT SLAVE")
        assert cs.attrs["surface"] == "BLOCK-BOTTOM" and len(cs) == len(fs) == 3
        worst = max(worst, compare_rows(cs, fs, {l: node_ids[l] for l in cs["label"]},
                                        ["x", "y", "gap", "force", "pressure"], "contact slave"))
        assert cs["state"] == fs["state"] == ["CLOSED"] * 3
        tc, tf = ic.block("CONTACT SUMMARY")["total_force"][0], iflat.block("CONTACT SUMMARY")["total_force"][0]
        assert abs(tc - tf) <= 1e-9 * tf and tf > 100.0, (tc, tf)
        rc = dict(zip(ic.block("REACTIONS")["set"], zip(ic.block("REACTIONS")["RF1"], ic.block("REACTIONS")["RF2"])))
        rf = dict(zip(iflat.block("REACTIONS")["set"],
                      zip(iflat.block("REACTIONS")["RF1"], iflat.block("REACTIONS")["RF2"])))
        for c, f in (("SET-TOP", "TOP"), ("BASE-1.BOTTOM", "BASE_BOTTOM"), ("SET-ANCHOR", "ANCHOR")):
            assert max(abs(a - b) for a, b in zip(rc[c], rf[f])) <= 1e-9 * tf, (c, rc[c], rf[f])
        # the top holds the block down against the contact force
        assert abs(rc["SET-TOP"][1] + tc) <= 1e-9 * tc
    print(f"  block on base: CAE and flat decks agree to {worst:.1e} of the largest values")


# ------------------------------------------------ two instances of one part

# A plate of 3 x 2 plane-stress quads, 1 x 0.4, in its part coordinates;
# Left: its edge x = 0, Right: x = 1.
PLATE_PART = """*Part, name=Plate
*Node
 1, 0., 0.
 2, 0.333333333333, 0.
 3, 0.666666666667, 0.
 4, 1., 0.
 5, 0., 0.2
 6, 0.35, 0.21
 7, 0.65, 0.19
 8, 1., 0.2
 9, 0., 0.4
 10, 0.333333333333, 0.4
 11, 0.666666666667, 0.4
 12, 1., 0.4
*Element, type=CPS4
 1, 1, 2, 6, 5
 2, 2, 3, 7, 6
 3, 3, 4, 8, 7
 4, 5, 6, 10, 9
 5, 6, 7, 11, 10
 6, 7, 8, 12, 11
*Elset, elset=All, generate
 1, 6, 1
*Nset, nset=Left
 1, 5, 9
*Nset, nset=Right
 4, 8, 12
*Solid Section, elset=All, material=Steel
0.1,
*End Part
"""

MATERIAL = """*Material, name=Steel
*Elastic
200000., 0.3
"""

# Plate-2 is moved by (2, 1), then turned by 30 degrees about an axis
# through (1.5, 0.5) pointing down (-z): clockwise, i.e. by -30 degrees.
TURN = -30.0
PLATE2_PLACEMENT = """ 2., 1., 0.
 1.5, 0.5, 2., 1.5, 0.5, -1., 30.
"""


def turned(v, degrees=TURN):
    t = math.radians(degrees)
    return (math.cos(t) * v[0] - math.sin(t) * v[1], math.sin(t) * v[0] + math.cos(t) * v[1])


def two_plates(plate2_instance):
    f = turned((10.0, 4.0))
    return (PLATE_PART + """*Assembly, name=Assembly
*Instance, name=Plate-1, part=Plate
*End Instance
""" + plate2_instance + """*End Assembly
""" + MATERIAL + f"""*Boundary
Plate-1.Left, ENCASTRE
Plate-2.Left, ENCASTRE
*Step
*Static
*Cload
Plate-1.Right, 1, 10.
Plate-1.Right, 2, 4.
Plate-2.Right, 1, {f[0]!r}
Plate-2.Right, 2, {f[1]!r}
*Node Print
U
*End Step
""")


def turned_copies_agree(run):
    """Plate-2, loaded by Plate-1's loads turned with it, moves as Plate-1
    turned: u(Plate-2.n) = R u(Plate-1.n) for every label n; so are the
    reactions of the two Left sets."""
    inc = run.listing.increments[-1]
    u = {r[-1]: (r[1], r[2]) for r in inc.block("NODE U").rows}
    assert len(u) == 24
    scale = max(math.hypot(*v) for v in u.values())
    worst = max(math.dist(turned(u[f"PLATE-1.{n}"]), u[f"PLATE-2.{n}"]) for n in range(1, 13)) / scale
    assert worst < 1e-9, worst
    rf = {r[0]: (r[1], r[2]) for r in inc.block("REACTIONS").rows}
    assert math.dist(turned(rf["PLATE-1.LEFT"]), rf["PLATE-2.LEFT"]) < 1e-9 * math.hypot(10.0, 4.0), rf
    return u


def test_two_instances_of_one_part_are_two_bodies():
    """One part instanced twice: each instance has its own nodes and
    elements (ids 1..12 and 13..24, labels PLATE-1.n and PLATE-2.n), its own
    sets (Plate-1.Left, Plate-2.Right) and its section; both are loaded.
    Plate-2 is turned by -30 degrees (30 about an axis pointing down) about
    a point off the origin: with its loads turned the same way it moves as
    Plate-1 turned, label by label."""
    run = run_deck("parts_two_instances", two_plates("*Instance, name=Plate-2, part=Plate\n" + PLATE2_PLACEMENT +
                                                     "*End Instance\n")).ok()
    rows = run.listing.increments[-1].block("NODE U").rows
    assert [int(r[0]) for r in rows] == list(range(1, 25))
    assert [r[-1] for r in rows] == [f"PLATE-1.{n}" for n in range(1, 13)] + [f"PLATE-2.{n}" for n in range(1, 13)]
    u = turned_copies_agree(run)
    assert min(math.hypot(*u[f"PLATE-{k}.12"]) for k in (1, 2)) > 1e-4, u
    inst = {r[0]: r for r in next(b for b in run.listing.header if b.name == "INSTANCES").rows}
    assert inst["PLATE-2"][1:9] == ["PLATE", 12.0, 12.0, 6.0, 6.0, 2.0, 1.0, TURN], inst


def test_independent_instance_holds_its_mesh():
    """An independent instance (CAE writes its mesh between *INSTANCE and
    *END INSTANCE, its part empty) is placed and read as a part's copy."""
    mesh = PLATE_PART.split("*Node", 1)[1].split("*End Part")[0]
    deck = two_plates("*Instance, name=Plate-2, part=Empty\n" + PLATE2_PLACEMENT + "*Node" + mesh + "*End Instance\n")
    deck = "*Part, name=Empty\n*End Part\n" + deck
    turned_copies_agree(run_deck("parts_independent_instance", deck).ok())


# ------------------------------------------------------------ node labels

LABELS = PLATE_PART + """*Assembly, name=Assembly
*Instance, name=Plate-1, part=Plate
*End Instance
*Instance, name=Plate-2, part=Plate
 0., 1., 0.
*End Instance
*End Assembly
""" + MATERIAL + """*Step
*Static
*Boundary
{bc}
Plate-2.Left, 1, 2
Plate-1.4, 1, 1, 0.001
Plate-2.Right, 1, 1, 0.001
*Cload
{cload}
Plate-2.12, 2, -5.
*Node Print
U, RF
*End Step
"""


def test_node_labels_in_boundary_and_cload():
    """`Plate-1.9` names node 9 of instance Plate-1 in *BOUNDARY and *CLOAD:
    Plate-1 held and loaded through labels moves as Plate-2 held through
    its part's set (Plate-2.Left) and loaded through its label."""
    deck = LABELS.format(bc="Plate-1.1, 1, 2\nPlate-1.5, 1, 2\nPlate-1.9, 1, 2\nPlate-1.8, 1, 1, 0.001\n"
                            "Plate-1.12, 1, 1, 0.001",
                         cload="Plate-1.12, 2, -5.")
    run = run_deck("parts_labels", deck).ok()
    inc = run.listing.increments[-1]
    u = {r[-1]: (r[1], r[2]) for r in inc.block("NODE U").rows}
    rf = {r[-1]: (r[1], r[2]) for r in inc.block("NODE RF").rows}
    scale = max(math.hypot(*v) for v in u.values())
    assert abs(u["PLATE-1.12"][0] - 0.001) < 1e-15 and u["PLATE-1.12"][1] < -1e-4, u["PLATE-1.12"]
    for n in range(1, 13):
        assert math.dist(u[f"PLATE-1.{n}"], u[f"PLATE-2.{n}"]) < 1e-9 * scale, n
        assert math.dist(rf[f"PLATE-1.{n}"], rf[f"PLATE-2.{n}"]) < 1e-9 * 50.0, n


def test_label_errors_stop_at_their_line():
    """A label the instance does not have, an instance that does not exist,
    and a bare number where there are no assembly-level nodes stop at the
    line, saying how an instance's node is named."""
    ok_bc = "Plate-1.1, 1, 2\nPlate-1.5, 1, 2\nPlate-1.9, 1, 2"
    for name, bc, cload, bad, fragment in (
            ("parts_label_missing", ok_bc, "Plate-1.99, 2, -5.", "Plate-1.99, 2, -5.",
             "undefined node PLATE-1.99 (instance PLATE-1 has no node 99)"),
            ("parts_label_instance", ok_bc + "\nPlate-3.4, 2, 2", "Plate-1.12, 2, -5.", "Plate-3.4, 2, 2",
             "undefined instance PLATE-3"),
            ("parts_label_bare", ok_bc, "12, 2, -5.", "12, 2, -5.",
             "undefined node 12 at the assembly level (a member of an instance is named INSTANCE.NUMBER, "
             "e.g. PLATE-1.12)")):
        stops_at(name, LABELS.format(bc=bc, cload=cload), bad, fragment)


# ------------------------------------------------------------------ errors

ASSEMBLY = """*Assembly, name=Assembly
*Instance, name=Plate-1, part=Plate
*End Instance
*End Assembly
"""
STEP = """*Boundary
Plate-1.Left, ENCASTRE
*Step
*Static
*Cload
Plate-1.12, 2, -1.
*End Step
"""


def test_rotation_about_an_in_plane_axis_is_an_error_at_its_line():
    """A rotation about an axis not parallel to z (here x) would turn the part
    out of the plane: an error at the rotation line. Its angle 0, and any
    angle about an axis along z or against it, are accepted."""
    bad = " 0., 0., 0., 1., 0., 0., 90."
    deck = PLATE_PART + ASSEMBLY.replace("part=Plate\n", "part=Plate\n 0., 0., 0.\n" + bad + "\n") + MATERIAL + STEP
    stops_at("parts_inplane_axis", deck, bad, "not parallel to z")
    tilted = " 0., 0., 0., 0.1, 0., 1., 45."
    deck = PLATE_PART + ASSEMBLY.replace("part=Plate\n", "part=Plate\n 0., 0., 0.\n" + tilted + "\n") + MATERIAL + STEP
    stops_at("parts_tilted_axis", deck, tilted, "turns the part out of the x-y plane")
    for k, line in enumerate((" 0., 0., 0., 1., 0., 0., 0.", " 1., 1., 5., 1., 1., 0., 45.")):
        deck = PLATE_PART + ASSEMBLY.replace("part=Plate\n", "part=Plate\n 0., 0., 0.\n" + line + "\n") + \
            MATERIAL + STEP
        run_deck(f"parts_axis_ok{k}", deck).ok()


def test_instance_of_undefined_part_is_an_error_at_its_line():
    bad = "*Instance, name=Plate-2, part=Plat"
    deck = PLATE_PART + ASSEMBLY.replace("*End Assembly", bad + "\n*End Instance\n*End Assembly") + MATERIAL + STEP
    stops_at("parts_undefined_part", deck, bad, "*INSTANCE of part PLAT, which no *PART before it defines (parts: PLATE)")


def test_cae_structure_errors_stop_at_their_line():
    """*PART nested or unclosed, a card a part cannot hold, mesh cards outside
    parts and assembly, *INSTANCE outside the assembly, an unclosed instance
    or assembly, a duplicate instance, INSTANCE= of an undefined instance:
    each an error at its line."""
    head, tail = PLATE_PART.split("*Elset, elset=All")
    cases = (
        ("nested", head + "*Part, name=Inner\n*Elset, elset=All" + tail + ASSEMBLY + MATERIAL + STEP,
         "*Part, name=Inner", "*PART inside *PART PLATE: its *END PART is missing"),
        ("unclosed", PLATE_PART.replace("*End Part\n", ""), "*Part, name=Plate", "*PART PLATE without *END PART"),
        ("material_in_part", PLATE_PART.replace("*End Part", MATERIAL + "*End Part") + ASSEMBLY + STEP,
         "*Material, name=Steel", "*MATERIAL cannot be inside *PART ... *END PART"),
        ("node_outside", PLATE_PART + ASSEMBLY + "*Node, nset=Extra\n 100, 5., 5.\n" + MATERIAL + STEP,
         "*Node, nset=Extra", "*NODE outside *PART and *ASSEMBLY"),
        ("flat_then_part", "*Node\n 100, 5., 5.\n" + PLATE_PART + ASSEMBLY + MATERIAL + STEP, "*Part, name=Plate",
         "a deck with parts defines its mesh inside them"),
        ("instance_outside", PLATE_PART + "*Instance, name=Plate-1, part=Plate\n*End Instance\n" + MATERIAL + STEP,
         "*Instance, name=Plate-1, part=Plate", "*INSTANCE outside *ASSEMBLY"),
        ("instance_unclosed", PLATE_PART + ASSEMBLY.replace("*End Instance\n", "") + MATERIAL + STEP,
         "*End Assembly", "*END ASSEMBLY inside *INSTANCE PLATE-1: its *END INSTANCE is missing"),
        ("assembly_unclosed", PLATE_PART + ASSEMBLY.replace("*End Assembly\n", "") + MATERIAL + STEP,
         "*Assembly, name=Assembly", "*ASSEMBLY without *END ASSEMBLY"),
        ("duplicate_instance", PLATE_PART + ASSEMBLY.replace("*End Assembly", "*Instance, name=plate-1, part=Plate\n"
                                                            "*End Instance\n*End Assembly") + MATERIAL + STEP,
         "*Instance, name=plate-1, part=Plate", "duplicate instance PLATE-1"),
        ("nset_instance", PLATE_PART + ASSEMBLY.replace("*End Assembly", "*Nset, nset=X, instance=Plate-9\n 1\n"
                                                        "*End Assembly") + MATERIAL + STEP,
         "*Nset, nset=X, instance=Plate-9", "undefined instance PLATE-9"),
        ("no_assembly", PLATE_PART + MATERIAL + "*Step\n*Static\n*End Step\n", "*Part, name=Plate",
         "this deck has no *ASSEMBLY"),
        ("part_error", PLATE_PART.replace(" 6, 7, 8, 12, 11", " 6, 7, 8, 12, 13") + ASSEMBLY + MATERIAL + STEP,
         " 6, 7, 8, 12, 13", "undefined node 13 (reading part PLATE for its instance PLATE-1)"),
    )
    for name, deck, bad, fragment in cases:
        stops_at("parts_" + name, deck, bad, fragment)


def test_assembly_sets_name_instance_members():
    """At the assembly level: *NSET/*ELSET with INSTANCE= take the part's
    numbers and set names, lists may name INSTANCE.NUMBER and INSTANCE.SET,
    and a part never instanced is a warning."""
    deck = PLATE_PART + "*Part, name=Spare\n*Node\n 1, 0., 0.\n*End Part\n" + ASSEMBLY.replace("*End Assembly", """\
*Nset, nset=Held, instance=Plate-1
 Left
*Nset, nset=Loaded
 Plate-1.12, Plate-1.8
*Elset, elset=Both, instance=Plate-1, generate
 1, 6, 2
*Elset, elset=Both
 Plate-1.2
*End Assembly""") + MATERIAL + """*Boundary
Held, ENCASTRE
*Step
*Static
*Cload
Loaded, 2, -1.
*Node Print, nset=Held
RF
*El Print, elset=Both
S
*End Step
"""
    run = run_deck("parts_assembly_sets", deck).ok()
    assert "part SPARE has no *INSTANCE: its nodes and elements are not in the model" in run.stderr, run.stderr
    inc = run.listing.increments[-1]
    assert inc.block("NODE RF", set="HELD")["label"] == ["PLATE-1.1", "PLATE-1.5", "PLATE-1.9"]
    assert abs(sum(inc.block("NODE RF", set="HELD")["RF2"]) - 2.0) < 1e-9
    labels = inc.block("ELEMENT S", set="BOTH")["label"]
    assert sorted(set(labels)) == ["PLATE-1.1", "PLATE-1.2", "PLATE-1.3", "PLATE-1.5"], labels


def test_assembly_level_nodes_keep_their_numbers():
    """An assembly-level node (a reference point) keeps its number, 50; the
    instance's ids start above it (offset 50); an assembly-level spring joins
    Plate-1.12 to it, and a plain 50 in *BOUNDARY is that node."""
    deck = PLATE_PART + """*Assembly, name=Assembly
*Instance, name=Plate-1, part=Plate
*End Instance
*Node
 50, 1.5, 0.4
*Element, type=SPRING2, elset=Pull
 7, Plate-1.12, 50
*Spring, elset=Pull
2, 2
1000.
*End Assembly
""" + MATERIAL + """*Boundary
Plate-1.Left, ENCASTRE
50, 1, 1
*Step
*Static
*Boundary
50, 2, 2, -0.01
*Node Print
U
*El Print, elset=Pull
S
*End Step
"""
    run = run_deck("parts_assembly_node", deck).ok()
    inst = next(b for b in run.listing.header if b.name == "INSTANCES").rows
    assert inst[0][:6] == ["PLATE-1", "PLATE", 12.0, 50.0, 6.0, 7.0], inst
    inc = run.listing.increments[-1]
    # (the listing reader reads the label 50 as a number)
    u = {r[-1]: r for r in inc.block("NODE U").rows}
    assert u[50.0][0] == 50 and u[50.0][2] == -0.01 and u["PLATE-1.12"][0] == 62, (u[50.0], u["PLATE-1.12"])
    force = inc.block("ELEMENT S", set="PULL")["S11"][0]
    assert abs(force - 1000.0 * (u["PLATE-1.12"][2] - u[50.0][2])) < 1e-9 * abs(force) and force > 1.0, force


def test_debug_and_sanitizer_builds_on_these_decks():
    """The debug build (-fcheck=all) and the sanitizer build run the example
    and every deck above (good and broken) with the optimised build's exit
    status and no runtime report: a part's cards are read again for every
    instance (recursion, bounds)."""
    builds = [b for b in (DEBUG, ASAN) if os.path.exists(b)]
    if not builds:
        raise Skip("neither build-debug/cfe2d nor build-asan/cfe2d is built (make debug, make sanitize)")
    decks = [EXAMPLE] + sorted(glob.glob(os.path.join(WORK, "parts_*", "parts_*.inp")))
    assert len(decks) > 20, "run after the other tests of this module"
    env = dict(os.environ, ASAN_OPTIONS="detect_leaks=0:abort_on_error=0", UBSAN_OPTIONS="print_stacktrace=1")
    out = os.path.join(WORK, "parts_builds")
    os.makedirs(out, exist_ok=True)
    for deck in decks:
        rcs = set()
        for exe in [os.path.join(ROOT, "bin", "cfe2d")] + builds:
            r = subprocess.run([exe, "-q", "-o", out, deck], capture_output=True, text=True, timeout=900, env=env)
            for rep in ("ERROR: AddressSanitizer", "runtime error:", "Fortran runtime", "Backtrace"):
                assert rep not in r.stderr, (exe, deck, r.stderr[-3000:])
            rcs.add(r.returncode)
        assert len(rcs) == 1 and rcs <= {0, 1}, (deck, rcs)
    print(f"  {len(decks)} decks through {len(builds)} checked build(s)")


def test_cae_interaction_thickness_line():
    """Abaqus/CAE writes the out-of-plane thickness `1.,` under *Surface
    Interaction for 2D models: accepted when it is the sections' thickness
    (the example carries it), an error at its line when it is not."""
    with open(os.path.join(ROOT, "input", "examples", "block_on_base.inp")) as f:
        deck = f.read()
    assert "*Surface Interaction, name=IntProp-1\n1.,\n" in deck
    bad = deck.replace("*Surface Interaction, name=IntProp-1\n1.,\n", "*Surface Interaction, name=IntProp-1\n2.5,\n")
    stops_at("cae_thickness_2_5", bad, "2.5,", "differs from the section thickness")


def test_orientation_inside_a_part_turns_with_each_instance():
    """An *ORIENTATION inside the part (material axes at 20 degrees in the
    part's coordinates) of an orthotropic plate (E1 = 10 E2): each
    instance has its own (PLATE-1.OR, PLATE-2.OR: no duplicate) and
    Plate-2's turns with it, so with its loads turned it moves as Plate-1
    turned, label by label, to 1e-9 (as the isotropic plates above). Had
    the axes stayed fixed, the copies would differ: the same deck with
    Plate-2's orientation given outside the part (not turned) moves
    Plate-2 differently, by more than 1 % of the largest displacement."""
    ortho = """*Material, name=Steel
*Elastic, type=ENGINEERING CONSTANTS
200000., 20000., 20000., 0.3, 0.3, 0.3, 15000., 15000.,
15000.
"""
    axes = "*Orientation, name=Or\n0.9396926207859084, 0.3420201433256687, 0., " \
           "-0.3420201433256687, 0.9396926207859084, 0.\n"
    part = PLATE_PART.replace("*Solid Section, elset=All, material=Steel",
                              axes + "*Solid Section, elset=All, material=Steel, orientation=Or")
    deck = two_plates("*Instance, name=Plate-2, part=Plate\n" + PLATE2_PLACEMENT + "*End Instance\n")
    deck = deck.replace(PLATE_PART, part).replace(MATERIAL, ortho)
    assert deck.count("orientation=Or") == 1 and "ENGINEERING" in deck
    run = run_deck("parts_orientation", deck).ok()
    u = turned_copies_agree(run)
    # the model-level orientation of the same name is not turned with Plate-2
    fixed = deck.replace(axes, "").replace("*Assembly", axes + "*Assembly")
    inc = run_deck("parts_orientation_fixed", fixed).ok().listing.increments[-1]
    v = {r[-1]: (r[1], r[2]) for r in inc.block("NODE U").rows}
    scale = max(math.hypot(*w) for w in u.values())
    assert max(math.dist(u[f"PLATE-1.{n}"], v[f"PLATE-1.{n}"]) for n in range(1, 13)) < 1e-12 * scale
    assert max(math.dist(u[f"PLATE-2.{n}"], v[f"PLATE-2.{n}"]) for n in range(1, 13)) > 1e-2 * scale
