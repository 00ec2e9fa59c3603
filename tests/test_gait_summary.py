"""The clinical gait summary (decisions L79-L82, W70, W71): walking time, gait speed, the straight strides'
speed, stride times across a short rest, the waist pipelines' cadence and speed, the distance error's scope."""

from __future__ import annotations

import json
import logging
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.track.gait import SUMMARY_KEYS, gait_summary, waist_gait_summary, walking_time

REAL = Path(__file__).resolve().parents[1] / "datasets" / "real"
TUG = "stand:3, straight:3, turn:180, straight:3, turn:180, stand:3"


@pytest.fixture(autouse=True)
def _quiet():  # restored after each test: a level left behind hides other tests' warnings
    logging.disable(logging.WARNING)
    yield
    logging.disable(logging.NOTSET)


def test_walking_time_splits_at_stops_and_gap_rows():
    # two strides, a 1 s rest (a turn: walking), two strides, a 4 s stop, one stride
    st, en = [0.0, 1.0, 3.0, 4.0, 9.0], [1.0, 2.0, 4.0, 5.0, 10.0]
    assert walking_time(st, en) == pytest.approx(5.0 + 1.0)
    # a gap row between strides 1 and 2 ends the piece: its time is not counted
    assert walking_time([0.0, 1.0, 2.0, 3.0], [1.0, 2.0, 3.0, 4.0], [True, True, False, True]) == pytest.approx(3.0)
    assert walking_time([], []) is None
    assert walking_time([1.0], [1.0]) is None  # no positive duration


def _foot_table():
    # 4 straight strides of 1.2 m / 1.1 s, two turn strides of 0.1 m, a short rest (0.2 s) before stride 6
    st = np.array([0.0, 1.1, 2.2, 3.3, 4.4, 5.5, 6.8, 7.9])
    en = np.array([1.1, 2.2, 3.3, 4.4, 5.5, 6.6, 7.9, 9.0])
    length = np.array([0.6, 1.2, 1.2, 1.2, 0.1, 0.1, 1.2, 1.2])
    turn = np.deg2rad([0, 2, -3, 5, 120, 60, 4, -1])
    t = pd.DataFrame({"start_s": st, "end_s": en, "event_s": en - 0.3, "length_m": length, "gap_s": 0.0,
                      "unit": "foot"})
    from pdrlearn.track.gait import add_gait_columns
    return add_gait_columns(t, turn_rad=turn)


def test_foot_summary_gait_speed_and_straight_strides():
    t = _foot_table()
    assert np.isfinite(t["stride_time_s"].iloc[6])  # L80: across the 0.2 s rest (L66 left it empty)
    assert t["stride_time_s"].iloc[6] == pytest.approx(1.3)
    g = gait_summary(t)
    assert set(SUMMARY_KEYS) <= set(g)
    assert g["walking_time_s"] == pytest.approx(9.0)
    assert g["gait_speed_mps"] == pytest.approx(t["length_m"].sum() / 9.0)
    # the turn strides (0.1 m / 1.1 s) pull the median of all strides down; the straight median leaves them out
    assert g["n_straight_strides"] == 5
    assert g["median_speed_straight_mps"] == pytest.approx(1.2 / 1.1)
    assert g["median_speed_mps"] < g["median_speed_straight_mps"]
    # a table without gait columns (streaming, run) gets the keys (B14): walking time and gait speed from its
    # rest-to-rest strides (E48), None / 0 for what needs an initial contact
    none = gait_summary(t.drop(columns=["stride_time_s", "cadence_spm", "speed_mps", "turn_angle_rad"]))
    assert set(SUMMARY_KEYS) <= set(none) and none["n_stride_times"] == 0 and none["median_speed_straight_mps"] is None
    assert none["walking_time_s"] == g["walking_time_s"] and none["gait_speed_mps"] == g["gait_speed_mps"]


def test_waist_summary_from_the_step_times():
    st = np.array([0.0, 0.5, 1.0, 1.6, 2.1, 6.0, 6.5, 7.0])
    en = np.array([0.5, 1.0, 1.6, 2.1, 2.1, 6.5, 7.0, 7.0])
    has_next = np.array([1, 1, 1, 1, 0, 1, 1, 0], bool)
    length = np.where(has_next, 0.6, 0.0)
    t = pd.DataFrame({"start_s": st, "end_s": en, "has_next": has_next, "length_m": length, "unit": "waist",
                      "turning": [0, 0, 0, 1, 0, 0, 0, 0]})
    g = gait_summary(t, cadence_from="steps")  # W70's step medians (an option since W225)
    assert all(g[k] == v for k, v in waist_gait_summary(t, "steps").items())  # the waist rule, for a waist table
    # W359/W361: the grouped-data median of the step times 0.5 x 5, 0.6 (class 0.1 s): 0.45 + 0.1 * 3 / 5
    assert g["median_step_time_s"] == pytest.approx(0.51)
    assert g["median_cadence_spm"] == pytest.approx(120.0)
    assert g["median_speed_mps"] == pytest.approx(1.2)
    assert g["n_stride_times"] == 3 + 1  # contacts k -> k + 2 inside each sequence (W47)
    assert g["median_stride_time_s"] == pytest.approx(1.05)
    assert g["walking_time_s"] == pytest.approx(2.1 + 1.0)  # the 3.9 s between the sequences is a stop
    assert g["gait_speed_mps"] == pytest.approx(6 * 0.6 / 3.1)
    assert g["n_straight_strides"] == 5  # the turning step left out
    # W225 (the default): strides 1.0, 1.1, 1.1, 1.0 s -> 120 / 1.05; stride speeds 1.2 / stride time; a stride
    # is straight when both its steps are (the stride 1.0 -> 2.1 s holds the turning step)
    d = gait_summary(t)
    assert all(d[k] == v for k, v in waist_gait_summary(t).items())
    assert d["median_cadence_spm"] == pytest.approx(120 / 1.05)
    assert d["median_speed_mps"] == pytest.approx((1.2 + 1.2 / 1.1) / 2)
    assert d["n_straight_strides"] == 3 and d["median_speed_straight_mps"] == pytest.approx(1.2)
    assert {k: d[k] for k in ("median_step_time_s", "median_stride_time_s", "walking_time_s", "gait_speed_mps")} \
        == {k: g[k] for k in ("median_step_time_s", "median_stride_time_s", "walking_time_s", "gait_speed_mps")}
    # W27: a fragment merged into its neighbour (its length 0, the neighbour's the whole step) and its
    # neighbours give no step time or stride through them; the walking time and gait speed keep them
    m = t.assign(merged=[False, False, False, False, False, False, True, False],
                 length_m=[0.6, 0.6, 0.6, 0.6, 0.0, 1.2, 0.0, 0.0])
    gm = gait_summary(m, cadence_from="steps")
    # W359: grouped median of 0.5, 0.5, 0.6, 0.5 (the merged step and its neighbours out): 0.45 + 0.1 * 2 / 3
    assert gm["median_step_time_s"] == pytest.approx(0.45 + 0.1 * 2 / 3)
    assert gm["median_speed_mps"] == pytest.approx(1.2)
    assert gm["n_stride_times"] == 3 and gm["gait_speed_mps"] == pytest.approx(g["gait_speed_mps"])
    assert gait_summary(m)["median_speed_mps"] == pytest.approx(1.2 / 1.1)  # the strides 0-1.0, 0.5-1.6, 1.0-2.1 s


def test_median_cadence_of_an_asymmetric_gait_from_the_strides_option():
    # L176's formula (W225: the lower back's default): a hemiparetic walk's steps alternate 0.4 / 0.8 s (bimodal):
    # 60 / step time has its median on one mode (150 or 75 steps/min) or between them; the strides are all 1.2 s
    from pdrlearn.track.bouts import cadence_spm

    st = np.cumsum([0.0, 0.4, 0.8, 0.4, 0.8, 0.4, 0.8, 0.4, 0.8, 0.4, 0.8])
    waist = pd.DataFrame({"start_s": st, "end_s": np.append(st[1:], st[-1]), "length_m": 0.5, "unit": "waist",
                          "has_next": [True] * (len(st) - 1) + [False]})
    g = gait_summary(waist, cadence_from="strides")
    true = cadence_spm(len(st) - 1, st[-1] - st[0])
    assert true == pytest.approx(100.0) and g["median_cadence_spm"] == pytest.approx(true)
    assert gait_summary(waist)["median_cadence_spm"] == pytest.approx(true)  # W225: the default
    assert gait_summary(waist, cadence_from="steps")["median_cadence_spm"] == pytest.approx(112.5)  # W70's option
    # W225: the stride speed (0.5 + 0.5) / 1.2 s; the step speeds 1.25 / 0.625 m/s put their median between modes
    assert gait_summary(waist)["median_speed_mps"] == pytest.approx(1.0 / 1.2)
    with pytest.raises(ValueError, match="W224"):
        gait_summary(waist, cadence_from="stride")
    # the foot's summary: the same function of its median stride time (strides of 1.1 and 1.3 s, median 1.2 s)
    t = _foot_table().assign(stride_time_s=[np.nan, 1.1, 1.3, 1.1, 1.3, 1.1, 1.3, np.nan])
    assert gait_summary(t, cadence_from="strides")["median_cadence_spm"] == pytest.approx(100.0)


@pytest.mark.skipif(not (REAL / "mobgap_HA001_Test5_Trial1").exists(), reason="bundled recording missing")
def test_waist_track_has_cadence_speed_and_the_error_scope(tmp_path, capsys):
    """Trial findings 3 and 5 on the real lower-back recording: cadence and speed are there, and the
    distance error says it counts the reference bouts (W70, W71)."""
    from pdrlearn.cli import main

    assert main(["track", "--no-plot", str(REAL / "mobgap_HA001_Test5_Trial1"), "--out", str(tmp_path / "t"),
                 "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    saved = json.loads((tmp_path / "t" / "summary.json").read_text())
    for s in (printed, saved):
        assert 80 < s["median_cadence_spm"] < 130 and 0.6 < s["median_speed_mps"] < 1.5
        assert 0.6 < s["gait_speed_mps"] < 1.5 and s["walking_time_s"] > 3
        assert s["distance_error_scope"] == "reference bouts"
        assert s["distance_in_ref_bouts_m"] == pytest.approx(s["bout_distance_m"])
        assert s["distance_in_ref_bouts_m"] < s["distance_m"]
        assert s["distance_error_pct"] == pytest.approx(
            100 * (s["distance_in_ref_bouts_m"] - s["distance_ref_m"]) / s["distance_ref_m"])
    steps = pd.read_csv(tmp_path / "t" / "steps.csv")
    dt = (steps["end_s"] - steps["start_s"])[steps["has_next"]]
    from pdrlearn.kernels.grouped_median import grouped_median

    # W359/W361: the grouped-data median of the whole-sample step times
    assert printed["median_step_time_s"] == pytest.approx(grouped_median(dt[dt <= 1.5].to_numpy(float)))


def test_simulated_tug_and_10m_walk(tmp_path, capsys):
    """Trial findings 1, 2, 4: the TUG's straight strides' speed, the stride after a turn has a stride time,
    the whole-track error scope, the report's gait table."""
    from pdrlearn.cli import main

    for name, route in (("tug", TUG), ("w10", "stand:3, straight:10, stand:3")):
        assert main(["simulate", "--route", route, "--user-seed", "4", "--out", str(tmp_path / name)]) == 0
        assert main(["track", "--no-plot", str(tmp_path / name), "--out", str(tmp_path / "r" / name)]) == 0
    out = capsys.readouterr().out
    assert "gait speed" in out and "straight strides" in out
    tug = json.loads((tmp_path / "r" / "tug" / "summary.json").read_text())
    w10 = json.loads((tmp_path / "r" / "w10" / "summary.json").read_text())
    steps = pd.read_csv(tmp_path / "r" / "tug" / "steps.csv")
    # L80: every stride after the first, with its own contact, has a stride time (a turn's rest included)
    assert steps["stride_time_s"].iloc[1:].notna().all()
    assert (steps["stride_time_s"].dropna() <= 3.0).all()
    # L79: the straight strides' speed is the walking speed (the simulated straight strides: 1.0-1.2 m/s)
    assert 0.9 < tug["median_speed_straight_mps"] < 1.3
    assert tug["median_speed_straight_mps"] > tug["median_speed_mps"] + 0.2
    assert 0.9 < w10["median_speed_straight_mps"] < 1.3
    assert w10["gait_speed_mps"] == pytest.approx(w10["distance_m"] / w10["walking_time_s"])
    assert 0.8 < w10["gait_speed_mps"] < 1.2 and tug["gait_speed_mps"] < w10["gait_speed_mps"]
    assert tug["distance_error_scope"] == "whole track"  # L82
    # L81: the report's gait parameters table
    assert main(["report", str(tmp_path / "r"), "--out", str(tmp_path / "rep")]) == 0
    md = (tmp_path / "rep" / "report.md").read_text()
    assert "gait parameters" in md and "gait_speed_mps" in md and "median_cadence_spm" in md
    assert "median_stride_time_s" in md and "distance_error_scope" in md and "whole track" in md
