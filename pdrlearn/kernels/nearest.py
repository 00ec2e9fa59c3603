"""Nearest neighbours on a line (decision L546): for each value its nearest reference value, by a binary search of
the sorted references - O((n + m) log m) time and O(n + m) memory, where the pairwise ``|x[:, None] - ref[None, :]|``
matrix it replaces grew with the square of a recording's length (a 107 min march: ~11 000 contacts, a 1 GB matrix)."""

from __future__ import annotations

import numpy as np


def nearest_index(x: np.ndarray, ref: np.ndarray) -> np.ndarray:
    """Per value of ``x`` the index into ``ref`` (not empty, any order) of its nearest value; a tie goes to the first
    in ``ref`` - as ``np.abs(x[:, None] - ref[None, :]).argmin(axis=1)``."""
    x, ref = np.asarray(x, dtype=float), np.asarray(ref, dtype=float)
    order = np.argsort(ref, kind="stable")
    r = ref[order]
    hi = np.clip(np.searchsorted(r, x, side="left"), 0, len(r) - 1)
    lo = np.clip(hi - 1, 0, len(r) - 1)
    lo = np.searchsorted(r, r[lo], side="left")  # the first of equal values
    d_lo, d_hi = np.abs(x - r[lo]), np.abs(r[hi] - x)
    return np.where(d_lo < d_hi, order[lo], np.where(d_hi < d_lo, order[hi], np.minimum(order[lo], order[hi])))


def nearest_distance(x: np.ndarray, ref: np.ndarray) -> np.ndarray:
    """Per value of ``x`` the distance to its nearest value in ``ref`` (not empty, any order):
    ``np.abs(x[:, None] - ref[None, :]).min(axis=1)`` without the matrix."""
    x = np.asarray(x, dtype=float)
    return np.abs(x - np.asarray(ref, dtype=float)[nearest_index(x, ref)])
