"""Decision W23: a weak vertical maximum without a lateral weight shift is no step (offline waist IC
detector, ``pdrlearn.waist._kernels.drop_unshifted``)."""

from __future__ import annotations

import numpy as np

from pdrlearn.waist import _kernels as K

FS = 100.0


def _walk(n: int = 8, period_s: float = 0.8):  # slow steps: an extra maximum mid-step is 0.4 s away
    cand = np.round(np.arange(n) * period_s * FS).astype(np.int64) + 100
    h = np.full(n, 1.5)
    side = np.where(np.arange(n) % 2 == 0, 1, -1).astype(np.int8)
    return cand, h, side


def _with_extra(h_extra: float, side_extra: int, at: int = 4):
    cand, h, side = _walk()
    c = (cand[at] + cand[at + 1]) // 2  # a maximum inside a step
    cand = np.insert(cand, at + 1, c)
    h = np.insert(h, at + 1, h_extra)
    side = np.insert(side, at + 1, np.int8(side_extra))
    return cand, h, side, at + 1


def test_weak_unshifted_maximum_is_dropped():
    cand, h, side, k = _with_extra(0.3, 0)
    acc = np.ones(cand.size, dtype=bool)
    out = K.drop_unshifted(cand, h, acc, acc, side, FS)
    assert not out[k] and out.sum() == cand.size - 1


def test_strong_or_shifted_or_filled_maxima_are_kept():
    cand, h, side, k = _with_extra(1.0, 0)  # 1.0 >= half of 1.5: a real (if undecided) step
    acc = np.ones(cand.size, dtype=bool)
    assert K.drop_unshifted(cand, h, acc, acc, side, FS).all()
    cand, h, side, k = _with_extra(0.3, 1)  # weak but with a weight shift: W20 decides, not W23
    assert K.drop_unshifted(cand, h, acc, acc, side, FS).all()
    cand, h, side, k = _with_extra(0.3, 0)  # a W18 rhythm fill (not accepted by the threshold): kept
    accepted = np.ones(cand.size, dtype=bool)
    accepted[k] = False
    assert K.drop_unshifted(cand, h, np.ones(cand.size, dtype=bool), accepted, side, FS).all()


def test_isolated_maximum_without_neighbours_is_kept():
    cand = np.array([100, 500], dtype=np.int64)  # 4 s apart: different sequences, no neighbours
    h = np.array([0.2, 1.5])
    side = np.zeros(2, dtype=np.int8)
    acc = np.ones(2, dtype=bool)
    assert K.drop_unshifted(cand, h, acc, acc, side, FS).all()


def test_rhythm_complete_applies_w23_only_with_sides():
    cand, h, side, k = _with_extra(0.3, 0)
    acc = np.ones(cand.size, dtype=bool)
    with_sides = K.rhythm_complete(cand, h, acc, FS, min_peak=0.1, side=side)
    assert not with_sides[k]
    assert K.rhythm_complete(cand, h, acc, FS, min_peak=0.1, side=side, unshifted=False)[k]
    assert K.rhythm_complete(cand, h, acc, FS, min_peak=0.1, side=None)[k]
