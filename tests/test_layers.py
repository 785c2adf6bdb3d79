"""Coated bodies (-t, -E2, -nu2) against the exact limits and the layered reference written in
driver/references/layered.py (Perriot and Barthel's integral equation, accurate to about 1e-8)."""
import math
import re

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from promise import check_promise

from driver.references import layered as L

from conftest import rel
from hertz_reference import ellipsoid_from_depth, sphere

E, NU, R, D = 10.0, 0.3, 0.5, 0.02
HZ = sphere(E, NU, R, D)  # a = 0.1: t = 0.1 is t = a


def reference(t, E2, nu=NU, nu2=NU, d=D):
    c = L.Coating(E1=E, nu1=nu, t=t, E2=E2, nu2=nu2)
    ref = L.sphere_from_depth(c, R, d)
    p = L.sphere_pressure(c, R, ref.a, np.linspace(0, 0.98, 99) * ref.a)
    return ref, float(np.max(p))


def error_against_layered(s, t, E2, nu=NU, nu2=NU):
    """Largest relative error of p0, F and a against the layered reference."""
    ref, p0 = reference(t, E2, nu, nu2)
    return max(rel(s["F_fe"], ref.F), rel(s["a_fe"], ref.a), rel(s["p0_fe"], p0))


@pytest.mark.parametrize("t", ["0.003", "0.03", "0.3"])
def test_one_material_on_both_sides_is_the_half_space(solve, t):
    homogeneous = solve().summary
    s = solve("-t", t, "-E2", repr(E), "-nu2", repr(NU)).summary
    assert s["reference"] == "hertz" and s["status"] == "converged"
    # the interface line changes the mesh alone: the Hertz errors move by less than 0.1%
    for q in ("err_p0", "err_F", "err_a"):
        assert abs(s[q] - homogeneous[q]) < 1e-3, (q, s[q], homogeneous[q])


@pytest.mark.parametrize("E2", [5.0, 20.0])
def test_a_film_300_contact_radii_thick_is_the_film_s_half_space(solve, E2):
    run = solve("-t", "30", "-E2", repr(E2))
    assert run.exit_code == 0, run.output
    s = run.summary
    # measured F -0.22% (E2 = E/2) and +0.14% (E2 = 2E): the substrate's own effect, of order a/t
    assert rel(s["F_fe"], HZ.F) < 5e-3 and rel(s["a_fe"], HZ.a) < 5e-3 and rel(s["p0_fe"], HZ.p0) < 5e-3
    assert abs(s["diff_film_F"]) < 5e-3 and abs(s["diff_sub_F"]) > 0.4  # the film's half-space is the model


def test_a_thin_compliant_film_is_the_substrate_s_half_space(solve):
    # t = a/1000 on a substrate 10 times stiffer: the film's own compression, about
    # (2/pi)(E2*/M)(t/a) of d, is what is left (0.5%); measured F -0.64% from the substrate's Hertz
    run = solve("-t", "1e-4", "-E2", "100", timeout=300)
    assert run.exit_code == 0, run.output
    s = run.summary
    substrate = sphere(100.0, NU, R, D)
    assert rel(s["F_fe"], substrate.F) < 0.02 and rel(s["a_fe"], substrate.a) < 0.02
    assert abs(s["diff_sub_F"]) < 0.02 and s["diff_film_F"] < -0.85


GRID = [(ta, ratio) for ta in (0.3, 1, 10) for ratio in (0.01, 0.1, 10, 100)]


@pytest.mark.parametrize("t_over_a,E2_over_E", GRID, ids=[f"t{a}a-E2{r}E" for a, r in GRID])
def test_intermediate_films_match_the_layered_reference(solve, t_over_a, E2_over_E):
    t, E2 = t_over_a * HZ.a, E2_over_E * E
    run = solve("-t", repr(t), "-E2", repr(E2))
    s = run.summary
    # converged exactly when its own estimate is within the 1% bar
    assert run.exit_code == (0 if s["accuracy_predicted"] <= 1e-2 else 5), run.output
    ref, p0 = reference(t, E2)
    truth = max(rel(s["F_fe"], ref.F), rel(s["a_fe"], ref.a), rel(s["p0_fe"], p0))
    # measured: at most 0.79% (p0 at t = 0.3 a on substrates 100 and 10 times softer, where a
    # stiff film's pressure peaks off the axis and zig-zags there: estimated 1.74% and 1.59%,
    # 'inaccurate'); estimates 1.1 to 4.5 times the truth (above 3 only below 0.2%)
    assert truth < 1e-2, truth
    assert 0.5 * truth <= s["accuracy_predicted"] <= max(3 * truth, 2e-3), (truth, s["accuracy_predicted"])


def test_a_stiff_penalty_on_a_stiff_film_keeps_its_contact_radius(solve):
    # each contact quadrature point is an unknown of the active set: with 4 per element edge a
    # stiff penalty's trace lifted between them, and a read -1.06% here (with 6 and 16: -0.28%)
    t, E2 = 0.5 * HZ.a, E / 10
    s = solve("-t", repr(t), "-E2", repr(E2), "-gamma", "1e5").summary
    ref, _ = reference(t, E2)
    assert s["status"] == "converged" and rel(s["a_fe"], ref.a) < 5e-3, (s["status"], s["a_fe"], ref.a)


@pytest.mark.parametrize("t_over_a,E2_over_E,gamma", [(1.0, 0.1, "3"), (1.0, 0.01, "5"), (0.2, 0.014, "5")])
def test_a_moderate_penalty_on_a_stiff_film_says_it_is_off_or_keeps_the_promise(solve, t_over_a,
                                                                                  E2_over_E, gamma):
    # a stiff film's depth is mostly its base's sink: per penetration over d the penalty moved p0
    # and a 2 to 7 times as much as on a half-space, and with the estimate's parts summed with
    # their signs these exited 0 with a +1.52% (estimated 0.66%) and a +1.01% (0.74%). With the
    # penalty part measured, the third still did: an error of 2.0% read 0.82% (in magnitude 4.1%)
    t, E2 = t_over_a * HZ.a, E2_over_E * E
    run = solve("-t", repr(t), "-E2", repr(E2), "-gamma", gamma)
    truth, estimate = check_promise(run, error_against_layered(run.summary, t, E2))
    assert estimate >= 0.5 * truth, (truth, estimate)  # exit 5 too


def test_a_coated_body_s_penalty_part_is_the_penalty_s_effect(solve):
    # t = 0.26 a, E2 = E/20 at 5 E*/h: p0 -1.45% where the half-space's penalty model read -0.07%
    # (the run said 'inaccurate' only because its mesh part came out large; on a mesh banded a
    # little elsewhere it exited 0); the part is now measured by a second solve at twice the
    # penalty: against exact contact on the same levels it read 0.93 of the effect
    args = ("-t", "0.02", "-E2", "0.5")
    pen = solve(*args, "-gamma", "5")
    exact = solve(*args, "-method", "lagrange")
    effect = pen.summary["p0_fe"] / exact.summary["p0_fe"] - 1
    part = float(re.search(r"penalty, domain: \S+ (\S+) \S+ on p0", pen.output).group(1))
    assert effect < -0.01 and part == pytest.approx(effect, rel=0.3), (part, effect)
    check_promise(pen, error_against_layered(pen.summary, 0.02, 0.5))


# Former misses, each a run that exited 0 with an error more than twice its estimate:
#  - thin films on a stiffer base (t = 0.03 to 0.06 a): the edge law forced over six nodes read a
#    -0.07% to -0.19% as 0.02% to 0.09% (its misfit now adds);
#  - stiff films on softer bases, whose pressure peaks off the axis and zig-zags there: 11 of 75
#    runs (t = 0.3 to 1.4 a, E2 = E/100 to E/10, n = 8 to 32) read p0 +0.21% to +1.69% as 0.05%
#    to 0.89% (the peak's zig-zag now adds).
COATED_MISSES = [
    ("-t", "0.00625", "-E2", "100", "-nu", "0.25", "-nu2", "0.25", "-method", "lagrange", "-n", "16"),
    ("-t", "0.00625", "-E2", "30", "-nu", "0.25", "-nu2", "0.25", "-method", "lagrange", "-n", "16"),
    ("-t", "0.004", "-E2", "100", "-n", "24", "-gamma", "1e4"),
    ("-t", "0.003", "-E2", "1000", "-n", "32", "-method", "lagrange"),
    ("-t", "0.03", "-E2", "1.0", "-n", "24", "-method", "lagrange"),
    ("-t", "0.02", "-E2", "0.2", "-n", "8", "-method", "lagrange"),
    ("-t", "0.04", "-E2", "0.5", "-nu", "0.4", "-nu2", "0.3", "-n", "8", "-gamma", "1e4"),
]


def test_a_stiff_penalty_s_noisy_edge_is_not_read_as_the_edge_law_s_misfit(solve):
    # at 1e4 E*/h the gap next to the edge lifts between quadrature points, and the three-node
    # fit read that noise: a thin film's a estimate was 1.24% (exit 5) where a was -0.098%; the
    # misfit is taken from the exact partner level (measured 0.14%, 1.5 times the truth)
    run = solve("-t", "0.00625", "-E2", "30", "-nu", "0.25", "-nu2", "0.25", "-n", "16", "-gamma", "1e4")
    truth = error_against_layered(run.summary, 0.00625, 30.0, 0.25, 0.25)
    assert run.exit_code == 0 and 0.5 * truth <= run.summary["accuracy_predicted"] <= 4 * truth, run.output


@pytest.mark.parametrize("args", COATED_MISSES, ids=[" ".join(a) for a in COATED_MISSES])
def test_the_former_coated_misses_keep_the_promise(solve, args):
    o = dict(zip(args[::2], args[1::2]))
    nu = float(o.get("-nu", NU))
    run = solve(*args)
    truth, estimate = check_promise(run, error_against_layered(run.summary, float(o["-t"]), float(o["-E2"]), nu,
                                                    float(o.get("-nu2", nu))))
    assert estimate >= 0.5 * truth, (truth, estimate)  # exit 5 too


@pytest.mark.parametrize("nu", ["0.4", "0.49"])
def test_a_soft_base_in_the_mixed_form_keeps_the_promise(solve, nu):
    # lambda div u jumps at the interface with E: one continuous pressure across it smeared the
    # jump, and that error did not shrink with n (t = a, E2 = E/100, nu 0.49: F -2.7% at n = 16,
    # -1.5% at n = 32); with a pressure for each material, measured F +0.03% (nu 0.49)
    t, E2 = HZ.a, E / 100
    run = solve("-t", repr(t), "-E2", repr(E2), "-nu", nu, "-nu2", nu)
    s = run.summary
    ref, _ = reference(t, E2, float(nu), float(nu))
    assert s["formulation"] == "mixed" and rel(s["F_fe"], ref.F) < 2e-3, (s["F_fe"], ref.F)
    check_promise(run, error_against_layered(s, t, E2, float(nu), float(nu)))


def test_two_poisson_s_ratios_in_the_mixed_form_converge_at_second_order(solve):
    # t = a, nu 0.44 on 0.125: one pressure across the interface was first order, F -0.21%,
    # -0.11%, -0.05% at n = 16, 32, 64; a pressure for each material: +0.011% and +0.001% at
    # n = 16 and 32. Here n = 8 and 16: the finer within 0.05%, and closer than the coarser
    t = HZ.a
    ref, _ = reference(t, E, 0.44, 0.125)
    errors = [solve("-t", repr(t), "-nu", "0.44", "-nu2", "0.125", "-formulation", "mixed",
                    "-method", "lagrange", "-n", n).summary["F_fe"] / ref.F - 1 for n in ("8", "16")]
    assert abs(errors[1]) < 5e-4 and abs(errors[1]) < abs(errors[0]), errors


@pytest.mark.parametrize("method", ["newton", "lagrange"])
def test_a_nearly_incompressible_thin_film_on_a_stiffer_base_keeps_the_promise(solve, method):
    # t = 0.15 a, E2 = 3 E, nu 0.49 on 0.3: with one pressure across the interface this exited 0
    # with p0 +1.2% (newton, estimated 0.98%) and +1.4% (lagrange, 0.77%); measured now p0 -0.08%
    # and +0.05%
    args = ("-t", "0.015", "-E2", "30", "-nu", "0.49", "-nu2", "0.3")
    run = solve(*args, "-method", method)
    truth, _ = check_promise(run, error_against_layered(run.summary, 0.015, 30.0, 0.49, 0.3))
    assert run.exit_code == 0 and truth < 3e-3, (truth, run.output)


def test_p1_on_a_coated_body_says_it_is_off(solve):
    # its estimate read about half of p0's error: t = a, E2 = 0.7 E, n = 32 exited 0 with p0
    # +1.6% against an estimate of 0.86%
    t, E2 = HZ.a, 0.7 * E
    run = solve("-order", "1", "-t", repr(t), "-E2", repr(E2), "-n", "32")
    s = run.summary
    _, p0 = reference(t, E2)
    assert rel(s["p0_fe"], p0) > 0.01  # the error it names
    assert run.exit_code == 5 and "p1-coated" in s["warnings"], run.output


def test_a_soft_penalty_on_a_soft_film_over_a_stiff_base_is_banded_once(solve):
    # nearly a Winkler foundation: the exact edge at 0.86 of the overlap, so a soft penalty
    # spreads only 0.1 (the half-space's law says 0.26): a band widened past the overlap
    # missed the fine edge and the level was solved again (n = 8 to 32 at 1e-2 E*/h)
    s = solve("-t", "0.05", "-E2", "100", "-gamma", "0.01").summary
    assert s["relevels"] == 0 and s["iterations"] + s["coarse_iterations"] <= 8


@pytest.mark.parametrize("t_over_a", [0.1, 0.01])
def test_a_thin_layer_on_a_rigid_base(solve, t_over_a):
    t = t_over_a * HZ.a
    run = solve("-t", repr(t), "-E2", "inf", "-method", "lagrange")
    assert run.exit_code == 0, run.output
    s = run.summary
    ref, _ = reference(t, math.inf)
    # measured F -0.005%, a -0.15% (t = a/10) and F 0.000%, a -0.017% (t = a/100, the film
    # meshed to its thickness); far stiffer than the film's half-space (F 4 and 40 times)
    assert rel(s["F_fe"], ref.F) < 2e-3 and rel(s["a_fe"], ref.a) < 3e-3
    assert s["farfield"] == "clamped" and math.isnan(s["hs_sub_F"]) and s["diff_film_F"] < -0.5


# 3D: the meridian section revolved (fe/mesh3d.idp), at its default n = 8; 6 to 25 s a run


def test_a_coated_sphere_in_3d_matches_the_layered_reference(solve):
    run = solve("-model", "3d", "-t", "0.1", "-E2", "100")
    assert run.exit_code == 0, run.output
    s = run.summary
    assert s["model"] == "3d" and s["n"] == 8 and s["status"] == "converged"
    ref, p0 = reference(0.1, 100.0)
    # measured F -0.13%, a -0.02%, b +0.05%, p0 -0.13%; estimate 0.50%
    errors = [rel(s["F_fe"], ref.F), rel(s["a_fe"], ref.a), rel(s["b_fe"], ref.a), rel(s["p0_fe"], p0)]
    assert max(errors) < 5e-3, errors
    assert s["accuracy_predicted"] >= 0.5 * max(errors)
    # the film's half-space is far off: the substrate carries the load
    assert s["diff_film_F"] < -0.5 and s["szz_interface"] < -0.5 * s["p0_fe"]


def test_a_coated_ellipsoid_of_one_material_is_elliptical_hertz(solve):
    """The stretched revolved mesh with its interface surface against Hertz (tests' own formulas),
    at n = 6, a coarser test of the estimate (the default n = 8 takes 25 s)."""
    run = solve("-Rx", "0.5", "-Ry", "2", "-t", "0.1", "-E2", repr(E), "-n", "6")
    assert run.exit_code == 0, run.output
    s = run.summary
    assert s["model"] == "3d" and s["reference"] == "hertz" and s["status"] == "converged"
    ref = ellipsoid_from_depth(D, E, NU, 0.5, 2.0)
    # measured p0 -0.13%, F -0.00%, a +0.28%, b -0.20% (estimates 0.30% and 0.63%)
    for column, value in (("p0_fe", ref.p0), ("F_fe", ref.P), ("a_fe", ref.b_short), ("b_fe", ref.a_long)):
        assert rel(s[column], value) < 5e-3, column
        assert rel(s[column], value) <= 2 * s[f"est_err_{column[:-3]}"], column
    assert s["hs_film_F"] == pytest.approx(ref.P, rel=1e-6)  # the film's half-space: this ellipse


def test_a_layer_on_a_rigid_base_in_3d(solve):
    t = 0.5 * HZ.a
    run = solve("-model", "3d", "-t", repr(t), "-E2", "inf")
    assert run.exit_code == 0, run.output
    s = run.summary
    ref, _ = reference(t, math.inf)
    # measured F -0.38%, a -0.08%, b -0.01% (estimates 0.23% to 0.66%)
    assert rel(s["F_fe"], ref.F) < 6e-3 and rel(s["a_fe"], ref.a) < 3e-3 and rel(s["b_fe"], ref.a) < 3e-3
    assert s["farfield"] == "clamped" and math.isnan(s["hs_sub_F"])


def test_load_control_on_a_coated_body(solve):
    t, E2 = 0.1, 100.0
    depth = solve("-t", repr(t), "-E2", repr(E2)).summary
    load = solve("-t", repr(t), "-E2", repr(E2), "-P", repr(depth["F_fe"])).summary
    # the same scene posed by its force finds the same depth
    assert load["d_fe"] == pytest.approx(D, rel=2e-3) and load["a_fe"] == pytest.approx(depth["a_fe"], rel=2e-3)


def test_the_under_modelling_columns_are_the_half_spaces_at_the_depth_found(solve):
    s = solve("-t", "0.1", "-E2", "100").summary
    film, sub = sphere(E, NU, R, D), sphere(100.0, NU, R, D)
    assert s["hs_film_F"] == pytest.approx(film.F, rel=1e-9) and s["hs_sub_F"] == pytest.approx(sub.F, rel=1e-9)
    assert s["hs_a"] == pytest.approx(film.a, rel=1e-9)
    assert s["diff_film_F"] == pytest.approx(film.F / s["F_fe"] - 1, rel=1e-9)


def test_p1_on_a_nearly_incompressible_substrate_says_it_locks(solve):
    # the substrate locks as the film would (F 6% off at nu2 = 0.49): inaccurate, not converged
    run = solve("-t", "0.1", "-E2", "10", "-nu2", "0.49", "-order", "1")
    assert run.exit_code == 5 and "p1-locking" in run.summary["warnings"], run.output


def test_the_interface_stresses_on_the_axis(solve):
    s = solve("-t", "0.1", "-E2", "100").summary
    # sigma_z is continuous across a bonded interface and compressive under the contact; at
    # t = a on a stiff substrate it carries about p0/(1 + (t/a)^2) or more (Hertz's own axis
    # value, which a stiffer substrate raises); the max shear is of the order of 0.3 p0
    assert -s["p0_fe"] < s["szz_interface"] < -0.5 * s["p0_fe"] / 2
    assert 0.1 * s["p0_fe"] < s["tau_interface"] < 0.6 * s["p0_fe"]


@pytest.mark.parametrize("args,option", [
    (["-t", "0"], "-t"), (["-t", "-1"], "-t"), (["-E2", "5"], "-E2"), (["-nu2", "0.2"], "-E2"),
    (["-t", "0.1", "-nu2", "0.6"], "-nu2"), (["-t", "0.1", "-E2", "0"], "-E2"),
    (["-t", "1e-9"], "-t"), (["-t", "1e5"], "-t"), (["-t", "1e-5", "-maxdof", "1e5"], "-t"),
    (["-t", "1e-5", "-E2", "0.01"], "-t"),  # passed the old floor, then the mesher crashed (exit 139)
    (["-t", "0.1", "-E2", "1e-9"], "-E2"),
    (["-t", "0.1", "-E2", "1e300"], "-E2"), (["-t", "0.1", "-E2", "inf", "-nu2", "0.3"], "-nu2"),
    (["-t", "0.1", "-nu2", "0.5", "-order", "1"], "-nu2"),
    (["-t", "0.1", "-E2", "inf", "-farfield", "boussinesq"], "-farfield"),
])
def test_bad_film_input_is_one_line_naming_the_option(solve, args, option):
    run = solve(*args)
    assert run.exit_code == 2, run.output
    errors = run.stderr.strip().splitlines()
    assert len(errors) == 1 and errors[0].startswith("hertz.edp: error:") and option in errors[0], run.output


# Random coated scenes, coarse meshes, nu near 1/2 and moderate penalties included: a run says
# it is off (exit 5), or its error (p0, F and a) is within 1% and at most twice its own estimate.
layered_scenes = st.fixed_dictionaries({
    "t_over_a": st.floats(0.03, 30).map(lambda x: float(f"{x:.3g}")),
    "E2_over_E": st.floats(-2, 2).map(lambda x: float(f"{10 ** x:.3g}")),
    "nu": st.floats(0.05, 0.4999).map(lambda x: float(f"{x:.4g}")),
    "nu2": st.floats(0.05, 0.4999).map(lambda x: float(f"{x:.4g}")),
    "n": st.sampled_from([4, 6, 8, 12, 16, 24]),
    "method": st.sampled_from(["newton", "lagrange"]),
    "gamma": st.sampled_from(["3", "5", "10", "100"]),
})


@settings(max_examples=16, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(layered_scenes)
def test_random_coated_scenes_keep_the_promise(solve, sc):
    t, E2 = sc["t_over_a"] * HZ.a, sc["E2_over_E"] * E
    penalty = ["-gamma", sc["gamma"]] if sc["method"] == "newton" else []
    run = solve("-t", repr(t), "-E2", repr(E2), "-nu", repr(sc["nu"]), "-nu2", repr(sc["nu2"]),
                "-n", str(sc["n"]), "-method", sc["method"], *penalty)
    assert run.exit_code in (0, 5), run.output
    s = run.summary
    ref, p0 = reference(t, E2, sc["nu"], sc["nu2"])
    truth = max(rel(s["F_fe"], ref.F), rel(s["a_fe"], ref.a), rel(s["p0_fe"], p0))
    if run.exit_code == 0:
        assert s["status"] == "converged" and truth <= 0.01, (truth, s["accuracy_predicted"])
        assert s["accuracy_predicted"] >= 0.5 * truth, (truth, s["accuracy_predicted"])


@pytest.mark.parametrize("t", ["0.3", "1"])
def test_a_clamped_stiff_film_on_a_soft_base_says_it_is_off_or_keeps_the_promise(solve, t):
    # a clamped far boundary holds back the sinking a stiff film spreads over its plate length:
    # t = 1, E2 = E/100 exited 0 with F +2.9% estimated at 0.14%, its domain part read as a/L alone
    run = solve("-t", t, "-E2", "0.1", "-farfield", "clamped")
    truth, estimate = check_promise(run, error_against_layered(run.summary, float(t), 0.1))
    assert estimate >= 0.5 * truth, (truth, estimate)  # exit 5 too


@pytest.mark.parametrize("t, E2, extra", [
    ("0.05", "100", ()),                      # t = a/2 on a base ten times stiffer, the default mesh
    ("0.1", "30", ("-n", "32")),              # t = a, E2 = 3 E
    ("0.03", "100", ("-method", "lagrange")),  # t = 0.3 a, exact contact
])
def test_a_punch_on_a_coated_body_reads_its_edge_coefficient_or_says_it_is_off(solve, t, E2, extra):
    # K = lim p sqrt(a - r) varies with the film near the edge: read as the half-space's mean of
    # p sqrt(a^2 - r^2) over 0.5 a to 0.9 a, t = a/2 on a base ten times stiffer exited 0 with K
    # 64% high and an estimate of 0.12%
    a = 0.1
    run = solve("-shape", "punch", "-a", repr(a), "-t", t, "-E2", E2, *extra)
    s = run.summary
    c = L.Coating(E1=E, nu1=NU, t=float(t), E2=float(E2), nu2=NU)
    truth = rel(s["K_fe"], L.punch_edge_coefficient(c, a, s["d"]))
    F = L.punch(c, a, s["d"]).F
    check_promise(run, max(truth, rel(s["F_fe"], F)))
    assert s["est_err_K"] >= 0.5 * truth, (truth, s["est_err_K"])  # exit 5 too


@pytest.mark.parametrize("t, E2", [("0.01", "0.1"), ("0.05", "1")])
def test_a_punch_on_a_stiff_film_over_a_soft_base_finds_its_lifted_face_and_says_so(solve, t, E2):
    # the film bends under the face and part of it lifts off (t = a/10, E2 = E/100: from 0.43 a to
    # 0.98 a; t = a/2, E2 = E/10: around the axis). The levels after the first banded the first
    # contact stretch from the axis as the punch's edge, which cut the face's contact surface
    # short: F half the force, a = 0 and "refine -n or widen -L"
    a = 0.1
    run = solve("-shape", "punch", "-a", repr(a), "-t", t, "-E2", E2)
    s = run.summary
    assert run.exit_code == 5 and "face-lifts" in s["warnings"], run.output
    assert "lifts off from r = " in run.stderr and "unmeasured" not in s["warnings"], run.output
    # a contact: no penetration beyond the penalty's (1e-3 d), and where it lifts a gap without
    # pressure (under 1% of the peak; the recovered field ripples within 0.05 a of the singular
    # edge)
    p = run.table("profile")
    face = p[p.r < a * (1 - 1e-9)]
    lifted = face[(face.gap > 1e-3 * s["d"]) & (face.r < 0.95 * a)]
    assert face.gap.min() > -1e-3 * s["d"] and len(lifted) > 4
    assert lifted.p_fe.abs().max() < 1e-2 * face.p_fe.max()
    # freed from the whole face's constraint, its force is at most the whole face's (energy:
    # F d / 2 is the minimum over a larger set), measured 0.9% and 0.1% below it
    full = L.punch(L.Coating(E1=E, nu1=NU, t=float(t), E2=float(E2), nu2=NU), a, s["d"]).F
    assert 0.97 * full < s["F_fe"] < full * (1 + 1e-3), (s["F_fe"], full)


def test_a_coated_punch_s_edge_coefficient_is_estimated_at_first_order(solve):
    # K is a fit extrapolated to the edge, which converges at first order: read at the second,
    # t = 3 a, E2 = E/1000, lagrange n = 32 exited 0 with K +0.53% estimated at 0.19%
    a, t, E2 = 0.1, "0.3", "0.01"
    run = solve("-shape", "punch", "-a", repr(a), "-t", t, "-E2", E2, "-method", "lagrange", "-n", "32")
    s = run.summary
    truth = rel(s["K_fe"], L.punch_edge_coefficient(L.Coating(E1=E, nu1=NU, t=0.3, E2=0.01, nu2=NU), a, s["d"]))
    assert truth > 3e-3 and s["est_err_K"] >= 0.5 * truth, (truth, s["est_err_K"])  # measured 0.53%, 0.53%


def test_a_punch_on_a_much_softer_base_says_its_edge_coefficient_is_not_certified(solve):
    # t = 3 a on a base a thousand times softer, nu 0.49, -accuracy 0.01: exited 0 with K +1.01%
    # estimated at 0.86% (the fit's bias there, which the levels do not see)
    a = 0.1
    run = solve("-shape", "punch", "-a", repr(a), "-t", "0.3", "-E2", "0.001", "-nu", "0.49", "-accuracy", "0.01")
    s = run.summary
    c = L.Coating(E1=E, nu1=0.49, t=0.3, E2=0.001, nu2=0.49)
    assert rel(s["K_fe"], L.punch_edge_coefficient(c, a, s["d"])) > s["est_err_K"]  # what it names
    assert run.exit_code == 5 and "edge-fit" in s["warnings"], run.output
    assert rel(s["F_fe"], L.punch(c, a, s["d"]).F) < 5e-3  # F is not affected


def test_forced_p2_displacements_near_incompressibility_say_they_lock(solve):
    # both materials at nu = 0.49, a base 1000 times softer: in displacements p0 +1.01% and F
    # +0.75% exited 0 estimated at 0.72% and 0.07%; the mixed form of the scene is within 0.1%
    args = ("-t", "0.05", "-E2", "0.01", "-nu", "0.49", "-nu2", "0.49", "-method", "lagrange")
    forced = solve(*args, "-formulation", "displacement")
    assert forced.exit_code == 5 and "p2-locking" in forced.summary["warnings"], forced.output
    assert error_against_layered(forced.summary, 0.05, 0.01, 0.49, 0.49) > 0.01  # the error it names
    auto = solve(*args)
    check_promise(auto, error_against_layered(auto.summary, 0.05, 0.01, 0.49, 0.49))
    assert "p2-locking" not in str(auto.summary["warnings"])


def test_an_incompressible_film_on_an_incompressible_base_a_thousand_times_softer(solve):
    # each material's pressure block is 1/lambda, floored at nu = 1/2: an absolute floor left the
    # soft base's block far below its own scale, and the run diverged at its first solve
    args = ("-t", "0.05", "-E2", "0.01", "-nu", "0.5", "-nu2", "0.5", "-method", "lagrange")
    run = solve(*args)
    truth, _ = check_promise(run, error_against_layered(run.summary, 0.05, 0.01, 0.5, 0.5))
    assert run.exit_code == 0 and truth < 3e-3, (truth, run.output)  # measured 0.08%
