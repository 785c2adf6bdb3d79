"""hertz report: the charts and REPORT.md from the study tables (reads CSV files only)."""
from __future__ import annotations

import argparse
import sys

from driver.commands.common import add_results, shown

HELP = "charts and REPORT.md from the study tables (reads CSV only)"
INTERRUPTED_LINE = "interrupted: each chart and REPORT.md is whole, the new one or the earlier one"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_results(parser)


def handle(args: argparse.Namespace) -> int:
    from driver.report import write_report
    print(shown(write_report(args.results, say=lambda m: print(m, file=sys.stderr))))
    return 0
