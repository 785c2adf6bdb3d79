"""The stability study's chart: cells coloured (and hatched) by status, with iteration counts."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from driver.charts.common import CELL_EDGE, STATUS_COLORS, STATUS_HATCHES, Chart, need, save

CAPTION = ("Left: fixed point, kpen x omega, cells coloured by status with the iteration count; "
           "dashed: the predicted limit kpen = (2/omega - 1)/mu. Middle: Newton from each start "
           "(the previous level's contact zone, zero, the Hertz zone), with and without line search "
           "and continuation, over the penalty in units of E*/h. Right: lagrange and Uzawa over "
           "the augmentation parameter.")


def _grid(ax, frame: pd.DataFrame, xcol: str, ycol: str, text) -> None:
    xs = sorted(frame[xcol].unique())
    ys = list(dict.fromkeys(frame.sort_values(ycol)[ycol]))
    for _, row in frame.iterrows():
        i, j = xs.index(row[xcol]), ys.index(row[ycol])
        ax.add_patch(plt.Rectangle((i - 0.5, j - 0.5), 1, 1, facecolor=STATUS_COLORS.get(row["status"], "white"),
                                   hatch=STATUS_HATCHES.get(row["status"], ""), edgecolor=CELL_EDGE, lw=0.3))
        ax.text(i, j, text(row), ha="center", va="center", fontsize=6.5,
                bbox={"boxstyle": "round,pad=0.15", "facecolor": (1, 1, 1, 0.75), "edgecolor": "none"})
    ax.set_xticks(range(len(xs)), [_tick(x) for x in xs], rotation=45, fontsize=7)
    ax.set_yticks(range(len(ys)), [str(y) for y in ys], fontsize=7)
    ax.set_xlim(-0.5, len(xs) - 0.5)
    ax.set_ylim(-0.5, len(ys) - 0.5)


def _tick(value) -> str:
    if isinstance(value, (int, float, np.number)):
        return f"{value:.0e}" if value >= 1e4 or value < 1e-1 else f"{value:g}"
    return str(value)


def stability_map(frame: pd.DataFrame, path: Path) -> Path:
    need(frame, "no stability rows")
    fig, axes = plt.subplots(1, 3, figsize=(19, 6.5), gridspec_kw={"width_ratios": [1, 1.15, 0.9]})
    fp = frame[frame["method"] == "fixedpoint"]
    n_map = fp["n"].mode().iloc[0] if len(fp) else 16
    fp = fp[fp["n"] == n_map]
    _grid(axes[0], fp, "kpen", "omega", lambda r: f"{r['iterations']:.0f}")
    if len(fp):
        kcrit = fp.groupby("omega")["kpen_critical"].first()
        kpens = sorted(fp["kpen"].unique())
        omegas = sorted(fp["omega"].unique())
        xs = np.interp(np.log10(kcrit.values), np.log10(kpens), np.arange(len(kpens)))
        axes[0].plot(xs, [omegas.index(w) for w in kcrit.index], "k--", lw=2,
                     label="theory: kpen = (2/omega - 1)/mu")
        axes[0].legend(fontsize=7, loc="upper right")
    axes[0].set(title=f"Fixed point (P2, n = {n_map:.0f}): iterations in cells", xlabel="kpen (absolute)",
                ylabel="relaxation omega")
    newton = frame[(frame["method"] == "newton")]
    _grid(axes[1], newton, "gamma", "variant",
          lambda r: f"{r['iterations'] + r['coarse_iterations']:.0f}")
    axes[1].set(title="Newton from each start: iterations (all levels) in cells",
                xlabel="penalty gamma = kpen h / E*", ylabel="")
    exact = frame[frame["method"].isin(["lagrange", "uzawa"])]
    _grid(axes[2], exact, "gamma", "variant",
          lambda r: f"{r['iterations'] + r['coarse_iterations']:.0f}")
    axes[2].set(title="Exact methods: iterations (all levels)", xlabel="augmentation c = gamma E*/h",
                ylabel="")
    handles = [plt.Rectangle((0, 0), 1, 1, facecolor=STATUS_COLORS[s], hatch=STATUS_HATCHES[s], edgecolor=CELL_EDGE)
               for s in STATUS_COLORS]
    fig.legend(handles, STATUS_COLORS.keys(), loc="lower center", ncol=len(STATUS_COLORS), fontsize=8)
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    return save(fig, path, layout=False)


CHARTS = {"stability": Chart(stability_map, CAPTION)}
