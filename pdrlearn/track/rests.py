"""Rests between walking bouts that are not turns (decision L647, docs/decisions/localization.md).

A gap between two walking bouts is standing - a rest - unless the walker turned in it: a lower back sees no step
in a slow turn on the spot (W331), so a slow walker's stepless cone turn splits the walk into two bouts (trial T1
finding F4: rests of 7 s at every cone of a walker who never stopped). Decision L647: the time a turns.csv turn
covers, widened by one step interval on each side (the turn's stepless entry and exit steps), is turning, not rest;
what is left of a gap is a rest only when it is at least :data:`REST_MIN_S` (L104's pause). laps.csv's ``rest_s``
(L384) and the report's rests between walking bouts (L386) are both this. Pure functions of bouts.csv and
turns.csv.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.kernels.rests import pieces_outside
from pdrlearn.track.clinical import PAUSE_MIN_S, walked_turns

#: decision L647 (L386's, L104's pause): a gap's time outside turns shorter than this is no rest (s)
REST_MIN_S = PAUSE_MIN_S


def step_interval_s(bouts: pd.DataFrame | None) -> float:
    """Decision L647: the walker's step interval (s), 60 / the median of bouts.csv's ``cadence_spm`` (steps of both
    feet per minute); 0 without a cadence."""
    if bouts is None or "cadence_spm" not in bouts:
        return 0.0
    cad = pd.to_numeric(bouts["cadence_spm"], errors="coerce").to_numpy(float)
    cad = cad[np.isfinite(cad) & (cad > 0)]
    return 60.0 / float(np.median(cad)) if cad.size else 0.0


def _turning(turns: pd.DataFrame | None, widen_s: float) -> np.ndarray:
    """(K, 2) the walker's turns' spans (turns.csv ``start_s`` / ``end_s``) widened by ``widen_s`` on each side;
    decision L662: a turn made seated or riding (L622's ``carried``) is no walker's turn, its time stays rest."""
    if turns is None or not len(turns) or not {"start_s", "end_s"} <= set(turns.columns):
        return np.zeros((0, 2))
    turns = walked_turns(turns)
    a = pd.to_numeric(turns["start_s"], errors="coerce").to_numpy(float) - widen_s
    b = pd.to_numeric(turns["end_s"], errors="coerce").to_numpy(float) + widen_s
    ok = np.isfinite(a) & np.isfinite(b)
    return np.column_stack([a[ok], b[ok]])


def rest_pieces(start: float, end: float, turns: pd.DataFrame | None, widen_s: float) -> list[tuple[float, float]]:
    """Decision L647: the rest of one gap ``[start, end]`` between walking bouts: its pieces outside every turn
    (widened by ``widen_s``), none when they sum to under :data:`REST_MIN_S`."""
    pieces = pieces_outside(start, end, _turning(turns, widen_s))
    return pieces if sum(e - s for s, e in pieces) >= REST_MIN_S else []


def bout_gaps(bouts: pd.DataFrame | None, start: float | None = None, end: float | None = None
              ) -> list[tuple[float, float]]:
    """The gaps between bouts.csv's walking bouts (time order); with ``start`` / ``end``, also the time before the
    first bout and after the last inside ``[start, end]`` (a lap's ends)."""
    if bouts is None or not len(bouts) or not {"start_s", "end_s"} <= set(bouts.columns):
        return [] if start is None or end is None or end <= start else [(float(start), float(end))]
    b = bouts.sort_values("start_s")
    s, e = b["start_s"].to_numpy(float), b["end_s"].to_numpy(float)
    gaps = list(zip(e[:-1].tolist(), s[1:].tolist(), strict=True))
    if start is not None:
        gaps.insert(0, (float(start), float(s[0])))
    if end is not None:
        gaps.append((float(e[-1]), float(end)))
    return [(a, z) for a, z in gaps if z > a]


def rests(bouts: pd.DataFrame | None, turns: pd.DataFrame | None, start: float | None = None,
          end: float | None = None) -> list[list[tuple[float, float]]]:
    """Decision L647: each gap of :func:`bout_gaps` as its rest pieces (:func:`rest_pieces`, the turns widened by
    :func:`step_interval_s`); an empty list for a gap that is no rest."""
    widen = step_interval_s(bouts)
    return [rest_pieces(a, z, turns, widen) for a, z in bout_gaps(bouts, start, end)]


def rest_seconds(start: float, end: float, bouts: pd.DataFrame | None, turns: pd.DataFrame | None) -> float:
    """Decision L647 (laps.csv ``rest_s``, L384): the rest time inside ``[start, end]`` - the time outside every
    walking bout that is neither a turn nor a gap's leftover under :data:`REST_MIN_S`."""
    if bouts is None or not len(bouts):
        return float(end - start)
    total = 0.0
    for gap in rests(bouts, turns, start, end):
        total += sum(max(min(e, end) - max(s, start), 0.0) for s, e in gap)
    return float(total)


def window_rests(bouts: pd.DataFrame | None, turns: pd.DataFrame | None, start: float, end: float
                 ) -> list[tuple[float, float]]:
    """Decision C217: the rests inside ``[start, end]`` (a timed walk test's window) as ``(first instant, rest
    seconds)``: each L647 rest (:func:`rests`) cut to the window, kept when at least :data:`REST_MIN_S` of it lies
    inside (standing after the test's end, or the wait before its go, is no rest of the test)."""
    if bouts is None or not len(bouts) or not end > start:
        return []
    out = []
    for gap in rests(bouts, turns, start, end):
        inside = [(max(s, start), min(e, end)) for s, e in gap if min(e, end) > max(s, start)]
        total = sum(e - s for s, e in inside)
        if inside and total >= REST_MIN_S:
            out.append((float(inside[0][0]), float(total)))
    return out
