"""driver/freefem.py: hertz.edp's option table, exit codes and columns, read from the solver, never copied."""
import json
import math
import os
import subprocess
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from driver import freefem
from driver.errors import OptionError

from conftest import cli, one_error_line


def test_the_option_table_and_the_exit_table_come_from_hertz_edp():
    options = freefem.options()
    assert {"kpen", "gamma", "method", "n", "out", "vtk"} <= set(options)
    assert options["method"].choices and "lagrange" in options["method"].choices
    exits = freefem.exits()
    assert exits["converged"].code == 0 and exits["rejected"].code == 2 and exits["inaccurate"].code == 5
    assert all(e.meaning for e in exits.values())
    columns = freefem.summary_columns()
    assert columns[0] == "model" and {"p0_fe", "F_fe", "a_fe", "status"} <= set(columns)


@pytest.mark.parametrize("name,value,expect", [
    ("n", "16", 16), ("n", 8.0, 8), ("kpen", "1e5", 1e5), ("Rx", "inf", math.inf), ("method", "lagrange", "lagrange"),
    ("nu", "0.4999999", 0.4999999), ("d", "0.6", 0.6),  # d's range scales with R: hertz.edp checks it
])
def test_good_values_parse_to_what_hertz_edp_reads(name, value, expect):
    assert freefem.options()[name].parse(value) == expect


@pytest.mark.parametrize("name,value,words", [
    ("nu", "0.7", "(-1, 0.5]"), ("kpen", "-1", "(0, inf)"), ("n", "2.5", "an integer"), ("n", "1", "[3, 400]"),
    ("model", "../../victim", "one of auto"), ("kpen", "1e400", "(0, inf)"), ("kpen", "nan", "(0, inf)"),
    ("n", 10**400, "[3, 400]"), ("E", 10**400, "(0, inf)"), ("order", True, "an integer"), ("d", "inf", "(0, 1) R"),
])
def test_bad_values_name_the_option_and_its_range(name, value, words):
    with pytest.raises(OptionError) as error:
        freefem.options()[name].parse(value, f"--{name}")
    assert f"--{name}" in str(error.value) and words in str(error.value)


@given(st.sampled_from(["n", "kpen", "nu", "gamma", "order", "method", "Rx", "tol", "maxdof"]),
       st.one_of(st.text(max_size=12), st.floats(), st.integers(-10**500, 10**500), st.booleans()))
def test_any_value_parses_within_its_range_or_is_one_clear_error(name, value):
    option = freefem.options()[name]
    try:
        parsed = option.parse(value)
    except OptionError as exc:
        assert f"-{name}" in str(exc) and option.range in str(exc) and "\n" not in str(exc)
        return
    if option.kind == "word":
        assert parsed in option.choices
    else:
        assert isinstance(parsed, int if option.kind == "int" else float) and not math.isnan(parsed)


def test_the_driver_follows_the_solvers_exit_table(fake_solver, monkeypatch, tmp_path):
    # a hertz.edp whose codes are all 10 higher: a copy of the old table in the driver would call
    # every run a mismatch; the driver reads -exits and agrees with the solver
    monkeypatch.setenv("FAKE_MODE", "exits_shifted")
    proc = cli("run", "--n", "4", "--L", "50", "--farfield", "clamped", "--results", str(tmp_path))
    assert proc.returncode == 15, proc.stderr  # inaccurate (5: the clamped boundary at 50 a), shifted
    assert "status                    inaccurate" in proc.stdout


def test_new_options_and_columns_are_read_from_the_solver_not_listed(fake_solver, monkeypatch, tmp_path):
    # a later hertz.edp with a word option -finish and columns finish, Z_fe: the driver takes them as they come
    monkeypatch.setenv("FAKE_MODE", "grown")
    proc = cli("run", "--finish", "rough", "--n", "8", "--json", "--results", str(tmp_path))
    assert proc.returncode == 0, proc.stderr
    row = json.loads(proc.stdout)
    assert row["finish"] == "rough" and row["Z_fe"] == 1.5 and row["status"] == "converged"
    assert one_error_line(cli("run", "--finish", "matte", "--results", str(tmp_path))).endswith(
        "--finish must be one of polished, rough, got 'matte'")


SKYLAKE = "flags\t\t: fpu sse2 avx avx2 fma avx512f avx512dq avx512cd avx512bw avx512vl\n"


@pytest.mark.parametrize("cpuinfo,kernels", [
    ("processor\t: 0\n" + SKYLAKE + "bugs\t\t: spectre_v1\n", "SkylakeX"),
    (SKYLAKE.replace(" avx512vl", ""), "Haswell"),  # AVX-512 without VL: not the SkylakeX kernels
    ("flags\t\t: fpu sse2 avx avx2 fma\n", "Haswell"),
    ("flags\t\t: fpu sse2 sse3 avx\n", None),  # no FMA: OpenBLAS's own choice
    ("Features\t: fp asimd evtstrm aes\n", None),  # an ARM CPU has no flags line
    ("", None),
])
def test_the_blas_kernels_follow_the_cpus_flags(cpuinfo, kernels):
    assert freefem.blas_kernels(cpuinfo) == kernels


def test_the_solver_runs_the_kernels_its_cpu_allows(tmp_path):
    # OpenBLAS names the kernels it loaded when asked (OPENBLAS_VERBOSE=2)
    env = freefem.freefem_env() | {"OPENBLAS_VERBOSE": "2"}
    expected = env.get("OPENBLAS_CORETYPE")
    assert expected == (os.environ.get("OPENBLAS_CORETYPE")
                        or freefem.blas_kernels(Path("/proc/cpuinfo").read_text()))
    proc = subprocess.run(freefem.command(["-n", "4", "-out", str(tmp_path)]), capture_output=True, text=True,
                          env=env, timeout=120)
    assert proc.returncode == 0, proc.stderr
    if expected:
        assert f"Core: {expected}" in proc.stdout + proc.stderr, proc.stdout + proc.stderr


@pytest.mark.parametrize("name, value, parsed", [
    ("path", "1, 0.5", "1,0.5"), ("path", [1, 0.25, 1], "1,0.25,1"), ("Qpath", "1,-1,1", "1,-1,1"),
    ("path", "1,0", None), ("path", "1,x", None), ("Qpath", "1,-2", None), ("path", "", None),
])
def test_a_list_option_is_its_numbers_each_in_the_range(name, value, parsed):
    option = freefem.options()[name]
    if parsed is None:
        with pytest.raises(OptionError) as error:
            option.parse(value)
        assert f"-{name}" in str(error.value) and option.range in str(error.value)
    else:
        assert option.parse(value) == parsed
