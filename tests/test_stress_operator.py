"""The stress recovery's linear path (assembly's linear_stresses: no element
call for isotropic linear elastic continuum elements in linear steps)
against the element routine, on every continuum shape and rule in plane
stress, plane strain and axisymmetry, with a thermal strain and with an
initial stress: tests/unit/test_stress_operator.f90 compares the stresses
and strains at the points and the nodal stresses to 1e-12 of their largest
magnitude. Built here (make's pattern rule for tests/unit programs) into
the default build tree."""
import os
import subprocess

from helpers import ROOT

EXE = os.path.join(ROOT, "build", "tests", "test_stress_operator")


def test_linear_stresses_match_element_routine():
    mk = subprocess.run(["make", "-s", "build/tests/test_stress_operator"], cwd=ROOT, capture_output=True, text=True)
    assert mk.returncode == 0, f"building {EXE} failed:\n{mk.stderr[-2000:]}"
    r = subprocess.run([EXE], capture_output=True, text=True, timeout=120)
    lines = [ln for ln in r.stdout.splitlines() if ln.startswith(("PASS ", "FAIL "))]
    fails = [ln for ln in lines if ln.startswith("FAIL ")]
    # 3 stress states x (plain, thermal, initial stress) x 5 checks
    assert len(lines) == 45, f"expected 45 checks, got {len(lines)}:\n{r.stdout}\n{r.stderr}"
    assert not fails and r.returncode == 0, "\n".join(fails) + r.stderr
