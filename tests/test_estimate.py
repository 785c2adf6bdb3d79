"""The error estimate is an upper bound in practice: no run exits 0 with a true error above 1%,
and every exit-0 run estimates at least half its true error. The truth comes from Hertz written
again in hertz_reference.py (the sphere from its depth, the cylinder's relations from its load)."""
import math
import re

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from promise import check_promise

from hertz_reference import cylinder_half_width, cylinder_pressure, sphere, sphere_from_load


def error_against_hertz(s: dict) -> float:
    """Largest relative error of p0, F and a (the cylinder: p0 and a against its load)."""
    E, nu, R = s["E"], s["nu"], s["R"]
    if s["model"] == "plane":
        P = s["F_fe"]
        return max(abs(s["a_fe"] / cylinder_half_width(P, E, nu, R) - 1),
                   abs(s["p0_fe"] / cylinder_pressure(P, E, nu, R) - 1))
    if not math.isnan(s["P"]):  # the load given: p0, the depth and a
        hz = sphere_from_load(E, nu, R, s["P"])
        return max(abs(s["p0_fe"] / hz.p0 - 1), abs(s["d_fe"] / (hz.a**2 / R) - 1), abs(s["a_fe"] / hz.a - 1))
    hz = sphere(E, nu, R, s["d"])
    return max(abs(s["p0_fe"] / hz.p0 - 1), abs(s["F_fe"] / hz.F - 1), abs(s["a_fe"] / hz.a - 1))


# The scenes that exited 0 with an estimate 3 to 30 times low (nu near 1/2 on coarse meshes,
# P2 displacements): the mixed formulation (Taylor-Hood) and the fitted edge now hold them.
BLIND_SPOT = [
    ("-E", "3e7", "-nu", "0.49", "-R", "0.01", "-d", "1e-5", "-n", "5"),
    ("-E", "3e7", "-nu", "0.49", "-R", "0.01", "-d", "1e-5", "-n", "4"),
    ("-E", "3e7", "-nu", "0.49", "-R", "0.01", "-d", "1e-5", "-n", "6"),
    ("-E", "3e7", "-nu", "0.49", "-R", "0.01", "-d", "1e-5", "-n", "10"),
    ("-E", "3e7", "-nu", "0.49", "-R", "0.01", "-d", "1e-5", "-n", "6", "-method", "lagrange"),
    ("-E", "7426.19", "-nu", "0.42777", "-R", "2.37659e-05", "-d", "5.275e-08", "-n", "6"),
    ("-E", "3e7", "-nu", "0.49", "-Rx", "inf", "-Ry", "0.01", "-d", "1e-5", "-n", "6"),
]


@pytest.mark.parametrize("args", BLIND_SPOT, ids=[" ".join(a) for a in BLIND_SPOT])
def test_the_former_blind_spot_keeps_the_promise(solve, args):
    run = solve(*args)
    truth, _ = check_promise(run, error_against_hertz(run.summary))
    assert truth < 0.01  # measured 0.1% to 0.45% (P2 displacements: 1.1% to 6.3%)


@pytest.mark.parametrize("args", [
    ("-model", "axi", "-method", "lagrange", "-nu", "0", "-n", "16"),
    ("-model", "plane", "-method", "newton", "-nu", "0", "-n", "12"),
    ("-n", "20"),  # Richardson alone: 0.31 of the truth (0.036%) since the edge fit reads past open nodes
])
def test_a_contact_edge_between_nodes_is_in_the_estimate(solve, args):
    # the part of the error that jumps with where the edge falls between nodes is not smooth in
    # n, and Richardson alone read 0.25 and 0.32 of it on the first two (before the edge fit read
    # past barely open nodes; now 1.75 and 2.48) and 0.31 on the third: the quantization floor
    # covers it
    run = solve(*args, "-E", "3e7", "-R", "0.01", "-d", "1e-5")
    check_promise(run, error_against_hertz(run.summary))


def test_nearly_incompressible_bodies_take_the_mixed_formulation(solve):
    s = solve("-nu", "0.49").summary
    assert s["formulation"] == "mixed" and solve().summary["formulation"] == "displacement"
    forced = solve("-nu", "0.49", "-n", "5", "-formulation", "displacement").summary
    mixed = solve("-nu", "0.49", "-n", "5").summary
    assert error_against_hertz(mixed) < 0.006 < error_against_hertz(forced)  # measured 0.52% and 0.96%


@pytest.mark.parametrize("model", ["axi", "plane"])
def test_an_incompressible_body_is_solved(solve, model):
    run = solve("-nu", "0.5", "-model", model)
    assert run.exit_code == 0, run.output
    assert error_against_hertz(run.summary) < 2e-3  # measured 0.03% (axi), 0.07% (plane)
    # MUMPS's solve of the indefinite form, refined to rounding: measured 2.5e-11 and 2.2e-11
    # (unrefined, the axi run stalled at 4.8e-3)
    assert run.summary["residual"] < 1e-9


def test_n_below_3_is_outside_the_range(solve):
    run = solve("-n", "2")
    assert run.exit_code == 2 and "-n must be an integer in [3, 400]" in run.stderr


# Scenes that exited 0 beyond their estimate: P1, whose estimate's partner level (n = 8) had the
# same far field as n = 16, so Richardson missed that field's error (F 2.7% read as 0.6%, 3.3% as
# 0.9%); and the cylinder's a(P) under a moderate penalty, which moves it by 8 times the
# penetration where the model said 1 (1.08% read as 0.82%); and P1 under a load, whose
# Richardson and penalty parts cancelled when summed with their signs (0.77% read as 0.09%)
FORMER_MISSES = [
    ("-order", "1", "-nu", "0"),
    ("-order", "1", "-n", "32", "-gamma", "5", "-P", "0.03"),
    ("-order", "1", "-farfield", "clamped"),
    ("-model", "plane", "-gamma", "5"),
    ("-model", "plane", "-nu", "0.45", "-gamma", "5"),
    # the cylinder's a at moderate penalties on coarse meshes: its parts summed with their signs
    # read 0.95% and 0.90% where a was +1.37% and +1.47% (now in magnitude: 2.7% and 3.4%)
    ("-model", "plane", "-n", "6", "-gamma", "8"),
    ("-model", "plane", "-n", "4", "-gamma", "10"),
]


@pytest.mark.parametrize("args", FORMER_MISSES, ids=[" ".join(a) for a in FORMER_MISSES])
def test_the_former_misses_keep_the_promise(solve, args):
    run = solve(*args)
    check_promise(run, error_against_hertz(run.summary))


@pytest.mark.parametrize("gamma", ["10", "100"])
def test_p1_s_penalty_part_is_the_penalty_s_effect(solve, gamma):
    # P1's p0, read against its nodal penetration, falls 2.5 times as fast as P2's: the part
    # the estimate prints is the penalty's effect against exact contact on the same levels
    # (measured 0.87 and 1.01 of it; with P2's coefficient it was 0.40)
    pen = solve("-order", "1", "-gamma", gamma)
    exact = solve("-order", "1", "-method", "lagrange")
    effect = pen.summary["p0_fe"] / exact.summary["p0_fe"] - 1
    part = float(re.search(r"penalty, domain: \S+ (\S+) \S+ on p0", pen.output).group(1))
    assert part == pytest.approx(effect, rel=0.3), (part, effect)


@pytest.mark.parametrize("target", ["0.05", "0.03", "0.01"])
def test_p1_accuracy_holds_by_the_truth(solve, target):
    # P1 with a penalty: -accuracy 0.03 stopped at n = 16 with p0 4.9% (est 2.6%)
    run = solve("-order", "1", "-method", "newton", "-accuracy", target)
    assert run.exit_code in (0, 5), run.output
    if run.exit_code == 0:
        assert error_against_hertz(run.summary) <= float(target)


@pytest.mark.parametrize("target", ["0.05", "0.02", "0.015", "0.01", "0.005", "0.002", "0.001", "0.0003", "0.0001"])
@pytest.mark.parametrize("scene", [(), ("-E", "2e6", "-nu", "0.49", "-R", "0.005", "-d", "2e-4"),
                                   ("-model", "plane", "-nu", "0.45")], ids=["seed", "rubber", "cylinder"])
def test_accuracy_holds_by_the_truth(solve, target, scene):
    run = solve(*scene, "-accuracy", target)
    assert run.exit_code == 0, run.output
    s = run.summary
    assert error_against_hertz(s) <= float(target) and s["accuracy_predicted"] <= float(target)


# Any scene of the targeted kind, drawn at random (the same draws on every run): it keeps the
# promise or says it is off.
scenes = st.fixed_dictionaries({
    "nu": st.floats(-0.9, 0.4999).map(lambda x: float(f"{x:.4g}")),
    "n": st.sampled_from([3, 4, 5, 6, 8, 10, 12, 16, 24, 32]),
    "model": st.sampled_from(["axi", "plane"]),
    "method": st.sampled_from(["newton", "lagrange"]),
    "d_over_R": st.floats(1e-5, 0.05).map(lambda x: float(f"{x:.3g}")),
    "stress_unit": st.sampled_from([1.0, 1e6, 1e9]),
    "length_unit": st.sampled_from([1e-3, 1.0]),
})


@settings(max_examples=30, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(scenes)
def test_random_scenes_keep_the_promise(solve, sc):
    E, R = 10.0 * sc["stress_unit"], 0.5 * sc["length_unit"]
    run = solve("-E", repr(E), "-nu", repr(sc["nu"]), "-R", repr(R), "-d", repr(sc["d_over_R"] * R),
                "-n", str(sc["n"]), "-model", sc["model"], "-method", sc["method"])
    check_promise(run, error_against_hertz(run.summary))
    assert math.isfinite(run.summary["accuracy_predicted"])


# The same over P1 and penalties between soft and stiff, where the penalty's own error is a part
# of the estimate (P1 and the cylinder had it too small)
penalty_scenes = st.fixed_dictionaries({
    "nu": st.floats(-0.5, 0.45).map(lambda x: float(f"{x:.4g}")),
    "n": st.sampled_from([4, 6, 8, 12, 16, 24, 32]),
    "model": st.sampled_from(["axi", "plane"]),
    "order": st.sampled_from(["1", "2"]),
    "gamma": st.sampled_from(["3", "5", "10", "30", "100", "1e3", "1e5"]),
    "d_over_R": st.floats(1e-4, 0.05).map(lambda x: float(f"{x:.3g}")),
})


@settings(max_examples=25, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(penalty_scenes)
def test_random_penalty_and_p1_scenes_keep_the_promise(solve, sc):
    run = solve("-nu", repr(sc["nu"]), "-d", repr(sc["d_over_R"] * 0.5), "-n", str(sc["n"]),
                "-model", sc["model"], "-order", sc["order"], "-gamma", sc["gamma"])
    check_promise(run, error_against_hertz(run.summary))



# Scenes that exited 5 at a true error under 0.3% (false alarms of the audit, seed 2026), each
# now exit 0 within its promise: the cylinder's a(P) moves by 1.1 to 1.8 times the penetration,
# not 8 (n = 8: a +0.06% read 1.9%); P2's off-axis peak (k > 2) converges at second order once
# the coarser level has 10 elements (k = 5.8 to 9.2, n = 14 to 31: 0.01% to 0.04% read 1.1% to
# 1.3%); a cusp's floor shrinks with the cusp as k -> 2 (k = 1.95, n = 15: 0.23% read 1.5%)
FORMER_FALSE_ALARMS = [
    "-E 2893634.4235511757 -nu 0.20459497064835064 -method newton -order 2 -n 8 -model plane "
    "-Rx 0.3402400437916241 -Ry inf -P 1770.3455475694564",
    "-E 6324836.783924942 -nu 0.14599718493394115 -method lagrange -order 2 -n 31 -shape power "
    "-R 0.5206233383350212 -k 5.8384369617712695 -d 0.00262559659",
    "-E 2.2341696571551126 -nu 0.08974115823422425 -method lagrange -order 2 -n 28 -shape power "
    "-R 1.1233445925426369 -k 9.171235348016555 -d 0.03173584882",
    "-E 1182126.5864417807 -nu 0.3 -method lagrange -order 2 -n 14 -shape power -R 0.378747716917896 "
    "-k 7.824275182520206 -d 0.0008587485662847061",
    "-E 25568292.45595143 -nu 0.3 -method newton -order 2 -n 15 -shape power -R 5.506073432381507 "
    "-k 1.947970185418945 -d 0.055782607366162903",
]


def audited_truth(args: list[str], s: dict) -> float:
    """The largest true error of the scene's quantities, by the audit's references."""
    from audit import truth
    return max(e for e in truth(args, s).values() if not math.isnan(e))


@pytest.mark.parametrize("line", FORMER_FALSE_ALARMS)
def test_the_former_false_alarms_converge_within_their_promise(solve, line):
    args = line.split()
    run = solve(*args)
    assert run.exit_code == 0, run.output
    check_promise(run, audited_truth(args, run.summary))


def test_a_p2_off_axis_peak_read_where_its_levels_agree_is_still_covered(solve):
    # k = 7.4, n = 8: p0 +0.54% estimated at 0.23% (its partner, n = 16, read the same peak)
    args = ("-E 16247.504002899075 -nu 0.4001990873077035 -method uzawa -order 2 -n 8 -shape power "
            "-R 0.14747297383328542 -k 7.4339347044806425 -d 0.005193487526065676").split()
    s = solve(*args).summary
    from audit import truth
    true = truth(args, s)["p0"]
    assert true > 0.004 and s["est_err_p0"] >= 0.5 * true, (true, s["est_err_p0"])


@pytest.mark.parametrize("control", [("-P", "0.01"), ("-d", "0.005")])
def test_the_cylinders_depth_or_force_has_its_estimate(solve, control):
    # it was NaN: a reported quantity without an estimate. The depth (under -P) or the force
    # (under -d) is the domain's, so the truth is a run of the same domain at n = 128
    scene = ("-model", "plane", "-Rx", "0.5", "-Ry", "inf", *control)
    run = solve(*scene, "-n", "9", "-method", "newton")
    fine = solve(*scene, "-n", "128", "-method", "lagrange").summary
    column = "d_fe" if control[0] == "-P" else "F_fe"
    truth = abs(run.summary[column] / fine[column] - 1)
    assert run.exit_code == 0 and math.isfinite(run.summary["est_err_F"]), run.output
    assert run.summary["est_err_F"] >= 0.5 * truth, (truth, run.summary["est_err_F"])
