"""Sweeps, tables and charts for the FreeFEM Hertz contact solver (hertz.edp), and a small Python API.

    from driver import solve, sweep
    result = solve(kpen=1e5)             # one case: a Result (status, exit_code, p0, F, a, files, row)
    table = sweep("kpen", quick=True)    # a study: a pandas DataFrame, one row per case

docs/driver.md is the reference. Importing the package runs nothing: no
solver is asked anything and no process setting changes until a function runs.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

__version__ = "0.4.0"
__all__ = ["HertzError", "Result", "__version__", "solve", "sweep"]

if TYPE_CHECKING:
    from driver.api import Result, solve, sweep
    from driver.errors import HertzError


def __getattr__(name: str):
    # the API loads pandas and the run machinery: only when it is used
    if name in ("Result", "solve", "sweep"):
        from driver import api
        return getattr(api, name)
    if name == "HertzError":
        from driver.errors import HertzError
        return HertzError
    raise AttributeError(f"module 'driver' has no attribute {name!r}")
