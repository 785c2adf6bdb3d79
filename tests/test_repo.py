"""The repository keeps its promises: one owner per fact, results from the current code."""
import re
import shutil

import pytest

from driver import EDP_DIR, RESULTS_DIR, ROOT, freefem, table
from driver.studies import STUDIES

README = (ROOT / "README.md").read_text()


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
    target = copy / "lib" / "fe" / "mesh2d.idp"
    text = target.read_text()
    target.write_text("// a new comment\n" + text.replace("int edgeRefine = 4;", "int  edgeRefine  =  4 ;  /* why */"))
    assert freefem.edp_hash() == before
    target.write_text(text.replace("int edgeRefine = 4;", "int edgeRefine = 5;"))
    assert freefem.edp_hash() != before


@pytest.mark.parametrize("study", list(STUDIES))
def test_committed_results_come_from_the_current_solver_code(study):
    path = RESULTS_DIR / f"{study}.csv"
    if not path.exists():
        pytest.skip(f"{path.name} not swept yet")
    hashes = set(table.read(path)["edp_hash"])
    assert hashes == {freefem.edp_hash()}, f"{path.name} is stale: run 'make sweep'"


def test_defaults_live_in_hertz_edp_only():
    # the driver names no solver default: the option table is hertz.edp's
    driver_code = "".join(p.read_text() for p in (ROOT / "driver").glob("*.py"))
    for option in ("kpen", "gamma", "tol", "maxit"):
        default = freefem.options()[option].default
        assert not re.search(rf"\b{option}\s*[:=]\s*{re.escape(default)}\b", driver_code), option
