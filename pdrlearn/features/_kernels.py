"""Pure numerical kernels of :mod:`pdrlearn.features` (no classes, no sessions).

Attitude of a foot unit through one step (gyroscope propagation from the stance, tilt drift spread
over the swing), the heading of a step in the levelled frame, and the per-signal statistics that the
thesis features are built from (peaks, peak instants, sums, segment max/min/mean/slope).
"""

from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

from pdrlearn.signal import gravity_rotation


def rest_index(acc: np.ndarray, gyr: np.ndarray | None, lo: int, hi: int) -> int:
    """Index in ``[lo, hi)`` where the unit moves least.

    Motion score = gyroscope norm (rad/s) when a gyroscope exists, plus the deviation of the
    specific-force norm from its window median scaled to rad/s-like magnitude (1 m/s^2 ~ 0.1 rad/s).
    """
    lo = max(0, lo)
    hi = max(lo + 1, min(hi, acc.shape[0]))
    an = np.linalg.norm(acc[lo:hi], axis=1)
    score = 0.1 * np.abs(an - np.median(np.linalg.norm(acc, axis=1)))
    if gyr is not None:
        score = score + np.linalg.norm(gyr[lo:hi], axis=1)
    return lo + int(np.argmin(score))


def propagate_attitude(gyr: np.ndarray, dt: np.ndarray, k0: int, r0: np.ndarray) -> np.ndarray:
    """Attitudes ``R_k`` (n, 3, 3), sensor -> levelled frame, from ``R_{k0} = r0`` and the angular rate.

    ``dR/dt = R [w]x`` integrated with the exact rotation of each sample interval
    (``R_{k+1} = R_k exp([w_k dt_k]x)``), forward and backward from ``k0``.

    Parameters
    ----------
    gyr : (n, 3) angular rate in the sensor frame (rad/s)
    dt : (n - 1,) sample intervals (s)
    """
    n = gyr.shape[0]
    out = np.empty((n, 3, 3))
    out[k0] = r0
    if n < 2:
        return out
    w = 0.5 * (gyr[:-1] + gyr[1:]) * dt[:, None]  # mean rate over each interval
    steps = Rotation.from_rotvec(w).as_matrix()
    if k0 < n - 1:  # forward: R_{k0+j} = r0 @ steps[k0] @ ... @ steps[k0+j-1]
        out[k0 + 1:] = r0 @ prefix_products(steps[k0:])
    if k0 > 0:  # backward: R_{k0-j} = r0 @ steps[k0-1].T @ ... @ steps[k0-j].T
        back = prefix_products(np.transpose(steps[:k0][::-1], (0, 2, 1)))
        out[:k0] = (r0 @ back)[::-1]
    return out


def prefix_products(m: np.ndarray) -> np.ndarray:
    """Inclusive prefix products ``m[0] @ m[1] @ ... @ m[k]`` of a stack of matrices (n, 3, 3).

    Hillis-Steele scan: log2(n) batched matrix products instead of a Python loop over the samples.
    """
    p = np.array(m, dtype=np.float64, copy=True)
    shift = 1
    while shift < p.shape[0]:
        p[shift:] = p[:-shift] @ p[shift:]
        shift *= 2
    return p


def correct_tilt_drift(rot: np.ndarray, g_end_sensor: np.ndarray, k0: int, k1: int) -> np.ndarray:
    """Spread the tilt error seen at the second rest ``k1`` linearly over ``k0..k1``.

    At ``k1`` the levelled specific force should point straight up; the minimal rotation that makes
    it so is applied with weight ``(k - k0) / (k1 - k0)`` (clipped to 0..1) to every sample.
    """
    if k1 <= k0:
        return rot
    g_lev = rot[k1] @ g_end_sensor
    corr = Rotation.from_matrix(gravity_rotation(g_lev)).as_rotvec()
    frac = np.clip((np.arange(rot.shape[0]) - k0) / float(k1 - k0), 0.0, 1.0)
    c = Rotation.from_rotvec(frac[:, None] * corr[None, :]).as_matrix()
    return c @ rot


def heading_rotation(forward_xy: np.ndarray) -> np.ndarray:
    """Rotation about z (3x3) that turns the horizontal unit vector ``forward_xy`` onto +x."""
    c, s = float(forward_xy[0]), float(forward_xy[1])
    return np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])


def principal_horizontal_axis(acc_lev: np.ndarray, reference_xy: np.ndarray) -> np.ndarray:
    """Unit principal axis of the horizontal acceleration, signed to agree with ``reference_xy``.

    The foot accelerates and brakes along its direction of travel, so the dominant eigenvector of the
    horizontal second-moment matrix is the line of the step; the sign (toes side) comes from the
    declared forward axis of the sensor, so backward steps keep their sign.
    """
    h = acc_lev[:, :2]
    m = h.T @ h
    vals, vecs = np.linalg.eigh(m)
    e = vecs[:, int(np.argmax(vals))]
    if float(e @ reference_xy) < 0:
        e = -e
    return e / np.linalg.norm(e)


# -- per-signal statistics on (n_steps, n_samples) arrays ------------------------------------------


def peak_stats(sig: np.ndarray, t: np.ndarray) -> dict[str, np.ndarray]:
    """Peak and sum statistics of each row of ``sig`` (n, m) sampled at times ``t`` (n, m) (s).

    Returns arrays (n,): ``min``, ``max``, ``t_min``, ``t_max`` (s from the step start), ``dt_peaks``
    (= t_max - t_min, s), ``abs_dt_peaks``, ``range`` (= max - min), ``peak_asym`` (= |max| - |min|),
    ``sum_pos`` / ``sum_neg`` (time integral of the positive part / magnitude of the negative part,
    unit x s; the thesis sums samples at 20 Hz, see docs/decisions/features.md), ``pos_minus_neg``.
    """
    n = sig.shape[0]
    rows = np.arange(n)
    i_min = np.argmin(sig, axis=1)
    i_max = np.argmax(sig, axis=1)
    vmin = sig[rows, i_min]
    vmax = sig[rows, i_max]
    t0 = t[:, :1]
    tt = t - t0
    dt = np.gradient(tt, axis=1)  # sample weights (s) on the possibly non-uniform grid
    sum_pos = np.sum(np.clip(sig, 0, None) * dt, axis=1)
    sum_neg = np.sum(np.clip(-sig, 0, None) * dt, axis=1)
    t_min = tt[rows, i_min]
    t_max = tt[rows, i_max]
    return {
        "min": vmin,
        "max": vmax,
        "t_min": t_min,
        "t_max": t_max,
        "dt_peaks": t_max - t_min,
        "abs_dt_peaks": np.abs(t_max - t_min),
        "range": vmax - vmin,
        "peak_asym": np.abs(vmax) - np.abs(vmin),
        "sum_pos": sum_pos,
        "sum_neg": sum_neg,
        "pos_minus_neg": sum_pos - sum_neg,
        "duration": tt[:, -1],
    }


def segment_bounds(m: int, n_segments: int) -> list[tuple[int, int]]:
    """Index ranges ``[a, b)`` of ``n_segments`` nearly equal consecutive parts of ``m`` samples."""
    if n_segments < 1 or n_segments > m:
        raise ValueError(f"n_segments={n_segments} must be between 1 and the window length {m}")
    edges = np.linspace(0, m, n_segments + 1).round().astype(int)
    return [(int(edges[i]), int(edges[i + 1])) for i in range(n_segments)]


def segment_stats(sig: np.ndarray, t: np.ndarray, n_segments: int = 6) -> np.ndarray:
    """Segment features (thesis ch. 6.1.1.2): per part max, min, mean and slope.

    The signal of each step (row of ``sig``, (n, m)) is divided into ``n_segments`` equal parts; for
    each part the maximum, minimum, mean and the slope between its first and last sample
    (``(x_last - x_first) / (t_last - t_first)``, unit/s) are returned, in that order:
    output (n, 4 * n_segments) = ``[max_1, min_1, mean_1, slope_1, max_2, ...]``.
    """
    n, m = sig.shape
    bounds = segment_bounds(m, n_segments)
    starts = np.array([a for a, _ in bounds])
    last = np.array([b - 1 for _, b in bounds])
    sizes = np.array([b - a for a, b in bounds], dtype=float)
    out = np.empty((n, n_segments, 4))
    out[:, :, 0] = np.maximum.reduceat(sig, starts, axis=1)
    out[:, :, 1] = np.minimum.reduceat(sig, starts, axis=1)
    out[:, :, 2] = np.add.reduceat(sig, starts, axis=1) / sizes
    span = t[:, last] - t[:, starts]
    with np.errstate(invalid="ignore", divide="ignore"):
        slope = (sig[:, last] - sig[:, starts]) / span
    out[:, :, 3] = np.where(span > 0, slope, 0.0)
    out = out.reshape(n, 4 * n_segments)
    return out


def _interp_rows(t_query: np.ndarray, t: np.ndarray, sig: np.ndarray) -> np.ndarray:
    """``sig[i]`` at time ``t_query[i]`` (clamped to the window), (n,)."""
    return np.array([np.interp(tq, ti, si) for tq, ti, si in zip(t_query, t, sig, strict=True)])


def force_stats(force: np.ndarray, t: np.ndarray, *, zero_fraction: float = 0.05,
                sample_s: float = 0.05) -> dict[str, np.ndarray]:
    """Force-sensor statistics of each step (thesis Table 29 and ch. 6.3.1), rows of ``force`` (n, m).

    A sample is "zero" (foot in the air) when below ``zero_fraction`` x the step's peak force. The
    thesis counts PLASYS samples (20 Hz, thesis ch. 4.3.2: 50 ms); here counts are times (s) and
    "the k-th measurement" is ``k * sample_s`` seconds.

    Returns (n,) arrays: ``air_time`` (s of zero force; Table 29 #1), ``time_to_peak`` (s from the last
    zero to the contact peak; Table 29 #2), ``peak_mean_4`` (mean force 4 samples before and after the
    contact peak; Table 29 #3), ``contact_force_2`` (force 2 samples after the last zero; Table 29 #4),
    ``takeoff_force`` (force 2 samples before the first zero; ch. 6.3.1).
    """
    n, m = force.shape
    tt = t - t[:, :1]
    dt = np.gradient(tt, axis=1)
    peak = force.max(axis=1, keepdims=True)
    zero = force < zero_fraction * np.where(peak > 0, peak, 1.0)
    air = np.sum(zero * dt, axis=1)
    any_zero = zero.any(axis=1)
    last_zero = np.where(any_zero, m - 1 - np.argmax(zero[:, ::-1], axis=1), np.argmin(force, axis=1))
    first_zero = np.where(any_zero, np.argmax(zero, axis=1), np.argmin(force, axis=1))
    rows = np.arange(n)
    after = np.arange(m)[None, :] >= last_zero[:, None]
    i_peak = np.argmax(np.where(after, force, -np.inf), axis=1)
    t_last = tt[rows, last_zero]
    t_peak = tt[rows, i_peak]
    return {
        "air_time": air,
        "time_to_peak": t_peak - t_last,
        "peak_mean_4": 0.5 * (_interp_rows(t_peak - 4 * sample_s, tt, force)
                              + _interp_rows(t_peak + 4 * sample_s, tt, force)),
        "contact_force_2": _interp_rows(t_last + 2 * sample_s, tt, force),
        "takeoff_force": _interp_rows(tt[rows, first_zero] - 2 * sample_s, tt, force),
    }
