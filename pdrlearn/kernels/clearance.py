"""Decisions L421, L795: per-stride foot clearance (sensor lift, minimum toe clearance) and sole angles from a
strapdown swing (pure numpy kernels).

The definitions follow gaitmap's ``SpatialParameterCalculation`` (its docs): the *max. sensor lift* is the
highest the sensor gets relative to its midstance height; the *sole angle* is the angle between the foot's
forward axis, rotated into the world frame, and the floor, positive toes up and 0 at midstance; the IC / TC
angles are the sole angle at initial contact / toe-off.
"""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels.strapdown import qrotate


def height_above_line(pos: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """(B, L) m: each stride sample's height above the straight line joining the stride's first and last position.

    ``pos`` (B, L, 3) ENU positions of each stride's samples (any origin), ``mask`` (B, L) the valid ones (each
    stride starts at sample 0; -inf on the others). The line's height at a sample is interpolated by the sample's
    horizontal progress along the start-to-end displacement (clipped to [0, 1]; a stride that does not move
    horizontally: its start height), so on level ground this is the height above the midstance height.
    """
    pos = np.asarray(pos, dtype=float)
    mask = np.asarray(mask, dtype=bool)
    B = pos.shape[0]
    if B == 0:
        return np.zeros((0, pos.shape[1] if pos.ndim > 1 else 0))
    last = mask.sum(axis=1) - 1
    p0, p1 = pos[:, 0], pos[np.arange(B), last]
    d = p1[:, :2] - p0[:, :2]
    dd = np.sum(d * d, axis=1)
    rel = pos[:, :, :2] - p0[:, None, :2]
    frac = np.where(dd[:, None] > 1e-12, np.sum(rel * d[:, None, :], axis=2) / np.maximum(dd, 1e-12)[:, None], 0.0)
    line = p0[:, None, 2] + np.clip(frac, 0.0, 1.0) * (p1[:, 2] - p0[:, 2])[:, None]
    return np.where(mask, pos[:, :, 2] - line, -np.inf)


def max_lift(pos: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """(B,) m: each stride's highest point above the straight line joining its first and last position
    (:func:`height_above_line`); on level ground gaitmap's max. sensor lift (the height above the midstance height).
    """
    if np.asarray(pos).shape[0] == 0:
        return np.zeros(0)
    return np.max(height_above_line(pos, mask), axis=1)


def rest_forward_body(q: np.ndarray) -> np.ndarray:
    """(B, 3): the foot's forward axis in the body frame - the body vector that points horizontally along the unit's
    x axis at each stride's starting rest (``q`` (B, L, 4) body -> navigation quaternions [w, x, y, z], sample 0 the
    rest; decision L421's sole axis)."""
    q = np.asarray(q, dtype=float)
    B = q.shape[0]
    x0 = qrotate(q[:, 0], np.tile([1.0, 0.0, 0.0], (B, 1)))
    h = x0.copy()
    h[:, 2] = 0.0
    h /= np.maximum(np.linalg.norm(h, axis=1), 1e-12)[:, None]
    conj = q[:, 0] * np.array([1.0, -1.0, -1.0, -1.0])
    return qrotate(conj, h)


def sole_pitch_deg(q: np.ndarray) -> np.ndarray:
    """(B, L) deg: the sole angle of every stride sample, positive toes up (gaitmap's convention).

    ``q`` (B, L, 4) body -> navigation quaternions [w, x, y, z] of each stride (sample 0 = the starting rest). The
    foot's forward axis is :func:`rest_forward_body`, so a sensor mounted pitched on the foot (an instep mount) reads
    0 at midstance, as gaitmap's aligned sensor does.
    """
    q = np.asarray(q, dtype=float)
    B, L = q.shape[:2]
    if B == 0:
        return np.zeros((0, L))
    f = qrotate(q, rest_forward_body(q)[:, None, :])  # broadcast over the stride's samples (decision L663: no copy)
    return np.degrees(np.arcsin(np.clip(f[:, :, 2], -1.0, 1.0)))


def toe_height(pos: np.ndarray, q: np.ndarray, mask: np.ndarray, toe_offset_m: float) -> np.ndarray:
    """Decision L795: (B, L) m, the toe point's height above the line joining its two rests
    (:func:`height_above_line`; -inf on padding samples). The toe point is the sensor's position ``pos`` (B, L, 3)
    plus R(t) (``toe_offset_m`` x :func:`rest_forward_body`), the rigid-foot model of Mariani et al. 2012 (IEEE TBME
    59(11), heel and toe clearance from a foot IMU), the toe taken at the sensor's height."""
    q = np.asarray(q, dtype=float)
    mask = np.asarray(mask, dtype=bool)
    if q.shape[0] == 0:
        return np.zeros((0, q.shape[1]))
    q = np.where(mask[..., None], q, np.array([1.0, 0.0, 0.0, 0.0]))  # padding samples: any valid attitude
    r = float(toe_offset_m) * rest_forward_body(q)
    return height_above_line(np.asarray(pos, dtype=float) + qrotate(q, r[:, None, :]), mask)


def min_clearance(height: np.ndarray, i_from: np.ndarray, i_to: np.ndarray, *, rise_frac: float = 0.1,
                  min_samples: int = 5) -> np.ndarray:
    """Decision L795: (B,) m, each stride's minimum toe clearance: the lowest of ``height`` (B, L) (:func:`toe_height`)
    after the toe's first peak of the swing up to the contact - the highest point in the first half of the window
    ``i_from`` .. ``i_to`` (the toe-off's and the contact's sample, inclusive), the definition of the MTC in mid-swing
    (Mariani et al. 2012). ``i_from`` < 0 (no toe-off): the window starts where the toe first rises above
    ``rise_frac`` of its highest point before the contact. NaN where ``i_to`` < 0 or the window is under
    ``min_samples``."""
    height = np.asarray(height, dtype=float)
    out = np.full(height.shape[0], np.nan)
    for b in range(height.shape[0]):
        a, e = int(i_from[b]), int(i_to[b])
        if e < 0:
            continue
        h = height[b, : e + 1]
        if a < 0:
            top = np.max(h)
            if not np.isfinite(top) or top <= 0:
                continue
            a = int(np.argmax(h > rise_frac * top))
        w = h[a:]
        if len(w) < min_samples or not np.all(np.isfinite(w)):
            continue
        k = int(np.argmax(w[: len(w) // 2 + 1]))
        out[b] = float(np.min(w[k:]))
    return out


def sample_at(t_grid: np.ndarray, idx: np.ndarray, mask: np.ndarray, times: np.ndarray) -> np.ndarray:
    """(B,) int: the position in each stride (0 .. its samples - 1) of its sample nearest ``times`` (B,) s, -1 where a
    time is NaN or outside the stride (``t_grid`` (n,) the sample clock, ``idx`` (B, L) each stride's samples)."""
    times = np.asarray(times, dtype=float)
    out = np.full(len(times), -1, dtype=int)
    for b in np.flatnonzero(np.isfinite(times)):
        tb = t_grid[idx[b, mask[b]]]
        if not len(tb) or times[b] < tb[0] or times[b] > tb[-1]:
            continue
        out[b] = int(np.argmin(np.abs(tb - times[b])))
    return out


def value_at(t_grid: np.ndarray, idx: np.ndarray, mask: np.ndarray, values: np.ndarray,
             times: np.ndarray) -> np.ndarray:
    """(B,) ``values`` (B, L) of each stride at its sample nearest ``times`` (B,) s (``t_grid`` (n,) the sample
    clock, ``idx`` (B, L) each stride's sample indices); NaN where the time is NaN or outside the stride."""
    at = sample_at(t_grid, idx, mask, times)
    out = np.full(len(at), np.nan)
    ok = at >= 0
    out[ok] = np.asarray(values)[np.flatnonzero(ok), at[ok]]
    return out
