"""The one door to hertz.edp: its command line, its option table, its exit codes and its columns.

hertz.edp owns its options (names, kinds, defaults, ranges, meanings), its exit
codes and the columns of summary.csv; the driver asks for them (`-options`,
`-exits`, `-columns`) instead of copying them. Each answer is kept in the user's
cache folder (layout.cache_dir) under the solver's fingerprint and the FreeFem++
that gave it: asking costs a FreeFEM start, three of them more than a default
case. Options and columns may grow: nothing here lists them.
"""
from __future__ import annotations

import contextlib
import csv
import functools
import hashlib
import io
import math
import os
import re
import shutil
import subprocess
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TypeVar

from driver import files, layout
from driver.errors import HertzError, OptionError, SetupError

FREEFEM = "FreeFem++"
SETUP_HINT = "run 'make setup' (driver/setup.sh) to install FreeFEM"
EDP_DIR = layout.EDP_DIR  # a module global, so that a test can point it at a copy

Value = int | float | str
T = TypeVar("T")


# OpenBLAS picks its kernels by CPU model. The one Debian ships (0.3.21) does not know
# CPUs newer than itself and falls back to its generic Prescott kernels (SSE3): on the
# Xeon of the README's timings, 59% of the 3D ellipsoid's time went to them (perf), and
# the CPU's AVX-512 kernels take that run from 20-22 s to 14-15 s (2D runs spend little
# in BLAS and do not change). The CPU's own flags name the kernels it can run.
KERNELS = (("SkylakeX", frozenset({"avx512f", "avx512cd", "avx512bw", "avx512dq", "avx512vl"})),
           ("Haswell", frozenset({"avx2", "fma"})))


def blas_kernels(cpuinfo: str) -> str | None:
    """The OpenBLAS kernels that a CPU's flags (the text of /proc/cpuinfo) allow, or None to
    leave OpenBLAS its own choice (no x86 flags line, or none of those kernels' flags)."""
    match = re.search(r"^flags\s*:(.*)$", cpuinfo, re.M)
    flags = set(match.group(1).split()) if match else set()
    return next((name for name, needs in KERNELS if needs <= flags), None)


@functools.cache
def _this_cpu_kernels() -> str | None:
    try:
        return blas_kernels(Path("/proc/cpuinfo").read_text())
    except OSError:
        return None


def blas_env() -> dict[str, str]:
    """The environment with OPENBLAS_CORETYPE set from this CPU's flags, unless it is set
    already: for the solver and for the benchmark's peers alike."""
    env = dict(os.environ)
    kernels = _this_cpu_kernels()
    if kernels:
        env.setdefault("OPENBLAS_CORETYPE", kernels)
    return env


def freefem_env() -> dict[str, str]:
    # Debian's packaged plugin and include paths are wrong (README): name the real ones
    env = blas_env()
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
    return [check_freefem(), "-nw", "-v", "0", str(EDP_DIR / layout.ENTRY), *args]


_COMMENTS = re.compile(r"/\*.*?\*/|//[^\n]*", re.S)


def _strip(text: str) -> str:
    """The code of one .edp/.idp/.cpp file without comments and whitespace."""
    return "".join(_COMMENTS.sub("", text).split())


def edp_hash() -> str:
    """Fingerprint of the solver's code: rows made by other code are stale.
    Comments and whitespace do not count. They are stripped again only when a
    file's text changes (stripping the 40 files took 6 ms, four times a case:
    a tenth of a default case through the driver; reading them takes 1 ms)."""
    return _stripped_hash(tuple((path.relative_to(EDP_DIR).as_posix(), path.read_text())
                                for path in sorted(EDP_DIR.rglob("*"))
                                if path.suffix in (".edp", ".idp", ".cpp")))  # .cpp: the 3D plugin (edp/plugin)


@functools.lru_cache(maxsize=16)
def _stripped_hash(texts: tuple[tuple[str, str], ...]) -> str:
    digest = hashlib.sha256()
    for name, text in texts:
        digest.update(name.encode())
        digest.update(_strip(text).encode())
    return digest.hexdigest()[:12]


def _query(flag: str) -> str:
    try:
        proc = subprocess.run(command([flag]), capture_output=True, text=True, env=freefem_env(),
                              timeout=120, check=False)
    except (OSError, subprocess.TimeoutExpired) as exc:
        raise SetupError(f"hertz.edp {flag} could not run: {exc}") from None
    if proc.returncode != 0:
        raise SetupError(f"hertz.edp {flag} failed (exit {proc.returncode}): "
                         + " ".join(proc.stdout[-300:].split()))
    return proc.stdout


CACHE_ENTRIES = 64  # answers kept: a few solver versions and FreeFEM installs, each three files


def _cache_file(flag: str, fingerprint: str) -> Path:
    """Where hertz.edp's answer to flag is kept: per solver code and per FreeFem++ binary
    (another FreeFEM, or a stand-in on PATH, may answer otherwise)."""
    binary = os.path.realpath(check_freefem())
    try:
        stat = os.stat(binary)
        identity = f"{binary}\0{stat.st_size}\0{stat.st_mtime_ns}"
    except OSError:
        identity = binary
    solver = hashlib.sha256(identity.encode()).hexdigest()[:12]
    return layout.cache_dir() / f"{fingerprint}-{solver}{flag}.txt"


def _keep(path: Path, text: str) -> None:
    """Store an answer whole (a temporary file renamed), and drop the oldest beyond CACHE_ENTRIES.
    A cache that cannot be written costs only speed."""
    with contextlib.suppress(OSError, HertzError):
        path.parent.mkdir(parents=True, exist_ok=True)
        files.write_text_atomically(path, text)  # through a fresh folder: no planted link followed
        entries = sorted(path.parent.glob("*.txt"), key=lambda p: p.stat().st_mtime_ns)
        for old in entries[:-CACHE_ENTRIES]:
            old.unlink(missing_ok=True)


def _answer(flag: str, fingerprint: str, parse: Callable[[str], T]) -> T:
    """hertz.edp's answer to flag, parsed: from the cache when this solver code and this
    FreeFem++ gave it before, else asked and kept. A cached answer that does not parse
    (cut, or written by hand) is asked again."""
    path = _cache_file(flag, fingerprint)
    try:
        return parse(path.read_text())
    except (OSError, UnicodeDecodeError, SetupError):
        pass
    text = _query(flag)
    parsed = parse(text)
    _keep(path, text)
    return parsed


def _table(text: str, header: str) -> list[list[str]]:
    """The CSV rows after a header line (FreeFEM prints its own lines around them)."""
    lines = text.splitlines()
    if header not in lines:
        raise SetupError(f"hertz.edp printed no table with the header {header!r}")
    rows = []
    for line in lines[lines.index(header) + 1:]:
        if not line.strip():
            break
        rows.append(line)
    return list(csv.reader(io.StringIO("\n".join(rows))))


# a range as hertz.edp writes it: "integer in [2, 400]", "(0, inf)", "[10, 100000] a";
# a unit after the bracket ("a", "R", "E*/h") scales the bounds with the scene
_RANGE = re.compile(r"^(?:integer in )?([\[(])\s*([^,\s]+)\s*,\s*([^\])\s]+)\s*([\])])\s*(.*)$")
_INTEGER = re.compile(r"^[+-]?\d+$")


@dataclass(frozen=True)
class Option:
    name: str      # without the leading dash
    kind: str      # real, int, word, path, list (numbers, comma separated, each in the range)
    default: str   # as hertz.edp documents it (a number, a word, or a rule)
    range: str
    help: str

    @property
    def choices(self) -> list[str] | None:
        return [w.strip() for w in self.range.split(",")] if self.kind == "word" else None

    def _bounds(self) -> tuple[float, float, bool, bool] | None:
        """(low, high, low included, high included), or None when the range is not
        a plain interval (or depends on the scene: hertz.edp checks those)."""
        match = _RANGE.match(self.range)
        if not match or match.group(5):
            return None
        opening, low, high, closing, _ = match.groups()
        try:
            return float(low), float(high), opening == "[", closing == "]"
        except ValueError:
            return None

    def parse(self, value: object, label: str | None = None) -> Value:
        """The value as hertz.edp will read it, or OptionError naming the option and its range.
        Text (a command line) and typed values (a spec file) are both accepted."""
        label = label or f"-{self.name}"
        shown = value if isinstance(value, str) else repr(value)
        if len(shown) > 40:
            shown = shown[:30] + "..." + shown[-6:]
        if self.kind == "word":
            if not isinstance(value, str) or value not in (self.choices or []):
                raise OptionError(f"{label} must be one of {self.range}, got {shown!r}")
            return value
        if self.kind == "path":
            if not isinstance(value, (str, Path)) or not str(value):
                raise OptionError(f"{label} must be a path, got {shown!r}")
            return str(value)
        if self.kind == "list":
            return self._parse_list(value, label, shown)
        what = "an integer" if self.kind == "int" else "a number"
        wrong = OptionError(f"{label} must be {what} in {self.range.removeprefix('integer in ')}, got {shown!r}")
        number: int | float
        if isinstance(value, bool):
            raise wrong
        if isinstance(value, str):
            text = value.strip()
            if self.kind == "int":
                if not _INTEGER.match(text):
                    raise wrong
                number = int(text)
            else:
                try:
                    number = float(text)
                except ValueError:
                    raise wrong from None
                if math.isinf(number) and text.lstrip("+-").lower() not in ("inf", "infinity"):
                    raise wrong  # 1e400: too large to be the number typed
        elif isinstance(value, int):
            number = value
        elif isinstance(value, float):
            number = value
            if self.kind == "int":
                if not value.is_integer():
                    raise wrong
                number = int(value)
        else:
            raise wrong
        if isinstance(number, float) and math.isnan(number):
            raise wrong
        bounds = self._bounds()
        if bounds is not None:
            low, high, low_in, high_in = bounds
            # Python compares a huge int with a float exactly: no overflow here
            if not ((low <= number if low_in else low < number) and (number <= high if high_in else number < high)):
                raise wrong
        elif isinstance(number, float) and math.isinf(number) and not self.range.rstrip().endswith("inf]"):
            raise wrong
        if self.kind == "int":
            return int(number)
        try:
            return float(number)
        except OverflowError:
            raise wrong from None


    def _parse_list(self, value: object, label: str, shown: str) -> str:
        """A list option as hertz.edp reads it: its numbers, comma separated,
        each in the range (hertz.edp checks what else the option asks)."""
        wrong = OptionError(f"{label} must be numbers in {self.range}, got {shown!r}")
        items = value.split(",") if isinstance(value, str) else value
        if not isinstance(items, (list, tuple)) or not items:
            raise wrong
        # each element's range: the interval the table's range text opens with
        interval = re.match(r"^[\[(][^\])]*[\])]", self.range)
        element = Option(self.name, "real", "", interval.group(0) if interval else self.range, "")
        try:
            numbers = [element.parse(item.strip() if isinstance(item, str) else item) for item in items]
        except OptionError:
            raise wrong from None
        return ",".join(repr(float(n)) if not float(n).is_integer() else str(int(n)) for n in numbers)


def _option_table(text: str) -> tuple[Option, ...]:
    rows = _table(text, "name,kind,default,range,help")
    try:
        return tuple(Option(r[0].lstrip("-"), r[1], r[2], r[3], r[4]) for r in rows if r and r[0].startswith("-"))
    except IndexError:
        raise SetupError("hertz.edp -options printed a malformed table") from None


@functools.cache
def _options(fingerprint: str) -> tuple[Option, ...]:
    return _answer("-options", fingerprint, _option_table)


def options() -> dict[str, Option]:
    """hertz.edp's option table, by name (without the dash)."""
    return {o.name: o for o in _options(edp_hash())}


# options that say where files go or what the run does, not what is solved: a case
# (its id, its row) never carries them; the driver passes them on where it allows them
RUN_ONLY = {"check"}


def case_options() -> dict[str, Option]:
    """The options that define a case: every option but paths and run modes."""
    return {name: o for name, o in options().items() if o.kind != "path" and name not in RUN_ONLY}


def parse_options(values: dict[str, object], prefix: str = "-") -> dict[str, Value]:
    """Values by option name, checked against the table; OptionError for the first bad one."""
    table = options()
    parsed = {}
    for name, value in values.items():
        if name not in table:
            raise OptionError(f"unknown option {prefix}{name}; 'hertz options' lists them")
        parsed[name] = table[name].parse(value, f"{prefix}{name}")
    return parsed


@dataclass(frozen=True)
class Exit:
    status: str
    code: int
    meaning: str


def _exit_table(text: str) -> tuple[Exit, ...]:
    rows = _table(text, "status,code,meaning")
    try:
        return tuple(Exit(r[0], int(r[1]), r[2]) for r in rows if r)
    except (ValueError, IndexError):
        raise SetupError("hertz.edp -exits printed a malformed table") from None


@functools.cache
def _exits(fingerprint: str) -> tuple[Exit, ...]:
    return _answer("-exits", fingerprint, _exit_table)


def exits() -> dict[str, Exit]:
    """hertz.edp's exit codes by status: the statuses a run ends with and what each means."""
    return {e.status: e for e in _exits(edp_hash())}


def exit_code(status: str) -> int:
    return exits()[status].code


_IDENTIFIER = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


def _column_list(text: str) -> tuple[str, ...]:
    for line in text.splitlines():
        names = line.split(",")
        if len(names) > 1 and all(_IDENTIFIER.match(n) for n in names):
            return tuple(names)
    raise SetupError("hertz.edp -columns printed no column list")


@functools.cache
def _columns(fingerprint: str) -> tuple[str, ...]:
    return _answer("-columns", fingerprint, _column_list)


def summary_columns() -> list[str]:
    """The columns of summary.csv, in hertz.edp's order."""
    return list(_columns(edp_hash()))


def refusal(args: list[str]) -> str:
    """hertz.edp's own check of a case (-check 1: the options and the scene, nothing solved):
    "" when it accepts the case, else its error line. It catches the ranges that depend on
    the scene (-d below R), which the option table cannot."""
    try:
        proc = subprocess.run(command([*args, "-check", "1"]), capture_output=True, text=True,
                              env=freefem_env(), timeout=120, check=False)
    except (OSError, subprocess.TimeoutExpired) as exc:
        raise SetupError(f"hertz.edp -check could not run: {exc}") from None
    if proc.returncode == 0:
        return ""
    lines = (proc.stdout + proc.stderr).splitlines()
    return next((line.strip() for line in lines if line.startswith("hertz.edp: error:")),
                f"hertz.edp -check refused {' '.join(args)} (exit {proc.returncode})")
