"""Decision E219: the flash and compute a bundle's models need, for a port to a small target.

Per ONNX graph: its size in bytes (the flash it takes as a file), its parameter count (the elements of its stored
tensors) and an estimate of the multiply-accumulates of one step (one input row; the step graph: one window): the
matrix products (``MatMul`` / ``Gemm``, shapes from ONNX shape inference with the batch of steps as 1), which
dominate a network's and an SVM kernel's cost. Element-wise operators, reductions and the step graph's other
feature arithmetic are not counted, so the estimate is a lower bound.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import onnx


def _shapes(model: onnx.ModelProto) -> dict:
    """Tensor name -> shape (a dynamic dimension, the batch of steps, as 1) after ONNX shape inference."""
    inferred = onnx.shape_inference.infer_shapes(model)
    g = inferred.graph
    out = {t.name: tuple(int(d) for d in t.dims) for t in g.initializer}
    for v in (*g.input, *g.value_info, *g.output):
        tt = v.type.tensor_type
        if tt.HasField("shape"):
            out[v.name] = tuple(int(d.dim_value) if d.HasField("dim_value") else 1 for d in tt.shape.dim)
    return out


def onnx_stats(model: onnx.ModelProto) -> dict:
    """``{"bytes", "parameters", "macs_per_step"}`` of one ONNX graph (see the module's note on the estimate)."""
    g = model.graph
    params = int(sum(int(np.prod(t.dims)) if t.dims else 1 for t in g.initializer))
    shapes = _shapes(model)
    macs = 0
    for node in g.node:
        if node.op_type not in ("MatMul", "Gemm"):
            continue
        a, b = (shapes.get(i) for i in node.input[:2])
        if not a or not b:
            continue
        if node.op_type == "Gemm":  # (m, k) x (k, n) or transposed: m * k * n
            ta = any(x.name == "transA" and x.i for x in node.attribute)
            m, k = (a[1], a[0]) if ta else (a[0], a[1])
            n = b[0] if any(x.name == "transB" and x.i for x in node.attribute) else b[1]
            macs += m * k * n
            continue
        a2, b2 = (a if len(a) > 1 else (1, *a)), (b if len(b) > 1 else (*b, 1))
        batch = np.broadcast_shapes(a2[:-2], b2[:-2])
        macs += int(np.prod(batch, dtype=np.int64)) * a2[-2] * a2[-1] * b2[-1]  # (m, k) x (k, n) per batch entry
    return {"bytes": int(model.ByteSize()), "parameters": params, "macs_per_step": int(macs)}


def bundle_sizes(path: str | Path, files) -> dict:
    """Relative path -> ``{"bytes"}`` of each of a bundle's ``files`` and its manifest (from disk), with
    :func:`onnx_stats`'s parameters and multiply-accumulates for each ONNX graph."""
    from pdrlearn.runtime.bundle import MANIFEST, MANIFEST_SHA

    root = Path(path)
    out = {}
    for rel in [MANIFEST, MANIFEST_SHA, *sorted(files)]:
        f = root / rel
        out[rel] = {**(onnx_stats(onnx.load(str(f))) if rel.endswith(".onnx") else {}), "bytes": f.stat().st_size}
    return out


def sizes_lines(sizes: dict) -> list[str]:
    """One printed line per file: size, parameters and multiply-accumulates per step where known."""
    lines = []
    for rel, s in sizes.items():
        extra = (f", {s['parameters']} parameters, ~{s['macs_per_step']} MAC/step" if "parameters" in s else "")
        lines.append(f"  {rel}: {s['bytes'] / 1e3:.1f} kB{extra}")
    return lines
