"""path.png: the ground truth drawn in the track's frame when the heading is relative (new-user trial: the
level walk's truth went west while the track went east, reading as a 160 deg heading error)."""

import numpy as np
import pytest

from pdrlearn.track.plots import initial_bearing, rotated_to_track


def test_initial_bearing_hand_computed():
    x, y = np.array([0.0, 0.5, 1.5, 3.0]), np.array([0.0, 0.5, 1.5, 3.0])
    assert initial_bearing(x, y) == pytest.approx(np.pi / 4)  # first point >= 2 m away: (1.5, 1.5)
    assert initial_bearing(np.array([0.0, 1.0]), np.array([0.0, 0.0])) is None  # never 2 m from the start
    assert initial_bearing(np.zeros(0), np.zeros(0)) is None


@pytest.mark.parametrize("turn_deg", [0.0, 90.0, -160.0])
def test_truth_rotated_onto_the_track_keeps_its_shape(turn_deg):
    # an out-and-back L: the truth walks north, the (relative-heading) track walks the same path turned
    gx = np.r_[np.zeros(10), np.linspace(0, 3, 10)]
    gy = np.r_[np.linspace(0, 9, 10), np.full(10, 9.0)]
    a = np.radians(turn_deg)
    tx, ty = np.cos(a) * gx - np.sin(a) * gy, np.sin(a) * gx + np.cos(a) * gy
    rx, ry = rotated_to_track(gx, gy, np.ones(20, bool), tx, ty)
    np.testing.assert_allclose(rx, tx, atol=1e-12)
    np.testing.assert_allclose(ry, ty, atol=1e-12)
    assert rotated_to_track(gx, gy, np.ones(20, bool), tx[:1], ty[:1]) is None  # a track too short: as it is
