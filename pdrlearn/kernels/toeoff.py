"""Toe-off (terminal contact) of each foot stride from the foot gyroscope (decision L73,
docs/decisions/localization.md), numpy only (decision E326: moved here from :mod:`pdrlearn.track.toeoff` so the
lean runtime calls the same code).

The toe-off is the instant of the largest toe-down (plantarflexion) angular velocity of the foot about its
mediolateral axis during the push-off, before the swing's toe-up peak: the negative sagittal-gyro peak before the
swing. Sources: gaitmap's HerzerEventDetection places TC at the gyr_ml minimum around the stride start (the
push-off); Salarian et al. 2004 (IEEE TBME 51(8)) take toe-off at the negative gyro peak before the swing's
positive peak (shank); gaitmap's FilteredRamppEventDetection low-passes gyr_ml at 15 Hz before its TC/IC search
(Rampp et al. 2015, IEEE TBME 62(4)).

Mounting-free: the mediolateral axis is found in the sensor frame from the data (the foot is rigid with the sensor,
so the axis is constant there): the principal axis of the gyroscope over the strides (sagittal rotation dominates
walking, Rampp et al. 2015 use gyr_ml for the same reason). Its sign (toe-up positive) comes from a majority vote
of the strides: after the rest, the first large excursion of the integrated angle is the push-off, toe-down
(heel first off the ground, toes last), in level walking as on stairs up and down. A recording walked mostly
backwards would get the sign wrong (its push-off lifts the toes first).

Everything is in seconds: the peak is refined to sub-sample time with a parabola through its three samples, so
the result does not hang on the native rate.

- :func:`toe_off_times`: every stride of a whole recording (offline ``--toe-off``, ``run --gait``).
- :class:`LiveToeOff`: one stride at a time as a stream returns it (decision E326, ``Tracker(gait=True)``): the
  same per-stride search and filter on the stride's own samples, the axis and its vote from the strides so far.
"""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels.dsp import butter_sos, sosfiltfilt

#: zero-phase low-pass of the sagittal rate (Hz), as gaitmap's FilteredRamppEventDetection (15 Hz on gyr_ml)
LOWPASS_HZ = 15.0
#: a stride votes on the axis sign only when its integrated sagittal angle reaches this (rad, 10 deg)
MIN_VOTE_ANGLE_RAD = np.radians(10.0)


def check_gyro(t, gyr) -> tuple[np.ndarray, np.ndarray]:
    """``(t, gyr)`` as float arrays; ValueError unless ``gyr`` is (N, 3) on a strictly increasing finite ``t``."""
    t = np.asarray(t, dtype=float)
    gyr = np.asarray(gyr, dtype=float)
    if t.ndim != 1 or gyr.ndim != 2 or gyr.shape != (len(t), 3):
        raise ValueError(f"toe_off_times: gyr must be (N, 3) with N = len(t) = {len(t)}, got {gyr.shape}")
    if len(t) > 1 and not np.all(np.diff(t) > 0):
        raise ValueError("toe_off_times: t must increase strictly")
    if not (np.isfinite(t).all() and np.isfinite(gyr).all()):
        raise ValueError("toe_off_times: t and gyr must be finite")
    return t, gyr


def stride_windows(t: np.ndarray, start_s, end_s, event_s) -> tuple[np.ndarray, np.ndarray]:
    """Sample ranges [a, c) from each stride's start to its IC (its end when the IC is missing/outside)."""
    st, en, ev = (np.asarray(v, dtype=float) for v in (start_s, end_s, event_s))
    stop = np.where(np.isfinite(ev) & (ev > st) & (ev <= en), ev, en)
    a = np.searchsorted(t, np.where(np.isfinite(st), st, np.inf), side="left")
    c = np.searchsorted(t, np.where(np.isfinite(stop), stop, -np.inf), side="right")
    return a, np.maximum(c, a)


def principal_axis(moment: np.ndarray) -> np.ndarray:
    """(3,) the unit eigenvector of the largest eigenvalue of the gyroscope's second moment ``moment`` (3, 3; rotation
    both ways about the same axis counts alike); its sign is arbitrary."""
    w, v = np.linalg.eigh(moment)
    return v[:, np.argmax(w)]


def stride_vote(t: np.ndarray, gyr: np.ndarray, axis: np.ndarray, i: int, j: int) -> int:
    """One stride's vote on ``axis``'s sign over samples [i, j): +1 when the first large excursion of its integrated
    rate about ``axis`` is negative (the push-off is toe-down, so ``axis`` is toe-up positive), -1 when positive, 0
    when the window is under three samples or never turns :data:`MIN_VOTE_ANGLE_RAD`."""
    if j - i < 3:
        return 0
    r = gyr[i:j] @ axis
    ang = np.concatenate([[0.0], np.cumsum(0.5 * (r[1:] + r[:-1]) * np.diff(t[i:j]))])
    big = np.abs(ang).max()
    if big < MIN_VOTE_ANGLE_RAD:
        return 0
    first = ang[np.argmax(np.abs(ang) >= 0.5 * big)]
    return 1 if first < 0 else -1  # the push-off (toe-down) comes first


def sagittal_axis(t, gyr, start_s, end_s, event_s) -> np.ndarray:
    """(3,) unit vector in the sensor frame: the foot's mediolateral axis with toe-up rotation positive (see the
    module docstring); the gyroscope ``gyr`` (N, 3) rad/s on ``t`` (N,) s, strides ``start_s``..``end_s`` with
    IC ``event_s``. NaN (3,) when no stride has a sample."""
    t, gyr = check_gyro(t, gyr)
    a, c = stride_windows(t, start_s, end_s, event_s)
    en = np.searchsorted(t, np.asarray(end_s, dtype=float), side="right")
    idx = np.concatenate([np.arange(i, max(i, j)) for i, j in zip(a, en, strict=True)] or [np.zeros(0, int)])
    idx = np.unique(idx.astype(int))
    if len(idx) < 3:
        return np.full(3, np.nan)
    g = gyr[idx]
    axis = principal_axis(g.T @ g)
    votes = sum(stride_vote(t, gyr, axis, i, j) for i, j in zip(a, c, strict=True))
    return axis if votes >= 0 else -axis


def lowpass_rate(t: np.ndarray, x: np.ndarray, cutoff_hz: float) -> np.ndarray:
    """``x`` on ``t`` low-passed zero-phase at ``cutoff_hz`` (2nd-order Butterworth, gaitmap's 15 Hz on gyr_ml; as
    ``scipy.signal.sosfiltfilt``, :mod:`pdrlearn.kernels.dsp`); unchanged at a rate under 2.2 x the cutoff or under
    16 samples (nothing to remove)."""
    fs = 1.0 / float(np.median(np.diff(t)))
    if cutoff_hz >= 0.45 * fs or len(x) < 16:  # nothing to remove at this rate
        return x
    return sosfiltfilt(butter_sos(2, cutoff_hz, fs), x)


def window_toe_off(t: np.ndarray, r: np.ndarray, i: int, j: int) -> float:
    """The toe-off (s) in samples [i, j) of the low-passed sagittal rate ``r`` (toe-up positive) on ``t``: the most
    negative rate before the swing's toe-up peak (the largest positive rate; the whole window without one), refined
    by a parabola through its three samples; NaN when the window is under three samples, the minimum is no toe-down
    rotation or lies on the window's first sample (the push-off began before the stride)."""
    if j - i < 3:
        return np.nan
    seg = r[i:j]
    peak = int(np.argmax(seg))
    stop = peak if seg[peak] > 0 and peak > 0 else len(seg)
    m = int(np.argmin(seg[:stop])) if stop > 0 else 0
    if seg[m] >= 0 or m == 0:
        return np.nan
    g = i + m
    tc = float(t[g])
    if 0 < g < len(t) - 1:  # parabola through the three samples around the peak
        y0, y1, y2 = r[g - 1], r[g], r[g + 1]
        den = y0 - 2.0 * y1 + y2
        if den > 0:
            off = float(np.clip(0.5 * (y0 - y2) / den, -0.5, 0.5))
            tc = float(t[g] + off * (t[g + 1] - t[g] if off > 0 else t[g] - t[g - 1]))
    return tc


def toe_off_times(t, gyr, start_s, end_s, event_s, *, axis=None, lowpass_hz: float | None = LOWPASS_HZ
                  ) -> np.ndarray:
    """(B,) s: the toe-off of each stride (decision L73), NaN where none can be had.

    ``t`` (N,) s and ``gyr`` (N, 3) rad/s: the foot gyroscope at its native rate, sensor frame. ``start_s``,
    ``end_s`` (B,): each stride's bounds from rest to rest; ``event_s`` (B,): its initial contact (IC; NaN or
    outside the window: the stride's end bounds the search). ``axis``: the sensor-frame mediolateral axis, toe-up
    positive (default :func:`sagittal_axis`). Per stride, on the low-passed sagittal rate: the swing's toe-up
    peak (the largest positive rate before the IC), then the toe-off at the most negative rate between the
    stride start and that peak (:func:`window_toe_off`).
    """
    t, gyr = check_gyro(t, gyr)
    st = np.asarray(start_s, dtype=float)
    out = np.full(len(st), np.nan)
    if len(st) == 0 or len(t) < 3:
        return out
    u = sagittal_axis(t, gyr, start_s, end_s, event_s) if axis is None else np.asarray(axis, dtype=float)
    if not np.isfinite(u).all() or np.linalg.norm(u) == 0:
        return out
    r = gyr @ (u / np.linalg.norm(u))
    if lowpass_hz:
        r = lowpass_rate(t, r, float(lowpass_hz))
    a, c = stride_windows(t, start_s, end_s, event_s)
    for k, (i, j) in enumerate(zip(a, c, strict=True)):
        out[k] = window_toe_off(t, r, int(i), int(j))
    return out


class LiveToeOff:
    """Decision E326: L73's toe-off of one foot's strides as a stream returns them. :meth:`stride` takes one stride's
    gyroscope samples (from ``pad_s`` before its start to its end, as the caller's buffer holds them) and gives its
    toe-off by :func:`toe_off_times`' search and filter on those samples; the sagittal axis is the principal axis
    of the second moment of every stride's samples so far (this one included), its sign the running sum of the
    strides' votes (:func:`stride_vote`; each new axis is turned to agree with the previous one, so the earlier votes
    keep their meaning). Offline filters the whole recording and reads the axis from all its strides: the same
    arithmetic, on less."""

    def __init__(self, *, lowpass_hz: float | None = LOWPASS_HZ, pad_s: float = 0.5):
        self.lowpass_hz = lowpass_hz
        self.pad_s = float(pad_s)
        self.moment = np.zeros((3, 3))
        self.axis: np.ndarray | None = None
        self.votes = 0

    def stride(self, t, gyr, start_s: float, end_s: float, event_s: float) -> float:
        """The toe-off (s) of the stride ``[start_s, end_s]`` with IC ``event_s`` from its samples ``t`` (N,) s,
        ``gyr`` (N, 3) rad/s (NaN when none can be had, and for samples :func:`check_gyro` would refuse: a stream's
        stride never stops the tracker)."""
        t, gyr = np.asarray(t, dtype=float), np.asarray(gyr, dtype=float)
        if gyr.shape != (len(t), 3):
            raise ValueError(f"LiveToeOff.stride: gyr must be (N, 3) with N = len(t) = {len(t)}, got {gyr.shape}")
        if len(t) < 3 or not (np.isfinite(t).all() and np.isfinite(gyr).all()) or np.any(np.diff(t) <= 0):
            return np.nan
        a, c = stride_windows(t, [start_s], [end_s], [event_s])
        i, j = int(a[0]), int(c[0])
        en = int(np.searchsorted(t, float(end_s), side="right"))
        g = gyr[i:max(i, en)]
        self.moment += g.T @ g
        if not np.any(self.moment):
            return np.nan
        axis = principal_axis(self.moment)
        if self.axis is not None and float(axis @ self.axis) < 0:
            axis = -axis  # keep the earlier votes' sense
        self.axis = axis
        self.votes += stride_vote(t, gyr, axis, i, j)
        u = axis if self.votes >= 0 else -axis
        r = gyr @ u
        if self.lowpass_hz:
            r = lowpass_rate(t, r, float(self.lowpass_hz))
        return window_toe_off(t, r, i, j)
