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
    with pytest.raises(ModelError, match=r"PDRLEARN_NO_PICKLE='yes' \(neither 1 nor 0: taken as 1\) refuses"):
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
        text = path.read_text(encoding="utf-8")
        if "matplotlib" not in text:  # no import can name it (session 46: parsing every module took 3 of 4 s)
            continue
        tree = ast.parse(text)
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


# --- E262 / E263: a tiny heuristic bundle (numpy only) and a walk -------------------------------------------------

@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    """A foot-only heuristic model (30 synthetic steps, CV 2), its bundle, and an 8-step walk."""
    from pdrlearn.classify import train_user
    from pdrlearn.export.from_model import export_model
    from pdrlearn.io import write_session
    from tests.runtime_helpers import synthetic_session

    root = tmp_path_factory.mktemp("e262")
    train_user([synthetic_session(30, seed=0)], cv=2, seed=0, units=["foot"], methods=["heuristic"]).save(
        root / "model")
    export_model(root / "model", root / "bundle")
    write_session(synthetic_session(8, seed=7, name="walk"), root / "walk")
    return root


_LOADED = ("import sys, json\nfrom pdrlearn.cli import main\nrc = main(sys.argv[1:])\n"
           "heavy = ('joblib', 'sklearn', 'torch')\n"
           "print(json.dumps({'rc': rc, 'loaded': sorted(m for m in heavy if m in sys.modules)}))")


def test_run_imports_neither_joblib_nor_sklearn_e262(tiny, tmp_path):
    r = subprocess.run([sys.executable, "-c", _LOADED, "run", str(tiny / "bundle"), str(tiny / "walk"), "--out",
                        str(tmp_path / "r"), "--no-plot"], capture_output=True, text=True, timeout=300,
                       env={**os.environ, "PYTHONPATH": str(ROOT)})
    out = json.loads(r.stdout.strip().splitlines()[-1])
    assert out == {"rc": 0, "loaded": []}, r.stderr[-2000:]


_NO_SEMAPHORE = ("import _multiprocessing\n"
                 "class _ReadOnlyShm:\n"
                 "    def __init__(self, *a, **k):\n"
                 "        raise OSError(30, 'Read-only file system')\n"
                 "_multiprocessing.SemLock = _ReadOnlyShm  # what a read-only /dev/shm gives joblib\n")


def test_joblib_serial_mode_warning_is_not_printed_e262(tiny, tmp_path):
    code = _NO_SEMAPHORE + _LOADED
    r = subprocess.run([sys.executable, "-c", code, "track", str(tiny / "walk"), "--out", str(tmp_path / "t"),
                        "--no-plot"], capture_output=True, text=True, timeout=300,
                       env={**os.environ, "PYTHONPATH": str(ROOT)})
    out = json.loads(r.stdout.strip().splitlines()[-1])
    assert out["rc"] == 0 and "joblib" in out["loaded"], r.stderr[-2000:]  # track imported joblib (scikit-learn)
    assert "serial mode" not in r.stderr and "site-packages" not in r.stderr, r.stderr


def _copy(bundle: Path, to: Path) -> Path:
    import shutil

    shutil.copytree(bundle, to)
    return to


def _relist(bundle: Path, rel: str) -> None:
    """List ``rel`` in the manifest with its sha256 and re-make manifest.sha256 (what a tamperer can do)."""
    from pdrlearn.runtime.bundle import sha256_file

    m = json.loads((bundle / "manifest.json").read_text())
    m["files"][rel] = sha256_file(bundle / rel)
    (bundle / "manifest.json").write_text(json.dumps(m))
    (bundle / "manifest.sha256").write_text(sha256_file(bundle / "manifest.json") + "\n")


def test_bundle_files_that_resolve_outside_are_refused_e263(tiny, tmp_path):
    from pdrlearn.runtime.bundle import load_bundle

    rel = "params/terrain_heuristic_foot.json"
    b = _copy(tiny / "bundle", tmp_path / "b")
    (tmp_path / "elsewhere").mkdir()
    (b / rel).rename(tmp_path / "elsewhere" / "t.json")
    (b / rel).symlink_to(tmp_path / "elsewhere" / "t.json")  # the same bytes: the checksum matches
    with pytest.raises(ModelError, match=r"file 'params/terrain_heuristic_foot\.json' is a symbolic link .* outside"):
        load_bundle(b)
    b2 = _copy(tiny / "bundle", tmp_path / "b2")  # the whole folder linked
    (b2 / "params").rename(tmp_path / "params_outside")
    (b2 / "params").symlink_to(tmp_path / "params_outside", target_is_directory=True)
    with pytest.raises(ModelError, match=r"inside a linked folder"):
        load_bundle(b2)
    b3 = _copy(tiny / "bundle", tmp_path / "b3")  # a link that stays inside the bundle is a file of it
    (b3 / "params" / "kept.json").write_bytes((b3 / rel).read_bytes())
    (b3 / rel).unlink()
    (b3 / rel).symlink_to("kept.json")
    assert load_bundle(b3).path == b3


def _tiny_onnx(external: Path | None):
    """An Identity graph whose one initializer holds 3 numbers, saved whole or with its data in ``external``."""
    import numpy as np
    from onnx import TensorProto, helper, numpy_helper

    w = numpy_helper.from_array(np.arange(3.0), name="w")
    graph = helper.make_graph([helper.make_node("Identity", ["w"], ["y"])], "g", [],
                              [helper.make_tensor_value_info("y", TensorProto.DOUBLE, [3])], [w])
    model = helper.make_model(graph)
    if external is not None:
        from onnx.external_data_helper import convert_model_to_external_data

        convert_model_to_external_data(model, location=external.name, size_threshold=0)
        external.write_bytes(np.arange(3.0).tobytes())
    return model.SerializeToString()


def test_onnx_external_data_is_refused_when_the_bundle_is_verified_e263(tiny, tmp_path):
    from pdrlearn.runtime.bundle import load_bundle
    from pdrlearn.runtime.onnx_scan import external_tensor

    assert external_tensor(_tiny_onnx(None)) is None
    b = _copy(tiny / "bundle", tmp_path / "b")
    (b / "models").mkdir()
    (b / "models" / "x.onnx").write_bytes(_tiny_onnx(b / "models" / "x.bin"))  # the data beside it, not listed
    _relist(b, "models/x.onnx")
    with pytest.raises(ModelError, match=r"'models/x\.onnx' keeps the data of tensor 'w' in an external file"):
        load_bundle(b)
    (b / "models" / "x.onnx").write_bytes(b"\x0b not protobuf")  # a group tag: not a graph the walker reads
    _relist(b, "models/x.onnx")
    with pytest.raises(ModelError, match=r"'models/x\.onnx' is not an ONNX graph"):
        load_bundle(b)


def test_the_shipped_bundle_graphs_keep_their_data_e263():
    from pdrlearn.runtime.bundle import load_bundle
    from pdrlearn.runtime.onnx_scan import external_tensor

    shipped = ROOT / "models" / "plasys-sim-default"
    graphs = sorted(shipped.rglob("*.onnx"))
    assert graphs and all(external_tensor(g.read_bytes()) is None for g in graphs)
    load_bundle(shipped)


class _EntryPoint:
    def __init__(self, name: str, loads: list):
        self.name, self.value, self._loads = name, "evilpkg:detector", loads

    def load(self):
        self._loads.append(self.name)
        return object


def test_no_entry_points_loads_no_installed_plug_in_e263(monkeypatch):
    import importlib.metadata

    from pdrlearn.plugins import Registry

    loads: list = []
    monkeypatch.setattr(importlib.metadata, "entry_points", lambda group: [_EntryPoint("evil", loads)])
    monkeypatch.setenv("PDRLEARN_NO_ENTRY_POINTS", "1")
    assert list(Registry("thing", "pdrlearn.things")) == [] and loads == []
    monkeypatch.setenv("PDRLEARN_NO_ENTRY_POINTS", "0")
    assert list(Registry("thing", "pdrlearn.things")) == ["evil"] and loads == ["evil"]


def test_plugin_help_says_it_runs_code_e263():
    from pdrlearn.cli import _root

    text = " ".join(inspect.signature(_root).parameters["plugin"].default.help.split())
    assert "Python code run with your rights" in text and "PDRLEARN_NO_ENTRY_POINTS=1" in text
