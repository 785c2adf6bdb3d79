"""driver/run.py: one case becomes a full row whatever the solver does; nothing of an
earlier run passes for this one."""
import time
from pathlib import Path

import pytest

from driver import freefem
from driver.cases import Case
from driver.run import run_case
from driver.schema import study_columns

from conftest import run_fault

TINY = Case.of(n=4, L=50.0, farfield="clamped")  # ~0.1 s (inaccurate: the clamped boundary at 50 a costs 2%)


def test_a_case_runs_with_exactly_the_value_it_was_given(tmp_path):
    row = run_case(Case.of(n=8, nu=0.4999999, method="lagrange"), tmp_path / "c", timeout=120)
    assert row["nu"] == 0.4999999 and row["status"] in ("converged", "inaccurate")


def test_run_case_returns_a_full_row(tmp_path):
    row = run_case(TINY, tmp_path / "case", timeout=120, study="t")
    columns = study_columns(freefem.summary_columns())
    assert set(columns) <= set(row)
    assert row["status"] == "inaccurate" and row["exit_code"] == 5  # its estimate says 2%
    assert row["wall_time"] > 0 and row["edp_hash"] == freefem.edp_hash() and row["max_rss_mb"] > 10
    assert (tmp_path / "case" / "freefem.log").read_text().strip()


def test_rejected_input_is_a_failed_row_with_the_solvers_message(tmp_path):
    row = run_case(TINY.with_(kpen=-1.0), tmp_path / "bad", timeout=120)
    assert row["status"] == "failed" and row["exit_code"] == 2 and "-kpen" in row["error"]


def test_a_hanging_case_becomes_a_timeout_row(tmp_path):
    row = run_case(Case.of(n=64), tmp_path / "slow", timeout=0.3)
    assert row["status"] == "timeout" and "0.3 s" in row["error"], row["error"]


def test_a_relative_work_folder_is_the_callers_not_the_solvers(tmp_path, monkeypatch):
    # the solver runs inside its work folder: a relative -out would point below it
    monkeypatch.chdir(tmp_path)
    row = run_case(Case.of(n=8), Path("rel") / "case", timeout=120)
    assert row["status"] == "converged", row["error"]
    assert (tmp_path / "rel" / "case" / "summary.csv").is_file()


def test_files_of_an_earlier_run_are_removed_before_a_run(tmp_path):
    # a 3D run left outline.csv and profile_y.csv; a 2D run there must not keep them
    workdir = tmp_path / "case"
    workdir.mkdir()
    for name in ("outline.csv", "profile_y.csv", "anything.csv", "fields_near.vtu"):
        (workdir / name).write_text("an earlier run's\n")
    (workdir / "notes.txt").write_text("the user's\n")
    row = run_case(Case.of(n=8), workdir, timeout=120)
    assert row["status"] == "converged"
    left = {p.name for p in workdir.iterdir()}
    assert not {"outline.csv", "profile_y.csv", "anything.csv", "fields_near.vtu"} & left, left
    assert {"summary.csv", "profile.csv", "notes.txt"} <= left


@pytest.mark.parametrize("mode,expect", [
    ("crash_after_summary", "signal 11"), ("exit4_after_summary", "exited with 4"),
    ("unknown_columns", "columns differ"), ("empty_summary", "unreadable"),
    ("header_only", "0 data rows"), ("binary_summary", "summary.csv"),
    ("dir_summary", "not a file"), ("non_numeric", "p0_fe is not a number"),
])
def test_every_solver_fault_is_a_failed_row_with_its_reason(fake_solver, tmp_path, monkeypatch, mode, expect):
    row = run_fault(mode, tmp_path, monkeypatch)
    assert row["status"] == "failed" and expect in row["error"], row["error"]


def test_a_helper_holding_stdout_does_not_hold_a_finished_case(fake_solver, tmp_path, monkeypatch):
    start = time.perf_counter()
    row = run_fault("holds_stdout", tmp_path, monkeypatch, timeout=20)
    assert row["status"] == "converged" and time.perf_counter() - start < 10


def test_an_unexecutable_solver_is_a_failed_row(fake_solver, monkeypatch, tmp_path):
    fake_solver.chmod(0o644)
    monkeypatch.setattr(freefem, "check_freefem", lambda: str(fake_solver))
    row = run_case(TINY, tmp_path / "x", timeout=10, summary_columns=["model", "status"])
    assert row["status"] == "failed" and "Permission denied" in row["error"]


def test_the_timeout_holds_against_a_solver_that_ignores_signals_in_its_group(fake_solver, tmp_path, monkeypatch):
    row = run_fault("hang", tmp_path, monkeypatch, timeout=0.5)
    assert row["status"] == "timeout", (row["error"], row["exit_code"])
