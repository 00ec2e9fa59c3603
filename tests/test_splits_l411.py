"""Decisions L411, B307 (session 34, trial T3 finding 8): split times at given distances along the tracked path
(``track --splits 5,10,20``): splits.csv, the summary line, a warning for marks beyond the path, one error line for
bad marks."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.columns import undocumented
from pdrlearn.errors import DataError
from pdrlearn.track.splits import SPLIT_COLUMNS, parse_splits, split_table


def _strides(lengths, start=10.0, swing_s=0.4, stance_s=0.6):
    """A foot table: each stride lifts at its start_s, lands (event_s) swing_s later, rests stance_s."""
    n = len(lengths)
    s = start + np.arange(n) * (swing_s + stance_s)
    return pd.DataFrame({"start_s": s, "end_s": s + swing_s + stance_s, "event_s": s + swing_s,
                         "length_m": np.asarray(lengths, float), "heading_rad": 0.0, "unit": "foot"})


def test_split_times_interpolate_within_the_crossing_stride():
    """L411: 2 m strides (0.4 s swing, 0.6 s rest): 5 m is crossed halfway through the third stride's swing, at
    2 s + 0.2 s from the first stride's start; 10 m at the end of the fifth stride's swing (4.4 s)."""
    table, keys, lines = split_table(_strides([2.0] * 6), [5, 10])
    assert lines == []
    assert list(table.columns) == list(SPLIT_COLUMNS)
    assert table["time_s"].tolist() == pytest.approx([2.2, 4.4])
    assert table["split_time_s"].tolist() == pytest.approx([2.2, 2.2])
    assert table["speed_mps"].tolist() == pytest.approx([5 / 2.2, 5 / 2.2])
    assert keys == {"splits_m": [5.0, 10.0], "split_times_s": pytest.approx([2.2, 4.4])}


def test_a_rest_adds_no_distance_and_marks_beyond_the_path_warn_once():
    """L411: a 3 s rest after the second stride delays the later marks by 3 s (the path does not move while
    standing); 20 and 30 m beyond the 12 m path are named in one line and have no row."""
    st = _strides([2.0] * 6)
    st.loc[2:, ["start_s", "end_s", "event_s"]] += 3.0
    table, keys, lines = split_table(st, [3, 5, 20, 30])
    assert table["time_s"].tolist() == pytest.approx([1.2, 5.2])
    assert keys["split_times_s"][2:] == [None, None]
    assert len(lines) == 1 and "20, 30 m" in lines[0] and "12.00 m" in lines[0]


@pytest.mark.parametrize("text", ["5,x", "0,10", "-5", "10,5", "5,5", "nan", "5,,10", ""])
def test_bad_marks_are_one_line_b307(text):
    with pytest.raises(DataError, match="--splits") as err:
        parse_splits(text)
    assert "\n" not in str(err.value) and "e.g. --splits 5,10,20" in str(err.value)


def test_track_splits_writes_splits_csv_and_summary_line(tmp_path, capsys):
    """L411 end to end: a simulated 12 m walk (user 7940) tracked with --splits 5,10,50: two rows, the line, and 50 m
    named beyond the path; the columns documented (C35); a bad --splits exits 2 before any folder is made (B307)."""
    ses = tmp_path / "walk"
    assert main(["simulate", "--route", "straight:12", "--user-seed", "7940", "--out", str(ses)]) == 0
    out = tmp_path / "track"
    capsys.readouterr()
    assert main(["track", "--no-plot", str(ses), "--splits", "5,10,50", "--out", str(out)]) == 0
    printed = capsys.readouterr()
    table = pd.read_csv(out / "splits.csv")
    assert table["distance_m"].tolist() == [5.0, 10.0]
    assert np.all(np.diff(table["time_s"]) > 0) and table["time_s"].iloc[0] > 0
    assert not undocumented("splits.csv", table.columns)
    summary = json.loads((out / "summary.json").read_text())
    assert summary["splits_m"] == [5.0, 10.0, 50.0] and summary["split_times_s"][2] is None
    assert "splits from the first step: 5 m" in printed.out and "50 m not reached" in printed.out
    assert "no split time at 50 m" in printed.err
    bad = tmp_path / "bad"
    assert main(["track", str(ses), "--splits", "10,5", "--out", str(bad)]) == 2
    err = capsys.readouterr().err
    assert "--splits '10,5'" in err and "Traceback" not in err and not bad.exists()
