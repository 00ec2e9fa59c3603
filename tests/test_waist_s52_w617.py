"""Decision W617: calibrate on a running lap says what track says of it (L95's fast line), on the walks' gait."""

from __future__ import annotations

import logging

import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.waist import calibration
from pdrlearn.waist.calibration import fast_gait_line

META = {"leg_length_m": 0.99}


def test_a_running_gait_gets_track_s_running_line():
    line = fast_gait_line({"median_cadence_spm": 182.0, "speed_mps": 3.04}, META, "waist-pendulum")
    assert line.startswith("the calibration walks' median cadence 182 steps/min, speed 3.04 m/s: this looks "
                           "like running")
    assert "0.99 m leg" in line and "(decision W617)" in line and "floors" not in line


@pytest.mark.parametrize("cad, speed", [(110.0, 1.3), (80.0, 0.4), (60.0, 0.3)])
def test_walking_and_slow_walks_get_no_line(cad, speed):
    assert fast_gait_line({"median_cadence_spm": cad, "speed_mps": speed}, META, "waist-pll") is None


def test_calibrate_warns_and_notes_it(monkeypatch, caplog):
    s = simulate_path(parse_route("straight:12"), UserProfile.from_seed(19371), rate_hz=20.0, seed=1)
    real = calibration.calibration_gait

    def running(*a, **k):  # the walk's figures as a running lap's (the simulator does not run, S48)
        return {**real(*a, **k), "median_cadence_spm": 182.0, "speed_mps": 3.04}

    monkeypatch.setattr(calibration, "calibration_gait", running)
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        params = calibration.calibrate([s], "waist-pendulum", distances=[12.0])
    lines = [r.getMessage() for r in caplog.records if "looks like running" in r.getMessage()]
    assert len(lines) == 1 and lines[0].startswith("calibrate: the calibration walks'") and "W617" in lines[0]
    assert any("W617" in n for n in params.notes)
