"""Decision L654 (trial T2, finding F10; amends L65): steps.csv ``length_m`` is negative exactly when the stride
travels backward (its measured x, ``raw_length_m``, negative; no side step, no turn on the spot), whatever the
model's class - main kept a backward stride classed forward at +0.46 m (heading turned by pi) and gave a forward
stride classed backward -1.41 m. The displacement, and so every position, is unchanged. Fresh user 12543."""

from __future__ import annotations

import logging
import math

import numpy as np
import pytest

from pdrlearn.kernels.stride import travel_sign, travel_sign_one
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.evaluate import backward_travel


def test_the_kernel_signs_by_the_measured_travel():
    length, head = travel_sign_one(0.46, 2.713, -0.46)  # T2 F10's row: the class rule made it +, measured back
    assert length == -0.46 and head == pytest.approx(2.713 + math.pi)
    assert travel_sign_one(-2.0, 0.1, 2.0) == (2.0, 0.1 + math.pi)  # F3's row with oracle classes: measured ahead
    ln, _ = travel_sign([0.46, -2.0, -0.3, -0.3], [0.0] * 4, [-0.46, 2.0, -0.3, -0.3], [False, False, True, False],
                        np.radians([0.0, 0.0, 0.0, 90.0]))
    assert ln.tolist() == [-0.46, 2.0, 0.3, 0.3]  # side step (C137) and turn on the spot (L578) stay positive


@pytest.mark.parametrize("streaming", [False, True])
def test_length_sign_is_backward_travel_whatever_the_class(streaming):
    s = simulate_path(parse_route("stand:2, straight:3, backward:3, straight:3, stand:2"),
                      UserProfile.from_seed(12543), speed="normal", rate_hz=50.0, seed=2, scenario="route")
    logging.disable(logging.WARNING)
    try:
        plain = get_pipeline("plasys")(s, model="oracle", streaming=streaming)
        g = s.steps
        flip = g.index[g["direction"] == "backward"][1]  # a backward stride labelled forward
        fwd = g.index[(g["direction"] == "forward") & (g["kind"] == "walk")][1]  # a forward one labelled backward
        s.steps.loc[flip, "direction"], s.steps.loc[fwd, "direction"] = "forward", "backward"
        res = get_pipeline("plasys")(s, model="oracle", streaming=streaming)
    finally:
        logging.disable(logging.NOTSET)
    st = res.steps
    assert set(st["direction"].dropna()) == {"forward", "backward"}
    back = backward_travel(st)
    assert back.sum() >= 2
    length = st["length_m"].to_numpy(float)
    assert ((length < 0) == back).all(), st[["direction", "length_m", "raw_length_m"]]  # main: 2 rows disagree
    step = np.diff(res.trajectory[["x", "y"]].to_numpy(), axis=0)
    h = st["heading_rad"].to_numpy(float)
    np.testing.assert_allclose(step[:, 0], length * np.cos(h), atol=1e-9)  # the row says where it went
    np.testing.assert_allclose(step[:, 1], length * np.sin(h), atol=1e-9)
    assert len(plain.steps) == len(st)
