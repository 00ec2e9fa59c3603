"""Decision L578 (trial T1, finding F4): a stride of a turn on the spot (own turn of 30 deg or more, steps.csv
``travel`` = turn) that the direction model classes backward keeps no negative ``length_m`` (main: -0.146,
-0.091, -0.159 ... m, no warning), and one line counts them, as C137 does for side steps. Fresh user 11517."""

from __future__ import annotations

import logging
import math

import numpy as np
import pandas as pd
import pytest

from pdrlearn.kernels.stride import travel_sign, travel_sign_one
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.travel import side_class_warning, travel_labels
from tests.runtime_helpers import trained_dirs

ROUTE = "stand:2, straight:3, turn:180, straight:3, turn:-360, straight:2, stand:2"  # T1's turn exercise


def test_the_sign_kernel_leaves_a_turn_on_the_spot_positive():
    assert travel_sign_one(-0.15, 0.0, -0.15, turn_rad=math.radians(10.0)) == (-0.15, 0.0)  # backward walking
    length, head = travel_sign_one(-0.15, 0.0, -0.15, turn_rad=math.radians(-120.0))
    assert length == 0.15 and head == pytest.approx(math.pi)  # the same displacement
    ln, hd = travel_sign([-0.15, -0.15, -0.4], [0.0, 0.0, 0.0], [-0.15, -0.15, -0.4],
                         turn_rad=np.radians([120.0, 30.0, 5.0]))
    assert ln.tolist() == [0.15, 0.15, -0.4] and hd[2] == 0.0


def test_the_line_counts_turn_strides_classed_backward():
    t = pd.DataFrame({"direction": ["forward", "backward", "backward", "backward"],
                      "sideways": [False, False, False, False], "confidence": [0.9, 0.97, 1.0, 0.8],
                      "turn_angle_rad": np.radians([0.0, 120.0, -120.0, 5.0])})
    lines: list[str] = []
    side_class_warning(t, lines)
    assert len(lines) == 1 and lines[0].startswith("2 of 2 strides turning on the spot") and "0.97-1.00" in lines[0]
    assert "decision L578" in lines[0]
    lines.clear()
    side_class_warning(t.assign(direction="forward"), lines)
    side_class_warning(t.drop(columns="turn_angle_rad"), lines)
    assert lines == []


@pytest.mark.parametrize("streaming", [False, True])
def test_a_model_track_keeps_turn_strides_positive(tmp_path_factory, streaming):
    model = trained_dirs(tmp_path_factory)["root"] / "model"
    s = simulate_path(parse_route(ROUTE), UserProfile.from_seed(11517), speed="slow", rate_hz=20.0, seed=0,
                      scenario="route")
    logging.disable(logging.WARNING)
    try:
        res = get_pipeline("plasys")(s, model=str(model), streaming=streaming)
    finally:
        logging.disable(logging.NOTSET)
    st = res.steps
    spot = travel_labels(st) == "turn"  # steps.csv travel (L412)
    classed_back = spot & (st["direction"].to_numpy(dtype=object) == "backward")
    assert classed_back.sum() >= 2, st[["direction", "travel", "length_m"]]  # T1's case: pivots classed backward
    length = st["length_m"].to_numpy(float)
    assert (length[spot] > 0).all()  # main: negative on the rows classed backward
    assert sum("decision L578" in w for w in res.info["warnings"]) == 1
