"""Backward travel of a foot stride (decisions L203, L224), one definition for the full tracks and the lean runtime.

A stride travels backward when its signed length is negative (the displacement points backward along the foot's
forward axis; a replayed stride's ``length_m`` carries that measured sign, decision L654),
unless it is a 0 m gap row (L67), a stride the last-line guard moved 0 m (``impossible``, L97), or a turn: a stride
turning :data:`BACKWARD_MAX_TURN_DEG` or more is a turn on the spot whose short chord can point anywhere (L203
amended) when its chord is under :data:`SPOT_MAX_CHORD_M` (L692: a longer one travelled, and its sign,
:func:`signed_chord`, is judged against the foot's mid-stride facing), or a side step (decision L270): a stride of
a side-stepping run (L219 / L228's ``sideways`` column; a streamed table's runs whole, L243) travels sideways, and
its chord's small backward component (the simulator's ``side`` item reads -0.38 to -0.44 m) is no backward travel.
Standard library and numpy only.
"""

from __future__ import annotations

import math

import numpy as np

#: decision L203 (amended): a stride turning this much (deg) or more is a turn, not backward travel -- L119's turn
#: cue, :data:`pdrlearn.track.clinical.PAUSE_MAX_TURN_DEG` (a test pins the two equal)
BACKWARD_MAX_TURN_DEG = 30.0
#: decision L692: a stride turning BACKWARD_MAX_TURN_DEG or more is on the spot only when its horizontal chord is
#: shorter than this (m): two of S41's pivot steps (``sim.path.PIVOT_MAX_STEP_M`` 0.3 m, "beyond this it is a
#: curve"; a foot stride spans two steps; a test pins the two)
SPOT_MAX_CHORD_M = 0.6


def _turning(turn_rad) -> np.ndarray:
    """(n,) bool: the strides whose own turn ``turn_rad`` is :data:`BACKWARD_MAX_TURN_DEG` or more (NaN: not)."""
    with np.errstate(invalid="ignore"):
        return np.abs(np.asarray(turn_rad, dtype=float)) >= math.radians(BACKWARD_MAX_TURN_DEG)


def on_the_spot(turn_rad, chord_m) -> np.ndarray:
    """Decision L692 (amends L203 / L578): (n,) bool, the strides that turn on the spot - their own turn
    ``turn_rad`` :data:`BACKWARD_MAX_TURN_DEG` or more and their chord ``|chord_m|`` (m; a NaN chord: on the spot)
    under :data:`SPOT_MAX_CHORD_M`. Their short chord points anywhere: no travel direction (steps.csv travel turn)."""
    with np.errstate(invalid="ignore"):
        return _turning(turn_rad) & ~(np.abs(np.asarray(chord_m, dtype=float)) >= SPOT_MAX_CHORD_M)


def signed_chord(dx, dy, turn_rad, frame_rad=0.0) -> np.ndarray:
    """Decision L692: (n,) each stride's horizontal chord ``hypot(dx, dy)`` (m) signed by its measured travel
    (steps.csv ``raw_length_m``): a stride turning under :data:`BACKWARD_MAX_TURN_DEG` (or NaN) by the sign of its x
    along the foot's facing at its start (as before); a turning stride negative when its chord points within 60 deg
    of straight back from the foot's mid-stride facing (the facing at its start turned by half its own turn; outside
    L219's 60-120 deg side window, ``kernels.sideways.SIDE_ANGLE_DEG``). ``dx``, ``dy`` in the step frame, which is
    turned ``frame_rad`` from the foot's facing at the stride's start (decision L34's; 0 offline)."""
    from pdrlearn.kernels.sideways import SIDE_ANGLE_DEG

    dx, dy = np.asarray(dx, dtype=float), np.asarray(dy, dtype=float)
    turn = np.asarray(turn_rad, dtype=float)
    chord = np.hypot(dx, dy)
    with np.errstate(invalid="ignore"):
        mid = np.arctan2(dy, dx) + np.asarray(frame_rad, dtype=float) - 0.5 * turn  # from the mid-stride facing
        back = np.where(_turning(turn), np.cos(mid) < math.cos(math.radians(SIDE_ANGLE_DEG[1])), dx < 0)
    return chord * np.where(back, -1.0, 1.0)


def first_unjudged(n: int, gap_s=None, streamed: bool = True) -> np.ndarray:
    """Decisions L505, E318: (n,) bool, a streamed table's first measured row (the first with no ``gap_s`` > 0), which
    no stream judges backward or side (no facing before it); all False for an offline table (``streamed`` False)."""
    out = np.zeros(n, bool)
    if streamed and n:
        with np.errstate(invalid="ignore"):
            measured = np.ones(n, bool) if gap_s is None else ~(np.asarray(gap_s, dtype=float) > 0)
        if measured.any():
            out[np.argmax(measured)] = True
    return out


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
    keep &= ~first_unjudged(len(length), gap_s, streamed)  # decision L505: the stream's first measured stride
    if impossible is not None:
        keep &= ~np.asarray(impossible, dtype=bool)
    if turn_angle_rad is not None:
        keep &= ~on_the_spot(turn_angle_rad, length)  # decision L692: a turn with a long chord travels
    if sideways is not None:
        keep &= ~np.asarray(sideways, dtype=bool)  # decision L270: a side step is no backward travel
    return (length < 0) & keep


def backward_rows(rows: list[dict]) -> list[bool]:
    """:func:`backward_mask` of a whole steps table given as row dicts (``length_m`` and optionally ``gap_s``,
    ``impossible``, ``turn_angle_rad``, ``sideways``; ``pivot_rad`` marks a streamed table, L106), for the lean
    runtime's steps.csv: the same flags as ``pdrlearn run``'s (:func:`pdrlearn.track.evaluate.backward_travel`),
    a streamed side run read whole (decisions L243, L270)."""
    from pdrlearn.kernels.sideways import side_rows
    from pdrlearn.kernels.travel import row_values

    def num(key):
        return row_values(rows, key)

    streamed = any("pivot_rad" in r for r in rows)
    side = side_rows([bool(r.get("sideways") or False) for r in rows], num("gap_s"), streamed=streamed)
    return backward_mask(num("length_m"), num("gap_s"), [bool(r.get("impossible") or False) for r in rows],
                         num("turn_angle_rad"), side, streamed=streamed).tolist()  # L505


def is_backward(row: dict) -> bool:
    """:func:`backward_rows` of one row (a table of one stride)."""
    return backward_rows([row])[0]
