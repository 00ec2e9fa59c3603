"""Decision E343 (session 52, FA, review s52r1 finding F1): ``track --streaming`` holds E338's end-phase yaw over the
strides the runtime ``Tracker`` places, in order, after L611 has judged the pedalling ones: a crank stroke is no gait
phase. Before, its measuring loop fed :class:`~pdrlearn.kernels.stride.CyclePhase` with every measured stride, so a
seated ride set the held psi and a turning stride after it went another way than live (1.35 deg on the reviewer's
route). The reviewer's route: a walk, a seated crank ride (L611's pedalling), then a curve (user 12020, 20 Hz)."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from tests.sim_helpers import quiet_walk
from tests.test_no_cycling_s46_e304 import _live
from tests.test_pedal_s43_l611 import _pedal


@pytest.fixture(scope="module")
def ride_then_curve():
    s = quiet_walk("stand:3, straight:8, stand:2, sit:40, stand:2, curve:120:1.5, straight:6, stand:3", 12020, 12020,
                   rate_hz=20.0)
    tr = s.extras["transfers"]
    _pedal(s, float(tr["seated_s"].iloc[0]) + 5, float(tr["rise_s"].iloc[0]) - 5, 40.0)
    return s


def test_streamed_heading_after_a_ride_equals_the_live_one(ride_then_curve):
    from pdrlearn.track.plasys import track_streaming

    _, steps, _ = _live(ride_then_curve)  # cycle_yaw on (E336's default)
    logging.disable(logging.WARNING)
    try:
        res = track_streaming(ride_then_curve, method="M2")
    finally:
        logging.disable(logging.NOTSET)
    assert any("cycling?" in w for w in res.info["warnings"])  # L611 judged the ride's strides pedalling
    live = np.array([st.heading_rad for st in steps])
    streamed = res.steps["heading_rad"].to_numpy(float)
    turned = np.abs(np.diff(np.unwrap(live))) > np.radians(15.0)  # the curve after the ride: E338 holds psi there
    assert len(live) == len(streamed) and turned.any()
    assert np.allclose(streamed, live, atol=1e-6)  # before E343: 1.35 deg off on the curve's strides
    assert np.allclose(res.trajectory[["x", "y"]].iloc[-1].to_numpy(float), [steps[-1].x, steps[-1].y], atol=1e-6)


def test_the_streamed_track_says_its_cycle_yaw_e342(ride_then_curve):
    """Decision E342: ``info["cycle_yaw"]``, which picks the radius's heading offset term (E331's with E336 off)."""
    from pdrlearn.track.plasys import track_streaming
    from pdrlearn.track.position_sigma import add_position_sigma

    logging.disable(logging.WARNING)
    try:
        res = track_streaming(ride_then_curve, method="M2", cycle_yaw=False)
    finally:
        logging.disable(logging.NOTSET)
    assert res.info["cycle_yaw"] is False
    add_position_sigma(res, ride_then_curve)
    assert res.info["position_sigma"]["model"] == "plasys-streaming"
    assert res.info["position_sigma"]["heading_offset_rad"] == 0.047
