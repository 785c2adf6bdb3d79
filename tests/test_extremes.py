"""Numerical extremes: each has a documented, tested behaviour."""
import pytest


def warnings_of(summary):
    text = summary["warnings"]
    return set() if not isinstance(text, str) else set(text.split(";"))


def max_err(s):
    return max(abs(s["err_p0"]), abs(s["err_F"]), abs(s["err_a"]))


def test_huge_penalty_stays_right_and_flags_roundoff(solve):
    stiff = solve("-kpen", "1e12").summary
    ref = solve("-kpen", "1e8").summary
    assert stiff["status"] == "converged"
    for key in ("p0_fe", "F_fe", "a_fe"):
        assert stiff[key] == pytest.approx(ref[key], rel=1e-4)
    assert "roundoff" in warnings_of(stiff)
    assert "roundoff" not in warnings_of(ref)


def test_p1_locking_is_warned_and_p2_is_fine_near_incompressibility(solve):
    p1 = solve("-order", "1", "-nu", "0.49").summary
    assert "p1-locking" in warnings_of(p1)
    assert p1["err_p0"] > 0.2  # the locking it warns about
    for nu in ("0.49", "0.499"):
        p2 = solve("-nu", nu).summary
        assert p2["status"] == "converged" and max_err(p2) < 0.01, nu
        assert "p1-locking" not in warnings_of(p2)


def test_tiny_depth_with_a_soft_penalty_is_warned(solve):
    soft = solve("-d", "5e-7").summary  # d = 1e-6 R, kpen = 1e5 is soft here
    assert "soft-penalty" in warnings_of(soft)
    stiff = solve("-d", "5e-7", "-kpen", "1e9").summary
    assert not warnings_of(stiff) and max_err(stiff) < 0.01


def test_deep_indentation_warns_about_the_parabolic_indenter(solve):
    deep = solve("-d", "0.25").summary  # a/R = 0.71
    assert "parabola" in warnings_of(deep)
    assert max_err(deep) < 0.01  # still the (parabolic) Hertz solution
    assert "parabola" not in warnings_of(solve().summary)  # a/R = 0.2: 0.5% of d


def test_coarsest_mesh_is_two_elements_per_radius(solve):
    run = solve("-n", "2")
    assert run.exit_code == 0 and run.summary["status"] == "converged"
    assert max_err(run.summary) < 0.1
