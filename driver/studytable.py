"""A study table (results/<study>.csv): validated on load, appended row by row, rewritten atomically.

While a sweep runs the table is append-only: each finished case is one line,
flushed and fsynced, so a kill loses no finished case. A rerun of a case
(--force, --retry-failed) is appended too, and replaces the earlier row of its
case only when the table is next prepared: until its rerun lands, the old row
stays. Anything that changes lines already written (dropping a line cut by a
kill, moving stale, bad or replaced rows aside into stale/) writes a new file
and renames it over the old one, so a kill during the repair leaves either the
old table or the new one, never a cut one.
"""
from __future__ import annotations

import csv
import fcntl
import io
import math
import os
import re
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import IO

import pandas as pd

from driver import files, layout, schema
from driver.errors import TableError

NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_-]{0,63}$")


def check_name(name: str) -> None:
    if not NAME.match(name) or name in layout.RESERVED_NAMES:
        raise TableError(f"study name {name!r} must be 1 to 64 letters, digits, - or _ "
                         f"(starting with a letter or digit) and not one of {sorted(layout.RESERVED_NAMES)}")


def refuse_symlink(path: Path, what: str = "table") -> None:
    files.refuse_symlink(path, what, TableError)


class StudyLock:
    """Exclusive and non-blocking: a second sweep of the same study refuses to start."""

    def __init__(self, path: Path):
        self.path = path
        self.handle: IO[str] | None = None

    def __enter__(self) -> StudyLock:
        try:
            # O_NOFOLLOW: a planted link is refused, not followed
            fd = os.open(self.path, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW, 0o644)
        except OSError as exc:
            raise TableError(f"cannot create the lock {self.path}: {exc.strerror}"
                             + (" (a symbolic link?)" if self.path.is_symlink() else "")) from None
        handle = os.fdopen(fd, "a+")
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
    files.write_text_atomically(path, text, TableError)


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
    replaced: list[list[str]] = field(default_factory=list)  # earlier rows of a case run again
    unanswered_reruns: list[list[str]] = field(default_factory=list)  # reruns that lost to an earlier answer
    cut_last_line: bool = False


def later_wins(earlier: dict, later: dict) -> bool:
    """Of two rows of one case, the later (its rerun) is kept, unless only the earlier
    has an answer: a rerun that failed or timed out must not replace a result."""
    return schema.answered(later) or not schema.answered(earlier)


def _numeric_ok(text: str) -> bool:
    if text == "":
        return True
    try:
        float(text)
    except ValueError:
        return False
    return True


def _raw(path: Path) -> bytes:
    refuse_symlink(path)
    if path.exists() and not path.is_file():
        raise TableError(f"the table {path} is not a file")
    try:
        return path.read_bytes() if path.exists() else b""
    except OSError as exc:
        raise TableError(f"cannot read {path}: {exc.strerror}") from None


def _row_problem(fields: list[str], columns: list[str], index: dict[str, int], statuses: list[str],
                 text: set[str]) -> str:
    """Why a line is not a valid row ("" if it is one)."""
    if len(fields) != len(columns):
        return f"{len(fields)} fields, not {len(columns)}"
    if not fields[index["case_id"]]:
        return "empty case_id"
    status = fields[index["status"]]
    if status not in statuses:
        return f"status {status!r} is not one of {statuses}"
    for col, value in zip(columns, fields):
        if col not in text and col != "expect_converged" and not _numeric_ok(value):
            return f"{col} is not a number: {value!r}"
    if status in schema.ANSWERED:
        # a hand-edited row must not pass for a finished case without its answer
        missing = schema.missing_answer(dict(zip(columns, fields)))
        if missing:
            return f"{status} without a finite {missing}"
    return ""


def check(path: Path, columns: list[str]) -> Checked:
    """Read a table line by line; every line that is not a valid row is reported, not kept.
    A case found twice keeps its later row; the earlier one is `replaced`."""
    raw = _raw(path)
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
    statuses = schema.statuses()
    text_cols = schema.text_columns()
    seen: dict[str, int] = {}
    rows: list[list[str] | None] = []
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
        reason = _row_problem(fields, columns, index, statuses, text_cols)
        if reason:
            result.bad.append((number, reason, text))
            continue
        case_id = fields[index["case_id"]]
        if case_id in seen:  # a rerun of the case: one of the two rows stays
            earlier = rows[seen[case_id]]
            assert earlier is not None
            if not later_wins(dict(zip(columns, earlier)), dict(zip(columns, fields))):
                result.unanswered_reruns.append(fields)
                continue
            result.replaced.append(earlier)
            rows[seen[case_id]] = None
        seen[case_id] = len(rows)
        rows.append(fields)
    result.rows = [r for r in rows if r is not None]
    return result


def _typed(frame: pd.DataFrame, text: set[str]) -> pd.DataFrame:
    """Each column typed at once, into a new frame (a column replaced in place, one at a time,
    left a frame of a block per column, which pandas warns about on the report's stderr)."""
    def typed(col: str) -> pd.Series:
        if col in text:
            return frame[col].fillna("").astype(str)
        if col == "expect_converged":
            return frame[col].map({"True": True, "False": False, "": True})
        return pd.to_numeric(frame[col].replace("", math.nan), errors="coerce")
    return pd.DataFrame({col: typed(col) for col in frame.columns}, index=frame.index)


def frame_of(columns: list[str], rows: list[list[str]]) -> pd.DataFrame:
    """Rows of text fields as a typed frame: numbers as floats, ids and words as text."""
    return _typed(pd.DataFrame(rows, columns=columns, dtype=object), schema.text_columns())


# columns a study table always holds as numbers, whatever hertz.edp's options are
# (read() must not ask hertz.edp: the report runs where FreeFEM is absent)
_NUMBER_COLUMNS = (*schema.ANSWER_COLUMNS, *schema.ERROR_COLUMNS, "wall_time", "max_rss_mb", "jobs", "exit_code")
_STUDY_KEYS = ("case_id", "status", "edp_hash")


def _reader_problem(record: dict[str, str]) -> str:
    """Why a line of a study table is no row ("" if it is one), from what the driver
    itself knows of its columns."""
    if not record["case_id"]:
        return "empty case_id"
    if not record["status"]:
        return "empty status"
    for col in _NUMBER_COLUMNS:
        if col in record and not _numeric_ok(record[col]):
            return f"{col} is not a number: {record[col]!r:.40}"
    if record["status"] in schema.ANSWERED:
        missing = schema.missing_answer(record)
        if missing:
            return f"{record['status']} without a finite {missing}"
    return ""


def _say_aside(path: Path, aside: list[tuple[int, str]], say) -> None:
    for number, reason in aside[:5]:
        say(f"{path.name}: line {number} set aside: {reason}")
    if len(aside) > 5:
        say(f"{path.name}: ... and {len(aside) - 5} more line(s) set aside")


def read(path: Path | str, say=None) -> pd.DataFrame:
    """A table for reading (charts, report, tests), without asking hertz.edp anything:
    the driver's text columns stay text, every other column that holds only numbers
    becomes numbers, the rest (words) stays text.

    A line that is not a row (too many or too few fields, not UTF-8, in a study table
    also an empty case_id or status, a word where the driver writes a number) is set
    aside with one line naming it (say, stderr by default), and the rest is read. A
    study table keeps one row per case, as prepare() would: a rerun's row unless only
    the earlier one has an answer (an interrupted --force leaves both in the file)."""
    path = Path(path)
    say = say or (lambda message: print(message, file=sys.stderr))
    raw = _raw(path)
    lines = raw.split(b"\n")
    if lines and lines[-1] == b"":
        lines.pop()
    if not lines:
        return pd.DataFrame()
    try:
        header = next(csv.reader([lines[0].decode("utf-8")]), [])
    except (UnicodeDecodeError, csv.Error):
        raise TableError(f"cannot read {path}: its header is not a CSV line") from None
    if not header:
        raise TableError(f"cannot read {path}: no header")
    study_table = set(_STUDY_KEYS) <= set(header)
    aside: list[tuple[int, str]] = []
    records: dict[object, dict[str, str]] = {}  # by case id in a study table, else by line
    twice = 0
    for number, line in enumerate(lines[1:], start=2):
        if not line.strip():
            continue
        try:
            fields = next(csv.reader([line.rstrip(b"\r").decode("utf-8")]))
        except (UnicodeDecodeError, csv.Error, StopIteration):
            aside.append((number, "not a CSV line of UTF-8 text"))
            continue
        if len(fields) != len(header):
            aside.append((number, f"{len(fields)} fields, not {len(header)}"))
            continue
        record = dict(zip(header, fields))
        reason = _reader_problem(record) if study_table else ""
        if reason:
            aside.append((number, reason))
            continue
        key: object = record["case_id"] if study_table else number
        if key in records:
            twice += 1
            if not later_wins(records[key], record):
                continue
        records.pop(key, None)  # the kept row takes its place in file order
        records[key] = record
    _say_aside(path, aside, say)
    if twice:
        say(f"{path.name}: {twice} case(s) found again (reruns the next sweep tidies away); one row of "
            "each is read, the rerun's unless only the earlier row has an answer")
    frame = pd.DataFrame(list(records.values()), columns=header, dtype=object)
    text = set(schema.DRIVER_TEXT)
    for col in frame.columns:
        if col in text or col == "expect_converged":
            continue
        numbers = pd.to_numeric(frame[col].replace("", math.nan), errors="coerce")
        if numbers.notna().sum() != (frame[col] != "").sum():
            text.add(col)  # words
    return _typed(frame, text)


def prepare(path: Path, columns: list[str], current_hash: str) -> tuple[pd.DataFrame, list[str]]:
    """Keep the rows of the current solver code; move the others aside, with a message each.

    Returns the kept table and the messages (bad lines by number, stale and replaced rows)."""
    checked = check(path, columns)
    messages = []
    stale_dir = path.parent / layout.STALE
    stamp = time.strftime("%Y%m%d-%H%M%S")

    def aside(name: str, text: str) -> Path:
        refuse_symlink(stale_dir, "folder")
        stale_dir.mkdir(exist_ok=True)
        target = stale_dir / name
        refuse_symlink(target)
        write_atomically(target, text)
        return target

    def rows_aside(name: str, rows: list[list[str]]) -> Path:
        """rows added to the stale table of that name, after the rows it holds already."""
        target = stale_dir / name
        old = check(target, columns).rows if target.exists() else []
        return aside(name, _csv_text(columns, old + rows))

    if checked.cut_last_line:
        messages.append(f"{path.name}: dropped a last line cut by an interrupted write")
    if checked.bad:
        target = aside(f"{path.stem}-bad-{stamp}.txt",
                       "\n".join(f"line {n}: {reason}: {line}" for n, reason, line in checked.bad) + "\n")
        for n, reason, _ in checked.bad[:5]:
            messages.append(f"{path.name}: line {n}: {reason}")
        if len(checked.bad) > 5:
            messages.append(f"{path.name}: ... {len(checked.bad) - 5} more")
        messages.append(f"{path.name}: {len(checked.bad)} bad line(s) moved to {target}")
    if checked.replaced:
        target = rows_aside(f"{path.stem}-replaced-{stamp}.csv", checked.replaced)
        messages.append(f"{path.name}: {len(checked.replaced)} row(s) replaced by a rerun of their case "
                        f"moved to {target}")
    if checked.unanswered_reruns:
        target = rows_aside(f"{path.stem}-unanswered-reruns-{stamp}.csv", checked.unanswered_reruns)
        messages.append(f"{path.name}: {len(checked.unanswered_reruns)} rerun(s) gave no answer and kept their "
                        f"case's earlier answered row; the reruns are in {target}")
    hash_col = columns.index("edp_hash")
    stale = [r for r in checked.rows if r[hash_col] != current_hash]
    kept = [r for r in checked.rows if r[hash_col] == current_hash]
    if stale:
        by_hash: dict[str, list[list[str]]] = {}
        for r in stale:
            by_hash.setdefault(r[hash_col], []).append(r)
        for h, rows in by_hash.items():
            rows_aside(f"{path.stem}-{h}.csv", rows)
        messages.append(f"{path.name}: {len(stale)} row(s) of other solver code moved to {stale_dir}/")
    if checked.cut_last_line or checked.bad or checked.replaced or checked.unanswered_reruns or stale:
        write_atomically(path, _csv_text(columns, kept))
    return frame_of(columns, kept), messages


def append_row(path: Path, row: dict, columns: list[str]) -> None:
    """One finished case, flushed and fsynced; raises TableError if the disk refuses."""
    buf = io.StringIO()
    writer = csv.DictWriter(buf, fieldnames=columns, lineterminator="\n", extrasaction="ignore")
    refuse_symlink(path)
    new = not path.exists() or path.stat().st_size == 0
    if new:
        writer.writeheader()
    writer.writerow({k: _cell(row.get(k)) for k in columns})
    data = buf.getvalue().encode("utf-8")
    try:
        fd = os.open(path, os.O_WRONLY | os.O_APPEND | os.O_CREAT | os.O_NOFOLLOW, 0o644)
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
