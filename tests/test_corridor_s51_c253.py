"""Decision C253 (session 51, FF; trial s51t2 finding F7): the time from an estimated "go" (auto, L739's first
contact dated back 1.4 step times; first-step) to the first step is no rest of the timed test, so C218 names no
"rest at 0:00"; a given "go" keeps the wait after it."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.track.corridor import corridor_laps, fatigue_rest_text, rest_window_start

SHIFT, REST_AT, REST_S = 10.0, 45, 20.0


def _walk() -> pd.DataFrame:
    """A lower-back table of 1 s steps of 0.8 m from SHIFT s on (laps of 30 steps on a 30 m corridor), standing
    REST_S seconds after step REST_AT."""
    t = np.arange(135, dtype=float)
    t[REST_AT:] += REST_S
    t += SHIFT
    heading = np.where((np.arange(135) // 30) % 2 == 0, 0.0, np.pi)
    return pd.DataFrame({"start_s": t, "end_s": t + 1.0, "event_s": t + 1.0, "length_m": 0.8,
                         "heading_rad": heading, "unit": "waist"})


TURNS = pd.DataFrame({"start_s": np.array([30.0, 80.0, 110.0, 140.0]) + SHIFT, "end_s": np.array(
    [30.0, 80.0, 110.0, 140.0]) + SHIFT, "angle_deg": 180.0})
BOUTS = pd.DataFrame({"start_s": [SHIFT, SHIFT + REST_AT + REST_S], "end_s": [SHIFT + REST_AT, SHIFT + 155.0],
                      "cadence_spm": [60.0, 60.0]})


def test_the_gap_before_the_first_step_of_an_estimated_go_is_no_rest_c253():
    _, s, _ = corridor_laps(_walk(), TURNS, 30.0, BOUTS, duration_s=120.0, start="auto")
    go = s["walk_test_start_s"]
    assert go == pytest.approx(SHIFT - 1.4)  # L739: the first contact less 1.4 step times
    # C217 / C218 before C253: [[0.0, 1.4], [46.4, 20.0]], "a 1 s rest at 0:00 (minute 1) ..."
    assert s["walk_test_rests"] == [[pytest.approx(SHIFT + REST_AT - go), pytest.approx(REST_S)]]
    assert s["walk_test_n_rests"] == 1 and s["walk_test_rest_time_s"] == pytest.approx(REST_S)
    assert "0:00" not in (fatigue_rest_text(s) or "")
    assert rest_window_start(_walk(), go, "auto") == SHIFT and rest_window_start(_walk(), go, "first-step") == SHIFT


def test_a_given_go_keeps_the_wait_after_it_c253():
    _, s, _ = corridor_laps(_walk(), TURNS, 30.0, BOUTS, duration_s=120.0, start=SHIFT - 3.0)
    assert s["walk_test_rests"][0] == [0.0, pytest.approx(3.0)]  # a real "go", 3 s before the first step
    assert fatigue_rest_text(s).startswith("a 3 s rest at 0:00 (minute 1)")
    assert rest_window_start(_walk(), 4.0, 4.0) == 4.0
