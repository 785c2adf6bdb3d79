"""hertz.edp against Hertz theory, between methods, and on bad input."""
import math

import numpy as np
import pytest

from driver.schema import SUMMARY_COLUMNS

E, NU, R, D = 10.0, 0.3, 0.5, 0.02
ESTAR = E / (1 - NU**2)


def test_default_case_within_one_percent_of_hertz(solve):
    run = solve()
    assert run.exit_code == 0, run.output
    s = run.summary
    assert s["status"] == "converged"
    # independent Hertz values (HERTZ.md), not the script's own
    a = math.sqrt(R * D)
    F = 4 / 3 * ESTAR * a * D
    p0 = 3 * F / (2 * math.pi * a**2)
    assert s["a_fe"] == pytest.approx(a, rel=0.01)
    assert s["F_fe"] == pytest.approx(F, rel=0.01)
    assert s["p0_fe"] == pytest.approx(p0, rel=0.01)
    assert "Maximum pressure FE:" in run.output and "Applied force FE:" in run.output


def test_summary_columns_match_the_documented_schema(solve):
    header = (solve().outdir / "summary.csv").read_text().splitlines()[0].split(",")
    assert header == SUMMARY_COLUMNS


def test_p2_beats_p1_at_the_same_mesh(solve):
    errors = {}
    for order in ("1", "2"):
        s = solve("-order", order, "-n", "8").summary
        errors[order] = max(abs(s["err_p0"]), abs(s["err_F"]), abs(s["err_a"]))
    assert errors["2"] < errors["1"] / 3, errors


def test_penetration_scales_as_one_over_kpen(solve):
    kpens = [1e4, 1e5, 1e6, 1e7]
    pen = [solve("-kpen", f"{k:g}").summary["max_penetration"] for k in kpens]
    product = np.array(pen) * np.array(kpens)
    # penetration * kpen is the peak pressure: constant within 2%
    assert product.max() / product.min() < 1.02, product
    # and close to the Hertz peak pressure
    assert product.mean() == pytest.approx(2 * ESTAR * math.sqrt(R * D) / (math.pi * R), rel=0.02)


def test_newton_and_fixed_point_agree_where_both_converge(solve):
    common = ("-kpen", "30", "-tol", "1e-11")
    newton = solve(*common, "-method", "newton").summary
    fixed = solve(*common, "-method", "fixedpoint").summary
    assert newton["status"] == fixed["status"] == "converged"
    for key in ("p0_fe", "F_fe", "a_fe", "max_penetration"):
        assert fixed[key] == pytest.approx(newton[key], rel=1e-6), key


def test_fixed_point_reports_divergence_at_large_kpen(solve):
    run = solve("-method", "fixedpoint", "-kpen", "1e4")
    assert run.exit_code == 3, run.output
    s = run.summary
    assert s["status"] == "diverged"
    assert s["iterations"] < 200  # stopped early, did not run to maxiter
    assert s["kpen_critical"] < 1e4  # and theory agrees that 1e4 is beyond the limit
    assert "did not converge" in run.output


def test_newton_converges_across_penalties_in_few_iterations(solve):
    for k in ("1e1", "1e3", "1e5", "1e7", "1e9"):
        s = solve("-kpen", k).summary
        assert s["status"] == "converged", k
        assert s["iterations"] <= 10, (k, s["iterations"])


def test_plane_strain_satisfies_the_line_contact_relations(solve):
    s = solve("-model", "plane").summary
    assert s["status"] == "converged"
    a, P, p0 = s["a_fe"], s["F_fe"], s["p0_fe"]
    assert p0 == pytest.approx(ESTAR * a / (2 * R), rel=0.01)
    assert a == pytest.approx(math.sqrt(4 * P * R / (math.pi * ESTAR)), rel=0.01)
    assert p0 == pytest.approx(2 * P / (math.pi * a), rel=0.01)
    assert math.isnan(s["F_hertz"])  # no depth-based reference in 2D


def test_pressure_profile_follows_hertz(solve):
    profile = solve().table("profile")
    a = math.sqrt(R * D)
    inside = profile[profile["r"] < 0.9 * a]
    p0 = profile["p_hertz"].max()
    assert np.abs(inside["p_fe"] - inside["p_hertz"]).max() < 0.01 * p0
    outside = profile[profile["r"] > 1.1 * a]
    assert (outside["p_point"] == 0).all()
    # the projected pressure rings a little beyond the edge (sqrt profile)
    assert (outside["p_fe"].abs() < 5e-3 * p0).all()
    assert (outside["gap"] > 0).all()


def test_axis_stresses_match_hertz(solve):
    axis = solve().table("axis")
    p0 = axis["sigma_z_hertz"].abs().max()
    zone = axis[(axis["depth_over_a"] > 0.1) & (axis["depth_over_a"] < 3)]
    assert np.abs(zone["sigma_z"] - zone["sigma_z_hertz"]).max() < 0.01 * p0
    peak = axis.loc[axis["tau_max"].idxmax()]
    assert peak["tau_max"] / p0 == pytest.approx(0.31, abs=0.005)  # Johnson: 0.31 p0
    assert peak["depth_over_a"] == pytest.approx(0.48, abs=0.03)   # at 0.48 a


def test_augmented_lagrangian_removes_penetration(solve):
    s = solve("-method", "auglag").summary
    assert s["status"] == "converged"
    assert s["nodal_penetration_over_d"] < 1e-6
    assert s["penetration_over_d"] < 1e-6  # on this mesh r = a is a node: no bulge
    assert abs(s["err_F"]) < 0.005 and abs(s["err_p0"]) < 0.005
    # the pointwise pressure includes the multiplier: <lambda + kpen (u_z - h)>_+
    assert s["p0_point"] == pytest.approx(s["p0_fe"], rel=0.01)


@pytest.mark.parametrize("args", [(), ("-method", "auglag"), ("-model", "plane"), ("-n", "32")])
def test_active_set_changes_reuse_the_first_factorization(solve, args):
    # later steps solve with preconditioned CG on the first factorization
    s = solve(*args).summary
    assert s["status"] == "converged"
    assert s["iterations"] >= 3 and s["factorizations"] == 1


def test_vtk_file_holds_the_fields(solve, tmp_path):
    vtk = tmp_path / "fields.vtk"
    run = solve("-n", "4", "-vtk", str(vtk))
    assert run.exit_code == 0, run.output
    text = vtk.read_text(errors="replace")
    for name in ("displacement", "sigma_zz", "von_mises", "pressure"):
        assert name in text


BAD_INPUTS = [
    (["-kpen", "-1"], "-kpen"), (["-kpen", "0"], "-kpen"), (["-kpen", "abc"], "-kpen"),
    (["-kpen", "1e5x"], "-kpen"), (["-E", "0"], "-E"), (["-E", "nan"], "-E"),
    (["-nu", "0.5"], "-nu"), (["-nu", "-1"], "-nu"), (["-R", "-0.5"], "-R"),
    (["-d", "0"], "-d"), (["-d", "0.5"], "-d"), (["-n", "1"], "-n"), (["-n", "2.5"], "-n"),
    (["-order", "3"], "-order"), (["-model", "sphere"], "-model"),
    (["-method", "lagrange"], "-method"), (["-omega", "0"], "-omega"),
    (["-omega", "2.5"], "-omega"), (["-L", "5"], "-L"), (["-L", "inf"], "-L"),
    (["-kpn", "1e5"], "-kpn"), (["-kpen"], "-kpen"), (["-kpen", "1e5", "-kpen", "1e6"], "-kpen"),
    (["-maxit", "0"], "-maxit"), (["-tol", "1"], "-tol"), (["-cont", "2"], "-cont"),
    (["-out", "/proc/forbidden"], "-out"), (["-accuracy", "0.5"], "-accuracy"),
    (["-accuracy", "0.01", "-n", "8"], "-n"),
]


@pytest.mark.parametrize("args,option", BAD_INPUTS, ids=[" ".join(a) for a, _ in BAD_INPUTS])
def test_bad_input_is_rejected_with_a_message_naming_the_option(solve, args, option):
    run = solve(*args)
    assert run.exit_code == 2, run.output
    errors = [ln for ln in run.output.splitlines() if ln.startswith("hertz.edp: error:")]
    assert len(errors) == 1 and option in errors[0], run.output
    assert not run.outdir.exists() or not any(run.outdir.iterdir())  # nothing written


@pytest.mark.parametrize("target", ["0.01", "0.003"])
def test_accuracy_preset_reaches_its_target(solve, target):
    run = solve("-accuracy", target)
    assert run.exit_code == 0, run.output
    s = run.summary
    achieved = max(abs(s["err_p0"]), abs(s["err_F"]), abs(s["err_a"]))
    assert achieved <= float(target), (achieved, s["accuracy_predicted"])
    assert s["accuracy_predicted"] <= float(target)
    assert s["order"] == 2 and "achieved max error" in run.output


def test_fixed_point_limit_scales_with_estar_over_a_not_with_the_mesh(solve):
    def limit(*args):
        return solve("-method", "fixedpoint", "-kpen", "1", *args).summary["kpen_critical"]
    base = limit("-n", "8")
    assert limit("-n", "16") == pytest.approx(base, rel=0.01)        # h halves: unchanged
    assert limit("-n", "8", "-E", "100") == pytest.approx(10 * base, rel=0.01)  # x E*
    # d x4 doubles a: the limit halves (mu is the compliance of the smoothest mode, ~ a/E*)
    assert limit("-n", "8", "-d", "0.08") == pytest.approx(base / 2, rel=0.03)
