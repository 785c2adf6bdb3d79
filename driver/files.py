"""Writing files safely: whole or not at all, and never through a planted symbolic link."""
from __future__ import annotations

import os
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
    a kill or a full disk leaves the old file or the new one, never a cut one."""
    tmp = path.with_name(f".{path.name}.{os.getpid()}.part")
    try:
        write(tmp)
        fd = os.open(tmp, os.O_RDONLY)
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
        tmp.unlink(missing_ok=True)  # a failure or Ctrl-C leaves no part file


def write_text_atomically(path: Path, text: str, error: type[HertzError] = HertzError) -> None:
    replace_atomically(path, lambda tmp: tmp.write_text(text, encoding="utf-8"), error)
