"""driver/cases.py: exact values, and ids that are one safe file name whatever the values."""
from hypothesis import given
from hypothesis import strategies as st

from driver.cases import Case, exact
from driver.studies import STUDIES


def test_values_travel_exactly_and_ids_tell_them_apart():
    assert exact(0.4999999) == "0.4999999" and float(exact(123456789.4)) == 123456789.4
    assert Case.of(kpen=123456789.4).case_id != Case.of(kpen=123456789.0).case_id
    assert Case.of(nu=0.4999999).args() == ["-nu", "0.4999999"]
    assert Case.of(n=4, L=50.0).case_id == Case.of(L=50.0, n=4).case_id  # order does not matter
    long = Case.of(**{f"x{k}": float(k) for k in range(40)})
    assert len(long.case_id) < 200  # still a file name


def test_quick_studies_are_subsets_of_full_ones():
    for study in STUDIES.values():
        assert {c.case_id for c in study.make(True)} <= {c.case_id for c in study.make(False)}


values = st.one_of(st.text(max_size=40), st.floats(allow_nan=False), st.integers())


@given(st.dictionaries(st.sampled_from(["model", "vtk", "out", "kpen", "n"]), values, min_size=1, max_size=3))
def test_a_case_id_is_one_safe_file_name_whatever_the_values(params):
    # a value such as ../../victim must not become a path
    case_id = Case.of(**params).case_id
    assert "/" not in case_id and "\0" not in case_id and case_id not in (".", "..")
    assert len(case_id.encode()) < 255 and case_id.isascii()


def test_ids_stay_distinct_after_escaping():
    assert Case.of(model="a/b").case_id != Case.of(model="a%2Fb").case_id
    assert Case.of(model="../x").case_id == "model=..%2Fx"
