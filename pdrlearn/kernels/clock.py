"""A stream's nominal sampling period from its timestamps, numpy only (decisions D7, B33): the one rule of
:attr:`pdrlearn.io.Stream.period_s` and of the lean runtime's session replay (``python -m pdrlearn.runtime``,
decision E76), so both give the Tracker the same input rates."""

from __future__ import annotations

import numpy as np

#: sampling jitter (:attr:`Stream.jitter`: SD of the regular intervals / period) above which a stream counts as
#: jittered (decision B33): its period is the mean interval and its gaps allow for the jitter. Quantised clocks
#: (D7: 4 and 5 ms intervals, SD 7 % of the period) have jitter 0; +-1 ms at 100 Hz gives 0.08, +-2 ms 0.16.
MAX_JITTER = 0.1


def jittered(regular: np.ndarray, med: float) -> bool:
    """The regular intervals (0.5-1.5 medians) vary by more than :data:`MAX_JITTER` of the median and take more
    than two values (so not a quantised clock, D7)."""
    return (regular.size >= 9 and float(np.std(regular)) > MAX_JITTER * med
            and np.unique(np.round(regular, 9)).size > 2)


def nominal_period_s(t: np.ndarray) -> float:
    """Nominal sampling period (s) of timestamps ``t`` (s): the median sample interval, unless the timestamps are
    quantised (decision D7: 204.8 Hz written as integer ms has 4 and 5 ms intervals, median 5 ms = 200 Hz, which
    scales every integrated stride by 2.4 %); then the mean of the regular intervals (gaps left out). The regular
    intervals lie within 0.5-1.5 medians, symmetric about it (decision B33): with only the upper bound, sampling
    jitter (+-4 ms at 100 Hz: intervals 2-18 ms) lost its long intervals, the mean fell to 9.56 ms and a 100 Hz
    stream read as 104.65 Hz. NaN for fewer than two samples."""
    if len(t) < 2:
        return float("nan")
    d = np.diff(t)
    med = float(np.median(d))
    regular = d[(d >= 0.5 * med) & (d <= 1.5 * med)]
    if jittered(regular, med):  # B33: the sum of the intervals telescopes to the span, the jitter cancels
        return float(d[d <= 2.0 * med].mean())
    mean = float(regular.mean()) if regular.size else med
    return mean if abs(mean - med) > 0.005 * med else med
