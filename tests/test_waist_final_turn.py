"""Session 27 trial `rehab` finding 8: a lower-back track lost a turn made on the spot after the last step (no step
follows it), so turns.csv and the final heading missed it. Decision W187: with ``integrate_end`` the gyro heading
integrates through the final stop as W72/W73's ``integrate_stops`` does between walking sequences; decision L205:
turns.csv gives such a turn its angle and no end (it ends after the last row)."""

from __future__ import annotations

import numpy as np

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.clinical import turn_summary, turn_table
from pdrlearn.track.waist import track_waist


def _session():
    return simulate_path(parse_route("straight:10, turn:180, stand:3"), UserProfile.from_seed(21), speed="slow",
                         seed=0)


def test_a_turn_on_the_spot_after_the_last_step_reaches_the_final_heading_and_turns_csv():
    s = _session()
    before = track_waist(s, pipeline="waist-pendulum", integrate_end=False)
    after = track_waist(s, pipeline="waist-pendulum", integrate_end=True)
    assert not len(turn_table(before.steps))  # the loss the trial saw
    table = turn_table(after.steps)
    assert len(table) == 1 and abs(abs(table["angle_deg"].iloc[0]) - 180.0) < 30.0
    assert np.isnan(table["end_s"].iloc[0]) and np.isnan(table["duration_s"].iloc[0])  # L205: its end is unknown
    summary = turn_summary(table)
    assert summary["turn_time_s"] is None and summary["median_turn_duration_s"] is None
    # L205: the last interval's rate (the final stop's rotation over one step's time) is no peak rate
    assert np.isnan(table["peak_rate_dps"].iloc[0]) and summary["median_turn_peak_rate_dps"] is None
    assert abs(summary["median_turn_angle_deg"] - abs(table["angle_deg"].iloc[0])) < 1e-9
    assert abs(abs(after.steps["heading_rad"].iloc[-1]) - np.pi) < np.radians(30.0)
    np.testing.assert_array_equal(after.steps["length_m"], before.steps["length_m"])  # positions do not move
    np.testing.assert_array_equal(after.steps["heading_rad"].iloc[:-1], before.steps["heading_rad"].iloc[:-1])


def test_the_realtime_track_does_not_integrate_the_final_stop():
    """W187: offline only - `run` of a waist bundle streams and is pinned to ``track_waist(realtime=True)``."""
    s = _session()
    on = track_waist(s, pipeline="waist-pendulum", realtime=True, integrate_end=True)
    off = track_waist(s, pipeline="waist-pendulum", realtime=True, integrate_end=False)
    np.testing.assert_array_equal(on.steps["heading_rad"], off.steps["heading_rad"])


def test_a_lone_contact_inside_the_final_turn_keeps_the_rotation_before_it():
    """W187 after its measurement: user 3641's walk ends with a lone contact found inside the turn (the last step at
    18.14 s, a contact at 21.21 s); the final heading takes the whole turn, not only the rotation after that contact."""
    s = simulate_path(parse_route("straight:10, turn:180, stand:3"), UserProfile.from_seed(3641), speed="slow",
                      seed=3641, rate_hz=100.0)
    res = track_waist(s, pipeline="waist-pendulum", integrate_end=True, stand_veto=False)  # "adjacent" drops it
    has_next = res.steps["has_next"].to_numpy(bool)
    assert not has_next[-1] and not has_next[-2]  # a lone contact after the walk's closing contact
    assert abs(abs(res.steps["heading_rad"].iloc[-1]) - np.pi) < np.radians(30.0)
    # W198's stand veto (W199's default, withdrawn by W217) drops the lone contact (a weak run of one, walking before
    # it only); the walk's last step still takes the whole turn (W187)
    dflt = track_waist(s, pipeline="waist-pendulum", integrate_end=True, stand_veto="adjacent")
    assert dflt.info["n_weak_run_contacts"] == 1 and len(dflt.steps) == len(res.steps) - 1
    assert abs(abs(dflt.steps["heading_rad"].iloc[-1]) - np.pi) < np.radians(30.0)
