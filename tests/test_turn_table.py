"""Decisions L200, L202: turns.csv (each turn's start, end, duration, signed angle, peak rate, bout) and its summary
keys, on a hand-made step table and a simulated TUG tracked by the command line (foot: no transfers.csv)."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.columns import TURNS, undocumented
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.clinical import TURN_SUMMARY_KEYS, TURN_TABLE_COLUMNS, turn_rows, turn_summary, turn_table, turns


def _table(dh_deg, dt=1.0):
    """A foot-like step table: one row a stride every ``dt`` s, each row's own turn ``dh_deg`` (row 0 turns 0)."""
    dh = np.radians(np.r_[0.0, dh_deg])
    t = dt * np.arange(dh.size)
    return pd.DataFrame({"start_s": t, "end_s": t + 0.8 * dt, "heading_rad": np.cumsum(dh), "length_m": 1.0,
                         "unit": "foot", "turn_angle_rad": dh})


def test_one_row_per_counted_turn_with_its_rows_times():
    # straight, a left 180 over rows 4-6 (60 deg each), straight, a right 90 over rows 11-12, a 40 deg turn (not
    # counted: under turn_count_min_deg), straight
    dh = [0, 0, 0, 60, 60, 60, 0, 0, 0, 0, -45, -45, 0, 0, 0, 40, 0, 0]
    st = _table(dh)
    tt = turn_table(st)
    assert list(tt.columns) == list(TURN_TABLE_COLUMNS)
    angles, first = turn_rows(st)
    assert len(tt) == int((np.abs(angles) >= 80).sum()) == 2  # exactly turn_count's turns
    assert tt["angle_deg"].tolist() == pytest.approx([180.0, -90.0])
    assert tt["angle_deg"].tolist() == pytest.approx([a for a in turns(st) if abs(a) >= 80])
    # the left turn sums rows 4-6: from row 4's start (4 s) to row 6's end (6.8 s)
    assert tt.loc[0, ["start_s", "end_s", "duration_s"]].tolist() == pytest.approx([4.0, 6.8, 2.8])
    assert tt.loc[1, ["start_s", "end_s"]].tolist() == pytest.approx([11.0, 12.8])
    assert tt["peak_rate_dps"].tolist() == pytest.approx([60.0, 45.0])
    assert tt["n_rows"].tolist() == [3, 2]
    assert tt["bout"].isna().all()  # no bouts table given
    s = turn_summary(tt)
    assert set(s) == set(TURN_SUMMARY_KEYS)
    assert s["median_turn_duration_s"] == pytest.approx(np.median([2.8, 1.8]))
    assert s["median_turn_angle_deg"] == pytest.approx(135.0) and s["turn_time_s"] == pytest.approx(4.6)


def test_bout_column_names_the_bouts_row_and_no_turn_gives_none():
    st = _table([0, 0, 60, 60, 60, 0, 0])
    bouts = pd.DataFrame({"bout": [1, 2], "start_s": [0.0, 10.0], "end_s": [5.0, 20.0]})
    assert turn_table(st, bouts)["bout"].tolist() == [1]
    assert turn_table(st, bouts.iloc[1:])["bout"].isna().all()  # outside every bout: empty
    straight = _table([0, 0, 0, 0])
    assert turn_table(straight).empty and list(turn_table(straight).columns) == list(TURN_TABLE_COLUMNS)
    assert turn_summary(turn_table(straight)) == dict.fromkeys(TURN_SUMMARY_KEYS)
    assert turn_table(straight.iloc[:1]).empty


@pytest.fixture(scope="module")
def tug(tmp_path_factory):
    """A seated-start, seated-end TUG with a 180 deg turn (user 3531, slow; L201's measurement user)."""
    d = tmp_path_factory.mktemp("tug") / "tug"
    s = simulate_path(parse_route("straight:3, turn:180, straight:3"), UserProfile.from_seed(3531), speed="slow",
                      seed=3531, sit_start_s=5.0, sit_end_s=5.0)
    write_session(s, d)
    return d


def test_track_writes_turns_and_foot_has_no_transfers(tug, tmp_path, capsys):
    out = tmp_path / "foot"
    assert main(["track", str(tug), "--pipeline", "plasys", "--out", str(out)]) == 0
    assert "turns.csv" in capsys.readouterr().out
    tt = pd.read_csv(out / "turns.csv")
    assert undocumented("turns.csv", tt.columns) == [] and [c[0] for c in TURNS] == list(tt.columns)
    assert len(tt) == 1 and tt["angle_deg"].iloc[0] == pytest.approx(180.0, abs=5.0)
    assert tt["bout"].iloc[0] == 1
    # the true turn (the waist unit's heading, 5 % to 95 % of the change) runs 17.10-19.45 s for this user
    assert tt["start_s"].iloc[0] <= 17.10 + 0.5 and tt["end_s"].iloc[0] >= 19.45 - 0.5
    summary = json.loads((out / "summary.json").read_text())
    assert summary["median_turn_duration_s"] == pytest.approx(tt["duration_s"].iloc[0])
    assert summary["turn_count"] == len(tt)
    assert not (out / "transfers.csv").exists()  # L202: a foot unit does not see the trunk
    assert all(summary[k] is None for k in ("n_sit_to_stand", "n_stand_to_sit", "tug_time_s"))
    streamed = tmp_path / "stream"
    assert main(["track", str(tug), "--pipeline", "plasys", "--streaming", "--out", str(streamed)]) == 0
    st = pd.read_csv(streamed / "turns.csv")
    assert len(st) == 1 and st["angle_deg"].iloc[0] == pytest.approx(180.0, abs=5.0)


def test_run_writes_turns_csv_as_track_streaming(tug, tmp_path):
    """L202: ``pdrlearn run`` (the streamed bundle) writes track's turns.csv beside bouts.csv."""
    from tests.test_run_gait_summary import BUNDLE

    assert main(["run", str(BUNDLE), str(tug), "--out", str(tmp_path / "r")]) == 0
    tt = pd.read_csv(tmp_path / "r" / "turns.csv")
    assert [c[0] for c in TURNS] == list(tt.columns)
    assert len(tt) == 1 and tt["angle_deg"].iloc[0] == pytest.approx(180.0, abs=5.0)
    summary = json.loads((tmp_path / "r" / "summary.json").read_text())
    assert summary["median_turn_duration_s"] == pytest.approx(tt["duration_s"].iloc[0])
    assert not (tmp_path / "r" / "transfers.csv").exists()
