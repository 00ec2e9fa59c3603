"""Trust and locked-down installs (trial T1, session 42; decisions E260-E263 in docs/decisions/export.md).

E260 a model folder is pickle: every argument that loads one says so, and ``PDRLEARN_NO_PICKLE=1`` refuses it before
any file is unpickled; E261 ``pdrlearn plot`` prints no matplotlib cache lines when the home cannot be written; E262
``pdrlearn run`` imports neither joblib nor scikit-learn, and joblib's serial-mode warning is silenced; E263 a bundle
file that resolves outside the bundle and an ONNX graph with external data are refused, and
``PDRLEARN_NO_ENTRY_POINTS=1`` turns the installed entry-point plug-ins off.
"""

from __future__ import annotations

import ast
import hashlib
import inspect
import json
import os
import pickle
import subprocess
import sys
from pathlib import Path

import pytest

from pdrlearn.errors import ModelError

ROOT = Path(__file__).resolve().parents[1]


# --- E260: model folders are pickle -----------------------------------------------------------------------------

class _Mkdir:
    """A pickle that makes a folder when loaded: what a tampered model file can do (trial T1 F2 made a file)."""

    def __init__(self, path: str):
        self.path = path

    def __reduce__(self):
        return (os.mkdir, (self.path,))


def _evil_model(folder: Path, marker: Path) -> Path:
    """A model folder that verify_model_dir accepts (checksums re-made) whose one model file runs code."""
    rel = "models/terrain__svm__foot.joblib"
    (folder / "models").mkdir(parents=True)
    (folder / rel).write_bytes(pickle.dumps(_Mkdir(str(marker))))
    manifest = {"schema_version": 1, "user": "u", "n_samples": 40, "files": {
        rel: hashlib.sha256((folder / rel).read_bytes()).hexdigest()},
        "tasks": {"terrain": {"classes": ["flat", "up", "down"], "models": {"svm": ["foot"]}, "chosen": None}}}
    (folder / "manifest.json").write_text(json.dumps(manifest))
    return folder


def test_no_pickle_refuses_a_model_folder_before_unpickling_it_e260(tmp_path, monkeypatch):
    from pdrlearn.classify.model_dir import load_model

    marker = tmp_path / "ran"
    evil = _evil_model(tmp_path / "evil", marker)
    monkeypatch.setenv("PDRLEARN_NO_PICKLE", "1")
    with pytest.raises(ModelError) as e:
        load_model(evil)
    msg = str(e.value)
    assert "\n" not in msg and str(evil) in msg and "PDRLEARN_NO_PICKLE=1" in msg and "bundle" in msg
    assert not marker.exists()
    monkeypatch.setenv("PDRLEARN_NO_PICKLE", "yes")  # neither 1 nor 0: refused too (fails closed), naming both
    with pytest.raises(ModelError, match=r"neither 1 .* nor 0"):
        load_model(evil)
    assert not marker.exists()
    monkeypatch.setenv("PDRLEARN_NO_PICKLE", "0")  # off: the folder is unpickled, and its code runs (the threat)
    try:
        load_model(evil)
    except ModelError:
        pass
    assert marker.is_dir()


def test_track_with_no_pickle_is_one_line_before_any_session_e260(tmp_path, monkeypatch, capsys):
    from pdrlearn.cli import main
    from pdrlearn.io import write_session
    from tests.runtime_helpers import synthetic_session

    write_session(synthetic_session(8, seed=7, name="walk"), tmp_path / "walk")
    marker = tmp_path / "ran"
    evil = _evil_model(tmp_path / "evil", marker)
    monkeypatch.setenv("PDRLEARN_NO_PICKLE", "1")
    rc = main(["track", str(tmp_path / "walk"), "--model", str(evil), "--out", str(tmp_path / "out"), "--no-plot"])
    err = capsys.readouterr().err
    assert rc == 2, err
    assert err.startswith("error: ") and err.count("\n") == 1 and "PDRLEARN_NO_PICKLE" in err, err
    assert not marker.exists() and not (tmp_path / "out").exists()


def test_every_argument_that_loads_a_model_folder_says_pickle_e260():
    from pdrlearn.cli import cohort, export, track, train
    from pdrlearn.cli.common import PICKLE_HELP

    for func, name in ((track.track, "model"), (cohort.track_all, "model"), (train.evaluate, "model_dir"),
                       (cohort.evaluate_all, "models_dir"), (export.export, "model_dir")):
        assert PICKLE_HELP in inspect.signature(func).parameters[name].default.help, func.__name__


# --- E261: plot with a home that cannot be written ----------------------------------------------------------------

def _unwritable_home_env(tmp_path: Path) -> dict:
    """B226's test environment: HOME inside a folder that cannot be written (root ignores the mode: /proc)."""
    env = {k: v for k, v in os.environ.items() if k not in ("MPLCONFIGDIR", "XDG_CONFIG_HOME", "XDG_CACHE_HOME")}
    (tmp_path / "missing").mkdir()
    (tmp_path / "missing").chmod(0o500)
    env.update(HOME=str(tmp_path / "missing" / "home"), PYTHONPATH=str(ROOT))
    if os.access(tmp_path / "missing", os.W_OK):
        env["HOME"] = "/proc/nonexistent-home"
    return env


def test_plot_prints_no_matplotlib_lines_when_the_home_cannot_be_written_e261(tmp_path):
    from pdrlearn.io import write_session
    from tests.runtime_helpers import synthetic_session

    write_session(synthetic_session(8, seed=7, name="walk"), tmp_path / "walk")
    env = _unwritable_home_env(tmp_path)
    r = subprocess.run([sys.executable, "-m", "pdrlearn", "plot", str(tmp_path / "walk"), "--out",
                        str(tmp_path / "p.png")], capture_output=True, text=True, env=env, timeout=300, cwd=tmp_path)
    (tmp_path / "missing").chmod(0o700)
    assert r.returncode == 0, r.stderr[-2000:]
    assert "matplotlib" not in r.stderr.lower(), r.stderr
    assert (tmp_path / "p.png").is_file()


def test_every_matplotlib_import_follows_ensure_config_dir_e261():
    """Static: in every function of pdrlearn that imports matplotlib, ``ensure_config_dir()`` is called on an
    earlier line of that function (E261: session_figure imported it before new_figure's call)."""
    bad = []
    for path in sorted((ROOT / "pdrlearn").rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for fn in ast.walk(tree):
            if not isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
                continue
            calls = [n.lineno for n in ast.walk(fn) if isinstance(n, ast.Call)
                     and getattr(n.func, "id", getattr(n.func, "attr", None)) == "ensure_config_dir"]
            for n in ast.walk(fn):
                names = ([a.name for a in n.names] if isinstance(n, ast.Import) else
                         [n.module or ""] if isinstance(n, ast.ImportFrom) else [])
                if any(m.split(".")[0] == "matplotlib" for m in names) and not any(c < n.lineno for c in calls):
                    if fn.name != "save_atomic":  # closes a figure made after ensure_config_dir, never the first
                        bad.append(f"{path.relative_to(ROOT)}:{n.lineno} {fn.name}")
    assert bad == []
