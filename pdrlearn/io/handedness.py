"""Is a unit's gyroscope right-handed with respect to its accelerometer? (decision D11, amends D10)

In a right-handed sensor frame a fixed world vector seen by the sensor turns against the angular rate,
d(g_b)/dt = -omega x g_b; data mirrored in one axis (the same column negated in the accelerometer and the
gyroscope, e.g. left-foot data mirrored to look like a right foot) obey d(g_b)/dt = +omega x g_b instead,
because the angular rate is a pseudovector. So the data can say which sign fits: the gyroscope turned
the right way (``+omega``) or reversed (``-omega``, what mirrored data look like to a right-handed model).
The comparison is made where the motion makes it decisive and the linear acceleration cannot mask it:

- **foot**: every rest-to-rest stride is integrated as the ZUPT stride integration does (levelled by the
  start rest, attitude from the gyroscope, gravity removed); the velocity at the end rest must be zero.
  A reversed attitude leaks gravity into it through the whole swing (the foot pitches 50-80 deg).
  Per stride: log(|v_end(-omega)| / |v_end(+omega)|).
- **waist**: windows of :data:`WAIST_WINDOW_S`; in each, the same integration from the window start, and
  the velocity after removing a straight line (gravity's projection and the start attitude's error give
  a constant acceleration): walking keeps it within the velocity's within-stride swing, a reversed
  attitude adds the leaked gravity. Per window: log(E(-omega) / E(+omega)), E the residual's mean square.
  Only windows in which the unit moves (:data:`WAIST_MIN_ACC_SD`) count.

Positive = right-handed. The check takes the median over the strides / windows of the first
:data:`~pdrlearn.track.frame_inference.CHECK_SPAN_S` seconds and warns only below
:data:`MIN_LOG_RATIO` with at least :data:`MIN_SEGMENTS` of them (docs/frames.md, the measurement).
A declared frame (D8/D10) says where the axes point; this says whether the two sensors agree on the
sense of rotation, which no frame entry can fix: the data have to be un-mirrored.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Warn when the median per-stride / per-window log ratio (positive = right-handed) lies below this.
#: Measured (experiments/handedness_check.py, docs/frames.md): truthful real foot units +1.88 to +3.37,
#: their mirrored versions the negatives; truthful waist units and simulated units see docs/frames.md.
#: -1.0 (the reversed gyroscope fits e = 2.7 times better in the median segment) is conservative.
MIN_LOG_RATIO = -1.0
#: Units whose test may warn. The waist test is measured but not adopted (docs/frames.md, decision D11): truthful
#: simulated waist units score -0.25 to -0.64 (the simulated pelvis rolls against its lateral acceleration at
#: the stride frequency, the real lower backs with it; both are right-handed: docs/decisions/simulator.md S26;
#: real +0.18 to +2.26), so its sign is set by the motion and is not a confident verdict, and at
#: a threshold that spares them it catches only the long real recordings' mirrored versions.
WARN_PLACEMENTS = ("foot",)
#: Least strides (foot) or moving windows (waist) for a verdict; fewer: no warning.
MIN_SEGMENTS = 4
#: Waist window length and hop (s): about one stride (0.8-1.4 s at 1.4-2.4 steps/s) to two.
WAIST_WINDOW_S = 2.0
WAIST_HOP_S = 1.0
#: A waist window counts when the standard deviation of |specific force| in it exceeds this (m/s^2):
#: walking at the lower back swings it by 1-3 m/s^2 (seed 003 Fig. 2), standing by less than 0.2.
WAIST_MIN_ACC_SD = 0.5


@dataclass
class Handedness:
    """Result of a handedness test: ``log_ratio`` the median over ``segments`` strides / windows of
    log(error with the gyroscope reversed / error as recorded) (> 0: right-handed), NaN when none."""

    placement: str
    log_ratio: float
    segments: int

    @property
    def mirrored(self) -> bool:
        """True when the data say with confidence that the pair is left-handed (mirrored); always False
        for a unit outside :data:`WARN_PLACEMENTS`."""
        return (self.placement in WARN_PLACEMENTS and self.segments >= MIN_SEGMENTS
                and bool(self.log_ratio < MIN_LOG_RATIO))

    @property
    def verdict(self) -> str:
        """``mirrored``, ``right-handed``, ``unsure`` (too few segments or between the thresholds) or
        ``not tested`` (a unit whose test is not adopted: the ratio is informative only)."""
        if self.placement not in WARN_PLACEMENTS:
            return "not tested"
        if self.segments < MIN_SEGMENTS:
            return "unsure"
        return "mirrored" if self.mirrored else "right-handed" if self.log_ratio > -MIN_LOG_RATIO else "unsure"

    def describe(self) -> str:
        what = "strides" if self.placement == "foot" else "moving windows"
        ratio = "no" if not np.isfinite(self.log_ratio) else f"{self.log_ratio:+.2f}"
        return f"{self.verdict} (log ratio {ratio} over {self.segments} {what}, decision D11)"

    def to_dict(self) -> dict:
        return {"log_ratio": None if not np.isfinite(self.log_ratio) else round(float(self.log_ratio), 3),
                "segments": int(self.segments), "verdict": self.verdict}


def _end_speed(acc: np.ndarray, gyr: np.ndarray, fs: float, i0: np.ndarray, i1: np.ndarray) -> np.ndarray:
    from pdrlearn.displace._kernels import strapdown, stride_index, zupt_velocity

    idx, mask = stride_index(i0, i1)
    a_nav, _ = strapdown(acc, gyr, 1.0 / fs, idx, mask, acc[i0])
    v = zupt_velocity(a_nav, mask, 1.0 / fs, zupt_end=False)
    return np.linalg.norm(v[np.arange(len(i0)), mask.sum(axis=1) - 1], axis=1)


def foot_handedness(acc: np.ndarray, gyr: np.ndarray, fs: float) -> Handedness:
    """Handedness test of a foot unit: specific force (n, 3) m/s^2 and angular rate (n, 3) rad/s on one
    clock of ``fs`` Hz. Pure function (the stance detector and stride integration of ``displace``)."""
    from pdrlearn.displace.foot import inertial_stance
    from pdrlearn.track.frame_inference import rest_to_rest

    acc, gyr = np.asarray(acc, dtype=float), np.asarray(gyr, dtype=float)
    i0, i1 = rest_to_rest(inertial_stance(acc, gyr, fs), fs)
    if not len(i0):
        return Handedness("foot", float("nan"), 0)
    vp, vm = _end_speed(acc, gyr, fs, i0, i1), _end_speed(acc, -gyr, fs, i0, i1)
    r = np.log(np.maximum(vm, 1e-9) / np.maximum(vp, 1e-9))
    return Handedness("foot", float(np.median(r)), int(len(r)))


def _detrended_energy(a_nav: np.ndarray, mask: np.ndarray, fs: float) -> np.ndarray:
    """Mean square (B,) of each window's velocity minus its least-squares straight line."""
    from pdrlearn.displace._kernels import zupt_velocity

    v = zupt_velocity(a_nav, mask, 1.0 / fs, zupt_end=False)
    L = v.shape[1]
    tt = np.arange(L) / fs
    A = np.stack([np.ones(L), tt - tt.mean()], axis=1)  # all windows have the same length
    coef = np.linalg.lstsq(A, v.transpose(1, 0, 2).reshape(L, -1), rcond=None)[0]
    r = v.transpose(1, 0, 2).reshape(L, -1) - A @ coef
    return (r.reshape(L, v.shape[0], 3) ** 2).sum(axis=2).mean(axis=0)


def waist_handedness(acc: np.ndarray, gyr: np.ndarray, fs: float) -> Handedness:
    """Handedness test of a waist unit (arguments as :func:`foot_handedness`). Pure function."""
    from pdrlearn.displace._kernels import strapdown, stride_index

    acc, gyr = np.asarray(acc, dtype=float), np.asarray(gyr, dtype=float)
    L = int(round(WAIST_WINDOW_S * fs))
    hop = max(1, int(round(WAIST_HOP_S * fs)))
    starts = np.arange(0, len(acc) - L, hop)
    if len(starts):
        norm = np.linalg.norm(acc, axis=1)
        sd = np.array([norm[a:a + L].std() for a in starts])
        starts = starts[sd > WAIST_MIN_ACC_SD]
    if not len(starts):
        return Handedness("waist", float("nan"), 0)
    idx, mask = stride_index(starts, starts + L - 1)
    e = []
    for sign in (1.0, -1.0):
        a_nav, _ = strapdown(acc, sign * gyr, 1.0 / fs, idx, mask, acc[starts])
        e.append(_detrended_energy(a_nav, mask, fs))
    r = np.log(np.maximum(e[1], 1e-12) / np.maximum(e[0], 1e-12))
    return Handedness("waist", float(np.median(r)), int(len(r)))


TESTS = {"foot": foot_handedness, "waist": waist_handedness}


def session_handedness(session, placement: str, *, max_s: float | None = None) -> Handedness | None:
    """The handedness test of a :class:`~pdrlearn.io.Session`'s ``placement`` unit (the gyroscope on the
    accelerometer's clock) over its first ``max_s`` seconds (default
    :data:`~pdrlearn.track.frame_inference.CHECK_SPAN_S`); ``None`` when the unit lacks either sensor,
    has too few samples or non-finite values."""
    from pdrlearn.io.sensors import UNIT_IMU
    from pdrlearn.signal.filters import interp_rows
    from pdrlearn.track.frame_inference import CHECK_SPAN_S

    if placement not in TESTS or placement not in UNIT_IMU:
        return None
    acc_n, gyr_n = UNIT_IMU[placement]
    if acc_n not in session.streams or gyr_n not in session.streams:
        return None
    acc_s, gyr_s = session.streams[acc_n], session.streams[gyr_n]
    if len(acc_s) < 16 or len(gyr_s) < 2 or not np.isfinite(acc_s.rate_hz):
        return None
    span = CHECK_SPAN_S if max_s is None else max_s
    n = int(np.searchsorted(acc_s.t, acc_s.t[0] + span, side="right"))
    acc, gyr = acc_s.values[:n], interp_rows(acc_s.t[:n], gyr_s.t, gyr_s.values)
    if not (np.isfinite(acc).all() and np.isfinite(gyr).all()):
        return None
    return TESTS[placement](acc, gyr, float(acc_s.rate_hz))


def check_handedness(session, placement: str) -> tuple[Handedness | None, str | None]:
    """The handedness test of the ``placement`` unit and, when the data say with confidence that its
    accelerometer and gyroscope form a left-handed pair (mirrored data), the warning (without the file
    location) with the fix; else ``None`` (decision D11)."""
    from pdrlearn.io.sensors import UNIT_IMU

    h = session_handedness(session, placement)
    if h is None or not h.mirrored:
        return h, None
    acc_n, gyr_n = UNIT_IMU[placement]
    err = ("the end-of-stride velocity error of the ZUPT integration" if placement == "foot"
           else "the velocity error of the walking windows")
    msg = (f"the {placement} unit's {acc_n} and {gyr_n} turn like a left-handed (mirrored) pair: {err} is "
           f"{np.exp(-h.log_ratio):.1f} times smaller with the gyroscope reversed (median of {h.segments}; "
           f"decision D11); the data were probably mirrored (one axis negated in both files, e.g. left-foot "
           f"data mirrored to look like a right foot, or a left-handed export): negate that axis back in both "
           f"{acc_n}.csv and {gyr_n}.csv (or re-export without mirroring); a \"frames\" entry cannot fix this")
    return h, msg


__all__ = ["Handedness", "foot_handedness", "waist_handedness", "session_handedness", "check_handedness",
           "MIN_LOG_RATIO", "MIN_SEGMENTS", "WARN_PLACEMENTS", "WAIST_WINDOW_S", "WAIST_HOP_S", "WAIST_MIN_ACC_SD"]
