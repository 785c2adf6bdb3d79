"""The repository keeps its promises: one owner per fact, results from the current code."""
import os
import re
import shutil
import subprocess
import sys

import pytest

from driver import freefem, studytable
from driver.layout import EDP_DIR
from driver.studies import STUDIES

from conftest import REPO as ROOT

README = (ROOT / "README.md").read_text()
RESULTS_DIR = ROOT / "results"  # the committed tables


def test_readme_documents_every_option_and_every_summary_column():
    for option in freefem.options():
        assert f"`-{option}`" in README, option
    for column in freefem.summary_columns():
        assert f"`{column}`" in README, column


def test_the_fingerprint_ignores_comments_and_whitespace(tmp_path, monkeypatch):
    copy = tmp_path / "edp"
    shutil.copytree(EDP_DIR, copy)
    monkeypatch.setattr(freefem, "EDP_DIR", copy)
    before = freefem.edp_hash()
    target = copy / "lib" / "fe" / "section.idp"
    text = target.read_text()
    target.write_text("// a new comment\n" + text.replace("int edgeRefine = 4;", "int  edgeRefine  =  4 ;  /* why */"))
    assert freefem.edp_hash() == before
    target.write_text(text.replace("int edgeRefine = 4;", "int edgeRefine = 5;"))
    assert freefem.edp_hash() != before


@pytest.mark.parametrize("study", list(STUDIES))
def test_committed_results_come_from_the_current_solver_code(study):
    path = RESULTS_DIR / f"{study}.csv"
    assert path.is_file(), f"{path.name} is not committed: run 'make sweep'"
    hashes = set(studytable.read(path)["edp_hash"])
    assert hashes == {freefem.edp_hash()}, f"{path.name} is stale: run 'make sweep'"


def test_defaults_live_in_hertz_edp_only():
    # the driver names no solver default: the option table is hertz.edp's
    driver_code = "".join(p.read_text() for p in (ROOT / "driver").rglob("*.py"))
    for option in ("kpen", "gamma", "tol", "maxit"):
        default = freefem.options()[option].default
        assert not re.search(rf"\b{option}\s*[:=]\s*{re.escape(default)}\b", driver_code), option


SKIPPING = """
import pytest

def test_needs_something_missing():
    pytest.skip("the frobnicator is not installed")
"""


@pytest.mark.parametrize("allow,code", [("", 1), ("1", 0)])
def test_a_skip_without_an_allowed_reason_fails_the_suite(tmp_path, allow, code):
    # CI must not pass by not testing: a skip is an error unless its reason is allowed (or HERTZ_ALLOW_SKIPS=1)
    shutil.copy(ROOT / "tests" / "conftest.py", tmp_path)
    (tmp_path / "test_skip.py").write_text(SKIPPING)
    env = dict(os.environ, HERTZ_ALLOW_SKIPS=allow, PYTHONPATH=str(ROOT))
    proc = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-rs", str(tmp_path)],
                          cwd=tmp_path, env=env, capture_output=True, text=True)
    assert proc.returncode == code, proc.stdout
    assert "the frobnicator is not installed" in proc.stdout  # -rs: the reason is in the summary


def test_every_mutation_finds_the_code_it_breaks():
    # a mutation whose code has since changed breaks nothing: make mutate reported it only when
    # run, and two had gone stale that way
    from mutations import MUTATIONS
    stale = [m.name for m in MUTATIONS if (ROOT / m.path).read_text().count(m.old) != 1]
    assert not stale, stale
