"""The solver's processes: a case's marker and pid file, killing a case, the
leftovers of a killed sweep, the subreaper that reaps orphans, and the lock of a
case folder.

The solver runs in its own process group with a marker in its environment; the
group is killed on timeout, and every process that still carries the marker
afterwards (a detached helper, or a leftover of a killed sweep, found again
through the pid file) is killed too. A case holds a lock on its folder while it
runs, so a leftover is only ever a dead run's, never a live one's. The solver
dies with the thread that started it (setpriv --pdeathsig). The sweep command
makes its process a child subreaper (become_subreaper), so that orphans of a
case stay within reach, and then reaps the ones that exit. Importing this
module changes nothing.
"""
from __future__ import annotations

import atexit
import contextlib
import ctypes
import fcntl
import os
import shutil
import signal
import threading
import time
from collections.abc import Iterator
from pathlib import Path

from driver import files
from driver.errors import HertzError

MARKER = "HERTZ_CASE_TOKEN"
PID_FILE = "freefem.pid"
LOCK_FILE = ".lock"

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
    """A killed sweep may have left this case's solver running and its NAME.part files
    half-written: kill the one, remove the others (a planted NAME.part link too, which
    the next run would write through). Call it only while holding the folder's lock:
    a live run holds that lock itself."""
    pid_file = workdir / PID_FILE
    try:
        pgid_text, token = pid_file.read_text().split()
        pgid = int(pgid_text)
        # a group is killed only while its leader carries the case's marker: a pid file
        # written by hand, or left while the pid went to another process, names no case
        killed = kill_case(token, pgid if pgid in processes_with(token) else None)
    except (OSError, ValueError):
        killed = 0
    pid_file.unlink(missing_ok=True)
    files.remove_part_files(workdir)
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
        try:
            self.workdir.mkdir(parents=True, exist_ok=True)
        except OSError as exc:  # a read-only results folder, or a plain file on the way
            raise HertzError(f"cannot create the work folder {self.workdir}: {exc.strerror}") from None
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


@contextlib.contextmanager
def children_waitable() -> Iterator[None]:
    """A process that ignores SIGCHLD has its children reaped by the kernel, so waiting
    for the solver fails (ECHILD) although it ran: restore the default while cases run.
    Only the main thread may change a handler; elsewhere it is left as it is."""
    if (threading.current_thread() is not threading.main_thread()
            or signal.getsignal(signal.SIGCHLD) is not signal.SIG_IGN):
        yield
        return
    signal.signal(signal.SIGCHLD, signal.SIG_DFL)
    try:
        yield
    finally:
        signal.signal(signal.SIGCHLD, signal.SIG_IGN)


def launcher() -> list[str]:
    # the solver dies with the thread that started it, whatever kills the driver
    setpriv = shutil.which("setpriv")
    return [setpriv, "--pdeathsig", "KILL", "--"] if setpriv else []


class Interrupted(KeyboardInterrupt):
    """SIGTERM or SIGHUP, handled like Ctrl-C."""
    signum = int(signal.SIGINT)


def _on_signal(signum, frame):  # noqa: ARG001
    interrupted = Interrupted(f"signal {signum}")
    interrupted.signum = signum  # the command exits 128 + signum, as a shell reports it
    raise interrupted


def install_signal_handlers() -> None:
    """SIGTERM and SIGHUP end a command as Ctrl-C does: its cases killed, what it kept said, and an
    earlier run's files brought back (a terminated hertz run had left them set aside)."""
    for sig in (signal.SIGTERM, signal.SIGHUP):
        signal.signal(sig, _on_signal)
    atexit.register(RUNNING.kill_all)
