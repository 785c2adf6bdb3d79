"""Adhesion of a rigid parabola of radius R on an elastic half-space (contact
modulus E*, work of adhesion w): Maugis and Dugdale's exact solution, with
JKR's and DMT's limits, that the tests and the adhesion chart compare with,
apart from the solver.

Maugis (J. Colloid Interface Sci. 150 (1992) 243): a Dugdale traction sigma0
acts between the contact radius a and the neck c, out to a separation
w/sigma0. With K = 4E*/3, lambda = 2 sigma0 (R/(pi w K^2))^(1/3), and the
units A = a (K/(pi w R^2))^(1/3), P/(pi w R), d (K^2/(pi^2 w^2 R))^(1/3),
m = c/a, the curve is, for each A, with m the root of
    (lambda A^2/2)[s + (m^2 - 2) t] + (4 lambda^2 A/3)[s t - m + 1] = 1,
    s = sqrt(m^2 - 1), t = atan(s):
    P = A^3 - lambda A^2 (s + m^2 t),    d = A^2 - (4/3) A lambda s.
Pure numpy (the driver's own dependencies): m by bisection, vectorized.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

PI = np.pi


def tabor(estar: float, R: float, w: float, sigma0: float) -> float:
    """Maugis's (Tabor's) parameter lambda = 2 sigma0 (R/(pi w K^2))^(1/3), K = 4E*/3."""
    K = 4 * estar / 3
    return 2 * sigma0 * (R / (PI * w * K**2)) ** (1 / 3)


def jkr_radius(P, estar: float, R: float, w: float):
    """JKR's contact radius under the load P (stable branch)."""
    P = np.asarray(P, dtype=float)
    g = 3 * PI * w * R
    return (3 * R / (4 * estar) * (P + g + np.sqrt(np.maximum(2 * g * P + g**2, 0)))) ** (1 / 3)


def jkr_depth(a, estar: float, R: float, w: float):
    """JKR's depth at the contact radius a: a^2/R - sqrt(2 pi w a/E*)."""
    a = np.asarray(a, dtype=float)
    return a**2 / R - np.sqrt(2 * PI * w * a / estar)


def jkr_zero_load_radius(estar: float, R: float, w: float) -> float:
    """a0^3 = 9 pi w R^2/(2 E*)."""
    return (9 * PI * w * R**2 / (2 * estar)) ** (1 / 3)


def dmt_force(d, estar: float, R: float, w: float):
    """DMT: Hertz's force at the depth d, less 2 pi w R."""
    d = np.asarray(d, dtype=float)
    return 4 / 3 * estar * np.sqrt(R) * np.maximum(d, 0) ** 1.5 - 2 * PI * w * R


@dataclass(frozen=True)
class Maugis:
    """The Maugis-Dugdale curve of one scene."""
    estar: float
    R: float
    w: float
    sigma0: float

    @property
    def lam(self) -> float:
        return tabor(self.estar, self.R, self.w, self.sigma0)

    @property
    def units(self) -> tuple[float, float, float]:
        """(length, force, depth): the units of A, P and d."""
        K = 4 * self.estar / 3
        return ((PI * self.w * self.R**2 / K) ** (1 / 3), PI * self.w * self.R,
                (PI**2 * self.w**2 * self.R / K**2) ** (1 / 3))

    def ratio(self, A):
        """m = c/a for each A (> 0), by bisection on (1, m_hi)."""
        A = np.atleast_1d(np.asarray(A, dtype=float))
        lam = self.lam

        def lhs(m):
            s = np.sqrt(m * m - 1)
            t = np.arctan(s)
            return lam * A * A / 2 * (s + (m * m - 2) * t) + 4 * lam**2 * A / 3 * (s * t - m + 1) - 1

        lo = np.ones_like(A)
        hi = np.full_like(A, 2.0)
        for _ in range(200):          # the left side grows with m: widen until it is positive
            grow = lhs(hi) < 0
            if not grow.any():
                break
            hi = np.where(grow, 2 * hi, hi)
        for _ in range(64):           # (2^-64 of the bracket: below rounding)
            mid = 0.5 * (lo + hi)
            below = lhs(mid) < 0
            lo = np.where(below, mid, lo)
            hi = np.where(below, hi, mid)
        return 0.5 * (lo + hi)

    def states(self, a):
        """The states at contact radii a: dict of arrays a, c, P, d."""
        La, Pu, Du = self.units
        A = np.atleast_1d(np.asarray(a, dtype=float)) / La
        m = self.ratio(A)
        s = np.sqrt(m * m - 1)
        t = np.arctan(s)
        P = A**3 - self.lam * A * A * (s + m * m * t)
        d = A * A - 4 / 3 * A * self.lam * s
        return {"a": A * La, "c": m * A * La, "P": P * Pu, "d": d * Du}

    def curve(self, a_max: float, n: int = 400):
        """The curve from a small contact to a_max (geometric in a)."""
        La = self.units[0]
        return self.states(np.geomspace(1e-4 * La, a_max, n))

    def _root(self, key: str, value: float, lo: float, hi: float) -> dict:
        """The state on [lo, hi] in a (the stable side) where key equals value: bisection."""
        f = lambda a: self.states(a)[key][0] - value  # noqa: E731
        flo = f(lo)
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            fm = f(mid)
            if (fm > 0) == (flo > 0):
                lo, flo = mid, fm
            else:
                hi = mid
        return {k: v[0] for k, v in self.states(0.5 * (lo + hi)).items()}

    def _stable(self, key: str, value: float) -> dict:
        """The stable state where key ('d' or 'P') equals value: on the curve's side past
        the least of key (the largest contact with that value), by bisection."""
        La = self.units[0]
        a = np.geomspace(1e-4 * La, 20 * La, 2000)
        lo = float(a[np.argmin(self.states(a)[key])])
        hi = 2 * lo
        while self.states(hi)[key][0] < value:
            hi *= 2
        return self._root(key, value, lo, hi)

    def at_depth(self, d: float) -> dict:
        """The stable state at the depth d."""
        return self._stable("d", d)

    def at_load(self, P: float) -> dict:
        """The stable state under the load P."""
        return self._stable("P", P)

    def zero_load(self) -> dict:
        return self.at_load(0.0)

    def pulloff(self, control: str) -> dict:
        """The pull-off: the least load (control 'load') or the state at the least depth
        ('depth'), by golden section about the least of a dense sample; a least at the
        smallest contact (a curve that falls all the way to a = 0) is that end,
        flagged 'at_end'."""
        key = "P" if control == "load" else "d"
        La = self.units[0]
        a = np.geomspace(1e-4 * La, 20 * La, 2000)
        values = self.states(a)[key]
        i = int(np.argmin(values))
        if i == 0:
            return {**{k: v[0] for k, v in self.states(a[0]).items()}, "at_end": True}
        lo, hi = a[i - 1], a[min(i + 1, len(a) - 1)]
        g = (np.sqrt(5) - 1) / 2
        for _ in range(70):           # (0.618^70 of the bracket: below rounding)
            x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
            v1, v2 = self.states(np.array([x1, x2]))[key]
            if v1 < v2:
                hi = x2
            else:
                lo = x1
        return {**{k: v[0] for k, v in self.states(0.5 * (lo + hi)).items()}, "at_end": False}
