"""Row-to-row intervals a walker's turn fills (decision C180, docs/decisions/cohort.md): no pause, no bout break.

A lower back sees no step in a slow turn on the spot (W331), so L104 / L119's pause rule reads a slow walker's cone
turn as a pause and splits a 6MWT into one walking bout per lap. Decision C180 (an option of the bout rule,
``BoutRule.turn_fill_min_deg``; C182: on by ``--corridor`` for the cone turns): an interval that is a pause is none
when a turn fills it - a yaw-rate turn (a lower-back track's ``info["yaw_turns"]``, L210) of at least
:data:`TURN_GAP_MIN_DEG` that is not ``carried`` (W488 / L622) overlaps it, the interval outside those turns (each
widened by one step interval, L647's turning time) leaves less than the pause's break (no rest), and no chair
transfer (``info["transfers"]``, W182) overlaps it (no sit). Pure functions of the track's info and the intervals.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pdrlearn.kernels.rests import pieces_outside
from pdrlearn.waist.turn_steps import CARRIED

#: decision C180 (ours, the lead's brief): a yaw-rate turn of at least this |angle| (deg) can fill a pause - a corner
#: or a turnaround, above L104's 80 deg turn count
TURN_GAP_MIN_DEG = 90.0


def _spans(records, keep=lambda r: True) -> np.ndarray:
    rows = [(r.get("start_s"), r.get("end_s")) for r in (records or []) if keep(r)]
    a = np.asarray([x for x in rows if x[0] is not None and x[1] is not None], dtype=float).reshape(-1, 2)
    return a[np.isfinite(a).all(axis=1) & (a[:, 1] > a[:, 0])] if len(a) else a


@dataclass(frozen=True)
class TurnGaps:
    """Decision C180: what may fill a pause - ``turns`` (K, 2) the walker's yaw-rate turns of at least
    :data:`TURN_GAP_MIN_DEG` (``start_s``, ``end_s``; none ``carried``), in time order - and what may not: ``sits``
    (M, 2) the chair transfers' spans."""

    turns: np.ndarray
    sits: np.ndarray

    @classmethod
    def of(cls, info: dict | None, min_deg: float = TURN_GAP_MIN_DEG) -> TurnGaps | None:
        """A track's turn gaps from its ``info`` (``yaw_turns``, ``transfers``), the turns of at least ``min_deg``
        (C180's 90 deg; C182: a corridor's cone turns, 135); None without yaw-rate turns (a foot track, or no info):
        no interval is filled."""
        if not info or info.get("yaw_turns") is None:
            return None
        turns = _spans(info["yaw_turns"], lambda r: r.get(CARRIED) is not True
                       and abs(float(r.get("angle_deg") or 0.0)) >= min_deg)
        return cls(turns=turns[np.argsort(turns[:, 0])], sits=_spans(info.get("transfers")))


def filled_intervals(lo: np.ndarray, hi: np.ndarray, gaps: TurnGaps | None, widen_s: float,
                     max_rest_s: float) -> np.ndarray:
    """Decision C180: (N,) whether a turn of ``gaps`` fills each interval ``[lo, hi]`` (s): a turn overlaps it, its
    time outside the turns widened by ``widen_s`` on each side sums to under ``max_rest_s``, and no sit overlaps
    it. All False without ``gaps``."""
    lo, hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
    out = np.zeros(len(lo), dtype=bool)
    if gaps is None or not len(gaps.turns):
        return out
    widened = np.column_stack([gaps.turns[:, 0] - widen_s, gaps.turns[:, 1] + widen_s])
    for i, (a, b) in enumerate(zip(lo.tolist(), hi.tolist(), strict=True)):
        if not (b > a) or not np.any((gaps.turns[:, 0] < b) & (gaps.turns[:, 1] > a)):
            continue
        if len(gaps.sits) and np.any((gaps.sits[:, 0] < b) & (gaps.sits[:, 1] > a)):
            continue
        out[i] = sum(e - s for s, e in pieces_outside(a, b, widened)) < max_rest_s
    return out
