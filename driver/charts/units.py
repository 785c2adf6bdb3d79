"""The units study's chart: one scene in three unit systems."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from driver.charts.common import ERRORS, Chart, need, save
from driver.schema import max_error

CAPTION = ("The same dimensionless scenes given in three unit systems: the errors agree to rounding "
           "(the spread under each scene is the largest difference of any relative error).")


def units_check(frame: pd.DataFrame, path: Path) -> Path:
    df = need(frame, "no units rows").copy()
    df["scene"] = df["variant"].str.rsplit(", ", n=1).str[0]
    df["units"] = df["variant"].str.rsplit(", ", n=1).str[1]
    scenes = list(dict.fromkeys(df["scene"]))
    units = list(dict.fromkeys(df["units"]))
    fig, ax = plt.subplots(figsize=(max(8, 1.6 * len(scenes)), 5))
    width = 0.8 / len(units)
    for k, unit in enumerate(units):
        part = df[df["units"] == unit].set_index("scene").reindex(scenes)
        ax.bar(np.arange(len(scenes)) + k * width, max_error(part) * 100, width,
               label=f"{unit} (E = {part['E'].iloc[0]:g} ...)")
    spread = df.groupby("scene")[list(ERRORS)].agg(lambda s: s.max() - s.min()).abs().max(axis=1)
    ax.set_xticks(np.arange(len(scenes)) + 0.4 - width / 2,
                  [f"{s}\nspread {spread[s]:.1e}" for s in scenes], fontsize=7)
    ax.set(ylabel="max |relative error| of p0, F, a [%]",
           title="One dimensionless scene in three unit systems (spread: largest difference of any error)")
    ax.grid(True, axis="y", alpha=0.3)
    ax.legend(fontsize=7)
    return save(fig, path)


CHARTS = {"units": Chart(units_check, CAPTION)}
