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
#: kernels.stats.force_stats' statistics
FORCE_STATS = ("air_time", "time_to_peak", "peak_mean_4", "contact_force_2", "takeoff_force")
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

    def block_diag(self, blocks: list[np.ndarray], hint: str) -> str:
        """Block-diagonal matrix of 2-D ``blocks``: each block padded with zero columns to its place, the
        rows concatenated. The nodes read only initializers, so onnxruntime folds them into one constant
        when the session is created, and the file stores the blocks without their zeros (decision E13)."""
        if len(blocks) == 1:
            return self.const(blocks[0], hint)
        width = sum(x.shape[1] for x in blocks)
        rows, c = [], 0
        for x in blocks:
            pads = np.array([0, c, 0, width - c - x.shape[1]], np.int64)
            rows.append(self.op("Pad", [self.const(x, hint), self.const(pads, "pads", np.int64)], hint))
            c += x.shape[1]
        return self.op("Concat", rows, hint, axis=0)

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
            # one product with a difference matrix: each output sums two exact terms (+-t or +-t/2) and
            # zeros, so it rounds once, like the differences it stands for
            m = self.m
            G = np.zeros((m, m))
            G[0, 0], G[1, 0], G[m - 2, m - 1], G[m - 1, m - 1] = -1.0, 1.0, -1.0, 1.0
            k = np.arange(1, m - 1)
            G[k - 1, k], G[k + 1, k] = -0.5, 0.5
            return self.op("MatMul", [t, self.const(G, "gradmat")], "grad")
        return self.memo_get(("grad", t), build)

    def reduce(self, op: str, x: str, keepdims: int = 0) -> str:
        """Reduction over axis 1 (opset 17: ReduceSum takes axes as an input, the others as an attribute)."""
        if op == "ReduceSum":
            return self.op(op, [x, self.const(np.array([1], np.int64), "ax", np.int64)], "sum", keepdims=keepdims)
        return self.op(op, [x], op.lower(), axes=[1], keepdims=keepdims)

    # -- statistics (kernels.stats), batched over the signals that share them -------------------------
    def stack(self, names: list[str]) -> str:
        """Signals side by side: (n, len(names), m)."""
        def build():
            if all(len(self.signals[nm][0]) == 1 for nm in names):  # one Gather (and one sign product)
                idx = [self.ci[self.signals[nm][0][0]] for nm in names]
                self.used_channels.update(idx)
                x = self.op("Gather", [INPUT, self.const(np.array(idx, np.int64), "chs", np.int64)], "stack", axis=1)
                sign = np.array([float(self.signals[nm][1]) for nm in names])
                if np.all(sign == 1.0):
                    return x
                return self.op("Mul", [x, self.const(sign[None, :, None], "signs")], "stack")
            ax1 = self.const(np.array([1], np.int64), "ax1", np.int64)
            return self.op("Concat", [self.op("Unsqueeze", [self.signal(nm), ax1]) for nm in names], "stack", axis=1)
        return self.memo_get(("stack", tuple(names)), build)

    def segment_block(self, names: list[str], n_segments: int) -> tuple[str, list]:
        """kernels.stats.segment_stats of each signal: a tensor (n, len(names) * 4 * n_segments) and the
        kernel column (``4 * part + stat``, stats max/min/mean/slope) of each of its columns. The columns
        are per signal ``[max_1..max_S, min_1..min_S, mean_1..mean_S, slope_1..slope_S]``: the models'
        Gathers pick them in recipe order, so the block needs no per-part interleaving (decision E16).
        Differences of two samples (the slope's rise and the part's time span) are one product with a
        +-1 matrix each: every output sums one exact ``+x`` and one exact ``-y`` term and zeros, so it
        rounds once, like the subtraction it replaces (two Gathers and a Sub, E16)."""
        from pdrlearn.kernels.stats import _edges

        x = self.stack(names)
        a, b, mean = _edges(self.m, n_segments)
        width = int(max(b - a))
        # each part's indices, padded with its own last index (max/min unchanged)
        idx = np.array([list(range(i, j)) + [j - 1] * (width - (j - i)) for i, j in zip(a, b, strict=True)])
        parts = self.op("Gather", [x, self.const(idx, "segidx", np.int64)], "parts", axis=2)  # (n, k, S, w)
        mx = self.op("ReduceMax", [parts], "segmax", axes=[3], keepdims=0)  # (n, k, S)
        mn = self.op("ReduceMin", [parts], "segmin", axes=[3], keepdims=0)
        mu = self.op("MatMul", [x, self.const(mean, "segmean")], "segmu")
        D = np.zeros((self.m, n_segments))  # column s: sample b_s - 1 minus sample a_s
        D[b - 1, np.arange(n_segments)] += 1.0
        D[a, np.arange(n_segments)] -= 1.0
        D = self.const(D, "segdiff")
        rise = self.op("MatMul", [x, D], "rise")  # (n, k, S)
        span = self.memo_get(("segspan", n_segments), lambda: self._span(D))  # (n, 1, S)
        slope = self.op("Div", [rise, span], "slope")
        inter = self.op("Concat", [mx, mn, mu, slope], "seg4", axis=2)  # (n, k, 4 S)
        shape = self.const(np.array([-1, len(names) * 4 * n_segments], np.int64), "shape", np.int64)
        order = [4 * p + st for _ in names for st in range(4) for p in range(n_segments)]
        return self.op("Reshape", [inter, shape], "seg"), order

    def _span(self, D: str) -> str:
        """Time span of each segment (n, 1, S), +inf for a one-sample part (the slope is then 0)."""
        j = self.ci["t_s"]
        self.used_channels.add(j)
        t = self.op("Gather", [INPUT, self.const(np.array([j], np.int64), "chs", np.int64)], "t3", axis=1)
        span = self.op("MatMul", [t, D], "span")
        pos = self.op("Greater", [span, self.const(np.array(0.0), "zero")])
        return self.op("Where", [pos, span, self.const(np.array(np.inf), "inf")], "span")

    def peak_block(self, names: list[str], stats: list[str]) -> dict[str, str]:
        """kernels.stats.peak_stats of each signal: stat -> (n, len(names)) (``duration``: (n, 1))."""
        x, tt = self.stack(names), self.tt()
        k: dict[str, str] = self.memo.setdefault(("peakblock", tuple(names)), {})

        def get(stat: str) -> str:
            if stat in k:
                return k[stat]
            if stat in ("i_min", "i_max"):
                v = self.op("ArgMin" if stat == "i_min" else "ArgMax", [x], stat, axis=2, keepdims=0)
            elif stat in ("min", "max"):  # the extreme's value (= x at its first index)
                v = self.op("ReduceMin" if stat == "min" else "ReduceMax", [x], stat, axes=[2], keepdims=0)
            elif stat in ("t_min", "t_max"):
                v = self.at(tt, get("i" + stat[1:]))
            elif stat in ("sum_pos", "sum_neg"):  # time integral of the positive part / |negative part|
                xx = self.op("Relu", [x if stat == "sum_pos" else self.op("Neg", [x])])
                dt = self.op("Unsqueeze", [self.gradient(tt), self.const(np.array([1], np.int64), "ax1", np.int64)])
                v = self.op("ReduceSum", [self.op("Mul", [xx, dt]), self.const(np.array([2], np.int64), "ax2",
                                                                               np.int64)], stat, keepdims=0)
            elif stat == "dt_peaks":
                v = self.op("Sub", [get("t_max"), get("t_min")], stat)
            elif stat == "abs_dt_peaks":
                v = self.op("Abs", [get("dt_peaks")])
            elif stat == "range":
                v = self.op("Sub", [get("max"), get("min")], stat)
            elif stat == "peak_asym":
                v = self.op("Sub", [self.op("Abs", [get("max")]), self.op("Abs", [get("min")])], stat)
            elif stat == "pos_minus_neg":
                v = self.op("Sub", [get("sum_pos"), get("sum_neg")], stat)
            elif stat == "duration":
                v = self.memo_get("duration", lambda: self.cols(tt, self.m - 1))
            else:
                raise KeyError(stat)
            k[stat] = v
            return v

        return {st: get(st) for st in stats}

    def prepare(self, recipes: list[list]) -> None:
        """Compute every column the recipes use, once, into one matrix ``(n, F)`` (few, batched nodes)."""
        seg: dict[int, list[str]] = {}
        peak_sigs: list[str] = []
        peak_stats: list[str] = []  # asked for by "peak" items
        force: dict[float, list[str]] = {}
        yaw: list[str] = []
        sign = False
        for recipe in recipes:
            for item in recipe:
                op = item[0]
                if op == "segments":
                    seg.setdefault(int(item[2]), [])
                    if item[1] not in seg[int(item[2])]:
                        seg[int(item[2])].append(item[1])
                elif op == "peak":
                    peak_sigs += [item[1]] if item[1] not in peak_sigs else []
                    peak_stats += [item[2]] if item[2] not in peak_stats else []
                elif op == "force":
                    force.setdefault(float(item[2]), [])
                    force[float(item[2])] += [item[1]] if item[1] not in force[float(item[2])] else []
                elif op == "yaw":
                    yaw += [item[1]] if item[1] not in yaw else []
                elif op == "yaw_sign":
                    sign = True
                else:
                    raise KeyError(op)
        blocks: list[tuple[str, list]] = []  # (tensor, the key of each of its columns)
        for n_seg, names in seg.items():
            seg_t, order = self.segment_block(names, n_seg)
            nms = [nm for nm in names for _ in range(4 * n_seg)]
            blocks.append((seg_t, [("seg", nm, n_seg, j) for nm, j in zip(nms, order, strict=True)]))
        yaw_need = {"amplitude": ["range"], "duration": ["duration"], "left": ["t_max"],
                    "right": ["duration", "t_max"], "left_minus_right": ["duration", "t_max"]}
        if yaw:
            if any(s not in yaw_need for s in yaw):
                raise KeyError(next(s for s in yaw if s not in yaw_need))
            peak_sigs += ["waist_yaw"] if "waist_yaw" not in peak_sigs else []
        if peak_stats:
            stats = self.peak_block(peak_sigs, peak_stats)
            for st in peak_stats:
                keys = [("duration",)] if st == "duration" else [("peak", nm, st) for nm in peak_sigs]
                blocks.append((stats[st], keys))
        if yaw:
            j = self.const(np.array([peak_sigs.index("waist_yaw")], np.int64), "idx", np.int64)
            one = peak_sigs == ["waist_yaw"]  # the block's statistics are already its (n, 1) columns (E18)
            st = {s: self.op("Gather", [v, j], s, axis=1) if s != "duration" and not one else v
                  for s, v in self.peak_block(peak_sigs, sorted({s for y in yaw for s in yaw_need[y]})).items()}
            table = {  # kernels.stats.yaw_stats (thesis Table 31, ch. 6.3.1)
                "amplitude": lambda: self.op("Mul", [st["range"], self.const(np.array(0.5), "half")]),
                "duration": lambda: st["duration"],
                "left": lambda: st["t_max"],
                "right": lambda: self.op("Sub", [st["duration"], st["t_max"]]),
                "left_minus_right": lambda: self.op("Sub", [
                    self.op("Mul", [st["t_max"], self.const(np.array(2.0), "two")]), st["duration"]]),
            }
            for y in yaw:
                blocks.append((table[y](), [("yaw", y)]))
        if sign:
            blocks.append((self.yaw_sign(), [("yaw_sign",)]))
        for zf, stats in force.items():
            if any(st not in FORCE_STATS for st in stats):
                raise KeyError(next(st for st in stats if st not in FORCE_STATS))
            blocks += self.force_block(stats, zf)
        keys = [key for _, ks in blocks for key in ks]
        self.index = {key: i for i, key in enumerate(keys) if key is not None}
        self.n_cols = len(keys)
        self.all = blocks[0][0] if len(blocks) == 1 else self.op("Concat", [t for t, _ in blocks], "all", axis=1)

    def features(self, recipe: list) -> str:
        """The feature matrix (n, F) of a recipe (columns in recipe order) from the prepared matrix."""
        cols = self.feature_cols(recipe)
        if cols == list(range(self.n_cols)):
            return self.all
        return self.cols(self.all, cols)

    def feature_cols(self, recipe: list) -> list[int]:
        """Columns of the prepared matrix that a recipe reads, in recipe order."""
        cols: list[int] = []
        for item in recipe:
            op = item[0]
            if op == "segments":
                cols += [self.index[("seg", item[1], int(item[2]), j)] for j in range(4 * int(item[2]))]
            elif op == "peak":
                cols.append(self.index[("duration",) if item[2] == "duration" else ("peak", item[1], item[2])])
            elif op == "force":
                cols.append(self.index[("force", item[1], float(item[2]))])
            elif op == "yaw":
                cols.append(self.index[("yaw", item[1])])
            else:
                cols.append(self.index[("yaw_sign",)])
        return cols

    def signal3(self, name: str) -> str:
        """A derived signal as (n, 1, m) (``signal``'s Adds on (n, 1, m) channel Gathers; decision E19)."""
        def build():
            chans, sign = self.signals[name][0], float(self.signals[name][1])
            ix = [self.ci[c] for c in chans]
            self.used_channels.update(ix)
            ch = [self.op("Gather", [INPUT, self.const(np.array([j], np.int64), "chs", np.int64)], c, axis=1)
                  for c, j in zip(chans, ix, strict=True)]
            out = ch[0]
            for c in ch[1:]:
                out = self.op("Add", [out, c], name)
            return out if sign == 1.0 else self.op("Mul", [out, self.const(np.array(sign), "sign")], name)
        return self.memo_get(("sig3", name), build)

    def tt3(self) -> str:
        """``tt`` as (n, 1, m)."""
        return self.memo_get("tt3", lambda: self.op(
            "Unsqueeze", [self.tt(), self.const(np.array([1], np.int64), "ax1", np.int64)], "tt3"))

    def interp(self, q: str, k: int, y: str) -> str:
        """``np.interp`` of each row: k queries q (n, k) on the grid ``tt`` (n, m) with values y (n, m) -> (n, k).
        The queries must lie in ``[0, duration]`` (the force statistics clip them to the window).

        Decision E19: every index is a count of grid points at or below the query, so one LessOrEqual, one
        product with a 0/1 count matrix and one GatherElements on ``[tt | y]`` fetch all of them. The
        interval ``a`` is the number of inner grid points ``tt[1..m-2]`` at or below q (E16) and ``a + 1``
        the number of ``tt[0..m-2]`` (``tt[0] = 0 <= q``); the ``y`` entries sit ``m`` further on, which
        the always-counted ``tt[0]`` adds with weight ``m``. The value is ``slope (q - x_b) + y_b`` with
        numpy's slope ``(y[a+1] - y[a]) / (x[a+1] - x[a])`` and ``b`` the number of ``tt[1..m-1]`` at or
        below q: ``b = a`` inside the grid (numpy's formula, in its order), and at the grid's end
        (``q = tt[m-1]``) ``b = m - 1`` gives ``slope * (+0) + y[m-1] = y[m-1]``, np.interp's end rule,
        without a Where. One product with a 0/+-1 matrix gives the two differences (one exact ``+u`` and one
        exact ``-v`` term each, so one rounding, like a Sub) and passes ``x_b`` and ``y_b`` through, and one
        Split names the four."""
        m = self.m
        q3 = self.op("Unsqueeze", [q, self.const(np.array([2], np.int64), "ax2", np.int64)])  # (n, k, 1)
        le = self.op("Cast", [self.op("LessOrEqual", [self.tt3(), q3])], "le", to=TensorProto.DOUBLE)  # (n, k, m)
        inner, head, full = np.zeros(m, np.int64), np.zeros(m, np.int64), np.zeros(m, np.int64)
        inner[1:m - 1], head[0:m - 1], full[1:m] = 1, 1, 1  # counts a, a + 1, b
        first = np.eye(m, dtype=np.int64)[0]
        C = np.stack([inner, head, full] + [c + m * first for c in (inner, head, full)], axis=1)  # (m, 6)
        # (n, k, 6) exact small integers (a double product costs less than an int64 one), then int64 indices
        cnt = self.op("Cast", [self.op("MatMul", [le, self.const(C, "icount")], "icount")], "icount",
                      to=TensorProto.INT64)
        idx = self.op("Reshape", [cnt, self.const(np.array([-1, 6 * k], np.int64), "shape", np.int64)], "iidx")
        xy = self.op("Concat", [self.tt(), y], "xy", axis=1)  # (n, 2 m)
        vals = self.op("GatherElements", [xy, idx], "ivals", axis=1)  # per query x_a, x_a+1, x_b, y_a, y_a+1, y_b
        D = np.zeros((6 * k, 4 * k))
        for j in range(k):
            o = 6 * j
            D[o + 4, j], D[o + 3, j] = 1.0, -1.0  # y[a+1] - y[a]
            D[o + 1, k + j], D[o, k + j] = 1.0, -1.0  # x[a+1] - x[a]
            D[o + 2, 2 * k + j] = D[o + 5, 3 * k + j] = 1.0  # x_b, y_b
        parts = self.op("MatMul", [vals, self.const(D, "idiff")], "idiff")
        dy, dx, xb, yb = (self.name(nm) for nm in ("dy", "dx", "xb", "yb"))
        self.nodes.append(helper.make_node("Split", [parts], [dy, dx, xb, yb], axis=1))  # 4 equal parts
        slope = self.op("Div", [dy, dx], "islope")
        return self.op("Add", [self.op("Mul", [slope, self.op("Sub", [q, xb])]), yb], "iv")  # numpy's order

    def force_block(self, stats: list[str], zero_fraction: float, sample_s: float = 0.05) -> list[tuple[str, list]]:
        """kernels.stats.force_stats (thesis Table 29, ch. 6.3.1) of the statistics ``stats``: tensors and the
        key of each of their columns (None = a column no recipe reads).

        Only the instants the asked statistics need are gathered and interpolated (decision E16), with few
        nodes (decision E19). The force is (n, 1, m) (one Gather and one ReduceSum of its two channels).
        The last and the first zero sample, each with the kernel's fallback (``argmin(force)`` when no
        sample is zero), come from one ArgMax over the rows ``Where(zero, score, -force)``: the score of a
        zero sample is ``k + 1`` (last zero) or ``m - k`` (first zero), at least 1, and a sample that is not
        zero has ``force >= zero_fraction * ref >= 0``, so ``-force <= 0`` is below every score. With a zero
        sample the ArgMax is the zero sample of the highest score (distinct), and without one it is
        numpy's first ``argmin(force)``. The contact peak is the first maximum of the force from the last
        zero on. One GatherElements takes the times at these instants, and one product with a 0/+-1 matrix
        plus one offset vector gives the interpolation queries and ``time_to_peak`` (each output one exact
        term, or one rounded difference, like the kernel's), which go through one interpolation.
        ``time_to_peak`` lies in ``[0, duration]`` (the peak is at or after the last zero), so the queries'
        clip leaves it unchanged; the clip at 0 is needed by the queries before an instant and the one at
        the duration by those after one.
        """
        if not zero_fraction >= 0.0:  # the ArgMax scores need a threshold >= 0
            raise KeyError(f"force zero fraction {zero_fraction}")
        key = lambda st: ("force", st, float(zero_fraction))  # noqa: E731
        m = self.m
        f, tt = self.signal3("force"), self.tt()  # (n, 1, m), (n, m)
        peak = self.op("ReduceMax", [f], "fpeak", axes=[2], keepdims=1)
        pos = self.op("Greater", [peak, self.const(np.array(0.0), "zero")])
        ref = self.op("Where", [pos, peak, self.const(np.array(1.0), "onef")])
        zero = self.op("Less", [f, self.op("Mul", [self.const(np.array(zero_fraction), "zf"), ref])], "zero")
        out: list[tuple[str, list]] = []
        if "air_time" in stats:
            zdt = self.op("Mul", [self.op("Cast", [zero], "zerof", to=TensorProto.DOUBLE), self.gradient(self.tt3())])
            out.append((self.op("ReduceSum", [zdt, self.const(np.array([2], np.int64), "ax2", np.int64)], "sum",
                                keepdims=0), [key("air_time")]))
        need_last = bool({"time_to_peak", "peak_mean_4", "contact_force_2"} & set(stats))
        need_peak = bool({"time_to_peak", "peak_mean_4"} & set(stats))
        need_first = "takeoff_force" in stats
        if not (need_last or need_first):
            return out
        ks = np.arange(m, dtype=np.float64)
        rows = (["last"] if need_last else []) + (["first"] if need_first else [])
        score = np.stack([ks + 1.0 if r == "last" else m - ks for r in rows])[None]  # (1, rows, m)
        negf = self.op("Neg", [f])
        idx = self.op("ArgMax", [self.op("Where", [zero, self.const(score, "zscore"), negf])], "izero", axis=2,
                      keepdims=0)  # (n, rows)
        if need_peak:  # each row's first maximum from its instant on (the "first" row's is not read)
            i3 = self.op("Unsqueeze", [idx, self.const(np.array([2], np.int64), "ax2", np.int64)])
            after = self.op("GreaterOrEqual", [self.const(np.arange(m)[None, None, :], "arange", np.int64), i3])
            masked = self.op("Where", [after, f, self.const(np.array(-np.inf), "ninf")])
            ipeak = self.op("ArgMax", [masked], "ipeak", axis=2, keepdims=0)
            idx = self.op("Concat", [idx, ipeak], "fidx", axis=1)
            rows = rows + ["peak" if r == "last" else "-" for r in rows]
        at = self.at(tt, idx)  # (n, len(rows))
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
        if (offs < 0).any():  # interp_rows' clip: a query before an instant can fall before the window
            q = self.op("Max", [q, self.const(np.array(0.0), "zero")], "qc")
        if (offs > 0).any():  # and one after an instant past its end
            q = self.op("Min", [q, self.memo_get("duration", lambda: self.cols(tt, m - 1))], "qc")
        out.append((q, [key(k) if k == "time_to_peak" else None for _, _, k in cols]))
        v = self.interp(q, len(cols), self.op("Reshape", [f, self.const(np.array([-1, m], np.int64), "shape",
                                                                               np.int64)], "force"))
        out.append((v, [None if k in (None, "time_to_peak") else key(k) for _, _, k in cols]))
        if "peak_mean_4" in stats:
            h = np.zeros((len(cols), 1))
            h[[c for c, (coef, o, k) in enumerate(cols) if k is None], 0] = 0.5  # 0.5 v0 + 0.5 v1, one rounding
            out.append((self.op("MatMul", [v, self.const(h, "pm4")], "pm4"), [key("peak_mean_4")]))
        return out

    def yaw_sign(self) -> str:
        """kernels.stats.positive_net_rotation of the waist yaw rate (n, 1)."""
        def build():
            t = self.channel("t_s")
            total = self.reduce("ReduceSum", self.op("Mul", [self.signal("waist_yaw"), self.gradient(t)]),
                                keepdims=1)
            return self.op("Cast", [self.op("Greater", [total, self.const(np.array(0.0), "zero")])], "yawsign",
                           to=TensorProto.DOUBLE)
        return self.memo_get("yaw_sign", build)

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


def build_step_graph(tasks: dict, onnx_models: dict[str, onnx.ModelProto], features: dict, *,
                     one_softmax: bool = True) -> tuple[onnx.ModelProto, dict] | None:
    """The bundle's step graph and its manifest entry, or None when no task's chosen model translates.

    Parameters
    ----------
    tasks : the manifest's ``tasks`` (classes, chosen method/unit, model entries).
    onnx_models : relative path -> the bundle's per-model ONNX graphs.
    features : the manifest's ``features`` (channels, signal table, n_samples).
    one_softmax : decision E19 (adopted): the network and SVM blocks share one scaler (Gather, Sub, Div, Split) and
        one Softmax (their classes padded to one width with a -1e300 score); False builds them apart as E13-E18 did
        (the same numbers bit for bit: the tests compare both; decision E251: a keyword, no module switch).
    """
    ci = {c: i for i, c in enumerate(features["channels"])}
    b = _Builder(int(features["n_samples"]), ci, features["signals"])
    b.onnx_models = onnx_models
    included: dict[str, dict] = {}
    for task, spec in tasks.items():
        ch = spec.get("chosen") or {}
        entry = spec["methods"].get(ch.get("method"), {}).get(ch.get("unit"))
        if entry is None or not _translatable(entry, onnx_models):
            continue
        entry = _pruned(entry)  # units with fusion weight 0 add exactly 0 (decision E13)
        try:  # a recipe statistic without a translation: the per-model path for this task
            _Builder(b.m, ci, features["signals"]).prepare([leaf["features"] for leaf in _leaf_models(entry)])
        except KeyError as exc:
            log.info("step graph: task %s left to the per-model path (%s)", task, exc)
            continue
        included[task] = entry
    if not included:
        return None
    b.prepare([leaf["features"] for e in included.values() for leaf in _leaf_models(e)])
    outputs = {task: f"proba_{task}" for task in included}
    _head(b, {task: (entry, list(tasks[task]["classes"])) for task, entry in included.items()}, outputs,
          one_softmax=one_softmax)
    out_infos = [helper.make_tensor_value_info(name, TensorProto.DOUBLE, [None, len(tasks[task]["classes"])])
                 for task, name in outputs.items()]
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
    # decision E69: ``input_channels`` = the rows of W in order (the window's whole channel layout, as
    # features.channels); ``channels`` = the rows the graph reads (the others may hold anything, NaN included)
    spec = {"input": INPUT, "dtype": "float64", "outputs": outputs,
            "input_channels": list(features["channels"]),
            "channels": [features["channels"][j] for j in sorted(b.used_channels)]}
    return model, spec


def _pruned(entry: dict) -> dict:
    """The entry without fusion members of weight 0 (``soft_vote`` adds them as exactly 0; at least one
    member is kept)."""
    if entry.get("type") != "fusion":
        return entry
    keep = [(u, e, w) for (u, e), w in zip(entry["members"].items(), entry["weights"], strict=True) if w != 0]
    if not keep:
        return entry
    return {**entry, "members": {u: _pruned(e) for u, e, _ in keep}, "weights": [w for _, _, w in keep]}


def _leaf_weights(entry: dict, classes: list[str], weight: float = 1.0) -> list[tuple[dict, float, list[int]]]:
    """Every ONNX leaf of an entry with its share of the task's soft vote (the product of the normalised
    fusion weights on its path) and, for each of its classes, the column of that class in ``classes``."""
    if entry.get("type") == "fusion":
        w = np.asarray(entry["weights"], dtype=float)
        total = max(float(w.sum()), 1e-12)
        return [leaf for (_, e), wi in zip(entry["members"].items(), w, strict=True)
                for leaf in _leaf_weights(e, classes, weight * float(wi) / total)]
    return [(entry, weight, [classes.index(c) for c in entry["classes"]])]


#: The torch networks' graph (pdrlearn.export.onnx_convert.torch_to_onnx of the project's MLP).
_MLP_OPS = ("Sub", "Div", "Gemm", "Tanh", "Gemm", "Softmax")


def _mlp_params(model: onnx.ModelProto) -> dict | None:
    """Weights of a one-hidden-layer network graph ``Softmax(Gemm(tanh(Gemm((X - mean) / scale))))``, or
    None when the graph has another form (it is then inlined unchanged)."""
    nodes = list(model.graph.node)
    if tuple(n.op_type for n in nodes) != _MLP_OPS:
        return None
    init = {i.name: numpy_helper.to_array(i) for i in model.graph.initializer}
    try:
        p = {"mean": init[nodes[0].input[1]], "scale": init[nodes[1].input[1]],
             "W1": init[nodes[2].input[1]], "b1": init[nodes[2].input[2]],
             "W2": init[nodes[4].input[1]], "b2": init[nodes[4].input[2]]}
    except (KeyError, IndexError):
        return None
    for g in (nodes[2], nodes[4]):
        a = {x.name: helper.get_attribute_value(x) for x in g.attribute}
        if a.get("alpha", 1.0) != 1.0 or a.get("beta", 1.0) != 1.0 or a.get("transA", 0) or not a.get("transB", 0):
            return None
    if any(v.dtype != np.float64 for v in p.values()):
        return None
    return p


#: The SVM decision graphs of pdrlearn.export.onnx_convert.svm_decision_to_onnx (rbf, poly/linear, mixed).
_SVM_OPS = {
    ("Sub", "Div", "MatMul", "Mul", "MatMul", "Mul", "Add", "Add", "Max", "Mul", "Exp", "MatMul", "Add", "Softmax"),
    ("Sub", "Div", "MatMul", "Mul", "Add", "Pow", "MatMul", "Add", "Softmax"),
    ("Sub", "Div", "MatMul", "Mul", "Add", "Pow", "Mul", "MatMul", "Mul", "Add", "Add", "Max", "Mul", "Exp", "Where",
     "MatMul", "Add", "Softmax"),
}


def _svm_params(model: onnx.ModelProto) -> dict | None:
    """Per-support-vector parameters of an SVM decision graph (``svm_decision_to_onnx``), or None."""
    if tuple(n.op_type for n in model.graph.node) not in _SVM_OPS:
        return None
    init = {i.name: numpy_helper.to_array(i) for i in model.graph.initializer}
    if not {"mean", "scale", "svT", "dual", "b"} <= set(init):
        return None
    n_sv = init["svT"].shape[1]
    rbf = "neg_gamma" in init
    poly = "degree" in init
    is_rbf = init["is_rbf"].astype(bool) if "is_rbf" in init else np.full(n_sv, rbf)
    return {"mean": init["mean"], "scale": init["scale"], "svT": init["svT"], "dual": init["dual"], "b": init["b"],
            "gamma": init["gamma"] if poly else np.ones(n_sv), "coef0": init["coef0"] if poly else np.zeros(n_sv),
            "degree": init["degree"] if poly else np.ones(n_sv),
            "neg_gamma": init["neg_gamma"] if rbf else np.zeros(n_sv),
            "sv_sq": init["sv_sq"].reshape(-1) if rbf else np.zeros(n_sv), "is_rbf": is_rbf}


def _svm_block(b: _Builder, leaves: list, svms: list[tuple[int, dict]], k: int | None = None,
               z: str | None = None) -> tuple[str, int]:
    """The SVM leaves as one graph (the formulas of ``svm_decision_to_onnx``): block-diagonal support
    vectors and dual coefficients, per-column kernel parameters; returns the probabilities
    ``(n, len(svms) * k)`` (classes padded to k with a -1e300 score) and k. With ``z`` (the scaled features,
    decision E19) it returns the scores ``(n, len(svms) * k)`` before the softmax, padded to ``k``."""
    scores_only = z is not None
    k = max(p["dual"].shape[1] for _, p in svms) if k is None else k
    if z is None:
        z = b.cols(b.all, _model_cols(b, leaves, svms))
        z = b.op("Sub", [z, b.const(np.concatenate([p["mean"] for _, p in svms]), "svm_mean")])
        z = b.op("Div", [z, b.const(np.concatenate([p["scale"] for _, p in svms]), "svm_scale")], "Z")
    dot = b.op("MatMul", [z, b.block_diag([p["svT"] for _, p in svms], "svT")], "dot")
    cat = {key: np.concatenate([p[key] for _, p in svms]) for key in ("gamma", "coef0", "degree", "neg_gamma",
                                                                      "sv_sq", "is_rbf")}
    kp = kr = None
    if not cat["is_rbf"].all():
        kp = b.op("Mul", [dot, b.const(cat["gamma"], "gamma")])
        kp = b.op("Add", [kp, b.const(cat["coef0"], "coef0")])
        if set(cat["degree"].tolist()) <= {1.0, 2.0}:  # t^2 = t * t, t^1 = t * 1: numpy's ** 2 and ** 1 exactly,
            # and no libm pow per column (E16); the factor t d + (1 - d) with d = 1 for degree 2, else 0, is t or
            # 1 exactly for finite t (t * 1 + 0, t * 0 + 1): two arithmetic nodes cost less than a Where (E18)
            d2 = (cat["degree"] == 2.0).astype(np.float64)
            sq = b.op("Add", [b.op("Mul", [kp, b.const(d2, "deg2")]), b.const(1.0 - d2, "deg1")])
            kp = b.op("Mul", [kp, sq], "K_poly")
        else:
            kp = b.op("Pow", [kp, b.const(cat["degree"], "degree")], "K_poly")
    if cat["is_rbf"].any():
        member = _block_diag([np.ones((len(p["mean"]), 1)) for _, p in svms])  # feature -> its model
        of_sv = np.repeat(np.arange(len(svms)), [p["svT"].shape[1] for _, p in svms])  # support vector -> model
        z_sq = b.op("MatMul", [b.op("Mul", [z, z]), b.const(member, "member")], "z_sq")  # |z|^2 of each model
        # each support vector's column takes its model's |z|^2: a product with a 0/1 matrix (one exact term
        # plus zeros per output, so the same value) costs less than a Gather of 387 int64 indices (E18)
        expand = np.zeros((len(svms), len(of_sv)))
        expand[of_sv, np.arange(len(of_sv))] = 1.0
        z_sq = b.op("MatMul", [z_sq, b.const(expand, "of_sv")], "z_sq")
        d2 = b.op("Add", [b.op("Add", [z_sq, b.op("Mul", [dot, b.const(np.array([-2.0]), "m2")])]),
                          b.const(cat["sv_sq"][None, :], "sv_sq")])
        d2 = b.op("Max", [d2, b.const(np.zeros(1), "zero")], "d2")
        kr = b.op("Exp", [b.op("Mul", [d2, b.const(cat["neg_gamma"], "neg_gamma")])], "K_rbf")
    K = kr if kp is None else kp if kr is None else b.op(
        "Where", [b.const(cat["is_rbf"], "is_rbf", bool), kr, kp], "K")
    dual = [np.hstack([p["dual"], np.zeros((len(p["dual"]), k - p["dual"].shape[1]))]) for _, p in svms]
    bias = np.concatenate([np.concatenate([p["b"], np.full(k - len(p["b"]), -1e300)]) for _, p in svms])
    scores = b.op("Add", [b.op("MatMul", [K, b.block_diag(dual, "dual")]), b.const(bias, "svm_b")], "scores")
    return (scores, k) if scores_only else (_grouped_softmax(b, scores, len(svms), k, "svm_proba"), k)


def _model_cols(b: _Builder, leaves: list, models: list[tuple[int, dict]]) -> list[int]:
    """The prepared matrix's columns that the models read, model after model."""
    return [c for i, _ in models for c in b.feature_cols(leaves[i][1]["features"])]


def _grouped_softmax(b: _Builder, x: str, groups: int, k: int, hint: str) -> str:
    """Softmax over each group of ``k`` columns of ``x (n, groups * k)``: one Softmax over (n, groups, k)."""
    x = b.op("Reshape", [x, b.const(np.array([-1, groups, k], np.int64), "shape", np.int64)])
    x = b.op("Softmax", [x], hint, axis=-1)
    return b.op("Reshape", [x, b.const(np.array([-1, groups * k], np.int64), "shape", np.int64)])


def _mlp_logits(b: _Builder, mlps: list[tuple[int, dict]], x: str, k: int) -> str:
    """The networks' logits ``(n, len(mlps) * k)`` from their scaled features ``x`` (one block-diagonal
    network, classes padded to k with a -1e300 logit; decision E13)."""
    x = b.op("Gemm", [x, b.block_diag([p["W1"] for _, p in mlps], "nn_W1"),
                      b.const(np.concatenate([p["b1"] for _, p in mlps]), "nn_b1")], "hidden", transB=1)
    x = b.op("Tanh", [x])
    W2 = [np.vstack([p["W2"], np.zeros((k - len(p["W2"]), p["W2"].shape[1]))]) for _, p in mlps]
    b2 = [np.concatenate([p["b2"], np.full(k - len(p["b2"]), -1e300)]) for _, p in mlps]
    return b.op("Gemm", [x, b.block_diag(W2, "nn_W2"), b.const(np.concatenate(b2), "nn_b2")], "logits", transB=1)


def _block_diag(blocks: list[np.ndarray]) -> np.ndarray:
    out = np.zeros((sum(x.shape[0] for x in blocks), sum(x.shape[1] for x in blocks)))
    r = c = 0
    for x in blocks:
        out[r:r + x.shape[0], c:c + x.shape[1]] = x
        r, c = r + x.shape[0], c + x.shape[1]
    return out


def _head(b: _Builder, tasks: dict[str, tuple[dict, list[str]]], outputs: dict[str, str], *,
          one_softmax: bool = True) -> None:
    """Every task's probabilities from the prepared feature matrix, in few nodes (decision E13).

    The networks of the project's form become one block-diagonal network (one Gather of all their
    features, one scaler, two Gemm, one Softmax over ``(n, networks, classes)``; missing classes of a
    smaller network are padded with a -1e300 logit, probability exactly 0), the SVM decision graphs one
    block of support vectors (:func:`_svm_block`); other models are inlined unchanged. One product
    with a head matrix then does every task's soft vote and class alignment
    (entries = the leaves' normalised fusion weights, :func:`pdrlearn.kernels.proba.soft_vote` without its
    final row renormalisation: the rows of softmax outputs already sum to 1, so the difference is
    rounding, <= 1e-15), and one Split names the outputs ``proba_<task>``.
    """
    leaves = [(task, leaf, w, cols) for task, (entry, classes) in tasks.items()
              for leaf, w, cols in _leaf_weights(entry, classes)]
    mlps = [(i, _mlp_params(b.onnx_models[leaf["file"]])) for i, (_, leaf, _, _) in enumerate(leaves)]
    mlps = [(i, p) for i, p in mlps if p is not None and "proba" in leaves[i][1]["outputs"]]
    mlps = mlps if len(mlps) > 1 else []  # one model alone: inlined (the block adds two Reshape)
    parts: list[tuple[str, list[tuple[int, int]]]] = []  # (tensor, (leaf, class) of each column)
    done = {i for i, _ in mlps}
    svms = [(i, _svm_params(b.onnx_models[leaf["file"]])) for i, (_, leaf, _, _) in enumerate(leaves)
            if i not in done and leaf.get("outputs", {}).get("proba") == "proba"]
    svms = [(i, p) for i, p in svms if p is not None]
    svms = svms if len(svms) > 1 else []
    k_nn = max((len(leaves[i][1]["classes"]) for i, _ in mlps), default=0)
    k_svm = max((p["dual"].shape[1] for _, p in svms), default=0)
    if mlps and svms and one_softmax:  # decision E19: one scaler and one Softmax for both blocks (one k)
        k = max(k_nn, k_svm)
        n_nn = len(_model_cols(b, leaves, mlps))
        x = b.cols(b.all, _model_cols(b, leaves, mlps) + _model_cols(b, leaves, svms))
        x = b.op("Sub", [x, b.const(np.concatenate([p["mean"] for _, p in mlps + svms]), "scaler_mean")])
        x = b.op("Div", [x, b.const(np.concatenate([p["scale"] for _, p in mlps + svms]), "scaler_scale")])
        xn, z = b.name("nn_x"), b.name("Z")
        b.nodes.append(helper.make_node("Split", [x, b.const(np.array([n_nn, len(_model_cols(b, leaves, svms))],
                                                                       np.int64), "split", np.int64)], [xn, z], axis=1))
        scores, _ = _svm_block(b, leaves, svms, k=k, z=z)
        logits = b.op("Concat", [_mlp_logits(b, mlps, xn, k), scores], "logits", axis=1)
        parts.append((_grouped_softmax(b, logits, len(mlps) + len(svms), k, "leaf_proba"),
                      [(i, j) for i, _ in mlps + svms for j in range(k)]))
    else:
        if mlps:
            x = b.cols(b.all, _model_cols(b, leaves, mlps))
            x = b.op("Sub", [x, b.const(np.concatenate([p["mean"] for _, p in mlps]), "nn_mean")])
            x = b.op("Div", [x, b.const(np.concatenate([p["scale"] for _, p in mlps]), "nn_scale")])
            parts.append((_grouped_softmax(b, _mlp_logits(b, mlps, x, k_nn), len(mlps), k_nn, "nn_proba"),
                          [(i, j) for i, _ in mlps for j in range(k_nn)]))
        if svms:
            x, k = _svm_block(b, leaves, svms)
            parts.append((x, [(i, j) for i, _ in svms for j in range(k)]))
    done |= {i for i, _ in svms}
    for i, (task, leaf, _, _) in enumerate(leaves):
        if i in done:
            continue
        outs = leaf["outputs"]
        model = b.onnx_models[leaf["file"]]
        x = b.features(leaf["features"])
        if "proba" in outs:
            p = b.inline(model, f"{task}_{i}_m_", x, outs["proba"])
        else:
            p = b.op("Softmax", [b.inline(model, f"{task}_{i}_m_", x, outs["logits"])], "softmax", axis=1)
        parts.append((p, [(i, j) for j in range(len(leaf["classes"]))]))
    offset, width = {}, 0
    for task, (_, classes) in tasks.items():
        offset[task], width = width, width + len(classes)
    columns = [col for _, cs in parts for col in cs]
    H = np.zeros((len(columns), width))
    for r, (i, j) in enumerate(columns):
        if j < len(leaves[i][3]):  # padded network classes stay 0
            task, _, w, cls_cols = leaves[i]
            H[r, offset[task] + cls_cols[j]] = w
    P = parts[0][0] if len(parts) == 1 else b.op("Concat", [t for t, _ in parts], "leaf_proba", axis=1)
    fused = b.op("MatMul", [P, b.const(H, "head")], "fused")
    sizes = np.array([len(classes) for _, classes in tasks.values()], np.int64)
    b.nodes.append(helper.make_node("Split", [fused, b.const(sizes, "split", np.int64)],
                                    [outputs[t] for t in tasks], axis=1))


def features_graph(recipe: list, features: dict) -> onnx.ModelProto:
    """A graph ``W -> features (n, F)`` of one recipe alone (tests pin it to the numpy recipe path)."""
    ci = {c: i for i, c in enumerate(features["channels"])}
    b = _Builder(int(features["n_samples"]), ci, features["signals"])
    b.prepare([recipe])
    b.nodes.append(helper.make_node("Identity", [b.features(recipe)], ["F"]))
    g = helper.make_graph(b.nodes, "pdrlearn_features",
                          [helper.make_tensor_value_info(INPUT, TensorProto.DOUBLE, [None, len(ci), b.m])],
                          [helper.make_tensor_value_info("F", TensorProto.DOUBLE, [None, None])], initializer=b.inits)
    model = helper.make_model(g, opset_imports=[helper.make_opsetid("", OPSET)], producer_name="pdrlearn")
    model.ir_version = 8
    onnx.checker.check_model(model, full_check=True)
    return model
