"""The bodies study's chart: two elastic bodies against Hertz with the combined E* and R,
an elastic exact sphere against Sneddon's as a/R grows, and two cylinders under a
tangential force against Cattaneo and the boundary elements."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from driver.charts.common import Chart, need, save
from driver.references.spence import dundurs_beta, equivalent_rigid, spence_path

CAPTION = ("Two elastic bodies (-E1, -nu1, -R2), each a half-space of its own material (the indenter "
           "meshed as the mirror image of the body's section), in contact along their relative displacement. "
           "Left: the force and the contact radius "
           "against the approach d, all made dimensionless by Hertz's combined E* (1/E* = (1 - nu1^2)/E1 + "
           "(1 - nu^2)/E) and relative radius (1/R = 1/R1 + 1/R2), for identical spheres, dissimilar ones "
           "(a stiffer indenter on a body of twice its radius), a soft indenter, and Code_Aster's SSNV104 "
           "(two hemispheres of R = 50 mm, E = 20,000 MPa, 4 mm approach: a = 10 mm); lines: Hertz. Middle: "
           "an elastic sphere's exact cap on a flat body of its own material, as a/R grows: the run's F and a "
           "against Hertz's parabola, and Sneddon's exact sphere (lines), which the run follows; the gap "
           "between them is the error Hertz makes; stars: SSNV104's two exact spheres (-shape sphere -R2), "
           "against Hertz's parabolas of the relative radius. Bars: twice the run's own estimate. Right: two cylinders "
           "(plane strain, mu = 0.3, nu = 0.3) pulled along x after the normal load up to Q = mu P/2 (16 "
           "steps): identical bodies have Dundurs' beta = 0, so Cattaneo's c/a = sqrt(1 - Q/(mu P)) holds "
           "at nu = 0.3; a three times stiffer indenter has beta = 0.14, against the boundary elements of "
           "the rigid indenter with the same E* and beta.")
STYLES = {"identical spheres": ("#0072B2", "o"), "dissimilar: E1 = 3E, R2 = 2R": ("#D55E00", "s"),
          "soft indenter: E1 = E/10": ("#009E73", "^"), "SSNV104": ("#CC79A7", "*")}


def contact_modulus(df: pd.DataFrame) -> pd.Series:
    """Hertz's E* of each row: the body's in series with the indenter's (E1 = inf: rigid)."""
    indenter = np.where(np.isfinite(df["E1"]), (1 - df["nu1"].fillna(0) ** 2) / df["E1"], 0.0)
    return 1 / ((1 - df["nu"] ** 2) / df["E"] + indenter)


def relative_radius(df: pd.DataFrame) -> pd.Series:
    return 1 / (1 / df["R"] + np.where(np.isfinite(df["R2"]), 1 / df["R2"], 0.0))


def bodies(frame: pd.DataFrame, paths: pd.DataFrame, path: Path) -> Path:
    df = need(frame[frame["status"].isin(["converged", "inaccurate"])], "no bodies rows").copy()
    df["Estar"], df["Rrel"] = contact_modulus(df), relative_radius(df)
    fig, (left, middle, right) = plt.subplots(1, 3, figsize=(17, 5.4))
    normal = df[df["variant"].isin(list(STYLES))]
    x = np.geomspace(3e-4, 0.3, 50)
    left.plot(x, 4 / 3 * x**1.5, "k-", lw=1, label="Hertz: F/(E* R^2) = (4/3)(d/R)^1.5")
    left.plot(x, np.sqrt(x), "k--", lw=1, label="Hertz: a/R = (d/R)^0.5")
    for variant, g in normal.groupby("variant"):
        color, marker = STYLES[variant]
        g = g.sort_values("d_fe")
        dr = g["d_fe"] / g["Rrel"]
        left.plot(dr, g["F_fe"] / (g["Estar"] * g["Rrel"] ** 2), marker, color=color, ms=8 if marker == "*" else 6,
                  label=f"{variant}: F")
        left.plot(dr, g["a_fe"] / g["Rrel"], marker, color=color, mfc="none", ms=8 if marker == "*" else 6,
                  label=f"{variant}: a")
    left.set(xscale="log", yscale="log", xlabel="approach d / R (R: the relative radius)",
             ylabel="F / (E* R^2) (filled), a / R (open)", title="Two elastic bodies against Hertz (combined E*, R)")
    left.grid(True, which="both", alpha=0.3)
    left.legend(fontsize=7, loc="lower right")

    caps = df[df["variant"] == "elastic exact sphere"].sort_values("d_fe")
    if len(caps):
        R = float(caps["Rrel"].iloc[0])
        a_over_r = caps["a_fe"] / R
        # Hertz's parabola at the run's depth (the runs' own reference is Sneddon's sphere)
        hertz_a = np.sqrt(R * caps["d_fe"])
        hertz_F = 4 / 3 * caps["Estar"] * np.sqrt(R) * caps["d_fe"] ** 1.5
        for column, hertz, color, marker, name in (("F_fe", hertz_F, "#0072B2", "o", "F"),
                                                   ("a_fe", hertz_a, "#D55E00", "s", "a")):
            est = caps["est_err_F" if name == "F" else "est_err_a"]
            middle.errorbar(a_over_r, 100 * (caps[column] / hertz - 1), yerr=200 * est, fmt=marker, color=color,
                            capsize=2, ms=6, label=f"FE {name} against Hertz's parabola")
        # the runs' own reference at their depths (reference = sneddon: the exact sphere)
        middle.plot(caps["a_hertz"] / R, 100 * (caps["F_hertz"] / hertz_F - 1), "-", color="#0072B2", lw=1,
                    label="Sneddon's exact sphere: F")
        middle.plot(caps["a_hertz"] / R, 100 * (caps["a_hertz"] / hertz_a - 1), "-", color="#D55E00", lw=1,
                    label="Sneddon's exact sphere: a")
    pair = df[df["variant"] == "SSNV104, exact caps"]
    for _, case in pair.iterrows():
        # against Hertz's parabolas of the relative radius at the same approach
        hertz_a = np.sqrt(case["Rrel"] * case["d_fe"])
        hertz_F = 4 / 3 * case["Estar"] * np.sqrt(case["Rrel"]) * case["d_fe"] ** 1.5
        x = case["a_fe"] / case["R"]
        middle.plot(x, 100 * (case["F_fe"] / hertz_F - 1), "*", color="#0072B2", ms=12, mec="k",
                    label="SSNV104's two exact spheres: F (a/R of each)")
        middle.plot(x, 100 * (case["a_fe"] / hertz_a - 1), "*", color="#D55E00", ms=12, mec="k",
                    label="SSNV104's two exact spheres: a")
    middle.axhline(0, color="k", lw=0.6)
    middle.set(xlabel="a / R", ylabel="difference from Hertz's parabola at the same d (%)",
               title="An elastic exact sphere on a flat body: Hertz's error")
    middle.grid(True, alpha=0.3)
    middle.legend(fontsize=8, loc="lower left")

    pulled = df[df["Q_fe"] > 0]
    for _, case in pulled.sort_values("E1").iterrows():
        every = paths[paths["case_id"] == case["case_id"]].sort_values("step")
        first = int(np.argmax(np.abs(every["Q"].to_numpy()) > 1e-6 * case["Q_fe"]))
        rows = every.iloc[first:]
        beta = dundurs_beta(case["E1"], case["nu1"], case["E"], case["nu"])
        ratio = rows["c"] / rows["a"]
        color, marker = ("#0072B2", "o") if abs(beta) < 1e-12 else ("#D55E00", "s")
        right.errorbar(rows["Q"] / (case["mu"] * rows["P"]), ratio, yerr=2 * rows["est_err"] * ratio, fmt=marker,
                       color=color, capsize=2, ms=6, label=f"FE, E1/E = {case['E1'] / case['E']:g} (beta = {beta:.2f})")
        if abs(beta) < 1e-12:
            q = np.linspace(0, 1, 60)
            right.plot(q, np.sqrt(1 - q), "k-", lw=1, label="Cattaneo: sqrt(1 - Q/(mu P))")
        else:
            E_eq, nu_eq = equivalent_rigid(case["E1"], case["nu1"], case["E"], case["nu"])
            bem = spence_path(case["mu"], nu_eq, every["P"].to_numpy(), cells=400, E=E_eq, R=case["Rrel"],
                              tangential=every["Q"].to_numpy())
            keep = (every["Q"] > 1e-6 * case["Q_fe"]).to_numpy()
            right.plot(every["Q"][keep] / (case["mu"] * every["P"][keep]),
                       [b["c_over_a"] for b, k in zip(bem, keep) if k], "-", color=color, lw=1,
                       label=f"boundary elements, beta = {beta:.2f}")
    if not len(pulled):
        right.text(0.5, 0.5, "no tangential runs\n(not in the quick subset)", ha="center", va="center",
                   transform=right.transAxes)
    right.set(xlabel="Q / (mu P)", ylabel="c / a", xlim=(0, 1), ylim=(0, 1.05),
              title="Two cylinders pulled along x (nu = 0.3)")
    right.grid(True, alpha=0.3)
    if len(pulled):
        right.legend(fontsize=8, loc="lower left")
    return save(fig, path)


CHARTS = {"bodies": Chart(bodies, CAPTION, kept=("path.csv",))}
