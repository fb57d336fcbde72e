"""McColl's fretting history split into steps (scripts/fretting.py writes a
long history as several *STEPs: the INC= limit), on the coarse mesh of
tests/test_fretting.py (h = 0.02 mm, 8 increments a cycle), one step a
cycle: every step after the pressing starts at a cycle's start, where the
stroke passes zero in gross slip, so the first status a step factors has
sliding couplings.

* The condensed solve runs through the steps and gives the worn depths of
  CONTACT SOLVE=FULL (every status factored whole) on the same deck to
  1e-10 of the deepest (measured: equal to the bit). Before, the sliding
  status became the low-rank solves' reference, whose inverse is
  unsymmetric while its products read one triangle: the next increment's
  statuses cycled ("contact status did not settle", seen at the 5 000th
  cycle of the 18 000-cycle bench run, whose steps are 2 500 cycles).
* The steps do not change the answer: the worn depths are the one-step
  history's to 1e-10 of the deepest (measured: equal to the bit). A
  step's first increment pairs the contact again on the configuration the
  last step ended in, as every other increment does with UPDATE SEARCH;
  before, it kept the pairing of the last increment's start, and a step a
  cycle wore 4 % (slave) and 5 % (master) more than one step.
"""
import os
import sys

import numpy as np

from helpers import ROOT, run_deck
from cfe2d_listing import read_listing

sys.path.insert(0, os.path.join(ROOT, "scripts"))
import fretting  # noqa: E402
import test_fretting as tf  # noqa: E402

CYCLES = 4


def _deck(steps_of, solve=None):
    """The coarse history, `steps_of` increments a step."""
    keep = fretting.MAX_INC
    fretting.MAX_INC = steps_of
    try:
        text = fretting.deck(tf._mesh(), CYCLES, 1, tf.INC, tf.INC)
    finally:
        fretting.MAX_INC = keep
    if solve:
        at = text.index("*STEP")
        text = text[:at] + f"*SOLVER, CONTACT SOLVE={solve}\n" + text[at:]
    return text


def _worn(run):
    """(slave, master) worn depths of the last increment's listing."""
    inc = read_listing(run.listing_path).increments[-1]
    return (np.asarray(inc.block("CONTACT SLAVE")["wear_slave"], float),
            np.asarray(inc.block("CONTACT MASTER")["wear_master"], float))


def test_fretting_steps_starting_in_gross_slip():
    """A step a cycle: the condensed solve's worn depths are the full
    solve's (1e-10 of the deepest)."""
    deck = _deck(tf.INC)
    assert deck.count("*STEP") == CYCLES + 1
    cond = run_deck("fretting_steps_condensed", deck).ok()
    full = run_deck("fretting_steps_full", _deck(tf.INC, "FULL")).ok()
    for a, b in zip(_worn(cond), _worn(full)):
        assert a.shape == b.shape and np.max(b) > 0
        assert np.max(np.abs(a - b)) <= 1e-10 * np.max(b), np.max(np.abs(a - b)) / np.max(b)


def test_fretting_steps_pair_again_at_each_start():
    """A step a cycle gives the worn depths of one step (1e-10)."""
    assert _deck(100000).count("*STEP") == 2
    split = run_deck("fretting_steps_split", _deck(tf.INC)).ok()
    one = run_deck("fretting_steps_one", _deck(100000)).ok()
    for a, b in zip(_worn(split), _worn(one)):
        assert a.shape == b.shape and np.max(b) > 0
        assert np.max(np.abs(a - b)) <= 1e-10 * np.max(b), np.max(np.abs(a - b)) / np.max(b)
