"""driver/cli.py and driver/commands/: every command a user types works, or is one clear line and exit 2;
no input loses data, escapes its folder or hangs."""
import http.server
import importlib
import json
import os
import re
import shutil
import subprocess
import sys
import threading
import time

import pytest

import driver
from driver import studytable

from conftest import REPO, checkout_first, cli, hertz, one_error_line


def test_version():
    proc = hertz("--version")
    assert proc.returncode == 0 and proc.stdout.strip() == f"hertz {driver.__version__}"


@pytest.mark.parametrize("args,words", [
    (["sweep", "kpen", "--jobs", "0"], "--jobs"),
    (["sweep", "kpen", "--timeout", "-1"], "--timeout"),
    (["sweep", "kpen", "--timeout", "1e10"], "(0, 1e+06] seconds"),  # was an OverflowError, then no timeout
    (["run", "--timeout", "1e10"], "(0, 1e+06] seconds"),
    (["run", "--timeout", "inf"], "--timeout"),
    (["sweep", "nosuch"], "unknown study 'nosuch'"),
    (["sweep"], "at least one study"),
    (["run", "--n", "6", "--n", "8"], "--n is given twice"),  # n = 8 used to run
    (["sweep", "kpen", "--jobs", "1", "--jobs", "2"], "--jobs is given twice"),
    (["run", "--nu", "0.7"], "--nu must be a number in (-1, 0.5], got '0.7'"),
    (["run", "--kpen", "-1"], "--kpen must be a number in (0, inf), got '-1'"),
    (["run", "--model", "../../../../../victim"], "--model must be one of auto, axi, plane, 3d"),
    (["run", "--check", "1"], "unrecognized arguments"),
    # a second --d won silently; --version after a command was suggested as itself
    (["curve", "--d", "0.005:0.04:3", "--out", "c", "--d", "0.01:0.02:2"], "--d is given twice"),
    (["run", "--version"], "--version goes before the command (hertz --version)"),
])
def test_bad_arguments_are_one_line_and_exit_2(tmp_path, args, words):
    proc = hertz(*args, "--results", str(tmp_path / "results"), cwd=tmp_path)
    assert words in one_error_line(proc)
    assert proc.stdout == ""
    assert not (tmp_path / "results").exists()  # refused before any file was touched


def test_values_that_would_escape_the_results_folder_touch_nothing_outside(tmp_path):
    # --model ../../victim used to become part of the work folder, which escaped and was cleaned
    home = tmp_path / "a" / "b" / "c"
    home.mkdir(parents=True)
    victim = tmp_path / "victim"
    victim.mkdir()
    (victim / "precious.csv").write_text("keep me\n")
    before = sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*"))
    for args in (["--model", "../../../../victim"], ["--vtk", "../.."], ["--vtk", "../../../victim"]):
        proc = hertz("run", *args, cwd=home)
        assert proc.returncode == 2 and proc.stdout == "", proc.stderr
    assert (victim / "precious.csv").read_text() == "keep me\n"
    assert sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*")) == before


@pytest.mark.parametrize("args", [["--nu", "0.7"], ["--d", "0.6"], ["--method", "lagrange", "--d", "0.6"]])
def test_a_rejected_run_prints_only_the_error_and_leaves_nothing_behind(tmp_path, args):
    # it used to print the error, then a row of NaN on stdout, and leave a runs/single/... folder
    proc = hertz("run", *args, cwd=tmp_path)
    line = one_error_line(proc)
    assert "-nu" in line or "-d must be a number in (0, 1) R" in line
    assert proc.stdout == "" and list(tmp_path.iterdir()) == []


def test_run_takes_every_solver_option_and_prints_json_at_full_precision(tmp_path):
    proc = cli("run", "--n", "8", "--method", "lagrange", "--nu", "0.4999999", "--json",
               "--results", str(tmp_path))
    assert proc.returncode in (0, 5), proc.stderr
    row = json.loads(proc.stdout)
    assert row["nu"] == 0.4999999 and row["method"] == "lagrange"
    assert row["status"] == {0: "converged", 5: "inaccurate"}[proc.returncode]


def test_run_writes_under_the_working_folder_by_default(tmp_path):
    # an editable install used to write every run into the clone
    proc = cli("run", "--n", "8", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "results" / "runs" / "single" / "n=8" / "summary.csv").is_file()
    assert "files: results/runs/single/n=8" in proc.stderr


def test_run_out_refuses_a_folder_of_someone_elses_files(tmp_path):
    (tmp_path / "data").mkdir()
    (tmp_path / "data" / "measurements.csv").write_text("keep\n")
    line = one_error_line(hertz("run", "--n", "8", "--out", "data", cwd=tmp_path))
    assert "--out" in line and "no run of hertz wrote" in line
    assert (tmp_path / "data" / "measurements.csv").read_text() == "keep\n"
    first = cli("run", "--n", "8", "--out", "fresh", cwd=tmp_path)
    again = cli("run", "--n", "8", "--out", "fresh", cwd=tmp_path)  # its own earlier run: fine
    assert first.returncode == again.returncode == 0 and (tmp_path / "fresh" / "summary.csv").is_file()


def test_run_passes_the_solvers_exit_code(tmp_path):
    proc = cli("run", "--n", "4", "--L", "50", "--farfield", "clamped", "--results", str(tmp_path))
    assert proc.returncode == 5 and "status                    inaccurate" in proc.stdout


def test_a_case_beyond_the_memory_is_its_own_status_row_and_code(tmp_path):
    # under 1 GB of address space, n = 200 (992 MB measured) died of a segfault: a "failed" row
    proc = subprocess.run(["bash", "-c", f"ulimit -v 1000000; exec {sys.executable} -m driver run --n 200 "
                           f"--results {tmp_path}"], cwd=REPO, capture_output=True, text=True,
                          env=checkout_first(dict(os.environ)), timeout=120)
    assert proc.returncode == 6, proc.stdout[-400:] + proc.stderr
    assert re.search(r"^status +out-of-memory$", proc.stdout, re.M), proc.stdout
    assert proc.stderr.strip().splitlines()[-1].startswith("hertz.edp: error: out of memory: -n 200")


@pytest.mark.parametrize("command,says", [("run", "before its answer"), ("report", "whole"),
                                          ("sweep", "run the same command to resume")])
def test_ctrl_c_says_what_the_command_kept(monkeypatch, command, says):
    module = importlib.import_module(f"driver.commands.{command}")

    def interrupted(args):
        raise KeyboardInterrupt
    monkeypatch.setattr(module, "handle", interrupted)
    args = {"run": ["--n", "4"], "report": [], "sweep": ["mesh"]}[command]
    proc = hertz(command, *args)
    lines = proc.stderr.strip().splitlines()
    assert proc.returncode == 130 and len(lines) == 1 and lines[0].startswith("interrupted: "), proc.stderr
    assert says in proc.stderr and (command == "sweep") == ("resume" in proc.stderr), proc.stderr


def test_a_long_run_shows_its_levels_as_they_end(tmp_path):
    # a 3D hertz run printed nothing for 49 s; a run under 2 s stays quiet (the default's stderr is empty)
    proc = cli("run", "--n", "100", "--results", str(tmp_path))
    assert proc.returncode == 0, proc.stderr
    line = r"^hertz\.edp: progress: level 2, \d+ dofs: converged after \d+ iterations \(\d"
    assert re.search(line, proc.stderr, re.M), proc.stderr
    quiet = cli("run", "--n", "8", "--results", str(tmp_path))
    assert "progress" not in quiet.stderr and cli("run", "--n", "100", "-q", "--results",
                                                   str(tmp_path)).stderr == ""


def test_run_help_lists_hertz_edp_options():
    out = hertz("run", "--help").stdout
    for option in ("--kpen", "--gamma", "--method", "--start", "--accuracy", "--vtk", "--out", "--json"):
        assert option in out


def test_the_console_command_works_from_any_folder(tmp_path):
    hertz = shutil.which("hertz")
    assert hertz, "the package is not installed (make setup: pip install -e .)"
    import subprocess
    proc = subprocess.run([hertz, "options"], cwd=tmp_path, capture_output=True, text=True)
    assert proc.returncode == 0 and "-kpen" in proc.stdout


def test_a_relative_results_folder_is_the_users_from_any_folder(tmp_path):
    # make sweep-quick on a fresh clone: a relative --results reached FreeFEM as a relative -out
    (tmp_path / "s.toml").write_text('name = "tiny"\n[base]\nn = 8\n[grid]\nkpen = [1e5, 1e7]\n')
    proc = cli("sweep", "--spec", "s.toml", "--results", "rel/out", "--no-progress", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    rows = studytable.read(tmp_path / "rel" / "out" / "tiny.csv")
    assert len(rows) == 2 and (rows["status"] == "converged").all()
    assert "in rel/out/tiny.csv" in proc.stdout


def test_sweep_exit_code_names_the_cases_that_should_have_converged(tmp_path):
    spec = tmp_path / "s.toml"
    # d = 0.6 passes the driver (its range scales with R) and hertz.edp refuses it: a failed row
    spec.write_text('name = "mixed"\n[base]\nn = 8\nmethod = "lagrange"\n[grid]\nd = [0.02, 0.6]\n')
    proc = cli("sweep", "--spec", str(spec), "--results", str(tmp_path), "--no-progress")
    assert proc.returncode == 1
    assert "not converged: mixed/d=0.6_method=lagrange_n=8: failed" in proc.stderr


def test_more_jobs_than_cores_is_warned_and_recorded(tmp_path):
    spec = tmp_path / "s.toml"
    spec.write_text('name = "j"\n[base]\nn = 8\nmethod = "lagrange"\n[grid]\nkpen = [1e5]\n')
    jobs = os.cpu_count() * 4
    proc = cli("sweep", "--spec", str(spec), "--results", str(tmp_path), "--jobs", str(jobs), "--no-progress")
    assert "more than the" in proc.stderr and proc.returncode == 0
    assert studytable.read(tmp_path / "j.csv")["jobs"].iloc[0] == jobs


def test_a_table_that_is_a_folder_is_one_clear_error(tmp_path):
    (tmp_path / "t.csv").mkdir()
    (tmp_path / "s.toml").write_text('name = "t"\n[grid]\nn = [8]\n')
    assert "not a file" in one_error_line(cli("sweep", "--spec", "s.toml", "--results", ".", cwd=tmp_path))


def test_a_spec_integer_beyond_any_float_is_one_clear_error(tmp_path):
    (tmp_path / "s.toml").write_text('name = "big"\n[grid]\nn = [1' + "0" * 400 + "]\n")
    assert "n must be an integer in [3, 400]" in one_error_line(hertz("sweep", "--spec", "s.toml", cwd=tmp_path))


def test_tls_without_its_settings_is_one_clear_error(tmp_path):
    (tmp_path / "s.toml").write_text('name = "t"\n[grid]\nn = [8]\n')
    line = one_error_line(cli("sweep", "--spec", "s.toml", "--scheduler", "tls://127.0.0.1:1", "--no-progress",
                              cwd=tmp_path))
    assert "tls://127.0.0.1:1" in line and "TLS settings" in line


class _Dashboard(http.server.BaseHTTPRequestHandler):
    def do_GET(self):  # noqa: N802 - http.server's name
        self.send_response(200)
        self.end_headers()

    def log_message(self, *args):
        pass


@pytest.mark.slow
def test_a_scheduler_address_that_speaks_http_fails_within_the_connect_timeout(tmp_path):
    # the dashboard's port used to hang the sweep forever, with no output
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), _Dashboard)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    try:
        (tmp_path / "s.toml").write_text('name = "t"\n[grid]\nn = [8]\n')
        env = dict(os.environ, DASK_DISTRIBUTED__COMM__TIMEOUTS__CONNECT="3s")
        start = time.monotonic()
        proc = cli("sweep", "--spec", "s.toml", "--no-progress", "--scheduler",
                   f"tcp://127.0.0.1:{server.server_address[1]}", cwd=tmp_path, env=env, timeout=60)
        assert time.monotonic() - start < 30
        assert "no Dask scheduler answered" in one_error_line(proc)
    finally:
        server.shutdown()
