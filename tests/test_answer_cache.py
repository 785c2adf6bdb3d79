"""hertz.edp's answers to -options, -columns and -exits are kept in the user's cache folder,
keyed by the solver's fingerprint and the FreeFem++ that gave them, and summary.csv is read
without pandas: a single `hertz run` costs little beyond the solver's own run."""
import math
import os
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest

from driver import freefem, layout, run

from conftest import REPO, checkout_first

CACHED = (freefem._options, freefem._exits, freefem._columns)


@pytest.fixture
def cache(tmp_path, monkeypatch):
    """A cache folder of this test's own, and no answer held in this process before or after it."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    for held in CACHED:
        held.cache_clear()
    yield tmp_path / "cache" / layout.CACHE_FOLDER
    for held in CACHED:
        held.cache_clear()


def _ask_all():
    return freefem.options(), freefem.exits(), freefem.summary_columns()


def test_the_answers_are_kept_on_disk_and_read_back_without_freefem(cache, monkeypatch):
    asked = _ask_all()
    kept = sorted(p.name for p in cache.iterdir())
    assert len(kept) == 3 and all(name.startswith(freefem.edp_hash()) for name in kept), kept
    for held in CACHED:
        held.cache_clear()

    def no_solver(flag):
        raise AssertionError(f"hertz.edp {flag} was asked again")
    monkeypatch.setattr(freefem, "_query", no_solver)
    assert _ask_all() == asked


def test_a_cut_or_foreign_answer_is_asked_again(cache):
    _ask_all()
    for path in cache.iterdir():
        path.write_text("name,kind\n" if "options" in path.name else "garbage\n")
    for held in CACHED:
        held.cache_clear()
    options, exits, columns = _ask_all()
    assert "kpen" in options and exits["converged"].code == 0 and "p0_fe" in columns
    assert all("garbage" not in path.read_text() for path in cache.iterdir())


def test_another_freefem_or_other_solver_code_has_answers_of_its_own(cache, fake_solver):
    # the stand-in on PATH (tests/fake_freefem.py) may answer otherwise: its answers are not the real one's
    with_fake = freefem._cache_file("-options", "0123456789ab")
    os.environ["PATH"] = os.environ["PATH"].split(os.pathsep, 1)[1]  # monkeypatch restores it
    real = freefem._cache_file("-options", "0123456789ab")
    assert with_fake != real and with_fake.parent == real.parent == cache
    assert freefem._cache_file("-options", "ba9876543210") != real


def test_the_cache_folder_is_the_users_never_the_package(tmp_path, monkeypatch):
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert layout.cache_dir() == tmp_path / "xdg" / "hertz-contact"
    monkeypatch.setenv("XDG_CACHE_HOME", "relative/cache")  # not absolute: XDG says ignore it
    assert layout.cache_dir() == tmp_path / "home" / ".cache" / "hertz-contact"
    monkeypatch.delenv("XDG_CACHE_HOME")
    assert layout.cache_dir() == tmp_path / "home" / ".cache" / "hertz-contact"


def test_an_unwritable_cache_costs_only_speed(tmp_path, monkeypatch):
    blocked = tmp_path / "file"
    blocked.write_text("")
    monkeypatch.setenv("XDG_CACHE_HOME", str(blocked))  # a file where the folder would go
    for held in CACHED:
        held.cache_clear()
    try:
        assert "kpen" in freefem.options()
    finally:
        for held in CACHED:
            held.cache_clear()


@pytest.mark.parametrize("cells,expected", [
    ({"p0_fe": "nan", "F_fe": "-nan", "a_fe": ""}, {"p0_fe": math.nan, "F_fe": math.nan, "a_fe": math.nan}),
    ({"p0_fe": "inf", "n": "16", "tol": "1e-08"}, {"p0_fe": math.inf, "n": 16, "tol": 1e-08}),
    ({"warnings": "", "status": "converged"}, {"warnings": math.nan, "status": "converged"}),
    ({"warnings": "nan", "p0_fe": "NA"}, {"warnings": math.nan, "p0_fe": math.nan}),
])
def test_summary_csv_reads_as_pandas_reads_it(solve, tmp_path, cells, expected):
    source = solve("-n", "8").outdir / "summary.csv"
    head, row = source.read_text().splitlines()[:2]
    columns = head.split(",")
    fields = row.split(",")
    for name, text in cells.items():
        fields[columns.index(name)] = text
    path = tmp_path / "summary.csv"
    path.write_text(f"{head}\n{','.join(fields)}\n")
    mine, why = run.read_summary(path, freefem.summary_columns())
    assert why == "" and mine is not None
    text = {c: str for c in run.schema.text_columns()}
    theirs = pd.read_csv(path, dtype=text).iloc[0].to_dict()
    assert list(mine) == list(theirs)
    for name in columns:
        a, b = mine[name], theirs[name]
        assert (a == b and type(a) is type(b)) or (a != a and b != b), (name, a, b)
    for name, value in expected.items():
        assert mine[name] == value or (value != value and mine[name] != mine[name]), name


@pytest.mark.parametrize("text", ["1_0", " 1", "abc", "0x10"])
def test_a_word_in_a_number_column_is_not_a_number(solve, tmp_path, text):
    source = solve("-n", "8").outdir / "summary.csv"
    head, row = source.read_text().splitlines()[:2]
    fields = row.split(",")
    fields[head.split(",").index("p0_fe")] = text
    path = tmp_path / "summary.csv"
    path.write_text(f"{head}\n{','.join(fields)}\n")
    assert run.read_summary(path, freefem.summary_columns()) == (None, f"summary.csv: p0_fe is not a number: {text!r}")


def test_hertz_run_imports_no_pandas(tmp_path):
    code = ("import sys; from driver.cli import main; code = main(['run', '--n', '8', '--out', sys.argv[1]]); "
            "print('pandas' in sys.modules); sys.exit(code)")
    proc = subprocess.run([sys.executable, "-c", code, str(tmp_path / "out")], cwd=tmp_path, capture_output=True,
                          text=True, env=checkout_first(dict(os.environ)))
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.split()[-1] == "False"


def test_the_cache_is_not_in_the_repository():
    assert REPO not in layout.cache_dir().parents and layout.PACKAGE_DIR not in layout.cache_dir().parents
    assert isinstance(layout.cache_dir(), Path)
