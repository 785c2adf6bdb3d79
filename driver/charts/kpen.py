"""The kpen study's chart: the penalty error and the iterations against kpen."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import pandas as pd

from driver.charts.common import METHOD_STYLE, Chart, need, save, scene
from driver.schema import max_error

CAPTION = ("Left: max error and penetration / d against the absolute penalty (seed scene). The "
           "penalty error falls as 1/kpen down to the discretization floor; lagrange and Uzawa have "
           "no penalty error. Right: iterations over all levels.")


def penalty_study(frame: pd.DataFrame, path: Path) -> Path:
    df = need(frame[frame["status"].isin(["converged", "inaccurate"])], "no converged or inaccurate kpen rows")
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(13, 5.2))
    for (method, order), g in df.groupby(["method", "order"]):
        if method == "fixedpoint":
            continue
        g = g.sort_values("kpen")
        color, marker = METHOD_STYLE.get((method, int(order)), ("k", "x"))
        ls = "-" if order == 2 else "--"
        ax.plot(g["kpen"], max_error(g) * 100, ls, color=color, marker=marker, ms=4,
                label=f"max |error| {method} P{int(order)}")
        if method == "newton":
            ax.plot(g["kpen"], g["penetration_over_d"] * 100, ":", color=color, marker="x", ms=4,
                    label=f"penetration / d, newton P{int(order)}")
        ax2.plot(g["kpen"], g["iterations"] + g["coarse_iterations"], ls, color=color, marker=marker,
                 ms=4, label=f"{method} P{int(order)}")
    ax.set(xscale="log", yscale="log", xlabel="penalty kpen (absolute) [force/length^3]",
           ylabel="max |relative error| of p0, F, a; penetration / d [%]",
           title=f"Penalty error against kpen ({scene(frame)})")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, loc="lower left")
    ax2.set(xscale="log", xlabel="penalty kpen (absolute) [force/length^3]",
            ylabel="iterations, all levels", title="Newton / active-set iterations (all levels)")
    ax2.grid(True, alpha=0.3)
    ax2.legend(fontsize=7)
    return save(fig, path)


CHARTS = {"penalty": Chart(penalty_study, CAPTION)}
