"""Decision E217: a float32-only bundle (``pdrlearn export --float32``) for single-precision targets.

A Cortex-M4F has a float32 FPU only (float64 is emulated in software, ~10-50x slower) and ~256 KB of flash.
:func:`graph_to_float32` rewrites a float64 ONNX graph (the step graph, the float64 SVM decision graph of
decision E4, the float64 network) to compute in float32: every double initializer, constant, ``Cast`` target
and declared tensor type becomes float. The formula is unchanged; only the rounding differs, which E217
measures on held-out simulated users (class agreement, largest probability difference).
"""

from __future__ import annotations

import numpy as np
import onnx
from onnx import TensorProto, numpy_helper

#: largest difference of a probability allowed between a float32 bundle and ``predict_proba`` before the bundle
#: is written (decision E217; the float64 bundles keep E80's 1e-5). float32 has a 6e-8 unit roundoff; a softmax of
#: decision values that sum ~100 kernel terms of size ~10 keeps ~1e-5 relative error, so 1e-3 leaves a margin of
#: ~100x while still stopping a wrong translation (those differ by > 0.01)
FLOAT32_PARITY_ATOL = 1e-3

_D, _F = TensorProto.DOUBLE, TensorProto.FLOAT


def _tensor32(t: TensorProto) -> TensorProto:
    if t.data_type != _D:
        return t
    a = numpy_helper.to_array(t).copy()
    big = np.finfo(np.float32).max  # a finite sentinel (the -1e300 class padding of decision E13) stays finite
    fin = np.isfinite(a)
    a[fin] = np.clip(a[fin], -big, big)
    return numpy_helper.from_array(a.astype(np.float32), t.name)


def _types32(values) -> None:
    for v in values:
        tt = v.type.tensor_type
        if tt.elem_type == _D:
            tt.elem_type = _F


def _graph32(g: onnx.GraphProto) -> None:
    for i, t in enumerate(g.initializer):
        if t.data_type == _D:
            g.initializer[i].CopyFrom(_tensor32(t))
    _types32(g.input)
    _types32(g.output)
    _types32(g.value_info)
    for node in g.node:
        for a in node.attribute:
            if a.type == onnx.AttributeProto.TENSOR and a.t.data_type == _D:
                a.t.CopyFrom(_tensor32(a.t))
            elif a.type == onnx.AttributeProto.GRAPH:
                _graph32(a.g)
            elif a.type == onnx.AttributeProto.GRAPHS:
                for sub in a.graphs:
                    _graph32(sub)
            elif node.op_type == "Cast" and a.name == "to" and a.i == _D:
                a.i = _F


def graph_to_float32(model: onnx.ModelProto) -> onnx.ModelProto:
    """A copy of ``model`` that computes in float32 wherever it computed in float64 (decision E217).

    Integer tensors (indices, shapes) are untouched. The result passes ``onnx.checker`` and shape inference
    when the input does; the caller checks its numbers (:func:`pdrlearn.export.parity.check_bundle_parity`).
    """
    out = onnx.ModelProto()
    out.CopyFrom(model)
    _graph32(out.graph)
    return out


def bundle_to_float32(onnx_models: dict, manifest: dict) -> dict:
    """The ``onnx_models`` of a bundle, all float32, with the float64 networks' ``.f32`` twins dropped (the network
    graph itself is float32 now) and every model entry's and the step graph's ``dtype`` set to ``float32``
    in ``manifest`` (changed in place). Returns the new ``{relative path: model}``."""
    twins = set()

    def entries(e):
        if e.get("type") == "fusion":
            for m in e["members"].values():
                yield from entries(m)
        else:
            yield e

    for task in manifest["tasks"].values():
        for per in task["methods"].values():
            for e in per.values():
                for leaf in entries(e):
                    if leaf.get("type") != "onnx":
                        continue
                    fb = leaf.pop("fallback_file", None)
                    if fb:
                        twins.add(fb)
                    leaf["dtype"] = "float32"
    if manifest.get("step_graph"):
        manifest["step_graph"]["dtype"] = "float32"
    manifest.setdefault("export", {})["precision"] = "float32"
    return {rel: graph_to_float32(m) for rel, m in onnx_models.items() if rel not in twins}
