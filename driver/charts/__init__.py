"""The report's charts (PNG, matplotlib), one module per study or per chart across studies.

A study names its charts in driver/studies.py (Study.charts; SUMMARY_CHARTS for those
that read every study); the module that draws them lists them in its CHARTS, with
their captions. Every module of this package is read here, so a new chart is its
module and its name in studies.py. Charts read CSV files only.
"""
from __future__ import annotations

import importlib
import pkgutil

import matplotlib

matplotlib.use("Agg")  # before any module of the package imports pyplot: no display needed

from driver.charts.common import Chart, NoData  # noqa: E402

CHARTS: dict[str, Chart] = {}
for _module in pkgutil.iter_modules(__path__):
    if _module.name != "common":
        CHARTS.update(importlib.import_module(f"{__name__}.{_module.name}").CHARTS)

__all__ = ["CHARTS", "Chart", "NoData"]
