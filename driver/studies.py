"""Named studies and user grids. Each quick study is a subset of its full one,
so a full sweep after a quick one only runs the missing cases."""
from __future__ import annotations

import itertools
import math
import json
import tomllib
from dataclasses import fields
from pathlib import Path

from driver.cases import Case

DEFAULT = Case()
MESH_GAMMA = 100.0  # kpen = MESH_GAMMA E*/h in the scaled-penalty mesh series
DECADES = [10.0**k for k in range(1, 10)]


def grid(base: Case = DEFAULT, **axes) -> list[Case]:
    """All combinations of the given values, on top of base."""
    names = list(axes)
    return [base.with_(**dict(zip(names, combo)))
            for combo in itertools.product(*(axes[k] for k in names))]


def kpen_study(quick: bool) -> list[Case]:
    if quick:
        return (grid(method=["newton"], order=[1, 2], kpen=[1e1, 1e3, 1e5, 1e7, 1e9])
                + grid(method=["fixedpoint"], order=[2], kpen=[1e1, 1e3]))
    return grid(method=["newton", "fixedpoint"], order=[1, 2], kpen=DECADES)


def mesh_study(quick: bool) -> list[Case]:
    # P2 at n = 160 (~600k dofs) would cost minutes for a point on the floor
    ns = {1: [5, 10, 20, 40], 2: [5, 10, 20, 40]} if quick else \
        {1: [5, 10, 20, 40, 80, 160], 2: [5, 10, 20, 40, 80]}
    cases = []
    for order, values in ns.items():
        cases += grid(order=[order], n=values, kpen=[1e5])
        cases += [c.with_(kpen=float(f"{c.scaled_kpen(MESH_GAMMA):.6g}"))
                  for c in grid(order=[order], n=values)]
    return cases


def domain_study(quick: bool) -> list[Case]:
    Ls = [20.0, 100.0, 1000.0, 5000.0] if quick else \
        [10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0, 2000.0, 5000.0, 20000.0]
    return grid(kpen=[1e8], L=Ls)


def plane_study(quick: bool) -> list[Case]:
    base = DEFAULT.with_(model="plane")
    if quick:
        return grid(base, n=[16, 32], kpen=[1e5], d=[0.01, 0.04])
    return grid(base, n=[8, 16, 32], kpen=[1e5, 1e8], d=[0.01, 0.02, 0.04])


def stability_study(quick: bool) -> list[Case]:
    fp = DEFAULT.with_(method="fixedpoint")
    if quick:
        return (grid(fp, n=[8, 16], omega=[0.5, 1.0], kpen=[10.0, 30.0, 100.0, 300.0, 1000.0])
                + grid(cont=[0, 1], kpen=[1e3, 1e6, 1e9]))
    return (grid(fp, n=[8, 16, 32], omega=[0.1, 0.2, 0.5, 1.0, 1.5],
                 kpen=[3.0, 10.0, 30.0, 100.0, 300.0, 1000.0, 1e4])
            + grid(cont=[0, 1], order=[1, 2], kpen=DECADES)
            + grid(n=[64], cont=[0, 1], order=[1, 2], kpen=[1e5, 1e7, 1e9]))


def speed_study(quick: bool) -> list[Case]:
    if quick:
        return (grid(order=[1, 2], n=[4, 8, 16], kpen=[1e8]) + grid(method=["auglag"], n=[8, 16])
                + grid(method=["auglag"], n=[32], kpen=[1e5, 1e7]))
    return (grid(order=[1, 2], n=[4, 8, 16, 32, 64], kpen=[1e5, 1e8])
            + grid(order=[1], n=[128], kpen=[1e5, 1e8])
            + grid(method=["auglag"], n=[4, 8, 16, 32, 64])
            # a stiff inner penalty closes the surface between nodes too (see README)
            + grid(method=["auglag"], n=[8, 16, 32, 64], kpen=[1e7])
            + grid(n=[8, 16, 32, 64], kpen=[1e3, 1e4])
            + grid(method=["fixedpoint"], n=[8, 16], kpen=[30.0]))


STUDIES = {
    "kpen": kpen_study,
    "mesh": mesh_study,
    "domain": domain_study,
    "plane": plane_study,
    "stability": stability_study,
    "speed": speed_study,
}


class SpecError(ValueError):
    """A study spec file that cannot define cases."""


_FIELDS = {f.name: f for f in fields(Case)}
_TYPES = {"model": str, "method": str, "order": int, "n": int, "cont": int, "maxit": int}


def load_spec(path: Path) -> tuple[str, list[Case]]:
    """A grid from TOML or JSON: name = "...", [base] fixed values, [grid] lists of values."""
    try:
        text = path.read_text()
        data = json.loads(text) if path.suffix == ".json" else tomllib.loads(text)
    except (OSError, ValueError) as exc:
        raise SpecError(f"spec {path}: cannot read: {exc}") from None
    unknown = set(data) - {"name", "base", "grid"}
    if unknown:
        raise SpecError(f"spec {path}: unknown key(s) {sorted(unknown)}; allowed: name, base, grid")
    name = data.get("name")
    if not isinstance(name, str) or not name.replace("-", "").replace("_", "").isalnum():
        raise SpecError(f"spec {path}: 'name' must be a word of letters, digits, - or _")
    if name in STUDIES:
        raise SpecError(f"spec {path}: name '{name}' is a built-in study; choose another")
    base = {k: _value(path, k, v) for k, v in _table(path, data, "base").items()}
    axes = {}
    for key, values in _table(path, data, "grid").items():
        if not isinstance(values, list) or not values:
            raise SpecError(f"spec {path}: grid.{key} must be a non-empty list")
        axes[key] = [_value(path, key, v) for v in values]
    if not axes:
        raise SpecError(f"spec {path}: [grid] must list at least one parameter")
    return name, grid(DEFAULT.with_(**base), **axes)


def _table(path: Path, data: dict, key: str) -> dict:
    table = data.get(key, {})
    if not isinstance(table, dict):
        raise SpecError(f"spec {path}: [{key}] must be a table of parameter = value")
    return table


def _value(path: Path, key: str, value):
    if key not in _FIELDS:
        raise SpecError(f"spec {path}: unknown parameter '{key}'; known: {', '.join(_FIELDS)}")
    want = _TYPES.get(key, float)
    ok = isinstance(value, str) if want is str else \
        isinstance(value, (int, float)) and not isinstance(value, bool)
    if not ok:
        raise SpecError(f"spec {path}: {key} must be a {want.__name__}, got {value!r}")
    if want is int:
        if not math.isfinite(value) or not float(value).is_integer():
            raise SpecError(f"spec {path}: {key} must be an integer, got {value!r}")
        return int(value)
    if want is float:
        value = float(value)
        if value != value or value in (float("inf"), float("-inf")):
            raise SpecError(f"spec {path}: {key} must be finite, got {value!r}")
    return value
