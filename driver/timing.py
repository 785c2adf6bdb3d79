"""Benchmark: medians of interleaved runs, one at a time, and the ratios the targets name.

Times are wall-clock seconds of whole processes (what a user waits for); the
solver's CPU breakdown comes from summary.csv. Configurations run in turn
(A B C ... A B C ...), so a slow spell of the machine touches all of them.
The table goes to an untracked file (results/local/bench.csv by default).
`hertz run` is timed against the bare FreeFEM command it wraps, in turn.
The Dask path is measured against the local pool, both with 2 workers on this
machine: one case at a time (what the scheduler adds to a case: submission,
transfer of the row and files) and in batches that keep both workers busy
(what a sweep pays, where the next case is already queued on its worker).
"""
from __future__ import annotations

import json
import math
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pandas as pd

from driver import freefem, layout
from driver.cases import Case
from driver.errors import SweepError
from driver.executors import Executor, LocalPool, make_executor
from driver.run import run_case
from driver.schema import ERROR_COLUMNS, max_error, study_columns

DEFAULT = "default (newton P2, n=16)"
ACCURACY_FINEST = "-accuracy 1e-4"
ELLIPSOID = "3d ellipsoid Ry/Rx=4 (P2, n=8)"
LOAD_CONTROL = "load control (-P 0.03, near the seed's force)"
FRICTION = "friction, sphere (-mu 0.3, 16 steps)"
FRICTION_TIMES = 3  # the target: a frictional normal indentation at most 3 times the frictionless run
TWO_BODIES = "two identical spheres (-E1 10)"
TWO_BODIES_TIMES = 2  # the target: a two-body run at default options at most 2 times the rigid one
PLASTIC_CYCLE = "plastic cycle, sphere (-Y 0.3 -unload 1, 10 + 10 steps)"
ELASTIC_CYCLE = "elastic cycle, sphere (-unload 1, lagrange, 10 + 10 steps)"
# the targets: a 20-step load-unload cycle within 3 s, and 2 times the elastic one
PLASTIC_WALL, PLASTIC_TIMES = 3.0, 2
ADHESION_CURVE = "adhesive curve to separation, sphere (-w 0.05 -sigma0 5 -P 0.05 -pulloff 1)"
ADHESION_WALL = 4.0  # the target: an approach-and-retract curve at default options within 4 s
CONFIGS = {
    DEFAULT: Case(),
    "seed command (-kpen 1e5)": Case.of(kpen=1e5),
    "lagrange (P2, n=16)": Case.of(method="lagrange"),
    "uzawa (P2, n=16)": Case.of(method="uzawa"),
    "newton P2, n=32": Case.of(n=32),
    "lagrange P2, n=32": Case.of(method="lagrange", n=32),
    "-accuracy 0.001": Case.of(accuracy=0.001),
    "-accuracy 0.01": Case.of(accuracy=0.01),
    ACCURACY_FINEST: Case.of(accuracy=1e-4),
    "SI steel ball": Case.of(E=210e9, R=0.01, d=1e-5),
    "plane (cylinder)": Case.of(model="plane"),
    # a round load near the seed's force: its cost against the depth-controlled default
    LOAD_CONTROL: Case.of(P=0.03),
    "exact sphere (-shape sphere)": Case.of(shape="sphere"),
    "cone 70.3": Case.of(shape="cone"),
    "flat punch": Case.of(shape="punch"),
    "coated: t = a, E2 = 10 E": Case.of(t=0.1, E2=100.0),
    "coated: t = a/100 on a rigid base (lagrange)": Case.of(t=0.001, E2=math.inf, method="lagrange"),
    "3d sphere (P2, n=8)": Case.of(model="3d"),
    ELLIPSOID: Case.of(Rx=0.5, Ry=2.0),
    FRICTION: Case.of(mu=0.3),
    TWO_BODIES: Case.of(E1=10.0),
    "two dissimilar spheres (-E1 30 -nu1 0.2 -R2 1, -P 0.01)": Case.of(E1=30.0, nu1=0.2, R2=1.0, P=0.01),
    PLASTIC_CYCLE: Case.of(Y=0.3, unload=1),
    ELASTIC_CYCLE: Case.of(unload=1, method="lagrange", steps=10),
    "adhesive sphere at the depth (-w 0.05 -sigma0 5)": Case.of(w=0.05, sigma0=5.0),
    ADHESION_CURVE: Case.of(w=0.05, sigma0=5.0, P=0.05, pulloff=1),
    "full stick, sphere (-mu inf, 16 steps)": Case.of(mu=math.inf),
    "friction, cylinder (-mu 0.3, -P 0.01)": Case.of(model="plane", Rx=0.5, Ry=math.inf, P=0.01, mu=0.3),
    "tangential, cylinder (-Q mu P/2, 16 + 16 steps)": Case.of(model="plane", Rx=0.5, Ry=math.inf, P=0.01, mu=0.3,
                                                                 Q=0.0015),
    "unloaded, cylinder (-path 1,0.5, -mu 0.2)": Case.of(model="plane", Rx=0.5, Ry=math.inf, P=0.01, mu=0.2,
                                                          path="1,0.5"),
}
FENICS = layout.PACKAGE_DIR.parent / "bench" / "fenics_peer.py"  # in a checkout only
TAMAAS = layout.PACKAGE_DIR.parent / "bench" / "tamaas_peer.py"
TAMAAS_PYTHON = layout.PACKAGE_DIR.parent / ".venv-peers" / "bin" / "python"  # driver/setup.sh --peers
TAMAAS_GRIDS = (64, 96, 128)  # dcfft on 4 a: 16, 24 and 32 cells per contact radius
DEBIAN_PYTHON = "/usr/bin/python3"  # python3-dolfin is a Debian package


def direct_run(case: Case, outdir: Path) -> tuple[float, dict]:
    cmd = freefem.command(case.args() + ["-out", str(outdir)])
    start = time.perf_counter()
    subprocess.run(cmd, capture_output=True, env=freefem.freefem_env(), check=False)
    wall = time.perf_counter() - start
    return wall, pd.read_csv(outdir / "summary.csv").iloc[0].to_dict()


def peer_run(cmd: list[str]) -> tuple[float, dict] | None:
    """A peer script's wall time and the JSON line it prints last, or None if it failed."""
    start = time.perf_counter()
    # the same BLAS kernels as the solver's runs (FEniCS's PETSc links Debian's OpenBLAS too)
    proc = subprocess.run(cmd, capture_output=True, text=True, check=False, env=freefem.blas_env())
    wall = time.perf_counter() - start
    if proc.returncode != 0:
        return None
    return wall, json.loads(proc.stdout.strip().splitlines()[-1])


def fenics_run() -> tuple[float, dict] | None:
    """The FEniCS peer (bench/fenics_peer.py), if dolfin is installed."""
    if not FENICS.exists() or not shutil.which(DEBIAN_PYTHON):
        return None
    return peer_run([DEBIAN_PYTHON, str(FENICS)])


def tamaas_run(n: int) -> tuple[float, dict] | None:
    """The Tamaas peer (bench/tamaas_peer.py, FFT boundary elements on an isolated
    half-space: dcfft), if driver/setup.sh --peers installed it."""
    if not TAMAAS.exists() or not TAMAAS_PYTHON.exists():
        return None
    return peer_run([str(TAMAAS_PYTHON), str(TAMAAS), "--operator", "dcfft", "--N", str(n)])


DASK_TARGET = 0.05  # at most 5% of a default case's time per case

# `hertz run` against the FreeFEM command it wraps: at most CLI_RATIO times it plus CLI_EXTRA
# seconds (a Python start, the driver's imports, reading the answers it keeps in the user's cache)
CLI_RATIO, CLI_EXTRA = 1.3, 0.3
HERTZ_RUN = "hertz run, default case"
BARE_RUN = "FreeFem++ hertz.edp, default case (beside hertz run)"


def cli_against_bare(root: Path, repeat: int = 5) -> dict[str, list[float]]:
    """Wall times of `hertz run` and of the bare FreeFEM command it wraps, default case, in turn.
    One `hertz run` first: the first run of new solver code asks hertz.edp for its tables."""
    # this driver whatever is installed: the console script `hertz` is the same one Python start
    command = [sys.executable, "-m", "driver"]
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, [str(layout.PACKAGE_DIR.parent),
                                                                     os.environ.get("PYTHONPATH")])))
    times: dict[str, list[float]] = {HERTZ_RUN: [], BARE_RUN: []}
    root.mkdir(parents=True, exist_ok=True)

    def hertz_run(out: Path) -> float:
        start = time.perf_counter()
        proc = subprocess.run([*command, "run", "--out", str(out)], cwd=root, env=env, capture_output=True,
                              check=False)
        wall = time.perf_counter() - start
        if proc.returncode != 0:
            raise SweepError(f"hertz run failed in the benchmark (exit {proc.returncode}): "
                             + " ".join(proc.stderr.decode(errors="replace").split())[:300])
        return wall

    hertz_run(root / "warm")
    for k in range(repeat):
        bare = root / f"bare{k}"
        bare.mkdir()
        times[BARE_RUN].append(direct_run(Case(), bare)[0])
        times[HERTZ_RUN].append(hertz_run(root / f"hertz{k}"))
    return times


def _through(executor: Executor, workdir: Path, count: int, summary: list[str], columns: list[str]) -> float:
    """Seconds per case from submitting `count` default cases until their rows and files are on this side."""
    start = time.perf_counter()
    cases = {executor.submit(Case(), workdir / str(k), 600, "bench", summary, 1): workdir / str(k)
             for k in range(count)}
    for future in executor.as_completed(list(cases)):
        executor.collect(future, Case(), cases[future], "bench", columns)
    return (time.perf_counter() - start) / count


# cases per worker in a benched sweep: a real sweep runs hundreds, so a batch of
# 4 per worker let the fixed cost of a batch (its first submissions and its
# tail, one worker idle) weigh as much as the per-case cost being measured
SWEEP_CASES = 16


def dask_overhead(root: Path, repeat: int = 5, workers: int = 2) -> dict[str, list[float]] | None:
    """Seconds per default case through the local pool and through a LocalCluster of
    the same size, interleaved: one case at a time (the latency of a case) and in
    batches that keep every worker busy (a sweep). None without Dask."""
    summary = freefem.summary_columns()
    columns = study_columns(summary)
    try:
        dask = make_executor(workers, f"local:{workers}", say=lambda message: None)
    except SweepError:
        return None
    local = LocalPool(workers)
    times: dict[str, list[float]] = {f"{name}, {kind}": [] for kind in ("one case", "sweep")
                                     for name in ("local pool", "dask")}
    try:
        _through(dask, root / "warm", workers, summary, columns)  # a worker's first task imports the driver
        for k in range(repeat):
            for name, executor in (("local pool", local), ("dask", dask)):
                times[f"{name}, one case"].append(_through(executor, root / name / f"one{k}", 1, summary, columns))
                times[f"{name}, sweep"].append(_through(executor, root / name / f"sweep{k}", SWEEP_CASES * workers,
                                                        summary, columns))
    finally:
        dask.close()
        local.close()
    return times


# the speed targets (target_lines)
DEFAULT_WALL, DEFAULT_ERROR = 0.2, 1e-3
NEWTON_ITERATIONS = 8
FINEST_WALL, FINEST_ERROR = 2.0, 1e-4
ELLIPSOID_WALL, ELLIPSOID_ERROR = 10.0, 5e-3


def target_lines(table: pd.DataFrame, starts: pd.DataFrame) -> list[str]:
    """Each speed target of the benchmark against what this run measured, one line each:
    the figure, the target and 'met' or 'missed' (a configuration that did not run: no line)."""
    by = table.assign(max_abs_err=max_error(table)).set_index("configuration")
    lines = []

    def line(name: str, ok: bool, figure: str, target: str) -> None:
        lines.append(f"{'met   ' if ok else 'missed'} {name}: {figure} (target {target})")

    if DEFAULT in by.index:
        default = by.loc[DEFAULT]
        line("default run", default.wall_median_s <= DEFAULT_WALL and default.max_abs_err <= DEFAULT_ERROR,
             f"{default.wall_median_s:.3f} s, max error {default.max_abs_err:.3%}",
             f"at most {DEFAULT_WALL:g} s and {DEFAULT_ERROR:.1%}")
        peers = by[[c.startswith("Tamaas") for c in by.index]]
        reach = peers[peers["err_p0"].abs() <= abs(default.err_p0)]
        figure = f"default p0 error {abs(default.err_p0):.4%} in {default.wall_median_s:.3f} s"
        if len(reach):
            fastest = reach["wall_median_s"].idxmin()
            ratio = default.wall_median_s / reach.loc[fastest, "wall_median_s"]
            line("against Tamaas at equal p0 error", ratio < 1,
                 f"{figure}; the fastest Tamaas grid reaching it, {fastest}, "
                 f"{reach.loc[fastest, 'wall_median_s']:.3f} s (ratio {ratio:.2f})", "faster")
        elif len(peers):
            finest = peers["err_p0"].abs().idxmin()
            line("against Tamaas at equal p0 error", True,
                 f"{figure}; no benched Tamaas grid reaches it (the closest, {finest}: p0 error "
                 f"{abs(peers.loc[finest, 'err_p0']):.4%} in {peers.loc[finest, 'wall_median_s']:.3f} s)", "faster")
    if len(starts):
        coarse = starts[starts["start"] == "coarse"]
        worst = coarse.groupby("order")["all_levels"].max()
        line(f"Newton over all levels, gamma {coarse['gamma'].min():g} to {coarse['gamma'].max():g}",
             bool((worst <= NEWTON_ITERATIONS).all()),
             ", ".join(f"P{order} at most {count:.0f}" for order, count in worst.items()),
             f"at most {NEWTON_ITERATIONS}")
    if ACCURACY_FINEST in by.index:
        finest_run = by.loc[ACCURACY_FINEST]
        line("-accuracy 1e-4", finest_run.wall_median_s <= FINEST_WALL and finest_run.max_abs_err <= FINEST_ERROR,
             f"{finest_run.wall_median_s:.2f} s, max error {finest_run.max_abs_err:.1e}",
             f"at most {FINEST_WALL:g} s and {FINEST_ERROR:g}")
    if ELLIPSOID in by.index:
        ellipsoid = by.loc[ELLIPSOID]
        line("3D ellipsoid Ry/Rx = 4",
             ellipsoid.wall_median_s <= ELLIPSOID_WALL and ellipsoid.max_abs_err <= ELLIPSOID_ERROR,
             f"{ellipsoid.wall_median_s:.1f} s, max error {ellipsoid.max_abs_err:.2%} (p0, F, a, b)",
             f"at most {ELLIPSOID_WALL:g} s and {ELLIPSOID_ERROR:.1%}")
    if FRICTION in by.index and DEFAULT in by.index:
        rough, smooth = by.loc[FRICTION, "wall_median_s"], by.loc[DEFAULT, "wall_median_s"]
        line("frictional normal indentation against the frictionless default", rough <= FRICTION_TIMES * smooth,
             f"{rough:.2f} s against {smooth:.3f} s (ratio {rough / smooth:.1f})",
             f"at most {FRICTION_TIMES} times")
    if TWO_BODIES in by.index and DEFAULT in by.index:
        two, one = by.loc[TWO_BODIES, "wall_median_s"], by.loc[DEFAULT, "wall_median_s"]
        line("two elastic bodies against the rigid indenter", two <= TWO_BODIES_TIMES * one,
             f"{two:.3f} s against {one:.3f} s (ratio {two / one:.2f})", f"at most {TWO_BODIES_TIMES} times")
    if PLASTIC_CYCLE in by.index and ELASTIC_CYCLE in by.index:
        plastic, elastic = by.loc[PLASTIC_CYCLE, "wall_median_s"], by.loc[ELASTIC_CYCLE, "wall_median_s"]
        line("a plastic load-unload cycle, and against the same path elastic",
             plastic <= PLASTIC_WALL and plastic <= PLASTIC_TIMES * elastic,
             f"{plastic:.2f} s against {elastic:.2f} s (ratio {plastic / elastic:.2f})",
             f"at most {PLASTIC_WALL:g} s and {PLASTIC_TIMES} times")
    if ADHESION_CURVE in by.index:
        curve = by.loc[ADHESION_CURVE, "wall_median_s"]
        line("an adhesive force curve to separation (its pull-off and zero-load levels)", curve <= ADHESION_WALL,
             f"{curve:.2f} s", f"at most {ADHESION_WALL:g} s")
    if HERTZ_RUN in by.index and BARE_RUN in by.index:
        hertz, bare = by.loc[HERTZ_RUN, "wall_median_s"], by.loc[BARE_RUN, "wall_median_s"]
        line("hertz run against the bare FreeFEM command", hertz <= CLI_RATIO * bare + CLI_EXTRA,
             f"{hertz:.3f} s against {bare:.3f} s (ratio {hertz / bare:.2f})",
             f"at most {CLI_RATIO:g} x bare + {CLI_EXTRA:g} s = {CLI_RATIO * bare + CLI_EXTRA:.3f} s")
    pool, dask = (f"default per case, 2 workers, {name}, sweep" for name in ("local pool", "dask"))
    if pool in by.index and dask in by.index:
        overhead = by.loc[dask, "wall_median_s"] / by.loc[pool, "wall_median_s"] - 1
        line("Dask's overhead per case in a sweep", overhead <= DASK_TARGET, f"{overhead:+.1%}",
             f"at most {DASK_TARGET:.0%}")
    return lines


def bench(out: Path, repeat: int = 5) -> int:
    walls: dict[str, list[float]] = {name: [] for name in CONFIGS}
    summaries: dict[str, dict] = {}
    fenics_walls, fenics_row = [], None
    tamaas_walls: dict[int, list[float]] = {}
    tamaas_rows: dict[int, dict] = {}
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        for _ in range(repeat):
            for name, case in CONFIGS.items():
                wall, summaries[name] = direct_run(case, root)
                walls[name].append(wall)
            peer = fenics_run()
            if peer is not None:
                fenics_walls.append(peer[0])
                fenics_row = peer[1]
            for n in TAMAAS_GRIDS:
                tamaas = tamaas_run(n)
                if tamaas is not None:
                    tamaas_walls.setdefault(n, []).append(tamaas[0])
                    tamaas_rows[n] = tamaas[1]
        # driver overhead: the default case through run_case and directly
        direct, through = [], []
        for _ in range(repeat):
            direct.append(direct_run(Case(), root)[0])
            start = time.perf_counter()
            run_case(Case(), root / "driver", timeout=600)
            through.append(time.perf_counter() - start)
        cli_times = cli_against_bare(root / "cli", repeat)
        dask_times = dask_overhead(root / "dask", repeat)
        # Newton from each start over the penalty (iterations, all levels)
        starts = []
        for gamma in [10.0**k for k in range(-2, 7)]:
            for order in (1, 2):
                for start_name in ("coarse", "zero", "hertz"):
                    _, s = direct_run(Case.of(gamma=gamma, order=order, start=start_name), root)
                    starts.append({"gamma": gamma, "order": order, "start": start_name, "status": s["status"],
                                   "iterations": s["iterations"],
                                   "all_levels": s["iterations"] + s["coarse_iterations"],
                                   "factorizations": s["factorizations"], "p0_fe": s["p0_fe"]})

        # lagrange over its augmentation, in SI units (a steel ball), P1 and P2
        augmentation = []
        for gamma in [10.0**k for k in range(-3, 4)]:
            for order in (1, 2):
                _, s = direct_run(Case.of(method="lagrange", E=210e9, R=0.01, d=1e-5, gamma=gamma, order=order),
                                  root)
                augmentation.append({"gamma": gamma, "order": order, "status": s["status"],
                                     "iterations": s["iterations"], "nodal_penetration_over_d":
                                     s["nodal_penetration_over_d"],
                                     **{k: s.get(k) for k in ERROR_COLUMNS}})

    rows = []
    for name, s in summaries.items():
        rows.append({"configuration": name, "wall_median_s": statistics.median(walls[name]),
                     "wall_min_s": min(walls[name]), "status": s["status"], "n": s["n"], "ndof": s["ndof"],
                     "iterations": s["iterations"], "all_levels": s["iterations"] + s["coarse_iterations"],
                     "factorizations": s["factorizations"], "t_solve_cpu": s["t_solve"],
                     "solve_over_one_linear_solve": s["t_solve"] / s["t_linear_one"] if s["t_linear_one"] else None,
                     **{k: s[k] for k in ERROR_COLUMNS},
                     "est_max_err": s["accuracy_predicted"],
                     "nodal_penetration_over_d": s["nodal_penetration_over_d"], "memory_mb": s["memory_mb"]})
    if fenics_row is not None:
        rows.append({"configuration": f"FEniCS peer (P2, n={fenics_row['n']}, L={fenics_row['L']}, "
                                      f"kpen={fenics_row['kpen']:g})",
                     "wall_median_s": statistics.median(fenics_walls), "wall_min_s": min(fenics_walls),
                     "status": "converged", "n": fenics_row["n"], "ndof": fenics_row["ndof"],
                     "iterations": fenics_row["newton_iterations"],
                     **{k: fenics_row.get(k) for k in ERROR_COLUMNS}})
    for n, peer_row in tamaas_rows.items():
        rows.append({"configuration": f"Tamaas peer (dcfft, N={n}, {peer_row['cells_per_a']:g} cells per a)",
                     "wall_median_s": statistics.median(tamaas_walls[n]), "wall_min_s": min(tamaas_walls[n]),
                     "status": "converged" if peer_row["converged"] else "not converged",
                     "iterations": peer_row["iterations"],
                     **{k: peer_row.get(k) for k in ERROR_COLUMNS}})
    for name, values in cli_times.items():
        rows.append({"configuration": name, "wall_median_s": statistics.median(values), "wall_min_s": min(values)})
    if dask_times is not None:
        for name, values in dask_times.items():
            rows.append({"configuration": f"default per case, 2 workers, {name}",
                         "wall_median_s": statistics.median(values), "wall_min_s": min(values)})
    table = pd.DataFrame(rows)
    table["max_abs_err"] = max_error(table)
    out.parent.mkdir(parents=True, exist_ok=True)
    table.to_csv(out, index=False)
    starts_table = pd.DataFrame(starts)
    starts_table.to_csv(out.with_name("bench_starts.csv"), index=False)
    by = table.set_index("configuration")["wall_median_s"]
    pd.set_option("display.width", 220)
    print(table.drop(columns=["wall_min_s"]).to_string(index=False, float_format=lambda v: f"{v:.4g}"))
    print()
    ratio16 = by["lagrange (P2, n=16)"] / by[DEFAULT]
    ratio32 = by["lagrange P2, n=32"] / by["newton P2, n=32"]
    print(f"lagrange / newton wall time: n=16 {ratio16:.2f}, n=32 {ratio32:.2f}")
    default = by[DEFAULT]
    for name in (LOAD_CONTROL, "exact sphere (-shape sphere)", "cone 70.3",
                 "flat punch", "coated: t = a, E2 = 10 E"):
        print(f"{name} / default wall time: {by[name] / default:.2f}")
    for peer in [c for c in by.index if c.startswith("Tamaas")]:
        print(f"{peer} / default: {by[peer] / default:.2f}")
    if fenics_row is not None:
        peer = [c for c in by.index if c.startswith("FEniCS")][0]
        print(f"FEniCS peer / -accuracy 0.001: {by[peer] / by['-accuracy 0.001']:.1f}x")
    overhead = (statistics.median(through) - statistics.median(direct)) / statistics.median(direct)
    print(f"driver overhead per case (default case, median of {repeat}): {overhead:+.1%} "
          f"(direct {statistics.median(direct):.3f} s, through the driver {statistics.median(through):.3f} s)")
    if dask_times is None:
        print("Dask overhead: not measured (pip install -e '.[dask]')")
    else:
        for kind in ("sweep", "one case"):
            pool = statistics.median(dask_times[f"local pool, {kind}"])
            dask = statistics.median(dask_times[f"dask, {kind}"])
            print(f"Dask overhead per case ({kind}, default case, 2 workers, median of {repeat}): "
                  f"{(dask - pool) / pool:+.1%} (local pool {pool:.3f} s, Dask {dask:.3f} s per case"
                  + (f"; target at most {DASK_TARGET:.0%})" if kind == "sweep" else ")"))
    pivot = starts_table.pivot_table(index=["order", "start"], columns="gamma", values="all_levels", aggfunc="first")
    print("\nNewton iterations over all levels, by start and gamma = kpen h/E*:")
    print(pivot.to_string())
    coarse = starts_table[starts_table["start"] == "coarse"]
    hertz = starts_table[starts_table["start"] == "hertz"].set_index(["gamma", "order"])
    worst = max(abs(r.p0_fe / hertz.loc[(r.gamma, r.order), "p0_fe"] - 1) for r in coarse.itertuples())
    print(f"coarse start against the Hertz start: p0 differs by at most {worst:.1e}; "
          f"fine-level factorizations at most {coarse['factorizations'].max():.0f}")
    aug = pd.DataFrame(augmentation)
    aug = aug.assign(max_abs_err=max_error(aug)).drop(columns=list(ERROR_COLUMNS))
    aug.to_csv(out.with_name("bench_lagrange.csv"), index=False)
    print("\nlagrange over its augmentation c = gamma E*/h, SI steel ball:")
    print(aug.to_string(index=False, float_format=lambda v: f"{v:.3g}"))
    print("\ntargets, measured in this run:")
    print("\n".join(target_lines(table, starts_table)))
    print(f"written: {out}, {out.with_name('bench_starts.csv')} and {out.with_name('bench_lagrange.csv')}")
    return 0


if __name__ == "__main__":
    sys.exit(bench(layout.user_path(f"{layout.DEFAULT_RESULTS}/{layout.LOCAL}/bench.csv")))
