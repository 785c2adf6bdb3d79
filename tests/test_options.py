"""hertz.edp's command line: one option table, -help, -options, -opt=value, one-line rejections."""
import csv
import io
import re
import subprocess
import time

import pytest

from driver import freefem
from driver.layout import EDP_DIR


def test_help_lists_every_option_with_default_range_and_meaning(solve):
    run = solve("-help", out=False)
    assert run.exit_code == 0 and "current line" not in run.stdout  # no FreeFEM exit trace
    for option in freefem.options().values():
        line = next(ln for ln in run.stdout.splitlines() if ln.strip().startswith(f"-{option.name} "))
        assert f"default {option.default}" in line and option.range in line
        assert option.help[:30] in run.stdout


@pytest.mark.parametrize("flag", ["-h", "--help"])
def test_short_help_flags_work(solve, flag):
    run = solve(flag, out=False)
    assert run.exit_code == 0 and "-kpen" in run.stdout


def test_options_table_is_machine_readable(solve):
    run = solve("-options", out=False)
    lines = run.stdout.splitlines()
    start = lines.index("name,kind,default,range,help")
    rows = list(csv.DictReader(io.StringIO("\n".join(lines[start:]))))
    names = [r["name"] for r in rows if r["name"].startswith("-")]
    assert {"-kpen", "-gamma", "-method", "-start", "-accuracy", "-maxdof"} <= set(names)
    assert all(r["kind"] in ("real", "int", "word", "path", "list") for r in rows if r["name"].startswith("-"))


def test_equals_form_is_the_same_as_two_words(solve):
    a = solve("-kpen=1e6", "-n=8").summary
    b = solve("-kpen", "1e6", "-n", "8").summary
    assert a["p0_fe"] == b["p0_fe"] and a["kpen"] == 1e6


def test_no_identifier_collides_with_freefems_equals_macros():
    # FreeFEM turns -xname=value into a macro 'name' before the script compiles
    names = {o.name[1:] for o in freefem.options().values() if len(o.name) > 2}
    code = "".join(freefem._COMMENTS.sub("", p.read_text()) for p in EDP_DIR.rglob("*.[ei]dp"))
    words = set(re.findall(r"[A-Za-z_][A-Za-z_0-9]*", re.sub(r'"[^"]*"', "", code)))
    assert not names & words, names & words


BAD_INPUTS = [
    (["-kpen", "-1"], "-kpen"), (["-kpen", "0"], "-kpen"), (["-kpen", "abc"], "-kpen"),
    (["-kpen", "1e5x"], "-kpen"), (["-kpen", "1e15"], "-kpen"), (["-kpen", "4e-320"], "-kpen"),
    (["-gamma", "1e9"], "-gamma"), (["-gamma", "1e8"], "-gamma"), (["-kpen", "1", "-gamma", "1"], "-gamma"),
    (["-E", "0"], "-E"), (["-E", "nan"], "-E"), (["-E", "inf"], "-E"),
    (["-nu", "0.51"], "-nu"), (["-nu", "0.5", "-formulation", "displacement"], "-nu"),
    (["-nu", "-1"], "-nu"), (["-formulation", "mixed", "-order", "1"], "-formulation"),
    (["-formulation", "mixed", "-nu", "0"], "-formulation"), (["-R", "-0.5"], "-R"),
    (["-d", "0"], "-d"), (["-d", "0.5"], "-d"), (["-R", "0.01"], "-d"), (["-n", "1"], "-n"),
    # a radius below the default depth: the message names the radius that was typed too
    (["-R", "0.015625"], "-R"), (["-Rx", "0.01", "-Ry", "0.02"], "-Rx"),
    (["-n", "2.5"], "-n"), (["-order", "3"], "-order"), (["-model", "sphere"], "-model"),
    (["-method", "lagrangian"], "-method"), (["-omega", "0"], "-omega"), (["-omega", "2.5"], "-omega"),
    (["-L", "5"], "-L"), (["-L", "1e5"], "-L"), (["-kpn", "1e5"], "-kpn"), (["-kpen"], "-kpen"),
    (["-kpen", "1e5", "-kpen", "1e6"], "-kpen"), (["-maxit", "0"], "-maxit"), (["-tol", "1"], "-tol"),
    (["-cont", "2"], "-cont"), (["-start", "hertz", "-model", "plane"], "-start"),
    (["-out", "/proc/forbidden"], "-out"), (["-vtk", "/tmp/x.vtk"], "-vtk"), (["-vtk", "/proc/x/f.vtu"], "-vtk"),
    (["-accuracy", "0.5"], "-accuracy"), (["-accuracy", "0.01", "-n", "8"], "-n"),
    (["-accuracy", "0.01", "-method", "fixedpoint"], "-method fixedpoint"),  # diverged (exit 3) every time
    (["-n", "400", "-L", "10"], "-maxdof"), (["-E", "1e-300", "-d", "1e-300"], "scale"),
    (["-E", "1e-6", "-kpen", "1e15"], "-kpen"), (["-R", "1e6", "-d", "1e4", "-kpen", "1e12"], "-kpen"),
    # values that used to stop FreeFEM with a division by zero (exit 8)
    (["-Rx", "0.5", "-Ry", "1e15"], "-Rx"), (["-Rx", "1e-300", "-Ry", "1e300"], "-Rx"),
    (["-Rx", "0.5", "-Ry", "inf", "-model", "3d"], "-model"), (["-d", "5e-324"], "scale"),
    (["-P", "5e-324"], "scale"), (["-Rx", "0.5", "-Ry", "1e15", "-check", "1"], "-Rx"),
    (["-vtk", "/tmp/" + "x" * 250 + ".vtu"], "-vtk"),
    # the option that sets the bound is named, and the scene as it is (a second adversarial pass)
    (["-E1", "10", "-R2", "1e-6"], "-R2"), (["-start", "hertz", "-shape", "cone"], "got -shape cone"),
    (["-E", "1e308"], "finite values stop below"), (["-kpen", "1.7e308"], "finite values stop below"),
    # Uzawa stalled on a punch's graded edge below -gamma 50 (n = 32: 10, 20 and 30)
    (["-shape", "punch", "-method", "uzawa", "-n", "32", "-gamma", "30"], "-gamma must be at least 50"),
    # -maxdof at the top of its range: "raise -maxdof" was advised
    (["-check", "1", "-model", "3d", "-n", "400", "-maxdof", "1e8"], "lower -n"),
]


@pytest.mark.parametrize("args,option", BAD_INPUTS, ids=[" ".join(a) for a, _ in BAD_INPUTS])
def test_bad_input_is_one_line_on_stderr_naming_the_option(solve, args, option):
    run = solve(*args)
    assert run.exit_code == 2, run.output
    errors = run.stderr.strip().splitlines()
    assert len(errors) == 1 and errors[0].startswith("hertz.edp: error:") and option in errors[0], run.output
    assert not run.outdir.exists() or not any(run.outdir.iterdir())  # nothing written


def test_check_validates_without_solving(solve):
    ok = solve("-check", "1", "-kpen", "1e5", out=False)
    assert ok.exit_code == 0 and "options ok" in ok.stdout and "Maximum pressure" not in ok.stdout
    assert solve("-check", "1", "-kpen", "1e15", out=False).exit_code == 2


def test_check_is_quick_on_the_thinnest_film(solve):
    # its coarse level alone took 21 s: -check solves only for a penalty's range
    start = time.perf_counter()
    run = solve("-t", "7.1e-5", "-E2", "10", "-check", "1", out=False)
    assert run.exit_code == 0 and "options ok" in run.stdout and time.perf_counter() - start < 3, run.output


def test_a_plain_run_prints_no_freefem_trace_on_success():
    proc = subprocess.run(freefem.command([]), capture_output=True, text=True,
                          env=freefem.freefem_env())
    assert proc.returncode == 0 and "current line" not in proc.stdout and proc.stderr == ""
