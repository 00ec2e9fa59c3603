"""Decision E217: ``pdrlearn export --float32`` writes a float32-only bundle whose outputs match the float64 one."""

from __future__ import annotations

import json

import numpy as np
import onnx
import pytest
from onnx import TensorProto

from pdrlearn.cli import main
from pdrlearn.export.parity import parity_windows
from pdrlearn.runtime import load_bundle
from pdrlearn.runtime.classify import StepGraph, TaskClassifier
from tests.runtime_helpers import ALL_METHODS, trained_dirs_and_walk


@pytest.fixture(scope="module")
def dirs(tmp_path_factory):
    return trained_dirs_and_walk(tmp_path_factory, "f32")


def _doubles(model: onnx.ModelProto) -> list[str]:
    g = model.graph
    out = [t.name for t in g.initializer if t.data_type == TensorProto.DOUBLE]
    out += [v.name for v in (*g.input, *g.output) if v.type.tensor_type.elem_type == TensorProto.DOUBLE]
    out += [n.name for n in g.node for a in n.attribute
            if (n.op_type == "Cast" and a.name == "to" and a.i == TensorProto.DOUBLE)
            or (a.type == onnx.AttributeProto.TENSOR and a.t.data_type == TensorProto.DOUBLE)]
    return out


def _probas(bundle, W):
    """The step graph's task probabilities and every model entry's, on windows ``W``."""
    from pdrlearn.runtime.classify import RuntimeModel

    ctx = {"signals": bundle.manifest["features"]["signals"],
           "channel_index": {c: i for i, c in enumerate(bundle.manifest["features"]["channels"])}}
    clfs = {t: TaskClassifier(bundle, t, ctx) for t in bundle.tasks}
    per_model = {(t, m, u): RuntimeModel(bundle, e, ctx).proba(W.copy()) for t, s in bundle.tasks.items()
                 for m, per in s["methods"].items() for u, e in per.items()}
    return StepGraph.open(bundle, clfs).predict(np.ascontiguousarray(W)), per_model


def test_float32_bundle_has_no_double_and_matches_the_float64_bundle(dirs, tmp_path, capsys):
    model = dirs["root"] / "model"
    assert main(["export", str(model), "--out", str(tmp_path / "b64"), "--methods", ",".join(ALL_METHODS),
                 "--json"]) == 0
    big = json.loads(capsys.readouterr().out)
    assert main(["export", str(model), "--out", str(tmp_path / "b32"), "--methods", ",".join(ALL_METHODS),
                 "--float32", "--json"]) == 0
    small = json.loads(capsys.readouterr().out)
    assert not [f for f in small["files"] if f.endswith(".f32.onnx")]
    assert [f for f in big["files"] if f.endswith(".f32.onnx")]  # the float64 bundle keeps its twins
    assert small["size_bytes"] < 0.7 * big["size_bytes"]  # DTW references (npz) and the manifest stay
    for f in small["files"]:
        if f.endswith(".onnx"):
            assert _doubles(onnx.load(str(tmp_path / "b32" / f))) == [], f
    b64, b32 = load_bundle(tmp_path / "b64"), load_bundle(tmp_path / "b32")
    assert b32.manifest["export"]["precision"] == "float32" and b32.manifest["step_graph"]["dtype"] == "float32"
    assert "precision" not in b64.manifest["export"]  # an old-style (float64) bundle still loads and runs
    W = parity_windows(int(b64.manifest["features"]["n_samples"]), "given")
    g64, m64 = _probas(b64, W)
    g32, m32 = _probas(b32, W)
    for task, p in g64.items():  # outputs compared, not only loaded
        q = np.asarray(g32[task], dtype=float)
        assert np.abs(q - p).max() < 1e-3 and np.abs(q - p).max() > 0  # float32 rounding, not the same graph
        assert (q.argmax(1) == np.asarray(p).argmax(1)).all()
    for k, p in m64.items():
        assert np.abs(m32[k] - p).max() < 1e-3, k


def test_float32_bundle_runs_a_walk_like_the_float64_one(dirs, tmp_path):
    model = dirs["root"] / "model"
    for name, extra in (("b64", []), ("b32", ["--float32"])):
        assert main(["export", str(model), "--out", str(tmp_path / name), *extra]) == 0
        assert main(["run", "--no-plot", str(tmp_path / name), str(dirs["walk"]), "--out",
                     str(tmp_path / f"run_{name}"),
                     "--json"]) == 0
    a = (tmp_path / "run_b64" / "steps.csv").read_text().splitlines()
    b = (tmp_path / "run_b32" / "steps.csv").read_text().splitlines()
    assert len(a) == len(b) > 10


def test_float32_is_refused_for_a_waist_calibration(tmp_path, capsys):
    p = tmp_path / "p.json"
    p.write_text(json.dumps({"pipeline": "waist-pca"}))
    rc = main(["export", str(p), "--out", str(tmp_path / "w"), "--float32"])
    err = capsys.readouterr().err
    assert rc == 2 and "Traceback" not in err
    assert "has no classifiers; drop --methods / --length-bounds / --float32" in err
    assert not (tmp_path / "w").exists()
