"""The driver against hostile or broken input: no write through a planted link, one row per
case whatever a rerun did, and one clear line (never a traceback) for every bad path, spec,
address or row."""
import os
import time

import pytest

from driver import api, files, freefem
from driver.cases import Case
from driver.dask_backend import _write_file
from driver.errors import HertzError, SweepError
from driver.run import run_case

from conftest import hertz, one_error_line

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


# -- one line, not a traceback ---------------------------------------------------------------

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
