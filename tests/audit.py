#!/usr/bin/env python3
"""The promise, audited against the truth: random scenes of every feature, drawn from a
recorded seed, each solved by hertz.edp and compared with references written here and in
hertz_reference.py, apart from the solver.

  python3 tests/audit.py [--runs 500] [--runs-3d 10] [--seed 47] [--jobs 2] [--out results/local/audit.csv]

(`make audit`.) It counts, over the runs:
- silent wrong answers: exit 0 above the 1% bar, or above twice its own estimate while above 0.1%;
- false alarms: exit 5 with a true error below 0.3 of the bar;
- estimate columns that read low: an est_err_* below half of its quantity's true error.
Every row (the scene, the exit, each quantity's truth and estimate) goes to the CSV; the
command exits 1 when any run is a silent wrong answer. tests/test_audit.py runs a small draw.
"""
from __future__ import annotations

import argparse
import csv
import math
import random
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from promise import BAR, ESTIMATE_SHARE  # noqa: E402  (what exit 0 promises)

from driver import freefem  # noqa: E402
from driver.references.maugis import Maugis  # noqa: E402  (adhesion's, apart from the solver)

import hertz_reference as ref  # noqa: E402  (the tests' own references)

SILENT_FLOOR = 1e-3     # below this a run's error is not held against its estimate
FALSE_ALARM = 0.3 * BAR
QUANTITIES = ["p0", "F", "a", "b", "K", "pulloff", "a0"]  # F holds the depth d under -P, as est_err_F does


def draw_adhesive(rng: random.Random) -> list[str]:
    """An adhesive sphere (Maugis-Dugdale): lambda from 0.1 to 10, the adhesion's force
    pi w R from a tenth to three times Hertz's at the depth; by depth or load, and a third
    of them followed to separation (-pulloff 1, lambda at most 5, from a positive load)."""
    E, nu, R = 10 ** rng.uniform(0, 9), rng.uniform(-0.3, 0.45), 10 ** rng.uniform(-1, 1)
    d = R * 10 ** rng.uniform(-2.5, -1.3)
    Es = ref.estar(E, nu)
    w = 10 ** rng.uniform(-1, 0.5) * ref.sphere(E, nu, R, d).F / (math.pi * R)
    pulloff = rng.random() < 0.3
    lam = 10 ** rng.uniform(-1, math.log10(5 if pulloff else 10))
    sigma0 = lam / Maugis(Es, R, w, 1.0).lam   # (lambda grows as sigma0)
    args = ["-E", repr(E), "-nu", repr(nu), "-R", repr(R), "-w", repr(w), "-sigma0", repr(sigma0),
            "-n", str(rng.choice([12, 16, 24]))]
    maugis = Maugis(Es, R, w, sigma0)
    load = rng.random() < 0.4 or pulloff
    P = float(abs(maugis.at_depth(d)["P"]) + 0.5 * math.pi * w * R)
    return args + (["-pulloff", "1"] if pulloff else []) + (["-P", repr(P)] if load else ["-d", repr(d)])


def draw(rng: random.Random, three_d: bool = False) -> list[str]:
    """One random scene's command line: every shape, model, method, order and control,
    and adhesion (one in eight)."""
    if not three_d and rng.random() < 0.125:
        return draw_adhesive(rng)
    E = 10 ** rng.uniform(0, 9)
    nu = rng.choice([rng.uniform(-0.5, 0.45), rng.uniform(0, 0.45), 0.3])
    R = 10 ** rng.uniform(-1, 1)
    load = rng.random() < 0.3
    method = rng.choice(["newton", "lagrange", "uzawa"])
    args = ["-E", repr(E), "-nu", repr(nu), "-method", method]
    if three_d:
        ratio = 10 ** rng.uniform(0.1, 0.8)
        d = R * 10 ** rng.uniform(-2.5, -1.5)
        args += ["-model", "3d", "-Rx", repr(R), "-Ry", repr(R * ratio), "-n", str(rng.choice([6, 8]))]
        return args + (["-P", repr(ref.ellipsoid_from_depth(d, E, nu, R, R * ratio).P)] if load else ["-d", repr(d)])
    shape = rng.choice(["parabola", "cylinder", "sphere", "cone", "power", "power", "punch"])
    order = rng.choice([1, 2, 2])
    args += ["-order", str(order), "-n", str(rng.randint(6, 32))]
    if order == 1 and nu > 0.45:
        nu = 0.3
    if shape in ("parabola", "sphere"):
        d = R * 10 ** rng.uniform(-3, -1.3)
        args += ["-shape", shape, "-R", repr(R)]
        P = ref.sphere(E, nu, R, d).F if shape == "parabola" else ref.punch_from_depth("sphere", d, E, nu, R=R).F
    elif shape == "cylinder":
        args += ["-model", "plane", "-Rx", repr(R), "-Ry", "inf"]
        d, P = None, ref.estar(E, nu) * R * 10 ** rng.uniform(-4, -2)
        load = True  # a cylinder's depth depends on its domain: posed by its load
    elif shape == "cone":
        angle = rng.uniform(55, 80)
        d = 10 ** rng.uniform(-3, 0)
        args += ["-shape", "cone", "-angle", repr(angle)]
        P = ref.punch_from_depth("cone", d, E, nu, angle=angle).F
    elif shape == "power":
        k = rng.choice([rng.uniform(1.2, 2), rng.uniform(2, 10)])
        d = R * 10 ** rng.uniform(-3, -1.3)
        args += ["-shape", "power", "-R", repr(R), "-k", repr(k)]
        P = ref.punch_from_depth("power", d, E, nu, R=R, k=k).F
    else:
        a = 10 ** rng.uniform(-2, 1)
        d = a * 10 ** rng.uniform(-3, -1)
        args += ["-shape", "punch", "-a", repr(a)]
        P = 2 * ref.estar(E, nu) * a * d
    args[args.index("-nu") + 1] = repr(nu)
    return args + (["-P", repr(P)] if load else ["-d", repr(d)])


def option(args: list[str], name: str, default=None):
    return args[args.index(name) + 1] if name in args else default


def truth(args: list[str], s: dict) -> dict[str, float]:
    """Each quantity's true relative error (NaN where the scene has no such result)."""
    E, nu = float(option(args, "-E")), float(option(args, "-nu"))
    Es = ref.estar(E, nu)
    load = "-P" in args
    P = float(option(args, "-P", "nan"))
    d = float(option(args, "-d", "nan"))
    shape = option(args, "-shape", "parabola")
    got = {q: float(s.get(f"{q}_fe", "nan")) for q in ("p0", "F", "a", "b", "K", "d")}
    err = dict.fromkeys(QUANTITIES, math.nan)

    def rel(x, r):
        return abs(x / r - 1)
    if "-w" in args:
        R = float(option(args, "-R"))
        maugis = Maugis(Es, R, float(option(args, "-w")), float(option(args, "-sigma0")))
        state = maugis.at_load(P) if load else maugis.at_depth(d)
        err.update(a=rel(got["a"], state["a"]), F=rel(got["d"], state["d"]) if load else rel(got["F"], state["P"]))
        if "-pulloff" in args:
            least = maugis.pulloff("load" if load else "depth")
            if not least["at_end"]:
                err["pulloff"] = rel(float(s.get("pulloff_fe", "nan")), least["P"])
            if float(s.get("F_fe", "nan")) > 0:
                err["a0"] = rel(float(s.get("a0_fe", "nan")), maugis.zero_load()["a"])
        return err
    if option(args, "-model") == "3d":
        Rx, Ry = float(option(args, "-Rx")), float(option(args, "-Ry"))
        e = ref.ellipsoid_from_load(P, E, nu, min(Rx, Ry), max(Rx, Ry)) if load else \
            ref.ellipsoid_from_depth(d, E, nu, min(Rx, Ry), max(Rx, Ry))
        ax, by = (e.a_long, e.b_short) if Rx >= Ry else (e.b_short, e.a_long)
        err.update(p0=rel(got["p0"], e.p0), F=rel(got["d"], e.d) if load else rel(got["F"], e.P),
                   a=rel(got["a"], ax), b=rel(got["b"], by))
        return err
    if option(args, "-model") == "plane":
        R = float(option(args, "-Rx"))
        err.update(p0=rel(got["p0"], ref.cylinder_pressure(P, E, nu, R)),
                   a=rel(got["a"], ref.cylinder_half_width(P, E, nu, R)))
        return err
    if shape == "parabola":
        R = float(option(args, "-R"))
        h = ref.sphere_from_load(E, nu, R, P) if load else ref.sphere(E, nu, R, d)
        err.update(p0=rel(got["p0"], h.p0), a=rel(got["a"], h.a),
                   F=rel(got["d"], ref.sphere_depth(E, nu, R, P)) if load else rel(got["F"], h.F))
        return err
    if shape == "punch":
        a = float(option(args, "-a"))
        force = P if load else 2 * Es * a * d
        err.update(F=rel(got["d"], P / (2 * Es * a)) if load else rel(got["F"], force),
                   K=rel(got["K"], ref.flat_punch_edge_coefficient(force, a)))
        return err
    geometry = {"R": float(option(args, "-R", "0.5"))} if shape in ("sphere", "power") else {}
    if shape == "cone":
        geometry = {"angle": float(option(args, "-angle"))}
    k = float(option(args, "-k")) if shape == "power" else None
    if k is not None:
        geometry["k"] = k
    p = ref.punch_from_load(shape, P, E, nu, **geometry) if load else ref.punch_from_depth(shape, d, E, nu, **geometry)
    err.update(a=rel(got["a"], p.a), F=rel(got["d"], p.d) if load else rel(got["F"], p.F))
    if shape != "cone":
        err["p0"] = rel(got["p0"], ref.max_pressure(shape, p.a, Es, **geometry))
    return err


def run(args: list[str]) -> dict:
    """One scene: its exit, status and, per quantity, the true error and the estimate."""
    with tempfile.TemporaryDirectory() as out:
        proc = subprocess.run(freefem.command(["-out", out, *args]), capture_output=True, text=True,
                              env=freefem.freefem_env(), timeout=900)
        try:
            with open(Path(out) / "summary.csv") as f:
                s = next(csv.DictReader(f))
        except (OSError, StopIteration):
            s = {}
    # (the estimate the status rests on: an adhesive run's pull-off and zero-load radius too)
    estimates = [float(s.get(c, "nan")) for c in ("accuracy_predicted", "est_err_pulloff", "est_err_a0")]
    finite_estimates = [e for e in estimates if not math.isnan(e)]
    row = {"args": " ".join(args), "exit": proc.returncode, "status": s.get("status", ""),
           "warnings": s.get("warnings", ""), "estimate": max(finite_estimates) if finite_estimates else math.nan}
    errors = truth(args, s) if proc.returncode in (0, 5) and s else dict.fromkeys(QUANTITIES, math.nan)
    for q in QUANTITIES:
        row[f"true_{q}"] = errors[q]
        row[f"est_{q}"] = float(s.get(f"est_err_{q}", "nan"))
    finite = [e for e in errors.values() if not math.isnan(e)]
    row["true"] = max(finite) if finite else math.nan
    return row


def judge(row: dict) -> dict:
    """The verdicts of one row."""
    t, e = row["true"], row["estimate"]
    low = [q for q in QUANTITIES if not math.isnan(row[f"true_{q}"]) and row[f"true_{q}"] > 1e-12
           and (math.isnan(row[f"est_{q}"]) or row[f"est_{q}"] < ESTIMATE_SHARE * row[f"true_{q}"])]
    answered = row["exit"] in (0, 5) and not math.isnan(t)
    return {"silent": row["exit"] == 0 and not math.isnan(t) and (t > BAR or (t > SILENT_FLOOR and t > 2 * e)),
            "false_alarm": row["exit"] == 5 and not math.isnan(t) and t < FALSE_ALARM,
            "low_columns": ",".join(low) if answered else ""}


def audit(runs: int, runs_3d: int, seed: int, jobs: int) -> list[dict]:
    rng = random.Random(seed)
    scenes = [draw(rng) for _ in range(runs)] + [draw(rng, three_d=True) for _ in range(runs_3d)]
    with ThreadPoolExecutor(jobs) as pool:
        rows = list(pool.map(run, scenes))
    for row in rows:
        row.update(judge(row))
    return rows


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=500, help="2D scenes (default 500)")
    parser.add_argument("--runs-3d", type=int, default=10, help="3D scenes (default 10; about 10 s each)")
    parser.add_argument("--seed", type=int, default=47)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--out", default="results/local/audit.csv")
    a = parser.parse_args()
    rows = audit(a.runs, a.runs_3d, a.seed, a.jobs)
    out = Path(a.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    with open(out, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    n = len(rows)
    two_d = [r for r in rows if "-model 3d" not in r["args"]]
    three_d = [r for r in rows if "-model 3d" in r["args"]]
    for name, part in (("2D", two_d), ("3D", three_d)):
        if part:
            alarms = sum(r["false_alarm"] for r in part)
            print(f"{name}: {len(part)} runs, exit 0: {sum(r['exit'] == 0 for r in part)}, exit 5: "
                  f"{sum(r['exit'] == 5 for r in part)}, false alarms {alarms} ({100 * alarms / len(part):.1f}%)")
    silent = [r for r in rows if r["silent"]]
    low = [r for r in rows if r["low_columns"]]
    print(f"silent wrong answers: {len(silent)} of {n} (seed {a.seed})")
    print(f"runs with an estimate column below half its true error: {len(low)} of {n}")
    for r in silent[:10]:
        print(f"  silent: {r['args']}  true {r['true']:.4g}, estimate {r['estimate']:.4g}")
    print(f"rows: {out}")
    return 1 if silent else 0


if __name__ == "__main__":
    sys.exit(main())
