"""Decision L739 (session 49, FB, trial s49t1 finding F4): on a lower-back table an auto "go" is the first contact
less 1.4 step times (gait initiation comes before the first heel strike), not before the previous row's end; a foot
table, ``first-step`` and a given time are unchanged."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.track.corridor import LB_GO_STEPS, corridor_laps
from tests.walk_test_s44_helpers import laps_after, strides, turns_at


def _walk(unit: str, wait: bool):
    """9 laps of 30 one-second rows from 40 s; with ``wait`` 4 rows to the start cone first (0-4 s), a turn and a
    36 s standstill (L642's wait for "go")."""
    t, cones = laps_after(40.0, 9)
    before = np.arange(4.0) if wait else np.array([])
    return strides(np.concatenate([before, t]), unit=unit), turns_at([*([4.5] if wait else []), *cones])


@pytest.mark.parametrize("wait", [False, True])
def test_the_lower_backs_go_is_its_first_contact_less_1_4_step_times_l739(wait):
    steps, turns = _walk("waist", wait)
    _, s, warnings = corridor_laps(steps, turns, 30.0, duration_s=270.0)
    assert s["walk_test_start_s"] == pytest.approx(40.0 - LB_GO_STEPS * 1.0) == pytest.approx(38.6)
    line = [w for w in warnings if "L642" in w]
    assert (len(line) == 1 and "started at 38.6 s (its first contact 40.0 s less 1.4 step times, L739)" in line[0]
            ) if wait else line == []
    # L516's first step and a given time stay as they are
    assert corridor_laps(steps, turns, 30.0, duration_s=270.0, start="first-step")[1]["walk_test_start_s"] == (
        0.0 if wait else 40.0)
    assert corridor_laps(steps, turns, 30.0, duration_s=270.0, start=40.5)[1]["walk_test_start_s"] == 40.5


def test_the_foot_and_a_go_right_after_a_row_are_unchanged_l739():
    steps, turns = _walk("foot", False)
    assert corridor_laps(steps, turns, 30.0, duration_s=270.0)[1]["walk_test_start_s"] == 40.0
    # a lower-back go 0.5 s after the previous row's end is dated no earlier than that end (nor before 0 s)
    t, cones = laps_after(0.5, 9)
    lb = strides(t, unit="waist")
    assert corridor_laps(lb, turns_at(cones), 30.0, duration_s=270.0)[1]["walk_test_start_s"] == 0.0


def test_a_timed_tests_last_partial_lap_is_not_snapped_to_the_cone_l740():
    """Decision L740: 8 laps and 29.5 of the 9th 30 m lap when the timer ends (trial s49t1's P06_post: 11 laps +
    29.56 m read 12 laps): a timed test's final stretch is a partial lap (main: 9 laps, 270 m); with a --window
    ending there (L645's own case) it still counts as a lap."""
    t, cones = laps_after(0.0, 9)
    steps, turns = strides(t), turns_at(cones[:8])
    laps, s, _ = corridor_laps(steps, turns, 30.0, duration_s=269.5, start=0.0)
    assert s["n_laps"] == 8 and s["walk_test_distance_m"] == pytest.approx(269.5)
    assert laps["corridor_laps"].iloc[-1] == 0 and laps["distance_source"].iloc[-1] == "tracked x scale"
    assert corridor_laps(steps, turns, 30.0, span=(0.0, 269.5))[1]["n_laps"] == 9
