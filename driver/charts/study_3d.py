"""The 3d study's charts: the price of over-modelling a sphere, and the ellipsoids' outlines and
pressures (from the outline.csv, profile.csv and profile_y.csv files the sweep kept)."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import matplotlib.ticker
import pandas as pd

from driver.charts.common import METHOD_STYLE, Chart, need, save
from driver.schema import max_error

OVER_MODELLING_CAPTION = ("The same sphere solved axisymmetric (solid) and in 3D (dashed, a quarter of the "
                          "half-space, the 2D section revolved) over meshes: error against wall time, peak memory and "
                          "dofs. The title compares, at the most accurate converged 3D case, the cheapest axi case "
                          "that is at least as accurate (same method).")


def matched_accuracy(frame: pd.DataFrame) -> pd.DataFrame:
    """For each converged 3D sphere case, the cheapest converged axisymmetric case
    of the same method at least as accurate (against Hertz): the price of
    over-modelling as ratios of wall time, memory and dofs."""
    rows = frame[frame["status"] == "converged"].assign(max_err=max_error(frame))
    axi = rows[rows["model"] == "axi"]
    full = rows[(rows["model"] == "3d") & (rows["Rx"] == rows["Ry"])]
    pairs = []
    for _, row in full.iterrows():
        match = axi[(axi["method"] == row["method"]) & (axi["max_err"] <= row["max_err"])]
        if len(match):
            best = match.loc[match["wall_time"].idxmin()]
            pairs.append({"method": row["method"], "n_3d": row["n"], "n_axi": best["n"],
                          "err_3d": row["max_err"], "err_axi": best["max_err"],
                          "time_3d": row["wall_time"], "time_axi": best["wall_time"],
                          "memory_3d": row["memory_mb"], "memory_axi": best["memory_mb"],
                          "ndof_3d": row["ndof"], "ndof_axi": best["ndof"]})
    return pd.DataFrame(pairs)


def over_modelling(frame: pd.DataFrame, path: Path) -> Path:
    rows = frame[frame["status"].isin(["converged", "inaccurate"])].assign(max_err=max_error(frame))
    spheres = need(rows[rows["Rx"] == rows["Ry"]], "no converged or inaccurate sphere rows in 3d")
    fig, axes = plt.subplots(1, 3, figsize=(16, 5))
    columns = (("wall_time", "wall time per case [s]"), ("memory_mb", "peak memory [MB]"),
               ("ndof", "degrees of freedom"))
    for ax, (col, label) in zip(axes, columns):
        for (model, method, order), g in spheres.groupby(["model", "method", "order"]):
            g = g.sort_values("n")
            color, marker = METHOD_STYLE.get((method, int(order)), ("k", "x"))
            ax.plot(g[col], g["max_err"] * 100, "-" if model == "axi" else "--", color=color, marker=marker,
                    mfc=color if model == "axi" else "none", label=f"{model} {method} P{int(order)}")
            for _, r in g.iterrows():
                ax.annotate(f"n={r['n']:.0f}", (r[col], r["max_err"] * 100), fontsize=6,
                            xytext=(3, 3), textcoords="offset points")
        ax.axhline(1, color="grey", ls=":", lw=0.8)
        ax.set(xscale="log", yscale="log", xlabel=label)
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())  # decades only: no crowding
        ax.grid(True, alpha=0.3)
    axes[0].set_ylabel("max |relative error| of p0, F, a (and b in 3D) against Hertz [%]")
    axes[0].legend(fontsize=7)
    pairs = matched_accuracy(frame)
    if len(pairs):
        p = pairs.sort_values("err_3d").iloc[0]
        fig.suptitle(f"The price of over-modelling a sphere: at {p['err_3d']:.2%} ({p['method']}), 3D n = "
                     f"{p['n_3d']:.0f} costs {p['time_3d'] / p['time_axi']:.0f}x the time, "
                     f"{p['memory_3d'] / p['memory_axi']:.0f}x the memory and "
                     f"{p['ndof_3d'] / p['ndof_axi']:.0f}x the dofs of axi n = {p['n_axi']:.0f}")
    else:
        fig.suptitle("The price of over-modelling a sphere: axi (solid) against 3d (dashed)")
    return save(fig, path)


def ellipses(frame: pd.DataFrame, outline: pd.DataFrame, profile: pd.DataFrame, profile_y: pd.DataFrame,
             path: Path) -> Path:
    """Contact outlines against Hertz's ellipses, and the pressure along both axes."""
    rows = frame[(frame["model"] == "3d") & (frame["method"] == "newton") & (frame["order"] == 2)
                 & frame["status"].isin(["converged", "inaccurate"])]
    need(rows, "no converged or inaccurate 3d newton P2 rows")
    need(outline, "no kept outline.csv of 3d")
    finest = rows.loc[rows.groupby(["Rx", "Ry"])["n"].idxmax()].sort_values(["Ry", "Rx"])
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(13.5, 5.6))
    colors = ("#1565c0", "#c62828", "#2e7d32", "#6a1b9a", "#ef6c00")
    for (_, case), color in zip(finest.iterrows(), colors):
        line = outline[outline["case_id"] == case["case_id"]]
        name = f"Rx = {case['Rx']:g}, Ry = {case['Ry']:g}, n = {case['n']:.0f}"
        ax.plot(line["x"], line["y"], "o", color=color, ms=3.5, label=f"FE edge, {name}")
        ax.plot(line["x_hertz"], line["y_hertz"], "-", color=color, lw=1)
    ax.plot([], [], "k-", lw=1, label="Hertz ellipse")
    ax.set(xlabel="x [length]", ylabel="y [length]", aspect="equal",
           title="Contact outline (a quarter; d = {:g})".format(finest["d"].iloc[0]) if len(finest) else "")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    longest = finest.loc[(finest["Ry"] / finest["Rx"]).idxmax()] if len(finest) else None
    if longest is not None:
        for data, edge, label, ls in ((profile, longest["a_hertz"], "x", "-"),
                                      (profile_y, longest["b_hertz"], "y", "--")):
            prof = data[data["case_id"] == longest["case_id"]]
            ax2.plot(prof["r"] / edge, prof["p_fe"] / longest["p0_hertz"], ls, color="#1565c0",
                     label=f"FE along {label} (semi-axis {edge:.4g})")
            ax2.plot(prof["r"] / edge, prof["p_hertz"] / longest["p0_hertz"], ls, color="k", lw=0.9,
                     label=f"Hertz along {label}")
        ax2.set(xlabel="distance / Hertz semi-axis of that direction", ylabel="p / p0 (Hertz)", xlim=(0, 1.6),
                title=f"Pressure along both axes: Rx = {longest['Rx']:g}, Ry = {longest['Ry']:g}, "
                      f"n = {longest['n']:.0f}, p0 error {longest['err_p0']:+.2%}")
        ax2.grid(True, alpha=0.3)
        ax2.legend(fontsize=7)
    fig.suptitle("Ellipsoids in 3D against elliptical Hertz")
    return save(fig, path)

ELLIPSES_CAPTION = ("Left: the contact outline (gap threshold along rays) for each ellipsoid at its finest mesh, "
                    "against Hertz's ellipse. Right: the pressure along both axes of the most elongated one "
                    "against p0 sqrt(1 - (s/semi-axis)^2).")


CHARTS = {
    "over_modelling": Chart(over_modelling, OVER_MODELLING_CAPTION),
    "ellipses": Chart(ellipses, ELLIPSES_CAPTION, kept=("outline.csv", "profile.csv", "profile_y.csv")),
}
