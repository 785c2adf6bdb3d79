"""Run a list of cases in parallel into one study CSV, row by row, resumable.

The CSV is append-only while a sweep runs: each finished case is one line,
flushed and fsynced, so an interrupted sweep keeps every finished case. A lock
file keeps two sweeps from writing the same study at once.
"""
from __future__ import annotations

import csv
import fcntl
import io
import os
import signal
import tempfile
from concurrent.futures import FIRST_COMPLETED, ThreadPoolExecutor, wait
from pathlib import Path

import pandas as pd
from tqdm import tqdm

from driver.cases import Case
from driver.run import check_freefem, edp_hash, run_case
from driver.schema import STUDY_COLUMNS


class SweepError(RuntimeError):
    """A sweep that cannot start; the message says why."""


def study_csv(results_dir: Path, study: str) -> Path:
    return results_dir / f"{study}.csv"


def load_study(path: Path) -> pd.DataFrame:
    if not path.exists() or path.stat().st_size == 0:
        return pd.DataFrame(columns=STUDY_COLUMNS)
    return pd.read_csv(path)


def check_writable(results_dir: Path) -> None:
    try:
        results_dir.mkdir(parents=True, exist_ok=True)
        with tempfile.NamedTemporaryFile(dir=results_dir, prefix=".write-test-"):
            pass
    except OSError as exc:
        raise SweepError(f"results directory {results_dir} is not writable: {exc.strerror}") from None


class StudyLock:
    """Exclusive, non-blocking: a second sweep of the same study refuses to start."""

    def __init__(self, path: Path):
        self.path = path
        self.handle = None

    def __enter__(self):
        self.handle = open(self.path, "a+")
        try:
            fcntl.flock(self.handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            self.handle.close()
            raise SweepError(f"another sweep is writing {self.path.with_suffix('.csv').name}; "
                             "wait for it to finish") from None
        return self

    def __exit__(self, *exc):
        fcntl.flock(self.handle, fcntl.LOCK_UN)
        self.handle.close()


def _rewrite(path: Path, frame: pd.DataFrame) -> None:
    tmp = path.with_suffix(".csv.part")
    frame.to_csv(tmp, index=False)
    os.replace(tmp, path)


def prepare(path: Path, current_hash: str) -> pd.DataFrame:
    """Drop a truncated last line (a killed sweep) and move stale rows aside."""
    if not path.exists():
        return pd.DataFrame(columns=STUDY_COLUMNS)
    raw = path.read_bytes()
    if raw and not raw.endswith(b"\n"):
        path.write_bytes(raw[: raw.rfind(b"\n") + 1])
    header = path.read_text().split("\n", 1)[0].split(",")
    frame = load_study(path) if header == STUDY_COLUMNS else None
    stale_dir = path.parent / "stale"
    if frame is None:
        stale_dir.mkdir(exist_ok=True)
        os.replace(path, stale_dir / f"{path.stem}-old-columns.csv")
        return pd.DataFrame(columns=STUDY_COLUMNS)
    stale = frame["edp_hash"].astype(str) != current_hash
    if stale.any():
        stale_dir.mkdir(exist_ok=True)
        for h, rows in frame[stale].groupby(frame["edp_hash"].astype(str)):
            rows.to_csv(stale_dir / f"{path.stem}-{h}.csv", index=False)
        frame = frame[~stale]
        _rewrite(path, frame)
    return frame


def append_row(path: Path, row: dict) -> None:
    new = not path.exists() or path.stat().st_size == 0
    buf = io.StringIO()
    writer = csv.DictWriter(buf, fieldnames=STUDY_COLUMNS, lineterminator="\n")
    if new:
        writer.writeheader()
    writer.writerow({k: row.get(k) for k in STUDY_COLUMNS})
    with open(path, "a") as f:
        f.write(buf.getvalue())
        f.flush()
        os.fsync(f.fileno())


def sweep(study: str, cases: list[Case], results_dir: Path, jobs: int, timeout: float,
          force: bool = False, progress: bool = True) -> pd.DataFrame:
    """Run the cases not yet in results/<study>.csv; return the whole study table."""
    check_freefem()
    check_writable(results_dir)
    path = study_csv(results_dir, study)
    current = edp_hash()
    unique = list({c.case_id: c for c in cases}.values())
    with StudyLock(path.with_suffix(".lock")):
        frame = prepare(path, current)
        if force:
            frame = frame[~frame["case_id"].isin([c.case_id for c in unique])]
            _rewrite(path, frame)
        done = set(frame["case_id"])
        todo = [c for c in unique if c.case_id not in done]
        _run_all(study, todo, path, results_dir / "runs" / study, jobs, timeout, progress)
    return load_study(path)


def _run_all(study, todo, path, workroot, jobs, timeout, progress) -> None:
    if not todo:
        return
    procs: set = set()
    failures = 0
    bar = tqdm(total=len(todo), desc=study, unit="case", disable=not progress, dynamic_ncols=True)
    pool = ThreadPoolExecutor(max_workers=jobs)
    pending = {pool.submit(run_case, c, workroot / c.case_id, timeout, study, procs): c for c in todo}
    try:
        while pending:
            finished, _ = wait(pending, return_when=FIRST_COMPLETED)
            for future in finished:
                pending.pop(future)
                row = future.result()
                append_row(path, row)
                failures += row["status"] != "converged"
                bar.update(1)
                bar.set_postfix(not_converged=failures)
    except BaseException:
        # Ctrl-C or a crash: stop the running cases and record none of them
        for future in pending:
            future.cancel()
        for proc in list(procs):
            try:
                os.killpg(proc.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
        raise
    finally:
        pool.shutdown(wait=True, cancel_futures=True)
        bar.close()
