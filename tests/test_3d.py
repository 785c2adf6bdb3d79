"""3D: ellipsoids against elliptical Hertz (written again in hertz_reference.py),
the sphere in 3D against its exact axisymmetric model, and -model auto.

Each 3D run takes 2 to 30 s on 2 cores; the mesh is the 2D section revolved and
stretched to the contact ellipse, so doubling n refines every element (README, 3D).
"""
import math
import shutil
import subprocess

import numpy as np
import promise
import pytest

from driver import freefem

from hertz_reference import SEED, ellipsoid_from_depth, ellipsoid_from_load, sphere

# The worked check of the issue (SI): Rx = 10 mm, Ry = 40 mm, steel, P = 100 N.
WORKED = dict(E=210e9, nu=0.3, Rx=0.010, Ry=0.040)


def seed_ellipse_errors(s: dict, Rx: float, Ry: float) -> dict[str, float]:
    """Relative errors of p0, F and the semi-axes along x (a) and y (b) against elliptical Hertz
    at the seed's depth: the short axis lies along the larger curvature (the smaller radius)."""
    ref = ellipsoid_from_depth(SEED["d"], SEED["E"], SEED["nu"], min(Rx, Ry), max(Rx, Ry))
    along_x, along_y = (ref.b_short, ref.a_long) if Rx <= Ry else (ref.a_long, ref.b_short)
    return {"p0": s["p0_fe"] / ref.p0 - 1, "F": s["F_fe"] / ref.P - 1,
            "a": s["a_fe"] / along_x - 1, "b": s["b_fe"] / along_y - 1}


def test_the_reference_meets_the_worked_elliptical_check():
    e = ellipsoid_from_load(100.0, WORKED["E"], WORKED["nu"], WORKED["Rx"], WORKED["Ry"])
    assert e.a_long == pytest.approx(0.28772e-3, rel=2e-5)
    assert e.b_short == pytest.approx(0.11506e-3, rel=5e-5)
    assert e.p0 == pytest.approx(1442.3e6, rel=5e-5)
    assert e.d == pytest.approx(1.697e-6, rel=5e-4)


def test_the_reference_reduces_to_the_sphere():
    e = ellipsoid_from_depth(SEED["d"], SEED["E"], SEED["nu"], SEED["R"] * (1 - 1e-9), SEED["R"])
    s = sphere(**SEED)
    assert e.a_long == pytest.approx(s.a, rel=1e-4)
    assert e.p0 == pytest.approx(s.p0, rel=1e-4)
    assert e.P == pytest.approx(s.F, rel=1e-4)


@pytest.fixture(scope="module")
def worked(solve):
    """The worked scene in SI at its Hertz approach, -model auto (an ellipsoid: 3d)."""
    return solve("-E", "210e9", "-nu", "0.3", "-Rx", "0.01", "-Ry", "0.04", "-d", "1.697e-6")


def test_an_ellipsoid_is_solved_in_3d_within_2_percent_of_elliptical_hertz(worked):
    assert worked.exit_code == 0, worked.output
    s = worked.summary
    assert s["model"] == "3d" and s["status"] == "converged"
    assert "model auto: an ellipsoid" in worked.stdout
    ref = ellipsoid_from_depth(1.697e-6, WORKED["E"], WORKED["nu"], WORKED["Rx"], WORKED["Ry"])
    # the solver's own references (hertz.idp) agree with the independent ones
    assert s["a_hertz"] == pytest.approx(ref.b_short, rel=1e-6)  # x: the smaller radius, the short axis
    assert s["b_hertz"] == pytest.approx(ref.a_long, rel=1e-6)
    assert s["p0_hertz"] == pytest.approx(ref.p0, rel=1e-6)
    assert s["F_hertz"] == pytest.approx(ref.P, rel=1e-6)
    # measured within 0.5% at the default n = 8 (the long axis: its elements are stretched)
    assert s["p0_fe"] == pytest.approx(ref.p0, rel=0.02)
    assert s["F_fe"] == pytest.approx(ref.P, rel=0.02)
    assert s["a_fe"] == pytest.approx(ref.b_short, rel=0.02)
    assert s["b_fe"] == pytest.approx(ref.a_long, rel=0.02)
    assert s["memory_mb"] > 50 and s["t_total"] > 0


def test_the_outline_and_both_profiles_follow_the_hertz_ellipse(worked):
    outline = worked.table("outline")
    fe = np.hypot(outline["x"], outline["y"])
    hz = np.hypot(outline["x_hertz"], outline["y_hertz"])
    assert len(outline) >= 10 and outline["theta_deg"].iloc[-1] == pytest.approx(90)
    assert np.all(np.abs(fe / hz - 1) < 0.03), (fe / hz - 1).tolist()
    s = worked.summary
    for name, edge in (("profile", s["a_hertz"]), ("profile_y", s["b_hertz"])):
        p = worked.table(name)
        inside = p[p["r"] < 0.8 * edge]
        # the pressure along each axis against p0 sqrt(1 - (r/edge)^2)
        assert np.max(np.abs(inside["p_fe"] - inside["p_hertz"])) < 0.03 * s["p0_hertz"], name
        assert abs(p["p_fe"].iloc[-1]) < 1e-9 * s["p0_hertz"], name  # open beyond the edge


def test_a_sphere_in_3d_agrees_with_its_axisymmetric_model(solve):
    axi, full = solve().summary, solve("-model", "3d").summary
    assert full["model"] == "3d" and full["status"] == "converged" and full["n"] == 8
    # the same scene: 3D at n = 8 against axi at n = 16 (0.03%); measured p0 +0.17%, the
    # rest within 0.08%
    for column in ("p0_fe", "F_fe", "a_fe"):
        assert full[column] == pytest.approx(axi[column], rel=0.005), column
    # round in 3D too: the mesh is symmetric about x = y up to the split of its prisms
    # (a box refined by TetGen read -0.43% along x and -0.02% along y); measured 0.08%
    assert full["b_fe"] == pytest.approx(full["a_fe"], rel=0.003)
    # over-modelling costs: more dofs and memory for the same answer
    assert full["ndof"] > 3 * axi["ndof"] and full["memory_mb"] > axi["memory_mb"]


def test_a_stiff_penalty_reads_both_semi_axes_of_an_ellipse(solve):
    """At gamma = 1e3 the nodes just inside the edge stand barely open between the
    penalty's quadrature points; the edge fit reads past them (it read a 1.9% short)."""
    run = solve("-Rx", "0.5", "-Ry", "2", "-gamma", "1e3")
    s = run.summary
    # (the long axis's estimate, about 1%, may call the run inaccurate: exit 5)
    assert run.exit_code in (0, 5) and s["status"] in ("converged", "inaccurate"), run.output
    ref = ellipsoid_from_depth(SEED["d"], SEED["E"], SEED["nu"], 0.5, 2.0)
    # measured a -0.04%, b -0.42% (the long axis), estimates 0.2% and 0.7%
    assert s["a_fe"] == pytest.approx(ref.b_short, rel=0.008)
    assert s["b_fe"] == pytest.approx(ref.a_long, rel=0.008)
    for axis, ref_axis in (("a", ref.b_short), ("b", ref.a_long)):
        assert abs(s[f"{axis}_fe"] / ref_axis - 1) <= 2 * s[f"est_err_{axis}"], axis


def test_lagrange_in_3d_is_nodally_exact(solve):
    run = solve("-model", "3d", "-method", "lagrange")
    s = run.summary
    assert run.exit_code == 0 and s["status"] == "converged", run.output
    assert abs(s["nodal_penetration_over_d"]) <= 1e-10
    ref = sphere(**SEED)
    assert s["F_fe"] == pytest.approx(ref.F, rel=0.02) and s["p0_fe"] == pytest.approx(ref.p0, rel=0.02)


@pytest.mark.parametrize("args, model, why", [
    ((), "axi", "a sphere"),
    (("-Ry", "inf"), "plane", "a cylinder"),
])
def test_model_auto_never_models_more_than_the_scene_needs(solve, args, model, why):
    run = solve(*args)
    assert run.summary["model"] == model
    assert f"model auto: {why}" in run.stdout


def test_the_3d_vtk_file_holds_the_fields(solve, tmp_path_factory):
    path = tmp_path_factory.mktemp("vtk") / "sphere3d.vtu"
    run = solve("-model", "3d", "-n", "3", "-vtk", str(path))
    assert run.exit_code in (0, 5), run.output
    volume = path.read_text(errors="replace")
    surface = path.with_name("sphere3d_surface.vtu").read_text(errors="replace")
    assert '<VTKFile type="UnstructuredGrid"' in volume and volume.rstrip().endswith("</VTKFile>")
    for field in ("displacement", "sigma_zz", "von_mises"):
        assert f'Name="{field}"' in volume, field
    assert 'Name="pressure"' in surface and path.with_name("sphere3d_near.vtu").exists()
    assert math.isfinite(run.summary["p0_fe"])


@pytest.mark.parametrize("ratio,model", [(1 + 1e-7, "axi"), (1.005, "axi"), (1.1, "3d")])
def test_model_auto_chooses_by_the_error_of_the_simpler_model(solve, ratio, model):
    # the axisymmetric model with R = sqrt(Rx Ry) is off by about ln(Ry/Rx)/3 on the semi-axes:
    # it is chosen while that is below a third of the 1% bar
    run = solve("-Rx", "0.5", "-Ry", repr(0.5 * ratio), "-check", "1")
    assert run.exit_code == 0 and "model auto: an ellipsoid with Ry/Rx" in run.stdout, run.output
    assert ("axisymmetric model with R = sqrt(Rx Ry) is off" in run.stdout) == (model == "axi")


def test_a_nearly_round_ellipsoid_is_solved_axisymmetric_in_a_fraction_of_a_second(solve):
    import time
    start = time.perf_counter()
    run = solve("-Rx", "0.5", "-Ry", repr(0.5 * (1 + 1e-7)))
    assert time.perf_counter() - start < 2  # measured 0.29 s (3D: about 9 s)
    s = run.summary
    assert run.exit_code == 0 and s["model"] == "axi"
    ref = ellipsoid_from_depth(SEED["d"], SEED["E"], SEED["nu"], 0.5, 0.5 * (1 + 1e-7))
    assert s["a_fe"] == pytest.approx(ref.b_short, rel=1e-3) and s["b_fe"] == pytest.approx(ref.a_long, rel=1e-3)


def test_the_axisymmetric_model_of_an_ellipsoid_estimates_its_own_error(solve):
    # Ry/Rx = 1.1 asked for as axi: the semi-axes are 3.2% off and the estimate says so
    s = solve("-Rx", "0.5", "-Ry", "0.55", "-model", "axi", "-method", "lagrange").summary
    truth = max(abs(s["err_a"]), abs(s["err_b"]))
    assert s["status"] == "inaccurate" and 0.02 < truth < 0.05
    assert truth / 1.5 < s["accuracy_predicted"] < 1.5 * truth


def test_the_estimate_reads_the_long_semi_axis_along_x_as_along_y(solve):
    """Ry/Rx = 1/4: the long axis lies along x, where the edge is read on the plane
    y = 0. Its mesh error falls slower than first order from n = 4 to 8, and the
    penalty's part of a (+delta) cancelled half of its Richardson part when the
    parts were added with their signs: the estimate read 0.16% (floored to 0.20%)
    where the truth was 0.44%. Every estimate holds at least half its truth."""
    run = solve("-Rx", "2", "-Ry", "0.5")
    s = run.summary
    assert run.exit_code == 0 and s["model"] == "3d" and s["n"] == 8, run.output
    truth = seed_ellipse_errors(s, 2.0, 0.5)  # the long axis along x
    # measured: a -0.44% (estimate 0.41%), b +0.18%, p0 -0.09%, F +0.04%
    assert abs(truth["a"]) > 0.003, truth
    for q, err in truth.items():
        assert abs(err) <= 2 * s[f"est_err_{q}"], (q, err, s[f"est_err_{q}"])


@pytest.mark.parametrize("radii", [(0.5, 0.5), (0.5, 2.0), (2.0, 0.5)], ids=["sphere", "Ry=4Rx", "Rx=4Ry"])
def test_a_coarse_3d_run_keeps_its_far_field_and_its_estimate(solve, radii):
    """n = 6 (the partner n = 3). The far field grows at 0.2 on both levels (fe/section.idp),
    so Richardson cannot see its error: that error must stay small. Grown at 0.3, F was +0.17%,
    +0.26% and +0.43%, the last one read as 0.30%."""
    Rx, Ry = radii
    run = solve("-model", "3d", "-Rx", repr(Rx), "-Ry", repr(Ry), "-n", "6")
    s = run.summary
    assert s["model"] == "3d" and s["n"] == 6 and run.exit_code in (0, 5), run.output
    truth = seed_ellipse_errors(s, Rx, Ry)
    assert abs(truth["F"]) < 0.0012, truth  # measured -0.004%, +0.065%, +0.046%
    for q, err in truth.items():  # every estimate holds its truth (the promise's factor 2)
        assert abs(err) <= 2 * s[f"est_err_{q}"], (q, err, s[f"est_err_{q}"])


def test_a_3d_estimate_reads_a_resolved_semi_axis_and_p0_at_second_order(solve):
    """The sphere's semi-axes in 3D converge as p0 does (n = 4 to 8: b -0.69% to +0.07%): read
    at first order against n = 4 they over-read 3.9 times (b 0.76%, where the largest error
    was p0's 0.20%); the pair (3, 6) over-read p0 at order 1.5 (0.96%, where n = 6 is within
    0.07% and the same scene under lagrange +0.30%). An unresolved long axis stays at
    first order."""
    s = solve("-model", "3d").summary
    errors = seed_ellipse_errors(s, SEED["R"], SEED["R"])
    truth = max(abs(e) for e in errors.values())
    assert truth > 1e-3  # measured 0.196% (p0)
    assert 0.5 <= s["accuracy_predicted"] / truth <= 3, (s["accuracy_predicted"], errors)
    assert s["est_err_b"] <= 0.4e-2  # measured 0.31%
    coarse = solve("-model", "3d", "-Rx", "0.5", "-Ry", "0.5", "-n", "6").summary  # the coarse test's run
    assert coarse["est_err_p0"] <= 0.7e-2  # measured 0.53%
    # the long axis of Ry/Rx = 4 (tipN = 1.3) stays at first order: under exact contact it is
    # -0.65%, read 0.75% (at second order 0.31%)
    ellipse = solve("-Rx", "0.5", "-Ry", "2", "-method", "lagrange").summary
    b = seed_ellipse_errors(ellipse, 0.5, 2.0)["b"]
    assert abs(b) > 3e-3 and ellipse["est_err_b"] >= abs(b), (b, ellipse["est_err_b"])


@pytest.mark.parametrize("method", ["newton", "lagrange"])
def test_a_3d_sphere_at_n_4_keeps_the_promise(solve, method):
    """n = 4 pairs with n = 2, which is not asymptotic: its Richardson part is read at first
    order (solve/estimate.idp)."""
    run = solve("-model", "3d", "-method", method, "-n", "4")
    s = run.summary
    assert s["model"] == "3d" and s["n"] == 4, run.output
    errors = seed_ellipse_errors(s, SEED["R"], SEED["R"])
    truth = max(abs(errors[q]) for q in ("p0", "F", "a"))
    assert truth > 0.009  # measured +0.92% and +1.43% on p0: the promise is at stake
    promise.check_promise(run, truth)
    # read at first order the estimate holds the whole of p0's error (measured 1.90% and 1.83%);
    # at 1.5 it read 1.00% of lagrange's 1.43%, an exit 5 by a hair
    assert s["est_err_p0"] >= abs(errors["p0"]), (s["est_err_p0"], truth)


@pytest.mark.parametrize("method", ["newton", "lagrange", "uzawa"])
def test_a_3d_level_factorizes_once_and_solves_every_step_exactly(solve, method):
    # K is factorized once per level with the contact surface's u_z dofs last
    # (edp/plugin/surfaceschur.cpp); a new active set is a dense Cholesky of the Schur
    # complement there, so each step's CG ends after one re-solve, and the responses take one
    # each. Before, CG preconditioned by an older factorization spent its budget of 22 re-solves
    # on the 70 rows a step changes at the edge, and the level factorized again (the ellipsoid
    # Ry/Rx = 4 at n = 8: 2 factorizations and 47 re-solves on its fine level, 4 on the coarser)
    run = solve("-Rx", "0.5", "-Ry", "1", "-n", "4", "-method", method)
    s = run.summary
    assert run.exit_code in (0, 5) and s["status"] in ("converged", "inaccurate"), run.output
    assert s["factorizations"] == 1 and s["coarse_factorizations"] == 2, s
    # at most a re-solve for the step and one for each response (uzawa: its inner Newton steps)
    assert s["resolves"] <= 3 * s["iterations"] + 3, s
    errors = seed_ellipse_errors(s, 0.5, 1)
    assert max(abs(e) for e in errors.values()) < 0.03, errors  # n = 4: within 3% of Hertz


def test_a_3d_run_whose_solver_plugin_does_not_build_says_so_in_one_line(tmp_path):
    # a checkout without the built plugin builds it on its first 3D run (edp/plugin/build.sh);
    # when that fails (here a broken source), the run names the plugin and what building it needs,
    # where FreeFEM alone would print its own "Load error" lines
    copy = tmp_path / "edp"
    shutil.copytree(freefem.EDP_DIR, copy, ignore=shutil.ignore_patterns("*.so", "*.o"))
    (copy / "plugin" / "surfaceschur.cpp").write_text("not C++\n")
    proc = subprocess.run(["FreeFem++", "-nw", "-v", "0", str(copy / "hertz.edp"), "-model", "3d", "-n", "3"],
                          capture_output=True, text=True, cwd=tmp_path, env=freefem.freefem_env(), timeout=120)
    said = [line for line in (proc.stdout + proc.stderr).splitlines() if line.startswith("hertz.edp:")]
    assert proc.returncode == 2, proc.stdout + proc.stderr
    assert len(said) == 1 and "surfaceschur.cpp) did not build" in said[0] and "libsuitesparse-dev" in said[0], said
    assert "Load error" not in proc.stdout + proc.stderr
    assert "did not build" in proc.stderr and "did not build" not in proc.stdout  # beside build.sh's own lines
    assert not (copy / "plugin" / "surfaceschur.so").exists()  # nothing half-built left behind


def test_a_3d_run_typed_by_its_full_path_from_another_folder_loads_its_plugin(tmp_path):
    # FreeFEM looks for a plugin from the working folder, and by a full path only along a set
    # FF_LOADPATH: a 3D run typed as `FreeFem++ /full/path/hertz.edp` elsewhere, with no FF_LOADPATH
    # (the driver sets one), stopped with FreeFEM's "Load error" (exit 2)
    env = freefem.freefem_env()
    env.pop("FF_LOADPATH", None)
    proc = subprocess.run(["FreeFem++", "-nw", "-v", "0", str(freefem.EDP_DIR.resolve() / "hertz.edp"), "-model", "3d",
                           "-n", "3", "-out", "out"], capture_output=True, text=True, cwd=tmp_path, env=env,
                          timeout=300)
    assert proc.returncode in (0, 5) and "Load error" not in proc.stdout + proc.stderr, proc.stdout + proc.stderr
    assert (tmp_path / "out" / "summary.csv").read_text().splitlines()[1].startswith("3d,")


def test_two_elastic_spheres_in_3d(solve):
    """The 3D quarter with an elastic indenter (its u_z alone changed to the
    relative approach): a sphere pair at n = 6 within 0.1% of Hertz, and its
    estimate covering it. Measured: p0 -0.003%, F -0.004%, a +0.066%,
    b -0.033% (estimate 0.53%)."""
    run = solve("-model", "3d", "-E1", "10", "-n", "6")
    s = run.summary
    assert run.exit_code == 0, run.output
    # two identical bodies: Hertz with half the body's modulus
    ref = sphere(SEED["E"] / 2, SEED["nu"], SEED["R"], SEED["d"])
    for q, v in (("p0_fe", ref.p0), ("F_fe", ref.F), ("a_fe", ref.a), ("b_fe", ref.a)):
        assert abs(s[q] / v - 1) < 0.002 and abs(s[q] / v - 1) <= s["accuracy_predicted"], q
    assert s["d1_fe"] == pytest.approx(s["d2_fe"], rel=1e-9)
    axis = run.table("axis")
    assert axis["sigma_z_indenter"].iloc[0] == pytest.approx(axis["sigma_z"].iloc[0], rel=0.01)
