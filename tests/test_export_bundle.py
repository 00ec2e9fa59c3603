"""Generic bundle infrastructure: ONNX conversion parity, atomic writing, verification errors."""

from __future__ import annotations

import json

import numpy as np
import onnx
import pytest
from sklearn.multiclass import OneVsRestClassifier
from sklearn.pipeline import make_pipeline
from sklearn.preprocessing import StandardScaler
from sklearn.svm import SVC

from pdrlearn.errors import DataError, MissingSensorError, ModelError
from pdrlearn.export import base_manifest, check_parity, sklearn_to_onnx, torch_to_onnx, write_bundle
from pdrlearn.runtime import load_bundle

CLASSES = np.array(["flat", "up", "down"])


def _data(n=240, d=17, seed=0):
    rng = np.random.default_rng(seed)
    y = CLASSES[rng.integers(0, 3, n)]
    X = rng.normal(size=(n, d)) * np.r_[np.full(6, 10.0), np.ones(d - 6)]
    X[y == "up", 0] += 12
    X[y == "down", 7] -= 2
    return X, y


@pytest.mark.parametrize(
    "clf",
    [
        OneVsRestClassifier(SVC(kernel="poly", degree=3, probability=True, random_state=0)),  # thesis terrain
        SVC(kernel="linear", probability=True, random_state=0),  # thesis direction
        OneVsRestClassifier(SVC(kernel="rbf")),  # no probabilities: decision scores only
    ],
    ids=["ovr-poly-proba", "svc-linear-proba", "ovr-rbf-scores"],
)
def test_sklearn_pipeline_onnx_matches_predict_and_proba(clf):
    X, y = _data()
    est = make_pipeline(StandardScaler(), clf).fit(X[:160], y[:160])
    model, spec = sklearn_to_onnx(est, X.shape[1], name="svm")
    onnx.checker.check_model(model, full_check=True)
    assert spec["classes"] == [str(c) for c in est.classes_]
    has_proba = (clf.estimator if hasattr(clf, "estimator") else clf).probability is True
    res = check_parity(model, spec, est.predict, est.predict_proba if has_proba else None, X[160:])
    assert res["label_agreement"] == 1.0
    assert ("proba" in spec["outputs"]) == bool(has_proba)
    if has_proba:
        assert res["proba_max_abs_diff"] <= 1e-5


def test_torch_network_onnx_matches_with_dynamic_batch():
    torch = pytest.importorskip("torch")
    torch.manual_seed(0)
    net = torch.nn.Sequential(torch.nn.Linear(72, 144), torch.nn.Sigmoid(), torch.nn.Linear(144, 3))
    model, spec = torch_to_onnx(net, 72, classes=list(CLASSES))
    assert any(o.version >= 17 for o in model.opset_import if o.domain in ("", "ai.onnx"))
    X = np.random.default_rng(1).normal(size=(7, 72)).astype(np.float32)
    with torch.no_grad():
        logits = net(torch.from_numpy(X)).numpy()
    proba = np.exp(logits) / np.exp(logits).sum(1, keepdims=True)
    res = check_parity(model, spec, lambda Z: CLASSES[np.argmax(logits, 1)], lambda Z: proba, X)
    assert res["proba_max_abs_diff"] <= 1e-5


def _small_bundle(tmp_path, **kw):
    X, y = _data()
    est = make_pipeline(StandardScaler(), SVC(kernel="linear", probability=True, random_state=0)).fit(X, y)
    model, spec = sklearn_to_onnx(est, X.shape[1])
    man = base_manifest(
        user="u1",
        tasks={
            "terrain": {
                "classes": list(est.classes_),
                "models": {"svm": {"file": "models/terrain_svm_foot.onnx", **spec}},
            }
        },
        sampling={"rate_hz": 20.0},
        sensors={"required": ["fAccelerometer", "fGyroscope"], "optional": []},
    )
    out = write_bundle(
        tmp_path / "b",
        man,
        onnx_models={"models/terrain_svm_foot.onnx": model},
        json_files={"params/heuristic.json": {"a": 1.5}},
        npz_files={"params/dtw.npz": {"refs": np.ones((3, 40, 2)), "labels": np.arange(3)}},
        **kw,
    )
    return out, est, X


def test_write_and_load_round_trip(tmp_path):
    out, est, X = _small_bundle(tmp_path)
    b = load_bundle(out)
    assert b.manifest["schema_version"] == 1 and set(b.manifest["files"]) == {
        "models/terrain_svm_foot.onnx",
        "params/heuristic.json",
        "params/dtw.npz",
    }
    spec = b.tasks["terrain"]["models"]["svm"]
    r = b.model(spec["file"], spec).run(X[:5])
    np.testing.assert_array_equal(r["label"].astype(str), est.predict(X[:5]))
    np.testing.assert_allclose(r["proba"], est.predict_proba(X[:5]), atol=1e-5)
    assert b.json("params/heuristic.json") == {"a": 1.5}
    assert b.npz("params/dtw.npz")["refs"].shape == (3, 40, 2)
    # no temporary folders left beside the bundle
    assert [p.name for p in tmp_path.iterdir()] == ["b"]


def test_write_refuses_existing_and_cleans_up_on_failure(tmp_path):
    out, _, _ = _small_bundle(tmp_path)
    with pytest.raises(ModelError, match="not empty"):
        _small_bundle(tmp_path)
    with pytest.raises(ModelError, match="object dtype"):
        write_bundle(tmp_path / "c", base_manifest(), npz_files={"x.npz": {"a": np.array([{}, 1])}})
    assert sorted(p.name for p in tmp_path.iterdir()) == ["b"]
    _small_bundle(tmp_path, overwrite=True)  # replacing works
    assert load_bundle(out).manifest["user"] == "u1"


def test_missing_file_is_a_model_error(tmp_path):
    out, _, _ = _small_bundle(tmp_path)
    (out / "params" / "dtw.npz").unlink()
    with pytest.raises(ModelError, match=r"'params/dtw.npz' .* missing"):
        load_bundle(out)


def test_altered_file_is_a_model_error(tmp_path):
    out, _, _ = _small_bundle(tmp_path)
    p = out / "params" / "heuristic.json"
    p.write_text(p.read_text().replace("1.5", "2.5"))
    with pytest.raises(ModelError, match="altered"):
        load_bundle(out)


def test_other_schema_version_is_a_model_error(tmp_path):
    out, _, _ = _small_bundle(tmp_path)
    m = json.loads((out / "manifest.json").read_text())
    m["schema_version"] = 2
    (out / "manifest.json").write_text(json.dumps(m))
    with pytest.raises(ModelError, match="schema version 2.*reads version 1"):
        load_bundle(out)


def test_not_a_bundle_messages(tmp_path):
    with pytest.raises(ModelError, match="not a folder"):
        load_bundle(tmp_path / "nope")
    (tmp_path / "e").mkdir()
    with pytest.raises(ModelError, match="no manifest.json"):
        load_bundle(tmp_path / "e")
    (tmp_path / "e" / "manifest.json").write_text("{")
    with pytest.raises(ModelError, match="not valid JSON"):
        load_bundle(tmp_path / "e")


def test_sensor_and_rate_mismatch_are_data_errors(tmp_path):
    out, _, _ = _small_bundle(tmp_path)
    b = load_bundle(out)
    b.check_streams({"fAccelerometer": 20.0, "fGyroscope": 20.1})  # within tolerance
    with pytest.raises(MissingSensorError, match="has no fGyroscope"):
        b.check_streams({"fAccelerometer": 20.0}, where="session s")
    with pytest.raises(DataError, match=r"sampled at 100 Hz .* trained at 20 Hz"):
        b.check_streams({"fAccelerometer": 100.0, "fGyroscope": 100.0})


def test_altered_or_unsigned_manifest_is_a_model_error(tmp_path):
    out, _, _ = _small_bundle(tmp_path)
    m = json.loads((out / "manifest.json").read_text())
    m["displacement"] = {"length_bounds_m": {"short": [0, 5]}}  # an edit that checksums of the files miss
    (out / "manifest.json").write_text(json.dumps(m))
    with pytest.raises(ModelError, match="manifest.json was altered"):
        load_bundle(out)
    (out / "manifest.sha256").unlink()
    with pytest.raises(ModelError, match="manifest.sha256 is missing"):
        load_bundle(out)
