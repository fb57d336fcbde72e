"""Newton on the condensed contact solve (issue 32; condensed_equilibrium's
newton_condensed_path_t): in a nonlinear step whose tangent is symmetric
(NLGEOM with *ELASTIC) the tangent at each Newton iterate is factored once
and the contact status searched on it by the condensed system; AUTO takes
it where the sparse factorisation is large (>= 1e8 flops, the flagship
mesh), `*SOLVER, CONTACT SOLVE=CONDENSED` forces it on the small decks here.

The model is test_nonlinear_contact_search's: a block slid ten edges along a
polygonal bowl under NLGEOM in one increment and in ten, EXACT frictionless
contact, both couplings, with its closed forms: (a) every bottom node on
the polygon edge K, (b) the reaction at the top normal to edge K, (c) the
end state independent of the increments. On the condensed path:

* the listing says `contact_solve condensed`, and the sparse
  factorisations are the Newton iterations (one tangent per Newton
  iteration; the status pivots between them are dense factorisations of the
  condensed matrix, `condensed_factorisations`, more than the Newton
  iterations in the ten-edge slide);
* (a) to the same tolerance as the full path (the gaps of EXACT contact are
  round-off);
* (b) to 1e-5 rad: the increment stops at CalculiX's convergence test, the
  largest residual force below R_n = 0.005 of the average force and the
  last correction below C_n = 0.02 of the increment's; the full path's
  iterates happen to go on to 1e-9 of the force (1e-7 rad there). Measured
  below (printed);
* the end state of the condensed and the full path within 1e-5 of the
  slide (the same convergence tolerance).
"""
import math

from helpers import run_deck
import test_nonlinear_contact_search as ncs

CONDENSED = "*SOLVER, CONTACT SOLVE=CONDENSED\n"
ANGLE_TOL = 1e-5
STATE_TOL = 1e-5


def condensed_deck(couplings, static):
    text = ncs.deck(couplings, static)
    return text.replace("*STEP, NLGEOM", CONDENSED + "*STEP, NLGEOM", 1)


def summary(run, name):
    with open(run.listing_path) as f:
        text = f.read()
    block = text.split("--- STEP SUMMARY", 1)[1].split("\n\n")[0]
    return int(next(line.split()[1] for line in block.splitlines() if line.startswith(name + " ")))


def angle_and_state(run, b):
    pos, (f1, f2), inc = ncs.end_state(run, b)
    worst = 0.0
    for p in pos.values():
        g, k = ncs.polygon_distance(p)
        assert k == ncs.K
        worst = max(worst, abs(g))
    return math.atan2(f1, -f2), worst, pos


def check_against_full(name, static):
    full = run_deck(name + "_full", ncs.deck(ncs.BOTH, static)).ok()
    cond = run_deck(name, condensed_deck(ncs.BOTH, static)).ok()
    with open(cond.listing_path) as f:
        assert "contact_solve condensed" in f.read()
    newton = summary(cond, "newton_iterations")
    assert summary(cond, "numeric_factorisations") == newton, "one sparse factorisation per Newton iteration"
    assert summary(cond, "condensed_factorisations") >= newton
    print(f"  {name}: Newton iterations {newton} (full path {summary(full, 'newton_iterations')}), "
          f"dense factorisations {summary(cond, 'condensed_factorisations')}")
    slide = ncs.R * math.sin(ncs.THETA)
    for b, coupling in enumerate(ncs.BOTH):
        label = ncs.NAMES[coupling]
        angle, gap, pos = angle_and_state(cond, b)
        _, _, pos_full = angle_and_state(full, b)
        diff = max(math.hypot(pos[n][0] - pos_full[n][0], pos[n][1] - pos_full[n][1]) for n in pos)
        print(f"    {label}: |gap| {gap / ncs.EDGE:.1e} of the edge, angle off by {abs(angle - ncs.THETA):.1e} rad, "
              f"against the full path {diff / slide:.1e} of the slide")
        assert gap < ncs.GAP_TOL[label] * ncs.EDGE, (label, gap)
        assert abs(angle - ncs.THETA) < ANGLE_TOL, (label, angle)
        assert diff < STATE_TOL * slide, (label, diff)


def test_condensed_newton_slide_in_one_increment():
    check_against_full("nl_condensed_1", "*STATIC, DIRECT\n1., 1.\n")


def test_condensed_newton_slide_in_ten_increments():
    check_against_full("nl_condensed_10", "*STATIC, DIRECT\n0.1, 1.\n")


def test_auto_keeps_the_full_path_on_a_small_deck():
    """AUTO (no *SOLVER card): the sparse factorisation of this deck is far
    below 1e8 flops, so Newton keeps the full path (the decks of the other
    nonlinear tests are unchanged)."""
    run = run_deck("nl_condensed_auto", ncs.deck(ncs.BOTH, "*STATIC, DIRECT\n1., 1.\n")).ok()
    with open(run.listing_path) as f:
        assert "contact_solve full" in f.read()
