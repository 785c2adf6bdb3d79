"""results/REPORT.md: the charts with captions and the best configurations.

Reads the study tables and the environment the sweep recorded; runs nothing,
so it works where FreeFEM is absent. A chart whose data is missing (a partial
sweep) is skipped with a one-line note; a file that cannot be written stops
the report with one error (ReportError).
"""
from __future__ import annotations

import datetime
import platform
import subprocess
from collections.abc import Callable
from pathlib import Path

import matplotlib
import numpy as np
import pandas as pd

from driver import freefem, layout, plots, studytable
from driver.errors import ReportError, TableError
from driver.studies import STUDIES

LEVELS = (0.01, 0.001)


def load_tables(results_dir: Path) -> dict[str, pd.DataFrame]:
    tables = {}
    for name in STUDIES:
        path = layout.study_csv(results_dir, name)
        if path.exists() or path.is_symlink():
            tables[name] = studytable.read(path)
    return tables


def best_configurations(tables: dict) -> pd.DataFrame:
    """Fastest converged sphere case of the speed study (its timings are medians of
    repeated runs) whose max |error| over p0, F and a is within each level."""
    try:
        rows = plots.sphere_cases({"speed": tables.get("speed", pd.DataFrame())})
    except (plots.NoData, KeyError):
        return pd.DataFrame()
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


BAND = "{:g} to {:g}".format(*plots.EFFECTIVITY_BAND)  # the estimate's target, as the charts draw it
CAPTIONS = {
    "shapes": "Left: the exact spherical cap against Hertz's parabola of the same radius at the same depth: "
              "the FE runs (markers) and Sneddon's exact sphere against Hertz (lines). Middle: F(d) of each "
              "indenter, FE (markers) and Sneddon (lines), with the fitted slopes. Right: each shape's largest "
              "error against Sneddon over n (exact contact); the punch is measured on F and its edge factor K, "
              "the cone on F and a (its pressure is singular at the tip). Bottom right: the pressure profiles "
              "at d = 0.02 against Sneddon's.",
    "layers": "A film (E, nu) bonded to a substrate (E2, nu2) or a rigid base, sphere at d = 0.02, exact "
              "contact. Top left: the effective modulus from the contact stiffness against a/t, with the two "
              "half-space limits and Perriot and Barthel's integral equation (tests/layered_reference.py, "
              "accurate to about 1e-8; the tests check every quantity against it). Top right: the coated F "
              "over the film's own Hertz at the same depth (the grey band is 1%). Bottom: pressure and axis "
              "stresses of a soft film on a stiff substrate and a stiff film on a soft one.",
    "loading": "Loading curves by -d (markers) against Hertz (lines), and two of the sphere's points again "
               "by their load (-P, crosses): an elastic frictionless contact unloads along its loading curve. "
               "Middle: the contact stiffness from the converged linearization against 2E*a. Right: the "
               "cylinder, by its load per unit length: a and p0 against Hertz's relations (its depth depends on "
               "the domain). Each point is its own run, started from its own coarse level.",
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
                         "pressure kpen<u_z - h>+, against the indenter the contact forms see (P1: its "
                         "interpolant between the nodes); solid: the recovered pressure that is reported "
                         "(P1: nodal contact force / nodal area; P2: L2 projection of the nodal forces).",
    "zigzag": "Pointwise against recovered peak pressure error (converged axisymmetric Newton runs of "
              "Hertz's parabola), against kpen h^2/(8R) in units of p0: the pressure a penalty would "
              "build on the sag of a P1 chord under the curved indenter. P1's contact forms use the "
              "indenter's interpolant, so no run builds it, and the pointwise peak stays within about "
              "1% of the recovered one at any penalty.",
    "seed_figure1": "The seed's Figure 1 redone: surface displacement, gap h - u_z and the indenter for "
                    "soft to stiff penalties; a soft penalty lets the indenter sink into the body.",
    "axis_stresses": "sigma_z, sigma_r and tau_max = |sigma_r - sigma_z|/2 along the axis against Hertz.",
    "domain": "Force and peak-pressure bias of a finite domain against its radius L/a (exact contact, so no "
              "penalty error): a clamped far boundary follows 0.94% x 100a/L; Boussinesq's boundary (the rest "
              "of the half-space moving as a point load of the contact force, the default) stays at the "
              "discretization floor from L = 10 a.",
    "over_modelling": "The same sphere solved axisymmetric (solid) and in 3D (dashed, a quarter of the "
                      "half-space, the 2D section revolved) over meshes: error against wall time, peak memory and "
                      "dofs. The title compares, at the most accurate converged 3D case, the cheapest axi case "
                      "that is at least as accurate (same method).",
    "calibration": "Left and middle: the run's own error estimate (no Hertz) against the true max error "
                   "of p0, F and a on scenes with closed forms (nu from -0.5 to 0.499, d/R from 1e-6 to 0.1, "
                   "SI units, plane strain, P1, lagrange, and -accuracy runs); the band is estimate/truth "
                   f"from {BAND}. Right: -accuracy X, the true error reached (dots) and the estimate "
                   "(crosses) against X; points on or below the line meet the target.",
    "effectivity": "The run's own error estimate (no reference used) over the true max error of the quantities "
                   "that have both an estimate and a reference (p0, F and a; b in 3D; a punch's K), for every "
                   "distinct answered result of every study (a study's copy of another's scene, with the same "
                   f"relative errors, counts once), a panel per model: the grey band is {BAND}. A point below "
                   "it would be an estimate that promised too much; above it the estimate is safe but pessimistic.",
    "ellipses": "Left: the contact outline (gap threshold along rays) for each ellipsoid at its finest mesh, "
                "against Hertz's ellipse. Right: the pressure along both axes of the most elongated one "
                "against p0 sqrt(1 - (s/semi-axis)^2).",
    "units": "The same dimensionless scenes given in three unit systems: the errors agree to rounding "
             "(the spread under each scene is the largest difference of any relative error).",
}


def _git(*args: str) -> str:
    try:
        return subprocess.run(["git", *args], cwd=freefem.EDP_DIR, capture_output=True, text=True,
                              check=False).stdout.strip()
    except OSError:
        return ""


def environment(results_dir: Path) -> list[str]:
    """Versions and dates: the sweep's machine (recorded when it ran) and this report's."""
    lines = []
    env_path = results_dir / layout.ENVIRONMENT_FILE
    try:
        env = pd.read_csv(env_path, dtype=str, keep_default_na=False) if env_path.is_file() else pd.DataFrame()
    except (OSError, ValueError):
        env = pd.DataFrame()  # an unreadable record only costs the report its sweep line
    if len(env):
        lines.append("Sweep: " + ", ".join(f"{k} {v}" for k, v in env.astype(str).iloc[0].items()) + ".")
    lines.append(f"Report: written {datetime.datetime.now().isoformat(timespec='seconds')} at commit "
                 f"{_git('rev-parse', '--short', 'HEAD') or 'unknown'}, Python {platform.python_version()}, "
                 f"pandas {pd.__version__}, numpy {np.__version__}, matplotlib {matplotlib.__version__}.")
    return lines


Chart = Callable[[dict[str, pd.DataFrame], Path, Path], Path]


def _kept(results_dir: Path, study: str, name: str) -> pd.DataFrame:
    """A per-case file the sweep gathered (results/<study>/<name>), empty if absent."""
    path = results_dir / study / name
    return studytable.read(path) if path.exists() else pd.DataFrame()


def _study(tables: dict[str, pd.DataFrame], name: str) -> pd.DataFrame:
    return plots.need(tables.get(name), f"{name}.csv has no rows" if name in tables else f"no {name}.csv")


# each chart: its name (the PNG's stem) and how to draw it from the tables and the kept files
CHARTS: dict[str, Chart] = {
    "accuracy_vs_speed": lambda t, r, png: plots.accuracy_vs_speed(t, png),
    "penalty": lambda t, r, png: plots.penalty_study(_study(t, "kpen"), png),
    "mesh": lambda t, r, png: plots.mesh_study(_study(t, "mesh"), png),
    "stability": lambda t, r, png: plots.stability_map(_study(t, "stability"), png),
    "pressure_profiles": lambda t, r, png: plots.pressure_profiles(_study(t, "figures"),
                                                                   _kept(r, "figures", "profile.csv"), png),
    "seed_figure1": lambda t, r, png: plots.seed_figure(_study(t, "figures"), _kept(r, "figures", "profile.csv"), png),
    "axis_stresses": lambda t, r, png: plots.axis_stresses(_study(t, "figures"), _kept(r, "figures", "axis.csv"), png),
    "zigzag": lambda t, r, png: plots.zigzag(t, png),
    "domain": lambda t, r, png: plots.domain_bias(_study(t, "domain"), png),
    "units": lambda t, r, png: plots.units_check(_study(t, "units"), png),
    "calibration": lambda t, r, png: plots.calibration(_study(t, "calibration"), png),
    "effectivity": lambda t, r, png: plots.effectivity(t, png),
    "over_modelling": lambda t, r, png: plots.over_modelling(_study(t, "3d"), png),
    "shapes": lambda t, r, png: plots.shapes(_study(t, "shapes"), _kept(r, "shapes", "profile.csv"), png),
    "layers": lambda t, r, png: plots.layers(_study(t, "layers"), _kept(r, "layers", "profile.csv"),
                                             _kept(r, "layers", "axis.csv"), png),
    "loading": lambda t, r, png: plots.loading(_study(t, "loading"), png),
    "ellipses": lambda t, r, png: plots.ellipses(_study(t, "3d"), _kept(r, "3d", "outline.csv"),
                                                 _kept(r, "3d", "profile.csv"), _kept(r, "3d", "profile_y.csv"), png),
}


def write_report(results_dir: Path, say: Callable[[str], None] = print) -> Path:
    """Every chart whose data is there, and REPORT.md; say() gets a note for each skipped chart."""
    results_dir = layout.user_path(results_dir)
    tables = load_tables(results_dir)
    if not any(len(t) for t in tables.values()):
        raise ReportError(f"no study rows in {results_dir}: run 'make sweep' or 'hertz sweep --all --quick'")
    charts = {}
    for name, draw in CHARTS.items():
        png = results_dir / f"{name}.png"
        try:
            charts[name] = draw(tables, results_dir, png)
        except plots.NoData as why:
            say(f"skipped {png.name}: {why}")
        except KeyError as column:
            say(f"skipped {png.name}: column {column} missing in its table")

    best = best_configurations(tables)
    counts = {name: len(t) for name, t in tables.items()}
    text = ["# Results", "",
            f"Generated by `make report` from {sum(counts.values())} cases "
            f"({', '.join(f'{k}: {v}' for k, v in counts.items())}).", ""]
    text += environment(results_dir) + [""]
    if len(best):
        text += ["## Best configuration for each accuracy level", "",
                 "Fastest converged sphere case of the speed study whose max |error| over p0, F and a is "
                 "within the level; its wall time is the median of the repeated runs listed.", "",
                 _fmt_table(best), ""]
    if len(tables.get("3d", ())):
        text += ["## 3D cases", "",
                 "Every case of the 3d study: the sphere as axi and as 3d, and ellipsoids against elliptical "
                 "Hertz (a along x, b along y). The estimate is the solver's own (no Hertz).", "",
                 _fmt_3d(tables["3d"]), ""]
    for name, path in charts.items():
        text += [f"## {name.replace('_', ' ').capitalize()}", "", f"![{name}]({path.name})", "",
                 CAPTIONS[name], ""]
    report = results_dir / layout.REPORT_FILE
    try:
        studytable.write_atomically(report, "\n".join(text))
    except TableError as exc:
        raise ReportError(str(exc)) from None
    return report
