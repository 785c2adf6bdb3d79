"""hertz run: one case, its row printed (every hertz.edp option is --name)."""
from __future__ import annotations

import argparse
import json
import math
import sys

from driver import freefem
from driver.commands.common import add_results, add_timeout, shown

HELP = "run one case; print its row (every hertz.edp option is --name)"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--json", action="store_true", help="print the row as JSON")
    add_timeout(parser, "seconds before the case is stopped")
    add_results(parser)
    # the solver's options come from hertz.edp's own table, whatever it holds today
    for option in freefem.options().values():
        if option.name in freefem.RUN_ONLY:
            continue
        parser.add_argument(f"--{option.name}", metavar=option.kind.upper(), dest=f"opt_{option.name}",
                            help=f"{option.help} (default {option.default}; {option.range})")


def handle(args: argparse.Namespace) -> int:
    from driver.api import solve_case
    options = {name: getattr(args, f"opt_{name}") for name in freefem.options()
               if getattr(args, f"opt_{name}", None) is not None}
    result = solve_case(options, args.timeout, args.results, prefix="--")
    clean = {k: (None if isinstance(v, float) and math.isnan(v) else v) for k, v in result.row.items()}
    if args.json:
        print(json.dumps(clean, indent=1, default=str))
    else:
        width = max(len(k) for k in clean)
        for key, value in clean.items():
            text = repr(value) if isinstance(value, float) else ("" if value is None else str(value))
            print(f"{key:{width}s}  {text}")
    print(f"files: {shown(result.files)}", file=sys.stderr)
    if result.status == "failed" and result.error:
        print(f"error: {result.error}", file=sys.stderr)
    return result.exit_code
