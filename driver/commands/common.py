"""What the subcommands share: argument types, hertz.edp's options as arguments, and a parser
that refuses an option given twice, suggests the option meant, and says `hertz: error:`."""
from __future__ import annotations

import argparse
import difflib
import math
import re
from pathlib import Path
from typing import Any

from driver import layout
from driver.errors import error_line


class Once(argparse.Action):
    """Store a value, refusing a second one: `--n 6 --n 8` is a mistake, not a choice
    (hertz.edp refuses an option given twice as well)."""

    def __call__(self, parser, namespace, values, option_string=None):
        given = namespace.__dict__.setdefault("_given", set())
        if self.dest in given:
            parser.error(f"{option_string} is given twice; give it once")
        given.add(self.dest)
        setattr(namespace, self.dest, values)


class Parser(argparse.ArgumentParser):
    """argparse with Once for every option that takes a value (subparsers inherit it)."""

    # the subcommand's parser, once build_parser made it: argparse reports a subcommand's
    # unknown options from the top parser, which alone does not know them
    chosen: argparse.ArgumentParser | None = None

    def add_argument(self, *args, **kwargs):
        if args and args[0].startswith("-") and "action" not in kwargs:
            kwargs["action"] = Once
        return super().add_argument(*args, **kwargs)

    def error(self, message: str):
        """One line naming the problem (argparse would print the whole usage first), with the
        option or command meant when a typo is close to one (argparse suggests only from 3.14)."""
        where = (self.chosen or self).prog
        self.exit(2, error_line(f"{message}{self._suggestion(message)} (see {where} --help)") + "\n")

    def _suggestion(self, message: str) -> str:
        # after a command, only its own options are taken (hertz --version is the program's)
        parsers = [self.chosen] if self.chosen is not None else [self]
        if message.startswith("unrecognized arguments:"):
            known = [name for p in parsers for name in p._option_string_actions if name.startswith("--")]
            typed = [word.split("=", 1)[0] for word in message.split(":", 1)[1].split() if word.startswith("--")]
        else:
            match = re.search(r"argument COMMAND: invalid choice: '([^']*)'", message)
            from driver.commands import NAMES
            known, typed = list(NAMES), [match.group(1)] if match else []
        for word in typed:
            if word in self._option_string_actions and word not in known:
                return f"; {word} goes before the command (hertz {word})"
            close = difflib.get_close_matches(word, known, n=1)
            if close:
                return f"; did you mean {close[0]}?"
        return ""


def positive(kind, upper: float = math.inf, unit: str = ""):
    """A parser of positive numbers of this kind, at most upper, naming the range when refused."""
    shown = f"(0, {upper:g}]" + (f" {unit}" if unit else "") if upper < math.inf else "(0, inf)"

    def parse(text: str):
        try:
            value = kind(text)
        except (ValueError, OverflowError):
            value = None
        if value is None or not 0 < value <= upper or not math.isfinite(value):
            raise argparse.ArgumentTypeError(f"must be a {'number' if kind is float else 'whole number'} "
                                             f"in {shown}, got {text!r}")
        return value
    return parse


def add_timeout(parser: argparse.ArgumentParser, help_text: str) -> None:
    from driver.run import MAX_TIMEOUT  # the run machinery only for the commands that run cases
    parser.add_argument("--timeout", type=positive(float, MAX_TIMEOUT, "seconds"), default=600.0,
                        help=f"{help_text} (default: %(default)s; at most {MAX_TIMEOUT:g})")


def add_results(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--results", type=layout.user_path, default=layout.user_path(layout.DEFAULT_RESULTS),
                        metavar="DIR", help="results folder, relative to the working directory "
                                            f"(default: ./{layout.DEFAULT_RESULTS})")


def shown(path: Path) -> str:
    """A path as short as it can be said from the working directory."""
    try:
        return str(path.relative_to(Path.cwd()))
    except ValueError:
        return str(path)


def add_solver_options(parser: argparse.ArgumentParser, taken: tuple[str, ...] = ()) -> None:
    """Every option of hertz.edp's table as --name (dest opt_name), but RUN_ONLY ones and those
    taken. A 0/1 option is also a switch: a bare --cont is --cont 1."""
    from driver import freefem
    for option in freefem.options().values():
        if option.name in freefem.RUN_ONLY or option.name in taken:
            continue
        switch = option.kind == "int" and option.range == "integer in [0, 1]"
        bare: dict[str, Any] = {"nargs": "?", "const": "1"} if switch else {}
        parser.add_argument(f"--{option.name}", metavar=option.kind.upper(), dest=f"opt_{option.name}",
                            help=f"{option.help} (default {option.default}; {option.range}"
                                 + (f"; a bare --{option.name} is 1)" if switch else ")"),
                            **bare)


def solver_values(args: argparse.Namespace) -> dict[str, str]:
    """The hertz.edp options given on the command line, by name, as typed."""
    return {name.removeprefix("opt_"): value for name, value in vars(args).items()
            if name.startswith("opt_") and value is not None}


def add_talk(parser: argparse.ArgumentParser, verbose: bool = True) -> None:
    talk = parser.add_mutually_exclusive_group()
    talk.add_argument("-q", "--quiet", action="store_true",
                      help="print only the results and errors: no solver warnings, no files line")
    if verbose:
        talk.add_argument("-v", "--verbose", action="store_true",
                          help="show the solver's output on stderr as it runs")
