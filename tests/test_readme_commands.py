"""The README's commands are tests.

Every shell command that README.md and docs/*.md show in ```sh blocks, and
every Makefile target that does not take hours, runs in a fresh copy of the
repository's tracked files (git ls-files, with uncommitted edits), with the
relative paths as written, the way a newcomer types them: make targets from
the clone's root, hertz.edp from edp/ (as the README says), and every hertz
command both from the root and from another folder. Commands that need a cluster or take long are listed in
EXCEPTIONS with the reason. About two minutes on 2 cores.
"""
from __future__ import annotations

import os
import re
import subprocess
import time
from pathlib import Path

import pytest

from driver import freefem, studytable
from driver.studies import STUDIES

from conftest import REPO, copy_tracked

DOCS = [REPO / "README.md", *sorted((REPO / "docs").glob("*.md"))]

# commands not run, by a pattern on "where: command", and why
EXCEPTIONS = {
    r"^\w+: make test$": "the whole suite, of which this test is a part",
    r"^\w+: make test-fast$": "a subset of make test, which is this suite",
    r"^\w+: make bench$": "installs the FEniCS peer and times every configuration: many minutes",
    r"^\w+: hertz bench$": "the timing benchmark: many minutes (make bench)",
    r"^\w+: make mutate$": "runs tests once per mutation: about 25 minutes",
    r"^\w+: make audit$": "510 random scenes, 10 of them 3D: several minutes (test_audit.py runs a small draw)",
    r"^\w+: make sweep-quick$": "the quick studies, which the quick_results fixture sweeps through the same "
                                 "run_studies (tests/conftest.py): 70 s more",
    r"^\w+: make rerun$": "recomputes every study from scratch: hours on 2 cores",
    r"^\w+: dask scheduler": "starts a server that runs until stopped (test_dask_backend runs a scheduler and workers)",
    r"tcp://host:8786": "host stands for the reader's own scheduler",
    r"^root: hertz report$": "the same as make report, which runs from the root (and hertz report runs elsewhere)",
}
# commands that recompute the committed studies: minutes when the tables are current, hours when not
STUDY_SWEEPS = [r"^root: make all$", r"^root: make sweep$"]
STALE = "committed results are stale: these would recompute every study"


def shell_commands(path: Path) -> list[str]:
    """The commands of a document's ```sh blocks: one per line, comments dropped."""
    found = []
    for block in re.findall(r"```sh\n(.*?)```", path.read_text(), re.S):
        for line in block.splitlines():
            command = re.sub(r"\s+#.*$", "", line).strip()
            if command and not command.startswith("#"):
                found.append(command)
    return found


def makefile_targets() -> list[str]:
    return re.findall(r"^([a-z][a-z-]*):.*##", (REPO / "Makefile").read_text(), re.M)


def plan() -> list[tuple[str, str]]:
    """(where, command) in the order a newcomer would go: the Makefile's targets (setup first),
    then the documents' commands, and make clean last."""
    targets = [f"make {t}" for t in makefile_targets()]
    documented = [c for doc in DOCS for c in shell_commands(doc) if c not in targets]
    steps: list[tuple[str, str]] = []
    for command in [t for t in targets if t != "make clean"] + documented + ["make clean"]:
        if command.startswith("hertz "):
            places = ["root", "elsewhere"]
        elif re.search(r"(^|\s)hertz\.edp\b", command) and not command.startswith("cd "):
            places = ["edp"]  # hertz.edp as written: from edp/, as the README says
        else:
            places = ["root"]
        steps += [(place, command) for place in places if (place, command) not in steps]
    return steps


STEPS = plan()


@pytest.fixture(scope="module")
def clone(tmp_path_factory) -> dict[str, Path]:
    root = copy_tracked(tmp_path_factory.mktemp("clone"))
    elsewhere = tmp_path_factory.mktemp("elsewhere")
    for doc in DOCS:  # a spec the docs show, saved under the name they give it
        for name, body in re.findall(r"Save this as\s+`([^`]+)`.*?```toml\n(.*?)```", doc.read_text(), re.S):
            for folder in (root, elsewhere):
                (folder / name).write_text(body)
    return {"root": root, "edp": root / "edp", "elsewhere": elsewhere}


def clone_env(clone: dict[str, Path]) -> dict[str, str]:
    """The environment a README command runs in: the clone's driver, no display, no scheduler."""
    env = dict(os.environ, MPLBACKEND="Agg")
    env["PYTHONPATH"] = str(clone["root"])  # `hertz` and python -m driver: the copy's driver
    env.pop("DASK_SCHEDULER_ADDRESS", None)
    return env


def _results_current(root: Path) -> bool:
    current = freefem.edp_hash()
    tables = [studytable.read(root / "results" / f"{name}.csv") for name in STUDIES]
    return all(len(t) and set(t["edp_hash"]) == {current} for t in tables)


def test_the_copy_runs_its_own_driver(clone):
    proc = subprocess.run(["hertz", "--version"], cwd=clone["elsewhere"], env=clone_env(clone), capture_output=True,
                          text=True)
    where = subprocess.run(["python3", "-c", "import driver; print(driver.__file__)"], cwd=clone["elsewhere"],
                           env=clone_env(clone), capture_output=True, text=True)
    assert proc.returncode == 0 and where.stdout.startswith(str(clone["root"])), where.stdout + where.stderr


@pytest.mark.parametrize("where,command", STEPS, ids=[f"{w}: {c}" for w, c in STEPS])
def test_a_documented_command_works_as_typed(clone, where, command):
    reason = next((why for pattern, why in EXCEPTIONS.items() if re.search(pattern, f"{where}: {command}")), None)
    if reason:
        pytest.skip(f"not run: {reason}")
    if any(re.search(p, f"{where}: {command}") for p in STUDY_SWEEPS) and not _results_current(clone["root"]):
        pytest.skip(STALE)
    typed = command
    start = time.perf_counter()
    proc = subprocess.run(["bash", "-c", typed], cwd=clone[where], env=clone_env(clone), capture_output=True,
                          text=True, timeout=900)
    seconds = time.perf_counter() - start
    assert proc.returncode == 0, f"{typed} in {where} ({seconds:.1f} s):\n{proc.stdout[-3000:]}\n{proc.stderr[-3000:]}"
    assert "Traceback" not in proc.stderr, proc.stderr


def test_every_exception_names_a_documented_command():
    # an exception for a command the documents no longer show is dead weight; say so
    for pattern in [*EXCEPTIONS, *STUDY_SWEEPS]:
        assert any(re.search(pattern, f"{where}: {command}") for where, command in STEPS), pattern
