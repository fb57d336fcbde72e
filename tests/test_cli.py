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


def test_output_dir_made_with_its_parents():
    """--output-dir names a folder three levels below one that exists: all
    three are made (mkdir -p) and the results land in the last one; a
    second run into the now existing folder works as well."""
    import os
    from helpers import ROOT, workdir
    deck = os.path.join(ROOT, "input", "examples", "cantilever.inp")
    out = os.path.join(workdir("cli_output_dir"), "a", "b", "c")
    for _ in range(2):
        r = run("-q", "--output-dir", out, deck)
        assert r.returncode == 0, r.stderr
        assert os.path.isfile(os.path.join(out, "cantilever.out")), os.listdir(os.path.dirname(out))
        assert r.stderr == "", r.stderr


def test_output_dir_that_cannot_be_made_is_an_error():
    """A regular file where a parent folder should be: one error line
    naming the directory and the reason, exit status 1, nothing written."""
    import os
    from helpers import ROOT, workdir
    deck = os.path.join(ROOT, "input", "examples", "cantilever.inp")
    d = workdir("cli_output_dir_bad")
    blocker = os.path.join(d, "file")
    with open(blocker, "w") as f:
        f.write("not a folder\n")
    for out in (os.path.join(blocker, "sub", "dir"), blocker):
        r = run("-q", "-o", out, deck)
        assert r.returncode == 1, (r.returncode, r.stderr)
        lines = r.stderr.splitlines()
        assert len(lines) == 1 and lines[0].startswith(f'cfe2d: error: cannot create output directory "{out}"'), \
            r.stderr
        assert "Not a directory" in lines[0], lines[0]
    assert sorted(os.listdir(d)) == ["file"]
