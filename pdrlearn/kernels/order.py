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


def repeated(t, seen=()) -> np.ndarray:
    """Decision E203 (E225: shared by both live trackers): True for each timestamp of ``t`` (s) that repeats one
    already seen - the sample before it in ``t``, or one of ``seen`` (sorted: the stream's times already taken; the
    lean ``WaistTracker`` passes its last one, the foot ``Tracker`` those it still buffers, so a packet sent twice is
    found whole). A step back to a time not seen is not a repeat (the order check names it)."""
    t = np.asarray(t, dtype=np.float64).reshape(-1)
    rep = np.zeros(t.shape, dtype=bool)
    rep[1:] = t[1:] == t[:-1]
    seen = np.asarray(seen, dtype=np.float64).reshape(-1)
    if seen.size and t.size:
        i = np.minimum(np.searchsorted(seen, t), seen.size - 1)
        rep |= seen[i] == t
    return rep


def repeats_dropped_line(where: str, count: str) -> str:
    """Decision E203's one warning line at a live tracker's first dropped repeat (E225: both trackers' wording):
    ``where`` names the push, ``count`` the attribute that counts them."""
    return (f"{where}: dropping samples whose timestamp repeats one already taken (the first is kept; "
            f"drop_duplicate_timestamps=True, decision E203); the count is {count}")


def reorder_hint() -> str:
    """Decision E349: the fix a live tracker's refusal of samples out of time order names: the runtime's jitter
    buffer (:class:`pdrlearn.runtime.Reorderer`, decision E296), which puts a link's late packets back in order."""
    return ("or put pdrlearn.runtime.Reorderer(hold_s=...) between the link and the tracker: it releases each "
            "sensor's samples in time order, a packet overtaken by a later one put back in place (decision E296)")
