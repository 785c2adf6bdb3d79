"""A small draw of the audit (tests/audit.py): random scenes of every 2D feature keep the promise
against the tests' own references, and the audit's verdicts are the promise's."""
import math
import random

import audit
import pytest


def test_the_verdicts_follow_the_promise():
    row = {"exit": 0, "true": 0.012, "estimate": 0.02, **{f"true_{q}": math.nan for q in audit.QUANTITIES},
           **{f"est_{q}": math.nan for q in audit.QUANTITIES}}
    assert audit.judge(row)["silent"]                      # above the bar
    row.update(true=0.004, estimate=0.0019)
    assert audit.judge(row)["silent"]                      # above twice its estimate
    row.update(true=0.0009, estimate=0.0001)
    assert not audit.judge(row)["silent"]                  # below the floor
    row.update(exit=5, true=0.002, estimate=0.02)
    assert audit.judge(row)["false_alarm"] and not audit.judge(row)["silent"]
    row.update(true_p0=0.004, est_p0=0.0015, true_a=0.001, est_a=0.002)
    assert audit.judge(row)["low_columns"] == "p0"


def test_every_drawn_scene_is_a_command_the_options_take():
    rng = random.Random(1)
    for _ in range(200):
        args = audit.draw(rng)
        assert ("-d" in args) != ("-P" in args), args
        assert float(audit.option(args, "-E")) > 0 and -1 < float(audit.option(args, "-nu")) < 0.5


@pytest.mark.slow
def test_a_small_random_draw_keeps_the_promise():
    rows = audit.audit(runs=16, runs_3d=0, seed=2026, jobs=1)
    silent = [(r["args"], r["true"], r["estimate"]) for r in rows if audit.judge(r)["silent"]]
    assert not silent
    assert sum(r["exit"] in (0, 5) for r in rows) >= 12  # the draw reaches answers, not only failures
