"""Benchmark: medians of repeated runs, one at a time, and the ratios the targets name.

Times are wall-clock seconds of whole FreeFEM processes (what a user waits for);
the solver's own CPU breakdown comes from summary.csv.
"""
from __future__ import annotations

import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import pandas as pd

from driver.cases import Case
from driver.run import freefem_command, freefem_env, run_case

CONFIGS = {
    "default (P2, n=16, kpen=1e5)": Case(),
    "accurate (P2, n=20, kpen=100 E*/h)": Case(n=20).with_(kpen=float(f"{Case(n=20).scaled_kpen(100):.6g}")),
    "auglag (P2, n=16, kpen=1e5)": Case(method="auglag"),
    "penalty (P2, n=32, kpen=1e5)": Case(n=32),
    "auglag (P2, n=32, kpen=1e5)": Case(method="auglag", n=32),
    "penalty kpen=1e9 (P2, n=16)": Case(kpen=1e9),
    "fixed point (P2, n=16, kpen=30)": Case(method="fixedpoint", kpen=30.0),
}


def direct_run(case: Case, outdir: Path) -> tuple[float, dict]:
    cmd = freefem_command(case.args(), outdir)
    start = time.perf_counter()
    subprocess.run(cmd, capture_output=True, env=freefem_env(), check=False)
    wall = time.perf_counter() - start
    return wall, pd.read_csv(outdir / "summary.csv").iloc[0].to_dict()


def bench(results_dir: Path, repeat: int = 5) -> int:
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp)
        for name, case in CONFIGS.items():
            walls, summary = [], None
            for _ in range(repeat):
                wall, summary = direct_run(case, out)
                walls.append(wall)
            rows.append({
                "configuration": name, "wall_median_s": statistics.median(walls),
                "wall_min_s": min(walls), "iterations": summary["iterations"],
                "factorizations": summary["factorizations"], "resolves": summary["resolves"],
                "status": summary["status"],
                "ndof": summary["ndof"], "t_solve_cpu": summary["t_solve"],
                "t_linear_one_cpu": summary["t_linear_one"],
                "solve_over_one_linear_solve": summary["t_solve"] / summary["t_linear_one"],
                "max_abs_err": max(abs(summary[k]) for k in ("err_p0", "err_F", "err_a")),
                "penetration_over_d": summary["penetration_over_d"],
                "nodal_penetration_over_d": summary["nodal_penetration_over_d"],
            })
        # driver overhead: the same case through run_case and directly
        direct = [direct_run(Case(), out)[0] for _ in range(repeat)]
        through = []
        for _ in range(repeat):
            start = time.perf_counter()
            run_case(Case(), out / "driver", timeout=600)
            through.append(time.perf_counter() - start)
        newton = []
        for k in [10.0**e for e in range(1, 10)]:
            _, s = direct_run(Case(kpen=k), out)
            newton.append({"kpen": k, "iterations": s["iterations"], "status": s["status"]})

    table = pd.DataFrame(rows)
    by = table.set_index("configuration")
    auglag_ratio = {n: by.loc[f"auglag (P2, n={n}, kpen=1e5)", "wall_median_s"]
                    / by.loc[penalty, "wall_median_s"]
                    for n, penalty in [(16, "default (P2, n=16, kpen=1e5)"),
                                       (32, "penalty (P2, n=32, kpen=1e5)")]}
    overhead = (statistics.median(through) - statistics.median(direct)) / statistics.median(direct)
    results_dir.mkdir(parents=True, exist_ok=True)
    table.to_csv(results_dir / "bench.csv", index=False)
    pd.set_option("display.width", 200)
    print(table.drop(columns=["wall_min_s"]).to_string(index=False, float_format=lambda v: f"{v:.4g}"))
    print()
    print("auglag / plain penalty wall time (same mesh): "
          + ", ".join(f"n={n}: {r:.2f}" for n, r in auglag_ratio.items()))
    print(f"driver overhead per case (default case, median of {repeat}): {overhead:+.1%} "
          f"(direct {statistics.median(direct):.3f} s, through the driver {statistics.median(through):.3f} s)")
    print("Newton iterations at the default mesh, kpen 1e1..1e9: "
          + ", ".join(f"{r['iterations']:.0f}" for r in newton)
          + f" (all converged: {all(r['status'] == 'converged' for r in newton)})")
    print(f"written: {results_dir / 'bench.csv'}")
    return 0
