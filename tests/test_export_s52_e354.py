"""Decision E354 (session 52, FK; E348's next candidate): across the waist gyroscope's own gap (a dropout of both
units) L91's bridge turns by the straight line between the gait-cycle MEAN rates of the stride before and the stride
after (``kernels.stride.CycleGapLine``), not between the two pelvic-rotation instants at the gap's edges (W389's
line: tens of degrees on a straight walk). The live ``Tracker`` and ``track --streaming`` share it."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pdrlearn.kernels.stride import CycleGapLine, waist_bridge_yaw, waist_gap_s
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.plasys import track_plasys, track_streaming
from tests.runtime_helpers import without


def _stream(gap=None, turn=0.0, fs=100.0):
    """E348's test stream: the pelvis' +-0.4 rad/s yaw oscillation over a 1.2 s gait cycle, plus a steady ``turn``."""
    t = np.arange(50.0, 70.0, 1.0 / fs)
    if gap is not None:
        t = t[(t < gap[0]) | (t >= gap[1])]
    w = 2 * math.pi / 1.2
    gyr = np.column_stack([0 * t, 0 * t, turn + 0.4 * np.sin(w * t + math.pi / 2)])
    acc = np.column_stack([0 * t, 0 * t, np.full_like(t, 9.81)])
    return {"wGyroscope": (t, gyr), "wAccelerometer": (t, acc)}.__getitem__


@pytest.mark.parametrize("turn", [0.0, 0.3])
def test_the_cycle_means_cancel_the_pelvis_and_keep_a_curves_rate(turn):
    """A 3.6 s hole between the strides [58.8, 60.0] and [63.6, 64.8]: the gap's turn is ~turn * 3.6 s (the cycle
    means), where W389's line of the two instants adds tens of degrees on the straight walk."""
    s = _stream((60.0, 63.6), turn)
    assert waist_gap_s(s, 58.8, 64.8) == pytest.approx(3.61, abs=0.011)  # the interval 59.99 -> 63.60 s
    line = CycleGapLine()
    line.note(s, 58.8, 60.0)  # decision E365: the stride before, recorded as it is measured
    line.hold(s, 60.0, 63.6)
    gap_turn = line.take(s, 63.6, 64.8)
    assert math.degrees(gap_turn) == pytest.approx(math.degrees(turn * 3.61), abs=3.0)
    assert line.take(s, 64.8, 66.0) == 0.0  # taken once
    if not turn:
        assert abs(math.degrees(waist_bridge_yaw(s, 58.8, 64.8))) > 20.0  # the default before E354: the line


@pytest.fixture(scope="module")
def dropout():
    """A fresh simulated straight walk (user 5254, 50 Hz) with every sensor silent for 3 s mid-walk."""
    s = simulate_path(parse_route("stand:2, straight:16, stand:2"), UserProfile.from_seed(5254), speed="normal",
                      rate_hz=50.0, seed=5254, name="e354", scenario="route")
    return without(s, 9.0, 12.0)


def _change(st, a: float, b: float) -> float:
    """The heading change (deg) from the mean of the 2 walking strides before ``a`` to that of the 2 after ``b``."""
    t0, t1, h = (st[k].to_numpy(float) for k in ("start_s", "end_s", "heading_rad"))
    walk = st["length_m"].to_numpy(float) > 0
    pre, post = np.flatnonzero(walk & (t1 <= a))[-2:], np.flatnonzero(walk & (t0 >= b))[:2]
    return math.degrees(math.remainder(float(np.mean(h[post]) - np.mean(h[pre])), 2 * math.pi))


def test_a_straight_walk_keeps_its_heading_across_a_3s_dropout(dropout):
    """``track --streaming`` (the live Tracker's kernel): before E354 the line of the instants turned this walk."""
    new = _change(track_plasys(dropout, streaming=True).steps, 9.0, 12.0)
    old = _change(track_streaming(dropout, method="M2", bridge_cycle=False).steps, 9.0, 12.0)
    assert _change(track_streaming(dropout, method="M2").steps, 9.0, 12.0) == pytest.approx(new, abs=1e-9)
    assert abs(new) < 5.0, (new, old)  # E354: -0.07 deg
    assert abs(old) > 8.0, (new, old)  # W389's line of the two instants: -10.06 deg (the default before E354)
