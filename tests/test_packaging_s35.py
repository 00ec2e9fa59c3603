"""Session 35, trial T5 (a packager building and installing the wheel away from the repository): the declared
dependency floors are versions that ran (decision E184); the MIT notice ships in the sdist and the wheel and the
sdist leaves the test suite out on purpose (decision E186); an installed build names the commit it was built from
(decision E187)."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tarfile
import tomllib
import zipfile
from pathlib import Path

import pytest
from packaging.requirements import Requirement
from packaging.version import Version

ROOT = Path(__file__).resolve().parents[1]

#: decision E184: the lowest versions trial T5 (and this session's check of typer with click 8.5) saw work
FLOORS = {"typer": "0.16", "scikit-learn": "1.6", "onnxruntime": "1.18", "dtaidistance": "2.3.13"}


def _floor(req: Requirement) -> Version | None:
    lows = [Version(s.version) for s in req.specifier if s.operator in (">=", "==", "~=")]
    return max(lows) if lows else None


def test_declared_floors_are_versions_that_ran_e184():
    deps = {(r := Requirement(d)).name: r for d in tomllib.loads((ROOT / "pyproject.toml").read_text())
            ["project"]["dependencies"]}
    for name, low in FLOORS.items():
        assert _floor(deps[name]) is not None and _floor(deps[name]) >= Version(low), (name, str(deps[name]))


@pytest.fixture(scope="module")
def built(tmp_path_factory) -> dict:
    """The sdist and the wheel the project's build backend makes of a copy of the package, committed to a fresh git
    repository (as a clone is): ``{"src", "commit", "sdist", "wheel"}``."""
    src = tmp_path_factory.mktemp("pkg") / "src"
    src.mkdir()
    for name in ("pyproject.toml", "README.md", "CHANGELOG.md", "LICENSE", "MANIFEST.in", "build_backend.py"):
        if (ROOT / name).exists():
            shutil.copy2(ROOT / name, src / name)
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc", ".hypothesis", "_build.json")
    shutil.copytree(ROOT / "pdrlearn", src / "pdrlearn", ignore=ignore)
    shutil.copytree(ROOT / "tests", src / "tests", ignore=ignore)
    git = ["git", "-c", "user.name=t", "-c", "user.email=t@t", "-c", "commit.gpgsign=false"]
    for args in (["init", "-q"], ["add", "."], ["commit", "-qm", "x"]):
        subprocess.run([*git, *args], cwd=src, check=True, capture_output=True, timeout=120)
    commit = subprocess.run(["git", "rev-parse", "HEAD"], cwd=src, capture_output=True, text=True,
                            check=True).stdout.strip()
    backend = tomllib.loads((src / "pyproject.toml").read_text())["build-system"]
    code = (f"import sys; sys.path[:0] = {backend.get('backend-path', [])!r}; "
            f"import importlib; b = importlib.import_module({backend['build-backend']!r}); "
            "s = b.build_sdist('dist'); w = b.build_wheel('dist'); print('BUILT', s, w)")
    r = subprocess.run([sys.executable, "-c", code], cwd=src, capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-2000:]
    sdist, wheel = (src / "dist" / n for n in r.stdout.strip().splitlines()[-1].split()[1:])
    return {"src": src, "commit": commit, "sdist": sdist, "wheel": wheel}


@pytest.mark.slow
def test_sdist_and_wheel_carry_the_licence_and_the_sdist_no_half_test_suite_e186(built):
    with tarfile.open(built["sdist"]) as t:
        names = [n.split("/", 1)[1] for n in t.getnames() if "/" in n]
    assert "LICENSE" in names and "CHANGELOG.md" in names
    assert not [n for n in names if n.startswith("tests/")]  # the suite needs the repository: left out whole
    with zipfile.ZipFile(built["wheel"]) as z:
        files = z.namelist()
        meta = z.read(next(n for n in files if n.endswith(".dist-info/METADATA"))).decode()
        lic = next(n for n in files if n.endswith(".dist-info/licenses/LICENSE"))
        assert "MIT License" in z.read(lic).decode() and "pdrlearn developers" in z.read(lic).decode()
    assert "License-Expression: MIT" in meta and "License-File: LICENSE" in meta


@pytest.mark.slow
def test_an_installed_build_names_its_commit_e187(built, tmp_path):
    with tarfile.open(built["sdist"]) as t:
        assert "build_backend.py" in [n.split("/", 1)[-1] for n in t.getnames()]  # the wheel builds from the sdist
    site = tmp_path / "site"
    with zipfile.ZipFile(built["wheel"]) as z:
        z.extractall(site)
    assert json.loads((site / "pdrlearn" / "_build.json").read_text()) == {"git_commit": built["commit"],
                                                                         "git_dirty": False}
    code = "from pdrlearn.buildinfo import git_stamp; import json; print(json.dumps(git_stamp()))"
    r = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True, timeout=60,
                       env={**os.environ, "PYTHONPATH": str(site)})
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout) == {"git_commit": built["commit"], "git_dirty": False}  # not a git checkout there
