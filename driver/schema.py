"""Columns and statuses the driver adds to hertz.edp's own (freefem.summary_columns).

A study CSV is  LEADING + summary.csv's columns + TRAILING.
"""
from __future__ import annotations

LEADING = ["study", "case_id", "variant", "expect_converged"]
TRAILING = ["edp_hash", "wall_time", "timings", "max_rss_mb", "jobs", "exit_code", "error"]

# read as text whatever they look like (an edp_hash such as 05426170e796 is not a number)
TEXT_COLUMNS = ["study", "case_id", "variant", "edp_hash", "error", "model", "method", "start", "farfield", "formulation",
                "status", "warnings", "timings"]

# statuses: hertz.edp's (README), then the driver's own
SOLVER_STATUSES = ["converged", "inaccurate", "roundoff", "stalled", "diverged", "maxiter"]
DRIVER_STATUSES = ["nan", "timeout", "failed"]
STATUSES = SOLVER_STATUSES + DRIVER_STATUSES
# worth running again with more time or after a fix elsewhere (--retry-failed)
RETRY_STATUSES = ["failed", "timeout"]

# hertz.edp's exit code for each of its statuses
EXIT_OF_STATUS = {"converged": 0, "inaccurate": 5, "roundoff": 3, "stalled": 3, "diverged": 3,
                  "maxiter": 3}


def study_columns(summary: list[str]) -> list[str]:
    return LEADING + list(summary) + TRAILING
