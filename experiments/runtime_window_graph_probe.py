"""Probe for decision E12 (docs/decisions/export.md): would the step window run faster inside the ONNX step
graph? Its sequential part, the attitude propagation (:func:`pdrlearn.kernels.stats.propagate_attitude`:
Rodrigues rotations of the sample intervals, Hillis-Steele prefix products, ``R_k = r0 P_k0^T P_k``), is
written as an onnxruntime graph (the scan unrolled for up to 1024 samples; levels past ``n`` act on empty
slices) and timed against the numpy kernel on one step of 23 (20 Hz) and 230 (204.8 Hz) samples.

Usage: ``.venv/bin/python experiments/runtime_window_graph_probe.py`` (prints the node count, the largest
difference to numpy and the best-of-7 time per call of each; first the time of chains of 1, 50 and 200
elementwise nodes, onnxruntime's cost per run and per node).
"""

from __future__ import annotations

import sys
import timeit
from pathlib import Path

import numpy as np
import onnxruntime as ort
from onnx import ModelProto, TensorProto, helper, numpy_helper

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from pdrlearn.kernels.stats import propagate_attitude  # noqa: E402

I64 = np.int64
END = 2**62  # "to the end" of a Slice


class _Graph:
    def __init__(self):
        self.nodes: list = []
        self.inits: list = []
        self.k = 0

    def c(self, v, dtype=np.float64) -> str:
        self.k += 1
        name = f"c{self.k}"
        self.inits.append(numpy_helper.from_array(np.asarray(v, dtype=dtype), name))
        return name

    def op(self, op_type: str, inputs: list[str], **attrs) -> str:
        self.k += 1
        name = f"n{self.k}"
        self.nodes.append(helper.make_node(op_type, inputs, [name], **attrs))
        return name

    def rows(self, x: str, a: int, b: int) -> str:
        return self.op("Slice", [x, self.c([a], I64), self.c([b], I64), self.c([0], I64)])


def attitude_graph(max_samples: int = 1024) -> tuple[ModelProto, int]:
    """Graph ``(gyr (n, 3), dt (n-1,), k0, r0 (3, 3)) -> R (n, 3, 3)``; returns it and its node count."""
    g = _Graph()
    w = g.op("Mul", [g.op("Mul", [g.op("Add", [g.rows("gyr", 0, -1), g.rows("gyr", 1, END)]), g.c(0.5)]),
                     g.op("Unsqueeze", ["dt", g.c([1], I64)])])  # mean rate x interval (rad)
    th = g.op("Sqrt", [g.op("ReduceSum", [g.op("Mul", [w, w]), g.c([1], I64)], keepdims=1)])
    a = g.op("Div", [g.op("Sin", [th]), th])
    b = g.op("Div", [g.op("Sub", [g.c(1.0), g.op("Cos", [th])]), g.op("Mul", [th, th])])
    wz = g.op("Concat", [g.op("Mul", [th, g.c(0.0)]), w], axis=1)  # (n, 4): [0, wx, wy, wz]
    K = g.op("Reshape", [g.op("Mul", [g.op("Gather", [wz, g.c([0, 3, 2, 3, 0, 1, 2, 1, 0], I64)], axis=1),
                                      g.c([0, -1, 1, 1, 0, -1, -1, 1, 0])]), g.c([-1, 3, 3], I64)])  # [w]x
    a3, b3 = g.op("Unsqueeze", [a, g.c([2], I64)]), g.op("Unsqueeze", [b, g.c([2], I64)])
    R = g.op("Add", [g.op("Add", [g.c(np.eye(3)), g.op("Mul", [a3, K])]), g.op("Mul", [b3, g.op("MatMul", [K, K])])])
    P = g.op("Concat", [g.c(np.eye(3)[None]), R], axis=0)
    shift = 1
    while shift < max_samples:  # Hillis-Steele inclusive scan, unrolled
        P = g.op("Concat", [g.rows(P, 0, shift), g.op("MatMul", [g.rows(P, 0, -shift), g.rows(P, shift, END)])],
                 axis=0)
        shift *= 2
    pk = g.op("Gather", [P, "k0"], axis=0)
    out = g.op("MatMul", [g.op("MatMul", ["r0", g.op("Transpose", [pk], perm=[1, 0])]), P])
    graph = helper.make_graph(
        g.nodes, "attitude",
        [helper.make_tensor_value_info("gyr", TensorProto.DOUBLE, [None, 3]),
         helper.make_tensor_value_info("dt", TensorProto.DOUBLE, [None]),
         helper.make_tensor_value_info("k0", TensorProto.INT64, []),
         helper.make_tensor_value_info("r0", TensorProto.DOUBLE, [3, 3])],
        [helper.make_tensor_value_info(out, TensorProto.DOUBLE, None)], initializer=g.inits)
    model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 17)])
    model.ir_version = 8
    return model, len(g.nodes)


def chain_graph(n_nodes: int) -> ModelProto:
    """``n_nodes`` elementwise nodes (Neg/Abs) in a row on a step window ``W (1, 18, 40)`` float64."""
    nodes, prev = [], "W"
    for i in range(n_nodes):
        nodes.append(helper.make_node("Abs" if i % 2 else "Neg", [prev], [f"y{i}"]))
        prev = f"y{i}"
    graph = helper.make_graph(nodes, "chain", [helper.make_tensor_value_info("W", TensorProto.DOUBLE, [None, 18, 40])],
                              [helper.make_tensor_value_info(prev, TensorProto.DOUBLE, None)])
    model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 17)])
    model.ir_version = 8
    return model


def main() -> None:
    opts = ort.SessionOptions()
    opts.intra_op_num_threads = opts.inter_op_num_threads = 1
    W = np.random.default_rng(1).normal(size=(1, 18, 40))
    for k in (1, 50, 200):  # onnxruntime's cost per run and per node
        s = ort.InferenceSession(chain_graph(k).SerializeToString(), opts, providers=["CPUExecutionProvider"])
        t = min(timeit.repeat(lambda s=s, k=k: s.run([f"y{k - 1}"], {"W": W}), number=2000, repeat=5)) / 2000
        print(f"chain of {k} elementwise nodes: {t * 1e6:.1f} us per run")
    model, n_nodes = attitude_graph()
    sess = ort.InferenceSession(model.SerializeToString(), opts, providers=["CPUExecutionProvider"])
    print(f"attitude graph: {n_nodes} nodes")
    rng = np.random.default_rng(0)
    for n, rate in ((23, 20.0), (230, 204.8)):
        gyr, dt, k0, r0 = rng.normal(size=(n, 3)), np.full(n - 1, 1.0 / rate), 3, np.eye(3)
        feed = {"gyr": gyr, "dt": dt, "k0": np.array(k0, I64), "r0": r0}
        diff = np.abs(propagate_attitude(gyr, dt, k0, r0) - sess.run(None, feed)[0]).max()
        t_np = min(timeit.repeat(lambda g=gyr, d=dt, k=k0, r=r0: propagate_attitude(g, d, k, r), number=1000, repeat=7))
        t_ort = min(timeit.repeat(lambda f=feed: sess.run(None, f), number=1000, repeat=7))
        print(f"n={n} ({rate} Hz): max diff {diff:.1e}; numpy {t_np * 1e3:.1f} us, onnxruntime {t_ort * 1e3:.1f} us")


if __name__ == "__main__":
    main()
