"""Session 43, fixer FJ: W498 (amends W490 / L614) - a standard TUG with pivot turns stays a TUG on the default
foot + waist track (review R1 finding 1: the foot's turns.csv merged the about-turn, the walk back and the pivot
turn-to-sit into one turn of about 360 deg, so W490's "one about-turn first" failed and the TUG became a chair walk)."""

from __future__ import annotations

import logging

import pandas as pd

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.clinical import turn_table
from pdrlearn.track.evaluate import track_summary
from pdrlearn.track.trunk_tug import foot_strides, tug_contacts, tug_yaw_turns
from pdrlearn.waist.transfers import shape_turns
from pdrlearn.waist.tug_phases import tug_trial_table

PIVOT_TUG = "stand:2, sit:5, straight:3, pivot:180, straight:3, pivot:180, sit:5, stand:2"  # R1's reproducer


def test_shape_turns_kernel_w498():
    foot = pd.DataFrame({"start_s": [20.6], "end_s": [28.4], "angle_deg": [360.2]})
    yaw = [{"start_s": 20.0, "end_s": 23.8, "angle_deg": 180.9}, {"start_s": 24.0, "end_s": 24.5, "angle_deg": 30.0},
           {"start_s": 25.0, "end_s": 28.8, "angle_deg": 182.4}]
    walk = pd.DataFrame({"start_s": [18.0], "length_m": [1.2], "heading_rad": [0.0]})
    got = shape_turns(foot, walk, yaw)
    assert got["angle_deg"].tolist() == [180.9, 182.4]  # the waist's, under 80 deg left out (L200)
    assert shape_turns(foot, None, yaw) is foot  # a lower-back track keeps its turns.csv
    assert shape_turns(None, walk, yaw) is None  # not judged without a turns table (W490)


def test_a_pivot_tug_is_a_tug_on_the_two_unit_track_w498():
    logging.disable(logging.WARNING)
    try:
        s = simulate_path(parse_route(PIVOT_TUG), UserProfile.from_seed(12115), seed=12115, scenario="route")
        r = get_pipeline("plasys")(s)
    finally:
        logging.disable(logging.NOTSET)
    table = turn_table(r.steps, yaw_turns=r.info.get("yaw_turns"))
    m = track_summary(r, s, pipeline="plasys")
    assert m["n_chair_walks"] == 0 and m["n_tug_trials"] == 1, m["tug_time_note"]
    assert 10.0 < m["tug_trials_median_s"] < 20.0  # the route: rise, 2 x 3 m, two about-turns, sit
    trials = tug_trial_table(r.info["transfers"], table, tug_contacts(r), yaw_turns=tug_yaw_turns(r),
                             foot=foot_strides(r))
    assert len(trials) == 1 and trials["steps_source"].iloc[0] == "foot"
