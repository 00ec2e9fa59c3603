"""Decision E18 (docs/decisions/export.md): fewer instructions per streamed step with the same numbers.

Each rewritten piece is pinned against the code it replaces (copied here as the reference), bit for bit.
"""

from __future__ import annotations

import math

import numpy as np
import onnxruntime as ort
from onnx import TensorProto, helper, numpy_helper

from pdrlearn.kernels import stats as KS
from pdrlearn.kernels import window as KW


def _tilt_fraction_e17(n, k0, k1, th):
    """The pre-E18 angle column of ``tilt_corrected``: three numpy calls per step."""
    frac = (np.arange(n, dtype=np.float64).reshape(n, 1, 1) - float(k0)) / float(k1 - k0)
    ang = np.minimum(np.maximum(frac, 0.0, out=frac), 1.0, out=frac)
    ang *= th
    return ang


def test_cached_tilt_fraction_gives_the_same_angles_and_cannot_be_written():
    rng = np.random.default_rng(18)
    for n in (2, 3, 7, 24, 40, 615):
        for _ in range(20):
            k0 = int(rng.integers(0, n - 1))
            k1 = int(rng.integers(k0 + 1, n))
            th = float(rng.uniform(-math.pi, math.pi))
            got = KS._tilt_fraction(n, k0, k1) * th
            assert got.shape == (n, 1, 1)
            assert np.array_equal(got, _tilt_fraction_e17(n, k0, k1, th))
    frac = KS._tilt_fraction(10, 2, 8)
    assert not frac.flags.writeable
    assert KS._tilt_fraction(10, 2, 8) is frac  # cached


def test_tilt_corrected_is_unchanged_by_the_cached_fraction():
    rng = np.random.default_rng(7)
    for n in (3, 21, 40):
        Y = rng.normal(size=(n, 3, 3))
        g = np.array([0.3, -0.2, 9.7]) + rng.normal(scale=0.1, size=3)
        k0, k1 = 1, n - 1
        got = KS.tilt_corrected(Y.copy(), g, k0, k1)
        # the E17 body of tilt_corrected with the E17 angle column
        gx, gy, gz = g.tolist()
        nrm = math.sqrt(gx * gx + gy * gy + gz * gz)
        s = math.sqrt(gx * gx + gy * gy) / nrm
        kx, ky, th = gy / nrm / s, -gx / nrm / s, math.atan2(s, gz / nrm)
        ang = _tilt_fraction_e17(n, k0, k1, th)
        KT = np.array([[0.0, 0.0, -ky], [0.0, 0.0, kx], [ky, -kx, 0.0]])
        KY = Y.reshape(-1, 3) @ KT
        K2Y = (KY @ KT).reshape(Y.shape)
        want = Y + np.sin(ang) * KY.reshape(Y.shape) + (1.0 - np.cos(ang)) * K2Y
        assert np.array_equal(got, want)


def _frame3_e17(a, b):
    """The pre-E18 ``_frame3`` (list indexing at every use)."""
    na = math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])
    if not na > 0:
        return None
    u = [a[0] / na, a[1] / na, a[2] / na]
    d = u[0] * b[0] + u[1] * b[1] + u[2] * b[2]
    v = [b[0] - d * u[0], b[1] - d * u[1], b[2] - d * u[2]]
    nv = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    if not nv > 1e-9 * math.sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]):
        return None
    v = [v[0] / nv, v[1] / nv, v[2] / nv]
    return u, v, [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]


def test_frame3_unpacked_equals_the_indexed_version_bit_for_bit():
    rng = np.random.default_rng(3)
    cases = [(rng.normal(size=3).tolist(), rng.normal(size=3).tolist()) for _ in range(2000)]
    cases += [([0.0, 0.0, 0.0], [1.0, 2.0, 3.0]), ([1.0, 2.0, 3.0], [2.0, 4.0, 6.0]),  # degenerate: None
              ([1.0, 0.0, 0.0], [0.0, 0.0, 0.0]), ([0.0, 0.0, 1.0], [1e-300, 0.0, 1.0])]
    for a, b in cases:
        assert KW._frame3(a, b) == _frame3_e17(a, b)


def _run(nodes, inits, x):
    g = helper.make_graph(nodes, "p", [helper.make_tensor_value_info("x", TensorProto.DOUBLE, list(x.shape))],
                          [helper.make_tensor_value_info("y", TensorProto.DOUBLE, None)],
                          initializer=[numpy_helper.from_array(v, k) for k, v in inits.items()])
    m = helper.make_model(g, opset_imports=[helper.make_opsetid("", 17)])
    m.ir_version = 8
    s = ort.InferenceSession(m.SerializeToString(), providers=["CPUExecutionProvider"])
    return s.run(["y"], {"x": x})[0]


def test_svm_block_expands_each_models_squared_norm_like_the_gather_it_replaces():
    """E18: the SVM block gives each support vector's column its model's |z|^2 by a product with a 0/1
    matrix instead of a Gather of int64 indices; the values are the same bit for bit."""
    rng = np.random.default_rng(0)
    of_sv = np.repeat(np.arange(3), [97, 290, 5])
    expand = np.zeros((3, len(of_sv)))
    expand[of_sv, np.arange(len(of_sv))] = 1.0
    z_sq = rng.uniform(0.0, 50.0, size=(16, 3)) ** 2
    z_sq[0] = 0.0
    gathered = _run([helper.make_node("Gather", ["x", "i"], ["y"], axis=1)], {"i": of_sv.astype(np.int64)}, z_sq)
    product = _run([helper.make_node("MatMul", ["x", "e"], ["y"])], {"e": expand}, z_sq)
    assert np.array_equal(gathered, product)
