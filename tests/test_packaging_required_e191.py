"""Session 36 (trial T5 of session 35, finding 3): the toolkit's packages stay required dependencies (decision E191,
superseding E189's `full` extra), so `pip install` of the wheel or the clone installs the whole toolkit; the lean
runtime stays the `--no-deps` install and imports none of them; a command that misses one of them says so in one
line (decision E190)."""

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

from pdrlearn.install import DISTRIBUTION, FULL_INSTALL
from tests.lean_helpers import ABSENT, lean_env

ROOT = Path(__file__).resolve().parents[1]
SHIPPED = ROOT / "models" / "plasys-sim-default"

#: the packages the mission requires
MISSION = {"torch", "scikit-learn", "numpy", "pandas", "opencv-python-headless"}
#: what python -m pdrlearn.runtime and pdrlearn.runtime.Tracker import (decision E76)
RUNTIME = {"numpy", "onnxruntime"}


def _project() -> dict:
    return tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]


def _import_name(dist: str) -> str:
    return {d: i for i, d in DISTRIBUTION.items()}.get(dist, dist)


def _required() -> set[str]:
    return {Requirement(d).name for d in _project()["dependencies"]}


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


def test_the_mission_packages_are_required_dependencies_and_no_extra_holds_the_toolkit_e191():
    project = _project()
    required = _required()
    assert MISSION | RUNTIME <= required  # pip install WHEEL (or the clone) brings the whole toolkit
    assert set(project.get("optional-dependencies", {})) == {"dev"}  # no `full` extra (E189 superseded)
    assert not {Requirement(d).name for d in project["optional-dependencies"]["dev"]} & required
    # every required package outside the runtime's is one whose absence the CLI names in one line (E190, B354)
    assert {_import_name(d) for d in required - RUNTIME} <= FULL_INSTALL
    # and every package pdrlearn imports is declared (or brought by one: click, joblib, distributed, threadpoolctl)
    assert _third_party_imports() <= {_import_name(d) for d in required} | FULL_INSTALL


def test_make_installs_the_package_with_the_test_tools_and_torch_pinned_e191():
    make = (ROOT / "Makefile").read_text()
    rule = make[make.index("$(STAMP): pyproject.toml"):make.index("\ndemo:")]
    assert "pip install -q torch==2.13.0" in rule
    installs = re.findall(r"pip install -q -e (\S+)", rule)
    assert installs == ["'.[dev]'"], rule
    assert rule.index("torch==2.13.0") < rule.index("-e '.[dev]'")  # the pinned CPU wheel first: pip keeps it


@pytest.mark.parametrize(("argv", "absent", "needer", "package"), [
    (["train", "datasets/real/gaitmap_level_right", "--out", "OUT"], ("sklearn",), "pdrlearn train",
     "scikit-learn (import sklearn)"),
    (["train", "datasets/real/gaitmap_level_right", "--out", "OUT"], ("torch",), "pdrlearn train", "torch"),
    (["track", "datasets/real/gaitmap_level_right", "--out", "OUT"], ("pandas",), "pdrlearn track", "pandas"),
    (["--version"], ABSENT, "the pdrlearn command", "typer"),  # the CLI's entry: a runtime-only install
])
def test_a_command_missing_a_toolkit_package_is_one_line_naming_how_to_install_it_e190(tmp_path, argv, absent,
                                                                                      needer, package):
    out = tmp_path / "out"
    argv = [str(ROOT / a) if a.startswith("datasets/") else str(out) if a == "OUT" else a for a in argv]
    module, func = _project()["scripts"]["pdrlearn"].split(":")  # the installed script's entry point
    code = f"import sys, importlib; sys.argv[0] = 'pdrlearn'; sys.exit(importlib.import_module({module!r}).{func}())"
    r = subprocess.run([sys.executable, "-c", code, *argv], capture_output=True, text=True, timeout=300,
                       env=lean_env(tmp_path, absent), cwd=tmp_path)
    assert r.returncode == 2, r.stderr[-3000:]
    lines = r.stderr.strip().splitlines()  # the command's own warnings before it, if any (train: its skipped tasks)
    assert "Traceback" not in r.stderr and all(x.startswith("warning: ") for x in lines[:-1]), r.stderr[-3000:]
    line = lines[-1]
    assert line.startswith(f"error: {needer} needs {package}, which is not installed"), line
    assert ("install the toolkit's dependencies: pip install PATH/pdrlearn-*.whl (the wheel) or pip install "
            "PATH/TO/CLONE (pdrlearn is not on PyPI), or make venv in the clone") in line
    assert "python -m pdrlearn.runtime BUNDLE SESSION" in line and "extra" not in line and "[" not in line
    assert not out.exists()  # nothing half-written


def test_the_lean_runtime_imports_and_loads_a_bundle_without_the_toolkit_e191(tmp_path):
    absent = sorted({_import_name(d) for d in _required() - RUNTIME} | FULL_INSTALL)
    code = ("import sys, json, pdrlearn.runtime; from pdrlearn.runtime import load_bundle, Tracker; "
            f"b = load_bundle({str(SHIPPED)!r}); Tracker(b); "
            f"print(json.dumps({{'tasks': sorted(b.tasks), 'loaded': sorted(m for m in {absent!r} "
            "if m in sys.modules)}))")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300,
                       env=lean_env(tmp_path, absent), cwd=tmp_path)
    assert r.returncode == 0, r.stderr[-3000:]
    out = json.loads(r.stdout.strip().splitlines()[-1])
    assert out["loaded"] == [] and {"terrain", "direction", "length"} <= set(out["tasks"])
    assert "torch" in absent and "sklearn" in absent and "pandas" in absent  # the test refuses the toolkit
