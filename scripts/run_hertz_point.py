#!/usr/bin/env python3
"""3D Hertz through axisymmetry: mesh the sphere-on-flat case with gmsh
(input/hertz/hertz_point.geo), name its elements axisymmetric (CAX4, or
CAX8 with --order 2), run cfe2d (input/hertz/hertz_point.inp) and compare
with Hertz's point contact at every increment.

  python3 scripts/run_hertz_point.py                   # CAX4 -> results/hertz_point
  python3 scripts/run_hertz_point.py --order 2         # CAX8 (8-node, gmsh -order 2)
  python3 scripts/run_hertz_point.py --h 0.02          # element size at the contact
"""
import argparse
import os
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)

import compare_hertz  # noqa: E402


def write_case(outdir, order=1, h=0.04):
    """Mesh and write the deck in outdir; returns the deck's path
    (outdir/hertz_point.inp)."""
    os.makedirs(outdir, exist_ok=True)
    mesh = os.path.join(outdir, "hertz_point_mesh.inp")
    cmd = ["gmsh", "-2", "-format", "inp", "-setnumber", "Mesh.SaveGroupsOfNodes", "1", "-setnumber", "h", str(h),
           "-o", mesh, os.path.join(ROOT, "input", "hertz", "hertz_point.geo")]
    if order == 2:
        cmd[2:2] = ["-order", "2", "-setnumber", "Mesh.SecondOrderIncomplete", "1"]
    subprocess.run(cmd, check=True, capture_output=True)
    # gmsh names every 2D element plane stress: the model is axisymmetric
    with open(mesh) as f:
        text = f.read()
    text = re.sub(r"type=CPS([348])\b", r"type=CAX\1", text, flags=re.IGNORECASE)
    with open(mesh, "w") as f:
        f.write(text)
    with open(os.path.join(ROOT, "input", "hertz", "hertz_point.inp")) as f:
        deck = f.read()
    path = os.path.join(outdir, "hertz_point.inp")
    with open(path, "w") as f:
        f.write(deck)
    return path


def run_case(outdir, order=1, h=0.04, quiet=True, digits=10):
    """Mesh, write the deck and run cfe2d in outdir; returns the job path
    (outdir/hertz_point) and the wall time of the cfe2d run."""
    path = write_case(outdir, order, h)
    t0 = time.time()
    args = [os.path.join(ROOT, "bin", "cfe2d"), "--digits", str(digits), "-o", outdir]
    if quiet:
        args.append("-q")
    subprocess.run(args + [path], check=True)
    return os.path.join(outdir, "hertz_point"), time.time() - t0


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--order", type=int, choices=[1, 2], default=1, help="1: CAX4, 2: CAX8")
    ap.add_argument("--h", type=float, default=0.04, help="element size of the flat at the contact (mm)")
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "hertz_point"))
    args = ap.parse_args(argv)
    job, tcfe = run_case(args.out, args.order, args.h, quiet=False)
    print(f"\ncfe2d ran in {tcfe:.1f} s; comparison with Hertz point contact (P the ring's contact force):\n")
    compare_hertz.main([args.out, "--point", "--job", "hertz_point"])


if __name__ == "__main__":
    main()
