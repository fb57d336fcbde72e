#!/usr/bin/env python3
"""Mutation fuzzer of cfe2d's deck reader and analysis.

Takes the project's own decks (input/examples, input/hertz with a small
gmsh mesh, decks written by the tests: contact, features, triangles, and
*EQUATION, *TIE, *PRE-TENSION SECTION, trusses, springs, point masses,
*NODAL THICKNESS, and nonlinear bodies: NLGEOM, *HYPERELASTIC, *PLASTIC,
*CONTROLS, follower pressures, a plastic collapse, as their tests write
them, and the O-ring example on a coarse mesh), mutates them with a fixed
seed (cards dropped, duplicated, moved or spliced in from another deck;
numbers replaced by 0, -1, 1e308, 1e-320, nan, inf, huge integers; lines
truncated, joined, deleted, made very long; CR-LF endings, binary bytes;
*INCLUDE of missing, self-including, directory and special files such as
/dev/zero and a FIFO; targeted at the constraint and element cards: a
field of their data lines replaced by a nasty value, a field of the same
line, or a node id or name of the deck; equations added in chains,
cycles, on a dof twice or a node itself; ties of empty, unknown, node or
the deck's surfaces; pre-tension cuts of the deck's surfaces; two nodes of
an element moved onto each other), runs every mutant on both builds under
a time and a memory limit and classifies each run:

  ok-error    non-zero exit with a "file:line: error:" or "cfe2d: error:" line
  ok-run      exit 0, a listing with increments, no NaN/Infinity or
              malformed number in the .out, .csv and .msh outputs
  crash       a signal, a Fortran runtime error or backtrace, an exit status
              other than 0/1, or a non-zero exit with no proper message
  hang        the time limit (or the output file size limit) was reached
  silent-bad  exit 0 but NaN/Infinity/malformed numbers in an output, no
              increment in the listing, a step that ran no increment or
              stopped before the end of its time period, or a model with
              no element

The two builds (optimised and debug) must also agree, on more than the
class: on every contact status (the state column of <job>_contact.csv and
the closed count of each CONTACT SUMMARY), the increments and their times,
the bisection notes, the coupling elements and contact equations, and the
error message of a run that stops (numbers with a fraction or an exponent
are masked: a last digit is no disagreement). These are defects; the
search path (each contact iteration's status changes, pivots and
factorisations), the other notes and warnings, and the nodes an error
names as examples of a round-off decision may differ and are only
reported ("search", "notes", "detail"; see AGREEMENT). A disagreement is
logged with the first item that differs, saved to
--out/failures/<mutant>-disagree-<kind>/ (up to --keep per kind), and
--minimise shrinks the first of each defect kind and seed deck, while both
builds still disagree on that kind, into --out/distinct/.

Failures are told apart by their class and a signature (the runtime error
and its source line, the signal, where a hang was: blocked in the kernel or
busy, and in which routines, from gdb on the debug build). Every failing
mutant (up to --keep per signature) is written to
--out/failures/<mutant>-<class>/: deck/ (the deck, its included files and
case.txt) and runs.txt (each build's class and stderr). --minimise shrinks
the first mutant of each distinct failure by delta debugging on its lines
while the same class and signature persist, into --out/distinct/. The
summary goes to stdout and --out/summary.txt; the exit status is 1 when any
crash, hang or silent-bad run or a defect disagreement of the builds was
seen (or a seed deck misbehaved).

  python3 scripts/fuzz.py --seed 1 --count 500 --out results/fuzz
  python3 scripts/fuzz.py --count 200 --minimise --time-limit 5
  python3 scripts/fuzz.py --replay tests/fuzz/empty_deck      # one saved deck folder
  python3 scripts/fuzz.py --seed 1 --index 17 --out /tmp/m17  # one mutant again

A saved deck folder holds the deck files and case.txt with key=value lines:
main= (the deck to run), fifo= and dir= (made before the run: git keeps
neither), expect= (ok-error, ok-run, or ok-error,ok-run when either is right;
for the regressions in tests/fuzz).
"""
import argparse
import os
import random
import re
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
DEFAULT_BUILDS = ("bin/cfe2d", "build-debug/cfe2d")

# Worst last: a deck's class is the worst class over the builds.
SEVERITY = ["ok-run", "ok-error", "silent-bad", "hang", "crash"]
FAILURES = ("crash", "hang", "silent-bad")

SPECIAL_NUMBERS = [b"0", b"-1", b"1e308", b"-1e308", b"1e-320", b"nan", b"inf", b"-inf",
                   b"2147483647", b"-2147483648", b"4294967299", b"1e20", b"1e160", b"20000",
                   b"1e-300", b"0.0", b"-0", b"99999999999999999999"]

# Hertz seed mesh: coarser than run_hertz.py's coarsest (0.1 mm gives 8800
# nodes) so that one run stays well under a second: about 900 nodes.
HERTZ_MESH = {"h": "0.5", "Lp": "20", "Hp": "20"}


# ----------------------------------------------------------------------------------- decks

@dataclass
class Deck:
    """A deck with the files it includes, and what must exist beside it."""
    name: str
    main: str
    files: dict                                    # relative path -> bytes
    fifos: list = field(default_factory=list)      # relative paths made with os.mkfifo
    dirs: list = field(default_factory=list)       # relative paths made as folders
    notes: list = field(default_factory=list)      # the mutations applied
    expect: str = "ok-run"                         # the class of the unmutated deck

    def copy(self):
        return Deck(self.name, self.main, dict(self.files), list(self.fifos), list(self.dirs),
                    list(self.notes), self.expect)

    @property
    def job(self):
        return os.path.splitext(os.path.basename(self.main))[0]

    def write(self, folder, meta=None):
        """Purpose: lay the deck out in folder, with case.txt describing it.
        Arguments: folder (created), meta: extra key=value pairs for case.txt."""
        os.makedirs(folder, exist_ok=True)
        for rel, data in self.files.items():
            path = os.path.join(folder, rel)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "wb") as f:
                f.write(data)
        for rel in self.dirs:
            os.makedirs(os.path.join(folder, rel), exist_ok=True)
        for rel in self.fifos:
            path = os.path.join(folder, rel)
            if not os.path.exists(path):
                os.makedirs(os.path.dirname(path), exist_ok=True)
                os.mkfifo(path)
        lines = [f"main={self.main}"] + [f"fifo={p}" for p in self.fifos] + [f"dir={p}" for p in self.dirs]
        lines += [f"# mutation: {n}" for n in self.notes]
        lines += [f"{k}={v}" for k, v in (meta or {}).items()]
        with open(os.path.join(folder, "case.txt"), "w") as f:
            f.write("\n".join(lines) + "\n")


def load_case(folder):
    """Purpose: read a saved deck folder (see the module docstring).
    Returns (Deck, meta dict of case.txt's other keys)."""
    meta, fifos, dirs = {}, [], []
    with open(os.path.join(folder, "case.txt")) as f:
        for line in f:
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            key, _, value = line.partition("=")
            if key == "fifo":
                fifos.append(value)
            elif key == "dir":
                dirs.append(value)
            else:
                meta[key] = value
    files = {}
    for base, subdirs, names in os.walk(folder):
        for name in names:
            path = os.path.join(base, name)
            rel = os.path.relpath(path, folder)
            if rel == "case.txt" or rel in fifos or not os.path.isfile(path):
                continue
            with open(path, "rb") as f:
                files[rel] = f.read()
    main = meta.pop("main", None)
    if main is None or main not in files:
        raise ValueError(f"{folder}/case.txt: main= must name a deck file of the folder")
    return Deck(os.path.basename(os.path.normpath(folder)), main, files, fifos, dirs), meta


SLOW_EXAMPLES = ("oring.inp",)


def example_seeds():
    """The self-contained examples. A deck that *INCLUDEs a file the folder
    does not hold (a gmsh mesh made from its .geo, e.g. sphere_on_block) is
    left out: its mesh is too large for quick mutants, and the Hertz seeds
    already carry a gmsh mesh. So is the O-ring (a mutant that keeps its
    contact from settling takes a minute of cut-backs on the debug build):
    a coarse O-ring is among the nonlinear seeds."""
    seeds = []
    folder = os.path.join(ROOT, "input", "examples")
    for name in sorted(os.listdir(folder)):
        if name.endswith(".inp") and name not in SLOW_EXAMPLES:
            with open(os.path.join(folder, name), "rb") as f:
                text = f.read()
            includes = re.findall(rb"(?im)^\*\s*INCLUDE\s*,\s*INPUT\s*=\s*([^,\r\n]+)", text)
            if any(not os.path.exists(os.path.join(folder, inc.strip().decode())) for inc in includes):
                continue
            seeds.append(Deck("examples/" + name[:-4], name, {name: text}))
    return seeds


def hertz_seeds(tmp, log):
    """The Hertz decks with a coarse mesh made by gmsh (none without gmsh)."""
    mesh = os.path.join(tmp, "hertz_mesh.inp")
    cmd = ["gmsh", "-2", "-format", "inp", "-setnumber", "Mesh.SaveGroupsOfNodes", "1"]
    for key, value in HERTZ_MESH.items():
        cmd += ["-setnumber", key, value]
    cmd += ["-o", mesh, os.path.join(ROOT, "input", "hertz", "hertz.geo")]
    try:
        subprocess.run(cmd, check=True, capture_output=True, timeout=120)
        with open(mesh, "rb") as f:
            mesh_text = f.read()
    except (OSError, subprocess.SubprocessError) as e:
        log(f"fuzz: no Hertz seeds (gmsh failed: {e})")
        return []
    seeds = []
    folder = os.path.join(ROOT, "input", "hertz")
    for name in sorted(os.listdir(folder)):
        if name.endswith(".inp"):
            with open(os.path.join(folder, name), "rb") as f:
                text = f.read()
            # only the decks on the mesh made here (hertz_point.inp has its own)
            if b"INPUT=hertz_mesh.inp" in text:
                seeds.append(Deck("hertz/" + name[:-4], name, {name: text, "hertz_mesh.inp": mesh_text}))
    return seeds


def test_seeds(log):
    """Decks written by the tests' own generators (skipped if they change shape)."""
    sys.path.insert(0, os.path.join(ROOT, "tests"))
    seeds = []
    makers = [("tests/bad_decks_good", _good_deck), ("tests/contact_push", _contact_push),
              ("tests/contact_force", _contact_force), ("tests/contact_unsettled", _contact_unsettled),
              ("tests/features_include", _features), ("tests/patch_tri", _patch_tri),
              ("tests/contact_friction", _contact_friction), ("tests/calculix_friction", _calculix_friction),
              ("tests/wear_punch", _wear_punch)] \
        + CARD_MAKERS + MORTAR_MAKERS
    for name, make in makers:
        try:
            main, files, *expect = make()
        except Exception as e:  # a test module was rewritten: fuzz the others
            log(f"fuzz: seed {name} skipped ({type(e).__name__}: {e})")
            continue
        seeds.append(Deck(name, main, {k: v.encode() for k, v in files.items()}, expect=(expect or ["ok-run"])[0]))
    return seeds


def _good_deck():
    import test_bad_decks
    return "good.inp", {"good.inp": test_bad_decks.GOOD}


def _contact_push():
    import test_contact as tc
    return "push.inp", {"push.inp": tc.blocks_deck([tc.push_step(3 * tc.G0, 2)])}


def _wear_punch():
    """test_wear's punch with Archard wear (*WEAR, a PERIODIC amplitude),
    held at its top only (partial slip), two cycles of 8 increments."""
    import test_wear as tw
    deck = tw.punch_deck(rigid=False, nx_base=14, base_span=(-2.0, 12.0), cycles=2, inc=0.125)
    assert "*WEAR" in deck
    return "wear.inp", {"wear.inp": deck}


def _contact_friction():
    """The pressed blocks of test_contact with Coulomb friction (cfe2d's own
    FRICTION= and STICK SLOPE=), pushed on after they touch."""
    import test_contact as tc
    deck = tc.blocks_deck([tc.push_step(3 * tc.G0, 2)])
    assert "*CONTACT PAIR" in deck
    return "friction.inp", {"friction.inp": deck.replace("*CONTACT PAIR", "*CONTACT PAIR, FRICTION=0.3, STICK SLOPE=1e5", 1)}


def _calculix_friction():
    """CalculiX's frictional blocks (tests/calculix): *SURFACE INTERACTION
    with *FRICTION (mu, stick slope), pressed, then pushed until they slide."""
    with open(os.path.join(ROOT, "tests", "calculix", "friction_blocks.inp")) as f:
        return "friction_blocks.inp", {"friction_blocks.inp": f.read()}


def _contact_force():
    import test_contact as tc
    return "force.inp", {"force.inp": tc.force_driven_deck(", OPEN PENALTY=1e-6")[0]}


def _contact_unsettled():
    import test_contact as tc
    deck = tc.blocks_deck([tc.push_step(0.5 * tc.G0), tc.push_step(3 * tc.G0)])
    deck = deck.replace("*CONTACT PAIR", "*CONTACT CONTROLS, MAXIT=1, CUTBACKS=2\n*CONTACT PAIR")
    return "unsettled.inp", {"unsettled.inp": deck}, "ok-error"   # stops after 2 bisections


def _features():
    import test_deck_features as tf
    step = "*STEP\n*STATIC\n0.5, 1.0\n*CLOAD, AMPLITUDE=UPDOWN\nRIGHT, 1, 3.0\n*NODE PRINT, NSET=RIGHT\nU, RF\n" \
           "*EL PRINT\nS\n*END STEP\n"
    amp = "*AMPLITUDE, NAME=UPDOWN\n0., 0., 0.5, 1., 1., 0.5\n"
    return "features.inp", {"features.inp": tf.block_deck(step, amp), **tf.FILES}


def _patch_tri():
    from decks import grid, node_lines, tri_lines
    nodes, ids, quads = grid(4, 3, 0.0, 2.0, 0.0, 1.5, distort=0.6)
    left = ", ".join(str(ids[0, j]) for j in range(4))
    right = ", ".join(str(ids[4, j]) for j in range(4))
    deck = (f"*HEADING\ntriangles\n*NODE, NSET=ALL\n{node_lines(nodes)}*ELEMENT, TYPE=CPE3, ELSET=PATCH\n"
            f"{tri_lines(quads)}*NSET, NSET=LEFT\n{left}\n*NSET, NSET=RIGHT\n{right}\n*MATERIAL, NAME=M\n"
            "*ELASTIC\n1000., 0.25\n*SOLID SECTION, ELSET=PATCH, MATERIAL=M\n0.7\n*SOLVER, TYPE=SKYLINE\n"
            "*BOUNDARY\nLEFT, ENCASTRE\n*STEP, INC=10\n*STATIC\n0.25, 1.0\n*BOUNDARY\nRIGHT, 1, 1, 0.01\n"
            "*NODE FILE\nU, S\n*EL FILE\nS\n*NODE PRINT\nU, RF\n*EL PRINT\nS, E\n*END STEP\n")
    return "patch.inp", {"patch.inp": deck}


def _equation_tied():
    import test_equation as te
    return "eq_tied.inp", {"eq_tied.inp": te.beam(True)}


def _equation_chain():
    import test_equation as te
    return "eq_chain.inp", {"eq_chain.inp": te.pressed_block(te.through_ref, te.ref_by_chain)}


def _equation_contact():
    import test_equation as te
    return "eq_contact.inp", {"eq_contact.inp": te.contact_deck()}


def _tie_patch():
    import test_constraint_decks as tc
    return "tie.inp", {"tie.inp": tc.tie_patch_deck(False, 4, 1e-4, "TOP, P, -3.\nRIGHT, P, -2.\n")}


def _tie_q8():
    import test_constraint_decks as tc
    return "tie8.inp", {"tie8.inp": tc.tie_patch_deck(True, 3, 1e-4, "RIGHT, P, -2.\n")}


def _pretension_bar():
    import test_constraint_decks as tc
    return "pret.inp", {"pret.inp": tc.bar("*BOUNDARY\nREF, 1, 1, 0.01\n")}


def _pretension_pret5():
    import test_constraint_decks as tc
    return "pret5.inp", {"pret5.inp": tc.two_square_cut_deck()}


def _truss_bar():
    import test_trusses as tt
    return "truss.inp", {"truss.inp": tt.bar_deck("T2D3")}


def _truss_v():
    import test_trusses as tt
    return "truss_v.inp", {"truss_v.inp": tt.v_truss(0.4)}


def _truss_block():
    import test_trusses as tt
    return "truss_block.inp", {"truss_block.inp": tt.block_with_truss(0.3)}


def _springs_grounded():
    import test_springs as ts
    return "springs.inp", {"springs.inp": ts.grounded()}


def _springs_axial():
    import test_springs as ts
    return "springa.inp", {"springa.inp": ts.v_springs(1.1)}


def _mass_bar():
    import test_point_mass as tm
    return "mass.inp", {"mass.inp": tm.bar(f"MA, GRAV, {tm.G}, 1., 0., 0.")}


def _mass_ring():
    import test_point_mass as tm
    return "mass_ring.inp", {"mass_ring.inp": tm.ring(f"*DLOAD\nMA, CENTRIF, {tm.W2}, 0., 0., 0., 0., 1., 0.\n")}


def _frequency_blocks():
    """*FREQUENCY after a preloading step: test_frequency's blocks pressed
    together (a linear penalty), then their modes."""
    import test_frequency as tf
    return "freq_blocks.inp", {"freq_blocks.inp": tf.blocks("contact", penalty=1e6)}


def _frequency_chain():
    """*FREQUENCY on trusses and point masses (test_frequency's chain)."""
    import test_frequency as tf
    return "freq_chain.inp", {"freq_chain.inp": tf.chain(5, 1000.0, 2.0)}


def _nodal_thickness():
    import test_nodal_thickness as tn
    from decks import grid, quad_lines
    nodes, ids, quads = grid(4, 3, 0.0, 2.0, 0.0, 1.0, distort=0.35)
    deck = tn.patch_deck("CPS4", nodes, quad_lines(quads), [4, 8, 12], 2, lambda x, y: 0.5 + 0.8 * y)
    return "thick.inp", {"thick.inp": deck}


def _nodal_thickness_taper():
    import test_nodal_thickness as tn
    return "taper.inp", {"taper.inp": tn.tapered_bar(2)[0]}


def _nl_neo_hooke():
    """A neo-Hookean block stretched under NLGEOM (automatic increments)."""
    import test_nonlinear_closed_forms as tn
    return "nl_hyper.inp", {"nl_hyper.inp": tn.block(1.5)}


def _nl_mooney_compression():
    import test_nonlinear_closed_forms as tn
    deck = tn.block(0.7, element="CPE8", material="*HYPERELASTIC, MOONEY-RIVLIN\n0.4, 0.1, 0.02\n")
    return "nl_mooney.inp", {"nl_mooney.inp": deck}


def _nl_plastic():
    """Plane-stress tension past yield and back (small strain, *PLASTIC, DIRECT)."""
    import test_nonlinear_closed_forms as tn
    material = "*ELASTIC\n200000., 0.3\n*PLASTIC\n200., 0.\n220., 0.5\n"
    steps = [("*STATIC, DIRECT\n0.25, 1.\n", 0.006), ("*STATIC\n0.25, 1.\n", -0.006)]
    return "nl_plastic.inp", {"nl_plastic.inp": tn.block(1.0, element="CPS4", material=material, nlgeom="",
                                                         steps=steps)}


def _nl_plastic_nlgeom():
    """Finite-strain plasticity: CAX4 block under NLGEOM."""
    import test_nonlinear_closed_forms as tn
    material = "*ELASTIC\n200000., 0.3\n*PLASTIC\n200., 0.\n400., 1.\n"
    deck = tn.block(1.05, element="CAX4", material=material)
    return "nl_plastic_nlgeom.inp", {"nl_plastic_nlgeom.inp": deck}


def _nl_follower_cylinder():
    """A neo-Hookean cylinder under a follower pressure (NLGEOM)."""
    import test_nonlinear_closed_forms as tn
    m = tn.annulus(1.0, 2.0, 4, 4)
    deck = tn.cylinder_deck(m, "CPE4", "*HYPERELASTIC, NEO HOOKE\n0.5, 0.01\n", 0.3, "*STATIC\n0.25, 1.\n")
    return "nl_follower.inp", {"nl_follower.inp": deck}


def _nl_collapse():
    """A perfectly plastic cylinder pushed past collapse: stops below the
    minimum increment."""
    import test_nonlinear_closed_forms as tn
    m = tn.annulus(1.0, 2.0, 4, 2, shape="Q8")
    deck = tn.cylinder_deck(m, "CPE8R", "*ELASTIC\n200000., 0.3\n*PLASTIC\n200., 0.\n", 300.0,
                            "*STATIC\n0.25, 1., 0.01\n")
    return "nl_collapse.inp", {"nl_collapse.inp": deck}, "ok-error"


def _nl_oring():
    """The O-ring example on a coarse mesh (scripts/oring.py): NLGEOM rubber,
    contact searched again every increment."""
    sys.path.insert(0, HERE)
    import oring
    return "oring_coarse.inp", {"oring_coarse.inp": oring.deck_text(2, 2, 10, "0.25, 1., 1e-3, 0.25")}


def _nl_controls():
    """Trusses under NLGEOM with *CONTROLS and three steps (NLGEOM carried, then off)."""
    import test_nonlinear_framework as tf
    second = ("*STEP\n*CONTROLS, PARAMETERS=FIELD\n1e-4, 1e-3\n*CONTROLS, PARAMETERS=TIME INCREMENTATION\n"
              "4, 8, 9, 16, 10, 4\n0.25, 0.5, 0.75, , , , 1.5\n*STATIC\n0.5, 1.\n*CLOAD\n4, 1, 0.\n*END STEP\n"
              "*STEP, NLGEOM=NO\n*CONTROLS, RESET\n*STATIC\n0.5, 1.\n*END STEP\n")
    return "nl_controls.inp", {"nl_controls.inp": tf.bar_deck(extra_steps=second)}


# Nonlinear bodies (NLGEOM, *HYPERELASTIC, *PLASTIC, *CONTROLS) as their tests write them.
NONLINEAR_MAKERS = [("tests/nl_neo_hooke", _nl_neo_hooke), ("tests/nl_mooney", _nl_mooney_compression),
                    ("tests/nl_plastic", _nl_plastic), ("tests/nl_plastic_nlgeom", _nl_plastic_nlgeom),
                    ("tests/nl_follower", _nl_follower_cylinder), ("tests/nl_collapse", _nl_collapse),
                    ("tests/nl_controls", _nl_controls), ("tests/nl_oring", _nl_oring)]


# Today's cards (*EQUATION, *TIE, *PRE-TENSION SECTION, trusses, springs,
# point masses, *NODAL THICKNESS) as the tests write them.
CARD_MAKERS = [("tests/equation_tied", _equation_tied), ("tests/equation_chain", _equation_chain),
               ("tests/equation_contact", _equation_contact), ("tests/tie_patch", _tie_patch),
               ("tests/tie_q8", _tie_q8), ("tests/pretension_bar", _pretension_bar),
               ("tests/pretension_pret5", _pretension_pret5), ("tests/truss_bar", _truss_bar),
               ("tests/truss_v", _truss_v), ("tests/truss_block", _truss_block),
               ("tests/springs_grounded", _springs_grounded), ("tests/springs_axial", _springs_axial),
               ("tests/mass_bar", _mass_bar), ("tests/mass_ring", _mass_ring),
               ("tests/frequency_blocks", _frequency_blocks), ("tests/frequency_chain", _frequency_chain),
               ("tests/nodal_thickness", _nodal_thickness), ("tests/nodal_thickness_taper", _nodal_thickness_taper)] \
    + NONLINEAR_MAKERS


def _mortar_exact():
    """Segment-to-segment contact with exact enforcement: 7 slave over 5
    master CPS4 faces (test_mortar's patch test)."""
    import test_contact_quadratic as tq
    return "mortar.inp", {"mortar.inp": tq.two_blocks("Q4", "Q4", 5, 7, pair=", TYPE=SURFACE TO SURFACE, EXACT")}


def _mortar_quadratic():
    """Segment-to-segment contact with a penalty: CPS6 slave faces on CPS8
    master faces."""
    import test_contact_quadratic as tq
    return "mortar_q.inp", {"mortar_q.inp": tq.two_blocks("Q8", "T6", 5, 7, pair=", TYPE=SURFACE TO SURFACE")}


def _mortar_axisymmetric():
    """Segment-to-segment contact, EXACT, on CAX8 columns (no radial support)."""
    import test_contact_quadratic as tq
    deck = tq.two_blocks("Q8", "Q8", 5, 3, state="AX", x0=0.5, pair=", TYPE=SURFACE TO SURFACE, EXACT")
    return "mortar_ax.inp", {"mortar_ax.inp": deck.replace("ANCHOR, 1, 1\nTOPLEFT, 1, 1\n", "")}


def _mortar_friction():
    """The frictional patch test with segment-to-segment contact and EXACT,
    the upper block held by contact alone (the stabilised search)."""
    import test_friction as tf
    deck = tf.patch_deck(7, "single")
    old = f"*CONTACT PAIR, FRICTION={tf.MU}\nSLV, MASTER\n"
    assert old in deck
    return "mortar_fric.inp", {"mortar_fric.inp": deck.replace(
        old, f"*CONTACT PAIR, FRICTION={tf.MU}, TYPE=SURFACE TO SURFACE, EXACT\nUPPERFACE, MASTER\n")}


def _mortar_hard_cards():
    """CalculiX's cards for the new coupling: a HARD interaction (exact
    enforcement) on a TYPE=SURFACE TO SURFACE pair."""
    import test_decks_contact as td
    deck = td.blocks(td.interaction("HARD", "") + "*CONTACT PAIR, INTERACTION=SI1, TYPE=SURFACE TO SURFACE\n"
                     "UPPERFACE, MASTER\n")
    return "mortar_hard.inp", {"mortar_hard.inp": deck}


def _mortar_tie():
    """The tied patch test with the mortar tie, the slave coarser."""
    import test_constraint_decks as tc
    deck = tc.tie_patch_deck(True, 1, 1e-4, "TOP, P, -3.\nRIGHT, P, -2.\n")
    return "mtie.inp", {"mtie.inp": deck.replace("*TIE, NAME=GLUE", "*TIE, NAME=GLUE, TYPE=SURFACE TO SURFACE")}


# Segment-to-segment contact, exact enforcement and the mortar tie (issue 21).
def _nl_contact_slide():
    """A block pressed into a polygonal bowl and slid ten edges in one
    NLGEOM increment, node-to-segment and mortar blocks in one deck
    (test_nonlinear_contact_search): the contact searched in every Newton
    iteration, renumbered where the couplings change."""
    import test_nonlinear_contact_search as tn
    return "nl_slide.inp", {"nl_slide.inp": tn.deck(couplings=(tn.NTS, tn.MORTAR))}


MORTAR_MAKERS = [("tests/mortar_exact", _mortar_exact), ("tests/mortar_quadratic", _mortar_quadratic),
                 ("tests/mortar_axisymmetric", _mortar_axisymmetric), ("tests/mortar_friction", _mortar_friction),
                 ("tests/mortar_hard_cards", _mortar_hard_cards), ("tests/mortar_tie", _mortar_tie),
                 ("tests/nl_contact_slide", _nl_contact_slide)]


def load_seeds(tmp, log):
    return example_seeds() + hertz_seeds(tmp, log) + test_seeds(log)


# ------------------------------------------------------------------------------- mutations

def _is_keyword(line):
    s = line.lstrip()
    return s.startswith(b"*") and not s.startswith(b"**")


def _cards(lines):
    """(start, end) line ranges of the keyword cards: a keyword line and what follows it."""
    starts = [k for k, line in enumerate(lines) if _is_keyword(line)]
    return [(s, e) for s, e in zip(starts, starts[1:] + [len(lines)])]


def _eol(line):
    for end in (b"\r\n", b"\n", b"\r"):
        if line.endswith(end):
            return end
    return b""


def _pick_file(rng, deck):
    """The main deck mostly; an included file now and then."""
    others = sorted(r for r in deck.files if r != deck.main)
    if others and rng.random() < 0.2:
        return rng.choice(others)
    return deck.main


def _lines(deck, rel):
    return deck.files[rel].splitlines(keepends=True)


def _set_lines(deck, rel, lines):
    deck.files[rel] = b"".join(lines)


def m_drop_card(rng, deck, pool):
    rel = _pick_file(rng, deck)
    lines = _lines(deck, rel)
    cards = _cards(lines)
    if not cards:
        return None
    s, e = rng.choice(cards)
    _set_lines(deck, rel, lines[:s] + lines[e:])
    return f"{rel}: dropped card at line {s + 1} ({lines[s].strip()[:40]!r})"


def m_dup_card(rng, deck, pool):
    rel = _pick_file(rng, deck)
    lines = _lines(deck, rel)
    cards = _cards(lines)
    if not cards:
        return None
    s, e = rng.choice(cards)
    _set_lines(deck, rel, lines[:e] + lines[s:e] + lines[e:])
    return f"{rel}: duplicated card at line {s + 1} ({lines[s].strip()[:40]!r})"


def m_move_card(rng, deck, pool):
    rel = _pick_file(rng, deck)
    lines = _lines(deck, rel)
    cards = _cards(lines)
    if len(cards) < 2:
        return None
    s, e = rng.choice(cards)
    card, rest = lines[s:e], lines[:s] + lines[e:]
    spots = [a for a, _ in _cards(rest)] + [len(rest)]
    at = rng.choice(spots)
    _set_lines(deck, rel, rest[:at] + card + rest[at:])
    return f"{rel}: moved card at line {s + 1} ({lines[s].strip()[:40]!r}) to line {at + 1}"


def m_splice_card(rng, deck, pool):
    """A card of another deck (e.g. *CONTACT CONTROLS) inserted at a card boundary."""
    if not pool:
        return None
    rel = deck.main
    lines = _lines(deck, rel)
    card = rng.choice(pool)
    spots = [a for a, _ in _cards(lines)] + [len(lines)]
    at = rng.choice(spots)
    _set_lines(deck, rel, lines[:at] + card + lines[at:])
    return f"{rel}: spliced {card[0].strip()[:40]!r} at line {at + 1}"


_NUMBER = re.compile(rb"(?<![\w.+-])[-+]?(?:\d+\.?\d*|\.\d+)(?:[eEdD][-+]?\d+)?(?![\w.])")


def _bulk_lines(lines):
    """Indexes of the data lines of *NODE and *ELEMENT cards (the mesh)."""
    bulk = set()
    for s, e in _cards(lines):
        word = re.sub(rb"\s+", b" ", lines[s].split(b",")[0].strip().upper())
        if word in (b"*NODE", b"*ELEMENT"):
            bulk.update(range(s + 1, e))
    return bulk


def m_number(rng, deck, pool):
    """A number replaced by a special value; mostly outside the mesh, where the
    numbers steer the analysis (increments, loads, controls)."""
    rel = _pick_file(rng, deck)
    lines = _lines(deck, rel)
    candidates = [k for k, line in enumerate(lines) if _NUMBER.search(line) and not line.lstrip().startswith(b"**")]
    bulk = _bulk_lines(lines)
    steering = [k for k in candidates if k not in bulk]
    if steering and rng.random() < 0.7:
        candidates = steering
    if not candidates:
        return None
    k = rng.choice(candidates)
    value = rng.choice(SPECIAL_NUMBERS)
    spans = [m.span() for m in _NUMBER.finditer(lines[k])]
    if rng.random() < 0.2:
        chosen = spans
    else:
        chosen = [rng.choice(spans)]
    line = lines[k]
    for a, b in reversed(chosen):
        line = line[:a] + value + line[b:]
    old = lines[k].strip()[:40]
    lines[k] = line
    _set_lines(deck, rel, lines)
    return f"{rel}:{k + 1}: {len(chosen)} number(s) -> {value.decode()} in {old!r}"


def m_truncate_line(rng, deck, pool):
    rel = _pick_file(rng, deck)
    lines = _lines(deck, rel)
    if not lines:
        return None
    k = rng.randrange(len(lines))
    body = lines[k][:len(lines[k]) - len(_eol(lines[k]))]
    cut = rng.randrange(len(body) + 1)
    lines[k] = body[:cut] + _eol(lines[k])
    _set_lines(deck, rel, lines)
    return f"{rel}:{k + 1}: truncated to {cut} characters"


def m_truncate_file(rng, deck, pool):
    rel = _pick_file(rng, deck)
    data = deck.files[rel]
    cut = rng.randrange(len(data) + 1)
    deck.files[rel] = data[:cut]
    return f"{rel}: file truncated at byte {cut} of {len(data)}"


def m_join_lines(rng, deck, pool):
    rel = _pick_file(rng, deck)
    lines = _lines(deck, rel)
    if len(lines) < 2:
        return None
    k = rng.randrange(len(lines) - 1)
    glue = rng.choice([b"", b", ", b" ", b","])
    lines[k:k + 2] = [lines[k][:len(lines[k]) - len(_eol(lines[k]))] + glue + lines[k + 1]]
    _set_lines(deck, rel, lines)
    return f"{rel}:{k + 1}: joined with the next line by {glue!r}"


def m_delete_line(rng, deck, pool):
    rel = _pick_file(rng, deck)
    lines = _lines(deck, rel)
    if not lines:
        return None
    k = rng.randrange(len(lines))
    del lines[k]
    _set_lines(deck, rel, lines)
    return f"{rel}:{k + 1}: line deleted"


def m_dup_line(rng, deck, pool):
    rel = _pick_file(rng, deck)
    lines = _lines(deck, rel)
    if not lines:
        return None
    k = rng.randrange(len(lines))
    lines.insert(k, lines[k])
    _set_lines(deck, rel, lines)
    return f"{rel}:{k + 1}: line duplicated"


def m_line_endings(rng, deck, pool):
    rel = _pick_file(rng, deck)
    how = rng.choice([b"\r\n", b"\r\n", b"\r", b"\n\n"])
    lines = _lines(deck, rel)
    _set_lines(deck, rel, [line[:len(line) - len(_eol(line))] + how for line in lines])
    return f"{rel}: line endings -> {how!r}"


def m_binary(rng, deck, pool):
    rel = _pick_file(rng, deck)
    data = deck.files[rel]
    junk = rng.choice([b"\x00", b"\xff\xfe", b"\xef\xbb\xbf", b"\x1a", b"\t", b"\x0c", b"\x7f",
                       bytes(rng.randrange(256) for _ in range(rng.randrange(1, 32)))])
    at = 0 if rng.random() < 0.1 else rng.randrange(len(data) + 1)
    deck.files[rel] = data[:at] + junk + data[at:]
    return f"{rel}: {len(junk)} binary byte(s) {junk[:8]!r} at byte {at}"


def m_long_line(rng, deck, pool):
    rel = _pick_file(rng, deck)
    lines = _lines(deck, rel)
    n = rng.choice([300, 1025, 4097, 70000, 1_000_000])
    kind = rng.choice(["comment", "data", "keyword", "digits", "name"])
    text = {"comment": b"**" + b"x" * n, "data": (b"1, " * (n // 3 + 1))[:n], "keyword": b"*" + b"A" * n,
            "digits": b"1" * n, "name": b"*NSET, NSET=" + b"N" * n}[kind]
    k = rng.randrange(len(lines) + 1)
    if rng.random() < 0.5 and lines and k < len(lines):
        lines[k] = lines[k][:len(lines[k]) - len(_eol(lines[k]))] + text[:n] + _eol(lines[k])
        note = f"{rel}:{k + 1}: line lengthened by {n} characters ({kind})"
    else:
        lines.insert(k, text + b"\n")
        note = f"{rel}:{k + 1}: inserted a {len(text)}-character {kind} line"
    _set_lines(deck, rel, lines)
    return note


def _include_target(rng, deck, rel):
    """A troublesome *INCLUDE target; adds to the deck whatever it needs."""
    kind = rng.choice(["missing", "self", "dir", "dev_zero", "fifo", "dev_null", "urandom", "cycle",
                       "etc", "empty_name", "long_name", "empty_file", "missing_dir"])
    here = os.path.dirname(rel)
    if kind == "self":
        return kind, os.path.basename(rel).encode()
    if kind == "dir":
        deck.dirs.append(os.path.join(here, "subdir"))
        return kind, b"subdir"
    if kind == "fifo":
        deck.fifos.append(os.path.join(here, "pipe.inp"))
        return kind, b"pipe.inp"
    if kind == "cycle":
        deck.files[os.path.join(here, "cycle_a.inp")] = b"*INCLUDE, INPUT=cycle_b.inp\n"
        deck.files[os.path.join(here, "cycle_b.inp")] = b"** b includes a\n*INCLUDE, INPUT=cycle_a.inp\n"
        return kind, b"cycle_a.inp"
    if kind == "empty_file":
        deck.files[os.path.join(here, "empty.inp")] = b""
        return kind, b"empty.inp"
    return kind, {"missing": b"missing.inp", "dev_zero": b"/dev/zero", "dev_null": b"/dev/null",
                  "urandom": b"/dev/urandom", "etc": b"/etc", "empty_name": b"",
                  "long_name": b"d" * 5000 + b".inp", "missing_dir": b"no/such/folder/x.inp"}[kind]


def m_include(rng, deck, pool):
    rel = _pick_file(rng, deck)
    lines = _lines(deck, rel)
    kind, target = _include_target(rng, deck, rel)
    spots = [a for a, _ in _cards(lines)] + [len(lines)]
    at = rng.choice(spots)
    lines.insert(at, b"*INCLUDE, INPUT=" + target + b"\n")
    _set_lines(deck, rel, lines)
    return f"{rel}:{at + 1}: *INCLUDE of a {kind} ({target[:40].decode()})"


def m_keyword(rng, deck, pool):
    rel = _pick_file(rng, deck)
    lines = _lines(deck, rel)
    cards = _cards(lines)
    if not cards:
        return None
    k = rng.choice(cards)[0]
    line, eol = lines[k][:len(lines[k]) - len(_eol(lines[k]))], _eol(lines[k])
    how = rng.choice(["no star", "lower", "drop params", "dup param", "empty value", "no value",
                      "unknown param", "spaces", "double comma", "only star"])
    head, _, params = line.partition(b",")
    parts = [p for p in params.split(b",") if p.strip()]
    if how == "no star":
        line = line.replace(b"*", b"", 1)
    elif how == "lower":
        line = line.lower()
    elif how == "drop params":
        line = head
    elif how == "dup param" and parts:
        line = line + b"," + rng.choice(parts)
    elif how == "empty value" and parts:
        p = rng.randrange(len(parts))
        parts[p] = parts[p].split(b"=")[0] + b"="
        line = head + b"," + b",".join(parts)
    elif how == "no value" and parts:
        p = rng.randrange(len(parts))
        parts[p] = parts[p].split(b"=")[0]
        line = head + b"," + b",".join(parts)
    elif how == "unknown param":
        line = line + b", FOO=1"
    elif how == "spaces":
        line = b"  " + line.replace(b" ", b"   ").replace(b"=", b" = ") + b"  "
    elif how == "double comma":
        line = line + b",,"
    elif how == "only star":
        line = b"*"
    else:
        return None
    lines[k] = line + eol
    _set_lines(deck, rel, lines)
    return f"{rel}:{k + 1}: keyword line {how}: {line[:50]!r}"


# ---------------------------------------------- targeted: today's constraint and element cards

# Cards whose data lines m_card_field rewrites field by field.
TARGET_CARDS = (b"*EQUATION", b"*TIE", b"*PRE-TENSION SECTION", b"*SPRING", b"*MASS", b"*SOLID SECTION",
                b"*NODAL THICKNESS", b"*SURFACE", b"*ELEMENT", b"*BOUNDARY", b"*DLOAD", b"*CLOAD")
# Values a field of those cards should not hold: zero, huge and tiny
# coefficients, constants and areas; NaN text; dofs 0, -1, 3, 7; a node id
# no deck defines; an empty field; a name nothing defines.
NASTY_FIELDS = [b"0", b"0.", b"-0.", b"-1", b"-1.5", b"3", b"7", b"1e300", b"-1e300", b"1e-300", b"1e-320",
                b"nan", b"NaN", b"-inf", b"999999", b"", b" ", b"NOSUCHNAME", b"1e20", b"2147483648"]


def _keyword_word(line):
    return re.sub(rb"\s+", b" ", line.split(b",")[0].strip().upper())


def _deck_names(deck, surfaces=False):
    """Node ids and set, surface and card names the deck defines (for
    fields that refer to something: a real but wrong referent); with
    surfaces, also the names of its *SURFACE cards alone."""
    ids, names, surfs = [], [], []
    for rel in sorted(deck.files):
        lines = _lines(deck, rel)
        for s, e in _cards(lines):
            found = [m.group(1) for m in re.finditer(rb"(?i)(?:NSET|ELSET|NAME)\s*=\s*([\w.-]+)", lines[s])]
            names += found
            if _keyword_word(lines[s]) == b"*SURFACE":
                surfs += found
            if _keyword_word(lines[s]) == b"*NODE":
                ids += [line.split(b",")[0].strip() for line in lines[s + 1:e] if re.match(rb"\s*\d+\s*,", line)]
    return (ids, names, surfs) if surfaces else (ids, names)


def m_card_field(rng, deck, pool):
    """One comma field of a data line of today's cards (an equation term, a
    tie's surfaces, a spring's dof or constant, a mass, an area, a nodal
    thickness, a line element's node) replaced by a nasty value, another
    field of the same line (a term on itself, a bar from a node to itself),
    or a node id or name the deck defines (a cycle, a tie of a surface to
    itself, a pre-tension on a node set)."""
    rel = _pick_file(rng, deck)
    lines = _lines(deck, rel)
    spots = []
    for s, e in _cards(lines):
        if _keyword_word(lines[s]) in TARGET_CARDS:
            spots += [k for k in range(s + 1, e) if lines[k].strip() and not lines[k].lstrip().startswith(b"**")]
    if not spots:
        return None
    k = rng.choice(spots)
    body, eol = lines[k][:len(lines[k]) - len(_eol(lines[k]))], _eol(lines[k])
    fields = body.split(b",")
    f = rng.randrange(len(fields))
    ids, names = _deck_names(deck)
    how = rng.choice(["nasty", "nasty", "same line", "node", "name"])
    if how == "same line" and len(fields) > 1:
        value = rng.choice([x for j, x in enumerate(fields) if j != f]).strip()
    elif how == "node" and ids:
        value = rng.choice(ids)
    elif how == "name" and names:
        value = rng.choice(names)
    else:
        how, value = "nasty", rng.choice(NASTY_FIELDS)
    fields[f] = b" " + value if f else value
    lines[k] = b",".join(fields) + eol
    _set_lines(deck, rel, lines)
    return f"{rel}:{k + 1}: field {f + 1} -> {value[:30]!r} ({how}) in {body.strip()[:40]!r}"


def _model_end(lines):
    """Where model-level cards go: before the first *STEP."""
    return next((k for k, line in enumerate(lines) if _keyword_word(line) == b"*STEP"), len(lines))


def m_constraint(rng, deck, pool):
    """A constraint card added among the deck's own nodes and names:
    equations in a chain, a cycle, on a dof twice, on a node itself, on a
    held dof; a tie of an empty, unknown or node surface, or of a surface
    to itself, or of two of the deck's surfaces (contact surfaces too); a
    pre-tension section on a node surface, an empty one, or one of the
    deck's surfaces with a new reference node held (a legal cut that opens
    by 0: on a tie's master surface it makes chains of constraints)."""
    ids, names, surfs = _deck_names(deck, surfaces=True)
    if len(ids) < 2:
        return None
    lines = _lines(deck, deck.main)
    nodes = rng.sample(ids, min(len(ids), rng.choice([2, 3, 5, 50])))
    dof = rng.choice([b"1", b"2", b"1", b"2", b"3", b"0", b"-1"])
    kind = rng.choice(["chain", "cycle", "twice", "self", "long", "tie empty", "tie unknown", "tie node",
                       "tie self", "tie surfaces", "pret node", "pret empty", "pret surface", "pret surface"])
    name = rng.choice(surfs or names or [b"X"])
    eq = lambda a, b, c=b"1.": b"2\n%s, %s, %s, %s, %s, -1.\n" % (a, dof, c, b, dof)  # noqa: E731
    if kind == "chain":
        card = b"*EQUATION\n" + b"".join(eq(a, b) for a, b in zip(nodes, nodes[1:]))
    elif kind == "cycle":
        card = b"*EQUATION\n" + b"".join(eq(a, b) for a, b in zip(nodes, nodes[1:] + nodes[:1]))
    elif kind == "twice":
        card = b"*EQUATION\n" + eq(nodes[0], nodes[1]) + eq(nodes[0], nodes[-1], b"2.")
    elif kind == "self":
        card = b"*EQUATION\n" + eq(nodes[0], nodes[0], rng.choice([b"1.", b"2.", b"1e300"]))
    elif kind == "long":
        card = b"*EQUATION\n%d\n" % (2 * len(nodes)) + b"".join(
            b"%s, 1, 1., %s, 2, -1e-300,\n" % (n, n) for n in nodes)
    elif kind == "tie empty":
        card = b"*SURFACE, NAME=FZEMPTY\n*TIE, NAME=FZ\nFZEMPTY, %s\n" % name
    elif kind == "tie unknown":
        card = b"*TIE, NAME=FZ\n%s, NOSUCHSURFACE\n" % name
    elif kind == "tie node":
        card = b"*SURFACE, NAME=FZN, TYPE=NODE\n%s\n*TIE, NAME=FZ\nFZN, %s\n" % (b", ".join(nodes), name)
    elif kind == "tie self":
        card = b"*TIE, NAME=FZ\n%s, %s\n" % (name, name)
    elif kind == "pret node":
        card = b"*SURFACE, NAME=FZN, TYPE=NODE\n%s\n*PRE-TENSION SECTION, SURFACE=FZN, NODE=%s\n" % (
            b", ".join(nodes[1:]), nodes[0])
    elif kind == "tie surfaces":
        card = b"*TIE, NAME=FZ\n%s, %s\n" % (name, rng.choice(surfs or names or [b"X"]))
    elif kind == "pret empty":
        card = b"*SURFACE, NAME=FZEMPTY\n*PRE-TENSION SECTION, SURFACE=FZEMPTY, NODE=%s\n" % nodes[0]
    else:
        card = (b"*NODE\n990001, 0., 0.\n*PRE-TENSION SECTION, SURFACE=%s, NODE=990001\n"
                b"*BOUNDARY\n990001, 1, 2\n" % name)
    at = _model_end(lines)
    lines.insert(at, card)
    _set_lines(deck, deck.main, lines)
    return f"{deck.main}:{at + 1}: added {kind} ({card[:60]!r})"


def m_coincide(rng, deck, pool):
    """Two nodes of one element moved onto each other (a truss or an axial
    spring of zero length, a collapsed face): the second node's
    coordinates set to the first's."""
    coords, elems = {}, []
    for rel in sorted(deck.files):
        lines = _lines(deck, rel)
        for s, e in _cards(lines):
            word = _keyword_word(lines[s])
            for k in range(s + 1, e):
                fields = [x.strip() for x in lines[k].split(b",")]
                if word == b"*NODE" and len(fields) >= 3:
                    coords[fields[0]] = (rel, k)
                elif word == b"*ELEMENT" and len(fields) >= 3:
                    elems.append(fields[1:])
    elems = [e for e in elems if sum(n in coords for n in e) >= 2]
    if not elems:
        return None
    a, b = rng.sample([n for n in rng.choice(elems) if n in coords], 2)
    (ra, ka), (rb, kb) = coords[a], coords[b]
    src = _lines(deck, ra)[ka]
    lines = _lines(deck, rb)
    lines[kb] = b + b"," + src[:len(src) - len(_eol(src))].split(b",", 1)[1] + _eol(lines[kb])
    _set_lines(deck, rb, lines)
    return f"{rb}:{kb + 1}: node {b.decode(errors='replace')} moved onto node {a.decode(errors='replace')}"


def m_gut(rng, deck, pool):
    """The whole deck replaced by nothing useful: empty, comments, blank lines."""
    kind = rng.choice(["empty", "comments", "blank crlf", "blank", "bom", "heading only"])
    deck.files[deck.main] = {"empty": b"", "comments": b"** only\n** comments\n", "blank crlf": b"\r\n\r\n\r\n",
                             "blank": b"\n \n\t\n", "bom": b"\xef\xbb\xbf", "heading only": b"*HEADING\nx\n"}[kind]
    return f"{deck.main}: whole deck -> {kind}"


MUTATORS = [(m_drop_card, 10), (m_dup_card, 8), (m_move_card, 8), (m_splice_card, 8), (m_number, 30),
            (m_truncate_line, 6), (m_truncate_file, 2), (m_join_lines, 5), (m_delete_line, 6),
            (m_dup_line, 4), (m_line_endings, 3), (m_binary, 4), (m_long_line, 3), (m_include, 4),
            (m_keyword, 6), (m_gut, 1), (m_card_field, 14), (m_constraint, 6), (m_coincide, 3)]


def card_pool(seeds):
    """Short cards of the seed decks, for m_splice_card."""
    pool, seen = [], set()
    for seed in seeds:
        lines = _lines(seed, seed.main)
        for s, e in _cards(lines):
            card = lines[s:e]
            if e - s <= 12 and b"INCLUDE" not in card[0].upper() and b"".join(card) not in seen:
                seen.add(b"".join(card))
                pool.append(card)
    return pool


def mutant(seeds, pool, seed, index):
    """Purpose: the index-th mutant of the run with this seed (reproducible alone).
    Returns a Deck with its notes."""
    rng = random.Random(f"cfe2d-fuzz:{seed}:{index}")
    deck = rng.choice(seeds).copy()
    deck.notes = []
    count = rng.choices([1, 2, 3, 4], weights=[55, 25, 12, 8])[0]
    funcs, weights = zip(*MUTATORS)
    tries = 0
    while len(deck.notes) < count and tries < 20:
        tries += 1
        note = rng.choices(funcs, weights=weights)[0](rng, deck, pool)
        if note:
            deck.notes.append(note)
    return deck


# ---------------------------------------------------------------------------- run, classify

@dataclass
class Result:
    build: str
    cls: str
    sig: str
    rc: int
    seconds: float
    stderr: bytes           # head and tail of stderr
    record: dict = field(default_factory=dict)   # contact_record of the run (ok-run, ok-error)


@dataclass
class Limits:
    time: float = 10.0      # seconds per run
    mem_mb: int = 2048      # address space per run
    file_mb: int = 512      # largest file a run may write


_ERROR_LINE = re.compile(rb"^(?:.+:\d+: error: |cfe2d: error: )", re.M)
_CRASH_TEXT = re.compile(rb"Fortran runtime error|Program received signal|Backtrace for this error|"
                         rb"Error termination|Operating system error|^At line \d+ of file|double free|"
                         rb"free\(\): |malloc\(\): |stack smashing|corrupted size", re.M)
_BAD_NUMBER = re.compile(rb"(?i)(?<![\w.])[-+]?(?:nan|inf|infinity)(?![\w.])")
# Fortran's Ew.d and ESw.d drop the E when the exponent has three digits.
_NO_E_EXPONENT = re.compile(rb"\d\.\d*[-+]\d{3}(?![\d.])")
_STARS = re.compile(rb"\*{4,}")


def _preexec(limits):
    def setup():
        mem = limits.mem_mb * 1024 * 1024
        resource.setrlimit(resource.RLIMIT_AS, (mem, mem))
        size = limits.file_mb * 1024 * 1024
        resource.setrlimit(resource.RLIMIT_FSIZE, (size, size))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    return setup


# ------------------------------------------------------------------- the builds must agree

# What two builds (optimised and debug) must agree on, most serious first.
# A run's record holds, for each kind, a list of items read from its
# listing, <job>_contact.csv and stderr; numbers with a fraction or an
# exponent are rounded or masked, so that round-off in the last printed
# digits is no disagreement, while every decision (a contact status, an
# increment, a bisection, a pivot, an error) is compared exactly.
#   class       one build errors, hangs or crashes while the other runs
#   status      the state column of <job>_contact.csv (CLOSED/OPEN per step,
#               increment, pair, side and node), the closed count of each
#               CONTACT SUMMARY
#   increments  the increments (step, increment, time to 6 digits) and the
#               bisection notes
#   layer       coupling elements, contact equations, uncoupled slave nodes
#   error       the error message of a run that stops (floats masked, and
#               the nodes a message names as examples of a round-off
#               decision: the node and dof of "singular stiffness at node
#               N, dof D" (and of a nonlinear step's "tangent stiffness is
#               singular at node N, dof D"), where any dof of a free body is
#               right and the first zero pivot is found by round-off, and the nodes
#               "still switching" when a search gives up)
#   notes       the other notes of the contact search (stabilised open
#               penalty, pivot taken back, matrix not positive definite)
#               and warnings on stderr (floats masked)
#   search      the search path: each contact iteration's status changes,
#               closed count and switching nodes, the iterations of each
#               increment; the step summaries' contact_iterations, pivots
#               and factorisations
#   detail      the error messages and notes with the nodes they name
# The first five are defects; the builds may take different paths to the
# same statuses, increments and errors (notes, search, detail), and that
# is counted and reported but is none.
AGREEMENT = ("class", "status", "increments", "layer", "error", "notes", "search", "detail")
AGREEMENT_DEFECTS = ("class", "status", "increments", "layer", "error")

_FLOAT = re.compile(r"[-+]?(?:\d+\.\d*|\.\d+)(?:[eE][-+]?\d+)?|[-+]?\d+[eE][-+]?\d+")
_INCREMENT = re.compile(r"^=== INCREMENT step=(\d+) increment=(\d+) time=(\S+) .*?iterations=(\d+)")
_ITERATION = re.compile(r"^contact iteration (\d+): status changes (\d+), closed (\d+), out-of-balance +\S+"
                        r"(?: \(nodes(.*)\))?\s*$")
_NOTE = re.compile(r"^(?:contact status |singular stiffness|the contact status |\S+: the matrix is not positive)")
_SEARCH_KEYS = ("contact_iterations", "contact_block_pivots", "contact_single_pivots", "numeric_factorisations",
                "condensed_factorisations")
_EXAMPLE_NODES = [re.compile(r"(singular stiffness at node )\d+(, dof )\d"),
                  re.compile(r"(tangent stiffness is singular at node )\d+(, dof )\d"),
                  re.compile(r"(still switching:)(?: \S+)+")]


def _mask(text):
    return _FLOAT.sub("#", text.strip())


def _mask_examples(text):
    """text without the nodes it names as examples of a round-off decision."""
    for pattern in _EXAMPLE_NODES:
        text = pattern.sub(lambda m: "".join(g + "N" for g in m.groups()), text)
    return text


def _round6(text):
    try:
        return f"{float(text):.6g}"
    except ValueError:
        return text


def contact_record(out_dir, job, stderr):
    """Purpose: what two builds must agree on in one run (see AGREEMENT).
    Arguments: out_dir and job, where the run wrote; stderr bytes.
    Returns {kind: [items]} (no entry for the kind "class")."""
    rec = {k: [] for k in AGREEMENT[1:]}
    text = ""
    listing = os.path.join(out_dir, job + ".out")
    if os.path.exists(listing):
        with open(listing, "rb") as f:
            text = f.read().decode(errors="replace")
    step, block, inc, pair = "?", "", "-", "?"
    for line in text.splitlines():
        words = line.split()
        if line.startswith("--- "):
            block = " ".join(w for w in words[1:] if "=" not in w)
            m = re.match(r"--- (?:STEP|SOLVER|STEP SUMMARY|CONTACT SUMMARY) (?:step|pair)=(\d+)", line)
            if m and block != "CONTACT SUMMARY":
                step = m.group(1)
            elif m:
                pair = m.group(1)
            continue
        if line.startswith("=== INCREMENT"):
            m = _INCREMENT.match(line)
            if m:
                inc = f"step {m.group(1)} increment {m.group(2)}"
                rec["increments"].append(f"{inc} time {_round6(m.group(3))}")
                rec["search"].append(f"{inc}: iterations {m.group(4)}")
            block = "INCREMENT"
            continue
        if line.startswith("=== END INCREMENT"):
            block = ""
            continue
        m = _ITERATION.match(line)
        if m:
            rec["search"].append(f"step {step} after {inc}: contact iteration {m.group(1)}: status changes "
                                 f"{m.group(2)}, closed {m.group(3)}, nodes{m.group(4) or ''}")
            continue
        if _NOTE.match(line):
            kind = "increments" if "bisected" in line or "did not settle" in line else "notes"
            rec[kind].append(f"step {step} after {inc}: {_mask_examples(_mask(line))}")
            rec["detail"].append(f"step {step} after {inc}: {_mask(line)}")
            continue
        if block == "STEP" and words[:1] == ["coupling_elements"]:
            rec["layer"].append(f"step {step}: {line.strip()}")
        elif block == "SOLVER" and words[:1] in (["contact_equations"], ["contact_solve"]):
            rec["layer"].append(f"step {step}: {line.strip()}")
        elif block.startswith("UNCOUPLED") and len(words) == 2 and all(w.isdigit() for w in words):
            rec["layer"].append(f"step {step}: uncoupled slave node: pair {words[0]} node {words[1]}")
        elif block == "CONTACT SUMMARY" and words[:1] and words[0].isdigit():
            rec["status"].append(f"{inc} pair {pair}: closed {words[0]}")
        elif block == "STEP SUMMARY" and len(words) == 2 and words[0] in _SEARCH_KEYS:
            rec["search"].append(f"step {step} summary: {words[0]} {words[1]}")
    csv = os.path.join(out_dir, job + "_contact.csv")
    if os.path.exists(csv):
        with open(csv, "rb") as f:
            rows = f.read().decode(errors="replace").splitlines()
        for row in rows[1:]:
            cols = row.split(",")
            if len(cols) >= 10:
                rec["status"].append(f"step {cols[0]} increment {cols[1]} pair {cols[3]} {cols[4]} node {cols[5]}: "
                                     f"{cols[9].strip()}")
    err = stderr.decode(errors="replace")
    for line in err.splitlines():
        if re.match(r"^(?:.+:\d+: error: |cfe2d: error: )", line):
            rec["error"].append(_mask_examples(_mask(line)))
            rec["detail"].append(_mask(line))
        elif re.match(r"^(?:.+:\d+: warning: |cfe2d: warning: )", line):
            rec["notes"].append(_mask_examples(_mask(line)))
            rec["detail"].append(_mask(line))
    return rec


def run_build(exe, deck_dir, deck, out_dir, limits):
    """Purpose: run one build on a laid-out deck and classify the run.
    Arguments: exe, the cfe2d executable; deck_dir, where deck.write put the deck;
    out_dir, the (new) output folder; limits, a Limits. Returns a Result."""
    os.makedirs(out_dir, exist_ok=True)
    err_path = out_dir + ".stderr"
    t0 = time.time()
    timed_out = ""
    with open(err_path, "wb") as err:
        proc = subprocess.Popen([exe, "-q", "-o", out_dir, deck.main], cwd=deck_dir, stdin=subprocess.DEVNULL,
                                stdout=subprocess.DEVNULL, stderr=err, preexec_fn=_preexec(limits),
                                start_new_session=True)
        try:
            rc = proc.wait(timeout=limits.time)
        except subprocess.TimeoutExpired:
            timed_out = hang_probe(proc.pid)
            os.killpg(proc.pid, signal.SIGKILL)
            rc = proc.wait()
    seconds = time.time() - t0
    stderr = _head_tail(err_path)
    cls, sig = classify(rc, timed_out, stderr, out_dir, deck.job)
    record = contact_record(out_dir, deck.job, stderr) if cls in ("ok-run", "ok-error") else {}
    return Result(os.path.relpath(exe, ROOT) if exe.startswith(ROOT) else exe, cls, sig, rc, seconds, stderr,
                  record)


def hang_probe(pid):
    """Purpose: where a process that ran out of time is: blocked in the kernel
    (and on what) or busy, and in which routines of src/ (a backtrace by gdb,
    when gdb is there and the build has debug information).
    Returns a short description (never empty)."""
    states = []
    for _ in range(3):
        try:
            with open(f"/proc/{pid}/stat") as f:
                states.append(f.read().rsplit(")", 1)[1].split()[0])
            with open(f"/proc/{pid}/wchan") as f:
                wchan = f.read().strip()
        except OSError:
            return "hung"
        time.sleep(0.05)
    what = "busy" if "R" in states else f"blocked ({wchan})" if wchan not in ("", "0") else "sleeping"
    if not shutil.which("gdb"):
        return what
    try:
        bt = subprocess.run(["gdb", "-p", str(pid), "-batch", "-nx", "-ex", "bt 60"], capture_output=True,
                            timeout=30).stdout
    except (OSError, subprocess.SubprocessError):
        return what
    names = []
    for m in re.finditer(rb"^#\d+\s+(?:0x[0-9a-f]+ in )?(\S+) \(.*\) at (src/\S+):\d+$", bt, re.M):
        name = m.group(1).decode(errors="replace").split("::")[-1]
        if name != "main" and (not names or names[-1] != name):
            names.append(name)
    # outermost first, without the main program; the innermost frames of a
    # loop vary from one sample to the next, so only the outer three count
    path = list(reversed(names))[1:4]
    return what + (" in " + " > ".join(path) if path else "")


def _head_tail(path, keep=4096):
    size = os.path.getsize(path)
    with open(path, "rb") as f:
        if size <= 2 * keep:
            return f.read()
        head = f.read(keep)
        f.seek(size - keep)
        return head + b"\n[... %d bytes left out ...]\n" % (size - 2 * keep) + f.read()


def classify(rc, timed_out, stderr, out_dir, job):
    """Purpose: the class of one run and a signature telling failures apart.
    Arguments: rc, the exit status (negative: signal); timed_out, '' or what
    hang_probe said; stderr bytes;
    out_dir and job, where the outputs are. Returns (class, signature)."""
    if timed_out:
        listing = os.path.join(out_dir, job + ".out")
        stage = "in the analysis" if os.path.exists(listing) else "before the listing"
        return "hang", f"time limit reached {stage}, {timed_out}"
    if rc == -signal.SIGXFSZ:
        return "hang", "output file size limit reached"
    crash = _crash_signature(rc, stderr)
    if crash:
        return "crash", crash
    if rc != 0:
        return "ok-error", ""
    bad = output_problem(out_dir, job)
    return ("silent-bad", bad) if bad else ("ok-run", "")


def _location(stderr):
    m = re.search(rb"At line (\d+) of file (\S+)", stderr)
    if m:
        return f"{m.group(2).decode(errors='replace')}:{m.group(1).decode()}"
    m = re.search(rb"\bat (src/\S+?:\d+)", stderr)
    return m.group(1).decode(errors="replace") if m else ""


def _crash_signature(rc, stderr):
    """'' when the run did not crash, else what and where."""
    where = _location(stderr)
    at = f" at {where}" if where else ""
    m = re.search(rb"Fortran runtime error: ([^\n]*)", stderr)
    if m:
        msg = re.sub(r"-?\d+", "#", m.group(1).decode(errors="replace")).strip()
        return f"runtime error{at}: {msg[:100]}"
    m = re.search(rb"Program received signal (SIG\w+)", stderr)
    if m:
        return f"{m.group(1).decode()}{at}"
    if rc < 0:
        try:
            return f"{signal.Signals(-rc).name}{at}"
        except ValueError:
            return f"signal {-rc}{at}"
    m = _CRASH_TEXT.search(stderr)
    if m:
        line = stderr[m.start():].split(b"\n", 1)[0].decode(errors="replace")
        return f"{re.sub(r'-?[0-9]+', '#', line)[:80]}{at}"
    if rc not in (0, 1):
        return f"exit status {rc}"
    if rc == 1 and not _ERROR_LINE.search(stderr):
        return "exit 1 without a file:line: error: or cfe2d: error: message"
    return ""


def output_problem(out_dir, job):
    """Purpose: what is wrong with the outputs of a run that exited 0 ('' if nothing)."""
    listing = os.path.join(out_dir, job + ".out")
    if not os.path.exists(listing):
        return "no listing"
    with open(listing, "rb") as f:
        text = f.read()
    # trusses or springs alone are a model; no element at all is none
    if re.search(rb"^elements 0\s*$", text, re.M):
        return "the model has no element (nothing was analysed)"
    steps = re.findall(rb"^--- STEP step=(\d+)", text, re.M)
    incs = set(re.findall(rb"^=== INCREMENT step=(\d+)", text, re.M))
    if not incs:
        return "no increment in the listing"
    for step in steps:
        if step not in incs:
            return "a step ran no increment"
    for name in sorted(os.listdir(out_dir)):
        if os.path.splitext(name)[1] in (".out", ".csv", ".msh"):
            bad = _number_problem(os.path.join(out_dir, name))
            if bad:
                return f"{bad} in the {os.path.splitext(name)[1]} output"
    return _short_step(text)


def _binary_msh_problem(path):
    """A binary gmsh result file: its values read back must be finite."""
    import numpy as np
    from gmsh_results import read_msh
    try:
        r = read_msh(path)
    except Exception as e:  # a file cfe2d wrote that its own reader cannot read
        return f"unreadable binary result file ({type(e).__name__})"
    arrays = [r.xy] + [vals for series in r.views.values() for _, _, vals in series]
    if any(not np.all(np.isfinite(a)) for a in arrays if a is not None):
        return "NaN or Infinity"
    return ""


def _short_step(text):
    """'a step stopped before the end of its time period' if the last increment
    of a step is not at the step's time_period (a *FREQUENCY step, which
    has an EIGENVALUES block, has no time: its increments are its modes)."""
    periods = dict(re.findall(rb"^--- STEP step=(\d+).*?^time_period\s+(\S+)", text, re.M | re.S))
    for step in re.findall(rb"^--- EIGENVALUES step=(\d+)", text, re.M):
        periods.pop(step, None)
    last = {}
    for step, t in re.findall(rb"^=== INCREMENT step=(\d+) increment=\d+ time=(\S+)", text, re.M):
        last[step] = t
    for step, t in last.items():
        try:
            period, reached = float(periods[step]), float(t)
        except (KeyError, ValueError):
            continue
        if abs(reached - period) > 1e-5 * abs(period):
            return "a step stopped before the end of its time period"
    return ""


def _number_problem(path):
    with open(path, "rb") as f:
        text = f.read()
    if path.endswith(".msh") and text.startswith(b"$MeshFormat\n2.2 1 8"):
        return _binary_msh_problem(path)
    if path.endswith(".out"):
        # the deck's name and heading are echoed as given
        text = re.sub(rb"^(?:heading|deck) .*$", b"", text, flags=re.M)
    if _BAD_NUMBER.search(text):
        return "NaN or Infinity"
    if _NO_E_EXPONENT.search(text):
        return "a number without E before its 3-digit exponent"
    if _STARS.search(text):
        return "a field of asterisks"
    return ""


def run_deck(deck, builds, limits, work):
    """Purpose: lay out deck in a new folder under work and run every build on it.
    Returns the list of Results, one per build."""
    folder = tempfile.mkdtemp(prefix="run-", dir=work)
    try:
        deck_dir = os.path.join(folder, "deck")
        deck.write(deck_dir)
        return [run_build(exe, deck_dir, deck, os.path.join(folder, f"out{k}"), limits)
                for k, exe in enumerate(builds)]
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def verdict(results):
    """The deck's class (the worst over the builds) and the signature of that failure;
    a signature naming a source line is preferred (the debug build's)."""
    worst = max(results, key=lambda r: SEVERITY.index(r.cls)).cls
    same = [r for r in results if r.cls == worst]
    best = max(same, key=lambda r: ("src/" in r.sig, r.build))
    return worst, best.sig, best


def disagreement(results):
    """Purpose: where the builds disagree on one deck (see AGREEMENT).
    Returns a list of (kind, detail), most serious kind first; [] when they agree."""
    if len(results) < 2:
        return []
    if len({r.cls for r in results}) > 1:
        return [("class", ", ".join(f"{r.build} {r.cls}" for r in results))]
    if results[0].cls not in ("ok-run", "ok-error"):
        return []
    found = []
    first = results[0]
    for kind in AGREEMENT[1:]:
        a = first.record.get(kind, [])
        for other in results[1:]:
            b = other.record.get(kind, [])
            if a != b:
                k = next((i for i, (x, y) in enumerate(zip(a, b)) if x != y), min(len(a), len(b)))
                x = a[k] if k < len(a) else "(nothing)"
                y = b[k] if k < len(b) else "(nothing)"
                found.append((kind, f"{first.build}: {x} | {other.build}: {y}"))
                break
    return found


# ---------------------------------------------------------------------------------- minimise

def minimise(deck, target, exe, limits, work, budget, seconds=300.0, still=None):
    """Purpose: shrink deck by deleting files and lines while exe still fails with target.
    Arguments: target, the (class, signature) to keep; budget, the most runs to spend;
    seconds, the most time to spend; still (optional), a test on the list of
    Results of the builds exe (then a list) that replaces target.
    Returns (smaller Deck, runs used)."""
    runs, seen, t_end = [0], {}, time.time() + seconds
    exes = exe if isinstance(exe, (list, tuple)) else [exe]

    def fails(candidate):
        key = (tuple(sorted(candidate.files.items())), tuple(candidate.fifos), tuple(candidate.dirs))
        if key not in seen:
            if runs[0] >= budget or time.time() > t_end:
                return False
            runs[0] += 1
            rs = run_deck(candidate, exes, limits, work)
            seen[key] = still(rs) if still else (rs[0].cls, rs[0].sig) == target
        return seen[key]

    deck = deck.copy()
    for rel in sorted(deck.files):
        if rel != deck.main:
            trial = deck.copy()
            del trial.files[rel]
            if fails(trial):
                deck = trial
    for rel in [deck.main] + sorted(r for r in deck.files if r != deck.main):
        lines = _ddmin(_lines(deck, rel), lambda ls: fails(_with_lines(deck, rel, ls)))
        deck = _with_lines(deck, rel, lines)
    for attr in ("fifos", "dirs"):
        for item in list(getattr(deck, attr)):
            trial = deck.copy()
            getattr(trial, attr).remove(item)
            if fails(trial):
                deck = trial
    return deck, runs[0]


def _with_lines(deck, rel, lines):
    d = deck.copy()
    d.files[rel] = b"".join(lines)
    return d


def _ddmin(items, fails):
    """Delta debugging on a list (Zeller's ddmin): keep one chunk alone, or
    remove one chunk, while the failure persists; halves, quarters, ... down
    to single items. Returns the smaller list."""
    if items and fails([]):
        return []
    n = 2
    while len(items) >= 2:
        size = -(-len(items) // n)
        chunks = [items[k:k + size] for k in range(0, len(items), size)]
        smaller = next((c for c in chunks if fails(c)), None)
        if smaller is not None:
            items, n = smaller, 2
            continue
        if len(chunks) > 2:
            for k in range(len(chunks)):
                rest = [x for j, c in enumerate(chunks) if j != k for x in c]
                if fails(rest):
                    items, n = rest, max(n - 1, 2)
                    break
            else:
                rest = None
            if rest is not None:
                continue
        if n >= len(items):
            break
        n = min(len(items), 2 * n)
    return items


# ------------------------------------------------------------------------------------ driver

@dataclass
class Report:
    decks: int = 0
    runs: int = 0
    seconds: float = 0.0
    counts: dict = field(default_factory=lambda: {c: 0 for c in SEVERITY})
    disagree: int = 0
    disagree_kinds: dict = field(default_factory=lambda: {k: [] for k in AGREEMENT})  # kind -> [indexes]
    disagree_distinct: dict = field(default_factory=dict)  # (kind, seed deck) -> [(index, detail)]
    failures: list = field(default_factory=list)     # (index, class, signature, folder)
    distinct: dict = field(default_factory=dict)     # (class, signature) -> [indexes]
    seed_failures: list = field(default_factory=list)

    def summary(self):
        c = self.counts
        return (f"fuzz: {self.decks} decks, {c['crash']} crashed, {c['hang']} hung, {c['silent-bad']} silent-bad, "
                f"{c['ok-error']} ok-error, {c['ok-run']} ok-run ({self.runs} runs in {self.seconds:.0f} s; "
                f"builds disagree on {self.disagree}; {len(self.distinct)} distinct failures)\n"
                f"fuzz: builds disagree on {self.disagree} decks: " +
                ", ".join(f"{k} {len(v)}" for k, v in self.disagree_kinds.items()) +
                f" (defects: {self.disagree_defects})")

    @property
    def disagree_defects(self):
        return sum(len(self.disagree_kinds[k]) for k in AGREEMENT_DEFECTS)


def save_failure(out, index, deck, results, cls, sig, disagree=()):
    folder = os.path.join(out, "failures", f"{index:05d}-{cls}")
    deck.write(os.path.join(folder, "deck"), {"found": cls, "signature": sig})
    with open(os.path.join(folder, "runs.txt"), "wb") as f:
        for kind, detail in disagree:
            f.write(f"=== the builds disagree on {kind}: {detail}\n".encode())
        for r in results:
            f.write(f"=== {r.build}: {r.cls} {r.sig} (exit {r.rc}, {r.seconds:.1f} s)\n".encode())
            f.write(r.stderr[-3000:] + b"\n")
    return folder


def fuzz(opts, log=print):
    """Purpose: the whole fuzzing run described by opts (see main). Returns a Report."""
    t0 = time.time()
    report = Report()
    os.makedirs(opts.out, exist_ok=True)
    work = tempfile.mkdtemp(prefix="cfe2d-fuzz-")
    try:
        seeds = load_seeds(work, log)
        pool = card_pool(seeds)
        if opts.check_seeds:
            check_seeds(seeds, opts, work, report, log)
        indexes = [opts.index] if opts.index is not None else range(opts.count)
        for k in indexes:
            one_mutant(mutant(seeds, pool, opts.seed, k), k, opts, work, report, log)
            if (report.decks % 100 == 0) and report.decks:
                log(f"fuzz: ... {report.decks} decks, {time.time() - t0:.0f} s")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    report.seconds = time.time() - t0
    return report


def check_seeds(seeds, opts, work, report, log):
    """The unmutated seeds must behave as they are meant to (mostly ok-run)."""
    for seed in seeds:
        results = run_deck(seed, opts.builds, opts.limits, work)
        report.runs += len(results)
        bad = [r for r in results if r.cls != seed.expect]
        for kind, detail in disagreement(results):
            if kind in AGREEMENT_DEFECTS:
                report.seed_failures.append((seed.name, f"disagree-{kind}", detail))
            log(f"fuzz: seed {seed.name}: the builds disagree on {kind}: {detail}")
        if bad:
            report.seed_failures.append((seed.name, bad[0].cls, bad[0].sig))
            log(f"fuzz: seed {seed.name} is not {seed.expect} on {bad[0].build}: {bad[0].cls} {bad[0].sig} "
                f"{bad[0].stderr[-300:].decode(errors='replace')}")
    log(f"fuzz: {len(seeds)} seed decks, {len(report.seed_failures)} not as expected")


def one_mutant(deck, k, opts, work, report, log):
    results = run_deck(deck, opts.builds, opts.limits, work)
    report.decks += 1
    report.runs += len(results)
    cls, sig, primary = verdict(results)
    report.counts[cls] += 1
    disagree = disagreement(results)
    if disagree:
        note_disagreement(deck, k, results, disagree, opts, work, report, log)
    if cls not in FAILURES:
        return
    key = (cls, sig)
    first = key not in report.distinct
    report.distinct.setdefault(key, []).append(k)
    folder = None
    if len(report.distinct[key]) <= opts.keep:
        folder = save_failure(opts.out, k, deck, results, cls, sig)
    report.failures.append((k, cls, sig, folder))
    log(f"fuzz: #{k} {cls} ({primary.build}): {sig} [{deck.name}: {'; '.join(deck.notes)[:200]}]")
    if first and opts.minimise:
        exe = os.path.join(ROOT, primary.build) if not os.path.isabs(primary.build) else primary.build
        small, used = minimise(deck, key, exe, opts.min_limits, work, opts.min_budget, opts.minimise_seconds)
        dest = os.path.join(opts.out, "distinct", f"{len(report.distinct):03d}-{cls}-{k:05d}")
        small.write(dest, {"found": cls, "signature": sig, "build": primary.build})
        nlines = sum(len(_lines(small, r)) for r in small.files)
        log(f"fuzz:    minimised to {nlines} line(s) in {used} runs: {dest}")


def note_disagreement(deck, k, results, disagree, opts, work, report, log):
    """Count, log, save (up to --keep per kind) and, with --minimise, shrink
    the first disagreement of each kind and seed deck."""
    report.disagree += 1
    kind, detail = disagree[0]
    report.disagree_kinds[kind].append(k)
    key = (kind, deck.name)
    first = key not in report.disagree_distinct
    report.disagree_distinct.setdefault(key, []).append((k, detail))
    log(f"fuzz: mutant {k}: the builds disagree on {', '.join(d for d, _ in disagree)}: {detail} "
        f"[{deck.name}: {'; '.join(deck.notes)[:200]}]")
    if len(report.disagree_kinds[kind]) <= opts.keep:
        save_failure(opts.out, k, deck, results, f"disagree-{kind}", detail, disagree)
    if first and opts.minimise and kind in AGREEMENT_DEFECTS:
        def still(rs):
            return [d for d, _ in disagreement(rs)][:1] == [kind]
        small, used = minimise(deck, None, opts.builds, opts.min_limits, work, opts.min_budget,
                               opts.minimise_seconds, still=still)
        dest = os.path.join(opts.out, "distinct", f"disagree-{kind}-{k:05d}")
        small.write(dest, {"found": f"disagree-{kind}", "signature": detail})
        nlines = sum(len(_lines(small, r)) for r in small.files)
        log(f"fuzz:    minimised to {nlines} line(s) in {used} runs: {dest}")


def replay(folder, opts, log=print):
    """Run the builds on one saved deck folder; print and return the Results."""
    deck, meta = load_case(folder)
    work = tempfile.mkdtemp(prefix="cfe2d-fuzz-")
    try:
        results = run_deck(deck, opts.builds, opts.limits, work)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    for r in results:
        log(f"{folder}: {r.build}: {r.cls} {r.sig} (exit {r.rc}, {r.seconds:.1f} s)"
            + (f", expected {meta['expect']}" if "expect" in meta else ""))
    for kind, detail in disagreement(results):
        log(f"{folder}: the builds disagree on {kind}: {detail}")
    return results, meta


def parse_args(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--count", type=int, default=200, help="number of mutants (default 200)")
    ap.add_argument("--index", type=int, help="run only this mutant of the seed")
    ap.add_argument("--time-limit", type=float, default=10.0, help="seconds per run (default 10)")
    ap.add_argument("--mem-limit", type=int, default=2048, help="MiB of address space per run (default 2048)")
    ap.add_argument("--file-limit", type=int, default=512, help="MiB per written file (default 512)")
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "fuzz"))
    ap.add_argument("--builds", default=",".join(DEFAULT_BUILDS), help="comma-separated executables")
    ap.add_argument("--keep", type=int, default=100,
                    help="failing mutants saved per distinct failure (default 100; the rest are counted)")
    ap.add_argument("--minimise", action="store_true", help="shrink the first mutant of each distinct failure")
    ap.add_argument("--minimise-time-limit", type=float, help="seconds per minimising run (default --time-limit)")
    ap.add_argument("--minimise-budget", type=int, default=1000, help="most runs per minimisation (default 1000)")
    ap.add_argument("--minimise-seconds", type=float, default=300.0,
                    help="most seconds per minimisation (default 300)")
    ap.add_argument("--no-seed-check", dest="check_seeds", action="store_false",
                    help="do not first run the unmutated seeds")
    ap.add_argument("--replay", nargs="+", metavar="FOLDER", help="classify saved deck folders and stop")
    args = ap.parse_args(argv)
    args.builds = [b if os.path.isabs(b) else os.path.join(ROOT, b) for b in args.builds.split(",") if b]
    args.limits = Limits(args.time_limit, args.mem_limit, args.file_limit)
    args.min_limits = Limits(args.minimise_time_limit or args.time_limit, args.mem_limit, args.file_limit)
    args.min_budget = args.minimise_budget
    args.out = os.path.abspath(args.out)
    return args


def main(argv=None):
    opts = parse_args(argv)
    missing = [b for b in opts.builds if not os.access(b, os.X_OK)]
    if missing:
        print(f"fuzz: error: not built: {', '.join(missing)} (make -j2 && make debug)", file=sys.stderr)
        return 2
    if opts.replay:
        bad = 0
        for folder in opts.replay:
            results, meta = replay(folder, opts)
            want = meta.get("expect")
            bad += any(r.cls in FAILURES or (want and r.cls not in want.split(",")) for r in results)
            bad += any(kind in AGREEMENT_DEFECTS for kind, _ in disagreement(results))
        return 1 if bad else 0
    report = fuzz(opts)
    lines = [report.summary()]
    for (cls, sig), ks in sorted(report.distinct.items(), key=lambda kv: kv[1][0]):
        lines.append(f"  {cls:10s} x{len(ks):<4d} {sig}  (first: mutant {ks[0]})")
    for (kind, name), items in sorted(report.disagree_distinct.items(), key=lambda kv: kv[1][0][0]):
        lines.append(f"  disagree {kind:10s} x{len(items):<4d} {name}: {items[0][1][:300]}  "
                     f"(first: mutant {items[0][0]})")
    for name, cls, sig in report.seed_failures:
        lines.append(f"  seed {name}: {cls} {sig}")
    print("\n".join(lines))
    with open(os.path.join(opts.out, "summary.txt"), "w") as f:
        f.write(f"python3 scripts/fuzz.py {' '.join(sys.argv[1:] if argv is None else argv)}\n")
        f.write("\n".join(lines) + "\n")
    return 1 if report.failures or report.seed_failures or report.disagree_defects else 0


if __name__ == "__main__":
    sys.exit(main())
