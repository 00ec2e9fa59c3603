"""The spans between the rows of a walk (its rests, pauses, standstills) - one pure kernel for the callers that
read them: the weather's standstills (decision L464, :mod:`pdrlearn.kernels.weather_drift`), the streamed rests of
the position sigma (decision E205, :mod:`pdrlearn.track.position_sigma`) and the clinical pauses (decision L110,
:mod:`pdrlearn.track.clinical`). Each caller keeps its own rule of which span counts (minimum length, trim, held
rows); this module only lays the spans out."""

from __future__ import annotations

import numpy as np


def between_rows(start, end, *, edges: tuple[float, float] | None = None,
                 carry: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """``(lo, hi)`` (s) each span between two consecutive rows of a walk whose rows (in the given order: sort them
    first) span ``start`` to ``end``: from a row's end to the next row's start (``end`` = ``start`` gives the
    start-to-start intervals, :func:`numpy.diff`'s). ``edges`` = ``(t_first, t_last)``, the recording's first and
    last time: the spans before the first row and after the last are included (a recording without rows is one
    span); None: only the spans between rows. ``carry``: a row overlapping the next keeps the walk going (each
    end is the latest end so far)."""
    s = np.asarray(start, dtype=float).ravel()
    e = np.asarray(end, dtype=float).ravel()
    if carry:
        e = np.maximum.accumulate(e)
    if edges is None:
        return e[:-1], s[1:]
    return np.concatenate([[edges[0]], e]), np.concatenate([s, [edges[1]]])


def pieces_outside(start: float, end: float, spans) -> list[tuple[float, float]]:
    """The pieces of ``[start, end]`` (s) outside every ``(a, b)`` of ``spans`` (any order; they may overlap):
    a gap's time that no turn covers (decisions L647, C180)."""
    pieces = [(float(start), float(end))]
    for a, b in spans:
        pieces = [p for s, e in pieces for p in ((s, min(e, a)), (max(s, b), e)) if p[1] > p[0]]
    return pieces
