"""Where the cases of a sweep run: a pool of threads on this machine, or a Dask cluster.

Either way each submitted case comes back once, as a row; the table, the locks
and the progress bar stay with the sweep (sweeps.py).
"""
from __future__ import annotations

from collections.abc import Callable, Iterable
from concurrent.futures import Future, ThreadPoolExecutor, as_completed
from pathlib import Path
from typing import Any, Protocol

from driver.cases import Case
from driver.run import run_case


class Executor(Protocol):
    """Where the cases run: each submitted case comes back once, as a row."""

    def submit(self, case: Case, workdir: Path, timeout: float, study: str, summary: list[str],
               repeats: int) -> Any: ...

    def as_completed(self, futures: list) -> Iterable: ...

    def collect(self, future: Any, case: Case, workdir: Path, study: str, columns: list[str]) -> dict: ...

    def cancel(self, futures: list) -> None: ...

    def close(self) -> None: ...


class LocalPool:
    """Each case in a thread of this process, which starts and watches its solver."""

    def __init__(self, jobs: int):
        self.jobs = jobs
        self.pool = ThreadPoolExecutor(max_workers=jobs)

    def submit(self, case: Case, workdir: Path, timeout: float, study: str, summary: list[str],
               repeats: int) -> Future:
        return self.pool.submit(run_case, case, workdir, timeout, study, summary, self.jobs, repeats)

    def as_completed(self, futures: list) -> Iterable:
        return as_completed(futures)

    def collect(self, future: Future, case: Case, workdir: Path, study: str, columns: list[str]) -> dict:
        return future.result()  # run_case returns a row whatever happened

    def cancel(self, futures: list) -> None:
        for future in futures:
            future.cancel()

    def close(self) -> None:
        self.pool.shutdown(wait=True, cancel_futures=True)


def make_executor(jobs: int, scheduler: str | None = None, say: Callable[[str], None] | None = None) -> Executor:
    """The local pool, or with a scheduler (a Dask address, or local:N) a Dask cluster."""
    if not scheduler:
        return LocalPool(jobs)
    from driver.dask_backend import DaskExecutor  # Dask only when asked for
    return DaskExecutor(scheduler, say or print)
