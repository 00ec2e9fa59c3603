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
    for k in range(n):
        if method == "ellipse":
            raw[k] = K.ellipse_direction(t, a_h, a_v, ev[k], ev[k + 1])
            continue
        if k == 0 and n < 2:
            continue
        t0, t1, t2 = (ev[0], ev[1], ev[2]) if k == 0 else (ev[k - 1], ev[k], ev[k + 1])
        if method == "ahe":
            raw[k] = K.tip_to_tail_direction(t, a_h, a_v, t0, t1, t2)
        else:
            raw[k] = K.stride_ellipse_direction(t, a_h, a_v, t0, t2)
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
        x = self._x(X)
        m, s, w = self._params()
        logp = -0.5 * ((x[:, None] - m) / s) ** 2 - np.log(s) + np.log(w)
        logp -= logp.max(axis=1, keepdims=True)
        p = np.exp(logp)
        return p / p.sum(axis=1, keepdims=True)

    def predict(self, X) -> np.ndarray:
        return (self.predict_proba(X)[:, 1] > 0.5).astype(int)

    def to_dict(self) -> dict:
        m, s, w = self._params()
        return {"means": m.tolist(), "sds": s.tolist(), "weights": w.tolist()}


#: Decision W82: the ``slow_turn_rps`` the W74 line suggests for gentle curves (rad/s, 2 deg/s): a straight-called
#: stride is integrated too when the mean rate of the strides k-3..k+1 (within the sequence) reaches it. An option,
#: not the default: it failed its adoption rule on sharp turns by 0.01 m
SLOW_TURN_RPS = 0.035
#: strides before / after stride k in its window: one after, because the live tracker (W64) knows stride k+1 but not
#: always k+2 when it reports k
SLOW_TURN_WINDOW = (3, 1)


def slow_turn_strides(mrz: np.ndarray, threshold_rps: float | None) -> np.ndarray:
    """Decision W82: strides inside a gentle curve, whose 5-stride (:data:`SLOW_TURN_WINDOW`) mean rate reaches
    ``threshold_rps``."""
    x = np.nan_to_num(np.asarray(mrz, np.float64))
    if not threshold_rps or x.size == 0:
        return np.zeros(x.shape, dtype=bool)
    c = np.concatenate([[0.0], np.cumsum(x)])
    k = np.arange(x.size)
    lo = np.maximum(k - SLOW_TURN_WINDOW[0], 0)
    hi = np.minimum(k + SLOW_TURN_WINDOW[1] + 1, x.size)
    return np.abs((c[hi] - c[lo]) / (hi - lo)) >= threshold_rps


def gyro_headings(imu: WaistIMU, events: np.ndarray, *, classifier: TurnClassifier | None = None,
                  bias_rps: float = 0.0, heading0: float = 0.0, cum: np.ndarray | None = None,
                  slow_turn_rps: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Per-step heading from the vertical gyroscope, integrated only over turning strides
    (seed 003 sec. 3.3).

    Each step's stride mean rate is classified; the rate (minus ``bias_rps``, seed 003 eq. 2) is
    integrated over the steps classified as turning and over the step before and after each of them
    (seed 003: "integrate two straight steps occurring before and after a curved walking step"), and over
    the strides of a gentle curve when ``slow_turn_rps`` > 0 (:func:`slow_turn_strides`, decision W82).
    ``cum``: :func:`pdrlearn.waist._kernels.rate_integral` of ``(imu.t, imu.w_z - bias_rps)`` when the
    caller integrates the same rate over many sequences (one pass over the recording, W43).

    Returns
    -------
    headings : (m - 1,) heading during each step (rad); turning : (m - 1,) 0/1 classification.
    """
    ev = np.asarray(events, dtype=np.float64)
    n = len(ev) - 1
    if n <= 0:
        return np.zeros(0), np.zeros(0, dtype=int)
    w = imu.w_z - bias_rps
    cum = K.rate_integral(imu.t, w) if cum is None else cum
    mrz = K.mean_rate_per_stride(imu.t, w, ev, cum=cum)
    clf = classifier if classifier is not None else TurnClassifier()
    turning = clf.predict(np.nan_to_num(mrz))
    integrate = turning.astype(bool).copy()
    integrate[1:] |= turning[:-1].astype(bool)
    integrate[:-1] |= turning[1:].astype(bool)
    integrate |= slow_turn_strides(mrz, slow_turn_rps)  # W82, off by default
    dpsi = K.integrate_rate(imu.t, w, ev[:-1], ev[1:], cum=cum)
    heading = np.empty(n)
    h = heading0
    for k in range(n):
        if integrate[k]:
            h += dpsi[k]
        heading[k] = h
    return heading, turning


#: Decision W74: a gyro-headed waist track warns when the waist's own yaw, integrated from the first contact to the
#: end of a step, and that step's heading differ by this much (deg) at some step: a turn the headings dropped
UNTRACKED_TURN_WARN_DEG = 60.0


def turn_gap(gyro_yaw, heading):
    """Decision W80: gyroscope yaw minus step heading (rad) as a direction difference, wrapped to (-pi, pi]: either
    may be wrapped, and a wrapped U-turn must not read as a missed full turn."""
    return np.angle(np.exp(1j * (np.asarray(gyro_yaw, np.float64) - np.asarray(heading, np.float64))))


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


def untracked_turn_message(diff_deg: float, t_s: float, integrate_stops: bool) -> str:
    """The one warning line of decision W74 (shared with :class:`pdrlearn.waist.live.WaistTracker`)."""
    cause = ("turns made during undetected steps or while standing are dropped with integrate_stops off: set "
             "\"options\": {\"integrate_stops\": true} in the PARAMS.json (or integrate_stops=True)"
             if not integrate_stops else
             "a turn on strides the turn classifier called straight (a gentle curve, under 8 deg/s: decision W82) "
             "or a gyroscope bias; for curves set \"options\": {\"slow_turn_rps\": 0.035} (live too) or "
             "{\"heading\": \"ellipse\"} in the PARAMS.json, or use '--pipeline waist-pll'; for a bias calibrate "
             "on a walk with a full turn ('pdrlearn calibrate --turns 1 --fit-turns')")
    return (f"the step headings miss {diff_deg:+.0f} deg of the waist gyroscope's turn by {t_s:.1f} s "
            f"(decision W74): the positions after it are off; {cause}")
