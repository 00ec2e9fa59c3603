"""Decisions L200, L202, L208, L209: turns.csv (each turn's start, end, duration, signed angle, peak and mean rate,
bout) and its summary keys, on a hand-made step table and a simulated TUG tracked by the command line (foot: no
transfers.csv); the turn timed by its heading (5 % to 95 % of the angle, the default) or by its rows (L200)."""

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
from pdrlearn.track.clinical import (
    TURN_SUMMARY_KEYS,
    TURN_TABLE_COLUMNS,
    TURN_TIMING,
    heading_crossings,
    spread_peak_rate,
    turn_rows,
    turn_summary,
    turn_table,
    turns,
)
from pdrlearn.track.clock import CLOCK_COLUMNS


def _unclocked(table):
    """The table's columns without L298's clock columns (a simulated session gives no start)."""
    return [c[0] for c in table if c[0] not in CLOCK_COLUMNS.values()]


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
    tt = turn_table(st, timing="rows")  # L200's timing (an option since L209)
    assert list(tt.columns) == list(TURN_TABLE_COLUMNS)
    angles, first = turn_rows(st)
    assert len(tt) == int((np.abs(angles) >= 80).sum()) == 2  # exactly turn_count's turns
    assert tt["angle_deg"].tolist() == pytest.approx([180.0, -90.0])
    assert tt["angle_deg"].tolist() == pytest.approx([a for a in turns(st) if abs(a) >= 80])
    # the left turn sums rows 4-6: from row 4's start (4 s) to row 6's end (6.8 s)
    assert tt.loc[0, ["start_s", "end_s", "duration_s"]].tolist() == pytest.approx([4.0, 6.8, 2.8])
    assert tt.loc[1, ["start_s", "end_s"]].tolist() == pytest.approx([11.0, 12.8])
    # decision L229: each row's change over its own 0.8 s span (L200's row-to-row 60 / 45 deg/s over 1 s before)
    assert tt["peak_rate_dps"].tolist() == pytest.approx([75.0, 56.25])
    assert tt["n_rows"].tolist() == [3, 2]
    assert tt["bout"].isna().all()  # no bouts table given
    s = turn_summary(tt)
    assert set(s) == set(TURN_SUMMARY_KEYS)
    assert s["median_turn_duration_s"] == pytest.approx(np.median([2.8, 1.8]))
    assert s["median_turn_angle_deg"] == pytest.approx(135.0) and s["turn_time_s"] == pytest.approx(4.6)
    # the whole angle over the rows' span: 180 / 2.8 and 90 / 1.8 deg/s
    assert tt["mean_rate_dps"].tolist() == pytest.approx([180 / 2.8, 90 / 1.8])
    assert s["median_turn_mean_rate_dps"] == pytest.approx(np.median([180 / 2.8, 50.0]))


def test_heading_timing_is_the_default_and_moves_only_the_times():
    """L208 / L209: the turn starts where its heading, each row's change spread over the row's span, has gone 5 % of
    the angle and ends at 95 %; angles, counts, peak rates, rows and bouts are the rows timing's."""
    assert TURN_TIMING == "heading"
    st = _table([0, 0, 0, 60, 60, 60, 0, 0, 0, 0, -45, -45, 0, 0, 0, 40, 0, 0])
    tt, rows = turn_table(st), turn_table(st, timing="rows")
    # 180 deg over rows 4-6 (each 0.8 s): 9 deg 0.12 s into row 4, 171 deg 0.68 s into row 6
    assert tt.loc[0, ["start_s", "end_s", "duration_s"]].tolist() == pytest.approx([4.12, 6.68, 2.56])
    assert tt.loc[1, ["start_s", "end_s"]].tolist() == pytest.approx([11.08, 12.72])  # -90 over rows 11-12
    # the heading turns 90 % of the angle between the two times
    assert tt["mean_rate_dps"].tolist() == pytest.approx([0.9 * 180 / 2.56, 0.9 * 90 / 1.64])
    same = ["turn", "angle_deg", "peak_rate_dps", "n_rows"]
    pd.testing.assert_frame_equal(tt[same], rows[same])
    assert (tt["duration_s"] < rows["duration_s"]).all()
    with pytest.raises(ValueError, match="timing"):
        turn_table(st, timing="steps")


def test_heading_crossings_spread_and_instant_changes():
    # a right 90 over 2 s: 5 % at 0.1 s, 95 % at 1.9 s
    assert heading_crossings([-90.0], [0.0], [2.0], -90.0) == pytest.approx((0.1, 1.9))
    # 10 deg over [0, 1] s then 170 deg at once at 1 s (a row without a span): 9 deg at 0.9 s, 171 deg at 1 s
    assert heading_crossings([10.0, 170.0], [0.0, 1.0], [1.0, 1.0], 180.0) == pytest.approx((0.9, 1.0))
    # overlapping spans add: 100 deg over [0, 2] and 100 deg over [1, 3]; 10 deg at 0.2 s, 190 deg at 2.8 s
    assert heading_crossings([100.0, 100.0], [0.0, 1.0], [2.0, 3.0], 200.0) == pytest.approx((0.2, 2.8))
    # a slower opposite row inside the turn: the first crossing counts
    assert heading_crossings([60.0, -10.0, 50.0], [0.0, 1.0, 2.0], [1.0, 2.0, 3.0], 100.0) == pytest.approx(
        (5 / 60, 2.0 + 45 / 50))


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
    assert main(["track", "--no-plot", str(tug), "--pipeline", "plasys", "--out", str(out)]) == 0
    assert "turns.csv" in capsys.readouterr().out
    tt = pd.read_csv(out / "turns.csv")
    assert undocumented("turns.csv", tt.columns) == [] and _unclocked(TURNS) == list(tt.columns)
    assert len(tt) == 1 and tt["angle_deg"].iloc[0] == pytest.approx(180.0, abs=5.0)
    assert tt["bout"].iloc[0] == 1
    # the true turn (the waist unit's heading, 5 % to 95 % of the change) runs 17.10-19.45 s for this user; L209:
    # the heading timing is within 0.5 s of both ends, the rows' timing (L200) reads the turn over 1.5 s longer
    assert tt["start_s"].iloc[0] == pytest.approx(17.10, abs=0.5) and tt["end_s"].iloc[0] == pytest.approx(19.45,
                                                                                                         abs=0.5)
    by_rows = turn_table(pd.read_csv(out / "steps.csv"), timing="rows")
    assert by_rows["duration_s"].iloc[0] > (19.45 - 17.10) + 1.5
    assert tt["mean_rate_dps"].iloc[0] == pytest.approx(0.9 * abs(tt["angle_deg"].iloc[0]) / tt["duration_s"].iloc[0])
    summary = json.loads((out / "summary.json").read_text())
    assert summary["median_turn_duration_s"] == pytest.approx(tt["duration_s"].iloc[0])
    assert summary["turn_count"] == len(tt)
    # L202: a foot unit does not see the trunk; W418: the two-unit track reads the waist unit's chair transfers
    assert (out / "transfers.csv").exists() and summary["tug_steps_source"] == "foot"
    assert all(summary[k] is not None for k in ("n_sit_to_stand", "n_stand_to_sit"))
    streamed = tmp_path / "stream"
    assert main(["track", "--no-plot", str(tug), "--pipeline", "plasys", "--streaming", "--out", str(streamed)]) == 0
    st = pd.read_csv(streamed / "turns.csv")
    assert len(st) == 1 and st["angle_deg"].iloc[0] == pytest.approx(180.0, abs=5.0)


def test_run_writes_turns_csv_as_track_streaming(tug, tmp_path):
    """L202: ``pdrlearn run`` (the streamed bundle) writes track's turns.csv beside bouts.csv."""
    from tests.test_run_gait_summary import BUNDLE

    assert main(["run", "--no-plot", str(BUNDLE), str(tug), "--out", str(tmp_path / "r")]) == 0
    tt = pd.read_csv(tmp_path / "r" / "turns.csv")
    assert _unclocked(TURNS) == list(tt.columns)
    assert len(tt) == 1 and tt["angle_deg"].iloc[0] == pytest.approx(180.0, abs=5.0)
    summary = json.loads((tmp_path / "r" / "summary.json").read_text())
    assert summary["median_turn_duration_s"] == pytest.approx(tt["duration_s"].iloc[0])
    assert not (tmp_path / "r" / "transfers.csv").exists()


def test_the_peak_rate_is_the_spread_headings_and_never_below_the_mean():
    """Decision L229 (trial tour finding 2): a slow turn on the spot after a stand - its first turning stride's row
    starts 2.5 s after the last straight one - read a row-to-row peak (L200) below the 5-95 % mean rate (L208)."""
    start = np.array([0.0, 1.3, 2.6, 3.9, 6.4, 7.75, 9.2, 10.5, 11.8])
    end = np.r_[start[1:], 13.1]
    end[3] = 5.3  # the stand before the turn: no row
    dh = np.radians([0.0, 0.0, 0.0, 0.0, 120.0, 60.0, 0.0, 0.0, 0.0])
    st = pd.DataFrame({"start_s": start, "end_s": end, "heading_rad": np.cumsum(dh), "length_m": 1.0,
                       "unit": "foot", "turn_angle_rad": dh})
    tt = turn_table(st)
    assert len(tt) == 1 and tt.loc[0, "angle_deg"] == pytest.approx(180.0)
    assert tt.loc[0, "peak_rate_dps"] == pytest.approx(120.0 / 1.35)  # row 4's change over its own span
    assert tt.loc[0, "peak_rate_dps"] >= tt.loc[0, "mean_rate_dps"]
    assert spread_peak_rate([30.0, 30.0], [0.0, 0.5], [1.0, 1.5]) == pytest.approx(60.0)  # overlaps add up
    assert np.isnan(spread_peak_rate([30.0], [1.0], [1.0]))  # an instant has no rate
