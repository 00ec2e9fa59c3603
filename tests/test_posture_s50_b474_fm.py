"""Decision B474 amended (session 50, FM): a stride's first "rest" that is no rest (moving: a window starting
mid-swing, a turning pedal) gives no rest pitch, so it is never skipped as a posture; a still pitched rest still is.
Before the amendment a limp's second stride (its window starting mid-swing, 61.5 deg "pitched") and a ride's
pedal strokes were skipped as B131's posture, which broke L611's ride line and live == streamed parity."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pdrlearn.kernels.window import pitched_from, rest_pitch_deg

FWD = np.array([1.0, 0.0, 0.0])  # the simulator's foot frame: x forward, y up, z right


def _rest(pitch_deg: float, n: int = 40, *, rate: float = 0.0, scale: float = 1.0):
    th = math.radians(pitch_deg)
    t = np.arange(n) / 100.0
    acc = scale * np.tile([-9.81 * math.sin(th), 9.81 * math.cos(th), 0.0], (n, 1))
    gyr = np.tile([0.0, 0.0, rate], (n, 1))
    return t, acc, gyr


def test_a_still_pitched_rest_is_read():
    assert rest_pitch_deg(*_rest(80.0), FWD, rest_search_s=0.25) == pytest.approx(80.0, abs=1e-6)
    assert pitched_from(rest_pitch_deg(*_rest(80.0, rate=0.2), FWD, rest_search_s=0.25), 1.0)


@pytest.mark.parametrize("kw", [{"rate": 1.0}, {"scale": 0.7}, {"scale": 1.05}])
def test_a_moving_rest_gives_no_pitch_and_no_posture(kw):
    # the turning pedal (0.2-0.5 rad/s, |a| 6.7-10.0 m/s^2) and the limp's mid-swing start (2.3 rad/s, 6.85 m/s^2)
    p = rest_pitch_deg(*_rest(80.0, **kw), FWD, rest_search_s=0.25)
    assert math.isnan(p) and not pitched_from(p, 1.0)
    loose = {"still_rad_s": 2.0, "still_acc": 4.0}  # the keywords are the test: loosened, the pitch is read again
    assert rest_pitch_deg(*_rest(80.0, **kw), FWD, rest_search_s=0.25, **loose) == pytest.approx(80.0, abs=1e-6)
