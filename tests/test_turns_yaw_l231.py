"""Decisions L231-L236 (session 29): a lower-back turn's angle takes the whole turns its yaw rate shows (L231,
adopted L232), a yaw-rate turn no step-heading turn overlaps is a row of its own (L233, an option: L234), and a
yaw-timed turn's peak rate is its yaw-rate turn's low-passed peak (L235, adopted L236)."""

from __future__ import annotations

import inspect

import numpy as np
import pandas as pd
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.clinical import turn_table

KEYS = ("start_s", "end_s", "peak_s", "angle_deg", "peak_dps")


def _yaw(*rows):
    return [dict(zip(KEYS, r, strict=True)) for r in rows]


def _table(change_deg: float):
    """A lower-back step table whose turn on the spot fell between two contacts (6.0 s and 9.6 s): the wrapped
    heading changes by ``change_deg`` there (user 3901's waist-pendulum read +181.8 deg as -178.2 deg)."""
    t = np.r_[np.arange(0, 6.01, 0.6), 9.6 + np.arange(0, 6.01, 0.6)]
    h = np.where(t > 9, np.radians(change_deg), 0.0)
    return pd.DataFrame({"start_s": t, "end_s": np.r_[t[1:], t[-1] + 0.6], "heading_rad": np.angle(np.exp(1j * h)),
                         "length_m": 0.4, "unit": "waist"})


def _default(name: str):
    """The default of ``turn_table``'s keyword ``name`` (decision L594: the decisions' values, no module switch)."""
    return inspect.signature(turn_table).parameters[name].default


def test_a_turn_between_two_contacts_takes_its_yaw_rate_branch():
    st, yaw = _table(181.8), _yaw((6.3, 9.0, 7.6, 180.0, 101.0))
    assert _default("branch") is True  # L232
    tt = turn_table(st, yaw_turns=yaw, yaw_angle=False)  # W328 off: L231's step-heading angle
    assert len(tt) == 1 and tt.loc[0, "angle_deg"] == pytest.approx(181.8)
    assert tt.loc[0, ["start_s", "end_s"]].tolist() == pytest.approx([6.3, 9.0])  # L210: timed by it
    # L211's reading (the option branch=False): the nearest branch, -178.2 deg, unmatched, L208's late times
    old = turn_table(st, yaw_turns=yaw, branch=False)
    assert old.loc[0, "angle_deg"] == pytest.approx(-178.2) and old.loc[0, "start_s"] > 9.5
    # a 360 deg turn wraps to ~0: no step-heading turn to resolve (L233's case; L255's row, whole=False without it); a
    # same-sign match has no shift
    assert turn_table(_table(360.0), yaw_turns=_yaw((6.3, 9.0, 7.6, 360.0, 120.0)), whole=False).empty
    same = turn_table(_table(90.0), yaw_turns=_yaw((6.3, 9.0, 7.6, 95.0, 60.0)), yaw_angle=False)
    assert same.loc[0, "angle_deg"] == pytest.approx(90.0)
    # a shift can bring a small step-heading turn over min_deg: -60 deg read for +300 deg
    assert turn_table(_table(300.0), yaw_turns=[], branch=False, min_deg=45).loc[0, "angle_deg"] == pytest.approx(-60)
    assert turn_table(_table(300.0), yaw_turns=[], branch=False).empty
    big = turn_table(_table(300.0), yaw_turns=_yaw((6.3, 9.0, 7.6, 298.0, 120.0)), yaw_angle=False)
    assert len(big) == 1 and big.loc[0, "angle_deg"] == pytest.approx(300.0)
    # foot tables and tables without yaw-rate turns do not change
    pd.testing.assert_frame_equal(turn_table(st), turn_table(st, timing="heading"))


def test_yaw_only_turns_are_an_option():
    st = _table(0.0)  # the steps saw no turn
    yaw = _yaw((6.3, 10.3, 8.0, 360.3, 102.0), (12.0, 13.0, 12.5, 60.0, 70.0))
    assert _default("yaw_only") is False  # L234: not adopted
    assert turn_table(st, yaw_turns=yaw, whole=False).empty  # (L256 counts this 360 deg turn by default)
    bouts = pd.DataFrame({"bout": [1, 2], "start_s": [0.0, 7.0], "end_s": [6.5, 16.0]})
    tt = turn_table(st, bouts, yaw_turns=yaw, yaw_only=True)
    assert len(tt) == 1  # 60 deg is under min_deg (80, L200)
    row = tt.iloc[0]
    assert (row.start_s, row.end_s, row.angle_deg, row.peak_rate_dps, row.n_rows, row.bout) == pytest.approx(
        (6.3, 10.3, 360.3, 102.0, 0, 2))
    assert row.mean_rate_dps == pytest.approx(360.3 / 4.0) and row.turn == 1
    # a yaw-rate turn overlapping a counted turn's rows is that turn's timing, not a second row; rows in time order
    st2 = _table(90.0)
    yaw2 = _yaw((1.0, 2.5, 1.8, -100.0, 80.0), (6.3, 9.0, 7.6, 92.0, 60.0))
    tt2 = turn_table(st2, yaw_turns=yaw2, yaw_only=True, yaw_angle=False)
    assert tt2["angle_deg"].tolist() == pytest.approx([-100.0, 90.0]) and tt2["turn"].tolist() == [1, 2]
    assert tt2["n_rows"].tolist() == [0, 1]


def test_a_yaw_timed_turn_peaks_at_its_yaw_rate_peak():
    st, yaw = _table(90.0), _yaw((6.3, 9.0, 7.6, 92.0, 61.5))
    assert _default("yaw_peak") is True  # L236
    assert turn_table(st, yaw_turns=yaw).loc[0, "peak_rate_dps"] == pytest.approx(61.5)
    # L229's reading: one row-to-row interval holds the turn and the stand, 90 deg / 3.6 s
    assert turn_table(st, yaw_turns=yaw, yaw_peak=False).loc[0, "peak_rate_dps"] == pytest.approx(90.0 / 3.6)
    # the kernel's peak: the filtered rate the detector found the turn on
    from pdrlearn.kernels.yaw_turns import lowpassed_yaw_rate, yaw_rate_turns

    fs = 100.0
    t = np.arange(0, 20, 1 / fs)
    x = (t - 8.0) / 2.0
    w = np.where((x >= 0) & (x <= 1), 90.0 * (1 - np.cos(2 * np.pi * x)), 0.0)  # 180 deg in 2 s, peak 180 deg/s
    row = yaw_rate_turns(w, fs)[0]
    f = np.abs(lowpassed_yaw_rate(w, fs))
    assert f[int(row[2])] == pytest.approx(f.max()) and 60.0 < f.max() < 180.0


def test_a_slow_tug_turn_reads_its_sign_angle_and_peak():
    """L232 / L236 on a spent L211 user (3901: slow 0.35 m / 0.58 s, TUG, 100 Hz, pendulum bounce): L211 read the
    +180 deg turn -178.2 deg with a 59 deg/s peak (true peak ~100 deg/s)."""
    from pdrlearn.cli.simulate import _custom_gait
    from pdrlearn.track.evaluate import track_summary
    from pdrlearn.track.waist import track_waist

    route = "straight:3, turn:180, straight:3"
    user = _custom_gait(UserProfile.from_seed(3901), "slow", 0.35, 0.58, route)
    s = simulate_path(parse_route(route), user, speed="slow", rate_hz=100.0, seed=3901, sit_start_s=5.0,
                      sit_end_s=5.0, bounce="pendulum")
    res = track_waist(s, pipeline="waist-pendulum")
    yaw = res.info["yaw_turns"]
    tt = turn_table(res.steps, yaw_turns=yaw)
    assert len(tt) == 1 and tt.loc[0, "angle_deg"] == pytest.approx(180.0, abs=5.0)
    assert 85.0 <= tt.loc[0, "peak_rate_dps"] <= 115.0
    assert turn_table(res.steps, yaw_turns=yaw, branch=False).loc[0, "angle_deg"] < -170.0  # L211's reading
    # L229's peak of the matched turn: one contact-to-contact interval holds the turn and the stand (~59 deg/s)
    assert turn_table(res.steps, yaw_turns=yaw, yaw_peak=False).loc[0, "peak_rate_dps"] < 70.0
    summary = track_summary(res, s)
    assert summary["turn_count"] == len(tt) and summary["median_turn_peak_rate_dps"] == pytest.approx(
        tt.loc[0, "peak_rate_dps"])
