"""Trust: numbers out of the ordinary range either give right, finite and
parseable results or a clear error; never NaN or Infinity in an output,
never an exponent without its E."""
import math
import os
import re

from helpers import ROOT, run_deck

CANTILEVER = open(os.path.join(ROOT, "input", "examples", "cantilever.inp")).read()
BAD_NUMBER = re.compile(r"(nan|inf|\d[+-]\d{3})", re.IGNORECASE)


def outputs_clean(run):
    """Every output file of the run has no NaN, Infinity or E-less exponent."""
    d = os.path.dirname(run.listing_path)
    for fn in os.listdir(d):
        if fn.endswith((".out", ".csv", ".msh")):
            text = open(os.path.join(d, fn)).read()
            m = BAD_NUMBER.search(text.replace("deck ", "").replace("heading ", ""))
            assert m is None, f"{fn}: {m.group(0)!r} near {text[max(0, m.start() - 60):m.end() + 20]!r}"


def tip_u2(run):
    inc = run.listing.increments[-1]
    return min(inc.block("NODE U", set="TIP")["U2"])


def test_huge_load_scales_exactly():
    """A load of 1e160 is legal: the answer is 1e160 / 0.2 times the unit one
    (linear), finite, and printed with a three-digit exponent."""
    ref = tip_u2(run_deck("trust_load_ref", CANTILEVER).ok())
    run = run_deck("trust_load_1e160", CANTILEVER.replace("TIP, 2, -0.2", "TIP, 2, -1e160")).ok()
    outputs_clean(run)
    u = tip_u2(run)
    assert math.isfinite(u) and abs(u / (ref * 5e160) - 1) < 1e-12, (u, ref)
    mises = run.listing.increments[-1].block("ELEMENT S", set="ALL")["MISES"]
    assert all(math.isfinite(v) and v > 1e150 for v in mises[:4]), mises[:4]


def test_overflow_is_an_error_naming_the_increment():
    """A thickness of 1e-300 under a load of 1e10 makes the displacements
    overflow: a clear error naming the increment and the quantity, non-zero
    exit, no NaN/Inf written."""
    deck = CANTILEVER.replace("*SOLID SECTION, ELSET=BEAM, MATERIAL=M\n1.",
                              "*SOLID SECTION, ELSET=BEAM, MATERIAL=M\n1e-300")
    run = run_deck("trust_thin", deck.replace("TIP, 2, -0.2", "TIP, 2, -1e10"))
    assert run.rc != 0, run.stdout
    assert "cfe2d: error:" in run.stderr and "increment 1" in run.stderr and "not a finite number" in run.stderr, \
        run.stderr
    assert "Traceback" not in run.stderr and "signal" not in run.stderr.lower()
    outputs_clean(run)
