"""Session 47, trial T2 (Nordic walking on hills). Decision L705 (F1): a ramp's strides are no stair strides -
``n_stair_strides_up`` / ``_down`` leave out the rows inside ramps.csv's ramps, which count as ``n_ramp_strides_up``
/ ``_down`` (a 1.8 m stride on a 10 % hill rises 0.18 m, over L179's 0.10 m: T2 read "94 / 93 stair strides" beside
flights of 11 and 10). Decision W537 (F4): a lower-back track's ``median_stride_length_m`` (summary, periods.csv,
segments.csv) is the median of two consecutive steps' lengths summed, bouts.csv's strides."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.track.evaluate import median_stride_length, waist_stride_lengths
from pdrlearn.track.gait import stair_ramp_split

#: a 40 m hill at 10 % walked with Nordic-walking strides (0.9 m steps), then a flight of 12 stairs up
ROUTE = "stand:3, straight:5, slope:40:10, stand:3, turn:180, straight:3, up:12, stand:3"
LONG = ["--step-length", "0.9", "--step-time", "0.5", "--bounce", "population"]


def _rows(dz, unit="foot"):
    n = len(dz)
    length = np.where(np.abs(dz) >= 0.25, 0.56, 1.2)  # a stair stride's tread run; a hill's long stride
    return pd.DataFrame({"start_s": np.arange(n, dtype=float), "end_s": np.arange(n) + 1.0, "length_m": length,
                         "dz_m": dz, "gap_s": 0.0, "unit": unit, "heading_rad": 0.0})


#: 5 level strides, 20 up a 15 % hill, 5 level, 10 stair strides up, 3 level, 8 down the hill
DZ = np.r_[np.zeros(5), np.full(20, 0.18), np.zeros(5), np.full(10, 0.30), np.zeros(3), np.full(8, -0.18)]
RAMPS = [{"first": 5, "last": 24, "direction": "up"}, {"first": 43, "last": 50, "direction": "down"}]


def test_a_foot_tracks_stair_strides_are_its_flights_and_a_ramps_strides_are_ramp_strides_l705():
    steps = _rows(DZ)
    assert stair_ramp_split(steps, RAMPS) == {"n_stair_strides_up": 10, "n_stair_strides_down": 0,
                                              "n_ramp_strides_up": 20, "n_ramp_strides_down": 8}
    # without ramps.csv (no grade source) the hill is still no flight: its strides are in neither count
    assert stair_ramp_split(steps, []) == {"n_stair_strides_up": 10, "n_stair_strides_down": 0,
                                           "n_ramp_strides_up": 0, "n_ramp_strides_down": 0}


def test_a_lower_back_tracks_ramp_steps_leave_its_stair_steps_l705():
    steps = _rows(DZ, unit="waist").assign(has_next=True, pause_dz_m=0.0)
    assert stair_ramp_split(steps, RAMPS) == {"n_stair_strides_up": 10, "n_stair_strides_down": 0,
                                              "n_ramp_strides_up": 20, "n_ramp_strides_down": 8}
    # before L705 (no ramps given) every step over L179's 0.10 m was a stair step
    assert stair_ramp_split(steps, [])["n_stair_strides_up"] == 30


def test_a_lower_back_stride_is_two_consecutive_steps_w537():
    # alternating 0.6 / 0.8 m steps; each sequence ends with a 0 m closing contact (has_next False)
    length = np.r_[np.tile([0.6, 0.8], 5), 0.0, np.tile([0.6, 0.8], 3), 0.0]
    has_next = np.r_[np.ones(10, bool), False, np.ones(6, bool), False]
    steps = pd.DataFrame({"start_s": np.arange(len(length)) * 0.5, "unit": "waist", "length_m": length,
                          "has_next": has_next})
    strides = waist_stride_lengths(steps)
    assert len(strides) == 9 + 5  # n_steps - 2 per sequence of contacts, as bouts.csv's n_strides
    assert np.allclose(strides, 1.4)
    assert median_stride_length(steps) == pytest.approx(1.4)
    assert waist_stride_lengths(steps.assign(unit="foot")) is None  # a foot table keeps C19's rule


@pytest.fixture(scope="module")
def hill(tmp_path_factory):
    root = tmp_path_factory.mktemp("hill")
    sim = root / "sim"
    assert main(["simulate", "--route", ROUTE, "-u", "15045", "--rate", "100", *LONG, "-o", str(sim)]) == 0
    return sim


def test_a_hill_walked_with_long_strides_has_ramp_strides_and_the_flights_own_stair_strides_l705(hill, tmp_path,
                                                                                                  capsys):
    out = tmp_path / "foot"
    assert main(["track", "--no-plot", str(hill), "--altitude", "fused", "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    s = json.loads((out / "summary.json").read_text())
    truth = pd.read_csv(hill / "steps.csv")
    ramp_truth = int(((truth["height_m"] > 0.01) & (truth["kind"] == "walk")).sum())
    flights = pd.read_csv(out / "stairs.csv")
    assert s["n_ramps"] >= 1 and s["n_flights_up"] == 1
    assert s["n_stair_strides_up"] == int(flights.loc[flights["direction"] == "up", "n_strides"].sum())
    assert s["n_ramp_strides_up"] >= 0.8 * ramp_truth  # the hill's strides, not stair strides
    assert s["n_stair_strides"] >= s["n_stair_strides_up"] + s["n_ramp_strides_up"] * 0.8  # L179's count unchanged
    assert s["n_stair_strides_up"] <= int((truth["kind"] == "stairs_up").sum()) + 1  # the flight's, no hill's
    assert f"({s['n_stair_strides_up']} / {s['n_stair_strides_down']} stair strides" in printed
    assert f"; {s['n_ramp_strides_up']} / {s['n_ramp_strides_down']} ramp strides; ramps.csv)" in printed


def test_the_lower_back_fills_the_stride_length_in_summary_and_periods_w537(hill, tmp_path):
    out = tmp_path / "waist"
    assert main(["track", "--no-plot", str(hill), "--pipeline", "waist-pendulum", "--per", "30s",
                 "--out", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    truth = pd.read_csv(hill / "steps.csv")
    true_stride = float(truth.loc[truth["kind"] == "walk", "length_m"].median())
    assert s["median_stride_length_m"] == pytest.approx(true_stride, rel=0.08)
    bouts = pd.read_csv(out / "bouts.csv")
    longest = bouts.loc[bouts["n_steps"].idxmax()]
    assert s["median_stride_length_m"] == pytest.approx(float(longest["stride_length_m"]), rel=0.08)
    periods = pd.read_csv(out / "periods.csv")
    walked = periods[periods["n_steps"] > 10] if "n_steps" in periods else periods
    assert np.isfinite(pd.to_numeric(walked["median_stride_length_m"], errors="coerce")).all()
