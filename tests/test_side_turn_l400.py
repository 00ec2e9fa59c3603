"""Decision L400 (session 33, new-user finding 5): the strides of a turn on the spot are no side steps (L219's line,
L228's sideways rows, L270's n_side_strides); a side-stepping stretch still is."""

from __future__ import annotations

import logging

import numpy as np

from pdrlearn.kernels import sideways as KS
from pdrlearn.kernels.sideways import SIDE_MAX_TURN_DEG, SideRun, is_sideways, sideways_runs
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline

SPIN = "straight:10, turn:360, stand:2, turn:-360, stand:2"  # the new user's route


def test_a_stride_that_turns_the_foot_is_not_judged_sideways(monkeypatch):
    monkeypatch.setattr(KS, "MIN_SIDE_STRIDES", 3)  # the run mechanism at L219's former 3 (L486 made it 1)
    angle, length = np.radians([90.0, 90.0, 90.0]), np.full(3, 0.3)
    assert sideways_runs(angle, length) == [(0, 2)] and sideways_runs(angle, length, np.radians([0, 5, 30])) == [(0, 2)]
    assert sideways_runs(angle, length, np.radians([0.0, 60.0, 0.0])) == []
    assert SIDE_MAX_TURN_DEG == 30.0 and not is_sideways(np.pi / 2, 0.3, np.radians(-31.0))
    run = SideRun()
    for _ in range(3):
        run.stride(0.0, 0.3, 0.3, 0.0, np.radians(90.0))
    assert not run.decided


def _spin(user: int):
    s = simulate_path(parse_route(SPIN), UserProfile.from_seed(user), rate_hz=20.0, seed=user, scenario="route")
    logging.disable(logging.WARNING)
    try:
        return get_pipeline("plasys")(s), get_pipeline("waist-pendulum")(s)
    finally:
        logging.disable(logging.NOTSET)


def test_turns_on_the_spot_give_no_side_strides_nor_l219_line():
    """User 7560 (experiments/sideways_turns_l400.py: 3 side-stride rows and one L219 line before L400)."""
    foot, waist = _spin(7560)
    assert int(foot.steps["sideways"].sum()) == 0
    assert [w for w in waist.info["warnings"] if "decision L219" in w] == []
