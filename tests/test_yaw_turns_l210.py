"""Decisions L210, L211: El-Gohary's turns of the pelvis yaw rate (mobgap TdElGohary's defaults) and turns.csv's
lower-back turns re-timed by them (same turns, angles and counts; a turn without a yaw-rate match keeps L208's
heading timing)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.kernels.yaw_turns import yaw_rate_turns
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.clinical import turn_table

FS = 100.0


def _bump(t, t0, dur, angle):
    """A raised-cosine yaw rate (deg/s) turning ``angle`` deg from ``t0`` over ``dur`` s."""
    x = (t - t0) / dur
    return np.where((x >= 0) & (x <= 1), angle / dur * (1 - np.cos(2 * np.pi * x)), 0.0)


def test_el_gohary_turns_of_a_yaw_rate():
    t = np.arange(0, 40, 1 / FS)
    # a 90 deg left turn over 2 s with a 1 Hz walking sway of 10 deg/s, a 90 deg right turn over 2 s
    w = _bump(t, 8, 2, 90) - _bump(t, 25, 2, 90) + 10 * np.sin(2 * np.pi * t)
    rows = yaw_rate_turns(w, FS)
    assert rows.shape == (2, 4)
    start, end, peak = rows[:, 0] / FS, rows[:, 1] / FS, rows[:, 2] / FS
    # the 5 deg/s boundaries of the 0.5 Hz low-passed rate hold the turn, within 0.5 s of it
    assert (start <= [8.0, 25.0]).all() and (start >= [7.5, 24.5]).all()
    assert (end >= [10.0, 27.0]).all() and (end <= [10.5, 27.5]).all()
    assert peak == pytest.approx([9.0, 26.0], abs=0.05)
    assert rows[:, 3] == pytest.approx([90.0, -90.0], abs=3.5)  # the unfiltered rate integrated (sway included)


def test_el_gohary_drops_slow_long_and_small_turns():
    t = np.arange(0, 60, 1 / FS)
    assert yaw_rate_turns(_bump(t, 5, 14, 90), FS).shape == (0, 4)  # peak under 15 deg/s
    assert yaw_rate_turns(_bump(t, 5, 18, 180), FS).shape == (0, 4)  # over 10 s above 5 deg/s
    assert yaw_rate_turns(_bump(t, 5, 1, 30), FS).shape == (0, 4)  # under 45 deg
    assert yaw_rate_turns(np.zeros(10), FS).shape == (0, 4)
    assert yaw_rate_turns(np.r_[np.zeros(10), np.nan], FS).shape == (0, 4)


def _waist_table():
    """A lower-back step table whose 90 deg left turn's steps were missed: contacts every 0.6 s to 6.0 s, the next
    at 9.6 s already facing the new way (the trial's finding 1)."""
    t = np.r_[np.arange(0, 6.01, 0.6), 9.6 + np.arange(0, 6.01, 0.6)]
    h = np.where(t > 9, np.pi / 2, 0.0)
    return pd.DataFrame({"start_s": t, "end_s": np.r_[t[1:], t[-1] + 0.6], "heading_rad": h, "length_m": 0.4,
                         "unit": "waist"})


def _yaw(*rows):
    return [dict(zip(("start_s", "end_s", "peak_s", "angle_deg"), r, strict=True)) for r in rows]


def test_yaw_timing_takes_the_matching_yaw_rate_turn():
    st = _waist_table()
    head = turn_table(st, timing="heading")
    assert len(head) == 1 and head.loc[0, "angle_deg"] == pytest.approx(90.0)
    assert head.loc[0, "start_s"] > 9.5  # L208: after the turn (on the first step after it)
    # two candidates: the larger one times the turn; one peaking after the rows and one of the other sign do not
    yaw = _yaw((6.3, 8.7, 7.5, 88.0), (6.0, 6.6, 6.3, 50.0), (11.0, 12.0, 11.5, 95.0), (6.2, 8.8, 7.4, -120.0))
    # W328 off (yaw_angle=False): these pin L210 / L231's step-heading angle
    tt = turn_table(st, timing="yaw", yaw_turns=yaw, branch=False, yaw_angle=False)  # L210's same-sign match
    # decision L231 (default since L232): the -120 deg turn is admissible too, on the -270 deg branch (nearer -120
    # than +90 is), and the larger: it times the turn and gives it that branch
    l231 = turn_table(st, timing="yaw", yaw_turns=yaw, yaw_angle=False)
    assert l231.loc[0, ["start_s", "end_s", "angle_deg"]].tolist() == pytest.approx([6.2, 8.8, -270.0])
    assert tt.loc[0, ["start_s", "end_s", "duration_s"]].tolist() == pytest.approx([6.3, 8.7, 2.4])
    assert tt.loc[0, "mean_rate_dps"] == pytest.approx(90.0 / 2.4)  # the whole angle: the boundaries hold it
    same = ["turn", "angle_deg", "n_rows", "bout"]
    pd.testing.assert_frame_equal(tt[same], head[same])
    # decision L229: a yaw-timed turn kept L200's row-to-row peak (L236: the option yaw_peak=False); the
    # heading-timed one the spread heading's
    h = np.degrees(st["heading_rad"].to_numpy(float))
    l229 = turn_table(st, timing="yaw", yaw_turns=yaw, branch=False, yaw_peak=False)
    assert l229.loc[0, "peak_rate_dps"] == pytest.approx(np.max(np.abs(np.diff(h)) / np.diff(st["start_s"])))
    assert head.loc[0, "peak_rate_dps"] >= head.loc[0, "mean_rate_dps"]
    # no match: L208's times (without L231's whole turns, a yaw-rate turn of the other sign never matches)
    for none in (None, [], _yaw((11.0, 12.0, 11.5, 95.0)), _yaw((6.2, 8.8, 7.4, -120.0))):
        pd.testing.assert_frame_equal(turn_table(st, timing="yaw", yaw_turns=none, branch=False), head)
    with pytest.raises(ValueError, match="timing"):
        turn_table(st, timing="gyro")


def test_default_timing_is_yaw_with_yaw_turns_l211():
    """L211 (L210 adopted; L594: the rule, no switch): with ``yaw_turns`` the default timing is ``"yaw"``."""
    st, yaw = _waist_table(), _yaw((6.3, 8.7, 7.5, 88.0))
    pd.testing.assert_frame_equal(turn_table(st, yaw_turns=yaw), turn_table(st, timing="yaw", yaw_turns=yaw))
    # without yaw_turns (a foot track, a streamed or replayed table) nothing changes
    pd.testing.assert_frame_equal(turn_table(st), turn_table(st, timing="heading"))


def test_lower_back_track_times_a_turn_on_the_spot_from_the_yaw_rate():
    from pdrlearn.track.waist import track_waist

    route = "stand:2, straight:5, turn:90, straight:5, stand:2"
    s = simulate_path(parse_route(route), UserProfile.from_seed(7), speed="slow", rate_hz=FS, seed=7,
                      bounce="pendulum")
    tr = s.trajectory
    h = np.degrees(np.unwrap(tr["heading_rad"].to_numpy(float)))
    h = np.convolve(np.pad(h, (50, 49), mode="edge"), np.ones(100) / 100, mode="valid")  # L201's truth: 1 s mean
    frac = (h - h[0]) / (h[-1] - h[0])
    ta, tb = (float(tr["t"].to_numpy()[np.argmax(frac >= f)]) for f in (0.05, 0.95))
    res = track_waist(s, pipeline="waist-pendulum")
    yaw = res.info["yaw_turns"]
    assert len(yaw) == 1 and yaw[0]["angle_deg"] == pytest.approx(90.0, abs=10.0)
    tt = turn_table(res.steps, timing="yaw", yaw_turns=yaw)
    assert len(tt) == 1
    assert turn_table(res.steps, timing="heading").loc[0, "start_s"] > tb  # L208: placed after the true turn
    # El-Gohary's 5 deg/s boundaries hold the true 5-95 % turn, within 0.6 s at each end
    assert ta - 0.6 <= tt.loc[0, "start_s"] <= ta + 0.1 and tb - 0.1 <= tt.loc[0, "end_s"] <= tb + 0.6
    # L211: the default - the summary's turn duration is the yaw-rate turn's; its records stay out
    from pdrlearn.track.evaluate import track_summary

    summary = track_summary(res, s)
    assert summary["median_turn_duration_s"] == pytest.approx(tt.loc[0, "duration_s"])
    assert "yaw_turns" not in summary["info"]
