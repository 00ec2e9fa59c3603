"""Session 51 (FE), trial s51t2 findings F1 / F3: each recording is scored for its own test (decision C249); the T25FW
starts at the body's first step, one step earlier when the unseen foot led (C250), and is the mean of two trials
(C251). Kernel-level, synthetic step tables."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.track.corridor import corridor_laps, too_short_note
from pdrlearn.track.own_test import is_walk_test_recording, own_test
from pdrlearn.track.walk_test import body_start, t25fw


def _walk(t0: float, n: int, heading: float, first_m: float, stride_m: float = 1.25, stride_s: float = 1.0):
    """``n`` foot strides from standing at ``t0``: the first ``first_m`` long (a half stride: the tracked foot led;
    a full one: the other foot led), the rest ``stride_m``; one stride per ``stride_s``."""
    rows = []
    for k in range(n):
        rows.append({"start_s": t0 + k * stride_s, "end_s": t0 + (k + 1) * stride_s,
                     "length_m": first_m if k == 0 else stride_m, "heading_rad": heading, "turn_angle_rad": 0.0})
    return rows


def _t25_recording(first_m: float, second_s: float = 1.0) -> pd.DataFrame:
    """A T25FW recording: two 10 m walks from standing, 20 s apart, the second back along the first (its strides
    ``second_s`` long)."""
    return pd.DataFrame(_walk(3.0, 9, 0.0, first_m) + _walk(25.0, 9, np.pi, first_m, stride_s=second_s))


@pytest.mark.parametrize("recorded, share, scored", [(40.0, 0.5, False), (200.0, 0.5, True), (40.0, None, True)])
def test_a_recording_under_half_the_test_is_no_walk_test_c249(recorded, share, scored):
    note = too_short_note(recorded, 360.0, share)
    assert (note is None) == scored
    if note:
        assert "not a 6MWT recording" in note and "decision C249" in note


def test_a_t25fw_recording_scores_no_6mwt_c249():
    steps = _t25_recording(0.62)
    turns = pd.DataFrame({"start_s": [13.0], "end_s": [24.0], "angle_deg": [180.0]})
    laps, out, lines = corridor_laps(steps, turns, 30.0, duration_s=360.0, start="first-step", data_end=40.0)
    assert out["walk_test_distance_m"] is None and laps.empty
    assert "decision C249" in out["walk_test_note"] and any("C249" in str(x) for x in lines)
    _, before, _ = corridor_laps(steps, turns, 30.0, duration_s=360.0, start="first-step", data_end=40.0,
                                 min_share=None)  # the rule before C249: two "laps" of 30 m
    assert before["walk_test_distance_m"] == pytest.approx(60.0)


def test_each_recording_keeps_its_own_test_c249():
    six = {"walk_test_protocol_s": 360.0, "walk_test_distance_m": 246.3, "t25fw_time_s": 8.2, "t25fw_speed_mps": 0.93,
           "t25fw_note": None, "ten_m_walk_time_s": 8.2, "ten_m_walk_speed_mps": 0.93, "ten_m_walk_note": None,
           "n_ten_m_walk_trials": 10, "ten_m_walk_max_speed_mps": 1.2, "n_t25fw_trials": 1,
           "t25fw_trial_times_s": [8.2]}
    assert is_walk_test_recording(six)
    _, lines = own_test(six)
    assert six["walk_test_distance_m"] == 246.3
    assert six["t25fw_time_s"] is None and six["ten_m_walk_time_s"] is None and six["n_ten_m_walk_trials"] == 0
    assert six["n_t25fw_trials"] == 0 and "decision C249" in six["t25fw_note"] and lines
    tug = {"walk_test_protocol_s": 360.0, "walk_test_distance_m": 61.8, "n_laps": 2, "fatigue_index": 0.9,
           "tug_time_s": 33.75}
    laps, lines = own_test(tug, pd.DataFrame({"lap": [1, 2]}))
    assert tug["walk_test_distance_m"] is None and tug["n_laps"] is None and laps.empty
    assert "TUG" in tug["walk_test_note"] and "C249" in tug["walk_test_note"]
    free = {"walk_test_protocol_s": None, "walk_test_distance_m": 60.0, "t25fw_time_s": 6.6}
    assert own_test(free) == (None, []) and free["t25fw_time_s"] == 6.6  # no duration: the test is not known


@pytest.mark.parametrize("first_m, earlier", [(0.62, 0.0), (1.25, 0.5)])
def test_the_t25fw_starts_one_step_earlier_when_the_unseen_foot_led_c250(first_m, earlier):
    steps = _t25_recording(first_m)
    assert body_start(steps, 0, 9, 3.0) == pytest.approx(3.0 - earlier)
    before, after = t25fw(steps, unseen_lead=False, n_mean=1), t25fw(steps)
    assert after["t25fw_trial_times_s"] == pytest.approx([t + earlier for t in before["t25fw_trial_times_s"]])
    lower_back = steps.assign(unit="waist")
    assert body_start(lower_back, 0, 9, 3.0) == 3.0  # the lower back: unchanged


def test_the_t25fw_is_the_mean_of_its_two_trials_c251():
    steps = _t25_recording(0.62, second_s=1.2)  # the second walk slower
    out = t25fw(steps)
    first, second = out["t25fw_trial_times_s"]
    assert out["n_t25fw_trials"] == 2 and second > first
    assert out["t25fw_time_s"] == pytest.approx((first + second) / 2)
    assert out["t25fw_speed_mps"] == pytest.approx(7.62 / out["t25fw_time_s"])
    assert "decision C251" in out["t25fw_note"]
    one = t25fw(steps.iloc[:9])
    assert one["n_t25fw_trials"] == 1 and one["t25fw_time_s"] == pytest.approx(first)


def test_the_change_line_names_the_recordings_of_each_measure_c252():
    from pdrlearn.report.clinical import change_lines

    def row(visit, name, **values):
        return ("track", name, f"P1/{visit}/{name}", {"subject": "P1", "visit": visit, "pipeline": "plasys", **values})

    rows = [row(v, n, **vals) for v, d, t in (("v1", 247.0, 6.6), ("v2", 213.0, 7.8)) for n, vals in (
        ("6mwt_left", {"walk_test_distance_m": d}), ("6mwt_right", {"walk_test_distance_m": d + 1.0}),
        ("t25_right", {"t25fw_time_s": t}))]
    (line,) = change_lines(rows)
    assert "walk test distance 248 -> 214 m (-34 m, -14 %) [from 6mwt_left, 6mwt_right; C252]" in line
    # C275: the T25FW is L387's first 7.62 m of a walk, said to be derived
    assert "T25FW (derived from the walk's first 7.62 m, L387) 6.6 -> 7.8 s (+1.2 s, +18 %) [from t25_right; C252]" \
        in line
    (alone,) = change_lines([r for r in rows if r[1] == "t25_right"])  # one session a visit: nothing to tell apart
    assert "C252" not in alone
