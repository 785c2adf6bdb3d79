"""results/REPORT.md: the charts with captions and the best configurations.

Reads the study tables and the environment the sweep recorded; runs nothing,
so it works where FreeFEM is absent.
"""
from __future__ import annotations

import datetime
import platform
import subprocess
from pathlib import Path

import matplotlib
import numpy as np
import pandas as pd

from driver import ROOT, plots, table
from driver.studies import STUDIES
from driver.sweep import ENVIRONMENT_FILE, study_csv

LEVELS = (0.01, 0.001)


def load_tables(results_dir: Path) -> dict[str, pd.DataFrame]:
    tables = {}
    for name in STUDIES:
        path = study_csv(results_dir, name)
        if path.exists():
            tables[name] = table.read(path)
    return tables


def best_configurations(tables: dict) -> pd.DataFrame:
    """Fastest converged sphere case of the speed study (its timings are medians of
    repeated runs) whose max |error| over p0, F and a is within each level."""
    rows = plots.sphere_cases({"speed": tables.get("speed", pd.DataFrame())})
    best = []
    for level in LEVELS:
        within = rows[rows["max_err"] <= level]
        if len(within):
            row = within.loc[within["wall_time"].idxmin()].copy()
            row["level"] = level
            best.append(row)
    return pd.DataFrame(best)


def _fmt_table(best: pd.DataFrame) -> str:
    head = ("| accuracy | method | order | n | wall time [s] (median) | timings [s] | iterations "
            "| err p0 | err F | err a | penetration/d | case |")
    lines = [head, "|" + "---|" * (head.count("|") - 1)]
    for _, r in best.iterrows():
        lines.append(
            f"| {r['level']:.1%} | {r['method']} | P{r['order']:.0f} | {r['n']:.0f} | {r['wall_time']:.3f} "
            f"| {r['timings']} | {r['iterations'] + r['coarse_iterations']:.0f} | {r['err_p0']:+.4%} "
            f"| {r['err_F']:+.4%} | {r['err_a']:+.4%} | {r['penetration_over_d']:.2e} | `{r['case_id']}` |")
    return "\n".join(lines)


def _pct(value: float) -> str:
    return "-" if pd.isna(value) else f"{value:+.3%}"


def _fmt_3d(frame: pd.DataFrame) -> str:
    head = ("| case | model | method | n | status | ndof | wall time [s] | memory [MB] | err p0 | err F "
            "| err a | err b | estimate |")
    lines = [head, "|" + "---|" * (head.count("|") - 1)]
    for _, r in frame.sort_values(["model", "Ry", "Rx", "method", "order", "n"]).iterrows():
        lines.append(
            f"| `{r['case_id']}` | {r['model']} | {r['method']} P{r['order']:.0f} | {r['n']:.0f} | {r['status']} "
            f"| {r['ndof']:.0f} | {r['wall_time']:.2f} | {r['memory_mb']:.0f} | {r['err_p0']:+.3%} "
            f"| {r['err_F']:+.3%} | {r['err_a']:+.3%} | {_pct(r['err_b'])} | {r['accuracy_predicted']:.3%} |")
    return "\n".join(lines)


CAPTIONS = {
    "accuracy_vs_speed": "Max relative error over p0, F and a against the wall time the driver measured, "
                         "every converged sphere case of every study (open markers: the sphere solved in "
                         "3D); the black line is the Pareto front (no case is both faster and more "
                         "accurate). Right: the same cases by their own error estimate, as a user without "
                         "a closed form would see them.",
    "penalty": "Left: max error and penetration / d against the absolute penalty (seed scene). The "
               "penalty error falls as 1/kpen down to the discretization floor; lagrange and Uzawa have "
               "no penalty error. Right: iterations over all levels.",
    "mesh": "Errors against element size h/a at the contact for each series; the slopes are fitted "
            "from the coarsest mesh until the curve meets its floor (penalty, domain or rounding), and "
            "the legend names that range.",
    "stability": "Left: fixed point, kpen x omega, cells coloured by status with the iteration count; "
                 "dashed: the predicted limit kpen = (2/omega - 1)/mu. Middle: Newton from each start "
                 "(the previous level's contact zone, zero, the Hertz zone), with and without line search "
                 "and continuation, over the penalty in units of E*/h. Right: lagrange and Uzawa over "
                 "the augmentation parameter.",
    "pressure_profiles": "Surface pressure for soft to stiff penalties. Dotted: the pointwise penalty "
                         "pressure kpen<u_z - h>+; solid: the recovered pressure that is reported "
                         "(P1: nodal contact force / nodal area; P2: L2 projection of the nodal forces).",
    "zigzag": "Pointwise against recovered peak pressure error, against the chord mismatch kpen h^2/(8R) "
              "in units of p0: the pointwise P1 value fails once the mismatch approaches p0, the "
              "recovered one does not.",
    "seed_figure1": "The seed's Figure 1 redone: surface displacement, gap h - u_z and the indenter for "
                    "soft to stiff penalties; a soft penalty lets the indenter sink into the body.",
    "axis_stresses": "sigma_z, sigma_r and tau_max = |sigma_r - sigma_z|/2 along the axis against Hertz.",
    "domain": "Force bias of the clamped finite domain against its radius L/a (exact contact, so no "
              "penalty error): it follows 0.94% x 100a/L until the discretization floor.",
    "over_modelling": "The same sphere solved axisymmetric (solid) and in 3D (dashed, a quarter of the "
                      "half-space on TetGen meshes) over meshes: error against wall time, peak memory and "
                      "dofs. The title compares, at the most accurate converged 3D case, the cheapest axi case "
                      "that is at least as accurate (same method).",
    "calibration": "Left and middle: the run's own error estimate (no Hertz) against the true max error "
                   "of p0, F and a on scenes with closed forms (nu from -0.5 to 0.499, d/R from 1e-6 to 0.1, "
                   "SI units, plane strain, P1, lagrange, and -accuracy runs); the band is estimate/truth "
                   "from 0.5 to 3. Right: -accuracy X, the true error reached (dots) and the estimate "
                   "(crosses) against X; points on or below the line meet the target.",
    "ellipses": "Left: the contact outline (gap threshold along rays) for each ellipsoid at its finest mesh, "
                "against Hertz's ellipse. Right: the pressure along both axes of the most elongated one "
                "against p0 sqrt(1 - (s/semi-axis)^2).",
    "units": "The same dimensionless scenes given in three unit systems: the errors agree to rounding "
             "(the spread under each scene is the largest difference of any relative error).",
}


def _git(*args: str) -> str:
    try:
        return subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True,
                              check=False).stdout.strip()
    except OSError:
        return ""


def environment(results_dir: Path) -> list[str]:
    """Versions and dates: the sweep's machine (recorded when it ran) and this report's."""
    lines = []
    env_path = results_dir / ENVIRONMENT_FILE
    if env_path.exists():
        env = pd.read_csv(env_path, dtype=str).iloc[0].to_dict()
        lines.append("Sweep: " + ", ".join(f"{k} {v}" for k, v in env.items()) + ".")
    lines.append(f"Report: written {datetime.datetime.now().isoformat(timespec='seconds')} at commit "
                 f"{_git('rev-parse', '--short', 'HEAD') or 'unknown'}, Python {platform.python_version()}, "
                 f"pandas {pd.__version__}, numpy {np.__version__}, matplotlib {matplotlib.__version__}.")
    return lines


def write_report(results_dir: Path) -> Path:
    tables = load_tables(results_dir)
    if not tables:
        raise FileNotFoundError(f"no study CSV in {results_dir}: run 'make sweep' or 'hertz sweep --all --quick'")
    charts = {}
    charts["accuracy_vs_speed"] = plots.accuracy_vs_speed(tables, results_dir / "accuracy_vs_speed.png")
    if "kpen" in tables:
        charts["penalty"] = plots.penalty_study(tables["kpen"], results_dir / "penalty.png")
    if "mesh" in tables:
        charts["mesh"] = plots.mesh_study(tables["mesh"], results_dir / "mesh.png")
    if "stability" in tables:
        charts["stability"] = plots.stability_map(tables["stability"], results_dir / "stability.png")
    figures = tables.get("figures")
    profile_path = results_dir / "figures" / "profile.csv"
    axis_path = results_dir / "figures" / "axis.csv"
    if figures is not None and profile_path.exists():
        profiles = table.read(profile_path)
        charts["pressure_profiles"] = plots.pressure_profiles(figures, profiles, results_dir / "pressure_profiles.png")
        charts["seed_figure1"] = plots.seed_figure(figures, profiles, results_dir / "seed_figure1.png")
    if figures is not None and axis_path.exists():
        charts["axis_stresses"] = plots.axis_stresses(figures, table.read(axis_path), results_dir / "axis_stresses.png")
    charts["zigzag"] = plots.zigzag(tables, results_dir / "zigzag.png")
    if "domain" in tables:
        charts["domain"] = plots.domain_bias(tables["domain"], results_dir / "domain.png")
    if "units" in tables:
        charts["units"] = plots.units_check(tables["units"], results_dir / "units.png")

    if "calibration" in tables:
        charts["calibration"] = plots.calibration(tables["calibration"], results_dir / "calibration.png")
    if "3d" in tables:
        charts["over_modelling"] = plots.over_modelling(tables["3d"], results_dir / "over_modelling.png")
        outline, profile, profile_y = (results_dir / "3d" / f"{name}.csv"
                                       for name in ("outline", "profile", "profile_y"))
        if outline.exists() and profile.exists() and profile_y.exists():
            charts["ellipses"] = plots.ellipses(tables["3d"], table.read(outline), table.read(profile),
                                                table.read(profile_y), results_dir / "ellipses.png")

    best = best_configurations(tables)
    counts = {name: len(t) for name, t in tables.items()}
    text = ["# Results", "",
            f"Generated by `make report` from {sum(counts.values())} cases "
            f"({', '.join(f'{k}: {v}' for k, v in counts.items())}).", ""]
    text += environment(results_dir) + [""]
    text += ["## Best configuration for each accuracy level", "",
             "Fastest converged sphere case of the speed study whose max |error| over p0, F and a is "
             "within the level; its wall time is the median of the repeated runs listed.", "",
             _fmt_table(best), ""]
    if "3d" in tables:
        text += ["## 3D cases", "",
                 "Every case of the 3d study: the sphere as axi and as 3d, and ellipsoids against elliptical "
                 "Hertz (a along x, b along y). The estimate is the solver's own (no Hertz).", "",
                 _fmt_3d(tables["3d"]), ""]
    for name, path in charts.items():
        text += [f"## {name.replace('_', ' ').capitalize()}", "", f"![{name}]({path.name})", "",
                 CAPTIONS[name], ""]
    report = results_dir / "REPORT.md"
    table.write_atomically(report, "\n".join(text))
    return report
