"""Backward travel of a foot stride (decisions L203, L224), one definition for the full tracks and the lean runtime.

A stride travels backward when its signed length is negative (the displacement points backward along the foot's
forward axis; a replayed stride's ``length_m`` carries that measured sign, decision L654),
unless it is a 0 m gap row (L67), a stride the last-line guard moved 0 m (``impossible``, L97), or a turn: a stride
turning :data:`BACKWARD_MAX_TURN_DEG` or more is a turn on the spot whose short chord can point anywhere (L203
amended), or a side step (decision L270): a stride of a side-stepping run (L219 / L228's ``sideways`` column; a
streamed table's runs whole, L243) travels sideways, and its chord's small backward component (the simulator's
``side`` item reads -0.38 to -0.44 m) is no backward travel. Standard library and numpy only.
"""

from __future__ import annotations

import math

import numpy as np

#: decision L203 (amended): a stride turning this much (deg) or more is a turn, not backward travel -- L119's turn
#: cue, :data:`pdrlearn.track.clinical.PAUSE_MAX_TURN_DEG` (a test pins the two equal)
BACKWARD_MAX_TURN_DEG = 30.0


def backward_mask(length_m, gap_s=None, impossible=None, turn_angle_rad=None, sideways=None,
                  streamed: bool = False) -> np.ndarray:
    """(n,) bool: the strides of signed lengths ``length_m`` that travel backward (module docstring); ``gap_s``,
    ``impossible``, ``turn_angle_rad`` and ``sideways`` (the side-stepping rows, decision L270) (n,) each optional
    (None: not known, no stride excluded by it; NaN turn: not a turn). ``streamed``: a streamed table, whose first
    measured stride has no facing before it and is not judged (decision L505)."""
    length = np.asarray(length_m, dtype=float)
    keep = np.ones(length.shape, bool)
    if gap_s is not None:
        keep &= ~(np.asarray(gap_s, dtype=float) > 0)
    if streamed and keep.any():
        keep[np.argmax(keep)] = False  # decision L505: the stream's first measured stride
    if impossible is not None:
        keep &= ~np.asarray(impossible, dtype=bool)
    if turn_angle_rad is not None:
        with np.errstate(invalid="ignore"):
            keep &= ~(np.abs(np.degrees(np.asarray(turn_angle_rad, dtype=float))) >= BACKWARD_MAX_TURN_DEG)
    if sideways is not None:
        keep &= ~np.asarray(sideways, dtype=bool)  # decision L270: a side step is no backward travel
    return (length < 0) & keep


def backward_rows(rows: list[dict]) -> list[bool]:
    """:func:`backward_mask` of a whole steps table given as row dicts (``length_m`` and optionally ``gap_s``,
    ``impossible``, ``turn_angle_rad``, ``sideways``; ``pivot_rad`` marks a streamed table, L106), for the lean
    runtime's steps.csv: the same flags as ``pdrlearn run``'s (:func:`pdrlearn.track.evaluate.backward_travel`),
    a streamed side run read whole (decisions L243, L270)."""
    from pdrlearn.kernels.sideways import side_rows

    def num(key):
        return [math.nan if r.get(key) is None else float(r[key]) for r in rows]

    streamed = any("pivot_rad" in r for r in rows)
    side = side_rows([bool(r.get("sideways") or False) for r in rows], num("gap_s"), streamed=streamed)
    return backward_mask(num("length_m"), num("gap_s"), [bool(r.get("impossible") or False) for r in rows],
                         num("turn_angle_rad"), side, streamed=streamed).tolist()  # L505


def is_backward(row: dict) -> bool:
    """:func:`backward_rows` of one row (a table of one stride)."""
    return backward_rows([row])[0]
