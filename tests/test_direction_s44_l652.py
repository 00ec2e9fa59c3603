"""Decision L652 (trial T2, finding F3): a stride measured travelling forward (steps.csv ``travel`` forward,
``raw_length_m`` positive) that the direction model classed backward gets one warning line, as C137's side steps
and L578's turn strides do (main: T2's side-step model classed the 2.0 m stride after each ``turn:180`` backward,
18 of 70 forward strides, with no line). Fresh user 12542; the classes are the session's labels with one forward
stride labelled backward (``model="oracle"``), offline and streamed."""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.travel import side_class_warning


def test_the_line_counts_forward_strides_classed_backward():
    t = pd.DataFrame({"start_s": [0.0, 1.2, 2.4, 3.6, 4.8], "end_s": [1.1, 2.3, 3.5, 4.7, 5.9],
                      "length_m": [1.4, 2.0, -0.5, 0.2, 1.4], "raw_length_m": [1.4, 2.0, -0.5, 0.2, 1.4],
                      "direction": ["forward", "backward", "backward", "backward", "forward"],
                      "sideways": False, "confidence": [0.9, 0.69, 1.0, 0.9, 0.9],
                      "turn_angle_rad": np.radians([0.0, 0.0, 0.0, 120.0, 0.0]), "gap_s": 0.0, "unit": "foot"})
    lines: list[str] = []
    side_class_warning(t, lines)
    ours = [w for w in lines if "decision L652" in w]
    assert len(ours) == 1 and ours[0].startswith("1 of 3 strides travelling forward") and "0.69-0.69" in ours[0]
    lines.clear()
    side_class_warning(t.assign(direction=["forward", "forward", "backward", "backward", "forward"]), lines)
    assert not any("L652" in w for w in lines)  # the backward walker and the turn stride are not counted here


@pytest.mark.parametrize("streaming", [False, True])
def test_a_track_says_a_forward_stride_was_classed_backward(streaming):
    s = simulate_path(parse_route("stand:2, straight:5, stand:2"), UserProfile.from_seed(12542), speed="normal",
                      rate_hz=50.0, seed=1, scenario="route")
    s.steps.loc[2, "direction"] = "backward"  # the class a model gave T2's 2 m strides
    logging.disable(logging.WARNING)
    try:
        res = get_pipeline("plasys")(s, model="oracle", streaming=streaming)
    finally:
        logging.disable(logging.NOTSET)
    st = res.steps
    back = st["direction"].to_numpy(dtype=object) == "backward"
    assert back.sum() == 1 and (st["raw_length_m"].to_numpy(float)[back] > 0).all()
    ours = [w for w in res.info["warnings"] if "decision L652" in w]
    assert len(ours) == 1 and ours[0].startswith("1 of ")


def test_a_leading_dropped_stride_is_not_the_first_measured_one(monkeypatch):
    """Review R2 F2: ``track --streaming`` judges L652's line on the rows it writes: a leading stride it drops (B131's
    posture, L611's pedalling; here the first stride judged pedalling) is not E318's first measured stride, so the
    real first stride (abs'd, classed backward) is not counted (main: "1 of 3 strides ... classed backward").
    Fresh user 16900."""
    import pdrlearn.track.plasys as plasys

    s = simulate_path(parse_route("stand:2, straight:5, stand:2"), UserProfile.from_seed(16900), speed="normal",
                      rate_hz=50.0, seed=1, scenario="route")
    s.steps.loc[1, "direction"] = "backward"  # the first stride the track keeps
    judge = plasys.closed_loop_strides

    def first_pedalling(*a, **k):
        out = judge(*a, **k).copy()
        out[0] = True
        return out

    monkeypatch.setattr(plasys, "closed_loop_strides", first_pedalling)
    logging.disable(logging.WARNING)
    try:
        res = get_pipeline("plasys")(s, model="oracle", streaming=True)
    finally:
        logging.disable(logging.NOTSET)
    assert res.steps["direction"].iloc[0] == "backward" and res.steps["raw_length_m"].iloc[0] > 0
    assert any("not walking, removed" in w for w in res.info["warnings"])  # the dropped leading stride
    assert not [w for w in res.info["warnings"] if "decision L652" in w]
