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
    stream read as 104.65 Hz. A jittered clock (decision B182) gets :func:`counted_period_s`: the median
    interval of receive-time stamps (+-12 ms at 104 Hz, sorted) read 138 Hz and halved the offline distance.
    NaN for fewer than two samples."""
    if len(t) < 2:
        return float("nan")
    d = np.diff(t)
    med = float(np.median(d))
    regular = d[(d >= 0.5 * med) & (d <= 1.5 * med)]
    if jittered(regular, med):  # B33, B182: the samples over the span, the jitter cancels
        return counted_period_s(t)
    mean = float(regular.mean()) if regular.size else med
    return mean if abs(mean - med) > 0.005 * med else med


#: decision B182: an interval of a jittered clock counts as dropped samples only when it exceeds the period by this
#: many stamp-jitter SDs (:func:`stamp_jitter_s`): uniform +-J jitter has SD J / sqrt(3) and makes intervals up to
#: p + 2 J = p + 3.5 SD; Gaussian jitter passes p + 7 SD (4.9 interval SDs) once in 2 million intervals
JITTER_GAP_SDS = 7.0


def stamp_jitter_s(t: np.ndarray) -> float:
    """Decision B182: the SD (s) of the timestamps about a uniform clock, from the second differences
    ``t[i+1] - 2 t[i] + t[i-1]`` (variance 6 SD^2 for independent stamp errors; a drift or a rate cancels) by their
    median absolute deviation (x 1.4826, so a few gaps do not count). 0 for a uniform clock; +-J uniform receive-time
    jitter gives J / sqrt(3) (less once the stamps are sorted: +-12 ms at 104 Hz reads 4.8 ms)."""
    if len(t) < 10:
        return 0.0
    dd = np.diff(t, 2)
    return float(1.4826 * np.median(np.abs(dd - np.median(dd))) / np.sqrt(6.0))


def jitter_gap_limit_s(period_s: float, jitter_s: float) -> float:
    """Decision B182: the interval (s) over which a jittered clock's interval holds dropped samples: 1.5 periods
    (B11) or the period plus :data:`JITTER_GAP_SDS` stamp-jitter SDs, whichever is longer."""
    return max(1.5 * period_s, period_s + JITTER_GAP_SDS * jitter_s)


def counted_period_s(t: np.ndarray) -> float:
    """Decision B182: a jittered clock's period, the span over the sample count with the dropped samples counted
    in: ``span / (n - 1 + missing)``, ``missing`` being round(interval / period) - 1 summed over the intervals over
    :func:`jitter_gap_limit_s`, iterated from the plain span / (n - 1) until it stops changing. Sorting jittered
    receive stamps makes many short intervals and a few long ones; the median (and B33's mean of the intervals up
    to two medians) fell to 7.2 ms for a 9.6 ms period, the count over the span does not."""
    d = np.diff(t)
    span, n = float(t[-1] - t[0]), len(t)
    limit_sd = stamp_jitter_s(t)
    p = span / (n - 1)
    for _ in range(50):
        g = d[d > jitter_gap_limit_s(p, limit_sd)]
        q = span / (n - 1 + float(np.sum(np.maximum(np.rint(g / p), 1.0) - 1.0)))
        if q == p:
            break
        p = q
    return p


#: decision B186: ``import --retime HZ`` refuses stamps whose own rate (samples, lost ones counted, over their span)
#: differs from HZ by more than this fraction (every stride would scale by it)
RETIME_RATE_TOL = 0.01


def batches(t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The runs of equal timestamps of ``t``: (index of each run's first sample, its length)."""
    first = np.flatnonzero(np.r_[True, np.diff(t) != 0])
    return first, np.diff(np.r_[first, t.size])


def batch_size(t: np.ndarray) -> int:
    """Decision B186: the number of samples that share one timestamp when they come in regular groups (a Bluetooth
    notification of 4 samples on its receive time): the commonest run length of equal stamps, when it is over 1
    and at least 80 % of the samples lie in runs of it; else 1."""
    if t.size < 8:
        return 1
    _, m = batches(t)
    k = int(np.bincount(m).argmax())
    return k if k > 1 and m[m == k].sum() >= 0.8 * t.size else 1


def coarse_stamp_rate(t: np.ndarray) -> float | None:
    """Decision B468: the samples' rate (Hz) when their timestamps are quantised coarser than their own sample period
    (a 1125 Hz unit stamped in whole ms repeats every ninth stamp): the mean interval over the span is under 95 % of
    the smallest step between distinct stamps; else None. Such repeats are real samples, to be re-timed, not dropped."""
    if t.size < 8:
        return None
    steps = np.diff(t)
    pos = steps[steps > 0]
    if not pos.size or not np.isfinite(t[[0, -1]]).all():
        return None
    mean = (t[-1] - t[0]) / (t.size - 1)
    return float(1.0 / mean) if 0 < mean < 0.95 * float(pos.min()) else None


def retimed(t: np.ndarray, hz: float) -> tuple[np.ndarray, dict]:
    """Decision B186: samples re-timed at a nominal output rate ``hz`` (s in, s out), anchored to their stamps.
    Runs of equal stamps (a notification's samples on its receive time) are spread one period apart; a stamp
    advance over the samples it brings by more than max(1.5, 4 SDs of that excess) periods counts the samples
    lost before it (round); each run's last sample lies at its stamp on the median (the receive latency is not
    known). Returns the new stamps (strictly increasing) and ``{"rate_hz", "lost", "stamps", "samples_per_stamp",
    "stamp_rate_hz"}``, ``stamp_rate_hz`` being the samples (lost ones counted) over the stamps' span."""
    p = 1.0 / hz
    first, m = batches(t)
    stamps = t[first]
    excess = np.diff(stamps) / p - m[1:]  # periods the stamp moved beyond the samples it brought
    sd = 1.4826 * float(np.median(np.abs(excess - np.median(excess)))) if excess.size else 0.0
    lost = np.where(excess > max(1.5, 4.0 * sd), np.rint(excess), 0.0).astype(np.int64)
    slot0 = np.r_[0, np.cumsum(m[:-1] + lost)]  # the slot of each run's first sample
    slot = np.repeat(slot0, m) + (np.arange(t.size) - np.repeat(first, m))
    t0 = float(np.median(stamps - (slot0 + m - 1) * p))
    span = float(stamps[-1] - stamps[0])
    rate = float((slot0[-1] + m[-1] - 1 - (m[0] - 1)) / span) if span > 0 else float("nan")
    return t0 + slot * p, {"rate_hz": float(hz), "lost": int(lost.sum()), "stamps": int(first.size),
                           "samples_per_stamp": float(np.median(m)), "stamp_rate_hz": rate}
