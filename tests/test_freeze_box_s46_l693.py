"""Decision L693 (session 46, trial T2 finding F4): a freeze-index episode whose every window holds part of a
side-stepping stride, with no other stride inside it, is a side shuffle's echo (the box step's false freeze)."""

from __future__ import annotations

import logging

import pandas as pd

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.freezes import SIDE_REACH_S, foot_freezes, side_echo, side_step_freezes

BOX = ("stand:3, straight:1.2, side:0.8, backward:2, side:-0.8, straight:1.2, side:0.8, backward:2, side:-0.8, "
       "stand:3")
# T2's box session's last strides (scratch_T2/tr/box/steps.csv): backward, then two side steps, then standing
STEPS = pd.DataFrame({"start_s": [26.084, 28.434, 29.854], "end_s": [27.536, 29.846, 31.256],
                      "sideways": [False, True, True], "unit": "foot"})


def test_the_reach_is_half_a_window_less_half_a_step():
    assert SIDE_REACH_S == 1.75  # Baechlin et al. 2010's 4 s windows every 0.5 s, centred


def test_an_episode_read_from_side_steps_only_is_an_echo():
    a, b = [28.434, 29.854], [29.846, 31.256]
    assert side_echo(30.75, 32.25, a, b, [26.084], [27.536])
    assert not side_echo(30.75, 33.25, a, b, [26.084], [27.536])  # a window past the side steps' reach
    assert not side_echo(30.75, 32.25, a, b, [31.3], [32.0])  # a forward stride inside the episode
    assert not side_echo(30.75, 32.25, [], [], [26.084], [27.536])


def test_the_box_steps_episode_is_left_out_with_a_line():
    rows = [{"freeze": 1, "start_s": 30.75, "end_s": 32.25, "duration_s": 1.5, "peak_fi": 3.319},
            {"freeze": 2, "start_s": 40.0, "end_s": 46.0, "duration_s": 6.0, "peak_fi": 5.0}]
    kept, lines = side_step_freezes(rows, STEPS)
    assert [(r["freeze"], r["start_s"]) for r in kept] == [(1, 40.0)]
    assert len(lines) == 1 and "30.8-32.2 s" in lines[0] and "decision L693" in lines[0]


def test_t2s_box_session_keeps_no_freeze():
    s = simulate_path(parse_route(BOX), UserProfile.from_seed(21), rate_hz=100, seed=0, scenario="route")
    from pdrlearn.track.plasys import track_plasys

    logging.disable(logging.WARNING)
    try:
        res = track_plasys(s)
    finally:
        logging.disable(logging.NOTSET)
    kept, lines = foot_freezes(s, res.info.get("pipeline"), res.steps)
    assert kept == [] and any("decision L693" in ln for ln in lines)
