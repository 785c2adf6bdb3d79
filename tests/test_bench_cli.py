"""make bench's target for `hertz run`: at most 1.3 times the bare FreeFEM command plus 0.3 s,
judged on the medians one benchmark run measured (no timing here: the figures are given)."""
import pandas as pd
import pytest

from driver.timing import BARE_RUN, HERTZ_RUN, target_lines


def _verdict(hertz: float, bare: float) -> str:
    table = pd.DataFrame([{"configuration": HERTZ_RUN, "wall_median_s": hertz},
                          {"configuration": BARE_RUN, "wall_median_s": bare}])
    return next(line for line in target_lines(table, pd.DataFrame()) if "hertz run" in line)


@pytest.mark.parametrize("hertz,bare,verdict", [
    (0.55, 0.20, "met"), (0.57, 0.20, "missed"),   # 1.3 x 0.2 + 0.3 = 0.56
    (1.60, 1.00, "met"), (1.70, 1.00, "missed"),   # a long case: the ratio decides
])
def test_hertz_run_is_judged_against_the_bare_command_it_wraps(hertz, bare, verdict):
    line = _verdict(hertz, bare)
    assert line.startswith(verdict) and f"{hertz:.3f} s against {bare:.3f} s" in line, line


def test_without_both_figures_there_is_no_line():
    table = pd.DataFrame([{"configuration": HERTZ_RUN, "wall_median_s": 0.4}])
    assert not [line for line in target_lines(table, pd.DataFrame()) if "hertz run" in line]
