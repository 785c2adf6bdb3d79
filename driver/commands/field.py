"""hertz field: the seed case's von Mises field rendered off-screen to <results>/field.png (pyvista)."""
from __future__ import annotations

import argparse

from driver.commands.common import add_results, shown
from driver.errors import SetupError

HELP = "render the seed case's von Mises field to results/field.png (pyvista)"
INTERRUPTED_LINE = "interrupted: the field picture is whole, the new one or the earlier one"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_results(parser)


def handle(args: argparse.Namespace) -> int:
    try:
        import pyvista  # noqa: F401 - optional: only this command needs it

        from driver.fields import make_field_picture
    except ImportError:
        raise SetupError("the field picture needs pyvista: pip install 'hertz-contact[fields]'") from None
    print(shown(make_field_picture(args.results)))
    return 0
