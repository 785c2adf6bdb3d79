"""Command line: hertz {run,curve,sweep,report,bench,options,field} --help  (or python -m driver ...).

Each subcommand is a module of driver.commands with its own arguments and
handler; this module only assembles them. A subcommand's arguments are built
only when it is the one typed: `hertz run` asks hertz.edp for its options, and
`hertz report` must work where FreeFEM is absent.
"""
from __future__ import annotations

import importlib
import os
import sys

from driver import __version__
from driver.commands import NAMES
from driver.commands.common import Parser
from driver.errors import HertzError, error_line
from driver.processes import Interrupted

INTERRUPTED = 130  # 128 + SIGINT, as a shell reports it


def build_parser(argv: list[str]) -> Parser:
    parser = Parser(prog="hertz", description="Hertz contact in FreeFEM: run cases, sweep studies, chart them "
                                              "(docs/driver.md).")
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    chosen = argv[0] if argv and argv[0] in NAMES else None
    for name in NAMES:
        module = importlib.import_module(f"driver.commands.{name}")
        command = sub.add_parser(name, help=module.HELP, description=module.HELP)
        if name == chosen:
            module.add_arguments(command)
            command.set_defaults(handle=module.handle)
            parser.chosen = command
    return parser


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    interrupted = "interrupted"  # a command that keeps work says what it kept (its INTERRUPTED_LINE)
    try:
        if argv and argv[0] in NAMES:
            command = importlib.import_module(f"driver.commands.{argv[0]}")
            interrupted = getattr(command, "INTERRUPTED_LINE", interrupted)
        args = build_parser(argv).parse_args(argv)
        return args.handle(args)
    except HertzError as exc:
        print(error_line(str(exc)), file=sys.stderr)
        return 2
    except KeyboardInterrupt as exc:  # Ctrl-C, or SIGTERM and SIGHUP (processes.Interrupted)
        print(interrupted, file=sys.stderr)
        return 128 + exc.signum if isinstance(exc, Interrupted) else INTERRUPTED
    except BrokenPipeError:
        # the reader went away (hertz run | head): not an error of the run's
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
