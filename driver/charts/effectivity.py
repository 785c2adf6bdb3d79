"""Across studies: the estimate over the truth for every distinct answered result with a reference."""
from __future__ import annotations

from pathlib import Path

import matplotlib.lines
import matplotlib.patches
import matplotlib.pyplot as plt
import matplotlib.ticker
import numpy as np
import pandas as pd

from driver.charts.common import BAND, EFFECTIVITY_BAND, Chart, need, save
from driver.schema import ANSWERED

MODEL_TITLES = {"axi": "axisymmetric", "plane": "plane strain", "3d": "3D"}

CAPTION = ("The run's own error estimate (no reference used) over the true max error of the quantities "
           "that have both an estimate and a reference (p0, F and a; b in 3D; a punch's K), for every "
           "distinct answered result of every study (a study's copy of another's scene, with the same "
           f"relative errors, counts once), a panel per model: the grey band is {BAND}. A point below "
           "it would be an estimate that promised too much; above it the estimate is safe but pessimistic.")


def effectivity_rows(tables: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Every distinct answered result of every study with a reference: its true
    max error and its effectivity, the run's own estimate (no reference) over
    that truth. Both are maxima over the same quantities, those with an
    estimate and a reference (a punch's K too); a study's scaled copy of
    another's scene (the same relative errors) counts once."""
    frames = []
    for study, table in tables.items():
        rows = table[table["status"].isin(ANSWERED)]
        if "accuracy_predicted" not in rows or not len(rows):
            continue
        # the quantities the run estimates (est_err_*) and, with a reference, measures (err_*)
        quantities = [c.removeprefix("est_") for c in rows if c.startswith("est_err_")]
        quantities = [q.removeprefix("err_") for q in quantities if q in rows]
        errors = rows[[f"err_{q}" for q in quantities]].abs()
        estimated = rows[[f"est_err_{q}" for q in quantities]].notna().to_numpy()
        true = errors.where(estimated).max(axis=1, skipna=True)
        frames.append(rows.assign(study=study, true=true, effectivity=rows["accuracy_predicted"] / true))
    rows = pd.concat(frames, ignore_index=True) if frames else pd.DataFrame(columns=["effectivity"])
    rows = rows[np.isfinite(rows["effectivity"].astype(float)) & (rows["effectivity"] > 0)]
    same = rows[["model", "true", "effectivity"]].astype({"true": float, "effectivity": float}).round(
        {"true": 9, "effectivity": 6})
    return rows[~same.duplicated()]


def effectivity(tables: dict[str, pd.DataFrame], path: Path) -> Path:
    """Estimate over truth for every distinct answered result with a reference, a panel per model."""
    rows = need(effectivity_rows(tables), "no answered rows with a reference and an estimate")
    low, high = EFFECTIVITY_BAND
    models = [m for m in MODEL_TITLES if m in set(rows["model"])]
    fig, axes = plt.subplots(1, len(models), figsize=(6 * len(models), 6.4), squeeze=False)
    # a marker and a colour for each study: no pair depends on hue alone
    styles = {study: (plt.get_cmap("tab10")(k % 10), "os^DvP"[k % 6])
              for k, study in enumerate(sorted(rows["study"].unique()))}
    top = max(rows["effectivity"].max() * 1.5, 2 * high)
    for ax, model in zip(axes[0], models):
        g = rows[rows["model"] == model]
        for study, h in g.groupby("study"):
            color, marker = styles[study]
            ax.scatter(h["true"] * 100, h["effectivity"], s=24, marker=marker, edgecolors=color,
                       facecolors=[color if s == "converged" else "none" for s in h["status"]])
        title = f"{MODEL_TITLES[model]}: {g['effectivity'].between(low, high).sum()} of {len(g)} in the band"
        if model == "3d":  # the band is 3D's target from n = 5 on
            fine = g[g["n"] >= 5]
            title += f" ({fine['effectivity'].between(low, high).sum()} of {len(fine)} at n >= 5)"
        ax.axhspan(low, high, color="grey", alpha=0.15)
        ax.axhline(1, color="k", lw=1)
        ax.set(xscale="log", yscale="log", ylim=(0.2, top),
               xlabel="true max |relative error| of the estimated quantities [%]",
               ylabel="effectivity = estimate / truth",
               title=f"{title}, {(g['effectivity'] < low).sum()} below {low:g}")
        ax.yaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
        ax.grid(True, alpha=0.3)
    handles: list = [matplotlib.lines.Line2D([], [], ls="", marker=m, color=c, label=study)
                     for study, (c, m) in styles.items()]
    handles += [matplotlib.lines.Line2D([], [], ls="", marker="o", color="k", label="converged (filled)"),
                matplotlib.lines.Line2D([], [], ls="", marker="o", mfc="none", color="k", label="inaccurate (open)"),
                matplotlib.patches.Patch(color="grey", alpha=0.15, label=f"target band {low:g} to {high:g}")]
    fig.legend(handles=handles, loc="lower center", ncol=min(len(handles), 8), fontsize=8)
    fig.suptitle(f"The run's own error estimate against the truth: {len(rows)} distinct answered results of every "
                 f"study with a reference, {rows['effectivity'].between(low, high).sum()} in the band, "
                 f"{(rows['effectivity'] < low).sum()} below {low:g} (an estimate that promised too much)")
    fig.tight_layout(rect=(0, 0.1, 1, 1))
    return save(fig, path, layout=False)


CHARTS = {"effectivity": Chart(effectivity, CAPTION)}
