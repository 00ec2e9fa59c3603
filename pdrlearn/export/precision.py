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

from pdrlearn.errors import ModelError

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
    for _, leaf in _leaves(manifest):
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


def range_rows(lo, hi) -> np.ndarray:
    """Feature rows on the edges of a model's training range (decision E221): all-``lo``, all-``hi``, the middle,
    and the middle with one feature at a time at its ``lo`` and at its ``hi`` (``3 + 2 n_features`` rows)."""
    lo, hi = np.asarray(lo, dtype=np.float64), np.asarray(hi, dtype=np.float64)
    mid = (lo + hi) / 2
    rows = [lo, hi, mid]
    for j in range(len(lo)):
        for v in (lo[j], hi[j]):
            r = mid.copy()
            r[j] = v
            rows.append(r)
    return np.array(rows)


def _leaves(manifest: dict):
    """``("task method/unit", leaf entry)`` of every model of a manifest, fusion members included."""

    def walk(e):
        if e.get("type") == "fusion":
            for m in e["members"].values():
                yield from walk(m)
        else:
            yield e

    for task, spec in manifest["tasks"].items():
        for method, per in spec["methods"].items():
            for unit, e in per.items():
                for leaf in walk(e):
                    yield f"{task} {method}/{unit}", leaf


def _graph_proba(model: onnx.ModelProto, leaf: dict, X: np.ndarray) -> np.ndarray:
    import onnxruntime as ort

    from pdrlearn.kernels.proba import softmax

    sess = ort.InferenceSession(model.SerializeToString(), providers=["CPUExecutionProvider"])
    dtype = np.float32 if model.graph.input[0].type.tensor_type.elem_type == _F else np.float64
    outs = leaf["outputs"]
    name = outs.get("proba") or outs["logits"]
    got = np.asarray(sess.run([name], {leaf["input"]: X.astype(dtype)})[0], dtype=np.float64)
    return got if "proba" in outs else softmax(got)


def check_float32_ranges(onnx64: dict, onnx32: dict, manifest: dict, *, atol: float = FLOAT32_PARITY_ATOL) -> dict:
    """Decision E221: every ONNX model of a float32 bundle against its float64 graph on the edges of its training
    range (:func:`range_rows` of the entry's ``training_range``, decision C16), before anything is written.

    E80's check runs simulated windows; a network whose input is sensitive to rounding (a near-constant feature,
    decision E220) agreed there within 1e-6 yet moved a probability by 0.2 on a walk (review R3). The training
    range's 1 % and 99 % quantiles are values the model saw, so they exercise the rounding of every input.
    Returns ``{"task method/unit": max abs difference}``; raises :class:`ModelError` (one line) above ``atol``.
    """
    out: dict = {}
    for name, leaf in _leaves(manifest):
        rng, rel = leaf.get("training_range") or {}, leaf.get("file")
        if leaf.get("type") != "onnx" or rel not in onnx64 or rel not in onnx32 or not rng.get("lo"):
            continue
        X = range_rows(rng["lo"], rng["hi"])
        diff = float(np.abs(_graph_proba(onnx32[rel], leaf, X) - _graph_proba(onnx64[rel], leaf, X)).max())
        out[name] = diff
        if not diff <= atol:
            raise ModelError(
                f"export --float32: the {name} model's float32 graph gives probabilities up to {diff:.3g} away from "
                f"its float64 graph on its training range (limit {atol:g}), so no bundle was written (decision "
                "E221); export without --float32, or re-train the model with this version (decision E220)")
    return out
