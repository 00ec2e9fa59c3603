"""Decision L796: the compass-headed offline track is turned by the waist unit's measured mount yaw
(``track_plasys(forward_yaw=...)``), the signed angle D10's check measures from the used forward to the walk."""
import logging

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from pdrlearn.io.frames import AxisFrame
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.simulate import simulate_path
from pdrlearn.sim.user import UserProfile
from pdrlearn.track.frame_inference import forward_reversal_deg, forward_yaw_deg
from pdrlearn.track.plasys import track_plasys

WAIST = AxisFrame(x="left", y="up", z="forward")  # the thesis waist frame


@pytest.mark.parametrize("deg", [7.0, -7.0, 30.0])
def test_forward_yaw_is_signed_about_up(deg):
    r = WAIST.matrix().T  # body FLU -> sensor axes
    up = r @ np.array([0.0, 0.0, 1.0])
    walk = r @ Rotation.from_euler("z", deg, degrees=True).apply([1.0, 0.0, 0.0])  # the walk, left of forward
    tilted = r @ Rotation.from_euler("y", -8.0, degrees=True).apply([0.0, 0.0, 1.0])  # gravity read tilted
    assert forward_yaw_deg(WAIST, up, walk) == pytest.approx(deg, abs=1e-6)
    assert abs(forward_yaw_deg(WAIST, tilted, walk)) == pytest.approx(forward_reversal_deg(WAIST, tilted, walk))
    assert forward_yaw_deg(WAIST, None, walk) is None


@pytest.fixture(scope="module")
def yawed_walk():
    """A noise-free two-unit straight walk whose waist unit is turned 10 deg to the left on its belt: its compass
    reads the unit's forward, 10 deg off the walk (no hard iron, no bias: the mount is the only error)."""
    user = UserProfile.from_seed(18979)
    return simulate_path(parse_route("stand:3, straight:16, stand:2"), user, rate_hz=50.0, seed=0, name="l796",
                         scenario="route", noise=False, waist_mount_deg=(0.0, 0.0, 10.0))


def _median_deg(res):
    return float(np.degrees(np.median(res.steps["heading_rad"].to_numpy(float)[1:-1])))


def test_the_mount_yaw_is_taken_off_the_compass(yawed_walk):
    logging.disable(logging.WARNING)
    try:
        off, on = track_plasys(yawed_walk, forward_yaw=False), track_plasys(yawed_walk)  # L796: on by default
    finally:
        logging.disable(logging.NOTSET)
    yaw = on.info["compass_mount"]["forward_yaw_deg"]
    mount = (Rotation.from_rotvec([0.0, 0.0, np.radians(10.0)])
             * Rotation.from_rotvec(np.radians(UserProfile.from_seed(18979).waist_misalignment_deg)))
    fwd = mount.apply([1.0, 0.0, 0.0])  # the unit's forward in the body (S34's mis @ frame)
    true_mount = float(np.degrees(np.arctan2(fwd[1], fwd[0])))
    assert "forward_yaw_deg" not in off.info["compass_mount"]
    assert true_mount > 5.0 and yaw == pytest.approx(-true_mount, abs=1.5)
    assert _median_deg(off) > 7.0  # the unit's forward, not the walk
    assert abs(_median_deg(on)) < 2.5


def test_the_params_key_turns_it_off_offline_only(tmp_path):
    from pdrlearn.cli.track import _track_params
    from pdrlearn.errors import DataError

    f = tmp_path / "p.json"
    assert _track_params({"forward_yaw": False}, f, False)[1] == {"forward_yaw": False}
    with pytest.raises(DataError, match="forward_yaw.*L796.*--streaming"):
        _track_params({"forward_yaw": False}, f, True)
