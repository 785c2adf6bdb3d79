"""The indentation study's chart: load-unload curves of elastic-plastic spheres and a
cone, the mean pressure across the elastic, elastic-plastic and fully plastic regimes,
and Oliver and Pharr's hardness and modulus against the run's own."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from driver.charts.bodies import contact_modulus
from driver.charts.common import Chart, need, save

CAPTION = ("Elastic-plastic indentation (J2, perfectly plastic: -Y, -H 0) along a load path of 10 steps to the "
           "peak depth and 10 back to zero load (-unload 1), for spheres of the default scene (E = 10, nu = 0.3, "
           "R = 0.5, d = 0.02) at four yield stresses and a cone of 70.3 degrees (d = 0.01), with exact contact "
           "at n = 16. Left: the load against the depth, every step of each path; an elastic sphere unloads "
           "along its loading curve, a plastic one leaves a residual depth h_f. Middle: the mean pressure P/(pi "
           "a^2) over Y at every loading step of the spheres, against E* a/(Y R): Hertz's elastic line (4/(3 "
           "pi)) E* a/(Y R) up to first yield (p0 = 1.6 Y, the star), Johnson's cavity model (2/3)(1 + ln(E* "
           "a/(3 Y R))) in the elastic-plastic range, and Tabor's fully plastic band 2.6 Y to 3.1 Y (shaded); "
           "the runs reach it beyond E* a/(Y R) = 40, as Johnson reports for spheres, above the cavity model, "
           "which is approximate there (the early steps of the softest sphere are coarse: its mesh is made for "
           "the peak's contact). Right: Oliver and Pharr's analysis of each unloading (S from the converged "
           "linearization at the peak, h_c = h - eps P/S, A = pi l(h_c)^2 of the indenter's profile) against the "
           "run's own contact: their hardness over P/(pi a^2), their area over pi a^2, and their modulus E_r "
           "over E*, against h_f/h_max. Elastic (h_f = 0) they agree; as h_f/h_max grows the material piles up "
           "around the indenter, the method (which assumes an elastic sink-in) reads less area than the contact "
           "has, and H and E_r read high: the pile-up error.")
COLORS = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9"]


def _label(row: pd.Series) -> str:
    y = row["Y"]
    name = "sphere" if row["shape"] == "parabola" else str(row["shape"])
    return f"{name}, elastic" if not np.isfinite(y) else f"{name}, Y = {y:g}"


def indentation(frame: pd.DataFrame, paths: pd.DataFrame, path: Path) -> Path:
    df = need(frame[frame["status"].isin(["converged", "inaccurate"])], "no indentation rows").copy()
    df["Estar"], df["label"] = contact_modulus(df), df.apply(_label, axis=1)
    df = df.sort_values(["shape", "Y"], ascending=[False, False])
    fig, (loops, regimes, op) = plt.subplots(1, 3, figsize=(17, 5.4))
    for k, (_, row) in enumerate(df.iterrows()):
        color = COLORS[k % len(COLORS)]
        steps = paths[paths["case_id"] == row["case_id"]].sort_values("step")
        marker = "^" if row["shape"] == "cone" else "o"
        loops.plot(steps["d"], steps["P"], marker + "-", color=color, ms=3.5, lw=1, label=row["label"])
        if row["shape"] != "parabola" or not np.isfinite(row["Y"]):
            continue
        loading = steps.iloc[: len(steps) // 2]
        loading = loading[loading["a"] > 0]
        x = row["Estar"] * loading["a"] / (row["Y"] * row["R"])
        regimes.plot(x, loading["pm"] / row["Y"], marker + "-", color=color, ms=5, lw=1, label=row["label"])
    loops.set(xlabel="depth d (the scene's length units)", ylabel="load P (the scene's force units)",
              title="Load and unload (10 + 10 steps)")
    loops.legend(fontsize=8)
    x = np.geomspace(0.3, 400, 200)
    elastic_end = 1.6 * 2 / 3 / (4 / (3 * np.pi))   # pm = (2/3) p0 at p0 = 1.6 Y
    regimes.plot(x[x <= elastic_end], 4 / (3 * np.pi) * x[x <= elastic_end], "k-", lw=1.2,
                 label="Hertz: (4/(3 pi)) E* a/(Y R)")
    regimes.plot([elastic_end], [1.6 * 2 / 3], "k*", ms=11, label="first yield, p0 = 1.6 Y")
    cavity = x[x >= 3]
    regimes.plot(cavity, 2 / 3 * (1 + np.log(cavity / 3)), "k--", lw=1.2,
                 label="Johnson's cavity model: (2/3)(1 + ln(E* a/(3 Y R)))")
    regimes.axhspan(2.6, 3.1, color="0.85", zorder=0, label="Tabor: fully plastic, 2.6 Y to 3.1 Y")
    regimes.set(xscale="log", xlabel="E* a / (Y R)", ylabel="mean pressure P/(pi a^2) / Y", ylim=(0, 3.6),
                title="Elastic, elastic-plastic, fully plastic")
    regimes.legend(fontsize=8, loc="upper left")
    unloaded = df[np.isfinite(df["hf_fe"]) & np.isfinite(df["Er_op"])].copy()
    unloaded["hf_ratio"] = unloaded["hf_fe"] / unloaded["d_fe"]
    ratios = {"hardness H_op / (P/(pi a^2))": ("o", COLORS[0], lambda g: g["H_op"] / g["pm_fe"]),
              "area A(h_c) / (pi a^2)": ("s", COLORS[1], lambda g: g["A_op"] / (np.pi * g["a_fe"] ** 2)),
              "modulus E_r / E*": ("D", COLORS[2], lambda g: g["Er_op"] / g["Estar"])}
    for text, (marker, color, value) in ratios.items():
        for shape, g in unloaded.groupby("shape"):
            filled = shape == "parabola"
            op.plot(g["hf_ratio"], value(g), marker, ms=7, color=color, mfc=None if filled else "none",
                    label=f"{'sphere' if filled else shape}: {text}")
    op.axhline(1, color="k", lw=0.8)
    op.set(xlabel="residual depth h_f / h_max", ylabel="Oliver and Pharr / the run's own",
           title="Oliver and Pharr against the contact")
    op.legend(fontsize=8)
    fig.tight_layout()
    return save(fig, path)


CHARTS = {"indentation": Chart(indentation, CAPTION, kept=("path.csv",))}
