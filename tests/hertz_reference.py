"""Hertz theory written again, independently of edp/lib/hertz.idp, for the tests (HERTZ.md)."""
from __future__ import annotations

import math
from dataclasses import dataclass


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


def cylinder_half_width(P: float, E: float, nu: float, R: float) -> float:
    return math.sqrt(4 * P * R / (math.pi * estar(E, nu)))


def cylinder_pressure(P: float, E: float, nu: float, R: float) -> float:
    return 2 * P / (math.pi * cylinder_half_width(P, E, nu, R))


SEED = dict(E=10.0, nu=0.3, R=0.5, d=0.02)
