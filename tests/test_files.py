"""driver/files.py: a file is replaced whole or not at all, and never written through a link."""
import pytest

from driver import files
from driver.errors import HertzError, ReportError


def test_a_write_that_fails_keeps_the_old_file_and_leaves_no_part(tmp_path):
    target = tmp_path / "t.csv"
    target.write_text("old\n")

    def half_then_full_disk(tmp):
        tmp.write_text("new, cut")
        raise OSError(28, "No space left on device")
    with pytest.raises(ReportError, match=r"cannot write .*t\.csv: No space left on device"):
        files.replace_atomically(target, half_then_full_disk, ReportError)
    assert target.read_text() == "old\n"
    assert [p.name for p in tmp_path.iterdir()] == ["t.csv"]


def test_a_whole_write_replaces_the_file(tmp_path):
    target = tmp_path / "t.csv"
    target.write_text("old\n")
    files.write_text_atomically(target, "new\n")
    assert target.read_text() == "new\n" and [p.name for p in tmp_path.iterdir()] == ["t.csv"]


def test_a_link_is_refused_even_a_dangling_one(tmp_path):
    link = tmp_path / "t.csv"
    link.symlink_to(tmp_path / "elsewhere.csv")
    with pytest.raises(HertzError, match="symbolic link"):
        files.refuse_symlink(link, "table")
    files.refuse_symlink(tmp_path / "plain.csv", "table")  # a path that is no link passes
