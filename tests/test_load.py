"""The load given instead of the depth (-P), and the contact stiffness S = dF/dd, against
Hertz written again in hertz_reference.py (a, d and p0 from the load; S = 2 E* a)."""
import math

import pytest

from hertz_reference import (
    SEED,
    cylinder_half_width,
    cylinder_pressure,
    ellipsoid_from_load,
    estar,
    punch_stiffness,
    sphere,
    sphere_depth,
    sphere_from_load,
)

SEED_LOAD = sphere(**SEED).F  # the load of the seed scene's depth


@pytest.mark.parametrize("method", ["newton", "lagrange", "uzawa"])
def test_the_seed_load_finds_the_seed_depth(solve, method):
    run = solve("-P", repr(SEED_LOAD), "-method", method)
    assert run.exit_code == 0, run.output
    s = run.summary
    assert s["status"] == "converged" and math.isnan(s["d"]) and s["P"] == pytest.approx(SEED_LOAD, rel=1e-15)
    ref = sphere_from_load(SEED["E"], SEED["nu"], SEED["R"], SEED_LOAD)
    # the load holds to the solver's tolerance; d, a and p0 within 0.5% (measured 0.01% to 0.07%)
    assert s["F_fe"] == pytest.approx(SEED_LOAD, rel=1e-8)
    assert s["d_fe"] == pytest.approx(SEED["d"], rel=5e-3)
    assert s["a_fe"] == pytest.approx(ref.a, rel=5e-3) and s["p0_fe"] == pytest.approx(ref.p0, rel=5e-3)
    # the solver's own references are the load's
    assert s["d_hertz"] == pytest.approx(SEED["d"], rel=1e-12) and s["a_hertz"] == pytest.approx(ref.a, rel=1e-12)
    assert "Depth FE:" in run.stdout


@pytest.mark.parametrize("units", [(1.0, 1.0), (1e9, 1e-3), (1e3, 1.0)])  # seed, SI, mm-N-MPa
def test_load_control_holds_in_any_units(solve, units):
    stress, length = units
    E, R, P = SEED["E"] * stress, SEED["R"] * length, 2 * SEED_LOAD * stress * length**2
    s = solve("-E", repr(E), "-R", repr(R), "-P", repr(P)).summary
    assert s["status"] == "converged"
    assert s["d_fe"] == pytest.approx(sphere_depth(E, SEED["nu"], R, P), rel=5e-3)
    ref = sphere_from_load(E, SEED["nu"], R, P)
    assert s["a_fe"] == pytest.approx(ref.a, rel=5e-3) and s["p0_fe"] == pytest.approx(ref.p0, rel=5e-3)


def test_a_cylinder_under_load_keeps_its_relations(solve):
    P = 0.04
    s = solve("-model", "plane", "-P", repr(P)).summary
    assert s["status"] == "converged" and s["F_fe"] == pytest.approx(P, rel=1e-8)
    E, nu, R = SEED["E"], SEED["nu"], SEED["R"]
    assert s["a_fe"] == pytest.approx(cylinder_half_width(P, E, nu, R), rel=5e-3)
    assert s["p0_fe"] == pytest.approx(cylinder_pressure(P, E, nu, R), rel=5e-3)
    # a line contact's depth depends on the domain: found, but not compared
    assert s["d_fe"] > 0 and math.isnan(s["d_hertz"]) and math.isnan(s["S_hertz"])


@pytest.mark.parametrize("method", ["newton", "lagrange"])
def test_the_stiffness_is_2_estar_a(solve, method):
    # from the converged linearization, not two runs; measured +0.02% (newton), +0.14% (lagrange)
    s = solve("-method", method).summary
    assert s["S_fe"] == pytest.approx(punch_stiffness(SEED["E"], SEED["nu"], s["a_fe"]), rel=5e-3)
    assert s["S_hertz"] == pytest.approx(punch_stiffness(SEED["E"], SEED["nu"], sphere(**SEED).a), rel=1e-12)


@pytest.mark.parametrize("n", ["8", "32"])
def test_the_penalty_stiffness_holds_on_every_mesh(solve, n):
    # Newton's stiffness (active set at the quadrature points): measured +0.14% of 2 E* a at
    # n = 8 and within 0.016% for n from 16 to 64; exact contact's held set of nodes is a discrete
    # flat punch whose edge sits between nodes: +0.03% to +0.44%, falling with n
    newton, exact = solve("-n", n).summary, solve("-method", "lagrange", "-n", n).summary
    assert newton["S_fe"] == pytest.approx(punch_stiffness(SEED["E"], SEED["nu"], newton["a_fe"]), rel=2e-3)
    assert exact["S_fe"] == pytest.approx(punch_stiffness(SEED["E"], SEED["nu"], exact["a_fe"]), rel=5e-3)


def test_a_penalty_adds_its_compliance_in_series(solve):
    # 1/S = 1/S_elastic + 1/S_penalty: the softer the penalty, the lower S, below the exact method's
    stiffness = [solve("-gamma", g).summary["S_fe"] for g in ("1", "10", "1e4")]
    exact = solve("-method", "lagrange").summary["S_fe"]
    assert stiffness[0] < 0.99 * stiffness[1] and stiffness[1] < stiffness[2] < 1.001 * exact


def test_the_elliptical_example_under_load(solve):
    # a rigid ellipsoid Rx = 10 mm, Ry = 40 mm on steel (N, mm, MPa), P = 100 N: elliptical Hertz
    # gives 0.11506 mm along x, 0.28772 mm along y, p0 = 1442.3 MPa, d = 1.6967 um
    # n = 10: at the default n = 8 the semi-axes read within 0.2%, but the pair (4, 8) estimates
    # the long one past 1% under load (inaccurate, README)
    run = solve("-E", "210000", "-nu", "0.3", "-Rx", "10", "-Ry", "40", "-P", "100", "-n", "10", timeout=300)
    assert run.exit_code == 0, run.output
    s = run.summary
    ref = ellipsoid_from_load(100.0, 210000.0, 0.3, 10.0, 40.0)
    assert (ref.b_short, ref.a_long) == pytest.approx((0.11506, 0.28772), rel=1e-4)
    assert ref.p0 == pytest.approx(1442.3, rel=1e-4) and ref.d == pytest.approx(1.6967e-3, rel=1e-4)
    # measured a +0.10%, b -0.28%, p0 and d within 0.1%
    assert s["a_fe"] == pytest.approx(ref.b_short, rel=0.02) and s["b_fe"] == pytest.approx(ref.a_long, rel=0.02)
    assert s["p0_fe"] == pytest.approx(ref.p0, rel=0.02) and s["d_fe"] == pytest.approx(ref.d, rel=0.02)
    # any paraboloid: S = 3F/(2d)
    assert s["S_fe"] == pytest.approx(1.5 * 100 / ref.d, rel=0.02)


def test_an_ellipsoids_parabola_warning_does_not_advise_a_shape_that_refuses_it(solve):
    """-shape sphere has one radius and refuses -Rx/-Ry: an ellipsoid's parabola
    warning says so instead of advising it."""
    run = solve("-Rx", "0.5", "-Ry", "1", "-P", "0.03")
    warning = next(x for x in run.stderr.splitlines() if "warning: d/R" in x)
    assert "use -shape sphere" not in warning and "-shape sphere has one radius" in warning
    assert "-shape sphere solves it" not in run.stdout
    plain = next(x for x in solve("-R", "0.5", "-d", "0.05").stderr.splitlines() if "warning: d/R" in x)
    assert "use -shape sphere" in plain


@pytest.mark.parametrize("args,option", [
    (["-P", "0"], "-P"), (["-P", "-1"], "-P"), (["-P", "1e-3", "-d", "0.01"], "-P"),
    (["-P", "1e6"], "-P"),  # the depth would pass the radius
])
def test_bad_loads_are_one_line_and_exit_2(solve, args, option):
    run = solve(*args)
    assert run.exit_code == 2, run.output
    errors = run.stderr.strip().splitlines()
    assert len(errors) == 1 and option in errors[0] and errors[0].startswith("hertz.edp: error:")
    assert not run.outdir.exists() or not any(run.outdir.iterdir())


def test_a_load_below_the_floating_point_range_is_refused(solve):
    run = solve("-P", "1e-300")
    assert run.exit_code == 2 and "scale" in run.stderr


def test_depth_control_reports_the_given_depth(solve):
    s = solve().summary
    assert s["d_fe"] == SEED["d"] and math.isnan(s["P"]) and s["d"] == SEED["d"]
    assert estar(SEED["E"], SEED["nu"]) > 0
