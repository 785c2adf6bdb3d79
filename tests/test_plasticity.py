"""J2 plasticity's return map and consistent tangent alone, without contact
(edp/lib/fe/plasticity.idp, driven by tests/edp/thick_cylinder.edp): a thick
cylinder in plane strain, its bore pushed out in steps. The references are
the tests' own: Lame's elastic cylinder, and the fully plastic collapse
pressure (2/sqrt 3) Y ln(b/a) of perfect plasticity."""
import io
import math
import subprocess

import numpy as np
import pandas as pd
import pytest

from driver import freefem

from conftest import REPO

A, B, E, NU, Y = 1.0, 2.0, 1.0, 0.3, 1e-3
MU, LAMBDA = E / (2 * (1 + NU)), E * NU / ((1 + NU) * (1 - 2 * NU))


def cylinder(*args: str) -> pd.DataFrame:
    proc = subprocess.run([freefem.check_freefem(), "-nw", "-v", "0", "tests/edp/thick_cylinder.edp", *args],
                          cwd=REPO, capture_output=True, text=True, env=freefem.freefem_env(), timeout=300)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    table = proc.stdout[proc.stdout.index("step,"):]
    return pd.read_csv(io.StringIO(table))


def lame_pressure(U: float) -> float:
    """The elastic bore pressure at a bore displacement U: u = A' r + B'/r with
    sigma_rr(b) = 0, so A' = mu B'/((lambda + mu) b^2), and p = 2 mu B' (1/a^2 - 1/b^2)."""
    Bc = U / (A * MU / ((LAMBDA + MU) * B**2) + 1 / A)
    return 2 * MU * Bc * (1 / A**2 - 1 / B**2)


@pytest.fixture(scope="module")
def perfect() -> pd.DataFrame:
    return cylinder("-H", "0", "-steps", "20", "-Umax", "0.01", "-n", "10")


def test_the_elastic_steps_are_lames(perfect):
    elastic = perfect[perfect["yielding"] == 0]
    assert len(elastic) >= 1
    for _, row in elastic.iterrows():
        assert row["p"] == pytest.approx(lame_pressure(row["U"]), rel=1e-4)


def test_the_cylinder_collapses_at_the_fully_plastic_pressure(perfect):
    """Perfect plasticity: the pressure rises to (2/sqrt 3) Y ln(b/a) and stays
    there (within 1%; the plane-strain axial stress reaches the mean of the other
    two only as the plastic strain outgrows the elastic)."""
    limit = 2 / math.sqrt(3) * Y * math.log(B / A)
    last = perfect["p"].iloc[-1]
    assert last == pytest.approx(limit, rel=0.01)
    assert perfect["p"].max() <= limit * 1.01
    assert (np.diff(perfect["p"]) > -1e-3 * limit).all()


def test_newton_converges_quadratically_on_the_consistent_tangent(perfect):
    """Each step within a few iterations, and in a plastic step each residual
    about the square of the one before, until rounding."""
    assert perfect["iterations"].max() <= 8
    plastic = perfect[perfect["yielding"] > 0]
    rates = []
    for history in plastic["residuals"]:
        r = [float(v) for v in str(history).split(";")]
        rates += [math.log(r[k + 1]) / math.log(r[k]) for k in range(1, len(r) - 1) if 1e-9 < r[k] < 0.1]
    assert rates and np.median(rates) > 1.7, rates


def test_unloading_is_elastic_from_the_plastic_state():
    """Pulled back by less than the elastic range, the bore's pressure falls along
    Lame's elastic slope (the plastic strain stays as it was), not back down the
    loading curve."""
    run = cylinder("-H", "0", "-steps", "20", "-Umax", "0.01", "-n", "10", "-back", "0.0004")
    peak, end = run.iloc[19], run.iloc[-1]
    assert end["U"] == pytest.approx(0.0096) and end["yielding"] == 0
    assert peak["p"] - end["p"] == pytest.approx(lame_pressure(0.0004), rel=2e-3)


def test_hardening_lifts_the_pressure_past_the_perfect_limit():
    hard = cylinder("-H", "0.01", "-steps", "10", "-Umax", "0.01", "-n", "8")
    limit = 2 / math.sqrt(3) * Y * math.log(B / A)
    assert (np.diff(hard["p"]) > 0).all() and hard["p"].iloc[-1] > 1.05 * limit
