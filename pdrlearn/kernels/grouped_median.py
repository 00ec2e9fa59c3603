"""Decision W359: the median of times that are whole sample periods, without snapping to a sample (numpy only)."""

from __future__ import annotations

import numpy as np

#: W359: two times closer than this (s) are the same value (timestamps written in ms or us round-trip with noise)
SAME_TIME_S = 1e-6


def grid_step(values: np.ndarray) -> float | None:
    """W359: the grid of ``values`` - the smallest difference between two distinct finite values (``SAME_TIME_S``
    apart or more); None with fewer than two distinct values."""
    v = np.unique(np.round(np.asarray(values, dtype=float)[np.isfinite(values)] / SAME_TIME_S) * SAME_TIME_S)
    d = np.diff(v)
    d = d[d >= SAME_TIME_S / 2]
    return float(d.min()) if len(d) else None


def sample_grid(times: np.ndarray) -> float | None:
    """W359 (amended after review R1): the sampling period the event ``times`` (s) sit on - the greatest common divisor
    of their differences from the first, by Euclid's algorithm to ``SAME_TIME_S``. Contact times of a whole recording
    share its sample grid, where a handful of stride times can all be several samples apart (R1: a 0.04 s "grid" at
    100 Hz). None with fewer than two distinct times or when they sit on no grid coarser than 10 ``SAME_TIME_S``
    (sub-sample times: nothing to interpolate)."""
    t = np.asarray(times, dtype=float)
    t = t[np.isfinite(t)]
    if len(t) < 2:
        return None
    d = np.unique(np.abs(t - t.min()))
    d = d[d >= SAME_TIME_S].tolist()
    if not d:
        return None
    g = d[0]
    for x in d[1:]:
        a, b = x, g
        while b > SAME_TIME_S:
            r = a % b
            if r < SAME_TIME_S or b - r < SAME_TIME_S:
                r = 0.0
            a, b = b, r
        g = a
        if g < 10 * SAME_TIME_S:
            return None
    return float(g)


def grouped_median(values: np.ndarray, width: float | None = None) -> float | None:
    """W359: the grouped-data (interpolated) median of the finite ``values`` with class ``width`` (the sample period,
    e.g. :func:`sample_grid` of the contact times; None: the values' own :func:`grid_step`, which with few values can
    be several samples wide - review R1): ``L + w (n/2 - F) / f``, ``L`` the lower edge of the plain median's class
    (median - w/2), ``F`` the count below that class and ``f`` the count in it (the textbook median of grouped data:
    Spiegel & Stephens, Statistics, Schaum's Outline, "Median" of grouped data). Within half a class of the plain
    median; equal to it when all values are the same. None without a finite value."""
    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v)]
    if not len(v):
        return None
    w = grid_step(v) if width is None else width
    if not w:
        return float(np.median(v))
    base = float(v.min())
    k = np.rint((v - base) / w).astype(np.int64)  # each value's class, centred on base + k w
    counts = np.bincount(k)
    cum = np.cumsum(counts)
    m = int(np.searchsorted(cum, len(v) / 2.0))  # the class that holds the middle position
    if cum[m] == len(v) / 2.0:  # an even count split between two classes: the plain median (their midpoint)
        return float(np.median(v))
    below = float(cum[m] - counts[m])
    return float(base + (m - 0.5) * w + w * (len(v) / 2.0 - below) / counts[m])
