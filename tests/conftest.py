"""Shared helpers and the suite's rules.

- solve: run hertz.edp directly; quick_results: every quick study swept into a
  temporary folder. Tests never write into the repository: every run and sweep
  goes under pytest's temporary folders, and the session fails if git sees a change.
- Tiers: tests of SLOW_MODULES, and tests that use the swept quick studies, are
  marked slow; `make test-fast` leaves them out, `make test` (CI) runs everything.
- Skips: every skip says why (-rs), and a skip whose reason is not in
  ALLOWED_SKIPS fails the session (CI must not pass by not testing), unless
  HERTZ_ALLOW_SKIPS=1 is set for a machine that lacks an optional tool.
"""
from __future__ import annotations

import contextlib
import fcntl
import functools
import io
import os
import re
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import pandas as pd
import pytest

from driver import freefem, studytable
from driver.cases import Case
from driver.run import run_case
from driver.studies import STUDIES
from driver.sweeps import Job, run_studies

REPO = Path(__file__).resolve().parent.parent
FAKE = Path(__file__).with_name("fake_freefem.py")

SLOW_MODULES = {"test_dask_backend", "test_install", "test_readme_commands", "test_study_results",
                "test_3d", "test_fuzz", "test_scale_free", "test_reliability"}
SLOW_FIXTURES = {"quick_results", "studies"}

# skips that do not fail the session, each with the reason it is acceptable
ALLOWED_SKIPS = {
    # README commands that recompute whole studies run only while the committed
    # tables are current; when they are stale test_repo fails instead
    r"committed results are stale": "make sweep would recompute every study (hours); test_repo flags it",
    # documented commands test_readme_commands does not run, each listed there with its reason
    r"^not run: ": "a command of the README or docs/ in test_readme_commands.EXCEPTIONS",
}


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
    folder; identical calls share one run. out=False leaves -out off; a run
    beyond timeout seconds fails the test (subprocess.TimeoutExpired)."""
    root = tmp_path_factory.mktemp("runs")

    def run(*args: str, out: bool = True, timeout: float = 600) -> Solve:
        name = "_".join(a.strip("-").replace("/", "_") for a in args) or "default"
        return _solve(tuple(args), str(root / name[:150]), out, timeout)
    return run


@pytest.fixture(scope="session")
def quick_results(tmp_path_factory) -> Path:
    """Every quick study swept into a temporary results folder (about 40 s on 2 cores), once for
    the whole session: under pytest-xdist the workers share it through their common temporary
    folder, the first to need it sweeping while a later one waits on the lock (the tests only
    read it, or copy it)."""
    # (a worker's base folder is the session's, one level down; without xdist it is the session's)
    base = tmp_path_factory.getbasetemp()
    shared = base.parent if os.environ.get("PYTEST_XDIST_WORKER") else base
    results, done = shared / "quick_results", shared / "quick_results.done"
    with open(shared / "quick_results.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not done.exists():
            shutil.rmtree(results, ignore_errors=True)
            results.mkdir()
            jobs = [Job(name, study.make(True), study.keep, study.repeats) for name, study in STUDIES.items()]
            run_studies(jobs, results, jobs=2, timeout=600)
            done.touch()
    return results


@pytest.fixture(scope="session")
def studies(quick_results) -> dict[str, pd.DataFrame]:
    return {name: studytable.read(quick_results / f"{name}.csv") for name in STUDIES}


def checkout_first(env: dict[str, str]) -> dict[str, str]:
    """env with this checkout first on PYTHONPATH: a child process imports this checkout's
    driver, whatever else is installed."""
    return env | {"PYTHONPATH": os.pathsep.join([str(REPO), *filter(None, [env.get("PYTHONPATH")])])}


def cli(*args: str, cwd: Path | str = REPO, env: dict[str, str] | None = None,
        **kw) -> subprocess.CompletedProcess:
    """`python -m driver ARGS` as a user runs it, in cwd (this checkout's driver, whatever is installed)."""
    env = checkout_first(dict(os.environ if env is None else env))
    return subprocess.run([sys.executable, "-m", "driver", *args], cwd=cwd, capture_output=True, text=True,
                          env=env, **kw)


def hertz(*args: str, cwd: Path | str = REPO) -> subprocess.CompletedProcess:
    """`hertz ARGS` in this process (fast: no interpreter start), for commands that stop before
    they run a sweep (a sweep would make the test process a subreaper)."""
    from driver.cli import main
    out, err = io.StringIO(), io.StringIO()
    with contextlib.chdir(cwd), contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main(list(args))
        except SystemExit as exc:  # argparse's usage errors
            code = exc.code if isinstance(exc.code, int) else 2
    return subprocess.CompletedProcess(["hertz", *args], code, out.getvalue(), err.getvalue())


def rel(x, ref):
    """|x/ref - 1|: the relative error of x against ref."""
    return abs(x / ref - 1)


# the relative errors a run writes against its own closed form (Hertz, Sneddon)
ERROR_COLUMNS = ("err_p0", "err_F", "err_a")


def max_err(rows):
    """The largest |error| of p0, F and a: of one summary (a number), or of each row of a table (a Series)."""
    if isinstance(rows, pd.DataFrame):
        return rows[list(ERROR_COLUMNS)].abs().max(axis=1)
    return max(abs(rows[column]) for column in ERROR_COLUMNS)


# what -out holds after a 2D run, every file whole (no *.part)
RUN_FILES_2D = ["axis.csv", "history.csv", "path.csv", "profile.csv", "summary.csv"]


def statuses_of(code: int) -> set[str]:
    """The statuses that exit with code, from the solver's own exit table."""
    return {status for status, e in freefem.exits().items() if e.code == code}


def one_error_line(proc: subprocess.CompletedProcess) -> str:
    """The one line a refused command prints (exit 2, no traceback): returned for more checks."""
    lines = proc.stderr.strip().splitlines()
    assert proc.returncode == 2, (proc.returncode, proc.stderr)
    assert len(lines) == 1 and "error" in lines[0] and "Traceback" not in proc.stderr, proc.stderr
    return lines[0]


@pytest.fixture
def fake_solver(tmp_path, monkeypatch):
    """Put a misbehaving FreeFem++ first on PATH (tests/fake_freefem.py); returns the
    environment that selects it, with FAKE_MODE picking the fault."""
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    fake = bin_dir / "FreeFem++"
    fake.write_text(f"#!{sys.executable}\n" + FAKE.read_text())
    fake.chmod(0o755)
    monkeypatch.setenv("REAL_FREEFEM", freefem.check_freefem())
    monkeypatch.setenv("PATH", f"{bin_dir}:{os.environ['PATH']}")
    return fake


def run_fault(mode: str, tmp_path: Path, monkeypatch, case: Case = Case.of(n=8, method="lagrange"),
              timeout: float = 60) -> dict:
    """run_case on the fake solver (fake_solver) in the fault mode given, in its own folder."""
    monkeypatch.setenv("FAKE_MODE", mode)
    return run_case(case, tmp_path / mode, timeout=timeout, summary_columns=freefem.summary_columns())


def solvers_under(path: Path) -> list[int]:
    """Pids of running case processes (the driver's marker in their environment) that belong to
    this test: their command line or environment names its folder. Other sweeps on the machine
    are not this test's."""
    from driver.processes import MARKER
    found = []
    needle = str(path).encode()
    for proc in Path("/proc").iterdir():
        if not proc.name.isdigit():
            continue
        try:
            environ = (proc / "environ").read_bytes()
            cmdline = (proc / "cmdline").read_bytes()
        except OSError:
            continue
        marked = any(e.startswith(MARKER.encode()) for e in environ.split(b"\0"))
        if marked and (needle in environ or needle in cmdline):
            found.append(int(proc.name))
    return found


def copy_tracked(target: Path) -> Path:
    """The repository's tracked files (git ls-files) as they are in the working tree, copied to
    target: what a fresh clone would hold, with uncommitted edits included."""
    names = subprocess.run(["git", "ls-files", "-z"], cwd=REPO, capture_output=True, check=True).stdout
    for name in names.decode().split("\0"):
        source = REPO / name
        if name and source.is_file():
            (target / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(source, target / name)
    return target


# -- tiers ----------------------------------------------------------------------------------

# the longest files first: pytest-xdist hands whole files (--dist loadfile) to whichever worker
# is free, in collection order, so a long file left to the end keeps one worker busy alone
LONGEST_FIRST = ["test_readme_commands", "test_report", "test_study_results", "test_friction", "test_layers",
                 "test_3d", "test_tangential"]


def pytest_collection_modifyitems(config, items):
    rank = {name: k for k, name in enumerate(LONGEST_FIRST)}
    items.sort(key=lambda item: rank.get(Path(str(item.fspath)).stem, len(rank)))  # stable: the rest as collected
    for item in items:
        module = Path(str(item.fspath)).stem
        if module in SLOW_MODULES or SLOW_FIXTURES & set(getattr(item, "fixturenames", ())):
            item.add_marker(pytest.mark.slow)


# -- skips must be explained and allowed ------------------------------------------------------

def _skip_reason(report) -> str:
    longrepr = report.longrepr
    if isinstance(longrepr, tuple) and len(longrepr) == 3:
        return str(longrepr[2]).removeprefix("Skipped: ")
    return str(longrepr)


def pytest_runtest_logreport(report):
    if report.skipped and not hasattr(report, "wasxfail"):
        reason = _skip_reason(report)
        if not any(re.search(pattern, reason) for pattern in ALLOWED_SKIPS):
            _UNEXPECTED.append(f"{report.nodeid}: {reason}")


_UNEXPECTED: list[str] = []


# -- tests never write into the repository ----------------------------------------------------

def _git_status() -> str:
    return subprocess.run(["git", "status", "--porcelain"], cwd=REPO, capture_output=True,
                          text=True).stdout


def pytest_sessionstart(session):
    session.config.git_status_before = _git_status()


def pytest_sessionfinish(session, exitstatus):
    after = _git_status()
    if after != session.config.git_status_before:
        print(f"\nthe tests changed the repository:\n{after}")
        session.exitstatus = 1
    if _UNEXPECTED and os.environ.get("HERTZ_ALLOW_SKIPS") != "1":
        print("\nskipped without an allowed reason (install what is missing, or set HERTZ_ALLOW_SKIPS=1):\n  "
              + "\n  ".join(_UNEXPECTED))
        session.exitstatus = 1
