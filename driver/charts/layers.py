"""The layers study's chart: the coated body against the half-space limits and Perriot and
Barthel's integral equation (driver/references/layered.py)."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from driver.charts.common import Chart, need, save
from driver.references import layered

CAPTION = ("A film (E, nu) bonded to a substrate (E2, nu2) or a rigid base, sphere at d = 0.02, exact "
           "contact. Top left: the effective modulus from the contact stiffness against a/t, with the two "
           "half-space limits and Perriot and Barthel's integral equation (driver/references/layered.py, "
           "accurate to about 1e-8; the tests check every quantity against it). Top right: the coated F "
           "over the film's own Hertz at the same depth (the grey band is 1%). Bottom: pressure and axis "
           "stresses of a soft film on a stiff substrate and a stiff film on a soft one.")


def layers(frame: pd.DataFrame, profiles: pd.DataFrame, axis: pd.DataFrame, path: Path) -> Path:
    """The coated body: effective modulus over a/t, the half-spaces' under-modelling, the
    pressure profiles and the stresses on the axis of a soft and a stiff film."""
    df = need(frame[frame["status"].isin(["converged", "inaccurate"])], "no layers rows").copy()
    estar1 = df["E"] / (1 - df["nu"] ** 2)
    df["E_eff"] = df["S_fe"] / (2 * df["a_fe"]) / estar1
    df["a_over_t"] = df["a_fe"] / df["t"]
    fig, axes = plt.subplots(2, 2, figsize=(13, 10))
    series = [v for v in dict.fromkeys(df["variant"]) if not v.startswith("profile")]
    colors = dict(zip(series, ["#0d47a1", "#42a5f5", "#ef6c00", "#b71c1c", "#212121"]))
    ax = axes[0, 0]
    for variant in series:
        g = df[df["variant"] == variant].sort_values("a_over_t")
        color = colors[variant]
        ax.plot(g["a_over_t"], g["E_eff"], "o", color=color, label=f"{variant} (FE)")
        row = g.iloc[0]
        coating = layered.Coating(E1=row["E"], nu1=row["nu"], t=1.0, E2=row["E2"],
                                  nu2=row["nu2"] if np.isfinite(row["nu2"]) else 0.3)
        x = np.logspace(np.log10(g["a_over_t"].min()) - 0.2, np.log10(g["a_over_t"].max()) + 0.2, 25)
        ax.plot(x, [layered.effective_modulus(coating, ax_) / estar1.iloc[0] for ax_ in x], "-",
                color=color, lw=1)
        if variant != "rigid base":
            ax.axhline(row["E2"] / (1 - row["nu2"] ** 2) / estar1.iloc[0], color=color, lw=0.8, ls="--")
    ax.axhline(1, color="grey", lw=0.8, ls="--")
    ax.plot([], [], "k--", lw=0.8, label="half-space limits: film (1), substrate (E2*/E*)")
    ax.plot([], [], "k-", lw=1, label="Perriot & Barthel (2004) integral equation (driver/references/layered.py)")
    ax.set(xscale="log", yscale="log", xlabel="contact radius / film thickness a/t",
           ylabel="effective modulus E_eff* / E_film*  (S = 2 E_eff* a)",
           title="Effective modulus of a coated body (sphere, exact contact)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    ax = axes[0, 1]
    for variant in series:
        g = df[df["variant"] == variant].sort_values("a_over_t")
        ax.plot(g["a_over_t"], g["F_fe"] / g["hs_film_F"], "o-", color=colors[variant], label=variant)
    ax.axhspan(0.99, 1.01, color="grey", alpha=0.2, label="the film's Hertz within 1%")
    ax.set(xscale="log", yscale="log", xlabel="a/t", ylabel="F (coated, FE) / F (film's Hertz, same d)",
           title="Where the film's half-space model stops being enough")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    pcases = df[df["variant"].str.startswith("profile")]
    for variant, color in zip(sorted(pcases["variant"]), ("#1565c0", "#c62828")):
        case = pcases[pcases["variant"] == variant].iloc[0]
        label = f"{variant[8:]}: t = {case['a_over_t'] ** -1:.2g} a, E2/E = {case['E2'] / case['E']:g}"
        prof = profiles[profiles["case_id"] == case["case_id"]] if len(profiles) else profiles
        if len(prof):
            axes[1, 0].plot(prof["r"] / case["a_fe"], prof["p_fe"] / case["p0_fe"], "-", color=color, label=label)
        data = axis[axis["case_id"] == case["case_id"]] if len(axis) else axis
        if len(data):
            z = data["depth"] / case["a_fe"]
            axes[1, 1].plot(data["sigma_z"] / case["p0_fe"], z, "-", color=color, label=f"sigma_z, {label}")
            axes[1, 1].plot(data["tau_max"] / case["p0_fe"], z, "--", color=color, label=f"tau_max, {label}")
            axes[1, 1].axhline(case["t"] / case["a_fe"], color=color, lw=0.8, ls=":")
    axes[1, 0].set(xlim=(0, 1.5), xlabel="r / a", ylabel="p / p0 (each its own)",
                   title="Surface pressure: a soft film on a stiff base, a stiff film on a soft one")
    axes[1, 1].invert_yaxis()
    axes[1, 1].set(xlabel="stress / p0", ylabel="depth z / a (dotted: the interface)",
                   title="Stresses on the axis, through the interface")
    for ax in axes[1]:
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    return save(fig, path)


CHARTS = {"layers": Chart(layers, CAPTION, kept=("profile.csv", "axis.csv"))}
