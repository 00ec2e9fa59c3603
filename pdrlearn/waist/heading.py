"""Heading of waist steps: harmonic (seed 000 A-HE, seed 001 ellipse) and gyroscope (seed 003).

Angles are radians in the navigation frame of :mod:`pdrlearn.waist.ahrs` (0 = initial facing,
counter-clockwise positive).
"""

from __future__ import annotations

import numpy as np
from sklearn.base import BaseEstimator, ClassifierMixin
from sklearn.mixture import GaussianMixture

from pdrlearn.errors import DataError
from pdrlearn.waist import _kernels as K
from pdrlearn.waist._kernels import (  # noqa: F401  (moved to the numpy kernels, W92)
    SLOW_TURN_RPS,
    SLOW_TURN_WINDOW,
    UNTRACKED_TURN_WARN_DEG,
    slow_turn_strides,
    turn_gap,
    untracked_turn_message,
)
from pdrlearn.waist.ahrs import WaistIMU

# Prior straight/turning mixture on |MRZ| (rad/s) used before any fit (decision W7): straight strides
# average close to zero (seed 003 Fig. 2: the peak near 0), turning strides spread over 0.2-0.9 rad/s.
DEFAULT_TURN_GMM = {"means": [0.03, 0.45], "sds": [0.04, 0.25], "weights": [0.7, 0.3]}


HARMONIC_METHODS = ("ahe", "ellipse", "ellipse-stride")


def harmonic_directions(imu: WaistIMU, events: np.ndarray, *, method: str = "ahe") -> np.ndarray:
    """Per-step motion direction (rad) from the planar acceleration's harmonics, one value per step
    ``[events[k], events[k+1]]``, before any averaging.

    ``method``: ``"ahe"`` (seed 000 Alg. 1 a-d: tip-to-tail of the first two harmonics over the stride
    ending with the step), ``"ellipse"`` (seed 001: closed-form first-harmonic ellipse axis of the step,
    decision W1) or ``"ellipse-stride"`` (the step-frequency harmonic over the stride ending with the step,
    decision W12). The first step, which has no stride before it, uses the stride that starts with it.
    NaN where undefined.
    """
    if method not in HARMONIC_METHODS:
        raise DataError(f"harmonic heading: method '{method}' is not one of {', '.join(HARMONIC_METHODS)}")
    ev = np.asarray(events, dtype=np.float64)
    n = len(ev) - 1
    raw = np.full(max(n, 0), np.nan)
    if n <= 0:
        return raw
    # the samples of the sequence only: every window below lies in [ev[0], ev[-1]] and selects the same
    # samples from this slice as from the recording (sorted clock), without a pass over all of it (W43)
    i0, i1 = np.searchsorted(imu.t, ev.min(), "left"), np.searchsorted(imu.t, ev.max(), "right")
    t, a_h, a_v = imu.t[i0:i1], imu.acc_h[i0:i1], imu.acc_v[i0:i1]
    # decision E100: each kernel gets only its window's samples [a, b] (the same samples its mask selects from
    # the sequence, sorted clock), so a long unbroken walk costs O(steps log n), not O(steps x n)
    lo, hi = np.searchsorted(t, ev, "left"), np.searchsorted(t, ev, "right")

    def window(a: int, b: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return t[lo[a]:hi[b]], a_h[lo[a]:hi[b]], a_v[lo[a]:hi[b]]

    for k in range(n):
        if method == "ellipse":
            raw[k] = K.ellipse_direction(*window(k, k + 1), ev[k], ev[k + 1])
            continue
        if k == 0 and n < 2:
            continue
        a, b = (0, 2) if k == 0 else (k - 1, k + 1)
        t0, t1, t2 = ev[a], ev[a + 1], ev[b]
        if method == "ahe":
            raw[k] = K.tip_to_tail_direction(*window(a, b), t0, t1, t2)
        else:
            raw[k] = K.stride_ellipse_direction(*window(a, b), t0, t2)
    return raw


def average_two(raw: np.ndarray) -> np.ndarray:
    """A-HE: the mean direction of each step and the one before it (seed 000 Alg. 1e; seed 001 sec. 2.2.3)."""
    out = np.asarray(raw, dtype=np.float64).copy()
    for k in range(1, len(out)):
        out[k] = K.circular_mean2(raw[k - 1], raw[k])
    return out


def harmonic_headings(imu: WaistIMU, events: np.ndarray, *, method: str = "ahe") -> np.ndarray:
    """Per-step heading (rad): :func:`harmonic_directions` averaged over two steps (no sign resolution;
    the pipelines also apply :func:`pdrlearn.waist._kernels.resolve_axis_signs`)."""
    return average_two(harmonic_directions(imu, events, method=method))


class TurnClassifier(ClassifierMixin, BaseEstimator):
    """Straight (0) / turning (1) classifier of strides from |MRZ|, the absolute mean vertical rate over
    the stride (seed 003 sec. 3.3), with a two-component Gaussian mixture.

    ``fit(X)`` fits the mixture without labels (seed 003: fitted on one trial, validated on another);
    ``fit(X, y)`` fits one Gaussian per labelled class. Before ``fit`` the prior of
    :data:`DEFAULT_TURN_GMM` is used.

    Parameters
    ----------
    means, sds, weights : starting / prior mixture (rad/s, rad/s, -), component 0 = straight
    random_state : seed of the mixture fit
    """

    def __init__(self, *, means=None, sds=None, weights=None, random_state: int = 0):
        self.means = means
        self.sds = sds
        self.weights = weights
        self.random_state = random_state

    def _prior(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        m = np.asarray(self.means if self.means is not None else DEFAULT_TURN_GMM["means"], float)
        s = np.asarray(self.sds if self.sds is not None else DEFAULT_TURN_GMM["sds"], float)
        w = np.asarray(self.weights if self.weights is not None else DEFAULT_TURN_GMM["weights"], float)
        return m, s, w / w.sum()

    @staticmethod
    def _x(X) -> np.ndarray:
        x = np.abs(np.asarray(X, dtype=np.float64)).reshape(-1)
        if not np.all(np.isfinite(x)):
            raise DataError("turn classifier: |MRZ| values contain NaN; drop undefined strides first")
        return x

    def fit(self, X, y=None) -> TurnClassifier:
        x = self._x(X)
        self.classes_ = np.array([0, 1])
        if y is not None:
            yy = np.asarray(y).astype(int).reshape(-1)
            if yy.shape != x.shape or not set(np.unique(yy)) <= {0, 1}:
                raise DataError("turn classifier: y must hold 0 (straight) / 1 (turning) for every X")
            m0, s0, w0 = self._prior()
            means, sds, ws = [], [], []
            for c in (0, 1):
                xc = x[yy == c]
                means.append(xc.mean() if xc.size else m0[c])
                sds.append(max(xc.std(), 1e-3) if xc.size > 1 else s0[c])
                ws.append(xc.size if yy.size else w0[c])
            self.means_, self.sds_ = np.array(means), np.array(sds)
            self.weights_ = np.array(ws, float) / max(sum(ws), 1)
            return self
        m0, s0, w0 = self._prior()
        if x.size < 4:
            self.means_, self.sds_, self.weights_ = m0, s0, w0
            return self
        gmm = GaussianMixture(2, means_init=m0.reshape(-1, 1), weights_init=w0,
                              precisions_init=(1.0 / s0 ** 2).reshape(-1, 1, 1),
                              random_state=self.random_state).fit(x.reshape(-1, 1))
        order = np.argsort(gmm.means_.ravel())
        self.means_ = gmm.means_.ravel()[order]
        self.sds_ = np.sqrt(gmm.covariances_.ravel())[order]
        self.weights_ = gmm.weights_[order]
        return self

    def _params(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        if hasattr(self, "means_"):
            return self.means_, self.sds_, self.weights_
        return self._prior()

    def predict_proba(self, X) -> np.ndarray:
        return K.turn_proba(self._x(X), *self._params())

    def predict(self, X) -> np.ndarray:
        return (self.predict_proba(X)[:, 1] > 0.5).astype(int)

    def to_dict(self) -> dict:
        m, s, w = self._params()
        return {"means": m.tolist(), "sds": s.tolist(), "weights": w.tolist()}


def gyro_headings(imu: WaistIMU, events: np.ndarray, *, classifier: TurnClassifier | None = None,
                  bias_rps: float = 0.0, heading0: float = 0.0, cum: np.ndarray | None = None,
                  slow_turn_rps: float = 0.0, gentle_curves: bool = False,
                  gentle_bias_rps: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """:func:`pdrlearn.kernels.waist.gyro_headings` (seed 003 sec. 3.3) on ``imu``'s vertical rate, the strides
    classified by ``classifier`` (default: the W7 prior)."""
    clf = classifier if classifier is not None else TurnClassifier()
    return K.gyro_headings(imu.t, imu.w_z, events, predict=clf.predict, bias_rps=bias_rps, heading0=heading0,
                           cum=cum, slow_turn_rps=slow_turn_rps, gentle_curves=gentle_curves,
                           gentle_bias_rps=gentle_bias_rps)


def untracked_turn(imu: WaistIMU, events: np.ndarray, ends: np.ndarray, headings: np.ndarray, *,
                   bias_rps: float = 0.0, cum: np.ndarray | None = None) -> tuple[float, float]:
    """Decision W74: the largest difference (rad, signed: gyroscope minus heading) between the vertical rate
    integrated from ``events[0]`` to each step's end ``ends[k]`` and the step's gyro heading ``headings[k]``
    (rad, 0 at the first contact, as :func:`gyro_headings` and the pipelines' ``integrate_stops`` give it), and
    the time (s) of that step's end. ``(0.0, nan)`` without steps. The heading drops a turn made during
    undetected steps or while standing (``integrate_stops`` off), or on strides the turn classifier calls
    straight; an uncalibrated gyroscope bias adds ``bias x time``. The difference is wrapped (:func:`turn_gap`)."""
    ev, en = np.asarray(events, np.float64), np.asarray(ends, np.float64)
    hd = np.asarray(headings, np.float64)
    if ev.size == 0 or en.size == 0:
        return 0.0, float("nan")
    w = imu.w_z - bias_rps
    cum = K.rate_integral(imu.t, w) if cum is None else cum
    diff = turn_gap(K.integrate_rate(imu.t, w, np.full(en.shape, ev[0]), en, cum=cum), hd)  # decision W80
    k = int(np.argmax(np.abs(diff)))
    return float(diff[k]), float(en[k])


#: the columns of a track's ``info["yaw_turns"]`` records (decision L210)
YAW_TURN_KEYS = ("start_s", "end_s", "peak_s", "angle_deg", "peak_dps", "start_5_s", "end_95_s")


def yaw_turns(imu: WaistIMU, bias_rps: float = 0.0) -> list[dict]:
    """Decision L210: El-Gohary's turns (:func:`pdrlearn.kernels.yaw_turns.yaw_rate_turns`) of the pelvis yaw
    rate, the vertical gyro in the gravity frame less ``bias_rps``, over the whole recording: one record each
    (:data:`YAW_TURN_KEYS`, times in ``imu.t``'s clock; ``end_s`` the first sample under the edge rate after the
    turn, the last sample at the recording's end; decision L345: ``start_5_s`` / ``end_95_s`` where its smoothed yaw
    has gone 5 % / 95 % of its change, :func:`pdrlearn.kernels.yaw_turns.turn_fraction_times`)."""
    from pdrlearn.kernels.yaw_turns import lowpassed_yaw_rate, turn_fraction_times, yaw_rate_turns

    t = np.asarray(imu.t, dtype=float)
    if t.size < 2:
        return []
    rate = np.degrees(imu.w_z - bias_rps)
    rows = yaw_rate_turns(rate, float(imu.fs))
    if not len(rows):
        return []
    f = np.abs(lowpassed_yaw_rate(rate, float(imu.fs)))  # decision L235: the detector's own peak, El-Gohary 2014
    last = t.size - 1
    frac = turn_fraction_times(rate, float(imu.fs), rows)  # decision L345
    return [dict(zip(YAW_TURN_KEYS, (float(t[int(a)]), float(t[min(int(b), last)]), float(t[int(p)]), float(ang),
                                     float(f[int(p)]), float(t[i0]), float(t[i1])), strict=True))
            for (a, b, p, ang), (i0, i1) in zip(rows, frac, strict=True)]
