"""Decision B454's candidate: declip an accelerometer or gyroscope file, numpy / scipy only.

Each run of clipped samples on one axis (B77 / B311's :func:`~pdrlearn.io.validate.clipped_axes`) is replaced by a
cubic through the :data:`DECLIP_CONTEXT` unclipped samples either side of it (trial T3 finding F1's user-side
declipping, scratch declip.py), kept at or beyond the rail on the rail's side: a saturated sensor only tells that the
true value was at least its full scale.
"""
from __future__ import annotations

import numpy as np

#: decision B454 (trial T3 F1's candidate, measured as it was given): unclipped samples fitted on each side of a run
DECLIP_CONTEXT = 3


def declip_axis(col: np.ndarray, clipped: np.ndarray) -> np.ndarray:
    """Decision B454: one axis ``col`` with its ``clipped`` samples (boolean, same length) replaced, run by run, by
    a not-a-knot cubic spline through up to :data:`DECLIP_CONTEXT` samples either side, its value held at least at the
    rail (|value| >= |col| there, the rail's sign); a run with fewer than 4 samples around it is left as it is."""
    from scipy.interpolate import CubicSpline

    out = np.array(col, dtype=float)
    edges = np.diff(np.concatenate([[0], np.asarray(clipped, dtype=np.int8), [0]]))
    for a, b in zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1), strict=True):
        around = np.r_[max(0, a - DECLIP_CONTEXT):a, b:min(len(out), b + DECLIP_CONTEXT)]
        around = around[~np.asarray(clipped, dtype=bool)[around]]
        if around.size < 4:
            continue
        fit = CubicSpline(around, out[around])(np.arange(a, b))
        rail = out[a:b]
        out[a:b] = np.where(np.sign(fit) == np.sign(rail), np.sign(rail) * np.maximum(np.abs(fit), np.abs(rail)),
                            rail)
    return out


def declip(values: np.ndarray, clipped: np.ndarray) -> np.ndarray:
    """Decision B454: ``values`` (n x axes) with each axis's ``clipped`` samples (same shape) declipped by
    :func:`declip_axis`; ``values`` unchanged (a copy) where nothing is clipped."""
    v = np.array(values, dtype=float)
    if not np.asarray(clipped).any():
        return v
    return np.column_stack([declip_axis(v[:, j], clipped[:, j]) for j in range(v.shape[1])])
