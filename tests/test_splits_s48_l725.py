"""Decision L725 (session 48, fixer FI, trial T1 finding F6): splits.csv gives each split's stride count and its
median cadence, stride length and stance % (the rows whose middle lies in the split, segments.csv's interval rule;
the medians by the summary's own rules), so a coach's 400 m laps need no legs file and second track."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.track.splits import SPLIT_COLUMNS, EverySplit, split_table


def _strides(lengths, times, stance=None):
    """A foot step table of back-to-back strides (no gap) with the gait columns the summary reads."""
    start = np.r_[0.0, np.cumsum(times)[:-1]] + 5.0
    end = start + np.asarray(times, float)
    st = pd.DataFrame({"start_s": start, "end_s": end, "event_s": end, "length_m": np.asarray(lengths, float),
                       "stride_time_s": times, "cadence_spm": 120.0 / np.asarray(times, float),
                       "speed_mps": np.asarray(lengths, float) / np.asarray(times, float), "turn_angle_rad": 0.0,
                       "dz_m": 0.0, "gap_s": 0.0, "impossible": False, "unit": "foot", "foot": "right",
                       "heading_rad": 0.0, "direction": "forward"})
    if stance is not None:
        st["stance_pct"] = stance
        st["stance_time_s"] = st["stride_time_s"] * st["stance_pct"] / 100
        st["swing_time_s"] = st["stride_time_s"] - st["stance_time_s"]
    return st


def test_each_split_gives_its_strides_medians_l725():
    # 10 strides of 1.0 m in 1.0 s (60 % stance), then 10 of 2.0 m in 0.8 s (55 %): 10 m and 30 m
    st = _strides([1.0] * 10 + [2.0] * 10, [1.0] * 10 + [0.8] * 10, stance=[60.0] * 10 + [55.0] * 10)
    splits, _, lines = split_table(st, (10.0, 30.0))
    assert list(splits.columns) == list(SPLIT_COLUMNS) and not lines
    assert splits["n_steps"].tolist() == [10, 10]
    assert splits["median_cadence_spm"].tolist() == pytest.approx([120.0, 150.0])
    assert splits["median_stride_length_m"].tolist() == pytest.approx([1.0, 2.0])
    assert splits["median_stance_pct"].tolist() == pytest.approx([60.0, 55.0])
    # every:24.5 m: 24.5 m (10 of 1 m + 7 of 2 m; the 18th, 24-26 m, has its middle past the mark) and the end
    every, _, _ = split_table(st, EverySplit(24.5))
    assert every["distance_m"].tolist() == [24.5, 30.0] and every["n_steps"].tolist() == [17, 3]
    assert every["n_steps"].sum() == len(st)  # the last split holds its end


def test_a_track_without_toe_off_gives_no_stance_l725():
    st = _strides([1.4] * 8, [1.1] * 8)
    splits, _, _ = split_table(st, (5.0,))
    assert splits["n_steps"].tolist() == [4] and splits["median_stance_pct"].isna().all()
    assert splits["median_stride_length_m"].tolist() == pytest.approx([1.4])


def test_periods_and_segments_give_the_stance_too_l725():
    """Trial T1 F6: segments.csv had no stance %; periods.csv and segments.csv end with it, by the same kernel."""
    from pdrlearn.track.periods import PERIOD_COLUMNS, interval_gait
    from pdrlearn.track.segments import segment_columns

    assert PERIOD_COLUMNS[-2] == segment_columns()[-2] == "median_stance_pct"  # W603: n_steps_with_turns last
    st = _strides([1.0] * 6, [1.0] * 6, stance=[58.0, 60.0, 62.0, 64.0, 66.0, 68.0])
    assert interval_gait(st, np.arange(6) >= 2)["median_stance_pct"] == pytest.approx(65.0)
    assert interval_gait(st, np.zeros(6, bool))["median_stance_pct"] is None


def test_a_lower_back_tables_last_contact_counts_in_the_last_split_r2_f4():
    """Review R2 F4 (session 48): the clock credits a lower-back contact row's length at its start; its middle had
    put the last contact after the last crossing (145 of 147 rows counted on the reviewer's walk)."""
    n = 12
    start = 5.0 + 0.5 * np.arange(n)
    st = pd.DataFrame({"start_s": start, "end_s": start + 0.5, "event_s": start, "length_m": 0.7,
                       "unit": "waist", "heading_rad": 0.0, "impossible": False})
    splits, _, _ = split_table(st, EverySplit(4.2))
    assert splits["n_steps"].sum() == n, splits
