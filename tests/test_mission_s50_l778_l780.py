"""Session 50, FK (trial s50t1 findings F7, F10): L778 steps in place are no slow walk for L95's line; L779 the
automatic walk tests are timed only on a recording that looks like a walk test; W589 L182's compass check leaves out
steps in place; L780 `export` of a runtime bundle says what it is and how to make one's own."""

from __future__ import annotations

import inspect
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli.export import bundle_refusal
from pdrlearn.track import plasys
from pdrlearn.track.gait import gait_range_warning, steps_in_place
from pdrlearn.track.walk_test import free_recording_note, t25fw, ten_metre_walk, ten_metre_walk_trials

SHUFFLE = {"median_cadence_spm": 92.7, "median_speed_straight_mps": 0.0137, "n_straight_strides": 36,
           "median_speed_mps": 0.0099, "gait_speed_mps": 0.34, "leg_length_m": 0.85}  # trial s50t1 shuffle_u17330


def test_steps_in_place_judge_no_speed_l778():
    assert steps_in_place(SHUFFLE) and gait_range_warning(SHUFFLE) is None  # before L778: "... 0.01 m/s: slower"
    slow = {**SHUFFLE, "median_speed_straight_mps": 0.30}  # a 0.39 m stride: a slow walk, still judged
    assert not steps_in_place(slow)
    assert "straight-walking speed 0.30 m/s: this is slower" in gait_range_warning(slow)
    assert not steps_in_place(SHUFFLE, in_place_stride_m=0.01)  # the bound is the keyword's
    slow_steps = {**SHUFFLE, "median_cadence_spm": 50.0}  # in place and a cadence under the range: still said
    assert "median cadence 50 steps/min" in gait_range_warning(slow_steps)
    assert "m/s" not in gait_range_warning(slow_steps).split(":")[0]


def _walk(t0: float, metres: float, step: float = 1.0, dz: float = 0.0) -> list[dict]:
    n = int(round(metres / step))
    return [{"start_s": t0 + i, "end_s": t0 + i + 1, "event_s": t0 + i + 1, "length_m": step, "heading_rad": 0.0,
             "turn_angle_rad": 0.0, "dz_m": dz} for i in range(n)]


def _recording(*bouts: tuple[float, float, float]) -> pd.DataFrame:
    """(metres, stride length, dz) per bout, 10 s pauses between them."""
    rows, t = [], 3.0
    for metres, step, dz in bouts:
        rows += _walk(t, metres, step, dz)
        t = rows[-1]["end_s"] + 10.0
    return pd.DataFrame(rows)


def test_walk_tests_only_on_a_test_like_recording_l779():
    level = _recording((16.0, 1.0, 0.0), (16.0, 1.0, 0.0))  # two walkway passes: timed as before
    assert ten_metre_walk(level)["ten_m_walk_time_s"] == pytest.approx(10.0)
    # C250: a first row as long as the next (a full stride: the unseen foot led) starts the walk half a stride earlier
    assert len(ten_metre_walk_trials(level)) == 2 and t25fw(level)["t25fw_time_s"] == pytest.approx(7.62 + 0.5)
    mission = _recording((16.0, 1.0, 0.0), (3.0, 0.3, 0.34), (16.0, 1.0, 0.0))  # a flight of 10 stair strides
    got, t25 = ten_metre_walk(mission), t25fw(mission)
    assert got["ten_m_walk_time_s"] is None and got["n_ten_m_walk_trials"] == 0 and t25["t25fw_time_s"] is None
    assert "walking bout 2 holds a stair flight" in got["ten_m_walk_note"] and "L779" in t25["t25fw_note"]
    before = ten_metre_walk(mission, any_recording=True)  # the rule before L779 timed the first level pass
    assert before["ten_m_walk_time_s"] == pytest.approx(10.0) and before["n_ten_m_walk_trials"] == 2
    declared = ten_metre_walk(mission, (2.0, 10.0, 2.0))  # a declared walkway is timed as before
    assert declared["ten_m_walk_time_s"] == pytest.approx(10.0) and t25fw(mission, walkway=True)["t25fw_time_s"]
    # a bout over L552's 100 m is L552's alone: not timed, the recording's walkway pass still is (review R2 F1)
    long_walk = _recording((16.0, 1.0, 0.0), (120.0, 1.0, 0.0))
    assert ten_metre_walk(long_walk)["ten_m_walk_time_s"] == pytest.approx(10.0)


def test_free_recording_note_reads_no_bout_length_l781():
    """L781 (session 51, I4): L779's note takes no ``max_bout_m`` (its >100 m clause was dropped at session 50's
    merge, the argument was unused); a level recording with a bout over 100 m is no mission for it, L552 refuses
    that bout alone."""
    assert "max_bout_m" not in inspect.signature(free_recording_note).parameters
    long_walk = _recording((16.0, 1.0, 0.0), (120.0, 1.0, 0.0))
    assert free_recording_note(long_walk, 10.0) is None
    trials = ten_metre_walk_trials(long_walk)
    assert len(trials) == 1 and "far longer than a walkway" in ten_metre_walk(_recording((120.0, 1.0, 0.0)))[
        "ten_m_walk_note"]
    mission = _recording((16.0, 1.0, 0.0), (3.0, 0.3, 0.34))
    assert "walking bout 2 holds a stair flight" in free_recording_note(mission, 10.0)


def test_compass_check_leaves_out_steps_in_place_w589(monkeypatch):
    seen = []
    monkeypatch.setattr(plasys, "stride_level_field", lambda session, strides, keep: seen.append(keep.copy()))
    keep = np.ones(6, bool)
    lengths = np.array([1.2, 0.02, 0.01, 1.3, 0.09, 0.11])
    assert plasys.compass_check(None, None, np.zeros(6), keep, lengths=lengths) == (None, None)
    assert seen[-1].tolist() == [True, False, False, True, False, True]
    plasys.compass_check(None, None, np.zeros(6), keep, lengths=lengths, in_place_stride_m=None)  # the rule before
    assert seen[-1].all()


def test_export_of_the_shipped_bundle_says_what_it_is_l780(tmp_path):
    bundle = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"
    line = bundle_refusal(bundle)
    assert "a 20 Hz runtime bundle" in line and "an exported runtime bundle" in line
    assert f"pdrlearn run {bundle} SESSION" in line and "pdrlearn train SESSION... --out models/u1" in line
    assert "docs/decisions/localization.md L780" in line
    assert bundle_refusal(tmp_path) is None  # no manifest: the model directory's own checks follow
