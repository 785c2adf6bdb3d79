"""The mesh study's chart: the errors against the element size, with fitted slopes."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from driver.charts.common import ERRORS, QUANTITY_COLORS, Chart, need, save

CAPTION = ("Errors against element size h/a at the contact for each series; the slopes are fitted "
           "from the coarsest mesh until the curve meets its floor (penalty, domain or rounding), and "
           "the legend names that range.")


def _fit_range(h: np.ndarray, err: np.ndarray) -> slice:
    """The points before the error stops falling (a floor: penalty, domain or
    rounding): from the coarsest while each refinement still cuts the error by
    more than a third of the element-size ratio."""
    end = 1
    while end < len(h) and err[end] > 0 and err[end - 1] / err[end] > (h[end - 1] / h[end]) ** (1 / 3):
        end += 1
    return slice(0, end)


def mesh_study(frame: pd.DataFrame, path: Path) -> Path:
    df = need(frame[frame["status"].isin(["converged", "inaccurate"])], "no converged or inaccurate mesh rows").copy()
    df["series"] = df["variant"].str.replace(r" P\d$", "", regex=True)
    series = sorted(df["series"].unique())
    fig, axes = plt.subplots(1, len(series), figsize=(5.2 * len(series), 4.8), sharey=True, squeeze=False)
    for ax, name in zip(axes[0], series):
        part = df[df["series"] == name]
        for order, ls in ((1, "--"), (2, "-")):
            g = part[part["order"] == order].sort_values("n")
            if not len(g):
                continue
            h = 1.0 / g["n"].to_numpy()
            for (col, qname), color in zip(ERRORS.items(), QUANTITY_COLORS):
                err = g[col].abs().to_numpy()
                fit = _fit_range(h, err)
                n_fit = g["n"].to_numpy()[fit]
                if fit.stop >= 2:
                    rate = np.polyfit(np.log(h[fit]), np.log(err[fit]), 1)[0]
                    label = f"{qname} P{order}: slope {rate:.2f} (n {n_fit[0]:.0f}-{n_fit[-1]:.0f})"
                else:
                    label = f"{qname} P{order}: at its floor"
                ax.plot(h, err * 100, ls, color=color, marker="o", ms=3, label=label)
        ax.set(xscale="log", yscale="log", xlabel="element size h / a at the contact", title=name)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=6.5)
    axes[0][0].set_ylabel("|relative error| against Hertz [%]")
    fig.suptitle("Mesh convergence (sphere): slopes fitted before each curve meets its floor")
    return save(fig, path)


CHARTS = {"mesh": Chart(mesh_study, CAPTION)}
