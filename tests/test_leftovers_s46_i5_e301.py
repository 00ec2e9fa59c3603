"""Decision E301 (session 46, I5): every script in experiments/ starts both as ``python experiments/NAME.py`` and as
``python -m experiments.NAME`` from the repository root, without PYTHONPATH=. : siblings are imported by their bare
names (experiments/ is on ``sys.path`` by path; ``experiments/__init__.py`` adds it for ``-m``), the tests' helpers
through ``experiments/_repo.py``.

Each launch is emulated in one fresh subprocess for both modes (decision D51): ``sys.path`` as Python sets it for
that launch (experiments/ first by path, the repository root first for ``-m``; the checkout's pdrlearn through a
folder that holds only it),
and every script is run under another name than ``__main__`` (its imports and module-level code, not its
experiment), with the modules of experiments/ and tests/ forgotten between scripts. A few scripts' ``--help`` are
then launched for real, both ways."""

from __future__ import annotations

import ast
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
EXP = ROOT / "experiments"

CHECK = r'''
import os, runpy, sys
from pathlib import Path
modes, root = sys.argv[1].split(","), Path(sys.argv[2])
exp = root / "experiments"
import pdrlearn  # noqa: F401  (the checkout's, through the folder on PYTHONPATH)
base = [p for p in sys.path if p not in ("", str(root), os.getcwd())]
keep = set(sys.modules)
bad = []
for mode, f in ((m, f) for m in modes for f in sorted(exp.glob("*.py"))):
    if f.name == "__init__.py":
        continue
    sys.path[:] = ([str(exp)] if mode == "path" else [str(root)]) + base
    for m in set(sys.modules) - keep:
        fn = getattr(sys.modules[m], "__file__", None) or ""
        if m.split(".")[0] in ("experiments", "tests") or fn.startswith((str(exp), str(root / "tests"))):
            del sys.modules[m]
    sys.argv = [str(f), "--help"]
    try:
        if mode == "path":
            runpy.run_path(str(f), run_name="_e301_check")
        else:
            runpy.run_module(f"experiments.{f.stem}", run_name="_e301_check", alter_sys=True)
    except BaseException as e:  # noqa: BLE001  (SystemExit too: a script that exits at import)
        bad.append(f"{mode} {f.name}: {type(e).__name__}: {str(e)[:150]}")
print("\n".join(bad))
print(f"FAILED {len(bad)}")
'''


def _env(tmp_path: Path) -> dict:
    """PYTHONPATH = a folder holding only a link to the checkout's pdrlearn: the repository root is not on it."""
    link = tmp_path / "pkg"
    link.mkdir(exist_ok=True)
    if not (link / "pdrlearn").exists():
        (link / "pdrlearn").symlink_to(ROOT / "pdrlearn", target_is_directory=True)
    return {**os.environ, "PYTHONPATH": str(link), "OMP_NUM_THREADS": "1", "MPLBACKEND": "Agg"}


def check_launches(root: Path, modes: str, tmp_path: Path) -> dict[str, list[str]]:
    """The scripts of ``root``/experiments that do not import as each of ``modes`` ("path", "module" or
    "path,module") launches them: ``{mode: ["NAME.py: error", ...]}``. One subprocess for all the modes (decision
    D51): between two scripts, of one mode or the next, it forgets the modules of experiments/ and tests/ and resets
    ``sys.path`` alike, so each script is imported as in a process of its own mode; the libraries stay imported."""
    script = tmp_path / "check.py"
    script.write_text(CHECK)
    r = subprocess.run([sys.executable, str(script), modes, str(root)], cwd=tmp_path, env=_env(tmp_path),
                       capture_output=True, text=True, timeout=900)
    lines = r.stdout.strip().splitlines()
    assert lines and lines[-1].startswith("FAILED "), r.stderr[-2000:]
    bad = {m: [] for m in modes.split(",")}
    for ln in lines[:-1]:
        mode, _, rest = ln.partition(" ")
        if mode in bad and ": " in rest and rest.split(":")[0].endswith(".py"):
            bad[mode].append(rest)
    return bad


@pytest.fixture(scope="module")
def both_launches(tmp_path_factory) -> dict[str, list[str]]:
    """Both launches' failures, checked in one subprocess for the module (decision D51: not one per mode)."""
    return check_launches(ROOT, "path,module", tmp_path_factory.mktemp("e301"))


@pytest.mark.slow
@pytest.mark.parametrize("mode", ["path", "module"])
def test_every_script_imports_as_each_launch_would_e301(mode, both_launches):
    assert both_launches[mode] == []


# by path: a former experiments.x import (drops, clock_origin_l198), bare siblings (waist_cadence_law), the tests'
# helpers (waist_gap_heading); with -m: bare siblings that only the by-path run found (waist_pll_edges)
LAUNCHED = ["drops", "clock_origin_l198", "waist_cadence_law", "waist_gap_heading", "waist_pll_edges"]


@pytest.mark.slow
@pytest.mark.parametrize("name", LAUNCHED)
def test_help_launches_both_ways_from_the_repo_root_e301(name, tmp_path):
    env = _env(tmp_path)
    for argv in ([f"experiments/{name}.py"], ["-m", f"experiments.{name}"]):
        r = subprocess.run([sys.executable, *argv, "--help"], cwd=ROOT, env=env, capture_output=True, text=True,
                           timeout=120)
        assert r.returncode == 0 and "usage:" in r.stdout, (argv, r.stderr[-600:])


def _imports(path: Path):
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            yield node.module
        elif isinstance(node, ast.Import):
            yield from (a.name for a in node.names)


def test_no_script_imports_experiments_dot_or_tests_without_repo_e301():
    """Also the imports inside functions (not run by the import check): ``experiments.x`` is not importable by path,
    ``tests.x`` only after ``import _repo``."""
    bad = []
    for f in sorted(EXP.glob("*.py")):
        mods = list(_imports(f))
        bad += [f"{f.name}: {m}" for m in mods if m.split(".")[0] == "experiments"]
        if any(m.split(".")[0] == "tests" for m in mods) and "_repo" not in mods:
            bad.append(f"{f.name}: tests.* without _repo")
    assert bad == []


def test_script_names_shadow_no_module_e301():
    """By path experiments/ is first on sys.path, with -m last: a script named as a standard or installed module
    would be read differently by the two launches."""
    import importlib.util

    clash = []
    for f in sorted(EXP.glob("*.py")):
        if f.stem == "__init__":
            continue
        if f.stem in sys.stdlib_module_names:
            clash.append(f.stem)
            continue
        spec = importlib.util.find_spec(f.stem)
        if spec is not None and spec.origin and Path(spec.origin).resolve().parent != EXP:
            clash.append(f.stem)
    assert clash == []
