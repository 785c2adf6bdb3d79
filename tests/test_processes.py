"""driver/processes.py: a case's processes die with it, runs of one case never kill each
other, a leftover of a killed run is found again, and orphans are reaped."""
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

from driver.processes import PID_FILE, Busy, CaseLock, reap_leftover

from conftest import REPO, cli, run_fault, solvers_under


def test_a_case_folder_holds_one_run_at_a_time(tmp_path):
    with CaseLock(tmp_path / "case"):
        with pytest.raises(Busy, match="another run is using"):
            with CaseLock(tmp_path / "case"):
                pass
    with CaseLock(tmp_path / "case"):  # released with its holder
        pass


def test_a_pid_file_of_nothing_alive_kills_nothing_and_goes(tmp_path):
    (tmp_path / PID_FILE).write_text("not a pid file\n")
    assert reap_leftover(tmp_path) == 0
    assert not (tmp_path / PID_FILE).exists()


def test_a_detached_child_is_killed_with_its_case(fake_solver, tmp_path, monkeypatch):
    row = run_fault("detached_child", tmp_path, monkeypatch)
    assert row["status"] == "converged"
    time.sleep(0.2)
    assert not solvers_under(tmp_path)


@pytest.mark.slow
def test_two_runs_of_one_case_at_once_both_finish(fake_solver, tmp_path):
    # the second run used to take the first's pid file for a leftover and kill it
    env = dict(os.environ, FAKE_MODE="slow", FAKE_DELAY="3")
    first = subprocess.Popen([sys.executable, "-m", "driver", "run", "--n", "8", "--results", str(tmp_path)],
                             cwd=REPO, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 30
    while not solvers_under(tmp_path) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert solvers_under(tmp_path), "the first run did not start"
    second = cli("run", "--n", "8", "--results", str(tmp_path), env=dict(os.environ, FAKE_MODE=""))
    out, err = first.communicate(timeout=60)
    assert second.returncode == 0, second.stderr
    assert first.returncode == 0, err  # not killed by the second
    folders = {line.split("files: ")[1] for line in (err + second.stderr).splitlines() if "files: " in line}
    assert len(folders) == 2 and all(Path(f).is_dir() for f in folders), folders  # a folder each


SUBREAPER = """
import ctypes, sys
{imports}
value = ctypes.c_int()
ctypes.CDLL(None).prctl(37, ctypes.byref(value), 0, 0, 0)  # PR_GET_CHILD_SUBREAPER
print(value.value)
"""


def test_importing_the_driver_changes_nothing_in_the_process():
    # a subreaper adopts every orphan below it: only the sweep command may become one
    imports = ("import driver, driver.processes, driver.run, driver.sweeps, driver.api, driver.report, driver.cli, "
               "driver.commands.sweep")
    proc = subprocess.run([sys.executable, "-c", SUBREAPER.format(imports=imports)], cwd=REPO,
                          capture_output=True, text=True)
    assert proc.stdout.strip() == "0", proc.stderr


REAPED = """
import os, sys, time
from pathlib import Path
from driver import processes, run
from driver.cases import Case
assert processes.become_subreaper()
row = run.run_case(Case.of(n=8), Path(sys.argv[1]), timeout=60)
time.sleep(2.5)  # the orphan exits after 1 s; the reaper looks every 0.5 s
me = os.getpid()
zombies = [p.name for p in Path("/proc").iterdir() if p.name.isdigit()
           and (s := processes._stat(p.name)) and s[0] == "Z" and s[1] == me]
print(row["status"], len(zombies))
"""


@pytest.mark.slow
def test_a_sweep_process_reaps_the_orphans_it_adopts(fake_solver, tmp_path):
    # a helper of the case outlives it without its marker: handed to the subreaper, it must not stay a zombie
    proc = subprocess.run([sys.executable, "-c", REAPED, str(tmp_path / "c")], cwd=REPO, capture_output=True,
                          text=True, env=dict(os.environ, FAKE_MODE="orphan_exits"), timeout=120)
    assert proc.stdout.split() == ["converged", "0"], proc.stdout + proc.stderr
