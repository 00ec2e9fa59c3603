"""Decision D57 (docs/testing.md): the tests marked ``extended`` run in ``make test-all`` only; ``make test`` deselects
them. Each is named in D57's table beside a default (unmarked) test that still exercises its mechanism."""

from __future__ import annotations

import ast
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
TESTS = ROOT / "tests"


def _recipe(target: str) -> str:
    """The command lines of a Makefile target (the tab-indented lines after ``target:``)."""
    lines = (ROOT / "Makefile").read_text(encoding="utf-8").splitlines()
    start = next(i for i, ln in enumerate(lines) if ln.startswith(f"{target}:"))
    body = []
    for ln in lines[start + 1:]:
        if not ln.startswith("\t"):
            break
        body.append(ln.strip())
    return "\n".join(body)


def _is_extended(node: ast.AST) -> bool:
    return isinstance(node, ast.Attribute) and node.attr == "extended" and ast.unparse(node.value) == "pytest.mark"


def _marked(tree: ast.Module) -> dict[str, bool]:
    """Each test function of a module: True when the whole test is marked ``extended``, False when only some of its
    parameters are (``pytest.param(..., marks=pytest.mark.extended)``); unmarked tests are left out."""
    out = {}
    for fn in tree.body:
        if not isinstance(fn, ast.FunctionDef) or not fn.name.startswith("test"):
            continue
        if any(_is_extended(d) for d in fn.decorator_list):
            out[fn.name] = True
        elif any(_is_extended(n) for d in fn.decorator_list for n in ast.walk(d)):
            out[fn.name] = False
    return out


def _d57_rows() -> list[tuple[str, str]]:
    text = (ROOT / "docs" / "testing.md").read_text(encoding="utf-8")
    section = text.split("\n## D57 ", 1)[1].split("\n## ", 1)[0]
    return re.findall(r"^\| `([^`]+)` \| `([^`]+)` \|$", section, flags=re.M)


def test_make_test_deselects_the_extended_tests_and_test_all_runs_them():
    test, every = _recipe("test"), _recipe("test-all")
    assert "pytest" in test and '-m "not extended"' in test, test
    assert "pytest" in every and "extended" not in every and not re.search(r"-m ['\"]", every), every
    pyproject = (ROOT / "pyproject.toml").read_text(encoding="utf-8")
    assert re.search(r'^\s*"extended: ', pyproject, flags=re.M), "the marker is not registered"


def test_the_extended_tests_are_d57s_table_each_beside_a_default_test():
    rows = _d57_rows()
    assert len(rows) >= 5, rows
    found = {}
    for path in sorted(TESTS.glob("test_*.py")):
        text = path.read_text(encoding="utf-8")
        if "mark.extended" in text:
            found.update({f"{path.name}::{k}": v for k, v in _marked(ast.parse(text)).items()})
    assert found, "no test is marked extended"
    named = {moved.split("[")[0] for moved, _ in rows}
    assert named == set(found), (sorted(named ^ set(found)))
    for moved, cover in rows:
        cover_file, cover_name = cover.split("::")
        tree = ast.parse((TESTS / cover_file).read_text(encoding="utf-8"))
        defined = {fn.name for fn in tree.body if isinstance(fn, ast.FunctionDef)}
        base = cover_name.split("[")[0]
        assert base in defined, cover
        # a whole-test cover must not be marked; a parameter of the moved test itself may be its cover
        assert _marked(tree).get(base) is not True, cover
        if "[" in moved:
            assert found[moved.split("[")[0]] is False, moved  # only some parameters moved
