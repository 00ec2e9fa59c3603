"""Decision C190 (trial T1 F6): clinical.md's session block of a one-foot + lower-back track gives the stair flights
(stairs.csv) and the step-time asymmetry with its standard error that the console printed, not only a `gait` pair's."""

from __future__ import annotations

import json

import pandas as pd

from pdrlearn.cli.common import asymmetry_clause
from pdrlearn.report.clinical import clinical_lines, clinical_markdown
from pdrlearn.report.stairs_asymmetry import asymmetry_line, stairs_line

#: trial T1's step-to stairs session tracked foot + lower back (`track stairs --toe-off --stair-rise 0.17`, user 4602)
FOOT_WAIST = {"pipeline": "plasys", "session": "stairs", "n_steps": 38, "n_steps_both_feet": 76,
              "n_steps_counts": "strides of the tracked foot", "walking_time_s": 49.59, "distance_m": 15.01,
              "n_flights_up": 1, "n_flights_down": 1, "n_stair_strides_up": 12, "n_stair_strides_down": 12,
              "step_time_asymmetry_pct": 31.433, "step_time_asymmetry_se_points": 5.624,
              "step_time_s_left": 0.5562, "step_time_s_right": 0.7636}
FLIGHTS = [{"flight": 1, "direction": "up", "n_strides": 12, "height_m": 2.038, "time_s": 16.002, "n_stairs": 12},
           {"flight": 2, "direction": "down", "n_strides": 12, "height_m": -2.050, "time_s": 13.746, "n_stairs": 12}]


def _track(folder, summary, flights=FLIGHTS):
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "summary.json").write_text(json.dumps(summary))
    if flights is not None:
        pd.DataFrame(flights).to_csv(folder / "stairs.csv", index=False)
    return folder


def test_the_stairs_session_block_has_its_flights_and_its_asymmetry(tmp_path):
    text = clinical_markdown(_track(tmp_path / "res" / "stairs", FOOT_WAIST).parent)
    assert ("- Stairs: 1 flight up (12 stairs, 2.04 m, 16.0 s, 45 stairs/min); 1 flight down (12 stairs, 2.05 m, "
            "13.7 s, 52 stairs/min) (foot unit)") in text
    assert ("- Step-time asymmetry 31.4 % (standard error 5.6 points, uncertain: over 3 points; right longer, "
            "0.556 / 0.764 s L/R) (foot + lower-back units)") in text


def test_flights_without_stair_rise_count_stair_strides_and_say_how_to_count_stairs(tmp_path):
    flights = [dict(f, n_stairs=None) for f in FLIGHTS] + [
        {"flight": 3, "direction": "up", "n_strides": 8, "height_m": 1.36, "time_s": 10.0, "n_stairs": None}]
    line = stairs_line(dict(FOOT_WAIST, n_flights_up=2), _track(tmp_path, FOOT_WAIST, flights), "foot unit")
    assert line == ("- Stairs: 2 flights up (20 stair strides, 3.40 m, 26.0 s, 46 stair strides/min); 1 flight down "
                    "(12 stair strides, 2.05 m, 13.7 s, 52 stair strides/min) (foot unit; stairs counted with track "
                    "--stair-rise METRES)")


def test_without_stairs_csv_the_summary_counts_stand(tmp_path):
    line = stairs_line(FOOT_WAIST, _track(tmp_path, FOOT_WAIST, flights=None), "foot unit")
    assert line == ("- Stairs: 1 flight up (12 stair strides); 1 flight down (12 stair strides) (foot unit; stairs "
                    "counted with track --stair-rise METRES)")


def test_no_flights_and_no_index_give_no_line(tmp_path):
    bare = {k: v for k, v in FOOT_WAIST.items() if not k.startswith(("n_flights", "step_time"))}
    lines = clinical_lines(bare, _track(tmp_path, bare, flights=None))
    assert not [x for x in lines if x.startswith(("- Stairs", "- Step-time"))]
    # a lower-back track has no flights (L440): its floors give no stairs line
    assert stairs_line({"pipeline": "waist-pendulum", "floors_up": 1, "floors_down": 1}, tmp_path,
                       "lower-back unit") is None


def test_the_index_words_are_the_consoles():
    small = dict(FOOT_WAIST, step_time_asymmetry_pct=2.3, step_time_asymmetry_se_points=1.4)
    assert "standard error 1.4 points, within noise;" in asymmetry_line(small, "foot unit")
    assert "standard error 1.4 points, within noise;" in asymmetry_clause(small)
    waist = {"pipeline": "waist-pendulum", "step_time_asymmetry_pct": 23.7, "step_time_s_left": 0.561,
             "step_time_s_right": 0.718}
    assert asymmetry_line(waist, "lower-back unit") == (
        "- Step-time asymmetry 23.7 % (its size is misread by the lower back alone (L121); right longer, 0.561 / "
        "0.718 s L/R) (lower-back unit)")
