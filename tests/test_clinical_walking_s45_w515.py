"""Decision W515 (trial T1 F7): clinical.md's "Walking" line for any recording with steps - steps, walking time,
bouts with their lengths, distance and ramps - read from the track's summary.json, bouts.csv and ramps.csv."""

from __future__ import annotations

import pandas as pd

from pdrlearn.report.clinical import clinical_lines
from pdrlearn.report.walking import MAX_BOUTS_LISTED, walking_line

FOOT = {"pipeline": "plasys", "n_steps": 103, "n_steps_both_feet": 206, "n_steps_counts": "strides of the tracked foot",
        "walking_time_s": 187.548, "n_walking_bouts": 4, "distance_m": 57.0015, "time_span_s": 248.69}


def _folder(tmp_path, bouts=(11.94, 12.64, 16.03, 16.39), ramps=((("up", 18)), ("down", 17))):
    pd.DataFrame({"bout": range(1, len(bouts) + 1), "distance_m": bouts}).to_csv(tmp_path / "bouts.csv", index=False)
    if ramps:
        pd.DataFrame([{"ramp": i + 1, "direction": d, "n_steps": n} for i, (d, n) in enumerate(ramps)]).to_csv(
            tmp_path / "ramps.csv", index=False)
    return tmp_path


def test_a_short_foot_session_gets_the_walking_line(tmp_path):
    line = walking_line(FOOT, _folder(tmp_path), "foot unit")
    assert line == ("- Walking: ~206 steps, 187.5 s walking in 4 bouts (11.9 / 12.6 / 16.0 / 16.4 m), 57.0 m; "
                    "ramps: 1 up (18 strides), 1 down (17 strides) (foot unit; steps 2 per stride of the tracked foot)")
    # in clinical.md's block for a 4-min session (W448's daily-living lines need an hour)
    assert line in clinical_lines(FOOT, tmp_path)


def test_lower_back_steps_many_bouts_and_no_ramps(tmp_path):
    waist = {"pipeline": "waist-pendulum", "n_steps": 204, "walking_time_s": 180.0, "distance_m": 57.18,
             "gait_speed_mps": 0.32, "info": {"params_source": "calibrated"}}
    bouts = [2.0 + i for i in range(MAX_BOUTS_LISTED + 1)]
    line = walking_line(waist, _folder(tmp_path, bouts=bouts, ramps=(("up", 30),)), "lower-back unit")
    assert line == (f"- Walking: 204 steps, 180.0 s walking in {len(bouts)} bouts (median 6.0 m, longest 10.0 m), "
                    "57.2 m; ramps: 1 up (30 steps) (lower-back unit)")
    assert line in clinical_lines(waist, tmp_path)


def test_an_uncalibrated_slow_lower_back_gives_no_metres(tmp_path):
    # W446: an uncalibrated lower-back speed under 0.5 m/s is not given; its metres are not either
    waist = {"pipeline": "waist-pendulum", "n_steps": 204, "walking_time_s": 180.0, "distance_m": 26.1,
             "gait_speed_mps": 0.14, "info": {"params_source": "defaults"}}
    lines = [x for x in clinical_lines(waist, _folder(tmp_path, ramps=())) if x.startswith("- Walking:")]
    assert lines == ["- Walking: 204 steps, 180.0 s walking in 4 bouts (lower-back unit; distance not given: "
                     "uncalibrated lower back under the validated speed (W446))"]


def test_no_steps_no_line(tmp_path):
    assert walking_line({"pipeline": "plasys", "n_steps": 0}, tmp_path, "foot unit") is None
    assert walking_line({"pipeline": "plasys"}, tmp_path, "foot unit") is None
