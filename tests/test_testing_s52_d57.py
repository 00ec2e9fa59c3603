"""Decision D57 (docs/testing.md): the tests marked ``extended`` run in ``make test-all`` only; ``make test`` deselects
them. Each is named in D57's table beside a default (unmarked) test that still exercises its mechanism."""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

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
    """``pytest.mark.extended`` (or ``mark.extended`` after ``from pytest import mark``), called or not."""
    if isinstance(node, ast.Call):
        node = node.func
    return isinstance(node, ast.Attribute) and node.attr == "extended" and (
        ast.unparse(node.value) in ("pytest.mark", "mark"))


def _pytestmark(body: list[ast.stmt]) -> list[ast.AST]:
    """The values assigned to ``pytestmark`` in a module's or a class's body (D60: it marks every test in it)."""
    out = []
    for st in body:
        targets = st.targets if isinstance(st, ast.Assign) else [st.target] if isinstance(st, ast.AnnAssign) else []
        if any(isinstance(t, ast.Name) and t.id == "pytestmark" for t in targets) and st.value is not None:
            out.append(st.value)
    return out


def _whole(marks: list[ast.AST]) -> bool:
    """A decorator list or ``pytestmark`` value that marks the whole test (a list or tuple of marks counted)."""
    return any(_is_extended(m) or (isinstance(m, ast.List | ast.Tuple) and any(_is_extended(e) for e in m.elts))
               for m in marks)


def _marked(tree: ast.Module) -> dict[str, bool]:
    """Each test of a module (``test_x``, or ``TestC::test_x`` for a method of a ``Test`` class): True when the whole
    test is marked ``extended`` (its decorator, its class's decorator or ``pytestmark``, the module's ``pytestmark``;
    decision D60), False when only some of its parameters are (``pytest.param(..., marks=pytest.mark.extended)``);
    unmarked tests are left out."""
    return _marked_and_placed(tree)[0]


def _unplaced(tree: ast.Module) -> list[int]:
    """Decision D60: the lines of ``extended`` marks that mark no test :func:`_marked` sees (an alias, a nested
    class, a helper's decorator): a form the check does not read, which must fail rather than escape the table."""
    placed = _marked_and_placed(tree)[1]
    return sorted(n.lineno for n in ast.walk(tree) if _is_extended(n) and not isinstance(n, ast.Call)
                  and id(n) not in placed)


def _marked_and_placed(tree: ast.Module) -> tuple[dict[str, bool], set[int]]:
    out: dict[str, bool] = {}
    placed: set[int] = set()

    def place(nodes):
        placed.update(id(n) for m in nodes for n in ast.walk(m) if _is_extended(n))

    def test(name, fn, inherited):
        if not isinstance(fn, ast.FunctionDef | ast.AsyncFunctionDef) or not fn.name.startswith("test"):
            return
        place(fn.decorator_list)
        if inherited or _whole(fn.decorator_list):
            out[name] = True
        elif any(_is_extended(n) for d in fn.decorator_list for n in ast.walk(d)):
            out[name] = False

    module = _pytestmark(tree.body)
    place(module)
    for node in tree.body:
        test(getattr(node, "name", ""), node, _whole(module))
        if isinstance(node, ast.ClassDef) and node.name.startswith("Test"):
            own = [*node.decorator_list, *_pytestmark(node.body)]
            place(own)
            for fn in node.body:
                test(f"{node.name}::{getattr(fn, 'name', '')}", fn, _whole(module) or _whole(own))
    return out, placed


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
        if "extended" in text:  # D60: any spelling; a mark the check cannot place fails below
            tree = ast.parse(text)
            assert not _unplaced(tree), f"{path.name}: an extended mark on no test the check reads, lines " \
                f"{_unplaced(tree)} (decision D60)"
            found.update({f"{path.name}::{k}": v for k, v in _marked(tree).items()})
    assert found, "no test is marked extended"
    named = {moved.split("[")[0] for moved, _ in rows}
    assert named == set(found), (sorted(named ^ set(found)))
    for moved, cover in rows:
        cover_file, cover_name = cover.split("::", 1)
        tree = ast.parse((TESTS / cover_file).read_text(encoding="utf-8"))
        defined = {fn.name for fn in tree.body if isinstance(fn, ast.FunctionDef)} | {
            f"{c.name}::{fn.name}" for c in tree.body if isinstance(c, ast.ClassDef) for fn in c.body
            if isinstance(fn, ast.FunctionDef)}  # D60: a method's node id
        base = cover_name.split("[")[0]
        assert base in defined, cover
        # a whole-test cover must not be marked; a parameter of the moved test itself may be its cover
        assert _marked(tree).get(base) is not True, cover
        if "[" in moved:
            assert found[moved.split("[")[0]] is False, moved  # only some parameters moved


_SOURCES = {  # decision D60 (review s53r1 F7): the forms the first check (D57) did not see, and what it saw
    "module pytestmark": ("import pytest\npytestmark = pytest.mark.extended\ndef test_a():\n    pass\n",
                          {"test_a": True}),
    "module pytestmark list": ("import pytest\npytestmark = [pytest.mark.slow, pytest.mark.extended]\n"
                               "def test_a():\n    pass\n", {"test_a": True}),
    "marked class": ("import pytest\n@pytest.mark.extended\nclass TestX:\n    def test_b(self):\n        pass\n",
                     {"TestX::test_b": True}),
    "class pytestmark": ("import pytest\nclass TestX:\n    pytestmark = pytest.mark.extended\n"
                         "    def test_b(self):\n        pass\n", {"TestX::test_b": True}),
    "marked method": ("import pytest\nclass TestY:\n    @pytest.mark.extended\n    def test_c(self):\n        pass\n"
                      "    def test_d(self):\n        pass\n", {"TestY::test_c": True}),
    "from pytest import mark": ("from pytest import mark\n@mark.extended\ndef test_e():\n    pass\n",
                                {"test_e": True}),
    "function": ("import pytest\n@pytest.mark.extended\ndef test_f():\n    pass\n", {"test_f": True}),
    "a parameter": ("import pytest\n@pytest.mark.parametrize('x', [1, pytest.param(2, marks=pytest.mark.extended)])"
                    "\ndef test_g(x):\n    pass\n", {"test_g": False}),
}


@pytest.mark.parametrize("form", sorted(_SOURCES))
def test_the_check_sees_every_form_of_the_mark_d60(form):
    src, expected = _SOURCES[form]
    tree = ast.parse(src)
    assert _marked(tree) == expected and _unplaced(tree) == []


def test_a_mark_the_check_cannot_place_is_reported_d60():
    tree = ast.parse("import pytest\nslow = pytest.mark.extended\n@slow\ndef test_h():\n    pass\n")
    assert _marked(tree) == {} and _unplaced(tree) == [2]
