"""driver/api.py: solve() and sweep(), the documented Python API."""
import dataclasses
import math
from concurrent.futures import ThreadPoolExecutor

import pandas as pd
import pytest

from driver import HertzError, Result, solve, sweep
from driver.errors import OptionError, RejectedError

from hertz_reference import SEED, sphere


def test_solve_returns_a_typed_result_with_the_main_numbers(tmp_path):
    result = solve(method="lagrange", results=tmp_path)
    hertz = sphere(**SEED)
    assert isinstance(result, Result) and result.status == "converged" and result.exit_code == 0
    assert result.p0 == pytest.approx(hertz.p0, rel=1e-3) and result.F == pytest.approx(hertz.F, rel=1e-3)
    assert result.a == pytest.approx(hertz.a, rel=2e-3) and math.isnan(result.b)
    assert 0 < result.estimated_error < 0.01 and result.answered and result.error == ""
    assert result.files == tmp_path / "runs" / "single" / "method=lagrange"
    assert (result.files / "summary.csv").is_file() and result.row["method"] == "lagrange"
    with pytest.raises(dataclasses.FrozenInstanceError):
        result.status = "failed"  # type: ignore[misc]


def test_solve_reports_an_unconverged_run_as_a_result_not_an_exception(tmp_path):
    result = solve(method="fixedpoint", kpen=1e4, results=tmp_path)
    assert result.status == "diverged" and result.exit_code == 3 and not result.answered


@pytest.mark.parametrize("options,error,words", [
    ({"kpn": 1e5}, OptionError, "unknown option kpn"),
    ({"nu": 0.7}, OptionError, "nu must be a number in (-1, 0.5]"),
    ({"method": "newtonian"}, OptionError, "method must be one of"),
    ({"timeout": 1e10}, OptionError, "timeout"),
    ({"d": 0.6}, RejectedError, "-d must be a number in (0, 1) R"),
])
def test_bad_input_raises_one_clear_error_and_leaves_nothing(tmp_path, options, error, words):
    with pytest.raises(error) as raised:
        solve(results=tmp_path / "results", **options)
    assert words in str(raised.value) and isinstance(raised.value, (HertzError, ValueError))
    assert not (tmp_path / "results").exists()


def test_solves_of_one_case_at_once_each_get_a_folder(tmp_path):
    with ThreadPoolExecutor(2) as pool:
        results = list(pool.map(lambda _: solve(n=32, method="lagrange", results=tmp_path), range(2)))
    assert {r.status for r in results} == {"converged"}
    assert len({r.files for r in results}) == 2


def test_sweep_returns_the_studys_rows_as_a_dataframe(tmp_path):
    cases = [{"n": 8, "kpen": 1e5}, {"n": 8, "method": "lagrange"}]
    frame = sweep("mine", cases=cases, results=tmp_path, jobs=2)
    assert isinstance(frame, pd.DataFrame) and len(frame) == 2
    assert set(frame["status"]) == {"converged"} and (tmp_path / "mine.csv").is_file()
    with pytest.raises(OptionError, match="kpen must be a number"):
        sweep("mine", cases=[{"kpen": -1}], results=tmp_path)


def test_sweep_returns_rows_in_the_order_the_cases_were_asked(tmp_path):
    # the table holds rows in the order they finished (two jobs: the larger n finishes last)
    from driver.api import sweep
    cases = [{"d": d, "n": n} for d, n in ((0.04, 24), (0.01, 6), (0.02, 12))]
    rows = sweep("ordered", cases=cases, results=tmp_path, jobs=2)
    assert list(rows["d"]) == [0.04, 0.01, 0.02]
    assert list(rows["n"]) == [24, 6, 12]


def test_two_solves_of_one_scene_keep_their_own_files(tmp_path):
    from driver.api import solve
    first = solve(n=6, results=tmp_path)
    kept = (first.files / "summary.csv").read_bytes()
    second = solve(n=6, results=tmp_path)
    assert second.files != first.files
    assert (first.files / "summary.csv").read_bytes() == kept and (second.files / "summary.csv").is_file()
