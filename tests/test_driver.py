"""The driver: exact cases, rows for every fault, resume, tables that repair themselves, the CLI."""
import json
import os
import shutil
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pandas as pd
import pytest

from driver import ROOT, freefem, table
from driver.cases import Case, exact
from driver.run import MARKER, processes_with, run_case
from driver.schema import study_columns
from driver.studies import STUDIES, SpecError, load_spec
from driver.sweep import SweepError, plan, sweep

TINY = Case.of(n=4, L=50.0)  # ~0.1 s (inaccurate: 2% off by its own estimate)
FAKE = Path(__file__).with_name("fake_freefem.py")


def test_values_travel_exactly_and_ids_tell_them_apart():
    assert exact(0.4999999) == "0.4999999" and float(exact(123456789.4)) == 123456789.4
    assert Case.of(kpen=123456789.4).case_id != Case.of(kpen=123456789.0).case_id
    assert Case.of(nu=0.4999999).args() == ["-nu", "0.4999999"]
    assert Case.of(n=4, L=50.0).case_id == Case.of(L=50.0, n=4).case_id  # order does not matter
    long = Case.of(**{f"x{k}": float(k) for k in range(40)})
    assert len(long.case_id) < 200  # still a file name


def test_quick_studies_are_subsets_of_full_ones():
    for study in STUDIES.values():
        assert {c.case_id for c in study.make(True)} <= {c.case_id for c in study.make(False)}


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


@pytest.fixture
def fake_solver(tmp_path, monkeypatch):
    """Put a misbehaving FreeFem++ first on PATH; returns a function to pick its fault."""
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    fake = bin_dir / "FreeFem++"
    fake.write_text(f"#!{sys.executable}\n" + FAKE.read_text())
    fake.chmod(0o755)
    monkeypatch.setenv("REAL_FREEFEM", shutil.which("FreeFem++"))
    monkeypatch.setenv("PATH", f"{bin_dir}:{os.environ['PATH']}")
    columns = freefem.summary_columns()

    def fault(mode: str, case: Case = Case.of(n=8, method="lagrange"), timeout: float = 60) -> dict:
        monkeypatch.setenv("FAKE_MODE", mode)
        return run_case(case, tmp_path / mode, timeout=timeout, summary_columns=columns)
    fault.path = fake
    return fault


@pytest.mark.parametrize("mode,expect", [
    ("crash_after_summary", "signal 11"), ("exit4_after_summary", "exited with 4"),
    ("unknown_columns", "columns differ"), ("empty_summary", "unreadable"),
    ("header_only", "0 data rows"), ("binary_summary", "summary.csv"),
    ("dir_summary", "not a file"), ("non_numeric", "p0_fe is not a number"),
])
def test_every_solver_fault_is_a_failed_row_with_its_reason(fake_solver, mode, expect):
    row = fake_solver(mode)
    assert row["status"] == "failed" and expect in row["error"], row["error"]


def test_a_helper_holding_stdout_does_not_hold_a_finished_case(fake_solver):
    start = time.perf_counter()
    row = fake_solver("holds_stdout", timeout=20)
    assert row["status"] == "converged" and time.perf_counter() - start < 10


def test_a_detached_child_is_killed_with_its_case(fake_solver):
    row = fake_solver("detached_child")
    assert row["status"] == "converged"
    time.sleep(0.2)
    leftovers = [p for p in Path("/proc").iterdir() if p.name.isdigit() and _has_marker(p)]
    assert not leftovers


def _has_marker(proc: Path) -> bool:
    try:
        return any(e.startswith(MARKER.encode()) for e in (proc / "environ").read_bytes().split(b"\0"))
    except OSError:
        return False


def test_an_unexecutable_solver_is_a_failed_row(fake_solver, monkeypatch):
    fake_solver.path.chmod(0o644)
    monkeypatch.setattr(freefem, "check_freefem", lambda: str(fake_solver.path))
    row = run_case(TINY, Path(fake_solver.path).parent / "x", timeout=10,
                   summary_columns=["model", "status"])
    assert row["status"] == "failed" and "Permission denied" in row["error"]


def test_the_timeout_holds_against_a_solver_that_ignores_signals_in_its_group(fake_solver):
    row = fake_solver("hang", timeout=0.5)
    assert row["status"] == "timeout", (row["error"], row["exit_code"])


def test_sweep_resumes_without_duplicates_and_retries_only_failures(tmp_path):
    cases = [TINY, TINY.with_(kpen=1e6), TINY.with_(kpen=-1.0)]
    first = sweep("t", cases, tmp_path, jobs=2, timeout=120)
    assert len(first.table) == 3 and first.ran == 3
    log = tmp_path / "runs" / "t" / TINY.case_id / "freefem.log"
    stamp = log.stat().st_mtime_ns
    again = sweep("t", cases + [TINY.with_(kpen=1e7)], tmp_path, jobs=2, timeout=120)
    assert again.ran == 1 and len(again.table) == 4 and again.table["case_id"].is_unique
    assert log.stat().st_mtime_ns == stamp  # not rerun
    retry = sweep("t", cases, tmp_path, jobs=2, timeout=120, retry_failed=True)
    assert retry.ran == 1  # only the failed one
    forced = sweep("t", cases, tmp_path, jobs=2, timeout=120, force=True)
    assert forced.ran == 3 and table.read(tmp_path / "t.csv")["case_id"].is_unique
    assert log.stat().st_mtime_ns != stamp


def _write_table(path: Path, rows: list[dict]) -> list[str]:
    columns = study_columns(freefem.summary_columns())
    for row in rows:
        table.append_row(path, {"status": "converged", "edp_hash": freefem.edp_hash()} | row, columns)
    return columns


def test_a_table_is_validated_on_load_and_bad_lines_go_aside_by_number(tmp_path):
    path = tmp_path / "t.csv"
    columns = _write_table(path, [{"case_id": "a"}, {"case_id": "b"}, {"case_id": "a", "p0_fe": 2.0}])
    with open(path, "ab") as f:
        f.write(b"garbage,line\n")
        f.write(("t,c," + ",".join("x" for _ in columns[2:]) + "\n").encode())  # non-numeric values
        f.write(b"\xff\xfe not utf-8\n")
    good = len(columns) * [""]
    good[columns.index("case_id")], good[columns.index("edp_hash")] = "d", freefem.edp_hash()
    with open(path, "a") as f:
        f.write(",".join(good) + "\n")  # empty status
        f.write("t,half-written-row")  # cut by a kill
    frame, messages = table.prepare(path, columns, freefem.edp_hash())
    assert sorted(frame["case_id"]) == ["a", "b"]
    assert frame.set_index("case_id").loc["a", "p0_fe"] == 2.0  # the later run of a case wins
    assert any("cut by an interrupted write" in m for m in messages)
    aside = next((tmp_path / "stale").glob("t-bad-*.txt")).read_text()
    for expect in ("line 2: duplicate of case a (line 4 kept)", "line 5: 2 fields", "line 6: ",
                   "line 7: not UTF-8", "line 8: status ''", "garbage", "not utf-8"):
        assert expect in aside, (expect, aside)
    assert table.check(path, columns).bad == []  # what is left is clean


def test_an_edp_hash_that_looks_like_a_number_stays_text(tmp_path):
    path = tmp_path / "t.csv"
    columns = _write_table(path, [{"case_id": "a", "edp_hash": "05426170e796"}])
    frame, _ = table.prepare(path, columns, "05426170e796")
    assert list(frame["case_id"]) == ["a"] and frame["edp_hash"].iloc[0] == "05426170e796"
    assert table.read(path)["edp_hash"].iloc[0] == "05426170e796"


# A repair whose file writes are slowed down (in chunks, announced on stdout),
# so that the kill lands in the middle of writing, whatever writes.
REPAIR_SCRIPT = """
import builtins, io, sys, time
from pathlib import Path
from driver import table
real_open = io.open
class Slow:
    def __init__(self, f, name): self.f, self.name = f, name
    def write(self, data):
        if len(data) > 100000:
            print("writing", self.name, flush=True)
            for k in range(0, len(data), 20000):
                self.f.write(data[k:k + 20000]); self.f.flush(); time.sleep(0.01)
            return len(data)
        return self.f.write(data)
    def __getattr__(self, name): return getattr(self.f, name)
    def __enter__(self): return self
    def __exit__(self, *a): return self.f.__exit__(*a)
def slow_open(*args, **kw):
    f = real_open(*args, **kw)
    mode = kw.get("mode", args[1] if len(args) > 1 else "r")
    return Slow(f, str(args[0])) if "w" in mode else f
builtins.open = io.open = slow_open
path, columns, current = Path(sys.argv[1]), sys.argv[2].split(","), sys.argv[3]
table.prepare(path, columns, current)
"""


def test_a_kill_during_a_table_repair_loses_nothing(tmp_path):
    columns = study_columns(freefem.summary_columns())
    rows = [{"case_id": f"c{k}", "edp_hash": "current" if k % 2 else "older"} for k in range(20000)]
    master = tmp_path / "master.csv"
    _write_table(master, rows[:1])
    buf = pd.DataFrame([{c: "" for c in columns} | {"status": "converged"} | r for r in rows])[columns]
    master.write_text(buf.to_csv(index=False) + "t,cut-line")
    current_rows = sum(1 for r in rows if r["edp_hash"] == "current")
    # kill during each large write of the table (or of its replacement), early and late in it
    for event, delay in ((1, 0.0), (1, 0.05), (2, 0.0), (2, 0.05)):
        path = tmp_path / f"t{event}-{delay}.csv"
        shutil.copy(master, path)
        proc = subprocess.Popen([sys.executable, "-c", REPAIR_SCRIPT, str(path), ",".join(columns), "current"],
                                cwd=ROOT, stdout=subprocess.PIPE, text=True)
        seen = 0
        while seen < event and (line := proc.stdout.readline()):
            seen += path.name in line
        time.sleep(delay)
        proc.send_signal(signal.SIGKILL)
        proc.wait()
        kept = table.check(path, columns)
        # either the old table (all rows, cut line included) or the repaired one
        assert len(kept.rows) in (len(rows), current_rows), (delay, len(kept.rows))


def test_a_full_disk_stops_the_sweep_with_a_message_and_keeps_its_rows(tmp_path, monkeypatch):
    real_write = os.write
    calls = {"n": 0}

    def failing_write(fd, data):
        calls["n"] += 1
        if calls["n"] > 1:
            raise OSError(28, "No space left on device")
        return real_write(fd, data)
    monkeypatch.setattr(table.os, "write", failing_write)
    with pytest.raises(SweepError, match="No space left"):
        sweep("t", [TINY, TINY.with_(kpen=1e6), TINY.with_(kpen=1e7)], tmp_path, jobs=1, timeout=120)
    monkeypatch.undo()
    assert len(table.read(tmp_path / "t.csv")) == 1


def test_a_second_sweep_of_the_same_study_refuses(tmp_path):
    with table.StudyLock(tmp_path / "t.lock"):
        with pytest.raises(table.TableError, match="another sweep"):
            sweep("t", [TINY], tmp_path, jobs=1, timeout=60)


@pytest.mark.parametrize("name", ["x" * 300, "bench", "runs", "../up", "a b"])
def test_study_names_are_checked(tmp_path, name):
    with pytest.raises(table.TableError, match="study name"):
        sweep(name, [TINY], tmp_path, jobs=1, timeout=60)


def test_spec_file_defines_a_grid(tmp_path):
    spec = tmp_path / "s.toml"
    spec.write_text(textwrap.dedent("""
        name = "mine"
        [base]
        n = 8
        [grid]
        kpen = [1e3, 1e5]
        order = [1, 2]
        method = ["newton", "lagrange"]
    """))
    name, cases = load_spec(spec)
    assert name == "mine" and len(cases) == 8
    assert {c.get("n") for c in cases} == {8} and {c.get("order") for c in cases} == {1, 2}


@pytest.mark.parametrize("text,message", [
    ('name = "x"\n[grid]\nkpn = [1]', "unknown parameter 'kpn'"),
    ('name = "x"\n[grid]\norder = [1.5]', "order must be an integer"),
    ('name = "x"\n[grid]\nkpen = []', "non-empty list"),
    ('name = "x"\n[grid]\nmethod = ["sphere"]', "method must be one of"),
    ('name = "x"\n[grid]\nout = ["/tmp"]', "unknown parameter 'out'"),
    ('name = "kpen"\n[grid]\nn = [4]', "built-in study"),
    ('name = "bench"\n[grid]\nn = [4]', "study name"),
    (f'name = "{"y" * 300}"\n[grid]\nn = [4]', "study name"),
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


@pytest.mark.parametrize("text", ["[1, 2]", '"name"', "3"])
def test_a_json_spec_must_be_an_object(tmp_path, text):
    spec = tmp_path / "s.json"
    spec.write_text(text)
    with pytest.raises(SpecError, match="top level"):
        load_spec(spec)


def cli(*args, **kw):
    return subprocess.run([sys.executable, "-m", "driver", *args], cwd=kw.pop("cwd", ROOT),
                          capture_output=True, text=True, **kw)


@pytest.mark.parametrize("args,word", [
    (["sweep", "kpen", "--jobs", "0"], "--jobs"),
    (["sweep", "kpen", "--timeout", "-1"], "--timeout"),
    (["sweep", "nosuch"], "unknown study 'nosuch'"),
    (["sweep"], "at least one study"),
])
def test_cli_rejects_bad_arguments(args, word):
    proc = cli(*args)
    assert proc.returncode == 2 and word in proc.stderr


def test_run_takes_every_solver_option_and_prints_json_at_full_precision(tmp_path):
    proc = cli("run", "--n", "8", "--method", "lagrange", "--nu", "0.4999999", "--json",
               "--results", str(tmp_path))
    assert proc.returncode in (0, 5), proc.stderr
    row = json.loads(proc.stdout)
    assert row["nu"] == 0.4999999 and row["method"] == "lagrange"
    assert row["status"] == {0: "converged", 5: "inaccurate"}[proc.returncode]


def test_run_passes_the_solvers_rejection_and_exit_code(tmp_path):
    proc = cli("run", "--kpen", "-1", "--results", str(tmp_path))
    assert proc.returncode == 2
    assert "-kpen must be a number in (0, inf), got '-1'" in proc.stderr


def test_run_help_lists_hertz_edp_options():
    out = cli("run", "--help").stdout
    for option in ("--kpen", "--gamma", "--method", "--start", "--accuracy", "--vtk", "--out", "--json"):
        assert option in out


def test_the_console_command_works_from_any_directory(tmp_path):
    hertz = shutil.which("hertz")
    if hertz is None:
        pytest.skip("the package is not installed (pip install -e .)")
    proc = subprocess.run([hertz, "options"], cwd=tmp_path, capture_output=True, text=True)
    assert proc.returncode == 0 and "-kpen" in proc.stdout


def test_sweep_exit_code_names_the_cases_that_should_have_converged(tmp_path):
    spec = tmp_path / "s.toml"
    spec.write_text('name = "mixed"\n[base]\nn = 8\nmethod = "lagrange"\n[grid]\nkpen = [1e5, -1.0]\n')
    proc = cli("sweep", "--spec", str(spec), "--results", str(tmp_path), "--no-progress")
    assert proc.returncode == 1
    assert "not converged: mixed/kpen=-1_method=lagrange_n=8: failed" in proc.stderr


def test_a_huge_grid_needs_yes(tmp_path):
    spec = tmp_path / "s.toml"
    values = ", ".join(str(1e3 + k) for k in range(200))
    spec.write_text(f'name = "huge"\n[grid]\nkpen = [{values}]\nE = [{values}]\n')
    proc = cli("sweep", "--spec", str(spec), "--results", str(tmp_path), "--no-progress")
    assert proc.returncode == 2 and "--yes" in proc.stderr


def test_more_jobs_than_cores_is_warned_and_recorded(tmp_path):
    spec = tmp_path / "s.toml"
    spec.write_text('name = "j"\n[base]\nn = 8\nmethod = "lagrange"\n[grid]\nkpen = [1e5]\n')
    jobs = os.cpu_count() * 4
    proc = cli("sweep", "--spec", str(spec), "--results", str(tmp_path), "--jobs", str(jobs), "--no-progress")
    assert "more than the" in proc.stderr and proc.returncode == 0
    assert table.read(tmp_path / "j.csv")["jobs"].iloc[0] == jobs


SLOW_SPEC = 'name = "slow"\n[base]\nn = 64\nmethod = "lagrange"\n[grid]\nkpen = [1e4, 1e6]\n'


def _freefem_with_marker() -> list[int]:
    return [int(p.name) for p in Path("/proc").iterdir() if p.name.isdigit() and _has_marker(p)]


@pytest.mark.parametrize("sig", [signal.SIGKILL, signal.SIGTERM, signal.SIGHUP, signal.SIGINT])
def test_killing_a_sweep_leaves_no_solver_running_and_resumes(tmp_path, sig):
    spec = tmp_path / "s.toml"
    spec.write_text(SLOW_SPEC)
    proc = subprocess.Popen([sys.executable, "-m", "driver", "sweep", "--spec", str(spec), "--results",
                             str(tmp_path), "--jobs", "2", "--no-progress"], cwd=ROOT,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    deadline = time.time() + 60
    while not _freefem_with_marker() and time.time() < deadline:
        time.sleep(0.05)
    assert _freefem_with_marker()
    time.sleep(0.5)
    proc.send_signal(sig)
    start = time.perf_counter()
    proc.wait(timeout=60)
    assert time.perf_counter() - start < 3  # a case takes 5 s: the driver did not wait for it
    time.sleep(0.5)
    assert not _freefem_with_marker()  # pdeathsig, or the handler, stopped them
    again = cli("sweep", "--spec", str(spec), "--results", str(tmp_path), "--no-progress")
    assert again.returncode == 0, again.stderr
    done = table.read(tmp_path / "slow.csv")
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


def test_plan_puts_costly_cases_first(tmp_path):
    cases = [Case.of(n=4), Case.of(n=64), Case.of(n=16, order=1), Case.of(n=32)]
    todo, _ = plan("t", cases, tmp_path)
    assert [c.get("n") for c in todo] == [64, 32, 16, 4]
