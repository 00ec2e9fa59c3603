"""Decision C262 (cohort.md): `calibrate --turns N` says in one line when the fitted gyro bias is more than a MEMS
gyroscope drifts at rest (W105's 0.015 rad/s) or the walk measured half a turn or more away from N."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.waist.plausibility import STILL_YAW_RATE_WARN_RPS, turns_bias_message


@pytest.fixture(scope="module")
def out_and_back():
    """A fresh user (18745, C262's measurement used 18730-18744) walking 8 m out, a 180 deg turn, 8 m back, 20 Hz."""
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    return simulate_path(parse_route("stand:2, straight:8, turn:180, straight:8, stand:2"),
                         UserProfile.from_seed(18745), rate_hz=20, seed=0)


def test_kernel_line_c262():
    assert turns_bias_message([1.01], 1.0, 0.002) is None  # a closed loop walked as given, a bias at rest level
    line = turns_bias_message([0.51], 1.0, -0.043)  # F10: half a turn walked, --turns 1
    assert "+0.51 turn(s)" in line and "-0.0430 rad/s" in line and "-2.46 deg/s" in line
    assert "--turns 0.5" in line and "C262" in line and "over the 0.015 rad/s" in line
    # a long walk: half a turn off with a bias under W105's bound still warns, and says it is under
    assert "under the 0.015" in turns_bias_message([1.5], 1.0, 0.01)
    # a bias over the bound with the turn right: no other --turns is suggested
    line = turns_bias_message([1.1], 1.0, 0.03)
    assert line is not None and "calibrate with --turns" not in line
    assert turns_bias_message([1.0], 1.0, STILL_YAW_RATE_WARN_RPS) is None  # at the bound: quiet


def test_calibrate_warns_on_wrong_turns_c262(out_and_back, caplog):
    from pdrlearn.waist.calibration import calibrate

    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        bad = calibrate([out_and_back], "waist-pendulum", distances=[16.0], turns=1.0)
    lines = [r.getMessage() for r in caplog.records if "C262" in r.getMessage()]
    assert len(lines) == 1 and "--turns 0.5" in lines[0]  # the walk measured about +0.5 turn
    # the same walk with --turns 0.5: the bias it would fit is at rest level, so no line (the kernel's quiet case)
    walked = float(lines[0].split("measured ")[1].split(" turn")[0])
    assert abs(walked - 0.5) < 0.1
    assert bad.gyro_bias_rps < -STILL_YAW_RATE_WARN_RPS  # still written (C262: a warning, not a refusal)
    assert any("C262" in n for n in bad.notes)
    assert np.isfinite(bad.k)
