"""Property-based: random options and spec files give a valid result or a clear error."""
import math
import subprocess
import tempfile
from pathlib import Path

import pandas as pd
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from driver.run import freefem_command, freefem_env
from driver.studies import SpecError, load_spec

NUMERIC = ["-kpen", "-E", "-nu", "-R", "-d", "-omega", "-L", "-n", "-order", "-maxit", "-tol"]
WORDS = {"-model": ["axi", "plane"], "-method": ["newton", "fixedpoint", "auglag"]}

values = st.one_of(
    st.sampled_from(["0", "-1", "nan", "inf", "-inf", "1e400", "1e-400", "abc", "", "1e5x",
                     "0x10", "1,5", "--", "2", "0.3", "1e5", "0.49", "-0.5", "3"]),
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.integers(-10, 10**6).map(str),
)
option = st.tuples(st.sampled_from(NUMERIC + list(WORDS)), st.one_of(values, st.sampled_from(
    ["axi", "plane", "newton", "fixedpoint", "auglag", "sphere"])))
command = st.lists(option, min_size=1, max_size=3)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(command, st.booleans())
def test_random_options_give_a_result_or_a_named_error(opts, drop_last_value):
    args = ["-n", "4", "-L", "50"] if all(o != "-n" for o, _ in opts) else []
    for name, value in opts:
        args += [name, value]
    if drop_last_value:
        args = args[:-1]  # a missing value
    with tempfile.TemporaryDirectory() as out:
        proc = subprocess.run(freefem_command(args, Path(out)),
                              capture_output=True, text=True, env=freefem_env(), timeout=300)
        errors = [ln for ln in proc.stdout.splitlines() if ln.startswith("hertz.edp: error:")]
        if proc.returncode == 2:
            assert len(errors) == 1
            named = [o for o in NUMERIC + list(WORDS) if o in errors[0]] or ["unknown option"]
            assert named and any(a in errors[0] for a in args if a.startswith("-")) \
                or "unknown option" in errors[0] or "needs a value" in errors[0]
            assert not any(Path(out).iterdir())
            return
        assert proc.returncode in (0, 3), proc.stdout[-2000:]
        s = pd.read_csv(Path(out) / "summary.csv").iloc[0]
        if proc.returncode == 0:
            assert s["status"] == "converged"
            for key in ("p0_fe", "F_fe", "a_fe"):
                assert math.isfinite(s[key]) and s[key] > 0
        else:
            assert s["status"] in ("diverged", "maxiter")


keys = st.sampled_from(["n", "kpen", "order", "model", "method", "E", "nope", "L", "cont"])
spec_values = st.one_of(st.integers(-5, 50), st.floats(allow_nan=True), st.text(max_size=5),
                        st.booleans(), st.lists(st.integers(1, 4), max_size=3))


@settings(max_examples=150, deadline=None)
@given(st.dictionaries(keys, st.lists(spec_values, max_size=3), max_size=3),
       st.dictionaries(keys, spec_values, max_size=2))
def test_random_spec_files_define_cases_or_name_the_problem(grid, base):
    def toml_value(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, str):
            return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
        if isinstance(v, float) and math.isnan(v):
            return "nan"
        if isinstance(v, list):
            return "[" + ", ".join(toml_value(x) for x in v) + "]"
        return repr(v)
    lines = ['name = "fuzz"', "[base]"] + [f"{k} = {toml_value(v)}" for k, v in base.items()]
    lines += ["[grid]"] + [f"{k} = {toml_value(v)}" for k, v in grid.items()]
    with tempfile.TemporaryDirectory() as tmp:
        spec = Path(tmp) / "s.toml"
        spec.write_text("\n".join(lines))
        try:
            name, cases = load_spec(spec)
        except SpecError as exc:
            text = str(exc)
            assert "spec" in text and ("grid" in text or "base" in text or any(k in text for k in
                   list(grid) + list(base)) or "cannot read" in text)
            return
        assert name == "fuzz" and cases
        for case in cases:
            assert isinstance(case.n, int) and isinstance(case.model, str)
            assert all(math.isfinite(getattr(case, f)) for f in ("kpen", "E", "L"))


cli_tokens = st.sampled_from(["run", "sweep", "report", "bench", "--kpen", "--order", "--n", "--jobs",
                              "--timeout", "--quick", "--all", "--spec", "--force", "kpen", "mesh",
                              "nosuch", "-1", "0", "nan", "inf", "1e5", "2", "x", ""])


@settings(max_examples=300, deadline=None)
@given(st.lists(cli_tokens, max_size=6))
def test_random_command_lines_parse_or_exit_with_a_usage_error(tokens):
    import contextlib
    import io

    from driver.cli import build_parser
    err = io.StringIO()
    try:
        with contextlib.redirect_stderr(err):
            args = build_parser().parse_args(tokens)
    except SystemExit as exc:
        assert exc.code in (0, 2)  # 0: --help; 2: usage error with a message
        if exc.code == 2:
            assert "error:" in err.getvalue()
        return
    for name in ("jobs", "timeout"):
        value = getattr(args, name, None)
        if value is not None:
            assert value > 0 and math.isfinite(value)
