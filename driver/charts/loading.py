"""The loading study's chart: loading curves, contact stiffness and the cylinder by its load."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import matplotlib.ticker
import pandas as pd

from driver.charts.common import Chart, need, save

CAPTION = ("Loading curves by -d (markers) against Hertz (lines), and two of the sphere's points again "
           "by their load (-P, crosses): an elastic frictionless contact unloads along its loading curve. "
           "Middle: the contact stiffness from the converged linearization against 2E*a. Right: the "
           "cylinder, by its load per unit length: a and p0 against Hertz's relations (its depth depends on "
           "the domain). Each point is its own run, started from its own coarse level.")


def loading(frame: pd.DataFrame, path: Path) -> Path:
    """Loading curves: F(d) with Hertz's lines, S(a) with S = 2E*a, the cylinder's a(P)."""
    df = need(frame[frame["status"] == "converged"], "no loading rows")
    fig, axes = plt.subplots(1, 3, figsize=(16, 5.2))
    styles = {"sphere": ("#1565c0", "o"), "exact sphere": ("#6a1b9a", "s"), "ellipsoid Ry/Rx = 2": ("#2e7d32", "D")}
    for variant, (color, marker) in styles.items():
        g = df[df["variant"] == variant].sort_values("d_fe")
        if not len(g):
            continue
        hollow = dict(mfc="none", ms=10, mew=1.5) if variant == "sphere" else {}
        axes[0].plot(g["d_fe"], g["F_fe"], marker, color=color, label=f"{variant}, loading (-d)", **hollow)
        axes[0].plot(g["d_fe"], g["F_hertz"], "-", color=color, lw=1)
        axes[1].plot(g["a_fe"], g["S_fe"], marker, color=color, label=f"{variant}: dF/dd from the linearization",
                     **hollow)
        axes[1].plot(g["a_fe"], g["S_hertz"], "-", color=color, lw=1)
    under = df[df["variant"] == "sphere under load"]
    axes[0].plot(under["d_fe"], under["F_fe"], "x", color="k", ms=10, mew=2,
                 label="sphere under load (-P): the same curve")
    axes[0].plot([], [], "-", color="grey", lw=1, label="lines: Hertz (the exact sphere: Sneddon), each series' colour")
    axes[0].set(xscale="log", yscale="log", xlabel="depth d", ylabel="force F", title="F(d): slope 3/2")
    axes[1].plot([], [], "-", color="grey", lw=1, label="lines: 2 E* a (ellipsoid: 3F/2d), each series' colour")
    axes[1].set(xscale="log", yscale="log", xlabel="contact radius a (ellipsoid: along x)",
                ylabel="contact stiffness S = dF/dd", title="Contact stiffness")
    cyl = df[df["variant"] == "cylinder"].sort_values("F_fe")
    if len(cyl):
        axes[2].plot(cyl["F_fe"], cyl["a_fe"], "o", color="#c62828", label="cylinder half-width a (FE)")
        axes[2].plot(cyl["F_fe"], cyl["a_hertz"], "-", color="#c62828", lw=1, label="sqrt(4PR/(pi E*))")
        axes[2].plot(cyl["F_fe"], cyl["p0_fe"], "s", color="#ef6c00", label="cylinder p0 (FE)")
        axes[2].plot(cyl["F_fe"], cyl["p0_hertz"], "-", color="#ef6c00", lw=1, label="2P/(pi a)")
    axes[2].set(xscale="log", yscale="log", xlabel="load per unit length P",
                ylabel="half-width a (length), p0 (stress), the scene's units",
                title="The cylinder, by its load (-P)")
    for ax in axes:
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    return save(fig, path)


CHARTS = {"loading": Chart(loading, CAPTION)}
