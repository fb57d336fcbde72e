#!/usr/bin/env python3
"""The test runner of `make check`.

Runs the Fortran unit-test programs (each prints PASS/FAIL lines) and every
function named test_* in tests/test_*.py (a test fails by raising), then
prints one line per test and the closing line "N passed, N failed".
A module may also define cases() yielding (name, callable) pairs.
"""
import argparse
import importlib
import os
import subprocess
import sys
import time
import traceback

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(ROOT, "scripts"))

from helpers import Skip  # noqa: E402

UNIT_PROGRAMS = ["test_elements", "test_skyline", "test_cfe", "test_solvers", "test_numbering", "test_constraints",
                 "test_strings", "test_contact_status", "test_nonlinear"]


def where_failed(e, limit):
    """A failure's exception and the test line that raised it first (a CI
    log may keep only a failure's first lines), then the traceback."""
    frames = traceback.extract_tb(e.__traceback__)
    test_frames = [f for f in frames if os.path.basename(f.filename).startswith("test_")]
    at = test_frames[-1] if test_frames else (frames[-1] if frames else None)
    head = f"{type(e).__name__}: {e}" if str(e) else type(e).__name__
    if at is not None:
        head += f" (at {os.path.basename(at.filename)}:{at.lineno}: {(at.line or '').strip()})"
    return head + "\n" + traceback.format_exc(limit=limit)


# Result files the tests write beside their listings: the gmsh and
# CalculiX result files of every increment (the flagship's are 166 MB a
# run) and the ParaView ones. A whole run wrote 6 GB into tests/work, 5.6
# of it these: enough to fill a machine's disk in the middle of the run
# (an ENOSPC fails every test after it; seen here on a shared machine).
BULKY = (".frd", ".msh", ".vtu")


def drop_bulky_results(since):
    """Deletes the bulky result files written into tests/work since the
    time `since` (a test file's start). Called after a test file whose
    tests all passed: its files were read by then; a failed file keeps
    them to be looked at."""
    work = os.path.join(HERE, "work")
    freed = 0
    for top, _, files in os.walk(work):
        for f in files:
            if f.endswith(BULKY):
                path = os.path.join(top, f)
                try:
                    st = os.stat(path)
                    if st.st_mtime >= since:
                        os.remove(path)
                        freed += st.st_size
                except OSError:
                    pass
    return freed


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default="build")
    ap.add_argument("-k", default="", help="run only tests whose name contains this")
    ap.add_argument("--keep-results", action="store_true",
                    help="keep the .frd, .msh and .vtu files of test files that passed (deleted by default)")
    args = ap.parse_args()
    passed = failed = skipped = 0

    def record(name, status, detail=""):
        nonlocal passed, failed, skipped
        if args.k and args.k not in name:
            return
        if status == "PASS":
            passed += 1
        elif status == "SKIP":
            skipped += 1
        else:
            failed += 1
        print(f"{status} {name}" + (f": {detail}" if detail else ""), flush=True)

    for prog in UNIT_PROGRAMS:
        exe = os.path.join(ROOT, args.build, "tests", prog)
        if not os.path.exists(exe):
            record(prog, "FAIL", f"{exe} was not built")
            continue
        r = subprocess.run([exe], capture_output=True, text=True)
        seen = 0
        for line in r.stdout.splitlines():
            if line.startswith("PASS ") or line.startswith("FAIL "):
                status, rest = line.split(" ", 1)
                name, detail = rest, ""
                if status == "FAIL":
                    name, _, detail = rest.rpartition(": ")
                record(f"{prog}: {name}", status, detail)
                seen += 1
        if seen == 0 or (r.returncode != 0 and "FAIL" not in r.stdout):
            record(prog, "FAIL", f"exit {r.returncode}: {r.stderr.strip()[:300]}")

    for fname in sorted(os.listdir(HERE)):
        if not (fname.startswith("test_") and fname.endswith(".py")):
            continue
        mod = importlib.import_module(fname[:-3])
        tests = [(f"{fname[:-3]}: {n}", getattr(mod, n)) for n in dir(mod)
                 if n.startswith("test_") and callable(getattr(mod, n))]
        tests.sort(key=lambda t: getattr(t[1], "__code__", None).co_firstlineno
                   if hasattr(t[1], "__code__") else 0)
        if hasattr(mod, "cases"):
            tests += [(f"{fname[:-3]}: {n}", f) for n, f in mod.cases()]
        failed_before = failed
        module_start = time.time() - 1.0   # mtimes may be coarser than time()
        for name, fn in tests:
            if args.k and args.k not in name:
                continue
            t0 = time.time()
            try:
                fn()
            except Skip as e:
                record(name, "SKIP", str(e))
            except AssertionError as e:
                record(name, "FAIL", str(e) or where_failed(e, 2))
            except Exception as e:
                record(name, "FAIL", where_failed(e, 3))
            else:
                record(name, "PASS", f"{time.time() - t0:.1f}s" if time.time() - t0 > 5 else "")
        if failed == failed_before and not args.keep_results:
            drop_bulky_results(module_start)

    line = f"{passed} passed, {failed} failed"
    if skipped:
        line += f", {skipped} skipped"
    print(line)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
