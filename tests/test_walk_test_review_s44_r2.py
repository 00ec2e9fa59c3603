"""Review R2 (session 44) findings 1-5 on the timed corridor walk test and its rests (decisions L659-L662 and the
amendment of C178, fixer FK): a recording stopped at the test's end beep is complete (L659); L645 does not count
the walk back after an L517 short lap (L660); a given "go" outside the window is one error line (L661); a turn made
seated or riding stays a rest (L662); an explicit ``--per-align first-step`` starts the periods at the test's "go"
(C178 amended)."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io.meta_keys import unknown_meta_keys
from pdrlearn.report.time_course import rest_table
from pdrlearn.track.corridor import END_TOL_S, corridor_laps, corridor_line
from pdrlearn.track.rests import rest_seconds
from tests.walk_test_s44_helpers import strides, turns_at


def _stopped_at_the_beep(go_step: float = 30.8):
    """R2's k4: 4 m to the start cone, a turn, a wait; the first step 30.8 s (0.8 s after the spoken "go" at 30.0 s),
    30 m laps of 1 m strides, walked until the recording stops."""
    t = go_step + np.arange(359.0)
    return strides(np.concatenate([np.arange(4.0), t])), turns_at([4.5, *(go_step + np.arange(30, 359, 30))])


def test_a_recording_stopped_at_the_beep_is_a_complete_test_l659():
    steps, turns = _stopped_at_the_beep()
    _, s, warnings = corridor_laps(steps, turns, 30.0, duration_s=360.0, data_end=390.0)  # 0.8 s short of go + 360
    assert s["walk_test_start_s"] == pytest.approx(30.8)
    assert s["walk_test_duration_s"] == pytest.approx(360.0)
    # the sixth minute is counted; L740: its last lap is the 29 m recorded (L645 had snapped it to the cone's 30 m)
    assert s["walk_test_distance_per_minute_m"] == pytest.approx([60.0] * 5 + [59.0])
    assert s["fatigue_index"] == pytest.approx(59.0 / 60.0)
    assert not [w for w in warnings if "incomplete" in w]
    assert "incomplete" not in corridor_line(s) and "for 6:00;" in corridor_line(s)


def test_a_recording_that_ends_beyond_the_tolerance_stays_incomplete_l659():
    steps, turns = _stopped_at_the_beep()
    end = 30.8 + 360.0 - END_TOL_S - 1.0
    _, s, warnings = corridor_laps(steps, turns, 30.0, duration_s=360.0, data_end=end)
    assert s["walk_test_duration_s"] == pytest.approx(end - 30.8)
    assert len(s["walk_test_distance_per_minute_m"]) == 5
    assert len([w for w in warnings if "incomplete" in w and "L644" in w]) == 1


def test_the_walk_back_after_a_short_lap_is_no_corridor_lap_l660():
    """R2's k1: an untimed test, 3 laps of 30 m, a 4th turned back after 15 m (L517), 30 m walked back."""
    laps, s, warnings = corridor_laps(strides(np.arange(135.0)), turns_at([30, 60, 90, 105]), 30.0)
    assert [w for w in warnings if "L517" in w]
    assert s["n_laps"] == 3 and s["walk_test_distance_m"] == pytest.approx(135.0)
    last = laps.iloc[-1]
    assert last["corridor_laps"] == 0 and last["distance_source"] == "tracked x scale"


def test_a_final_lap_that_reaches_the_cone_still_counts_without_a_short_lap_l660():
    """L645's own case is kept: 3 laps and a final 29 m stretch (the test ended at the cone)."""
    laps, s, _ = corridor_laps(strides(np.arange(119.0)), turns_at([30, 60, 90]), 30.0)
    assert s["n_laps"] == 4 and laps.iloc[-1]["distance_source"] == "corridor"


def test_a_given_go_outside_the_window_is_an_error_l661():
    """R2's k2: a window 100-460 s holding a 6MWT from 100 s, a go of 12.5 s (meta.json / --walk-test-start)."""
    steps, turns = strides(100 + np.arange(360.0)), turns_at(100 + np.arange(30, 360, 30))
    with pytest.raises(DataError, match=r"12.5 s .*outside --window 100,460.*L661"):
        corridor_laps(steps, turns, 30.0, span=(100.0, 460.0), duration_s=360.0, start=12.5, data_end=600.0)
    _, s, _ = corridor_laps(steps, turns, 30.0, span=(100.0, 460.0), duration_s=360.0, start=100.0, data_end=600.0)
    assert s["walk_test_distance_m"] == pytest.approx(360.0)  # a go inside the window is taken


def test_a_go_after_the_recording_end_is_an_error_not_a_negative_test_l661():
    """R2's k1 "data_end < go" (API only): no walk_test_duration_s of -50 s."""
    with pytest.raises(DataError, match=r"150 s .*recording's end \(100.0 s\).*L661"):
        corridor_laps(strides(np.arange(200.0)), turns_at(np.arange(30, 200, 30)), 30.0, duration_s=120.0,
                      start=150.0, data_end=100.0)


def test_turns_made_seated_or_riding_are_rest_l662():
    """R2's k5: bouts 0-100 and 400-500 s at 100 steps/min; two carried turns in the gap (L622) and the walker's own
    turn 398-399 s: only the walker's turn, widened by a 0.6 s step each side, is left out of the 300 s gap."""
    bouts = pd.DataFrame({"start_s": [0.0, 400.0], "end_s": [100.0, 500.0], "cadence_spm": [100.0, 100.0]})
    turns = pd.DataFrame({"start_s": [150.0, 200.0, 398.0], "end_s": [160.0, 230.0, 399.0],
                          "angle_deg": [90.0, -180.0, 90.0], "carried": [True, True, False]})
    assert rest_seconds(0.0, 500.0, bouts, turns) == pytest.approx(300.0 - 1.0 - 2 * 0.6)
    table = rest_table(bouts, turns)
    assert len(table) == 1 and table["duration_s"].iloc[0] == pytest.approx(297.8)


ROUTE = ("stand:3, straight:4, turn:180, stand:12, straight:15, turn:180, straight:15, turn:180, straight:15, "
         "turn:180, straight:15, turn:180, straight:15, stand:3")


@pytest.fixture(scope="module")
def walk_to_start(tmp_path_factory):
    """User 12400 (R2's finding 5): 4 m to the start cone, a turn, 12 s standing, then 5 x 15 m."""
    ses = tmp_path_factory.mktemp("r2") / "s"
    assert main(["simulate", "--route", ROUTE, "--step-length", "0.5", "--step-time", "0.6", "--bounce",
                 "pendulum", "--user-seed", "12400", "--rate", "100", "--out", str(ses)]) == 0
    return ses


BASE = ["--units", "waist", "--corridor", "15", "--walk-test-duration", "60", "--no-plot"]


def test_an_explicit_first_step_starts_the_periods_at_go_c178(walk_to_start, tmp_path):
    for tag, extra in (("default", []), ("explicit", ["--per-align", "first-step"])):
        out = tmp_path / tag
        assert main(["track", str(walk_to_start), *BASE, "--per", "20s", *extra, "--out", str(out)]) == 0
        s = json.loads((out / "summary.json").read_text())
        assert s["walk_test_start_s"] > 20.0  # L642: after the wait at the start cone
        assert s["per_align"] == "first-step" and s["per_start_s"] == pytest.approx(s["walk_test_start_s"]), tag


def test_a_go_before_the_window_is_one_error_line_l661(walk_to_start, tmp_path, capsys):
    capsys.readouterr()
    assert main(["track", str(walk_to_start), *BASE, "--window", "20,90", "--walk-test-start", "5",
                 "--out", str(tmp_path / "o")]) != 0
    text = capsys.readouterr().err
    err = [x for x in text.splitlines() if x.startswith("error")]
    assert len(err) == 1 and "outside --window 20,90" in err[0] and "Traceback" not in text
    assert not (tmp_path / "o").exists()


def test_meta_json_walk_test_start_s_is_a_key_pdrlearn_reads_l642():
    """L642 reads meta.json ``walk_test_start_s``; B262's line called it "not read by pdrlearn (a typo ...)"."""
    assert unknown_meta_keys({"walk_test_start_s": 37.1, "walk_test_startt_s": 1.0}) == ["walk_test_startt_s"]
