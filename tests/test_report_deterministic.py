"""The tracked outputs of `hertz report` are a function of the tables: drawn twice from the
committed CSV files they are the same bytes, so a fresh clone's `make report` leaves git
status clean. Nothing here writes into results/: the tables are copied out of git first."""
import re
import subprocess
import zlib
from pathlib import Path

import pytest

from conftest import REPO, cli

# PNG chunks that carry text or a time: a chart holds none of them
VARIABLE_CHUNKS = {b"tEXt", b"iTXt", b"zTXt", b"tIME"}


def _committed_tables(target: Path) -> Path:
    """results/**/*.csv as the last commit holds them (another sweep may be rewriting the working copies)."""
    names = subprocess.run(["git", "ls-files", "-z", "results"], cwd=REPO, capture_output=True,
                           check=True).stdout.decode().split("\0")
    for name in (n for n in names if n.endswith(".csv")):
        data = subprocess.run(["git", "show", f"HEAD:{name}"], cwd=REPO, capture_output=True, check=True).stdout
        path = target / Path(name).relative_to("results")
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(data)
    return target


def _outputs(folder: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir()) if p.suffix in (".png", ".md")}


def png_chunks(data: bytes) -> list[bytes]:
    assert data.startswith(b"\x89PNG\r\n\x1a\n")
    kinds, at = [], 8
    while at < len(data):
        length = int.from_bytes(data[at:at + 4], "big")
        kind = data[at + 4:at + 8]
        assert zlib.crc32(data[at + 4:at + 8 + length]) == int.from_bytes(data[at + 8 + length:at + 12 + length], "big")
        kinds.append(kind)
        at += 12 + length
    return kinds


@pytest.mark.slow
def test_the_report_drawn_from_the_committed_tables_is_the_same_bytes(tmp_path):
    # drawn in a fresh process as `make report` runs it; the committed report was drawn by another
    # (make rerun), so equal bytes are a report drawn twice alike (drawing it twice here cost 20 s)
    first = _committed_tables(tmp_path / "first")
    proc = cli("report", "--results", str(first))
    assert proc.returncode == 0, proc.stderr
    drawn = _outputs(first)
    assert "REPORT.md" in drawn and sum(name.endswith(".png") for name in drawn) >= 10, sorted(drawn)
    for name, data in drawn.items():
        if name.endswith(".png"):
            assert VARIABLE_CHUNKS.isdisjoint(png_chunks(data)), name
    # and the same bytes as the committed report: a fresh clone's make all leaves git status clean
    committed = {name: subprocess.run(["git", "show", f"HEAD:results/{name}"], cwd=REPO, capture_output=True,
                                      check=True).stdout for name in drawn}
    assert [name for name in drawn if drawn[name] != committed[name]] == []
    report = drawn["REPORT.md"].decode()
    assert not re.search(r"\d\d:\d\d:\d\d|\d{4}-\d\d-\d\dT\d\d", report), "a time of day in REPORT.md"
    # the versions and the sweep's own record stay
    assert "matplotlib" in report and "Sweep (the newest): date" in report
