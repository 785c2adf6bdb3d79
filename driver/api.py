"""The Python API: one case (solve) or a study (sweep), as `hertz run` and `hertz sweep` do them.

    >>> from driver import solve, sweep
    >>> result = solve(kpen=1e5)                 # hertz.edp -kpen 1e5, files in ./results/runs/single/
    >>> result.status, result.p0, result.exit_code
    ('converged', 1.39881..., 0)
    >>> table = sweep("kpen", quick=True)        # a pandas DataFrame, one row per case

Option names are hertz.edp's (`hertz options` lists them); values are checked
against its option table before anything runs. Bad input raises OptionError,
a case hertz.edp itself refuses raises RejectedError (both ValueErrors, and
HertzErrors with a one-line message); a run that fails otherwise is a Result
with its status and error.
"""
from __future__ import annotations

import math
import os
import shutil
import sys
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from driver import freefem, layout, schema
from driver.cases import Case
from driver.errors import HertzError, OptionError, RejectedError
from driver.files import refuse_symlink
from driver.processes import LOCK_FILE, Busy, CaseLock, children_waitable
from driver.run import LOG_FILE, MAX_TIMEOUT, UNANSWERED_LOG, rejected, run_case

if TYPE_CHECKING:  # only annotations use it: hertz run does not load pandas
    import pandas as pd

DEFAULT_TIMEOUT = 600.0


@dataclass(frozen=True)
class Result:
    """One run of hertz.edp: how it ended, its main numbers and where its files are."""

    status: str      # hertz.edp's (converged, inaccurate, roundoff, ...) or the driver's (nan, timeout, failed)
    exit_code: int   # hertz.edp's exit code for that status (its -exits table)
    p0: float        # peak contact pressure
    F: float         # force (plane: per unit length)
    a: float         # contact radius (plane: half-width; 3d: semi-axis along x)
    b: float         # 3d: semi-axis along y; NaN in 2D
    estimated_error: float  # the run's own estimate of its max relative error (no Hertz)
    files: Path      # the run's folder: summary.csv, profile.csv, history.csv, path.csv, axis.csv, freefem.log
    error: str       # why it did not converge ("" if it did)
    row: Mapping[str, Any] = field(repr=False, compare=False)  # every column, as in a study table

    @property
    def answered(self) -> bool:
        """Converged or inaccurate, with finite p0, F and a."""
        return schema.answered(self.row)

    @classmethod
    def of(cls, row: dict, files: Path) -> Result:
        def number(key: str) -> float:
            value = row.get(key)
            return float(value) if isinstance(value, (int, float)) and not isinstance(value, bool) else math.nan
        return cls(status=str(row.get("status")), exit_code=schema.exit_code_of(row), p0=number("p0_fe"),
                   F=number("F_fe"), a=number("a_fe"), b=number("b_fe"),
                   estimated_error=number("accuracy_predicted"), files=files,
                   error=str(row.get("error") or ""), row=dict(row))


def _check_timeout(timeout: float, prefix: str = "") -> None:
    if isinstance(timeout, bool) or not isinstance(timeout, (int, float)) or not 0 < timeout <= MAX_TIMEOUT:
        raise OptionError(f"{prefix}timeout must be a number of seconds in (0, {MAX_TIMEOUT:g}], got {timeout!r}")


def _folder(value: object, label: str) -> Path:
    """A folder argument as an absolute path; OptionError for anything that is not a path."""
    if not isinstance(value, (str, os.PathLike)) or not str(value):
        raise OptionError(f"{label} must be a folder (a str or a Path), got {value!r}")
    return layout.user_path(Path(value))


def _missing_folders(path: Path) -> list[Path]:
    """The folders on the way to path that do not exist yet, deepest first."""
    missing = []
    while not path.exists() and not path.is_symlink() and path != path.parent:
        missing.append(path)
        path = path.parent
    return missing


def _check_out(out: Path, label: str) -> None:
    """A folder the user names is used only if it is new, empty, or an earlier run's:
    the run clears the CSV and VTU files there first."""
    if out.is_symlink():
        raise OptionError(f"{label}out {out} is a symbolic link; give the folder itself")
    if out.exists() and not out.is_dir():
        raise OptionError(f"{label}out {out} is not a folder")
    if out.is_dir() and any(out.iterdir()) and not (out / LOG_FILE).exists():
        raise OptionError(f"{label}out {out} holds files that no run of hertz wrote; give a new or empty folder")


def _run_single(case: Case, workdir: Path, timeout: float, extra: tuple[str, ...], unique: bool,
                fresh: bool = False) -> tuple[dict, Path]:
    """Run in workdir, or (unique) in the first of workdir, workdir.2, ... that no other run holds
    (fresh: that does not exist yet, so that an earlier run's files stay its own)."""
    for k in range(1, 1000 if unique else 2):
        candidate = workdir if k == 1 else workdir.with_name(f"{workdir.name}.{k}")
        if fresh and candidate.exists():
            continue
        missing = _missing_folders(candidate)
        try:
            with CaseLock(candidate):
                row = run_case(case, candidate, timeout, study=layout.SINGLE, extra=extra, lock=False)
        except Busy:
            continue
        if rejected(row):
            # a refused run leaves nothing behind: no folder, no log
            if candidate in missing:
                shutil.rmtree(candidate, ignore_errors=True)
            else:  # (an earlier run's files came back with its log: the refused run's is set apart)
                refused_log = UNANSWERED_LOG if (candidate / UNANSWERED_LOG).exists() else LOG_FILE
                for name in (refused_log, LOCK_FILE):
                    (candidate / name).unlink(missing_ok=True)
            for folder in missing:
                if folder != candidate:
                    try:
                        folder.rmdir()
                    except OSError:
                        pass
        return row, candidate
    if not unique:
        raise HertzError(f"another run is using {workdir}")
    raise HertzError(f"every work folder for this case under {workdir.parent} is in use")


def solve_case(options: Mapping[str, object], timeout: float = DEFAULT_TIMEOUT,
               results: str | Path = layout.DEFAULT_RESULTS, prefix: str = "", fresh: bool = False) -> Result:
    """solve() with the option names shown as the caller typed them (prefix "--" for hertz run);
    fresh: a folder of its own, never an earlier run's (solve())."""
    _check_timeout(timeout, prefix)
    _folder(results, f"{prefix}results")  # before anything runs
    table = freefem.options()
    case_values: dict[str, object] = {}
    paths: dict[str, Path] = {}
    for name, value in options.items():
        if name in table and table[name].kind == "path":
            table[name].parse(value, f"{prefix}{name}")
            paths[name] = layout.user_path(str(value))
        elif name in freefem.RUN_ONLY:
            raise OptionError(f"{prefix}{name} is not a case option (hertz.edp -{name} does it)")
        else:
            case_values[name] = value
    case = Case.of(**freefem.parse_options(case_values, prefix))
    extra = tuple(arg for name, path in paths.items() if name != "out" for arg in (f"-{name}", str(path)))
    with children_waitable():
        if "out" in paths:
            _check_out(paths["out"], prefix)
            row, files = _run_single(case, paths["out"], timeout, extra, unique=False)
        else:
            root = _folder(results, f"{prefix}results")
            single = layout.work_root(root, layout.SINGLE)
            # as a sweep does: a planted link on the way would send the run's files anywhere
            for path in (root / layout.RUNS, single, single / case.case_id):
                refuse_symlink(path, "work folder", OptionError)
            row, files = _run_single(case, single / case.case_id, timeout, extra, unique=True, fresh=fresh)
    if rejected(row):
        raise RejectedError(str(row["error"]))
    return Result.of(row, files)


def solve(*, timeout: float = DEFAULT_TIMEOUT, results: str | Path = layout.DEFAULT_RESULTS,
          **options: object) -> Result:
    """Run hertz.edp once with these options (names without the dash: kpen=1e5,
    method="lagrange", vtk="fields.vtu", out="folder") and return its Result.

    The run's files go to <results>/runs/single/<case_id>/, or, where an earlier
    run's are, to the first of <case_id>.2, .3, ... that is new (each Result
    keeps its own files), or to `out`. Relative paths are
    taken from the working directory. Raises OptionError or RejectedError for
    bad input; every other outcome is a Result."""
    return solve_case(options, timeout, results, fresh=True)


def sweep(study: str | Path, *, cases: Iterable[Mapping[str, object]] | None = None, quick: bool = False,
          results: str | Path = layout.DEFAULT_RESULTS, jobs: int | None = None,
          timeout: float = DEFAULT_TIMEOUT, force: bool = False, retry_failed: bool = False,
          scheduler: str | None = None, yes: bool = False) -> pd.DataFrame:
    """Run a study into <results>/<study>.csv, resumably, and return its rows (one per case).

    study: a built-in study's name ("kpen", ...; quick=True for its small subset),
    a spec file (TOML or JSON, a Path or a name ending in .toml/.json), or, with
    `cases` (option dicts), the name of a study of your own. Cases already in
    the table are not run again unless force (or retry_failed for failed and
    timed-out ones). scheduler: a Dask address or local:N."""
    from driver import sweeps  # the sweep machinery only when a sweep is asked for
    from driver.studies import STUDIES, case_of
    results_dir = _folder(results, "results")
    if cases is not None:
        if isinstance(cases, (str, bytes, Mapping)) or not isinstance(cases, Iterable):
            raise OptionError(f"cases must be a list of option dicts, got {type(cases).__name__} {cases!r:.80}")
        if str(study) in STUDIES:  # its table is the built-in study's: no foreign rows in it
            raise OptionError(f"sweep('{study}', cases=...): '{study}' is a built-in study; name yours another way")
        job = sweeps.Job(str(study), [case_of(c, str(study), f"cases[{k}]") for k, c in enumerate(cases)])
        if not job.cases:
            raise OptionError("cases is empty: give at least one option dict (cases=[{}] is the default scene)")
    elif isinstance(study, Path) or str(study).endswith((".toml", ".json")):
        job = sweeps.jobs_from(spec=layout.user_path(study), yes=yes)[0]
    else:
        job = sweeps.jobs_from(names=[str(study)], quick=quick, yes=yes)[0]
    _check_timeout(timeout)
    if jobs is not None and (isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1):
        raise OptionError(f"jobs must be a positive integer, got {jobs!r}")
    outcome = sweeps.run_studies([job], results_dir, jobs or sweeps.cores(), timeout, force,
                                 retry_failed, say=lambda message: print(message, file=sys.stderr),
                                 scheduler=scheduler)[0]
    # in the order the cases were asked (the table holds them in the order they finished),
    # then the table's other cases
    order = {case.case_id: k for k, case in enumerate(job.cases)}
    table = outcome.table.reset_index(drop=True)
    rank = table["case_id"].map(order).fillna(len(order))
    return table.iloc[rank.argsort(kind="stable")].reset_index(drop=True)
