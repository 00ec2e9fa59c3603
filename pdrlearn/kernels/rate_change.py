"""A sustained change of a stream's sample rate, told from dropped samples (decision B457), numpy only.

A unit that switches from 100 Hz to 50 Hz mid-walk has a median interval of one of the two periods; B64 then calls
every interval of the slower stretch "dropped samples" (or, the other way round, integrates the faster stretch
with the slower period). The median interval over consecutive 1 s blocks is the period while fewer than half a
block's intervals hold a drop, so random drops leave it level and a rate change steps it.
"""

from __future__ import annotations

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


def rate_changes(t: np.ndarray) -> list[RateChange]:
    """Decision B457: the sustained rate changes of timestamps ``t`` (s): consecutive stretches of blocks at one
    level (within :data:`LEVEL_TOL`) lasting at least :data:`MIN_STRETCH_S`, whose median intervals differ by at
    least :data:`MIN_FACTOR`. Blocks between two stretches (the change itself, a gap) are left out. Empty for a
    steady rate, dropped samples, or fewer than two stretches."""
    t = np.asarray(t, dtype=float)
    if t.size < 3 or t[-1] - t[0] < 2 * MIN_STRETCH_S:
        return []
    med, t0 = _block_medians(t)
    stretches = []  # (first block, last block, median interval)
    csum = np.concatenate([[0.0], np.cumsum(med)])  # the running level's mean in O(1): long recordings stay linear
    a = 0
    for i in range(1, med.size + 1):
        level = (csum[i] - csum[a]) / (i - a)
        if i == med.size or abs(med[i] - level) > LEVEL_TOL * level:
            if (i - a) * BLOCK_S >= MIN_STRETCH_S:
                stretches.append((a, i - 1, float(np.median(med[a:i]))))
            a = i
    out = []
    for (_, _, p0), (b, _, p1) in zip(stretches, stretches[1:], strict=False):
        if max(p0, p1) / min(p0, p1) >= MIN_FACTOR:
            i = int(np.searchsorted(t, t0[b]))
            # the first sample after which the intervals are the new period: step back while they already are
            while i > 0 and abs((t[i] - t[i - 1]) - p1) < LEVEL_TOL * p1 and t[i] > t0[b] - MIN_STRETCH_S:
                i -= 1
            out.append(RateChange(float(t[i]), 1.0 / p0, 1.0 / p1))
    return out


def fastest_period_s(t: np.ndarray) -> float:
    """Decision B457: the shortest of the stretches' median intervals (the rate to resample every stretch to)."""
    ch = rate_changes(t)
    return min(min(1.0 / c.before_hz, 1.0 / c.after_hz) for c in ch) if ch else float("nan")
