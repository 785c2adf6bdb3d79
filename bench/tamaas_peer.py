#!/usr/bin/env python3
"""Hertz contact (rigid paraboloid on an elastic half-space, depth imposed) in
Tamaas (FFT boundary elements, https://tamaas.readthedocs.io): the peer of
edp/hertz.edp for side-by-side timing.

Install (driver/setup.sh --peers does this), see install_hint():
    python3 -m venv .venv-peers && .venv-peers/bin/pip install "tamaas>=2.9" numpy
Run with that environment's python:
    .venv-peers/bin/python bench/tamaas_peer.py [--N 256] [--L 16] [--operator periodic|dcfft] [--tol 1e-12]
Prints one JSON line. Importable without Tamaas: run(N, L, operator, tol) -> dict
imports it; the scene, the depth update and the edge fit need numpy alone.

The surface is an N x N grid of side L a, the paraboloid's apex on the grid
point at its centre (tamaas.utils.hertz_surface). Tamaas solves for the
pressures at the grid points (Polonsky-Keer-Rey, conjugate gradients on the
pressures), for an imposed mean pressure W / L^2. The depth is imposed by
adjusting W (see solve_depth) until the apex's approach is d to DEPTH_TOL:
the imposed-mean-gap mode (primal and constraint on the gap) gives the same
solution in the periodic case but is 10 to 30 times slower.

Two integral operators, the two Tamaas offers for elastic normal contact:
- periodic (default): Westergaard's, a square array of indenters with period
  L a. A periodic surface has no far field, so the depth is the apex's approach
  relative to the mean plane of the deformed surface (Tamaas' mean gap is
  measured from it). The neighbours' pressure pushes that plane down, about
  -3.9 F / (pi E* L a) for a square array: an isolated indenter at depth d
  meets fewer than its periodic twin, so the imposed mean-plane depth d buys a
  larger contact than Hertz's. The bias falls off as a/L only: err_p0 and
  err_a near +0.8 a/L... (measured: about +6% at L = 16 a, +3% at 32 a).
- dcfft: Tamaas' documented non-periodic Boussinesq operator (DC-FFT, zero
  padding to 2N), an isolated indenter on an infinite half-space. The solver
  shifts the displacement (the gap is zero in contact); the absolute one is
  recovered post-solve with model.operators['dcfft'], as Tamaas documents, and
  the depth is the apex's absolute displacement. The grid needs only to cover
  the contact (L = 4 a by default for it).
"""
import time

T_START = time.perf_counter()  # wall_time_total counts the imports too

import argparse  # noqa: E402
import contextlib  # noqa: E402
import math  # noqa: E402
import os  # noqa: E402
import re  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402

import numpy as np  # noqa: E402
from seed_scene import A_H, F_H, NU, P0_H, D, E, R, finish  # noqa: E402  (the seed scene, beside this script)

OPERATORS = ("periodic", "dcfft")
DEPTH_TOL = 1e-7     # relative: the depth's own error is then < 1e-7 in p0 and a, < 2e-7 in F
MAX_LOAD_STEPS = 30
EDGE_FIT_FLOOR = 0.3  # the edge fit uses the points with p > 0.3 p0


def install_hint():
    return 'python3 -m venv .venv-peers && .venv-peers/bin/pip install "tamaas>=2.9" numpy'


def grid(N, L):
    """Coordinates of the grid points along one side (x = i L a / N, as Tamaas'
    grids and tamaas.utils.hertz_surface), shifted so that point N // 2 is the apex."""
    side = L * A_H
    return (np.arange(N) - N // 2) * (side / N)


def surface(N, L):
    """The indenter's heights, Tamaas' sign: the apex highest, at 0 on point (N//2, N//2)."""
    x = grid(N, L)
    return -(x[:, None] ** 2 + x[None, :] ** 2) / (2 * R)


def fit_edge(p, N, L):
    """Contact radius and peak pressure from a fit of Hertz's profile, not from
    counting contact cells (that counts whole cells, a/N-coarse at the edge):
    p^2 = p0^2 (1 - r^2/a^2) is a straight line in r^2, fitted by least squares
    over the points with p > EDGE_FIT_FLOOR * max(p) (r < 0.95 a for Hertz), where
    the discrete pressure is smooth; a^2 = -intercept / slope. Returns (a, p0_fit)."""
    x = grid(N, L)
    r2 = x[:, None] ** 2 + x[None, :] ** 2
    inside = p > EDGE_FIT_FLOOR * p.max()
    if inside.sum() < 3:
        return float("nan"), float("nan")
    slope, intercept = np.polyfit(r2[inside], p[inside] ** 2, 1)
    if slope >= 0 or intercept <= 0:
        return float("nan"), float("nan")
    return math.sqrt(-intercept / slope), math.sqrt(intercept)


def next_load(loads, depths):
    """The next mean load for the depth D, from the (load, depth) pairs so far:
    a secant step on log depth against log load, Hertz's slope 2/3 for the first."""
    if len(loads) < 2 or depths[-1] == depths[-2] or loads[-1] == loads[-2]:
        slope = 2.0 / 3.0
    else:
        slope = math.log(depths[-1] / depths[-2]) / math.log(loads[-1] / loads[-2])
        slope = min(max(slope, 0.3), 1.0)  # a guard: Hertz 2/3, a flat punch 1
    return loads[-1] * (D / depths[-1]) ** (1.0 / slope)


@contextlib.contextmanager
def captured_stderr(lines):
    """Tamaas' C++ log (the solver's iteration table) goes to file descriptor 2:
    catch it there and keep its lines (the iterations are counted from them)."""
    sys.stderr.flush()
    saved = os.dup(2)
    with tempfile.TemporaryFile() as tmp:
        os.dup2(tmp.fileno(), 2)
        try:
            yield
        finally:
            os.dup2(saved, 2)
            os.close(saved)
            tmp.seek(0)
            lines.extend(tmp.read().decode(errors="replace").splitlines())


def iterations_of(log):
    """Polonsky-Keer-Rey iterations per solve: the last row of each iteration table."""
    counts, last = [], None
    for line in log + ["Iter"]:
        if line.strip().startswith("Iter"):
            if last is not None:
                counts.append(last)
            last = None
        elif re.match(r"^\s*\d+\s+\S+\s+\S+\s*$", line):
            last = int(line.split()[0])
    return counts


def run(N=256, L=None, operator="periodic", tol=1e-12):
    import tamaas as tm

    if operator not in OPERATORS:
        raise ValueError(f"operator {operator!r}: one of {OPERATORS}")
    if L is None:
        L = 16.0 if operator == "periodic" else 4.0
    side = L * A_H
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [side, side], [N, N])
    model.E, model.nu = E, NU  # Tamaas' contact modulus is E / (1 - nu^2) = E*
    h = surface(N, L)
    solver = tm.PolonskyKeerRey(model, h, tol)  # primal and constraint: the pressure
    solver.max_iter = 10000
    if operator == "dcfft":
        tm.ModelFactory.registerNonPeriodic(model, "dcfft")
        solver.setIntegralOperator("dcfft")
    c = N // 2

    def depth():
        if operator == "dcfft":  # the absolute displacement, as Tamaas documents
            model.operators["dcfft"](model.traction, model.displacement)
            return float(model.displacement[c, c])
        u = np.asarray(model.displacement)
        return float(u[c, c] - u.mean())  # the apex's approach from the mean plane

    # Hertz's load as the first guess: the converged state does not depend on it
    # (DEPTH_TOL), it only spares load steps
    loads, depths, log = [F_H / side**2], [], []
    t0 = time.perf_counter()
    tm.set_log_level(tm.LogLevel.info)  # the iteration table: counted, not shown
    with captured_stderr(log):
        while True:
            residual = solver.solve(loads[-1])
            depths.append(depth())
            done = abs(depths[-1] / D - 1) < DEPTH_TOL
            if done or len(loads) >= MAX_LOAD_STEPS:
                break
            loads.append(next_load(loads, depths))
    t_solve = time.perf_counter() - t0

    p = np.array(model.traction, dtype=float).reshape(N, N)
    p0 = float(p.max())
    F = float(p.sum()) * (side / N) ** 2
    a, p0_fit = fit_edge(p, N, L)
    steps = iterations_of(log)
    return {
        "N": N, "L_over_a": L, "operator": operator, "cells_per_a": N / L, "tol": tol,
        "load_steps": len(loads), "iterations": int(sum(steps)), "iterations_per_step": steps,
        "converged": bool(done and residual < tol), "depth_over_d": depths[-1] / D,
        "p0": p0, "F": F, "a": a, "p0_fit": p0_fit,
        "err_p0": p0 / P0_H - 1, "err_F": F / F_H - 1, "err_a": a / A_H - 1,
        "wall_time_solve": t_solve,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--N", type=int, default=256, help="grid points per side")
    ap.add_argument("--L", type=float, default=None,
                    help="side in units of a (default 16 periodic, 4 dcfft)")
    ap.add_argument("--operator", choices=OPERATORS, default="periodic",
                    help="periodic (Westergaard) or dcfft (non-periodic)")
    ap.add_argument("--tol", type=float, default=1e-12, help="the solver's relative tolerance")
    args = ap.parse_args()
    out = run(args.N, args.L, args.operator, args.tol)
    return finish(out, T_START)


if __name__ == "__main__":
    raise SystemExit(main())
