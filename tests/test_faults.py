"""Interrupted, killed and concurrent sweeps lose and corrupt nothing."""
import os
import signal
import subprocess
import sys
import time

import pandas as pd
import pytest

from driver import ROOT
from driver.schema import STUDY_COLUMNS

SPEC = """
name = "faults"
[base]
n = 6
L = 50.0
[grid]
kpen = [1e3, 1e4, 1e5, 1e6, 1e7, 1e8]
"""


def start_sweep(spec, results):
    return subprocess.Popen([sys.executable, "-m", "driver", "sweep", "--spec", str(spec),
                             "--results", str(results), "--jobs", "1", "--no-progress"],
                            cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def wait_for_rows(csv, count, proc, limit=120):
    deadline = time.time() + limit
    while time.time() < deadline and proc.poll() is None:
        if csv.exists() and len(csv.read_text().splitlines()) - 1 >= count:
            return
        time.sleep(0.05)
    raise AssertionError("the sweep did not write rows in time")


def check_complete(csv, expected):
    frame = pd.read_csv(csv)
    assert list(frame.columns) == STUDY_COLUMNS
    assert len(frame) == expected and frame["case_id"].is_unique
    assert frame["status"].notna().all() and (frame["status"] == "converged").all()
    assert csv.read_text().endswith("\n")


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGKILL], ids=["SIGINT", "SIGKILL"])
def test_interrupted_sweep_resumes_to_a_complete_table(tmp_path, sig):
    spec = tmp_path / "spec.toml"
    spec.write_text(SPEC)
    csv = tmp_path / "faults.csv"
    proc = start_sweep(spec, tmp_path)
    wait_for_rows(csv, 2, proc)
    proc.send_signal(sig)
    proc.communicate(timeout=60)
    assert proc.returncode == (130 if sig == signal.SIGINT else -9)
    kept = pd.read_csv(csv)
    assert 2 <= len(kept) < 6 and kept["case_id"].is_unique
    again = start_sweep(spec, tmp_path)
    out, err = again.communicate(timeout=300)
    assert again.returncode == 0, err
    check_complete(csv, 6)


def test_two_sweeps_of_one_study_do_not_both_write(tmp_path):
    spec = tmp_path / "spec.toml"
    spec.write_text(SPEC)
    first = start_sweep(spec, tmp_path)
    wait_for_rows(tmp_path / "faults.csv", 1, first)
    second = start_sweep(spec, tmp_path)
    _, err = second.communicate(timeout=60)
    assert second.returncode == 2 and "another sweep is writing faults.csv" in err
    assert first.wait(timeout=300) == 0
    check_complete(tmp_path / "faults.csv", 6)


def test_missing_freefem_is_a_clear_cli_error(tmp_path):
    env = dict(os.environ, PATH=os.path.dirname(sys.executable))
    proc = subprocess.run([sys.executable, "-m", "driver", "sweep", "kpen", "--quick",
                           "--results", str(tmp_path)], cwd=ROOT, env=env,
                          capture_output=True, text=True)
    assert proc.returncode == 2
    assert "FreeFem++ is not on PATH" in proc.stderr and "make setup" in proc.stderr
