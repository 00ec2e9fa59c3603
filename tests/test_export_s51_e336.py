"""Decision E336 (session 51, FG): a streamed waist-headed stride is placed along its gait cycle's mean yaw, not the
pelvis' yaw at its end (the foot's rest), which carries the pelvic rotation's value at that phase: E331's -2..-3 deg
offset from the first stride on. Kernel on hand-made rates; one short simulated walk from a stand (fresh user 18440),
replayed in-process by the runtime Tracker and by ``track --streaming``, with ``cycle_yaw`` on and off."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pdrlearn.kernels.stride import CyclePhase, end_phase_yaw, waist_end_phase_yaw
from tests.lean_helpers import ROOT


def test_end_phase_yaw_is_the_oscillation_at_the_ends():
    t = np.linspace(0.0, 1.1, 111)  # one gait cycle at 100 Hz
    w, a, phi = 2 * math.pi / 1.1, math.radians(4.0), 1.2
    osc = a * w * np.cos(w * t + phi)  # Y(t) = a (sin(w t + phi) - sin phi): its ends at 0, its mean -a sin(phi)
    assert end_phase_yaw(t, osc, 0.0, 1.1) == pytest.approx(a * math.sin(phi), abs=2e-4)
    turn = 0.8  # rad/s: a steady turn adds nothing, with or without the oscillation
    assert end_phase_yaw(t, np.full_like(t, turn), 0.0, 1.1) == pytest.approx(0.0, abs=1e-12)
    assert end_phase_yaw(t, osc + turn, 0.0, 1.1) == pytest.approx(a * math.sin(phi), abs=2e-4)
    assert end_phase_yaw(t, osc, 0.5, 0.5) == 0.0 and end_phase_yaw(t[:1], osc[:1], 0.0, 1.0) == 0.0
    lev = {"waist": (t, None, np.column_stack([0 * t, 0 * t, osc]), None, 0.0)}
    assert waist_end_phase_yaw(lev, 0.0, 1.1) == end_phase_yaw(t, osc, 0.0, 1.1)
    assert waist_end_phase_yaw({"foot": lev["waist"]}, 0.0, 1.1) == 0.0  # no waist unit: nothing


def test_a_turning_stride_takes_the_last_straight_strides_phase_e338():
    """Decision E338: psi is read on strides turning under L79's 15 deg; a turning one (a curve's start or end: no
    steady ramp) takes the last straight stride's, or its own before any."""
    ph = CyclePhase()
    assert ph.stride(-0.12, math.radians(40.0)) == -0.12  # no straight stride yet: its own
    assert ph.stride(-0.05, math.radians(2.0)) == -0.05
    assert ph.stride(-0.12, math.radians(40.0)) == -0.05  # held over the curve
    assert ph.stride(-0.04, math.radians(-14.0)) == -0.04
    t = np.linspace(0.0, 1.1, 111)
    ramp = np.where(t < 0.55, math.radians(60.0) / 0.55, 0.0)  # a 60 deg turn over the stride's first half
    lev = {"waist": (t, None, np.column_stack([0 * t, 0 * t, ramp]), None, 0.0)}
    assert abs(waist_end_phase_yaw(lev, 0.0, 1.1)) > math.radians(10.0)  # E336 alone: the turn's shape as psi
    assert waist_end_phase_yaw(lev, 0.0, 1.1, ph) == -0.04


@pytest.fixture(scope="module")
def walk():
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    return simulate_path(parse_route("stand:3, straight:12, stand:2"), UserProfile.from_seed(18440), speed="normal",
                         rate_hz=20.0, seed=18440, scenario="route")


def _headings(walk, cycle_yaw):
    from pdrlearn.runtime import Tracker, load_bundle
    from tests.runtime_helpers import time_chunks

    tr = Tracker(load_bundle(ROOT / "models" / "plasys-sim-default"), tasks=[], sensors=list(walk.streams),
                 cycle_yaw=cycle_yaw)
    steps = [st for _, c in time_chunks(walk, 1.0) for st in tr.push(c)] + list(tr.flush())
    return np.array([st.heading_rad for st in steps]), tr.heading


def test_the_streamed_walk_goes_along_the_walking_direction(walk):
    """The walker goes straight along x (heading 0). Before E336 the strides after the first are held at the pelvis'
    yaw at the right foot's rest (about -3 deg on the simulator's walkers); after, within about 1 deg. The heading the
    tracker carries (its boundary yaw) is the same either way: E336 moves where a stride goes, not the turns."""
    from pdrlearn.track.plasys import track_plasys

    on, heading_on = _headings(walk, True)
    off, heading_off = _headings(walk, False)
    assert len(on) == len(off) >= 6 and heading_on == heading_off
    walked = slice(1, len(on) - 1)  # a full cycle each: the first (from the stand) and last (into it) are halves
    assert np.degrees(np.median(off[walked])) < -1.5  # the offset E331 covered
    assert abs(np.degrees(np.median(on[walked]))) < 1.0
    streamed = track_plasys(walk, streaming=True).steps["heading_rad"].to_numpy(float)  # track --streaming's call
    assert np.allclose(streamed, on, atol=1e-6)
