"""The loading chart: every axis has units and at least two labelled ticks, and a panel shows
each point's error against its reference. Drawn from the committed loading.csv (copied out of git)."""
import subprocess

import matplotlib.pyplot as plt
import pytest

from driver import studytable
from driver.charts import loading as chart

from conftest import REPO


@pytest.fixture(scope="module")
def figure(tmp_path_factory):
    table = tmp_path_factory.mktemp("loading") / "loading.csv"
    table.write_bytes(subprocess.run(["git", "show", "HEAD:results/loading.csv"], cwd=REPO, capture_output=True,
                                     check=True).stdout)
    drawn = []
    original = chart.save
    chart.save = lambda fig, path: drawn.append(fig) or path
    try:
        chart.loading(studytable.read(table), table.with_suffix(".png"))
    finally:
        chart.save = original
    fig = drawn[0]
    fig.canvas.draw()
    yield fig
    plt.close(fig)


def labelled(axis) -> list[str]:
    low, high = sorted(axis.get_view_interval())
    return [t.get_text() for t in axis.get_ticklabels(which="both") if t.get_text() and low <= t.get_position()[
        0 if axis.axis_name == "x" else 1] <= high]


def test_every_axis_has_units_and_two_labelled_ticks(figure):
    assert len(figure.axes) == 4
    for ax in figure.axes:
        for axis, label in ((ax.xaxis, ax.get_xlabel()), (ax.yaxis, ax.get_ylabel())):
            assert "[" in label, label  # its unit, in the scene's units
            assert len(labelled(axis)) >= 2, (ax.get_title(), axis.axis_name, labelled(axis))


def test_an_error_panel_shows_each_series_against_its_reference(figure):
    errors = figure.axes[3]
    assert "error" in errors.get_ylabel()
    shown = {line.get_label().split(":")[0] for line in errors.get_lines()}
    assert shown == set(chart.ERROR_PANEL), shown
