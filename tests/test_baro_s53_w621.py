"""Decisions W621 / W622 (session 53, FD, trial s53t2 finding F2): a barometer's altitude is averaged over a window
its own noise sets (a running median where that is longer than W89's 1 s), so a phone's 1 Hz barometer does not read
level steps as stairs; the live W91 rise reads its two ends on windows cut alike."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.kernels.barometer import (
    LiveAltitude,
    altitude_noise,
    noise_smoothing,
    noise_window_s,
    pressure_hpa,
    relative_altitude,
    stairs_rate_test,
)

P0 = 1013.25
#: the trial's phone: one sample's altitude noise ~0.27 m (0.025 hPa of the simulated BMP280 + the phone's 0.02 hPa)
PHONE_HPA = 0.032


def _walk(rate_hz: float, noise_hpa: float, seed: int = 1):
    """A level walk (0-100 s), a 5 m flight down at 0.3 m/s (100-116.7 s), level again to 160 s, a 5 m lift ride up
    in 5 s at 180-185 s after a stand, level to 240 s: times (s), pressures (hPa), the true altitude (m)."""
    t = np.arange(0.0, 240.0, 1.0 / rate_hz)
    z = np.where(t < 100, 0.0, -0.3 * np.clip(t - 100, 0, 5 / 0.3)) + np.clip((t - 180) / 5.0, 0, 1) * 5.0
    rng = np.random.default_rng(seed)
    return t, pressure_hpa(z, P0) + rng.normal(0.0, noise_hpa, t.size), z


@pytest.fixture(scope="module")
def phone():
    return _walk(1.0, PHONE_HPA)


def _stairs(t, p, mids, **kw):
    """W91's test on each step middle's 2 s rise (as track_waist's _stair_proposals: one altitude read)."""
    h = relative_altitude(t, p, np.concatenate([mids - 1.0, mids + 1.0]), **kw)
    return stairs_rate_test(h[len(mids):] - h[:len(mids)])


def test_a_1hz_phone_barometer_reads_level_steps_level_and_the_flight_as_stairs(phone):
    t, p, _ = phone
    level = np.arange(10.0, 95.0, 0.55)  # step middles on the level walk before the flight
    flight = np.arange(103.0, 114.0, 0.55)  # inside the flight (its ends left out)
    before = _stairs(t, p, level, noise_window=False).mean()
    after = _stairs(t, p, level).mean()
    assert before > 0.3  # W89's 1 s mean: one sample a second, the trial's 143-178 of ~300 steps
    assert after < 0.03
    assert _stairs(t, p, flight).mean() > 0.9
    assert 6.0 < noise_window_s(t, p) < 12.0  # ~0.27 m a sample at 1 Hz: W621's window (s)


def test_the_long_window_is_a_median_a_lift_ride_stays_in_its_pause(phone):
    t, p, _ = phone
    h = relative_altitude(t, p, np.array([0.0, 176.0, 189.0]))
    assert abs(h[1] - (-5.0)) < 0.3  # 4 s before the ride: still the flight's foot
    assert abs(h[2] - 0.0) < 0.3  # 4 s after it: the top (a 10 s mean would be ~1 m short)
    w, mean_s = noise_smoothing(t, p)
    assert mean_s == 2.0 and w > 1.0


def test_the_full_rate_barometer_keeps_w89s_one_second_mean_exactly():
    t, p, _ = _walk(50.0, 0.0157 * np.sqrt(5) / np.sqrt(2), seed=2)  # the simulator's 50 Hz BMP280 (S62)
    assert noise_window_s(t, p) == 1.0
    at = np.arange(0.0, 240.0, 0.37)
    assert np.array_equal(relative_altitude(t, p, at), relative_altitude(t, p, at, noise_window=False))
    sigma, dt = altitude_noise(t, p)
    assert 0.15 < sigma < 0.26 and dt == pytest.approx(0.02)


def test_a_smooth_resampled_barometer_reads_no_noise():
    t = np.arange(0.0, 60.0, 0.01)
    p = 972.6 + 0.001 * np.sin(t / 5.0)  # mobgap's smooth 100 Hz stream: no sample noise
    assert altitude_noise(t, p)[0] < 1e-6 and noise_window_s(t, p) == 1.0


def test_live_altitude_reads_the_offline_window_and_equal_cut_ends_w622(phone):
    t, p, _ = phone
    live = LiveAltitude()
    live.set_origin(0.0)
    k = t <= 150.0
    live.push(t[k], p[k])
    assert live.smoothing == noise_smoothing(t, p)  # read on the first 64 samples, as offline
    off = relative_altitude(t, p, np.array([0.0, 60.0]))
    assert live.at(60.0) == pytest.approx(off[1], abs=1e-9)  # its window complete: the offline value
    # a rise inside the flight read when only 3 s after its later end are pushed: the equal cut keeps it near the
    # true 0.6 m, the earlier end on its full window shrinks it
    live2 = LiveAltitude()
    live2.set_origin(0.0)
    k = t <= 106.0
    live2.push(t[k], p[k])
    b = live2.at(103.0)
    cut = b - live2.at(101.0, upto=104.0)
    full = b - live2.at(101.0)
    assert abs(cut + 0.6) < abs(full + 0.6)
    assert abs(cut + 0.6) < 0.25
