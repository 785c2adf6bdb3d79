"""hertz options: hertz.edp's option table (and, with --exits, its exit codes)."""
from __future__ import annotations

import argparse

from driver import freefem

HELP = "hertz.edp's option table (--exits: its exit codes)"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--exits", action="store_true", help="the exit codes and what each status means")


def handle(args: argparse.Namespace) -> int:
    if args.exits:
        for e in freefem.exits().values():
            print(f"{e.code:3d}  {e.status:14s} {e.meaning}")
        return 0
    for option in freefem.options().values():
        print(f"-{option.name:12s} {option.default:24s} {option.range:32s} {option.help}")
    return 0
