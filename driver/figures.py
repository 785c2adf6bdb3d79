"""Single runs behind the profile and stress charts (not part of any study)."""
from __future__ import annotations

from pathlib import Path

import pandas as pd

from driver.cases import Case
from driver.sweep import sweep

PROFILE_CASES = [Case(n=8, order=o, kpen=k) for o in (1, 2) for k in (1e3, 1e5, 1e8)]
SEED_FIGURE_CASES = [Case(kpen=k) for k in (1e1, 1e2, 1e3, 1e5)]
AXIS_CASE = Case(kpen=1e8)


def figure_runs(results_dir: Path) -> dict[str, Path]:
    """Run (or reuse) the figure cases; return their work directories by case id."""
    cases = PROFILE_CASES + SEED_FIGURE_CASES + [AXIS_CASE]
    sweep("figures", cases, results_dir, jobs=2, timeout=600, progress=False)
    workroot = results_dir / "runs" / "figures"
    missing = [c for c in cases if not (workroot / c.case_id / "profile.csv").exists()]
    if missing:  # CSV rows kept but work files deleted: rerun them
        sweep("figures", missing, results_dir, jobs=2, timeout=600, force=True, progress=False)
    return {c.case_id: workroot / c.case_id for c in cases}


def load(workdir: Path, name: str) -> pd.DataFrame:
    return pd.read_csv(workdir / f"{name}.csv")
