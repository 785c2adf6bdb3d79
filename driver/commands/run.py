"""hertz run: one case, its row printed (every hertz.edp option is --name)."""
from __future__ import annotations

import argparse
import contextlib
import json
import math
import sys

from driver.commands.common import add_results, add_solver_options, add_talk, add_timeout, shown, solver_values
from driver.errors import error_line

HELP = "run one case; print its row (every hertz.edp option is --name)"
INTERRUPTED_LINE = "interrupted: the case was stopped, its solver with it, before its answer"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--json", action="store_true", help="print the row as JSON")
    add_timeout(parser, "seconds before the case is stopped")
    add_results(parser)
    add_talk(parser)
    # the solver's options come from hertz.edp's own table, whatever it holds today
    add_solver_options(parser)


def say(line: str) -> None:
    print(line, file=sys.stderr, flush=True)


def handle(args: argparse.Namespace) -> int:
    from driver.processes import install_signal_handlers
    install_signal_handlers()  # SIGTERM and SIGHUP end it as Ctrl-C does
    from driver.api import solve_case
    from driver.run import LOG_FILE, MEMORY, SOLVER_PROGRESS, echoing, solver_warnings

    def progress(line: str) -> None:  # a long run's levels, as they end
        if line.startswith(SOLVER_PROGRESS):
            say(line)
    with echoing(say if args.verbose else progress) if not args.quiet else contextlib.nullcontext():
        result = solve_case(solver_values(args), args.timeout, args.results, prefix="--")
    clean = {k: (None if isinstance(v, float) and math.isnan(v) else v) for k, v in result.row.items()}
    if args.json:
        print(json.dumps(clean, indent=1, default=str))
    else:
        width = max(len(k) for k in clean)
        for key, value in clean.items():
            text = repr(value) if isinstance(value, float) else ("" if value is None else str(value))
            print(f"{key:{width}s}  {text}")
    sys.stdout.flush()
    if not args.quiet:
        if not args.verbose:  # -v showed them as they came
            for warning in solver_warnings(result.files / LOG_FILE):
                say(warning)
        say(f"files: {shown(result.files)}")
    if result.status in ("failed", MEMORY) and result.error:
        say(error_line(result.error))
    return result.exit_code


