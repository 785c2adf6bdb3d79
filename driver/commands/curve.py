"""hertz curve: an indentation curve, P against h with the contact stiffness, hardness and
reduced modulus, from one command (--d or --P START:STOP:N, and any other option of hertz run).

The N cases run as a sweep of a study named `curve_cases` in --out DIR (its table
curve_cases.csv, every column, and its cases' folders under runs/), resumably: the same
command again runs only the missing points. curve.csv holds the curve sorted by h:
  h   depth (d_fe: the depth given, or found under -P)
  P   force (F_fe)
  S   contact stiffness dF/dd (S_fe)
  a   contact radius (a_fe)
  A   projected contact area, pi a^2 (pi a b in 3D, where b_fe is measured)
  H   hardness (mean pressure), P/A
  Er  reduced modulus, S sqrt(pi) / (2 sqrt(A)) (Sneddon's relation, as Oliver and Pharr use it)
For an elastic body Er is E* = E/(1 - nu^2) at every depth; curve.png draws P, H and Er against h.
With --Y each point is its own load path to its depth (the loading curve: the material
remembers only its own path), S its unloading stiffness at that depth.
"""
from __future__ import annotations

import argparse
import math
import re
import sys
from pathlib import Path

from driver import freefem, layout
from driver.commands.common import Once, add_solver_options, add_talk, add_timeout, positive, shown, solver_values
from driver.errors import HertzError, OptionError

HELP = "an indentation curve: --d or --P START:STOP:N; writes curve.csv (h, P, S, a, A, H, Er) and curve.png"
INTERRUPTED_LINE = "interrupted: finished points are kept; run the same command to resume"
STUDY = "curve_cases"  # (the built-in study `indentation` is another)
CSV, PNG = "curve.csv", "curve.png"
COLUMNS = ["h", "P", "S", "a", "A", "H", "Er"]
MAX_POINTS = 1000
_SPAN = re.compile(r"^([^:]+):([^:]+):([^:]+)$")


def span(text: str) -> tuple[float, float, int]:
    """START:STOP:N, N >= 2 points from START to STOP, both included."""
    match = _SPAN.match(text)
    try:
        start, stop, count = float(match.group(1)), float(match.group(2)), int(match.group(3))  # type: ignore[union-attr]
    except (AttributeError, ValueError):
        raise argparse.ArgumentTypeError(f"must be START:STOP:N (two numbers and a count), got {text!r}") from None
    if not (math.isfinite(start) and math.isfinite(stop)) or not 2 <= count <= MAX_POINTS:
        raise argparse.ArgumentTypeError(f"must be START:STOP:N with finite ends and N in [2, {MAX_POINTS}], "
                                         f"got {text!r}")
    return start, stop, count


def points(start: float, stop: float, count: int) -> list[float]:
    # 12 digits: the values (and so the case ids) read as typed, 0.0133333333333 not ...334
    return [float(f"{start + (stop - start) * k / (count - 1):.12g}") for k in range(count)]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    control = parser.add_mutually_exclusive_group(required=True)
    # (a group's add_argument is argparse's own: Once is named here, so a second --d is refused)
    control.add_argument("--d", type=span, metavar="START:STOP:N", help="N depths from START to STOP", action=Once)
    control.add_argument("--P", type=span, metavar="START:STOP:N", help="N loads from START to STOP", action=Once)
    parser.add_argument("--out", type=layout.user_path, required=True, metavar="DIR",
                        help=f"folder of {CSV}, {PNG} and the cases (new, or an earlier curve's)")
    parser.add_argument("--jobs", type=positive(int, 4096), default=None,
                        help="parallel FreeFEM processes (default: the cores)")
    add_timeout(parser, "seconds per case")
    add_talk(parser, verbose=False)  # the cases run in parallel: their outputs would interleave
    add_solver_options(parser, taken=tuple(name for name, o in freefem.options().items() if o.kind == "path")
                       + ("d", "P"))


def cases(args: argparse.Namespace) -> list[dict[str, object]]:
    """The options of each point, checked against the table, the ends also by hertz.edp itself."""
    control = "d" if args.d is not None else "P"
    base = solver_values(args)
    if base.get("model") == "plane":
        raise OptionError("--model plane has no contact area (a cylinder's load is per length); "
                          "hertz curve is for axi and 3d")
    chosen: list[dict[str, object]] = [base | {control: value} for value in points(*getattr(args, control))]
    checked = [freefem.parse_options(values, "--") for values in chosen]
    for values in (checked[0], checked[-1]):  # the options' ranges are intervals: the ends decide
        args_of = [arg for name, value in values.items() for arg in (f"-{name}", str(value))]
        refused = freefem.refusal(args_of)
        if refused:
            raise OptionError(refused)
    return chosen


def curve(rows):
    """curve.csv's table from the study rows of answered cases, sorted by h."""
    import numpy as np
    import pandas as pd
    b = rows["b_fe"] if "b_fe" in rows else pd.Series(np.nan, index=rows.index)
    area = np.pi * rows["a_fe"] * b.where(b.notna(), rows["a_fe"])
    table = pd.DataFrame({"h": rows["d_fe"], "P": rows["F_fe"], "S": rows["S_fe"], "a": rows["a_fe"], "A": area})
    table["H"] = table["P"] / table["A"]
    table["Er"] = table["S"] * np.sqrt(np.pi) / (2 * np.sqrt(table["A"]))
    return table.astype(float).sort_values("h", kind="stable").reset_index(drop=True)


def draw(table, rows, png: Path) -> Path:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from driver.charts.common import save
    fig, axes = plt.subplots(1, 3, figsize=(12, 3.8))
    for ax, column, label in zip(axes, ("P", "H", "Er"), ("force P", "hardness H = P/A", "reduced modulus Er")):
        ax.plot(table["h"], table[column], "o-", color="#1565c0", label="FE")
        ax.set_xlabel("depth h")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    homogeneous = "t" not in rows or rows["t"].isna().all()
    if homogeneous and rows["E"].nunique() == 1 and rows["nu"].nunique() == 1:
        star = float(rows["E"].iloc[0]) / (1 - float(rows["nu"].iloc[0]) ** 2)
        axes[2].axhline(star, color="#c62828", ls="--", label=f"E* = E/(1-nu^2) = {star:.4g}")
        axes[2].set_ylim(star * 0.98, star * 1.02)
    axes[2].legend(fontsize=8)
    fig.suptitle("indentation curve (lengths in the unit of R, forces in that of E times a length squared)")
    return save(fig, png)


def handle(args: argparse.Namespace) -> int:
    from driver.processes import install_signal_handlers
    install_signal_handlers()  # SIGTERM and SIGHUP end it as Ctrl-C does
    from driver import api, schema, studytable
    chosen = cases(args)
    say = (lambda line: None) if args.quiet else (lambda line: print(line, file=sys.stderr, flush=True))
    rows = api.sweep(STUDY, cases=chosen, results=args.out, jobs=args.jobs, timeout=args.timeout)
    answered = rows[[schema.answered(row) for row in rows.to_dict("records")]]
    for row in rows.to_dict("records"):
        if row["status"] != "converged":
            why = next((str(row[c]) for c in ("error", "warnings") if isinstance(row.get(c), str) and row[c]), "")
            kind = "hertz: warning" if row["status"] == "inaccurate" else "hertz: error"
            say(f"{kind}: {row['case_id']}: {row['status']}" + (f" ({why})" if why else ""))
    if not len(answered):
        raise HertzError(f"no case of the curve gave an answer (see {shown(layout.study_csv(args.out, STUDY))})")
    table = curve(answered)
    studytable.write_atomically(args.out / CSV, table.to_csv(index=False))
    draw(table, answered, args.out / PNG)
    print(table.to_string(index=False, float_format=lambda v: f"{v:.6g}"))
    say(f"files: {shown(args.out / CSV)}, {shown(args.out / PNG)}")
    if len(answered) < len(rows):
        return 1
    return 5 if (rows["status"] == "inaccurate").any() else 0
