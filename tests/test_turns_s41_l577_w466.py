"""Decision L577 (trial T1, finding F1): a foot turn ends at a pause, a bout boundary or a rest of the tracked foot
clearly longer than its usual rest, so two same-direction turns on the spot with a rest between them are two turns
(main: one 720 deg turn of 14.96 s, ``bout`` 1 for a turn ending in bout 2). Decision W466 (finding F3): the
lower back's sustained-reversal cut, an option (its adoption rule was not met on waist-pll). Fresh users 11514,
11516."""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.bouts import detected_bouts
from pdrlearn.track.clinical import foot_turn_stops, pauses, split_sustained_reversals, turn_rows, turn_table


def _foot(turns_deg, starts, stride_s=1.4):
    """A foot table: one stride a row, starting at ``starts`` (s), each ``stride_s`` long, own turn ``turns_deg``."""
    starts = np.asarray(starts, float)
    own = np.radians(np.asarray(turns_deg, float))
    return pd.DataFrame({"start_s": starts, "end_s": starts + stride_s, "turn_angle_rad": own,
                         "heading_rad": np.cumsum(own), "length_m": 0.13, "gap_s": 0.0, "unit": "foot"})


def _two_turns_on_the_spot(rest_s):
    """Walk 3 strides, turn 360 deg in 3 strides, stand ``rest_s``, turn 360 deg again, walk 3 strides (T1's F1)."""
    t, starts = 0.0, []
    for k in range(12):
        starts.append(t)
        t += 1.4 + 0.1 + (rest_s if k == 5 else 0.0)
    return _foot([0, 0, 0, 120, 120, 120, 120, 120, 120, 0, 0, 0], starts)


@pytest.mark.parametrize("rest_s", [5.0, 1.5])
def test_two_same_way_turns_on_the_spot_with_a_rest_between_are_two(rest_s):
    st = _two_turns_on_the_spot(rest_s)
    assert (len(pauses(st)) == 1) == (rest_s == 5.0)  # 1.5 s: no L104 pause (L119's turn allowance), a rest gap
    angles, _ = turn_rows(st)
    assert np.round(angles).tolist() == [360.0, 360.0]  # main: [720.0]
    tt = turn_table(st, detected_bouts(st))
    assert len(tt) == 2 and tt["end_s"].iloc[0] <= tt["start_s"].iloc[1]
    if rest_s == 5.0:  # the bouts are the pause's: the second turn is in bout 2 (main: 1)
        assert tt["bout"].tolist() == [1, 2]


def test_a_slow_walkers_long_rests_do_not_split_a_turn():
    """The rest gap is judged against the foot's usual rest (as L104's pause against the rhythm): a slow turn on the
    spot whose strides all rest 1.2 s stays one turn."""
    st = _foot([0, 0, 60, 60, 60, 0, 0], 2.6 * np.arange(7))
    assert not foot_turn_stops(st)[1:4].any()  # the turn's intervals (L500 makes the straight ones pauses)
    assert np.round(turn_rows(st)[0]).tolist() == [180.0]


def test_the_stops_are_a_foot_tables_only():
    st = _two_turns_on_the_spot(5.0).assign(unit="waist")
    assert not foot_turn_stops(st).any()


@pytest.mark.parametrize("streaming", [False, True])
def test_simulated_turns_on_the_spot_across_a_stand(streaming):
    """T1's F1 route on a fresh slow user: two 360 deg turns, in bouts 1 and 2, offline and streamed."""
    route = "stand:2, straight:3, turn:360, stand:5, turn:360, straight:3, stand:2"
    s = simulate_path(parse_route(route), UserProfile.from_seed(11514), speed="slow", rate_hz=20.0, seed=0,
                      scenario="route")
    logging.disable(logging.WARNING)
    try:
        res = get_pipeline("plasys")(s, streaming=streaming)
    finally:
        logging.disable(logging.NOTSET)
    tt = res.turns()
    assert len(tt) == 2, tt  # main: one 720 deg turn
    assert np.abs(tt["angle_deg"].to_numpy() - 360.0).max() < 20.0
    assert tt["bout"].tolist() == [1, 2]
    assert (tt["duration_s"] < 6.0).all()  # main: 14.7 s


def test_sustained_reversal_cut_kernel():
    dh = np.r_[np.full(18, 20.0), np.full(18, -20.0)]  # a figure of eight's two loops, one run of net 0 deg
    assert split_sustained_reversals(dh, 0, dh.size) == [(0, 18), (18, 36)]
    wobble = np.r_[np.full(9, 20.0), [-30.0, -30.0], np.full(9, 20.0)]  # 60 deg back: under a turn's 80 deg
    assert split_sustained_reversals(wobble, 0, wobble.size) == [(0, 20)]


def test_sustained_reversal_is_an_option_on_the_lower_back():
    """W466: a lower-back figure of eight (one turning run, net ~0 deg) gives its two loops with
    ``sustained=True``; the default (rule not met) keeps L370's runs: no turn."""
    dh = np.radians(np.r_[0.0, np.full(18, 20.0), np.full(18, -20.0), 0.0])
    st = pd.DataFrame({"start_s": 0.7 * np.arange(dh.size), "heading_rad": np.cumsum(dh), "unit": "waist"})
    assert len(turn_table(st)) == 0
    tt = turn_table(st, sustained=True)
    assert np.round(tt["angle_deg"]).tolist() == [360.0, -360.0]
