"""The figures study's charts: pressure profiles, the seed's Figure 1 and the axis stresses,
from the profile.csv and axis.csv files the sweep kept."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import pandas as pd

from driver.charts.common import QUANTITY_COLORS, Chart, need, save

PRESSURE_PROFILES_CAPTION = ("Surface pressure for soft to stiff penalties. Dotted: the pointwise penalty "
                             "pressure kpen<u_z - h>+, against the indenter the contact forms see (P1: its "
                             "interpolant between the nodes); solid: the recovered pressure that is reported "
                             "(P1: nodal contact force / nodal area; P2: L2 projection of the nodal forces).")


def pressure_profiles(figures: pd.DataFrame, profiles: pd.DataFrame, path: Path) -> Path:
    cases = need(figures[figures["variant"].str.startswith("profile")], "no profile rows in figures")
    need(profiles, "no kept profile.csv of figures")
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8), sharey=True)
    for ax, order in zip(axes, (1, 2)):
        part = cases[cases["order"] == order].sort_values("kpen")
        hertz_drawn = False
        for (_, case), color in zip(part.iterrows(), QUANTITY_COLORS):
            prof = profiles[profiles["case_id"] == case["case_id"]]
            a, p0 = case["a_hertz"], case["p0_hertz"]
            if not hertz_drawn:
                ax.plot(prof["r"] / a, prof["p_hertz"] / p0, "k-", lw=2, label="Hertz")
                hertz_drawn = True
            ax.plot(prof["r"] / a, prof["p_point"] / p0, ":", color=color, lw=1,
                    label=f"pointwise kpen<g>+, kpen={case['kpen']:.0e}")
            ax.plot(prof["r"] / a, prof["p_fe"] / p0, "-", color=color, lw=1.2,
                    label=f"recovered p, kpen={case['kpen']:.0e}")
        ax.set(xlabel="r / a", title=f"P{order}, n = {part['n'].iloc[0]:.0f}" if len(part) else f"P{order}",
               xlim=(0, 1.6))
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    axes[0].set_ylabel("p / p0 (Hertz)")
    axes[0].set_ylim(-0.1, 1.6)
    fig.suptitle("Surface pressure against Hertz: the pointwise penalty pressure (dotted) and the reported one (solid)")
    return save(fig, path)


def seed_figure(figures: pd.DataFrame, profiles: pd.DataFrame, path: Path) -> Path:
    cases = need(figures[figures["variant"] == "seed figure"], "no seed-figure rows in figures").sort_values("kpen")
    need(profiles, "no kept profile.csv of figures")
    fig, ax = plt.subplots(figsize=(8, 5))
    colors = ("#90caf9", "#42a5f5", "#1565c0", "#0d47a1")
    prof = None
    for (_, case), color in zip(cases.iterrows(), colors):
        prof = profiles[profiles["case_id"] == case["case_id"]]
        a, d = case["a_hertz"], case["d"]
        ax.plot(prof["r"] / a, prof["u_z"] / d, "-", color=color, label=f"u_z, kpen={case['kpen']:.0e}")
        ax.plot(prof["r"] / a, prof["gap"] / d, "--", color=color, lw=1,
                label=f"gap h - u_z, kpen={case['kpen']:.0e}")
    if prof is not None:
        ax.plot(prof["r"] / a, prof["indenter"] / d, "r-", lw=2, label="indenter h = -d + r^2/2R")
    ax.axhline(0, color="grey", lw=0.5)
    ax.set(xlabel="r / a", ylabel="displacement / d", xlim=(0, 2.5),
           title="Seed Figure 1 redone: surface u_z, gap and indenter, soft to stiff penalty")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    return save(fig, path)


def axis_stresses(figures: pd.DataFrame, axis: pd.DataFrame, path: Path) -> Path:
    case = need(figures[figures["variant"] == "axis"], "no axis row in figures").iloc[0]
    data = need(axis[axis["case_id"] == case["case_id"]], "no kept axis.csv for the axis case")
    p0 = data["sigma_z_hertz"].abs().max()
    fig, ax = plt.subplots(figsize=(7, 5.5))
    z = data["depth_over_a"]
    for col, hcol, color in (("sigma_z", "sigma_z_hertz", QUANTITY_COLORS[0]),
                             ("sigma_r", "sigma_r_hertz", QUANTITY_COLORS[2]),
                             ("tau_max", "tau_max_hertz", QUANTITY_COLORS[1])):
        ax.plot(data[col] / p0, z, "-", color=color, lw=2, label=f"{col} FE")
        ax.plot(data[hcol] / p0, z, "k:", lw=1.2)
    ax.plot([], [], "k:", label="Hertz")
    peak = data.loc[data["tau_max"].idxmax()]
    ax.plot(peak["tau_max"] / p0, peak["depth_over_a"], "o", color=QUANTITY_COLORS[1])
    ax.annotate(f"tau_max {peak['tau_max'] / p0:.3f} p0 at {peak['depth_over_a']:.2f} a",
                (peak["tau_max"] / p0, peak["depth_over_a"]), xytext=(10, -5),
                textcoords="offset points", fontsize=8)
    ax.invert_yaxis()
    ax.set(xlabel="stress / p0 (Hertz)", ylabel="depth z / a",
           title=f"Stresses on the axis (sphere, {case['method']} P{case['order']:.0f}, n = {case['n']:.0f})")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="lower left")
    return save(fig, path)

SEED_FIGURE1_CAPTION = ("The seed's Figure 1 redone: surface displacement, gap h - u_z and the indenter for "
                        "soft to stiff penalties; a soft penalty lets the indenter sink into the body.")

AXIS_STRESSES_CAPTION = "sigma_z, sigma_r and tau_max = |sigma_r - sigma_z|/2 along the axis against Hertz."


CHARTS = {
    "pressure_profiles": Chart(pressure_profiles, PRESSURE_PROFILES_CAPTION, kept=("profile.csv",)),
    "seed_figure1": Chart(seed_figure, SEED_FIGURE1_CAPTION, kept=("profile.csv",)),
    "axis_stresses": Chart(axis_stresses, AXIS_STRESSES_CAPTION, kept=("axis.csv",)),
}
