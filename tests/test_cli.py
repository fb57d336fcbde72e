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


def test_times_print_with_a_zero_before_the_point():
    """A short run's times are below one second: the progress line's step
    line ends '0.00 s' style (never '.00 s'), and the listing's
    wall_seconds and timing rows are '0.001' style, without a sign."""
    import os
    import re
    from helpers import ROOT, workdir
    deck = os.path.join(ROOT, "input", "examples", "cantilever.inp")
    out = workdir("cli_times")
    r = run("-o", out, deck)
    assert r.returncode == 0, r.stderr
    steps = [line for line in r.stdout.splitlines() if re.match(r"step \d+ done:", line)]
    assert steps, r.stdout
    for line in steps:
        assert re.search(r", (0|[1-9]\d*)\.\d\d s$", line), line
        assert float(line.rsplit(", ", 1)[1][:-2]) < 1.0, "the run is meant to take under a second: " + line
    timing = [line for line in r.stdout.splitlines() if line.startswith("time (s): ")]
    assert len(timing) == 1, r.stdout
    for item in timing[0][len("time (s): "):].split(", "):
        assert re.fullmatch(r"[a-z ]+ (0|[1-9]\d*)\.\d{3}", item), item
    text = open(os.path.join(out, "cantilever.out")).read()
    seconds = re.findall(r"^wall_seconds (\S+)$", text, re.M)
    assert seconds, "no wall_seconds in the listing"
    for s in seconds:
        assert re.fullmatch(r"(0|[1-9]\d*)\.\d{3}", s), s
    rows = text[text.index("--- TIMING"):].splitlines()[2:]
    times = [row.split() for row in rows if row and not row.split()[0].endswith("factorisations")]
    assert len(times) == 11, rows
    for name, value in times:
        assert re.fullmatch(r"(0|[1-9]\d*)\.\d{3}", value), (name, value)
