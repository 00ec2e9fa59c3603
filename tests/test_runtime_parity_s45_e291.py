"""Decision E291 (session 45, FH): ``Tracker(bundle, tasks=[])`` classifies no task.

It classified every task (``tasks or list(bundle.tasks)``), so a "no classifier" live track compared with
``track --streaming --method M2`` carried the model's classes: E216 turned each waist-headed pivot stride classed
forward by pi (live ``heading_rad`` an odd multiple of pi off, positions 0.34-0.79 m apart on users 12880-12889's turn
on the spot), and the length class moved a stop-and-go walk's strides by up to 2.33e-3 m (E289's test). The two paths
run the same code; with the same (no) classes they agree to rounding."""

from __future__ import annotations

import logging
import math
from pathlib import Path

import numpy as np
import pytest

from tests.test_live_heading_s45_e289 import _live  # the live Tracker(shipped bundle, tasks=[]), 0.1 s pushes

ROOT = Path(__file__).resolve().parents[1]
#: stand, walk, stop, turn on the spot both ways (I1's finding's route items, session 45)
ROUTE = ("stand:12, straight:3, stand:4, turn:180, straight:3, turn:90, straight:2, stand:3, turn:-180, straight:3, "
         "stand:3")
#: one computation (E6): rounding only (4.77e-15 - 1.79e-14 m printed on users 12880-12889)
POS_TOL_M = 1e-6
HEADING_TOL_RAD = 1e-9


def test_an_empty_task_list_classifies_nothing_e291():
    from pdrlearn.runtime import Tracker, load_bundle

    bundle = load_bundle(ROOT / "models" / "plasys-sim-default")
    assert Tracker(bundle, tasks=[]).classifiers == {}
    assert set(Tracker(bundle).classifiers) == set(bundle.tasks)  # None: every task, as before
    assert set(Tracker(bundle, tasks=["length"]).classifiers) == {"length"}


@pytest.mark.parametrize("user", [12880, 12886])
def test_live_equals_track_streaming_on_a_turn_on_the_spot_e291(user):
    """The same strides, lengths and positions; ``Step.to_dict()``'s heading equals steps.csv's, and the attribute
    (unwrapped, decision E87) is it plus whole turns. Fails with ``tasks=[]`` read as every task (pi, ~0.7 m)."""
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route
    from pdrlearn.track.plasys import track_plasys

    logging.disable(logging.WARNING)
    try:
        session = simulate_path(parse_route(ROUTE), UserProfile.from_seed(user), seed=user, scenario="route")
        res = track_plasys(session, streaming=True, method="M2")
    finally:
        logging.disable(logging.NOTSET)
    steps = _live(session)
    st, traj = res.steps, res.trajectory.iloc[1:]  # the trajectory's first row is the start
    assert [(x.start_s, x.end_s) for x in steps] == list(zip(st["start_s"], st["end_s"], strict=True))
    pivots = np.abs(st["turn_angle_rad"].to_numpy(float)) >= math.radians(30.0)  # L578's turn on the spot
    assert pivots.sum() >= 4
    np.testing.assert_allclose([x.length_m for x in steps], st["length_m"].to_numpy(float), rtol=0, atol=1e-9)
    wrapped = np.array([x.to_dict()["heading_rad"] for x in steps])
    np.testing.assert_allclose(wrapped, st["heading_rad"].to_numpy(float), rtol=0, atol=HEADING_TOL_RAD)
    turns = (np.array([x.heading_rad for x in steps]) - st["heading_rad"].to_numpy(float)) / (2 * np.pi)
    np.testing.assert_allclose(turns, np.round(turns), rtol=0, atol=HEADING_TOL_RAD)
    d = np.hypot([x.x for x in steps] - traj["x"].to_numpy(), [x.y for x in steps] - traj["y"].to_numpy())
    assert d.max() < POS_TOL_M, d.max()
    assert all(x.classes == {} for x in steps)  # M2's: no class
