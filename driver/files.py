"""Writing files safely: whole or not at all, and never through a planted symbolic link."""
from __future__ import annotations

import os
import shutil
import tempfile
from collections.abc import Callable
from pathlib import Path

from driver.errors import HertzError


def refuse_symlink(path: Path, what: str, error: type[HertzError] = HertzError) -> None:
    """A table, lock or work folder that is a symbolic link could send writes anywhere
    (a dangling one creates its target): refuse it rather than follow it."""
    if path.is_symlink():
        raise error(f"{what} {path} is a symbolic link; refusing to write through it (remove it)")


def replace_atomically(path: Path, write: Callable[[Path], object], error: type[HertzError] = HertzError) -> None:
    """write(tmp) into a temporary file beside path, fsync it, then rename it over path:
    a kill or a full disk leaves the old file or the new one, never a cut one.

    tmp lies in a folder made for this write alone (mkdtemp: a fresh name, created
    exclusively, mode 0700), so no link planted under a predictable name is followed;
    the rename replaces a link at path itself, never its target."""
    folder: Path | None = None
    try:
        folder = Path(tempfile.mkdtemp(prefix=f".{path.name}.", suffix=".part", dir=path.parent))
        tmp = folder / f"{path.name}.part"
        write(tmp)
        fd = os.open(tmp, os.O_RDONLY | os.O_NOFOLLOW)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)
        os.replace(tmp, path)
        fd = os.open(path.parent, os.O_RDONLY)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)
    except OSError as exc:
        raise error(f"cannot write {path}: {exc.strerror or exc}") from None
    finally:
        if folder is not None:
            shutil.rmtree(folder, ignore_errors=True)  # a failure or Ctrl-C leaves no part file


def write_text_atomically(path: Path, text: str, error: type[HertzError] = HertzError) -> None:
    replace_atomically(path, lambda tmp: tmp.write_text(text, encoding="utf-8"), error)


def write_bytes_atomically(path: Path, data: bytes, error: type[HertzError] = HertzError) -> None:
    replace_atomically(path, lambda tmp: tmp.write_bytes(data), error)


def remove_part_files(folder: Path) -> None:
    """A run killed while writing leaves NAME.part files, and a planted NAME.part link
    would send the next run's write elsewhere: remove them (links themselves, never
    their targets) before a run writes there."""
    for path in folder.glob("*.part"):
        if path.is_symlink() or path.is_file():
            path.unlink(missing_ok=True)
