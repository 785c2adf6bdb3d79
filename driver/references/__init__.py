"""Closed forms and reference solutions the charts draw, written apart from the solver: edp/
never reads them, and the tests check the solver against them (and them against known limits)."""
