"""results/REPORT.md: the charts with captions and the best configurations.

Reads the study tables and the environment the sweep recorded; runs nothing,
so it works where FreeFEM is absent. A chart whose data is missing (a partial
sweep) is skipped with a one-line note; a file that cannot be written stops
the report with one error (ReportError).
"""
from __future__ import annotations

import platform
from collections.abc import Callable
from pathlib import Path

import matplotlib
import numpy as np
import pandas as pd

from driver import charts, layout, studytable
from driver.charts import Chart
from driver.charts.common import draw, need, sphere_cases
from driver.charts.own_study import CAPTION as OWN_CAPTION
from driver.charts.own_study import own_study
from driver.errors import ReportError, TableError
from driver.studies import STUDIES, report_charts

LEVELS = (0.01, 0.001)


def load_tables(results_dir: Path) -> dict[str, pd.DataFrame]:
    tables = {}
    for name in STUDIES:
        path = layout.study_csv(results_dir, name)
        if path.exists() or path.is_symlink():
            tables[name] = studytable.read(path)
    return tables


def own_tables(results_dir: Path) -> dict[str, pd.DataFrame]:
    """The user's own studies in the folder (hertz sweep --spec, sweep(name, cases=...)): every
    <name>.csv that is a study table (its header has study, case_id and status) and not a
    built-in study's or the driver's."""
    tables = {}
    for path in sorted(results_dir.glob("*.csv")):
        if path.stem in STUDIES or path.stem in layout.RESERVED_NAMES or not path.is_file():
            continue
        try:
            with open(path, encoding="utf-8", errors="replace") as handle:
                header = set(handle.readline().strip().split(","))
        except OSError:
            continue
        if {"study", "case_id", "status"} <= header:
            tables[path.stem] = studytable.read(path)
    return tables


def best_configurations(tables: dict) -> pd.DataFrame:
    """Fastest converged sphere case of the speed study (its timings are medians of
    repeated runs) whose max |error| over p0, F and a is within each level."""
    try:
        rows = sphere_cases({"speed": tables.get("speed", pd.DataFrame())})
    except (charts.NoData, KeyError):
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


def environment(results_dir: Path) -> list[str]:
    """Versions: the sweep's machine (recorded when it ran: date, commit) and the libraries that
    draw this report. No date or commit of the report's own: drawn again from the same tables
    it is the same file, so a fresh clone's `make report` leaves git status clean."""
    lines = []
    env_path = results_dir / layout.ENVIRONMENT_FILE
    try:
        env = pd.read_csv(env_path, dtype=str, keep_default_na=False) if env_path.is_file() else pd.DataFrame()
    except (OSError, ValueError):
        env = pd.DataFrame()  # an unreadable record only costs the report its sweep line
    if len(env):
        lines.append("Sweep (the newest): " + ", ".join(f"{k} {v}" for k, v in env.astype(str).iloc[-1].items()) + ".")
    lines.append(f"Report: drawn with Python {platform.python_version()}, pandas {pd.__version__}, "
                 f"numpy {np.__version__}, matplotlib {matplotlib.__version__}.")
    return lines


# each chart of the report, in its order, under its name (the PNG's stem)
CHARTS: dict[str, Chart] = {name: charts.CHARTS[name] for name in report_charts()}
# the study whose table each chart draws (a summary chart reads every table)
OWNERS = {name: study.name for study in STUDIES.values() for name in study.charts}


def write_report(results_dir: Path, say: Callable[[str], None] = print) -> Path:
    """Every chart whose data is there, and REPORT.md; say() gets a note for each skipped chart."""
    results_dir = layout.user_path(results_dir)
    tables = load_tables(results_dir)
    own = own_tables(results_dir)
    if not any(len(t) for t in [*tables.values(), *own.values()]):
        raise ReportError(f"no study rows in {results_dir}: run 'make sweep' or 'hertz sweep --all --quick'")
    drawn = {}
    if not any(len(t) for t in tables.values()):
        say("skipped the built-in charts: no built-in study rows here (make sweep, or hertz sweep --all --quick)")
    for name, chart in CHARTS.items() if any(len(t) for t in tables.values()) else ():
        png = results_dir / f"{name}.png"
        try:
            drawn[name] = draw(chart, OWNERS.get(name), tables, results_dir, png)
        except charts.NoData as why:
            say(f"skipped {png.name}: {why}")
        except KeyError as column:
            say(f"skipped {png.name}: its table lacks a column ({column.args[0] if column.args else column})")

    own_drawn = {}
    for name, table in own.items():
        png = results_dir / f"{name}.png"
        if name in CHARTS:
            say(f"skipped {png.name}: the study {name} has the name of a chart of the report")
            continue
        try:
            own_drawn[name] = own_study(need(table, f"{name}.csv has no rows"), png)
        except charts.NoData as why:
            say(f"skipped {png.name}: {why}")
        except KeyError as column:
            say(f"skipped {png.name}: its table lacks a column ({column.args[0] if column.args else column})")

    best = best_configurations(tables)
    counts = {name: len(t) for name, t in [*tables.items(), *own.items()]}
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
    for name, path in drawn.items():
        text += [f"## {name.replace('_', ' ').capitalize()}", "", f"![{name}]({path.name})", "",
                 CHARTS[name].caption, ""]
    for name, path in own_drawn.items():
        text += [f"## Study {name}", "", f"![{name}]({path.name})", "", OWN_CAPTION, ""]
    report = results_dir / layout.REPORT_FILE
    try:
        studytable.write_atomically(report, "\n".join(text))
    except TableError as exc:
        raise ReportError(str(exc)) from None
    return report
