"""Charts from the study tables (PNG, matplotlib). Reads CSV files only.

Series are chosen by the `variant` column the studies write, and titles take
their facts (mesh, penalty, scene) from the rows they draw.
"""
from __future__ import annotations

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

ERRORS = {"err_p0": "p0", "err_F": "F", "err_a": "a"}
QUANTITY_COLORS = ("#1565c0", "#c62828", "#2e7d32")
STATUS_COLORS = {"converged": "#4caf50", "inaccurate": "#c0ca33", "roundoff": "#26c6da",
                 "stalled": "#ff7043", "maxiter": "#ffb300", "diverged": "#e53935",
                 "nan": "#8e24aa", "timeout": "#757575", "failed": "#212121"}
METHOD_STYLE = {("newton", 2): ("#1565c0", "o"), ("newton", 1): ("#64b5f6", "s"),
                ("lagrange", 2): ("#2e7d32", "D"), ("lagrange", 1): ("#a5d6a7", "d"),
                ("uzawa", 2): ("#6a1b9a", "P"), ("uzawa", 1): ("#ce93d8", "p"),
                ("fixedpoint", 2): ("#c62828", "^"), ("fixedpoint", 1): ("#ef9a9a", "v")}


def max_error(frame: pd.DataFrame) -> pd.Series:
    return frame[list(ERRORS)].abs().max(axis=1, skipna=True)


def sphere_cases(tables: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Converged sphere cases of every study, once each (the same case in two
    studies is one point), with their max |error|."""
    frames = [t for name, t in tables.items() if len(t) and name != "figures"]
    rows = pd.concat(frames, ignore_index=True)
    rows = rows[(rows["status"] == "converged") & (rows["model"] == "axi")].drop_duplicates("case_id")
    return rows.assign(max_err=max_error(rows))


def _save(fig, path: Path) -> Path:
    fig.tight_layout()
    fig.savefig(path, dpi=110)
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
    rows = sphere_cases(tables)
    fig, ax = plt.subplots(figsize=(8.5, 5.8))
    for (method, order), group in rows.groupby(["method", "order"]):
        color, marker = METHOD_STYLE.get((method, int(order)), ("k", "x"))
        ax.scatter(group["wall_time"], group["max_err"] * 100, marker=marker, s=26, alpha=0.75,
                   color=color, label=f"{method} P{int(order)} ({len(group)})")
    front = pareto(rows, "wall_time", "max_err")
    ax.plot(front["wall_time"], front["max_err"] * 100, "k-", lw=1, label="Pareto front")
    last = None
    for _, row in front.iterrows():
        point = (row["wall_time"], row["max_err"] * 100)
        # label points that stand apart (a label is ~0.8 wide in ln x at this size)
        if last is not None and abs(math.log(point[0] / last[0])) < 0.9 \
                and abs(math.log(point[1] / last[1])) < 0.6:
            continue
        ax.annotate(f"{row['method']} P{int(row['order'])} n={int(row['n'])}", point,
                    fontsize=7, xytext=(5, 2), textcoords="offset points")
        last = point
    ax.set(xscale="log", yscale="log", xlabel="wall time per case [s] (whole FreeFEM process)",
           ylabel="max |relative error| of p0, F, a against Hertz [%]",
           title=f"Accuracy against speed: {len(rows)} converged sphere cases")
    for level in (1, 0.1):
        ax.axhline(level, color="grey", ls=":", lw=0.8)
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=7, loc="upper right")
    return _save(fig, path)


def penalty_study(frame: pd.DataFrame, path: Path) -> Path:
    df = frame[frame["status"].isin(["converged", "inaccurate"])]
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
    df = frame[frame["status"].isin(["converged", "inaccurate"])].copy()
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
        ax.add_patch(plt.Rectangle((i - 0.5, j - 0.5), 1, 1,
                                   color=STATUS_COLORS.get(row["status"], "white"), alpha=0.85))
        ax.text(i, j, text(row), ha="center", va="center", fontsize=6.5)
    ax.set_xticks(range(len(xs)), [_tick(x) for x in xs], rotation=45, fontsize=7)
    ax.set_yticks(range(len(ys)), [str(y) for y in ys], fontsize=7)
    ax.set_xlim(-0.5, len(xs) - 0.5)
    ax.set_ylim(-0.5, len(ys) - 0.5)


def _tick(value) -> str:
    if isinstance(value, (int, float, np.number)):
        return f"{value:.0e}" if value >= 1e4 or value < 1e-1 else f"{value:g}"
    return str(value)


def stability_map(frame: pd.DataFrame, path: Path) -> Path:
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
    handles = [plt.Rectangle((0, 0), 1, 1, color=c) for c in STATUS_COLORS.values()]
    fig.legend(handles, STATUS_COLORS.keys(), loc="lower center", ncol=len(STATUS_COLORS), fontsize=8)
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def pressure_profiles(figures: pd.DataFrame, profiles: pd.DataFrame, path: Path) -> Path:
    cases = figures[figures["variant"].str.startswith("profile")]
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
    fig.suptitle("Surface pressure against Hertz: the pointwise P1 penalty pressure zig-zags at high kpen")
    return _save(fig, path)


def zigzag(tables: dict, path: Path) -> Path:
    rows = pd.concat([t for name, t in tables.items() if len(t) and name != "figures"])
    rows = rows[(rows["status"] == "converged") & (rows["method"] == "newton")
                & (rows["model"] == "axi")].drop_duplicates("case_id")
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
    cases = figures[figures["variant"] == "seed figure"].sort_values("kpen")
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
    case = figures[figures["variant"] == "axis"].iloc[0]
    data = axis[axis["case_id"] == case["case_id"]]
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
    df = frame[frame["status"] == "converged"].sort_values("L")
    fig, ax = plt.subplots(figsize=(7, 5))
    ax.plot(df["L"], df["err_F"].abs() * 100, "o-", color=QUANTITY_COLORS[1], label="|F error| (measured)")
    ax.plot(df["L"], df["err_p0"].abs() * 100, "s--", color=QUANTITY_COLORS[0], label="|p0 error|")
    L = np.logspace(np.log10(df["L"].min()), np.log10(df["L"].max()), 50)
    ax.plot(L, 0.94 * 100 / L, "k:", label="0.94% x 100a / L (clamped far boundary)")
    ax.set(xscale="log", yscale="log", xlabel="domain radius L / a", ylabel="relative error [%]",
           title=f"Finite-domain bias ({df['method'].iloc[0]}, {_scene(df)})")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return _save(fig, path)


def units_check(frame: pd.DataFrame, path: Path) -> Path:
    df = frame.copy()
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
