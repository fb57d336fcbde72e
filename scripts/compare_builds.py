#!/usr/bin/env python3
"""Run two cfe2d binaries on the same decks and say where their results
differ: a refactoring must leave every result byte-identical.

  python3 scripts/compare_builds.py --ref /path/to/old/cfe2d --new bin/cfe2d \
      --collect /work/main/tests/work      # the decks a test-suite run wrote

Decks: those collected from a test-suite run's tests/work (copied once into
--decks, default tests/work/compare_builds/decks: tests/helpers.py run_deck writes every
deck it runs there), input/**/*.inp, tests/decks/*, the fuzz seeds
(tests/fuzz/*, with the FIFO and folder case.txt asks for), and the flagship
(input/hertz: hertz.inp and hertz_paper_penalty.inp on the coarse, default
and fine gmsh meshes, hertz_point.inp on its mesh, each with both couplings:
TYPE=NODE TO SURFACE and TYPE=SURFACE TO SURFACE).

Each deck runs once per binary (`-q -d 16 --vtu -o <dir>`, the same deck
path), and compared are: the exit code, stdout and stderr (the output folder
named as <OUT>), the set of files written and every one byte for byte: the
listing with its wall times masked (the `wall_seconds` line and the timing
section's seconds) and its `blas` line (kernel and threads: with
OMP_NUM_THREADS=2 a threaded binary names its element team there), the
contact CSV, the gmsh and VTU files. The iteration
and factorisation counts (the listing's step summaries and increment
headers) are compared on their own too and summed in the last line.
Exit status 1 if any deck differs.

With --rtol R (a change that may move results within a convergence
tolerance, e.g. the Newton iteration's tangent): files that are not
byte-identical are compared as numbers. The iteration logs are left out
(.cvg and .sta files, the listing's "contact iteration" lines, its
iteration and factorisation counts, `iterations=` of the increment
headers, the solver block's factor and contact-solve lines and the exact
contact's notes), and so are the VTU files (binary: their numbers are the
listing's and the CSV's); the rest must have the same lines and words,
and each number a within R of b relative to the largest magnitude of its
column (the same word position in lines with the same number of words)
in the reference file, or 1e-10 of the file's largest where the column is
round-off: |a - b| <= R max(max|column|, 1e-10 max|file|). The largest
such difference is printed per deck.
"""
import argparse
import concurrent.futures
import os
import re
import shutil
import stat
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)

# what a test run leaves beside its decks that is output, not input
OUTPUT_ENDINGS = (".out", ".csv", ".vtu", ".pvd", ".frd", ".msh", ".ref", ".dat", ".sta", ".cvg")
COUNT_KEYS = ("numeric_factorisations", "condensed_factorisations", "condensed_lowrank_statuses", "contact_iterations",
              "newton_iterations", "cutbacks", "contact_block_pivots", "contact_single_pivots")
MESHES = ("coarse", "default", "fine")
COUPLINGS = ("NODE TO SURFACE", "SURFACE TO SURFACE")


def regular(path):
    """A regular file (not a FIFO or device a fuzz test made: opening
    one would wait for a writer)."""
    try:
        return stat.S_ISREG(os.lstat(path).st_mode)
    except OSError:
        return False


def included_names(path):
    """The file names a deck's *INCLUDE cards name (to keep a .msh input)."""
    names = set()
    if not regular(path):
        return names
    try:
        with open(path, errors="replace") as f:
            for line in f:
                m = re.match(r"\s*\*include\s*,\s*input\s*=\s*(.+?)\s*$", line, re.I)
                if m:
                    names.add(os.path.basename(m.group(1).strip('"')))
    except OSError:
        pass
    return names


def collect(src, dest):
    """Copy the input files of every folder below src that holds a deck."""
    n = 0
    for dirpath, _, files in os.walk(src):
        decks = [f for f in files if f.endswith(".inp") and regular(os.path.join(dirpath, f))]
        if not decks:
            continue
        keep = set()
        for d in decks:
            keep |= included_names(os.path.join(dirpath, d))
        out = os.path.join(dest, os.path.relpath(dirpath, src))
        os.makedirs(out, exist_ok=True)
        for f in files:
            p = os.path.join(dirpath, f)
            if not regular(p):
                continue
            if f.endswith(OUTPUT_ENDINGS) and f not in keep:
                continue
            shutil.copy2(p, os.path.join(out, f))
        n += len(decks)
    return n


def flagship(dest):
    """The flagship decks: every mesh, both couplings."""
    import run_hertz
    paths = []
    for mesh in MESHES:
        for penalty in ("auto", "paper"):
            base = os.path.join(dest, f"{mesh}_{penalty}")
            deck = run_hertz.write_case(base, mesh=mesh, penalty=penalty)
            paths += couplings(deck)
    d = os.path.join(dest, "point")
    os.makedirs(d, exist_ok=True)
    subprocess.run(["gmsh", "-2", "-format", "inp", "-setnumber", "Mesh.SaveGroupsOfNodes", "1", "-o",
                    os.path.join(d, "hertz_point_mesh.inp"), os.path.join(ROOT, "input", "hertz", "hertz_point.geo")],
                   check=True, capture_output=True)
    shutil.copy(os.path.join(ROOT, "input", "hertz", "hertz_point.inp"), d)
    paths += couplings(os.path.join(d, "hertz_point.inp"))
    return paths


def couplings(deck):
    """The deck with each coupling written on its *CONTACT PAIR cards."""
    with open(deck) as f:
        text = f.read()
    out = []
    for c in COUPLINGS:
        t, n = re.subn(r"(?im)^(\*CONTACT PAIR[^\n]*)$", lambda m: m.group(1) + ", TYPE=" + c, text)
        if n == 0:
            return [deck]
        p = deck[:-4] + "_" + c.split()[0].lower() + ".inp"
        with open(p, "w") as f:
            f.write(t)
        out.append(p)
    return out


def fuzz_seeds():
    """(deck, setup) of every fuzz seed: setup makes its FIFO or folder."""
    out = []
    base = os.path.join(ROOT, "tests", "fuzz")
    for name in sorted(os.listdir(base)):
        case = os.path.join(base, name, "case.txt")
        if not os.path.isfile(case):
            continue
        kv = dict(l.strip().split("=", 1) for l in open(case) if "=" in l and not l.startswith("#"))
        out.append((os.path.join(base, name), kv))
    return out


def gather(args):
    decks = []
    if args.collect:
        if os.path.isdir(args.decks):
            shutil.rmtree(args.decks)
        print(f"collected {collect(args.collect, args.decks)} deck files from {args.collect}", flush=True)
    if os.path.isdir(args.decks):
        for dirpath, _, files in os.walk(args.decks):
            decks += [os.path.join(dirpath, f) for f in sorted(files) if f.endswith(".inp")]
    for dirpath, _, files in os.walk(os.path.join(ROOT, "input")):
        decks += [os.path.join(dirpath, f) for f in sorted(files) if f.endswith(".inp")]
    for dirpath, _, files in os.walk(os.path.join(ROOT, "tests", "decks")):
        decks += [os.path.join(dirpath, f) for f in sorted(files) if f.endswith(".inp")]
    work = os.path.join(args.work, "seeds")
    if os.path.isdir(work):
        shutil.rmtree(work)
    for src, kv in fuzz_seeds():
        d = os.path.join(work, os.path.basename(src))
        shutil.copytree(src, d)
        if "fifo" in kv:
            continue          # a FIFO with no writer: each run would wait for the other's
        if "dir" in kv:
            os.makedirs(os.path.join(d, kv["dir"]), exist_ok=True)
        decks.append(os.path.join(d, kv.get("main", "deck.inp")))
    if args.flagship:
        fl = os.path.join(args.work, "flagship")
        if os.path.isdir(fl):
            shutil.rmtree(fl)
        decks += flagship(fl)
    decks = sorted(set(decks))
    if args.k:
        decks = [d for d in decks if args.k in d]
    return decks


def mask_listing(text):
    """The listing without its wall times and its blas line (the BLAS
    kernel and the thread counts of the run's environment)."""
    out, timing = [], False
    for line in text.splitlines(keepends=True):
        if line.startswith("---"):
            timing = line.startswith("--- TIMING")
        if line.startswith("wall_seconds "):
            line = "wall_seconds <masked>\n"
        elif line.startswith("blas "):
            line = "blas <masked>\n"
        elif timing and re.match(r"^\S+ [-+0-9.Ee]*\.[-+0-9.Ee]*\s*$", line):
            line = line.split()[0] + " <masked>\n"
        out.append(line)
    return "".join(out)


def mask_frd(text):
    """A .frd without the date and time of its run (its 1UDATE and 1UTIME
    header records)."""
    return re.sub(r"(?m)^(    1U(?:DATE|TIME)) .*$", r"\1 <masked>", text)


def counts(text):
    """The iteration and factorisation counts a listing reports."""
    c = {k: 0 for k in COUNT_KEYS}
    c["increment_iterations"] = 0
    timing = False
    for line in text.splitlines():
        if line.startswith("---"):
            timing = line.startswith("--- TIMING")
        parts = line.split()
        if not timing and len(parts) == 2 and parts[0] in c and parts[1].isdigit():
            c[parts[0]] += int(parts[1])
        m = re.search(r" iterations=(\d+)", line)
        if line.startswith("=== INCREMENT") and m:
            c["increment_iterations"] += int(m.group(1))
    return c


NUMBER = re.compile(r"^[-+]?(?:\d+\.?\d*|\.\d+)(?:[Ee][-+]?\d+)?$")
LOG_LINE = re.compile(r"^(contact iteration |exact contact: |(?:" + "|".join(COUNT_KEYS) + r"|element_calls_\w+|"
                      r"iterations|increment_iterations|direct_multiplier_solves|factor|contact_solve|"
                      r"contact_equations) )")


def words(text):
    """The lines of a result file as lists of words, iteration logs left out."""
    out = []
    for line in text.splitlines():
        if LOG_LINE.match(line) or "direct multiplier solves" in line or " Newton iterations" in line:
            continue
        line = re.sub(r" iterations=\d+", " iterations=<masked>", line)
        out.append(re.split(r"[\s,;]+", line.strip()))
    return out


def numeric_difference(a, b):
    """The largest difference of the numbers of two result files relative
    to their column's largest magnitude (words()), or None where lines or
    other words differ."""
    la, lb = words(a), words(b)
    if len(la) != len(lb):
        return None
    scale = {}
    for wa in la:
        for i, w in enumerate(wa):
            if NUMBER.match(w):
                key = (len(wa), i)
                scale[key] = max(scale.get(key, 0.0), abs(float(w)))
    # a column of round-off (gaps of closed contact: 1e-17) is judged
    # against 1e-10 of the file's largest magnitude
    floor = 1e-10 * max(scale.values(), default=0.0)
    worst = 0.0
    for wa, wb in zip(la, lb):
        if len(wa) != len(wb):
            return None
        for i, (x, y) in enumerate(zip(wa, wb)):
            if x == y:
                continue
            if not (NUMBER.match(x) and NUMBER.match(y)):
                return None
            ref = max(scale[(len(wa), i)], floor)
            d = abs(float(x) - float(y))
            worst = max(worst, d / ref if ref > 0.0 else float("inf"))
    return worst


def run(binary, deck, outdir, timeout):
    if os.path.isdir(outdir):
        shutil.rmtree(outdir)
    os.makedirs(outdir)
    try:
        p = subprocess.run([binary, "-q", "-d", "16", "--vtu", "-o", outdir, deck], capture_output=True,
                           timeout=timeout, cwd=os.path.dirname(deck))
        rc, so, se = p.returncode, p.stdout, p.stderr
    except subprocess.TimeoutExpired:
        rc, so, se = "timeout", b"", b""
    files = {}
    for dirpath, _, names in os.walk(outdir):
        for f in names:
            p = os.path.join(dirpath, f)
            with open(p, "rb") as fh:
                data = fh.read().replace(outdir.encode(), b"<OUT>")
            if f.endswith(".out"):
                data = mask_listing(data.decode(errors="replace")).encode()
            elif f.endswith(".frd"):
                data = mask_frd(data.decode(errors="replace")).encode()
            files[os.path.relpath(p, outdir)] = data
    return dict(rc=rc, stdout=so.replace(outdir.encode(), b"<OUT>"), stderr=se.replace(outdir.encode(), b"<OUT>"),
                files=files)


def compare(args, i, deck):
    tag = f"{i:05d}"
    a = run(args.ref, deck, os.path.join(args.work, "ref", tag), args.timeout)
    b = run(args.new, deck, os.path.join(args.work, "new", tag), args.timeout)
    diffs = []
    for key in ("rc", "stdout", "stderr"):
        if a[key] != b[key]:
            diffs.append(key)
    if sorted(a["files"]) != sorted(b["files"]):
        diffs.append("file set: " + " ".join(sorted(set(a["files"]) ^ set(b["files"]))))
    worst = 0.0
    for f in sorted(set(a["files"]) & set(b["files"])):
        if a["files"][f] == b["files"][f]:
            continue
        if args.rtol is None:
            diffs.append(f)
        elif not f.endswith((".cvg", ".sta", ".vtu")):
            d = numeric_difference(a["files"][f].decode(errors="replace"), b["files"][f].decode(errors="replace"))
            if d is None or d > args.rtol:
                diffs.append(f + (": lines or words differ" if d is None else f": {d:.2e}"))
            else:
                worst = max(worst, d)
    if worst > 0.0:
        print(f"within {args.rtol:g}: {deck} ({tag}): largest relative difference {worst:.2e}", flush=True)
    ca, cb = {}, {}
    for f, data in a["files"].items():
        if f.endswith(".out"):
            ca = counts(data.decode(errors="replace"))
            cb = counts(b["files"].get(f, b"").decode(errors="replace"))
            if ca != cb and args.rtol is None:
                diffs.append(f"counts {ca} != {cb}")
    if not args.keep and not diffs:
        shutil.rmtree(os.path.join(args.work, "ref", tag), ignore_errors=True)
        shutil.rmtree(os.path.join(args.work, "new", tag), ignore_errors=True)
    return deck, tag, diffs, cb if args.rtol is not None else ca, len(a["files"])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--ref", required=True, help="the binary before the change")
    ap.add_argument("--new", default=os.path.join(ROOT, "bin", "cfe2d"), help="the binary after it")
    ap.add_argument("--collect", help="a tests/work folder of a test-suite run: copy its decks into --decks")
    ap.add_argument("--decks", default=os.path.join(ROOT, "tests", "work", "compare_builds", "decks"))
    ap.add_argument("--work", default=os.path.join(ROOT, "tests", "work", "compare_builds", "runs"))
    ap.add_argument("--no-flagship", dest="flagship", action="store_false", help="leave out the gmsh-meshed flagship")
    ap.add_argument("-k", default="", help="only decks whose path contains this")
    ap.add_argument("-j", "--jobs", type=int, default=1)
    ap.add_argument("--timeout", type=float, default=300.0)
    ap.add_argument("--keep", action="store_true", help="keep the outputs of decks that agree")
    ap.add_argument("--rtol", type=float, help="numbers within this of their column's largest magnitude agree; "
                    "iteration logs and counts are not compared (the counts summed are the new binary's)")
    args = ap.parse_args()
    args.ref, args.new = os.path.abspath(args.ref), os.path.abspath(args.new)
    decks = gather(args)
    print(f"{len(decks)} decks, {args.ref} against {args.new}", flush=True)
    total = {}
    ndiff = nfiles = 0
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as ex:
        for deck, tag, diffs, c, nf in ex.map(lambda x: compare(args, *x), enumerate(decks)):
            nfiles += nf
            for k, v in c.items():
                total[k] = total.get(k, 0) + v
            if diffs:
                ndiff += 1
                print(f"DIFF {deck} ({tag}): {'; '.join(diffs)[:800]}", flush=True)
    print(f"{len(decks)} decks compared, {nfiles} result files each, {ndiff} differ; counts summed: " +
          ", ".join(f"{k} {v}" for k, v in total.items()), flush=True)
    sys.exit(1 if ndiff else 0)


if __name__ == "__main__":
    main()
