"""The subcommands of `hertz`: each module has HELP, add_arguments(parser) and handle(args) -> int."""

NAMES = ("run", "curve", "sweep", "report", "bench", "options", "field")
