"""Regression: the example decks against reference listings made with
`python3 tests/test_regression.py --update` (after a change that is meant
to alter results, and only then). Every number of every increment block
must agree within |a - b| <= 1e-6 |b| + 1e-9 * (largest value in the
blocks of that name over the whole reference), so that round-off around
zero (an unloaded increment) does not count; the verification tests elsewhere check that the answers are right,
these check that they do not drift."""
import os
import shutil
import sys

from helpers import ROOT, run_deck

REF_DIR = os.path.join(ROOT, "tests", "regression")
DECKS = ["cantilever", "blocks"]
RTOL, ATOL = 1e-6, 1e-9


def run_example(name):
    return run_deck("regression_" + name, path=os.path.join(ROOT, "input", "examples", name + ".inp"),
                    args=("--digits", "10")).ok()


def compare(listing, reference):
    incs, refs = listing.increments, reference.increments
    assert len(incs) == len(refs), f"{len(incs)} increments, reference has {len(refs)}"
    scales = {}
    for ref in refs:
        for r in ref.blocks:
            vals = [abs(v) for row in r.rows for v in row[1:] if isinstance(v, float)]
            scales[r.name] = max([scales.get(r.name, 0.0)] + vals)
    for inc, ref in zip(incs, refs):
        assert inc.attrs == ref.attrs, (inc.attrs, ref.attrs)
        assert [b.name for b in inc.blocks] == [b.name for b in ref.blocks]
        for b, r in zip(inc.blocks, ref.blocks):
            assert b.columns == r.columns and len(b.rows) == len(r.rows), b.name
            scale = scales[r.name]
            for j, col in enumerate(b.columns):
                vals = [row[j] for row in r.rows]
                if not all(isinstance(v, float) for v in vals):
                    assert [row[j] for row in b.rows] == vals, f"{b.name} {col}"
                    continue
                for row, rv in zip(b.rows, vals):
                    v = row[j]
                    assert abs(v - rv) <= RTOL * abs(rv) + ATOL * scale, \
                        f"step {inc.step} inc {inc.number} {b.name} {col}: {v} vs reference {rv}"


def check(name):
    from cfe2d_listing import read_listing
    run = run_example(name)
    compare(run.listing, read_listing(os.path.join(REF_DIR, name + ".ref")))


def cases():
    for name in DECKS:
        yield f"regression {name}", (lambda n=name: check(n))


if __name__ == "__main__" and "--update" in sys.argv:
    sys.path.insert(0, os.path.join(ROOT, "scripts"))
    os.makedirs(REF_DIR, exist_ok=True)
    for name in DECKS:
        run = run_example(name)
        shutil.copy(run.listing_path, os.path.join(REF_DIR, name + ".ref"))
        print("updated", os.path.join(REF_DIR, name + ".ref"))
