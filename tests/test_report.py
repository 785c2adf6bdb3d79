"""driver/report.py: the report reads CSV files only, draws what its data allows, and never leaves a cut chart."""
import os
import re
import shutil
import subprocess
import sys

import matplotlib.figure
import pytest

from driver import charts, studytable
from driver.charts.common import sphere_cases
from driver.errors import ReportError
from driver.report import CHARTS, LEVELS, write_report
from driver.studies import STUDIES

from conftest import REPO, cli, one_error_line


def _copy(quick_results, target, studies=None):
    shutil.copytree(quick_results, target, ignore=shutil.ignore_patterns("runs", "*.lock", "*.png", "REPORT.md"))
    for name in STUDIES:
        if studies is not None and name not in studies:
            (target / f"{name}.csv").unlink()
            shutil.rmtree(target / name, ignore_errors=True)
    return target


def test_report_runs_without_freefem_and_matches_the_data(quick_results, tmp_path):
    results = _copy(quick_results, tmp_path / "results")
    env = dict(os.environ, PATH=os.path.dirname(sys.executable))  # no FreeFem++ here
    proc = cli("report", "--results", str(results), env=env)
    assert proc.returncode == 0, proc.stderr
    text = (results / "REPORT.md").read_text()
    images = re.findall(r"!\[[^\]]*\]\(([^)]+\.png)\)", text)
    assert len(images) == len(CHARTS)
    for image in images:
        data = (results / image).read_bytes()
        assert data.startswith(b"\x89PNG") and len(data) > 20_000, image
    assert "FreeFEM 4.11" in text and "commit" in text  # versions, date and commit

    speed = {"speed": studytable.read(results / "speed.csv")}
    candidates = sphere_cases(speed)
    lines = [ln for ln in text.splitlines() if ln.startswith("| ") and "%" in ln.split("|")[1]]
    assert 1 <= len(lines) <= len(LEVELS)
    for line in lines:
        cells = [c.strip() for c in line.strip("|").split("|")]
        level = float(cells[0].rstrip("%")) / 100
        row = candidates.set_index("case_id").loc[cells[-1].strip("`")]
        assert row["max_err"] <= level
        assert float(cells[4]) == round(row["wall_time"], 3) and cells[5] == row["timings"]
        # nothing in the speed study reaches the level faster (medians of repeated runs)
        assert candidates[candidates["max_err"] <= level]["wall_time"].min() == row["wall_time"]


@pytest.mark.parametrize("study", list(STUDIES))
def test_one_study_alone_gives_its_charts_and_a_note_for_each_other(quick_results, tmp_path, study):
    # with one study present most charts used to raise (No objects to concatenate, ...)
    results = _copy(quick_results, tmp_path / "results", studies={study})
    notes: list[str] = []
    report = write_report(results, say=notes.append)
    drawn = re.findall(r"!\[([^\]]*)\]", report.read_text())
    assert len(drawn) + len(notes) == len(CHARTS), (drawn, notes)
    assert all(re.fullmatch(r"skipped \w+\.png: .+", note) for note in notes), notes


def test_header_only_tables_are_skipped_with_a_note(quick_results, tmp_path):
    results = _copy(quick_results, tmp_path / "results", studies={"kpen"})
    for name in ("mesh", "stability", "3d"):  # a sweep that wrote its header and was stopped
        (results / f"{name}.csv").write_text((results / "kpen.csv").read_text().splitlines()[0] + "\n")
    notes: list[str] = []
    write_report(results, say=notes.append)
    assert "skipped mesh.png: mesh.csv has no rows" in notes
    assert "skipped stability.png: stability.csv has no rows" in notes
    assert "skipped pressure_profiles.png: no figures.csv" in notes
    assert (results / "penalty.png").is_file()
    for name in STUDIES:
        if name != "kpen":
            (results / f"{name}.csv").unlink(missing_ok=True)
    (results / "kpen.csv").write_text((results / "kpen.csv").read_text().splitlines()[0] + "\n")
    assert "no study rows" in one_error_line(cli("report", "--results", str(results)))


def test_an_interrupted_chart_leaves_the_old_one_whole(quick_results, tmp_path, monkeypatch):
    # Ctrl-C during report used to replace a good penalty.png by 124 bytes
    results = _copy(quick_results, tmp_path / "results", studies={"kpen"})
    write_report(results, say=lambda note: None)
    good = {p.name: p.read_bytes() for p in results.glob("*.png")}

    def cut_short(self, target, **kwargs):
        with open(target, "wb") as f:
            f.write(b"\x89PNG cut")
        raise KeyboardInterrupt
    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", cut_short)
    with pytest.raises(KeyboardInterrupt):
        write_report(results, say=lambda note: None)
    assert {p.name: p.read_bytes() for p in results.glob("*.png")} == good  # the chart cut short too
    assert not list(results.glob(".*.part"))


def test_a_full_disk_is_one_clear_error_and_keeps_the_charts(quick_results, tmp_path):
    # a full disk used to give a PIL traceback; a file size limit fails writes the same way
    results = _copy(quick_results, tmp_path / "results", studies={"kpen", "mesh"})
    write_report(results, say=lambda note: None)
    charts = {p.name: p.read_bytes() for p in results.glob("*.png")}
    command = f"ulimit -f 40; trap '' XFSZ; exec {sys.executable} -m driver report --results {results}"
    proc = subprocess.run(["bash", "-c", command], cwd=REPO, capture_output=True, text=True)
    line = one_error_line(proc)
    assert "cannot write" in line and "File too large" in line
    assert {p.name: p.read_bytes() for p in results.glob("*.png")} == charts


def test_no_tables_at_all_is_one_clear_error(tmp_path):
    with pytest.raises(charts.NoData):
        sphere_cases({})
    with pytest.raises(ReportError, match="no study rows"):
        write_report(tmp_path)
    assert list(tmp_path.iterdir()) == []


def test_the_report_imports_no_run_or_sweep_machinery():
    # it reads CSV files: the machinery that starts solvers (and would need FreeFEM) stays out
    code = ("import sys, driver.report, driver.commands.report; "
            "print(sorted(m for m in sys.modules if m.startswith('driver')))")
    proc = subprocess.run([sys.executable, "-c", code], cwd=REPO, capture_output=True, text=True)
    loaded = proc.stdout
    assert proc.returncode == 0 and "driver.charts" in loaded, proc.stderr
    for machinery in ("driver.run", "driver.sweeps", "driver.executors", "driver.dask_backend", "driver.api"):
        assert f"'{machinery}'" not in loaded, machinery
