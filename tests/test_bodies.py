"""Two elastic bodies (-E1, -nu1, -R2): each a half-space of its own material and
shape, meshed beside the other, in contact along their relative displacement.
The references are the tests' own: Hertz with 1/E* = (1 - nu1^2)/E1 + (1 - nu^2)/E
and 1/R = 1/R1 + 1/R2, Code_Aster's SSNV104, the rigid indenter's run, Cattaneo
where Dundurs' beta vanishes (identical bodies), and the boundary elements of the
rigid indenter with the same E* and beta (driver/references/spence.py) where it
does not."""
import math

import meshio
import numpy as np
import pandas as pd
import pytest
from promise import check_promise

from driver.references.spence import dundurs_beta, equivalent_rigid, spence_path

import hertz_reference
from conftest import REPO


def contact_modulus(E, nu, E1, nu1):
    """Hertz's E* of two bodies: the two compliances in series."""
    return 1 / (1 / hertz_reference.estar(E, nu) + 1 / hertz_reference.estar(E1, nu1))


# (hertz_reference's formulas take a body's E and nu: E* itself is (E*, 0))
def hertz_sphere_at_depth(Estar, R, d):
    ref = hertz_reference.sphere(Estar, 0.0, R, d)
    return {"a_fe": ref.a, "F_fe": ref.F, "p0_fe": ref.p0}


def hertz_sphere_under_load(Estar, R, P):
    ref = hertz_reference.sphere_from_load(Estar, 0.0, R, P)
    return {"a_fe": ref.a, "d_fe": hertz_reference.sphere_depth(Estar, 0.0, R, P), "p0_fe": ref.p0}


def assert_within(s, ref, bar, estimates=("est_err_p0", "est_err_F", "est_err_a")):
    """Each of ref's quantities (p0, F or d, a: in that order) within bar of the run and within twice its estimate."""
    for (q, value), est in zip(ref.items(), estimates):
        err = s[q] / value - 1
        assert abs(err) < bar and abs(err) <= 2 * s[est], (q, err, s[est])


def test_identical_spheres_are_hertz_with_half_the_modulus(solve):
    """E1 = E, nu1 = nu: E* is half the body's. Measured at the defaults (d =
    0.02, R = 0.5): p0 +0.031%, F +0.002%, a +0.032%, each half of the
    approach to 1e-12."""
    run = solve("-E1", "10")
    s = run.summary
    assert run.exit_code == 0, run.output
    ref = hertz_sphere_at_depth(contact_modulus(10, 0.3, 10, 0.3), 0.5, 0.02)
    assert_within(s, {q: ref[q] for q in ("p0_fe", "F_fe", "a_fe")}, 0.005)
    # the run's own comparison is with the combined modulus
    for q in ("p0", "F", "a"):
        assert s[f"{q}_hertz"] == pytest.approx(ref[f"{q}_fe"], rel=1e-9), q
    assert s["d1_fe"] == pytest.approx(s["d2_fe"], rel=1e-9)
    # the two shares make the approach, but for the penalty's penetration
    assert s["d1_fe"] + s["d2_fe"] == pytest.approx(0.02, abs=1.5 * s["max_penetration"])
    assert "Two bodies:" in run.stdout


def test_dissimilar_spheres_under_load_and_their_shares(solve):
    """A stiffer indenter (E1 = 3E, nu1 = 0.2) on a body of nu = 0.35 curved
    itself (R2 = 2R: 1/R = 1/0.5 + 1/1), under a load, by the exact method.
    Each body's compression is its own compliance's share: d1/d2 = E2*/E1*.
    Measured: p0 +0.085%, a -0.021%, d -0.022%; the shares' ratio within 7e-5."""
    run = solve("-E1", "30", "-nu1", "0.2", "-nu", "0.35", "-R2", "1", "-P", "0.01", "-method", "lagrange")
    s = run.summary
    assert run.exit_code == 0, run.output
    ref = hertz_sphere_under_load(contact_modulus(10, 0.35, 30, 0.2), 1 / (1 / 0.5 + 1 / 1), 0.01)
    assert_within(s, {q: ref[q] for q in ("p0_fe", "d_fe", "a_fe")}, 0.005)
    assert s["E1"] == 30 and s["nu1"] == 0.2 and s["R2"] == 1 and s["R"] == 0.5
    own = (10 / (1 - 0.35**2)) / (30 / (1 - 0.2**2))
    assert s["d1_fe"] / s["d2_fe"] == pytest.approx(own, rel=5e-4)
    assert s["d1_fe"] + s["d2_fe"] == pytest.approx(s["d_fe"], rel=1e-6)


def test_the_indenters_stresses_and_field(solve, tmp_path):
    """The indenter's own fields: on the axis its sigma_z is the body's (the
    same pressure) and its sigma_r at the surface Hertz's -(1 + 2 nu1)/2 p0;
    its VTU sits above the surface, its surface raised by its share of the
    approach (the body's lowered by the rest)."""
    vtk = tmp_path / "f.vtu"
    run = solve("-E1", "30", "-nu1", "0.2", "-vtk", str(vtk))
    s, axis = run.summary, run.table("axis")
    assert run.exit_code == 0, run.output
    assert axis["sigma_z_indenter"].to_numpy() == pytest.approx(axis["sigma_z"].to_numpy(), rel=0.01,
                                                                abs=0.005 * s["p0_fe"])
    assert axis["sigma_r_indenter"].iloc[0] == pytest.approx(-(1 + 2 * 0.2) / 2 * s["p0_fe"], rel=0.005)
    assert axis["sigma_r"].iloc[0] == pytest.approx(-(1 + 2 * 0.3) / 2 * s["p0_fe"], rel=0.005)
    indenter, body = meshio.read(tmp_path / "f_indenter.vtu"), meshio.read(tmp_path / "f_near.vtu")
    assert indenter.points[:, 1].min() >= 0 and indenter.points[:, 1].max() > 0
    top = np.argmin(np.hypot(indenter.points[:, 0], indenter.points[:, 1]))
    low = np.argmin(np.hypot(body.points[:, 0], body.points[:, 1]))
    assert indenter.point_data["displacement"][top, 1] == pytest.approx(s["d1_fe"], rel=1e-6)
    assert -body.point_data["displacement"][low, 1] == pytest.approx(s["d2_fe"], rel=1e-6)
    assert np.isnan(solve().table("axis")["sigma_z_indenter"]).all()


def test_a_stiff_indenter_is_the_rigid_one(solve):
    """E1 = 1e6 E: everything within about E*/E1* = 1e-6 of the rigid run,
    the indenter's share of the approach that small."""
    elastic, rigid = solve("-E1", "1e7").summary, solve().summary
    for q in ("p0_fe", "F_fe", "a_fe", "d2_fe"):
        assert elastic[q] == pytest.approx(rigid[q], rel=3e-6), q
    assert rigid["d1_fe"] == 0 and 0 < elastic["d1_fe"] < 3e-6 * elastic["d2_fe"]
    assert math.isinf(rigid["E1"]) and math.isinf(rigid["R2"]) and np.isnan(rigid["nu1"])


SSNV104 = ["-E", "20000", "-nu", "0.3", "-E1", "20000", "-R", "50", "-R2", "50", "-d", "4"]


def test_ssnv104_two_hemispheres(solve):
    """Code_Aster's SSNV104: two spheres of R = 50 mm, E = 20,000 MPa, nu =
    0.3, pressed 4 mm together: Hertz a = 10 mm, p0 = 2798.3 MPa, each within
    the run's estimate (measured +0.032% and +0.031% against 0.069%). At a/R =
    0.2 two real caps differ from the parabolas, by (d/R)/6 R^3 (1/R1^3 +
    1/R2^3) in a at first order: the run says so, and warns."""
    run = solve(*SSNV104)
    s = run.summary
    assert run.exit_code == 0, run.output
    Estar = contact_modulus(20000, 0.3, 20000, 0.3)
    assert 2 * Estar * 10 / (math.pi * 25) == pytest.approx(2798.3, abs=0.05)
    assert abs(s["a_fe"] / 10 - 1) <= s["est_err_a"]
    assert abs(s["p0_fe"] / 2798.3 - 1) <= s["est_err_p0"] + 2e-5   # (the four digits)
    assert s["d1_fe"] == pytest.approx(2, rel=1e-3) and s["d2_fe"] == pytest.approx(2, rel=1e-3)
    caps = 25**3 * (2 / 50**3)   # a quarter: two equal spheres
    assert s["parabola_error"] == pytest.approx(4 / 25 / 6 * caps, rel=1e-9)
    assert "spheres of radii R and R2" in run.stderr and "spheres of these radii" in run.stdout


def two_caps(d, Estar, R1, R2):
    """Two exact spheres' caps: the profile of slope r/sqrt(R1^2 - r^2) + r/sqrt(R2^2 - r^2),
    by the tests' method of dimensionality reduction (hertz_reference: not the solver's
    Sneddon closed forms); a and F at the approach d."""
    slope = hertz_reference.profile_slope("sphere", R=R1), hertz_reference.profile_slope("sphere", R=R2)
    ref = hertz_reference.profile_from_depth(lambda r: slope[0](r) + slope[1](r), d, Estar, 0.999999 * min(R1, R2))
    return ref.a, ref.F


def test_ssnv104_with_its_exact_spheres(solve):
    """SSNV104's two real spheres (-shape sphere -R2: each body's own exact cap):
    a and F against the tests' two-cap Sneddon within the run's estimate, and
    the difference from Hertz that a/R = 0.2 makes (measured: a -0.67%, F
    -0.37%)."""
    run = solve(*SSNV104, "-shape", "sphere", "-method", "lagrange")
    s = run.summary
    assert run.exit_code == 0, run.output
    a, F = two_caps(4, contact_modulus(20000, 0.3, 20000, 0.3), 50, 50)
    assert abs(s["a_fe"] / a - 1) <= 2 * s["est_err_a"] and abs(s["F_fe"] / F - 1) <= 2 * s["est_err_F"]
    assert s["a_fe"] / 10 - 1 == pytest.approx(-0.0067, abs=0.0005)
    assert s["a_hertz"] == pytest.approx(a, rel=1e-9) and s["reference"] == "sneddon"


@pytest.mark.parametrize("args", [
    ["-E1", "3", "-method", "uzawa"],
    ["-E1", "3", "-order", "1", "-accuracy", "1e-2"],
    ["-E1", "3", "-accuracy", "1e-3"],
])
def test_every_method_solves_two_spheres(solve, args):
    """Uzawa, P1 and -accuracy on two bodies: exit 0 within 1% of Hertz
    and at most twice the estimate."""
    run = solve(*args)
    s = run.summary
    assert run.exit_code == 0, run.output
    ref = hertz_sphere_at_depth(contact_modulus(10, 0.3, 3, 0.3), 0.5, 0.02)
    assert_within(s, {q: ref[q] for q in ("p0_fe", "F_fe", "a_fe")}, 0.01)


def test_two_cylinders_in_plane_strain(solve):
    """Plane strain: the half-width b = sqrt(4 P R/(pi E*)) and p0 = 2P/(pi b),
    with E* and R combined (two parallel cylinders). Measured: b +0.05%, p0 +0.004%."""
    run = solve("-model", "plane", "-Rx", "1", "-Ry", "inf", "-R2", "3", "-E1", "3", "-nu1", "0.25", "-P", "0.05")
    s = run.summary
    assert run.exit_code == 0, run.output
    Estar, R = contact_modulus(10, 0.3, 3, 0.25), 1 / (1 + 1 / 3)
    b = hertz_reference.cylinder_half_width(0.05, Estar, 0.0, R)
    assert abs(s["a_fe"] / b - 1) < 0.005 and abs(s["a_fe"] / b - 1) <= 2 * s["est_err_a"]
    assert abs(s["p0_fe"] / hertz_reference.cylinder_pressure(0.05, Estar, 0.0, R) - 1) < 0.005


def test_identical_bodies_with_friction_do_not_shear(solve):
    """Dundurs' beta = 0 for identical bodies at any nu: pressing them together
    with friction moves neither surface against the other, and the shear
    traction vanishes (to rounding), where a rigid indenter on the same body
    (beta = 0.29) leaves a slip annulus carrying mu p."""
    elastic, rigid = solve("-E1", "10", "-mu", "0.1", "-steps", "4"), solve("-mu", "0.1", "-steps", "4")
    q2, q1 = elastic.table("profile"), rigid.table("profile")
    p0 = elastic.summary["p0_fe"]
    assert q2["q_fe"].abs().max() < 1e-9 * 0.1 * p0
    assert q1["q_fe"].abs().max() > 0.3 * 0.1 * rigid.summary["p0_fe"]
    # (nothing slips: the stick zone is read out to the nodes the last step brought in)
    assert elastic.summary["c_fe"] / elastic.summary["a_fe"] > rigid.summary["c_fe"] / rigid.summary["a_fe"] + 0.3


def random_two_body_scene(seed: int) -> tuple[list[str], dict]:
    """A scene drawn from the seed: either model, depth or load, any method and
    order, both materials and the body's radius at random; with Hertz's own
    values for it (the tests' formulas)."""
    rng = np.random.default_rng(seed)
    E, nu = 10 ** rng.uniform(0, 6), rng.uniform(-0.3, 0.39)
    E1, nu1 = E * 10 ** rng.uniform(-2, 2), rng.uniform(-0.3, 0.39)
    R, R2 = 10 ** rng.uniform(-1, 1), float(rng.choice([np.inf, 10 ** rng.uniform(-0.5, 1.5)]))
    plane, load = bool(rng.random() < 0.3), bool(rng.random() < 0.4)
    method, order = str(rng.choice(["newton", "lagrange", "uzawa"])), int(rng.choice([1, 2, 2, 2]))
    Rrel = 1 / (1 / R + (0 if math.isinf(R2) else 1 / R2))
    Estar = contact_modulus(E, nu, E1, nu1)
    args = ["-E", repr(E), "-nu", repr(nu), "-E1", repr(E1), "-nu1", repr(nu1),
            "-R2", "inf" if math.isinf(R2) else repr(R2), "-method", method, "-order", str(order),
            "-n", str(int(rng.integers(8, 33)))]
    if plane:
        P = Estar * R * 10 ** rng.uniform(-4, -2)
        return args + ["-model", "plane", "-Rx", repr(R), "-Ry", "inf", "-P", repr(P)], \
            {"a_fe": hertz_reference.cylinder_half_width(P, Estar, 0.0, Rrel),
             "p0_fe": hertz_reference.cylinder_pressure(P, Estar, 0.0, Rrel)}
    d = Rrel * 10 ** rng.uniform(-3, -1.5)
    args += ["-R", repr(R)]
    if load:
        P = hertz_sphere_at_depth(Estar, Rrel, d)["F_fe"]
        return args + ["-P", repr(P)], hertz_sphere_under_load(Estar, Rrel, P)
    return args + ["-d", repr(d)], hertz_sphere_at_depth(Estar, Rrel, d)


@pytest.mark.parametrize("seed", range(12))
def test_the_promise_holds_on_random_two_body_scenes(solve, seed):
    """exit 0 only within 1% of Hertz (combined E*, R) and at most twice the
    estimate; otherwise exit 5."""
    args, ref = random_two_body_scene(seed)
    run = solve(*args)
    s = run.summary
    truth = max(abs(s[q] / v - 1) for q, v in ref.items())
    check_promise(run, truth)


@pytest.mark.parametrize("args, option", [
    (["-nu1", "0.2"], "-nu1"),
    (["-E1", "0"], "-E1"),
    (["-E1", "1e-9"], "-E1"),
    (["-E1", "abc"], "-E1"),
    (["-R2", "-1"], "-R2"),
    (["-R2", "1", "-shape", "cone"], "-R2"),
    (["-R2", "0.1", "-shape", "sphere", "-d", "0.15"], "-shape sphere"),
    (["-E1", "10", "-formulation", "mixed"], "-E1"),
    (["-E1", "10", "-t", "0.05"], "-E1"),
    (["-E1", "10", "-nu", "0.45"], "-E1"),
])
def test_bad_two_body_input_is_one_line(solve, args, option):
    run = solve(*args, out=False)
    lines = [line for line in run.stderr.splitlines() if line.strip()]
    assert run.exit_code == 2 and len(lines) == 1 and option in lines[0], run.output


def committed(name: str) -> pd.DataFrame:
    return pd.read_csv(REPO / "results" / name)


def pulled(variant: str) -> tuple[pd.Series, pd.DataFrame]:
    table = committed("bodies.csv")
    case = table[table["variant"] == variant].iloc[0]
    paths = committed("bodies/path.csv")
    return case, paths[paths["case_id"] == case["case_id"]].sort_values("step")


def test_identical_cylinders_under_q_follow_cattaneo_at_nu_0_3():
    """The committed bodies study: two identical cylinders (nu = 0.3, beta = 0)
    pulled to Q = mu P/2: c/a = sqrt(1 - Q/(mu P)) at every step, the stick
    zone centred. Measured at n = 16, 16 steps a leg: c/a +0.96% at the end
    (its estimate 2.1%). (A rigid indenter on the same body, beta = 0.29,
    leaves it larger and off centre: test_tangential.py.)"""
    case, rows = pulled("identical cylinders under Q")
    along = rows[rows["Q"] > 1e-6 * case["Q_fe"]]
    ratio = (along["c"] / along["a"]).to_numpy()
    cattaneo = np.sqrt(1 - along["Q"].to_numpy() / (case["mu"] * along["P"].to_numpy()))
    assert len(along) == 16 and np.abs(ratio / cattaneo - 1).max() < 0.03
    end = case["c_fe"] / case["a_fe"] / math.sqrt(0.5) - 1
    assert abs(end) < 0.015 and abs(end) <= 2 * case["est_err_c"]


def test_the_ellipsoid_pair_in_3d_is_within_2_percent():
    """The committed bodies study: two ellipsoids (Rx = 0.5, Ry = 2, a stiffer
    indenter) in 3D at n = 8, against elliptical Hertz with the combined E*
    (the tests' own elliptic integrals): p0, F, a and b within 2% and within
    twice the run's estimate. Measured: b -0.46% (estimate 0.91%), the rest
    within 0.11%."""
    table = committed("bodies.csv")
    s = table[table["variant"] == "ellipsoid pair, 3D"].iloc[0]
    assert s["status"] == "converged" and s["model"] == "3d"
    Estar = contact_modulus(s["E"], s["nu"], s["E1"], s["nu1"])
    ref = hertz_reference.ellipsoid_from_depth(s["d"], Estar, 0.0, 0.5, 2.0)
    for q, v in (("p0_fe", ref.p0), ("F_fe", ref.P), ("a_fe", ref.b_short), ("b_fe", ref.a_long)):
        err = abs(s[q] / v - 1)
        assert err < 0.02 and err <= 2 * s["accuracy_predicted"], (q, err)


def test_dissimilar_cylinders_under_q_follow_the_boundary_elements():
    """E1 = 3E, nu1 = nu = 0.3: beta = 0.14, half the rigid indenter's. The
    boundary elements of the rigid indenter with the same E* and beta give
    the stick zone along the path. Measured at n = 16, 16 steps a leg: c/a
    +3.2% at the end (its estimate 2.7%), a -0.2%."""
    case, rows = pulled("dissimilar cylinders under Q")
    assert dundurs_beta(case["E1"], case["nu1"], case["E"], case["nu"]) == pytest.approx(1 / 7)
    E, nu = equivalent_rigid(case["E1"], case["nu1"], case["E"], case["nu"])
    bem = spence_path(case["mu"], nu, rows["P"].to_numpy(), cells=400, E=E, R=case["Rx"],
                      tangential=rows["Q"].to_numpy())
    err = case["c_fe"] / case["a_fe"] / bem[-1]["c_over_a"] - 1
    assert abs(err) < 0.04 and abs(err) <= 2 * case["est_err_c"], (err, case["est_err_c"])
    assert case["a_fe"] / bem[-1]["a"] == pytest.approx(1, abs=0.005)
