"""Decision L494 (trial T3 finding 2): a foot-only track's heading 0 is the first walk's direction, so a foot unit
yawed on the shoe (its nearest-axis frame declared, as docs/frames.md advises) no longer turns the whole path by the
yaw (trial: 20 deg -> 13.24 m off on a 45 m route), and ``initial_heading`` sets the first walk's direction."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.frame_inference import remount

ROUTE = "stand:3, straight:14, turn:90, straight:8, turn:-90, straight:10, stand:3"


@pytest.fixture(scope="module")
def walk():
    return simulate_path(parse_route(ROUTE), UserProfile.from_seed(9632), rate_hz=100.0, seed=0, scenario="route")


def _yawed(walk, deg: float):
    """The foot unit turned ``deg`` about its own y axis (up in the simulator's foot frame: a yaw on the shoe), its
    meta.json frame kept (the nearest-axis declaration)."""
    s = remount(walk, "foot", Rotation.from_euler("y", deg, degrees=True).as_matrix().T)
    s.frames["foot"] = walk.frames["foot"]
    return s


def _final(result) -> np.ndarray:
    xy = result.trajectory[["x", "y"]].to_numpy(float)
    return xy[-1] - xy[0]


@pytest.mark.parametrize("deg", [20.0, -30.0])
def test_a_foot_unit_yawed_on_the_shoe_does_not_turn_a_foot_only_path(walk, deg):
    from pdrlearn.track.plasys import track_plasys

    true = walk.trajectory[["x", "y"]].to_numpy(float)
    truth = true[-1] - true[0]
    straight, yawed = (track_plasys(s, heading="foot") for s in (walk, _yawed(walk, deg)))
    assert np.hypot(*(_final(yawed) - _final(straight))) < 1.0  # before L494: turned by the yaw (5-9 m here)
    assert np.hypot(*(_final(yawed) - truth)) < 2.0


def test_initial_heading_is_the_first_walks_direction(walk):
    from pdrlearn.track.plasys import track_plasys

    north = track_plasys(_yawed(walk, 20.0), heading="foot", initial_heading=np.pi / 2)
    first = north.trajectory[["x", "y"]].to_numpy(float)
    d = first[5] - first[0]
    assert abs(np.degrees(np.arctan2(d[1], d[0])) - 90.0) < 6.0  # the first strides head north, not 90 - 20
