"""Decision L692 (session 46, trial T2 finding F3): a stride turning 30 deg or more is on the spot only on a chord
under SPOT_MAX_CHORD_M; a longer one is judged against the foot's mid-stride facing, so a waltz's backward step taken
while turning counts backward and a forward stride on a curve is no turn on the spot."""

from __future__ import annotations

import logging
import math

import numpy as np
import pandas as pd
import pytest

from pdrlearn.kernels.backward import SPOT_MAX_CHORD_M, backward_mask, on_the_spot, signed_chord
from pdrlearn.kernels.stride import travel_sign_one
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.path import PIVOT_MAX_STEP_M
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import backward_travel
from pdrlearn.track.travel import side_class_warning, travel_labels

WALTZ = ("stand:3, straight:2, curve:135:0.6, backward:3:direct, curve:-135:0.6, straight:2, curve:-135:0.6, "
         "backward:3:direct, curve:135:0.6, straight:2, stand:3")


def test_the_chord_bound_is_two_pivot_steps():
    assert SPOT_MAX_CHORD_M == pytest.approx(2 * PIVOT_MAX_STEP_M)  # S41's per-step bound, two steps a stride


def test_a_turning_stride_is_signed_against_its_mid_stride_facing():
    turn = math.radians(66.0)
    back = turn / 2 + math.pi  # straight back from the mid-stride facing, in the start frame
    fwd = turn / 2
    c = signed_chord([math.cos(back), math.cos(fwd), 0.3, -0.3], [math.sin(back), math.sin(fwd), 0.95, 0.05],
                     [turn, turn, math.radians(5.0), math.radians(5.0)])
    assert c[0] == pytest.approx(-1.0) and c[1] == pytest.approx(1.0)
    assert c[2] > 0 and c[3] < 0  # under 30 deg: the sign of x, as before
    # where the start facing's x and the mid-stride facing disagree, the mid-stride facing decides
    a, b = math.radians(100.0), math.radians(300.0)
    assert signed_chord([math.cos(a)], [math.sin(a)], [math.radians(120.0)])[0] > 0  # 40 deg off the mid facing
    assert signed_chord([math.cos(b)], [math.sin(b)], [math.radians(150.0)])[0] < 0  # 45 deg off straight back
    # a turnaround whose chord lies across the mid-stride facing is not backward
    assert signed_chord([1.0], [0.0], [math.pi])[0] > 0
    # the step frame turned 90 deg from the start facing (the streamed kernels' E124 frame)
    assert signed_chord([math.cos(back - 0.5)], [math.sin(back - 0.5)], [turn], 0.5)[0] < 0


def test_only_a_short_turning_chord_is_on_the_spot():
    turn = np.radians([120.0, 120.0, 10.0, 120.0])
    assert on_the_spot(turn, [0.2, -0.95, 0.2, np.nan]).tolist() == [True, False, False, True]
    assert backward_mask([-0.2, -0.95, -0.95], turn_angle_rad=turn[:3]).tolist() == [False, True, True]
    assert travel_sign_one(0.95, 0.0, -0.95, turn_rad=turn[1])[0] == -0.95  # L654's sign: backward travel
    assert travel_sign_one(-0.2, 0.0, -0.2, turn_rad=turn[0])[0] == 0.2  # L578: on the spot stays positive


def test_the_l578_line_leaves_out_long_turning_chords():
    t = pd.DataFrame({"direction": ["backward", "backward"], "sideways": [False, False], "confidence": [0.9, 1.0],
                      "raw_length_m": [0.2, 1.06], "length_m": [0.2, 1.06], "unit": "foot",
                      "turn_angle_rad": np.radians([120.0, -135.0])})
    lines: list[str] = []
    side_class_warning(t, lines)
    assert lines[0].startswith("1 of 1 strides turning on the spot")
    assert travel_labels(t).tolist() == ["turn", "forward"]


@pytest.mark.parametrize("streaming", [False, True])
def test_a_backward_step_in_a_waltz_turn_counts_backward(streaming):
    from pdrlearn.track.plasys import track_plasys

    s = simulate_path(parse_route(WALTZ), UserProfile.from_seed(14454), rate_hz=20, seed=14454, scenario="route")
    logging.disable(logging.WARNING)
    try:
        st = track_plasys(s, streaming=streaming).steps
    finally:
        logging.disable(logging.NOTSET)
    truth = s.steps
    a, b = truth["start_s"].to_numpy(float), truth["end_s"].to_numpy(float)
    kind = np.array([truth["direction"].iloc[int(np.argmax(np.minimum(b, s1) - np.maximum(a, s0)))]
                     for s0, s1 in zip(st["start_s"], st["end_s"], strict=True)])
    back = backward_travel(st)
    assert (kind == "backward").sum() == 4
    assert back[kind == "backward"].all() and not back[kind != "backward"].any(), st[["raw_length_m", "turn_angle_rad"]]
    turning = np.abs(st["turn_angle_rad"].to_numpy(float)) >= math.radians(30.0)
    assert (back & turning).any()  # the backward step taken while turning
    assert (np.sign(st["length_m"]) == np.sign(st["raw_length_m"]))[st["raw_length_m"].abs() > 0].all()
    assert not (travel_labels(st)[turning] == "turn").any()  # the curve's 1 m strides are no turn on the spot
