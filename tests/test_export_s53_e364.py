"""Decisions E364 / E365 (session 53, FB; review s53r1 F2-F4). E364: E354's line across the waist gyroscope's own gap
takes the rate after the gap only up to the size of the rate before (a turn seen only after the gap is not drawn back
into it). E365: the rate before a gap is recorded as each stride is measured (``CycleGapLine.note``), so the live
``Tracker`` (whose buffer keeps 1 s before the last step boundary) equals ``track --streaming`` for strides over 1 s;
the gap lines say what is done across the waist's own gap (``kernels.gaps.waist_gap_turn``)."""

from __future__ import annotations

import logging
import math

import numpy as np
import pytest

from pdrlearn.kernels.gaps import waist_gap_turn
from pdrlearn.kernels.stride import CycleGapLine
from pdrlearn.runtime.tracker import heading_gap_line
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.gaps import gap_heading_clause
from pdrlearn.track.plasys import track_streaming
from tests.runtime_helpers import without
from tests.test_no_cycling_s46_e304 import _live

SPOT = "a turn on the spot inside the gap is lost"


def _waist(before: float, after: float, gap=(60.0, 63.6), fs=100.0):
    """The pelvis' +-0.4 rad/s yaw oscillation over a 1.2 s gait cycle plus a steady rate ``before`` until the gap
    and ``after`` from its end (E348's test stream)."""
    t = np.arange(50.0, 70.0, 1.0 / fs)
    t = t[(t < gap[0]) | (t >= gap[1])]
    rate = np.where(t < gap[0], before, after) + 0.4 * np.sin(2 * math.pi / 1.2 * t + math.pi / 2)
    gyr = np.column_stack([0 * t, 0 * t, rate])
    acc = np.column_stack([0 * t, 0 * t, np.full_like(t, 9.81)])
    return {"wGyroscope": (t, gyr), "wAccelerometer": (t, acc)}.__getitem__


def _gap_turn(stream, **kw) -> float:
    line = CycleGapLine(**kw)
    line.note(stream, 58.8, 60.0)  # the stride before, recorded as it is measured (E365)
    line.hold(stream, 60.0, 63.6)
    return math.degrees(line.take(stream, 63.6, 64.8))


def test_a_turn_after_the_gap_is_not_drawn_into_it_but_a_curve_into_the_gap_is():
    """A straight walk, 3.6 s gap, then a 1.5 rad/s turn: E354's line added ~155 deg; E364 keeps the straight's ~0.
    A 0.3 rad/s curve that ends inside the gap keeps E354's line (half the rate across the gap) either way."""
    turn_after = _waist(0.0, 1.5)
    assert abs(_gap_turn(turn_after)) < 3.0
    assert _gap_turn(turn_after, limit_after=False) > 100.0  # E354's line as it was
    into = _waist(0.3, 0.0)
    assert _gap_turn(into) == pytest.approx(math.degrees(0.5 * 0.3 * 3.61), abs=3.0)
    assert _gap_turn(into) == pytest.approx(_gap_turn(into, limit_after=False), abs=1e-9)


def test_the_rate_before_is_the_last_stride_noted_not_the_buffer():
    """E365: ``hold`` reads the last :meth:`note`'s rate, whatever the stream still holds (a trimmed live buffer)."""
    line = CycleGapLine()
    line.note(_waist(0.3, 0.3), 58.8, 60.0)
    line.hold(_waist(0.0, 0.0), 60.0, 63.6)  # the samples of the stride before would now read 0 rad/s
    assert line.before == pytest.approx(0.3, abs=0.02)


def test_the_gap_lines_say_what_is_done_across_the_waists_own_gap():
    foot = {"fGyroscope": [(14.3, 17.0)]}
    clause = gap_heading_clause(foot, "bridged", [(14.3, 17.0)])
    assert "E354" in clause and SPOT in clause and "straight line" not in clause
    assert "straight line" in gap_heading_clause(foot, "bridged", [(14.3, 17.0)], cycle=False)
    assert gap_heading_clause(foot, "bridged") == "; the turn inside them is the waist gyroscope's (L91)"  # L91 only
    assert SPOT in heading_gap_line(14.3, 17.0, True) and "straight line" in heading_gap_line(14.3, 17.0)
    assert SPOT in waist_gap_turn() and "straight line" in waist_gap_turn(False)


@pytest.fixture(scope="module")
def slow_gap():
    """A slow walker (user 5311, strides ~1.4 s, 50 Hz), every sensor silent 12-16 s: the stride before the gap is
    longer than the live buffer's 1 s look-back."""
    s = simulate_path(parse_route("stand:2, straight:20, stand:2"), UserProfile.from_seed(5311), rate_hz=50.0,
                      seed=5311, name="e365", scenario="route", speed="slow")
    return without(s, 12.0, 16.0)


def test_the_live_tracker_bridges_a_slow_walkers_gap_as_track_streaming(slow_gap):
    """Review s53r1 F3: before E365 the live before-rate was a partial cycle (user 5311: -0.0268 against +0.0022
    rad/s, final heading -3.34 deg apart)."""
    tr, live, _ = _live(slow_gap)
    logging.disable(logging.WARNING)
    try:
        res = track_streaming(slow_gap, method="M2")
    finally:
        logging.disable(logging.NOTSET)
    lh = np.array([x.heading_rad for x in live])
    sh = res.steps.heading_rad.to_numpy(float)
    assert len(lh) == len(sh) and np.any(res.steps.gap_s.to_numpy(float) > 0)
    np.testing.assert_allclose(lh, sh, rtol=0, atol=1e-6)
    assert any(SPOT in w for w in tr.warnings) and not any("a straight line across" in w for w in tr.warnings)
    assert any(SPOT in w for w in res.info["warnings"])
