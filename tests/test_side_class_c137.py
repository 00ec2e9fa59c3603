"""Decision C137: a side step (L219 / L486's ``sideways`` stride) that the direction model classes backward - its
calibration had no side steps - keeps no negative ``length_m`` (``direction`` keeps the model's class, ``travel``
says the side), and one warning line counts them. Trial T2 finding 3: 5 of 8 side strides classed backward at
0.63-0.99, ``length_m`` -0.35 to -0.38 m, ``sum(length_m)`` 9.03 m against a distance of 12.01 m. Fresh user 9572."""

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
from pdrlearn.track.travel import side_class_warning
from tests.runtime_helpers import trained_dirs

ROUTE = "straight:3, side:-1.5, straight:3, side:1.5, straight:3"


def test_the_sign_kernel_leaves_a_side_step_positive():
    assert travel_sign_one(-0.4, 0.0, -0.4) == (-0.4, 0.0)  # L654: a stride measured backward keeps its sign
    length, head = travel_sign_one(-0.4, 0.0, -0.4, sideways=True)
    assert length == 0.4 and head == pytest.approx(math.pi)  # the same displacement
    ln, hd = travel_sign([-0.4, -0.4, 0.5], [0.0, 0.0, 0.0], [-0.4, -0.4, 0.5], [True, False, False])
    assert ln.tolist() == [0.4, -0.4, 0.5] and hd[0] == pytest.approx(math.pi) and hd[1] == 0.0


def test_the_line_counts_side_steps_classed_backward():
    t = pd.DataFrame({"direction": ["forward", "backward", "backward", "backward"],
                      "sideways": [False, True, True, False], "confidence": [0.9, 0.63, 0.99, 0.8]})
    lines: list[str] = []
    side_class_warning(t, lines)
    assert len(lines) == 1 and lines[0].startswith("2 of 2 side-step strides") and "0.63-0.99" in lines[0]
    lines.clear()
    side_class_warning(t.assign(direction="forward"), lines)
    side_class_warning(t.drop(columns="direction"), lines)
    assert lines == []


@pytest.mark.parametrize("streaming", [False, True])
def test_a_model_track_keeps_side_steps_positive(tmp_path_factory, streaming):
    model = trained_dirs(tmp_path_factory)["root"] / "model"
    s = simulate_path(parse_route(ROUTE), UserProfile.from_seed(9572), rate_hz=20.0, seed=9572, scenario="route")
    logging.disable(logging.WARNING)
    try:
        res = get_pipeline("plasys")(s, model=str(model), streaming=streaming)
    finally:
        logging.disable(logging.NOTSET)
    st = res.steps
    side = st["sideways"].astype(bool).to_numpy()
    classed_back = side & (st["direction"].to_numpy(dtype=object) == "backward")
    assert classed_back.sum() >= 2  # the model never saw side steps (the trial's case)
    length = st["length_m"].to_numpy(float)
    assert (length[side] > 0).all()  # main: negative on the rows classed backward
    assert length.sum() == pytest.approx(np.abs(length).sum())  # no backward item: sum = distance
    tr = res.trajectory
    assert math.hypot(tr["x"].iloc[-1], tr["y"].iloc[-1]) > 5  # the path itself is L65's, unchanged
    assert sum("decision C137" in w for w in res.info["warnings"]) == 1
