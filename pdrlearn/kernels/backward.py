"""Backward travel of a foot stride (decisions L203, L224), one definition for the full tracks and the lean runtime.

A stride travels backward when its signed length is negative (the displacement points backward along the foot's
forward axis; a replayed stride's ``length_m`` is negative only for a stride classed backward, thesis eq. 61's sign),
unless it is a 0 m gap row (L67), a stride the last-line guard moved 0 m (``impossible``, L97), or a turn: a stride
turning :data:`BACKWARD_MAX_TURN_DEG` or more is a turn on the spot whose short chord can point anywhere (L203
amended). Standard library and numpy only.
"""

from __future__ import annotations

import math

import numpy as np

#: decision L203 (amended): a stride turning this much (deg) or more is a turn, not backward travel -- L119's turn
#: cue, :data:`pdrlearn.track.clinical.PAUSE_MAX_TURN_DEG` (a test pins the two equal)
BACKWARD_MAX_TURN_DEG = 30.0


def backward_mask(length_m, gap_s=None, impossible=None, turn_angle_rad=None) -> np.ndarray:
    """(n,) bool: the strides of signed lengths ``length_m`` that travel backward (module docstring); ``gap_s``,
    ``impossible`` and ``turn_angle_rad`` (n,) each optional (None: not known, no stride excluded by it; NaN turn:
    not a turn)."""
    length = np.asarray(length_m, dtype=float)
    keep = np.ones(length.shape, bool)
    if gap_s is not None:
        keep &= ~(np.asarray(gap_s, dtype=float) > 0)
    if impossible is not None:
        keep &= ~np.asarray(impossible, dtype=bool)
    if turn_angle_rad is not None:
        with np.errstate(invalid="ignore"):
            keep &= ~(np.abs(np.degrees(np.asarray(turn_angle_rad, dtype=float))) >= BACKWARD_MAX_TURN_DEG)
    return (length < 0) & keep


def is_backward(row: dict) -> bool:
    """:func:`backward_mask` of one steps-table row (a dict with ``length_m`` and optionally ``gap_s``,
    ``impossible``, ``turn_angle_rad``), for the lean runtime's steps.csv."""
    def num(key):
        v = row.get(key)
        return math.nan if v is None else float(v)

    return bool(backward_mask([num("length_m")], [num("gap_s")], [bool(row.get("impossible") or False)],
                              [num("turn_angle_rad")])[0])
