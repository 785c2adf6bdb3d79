"""Run one case of hertz.edp in its own folder and turn what happened into a row.

run_case never raises: a solver that crashes, hangs, writes garbage or cannot
start becomes a row with its status and message. How the solver's processes are
started, killed and reaped, and how a case folder is locked, is
driver/processes.py's. Importing this module changes nothing.
"""
from __future__ import annotations

import contextlib
import contextvars
import csv
import math
import os
import re
import shutil
import statistics
import subprocess
import tempfile
import threading
import time
import uuid
from collections.abc import Callable, Iterator
from pathlib import Path

from driver import freefem, schema
from driver.cases import Case
from driver.errors import SOLVER_ERROR, HertzError
from driver.processes import MARKER, PID_FILE, RUNNING, CaseLock, kill_case, launcher, reap_adopted, reap_leftover

LOG_FILE = "freefem.log"
MEMORY = "out-of-memory"  # hertz.edp's status for a mesh refused for its memory (no summary.csv)
# everything hertz.edp may write into -out (its CSV tables, and VTK files a user
# pointed there): removed before a run, so no earlier run's file passes for this one's
OUTPUT_SUFFIXES = (".csv", ".vtu")
MAX_TIMEOUT = 1e6  # seconds (11.6 days); threading's timers overflow not far above 1e9
SOLVER_WARNING = "hertz.edp: warning:"
SOLVER_PROGRESS = "hertz.edp: progress:"  # a long run's levels as they end (edp/lib/messages.idp)

# who is shown the solver's output as it comes (hertz run -v); set by the caller around
# one run, in its own thread: a sweep's worker threads never see it
_ECHO: contextvars.ContextVar[Callable[[str], None] | None] = contextvars.ContextVar("echo", default=None)


@contextlib.contextmanager
def echoing(say: Callable[[str], None]) -> Iterator[None]:
    """Runs started inside show each line of their log to say() as the solver writes it."""
    token = _ECHO.set(say)
    try:
        yield
    finally:
        _ECHO.reset(token)


def _follow(log_path: Path, say: Callable[[str], None], done: threading.Event) -> threading.Thread:
    """A thread that passes the log's lines to say() as they are written, until done and read."""
    def follow() -> None:
        with open(log_path, "rb") as log:
            pending = b""
            while True:
                finished = done.is_set()  # read once more after the solver exits: its last lines
                chunk = log.read()
                pending += chunk
                *lines, pending = pending.split(b"\n")
                for line in lines:
                    say(line.decode(errors="replace"))
                if finished and not chunk:
                    break
                if not chunk:
                    time.sleep(0.05)
            if pending:
                say(pending.decode(errors="replace"))
    thread = threading.Thread(target=follow, daemon=True)
    thread.start()
    return thread


def solver_warnings(log: Path) -> list[str]:
    """The warning lines hertz.edp wrote (on its stderr, in the log), in order."""
    try:
        text = log.read_text(errors="replace")
    except OSError:
        return []
    return [line.strip() for line in text.splitlines() if line.startswith(SOLVER_WARNING)]


def empty_row(case: Case, study: str, columns: list[str]) -> dict:
    row: dict = {col: math.nan for col in columns}
    row.update(case.params)
    row.update(study=study, case_id=case.case_id, variant=case.variant,
               expect_converged=case.expect_converged, edp_hash=freefem.edp_hash())
    return row


# what pandas reads as missing (a study table is read by pandas; a row must mean the same here)
_MISSING = frozenset({"", "nan", "-nan", "NaN", "-NaN", "NA", "N/A", "n/a", "NULL", "null", "None", "<NA>",
                      "#N/A", "#NA", "#N/A N/A", "1.#IND", "-1.#IND", "1.#QNAN", "-1.#QNAN"})
_INTEGER = re.compile(r"^[+-]?\d+$")


def _cell(text: str, word: bool) -> object:
    """One value of summary.csv as pandas would read it: a word, an int, a float, NaN for
    missing, else the text itself (which the caller refuses as not a number)."""
    if text in _MISSING:
        return math.nan
    if word:
        return text
    if _INTEGER.match(text):
        return int(text)
    if "_" not in text and text == text.strip():  # float() would take "1_0" and " 1"
        try:
            return float(text)
        except ValueError:
            pass
    return text


def read_summary(path: Path, summary_columns: list[str]) -> tuple[dict | None, str]:
    """The one row of summary.csv, or None and why it is unusable. Read with the csv module:
    pandas costs a single `hertz run` a quarter of a second to import."""
    if not path.is_file():
        return None, "no summary.csv" if not path.exists() else "summary.csv is not a file"
    try:
        with open(path, newline="", encoding="utf-8") as handle:
            lines = [line for line in csv.reader(handle) if line]
    except (ValueError, UnicodeDecodeError, OSError, csv.Error) as exc:
        return None, f"summary.csv unreadable: {exc}".splitlines()[0][:200]
    if not lines:
        return None, "summary.csv unreadable: it is empty"
    header, rows = lines[0], lines[1:]
    if len(rows) != 1:
        return None, f"summary.csv has {len(rows)} data rows, not 1"
    if header != summary_columns:
        unknown = sorted(set(header) - set(summary_columns))
        missing = sorted(set(summary_columns) - set(header))
        return None, f"summary.csv columns differ from hertz.edp's (unknown {unknown}, missing {missing})"
    if len(rows[0]) > len(header):
        return None, f"summary.csv unreadable: its row has {len(rows[0])} fields for {len(header)} columns"
    text = schema.text_columns()
    values = rows[0] + [""] * (len(header) - len(rows[0]))  # a short row: the rest missing, as pandas reads it
    row = {col: _cell(value, col in text) for col, value in zip(header, values)}
    for col in summary_columns:
        if col not in text and isinstance(row[col], str):
            return None, f"summary.csv: {col} is not a number: {row[col]!r}"
    return row, ""


def _status(exit_code: int, summary: dict | None, why: str) -> tuple[str, str]:
    """The row's status and message from the exit code and the summary together."""
    if exit_code < 0:
        return "failed", f"killed by signal {-exit_code}"
    if summary is None:
        # a mesh that would not fit is refused before it is built: no files, its own code
        if exit_code == freefem.exit_code(MEMORY):
            return MEMORY, ""
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
        if line.startswith(SOLVER_ERROR):
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


EARLIER = ".earlier-"  # the folder an earlier run's files wait in while a new run runs
UNANSWERED_LOG = "freefem.unanswered.log"  # the log of a run that gave no answer, beside the files it did not replace
UNANSWERED_FOLDER = "unanswered"  # the files of such a run (diverged, maxiter, ...), where it wrote any


def earlier_files(workdir: Path) -> list[Path]:
    return [p for p in workdir.iterdir() if (p.suffix in OUTPUT_SUFFIXES or p.name in (LOG_FILE, UNANSWERED_LOG))
            and (p.is_file() or p.is_symlink())]


def clear_outputs(workdir: Path) -> None:
    """Remove what an earlier run left: a file from it must not pass for this run's."""
    for path in earlier_files(workdir):
        path.unlink()
    (workdir / PID_FILE).unlink(missing_ok=True)


def set_aside(workdir: Path) -> Path | None:
    """Move what an earlier run left into a fresh folder of its own (a file from it must not pass
    for this run's); settle() brings it back if this run gives no answer. A folder a killed driver
    left is settled first."""
    for left in workdir.glob(EARLIER + "*"):
        settle(workdir, left)
    (workdir / PID_FILE).unlink(missing_ok=True)
    earlier = earlier_files(workdir)
    if not earlier:
        return None
    aside = Path(tempfile.mkdtemp(prefix=EARLIER, dir=workdir))
    for path in earlier:
        path.rename(aside / path.name)
    return aside


def answered_files(folder: Path) -> bool:
    """The folder's summary.csv holds an answer (converged or inaccurate)."""
    try:
        with open(folder / "summary.csv", newline="") as f:
            return next(csv.DictReader(f), {}).get("status") in schema.ANSWERED
    except (OSError, csv.Error, UnicodeDecodeError):
        return False


def settle(workdir: Path, aside: Path | None) -> None:
    """After a run: its answer (a summary.csv) replaces the earlier files. A run without one, or
    one that is no answer (diverged, maxiter, ...) after an earlier answer, never destroys it: the
    earlier files come back whole, and this run's log is kept beside them as UNANSWERED_LOG (its
    files, if it wrote any, in UNANSWERED_FOLDER)."""
    if aside is None or not aside.is_dir() or aside.is_symlink():
        return
    wrote = (workdir / "summary.csv").is_file()
    if not wrote or (not answered_files(workdir) and answered_files(aside)):
        unanswered = workdir / UNANSWERED_FOLDER
        if wrote:
            clear_unanswered(workdir)
            unanswered.mkdir()
        for path in earlier_files(workdir):  # what the run left
            if path.name == LOG_FILE:
                path.replace(workdir / UNANSWERED_LOG)
            elif wrote:
                path.replace(unanswered / path.name)
            else:
                path.unlink()
        for path in aside.iterdir():
            if path.is_file() and not path.is_symlink() and path.name != UNANSWERED_LOG:
                path.replace(workdir / path.name)
    else:  # an answer, or a first run: what an earlier unanswered run left goes
        clear_unanswered(workdir)
    shutil.rmtree(aside, ignore_errors=True)


def clear_unanswered(workdir: Path) -> None:
    unanswered = workdir / UNANSWERED_FOLDER
    if unanswered.is_symlink() or unanswered.is_file():
        unanswered.unlink()
    shutil.rmtree(unanswered, ignore_errors=True)


def _run(case: Case, workdir: Path, timeout: float, columns: list[str], extra: tuple[str, ...]) -> dict:
    reap_leftover(workdir)
    aside = set_aside(workdir)
    try:
        return _solve(case, workdir, timeout, columns, extra)
    finally:
        settle(workdir, aside)


def _solve(case: Case, workdir: Path, timeout: float, columns: list[str], extra: tuple[str, ...]) -> dict:
    cmd = launcher() + freefem.command(case.args() + list(extra) + ["-out", str(workdir)])
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
            # (restore_signals=False: SIGXFSZ stays ignored, as Python keeps it, so a write past a
            # file-size limit fails and the solver says so with exit 4, where the signal killed it)
            proc = subprocess.Popen(cmd, cwd=workdir, stdout=log, stderr=subprocess.STDOUT,
                                    env=env, start_new_session=True, restore_signals=False)
            RUNNING.cases[token] = proc.pid
    (workdir / PID_FILE).write_text(f"{proc.pid} {token}\n")
    say, exited = _ECHO.get(), threading.Event()
    follower = _follow(log_path, say, exited) if say is not None else None

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
        exited.set()
        if follower is not None:
            follower.join(timeout=5)
    out: dict[str, object] = {"exit_code": proc.returncode, "max_rss_mb": usage.ru_maxrss / 1024}
    if timed_out.is_set():
        out.update(status="timeout", error=f"no result after {timeout:g} s")
        return out
    summary, why = read_summary(workdir / "summary.csv", columns)
    status, error = _status(proc.returncode, summary, why)
    if summary is not None:
        out.update(summary)
    if status in ("failed", MEMORY):
        error = solver_error(log_path) or error
        if summary is None and not error.startswith("hertz.edp"):
            error = f"{error}; last output: {_last_output(log_path)}"
    out.update(status=status, error=error)
    return out


def rejected(row: dict) -> bool:
    """hertz.edp refused the case's input (its one error line is the row's error)."""
    return (row.get("status") == "failed" and row.get("exit_code") == freefem.exit_code("rejected")
            and str(row.get("error", "")).startswith(SOLVER_ERROR))
