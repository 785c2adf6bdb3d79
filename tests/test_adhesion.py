"""Adhesion (-w, -sigma0, -pulloff; edp/lib/methods/adhesion.idp and
edp/lib/solve/pulloff.idp) against Maugis and Dugdale's exact solution and its
JKR and DMT limits (driver/references/maugis.py, apart from the solver)."""
import re

import numpy as np
import pytest

from driver.references.maugis import Maugis, jkr_depth, jkr_radius, jkr_zero_load_radius

E, NU, R, D = 10.0, 0.3, 0.5, 0.02          # the default scene
ESTAR = E / (1 - NU**2)
W = 0.05
PWR = np.pi * W * R


def rel(x, ref):
    return abs(x / ref - 1)


# -- the reference itself ----------------------------------------------------

def test_maugis_reaches_jkr_and_dmt():
    """At lambda = 30 the Maugis curve is JKR's (a at a load, the depth at that a, the
    zero-load radius and both pull-offs within 0.3%); at lambda = 0.05 its load-controlled
    pull-off is DMT's -2 pi w R within 3% (approached as lambda^(2/3); DMT's force at a
    depth holds only where the traction's own sink, about 2 sigma0 c/E*, is small against
    the depth: at d = 0.02 it is 60% of it, and the force 20% off)."""
    jkr = Maugis(ESTAR, R, W, sigma0=60.0)
    assert jkr.lam > 29
    s = jkr.at_load(0.05)
    assert rel(s["a"], jkr_radius(0.05, ESTAR, R, W)) < 3e-3
    # a pull above the pull-off has two states: the stable one is JKR's larger radius
    assert rel(jkr.at_load(-PWR)["a"], jkr_radius(-PWR, ESTAR, R, W)) < 3e-3
    assert rel(s["d"], jkr_depth(s["a"], ESTAR, R, W)) < 3e-3
    assert rel(jkr.zero_load()["a"], jkr_zero_load_radius(ESTAR, R, W)) < 3e-3
    assert rel(jkr.pulloff("load")["P"], -1.5 * PWR) < 3e-3
    assert rel(jkr.pulloff("load")["a"], 0.630 * jkr_zero_load_radius(ESTAR, R, W)) < 3e-3
    assert rel(jkr.pulloff("depth")["P"], -5 / 6 * PWR) < 3e-3
    assert rel(jkr.pulloff("depth")["a"], 0.303 * jkr_zero_load_radius(ESTAR, R, W)) < 1e-2
    dmt = Maugis(ESTAR, R, W, sigma0=0.1)
    assert dmt.lam < 0.05
    assert rel(dmt.pulloff("load")["P"], -2 * PWR) < 3e-2


def test_maugis_pulloff_falls_from_dmt_to_jkr():
    """The load-controlled pull-off over pi w R falls monotonically from near 2 to near 1.5
    as lambda grows (Maugis's figure 5)."""
    values = [-Maugis(ESTAR, R, W, s).pulloff("load")["P"] / PWR for s in (0.1, 0.5, 2, 5, 20, 60)]
    assert all(a > b for a, b in zip(values, values[1:]))
    assert values[0] == pytest.approx(2, abs=0.1) and values[-1] == pytest.approx(1.5, abs=0.01)


# -- the solver ----------------------------------------------------------------

def test_zero_adhesion_is_the_frictionless_run_to_the_digit(solve):
    """-w 0 is today's run: every number of summary.csv equal (timings apart)."""
    plain, zero = solve("-n", "8"), solve("-n", "8", "-w", "0")
    assert plain.exit_code == zero.exit_code == 0
    for key, value in plain.summary.items():
        if key.startswith("t_") or key == "memory_mb":
            continue
        other = zero.summary[key]
        assert (value == other) or (isinstance(value, float) and np.isnan(value) and np.isnan(other)), key


SCENES = [  # (sigma0, its lambda, n): DMT's side, the middle, JKR's side (where the net
    # force is a fiftieth of the push and the pull: n = 32 read it -0.11%, and the level
    # pair alone 0.024%)
    (0.3, 0.147, 16), (5.0, 2.46, 16), (20.0, 9.83, 32)]


@pytest.mark.parametrize("sigma0, lam, n", SCENES)
def test_a_depth_gives_maugis_force_radius_and_neck(solve, sigma0, lam, n):
    """At the default depth: F, a and the neck within 0.5% of Maugis (measured: at most
    0.13%), F and a within twice their estimates, and the Tabor parameter written."""
    run = solve("-w", str(W), "-sigma0", str(sigma0), "-n", str(n))
    assert run.exit_code == 0, run.output
    s = run.summary
    ref = Maugis(ESTAR, R, W, sigma0).at_depth(D)
    assert s["tabor"] == pytest.approx(lam, abs=0.01)
    for column, key, estimate in [("F_fe", "P", "est_err_F"), ("a_fe", "a", "est_err_a")]:
        error = rel(s[column], ref[key])
        assert error < 5e-3, (column, error)
        assert error <= 2 * s[estimate], (column, error, s[estimate])
    assert rel(s["neck_fe"], ref["c"]) < 5e-3
    assert np.isnan(s["pulloff_fe"]) and np.isnan(s["S_fe"])


def test_a_load_gives_maugis_depth_and_radius(solve):
    """-P 0.05 at lambda = 2.5: the depth and the contact radius within 0.1% of Maugis."""
    run = solve("-w", str(W), "-sigma0", "5", "-P", "0.05")
    assert run.exit_code == 0, run.output
    s = run.summary
    ref = Maugis(ESTAR, R, W, 5.0).at_load(0.05)
    assert s["F_fe"] == pytest.approx(0.05, rel=1e-8)
    assert rel(s["d_fe"], ref["d"]) < 1e-3 and rel(s["a_fe"], ref["a"]) < 1e-3


@pytest.fixture(scope="module")
def retract(solve):
    """From -P 0.05 to separation at lambda = 2.5 (about 6 s)."""
    run = solve("-w", str(W), "-sigma0", "5", "-P", "0.05", "-pulloff", "1")
    assert run.exit_code in (0, 5), run.output
    return run


def test_pulloff_under_load_control_is_maugis(retract):
    """The least force within 0.2% of Maugis (measured 0.04%) and within twice its
    estimate; the zero-load radius within 0.2% (measured 0.02%), likewise; the
    pull-off radius within 1%, its estimate over its error."""
    s = retract.summary
    maugis = Maugis(ESTAR, R, W, 5.0)
    least, zero = maugis.pulloff("load"), maugis.zero_load()
    error = rel(s["pulloff_fe"], least["P"])
    assert error < 2e-3 and error <= 2 * s["est_err_pulloff"], (error, s["est_err_pulloff"])
    error = rel(s["a0_fe"], zero["a"])
    assert error < 2e-3 and error <= 2 * s["est_err_a0"], (error, s["est_err_a0"])
    error = rel(s["a_pulloff_fe"], least["a"])
    assert error < 1e-2 and error <= s["est_err_a_pulloff"], (error, s["est_err_a_pulloff"])
    assert s["pulloff_fe"] / PWR == pytest.approx(-1.524, abs=0.005)


def test_the_curve_lies_on_maugis(retract):
    """path.csv: the scene's state, then states down the curve past the least force and
    the contact's loss; each (neck, depth, force) on Maugis's curve: at the row's neck the
    depth within 0.5% of the curve's depth range and the force within 2% of pi w R
    (measured 1.1%: the trace's mesh is the scene's, its band widened out to the neck)."""
    rows = retract.table("path")
    assert len(rows) >= 10 and rows["a"].iloc[0] > rows["a"].iloc[-1]
    assert (rows["a"] == 0).any(), "the trace stops only after the contact is lost"
    assert rows["P"].min() < retract.summary["pulloff_fe"] + 0.05 * PWR
    maugis = Maugis(ESTAR, R, W, 5.0)
    curve = maugis.curve(0.4, 4000)
    contact = rows[rows["a"] > 0]
    order = np.argsort(curve["c"])
    d_at = np.interp(contact["neck"], curve["c"][order], curve["d"][order])
    P_at = np.interp(contact["neck"], curve["c"][order], curve["P"][order])
    span = curve["d"].max() - curve["d"].min()
    assert np.abs(contact["d"] - d_at).max() < 5e-3 * span
    assert np.abs(contact["P"] - P_at).max() < 2e-2 * PWR


DEPTH_CONTROL = ("-w", str(W), "-sigma0", "5", "-d", "0.06", "-pulloff", "1")


def test_pulloff_under_depth_control(solve):
    """-d 0.06 at lambda = 2.5: the depth at pull-off within 0.2% of Maugis, and the force
    there within 2% (a flat least: measured 0.5%), within twice its estimate."""
    run = solve(*DEPTH_CONTROL)
    assert run.exit_code in (0, 5), run.output
    s = run.summary
    least = Maugis(ESTAR, R, W, 5.0).pulloff("depth")
    assert not least["at_end"]
    assert rel(s["d_pulloff_fe"], least["d"]) < 2e-3
    error = rel(s["pulloff_fe"], least["P"])
    assert error < 2e-2 and error <= 2 * s["est_err_pulloff"], (error, s["est_err_pulloff"])


def test_the_depth_controlled_pulloffs_estimate_spans_its_meshes(solve):
    """The force at the least depth moves with the mesh more than the level pair says (a
    flat least: +0.52% at n = 16, -0.51% at n = 24): the estimate at n = 16 spans the two."""
    coarse, fine = solve(*DEPTH_CONTROL), solve(*DEPTH_CONTROL, "-n", "24")
    spread = rel(coarse.summary["pulloff_fe"], fine.summary["pulloff_fe"])
    assert spread > 2e-3   # (the scatter the estimate must cover is there)
    assert coarse.summary["est_err_pulloff"] >= spread


def test_a_contact_held_by_its_traction_alone_is_solved(solve):
    """A depth of 1e-6 (a range 1e4 times the depth: the contact is JKR's zero-load one) within
    0.01% of Maugis, in about a second: the first level's scale follows the neck's reach."""
    run = solve("-w", str(W), "-sigma0", "5", "-d", "1e-6", timeout=60)
    assert run.exit_code == 0, run.output
    s = run.summary
    ref = Maugis(ESTAR, R, W, 5.0).at_depth(1e-6)
    assert rel(s["F_fe"], ref["P"]) < 1e-3 and rel(s["a_fe"], ref["a"]) < 1e-3


def test_a_narrow_zone_needs_its_own_limit(solve):
    """-pulloff beyond lambda = 5 is refused with one line naming -sigma0's window."""
    run = solve("-w", str(W), "-sigma0", "20", "-pulloff", "1", out=False)
    assert run.exit_code == 2
    assert "-sigma0 from" in run.stderr and len(run.stderr.strip().splitlines()) == 1


@pytest.mark.parametrize("args", [("-w", "0.05", "-sigma0", "0.01"), ("-w", "0.05", "-sigma0", "1e4"),
                                  ("-w", "0.05", "-sigma0", "30", "-pulloff", "1"), ("-w", "1e5", "-sigma0", "1"),
                                  ("-w", "1e5", "-sigma0", "2e5")])
def test_what_a_refusal_advises_is_accepted(solve, args):
    # each bound advised a -sigma0 the other refused, and a -w too strong for any was not named
    run = solve(*args, "-check", "1", out=False)
    assert run.exit_code == 2, run.output
    rest = [a for a in args[2:] if a not in ("-sigma0",)][1:]
    window = re.search(r"-sigma0 from (\S+) to ([^\s:;()]+)", run.stderr)
    if window:
        middle = (float(window.group(1)) * float(window.group(2))) ** 0.5
        ok = solve("-w", args[1], "-sigma0", repr(middle), *rest, "-check", "1", out=False)
    else:
        w = 0.9 * float(re.search(r"-w at most (\S+)$", run.stderr.strip()).group(1))
        ok = solve("-w", repr(w), "-sigma0", repr(w / R), *rest, "-check", "1", out=False)
    assert ok.exit_code == 0, ok.output


@pytest.mark.parametrize("args, phrase", [
    (("-w", "-0.1", "-sigma0", "1"), "-w must be a number in [0, inf)"),
    (("-w", "0.1"), "-w needs -sigma0"),
    (("-sigma0", "1"), "give -w too"),
    (("-w", "0.1", "-sigma0", "0"), "-sigma0 must be a number in (0, inf)"),
    (("-w", "0.1", "-sigma0", "nan"), "-sigma0 must be a number"),
    (("-w", "0.1", "-sigma0", "1", "-model", "plane"), "-w needs -model axi and -shape parabola"),
    (("-w", "0.1", "-sigma0", "1", "-method", "newton"), "-method lagrange"),
    (("-w", "0.1", "-sigma0", "1", "-Y", "1"), "not built yet"),
    (("-pulloff", "1"), "give -w and -sigma0"),
    (("-w", "1e300", "-sigma0", "1"), "-w 1e+300 is too strong"),
    (("-w", "0.05", "-sigma0", "0.01"), "the interaction's range, must be at most R"),
    (("-w", "0.05", "-sigma0", "1e300"), "above 100"),
])
def test_bad_adhesive_input_is_one_line(solve, args, phrase):
    run = solve(*args, out=False)
    assert run.exit_code == 2 and phrase in run.stderr, run.output
    assert len(run.stderr.strip().splitlines()) == 1
