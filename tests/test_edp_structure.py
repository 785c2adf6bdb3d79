"""The solver's house rules, read from its text: every global is written only by
the file that declares it, included files only define, and the shapes are rows
of one property table."""
import re
import subprocess

import pytest

from driver.layout import EDP_DIR

FILES = [EDP_DIR / "hertz.edp"] + sorted((EDP_DIR / "lib").rglob("*.idp"))
DECLARATION = re.compile(r"^(?:real|int|bool|string)(?:\[[^\]]*\])*\s+(.*)$")
WRITE = r"(?:\[[^\]]*\]|\([^)]*\))?\s*(?:=(?!=)|\+=|-=|\*=|/=|\.\*=|\./=|\+\+|--)"


def code(text: str) -> list[str]:
    """The lines without comments and with every string literal emptied."""
    lines = []
    for line in text.splitlines():
        line = re.sub(r'"(?:[^"\\]|\\.)*"', '""', line)
        lines.append(re.sub(r"//.*", "", line))
    return lines


def top_level_names(line: str) -> list[str]:
    """The names a top-level declaration line declares (commas at depth 0)."""
    match = DECLARATION.match(line)
    if not match:
        return []
    names, depth, current = [], 0, ""
    for ch in match.group(1):
        depth += ch in "([{"
        depth -= ch in ")]}"
        if ch == "," and depth == 0:
            names.append(current)
            current = ""
        else:
            current += ch
    names.append(current)
    return [m.group(1) for n in names if (m := re.match(r"\s*([A-Za-z_]\w*)", n))]


def owners(files) -> dict[str, set]:
    found: dict[str, set] = {}
    for path in files:
        for line in code(path.read_text()):
            for name in top_level_names(line):
                found.setdefault(name, set()).add(path)
    return found


def foreign_writes(files, root=EDP_DIR) -> list[str]:
    """'file:line name' for each write to a global outside the files that declare it
    (the 2D and 3D branches may both declare one). A local of the same name
    declared in the function is not the global."""
    owner = owners(files)
    bad = []
    for path in files:
        foreign = [n for n, paths in owner.items() if path not in paths]
        if not foreign:
            continue
        write = re.compile(r"(?<![\w.])(" + "|".join(map(re.escape, foreign)) + r")" + WRITE)
        local = re.compile(r"\b(?:real|int|bool|string)\b(?:\[[^\]]*\])*\s+(\w+)")
        locals_here: set[str] = set()
        for number, line in enumerate(code(path.read_text()), 1):
            if re.match(r"^(func|macro)\b", line):
                locals_here = set()
            locals_here.update(local.findall(line))
            for match in write.finditer(line):
                name = match.group(1)
                if name in locals_here or re.search(r"[,(]\s*$", line[:match.start()]):  # a named argument
                    continue
                bad.append(f"{path.relative_to(root)}:{number} {name}")
    return bad


def test_every_global_is_written_only_by_its_owner_file():
    assert foreign_writes(FILES) == []


def test_the_owner_check_finds_a_write_from_another_file(tmp_path):
    owner = tmp_path / "a.idp"
    owner.write_text("real growthCap = 0.2;\nfunc real rate() { return growthCap; }\n")
    other = tmp_path / "b.idp"
    other.write_text("func int build() {\n  growthCap = 2;  // a hidden parameter\n  return 0;\n}\n")
    local = tmp_path / "c.idp"
    local.write_text("func int mine() {\n  real growthCap = 1;\n  growthCap = 3;\n  return 0;\n}\n")
    assert foreign_writes([owner, other, local], root=tmp_path) == ["b.idp:2 growthCap"]


def top_level_statements(path, root=EDP_DIR) -> list[str]:
    """Statements at the top level of an included file that act rather than define:
    a call, an if or a while, an exit (a loop that fills a constant table is a definition)."""
    acts, depth = [], 0
    for number, line in enumerate(code(path.read_text()), 1):
        stripped = line.strip()
        if depth == 0 and stripped and (
                re.match(r"^(if|while)\s*\(", stripped)
                or re.match(r"^exit", stripped)
                or re.match(r"^[A-Za-z_]\w*\s*\(.*\)\s*;$", stripped)):
            acts.append(f"{path.relative_to(root)}:{number} {stripped}")
        depth += line.count("{") - line.count("}")
    return acts


def test_included_files_only_define():
    acts = [a for path in FILES[1:] for a in top_level_statements(path)]
    assert acts == []


def test_the_define_check_finds_a_file_that_acts(tmp_path):
    acting = tmp_path / "acting.idp"
    acting.write_text("real x = 1;\nfunc int f() {\n  if (x > 0) x = 2;\n  return 0;\n}\n"
                      "if (x > 0) x = 3;\nreadTable();\n")
    assert [a.split(" ", 1)[0] for a in top_level_statements(acting, root=tmp_path)] == ["acting.idp:6", "acting.idp:7"]


def test_the_shape_table_has_one_row_per_shape():
    text = (EDP_DIR / "lib" / "shapes.idp").read_text()
    rows = dict(re.findall(r"^(?:string|int)\[int\] (shape\w+) = \[(.*?)\];", text, re.M | re.S))
    names = re.findall(r'"(\w+)"', rows.pop("shapeNames"))
    assert names == ["parabola", "sphere", "cone", "punch", "power", "table"]
    for column, cells in rows.items():
        count = len(re.findall(r'"[^"]*"', cells)) if '"' in cells else len(cells.split(","))
        assert count == len(names), column


@pytest.mark.parametrize("args", [["-help", "-n", "1"], ["-n", "1", "-help"], ["-help", "-shape", "nothing"]])
def test_help_prints_whatever_else_is_on_the_line(args):
    done = subprocess.run(["FreeFem++", "-nw", "-v", "0", "hertz.edp", *args], cwd=EDP_DIR,
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert "-shape  (default parabola; parabola, sphere, cone, punch, power, table)" in done.stdout
    assert "Exit codes:" in done.stdout
