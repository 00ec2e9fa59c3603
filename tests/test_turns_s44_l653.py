"""Decision L653 (trial T2, finding F6): a walking stride (steps.csv ``travel`` forward / backward, longer than the
thesis' 30 cm short step) is no "slower row" of a turn (L104): ``turn:180, straight:2, turn:90`` are two turns, not
one 271 deg turn (main: the 2 m stride between them was taken into the turn). The trial's user 21 (its
simulated walker makes the 2 m of ``straight:2`` after ``turn:180`` one stride, as in T2's vr10 session)."""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.clinical import WALK_MIN_STRIDE_M, turn_table, walking_rows


def _table(length_m, turn_deg):
    n = len(length_m)
    start = np.arange(n) * 1.4
    return pd.DataFrame({"start_s": start, "end_s": start + 1.3, "length_m": length_m,
                         "raw_length_m": length_m, "heading_rad": np.radians(np.cumsum(turn_deg)),
                         "turn_angle_rad": np.radians(turn_deg), "gap_s": 0.0, "sideways": False,
                         "unit": "foot"})


def test_a_walking_stride_ends_a_turn():
    # T2's vr10 rows 23-26: turn 120 + 60 deg, a 2.0 m forward stride, turn 90 deg; walking before and after
    st = _table([1.0, 1.0, 0.18, 0.12, 2.0, 0.17, 1.0, 1.0], [0, 0, 120, 60, 0.2, 90, 0, 0])
    t = turn_table(st)
    assert np.round(t["angle_deg"].to_numpy(float)).tolist() == [180.0, 90.0]  # main: one turn of 270 deg
    assert walking_rows(st).tolist() == [True, True, False, False, True, False, True, True]


def test_a_slow_small_step_inside_a_turn_stays_in_it():
    # L104's slower row: a 0.2 m step turning 10 deg (under the walk threshold) between two turning strides
    st = _table([1.0, 1.0, 0.18, 0.20, 0.17, 1.0, 1.0], [0, 0, 90, 10, 80, 0, 0])
    assert 0.20 < WALK_MIN_STRIDE_M
    assert np.round(turn_table(st)["angle_deg"].to_numpy(float)).tolist() == [180.0]


def test_a_simulated_turn_walk_turn_gives_two_turns():
    s = simulate_path(parse_route("straight:3, turn:180, straight:2, turn:90, straight:3"),
                      UserProfile.from_seed(21), speed="normal", rate_hz=50.0, seed=1, scenario="route")
    logging.disable(logging.WARNING)
    try:
        res = get_pipeline("plasys")(s)
    finally:
        logging.disable(logging.NOTSET)
    length = res.steps["length_m"].to_numpy(float)
    assert (length > 1.8).sum() == 1  # the single 2 m stride between the turns
    angles = np.abs(turn_table(res.steps)["angle_deg"].to_numpy(float))
    big = angles[angles >= 80]
    assert len(big) == 2 and (big < 200).all(), angles  # main: one turn of 271 deg
