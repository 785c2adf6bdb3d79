"""Command line: python -m driver {run,sweep,report,bench} --help."""
from __future__ import annotations

import argparse
import os
import sys
import time
from dataclasses import fields
from pathlib import Path

import pandas as pd

from driver import RESULTS_DIR
from driver.cases import Case
from driver.run import SetupError, run_case
from driver.studies import STUDIES, SpecError, load_spec
from driver.sweep import SweepError, sweep

_HELP = {
    "model": "axi (sphere) or plane (cylinder)", "method": "newton, fixedpoint or auglag",
    "order": "element order, 1 or 2", "n": "elements per contact radius",
    "L": "domain radius in contact radii", "kpen": "penalty stiffness",
    "omega": "fixed-point relaxation", "E": "Young's modulus", "nu": "Poisson's ratio",
    "R": "indenter radius", "d": "indentation depth", "cont": "Newton penalty continuation, 0 or 1",
    "maxit": "maximum iterations", "tol": "tolerance on residual and increment",
}


def _positive(kind):
    def parse(text):
        try:
            value = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"must be a positive {kind.__name__}, got {text!r}")
        if not value > 0 or value != value or value == float("inf"):
            raise argparse.ArgumentTypeError(f"must be a positive {kind.__name__}, got {text!r}")
        return value
    return parse


def _common(p: argparse.ArgumentParser) -> None:
    p.add_argument("--results", type=Path, default=RESULTS_DIR,
                   help="results directory (default: %(default)s)")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="python -m driver", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)

    run = sub.add_parser("run", help="run one case and print its row")
    defaults = Case()
    for f in fields(Case):
        kind = {"model": str, "method": str, "order": int, "n": int, "cont": int,
                "maxit": int}.get(f.name, float)
        run.add_argument(f"--{f.name}", type=kind, default=getattr(defaults, f.name),
                         help=f"{_HELP[f.name]} (default: %(default)s)")
    run.add_argument("--timeout", type=_positive(float), default=600.0,
                     help="seconds before the case is stopped (default: %(default)s)")
    _common(run)

    sw = sub.add_parser("sweep", help="run named studies or a spec file, resumably")
    sw.add_argument("studies", nargs="*", metavar="STUDY",
                    help=f"study names: {', '.join(STUDIES)}; none with --spec")
    sw.add_argument("--all", action="store_true", help="every named study")
    sw.add_argument("--quick", action="store_true", help="the small subset used by tests and CI")
    sw.add_argument("--spec", type=Path, help="TOML or JSON grid: name, [base], [grid]")
    sw.add_argument("--jobs", type=_positive(int), default=os.cpu_count() or 1,
                    help="parallel FreeFEM processes (default: cores = %(default)s)")
    sw.add_argument("--timeout", type=_positive(float), default=600.0,
                    help="seconds per case before it becomes a timeout row (default: %(default)s)")
    sw.add_argument("--force", action="store_true", help="rerun cases already in the CSV")
    sw.add_argument("--no-progress", action="store_true", help="no progress bar")
    _common(sw)

    rep = sub.add_parser("report", help="charts and REPORT.md from the study CSVs")
    _common(rep)

    bench = sub.add_parser("bench", help="timing benchmark: medians of repeated runs")
    bench.add_argument("--repeat", type=_positive(int), default=5, help="runs per configuration")
    _common(bench)
    return parser


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    try:
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
            return bench(args.results, args.repeat)
    except (SetupError, SweepError, SpecError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("interrupted: finished cases are kept; run the same command to resume",
              file=sys.stderr)
        return 130
    return 1


def _run(args) -> int:
    case = Case(**{f.name: getattr(args, f.name) for f in fields(Case)})
    workdir = args.results / "runs" / "single" / case.case_id
    row = run_case(case, workdir, args.timeout, study="single")
    print(pd.Series(row, dtype=object).to_string())
    print(f"files: {workdir}", file=sys.stderr)
    return 0 if row["status"] == "converged" else 3


def _sweep(args) -> int:
    jobs = []
    if args.spec:
        if args.studies or args.all:
            raise SweepError("--spec runs one grid; give no study names or --all with it")
        name, cases = load_spec(args.spec)
        jobs.append((name, cases))
    else:
        names = list(STUDIES) if args.all else args.studies
        if not names:
            raise SweepError("name at least one study, or use --all or --spec")
        for name in names:
            if name not in STUDIES:
                raise SweepError(f"unknown study '{name}'; known: {', '.join(STUDIES)}")
            jobs.append((name, STUDIES[name](args.quick)))
    start = time.perf_counter()
    bad = 0
    for name, cases in jobs:
        frame = sweep(name, cases, args.results, args.jobs, args.timeout, args.force,
                      progress=not args.no_progress)
        ids = {c.case_id for c in cases}
        mine = frame[frame["case_id"].isin(ids)]
        counts = mine["status"].value_counts().to_dict()
        bad += int((mine["status"] != "converged").sum())
        print(f"{name}: {len(mine)} cases in {args.results / (name + '.csv')}: {counts}")
    print(f"sweep done in {time.perf_counter() - start:.1f} s")
    return 0
