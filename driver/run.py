"""Run one case of hertz.edp in its own work directory and turn its output into a row."""
from __future__ import annotations

import hashlib
import math
import os
import shutil
import signal
import subprocess
import time
from pathlib import Path

import pandas as pd

from driver import EDP_DIR, HERTZ_EDP
from driver.cases import Case
from driver.schema import STUDY_COLUMNS, SUMMARY_COLUMNS

FREEFEM = "FreeFem++"
SETUP_HINT = "run 'make setup' (driver/setup.sh) to install FreeFEM"


class SetupError(RuntimeError):
    """The solver cannot run at all on this machine."""


def edp_hash() -> str:
    """Fingerprint of the solver sources: rows made by other sources are stale."""
    digest = hashlib.sha256()
    for path in sorted(EDP_DIR.rglob("*")):
        if path.suffix in (".edp", ".idp"):
            digest.update(path.relative_to(EDP_DIR).as_posix().encode())
            digest.update(path.read_bytes())
    return digest.hexdigest()[:12]


def freefem_env() -> dict:
    # Debian's packaged paths are wrong (see README): name the real ones
    env = dict(os.environ)
    env.setdefault("FF_LOADPATH", "/usr/lib/freefem++")
    env.setdefault("FF_INCLUDEPATH", "/usr/include/freefem++/idp")
    return env


def check_freefem() -> str:
    path = shutil.which(FREEFEM)
    if path is None:
        raise SetupError(f"{FREEFEM} is not on PATH; {SETUP_HINT}")
    return path


def freefem_command(args: list[str], outdir: Path) -> list[str]:
    """The one way hertz.edp is called: no window, quiet, files in outdir."""
    return [check_freefem(), "-nw", "-v", "0", str(HERTZ_EDP), *args, "-out", str(outdir)]


def run_case(case: Case, workdir: Path, timeout: float, study: str = "",
             procs: set | None = None) -> dict:
    """Run hertz.edp; always return a full row, whatever happened."""
    workdir.mkdir(parents=True, exist_ok=True)
    for name in ("summary.csv", "profile.csv", "history.csv", "axis.csv"):
        (workdir / name).unlink(missing_ok=True)
    cmd = freefem_command(case.args(), workdir)
    log_path = workdir / "freefem.log"
    start = time.perf_counter()
    status, error = None, ""
    # output through a pipe: communicate() returns as soon as FreeFEM exits,
    # where wait(timeout) on a file-backed process polls (up to 50 ms late)
    proc = subprocess.Popen(cmd, cwd=workdir, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            env=freefem_env(), start_new_session=True)
    if procs is not None:
        procs.add(proc)
    try:
        output, _ = proc.communicate(timeout=timeout)
        exit_code = proc.returncode
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)  # its own process group: nothing survives
        output, _ = proc.communicate()
        exit_code, status, error = proc.returncode, "timeout", f"no result after {timeout:g} s"
    finally:
        if procs is not None:
            procs.discard(proc)
    wall = time.perf_counter() - start
    log_path.write_bytes(" ".join(cmd).encode() + b"\n" + (output or b""))

    row = {col: math.nan for col in STUDY_COLUMNS}
    row.update(case.as_dict())
    row["maxit"] = case.maxit if case.maxit is not None else math.nan
    summary = workdir / "summary.csv"
    if status is None and summary.exists():
        values = pd.read_csv(summary).iloc[0].to_dict()
        row.update({k: values.get(k, math.nan) for k in SUMMARY_COLUMNS})
        status = row["status"]
        numbers = [row[k] for k in ("p0_fe", "F_fe", "a_fe")]
        if status == "converged" and any(pd.isna(v) or math.isinf(v) for v in numbers):
            status, error = "nan", "converged but p0, F or a is NaN/inf"
        elif status != "converged":
            error = f"{status} after {row['iterations']:.0f} iterations, residual {row['residual']:.3g}"
    elif status is None:
        status = "failed"
        error = _last_error(log_path) or f"exit code {exit_code} without summary.csv"
    row.update(status=status, error=error, study=study, case_id=case.case_id,
               edp_hash=edp_hash(), wall_time=wall, exit_code=exit_code)
    return row


def _last_error(log_path: Path) -> str:
    lines = [ln.strip() for ln in log_path.read_text(errors="replace").splitlines() if ln.strip()]
    for line in reversed(lines):
        if "error" in line.lower():
            return line[:300]
    return lines[-1][:300] if len(lines) > 1 else ""
