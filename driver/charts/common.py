"""What the charts share: colours and markers, the rows a chart draws (NoData when they are
missing), and writing a PNG whole.

Series are chosen by the `variant` column the studies write, and titles take
their facts (mesh, penalty, scene) from the rows they draw. A chart whose rows
are missing raises NoData (the report skips it with a note), and every PNG is
written to a temporary file and renamed, so an interrupted report leaves the
old chart whole.
"""
from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import NamedTuple

import matplotlib.pyplot as plt
import pandas as pd

from driver import files, studytable
from driver.errors import ReportError
from driver.schema import max_error

Tables = dict[str, pd.DataFrame]

ERRORS = {"err_p0": "p0", "err_F": "F", "err_a": "a"}
# p0, F, a: blue, vermillion and reddish purple from Okabe and Ito's palette, apart under every
# colour-vision deficiency (red against green is the pair deuteranopes lose); not black, which
# the charts keep for their references (Hertz, Sneddon)
QUANTITY_COLORS = ("#0072B2", "#D55E00", "#CC79A7")
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
# Okabe and Ito's palette but yellow (washed out on a white page) and black (the references)
SHAPE_COLORS = {"cone 70.3": "#D55E00", "cone 60": "#E69F00", "punch": "#CC79A7", "power k = 3": "#009E73",
                "power k = 1.5": "#56B4E9", "sphere": "#0072B2"}

# the estimate's target: from half to three times the true error
EFFECTIVITY_BAND = (0.5, 3.0)
BAND = "{:g} to {:g}".format(*EFFECTIVITY_BAND)  # as the captions name it


class Chart(NamedTuple):
    """A chart of the report, under its name (the PNG's stem) in a module's CHARTS.

    draw(table, *kept frames, png) for a chart of one study: that study's table, then the
    files of its cases the sweep kept (kept, names of Study.keep), in that order;
    draw(tables, png) for a summary chart, which reads every study's tables."""
    draw: Callable[..., Path]
    caption: str  # in REPORT.md, under the chart
    kept: tuple[str, ...] = ()


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
    # (an adhesive contact's force is Maugis's, not Hertz's: the adhesion chart)
    if "w" in rows:
        sphere &= ~(rows["w"] > 0)
    sphere &= rows["Rx"] == rows["Ry"]
    rows = rows[(rows["status"] == "converged") & sphere].drop_duplicates("case_id")
    return rows.assign(max_err=max_error(rows))


def shape_label(row: pd.Series) -> str:
    """A shape as the charts name it: cone 70.3, power k = 3, punch, sphere, parabola."""
    if row["shape"] == "cone":
        return f"cone {row['angle']:g}"
    if row["shape"] == "power":
        return f"power k = {row['k']:g}"
    return str(row["shape"])


# no text chunks: a chart redrawn from the same tables is the same bytes on any matplotlib
# (its default names its version in a Software chunk)
PNG_METADATA = {"Software": None}


def save(fig, path: Path, layout: bool = True) -> Path:
    """The chart as PNG, whole or not at all (a kill or a full disk keeps the old one)."""
    try:
        if layout:
            fig.tight_layout()
        files.replace_atomically(path, lambda tmp: fig.savefig(tmp, dpi=110, format="png", metadata=PNG_METADATA),
                                 ReportError)
    finally:
        plt.close(fig)
    return path


def scene(frame: pd.DataFrame) -> str:
    """The scene the rows share, for titles (only the values that are common)."""
    parts = []
    for col, fmt in (("n", "n = {:.0f}"), ("L", "L = {:g} a"), ("nu", "nu = {:g}")):
        values = frame[col].dropna().unique()
        if len(values) == 1:
            parts.append(fmt.format(values[0]))
    return ", ".join(parts)


def draw(chart: Chart, owner: str | None, tables: Tables, results_dir: Path, png: Path) -> Path:
    """Draw a chart into png: of its owner study's table and kept files, or, owner None, of every table."""
    if owner is None:
        return chart.draw(tables, png)
    return chart.draw(study(tables, owner), *(kept(results_dir, owner, name) for name in chart.kept), png)


def study(tables: Tables, name: str) -> pd.DataFrame:
    """A study's table, or NoData naming what is missing."""
    return need(tables.get(name), f"{name}.csv has no rows" if name in tables else f"no {name}.csv")


def kept(results_dir: Path, study_name: str, name: str) -> pd.DataFrame:
    """A per-case file the sweep gathered (results/<study>/<name>), empty if absent."""
    path = results_dir / study_name / name
    return studytable.read(path) if path.exists() else pd.DataFrame()
