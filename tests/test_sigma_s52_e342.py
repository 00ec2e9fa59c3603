"""Decision E342 (session 52, FA, review s52r1 finding F5): the streamed radius's heading offset term follows
``cycle_yaw`` - E331's 0.047 for a track with E336 off (its strides along the pelvis' yaw at the foot's rest, the
offset E331 measured), E337's term for the default; no other regime is changed."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.track.base import TrackResult
from pdrlearn.track.position_sigma import SIGMA_PARAMS, add_position_sigma, sigma_params


def test_the_offset_term_is_chosen_by_cycle_yaw():
    shipped = SIGMA_PARAMS["plasys-streaming"]["heading_offset_rad"]
    assert sigma_params("plasys-streaming")["heading_offset_rad"] == shipped  # no info: the default (E336 on)
    assert sigma_params("plasys-streaming", {"cycle_yaw": True})["heading_offset_rad"] == shipped
    assert sigma_params("plasys-streaming", {"cycle_yaw": False})["heading_offset_rad"] == 0.047  # E331's delta
    for regime in ("plasys-foot-streaming", "plasys-gyro-fallback", "plasys-fused", "plasys-foot", "waist"):
        assert sigma_params(regime, {"cycle_yaw": False}) == SIGMA_PARAMS[regime]


def test_a_track_with_e336_off_gets_the_wider_radius():
    n = 40  # 40 one-metre strides east: the offset's error is across the walk, delta x 40 m
    steps = pd.DataFrame({"start_s": np.arange(0.0, n), "end_s": np.arange(1.0, n + 1), "length_m": np.ones(n),
                          "heading_rad": np.zeros(n)})
    traj = pd.DataFrame({"t": np.r_[0.0, steps["end_s"]], "x": np.r_[0.0, np.arange(1.0, n + 1)], "y": 0.0})
    radius = {}
    for on in (True, False):
        res = TrackResult(steps=steps.copy(), trajectory=traj.copy(),
                          info={"pipeline": "plasys", "streaming": True, "cycle_yaw": on})
        add_position_sigma(res, None, "plasys-streaming")
        radius[on] = res.trajectory["pos_sigma_m"].to_numpy(float)
        assert res.info["position_sigma"]["heading_offset_rad"] == (SIGMA_PARAMS["plasys-streaming"]
                                                                    ["heading_offset_rad"] if on else 0.047)
    shipped = SIGMA_PARAMS["plasys-streaming"]["heading_offset_rad"]
    assert radius[False][-1] ** 2 - radius[True][-1] ** 2 == pytest.approx((0.047 ** 2 - shipped ** 2) * n ** 2,
                                                                          rel=1e-6)
