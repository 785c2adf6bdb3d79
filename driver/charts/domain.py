"""The domain study's chart: the finite domain's bias against its radius."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from driver.charts.common import QUANTITY_COLORS, Chart, need, save, scene

CAPTION = ("Force and peak-pressure bias of a finite domain against its radius L/a (exact contact, so no "
           "penalty error): a clamped far boundary follows 0.94% x 100a/L; Boussinesq's boundary (the rest "
           "of the half-space moving as a point load of the contact force, the default) stays at the "
           "discretization floor from L = 10 a.")


def domain_bias(frame: pd.DataFrame, path: Path) -> Path:
    """|F| and |p0| errors against the domain radius, for a clamped far boundary and
    for Boussinesq's (inaccurate cases included: a clamped boundary near the contact is
    far off, and says so)."""
    df = need(frame[frame["status"].isin(["converged", "inaccurate"])], "no domain rows").sort_values("L")
    fig, ax = plt.subplots(figsize=(7.5, 5.2))
    styles = {"clamped": ("o", "-"), "boussinesq": ("D", "--")}
    for far, g in df.groupby("farfield"):
        marker, ls = styles.get(far, ("x", ":"))
        ax.plot(g["L"], g["err_F"].abs() * 100, marker=marker, ls=ls, color=QUANTITY_COLORS[1],
                label=f"|F error|, {far} far boundary")
        ax.plot(g["L"], g["err_p0"].abs() * 100, marker=marker, ls=ls, color=QUANTITY_COLORS[0], ms=4,
                label=f"|p0 error|, {far} far boundary")
    L = np.logspace(np.log10(df["L"].min()), np.log10(df["L"].max()), 50)
    ax.plot(L, 0.94 * 100 / L, "k:", label="0.94% x 100a / L (a clamped boundary)")
    ax.set(xscale="log", yscale="log", xlabel="domain radius L / a", ylabel="relative error against Hertz [%]",
           title=f"Finite-domain bias ({df['method'].iloc[0]}, {scene(df)})")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    return save(fig, path)


CHARTS = {"domain": Chart(domain_bias, CAPTION)}
