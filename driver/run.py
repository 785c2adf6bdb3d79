"""Run one case of hertz.edp in its own directory and turn what happened into a row.

run_case never raises: a solver that crashes, hangs, writes garbage or cannot
start becomes a row with its status and message. The solver runs in its own
process group with a marker in its environment; the group is killed on timeout,
and every process that still carries the marker afterwards (a detached helper,
or a leftover of a killed sweep, found again through the pid file) is killed
too. The driver is a child subreaper, so orphans of a case stay within reach,
and the solver dies with the thread that started it (setpriv --pdeathsig).
"""
from __future__ import annotations

import ctypes
import math
import os
import shutil
import signal
import statistics
import subprocess
import threading
import time
import uuid
from pathlib import Path

import pandas as pd

from driver import freefem
from driver.cases import Case
from driver.schema import EXIT_OF_STATUS, TEXT_COLUMNS, study_columns

OUTPUT_FILES = ("summary.csv", "profile.csv", "history.csv", "axis.csv")
MARKER = "HERTZ_CASE_TOKEN"
PID_FILE = "freefem.pid"


def _become_subreaper() -> None:
    try:
        ctypes.CDLL(None, use_errno=True).prctl(36, 1, 0, 0, 0)  # PR_SET_CHILD_SUBREAPER
    except (OSError, AttributeError):
        pass


_become_subreaper()


def processes_with(token: str) -> list[int]:
    """Pids whose environment carries this case's marker."""
    found = []
    needle = f"{MARKER}={token}".encode()
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            if needle in (entry / "environ").read_bytes().split(b"\0"):
                found.append(int(entry.name))
        except OSError:
            continue
    return found


def kill_case(token: str, pgid: int | None = None) -> int:
    """Kill a case's process group and every process that carries its marker."""
    killed = 0
    if pgid:
        try:
            os.killpg(pgid, signal.SIGKILL)
            killed += 1
        except (ProcessLookupError, PermissionError):
            pass
    for pid in processes_with(token):
        try:
            os.kill(pid, signal.SIGKILL)
            killed += 1
        except (ProcessLookupError, PermissionError):
            continue
        if pid == pgid:
            continue  # the solver itself: run_case's own wait reaps it
        try:
            os.waitpid(pid, 0)  # an orphan handed to this subreaper: no zombie left
        except ChildProcessError:
            pass
    return killed


def reap_leftover(workdir: Path) -> int:
    """A killed sweep may have left this case's solver running: kill it."""
    pid_file = workdir / PID_FILE
    try:
        pgid_text, token = pid_file.read_text().split()
        killed = kill_case(token, int(pgid_text))
    except (OSError, ValueError):
        killed = 0
    pid_file.unlink(missing_ok=True)
    return killed


class Running:
    """The solver processes running now, so that a signal can stop them all."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._cases: dict[str, int] = {}

    def add(self, token: str, pgid: int) -> None:
        with self._lock:
            self._cases[token] = pgid

    def discard(self, token: str) -> None:
        with self._lock:
            self._cases.pop(token, None)

    def kill_all(self) -> None:
        with self._lock:
            cases = list(self._cases.items())
        for token, pgid in cases:
            kill_case(token, pgid)


RUNNING = Running()


def _launcher() -> list[str]:
    # the solver dies with the thread that started it, whatever kills the driver
    setpriv = shutil.which("setpriv")
    return [setpriv, "--pdeathsig", "KILL", "--"] if setpriv else []


def _empty_row(case: Case, study: str, columns: list[str]) -> dict:
    row: dict = {col: math.nan for col in columns}
    row.update(case.params)
    row.update(study=study, case_id=case.case_id, variant=case.variant,
               expect_converged=case.expect_converged, edp_hash=freefem.edp_hash())
    return row


def read_summary(path: Path, summary_columns: list[str]) -> tuple[dict | None, str]:
    """The one row of summary.csv, or None and why it is unusable."""
    if not path.is_file():
        return None, "no summary.csv" if not path.exists() else "summary.csv is not a file"
    try:
        frame = pd.read_csv(path, dtype={c: str for c in TEXT_COLUMNS})
    except (ValueError, UnicodeDecodeError, OSError) as exc:
        return None, f"summary.csv unreadable: {exc}".splitlines()[0][:200]
    if len(frame) != 1:
        return None, f"summary.csv has {len(frame)} data rows, not 1"
    if list(frame.columns) != summary_columns:
        unknown = sorted(set(frame.columns) - set(summary_columns))
        missing = sorted(set(summary_columns) - set(frame.columns))
        return None, f"summary.csv columns differ from hertz.edp's (unknown {unknown}, missing {missing})"
    row = frame.iloc[0].to_dict()
    for col in summary_columns:
        if col in TEXT_COLUMNS:
            continue
        value = row[col]
        if isinstance(value, str):
            return None, f"summary.csv: {col} is not a number: {value!r}"
    return row, ""


def _status(exit_code: int, summary: dict | None, why: str) -> tuple[str, str]:
    """The row's status and message from the exit code and the summary together."""
    if exit_code < 0:
        return "failed", f"killed by signal {-exit_code}"
    if summary is None:
        return "failed", why or f"exit code {exit_code} without summary.csv"
    status = str(summary.get("status"))
    if status not in EXIT_OF_STATUS:
        return "failed", f"unknown status {status!r} in summary.csv (exit code {exit_code})"
    if EXIT_OF_STATUS[status] != exit_code:
        return "failed", f"summary.csv says {status} but hertz.edp exited with {exit_code}"
    if status in ("converged", "inaccurate"):
        values = [summary.get(k) for k in ("p0_fe", "F_fe", "a_fe")]
        if any(not isinstance(v, (int, float)) or not math.isfinite(v) for v in values):
            return "nan", f"{status} but p0, F or a is not finite"
        return status, ""
    return status, f"{status} after {summary.get('iterations')} iterations, residual {summary.get('residual')}"


def _solver_error(log: Path) -> str:
    """The solver's own error line (hertz.edp's, or FreeFEM's), if it printed one."""
    try:
        lines = [ln.strip() for ln in log.read_text(errors="replace").splitlines() if ln.strip()]
    except OSError:
        return ""
    for line in lines:
        if line.startswith("hertz.edp: error:"):
            return line[:300]
    for line in lines:
        if line.startswith(("Exec error", "Compile error", "Error line")) or "Error" in line.split(":")[0]:
            return line[:300]
    return ""


def _last_output(log: Path) -> str:
    try:
        lines = [ln.strip() for ln in log.read_text(errors="replace").splitlines() if ln.strip()]
    except OSError:
        return ""
    return lines[-1][:200] if len(lines) > 1 else ""  # the first line is the command


def run_case(case: Case, workdir: Path, timeout: float, study: str = "",
             summary_columns: list[str] | None = None, jobs: int = 1, repeats: int = 1) -> dict:
    """Run hertz.edp for one case; always return a full row, whatever happened.
    With repeats > 1 the case runs that many times (the rest of the row is the
    last run's) and wall_time is the median of their times, listed in timings."""
    start = time.perf_counter()
    try:
        columns = summary_columns or freefem.summary_columns()
    except Exception as exc:  # noqa: BLE001 - a row is the answer to anything
        columns = []
        row = _empty_row(case, study, study_columns(columns))
        row.update(status="failed", error=f"cannot read hertz.edp's columns: {exc}"[:300])
        return row
    row = _empty_row(case, study, study_columns(columns))
    row["jobs"] = jobs
    times = []
    try:
        for _ in range(repeats):
            t0 = time.perf_counter()
            row.update(_run(case, workdir, timeout, columns))
            times.append(time.perf_counter() - t0)
            if row["status"] in ("timeout", "failed"):
                break
    except Exception as exc:  # noqa: BLE001 - a row is the answer to anything
        row.update(status="failed", error=f"driver error: {exc!r}"[:300])
    row["wall_time"] = statistics.median(times) if times else time.perf_counter() - start
    row["timings"] = ";".join(f"{t:.4f}" for t in times)
    row.update(study=study, case_id=case.case_id, variant=case.variant,
               expect_converged=case.expect_converged)
    return row


def _run(case: Case, workdir: Path, timeout: float, columns: list[str]) -> dict:
    workdir.mkdir(parents=True, exist_ok=True)
    reap_leftover(workdir)
    for name in OUTPUT_FILES:
        (workdir / name).unlink(missing_ok=True)
    cmd = _launcher() + freefem.command(case.args() + ["-out", str(workdir)])
    token = uuid.uuid4().hex
    env = freefem.freefem_env() | {MARKER: token}
    log_path = workdir / "freefem.log"
    timed_out = threading.Event()
    with open(log_path, "wb") as log:
        log.write((" ".join(cmd) + "\n").encode())
        log.flush()
        # output to a file, not a pipe: a helper that keeps the pipe open would
        # hold a finished case until its timeout
        proc = subprocess.Popen(cmd, cwd=workdir, stdout=log, stderr=subprocess.STDOUT,
                                env=env, start_new_session=True)
    (workdir / PID_FILE).write_text(f"{proc.pid} {token}\n")
    RUNNING.add(token, proc.pid)

    def expire() -> None:
        timed_out.set()
        kill_case(token, proc.pid)
    timer = threading.Timer(timeout, expire)
    timer.start()
    try:
        # a blocking wait returns the moment the solver exits (Popen.wait with
        # a timeout polls, up to 50 ms late), and wait4 gives its peak memory
        _, wait_status, usage = os.wait4(proc.pid, 0)
        proc.returncode = os.waitstatus_to_exitcode(wait_status)
    finally:
        timer.cancel()
        kill_case(token, proc.pid)  # helpers left in its group or detached
        RUNNING.discard(token)
        (workdir / PID_FILE).unlink(missing_ok=True)
    out: dict[str, object] = {"exit_code": proc.returncode, "max_rss_mb": usage.ru_maxrss / 1024}
    if timed_out.is_set():
        out.update(status="timeout", error=f"no result after {timeout:g} s")
        return out
    summary, why = read_summary(workdir / "summary.csv", columns)
    status, error = _status(proc.returncode, summary, why)
    if summary is not None:
        out.update(summary)
    if status == "failed":
        error = _solver_error(log_path) or error
        if summary is None and not error.startswith("hertz.edp"):
            error = f"{error}; last output: {_last_output(log_path)}"
    out.update(status=status, error=error)
    return out
