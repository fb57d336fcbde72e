"""The cost of an increment's results (issue 32, item 4): stresses are
computed only at the increments whose output is written (FREQUENCY=,
TIME POINTS=, the step's last), and only when a card asks for them; the
written ones are still right. Counted by the listing's element routine
calls (element_calls_continuum_stresses: one per element and evaluation)."""
import os
import re

from helpers import run_deck
from test_frd import LX, SIG, plate, read_frd

NE = 8          # the plate's CPS4 elements (4 x 2)


def stress_calls(listing):
    with open(listing) as f:
        return sum(int(v) for v in re.findall(r"^element_calls_continuum_stresses (\d+)$", f.read(), re.M))


def test_output_cost_stresses_at_written_increments_only():
    """Four increments (0.25 each): FREQUENCY=2 writes increments 2 and 4,
    FREQUENCY=3 writes 3 and 4 (the step's end), FREQUENCY=1 all four,
    TIME POINTS 0.25 and 0.6 increments 1, 3 and 4;
    the stresses are evaluated exactly there (8 elements each time), and
    the .frd's stresses at those increments are SIG t (uniform tension,
    to 1e-6)."""
    cases = [(f"FREQUENCY={f}", "", w) for f, w in ((2, [2, 4]), (3, [3, 4]), (1, [1, 2, 3, 4]))]
    # a point on increment 1's end (written there, not again at 2), one
    # inside increment 3, the step's end
    cases.append(("TIME POINTS=TP", "*TIME POINTS, NAME=TP\n0.25, 0.6\n", [1, 3, 4]))
    for k, (param, points, written) in enumerate(cases):
        name = f"cost_schedule{k}"
        run = run_deck(name, plate("CPS4", f"*NODE FILE, {param}\nU\n*EL FILE\nS\n") + points).ok()
        freq = param
        assert stress_calls(run.listing_path) == NE * len(written), (freq, stress_calls(run.listing_path))
        frd = os.path.join(os.path.dirname(run.listing_path), name + ".frd")
        sets = read_frd(frd)[2]
        assert [inc for _, inc, _, _ in sets] == written, sets
        for _, _, t, blocks in sets:
            sxx = [v[0] for v in blocks["STRESS"].values()]
            assert max(abs(s - SIG * t) for s in sxx) <= 1e-6 * SIG, (t, sxx)


def test_output_cost_no_stresses_unless_asked():
    """Displacements alone asked for: no stress evaluation at all; the
    right edge moves by SIG LX / E at the end (plane stress, to 1e-6)."""
    run = run_deck("cost_u_only", plate("CPS4", "*NODE FILE\nU\n")).ok()
    assert stress_calls(run.listing_path) == 0
    frd = os.path.join(os.path.dirname(run.listing_path), "cost_u_only.frd")
    nodes, _, sets = read_frd(frd)
    _, _, t, blocks = sets[-1]
    right = [n for n, x in nodes.items() if abs(x[0] - LX) < 1e-12]
    for n in right:
        assert abs(blocks["DISP"][n][0] - SIG * LX / 210000.0) <= 1e-6 * SIG * LX / 210000.0, blocks["DISP"][n]
