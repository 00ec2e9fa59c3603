"""Numpy-only kernels of the runtime: step-frame attitude, step statistics, DTW, soft vote.

These mirror the training side (:mod:`pdrlearn.features._kernels`, :func:`pdrlearn.signal.gravity_rotation`,
:mod:`pdrlearn.classify.dtw`, :mod:`pdrlearn.classify.fusion`), whose modules import scipy, scikit-learn
or pandas at module level and so cannot be loaded by the runtime (decision E5, docs/decisions/export.md).
``tests/test_runtime_parity.py`` checks every function here against its training-side counterpart.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from pdrlearn.errors import DataError


# -- rotations --------------------------------------------------------------------------------------
def _skew(k: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])


def gravity_rotation(g_sensor: np.ndarray) -> np.ndarray:
    """Minimal rotation (3x3) with ``R @ g = [0, 0, |g|]`` (Rodrigues about ``g x z``)."""
    g = np.asarray(g_sensor, dtype=np.float64).reshape(3)
    n = float(np.linalg.norm(g))
    if not np.isfinite(n) or n < 1e-9:
        raise DataError(f"gravity vector {g.tolist()} is zero or not finite; the step has no rest sample")
    a = g / n
    c = float(a[2])
    v = np.array([a[1], -a[0], 0.0])  # a x z
    s = float(np.linalg.norm(v))
    if s < 1e-12:
        return np.eye(3) if c > 0 else np.diag([1.0, -1.0, -1.0])
    kx = _skew(v / s)
    return np.eye(3) + s * kx + (1 - c) * (kx @ kx)


def rotvec_to_matrix(w: np.ndarray) -> np.ndarray:
    """Rotation matrices ``(n, 3, 3)`` of rotation vectors ``(n, 3)`` (rad), Rodrigues' formula."""
    w = np.atleast_2d(np.asarray(w, dtype=np.float64))
    th = np.linalg.norm(w, axis=1)
    small = th < 1e-8
    safe = np.where(small, 1.0, th)
    # sin(th)/th and (1-cos th)/th^2 with their Taylor series near 0
    a = np.where(small, 1.0 - th**2 / 6.0, np.sin(th) / safe)
    b = np.where(small, 0.5 - th**2 / 24.0, (1.0 - np.cos(th)) / safe**2)
    K = np.zeros((len(w), 3, 3))
    K[:, 0, 1], K[:, 0, 2], K[:, 1, 2] = -w[:, 2], w[:, 1], -w[:, 0]
    K[:, 1, 0], K[:, 2, 0], K[:, 2, 1] = w[:, 2], -w[:, 1], w[:, 0]
    return np.eye(3)[None] + a[:, None, None] * K + b[:, None, None] * (K @ K)


def matrix_to_rotvec(R: np.ndarray) -> np.ndarray:
    """Rotation vector (3,) of a rotation matrix (angle < pi, the minimal tilt corrections used here)."""
    c = np.clip((np.trace(R) - 1.0) / 2.0, -1.0, 1.0)
    th = math.acos(c)
    v = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    if th < 1e-8:
        return 0.5 * v
    if math.pi - th < 1e-6:  # 180 deg: axis from the symmetric part
        k = np.sqrt(np.clip((np.diag(R) + 1.0) / 2.0, 0.0, None))
        i = int(np.argmax(k))
        k = (R[i] + R[:, i]) / (2.0 * k[i]) if k[i] > 0 else k
        k[i] = math.sqrt(max((R[i, i] + 1.0) / 2.0, 0.0))
        return th * k / np.linalg.norm(k)
    return th * v / (2.0 * math.sin(th))


def rest_index(acc: np.ndarray, gyr: np.ndarray | None, lo: int, hi: int) -> int:
    """Index in ``[lo, hi)`` where the unit moves least (gyro norm + 0.1 x |acc| deviation)."""
    lo = max(0, lo)
    hi = max(lo + 1, min(hi, acc.shape[0]))
    an = np.linalg.norm(acc[lo:hi], axis=1)
    score = 0.1 * np.abs(an - np.median(np.linalg.norm(acc, axis=1)))
    if gyr is not None:
        score = score + np.linalg.norm(gyr[lo:hi], axis=1)
    return lo + int(np.argmin(score))


def propagate_attitude(gyr: np.ndarray, dt: np.ndarray, k0: int, r0: np.ndarray) -> np.ndarray:
    """Attitudes ``(n, 3, 3)`` from ``R_k0 = r0``, ``R_{k+1} = R_k exp([w dt]x)`` forward and backward."""
    n = gyr.shape[0]
    out = np.empty((n, 3, 3))
    out[k0] = r0
    if n < 2:
        return out
    steps = rotvec_to_matrix(0.5 * (gyr[:-1] + gyr[1:]) * dt[:, None])
    if k0 < n - 1:  # forward: R_{k0+j} = r0 @ steps[k0] @ ... @ steps[k0+j-1]
        out[k0 + 1 :] = r0 @ prefix_products(steps[k0:])
    if k0 > 0:  # backward, with the transposed steps
        out[:k0] = (r0 @ prefix_products(np.transpose(steps[:k0][::-1], (0, 2, 1))))[::-1]
    return out


def prefix_products(m: np.ndarray) -> np.ndarray:
    """Inclusive prefix products ``m[0] @ ... @ m[k]`` of ``(n, 3, 3)`` matrices (Hillis-Steele scan)."""
    p = np.array(m, dtype=np.float64, copy=True)
    shift = 1
    while shift < p.shape[0]:
        p[shift:] = p[:-shift] @ p[shift:]
        shift *= 2
    return p


def correct_tilt_drift(rot: np.ndarray, g_end_sensor: np.ndarray, k0: int, k1: int) -> np.ndarray:
    """Spread the tilt error seen at rest ``k1`` linearly over ``k0..k1``."""
    if k1 <= k0:
        return rot
    corr = matrix_to_rotvec(gravity_rotation(rot[k1] @ g_end_sensor))
    frac = np.clip((np.arange(rot.shape[0]) - k0) / float(k1 - k0), 0.0, 1.0)
    return rotvec_to_matrix(frac[:, None] * corr[None, :]) @ rot


def heading_rotation(forward_xy: np.ndarray) -> np.ndarray:
    """Rotation about z turning the horizontal unit vector ``forward_xy`` onto +x."""
    c, s = float(forward_xy[0]), float(forward_xy[1])
    return np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])


def principal_horizontal_axis(acc_lev: np.ndarray, reference_xy: np.ndarray) -> np.ndarray:
    """Unit principal axis of the horizontal acceleration, signed to agree with ``reference_xy``."""
    h = acc_lev[:, :2]
    vals, vecs = np.linalg.eigh(h.T @ h)
    e = vecs[:, int(np.argmax(vals))]
    if float(e @ reference_xy) < 0:
        e = -e
    return e / np.linalg.norm(e)


# -- step statistics (rows = steps) -----------------------------------------------------------------
def _gradient(tt: np.ndarray) -> np.ndarray:
    """``np.gradient(tt, axis=1)`` for unit spacing (same formula, without its overhead)."""
    g = np.empty_like(tt)
    g[:, 0] = tt[:, 1] - tt[:, 0]
    g[:, -1] = tt[:, -1] - tt[:, -2]
    g[:, 1:-1] = (tt[:, 2:] - tt[:, :-2]) / 2.0
    return g


def peak_stats(sig: np.ndarray, t: np.ndarray) -> dict[str, np.ndarray]:
    """Peaks, peak instants (s from the step start) and time integrals of each row (thesis ch. 6.1.1.1)."""
    rows = np.arange(sig.shape[0])
    i_min, i_max = np.argmin(sig, axis=1), np.argmax(sig, axis=1)
    vmin, vmax = sig[rows, i_min], sig[rows, i_max]
    tt = t - t[:, :1]
    dt = _gradient(tt)
    sum_pos = np.sum(np.clip(sig, 0, None) * dt, axis=1)
    sum_neg = np.sum(np.clip(-sig, 0, None) * dt, axis=1)
    t_min, t_max = tt[rows, i_min], tt[rows, i_max]
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


@functools.lru_cache(maxsize=64)
def _segment_edges(m: int, n_segments: int) -> tuple[np.ndarray, np.ndarray]:
    edges = np.linspace(0, m, n_segments + 1).round().astype(int)
    return edges[:-1], edges[1:]


def segment_stats(sig: np.ndarray, t: np.ndarray, n_segments: int = 6) -> np.ndarray:
    """Per part of ``n_segments`` equal parts: max, min, mean, slope (thesis ch. 6.1.1.2)."""
    n, m = sig.shape
    a, b = _segment_edges(m, n_segments)
    mx = np.maximum.reduceat(sig, a, axis=1)
    mn = np.minimum.reduceat(sig, a, axis=1)
    mean = np.add.reduceat(sig, a, axis=1) / (b - a)
    span = t[:, b - 1] - t[:, a]
    d = sig[:, b - 1] - sig[:, a]
    slope = np.divide(d, span, out=np.zeros_like(d), where=span > 0)
    return np.stack([mx, mn, mean, slope], axis=2).reshape(n, 4 * n_segments)


def force_stats(
    force: np.ndarray, t: np.ndarray, *, zero_fraction: float = 0.05, sample_s: float = 0.05
) -> dict[str, np.ndarray]:
    """Force statistics of each row (thesis Table 29, ch. 6.3.1; 50 ms PLASYS sample, thesis ch. 4.3.2)."""
    n, m = force.shape
    tt = t - t[:, :1]
    dt = _gradient(tt)
    peak = force.max(axis=1, keepdims=True)
    zero = force < zero_fraction * np.where(peak > 0, peak, 1.0)
    any_zero = zero.any(axis=1)
    last_zero = np.where(any_zero, m - 1 - np.argmax(zero[:, ::-1], axis=1), np.argmin(force, axis=1))
    first_zero = np.where(any_zero, np.argmax(zero, axis=1), np.argmin(force, axis=1))
    rows = np.arange(n)
    i_peak = np.argmax(np.where(np.arange(m)[None, :] >= last_zero[:, None], force, -np.inf), axis=1)
    t_last, t_peak = tt[rows, last_zero], tt[rows, i_peak]

    def at(tq):
        return np.array([np.interp(q, ti, si) for q, ti, si in zip(tq, tt, force, strict=True)])

    return {
        "air_time": np.sum(zero * dt, axis=1),
        "time_to_peak": t_peak - t_last,
        "peak_mean_4": 0.5 * (at(t_peak - 4 * sample_s) + at(t_peak + 4 * sample_s)),
        "contact_force_2": at(t_last + 2 * sample_s),
        "takeoff_force": at(tt[rows, first_zero] - 2 * sample_s),
    }


# -- DTW --------------------------------------------------------------------------------------------
def dtw_to_refs(q: np.ndarray, refs: np.ndarray, window: int | None) -> np.ndarray:
    """DTW distance of one query ``(n, c)`` to every reference ``(r, n, c)``, vectorised over references
    (anti-diagonal-free row recursion: each row's in-row dependency is a cumulative min-plus scan)."""
    r, n, _ = refs.shape
    m = q.shape[0]
    w = max(n, m) if window is None else max(int(window), abs(n - m) + 1)
    cost = ((q[None, :, None, :] - refs[:, None, :, :]) ** 2).sum(axis=3)  # (r, m, n)
    prev = np.full((r, n + 1), np.inf)
    prev[:, 0] = 0.0
    for i in range(1, m + 1):
        j0, j1 = max(1, i - w + 1), min(n, i + w - 1)
        row = np.full((r, n + 1), np.inf)
        diag_up = np.minimum(prev[:, j0 - 1 : j1], prev[:, j0 : j1 + 1])  # (r, k)
        c = cost[:, i - 1, j0 - 1 : j1]
        acc = row[:, j0 - 1]
        for k in range(j1 - j0 + 1):
            acc = c[:, k] + np.minimum(diag_up[:, k], acc)
            row[:, j0 + k] = acc
        prev = row
    return np.sqrt(prev[:, n])


# -- fusion -----------------------------------------------------------------------------------------
def softmax(z: np.ndarray) -> np.ndarray:
    z = z - z.max(axis=1, keepdims=True)
    e = np.exp(z)
    return e / e.sum(axis=1, keepdims=True)


def soft_vote(probas: list[np.ndarray], weights) -> np.ndarray:
    """Weighted mean of aligned probability matrices, rows renormalised (thesis ch. 6 fusion rows)."""
    w = np.asarray(weights, dtype=float)
    fused = sum(wi * p for wi, p in zip(w, probas, strict=True)) / max(w.sum(), 1e-12)
    return fused / np.clip(fused.sum(axis=1, keepdims=True), 1e-12, None)
