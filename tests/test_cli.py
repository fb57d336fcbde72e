"""Command line: --help, --version, unknown options, no deck."""
import subprocess

from helpers import CFE2D


def run(*args):
    return subprocess.run([CFE2D, *args], capture_output=True, text=True)


def test_help():
    r = run("--help")
    assert r.returncode == 0 and "usage: cfe2d" in r.stdout and "--output-dir" in r.stdout


def test_version():
    r = run("--version")
    assert r.returncode == 0 and r.stdout.startswith("cfe2d ")


def test_unknown_option():
    r = run("--frobnicate", "x.inp")
    assert r.returncode != 0 and "unknown option" in r.stderr


def test_no_deck():
    r = run()
    assert r.returncode != 0 and "no deck given" in r.stderr
