"""Nearest neighbours on a line (decision L546): for each value its nearest reference value, by a binary search of
the sorted references - O((n + m) log m) time and O(n + m) memory, where the pairwise ``|x[:, None] - ref[None, :]|``
matrix it replaces grew with the square of a recording's length (a 107 min march: ~11 000 contacts, a 1 GB matrix).

Decision L557: the equivalence with the matrix holds for finite ``ref``. A NaN in ``ref`` sorts last and the nearest
*finite* value is returned, where the matrix gave NaN (its ``<= gap`` False, its argmin the NaN's index); callers pass
finite times or indices (review R3: no output changed). A NaN in ``x`` gives an arbitrary index and a NaN distance, so
a ``<= tolerance`` test on the distance is False, as with the matrix."""

from __future__ import annotations

import numpy as np


def nearest_index(x: np.ndarray, ref: np.ndarray) -> np.ndarray:
    """Per value of ``x`` the index into ``ref`` (not empty, finite, any order) of its nearest value; a tie goes to the
    first in ``ref`` - as ``np.abs(x[:, None] - ref[None, :]).argmin(axis=1)`` for finite values (decision L557)."""
    x, ref = np.asarray(x, dtype=float), np.asarray(ref, dtype=float)
    order = np.argsort(ref, kind="stable")
    r = ref[order]
    hi = np.clip(np.searchsorted(r, x, side="left"), 0, len(r) - 1)
    lo = np.clip(hi - 1, 0, len(r) - 1)
    lo = np.searchsorted(r, r[lo], side="left")  # the first of equal values
    d_lo, d_hi = np.abs(x - r[lo]), np.abs(r[hi] - x)
    return np.where(d_lo < d_hi, order[lo], np.where(d_hi < d_lo, order[hi], np.minimum(order[lo], order[hi])))


def nearest_distance(x: np.ndarray, ref: np.ndarray) -> np.ndarray:
    """Per value of ``x`` the distance to its nearest value in ``ref`` (not empty, finite, any order):
    ``np.abs(x[:, None] - ref[None, :]).min(axis=1)`` without the matrix (NaN for a NaN ``x``; decision L557)."""
    x = np.asarray(x, dtype=float)
    return np.abs(x - np.asarray(ref, dtype=float)[nearest_index(x, ref)])
