"""Decisions E269 and E270 (session 43, implementer I3; docs/decisions/export.md).

E269: a model folder (what ``train`` writes, ``track --model`` / ``evaluate`` load) refuses a listed file that leads
outside it (a symbolic link, an absolute or ``..`` entry), by E263's one check (``pdrlearn.listed_files``).
E270: ``load_bundle(..., verify=False)`` skips only the checksums; E263's link and ONNX external-data checks run.
"""

from __future__ import annotations

import hashlib
import json
import os
import pickle
import shutil
from pathlib import Path

import pytest

from pdrlearn.errors import ModelError

ROOT = Path(__file__).resolve().parents[1]
REL = "models/terrain__svm__foot.joblib"


class _Mkdir:
    """A pickle that makes a folder when loaded: what a file linked in from elsewhere can do."""

    def __init__(self, path: str):
        self.path = path

    def __reduce__(self):
        return (os.mkdir, (self.path,))


def _model_folder(folder: Path, payload: bytes, rel: str = REL) -> Path:
    """A model folder whose manifest lists ``rel`` with ``payload``'s checksum (the file itself is the caller's)."""
    (folder / "models").mkdir(parents=True)
    manifest = {"schema_version": 1, "user": "u", "n_samples": 40,
                "files": {rel: hashlib.sha256(payload).hexdigest()},
                "tasks": {"terrain": {"classes": ["flat", "up", "down"], "models": {"svm": ["foot"]},
                                      "chosen": None}}}
    (folder / "manifest.json").write_text(json.dumps(manifest))
    return folder


def test_a_model_file_linked_outside_is_refused_before_it_is_unpickled_e269(tmp_path):
    from pdrlearn.classify.model_dir import load_model

    marker = tmp_path / "ran"
    payload = pickle.dumps(_Mkdir(str(marker)))
    (tmp_path / "elsewhere.joblib").write_bytes(payload)
    m = _model_folder(tmp_path / "m", payload)
    (m / REL).symlink_to(tmp_path / "elsewhere.joblib")  # the same bytes: the checksum matches
    with pytest.raises(ModelError) as e:
        load_model(m)
    msg = str(e.value)
    assert "\n" not in msg and msg.startswith(f"{m}: model file '{REL}' is a symbolic link"), msg
    assert "outside the model; copy the whole model folder with its files (cp -rL), not links" in msg
    assert not marker.exists()
    m2 = _model_folder(tmp_path / "m2", payload)  # the whole models/ folder linked out
    (m2 / "models").rmdir()
    (m2 / "models").symlink_to(tmp_path / "m" / "models", target_is_directory=True)
    with pytest.raises(ModelError, match=r"inside a linked folder"):
        load_model(m2)
    assert not marker.exists()


def test_a_model_entry_that_climbs_out_is_refused_e269(tmp_path):
    from pdrlearn.classify.model_dir import verify_model_dir

    payload = b"x"
    (tmp_path / "abs.joblib").write_bytes(payload)
    for rel in (str(tmp_path / "abs.joblib"), "../abs.joblib"):
        m = _model_folder(tmp_path / f"m{len(rel)}", payload, rel=rel)
        with pytest.raises(ModelError, match=r"points outside the model folder; retrain the model"):
            verify_model_dir(m)


def test_a_link_inside_the_model_folder_is_its_own_e269(tmp_path):
    from pdrlearn.classify.model_dir import verify_model_dir

    m = _model_folder(tmp_path / "m", b"x")
    (m / "models" / "kept.bin").write_bytes(b"x")
    (m / REL).symlink_to("kept.bin")
    assert verify_model_dir(m)["files"] == {REL: hashlib.sha256(b"x").hexdigest()}


def test_track_with_a_linked_model_file_is_one_line_e269(tmp_path, capsys):
    from pdrlearn.cli import main

    payload = b"x"
    (tmp_path / "elsewhere.joblib").write_bytes(payload)
    m = _model_folder(tmp_path / "m", payload)
    (m / REL).symlink_to(tmp_path / "elsewhere.joblib")
    (tmp_path / "walk").mkdir()  # B128: --model is checked before any session is read
    rc = main(["track", str(tmp_path / "walk"), "--model", str(m), "--out", str(tmp_path / "out"), "--no-plot"])
    err = capsys.readouterr().err
    assert rc == 2 and err.startswith("error: ") and err.count("\n") == 1 and "cp -rL" in err, err
    assert not (tmp_path / "out").exists()


# --- E270: verify=False skips the checksums only ----------------------------------------------------------------

def _shipped_copy(to: Path) -> Path:
    return Path(shutil.copytree(ROOT / "models" / "plasys-sim-default", to))


def test_verify_false_still_refuses_a_file_linked_outside_e270(tmp_path):
    from pdrlearn.runtime.bundle import load_bundle

    rel = "models/step.onnx"
    b = _shipped_copy(tmp_path / "b")
    (b / rel).rename(tmp_path / "step.onnx")
    (b / rel).symlink_to(tmp_path / "step.onnx")
    for verify in (True, False):
        with pytest.raises(ModelError, match=r"file 'models/step\.onnx' is a symbolic link .* outside the bundle"):
            load_bundle(b, verify=verify)


def test_verify_false_still_refuses_onnx_external_data_e270(tmp_path):
    import numpy as np
    from onnx import TensorProto, helper, numpy_helper
    from onnx.external_data_helper import convert_model_to_external_data

    from pdrlearn.runtime.bundle import load_bundle

    b = _shipped_copy(tmp_path / "b")
    w = numpy_helper.from_array(np.arange(3.0), name="w")
    graph = helper.make_graph([helper.make_node("Identity", ["w"], ["y"])], "g", [],
                              [helper.make_tensor_value_info("y", TensorProto.DOUBLE, [3])], [w])
    model = helper.make_model(graph)
    convert_model_to_external_data(model, location="x.bin", size_threshold=0)
    (b / "models" / "x.bin").write_bytes(np.arange(3.0).tobytes())
    (b / "models" / "x.onnx").write_bytes(model.SerializeToString())
    m = json.loads((b / "manifest.json").read_text())
    m["files"]["models/x.onnx"] = "0" * 64  # no checksum re-made: verify=False does not read it
    (b / "manifest.json").write_text(json.dumps(m))
    with pytest.raises(ModelError, match=r"'models/x\.onnx' keeps the data of tensor 'w' in an external file"):
        load_bundle(b, verify=False)


def test_verify_false_still_skips_the_checksums_e270(tmp_path):
    from pdrlearn.runtime.bundle import load_bundle

    b = _shipped_copy(tmp_path / "b")
    (b / "manifest.sha256").unlink()
    with pytest.raises(ModelError, match="manifest.sha256 is missing"):
        load_bundle(b)
    assert load_bundle(b, verify=False).path == b


def test_verify_false_waist_bundle_refuses_a_linked_file_too_e270(tmp_path):
    from pdrlearn.runtime.bundle import verify_files

    b = _shipped_copy(tmp_path / "b")  # verify_files is the waist loader's check too (load_waist_bundle)
    rel = "models/length_svm_foot.onnx"
    (b / rel).rename(tmp_path / "l.onnx")
    (b / rel).symlink_to(tmp_path / "l.onnx")
    with pytest.raises(ModelError, match="outside the bundle"):
        verify_files(b, json.loads((b / "manifest.json").read_text()), checksums=False)
