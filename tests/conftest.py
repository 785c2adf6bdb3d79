"""Shared helpers: run hertz.edp directly, and the quick studies swept into a temporary directory.

Tests never write into the repository: every run and sweep goes under pytest's
temporary directories.
"""
from __future__ import annotations

import functools
import subprocess
from dataclasses import dataclass
from pathlib import Path

import pandas as pd
import pytest

from driver import freefem, table
from driver.studies import STUDIES
from driver.sweep import Job, run_studies


@dataclass
class Solve:
    exit_code: int
    stdout: str
    stderr: str
    outdir: Path

    @property
    def output(self) -> str:
        return self.stdout + self.stderr

    @property
    def summary(self) -> dict:
        return pd.read_csv(self.outdir / "summary.csv").iloc[0].to_dict()

    def table(self, name: str) -> pd.DataFrame:
        return pd.read_csv(self.outdir / f"{name}.csv")


@functools.cache
def _solve(args: tuple[str, ...], outdir: str, with_out: bool, timeout: float) -> Solve:
    extra = ["-out", outdir] if with_out else []
    proc = subprocess.run(freefem.command(list(args) + extra), capture_output=True, text=True,
                          env=freefem.freefem_env(), timeout=timeout)
    return Solve(proc.returncode, proc.stdout, proc.stderr, Path(outdir))


@pytest.fixture(scope="session")
def solve(tmp_path_factory):
    """solve("-kpen", "1e5", ...) -> Solve with its files in a temporary -out
    directory; identical calls share one run. out=False leaves -out off; a run
    beyond timeout seconds fails the test (subprocess.TimeoutExpired)."""
    root = tmp_path_factory.mktemp("runs")

    def run(*args: str, out: bool = True, timeout: float = 600) -> Solve:
        name = "_".join(a.strip("-").replace("/", "_") for a in args) or "default"
        return _solve(tuple(args), str(root / name[:150]), out, timeout)
    return run


@pytest.fixture(scope="session")
def quick_results(tmp_path_factory) -> Path:
    """Every quick study swept into a temporary results directory (about 25 s on 2 cores)."""
    results = tmp_path_factory.mktemp("results")
    jobs = [Job(name, study.make(True), study.keep, study.repeats) for name, study in STUDIES.items()]
    run_studies(jobs, results, jobs=2, timeout=600)
    return results


@pytest.fixture(scope="session")
def studies(quick_results) -> dict[str, pd.DataFrame]:
    return {name: table.read(quick_results / f"{name}.csv") for name in STUDIES}


# Tests never write into the repository: the session fails if git sees a change.
def _git_status() -> str:
    from driver import ROOT
    return subprocess.run(["git", "status", "--porcelain"], cwd=ROOT, capture_output=True,
                          text=True).stdout


def pytest_sessionstart(session):
    session.config.git_status_before = _git_status()


def pytest_sessionfinish(session, exitstatus):
    after = _git_status()
    if after != session.config.git_status_before:
        print(f"\nthe tests changed the repository:\n{after}")
        session.exitstatus = 1
