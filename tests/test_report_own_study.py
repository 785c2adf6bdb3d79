"""hertz report charts a study of the user's own (hertz sweep --spec): <name>.png and its section
of REPORT.md, beside the built-in charts it skips for want of their tables."""
import pandas as pd
import pytest

from driver import layout
from driver.report import own_tables

from conftest import cli

SPEC = 'name = "soft"\n[base]\nE = 1.0\n[grid]\nn = [8, 16]\nmethod = ["newton", "lagrange"]\n'


@pytest.fixture(scope="module")
def own_results(tmp_path_factory):
    root = tmp_path_factory.mktemp("own")
    (root / "soft.toml").write_text(SPEC)
    results = root / "results"
    proc = cli("sweep", "--spec", str(root / "soft.toml"), "--results", str(results), "--no-progress")
    assert proc.returncode == 0, proc.stderr
    return results


def test_a_users_own_study_is_charted_with_its_section(own_results):
    proc = cli("report", "--results", str(own_results))
    assert proc.returncode == 0, proc.stderr
    assert (own_results / "soft.png").read_bytes().startswith(b"\x89PNG")
    text = (own_results / layout.REPORT_FILE).read_text()
    assert "## Study soft\n\n![soft](soft.png)" in text and "from 4 cases (soft: 4)" in text
    # the built-in charts say why they are missing, in one line (a chart read a pandas KeyError's text)
    assert "skipped the built-in charts: no built-in study rows" in proc.stderr, proc.stderr
    assert "not in index" not in proc.stderr and "skipped penalty.png" not in proc.stderr


def test_only_study_tables_are_a_users_studies(own_results, tmp_path):
    pd.DataFrame({"h": [0.01], "P": [0.1]}).to_csv(tmp_path / "curve.csv", index=False)  # hertz curve's table
    (tmp_path / "sweep_environment.csv").write_text("study,case_id,status\n")  # the driver's own name
    (tmp_path / "kpen.csv").write_text((own_results / "soft.csv").read_text())  # a built-in study's name
    (tmp_path / "mine.csv").write_text((own_results / "soft.csv").read_text())
    assert list(own_tables(tmp_path)) == ["mine"]


def test_the_series_are_the_options_that_vary_besides_n(own_results):
    from driver.charts.own_study import series_of
    rows = pd.read_csv(own_results / "soft.csv")
    assert sorted(series_of(rows).unique()) == ["method lagrange", "method newton"]


def test_a_study_without_a_reference_is_charted_by_its_estimate(tmp_path):
    # coated bodies (and adhesion) have no true error: the report crashed on the log axis of NaNs
    (tmp_path / "coat.toml").write_text('name = "coat"\n[base]\nt = 0.05\nE2 = 100\n[grid]\nn = [8, 16]\n')
    results = tmp_path / "results"
    assert cli("sweep", "--spec", str(tmp_path / "coat.toml"), "--results", str(results),
               "--no-progress").returncode == 0
    proc = cli("report", "--results", str(results))
    assert proc.returncode == 0 and "Traceback" not in proc.stderr, proc.stderr
    assert (results / "coat.png").read_bytes().startswith(b"\x89PNG")
