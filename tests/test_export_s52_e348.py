"""Decision E348 (session 52, FF, trial s52t1 F2): a waist gyroscope gap inside L91's bridge (a dropout of both
units) adds no turn; before, the trapezoid drew a straight line of the rate between the two pelvic-rotation instants
around the gap, a turn of tens of degrees on a straight walk (trial: -41.9 deg over 3 s). Kernel on hand-made rates;
one short simulated straight walk (user 19369) with a 3 s dropout of every sensor, replayed by the runtime Tracker."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pdrlearn.kernels.stride import waist_bridge_yaw
from tests.lean_helpers import ROOT


def _stream(gap=None, fs=100.0):
    t = np.arange(50.0, 70.0, 1.0 / fs)
    if gap is not None:
        t = t[(t < gap[0]) | (t >= gap[1])]
    w = 2 * math.pi / 1.2  # a 1.2 s gait cycle; the pelvis' yaw rate +-0.4 rad/s, zero mean (no turn)
    gyr = np.column_stack([0 * t, 0 * t, 0.4 * np.sin(w * t + math.pi / 2)])
    acc = np.column_stack([0 * t, 0 * t, np.full_like(t, 9.81)])
    data = {"wGyroscope": (t, gyr), "wAccelerometer": (t, acc)}
    return data.__getitem__


def test_the_waist_gyroscopes_own_gap_adds_no_turn():
    """Over whole gait cycles of an oscillating rate the bridge is ~0. With a 3 s hole in it: before E348 the line
    between the rates at 59.99 and 63.60 s turned it by tens of degrees; now only the samples either side count, so
    the turn is at most the pelvis' own swing (a few degrees)."""
    whole = waist_bridge_yaw(_stream(), 58.8, 64.8)  # 5 cycles
    assert abs(math.degrees(whole)) < 0.5
    holed = waist_bridge_yaw(_stream((60.0, 63.6)), 58.8, 64.8)  # 3 cycles missing, the rate 0.4 rad/s at both ends
    assert abs(math.degrees(holed)) < 10.0
    t, g = _stream((60.0, 63.6))("wGyroscope")
    i = int(np.searchsorted(t, 60.0))
    line = 0.5 * (g[i - 1, 2] + g[i, 2]) * (t[i] - t[i - 1])  # what the straight line alone added before
    assert abs(math.degrees(line)) > 20.0  # the case is one the old rule got badly wrong


def test_a_short_interval_is_still_integrated_w389():
    """Intervals of 1 s or less are integrated on the timestamps as before (W389: a straight line across them)."""
    full = waist_bridge_yaw(_stream(), 58.8, 63.6)
    short = waist_bridge_yaw(_stream((60.0, 60.6)), 58.8, 63.6)
    t, g = _stream((60.0, 60.6))("wGyroscope")
    m = (t >= 58.8 - 1e-9) & (t <= 63.6 + 1e-9)
    trap = float(np.sum(0.5 * (g[m][1:, 2] + g[m][:-1, 2]) * np.diff(t[m])))
    assert short == pytest.approx(trap, abs=1e-9) and short != pytest.approx(full, abs=1e-3)


@pytest.fixture(scope="module")
def walk():
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    return simulate_path(parse_route("stand:3, straight:16, stand:2"), UserProfile.from_seed(19369), speed="normal",
                         rate_hz=20.0, seed=19369, scenario="route")


def test_the_live_heading_keeps_its_direction_across_a_dropout_of_both_units(walk):
    """Every sensor silent 3 s mid-walk (the trial's F2 on a short walk): the strides after the gap head as the
    strides before it (the walker goes straight on), within 10 deg; before E348 the bridge turned them."""
    from pdrlearn.runtime import Tracker, load_bundle
    from tests.runtime_helpers import time_chunks

    t = walk.streams["fAccelerometer"].t
    a = float(t[0]) + 12.0
    tr = Tracker(load_bundle(ROOT / "models" / "plasys-sim-default"), tasks=[], sensors=list(walk.streams))
    steps = []
    for _, chunk in time_chunks(walk, 1.0):
        cut = {n: (tt[(tt < a) | (tt >= a + 3.0)], v[(tt < a) | (tt >= a + 3.0)]) for n, (tt, v) in chunk.items()}
        steps += tr.push({n: c for n, c in cut.items() if len(c[0])})
    steps += tr.flush()
    g = next(i for i, s in enumerate(steps) if s.gap_s > 0)
    before = np.mean([s.heading_rad for s in steps[g - 2:g]])
    after = np.mean([s.heading_rad for s in steps[g + 1:g + 3]])
    assert abs(math.degrees(after - before)) < 10.0, [round(math.degrees(s.heading_rad), 1) for s in steps]
