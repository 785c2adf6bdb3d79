"""Hertz theory written again, independently of edp/lib/reference.idp, for the tests (docs/physics.md)."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import quad
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


def sphere_axis_stresses(zeta, p0: float, nu: float):
    """Hertz's sigma_r and sigma_z on the axis below a sphere at depths zeta = z/a
    (Johnson 3.45): sigma_z = -p0/(1 + zeta^2), sigma_r = p0 [-(1 + nu)(1 - zeta
    atan(1/zeta)) + 1/(2 (1 + zeta^2))]; zeta an array or a number."""
    zeta = np.asarray(zeta, dtype=float)
    atan_inv = np.where(zeta > 0, np.arctan(1 / np.where(zeta > 0, zeta, 1.0)), math.pi / 2)
    sigma_r = p0 * (-(1 + nu) * (1 - zeta * atan_inv) + 0.5 / (1 + zeta**2))
    return sigma_r, -p0 / (1 + zeta**2)


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


# Indenters beyond the parabola, by Popov's method of dimensionality reduction (MDR), not by
# Sneddon's integrals as the solver writes them: an axisymmetric profile f(r) maps to the 1D
# profile g(x) = x int_0^x f'(r)/sqrt(x^2 - r^2) dr; then d = g(a), F = 2 E* int_0^a (d - g) dx
# and p(r) = (E*/pi) int_r^a g'(x)/sqrt(x^2 - r^2) dx (Popov, Hess, Willert 2019, ch. 3).
@dataclass(frozen=True)
class Punch:
    a: float
    d: float
    F: float


def _mdr_g(fprime, x: float) -> float:
    # r = x sin(t): int_0^x f'(r)/sqrt(x^2 - r^2) dr = int_0^(pi/2) f'(x sin t) dt, no singularity
    return x * quad(lambda t: fprime(x * math.sin(t)), 0, math.pi / 2, limit=200)[0]


def mdr_depth_force(fprime, a: float, Es: float) -> tuple[float, float]:
    d = _mdr_g(fprime, a)
    F = 2 * Es * quad(lambda x: d - _mdr_g(fprime, x), 0, a, limit=200)[0]
    return d, F


def mdr_pressure(fprime, r: float, a: float, Es: float, h: float = 1e-6) -> float:
    """p(r) for r < a, with x = sqrt(r^2 + s^2) so that the integrand is smooth: g'(x)/x ds."""
    def gprime(x):
        return (_mdr_g(fprime, x * (1 + h)) - _mdr_g(fprime, x * (1 - h))) / (2 * h * x)
    return Es / math.pi * quad(lambda s: gprime(math.hypot(r, s)) / math.hypot(r, s), 0,
                               math.sqrt(a * a - r * r), limit=200)[0]


def profile_slope(shape: str, R: float = 0.5, angle: float = 70.3, k: float = 1.5):
    """f'(r) of the solver's shapes: sphere R - sqrt(R^2 - r^2), cone r cot(alpha), power
    r^k/(k R^(k-1))."""
    if shape == "sphere":
        return lambda r: r / math.sqrt(R * R - r * r)
    if shape == "cone":
        return lambda r: 1 / math.tan(math.radians(angle))
    if shape == "power":
        return lambda r: (r / R) ** (k - 1)
    raise ValueError(shape)


def max_pressure(shape: str, a: float, Es: float, **geometry) -> float:
    """The largest pressure: at the centre, or off it for a power law k > 2 (whose pressure dips there)."""
    from scipy.optimize import minimize_scalar
    fp = profile_slope(shape, **geometry)
    if shape == "power" and geometry["k"] > 2:
        best = minimize_scalar(lambda r: -mdr_pressure(fp, r, a, Es), bounds=(0, 0.95 * a),
                               method="bounded", options={"xatol": 1e-4 * a})
        return -best.fun
    return mdr_pressure(fp, 0.0, a, Es)


def profile_from_depth(fprime, d: float, Es: float, a_max: float) -> Punch:
    """a, d and F of the axisymmetric profile of slope fprime pressed to depth d (a by bisection
    on d = g(a), below a_max)."""
    lo, hi = 0.0, a_max
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if _mdr_g(fprime, mid) < d else (lo, mid)
    a = 0.5 * (lo + hi)
    return Punch(a, d, mdr_depth_force(fprime, a, Es)[1])


def punch_from_depth(shape: str, d: float, E: float, nu: float, **geometry) -> Punch:
    """profile_from_depth for the solver's named shapes."""
    a_max = geometry.get("R", 0.5) * (0.999999 if shape == "sphere" else 100)
    return profile_from_depth(profile_slope(shape, **geometry), d, estar(E, nu), a_max)


def punch_from_load(shape: str, P: float, E: float, nu: float, **geometry) -> Punch:
    Es, fp = estar(E, nu), profile_slope(shape, **geometry)
    lo, hi = 0.0, geometry.get("R", 0.5) * (0.999999 if shape == "sphere" else 100)
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if mdr_depth_force(fp, mid, Es)[1] < P else (lo, mid)
    a = 0.5 * (lo + hi)
    return Punch(a, _mdr_g(fp, a), P)


def flat_punch_edge_coefficient(P: float, a: float, plane: bool = False) -> float:
    """lim p sqrt(a - r) at a flat punch's edge: p = P/(2 pi a sqrt(a^2 - r^2)) (axisymmetric),
    P/(pi sqrt(a^2 - x^2)) per unit length (plane, Johnson 2.64)."""
    return P / (math.pi * math.sqrt(2 * a)) if plane else P / (2 * math.pi * a * math.sqrt(2 * a))


def plane_half_width(shape: str, P: float, E: float, nu: float, **geometry) -> float:
    """Half-width of a plane (line) contact under P per unit length: P = (E*/2) int_-a^a x f'(x)/
    sqrt(a^2 - x^2) dx (Johnson 2.48 with the pressure bounded at both edges), by bisection."""
    Es, fp = estar(E, nu), profile_slope(shape, **geometry)

    def load(a):  # x = a sin t
        return Es * a * quad(lambda t: math.sin(t) * fp(a * math.sin(t)), 0, math.pi / 2)[0]
    lo, hi = 0.0, geometry.get("R", 0.5) * (0.999999 if shape == "sphere" else 100)
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if load(mid) < P else (lo, mid)
    return 0.5 * (lo + hi)
