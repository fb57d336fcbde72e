"""The sanitizer build (-fsanitize=address,undefined, `make sanitize`):
the examples, every broken deck of the battery and the flagship's coarse
mesh run without an address or undefined-behaviour report, with the exit
status of the optimised build. Leaks at exit are not checked: the program
ends through exit() with its arrays still allocated, by design."""
import glob
import os
import shutil
import subprocess

from helpers import ROOT, Skip, WORK

ASAN = os.path.join(ROOT, "build-asan", "cfe2d")
ENV = dict(os.environ, ASAN_OPTIONS="detect_leaks=0:abort_on_error=0", UBSAN_OPTIONS="print_stacktrace=1")
REPORTS = ("ERROR: AddressSanitizer", "runtime error:", "Fortran runtime", "Backtrace")


def run(deck, outdir):
    os.makedirs(outdir, exist_ok=True)
    return subprocess.run([ASAN, "-q", "-o", outdir, deck], capture_output=True, text=True, timeout=900, env=ENV)


def clean(r, what):
    for rep in REPORTS:
        assert rep not in r.stderr, (what, r.stderr[-3000:])


def need_build():
    if not os.path.exists(ASAN):
        raise Skip("build-asan/cfe2d not built (make sanitize)")


def test_sanitizer_examples():
    need_build()
    for name in ("cantilever", "blocks", "shrink_fit"):
        r = run(os.path.join(ROOT, "input", "examples", name + ".inp"), os.path.join(WORK, "asan_" + name))
        clean(r, name)
        assert r.returncode == 0, r.stderr


def test_sanitizer_bad_decks():
    need_build()
    decks = sorted(glob.glob(os.path.join(WORK, "bad_*", "bad_*.inp")))
    assert len(decks) >= 25, "run after the bad-deck battery"
    for deck in decks:
        r = run(deck, os.path.join(WORK, "asan_bad"))
        clean(r, deck)
        assert r.returncode == 1 and ": error:" in r.stderr, (deck, r.returncode, r.stderr[-2000:])


def test_sanitizer_flagship_coarse():
    """The flagship deck on the coarse mesh (h = 0.1 mm, 17 534 equations),
    the whole contact history."""
    need_build()
    if shutil.which("gmsh") is None:
        raise Skip("gmsh is not installed")
    out = os.path.join(WORK, "asan_hertz_coarse")
    os.makedirs(out, exist_ok=True)
    subprocess.run(["gmsh", "-2", "-format", "inp", "-setnumber", "Mesh.SaveGroupsOfNodes", "1",
                    "-setnumber", "h", "0.1", "-o", os.path.join(out, "hertz_mesh.inp"),
                    os.path.join(ROOT, "input", "hertz", "hertz.geo")], check=True, capture_output=True)
    shutil.copy(os.path.join(ROOT, "input", "hertz", "hertz.inp"), out)
    r = run(os.path.join(out, "hertz.inp"), out)
    clean(r, "hertz coarse")
    assert r.returncode == 0, r.stderr[-2000:]
    assert open(os.path.join(out, "hertz.out")).read().count("=== INCREMENT") == 20


def test_sanitizer_constraints_trusses_springs_masses():
    """The decks of the cards that grow the model while it is read or
    resolve chains of constraints (*PRE-TENSION SECTION copies nodes, *TIE
    and *EQUATION make constraints, a tie onto a cut chains them), and
    trusses, springs and point masses, run clean under the sanitizers
    (two use-after-free bugs of this kind were found by reading: the
    release build survived them by luck)."""
    need_build()
    import test_constraint_decks as tc
    import test_equation as te  # noqa: F401  (its decks are built by its tests' helpers)
    import test_point_mass as tm
    import test_springs as ts
    import test_trusses as tt
    decks = {"pret5": tc.PRET5, "tie_patch": tc.tie_patch_deck(True, 4, 1e-4, "TOP, P, -3.\nRIGHT, P, -2.\n"),
             "truss3": tt.bar_deck("T3D3"), "springs": ts.v_springs(0.4),
             "mass": tm.bar(f"MA, GRAV, {tm.G}, 1., 0., 0.")}
    # a chain long enough to grow the constraint buffers while it is substituted
    chain = tt.bar_deck().replace("*BOUNDARY", "*NODE\n" + "".join(f"{100 + k}, 5., {k}.\n" for k in range(40))
                                   + "*EQUATION\n" + "".join(f"2\n{100 + k}, 1, 1., {101 + k}, 1, -1.\n"
                                                               for k in range(39))
                                   + "2\n139, 1, 1., 2, 1, -1.\n*BOUNDARY", 1)
    decks["chain"] = chain
    for name, text in decks.items():
        out = os.path.join(WORK, "asan_" + name)
        os.makedirs(out, exist_ok=True)
        path = os.path.join(out, name + ".inp")
        with open(path, "w") as f:
            f.write(text)
        r = run(path, out)
        clean(r, name)
        assert r.returncode == 0, (name, r.stderr[-2000:])


def test_sanitizer_rigid_couplings_transforms():
    """The decks of *RIGID BODY, *COUPLING (*KINEMATIC, *DISTRIBUTING) and
    *TRANSFORM (nodes made while the deck is read, equations appended,
    cards redirected to the nodes of local displacements) run clean, the
    good ones to the end and the bad ones to their error at a line."""
    need_build()
    import test_rigid as tr
    for good, decks in ((True, tr.decks()), (False, tr.bad_decks())):
        for name, text in decks.items():
            out = os.path.join(WORK, "asan_" + name)
            os.makedirs(out, exist_ok=True)
            path = os.path.join(out, name + ".inp")
            with open(path, "w") as f:
                f.write(text)
            r = run(path, out)
            clean(r, name)
            if good:
                assert r.returncode == 0, (name, r.stderr[-2000:])
            else:
                assert r.returncode == 1 and ": error:" in r.stderr, (name, r.returncode, r.stderr[-2000:])
