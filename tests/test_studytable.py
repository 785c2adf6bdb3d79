"""driver/studytable.py: study tables validated on load, appended row by row, repaired atomically, never
written through links."""
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd
import pytest

from driver import freefem, studytable
from driver.errors import TableError
from driver.schema import study_columns

from conftest import REPO


def _write_table(path: Path, rows: list[dict]) -> list[str]:
    columns = study_columns(freefem.summary_columns())
    for row in rows:
        good = {"status": "converged", "edp_hash": freefem.edp_hash(), "p0_fe": 1.0, "F_fe": 1.0, "a_fe": 1.0}
        studytable.append_row(path, good | row, columns)
    return columns


def test_a_table_is_validated_on_load_and_bad_lines_go_aside_by_number(tmp_path):
    path = tmp_path / "t.csv"
    columns = _write_table(path, [{"case_id": "a"}, {"case_id": "b"}, {"case_id": "a", "p0_fe": 2.0}])
    with open(path, "ab") as f:
        f.write(b"garbage,line\n")
        f.write(("t,c," + ",".join("x" for _ in columns[2:]) + "\n").encode())  # non-numeric values
        f.write(b"\xff\xfe not utf-8\n")
    good = len(columns) * [""]
    good[columns.index("case_id")], good[columns.index("edp_hash")] = "d", freefem.edp_hash()
    with open(path, "a") as f:
        f.write(",".join(good) + "\n")  # empty status
        f.write("t,half-written-row")  # cut by a kill
    frame, messages = studytable.prepare(path, columns, freefem.edp_hash())
    assert sorted(frame["case_id"]) == ["a", "b"]
    assert frame.set_index("case_id").loc["a", "p0_fe"] == 2.0  # the later run of a case wins
    assert any("cut by an interrupted write" in m for m in messages)
    aside = next((tmp_path / "stale").glob("t-bad-*.txt")).read_text()
    for expect in ("line 5: 2 fields", "line 6: ", "line 7: not UTF-8", "line 8: status ''", "garbage", "not utf-8"):
        assert expect in aside, (expect, aside)
    # the earlier row of a rerun case is kept aside as a table, not dropped
    replaced = pd.read_csv(next((tmp_path / "stale").glob("t-replaced-*.csv")))
    assert list(replaced["case_id"]) == ["a"] and replaced["p0_fe"].iloc[0] == 1.0
    assert any("replaced by a rerun" in m for m in messages)
    assert studytable.check(path, columns).bad == []  # what is left is clean


@pytest.mark.parametrize("edit", [{"p0_fe": ""}, {"F_fe": "nan"}, {"a_fe": "inf"},
                                  {"status": "inaccurate", "p0_fe": ""}])
def test_a_hand_edited_answer_without_numbers_is_not_a_finished_case(tmp_path, edit):
    # a row marked converged with an empty p0_fe used to count as done
    path = tmp_path / "t.csv"
    columns = _write_table(path, [{"case_id": "good"}, {"case_id": "edited"} | edit])
    frame, messages = studytable.prepare(path, columns, freefem.edp_hash())
    assert list(frame["case_id"]) == ["good"]
    assert any("without a finite" in m for m in messages), messages


def test_an_edp_hash_that_looks_like_a_number_stays_text(tmp_path):
    path = tmp_path / "t.csv"
    columns = _write_table(path, [{"case_id": "a", "edp_hash": "05426170e796"}])
    frame, _ = studytable.prepare(path, columns, "05426170e796")
    assert list(frame["case_id"]) == ["a"] and frame["edp_hash"].iloc[0] == "05426170e796"
    assert studytable.read(path)["edp_hash"].iloc[0] == "05426170e796"


def test_reading_a_table_needs_no_solver_and_keeps_words_as_words(tmp_path):
    path = tmp_path / "t.csv"
    _write_table(path, [{"case_id": "a", "model": "axi", "method": "lagrange"}])
    frame = studytable.read(path)
    assert frame["model"].iloc[0] == "axi" and frame["p0_fe"].dtype.kind == "f"


@pytest.mark.parametrize("kind", ["table", "lock", "stale"])
def test_a_planted_link_is_refused_not_written_through(tmp_path, kind):
    # a dangling link at results/<study>.csv used to make the sweep write outside the folder
    target = tmp_path / "elsewhere" / "victim"
    target.parent.mkdir()
    columns = study_columns(freefem.summary_columns())
    if kind == "table":
        (tmp_path / "t.csv").symlink_to(target)
        with pytest.raises(TableError, match="symbolic link"):
            studytable.append_row(tmp_path / "t.csv", {"case_id": "a"}, columns)
        with pytest.raises(TableError, match="symbolic link"):
            studytable.prepare(tmp_path / "t.csv", columns, "h")
    elif kind == "lock":
        (tmp_path / "t.lock").symlink_to(target)
        with pytest.raises(TableError, match="lock"):
            studytable.StudyLock(tmp_path / "t.lock").__enter__()
    else:
        _write_table(tmp_path / "t.csv", [{"case_id": "a", "edp_hash": "old"}])
        (tmp_path / "stale").symlink_to(target.parent)
        with pytest.raises(TableError, match="symbolic link"):
            studytable.prepare(tmp_path / "t.csv", columns, "new")
    assert not target.exists() and list(target.parent.iterdir()) == []


def test_a_table_that_is_a_folder_is_one_clear_error(tmp_path):
    (tmp_path / "t.csv").mkdir()
    with pytest.raises(TableError, match="not a file"):
        studytable.check(tmp_path / "t.csv", study_columns(freefem.summary_columns()))
    with pytest.raises(TableError, match="not a file"):
        studytable.read(tmp_path / "t.csv")


# A repair whose file writes are slowed down (in chunks, announced on stdout),
# so that the kill lands in the middle of writing, whatever writes.
REPAIR_SCRIPT = """
import builtins, io, sys, time
from pathlib import Path
from driver import studytable
real_open = io.open
class Slow:
    def __init__(self, f, name): self.f, self.name = f, name
    def write(self, data):
        if len(data) > 100000:
            print("writing", self.name, flush=True)
            for k in range(0, len(data), 20000):
                self.f.write(data[k:k + 20000]); self.f.flush(); time.sleep(0.01)
            return len(data)
        return self.f.write(data)
    def __getattr__(self, name): return getattr(self.f, name)
    def __enter__(self): return self
    def __exit__(self, *a): return self.f.__exit__(*a)
def slow_open(*args, **kw):
    f = real_open(*args, **kw)
    mode = kw.get("mode", args[1] if len(args) > 1 else "r")
    return Slow(f, str(args[0])) if "w" in mode else f
builtins.open = io.open = slow_open
path, columns, current = Path(sys.argv[1]), sys.argv[2].split(","), sys.argv[3]
studytable.prepare(path, columns, current)
"""


@pytest.mark.slow
def test_a_kill_during_a_table_repair_loses_nothing(tmp_path):
    columns = study_columns(freefem.summary_columns())
    rows = [{"case_id": f"c{k}", "edp_hash": "current" if k % 2 else "older"} for k in range(20000)]
    master = tmp_path / "master.csv"
    _write_table(master, rows[:1])
    fill = {"status": "converged", "p0_fe": 1.0, "F_fe": 1.0, "a_fe": 1.0}
    buf = pd.DataFrame([{c: "" for c in columns} | fill | r for r in rows])[columns]
    master.write_text(buf.to_csv(index=False) + "t,cut-line")
    current_rows = sum(1 for r in rows if r["edp_hash"] == "current")
    # kill during each large write of the table (or of its replacement), early and late in it
    for event, delay in ((1, 0.0), (1, 0.05), (2, 0.0), (2, 0.05)):
        path = tmp_path / f"t{event}-{delay}.csv"
        shutil.copy(master, path)
        proc = subprocess.Popen([sys.executable, "-c", REPAIR_SCRIPT, str(path), ",".join(columns), "current"],
                                cwd=REPO, stdout=subprocess.PIPE, text=True)
        seen = 0
        while seen < event and (line := proc.stdout.readline()):
            seen += path.name in line
        time.sleep(delay)
        proc.send_signal(signal.SIGKILL)
        proc.wait()
        kept = studytable.check(path, columns)
        # either the old table (all rows, cut line included) or the repaired one
        assert len(kept.rows) in (len(rows), current_rows), (delay, len(kept.rows))


def test_a_short_write_leaves_whole_lines(tmp_path, monkeypatch):
    path = tmp_path / "t.csv"
    columns = _write_table(path, [{"case_id": "a"}])
    before = path.read_bytes()
    monkeypatch.setattr(studytable.os, "write", lambda fd, data: 0)  # the disk took nothing
    with pytest.raises(TableError, match="No space left"):
        studytable.append_row(path, {"case_id": "b", "status": "converged"}, columns)
    assert path.read_bytes() == before
