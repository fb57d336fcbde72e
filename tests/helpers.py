"""Shared helpers for the Python tests: run cfe2d on a deck and read back
its listing."""
import os
import shutil
import subprocess

from cfe2d_listing import read_listing

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
CFE2D = os.path.join(ROOT, "bin", "cfe2d")
WORK = os.path.join(HERE, "work")


class Skip(Exception):
    """Raised by a test that cannot run here (and says why)."""


class Run:
    def __init__(self, deck, proc, listing_path):
        self.deck = deck
        self.rc = proc.returncode
        self.stdout = proc.stdout
        self.stderr = proc.stderr
        self.listing_path = listing_path
        self._listing = None

    @property
    def listing(self):
        if self._listing is None:
            self._listing = read_listing(self.listing_path)
        return self._listing

    def ok(self):
        assert self.rc == 0, f"cfe2d failed ({self.rc}) on {self.deck}:\n{self.stderr}"
        return self


def workdir(name):
    d = os.path.join(WORK, name)
    if os.path.isdir(d):
        shutil.rmtree(d)
    os.makedirs(d)
    return d


def run_deck(name, text=None, path=None, files=None, args=()):
    """Run cfe2d on a deck given as text (written to tests/work/<name>/) or
    as an existing path. files: extra {filename: text} written beside it."""
    if text is not None:
        d = workdir(name)
        path = os.path.join(d, name + ".inp")
        with open(path, "w") as f:
            f.write(text)
        for fn, t in (files or {}).items():
            with open(os.path.join(d, fn), "w") as f:
                f.write(t)
        outdir = d
    else:
        outdir = workdir(name)
    proc = subprocess.run([CFE2D, "-q", "-d", "16", "-o", outdir, *args, path], capture_output=True, text=True,
                          timeout=600)
    base = os.path.splitext(os.path.basename(path))[0]
    return Run(path, proc, os.path.join(outdir, base + ".out"))


def rel_err(a, b):
    return abs(a - b) / abs(b)
