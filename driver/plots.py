"""Charts from the study tables and the figure runs (PNG, matplotlib)."""
from __future__ import annotations

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from driver.figures import AXIS_CASE, PROFILE_CASES, SEED_FIGURE_CASES, load  # noqa: E402

ERRORS = {"err_p0": "p0", "err_F": "F", "err_a": "a"}
STATUS_COLORS = {"converged": "#4caf50", "maxiter": "#ffb300", "diverged": "#e53935",
                 "nan": "#8e24aa", "timeout": "#757575", "failed": "#212121"}
STYLE = {("newton", 2): ("#1565c0", "o"), ("newton", 1): ("#64b5f6", "s"),
         ("fixedpoint", 2): ("#c62828", "^"), ("fixedpoint", 1): ("#ef9a9a", "v"),
         ("auglag", 2): ("#2e7d32", "D"), ("auglag", 1): ("#a5d6a7", "d")}


def max_error(frame: pd.DataFrame) -> pd.Series:
    return frame[list(ERRORS)].abs().max(axis=1, skipna=True)


def sphere_cases(tables: dict) -> pd.DataFrame:
    """Converged sphere cases of every study, once each, with their max |error|."""
    rows = pd.concat(tables.values(), ignore_index=True)
    rows = rows[(rows["status"] == "converged") & (rows["model"] == "axi")].drop_duplicates("case_id")
    return rows.assign(max_err=max_error(rows))


def _save(fig, path: Path) -> Path:
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


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
    fig, ax = plt.subplots(figsize=(8, 5.5))
    # auglag with a stiff inner penalty closes the surface between nodes and
    # loses a surface element on a (README, auglag): drawn hollow
    stiff = (rows["method"] == "auglag") & (rows["kpen"] >= 1e7)
    for (method, order, hollow), group in rows.groupby(["method", "order", stiff]):
        color, marker = STYLE.get((method, order), ("k", "x"))
        label = f"{method} P{order}" + (", kpen ≥ 1e7" if hollow else "")
        ax.scatter(group["wall_time"], group["max_err"] * 100, marker=marker, s=28, alpha=0.75,
                   label=label, facecolors="none" if hollow else color,
                   edgecolors=color if hollow else "none")
    front = pareto(rows, "wall_time", "max_err")
    ax.plot(front["wall_time"], front["max_err"] * 100, "k-", lw=1, label="Pareto front")
    last = None
    for _, row in front.iterrows():
        point = (row["wall_time"], row["max_err"] * 100)
        # label points that stand apart (log distance; a label is ~0.8 wide in
        # ln x at this size), so labels do not overlap
        if last is not None and abs(math.log(point[0] / last[0])) < 0.9 \
                and abs(math.log(point[1] / last[1])) < 0.6:
            continue
        ax.annotate(f"{row['method']} P{row['order']} n={row['n']} k={row['kpen']:.1e}", point,
                    fontsize=7, xytext=(5, 2), textcoords="offset points")
        last = point
    ax.set(xscale="log", yscale="log", xlabel="wall time per case [s]",
           ylabel="max |relative error| of p0, F, a [%]",
           title="Accuracy against speed (sphere, every converged case)")
    ax.axhline(1, color="grey", ls=":", lw=0.8)
    ax.axhline(0.1, color="grey", ls=":", lw=0.8)
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=8, loc="upper right")
    return _save(fig, path)


def penalty_study(frame: pd.DataFrame, path: Path) -> Path:
    df = frame[(frame["method"] == "newton") & (frame["status"] == "converged")]
    fig, ax = plt.subplots(figsize=(8, 5.5))
    twin = ax.twinx()
    for order, ls in ((2, "-"), (1, "--")):
        g = df[df["order"] == order].sort_values("kpen")
        for (col, name), color in zip(ERRORS.items(), ("#1565c0", "#c62828", "#2e7d32")):
            ax.plot(g["kpen"], g[col].abs() * 100, ls, color=color, marker="o", ms=3,
                    label=f"|error {name}| P{order}")
        ax.plot(g["kpen"], g["penetration_over_d"] * 100, ls, color="k", marker="x", ms=4,
                label=f"max penetration / d, P{order}")
        twin.plot(g["kpen"], g["iterations"], ls, color="#ff8f00", drawstyle="steps-mid",
                  alpha=0.8, label=f"Newton iterations P{order}")
    ax.set(xscale="log", yscale="log", xlabel="penalty stiffness kpen [force/length^3]",
           ylabel="relative error, penetration / d [%]",
           title="Penalty study (sphere, n = 16, L = 5000 a)")
    twin.set_ylabel("Newton iterations (orange)")
    twin.set_ylim(0, max(12, df["iterations"].max() + 2))
    ax.grid(True, alpha=0.3)
    h1, l1 = ax.get_legend_handles_labels()
    h2, l2 = twin.get_legend_handles_labels()
    ax.legend(h1 + h2, l1 + l2, fontsize=7, loc="lower left", ncol=2)
    return _save(fig, path)


def mesh_study(frame: pd.DataFrame, path: Path) -> Path:
    df = frame[frame["status"] == "converged"]
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.8), sharey=True)
    for ax, (title, scaled) in zip(axes, (("kpen = 1e5 (fixed)", False),
                                          ("kpen = 100 E*/h (scaled)", True))):
        part = df[(df["kpen"] != 1e5) == scaled]
        for order, ls in ((1, "--"), (2, "-")):
            g = part[part["order"] == order].sort_values("n")
            h = 1.0 / g["n"]
            for (col, name), color in zip(ERRORS.items(), ("#1565c0", "#c62828", "#2e7d32")):
                err = g[col].abs()
                ok = err > 0
                rate = np.polyfit(np.log(h[ok]), np.log(err[ok]), 1)[0] if ok.sum() > 1 else np.nan
                ax.plot(h, err * 100, ls, color=color, marker="o", ms=3,
                        label=f"{name} P{order}: slope {rate:.2f}")
        ax.set(xscale="log", yscale="log", xlabel="element size h / a", title=title)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    axes[0].set_ylabel("|relative error| [%]")
    fig.suptitle("Mesh convergence (sphere): fitted log-log slopes in the legend")
    return _save(fig, path)


def stability_map(frame: pd.DataFrame, path: Path) -> Path:
    fig, axes = plt.subplots(1, 2, figsize=(13, 5), gridspec_kw={"width_ratios": [1.1, 1]})
    fp = frame[(frame["method"] == "fixedpoint") & (frame["n"] == 16)]
    _grid(axes[0], fp, "kpen", "omega", lambda r: f"{r['iterations']:.0f}")
    kcrit = fp.groupby("omega")["kpen_critical"].first()
    kpens = sorted(fp["kpen"].unique())
    omegas = sorted(fp["omega"].unique())
    # theory: kpen < (2/omega - 1)/mu, drawn in the grid's index coordinates
    xs = np.interp(np.log10(kcrit.values), np.log10(kpens), np.arange(len(kpens)))
    ys = [omegas.index(w) for w in kcrit.index]
    axes[0].plot(xs, ys, "k--", lw=2, label="theory: kpen = (2/omega - 1)/mu")
    axes[0].legend(fontsize=8, loc="upper right")
    axes[0].set(title="Fixed point (P2, n = 16): status, iterations in cells",
                xlabel="kpen", ylabel="relaxation omega")
    nt = frame[(frame["method"] == "newton") & (frame["n"] == 16)].copy()
    nt["variant"] = nt.apply(lambda r: f"P{r['order']} {'cont' if r['cont'] else 'no cont'}", axis=1)
    _grid(axes[1], nt, "kpen", "variant", lambda r: f"{r['iterations']:.0f}")
    axes[1].set(title="Newton (n = 16): status, iterations in cells", xlabel="kpen", ylabel="")
    handles = [plt.Rectangle((0, 0), 1, 1, color=c) for c in STATUS_COLORS.values()]
    fig.legend(handles, STATUS_COLORS.keys(), loc="lower center", ncol=6, fontsize=8)
    fig.subplots_adjust(bottom=0.2)
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def _grid(ax, frame, xcol, ycol, text):
    xs = sorted(frame[xcol].unique())
    ys = sorted(frame[ycol].unique())
    for _, row in frame.iterrows():
        i, j = xs.index(row[xcol]), ys.index(row[ycol])
        ax.add_patch(plt.Rectangle((i - 0.5, j - 0.5), 1, 1,
                                   color=STATUS_COLORS.get(row["status"], "white"), alpha=0.85))
        ax.text(i, j, text(row), ha="center", va="center", fontsize=7)
    ax.set_xticks(range(len(xs)), [_tick(x) for x in xs], rotation=45, fontsize=7)
    ax.set_yticks(range(len(ys)), [str(y) for y in ys], fontsize=8)
    ax.set_xlim(-0.5, len(xs) - 0.5)
    ax.set_ylim(-0.5, len(ys) - 0.5)


def _tick(value) -> str:
    if isinstance(value, (int, float, np.number)):
        return f"{value:.0e}" if value >= 1e4 else f"{value:g}"
    return str(value)


def pressure_profiles(runs: dict, path: Path) -> Path:
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8), sharey=True)
    for ax, order in zip(axes, (1, 2)):
        hertz_drawn = False
        for case, color in zip([c for c in PROFILE_CASES if c.order == order],
                               ("#1565c0", "#2e7d32", "#c62828")):
            prof = load(runs[case.case_id], "profile")
            a = case.contact_scale
            p0 = prof["p_hertz"].max()
            if not hertz_drawn:
                ax.plot(prof["r"] / a, prof["p_hertz"] / p0, "k-", lw=2, label="Hertz")
                hertz_drawn = True
            ax.plot(prof["r"] / a, prof["p_point"] / p0, ":", color=color, lw=1,
                    label=f"pointwise kpen<g>+, kpen={case.kpen:.0e}")
            ax.plot(prof["r"] / a, prof["p_fe"] / p0, "-", color=color, lw=1.2,
                    label=f"recovered p, kpen={case.kpen:.0e}")
        mismatch = case.kpen * (case.contact_scale / case.n) ** 2 / (8 * case.R) / p0
        ax.set(xlabel="r / a", title=f"P{order}, n = {case.n}: kpen h^2/(8R) = {mismatch:.2g} p0 at kpen=1e8",
               xlim=(0, 1.6))
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    axes[0].set_ylabel("p / p0 (Hertz)")
    axes[0].set_ylim(-0.1, 1.6)
    fig.suptitle("Surface pressure: FE against Hertz (P1 pointwise pressure zig-zags at high kpen)")
    return _save(fig, path)


def zigzag(tables: dict, path: Path) -> Path:
    rows = pd.concat([tables[s] for s in ("kpen", "mesh", "stability", "speed") if s in tables])
    rows = rows[(rows["status"] == "converged") & (rows["method"] == "newton")].drop_duplicates("case_id")
    h = np.sqrt(rows["R"] * rows["d"]) / rows["n"]
    mismatch = rows["kpen"] * h**2 / (8 * rows["R"]) / rows["p0_hertz"]
    fig, ax = plt.subplots(figsize=(7.5, 5))
    for order, color in ((1, "#64b5f6"), (2, "#1565c0")):
        sel = rows["order"] == order
        ax.scatter(mismatch[sel], (rows["p0_point"][sel] / rows["p0_hertz"][sel] - 1).abs() * 100,
                   c=color, marker="o", s=18, label=f"pointwise max kpen<g>+, P{order}")
        ax.scatter(mismatch[sel], rows["err_p0"][sel].abs() * 100, c=color, marker="x", s=22,
                   label=f"recovered p0 (reported), P{order}")
    ax.axvline(1, color="grey", ls=":", label="kpen h^2/(8R) = p0")
    ax.set(xscale="log", yscale="log", xlabel="chord mismatch kpen h^2 / (8 R p0)",
           ylabel="|p0 error| [%]", title="Pointwise vs recovered peak pressure (sphere, Newton)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    return _save(fig, path)


def seed_figure(runs: dict, path: Path) -> Path:
    fig, ax = plt.subplots(figsize=(8, 5))
    colors = ("#90caf9", "#42a5f5", "#1565c0", "#0d47a1")
    for case, color in zip(SEED_FIGURE_CASES, colors):
        prof = load(runs[case.case_id], "profile")
        a = case.contact_scale
        ax.plot(prof["r"] / a, prof["u_z"] / case.d, "-", color=color, label=f"u_z, kpen={case.kpen:.0e}")
        ax.plot(prof["r"] / a, prof["gap"] / case.d, "--", color=color, lw=1,
                label=f"gap h - u_z, kpen={case.kpen:.0e}")
    ax.plot(prof["r"] / a, prof["indenter"] / case.d, "r-", lw=2, label="indenter h = -d + r^2/2R")
    ax.axhline(0, color="grey", lw=0.5)
    ax.set(xlabel="r / a", ylabel="displacement / d", xlim=(0, 2.5),
           title="Seed Figure 1 redone: surface u_z, gap and indenter, soft to stiff penalty")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    return _save(fig, path)


def axis_stresses(runs: dict, path: Path) -> Path:
    axis = load(runs[AXIS_CASE.case_id], "axis")
    p0 = axis["sigma_z_hertz"].abs().max()
    fig, ax = plt.subplots(figsize=(7, 5.5))
    z = axis["depth_over_a"]
    for col, hcol, color, name in (("sigma_z", "sigma_z_hertz", "#1565c0", "sigma_z"),
                                   ("sigma_r", "sigma_r_hertz", "#2e7d32", "sigma_r"),
                                   ("tau_max", "tau_max_hertz", "#c62828", "tau_max")):
        ax.plot(axis[col] / p0, z, "-", color=color, lw=2, label=f"{name} FE")
        ax.plot(axis[hcol] / p0, z, "k:", lw=1.2)
    ax.plot([], [], "k:", label="Hertz")
    peak = axis.loc[axis["tau_max"].idxmax()]
    ax.plot(peak["tau_max"] / p0, peak["depth_over_a"], "o", color="#c62828")
    ax.annotate(f"tau_max {peak['tau_max'] / p0:.3f} p0 at {peak['depth_over_a']:.2f} a\n(Hertz 0.31 p0 at 0.48 a)",
                (peak["tau_max"] / p0, peak["depth_over_a"]), xytext=(10, -5),
                textcoords="offset points", fontsize=8)
    ax.invert_yaxis()
    ax.set(xlabel="stress / p0", ylabel="depth z / a",
           title="Stresses on the axis (sphere, P2, n = 16, kpen = 1e8)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="lower left")
    return _save(fig, path)


def domain_bias(frame: pd.DataFrame, path: Path) -> Path:
    df = frame[frame["status"] == "converged"].sort_values("L")
    fig, ax = plt.subplots(figsize=(7, 5))
    ax.plot(df["L"], df["err_F"] * 100, "o-", color="#1565c0", label="F error (measured)")
    ax.plot(df["L"], df["err_p0"].abs() * 100, "s--", color="#2e7d32", label="|p0 error|")
    L = np.logspace(np.log10(df["L"].min()), np.log10(df["L"].max()), 50)
    ax.plot(L, 0.94 * 100 / L, "k:", label="0.94% x 100a / L (clamped far boundary)")
    ax.set(xscale="log", yscale="log", xlabel="domain radius L / a", ylabel="relative error [%]",
           title="Finite-domain bias (sphere, P2, n = 16, kpen = 1e8)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return _save(fig, path)
