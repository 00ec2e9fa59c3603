"""Decision L30 (docs/decisions/localization.md): a stride's heading change is the twist about the vertical
of the foot's attitude change from rest to rest, not the heading of the unit's x axis (ill-conditioned when an
instep mount pitches that axis 45-60 degrees down, as on the gaitmap 4x10 m walk)."""

from __future__ import annotations

import logging

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from pdrlearn.displace import _kernels as K
from pdrlearn.displace.foot import FootDisplacement, twist_yaw
from pdrlearn.errors import DataError
from tests.conftest import external_session


def _wxyz(r: Rotation) -> np.ndarray:
    q = r.as_quat()
    return np.column_stack([q[:, 3], q[:, :3]])


def test_twist_ignores_a_tilt_error_that_the_pitched_x_axis_turns_into_heading():
    pitch = np.radians(57.0)  # the right foot's mount: the x axis 57 degrees below the horizontal
    eps = np.radians(5.0)  # tilt error of the end attitude about the horizontal forward axis
    yaw = np.radians([-150.0, -30.0, 0.0, 45.0, 120.0, 179.0])
    n = len(yaw)
    start = Rotation.from_euler("y", np.full((n, 1), pitch))
    end = Rotation.from_euler("x", np.full((n, 1), eps)) * Rotation.from_euler("z", yaw[:, None]) * start
    got = twist_yaw(_wxyz(start), _wxyz(end))
    np.testing.assert_allclose(got, yaw, atol=1e-9)
    x = K._qrotate(_wxyz(end), np.tile([1.0, 0.0, 0.0], (n, 1)))  # the former rule: heading of the x axis
    err = np.degrees(np.abs(np.angle(np.exp(1j * (np.arctan2(x[:, 1], x[:, 0]) - yaw)))))
    assert err.max() > 5.0  # eps x tan(pitch) ~ 7.7 degrees at the worst heading


def test_twist_of_a_pure_turn_and_its_inverse():
    a = Rotation.random(20, random_state=3)
    yaw = np.random.default_rng(3).uniform(-3.1, 3.1, 20)
    b = Rotation.from_euler("z", yaw[:, None]) * a
    np.testing.assert_allclose(twist_yaw(_wxyz(a), _wxyz(b)), yaw, atol=1e-9)
    np.testing.assert_allclose(twist_yaw(_wxyz(b), -_wxyz(a)), -yaw, atol=1e-9)  # q and -q: one attitude


def test_unknown_yaw_rule_is_an_error():
    with pytest.raises(DataError, match="twist"):
        FootDisplacement(yaw="pca")


@pytest.mark.parametrize("side", ["left", "right"])
def test_walk4x10_turnarounds_are_half_turns_on_both_feet(side):
    """Before L30: +186/+207/+202 deg (left) and +136/+143 deg with a leg lost (right)."""
    import pdrlearn.steps as S
    from pdrlearn.io import read_session
    from pdrlearn.orient import unit_data
    from pdrlearn.track.evaluate import straight_legs

    s = read_session(external_session(f"gaitmap_walk4x10_{side}"))
    logging.disable(logging.WARNING)
    try:
        fd = FootDisplacement().estimate(unit_data(s, "foot"), S.AccelStepDetector().detect(s))
    finally:
        logging.disable(logging.NOTSET)
    h = np.degrees(fd.foot_heading())
    legs = straight_legs(h)
    turns = np.diff([np.mean(h[g[1:-1]]) for g in legs])
    assert len(legs) == 4, [len(g) for g in legs]  # four passes of 10 m
    assert np.all(np.abs(turns - 180.0) < 15.0), turns


def test_streamed_twist_matches_the_attitude_change_and_survives_a_zeroed_last_sample():
    """kernels.window.twist_dpsi (the streamed L30 rule): the twist of R_end r0^T; a last specific force that is
    zero (a zeroed sample) or along the forward axis gives the forward axis's heading change, not a
    ZeroDivisionError."""
    from pdrlearn.kernels.window import twist_about_z, twist_dpsi

    rng = np.random.default_rng(5)
    r0, r1 = Rotation.random(2, random_state=5).as_matrix()
    fwd, acc = np.array([0.6, 0.0, -0.8]), rng.normal(size=3) + [0.0, 0.0, 9.8]
    want = twist_about_z(r1 @ r0.T)
    assert twist_dpsi(r0, fwd, acc, r1 @ fwd, r1 @ acc) == pytest.approx(want, abs=1e-12)
    s, f = r0 @ fwd, r1 @ fwd
    axis = np.arctan2(s[0] * f[1] - s[1] * f[0], s[0] * f[0] + s[1] * f[1])
    for e2 in (np.zeros(3), 2.0 * fwd):
        assert twist_dpsi(r0, fwd, e2, r1 @ fwd, r1 @ e2) == pytest.approx(axis, abs=1e-12)
