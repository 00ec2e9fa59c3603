"""Decisions L300-L303, S57 (ramp / accessibility trial, session 30, findings 3, 6, 7, 8): steps.csv's grade_pct,
ramps.csv, distance_along_slope_m and the floors split by stairs / ramps / rides."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.track.evaluate import floors_by_kind
from pdrlearn.track.grade import grade_source, grades_pct, ramp_runs

R12UP = ("stand:3, straight:5, slope:9:8.33, straight:1.5, slope:9:8.33, straight:1.5, slope:9:8.33, straight:1.5, "
         "slope:9:8.33, straight:5, stand:3")


def test_grade_is_rise_over_horizontal_run_and_empty_on_a_short_row():
    g = grades_pct([1.2, -1.0, 0.1, np.nan], [0.1, -0.05, 0.05, 0.1])
    assert g[0] == pytest.approx(100 * 0.1 / 1.2) and g[1] == pytest.approx(-5.0)
    assert np.isnan(g[2]) and np.isnan(g[3])  # under GRADE_MIN_LENGTH_M; not finite


def test_four_runs_with_landings_are_one_ramp_and_a_stair_breaks_it():
    run = [(1.3, 1.3 * 0.0833)] * 7
    landing = [(1.5, 0.0)]
    rows = run + landing + run + landing + run + landing + run
    length, dz = (np.array(c) for c in zip(*rows, strict=True))
    (ramp,) = ramp_runs(length, dz)
    assert (ramp["n_runs"], ramp["landings"], ramp["direction"]) == (4, 3, "up")
    assert ramp["mean_grade_pct"] == pytest.approx(8.33) and ramp["landing_m"] == pytest.approx(4.5)
    assert ramp["horizontal_run_m"] == pytest.approx(4 * 7 * 1.3) and ramp["rise_m"] == pytest.approx(dz.sum())
    stair = [(0.56, 0.34)]
    length, dz = (np.array(c) for c in zip(*(run + stair + run), strict=True))
    assert [r["n_runs"] for r in ramp_runs(length, dz)] == [1, 1]  # a stair stride is no landing
    length, dz = (np.array(c) for c in zip(*(run + [(4.0, 0.0)] + [(1.3, -0.11)] * 7), strict=True))
    assert [r["direction"] for r in ramp_runs(length, dz)] == ["up", "down"]
    assert ramp_runs(np.full(5, 1.3), np.full(5, 0.01)) == []  # 0.8 %: level


def _steps(length, dz, pause=None, unit="foot"):
    df = pd.DataFrame({"start_s": np.arange(len(length)), "end_s": np.arange(len(length)) + 1.0,
                       "length_m": length, "dz_m": dz, "unit": unit})
    if pause is not None:
        df["pause_dz_m"] = pause
    return df


def test_floors_split_by_what_climbed_sum_to_the_floor_counts():
    street = _steps(np.full(110, 1.4), np.full(110, 0.112))
    assert floors_by_kind(street)["floors_up_ramps"] == 4 and floors_by_kind(street)["floors_up_stairs"] == 0
    stairs = _steps(np.r_[np.ones(3), np.full(9, 0.56), np.ones(3)], np.r_[np.zeros(3), np.full(9, 0.34),
                                                                          np.zeros(3)])
    got = floors_by_kind(stairs)
    assert (got["floors_up_stairs"], got["floors_up_ramps"], got["floors_up_rides"]) == (1, 0, 0)
    lift = _steps(np.full(10, 0.7), np.zeros(10), np.r_[np.zeros(5), 3.0, np.zeros(4)], unit="waist")
    assert floors_by_kind(lift)["floors_up_rides"] == 1 and floors_by_kind(lift)["floors_up_stairs"] == 0
    well = _steps(np.r_[np.full(8, 0.6), np.full(3, 2.0), np.full(8, 0.6)],  # L302: the landing's rows left out
                  np.r_[np.full(8, 0.17), np.zeros(3), np.full(8, 0.17)], unit="waist")
    assert floors_by_kind(well)["floors_up_stairs"] == 1  # span 17 %, stair rows 28 %
    down = _steps(np.full(110, 1.4), np.full(110, -0.112))
    assert floors_by_kind(down)["floors_down_ramps"] == 4
    assert set(floors_by_kind(_steps([], [])).values()) == {None}


def test_grade_source_names_a_barometric_altitude_only():
    foot = _steps(np.full(3, 1.3), np.full(3, 0.11))
    assert grade_source(foot, {}) is None and grade_source(foot, {"altitude_source": "fused"}) == "fused"
    assert grade_source(_steps(np.ones(3), np.zeros(3), unit="waist"), {}) is None  # W90: no barometer
    assert grade_source(_steps(np.ones(3), [0.0, 0.05, 0.0], unit="waist"), {}) == "barometer"


@pytest.fixture(scope="module")
def r12up(tmp_path_factory):
    d = tmp_path_factory.mktemp("grade")
    assert main(["simulate", "--route", R12UP, "--user-seed", "5700", "--out", str(d / "sim")]) == 0
    assert main(["track", "--no-plot", str(d / "sim"), "--altitude", "fused", "--out", str(d / "fused")]) == 0
    assert main(["track", "--no-plot", str(d / "sim"), "--out", str(d / "foot")]) == 0
    return d


def test_fused_r12up_reads_its_grade_ramp_and_floor(r12up):
    s = json.loads((r12up / "fused" / "summary.json").read_text())
    steps = pd.read_csv(r12up / "fused" / "steps.csv")
    ramps = pd.read_csv(r12up / "fused" / "ramps.csv")
    assert s["grade_source"] == "fused" and s["n_ramps"] == len(ramps) == 1
    g = steps["grade_pct"]
    assert 7.0 < g[g > 3].median() < 10.5  # truth 8.33
    # L301: the 1.5 m landings are resolved only where a stride falls on them (this user's 1.3 m strides straddle
    # some and read 4-5 %), so the runs are 1-4; the rise is the route's 3.0 m either way
    assert ramps["landings"][0] == ramps["n_runs"][0] - 1 and 1 <= ramps["n_runs"][0] <= 4
    assert ramps["rise_m"][0] == pytest.approx(3.0, abs=0.3) and 7.0 < ramps["mean_grade_pct"][0] < 10.5
    assert s["distance_along_slope_m"] > s["distance_m"]
    for d in ("up", "down"):
        assert sum(s[f"floors_{d}_{k}"] for k in ("stairs", "ramps", "rides")) == s[f"floors_{d}"]
    assert s["floors_up_stairs"] == 0


def test_foot_track_without_fusion_has_no_grade_but_says_its_floors_are_ramps(r12up):
    s = json.loads((r12up / "foot" / "summary.json").read_text())
    steps = pd.read_csv(r12up / "foot" / "steps.csv")
    assert s["grade_source"] is None and s["distance_along_slope_m"] is None and s["n_ramps"] is None
    assert steps["grade_pct"].isna().all() and len(pd.read_csv(r12up / "foot" / "ramps.csv")) == 0
    assert s["floors_up_ramps"] == s["floors_up"] and s["floors_up_stairs"] == 0


def test_s57_ramp_label_depends_on_stride_length(tmp_path):
    """S57: a 1:12 ramp is `up` in the labels for a 1.3 m stride (rise 0.11 m > 0.08 m) and `flat` for a walker's
    0.6 m stride (0.05 m)."""
    route = "stand:3, straight:3, slope:9:8.33, straight:3, stand:3"
    assert main(["simulate", "--route", route, "--user-seed", "5701", "--out", str(tmp_path / "a")]) == 0
    assert main(["simulate", "--route", route, "--step-length", "0.3", "--step-time", "0.75", "--user-seed", "5701",
                 "--out", str(tmp_path / "w")]) == 0
    a, w = (pd.read_csv(tmp_path / n / "steps.csv") for n in ("a", "w"))
    assert (a["terrain"] == "up").sum() >= 4 and (w["terrain"] == "up").sum() == 0
    assert (a["height_m"][a["terrain"] == "up"] > 0.08).all()


def test_l303_option_drops_ramp_strides_only():
    """L303 (an option, its rule not met): a stride of a climb walked under 20 % is no stair stride; stairs keep
    theirs; off by default, L179's |dz| >= 0.10 m."""
    import inspect

    from pdrlearn.track.gait import stair_rows

    street = _steps(np.full(110, 1.4), np.full(110, 0.112))
    stairs = _steps(np.r_[np.ones(3), np.full(9, 0.56), np.ones(3)], np.r_[np.zeros(3), np.full(9, 0.34),
                                                                          np.zeros(3)])
    assert inspect.signature(stair_rows).parameters["ramp_not_stair"].default is False  # L595: a keyword, no switch
    assert stair_rows(street).sum() == 110
    assert stair_rows(street, ramp_not_stair=True).sum() == 0
    assert stair_rows(stairs, ramp_not_stair=True).sum() == stair_rows(stairs).sum() == 9
