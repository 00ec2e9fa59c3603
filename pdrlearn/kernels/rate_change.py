"""A sustained change of a stream's sample rate, told from dropped samples (decision B457), numpy only.

A unit that switches from 100 Hz to 50 Hz mid-walk has a median interval of one of the two periods; B64 then calls
every interval of the slower stretch "dropped samples" (or, the other way round, integrates the faster stretch
with the slower period). The median interval over consecutive 1 s blocks is the period while fewer than half a
block's intervals hold a drop, so random drops leave it level and a rate change steps it.
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass

import numpy as np

#: decision B457: the blocks (s) whose median sample interval is compared
BLOCK_S = 1.0
#: decision B457: each stretch at a rate lasts at least this long (s): "a few seconds", longer than a burst of drops
MIN_STRETCH_S = 5.0
#: decision B457: two stretches' median intervals differ by at least this factor (a 2x change is 2.0; B64's
#: dropped-sample limit is 1.5 periods, so a smaller step is clock drift or jitter, not a rate setting)
MIN_FACTOR = 1.4
#: decision B457: blocks whose median interval lies within this fraction of each other are one level
LEVEL_TOL = 0.1


@dataclass(frozen=True)
class RateChange:
    """One change: at ``t_s`` (the first sample of the new stretch) from ``before_hz`` to ``after_hz``."""

    t_s: float
    before_hz: float
    after_hz: float


def _block_medians(t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The median interval of each :data:`BLOCK_S` block of ``t`` and the block's first sample time."""
    d = np.diff(t)
    blk = np.floor((t[:-1] - t[0]) / BLOCK_S).astype(np.int64)
    edges = np.flatnonzero(np.diff(blk)) + 1
    starts = np.concatenate([[0], edges])
    med = np.array([np.median(d[a:b]) for a, b in zip(starts, np.concatenate([edges, [d.size]]), strict=True)])
    return med, t[starts]


#: decision B460: the blocks a stretch needs (:data:`MIN_STRETCH_S` of them); a stretch's period is the median of
#: this many of its blocks next to the change (the new stretch's first, the old one's last): bounded state, live too
STRETCH_BLOCKS = int(np.ceil(MIN_STRETCH_S / BLOCK_S - 1e-9))


class RateLevels:
    """Decisions B457 / B460: the level runs of consecutive blocks' median intervals, one block at a time (bounded
    state: a running sum and :data:`STRETCH_BLOCKS` medians at each end of the current run). A run whose blocks lie
    within :data:`LEVEL_TOL` of its running mean and that lasts :data:`STRETCH_BLOCKS` blocks is a stretch; the
    change is said when a stretch is reached whose period differs from the previous stretch's by
    :data:`MIN_FACTOR` or more (runs shorter than a stretch between them are left out). :func:`rate_changes` (a
    whole recording) and the live Tracker's watch (pushed samples, E309) feed it the same blocks."""

    def __init__(self):
        self.prev: float | None = None  # the period of the last stretch (median of its last STRETCH_BLOCKS blocks)
        self._n, self._sum, self._t0 = 0, 0.0, math.nan
        self._first: list[float] = []
        self._last: deque[float] = deque(maxlen=STRETCH_BLOCKS)

    def add(self, med: float, t_first: float) -> tuple[float, float, float] | None:
        """The next block: its median interval ``med`` (s) and its first sample's time ``t_first`` (s). Returns
        ``(t_first of the new stretch's first block, old period, new period)`` when this block makes the current
        run a stretch at another rate, else None."""
        if self._n:
            level = self._sum / self._n
            if abs(med - level) > LEVEL_TOL * level:
                self._end()
        if not self._n:
            self._t0 = float(t_first)
        self._n += 1
        self._sum += med
        if len(self._first) < STRETCH_BLOCKS:
            self._first.append(med)
        self._last.append(med)
        if self._n != STRETCH_BLOCKS or self.prev is None:
            return None
        p1 = float(np.median(self._first))
        if max(self.prev, p1) / min(self.prev, p1) >= MIN_FACTOR:
            return self._t0, self.prev, p1
        return None

    def _end(self) -> None:
        if self._n >= STRETCH_BLOCKS:
            self.prev = float(np.median(self._last))
        self._n, self._sum = 0, 0.0
        self._first = []
        self._last.clear()


def change_time(t: np.ndarray, t_first: float, period: float) -> float:
    """Decision B457: the first sample after which the intervals of ``t`` (s) are the new ``period``: from the new
    stretch's first block (``t_first``) back while they already are (at most :data:`MIN_STRETCH_S` back)."""
    i = int(np.searchsorted(t, t_first))
    while i > 0 and abs((t[i] - t[i - 1]) - period) < LEVEL_TOL * period and t[i] > t_first - MIN_STRETCH_S:
        i -= 1
    return float(t[i])


def rate_changes(t: np.ndarray) -> list[RateChange]:
    """Decision B457: the sustained rate changes of timestamps ``t`` (s): consecutive stretches of blocks at one
    level (within :data:`LEVEL_TOL`) lasting at least :data:`MIN_STRETCH_S`, whose periods differ by at least
    :data:`MIN_FACTOR` (:class:`RateLevels`, the live Tracker's kernel too, B460). Blocks between two stretches (the
    change itself, a gap) are left out. Empty for a steady rate, dropped samples, or fewer than two stretches."""
    t = np.asarray(t, dtype=float)
    if t.size < 3 or t[-1] - t[0] < 2 * MIN_STRETCH_S:
        return []
    med, t0 = _block_medians(t)
    levels, out = RateLevels(), []
    for m, tb in zip(med.tolist(), t0.tolist(), strict=True):
        hit = levels.add(m, tb)
        if hit is not None:
            out.append(RateChange(change_time(t, hit[0], hit[2]), 1.0 / hit[1], 1.0 / hit[2]))
    return out


def change_text(names, key) -> str:
    """Decision B457's line without its path's tail (shared by ``read_session`` and the live Tracker, E309):
    ``fAccelerometer, fGyroscope: the sample rate changed 100 -> 50 Hz at 30.0 s (a unit's rate setting, not dropped
    samples; decision B457)``; ``key``: ``(time s rounded to 0.1, before Hz text, after Hz text)`` per change."""
    said = ", ".join(f"{a} -> {b} Hz at {t:.1f} s" for t, a, b in key)
    return (f"{', '.join(names)}: the sample rate changed {said} (a unit's rate setting, not dropped samples; "
            "decision B457)")


def fastest_period_s(t: np.ndarray) -> float:
    """Decision B457: the shortest of the stretches' median intervals (the rate to resample every stretch to)."""
    ch = rate_changes(t)
    return min(min(1.0 / c.before_hz, 1.0 / c.after_hz) for c in ch) if ch else float("nan")
