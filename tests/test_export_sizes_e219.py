"""Decision E219: export prints and records each file's size, and each ONNX graph's parameters and
multiply-accumulates per step."""

from __future__ import annotations

import json

import numpy as np
import pytest
from onnx import TensorProto, helper, numpy_helper

from pdrlearn.cli import main
from pdrlearn.export.sizes import onnx_stats
from pdrlearn.runtime import load_bundle
from tests.runtime_helpers import trained_dirs_and_walk


@pytest.fixture(scope="module")
def dirs(tmp_path_factory):
    return trained_dirs_and_walk(tmp_path_factory, "sizes")


def _graph(op: str, trans_b: bool = False):
    w = np.ones((3, 4) if trans_b else (4, 3), np.float32)
    inits = [numpy_helper.from_array(w, "W"), numpy_helper.from_array(np.zeros(3, np.float32), "b")]
    if op == "Gemm":
        node = helper.make_node("Gemm", ["X", "W", "b"], ["Y"], transB=int(trans_b))
    else:
        node = helper.make_node("MatMul", ["X", "W"], ["Y"])
    g = helper.make_graph([node], "g", [helper.make_tensor_value_info("X", TensorProto.FLOAT, ["n", 4])],
                          [helper.make_tensor_value_info("Y", TensorProto.FLOAT, ["n", 3])], inits)
    return helper.make_model(g, opset_imports=[helper.make_opsetid("", 17)])


@pytest.mark.parametrize("op,trans_b", [("MatMul", False), ("Gemm", False), ("Gemm", True)])
def test_onnx_stats_counts_parameters_and_macs_of_one_row(op, trans_b):
    m = _graph(op, trans_b)
    assert onnx_stats(m) == {"bytes": m.ByteSize(), "parameters": 15, "macs_per_step": 12}


def test_export_prints_and_records_sizes(dirs, tmp_path, capsys):
    out = tmp_path / "b"
    assert main(["export", str(dirs["root"] / "model"), "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "multiply-accumulates per step" in text and "manifest.json:" in text
    assert main(["export", str(dirs["root"] / "model"), "--out", str(out), "--force", "--json"]) == 0
    sizes = json.loads(capsys.readouterr().out)["model_sizes"]
    b = load_bundle(out)
    assert set(sizes) == {"manifest.json", "manifest.sha256", *b.manifest["files"]}
    for rel, s in sizes.items():
        assert s["bytes"] == (out / rel).stat().st_size, rel
    step = sizes["models/step.onnx"]
    assert step["parameters"] > 100 and step["macs_per_step"] > 100
    assert f"models/step.onnx: {step['bytes'] / 1e3:.1f} kB, {step['parameters']} parameters" in text
    recorded = b.manifest["export"]["model_sizes"]  # the manifest holds each graph's figures too
    assert set(recorded) == {f for f in b.manifest["files"] if f.endswith(".onnx")}
    assert all(recorded[f] == sizes[f] for f in recorded)
