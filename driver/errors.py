"""The driver's exception types, in one place so that every module can raise them
without importing another's machinery.

Each is an error a user can act on: the command line prints its message as one
line and exits with code 2.
"""
from __future__ import annotations

SOLVER_ERROR = "hertz.edp: error:"  # hertz.edp's own error lines start so, and are shown as they are


def error_line(message: str) -> str:
    """The one line an error is shown as: `hertz: error: ...`, or the solver's own line."""
    return message if message.startswith(SOLVER_ERROR) else f"hertz: error: {message}"


class HertzError(Exception):
    """An error the user can act on; its message is one line that says what and why."""


class SetupError(HertzError):
    """The solver cannot run at all on this machine."""


class OptionError(HertzError, ValueError):
    """A value outside hertz.edp's option table (unknown name, wrong type, out of range)."""


class RejectedError(HertzError, ValueError):
    """hertz.edp itself refused the case (ranges that depend on the scene, such as -d < R)."""


class SpecError(HertzError, ValueError):
    """A study spec file that cannot define cases."""


class TableError(HertzError):
    """A study table that cannot be read or written; the message says which and why."""


class SweepError(HertzError):
    """A sweep that cannot start or go on."""


class ReportError(HertzError):
    """A chart or the report could not be written."""
