"""The Newton framework of nonlinear steps (NLGEOM, hyperelastic and
plastic materials) on what needs no nonlinear element: the cards that
switch it on, CalculiX's automatic increments, DIRECT, NLGEOM carried into
later steps, the PEEQ output and the errors at the line.

The model is a bar of trusses, which stay linear under NLGEOM (the truss
element has no large-deformation form): the Newton iteration must
converge in one iteration per increment (the residual after the first
solve is round-off, below R_l = 1e-8 of the average force) and give the
linear path's answers (to 1e-12 relative); the increments follow
CalculiX's rule: the initial one, 1.5 times larger after two increments
of at most 4 iterations, never beyond the step's end. The cards are
checked on a plane-strain block."""
import re

from helpers import run_deck
from quadmesh import Mesh

E, NU, F = 1000.0, 0.3, 5.0


def bar_deck(step_card="*STEP, NLGEOM", static="*STATIC\n0.25, 1.\n", requests=None, extra_steps=""):
    """Three T2D2 trusses along x (area 2), held at x = 0, pulled by F at x = 3."""
    requests = requests if requests is not None else "*NODE PRINT, NSET=END\nU\n*EL PRINT\nS\n"
    return f"""*NODE, NSET=ALL
1, 0., 0.
2, 1., 0.
3, 2., 0.
4, 3., 0.
*ELEMENT, TYPE=T2D2, ELSET=BAR
1, 1, 2
2, 2, 3
3, 3, 4
*NSET, NSET=END
4
*MATERIAL, NAME=M
*ELASTIC
{E}, {NU}
*SOLID SECTION, ELSET=BAR, MATERIAL=M
2.
{step_card}
{static}*BOUNDARY
ALL, 2, 2
1, 1, 1
*CLOAD
4, 1, {F}
{requests}*END STEP
{extra_steps}"""


def block_deck(step_card="*STEP, NLGEOM", static="*STATIC\n0.25, 1.\n", material=None, requests=None,
               nx=3, ny=2, load=1.0):
    """A plane-strain CPE4 block 3 x 1 pulled at its right side (for the cards)."""
    m = Mesh("Q4", nx, ny, lambda s, t: (s, t / ny))
    material = material or f"*ELASTIC\n{E}, {NU}\n"
    requests = requests if requests is not None else "*NODE PRINT, NSET=RIGHT\nU\n*EL PRINT\nS\n"
    right = m.side("right")
    return f"""*NODE, NSET=ALL
{m.node_lines()}{m.element_card('CPE4', 'B')}*NSET, NSET=LEFT
{", ".join(map(str, m.side('left')))}
*NSET, NSET=RIGHT
{", ".join(map(str, right))}
*MATERIAL, NAME=M
{material}*SOLID SECTION, ELSET=B, MATERIAL=M
1.
{step_card}
{static}*BOUNDARY
LEFT, 1, 1
1, 2, 2
*CLOAD
RIGHT, 1, {load / len(right)}
{requests}*END STEP
"""


def progress_sizes(stdout):
    """(increment size, Newton iterations) of every progress line of a nonlinear step."""
    return [(float(a), int(b)) for a, b in re.findall(r"size\s+(\S+)\s+newton iterations (\d+)", stdout)]


def run_progress(name, text):
    """Runs with the progress lines (run_deck runs quietly)."""
    import subprocess
    from helpers import CFE2D, workdir
    import os
    d = workdir(name)
    path = os.path.join(d, name + ".inp")
    with open(path, "w") as f:
        f.write(text)
    proc = subprocess.run([CFE2D, "-d", "16", "-o", d, path], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    return proc.stdout


def test_nlgeom_linear_material_one_iteration_same_answers():
    lin = run_deck("nl_frame_lin", bar_deck(step_card="*STEP")).ok()
    nl = run_deck("nl_frame_nlgeom", bar_deck()).ok()
    u_lin = lin.listing.increments[-1].block("NODE U", set="END")["U1"][0]
    inc = nl.listing.increments[-1]
    u_nl = inc.block("NODE U", set="END")["U1"][0]
    assert abs(inc.time - 1.0) < 1e-15
    assert abs(u_lin - 3 * F / (E * 2.0)) <= 1e-12 * u_lin
    assert abs(u_nl - u_lin) <= 1e-12 * u_lin, (u_nl, u_lin)
    for a in inc.block("ELEMENT S")["S11"]:
        assert abs(a - F / 2.0) <= 1e-12 * F
    # one Newton iteration per increment; 0.25, 0.25, then 1.5 times larger, then the rest of the step
    for i in nl.listing.increments:
        assert int(i.attrs["iterations"]) == 1
    times = [i.time for i in nl.listing.increments]
    assert [round(t, 12) for t in times] == [0.25, 0.5, 0.875, 1.0], times


def test_progress_line_has_size_and_newton_iterations():
    out = run_progress("nl_frame_progress", bar_deck())
    sizes = progress_sizes(out)
    assert [round(s, 12) for s, _ in sizes] == [0.25, 0.25, 0.375, 0.125], out
    assert all(n == 1 for _, n in sizes)
    assert "step 1 nonlinear: 4 Newton iterations, 0 increments cut back" in out


def test_direct_fixes_the_increments_and_maximum_caps_them():
    nl = run_deck("nl_frame_direct", bar_deck(static="*STATIC, DIRECT\n0.25, 1.\n")).ok()
    assert [round(i.time, 12) for i in nl.listing.increments] == [0.25, 0.5, 0.75, 1.0]
    # maximum 0.3: 0.25, 0.25, min(0.375, 0.3), rest 0.2
    nl = run_deck("nl_frame_max", bar_deck(static="*STATIC\n0.25, 1., 1e-5, 0.3\n")).ok()
    assert [round(i.time, 12) for i in nl.listing.increments] == [0.25, 0.5, 0.8, 1.0]


def test_nlgeom_stays_on_in_later_steps_until_nlgeom_no():
    second = ("*STEP\n*STATIC\n0.5, 1.\n*CLOAD\n4, 1, 0.\n*NODE PRINT, NSET=END\nU\n*END STEP\n"
              "*STEP, NLGEOM=NO\n*STATIC\n0.5, 1.\n*NODE PRINT, NSET=END\nU\n*END STEP\n")
    out = run_progress("nl_frame_carry", bar_deck(extra_steps=second))
    assert "step 1 nonlinear:" in out and "step 2 nonlinear:" in out and "step 3 nonlinear:" not in out
    # the linear third step runs its fixed increments (two of 0.5)
    assert len(re.findall(r"^step 3  increment \d+  time .* iterations", out, re.M)) == 2


def test_summary_rows_and_peeq_output():
    nl = run_deck("nl_frame_peeq", block_deck(requests="*EL PRINT\nS, PEEQ\n*EL FILE, FORMAT=VTU\nS, PEEQ\n",
                                              static="*STATIC, DIRECT\n0.25, 1.\n")).ok()
    inc = nl.listing.increments[-1]
    peeq = inc.block("ELEMENT PEEQ")["PEEQ"]
    assert len(peeq) == 6 * 4 and all(p == 0.0 for p in peeq)
    text = open(nl.listing_path).read()
    assert re.search(r"^newton_iterations \d+$", text, re.M) and re.search(r"^cutbacks 0$", text, re.M)
    msh = open(nl.listing_path[:-4] + ".msh", "rb").read()
    assert b'"PEEQ (element)"' in msh
    vtu = open(nl.listing_path[:-4] + "_0004.vtu", "rb").read()
    assert b'Name="PEEQ (element)"' in vtu
    # a linear step has neither the rows nor the size in its progress line
    lin = run_deck("nl_frame_lin_rows", bar_deck(step_card="*STEP")).ok()
    assert "newton_iterations" not in open(lin.listing_path).read()


def error_at(name, text, line_text, fragment):
    run = run_deck(name, text)
    line = text.splitlines().index(line_text) + 1
    assert run.rc == 1 and f"{name}.inp:{line}: error:" in run.stderr and fragment in run.stderr, run.stderr


HYPER_SQUARE = """*NODE, NSET=NALL
1, 0.0, 0.0
2, 1.0, 0.0
3, 1.0, 1.0
4, 0.0, 1.0
*ELEMENT, TYPE=CPE4, ELSET=EALL
1, 1, 2, 3, 4
*MATERIAL, NAME=M
*HYPERELASTIC, NEO HOOKE
150.0, {d1}
*SOLID SECTION, ELSET=EALL, MATERIAL=M
1.0
*BOUNDARY
1, 1, 2, 0.0
2, 1, 2, 0.0
3, 1, 1, 0.4
3, 2, 2, 0.3
4, 1, 1, 0.4
4, 2, 2, 0.3
*STEP, NLGEOM
*STATIC
1.0, 1.0
*EL PRINT, ELSET=EALL
S
*END STEP
"""


def test_hyperelastic_d1_zero_is_calculix_default():
    """D1 = 0 is CalculiX 2.20's 0.1 / mu0 = 0.1 / (2 C10) = 1/3000 (hyperelastics.f), with a warning at
    the data line naming the value: the same stresses as D1 = 1/3000 given, and CalculiX's own (ccx 2.20 on
    this deck with D1 = 0, its .dat: S11 1776.106, S22 1878.787, S33 1745.107, S12 100.7440, 7 digits)."""
    zero = run_deck("nl_hyper_d1zero", HYPER_SQUARE.format(d1="0.0")).ok()
    line = HYPER_SQUARE.splitlines().index("150.0, {d1}") + 1
    assert f"nl_hyper_d1zero.inp:{line}: warning: D1 = 0" in zero.stderr and "3.33333E-04" in zero.stderr, \
        zero.stderr
    given = run_deck("nl_hyper_d1given", HYPER_SQUARE.format(d1=repr(1.0 / 3000.0))).ok()
    assert "warning" not in given.stderr, given.stderr
    s0 = zero.listing.increments[-1].block("ELEMENT S")
    s1 = given.listing.increments[-1].block("ELEMENT S")
    ccx = {"S11": 1776.106, "S22": 1878.787, "S33": 1745.107, "S12": 100.7440}
    for comp, ref in ccx.items():
        for a, b in zip(s0[comp], s1[comp]):
            assert abs(a - b) <= 1e-12 * abs(ref), (comp, a, b)
            assert abs(a - ref) <= 1e-6 * abs(ref), (comp, a, ref)


def test_cards_errors_at_the_line():
    hyper = "*HYPERELASTIC, OGDEN\n1., 2., 0.01\n"
    error_at("nl_card_ogden", block_deck(material=hyper), "*HYPERELASTIC, OGDEN", "OGDEN is not implemented")
    error_at("nl_card_n2", block_deck(material="*HYPERELASTIC, POLYNOMIAL, N=2\n1., 0., 0., 0., 0., 0.1\n"),
             "*HYPERELASTIC, POLYNOMIAL, N=2", "only N=1")
    error_at("nl_card_d1", block_deck(material="*HYPERELASTIC, NEO HOOKE\n1., -0.1\n"), "1., -0.1",
             "D1 must not be negative")
    # 1e-9 is not CalculiX's zero (|D1| < 1e-10): K / mu = 1e9
    error_at("nl_card_ratio", block_deck(material="*HYPERELASTIC, NEO HOOKE\n1., 1e-9\n"), "1., 1e-9",
             "more than 1e8 times the shear modulus")
    error_at("nl_card_nh_fields", block_deck(material="*HYPERELASTIC, NEO HOOKE\n1.\n"), "1.",
             "needs: C10, D1")
    error_at("nl_card_temp", block_deck(material="*HYPERELASTIC, NEO HOOKE\n1., 0.1, 20.\n1.1, 0.1, 100.\n"),
             "1.1, 0.1, 100.", "temperature-dependent")
    error_at("nl_card_kinematic", block_deck(material=f"*ELASTIC\n{E}, {NU}\n*PLASTIC, HARDENING=KINEMATIC\n10., 0.\n"),
             "*PLASTIC, HARDENING=KINEMATIC", "only HARDENING=ISOTROPIC")
    error_at("nl_card_first", block_deck(material=f"*ELASTIC\n{E}, {NU}\n*PLASTIC\n10., 0.1\n"), "10., 0.1",
             "at equivalent plastic strain 0")
    error_at("nl_card_order", block_deck(material=f"*ELASTIC\n{E}, {NU}\n*PLASTIC\n10., 0.\n12., 0.2\n13., 0.1\n"),
             "13., 0.1", "must increase")
    error_at("nl_card_ptemp", block_deck(material=f"*ELASTIC\n{E}, {NU}\n*PLASTIC\n10., 0., 20.\n12., 0., 300.\n"),
             "12., 0., 300.", "temperature-dependent *PLASTIC")
    error_at("nl_card_hyper_plastic",
             block_deck(material="*HYPERELASTIC, NEO HOOKE\n1., 0.1\n*PLASTIC\n10., 0.\n"), "*PLASTIC",
             "plasticity of a hyperelastic material")
    error_at("nl_card_minmax", block_deck(static="*STATIC\n0.1, 1., 0.5, 0.2\n"), "0.1, 1., 0.5, 0.2",
             "minimum time increment exceeds the maximum")
    error_at("nl_card_peeq_nodal", block_deck(requests="*NODE PRINT\nPEEQ\n"), "PEEQ", "PEEQ is an element quantity")
    error_at("nl_card_nlgeom", block_deck(step_card="*STEP, NLGEOM=MAYBE"), "*STEP, NLGEOM=MAYBE",
             "NLGEOM must be YES or NO")
    # a plastic material needs its elastic part
    text = block_deck(material="*PLASTIC\n10., 0.\n")
    run = run_deck("nl_card_no_elastic", text)
    line = text.splitlines().index("*MATERIAL, NAME=M") + 1
    assert run.rc == 1 and f"nl_card_no_elastic.inp:{line}: error: material M has no *ELASTIC" in run.stderr, \
        run.stderr
