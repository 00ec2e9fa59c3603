"""Session 18's rehab trial on the waist pipelines: a track with no steps says why (W76), the slow-gait line of an
uncalibrated waist names the calibration (W77), and calibrate's implausible-factor line allows a slow walker (W78)."""

from __future__ import annotations

import dataclasses
import math
import re

import numpy as np
import pandas as pd

from pdrlearn.io.session import Stream
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.track.gait import gait_range_warning
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.calibration import CalibrationWalk, check_gain
from pdrlearn.waist.params import WaistParams


def _damped_patient(gain: float = 0.4, lean_deg: float = 20.0):
    """The trial's rollator patient: 0.3 m steps in 0.75 s (0.4 m/s) over 14 m, the waist's dynamic part x gain
    about its 2 s mean and a forward lean (the trial's damp.py)."""
    u = dataclasses.replace(UserProfile.from_seed(1), step_length_m=0.30 / 0.85, step_time_s=0.75 / 1.2)
    s = simulate_path([Stand(3), Straight(14), Stand(3)], u, speed="slow", rate_hz=20, seed=0)
    a = math.radians(lean_deg)
    rot = np.array([[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]])
    for name in ("wAccelerometer", "wGyroscope"):
        st = s.streams[name]
        lo = pd.DataFrame(st.values).rolling(40, center=True, min_periods=1).mean().to_numpy()
        s.streams[name] = Stream(name, st.t.copy(), (lo + gain * (st.values - lo)) @ rot.T)
    return s


def test_no_steps_warns_with_the_gate_the_level_and_a_fix_that_works():
    """W76: 0 steps on the damped walk is one warning naming the gate, the data's SD and the params fix; the
    threshold it suggests finds the walk's steps."""
    s = _damped_patient()
    r = track_waist(s, pipeline="waist-pendulum", relative_gate=False)  # W4's fixed gate
    assert not r.steps["has_next"].any()
    msg = [w for w in r.info["warnings"] if w.startswith("no steps found")]
    assert len(msg) == 1, r.info["warnings"]
    assert ">= 0.50 m/s^2" in msg[0] and "largest 2 s SD is" in msg[0] and "walk_threshold_mps2" in msg[0]
    x = float(re.search(r'"walk_threshold_mps2": ([0-9.]+)', msg[0]).group(1))
    assert 0.15 <= x < 0.5
    r2 = track_waist(s, pipeline="waist-pendulum", params={"walk_threshold_mps2": x}, relative_gate=False)
    n_true = len(s.extras["ics"])
    assert r2.steps["has_next"].sum() >= 0.9 * (n_true - 1), (len(r2.steps), n_true)
    assert not any(w.startswith("no steps found") for w in r2.info["warnings"])
    # W76's session-relative gate (the default) finds them with no params
    r3 = track_waist(s, pipeline="waist-pendulum")
    assert r3.steps["has_next"].sum() >= 0.9 * (n_true - 1) and r3.info["walk_threshold_mps2"] < 0.5
    assert not any(w.startswith("no steps found") for w in r3.info["warnings"])


def test_relative_gate_leaves_a_normal_walk_and_standing_alone():
    """W76: a normal walk keeps W4's 0.5 exactly (same steps, same distance); a standing-only recording gets the
    0.15 floor, no step, and the no-steps line (the gate never opened)."""
    u = UserProfile.from_seed(3)
    walk = simulate_path([Stand(2), Straight(12), Stand(2)], u, speed="normal", rate_hz=20, seed=1)
    a = track_waist(walk, pipeline="waist-pendulum")
    b = track_waist(walk, pipeline="waist-pendulum", relative_gate=False)
    assert a.info["walk_threshold_mps2"] == 0.5 and a.steps["length_m"].sum() == b.steps["length_m"].sum()
    still = simulate_path([Stand(20)], u, speed="normal", rate_hz=20, seed=1)
    r = track_waist(still, pipeline="waist-pendulum")
    assert len(r.steps) == 0 and r.info["walk_threshold_mps2"] == 0.15
    assert any(w.startswith("no steps found") and "never opened" in w for w in r.info["warnings"])


def test_slow_line_of_an_uncalibrated_waist_names_the_calibration():
    """W77: the L95 slow line fires on the measured cadence even when the (uncalibrated) speed looks normal, and on
    an uncalibrated waist track it says the distance depends on a calibration; calibrated or foot: no such clause."""
    base = {"median_cadence_spm": 62.0, "median_speed_mps": 0.9}
    waist = {**base, "info": {"pipeline": "waist-pendulum", "params_source": "defaults"}}
    line = gait_range_warning(waist)
    assert line is not None and "62 steps/min" in line and "slower than" in line
    assert "uncalibrated" in line and "pdrlearn calibrate" in line
    for other in ({**base, "info": {"pipeline": "waist-pendulum", "params_source": "calibrated"}},
                  {**base, "info": {"pipeline": "plasys", "params_source": "defaults"}}, base):
        line = gait_range_warning(other)
        assert line is not None and "uncalibrated" not in line
    assert gait_range_warning({**waist, "median_cadence_spm": 100.0}) is None


def test_implausible_calibration_factor_allows_a_slow_walker():
    """W78: a known distance well under the default model's names both a wrong --distance and a shuffling walker,
    and says the calibration is kept; above, a damped trunk."""
    base = WaistParams(leg_m=0.9, k=1.0, f_m=0.0)
    g = np.full(9, 0.6)  # 5.4 m under the default model
    low = check_gain([CalibrationWalk(2.9, np.full(9, 1.3), g, name="tenmwt")], "waist-pendulum", base)
    assert len(low) == 1 and "0.54 x" in low[0]
    assert "--distance is wrong" in low[0] and "shorter steps" in low[0] and "kept" in low[0]
    assert "check --distance" not in low[0]
    high = check_gain([CalibrationWalk(11.0, np.full(9, 1.3), g, name="aid")], "waist-pendulum", base)
    assert len(high) == 1 and "walking aid" in high[0] and "--distance is wrong" in high[0]
