"""Sweeps on a Dask cluster: each case is one task that runs run_case on a worker.

The client keeps the table, the locks, the progress bar and the per-case
folders (sweeps.py); a worker runs the case in its own scratch directory and
sends back the row with the case's CSV files and freefem.log. Workers need
FreeFEM and this repository at the same commit (make setup); the client checks
the solver code of the workers it sees and of every row that comes back.

A task that raises is retried (retries=), a task whose worker died is
rescheduled by Dask on another worker, and one that still fails becomes a
failure row, so a case is never dropped. Dask cannot stop a running task's
thread, so the task watches its own state on the worker and kills its solver
when it is cancelled (Ctrl-C on the client, or the client gone).
"""
from __future__ import annotations

import asyncio
import concurrent.futures
import logging
import shutil
import signal
import socket
import threading
import uuid
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from driver import files, freefem
from driver.cases import Case
from driver.errors import HertzError, SweepError
from driver.processes import CaseLock, reap_leftover
from driver.run import (
    LOG_FILE,
    UNANSWERED_FOLDER,
    answered_files,
    clear_outputs,
    clear_unanswered,
    empty_row,
    run_case,
)
from driver.schema import ANSWERED

LOCAL_PREFIX = "local:"
RETRIES = 2           # a task that raised runs again, on any worker
CANCEL_POLL = 0.2     # seconds between a running task's looks at its own state
SCHEDULER_LOST = ("scheduler-connection-lost", "scheduler-restart")  # reasons of a cancelled future


REMOTE_SCHEMES = ("tcp", "tls", "ws", "wss", "ucx")  # Dask's, but inproc: (its own process only)


def check_address(address: str) -> None:
    """Refuse at once an address no scheduler can have (ValueError): a scheme other than
    Dask's network ones, or a port outside 1..65535 (which Dask would wait 30 s on)."""
    scheme, sep, rest = address.partition("://")
    if not sep:
        scheme, rest = "tcp", address  # Dask reads host:port as tcp://host:port
    if scheme not in REMOTE_SCHEMES:
        raise ValueError(f"a scheduler address is SCHEME://HOST:PORT (SCHEME one of {', '.join(REMOTE_SCHEMES)}) "
                         f"or local:N, got {address!r}")
    host, colon, port = rest.rpartition(":")
    if colon and not port.isdigit() and "]" not in port:
        raise ValueError(f"the port in {address!r} must be a whole number in 1..65535")
    if colon and port.isdigit() and not 1 <= int(port) <= 65535:
        raise ValueError(f"the port in {address!r} must be in 1..65535, got {port}")
    if not (host if colon else rest).strip("[]"):
        raise ValueError(f"no host in the scheduler address {address!r}")


def parse_local(address: str) -> int | None:
    """N for 'local:N' (a LocalCluster of N single-threaded workers), else None after
    checking the address (check_address)."""
    if not address.startswith(LOCAL_PREFIX):
        check_address(address)
        return None
    text = address[len(LOCAL_PREFIX):]
    if not text.isdigit() or int(text) < 1:
        raise ValueError(f"N in local:N must be a positive integer, got {address!r}")
    return int(text)


def connect_timeout() -> float:
    """Seconds to wait for a scheduler: Dask's own setting (distributed.comm.timeouts.connect)."""
    import dask.config
    from dask.utils import parse_timedelta
    return float(parse_timedelta(dask.config.get("distributed.comm.timeouts.connect"), default="seconds"))


def probe(address: str, timeout: float) -> None:
    """Connect and shake hands once, within timeout seconds. Dask's Client waits for
    the handshake without a limit, so a port that speaks something else (the
    dashboard's HTTP) would hang it forever. In a thread of its own: the caller
    may have an event loop running already."""
    from distributed.comm import connect

    async def shake() -> None:
        comm = await asyncio.wait_for(connect(address, timeout=timeout), timeout)
        await comm.close()
    with concurrent.futures.ThreadPoolExecutor(1) as pool:
        try:
            pool.submit(asyncio.run, shake()).result()
        except TimeoutError:
            raise SweepError(f"no Dask scheduler answered at {address} within {timeout:g} s (the scheduler's "
                             "port, usually 8786, not its dashboard's)") from None
        except Exception as exc:  # noqa: BLE001 - whatever the comm layer raises is one line for the user
            why = " ".join(f"{type(exc).__name__}: {exc}".split())
            hint = " (tls:// needs Dask's TLS settings, distributed.comm.tls.*)" if address.startswith("tls") else ""
            raise SweepError(f"cannot reach the Dask scheduler at {address}: {why}{hint}") from None


def _worker_facts(dask_worker: Any) -> dict[str, Any]:
    """Runs on each worker: what the client must agree with, and where it runs."""
    return {"edp_hash": freefem.edp_hash(), "freefem": shutil.which(freefem.FREEFEM) or "",
            "host": socket.gethostname(), "nthreads": dask_worker.state.nthreads}


def _kill_when_cancelled(worker: Any, key: str, workdir: Path, finished: threading.Event) -> None:
    while not finished.wait(CANCEL_POLL):
        task = worker.state.tasks.get(key)
        if task is None or task.state == "cancelled":
            # each look kills again: a solver started after the first kill dies too
            reap_leftover(workdir)


def run_on_worker(case: Case, study: str, sweep_id: str, timeout: float, summary_columns: list[str],
                  jobs: int, repeats: int) -> dict:
    """The task: run_case in the worker's scratch space, then the row and the files as data.
    jobs 0: the client saw no worker, so this worker's threads stand for its host's."""
    from distributed import get_worker
    worker = get_worker()
    key = worker.get_current_task()
    jobs = jobs or worker.state.nthreads
    workdir = Path(worker.local_directory) / "hertz" / sweep_id / study / case.case_id
    finished = threading.Event()
    watcher = threading.Thread(target=_kill_when_cancelled, args=(worker, key, workdir, finished), daemon=True)
    watcher.start()
    try:
        row = run_case(case, workdir, timeout, study, summary_columns, jobs, repeats)
        outputs = {p.name: p.read_bytes() for p in sorted(workdir.glob("*"))
                 if p.is_file() and not p.is_symlink() and (p.suffix == ".csv" or p.name == LOG_FILE)}
    finally:
        finished.set()
        watcher.join()
        shutil.rmtree(workdir, ignore_errors=True)
    return {"row": row, "files": outputs, "worker": worker.address}


def _quiet_on_ctrl_c(start):
    """Start local worker processes that ignore Ctrl-C: the terminal sends it to
    them too, and the client cancels their tasks and stops them anyway (an
    ignored signal stays ignored in a child; a Ctrl-C during the start is lost)."""
    if threading.current_thread() is not threading.main_thread():
        return start()
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        return start()
    finally:
        signal.signal(signal.SIGINT, previous)


def failure_row(case: Case, study: str, columns: list[str], error: str) -> dict:
    row = empty_row(case, study, columns)
    row.update(status="failed", error=error[:300], timings="")
    return row


def _write_file(path: Path, data: bytes) -> None:
    try:
        files.write_bytes_atomically(path, data, SweepError)
    except SweepError as exc:
        raise SweepError(f"{exc}; the rows written so far are kept") from None


class DaskExecutor:
    """Cases as Dask tasks: the same calls as sweep.LocalPool."""

    def __init__(self, address: str, say=print):
        try:
            from distributed import Client, LocalCluster
        except ImportError:
            raise SweepError("--scheduler needs Dask: pip install -e '.[dask]'") from None
        self.cluster = None
        try:
            workers = parse_local(address)
        except ValueError as exc:
            raise SweepError(str(exc)) from None
        try:
            if workers is not None:
                # any free port for its web server: another local cluster may hold 8787. Logs only
                # at CRITICAL: on close the scheduler may leave before a slow worker's last heartbeat,
                # which Dask logs as an ERROR with a traceback; a case's own failure comes back as
                # its row, never through these logs
                self.cluster = _quiet_on_ctrl_c(lambda: LocalCluster(n_workers=workers, threads_per_worker=1,
                                                                     processes=True, dashboard_address=":0",
                                                                     silence_logs=logging.CRITICAL))
                self.client = Client(self.cluster)
            else:
                timeout = connect_timeout()
                probe(address, timeout)
                self.client = Client(address, timeout=timeout)
        except SweepError:
            raise
        except Exception as exc:  # noqa: BLE001 - one line for the user, whatever Dask raised
            if self.cluster is not None:
                self.cluster.close()
            why = " ".join(f"{type(exc).__name__}: {exc}".split())
            raise SweepError(f"cannot reach the Dask scheduler at {address}: {why}") from None
        self.sweep_id = uuid.uuid4().hex[:12]
        self.edp_hash = freefem.edp_hash()
        try:
            self.jobs = self._check_workers(say)
        except BaseException:
            self.close()
            raise

    def _check_workers(self, say) -> int:
        """Refuse workers with other solver code or no FreeFEM; return the most
        solver threads on one host (the row's jobs: cases that may share a
        machine), 0 if no worker has come yet."""
        try:
            facts = self.client.run(_worker_facts)
        except ImportError as exc:
            raise SweepError(f"a Dask worker cannot import the driver ({exc}): install this repository "
                             "on every worker (make setup)") from None
        for address, fact in sorted(facts.items()):
            if fact["edp_hash"] != self.edp_hash:
                raise SweepError(f"Dask worker {address} runs other solver code (edp_hash {fact['edp_hash']}, "
                                 f"here {self.edp_hash}): install the same commit on every worker")
            if not fact["freefem"]:
                raise SweepError(f"Dask worker {address}: FreeFem++ is not on PATH; {freefem.SETUP_HINT}")
        if not facts:
            say("no Dask worker yet: the cases wait for one")
        per_host: dict[str, int] = {}
        for fact in facts.values():
            per_host[fact["host"]] = per_host.get(fact["host"], 0) + int(fact["nthreads"])
        return max(per_host.values(), default=0)

    def submit(self, case: Case, workdir: Path, timeout: float, study: str, summary: list[str], repeats: int):
        # impure: the same case submitted again is a new run, never a cached result;
        # in submission order, so costly cases start first
        return self.client.submit(run_on_worker, case, study, self.sweep_id, timeout, summary, self.jobs, repeats,
                                  key=f"hertz-{study}-{case.case_id}-{uuid.uuid4().hex[:8]}", pure=False,
                                  retries=RETRIES)

    def as_completed(self, futures: list) -> Iterator:
        from distributed import as_completed
        return iter(as_completed(futures))

    def collect(self, future, case: Case, workdir: Path, study: str, columns: list[str]) -> dict:
        """The case's row, its files written into workdir; a lost or failed task is a failure row."""
        try:
            result = future.result()
        except Exception as exc:  # noqa: BLE001 - a row is the answer to anything
            why = " ".join(f"{type(exc).__name__}: {exc}".split())  # one line: the table is read line by line
            # without a scheduler every pending case would fail: stop, and resume later instead
            if getattr(exc, "reason", "") in SCHEDULER_LOST or self.client.status != "running":
                raise SweepError(f"lost the Dask scheduler ({why}); the rows written so far are kept, "
                                 "run the same command to resume") from None
            result = {"row": failure_row(case, study, columns, f"Dask task lost: {why}"), "files": {}}
        row = result["row"]
        if row.get("edp_hash") != self.edp_hash:
            return failure_row(case, study, columns, f"Dask worker {result.get('worker')} runs other solver "
                               f"code (edp_hash {row.get('edp_hash')}): install the same commit on every worker")
        try:
            with CaseLock(workdir):
                reap_leftover(workdir)  # a local sweep killed earlier may have left its solver here
                # an answer replaces the earlier run's files; a run without one leaves them, and
                # one that is no answer after an answer goes to its own folder (as run.settle)
                target = workdir
                if "summary.csv" in result["files"]:
                    if row.get("status") in ANSWERED or not answered_files(workdir):
                        clear_outputs(workdir)
                        clear_unanswered(workdir)
                    else:
                        target = workdir / UNANSWERED_FOLDER
                        clear_unanswered(workdir)
                        target.mkdir()
                for name, data in result["files"].items():
                    if Path(name).name == name and not name.startswith("."):
                        _write_file(target / name, data)
        except HertzError as exc:
            return failure_row(case, study, columns, str(exc))
        return row

    def cancel(self, futures: list) -> None:
        """Ctrl-C: drop the queued tasks; the running ones see it and kill their solvers."""
        try:
            self.client.cancel(futures)
        except Exception:  # noqa: BLE001 - the scheduler may be gone already; the workers see the client leave
            pass

    def close(self) -> None:
        self.client.close()
        if self.cluster is not None:
            self.cluster.close()

    def __enter__(self) -> DaskExecutor:
        return self

    def __exit__(self, *exc) -> None:
        self.close()
