"""Decision W362 (session 34, trial T3 finding 5): L219's side-step line on the lower-back tracks names the sides
the strides went, not the median's side alone (a shuffle 4 m left then 4 m right read "to the right")."""

from __future__ import annotations

import logging

import numpy as np

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.sideways import side_ways


def test_side_ways_names_each_stretch_in_order():
    assert side_ways(np.array([90.0, 88, 92])) == "to the left"
    assert side_ways(np.array([-90.0, -88])) == "to the right"
    assert side_ways(np.array([90.0] * 10 + [-90.0] * 10)) == "10 to the left, then 10 to the right"


def test_a_left_then_right_shuffle_is_named_both_ways():
    logging.disable(logging.WARNING)
    try:
        s = simulate_path(parse_route("straight:5, side:4, side:-4, straight:5"), UserProfile.from_seed(7925),
                          rate_hz=20.0, seed=1, scenario="route")
        lines = [w for w in get_pipeline("waist-pendulum")(s).info["warnings"] if "decision L219" in w]
    finally:
        logging.disable(logging.NOTSET)
    assert len(lines) == 1
    assert "to the left, then" in lines[0] and "to the right" in lines[0].split("then")[1]
