"""Decisions L255 / L256 (session 29; trial s29 finding 1): a lower-back turns.csv counts a full turn on the spot
whose steps were missed - a yaw-rate turn no counted turn overlaps, over which the step rows' heading is on another
branch (L231's whole turns) - and leaves out the yaw-rate turns the rows' heading follows."""

from __future__ import annotations

import inspect

import numpy as np
import pandas as pd
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.clinical import rows_heading_change, turn_table, whole_turns

KEYS = ("start_s", "end_s", "peak_s", "angle_deg", "peak_dps")


def _yaw(*rows):
    return [dict(zip(KEYS, r, strict=True)) for r in rows]


def _table(change_deg: float, drift_deg: float = 0.0):
    """A lower-back step table whose turn on the spot fell between two contacts (6.0 s and 9.6 s): the wrapped
    heading changes by ``change_deg`` there; the walk after it drifts ``drift_deg`` in all."""
    t = np.r_[np.arange(0, 6.01, 0.6), 9.6 + np.arange(0, 6.01, 0.6)]
    h = np.where(t > 9, np.radians(change_deg), 0.0) + np.radians(drift_deg) * t / t[-1]
    return pd.DataFrame({"start_s": t, "end_s": np.r_[t[1:], t[-1] + 0.6], "heading_rad": np.angle(np.exp(1j * h)),
                         "length_m": 0.4, "unit": "waist"})


def test_whole_turns_and_the_rows_heading_change():
    assert whole_turns([354.0, 186.0, 180.0, -350.0, 95.0], 4.0).tolist() == [360.0, 360.0, 0.0, -360.0, 0.0]
    assert whole_turns(190.0, -5.0) == 360.0  # more than half a turn from the rows' heading
    st = _table(90.0)
    assert rows_heading_change(st, 6.3, 9.0) == pytest.approx(90.0)  # rows 6.0 s -> 9.6 s
    assert rows_heading_change(st, -1.0, 0.3) == pytest.approx(0.0)  # first valid row where there is none before
    assert rows_heading_change(st.iloc[:1], 6.3, 9.0) == 0.0


def test_a_full_turn_whose_steps_were_missed_is_counted():
    assert inspect.signature(turn_table).parameters["whole"].default is True  # L256
    bouts = pd.DataFrame({"bout": [1, 2], "start_s": [0.0, 9.6], "end_s": [6.0, 15.6]})
    yaw = _yaw((6.3, 9.3, 7.8, 359.4, 104.0), (11.0, 12.4, 11.7, 95.0, 70.0))
    tt = turn_table(_table(360.0, drift_deg=20.0), bouts, yaw_turns=yaw)
    # the 360 deg turn reads ~0 deg on the rows: L233's row; the 95 deg yaw-rate turn the rows' heading follows
    # (its drift is no turn, shift 0) is no row, where L233's yaw_only adds it
    assert len(tt) == 1
    row = tt.iloc[0]
    assert (row.start_s, row.end_s, row.angle_deg, row.peak_rate_dps, row.n_rows) == pytest.approx(
        (6.3, 9.3, 359.4, 104.0, 0))
    assert pd.isna(row.bout) and row.mean_rate_dps == pytest.approx(359.4 / 3.0)
    assert turn_table(_table(360.0, drift_deg=20.0), yaw_turns=yaw, whole=False).empty  # L234's default
    assert len(turn_table(_table(360.0, drift_deg=20.0), yaw_turns=yaw, whole=False, yaw_only=True)) == 2
    # a turn the steps saw (L231's branch) is that turn's timing, not a second row; under min_deg no row
    assert turn_table(_table(181.8), yaw_turns=_yaw((6.3, 9.0, 7.6, 180.0, 101.0)))["n_rows"].tolist() == [1]
    assert turn_table(_table(0.0), yaw_turns=_yaw((6.3, 9.0, 7.6, 60.0, 50.0)), min_deg=80.0).empty
    # foot tables and tables without yaw-rate turns do not change
    pd.testing.assert_frame_equal(turn_table(_table(360.0)), turn_table(_table(360.0), timing="heading"))


def test_lower_back_counts_the_trials_360_turn_on_the_spot():
    """The trial's spent user 4813 (``simulate --route ... --step-length 0.2 --step-time 0.55 --bounce pendulum
    --rate 100``): today's lower back listed only the 180 deg turn (171.8 deg); the pelvis yaw rate holds both."""
    from pdrlearn.cli.simulate import _custom_gait
    from pdrlearn.track.evaluate import track_summary
    from pdrlearn.track.waist import track_waist

    route = "stand:2, straight:4, turn:180, straight:4, turn:360, straight:2, stand:2"
    user = _custom_gait(UserProfile.from_seed(4813), "normal", 0.2, 0.55, route)
    s = simulate_path(parse_route(route), user, speed="normal", rate_hz=100.0, seed=0, bounce="pendulum")
    res = track_waist(s, pipeline="waist-pendulum")
    yaw = res.info["yaw_turns"]
    assert len(turn_table(res.steps, yaw_turns=yaw, whole=False)) == 1  # L254's reading: the 360 deg turn missed
    tt = turn_table(res.steps, yaw_turns=yaw)
    assert len(tt) == 2
    assert tt["angle_deg"].tolist() == pytest.approx([180.0, 360.0], abs=10.0)
    t = s.trajectory["t"].to_numpy(float)
    h = np.degrees(np.unwrap(s.trajectory["heading_rad"].to_numpy(float)))
    spin = t[(h > 200.0) & (h < 520.0)]  # the true 360 deg turn (heading from 180 to 540 deg)
    assert abs(tt.loc[1, "start_s"] - spin.min()) < 1.5 and abs(tt.loc[1, "end_s"] - spin.max()) < 1.5
    assert 80.0 <= tt.loc[1, "peak_rate_dps"] <= 130.0 and tt.loc[1, "n_rows"] == 0
    summary = track_summary(res, s)
    assert summary["turn_count"] == 2
