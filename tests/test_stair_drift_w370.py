"""Decisions W370 (an option, not adopted) and W371: a barometric "drift" more than the fastest weather makes in
the track's span is a climb's uncounted remainder, not weather (trial T3 finding 2)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.kernels import altitude_check
from pdrlearn.track.base import TrackResult
from pdrlearn.track.evaluate import drift_warning, evaluate_track


def _stairs_z() -> tuple[np.ndarray, np.ndarray]:
    """A lower-back barometric z at the strides (every 1.1 s): level, six strides up of 0.34 m (2.04 m), a
    turn, down by 0.30 m strides and a last 0.24 m, level (as the trial's stairs_u8390): L172's 0.5 m bands count
    the descent at 1.44, 0.84 and 0.24 m and leave the flight's last 0.24 m uncounted."""
    dz = [0.0] * 6 + [0.34] * 6 + [0.0] * 3 + [-0.30] * 6 + [-0.24] + [0.0] * 6
    z = np.concatenate([[0.0], np.cumsum(dz)])
    return np.arange(len(z)) * 1.1, z


def _track(t: np.ndarray, z: np.ndarray) -> TrackResult:
    steps = pd.DataFrame({"start_s": t[:-1], "end_s": t[1:], "length_m": 0.3, "heading_rad": 0.0,
                          "dz_m": np.diff(z), "unit": "waist"})
    return TrackResult(steps=steps, trajectory=pd.DataFrame({"t": t, "x": 0.0, "y": 0.0, "z": z}), info={})


def test_weather_rate_is_two_hpa_per_hour_in_metres():
    # 6 hPa in 3 h (very rapidly) x 8.32 m/hPa (the ICAO formula at sea level)
    assert altitude_check.WEATHER_RATE_MAX_M_PER_S * 3600 == pytest.approx(16.6, abs=0.1)


def test_a_short_stair_walk_books_more_drift_than_the_weather_and_says_so():
    t, z = _stairs_z()
    s = evaluate_track(_track(t, z))
    # L172's count as before (W370 not adopted): the flight's end is lost
    assert s["descent_m"] == pytest.approx(2.04 - 0.24)
    assert s["altitude_drift_limit_m"] == pytest.approx(altitude_check.WEATHER_RATE_MAX_M_PER_S * (t[-1] - t[0]))
    assert abs(s["altitude_drift_m"]) > s["altitude_drift_limit_m"]
    line = drift_warning(s)
    assert line is not None and "W371" in line and "fastest weather" in line


def test_the_weather_drift_of_a_long_level_walk_keeps_the_l172_line():
    t = np.arange(0.0, 73 * 60.0, 0.5)
    s = evaluate_track(_track(t, 4.67 * t / t[-1]))  # the simulator's 0.3 hPa/h over 73 min
    assert abs(s["altitude_drift_m"]) < s["altitude_drift_limit_m"]
    assert "drifted +4.67 m slowly" in drift_warning(s)
    tiny = evaluate_track(_track(t[:40], 0.0 * t[:40]))
    assert drift_warning(tiny) is None


def test_the_option_counts_the_short_stair_walk_whole(monkeypatch):
    t, z = _stairs_z()
    monkeypatch.setattr(altitude_check, "CLIMBS_WITHIN_WEATHER", True)
    s = evaluate_track(_track(t, z))
    assert s["ascent_m"] == pytest.approx(2.04, abs=0.02) and s["descent_m"] == pytest.approx(2.04, abs=0.02)
    assert s["altitude_drift_m"] == pytest.approx(0.0, abs=1e-9)
    # a long walk whose drift the weather can make keeps L172's count
    tl = np.arange(0.0, 30 * 60.0, 0.5)
    zl = 1.0 * tl / tl[-1]
    assert altitude_check.climbs_within_weather(zl, tl) == altitude_check.ascent_descent(
        zl, altitude_check.ASCENT_BAND_BARO_M, tl, altitude_check.CLIMB_WINDOW_S)


def test_a_level_walk_without_counted_climbs_gets_no_w371_line():
    """A short level walk whose barometer moves 0.3 m (the mobgap Test5 recordings' own error) has no climb whose
    remainder could be lost: no W371 line."""
    t = np.arange(0.0, 10.0, 0.5)
    s = evaluate_track(_track(t, np.where(t > 7.0, -0.3, 0.0)))
    assert (s["ascent_m"], s["descent_m"]) == (0.0, 0.0) and abs(s["altitude_drift_m"]) > s["altitude_drift_limit_m"]
    assert drift_warning(s) is None
