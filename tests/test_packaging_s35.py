"""Session 35, trial T5 (a packager building and installing the wheel away from the repository): the declared
dependency floors are versions that ran (decision E184); the MIT notice ships in the sdist and the wheel and the
sdist leaves the test suite out on purpose (decision E186)."""

from __future__ import annotations

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


@pytest.mark.slow
def test_sdist_and_wheel_carry_the_licence_and_the_sdist_no_half_test_suite_e186(tmp_path):
    src = tmp_path / "src"
    src.mkdir()
    for name in ("pyproject.toml", "README.md", "CHANGELOG.md", "LICENSE", "MANIFEST.in"):
        if (ROOT / name).exists():
            shutil.copy2(ROOT / name, src / name)
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc", ".hypothesis")
    shutil.copytree(ROOT / "pdrlearn", src / "pdrlearn", ignore=ignore)
    shutil.copytree(ROOT / "tests", src / "tests", ignore=ignore)
    code = ("import setuptools.build_meta as b; s = b.build_sdist('dist'); w = b.build_wheel('dist'); "
            "print('BUILT', s, w)")
    r = subprocess.run([sys.executable, "-c", code], cwd=src, capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-2000:]
    sdist, wheel = (src / "dist" / n for n in r.stdout.strip().splitlines()[-1].split()[1:])
    with tarfile.open(sdist) as t:
        names = [n.split("/", 1)[1] for n in t.getnames() if "/" in n]
    assert "LICENSE" in names and "CHANGELOG.md" in names
    assert not [n for n in names if n.startswith("tests/")]  # the suite needs the repository: left out whole
    with zipfile.ZipFile(wheel) as z:
        files = z.namelist()
        meta = z.read(next(n for n in files if n.endswith(".dist-info/METADATA"))).decode()
        lic = next(n for n in files if n.endswith(".dist-info/licenses/LICENSE"))
        assert "MIT License" in z.read(lic).decode() and "pdrlearn developers" in z.read(lic).decode()
    assert "License-Expression: MIT" in meta and "License-File: LICENSE" in meta
