"""driver/studies.py: spec files define grids, or are refused with a message naming the key."""
import json
import subprocess
import sys
import textwrap

import pytest

from driver.errors import SpecError
from driver.studies import load_spec

from conftest import REPO, cli, one_error_line


def test_spec_file_defines_a_grid(tmp_path):
    spec = tmp_path / "s.toml"
    spec.write_text(textwrap.dedent("""
        name = "mine"
        [base]
        n = 8
        [grid]
        kpen = [1e3, 1e5]
        order = [1, 2]
        method = ["newton", "lagrange"]
    """))
    grid = load_spec(spec)
    cases = grid.cases()
    assert grid.name == "mine" and grid.count == len(cases) == 8
    assert {c.get("n") for c in cases} == {8} and {c.get("order") for c in cases} == {1, 2}


@pytest.mark.parametrize("text,message", [
    ('name = "x"\n[grid]\nkpn = [1]', "unknown parameter 'kpn'"),
    ('name = "x"\n[grid]\norder = [1.5]', "order must be an integer"),
    ('name = "x"\n[grid]\nkpen = []', "non-empty list"),
    ('name = "x"\n[grid]\nmethod = ["sphere"]', "method must be one of"),
    ('name = "x"\n[grid]\nout = ["/tmp"]', "unknown parameter 'out'"),
    ('name = "x"\n[grid]\nkpen = [-1.0]', r"kpen must be a number in \(0, inf\)"),
    ('name = "x"\n[grid]\nn = [1' + "0" * 400 + "]", r"n must be an integer in \[3, 400\]"),
    ('name = "x"\n[grid]\nE = [1' + "0" * 400 + "]", r"E must be a number in \(0, inf\)"),
    ('name = "kpen"\n[grid]\nn = [4]', "built-in study"),
    ('name = "bench"\n[grid]\nn = [4]', "study name"),
    ('name = "sweep_environment"\n[grid]\nn = [8]', "study name"),
    ('name = "REPORT"\n[grid]\nn = [8]', "study name"),
    (f'name = "{"y" * 300}"\n[grid]\nn = [4]', "study name"),
    ('[grid]\nn = [4]', "'name'"),
    ('name = "x"\nextra = 1\n[grid]\nn = [4]', "unknown key"),
    ('name = "x"', "at least one parameter"),
    ('name = "x"\n[grid\n', "cannot read"),
    ('name = "x"\n[grid]\nn = [4]\nn = [8]', "cannot read"),  # TOML refuses a repeated key itself
])
def test_bad_spec_files_are_rejected_with_a_message(tmp_path, text, message):
    spec = tmp_path / "s.toml"
    spec.write_text(text)
    with pytest.raises(SpecError, match=message):
        load_spec(spec)


@pytest.mark.parametrize("text", ["[1, 2]", '"name"', "3"])
def test_a_json_spec_must_be_an_object(tmp_path, text):
    spec = tmp_path / "s.json"
    spec.write_text(text)
    with pytest.raises(SpecError, match="top level"):
        load_spec(spec)


@pytest.mark.parametrize("text", ['{"name": "d", "grid": {"n": [4]}, "grid": {"n": [8]}}',
                                  '{"name": "d", "grid": {"n": [4], "n": [8]}}'])
def test_a_json_key_given_twice_is_refused(tmp_path, text):
    # json keeps the last of a repeated key, silently: refused instead
    spec = tmp_path / "s.json"
    spec.write_text(text)
    with pytest.raises(SpecError, match="given twice"):
        load_spec(spec)


def test_a_json_spec_defines_the_same_grid_as_toml(tmp_path):
    (tmp_path / "s.json").write_text(json.dumps({"name": "j", "base": {"n": 8}, "grid": {"kpen": [1e3, 1e5]}}))
    assert [c.case_id for c in load_spec(tmp_path / "s.json").cases()] == ["kpen=1000_n=8", "kpen=100000_n=8"]


def test_a_huge_grid_needs_yes(tmp_path):
    spec = tmp_path / "s.toml"
    values = ", ".join(str(1e3 + k) for k in range(200))
    spec.write_text(f'name = "huge"\n[grid]\nkpen = [{values}]\nE = [{values}]\n')
    assert "--yes" in one_error_line(cli("sweep", "--spec", str(spec), "--results", str(tmp_path), "--no-progress"))


GIGANTIC = """
import resource, sys
from pathlib import Path
resource.setrlimit(resource.RLIMIT_AS, (2 << 30, 2 << 30))  # 2 GB: building the grid would need > 12
from driver.cli import main
sys.exit(main(["sweep", "--spec", sys.argv[1], "--results", sys.argv[2], "--yes", "--no-progress"]))
"""


def test_a_grid_is_counted_before_it_is_built(tmp_path):
    # 7e8 cases used to be built (past 12 GB) before the size check
    axes = {name: [float(k + 1) for k in range(60)] for name in ("kpen", "E", "R", "gamma")}
    axes["order"] = [1, 2]
    axes["n"] = list(range(4, 34))
    spec = tmp_path / "s.json"
    spec.write_text(json.dumps({"name": "giant", "grid": axes}))
    proc = subprocess.run([sys.executable, "-c", GIGANTIC, str(spec), str(tmp_path)], cwd=REPO,
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 2 and "7.78e+08 cases" in proc.stderr and "split it" in proc.stderr, proc.stderr
