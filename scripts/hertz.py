"""Hertz's solution for the frictionless contact of two parallel cylinders
(line contact, 2D), a cylinder on a flat being the case R2 -> infinity;
and (at the end, HertzPoint) of two spheres (point contact, 3D, as an
axisymmetric model computes it).

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
           "HertzLine", "point_modulus", "contact_radius", "point_peak_pressure", "point_approach",
           "HertzPoint"]


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


# Point contact (two spheres, or a sphere on a flat: R2 -> infinity), 3D:
#   1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2
#   a  = (3 P R / (4 E*))^(1/3)   radius of the contact circle
#   p0 = 3 P / (2 pi a^2)         peak pressure, p(r) = p0 sqrt(1 - r^2/a^2)
#   delta = a^2 / R               approach of distant points
# with P the total load (an axisymmetric model's whole-ring force).


def point_modulus(e1, nu1, e2=None, nu2=None):
    """E* of point contact for two materials; the second defaults to the first."""
    e2 = e1 if e2 is None else e2
    nu2 = nu1 if nu2 is None else nu2
    return 1.0 / ((1 - nu1 ** 2) / e1 + (1 - nu2 ** 2) / e2)


def contact_radius(p, r, estar):
    return (3.0 * p * r / (4.0 * estar)) ** (1.0 / 3.0)


def point_peak_pressure(p, r, estar):
    return 3.0 * p / (2.0 * math.pi * contact_radius(p, r, estar) ** 2)


def point_approach(p, r, estar):
    return contact_radius(p, r, estar) ** 2 / r


class HertzPoint:
    """The point-contact solution for one load: h = HertzPoint(P, R, E*);
    h.a (contact radius), h.p0, h.delta, h(r) the pressure."""

    def __init__(self, p, r, estar):
        self.P, self.R, self.Estar = p, r, estar
        self.a = contact_radius(p, r, estar)
        self.p0 = point_peak_pressure(p, r, estar)
        self.delta = point_approach(p, r, estar)

    def __call__(self, x):
        x = np.asarray(x, dtype=float)
        return self.p0 * np.sqrt(np.clip(1.0 - (x / self.a) ** 2, 0.0, None))


if __name__ == "__main__":
    import argparse
    ap = argparse.ArgumentParser(description="Hertz line contact: half-width and peak pressure")
    ap.add_argument("P", type=float, help="load per unit thickness")
    ap.add_argument("R", type=float, help="cylinder radius (effective radius)")
    ap.add_argument("E", type=float, help="Young's modulus of both bodies")
    ap.add_argument("nu", type=float, help="Poisson's ratio of both bodies")
    ap.add_argument("--plane", choices=["stress", "strain"], default="stress")
    ap.add_argument("--point", action="store_true", help="point contact (sphere; P the total load)")
    a = ap.parse_args()
    if a.point:
        h = HertzPoint(a.P, a.R, point_modulus(a.E, a.nu))
        print(f"E* = {h.Estar:.6g}  a = {h.a:.6g}  p0 = {h.p0:.6g}  delta = {h.delta:.6g}")
    else:
        h = HertzLine(a.P, a.R, effective_modulus(a.E, a.nu, plane=a.plane))
        print(f"E* = {h.Estar:.6g}  a = {h.a:.6g}  p0 = {h.p0:.6g}")
