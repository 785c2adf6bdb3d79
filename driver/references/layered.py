"""Frictionless contact of a rigid axisymmetric indenter on a coated half-space, written
independently of the solver (edp/ never reads it), for the tests and the layers chart: an
elastic film (E1, nu1, thickness t), the body the indenter touches, perfectly bonded to an
elastic substrate half-space (E2, nu2) or to a rigid base (E2 = inf). The method is the exact
integral formulation of Perriot & Barthel, J. Mater. Res. 19 (2004) 600, solved by Nystrom
quadrature.

1. Surface response of the coated body (Hankel space)
   Hankel pair: f~(k) = int_0^inf f(r) J0(kr) r dr, f(r) = int_0^inf f~(k) J0(kr) k dk.
   A pressure p(r) on the free surface, without shear, moves the surface by u(r) (into the body):
       u~(k) = 2 p~(k) C(kt) / (E1* k),     E* = E / (1 - nu^2)               (1)
   C = 1 for a half-space of film (Boussinesq: u = P / (pi E* r) for a point load P). For the
   bonded layer, with m = G1/G2 and kj = 3 - 4 nuj (Kolosov's constant),
       C(u) = (1 + 4 B u e^{-2u} - A B e^{-4u}) / (1 - (A + B + 4 B u^2) e^{-2u} + A B e^{-4u})   (2)
       A = (m k2 - k1) / (1 + m k2),   B = (m - 1) / (m + k1);   rigid base (m = 0): A = -k1, B = -1/k1,
   the bonded-layer factor of Perriot & Barthel (2004). Rather than taken on trust, (2) is checked
   against a second derivation, surface_factor_by_propagator: Navier's equations for
   u_r = U(z) J1(kr), u_z = W(z) J0(kr) give the first-order system d/d(kz) [U, W, T/(Gk), S/(Gk)] =
   P(nu) [...] (T, S the J1, J0 amplitudes of sigma_rz, sigma_zz), integrated across the film by
   the matrix exponential, with the substrate's decaying solutions (the null space of (P + I)^2)
   or U = W = 0 on a rigid base; they agree to rounding (tests). The limits of (2): C(0) = E1*/E2*
   (the substrate), C -> 1 for kt >> 1 (the film: D = C - 1 = O(u^2 e^{-2u})), and on a rigid base
   C ~ E1* kt / (2 M) (a Winkler layer p = M u / t, M = E1 (1 - nu1) / ((1 + nu1)(1 - 2 nu1))) or,
   incompressible (nu1 = 1/2), C ~ 2 (kt)^3 / 3 (u = -(t^3 / 3 G1) Laplacian p).

2. The contact integral equation (Sneddon's auxiliary function, Barthel's g up to a factor 2/pi)
   Write the pressure, zero outside the contact radius a, through g on [0, a]:
       p~(k) = int_0^a g(s) cos(ks) ds,
       p(r) = g(a) / sqrt(a^2 - r^2) - int_r^a g'(s) ds / sqrt(s^2 - r^2),   F = 2 pi int_0^a g(s) ds.
   On a half-space of film, u(r) = (2 / E1*) int_0^r g(s) ds / sqrt(r^2 - s^2) inside the contact
   (int_0^inf J0(kr) cos(ks) dk = 1 / sqrt(r^2 - s^2) for s < r, 0 beyond), which Abel's inversion
   turns into g = (E1*/pi) d/ds int_0^s r u(r) dr / sqrt(s^2 - r^2): flat punch u = d gives
   g = E1* d / pi, a parabola u = d - r^2/(2R) gives g = (E1*/pi)(d - s^2/R). With (1), the same
   inversion (it maps J0(kr) to (2/pi) cos(ks)) gives the Fredholm equation of the second kind
       g(s) + int_0^a K(s, s') g(s') ds' = (E1*/pi) * {d  |  d - s^2/R}                       (3)
       K(s, s') = (2/pi) int_0^inf [C(kt) - 1] cos(ks) cos(ks') dk,
   the deviation of the coated body from the film's half-space (Perriot & Barthel's kernel). In
   x = s/a, q = k a, eps = t/a, by linearity g = (E1*/pi)(d psi(x) - (a^2/R) chi(x)) with
       psi + K^ psi = 1,   chi + K^ chi = x^2,   K^(x, x') = (2/pi) int_0^inf D(q eps) cos(qx) cos(qx') dq.
   Flat punch of radius a: F = 2 E1* a d Psi, Psi = int_0^1 psi, so the stiffness S = dF/dd = 2 E_eff* a
   with E_eff* = E1* Psi (E_eff* in the plane-strain sense, E* of a half-space giving the same S).
   Parabola (sphere) with a smooth edge, g(a) = 0:
       d = (a^2/R) chi(1)/psi(1),   F = 2 E1* (a^3/R) (chi(1) Psi / psi(1) - X),   X = int_0^1 chi,
   and its pressure p(r) = -(E1*/(pi a)) int_0^{sqrt(1 - rho^2)} gamma'(x) / x dv, rho = r/a,
   x = sqrt(rho^2 + v^2), gamma = d psi - (a^2/R) chi. Homogeneous (D = 0): psi = 1, chi = x^2, and
   Sneddon/Hertz come back exactly: F = 2 E* a d, d = a^2/R, F = 4/3 E* a^3/R.

3. Numerics and their accuracy
   The kernel is a cosine transform of D, itself exact (no truncated series). With the even extension,
   (3) lives on [-1, 1]; psi and chi are analytic there, with features of width ~t near the edge, so
   Gauss-Legendre nodes of [-1, 1] (their positive half) converge exponentially once they resolve t:
   n = max(32, 8 a/t) nodes on [-1, 1] by default. K^ = (2/pi) Cos^T diag(w_q D) Cos with Cos_mj = cos(q_m x_j)
   on composite Gauss panels (16 nodes) in q: panels of at most 4 in q (cos(2q) resolved) and 0.5 in
   kt (D resolved), graded geometrically towards q = 0 down to kt = 1e-3 min(1, G2/G1) (a stiff film on
   a soft substrate has a feature at kt ~ G2/G1: its membrane stiffness), truncated at kt = 20. The tail
   is analytic: the half-space of film (C -> 1) is the identity in (3), so what is left, D, decays as
   (kt)^2 e^{-2kt} (|D| < 1e-14 beyond). psi(1), chi(1) come from Nystrom's interpolation.
   error_estimate compares with every count doubled (and the panels halved). Measured with it
   (relative change of F on doubling, flat punch and sphere, nu1 = nu2 = 0.3), over t/a in [0.01, 100],
   E2/E1 in [0.01, 100] and a rigid base: below 3e-9 everywhere; the worst are thin films on a much
   stiffer or rigid base (1e-9 to 3e-9 at t/a = 0.01), where (3) is ill-conditioned by a/t (the
   body is a/t times stiffer than the film). nu1 -> 1/2 on a rigid base is harder: an incompressible
   thin layer is (a/t)^2 stiffer again (F ~ a^6/t^3): at nu1 = 0.5 and t/a = 0.01 the estimate is
   about 1e-6 (1e-8 at t/a = 0.03). Run time: under 0.01 s for t/a >= 0.3, about 0.1 s at t/a = 0.03,
   0.3 s at 0.01 (the work grows as (a/t)^3); the doubled check costs 8 times as much.

4. Limits the tests check (tests/test_layered_reference.py)
   - E2 = E1, nu2 = nu1: D = 0, the homogeneous half-space exactly (Hertz, Sneddon).
   - t >> a: the film's half-space plus the substrate seen as at a point: K^ = K1 + O((a/t)^3) with
     K1 = (2 a/(pi t)) int_0^inf D(u) du, so E_eff* = E1* / (1 + K1), d = (a^2/R)(1 + 2 K1/3),
     F = 4/3 E1* a^3/R (thick_film_asymptote).
   - t << a: the substrate's half-space, approached as (t/a) ln(a/t) (the edge of a flat punch
     concentrates the film's own compliance).
   - A thin layer on a rigid base (Johnson, Contact Mechanics, 1985, section 5.9): compressible, the
     Winkler foundation p = (M/t) u: E_eff* = pi M a / (2t); sphere a^2 = 2 R d, F = pi M a^4 / (4 R t).
     Incompressible (a lubrication-type thin-layer solution, p = 3 G1 (a^2 - r^2)^2 / (32 R t^3)):
     a^2 = 4 R d, F = pi G1 a^6 / (32 R t^3); flat punch E_eff* = 3 pi G1 a^3 / (16 t^3).
   - Gao, Chiu & Lee, Int. J. Solids Struct. 29 (1992) 2471 (gao_effective_modulus): the first-order
     perturbation in the moduli mismatch, exact to that order (the derivative at E2 = E1 agrees to 1e-7).
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from numpy.polynomial.legendre import leggauss

# scipy (a test dependency) is imported where it is used: the layers chart needs only the
# effective modulus, which is numpy alone, so the package does not depend on scipy


def estar(E: float, nu: float) -> float:
    """Plane-strain modulus E / (1 - nu^2)."""
    return E / (1 - nu**2)


def constrained_modulus(E: float, nu: float) -> float:
    """Oedometric (uniaxial strain) modulus M = E (1 - nu) / ((1 + nu)(1 - 2 nu)); inf at nu = 1/2."""
    return math.inf if nu >= 0.5 else E * (1 - nu) / ((1 + nu) * (1 - 2 * nu))


@dataclass(frozen=True)
class Coating:
    """Film (E1, nu1, thickness t) bonded to a substrate half-space (E2, nu2); E2 = math.inf: rigid base."""
    E1: float
    nu1: float
    t: float
    E2: float = math.inf
    nu2: float = 0.3

    def __post_init__(self) -> None:
        if not (self.E1 > 0 and self.E2 > 0 and self.t > 0):
            raise ValueError(f"moduli and thickness must be positive: {self}")
        if not (-1 < self.nu1 <= 0.5 and -1 < self.nu2 <= 0.5):
            raise ValueError(f"Poisson's ratios must lie in (-1, 1/2]: {self}")

    @property
    def rigid_base(self) -> bool:
        return math.isinf(self.E2)

    @property
    def G1(self) -> float:
        return self.E1 / (2 * (1 + self.nu1))

    @property
    def G2(self) -> float:
        return self.E2 / (2 * (1 + self.nu2))

    @property
    def E1s(self) -> float:
        """The film's E*."""
        return estar(self.E1, self.nu1)

    @property
    def E2s(self) -> float:
        """The substrate's E* (inf on a rigid base)."""
        return math.inf if self.rigid_base else estar(self.E2, self.nu2)

    @property
    def M1(self) -> float:
        """The film's constrained modulus."""
        return constrained_modulus(self.E1, self.nu1)


# --- 1. surface response --------------------------------------------------------------------------


def layer_coefficients(c: Coating) -> tuple[float, float]:
    """A, B of eq. (2): the film-substrate mismatch (both 0 for a homogeneous body)."""
    k1, k2 = 3 - 4 * c.nu1, 3 - 4 * c.nu2
    if c.rigid_base:
        return -k1, -1 / k1
    m = c.G1 / c.G2
    return (m * k2 - k1) / (1 + m * k2), (m - 1) / (m + k1)


def surface_factor(u, c: Coating):
    """C(u), u = k t, eq. (2): the coated surface's compliance over the film half-space's."""
    return 1 + surface_deviation(u, c)


def surface_deviation(u, c: Coating):
    """D(u) = C(u) - 1 = e^{-2u} (A + B + 4 B u + 4 B u^2 - 2 A B e^{-2u}) / denominator of (2),
    without the cancellation of C - 1 at large u."""
    A, B = layer_coefficients(c)
    u = np.asarray(u, dtype=float)
    e = np.exp(-2 * u)
    den = 1 - (A + B + 4 * B * u * u) * e + A * B * e * e
    return e * (A + B + 4 * B * u * (1 + u) - 2 * A * B * e) / den


def _navier_matrix(nu: float) -> np.ndarray:
    """d/dz' [U, W, tau, sigma] for u_r = U J1(kr), u_z = W J0(kr), sigma_rz = G k tau J1(kr),
    sigma_zz = G k sigma J0(kr), z' = k z into the body (Navier's equations in Hankel space)."""
    return np.array([[0.0, 1.0, 1.0, 0.0],
                     [-nu / (1 - nu), 0.0, 0.0, (1 - 2 * nu) / (2 * (1 - nu))],
                     [2 / (1 - nu), 0.0, 0.0, nu / (1 - nu)],
                     [0.0, 0.0, -1.0, 0.0]])


def surface_factor_by_propagator(u: float, c: Coating) -> float:
    """C(u) again, by a second route: the film's propagator expm(P u) from a traction-free,
    unit-pressure surface, continuity of U, W, G tau, G sigma into the substrate's decaying
    solutions (null space of (P + I)^2), or U = W = 0 on a rigid base. For checking (2); loses
    digits as e^{2u}, so for u up to ~10."""
    from scipy.linalg import expm, null_space
    prop = expm(_navier_matrix(c.nu1) * u)
    sigma0 = -1.0  # sigma_zz = -p at the surface, tau = 0 there
    if c.rigid_base:
        U0, W0 = np.linalg.solve(prop[:2, :2], -prop[:2, 3] * sigma0)
    else:
        decaying = null_space(np.linalg.matrix_power(_navier_matrix(c.nu2) + np.eye(4), 2))
        s1, s2 = np.diag([1, 1, c.G1, c.G1]), np.diag([1, 1, c.G2, c.G2])
        lhs = np.column_stack([s1 @ prop[:, 0], s1 @ prop[:, 1], -s2 @ decaying[:, 0], -s2 @ decaying[:, 1]])
        U0, W0, _, _ = np.linalg.solve(lhs, -s1 @ prop[:, 3] * sigma0)
    # film half-space: W = 2 p~/(E1* k) = (1 - nu1) p~/(G1 k), and p~ = -G1 k sigma0
    return float(W0 / ((1 - c.nu1) * -sigma0))


# --- 2./3. the integral equation -----------------------------------------------------------------


@dataclass(frozen=True)
class Resolution:
    """Quadrature of eq. (3); the defaults reach about 1e-8 (module docstring, part 3)."""
    nodes_per_eps: float = 8.0  # Gauss nodes on [-1, 1] per unit of a/t
    min_nodes: int = 32
    q_panel: float = 4.0  # longest panel in q = k a
    u_panel: float = 0.5  # longest panel in u = k t
    u_max: float = 20.0  # truncation of D (|D| < 1e-14 beyond)
    u_floor: float = 1e-3  # grading towards u = 0 down to u_floor * min(1, G2/G1)
    order: int = 16  # Gauss nodes per panel
    max_nodes: int = 2000  # t/a >= 0.004

    def doubled(self) -> Resolution:
        return Resolution(2 * self.nodes_per_eps, 2 * self.min_nodes, self.q_panel / 2, self.u_panel / 2,
                          self.u_max + 4, self.u_floor / 8, self.order, 2 * self.max_nodes)


DEFAULT = Resolution()


def _q_rule(c: Coating, eps: float, res: Resolution) -> tuple[np.ndarray, np.ndarray]:
    """Nodes and weights in q on [0, u_max/eps]: geometric panels towards 0, then panels of at most
    u_panel in u and q_panel in q."""
    floor = res.u_floor * (1.0 if c.rigid_base else min(1.0, c.G2 / c.G1))
    levels = max(0, math.ceil(math.log2(res.u_panel / floor)))
    edges_u = [0.0] + [res.u_panel * 2.0**-j for j in range(levels, 0, -1)]
    edges_u += [res.u_panel * j for j in range(1, math.ceil(res.u_max / res.u_panel) + 1)]
    edges: list[float] = []
    for lo, hi in zip(edges_u[:-1], edges_u[1:]):
        n = max(1, math.ceil((hi - lo) / eps / res.q_panel))
        edges.extend(np.linspace(lo / eps, hi / eps, n + 1)[:-1])
    edges.append(edges_u[-1] / eps)
    e = np.asarray(edges)
    xg, wg = leggauss(res.order)
    mid, half = 0.5 * (e[1:] + e[:-1]), 0.5 * (e[1:] - e[:-1])
    return (mid[:, None] + half[:, None] * xg).ravel(), (half[:, None] * wg).ravel()


@dataclass(frozen=True)
class UnitSolution:
    """psi, chi of part 2 for eps = t/a: at the Gauss nodes x (weights w of int_0^1), at x = 1, and
    their cosine transforms on the q rule (wd = weight * D(q eps)) for derivatives."""
    eps: float
    x: np.ndarray
    w: np.ndarray
    psi: np.ndarray
    chi: np.ndarray
    psi_edge: float
    chi_edge: float
    q: np.ndarray
    wd: np.ndarray
    psi_hat: np.ndarray
    chi_hat: np.ndarray

    @property
    def Psi(self) -> float:
        """int_0^1 psi = E_eff*/E1*."""
        return float(self.w @ self.psi)

    @property
    def X(self) -> float:
        return float(self.w @ self.chi)

    @property
    def depth_ratio(self) -> float:
        """d R / a^2 of the sphere."""
        return self.chi_edge / self.psi_edge

    @property
    def force_ratio(self) -> float:
        """F R / (E1* a^3) of the sphere."""
        return 2 * (self.depth_ratio * self.Psi - self.X)

    def derivatives(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """psi'(x), chi'(x) from the equations: psi' = (2/pi) int D q sin(qx) psi^(q) dq."""
        s = np.sin(np.outer(x, self.q)) * (self.wd * self.q)
        return (2 / np.pi) * (s @ self.psi_hat), 2 * x + (2 / np.pi) * (s @ self.chi_hat)


@functools.lru_cache(maxsize=32)
def _half_gauss(n: int) -> tuple[np.ndarray, np.ndarray]:
    """The positive half of the n-point Gauss-Legendre rule of [-1, 1] (n even): int_0^1 of even functions."""
    xg, wg = leggauss(n)
    return xg[n // 2:], wg[n // 2:]


@functools.lru_cache(maxsize=512)
def solve_unit(c: Coating, eps: float, res: Resolution = DEFAULT) -> UnitSolution:
    """Nystrom solution of psi + K^ psi = 1, chi + K^ chi = x^2 on [0, 1] (part 2)."""
    n = 2 * math.ceil(max(res.min_nodes, res.nodes_per_eps / eps) / 2)
    if n > res.max_nodes:
        raise ValueError(f"t/a = {eps:g} needs {n} nodes, more than {res.max_nodes}: film too thin for this method")
    x, w = _half_gauss(n)
    q, wq = _q_rule(c, eps, res)
    wd = wq * surface_deviation(q * eps, c)
    cos = np.cos(np.outer(q, np.append(x, 1.0)))
    kernel = (2 / np.pi) * ((cos * wd[:, None]).T @ cos)  # K^(x_i, x_j), last row x = 1
    system = np.eye(n // 2) + kernel[:-1, :-1] * w
    sol = np.linalg.solve(system, np.column_stack([np.ones_like(x), x * x]))
    edge = np.array([1.0, 1.0]) - (kernel[-1, :-1] * w) @ sol
    hat = cos[:, :-1] @ (w[:, None] * sol)
    return UnitSolution(eps, x, w, sol[:, 0], sol[:, 1], float(edge[0]), float(edge[1]), q, wd, hat[:, 0], hat[:, 1])


def effective_modulus(c: Coating, a: float, res: Resolution = DEFAULT) -> float:
    """E_eff* of a flat punch of radius a: its stiffness is S = 2 E_eff* a."""
    return c.E1s * solve_unit(c, c.t / a, res).Psi


@dataclass(frozen=True)
class Contact:
    """Contact radius a, depth d, force F and unloading stiffness S = dF/dd = 2 E_eff*(a) a."""
    a: float
    d: float
    F: float
    S: float


def punch(c: Coating, a: float, d: float, res: Resolution = DEFAULT) -> Contact:
    """Flat punch of radius a pressed to depth d: F = 2 E_eff* a d."""
    S = 2 * effective_modulus(c, a, res) * a
    return Contact(a, d, S * d, S)


def punch_edge_coefficient(c: Coating, a: float, d: float, res: Resolution = DEFAULT) -> float:
    """K = lim p sqrt(a - r) of a flat punch of radius a at depth d: the pressure's singular part is
    g(a)/sqrt(a^2 - r^2) (part 2) with g(a) = (E1*/pi) d psi(1), so K = g(a)/sqrt(2a)."""
    return c.E1s * d * solve_unit(c, c.t / a, res).psi_edge / (math.pi * math.sqrt(2 * a))


def sphere(c: Coating, R: float, a: float, res: Resolution = DEFAULT) -> Contact:
    """Parabolic indenter z = r^2/(2R) with contact radius a (smooth edge, p(a) = 0)."""
    u = solve_unit(c, c.t / a, res)
    return Contact(a, u.depth_ratio * a * a / R, u.force_ratio * c.E1s * a**3 / R, 2 * c.E1s * u.Psi * a)


def _radius_where(f, target: float, guess: float, power: float) -> float:
    """The a > 0 where f(a) = target, f increasing and about a power law (f ~ a^power near guess):
    secant steps in ln f(ln a), each overshooting by 10%, until the root is bracketed, then brentq.
    Few evaluations, and none far above the root (thin films, a >> t, are the costly ones)."""
    from scipy.optimize import brentq
    x0, g0 = math.log(guess), math.log(f(guess) / target)
    slope = power
    for _ in range(100):
        if abs(g0) < 1e-14:  # at the root to rounding (a step would not move x)
            return math.exp(x0)
        x1 = x0 - 1.1 * g0 / slope
        x1 = min(max(x1, x0 - 2.0), x0 + 2.0)  # at most a factor e^2 per step
        g1 = math.log(f(math.exp(x1)) / target)
        if g0 * g1 <= 0:
            lo, hi = sorted((x0, x1))
            return math.exp(brentq(lambda x: math.log(f(math.exp(x)) / target), lo, hi, xtol=1e-12, rtol=1e-13))
        if (g1 - g0) / (x1 - x0) > 0.1:
            slope = (g1 - g0) / (x1 - x0)
        x0, g0 = x1, g1
    raise RuntimeError(f"no contact radius found for {target}")


def _guesses(c: Coating, R: float) -> list:
    """Contact radius a(F) of the limiting bodies: the film's half-space, the substrate's, or the thin layer
    on a rigid base (Winkler, incompressible)."""
    film = [lambda F: (3 * F * R / (4 * c.E1s)) ** (1 / 3)]
    if not c.rigid_base:
        return film + [lambda F: (3 * F * R / (4 * c.E2s)) ** (1 / 3)]
    if c.nu1 < 0.5:
        film.append(lambda F: (4 * R * c.t * F / (math.pi * c.M1)) ** 0.25)
    return film + [lambda F: (32 * R * c.t**3 * F / (math.pi * c.G1)) ** (1 / 6)]


def sphere_from_load(c: Coating, R: float, F: float, res: Resolution = DEFAULT) -> Contact:
    """The sphere under load F (a and d from F(a) = F): about ten evaluations of sphere()."""
    guess = min(g(F) for g in _guesses(c, R))
    a = _radius_where(lambda a: sphere(c, R, a, res).F, F, guess, 3.0)
    return sphere(c, R, a, res)


def sphere_from_depth(c: Coating, R: float, d: float, res: Resolution = DEFAULT) -> Contact:
    """The sphere at depth d (a and F from d(a) = d): about ten evaluations of sphere()."""
    a = _radius_where(lambda a: sphere(c, R, a, res).d, d, math.sqrt(R * d), 2.0)
    return sphere(c, R, a, res)


def sphere_pressure(c: Coating, R: float, a: float, r, res: Resolution = DEFAULT, n_abel: int | None = None):
    """Pressure p(r) under the sphere of contact radius a (0 outside), part 2:
    p = -(E1*/(pi a)) int_0^{sqrt(1 - rho^2)} gamma'(x)/x dv, x^2 = rho^2 + v^2."""
    u = solve_unit(c, c.t / a, res)
    d_hat = u.depth_ratio  # d = d_hat a^2/R; gamma = (a^2/R)(d_hat psi - chi)
    rho = np.atleast_1d(np.asarray(r, dtype=float)) / a
    n_abel = n_abel or max(64, len(u.x))
    vg, wv = leggauss(n_abel)
    p = np.zeros_like(rho)
    for i, rh in enumerate(rho):
        if rh >= 1:
            continue
        top = math.sqrt(1 - rh * rh)
        v, wvi = 0.5 * top * (vg + 1), 0.5 * top * wv
        x = np.sqrt(rh * rh + v * v)
        dpsi, dchi = u.derivatives(x)
        p[i] = -(c.E1s / (math.pi * a)) * (a * a / R) * (wvi @ ((d_hat * dpsi - dchi) / x))
    return p if np.ndim(r) else float(p[0])


@dataclass(frozen=True)
class ErrorEstimate:
    """Relative changes on doubling every count: punch F, sphere F and sphere d."""
    punch_F: float
    sphere_F: float
    sphere_d: float

    @property
    def F(self) -> float:
        return max(self.punch_F, self.sphere_F)


def error_estimate(c: Coating, a: float, res: Resolution = DEFAULT) -> ErrorEstimate:
    """Estimated relative error of the results at resolution res: their change with res.doubled()."""
    u, v = solve_unit(c, c.t / a, res), solve_unit(c, c.t / a, res.doubled())
    return ErrorEstimate(abs(u.Psi / v.Psi - 1), abs(u.force_ratio / v.force_ratio - 1),
                         abs(u.depth_ratio / v.depth_ratio - 1))


# --- 4. other references and limits --------------------------------------------------------------


def gao_weights(xi: float, nu: float) -> tuple[float, float]:
    """Gao, Chiu & Lee (1992) weights of xi = t/a:
    I0 = (2/pi) atan(xi) + [(1 - 2 nu) xi ln((1 + xi^2)/xi^2) - xi/(1 + xi^2)] / (2 pi (1 - nu)),
    I1 = (2/pi) atan(xi) + (xi/pi) ln((1 + xi^2)/xi^2); both go from 0 (xi = 0) to 1 (xi = inf)."""
    log = xi * math.log1p(1 / (xi * xi))
    base = 2 / math.pi * math.atan(xi)
    I0 = base + ((1 - 2 * nu) * log - xi / (1 + xi * xi)) / (2 * math.pi * (1 - nu))
    return I0, base + log / math.pi


def gao_effective_modulus(c: Coating, a: float) -> float:
    """Gao et al.'s E_eff* = 2 G/(1 - nu) of a flat punch on a film/substrate:
    G = G2 + (G1 - G2) I0,   1/(1 - nu) = I1/(1 - nu1) + (1 - I1)/(1 - nu2),
    I0 taken with that nu. A first-order perturbation in the mismatch: good for E2/E1 near 1."""
    if c.rigid_base:
        raise ValueError("Gao et al.'s perturbation needs an elastic substrate")
    xi = c.t / a
    _, I1 = gao_weights(xi, 0.0)
    nu = 1 - 1 / (I1 / (1 - c.nu1) + (1 - I1) / (1 - c.nu2))
    I0, _ = gao_weights(xi, nu)
    return 2 * (c.G2 + (c.G1 - c.G2) * I0) / (1 - nu)


@functools.lru_cache(maxsize=64)
def deviation_integral(c: Coating) -> float:
    """int_0^inf D(u) du by adaptive quadrature (scipy quad, independent of the panel rule)."""
    from scipy.integrate import quad
    floor = 1e-3 * (1.0 if c.rigid_base else min(1.0, c.G2 / c.G1))
    pieces = [(0, floor), (floor, 1e-1), (1e-1, 2), (2, 40)]
    return sum(quad(lambda u: float(surface_deviation(u, c)), lo, hi, epsabs=1e-15, epsrel=1e-13, limit=200)[0]
               for lo, hi in pieces)


def thick_film_asymptote(c: Coating, R: float, a: float) -> Contact:
    """t >> a: K^ = K1 + O((a/t)^3), K1 = (2a/(pi t)) int D: E_eff* = E1*/(1 + K1),
    sphere d = (a^2/R)(1 + 2 K1/3), F = 4/3 E1* a^3/R (the substrate moves the contact rigidly)."""
    K1 = 2 * a / (math.pi * c.t) * deviation_integral(c)
    return Contact(a, a * a / R * (1 + 2 * K1 / 3), 4 / 3 * c.E1s * a**3 / R, 2 * c.E1s * a / (1 + K1))


def winkler_modulus(c: Coating, a: float) -> float:
    """Thin compressible layer on a rigid base (Johnson 5.9): p = M d/t under a punch, E_eff* = pi M a/(2t)."""
    return math.pi * c.M1 * a / (2 * c.t)


def winkler_sphere(c: Coating, R: float, a: float) -> Contact:
    """Thin compressible layer on a rigid base: p = (M/t)(d - r^2/(2R)), a^2 = 2 R d, F = pi M a^4/(4 R t)."""
    return Contact(a, a * a / (2 * R), math.pi * c.M1 * a**4 / (4 * R * c.t), 2 * winkler_modulus(c, a) * a)


def incompressible_layer_modulus(c: Coating, a: float) -> float:
    """Thin incompressible layer on a rigid base, frictionless top: p = 3 G1 d (a^2 - r^2)/(4 t^3) under a
    punch (Laplacian p = -3 G1 u / t^3, p(a) = 0), E_eff* = 3 pi G1 a^3/(16 t^3)."""
    return 3 * math.pi * c.G1 * a**3 / (16 * c.t**3)


def incompressible_layer_sphere(c: Coating, R: float, a: float) -> Contact:
    """The same under a sphere (p(a) = p'(a) = 0): p = 3 G1 (a^2 - r^2)^2/(32 R t^3), a^2 = 4 R d,
    F = pi G1 a^6/(32 R t^3) (the a^6/t^3 law of Johnson 5.9)."""
    return Contact(a, a * a / (4 * R), math.pi * c.G1 * a**6 / (32 * R * c.t**3),
                   2 * incompressible_layer_modulus(c, a) * a)
