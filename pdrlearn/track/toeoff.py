"""Toe-off (terminal contact) of each foot stride from the foot gyroscope (decision L73,
docs/decisions/localization.md).

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
"""

from __future__ import annotations

import numpy as np

from pdrlearn.warning_lines import coded

#: zero-phase low-pass of the sagittal rate (Hz), as gaitmap's FilteredRamppEventDetection (15 Hz on gyr_ml)
LOWPASS_HZ = 15.0
#: a stride votes on the axis sign only when its integrated sagittal angle reaches this (rad, 10 deg)
MIN_VOTE_ANGLE_RAD = np.radians(10.0)
#: decision L414: the shortest median stance time (s) at which L73 checked the stance times against a contact
#: reference - the smaller of `track datasets/real/gaitmap_level_{left,right} --toe-off`'s medians (0.692 / 0.701 s,
#: printed in session 34), rounded down to 0.01 s (L414's rule, fixed before reading it)
TOE_OFF_MIN_CHECKED_STANCE_S = 0.69
#: decision L73: the median stance-time error (ms) on those two recordings (ours - mocap), quoted in L414's line
TOE_OFF_STANCE_BIAS_MS = (-36.9, -40.1)


def stance_range_warning(summary: dict) -> str | None:
    """Decision L414: one line when a ``--toe-off`` track's ``median_stance_time_s`` is below
    :data:`TOE_OFF_MIN_CHECKED_STANCE_S`, the shortest contacts L73 checked (None otherwise, or without stance
    times). Decision L703: it states the known stance bias of the track's set-up (``info["stance_source"]``: force
    insoles or the IMU) in ms, in % of this walk's stance and in points of its gait cycle
    (``median_stride_time_s``)."""
    from pdrlearn.track.support_bias import STANCE_BIAS, bias_terms, setup_of, stance_bias_ms

    stance = summary.get("median_stance_time_s")
    if stance is None or not np.isfinite(stance) or stance >= TOE_OFF_MIN_CHECKED_STANCE_S:
        return None
    setup = setup_of((summary.get("info") or {}).get("stance_source"))
    cycle, rate = summary.get("median_stride_time_s"), summary.get("rate_hz")  # decision L737: the foot's rate
    terms = bias_terms(setup, cycle, rate)
    ms = [r for r in (stance_bias_ms(k, cycle, rate) for k in ([setup] if setup else STANCE_BIAS)) if r is not None]
    share = (f" ({100 * -max(r[1] for r in ms) / 1000 / stance:.0f}-{100 * -min(r[0] for r in ms) / 1000 / stance:.0f}"
             f" % of this walk's {stance:.3f} s stance)") if ms else ""
    return coded(f"median stance (contact) time {stance:.3f} s is below {TOE_OFF_MIN_CHECKED_STANCE_S:.2f} s, the "
            "range at which --toe-off's stance times were checked against a reference: one walk, gaitmap's level "
            "walks with mocap at 0.69-0.70 s median contact (decision L73); most ordinary walks have shorter contacts "
            f"and get this line. The known bias, in this walk's terms (L703): {terms}{share} (decision L414)",
                 "L414")  # decision E170


def _check(t, gyr) -> tuple[np.ndarray, np.ndarray]:
    t = np.asarray(t, dtype=float)
    gyr = np.asarray(gyr, dtype=float)
    if t.ndim != 1 or gyr.ndim != 2 or gyr.shape != (len(t), 3):
        raise ValueError(f"toe_off_times: gyr must be (N, 3) with N = len(t) = {len(t)}, got {gyr.shape}")
    if len(t) > 1 and not np.all(np.diff(t) > 0):
        raise ValueError("toe_off_times: t must increase strictly")
    if not (np.isfinite(t).all() and np.isfinite(gyr).all()):
        raise ValueError("toe_off_times: t and gyr must be finite")
    return t, gyr


def _windows(t: np.ndarray, start_s, end_s, event_s) -> tuple[np.ndarray, np.ndarray]:
    """Sample ranges [a, c) from each stride's start to its IC (its end when the IC is missing/outside)."""
    st, en, ev = (np.asarray(v, dtype=float) for v in (start_s, end_s, event_s))
    stop = np.where(np.isfinite(ev) & (ev > st) & (ev <= en), ev, en)
    a = np.searchsorted(t, np.where(np.isfinite(st), st, np.inf), side="left")
    c = np.searchsorted(t, np.where(np.isfinite(stop), stop, -np.inf), side="right")
    return a, np.maximum(c, a)


def sagittal_axis(t, gyr, start_s, end_s, event_s) -> np.ndarray:
    """(3,) unit vector in the sensor frame: the foot's mediolateral axis with toe-up rotation positive (see the
    module docstring); the gyroscope ``gyr`` (N, 3) rad/s on ``t`` (N,) s, strides ``start_s``..``end_s`` with
    IC ``event_s``. NaN (3,) when no stride has a sample."""
    t, gyr = _check(t, gyr)
    a, c = _windows(t, start_s, end_s, event_s)
    en = np.searchsorted(t, np.asarray(end_s, dtype=float), side="right")
    idx = np.concatenate([np.arange(i, max(i, j)) for i, j in zip(a, en, strict=True)] or [np.zeros(0, int)])
    idx = np.unique(idx.astype(int))
    if len(idx) < 3:
        return np.full(3, np.nan)
    g = gyr[idx]
    w, v = np.linalg.eigh(g.T @ g)  # second moment: rotation both ways about the same axis
    axis = v[:, np.argmax(w)]
    votes = 0
    for i, j in zip(a, c, strict=True):
        if j - i < 3:
            continue
        r = gyr[i:j] @ axis
        ang = np.concatenate([[0.0], np.cumsum(0.5 * (r[1:] + r[:-1]) * np.diff(t[i:j]))])
        big = np.abs(ang).max()
        if big < MIN_VOTE_ANGLE_RAD:
            continue
        first = ang[np.argmax(np.abs(ang) >= 0.5 * big)]
        votes += 1 if first < 0 else -1  # the push-off (toe-down) comes first
    return axis if votes >= 0 else -axis


def _lowpass(t: np.ndarray, x: np.ndarray, cutoff_hz: float) -> np.ndarray:
    from scipy.signal import butter, sosfiltfilt

    fs = 1.0 / float(np.median(np.diff(t)))
    if cutoff_hz >= 0.45 * fs or len(x) < 16:  # nothing to remove at this rate
        return x
    sos = butter(2, cutoff_hz, fs=fs, output="sos")
    return sosfiltfilt(sos, x)


def toe_off_times(t, gyr, start_s, end_s, event_s, *, axis=None, lowpass_hz: float | None = LOWPASS_HZ
                  ) -> np.ndarray:
    """(B,) s: the toe-off of each stride (decision L73), NaN where none can be had.

    ``t`` (N,) s and ``gyr`` (N, 3) rad/s: the foot gyroscope at its native rate, sensor frame. ``start_s``,
    ``end_s`` (B,): each stride's bounds from rest to rest; ``event_s`` (B,): its initial contact (IC; NaN or
    outside the window: the stride's end bounds the search). ``axis``: the sensor-frame mediolateral axis, toe-up
    positive (default :func:`sagittal_axis`). Per stride, on the low-passed sagittal rate: the swing's toe-up
    peak (the largest positive rate before the IC), then the toe-off at the most negative rate between the
    stride start and that peak (before the IC when the stride has no toe-up rate). NaN when that minimum is not
    a toe-down rotation, lies on the window's first sample (the push-off began before the stride) or the window
    is shorter than three samples.
    """
    t, gyr = _check(t, gyr)
    st = np.asarray(start_s, dtype=float)
    out = np.full(len(st), np.nan)
    if len(st) == 0 or len(t) < 3:
        return out
    u = sagittal_axis(t, gyr, start_s, end_s, event_s) if axis is None else np.asarray(axis, dtype=float)
    if not np.isfinite(u).all() or np.linalg.norm(u) == 0:
        return out
    r = gyr @ (u / np.linalg.norm(u))
    if lowpass_hz:
        r = _lowpass(t, r, float(lowpass_hz))
    a, c = _windows(t, start_s, end_s, event_s)
    for k, (i, j) in enumerate(zip(a, c, strict=True)):
        if j - i < 3:
            continue
        seg = r[i:j]
        peak = int(np.argmax(seg))
        stop = peak if seg[peak] > 0 and peak > 0 else len(seg)
        m = int(np.argmin(seg[:stop])) if stop > 0 else 0
        if seg[m] >= 0 or m == 0:
            continue
        g = i + m
        tc = t[g]
        if 0 < g < len(t) - 1:  # parabola through the three samples around the peak
            y0, y1, y2 = r[g - 1], r[g], r[g + 1]
            den = y0 - 2.0 * y1 + y2
            if den > 0:
                off = float(np.clip(0.5 * (y0 - y2) / den, -0.5, 0.5))
                tc = t[g] + off * (t[g + 1] - t[g] if off > 0 else t[g] - t[g - 1])
        out[k] = tc
    return out
