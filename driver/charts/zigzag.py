"""Across studies: the pointwise against the recovered peak pressure of every converged
axisymmetric Newton run of the parabola."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import pandas as pd

from driver.charts.common import Chart, need, save

CAPTION = ("Pointwise against recovered peak pressure error (converged axisymmetric Newton runs of "
           "Hertz's parabola), against kpen h^2/(8R) in units of p0: the pressure a penalty would "
           "build on the sag of a P1 chord under the curved indenter. P1's contact forms use the "
           "indenter's interpolant, so no run builds it, and the pointwise peak stays within about "
           "1% of the recovered one at any penalty.")


def zigzag(tables: dict, path: Path) -> Path:
    rows = pd.concat(need([t for name, t in tables.items() if len(t) and name != "figures"], "no study rows"))
    rows = need(rows[(rows["status"] == "converged") & (rows["method"] == "newton")
                     & (rows["model"] == "axi") & (rows["shape"] == "parabola")].drop_duplicates("case_id"),
                "no converged axisymmetric Newton rows of the parabola")
    h = rows["contact_scale"] / rows["n"]
    mismatch = rows["kpen"] * h**2 / (8 * rows["R"]) / rows["p0_hertz"]
    fig, ax = plt.subplots(figsize=(7.5, 5))
    for order, color in ((1, "#64b5f6"), (2, "#1565c0")):
        sel = rows["order"] == order
        ax.scatter(mismatch[sel], (rows["p0_point"][sel] / rows["p0_hertz"][sel] - 1).abs() * 100,
                   color=color, marker="o", s=18, label=f"pointwise max kpen<g>+, P{order}")
        ax.scatter(mismatch[sel], rows["err_p0"][sel].abs() * 100, color=color, marker="x", s=22,
                   label=f"recovered p0 (reported), P{order}")
    ax.axvline(1, color="grey", ls=":", label="kpen h^2/(8R) = p0")
    ax.set(xscale="log", yscale="log", xlabel="chord mismatch kpen h^2 / (8 R p0)",
           ylabel="|p0 error| against Hertz [%]", title="Pointwise and recovered peak pressure (sphere, Newton)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    return save(fig, path)


CHARTS = {"zigzag": Chart(zigzag, CAPTION)}
