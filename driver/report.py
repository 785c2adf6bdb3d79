"""results/REPORT.md: the charts with captions and the best configurations."""
from __future__ import annotations

from pathlib import Path

import pandas as pd

from driver import plots
from driver.figures import figure_runs
from driver.studies import STUDIES
from driver.sweep import load_study, study_csv

LEVELS = (0.01, 0.001)
BEST_COLUMNS = ["method", "order", "n", "L", "kpen", "omega", "wall_time", "iterations",
                "err_p0", "err_F", "err_a", "penetration_over_d", "case_id"]


def load_tables(results_dir: Path) -> dict[str, pd.DataFrame]:
    tables = {}
    for name in STUDIES:
        path = study_csv(results_dir, name)
        if path.exists():
            tables[name] = load_study(path)
    return tables


def best_configurations(tables: dict) -> pd.DataFrame:
    """Fastest converged sphere case whose max |error| over p0, F, a is within each level."""
    rows = plots.sphere_cases(tables)
    best = []
    for level in LEVELS:
        within = rows[rows["max_err"] <= level]
        if len(within):
            row = within.loc[within["wall_time"].idxmin()].copy()
            row["level"] = level
            best.append(row)
    return pd.DataFrame(best)


def _fmt_table(best: pd.DataFrame) -> str:
    head = "| accuracy | method | order | n | L/a | kpen | wall time [s] | iterations | err p0 | err F | err a | penetration/d | case |"
    lines = [head, "|" + "---|" * (head.count("|") - 1)]
    for _, r in best.iterrows():
        lines.append(
            f"| {r['level']:.1%} | {r['method']} | P{r['order']} | {r['n']} | {r['L']:g} | {r['kpen']:.3g} "
            f"| {r['wall_time']:.3f} | {r['iterations']:.0f} | {r['err_p0']:+.4%} | {r['err_F']:+.4%} "
            f"| {r['err_a']:+.4%} | {r['penetration_over_d']:.2e} | `{r['case_id']}` |")
    return "\n".join(lines)


CAPTIONS = {
    "accuracy_vs_speed": "Max relative error over p0, F and a against the wall time the driver "
                         "measured, every converged sphere case of every study; the black line is "
                         "the Pareto front (no case is both faster and more accurate).",
    "penalty": "Errors and max penetration / d against kpen (Newton, n = 16). Penetration falls as "
               "1/kpen; the errors reach the discretization floor near kpen = 1e5 (P2). Orange: "
               "Newton iterations (semismooth, Hertz-zone initial active set, no continuation).",
    "mesh": "Errors against element size h/a at the contact, with the fitted log-log slopes; left a "
            "fixed kpen (its penalty floor stops the P2 curves), right kpen = 100 E*/h.",
    "stability": "Left: fixed point, kpen x omega, cells coloured by status with the iteration count; "
                 "dashed: the predicted limit kpen = (2/omega - 1)/mu, mu the largest eigenvalue of "
                 "K^-1 M on the first active set. Right: Newton with and without penalty continuation.",
    "pressure_profiles": "Surface pressure for soft to stiff penalties. Dotted: the pointwise penalty "
                         "pressure kpen<u_z - h>+; solid: the recovered pressure that is reported "
                         "(P1: nodal contact force / nodal area; P2: L2 projection of the nodal forces).",
    "zigzag": "Pointwise against recovered peak pressure error, against the chord mismatch "
              "kpen h^2/(8R) in units of p0: the pointwise P1 value fails once the mismatch "
              "approaches p0, the recovered one does not.",
    "seed_figure1": "The seed's Figure 1 redone: surface displacement, gap h - u_z and the indenter "
                    "for kpen from 1e1 to 1e5; a soft penalty lets the indenter sink into the body.",
    "axis_stresses": "sigma_z, sigma_r and tau_max = |sigma_r - sigma_z|/2 along the axis against Hertz.",
    "domain": "Force bias of the clamped finite domain against its radius L/a: it follows "
              "0.94% x 100a/L until the discretization floor.",
}


def write_report(results_dir: Path) -> Path:
    tables = load_tables(results_dir)
    if not tables:
        raise FileNotFoundError(f"no study CSV in {results_dir}: run 'make sweep' or 'make sweep-quick'")
    runs = figure_runs(results_dir)
    charts = {}
    charts["accuracy_vs_speed"] = plots.accuracy_vs_speed(tables, results_dir / "accuracy_vs_speed.png")
    if "kpen" in tables:
        charts["penalty"] = plots.penalty_study(tables["kpen"], results_dir / "penalty.png")
    if "mesh" in tables:
        charts["mesh"] = plots.mesh_study(tables["mesh"], results_dir / "mesh.png")
    if "stability" in tables:
        charts["stability"] = plots.stability_map(tables["stability"], results_dir / "stability.png")
    charts["pressure_profiles"] = plots.pressure_profiles(runs, results_dir / "pressure_profiles.png")
    charts["zigzag"] = plots.zigzag(tables, results_dir / "zigzag.png")
    charts["seed_figure1"] = plots.seed_figure(runs, results_dir / "seed_figure1.png")
    charts["axis_stresses"] = plots.axis_stresses(runs, results_dir / "axis_stresses.png")
    if "domain" in tables:
        charts["domain"] = plots.domain_bias(tables["domain"], results_dir / "domain.png")

    best = best_configurations(tables)
    counts = {name: len(t) for name, t in tables.items()}
    text = ["# Results", "",
            f"Generated by `make report` from {sum(counts.values())} cases "
            f"({', '.join(f'{k}: {v}' for k, v in counts.items())}).", "",
            "## Best configuration for each accuracy level", "",
            "Fastest converged sphere case whose max |error| over p0, F and a is within the level "
            "(wall time measured by the driver, one case at a time per core).", "",
            _fmt_table(best), ""]
    for name, path in charts.items():
        text += [f"## {name.replace('_', ' ').capitalize()}", "", f"![{name}]({path.name})", "",
                 CAPTIONS[name], ""]
    report = results_dir / "REPORT.md"
    tmp = report.with_suffix(".md.part")
    tmp.write_text("\n".join(text))
    tmp.replace(report)
    return report
