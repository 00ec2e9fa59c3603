"""Decision E19 (docs/decisions/export.md): the step graph's force statistics in fewer, cheaper nodes, with
the same numbers.

The E18 force block is copied here as the reference; the E19 block must give its values bit for bit (and the
numpy kernel's within 1e-12) on windows built to hit every branch of ``kernels.stats.force_stats``: no zero
sample (its argmin fallback, with ties at the minimum), zero force everywhere (peak 0), a negative force
(peak < 0), a zero only at the last or only at the first samples, scattered zeros, quantised forces (ties
everywhere) and grids whose queries land on grid points and on the grid's end.
"""

from __future__ import annotations

import numpy as np
import onnxruntime as ort
import pytest
from onnx import TensorProto

from pdrlearn.export import step_graph as SG
from pdrlearn.runtime.features import compute_features

M = 40
FEATURES = {"channels": ["t_s", "force_a", "force_b", "other"], "n_samples": M,
            "signals": {"force": [["force_a", "force_b"], 1.0], "force_neg": [["force_a"], -1.0]}}
STATS = [["air_time"], ["time_to_peak"], ["peak_mean_4"], ["contact_force_2"], ["takeoff_force"],
         ["air_time", "time_to_peak", "takeoff_force"],  # the default bundle's
         ["contact_force_2", "peak_mean_4"],
         ["contact_force_2", "peak_mean_4", "time_to_peak", "takeoff_force", "air_time"]]


# -- the E18 force block (pdrlearn/export/step_graph.py at commit 38c34bd), the reference --------------
def _interp_e18(self, q: str, x: str, y: str) -> str:
    """``np.interp`` of each row: queries q (n, k) on the row's grid x (n, m) (increasing) -> (n, k).
    The queries must lie in ``[x[:, 0], x[:, -1]]`` (the force statistics clip them to the window)."""
    m = self.m
    q3 = self.op("Unsqueeze", [q, self.const(np.array([2], np.int64), "ax2", np.int64)])  # (n, k, 1)
    # the interval j = the last grid point at or below q, within 0..m-2: the number of inner grid points
    # x[1..m-2] at or below q (x[0] <= q always), so no Clip of the full count (decision E16)
    inner = self.op("Gather", [x, self.const(np.arange(1, m - 1)[None, :], "inner", np.int64)], "xin", axis=1)
    le = self.op("Cast", [self.op("LessOrEqual", [inner, q3])], "le", to=TensorProto.INT64)  # (n, k, m-2)
    j = self.op("ReduceSum", [le, self.const(np.array([2], np.int64), "ax2", np.int64)], "j", keepdims=0)
    j1 = self.op("Add", [j, self.const(np.array(1, np.int64), "one", np.int64)], "j1")
    xj, xj1, yj, yj1 = self.at(x, j), self.at(x, j1), self.at(y, j), self.at(y, j1)
    slope = self.op("Div", [self.op("Sub", [yj1, yj]), self.op("Sub", [xj1, xj])], "islope")
    v = self.op("Add", [self.op("Mul", [slope, self.op("Sub", [q, xj])]), yj], "iv")  # numpy's order
    # np.interp returns the last value exactly at (and past) the grid's end
    last = self.op("GreaterOrEqual", [q, self.cols(x, m - 1)])
    return self.op("Where", [last, self.cols(y, m - 1), v], "interp")

def _force_block_e18(self, stats: list[str], zero_fraction: float, sample_s: float = 0.05) -> list[tuple[str, list]]:
    """kernels.stats.force_stats (thesis Table 29, ch. 6.3.1) of the statistics ``stats``: tensors and the
    key of each of their columns (None = a column no recipe reads).

    Only the instants the asked statistics need are gathered and interpolated (decision E16): one
    GatherElements of the times at (last zero, contact peak, first zero), one product with a 0/+-1
    matrix plus one offset vector gives the interpolation queries and ``time_to_peak`` (each output
    one exact term, or one rounded difference, like the kernel's), and the queries go through one
    interpolation. ``time_to_peak`` lies in ``[0, duration]`` (the peak is at or after the last zero),
    so the clip of the queries to the window leaves it unchanged.
    """
    key = lambda st: ("force", st, float(zero_fraction))  # noqa: E731
    f, tt = self.signal("force"), self.tt()
    peak = self.op("ReduceMax", [f], "fpeak", axes=[1], keepdims=1)
    pos = self.op("Greater", [peak, self.const(np.array(0.0), "zero")])
    ref = self.op("Where", [pos, peak, self.const(np.array(1.0), "onef")])
    zero = self.op("Less", [f, self.op("Mul", [self.const(np.array(zero_fraction), "zf"), ref])], "zero")
    zf = self.op("Cast", [zero], "zerof", to=TensorProto.DOUBLE)
    out: list[tuple[str, list]] = []
    if "air_time" in stats:
        out.append((self.reduce("ReduceSum", self.op("Mul", [zf, self.gradient(tt)]), keepdims=1),
                    [key("air_time")]))
    need_last = bool({"time_to_peak", "peak_mean_4", "contact_force_2"} & set(stats))
    need_peak = bool({"time_to_peak", "peak_mean_4"} & set(stats))
    need_first = "takeoff_force" in stats
    if not (need_last or need_first):
        return out
    any_zero = self.op("Greater", [self.op("ReduceMax", [zf], "anyz", axes=[1], keepdims=1),
                                   self.const(np.array(0.0), "zero")])
    i_fmin = self.op("ArgMin", [f], "ifmin", axis=1, keepdims=1)
    idx: list[str] = []  # the instants, in the order of the rows of L below
    rows: list[str] = []
    if need_last:
        last_zero = self.op("Where", [any_zero, self.op("ArgMax", [zf], "lz", axis=1, keepdims=1,
                                                        select_last_index=1), i_fmin])
        idx.append(last_zero)
        rows.append("last")
    if need_peak:
        after = self.op("GreaterOrEqual", [self.const(np.arange(self.m)[None, :], "arange", np.int64), last_zero])
        masked = self.op("Where", [after, f, self.const(np.array(-np.inf), "ninf")])
        idx.append(self.op("ArgMax", [masked], "ipeak", axis=1, keepdims=1))
        rows.append("peak")
    if need_first:
        idx.append(self.op("Where", [any_zero, self.op("ArgMax", [zf], "fz", axis=1, keepdims=1), i_fmin]))
        rows.append("first")
    at = self.at(tt, idx[0] if len(idx) == 1 else self.op("Concat", idx, "fidx", axis=1))  # (n, len(rows))
    # columns: (coefficients on the rows, offset, key or None); the kernel's queries are
    # t_peak -+ 4 samples, t_last + 2 samples, t_first - 2 samples (thesis Table 29 #3-4, ch. 6.3.1)
    cols: list[tuple[dict, float, str | None]] = []
    if "time_to_peak" in stats:
        cols.append(({"peak": 1.0, "last": -1.0}, 0.0, "time_to_peak"))
    if "peak_mean_4" in stats:
        cols += [({"peak": 1.0}, -4 * sample_s, None), ({"peak": 1.0}, 4 * sample_s, None)]
    if "contact_force_2" in stats:
        cols.append(({"last": 1.0}, 2 * sample_s, "contact_force_2"))
    if "takeoff_force" in stats:
        cols.append(({"first": 1.0}, -2 * sample_s, "takeoff_force"))
    L = np.zeros((len(rows), len(cols)))
    for c, (coef, _, _) in enumerate(cols):
        for r, w in coef.items():
            L[rows.index(r), c] = w
    q = self.op("MatMul", [at, self.const(L, "fsel")], "fq")
    offs = np.array([o for _, o, _ in cols])
    if offs.any():
        q = self.op("Add", [q, self.const(offs, "foff")], "fq")  # + 0.0 leaves time_to_peak exact
    interpolated = [k for _, _, k in cols if k != "time_to_peak"]
    if not interpolated:
        return out + [(q, [key("time_to_peak")])]
    dur = self.memo_get("duration", lambda: self.cols(tt, self.m - 1))
    q = self.op("Min", [self.op("Max", [q, self.const(np.array(0.0), "zero")]), dur], "qc")  # interp_rows
    out.append((q, [key(k) if k == "time_to_peak" else None for _, _, k in cols]))
    v = _interp_e18(self, q, tt, f)
    out.append((v, [None if k in (None, "time_to_peak") else key(k) for _, _, k in cols]))
    if "peak_mean_4" in stats:
        h = np.zeros((len(cols), 1))
        h[[c for c, (coef, o, k) in enumerate(cols) if k is None], 0] = 0.5  # 0.5 v0 + 0.5 v1, one rounding
        out.append((self.op("MatMul", [v, self.const(h, "pm4")], "pm4"), [key("peak_mean_4")]))
    return out



def _windows(n=1500, seed=19):
    rng = np.random.default_rng(seed)
    W = rng.normal(size=(n, 4, M))
    W[:, 0] = np.cumsum(rng.uniform(0.01, 0.08, (n, M)), axis=1)
    W[:, 0] -= W[:, 0, :1]
    W[:, 1] = np.abs(W[:, 1]) * 100
    W[:, 2] = np.abs(W[:, 2]) * 50
    for i, kind in enumerate(rng.integers(0, 9, n)):
        if kind == 1:  # never zero, ties at the minimum (the argmin fallback takes the first)
            W[i, 1], W[i, 2] = 50.0 + rng.integers(0, 5, M), 0.0
        elif kind == 2:  # no force at all: peak 0, every sample zero
            W[i, 1] = W[i, 2] = 0.0
        elif kind == 3:  # quantised: ties everywhere
            W[i, 1], W[i, 2] = np.round(W[i, 1] / 40) * 40, 0.0
        elif kind == 4:  # zero at the last sample only
            W[i, 1, -1] = W[i, 2, -1] = -1.0
        elif kind == 5:  # zeros at the start only
            W[i, 1, :rng.integers(1, M)] = 0.0
            W[i, 2] = 0.0
        elif kind == 6:  # scattered zeros
            W[i, 1, rng.integers(0, M, 5)] = 0.0
            W[i, 2] = 0.0
        elif kind == 7:  # negative force: peak < 0
            W[i, 1], W[i, 2] = -np.abs(W[i, 1]), 0.0
        elif kind == 8:  # zero at the first sample only
            W[i, 1, 0] = W[i, 2, 0] = -1.0
    W[:20, 0] = np.linspace(0.0, 0.05 * (M - 1), M)  # the 50 ms grid: queries land on grid points and its end
    return W


def _run(model, W):
    sess = ort.InferenceSession(model.SerializeToString(), providers=["CPUExecutionProvider"])
    return sess.run(["F"], {"W": W})[0]


@pytest.fixture(scope="module")
def windows():
    return _windows()


@pytest.mark.parametrize("stats", STATS)
@pytest.mark.parametrize("zf", [0.05, 0.2, 0.0])
def test_force_block_equals_the_e18_block_bit_for_bit(windows, stats, zf, monkeypatch):
    recipe = [["force", st, zf] for st in stats]
    new = SG.features_graph(recipe, FEATURES)
    got = _run(new, windows)
    monkeypatch.setattr(SG._Builder, "force_block", _force_block_e18)
    old = SG.features_graph(recipe, FEATURES)
    want = _run(old, windows)
    assert np.array_equal(got, want)
    ci = {c: i for i, c in enumerate(FEATURES["channels"])}
    # the kernel in chunks of 8 windows (interp_rows chains a call's rows on one grid, which rounds more
    # the more rows it holds; the runtime classifies one window at a time)
    kernel = np.concatenate([compute_features(windows[i:i + 8], recipe, signals=FEATURES["signals"], channel_index=ci)
                             for i in range(0, len(windows), 8)])
    np.testing.assert_allclose(got, kernel, rtol=1e-12, atol=1e-12)
    ops = [n.op_type for n in new.graph.node]
    old_ops = [n.op_type for n in old.graph.node]
    # fewer nodes whenever an instant is needed (air time alone: one Unsqueeze more, the (n, 1, m) time grid)
    assert len(ops) < len(old_ops) if stats != ["air_time"] else len(ops) == len(old_ops) + 1
    assert "ArgMin" not in ops  # the no-zero fallback is in the ArgMax scores
    # no Where on indices: at most the peak reference's, the zero scores' and the contact-peak mask's
    assert ops.count("Where") <= 1 + bool({"time_to_peak", "peak_mean_4", "contact_force_2", "takeoff_force"}
                                          & set(stats)) + bool({"time_to_peak", "peak_mean_4"} & set(stats))
    interpolated = bool({"peak_mean_4", "contact_force_2", "takeoff_force"} & set(stats))
    assert ops.count("LessOrEqual") == ops.count("Split") == int(interpolated)  # one interpolation, no end-rule Where
    assert ops.count("GatherElements") == int(len(stats) > stats.count("air_time")) + int(interpolated)


def test_a_negative_zero_fraction_leaves_the_task_to_the_per_model_path():
    with pytest.raises(KeyError):
        SG.features_graph([["force", "takeoff_force", -0.1]], FEATURES)


def test_a_signed_one_channel_force_signal_is_gathered_as_one_row(windows):
    """signal3 keeps ``signal``'s sign and Adds (a one-channel signal with sign -1)."""
    b = SG._Builder(M, {c: i for i, c in enumerate(FEATURES["channels"])}, FEATURES["signals"])
    x3, x2 = b.signal3("force_neg"), b.signal("force_neg")
    b.nodes.append(SG.helper.make_node("Identity", [x3], ["A"]))
    b.nodes.append(SG.helper.make_node("Identity", [x2], ["B"]))
    g = SG.helper.make_graph(b.nodes, "t", [SG.helper.make_tensor_value_info("W", TensorProto.DOUBLE, [None, 4, M])],
                             [SG.helper.make_tensor_value_info(o, TensorProto.DOUBLE, None) for o in "AB"],
                             initializer=b.inits)
    model = SG.helper.make_model(g, opset_imports=[SG.helper.make_opsetid("", SG.OPSET)])
    model.ir_version = 8
    sess = ort.InferenceSession(model.SerializeToString(), providers=["CPUExecutionProvider"])
    a, c = sess.run(["A", "B"], {"W": windows})
    assert a.shape == (len(windows), 1, M) and np.array_equal(a[:, 0], c) and np.array_equal(c, -windows[:, 1])


def _mlp(rng, n_in, n_hidden, n_classes):
    """A network graph of the project's form (Sub, Div, Gemm, Tanh, Gemm, Softmax; float64)."""
    from onnx import numpy_helper

    p = {"mean": rng.normal(size=n_in), "scale": rng.uniform(0.5, 2.0, n_in),
         "W1": rng.normal(size=(n_hidden, n_in)), "b1": rng.normal(size=n_hidden),
         "W2": rng.normal(size=(n_classes, n_hidden)), "b2": rng.normal(size=n_classes)}
    h = SG.helper
    nodes = [h.make_node("Sub", ["X", "mean"], ["a"]), h.make_node("Div", ["a", "scale"], ["b"]),
             h.make_node("Gemm", ["b", "W1", "b1"], ["c"], transB=1), h.make_node("Tanh", ["c"], ["d"]),
             h.make_node("Gemm", ["d", "W2", "b2"], ["e"], transB=1), h.make_node("Softmax", ["e"], ["proba"], axis=1)]
    g = h.make_graph(nodes, "nn", [h.make_tensor_value_info("X", TensorProto.DOUBLE, [None, n_in])],
                     [h.make_tensor_value_info("proba", TensorProto.DOUBLE, [None, n_classes])],
                     [numpy_helper.from_array(v, k) for k, v in p.items()])
    model = h.make_model(g, opset_imports=[h.make_opsetid("", SG.OPSET)])
    model.ir_version = 8
    return model


def test_one_scaler_and_softmax_for_the_network_and_svm_blocks_give_the_separate_blocks_numbers(windows):
    """E19: the network block (2 networks, 3 and 2 classes) and the SVM block (2 SVMs, 2 and 3 classes,
    mixed kernels) share one Gather/Sub/Div scaler (then a Split) and one Softmax over one padded width; the
    probabilities equal those of the separate blocks (E13-E18) bit for bit, and the per-model graphs'
    soft vote within 1e-12."""
    from pdrlearn.export.onnx_convert import svm_decision_to_onnx
    from pdrlearn.kernels.proba import soft_vote

    rng = np.random.default_rng(19)
    feats = {"channels": FEATURES["channels"], "n_samples": M,
             "signals": {**FEATURES["signals"], "other_sig": [["other"], 1.0]}}
    ci = {c: i for i, c in enumerate(feats["channels"])}
    recipes = {"foot": [["force", "air_time", 0.05], ["force", "takeoff_force", 0.05], ["segments", "other_sig", 2]],
               "waist": [["segments", "other_sig", 3], ["force", "time_to_peak", 0.05]]}
    W = windows[:300]
    models, tasks, want = {}, {}, {}
    for task, method, classes in (("terrain", "nn", ["f", "u", "d"]), ("direction", "nn", ["fw", "bw"]),
                                  ("length", "svm", ["s", "n", "l"]), ("side", "svm", ["a", "b"])):
        members, probas = {}, []
        for unit, recipe in recipes.items():
            F = compute_features(W, recipe, signals=feats["signals"], channel_index=ci)
            if method == "nn":
                model = _mlp(rng, F.shape[1], 5, len(classes))
                spec = {"classes": classes, "outputs": {"proba": "proba"}}
            else:
                params = [{"kernel": ("rbf", "poly", "linear")[c % 3], "sv": rng.normal(size=(6, F.shape[1])),
                           "dual": rng.normal(size=6), "b": float(rng.normal()), "gamma": 0.1,
                           "degree": 2 if c % 3 == 1 else 1, "coef0": 1.0 if c % 3 == 1 else 0.0}
                          for c in range(len(classes))]
                model, spec = svm_decision_to_onnx(F.mean(axis=0), F.std(axis=0) + 0.5, params, classes)
            rel = f"models/{task}_{unit}.onnx"
            models[rel] = model
            members[unit] = {"type": "onnx", "file": rel, "features": recipe, **spec}
            sess = ort.InferenceSession(model.SerializeToString(), providers=["CPUExecutionProvider"])
            probas.append(sess.run(["proba"], {sess.get_inputs()[0].name: F})[0])
        weights = [0.4, 0.6]
        tasks[task] = {"classes": classes, "chosen": {"method": method, "unit": "fused"},
                       "methods": {method: {"fused": {"type": "fusion", "weights": weights, "classes": classes,
                                                      "members": members}}}}
        want[task] = soft_vote(probas, weights)
    model, spec = SG.build_step_graph(tasks, models, feats)
    apart, _ = SG.build_step_graph(tasks, models, feats, one_softmax=False)
    ops, ops_apart = [n.op_type for n in model.graph.node], [n.op_type for n in apart.graph.node]
    assert ops.count("Softmax") == 1 and ops_apart.count("Softmax") == 2
    # the scaler 6 -> 4 nodes (Gather, Sub, Div, Split), one Reshape, Softmax, Reshape instead of two
    assert ops.count("Tanh") == 1 and len(ops) == len(ops_apart) - 5
    sess = {k: ort.InferenceSession(m.SerializeToString(), providers=["CPUExecutionProvider"])
            for k, m in (("one", model), ("apart", apart))}
    names = list(spec["outputs"].values())
    got = dict(zip(names, sess["one"].run(names, {"W": W}), strict=True))
    ref = dict(zip(names, sess["apart"].run(names, {"W": W}), strict=True))
    for task, name in spec["outputs"].items():
        assert np.array_equal(got[name], ref[name])
        np.testing.assert_allclose(got[name], want[task], rtol=0, atol=1e-12)
