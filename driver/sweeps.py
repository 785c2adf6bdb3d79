"""Run the cases of studies in parallel into their tables, row by row, resumably.

Each case runs in its own folder, <results>/runs/<study>/<case_id>/. Finished
cases are appended to <results>/<study>.csv as they arrive (studytable.py); running
the same command again runs only the missing cases. A rerun (--force,
--retry-failed) replaces a case's row when it lands, so an interrupted rerun
keeps every old row it did not replace. A lock keeps two sweeps off one table.
Costly cases start first and the progress bar counts predicted cost, not
cases, so its ETA holds. Ctrl-C, SIGTERM and SIGHUP stop the running solvers
and keep every finished row. The cases run in a local thread pool or on a Dask
cluster (executors.py).
"""
from __future__ import annotations

import os
import platform
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from contextlib import ExitStack
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
from tqdm import tqdm

from driver import files, freefem, layout, studytable
from driver.cases import Case
from driver.errors import SweepError, TableError
from driver.executors import Executor, make_executor
from driver.processes import RUNNING, children_waitable
from driver.schema import RETRY_STATUSES, study_columns
from driver.studies import STUDIES, load_spec

LARGE_GRID = 10_000     # cases; more need --yes
LARGEST_GRID = 1_000_000  # cases; more cannot be held as a plan at all


def check_writable(results_dir: Path) -> None:
    try:
        results_dir.mkdir(parents=True, exist_ok=True)
        with tempfile.NamedTemporaryFile(dir=results_dir, prefix=".write-test-"):
            pass
    except OSError as exc:
        raise SweepError(f"results folder {results_dir} is not writable: {exc.strerror}") from None


def predicted_cost(case: Case) -> float:
    """Relative cost of a case: its degrees of freedom (the mesh grows as n^2),
    times the extra solves of the slower methods."""
    n = float(case.get("n", 16))
    dofs = n * n * (8.0 if case.get("order", 2) == 2 else 2.0) + 200.0
    factor = {"fixedpoint": 4.0, "uzawa": 2.0}.get(str(case.get("method", "newton")), 1.0)
    return dofs * factor


@dataclass
class Outcome:
    study: str
    table: pd.DataFrame
    ran: int
    unexpected: list[tuple[str, str]] = field(default_factory=list)  # case_id, status
    messages: list[str] = field(default_factory=list)


def plan(study: str, cases: list[Case], results_dir: Path, force: bool = False,
         retry_failed: bool = False) -> tuple[list[Case], list[str]]:
    """The cases still to run (costly first), after repairing the table; messages say
    what changed. The caller holds the study's lock. Cases to run again keep their
    rows until their reruns land."""
    columns = study_columns(freefem.summary_columns())
    path = layout.study_csv(results_dir, study)
    unique = list({c.case_id: c for c in cases}.values())
    frame, messages = studytable.prepare(path, columns, freefem.edp_hash())
    ids = {c.case_id for c in unique}
    redo: set[str] = set()
    if force:
        redo = ids & set(frame["case_id"])
    elif retry_failed:
        redo = ids & set(frame.loc[frame["status"].isin(RETRY_STATUSES), "case_id"])
    done = set(frame["case_id"]) - redo
    todo = [c for c in unique if c.case_id not in done]
    todo.sort(key=predicted_cost, reverse=True)
    return todo, messages


@dataclass
class Job:
    """One study to sweep: its name, its cases and the per-case files it keeps."""

    study: str
    cases: list[Case]
    keep: tuple[str, ...] = ()
    repeats: int = 1


def jobs_from(names: list[str] | None = None, spec: Path | None = None, quick: bool = False,
              yes: bool = False) -> list[Job]:
    """The jobs of named studies, or of one spec file; its grid is counted before it is built."""
    if spec is not None:
        if names:
            raise SweepError("--spec runs one grid; give no study names or --all with it")
        grid = load_spec(spec)
        _check_size(grid.count, yes)  # before building: a product of axes can be astronomical
        return [Job(grid.name, grid.cases())]
    if not names:
        raise SweepError("name at least one study, or use --all or --spec")
    jobs = []
    for name in dict.fromkeys(names):  # a name given twice is swept once (its lock is held once)
        if name not in STUDIES:
            raise SweepError(f"unknown study '{name}'; known: {', '.join(STUDIES)}")
        study = STUDIES[name]
        jobs.append(Job(name, study.make(quick), study.keep, study.repeats))
    _check_size(sum(len(j.cases) for j in jobs), yes)
    return jobs


def _check_size(count: int, yes: bool) -> None:
    if count > LARGEST_GRID:
        raise SweepError(f"{count:.3g} cases: a grid above {LARGEST_GRID:.0e} cannot be planned; split it")
    if count > LARGE_GRID and not yes:
        raise SweepError(f"{count} cases: a grid above {LARGE_GRID} needs --yes")


def _check_folders(results_dir: Path, study: str) -> None:
    """Nothing a sweep writes may be a planted symbolic link."""
    for path, what in ((layout.study_csv(results_dir, study), "table"),
                       (layout.study_lock(results_dir, study), "lock"),
                       (results_dir / layout.RUNS, "work folder"),
                       (layout.work_root(results_dir, study), "work folder"),
                       (results_dir / study, "folder"),
                       (results_dir / layout.STALE, "folder")):
        files.refuse_symlink(path, what, SweepError)


def run_studies(jobs_list: list[Job], results_dir: Path, jobs: int, timeout: float,
                force: bool = False, retry_failed: bool = False, progress: bool = False,
                say: Callable[[str], None] | None = None, scheduler: str | None = None) -> list[Outcome]:
    """Sweep several studies under one progress bar, holding their locks throughout.
    With a scheduler (a Dask address, or local:N) the cases run on its workers."""
    say = say or print
    if scheduler:
        from driver.dask_backend import parse_local
        try:
            parse_local(scheduler)  # a bad address is refused before anything waits on it
        except ValueError as exc:
            raise SweepError(str(exc)) from None
    results_dir = layout.user_path(results_dir)
    freefem.check_freefem()
    for job in jobs_list:
        studytable.check_name(job.study)
    check_writable(results_dir)
    for job in jobs_list:
        _check_folders(results_dir, job.study)
    columns = study_columns(freefem.summary_columns())
    outcomes = []
    with ExitStack() as locks:
        locks.enter_context(children_waitable())
        for job in jobs_list:
            locks.enter_context(studytable.StudyLock(layout.study_lock(results_dir, job.study)))
        plans = []
        for job in jobs_list:
            todo, messages = plan(job.study, job.cases, results_dir, force, retry_failed)
            for message in messages:
                say(message)
            plans.append((job, todo, messages))
        total = sum(predicted_cost(c) * job.repeats for job, todo, _ in plans for c in todo)
        # connect only when there is work: a finished sweep needs no cluster
        executor = make_executor(jobs, scheduler, say) if total else None
        if executor is not None:
            locks.callback(executor.close)
        bar = tqdm(total=total, disable=not progress, unit="", dynamic_ncols=True,
                   bar_format="{l_bar}{bar}| {percentage:3.0f}% [{elapsed}<{remaining}]{postfix}")
        try:
            for job, todo, messages in plans:
                path = layout.study_csv(results_dir, job.study)
                ran = _run_all(job.study, todo, path, columns, layout.work_root(results_dir, job.study),
                               executor, timeout, bar, job.repeats) if executor else 0
                if ran:
                    record_environment(results_dir, job.study)
                    # reruns landed: their cases' earlier rows go to stale/
                    for message in studytable.prepare(path, columns, freefem.edp_hash())[1]:
                        say(message)
                frame = studytable.read(path)
                ids = {c.case_id for c in job.cases}
                mine = frame[frame["case_id"].isin(ids)] if len(frame) else frame
                if job.keep and len(mine):
                    gather(job.study, results_dir, mine, job.keep)
                expected = {c.case_id for c in job.cases if c.expect_converged}
                unexpected = [(r.case_id, r.status) for r in mine.itertuples()
                              if r.case_id in expected and r.status != "converged"]
                outcomes.append(Outcome(job.study, mine, ran, unexpected, messages))
        finally:
            bar.close()
    return outcomes


def sweep(study: str, cases: list[Case], results_dir: Path, jobs: int, timeout: float,
          force: bool = False, retry_failed: bool = False, keep: tuple[str, ...] = (),
          scheduler: str | None = None) -> Outcome:
    """One study, no progress bar (tests, scripts)."""
    return run_studies([Job(study, cases, keep)], results_dir, jobs, timeout, force, retry_failed,
                       scheduler=scheduler)[0]


def _run_all(study: str, todo: list[Case], path: Path, columns: list[str], workroot: Path,
             executor: Executor, timeout: float, bar: tqdm | None, repeats: int = 1) -> int:
    if not todo:
        return 0
    summary = freefem.summary_columns()
    pending: dict[Any, Case] = {}
    done = 0
    try:
        for case in todo:
            pending[executor.submit(case, workroot / case.case_id, timeout, study, summary, repeats)] = case
        for future in executor.as_completed(list(pending)):
            case = pending.pop(future)
            row = executor.collect(future, case, workroot / case.case_id, study, columns)
            try:
                studytable.append_row(path, row, columns)
            except TableError as exc:
                raise SweepError(f"{exc}; the rows written so far are kept") from None
            done += 1
            if bar is not None:
                bar.update(predicted_cost(case) * repeats)
                bar.set_postfix_str(f"{study}: {row['status']}", refresh=False)
    except BaseException:
        # Ctrl-C, a signal or a full disk: stop the running cases, record none of them
        executor.cancel(list(pending))
        RUNNING.kill_all()
        raise
    return done


def gather(study: str, results_dir: Path, rows: pd.DataFrame, keep: tuple[str, ...]) -> None:
    """Collect the kept per-case files of the study's rows into results/<study>/<file>,
    keeping earlier data of cases whose work folder is gone (a fresh clone)."""
    target_dir = results_dir / study
    files.refuse_symlink(target_dir, "folder", SweepError)
    target_dir.mkdir(exist_ok=True)
    ids = set(rows["case_id"])
    for name in keep:
        target = target_dir / name
        old = studytable.read(target) if target.exists() else pd.DataFrame()
        parts = []
        fresh = set()
        for case_id in sorted(ids):  # one order on every run: the file changes only with its data
            source = layout.work_root(results_dir, study) / case_id / name
            if source.is_file() and not source.is_symlink() and source.stat().st_size > 0:
                try:
                    part = pd.read_csv(source)
                except (ValueError, OSError):
                    continue
                parts.append(part.assign(case_id=case_id))
                fresh.add(case_id)
        if len(old):
            parts.insert(0, old[old["case_id"].isin(ids - fresh)])
        if parts:
            combined = pd.concat(parts, ignore_index=True).sort_values("case_id", kind="stable")
            cols = ["case_id"] + [c for c in combined.columns if c != "case_id"]
            studytable.write_atomically(target, combined[cols].to_csv(index=False))


def _command_output(cmd: list[str]) -> str:
    try:
        return subprocess.run(cmd, capture_output=True, text=True, check=False, timeout=30).stdout
    except (OSError, subprocess.SubprocessError):
        return ""


def _version(packages: list[str], prefix: str) -> str:
    """The version of the first installed package whose line starts with prefix."""
    return next((p.split()[1] for p in packages if p.startswith(prefix) and len(p.split()) > 1), "unknown")


ENVIRONMENT_ROWS = 200  # the record keeps the newest rows: a make rerun adds one a study


def record_environment(results_dir: Path, study: str) -> None:
    """What each sweep of a study ran on, appended to the record (the report shows the newest row;
    it runs nothing itself)."""
    from driver import __version__
    packages = _command_output(["dpkg-query", "-W", "-f=${Package} ${Version}\n", "freefem++",
                                "libmumps-seq-*", "libcholmod*", "libopenblas0-*"]).split("\n")
    cpu = next((ln.split(":", 1)[1].strip() for ln in _command_output(["cat", "/proc/cpuinfo"]).splitlines()
                if ln.startswith("model name")), platform.machine())
    env = {"date": time.strftime("%Y-%m-%d"), "study": study, "version": __version__,
           "commit": _command_output(["git", "-C", str(freefem.EDP_DIR), "rev-parse", "--short", "HEAD"]).strip()
           or "unknown",
           "solver code": freefem.edp_hash(),
           "FreeFEM": _version(packages, "freefem++ "),
           "MUMPS": _version(packages, "libmumps"),
           "CHOLMOD": _version(packages, "libcholmod"),
           "OpenBLAS": _version(packages, "libopenblas0"),
           "OpenBLAS kernels": freefem.freefem_env().get("OPENBLAS_CORETYPE", "detected"),
           "Python": platform.python_version(), "numpy": np.__version__, "pandas": pd.__version__,
           "CPU": f"{cpu}, {cores()} cores"}
    target = results_dir / layout.ENVIRONMENT_FILE
    studytable.refuse_symlink(target, "environment record")
    try:
        earlier = pd.read_csv(target, dtype=str, keep_default_na=False) if target.is_file() else pd.DataFrame()
    except (OSError, ValueError):
        earlier = pd.DataFrame()  # an unreadable record is started anew
    record = pd.concat([earlier, pd.DataFrame([env], dtype=str)], ignore_index=True).tail(ENVIRONMENT_ROWS)
    studytable.write_atomically(target, record.reindex(columns=list(env)).to_csv(index=False))


def report_unexpected(outcomes: list[Outcome], stream=sys.stderr, limit: int = 20) -> int:
    """Name the cases that should have converged and did not; return how many."""
    bad = [(o.study, case_id, status) for o in outcomes for case_id, status in o.unexpected]
    for study, case_id, status in bad[:limit]:
        print(f"not converged: {study}/{case_id}: {status}", file=stream)
    if len(bad) > limit:
        print(f"... and {len(bad) - limit} more", file=stream)
    return len(bad)


def cores() -> int:
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
