"""The structure of the analysis layer that issue 29 set up, checked on the
sources: routines short enough to read, one equilibrium loop (the full and
condensed paths differ only in how a status's linear system is solved), and
the masking of scripts/compare_builds.py, which shows refactorings of it to
be byte-identical."""
import glob
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(ROOT, "scripts"))

import compare_builds  # noqa: E402

ANALYSIS = os.path.join(ROOT, "src", "analysis")
_START = re.compile(r"^\s*(?:(?:pure|elemental|recursive|impure|module)\s+)*(?:(?:real|integer|logical|character|type)"
                    r"\S*\s+)?(?:(?:pure|elemental|recursive|impure)\s+)*(subroutine|function)\s+(\w+)", re.I)
_END = re.compile(r"^\s*end\s+(subroutine|function)\b", re.I)


def routine_lengths(path):
    """(name, first line, number of lines) of every routine of a file."""
    out, stack = [], []
    with open(path) as f:
        for i, line in enumerate(f, 1):
            if _END.match(line):
                name, start = stack.pop()
                out.append((name, start, i - start + 1))
            elif _START.match(line) and not line.strip().lower().startswith("end"):
                stack.append((_START.match(line).group(2), i))
    assert not stack, f"{path}: unterminated routine {stack}"
    return out


def test_analysis_routines_at_most_80_lines():
    """No routine of src/ (every layer, not only the analysis) is over 80
    lines (issue 29)."""
    long = []
    files = sorted(glob.glob(os.path.join(ROOT, "src", "**", "*.f90"), recursive=True))
    assert len(files) >= 80
    for path in files:
        long += [f"{os.path.basename(path)}:{s} {n} ({k} lines)" for n, s, k in routine_lengths(path) if k > 80]
    assert not long, "routines over 80 lines: " + ", ".join(long)


def test_routine_lengths_counts_a_long_routine():
    path = os.path.join(HERE, "work", "structure_long.f90")
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write("module x\ncontains\n  pure real(dp) function f(a)\n" + "    a = a\n" * 90 +
                "  end function f\n  subroutine s()\n  end subroutine s\nend module x\n")
    assert routine_lengths(path) == [("f", 3, 92), ("s", 95, 2)]


def test_one_status_loop():
    """The status switch and the Newton test are called in one place, the
    loop (equilibrium_loop.f90), which both paths share."""
    calls = {}
    for path in glob.glob(os.path.join(ANALYSIS, "*.f90")):
        with open(path) as f:
            text = re.sub(r"!.*", "", f.read())
        for name in ("contact_switch", "newton_test", "augment_multipliers", "begin_status_search"):
            if re.search(r"\bcall\s+" + name + r"\b|=\s*" + name + r"\s*\(|\(\s*\.not\.\s*" + name, text, re.I):
                calls.setdefault(name, set()).add(os.path.basename(path))
    assert calls["contact_switch"] == {"equilibrium_loop.f90"}, calls
    assert calls["newton_test"] == {"equilibrium_loop.f90"}, calls
    assert calls["augment_multipliers"] == {"equilibrium_loop.f90"}, calls


def test_compare_builds_masks_only_wall_times():
    listing = ("--- STEP SUMMARY step=1\nitem value\nincrements 2\nnumeric_factorisations 3\n"
               "contact_iterations 7\nwall_seconds 0.013\n\n--- TIMING (wall seconds)\nitem value\nread 0.002\n"
               "factor 1.250\nnumeric_factorisations 3\ncondensed_factorisations 1\n"
               "=== INCREMENT step=1 increment=1 time=1.0 total_time=1.0 iterations=4 ===\n")
    masked = compare_builds.mask_listing(listing)
    assert "0.013" not in masked and "0.002" not in masked and "1.250" not in masked
    assert "numeric_factorisations 3\ncondensed_factorisations 1\n" in masked
    assert "contact_iterations 7\n" in masked and "iterations=4" in masked
    c = compare_builds.counts(listing)
    assert c["numeric_factorisations"] == 3 and c["contact_iterations"] == 7
    assert c["increment_iterations"] == 4
    # a different count is a difference; a different wall time is not
    assert compare_builds.mask_listing(listing.replace("0.013", "9.9")) == masked
    assert compare_builds.mask_listing(listing.replace("contact_iterations 7", "contact_iterations 8")) != masked


def test_compare_builds_masks_the_frd_run_date_only():
    """A .frd's 1UDATE and 1UTIME records (when it was run) are masked, its
    values are not."""
    frd = ("    1C\n    1UDATE              27.november.2026\n    1UTIME              05:22:57\n"
           "    1UPGM               cfe2d\n -1         1 1.00000E+00 2.00000E+00\n")
    masked = compare_builds.mask_frd(frd)
    assert "05:22:57" not in masked and "27.november" not in masked
    assert compare_builds.mask_frd(frd.replace("05:22:57", "06:00:01")) == masked
    assert compare_builds.mask_frd(frd.replace("2.00000E+00", "2.00001E+00")) != masked
    assert "    1UPGM               cfe2d\n" in masked
