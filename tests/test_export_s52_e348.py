"""Decision E348 (session 52, FF, trial s52t1 F2): L91's bridge across a waist gyroscope gap (a dropout of both units)
draws a straight line of the rate between the two pelvic-rotation instants around the gap, a turn of tens of degrees
on a straight walk (trial: -41.9 deg over 3 s). E348's candidate (``waist_bridge_yaw(gap_line=False)``: the gap adds
no turn) was measured and not adopted (it loses the turn of a gap inside a curve); it stays a keyword option. Kernel
on hand-made rates."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pdrlearn.kernels.stride import waist_bridge_yaw


def _stream(gap=None, fs=100.0):
    t = np.arange(50.0, 70.0, 1.0 / fs)
    if gap is not None:
        t = t[(t < gap[0]) | (t >= gap[1])]
    w = 2 * math.pi / 1.2  # a 1.2 s gait cycle; the pelvis' yaw rate +-0.4 rad/s, zero mean (no turn)
    gyr = np.column_stack([0 * t, 0 * t, 0.4 * np.sin(w * t + math.pi / 2)])
    acc = np.column_stack([0 * t, 0 * t, np.full_like(t, 9.81)])
    data = {"wGyroscope": (t, gyr), "wAccelerometer": (t, acc)}
    return data.__getitem__


def test_the_candidate_counts_no_turn_across_the_waist_gyroscopes_own_gap():
    """Over whole gait cycles of an oscillating rate the bridge is ~0. With a 3.6 s hole in it the default (the
    line between the rates at 59.99 and 63.60 s) turns it by tens of degrees; E348's candidate counts only the
    samples either side, so the turn is at most the pelvis' own swing."""
    whole = waist_bridge_yaw(_stream(), 58.8, 64.8)  # 5 cycles
    assert abs(math.degrees(whole)) < 0.5
    assert waist_bridge_yaw(_stream(), 58.8, 64.8, gap_line=False) == whole  # no gap: the same sum
    holed = waist_bridge_yaw(_stream((60.0, 63.6)), 58.8, 64.8, gap_line=False)  # 3 cycles missing
    assert abs(math.degrees(holed)) < 10.0
    assert abs(math.degrees(waist_bridge_yaw(_stream((60.0, 63.6)), 58.8, 64.8))) > 20.0  # the default: the line
    t, g = _stream((60.0, 63.6))("wGyroscope")
    i = int(np.searchsorted(t, 60.0))
    line = 0.5 * (g[i - 1, 2] + g[i, 2]) * (t[i] - t[i - 1])  # what the straight line alone added before
    assert abs(math.degrees(line)) > 20.0  # the case is one the line gets badly wrong


def test_a_short_interval_is_still_integrated_w389():
    """With the candidate too, intervals of 1 s or less are integrated on the timestamps (W389: a straight line)."""
    full = waist_bridge_yaw(_stream(), 58.8, 63.6)
    short = waist_bridge_yaw(_stream((60.0, 60.6)), 58.8, 63.6, gap_line=False)
    assert short == waist_bridge_yaw(_stream((60.0, 60.6)), 58.8, 63.6)
    t, g = _stream((60.0, 60.6))("wGyroscope")
    m = (t >= 58.8 - 1e-9) & (t <= 63.6 + 1e-9)
    trap = float(np.sum(0.5 * (g[m][1:, 2] + g[m][:-1, 2]) * np.diff(t[m])))
    assert short == pytest.approx(trap, abs=1e-9) and short != pytest.approx(full, abs=1e-3)
