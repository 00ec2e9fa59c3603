"""Decision L701: the lower back's turn a foot track's rest gap missed (numpy only).

A foot track's heading adds between two strides only the foot's own turn over samples turning at 0.4 rad/s or more
(L28); a slow turn on the spot on a planted foot (S106's ``spin``) passes under it, while the lower back turns with
the body. :func:`gated_turn` is the lower back's turn over a span, :func:`missed_turn` the part the foot missed.
"""

from __future__ import annotations

import math

import numpy as np

#: decision L701: the lower back's samples turning at least this fast (rad/s; 2 deg/s) count towards its turn over a
#: foot's rest gap (not from a document: a standing walker's pelvis stays under it, and a gyroscope offset under it
#: adds nothing over a long stand; a 90 deg spin in 20 s, peak 8.4 deg/s, loses about 5 % of its angle to it)
GAP_TURN_GATE_RAD_S = math.radians(2.0)
#: decision L701: the foot's heading missed the lower back's turn by more than this (deg) before the lower back's is
#: taken (L682's margin; El-Gohary's smallest turn, ``kernels.yaw_turns.YAW_TURN_MIN_DEG``)
GAP_TURN_MISS_DEG = 45.0
#: decision L208: a turn is timed where it has gone these fractions of its angle (``yaw_turns.TURN_TIMING_FRACTIONS``)
GAP_TURN_FRACTIONS = (0.05, 0.95)


def _span_up(acc: np.ndarray) -> np.ndarray | None:
    """The unit vector of the span's summed specific force ``acc`` (m, 3): the unit's vertical; None without one."""
    up = np.add.reduce(np.asarray(acc, float), axis=0)
    n = float(np.sqrt(np.dot(up, up)))
    return up / n if n > 0 else None


def vertical_rate(gyr: np.ndarray, acc: np.ndarray) -> np.ndarray:
    """(n,) the rate (rad/s, CCW) about the mean specific force ``acc`` (m, 3) of the span: the unit's vertical."""
    up = _span_up(acc)
    return np.zeros(len(gyr)) if up is None else np.asarray(gyr, float) @ up


def gated_turn(t: np.ndarray, gyr: np.ndarray, acc: np.ndarray, *, gate_rad_s: float = GAP_TURN_GATE_RAD_S,
               bias_rad_s: np.ndarray | float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The lower back's turn over a span: its vertical rate (:func:`vertical_rate`) zeroed on the samples whose
    |gyr| is under ``gate_rad_s``, and the running turn (rad, trapezoid, 0 at the first sample) at each sample.
    ``bias_rad_s`` (scalar or (n,)): the vertical-rate bias read at rest (W125 / W126), taken off the rate about
    the span's vertical before the gate (decision L709: a bias over the gate would count as a turn)."""
    w = np.asarray(gyr, float)
    up = None if bias_rad_s is None else _span_up(acc)
    if up is not None:  # decision L709
        w = w - np.multiply.outer(np.broadcast_to(np.asarray(bias_rad_s, float), (len(w),)), up)
    rate = np.where(np.sqrt(np.add.reduce(w * w, axis=1)) >= gate_rad_s, vertical_rate(w, acc), 0.0)
    if len(t) < 2:
        return rate, np.zeros(len(t))
    return rate, np.concatenate([[0.0], np.cumsum(0.5 * (rate[1:] + rate[:-1]) * np.diff(np.asarray(t, float)))])


def missed_turn(waist_rad: float, foot_rad: float, min_deg: float, miss_deg: float = GAP_TURN_MISS_DEG) -> float:
    """Decision L701: ``waist_rad - foot_rad`` when the lower back turned at least ``min_deg`` and the foot's heading
    missed it by more than ``miss_deg``, else 0 (rad)."""
    if abs(waist_rad) >= math.radians(min_deg) and abs(waist_rad - foot_rad) > math.radians(miss_deg):
        return float(waist_rad - foot_rad)
    return 0.0


def fraction_times(t: np.ndarray, turn: np.ndarray, fractions: tuple[float, float] = GAP_TURN_FRACTIONS
                   ) -> tuple[float, float]:
    """The first times (s) at which the running ``turn`` has gone ``fractions`` of its last value (L208); (nan, nan)
    on an empty span (decision L709)."""
    if not len(t):
        return math.nan, math.nan
    total = float(turn[-1]) if len(turn) else 0.0
    if not total:
        return float(t[0]), float(t[-1])
    gone = np.asarray(turn, float) / total
    return tuple(float(t[min(int(np.argmax(gone >= f)), len(t) - 1)]) for f in fractions)
