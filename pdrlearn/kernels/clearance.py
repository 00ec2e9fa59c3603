"""Decision L421: per-stride foot clearance and sole angles from a strapdown swing (pure numpy kernels).

The definitions follow gaitmap's ``SpatialParameterCalculation`` (its docs): the *max. sensor lift* is the
highest the sensor gets relative to its midstance height; the *sole angle* is the angle between the foot's
forward axis, rotated into the world frame, and the floor, positive toes up and 0 at midstance; the IC / TC
angles are the sole angle at initial contact / toe-off.
"""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels.strapdown import qrotate


def max_lift(pos: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """(B,) m: each stride's highest point above the straight line joining its first and last position.

    ``pos`` (B, L, 3) ENU positions of each stride's samples (any origin), ``mask`` (B, L) the valid ones (each
    stride starts at sample 0). The line's height at a sample is interpolated by the sample's horizontal progress
    along the start-to-end displacement (clipped to [0, 1]; a stride that does not move horizontally: its start
    height), so on level ground this is gaitmap's max. sensor lift (the height above the midstance height).
    """
    pos = np.asarray(pos, dtype=float)
    mask = np.asarray(mask, dtype=bool)
    B = pos.shape[0]
    if B == 0:
        return np.zeros(0)
    last = mask.sum(axis=1) - 1
    p0, p1 = pos[:, 0], pos[np.arange(B), last]
    d = p1[:, :2] - p0[:, :2]
    dd = np.sum(d * d, axis=1)
    rel = pos[:, :, :2] - p0[:, None, :2]
    frac = np.where(dd[:, None] > 1e-12, np.sum(rel * d[:, None, :], axis=2) / np.maximum(dd, 1e-12)[:, None], 0.0)
    line = p0[:, None, 2] + np.clip(frac, 0.0, 1.0) * (p1[:, 2] - p0[:, 2])[:, None]
    return np.max(np.where(mask, pos[:, :, 2] - line, -np.inf), axis=1)


def sole_pitch_deg(q: np.ndarray) -> np.ndarray:
    """(B, L) deg: the sole angle of every stride sample, positive toes up (gaitmap's convention).

    ``q`` (B, L, 4) body -> navigation quaternions [w, x, y, z] of each stride (sample 0 = the starting rest). The
    foot's forward axis is the body vector that points horizontally along the unit's x axis at that rest, so a
    sensor mounted pitched on the foot (an instep mount) reads 0 at midstance, as gaitmap's aligned sensor does.
    """
    q = np.asarray(q, dtype=float)
    B, L = q.shape[:2]
    if B == 0:
        return np.zeros((0, L))
    x0 = qrotate(q[:, 0], np.tile([1.0, 0.0, 0.0], (B, 1)))
    h = x0.copy()
    h[:, 2] = 0.0
    h /= np.maximum(np.linalg.norm(h, axis=1), 1e-12)[:, None]
    conj = q[:, 0] * np.array([1.0, -1.0, -1.0, -1.0])
    f_body = qrotate(conj, h)  # the horizontal forward direction at rest, in the body frame
    f = qrotate(q, f_body[:, None, :])  # broadcast over the stride's samples (decision L663: no repeated copy)
    return np.degrees(np.arcsin(np.clip(f[:, :, 2], -1.0, 1.0)))


def value_at(t_grid: np.ndarray, idx: np.ndarray, mask: np.ndarray, values: np.ndarray,
             times: np.ndarray) -> np.ndarray:
    """(B,) ``values`` (B, L) of each stride at its sample nearest ``times`` (B,) s (``t_grid`` (n,) the sample
    clock, ``idx`` (B, L) each stride's sample indices); NaN where the time is NaN or outside the stride."""
    times = np.asarray(times, dtype=float)
    B = len(times)
    out = np.full(B, np.nan)
    for b in np.flatnonzero(np.isfinite(times)):
        tb = t_grid[idx[b, mask[b]]]
        if not len(tb) or times[b] < tb[0] or times[b] > tb[-1]:
            continue
        out[b] = values[b, int(np.argmin(np.abs(tb - times[b])))]
    return out
