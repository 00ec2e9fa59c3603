"""Cross-validation folds of contiguous blocks of each walk (decision C95, ``train --cv-groups block``).

A pure kernel on arrays: no estimator, no session object."""

from __future__ import annotations

import numpy as np


def _purged(start: np.ndarray, end: np.ndarray, side: np.ndarray, test: np.ndarray) -> np.ndarray:
    """Positions (into the session's arrays) left out of training while ``test`` (positions) is held out, decision
    C95 as amended by review R2: every step whose window overlaps or touches the test span [first start, last
    end], and for each foot its stride right before and right after the block (by start time)."""
    lo, hi = start[test].min(), end[test].max()
    out = set(np.flatnonzero((start <= hi) & (end >= lo)))  # consecutive windows share their boundary sample
    first = start[test].min()
    rest = np.setdiff1d(np.arange(len(start)), test)
    for f in np.unique(side[rest]):
        own = rest[side[rest] == f]
        before, after = own[start[own] < first], own[start[own] >= first]
        if len(before):
            out.add(before[np.argmax(start[before])])
        if len(after):
            out.add(after[np.argmin(start[after])])
    return np.asarray(sorted(out | set(test)), dtype=int)


def block_folds(session: np.ndarray, start: np.ndarray, end: np.ndarray, n_blocks: int,
                side: np.ndarray | None = None) -> list[tuple[np.ndarray, np.ndarray]]:
    """Folds ``[(train, test), ...]`` over steps given each step's ``session``, its window's ``start`` and ``end``
    time and, for a two-feet table, its ``side`` (steps.csv ``foot``; None: one sequence). Each session's steps,
    sorted by start time (not by their row: a steps.csv need not be sorted), are cut into ``n_blocks`` contiguous
    blocks of (almost) equal size; fold k tests block k of every session and trains on the rest less, in the same
    session, every step overlapping or touching the block's time span and each foot's neighbouring stride on
    either side (decision C95, amended by review R2). Folds with no test step are dropped."""
    session, start, end = np.asarray(session), np.asarray(start, float), np.asarray(end, float)
    side = np.zeros(len(session), dtype=int) if side is None else np.asarray(side, dtype=object).astype(str)
    if n_blocks < 2:
        raise ValueError(f"block folds need at least 2 blocks, got {n_blocks}")
    block = np.full(len(session), -1)
    purge = [np.zeros(len(session), dtype=bool) for _ in range(n_blocks)]
    for s in np.unique(session):
        idx = np.flatnonzero(session == s)
        idx = idx[np.lexsort((end[idx], start[idx]))]  # walking order: by start time, then end
        for k, part in enumerate(np.array_split(np.arange(len(idx)), n_blocks)):
            if not len(part):
                continue
            block[idx[part]] = k
            purge[k][idx[_purged(start[idx], end[idx], side[idx], part)]] = True  # none of them trains fold k
    folds = []
    for k in range(n_blocks):
        test = np.flatnonzero(block == k)
        if len(test):
            folds.append((np.flatnonzero(~purge[k]), test))
    return folds
