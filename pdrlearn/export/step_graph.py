"""One ONNX graph per bundle that classifies a step for every task: window -> features -> models -> fusion.

The runtime's per-model path evaluates each model's feature recipe in numpy, runs one onnxruntime
session per model (a fused task = 2) and fuses the units' probabilities in Python: about 100 small
numpy calls and 6 session runs per step for the default bundle (docs/deploying.md, "Parity and
performance"). The *step graph* (decision E10, docs/decisions/export.md) does the same arithmetic in
one session run: its input is the step window ``W (n, channels, n_samples)`` float64, it computes the
recipes' features (segment, peak, force and yaw statistics: the formulas of
:mod:`pdrlearn.kernels.stats`), inlines every chosen model's own ONNX graph (the very graphs the bundle
ships), aligns each model's classes to the task's and soft-votes the units with the fusion weights
(:func:`pdrlearn.kernels.proba.soft_vote`). Outputs: one probability matrix ``(n, n_classes)`` per task
in the task's class order. Tasks whose chosen model is not an ONNX model (DTW, heuristic rules) or
uses a recipe item without a graph translation are left out and run on the per-model path.
"""

from __future__ import annotations

import logging

import numpy as np
import onnx
from onnx import TensorProto, helper, numpy_helper

from pdrlearn.export.onnx_convert import OPSET

log = logging.getLogger(__name__)

#: Recipe operations the step graph translates (see :func:`pdrlearn.runtime.features.compute_features`).
GRAPH_OPS = ("peak", "segments", "force", "yaw_sign", "yaw")
INPUT = "W"


class _Builder:
    """Appends nodes/initializers with unique names; memoizes the shared signals and statistics."""

    def __init__(self, n_samples: int, channel_index: dict[str, int], signals: dict):
        self.m = int(n_samples)
        self.ci = channel_index
        self.signals = signals
        self.nodes: list = []
        self.inits: list = []
        self.memo: dict = {}
        self.onnx_models: dict[str, onnx.ModelProto] = {}
        self.used_channels: set[int] = set()
        self._k = 0

    # -- primitives ---------------------------------------------------------------------------------
    def name(self, hint: str) -> str:
        self._k += 1
        return f"s{self._k}_{hint}"

    def const(self, value, hint: str = "c", dtype=np.float64) -> str:
        key = ("const", hint, np.asarray(value, dtype).tobytes(), np.asarray(value).shape, np.dtype(dtype).str)
        if key not in self.memo:
            nm = self.name(hint)
            self.inits.append(numpy_helper.from_array(np.asarray(value, dtype=dtype), nm))
            self.memo[key] = nm
        return self.memo[key]

    def op(self, op_type: str, inputs: list[str], hint: str = "", **attrs) -> str:
        out = self.name(hint or op_type.lower())
        self.nodes.append(helper.make_node(op_type, inputs, [out], **attrs))
        return out

    def cols(self, x: str, idx) -> str:
        """``x[:, idx]`` of a 2-D tensor (idx an int -> (n, 1), a list -> (n, len))."""
        idx = np.asarray([idx] if np.isscalar(idx) else idx, dtype=np.int64)
        return self.op("Gather", [x, self.const(idx, "idx", np.int64)], "cols", axis=1)

    def at(self, x: str, idx: str) -> str:
        """``x[row, idx[row]]`` for an (n, k) int64 index tensor -> (n, k)."""
        return self.op("GatherElements", [x, idx], "at", axis=1)

    def memo_get(self, key, build):
        if key not in self.memo:
            self.memo[key] = build()
        return self.memo[key]

    # -- window quantities ----------------------------------------------------------------------------
    def channel(self, c: str) -> str:
        j = self.ci[c]
        self.used_channels.add(j)
        return self.memo_get(("chan", c), lambda: self.op(
            "Gather", [INPUT, self.const(np.array(j, np.int64), "ch", np.int64)], c, axis=1))  # (n, m)

    def signal(self, name: str) -> str:
        """Derived signal (runtime.features.signal): sum of its channels times its sign."""
        def build():
            chans, sign = self.signals[name][0], float(self.signals[name][1])
            out = self.channel(chans[0])
            for c in chans[1:]:
                out = self.op("Add", [out, self.channel(c)], name)
            return out if sign == 1.0 else self.op("Mul", [out, self.const(np.array(sign), "sign")], name)
        return self.memo_get(("sig", name), build)

    def tt(self) -> str:
        """Time since the step's first sample (n, m) (s)."""
        def build():
            t = self.channel("t_s")
            return self.op("Sub", [t, self.cols(t, 0)], "tt")
        return self.memo_get("tt", build)

    def gradient(self, t: str) -> str:
        """kernels.stats.row_gradient: sample weights (s) of each row's time grid (n, m)."""
        def build():
            m = self.m
            first = self.op("Sub", [self.cols(t, 1), self.cols(t, 0)], "g0")
            last = self.op("Sub", [self.cols(t, m - 1), self.cols(t, m - 2)], "g1")
            mid = self.op("Div", [self.op("Sub", [self.cols(t, list(range(2, m))), self.cols(t, list(range(m - 2)))]),
                                  self.const(np.array(2.0), "two")], "gm")
            return self.op("Concat", [first, mid, last], "grad", axis=1)
        return self.memo_get(("grad", t), build)

    def reduce(self, op: str, x: str, keepdims: int = 0) -> str:
        """Reduction over axis 1 (opset 17: ReduceSum takes axes as an input, the others as an attribute)."""
        if op == "ReduceSum":
            return self.op(op, [x, self.const(np.array([1], np.int64), "ax", np.int64)], "sum", keepdims=keepdims)
        return self.op(op, [x], op.lower(), axes=[1], keepdims=keepdims)

    # -- statistics (kernels.stats) -------------------------------------------------------------------
    def peak(self, sig_name: str, stat: str) -> str:
        """One column (n, 1) of kernels.stats.peak_stats."""
        def build():
            s, tt = self.signal(sig_name), self.tt()
            k = ("peak", sig_name)
            i_min = self.memo_get(k + ("i_min",), lambda: self.op("ArgMin", [s], "imin", axis=1, keepdims=1))
            i_max = self.memo_get(k + ("i_max",), lambda: self.op("ArgMax", [s], "imax", axis=1, keepdims=1))
            vmin = self.memo_get(k + ("vmin",), lambda: self.at(s, i_min))
            vmax = self.memo_get(k + ("vmax",), lambda: self.at(s, i_max))
            t_min = self.memo_get(k + ("t_min",), lambda: self.at(tt, i_min))
            t_max = self.memo_get(k + ("t_max",), lambda: self.at(tt, i_max))
            dt = self.gradient(tt)

            def psum(neg: bool) -> str:
                x = self.op("Neg", [s]) if neg else s
                return self.reduce("ReduceSum", self.op("Mul", [self.op("Relu", [x]), dt]), keepdims=1)

            sum_pos = self.memo_get(k + ("sum_pos",), lambda: psum(False))
            sum_neg = self.memo_get(k + ("sum_neg",), lambda: psum(True))
            dtp = self.memo_get(k + ("dt_peaks",), lambda: self.op("Sub", [t_max, t_min], "dtp"))
            table = {
                "min": lambda: vmin,
                "max": lambda: vmax,
                "t_min": lambda: t_min,
                "t_max": lambda: t_max,
                "dt_peaks": lambda: dtp,
                "abs_dt_peaks": lambda: self.op("Abs", [dtp]),
                "range": lambda: self.op("Sub", [vmax, vmin], "range"),
                "peak_asym": lambda: self.op("Sub", [self.op("Abs", [vmax]), self.op("Abs", [vmin])], "asym"),
                "sum_pos": lambda: sum_pos,
                "sum_neg": lambda: sum_neg,
                "pos_minus_neg": lambda: self.op("Sub", [sum_pos, sum_neg], "pmn"),
                "duration": lambda: self.memo_get("duration", lambda: self.cols(tt, self.m - 1)),
            }
            if stat not in table:
                raise KeyError(stat)
            return table[stat]()
        return self.memo_get(("peakstat", sig_name, stat), build)

    def segments(self, sig_name: str, n_segments: int) -> str:
        """kernels.stats.segment_stats (n, 4 * n_segments): per part max, min, mean, slope."""
        from pdrlearn.kernels.stats import _edges

        def build():
            s, t = self.signal(sig_name), self.channel("t_s")
            a, b, mean = _edges(self.m, n_segments)
            width = int(max(b - a))
            # each part's indices, padded with its own last index (max/min unchanged)
            idx = np.array([list(range(i, j)) + [j - 1] * (width - (j - i)) for i, j in zip(a, b, strict=True)])
            parts = self.op("Gather", [s, self.const(idx, "segidx", np.int64)], "parts", axis=1)  # (n, k, w)
            mx = self.op("ReduceMax", [parts], "segmax", axes=[2], keepdims=1)
            mn = self.op("ReduceMin", [parts], "segmin", axes=[2], keepdims=1)
            three = self.const(np.array([-1, n_segments, 1], np.int64), "shape3", np.int64)
            mu = self.op("Reshape", [self.op("MatMul", [s, self.const(mean, "segmean")]), three])
            span = self.op("Sub", [self.cols(t, b - 1), self.cols(t, a)], "span")
            pos = self.op("Greater", [span, self.const(np.array(0.0), "zero")])
            span = self.op("Where", [pos, span, self.const(np.array(np.inf), "inf")])
            slope = self.op("Div", [self.op("Sub", [self.cols(s, b - 1), self.cols(s, a)]), span], "slope")
            slope = self.op("Reshape", [slope, three])
            inter = self.op("Concat", [mx, mn, mu, slope], "seg4", axis=2)  # (n, k, 4)
            return self.op("Reshape", [inter, self.const(np.array([-1, 4 * n_segments], np.int64), "shape2",
                                                         np.int64)], "seg")
        return self.memo_get(("seg", sig_name, int(n_segments)), build)

    def interp(self, q: str, x: str, y: str) -> str:
        """``np.interp`` of each row: queries q (n, k) on the row's grid x (n, m) (increasing) -> (n, k)."""
        m = self.m
        q3 = self.op("Unsqueeze", [q, self.const(np.array([2], np.int64), "ax2", np.int64)])  # (n, k, 1)
        x3 = self.op("Unsqueeze", [x, self.const(np.array([1], np.int64), "ax1", np.int64)])  # (n, 1, m)
        le = self.op("Cast", [self.op("LessOrEqual", [x3, q3])], "le", to=TensorProto.INT64)
        cnt = self.op("ReduceSum", [le, self.const(np.array([2], np.int64), "ax2", np.int64)], "cnt", keepdims=0)
        j = self.op("Clip", [self.op("Sub", [cnt, self.const(np.array(1, np.int64), "one", np.int64)]),
                             self.const(np.array(0, np.int64), "zero_i", np.int64),
                             self.const(np.array(m - 2, np.int64), "m2", np.int64)], "j")
        j1 = self.op("Add", [j, self.const(np.array(1, np.int64), "one", np.int64)], "j1")
        xj, xj1, yj, yj1 = self.at(x, j), self.at(x, j1), self.at(y, j), self.at(y, j1)
        slope = self.op("Div", [self.op("Sub", [yj1, yj]), self.op("Sub", [xj1, xj])], "islope")
        v = self.op("Add", [self.op("Mul", [slope, self.op("Sub", [q, xj])]), yj], "iv")  # numpy's order
        # np.interp returns the last value exactly at (and past) the grid's end
        last = self.op("GreaterOrEqual", [q, self.cols(x, m - 1)])
        return self.op("Where", [last, self.cols(y, m - 1), v], "interp")

    def force(self, stat: str, zero_fraction: float, sample_s: float = 0.05) -> str:
        """One column (n, 1) of kernels.stats.force_stats (thesis Table 29, ch. 6.3.1)."""
        def build():
            f, tt = self.signal("force"), self.tt()
            m = self.m
            peak = self.op("ReduceMax", [f], "fpeak", axes=[1], keepdims=1)
            pos = self.op("Greater", [peak, self.const(np.array(0.0), "zero")])
            ref = self.op("Where", [pos, peak, self.const(np.array(1.0), "onef")])
            zero = self.op("Less", [f, self.op("Mul", [self.const(np.array(zero_fraction), "zf"), ref])], "zero")
            zf = self.op("Cast", [zero], "zerof", to=TensorProto.DOUBLE)
            any_zero = self.op("Greater", [self.op("ReduceMax", [zf], "anyz", axes=[1], keepdims=1),
                                           self.const(np.array(0.0), "zero")])
            i_fmin = self.op("ArgMin", [f], "ifmin", axis=1, keepdims=1)
            last_zero = self.op("Where", [any_zero, self.op("ArgMax", [zf], "lz", axis=1, keepdims=1,
                                                            select_last_index=1), i_fmin])
            first_zero = self.op("Where", [any_zero, self.op("ArgMax", [zf], "fz", axis=1, keepdims=1), i_fmin])
            after = self.op("GreaterOrEqual", [self.const(np.arange(m)[None, :], "arange", np.int64), last_zero])
            masked = self.op("Where", [after, f, self.const(np.array(-np.inf), "ninf")])
            i_peak = self.op("ArgMax", [masked], "ipeak", axis=1, keepdims=1)
            t_last, t_peak, t_first = self.at(tt, last_zero), self.at(tt, i_peak), self.at(tt, first_zero)
            q = self.op("Concat", [
                self.op("Sub", [t_peak, self.const(np.array(4 * sample_s), "s4")]),
                self.op("Add", [t_peak, self.const(np.array(4 * sample_s), "s4")]),
                self.op("Add", [t_last, self.const(np.array(2 * sample_s), "s2")]),
                self.op("Sub", [t_first, self.const(np.array(2 * sample_s), "s2")]),
            ], "q", axis=1)
            dur = self.cols(tt, m - 1)
            q = self.op("Min", [self.op("Max", [q, self.const(np.array(0.0), "zero")]), dur], "qc")  # interp_rows' clip
            v = self.interp(q, tt, f)
            out = {
                "air_time": lambda: self.reduce("ReduceSum", self.op("Mul", [zf, self.gradient(tt)]), keepdims=1),
                "time_to_peak": lambda: self.op("Sub", [t_peak, t_last], "ttp"),
                "peak_mean_4": lambda: self.op("Mul", [self.op("Add", [self.cols(v, 0), self.cols(v, 1)]),
                                                       self.const(np.array(0.5), "half")]),
                "contact_force_2": lambda: self.cols(v, 2),
                "takeoff_force": lambda: self.cols(v, 3),
            }
            if stat not in out:
                raise KeyError(stat)
            return out[stat]()
        return self.memo_get(("force", stat, float(zero_fraction)), build)

    def yaw_sign(self) -> str:
        """kernels.stats.positive_net_rotation of the waist yaw rate (n, 1)."""
        def build():
            t = self.channel("t_s")
            total = self.reduce("ReduceSum", self.op("Mul", [self.signal("waist_yaw"), self.gradient(t)]),
                                keepdims=1)
            return self.op("Cast", [self.op("Greater", [total, self.const(np.array(0.0), "zero")])], "yawsign",
                           to=TensorProto.DOUBLE)
        return self.memo_get("yaw_sign", build)

    def yaw(self, stat: str) -> str:
        """kernels.stats.yaw_stats of the waist yaw rate's peak statistics (n, 1)."""
        def build():
            rng, dur, left = (self.peak("waist_yaw", s) for s in ("range", "duration", "t_max"))
            table = {
                "amplitude": lambda: self.op("Mul", [rng, self.const(np.array(0.5), "half")]),
                "duration": lambda: dur,
                "left": lambda: left,
                "right": lambda: self.op("Sub", [dur, left]),
                "left_minus_right": lambda: self.op("Sub", [self.op("Mul", [left, self.const(np.array(2.0), "two")]),
                                                            dur]),
            }
            if stat not in table:
                raise KeyError(stat)
            return table[stat]()
        return self.memo_get(("yaw", stat), build)

    def features(self, recipe: list) -> str:
        """The feature matrix (n, F) of a recipe, columns in recipe order."""
        cols = []
        for item in recipe:
            op = item[0]
            if op == "peak":
                cols.append(self.peak(item[1], item[2]))
            elif op == "segments":
                cols.append(self.segments(item[1], int(item[2])))
            elif op == "force":
                cols.append(self.force(item[1], float(item[2])))
            elif op == "yaw_sign":
                cols.append(self.yaw_sign())
            elif op == "yaw":
                cols.append(self.yaw(item[1]))
            else:
                raise KeyError(op)
        return cols[0] if len(cols) == 1 else self.op("Concat", cols, "features", axis=1)

    # -- models -------------------------------------------------------------------------------------
    def inline(self, model: onnx.ModelProto, prefix: str, x: str, output: str) -> str:
        """Inline a model's graph with its input bound to tensor ``x``; returns its ``output`` tensor."""
        p = onnx.compose.add_prefix(model, prefix)
        g = p.graph
        inp = g.input[0].name
        for node in g.node:
            node.input[:] = [x if i == inp else i for i in node.input]
            self.nodes.append(node)
        self.inits.extend(g.initializer)
        return prefix + output


def _leaf_models(entry: dict) -> list[dict]:
    if entry.get("type") == "fusion":
        return [leaf for e in entry["members"].values() for leaf in _leaf_models(e)]
    return [entry]


def _translatable(entry: dict, onnx_models: dict) -> bool:
    for leaf in _leaf_models(entry):
        if leaf.get("type") != "onnx" or leaf.get("file") not in onnx_models:
            return False
        if any(item[0] not in GRAPH_OPS for item in leaf["features"]):
            return False
        if "proba" not in leaf.get("outputs", {}) and "logits" not in leaf.get("outputs", {}):
            return False
    return True


def build_step_graph(tasks: dict, onnx_models: dict[str, onnx.ModelProto], features: dict
                     ) -> tuple[onnx.ModelProto, dict] | None:
    """The bundle's step graph and its manifest entry, or None when no task's chosen model translates.

    Parameters
    ----------
    tasks : the manifest's ``tasks`` (classes, chosen method/unit, model entries).
    onnx_models : relative path -> the bundle's per-model ONNX graphs.
    features : the manifest's ``features`` (channels, signal table, n_samples).
    """
    ci = {c: i for i, c in enumerate(features["channels"])}
    b = _Builder(int(features["n_samples"]), ci, features["signals"])
    b.onnx_models = onnx_models
    outputs: dict[str, str] = {}
    out_infos = []
    for task, spec in tasks.items():
        ch = spec.get("chosen") or {}
        entry = spec["methods"].get(ch.get("method"), {}).get(ch.get("unit"))
        if entry is None or not _translatable(entry, onnx_models):
            continue
        n_nodes, n_inits, memo = len(b.nodes), len(b.inits), dict(b.memo)
        try:
            p = _entry_proba(b, entry, list(spec["classes"]), f"{task}_")
        except KeyError as exc:  # a recipe statistic without a translation: per-model path for this task
            log.info("step graph: task %s left to the per-model path (%s)", task, exc)
            del b.nodes[n_nodes:], b.inits[n_inits:]
            b.memo = memo
            continue
        name = f"proba_{task}"
        b.nodes.append(helper.make_node("Identity", [p], [name]))
        outputs[task] = name
        out_infos.append(helper.make_tensor_value_info(name, TensorProto.DOUBLE, [None, len(spec["classes"])]))
    if not outputs:
        return None
    domains = {"": OPSET}
    for m in onnx_models.values():
        for o in m.opset_import:
            if o.domain not in ("", "ai.onnx"):
                domains[o.domain] = max(domains.get(o.domain, 0), o.version)
    g = helper.make_graph(
        b.nodes, "pdrlearn_step",
        [helper.make_tensor_value_info(INPUT, TensorProto.DOUBLE, [None, len(ci), b.m])],
        out_infos, initializer=b.inits,
    )
    model = helper.make_model(g, opset_imports=[helper.make_opsetid(d, v) for d, v in domains.items()],
                              producer_name="pdrlearn")
    model.ir_version = 8
    onnx.checker.check_model(model, full_check=True)
    spec = {"input": INPUT, "dtype": "float64", "outputs": outputs,
            "channels": [features["channels"][j] for j in sorted(b.used_channels)]}
    return model, spec


def _entry_proba(b: _Builder, entry: dict, classes: list[str], prefix: str) -> str:
    """Probabilities (n, len(classes)) of a model entry, aligned to ``classes`` (kernels.proba)."""
    if entry["type"] == "fusion":
        probas = [_entry_proba(b, e, list(entry["classes"]), f"{prefix}{u}_")
                  for u, e in entry["members"].items()]
        w = np.asarray(entry["weights"], dtype=float)
        acc = None
        for wi, p in zip(w, probas, strict=True):  # soft_vote: sum(w_i p_i) / sum(w), rows renormalised
            term = b.op("Mul", [b.const(np.array(wi), "w"), p])
            acc = term if acc is None else b.op("Add", [acc, term])
        fused = b.op("Div", [acc, b.const(np.array(max(w.sum(), 1e-12)), "wsum")], "fused")
        tot = b.op("Clip", [b.reduce("ReduceSum", fused, keepdims=1), b.const(np.array(1e-12), "eps")])
        p = b.op("Div", [fused, tot], "vote")
        return _align(b, p, list(entry["classes"]), classes)
    x = b.features(entry["features"])
    outs = entry["outputs"]
    model = b.onnx_models[entry["file"]]
    if "proba" in outs:
        p = b.inline(model, f"{prefix}m_", x, outs["proba"])
    else:
        p = b.op("Softmax", [b.inline(model, f"{prefix}m_", x, outs["logits"])], "softmax", axis=1)
    return _align(b, p, list(entry["classes"]), classes)


def _align(b: _Builder, p: str, model_classes: list[str], classes: list[str]) -> str:
    """kernels.proba.align_proba as a 0/1 matrix product (exact: each column copies one input column)."""
    if model_classes == classes:
        return p
    A = np.zeros((len(model_classes), len(classes)))
    for j, c in enumerate(model_classes):
        A[j, classes.index(c)] = 1.0
    return b.op("MatMul", [p, b.const(A, "align")], "aligned")


def features_graph(recipe: list, features: dict) -> onnx.ModelProto:
    """A graph ``W -> features (n, F)`` of one recipe alone (tests pin it to the numpy recipe path)."""
    ci = {c: i for i, c in enumerate(features["channels"])}
    b = _Builder(int(features["n_samples"]), ci, features["signals"])
    x = b.features(recipe)
    b.nodes.append(helper.make_node("Identity", [x], ["F"]))
    g = helper.make_graph(b.nodes, "pdrlearn_features",
                          [helper.make_tensor_value_info(INPUT, TensorProto.DOUBLE, [None, len(ci), b.m])],
                          [helper.make_tensor_value_info("F", TensorProto.DOUBLE, [None, None])], initializer=b.inits)
    model = helper.make_model(g, opset_imports=[helper.make_opsetid("", OPSET)], producer_name="pdrlearn")
    model.ir_version = 8
    onnx.checker.check_model(model, full_check=True)
    return model
