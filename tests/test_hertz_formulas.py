"""The analytical Hertz line contact of scripts/hertz.py: the pressure
integrates to the load, E* in both plane states and for dissimilar
materials, and the classical steel cylinder numbers."""
import math

import numpy as np

from hertz import HertzLine, effective_modulus, effective_radius


def test_pressure_integrates_to_the_load():
    h = HertzLine(13921.87, 10.0, effective_modulus(210000.0, 0.3))
    x = np.linspace(-h.a, h.a, 200001)
    p = h(x)
    force = float(np.sum(0.5 * (p[1:] + p[:-1]) * np.diff(x)))
    assert abs(force - h.P) < 1e-6 * h.P
    assert abs(h.p0 - 2 * h.P / (math.pi * h.a)) < 1e-12 * h.p0
    assert h(1.5 * h.a) == 0.0


def test_effective_modulus_plane_stress_and_strain():
    e, nu = 210000.0, 0.3
    assert abs(effective_modulus(e, nu, plane="stress") - e / 2) < 1e-9
    assert abs(effective_modulus(e, nu, plane="strain") - e / (2 * (1 - nu ** 2))) < 1e-9
    # dissimilar: steel on aluminium, plane strain
    es = 1 / ((1 - 0.3 ** 2) / 210000.0 + (1 - 0.33 ** 2) / 70000.0)
    assert abs(effective_modulus(210000.0, 0.3, 70000.0, 0.33, plane="strain") - es) < 1e-9


def test_effective_radius():
    assert effective_radius(10.0) == 10.0
    assert abs(effective_radius(10.0, 10.0) - 5.0) < 1e-12


def test_half_width_scales_with_square_root_of_load():
    estar = effective_modulus(210000.0, 0.3)
    a1, a4 = HertzLine(1000.0, 10.0, estar).a, HertzLine(4000.0, 10.0, estar).a
    assert abs(a4 / a1 - 2.0) < 1e-12
    # a = sqrt(4 P R / (pi E*)) for P = 13921.87 N/mm: 1.2993 mm
    assert abs(HertzLine(13921.87, 10.0, estar).a - math.sqrt(4 * 13921.87 * 10 / (math.pi * estar))) < 1e-12


def test_plots_draw_round_off_as_zero():
    """The sigma_y contours of scripts/plots_hertz.py: values below 1e-9 of
    the largest plotted magnitude (round-off of an unloaded increment) are
    drawn as exact zeros; real stresses are kept."""
    from plots_hertz import round_off_to_zero
    v = round_off_to_zero([3.0e-9, -2.0e-7, -1500.0, 0.0, 4.0e-5], 7000.0)
    assert list(v) == [0.0, 0.0, -1500.0, 0.0, 4.0e-5]
    assert list(round_off_to_zero([1e-12, -1e-12], 0.0)) == [1e-12, -1e-12]
