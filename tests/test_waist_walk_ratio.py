"""Session 20's trial `aids` (finding 2): an uncalibrated waist track of a short-stepping walker read 1.4-4x too
far with no warning. Its walk ratio (step length / cadence) lies far under healthy gait's, and the track now
says so and names `calibrate` (decision W100); a normal walk and a calibrated short-step walk do not warn."""

from __future__ import annotations

import dataclasses

import numpy as np

from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.calibration import calibrate
from pdrlearn.waist.plausibility import WALK_RATIO_BAND, walk_ratio, walk_ratio_message

ROUTE = [Stand(3), Straight(14), Stand(3)]


def _festination(seed: int, route=ROUTE):
    """The trial's festinating walker: user 403, 0.15 m steps every 0.4 s (0.375 m/s), the pendulum bounce."""
    u = dataclasses.replace(UserProfile.from_seed(403), step_length_m=0.15, step_time_s=0.4)
    return simulate_path(route, u, speed="normal", rate_hz=100, seed=seed, bounce="pendulum")


def _w100(r) -> list[str]:
    return [w for w in r.info["warnings"] if "decision W100" in w]


def test_walk_ratio_is_median_length_over_median_cadence_and_needs_ten_steps():
    step_s = np.array([0.5, 0.5, 0.6, np.nan, 0.5])
    ratio, n, length, cadence = walk_ratio(np.array([0.6, 0.7, 0.65, 0.0, -0.6]), step_s)
    assert (n, length, cadence) == (4, 0.625, 120.0)
    assert ratio == 0.625 / 120.0
    assert walk_ratio(np.ones(3), np.full(3, np.nan)) == (None, 0, None, None)
    assert walk_ratio_message(0.0064, 40, 0.64, 100.0) is None  # healthy
    assert walk_ratio_message(0.002, 9, 0.3, 150.0) is None  # too few steps to judge
    low = walk_ratio_message(WALK_RATIO_BAND[0] * 0.99, 40, 0.3, 95.0)
    high = walk_ratio_message(WALK_RATIO_BAND[1] * 1.01, 40, 0.6, 62.0)
    assert "short-stepping" in low and "implausibly long" in high
    assert all("pdrlearn calibrate DIR --distance M" in line for line in (low, high))


def test_an_uncalibrated_festinating_walk_warns_naming_calibrate():
    """The trial's +75 % walk: about 94 steps at 150 steps/min read at about 0.28 m each (truth 0.15 m)."""
    s = _festination(403)
    r = track_waist(s, pipeline="waist-pendulum")
    assert r.steps["length_m"].sum() > 1.5 * 14.0  # the error the warning is about
    assert r.info["walk_ratio"] < WALK_RATIO_BAND[0]
    (line,) = _w100(r)
    assert "short-stepping" in line and "pdrlearn calibrate DIR --distance M" in line
    assert line in r.summary(s)["info"]["warnings"]  # the track summary's warnings (summary.json, track-all)


def test_a_normal_walk_and_a_calibrated_festinating_walk_do_not_warn():
    s = simulate_path(ROUTE, UserProfile.from_seed(403), speed="normal", rate_hz=100, seed=403, bounce="pendulum")
    r = track_waist(s, pipeline="waist-pendulum")
    assert WALK_RATIO_BAND[0] < r.info["walk_ratio"] < WALK_RATIO_BAND[1]
    assert not _w100(r)
    params = calibrate([_festination(7, [Stand(3), Straight(10), Stand(3)])], "waist-pendulum", distances=[10.0])
    cal = track_waist(_festination(403), pipeline="waist-pendulum", params=params)
    assert cal.info["params_source"] == "calibrated"
    assert cal.info["walk_ratio"] is None and not _w100(cal)
    assert abs(cal.steps["length_m"].sum() / 14.0 - 1.0) < 0.2  # the fix the line names works
