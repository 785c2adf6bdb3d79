"""What `hertz` says: the solver's warnings on stderr (-q silences them, -v shows the solver's
output as it runs), one error prefix, the option meant for a typo, and 0/1 options as switches."""
import json
import os
import subprocess
import sys
import time

import pytest

from conftest import checkout_first, cli, hertz, one_error_line


def test_an_inaccurate_run_echoes_the_solvers_warning_and_exits_5(tmp_path):
    # the power law k = 1.5 at n = 16 estimates its p0 error above 1%: inaccurate, exit 5
    proc = hertz("run", "--shape", "power", "--out", str(tmp_path / "out"), cwd=tmp_path)
    assert proc.returncode == 5, proc.stderr
    warnings = [line for line in proc.stderr.splitlines() if line.startswith("hertz.edp: warning:")]
    assert warnings and "estimated error" in warnings[0], proc.stderr
    assert proc.stderr.splitlines()[-1] == "files: out"
    assert "warnings" in proc.stdout and "estimate" in proc.stdout  # the row's column too


def test_quiet_prints_the_row_only(tmp_path):
    proc = hertz("run", "--shape", "power", "-q", "--out", str(tmp_path / "out"), cwd=tmp_path)
    assert proc.returncode == 5 and proc.stderr == "" and "inaccurate" in proc.stdout


def test_a_converged_run_has_no_warning_lines(tmp_path):
    proc = hertz("run", "--n", "8", "--out", str(tmp_path / "out"), cwd=tmp_path)
    assert proc.returncode == 0 and proc.stderr == "files: out\n", proc.stderr


SLOW_SOLVER = """#!{python}
import os, subprocess, sys, time
args = sys.argv[1:]
if any(flag in args for flag in ("-options", "-columns", "-exits")):
    sys.exit(subprocess.run([{real!r}, *args]).returncode)
print("first level done", flush=True)
# go on only once the test has seen that line: shown after the run, it would never come
for _ in range(600):
    if os.path.exists({go!r}):
        sys.exit(subprocess.run([{real!r}, *args]).returncode)
    time.sleep(0.05)
print("the first line was not shown while the solver ran", flush=True)
sys.exit(3)
"""


def test_verbose_shows_the_solvers_output_while_it_runs(tmp_path):
    from driver import freefem
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    fake = bin_dir / "FreeFem++"
    go = tmp_path / "go"
    fake.write_text(SLOW_SOLVER.format(python=sys.executable, real=freefem.check_freefem(), go=str(go)))
    fake.chmod(0o755)
    env = checkout_first(dict(os.environ, PATH=f"{bin_dir}{os.pathsep}{os.environ['PATH']}"))
    proc = subprocess.Popen([sys.executable, "-m", "driver", "run", "-v", "--n", "8", "--out", str(tmp_path / "out")],
                            cwd=tmp_path, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 120
        for line in proc.stderr:
            if line.strip() == "first level done":
                go.touch()
                break
            assert time.monotonic() < deadline
        else:
            pytest.fail("the solver's first line was not shown")
        rest = proc.stderr.read()
        assert proc.wait(timeout=120) == 0, rest
    finally:
        proc.kill()
        proc.wait()
    assert "Maximum pressure FE" in rest and rest.splitlines()[-1] == "files: out"
    assert "status" in proc.stdout.read()  # the row stays alone on stdout


def test_verbose_and_quiet_exclude_each_other(tmp_path):
    assert "not allowed with" in one_error_line(hertz("run", "-q", "-v", cwd=tmp_path))


@pytest.mark.parametrize("args,line", [
    (["run", "--kpn", "1e5"], "hertz: error: unrecognized arguments: --kpn 1e5; did you mean --kpen?"),
    (["run", "--metod=lagrange"], "hertz: error: unrecognized arguments: --metod=lagrange; did you mean --method?"),
    (["rnu"], "hertz: error: argument COMMAND: invalid choice: 'rnu'"),
    (["swep", "kpen"], "hertz: error: argument COMMAND: invalid choice: 'swep'"),
    (["run", "--n", "6", "--n", "8"], "hertz: error: --n is given twice; give it once (see hertz run --help)"),
    (["run", "--nu", "0.7"], "hertz: error: --nu must be a number in (-1, 0.5], got '0.7'"),
    (["run", "--d", "0.6"], "hertz.edp: error: -d must be a number in (0, 1) R (R = 0.5), got '0.6'"),
    (["run", "--cont", "2"], "hertz: error: --cont must be an integer in [0, 1], got '2'"),
    (["sweep", "nosuch"], "hertz: error: unknown study 'nosuch'"),
    (["report"], "hertz: error: no study rows"),
    ([], "hertz: error: the following arguments are required: COMMAND"),
])
def test_every_error_line_has_one_prefix(tmp_path, args, line):
    got = one_error_line(hertz(*args, cwd=tmp_path))
    assert got.startswith(line), got
    assert got.startswith(("hertz: error: ", "hertz.edp: error: ")) and "error: hertz" not in got
    assert ("did you mean run?" in got) == (args[:1] == ["rnu"])
    assert ("did you mean sweep?" in got) == (args[:1] == ["swep"])


def test_an_unknown_option_far_from_any_gets_no_guess(tmp_path):
    got = one_error_line(hertz("run", "--zzzzzz", cwd=tmp_path))
    assert "did you mean" not in got and got.startswith("hertz: error: unrecognized arguments: --zzzzzz")


def test_a_failed_run_says_why_with_the_prefix(tmp_path, fake_solver, monkeypatch):
    monkeypatch.setenv("FAKE_MODE", "empty_summary")
    proc = cli("run", "--n", "8", "--out", str(tmp_path / "out"), cwd=tmp_path)
    assert proc.returncode == 1 and proc.stderr.splitlines()[-1].startswith("hertz: error: summary.csv unreadable")


@pytest.mark.parametrize("args,cont,linesearch", [
    (["--cont"], 1, 1), (["--cont", "--linesearch", "0"], 1, 0), (["--linesearch", "--cont", "0"], 0, 1),
    (["--cont", "1"], 1, 1), (["--linesearch=0"], 0, 0),
])
def test_zero_one_options_are_switches_and_still_take_0_or_1(tmp_path, args, cont, linesearch):
    proc = hertz("run", *args, "--n", "8", "--json", "--out", str(tmp_path / "out"), cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    row = json.loads(proc.stdout)
    assert (row["cont"], row["linesearch"]) == (cont, linesearch)


def test_help_says_which_options_are_switches():
    assert "a bare --cont is 1" in " ".join(hertz("run", "--help").stdout.split())


