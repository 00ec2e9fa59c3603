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
    # .gitignore as a clone has it: the build's own bytecode (__pycache__/) is no change to the tree (session 47)
    for name in ("pyproject.toml", "README.md", "CHANGELOG.md", "LICENSE", "MANIFEST.in", "build_backend.py",
                 ".gitignore"):
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


def _stamp_tree(tmp_path: Path, *, git: bool, pkg_info: bool = False) -> Path:
    """A small tree the build backend's ``_stamp`` runs in: build_backend.py, pdrlearn/buildinfo.py, a stale stamp;
    with ``git`` committed to a fresh repository (clean), with ``pkg_info`` an sdist's PKG-INFO beside it."""
    src = tmp_path / "tree"
    (src / "pdrlearn").mkdir(parents=True)
    shutil.copy2(ROOT / "build_backend.py", src / "build_backend.py")
    shutil.copy2(ROOT / "pdrlearn" / "buildinfo.py", src / "pdrlearn" / "buildinfo.py")
    (src / "pdrlearn" / "__init__.py").write_text("")
    (src / ".gitignore").write_text("__pycache__/\npdrlearn/_build.json\n")
    if git:
        cmd = ["git", "-c", "user.name=t", "-c", "user.email=t@t", "-c", "commit.gpgsign=false"]
        for args in (["init", "-q"], ["add", "."], ["commit", "-qm", "x"]):
            subprocess.run([*cmd, *args], cwd=src, check=True, capture_output=True, timeout=60)
    if pkg_info:
        (src / "PKG-INFO").write_text("Metadata-Version: 2.4\nName: pdrlearn\nVersion: 0.1.0\n")
    (src / "pdrlearn" / "_build.json").write_text('{"git_commit": "c9eaeca3OLD", "git_dirty": false}\n')
    return src


def _run_stamp(src: Path, path: str | None = None) -> dict | None:
    env = {**os.environ, "PYTHONDONTWRITEBYTECODE": "1"}
    if path is not None:
        env["PATH"] = path
    r = subprocess.run([sys.executable, "-c", "import build_backend; build_backend._stamp()"], cwd=src,
                       capture_output=True, text=True, timeout=120, env=env)
    assert r.returncode == 0, r.stderr[-2000:]
    stamp = src / "pdrlearn" / "_build.json"
    return json.loads(stamp.read_text()) if stamp.exists() else None


def _head(src: Path) -> str:
    return subprocess.run(["git", "rev-parse", "HEAD"], cwd=src, capture_output=True, text=True,
                          check=True).stdout.strip()


def test_a_stale_build_stamp_is_never_shipped_e187(tmp_path):
    """Review R4 #2a: an earlier build's _build.json stayed when git failed or .git was absent, and the build named
    that commit. Now: a copied tree (no .git, no PKG-INFO) ships no stamp; git failing in a checkout stamps nulls;
    an unpacked sdist (PKG-INFO) keeps its stamp."""
    assert _run_stamp(_stamp_tree(tmp_path / "copy", git=False)) is None
    assert _run_stamp(_stamp_tree(tmp_path / "nogit", git=True), path="/nonexistent") == {"git_commit": None,
                                                                                          "git_dirty": None}
    assert _run_stamp(_stamp_tree(tmp_path / "sdist", git=False, pkg_info=True)) == {"git_commit": "c9eaeca3OLD",
                                                                                     "git_dirty": False}


def test_the_build_stamp_counts_untracked_package_files_as_dirty_e187(tmp_path):
    """Review R4 #2b: setuptools packs an untracked pdrlearn/*.py into the wheel, and the stamp said clean. An
    untracked file elsewhere (not packed) leaves the stamp clean; buildinfo.git_state's runtime answer (tracked files
    only, L136) is unchanged."""
    src = _stamp_tree(tmp_path, git=True)
    assert _run_stamp(src) == {"git_commit": _head(src), "git_dirty": False}
    (src / "notes.txt").write_text("x\n")
    assert _run_stamp(src) == {"git_commit": _head(src), "git_dirty": False}
    (src / "pdrlearn" / "zz_untracked.py").write_text("X = 1\n")
    assert _run_stamp(src) == {"git_commit": _head(src), "git_dirty": True}
    from pdrlearn.buildinfo import checkout_state

    assert checkout_state(src) == (_head(src), False)
