"""Decision C108 (session 36, trial T2 finding 7): subjects.csv, the natural table for a day's totals across a
subject's files, sums sessions.csv's additive columns - floors, time without data, the lower back's posture times
and transfers - and leaves a sum empty when one of the sessions has no value (a foot track's posture)."""

import math

import pandas as pd

from pdrlearn.visits import SUBJECT_COLUMNS, subject_totals


def _day(posture_b=40.0):
    """Two tracked parts of one subject's day and a failed third (counted nowhere)."""
    return pd.DataFrame([
        {"path": "P1/day1/am", "group": "P1", "subject": "P1", "visit": "day1", "status": "ok", "distance_m": 100.0,
         "floors_up": 2, "floors_down": 1, "time_no_data_s": 12.5, "standing_time_s": 300.0, "sitting_time_s": 600.0,
         "lying_time_s": 0.0, "n_sit_to_stand": 3, "n_stand_to_sit": 3},
        {"path": "P1/day1/pm", "group": "P1", "subject": "P1", "visit": "day1", "status": "ok", "distance_m": 50.0,
         "floors_up": 1, "floors_down": 2, "time_no_data_s": 0.0, "standing_time_s": posture_b,
         "sitting_time_s": 20.0, "lying_time_s": 5.0, "n_sit_to_stand": 1, "n_stand_to_sit": 2},
        {"path": "P1/day1/bad", "group": "P1", "subject": "P1", "visit": "day1", "status": "failed",
         "distance_m": None, "floors_up": 9, "floors_down": 9, "time_no_data_s": 99.0, "standing_time_s": 99.0,
         "sitting_time_s": 99.0, "lying_time_s": 99.0, "n_sit_to_stand": 9, "n_stand_to_sit": 9}])


def test_subjects_csv_sums_floors_gaps_and_posture_over_a_days_files():
    out = subject_totals(_day())
    assert list(out.columns) == list(SUBJECT_COLUMNS)
    row = out.iloc[0]
    assert (row["n_tracked"], row["n_failed"]) == (2, 1)
    assert (row["floors_up"], row["floors_down"]) == (3, 3)
    assert row["time_no_data_s"] == 12.5
    assert (row["standing_time_s"], row["sitting_time_s"], row["lying_time_s"]) == (340.0, 620.0, 5.0)
    assert (row["n_sit_to_stand"], row["n_stand_to_sit"]) == (4, 5)
    # the columns before visit_as_written keep their places (C82, C108)
    assert list(out.columns).index("visit_as_written") == 14


def test_a_partial_posture_sum_is_left_empty():
    """A foot track of the day has no posture: the sum of the other part is not the day's standing time."""
    out = subject_totals(_day(posture_b=float("nan")))
    assert math.isnan(out.iloc[0]["standing_time_s"])
    assert out.iloc[0]["sitting_time_s"] == 620.0
