"""The driver: rows, failures as data, resume without duplicates, locks, specs, CLI."""
import os
import subprocess
import sys
import textwrap

import pandas as pd
import pytest

from driver import ROOT
from driver.cases import Case
from driver.run import SetupError, edp_hash, run_case
from driver.schema import STUDY_COLUMNS
from driver.studies import STUDIES, SpecError, load_spec
from driver.sweep import StudyLock, SweepError, append_row, prepare, sweep

TINY = Case(n=4, L=50.0)  # ~0.1 s


def test_case_arguments_and_ids():
    args = TINY.args()
    assert args[args.index("-kpen") + 1] == "100000"
    assert "-maxit" not in args  # None: hertz.edp chooses by method
    assert TINY.case_id != TINY.with_(kpen=1e6).case_id
    assert TINY.case_id == Case(n=4, L=50).case_id


def test_quick_studies_are_subsets_of_full_ones():
    for make in STUDIES.values():
        full = {c.case_id for c in make(False)}
        assert {c.case_id for c in make(True)} <= full


def test_run_case_returns_a_full_row(tmp_path):
    row = run_case(TINY, tmp_path / "case", timeout=120, study="t")
    assert set(STUDY_COLUMNS) <= set(row)
    assert row["status"] == "converged" and row["exit_code"] == 0
    assert row["wall_time"] > 0 and row["edp_hash"] == edp_hash()
    assert (tmp_path / "case" / "freefem.log").read_text().strip()


def test_bad_case_becomes_a_failed_row_with_the_message(tmp_path):
    row = run_case(TINY.with_(kpen=-1.0), tmp_path / "bad", timeout=120)
    assert row["status"] == "failed" and row["exit_code"] == 2
    assert "-kpen" in row["error"]


def test_hanging_case_becomes_a_timeout_row(tmp_path):
    row = run_case(Case(n=64), tmp_path / "slow", timeout=0.2)
    assert row["status"] == "timeout" and "0.2 s" in row["error"]


def test_diverged_case_is_a_row_not_a_crash(tmp_path):
    row = run_case(TINY.with_(method="fixedpoint", kpen=1e4), tmp_path / "div", timeout=120)
    assert row["status"] == "diverged" and row["exit_code"] == 3
    assert "iterations" in row["error"]


def test_sweep_resumes_without_duplicates(tmp_path):
    cases = [TINY, TINY.with_(kpen=1e6)]
    first = sweep("t", cases, tmp_path, jobs=2, timeout=120, progress=False)
    assert len(first) == 2
    log = tmp_path / "runs" / "t" / TINY.case_id / "freefem.log"
    stamp = log.stat().st_mtime_ns
    again = sweep("t", cases + [TINY.with_(kpen=1e7)], tmp_path, jobs=2, timeout=120, progress=False)
    assert len(again) == 3 and again["case_id"].is_unique
    assert log.stat().st_mtime_ns == stamp  # not rerun
    forced = sweep("t", cases, tmp_path, jobs=2, timeout=120, force=True, progress=False)
    assert len(forced) == 3 and forced["case_id"].is_unique
    assert log.stat().st_mtime_ns != stamp


def test_truncated_last_line_and_stale_rows_are_repaired(tmp_path):
    path = tmp_path / "t.csv"
    good = {c: "" for c in STUDY_COLUMNS} | {"case_id": "a", "edp_hash": "current", "status": "converged"}
    old = good | {"case_id": "b", "edp_hash": "older"}
    append_row(path, good)
    append_row(path, old)
    with open(path, "a") as f:
        f.write("t,half-written-row,axi,new")  # a sweep killed mid-write
    frame = prepare(path, "current")
    assert list(frame["case_id"]) == ["a"]
    assert list(pd.read_csv(path)["case_id"]) == ["a"]
    assert list(pd.read_csv(tmp_path / "stale" / "t-older.csv")["case_id"]) == ["b"]


def test_a_second_sweep_of_the_same_study_refuses(tmp_path):
    with StudyLock(tmp_path / "t.lock"):
        with pytest.raises(SweepError, match="another sweep"):
            sweep("t", [TINY], tmp_path, jobs=1, timeout=60, progress=False)


def test_unwritable_results_directory_fails_before_any_work(tmp_path):
    target = tmp_path / "ro"
    target.mkdir()
    target.chmod(0o500)
    if os.access(target, os.W_OK):  # root ignores permissions
        target = tmp_path / "file"
        target.write_text("")
    with pytest.raises(SweepError, match="not writable"):
        sweep("t", [TINY], target / "sub" if target.is_file() else target, jobs=1, timeout=60,
              progress=False)


def test_missing_freefem_names_the_setup_command(tmp_path, monkeypatch):
    monkeypatch.setenv("PATH", str(tmp_path))
    with pytest.raises(SetupError, match="make setup"):
        run_case(TINY, tmp_path / "x", timeout=10)


def test_spec_file_defines_a_grid(tmp_path):
    spec = tmp_path / "s.toml"
    spec.write_text(textwrap.dedent("""
        name = "mine"
        [base]
        n = 8
        [grid]
        kpen = [1e3, 1e5]
        order = [1, 2]
    """))
    name, cases = load_spec(spec)
    assert name == "mine" and len(cases) == 4
    assert {c.n for c in cases} == {8} and {c.order for c in cases} == {1, 2}


@pytest.mark.parametrize("text,message", [
    ('name = "x"\n[grid]\nkpn = [1]', "unknown parameter 'kpn'"),
    ('name = "x"\n[grid]\norder = [1.5]', "order must be an integer"),
    ('name = "x"\n[grid]\nkpen = []', "non-empty list"),
    ('name = "x"\n[grid]\nmodel = [1]', "model must be a str"),
    ('name = "kpen"\n[grid]\nn = [4]', "built-in study"),
    ('[grid]\nn = [4]', "'name'"),
    ('name = "x"\nextra = 1\n[grid]\nn = [4]', "unknown key"),
    ('name = "x"', "at least one parameter"),
    ('name = "x"\n[grid\n', "cannot read"),
])
def test_bad_spec_files_are_rejected_with_a_message(tmp_path, text, message):
    spec = tmp_path / "s.toml"
    spec.write_text(text)
    with pytest.raises(SpecError, match=message):
        load_spec(spec)


def cli(*args, **kw):
    return subprocess.run([sys.executable, "-m", "driver", *args], cwd=ROOT,
                          capture_output=True, text=True, **kw)


@pytest.mark.parametrize("args,word", [
    (["sweep", "kpen", "--jobs", "0"], "--jobs"),
    (["sweep", "kpen", "--timeout", "-1"], "--timeout"),
    (["sweep", "nosuch"], "unknown study 'nosuch'"),
    (["sweep"], "at least one study"),
    (["run", "--order", "x"], "--order"),
])
def test_cli_rejects_bad_arguments(args, word):
    proc = cli(*args)
    assert proc.returncode == 2 and word in proc.stderr


def test_cli_help_lists_every_option():
    out = cli("run", "--help").stdout
    for field in ("--kpen", "--model", "--method", "--order", "--omega", "--timeout"):
        assert field in out
    out = cli("sweep", "--help").stdout
    for option in ("--all", "--quick", "--spec", "--jobs", "--timeout", "--force"):
        assert option in out


def test_contact_scale_matches_the_mesh_scale_of_hertz_edp(tmp_path):
    # n elements per contact scale: the finest element is scale/(4n) in both
    for case in (Case(n=4, L=50.0), Case(model="plane", n=4, L=50.0)):
        row = run_case(case.with_(kpen=case.scaled_kpen(100)), tmp_path / case.model, timeout=120)
        assert row["status"] == "converged"
        # scaled_kpen used the same contact scale as hertz.edp: a_fe is within 5% of it
        assert row["a_fe"] == pytest.approx(case.contact_scale, rel=0.05)
