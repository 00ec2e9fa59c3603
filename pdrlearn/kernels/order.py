"""The timestamp-order check the streaming runtime, its sensor pairing and ``pdrlearn split`` share (decision D3:
unsorted or repeated timestamps are errors, not silently repaired) - a pure kernel; each caller words its own
one-line :class:`~pdrlearn.errors.DataError` naming its file or stream."""

from __future__ import annotations

import math

import numpy as np


def first_out_of_order(t, last: float = -math.inf, *, strict: bool = True) -> int | None:
    """The index of the first timestamp of ``t`` (s) that does not increase from the one before it (the first's:
    ``last``, the stream's previous one; -inf for none), or None when all do. ``strict``: a repeat does not
    increase either (decision E203's push); False: only a step back does (a repeat kept: E204's pairing, B380's
    split)."""
    t = np.asarray(t, dtype=np.float64).reshape(-1)
    prev = np.concatenate([[last], t[:-1]])
    bad = np.flatnonzero(t <= prev if strict else t < prev)
    return int(bad[0]) if bad.size else None
