"""Decisions W269-W271: lying in bed turns the lower-back gyro heading by the yaw of the trunk's long axis about
gravity only, not by the vertical rate of turning over (``lying_heading``, on by default since W271)."""

from __future__ import annotations

import logging

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from pdrlearn.errors import DataError
from pdrlearn.kernels.lying_heading import long_axis_yaw_rate, stop_pieces
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.waist import OPTION_DEFAULTS
from pdrlearn.waist.live import live_value, unapplied_options_line
from pdrlearn.waist.lying import lying_episodes
from pdrlearn.waist.params import WaistParams

FS = 20.0
ROLLS = "stand:3, straight:8, lie:120:60, turn:180, straight:8, stand:3"  # users 6444 / 6446: 2 / 3 rolls


def _last_heading_deg(session, on: bool | None) -> tuple[float, np.ndarray]:
    params = None if on is None else {"options": {"lying_heading": on}}
    r = get_pipeline("waist-pendulum")(session, params=params)
    walking = r.steps[r.steps["has_next"].to_numpy(bool)]
    return float(np.degrees(walking["heading_rad"].iloc[-1])), r.trajectory[["x", "y"]].to_numpy(float)


def _off_180(deg: float) -> float:
    return abs(abs((deg + 180.0) % 360.0 - 180.0) - 180.0)


@pytest.mark.parametrize("user", [6444, 6446])
def test_turning_over_in_bed_no_longer_turns_the_walk_back_w269(user):
    """The failing-before test: a walk, two minutes in bed turning over, a 180 deg turn and the walk back. The
    vertical rate of the rolls and of sitting up turned the walk back by 50-110 deg; the long axis's yaw leaves it
    within 10 deg of the way back (the track ends near its start)."""
    logging.disable(logging.WARNING)
    try:
        s = simulate_path(parse_route(ROLLS), UserProfile.from_seed(user), rate_hz=FS, seed=user)
        assert len(s.extras["rolls"]) >= 2
        on, xy_on = _last_heading_deg(s, None)  # the default (W271)
        off, xy_off = _last_heading_deg(s, False)
    finally:
        logging.disable(logging.NOTSET)
    print(f"user {user}: walk back {off:+.1f} deg (vertical rate) -> {on:+.1f} deg (long axis), truth 180")
    assert _off_180(on) < 10.0 < 40.0 < _off_180(off)
    assert np.hypot(*xy_on[-1]) < 2.0 < np.hypot(*xy_off[-1])


def test_a_session_without_lying_is_tracked_as_before_w269():
    logging.disable(logging.WARNING)
    try:
        s = simulate_path(parse_route("stand:3, straight:8, sit:60, turn:180, straight:8, stand:3"),
                          UserProfile.from_seed(6444), rate_hz=FS, seed=6444)
        a, xy_a = _last_heading_deg(s, True)
        b, xy_b = _last_heading_deg(s, False)
    finally:
        logging.disable(logging.NOTSET)
    assert a == b and np.array_equal(xy_a, xy_b)


def test_the_long_axis_yaw_rate_ignores_a_roll_about_it_and_reads_a_turn_about_gravity():
    rng = np.random.default_rng(3)
    u = np.array([0.05, 0.0, 1.0]) / np.linalg.norm([0.05, 0.0, 1.0])  # the walking upright, a little forward
    # lying: the long axis 87 deg from the vertical, at random attitudes about gravity and about the axis itself
    for _ in range(20):
        att = Rotation.from_euler("zyx", [rng.uniform(-np.pi, np.pi), 0.0, 0.0]) * \
            Rotation.align_vectors([[np.sin(np.radians(87)), 0.0, np.cos(np.radians(87))]], [u])[0] * \
            Rotation.from_rotvec(u * rng.uniform(-np.pi, np.pi))
        up_body = att.inv().apply([0.0, 0.0, 1.0])[None, :]
        roll = 1.3 * u  # a roll about the long axis (body frame): no yaw of it
        assert long_axis_yaw_rate(up_body, roll[None, :], u)[0] == pytest.approx(0.0, abs=1e-12)
        turn = 0.4 * up_body[0]  # a turn about gravity: its own rate
        assert long_axis_yaw_rate(up_body, turn[None, :], u)[0] == pytest.approx(0.4, abs=1e-12)
        # any rate: the time derivative of the azimuth of the long axis in the navigation frame
        w = rng.normal(size=3)
        dt = 1e-6
        az = [np.arctan2(*(a.apply(u)[[1, 0]])) for a in (att, att * Rotation.from_rotvec(w * dt))]
        assert long_axis_yaw_rate(up_body, w[None, :], u)[0] == pytest.approx((az[1] - az[0]) / dt, abs=1e-4)
    # upright (the axis within 30 deg of the vertical): no azimuth, no rate
    assert long_axis_yaw_rate(u[None, :], np.array([[0.3, 0.2, 0.5]]), u)[0] == 0.0


def test_a_stop_is_cut_at_its_lying_episodes():
    eps = [(20.0, 23.0, 600.0, 603.0)]
    assert stop_pieces(18.0, 610.0, eps) == ([(18.0, 20.0), (603.0, 610.0)], [(23.0, 600.0)])
    assert stop_pieces(18.0, 19.0, eps) == ([(18.0, 19.0)], [])  # an episode outside the stop: as before
    assert stop_pieces(21.0, 601.0, eps) == ([], [(23.0, 600.0)])  # inside the movements: nothing added
    assert stop_pieces(0.0, 10.0, []) == ([(0.0, 10.0)], [])


def test_lying_episodes_are_w222s_lying_runs_of_10_s_or_more_with_their_movements():
    t = np.arange(0.0, 60.0, 1 / FS)
    tilt = np.interp(t, [0, 10, 13, 40, 43, 45, 46, 50, 51, 60], [3, 3, 90, 90, 3, 3, 90, 90, 3, 3])
    code = np.where(tilt >= 60.0, 3, 1)  # W222's lying (the averaged tilt is this ramp's, near enough)
    eps = lying_episodes(t, tilt, code, FS)
    assert len(eps) == 1  # the 4 s run at 46-50 s is under W247's 10 s
    s, a, b, e = eps[0]
    assert s == pytest.approx(10.0, abs=0.3) and a == pytest.approx(13.0, abs=0.3)
    assert b == pytest.approx(40.0, abs=0.3) and e == pytest.approx(43.0, abs=0.3)


def test_the_default_is_on_w271_and_the_live_tracker_names_it_only_when_given():
    assert OPTION_DEFAULTS["lying_heading"] is True
    others = {"stand_veto": False, "sit_veto": False, "contact_shift": False, "parity_fill": False,
              "pause_ride": False, "turn_bridge": False}  # W385: the offline default "side" is not live
    assert unapplied_options_line(WaistParams(leg_m=0.9, options=others)) is None
    line = unapplied_options_line(WaistParams(leg_m=0.9, options={**others, "lying_heading": True}))
    assert line is not None and "lying_heading=true" in line
    assert live_value("lying_heading", {"lying_heading": False}) is False


def test_a_bad_value_is_one_line():
    s = simulate_path(parse_route("stand:3, straight:8, stand:3"), UserProfile.from_seed(6445), rate_hz=FS, seed=1)
    with pytest.raises(DataError, match="lying_heading"):
        get_pipeline("waist-pendulum")(s, params={"options": {"lying_heading": "yes"}})
