"""The repository keeps its promises: one owner per fact, results from the current code."""
import os
import re
import shutil
import subprocess
import sys

import pytest

from driver import freefem, studytable
from driver.layout import EDP_DIR
from driver.studies import STUDIES

from conftest import REPO as ROOT

README = (ROOT / "README.md").read_text()
RESULTS_DIR = ROOT / "results"  # the committed tables


def test_readme_documents_every_option_and_every_summary_column():
    for option in freefem.options():
        assert f"`-{option}`" in README, option
    for column in freefem.summary_columns():
        assert f"`{column}`" in README, column


def test_the_fingerprint_ignores_comments_and_whitespace(tmp_path, monkeypatch):
    copy = tmp_path / "edp"
    shutil.copytree(EDP_DIR, copy)
    monkeypatch.setattr(freefem, "EDP_DIR", copy)
    before = freefem.edp_hash()
    target = copy / "lib" / "fe" / "section.idp"
    text = target.read_text()
    target.write_text("// a new comment\n" + text.replace("int edgeRefine = 4;", "int  edgeRefine  =  4 ;  /* why */"))
    assert freefem.edp_hash() == before
    target.write_text(text.replace("int edgeRefine = 4;", "int edgeRefine = 5;"))
    assert freefem.edp_hash() != before


@pytest.mark.parametrize("study", list(STUDIES))
def test_committed_results_come_from_the_current_solver_code(study):
    path = RESULTS_DIR / f"{study}.csv"
    assert path.is_file(), f"{path.name} is not committed: run 'make sweep'"
    hashes = set(studytable.read(path)["edp_hash"])
    assert hashes == {freefem.edp_hash()}, f"{path.name} is stale: run 'make sweep'"


def test_defaults_live_in_hertz_edp_only():
    # the driver names no solver default: the option table is hertz.edp's
    driver_code = "".join(p.read_text() for p in (ROOT / "driver").rglob("*.py"))
    for option in ("kpen", "gamma", "tol", "maxit"):
        default = freefem.options()[option].default
        assert not re.search(rf"\b{option}\s*[:=]\s*{re.escape(default)}\b", driver_code), option


SKIPPING = """
import pytest

def test_needs_something_missing():
    pytest.skip("the frobnicator is not installed")
"""


@pytest.mark.parametrize("allow,code", [("", 1), ("1", 0)])
def test_a_skip_without_an_allowed_reason_fails_the_suite(tmp_path, allow, code):
    # CI must not pass by not testing: a skip is an error unless its reason is allowed (or HERTZ_ALLOW_SKIPS=1)
    shutil.copy(ROOT / "tests" / "conftest.py", tmp_path)
    (tmp_path / "test_skip.py").write_text(SKIPPING)
    env = dict(os.environ, HERTZ_ALLOW_SKIPS=allow, PYTHONPATH=str(ROOT))
    proc = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-rs", str(tmp_path)],
                          cwd=tmp_path, env=env, capture_output=True, text=True)
    assert proc.returncode == code, proc.stdout
    assert "the frobnicator is not installed" in proc.stdout  # -rs: the reason is in the summary


def test_every_mutation_finds_the_code_it_breaks():
    # a mutation whose code has since changed breaks nothing: make mutate reported it only when
    # run, and two had gone stale that way
    from mutations import MUTATIONS, locate
    stale = [m.name for m in MUTATIONS if locate(m) is None]
    assert not stale, stale


def test_every_mutation_names_tests_that_exist():
    from mutations import MUTATIONS
    missing = []
    for mutation in MUTATIONS:
        for test in mutation.tests:
            path, _, name = test.partition("::")
            if not (ROOT / path).is_file() or (name and f"def {name}(" not in (ROOT / path).read_text()):
                missing.append(f"{mutation.name}: {test}")
    assert not missing, missing


def test_a_mutation_follows_its_code_to_another_file(tmp_path, monkeypatch):
    import mutations
    (tmp_path / "edp" / "lib").mkdir(parents=True)
    (tmp_path / "edp" / "lib" / "moved.idp").write_text("real x = 1;\nreal y = 2;\n")
    (tmp_path / "edp" / "lib" / "other.idp").write_text("real z = 1;\n")
    monkeypatch.setattr(mutations, "ROOT", tmp_path)
    moved = mutations.Mutation("x", "edp/lib/gone.idp", "real x = 1;", "real x = 2;", [])
    assert mutations.locate(moved) == tmp_path / "edp" / "lib" / "moved.idp"
    twice = mutations.Mutation("z", "edp/lib/gone.idp", "= 1;", "= 2;", [])
    assert mutations.locate(twice) is None  # in two files: no guess
    changed = mutations.Mutation("w", "edp/lib/moved.idp", "real w = 1;", "real w = 2;", [])
    assert mutations.locate(changed) is None


# -- every path the docs and the comments cite exists -----------------------------------------

# a path from the repository's root: edp/lib/fe/section.idp, driver/charts/, results/REPORT.md
ROOTED = re.compile(r"(?<![\w./-])((?:edp|driver|tests|docs|results|bench)(?:/[\w.+-]+)+/?)")
# what an .idp file's comment or include names: lib/ from edp/, solve/, post/, fe/, methods/ from edp/lib/
IN_EDP = re.compile(r"(?<![\w./-])((lib|solve|post|fe|methods)/[\w.+-]+\.idp)\b")
# a file named alone (messages.idp, hertz_reference.py): some file of the repository has that name
BARE = re.compile(r"(?<![\w./-])([\w+-]+\.(?:idp|edp|py|md|cpp))\b")
# outputs a run or a sweep writes, never committed: cited as places, not as files
UNTRACKED = ("results/local", "results/runs")
# names the docs give that are not this repository's paths, each with why
NOT_PATHS_HERE = {
    "driver/edp/": "the installed wheel's copy of edp/ (setup.py), not a folder of the checkout",
    "slurm_sweep.py": "the file a reader saves docs/driver.md's cluster example as",
}


def _comments(path):
    """(line number, text) of what a file says in prose: the whole of a Markdown file, the
    comments of a FreeFEM, C++ or shell file, the comments and docstrings of a Python file."""
    text = path.read_text(errors="replace")
    if path.suffix == ".md":
        yield from enumerate(text.splitlines(), 1)
    elif path.suffix == ".py":
        import ast
        import io
        import tokenize
        for token in tokenize.generate_tokens(io.StringIO(text).readline):
            if token.type == tokenize.COMMENT:
                yield token.start[0], token.string
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
                body = node.body
                if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant) \
                        and isinstance(body[0].value.value, str):
                    for k, line in enumerate(body[0].value.value.splitlines()):
                        yield body[0].lineno + k, line
    elif path.suffix == ".sh":
        for number, line in enumerate(text.splitlines(), 1):
            if "#" in line:
                yield number, line[line.index("#"):]
    else:  # FreeFEM and C++: // to the end of the line, and /* ... */
        for match in re.finditer(r"//[^\n]*|/\*.*?\*/", text, re.S):
            first = text.count("\n", 0, match.start()) + 1
            for k, line in enumerate(match.group(0).splitlines()):
                yield first + k, line


def _cited_files():
    yield ROOT / "README.md"
    yield from sorted((ROOT / "docs").glob("*.md"))
    for folder in ("edp", "driver"):
        for path in sorted((ROOT / folder).rglob("*")):
            if path.suffix in (".idp", ".edp", ".cpp", ".py", ".sh") and path.is_file():
                yield path


def _missing(text, names):
    """The paths a line cites that are not in the repository."""
    for match in ROOTED.finditer(text):
        cited = match.group(1).rstrip(".")
        bare_word = "." not in cited.rsplit("/", 1)[-1] and not cited.endswith("/")
        if cited in NOT_PATHS_HERE or cited.startswith(UNTRACKED) or bare_word:
            continue  # an output, or a name that is neither a file nor a folder/ (driver/edp: the wheel's)
        if not (ROOT / cited).exists():
            yield cited
    for match in IN_EDP.finditer(text):
        base = EDP_DIR if match.group(2) == "lib" else EDP_DIR / "lib"
        if not (base / match.group(1)).is_file():
            yield match.group(1)
    for match in BARE.finditer(text):
        if match.group(1) not in names and match.group(1) not in NOT_PATHS_HERE:
            yield match.group(1)


def test_every_path_the_docs_and_comments_cite_exists():
    names = {p.name for p in ROOT.rglob("*") if ".git" not in p.parts}
    missing = [f"{path.relative_to(ROOT)}:{number}: {cited}"
               for path in _cited_files() for number, text in _comments(path)
               for cited in _missing(text, names)]
    assert not missing, "\n".join(missing)


def test_the_citation_check_finds_each_kind_of_path():
    names = {"options.idp", "conftest.py"}
    text = ("edp/lib/options.idp, edp/lib/gone.idp, docs/gone.md, driver/charts/, driver/gone/, lib/options.idp, "
            "solve/gone.idp, fe/section.idp, options.idp, conftest.py, gone.py, results/local/bench.csv, driver/edp/")
    assert list(_missing(text, names)) == ["edp/lib/gone.idp", "docs/gone.md", "driver/gone/", "solve/gone.idp",
                                           "gone.py"]
