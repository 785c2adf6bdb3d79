"""The headline chart: every converged sphere case of every study, error against wall time."""
from __future__ import annotations

import math
from pathlib import Path

import matplotlib.pyplot as plt
import matplotlib.ticker
import pandas as pd

from driver.charts.common import METHOD_STYLE, SHAPE_COLORS, Chart, need, save, shape_label, sphere_cases

CAPTION = ("Max relative error over p0, F and a against the wall time the driver measured, every converged sphere "
           "case of every study (open markers: the sphere solved in 3D); the black line is the Pareto front of the "
           "scene most cases share (no case of it is both faster and more accurate: other scenes, deeper or "
           "softer, are other problems). Right: the same cases by their own error estimate, as a user without a "
           "closed form would see them.")
# the options that make a scene: cases that differ in one of them solve different problems
SCENE = ("d", "P", "E", "nu", "R", "Rx", "Ry", "L", "farfield")


def accuracy_vs_speed(tables: dict, path: Path) -> Path:
    """Left: the error against Hertz; right: the same cases by their own estimate."""
    rows = need(sphere_cases(tables), "no converged sphere case")
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(16, 7.2), sharey=True)
    _accuracy_panel(ax, rows, "max_err", "max |relative error| of p0, F, a against Hertz (stars: Sneddon) [%]",
                    f"Accuracy against speed: {len(rows)} converged sphere cases (open: solved in 3D)")
    # the other indenters against Sneddon, at the same kind of cost (not on the front)
    shapes_rows = tables.get("shapes")
    if shapes_rows is not None and len(shapes_rows) and "shape" in shapes_rows:
        other = shapes_rows[(shapes_rows["status"] == "converged") & (shapes_rows["shape"] != "parabola")].copy()
        other["label"] = other.apply(shape_label, axis=1) if len(other) else []
        for name, g in other.groupby("label"):
            err = g[["err_p0", "err_F", "err_a", "err_K"]].abs().max(axis=1, skipna=True)
            ax.scatter(g["wall_time"], err * 100, marker="*", s=60, color=SHAPE_COLORS.get(name, "grey"),
                       label=f"{name} against Sneddon ({len(g)})")
        _legend(ax)
    estimated = rows.assign(max_est=rows["accuracy_predicted"])
    _accuracy_panel(ax2, estimated[estimated["max_est"] > 0], "max_est",
                    "estimated max relative error (no Hertz) [%]", "The same cases by their own error estimate")
    ax2.yaxis.set_tick_params(labelleft=True)
    return save(fig, path)


def _accuracy_panel(ax, rows: pd.DataFrame, column: str, ylabel: str, title: str) -> None:
    rows = rows.assign(max_err=rows[column])
    for (model, method, order), group in rows.groupby(["model", "method", "order"]):
        color, marker = METHOD_STYLE.get((method, int(order)), ("k", "x"))
        solid = model == "axi"  # 3D spheres: open markers
        ax.scatter(group["wall_time"], group["max_err"] * 100, marker=marker, s=26 if solid else 44,
                   alpha=0.75, color=color if solid else "none", edgecolors=color,
                   label=f"{method} P{int(order)}{'' if solid else ', 3d'} ({len(group)})")
    front = pareto(common_scene(rows), "wall_time", "max_err")
    ax.plot(front["wall_time"], front["max_err"] * 100, "k-", lw=1, label=f"Pareto front ({describe(front)})")
    last = None
    for _, row in front.iterrows():
        point = (row["wall_time"], row["max_err"] * 100)
        # label points that stand apart (a label is ~0.8 wide in ln x at this size)
        if last is not None and abs(math.log(point[0] / last[0])) < 0.9 \
                and abs(math.log(point[1] / last[1])) < 0.6:
            continue
        ax.annotate(f"{row['method']} P{int(row['order'])} n={int(row['n'])}"
                    + ("" if row["model"] == "axi" else " 3d"), point,
                    fontsize=7, xytext=(5, 2), textcoords="offset points")
        last = point
    ax.set(xscale="log", yscale="log", xlabel="wall time per case [s] (whole FreeFEM process)",
           ylabel=ylabel, title=title)
    for level in (1, 0.1):
        ax.axhline(level, color="grey", ls=":", lw=0.8)
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())  # labelled minor ticks ran into each other
    ax.grid(True, which="major", alpha=0.3)
    _legend(ax)


def _legend(ax) -> None:
    # below the axes: inside, it covered the slow cases (3D, P1) in the upper right
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=3)


def common_scene(rows: pd.DataFrame) -> pd.DataFrame:
    """The rows of the scene most rows share (SCENE's options; a missing one counts as a value)."""
    key = [c for c in SCENE if c in rows]
    if not key or not len(rows):
        return rows
    labels = rows[key].apply(lambda row: "|".join(str(value) for value in row), axis=1)
    return rows[labels == labels.value_counts().index[0]]


def describe(rows: pd.DataFrame) -> str:
    """The scene of rows that share one, as the legend says it."""
    first = rows.iloc[0]
    shown = [f"{c} = {first[c]:g}" for c in ("d", "P", "E", "nu", "R", "L")
             if c in rows and pd.api.types.is_number(first[c]) and first[c] == first[c]]
    return ", ".join(shown)


def pareto(frame: pd.DataFrame, x: str, y: str) -> pd.DataFrame:
    """Rows no other row beats in both x and y (smaller is better)."""
    ordered = frame.sort_values([x, y])
    front, best = [], math.inf
    for idx, row in ordered.iterrows():
        if row[y] < best:
            front.append(idx)
            best = row[y]
    return ordered.loc[front]


CHARTS = {"accuracy_vs_speed": Chart(accuracy_vs_speed, CAPTION)}
