"""Decision L326 (trial 31 finding 9): summary.json gives the backward strides' own median length and speed
(``median_stride_length_m`` / ``gait_speed_mps`` pool both ways)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import backward_gait, track_summary
from pdrlearn.track.plasys import track_plasys


def test_forward_backward_forward_gives_the_backward_strides_length_and_speed():
    s = simulate_path(parse_route("stand:2, straight:6, stand:2, backward:8, stand:2, straight:6, stand:2"),
                      UserProfile.from_seed(6145), rate_hz=20.0, seed=2, scenario="route")
    res = track_plasys(s)
    out = track_summary(res, s)
    truth = s.steps[s.steps["direction"] == "backward"]
    back = res.steps[res.steps["backward_travel"]]
    assert out["n_backward_strides"] == len(back) > 0
    assert out["median_backward_stride_length_m"] == pytest.approx(np.median(np.abs(back["length_m"])))
    # the backward strides are shorter than the pooled median, as the simulated truth's
    assert out["median_backward_stride_length_m"] < out["median_stride_length_m"]
    assert out["median_backward_stride_length_m"] == pytest.approx(
        np.median(np.abs(truth["length_m"][truth["kind"] == "backward"])), rel=0.25)
    assert out["median_backward_speed_mps"] == pytest.approx(np.nanmedian(back["speed_mps"]))


def test_no_backward_stride_or_a_lower_back_table_gives_none():
    none = {"median_backward_stride_length_m": None, "median_backward_speed_mps": None}
    fwd = pd.DataFrame({"raw_length_m": [1.2, 1.3], "length_m": [1.2, 1.3], "speed_mps": [1.0, 1.1],
                        "unit": ["foot", "foot"]})
    assert backward_gait(fwd) == none
    assert backward_gait(fwd.assign(unit="waist")) == none
    back = fwd.assign(raw_length_m=[-0.8, 1.3], length_m=[0.8, 1.3], speed_mps=[0.5, 1.1])
    assert backward_gait(back) == {"median_backward_stride_length_m": 0.8, "median_backward_speed_mps": 0.5}
