"""Session 47 (I2): tests/test_docs_commands.py builds its command list when a test first reads it, not while pytest
collects the file: every xdist worker collects every test file (and tests/test_builtins_listed_c157.py imports this
one), and building the list at import took 7.15 -> 2.70 CPU s of collecting the two files (docs/testing.md)."""

from __future__ import annotations

import ast
from pathlib import Path

DOCS_COMMANDS = Path(__file__).resolve().parent / "test_docs_commands.py"
#: the functions that scan the docs, the --help texts and the sources
BUILDERS = {"documented_commands", "help_commands", "code_commands", "commands"}


def _module_level_calls(path: Path) -> list[str]:
    """Names of the module's own functions called by a statement at module level (run at import), with its line."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    out = []
    for stmt in tree.body:
        if isinstance(stmt, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            continue  # a body runs when called; decorators are names or cache wrappers here
        for node in ast.walk(stmt):
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in BUILDERS:
                out.append(f"line {node.lineno}: {node.func.id}()")
    return out


def test_the_docs_command_list_is_not_built_at_import():
    calls = _module_level_calls(DOCS_COMMANDS)
    assert not calls, f"{DOCS_COMMANDS.name} scans at import (every xdist worker pays it at collection): {calls}"


def test_the_check_sees_a_list_built_at_import(tmp_path):
    f = tmp_path / "m.py"
    f.write_text("def code_commands():\n    return []\n\n\nCOMMANDS = [*code_commands()]\n", encoding="utf-8")
    assert _module_level_calls(f) == ["line 5: code_commands()"]
