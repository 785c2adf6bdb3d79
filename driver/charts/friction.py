"""The friction study's chart: Spence's stick zone against beta/mu, and full stick's stiffness."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from driver.charts.common import Chart, need, save
from driver.references.spence import mossakovskii, rigid_beta, spence_path, spence_plane

CAPTION = ("Left: the stick zone's radius c over the contact radius a after monotone normal loading with "
           "Coulomb friction (Spence's problem), against beta/mu, beta = (1 - 2nu)/(2(1 - nu)) for a rigid "
           "indenter: spheres (axisymmetric) at four Poisson's ratios, and the cylinder (plane strain) "
           "against a boundary-element solution of the half-plane (line). Bars: twice the run's own estimate "
           "of c, which reads c to half a node gap (most finite-mu runs end inaccurate, exit 5, on it). "
           "Right: full stick's contact stiffness S/(2E*a) against Mossakovskii's factor "
           "(1 - nu) ln(3 - 4nu)/(1 - 2nu). Each point is a load path of 16 steps at n = 16. "
           "Bottom left: a cylinder (mu = 0.2, nu = 0.3) loaded and unloaded to half its load (-path 1,0.5, 16 "
           "steps a leg): c/a and a over the peak's a at every step, against the boundary elements along the same "
           "loads. Bottom right: a cylinder (mu = 0.3) pulled along x after the normal load up to Q = mu P/2 (-Q, "
           "16 steps): c/a at each step against Cattaneo's (incompressible, beta = 0) and the boundary elements "
           "(nu = 0.3), and a fretting cycle (-Qpath 1,-1,1, open squares) against Mindlin and Deresiewicz's "
           "branches. Bars: twice each step's estimate.")
# Okabe and Ito's colours, apart under every colour-vision deficiency; black is the reference
NU_STYLES = {0.0: ("#0072B2", "o"), 0.2: ("#009E73", "s"), 0.3: ("#D55E00", "D"), 0.4: ("#CC79A7", "^")}


def friction(frame: pd.DataFrame, paths: pd.DataFrame, path: Path) -> Path:
    df = need(frame[frame["status"].isin(["converged", "inaccurate"])], "no friction rows")
    fig = plt.figure(figsize=(14, 10.5))
    grid = fig.add_gridspec(2, 2, width_ratios=[1.6, 1])
    left, right = fig.add_subplot(grid[0, 0]), fig.add_subplot(grid[0, 1])
    bottom, along = fig.add_subplot(grid[1, 0]), fig.add_subplot(grid[1, 1])
    # a case whose load falls somewhere along its kept path was unloaded; one with Q_fe, pulled along x
    # (a held load reads equal to rounding: a fall is one beyond it)
    falls = paths.sort_values("step").groupby("case_id")["P"].apply(
        lambda p: bool((np.diff(p) < -1e-9 * p.max()).any()))
    monotone = ~df["case_id"].map(falls).fillna(False).astype(bool)
    pulled = df["Q_fe"] > 0
    unloaded, tangential, df = df[~monotone & ~pulled], df[pulled], df[monotone & ~pulled]
    finite = df[np.isfinite(df["mu"]) & (df["mu"] > 0)].copy()
    finite["x"] = rigid_beta(finite["nu"]) / finite["mu"]
    finite["c_over_a"] = finite["c_fe"] / finite["a_fe"]
    spheres = finite[finite["model"] == "axi"]
    for nu, g in spheres.groupby("nu"):
        color, marker = NU_STYLES.get(round(nu, 3), ("#999999", "x"))
        g = g.sort_values("x")
        left.errorbar(g["x"], g["c_over_a"], yerr=2 * g["est_err_c"] * g["c_over_a"], fmt=marker + "-",
                      color=color, ms=6, capsize=2, lw=1, label=f"sphere, nu = {nu:g}")
    cylinders = finite[finite["model"] == "plane"].sort_values("x")
    if len(cylinders):
        nu = cylinders["nu"].iloc[0]
        left.errorbar(cylinders["x"], cylinders["c_over_a"], yerr=2 * cylinders["est_err_c"] * cylinders["c_over_a"],
                      fmt="v", color="#E69F00", ms=7, capsize=2, label=f"cylinder, nu = {nu:g} (FE)")
        mus = np.geomspace(cylinders["mu"].min() * 0.8, cylinders["mu"].max() * 1.2, 9)
        ref = [spence_plane(mu, nu, steps=40, cells=300)["c_over_a"] for mu in mus]
        left.plot(rigid_beta(nu) / mus, ref, "k-", lw=1.2, label=f"cylinder, nu = {nu:g}: boundary elements")
    left.set(xscale="log", xlabel="beta / mu", ylabel="c / a", ylim=(0, 1.05),
             title="Spence: the stick zone after monotone normal loading")
    left.grid(True, which="both", alpha=0.3)
    left.legend(fontsize=8)

    stick = df[np.isinf(df["mu"])].sort_values("nu")
    if len(stick):
        ratio = stick["S_fe"] / (2 * stick["E"] / (1 - stick["nu"] ** 2) * stick["a_fe"])
        nus = np.linspace(0, 0.45, 50)
        right.plot(nus, mossakovskii(nus), "k-", label="Mossakovskii: (1 - nu) ln(3 - 4nu)/(1 - 2nu)")
        right.plot(stick["nu"], ratio, "o", color="#0072B2", ms=7, label="FE, full stick (mu = inf)")
        right.plot(nus, np.ones_like(nus), ":", color="#999999", label="frictionless: 1")
        for nu, r in zip(stick["nu"], ratio):
            right.annotate(f"{(r / mossakovskii(nu) - 1) * 100:+.2f}%", (nu, r), textcoords="offset points",
                           xytext=(6, -12), fontsize=8)
    right.set(xlabel="Poisson's ratio nu", ylabel="S / (2 E* a)", title="Full stick: the contact stiffness")
    right.grid(True, alpha=0.3)
    right.legend(fontsize=8)

    for _, case in unloaded.iterrows():
        rows = paths[paths["case_id"] == case["case_id"]].sort_values("step")
        if not len(rows):
            continue
        peak = rows["a"].max()
        bem = spence_path(case["mu"], case["nu"], rows["P"].to_numpy(), cells=400, E=case["E"], R=case["Rx"])
        ratio = rows["c"] / rows["a"]
        bottom.errorbar(rows["step"], ratio, yerr=2 * rows["est_err"] * ratio, fmt="v", color="#E69F00", ms=6,
                        capsize=2, label=f"c/a, FE (mu = {case['mu']:g}, nu = {case['nu']:g})")
        bottom.plot(rows["step"], [b["c_over_a"] for b in bem], "k-", lw=1.2, label="c/a, boundary elements")
        bottom.plot(rows["step"], rows["a"] / peak, "o", color="#0072B2", ms=5, label="a / a_peak, FE")
        bottom.plot(rows["step"], [b["a"] / peak for b in bem], "k--", lw=1, label="a / a_peak, boundary elements")
        bottom.axvline(len(rows) / 2 + 0.5, color="#999999", ls=":", lw=1)
    bottom.set(xlabel="step of the path (loading to the peak, then unloading to half the load)",
               ylabel="c / a, a / a_peak", ylim=(0, 1.05),
               title="A cylinder loaded and unloaded: the stick zone along the path")
    bottom.grid(True, alpha=0.3)
    bottom.legend(fontsize=8, loc="center right")

    shares = np.linspace(0, 0.99, 100)
    along.plot(shares, np.sqrt(1 - shares), "k-", lw=1.2, label="Cattaneo: sqrt(1 - Q/(mu P)) (beta = 0)")
    reversed_any = False
    for _, case in tangential.sort_values("nu", ascending=False).iterrows():
        # the tangential legs' rows: after the normal legs, whose Q is 0 (to rounding) and whose P rises
        every = paths[paths["case_id"] == case["case_id"]].sort_values("step")
        first = int(np.argmax(np.abs(every["Q"].to_numpy()) > 1e-6 * abs(case["Q_fe"])))
        rows = every.iloc[first:]
        cycle = case["Q_fe"] < 0 or (np.diff(rows["Q"]) < 0).any()
        color, marker = ("#009E73", "s") if cycle else NU_STYLES.get(round(case["nu"], 3), ("#E69F00", "v"))
        ratio = rows["c"] / rows["a"]
        label = f"FE, nu = {case['nu']:g} (beta = {rigid_beta(case['nu']):.2f})"
        label += ", a fretting cycle" if cycle else ""
        along.errorbar(rows["Q"] / (case["mu"] * rows["P"]), ratio, yerr=2 * rows["est_err"] * ratio, fmt=marker,
                       color=color, ms=5 if cycle else 6, capsize=2, label=label, lw=0.6, elinewidth=1,
                       ls="-" if cycle else "none", mfc="none" if cycle else color)
        if cycle:
            reversed_any = True
            peak = rows["Q"].abs().max() / (case["mu"] * case["P"])
            back = np.linspace(peak, -peak, 100)
            along.plot(back, np.sqrt(1 - (peak - back) / 2), "k:", lw=1.2,
                       label="Mindlin-Deresiewicz: back, sqrt(1 - (Q* - Q)/(2 mu P)); again, mirrored")
            along.plot(back, np.sqrt(1 - (peak + back) / 2), "k:", lw=1.2)
            continue
        if case["nu"] < 0.5:
            every = paths[paths["case_id"] == case["case_id"]].sort_values("step")
            bem = spence_path(case["mu"], case["nu"], every["P"].to_numpy(), cells=400, E=case["E"], R=case["Rx"],
                              tangential=every["Q"].to_numpy())
            pulled_steps = (every["Q"] > 1e-6 * case["Q_fe"]).to_numpy()
            along.plot(every["Q"][pulled_steps] / (case["mu"] * every["P"][pulled_steps]),
                       [b["c_over_a"] for b, k in zip(bem, pulled_steps) if k], "-", color=color, lw=1,
                       label=f"nu = {case['nu']:g}: boundary elements")
    along.set(xlabel="Q / (mu P)", ylabel="c / a", xlim=(-0.55 if reversed_any else 0, 1), ylim=(0, 1.05),
              title="A cylinder pulled along x after the normal load")
    along.grid(True, alpha=0.3)
    along.legend(fontsize=8, loc="lower left")
    return save(fig, path)


CHARTS = {"friction": Chart(friction, CAPTION, kept=("path.csv",))}
