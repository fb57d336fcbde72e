"""The re-search of UPDATE SEARCH (issue 33, fretting; src/contact/edge_tree.f90):
the master edge tree kept from one search to the next and refit to each
new configuration, and each point's last edge tried first (nearest_edge's
hint), against the search over every master edge.

tests/unit/test_fretting_search.f90 moves random master surfaces through
histories (a rough profile of 2-node edges slid back and forth by 2.5
edges as in a fretting cycle, with and without a search distance, and
stretched by half; a circle of 3-node edges slid; a polyline whose edges
are all given twice; a channel of two facing strips closing in, whose
points' last edges on the lower strip stop being the nearest; a flat
surface whose 2000 edges are dealt out to random places) with every node
perturbed, and at each configuration asks
nearest_edge for random points with the kept tree (hints: the point's edge
of the configuration before, a random edge, none, one out of range) and
over every edge: the edge and the position along it must be the same bit
for bit (the first of equally near edges wins in both), and the refit
tree's root box and mean box size those of a tree built on the
configuration. After the shuffle the tree must have been built again: at
most 8 candidate edges within one mean box size of a point.

The program is built here (make build/tests/test_fretting_search, the
Makefile's rule for tests/unit/*.f90) and its PASS/FAIL lines read.
"""
import os
import subprocess

from helpers import ROOT

PROGRAM = os.path.join(ROOT, "build", "tests", "test_fretting_search")


def test_kept_tree_and_hints_answer_as_the_search_over_all_edges():
    built = subprocess.run(["make", "-s", "build/tests/test_fretting_search"], cwd=ROOT, capture_output=True,
                           text=True)
    assert built.returncode == 0, f"make build/tests/test_fretting_search failed:\n{built.stdout}\n{built.stderr}"
    run = subprocess.run([PROGRAM], capture_output=True, text=True, timeout=600)
    lines = [ln for ln in run.stdout.splitlines() if ln.startswith(("PASS ", "FAIL "))]
    failed = [ln for ln in lines if ln.startswith("FAIL ")]
    assert not failed, "\n".join(failed)
    # every case ran (a crash part-way would leave some out)
    assert len(lines) == 7, f"expected 7 results, got {len(lines)}:\n{run.stdout}\n{run.stderr}"
    assert run.returncode == 0, run.stderr
