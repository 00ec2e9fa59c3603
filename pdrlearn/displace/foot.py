"""Per-stride displacement of the foot unit (thesis ch.7.2.1): stance, ZUPT/ZARU, attitude,
gravity removal and integration (equations of motion or the white-noise-jerk Kalman filter)."""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd

from pdrlearn.displace import _kernels as K
from pdrlearn.errors import DataError
from pdrlearn.io.session import Session
from pdrlearn.orient import FootAttitude, UnitData
from pdrlearn.signal import standstill_mask
from pdrlearn.signal.conditioning import runs

log = logging.getLogger(__name__)


def force_stance(session: Session, t: np.ndarray, *, level: float = 0.2) -> np.ndarray | None:
    """Stance samples from the heel + toe force sensors: load above ``level`` x its 95th percentile.

    Returns None when the session has no force sensor. Works in N or normalised units (relative level).
    """
    names = [n for n in ("fForceA", "fForceB") if n in session.streams and len(session.streams[n]) >= 2]
    if not names:
        return None
    total = np.zeros(t.shape[0])
    for n in names:
        s = session.streams[n]
        total += np.interp(t, s.t, s.values[:, 0])
    ref = float(np.percentile(total, 95))
    if not np.isfinite(ref) or ref <= 0:
        return None
    return total > level * ref


def inertial_stance(acc: np.ndarray, gyr: np.ndarray, fs: float, *, window_s: float = 0.1,
                    acc_tol: float = 1.5, gyr_tol: float = 1.0) -> np.ndarray:
    """Foot-flat samples from accelerometer + gyroscope (short window, looser tolerances than
    :func:`pdrlearn.signal.standstill_mask`, whose test this reuses)."""
    return standstill_mask(acc, gyr, fs, window_s=max(window_s, 2.5 / fs), acc_tol=acc_tol, gyr_tol=gyr_tol)


def snap_to_rest(t: np.ndarray, stance: np.ndarray, times: np.ndarray, *, half_window_s: float) -> np.ndarray:
    """Sample index of each time, moved to the nearest stance sample within +-``half_window_s`` when the
    time itself is not in stance (a detector's boundary slightly off the foot-flat period)."""
    i = np.clip(np.searchsorted(t, np.asarray(times, dtype=float)), 0, len(t) - 1)
    st_idx = np.flatnonzero(stance)
    if st_idx.size == 0 or half_window_s <= 0:
        return i
    pos = np.clip(np.searchsorted(st_idx, i), 1, st_idx.size - 1) if st_idx.size > 1 else np.zeros_like(i)
    cand = np.stack([st_idx[np.maximum(pos - 1, 0)], st_idx[pos]])
    best = cand[np.argmin(np.abs(cand - i), axis=0), np.arange(len(i))]
    ok = (~stance[i]) & (np.abs(t[best] - t[i]) <= half_window_s)
    return np.where(ok, best, i)


class FootDisplacement:
    """Displacement of each stride of the foot unit between two rests.

    Parameters
    ----------
    integrator : ``"kalman"`` (white-noise-jerk filter with ZUPT + RTS smoothing, thesis eq. 44-55) or
        ``"integration"`` (double integration, equations of motion)
    zupt_end : remove the velocity found at the stride end (ZUPT drift correction); ``False`` only
        resets the velocity at each stride start (the traditional accelerometer method, M1)
    gyro_bias : gyroscope offset removed: ``"standstill"`` (the thesis' setup standstill, ch.7.2.1; none
        found -> no correction), ``"stance"`` (mean rate of the stance run before each stride) or ``"none"``.
        The attitude itself is re-initialised from gravity at every stride start (ZARU).
    attitude : ``"kalman"`` -> initial roll/pitch of each stride from the 2-state angle Kalman filter
        (thesis eq. 40-43); ``"accel"`` -> from the accelerometer at rest (thesis eq. 38/39)
    sw, r : white-noise-jerk filter settings (thesis ch.7.2.1: Sw = 1.8, R = 0.01)
    snap_s : a stride boundary outside stance moves to the nearest stance sample within +- this (s)
    rest_s : half-width (s) of the window averaged for gravity at a stride boundary

    Attributes
    ----------
    disp_ : (B, 3) displacement (m) in each stride's level frame (x = foot forward at the start, z up)
    yaw_change_ : (B,) foot heading change over each stride (rad, CCW)
    start_idx_, end_idx_ : (B,) sample indices of the stride boundaries used
    stance_ : (n,) bool stance mask;  stance_source_ : "force" or "inertial"
    """

    def __init__(self, *, integrator: str = "kalman", zupt_end: bool = True, gyro_bias: str = "standstill",
                 attitude: str = "kalman", sw: float = 1.8, r: float = 0.01, snap_s: float = 0.2,
                 rest_s: float = 0.05):
        if integrator not in ("kalman", "integration"):
            raise DataError(f"FootDisplacement: integrator '{integrator}' is not 'kalman' or 'integration'")
        if attitude not in ("kalman", "accel"):
            raise DataError(f"FootDisplacement: attitude '{attitude}' is not 'kalman' or 'accel'")
        self.integrator = integrator
        self.zupt_end = zupt_end
        if gyro_bias not in ("standstill", "stance", "none"):
            raise DataError(f"FootDisplacement: gyro_bias '{gyro_bias}' is not standstill, stance or none")
        self.gyro_bias = gyro_bias
        self.attitude = attitude
        self.sw = sw  # thesis ch.7.2.1: Sw = 1.8
        self.r = r  # thesis eq. 55: R = 0.01
        self.snap_s = snap_s
        self.rest_s = rest_s

    def estimate(self, unit: UnitData, steps: pd.DataFrame, *,
                 stance: np.ndarray | None = None) -> FootDisplacement:
        """Estimate the displacement of each row (``start_s``, ``end_s``) of ``steps``.

        ``stance`` (n,) bool on ``unit.t``; default: the inertial stance detector.
        """
        t, acc, gyr, fs = unit.t, unit.acc, unit.gyr, unit.fs
        self.warnings_: list[str] = []
        dt = 1.0 / fs
        self.stance_source_ = "inertial" if stance is None else "given"
        self.stance_ = inertial_stance(acc, gyr, fs) if stance is None else np.asarray(stance, dtype=bool)
        st = steps["start_s"].to_numpy(dtype=float)
        en = steps["end_s"].to_numpy(dtype=float)
        half = self.snap_s
        i0 = snap_to_rest(t, self.stance_, st, half_window_s=half)
        i1 = snap_to_rest(t, self.stance_, en, half_window_s=half)
        i1 = np.maximum(i1, i0 + 2)
        i1 = np.minimum(i1, len(t) - 1)
        self.start_idx_, self.end_idx_ = i0, i1
        B = len(i0)
        w = max(1, int(round(self.rest_s * fs)))
        csum = np.concatenate([np.zeros((1, 3)), np.cumsum(acc, axis=0)])
        lo = np.clip(i0 - w, 0, len(t))
        hi = np.clip(i0 + w + 1, 0, len(t))
        g_body = (csum[hi] - csum[lo]) / (hi - lo)[:, None]
        init = None
        if self.attitude == "kalman" and B:
            att = FootAttitude().estimate(acc, gyr, fs, self.stance_)
            self.attitude_ = att
            from scipy.spatial.transform import Rotation

            roll, pitch = att.roll_[i0], att.pitch_[i0]
            init = Rotation.from_euler("YX", np.column_stack([pitch, roll]))  # R = Ry(pitch) Rx(roll)
        bias = None
        if self.gyro_bias == "stance" and B:
            bias = self._zaru_bias(gyr, i0, fs)
        elif self.gyro_bias == "standstill" and B:
            bias = np.tile(self._standstill_bias(acc, gyr, fs), (B, 1))
        idx, mask = K.stride_index(i0, i1)
        a_nav, self.yaw_change_ = K.strapdown(acc, gyr, dt, idx, mask, g_body, bias, init)
        zm = K.zupt_mask(self.stance_, idx, mask)
        if self.integrator == "kalman":
            self.disp_ = K.wnj_displacement(a_nav, mask, dt, sw=self.sw, r=self.r, zupt=self.zupt_end,
                                            zupt_at=zm)
        else:
            self.disp_ = K.double_integrate(a_nav, mask, dt, zupt_end=self.zupt_end, zupt=zm)
        return self

    def _standstill_bias(self, acc: np.ndarray, gyr: np.ndarray, fs: float,
                         min_s: float = 1.0) -> np.ndarray:
        """Gyroscope offset (rad/s) over the first standstill of >= ``min_s`` s (thesis ch.7.2.1 setup)."""
        still = standstill_mask(acc, gyr, fs)
        for a, b in runs(still):
            if (b - a) / fs >= min_s:
                return gyr[a:b].mean(axis=0)
        self.warnings_.append("no standstill of 1 s: gyroscope offset not removed")
        return np.zeros(3)

    def _zaru_bias(self, gyr: np.ndarray, i0: np.ndarray, fs: float) -> np.ndarray:
        """Mean rate over the stance run around each stride start (ZARU: the foot does not turn at rest);
        falls back to a +-rest_s window when the start is not in a detected stance run."""
        bias = np.zeros((len(i0), 3))
        run_of = np.full(len(gyr), -1)
        rr = runs(self.stance_)
        for k, (a, b) in enumerate(rr):
            run_of[a:b] = k
        w = max(1, int(round(self.rest_s * fs)))
        for s, i in enumerate(i0):
            k = run_of[i]
            a, b = rr[k] if k >= 0 else (max(i - w, 0), min(i + w + 1, len(gyr)))
            bias[s] = gyr[a:b].mean(axis=0)
        return bias

    def foot_heading(self, initial: float = 0.0) -> np.ndarray:
        """Foot heading (rad, ENU) at each stride start: the stride yaw changes accumulated (ZARU between
        strides, so the heading does not change at rest)."""
        return initial + np.concatenate([[0.0], np.cumsum(self.yaw_change_)[:-1]]) if len(self.yaw_change_) \
            else np.zeros(0)


