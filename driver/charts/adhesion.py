"""The adhesion study's chart: force curves from loading to separation across the JKR-DMT
transition, against Maugis and Dugdale's exact curves, and the pull-off against the Tabor
parameter."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from driver.charts.bodies import contact_modulus
from driver.charts.common import Chart, need, save
from driver.references.maugis import Maugis

CAPTION = ("Adhesion (Maugis-Dugdale: a traction sigma0 out to a separation w/sigma0) of a sphere of the "
           "default scene (E = 10, nu = 0.3, R = 0.5) with w = 0.05, from the load -P 0.05 to separation "
           "(-pulloff 1), exact contact at n = 16, for Tabor parameters lambda from 0.15 (DMT's side) to 4.9 "
           "(JKR's side). Each curve is traced by its neck c (the cohesive zone's outer radius), through the "
           "least force, which under load control is the pull-off, and on beyond it, where neither the load nor "
           "the depth could follow it, to the contact's loss (markers: the trace's states, on the scene's "
           "mesh; lines: Maugis's exact curves). Left: the load against the depth; the curves of small lambda "
           "reach a = 0 at finite force and go on without contact, hanging on the cohesive zone. Middle: the "
           "contact radius against the load. Right: the pull-off force over pi w R against lambda, each run's "
           "(its own pair of levels, meshed at the pull-off, with its estimate as the error bar) on Maugis's "
           "curve, from DMT's 2 toward JKR's 1.5.")
COLORS = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9"]


def adhesion(frame: pd.DataFrame, paths: pd.DataFrame, path: Path) -> Path:
    df = need(frame[frame["status"].isin(["converged", "inaccurate"]) & (frame["w"] > 0)], "no adhesion rows").copy()
    df["Estar"] = contact_modulus(df)
    df = df.sort_values("tabor")
    fig, (curves, radii, pulloff) = plt.subplots(1, 3, figsize=(17, 5.4))
    for k, (_, row) in enumerate(df.iterrows()):
        color = COLORS[k % len(COLORS)]
        maugis = Maugis(row["Estar"], row["R"], row["w"], row["sigma0"])
        scale = np.pi * row["w"] * row["R"]
        rows = paths[paths["case_id"] == row["case_id"]].sort_values("step")
        exact = maugis.curve(1.05 * rows["a"].max(), 600)
        label = f"lambda = {row['tabor']:.2g}"
        curves.plot(exact["d"], exact["P"] / scale, "-", color=color, lw=1.2)
        curves.plot(rows["d"], rows["P"] / scale, "o", color=color, ms=3.5, label=label)
        curves.plot([row["d_pulloff_fe"]], [row["pulloff_fe"] / scale], "*", color=color, ms=12, mec="k", mew=0.6)
        radii.plot(exact["P"] / scale, exact["a"], "-", color=color, lw=1.2)
        radii.plot(rows["P"] / scale, rows["a"], "o", color=color, ms=3.5, label=label)
        radii.plot([row["pulloff_fe"] / scale], [row["a_pulloff_fe"]], "*", color=color, ms=12, mec="k", mew=0.6)
    curves.axhline(0, color="k", lw=0.6)
    curves.plot([], [], "k-", lw=1.2, label="Maugis (exact)")
    curves.plot([], [], "k*", ms=10, label="pull-off (its own levels)")
    curves.set(xlabel="depth d (the scene's length units)", ylabel="load P / (pi w R)",
               title="Load and depth, to separation")
    curves.legend(fontsize=8)
    radii.axvline(0, color="k", lw=0.6)
    radii.set(xlabel="load P / (pi w R)", ylabel="contact radius a (the scene's length units)",
              title="Contact radius and load")
    radii.legend(fontsize=8)
    first = df.iloc[0]
    lams = np.geomspace(0.05, 50, 20)
    sigmas = lams / Maugis(first["Estar"], first["R"], first["w"], 1.0).lam
    exact = [-Maugis(first["Estar"], first["R"], first["w"], s).pulloff("load")["P"] / (np.pi * first["w"] * first["R"])
             for s in sigmas]
    pulloff.plot(lams, exact, "k-", lw=1.2, label="Maugis (exact), load control")
    pulloff.axhline(2.0, color="0.5", ls="--", lw=1, label="DMT: 2")
    pulloff.axhline(1.5, color="0.5", ls=":", lw=1.2, label="JKR: 1.5")
    load = df[df["P"].notna()]
    value = -load["pulloff_fe"] / (np.pi * load["w"] * load["R"])
    pulloff.errorbar(load["tabor"], value, yerr=value * load["est_err_pulloff"], fmt="o", color=COLORS[0],
                     ms=6, capsize=3, label="runs (error bar: their estimate)")
    pulloff.set(xscale="log", xlabel="Tabor parameter lambda", ylabel="pull-off force / (pi w R)", ylim=(1.4, 2.1),
                title="Pull-off across the JKR-DMT transition")
    pulloff.legend(fontsize=8)
    return save(fig, path)


CHARTS = {"adhesion": Chart(adhesion, CAPTION, kept=("path.csv",))}
