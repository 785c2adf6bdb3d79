"""driver/sweeps.py: resumable sweeps that lose no finished row, whatever stops them."""
import os
import signal
import subprocess
import sys
import time

import pandas as pd
import pytest

import driver
from driver import studytable
from driver.cases import Case
from driver.errors import SweepError, TableError
from driver.processes import MARKER, processes_with
from driver.sweeps import plan, sweep

from conftest import REPO, cli, solvers_under

TINY = Case.of(n=4, L=50.0, farfield="clamped")  # ~0.1 s (inaccurate: the clamped boundary at 50 a costs 2%)


def test_sweep_resumes_without_duplicates_and_retries_only_failures(tmp_path):
    cases = [TINY, TINY.with_(kpen=1e6), TINY.with_(kpen=-1.0)]  # -1: refused by hertz.edp, a failed row
    first = sweep("t", cases, tmp_path, jobs=2, timeout=120)
    assert len(first.table) == 3 and first.ran == 3
    assert (first.table["status"] == "failed").sum() == 1
    log = tmp_path / "runs" / "t" / TINY.case_id / "freefem.log"
    stamp = log.stat().st_mtime_ns
    again = sweep("t", cases + [TINY.with_(kpen=1e7)], tmp_path, jobs=2, timeout=120)
    assert again.ran == 1 and len(again.table) == 4 and again.table["case_id"].is_unique
    assert log.stat().st_mtime_ns == stamp  # not rerun
    retry = sweep("t", cases, tmp_path, jobs=2, timeout=120, retry_failed=True)
    assert retry.ran == 1  # only the failed one
    forced = sweep("t", cases, tmp_path, jobs=2, timeout=120, force=True)
    assert forced.ran == 3 and studytable.read(tmp_path / "t.csv")["case_id"].is_unique
    assert log.stat().st_mtime_ns != stamp


def test_a_completed_forced_rerun_keeps_the_rows_it_replaced_in_stale(tmp_path):
    cases = [TINY, TINY.with_(kpen=1e6)]
    sweep("t", cases, tmp_path, jobs=2, timeout=120)
    old = studytable.read(tmp_path / "t.csv")
    sweep("t", cases, tmp_path, jobs=2, timeout=120, force=True)
    replaced = pd.concat([pd.read_csv(p) for p in (tmp_path / "stale").glob("t-replaced-*.csv")])
    assert sorted(replaced["case_id"]) == sorted(old["case_id"])
    assert sorted(replaced["wall_time"]) == sorted(old["wall_time"])  # the old rows themselves


@pytest.mark.slow
def test_ctrl_c_during_a_forced_rerun_keeps_every_old_row(fake_solver, tmp_path):
    # --force used to delete the old rows before their reruns finished
    spec = tmp_path / "s.toml"
    spec.write_text('name = "t"\n[base]\nn = 4\nL = 50.0\nfarfield = "clamped"\n[grid]\nkpen = [1e5, 1e6, 1e7]\n')
    first = cli("sweep", "--spec", str(spec), "--results", str(tmp_path), "--no-progress",
                env=dict(os.environ, FAKE_MODE=""))
    assert first.returncode == 1 and "3 case(s)" in first.stderr  # inaccurate (clamped at 50 a), and said so
    before = studytable.read(tmp_path / "t.csv")
    assert len(before) == 3
    rerun = subprocess.Popen([sys.executable, "-m", "driver", "sweep", "--spec", str(spec), "--force",
                              "--results", str(tmp_path), "--no-progress", "--jobs", "2"], cwd=REPO,
                             env=dict(os.environ, FAKE_MODE="slow", FAKE_DELAY="30"),
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 30
    while len(solvers_under(tmp_path)) < 2 and time.monotonic() < deadline:
        time.sleep(0.05)
    time.sleep(1.0)
    rerun.send_signal(signal.SIGINT)
    _, err = rerun.communicate(timeout=30)
    assert rerun.returncode == 130, err
    after = studytable.read(tmp_path / "t.csv")
    assert sorted(after["case_id"]) == sorted(before["case_id"])  # nothing lost
    pd.testing.assert_frame_equal(after.sort_values("case_id").reset_index(drop=True),
                                  before.sort_values("case_id").reset_index(drop=True))


def test_a_converged_row_without_its_answer_is_run_again(tmp_path):
    # in a sweep: the edited row is set aside and its case runs
    sweep("t", [TINY], tmp_path, jobs=1, timeout=120)
    path = tmp_path / "t.csv"
    frame = pd.read_csv(path, dtype=str, keep_default_na=False)
    frame.loc[0, "status"], frame.loc[0, "p0_fe"] = "converged", ""
    path.write_text(frame.to_csv(index=False))
    again = sweep("t", [TINY], tmp_path, jobs=1, timeout=120)
    assert again.ran == 1 and again.table["p0_fe"].notna().all()


def test_a_full_disk_stops_the_sweep_with_a_message_and_keeps_its_rows(tmp_path, monkeypatch):
    real_write = os.write
    calls = {"n": 0}

    def failing_write(fd, data):
        calls["n"] += 1
        if calls["n"] > 1:
            raise OSError(28, "No space left on device")
        return real_write(fd, data)
    monkeypatch.setattr(studytable.os, "write", failing_write)
    with pytest.raises(SweepError, match="No space left"):
        sweep("t", [TINY, TINY.with_(kpen=1e6), TINY.with_(kpen=1e7)], tmp_path, jobs=1, timeout=120)
    monkeypatch.undo()
    assert len(studytable.read(tmp_path / "t.csv")) == 1


def test_a_second_sweep_of_the_same_study_refuses(tmp_path):
    with studytable.StudyLock(tmp_path / "t.lock"):
        with pytest.raises(TableError, match="another sweep"):
            sweep("t", [TINY], tmp_path, jobs=1, timeout=60)


@pytest.mark.parametrize("name", ["x" * 300, "bench", "runs", "../up", "a b", "sweep_environment", "REPORT",
                                  "single", "stale"])
def test_study_names_that_would_share_a_projects_file_are_refused(tmp_path, name):
    # a study named sweep_environment used to write its rows into the environment record
    with pytest.raises(TableError, match="study name"):
        sweep(name, [TINY], tmp_path, jobs=1, timeout=60)


@pytest.mark.parametrize("planted", ["t.csv", "t.lock", "runs", "runs/t"])
def test_a_planted_link_in_the_results_folder_stops_the_sweep(tmp_path, planted):
    # a dangling link at results/<study>.csv used to send the rows outside the folder
    results, outside = tmp_path / "results", tmp_path / "outside"
    results.mkdir()
    outside.mkdir()
    link = results / planted
    link.parent.mkdir(parents=True, exist_ok=True)
    link.symlink_to(outside / "target")
    with pytest.raises(SweepError, match="symbolic link"):
        sweep("t", [TINY], results, jobs=1, timeout=60)
    assert list(outside.iterdir()) == []


def test_plan_puts_costly_cases_first(tmp_path):
    cases = [Case.of(n=4), Case.of(n=64), Case.of(n=16, order=1), Case.of(n=32)]
    todo, _ = plan("t", cases, tmp_path)
    assert [c.get("n") for c in todo] == [64, 32, 16, 4]


SLOW_SPEC = 'name = "slow"\n[base]\nn = 128\nmethod = "lagrange"\n[grid]\nkpen = [1e4, 1e6]\n'


@pytest.mark.slow
@pytest.mark.parametrize("sig", [signal.SIGKILL, signal.SIGTERM, signal.SIGHUP, signal.SIGINT])
def test_killing_a_sweep_leaves_no_solver_running_and_resumes(tmp_path, sig):
    spec = tmp_path / "s.toml"
    spec.write_text(SLOW_SPEC)
    proc = subprocess.Popen([sys.executable, "-m", "driver", "sweep", "--spec", str(spec), "--results",
                             str(tmp_path), "--jobs", "2", "--no-progress"], cwd=REPO,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    deadline = time.time() + 60
    while not solvers_under(tmp_path) and time.time() < deadline:
        time.sleep(0.05)
    assert solvers_under(tmp_path)
    time.sleep(0.5)
    proc.send_signal(sig)
    start = time.perf_counter()
    proc.wait(timeout=60)
    assert time.perf_counter() - start < 2  # a case takes about 4 s: the driver did not wait for it
    time.sleep(0.5)
    assert not solvers_under(tmp_path)  # pdeathsig, or the handler, stopped them
    again = cli("sweep", "--spec", str(spec), "--results", str(tmp_path), "--no-progress")
    assert again.returncode == 0, again.stderr
    done = studytable.read(tmp_path / "slow.csv")
    assert len(done) == 2 and done["case_id"].is_unique and (done["status"] == "converged").all()


def test_a_resumed_sweep_kills_a_leftover_solver_of_its_case(tmp_path):
    case = Case.of(n=8, method="lagrange")
    workdir = tmp_path / "runs" / "t" / case.case_id
    workdir.mkdir(parents=True)
    token = "leftover-token"
    leftover = subprocess.Popen(["sleep", "60"], env=os.environ | {MARKER: token}, start_new_session=True)
    (workdir / "freefem.pid").write_text(f"{leftover.pid} {token}\n")
    # until exec, /proc shows the parent's environment: wait for the marker
    deadline = time.monotonic() + 5
    while not processes_with(token) and time.monotonic() < deadline:
        time.sleep(0.01)
    assert processes_with(token)
    sweep("t", [case], tmp_path, jobs=1, timeout=120)
    time.sleep(0.2)
    assert leftover.poll() is not None and not processes_with(token)


@pytest.mark.parametrize("seed", ["1", "2"])
def test_gathered_files_come_in_one_order_whatever_the_hash_seed(tmp_path, seed):
    # a set's order follows PYTHONHASHSEED: gathered in it, a rerun rewrote every kept file in
    # another row order with the same data
    code = (f"import pandas as pd, pathlib; from driver import layout; from driver.sweeps import gather\n"
            f"r = pathlib.Path({str(tmp_path)!r})\n"
            f"ids = ['c', 'a', 'b', 'e', 'd']\n"
            f"for i in ids:\n"
            f"    d = layout.work_root(r, 'demo') / i; d.mkdir(parents=True, exist_ok=True)\n"
            f"    (d / 'profile.csv').write_text('r,p\\n0,1\\n1,0\\n')\n"
            f"gather('demo', r, pd.DataFrame({{'case_id': ids}}), ('profile.csv',))\n")
    env = dict(os.environ, PYTHONHASHSEED=seed, PYTHONPATH=str(REPO))
    subprocess.run([sys.executable, "-c", code], check=True, env=env)
    gathered = pd.read_csv(tmp_path / "demo" / "profile.csv")
    assert list(gathered["case_id"]) == [c for c in "abcde" for _ in range(2)]
    assert list(gathered["r"]) == [0, 1] * 5


def test_the_environment_record_is_appended_with_the_study_and_the_version(tmp_path):
    # one row a study that ran, the package's version in each (it was one row, overwritten, and
    # a non-editable install said only "commit unknown")
    sweep("t", [TINY], tmp_path, jobs=1, timeout=120)
    sweep("u", [TINY], tmp_path, jobs=1, timeout=120)
    record = pd.read_csv(tmp_path / "sweep_environment.csv", dtype=str)
    assert list(record["study"]) == ["t", "u"] and set(record["version"]) == {driver.__version__}


def test_a_study_named_twice_is_swept_once():
    # 'hertz sweep units units' said another sweep was writing units.csv (its own second lock)
    from driver.sweeps import jobs_from
    assert [job.study for job in jobs_from(names=["plane", "units", "plane"], quick=True)] == ["plane", "units"]
