"""Turns of a lower-back unit from its yaw rate (decision L210), numpy only.

El-Gohary M, Pearson S, McNames J, et al. "Continuous monitoring of turning in patients with movement disability",
Sensors 2014 (Parkinson's disease turning), as mobgap's ``TdElGohary`` implements it (mobgap
``turning/_td_elgohary.py``; its defaults are this module's constants): the yaw rate is low-passed, each peak of its
magnitude of at least :data:`YAW_TURN_PEAK_DPS` is a turn candidate, the turn runs from the last sample under
:data:`YAW_TURN_EDGE_DPS` before the peak to the first one after it, candidates of one direction closer than
:data:`YAW_TURN_MERGE_S` are merged, and the turns of :data:`YAW_TURN_DURATION_S` and at least
:data:`YAW_TURN_MIN_DEG` are kept. Its angle is the unfiltered rate integrated over the turn.
"""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels.dsp import find_peaks, lowpass

#: mobgap TdElGohary: 4th-order Butterworth low-pass at 0.5 Hz, zero phase (its ButterworthFilter default)
YAW_TURN_LOWPASS_HZ = 0.5
YAW_TURN_LOWPASS_ORDER = 4
#: mobgap TdElGohary ``min_peak_angle_velocity_dps`` (El-Gohary 2014: a turn peaks at 15 deg/s or more)
YAW_TURN_PEAK_DPS = 15.0
#: mobgap TdElGohary ``lower_threshold_velocity_dps`` (El-Gohary 2014: a turn starts / ends under 5 deg/s)
YAW_TURN_EDGE_DPS = 5.0
#: mobgap TdElGohary ``min_gap_between_turns_s``
YAW_TURN_MERGE_S = 0.05
#: mobgap TdElGohary ``allowed_turn_duration_s`` (inclusive)
YAW_TURN_DURATION_S = (0.5, 10.0)
#: mobgap TdElGohary ``allowed_turn_angle_deg`` lower bound (deg)
YAW_TURN_MIN_DEG = 45.0
#: decision L345: the centred moving mean (s) of the integrated yaw a turn's 5-95 % times are read on (L201's truth
#: smoothing: one stride's pelvis rotation averaged out)
YAW_TURN_SMOOTH_S = 1.0
#: decision L208: the fractions of a turn's angle at which it is timed (L201's truth definition of a simulated turn:
#: the body's heading 5 % to 95 % of its change); :data:`pdrlearn.track.clinical.TURN_TIMING_FRACTIONS` is this one
#: (defined here, the lower layer, so this numpy-only module imports nothing of ``pdrlearn.track``)
TURN_TIMING_FRACTIONS = (0.05, 0.95)


def _merge(iv: np.ndarray, gap: int) -> np.ndarray:
    """Intervals ``[start, end)`` (k, 2) merged where one starts at most ``gap`` samples after the last ended."""
    if not len(iv):
        return iv
    iv = iv[np.argsort(iv[:, 0], kind="stable")]
    out = [list(iv[0])]
    for a, b in iv[1:]:
        if a <= out[-1][1] + gap:
            out[-1][1] = max(out[-1][1], b)
        else:
            out.append([a, b])
    return np.asarray(out, dtype=np.intp)


def lowpassed_yaw_rate(rate_dps: np.ndarray, fs: float) -> np.ndarray:
    """El-Gohary's low-passed yaw rate (deg/s, signed): the 0.5 Hz 4th-order Butterworth, forward and backward
    (mobgap TdElGohary's filter), whose |peak| :func:`yaw_rate_turns` detects a turn on; decision L235: that peak is
    a turn's peak rate."""
    return lowpass(np.asarray(rate_dps, dtype=np.float64), YAW_TURN_LOWPASS_HZ, fs, order=YAW_TURN_LOWPASS_ORDER)


def yaw_rate_turns(rate_dps: np.ndarray, fs: float) -> np.ndarray:
    """(k, 4) El-Gohary's turns (module docstring) of the yaw rate ``rate_dps`` (n,) deg/s sampled at ``fs`` Hz:
    each row ``start`` (index of the last sample under the edge rate before the turn, 0 at the recording's start),
    ``end`` (exclusive: the first sample under it after the turn, n at the end), ``peak`` (index of the largest
    filtered |rate| inside) and ``angle`` (deg, left +: the unfiltered rate integrated, trapezoid, from ``start``
    to ``end - 1``), in time order."""
    w = np.asarray(rate_dps, dtype=np.float64)
    n = w.size
    empty = np.zeros((0, 4))
    if n < 2 or not np.isfinite(w).all():
        return empty
    f = np.abs(lowpassed_yaw_rate(w, fs))
    peaks = find_peaks(f, height=YAW_TURN_PEAK_DPS)
    below = f < YAW_TURN_EDGE_DPS
    cross = np.flatnonzero(below[1:] != below[:-1])  # i: the state changes from sample i to i + 1
    if not peaks.size or not cross.size:
        return empty
    k = np.searchsorted(cross, peaks, side="left") - 1
    starts = np.where(k < 0, 0, cross[np.clip(k, 0, cross.size - 1)])
    k = np.searchsorted(cross + 1, peaks, side="right")
    ends = np.where(k >= cross.size, n - 1, cross[np.clip(k, 0, cross.size - 1)]) + 1
    yaw = np.concatenate([[0.0], np.cumsum(0.5 * (w[1:] + w[:-1]) / fs)])

    def angle(iv: np.ndarray) -> np.ndarray:
        return yaw[iv[:, 1] - 1] - yaw[iv[:, 0]]

    iv = np.column_stack([starts, ends]).astype(np.intp)
    side = np.sign(angle(iv))
    gap = int(round(YAW_TURN_MERGE_S * fs))
    iv = np.concatenate([_merge(iv[side == s], gap) for s in (-1.0, 0.0, 1.0)])
    iv = iv[np.argsort(iv[:, 0], kind="stable")]
    ang = angle(iv)
    dur = (iv[:, 1] - iv[:, 0]) / fs
    keep = (dur >= YAW_TURN_DURATION_S[0]) & (dur <= YAW_TURN_DURATION_S[1]) & (np.abs(ang) >= YAW_TURN_MIN_DEG)
    iv, ang = iv[keep], ang[keep]
    peak = np.asarray([a + int(np.argmax(f[a:b])) for a, b in iv], dtype=float)
    return np.column_stack([iv.astype(float), peak, ang]) if len(iv) else empty


def turn_fraction_times(rate_dps: np.ndarray, fs: float, turns: np.ndarray,
                        fractions: tuple[float, float] = TURN_TIMING_FRACTIONS) -> np.ndarray:
    """Decision L345: (k, 2) sample indices where each of ``turns`` (:func:`yaw_rate_turns`' rows: start, end
    exclusive, ...) has gone ``fractions`` of its yaw change (L208's 5 % / 95 %): the unfiltered rate ``rate_dps``
    integrated (trapezoid) and smoothed by a :data:`YAW_TURN_SMOOTH_S` centred moving mean (edges held), its change
    from the turn's start to its last sample; each index the first inside the turn at or beyond its fraction (the
    turn's own start / last sample where the smoothed yaw does not change)."""
    w = np.asarray(rate_dps, dtype=np.float64)
    turns = np.asarray(turns, dtype=float).reshape(-1, 4)
    if not len(turns):
        return np.zeros((0, 2), dtype=np.intp)
    yaw = np.concatenate([[0.0], np.cumsum(0.5 * (w[1:] + w[:-1]) / fs)])
    k = max(int(round(YAW_TURN_SMOOTH_S * fs)), 1)
    c = np.concatenate([[0.0], np.cumsum(np.pad(yaw, (k // 2, k - 1 - k // 2), mode="edge"))])
    ys = (c[k:] - c[:-k]) / k  # the centred k-sample mean, O(n) (a day's recording at 100 Hz)
    out = []
    for a, b in turns[:, :2].astype(np.intp):
        b = max(min(b, ys.size), a + 1)
        seg = ys[a:b] - ys[a]
        total = seg[-1]
        if total == 0 or not np.isfinite(total):
            out.append((a, b - 1))
            continue
        frac = seg / total
        i0 = int(np.argmax(frac >= fractions[0])) if (frac >= fractions[0]).any() else 0
        hit = frac[i0:] >= fractions[1]
        i1 = i0 + int(np.argmax(hit)) if hit.any() else b - 1 - a
        out.append((a + i0, a + i1))
    return np.asarray(out, dtype=np.intp)
