"""Decision B475 (session 51, FA, review s51r1 F5): B474's pitch reference is one mechanism,
``kernels.window.PitchReference``, for the live Tracker and ``track --streaming``; the rest's +-20 ms half width is
read once (``rest_half_width``)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pdrlearn.kernels.window import PitchReference, level_reference, pitched_from, rest_half_width

FWD = np.array([1.0, 0.0, 0.0])  # the simulator's foot frame: x forward, y up, z right


def _rests(pitches, n: int = 20, fs: float = 20.0):
    """One still window of ``n`` samples per pitch (deg; NaN: a window off a rest, turning at 1 rad/s), in turn."""
    t, acc, gyr = [], [], []
    for k, p in enumerate(pitches):
        th = math.radians(0.0 if math.isnan(p) else p)
        t.append(k * 10.0 + np.arange(n) / fs)
        acc.append(np.tile([-9.81 * math.sin(th), 9.81 * math.cos(th), 0.0], (n, 1)))
        gyr.append(np.tile([0.0, 0.0, 1.0 if math.isnan(p) else 0.0], (n, 1)))
    tt = np.concatenate(t)
    s = {"fAccelerometer": (tt, np.concatenate(acc)), "fGyroscope": (tt, np.concatenate(gyr))}
    return s.__getitem__, [(k * 10.0, k * 10.0 + (n - 1) / fs) for k in range(len(pitches))]


def test_the_reference_is_b474_s_rule_in_one_object():
    pitches = [70.0, 5.0, float("nan"), 20.0, 80.0, 52.0]  # a kneeling start, a walk, no rest, a crawl
    stream, windows = _rests(pitches)
    ref, got, want = PitchReference(), [], []
    old = None
    for p, (t0, t1) in zip(pitches, windows, strict=True):
        got.append(ref.pitched(stream, FWD, t0, t1, rest_search_s=0.25))
        hit = pitched_from(p, old)
        want.append(hit)
        old = old if hit else level_reference(old, p)
    assert got == want == [False, False, False, False, True, True]
    assert ref.deg == pytest.approx(5.0, abs=1e-6)  # a pitched stride does not move the reference
    wide = PitchReference(max_change_deg=80.0)  # pitched_from's keyword, kept
    assert not wide.pitched(stream, FWD, *windows[1], rest_search_s=0.25)
    assert not wide.pitched(stream, FWD, *windows[4], rest_search_s=0.25) and wide.deg == pytest.approx(5.0, abs=1e-6)


def test_the_rest_half_width():
    assert rest_half_width(np.arange(41) / 100.0) == (pytest.approx(100.0), 2)
    assert rest_half_width(np.array([3.0])) == (1.0, 0)
