"""The loading study's chart: loading curves, contact stiffness and the cylinder by its load."""
from __future__ import annotations

import math
from pathlib import Path

import matplotlib.pyplot as plt
import matplotlib.ticker
import pandas as pd

from driver.charts.common import Chart, need, save

CAPTION = ("Top left: loading curves by -d (markers) against Hertz (lines), and two of the sphere's points "
           "again by their load (-P, crosses): an elastic frictionless contact unloads along its loading "
           "curve. Top right: the contact stiffness from the converged linearization against 2E*a. Bottom "
           "left: the cylinder, by its load per unit length: a and p0 against Hertz's relations (its depth "
           "depends on the domain). Bottom right: each point's relative error against its reference, for "
           "what the run computes (F and S under -d; the depth, a and p0 under -P). Each point is its own "
           "run, started from its own coarse level. Units are the scene's: lengths as R, stresses as E.")
# the series' colours: Okabe and Ito's, apart under every colour-vision deficiency
STYLES = {"sphere": ("#0072B2", "o"), "exact sphere": ("#D55E00", "s"), "ellipsoid Ry/Rx = 2": ("#009E73", "D")}
CYLINDER_A, CYLINDER_P0 = "#CC79A7", "#E69F00"
# the errors each series is drawn with: a column a run computes (not the one it was given)
ERROR_PANEL = {"sphere": (("err_F", "F"), ("err_S", "S")), "exact sphere": (("err_F", "F"), ("err_S", "S")),
               "ellipsoid Ry/Rx = 2": (("err_F", "F"), ("err_S", "S")),
               "sphere under load": (("err_d", "d"), ("err_S", "S")),
               "cylinder": (("err_a", "a"), ("err_p0", "p0"))}


def loading(frame: pd.DataFrame, path: Path) -> Path:
    """Loading curves: F(d) with Hertz's lines, S(a) with S = 2E*a, the cylinder's a(P)."""
    df = need(frame[frame["status"] == "converged"], "no loading rows")
    fig, grid = plt.subplots(2, 2, figsize=(14, 10.4))
    axes = grid.ravel()
    for variant, (color, marker) in STYLES.items():
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
    axes[0].set(xscale="log", yscale="log", xlabel="depth d [length]", ylabel="force F [E x length^2]",
                title="F(d): slope 3/2")
    axes[1].plot([], [], "-", color="grey", lw=1, label="lines: 2 E* a (ellipsoid: 3F/2d), each series' colour")
    axes[1].set(xscale="log", yscale="log", xlabel="contact radius a [length] (ellipsoid: along x)",
                ylabel="contact stiffness S = dF/dd [E x length]", title="Contact stiffness")
    cyl = df[df["variant"] == "cylinder"].sort_values("F_fe")
    if len(cyl):
        axes[2].plot(cyl["F_fe"], cyl["a_fe"], "o", color=CYLINDER_A, label="cylinder half-width a (FE)")
        axes[2].plot(cyl["F_fe"], cyl["a_hertz"], "-", color=CYLINDER_A, lw=1, label="sqrt(4PR/(pi E*))")
        axes[2].plot(cyl["F_fe"], cyl["p0_fe"], "s", color=CYLINDER_P0, label="cylinder p0 (FE)")
        axes[2].plot(cyl["F_fe"], cyl["p0_hertz"], "-", color=CYLINDER_P0, lw=1, label="2P/(pi a)")
    axes[2].set(xscale="log", yscale="log", xlabel="load per unit length P [E x length]",
                ylabel="half-width a [length], peak pressure p0 [E]", title="The cylinder, by its load (-P)")
    errors(df, axes[3])
    for ax in axes:
        for axis in (ax.xaxis, ax.yaxis):
            low, high = axis.get_view_interval()
            # a log axis with fewer than two powers of ten in view has one labelled tick at most:
            # its minor ticks are labelled then
            if axis.get_scale() == "log" and math.floor(math.log10(high)) - math.ceil(math.log10(low)) >= 1:
                axis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    return save(fig, path)


def errors(df: pd.DataFrame, ax) -> None:
    """Each point's |relative error| against its reference, for what its run computes."""
    colours = {name: style[0] for name, style in STYLES.items()} | {"sphere under load": "#000000",
                                                                   "cylinder": CYLINDER_A}
    for variant, columns in ERROR_PANEL.items():
        g = df[df["variant"] == variant].sort_values("d_fe")
        for (column, name), ls in zip(columns, ("-", "--")):
            if len(g) and column in g and g[column].notna().any():
                ax.plot(g["d_fe"], g[column].abs() * 100, ls, marker=STYLES.get(variant, ("", "x"))[1],
                        color=colours[variant], ms=5, label=f"{variant}: {name}")
    ax.set(xscale="log", yscale="log", xlabel="depth d [length]", ylabel="|relative error| [%]",
           title="Errors against Hertz (the exact sphere: Sneddon)")


CHARTS = {"loading": Chart(loading, CAPTION)}
