"""hertz sweep: named studies or a spec file, into their tables, resumably."""
from __future__ import annotations

import argparse
import os
import sys
import time

from driver import layout
from driver.commands.common import add_results, add_timeout, positive, shown

HELP = "run named studies or a spec file, resumably"
INTERRUPTED_LINE = "interrupted: finished cases are kept; run the same command to resume"


def _scheduler(text: str) -> str:
    from driver.dask_backend import parse_local
    try:
        parse_local(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None
    return text


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("studies", nargs="*", metavar="STUDY", help="study names (see --list); none with --spec")
    parser.add_argument("--all", action="store_true", help="every named study")
    parser.add_argument("--list", action="store_true", help="list the named studies and exit")
    parser.add_argument("--quick", action="store_true", help="the small subsets used by the tests")
    parser.add_argument("--spec", type=layout.user_path, metavar="FILE", help="TOML or JSON grid: name, [base], [grid]")
    parser.add_argument("--jobs", type=positive(int, 4096), default=None,
                        help="parallel FreeFEM processes (default: the cores; with --scheduler the workers decide)")
    parser.add_argument("--scheduler", type=_scheduler, metavar="ADDRESS",
                        default=os.environ.get("DASK_SCHEDULER_ADDRESS") or None,
                        help="run the cases on a Dask cluster: a scheduler address (tcp://host:8786), or local:N "
                             "for N single-threaded local workers (default: $DASK_SCHEDULER_ADDRESS, else this "
                             "machine's cores)")
    add_timeout(parser, "seconds per case before it becomes a timeout row")
    parser.add_argument("--force", action="store_true",
                        help="rerun cases already in the table (each old row stays until its rerun lands)")
    parser.add_argument("--retry-failed", action="store_true", help="rerun only failed and timeout rows")
    parser.add_argument("--yes", action="store_true", help="run a grid above 10000 cases")
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")
    add_results(parser)


def handle(args: argparse.Namespace) -> int:
    from driver import processes, sweeps
    from driver.studies import STUDIES
    if args.list:
        for name, study in STUDIES.items():
            print(f"{name:12s} {len(study.make(False)):4d} cases ({len(study.make(True))} quick): "
                  f"{(study.make.__doc__ or '').strip().splitlines()[0]}")
        return 0
    names = list(STUDIES) if args.all else args.studies
    jobs_list = sweeps.jobs_from(names=names, spec=args.spec, quick=args.quick, yes=args.yes)
    jobs = args.jobs or sweeps.cores()
    if args.scheduler and args.jobs:
        print(f"hertz: warning: --jobs is ignored with --scheduler {args.scheduler}: each worker thread runs "
              "one case at a time", file=sys.stderr)
    elif jobs > sweeps.cores():
        print(f"hertz: warning: --jobs {jobs} is more than the {sweeps.cores()} cores: cases will share cores "
              "and their wall_time (column jobs records it) will grow", file=sys.stderr)
    # orphans of this sweep's cases come to this process, which kills and reaps them
    processes.become_subreaper()
    processes.install_signal_handlers()
    start = time.perf_counter()
    try:
        outcomes = sweeps.run_studies(jobs_list, args.results, jobs, args.timeout, args.force,
                                      args.retry_failed, progress=not args.no_progress,
                                      say=lambda m: print(m, file=sys.stderr), scheduler=args.scheduler)
    finally:
        processes.reap_adopted()
    for o in outcomes:
        counts = o.table["status"].value_counts().to_dict() if len(o.table) else {}
        print(f"{o.study}: {len(o.table)} cases ({o.ran} run now) in "
              f"{shown(layout.study_csv(args.results, o.study))}: "
              + (", ".join(f"{count} {status}" for status, count in counts.items()) or "none"))
    print(f"sweep done in {time.perf_counter() - start:.1f} s")
    bad = sweeps.report_unexpected(outcomes)
    if bad:
        print(f"{bad} case(s) expected to converge did not (listed above)", file=sys.stderr)
        return 1
    return 0
