"""The accuracy-against-speed chart: its Pareto front is drawn within one scene, and its legends
sit below the axes, off the points."""
import matplotlib.pyplot as plt
import pandas as pd
from test_report_deterministic import _committed_tables

from driver.charts import accuracy_vs_speed as chart
from driver.charts.common import sphere_cases
from driver.report import load_tables


def _rows(scene_d, times, errors, method="newton"):
    return [{"d": scene_d, "E": 10.0, "nu": 0.3, "R": 0.5, "L": 50, "farfield": "boussinesq", "method": method,
             "order": 2, "n": 16, "model": "axi", "wall_time": t, "max_err": e} for t, e in zip(times, errors)]


def test_the_front_holds_only_the_scene_most_cases_share():
    seed = _rows(0.02, [0.2, 0.3, 0.5], [1e-2, 5e-3, 1e-3])
    deeper = _rows(0.05, [0.1, 0.15], [1e-4, 1e-5])  # faster and more accurate, but another problem
    rows = pd.DataFrame(seed + deeper)
    front = chart.pareto(chart.common_scene(rows), "wall_time", "max_err")
    assert set(front["d"]) == {0.02} and len(front) == 3
    assert chart.describe(front) == "d = 0.02, E = 10, nu = 0.3, R = 0.5, L = 50"


def test_the_legends_sit_below_the_points(tmp_path, monkeypatch):
    tables = load_tables(_committed_tables(tmp_path))
    drawn = []
    monkeypatch.setattr(chart, "save", lambda fig, path: drawn.append(fig) or path)
    chart.accuracy_vs_speed(tables, tmp_path / "chart.png")
    fig = drawn[0]
    fig.tight_layout()
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    try:
        for ax in fig.axes:
            legend = ax.get_legend()
            assert legend is not None
            assert legend.get_window_extent(renderer).y1 < ax.get_window_extent(renderer).y0, ax.get_title()
            front = next(line for line in ax.get_lines() if line.get_label().startswith("Pareto front (d = 0.02"))
            assert len(front.get_xdata()) >= 3
        # the left panel's front: every point a case of the seed scene (the deeper, the load-controlled
        # and the differently sized cases solve other problems)
        seed = chart.common_scene(sphere_cases(tables))
        points = set(zip(seed["wall_time"], seed["max_err"] * 100))
        front = next(line for line in fig.axes[0].get_lines() if line.get_label().startswith("Pareto front"))
        assert set(zip(front.get_xdata(), front.get_ydata())) <= points
    finally:
        plt.close(fig)
