"""Columns and statuses the driver adds to hertz.edp's own.

A study CSV is  LEADING + summary.csv's columns (freefem.summary_columns) + TRAILING.
hertz.edp's statuses and exit codes come from its -exits table (freefem.exits);
the driver adds three statuses of its own for runs that gave no answer.
"""
from __future__ import annotations

import math
from collections.abc import Mapping
from typing import TYPE_CHECKING

from driver import freefem

if TYPE_CHECKING:  # only annotations use it: hertz run does not load pandas
    import pandas as pd

LEADING = ["study", "case_id", "variant", "expect_converged"]
TRAILING = ["edp_hash", "wall_time", "timings", "max_rss_mb", "jobs", "exit_code", "error"]

# read as text whatever they look like (an edp_hash such as 05426170e796 is not a number)
DRIVER_TEXT = ["study", "case_id", "variant", "edp_hash", "error", "timings"]
# hertz.edp's outputs that are words; its word and path options are text too (text_columns)
OUTPUT_TEXT = ["status", "warnings", "reference"]

# the relative errors against the reference (err_b: 3D only, NaN in 2D)
ERROR_COLUMNS = ("err_p0", "err_F", "err_a", "err_b")


def max_error(frame: pd.DataFrame) -> pd.Series:
    """Largest |relative error| of each row over ERROR_COLUMNS (absent or NaN ones skipped)."""
    return frame.reindex(columns=list(ERROR_COLUMNS)).abs().max(axis=1, skipna=True)


# a run that gave an answer: its p0, F and a must be finite numbers
ANSWERED = ("converged", "inaccurate")
ANSWER_COLUMNS = ("p0_fe", "F_fe", "a_fe")
# ... but for these shapes the pressure is singular and p0 is not a result
# (under a cone's tip and at a punch's edge; edp/lib/shape.idp: finitePressure)
SINGULAR_PRESSURE_SHAPES = ("cone", "punch")

DRIVER_STATUSES = ["nan", "timeout", "failed"]
# worth running again with more time or after a fix elsewhere (--retry-failed)
RETRY_STATUSES = ["failed", "timeout"]
# a driver status exits like the solver status it stands for (hertz run)
DRIVER_EXITS_LIKE = {"nan": "diverged", "timeout": "maxiter"}
EXIT_FAILED = 1  # the driver could not get an answer, and no solver code says why


def study_columns(summary: list[str]) -> list[str]:
    return LEADING + list(summary) + TRAILING


def text_columns() -> set[str]:
    """Columns that hold words: the driver's, hertz.edp's word outputs, and every word
    or path option (a new one is text without a change here)."""
    words = {name for name, o in freefem.options().items() if o.kind in ("word", "path", "list")}
    return set(DRIVER_TEXT) | set(OUTPUT_TEXT) | words


def statuses() -> list[str]:
    """Every status a row may carry: hertz.edp's (its -exits table), then the driver's."""
    return list(freefem.exits()) + DRIVER_STATUSES


def missing_answer(row: Mapping) -> str | None:
    """The first answer column (ANSWER_COLUMNS) of a row that is not a finite number, or None."""
    for column in ANSWER_COLUMNS:
        if column == "p0_fe" and row.get("shape") in SINGULAR_PRESSURE_SHAPES:
            continue
        value = row.get(column)
        if isinstance(value, str):
            try:
                value = float(value) if value else math.nan
            except ValueError:
                return column
        if not isinstance(value, (int, float)) or not math.isfinite(value):
            return column
    return None


def answered(row: Mapping) -> bool:
    """A converged or inaccurate row with finite p0 (unless singular), F and a."""
    return row.get("status") in ANSWERED and missing_answer(row) is None


def exit_code_of(row: Mapping) -> int:
    """The exit code `hertz run` gives for a row: hertz.edp's code for its status, the
    solver's own code when the driver could not read an answer, else EXIT_FAILED."""
    table = freefem.exits()
    status = str(row.get("status"))
    status = DRIVER_EXITS_LIKE.get(status, status)
    if status in table:
        return table[status].code
    code = row.get("exit_code")
    known = {e.code for name, e in table.items() if name not in ANSWERED and e.code != 0}
    if isinstance(code, (int, float)) and not isinstance(code, bool) and code == code and int(code) in known:
        return int(code)
    return EXIT_FAILED
