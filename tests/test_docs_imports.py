"""Every name the documentation imports or lists as an entry point is importable (session-13 API trial:
``from pdrlearn.steps import align_units``, ``pdrlearn.export.export_model`` and ``make_estimator`` were
documented but did not import)."""

from __future__ import annotations

import ast
import importlib
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = [*sorted((ROOT / "docs").glob("*.md")), ROOT / "README.md"]
BLOCK = re.compile(r"^```python[^\n]*\n(.*?)^```", re.S | re.M)
IMPORT_LINE = re.compile(
    r"^[ \t]*(from[ \t]+pdrlearn[\w.]*[ \t]+import[ \t]+(?:\([^)]*\)|[^\n]+)|import[ \t]+pdrlearn[^\n]*)", re.M
)


def _imports(code: str) -> list[ast.stmt]:
    """The import statements of a code block (statement by statement when the block is not valid Python as
    a whole, e.g. with ``...`` placeholders)."""
    try:
        tree = ast.parse(code)
    except SyntaxError:
        tree = ast.parse("\n".join(m.group(1) for m in IMPORT_LINE.finditer(code)))
    return [n for n in ast.walk(tree) if isinstance(n, ast.Import | ast.ImportFrom)]


def _documented_imports() -> list[tuple[str, str, str | None]]:
    """``(doc file, module, name or None)`` for every ``pdrlearn`` import in a ```python block."""
    out = []
    for doc in DOCS:
        for block in BLOCK.finditer(doc.read_text(encoding="utf-8")):
            for node in _imports(block.group(1)):
                if isinstance(node, ast.ImportFrom) and (node.module or "").split(".")[0] == "pdrlearn":
                    out += [(doc.name, node.module, a.name) for a in node.names]
                elif isinstance(node, ast.Import):
                    out += [(doc.name, a.name, None) for a in node.names if a.name.split(".")[0] == "pdrlearn"]
    return out


DOCUMENTED = _documented_imports()


def test_the_docs_have_python_snippets():
    assert len(DOCUMENTED) > 20  # the scan finds them (a changed fence style would silently check nothing)


@pytest.mark.parametrize("doc, module, name", DOCUMENTED, ids=[f"{d}:{m}.{n}" for d, m, n in DOCUMENTED])
def test_documented_import_works(doc, module, name):
    mod = importlib.import_module(module)
    if name is not None and name != "*":
        assert hasattr(mod, name), f"{doc}: `from {module} import {name}` fails"


def _architecture_entries() -> list[tuple[str, str]]:
    """``(package, name)`` for the code names of docs/architecture.md's "main entry points" table: backticked
    identifiers that are called (``name(``) or look like code (CamelCase, ``snake_case``)."""
    out = []
    for line in (ROOT / "docs" / "architecture.md").read_text(encoding="utf-8").splitlines():
        m = re.match(r"^\|[^|]*\|\s*(`pdrlearn[^|]*)\|(.*)\|\s*$", line)
        if not m:
            continue
        packages = re.findall(r"`(pdrlearn[\w.]*)`", m.group(1))
        for name, after in re.findall(r"`([A-Za-z_]\w*)(\(|`|\.)", m.group(2)):
            if after == "(" or "_" in name or name != name.lower():
                out.append((" ".join(packages), name))
    return out


ENTRIES = _architecture_entries()


@pytest.mark.parametrize("packages, name", ENTRIES, ids=[f"{p}:{n}" for p, n in ENTRIES])
def test_architecture_entry_points_import(packages, name):
    mods = [importlib.import_module(p) for p in packages.split()]
    assert any(hasattr(m, name) for m in mods), f"docs/architecture.md lists {name} under {packages}"


def test_architecture_table_is_scanned():
    names = {n for _, n in ENTRIES}
    assert {"align_units", "segment_steps", "make_estimator", "export_model", "get_pipeline"} <= names


@pytest.mark.parametrize("name", ["align_units", "apply_alignment", "align_events", "segment_steps"])
def test_steps_doc_entry_points(name):
    """docs/steps.md "Other entry points" names these as pdrlearn.steps functions."""
    import pdrlearn.steps

    assert name in pdrlearn.steps.__all__ and callable(getattr(pdrlearn.steps, name))


def test_public_model_routes():
    from pdrlearn.classify import make_estimator
    from pdrlearn.export import export_model

    assert make_estimator.__module__ == "pdrlearn.classify.training"
    assert export_model.__module__ == "pdrlearn.export.from_model"
