"""Decision L489 (L488 not adopted): a foot track with many turns on the spot gets one line saying that those
strides' lengths depend on the tracked point and naming ``--reference-point``. Trial T2 finding 4: user 9423's
turn route read +7.48 % with no word. Fresh user 9579."""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd

from pdrlearn.displace.foot import FootDisplacement
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.turn_reference import MIN_TURN_STRIDES, TURN_SHARE, turn_reference_warning

TURNS = ("stand:2, straight:3, turn:90, straight:2, turn:-90, straight:3, turn:180, straight:3, stand:2, pivot:90, "
         "straight:2, turn:360, straight:2, stand:2")


def _table(turn_deg, gap=None):
    t = pd.DataFrame({"turn_angle_rad": np.radians(turn_deg), "length_m": 0.5})
    return t if gap is None else t.assign(gap_s=gap)


def test_the_line_needs_a_share_and_a_count_of_turning_strides():
    assert TURN_SHARE == 0.10 and MIN_TURN_STRIDES == 4
    lines: list[str] = []
    turn_reference_warning(_table([90, 0] * 4 + [0] * 32), "sensor", lines)  # 4 of 40: the share (4 episodes, L504)
    assert len(lines) == 1 and lines[0].startswith("4 turns on the spot (4 of 40 strides") and \
        "--reference-point heel" in lines[0] and "2.0 m = 10 %" in lines[0]
    lines.clear()
    turn_reference_warning(_table([90, 0] * 3 + [0] * 4), "heel", lines)  # 3: too few
    turn_reference_warning(_table([90, 0] * 4 + [0] * 33), "sensor", lines)  # 4 of 41: under a tenth
    turn_reference_warning(_table([90, 0] * 4 + [0] * 2, gap=[1.0] + [0.0] * 9), "sensor", lines)  # a gap row: 3
    assert lines == []
    turn_reference_warning(_table([-45, 0] * 4), "heel", lines)
    assert "--reference-point sensor" in lines[0]


def _warnings(route: str) -> list[str]:
    s = simulate_path(parse_route(route), UserProfile.from_seed(9579), rate_hz=100.0, seed=9579, scenario="route")
    logging.disable(logging.WARNING)
    try:
        return [w for w in get_pipeline("plasys")(s).info["warnings"] if "L489" in w]
    finally:
        logging.disable(logging.NOTSET)


def test_a_turn_route_warns_and_a_straight_walk_does_not():
    assert FootDisplacement().reference_point == "sensor"  # L488 not adopted
    assert len(_warnings(TURNS)) == 1
    assert _warnings("stand:2, straight:10, stand:2, straight:10, stand:2") == []
