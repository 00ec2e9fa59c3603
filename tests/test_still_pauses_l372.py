"""Decision L372 (session 33, trial T3 finding F5): a still stretch between two rows is standing, not a turn's
time: the pause, bout and walking-time rules (L119, L194) give a turn at most the time the unit was not still."""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd
import pytest

from experiments.still_pauses import before_l372
from pdrlearn.track.clinical import bout_rows, clinical_summary, pauses
from pdrlearn.track.gait import session_walking_pieces


def _foot(starts, turns_deg, length=1.17):
    starts = np.asarray(starts, dtype=float)
    return pd.DataFrame({"start_s": starts, "end_s": starts + length, "unit": "foot",
                         "turn_angle_rad": np.radians(turns_deg), "heading_rad": np.cumsum(np.radians(turns_deg))})


def test_a_foot_rest_between_two_turns_is_a_pause():
    # three turning strides, a 3.6 s rest, four turning strides back (trial T3's turns on the spot, one foot)
    st = _foot([8.82, 10.0, 11.17, 15.98, 17.15, 18.32, 19.49], [120, 120, 120, -60, -120, -120, -60])
    assert len(pauses(st)) == 1 and pauses(st)[0] > 1.0  # was: none (the next stride's 60 deg took 3 s at 20 deg/s)
    assert bout_rows(st) == [(0, 3), (3, 7)]
    pieces = session_walking_pieces(st)
    assert len(pieces) == 2  # the rest is no walking time (L194's bridge stops at the still stretch)
    # the same strides without the rest: no pause, one bout
    back = _foot(np.arange(7) * 1.17 + 8.82, [120, 120, 120, -60, -120, -120, -60])
    assert len(pauses(back)) == 0 and bout_rows(back) == [(0, 7)]


def test_a_lower_back_gap_holds_a_pause_only_where_the_pelvis_was_still():
    ev = np.r_[np.arange(9.14, 12.4, 0.6), np.arange(17.02, 20.2, 0.6)]
    heading = np.r_[np.linspace(0.0, 6.0, 6), np.linspace(4.7, -1.6, 6)]  # the second turn 73 deg on at its start
    st = pd.DataFrame({"start_s": ev, "end_s": np.r_[ev[1:], ev[-1]], "event_s": ev, "unit": "waist",
                       "heading_rad": heading})
    assert len(pauses(st)) == 0  # no still time known (an older steps.csv): L119 as it was, a slow turn
    still = st.assign(still_before_s=np.where(np.isclose(ev, 17.02), 3.6, 0.0))
    assert len(pauses(still)) == 1 and clinical_summary(still)["n_walking_bouts"] == 2
    with before_l372():  # the old switch's off branch, the experiment's "before" arm (L594: no switch)
        assert len(pauses(still)) == 0


@pytest.mark.parametrize("pipeline", ["plasys", "waist-pendulum"])
def test_standing_between_two_turns_on_the_spot_splits_the_bout(pipeline):
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route
    from pdrlearn.track.evaluate import evaluate_track
    from pdrlearn.track.plasys import track_plasys
    from pdrlearn.track.waist import track_waist

    logging.disable(logging.WARNING)
    try:
        s = simulate_path(parse_route("stand:3, turn:360, stand:3, turn:-360, stand:3"), UserProfile.from_seed(7163),
                          rate_hz=100.0, seed=0)
        res = track_plasys(s) if pipeline == "plasys" else track_waist(s, pipeline=pipeline)
        summary = evaluate_track(res, s)
    finally:
        logging.disable(logging.NOTSET)
    assert summary["n_pauses"] == 1 and summary["n_walking_bouts"] == 2  # was 0 and 1
    assert summary["walking_time_s"] < 10.0  # was 11.9 (foot) / 11.0 s (lower back): the stand counted as walking
    if pipeline == "waist-pendulum":
        assert res.steps["still_before_s"].max() > 2.5  # the 3 s stand between the turns, still
