"""Decision W24: the stride mean yaw rate (seed 003 MRZ) of a sequence's first step spans a whole stride,
so the pelvis's per-step yaw swing cancels and a straight walk's first step is not taken for a turn."""

from __future__ import annotations

import numpy as np

from pdrlearn.waist import _kernels as K

FS = 100.0


def test_first_step_uses_a_whole_stride():
    step = 0.55
    t = np.arange(0.0, 12 * step, 1.0 / FS)
    w = 0.3 * np.sin(np.pi * t / step)  # pelvic yaw swing: one period per stride (two steps), no turn
    events = np.arange(0.0, 11 * step, step)
    mrz = K.mean_rate_per_stride(t, w, events)
    assert mrz.shape == (events.size - 1,)
    assert np.all(np.abs(mrz) < 0.01)  # every window is one stride: the swing cancels, also at k = 0
    one_step = (np.interp(events[1], t, np.cumsum(w) / FS) - 0.0) / step  # the old clipped window
    assert abs(one_step) > 0.1


def test_turn_is_still_seen_and_short_sequences_work():
    step = 0.55
    t = np.arange(0.0, 6 * step, 1.0 / FS)
    w = 0.3 * np.sin(np.pi * t / step) + 0.5  # the same swing on a steady 0.5 rad/s turn
    events = np.arange(0.0, 5 * step, step)
    np.testing.assert_allclose(K.mean_rate_per_stride(t, w, events), 0.5, atol=0.01)
    two = K.mean_rate_per_stride(t, w, events[:2])  # a one-step sequence: that step
    assert two.shape == (1,) and np.isfinite(two[0])
