"""A study table (results/<study>.csv): validated on load, appended row by row, rewritten atomically.

While a sweep runs the table is append-only: each finished case is one line,
flushed and fsynced, so a kill loses no finished case. Anything that changes
lines already written (dropping a line cut by a kill, moving stale or bad rows
aside) writes a new file and renames it over the old one, so a kill during the
repair leaves either the old table or the new one, never a cut one.
"""
from __future__ import annotations

import csv
import fcntl
import io
import math
import os
import re
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import IO

import pandas as pd

from driver.schema import STATUSES, TEXT_COLUMNS

NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_-]{0,63}$")
RESERVED = {"runs", "stale", "local", "REPORT", "bench"}


class TableError(RuntimeError):
    """A study table that cannot be read or written; the message says which and why."""


def check_name(name: str) -> None:
    if not NAME.match(name) or name in RESERVED:
        raise TableError(f"study name {name!r} must be 1 to 64 letters, digits, - or _ "
                         f"(starting with a letter or digit) and not one of {sorted(RESERVED)}")


class StudyLock:
    """Exclusive and non-blocking: a second sweep of the same study refuses to start."""

    def __init__(self, path: Path):
        self.path = path
        self.handle: IO[str] | None = None

    def __enter__(self) -> StudyLock:
        try:
            handle = open(self.path, "a+")
        except OSError as exc:
            raise TableError(f"cannot create the lock {self.path}: {exc.strerror}") from None
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            handle.close()
            raise TableError(f"another sweep is writing {self.path.with_suffix('.csv').name}; "
                             "wait for it to finish") from None
        self.handle = handle
        return self

    def __exit__(self, *exc) -> None:
        assert self.handle is not None
        fcntl.flock(self.handle, fcntl.LOCK_UN)
        self.handle.close()


def write_atomically(path: Path, text: str) -> None:
    tmp = path.with_name(f".{path.name}.{os.getpid()}.part")
    try:
        with open(tmp, "w", encoding="utf-8") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
        fd = os.open(path.parent, os.O_RDONLY)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)
    except OSError as exc:
        tmp.unlink(missing_ok=True)
        raise TableError(f"cannot write {path}: {exc.strerror}") from None


def _csv_text(columns: list[str], rows: list[list[str]]) -> str:
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(columns)
    writer.writerows(rows)
    return buf.getvalue()


@dataclass
class Checked:
    """A table's good rows (raw text fields, in file order) and what was wrong with the rest."""

    columns: list[str]
    rows: list[list[str]] = field(default_factory=list)
    bad: list[tuple[int, str, str]] = field(default_factory=list)  # line number, reason, line
    cut_last_line: bool = False


def _numeric_ok(text: str) -> bool:
    if text == "":
        return True
    try:
        float(text)
    except ValueError:
        return False
    return True


def check(path: Path, columns: list[str]) -> Checked:
    """Read a table line by line; every line that is not a valid row is reported, not kept."""
    raw = path.read_bytes() if path.exists() else b""
    result = Checked(columns)
    if not raw:
        return result
    if not raw.endswith(b"\n"):  # a kill cut the last line
        raw = raw[: raw.rfind(b"\n") + 1]
        result.cut_last_line = True
    lines = raw.split(b"\n")[:-1]
    if not lines:
        return result
    header = lines[0].decode("utf-8", errors="replace")
    if next(csv.reader([header]), []) != columns:
        result.bad = [(1, "header differs from the current columns", header)]
        result.bad += [(k + 1, "row under an old header", ln.decode("utf-8", errors="replace"))
                       for k, ln in enumerate(lines[1:], start=1)]
        return result
    index = {c: k for k, c in enumerate(columns)}
    seen: dict[str, int] = {}
    for number, line in enumerate(lines[1:], start=2):
        try:
            text = line.decode("utf-8")
        except UnicodeDecodeError:
            result.bad.append((number, "not UTF-8", line.decode("utf-8", errors="replace")))
            continue
        try:
            fields = next(csv.reader([text]))
        except (csv.Error, StopIteration):
            result.bad.append((number, "not a CSV line", text))
            continue
        reason = ""
        if len(fields) != len(columns):
            reason = f"{len(fields)} fields, not {len(columns)}"
        elif not fields[index["case_id"]]:
            reason = "empty case_id"
        elif fields[index["status"]] not in STATUSES:
            reason = f"status {fields[index['status']]!r} is not one of {STATUSES}"
        else:
            for col, value in zip(columns, fields):
                if col not in TEXT_COLUMNS and col != "expect_converged" and not _numeric_ok(value):
                    reason = f"{col} is not a number: {value!r}"
                    break
        if reason:
            result.bad.append((number, reason, text))
            continue
        case_id = fields[index["case_id"]]
        if case_id in seen:  # the later run of a case replaces the earlier one
            earlier = seen[case_id]
            result.bad.append((earlier + 2, f"duplicate of case {case_id} (line {number} kept)",
                               _csv_text(columns, [result.rows[earlier]]).split("\n")[1]))
            result.rows[earlier] = []
        seen[case_id] = len(result.rows)
        result.rows.append(fields)
    result.rows = [r for r in result.rows if r]
    return result


def frame_of(columns: list[str], rows: list[list[str]]) -> pd.DataFrame:
    """Rows of text fields as a typed frame: numbers as floats, ids and words as text."""
    frame = pd.DataFrame(rows, columns=columns, dtype=object)
    for col in columns:
        if col in TEXT_COLUMNS:
            frame[col] = frame[col].fillna("").astype(str)
        elif col == "expect_converged":
            frame[col] = frame[col].map({"True": True, "False": False, "": True})
        else:
            frame[col] = pd.to_numeric(frame[col].replace("", math.nan), errors="coerce")
    return frame


def read(path: Path | str) -> pd.DataFrame:
    """A table for reading (charts, report, tests): its own header, ids as text."""
    path = Path(path)
    if not path.exists() or path.stat().st_size == 0:
        return pd.DataFrame()
    header = next(csv.reader([path.open(encoding="utf-8", errors="replace").readline()]))
    return pd.read_csv(path, dtype={c: str for c in TEXT_COLUMNS if c in header},
                       keep_default_na=False, na_values=[""])


def prepare(path: Path, columns: list[str], current_hash: str) -> tuple[pd.DataFrame, list[str]]:
    """Keep the rows of the current solver code; move the others aside, with a message each.

    Returns the kept table and the messages (bad lines by number, stale rows)."""
    checked = check(path, columns)
    messages = []
    stale_dir = path.parent / "stale"
    stamp = time.strftime("%Y%m%d-%H%M%S")
    if checked.cut_last_line:
        messages.append(f"{path.name}: dropped a last line cut by an interrupted write")
    if checked.bad:
        text = "\n".join(f"line {n}: {reason}: {line}" for n, reason, line in checked.bad) + "\n"
        stale_dir.mkdir(exist_ok=True)
        aside = stale_dir / f"{path.stem}-bad-{stamp}.txt"
        write_atomically(aside, text)
        for n, reason, _ in checked.bad[:5]:
            messages.append(f"{path.name}: line {n}: {reason}")
        if len(checked.bad) > 5:
            messages.append(f"{path.name}: ... {len(checked.bad) - 5} more")
        messages.append(f"{path.name}: {len(checked.bad)} bad line(s) moved to {aside}")
    hash_col = columns.index("edp_hash")
    stale = [r for r in checked.rows if r[hash_col] != current_hash]
    kept = [r for r in checked.rows if r[hash_col] == current_hash]
    if stale:
        stale_dir.mkdir(exist_ok=True)
        by_hash: dict[str, list[list[str]]] = {}
        for r in stale:
            by_hash.setdefault(r[hash_col], []).append(r)
        for h, rows in by_hash.items():
            target = stale_dir / f"{path.stem}-{h}.csv"
            old = check(target, columns).rows if target.exists() else []
            write_atomically(target, _csv_text(columns, old + rows))
        messages.append(f"{path.name}: {len(stale)} row(s) of other solver code moved to {stale_dir}/")
    if checked.cut_last_line or checked.bad or stale:
        write_atomically(path, _csv_text(columns, kept))
    return frame_of(columns, kept), messages


def remove_cases(path: Path, columns: list[str], case_ids: set[str]) -> None:
    """Drop these cases' rows (to run them again), atomically."""
    checked = check(path, columns)
    index = columns.index("case_id")
    write_atomically(path, _csv_text(columns, [r for r in checked.rows if r[index] not in case_ids]))


def append_row(path: Path, row: dict, columns: list[str]) -> None:
    """One finished case, flushed and fsynced; raises TableError if the disk refuses."""
    buf = io.StringIO()
    writer = csv.DictWriter(buf, fieldnames=columns, lineterminator="\n", extrasaction="ignore")
    new = not path.exists() or path.stat().st_size == 0
    if new:
        writer.writeheader()
    writer.writerow({k: _cell(row.get(k)) for k in columns})
    data = buf.getvalue().encode("utf-8")
    try:
        fd = os.open(path, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o644)
        try:
            written = os.write(fd, data)
            if written != len(data):
                # a short write: cut it off again, so the table keeps whole lines
                os.ftruncate(fd, os.lseek(fd, 0, os.SEEK_END) - written)
                raise OSError(28, "No space left on device")
            os.fsync(fd)
        finally:
            os.close(fd)
    except OSError as exc:
        raise TableError(f"cannot append to {path}: {exc.strerror}") from None


def _cell(value) -> str:
    if value is None:
        return ""
    if isinstance(value, float):
        return "" if math.isnan(value) else repr(value)
    return str(value)
