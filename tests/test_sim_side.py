"""Side-stepping: ``Side`` / ``--route side:METRES`` (decision S49; labels S50)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.sim import Side, Straight, UserProfile, simulate_path
from pdrlearn.sim.path import SIDE_STEP_FRACTION, path_length, plan_footsteps
from pdrlearn.sim.route import parse_route


def _plan(segs, user=1):
    return plan_footsteps(segs, UserProfile.from_seed(user), rng=np.random.default_rng(0))[0]


def test_route_side_parses_signed_metres():
    assert parse_route("side:3, side:-2.5") == [Side(3.0), Side(-2.5)]
    assert path_length([Straight(10.0), Side(-3.0)]) == pytest.approx(13.0)


@pytest.mark.parametrize(("spec", "message"), [("side:0", "non-zero"), ("side:x", "not a number"),
                                               ("side:nan", "finite"), ("side", "takes 1 value"),
                                               ("side:2:3", "takes 1 value")])
def test_route_side_refuses_bad_items_in_one_line(spec, message):
    with pytest.raises(DataError, match=message) as err:
        parse_route(spec)
    assert "\n" not in str(err.value)


def test_side_segment_refuses_a_zero_distance():
    with pytest.raises(DataError, match="non-zero"):
        _plan([Side(0.0)])


@pytest.mark.parametrize("metres", [3.0, -4.0])
def test_side_steps_lead_out_trail_closes_facing_ahead(metres):
    user = UserProfile.from_seed(1)
    steps = _plan([Straight(4.0), Side(metres), Straight(4.0)])
    idx = [k for k, s in enumerate(steps) if s.kind == "side"]
    side = [steps[k] for k in idx]
    lead = "left" if metres > 0 else "right"
    assert [s.foot for s in side] == [lead, "right" if lead == "left" else "left"] * (len(side) // 2)
    assert all(s.yaw == 0.0 and s.direction == "forward" for s in side)
    assert side[0].pause_before_s > 0  # the walker stops before side-stepping ...
    after = steps[idx[-1] + 1]
    assert after.kind == "walk" and after.pause_before_s > 0  # ... and after
    # each side step moves the lead foot 0.3-0.5 m sideways (SIDE_STEP_FRACTION x the step length)
    y = np.array([s.heel[1] for s in side])
    assert 0.3 < SIDE_STEP_FRACTION * user.step_length() < 0.5
    for moves in (np.diff(y[0::2]), np.diff(y[1::2])):  # lead and trail foot: one side step each per cycle
        assert np.all((np.sign(moves) == math.copysign(1.0, metres)) & (np.abs(moves) > 0.25)
                      & (np.abs(moves) < 0.6))
    # the feet end side by side at the user's step width, ``metres`` to the side
    assert side[-1].heel[1] + side[-2].heel[1] == pytest.approx(2 * metres, abs=0.05)
    assert abs(side[-1].heel[1] - side[-2].heel[1]) == pytest.approx(user.step_width_m, abs=0.05)


@pytest.mark.parametrize("user", [3, 8])
def test_side_route_trajectory_moves_sideways_with_the_heading_unchanged(user):
    s = simulate_path(parse_route("side:-4"), UserProfile.from_seed(user), rate_hz=20.0, seed=1, scenario="route")
    tr = s.trajectory
    d = tr[["x", "y"]].iloc[-1].to_numpy(float) - tr[["x", "y"]].iloc[0].to_numpy(float)
    assert d[1] == pytest.approx(-4.0, rel=0.03)  # net lateral displacement within 3 %
    assert abs(d[0]) < 0.05  # no forward travel
    yaw = np.degrees(tr["heading_rad"].to_numpy(float))
    assert abs(yaw[-1] - yaw[0]) < 1.0 and np.abs(yaw).max() < 4.0  # heading unchanged (pelvic rotation only)
    foot = s.extras["foot_trajectory"]
    assert foot["y"].iloc[-1] - foot["y"].iloc[0] == pytest.approx(-4.0, rel=0.03)
    # step time: slower than the user's forward step, 0.5-1 s
    ics = s.extras["ics"]
    dt = np.diff(ics["ic_s"].to_numpy(float))
    assert 0.5 < np.median(dt) < 1.0 and set(ics["kind"]) == {"side"}


def test_side_labels_keep_direction_and_add_lateral_m():
    user = UserProfile.from_seed(2)
    s = simulate_path(parse_route("straight:6, side:3, straight:6"), user, rate_hz=20.0, seed=1, scenario="route")
    st = s.steps
    side = st[st["kind"] == "side"]
    assert len(side) >= 5 and set(st["direction"]) == {"forward"}  # decision S50: no third direction class
    assert (side["lateral_m"] > 0.25).all() and not side["steady"].any()
    walk = st[st["kind"] == "walk"]
    assert (walk["lateral_m"].abs() < 0.1).all()
    assert st["lateral_m"].sum() == pytest.approx(3.0, rel=0.05)
    plain = simulate_path(parse_route("straight:6"), user, rate_hz=20.0, seed=1, scenario="route")
    assert "lateral_m" not in plain.steps  # sessions without side steps: label files unchanged
