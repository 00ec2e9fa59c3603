"""Decision L622 (session 44, helper I2): a turn the pelvis made seated or in a ride (W488's ``carried`` yaw-rate
turn) stays in turns.csv, marked ``carried``, and is left out of ``turn_count``, the turn medians and periods.csv's
``n_turns``. Simulated user 12130 (seed = user): a 90 deg seat swivel spliced into the lower back's yaw rate while
seated (the simulator's vehicle S-bend turns 15-45 deg, under turn_count's 80)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pandas as pd
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.clinical import TURN_TABLE_COLUMNS, turn_table, walked_turns


def _swivel(session, a: float, b: float, deg: float = 90.0):
    """``session`` with a ``deg`` turn of the lower back's yaw rate (the simulator's waist frame: y up) from ``a`` to
    ``b`` s, a (1 - cos) rate bump."""
    g = session["wGyroscope"]
    v = g.values.copy()
    m = (g.t > a) & (g.t < b)
    v[m, 1] += np.radians(deg) / (b - a) * (1 - np.cos(2 * np.pi * (g.t[m] - a) / (b - a)))
    return dataclasses.replace(session, streams={**session.streams, "wGyroscope": dataclasses.replace(g, values=v)})


@pytest.fixture(scope="module")
def seated_turn():
    s = simulate_path(parse_route("stand:3, straight:12, sit:40, straight:12, stand:3"), UserProfile.from_seed(12130),
                      rate_hz=100.0, seed=12130)
    tr = s.extras["transfers"]
    mid = 0.5 * (float(tr["seated_s"].iloc[0]) + float(tr["rise_s"].iloc[0]))
    return _swivel(s, mid - 4.0, mid + 4.0), mid


def test_a_seated_turn_is_marked_and_not_counted_l622(seated_turn):
    """The swivel is a turns.csv row marked carried (before: unmarked) and turn_count is 0 (before: 1)."""
    from pdrlearn.track.evaluate import track_summary
    from pdrlearn.track.waist import track_waist

    s, mid = seated_turn
    r = track_waist(s, pipeline="waist-pendulum")
    table = turn_table(r)
    assert list(table.columns) == list(TURN_TABLE_COLUMNS)
    seat = table[(table["start_s"] < mid) & (table["end_s"] > mid)]
    assert len(seat) == 1 and bool(seat["carried"].iloc[0]) and abs(float(seat["angle_deg"].iloc[0])) >= 80
    m = track_summary(r, s, pipeline="waist-pendulum")
    assert m["turn_count"] == int((~table["carried"]).sum()) == len(table) - 1


def test_only_carried_yaw_turns_mark_their_rows_l622():
    """turn_table's ``carried`` follows the yaw-rate turn that times a row: a lower-back walk turning 90 deg, its
    yaw-rate turn marked or not; walked_turns keeps the unmarked rows only; a foot table has none marked."""
    t = np.arange(0.0, 12.0, 0.5)
    heading = np.where(t < 6.0, 0.0, np.pi / 2)
    steps = pd.DataFrame({"start_s": t, "end_s": t + 0.5, "event_s": t, "heading_rad": heading,
                          "length_m": 0.7, "unit": "waist"})
    yaw = {"start_s": 5.0, "end_s": 7.0, "peak_s": 6.0, "angle_deg": 90.0, "peak_dps": 60.0, "start_5_s": 5.2,
           "end_95_s": 6.8}
    plain = turn_table(steps, yaw_turns=[yaw])
    marked = turn_table(steps, yaw_turns=[{**yaw, "carried": True}])
    assert len(plain) == len(marked) == 1
    assert not plain["carried"].any() and marked["carried"].all()
    assert len(walked_turns(plain)) == 1 and len(walked_turns(marked)) == 0
    assert not turn_table(steps.drop(columns="unit"))["carried"].any()


def test_the_written_files_keep_the_turn_marked_l622(seated_turn, tmp_path):
    """`track --units waist --per 20s`: turns.csv keeps the swivel with carried true; periods.csv's n_turns (which
    sums to turn_count) and summary.json's turn_count leave it out."""
    import json

    from pdrlearn.cli import main
    from pdrlearn.io import write_session

    s, mid = seated_turn
    write_session(s, tmp_path / "s")
    assert main(["track", str(tmp_path / "s"), "--units", "waist", "--per", "20s", "--no-plot",
                 "--out", str(tmp_path / "o")]) == 0
    turns = pd.read_csv(tmp_path / "o" / "turns.csv")
    seat = turns[(turns["start_s"] < mid) & (turns["end_s"] > mid)]
    assert len(seat) == 1 and seat["carried"].astype(str).str.lower().tolist() == ["true"]
    periods = pd.read_csv(tmp_path / "o" / "periods.csv")
    summary = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert int(periods["n_turns"].sum()) == summary["turn_count"] == len(turns) - 1
