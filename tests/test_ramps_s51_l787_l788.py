"""Session 51, FD (trial s51t1 finding F4): a long stop splits a ramp (L787); a stair "flight" far longer than a
building's at a slope's grade is a ramp (L788). Kernel-level: pure functions on small tables."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.track.grade import long_slope_rows, ramp_runs, ramp_table, stop_rows


def _steps(length, dz, start=None):
    n = len(length)
    start = np.arange(n) * 1.0 if start is None else np.asarray(start, dtype=float)
    return pd.DataFrame({"start_s": start, "end_s": start + 1.0, "length_m": length, "dz_m": dz, "unit": "foot",
                         "gap_s": 0.0})


def _hike(stop_s: float):
    """40 strides at 15 %, a stop of ``stop_s`` seconds, 30 strides at 25 % (trial s51t1's ramp 2)."""
    length = np.full(70, 1.4)
    dz = length * np.r_[np.full(40, 0.15), np.full(30, 0.25)]
    start = np.arange(70) * 1.0 + np.where(np.arange(70) >= 40, stop_s, 0.0)
    return _steps(length, dz, start)


def test_stop_rows_mark_a_row_after_a_stand_of_30_s_l787():
    assert stop_rows([0.0, 1.0, 40.0, 41.0], [1.0, 2.0, 41.0, 42.0]).tolist() == [False, False, True, False]
    assert not stop_rows([0.0, 1.0, 20.0], [1.0, 2.0, 21.0]).any()  # 18 s: a breath, no stop
    assert stop_rows([0.0, np.nan], [1.0, 2.0]).tolist() == [False, False]


def test_a_map_stop_splits_a_ramp_and_its_steepest_run_is_read_l787():
    from pdrlearn.track.grade import stair_grade_set

    info = {"altitude_source": "fused"}
    with stair_grade_set(30.0):  # the trial's --stair-grade 30
        split, joined = ramp_table(_hike(120.0), info), ramp_table(_hike(10.0), info)
    assert split["mean_grade_pct"].round(1).tolist() == [15.0, 25.0]  # two ramps (before: one 19.3 % run)
    assert len(joined) == 1 and joined["n_runs"].iloc[0] == 1  # a 10 s pause is walked through
    st = _hike(120.0)
    one = ramp_runs(st["length_m"], st["dz_m"], stair_grade_pct=30.0)  # no stops given: the old single run
    assert len(one) == 1 and one[0]["max_run_grade_pct"] == pytest.approx(19.3, abs=0.1)


def test_long_slope_rows_are_a_slopes_not_a_stairwells_or_a_stair_section_l788():
    n = 30
    slope = long_slope_rows(np.full(n, 0.35), np.full(n, 1.4), np.ones(n, bool))
    assert slope.all()  # 30 strides at 25 %: a slope
    assert not long_slope_rows(np.full(24, 0.35), np.full(24, 1.4), np.ones(24, bool)).any()  # 24: a flight
    flight = np.r_[np.full(11, 0.34), 0.0, 0.0, np.full(11, 0.34), 0.0, np.full(11, 0.34)]
    length = np.where(flight > 0, 0.56, 1.2)  # three 61 % flights with landings: a stairwell
    assert not long_slope_rows(flight, length, flight > 0.1).any()
    steep = np.r_[np.full(15, 0.14), np.full(6, 0.34), np.full(15, 0.14)]  # L466: stairs inside a 10 % trail
    length = np.r_[np.full(15, 1.4), np.full(6, 0.56), np.full(15, 1.4)]
    got = long_slope_rows(steep, length, np.ones(36, bool))
    assert got[:15].all() and not got[15:21].any() and got[21:].all()
    assert not long_slope_rows(np.full(n, 0.9), np.full(n, 1.4), np.ones(n, bool)).any()  # 64 %: a stair


def test_a_long_25_pct_climb_at_the_default_grade_is_a_ramp_not_a_flight_l788():
    from pdrlearn.track.evaluate import floors_by_kind
    from pdrlearn.track.stair_flights import flight_table

    rng = np.random.default_rng(18250)
    length = np.r_[np.full(5, 1.4), np.full(60, 1.4), np.full(5, 1.4), np.full(10, 0.56), np.full(5, 1.4)]
    dz = np.r_[np.zeros(5), 1.4 * (0.25 + rng.normal(0.0, 0.02, 60)), np.zeros(5), np.full(10, 0.34), np.zeros(5)]
    st = _steps(length, dz)
    flights = flight_table(st)
    assert flights["n_strides"].tolist() == [10]  # the real 10-stride flight alone (before: 60 and 10)
    ramps = ramp_table(st, {"altitude_source": "fused"})
    assert len(ramps) == 1 and ramps["mean_grade_pct"].iloc[0] == pytest.approx(25.0, abs=1.0)
    got = floors_by_kind(st)
    assert got["floors_up_ramps"] >= 6 and got["floors_up_stairs"] == 1  # 21 m on the slope, 3.4 m of stairs
