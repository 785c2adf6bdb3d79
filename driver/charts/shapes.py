"""The shapes study's chart: the exact sphere, F(d), convergence and pressures against Sneddon."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import matplotlib.ticker
import numpy as np
import pandas as pd

from driver.charts.common import QUANTITY_COLORS, SHAPE_COLORS, Chart, need, save, shape_label

CAPTION = ("Top left: the exact spherical cap against Hertz's parabola of the same radius at the same depth: "
           "the FE runs (markers) and Sneddon's exact sphere against Hertz (lines). Top right: F(d) of each "
           "indenter, FE (markers) and Sneddon (lines), with the fitted slopes. Bottom left: each shape's "
           "largest error against Sneddon over n (exact contact); the punch is measured on F and its edge "
           "factor K, the cone on F and a (its pressure is singular at the tip). Bottom right: the pressure "
           "profiles at d = 0.02 against Sneddon's.")


def shapes(frame: pd.DataFrame, profiles: pd.DataFrame, path: Path) -> Path:
    """A 2 x 2 grid: the exact sphere against Hertz's parabola of the same radius over d/R; F
    against d for each shape (markers FE, lines Sneddon); each shape's error against n (exact
    contact); the pressure profiles. Rows are chosen by their columns (a case shared by two
    series is one row)."""
    df = need(frame[frame["status"].isin(["converged", "inaccurate"])], "no shapes rows").copy()
    df["label"] = df.apply(shape_label, axis=1)
    default = df[(df["method"] == "newton") & (df["n"] == 16)]
    sph = need(default[default["label"] == "sphere"], "no sphere rows").set_index("d").sort_index()
    par = need(default[default["label"] == "parabola"], "no parabola rows").set_index("d").sort_index()
    common = sph.index.intersection(par.index)
    ratio = common / sph.loc[common, "R"]
    fig, axes2 = plt.subplots(2, 2, figsize=(13, 10))
    axes = axes2.ravel()
    ax = axes[0]
    for q, color in (("F", QUANTITY_COLORS[1]), ("a", QUANTITY_COLORS[2])):
        ax.plot(ratio, (sph.loc[common, f"{q}_fe"] / par.loc[common, f"{q}_fe"] - 1) * 100, "o", color=color,
                label=f"{q}: FE sphere / FE parabola - 1")
        ax.plot(ratio, (sph.loc[common, f"{q}_hertz"] / par.loc[common, f"{q}_hertz"] - 1) * 100, "-", color=color,
                lw=1, label=f"{q}: Sneddon's sphere / Hertz - 1")
    x = np.linspace(0, ratio.max(), 50)
    ax.plot(x, -x / 10 * 100, "k:", lw=1, label="-(d/R)/10, -(d/R)/6 (first order)")
    ax.plot(x, -x / 6 * 100, "k:", lw=1)
    ax.set(xlabel="depth d / R", ylabel="sphere against parabola [%]",
           title="The exact sphere against Hertz's parabola (same R, same d)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    ax = axes[1]
    for name, g in default[default["label"] != "parabola"].groupby("label"):
        g = g.sort_values("d")
        if len(g) < 3:
            continue
        color = SHAPE_COLORS.get(name, "grey")
        ax.plot(g["d"], g["F_hertz"], "-", color=color, lw=1)
        slope = np.polyfit(np.log(g["d"]), np.log(g["F_fe"]), 1)[0]
        ax.plot(g["d"], g["F_fe"], "o", color=color, label=f"{name}: slope {slope:.3f}")
    ax.plot([], [], "k-", lw=1, label="Sneddon (lines)")
    ax.set(xscale="log", yscale="log", xlabel="depth d", ylabel="force F",
           title="F(d): cone 2, punch 1, power k: 1 + 1/k, sphere 1.5 (small d)")
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    ax = axes[2]
    errors = {"F": "err_F", "a": "err_a", "K": "err_K", "p0": "err_p0"}
    for name, g in df[df["method"] == "lagrange"].groupby("label"):
        g = g.sort_values("n")
        cols = [c for c in errors.values() if g[c].notna().any()]
        ax.plot(g["n"], g[cols].abs().max(axis=1) * 100, "o-", color=SHAPE_COLORS.get(name, "grey"),
                label=f"{name} ({', '.join(k for k, c in errors.items() if c in cols)})")
    ax.set(xscale="log", yscale="log", xlabel="elements per contact radius n",
           ylabel="max |relative error| against Sneddon [%]",
           title="Convergence (lagrange P2; a cone at any angle is one problem)")
    ns = sorted(df.loc[df["method"] == "lagrange", "n"].unique())
    ax.set_xticks(ns, [f"{n:g}" for n in ns])
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.grid(True, which="both", alpha=0.3)
    if ax.get_legend_handles_labels()[0]:  # a study without lagrange rows draws none
        ax.legend(fontsize=7)
    ax = axes[3]
    at = default[(default["d"] == 0.02) & (default["label"] != "parabola")]
    for _, row in at.iterrows():
        prof = profiles[profiles["case_id"] == row["case_id"]] if len(profiles) else profiles
        if not len(prof):
            continue
        a = row["a_fe"]
        scale = row["F_fe"] / (np.pi * a * a)  # the mean pressure
        color = SHAPE_COLORS.get(row["label"], "grey")
        inside = prof[prof["r"] < 0.995 * a]
        ax.plot(prof["r"] / a, prof["p_fe"] / scale, "-", color=color, label=f"{row['label']} (FE)")
        ax.plot(inside["r"] / a, inside["p_hertz"] / scale, "k:", lw=1)
    ax.plot([], [], "k:", lw=1, label="Sneddon")
    ax.set(xlim=(0, 1.3), ylim=(0, 4), xlabel="r / a", ylabel="p / mean pressure F/(pi a^2)",
           title="Pressure at d = 0.02 (cone: log tip; punch: 1/sqrt edge)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    return save(fig, path)


CHARTS = {"shapes": Chart(shapes, CAPTION, kept=("profile.csv",))}
