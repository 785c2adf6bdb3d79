"""hertz curve: a P-h curve from one command, sorted by h, with S, A = pi a^2, H = P/A and
Er = S sqrt(pi)/(2 sqrt(A)); on an elastic sphere Er is E* at every depth (Sneddon)."""
import math

import pandas as pd
import pytest

from driver.commands.curve import COLUMNS

import hertz_reference as ref
from conftest import cli, hertz, one_error_line, rel

E, NU, R = 10.0, 0.3, 0.5  # hertz.edp's defaults


@pytest.fixture(scope="module")
def depth_curve(tmp_path_factory):
    out = tmp_path_factory.mktemp("curve") / "out"
    # asked from deep to shallow: the curve comes back sorted by h whatever the order asked or finished
    proc = cli("curve", "--d", "0.04:0.01:4", "--n", "8", "--jobs", "2", "--out", str(out))
    assert proc.returncode == 0, proc.stderr
    return out, proc


def test_the_curve_is_sorted_by_h_and_holds_its_columns(depth_curve):
    out, proc = depth_curve
    table = pd.read_csv(out / "curve.csv")
    assert list(table.columns) == COLUMNS == ["h", "P", "S", "a", "A", "H", "Er"]
    assert table["h"].tolist() == pytest.approx([0.01, 0.02, 0.03, 0.04], rel=1e-12)
    assert (out / "curve.png").read_bytes().startswith(b"\x89PNG")
    assert proc.stderr.splitlines()[-1] == f"files: {out / 'curve.csv'}, {out / 'curve.png'}"


def test_area_hardness_and_modulus_follow_their_definitions(depth_curve):
    table = pd.read_csv(depth_curve[0] / "curve.csv")
    for row in table.itertuples():
        assert row.A == pytest.approx(math.pi * row.a**2, rel=1e-12)
        assert row.H == pytest.approx(row.P / row.A, rel=1e-12)
        assert row.Er == pytest.approx(row.S * math.sqrt(math.pi) / (2 * math.sqrt(row.A)), rel=1e-12)


def test_an_elastic_sphere_gives_e_star_at_every_depth(depth_curve):
    table = pd.read_csv(depth_curve[0] / "curve.csv")
    star = ref.estar(E, NU)
    for row in table.itertuples():
        assert rel(row.Er, star) < 0.005, (row.h, row.Er, star)
        hertz_case = ref.sphere(E, NU, R, row.h)
        assert rel(row.P, hertz_case.F) < 0.01 and rel(row.a, hertz_case.a) < 0.01


def test_a_load_curve_finds_its_depths(tmp_path):
    out = tmp_path / "out"
    proc = cli("curve", "--P", "0.01:0.03:2", "--n", "8", "-q", "--out", str(out))
    assert proc.returncode == 0 and proc.stderr == "", proc.stderr
    table = pd.read_csv(out / "curve.csv")
    assert table["P"].tolist() == pytest.approx([0.01, 0.03], rel=2e-3)
    for row in table.itertuples():
        assert rel(row.h, ref.sphere_depth(E, NU, R, row.P)) < 0.01
        assert rel(row.Er, ref.estar(E, NU)) < 0.005


@pytest.mark.parametrize("args,words", [
    (["--d", "0.01:0.02"], "--d: must be START:STOP:N"),
    (["--d", "0.01:0.02:1"], "N in [2, 1000]"),
    (["--d", "0.01:0.02:3", "--P", "0.1:0.2:3"], "not allowed with"),
    ([], "one of the arguments --d --P is required"),
    (["--d", "0.01:0.02:3", "--model", "plane"], "--model plane has no contact area"),
    (["--d", "0.1:0.6:3"], "hertz.edp: error: -d must be a number in (0, 1) R"),
    (["--d", "0.01:0.02:3", "--nu", "0.7"], "hertz: error: --nu must be a number"),
    (["--d", "0.01:0.02:3", "--vtk", "x.vtu"], "unrecognized arguments: --vtk"),
])
def test_bad_input_is_one_line_and_writes_nothing(tmp_path, args, words):
    line = one_error_line(hertz("curve", *args, "--out", str(tmp_path / "out"), cwd=tmp_path))
    assert words in line, line
    assert not (tmp_path / "out").exists()


def test_inaccurate_points_stay_in_the_curve_and_are_named(tmp_path):
    # the power law k = 1.5 at n = 16 estimates p0's error above 1%: inaccurate, exit 5
    proc = cli("curve", "--d", "0.01:0.03:2", "--shape", "power", "--out", str(tmp_path / "out"))
    assert proc.returncode == 5, proc.stderr
    assert len(pd.read_csv(tmp_path / "out" / "curve.csv")) == 2
    named = [line for line in proc.stderr.splitlines() if line.startswith("hertz: warning:")]
    assert len(named) == 2 and all("inaccurate (estimate" in line for line in named), proc.stderr
