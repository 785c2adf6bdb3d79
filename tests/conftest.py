"""Shared helpers: run hertz.edp directly, and the quick-sweep study tables."""
from __future__ import annotations

import functools
import subprocess
from dataclasses import dataclass
from pathlib import Path

import pandas as pd
import pytest

from driver import RESULTS_DIR
from driver.run import freefem_command, freefem_env
from driver.studies import STUDIES
from driver.sweep import sweep


@dataclass
class Solve:
    exit_code: int
    output: str
    outdir: Path

    @property
    def summary(self) -> dict:
        return pd.read_csv(self.outdir / "summary.csv").iloc[0].to_dict()

    def table(self, name: str) -> pd.DataFrame:
        return pd.read_csv(self.outdir / f"{name}.csv")


@functools.lru_cache(maxsize=None)
def _solve(args: tuple[str, ...], outdir: str) -> Solve:
    proc = subprocess.run(freefem_command(list(args), Path(outdir)),
                          capture_output=True, text=True, env=freefem_env(), timeout=600)
    return Solve(proc.returncode, proc.stdout + proc.stderr, Path(outdir))


@pytest.fixture(scope="session")
def solve(tmp_path_factory):
    """solve("-kpen", "1e5", ...) -> Solve; identical calls share one run."""
    root = tmp_path_factory.mktemp("runs")

    def run(*args: str) -> Solve:
        name = "_".join(a.strip("-") for a in args) or "default"
        return _solve(tuple(args), str(root / name))
    return run


@pytest.fixture(scope="session")
def studies() -> dict[str, pd.DataFrame]:
    """results/<study>.csv for every study; the quick sweep fills in missing or
    stale rows (a full sweep's rows are used as they are)."""
    tables = {}
    for name, make in STUDIES.items():
        frame = sweep(name, make(True), RESULTS_DIR, jobs=2, timeout=600, progress=False)
        tables[name] = frame
    return tables
