"""Decision L580 (session 41, trial T1 finding F2): a stride that travels backward (L203's ``backward_travel``) is
left out of ``median_speed_straight_mps`` / ``n_straight_strides`` and so out of L95's judged speed, as a side step
is (L228): a backward-walking exercise of a patient whose forward walking is in range gets no "not reliable" line."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import track_summary
from pdrlearn.track.gait import STRAIGHT_MAX_RAD, not_straight_travel_rows, session_range_side
from pdrlearn.track.plasys import track_plasys


def test_a_backward_exercise_judges_the_forward_strides_speed():
    # T1's bwd exercise (simulated user 11521, slow): before L580 the straight speed 0.49 m/s pooled the 3 backward
    # strides and L95 called the walk slow
    s = simulate_path(parse_route("stand:2, straight:4, backward:6, straight:4, stand:2"), UserProfile.from_seed(11521),
                      rate_hz=100.0, seed=0, scenario="route", speed="slow")
    res = track_plasys(s)
    out = track_summary(res, s)
    steps = res.steps
    back = steps["backward_travel"].to_numpy(bool)
    assert out["n_backward_strides"] == int(back.sum()) == 3
    straight = (np.abs(steps["turn_angle_rad"].to_numpy(float)) < STRAIGHT_MAX_RAD) & np.isfinite(steps["speed_mps"])
    forward = straight & ~back
    assert out["n_straight_strides"] == int(forward.sum())
    assert out["median_speed_straight_mps"] == pytest.approx(float(np.median(steps["speed_mps"][forward])))
    assert out["median_speed_straight_mps"] > 0.8
    assert session_range_side(out) is None
    assert not out["gait_out_of_range"]


def test_rows_left_out_are_side_and_backward_travel_only_on_a_foot_table():
    foot = pd.DataFrame({"raw_length_m": [1.2, -0.7, 1.3], "length_m": [1.2, -0.7, 1.3],
                         "turn_angle_rad": [0.0, 0.0, 0.0], "gap_s": [0.0, 0.0, 0.0], "unit": ["foot"] * 3})
    assert not_straight_travel_rows(foot).tolist() == [False, True, False]
    # a lower-back table has no backward travel per step (no raw length): nothing left out
    assert not not_straight_travel_rows(foot.assign(unit="waist")).any()
