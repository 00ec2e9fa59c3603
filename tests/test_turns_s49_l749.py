"""Decision L749 (trial s49t2 finding F5): a foot track's turns.csv gives the steps per turn - the lower back's
contacts inside the turn (widened to the waist's own yaw-rate turn) when the session has that unit, else 2 x the
foot's strides inside it, marked ``foot_x2`` - where ``turn_steps`` was empty and ``n_rows`` counted one foot."""

from __future__ import annotations

import numpy as np
import pandas as pd

#: a foot track's 360-degree turn, timed by its heading (5-95 %), as the trial's: 9.03-12.21 s
TURNS = pd.DataFrame({"turn": [1], "start_s": [9.03], "end_s": [12.21], "angle_deg": [360.0], "n_rows": [3]})
#: one foot's strides: contacts 9.73, 10.87, 12.00 s (the other foot between them)
FOOT = pd.DataFrame({"start_s": [8.9, 10.0, 11.2], "end_s": [10.0, 11.2, 12.3], "event_s": [9.73, 10.87, 12.00],
                     "unit": "foot"})
#: the lower back's contacts: the 7 steps of the turn, 9.15 .. 12.54 s (the closing step after the foot's end_s)
TRUNK = [{"start_s": t, "end_s": t + 0.57, "event_s": t} for t in (9.15, 9.73, 10.30, 10.87, 11.44, 12.00, 12.54)]
#: the waist's yaw-rate turn of that turn (El-Gohary's times), as the waist pipeline times it
YAW = [{"start_s": 8.26, "end_s": 12.87, "peak_s": 10.5, "angle_deg": 359.9, "peak_dps": 111.0}]


def test_foot_and_lower_back_count_the_lower_backs_contacts_in_the_waists_turn():
    from pdrlearn.track.clinical import add_turn_steps

    out = add_turn_steps(TURNS, FOOT, {"trunk_contacts": TRUNK, "trunk_yaw_turns": YAW})
    assert out["turn_steps"].tolist() == [7] and out["turn_steps_source"].tolist() == ["waist"]
    # without the waist's yaw-rate turn the foot's 5-95 % times cut the closing step
    assert add_turn_steps(TURNS, FOOT, {"trunk_contacts": TRUNK})["turn_steps"].tolist() == [6]
    # a yaw-rate turn of the other sign is not this turn's (L210's match)
    other = [{**YAW[0], "angle_deg": -359.9}]
    assert add_turn_steps(TURNS, FOOT, {"trunk_contacts": TRUNK, "trunk_yaw_turns": other})["turn_steps"].tolist() \
        == [6]


def test_a_foot_alone_estimates_twice_its_strides_and_says_so():
    from pdrlearn.track.clinical import add_turn_steps

    out = add_turn_steps(TURNS, FOOT, {})
    assert out["turn_steps"].tolist() == [6] and out["turn_steps_source"].tolist() == ["foot_x2"]
    assert out["n_rows"].tolist() == [3]  # n_rows unchanged
    # pdrlearn run's foot strides carry no contact time: no count rather than a guess
    run = add_turn_steps(TURNS, FOOT.assign(event_s=float("nan")), {})
    assert run["turn_steps"].isna().all() and run["turn_steps_source"].tolist() == [""]


def test_a_lower_back_track_is_unchanged_and_an_empty_table_keeps_its_columns():
    from pdrlearn.track.clinical import add_turn_steps

    waist = pd.DataFrame({"start_s": [t["start_s"] for t in TRUNK], "end_s": [t["end_s"] for t in TRUNK],
                          "event_s": [t["event_s"] for t in TRUNK], "unit": "waist"})
    out = add_turn_steps(TURNS, waist)
    assert out["turn_steps"].tolist() == [6] and out["turn_steps_source"].tolist() == ["waist"]  # W398's span
    empty = add_turn_steps(TURNS.iloc[:0], FOOT, {})
    assert list(empty.columns[-2:]) == ["turn_steps", "turn_steps_source"] and len(empty) == 0
    assert add_turn_steps(TURNS.assign(end_s=np.nan), FOOT, {})["turn_steps"].tolist() == [0]  # no end: 0 (W398)
