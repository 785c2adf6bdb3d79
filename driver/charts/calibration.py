"""The calibration study's chart: the run's own estimate against the truth, and -accuracy."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import matplotlib.ticker
import numpy as np
import pandas as pd

from driver.charts.common import BAND, EFFECTIVITY_BAND, STATUS_COLORS, Chart, need, save, scene
from driver.schema import max_error

CAPTION = ("Left and middle: the run's own error estimate (no Hertz) against the true max error "
           "of p0, F and a on scenes with closed forms (nu from -0.5 to 0.499, d/R from 1e-6 to 0.1, "
           "SI units, plane strain, P1, lagrange, and -accuracy runs); the band is estimate/truth "
           f"from {BAND}. Right: -accuracy X, the true error reached (dots) and the estimate "
           "(crosses) against X; points on or below the line meet the target.")


def calibration(frame: pd.DataFrame, path: Path) -> Path:
    """The estimate against the truth (closed forms), its effectivity, and
    -accuracy's achieved error against its target."""
    df = need(frame[frame["status"].isin(["converged", "inaccurate"])],
              "no converged or inaccurate calibration rows").copy()
    df["true"] = max_error(df)
    df["est"] = df["accuracy_predicted"]
    df["group"] = df["variant"].where(~df["variant"].str.startswith("accuracy"), "-accuracy")
    fig, axes = plt.subplots(1, 3, figsize=(18, 5.6))
    colors = dict(zip(sorted(df["group"].unique()), [plt.get_cmap("tab10")(k) for k in range(10)]))
    for group, g in df.groupby("group"):
        axes[0].scatter(g["true"] * 100, g["est"] * 100, s=22, color=colors[group], label=group)
        axes[1].scatter(g["true"] * 100, g["est"] / g["true"], s=22, color=colors[group], label=group)
    lim = np.array([1e-4, 30.0])
    axes[0].plot(lim, lim, "k-", lw=1, label="estimate = truth")
    low, high = EFFECTIVITY_BAND
    axes[0].fill_between(lim, lim * low, lim * high, color="grey", alpha=0.15, label=f"truth x {low:g} to {high:g}")
    axes[0].set(xscale="log", yscale="log", xlabel="true max |error| of p0, F, a (and b) [%]",
                ylabel="estimated max error (no Hertz) [%]", title="Estimate against truth")
    axes[1].axhspan(low, high, color="grey", alpha=0.15, label=f"target band {low:g} to {high:g}")
    axes[1].axhline(1, color="k", lw=1)
    axes[1].set(xscale="log", yscale="log", xlabel="true max |error| [%]",
                ylabel="effectivity = estimate / truth", title="Effectivity")
    axes[1].yaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
    axes[1].yaxis.set_minor_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
    acc = df[df["group"] == "-accuracy"]
    for status, g in acc.groupby("status"):
        axes[2].scatter(g["accuracy_target"] * 100, g["true"] * 100, s=28,
                        color=STATUS_COLORS.get(status, "k"), label=f"achieved ({status})", zorder=3)
        axes[2].scatter(g["accuracy_target"] * 100, g["est"] * 100, s=28, marker="x",
                        color=STATUS_COLORS.get(status, "k"), label=f"estimated ({status})", zorder=3)
    targets = np.array([0.8, 1.25]) * [acc["accuracy_target"].min() * 100, acc["accuracy_target"].max() * 100] \
        if len(acc) else np.array([0.08, 6.0])
    axes[2].plot(targets, targets, "k-", lw=1, label="error = target")
    axes[2].set(xscale="log", yscale="log", xlabel="-accuracy target X [%]", ylabel="max error [%]",
                title="-accuracy X: achieved (truth) and estimated error")
    for ax in axes:
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle(f"Error estimate calibration: {len(df)} cases with closed forms ({scene(df) or 'many scenes'})")
    return save(fig, path)


CHARTS = {"calibration": Chart(calibration, CAPTION)}
