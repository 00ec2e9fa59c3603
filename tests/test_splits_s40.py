"""Decisions L552-L554 (session 40, fixer FN, trial T3 finding 9, a load-carriage march): no automatic 10 m walk or
T25FW on a bout far longer than a walkway (L552); ``--splits every:STEP`` with the final partial split (L553); each
split's pace in min/km (L554)."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.columns import undocumented
from pdrlearn.errors import DataError
from pdrlearn.track.splits import EverySplit, parse_splits, split_table
from pdrlearn.track.walk_test import WALKWAY_BOUT_MAX_M, t25fw, ten_metre_walk, ten_metre_walk_trials


def _strides(lengths, start=10.0, swing_s=0.4, stance_s=0.6):
    """A straight foot walk: each stride lifts at its start_s, lands (event_s) swing_s later, rests stance_s."""
    n = len(lengths)
    s = start + np.arange(n) * (swing_s + stance_s)
    return pd.DataFrame({"start_s": s, "end_s": s + swing_s + stance_s, "event_s": s + swing_s,
                         "length_m": np.asarray(lengths, float), "heading_rad": 0.0, "unit": "foot"})


def test_every_step_marks_each_step_and_the_final_partial_split_l553_l554():
    """L553: 2 m strides to 13.3 m with every:5 -> 5, 10 and the path's end 13.3 m; L554: pace = minutes / km."""
    assert parse_splits("every:5") == EverySplit(5.0) and parse_splits(" Every:1000 ") == EverySplit(1000.0)
    table, keys, lines = split_table(_strides([2.0] * 6 + [1.3]), parse_splits("every:5"))
    assert lines == [] and table["distance_m"].tolist() == [5.0, 10.0, 13.3]
    assert keys["splits_m"] == [5.0, 10.0, 13.3] and keys["split_times_s"] == pytest.approx([2.2, 4.4, 6.4])
    assert table["pace_min_per_km"].tolist() == pytest.approx([2.2 / 60 / 0.005, 2.2 / 60 / 0.005, 2.0 / 60 / 0.0033])
    exact, _, _ = split_table(_strides([2.0] * 5), EverySplit(5.0))  # a path ending on a mark: no extra row
    assert exact["distance_m"].tolist() == [5.0, 10.0]
    short, _, _ = split_table(_strides([2.0] * 2), EverySplit(5.0))  # shorter than one step: the end alone
    assert short["distance_m"].tolist() == [4.0]


@pytest.mark.parametrize("text", ["every:", "every:x", "every:0", "every:-5", "every:nan", "every:5,10"])
def test_bad_step_is_one_line_l553(text):
    with pytest.raises(DataError, match="--splits") as err:
        parse_splits(text)
    assert "\n" not in str(err.value) and "every:1000" in str(err.value)


def test_a_bout_far_longer_than_a_walkway_is_not_timed_unless_declared_l552():
    """L552: a 150 m straight bout gets no automatic 10 m walk, trial or T25FW (a note says why); --ten-m-walk's
    walkway (or walkway=True) times it; a 20 m walkway bout after the march is still timed automatically."""
    march = _strides([1.5] * 100)
    assert march["length_m"].sum() > WALKWAY_BOUT_MAX_M
    auto = ten_metre_walk(march)
    assert auto["ten_m_walk_time_s"] is None and "decision L552" in auto["ten_m_walk_note"]
    assert auto["n_ten_m_walk_trials"] == 0 and len(ten_metre_walk_trials(march)) == 0
    assert t25fw(march)["t25fw_time_s"] is None and "L552" in t25fw(march)["t25fw_note"]
    assert ten_metre_walk(march, (2.0, 10.0, 2.0))["ten_m_walk_time_s"] == pytest.approx(10 / 1.5)
    assert t25fw(march, walkway=True)["t25fw_time_s"] is not None
    walkway = _strides([1.0] * 20, start=float(march["end_s"].iloc[-1]) + 30.0)  # a pause, then a 20 m walk
    both = ten_metre_walk(pd.concat([march, walkway], ignore_index=True))
    assert both["ten_m_walk_time_s"] == pytest.approx(10.0) and "walking bout 1 before it" in both["ten_m_walk_note"]


def test_track_a_long_walk_every_split_and_no_walk_test_line(tmp_path, capsys):
    """L552-L554 end to end: a simulated 230 m walk (user 11060) with --splits every:100: rows at 100, 200 m and the
    path's end, a pace column documented, and no 10 m walk or T25FW line in the console."""
    ses = tmp_path / "walk"
    assert main(["simulate", "--route", "stand:2, straight:230, stand:2", "--user-seed", "11060",
                 "--out", str(ses)]) == 0
    out = tmp_path / "track"
    capsys.readouterr()
    assert main(["track", str(ses), "--splits", "every:100", "--no-plot", "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    table = pd.read_csv(out / "splits.csv")
    print(table.to_string())
    assert table["distance_m"].tolist()[:2] == [100.0, 200.0] and len(table) == 3
    assert 200.0 < table["distance_m"].iloc[2] < 260.0
    assert np.all(table["pace_min_per_km"].between(5.0, 30.0)) and not undocumented("splits.csv", table.columns)
    summary = json.loads((out / "summary.json").read_text())
    assert summary["ten_m_walk_time_s"] is None and "L552" in summary["ten_m_walk_note"]
    assert summary["t25fw_time_s"] is None
    assert "10 m walk test" not in printed and "timed 25-foot walk" not in printed
    assert "splits from the first step: 100 m" in printed
