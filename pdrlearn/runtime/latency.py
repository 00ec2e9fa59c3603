"""How long after a stride its Step arrives, in the data's time (decision E288 in docs/decisions/export.md).

``run.json``'s ``latency_ms_per_step`` (E157) is the compute time of a push; a step's data latency is longer: the
tracker releases a stride once the stance that ends it has been seen (and, for a bundle cut at rests, its look-ahead
``features.rest_search_s`` + 0.05 s more). Trial T2 (session 44, F2) measured 350 ms after ``end_s`` and ~700 ms
after the heel contact, pushing sample by sample, while run.json said 7 ms. :class:`DataLatency` records, for each
step a push returns, the time of the push's last sample less the step's end (and its contact, ``--contacts``).
"""

from __future__ import annotations

import math

import numpy as np


class DataLatency:
    """Decision E288: the data latency of the steps a replay's pushes return (not those of the final flush)."""

    def __init__(self) -> None:
        self.after_end: list[float] = []
        self.after_contact: list[float] = []

    def add(self, steps, data_s: float) -> None:
        """The ``steps`` one push returned, its last sample at ``data_s`` (s)."""
        for st in steps:
            end = getattr(st, "end_s", None)
            if end is not None and math.isfinite(end) and math.isfinite(data_s):
                self.after_end.append(data_s - float(end))
            ev = getattr(st, "event_s", math.nan)
            if ev is not None and math.isfinite(ev) and math.isfinite(data_s):
                self.after_contact.append(data_s - float(ev))

    def report(self, chunk_s: float | None) -> dict:
        """run.json's ``data_latency_ms``: the median and 95th percentile (ms) after each step's end and after its
        initial contact (None without ``--contacts``), and the replay's chunk (s; a push's samples span up to it, so a
        device pushing each sample gets up to ``chunk_s`` less; None for a capture)."""
        def q(v: list[float]):
            return {k: round(float(np.percentile(v, p)) * 1e3, 1) for k, p in (("p50", 50), ("p95", 95))} if v else None

        return {"after_stride_end": q(self.after_end), "after_contact": q(self.after_contact),
                "replay_chunk_s": chunk_s}
