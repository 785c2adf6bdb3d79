"""Where things are: the solver scripts, and the names inside a results folder.

The solver scripts are the checkout's edp/ when the package runs from a clone
(an editable install, or `python -m driver` in the repository); a non-editable
install carries its own copy inside the package (setup.py puts it there).
A results folder is the user's: commands take it relative to their working
directory (./results by default), never relative to this package.
"""
from __future__ import annotations

import os
from pathlib import Path

PACKAGE_DIR = Path(__file__).resolve().parent
_CHECKOUT_EDP = PACKAGE_DIR.parent / "edp"
EDP_DIR = _CHECKOUT_EDP if (_CHECKOUT_EDP / "hertz.edp").is_file() else PACKAGE_DIR / "edp"
ENTRY = "hertz.edp"

DEFAULT_RESULTS = "results"  # resolved against the working directory when a command starts

# inside a results folder
RUNS = "runs"                # runs/<study>/<case_id>/: one folder per case
SINGLE = "single"            # runs/single/<case_id>/: hertz run and solve()
FIELD = "field"              # runs/field/: hertz field
STALE = "stale"              # rows of other solver code, bad lines, replaced rows
LOCAL = "local"              # untracked outputs (make run, bench, quick sweeps)
ENVIRONMENT_FILE = "sweep_environment.csv"
REPORT_FILE = "REPORT.md"

# a study's table is <name>.csv and its kept files <name>/: no study may take a name these use
RESERVED_NAMES = frozenset({RUNS, SINGLE, FIELD, STALE, LOCAL, "bench", Path(ENVIRONMENT_FILE).stem,
                            Path(REPORT_FILE).stem})


CACHE_FOLDER = "hertz-contact"


def cache_dir() -> Path:
    """The user's cache folder (hertz.edp's answers to -options, -columns, -exits):
    $XDG_CACHE_HOME/hertz-contact, else ~/.cache/hertz-contact. Never the package's
    folder, which a system install may not let its users write."""
    base = os.environ.get("XDG_CACHE_HOME", "")
    # the XDG specification: a relative value is invalid and is ignored
    return (Path(base) if os.path.isabs(base) else Path.home() / ".cache") / CACHE_FOLDER


def user_path(text: str | Path) -> Path:
    """A path as the user typed it, made absolute against their working directory once,
    before anything starts (a relative path handed on would be read from elsewhere)."""
    return Path(os.path.abspath(Path(text).expanduser()))  # abspath: "a/../b" is b, links stay links


def study_csv(results_dir: Path, study: str) -> Path:
    return results_dir / f"{study}.csv"


def study_lock(results_dir: Path, study: str) -> Path:
    return results_dir / f"{study}.lock"


def work_root(results_dir: Path, study: str) -> Path:
    return results_dir / RUNS / study
