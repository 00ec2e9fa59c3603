"""Learned second stage of the offline waist IC detector (decision W33; an option, off by default).

Stage 1 takes every maximum of seed 003's 2.5 Hz zero-lag vertical acceleration (any height, at least
``CAND_MIN_S`` apart, plus the rule detector's own maxima), each with its IC by W3's rule (the last local
AP maximum within 0.25 s before it). Stage 2 scores each candidate from local features (the rule
detector's outcomes, the motion gate, the shape of the accelerations and the yaw rate around it,
intervals to its neighbours, the W20 side) with gradient-boosted trees, and keeps the candidates whose
score passes the model's threshold, greedily by score, none within the shortest step (0.3 s, W16) of a
kept one (non-maximum suppression).

The trees ship as plain JSON (``ic_model.json`` beside this module; no pickle, no torch, no
scikit-learn at run time): :class:`TreeEnsembleClassifier` evaluates them with numpy. They were trained by
``experiments/waist_ic_learned.py --export`` (scikit-learn's ``HistGradientBoostingClassifier``, on the
simulator and the three mobgap subjects; the leave-one-subject-out numbers are in
docs/decisions/waist.md W33).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
from scipy import signal as _sig
from scipy.ndimage import uniform_filter1d

from pdrlearn.errors import DataError
from pdrlearn.textfile import read_json
from pdrlearn.waist import _kernels as K

MODEL_PATH = Path(__file__).with_name("ic_model.json")
SCHEMA = 1
CAND_MIN_S = 0.1  # W33 stage 1: vertical maxima at least this far apart (recall, not a step limit)
LOCAL_S = 3.0  # W33: neighbourhood of the local scales (about two strides either side)
SIDE_PEAK_MPS2 = 0.1  # W16: full-height vertical maximum (the scale of the W20 side)
FEATURES = ("kept", "rule_cand", "strong", "gate", "h", "h_rel_kept", "h_rel_near", "side_strength",
            "same_side_prev", "same_side_next", "dt_prev_cand", "dt_next_cand", "dt_prev_kept",
            "dt_next_kept", "r_prev_kept", "r_next_kept", "period", "ap_ic", "ap_above_mean", "ap_rise",
            "ap_drop", "ic_delay", "w29_offset", "yaw_rate", "sd_v", "sd_ml", "sd_ap")


def _window_mean(x: np.ndarray, fs: float, half_s: float) -> np.ndarray:
    w = max(3, int(round(2 * half_s * fs)) | 1)
    return uniform_filter1d(np.asarray(x, dtype=np.float64), w, mode="nearest")


def _window_std(x: np.ndarray, fs: float, half_s: float) -> np.ndarray:
    m = _window_mean(x, fs, half_s)
    m2 = _window_mean(np.asarray(x, dtype=np.float64) ** 2, fs, half_s)
    return np.sqrt(np.maximum(m2 - m * m, 0.0))


def candidate_features(acc_v: np.ndarray, ap: np.ndarray, acc_ml: np.ndarray, w_z: np.ndarray, fs: float,
                       rule_anchor: np.ndarray, *, walk_threshold: float, cutoff_hz: float = 2.5,
                       fir_order_s: float = 0.3, search_s: float = 0.25, min_step_s: float = 0.3,
                       max_step_s: float = 1.5) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Stage 1 candidates and their features (decision W33).

    Parameters
    ----------
    acc_v, ap, acc_ml, w_z : (n,) vertical acceleration without gravity, low-passed AP acceleration (as
        the rule detector uses it), ML acceleration (m/s^2) and vertical rate (rad/s)
    fs : rate (Hz)
    rule_anchor : vertical maxima (sample indices) kept by the rule detector (W18-W28)
    walk_threshold : motion-gate threshold (m/s^2, W4)

    Returns
    -------
    ic, anchor : (m,) sample indices of each candidate's IC and vertical maximum, increasing anchors
    X : (m, len(FEATURES)) features, finite
    """
    v = np.asarray(acc_v, dtype=np.float64)
    ap = np.asarray(ap, dtype=np.float64)
    rule_anchor = np.asarray(rule_anchor, dtype=np.int64)
    taps = K.fir_taps(cutoff_hz, fs, int(round(fir_order_s * fs)))  # seed 003 sec. 3.1, as ic_offline
    vf = K.fir_zero_lag(v - np.mean(v), taps) if v.size else v
    cand, _ = _sig.find_peaks(vf, distance=max(1, int(round(CAND_MIN_S * fs))))
    near = max(1, int(round(min_step_s * fs)))
    rule_cand, _ = _sig.find_peaks(vf, height=0.0, distance=near)
    anchor = np.unique(np.concatenate([cand, rule_cand, rule_anchor])).astype(np.int64)
    n = anchor.size
    if n == 0:
        return np.zeros(0, dtype=int), np.zeros(0, dtype=int), np.zeros((0, len(FEATURES)))
    ws = max(1, int(round(search_s * fs)))
    level = K.ap_mean_level(ap, fs)
    ic = np.array([K._nearest_local_max_before(ap, p, max(0, p - ws)) for p in anchor], dtype=np.int64)
    ic29 = np.array([K._nearest_local_max_before(ap, p, max(0, p - ws), level=level) for p in anchor],
                    dtype=np.int64)
    sigma = K.rolling_std(v, fs, causal=False)  # seed 000 sec. II-B, centred (offline)
    gate = sigma >= walk_threshold
    h = vf[anchor]
    vml = K.lateral_velocity(acc_ml, fs)
    rc_strong = (vf[rule_cand] >= SIDE_PEAK_MPS2) & gate[rule_cand]
    scale = float(np.median(np.abs(vml[rule_cand[rc_strong]]))) if rc_strong.any() else 0.0
    if not np.isfinite(scale) or scale <= 0:
        scale = np.inf
    strength = np.abs(vml[anchor]) / scale
    side = np.where(strength >= K.SIDE_MIN_FRAC, np.sign(vml[anchor]), 0.0)  # W20
    ka = np.sort(rule_anchor)
    ka_side = np.where(np.abs(vml[ka]) / scale >= K.SIDE_MIN_FRAC, np.sign(vml[ka]), 0.0)
    ka_t, at = ka / fs, anchor / fs
    kept_iv = np.diff(ka_t)
    f = {k: np.zeros(n) for k in FEATURES}
    f["kept"] = np.isin(anchor, ka).astype(float)
    f["rule_cand"] = np.isin(anchor, rule_cand).astype(float)
    f["strong"] = ((h >= SIDE_PEAK_MPS2) & gate[anchor]).astype(float)
    f["gate"] = sigma[anchor] / walk_threshold
    f["h"] = h
    f["side_strength"] = np.where(np.isfinite(strength), strength, 0.0)
    far = 5.0  # s: "no neighbour" (beyond any step, W16)
    for j, p in enumerate(anchor):
        m = (np.abs(ka_t - at[j]) <= LOCAL_S) & (ka != p)
        med = float(np.median(vf[ka[m]])) if m.any() else 0.0
        f["h_rel_kept"][j] = h[j] / med if med > 0 else 0.0
        lo, hi = max(0, p - near), min(vf.size, p + near + 1)
        f["h_rel_near"][j] = h[j] / max(float(np.max(vf[lo:hi])), 1e-6)
        pk = int(np.searchsorted(ka, p, side="left")) - 1
        nk = int(np.searchsorted(ka, p, side="right"))
        f["dt_prev_kept"][j] = at[j] - ka_t[pk] if pk >= 0 else far
        f["dt_next_kept"][j] = ka_t[nk] - at[j] if nk < ka.size else far
        f["same_side_prev"][j] = side[j] * ka_side[pk] if pk >= 0 else 0.0
        f["same_side_next"][j] = side[j] * ka_side[nk] if nk < ka.size else 0.0
        mi = (np.abs(ka_t[:-1] - at[j]) <= LOCAL_S) & (kept_iv <= max_step_s)
        per = float(np.median(kept_iv[mi])) if mi.any() else 1.0
        f["period"][j] = per
        f["r_prev_kept"][j] = f["dt_prev_kept"][j] / per
        f["r_next_kept"][j] = f["dt_next_kept"][j] / per
    f["dt_prev_cand"] = np.clip(np.diff(at, prepend=at[0] - far), 0.0, far)
    f["dt_next_cand"] = np.clip(np.diff(at, append=at[-1] + far), 0.0, far)
    apsd = max(float(np.std(ap)), 1e-6)
    back = max(1, int(round(0.15 * fs)))
    f["ap_ic"] = ap[ic] / apsd
    f["ap_above_mean"] = (ap[ic] - level[ic]) / apsd
    f["ap_rise"] = np.array([ap[i] - np.min(ap[max(0, i - back):i + 1]) for i in ic]) / apsd
    f["ap_drop"] = np.array([ap[i] - np.min(ap[p:min(ap.size, p + ws + 1)])
                             for i, p in zip(ic, anchor, strict=True)]) / apsd
    f["ic_delay"] = (anchor - ic) / fs
    f["w29_offset"] = (ic29 - ic) / fs
    f["yaw_rate"] = _window_mean(np.abs(w_z), fs, 0.3)[anchor]
    f["sd_v"] = _window_std(v, fs, 0.5)[anchor]
    f["sd_ml"] = _window_std(acc_ml, fs, 0.5)[anchor]
    f["sd_ap"] = _window_std(ap, fs, 0.5)[anchor]
    X = np.column_stack([np.asarray(f[k], dtype=np.float64) for k in FEATURES])
    return ic, anchor, np.nan_to_num(X, nan=0.0, posinf=far, neginf=-far)


def suppress(t: np.ndarray, score: np.ndarray, threshold: float, radius: float) -> np.ndarray:
    """Non-maximum suppression: the candidates (times or sample indices ``t``) with ``score >=
    threshold``, taken greedily by score, none closer than ``radius`` to one already kept. Returns the
    mask of kept candidates."""
    t = np.asarray(t, dtype=np.float64)
    s = np.asarray(score, dtype=np.float64)
    out = np.zeros(t.size, dtype=bool)
    kept: list[float] = []
    for i in np.argsort(-s, kind="stable"):
        if not s[i] >= threshold:
            break
        if all(abs(t[i] - k) >= radius for k in kept):
            kept.append(float(t[i]))
            out[i] = True
    return out


class TreeEnsembleClassifier:
    """Binary gradient-boosted regression trees stored as data (decision W33).

    ``P(step) = sigmoid(baseline + sum of the leaf values)``; in each tree a sample goes left when its
    feature is ``<= threshold`` (NaN: as ``missing_left``). The form of scikit-learn's
    ``HistGradientBoostingClassifier`` (binary, numerical features), evaluated with numpy only.

    Parameters
    ----------
    baseline : raw score before the trees
    trees : list of dicts of equal-length node lists ``feature``, ``threshold``, ``left``, ``right``,
        ``leaf`` (bool), ``value``, ``missing_left`` (bool); node 0 is the root
    features : feature names, in the column order of ``X``
    threshold : score threshold of a step (chosen on training data)
    info : training summary (free-form)
    """

    def __init__(self, *, baseline: float, trees: list[dict], features: tuple[str, ...] | list[str],
                 threshold: float = 0.5, info: dict | None = None):
        self.baseline = float(baseline)
        self.features = tuple(features)
        self.threshold = float(threshold)
        self.info = dict(info or {})
        self.trees = []
        for tr in trees:
            nodes = {k: np.asarray(tr[k]) for k in ("feature", "threshold", "left", "right", "leaf", "value",
                                                    "missing_left")}
            sizes = {v.size for v in nodes.values()}
            if len(sizes) != 1 or 0 in sizes:
                raise DataError("tree ensemble: every node list of a tree must have the same, non-zero length")
            nodes["feature"] = nodes["feature"].astype(np.int64)
            nodes["left"], nodes["right"] = nodes["left"].astype(np.int64), nodes["right"].astype(np.int64)
            nodes["leaf"], nodes["missing_left"] = nodes["leaf"].astype(bool), nodes["missing_left"].astype(bool)
            nodes["threshold"], nodes["value"] = (nodes["threshold"].astype(np.float64),
                                                  nodes["value"].astype(np.float64))
            inner = ~nodes["leaf"]
            m = nodes["feature"].size
            if (np.any(nodes["feature"][inner] < 0) or np.any(nodes["feature"][inner] >= len(self.features))
                    or np.any((nodes["left"][inner] <= 0) | (nodes["left"][inner] >= m))
                    or np.any((nodes["right"][inner] <= 0) | (nodes["right"][inner] >= m))):
                raise DataError("tree ensemble: a node refers to a feature or child that does not exist")
            self.trees.append(nodes)

    def decision_function(self, X: np.ndarray) -> np.ndarray:
        """Raw score (log-odds of a step) per row of ``X`` (n, len(features))."""
        X = np.asarray(X, dtype=np.float64)
        if X.ndim != 2 or X.shape[1] != len(self.features):
            raise DataError(f"tree ensemble: X must have {len(self.features)} columns, got shape {X.shape}")
        rows = np.arange(X.shape[0])
        raw = np.full(X.shape[0], self.baseline)
        for nd in self.trees:
            idx = np.zeros(X.shape[0], dtype=np.int64)
            for _ in range(nd["leaf"].size):  # depth <= number of nodes
                inner = ~nd["leaf"][idx]
                if not inner.any():
                    break
                x = X[rows, np.where(inner, nd["feature"][idx], 0)]
                go_left = np.where(np.isnan(x), nd["missing_left"][idx], x <= nd["threshold"][idx])
                idx = np.where(inner, np.where(go_left, nd["left"][idx], nd["right"][idx]), idx)
            raw += nd["value"][idx]
        return raw

    def predict_proba(self, X: np.ndarray) -> np.ndarray:
        """(n, 2) probabilities of no step / step."""
        p = 1.0 / (1.0 + np.exp(-self.decision_function(X)))
        return np.column_stack([1.0 - p, p])

    def predict(self, X: np.ndarray) -> np.ndarray:
        """1 where the step probability reaches ``threshold``."""
        return (self.predict_proba(X)[:, 1] >= self.threshold).astype(int)

    def to_dict(self) -> dict:
        trees = [{"feature": nd["feature"].tolist(), "threshold": nd["threshold"].tolist(),
                  "left": nd["left"].tolist(), "right": nd["right"].tolist(), "leaf": nd["leaf"].tolist(),
                  "value": nd["value"].tolist(), "missing_left": nd["missing_left"].tolist()}
                 for nd in self.trees]
        return {"schema": SCHEMA, "kind": "gradient-boosted-trees", "features": list(self.features),
                "baseline": self.baseline, "threshold": self.threshold, "info": self.info, "trees": trees}

    @classmethod
    def from_dict(cls, d: dict) -> TreeEnsembleClassifier:
        if d.get("schema") != SCHEMA or d.get("kind") != "gradient-boosted-trees":
            raise DataError(f"IC model: schema {d.get('schema')!r} / kind {d.get('kind')!r}; expected {SCHEMA} / "
                            "gradient-boosted-trees")
        return cls(baseline=d["baseline"], trees=d["trees"], features=d["features"], threshold=d["threshold"],
                   info=d.get("info"))

    @classmethod
    def load(cls, path: str | Path | None = None) -> TreeEnsembleClassifier:
        """The model in ``path`` (default: the shipped ``ic_model.json``)."""
        p = Path(path) if path is not None else MODEL_PATH
        try:
            d = read_json(p)
        except (OSError, ValueError) as e:
            raise DataError(f"{p}: cannot read the IC model ({e})") from e
        try:  # valid JSON of another shape (a list, missing keys, text for numbers): one line naming the file
            model = cls.from_dict(d)
        except DataError as e:
            raise DataError(f"{p}: {e}") from e
        except (AttributeError, KeyError, TypeError, ValueError) as e:
            raise DataError(f"{p}: not an IC model ({type(e).__name__}: {e})") from e
        if model.features != FEATURES:
            raise DataError(f"{p}: the model's features differ from this version's FEATURES")
        return model

    def save(self, path: str | Path) -> None:
        """Write the model as JSON (atomically: a temporary file renamed)."""
        p = Path(path)
        tmp = p.with_suffix(p.suffix + ".tmp")
        tmp.write_text(json.dumps(self.to_dict(), separators=(",", ":")) + "\n")
        tmp.replace(p)

    @classmethod
    def from_sklearn(cls, model, *, features, threshold: float, info: dict | None = None) -> TreeEnsembleClassifier:
        """Convert a fitted binary ``HistGradientBoostingClassifier`` with numerical features (training side)."""
        if getattr(model, "n_trees_per_iteration_", 1) != 1:
            raise DataError("tree ensemble: only binary classifiers convert")
        trees = []
        for (pred,) in model._predictors:
            nd = pred.nodes
            if np.any(nd["is_categorical"]):
                raise DataError("tree ensemble: categorical splits do not convert")
            trees.append({"feature": nd["feature_idx"].astype(int).tolist(),
                          "threshold": nd["num_threshold"].astype(float).tolist(),
                          "left": nd["left"].astype(int).tolist(), "right": nd["right"].astype(int).tolist(),
                          "leaf": nd["is_leaf"].astype(bool).tolist(), "value": nd["value"].astype(float).tolist(),
                          "missing_left": nd["missing_go_to_left"].astype(bool).tolist()})
        return cls(baseline=float(np.ravel(model._baseline_prediction)[0]), trees=trees, features=features,
                   threshold=threshold, info=info)


_CACHE: dict[str, TreeEnsembleClassifier] = {}


def shipped_model(path: str | Path | None = None) -> TreeEnsembleClassifier:
    """The shipped model, or the one in ``path`` (each file loaded once per process)."""
    key = str(Path(path).resolve()) if path is not None else ""
    if key not in _CACHE:
        _CACHE[key] = TreeEnsembleClassifier.load(path)
    return _CACHE[key]


def learned_contacts(acc_v: np.ndarray, ap: np.ndarray, acc_ml: np.ndarray, w_z: np.ndarray, fs: float,
                     rule_anchor: np.ndarray, *, model: TreeEnsembleClassifier | None = None,
                     walk_threshold: float, cutoff_hz: float = 2.5, fir_order_s: float = 0.3,
                     search_s: float = 0.25, min_step_s: float = 0.3, max_step_s: float = 1.5
                     ) -> tuple[np.ndarray, np.ndarray]:
    """ICs and their vertical maxima (sample indices, increasing) kept by the learned stage (W33)."""
    model = model if model is not None else shipped_model()
    ic, anchor, X = candidate_features(acc_v, ap, acc_ml, w_z, fs, rule_anchor, walk_threshold=walk_threshold,
                                       cutoff_hz=cutoff_hz, fir_order_s=fir_order_s, search_s=search_s,
                                       min_step_s=min_step_s, max_step_s=max_step_s)
    if ic.size == 0:
        return ic, anchor
    keep = suppress(ic, model.predict_proba(X)[:, 1], model.threshold, round(min_step_s * fs))
    order = np.argsort(anchor[keep], kind="stable")
    return ic[keep][order], anchor[keep][order]
