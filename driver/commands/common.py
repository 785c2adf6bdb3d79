"""What the subcommands share: argument types, and a parser that refuses an option given twice."""
from __future__ import annotations

import argparse
import math
from pathlib import Path

from driver import layout


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

    def add_argument(self, *args, **kwargs):
        if args and args[0].startswith("-") and "action" not in kwargs:
            kwargs["action"] = Once
        return super().add_argument(*args, **kwargs)

    def error(self, message: str):
        """One line naming the problem (argparse would print the whole usage first)."""
        self.exit(2, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


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
