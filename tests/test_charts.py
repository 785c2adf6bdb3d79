"""driver/charts/: charts a colour-blind reader can read."""
import itertools

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import pytest
from matplotlib.colors import to_rgb

from driver.charts import CHARTS, common, effectivity, stability
from driver.studies import STUDIES, report_charts

# Machado, Oliveira and Fernandes (2009), full severity, on linear RGB
VISION = {
    "normal": np.eye(3),
    "protanopia": np.array([[0.152286, 1.052583, -0.204868], [0.114503, 0.786281, 0.099216],
                            [-0.003882, -0.048116, 1.051998]]),
    "deuteranopia": np.array([[0.367322, 0.860646, -0.227968], [0.280085, 0.672501, 0.047413],
                              [-0.011820, 0.042940, 0.968881]]),
    "tritanopia": np.array([[1.255528, -0.076749, -0.178779], [-0.078411, 0.930809, 0.147602],
                            [0.004733, 0.691367, 0.303900]]),
}


def _lab(color: str, vision: str) -> np.ndarray:
    """CIELAB of a colour as a reader with this vision sees it."""
    srgb = np.asarray(to_rgb(color))
    linear = np.where(srgb <= 0.04045, srgb / 12.92, ((srgb + 0.055) / 1.055) ** 2.4)
    seen = np.clip(VISION[vision] @ linear, 0, 1)
    xyz = np.array([[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]]) @ seen
    t = xyz / np.array([0.95047, 1.0, 1.08883])
    f = np.where(t > 0.008856, np.cbrt(t), 7.787 * t + 16 / 116)
    return np.array([116 * f[1] - 16, 500 * (f[0] - f[1]), 200 * (f[1] - f[2])])


@pytest.mark.parametrize("vision", list(VISION))
def test_converged_and_inaccurate_are_far_apart_for_every_reader(vision):
    # olive against green (delta E 32 for protanopes); a clear difference is above 50
    colors = common.STATUS_COLORS
    distance = np.linalg.norm(_lab(colors["converged"], vision) - _lab(colors["inaccurate"], vision))
    assert distance > 50, distance


def test_statuses_that_colour_alone_cannot_separate_differ_by_hatch():
    hatches = common.STATUS_HATCHES
    assert set(hatches) == set(common.STATUS_COLORS) and len(set(hatches.values())) == len(hatches)
    for a, b in itertools.combinations(common.STATUS_COLORS, 2):
        close = min(np.linalg.norm(_lab(common.STATUS_COLORS[a], v) - _lab(common.STATUS_COLORS[b], v)) for v in VISION)
        assert close > 20 or hatches[a] != hatches[b], (a, b)


def test_the_stability_cells_carry_their_status_hatch():
    frame = pd.DataFrame({"x": [1, 2, 3], "y": ["a", "a", "a"], "status": ["converged", "inaccurate", "diverged"]})
    fig, ax = plt.subplots()
    stability._grid(ax, frame, "x", "y", lambda row: "")
    hatches = [patch.get_hatch() or "" for patch in ax.patches]
    plt.close(fig)
    assert hatches == [common.STATUS_HATCHES[s] for s in frame["status"]]


def test_effectivity_keeps_every_distinct_answered_result_with_a_reference_and_its_ratio(tmp_path):
    # the estimate over the largest |error| of the quantities that have both an
    # estimate and a reference (b in 3D, K for a punch); a diverged run, a run
    # without an estimate and a scene without a reference are not cases, and a
    # study's copy of another's result counts once
    nan = np.nan
    columns = {"status": ["converged", "inaccurate", "diverged", "converged", "converged", "converged"],
               "model": ["axi", "3d", "axi", "plane", "axi", "axi"], "n": [16, 8, 16, 16, 16, 16],
               "err_p0": [0.001, -0.002, 0.3, 0.004, nan, nan], "err_F": [-0.004, 0.001, 0.1, 0.0, nan, 0.001],
               "err_a": [0.002, 0.0005, 0.2, 0.001, nan, 0.0], "err_b": [nan, -0.006, nan, nan, nan, nan],
               "err_K": [0.05, nan, nan, nan, nan, -0.003],
               "est_err_p0": [0.008, 0.003, 0.01, nan, 0.01, nan],
               "est_err_F": [0.001, 0.001, 0.01, nan, 0.01, 0.001],
               "est_err_a": [0.001, 0.001, 0.01, nan, 0.01, 0.001],
               "est_err_b": [nan, 0.003, nan, nan, nan, nan], "est_err_K": [nan, nan, nan, nan, nan, 0.006],
               "accuracy_predicted": [0.008, 0.003, 0.01, nan, 0.01, 0.006]}
    rows = pd.DataFrame(columns)
    kept = effectivity.effectivity_rows({"one": rows, "copy": rows.iloc[:1]})
    assert list(kept["study"]) == ["one", "one", "one"]
    # 0.008/0.004 (K has no estimate there), 0.003/0.006 (b), 0.006/0.003 (a punch's K)
    assert kept["effectivity"].tolist() == pytest.approx([2.0, 0.5, 2.0])
    png = effectivity.effectivity({"one": rows}, tmp_path / "effectivity.png")
    assert png.stat().st_size > 10_000


def test_every_chart_a_study_names_is_drawn_by_one_module_and_every_drawn_chart_is_named():
    # a chart is registered beside its study: studies.py names it, a module of driver/charts/ draws it
    named = report_charts()
    assert len(named) == len(set(named)), named
    assert set(named) == set(CHARTS), set(named) ^ set(CHARTS)
    assert all(chart.caption.strip() for chart in CHARTS.values())
    for study in STUDIES.values():  # a chart reads only the files its study keeps
        for name in study.charts:
            assert set(CHARTS[name].kept) <= set(study.keep), (study.name, name)
