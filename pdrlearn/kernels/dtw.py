"""DTW distance of one step to a reference set, numpy only (the runtime's DTW; training uses
dtaidistance's C implementation of the same recursion, see :mod:`pdrlearn.classify.dtw`)."""

from __future__ import annotations

import numpy as np


def dtw_to_refs(q: np.ndarray, refs: np.ndarray, window: int | None) -> np.ndarray:
    """DTW distance of one query ``(m, c)`` to every reference ``(r, n, c)`` -> ``(r,)``.

    Sakoe-Chiba half-width ``window`` samples (``None`` = unconstrained); distance = square root of the
    summed squared Euclidean inner distances (dtaidistance's ``dtw_ndim`` convention). Vectorised over
    references; each row's in-row dependency is a cumulative min-plus scan.
    """
    r, n, _ = refs.shape
    m = q.shape[0]
    w = max(n, m) if window is None else max(int(window), abs(n - m) + 1)
    cost = ((q[None, :, None, :] - refs[:, None, :, :]) ** 2).sum(axis=3)  # (r, m, n)
    prev = np.full((r, n + 1), np.inf)
    prev[:, 0] = 0.0
    for i in range(1, m + 1):
        j0, j1 = max(1, i - w + 1), min(n, i + w - 1)
        row = np.full((r, n + 1), np.inf)
        diag_up = np.minimum(prev[:, j0 - 1: j1], prev[:, j0: j1 + 1])  # (r, k)
        c = cost[:, i - 1, j0 - 1: j1]
        acc = row[:, j0 - 1]
        for k in range(j1 - j0 + 1):
            acc = c[:, k] + np.minimum(diag_up[:, k], acc)
            row[:, j0 + k] = acc
        prev = row
    return np.sqrt(prev[:, n])
