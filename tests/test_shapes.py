"""Indenters beyond the parabola (-shape) against their exact solutions, written again in
hertz_reference.py by the method of dimensionality reduction (the solver uses Sneddon's
integrals): the exact sphere, cones, power laws, the flat punch and a tabulated profile."""
import math
import time

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from promise import check_promise

from conftest import rel
from hertz_reference import (
    estar,
    flat_punch_edge_coefficient,
    max_pressure,
    plane_half_width,
    profile_from_depth,
    punch_from_depth,
    punch_from_load,
    sphere,
)

E, NU, R = 10.0, 0.3, 0.5
ESTAR = estar(E, NU)
GEOMETRY = {"sphere": dict(R=R), "cone": dict(angle=70.3), "power": dict(R=R, k=1.5)}


def center_or_max_pressure(shape: str, a: float, modulus: float = ESTAR, **geometry) -> float:
    return max_pressure(shape, a, modulus, **geometry)


@pytest.mark.parametrize("d_over_R", [0.01, 0.04, 0.1, 0.3])
def test_the_exact_sphere_matches_its_exact_solution(solve, d_over_R):
    run = solve("-shape", "sphere", "-d", repr(d_over_R * R))
    assert run.exit_code == 0, run.output
    s = run.summary
    ref = punch_from_depth("sphere", d_over_R * R, E, NU, R=R)
    p0 = center_or_max_pressure("sphere", ref.a, R=R)
    # measured at d/R = 0.04: p0 +0.006%, F -0.010%, a +0.040%
    assert rel(s["F_fe"], ref.F) < 3e-3 and rel(s["a_fe"], ref.a) < 3e-3 and rel(s["p0_fe"], p0) < 3e-3, s
    assert s["reference"] == "sneddon" and rel(s["F_hertz"], ref.F) < 1e-6  # the solver's own reference
    # the contact stiffness of any axisymmetric punch, 2 E* a
    assert rel(s["S_fe"], 2 * ESTAR * ref.a) < 5e-3


def test_the_sphere_is_not_the_parabola_at_a_tenth_of_its_radius(solve):
    sph = solve("-shape", "sphere", "-d", "0.05").summary
    par = solve("-d", "0.05", "-R", "0.5").summary
    # Sneddon: at d/R = 0.1 the sphere's F is lower by about (d/R)/10, its a by (d/R)/6
    assert sph["F_fe"] / par["F_fe"] - 1 == pytest.approx(-0.1 / 10, abs=2e-3)
    assert sph["a_fe"] / par["a_fe"] - 1 == pytest.approx(-0.1 / 6, abs=3e-3)
    # the parabola's run says so when the radius is the user's
    assert par["parabola_error"] > 5e-3 and "parabola" in str(par["warnings"])


@pytest.mark.parametrize("angle", [60, 70.3, 80])
def test_cones_match_sneddon(solve, angle):
    run = solve("-shape", "cone", "-angle", str(angle))
    assert run.exit_code == 0, run.output
    s = run.summary
    ref = punch_from_depth("cone", 0.02, E, NU, angle=angle)
    # measured at 70.3 degrees: F -0.010%, a +0.027%
    assert rel(s["F_fe"], ref.F) < 5e-3 and rel(s["a_fe"], ref.a) < 5e-3, s
    assert math.isnan(s["p0_fe"])  # logarithmic under the tip: no maximum to report
    assert rel(s["S_fe"], 2 * ESTAR * ref.a) < 5e-3


def test_a_moderate_penalty_on_a_power_law_says_it_is_off(solve):
    # p0 -1.02% (Sneddon), F -0.61%, a +0.71% at 5 E*/h: the penalty's part of the estimate
    # (-1.02%, its coefficients measured on the paraboloid) and Richardson's (+0.24%, where the
    # mesh's error is +0.13%) summed with their signs to 0.78%, and the run exited 0; for a shape
    # other than the paraboloid they now add in magnitude (1.26%: inaccurate)
    run = solve("-shape", "power", "-k", "3", "-gamma", "5")
    s = run.summary
    ref = punch_from_depth("power", 0.02, E, NU, R=R, k=3)
    truth = rel(s["p0_fe"], center_or_max_pressure("power", ref.a, R=R, k=3))
    assert truth > 0.01  # the scene is the one that was missed (measured 1.015%)
    assert run.exit_code == 5 and s["est_err_p0"] >= truth, (truth, s["est_err_p0"])


@pytest.mark.parametrize("k,args", [
    (1.5, ("-n", "6")), (3, ("-n", "4", "-gamma", "1e4")),
    (3, ("-n", "4", "-method", "lagrange")), (5, ("-n", "16", "-gamma", "8")),
    (7, ("-n", "8", "-gamma", "1e4")), (7, ("-n", "8", "-method", "lagrange")),
])
def test_a_power_law_s_p0_on_a_coarse_mesh_keeps_the_promise(solve, k, args):
    # a cusp's p0 (k = 1.5) read 0.54% at n = 6 where it was -5.2% (its level pair crossed); the
    # off-axis maximum of k = 3 read 0.89% at n = 4 where it was +1.2% (second order assumed);
    # the nodal maximum of a zig-zagging peak: k = 3 and 7 at n = 4 and 8 read 0.2% to 0.8% where
    # p0 was +0.9% to +1.15%, k = 5 at n = 16 and 8 E*/h read 0.99% where it was -1.11%
    run = solve("-shape", "power", "-k", str(k), *args)
    s = run.summary
    ref = punch_from_depth("power", 0.02, E, NU, R=R, k=k)
    truth = max(rel(s["p0_fe"], center_or_max_pressure("power", ref.a, R=R, k=k)),
                rel(s["F_fe"], ref.F), rel(s["a_fe"], ref.a))
    truth, estimate = check_promise(run, truth)
    assert estimate >= 0.5 * truth, (truth, estimate)  # exit 5 too


def test_an_off_axis_p0_is_estimated_at_first_order(solve):
    # k = 5 at n = 16 and 8 E*/h: p0 +1.11%, read 1.18% at first order and 1.01% at the second,
    # where one nodal step more would have read it under the bar and exited 0
    run = solve("-shape", "power", "-k", "5", "-n", "16", "-gamma", "8")
    s = run.summary
    ref = punch_from_depth("power", 0.02, E, NU, R=R, k=5)
    truth = rel(s["p0_fe"], center_or_max_pressure("power", ref.a, R=R, k=5))
    assert truth > 0.01 and s["est_err_p0"] >= truth, (truth, s["est_err_p0"])
    assert run.exit_code == 5, run.output


@pytest.mark.parametrize("k,gamma", [("3", "4e5"), ("4", "25600")])
def test_a_plane_power_law_straight_at_a_stiff_penalty_under_load_ends_with_a_row(solve, k, gamma):
    # straight at a stiff penalty under -P, Newton cycles through its active sets (none among them:
    # the plane relations divided by that level's zero force and the run crashed, exit 8, no
    # files); it ends maxiter with its iterations and residual in summary.csv (-cont 1 converges)
    run = solve("-model", "plane", "-shape", "power", "-k", k, "-n", "16", "-gamma", gamma, "-P", "0.03",
                "-method", "newton")
    s = run.summary
    assert run.exit_code == 3 and s["status"] == "maxiter", run.output
    assert s["iterations"] > 0 and math.isfinite(s["residual"])


def test_a_load_step_without_contact_keeps_its_depth_and_ends_with_a_row(solve):
    # from zero straight at 1e4 E*/h under -P, Newton steps off the indenter: a step with no node in
    # contact has no depth response (FD = 0), and the depth update divided by it (exit 8, no
    # files); the depth now waits for a step in contact, and the run ends maxiter with a row
    run = solve("-model", "plane", "-P", "0.03", "-start", "zero", "-gamma", "1e4", "-maxit", "10")
    s, history = run.summary, run.table("history")
    assert (history["active_nodes"] == 0).any(), history  # the scene reaches that step
    assert run.exit_code == 3 and s["status"] == "maxiter", run.output
    assert s["iterations"] == 10 and math.isfinite(s["residual"]) and math.isfinite(s["d_fe"]), s


@pytest.mark.parametrize("k", ["3", "4"])
def test_a_plane_power_law_under_load_with_accuracy_meets_it(solve, k):
    # a stiffened penalty's level lost its contact: the load's depth update (k = 3) and the plane
    # relations (k = 4) divided by its zero force, and the run crashed (exit 8, no files); then,
    # started straight at 6400 E*/h, the level cycled through its active sets and ended maxiter.
    # A stiffened level now approaches its penalty in stages: measured a +0.005% and +0.011%
    run = solve("-accuracy", "0.003", "-method", "newton", "-model", "plane", "-shape", "power", "-k", k,
                "-P", "0.03")
    s = run.summary
    assert run.exit_code == 0 and s["accuracy_predicted"] <= 0.003, run.output
    assert rel(s["a_fe"], plane_half_width("power", 0.03, E, NU, R=R, k=float(k))) <= 0.003


@pytest.mark.parametrize("k", [1.5, 3])
def test_power_law_profiles_match_sneddon(solve, k):
    run = solve("-shape", "power", "-k", str(k))
    s = run.summary
    ref = punch_from_depth("power", 0.02, E, NU, R=R, k=k)
    assert rel(s["F_fe"], ref.F) < 5e-3 and rel(s["a_fe"], ref.a) < 5e-3, s
    p0 = center_or_max_pressure("power", ref.a, R=R, k=k)
    if k == 3:
        # the maximum lies off the axis: measured +0.006%
        assert run.exit_code == 0 and rel(s["p0_fe"], p0) < 5e-3, (s["p0_fe"], p0)
    else:
        # a cusp at the tip (f'' infinite there): p0 converges as h^(k-1), and the run says how far
        # off it is (measured -1.6% at n = 16, estimated 12%: 'inaccurate', never 'converged'; at
        # the second order of a smooth tip the estimate read 1.75%, barely above the truth)
        err = rel(s["p0_fe"], p0)
        assert run.exit_code == 5 and s["est_err_p0"] >= 2 * err, (err, s["est_err_p0"])


@pytest.mark.parametrize("method,tol", [("newton", 3e-3), ("lagrange", 1e-3)])
def test_the_flat_punch_matches_its_exact_force_and_edge(solve, method, tol):
    run = solve("-shape", "punch", "-method", method)
    assert run.exit_code == 0, run.output
    s = run.summary
    F = 2 * ESTAR * 0.1 * 0.02  # Boussinesq's punch: F = 2 E* a d
    # measured: newton F -0.073%, K +0.15%; lagrange F -0.041%, K -0.047%
    assert rel(s["F_fe"], F) < tol and rel(s["K_fe"], flat_punch_edge_coefficient(F, 0.1)) < 2 * tol, s
    assert s["a_fe"] == pytest.approx(0.1, rel=1e-12) and math.isnan(s["p0_fe"])
    assert rel(s["S_fe"], 2 * ESTAR * 0.1) < tol


def test_the_punch_converges_at_its_order_despite_the_edge_singularity(solve):
    # the graded band restores convergence: lagrange F error 0.19%, 0.041%, 0.005% at n = 8, 16, 32
    F = 2 * ESTAR * 0.1 * 0.02
    errors = [rel(solve("-shape", "punch", "-method", "lagrange", "-n", n).summary["F_fe"], F)
              for n in ("8", "16", "32")]
    assert errors[2] < 2e-4 and errors[0] / errors[2] > 16, errors


@pytest.mark.parametrize("shape,geometry", [("sphere", dict(R=R)), ("cone", dict(angle=70.3))])
def test_load_control_finds_the_depth_of_any_shape(solve, shape, geometry):
    run = solve("-shape", shape, "-P", "0.01")
    assert run.exit_code == 0, run.output
    s = run.summary
    ref = punch_from_load(shape, 0.01, E, NU, **geometry)
    # measured: sphere a +0.043%; cone d +0.005%, a +0.034%
    assert s["F_fe"] == pytest.approx(0.01, rel=1e-9)
    assert rel(s["d_fe"], ref.d) < 3e-3 and rel(s["a_fe"], ref.a) < 3e-3, s


def test_load_control_presses_a_punch_to_its_exact_depth(solve):
    s = solve("-shape", "punch", "-P", "0.01").summary
    assert rel(s["d_fe"], 0.01 / (2 * ESTAR * 0.1)) < 3e-3  # measured +0.073%


@pytest.mark.parametrize("shape,args,geometry", [
    ("punch", ("-shape", "punch"), None),
    ("cone", ("-shape", "cone"), dict(angle=70.3)),
    ("power", ("-shape", "power", "-k", "3"), dict(R=R, k=3)),
])
def test_plane_strain_profiles_keep_the_relations_of_their_load(solve, shape, args, geometry):
    # a line contact's depth depends on the domain: only a(P) and the edge K(P) are checked
    run = solve("-model", "plane", *args)
    assert run.exit_code == 0, run.output
    s = run.summary
    P = s["F_fe"]
    if shape == "punch":
        assert rel(s["K_fe"], flat_punch_edge_coefficient(P, 0.1, plane=True)) < 5e-3  # measured +0.15%
    else:
        assert rel(s["a_fe"], plane_half_width(shape, P, E, NU, **geometry)) < 5e-3, s


def write_profile(path, r, f, sep=","):
    path.write_text("r" + sep + "f\n" + "".join(f"{x:.17g}{sep}{y:.17g}\n" for x, y in zip(r, f)))
    return str(path)


@pytest.mark.parametrize("sep", [",", " "])
def test_a_table_of_the_sphere_is_the_sphere(solve, tmp_path, sep):
    r = np.linspace(0, 0.4, 401)
    table = write_profile(tmp_path / "sphere.csv", r, R - np.sqrt(R * R - r * r), sep)
    tab = solve("-shape", "table", "-profile", table, "-d", "0.02")
    assert tab.exit_code == 0, tab.output
    t, s = tab.summary, solve("-shape", "sphere", "-d", "0.02").summary
    # the spline through 401 rows is the cap to about 1e-9: the same contact to 1e-6
    for q in ("p0_fe", "F_fe", "a_fe"):
        assert rel(t[q], s[q]) < 1e-6, (q, t[q], s[q])
    assert t["reference"] == "none" and math.isnan(t["F_hertz"])


def test_a_table_of_a_cone_tip_rounded_by_a_sphere(solve, tmp_path):
    # a Berkovich-like cone whose tip is a sphere of radius 0.05, met tangentially: a profile with
    # no closed form, against the MDR integrals of its own slope
    rho, alpha = 0.05, math.radians(70.3)
    r_t = rho * math.cos(alpha)  # where the cap meets the cone
    r = np.linspace(0, 0.3, 3001)
    cap = rho - np.sqrt(rho * rho - np.minimum(r, r_t) ** 2)
    f = np.where(r <= r_t, cap, cap[-1] + (r - r_t) / math.tan(alpha))
    run = solve("-shape", "table", "-profile", write_profile(tmp_path / "tip.csv", r, f), "-d", "0.02")
    assert run.exit_code == 0, run.output
    s = run.summary

    def slope(x):
        return x / math.sqrt(rho * rho - x * x) if x < r_t else 1 / math.tan(alpha)
    ref = profile_from_depth(slope, 0.02, ESTAR, 0.3)
    # measured F -0.010%, a +0.027% (estimated 0.069%)
    assert rel(s["F_fe"], ref.F) < 5e-3 and rel(s["a_fe"], ref.a) < 5e-3, (s["F_fe"], ref.F, s["a_fe"], ref.a)
    # blunter than the sharp cone: the missing tip lets the flanks in deeper at the same depth
    assert s["a_fe"] > punch_from_depth("cone", 0.02, E, NU, angle=70.3).a


def test_a_table_that_stays_flat_then_rises_has_no_dip(solve, tmp_path):
    # a cubic spline through these rows dips to -0.0084 at r = 0.16 (a deeper indenter than the
    # table); Steffen's spline has no extrema between rows, so the flat part is a punch's face
    table = write_profile(tmp_path / "kink.csv", [0, 0.1, 0.2, 0.3, 0.4, 0.5], [0, 0, 0, 0.1, 0.2, 0.3])
    s = solve("-shape", "table", "-profile", table, "-d", "0.02").summary
    flat = 2 * ESTAR * 0.2 * 0.02  # the flat face alone, radius 0.2, pressed to d
    assert flat < s["F_fe"] < 1.1 * flat, s["F_fe"]


def bad_tables(tmp_path):
    return {
        "unsorted": write_profile(tmp_path / "u.csv", [0, 0.2, 0.1, 0.3, 0.4], [0, 0.01, 0.02, 0.03, 0.04]),
        "not at 0": write_profile(tmp_path / "z.csv", [0.1, 0.2, 0.3, 0.4], [0, 0.01, 0.02, 0.03]),
        "offset": write_profile(tmp_path / "o.csv", [0, 0.1, 0.2, 0.3], [0.01, 0.02, 0.03, 0.04]),
        "short": write_profile(tmp_path / "s.csv", [0, 0.1, 0.2], [0, 0.01, 0.04]),
        "low": write_profile(tmp_path / "l.csv", [0, 0.1, 0.2, 0.3], [0, 0.001, 0.002, 0.003]),
        "words": str(tmp_path / "w.csv"),
    }


@pytest.mark.parametrize("args,option", [
    (["-shape", "ball"], "-shape"), (["-shape", "cone", "-angle", "0"], "-angle"),
    (["-shape", "cone", "-angle", "90"], "-angle"), (["-shape", "punch", "-a", "0"], "-a"),
    (["-shape", "power", "-k", "0.5"], "-k"), (["-shape", "power", "-k", "1"], "-k"),
    (["-shape", "sphere", "-d", "0.6"], "-d"),
    (["-angle", "60"], "-angle"), (["-shape", "cone", "-R", "1"], "-R"), (["-a", "0.2"], "-a"),
    (["-shape", "sphere", "-Rx", "1", "-Ry", "2"], "-Rx"), (["-shape", "table"], "-profile"),
    (["-shape", "table", "-profile", "/nonexistent.csv"], "-profile"),
    (["-shape", "cone", "-model", "3d"], "-model"), (["-shape", "sphere", "-P", "1e3"], "-P"),
], ids=lambda v: " ".join(v) if isinstance(v, list) else v)
def test_bad_shape_input_is_one_line_naming_the_option(solve, args, option):
    run = solve(*args)
    assert run.exit_code == 2, run.output
    errors = run.stderr.strip().splitlines()
    assert len(errors) == 1 and errors[0].startswith("hertz.edp: error:") and option in errors[0], run.output


@pytest.mark.parametrize("case", ["unsorted", "not at 0", "offset", "short", "low", "words"])
def test_bad_profiles_are_refused_with_the_reason(solve, tmp_path, case):
    tables = bad_tables(tmp_path)
    (tmp_path / "w.csv").write_text("r,f\n0,0\nzero,one\n0.2,0.1\n0.3,0.2\n")
    run = solve("-shape", "table", "-profile", tables[case], "-d", "0.02")
    errors = run.stderr.strip().splitlines()
    assert run.exit_code == 2 and len(errors) == 1 and "-profile" in errors[0], run.output


def test_a_table_is_bounded_before_it_is_read(solve, tmp_path):
    # the reader takes about 0.5 ms a row: a million rows took minutes, -check included
    r = np.linspace(0, 0.4, 10001)
    rows = solve("-shape", "table", "-profile", write_profile(tmp_path / "rows.csv", r, r * r), "-check", "1")
    errors = rows.stderr.strip().splitlines()
    assert rows.exit_code == 2 and len(errors) == 1 and "more than 10000 rows" in errors[0], rows.output
    big = tmp_path / "big.csv"
    big.write_text("0,0\n" + "1" * 1_000_001 + ",1\n")
    start = time.perf_counter()
    run = solve("-shape", "table", "-profile", str(big), "-check", "1")
    errors = run.stderr.strip().splitlines()
    assert run.exit_code == 2 and len(errors) == 1 and "above 1000000 bytes" in errors[0], run.output
    assert time.perf_counter() - start < 5
    # the largest table it reads is read
    ok = solve("-shape", "table", "-profile", write_profile(tmp_path / "ok.csv", r[:-1], r[:-1] ** 2), "-check", "1")
    assert ok.exit_code == 0 and "options ok" in ok.stdout, ok.output


@pytest.mark.parametrize("args,target", [(("-shape", "sphere", "-d", "0.05"), "0.002"),
                                         (("-shape", "cone",), "0.005"), (("-shape", "punch",), "0.005")])
def test_accuracy_holds_by_the_truth_for_other_shapes(solve, args, target):
    run = solve(*args, "-accuracy", target)
    assert run.exit_code == 0, run.output
    s = run.summary
    shape = args[1]
    if shape == "punch":
        F = 2 * ESTAR * 0.1 * 0.02
        truth = max(rel(s["F_fe"], F), rel(s["K_fe"], flat_punch_edge_coefficient(F, 0.1)))
    else:
        ref = punch_from_depth(shape, s["d"], E, NU, **GEOMETRY[shape])
        truth = max(rel(s["F_fe"], ref.F), rel(s["a_fe"], ref.a))
    assert truth <= float(target) and s["accuracy_predicted"] <= float(target), (truth, s["accuracy_predicted"])


# Random scenes of every shape, coarse meshes, nu near 1/2 and penalties from moderate to stiff
# included: a run either says it is off (exit 5) or its error (p0 too, where it is finite) is
# within 1% and at most twice its own estimate. (A power law k = 3 at 5 E*/h exited 0 with p0
# -1.02% against an estimate of 0.78%: its penalty and Richardson parts cancelled.)
shape_scenes = st.fixed_dictionaries({
    "shape": st.sampled_from(["sphere", "cone", "power", "punch"]),
    "nu": st.floats(-0.5, 0.4999).map(lambda x: float(f"{x:.4g}")),
    "n": st.sampled_from([4, 5, 6, 8, 12, 16, 24]),
    "method": st.sampled_from(["newton", "lagrange"]),
    "gamma": st.sampled_from(["3", "5", "10", "100"]),
    "d_over_R": st.floats(1e-3, 0.3).map(lambda x: float(f"{x:.3g}")),
    "angle": st.floats(45, 85).map(lambda x: float(f"{x:.4g}")),
    "k": st.floats(1.2, 4).map(lambda x: float(f"{x:.3g}")),
})


@settings(max_examples=24, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(shape_scenes)
def test_random_shape_scenes_keep_the_promise(solve, sc):
    shape, nu, d = sc["shape"], sc["nu"], sc["d_over_R"] * R
    extra = {"cone": ["-angle", repr(sc["angle"])], "power": ["-k", repr(sc["k"])]}.get(shape, [])
    penalty = ["-gamma", sc["gamma"]] if sc["method"] == "newton" else []
    run = solve("-shape", shape, "-nu", repr(nu), "-d", repr(d), "-n", str(sc["n"]),
                "-method", sc["method"], *penalty, *extra)
    assert run.exit_code in (0, 5), run.output
    s = run.summary
    if shape == "punch":
        F = 2 * estar(E, nu) * 0.1 * d
        truth = max(rel(s["F_fe"], F), rel(s["K_fe"], flat_punch_edge_coefficient(F, 0.1)))
    else:
        geometry = {"sphere": dict(R=R), "cone": dict(angle=sc["angle"]), "power": dict(R=R, k=sc["k"])}[shape]
        ref = punch_from_depth(shape, d, E, nu, **geometry)
        truth = max(rel(s["F_fe"], ref.F), rel(s["a_fe"], ref.a))
        if shape != "cone":  # a cone's pressure is singular at its tip
            truth = max(truth, rel(s["p0_fe"], center_or_max_pressure(shape, ref.a, estar(E, nu), **geometry)))
    check_promise(run, truth)


def test_the_parabola_s_sphere_estimate_is_sneddon_s_expansion(solve):
    # the parabola run's own figure for a sphere of its radius against the two runs' difference
    par = solve("-d", "0.01", "-R", "0.5").summary
    ref_sphere = punch_from_depth("sphere", 0.01, E, NU, R=R)
    hz = sphere(E, NU, R, 0.01)
    assert par["parabola_error"] == pytest.approx(max(rel(ref_sphere.F, hz.F), rel(ref_sphere.a, hz.a)), rel=0.1)


@pytest.mark.parametrize("args", [("-method", "lagrange"), ("-gamma", "0.5"), ()])
def test_a_p1_plane_wedge_is_solved_and_says_how_far_off(solve, args):
    # P1's nodal contact of a plane wedge on level 0 peeled to its tip alone (a contact radius of
    # 4e-10): lagrange ended unmeasured, a penalty was refused with a wrong range, and at 0.5 E*/h
    # the fine band lay beyond the fine zone and the mesher crashed; level 0 now keeps the overlap
    # radius when its edge is below half an element (measured: a -20%, estimated 50%)
    run = solve("-order", "1", "-model", "plane", "-shape", "cone", *args)
    assert run.exit_code == 5, run.output
    s = run.summary
    err = rel(s["a_fe"], plane_half_width("cone", s["F_fe"], E, NU, **GEOMETRY["cone"]))
    assert s["status"] == "inaccurate" and s["est_err_a"] >= 0.5 * err, (err, s["est_err_a"])
