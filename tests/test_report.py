"""The report reads CSV files only: it works without FreeFEM, and its table matches the data."""
import os
import re
import shutil
import subprocess
import sys

import pytest

from driver import ROOT, table
from driver.plots import sphere_cases
from driver.report import LEVELS


def test_report_runs_without_freefem_and_matches_the_data(quick_results, tmp_path):
    results = tmp_path / "results"
    shutil.copytree(quick_results, results, ignore=shutil.ignore_patterns("runs", "*.lock"))
    env = dict(os.environ, PATH=os.path.dirname(sys.executable))  # no FreeFem++ here
    proc = subprocess.run([sys.executable, "-m", "driver", "report", "--results", str(results)],
                          cwd=ROOT, env=env, capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    text = (results / "REPORT.md").read_text()
    images = re.findall(r"!\[[^\]]*\]\(([^)]+\.png)\)", text)
    assert len(images) >= 10
    for image in images:
        data = (results / image).read_bytes()
        assert data.startswith(b"\x89PNG") and len(data) > 20_000, image
    assert "FreeFEM 4.11" in text and "commit" in text  # versions, date and commit

    speed = {"speed": table.read(results / "speed.csv")}
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


def test_the_field_picture_renders_the_stress_near_the_contact(tmp_path):
    pytest.importorskip("pyvista")
    import matplotlib.image

    from driver.fields import make_field_picture
    png = make_field_picture(tmp_path)
    image = matplotlib.image.imread(png)
    assert image.shape[0] >= 500 and image.shape[1] >= 800
    # a coloured field, not a blank window: many distinct colours
    colours = {tuple(px) for px in (image[::7, ::7, :3] * 255).astype(int).reshape(-1, 3)}
    assert len(colours) > 200
    assert (tmp_path / "runs" / "field" / "seed_near.vtu").exists()
