"""Decision L486: a side-stepping stretch of 1 or 2 foot strides (a shuffle along a shelf) is side, not backward -
L219's run test needs one sideways stride (``MIN_SIDE_STRIDES`` 1; 3 before, so ``side:0.8`` read
``n_side_strides`` 0 and ``n_backward_strides`` 1-2 in trial T2, finding 2). Fresh users 9570-9571."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.kernels.sideways import MIN_SIDE_STRIDES, sideways_runs
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.evaluate import backward_travel, evaluate_track

SHORT = "stand:2, straight:3, stand:2, side:0.4, stand:2, straight:3, stand:2, side:-0.8, stand:2, backward:2, stand:2"


def test_one_sideways_stride_is_a_side_stretch():
    assert MIN_SIDE_STRIDES == 1
    deg = np.radians([3, 95, 4, 91, -89, 5, 30])
    length = np.array([1.5, 0.4, 1.5, 0.4, 0.4, 1.5, 0.4])
    assert sideways_runs(deg, length) == [(1, 1), (3, 4)]


@pytest.mark.parametrize("streaming", [False, True])
def test_short_side_stretches_are_side_and_backward_stays_backward(streaming):
    s = simulate_path(parse_route(SHORT), UserProfile.from_seed(9570), rate_hz=100.0, seed=9570, scenario="route")
    foot = s.steps[s.steps["foot"] == s.steps["foot"].iloc[0]]
    assert (foot["kind"] == "side").sum() == 3 and (foot["direction"] == "backward").sum() == 2  # the simulator's
    logging.disable(logging.WARNING)
    try:
        res = get_pipeline("plasys")(s, streaming=streaming)
    finally:
        logging.disable(logging.NOTSET)
    out = evaluate_track(res, s)
    assert out["n_side_strides"] == 3  # main: 0 (the 1- and 2-stride stretches were no run of 3)
    if not streaming:  # main: 3 (a side stride read backward); streamed also reads a 0.03 m split stride backward
        assert out["n_backward_strides"] == 2
    assert not (res.steps["sideways"].astype(bool) & backward_travel(res.steps)).any()


def test_the_warning_lines_keep_a_three_stride_stretch_l487():
    from pdrlearn.track.sideways import WARN_MIN_SIDE_STRIDES

    deg, length = np.radians([3, 95, 92, 4, 91, 89, 90, 5]), np.array([1.5, 0.4, 0.4, 1.5, 0.4, 0.4, 0.4, 1.5])
    assert WARN_MIN_SIDE_STRIDES == 3
    assert sideways_runs(deg, length, min_strides=WARN_MIN_SIDE_STRIDES) == [(4, 6)]
    assert sideways_runs(deg, length) == [(1, 2), (4, 6)]
