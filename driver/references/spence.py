"""Frictional indentation of an elastic half-plane by a rigid cylinder, by a
boundary-element method of its own: the reference for the stick zone of
Spence's problem (plane strain, monotone loading), and along any sequence of
loads (unloading too), that the tests and the friction chart compare with,
apart from the solver.

The surface is cut into cells of constant pressure p and shear q. Their
surface displacements come from the half-plane's line-load solutions
(Johnson, Contact Mechanics, eqs. 2.19 and 2.25; u_z positive into the
body, q positive along +x):
    u_x = -(1 - 2nu)(1 + nu)/(2E) int p sgn(x - s) ds - 2(1 - nu^2)/(pi E) int q ln|x - s| ds
    u_z = -2(1 - nu^2)/(pi E) int p ln|x - s| ds + (1 - 2nu)(1 + nu)/(2E) int q sgn(x - s) ds
Each load step is solved by an active set on the contact cells (p > 0, no
penetration) and on their stick cells (no change of u_x in the step, and
|q| <= mu p) against the slip cells (q = mu p times the slip's direction,
against the slide: under loading the surface slides toward the axis and q =
mu p sgn(x); under unloading it may slide back).
"""
from __future__ import annotations

import numpy as np


def mossakovskii(nu):
    """Full stick's contact stiffness over 2 E* a, any axisymmetric indenter
    (Mossakovskii; Borodich and Keer 2004): (1 - nu) ln(3 - 4 nu)/(1 - 2 nu), 1 at nu = 1/2."""
    nu = np.asarray(nu, dtype=float)
    safe = np.minimum(nu, 0.4999)
    return np.where(np.isclose(nu, 0.5), 1.0, (1 - safe) * np.log(3 - 4 * safe) / (1 - 2 * safe))


def rigid_beta(nu):
    """Dundurs' beta in magnitude for a rigid indenter on a body of Poisson's ratio nu."""
    return (1 - 2 * np.asarray(nu, dtype=float)) / (2 * (1 - np.asarray(nu, dtype=float)))


def dundurs_beta(E1: float, nu1: float, E2: float, nu2: float) -> float:
    """Dundurs' beta of an indenter (E1, nu1; E1 = inf: rigid) on a body (E2, nu2), plane
    strain: [G1 (k2 - 1) - G2 (k1 - 1)]/[G1 (k2 + 1) + G2 (k1 + 1)] with k = 3 - 4 nu;
    0 for identical bodies, rigid_beta(nu2) for a rigid indenter."""
    if not np.isfinite(E1):
        return float(rigid_beta(nu2))
    g1, g2 = E1 / (2 * (1 + nu1)), E2 / (2 * (1 + nu2))
    k1, k2 = 3 - 4 * nu1, 3 - 4 * nu2
    return (g1 * (k2 - 1) - g2 * (k1 - 1)) / (g1 * (k2 + 1) + g2 * (k1 + 1))


def equivalent_rigid(E1: float, nu1: float, E2: float, nu2: float) -> tuple[float, float]:
    """(E, nu) of a body under a rigid indenter whose surfaces' relative displacements
    equal those of two elastic half-planes: the same 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2
    for p and q, and the same beta for their coupling (plane strain, where the normal and
    the tangential kernels share E*), so that spence_path solves two bodies."""
    beta = dundurs_beta(E1, nu1, E2, nu2)
    nu = (1 - 2 * beta) / (2 - 2 * beta)
    inv = (1 - nu2**2) / E2 + ((1 - nu1**2) / E1 if np.isfinite(E1) else 0.0)
    return (1 - nu**2) / inv, nu


def _ln_integral(t: np.ndarray) -> np.ndarray:
    """int ln|t| dt = t ln|t| - t (0 at t = 0)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(t == 0, 0.0, t * np.log(np.abs(t)) - t)


def influence(x: np.ndarray, h: float, E: float, nu: float):
    """Matrices of u_x and u_z at the cell centres x per unit p and q of each cell."""
    d = x[:, None] - x[None, :]
    ln = _ln_integral(d + h / 2) - _ln_integral(d - h / 2)   # int over the cell of ln|x - s| ds
    sg = np.clip(d + h / 2, 0, h) - np.clip(h / 2 - d, 0, h)   # int over the cell of sgn(x - s) ds
    c_ln = 2 * (1 - nu**2) / (np.pi * E)
    c_sg = (1 - 2 * nu) * (1 + nu) / (2 * E)
    return {"xp": -c_sg * sg, "xq": -c_ln * ln, "zp": -c_ln * ln, "zq": c_sg * sg}


def spence_path(mu: float, nu: float, loads, cells: int = 600, E: float = 1.0, R: float = 1.0,
                X: float | None = None, tangential=None) -> list[dict]:
    """The state after each load (per unit length) of the sequence `loads`,
    each step solved from the one before: a list of dicts with a, c, the
    stick zone's middle, the indenter's move along x (dt, from the state of
    the first step) and the cells' p, q and x. Loads may rise and fall
    (unloading); tangential, beside them, is the force along x on the body
    (0 unless given), which the indenter's move along x settles. X is the
    half-width of the meshed surface (1.25 times the largest load's Hertz
    half-width unless given)."""
    loads = np.asarray(loads, dtype=float)
    forces = np.zeros_like(loads) if tangential is None else np.asarray(tangential, dtype=float)
    Estar = E / (1 - nu**2)
    a_peak = np.sqrt(4 * loads.max() * R / (np.pi * Estar))
    X = 1.25 * a_peak if X is None else X
    h = 2 * X / cells
    x = -X + h * (np.arange(cells) + 0.5)
    G = influence(x, h, E, nu)
    sgn = np.sign(x)
    ux_before = np.zeros(cells)
    a_first = np.sqrt(4 * loads[0] * R / (np.pi * Estar))
    contact = np.abs(x) < 0.5 * a_first + h
    stick = contact.copy()
    # the direction of a slip cell's shear: the surface slides against it
    # (toward the axis under loading, q = mu p sgn(x); away under unloading)
    direction = sgn.copy()
    states = []
    shift = 0.0   # the indenter's move along x
    for P, Q in zip(loads, forces):
        for _ in range(200):
            C, S = np.flatnonzero(contact), np.flatnonzero(stick & contact)
            L = np.flatnonzero(contact & ~stick)
            nC, nS = len(C), len(S)
            # unknowns: p on C, q on S, the approach d, and the step's move along x
            n = nC + nS + 2
            A = np.zeros((n, n))
            b = np.zeros(n)
            # slip cells' shear follows their pressure: q = slip p on L, at their columns of p
            slip = mu * direction[L]
            at = np.searchsorted(C, L)   # (C is sorted: flatnonzero)
            # u_z(x_i) - d = -x_i^2/(2R) on C (the indenter's surface, d deep)
            A[:nC, :nC] = G["zp"][np.ix_(C, C)]
            A[:nC, at] += G["zq"][np.ix_(C, L)] * slip
            A[:nC, nC:nC + nS] = G["zq"][np.ix_(C, S)]
            A[:nC, -2] = -1
            b[:nC] = -x[C] ** 2 / (2 * R)
            # u_x(x_i) = its value before the step plus the indenter's move, on S
            A[nC:nC + nS, :nC] = G["xp"][np.ix_(S, C)]
            A[nC:nC + nS, at] += G["xq"][np.ix_(S, L)] * slip
            A[nC:nC + nS, nC:nC + nS] = G["xq"][np.ix_(S, S)]
            A[nC:nC + nS, -1] = -1
            b[nC:nC + nS] = ux_before[S]
            # the load, and the force along x (q on the slip cells follows p)
            A[-2, :nC] = h
            b[-2] = P
            A[-1, :nC] = 0
            A[-1, at] = h * slip
            A[-1, nC:nC + nS] = h
            b[-1] = Q
            if nS == 0:   # nothing sticks: the move is not defined, and the force is the slip's
                A[-1, :] = 0
                A[-1, -1] = 1
                b[-1] = 0
            sol = np.linalg.solve(A, b)
            p = np.zeros(cells)
            p[C] = sol[:nC]
            q = np.zeros(cells)
            q[L] = slip * sol[at]
            q[S] = sol[nC:nC + nS]
            d, step_shift = sol[-2], sol[-1]
            uz = G["zp"] @ p + G["zq"] @ q
            ux = G["xp"] @ p + G["xq"] @ q
            new_contact = contact & (p >= 0) | (~contact & (uz - d < -x**2 / (2 * R)))
            ok = np.abs(q) <= mu * p + 1e-14
            # a slip cell that moved with its shear sticks; a stick cell past
            # the cone slips against its shear
            moved = (ux - ux_before - step_shift) * direction
            new_stick = new_contact & ((stick & ok) | (~stick & (moved > 0)))
            new_direction = np.where(stick & ~ok, np.sign(q), direction)
            if np.array_equal(new_contact, contact) and np.array_equal(new_stick, stick & contact) \
                    and np.array_equal(new_direction, direction):
                break
            contact, stick, direction = new_contact, new_stick, new_direction
        ux_before = ux
        shift += step_shift
        # cells that leave the contact forget their direction: one that
        # touches again slides toward the axis first, as under loading
        direction = np.where(contact, direction, sgn)
        # the stick zone: the longest run of stick cells (around the axis
        # under normal loading), its half-width c and its middle
        held = np.concatenate([[0], (stick & contact).astype(int), [0]])
        starts, ends = np.flatnonzero(np.diff(held) == 1), np.flatnonzero(np.diff(held) == -1)
        if len(starts):
            k = int(np.argmax(ends - starts))
            c, middle = (ends[k] - starts[k]) * h / 2, float(x[starts[k]] + x[ends[k] - 1]) / 2
        else:
            c, middle = 0.0, float("nan")
        a = float((x[contact].max() - x[contact].min() + h) / 2)
        states.append({"P": float(P), "Q": float(Q), "a": a, "c": c, "c_over_a": c / a, "middle": middle,
                       "d": float(d), "dt": shift, "p": p, "q": q, "x": x})
    return states


def spence_plane(mu: float, nu: float, steps: int = 80, cells: int = 600, E: float = 1.0, R: float = 1.0,
                 load: float = 1e-3) -> dict:
    """c/a and a after monotone loading to `load` (per unit length) in `steps`
    steps of equal growth of the contact half-width."""
    Estar = E / (1 - nu**2)
    a_final = np.sqrt(4 * load * R / (np.pi * Estar))
    loads = load * (np.arange(1, steps + 1) / steps) ** 2
    last = spence_path(mu, nu, loads, cells, E, R)[-1]
    return {**last, "a_hertz": a_final}
