"""Decision E309: the live Tracker's word on a sustained sample-rate change of a pushed stream (B457's detection,
numpy only): the same kernel, :class:`~pdrlearn.kernels.rate_change.RateLevels`, as ``read_session`` (decision B460),
fed the same 1 s blocks of each stream's own time.

A block is judged when the stream has a sample at or after its end (that sample closes its last interval, as the
offline blocks' intervals run from each sample to the next; each stream a fraction of a block later than the one
before, so that one push does not judge every stream's block) and at :meth:`RateWatch.flush` on what it holds. Each
change is said once, in one line for the streams that changed the same way (decision E310: the line is held until
every other stream has judged its blocks up to the change's block, at most :data:`HOLD_BLOCKS` blocks more), and kept
in :attr:`RateWatch.changes` (``Tracker.rate_changes``). Per push: a list append and a comparison per stream; per
block: one median. Memory: the open block and the last :data:`KEPT_BLOCKS` blocks' times per stream (for the time
of the change, B457's step back).
"""

from __future__ import annotations

from collections import deque

import numpy as np

from pdrlearn.kernels.gaps import MIN_GAP_S
from pdrlearn.kernels.rate_change import BLOCK_S, STRETCH_BLOCKS, RateLevels, change_text, change_time

#: the blocks kept for B457's step back to the change's first sample: the new stretch's and as many before it
KEPT_BLOCKS = 2 * STRETCH_BLOCKS + 2

#: decision E310: a held line is said at the latest when its first stream has closed this many further blocks (the
#: other streams' blocks lag by less than one block each, RateWatch.lag; a stream that stopped does not hold it)
HOLD_BLOCKS = 2

#: decision E230 / B64: an interval over this many periods encloses dropped samples
DROP_FACTOR = 1.5

#: decision E309: what the live path does with the change (measured, docs/decisions/export.md)
LIVE_TAIL = ("integrated on the samples' own timestamps, as the live path integrates every stride (decision E36; "
             "E309: not resampled, measured) - or record at one rate")


class RateWatch:
    """Decision E309: B457's rate changes on each pushed stream the tracker uses, block by block."""

    def __init__(self, used, limit=None):
        self.items: dict[str, list] = {n: [] for n in dict.fromkeys(used)}  # every stream, as read_session
        self.start: dict[str, float] = {}
        self.k: dict[str, int] = dict.fromkeys(self.items, 0)
        #: each stream's blocks are judged this far (s) after their end, streams spread over one block: a push closes
        #: one stream's block, not every stream's at once (a block costs ~50 us; the p99 push, E309)
        self.lag: dict[str, float] = {n: j * BLOCK_S / len(self.items) for j, n in enumerate(self.items)}
        self.levels: dict[str, RateLevels] = {n: RateLevels() for n in self.items}
        self.kept: dict[str, deque] = {n: deque(maxlen=KEPT_BLOCKS) for n in self.items}
        #: the changes found: ``{"streams": [...], "t_s", "before_hz", "after_hz"}`` each, in the order said
        self.changes: list[dict] = []
        #: decision B461: ``limit(name)``, the interval (s) over which the caller counts dropped samples (E230)
        self.limit = limit
        #: decision B461: per stream, the intervals the caller counted as dropped samples that are within 1.5 of their
        #: block's own median interval, since the last change (taken back out of the count at the next one)
        self.excess: dict[str, int] = dict.fromkeys(self.items, 0)
        #: decision B461: (stream, time of the change s, new period s, intervals to take back out) of the last push
        self.new: list[tuple[str, float, float, int]] = []
        #: decision E310: the changes found and not yet said, each ``{"key", "streams", "end", "by"}``: ``end`` (s) the
        #: end of the block of stream ``by`` that showed it, which every other stream is to have judged first
        self.held: list[dict] = []

    def push(self, arrays: dict, fast: dict | None = None) -> list[str]:
        """One push (``arrays`` name -> ``(t, values)``, ``fast`` name -> one ``(t, values)`` sample, as
        :class:`~pdrlearn.runtime.clip_watch.ClipWatch`); the lines of the changes now due (decision E310: held until
        every stream judged the change's blocks)."""
        found: list[tuple[str, float, float, float, int]] = []
        for name, items in self.items.items():
            f = fast.get(name) if fast else None
            if f is not None:
                newest = f[0]
                items.append(newest)
            elif name in arrays and len(arrays[name][0]):
                t = arrays[name][0]
                newest = float(t[-1])
                items.append(newest if len(t) == 1 else t)  # one sample: a float, as the fast path's
            else:
                continue
            start = self.start.get(name)
            if start is None:
                start = self.start[name] = float(items[0] if isinstance(items[0], float) else items[0][0])
            if (newest - start - self.lag[name]) // BLOCK_S > self.k[name]:  # B457's block floor((t - t0) / BLOCK_S)
                found += self._close(name)
        if not found:  # the common push: no block closed with a change
            if self.new:
                self.new = []
            return self._said() if self.held else found
        return self._lines(found)

    def flush(self) -> list[str]:
        """The end of the streams: each open block judged on what it holds, every held line said."""
        found: list[tuple[str, float, float, float, int]] = []
        for name in self.items:
            if name in self.start:
                found += self._close(name, final=True)
        return self._lines(found, final=True)

    def _close(self, name: str, final: bool = False) -> list[tuple[str, float, float, float, int]]:
        """The blocks the stream's samples so far close (all at ``final``), each judged by the levels."""
        t = _times(self.items[name])
        blk = np.floor((t - self.start[name]) / BLOCK_S)  # B457's block of each sample (as _block_medians)
        edges = np.flatnonzero(np.diff(blk)) + 1
        bounds = [0, *edges.tolist()] + ([len(t)] if final else [])
        found = []
        for a, b in zip(bounds, bounds[1:], strict=False):
            d = np.diff(t[a:b + 1])  # each sample to the next: the block's last interval ends in the next block
            self.kept[name].append(t[a:b])
            if not len(d):
                continue
            med = float(np.median(d))
            self.excess[name] += self._excess(name, d, med)
            hit = self.levels[name].add(med, float(t[a]))
            if hit is not None:
                kept = np.concatenate(self.kept[name])
                found.append((name, change_time(kept, hit[0], hit[2]), 1.0 / hit[1], 1.0 / hit[2], 0))
        rest = t[bounds[-1]:]
        if found:  # B461: taken back at the (last) change; the open block's intervals are the new stretch's
            self.excess[name] += self._excess(name, np.diff(rest), 1.0 / found[-1][3])
            found[-1] = (*found[-1][:4], self.excess[name])
            self.excess[name] = 0
        self.items[name] = [rest] if len(rest) else []
        self.k[name] = int(blk[-1]) if len(t) else self.k[name]
        return found

    def _excess(self, name: str, d: np.ndarray, period: float) -> int:
        """Decision B461: of the intervals ``d`` (s), those the caller counts as dropped samples (over ``limit``, up to
        B11's 1 s) that are within 1.5 of ``period``, the stretch's own (none without ``limit``)."""
        if self.limit is None or not len(d):
            return 0
        return int(np.count_nonzero((d > self.limit(name)) & (d <= min(DROP_FACTOR * period, MIN_GAP_S))))

    def _lines(self, found: list[tuple[str, float, float, float, int]], final: bool = False) -> list[str]:
        """Decision E310: the changes of ``found`` (keyed to 0.1 s and the rates' 4 digits, as read_session groups
        them) join the held line of the same change or start one; a stream whose change was already said joins it
        quietly. Then the held lines that are due (:meth:`_said`)."""
        self.new = [(name, t_s, 1.0 / b, n) for name, t_s, _, b, n in found]
        for name, t_s, a, b, _ in found:
            key = (round(t_s, 1), f"{a:.4g}", f"{b:.4g}")
            group = next((c for c in (*self.held, *self.changes) if c["key"] == key), None)
            if group is not None:
                group["streams"].append(name)
            else:
                self.held.append({"key": key, "streams": [name], "end": self._judged(name), "by": name})
        return self._said(final)

    def _judged(self, name: str) -> float:
        """The time (s) up to which the stream's blocks are judged: the start of its open block."""
        return self.start[name] + self.k[name] * BLOCK_S

    def _said(self, final: bool = False) -> list[str]:
        """Decision E310: one line per held change that every other stream seen has judged up to (its blocks to the
        held block's end), whose first stream closed :data:`HOLD_BLOCKS` blocks since, or at ``final``; each kept in
        :attr:`changes`."""
        lines, held = [], []
        for g in self.held:
            due = final or self._judged(g["by"]) >= g["end"] + HOLD_BLOCKS * BLOCK_S or all(
                self._judged(n) >= g["end"] - 1e-9 for n in self.start if n not in g["streams"])
            if not due:
                held.append(g)
                continue
            t_s, a, b = g["key"]
            self.changes.append({"key": g["key"], "streams": g["streams"], "t_s": t_s, "before_hz": float(a),
                                 "after_hz": float(b)})
            lines.append(f"{change_text(g['streams'], [g['key']])}: {LIVE_TAIL}")
        self.held = held
        return lines


def _times(items: list) -> np.ndarray:
    """The pushed times of a stream's items (one-sample floats and arrays, in push order) as one array."""
    if all(isinstance(it, float) for it in items):
        return np.array(items)
    parts, ones = [], []
    for it in items:
        if isinstance(it, float):
            ones.append(it)
            continue
        if ones:
            parts.append(np.array(ones))
            ones = []
        parts.append(np.asarray(it, dtype=float))
    if ones:
        parts.append(np.array(ones))
    return np.concatenate(parts) if parts else np.zeros(0)
