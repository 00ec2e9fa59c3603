"""What a bundle gives away and how it is read back: decisions E67 (no path of the user's machine),
E68 (``pdrlearn export --no-training-samples``), E69 (the step graph's input rows named in the manifest) and B125
(a bundle file whose checksum was re-made after an edit is one line, not a traceback)."""

from __future__ import annotations

import hashlib
import json
import logging
import shutil

import numpy as np
import pytest

from pdrlearn.cli import main
from tests.runtime_helpers import trained_dirs_and_walk

#: methods whose models hold training samples (DTW references, SVM support vectors; the ensemble has both)
SAMPLE_METHODS = ("dtw", "svm", "ensemble")


@pytest.fixture(scope="module")
def dirs(tmp_path_factory):
    return trained_dirs_and_walk(tmp_path_factory, "privacy")


def _manifest(bundle) -> dict:
    return json.loads((bundle / "manifest.json").read_text())


def test_source_model_dir_is_the_folder_name_only(dirs, tmp_path, capsys):
    """Decision E67: `pdrlearn export /home/alice/models/u1` recorded the path as typed."""
    model = (dirs["root"] / "model").resolve()
    assert main(["export", str(model), "--out", str(tmp_path / "b")]) == 0
    m = _manifest(tmp_path / "b")
    assert m["training"]["source_model_dir"] == "model"
    assert str(dirs["root"].resolve()) not in (tmp_path / "b" / "manifest.json").read_text()


def test_no_training_samples_drops_dtw_and_svm_and_chooses_as_training(dirs, tmp_path, capsys):
    """Decision E68: no DTW reference or SVM support vector in the bundle; each task's model is the one training
    would have chosen without them (best-ranked two-unit model, else best-ranked), its foot-only one likewise; the
    bundle tracks."""
    from pdrlearn.classify.model_dir import load_model

    out = tmp_path / "shared"
    assert main(["export", str(dirs["root"] / "model"), "--out", str(out), "--no-training-samples", "--json"]) == 0
    info = json.loads(capsys.readouterr().out)
    assert info["training_samples"] is False
    m = _manifest(out)
    assert not [f for f in m["files"] if f.endswith(".npz")]
    model = load_model(dirs["root"] / "model")
    replaced = 0
    for task, spec in m["tasks"].items():
        ranking = [p for p in model.tasks[task].ranking() if p[0] not in SAMPLE_METHODS]
        two = [p for p in ranking if p[1] in ("fused", "combined")]
        assert (spec["chosen"]["method"], spec["chosen"]["unit"]) == (two or ranking)[0]
        foot = next(p for p in ranking if p[1] == "foot")
        assert spec["foot_only"] == {"method": foot[0], "unit": "foot"}
        assert not set(spec["methods"]) & set(SAMPLE_METHODS)
        replaced += model.tasks[task].chosen[0] in SAMPLE_METHODS
        chosen = "/".join(model.tasks[task].chosen)
        assert (f"{task} {chosen}" in m["export"]["dropped"]) == (model.tasks[task].chosen[0] in SAMPLE_METHODS)
    assert replaced >= 1  # the fixture's model chooses an SVM somewhere, so the rule was exercised
    for rel in m["files"]:  # no SVM graph (its support vectors are an initializer named svT)
        if rel.endswith(".onnx"):
            import onnx

            assert "svT" not in {i.name for i in onnx.load(str(out / rel)).graph.initializer}, rel
    assert m["export"]["training_samples"] is False
    assert main(["run", "--no-plot", str(out), str(dirs["walk"]), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["n_steps"] >= 18


def test_no_training_samples_with_methods_keeps_the_others(dirs, tmp_path, capsys, caplog):
    """E68 amended (review): the manifest records what was left out, and one warning per requested method."""
    with caplog.at_level(logging.WARNING):
        assert main(["export", str(dirs["root"] / "model"), "--out", str(tmp_path / "b"), "--methods",
                     "svm,nn,dtw", "--no-training-samples"]) == 0
    m = _manifest(tmp_path / "b")
    assert {meth for t in m["tasks"].values() for meth in t["methods"]} == {"nn"}
    from pdrlearn.classify.model_dir import load_model

    model = load_model(dirs["root"] / "model")
    want = {f"{t} {meth}/{u}" for t, tm in model.tasks.items() for meth in ("svm", "dtw") for u in tm.models[meth]}
    assert set(m["export"]["dropped"]) == want
    lines = [r.getMessage() for r in caplog.records if "--no-training-samples:" in r.getMessage()]
    assert len(lines) == 2 and "--methods svm left out" in lines[0] and "--methods dtw left out" in lines[1], lines


def test_no_training_samples_refuses_a_task_left_without_a_model(dirs, tmp_path, capsys):
    """The foot model of the fixture has SVM and DTW models only: one line, nothing written."""
    out = tmp_path / "b"
    assert main(["export", str(dirs["root"] / "model_foot"), "--out", str(out), "--no-training-samples"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--no-training-samples leaves task" in err[0] and "without a model" in err[0], err
    assert not out.exists()


def _resign(bundle, rel: str) -> None:
    """Re-make the checksums after an edit, as an attacker (or a careless tool) would."""
    m = _manifest(bundle)
    m["files"][rel] = hashlib.sha256((bundle / rel).read_bytes()).hexdigest()
    (bundle / "manifest.json").write_text(json.dumps(m))
    digest = hashlib.sha256((bundle / "manifest.json").read_bytes()).hexdigest()
    (bundle / "manifest.sha256").write_text(f"{digest}  manifest.json\n")


@pytest.mark.parametrize("kind", ["object_array", "not_a_zip", "missing_array", "json_list", "json_no_keys",
                                  "json_garbage"])
def test_resigned_npz_is_one_line(dirs, tmp_path, capsys, kind):
    """Decision B125: an NPZ with an object array (which only pickle loads), a file that is not an archive, or one
    without the DTW arrays, and a heuristic's JSON that is not JSON, not an object or without its keys (amended,
    review): `pdrlearn run` prints one line naming the file instead of a traceback."""
    bundle = tmp_path / "b"
    shutil.copytree(dirs["root"] / "bundle_all", bundle)
    method = "heuristic" if kind.startswith("json") else "dtw"
    rel = next(f for f in _manifest(bundle)["files"] if f"terrain_{method}_foot." in f)
    if kind.startswith("json"):
        (bundle / rel).write_text({"json_list": "[1, 2]", "json_no_keys": '{"x": 1}', "json_garbage": "{not"}[kind])
    elif kind == "object_array":
        with open(bundle / rel, "wb") as f:
            np.savez(f, references=np.array([{"a": 1}], dtype=object), reference_labels=np.zeros(1),
                     channel_mean=np.zeros(3), channel_std=np.ones(3))
    elif kind == "not_a_zip":
        (bundle / rel).write_bytes(b"PK\x03\x04 truncated")
    else:
        with open(bundle / rel, "wb") as f:
            np.savez(f, references=np.zeros((2, 3, 40)))
    _resign(bundle, rel)
    assert main(["run", str(bundle), str(dirs["walk"]), "--method", f"terrain={method}/foot"]) == 2
    # `run` checks the session's frames as track does (D10/D11, D23): the synthetic walk's D11 warning is not the error
    err = [ln for ln in capsys.readouterr().err.strip().splitlines() if not ln.startswith("warning:")]
    assert len(err) == 1 and f"file '{rel}' is not" in err[0] and "re-export" in err[0], err


def test_resigned_onnx_garbage_is_one_line(dirs, tmp_path, capsys):
    bundle = tmp_path / "b"
    shutil.copytree(dirs["root"] / "bundle_all", bundle)
    rel = next(f for f in _manifest(bundle)["files"] if f.endswith("terrain_nn_foot.onnx"))
    (bundle / rel).write_bytes(b"not a protobuf")
    _resign(bundle, rel)
    assert main(["run", str(bundle), str(dirs["walk"]), "--method", "terrain=nn/foot"]) == 2
    # `run` checks the session's frames as track does (D10/D11, D23): the synthetic walk's D11 warning is not the error
    err = [ln for ln in capsys.readouterr().err.strip().splitlines() if not ln.startswith("warning:")]
    # decision E263: the bundle's verification reads each graph's tensors, so garbage is refused there, before
    # onnxruntime (which said "onnxruntime cannot open this model" before E263)
    assert len(err) == 1 and f"file '{rel}' is not an ONNX graph" in err[0] and "B125" in err[0], err


def test_step_graph_names_its_input_rows(dirs):
    """Decision E69: ``step_graph.input_channels`` is the row order of W (= ``features.channels``), ``channels`` the
    rows the graph reads; rows it does not read may be NaN."""
    import onnxruntime as ort

    bundle = dirs["root"] / "bundle"
    m = _manifest(bundle)
    sg = m["step_graph"]
    assert sg["input_channels"] == m["features"]["channels"]
    assert set(sg["channels"]) < set(sg["input_channels"])
    sess = ort.InferenceSession(str(bundle / sg["file"]), providers=["CPUExecutionProvider"])
    (inp,) = sess.get_inputs()
    assert inp.name == sg["input"] and inp.shape[1:] == [len(sg["input_channels"]), m["features"]["n_samples"]]
    rng = np.random.default_rng(3)
    W = rng.normal(size=(4, len(sg["input_channels"]), m["features"]["n_samples"]))
    W[:, 0] = np.linspace(0.0, 1.1, W.shape[2])  # t_s
    unread = [i for i, c in enumerate(sg["input_channels"]) if c not in sg["channels"]]
    W2 = W.copy()
    W2[:, unread] = np.nan
    a, b = sess.run(None, {"W": W}), sess.run(None, {"W": W2})
    for x, y in zip(a, b, strict=True):
        assert np.isfinite(x).all() and np.array_equal(x, y)
    names = [o.name for o in sess.get_outputs()]
    assert names == [sg["outputs"][t] for t in sg["outputs"]]
    assert a[0].shape[1] == len(m["tasks"][next(iter(sg["outputs"]))]["classes"])
