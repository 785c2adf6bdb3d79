"""The chart of a study of the user's own (hertz sweep --spec, sweep(name, cases=...)): whatever
its grid, the errors against the mesh, the time against the mesh, and the solver's estimate
against the true error. Its name is the study's, so it is drawn by report.py, not listed here."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.ticker import NullFormatter

from driver.charts.common import Chart, need, save
from driver.schema import ANSWERED, max_error

CAPTION = ("A study of your own. Left: the largest |relative error| of p0, F and a against the mesh "
           "parameter n (where the scene has a reference). Middle: the wall time of each case. Right: the "
           "solver's own error estimate against that error (the dashed line is equality; above it the "
           "estimate is safe). One series for each value of the options that vary besides n.")
# options whose values name a series when they vary (n is the x axis; kpen, Rx and Ry are not here
# because a row holds the values the run derived from n and R); the report reads no option table
SERIES_OPTIONS = ("model", "shape", "method", "order", "formulation", "farfield", "start", "E", "nu", "R",
                  "d", "P", "L", "gamma", "t", "E2", "nu2", "angle", "k", "accuracy")


def series_of(rows: pd.DataFrame) -> pd.Series:
    """Each row's series: the values of the options that vary among the rows, but n."""
    varying = [c for c in SERIES_OPTIONS if c in rows and rows[c].nunique(dropna=True) > 1]
    if not varying:
        return pd.Series("all cases", index=rows.index)
    return rows[varying].astype(str).apply(lambda r: ", ".join(f"{c} {v}" for c, v in r.items()), axis=1)


def _positive(values: pd.Series) -> bool:
    return bool((values.to_numpy(dtype=float) > 0).any())


def own_study(frame: pd.DataFrame, path: Path) -> Path:
    rows = need(frame[frame["status"].isin(ANSWERED)], "no converged or inaccurate rows").copy()
    rows["max_err"] = max_error(rows)
    rows["series"] = series_of(rows)
    # scenes without a reference (a coated body, adhesion) have no true error: the left panel
    # shows the estimate instead, and the right one says why it is empty
    truth = _positive(rows["max_err"])
    left = "max_err" if truth else "accuracy_predicted"
    fig, (err_ax, time_ax, est_ax) = plt.subplots(1, 3, figsize=(15, 4.6))
    for k, (name, part) in enumerate(sorted(rows.groupby("series"), key=lambda item: str(item[0]))):
        part = part.sort_values("n")
        style = dict(marker="os^Dvp<>"[k % 8], ls="-", label=str(name))
        err_ax.plot(part["n"], part[left] * 100, **style)
        time_ax.plot(part["n"], part["wall_time"], **style)
        if truth:
            est_ax.plot(part["max_err"] * 100, part["accuracy_predicted"] * 100, ls="", marker=style["marker"],
                        label=str(name))
    err_ax.set(yscale="log" if _positive(rows[left]) else "linear", xlabel="mesh parameter n",
               ylabel="max |relative error| of p0, F, a [%]" if truth else "the solver's error estimate [%]",
               title="Error against the mesh" if truth else "Estimate against the mesh (no reference here)")
    time_ax.set(xlabel="mesh parameter n", ylabel="wall time [s]", title="Time of a case")
    known = rows[["max_err", "accuracy_predicted"]].to_numpy(dtype=float) * 100
    known = known[np.isfinite(known).all(axis=1) & (known > 0).all(axis=1)]
    if len(known):
        span = [known.min() / 2, known.max() * 2]
        est_ax.plot(span, span, "k--", lw=0.8)
        est_ax.set(xscale="log", yscale="log")
        for axis in (est_ax.xaxis, est_ax.yaxis):
            axis.set_minor_formatter(NullFormatter())  # labels on every minor tick of a short log axis overlap
    else:
        est_ax.text(0.5, 0.5, "no reference for these scenes:\nno true error to compare with",
                    ha="center", va="center", transform=est_ax.transAxes)
    est_ax.set(xlabel="true max |error| [%]", ylabel="estimated error [%]",
               title="The solver's estimate against the error")
    for ax in (err_ax, time_ax, est_ax):
        ax.grid(True, alpha=0.3)
    err_ax.legend(fontsize=7)
    fig.suptitle(f"study {frame['study'].iloc[0]}: {len(rows)} answered of {len(frame)} cases")
    return save(fig, path)


CHARTS: dict[str, Chart] = {}
