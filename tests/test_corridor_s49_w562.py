"""Decisions W562, W563, C217, C218 (session 49, FC, trial s49t1 findings F2 / F3): a lower-back corridor walk test
puts the step lengths on the corridor's scale (gait speed, periods), and the rests inside a timed test are counted
and named, also where they drive the fatigue index."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.report.clinical import change_lines, gait_speed_line, walk_test_pace_line, walk_test_rests_line
from pdrlearn.report.time_course import time_course_section
from pdrlearn.track.corridor import (
    corridor_gait_speed,
    corridor_laps,
    fatigue_rest_text,
    lap_metres,
    lap_scale,
    own_corridor_line,
    rests_text,
)
from pdrlearn.track.periods import with_corridor_scale
from pdrlearn.track.rests import window_rests

REST_AT, REST_S = 45, 20.0


def _waist_walk(rows: int = 135, step_m: float = 0.8) -> pd.DataFrame:
    """A lower-back table of 1 s steps of ``step_m`` tracked metres, laps of 30 steps (24 m tracked on a 30 m
    corridor), standing REST_S seconds after step REST_AT."""
    t = np.arange(rows, dtype=float)
    t[REST_AT:] += REST_S
    heading = np.where((np.arange(rows) // 30) % 2 == 0, 0.0, np.pi)
    return pd.DataFrame({"start_s": t, "end_s": t + 1.0, "event_s": t + 1.0, "length_m": step_m,
                         "heading_rad": heading, "unit": "waist"})


def _turns(width: float) -> pd.DataFrame:
    mids = np.array([30.0, 80.0, 110.0, 140.0])  # between steps 29/30, 59/60, ... (after the rest: + REST_S)
    return pd.DataFrame({"start_s": mids - width / 2, "end_s": mids + width / 2, "angle_deg": 180.0})


BOUTS = pd.DataFrame({"start_s": [0.0, REST_AT + REST_S], "end_s": [float(REST_AT), 155.0],
                      "cadence_spm": [60.0, 60.0]})


def test_lap_scale_counts_the_cone_arc():
    """W562: corridor / (median lap - the cone arc); under 2 laps or no length left: none."""
    assert lap_scale([24.0, 24.0, 25.0], 0.0, 30.0) == pytest.approx(1.25)
    assert lap_scale([24.0, 24.0], 0.8, 30.0, first_stretch=False) == pytest.approx(30.0 / 23.2)
    assert lap_scale([24.0], 0.0, 30.0) is None and lap_scale([0.5, 1.0], 1.0, 30.0) is None
    assert corridor_gait_speed({"gait_speed_mps": 0.8, "walk_test_scale": 1.25}) == pytest.approx(1.0)
    assert corridor_gait_speed({"gait_speed_mps": 0.8}) is None


def test_the_first_stretch_holds_half_an_arc():
    """Review R2 F1: the stretch from the first step to the first turn's middle holds half a cone arc, the laps
    between two turns a whole one: with exactly 2 laps of an exact track the scale is 1 (main: 1.0191), and C207's
    own corridor length (the same metres) is the corridor's."""
    first, inner = 20.0 + 1.5 / 2, 20.0 + 1.5
    for laps in ([first, inner], [first, inner, inner]):
        assert lap_scale(laps, 1.5, 20.0) == pytest.approx(1.0)
    assert lap_metres([first, inner], 1.5).tolist() == [20.0, 20.0]
    assert own_corridor_line(np.array([first, inner, 5.0]), 1.5, 20.0, 0.01) is None  # main: -1.9 %, a line
    assert "C207" in own_corridor_line(np.array([first, inner, 5.0]), 1.5, 19.0, 0.01)


def test_corridor_laps_give_the_scale_on_the_lower_back_only():
    """W562: walk_test_scale from the laps between cone turns less C181's arc (the metres inside a cone turn); a
    foot track keeps its step lengths."""
    _, on_spot, _ = corridor_laps(_waist_walk(), _turns(0.0), 30.0, BOUTS)
    _, arcs, _ = corridor_laps(_waist_walk(), _turns(1.0), 30.0, BOUTS)
    assert on_spot["walk_test_scale"] == pytest.approx(1.25)
    assert arcs["walk_test_scale"] == pytest.approx(30.0 / (24.0 - 0.8))  # 1 s of the turn walked: 0.8 m of arc
    _, foot, _ = corridor_laps(_waist_walk().assign(unit="foot"), _turns(0.0), 30.0, BOUTS)
    assert "walk_test_scale" not in foot


def test_rests_inside_the_timed_test_only():
    """C217: the L647 rests inside the test's window; one that lies after the test's end (or under 1 s inside it)
    is no rest of the test; an untimed corridor walk has no rest keys."""
    _, s, _ = corridor_laps(_waist_walk(), _turns(0.0), 30.0, BOUTS, duration_s=120.0, start="first-step")
    assert s["walk_test_n_rests"] == 1 and s["walk_test_rest_time_s"] == pytest.approx(REST_S)
    assert s["walk_test_rests"] == [[pytest.approx(45.0), pytest.approx(REST_S)]]
    assert window_rests(BOUTS, _turns(0.0), 0.0, 40.0) == []
    assert window_rests(BOUTS, _turns(0.0), 0.0, REST_AT + 0.5) == []
    assert window_rests(BOUTS, _turns(0.0), 50.0, 150.0) == [(50.0, pytest.approx(15.0))]
    assert "walk_test_n_rests" not in corridor_laps(_waist_walk(), _turns(0.0), 30.0, BOUTS)[1]
    assert rests_text(s) == "Rests during the test: 1 (20 s at 0:45; 20 s in all, C217)"
    assert rests_text({"walk_test_rests": []}) == "Rests during the test: none (C217)"


def test_the_fatigue_index_names_a_rest_in_its_minutes():
    """C218: a rest in the first or last full minute drives the fatigue index, and the lines say so; a rest in a
    middle minute does not."""
    _, s, _ = corridor_laps(_waist_walk(), _turns(0.0), 30.0, BOUTS, duration_s=120.0, start="first-step")
    # the rest (45-65 s) reaches into minute 2, the last of two
    assert fatigue_rest_text(s) == "a 20 s rest at 0:45 (minute 1 and 2) drives it, not slowing (C218)"
    assert "fatigue index 1.22 (last / first full minute): a 20 s rest at 0:45" in walk_test_pace_line(s)
    first = {**s, "walk_test_distance_per_minute_m": [40.0, 60.0, 60.0], "walk_test_rests": [[10.0, 20.0]]}
    assert fatigue_rest_text(first) == "a 20 s rest at 0:10 (minute 1) drives it, not slowing (C218)"
    middle = {**s, "walk_test_distance_per_minute_m": [60.0, 40.0, 60.0], "walk_test_rests": [[70.0, 20.0]]}
    assert fatigue_rest_text(middle) is None
    assert walk_test_rests_line(s) == "  - Rests during the test: 1 (20 s at 0:45; 20 s in all, C217)"


def test_gait_speed_line_and_periods_on_the_corridors_scale(tmp_path):
    """W562: clinical.md's gait speed is the corridor-scaled one, the step lengths' beside it; W563: periods.csv's
    corridor columns."""
    summary = {"gait_speed_mps": 0.85, "median_cadence_spm": 100.0, "walk_test_distance_m": 340.0,
               "walk_test_scale": 1.15, "gait_speed_corridor_mps": 0.9775}
    line = gait_speed_line(summary, "lower-back unit")
    assert line.startswith("- Gait speed 0.98 m/s on the corridor's scale") and "alone 0.85 m/s" in line
    assert gait_speed_line({k: summary[k] for k in ("gait_speed_mps", "median_cadence_spm")},
                           "lower-back unit").startswith("- Gait speed 0.85 m/s, cadence")
    periods = pd.DataFrame({"distance_m": [50.0, 20.0], "time_walking_s": [60.0, 0.0]})
    out = with_corridor_scale(periods, 1.15)
    assert list(out["distance_corridor_m"]) == pytest.approx([57.5, 23.0])
    assert out["speed_corridor_mps"].iloc[0] == pytest.approx(57.5 / 60.0) and np.isnan(out["speed_corridor_mps"][1])
    folder = tmp_path / "track"
    folder.mkdir()
    out.assign(period=[1, 2], start_s=[0.0, 60.0], end_s=[60.0, 120.0], duration_s=60.0).to_csv(
        folder / "periods.csv", index=False)
    section = time_course_section(folder, "track")  # W563: the report's Time course table shows them
    assert {"distance_corridor_m", "speed_corridor_mps"} <= set(section.tables[0][1].columns)


def test_change_from_baseline_compares_the_corridor_scaled_gait_speed():
    """W562: clinical.md's change line compares gait_speed_corridor_mps between visits."""
    rows = [("track", None, f"P01_{v}", {"subject": "P01", "visit": v, "pipeline": "waist-pendulum",
                                         "walk_test_distance_m": d, "gait_speed_corridor_mps": g})
            for v, d, g in (("pre", 288.0, 0.85), ("post", 340.0, 1.01))]
    line = change_lines(rows)[0]
    assert "gait speed (corridor's scale, W562) 0.85 -> 1.01 m/s (+0.16 m/s" in line
