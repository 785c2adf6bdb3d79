"""The subcommands of `hertz`: each module has HELP, add_arguments(parser) and handle(args) -> int."""

NAMES = ("run", "sweep", "report", "bench", "options", "field")
