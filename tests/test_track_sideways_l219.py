"""Decision L219: a side-stepping stretch seen by the foot unit gives one warning line (no track number changes)."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.sideways import MIN_SIDE_STRIDES, sideways_runs


def test_sideways_runs_need_three_long_sideways_strides_in_a_row():
    deg = np.radians([3, 95, 92, 88, 4, 91, 89, 5, -95, -90, -100, -80, 2])
    length = np.array([1.5, 0.4, 0.4, 0.4, 1.5, 0.4, 0.4, 1.5, 0.4, 0.4, 0.1, 0.4, 1.5])
    # 1-3: a run; 5-6: too short; 8-11: broken by a 0.1 m stride at 10
    assert MIN_SIDE_STRIDES == 3
    assert sideways_runs(deg, length) == [(1, 3)]
    assert sideways_runs(np.radians([61, 119, 90]), np.full(3, 0.3)) == [(0, 2)]
    assert sideways_runs(np.radians([59, 90, 90]), np.full(3, 0.3)) == []


def _lines(route: str, pipeline: str) -> list[str]:
    logging.disable(logging.WARNING)
    try:
        s = simulate_path(parse_route(route), UserProfile.from_seed(4), rate_hz=20.0, seed=1, scenario="route")
        return [w for w in get_pipeline(pipeline)(s).info["warnings"] if "decision L219" in w]
    finally:
        logging.disable(logging.NOTSET)


@pytest.mark.parametrize("pipeline", ["plasys", "waist-pendulum", "waist-pll"])
def test_a_side_stretch_gives_one_line_and_a_walk_none(pipeline):
    lines = _lines("straight:6, side:-3, straight:6", pipeline)
    assert len(lines) == 1 and "sideways to the right" in lines[0]
    assert "deg from the foot's facing" in lines[0]
    assert _lines("straight:6, turn:90, straight:6", pipeline) == []
