"""hertz bench: timing benchmark, medians of interleaved runs (peers included when installed)."""
from __future__ import annotations

import argparse

from driver import layout
from driver.commands.common import positive

HELP = "timing benchmark: medians of repeated runs"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--repeat", type=positive(int, 1000), default=5, help="runs per configuration")
    parser.add_argument("--out", type=layout.user_path,
                        default=layout.user_path(f"{layout.DEFAULT_RESULTS}/{layout.LOCAL}/bench.csv"),
                        metavar="FILE", help="where the table goes (default: %(default)s, not tracked)")


def handle(args: argparse.Namespace) -> int:
    from driver.timing import bench
    return bench(args.out, args.repeat)
