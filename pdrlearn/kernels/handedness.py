"""The mirrored-pair test of a foot unit's accelerometer and gyroscope (decision D11), numpy only: one
implementation for ``pdrlearn info`` / ``track`` (:func:`pdrlearn.io.handedness.foot_handedness`, strides from
its stance detector) and the streaming :class:`pdrlearn.runtime.Tracker` (its own strides, decision B129).

In a right-handed sensor frame a fixed world vector seen by the sensor turns against the angular rate,
d(g_b)/dt = -omega x g_b; a gyroscope whose sign is reversed, or data mirrored in one axis, obey +omega x g_b.
Each rest-to-rest stride is integrated as the ZUPT stride integration does (levelled by the start rest, attitude
from the gyroscope, gravity removed) with the gyroscope as recorded and reversed: the velocity at the end rest must
be zero, and a reversed attitude leaks gravity into it through the whole swing. Per stride:
log(|v_end(-omega)| / |v_end(+omega)|), > 0 right-handed (:mod:`pdrlearn.io.handedness` for the measurement).
"""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels.strapdown import cumtrapz, level_quat, qrotate, stride_index, stride_quaternions

#: Warn when the median per-stride / per-window log ratio (positive = right-handed) lies below this.
#: Measured (experiments/handedness_check.py, docs/frames.md): truthful real foot units +1.88 to +3.37,
#: their mirrored versions the negatives; truthful waist units and simulated units see docs/frames.md.
#: -1.0 (the reversed gyroscope fits e = 2.7 times better in the median segment) is conservative.
MIN_LOG_RATIO = -1.0
#: Least strides (foot) or moving windows (waist) for a verdict; fewer: no warning.
MIN_SEGMENTS = 4


def end_speeds(acc: np.ndarray, gyr: np.ndarray, dt: float, i0: np.ndarray, i1: np.ndarray,
               signs: tuple[float, ...] = (1.0, -1.0)) -> np.ndarray:
    """|velocity| (len(signs), B) at the end of each stride ``i0[b]..i1[b]`` of specific force ``acc`` (n, 3)
    m/s^2 and angular rate ``gyr`` (n, 3) rad/s on one clock ``dt`` s apart, integrated from rest (levelled by
    ``acc[i0]``, gravity ``|acc[i0]|`` removed) with the gyroscope times each of ``signs``; the signs are one
    batch (the loop over the stride's samples runs once)."""
    acc, gyr = np.asarray(acc, dtype=float), np.asarray(gyr, dtype=float)
    n, k = len(acc), len(signs)
    off = (np.arange(k) * n)[:, None]
    starts, ends = (off + np.asarray(i0)[None, :]).ravel(), (off + np.asarray(i1)[None, :]).ravel()
    A = np.tile(acc, (k, 1))
    G = np.concatenate([s * gyr for s in signs])
    idx, mask = stride_index(starts, ends)
    g_body = A[starts]
    # decision L626: D11's verdict compares two integrations of the same order; it keeps the first-order
    # propagation (its ratios as before; the coning term is for the track's attitude, not this vote)
    q = stride_quaternions(level_quat(g_body), G, dt, idx, mask, coning=0.0)
    a_nav = qrotate(q, A[idx])
    a_nav[:, :, 2] -= np.linalg.norm(g_body, axis=1)[:, None]
    a_nav[~mask] = 0.0
    v = cumtrapz(a_nav, dt)
    B = len(starts)
    return np.linalg.norm(v[np.arange(B), mask.sum(axis=1) - 1], axis=1).reshape(k, -1)


def log_ratio(v_other: np.ndarray, v_asis: np.ndarray) -> np.ndarray:
    """Per stride log(|v_end| of another gyroscope / |v_end| as recorded) (> 0: as recorded fits better)."""
    return np.log(np.maximum(v_other, 1e-9) / np.maximum(v_asis, 1e-9))


def mirror_log_ratios(acc: np.ndarray, gyr: np.ndarray, dt: float, i0: np.ndarray, i1: np.ndarray) -> np.ndarray:
    """Decision D11's per-stride log ratio (B,) of the strides ``i0[b]..i1[b]`` (arguments as :func:`end_speeds`):
    > 0 right-handed, < 0 the gyroscope reversed fits better."""
    vp, vm = end_speeds(acc, gyr, dt, i0, i1)
    return log_ratio(vm, vp)


def mirrored(median_log_ratio: float, segments: int) -> bool:
    """Decision D11's verdict: at least :data:`MIN_SEGMENTS` strides whose median log ratio lies below
    :data:`MIN_LOG_RATIO` (the gyroscope reversed fits e times better)."""
    return segments >= MIN_SEGMENTS and bool(median_log_ratio < MIN_LOG_RATIO)


def mirrored_pair_line(placement: str, acc_n: str, gyr_n: str, median_log_ratio: float, segments: int, err: str,
                       *, of: str = "", decision: str = "decision D11") -> str:
    """The first clause of the mirrored-pair warning (offline and live): the numbers of the test."""
    return (f"the {placement} unit's {acc_n} and {gyr_n} turn like a left-handed (mirrored) pair: {err} is "
            f"{np.exp(-median_log_ratio):.1f} times smaller with the gyroscope reversed (median of {segments}{of}; "
            f"{decision})")
