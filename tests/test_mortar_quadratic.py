"""Segment-to-segment contact with 3-node faces on the flagship geometry
(cylinder on plate, h = 0.1, the cylinder meshed at half the plate's
size, gmsh -order 2), the figures of issue 21 computed as
scripts/contact_accuracy.py computes them (contact_accuracy.figures: the
oscillation about the fitted Hertz ellipse, the largest nodal pressure
against the fitted p0, the slave-master difference, all relative to p0,
at the peak of the flagship history).

The coupling on 3-node faces: where the master surface is straight (the
flagship's plate) and the slave the finer side, the master-mesh
multipliers of
contact_master_multipliers (linear between the master corners, the
master side consistent, integrated over the master faces); elsewhere
the dual mortar. On the q8 case (gmsh's default recombination into
8-node quadrilaterals on both sides) the dual mortar missed the targets
(osc 0.84 %, s-m 4.3 %: a beat of the slave/master node offset,
docs/contact.md, "Quadratic faces: where the CPS8 figures come from");
the master-mesh multipliers meet them there and on gmsh's triangle
meshes (CPS6 on both sides), a CPS6 cylinder on the default CPS8 plate
(3-node master faces of 8-node quadrilaterals) and the mixed CPS8/CPS6
meshes of gmsh's simple recombination; and its answer does not depend on the penalty."""
import os
import shutil
import subprocess

from helpers import WORK, Skip

HERE = os.path.dirname(os.path.abspath(__file__))
GEO = os.path.join(os.path.dirname(HERE), "input", "hertz", "hertz.geo")
STS = ", TYPE=SURFACE TO SURFACE, EXACT"
NTS = ", TYPE=NODE TO SURFACE"
_CACHE = {}


def mesh(folder, layout):
    """The flagship geometry at h = 0.1, written to folder/hertz_mesh.inp
    (which contact_accuracy.write_case then takes as it is). layout:
    "plate8" 6-node triangles in the cylinder and gmsh's default 8-node
    quadrilaterals in the plate, "tri6" 6-node triangles in both,
    "simple" both recombined by gmsh's simple algorithm (8-node
    quadrilaterals and the 6-node triangles it leaves)."""
    os.makedirs(folder, exist_ok=True)
    with open(GEO) as f:
        geo = f.read()
    assert "Recombine Surface{1, 2};" in geo
    # surface 1 is the plate, 2 the cylinder (hertz.geo)
    geo = geo.replace("Recombine Surface{1, 2};", {"plate8": "Recombine Surface{1};", "tri6": "",
                                                    "simple": "Recombine Surface{1, 2};"}[layout])
    path = os.path.join(folder, "hertz.geo")
    with open(path, "w") as f:
        f.write(geo)
    subprocess.run(["gmsh", "-order", "2", "-setnumber", "Mesh.SecondOrderIncomplete", "1", "-setnumber",
                    "Mesh.RecombinationAlgorithm", "0" if layout == "simple" else "1", "-2", "-format", "inp",
                    "-setnumber", "Mesh.SaveGroupsOfNodes", "1", "-setnumber", "h", "0.1", "-o",
                    os.path.join(folder, "hertz_mesh.inp"), path], check=True, capture_output=True)


def fig(layout, params):
    """The figures of one run (cached per mesh layout and pair parameters)."""
    if shutil.which("gmsh") is None:
        raise Skip("gmsh is not installed")
    import contact_accuracy
    key = (layout, params)
    if key not in _CACHE:
        name = layout + "".join(c if c.isalnum() else "_" for c in params)
        folder = os.path.join(WORK, "mortar_quadratic", name)
        if os.path.exists(folder):
            shutil.rmtree(folder)
        if layout != "q8":
            mesh(folder, layout)
        deck = contact_accuracy.write_case(folder, "q8", params)
        with open(os.path.join(folder, "hertz_mesh.inp")) as f:
            text = f.read()
        if layout == "q8":
            assert "type=CPS8" in text
        else:
            assert "type=CPS6" in text and ("type=CPS8" in text) == (layout != "tri6")
        wall = contact_accuracy.run(deck)
        f = contact_accuracy.figures(os.path.splitext(deck)[0] + "_contact.csv")
        f["wall"] = wall
        _CACHE[key] = f
    return _CACHE[key]


def check_targets(label, sts, nts):
    print(f"  {label}: osc {sts['osc']:.3%} (nts {nts['osc']:.3%}), node_p0 {sts['node_p0']:+.3%} "
          f"(nts {nts['node_p0']:+.3%}), s-m {sts['s-m']:.3%} (nts {nts['s-m']:.3%}), P {sts['P']:.2f}")
    # issue 21's targets (measured: osc 0.187 %, node_p0 +0.110 %, s-m 0.47 %
    # on CPS6 | CPS6; 0.198 %, +0.111 %, 0.47 % on the CPS8 plate; 0.197 %,
    # +0.114 %, 0.48 % on the simple recombination; 0.189 %, +0.108 %,
    # 0.47 % on q8. The dual mortar: 0.065 %, 0.049 %, 0.069 %, 0.84 % osc)
    assert sts["osc"] < 0.005 and abs(sts["node_p0"]) < 0.01 and sts["s-m"] < 0.01, sts
    # and better than node-to-segment's Gauss points of the slave faces
    # (measured 0.48 %, +0.80 to +0.82 %, 1.0 % on all three)
    assert sts["osc"] < nts["osc"] and sts["s-m"] < nts["s-m"], (sts, nts)


def test_cps6_slave_and_master_meet_the_targets():
    check_targets("CPS6 cylinder on CPS6 plate", fig("tri6", STS), fig("tri6", NTS))


def test_cps6_slave_on_cps8_plate_meets_the_targets():
    """3-node master faces of 8-node quadrilaterals: the same figures."""
    check_targets("CPS6 cylinder on CPS8 plate", fig("plate8", STS), fig("plate8", NTS))


def test_simple_recombination_cps8_meets_the_targets():
    """8-node quadrilaterals (and the triangles gmsh's simple
    recombination leaves) on both sides, slave faces among them."""
    check_targets("CPS8/CPS6, simple recombination", fig("simple", STS), fig("simple", NTS))


def test_q8_master_mesh_multipliers_meet_the_targets():
    """The flagship's CPS8 case of scripts/contact_accuracy.py (gmsh's
    default recombination into 8-node quadrilaterals on both sides, h =
    0.1): the master-mesh multipliers on its straight 3-node master faces
    (contact_master_multipliers) meet issue 21's targets, which the dual
    mortar missed there (osc 0.84 %, s-m 4.3 %; measured now 0.19 %,
    +0.11 %, 0.47 %), and its total force agrees with the linear meshes'
    (13 917.7 to 13 921.9 on the default and coarse meshes, both
    couplings) to 0.1 % of 13 921.8 (measured 13 925.8; the dual mortar's
    13 887.8 is 0.24 % below)."""
    sts = fig("q8", STS)
    check_targets("CPS8 cylinder on CPS8 plate", sts, fig("q8", NTS))
    assert abs(sts["P"] / 13921.8 - 1) < 1e-3, sts


def test_exact_quadratic_faces_independent_of_the_penalty():
    """EXACT with PENALTY= 1e8 and 1e11 per area on the CPS6 | CPS8 mesh:
    the same contact force and oscillation to 1e-9."""
    a = fig("plate8", STS + ", PENALTY=1e8")
    b = fig("plate8", STS + ", PENALTY=1e11")
    print(f"  PENALTY 1e8 / 1e11: P {a['P']:.9f} / {b['P']:.9f}, osc {a['osc']:.6%} / {b['osc']:.6%}")
    assert abs(a["P"] - b["P"]) < 1e-9 * a["P"] and abs(a["osc"] - b["osc"]) < 1e-9, (a, b)
