"""The one door to hertz.edp: its command line, its option table and its columns.

hertz.edp owns its options (names, defaults, ranges, meanings) and the columns
of summary.csv; the driver asks for them (`-options`, `-columns`) instead of
copying them, and caches the answer per solver fingerprint.
"""
from __future__ import annotations

import csv
import functools
import hashlib
import io
import os
import re
import shutil
import subprocess
from dataclasses import dataclass
from pathlib import Path

from driver import EDP_DIR, HERTZ_EDP

FREEFEM = "FreeFem++"
SETUP_HINT = "run 'make setup' (driver/setup.sh) to install FreeFEM"

# hertz.edp's exit codes (README): the status a row may carry with each
EXIT_CODES = {0: "converged", 2: "rejected input", 3: "not converged", 4: "write failure",
              5: "inaccurate"}


class SetupError(RuntimeError):
    """The solver cannot run at all on this machine."""


def freefem_env() -> dict[str, str]:
    # Debian's packaged plugin and include paths are wrong (README): name the real ones
    env = dict(os.environ)
    env.setdefault("FF_LOADPATH", "/usr/lib/freefem++")
    env.setdefault("FF_INCLUDEPATH", "/usr/include/freefem++/idp")
    return env


def check_freefem() -> str:
    path = shutil.which(FREEFEM)
    if path is None:
        raise SetupError(f"{FREEFEM} is not on PATH; {SETUP_HINT}")
    return path


def command(args: list[str]) -> list[str]:
    """The one way hertz.edp is called: no window, quiet."""
    return [check_freefem(), "-nw", "-v", "0", str(HERTZ_EDP), *args]


_COMMENTS = re.compile(r"/\*.*?\*/|//[^\n]*", re.S)


def _source_text(path: Path) -> str:
    """The code of one .edp/.idp file without comments and whitespace."""
    return "".join(_COMMENTS.sub("", path.read_text()).split())


def edp_hash() -> str:
    """Fingerprint of the solver's code: rows made by other code are stale.
    Comments and whitespace do not count."""
    digest = hashlib.sha256()
    for path in sorted(EDP_DIR.rglob("*")):
        if path.suffix in (".edp", ".idp"):
            digest.update(path.relative_to(EDP_DIR).as_posix().encode())
            digest.update(_source_text(path).encode())
    return digest.hexdigest()[:12]


def _query(flag: str) -> str:
    proc = subprocess.run(command([flag]), capture_output=True, text=True, env=freefem_env(),
                          timeout=120, check=False)
    if proc.returncode != 0:
        raise SetupError(f"hertz.edp {flag} failed (exit {proc.returncode}): {proc.stdout[-500:]}")
    return proc.stdout


@dataclass(frozen=True)
class Option:
    name: str      # without the leading dash
    kind: str      # real, int, word, path
    default: str   # as hertz.edp documents it (a number, a word, or a rule)
    range: str
    help: str

    @property
    def choices(self) -> list[str] | None:
        return [w.strip() for w in self.range.split(",")] if self.kind == "word" else None


@functools.cache
def _options(fingerprint: str) -> tuple[Option, ...]:
    text = _query("-options")
    lines = text.splitlines()
    start = lines.index("name,kind,default,range,help")
    rows = [ln for ln in lines[start + 1:] if ln.startswith("-")]
    return tuple(Option(r[0].lstrip("-"), r[1], r[2], r[3], r[4])
                 for r in csv.reader(io.StringIO("\n".join(rows))))


def options() -> dict[str, Option]:
    """hertz.edp's option table, by name (without the dash)."""
    return {o.name: o for o in _options(edp_hash())}


@functools.cache
def _columns(fingerprint: str) -> tuple[str, ...]:
    for line in _query("-columns").splitlines():
        if line.startswith("model,"):
            return tuple(line.split(","))
    raise SetupError("hertz.edp -columns printed no column list")


def summary_columns() -> list[str]:
    """The columns of summary.csv, in hertz.edp's order."""
    return list(_columns(edp_hash()))
