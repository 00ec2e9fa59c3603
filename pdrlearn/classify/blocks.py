"""Cross-validation folds of contiguous blocks of each walk (decision C95, ``train --cv-groups block``).

A pure kernel on index arrays: no estimator, no session object."""

from __future__ import annotations

import numpy as np

#: labelled steps left out of training on each side of a held-out block (decision C95): one stride, so no training
#: window touches a test window (consecutive step windows share their boundary sample)
BLOCK_GAP = 1


def block_folds(session: np.ndarray, order: np.ndarray, n_blocks: int,
                gap: int = BLOCK_GAP) -> list[tuple[np.ndarray, np.ndarray]]:
    """Folds ``[(train, test), ...]`` over steps given each step's ``session`` and its walking ``order`` within the
    session (its row in steps.csv). Each session's steps, sorted by ``order``, are cut into ``n_blocks`` contiguous
    blocks of (almost) equal size; fold k tests block k of every session and trains on the rest less the ``gap``
    steps on each side of each held-out block (same session). Folds with no test step are dropped."""
    session, order = np.asarray(session), np.asarray(order)
    if n_blocks < 2:
        raise ValueError(f"block folds need at least 2 blocks, got {n_blocks}")
    block = np.full(len(session), -1)
    purge = [np.zeros(len(session), dtype=bool) for _ in range(n_blocks)]
    for s in np.unique(session):
        idx = np.flatnonzero(session == s)
        idx = idx[np.argsort(order[idx], kind="stable")]
        for k, part in enumerate(np.array_split(np.arange(len(idx)), n_blocks)):
            if not len(part):
                continue
            block[idx[part]] = k
            lo, hi = max(0, part[0] - gap), min(len(idx), part[-1] + 1 + gap)
            purge[k][idx[lo:hi]] = True  # the block and its neighbours: none of them trains fold k
    folds = []
    for k in range(n_blocks):
        test = np.flatnonzero(block == k)
        if len(test):
            folds.append((np.flatnonzero(~purge[k]), test))
    return folds
