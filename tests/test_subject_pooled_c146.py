"""Decision C146: subjects.csv pools each subject's strides over its sessions (several short walkway trials of a
child): a pooled median stride length and a stride-time CV taken within each session (session 38, trial T1
finding 5). Simulated users 9680-9699 only."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main


def _session(times, lengths=None, steady=True, unit="foot"):
    times = np.asarray(times, float)
    start = np.concatenate([[0.0], np.cumsum(times)[:-1]])
    return pd.DataFrame({"start_s": start, "end_s": start + times, "stride_time_s": times, "steady": steady,
                         "length_m": 0.9 if lengths is None else lengths, "gap_s": 0.0, "unit": unit})


def test_pooled_cv_is_within_sessions_not_across_their_pace():
    from pdrlearn.track.clinical import cv_pct, within_groups_cv_pct
    from pdrlearn.track.subject_pool import pooled_stride_measures

    rng = np.random.default_rng(9680)
    groups = [m + 0.01 * rng.standard_normal(5) for m in (0.70, 0.80, 0.90)]  # three trials at three paces
    got = pooled_stride_measures([_session(t, lengths=[0.8, 0.9, 1.0, 0.9, 0.85]) for t in groups])
    assert got["pooled_n_cv_strides"] == 15 and got["pooled_n_cv_sessions"] == 3 and got["pooled_n_sessions"] == 3
    assert got["pooled_stride_time_cv_pct"] == pytest.approx(within_groups_cv_pct(groups))
    assert got["pooled_stride_time_cv_pct"] < 2.5 < cv_pct(np.concatenate(groups))  # the pace change is not in it
    assert got["pooled_n_strides"] == 15 and got["pooled_median_stride_length_m"] == pytest.approx(0.9)
    assert got["pooled_stride_time_cv_reason"] is None


def test_pooled_cv_needs_nine_degrees_of_freedom_and_foot_strides():
    from pdrlearn.track.subject_pool import pooled_stride_measures

    one = pooled_stride_measures([_session(np.full(9, 0.77) + np.arange(9) * 0.002)])  # 8 degrees of freedom
    assert np.isnan(one["pooled_stride_time_cv_pct"]) and "9 steady level forward strides in 1 session" in \
        one["pooled_stride_time_cv_reason"] and "9 needed" in one["pooled_stride_time_cv_reason"]
    two = pooled_stride_measures([_session(np.full(5, 0.77) + np.arange(5) * 0.002)] * 2 + [_session([0.8])])
    assert np.isnan(two["pooled_stride_time_cv_pct"])  # 10 strides in 2 sessions (8 dof); the single stride adds none
    assert two["pooled_n_cv_strides"] == 10 and two["pooled_n_strides"] == 11
    back = pooled_stride_measures([_session(np.full(12, 0.5), unit="waist").drop(columns=["steady"])])
    assert back["pooled_n_strides"] == 0 and np.isnan(back["pooled_median_stride_length_m"])
    assert "lower-back" in back["pooled_stride_time_cv_reason"]


def test_track_all_pools_a_childs_short_trials(tmp_path):
    for seed in (1, 2, 3):  # three 10 m walkway passes of one child (T1's protocol)
        assert main(["simulate", "--route", "stand:3, straight:10, stand:3", "--height", "1.25", "--leg-length",
                     "0.62", "--step-length", "0.45", "--step-time", "0.38", "--rate", "100", "--user-seed", "9681",
                     "--seed", str(seed), "--out", str(tmp_path / "child" / f"p{seed}")]) == 0
    assert main(["track-all", "--no-plot", str(tmp_path / "child"), "--out", str(tmp_path / "out")]) == 0
    sessions = pd.read_csv(tmp_path / "out" / "sessions.csv")
    assert sessions["stride_time_cv_pct"].isna().all()  # each pass alone: under 10 steady strides
    subjects = pd.read_csv(tmp_path / "out" / "subjects.csv")
    assert len(subjects) == 1
    row = subjects.iloc[0]
    assert row["pooled_n_sessions"] == 3 and row["pooled_n_cv_sessions"] == 3
    assert row["pooled_n_cv_strides"] - 3 >= 9 and 0.5 < row["pooled_stride_time_cv_pct"] < 6
    strides = pd.read_csv(tmp_path / "out" / "strides.csv")
    assert row["pooled_n_strides"] == len(strides)
    assert row["pooled_median_stride_length_m"] == pytest.approx(strides["length_m"].abs().median())
    assert 0.8 < row["pooled_median_stride_length_m"] < 1.0  # 2 x the simulated 0.45 m step
    # the report of the batch shows the pooled table (C146), read from subjects.csv
    assert main(["report", str(tmp_path / "out"), "--out", str(tmp_path / "rep")]) == 0
    md = (tmp_path / "rep" / "report.md").read_text()
    pooled = md.split("within each session, decision C146)**")[1].split("**")[0]
    assert "pooled_stride_time_cv_pct" in pooled and f"{row['pooled_stride_time_cv_pct']:.4g}" in pooled
