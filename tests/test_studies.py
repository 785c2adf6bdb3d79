"""Physics claims checked on the study tables in results/ (quick sweep if missing)."""
import math

import numpy as np
import pytest


def slope(x, y):
    """Least-squares slope of log|y| against log x."""
    return np.polyfit(np.log(np.asarray(x, float)), np.log(np.abs(np.asarray(y, float))), 1)[0]


def converged(frame):
    return frame[frame["status"] == "converged"]


def test_penalty_error_falls_as_one_over_kpen_to_the_discretization_floor(studies):
    df = converged(studies["kpen"])
    p2 = df[(df["method"] == "newton") & (df["order"] == 2)].sort_values("kpen")
    # penetration ~ p0/kpen once kpen >> E*/a (~100 here): slope -1 within 2%;
    # softer penalties approach the rigid-body limit penetration = d
    stiffish = p2[p2["kpen"] >= 1e3]
    assert slope(stiffish["kpen"], stiffish["penetration_over_d"]) == pytest.approx(-1, abs=0.02)
    assert p2[p2["kpen"] == p2["kpen"].min()]["penetration_over_d"].iloc[0] > 0.5
    # force error: its penalty part (against the stiffest run) falls as 1/kpen
    err = p2.set_index("kpen")["err_F"]
    penalty_part = err - err[err.index.max()]
    assert penalty_part[1e5] < 0  # a soft penalty lowers the force
    assert penalty_part[1e5] / penalty_part[1e7] == pytest.approx(100, rel=0.25)
    # ... and flat at the discretization floor for stiff penalties
    stiff = p2[p2["kpen"] >= 1e7]["err_F"]
    assert stiff.max() - stiff.min() < 1e-5
    assert stiff.abs().max() < 2e-3


def test_mesh_convergence_orders_are_positive(studies):
    df = converged(studies["mesh"])
    scaled = df[df["kpen"] != 1e5]  # kpen = 100 E*/h
    orders = {}
    for order in (1, 2):
        series = scaled[scaled["order"] == order].sort_values("n")
        h = 1.0 / series["n"]
        orders[(order, "a")] = slope(h, series["err_a"])
        if order == 1:
            orders[(order, "F")] = slope(h, series["err_F"])
        else:
            # P2 force error sits on the domain/penalty floor (< 0.2%) from n = 5
            assert series["err_F"].abs().max() < 2e-3
    # measured on the full sweep (n up to 160 / 80): P1 F 1.6, P1 a 1.9,
    # P2 a 1.0 (the square-root pressure edge limits a to first order)
    assert orders[(1, "F")] > 1.2, orders
    assert orders[(1, "a")] > 0.8, orders
    assert orders[(2, "a")] > 0.5, orders


def test_newton_iteration_counts_stay_bounded(studies):
    frames = [studies[s] for s in ("kpen", "mesh", "domain", "plane", "speed")]
    frames.append(studies["stability"][studies["stability"]["cont"] == 0])
    for frame in frames:
        p2 = frame[(frame["method"] == "newton") & (frame["order"] == 2)]
        assert (p2["status"] == "converged").all()
        # a small clamped domain (L < 100 a) stiffens the body and moves the
        # contact edge away from the Hertz-zone first guess: more iterations
        usual = p2["L"] >= 100
        assert p2[usual]["iterations"].max() <= 10, p2[["case_id", "iterations"]]
        assert p2["iterations"].max() <= 30, p2[["case_id", "iterations"]]  # L = 10 a: 24


def test_fixed_point_limit_matches_theory_and_does_not_depend_on_the_mesh(studies):
    df = studies["stability"]
    fp = df[df["method"] == "fixedpoint"]
    limits = {}
    for (n, omega), group in fp.groupby(["n", "omega"]):
        ok = group[group["status"] == "converged"]["kpen"]
        bad = group[group["status"] == "diverged"]["kpen"]
        assert len(ok) and len(bad), (n, omega)
        assert ok.max() < bad.min(), (n, omega)  # one sharp boundary
        theory = group["kpen_critical"].iloc[0]
        # the predicted limit (2/omega - 1)/mu is sufficient: every kpen below it
        # converges, the first unstable kpen lies above it, and the measured
        # limit is within one grid step of it. (mu is taken on the first,
        # largest active set; a small omega may leave it before diverging.)
        assert (group[group["kpen"] < theory]["status"] == "converged").all(), (n, omega)
        assert theory < bad.min(), (n, omega, theory)
        assert (ok > theory).sum() <= 1, (n, omega, theory)  # sharp: at most one grid step off
        limits[(n, omega)] = theory
    # mu is the compliance of the smoothest contact mode, ~ a/E*: the limit
    # scales with E*/a, not with E/h, so refining the mesh leaves it unchanged
    for omega in fp["omega"].unique():
        values = [v for (n, w), v in limits.items() if w == omega]
        assert max(values) / min(values) < 1.01, limits


def test_finite_domain_bias_falls_as_the_domain_grows(studies):
    df = converged(studies["domain"]).sort_values("L")
    assert (np.diff(df["err_F"].to_numpy()) < 0).all()
    # about 0.94% x 100a/L (HERTZ.md); 0.05% of discretization error on top
    for _, row in df[df["L"].between(100, 1000)].iterrows():  # asymptotic regime
        assert row["err_F"] == pytest.approx(0.0094 * 100 / row["L"], abs=0.2 * 0.0094 * 100 / row["L"] + 5e-4)
    assert df["err_F"].iloc[-1] < 1e-3


def test_plane_strain_relations_hold(studies):
    df = converged(studies["plane"])
    assert len(df) >= 4
    estar = df["E"] / (1 - df["nu"] ** 2)
    p0_from_a = estar * df["a_fe"] / (2 * df["R"])
    assert np.allclose(df["p0_fe"], p0_from_a, rtol=0.01)
    a_from_P = np.sqrt(4 * df["F_fe"] * df["R"] / (math.pi * estar))
    assert np.allclose(df["a_fe"], a_from_P, rtol=0.01)


def test_augmented_lagrangian_closes_every_node_at_a_moderate_penalty(studies):
    aug = studies["speed"][studies["speed"]["method"] == "auglag"]
    assert len(aug) >= 4 and (aug["status"] == "converged").all()
    # Uzawa stops when every surface node is closed to tol = 1e-8 d
    assert (aug["nodal_penetration_over_d"] < 1e-6).all()
    moderate = aug[(aug["kpen"] == 1e5) & (aug["n"] >= 16)]
    assert (moderate[["err_p0", "err_F", "err_a"]].abs().max(axis=1) < 0.001).all()


def test_closing_the_surface_between_nodes_pins_the_contact_edge_to_a_node(studies):
    # The P2 gap is quadratic on each surface edge: inside the edge that
    # straddles r = a it bulges past the indenter between closed nodes. A stiff
    # inner penalty pushes the bulge down, and with it the whole edge out of
    # contact: the contact radius drops by about one surface element a/(4n).
    aug = studies["speed"][(studies["speed"]["method"] == "auglag") & (studies["speed"]["n"] == 32)]
    rows = aug.set_index("kpen")
    moderate, stiff = rows.loc[1e5], rows.loc[1e7]
    assert moderate["penetration_over_d"] > 1e-6 > stiff["penetration_over_d"]
    element = 1 / (4 * 32)
    assert abs(moderate["err_a"]) < 0.1 * element
    assert -stiff["err_a"] > 0.5 * element
    # p0 and F do not notice
    assert stiff["err_p0"] == pytest.approx(moderate["err_p0"], abs=1e-5)
    assert stiff["err_F"] == pytest.approx(moderate["err_F"], abs=1e-5)
