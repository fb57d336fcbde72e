"""Hertz's solution for the frictionless contact of two parallel cylinders
(line contact, 2D), a cylinder on a flat being the case R2 -> infinity.

    1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2   plane strain
    1/E* = 1/E1 + 1/E2                       plane stress
    a  = sqrt(4 P R / (pi E*))   half-width of the contact
    p0 = 2 P / (pi a)            peak pressure
    p(x) = p0 sqrt(1 - x^2/a^2)

P is the load per unit thickness and R the effective radius
1/R = 1/R1 + 1/R2. Units are the caller's (consistent) units.
"""
import math

import numpy as np

__all__ = ["effective_modulus", "effective_radius", "half_width", "peak_pressure", "pressure",
           "HertzLine"]


def effective_modulus(e1, nu1, e2=None, nu2=None, plane="stress"):
    """E* for two materials; the second defaults to the first."""
    e2 = e1 if e2 is None else e2
    nu2 = nu1 if nu2 is None else nu2
    if plane == "stress":
        return 1.0 / (1.0 / e1 + 1.0 / e2)
    if plane == "strain":
        return 1.0 / ((1 - nu1 ** 2) / e1 + (1 - nu2 ** 2) / e2)
    raise ValueError("plane must be 'stress' or 'strain'")


def effective_radius(r1, r2=math.inf):
    return 1.0 / (1.0 / r1 + (0.0 if math.isinf(r2) else 1.0 / r2))


def half_width(p, r, estar):
    return math.sqrt(4.0 * p * r / (math.pi * estar))


def peak_pressure(p, r, estar):
    return 2.0 * p / (math.pi * half_width(p, r, estar))


def pressure(x, p, r, estar):
    """Hertz pressure at positions x (zero outside the contact)."""
    a = half_width(p, r, estar)
    x = np.asarray(x, dtype=float)
    return peak_pressure(p, r, estar) * np.sqrt(np.clip(1.0 - (x / a) ** 2, 0.0, None))


class HertzLine:
    """The solution for one load: h = HertzLine(P, R, E*); h.a, h.p0, h(x)."""

    def __init__(self, p, r, estar):
        self.P, self.R, self.Estar = p, r, estar
        self.a = half_width(p, r, estar)
        self.p0 = peak_pressure(p, r, estar)

    def __call__(self, x):
        return pressure(x, self.P, self.R, self.Estar)


if __name__ == "__main__":
    import argparse
    ap = argparse.ArgumentParser(description="Hertz line contact: half-width and peak pressure")
    ap.add_argument("P", type=float, help="load per unit thickness")
    ap.add_argument("R", type=float, help="cylinder radius (effective radius)")
    ap.add_argument("E", type=float, help="Young's modulus of both bodies")
    ap.add_argument("nu", type=float, help="Poisson's ratio of both bodies")
    ap.add_argument("--plane", choices=["stress", "strain"], default="stress")
    a = ap.parse_args()
    h = HertzLine(a.P, a.R, effective_modulus(a.E, a.nu, plane=a.plane))
    print(f"E* = {h.Estar:.6g}  a = {h.a:.6g}  p0 = {h.p0:.6g}")
