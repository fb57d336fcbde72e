#!/usr/bin/env python3
"""Contact decks with many contact points (issue 22): two long strips
pressed together, or a rough elastic body (a self-affine profile) pressed on
a flat one. Both are plane strain CPE4, steel, node-to-surface contact with
the upper body's bottom nodes as slaves; `--points` sets the number of slave
nodes (1 000 to 50 000 and more), `--ny` the element layers of each body.

  python3 scripts/contact_decks.py strips --points 4000 -o strips4000.inp
  python3 scripts/contact_decks.py rough --points 20000 --hurst 0.8 -o rough.inp
  mpirun -np 2 bin/cfe2d --solver MUMPS rough.inp

The rough profile: z(x) = sum_k a_k cos(2 pi k x / L + phi_k), k = 1..K,
with a_k proportional to k^-(H + 1/2) (the power spectrum of a self-affine
profile of Hurst exponent H falls as q^-(1 + 2H)), random phases from
--seed, scaled to the rms roughness --rms and shifted so that its lowest
point touches the flat (gap 0). K = points / 4 (four nodes per shortest
wavelength). The upper body's nodes blend from the profile at its bottom
to a straight top edge. The top edge is pushed down by --press (in rms
units) in --incs increments of one step (a contact history), then lifted
back by half in a second step.
"""
import argparse
import math
import random


def grid_nodes(nx, ny, x0, x1, ybot, ytop, first):
    """Node ids and lines of a structured nx x ny grid; ybot(x) and ytop are
    the bottom curve and the (flat) top."""
    ids, lines = {}, []
    nid = first
    for j in range(ny + 1):
        for i in range(nx + 1):
            x = x0 + (x1 - x0) * i / nx
            yb = ybot(x)
            y = yb + (ytop - yb) * j / ny
            ids[i, j] = nid
            lines.append(f"{nid}, {x:.15g}, {y:.15g}\n")
            nid += 1
    return ids, lines


def quads(ids, nx, ny, first):
    out = []
    e = first
    for j in range(ny):
        for i in range(nx):
            out.append(f"{e}, {ids[i, j]}, {ids[i + 1, j]}, {ids[i + 1, j + 1]}, {ids[i, j + 1]}\n")
            e += 1
    return out


def id_lines(ns):
    return "".join(", ".join(map(str, ns[i:i + 16])) + "\n" for i in range(0, len(ns), 16))


def profile(points, hurst, rms, seed, length):
    """The self-affine profile as a function of x (lowest point at 0)."""
    rng = random.Random(seed)
    kmax = max(1, points // 4)
    amp = [k ** -(hurst + 0.5) for k in range(1, kmax + 1)]
    phase = [rng.uniform(0.0, 2.0 * math.pi) for _ in amp]
    scale = rms / math.sqrt(0.5 * sum(a * a for a in amp))
    xs = [length * i / (points - 1) for i in range(points)]

    def raw(x):
        return scale * sum(a * math.cos(2.0 * math.pi * (k + 1) * x / length + p)
                           for k, (a, p) in enumerate(zip(amp, phase)))
    # the profile at the slave nodes, interpolated between them elsewhere
    zs = [raw(x) for x in xs] if points <= 4000 else fast_profile(amp, phase, scale, points)
    lo = min(zs)
    zs = [z - lo for z in zs]

    def z(x):
        t = x / length * (points - 1)
        i = min(int(t), points - 2)
        return zs[i] + (zs[i + 1] - zs[i]) * (t - i)
    return z


def fast_profile(amp, phase, scale, points):
    """The same sum at the equally spaced slave nodes, by numpy's FFT."""
    import numpy as np
    n = points - 1                        # one period over the slave nodes
    spec = np.zeros(n // 2 + 1, dtype=complex)
    for k, (a, p) in enumerate(zip(amp, phase), start=1):
        if k < spec.size:
            spec[k] = 0.5 * n * scale * a * np.exp(1j * p)
    full = np.fft.irfft(spec, n)
    return list(full) + [full[0]]


def deck(kind, points, ny, hurst, rms, seed, press, incs, solver, contact_solve):
    h = 1.0                               # slave element length
    length = h * (points - 1)
    nx2 = points - 1                      # upper body: points slave nodes
    nx1 = max(1, round(0.9 * nx2))        # lower body: a master a little coarser
    thick = ny * h
    if kind == "rough":
        z = profile(points, hurst, rms, seed, length)
        title = f"rough surface (self-affine, H = {hurst}, rms {rms}) on a flat, {points} contact points"
    else:
        def z(x):
            return 0.0
        rms = 0.01 * h
        title = f"two long strips pressed together, {points} contact points"
    ids1, n1 = grid_nodes(nx1, ny, 0.0, length, lambda x: -thick, 0.0, 1)
    first2 = len(n1) + 1
    ids2, n2 = grid_nodes(nx2, ny, 0.0, length, z, thick, first2)
    q1 = quads(ids1, nx1, ny, 1)
    q2 = quads(ids2, nx2, ny, nx1 * ny + 1)
    top_elems = [nx1 * (ny - 1) + i + 1 for i in range(nx1)]
    d = press * rms
    solver_card = "*SOLVER"
    if solver:
        solver_card += f", TYPE={solver}"
    if contact_solve:
        solver_card += f", CONTACT SOLVE={contact_solve}"
    solver_card = solver_card + "\n" if solver_card != "*SOLVER" else ""
    return "".join([
        f"*HEADING\n{title}\n*NODE\n", *n1, *n2,
        "*ELEMENT, TYPE=CPE4, ELSET=LOWER\n", *q1,
        "*ELEMENT, TYPE=CPE4, ELSET=UPPER\n", *q2,
        "*NSET, NSET=GROUND\n", id_lines([ids1[i, 0] for i in range(nx1 + 1)]),
        f"*NSET, NSET=ANCHOR\n{ids1[0, 0]}\n",
        "*NSET, NSET=SLAVE\n", id_lines([ids2[i, 0] for i in range(nx2 + 1)]),
        "*NSET, NSET=TOP\n", id_lines([ids2[i, ny] for i in range(nx2 + 1)]),
        "*ELSET, ELSET=LOWERTOP\n", id_lines(top_elems),
        "*SURFACE, NAME=MASTER\nLOWERTOP, S3\n",
        "*MATERIAL, NAME=STEEL\n*ELASTIC\n210000., 0.3\n",
        "*SOLID SECTION, ELSET=LOWER, MATERIAL=STEEL\n*SOLID SECTION, ELSET=UPPER, MATERIAL=STEEL\n",
        solver_card,
        "*CONTACT PAIR\nSLAVE, MASTER\n",
        "*BOUNDARY\nGROUND, 2, 2\nANCHOR, 1, 1\nTOP, 1, 1\n",
        f"*STEP\n*STATIC\n{1.0 / incs}, 1.0\n*BOUNDARY\nTOP, 2, 2, {-d:.15g}\n"
        "*NODE PRINT, NSET=TOP, TOTALS=ONLY\nRF\n*END STEP\n",
        f"*STEP\n*STATIC\n{1.0 / incs}, 1.0\n*BOUNDARY\nTOP, 2, 2, {-0.5 * d:.15g}\n"
        "*NODE PRINT, NSET=TOP, TOTALS=ONLY\nRF\n*END STEP\n",
    ])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("kind", choices=["strips", "rough"])
    ap.add_argument("--points", type=int, default=1000, help="contact (slave) nodes")
    ap.add_argument("--ny", type=int, default=4, help="element layers of each body")
    ap.add_argument("--hurst", type=float, default=0.8, help="Hurst exponent of the rough profile")
    ap.add_argument("--rms", type=float, default=0.02, help="rms roughness (element lengths)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--press", type=float, default=3.0, help="push of the top edge, in rms (strips: 0.01 h)")
    ap.add_argument("--incs", type=int, default=4, help="increments of each step")
    ap.add_argument("--solver", default="", help="TYPE= of *SOLVER (default: none, CHOLMOD)")
    ap.add_argument("--contact-solve", default="", help="CONTACT SOLVE= of *SOLVER (AUTO, CONDENSED, FULL)")
    ap.add_argument("-o", "--output", required=True)
    a = ap.parse_args()
    if a.points < 2:
        ap.error("--points must be at least 2")
    with open(a.output, "w") as f:
        f.write(deck(a.kind, a.points, a.ny, a.hurst, a.rms, a.seed, a.press, a.incs, a.solver.upper(),
                     a.contact_solve.upper()))


if __name__ == "__main__":
    main()
