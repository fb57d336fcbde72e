"""A non-zero *BOUNDARY value of the model data (before the first *STEP)
follows the first step as a step's own value: it ramps from zero over the
step, then stays where the steps leave it. CalculiX 2.20, measured with
NLGEOM and *STATIC, DIRECT 0.25 (its linear static step takes a single
increment): a model-data u2 = -0.9 gives -0.225, -0.45, -0.675, -0.9; a
second step without *BOUNDARY holds -0.9; a second step's *BOUNDARY of
-0.5 on that dof ramps -0.9 -> -0.5; a first step's *BOUNDARY of -0.5 on
a model-data dof ramps 0 -> -0.5 and a second step holds -0.5 (not the
model-data value).

The linear checks are on three trusses in series (closed form: the end
displacement is the prescribed value, the reaction E A u / L, the middle
nodes at thirds), the nonlinear one on CalculiX's neo-Hooke CPE4 square
compressed to 10 % of its height, whose prescribed u2 are CalculiX's."""
from helpers import run_deck

E, AREA, L = 1000.0, 2.0, 3.0


def bar(model_bc, steps):
    """Three T2D2 trusses along x, node 1 held; model_bc: *BOUNDARY lines of the model data."""
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
{E}, 0.3
*SOLID SECTION, ELSET=BAR, MATERIAL=M
{AREA}
*BOUNDARY
ALL, 2, 2
1, 1, 1
{model_bc}{steps}"""


def step(inc, bc="", nlgeom=False):
    return (f"*STEP{', NLGEOM' if nlgeom else ''}\n*STATIC, DIRECT\n{inc}, 1.\n{bc}"
            "*NODE PRINT, NSET=ALL\nU\n*END STEP\n")


def u1(inc, node):
    b = inc.block("NODE U", set="ALL")
    return b["U1"][node - 1]


def check_history(run, expected, tol=1e-12):
    """expected: u1 of node 4 at each increment, in order; node 3 at 2/3 of it (uniform bar)."""
    incs = run.listing.increments
    assert len(incs) == len(expected), [i.time for i in incs]
    for inc, want in zip(incs, expected):
        assert abs(u1(inc, 4) - want) <= tol, (inc.step, inc.time, u1(inc, 4), want)
        assert abs(u1(inc, 3) - 2.0 / 3.0 * want) <= tol, (inc.step, inc.time, u1(inc, 3), want)


def test_model_data_value_ramps_over_the_first_step_linear():
    """Linear steps: the intermediate increments ramp (before: 0.03 from the first); the end is unchanged."""
    run = run_deck("mbc_lin", bar("4, 1, 1, 0.03\n", step(0.25) + step(0.5))).ok()
    check_history(run, [0.0075, 0.015, 0.0225, 0.03, 0.03, 0.03])


def test_model_data_value_ramps_over_the_first_step_nlgeom():
    """The same under NLGEOM (trusses stay linear: the same answers)."""
    run = run_deck("mbc_nl", bar("4, 1, 1, 0.03\n", step(0.25, nlgeom=True) + step(0.5))).ok()
    check_history(run, [0.0075, 0.015, 0.0225, 0.03, 0.03, 0.03], tol=1e-12)


def test_step_changes_a_model_data_value():
    """A second step's *BOUNDARY ramps from the model-data value to its own."""
    run = run_deck("mbc_change", bar("4, 1, 1, 0.03\n", step(0.5) + step(0.5, "*BOUNDARY\n4, 1, 1, 0.01\n"))).ok()
    check_history(run, [0.015, 0.03, 0.02, 0.01])


def test_first_step_overrides_a_model_data_value_and_later_steps_hold_it():
    """A first step's *BOUNDARY on a model-data dof ramps from zero to the step's value, and the next step
    holds it there (before: it started at the model-data value and jumped back to it in the next step)."""
    run = run_deck("mbc_override", bar("4, 1, 1, 0.03\n", step(0.5, "*BOUNDARY\n4, 1, 1, 0.01\n") + step(0.5))).ok()
    check_history(run, [0.005, 0.01, 0.01, 0.01])


def test_op_new_keeps_model_data_dofs_where_they_are():
    """OP=NEW does not remove model-data conditions (cfe2d's documented rule): the end stays at 0.03 held
    while a load is added."""
    run = run_deck("mbc_opnew", bar("4, 1, 1, 0.03\n", step(1.0) + step(
        1.0, "*BOUNDARY, OP=NEW\n3, 1, 1, 0.01\n*CLOAD\n2, 1, 1.\n"))).ok()
    incs = run.listing.increments
    assert abs(u1(incs[0], 4) - 0.03) <= 1e-12
    assert abs(u1(incs[1], 4) - 0.03) <= 1e-12 and abs(u1(incs[1], 3) - 0.01) <= 1e-12


SQUARE = """*NODE, NSET=NALL
1, 0.0, 0.0
2, 1.0, 0.0
3, 1.0, 1.0
4, 0.0, 1.0
*ELEMENT, TYPE=CPE4, ELSET=EALL
1, 1, 2, 3, 4
*MATERIAL, NAME=RUBBER
*HYPERELASTIC, NEO HOOKE
150.0, 0.002
*SOLID SECTION, ELSET=EALL, MATERIAL=RUBBER
1.0
*BOUNDARY
1, 1, 2, 0.0
2, 1, 2, 0.0
3, 2, 2, {v}
4, 2, 2, {v}
*STEP, NLGEOM
*STATIC, DIRECT
0.25, 1.0
*NODE PRINT, NSET=NALL
U
*END STEP
"""


def test_hyperelastic_square_compressed_by_model_data_values():
    """CalculiX's prescribed u2 of nodes 3 and 4 in its four increments: -0.225, -0.45, -0.675, -0.9
    (before: -0.9 in all four). To 99 % of the height the first increment inverted the element and no
    cut-back helped (the value was not scaled); ramped, it runs."""
    run = run_deck("mbc_square", SQUARE.format(v="-0.9")).ok()
    incs = run.listing.increments
    assert [round(i.time, 12) for i in incs] == [0.25, 0.5, 0.75, 1.0]
    for inc, want in zip(incs, [-0.225, -0.45, -0.675, -0.9]):
        b = inc.block("NODE U", set="NALL")
        assert abs(b["U2"][2] - want) <= 1e-12 and abs(b["U2"][3] - want) <= 1e-12, (inc.time, b["U2"])
    run = run_deck("mbc_square99", SQUARE.format(v="-0.99")).ok()
    b = run.listing.increments[-1].block("NODE U", set="NALL")
    assert abs(run.listing.increments[-1].time - 1.0) < 1e-12 and abs(b["U2"][2] + 0.99) <= 1e-12
