"""The debug build (-std=f2008 -fcheck=all: bounds, pointers, recursion)
runs the examples and every broken deck of the battery without a Fortran
runtime error, with the same exit status as the optimised build."""
import glob
import os
import subprocess

from helpers import ROOT, Skip, WORK


DEBUG = os.path.join(ROOT, "build-debug", "cfe2d")


def run(deck, outdir):
    os.makedirs(outdir, exist_ok=True)
    return subprocess.run([DEBUG, "-q", "-o", outdir, deck], capture_output=True, text=True, timeout=600)


def test_debug_build_examples():
    if not os.path.exists(DEBUG):
        raise Skip("build-debug/cfe2d not built (make debug)")
    for name in ("cantilever", "blocks", "shrink_fit"):
        r = run(os.path.join(ROOT, "input", "examples", name + ".inp"), os.path.join(WORK, "debug_" + name))
        assert r.returncode == 0, r.stderr
        assert "Fortran runtime" not in r.stderr, r.stderr


def test_debug_build_bad_decks():
    if not os.path.exists(DEBUG):
        raise Skip("build-debug/cfe2d not built (make debug)")
    decks = sorted(glob.glob(os.path.join(WORK, "bad_*", "bad_*.inp")))
    assert len(decks) >= 25, "run after the bad-deck battery"
    for deck in decks:
        r = run(deck, os.path.join(WORK, "debug_bad"))
        assert r.returncode == 1, (deck, r.returncode, r.stderr)
        assert "Fortran runtime" not in r.stderr and "Backtrace" not in r.stderr, (deck, r.stderr)
        assert ": error:" in r.stderr, (deck, r.stderr)


def test_debug_build_rigid_couplings_transforms():
    """*RIGID BODY, *COUPLING (*KINEMATIC, *DISTRIBUTING) and *TRANSFORM
    decks, good and bad, under -fcheck=all: the good ones run, the bad
    ones stop at their line, none with a runtime error."""
    if not os.path.exists(DEBUG):
        raise Skip("build-debug/cfe2d not built (make debug)")
    import test_rigid as tr
    for good, decks in ((True, tr.decks()), (False, tr.bad_decks())):
        for name, text in decks.items():
            out = os.path.join(WORK, "debug_" + name)
            os.makedirs(out, exist_ok=True)
            path = os.path.join(out, name + ".inp")
            with open(path, "w") as f:
                f.write(text)
            r = run(path, out)
            assert "Fortran runtime" not in r.stderr and "Backtrace" not in r.stderr, (name, r.stderr)
            if good:
                assert r.returncode == 0, (name, r.stderr)
            else:
                assert r.returncode == 1 and ": error:" in r.stderr, (name, r.stderr)
