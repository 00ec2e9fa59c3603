"""Session 36 (trial T5 of session 35, finding 3): the required dependencies are the lean runtime's and the toolkit is
the ``full`` extra (decision E189), so a runtime-only install passes ``pip check``; a command that needs a package of
that extra says in one line which extra to install (decision E190)."""

from __future__ import annotations

import ast
import json
import re
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest
from packaging.requirements import Requirement

from pdrlearn.install import DISTRIBUTION, FULL_EXTRA, FULL_INSTALL
from tests.lean_helpers import ABSENT, lean_env

ROOT = Path(__file__).resolve().parents[1]
SHIPPED = ROOT / "models" / "plasys-sim-default"

#: the packages the mission requires: declared (required or in an extra) and installed by make
MISSION = {"torch", "scikit-learn", "numpy", "pandas", "opencv-python-headless"}


def _project() -> dict:
    return tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]


def _import_name(dist: str) -> str:
    return {d: i for i, d in DISTRIBUTION.items()}.get(dist, dist)


def _third_party_imports() -> set[str]:
    """The top-level modules outside the standard library that pdrlearn's source imports anywhere."""
    found = set()
    for f in (ROOT / "pdrlearn").rglob("*.py"):
        for node in ast.walk(ast.parse(f.read_text())):
            if isinstance(node, ast.Import):
                found |= {a.name.split(".")[0] for a in node.names}
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                found.add(node.module.split(".")[0])
    return {m for m in found if m not in sys.stdlib_module_names and m != "pdrlearn"}


def test_required_dependencies_are_the_lean_runtime_and_the_full_extra_the_toolkit_e189():
    project = _project()
    required = {Requirement(d).name for d in project["dependencies"]}
    assert required == {"numpy", "onnxruntime"}  # what python -m pdrlearn.runtime needs (E76)
    full = {Requirement(d).name for d in project["optional-dependencies"][FULL_EXTRA]}
    assert MISSION <= required | full
    assert not required & full
    # every package of the extra is one whose absence the CLI and `import pdrlearn` name in one line (E190, B354)
    assert {_import_name(d) for d in full} <= FULL_INSTALL
    # and every package pdrlearn imports is declared: required, or in the extra (or brought by one of it)
    assert _third_party_imports() <= {_import_name(d) for d in required} | FULL_INSTALL


def test_make_installs_the_full_extra_and_the_test_tools_with_torch_pinned_e189():
    make = (ROOT / "Makefile").read_text()
    rule = make[make.index("$(STAMP): pyproject.toml"):make.index("\ndemo:")]
    assert "pip install -q torch==2.13.0" in rule
    extras = re.search(r"pip install -q -e '\.\[([a-z,]+)\]'", rule)
    assert extras is not None and set(extras.group(1).split(",")) >= {FULL_EXTRA, "dev"}, rule
    assert rule.index("torch==2.13.0") < rule.index("-e '.[")  # the pinned CPU wheel first: the extra finds it


@pytest.mark.parametrize(("argv", "absent", "needer", "package"), [
    (["train", "datasets/real/gaitmap_level_right", "--out", "OUT"], ("sklearn",), "pdrlearn train",
     "scikit-learn (import sklearn)"),
    (["train", "datasets/real/gaitmap_level_right", "--out", "OUT"], ("torch",), "pdrlearn train", "torch"),
    (["track", "datasets/real/gaitmap_level_right", "--out", "OUT"], ("pandas",), "pdrlearn track", "pandas"),
    (["--version"], ABSENT, "the pdrlearn command", "typer"),  # the CLI's entry: a runtime-only install
])
def test_a_command_missing_a_package_of_the_extra_is_one_line_naming_the_extra_e190(tmp_path, argv, absent, needer,
                                                                                   package):
    out = tmp_path / "out"
    argv = [str(ROOT / a) if a.startswith("datasets/") else str(out) if a == "OUT" else a for a in argv]
    module, func = _project()["scripts"]["pdrlearn"].split(":")  # the installed script's entry point
    code = f"import sys, importlib; sys.argv[0] = 'pdrlearn'; sys.exit(importlib.import_module({module!r}).{func}())"
    r = subprocess.run([sys.executable, "-c", code, *argv], capture_output=True, text=True, timeout=300,
                       env=lean_env(tmp_path, absent), cwd=tmp_path)
    assert r.returncode == 2, r.stderr[-3000:]
    lines = r.stderr.strip().splitlines()  # the command's own warnings before it, if any (train: its skipped tasks)
    assert "Traceback" not in r.stderr and all(x.startswith("warning: ") for x in lines[:-1]), r.stderr[-3000:]
    lines = lines[-1:]
    assert lines[0].startswith(f"error: {needer} needs {package}, which is not installed"), lines[0]
    assert f"install the '{FULL_EXTRA}' extra: pip install 'PATH/pdrlearn-*.whl[{FULL_EXTRA}]'" in lines[0]
    assert f"'PATH/TO/CLONE[{FULL_EXTRA}]'" in lines[0] and "python -m pdrlearn.runtime BUNDLE SESSION" in lines[0]
    assert not out.exists()  # nothing half-written


def test_the_lean_runtime_imports_and_loads_a_bundle_without_the_full_extra_e189(tmp_path):
    full = {_import_name(Requirement(d).name) for d in _project()["optional-dependencies"][FULL_EXTRA]}
    absent = sorted(full | FULL_INSTALL)
    code = ("import sys, json, pdrlearn.runtime; from pdrlearn.runtime import load_bundle, Tracker; "
            f"b = load_bundle({str(SHIPPED)!r}); Tracker(b); "
            f"print(json.dumps({{'tasks': sorted(b.tasks), 'loaded': sorted(m for m in {absent!r} "
            "if m in sys.modules)}))")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300,
                       env=lean_env(tmp_path, absent), cwd=tmp_path)
    assert r.returncode == 0, r.stderr[-3000:]
    out = json.loads(r.stdout.strip().splitlines()[-1])
    assert out["loaded"] == [] and {"terrain", "direction", "length"} <= set(out["tasks"])
