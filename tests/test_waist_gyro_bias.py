"""Decision W105: a waist gyroscope that turns while the unit stands still (a phone's uncalibrated gyroscope
export) is warned about by ``track``, naming the calibrated-gyroscope export; no number changes."""

from __future__ import annotations

import logging
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.io import read_session
from pdrlearn.io.session import Stream
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.plausibility import STILL_YAW_RATE_WARN_RPS, still_yaw_rate, still_yaw_rate_message

T11 = Path(__file__).resolve().parents[1] / "datasets" / "real" / "mobgap_HA001_Test11_Trial1"


def _w105(r) -> list[str]:
    return [w for w in r.info["warnings"] if "decision W105" in w]


def _t11(bias_up: float = 0.0):
    logging.disable(logging.WARNING)
    try:
        s = read_session(T11)
    finally:
        logging.disable(logging.NOTSET)
    g = s["wGyroscope"]
    up = s.frames["waist"].matrix()[2]  # the sensor axes' share of the body's up
    s.streams["wGyroscope"] = Stream(g.name, g.t, g.values + bias_up * up)
    return s


def test_the_rate_at_rest_is_the_first_standstill_mean_less_the_calibrated_bias():
    t = np.arange(1000) / 100.0
    acc = np.tile([0.0, 0.0, 9.81], (1000, 1))
    gyr = np.zeros((1000, 3))
    gyr[:, 2] = 0.03
    acc[600:, 2] += 3.0 * np.sin(2 * np.pi * 2 * t[600:])  # walking from 6 s
    rate, t0, t1 = still_yaw_rate(t, acc, gyr, 100.0, bias_rps=0.01)
    assert rate == pytest.approx(0.02) and t0 == 0.0 and t1 == pytest.approx(5.0)
    assert still_yaw_rate(t[:150], acc[:150], gyr[:150], 100.0) is None  # 1.5 s still: not judged
    assert still_yaw_rate_message((STILL_YAW_RATE_WARN_RPS, 0.0, 5.0)) is None
    line = still_yaw_rate_message((-0.02, 0.0, 5.0))
    assert "-0.0200 rad/s" in line and "export the calibrated gyroscope" in line and "69 deg a minute" in line


def test_a_biased_phone_gyroscope_warns_and_the_real_recording_does_not():
    """HA001 Test11 rests at +0.0103 rad/s (its lab IMU: no warning); +0.02 rad/s on the up axis (+0.0302 read), an
    uncalibrated phone gyroscope's size, warns once and changes no number."""
    clean = track_waist(_t11(), pipeline="waist-pendulum")
    biased = track_waist(_t11(0.02), pipeline="waist-pendulum")
    assert not _w105(clean)
    (line,) = _w105(biased)
    assert "+0.0302 rad/s" in line and "(0.0-3.9 s" in line
    assert len(biased.steps) == len(clean.steps)
