"""*FREQUENCY (issue 31, item 1): natural frequencies K x = omega^2 M x
with the consistent mass, point masses, after a preloading step (stress
stiffening under NLGEOM, closed contact as it stands, open contact free).

1. A fixed-free chain of n point masses m on n springs k (T2D2 trusses
   without density): lambda_j = 4 k / m sin^2((2j - 1) pi / (2 (2n + 1))),
   exact: 1e-8 (the listing's 9 digits).
2. A CPS8 cantilever, L / H = 100, against Euler-Bernoulli, lambda =
   (beta L)^4 E I / (rho A L^4), beta L = 1.8751041, 4.6940911: three
   meshes (25x1, 50x2, 100x4 elements); the difference between
   successive meshes shrinks at least 4 times per halving and the finest
   is within 0.2 % of Euler-Bernoulli (Timoshenko's shear and rotary
   inertia lower lambda by about (beta r)^2 (1 + E / (kappa G)): 0.01 %
   and 0.08 % here). The finest mesh (2 800 equations) takes ARPACK, the
   others LAPACK. Measured: +0.039 %, -0.053 %.
3. The same beam free-free (50x2): three rigid modes (|lambda| below
   1e-8 of the first flexural one), then beta L = 4.7300408, 7.8532046
   within 0.3 % (Timoshenko: -0.09 %, -0.21 %; measured -0.06 %, -0.17 %).
4. A pre-tensioned CPS8 strip (L / H = 100, pinned at the mid-height
   nodes of its ends) stretched under NLGEOM, then *FREQUENCY: the first
   two modes against the pinned beam under tension,
   lambda_n = (n pi)^2 N / (rho A0 L0 L) + (n pi / L0)^4 E I / (rho A0) / s,
   L = L0 + delta the stretched length, N the measured end reaction and
   s = 1 + (n pi r / L0)^2 (1 + E / (kappa G)) Timoshenko's first-order
   correction of the bending part: within 5e-4 at three tensions
   (measured 2e-5 .. 2.4e-4, growing with the stretch: the closed form
   leaves out the Poisson contraction of the section, nu eps = 1e-3), the
   frequency rising with the tension (N = 0 leaves the beam alone).
5. Two blocks pressed together (a linear penalty K per area) against the
   same model tied (*TIE): the lowest three frequencies agree to 2e-4 at
   K = 1e7 and the difference falls with K (the interface's compliance
   1/K); the blocks apart (an open contact, no preload) leave the upper
   block free: its lowest eigenvalue is below 1e-8 of the tied model's.
6. CalculiX 2.20 on a 10 x 1 cantilever (20x2 CPS8, four modes),
   tests/calculix/frequency_cantilever.dat: the total effective masses
   (the mass matrix and the participation factors' rigid motions) agree
   to its 7 printed digits; the eigenvalues to 1 % (CalculiX expands
   CPS8 to 3D C3D20R bricks, another element: measured 0.78 %, 0.76 %,
   0.001 %, 0.74 %); cfe2d's .dat has CalculiX's layout line for line.
7. An axisymmetric CAX8 ring (radius R = 100, 1 x 1 section, nu = 0):
   the breathing mode lambda = E / (rho R^2) of a thin ring (the mass
   2 pi r dA: 1e-4, the section's size (w / R)^2), and with point masses
   m at the five mid-height nodes (each the whole ring's mass there, as
   CalculiX counts axisymmetric masses): lambda = (2 pi E A / R) /
   (2 pi R rho A + 5 m), the same bound.
8. The card: its errors name their line. The frequency range: the nev
   lowest modes at or above the lower frequency (the shift (2 pi
   lower)^2 inside the spectrum: LAPACK and ARPACK) and up to the upper
   one; the chain's exact values and the L / H = 100 cantilever's modes 2
   to 4 of a run without bounds (1e-6: the model's conditioning).
9. The debug build (make debug) on the chain and CalculiX's cantilever:
   the same .dat byte for byte (round-off below 1e-12 of a mode's largest
   component and participation below 1e-10 of its total are printed as
   0). Ill-conditioned models differ in the last digits: the L / H = 100
   cantilever's lambda_1 by 1e-7 (dense) to 5e-7 (ARPACK) between the
   builds, its condition number being about 1e9.
"""
import math
import os
import re
import subprocess

from helpers import HERE, ROOT, WORK, Skip, run_deck
from quadmesh import Mesh

E, NU, RHO, T = 210000.0, 0.3, 7.85e-9, 0.5
KAPPA = 5.0 / 6.0     # shear coefficient of a rectangle


def eigen_rows(run, step=None):
    """The listing's EIGENVALUES block (of the given step: the last one)
    as dicts, and its EIGENSOLVER method."""
    blocks = [b for b in run.listing.header if b.name == "EIGENVALUES"]
    solvers = [b for b in run.listing.header if b.name == "EIGENSOLVER"]
    assert blocks, "no EIGENVALUES block in the listing"
    b = blocks[-1] if step is None else [x for x in blocks if x.attrs.get("step") == str(step)][0]
    s = solvers[-1] if step is None else [x for x in solvers if x.attrs.get("step") == str(step)][0]
    rows = [dict(zip(b.columns, r)) for r in b.rows]
    method = dict((r[0], r[1]) for r in s.rows)["method"]
    return rows, method


def total_mass(run):
    b = [b for b in run.listing.header if b.name == "TOTAL EFFECTIVE MASS"][-1]
    return dict(zip(b.columns, b.rows[0]))


def beam(nx, ny, L=40.0, H=1.0, bc="LEFT, 1, 2", nev=4):
    """A plane-stress CPS8 beam [0, L] x [0, H], thickness T."""
    m = Mesh("Q8", nx, ny, lambda s, t: (s * L / nx, t * H / ny))
    out = ["*NODE, NSET=ALLN"] + [f"{k}, {x!r}, {y!r}" for k, (x, y) in m.nodes.items()]
    out.append("*ELEMENT, TYPE=CPS8, ELSET=BEAM")
    out += [f"{i + 1}, " + ", ".join(map(str, e)) for i, e in enumerate(m.elements)]
    out += ["*NSET, NSET=LEFT"] + [str(n) for n in m.side("left")]
    out += ["*MATERIAL, NAME=STEEL", "*ELASTIC", f"{E}, {NU}", "*DENSITY", f"{RHO}",
            "*SOLID SECTION, ELSET=BEAM, MATERIAL=STEEL", f"{T}"]
    if bc:
        out += ["*BOUNDARY", bc]
    out += ["*STEP", "*FREQUENCY", f"{nev}", "*END STEP"]
    return "\n".join(out) + "\n"


def euler_bernoulli(beta_l, L=40.0, H=1.0):
    return beta_l ** 4 * E * T * H ** 3 / 12 / (RHO * T * H * L ** 4)


def chain(n, k, mass):
    nodes = "\n".join(f"{i + 1}, {float(i)}, 0." for i in range(n + 1))
    trusses = "\n".join(f"{i + 1}, {i + 1}, {i + 2}" for i in range(n))
    masses = "\n".join(f"{100 + i}, {i + 2}" for i in range(n))
    return f"""*NODE, NSET=ALLN
{nodes}
*ELEMENT, TYPE=T2D2, ELSET=BARS
{trusses}
*ELEMENT, TYPE=MASS, ELSET=MASSES
{masses}
*MATERIAL, NAME=SPRINGY
*ELASTIC
{k}, 0.
*SOLID SECTION, ELSET=BARS, MATERIAL=SPRINGY
1.
*MASS, ELSET=MASSES
{mass}
*BOUNDARY
1, 1, 2
ALLN, 2
*STEP
*FREQUENCY
{n}
*NODE FILE
U
*END STEP
"""


def test_spring_mass_chain_exact():
    """Fixed-free chain, n = 5, k = 1000 (EA / h with h = A = 1), m = 2:
    every eigenvalue exact, participation x sums to the total mass, and
    one .frd result block per mode."""
    n, k, mass = 5, 1000.0, 2.0
    run = run_deck("freq_chain", chain(n, k, mass), args=("--vtu",)).ok()
    rows, method = eigen_rows(run)
    assert "LAPACK" in method, method
    assert len(rows) == n
    for j, r in enumerate(rows, 1):
        exact = 4 * k / mass * math.sin((2 * j - 1) * math.pi / (2 * (2 * n + 1))) ** 2
        assert abs(r["eigenvalue"] - exact) < 1e-8 * exact, (j, r["eigenvalue"], exact)
        assert abs(r["omega"] - math.sqrt(exact)) < 1e-8 * math.sqrt(exact)
        assert abs(r["frequency"] - math.sqrt(exact) / (2 * math.pi)) < 1e-8 * math.sqrt(exact)
    assert abs(sum(r["mass_x"] for r in rows) - n * mass) < 1e-7 * n * mass
    assert abs(total_mass(run)["mass_x"] - n * mass) < 1e-8 * n * mass
    frd = open(os.path.join(os.path.dirname(run.listing_path), "freq_chain.frd")).read()
    assert len(re.findall(r"^ -4  DISP", frd, re.M)) == n
    # each mode's value in the .frd and its time in the .pvd: its frequency
    values = [float(v) for v in re.findall(r"^  100CL\s+\d+\s+(\S+)", frd, re.M)]
    pvd = open(os.path.join(os.path.dirname(run.listing_path), "freq_chain.pvd")).read()
    times = [float(v) for v in re.findall(r'timestep="([^"]+)"', pvd)]
    for j, r in enumerate(rows):
        assert abs(values[j] / r["frequency"] - 1) < 1e-5 and abs(times[j] / r["frequency"] - 1) < 1e-8


def test_cantilever_converges_to_euler_bernoulli():
    """L / H = 100: the successive meshes' eigenvalues differ less and less
    (the differences shrink at least 4 times per halving), the finest is
    within 0.2 % of Euler-Bernoulli."""
    lams = []
    for nx, ny in ((25, 1), (50, 2), (100, 4)):
        rows, method = eigen_rows(run_deck(f"freq_cantilever_{nx}", beam(nx, ny, L=100.0, nev=2)).ok())
        assert ("ARPACK" in method) == (nx == 100), method
        lams.append([rows[i]["eigenvalue"] for i in range(2)])
        errs = [lams[-1][i] / euler_bernoulli(bl, L=100.0) - 1 for i, bl in enumerate((1.8751041, 4.6940911))]
        print(f"cantilever {nx}x{ny}: {method}; lambda / Euler-Bernoulli - 1 = {errs[0]:+.5f}, {errs[1]:+.5f}")
    for i, bl in enumerate((1.8751041, 4.6940911)):
        d1, d2 = abs(lams[1][i] - lams[0][i]), abs(lams[2][i] - lams[1][i])
        assert d2 < d1 / 4, (i, d1, d2)
        assert abs(lams[2][i] / euler_bernoulli(bl, L=100.0) - 1) < 2e-3, lams


def test_free_free_beam():
    rows, method = eigen_rows(run_deck("freq_free", beam(50, 2, L=100.0, bc="", nev=5)).ok())
    lam = [r["eigenvalue"] for r in rows]
    assert max(abs(x) for x in lam[:3]) < 1e-8 * lam[3], lam
    for x, bl in zip(lam[3:], (4.7300408, 7.8532046)):
        err = x / euler_bernoulli(bl, L=100.0) - 1
        print(f"free-free: lambda / Euler-Bernoulli - 1 = {err:+.5f}")
        assert abs(err) < 3e-3, (x, euler_bernoulli(bl, L=100.0))


def strip(stretch, nx=100, ny=2, L=1000.0, H=10.0):
    m = Mesh("Q8", nx, ny, lambda s, t: (s * L / nx, t * H / ny - H / 2))
    out = ["*NODE, NSET=ALLN"] + [f"{k}, {x!r}, {y!r}" for k, (x, y) in m.nodes.items()]
    out.append("*ELEMENT, TYPE=CPS8, ELSET=STRIP")
    out += [f"{i + 1}, " + ", ".join(map(str, e)) for i, e in enumerate(m.elements)]
    mid = {s: [n for n in m.side(s) if abs(m.nodes[n][1]) < 1e-9][0] for s in ("left", "right")}
    out += [f"*NSET, NSET=PINL\n{mid['left']}", f"*NSET, NSET=PINR\n{mid['right']}"]
    out += ["*MATERIAL, NAME=STEEL", "*ELASTIC", f"{E}, {NU}", "*DENSITY", f"{RHO}",
            "*SOLID SECTION, ELSET=STRIP, MATERIAL=STEEL", "1.", "*BOUNDARY", "PINL, 1, 2", "PINR, 2",
            "*STEP, NLGEOM", "*STATIC", "1., 1.", "*BOUNDARY", f"PINR, 1, 1, {stretch}",
            "*NODE PRINT, NSET=PINL", "RF", "*END STEP", "*STEP", "*FREQUENCY", "2", "*END STEP"]
    return "\n".join(out) + "\n"


def test_pretensioned_strip_follows_the_tension():
    L0, H = 1000.0, 10.0
    a0, inertia = H * 1.0, H ** 3 / 12
    first = []
    for stretch in (0.0, 1.0, 3.0):
        run = run_deck(f"freq_strip_{int(stretch)}", strip(stretch)).ok()
        static = [i for i in run.listing.increments if i.step == 1][-1]
        n_force = -sum(static.block("NODE RF", set="PINL")["RF1"])
        rows, _ = eigen_rows(run)
        for n, r in enumerate(rows, 1):
            # Timoshenko's first-order shear and rotary inertia on the bending part
            shear = 1 + (n * math.pi / L0) ** 2 * inertia / a0 * (1 + E / (KAPPA * E / (2 * (1 + NU))))
            exact = (n * math.pi) ** 2 * n_force / (RHO * a0 * L0 * (L0 + stretch)) + \
                (n * math.pi / L0) ** 4 * E * inertia / (RHO * a0) / shear
            err = r["eigenvalue"] / exact - 1
            print(f"strip stretched {stretch}: N = {n_force:.2f}, mode {n}: lambda / closed form - 1 = {err:+.6f}")
            assert abs(err) < 5e-4, (stretch, n, r["eigenvalue"], exact)
        first.append(rows[0]["eigenvalue"])
    assert first[0] < first[1] < first[2], first
    # CalculiX's idiom for prestressed modes, *STEP, PERTURBATION: the same
    deck = strip(3.0).replace("*STEP\n*FREQUENCY", "*STEP, PERTURBATION\n*FREQUENCY")
    assert "PERTURBATION" in deck
    same, _ = eigen_rows(run_deck("freq_strip_perturbation", deck).ok())
    assert [r["eigenvalue"] for r in same] == [r["eigenvalue"] for r in rows]


def blocks(joint, gap=0.0, pressure=10.0, penalty=None, preload=True):
    """A CPS4 block 4x4 on [0,1]^2 and another 6x4 on [0,1] x [1+gap, 2+gap]
    (meshes that do not match), every x held (the motion is along y),
    the lower one on the ground; the upper one pressed by `pressure` on
    its top in a static step, then *FREQUENCY (3 modes)."""
    lo = Mesh("Q4", 4, 4, lambda s, t: (s / 4, t / 4))
    up = Mesh("Q4", 6, 4, lambda s, t: (s / 6, 1 + gap + t / 4), first_node=1001)
    nodes = "\n".join(f"{k}, {x!r}, {y!r}" for msh in (lo, up) for k, (x, y) in msh.nodes.items())
    le = "\n".join(f"{i + 1}, " + ", ".join(map(str, e)) for i, e in enumerate(lo.elements))
    ue = "\n".join(f"{i + 101}, " + ", ".join(map(str, e)) for i, e in enumerate(up.elements))
    if joint == "tie":
        j = "*TIE, NAME=GLUE\nUPPER_BOTTOM, LOWER_TOP\n"
    elif penalty is None:
        j = "*CONTACT PAIR\nUPPER_BOTTOM, LOWER_TOP\n"
    else:
        j = ("*SURFACE INTERACTION, NAME=SI\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n"
             f"{penalty}\n*CONTACT PAIR, INTERACTION=SI\nUPPER_BOTTOM, LOWER_TOP\n")
    static = "*STEP\n*STATIC\n*DLOAD\n" + "".join(f"{119 + i}, P3, {pressure}\n" for i in range(6)) + "*END STEP\n"
    return f"""*NODE, NSET=ALLN
{nodes}
*ELEMENT, TYPE=CPS4, ELSET=LOWER
{le}
*ELEMENT, TYPE=CPS4, ELSET=UPPER
{ue}
*ELSET, ELSET=ALL
LOWER, UPPER
*NSET, NSET=GROUND
{", ".join(map(str, lo.side("bottom")))}
*SURFACE, NAME=LOWER_TOP
""" + "".join(f"{13 + i}, S3\n" for i in range(4)) + "*SURFACE, NAME=UPPER_BOTTOM\n" + \
        "".join(f"{101 + i}, S1\n" for i in range(6)) + f"""*MATERIAL, NAME=M
*ELASTIC
1000., 0.3
*DENSITY
1.e-3
*SOLID SECTION, ELSET=ALL, MATERIAL=M
1.
{j}*BOUNDARY
GROUND, 2, 2
ALLN, 1, 1
{static if preload else ""}*STEP
*FREQUENCY
3
*END STEP
"""


def test_pressed_blocks_against_tied():
    tied = [r["eigenvalue"] for r in eigen_rows(run_deck("freq_blocks_tied", blocks("tie")).ok())[0]]
    diffs = []
    for k in (1e5, 1e6, 1e7):
        lam = [r["eigenvalue"] for r in eigen_rows(run_deck(f"freq_blocks_{k:.0e}", blocks("contact", penalty=k))
                                                   .ok())[0]]
        diffs.append(max(abs(a / b - 1) for a, b in zip(lam, tied)))
        print(f"pressed, K = {k:.0e}: largest |lambda / tied - 1| = {diffs[-1]:.2e}")
    assert diffs[-1] < 2e-4, diffs
    assert diffs[0] > 5 * diffs[1] > 25 * diffs[2], diffs
    apart = eigen_rows(run_deck("freq_blocks_apart", blocks("contact", gap=0.01, preload=False)).ok())[0]
    assert 0 <= apart[0]["eigenvalue"] < 1e-8 * tied[0], (apart[0], tied[0])


def test_cantilever_against_calculix():
    """tests/calculix/frequency_cantilever.inp (beam(20, 2, L=10)) and
    CalculiX 2.20's .dat of it."""
    path = os.path.join(HERE, "calculix", "frequency_cantilever.inp")
    run = run_deck("frequency_cantilever", path=path).ok()
    rows, _ = eigen_rows(run)
    ref = open(os.path.join(HERE, "calculix", "frequency_cantilever.dat")).read()
    lam_ref = [float(x) for x in re.findall(r"^\s+\d+\s+(\S+)\s+\S+\s+\S+\s+0\.0000000E\+00$", ref, re.M)]
    assert len(lam_ref) == 4 == len(rows)
    for r, x in zip(rows, lam_ref):
        assert abs(r["eigenvalue"] / x - 1) < 1e-2, (r["eigenvalue"], x)
    tot = ref.split("T O T A L   E F F E C T I V E   M A S S")[1].split()
    tx, ty, trz = float(tot[-6]), float(tot[-5]), float(tot[-1])
    got = total_mass(run)
    for a, b in ((got["mass_x"], tx), (got["mass_y"], ty), (got["mass_rz"], trz)):
        assert abs(a / b - 1) < 1e-6, (a, b)
    # cfe2d's .dat: CalculiX's layout line for line (captions, headers, blank
    # lines, column widths), the total effective masses in and out of the
    # plane as CalculiX prints them for x, y and about z
    dat = open(os.path.join(os.path.dirname(run.listing_path), "frequency_cantilever.dat")).read().splitlines()
    lines = ref.splitlines()
    assert len(dat) == len(lines), (len(dat), len(lines))
    number = re.compile(r"^(\s*\d+|TOTAL|)(\s+-?\d\.\d{7}E[+-]\d\d)+$")
    for a, b in zip(dat, lines):
        if number.match(b):
            assert number.match(a) and len(a) == len(b), (a, b)
        else:
            assert a == b, (a, b)
    assert dat[-2].split()[0:2] == lines[-2].split()[0:2] and dat[-2].split()[5] == lines[-2].split()[5], dat[-2]


def ring(masses=None, R=100.0):
    """A CAX8 ring section [R - 1/2, R + 1/2] x [0, 1] (2 x 2), held
    axially at one corner; masses: point masses at the mid-height nodes."""
    m = Mesh("Q8", 2, 2, lambda s, t: (R - 0.5 + s / 2, t / 2))
    out = ["*NODE, NSET=ALLN"] + [f"{k}, {x!r}, {y!r}" for k, (x, y) in m.nodes.items()]
    out.append("*ELEMENT, TYPE=CAX8, ELSET=RING")
    out += [f"{i + 1}, " + ", ".join(map(str, e)) for i, e in enumerate(m.elements)]
    mid = [n for n, (x, y) in m.nodes.items() if abs(y - 0.5) < 1e-12]
    cards = []
    if masses:
        out += ["*ELEMENT, TYPE=MASS, ELSET=PM"] + [f"{1000 + i}, {n}" for i, n in enumerate(mid)]
        cards = ["*MASS, ELSET=PM", f"{masses}"]
    out += ["*MATERIAL, NAME=STEEL", "*ELASTIC", f"{E}, 0.", "*DENSITY", f"{RHO}",
            "*SOLID SECTION, ELSET=RING, MATERIAL=STEEL"] + cards
    out += ["*BOUNDARY", f"{m.side('bottom')[0]}, 2", "*STEP", "*FREQUENCY", "2", "*END STEP"]
    return "\n".join(out) + "\n", len(mid)


def test_axisymmetric_ring_breathing():
    R, A = 100.0, 1.0
    deck, _ = ring()
    lam = eigen_rows(run_deck("freq_ring", deck).ok())[0][1]["eigenvalue"]
    print(f"ring: breathing lambda / (E / rho R^2) - 1 = {lam / (E / (RHO * R * R)) - 1:+.2e}")
    assert abs(lam / (E / (RHO * R * R)) - 1) < 1e-4, lam
    deck, n = ring(masses=1e-6)
    assert n == 5
    lam = eigen_rows(run_deck("freq_ring_masses", deck).ok())[0][1]["eigenvalue"]
    exact = (2 * math.pi * E * A / R) / (2 * math.pi * R * RHO * A + n * 1e-6)
    print(f"ring with masses: breathing lambda / closed form - 1 = {lam / exact - 1:+.2e}")
    assert abs(lam / exact - 1) < 1e-4, (lam, exact)


def test_frequency_card_errors():
    good = beam(2, 1, nev=2)
    for bad, words in ((good.replace("*FREQUENCY\n2", "*FREQUENCY\n0"), "at least 1"),
                       (good.replace("*FREQUENCY\n2", "*FREQUENCY\n2, 10., 5."), "above the lower"),
                       (good.replace("*FREQUENCY\n2", "*FREQUENCY, STORAGE=MAYBE\n2"), "STORAGE"),
                       (good.replace("*FREQUENCY\n2", "*FREQUENCY\n2\n*STATIC"), "second procedure"),
                       (good.replace("*DENSITY\n7.85e-09\n", ""), "no mass")):
        run = run_deck("freq_bad", bad)
        assert run.rc == 1 and words in run.stderr, (words, run.stderr)
        assert "error" in run.stderr and "Traceback" not in run.stderr
    line = [i for i, t in enumerate(good.replace("*FREQUENCY\n2", "*FREQUENCY\n0").splitlines(), 1) if t == "0"][0]
    run = run_deck("freq_bad", good.replace("*FREQUENCY\n2", "*FREQUENCY\n0"))
    assert f":{line}: error" in run.stderr, run.stderr
    # no mass: named at the *FREQUENCY line
    bad = good.replace("*DENSITY\n7.85e-09\n", "")
    line = bad.splitlines().index("*FREQUENCY") + 1
    run = run_deck("freq_bad", bad)
    assert f"freq_bad.inp:{line}: error: *FREQUENCY: the model has no mass" in run.stderr, run.stderr


def test_debug_build_prints_the_same_dat():
    debug = os.path.join(ROOT, "build-debug", "cfe2d")
    if not os.path.exists(debug):
        raise Skip("build-debug/cfe2d not built (make debug)")
    for name, path in (("freq_chain", None), ("frequency_cantilever",
                                              os.path.join(HERE, "calculix", "frequency_cantilever.inp"))):
        run = run_deck(name, chain(5, 1000.0, 2.0) if path is None else None, path=path).ok()
        out = os.path.join(WORK, name + "_debug")
        os.makedirs(out, exist_ok=True)
        p = subprocess.run([debug, "-q", "-o", out, run.deck], capture_output=True, text=True, timeout=600)
        assert p.returncode == 0 and "Fortran runtime" not in p.stderr, p.stderr
        base = os.path.splitext(os.path.basename(run.deck))[0] + ".dat"
        a = open(os.path.join(os.path.dirname(run.listing_path), base)).read()
        b = open(os.path.join(out, base)).read()
        assert a == b and "E I G E N V A L U E" in a, name


def test_print_card_without_quantities_prints_nothing():
    """CalculiX's spring4 ends its *FREQUENCY step with a *NODE PRINT
    without a data line, which CalculiX reads as nothing to print: a
    warning at the card, the run goes on, no NODE U block."""
    deck = chain(3, 1000.0, 2.0).replace("*NODE FILE\nU\n", "*NODE PRINT, NSET=ALLN\n")
    run = run_deck("freq_empty_print", deck).ok()
    line = deck.splitlines().index("*NODE PRINT, NSET=ALLN") + 1
    assert f"freq_empty_print.inp:{line}: warning: *NODE PRINT has no output quantities" in run.stderr, run.stderr
    assert not any(inc.has("NODE U", set="ALLN") for inc in run.listing.increments)
    assert len(eigen_rows(run)[0]) == 3


def test_frequency_range():
    n, k, mass = 5, 1000.0, 2.0
    exact = [4 * k / mass * math.sin((2 * j - 1) * math.pi / (2 * (2 * n + 1))) ** 2 for j in range(1, n + 1)]
    f = [math.sqrt(x) / (2 * math.pi) for x in exact]
    base = chain(n, k, mass)
    for line, want in ((f"2, {0.5 * (f[1] + f[2])}", exact[2:4]), (f"5, , {0.5 * (f[1] + f[2])}", exact[:2]),
                       (f"2, {0.5 * (f[0] + f[1])}, {0.5 * (f[1] + f[2])}", exact[1:2]),
                       (f"3, {f[4] * 1.1}", [])):
        rows, _ = eigen_rows(run_deck("freq_range", base.replace("*FREQUENCY\n5", "*FREQUENCY\n" + line)).ok())
        got = [r["eigenvalue"] for r in rows]
        assert len(got) == len(want) and all(abs(a / b - 1) < 1e-8 for a, b in zip(got, want)), (line, got, want)
    # the sparse path with the shift inside the spectrum (CHOLMOD's factor of
    # an indefinite K - sigma M falls back to UMFPACK)
    free = [r["eigenvalue"] for r in eigen_rows(run_deck("freq_range_all", beam(100, 4, L=100.0, nev=4)).ok())[0]]
    f1 = math.sqrt(free[0]) / (2 * math.pi)
    rows, method = eigen_rows(run_deck("freq_range_arpack", beam(100, 4, L=100.0, nev=3).replace(
        "*FREQUENCY\n3", f"*FREQUENCY\n3, {2 * f1}")).ok())
    assert "ARPACK" in method, method
    got = [r["eigenvalue"] for r in rows]
    assert len(got) == 3 and all(abs(a / b - 1) < 1e-6 for a, b in zip(got, free[1:])), (got, free)
