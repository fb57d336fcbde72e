"""The contact search's tree (src/contact/edge_tree.f90) against the search
over every master edge.

tests/unit/test_search.f90 draws random master surfaces (a rough profile of
2-node edges, a circle of 3-node edges, scattered edges from 0.001 to 30
long, a polyline whose edges are all given twice) and random points (on and
near the edges, on their vertices, far away), and asks nearest_edge for
each point with and without the tree, also with a search distance and with
an element and a node skipped: the edge and the position along it must be
the same bit for bit (the first of equally near edges wins in both).
The segment-to-segment coupling's face_cuts (where the corners of the
master edges project onto a straight slave face) on random faces, with and
without a search distance and with the tree: the same cuts bit for bit. It
also checks that near a flat surface of 20 000 edges the tree offers at
most 8 edges within one edge length of a point.

The program is built here (make build/tests/test_search, the Makefile's
rule for tests/unit/*.f90) and its PASS/FAIL lines read.
"""
import os
import subprocess

from helpers import ROOT

PROGRAM = os.path.join(ROOT, "build", "tests", "test_search")


def unit_results():
    built = subprocess.run(["make", "-s", "build/tests/test_search"], cwd=ROOT, capture_output=True, text=True)
    assert built.returncode == 0, f"make build/tests/test_search failed:\n{built.stdout}\n{built.stderr}"
    run = subprocess.run([PROGRAM], capture_output=True, text=True, timeout=600)
    lines = [ln for ln in run.stdout.splitlines() if ln.startswith(("PASS ", "FAIL "))]
    return run, lines


def test_tree_search_same_edges_as_search_over_all():
    run, lines = unit_results()
    failed = [ln for ln in lines if ln.startswith("FAIL ")]
    assert not failed, "\n".join(failed)
    # every case ran (a crash part-way would leave some out)
    assert len(lines) == 9, f"expected 9 results, got {len(lines)}:\n{run.stdout}\n{run.stderr}"
    assert run.returncode == 0, run.stderr
