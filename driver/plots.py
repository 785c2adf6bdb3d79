"""Charts from the study tables (PNG, matplotlib). Reads CSV files only.

Series are chosen by the `variant` column the studies write, and titles take
their facts (mesh, penalty, scene) from the rows they draw. A chart whose rows
are missing raises NoData (the report skips it with a note), and every PNG is
written to a temporary file and renamed, so an interrupted report leaves the
old chart whole.
"""
from __future__ import annotations

import math
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.lines  # noqa: E402
import matplotlib.patches  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from driver import files, layout  # noqa: E402
from driver.errors import ReportError  # noqa: E402
from driver.schema import ANSWERED, max_error  # noqa: E402

ERRORS = {"err_p0": "p0", "err_F": "F", "err_a": "a"}
QUANTITY_COLORS = ("#1565c0", "#c62828", "#2e7d32")
# Okabe and Ito's colour-blind-safe palette (distinct hues and lightness), and a
# hatch on every status but converged, so no pair depends on telling hues apart
STATUS_COLORS = {"converged": "#009E73", "inaccurate": "#F0E442", "roundoff": "#56B4E9",
                 "stalled": "#E69F00", "maxiter": "#CC79A7", "diverged": "#D55E00",
                 "nan": "#0072B2", "timeout": "#999999", "failed": "#000000"}
STATUS_HATCHES = {"converged": "", "inaccurate": ".", "roundoff": "/", "stalled": "\\\\", "maxiter": "-",
                  "diverged": "x", "nan": "+", "timeout": "|", "failed": "o"}
CELL_EDGE = (0, 0, 0, 0.3)  # cell borders and hatches: light enough to read the numbers through
METHOD_STYLE = {("newton", 2): ("#1565c0", "o"), ("newton", 1): ("#64b5f6", "s"),
                ("lagrange", 2): ("#2e7d32", "D"), ("lagrange", 1): ("#a5d6a7", "d"),
                ("uzawa", 2): ("#6a1b9a", "P"), ("uzawa", 1): ("#ce93d8", "p"),
                ("fixedpoint", 2): ("#c62828", "^"), ("fixedpoint", 1): ("#ef9a9a", "v")}


class NoData(Exception):
    """The rows a chart draws are not in the tables (a partial sweep): skip the chart."""


def need(frame: pd.DataFrame | None, what: str) -> pd.DataFrame:
    """The rows a chart draws, or NoData naming what is missing."""
    if frame is None or not len(frame):
        raise NoData(what)
    return frame


def sphere_cases(tables: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Converged sphere cases of every study (axisymmetric, and in 3D), once each
    (the same case in two studies is one point), with their max |error|."""
    frames = [t for name, t in tables.items() if len(t) and name != "figures"]
    rows = pd.concat(need(frames, "no study rows"), ignore_index=True)
    sphere = (rows["model"] == "axi") | ((rows["model"] == "3d") & (rows["Rx"] == rows["Ry"]))
    # Hertz's paraboloid on a homogeneous body: the other shapes and the coated bodies have their own charts
    if "shape" in rows:
        sphere &= rows["shape"].fillna("parabola").eq("parabola")
    if "t" in rows:
        sphere &= rows["t"].isna()
    sphere &= rows["Rx"] == rows["Ry"]
    rows = rows[(rows["status"] == "converged") & sphere].drop_duplicates("case_id")
    return rows.assign(max_err=max_error(rows))


def _save(fig, path: Path, layout: bool = True) -> Path:
    """The chart as PNG, whole or not at all (a kill or a full disk keeps the old one)."""
    try:
        if layout:
            fig.tight_layout()
        files.replace_atomically(path, lambda tmp: fig.savefig(tmp, dpi=110, format="png"), ReportError)
    finally:
        plt.close(fig)
    return path


def _scene(frame: pd.DataFrame) -> str:
    """The scene the rows share, for titles (only the values that are common)."""
    parts = []
    for col, fmt in (("n", "n = {:.0f}"), ("L", "L = {:g} a"), ("nu", "nu = {:g}")):
        values = frame[col].dropna().unique()
        if len(values) == 1:
            parts.append(fmt.format(values[0]))
    return ", ".join(parts)


def pareto(frame: pd.DataFrame, x: str, y: str) -> pd.DataFrame:
    """Rows no other row beats in both x and y (smaller is better)."""
    ordered = frame.sort_values([x, y])
    front, best = [], math.inf
    for idx, row in ordered.iterrows():
        if row[y] < best:
            front.append(idx)
            best = row[y]
    return ordered.loc[front]


def accuracy_vs_speed(tables: dict, path: Path) -> Path:
    """Left: the error against Hertz; right: the same cases by their own estimate."""
    rows = need(sphere_cases(tables), "no converged sphere case")
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(16, 5.8), sharey=True)
    _accuracy_panel(ax, rows, "max_err", "max |relative error| of p0, F, a against Hertz (stars: Sneddon) [%]",
                    f"Accuracy against speed: {len(rows)} converged sphere cases (open: solved in 3D)")
    # the other indenters against Sneddon, at the same kind of cost (not on the front)
    shapes_rows = tables.get("shapes")
    if shapes_rows is not None and len(shapes_rows) and "shape" in shapes_rows:
        other = shapes_rows[(shapes_rows["status"] == "converged") & (shapes_rows["shape"] != "parabola")].copy()
        other["label"] = other.apply(shape_label, axis=1) if len(other) else []
        for name, g in other.groupby("label"):
            err = g[["err_p0", "err_F", "err_a", "err_K"]].abs().max(axis=1, skipna=True)
            ax.scatter(g["wall_time"], err * 100, marker="*", s=60, color=SHAPE_COLORS.get(name, "grey"),
                       label=f"{name} against Sneddon ({len(g)})")
        ax.legend(fontsize=7, loc="upper right")
    estimated = rows.assign(max_est=rows["accuracy_predicted"])
    _accuracy_panel(ax2, estimated[estimated["max_est"] > 0], "max_est",
                    "estimated max relative error (no Hertz) [%]", "The same cases by their own error estimate")
    ax2.yaxis.set_tick_params(labelleft=True)
    return _save(fig, path)


def _accuracy_panel(ax, rows: pd.DataFrame, column: str, ylabel: str, title: str) -> None:
    rows = rows.assign(max_err=rows[column])
    for (model, method, order), group in rows.groupby(["model", "method", "order"]):
        color, marker = METHOD_STYLE.get((method, int(order)), ("k", "x"))
        solid = model == "axi"  # 3D spheres: open markers
        ax.scatter(group["wall_time"], group["max_err"] * 100, marker=marker, s=26 if solid else 44,
                   alpha=0.75, color=color if solid else "none", edgecolors=color,
                   label=f"{method} P{int(order)}{'' if solid else ', 3d'} ({len(group)})")
    front = pareto(rows, "wall_time", "max_err")
    ax.plot(front["wall_time"], front["max_err"] * 100, "k-", lw=1, label="Pareto front")
    last = None
    for _, row in front.iterrows():
        point = (row["wall_time"], row["max_err"] * 100)
        # label points that stand apart (a label is ~0.8 wide in ln x at this size)
        if last is not None and abs(math.log(point[0] / last[0])) < 0.9 \
                and abs(math.log(point[1] / last[1])) < 0.6:
            continue
        ax.annotate(f"{row['method']} P{int(row['order'])} n={int(row['n'])}"
                    + ("" if row["model"] == "axi" else " 3d"), point,
                    fontsize=7, xytext=(5, 2), textcoords="offset points")
        last = point
    ax.set(xscale="log", yscale="log", xlabel="wall time per case [s] (whole FreeFEM process)",
           ylabel=ylabel, title=title)
    for level in (1, 0.1):
        ax.axhline(level, color="grey", ls=":", lw=0.8)
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=7, loc="upper right")


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
           title=f"Penalty error against kpen ({_scene(frame)})")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, loc="lower left")
    ax2.set(xscale="log", xlabel="penalty kpen (absolute) [force/length^3]",
            ylabel="iterations, all levels", title="Newton / active-set iterations (all levels)")
    ax2.grid(True, alpha=0.3)
    ax2.legend(fontsize=7)
    return _save(fig, path)


def _fit_range(h: np.ndarray, err: np.ndarray) -> slice:
    """The points before the error stops falling (a floor: penalty, domain or
    rounding): from the coarsest while each refinement still cuts the error by
    more than a third of the element-size ratio."""
    end = 1
    while end < len(h) and err[end] > 0 and err[end - 1] / err[end] > (h[end - 1] / h[end]) ** (1 / 3):
        end += 1
    return slice(0, end)


def mesh_study(frame: pd.DataFrame, path: Path) -> Path:
    df = need(frame[frame["status"].isin(["converged", "inaccurate"])], "no converged or inaccurate mesh rows").copy()
    df["series"] = df["variant"].str.replace(r" P\d$", "", regex=True)
    series = sorted(df["series"].unique())
    fig, axes = plt.subplots(1, len(series), figsize=(5.2 * len(series), 4.8), sharey=True, squeeze=False)
    for ax, name in zip(axes[0], series):
        part = df[df["series"] == name]
        for order, ls in ((1, "--"), (2, "-")):
            g = part[part["order"] == order].sort_values("n")
            if not len(g):
                continue
            h = 1.0 / g["n"].to_numpy()
            for (col, qname), color in zip(ERRORS.items(), QUANTITY_COLORS):
                err = g[col].abs().to_numpy()
                fit = _fit_range(h, err)
                n_fit = g["n"].to_numpy()[fit]
                if fit.stop >= 2:
                    rate = np.polyfit(np.log(h[fit]), np.log(err[fit]), 1)[0]
                    label = f"{qname} P{order}: slope {rate:.2f} (n {n_fit[0]:.0f}-{n_fit[-1]:.0f})"
                else:
                    label = f"{qname} P{order}: at its floor"
                ax.plot(h, err * 100, ls, color=color, marker="o", ms=3, label=label)
        ax.set(xscale="log", yscale="log", xlabel="element size h / a at the contact", title=name)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=6.5)
    axes[0][0].set_ylabel("|relative error| against Hertz [%]")
    fig.suptitle("Mesh convergence (sphere): slopes fitted before each curve meets its floor")
    return _save(fig, path)


def _grid(ax, frame: pd.DataFrame, xcol: str, ycol: str, text) -> None:
    xs = sorted(frame[xcol].unique())
    ys = list(dict.fromkeys(frame.sort_values(ycol)[ycol]))
    for _, row in frame.iterrows():
        i, j = xs.index(row[xcol]), ys.index(row[ycol])
        ax.add_patch(plt.Rectangle((i - 0.5, j - 0.5), 1, 1, facecolor=STATUS_COLORS.get(row["status"], "white"),
                                   hatch=STATUS_HATCHES.get(row["status"], ""), edgecolor=CELL_EDGE, lw=0.3))
        ax.text(i, j, text(row), ha="center", va="center", fontsize=6.5,
                bbox={"boxstyle": "round,pad=0.15", "facecolor": (1, 1, 1, 0.75), "edgecolor": "none"})
    ax.set_xticks(range(len(xs)), [_tick(x) for x in xs], rotation=45, fontsize=7)
    ax.set_yticks(range(len(ys)), [str(y) for y in ys], fontsize=7)
    ax.set_xlim(-0.5, len(xs) - 0.5)
    ax.set_ylim(-0.5, len(ys) - 0.5)


def _tick(value) -> str:
    if isinstance(value, (int, float, np.number)):
        return f"{value:.0e}" if value >= 1e4 or value < 1e-1 else f"{value:g}"
    return str(value)


def stability_map(frame: pd.DataFrame, path: Path) -> Path:
    need(frame, "no stability rows")
    fig, axes = plt.subplots(1, 3, figsize=(19, 6.5), gridspec_kw={"width_ratios": [1, 1.15, 0.9]})
    fp = frame[frame["method"] == "fixedpoint"]
    n_map = fp["n"].mode().iloc[0] if len(fp) else 16
    fp = fp[fp["n"] == n_map]
    _grid(axes[0], fp, "kpen", "omega", lambda r: f"{r['iterations']:.0f}")
    if len(fp):
        kcrit = fp.groupby("omega")["kpen_critical"].first()
        kpens = sorted(fp["kpen"].unique())
        omegas = sorted(fp["omega"].unique())
        xs = np.interp(np.log10(kcrit.values), np.log10(kpens), np.arange(len(kpens)))
        axes[0].plot(xs, [omegas.index(w) for w in kcrit.index], "k--", lw=2,
                     label="theory: kpen = (2/omega - 1)/mu")
        axes[0].legend(fontsize=7, loc="upper right")
    axes[0].set(title=f"Fixed point (P2, n = {n_map:.0f}): iterations in cells", xlabel="kpen (absolute)",
                ylabel="relaxation omega")
    newton = frame[(frame["method"] == "newton")]
    _grid(axes[1], newton, "gamma", "variant",
          lambda r: f"{r['iterations'] + r['coarse_iterations']:.0f}")
    axes[1].set(title="Newton from each start: iterations (all levels) in cells",
                xlabel="penalty gamma = kpen h / E*", ylabel="")
    exact = frame[frame["method"].isin(["lagrange", "uzawa"])]
    _grid(axes[2], exact, "gamma", "variant",
          lambda r: f"{r['iterations'] + r['coarse_iterations']:.0f}")
    axes[2].set(title="Exact methods: iterations (all levels)", xlabel="augmentation c = gamma E*/h",
                ylabel="")
    handles = [plt.Rectangle((0, 0), 1, 1, facecolor=STATUS_COLORS[s], hatch=STATUS_HATCHES[s], edgecolor=CELL_EDGE)
               for s in STATUS_COLORS]
    fig.legend(handles, STATUS_COLORS.keys(), loc="lower center", ncol=len(STATUS_COLORS), fontsize=8)
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    return _save(fig, path, layout=False)


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
    return _save(fig, path)


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
    return _save(fig, path)


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
    return _save(fig, path)


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
    return _save(fig, path)


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
           title=f"Finite-domain bias ({df['method'].iloc[0]}, {_scene(df)})")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    return _save(fig, path)


def units_check(frame: pd.DataFrame, path: Path) -> Path:
    df = need(frame, "no units rows").copy()
    df["scene"] = df["variant"].str.rsplit(", ", n=1).str[0]
    df["units"] = df["variant"].str.rsplit(", ", n=1).str[1]
    scenes = list(dict.fromkeys(df["scene"]))
    units = list(dict.fromkeys(df["units"]))
    fig, ax = plt.subplots(figsize=(max(8, 1.6 * len(scenes)), 5))
    width = 0.8 / len(units)
    for k, unit in enumerate(units):
        part = df[df["units"] == unit].set_index("scene").reindex(scenes)
        ax.bar(np.arange(len(scenes)) + k * width, max_error(part) * 100, width,
               label=f"{unit} (E = {part['E'].iloc[0]:g} ...)")
    spread = df.groupby("scene")[list(ERRORS)].agg(lambda s: s.max() - s.min()).abs().max(axis=1)
    ax.set_xticks(np.arange(len(scenes)) + 0.4 - width / 2,
                  [f"{s}\nspread {spread[s]:.1e}" for s in scenes], fontsize=7)
    ax.set(ylabel="max |relative error| of p0, F, a [%]",
           title="One dimensionless scene in three unit systems (spread: largest difference of any error)")
    ax.grid(True, axis="y", alpha=0.3)
    ax.legend(fontsize=7)
    return _save(fig, path)


def matched_accuracy(frame: pd.DataFrame) -> pd.DataFrame:
    """For each converged 3D sphere case, the cheapest converged axisymmetric case
    of the same method at least as accurate (against Hertz): the price of
    over-modelling as ratios of wall time, memory and dofs."""
    rows = frame[frame["status"] == "converged"].assign(max_err=max_error(frame))
    axi = rows[rows["model"] == "axi"]
    full = rows[(rows["model"] == "3d") & (rows["Rx"] == rows["Ry"])]
    pairs = []
    for _, row in full.iterrows():
        match = axi[(axi["method"] == row["method"]) & (axi["max_err"] <= row["max_err"])]
        if len(match):
            best = match.loc[match["wall_time"].idxmin()]
            pairs.append({"method": row["method"], "n_3d": row["n"], "n_axi": best["n"],
                          "err_3d": row["max_err"], "err_axi": best["max_err"],
                          "time_3d": row["wall_time"], "time_axi": best["wall_time"],
                          "memory_3d": row["memory_mb"], "memory_axi": best["memory_mb"],
                          "ndof_3d": row["ndof"], "ndof_axi": best["ndof"]})
    return pd.DataFrame(pairs)


def over_modelling(frame: pd.DataFrame, path: Path) -> Path:
    rows = frame[frame["status"].isin(["converged", "inaccurate"])].assign(max_err=max_error(frame))
    spheres = need(rows[rows["Rx"] == rows["Ry"]], "no converged or inaccurate sphere rows in 3d")
    fig, axes = plt.subplots(1, 3, figsize=(16, 5))
    columns = (("wall_time", "wall time per case [s]"), ("memory_mb", "peak memory [MB]"),
               ("ndof", "degrees of freedom"))
    for ax, (col, label) in zip(axes, columns):
        for (model, method, order), g in spheres.groupby(["model", "method", "order"]):
            g = g.sort_values("n")
            color, marker = METHOD_STYLE.get((method, int(order)), ("k", "x"))
            ax.plot(g[col], g["max_err"] * 100, "-" if model == "axi" else "--", color=color, marker=marker,
                    mfc=color if model == "axi" else "none", label=f"{model} {method} P{int(order)}")
            for _, r in g.iterrows():
                ax.annotate(f"n={r['n']:.0f}", (r[col], r["max_err"] * 100), fontsize=6,
                            xytext=(3, 3), textcoords="offset points")
        ax.axhline(1, color="grey", ls=":", lw=0.8)
        ax.set(xscale="log", yscale="log", xlabel=label)
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())  # decades only: no crowding
        ax.grid(True, alpha=0.3)
    axes[0].set_ylabel("max |relative error| of p0, F, a (and b in 3D) against Hertz [%]")
    axes[0].legend(fontsize=7)
    pairs = matched_accuracy(frame)
    if len(pairs):
        p = pairs.sort_values("err_3d").iloc[0]
        fig.suptitle(f"The price of over-modelling a sphere: at {p['err_3d']:.2%} ({p['method']}), 3D n = "
                     f"{p['n_3d']:.0f} costs {p['time_3d'] / p['time_axi']:.0f}x the time, "
                     f"{p['memory_3d'] / p['memory_axi']:.0f}x the memory and "
                     f"{p['ndof_3d'] / p['ndof_axi']:.0f}x the dofs of axi n = {p['n_axi']:.0f}")
    else:
        fig.suptitle("The price of over-modelling a sphere: axi (solid) against 3d (dashed)")
    return _save(fig, path)


def ellipses(frame: pd.DataFrame, outline: pd.DataFrame, profile: pd.DataFrame, profile_y: pd.DataFrame,
             path: Path) -> Path:
    """Contact outlines against Hertz's ellipses, and the pressure along both axes."""
    rows = frame[(frame["model"] == "3d") & (frame["method"] == "newton") & (frame["order"] == 2)
                 & frame["status"].isin(["converged", "inaccurate"])]
    need(rows, "no converged or inaccurate 3d newton P2 rows")
    need(outline, "no kept outline.csv of 3d")
    finest = rows.loc[rows.groupby(["Rx", "Ry"])["n"].idxmax()].sort_values(["Ry", "Rx"])
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(13.5, 5.6))
    colors = ("#1565c0", "#c62828", "#2e7d32", "#6a1b9a", "#ef6c00")
    for (_, case), color in zip(finest.iterrows(), colors):
        line = outline[outline["case_id"] == case["case_id"]]
        name = f"Rx = {case['Rx']:g}, Ry = {case['Ry']:g}, n = {case['n']:.0f}"
        ax.plot(line["x"], line["y"], "o", color=color, ms=3.5, label=f"FE edge, {name}")
        ax.plot(line["x_hertz"], line["y_hertz"], "-", color=color, lw=1)
    ax.plot([], [], "k-", lw=1, label="Hertz ellipse")
    ax.set(xlabel="x [length]", ylabel="y [length]", aspect="equal",
           title="Contact outline (a quarter; d = {:g})".format(finest["d"].iloc[0]) if len(finest) else "")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    longest = finest.loc[(finest["Ry"] / finest["Rx"]).idxmax()] if len(finest) else None
    if longest is not None:
        for data, edge, label, ls in ((profile, longest["a_hertz"], "x", "-"),
                                      (profile_y, longest["b_hertz"], "y", "--")):
            prof = data[data["case_id"] == longest["case_id"]]
            ax2.plot(prof["r"] / edge, prof["p_fe"] / longest["p0_hertz"], ls, color="#1565c0",
                     label=f"FE along {label} (semi-axis {edge:.4g})")
            ax2.plot(prof["r"] / edge, prof["p_hertz"] / longest["p0_hertz"], ls, color="k", lw=0.9,
                     label=f"Hertz along {label}")
        ax2.set(xlabel="distance / Hertz semi-axis of that direction", ylabel="p / p0 (Hertz)", xlim=(0, 1.6),
                title=f"Pressure along both axes: Rx = {longest['Rx']:g}, Ry = {longest['Ry']:g}, "
                      f"n = {longest['n']:.0f}, p0 error {longest['err_p0']:+.2%}")
        ax2.grid(True, alpha=0.3)
        ax2.legend(fontsize=7)
    fig.suptitle("Ellipsoids in 3D against elliptical Hertz")
    return _save(fig, path)


# the estimate's target: from half to three times the true error
EFFECTIVITY_BAND = (0.5, 3.0)


def calibration(frame: pd.DataFrame, path: Path) -> Path:
    """The estimate against the truth (closed forms), its effectivity, and
    -accuracy's achieved error against its target."""
    df = need(frame[frame["status"].isin(["converged", "inaccurate"])],
              "no converged or inaccurate calibration rows").copy()
    df["true"] = max_error(df)
    df["est"] = df["accuracy_predicted"]
    df["group"] = df["variant"].where(~df["variant"].str.startswith("accuracy"), "-accuracy")
    fig, axes = plt.subplots(1, 3, figsize=(18, 5.6))
    colors = dict(zip(sorted(df["group"].unique()), [plt.get_cmap("tab10")(k) for k in range(10)]))
    for group, g in df.groupby("group"):
        axes[0].scatter(g["true"] * 100, g["est"] * 100, s=22, color=colors[group], label=group)
        axes[1].scatter(g["true"] * 100, g["est"] / g["true"], s=22, color=colors[group], label=group)
    lim = np.array([1e-4, 30.0])
    axes[0].plot(lim, lim, "k-", lw=1, label="estimate = truth")
    low, high = EFFECTIVITY_BAND
    axes[0].fill_between(lim, lim * low, lim * high, color="grey", alpha=0.15, label=f"truth x {low:g} to {high:g}")
    axes[0].set(xscale="log", yscale="log", xlabel="true max |error| of p0, F, a (and b) [%]",
                ylabel="estimated max error (no Hertz) [%]", title="Estimate against truth")
    axes[1].axhspan(low, high, color="grey", alpha=0.15, label=f"target band {low:g} to {high:g}")
    axes[1].axhline(1, color="k", lw=1)
    axes[1].set(xscale="log", yscale="log", xlabel="true max |error| [%]",
                ylabel="effectivity = estimate / truth", title="Effectivity")
    axes[1].yaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
    axes[1].yaxis.set_minor_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
    acc = df[df["group"] == "-accuracy"]
    for status, g in acc.groupby("status"):
        axes[2].scatter(g["accuracy_target"] * 100, g["true"] * 100, s=28,
                        color=STATUS_COLORS.get(status, "k"), label=f"achieved ({status})", zorder=3)
        axes[2].scatter(g["accuracy_target"] * 100, g["est"] * 100, s=28, marker="x",
                        color=STATUS_COLORS.get(status, "k"), label=f"estimated ({status})", zorder=3)
    targets = np.array([0.8, 1.25]) * [acc["accuracy_target"].min() * 100, acc["accuracy_target"].max() * 100] \
        if len(acc) else np.array([0.08, 6.0])
    axes[2].plot(targets, targets, "k-", lw=1, label="error = target")
    axes[2].set(xscale="log", yscale="log", xlabel="-accuracy target X [%]", ylabel="max error [%]",
                title="-accuracy X: achieved (truth) and estimated error")
    for ax in axes:
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle(f"Error estimate calibration: {len(df)} cases with closed forms ({_scene(df) or 'many scenes'})")
    return _save(fig, path)


MODEL_TITLES = {"axi": "axisymmetric", "plane": "plane strain", "3d": "3D"}


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
    return _save(fig, path, layout=False)


SHAPE_COLORS = {"cone 70.3": "#c62828", "cone 60": "#ef9a9a", "punch": "#6a1b9a", "power k = 3": "#2e7d32",
                "power k = 1.5": "#a5d6a7", "sphere": "#1565c0"}


def shape_label(row: pd.Series) -> str:
    """A shape as the charts name it: cone 70.3, power k = 3, punch, sphere, parabola."""
    if row["shape"] == "cone":
        return f"cone {row['angle']:g}"
    if row["shape"] == "power":
        return f"power k = {row['k']:g}"
    return str(row["shape"])


def shapes(frame: pd.DataFrame, profiles: pd.DataFrame, path: Path) -> Path:
    """Left: the exact sphere against Hertz's parabola of the same radius over d/R. Middle:
    F against d for each shape (markers FE, lines Sneddon). Right: each shape's error against
    n (exact contact). Rows are chosen by their columns (a case shared by two series is one row)."""
    df = need(frame[frame["status"].isin(["converged", "inaccurate"])], "no shapes rows").copy()
    df["label"] = df.apply(shape_label, axis=1)
    default = df[(df["method"] == "newton") & (df["n"] == 16)]
    sph = need(default[default["label"] == "sphere"], "no sphere rows").set_index("d").sort_index()
    par = need(default[default["label"] == "parabola"], "no parabola rows").set_index("d").sort_index()
    common = sph.index.intersection(par.index)
    ratio = common / sph.loc[common, "R"]
    fig, axes2 = plt.subplots(2, 2, figsize=(13, 10))
    axes = axes2.ravel()
    ax = axes[0]
    for q, color in (("F", QUANTITY_COLORS[1]), ("a", QUANTITY_COLORS[2])):
        ax.plot(ratio, (sph.loc[common, f"{q}_fe"] / par.loc[common, f"{q}_fe"] - 1) * 100, "o", color=color,
                label=f"{q}: FE sphere / FE parabola - 1")
        ax.plot(ratio, (sph.loc[common, f"{q}_hertz"] / par.loc[common, f"{q}_hertz"] - 1) * 100, "-", color=color,
                lw=1, label=f"{q}: Sneddon's sphere / Hertz - 1")
    x = np.linspace(0, ratio.max(), 50)
    ax.plot(x, -x / 10 * 100, "k:", lw=1, label="-(d/R)/10, -(d/R)/6 (first order)")
    ax.plot(x, -x / 6 * 100, "k:", lw=1)
    ax.set(xlabel="depth d / R", ylabel="sphere against parabola [%]",
           title="The exact sphere against Hertz's parabola (same R, same d)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    ax = axes[1]
    for name, g in default[default["label"] != "parabola"].groupby("label"):
        g = g.sort_values("d")
        if len(g) < 3:
            continue
        color = SHAPE_COLORS.get(name, "grey")
        ax.plot(g["d"], g["F_hertz"], "-", color=color, lw=1)
        slope = np.polyfit(np.log(g["d"]), np.log(g["F_fe"]), 1)[0]
        ax.plot(g["d"], g["F_fe"], "o", color=color, label=f"{name}: slope {slope:.3f}")
    ax.plot([], [], "k-", lw=1, label="Sneddon (lines)")
    ax.set(xscale="log", yscale="log", xlabel="depth d", ylabel="force F",
           title="F(d): cone 2, punch 1, power k: 1 + 1/k, sphere 1.5 (small d)")
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    ax = axes[2]
    errors = {"F": "err_F", "a": "err_a", "K": "err_K", "p0": "err_p0"}
    for name, g in df[df["method"] == "lagrange"].groupby("label"):
        g = g.sort_values("n")
        cols = [c for c in errors.values() if g[c].notna().any()]
        ax.plot(g["n"], g[cols].abs().max(axis=1) * 100, "o-", color=SHAPE_COLORS.get(name, "grey"),
                label=f"{name} ({', '.join(k for k, c in errors.items() if c in cols)})")
    ax.set(xscale="log", yscale="log", xlabel="elements per contact radius n",
           ylabel="max |relative error| against Sneddon [%]",
           title="Convergence (lagrange P2; a cone at any angle is one problem)")
    ns = sorted(df.loc[df["method"] == "lagrange", "n"].unique())
    ax.set_xticks(ns, [f"{n:g}" for n in ns])
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.grid(True, which="both", alpha=0.3)
    if ax.get_legend_handles_labels()[0]:  # a study without lagrange rows draws none
        ax.legend(fontsize=7)
    ax = axes[3]
    at = default[(default["d"] == 0.02) & (default["label"] != "parabola")]
    for _, row in at.iterrows():
        prof = profiles[profiles["case_id"] == row["case_id"]] if len(profiles) else profiles
        if not len(prof):
            continue
        a = row["a_fe"]
        scale = row["F_fe"] / (np.pi * a * a)  # the mean pressure
        color = SHAPE_COLORS.get(row["label"], "grey")
        inside = prof[prof["r"] < 0.995 * a]
        ax.plot(prof["r"] / a, prof["p_fe"] / scale, "-", color=color, label=f"{row['label']} (FE)")
        ax.plot(inside["r"] / a, inside["p_hertz"] / scale, "k:", lw=1)
    ax.plot([], [], "k:", lw=1, label="Sneddon")
    ax.set(xlim=(0, 1.3), ylim=(0, 4), xlabel="r / a", ylabel="p / mean pressure F/(pi a^2)",
           title="Pressure at d = 0.02 (cone: log tip; punch: 1/sqrt edge)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    return _save(fig, path)


def _layered_reference():
    """tests/layered_reference.py (Perriot and Barthel's integral equation), when the
    package runs from a checkout; None otherwise (the chart then draws the limits alone)."""
    path = layout.TESTS_DIR / "layered_reference.py"
    if not path.is_file():
        return None
    import importlib.util
    spec = importlib.util.spec_from_file_location("layered_reference", path)
    if spec is None or spec.loader is None:
        return None
    module = importlib.util.module_from_spec(spec)
    sys.modules.setdefault("layered_reference", module)  # its dataclasses look their module up
    spec.loader.exec_module(module)
    return module


def layers(frame: pd.DataFrame, profiles: pd.DataFrame, axis: pd.DataFrame, path: Path) -> Path:
    """The coated body: effective modulus over a/t, the half-spaces' under-modelling, the
    pressure profiles and the stresses on the axis of a soft and a stiff film."""
    df = need(frame[frame["status"].isin(["converged", "inaccurate"])], "no layers rows").copy()
    estar1 = df["E"] / (1 - df["nu"] ** 2)
    df["E_eff"] = df["S_fe"] / (2 * df["a_fe"]) / estar1
    df["a_over_t"] = df["a_fe"] / df["t"]
    reference = _layered_reference()
    fig, axes = plt.subplots(2, 2, figsize=(13, 10))
    series = [v for v in dict.fromkeys(df["variant"]) if not v.startswith("profile")]
    colors = dict(zip(series, ["#0d47a1", "#42a5f5", "#ef6c00", "#b71c1c", "#212121"]))
    ax = axes[0, 0]
    for variant in series:
        g = df[df["variant"] == variant].sort_values("a_over_t")
        color = colors[variant]
        ax.plot(g["a_over_t"], g["E_eff"], "o", color=color, label=f"{variant} (FE)")
        row = g.iloc[0]
        if reference is not None:
            coating = reference.Coating(E1=row["E"], nu1=row["nu"], t=1.0, E2=row["E2"],
                                        nu2=row["nu2"] if np.isfinite(row["nu2"]) else 0.3)
            x = np.logspace(np.log10(g["a_over_t"].min()) - 0.2, np.log10(g["a_over_t"].max()) + 0.2, 25)
            ax.plot(x, [reference.effective_modulus(coating, ax_) / estar1.iloc[0] for ax_ in x], "-",
                    color=color, lw=1)
        if variant != "rigid base":
            ax.axhline(row["E2"] / (1 - row["nu2"] ** 2) / estar1.iloc[0], color=color, lw=0.8, ls="--")
    ax.axhline(1, color="grey", lw=0.8, ls="--")
    ax.plot([], [], "k--", lw=0.8, label="half-space limits: film (1), substrate (E2*/E*)")
    if reference is not None:
        ax.plot([], [], "k-", lw=1, label="Perriot & Barthel (2004) integral equation (tests/layered_reference.py)")
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
    return _save(fig, path)


def loading(frame: pd.DataFrame, path: Path) -> Path:
    """Loading curves: F(d) with Hertz's lines, S(a) with S = 2E*a, the cylinder's a(P)."""
    df = need(frame[frame["status"] == "converged"], "no loading rows")
    fig, axes = plt.subplots(1, 3, figsize=(16, 5.2))
    styles = {"sphere": ("#1565c0", "o"), "exact sphere": ("#6a1b9a", "s"), "ellipsoid Ry/Rx = 2": ("#2e7d32", "D")}
    for variant, (color, marker) in styles.items():
        g = df[df["variant"] == variant].sort_values("d_fe")
        if not len(g):
            continue
        hollow = dict(mfc="none", ms=10, mew=1.5) if variant == "sphere" else {}
        axes[0].plot(g["d_fe"], g["F_fe"], marker, color=color, label=f"{variant}, loading (-d)", **hollow)
        axes[0].plot(g["d_fe"], g["F_hertz"], "-", color=color, lw=1)
        axes[1].plot(g["a_fe"], g["S_fe"], marker, color=color, label=f"{variant}: dF/dd from the linearization",
                     **hollow)
        axes[1].plot(g["a_fe"], g["S_hertz"], "-", color=color, lw=1)
    under = df[df["variant"] == "sphere under load"]
    axes[0].plot(under["d_fe"], under["F_fe"], "x", color="k", ms=10, mew=2,
                 label="sphere under load (-P): the same curve")
    axes[0].plot([], [], "-", color="grey", lw=1, label="lines: Hertz (the exact sphere: Sneddon), each series' colour")
    axes[0].set(xscale="log", yscale="log", xlabel="depth d", ylabel="force F", title="F(d): slope 3/2")
    axes[1].plot([], [], "-", color="grey", lw=1, label="lines: 2 E* a (ellipsoid: 3F/2d), each series' colour")
    axes[1].set(xscale="log", yscale="log", xlabel="contact radius a (ellipsoid: along x)",
                ylabel="contact stiffness S = dF/dd", title="Contact stiffness")
    cyl = df[df["variant"] == "cylinder"].sort_values("F_fe")
    if len(cyl):
        axes[2].plot(cyl["F_fe"], cyl["a_fe"], "o", color="#c62828", label="cylinder half-width a (FE)")
        axes[2].plot(cyl["F_fe"], cyl["a_hertz"], "-", color="#c62828", lw=1, label="sqrt(4PR/(pi E*))")
        axes[2].plot(cyl["F_fe"], cyl["p0_fe"], "s", color="#ef6c00", label="cylinder p0 (FE)")
        axes[2].plot(cyl["F_fe"], cyl["p0_hertz"], "-", color="#ef6c00", lw=1, label="2P/(pi a)")
    axes[2].set(xscale="log", yscale="log", xlabel="load per unit length P",
                ylabel="half-width a (length), p0 (stress), the scene's units",
                title="The cylinder, by its load (-P)")
    for ax in axes:
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    return _save(fig, path)
