"""Coulomb friction along a load path (-mu, -steps), against references apart
from the solver: Mossakovskii's full-stick stiffness, a boundary-element
solution of Spence's plane problem (driver/references/spence.py), the decoupled
incompressible body, and the frictionless run itself."""
import math

import numpy as np
import pytest

from driver.references.spence import mossakovskii, spence_plane

from hertz_reference import estar

NUMBERS = ["p0_fe", "F_fe", "a_fe", "S_fe", "d_fe"]


def test_mu_zero_is_the_frictionless_run_to_the_digit(solve):
    plain, zero = solve(), solve("-mu", "0")
    assert plain.exit_code == zero.exit_code == 0, zero.output
    for col in NUMBERS + ["est_err_p0", "est_err_F", "est_err_a"]:
        assert zero.summary[col] == plain.summary[col], col
    assert math.isnan(zero.summary["c_fe"]) and zero.summary["Q_fe"] == 0 and zero.summary["steps"] == 1
    # a run of one step: its path is its result
    path = zero.table("path")
    assert len(path) == 1
    assert path["P"].iloc[0] == pytest.approx(zero.summary["F_fe"], rel=1e-12)
    assert path["a"].iloc[0] == pytest.approx(zero.summary["a_fe"], rel=1e-12)
    assert (zero.table("profile")["q_fe"] == 0).all()


def test_a_frictionless_path_ends_where_one_step_does(solve):
    one, path = solve("-method", "lagrange"), solve("-method", "lagrange", "-steps", "4")
    assert one.exit_code == path.exit_code == 0, path.output
    for col in NUMBERS:
        assert path.summary[col] == pytest.approx(one.summary[col], rel=1e-9), col
    rows = path.table("path")
    assert list(rows["step"]) == [1, 2, 3, 4]
    assert (np.diff(rows["d"]) > 0).all() and (np.diff(rows["P"]) > 0).all()
    # equal steps of a parabola's contact radius: d grows as (s/N)^2
    assert rows["d"].to_numpy() == pytest.approx(0.02 * (np.arange(1, 5) / 4) ** 2, rel=1e-12)
    # each step is Hertz's at its own depth (the tests' own formula: F = 4/3 E* sqrt(R) d^1.5)
    hertz = 4 / 3 * estar(10, 0.3) * math.sqrt(0.5) * rows["d"] ** 1.5
    assert rows["P"].to_numpy() == pytest.approx(hertz.to_numpy(), rel=0.02)


@pytest.mark.parametrize("nu, n, tol", [(0.3, "16", 0.003), (0.0, "32", 0.003)])
def test_full_stick_stiffness_is_mossakovskiis(solve, nu, n, tol):
    # measured: +0.13% at nu = 0.3, n = 16; +0.45%, +0.32%, +0.09% at nu = 0, n = 16, 24, 32
    run = solve("-mu", "inf", "-nu", str(nu), "-n", n)
    s = run.summary
    assert run.exit_code in (0, 5), run.output
    ratio = s["S_fe"] / (2 * estar(s["E"], nu) * s["a_fe"])
    assert ratio == pytest.approx(mossakovskii(nu), rel=tol)
    # and the frictionless stiffness is 2 E* a: full stick is stiffer by the factor
    assert ratio > 1.02
    assert s["c_fe"] == s["a_fe"] and math.isinf(s["mu"])


@pytest.mark.parametrize("mu", [0.2, 0.5])
def test_plane_stick_zone_against_boundary_elements(solve, mu):
    """Spence's plane problem: c/a of the FE against the tests' boundary elements
    (measured at n = 16: -2.3% and -2.5%, with the estimate 4.7% and 12.6%)."""
    run = solve("-model", "plane", "-Rx", "0.5", "-Ry", "inf", "-P", "0.01", "-mu", str(mu), "-nu", "0.3", "-E", "10")
    s = run.summary
    assert run.exit_code in (0, 5), run.output
    # the reference in the FE's units: the same E, nu, R and load per unit length
    bem = spence_plane(mu, 0.3, steps=80, cells=600, E=10.0, R=0.5, load=0.01)
    assert s["a_fe"] == pytest.approx(bem["a"], rel=0.01)  # the reference's cells are 0.4% of a
    err = s["c_fe"] / s["a_fe"] / bem["c_over_a"] - 1
    assert abs(err) < 0.07
    assert abs(err) <= 2 * s["est_err_c"], (err, s["est_err_c"])
    # friction narrows the contact a little: a below Hertz's, as the reference says
    assert s["a_fe"] < s["a_hertz"]


def test_axisymmetric_stick_ratio_does_not_depend_on_the_load(solve):
    """Spence: under monotone loading of a parabola c/a is the same at every
    load. Along one path the readings of the last half of the steps scatter
    (the slip zone's nodes stick for a step now and then: measured 0.66 to
    0.73 at mu = 0.2); each stays within twice the run's estimate of c, and
    they do not drift."""
    run = solve("-mu", "0.2")
    rows, s = run.table("path"), run.summary
    ratio = (rows["c"] / rows["a"]).to_numpy()
    final = s["c_fe"] / s["a_fe"]
    late = ratio[len(ratio) // 2:]
    assert (np.abs(late / final - 1) <= 2 * s["est_err_c"]).all(), (late, s["est_err_c"])
    slope = np.polyfit(np.arange(len(late)), late / final, 1)[0] * len(late)
    assert abs(slope) < s["est_err_c"], slope


def test_the_stick_zone_grows_with_mu_toward_full_stick(solve):
    ratios = []
    for mu in ("0.1", "0.3", "1"):
        run = solve("-mu", mu)
        assert run.exit_code in (0, 5), run.output
        ratios.append(run.summary["c_fe"] / run.summary["a_fe"])
    assert ratios[0] < ratios[1] < ratios[2] < 1, ratios
    # at mu = 0.1 and nu = 0.3 (beta = 0.286) most of the contact slips
    assert ratios[0] < 0.5


def test_slip_zone_carries_mu_p_and_the_stick_zone_less(solve):
    # mu = 0.1: a wide slip zone (c/a about 0.19), clear of the ring that
    # touched in the last step (free along r in it: a/16 wide)
    run = solve("-mu", "0.1")
    s, prof = run.summary, run.table("profile")
    a, c = s["a_fe"], s["c_fe"]
    slip = prof[(prof["r"] > c + 0.2 * (a - c)) & (prof["r"] < a - 0.2 * (a - c))]
    stick = prof[prof["r"] < 0.7 * c]
    assert len(slip) > 3 and len(stick) > 3
    # the surface slides toward the axis: friction on the body points outward
    assert (slip["q_fe"] > 0).all()
    assert slip["q_fe"].to_numpy() == pytest.approx(0.1 * slip["p_fe"].to_numpy(), rel=0.03)
    assert (stick["q_fe"].abs() < 0.1 * stick["p_fe"]).all()
    # the stick zone did not slip; the slip zone slid inward
    assert stick["slip"].abs().max() < 0.1 * slip["slip"].abs().max()
    assert (slip["slip"] < 0).all()


def test_an_incompressible_body_is_decoupled(solve):
    """beta = 0 at nu = 1/2: friction changes nothing under normal loading."""
    plain, rough = solve("-nu", "0.5"), solve("-nu", "0.5", "-mu", "0.3")
    assert rough.exit_code in (0, 5), rough.output
    for col in ("F_fe", "a_fe", "p0_fe"):
        assert rough.summary[col] == pytest.approx(plain.summary[col], rel=1e-3), col
    # nothing slips: the stick zone reaches the ring that touched in the last
    # step (free along r in that step, a/16 wide)
    assert rough.summary["c_fe"] / rough.summary["a_fe"] > 1 - 1.5 / 16


def test_path_rows_follow_the_run_and_end_at_its_summary(solve):
    run = solve("-mu", "0.2", "-P", "0.03")
    s, rows = run.summary, run.table("path")
    assert list(rows.columns) == ["step", "d", "P", "Q", "dt", "a", "c", "S", "p0", "est_err", "status", "pm",
                                  "ep_max", "plastic_reach", "neck"]
    assert rows["ep_max"].isna().all() and rows["plastic_reach"].isna().all()   # an elastic body
    assert len(rows) == s["steps"] == 16
    assert rows["P"].iloc[-1] == pytest.approx(0.03, rel=1e-9)
    assert rows["P"].to_numpy() == pytest.approx(0.03 * (np.arange(1, 17) / 16) ** 3, rel=1e-9)
    last = rows.iloc[-1]
    assert last["c"] == pytest.approx(s["c_fe"], rel=1e-12) and last["a"] == pytest.approx(s["a_fe"], rel=1e-12)
    assert last["status"] == s["status"] and last["est_err"] == pytest.approx(s["accuracy_predicted"], rel=1e-12)
    assert (rows["status"].iloc[:-1] == "converged").all()


@pytest.mark.parametrize("args, option", [
    (["-mu", "-1"], "-mu"), (["-mu", "nan"], "-mu"), (["-mu", "abc"], "-mu"),
    (["-mu", "0.3", "-method", "newton"], "-mu"), (["-mu", "0.3", "-model", "3d"], "-mu"),
    (["-steps", "0"], "-steps"), (["-steps", "2.5"], "-steps"),
    # a node sticks from the step after it touched: with 1 to 3 steps most of the contact is frictionless
    (["-mu", "0.3", "-steps", "2"], "-steps"), (["-mu", "0.3", "-accuracy", "0.01"], "-accuracy"),
])
def test_bad_friction_input_is_one_line(solve, args, option):
    run = solve(*args)
    assert run.exit_code == 2
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1 and option in lines[0], run.stderr


def random_plane_scenes(count: int, seed: int) -> list[tuple[float, float, int]]:
    rng = np.random.default_rng(seed)
    return [(round(float(10 ** rng.uniform(-0.9, 0.2)), 3), round(float(rng.uniform(0.0, 0.45)), 3),
             int(rng.choice([10, 12, 16, 20, 24]))) for _ in range(count)]


@pytest.mark.parametrize("mu, nu, n", random_plane_scenes(4, 2026))
def test_the_promise_holds_on_random_frictional_scenes(solve, mu, nu, n):
    """Each reading within twice its own estimate of the boundary elements: c,
    and a (with the reference's cell, 0.4% of a). Measured on 14 scenes
    (mu 0.13 to 1.6, nu 0 to 0.43, n 10 to 24): c within its estimate in all
    (at worst c/a -10.5% read 10.9%), and two with c under the first node
    (stick-unresolved, c_fe NaN)."""
    run = solve("-model", "plane", "-Rx", "0.5", "-Ry", "inf", "-P", "0.01", "-mu", str(mu), "-nu", str(nu),
                "-n", str(n))
    s = run.summary
    assert run.exit_code in (0, 5), run.output
    # (40 steps of 400 cells: within 0.4% of c/a and 0.2% of a of 80 steps of 600, at a sixth of the time)
    bem = spence_plane(mu, nu, steps=40, cells=400, E=10.0, R=0.5, load=0.01)
    assert abs(s["a_fe"] / bem["a"] - 1) <= 2 * s["est_err_a"] + 0.004
    if math.isnan(s["c_fe"]):
        assert "stick-unresolved" in s["warnings"]
        assert bem["c_over_a"] * s["a_fe"] < 2 * (s["a_fe"] / n)  # within the first element or so
    else:
        err = s["c_fe"] / s["a_fe"] / bem["c_over_a"] - 1
        assert abs(err) <= 2 * s["est_err_c"], (err, s["est_err_c"])
