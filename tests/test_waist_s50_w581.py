"""Decisions W581 / W582 (trial s50 T3 finding F3): a forward low-swing shuffle is not called backward (W173's cue
also needs the foot's stride to travel behind its facing), and a track's backward stretches give one line."""

from __future__ import annotations

import dataclasses

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli.simulate import with_swing_and_sway
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.waist.backward import backward_message, backward_warnings


def _grid(s, hop: float = 0.4) -> pd.DataFrame:
    """Waist-track-like contacts every ``hop`` s over the session's simulated strides, one walking sequence."""
    ev = np.arange(float(s.steps["start_s"].min()), float(s.steps["end_s"].max()), hop)
    return pd.DataFrame({"event_s": ev, "end_s": ev + hop, "has_next": np.r_[np.ones(len(ev) - 1, bool), False]})


@pytest.fixture(scope="module")
def shuffle():
    slow = dataclasses.replace(UserProfile.from_seed(5), step_length_m=0.3, step_time_s=0.8)
    return simulate_path(parse_route("stand:2, straight:5, stand:2"), with_swing_and_sway(slow, 0.06, None),
                         rate_hz=20.0, seed=0, scenario="route")


def test_a_forward_shuffle_is_not_backward_w581(shuffle):
    steps = _grid(shuffle)
    assert backward_warnings(steps, shuffle, max_travel_deg=None)  # W173's push-off alone called it backward
    assert backward_warnings(steps, shuffle) == []


def test_a_backward_stretch_is_still_warned_w581():
    s = simulate_path(parse_route("straight:4, backward:6, straight:3"), UserProfile.from_seed(14), rate_hz=20.0,
                      seed=3, scenario="route")
    lines = backward_warnings(_grid(s), s)
    assert len(lines) == 1 and "look backward" in lines[0] and "W581" in lines[0]
    t0, t1 = (float(x) for x in lines[0].split(" steps at ")[1].split(" s look")[0].split("-"))
    back = s.steps[s.steps["direction"] == "backward"]
    assert back["start_s"].min() - 0.8 <= t0 and t1 <= back["end_s"].max() + 0.8


def test_several_stretches_give_one_line_w582():
    ev = np.arange(30) * 0.5
    steps = pd.DataFrame({"event_s": ev, "end_s": ev + 0.5, "has_next": np.ones(30, bool)})
    one = backward_message(steps, [(1, 4)])
    assert one.startswith("4 steps at 0.5-2.5 s look backward")
    line = backward_message(steps, [(1, 4), (10, 15), (18, 21), (24, 28)])
    assert line.startswith("19 steps in 4 stretches at 0.5-2.5 s, 5.0-8.0 s, 9.0-11.0 s, ... look backward")
    assert line.count("decision W173") == 1
