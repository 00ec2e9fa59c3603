"""Decision L37: a foot-headed stride whose length the rules signed against its measured x goes along its
measured displacement (offline's placement), not ~160 deg the wrong way."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from pdrlearn import sim
from pdrlearn.kernels.stride import headed_by_foot, reversed_by_rules
from pdrlearn.orient import wrap_angle
from pdrlearn.track.plasys import track_streaming

FOOT = {"foot": (None,) * 6}
WAIST = {"foot": (None,) * 6, "waist": (None, None, np.zeros(3))}


def test_reversed_only_when_the_rules_flip_a_foot_headed_stride():
    assert reversed_by_rules(headed_by_foot(FOOT, "foot"), -0.4, 0.4) == math.pi  # measured backwards, classed forward
    assert reversed_by_rules(headed_by_foot(FOOT, "foot"), 0.4, -0.4) == math.pi
    assert reversed_by_rules(headed_by_foot(FOOT, "foot"), -0.4, -0.4) == 0.0  # the rule agrees with the measurement
    assert reversed_by_rules(headed_by_foot(FOOT, "foot"), 0.4, 0.0) == 0.0
    assert reversed_by_rules(headed_by_foot(WAIST, "auto"), -0.4, 0.4) == 0.0  # waist-headed: the thesis sign rule
    assert reversed_by_rules(headed_by_foot(FOOT, "auto"), -0.4, 0.4) == math.pi


def test_simulated_turning_strides_keep_their_turn():
    # user 3, scenario C: two turning strides have a negative raw x; under L34 alone they went ~160 deg the
    # wrong way and the total turn was off by ~720 deg
    s = sim.simulate("C", user_seed=3, speed="normal")
    r = track_streaming(s, method="M3", model="oracle", heading="foot")
    traj = s.trajectory
    t = r.steps["end_s"].to_numpy(float)
    xy = np.column_stack([np.interp(t, traj["t"], traj["x"]), np.interp(t, traj["t"], traj["y"])])
    true_turn = np.sum(wrap_angle(np.diff(np.arctan2(*np.diff(xy, axis=0).T[::-1]))))
    est_turn = np.sum(wrap_angle(np.diff(r.steps["heading_rad"].to_numpy(float)[1:])))
    assert abs(math.degrees(est_turn - true_turn)) < 90
    # decision L692: a turning stride's raw_length_m is signed against the foot's mid-stride facing (these went
    # forward), so it agrees with length_m's measured sign (L654); L37's reversed step frame shows in the turn above
    flipped = (np.sign(r.steps["length_m"]) != np.sign(r.steps["raw_length_m"])) & (r.steps["length_m"] != 0)
    assert flipped.sum() == 0 and isinstance(r.steps, pd.DataFrame)
