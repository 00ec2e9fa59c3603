"""A turn on the spot without stopping: ``Pivot`` / ``--route pivot:DEG[:N[:STEP_M]]`` (decision S41)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.sim import Pivot, Straight, UserProfile, simulate_path
from pdrlearn.sim.path import path_length, plan_footsteps
from pdrlearn.sim.route import parse_route


def _plan(segs):
    return plan_footsteps(segs, UserProfile.from_seed(1), rng=np.random.default_rng(0))[0]


def test_route_pivot_parses_with_defaults_and_values():
    assert parse_route("pivot:180, pivot:-90:3:0.1") == [Pivot(math.pi), Pivot(math.radians(-90), 3, 0.1)]


@pytest.mark.parametrize(("spec", "message"), [("pivot:0", "non-zero"), ("pivot:180:0", "positive"),
                                               ("pivot:180:2.5", "whole number"), ("pivot", "takes 1 or 2 or 3")])
def test_route_pivot_refuses_bad_items_in_one_line(spec, message):
    with pytest.raises(DataError, match=message) as err:
        parse_route(spec)
    assert "\n" not in str(err.value)


def test_pivot_steps_turn_inside_the_walk_without_a_stop():
    steps = _plan([Straight(3.0), Pivot(math.pi), Straight(3.0)])
    turn = [k for k, s in enumerate(steps) if s.kind == "turn"]
    assert len(turn) == 4  # one step per 45 deg (PIVOT_STEP_RAD)
    assert [s.kind for s in steps].count("close") == 1  # only the walk's final closing step: no stop at the turn
    assert all(steps[k].pause_before_s == 0 for k in range(turn[0], turn[-1] + 2))
    feet = [s.foot for s in steps[turn[0] - 1:turn[-1] + 2]]
    assert all(a != b for a, b in zip(feet[:-1], feet[1:], strict=True))  # the walk's alternation continues
    yaw = [steps[k].yaw for k in turn]
    assert np.allclose(np.diff([steps[turn[0] - 1].yaw, *yaw]), math.pi / 4)
    # the body centre (each heel less half the step width to its side) moves step_m (0.15 m) per pivot step
    width = UserProfile.from_seed(1).step_width_m

    def centre(s):
        side = 1.0 if s.foot == "left" else -1.0
        return s.heel[:2] - side * 0.5 * width * np.array([-math.sin(s.yaw), math.cos(s.yaw)])

    c = np.array([centre(steps[k]) for k in range(turn[0] - 1, turn[-1] + 1)])
    assert np.linalg.norm(np.diff(c, axis=0), axis=1) == pytest.approx(0.15, abs=0.04)  # lateral placement noise


def test_pivot_path_length_and_refusals():
    assert path_length([Straight(2.0), Pivot(math.pi, 4, 0.15)]) == pytest.approx(2.6)
    with pytest.raises(DataError, match="step_m"):
        _plan([Straight(2.0), Pivot(math.pi, 4, 0.5)])
    with pytest.raises(DataError, match="at most 60 deg"):
        _plan([Straight(2.0), Pivot(math.pi, 2)])


def test_pivot_session_walks_through_the_turn():
    s = simulate_path([Straight(4.0), Pivot(math.pi), Straight(4.0)], UserProfile.from_seed(2), rate_hz=50.0, seed=1)
    ics = s.extras["ics"]
    assert (ics["kind"] == "turn").sum() == 4
    t = ics["ic_s"].to_numpy(float)
    assert np.diff(t).max() < 1.2  # no pause anywhere inside the walk
