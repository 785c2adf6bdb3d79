"""Hertz theory written again, independently of edp/lib/reference.idp, for the tests (docs/physics.md)."""
from __future__ import annotations

import math
from dataclasses import dataclass

from scipy.special import ellipe, ellipk


def estar(E: float, nu: float) -> float:
    return E / (1 - nu**2)


@dataclass(frozen=True)
class Sphere:
    a: float
    F: float
    p0: float


def sphere(E: float, nu: float, R: float, d: float) -> Sphere:
    a = math.sqrt(R * d)
    F = 4 / 3 * estar(E, nu) * a * d
    return Sphere(a, F, 3 * F / (2 * math.pi * a**2))


def sphere_from_load(E: float, nu: float, R: float, P: float) -> Sphere:
    """The sphere under a load P: a = (3 P R/(4 E*))^(1/3), d = a^2/R."""
    a = (3 * P * R / (4 * estar(E, nu))) ** (1 / 3)
    return Sphere(a, P, 3 * P / (2 * math.pi * a**2))


def sphere_depth(E: float, nu: float, R: float, P: float) -> float:
    return sphere_from_load(E, nu, R, P).a ** 2 / R


def sphere_deflection(r: float, a: float, d: float, R: float) -> float:
    """Hertz's surface deflection (downwards) at radius r: the indenter's shape inside
    the contact, (d/pi)[(2 - r^2/a^2) asin(a/r) + sqrt(r^2/a^2 - 1)] outside (Johnson 3.42)."""
    if r <= a:
        return d - r * r / (2 * R)
    rho = r / a
    return d / math.pi * ((2 - rho * rho) * math.asin(1 / rho) + math.sqrt(rho * rho - 1))


def punch_stiffness(E: float, nu: float, a: float) -> float:
    """dF/dd of any axisymmetric punch of contact radius a (Sneddon): 2 E* a."""
    return 2 * estar(E, nu) * a


def cylinder_half_width(P: float, E: float, nu: float, R: float) -> float:
    return math.sqrt(4 * P * R / (math.pi * estar(E, nu)))


def cylinder_pressure(P: float, E: float, nu: float, R: float) -> float:
    return 2 * P / (math.pi * cylinder_half_width(P, E, nu, R))


SEED = dict(E=10.0, nu=0.3, R=0.5, d=0.02)


def elliptic_ke(m: float) -> tuple[float, float]:
    """Complete elliptic integrals K(m), E(m) of parameter m = e^2, from scipy (Cephes):
    not the solver's arithmetic-geometric mean, so that the check is independent."""
    return float(ellipk(m)), float(ellipe(m))


@dataclass(frozen=True)
class Ellipse:
    a_long: float
    b_short: float
    p0: float
    d: float
    P: float


def ellipsoid_from_load(P: float, E: float, nu: float, R_small: float, R_large: float) -> Ellipse:
    """Elliptical Hertz contact (Johnson ch. 4): the long semi-axis lies along the larger radius."""
    A, B = 1 / (2 * R_large), 1 / (2 * R_small)
    lo, hi = 0.0, 1.0
    for _ in range(200):  # B/A = [(a/b)^2 E - K]/(K - E), increasing in m = e^2
        m = 0.5 * (lo + hi)
        K, Ee = elliptic_ke(m)
        ratio = (Ee / (1 - m) - K) / (K - Ee)
        lo, hi = (m, hi) if ratio < B / A else (lo, m)
    m = 0.5 * (lo + hi)
    K, Ee = elliptic_ke(m)
    es = estar(E, nu)
    a = (3 * P * (K - Ee) / (2 * math.pi * es * m * A)) ** (1 / 3)
    b = a * math.sqrt(1 - m)
    return Ellipse(a, b, 3 * P / (2 * math.pi * a * b), 3 * P * K / (2 * math.pi * a * es), P)


def ellipsoid_from_depth(d: float, E: float, nu: float, R_small: float, R_large: float) -> Ellipse:
    """The same at a given approach d: d grows as P^(2/3)."""
    unit = ellipsoid_from_load(1.0, E, nu, R_small, R_large)
    return ellipsoid_from_load((d / unit.d) ** 1.5, E, nu, R_small, R_large)
