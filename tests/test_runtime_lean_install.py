"""A runtime-only install (decisions E76, B157, E191): numpy + onnxruntime and pdrlearn installed with ``--no-deps``.

A fresh interpreter whose import system refuses every package of the full install (as a lean venv lacks them:
``ModuleNotFoundError``) replays a simulated session through the shipped bundle with ``python -m
pdrlearn.runtime``; its steps and track equal ``pdrlearn run``'s. The ``pdrlearn`` script there prints one line
naming that command instead of a ``typer`` traceback.
"""

from __future__ import annotations

import json
import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from tests.lean_helpers import ABSENT, lean_env

ROOT = Path(__file__).resolve().parents[1]
SHIPPED = ROOT / "models" / "plasys-sim-default"


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    """Simulated scenario A of user 801 (20 Hz) and `pdrlearn run`'s output folder for it (shipped bundle)."""
    sim = pytest.importorskip("pdrlearn.sim")
    from pdrlearn.cli import main
    from pdrlearn.io import write_session

    root = tmp_path_factory.mktemp("lean")
    write_session(sim.simulate("A", 801, seed=801), root / "A")
    assert main(["run", "--no-plot", str(SHIPPED), str(root / "A"), "--out", str(root / "full")]) == 0
    return root


def test_lean_replay_without_the_full_install_equals_pdrlearn_run(walk, tmp_path):
    r = subprocess.run([sys.executable, "-m", "pdrlearn.runtime", str(SHIPPED), str(walk / "A"), "--out",
                        str(tmp_path / "lean"), "--json"], capture_output=True, text=True, timeout=300,
                       env=lean_env(tmp_path), cwd=tmp_path)
    assert r.returncode == 0, r.stderr[-2000:]
    out = json.loads(r.stdout)
    full, lean = pd.read_csv(walk / "full" / "steps.csv"), pd.read_csv(tmp_path / "lean" / "steps.csv")
    assert len(lean) == len(full) == out["n_steps"] >= 10
    shared = [c for c in lean.columns if c in full.columns]
    assert {"start_s", "end_s", "length_m", "heading_rad", "x", "y", "z", "terrain", "direction",
            "length_class", "p_terrain_up", "sideways"} <= set(shared)  # sideways: decision L243
    assert list(lean.columns[:9]) == list(full.columns[:9])  # pdrlearn run's column order (B14)
    for c in shared:
        if full[c].dtype.kind == "f":
            np.testing.assert_allclose(lean[c], full[c], rtol=0, atol=1e-9, err_msg=c)
        else:
            assert lean[c].astype(str).tolist() == full[c].astype(str).tolist(), c
    summary = json.loads((walk / "full" / "summary.json").read_text())
    np.testing.assert_allclose([out["final_position"][k] for k in "xyz"],
                               [summary["final_position"][k] for k in "xyz"], atol=1e-9)
    np.testing.assert_allclose(out["distance_m"], summary["distance_m"], atol=1e-6)
    tl, tf = pd.read_csv(tmp_path / "lean" / "trajectory.csv"), pd.read_csv(walk / "full" / "trajectory.csv")
    np.testing.assert_allclose(tl[["t", "x", "y", "z"]], tf[["t", "x", "y", "z"]], atol=1e-9)


def test_pdrlearn_script_without_typer_prints_one_line_naming_the_lean_command(walk, tmp_path):
    module, func = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["scripts"]["pdrlearn"].split(":")
    code = f"import sys, importlib; sys.argv[0] = 'pdrlearn'; sys.exit(importlib.import_module({module!r}).{func}())"
    r = subprocess.run([sys.executable, "-c", code, "run", "--no-plot", str(SHIPPED), str(walk / "A")],
                       capture_output=True,
                       text=True, timeout=120, env=lean_env(tmp_path), cwd=tmp_path)
    assert r.returncode == 2
    assert "Traceback" not in r.stderr and len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert "typer" in r.stderr and "python -m pdrlearn.runtime BUNDLE SESSION" in r.stderr


def test_lean_reader_refuses_what_only_the_full_reader_repairs(walk, tmp_path, capsys):
    import shutil

    from pdrlearn.runtime.__main__ import main

    s = tmp_path / "A"
    shutil.copytree(walk / "A", s)
    meta = json.loads((s / "meta.json").read_text())
    meta["units"]["timestamp"] = "samples"
    (s / "meta.json").write_text(json.dumps(meta))
    assert main([str(SHIPPED), str(s)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: ") and "\n" not in err
    assert "units.timestamp" in err and "meta.json" in err and "pdrlearn run" in err


@pytest.mark.parametrize("method", ["dtw", "fusion"])
def test_numpy_alone_runs_the_non_onnx_methods_and_refuses_svm_in_one_line(tmp_path_factory, tmp_path, method):
    from tests.runtime_helpers import trained_dirs_and_walk

    d = trained_dirs_and_walk(tmp_path_factory)
    bundle, session = d["root"] / "bundle_all", d["walk"]
    from pdrlearn.cli import main

    assert main(["run", "--no-plot", str(bundle), str(session), "--method", method, "--out",
                 str(tmp_path / "full")]) == 0
    env = lean_env(tmp_path, (*ABSENT, "onnxruntime"))  # numpy alone
    r = subprocess.run([sys.executable, "-m", "pdrlearn.runtime", str(bundle), str(session), "--method", method,
                        "--out", str(tmp_path / "lean")], capture_output=True, text=True, timeout=300, env=env)
    assert r.returncode == 0, r.stderr[-2000:]
    full, lean = pd.read_csv(tmp_path / "full" / "steps.csv"), pd.read_csv(tmp_path / "lean" / "steps.csv")
    assert len(lean) == len(full) >= 10
    for c in ("end_s", "length_m", "x", "y", "z", "p_terrain_up"):
        np.testing.assert_allclose(lean[c], full[c], rtol=0, atol=1e-9, err_msg=c)
    assert lean["terrain"].tolist() == full["terrain"].tolist()
    r = subprocess.run([sys.executable, "-m", "pdrlearn.runtime", str(bundle), str(session), "--method", "svm/foot"],
                       capture_output=True, text=True, timeout=300, env=env)
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr[-2000:]
    assert r.stderr.startswith("error: ") and "pip install onnxruntime" in r.stderr


def test_a_top_level_name_needing_the_full_install_is_one_line_naming_the_lean_reader_b354(tmp_path):
    r = subprocess.run([sys.executable, "-c", "from pdrlearn import read_session"], capture_output=True, text=True,
                       timeout=120, env=lean_env(tmp_path), cwd=tmp_path)
    assert r.returncode == 1
    last = r.stderr.strip().splitlines()[-1]
    assert last.startswith("ModuleNotFoundError: pdrlearn.read_session needs pandas"), r.stderr
    assert "python -m pdrlearn.runtime BUNDLE SESSION" in last and "pdrlearn.runtime.replay.read_streams" in last
    assert "pandas/" not in r.stderr and "During handling" not in r.stderr  # no chained traceback of the import
    r = subprocess.run([sys.executable, "-c", "import pdrlearn, pdrlearn.runtime.replay; pdrlearn.io"],
                       capture_output=True, text=True, timeout=120, env=lean_env(tmp_path), cwd=tmp_path)
    assert "ModuleNotFoundError: pdrlearn.io needs pandas" in r.stderr  # a subpackage as attribute likewise


def test_the_install_advice_names_the_wheel_or_clone_not_pypi_e185(tmp_path):
    r = subprocess.run([sys.executable, "-m", "pdrlearn", "--version"], capture_output=True, text=True,
                       timeout=120, env=lean_env(tmp_path), cwd=tmp_path)
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert "pip install PATH/pdrlearn-*.whl" in r.stderr and "not on PyPI" in r.stderr
    assert "pip install pdrlearn" not in r.stderr
