"""Foot strides that are pedalling, not walking: a closed vertical loop (decisions L611 / L612 in
docs/decisions/localization.md), numpy only.

A crank takes the foot up and down a circle with no travel; a rest-to-rest segmentation cuts it into half or whole
turns whose raw height changes (the stride integrator's, before any levelling or class rule) flip sign every one or
two "strides" (trial T3: +-0.1 to +-0.9 m), where a level walking stride's raw height stays within a few cm and a stair
stride's keeps its sign along the flight. Offline (``track``) and streamed (``track --streaming``) tracks call the same
functions.
"""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels.units import STANDARD_GRAVITY

#: decision L611: a raw height change at least this large (m) has a sign that counts (a level stride's raw height stays
#: within a few cm; T3's pedalling strides changed 0.07-0.9 m)
REVERSAL_MIN_DZ_M = 0.05
#: decision L611 (third rule): a reversing stride rises or falls at least this fraction of its horizontal travel (real
#: level walking's raw height wanders 0.06-0.10 of a 1.4 m stride, gaitmap_level_right; a crank's "strides" 0.8-20)
STEEP = 0.3
#: decision L621: a reversing stride counts only when it travels less than this (m, raw horizontal) or is unrested (the
#: crank "strides" of tests/test_pedal_s43_l611.py travel 0.012-0.254 m; a stair stride 0.56-0.58 m; review R2 F4)
TRAVEL_MAX_M = 0.3
#: decision L611: two strides belong to one chain when the second starts at most this long (s) after the first ends
CHAIN_PAUSE_S = 1.0
#: decision L611: a stride's neighbourhood: itself and up to this many strides of its chain before and after it
NEIGHBOURS = 2
#: decision L611: a stride is pedalling with at least this many reversals in its neighbourhood (a curb up and down or a
#: stair flight up then down is one)
MIN_REVERSALS = 2
#: decision L611 (second rule): a stride end's rest reads the foot accelerometer within this long (s) of it
REST_WINDOW_S = 0.1
#: decision L611 (second rule): a rest whose median | |acc| - g | is at least this (m/s^2) is no rest (simulated walks'
#: mid-stance 0.01-0.09, the real gaitmap recordings' at most 0.43; a crank at 40-95 rpm 1.7-10.3 in the median)
UNRESTED_MPS2 = 1.0
#: decision L611 (second rule): a stride is pedalling when this many strides of its neighbourhood are unrested
MIN_UNRESTED = 3
#: decision L611: pedalling spans closer than this (s) are named as one in the warning line
MERGE_SPANS_S = 10.0


def unrested_strides(t: np.ndarray, acc: np.ndarray, start_s: np.ndarray, end_s: np.ndarray,
                     g_rest: float = STANDARD_GRAVITY) -> np.ndarray:
    """Decision L611 (second rule): (B,) bool, the strides whose two ends both lack a rest: the median of
    | |acc| - g_rest | over the foot accelerometer's samples (``t`` s, ``acc`` (n, 3) m/s^2) within
    :data:`REST_WINDOW_S` of the end is at least :data:`UNRESTED_MPS2` (an end without samples is a rest: nothing to
    judge). ``g_rest``: the accelerometer's own rest reading (decision L621: a mis-scaled one, B201, reads 1.2 g)."""
    t = np.asarray(t, dtype=float)
    dev = np.abs(np.linalg.norm(np.asarray(acc, dtype=float)[:, :3], axis=1) - float(g_rest))

    def moving(x: np.ndarray) -> np.ndarray:
        a = np.searchsorted(t, np.asarray(x, dtype=float) - REST_WINDOW_S, side="left")
        b = np.searchsorted(t, np.asarray(x, dtype=float) + REST_WINDOW_S, side="right")
        return np.array([b_ > a_ and float(np.median(dev[a_:b_])) >= UNRESTED_MPS2
                         for a_, b_ in zip(a, b, strict=True)], dtype=bool)

    return moving(start_s) & moving(end_s)


def closed_loop_strides(dz: np.ndarray, start_s: np.ndarray, end_s: np.ndarray,
                        unrested: np.ndarray | None = None, travel: np.ndarray | None = None) -> np.ndarray:
    """Decision L611: (B,) bool, the strides whose neighbourhood (:data:`NEIGHBOURS` strides of their chain either
    side) holds :data:`MIN_REVERSALS` or more height reversals: two consecutive strides of one chain (the next starting
    within :data:`CHAIN_PAUSE_S` of the previous's end) whose raw height changes ``dz`` (m) have opposite signs, each at
    least :data:`REVERSAL_MIN_DZ_M` and (third rule) at least :data:`STEEP` of its horizontal ``travel`` (m), and
    (decision L621) each ``unrested`` or travelling less than :data:`TRAVEL_MAX_M`; or
    (second rule) :data:`MIN_UNRESTED` or more ``unrested`` strides
    (:func:`unrested_strides`)."""
    dz = np.asarray(dz, dtype=float)
    start_s, end_s = np.asarray(start_s, dtype=float), np.asarray(end_s, dtype=float)
    n = len(dz)
    if n < 3:
        return np.zeros(n, dtype=bool)
    chained = start_s[1:] - end_s[:-1] <= CHAIN_PAUSE_S  # (B-1,) pair i, i+1 in one chain
    still = np.zeros(n, dtype=bool) if unrested is None else np.asarray(unrested, dtype=bool)
    big = np.abs(dz) >= REVERSAL_MIN_DZ_M
    if travel is not None:
        travel = np.abs(np.asarray(travel, dtype=float))
        big &= np.abs(dz) >= STEEP * travel
        big &= still | (travel < TRAVEL_MAX_M)  # decision L621: a stride that travels and rests is walking (a stile)
    rev = chained & big[:-1] & big[1:] & (np.sign(dz[:-1]) != np.sign(dz[1:]))  # pair i, i+1 reverses
    out = np.zeros(n, dtype=bool)
    for i in range(n):
        lo, hi = i, i  # the stride's neighbourhood within its chain: pairs lo..hi-1
        while lo > 0 and i - lo < NEIGHBOURS and chained[lo - 1]:
            lo -= 1
        while hi < n - 1 and hi - i < NEIGHBOURS and chained[hi]:
            hi += 1
        out[i] = int(rev[lo:hi].sum()) >= MIN_REVERSALS or int(still[lo:hi + 1].sum()) >= MIN_UNRESTED
    return out


def seated_strides(start_s: np.ndarray, end_s: np.ndarray, transfers) -> tuple[np.ndarray, list[tuple[float, float]]]:
    """Decision L612: (B,) bool, the strides lying wholly inside a seated span of the chair ``transfers`` (rows with
    ``kind``, ``start_s``, ``end_s``, in time order: W182's), and the spans: from a stand-to-sit's end to the next
    transfer's start when that is a sit-to-stand."""
    start_s, end_s = np.asarray(start_s, dtype=float), np.asarray(end_s, dtype=float)
    rows = sorted(transfers or [], key=lambda r: float(r["start_s"]))
    spans = [(float(a["end_s"]), float(b["start_s"])) for a, b in zip(rows[:-1], rows[1:], strict=True)
             if a.get("kind") == "stand-to-sit" and b.get("kind") == "sit-to-stand" and b["start_s"] > a["end_s"]]
    out = np.zeros(len(start_s), dtype=bool)
    for a, b in spans:
        out |= (start_s >= a) & (end_s <= b)
    return out, spans


def spans_of(mask: np.ndarray, start_s: np.ndarray, end_s: np.ndarray) -> list[tuple[float, float, int]]:
    """The marked strides' spans (start s, end s, strides), merged when under :data:`MERGE_SPANS_S` apart."""
    out: list[list] = []
    for i in np.flatnonzero(mask):
        if out and float(start_s[i]) - out[-1][1] < MERGE_SPANS_S:
            out[-1][1], out[-1][2] = float(end_s[i]), out[-1][2] + 1
        else:
            out.append([float(start_s[i]), float(end_s[i]), 1])
    return [(a, b, k) for a, b, k in out]


#: decision L611: what the track does with the pedalling strides, for the line
TRACK_REMOVED = "removed from the track (no row, 0 m)"


def pedal_line(loop: np.ndarray, seated: np.ndarray, start_s: np.ndarray, end_s: np.ndarray,
               seats: list[tuple[float, float]] | None = None, removed: str = TRACK_REMOVED) -> str | None:
    """Decisions L611 / L612: the one warning line naming the removed strides' spans and why, or None; ``removed``
    says what was done with them (decision L625: ``pdrlearn steps`` leaves them out of its count or counts them)."""
    parts = []
    if loop.any():
        where = ", ".join(f"{a:.2f}-{b:.2f} s ({k})" for a, b, k in spans_of(loop, start_s, end_s))
        parts.append(f"{int(loop.sum())} stride(s) at {where} went round a closed loop without rests or travel "
                     "(cycling? decision L611)")
    only_seated = seated & ~loop
    if only_seated.any():
        where = ", ".join(f"{a:.2f}-{b:.2f} s ({k})" for a, b, k in spans_of(only_seated, start_s, end_s))
        seat = "; ".join(f"stand-to-sit at {a:.2f} s, sit-to-stand at {b:.2f} s" for a, b in (seats or [])
                         if (only_seated & (start_s >= a) & (end_s <= b)).any())
        parts.append(f"{int(only_seated.sum())} stride(s) at {where} lie in a span the lower-back unit calls seated "
                     f"({seat}; cycling or a foot moving while seated? decision L612)")
    if not parts:
        return None
    return f"not walking, {removed}: " + "; ".join(parts)
