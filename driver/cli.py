"""Command line: hertz {run,sweep,report,bench,options} --help  (or python -m driver ...)."""
from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from pathlib import Path

from driver import RESULTS_DIR, freefem
from driver.cases import Case
from driver.table import TableError

EXIT_FAILED = 1  # the driver could not get an answer (hertz.edp's own codes are 0, 2, 3, 4, 5)


def _positive(kind):
    def parse(text):
        try:
            value = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"must be a positive {kind.__name__}, got {text!r}") from None
        if not value > 0 or not math.isfinite(value):
            raise argparse.ArgumentTypeError(f"must be a positive {kind.__name__}, got {text!r}")
        return value
    return parse


def _scheduler(text: str) -> str:
    from driver.dask_backend import parse_local
    try:
        parse_local(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None
    return text


def _results(p: argparse.ArgumentParser) -> None:
    p.add_argument("--results", type=Path, default=RESULTS_DIR,
                   help="results directory (default: %(default)s)")


def build_parser(with_solver_options: bool = False) -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="hertz", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)

    run = sub.add_parser("run", help="run one case; print its row (every hertz.edp option is --name)")
    run.add_argument("--json", action="store_true", help="print the row as JSON")
    run.add_argument("--timeout", type=_positive(float), default=600.0,
                     help="seconds before the case is stopped (default: %(default)s)")
    _results(run)
    if with_solver_options:
        for option in freefem.options().values():
            if option.name in ("check",):
                continue
            run.add_argument(f"--{option.name}", metavar=option.kind.upper(), dest=f"opt_{option.name}",
                             help=f"{option.help} (default {option.default}; {option.range})")

    sw = sub.add_parser("sweep", help="run named studies or a spec file, resumably")
    sw.add_argument("studies", nargs="*", metavar="STUDY", help="study names (see --list); none with --spec")
    sw.add_argument("--all", action="store_true", help="every named study")
    sw.add_argument("--list", action="store_true", help="list the named studies and exit")
    sw.add_argument("--quick", action="store_true", help="the small subsets used by the tests")
    sw.add_argument("--spec", type=Path, help="TOML or JSON grid: name, [base], [grid]")
    sw.add_argument("--jobs", type=_positive(int), default=None,
                    help="parallel FreeFEM processes (default: the cores; with --scheduler the workers decide)")
    sw.add_argument("--scheduler", type=_scheduler, metavar="ADDRESS",
                    default=os.environ.get("DASK_SCHEDULER_ADDRESS") or None,
                    help="run the cases on a Dask cluster: a scheduler address (tcp://host:8786), or local:N "
                         "for N single-threaded local workers (default: $DASK_SCHEDULER_ADDRESS, else this "
                         "machine's cores)")
    sw.add_argument("--timeout", type=_positive(float), default=600.0,
                    help="seconds per case before it becomes a timeout row (default: %(default)s)")
    sw.add_argument("--force", action="store_true", help="rerun cases already in the table")
    sw.add_argument("--retry-failed", action="store_true", help="rerun only failed and timeout rows")
    sw.add_argument("--yes", action="store_true", help="run a grid above 10000 cases")
    sw.add_argument("--no-progress", action="store_true", help="no progress bar")
    _results(sw)

    rep = sub.add_parser("report", help="charts and REPORT.md from the study tables (reads CSV only)")
    _results(rep)

    bench = sub.add_parser("bench", help="timing benchmark: medians of repeated runs")
    bench.add_argument("--repeat", type=_positive(int), default=5, help="runs per configuration")
    bench.add_argument("--out", type=Path, default=RESULTS_DIR / "local" / "bench.csv",
                       help="where the table goes (default: %(default)s, not tracked)")

    sub.add_parser("options", help="hertz.edp's option table")

    field = sub.add_parser("field", help="render the seed case's von Mises field to results/field.png (pyvista)")
    _results(field)
    return parser


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    try:
        # the run command's options come from hertz.edp's own table
        parser = build_parser(with_solver_options=bool(argv) and argv[0] == "run")
        args = parser.parse_args(argv)
        if args.command == "run":
            return _run(args)
        if args.command == "sweep":
            return _sweep(args)
        if args.command == "report":
            from driver.report import write_report
            print(write_report(args.results))
            return 0
        if args.command == "bench":
            from driver.bench import bench
            return bench(args.out, args.repeat)
        if args.command == "field":
            from driver.fields import make_field_picture
            try:
                print(make_field_picture(args.results))
            except ImportError:
                print("error: the field picture needs pyvista: pip install -e '.[fields]'", file=sys.stderr)
                return 2
            except RuntimeError as exc:
                print(f"error: {exc}", file=sys.stderr)
                return EXIT_FAILED
            return 0
        if args.command == "options":
            for option in freefem.options().values():
                print(f"-{option.name:12s} {option.default:24s} {option.range:32s} {option.help}")
            return 0
    except (freefem.SetupError, TableError, FileNotFoundError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("interrupted: finished cases are kept; run the same command to resume", file=sys.stderr)
        return 130
    return EXIT_FAILED


def _exit_code(row: dict) -> int:
    """hertz.edp's exit code for this row's outcome."""
    from driver.schema import EXIT_OF_STATUS
    status = row.get("status")
    if status in EXIT_OF_STATUS:
        return EXIT_OF_STATUS[status]
    if status in ("timeout", "nan"):
        return 3
    code = row.get("exit_code")
    return int(code) if isinstance(code, (int, float)) and code == code and code in (2, 4) else EXIT_FAILED


def _run(args) -> int:
    from driver.run import run_case
    params = {}
    for option in freefem.options().values():
        text = getattr(args, f"opt_{option.name}", None)
        if text is not None:
            params[option.name] = text  # passed on as typed: hertz.edp checks it
    out = params.pop("out", None)
    case = Case(tuple(sorted(params.items())))
    workdir = Path(out) if out else args.results / "runs" / "single" / case.case_id
    row = run_case(case, workdir, args.timeout, study="single")
    clean = {k: (None if isinstance(v, float) and math.isnan(v) else v) for k, v in row.items()}
    if args.json:
        print(json.dumps(clean, indent=1, default=str))
    else:
        width = max(len(k) for k in clean)
        for key, value in clean.items():
            text = repr(value) if isinstance(value, float) else ("" if value is None else str(value))
            print(f"{key:{width}s}  {text}")
    print(f"files: {workdir}", file=sys.stderr)
    if row.get("status") == "failed" and row.get("error"):
        print(f"error: {row['error']}", file=sys.stderr)
    return _exit_code(row)


def _sweep(args) -> int:
    from driver.studies import STUDIES, SpecError, load_spec
    from driver.sweep import Job, SweepError, cores, install_signal_handlers, report_unexpected, run_studies
    if args.list:
        for name, study in STUDIES.items():
            print(f"{name:10s} {len(study.make(False)):4d} cases ({len(study.make(True))} quick): "
                  f"{(study.make.__doc__ or '').strip().splitlines()[0]}")
        return 0
    try:
        jobs_list = []
        if args.spec:
            if args.studies or args.all:
                raise SweepError("--spec runs one grid; give no study names or --all with it")
            name, cases = load_spec(args.spec)
            jobs_list.append(Job(name, cases))
        else:
            names = list(STUDIES) if args.all else args.studies
            if not names:
                raise SweepError("name at least one study, or use --all or --spec")
            for name in names:
                if name not in STUDIES:
                    raise SweepError(f"unknown study '{name}'; known: {', '.join(STUDIES)}")
                study = STUDIES[name]
                jobs_list.append(Job(name, study.make(args.quick), study.keep, study.repeats))
        count = sum(len(j.cases) for j in jobs_list)
        if count > 10_000 and not args.yes:
            raise SweepError(f"{count} cases: a grid above 10000 needs --yes")
        jobs = args.jobs or cores()
        if args.scheduler and args.jobs:
            print(f"warning: --jobs is ignored with --scheduler {args.scheduler}: each worker thread runs "
                  "one case at a time", file=sys.stderr)
        elif jobs > cores():
            print(f"warning: --jobs {jobs} is more than the {cores()} cores: cases will share cores "
                  "and their wall_time (column jobs records it) will grow", file=sys.stderr)
        install_signal_handlers()
        start = time.perf_counter()
        outcomes = run_studies(jobs_list, args.results, jobs, args.timeout, args.force,
                               args.retry_failed, progress=not args.no_progress,
                               say=lambda m: print(m, file=sys.stderr), scheduler=args.scheduler)
    except (SweepError, SpecError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    for o in outcomes:
        counts = o.table["status"].value_counts().to_dict() if len(o.table) else {}
        print(f"{o.study}: {len(o.table)} cases ({o.ran} run now) in "
              f"{args.results / (o.study + '.csv')}: {counts}")
    print(f"sweep done in {time.perf_counter() - start:.1f} s")
    bad = report_unexpected(outcomes)
    if bad:
        print(f"{bad} case(s) expected to converge did not (listed above)", file=sys.stderr)
        return EXIT_FAILED
    return 0
