"""Decisions W547 / W548 (trial T1 finding F2, a race-walking coach): a foot unit `--units waist` left out is not read
by W336's foot-rest veto (nor W488's strideless turns), and W336's foot swings are read without L596's rhythm rule, so
a race walker's short rests count. Users 15860-15861 (session 48)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from pdrlearn.kernels import foot_rhythm as FR
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.frame_inference import _declared_foot, foot_swing_strides, rest_swings
from pdrlearn.track.units import keep_units
from pdrlearn.track.waist import track_waist


@pytest.fixture(scope="module")
def ride():
    route = parse_route("stand:3, straight:10, vehicle:25:1.0, straight:10, stand:3")
    return simulate_path(route, UserProfile.from_seed(15860), rate_hz=100.0, seed=15860)


def _inside(res, row) -> int:
    ev = res.steps["event_s"].to_numpy(float)
    return int(((ev > row.start_s + 1.0) & (ev < row.end_s - 1.0)).sum())


def test_units_waist_does_not_read_the_left_out_foot(ride):
    """W547: with the foot in the session the default veto drops the ride's bounce (W336 / W337) and names it; with
    the foot left out by --units waist (B127's keep_units) the track reads the lower back alone: the contacts are
    kept and no W336 line names a foot the user left out (before: dropped, T1's 0 m tracks)."""
    row = ride.extras["rides"].iloc[0]
    both = track_waist(ride, pipeline="waist-pendulum")
    assert _inside(both, row) == 0 and any("decision W336" in w for w in both.info["warnings"])
    waist = track_waist(keep_units(ride, ("waist",)), pipeline="waist-pendulum")
    phone = track_waist(dataclasses.replace(keep_units(ride, ("waist",)), _left_out={}), pipeline="waist-pendulum")
    assert _inside(waist, row) > 10
    assert not [w for w in waist.info["warnings"] if "decision W336" in w]
    assert np.array_equal(waist.steps["event_s"].to_numpy(), phone.steps["event_s"].to_numpy())


def test_a_race_walkers_rests_count_when_the_period_reads_six_strides(monkeypatch):
    """W548: T1's race walks read the foot's stride period at six strides (3.48 s on rw15634: the highest
    autocorrelation peak of a very regular stride), and L596's rule then drops every rest under 0.21 s - all of a race
    walker's. Forced here (the period 3.48 s) on a short race walk (0.95 m steps in 0.29 s): the rhythm stance has no
    swing left, W336's swings (W548) keep every stride, and the default veto drops no contact."""
    p = dataclasses.replace(UserProfile.from_seed(15861), step_length_m=0.95, step_time_s=0.29)
    walk = simulate_path(parse_route("stand:3, straight:30, stand:3"), p, rate_hz=100.0, seed=15861)
    monkeypatch.setattr(FR, "foot_period", lambda *a, **k: 3.48)
    fs = _declared_foot(walk, need_frame=False)[3]
    assert len(rest_swings(_declared_foot(walk, need_frame=False)[5], fs)[0]) == 0  # L596's stance: no swing
    t0, _t1, turn = foot_swing_strides(walk)
    assert len(t0) >= 12 and (turn >= 0.5).sum() >= 12
    on = track_waist(walk, pipeline="waist-pendulum")
    off = track_waist(walk, pipeline="waist-pendulum", foot_rest_veto=False)
    assert not [w for w in on.info["warnings"] if "decision W336" in w]
    assert len(on.steps) >= 25 and np.array_equal(on.steps["event_s"].to_numpy(), off.steps["event_s"].to_numpy())
