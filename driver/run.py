"""Run one case of hertz.edp in its own folder and turn what happened into a row.

run_case never raises: a solver that crashes, hangs, writes garbage or cannot
start becomes a row with its status and message. The solver runs in its own
process group with a marker in its environment; the group is killed on timeout,
and every process that still carries the marker afterwards (a detached helper,
or a leftover of a killed sweep, found again through the pid file) is killed
too. A case holds a lock on its folder while it runs, so a leftover is only
ever a dead run's, never a live one's. The solver dies with the thread that
started it (setpriv --pdeathsig). The sweep command makes its process a
child subreaper (become_subreaper), so that orphans of a case stay within
reach, and then reaps the ones that exit. Importing this module changes
nothing.
"""
from __future__ import annotations

import ctypes
import fcntl
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

from driver import files, freefem, schema
from driver.cases import Case
from driver.errors import HertzError

MARKER = "HERTZ_CASE_TOKEN"
PID_FILE = "freefem.pid"
LOG_FILE = "freefem.log"
LOCK_FILE = ".lock"
# everything hertz.edp may write into -out (its CSV tables, and VTK files a user
# pointed there): removed before a run, so no earlier run's file passes for this one's
OUTPUT_SUFFIXES = (".csv", ".vtu")
MAX_TIMEOUT = 1e6  # seconds (11.6 days); threading's timers overflow not far above 1e9

_PR_SET_CHILD_SUBREAPER = 36
_subreaper = False


REAP_EVERY = 0.5  # seconds between looks for exited orphans


def become_subreaper() -> bool:
    """Orphans of the cases this process runs are handed to it, not to init (Linux):
    they stay within reach of kill_case, and a thread reaps those that exit."""
    global _subreaper
    if _subreaper:
        return True
    try:
        _subreaper = ctypes.CDLL(None, use_errno=True).prctl(_PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0) == 0
    except (OSError, AttributeError):
        _subreaper = False
    if _subreaper:
        threading.Thread(target=_reap_forever, name="reaper", daemon=True).start()
    return _subreaper


def _reap_forever() -> None:
    while True:
        time.sleep(REAP_EVERY)
        reap_adopted()


def _stat(pid: str) -> tuple[str, int, int] | None:
    """(state, parent pid, session id) of a process, from /proc."""
    try:
        text = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return None
    fields = text[text.rfind(")") + 2:].split()  # the command name may hold spaces
    return fields[0], int(fields[1]), int(fields[3])


def reap_adopted() -> int:
    """Reap the exited orphans this subreaper adopted. Only zombies outside this process's
    session qualify, and not a solver run_case is waiting for: the driver's own
    children (git, dask's processes) are waited for by their owners."""
    if not _subreaper:
        return 0
    me, my_session = os.getpid(), os.getsid(0)
    reaped = 0
    with RUNNING.lock:  # a solver being started is registered before it can exit
        waited = set(RUNNING.cases.values())
        for entry in Path("/proc").iterdir():
            if not entry.name.isdigit() or int(entry.name) in waited:
                continue
            stat = _stat(entry.name)
            if stat is None or stat[0] != "Z" or stat[1] != me or stat[2] == my_session:
                continue
            try:
                os.waitpid(int(entry.name), os.WNOHANG)
                reaped += 1
            except ChildProcessError:
                pass
    return reaped


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
    """A killed sweep may have left this case's solver running: kill it. Call it only
    while holding the folder's lock: a live run holds that lock itself."""
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
        self.lock = threading.Lock()
        self.cases: dict[str, int] = {}

    def discard(self, token: str) -> None:
        with self.lock:
            self.cases.pop(token, None)

    def kill_all(self) -> None:
        with self.lock:
            cases = list(self.cases.items())
        for token, pgid in cases:
            kill_case(token, pgid)


RUNNING = Running()


class Busy(HertzError):
    """Another run holds this case folder."""


class CaseLock:
    """Exclusive and non-blocking, on <workdir>/.lock: one run per case folder at a time.
    The kernel drops it when its process dies, so a held lock means a live run."""

    def __init__(self, workdir: Path):
        self.workdir = workdir
        self.fd: int | None = None

    def __enter__(self) -> CaseLock:
        files.refuse_symlink(self.workdir, "work folder")
        self.workdir.mkdir(parents=True, exist_ok=True)
        files.refuse_symlink(self.workdir, "work folder")
        path = self.workdir / LOCK_FILE
        try:
            fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW, 0o644)
        except OSError as exc:
            raise HertzError(f"cannot lock {self.workdir}: {exc.strerror}") from None
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            os.close(fd)
            raise Busy(f"another run is using {self.workdir}") from None
        self.fd = fd
        return self

    def __exit__(self, *exc) -> None:
        assert self.fd is not None
        os.close(self.fd)


def _launcher() -> list[str]:
    # the solver dies with the thread that started it, whatever kills the driver
    setpriv = shutil.which("setpriv")
    return [setpriv, "--pdeathsig", "KILL", "--"] if setpriv else []


def empty_row(case: Case, study: str, columns: list[str]) -> dict:
    row: dict = {col: math.nan for col in columns}
    row.update(case.params)
    row.update(study=study, case_id=case.case_id, variant=case.variant,
               expect_converged=case.expect_converged, edp_hash=freefem.edp_hash())
    return row


def read_summary(path: Path, summary_columns: list[str]) -> tuple[dict | None, str]:
    """The one row of summary.csv, or None and why it is unusable."""
    if not path.is_file():
        return None, "no summary.csv" if not path.exists() else "summary.csv is not a file"
    text = schema.text_columns()
    try:
        frame = pd.read_csv(path, dtype={c: str for c in text})
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
        if col in text:
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
    table = freefem.exits()
    if status not in table:
        return "failed", f"unknown status {status!r} in summary.csv (exit code {exit_code})"
    if table[status].code != exit_code:
        return "failed", f"summary.csv says {status} but hertz.edp exited with {exit_code}"
    if status in schema.ANSWERED:
        if not schema.answered(summary):
            return "nan", f"{status} but p0, F or a is not finite"
        return status, ""
    return status, f"{status} after {summary.get('iterations')} iterations, residual {summary.get('residual')}"


def solver_error(log: Path) -> str:
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
             summary_columns: list[str] | None = None, jobs: int = 1, repeats: int = 1,
             extra: tuple[str, ...] = (), lock: bool = True) -> dict:
    """Run hertz.edp for one case; always return a full row, whatever happened.
    With repeats > 1 the case runs that many times (the rest of the row is the
    last run's) and wall_time is the median of their times, listed in timings.
    extra: options that are not part of the case (-vtk PATH). lock=False: the
    caller holds the folder's CaseLock already."""
    start = time.perf_counter()
    workdir = workdir.absolute()  # the solver runs inside it: a relative -out would point elsewhere
    try:
        columns = summary_columns or freefem.summary_columns()
    except Exception as exc:  # noqa: BLE001 - a row is the answer to anything
        row = empty_row(case, study, schema.study_columns([]))
        row.update(status="failed", error=f"cannot read hertz.edp's columns: {exc}"[:300])
        return row
    row = empty_row(case, study, schema.study_columns(columns))
    row["jobs"] = jobs
    times = []
    try:
        if not 0 < timeout <= MAX_TIMEOUT:
            raise HertzError(f"timeout must be in (0, {MAX_TIMEOUT:g}] seconds, got {timeout!r}")
        held = CaseLock(workdir) if lock else None
        if held is not None:
            held.__enter__()
        try:
            for _ in range(repeats):
                t0 = time.perf_counter()
                row.update(_run(case, workdir, timeout, columns, extra))
                times.append(time.perf_counter() - t0)
                if row["status"] in ("timeout", "failed"):
                    break
        finally:
            if held is not None:
                held.__exit__()
    except HertzError as exc:
        row.update(status="failed", error=str(exc)[:300])
    except Exception as exc:  # noqa: BLE001 - a row is the answer to anything
        row.update(status="failed", error=f"driver error: {exc!r}"[:300])
    row["wall_time"] = statistics.median(times) if times else time.perf_counter() - start
    row["timings"] = ";".join(f"{t:.4f}" for t in times)
    row.update(study=study, case_id=case.case_id, variant=case.variant,
               expect_converged=case.expect_converged)
    return row


def clear_outputs(workdir: Path) -> None:
    """Remove what an earlier run left: a file from it must not pass for this run's."""
    for path in workdir.iterdir():
        if path.suffix in OUTPUT_SUFFIXES or path.name in (LOG_FILE, PID_FILE):
            if path.is_file() or path.is_symlink():
                path.unlink()


def _run(case: Case, workdir: Path, timeout: float, columns: list[str], extra: tuple[str, ...]) -> dict:
    reap_leftover(workdir)
    clear_outputs(workdir)
    cmd = _launcher() + freefem.command(case.args() + list(extra) + ["-out", str(workdir)])
    token = uuid.uuid4().hex
    env = freefem.freefem_env() | {MARKER: token}
    log_path = workdir / LOG_FILE
    timed_out = threading.Event()
    with open(log_path, "wb") as log:
        log.write((" ".join(cmd) + "\n").encode())
        log.flush()
        with RUNNING.lock:  # registered before it can exit: reap_adopted leaves it to us
            # output to a file, not a pipe: a helper that keeps the pipe open would
            # hold a finished case until its timeout
            proc = subprocess.Popen(cmd, cwd=workdir, stdout=log, stderr=subprocess.STDOUT,
                                    env=env, start_new_session=True)
            RUNNING.cases[token] = proc.pid
    (workdir / PID_FILE).write_text(f"{proc.pid} {token}\n")

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
        reap_adopted()
    out: dict[str, object] = {"exit_code": proc.returncode, "max_rss_mb": usage.ru_maxrss / 1024}
    if timed_out.is_set():
        out.update(status="timeout", error=f"no result after {timeout:g} s")
        return out
    summary, why = read_summary(workdir / "summary.csv", columns)
    status, error = _status(proc.returncode, summary, why)
    if summary is not None:
        out.update(summary)
    if status == "failed":
        error = solver_error(log_path) or error
        if summary is None and not error.startswith("hertz.edp"):
            error = f"{error}; last output: {_last_output(log_path)}"
    out.update(status=status, error=error)
    return out


def rejected(row: dict) -> bool:
    """hertz.edp refused the case's input (its one error line is the row's error)."""
    return (row.get("status") == "failed" and row.get("exit_code") == freefem.exit_code("rejected")
            and str(row.get("error", "")).startswith("hertz.edp: error:"))
