"""The driver against hostile or broken input: no write through a planted link, one row per
case whatever a rerun did, and one clear line (never a traceback) for every bad path, spec,
address or row."""
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd
import pytest
from test_studytable import _write_table

from driver import api, files, freefem, studytable
from driver.cases import Case
from driver.dask_backend import _write_file
from driver.errors import HertzError, OptionError, SpecError, SweepError
from driver.processes import PID_FILE, reap_leftover
from driver.run import run_case
from driver.studies import load_spec
from driver.sweeps import sweep

from conftest import REPO, checkout_first, cli, hertz, one_error_line, solvers_under

TINY = Case.of(n=4, L=50.0, farfield="clamped")  # ~0.1 s, inaccurate (an answer all the same)


def _precious(tmp_path):
    precious = tmp_path / "outside" / "precious.csv"
    precious.parent.mkdir()
    precious.write_text("keep me\n")
    return precious


# -- no write through a planted link ---------------------------------------------------------

@pytest.mark.parametrize("write", [
    lambda path: files.write_text_atomically(path, "new\n"),
    lambda path: _write_file(path, b"new\n"),  # a Dask worker's file, written on the client
])
def test_a_temporary_file_is_fresh_and_never_a_planted_link(tmp_path, write):
    precious = _precious(tmp_path)
    target = tmp_path / "t.csv"
    # every name a predictable temporary file could take, planted as a link to the precious file
    for pid in {os.getpid(), os.getppid()}:
        (tmp_path / f".t.csv.{pid}.part").symlink_to(precious)
        (tmp_path / f"t.csv.{pid}.part").symlink_to(precious)
    (tmp_path / "t.csv.part").symlink_to(precious)
    write(target)
    assert precious.read_text() == "keep me\n"
    assert target.read_text() == "new\n" and not target.is_symlink()
    assert not [p for p in tmp_path.iterdir() if p.is_dir() and p.name.endswith(".part")]


def test_a_run_removes_part_files_and_writes_through_no_planted_link(tmp_path):
    precious = _precious(tmp_path)
    workdir = tmp_path / "case"
    workdir.mkdir()
    for name in ("summary.csv.part", "history.csv.part", "profile.csv.part"):
        (workdir / name).symlink_to(precious)
    (workdir / "axis.csv.part").write_text("cut by a kill\n")
    row = run_case(TINY, workdir, timeout=120, summary_columns=freefem.summary_columns())
    assert row["status"] in ("converged", "inaccurate"), row["error"]
    assert precious.read_text() == "keep me\n"
    for name in ("summary.csv", "history.csv", "profile.csv"):
        assert (workdir / name).is_file() and not (workdir / name).is_symlink()
    assert not list(workdir.glob("*.part"))


def test_a_pid_file_that_names_no_case_kills_nothing(tmp_path):
    # a planted (or stale) freefem.pid would have the next run kill any process group of the user's
    bystander = subprocess.Popen(["sleep", "60"], start_new_session=True)
    try:
        workdir = tmp_path / "case"
        workdir.mkdir()
        (workdir / PID_FILE).write_text(f"{bystander.pid} {'0' * 32}\n")
        reap_leftover(workdir)
        time.sleep(0.2)
        assert bystander.poll() is None
        assert not (workdir / PID_FILE).exists()
    finally:
        bystander.kill()
        bystander.wait()


# -- one row per case ------------------------------------------------------------------------

def test_a_reader_sees_one_row_per_case_while_a_forced_rerun_is_cut_short(tmp_path):
    # an interrupted --force leaves both rows of a case in the file until the next sweep
    path = tmp_path / "t.csv"
    _write_table(path, [{"case_id": "a"}, {"case_id": "b"}, {"case_id": "c"},
                  {"case_id": "a", "p0_fe": 2.0}, {"case_id": "b", "status": "timeout", "p0_fe": ""}])
    said = []
    frame = studytable.read(path, say=said.append)
    assert sorted(frame["case_id"]) == ["a", "b", "c"]
    assert len(said) == 1 and "2 case(s) found again" in said[0]
    by_id = frame.set_index("case_id")
    assert by_id.loc["a", "p0_fe"] == 2.0  # the rerun's answer
    assert by_id.loc["b", "status"] == "converged"  # a rerun without an answer does not hide one


def test_a_forced_rerun_that_fails_keeps_the_answered_row_and_shows_the_failure(tmp_path):
    first = sweep("t", [TINY], tmp_path, jobs=1, timeout=120)
    assert first.table["status"].iloc[0] == "inaccurate"
    forced = sweep("t", [TINY], tmp_path, jobs=1, timeout=0.01, force=True)
    assert forced.ran == 1
    assert list(forced.table["status"]) == ["inaccurate"]
    assert list(studytable.read(tmp_path / "t.csv")["status"]) == ["inaccurate"]
    rerun = studytable.read(next((tmp_path / "stale").glob("t-unanswered-reruns-*.csv")))
    assert list(rerun["status"]) == ["timeout"]


def _contents(folder: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in folder.iterdir() if p.suffix == ".csv"}


def test_a_forced_rerun_that_fails_keeps_the_answered_rows_files(tmp_path):
    # the rows were kept, but the case folder had lost every file but the timed-out run's log
    sweep("t", [TINY], tmp_path, jobs=1, timeout=120)
    folder = next((tmp_path / "runs" / "t").iterdir())
    before = _contents(folder)
    assert "summary.csv" in before
    sweep("t", [TINY], tmp_path, jobs=1, timeout=0.01, force=True)
    assert _contents(folder) == before and (folder / "freefem.unanswered.log").is_file()
    assert not list(folder.glob(".earlier-*"))


def test_a_rerun_refused_or_cut_short_keeps_the_earlier_files(tmp_path):
    out = tmp_path / "out"
    first = api.solve(n=4, L=50.0, farfield="clamped", out=out)
    assert first.status == "inaccurate"
    before = _contents(out)
    with pytest.raises(HertzError):
        api.solve(n=4, L=50.0, farfield="clamped", d=0.6, out=out)  # refused: -d is at most R
    assert _contents(out) == before and (out / "freefem.log").is_file()
    assert not (out / "freefem.unanswered.log").exists()  # a refused run leaves nothing behind
    cut = api.solve(n=4, L=50.0, farfield="clamped", out=out, timeout=0.01)
    assert cut.status == "timeout" and _contents(out) == before
    # an answer replaces them together: no earlier file passes for the new run's
    again = api.solve(n=4, L=50.0, farfield="clamped", d=0.01, out=out)
    assert again.status in ("converged", "inaccurate") and _contents(out) != before
    assert not (out / "freefem.unanswered.log").exists()


def test_a_rerun_that_is_no_answer_keeps_the_earlier_answer_and_its_own_files_apart(tmp_path):
    # a maxiter rerun's files had replaced a converged run's: a result that is not trustworthy
    # never destroys results already written; its own files are data, kept apart
    out = tmp_path / "out"
    assert api.solve(n=8, out=out).status == "converged"
    before = _contents(out)
    failed = api.solve(n=8, E=20, maxit=1, out=out)
    assert failed.status == "maxiter" and _contents(out) == before
    kept = pd.read_csv(out / "unanswered" / "summary.csv")
    assert kept["status"].iloc[0] == "maxiter" and kept["E"].iloc[0] == 20
    # the next answer replaces both
    assert api.solve(n=8, E=20, out=out).status == "converged"
    assert _contents(out) != before and not (out / "unanswered").exists()


def test_prepare_keeps_the_answered_row_against_a_later_failure_and_says_so(tmp_path):
    path = tmp_path / "t.csv"
    columns = _write_table(path, [{"case_id": "a"}, {"case_id": "a", "status": "failed", "p0_fe": ""},
                            {"case_id": "b", "status": "failed", "p0_fe": ""}, {"case_id": "b"}])
    frame, messages = studytable.prepare(path, columns, freefem.edp_hash())
    assert sorted(zip(frame["case_id"], frame["status"])) == [("a", "converged"), ("b", "converged")]
    assert any("1 rerun(s) gave no answer" in m for m in messages), messages
    assert studytable.check(path, columns).unanswered_reruns == []  # the table itself is repaired


# -- one line, not a traceback ---------------------------------------------------------------

def test_an_endless_spec_file_is_one_line_at_once(tmp_path):
    start = time.monotonic()
    line = one_error_line(hertz("sweep", "--spec", "/dev/zero", cwd=tmp_path))
    assert "larger than" in line and time.monotonic() - start < 10


@pytest.mark.parametrize("cases, message", [("abc", "cases must be a list of option dicts"),
                                            ({"n": 8}, "cases must be a list of option dicts"),
                                            (5, "cases must be a list of option dicts"),
                                            ([1], r"cases\[0\] must be a dict of options"),
                                            ([{"n": 8}, "n"], r"cases\[1\] must be a dict of options"),
                                            ([], "cases is empty")])
def test_cases_that_are_not_option_dicts_are_the_packages_error(tmp_path, cases, message):
    with pytest.raises(OptionError, match=message):
        api.sweep("x", cases=cases, results=tmp_path)
    assert not list(tmp_path.iterdir())


def test_a_built_in_studys_table_takes_no_cases_of_the_callers(tmp_path):
    # sweep("units", cases=...) appended a foreign row to units.csv, which a spec named so is refused
    with pytest.raises(OptionError, match="'units' is a built-in study"):
        api.sweep("units", cases=[{"n": 8}], results=tmp_path)
    assert not list(tmp_path.iterdir())




@pytest.mark.parametrize("results", [5, None, 1.5, ""])
def test_a_results_folder_that_is_no_path_is_the_packages_error(tmp_path, monkeypatch, results):
    monkeypatch.chdir(tmp_path)  # were "" taken for the working folder, a run would land here
    with pytest.raises(OptionError, match="results must be a folder"):
        api.solve(n=8, results=results)
    with pytest.raises(OptionError, match="results must be a folder"):
        api.sweep("x", cases=[{"n": 8}], results=results)


@pytest.mark.parametrize("where", ["plain file", "under a plain file", "cannot be created"])
def test_a_results_folder_that_cannot_hold_a_run_is_one_line(tmp_path, where):
    plain = tmp_path / "plain"
    plain.write_text("not a folder\n")
    # (/proc takes no new folder, even from root, for whom a read-only mode means nothing)
    results = {"plain file": plain, "under a plain file": plain / "results",
               "cannot be created": "/proc/hertz-results"}[where]
    with pytest.raises(HertzError, match="cannot create the work folder") as caught:
        api.solve(n=8, results=results)
    assert "\n" not in str(caught.value)
    assert "cannot create the work folder" in one_error_line(
        hertz("run", "--n", "8", "--results", str(results), cwd=tmp_path))
    assert plain.read_text() == "not a folder\n"


def test_a_table_that_cannot_be_written_is_one_line(tmp_path):
    # (/proc takes no new file, even from root); the temporary file's own cleanup must not
    # raise over the error that names the table
    with pytest.raises(HertzError, match=r"cannot write /proc/hertz\.csv") as caught:
        files.write_text_atomically(Path("/proc/hertz.csv"), "a\n")
    assert "\n" not in str(caught.value)


def test_a_caller_that_ignores_sigchld_still_gets_its_answers(tmp_path):
    # the kernel reaps the children of such a process, and waiting for the solver failed
    previous = signal.signal(signal.SIGCHLD, signal.SIG_IGN)
    try:
        result = api.solve(n=4, L=50.0, farfield="clamped", results=tmp_path)
        table = api.sweep("t", cases=[{"n": 4, "L": 50.0, "farfield": "clamped"}], results=tmp_path)
        assert signal.getsignal(signal.SIGCHLD) is signal.SIG_IGN  # the caller's choice, given back
    finally:
        signal.signal(signal.SIGCHLD, previous)
    assert result.answered, result.error
    assert list(table["status"]) == ["inaccurate"], list(table["error"])


def test_a_sweep_started_with_sigchld_ignored_gets_its_answers(tmp_path):
    (tmp_path / "s.toml").write_text('name = "t"\n[base]\nL = 50.0\nfarfield = "clamped"\n[grid]\nn = [4]\n')
    # an ignored signal stays ignored across exec: the shell's choice reaches hertz
    proc = cli("sweep", "--spec", "s.toml", "--no-progress", cwd=tmp_path,
               preexec_fn=lambda: signal.signal(signal.SIGCHLD, signal.SIG_IGN))
    assert "Traceback" not in proc.stderr, proc.stderr
    assert list(studytable.read(tmp_path / "results" / "t.csv")["status"]) == ["inaccurate"]


# -- spec keys and cases that could only fail are refused up front -----------------------------

@pytest.mark.parametrize("text, message", [
    ('name = "x"\n[grid]\nout = ["/tmp"]', "unknown parameter 'out'"),
    ('name = "x"\n[grid]\ncheck = [1]', "unknown parameter 'check'"),
    ('name = "x"\n[grid]\nvtk = ["f.vtu"]', "unknown parameter 'vtk'"),
    ('name = "x"\n[base]\nshape = "table"\n[grid]\nn = [8]', "shape = 'table' needs -profile"),
    ('name = "x"\n[grid]\nshape = ["sphere", "table"]', "shape = 'table' needs -profile"),
    ('name = "x"\n[base]\nn = 8\n[grid]\nn = [16, 32]', "'n' is set in both \\[base\\] and \\[grid\\]"),
])
def test_spec_keys_that_can_only_fail_are_refused_with_one_line(tmp_path, text, message):
    spec = tmp_path / "s.toml"
    spec.write_text(text)
    with pytest.raises(SpecError, match=message) as caught:
        load_spec(spec)
    assert "\n" not in str(caught.value)
    assert one_error_line(hertz("sweep", "--spec", "s.toml", cwd=tmp_path))
    assert not (tmp_path / "results").exists()


@pytest.mark.parametrize("case, message", [
    ({"out": "elsewhere"}, "out is not a case option"),
    ({"check": 1}, "check is not a case option"),
    ({"profile": "p.csv"}, "profile cannot be given"),
    ({"shape": "table"}, "shape = 'table' needs -profile"),
    ({"vtk": "/abs/evil.vtu"}, "vtk must be a file name"),
    ({"vtk": "../../evil.vtu"}, "vtk must be a file name"),
])
def test_case_options_that_can_only_fail_or_escape_are_refused(tmp_path, case, message):
    with pytest.raises(OptionError, match=message):
        api.sweep("x", cases=[{"n": 8}, case], results=tmp_path)
    assert not list(tmp_path.iterdir())


# -- scheduler addresses ---------------------------------------------------------------------

@pytest.mark.parametrize("address, message", [("inproc://x", "SCHEME://HOST:PORT"),
                                              ("tcp://127.0.0.1:99999", "must be in 1..65535"),
                                              ("tcp://127.0.0.1:0", "must be in 1..65535"),
                                              ("127.0.0.1:port", "whole number"),
                                              ("tcp://:8786", "no host")])
def test_a_scheduler_address_no_scheduler_can_have_is_refused_at_once(tmp_path, address, message):
    (tmp_path / "s.toml").write_text('name = "t"\n[grid]\nn = [8]\n')
    start = time.monotonic()
    assert message in one_error_line(hertz("sweep", "--spec", "s.toml", "--scheduler", address, cwd=tmp_path))
    with pytest.raises(SweepError, match=message):
        api.sweep("t", cases=[{"n": 8}], results=tmp_path / "results", scheduler=address)
    assert time.monotonic() - start < 10
    assert not (tmp_path / "results" / "t.csv").exists()


# -- rows a reader cannot use are set aside, by line -----------------------------------------

def test_broken_rows_are_set_aside_by_line_and_the_rest_is_read(tmp_path):
    path = tmp_path / "t.csv"
    columns = _write_table(path, [{"case_id": "a", "wall_time": 2.5}, {"case_id": "b"}])
    good = path.read_text().splitlines()[1]
    with open(path, "a") as f:
        f.write(good.replace(",a,", ",extra,", 1) + ",one too many\n")   # line 4
        f.write(",".join(good.split(",")[:7]) + "\n")                    # line 5: truncated
        f.write("\x00\x01garbage" + "," * (len(columns) - 1) + "\n")     # line 6: empty case_id etc.
        f.write(good.replace(",a,", ",words,", 1).replace(",2.5,", ",lots,", 1) + "\n")  # line 7
    said = []
    frame = studytable.read(path, say=said.append)
    assert sorted(frame["case_id"]) == ["a", "b"]
    assert frame["wall_time"].dtype.kind == "f"  # a garbage word does not turn the numbers into text
    text = "\n".join(said)
    for expect in ("line 4 set aside", f"{len(columns) + 1} fields", "line 5 set aside", "line 6 set aside",
                   "line 7 set aside"):
        assert expect in text, (expect, text)
    assert len(said) == 4


def test_a_cut_last_line_is_set_aside_not_read_as_a_short_row(tmp_path):
    path = tmp_path / "t.csv"
    _write_table(path, [{"case_id": "a"}])
    with open(path, "a") as f:
        f.write("t,b,half")
    said = []
    assert list(studytable.read(path, say=said.append)["case_id"]) == ["a"]
    assert said and "line 3 set aside" in said[0]


def test_a_report_reads_a_table_with_broken_rows_and_names_them(tmp_path):
    # one row with an extra field used to abort the whole report
    table = subprocess.run(["git", "show", "HEAD:results/units.csv"], cwd=REPO, capture_output=True,
                           check=True, text=True).stdout
    last = table.splitlines()[-1]
    (tmp_path / "units.csv").write_text(table + last + ",extra\n" + last[:40] + "\n")
    proc = hertz("report", "--results", str(tmp_path))
    assert proc.returncode == 0, proc.stderr
    rows = len(table.splitlines())
    assert f"units.csv: line {rows + 1} set aside" in proc.stderr
    assert f"units.csv: line {rows + 2} set aside" in proc.stderr
    assert (tmp_path / "units.png").is_file()


def test_run_refuses_a_planted_link_on_the_way_to_its_folder(tmp_path):
    # a sweep refused it; hertz run wrote its case through it (exit 0)
    victim = tmp_path / "victim"
    victim.mkdir()
    (tmp_path / "results").mkdir()
    (tmp_path / "results" / "runs").symlink_to(victim)
    proc = hertz("run", "--n", "4", cwd=tmp_path)
    assert proc.returncode == 2 and "symbolic link" in one_error_line(proc) and not any(victim.iterdir())


def test_a_file_size_limit_is_a_write_failure_that_keeps_the_earlier_files(tmp_path):
    # SIGXFSZ killed the solver (a 'failed' row, 'killed by signal 25') after the files had been deleted
    out = tmp_path / "out"
    assert cli("run", "--n", "16", "--out", str(out)).returncode == 0
    before = _contents(out)
    command = f"ulimit -f 10; exec {sys.executable} -m driver run --n 16 --E 20 --out {out}"
    proc = subprocess.run(["bash", "-c", command], cwd=REPO, capture_output=True, text=True, timeout=120,
                          env=checkout_first(dict(os.environ)))
    assert proc.returncode == 4 and "cannot write the output files" in proc.stderr, proc.stderr
    assert _contents(out) == before


def test_a_terminated_run_says_so_and_keeps_the_earlier_files(tmp_path, fake_solver):
    # SIGTERM ended hertz run with 143 and no line, its earlier files left in a hidden .earlier-*
    out = tmp_path / "out"
    command = [sys.executable, "-m", "driver", "run", "--n", "4", "--L", "50", "--farfield", "clamped",
               "--out", str(out), "-q"]
    env = checkout_first(dict(os.environ))
    assert subprocess.run(command, cwd=REPO, env=env | {"FAKE_MODE": ""}, capture_output=True).returncode == 5
    before = _contents(out)
    proc = subprocess.Popen(command, cwd=REPO, env=env | {"FAKE_MODE": "slow", "FAKE_DELAY": "30"},
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 30
    while not solvers_under(tmp_path) and time.monotonic() < deadline:
        time.sleep(0.05)
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=30)
    assert proc.returncode == 143 and err.strip().startswith("interrupted:"), err
    assert _contents(out) == before and not list(out.glob(".earlier-*")) and not solvers_under(tmp_path)
