#!/usr/bin/env python3
"""The flagship run: mesh the cylinder-on-plate case with gmsh, run cfe2d,
compare with Hertz, draw the plots. Everything lands in one folder.

  python3 scripts/run_hertz.py                      # default mesh -> results/hertz
  python3 scripts/run_hertz.py --mesh fine          # coarse | default | fine
  python3 scripts/run_hertz.py --penalty paper      # the paper's c = 1e10 N/mm per node
  python3 scripts/run_hertz.py --plate 4            # plate 4x larger (model-error study)
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)

import compare_hertz  # noqa: E402

MESHES = {"coarse": 0.1, "default": 0.05, "fine": 0.025}
DECKS = {"auto": "hertz.inp", "paper": "hertz_paper_penalty.inp"}


def write_case(outdir, mesh="default", penalty="auto", plate=1.0, approach=None):
    """Mesh and write the deck in outdir; returns the deck's path
    (outdir/hertz.inp)."""
    os.makedirs(outdir, exist_ok=True)
    h = MESHES[mesh] if isinstance(mesh, str) else float(mesh)
    geo = os.path.join(ROOT, "input", "hertz", "hertz.geo")
    cmd = ["gmsh", "-2", "-format", "inp", "-setnumber", "Mesh.SaveGroupsOfNodes", "1",
           "-setnumber", "h", str(h), "-setnumber", "Lp", str(40 * plate), "-setnumber", "Hp", str(40 * plate),
           "-o", os.path.join(outdir, "hertz_mesh.inp"), geo]
    subprocess.run(cmd, check=True, capture_output=True)
    with open(os.path.join(ROOT, "input", "hertz", DECKS[penalty])) as f:
        deck = f.read()
    if approach is not None:
        deck, n = re.subn(r"CYL_TOP, 2, 2, -0\.4", f"CYL_TOP, 2, 2, {-approach}", deck)
        assert n == 1
    path = os.path.join(outdir, "hertz.inp")
    with open(path, "w") as f:
        f.write(deck)
    return path


def run_case(outdir, mesh="default", penalty="auto", plate=1.0, approach=None, quiet=True, digits=10):
    """Mesh, write the deck and run cfe2d in outdir; returns the job path
    (outdir/hertz) and the wall time of the cfe2d run."""
    path = write_case(outdir, mesh, penalty, plate, approach)
    t0 = time.time()
    args = [os.path.join(ROOT, "bin", "cfe2d"), "--digits", str(digits), "-o", outdir]
    if quiet:
        args.append("-q")
    subprocess.run(args + [path], check=True)
    return os.path.join(outdir, "hertz"), time.time() - t0


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--mesh", default="default", help="coarse, default, fine, or a size h in mm")
    ap.add_argument("--penalty", choices=sorted(DECKS), default="auto")
    ap.add_argument("--plate", type=float, default=1.0, help="plate size factor (1: 80 x 40 mm)")
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "hertz"))
    ap.add_argument("--no-plots", action="store_true")
    args = ap.parse_args(argv)
    t0 = time.time()
    job, tcfe = run_case(args.out, args.mesh, args.penalty, args.plate, quiet=False)
    print(f"\ncfe2d ran in {tcfe:.1f} s; comparison with Hertz (P from the FE contact force):\n")
    compare_hertz.main([args.out] + ([] if args.no_plots else ["--plots"]))
    print(f"\nresults in {args.out} (listing hertz.out, table hertz_contact.csv, comparison hertz_hertz.txt,")
    print(f"gmsh result file hertz.msh: open it with `gmsh {os.path.join(args.out, 'hertz.msh')}`); "
          f"total {time.time() - t0:.1f} s")


if __name__ == "__main__":
    main()
