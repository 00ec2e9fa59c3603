"""Decision L699 (session 47, I4): a two-unit streamed stride (``track --streaming``, ``run``, the live Tracker) reports
the FOOT's own turn in steps.csv ``turn_angle_rad``, as offline's row does (L66); its heading, placement and position
stay the lower back's (L61). Before, the row carried the lower back's yaw over the stride's window, 45-62 deg behind a
foot spinning 270-360 deg in one stride (L690's measurement)."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.kernels.sideways import own_turn

#: L699's tolerance (deg) against the foot's own turn (L690's)
TOL_DEG = 5.0


def test_l699_the_kernel_takes_the_foot_turn_when_the_foot_does_not_head():
    lev = {"foot": (None, None, None, None, 4.2, 0.0), "waist": (None, None, np.zeros((3, 3)), None, None)}
    assert own_turn(lev, "foot", 3.3) == 3.3
    assert own_turn(lev, "waist-gyro", 3.3) == 4.2
    assert own_turn({"foot": lev["foot"]}, "auto", 3.3) == 3.3  # no waist: the foot heads, its turn is dyaw


@pytest.fixture(scope="module")
def spin():
    """User 14675 (50 Hz, two units): a +270 and a -300 deg spin inside a stride, streamed (M2) and live."""
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route
    from pdrlearn.track.plasys import track_plasys
    from tests.test_live_heading_s45_e289 import _live

    route = "stand:2, straight:2, curve:270:0.3, straight:2, curve:-300:0.3, straight:2, stand:2"
    s = simulate_path(parse_route(route), UserProfile.from_seed(14675), rate_hz=50, seed=0, scenario="route")
    logging.disable(logging.WARNING)
    try:
        st = track_plasys(s, streaming=True, method="M2")
    finally:
        logging.disable(logging.NOTSET)
    return s, st, _live(s)


def _foot_truth(s, a, b):
    ft = s.extras["foot_trajectory"]
    t = ft["t_s"].to_numpy(float)
    yaw = np.unwrap(2 * np.arctan2(ft["qz"].to_numpy(float), ft["qw"].to_numpy(float)))
    return np.degrees(np.interp(b, t, yaw) - np.interp(a, t, yaw))


def test_l699_a_streamed_two_unit_stride_reads_the_foot_s_turn(spin):
    """Every streamed stride reads the foot's true turn over its own window within 5 deg (the spins' strides included,
    which read 45-62 deg short before), and the live Tracker equals track --streaming."""
    s, st, live = spin
    steps = st.steps
    truth = np.array([_foot_truth(s, a, b) for a, b in zip(steps["start_s"], steps["end_s"], strict=True)])
    turn = np.degrees(steps["turn_angle_rad"].to_numpy(float))
    assert (np.abs(truth) > 150).sum() >= 2  # the spins are in the strides
    np.testing.assert_allclose(turn, truth, rtol=0, atol=TOL_DEG)
    np.testing.assert_allclose([x.turn_angle_rad for x in live], steps["turn_angle_rad"].to_numpy(float),
                               rtol=0, atol=1e-9)


def test_l699_only_the_turn_column_changes(spin, monkeypatch):
    """Against the heading unit's turn (before L699): every column but ``turn_angle_rad`` / ``pivot_rad`` is the same,
    ``turn + pivot`` (the heading turns.csv sums, L104 / L106) is the same modulo a turn, and so is turns.csv."""
    from pdrlearn.kernels import sideways
    from pdrlearn.track.clinical import turn_table
    from pdrlearn.track.plasys import track_plasys

    s, st, _ = spin
    monkeypatch.setattr(sideways, "own_turn", lambda lev, heading, turn: float(turn))
    logging.disable(logging.WARNING)
    try:
        old = track_plasys(s, streaming=True, method="M2").steps
    finally:
        logging.disable(logging.NOTSET)
    new = st.steps
    same = [c for c in new.columns if c not in ("turn_angle_rad", "pivot_rad")]
    assert new[same].astype(str).equals(old[same].astype(str))
    assert not np.allclose(new["turn_angle_rad"], old["turn_angle_rad"])  # the spins' strides read the foot now
    d = (new["turn_angle_rad"] + new["pivot_rad"]) - (old["turn_angle_rad"] + old["pivot_rad"])
    np.testing.assert_allclose(np.angle(np.exp(1j * d.to_numpy(float))), 0.0, atol=1e-9)
    np.testing.assert_allclose(turn_table(new)["angle_deg"], turn_table(old)["angle_deg"], atol=1e-6)
