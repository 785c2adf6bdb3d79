"""driver/schema.py: the largest error of a row, and which rows gave an answer."""
import math

import pandas as pd
import pytest

from driver import schema


def test_the_largest_error_skips_absent_and_missing_quantities():
    rows = pd.DataFrame({"err_p0": [0.001, -0.02, math.nan], "err_F": [-0.004, 0.001, math.nan],
                         "err_a": [0.002, math.nan, math.nan]})  # no err_b column: a 2D table
    largest = schema.max_error(rows)
    assert largest.iloc[:2].tolist() == [0.004, 0.02] and math.isnan(largest.iloc[2])


@pytest.mark.parametrize("row,answered", [
    ({"status": "converged", "p0_fe": 1.0, "F_fe": 2.0, "a_fe": 0.1}, True),
    ({"status": "inaccurate", "p0_fe": "1.0", "F_fe": "2", "a_fe": "0.1"}, True),  # a CSV's text
    ({"status": "converged", "p0_fe": 1.0, "F_fe": math.nan, "a_fe": 0.1}, False),
    ({"status": "converged", "p0_fe": 1.0, "F_fe": "", "a_fe": 0.1}, False),
    ({"status": "converged", "p0_fe": 1.0, "F_fe": math.inf, "a_fe": 0.1}, False),
    ({"status": "converged", "shape": "cone", "p0_fe": math.nan, "F_fe": 2.0, "a_fe": 0.1}, True),
    ({"status": "converged", "shape": "sphere", "p0_fe": math.nan, "F_fe": 2.0, "a_fe": 0.1}, False),
    ({"status": "diverged", "p0_fe": 1.0, "F_fe": 2.0, "a_fe": 0.1}, False),
])
def test_a_row_answered_only_with_finite_p0_f_and_a(row, answered):
    # p0 is no result under a cone's tip or at a punch's edge, where the pressure is singular
    assert schema.answered(row) == answered
